// Tracks and truth in the MOTChallenge text layout, so that py-motmetrics or TrackEval can score
// them (MOTA, MOTP, IDF1, HOTA, ...). One line per object and frame:
//   frame,id,bb_left,bb_top,bb_width,bb_height,conf,x,y,z
// Point targets get a fixed square box of side `box` centred on the point. MOTChallenge boxes
// are 1-based (the top-left pixel is (1, 1)), so bb_left = x + 1 - box / 2 for pftrack's 0-based
// x (docs/design.md, "Pixel coordinates"); x, y repeat the point (0-based), z is -1. conf is the
// track's existence probability for tracks and 1 for truth (py-motmetrics reads ground truth
// with a minimum confidence of 1). Two boxes of side S offset along one axis by e have IoU
// (S - e) / (S + e), which is 0.5 at e = S / 3: with S = 3 d the usual IoU >= 0.5 match means
// an offset of at most d along an axis (diagonal offsets match a little closer).
#pragma once
#include <string>
#include <vector>

namespace pft::host {

struct MotRow {
    long frame = 0;  ///< 1-based
    long id = 0;     ///< track id or target id (positive)
    double x = 0, y = 0;
    double conf = 1.0;
};

/** Writes the rows (sorted by frame, then id) atomically. */
void write_mot_file(const std::string &path, std::vector<MotRow> rows, double box);

/** The folder layout of py-motmetrics' eval_motchallenge under `dir`:
 *  dir/gt/<seq>/gt/gt.txt (truth, when `truth` is not empty) and dir/trackers/<seq>.txt. */
void write_mot_layout(const std::string &dir, const std::string &seq, const std::vector<MotRow> &tracks,
                      const std::vector<MotRow> &truth, double box, bool with_truth);

}  // namespace pft::host
