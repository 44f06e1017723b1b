#include "progress.hpp"

#include <cstdio>

#include <unistd.h>

namespace pft::host {

bool progress_wanted(bool forced) { return forced || ::isatty(STDERR_FILENO) == 1; }

Progress::Progress(std::size_t total, std::string label, bool enabled)
    : total_(total), label_(std::move(label)), enabled_(enabled),
      start_(std::chrono::steady_clock::now()), last_draw_(start_)
{
    if (enabled_)
        draw(0);
}

Progress::~Progress() { finish(); }

void Progress::tick(std::size_t n)
{
    std::size_t d = done_ += n;
    if (!enabled_)
        return;
    auto now = std::chrono::steady_clock::now();
    std::lock_guard<std::mutex> lk(mu_);
    if (d < total_ && now - last_draw_ < std::chrono::milliseconds(100))
        return;
    last_draw_ = now;
    draw(d);
}

void Progress::finish()
{
    std::lock_guard<std::mutex> lk(mu_);
    if (finished_ || !enabled_) {
        finished_ = true;
        return;
    }
    finished_ = true;
    draw(done_.load());
    std::fputc('\n', stderr);
    std::fflush(stderr);
}

void Progress::draw(std::size_t done)
{
    const int width = 30;
    double frac = total_ ? static_cast<double>(done) / static_cast<double>(total_) : 1.0;
    if (frac > 1.0)
        frac = 1.0;
    int fill = static_cast<int>(frac * width + 0.5);
    double el = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    double eta = done ? el * (static_cast<double>(total_) - static_cast<double>(done)) /
                            static_cast<double>(done)
                      : 0.0;
    char bar[width + 1];
    for (int i = 0; i < width; ++i)
        bar[i] = i < fill ? '#' : '.';
    bar[width] = 0;
    std::fprintf(stderr, "\r%s [%s] %zu/%zu  %.1fs elapsed, ETA %.1fs   ", label_.c_str(), bar,
                 done, total_, el, eta);
    std::fflush(stderr);
}

}  // namespace pft::host
