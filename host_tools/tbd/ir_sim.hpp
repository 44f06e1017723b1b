// The tbd_ir simulator: a scene (ir_scene.hpp) seen through a drifting, jittering platform,
// resampled bicubically at sub-pixel positions, vignetted, with injected point targets
// (Gaussian PSF of peak amplitude sigma_t 10^(SNR/20)), column fixed-pattern noise, temporal
// Gaussian noise, quantised to the sensor's bit depth, with dead and saturated pixels.
// Targets move in sensor coordinates; labelled objects of the background move with the scene.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "ir_scenario.hpp"

namespace pft::host {
class Progress;
}

namespace pft::host::tbd_ir {

/** One row of truth.csv: frame (1-based), id, position (0-based pixels), SNR, kind. */
struct TruthRow {
    int frame = 0, id = 0;
    double x = 0, y = 0;
    double snr_db = NAN;
    bool labelled = false;
};

/** A target's path: positions of frames birth..death (1-based, inclusive). */
struct TargetPath {
    int id = 0, birth = 1, death = 0;
    double snr_db = 0, amplitude = 0;  ///< peak in counts
    std::vector<double> x, y;
    bool present(int k) const { return k >= birth && k <= death; }
};

struct IrSequence {
    int width = 0, height = 0, frames = 0, bit_depth = 14;
    std::vector<cv::Mat> images;                   ///< CV_16U, one per frame
    std::vector<TruthRow> truth;                   ///< by frame, then id
    std::vector<TargetPath> targets;               ///< injected
    std::vector<std::array<double, 2>> platform;   ///< background position of frame pixel (0, 0)
    std::string background;                        ///< its source
    int labelled_objects = 0;
    int mirrored_px = 0;
};

/** The injected targets' paths (random from the seed, then the explicit list). */
std::vector<TargetPath> make_targets(const IrScenario &s, int width, int height, uint64_t seed);

/** Simulates the scenario with `seed`; bar (optional) ticks once per frame. */
IrSequence simulate_ir(const IrScenario &s, uint64_t seed, Progress *bar = nullptr);

/** Adds A exp(-d^2 / (2 psf^2)) around (x, y) to a CV_32F image (point-sampled, +-4 psf). */
void add_point(cv::Mat &img, double x, double y, double amplitude, double psf_sigma);

}  // namespace pft::host::tbd_ir
