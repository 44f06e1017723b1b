// A diagnostic trace of the IR pipeline's TBD manager against the truth (`pft eval --trace DIR`,
// kind tbd_ir): where an injected target is lost, read from the library's own state after every
// frame. Not a measure of the evaluation (the summary does not change with it); the input of
// host_tools/scripts/ir_miss_diag.py (docs/results/ir_clutter.md, "Branch irmiss").
//
// It reads the manager's layers (the search layer's particles, the track records and track
// layers) through the instance's layout (pft/internal/pft_tbd_types.h), which is NOT API: a
// host diagnostic only, to be adapted when the layout changes.
#pragma once
#include <cstdint>
#include <map>
#include <ostream>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "ir_eval.hpp"
#include "ir_pipeline.hpp"
#include "ir_sim.hpp"

namespace pft::host::tbd_ir {

class IrTrace {
public:
    /** For the run of seed `seed` over q (its truth); the matched filter is the scenario's PSF
     *  (targets.psf_sigma). s and q must outlive the trace. */
    IrTrace(const IrScenario &s, const IrSequence &q, uint64_t seed);
    /** After the pipeline's step of frame k (1-based): the manager's state, the residual it
     *  saw, the tracks reported. */
    void frame(int k, const IrPipeline &pl, const tbd::FrameOut &out);
    /** Writes DIR/s<seed>_targets.csv (one row per frame and truth point) and
     *  DIR/s<seed>_tracks.csv (one row per track layer), the false tracks of ev marked, and
     *  DIR/s<seed>_layers.csv (one row per frame and live track layer: its age, position,
     *  existence probability, intensity, frame log likelihood ratio, the nearest truth point). */
    void write(const std::string &dir, const IrRunEval &ev) const;

private:
    void write_tracks_(std::ostream &f, const IrRunEval &ev) const;
    struct TrackLife {
        uint32_t id = 0;
        int handover = 0, end = 0, alive = 0, reported = 0, first_reported = 0, last_reported = 0;
        double hx = 0, hy = 0, lx = 0, ly = 0;
        double hp = 0;            // existence probability at the hand-over
        double hi = 0, li = 0;    // intensity at the hand-over and at the last frame
        std::string reason;       // why the manager dropped it ("" while alive)
        bool merged = false;      // another track layer within 3 px when it ended
        bool scene = false;       // the pipeline's scene-motion test flagged it
        std::map<int, int> near;  // truth id -> frames within 3 px (alive)
        std::map<int, int> near_rep;  // truth id -> reported frames within 3 px
        double scene_dx = 0, scene_dy = 0;  // the scene's shift over its life
        double sx0 = 0, sy0 = 0;  // the scene's position at its hand-over
        int hlayer = -1;          // the search layer it was handed over from (-1: not known)
    };
    const IrScenario &s_;
    const IrSequence &q_;
    uint64_t seed_;
    cv::Mat kern_;
    std::vector<std::string> rows_;
    std::vector<std::string> layer_rows_;
    std::vector<uint32_t> slot_id_;
    std::map<uint32_t, TrackLife> life_;
    double scene_x_ = 0, scene_y_ = 0;
};

}  // namespace pft::host::tbd_ir
