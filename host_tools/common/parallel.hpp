// Runs fn(i) for i in [0, n) on `threads` worker threads (a small work-sharing pool: each
// worker takes the next index). The first exception thrown by any job is rethrown after all
// workers stopped; remaining jobs are skipped.
#pragma once
#include <cstddef>
#include <functional>

namespace pft::host {

/** threads == 0 means std::thread::hardware_concurrency(). */
void parallel_for(std::size_t n, unsigned threads, const std::function<void(std::size_t)> &fn);

/** The thread count actually used for `requested` (0 = hardware). */
unsigned resolve_threads(unsigned requested);

}  // namespace pft::host
