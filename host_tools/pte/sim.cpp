#include "sim.hpp"

#include <cmath>
#include <memory>
#include <random>

namespace pft::host::pte {

namespace {

std::vector<Truth> truth_of(const Scenario &s, const Motion &m, int frames)
{
    int nf = frames > 0 ? frames : s.frames;
    std::vector<Truth> tr(nf);
    const double T = s.radar.frame_period, h = 1e-3 * T;
    for (int k = 0; k < nf; ++k) {
        double t = k * T;
        double r = slant_range(s.radar, target_position(m, t));
        double rp = slant_range(s.radar, target_position(m, t + h));
        double rm = slant_range(s.radar, target_position(m, t > h ? t - h : 0.0));
        double dt = t > h ? 2.0 * h : h;
        tr[k].range_m = r;
        tr[k].r = range_cells(s.radar, r);
        tr[k].rdot = (rp - rm) / dt * T / s.radar.range_res;
        tr[k].active = m.active(t);
    }
    return tr;
}

}  // namespace

std::vector<Truth> simulate_truth(const Scenario &s, int frames) { return truth_of(s, s.motion, frames); }

std::vector<std::vector<Truth>> simulate_truths(const Scenario &s, int frames)
{
    std::vector<std::vector<Truth>> all;
    if (s.targets.empty())
        all.push_back(truth_of(s, s.motion, frames));
    for (const Motion &m : s.targets)
        all.push_back(truth_of(s, m, frames));
    return all;
}

namespace {

/** Gamma texture fields: nu = shape, built from 2 nu unit Gaussian fields, each AR(1) in time
 *  (coefficient exp(-1/time_corr)) with innovations AR(1) along range (exp(-1/range_corr)),
 *  so every field is N(0,1) at each cell and the texture tau = sum g^2 / (2 nu) is
 *  Gamma(nu, 1/nu) distributed with mean 1. */
class Texture {
public:
    Texture(const Background &b, int cells, std::mt19937_64 &rng)
        : cells_(cells), nf_(static_cast<int>(std::lround(2.0 * b.shape))), rng_(rng)
    {
        rt_ = b.time_corr > 0 ? std::exp(-1.0 / b.time_corr) : 0.0;
        rr_ = b.range_corr > 0 ? std::exp(-1.0 / b.range_corr) : 0.0;
        g_.assign(static_cast<std::size_t>(nf_) * cells_, 0.0);
        for (int f = 0; f < nf_; ++f)
            innovation(&g_[static_cast<std::size_t>(f) * cells_], 1.0, 0.0);
    }
    void step()
    {
        double a = std::sqrt(1.0 - rt_ * rt_);
        for (int f = 0; f < nf_; ++f)
            innovation(&g_[static_cast<std::size_t>(f) * cells_], a, rt_);
    }
    double tau(int u) const
    {
        double s = 0.0;
        for (int f = 0; f < nf_; ++f) {
            double v = g_[static_cast<std::size_t>(f) * cells_ + u];
            s += v * v;
        }
        return s / nf_;
    }

private:
    int cells_, nf_;
    std::mt19937_64 &rng_;
    double rt_ = 0.0, rr_ = 0.0;
    std::vector<double> g_;
    std::normal_distribution<double> n_;
    void innovation(double *g, double a, double keep)
    {
        double b = std::sqrt(1.0 - rr_ * rr_), e = n_(rng_);
        for (int u = 0; u < cells_; ++u) {
            if (u > 0)
                e = rr_ * e + b * n_(rng_);
            g[u] = keep * g[u] + a * e;
        }
    }
};

}  // namespace

Sequence simulate(const Scenario &s, uint64_t seed, int frames)
{
    Sequence q;
    q.cells = s.radar.cells;
    q.frames = frames > 0 ? frames : s.frames;
    q.amplitude = s.amplitude();
    q.truths = simulate_truths(s, q.frames);
    q.truth = q.truths[0];
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> n01;
    const double sig = s.background.sigma;
    double sc = sig, sn = 0.0;  // clutter and thermal standard deviations
    std::unique_ptr<Texture> tex;
    if (s.clutter()) {
        double cnr = std::pow(10.0, s.background.cnr_db / 10.0);
        sc = sig * std::sqrt(cnr / (1.0 + cnr));
        sn = sig * std::sqrt(1.0 / (1.0 + cnr));
        tex = std::make_unique<Texture>(s.background, q.cells, rng);
    }
    const double inv2s2 = 1.0 / (2.0 * s.psf_sigma * s.psf_sigma);
    q.z.assign(q.frames, std::vector<float>(q.cells));
    for (int k = 0; k < q.frames; ++k) {
        if (tex && k > 0)
            tex->step();
        std::vector<float> &z = q.z[k];
        for (int u = 0; u < q.cells; ++u) {
            double v;
            if (tex)
                v = sc * std::sqrt(tex->tau(u)) * n01(rng) + sn * n01(rng);
            else
                v = sig * n01(rng);
            for (const std::vector<Truth> &tr : q.truths) {
                if (!tr[k].active)
                    continue;
                double d = u - tr[k].r;
                if (std::fabs(d) < 8.0 * s.psf_sigma)
                    v += q.amplitude * std::exp(-d * d * inv2s2);
            }
            z[u] = static_cast<float>(v);
        }
    }
    return q;
}

}  // namespace pft::host::pte
