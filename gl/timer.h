#pragma once
// Per-pass timing. On a GPU: GL_TIME_ELAPSED queries (a CPU stopwatch around a dispatch would measure only
// its submission). On Mesa's llvmpipe the queries read 0 for compute work, and the "GPU" is the CPU
// running each dispatch to completion, so there the scope is timed between glFinish calls instead
// (synchronous mode). A TimerSet owns one query per named scope; results are read after the frame.

#include "gl/objects.h"

#include <chrono>
#include <string>
#include <vector>

namespace curette::gl {

class TimerSet {
public:
    // Synchronous mode: wall time between glFinish calls (set for software renderers).
    void setSynchronous(bool synchronous) { synchronous_ = synchronous; }
    bool synchronous() const { return synchronous_; }
    // Starts the scope `name` (creating its query the first time). Scopes must not nest (GL limitation).
    void begin(const std::string& name);
    void end();
    // Waits for and returns the elapsed milliseconds of every scope run since the last reset, in first-use
    // order, accumulating repeated scopes.
    std::vector<std::pair<std::string, double>> collectMilliseconds();

private:
    struct Scope {
        std::string name;
        std::vector<Query> queries;  // one per begin() this frame
        std::size_t used = 0;
        double synchronousMs = 0;
    };
    bool synchronous_ = false;
    std::chrono::steady_clock::time_point started_;
    std::vector<Scope> scopes_;
    Scope* open_ = nullptr;
};

}  // namespace curette::gl
