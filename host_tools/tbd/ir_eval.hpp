// Measures of a tbd_ir run against its truth (self-contained; meant to move onto the common
// evaluation skeleton later).
//
// Association, per frame: every track point within d_assoc of a truth point is a candidate;
// pairs are taken greedily by increasing distance, one track per target and one target per
// track. Per target (injected or labelled): detected when some track was associated with it in
// some frame; appearance delay = first associated frame - first frame present; correct frames
// = frames whose associated track is within d_c; RMSE over the correct points. A track never
// associated with any target is a false track.
#pragma once
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "ir_sim.hpp"
#include "tracker.hpp"

namespace pft::host::tbd_ir {

struct TargetResult {
    int id = 0;
    bool labelled = false;
    double snr_db = NAN;
    int first = 0, last = 0, present = 0;  ///< frames
    bool detected = false;
    int appear_delay = 0;
    int correct = 0;
    double sq_correct = 0;
    int tracks = 0;                        ///< distinct tracks associated with it
    double first_x = NAN, first_y = NAN;   ///< its truth position in its first frame
    std::string entry;                     ///< the frame border it entered by ("left", "right", "top", "bottom": its first truth point within 2 px of it, checked in that order), "inside", or "" when the frame size is unknown
};

/** Where and when a track was reported (frame coordinates, 1-based frames): the entries of
 *  IrRunEval's false_list and target_list. */
struct TrackSpan {
    uint32_t id = 0;
    int first = 0, last = 0, frames = 0;   ///< first and last reported frame, frames reported
    double x = 0, y = 0;                   ///< position in its first reported frame
    double scene_x = NAN, scene_y = NAN;   ///< the same in the background image (set by the caller)
};

struct IrRunEval {
    uint64_t seed = 0;
    int frames = 0;
    std::vector<TargetResult> targets;
    int tracks = 0, false_tracks = 0;
    std::vector<uint32_t> false_ids;
    std::vector<TrackSpan> false_list;    ///< one per false track, in the order of false_ids
    std::vector<TrackSpan> target_list;   ///< the same spans for the tracks associated with a target in some frame, by id
    /// injected targets' frames (1-based frame > 1, inside the image), and those with a birth
    /// candidate of the search layer within 1 px (Chebyshev) of the target's nearest pixel
    long birth_frames = 0, birth_hits = 0;
};

/** truth.csv of tbd_ir: frame,id,x,y,snr_db,kind; InputError naming the file and line. */
std::vector<TruthRow> read_ir_truth(const std::string &path);
void write_ir_truth(const std::string &path, const std::vector<TruthRow> &rows);

/** out[i] is the frame out[i].frame (1-based). */
IrRunEval evaluate_ir(const std::vector<TruthRow> &truth, const std::vector<tbd::FrameOut> &out,
                      double d_c, double d_assoc);

/** Aggregate over runs: overall ("averaged") and per kind of target. */
nlohmann::json summarize_ir(const std::vector<IrRunEval> &runs);

/** The lines of a printed summary table. */
void print_ir_summary(const nlohmann::json &sum);

}  // namespace pft::host::tbd_ir
