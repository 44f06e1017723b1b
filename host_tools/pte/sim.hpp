// Range-time image simulation for the radar scenarios: a point target spread over range cells
// by a Gaussian of psf_sigma cells, in Gaussian noise or K-distributed sea clutter
// (compound Gaussian with a gamma texture correlated in range and time, plus thermal noise).
#pragma once
#include <cstdint>
#include <vector>

#include "scenario.hpp"

namespace pft::host::pte {

struct Truth {
    double r = 0.0;       ///< range, cells
    double rdot = 0.0;    ///< range rate, cells per frame
    double range_m = 0.0; ///< metres
    bool active = true;   ///< the target exists at this frame (scenario start_s / end_s)
};

struct Sequence {
    int cells = 0, frames = 0;
    double amplitude = 0.0;            ///< target peak A (input units)
    std::vector<std::vector<float>> z; ///< [frame][cell] in input units
    std::vector<Truth> truth;          ///< [frame] of the first target
    std::vector<std::vector<Truth>> truths;  ///< [target][frame], every target
};

/** Truth only (no random numbers). */
std::vector<Truth> simulate_truth(const Scenario &s, int frames = 0);
/** Truth of every target ([target][frame]). */
std::vector<std::vector<Truth>> simulate_truths(const Scenario &s, int frames = 0);
/** Frames and truth; noise from std::mt19937_64(seed). frames = 0: the scenario's. */
Sequence simulate(const Scenario &s, uint64_t seed, int frames = 0);

}  // namespace pft::host::pte
