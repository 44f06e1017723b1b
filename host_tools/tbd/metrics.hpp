// Performance measures of docs/algorithms.md section 6 ([P1] metrics) for one run and their
// Monte Carlo aggregate with the contract field names of `pft eval`.
//
// Association, per frame: every reported track point within d_assoc of a present target is a
// candidate; pairs are taken greedily by increasing distance, one track per target and one
// target per track. A track may thus follow different targets in different frames (a swap when
// targets cross); a track never associated with any target is a false track.
// Per target (1-based frames, life birth..death):
//   appearance delay    = first frame of the life with an associated track - birth
//   disappearance delay = frame at which the track that followed the target last was declared
//                         gone (or first associated with another target) - death; negative
//                         when the target was lost early; a track still alive at the end of the
//                         sequence counts with the lower bound frames + 1 - death and is
//                         reported in censored_disappearances
//   confirmation delay  = first frame of the life at which a new track is confirmed whose first
//                         point is associated with the target - birth (differs from the
//                         appearance delay when an existing track moves onto a spawned target)
//   correct frames      = frames of the life whose associated track is within d_c of the truth
//   RMSE                = eq. 25 over the correct points, pooled over runs
//   false tracks        = per target: distinct tracks associated with it beyond the first
//                         (re-acquisitions, swaps); overall: those plus the never-associated
//                         tracks, per run.
//   detection rate      = runs in which the target was ever associated / runs; the appearance
//                         delay over all runs counts a miss as the whole life (true_frames).
// Set measures per frame (common/set_metrics.hpp): GOSPA (alpha 2) and OSPA between the present
// targets' true positions and every track point reported at that frame, cut-off gospa_c
// (default d_assoc) and order gospa_p (default 2).
#pragma once
#include <cstdint>
#include <vector>

#include <nlohmann/json.hpp>

#include "../common/set_metrics.hpp"
#include "pcrlb.hpp"
#include "scenario.hpp"
#include "sim.hpp"
#include "tracker.hpp"

namespace pft::host::tbd {

struct TrackHist {
    uint32_t id = 0;
    int first = 0;          ///< first frame reported
    int last = 0;           ///< last frame reported
    int end_frame = 0;      ///< frame at which it was declared gone (0: alive at the end)
    std::vector<int> frames;
    std::vector<double> xs, ys, ps;
    std::vector<int> assoc; ///< per point: target index it was associated with, -1: none
    int assigned = -1;      ///< target it was associated with most often, -1: never (false track)
};

struct TargetRun {
    bool detected = false;
    int appear_frame = 0;
    double appear_delay = 0;
    bool confirmed = false; ///< a new track was confirmed on this target during its life
    double confirm_delay = 0; ///< first such confirmation frame - birth
    bool censored = false;  ///< last assigned track still alive at the end of the sequence
    double disappear_delay = 0;
    int correct = 0;
    int true_frames = 0;
    double sq_correct = 0;  ///< sum of squared radial errors over correct points
    double sq_all = 0;      ///< ... over every assigned point in the life
    int n_all = 0;
    int tracks = 0;         ///< assigned tracks
    std::vector<double> err2;     ///< per frame: squared error of a correct point, NaN if none
    std::vector<double> p_exist;  ///< per frame
};

/** One frame's set measures, kept as their additive terms (see SetMetricSums). */
struct SetFrame {
    double localisation = 0;  ///< sum of d^p over the GOSPA pairs
    int missed = 0, false_ = 0;
    double ospa_pow = 0;      ///< OSPA^p
};

struct RunEval {
    uint64_t seed = 0;
    std::vector<SetFrame> set;     ///< per frame
    std::vector<TargetRun> targets;
    std::vector<TrackHist> tracks;
    int unassigned = 0;
    int declared_points = 0, incorrect_points = 0;
    std::vector<double> search_p;  ///< per frame
};

std::vector<TrackHist> collect_tracks(const std::vector<FrameOut> &out);

RunEval evaluate_run(const Scenario &s, const std::vector<std::vector<TruthState>> &truth,
                     const std::vector<FrameOut> &out, bool single);

/** Floor of section 7 for one target of the scenario (its motion, intensity, life length). */
PcrlbResult target_floor(const Scenario &s, const Target &t);

/** The eval summary (contract names, see docs/host_tools.md) from the runs. */
nlohmann::json summarize(const Scenario &s, const std::vector<RunEval> &runs, bool single);

/** GOSPA/OSPA cut-off of a scenario: eval.gospa_c, else d_assoc. */
double gospa_cutoff(const Scenario &s);

/** A run's record in a partial summary (everything summarize reads), and back. */
nlohmann::json run_to_json(const RunEval &r);
RunEval run_from_json(const nlohmann::json &j);

}  // namespace pft::host::tbd
