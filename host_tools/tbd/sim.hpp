// TBD sequence simulator (host side, double precision, own seeded RNG): targets per
// docs/algorithms.md 2.10, the point-sampled PSF of section 1 summed over targets on every pixel,
// plus i.i.d. Gaussian noise.
#pragma once
#include <cstdint>
#include <vector>

#include "scenario.hpp"

namespace pft::host::tbd {

struct TruthState {
    bool present = false;
    double x = 0, vx = 0, y = 0, vy = 0, I = 0;
};

struct Sequence {
    int width = 0, height = 0, frames = 0;
    std::vector<std::vector<float>> images;        ///< [frame-1][row*width + col], intensity units
    std::vector<std::vector<TruthState>> truth;    ///< [frame-1][target index in scenario order]
};

/** Truth trajectories only (stream "truth" of the seed). */
std::vector<std::vector<TruthState>> simulate_truth(const Scenario &s, uint64_t seed, int frames);

/** Truth and images. frames <= 0: the scenario's frame count (more frames simply extend the
 *  sequence with background). The truth and the noise use independent streams of `seed`. */
Sequence simulate(const Scenario &s, uint64_t seed, int frames = 0, bool want_images = true);

/** Noise-free PSF image of the present targets of one frame (double precision). */
void render_psf(const Scenario &s, const std::vector<TruthState> &targets, std::vector<double> &img);

}  // namespace pft::host::tbd
