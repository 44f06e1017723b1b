// A thread-safe progress bar on stderr, drawn only when stderr is a terminal or when forced
// (--progress), redrawn at most ten times a second.
#pragma once
#include <atomic>
#include <chrono>
#include <mutex>
#include <string>

namespace pft::host {

class Progress {
public:
    /** enabled: draw at all; use progress_wanted() to decide. */
    Progress(std::size_t total, std::string label, bool enabled);
    ~Progress();
    void tick(std::size_t n = 1);  ///< safe from any thread
    void finish();                  ///< final redraw and newline (idempotent)

private:
    std::size_t total_;
    std::string label_;
    bool enabled_;
    std::atomic<std::size_t> done_{0};
    std::mutex mu_;
    std::chrono::steady_clock::time_point start_, last_draw_;
    bool finished_ = false;
    void draw(std::size_t done);
};

/** True when stderr is a terminal, or when `forced`. */
bool progress_wanted(bool forced);

}  // namespace pft::host
