#include "gl/timer.h"

#include <cassert>

namespace curette::gl {

void TimerSet::begin(const std::string& name) {
    assert(!open_ && "GL timer scopes cannot nest");
    Scope* scope = nullptr;
    for (Scope& s : scopes_)
        if (s.name == name) scope = &s;
    if (!scope) scope = &scopes_.emplace_back(Scope{name, {}, 0, 0.0});
    open_ = scope;
    if (synchronous_) {
        glFinish();
        ++scope->used;
        started_ = std::chrono::steady_clock::now();
        return;
    }
    if (scope->used == scope->queries.size()) scope->queries.push_back(createQuery(GL_TIME_ELAPSED));
    glBeginQuery(GL_TIME_ELAPSED, scope->queries[scope->used++].name());
}

void TimerSet::end() {
    assert(open_);
    if (synchronous_) {
        glFinish();
        open_->synchronousMs += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - started_).count();
    } else {
        glEndQuery(GL_TIME_ELAPSED);
    }
    open_ = nullptr;
}

std::vector<std::pair<std::string, double>> TimerSet::collectMilliseconds() {
    std::vector<std::pair<std::string, double>> result;
    for (Scope& s : scopes_) {
        if (!s.used) continue;
        double total = s.synchronousMs;
        s.synchronousMs = 0;
        for (std::size_t i = 0; i < s.used && !synchronous_; ++i) {
            GLuint64 ns = 0;
            glGetQueryObjectui64v(s.queries[i].name(), GL_QUERY_RESULT, &ns);
            total += static_cast<double>(ns) * 1e-6;
        }
        result.emplace_back(s.name, total);
        s.used = 0;
    }
    return result;
}

}  // namespace curette::gl
