#pragma once
// GPU timing with GL_TIME_ELAPSED queries (never CPU stopwatches around dispatches, which measure only the
// submission). A TimerSet owns one query per named scope; results are read after the frame has finished.

#include "render/gl/objects.h"

#include <string>
#include <vector>

namespace curette::gl {

class TimerSet {
public:
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
    };
    std::vector<Scope> scopes_;
    Scope* open_ = nullptr;
};

}  // namespace curette::gl
