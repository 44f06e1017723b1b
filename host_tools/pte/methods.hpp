// The three trackers of the multi-frame TBD comparison behind one C++ interface: PTE-TBD,
// sliding DP-TBD and the Kalman DBT (pft_pte.h), configured from the library defaults,
// the scenario's background (fixed sigma or CA-CFAR) and the scenario's per-method overrides.
// Thresholds not given in the scenario are set by the library's noise-only Monte Carlo.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

extern "C" {
#include "pft/pft_pte.h"
}

#include "../common/real.hpp"
#include "scenario.hpp"

namespace pft::host::pte {

using ::pft::host::from_real;
using ::pft::host::numeric_name;
using ::pft::host::to_real;

/** Method names in evaluation order and their labels. */
std::string method_label(const std::string &name);  // "PTE-TBD", "DP-TBD", "Kalman DBT"

struct Report {
    uint32_t id = 0;
    bool detected = false;
    double pos = 0.0, vel = 0.0, var = 0.0, amplitude = 0.0, score = 0.0;
    uint32_t age = 0;
};

struct MethodSpec {
    std::string name;   ///< pte | dp | dbt
    pft_pte_config_t pte{};
    pft_pte_dp_config_t dp{};
    pft_pte_dbt_config_t dbt{};
    bool threshold_from_mc = false;
    double threshold = 0.0;   ///< DP V_T / PTE init V_T / DBT zeta threshold
    /** Every setting as JSON (reals as doubles). */
    nlohmann::json settings() const;
    /** "PTE-TBD M=40", "DP-TBD K=10", "Kalman DBT". */
    std::string label() const;
};

/** Library defaults + background + overrides; runs the threshold Monte Carlo when the scenario
 *  gives no threshold (cached per configuration within the process). */
MethodSpec make_spec(const Scenario &s, const std::string &name);

class Method {
public:
    explicit Method(const MethodSpec &spec);
    Method(const Method &) = delete;
    Method &operator=(const Method &) = delete;
    /** Pushes one profile (cells floats, input units); InputError on a library refusal. */
    /** One frame numbered seq (frames lost before it leave holes in the numbering). */
    const std::vector<Report> &update(const float *z, uint32_t seq);
    const std::vector<Report> &update(const float *z) { return update(z, seq_++); }
    std::size_t workspace_bytes() const { return ws_bytes_; }
    const MethodSpec &spec() const { return spec_; }

private:
    MethodSpec spec_;
    std::vector<uint64_t> work_;
    std::size_t ws_bytes_ = 0;
    pft_pte_t pte_{};
    pft_pte_dp_t dp_{};
    pft_pte_dbt_t dbt_{};
    std::vector<Report> out_;
    std::vector<pft_pte_report_t> rep_;
    uint32_t seq_ = 0;
};

}  // namespace pft::host::pte
