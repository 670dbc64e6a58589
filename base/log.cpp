#include "base/log.h"

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <mutex>

namespace curette::log {

static Level initialLevel() {
    const char* env = std::getenv("CURETTE_LOG");
    if (!env) return Level::Warn;
    if (!std::strcmp(env, "debug")) return Level::Debug;
    if (!std::strcmp(env, "info")) return Level::Info;
    if (!std::strcmp(env, "error")) return Level::Error;
    return Level::Warn;
}

static std::atomic<Level>& current() {
    static std::atomic<Level> value{initialLevel()};
    return value;
}

void setLevel(Level l) { current() = l; }
Level level() { return current(); }

void write(Level l, std::string_view message) {
    if (l < current().load()) return;
    static std::mutex mutex;
    static const char* names[] = {"debug", "info", "warning", "error"};
    std::lock_guard lock(mutex);
    std::fprintf(stderr, "curette: %s: %.*s\n", names[static_cast<int>(l)], static_cast<int>(message.size()),
                 message.data());
}

}  // namespace curette::log
