#include "render/frame_run.h"

#include <algorithm>

namespace curette {

std::uint32_t SliceSizer::next(double budgetMs, std::uint32_t left, std::uint32_t probe, std::uint32_t fixed) {
    std::uint32_t n = 0;
    if (fixed > 0)
        n = std::min(fixed, left);
    else if (!(unitsPerMs_ > 0))
        n = std::clamp<std::uint32_t>(probe, 1, std::max<std::uint32_t>(left, 1));
    else
        n = static_cast<std::uint32_t>(std::clamp(unitsPerMs_ * std::max(budgetMs, 1.0), 1.0, double(std::max<std::uint32_t>(left, 1))));
    if (rule_ == Rate::Last && fixed == 0 && last_ > 0) n = std::min(n, 2 * last_);
    last_ = n;
    return n;
}

void SliceSizer::measured(std::uint32_t units, double ms) {
    if (!(ms > 0.5)) return;
    double rate = units / ms;
    unitsPerMs_ = rule_ == Rate::Slowest && unitsPerMs_ > 0 ? std::min(unitsPerMs_, rate) : rate;
}

}  // namespace curette
