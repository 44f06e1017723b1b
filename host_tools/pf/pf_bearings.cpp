#include "pf_bearings.hpp"

#include <chrono>
#include <cmath>
#include <memory>
#include <random>

#include "../common/errors.hpp"
#include "../common/json_field.hpp"
#include "../tbd/tracker.hpp"

namespace pft::host::pf {

double wrap_pi(double a)
{
    const double pi = 3.14159265358979323846;
    while (a > pi)
        a -= 2.0 * pi;
    while (a <= -pi)
        a += 2.0 * pi;
    return a;
}

namespace {
std::array<double, 4> four(const Field &f, const char *key, std::array<double, 4> dflt)
{
    if (!f.has(key))
        return dflt;
    auto v = f.numbers(key, 4);
    return {v[0], v[1], v[2], v[3]};
}
}  // namespace

namespace {

/** "model", "truth" and "prior". */
void parse_model(const Field &root, BearingsScenario &s)
{
    if (root.has("model")) {
        Field m = root.at("model");
        m.only({"T", "q_sd", "r_sd"});
        s.T = m.number_in("T", 1.0, 1e-6, 1e6);
        s.q_sd = m.number_in("q_sd", 0.001, 0.0, 1e6);
        s.r_sd = m.number_in("r_sd", 0.005, 1e-6, 3.0);
    }
    if (root.has("truth")) {
        Field t = root.at("truth");
        t.only({"x0", "process_noise"});
        s.x0 = four(t, "x0", s.x0);
        s.truth_noise = t.boolean_or("process_noise", true);
    }
    if (root.has("prior")) {
        Field p = root.at("prior");
        p.only({"mean", "sd"});
        s.prior_mean = four(p, "mean", s.prior_mean);
        s.prior_sd = four(p, "sd", s.prior_sd);
        for (double v : s.prior_sd)
            if (v < 0)
                p.at("sd").fail("standard deviations must be >= 0");
    }
}

/** "filters" (default SIS, SIR, APF), "particles" and "table_particles". */
void parse_filters(const Field &root, BearingsScenario &s)
{
    if (root.has("filters")) {
        Field fl = root.at("filters");
        for (std::size_t i = 0; i < fl.size(); ++i)
            s.filters.push_back(parse_engine(fl.at(i), false));
    } else {
        for (const char *e : {"sis", "sir", "apf"}) {
            EngineSpec sp;
            sp.engine = e;
            sp.label = e == std::string("sis") ? "SIS" : e == std::string("sir") ? "SIR" : "APF";
            s.filters.push_back(sp);
        }
    }
    if (s.filters.empty())
        root.at("filters").fail("at least one filter");
    for (std::size_t i = 0; i < s.filters.size(); ++i)
        for (std::size_t k = 0; k < i; ++k)
            if (s.filters[i].label == s.filters[k].label)
                root.at("filters").at(i).fail("duplicate label \"" + s.filters[i].label + "\"");
    if (root.has("particles")) {
        Field pn = root.at("particles");
        s.particles.clear();
        for (std::size_t i = 0; i < pn.size(); ++i) {
            int64_t v = pn.at(i).as_int();
            if (v < 1 || v > static_cast<int64_t>(PFT_CFG_MAX_PARTICLES))
                pn.at(i).fail("particle count out of range");
            s.particles.push_back(static_cast<uint32_t>(v));
        }
        if (s.particles.empty())
            pn.fail("at least one particle count");
    }
    s.table_particles = static_cast<uint32_t>(
        root.integer_in("table_particles", s.particles.size() > 3 ? s.particles[3] : s.particles.back(),
                        1, PFT_CFG_MAX_PARTICLES));
}

}  // namespace

BearingsScenario parse_bearings(const nlohmann::json &j, const std::string &file)
{
    Field root(j, file);
    root.only({"kind", "name", "description", "steps", "model", "truth", "prior", "scale",
               "ll_clip", "filters", "particles", "table_particles", "lost_radius", "eval",
               "reference", "reference_filter"});
    BearingsScenario s;
    s.file = file;
    s.raw = j;
    s.name = root.string_or("name", "");
    s.description = root.string_or("description", "");
    s.steps = static_cast<int>(root.integer_in("steps", 24, 1, 100000));
    parse_model(root, s);
    s.scale = static_cast<int>(root.integer_in("scale", 1000, 1, 100000));
    s.ll_clip = root.number_in("ll_clip", 50.0, 1.0, 1000.0);
    parse_filters(root, s);
    s.lost_radius = root.number_in("lost_radius", 0.1, 0.0, 1e9);
    if (root.has("reference_filter")) {
        Field rf = root.at("reference_filter");
        s.reference_filter = parse_engine(rf, true);
        if (!s.reference_filter.match_time_of.empty() || s.reference_filter.engine == "rbpf")
            rf.fail("a reference filter is sis, sir or apf with a particle count");
        s.has_reference_filter = true;
    }
    if (root.has("eval")) {
        Field e = root.at("eval");
        e.only({"runs", "base_seed"});
        s.runs = static_cast<unsigned>(e.integer_in("runs", 100, 1, 10000000));
        s.base_seed = static_cast<uint64_t>(e.integer_in("base_seed", 1, 0, INT64_MAX));
    }
    if (root.has("reference"))
        s.reference = root.at("reference").node();
    // every position must stay inside the q16 range in model units (checked on the prior's
    // 5-sigma box and the truth's start)
    for (int c = 0; c < 4; ++c) {
        double lim = (std::fabs(s.prior_mean[c]) + 5.0 * s.prior_sd[c]) * s.scale;
        if (lim > 30000.0 || std::fabs(s.x0[c]) * s.scale > 30000.0)
            root.fail("scale " + std::to_string(s.scale) +
                      " puts the prior or the truth outside the Q16.16 range (+-32768 model units)");
    }
    return s;
}

BearingsSequence simulate_bearings(const BearingsScenario &s, uint64_t seed, int steps)
{
    if (steps <= 0)
        steps = s.steps;
    std::seed_seq seq{static_cast<uint32_t>(seed), static_cast<uint32_t>(seed >> 32), 7u, 0x4252u /* "BR" */};
    std::mt19937_64 rng(seq);
    std::normal_distribution<double> g(0.0, 1.0);
    BearingsSequence q;
    std::array<double, 4> x = s.x0;
    const double T = s.T;
    for (int k = 0; k < steps; ++k) {
        double w1 = s.truth_noise ? s.q_sd * g(rng) : 0.0;
        double w2 = s.truth_noise ? s.q_sd * g(rng) : 0.0;
        x[0] += T * x[1] + 0.5 * T * T * w1;
        x[1] += T * w1;
        x[2] += T * x[3] + 0.5 * T * T * w2;
        x[3] += T * w2;
        q.truth.push_back(x);
        q.z.push_back(wrap_pi(std::atan2(x[2], x[0]) + s.r_sd * g(rng)));
    }
    return q;
}

pft_pf_bearings_config_t bearings_config(const BearingsScenario &s, double first_r_sd)
{
    using tbd::to_real;
    pft_pf_bearings_config_t c;
    pft_pf_bearings_config_default(&c, s.scale);
    const double k = s.scale;
    c.T = to_real(s.T);
    c.q_sd = to_real(s.q_sd * k);
    c.r_sd = to_real(s.r_sd);
    for (int i = 0; i < 4; ++i) {
        c.prior_mean[i] = to_real(s.prior_mean[i] * k);
        c.prior_sd[i] = to_real(s.prior_sd[i] * k);
    }
    c.ll_clip = to_real(s.ll_clip);
    c.first_r_sd = to_real(first_r_sd);
    return c;
}

BearingsFilter::BearingsFilter(const BearingsScenario &s, const EngineSpec &e, uint32_t n)
    : scale_(s.scale)
{
    pft_pf_bearings_config_t bc = bearings_config(s, e.first_r_sd);
    if (pft_pf_bearings_model_init(&model_, &bc, &iface_) != PFT_OK)
        throw InputError(s.file + ": the bearings model refuses this configuration");
    runner_ = std::make_unique<PfRunner>(engine_config(e, n, 1), iface_);
}

PassResult BearingsFilter::pass(const BearingsSequence &q, uint64_t seed)
{
    runner_->reset(seed);
    PassResult r;
    const std::size_t K = q.z.size();
    r.ex.resize(K);
    r.ey.resize(K);
    r.est.resize(K);
    for (std::size_t k = 0; k < K; ++k) {
        pft_real_t z = tbd::to_real(q.z[k]);
        auto t0 = std::chrono::steady_clock::now();
        runner_->update(&z);
        auto t1 = std::chrono::steady_clock::now();
        r.ns += std::chrono::duration<double, std::nano>(t1 - t0).count();
        std::vector<double> e = runner_->estimate();
        for (int c = 0; c < 4; ++c)
            r.est[k][c] = e[c] / scale_;
        r.ex[k] = r.est[k][0] - q.truth[k][0];
        r.ey[k] = r.est[k][2] - q.truth[k][2];
        pft_pf_stats_t st = runner_->stats();
        r.ess_sum += tbd::from_real(st.ess_ratio);
        r.ess_first_sum += tbd::from_real(st.ess_first);
        r.resamples += st.resampled ? 1 : 0;
    }
    return r;
}

}  // namespace pft::host::pf
