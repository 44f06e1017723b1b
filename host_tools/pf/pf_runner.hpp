// C++ wrapper over the library's particle-filter engine (pft_pf.h): one engine instance with
// its workspace, driven through a model interface (pft_pf_model_t) owned by the caller.
// Also the engine specification read from scenario files ("sis" | "sir" | "apf", particles,
// resampling scheme and policy), shared by the "pf_bearings" and "pf_tbd" kinds.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

extern "C" {
#include "pft/pft_pf.h"
}

#include "../common/json_field.hpp"

namespace pft::host::pf {

/** One filter of a comparison. */
struct EngineSpec {
    std::string label;             ///< shown in tables and plots (default: upper-case engine)
    std::string engine = "apf";    ///< sis | sir | apf (pf_tbd also: rbpf, the tbd module's RBPF-TBD)
    std::string scheme = "systematic";  ///< systematic | stratified | residual | multinomial
    std::string policy;            ///< always | ess | never ("": the engine's default)
    double ess_threshold = 0.5;    ///< fraction of N for policy "ess"
    double first_r_sd = 0.0;       ///< bearings APF: widened first-stage bearing sd (0: r_sd)
    // pf_tbd only
    uint32_t particles = 0;        ///< particle count of this filter
    std::string match_time_of;     ///< label of a filter whose time per frame this one matches
                                   ///< (its particle count is then calibrated, "equal compute")
    uint32_t budget = 0;           ///< the TBD model's birth budget (pft_pf_tbd_model_set_budget; 0: off)
};

/** Reads one entry of a "filters" array (object with the fields above; unknown fields refused;
 *  "particles" / "match_time_of" only when with_particles, and then one of them is required). */
EngineSpec parse_engine(const Field &f, bool with_particles);
/** The library configuration of a spec for n particles and a seed. */
pft_pf_config_t engine_config(const EngineSpec &e, uint32_t n, uint64_t seed);
/** JSON of a spec (for summaries). */
nlohmann::json engine_json(const EngineSpec &e);

class PfRunner {
public:
    /** InputError with the library's status when init fails. The model's ctx must outlive
     *  the runner. */
    PfRunner(const pft_pf_config_t &cfg, const pft_pf_model_t &model);
    PfRunner(const PfRunner &) = delete;
    PfRunner &operator=(const PfRunner &) = delete;

    void reset(uint64_t seed);
    /** One update; InputError on a refused measurement. */
    void update(const void *z);
    /** The engine's estimate, as doubles. */
    std::vector<double> estimate() const;
    pft_pf_stats_t stats() const;
    std::size_t workspace_bytes() const { return ws_bytes_; }

private:
    pft_pf_config_t cfg_;  // the engine's configuration, the model included
    std::vector<uint64_t> work_;
    std::size_t ws_bytes_ = 0;
    pft_pf_t pf_{};
};

/** Non-inlined per-engine update entry points, so that `callgrind_annotate --inclusive=yes`
 *  attributes instructions to each engine in one profile. */
extern "C" pft_status_t pft_host_update_sis(pft_pf_t *pf, const void *z);
extern "C" pft_status_t pft_host_update_sir(pft_pf_t *pf, const void *z);
extern "C" pft_status_t pft_host_update_apf(pft_pf_t *pf, const void *z);

}  // namespace pft::host::pf
