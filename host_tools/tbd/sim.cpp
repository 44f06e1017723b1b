#include "sim.hpp"

#include <cmath>
#include <random>

namespace pft::host::tbd {

namespace {
std::mt19937_64 stream(uint64_t seed, uint64_t which)
{
    std::seed_seq seq{static_cast<uint32_t>(seed), static_cast<uint32_t>(seed >> 32),
                      static_cast<uint32_t>(which), 0x5054u /* "PT" */};
    return std::mt19937_64(seq);
}
}  // namespace

std::vector<std::vector<TruthState>> simulate_truth(const Scenario &s, uint64_t seed, int frames)
{
    if (frames <= 0)
        frames = s.frames;
    std::mt19937_64 rng = stream(seed, 1);
    std::normal_distribution<double> g(0.0, 1.0);
    const double T = s.T;
    // Cholesky factor of Q_s = q1 [[T^3/3, T^2/2], [T^2/2, T]]
    const double a = std::sqrt(s.q1 * T * T * T / 3.0);
    const double b = a > 0 ? (s.q1 * T * T / 2.0) / a : 0.0;
    const double c2 = s.q1 * T - b * b;
    const double c = c2 > 0 ? std::sqrt(c2) : 0.0;
    const double si = std::sqrt(s.q2 * T);

    std::vector<std::vector<TruthState>> truth(frames, std::vector<TruthState>(s.targets.size()));
    for (std::size_t ti = 0; ti < s.targets.size(); ++ti) {
        const Target &t = s.targets[ti];
        if (t.birth > frames)
            continue;  // a short sequence (bench --frames) ends before this target is born
        TruthState st;
        st.x = t.x0[0];
        st.vx = t.x0[1];
        st.y = t.x0[2];
        st.vy = t.x0[3];
        st.I = t.x0[4];
        if (t.spawn_from) {
            // the parent is listed earlier (checked at parse time), so its truth exists
            std::size_t pi = 0;
            while (s.targets[pi].id != t.spawn_from)
                ++pi;
            const TruthState &p = truth[t.birth - 1][pi];
            st.x = p.x;
            st.y = p.y;
        }
        for (int k = t.birth; k <= t.death && k <= frames; ++k) {
            if (k > t.birth) {
                st.x += T * st.vx;
                st.y += T * st.vy;
                if (t.motion == Motion::StochasticCV) {
                    double n1 = g(rng), n2 = g(rng), n3 = g(rng), n4 = g(rng), n5 = g(rng);
                    st.x += a * n1;
                    st.vx += b * n1 + c * n2;
                    st.y += a * n3;
                    st.vy += b * n3 + c * n4;
                    st.I += si * n5;
                }
            }
            st.present = true;
            truth[k - 1][ti] = st;
        }
    }
    return truth;
}

void render_psf(const Scenario &s, const std::vector<TruthState> &targets, std::vector<double> &img)
{
    img.assign(static_cast<std::size_t>(s.width) * s.height, 0.0);
    const double inv2s2 = 1.0 / (2.0 * s.psf_sigma * s.psf_sigma);
    for (const auto &t : targets) {
        if (!t.present)
            continue;
        const double amp = s.peak(t.I);
        for (int r = 0; r < s.height; ++r) {
            const double dy = r * s.dy - t.y;  // row r is centred at r dy (0-based)
            const double ey = std::exp(-dy * dy * inv2s2);
            double *row = &img[static_cast<std::size_t>(r) * s.width];
            for (int c = 0; c < s.width; ++c) {
                const double dx = c * s.dx - t.x;
                row[c] += amp * ey * std::exp(-dx * dx * inv2s2);
            }
        }
    }
}

Sequence simulate(const Scenario &s, uint64_t seed, int frames, bool want_images)
{
    if (frames <= 0)
        frames = s.frames;
    Sequence q;
    q.width = s.width;
    q.height = s.height;
    q.frames = frames;
    q.truth = simulate_truth(s, seed, frames);
    if (!want_images)
        return q;
    std::mt19937_64 rng = stream(seed, 2);
    std::normal_distribution<double> g(0.0, s.noise_sigma);
    std::vector<double> psf;
    q.images.resize(frames);
    for (int k = 0; k < frames; ++k) {
        render_psf(s, q.truth[k], psf);
        auto &im = q.images[k];
        im.resize(psf.size());
        for (std::size_t i = 0; i < psf.size(); ++i)
            im[i] = static_cast<float>(psf[i] + g(rng));
    }
    return q;
}

}  // namespace pft::host::tbd
