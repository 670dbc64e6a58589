#pragma once
// A progress bar on a terminal for anything that may take over a second (loading a large volume, the LAO
// precompute). It draws only when stderr is a terminal and only once the task has run for a second, so
// short tasks and piped output stay quiet.

#include <chrono>
#include <string>

namespace curette {

class Progress {
public:
    Progress(std::string label, double total);
    ~Progress();
    Progress(const Progress&) = delete;
    Progress& operator=(const Progress&) = delete;

    void advance(double amount) { update(done_ + amount); }
    void update(double done);
    void finish();

    // Tests and pipes: force-enable or disable drawing regardless of isatty.
    static void setEnabled(bool enabled);

private:
    void draw(bool final);
    std::string label_;
    double total_;
    double done_ = 0;
    bool drawn_ = false;
    bool finished_ = false;
    std::chrono::steady_clock::time_point start_, lastDraw_;
};

}  // namespace curette
