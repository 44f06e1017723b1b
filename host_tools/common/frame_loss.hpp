// Frames lost on the way from the sensor, as scenario files describe them (eval.drop_prob,
// eval.drop_frames): `pft eval` does not feed them, `pft sim` writes no file for them, and both
// draw the same frames for a seed. Kinds tbd and tbd_ir (docs/host_tools.md).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "json_field.hpp"

namespace pft::host {

struct FrameLoss {
    double drop_prob = 0.0;        ///< each frame after the first is lost with this probability (per run seed)
    std::vector<int> drop_frames;  ///< 1-based frames lost in every run
    bool any() const { return drop_prob > 0.0 || !drop_frames.empty(); }
};

/** Reads drop_prob (0..0.9) and drop_frames (1-based numbers above 1) of an "eval" object;
 *  a bad value fails naming the file and field. */
FrameLoss parse_frame_loss(const Field &eval);

/** Which frames of a run are lost: index k is frame k + 1; the first frame is never lost. */
std::vector<bool> lost_frame_mask(const FrameLoss &loss, int frames, uint64_t seed);

/** The frames `pft sim` loses for a seed (no file for them; the reader sees a gap in the
 *  numbers): the mask and their 1-based numbers. Losing frames needs one file per frame:
 *  with another output format than "pgm" it is refused (InputError naming the scenario file). */
struct SimLoss {
    std::vector<bool> mask;
    std::vector<int> numbers;
};
SimLoss sim_lost_frames(const FrameLoss &loss, int frames, uint64_t seed, const std::string &format,
                        const std::string &scenario_file);

}  // namespace pft::host
