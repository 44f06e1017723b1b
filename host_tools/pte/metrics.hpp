// Measures of docs/algorithms.md 6 (Deng et al. 2011, as used by He et al. 2015) for one target:
// a declared point (a reported track at a frame) is correct when it is the report nearest to
// the truth and within d_c cells; detection probability = correct points / true frames;
// 3-frame reliable tracking = frames with correct points at k-2, k-1, k / true frames from
// the third on; false-track probability = incorrect declared points / declared points;
// RMSE over the correct points. Declared points are the reports flagged `detected` (the
// method's own detection test passed at that frame: PTE T* >= eta_T, every DP report, a DBT
// track updated by a plot); with_coasting = true also counts reports carried on without a
// detection (PTE misses, DBT coasting) [A].
#pragma once
#include <vector>

#include <nlohmann/json.hpp>

#include "../common/set_metrics.hpp"
#include "methods.hpp"
#include "sim.hpp"

namespace pft::host::pte {

struct Counts {
    long long true_frames = 0, correct = 0, declared = 0, false_points = 0;
    long long rel_num = 0, rel_den = 0, frames = 0;
    double sq = 0.0;       ///< sum of squared errors of the correct points (cells^2)
    double time_s = 0.0;   ///< update time summed over frames
    /// GOSPA (alpha = 2) and OSPA per frame between the targets present and the declared
    /// reports (positions in cells), accumulated over every frame (set: one slot for the
    /// averages) and per frame (per_frame: one slot per frame, for the curves over the runs)
    double gospa_c = 3.0, gospa_p = 2.0;
    metrics::SetMetricSums set{1, 3.0, 2.0};
    metrics::SetMetricSums per_frame{0, 3.0, 2.0};
    void add(const Counts &o);
    double detection_prob() const;
    double reliable3_prob() const;
    double false_track_prob() const;  ///< 0 when nothing was declared
    double rmse() const;              ///< NaN without correct points
    double us_per_frame() const;
    nlohmann::json to_json() const;
    /** Every member exactly (a run's record in a partial summary of `pft eval --shard`);
     *  from_raw(raw()) adds bit for bit like the original. */
    nlohmann::json raw() const;
    static Counts from_raw(const nlohmann::json &j);
};

/** Scores one run; correct (optional) receives a 0/1 flag per frame. The target counts as
 *  present at frames whose true range lies inside the window [0, cells - 1]. */
Counts score_run(const std::vector<Truth> &truth, const std::vector<std::vector<Report>> &out,
                 int cells, double d_c, std::vector<char> *correct = nullptr, bool with_coasting = false,
                 double gospa_c = 0.0, double gospa_p = 2.0);

/** Several targets ([target][frame]): at each frame the declared reports are assigned one to
 *  one to the targets present (active and inside the window), closest pairs first, within
 *  d_c cells; an assigned report is a correct point of its target, every other declared
 *  report is false. true_frames counts target-frames; reliable3 is counted per target. With
 *  one target this is score_run. */
Counts score_runs(const std::vector<std::vector<Truth>> &truths, const std::vector<std::vector<Report>> &out,
                  int cells, double d_c, bool with_coasting = false, double gospa_c = 0.0, double gospa_p = 2.0);
// GOSPA / OSPA (host_tools/common/set_metrics.hpp) are computed at every frame of score_run and
// score_runs with cut-off gospa_c (0: d_c) and order gospa_p, on the same declared reports.

}  // namespace pft::host::pte
