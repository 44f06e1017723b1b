#include "parallel.hpp"

#include <atomic>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace pft::host {

unsigned resolve_threads(unsigned requested)
{
    if (requested)
        return requested;
    unsigned hw = std::thread::hardware_concurrency();
    return hw ? hw : 1;
}

void parallel_for(std::size_t n, unsigned threads, const std::function<void(std::size_t)> &fn)
{
    unsigned t = resolve_threads(threads);
    if (t > n)
        t = static_cast<unsigned>(n ? n : 1);
    std::atomic<std::size_t> next{0};
    std::atomic<bool> stop{false};
    std::exception_ptr err;
    std::mutex err_mu;
    auto worker = [&]() {
        for (;;) {
            if (stop.load())
                return;
            std::size_t i = next++;
            if (i >= n)
                return;
            try {
                fn(i);
            } catch (...) {
                std::lock_guard<std::mutex> lk(err_mu);
                if (!err)
                    err = std::current_exception();
                stop = true;
            }
        }
    };
    if (t <= 1) {
        worker();
    } else {
        std::vector<std::thread> pool;
        pool.reserve(t);
        for (unsigned k = 0; k < t; ++k)
            pool.emplace_back(worker);
        for (auto &th : pool)
            th.join();
    }
    if (err)
        std::rethrow_exception(err);
}

}  // namespace pft::host
