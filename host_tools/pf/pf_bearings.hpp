// The Gordon-Salmond-Smith bearings-only benchmark (docs/algorithms.md 3.1) on the host: scenario
// files (kind "pf_bearings"), the double-precision truth and measurement simulator, and one
// filter's pass over a simulated sequence through the library's engine and bearings model.
//
// Units: the scenario and every reported number are in the benchmark's units; the library
// model works in positions times `scale` (pft_pf_models.h), converted here.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <memory>

#include <nlohmann/json.hpp>

extern "C" {
#include "pft/pft_pf_models.h"
}

#include "pf_runner.hpp"

namespace pft::host::pf {

struct BearingsScenario {
    std::string file, name, description;
    int steps = 24;
    double T = 1.0;
    double q_sd = 0.001;                                  ///< sqrt(q)
    double r_sd = 0.005;                                  ///< sqrt(r), rad
    std::array<double, 4> x0{-0.05, 0.001, 0.7, -0.055};  ///< truth at k = 0: x, vx, y, vy
    bool truth_noise = true;         ///< truth driven by the process noise (Gordon et al.)
    std::array<double, 4> prior_mean{0.0, 0.0, 0.4, -0.05};
    std::array<double, 4> prior_sd{0.5, 0.005, 0.3, 0.01};
    int scale = 1000;                ///< model units per benchmark unit
    double ll_clip = 50.0;           ///< see pft_pf_bearings_config_t
    std::vector<EngineSpec> filters;
    std::vector<uint32_t> particles{100, 200, 500, 1000, 2000, 5000};
    uint32_t table_particles = 1000; ///< N of the per-step tables (paper's Table 1)
    double lost_radius = 0.1;        ///< runs whose final radial error exceeds this are counted
    bool has_reference_filter = false;
    EngineSpec reference_filter;     ///< a large-N filter whose mean stands in for the exact
                                     ///< posterior mean (Monte Carlo error of the others)
    unsigned runs = 100;
    uint64_t base_seed = 1;
    nlohmann::json reference;        ///< paper figures to print beside ours
    nlohmann::json raw;
};

/** Parses and validates (InputError naming the field). */
BearingsScenario parse_bearings(const nlohmann::json &j, const std::string &file);

struct BearingsSequence {
    std::vector<std::array<double, 4>> truth;  ///< x_1 .. x_K
    std::vector<double> z;                     ///< bearings z_1 .. z_K in (-pi, pi]
};

/** Truth from x0 with the process noise (if truth_noise) and noisy bearings; own RNG stream
 *  of `seed` (std::mt19937_64 seeded through seed_seq, deterministic on one platform). */
BearingsSequence simulate_bearings(const BearingsScenario &s, uint64_t seed, int steps = 0);

/** The library model configuration (scaled units). */
pft_pf_bearings_config_t bearings_config(const BearingsScenario &s, double first_r_sd);

/** One filter over one sequence. */
struct PassResult {
    std::vector<double> ex, ey;       ///< estimate - truth per step (benchmark units)
    std::vector<double> dref;         ///< squared distance to the reference filter's estimate
    std::vector<std::array<double, 4>> est;  ///< estimates per step (benchmark units)
    double ns = 0;                    ///< total update time (steady_clock)
    double ess_sum = 0, ess_first_sum = 0;
    int resamples = 0;
};

/** A filter (engine + bearings model) bound to one configuration, reused across runs. */
class BearingsFilter {
public:
    BearingsFilter(const BearingsScenario &s, const EngineSpec &e, uint32_t n);
    BearingsFilter(const BearingsFilter &) = delete;
    BearingsFilter &operator=(const BearingsFilter &) = delete;
    /** Resets with `seed` and filters the whole sequence. */
    PassResult pass(const BearingsSequence &q, uint64_t seed);
    std::size_t workspace_bytes() const { return runner_->workspace_bytes(); }

private:
    double scale_;
    pft_pf_bearings_model_t model_{};
    pft_pf_model_t iface_{};
    std::unique_ptr<PfRunner> runner_;
};

/** Wrap to (-pi, pi]. */
double wrap_pi(double a);

}  // namespace pft::host::pf
