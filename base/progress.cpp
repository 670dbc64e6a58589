#include "base/progress.h"

#include <algorithm>
#include <cstdio>
#include <unistd.h>

namespace curette {

static int& enabledOverride() {
    static int value = -1;  // -1: decide by isatty
    return value;
}

void Progress::setEnabled(bool enabled) { enabledOverride() = enabled ? 1 : 0; }

static bool drawingEnabled() {
    if (enabledOverride() >= 0) return enabledOverride() == 1;
    static const bool tty = isatty(STDERR_FILENO) == 1;
    return tty;
}

Progress::Progress(std::string label, double total)
    : label_(std::move(label)), total_(total > 0 ? total : 1), start_(std::chrono::steady_clock::now()),
      lastDraw_(start_) {}

Progress::~Progress() { finish(); }

void Progress::update(double done) {
    done_ = std::clamp(done, 0.0, total_);
    if (!drawingEnabled()) return;
    auto now = std::chrono::steady_clock::now();
    if (now - start_ < std::chrono::seconds(1)) return;
    if (drawn_ && now - lastDraw_ < std::chrono::milliseconds(100)) return;
    lastDraw_ = now;
    draw(false);
}

void Progress::finish() {
    if (finished_) return;
    finished_ = true;
    if (drawn_) {
        done_ = total_;
        draw(true);
    }
}

void Progress::draw(bool final) {
    drawn_ = true;
    constexpr int width = 30;
    double fraction = done_ / total_;
    int filled = static_cast<int>(fraction * width);
    char bar[width + 1];
    for (int i = 0; i < width; ++i) bar[i] = i < filled ? '#' : '.';
    bar[width] = 0;
    double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    std::fprintf(stderr, "\r%s [%s] %3d%% %.1fs%s", label_.c_str(), bar, static_cast<int>(fraction * 100 + 0.5),
                 seconds, final ? "\n" : "");
    std::fflush(stderr);
}

}  // namespace curette
