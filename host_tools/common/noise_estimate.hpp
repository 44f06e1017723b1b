// Robust estimates of the temporal noise sigma of a sequence from its frames, for inputs that
// come without a sidecar (`pft run`) and for the noise figure `pft run` prints.
//  - spatial: r = z - (mean of the 8 neighbours); a plane (any linear gradient) cancels
//    exactly and white noise of sigma s gives var(r) = (1 + 1/8) s^2, so
//    sigma = robust_sigma(r) / sqrt(9/8). Structure that is not linear over 3x3 (edges, targets)
//    lands in the tails that the median ignores.
//  - temporal: d = z_k - z_(k-1) over consecutive frames, sigma = robust_sigma(d) / sqrt(2);
//    exact for a static scene, biased up by scene motion (a drifting platform).
// robust_sigma: 1.4826 MAD to start, then three passes of the deviation of the values within
// 3 sigma of the median, scaled for the truncation (x 1/0.98658): outliers (targets, edges) stay
// out, and integer data do not make the estimate move in steps as a bare MAD does. Quantised
// data can make the MAD 0 (more than half the values equal): then the start is the mean
// absolute deviation from the median (x sqrt(pi/2)). A constant input gives sigma 0 and
// `degenerate`; no estimate divides by zero.
#pragma once
#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace pft::host {

struct NoiseEstimate {
    double sigma = 0.0;        ///< in the units of the frames given
    double background = 0.0;   ///< median pixel value of the frames
    long samples = 0;          ///< residuals the sigma was taken from
    int frames = 0;
    bool degenerate = false;   ///< no spread at all (constant frames): sigma is 0
    std::string method;        ///< "spatial" | "temporal", for messages
};

/** Robust sigma of v (reordered; see above); 0 when v has no spread. `median` receives the
 *  median of v. */
double robust_sigma(std::vector<float> &v, double *median = nullptr);

/** Spatial estimate over frames (CV_32F, one channel); mask (CV_8U, optional): nonzero = a
 *  usable pixel; residuals whose 3x3 neighbourhood touches an unusable pixel, and the border
 *  row/column, are skipped. */
NoiseEstimate estimate_noise_spatial(const std::vector<cv::Mat> &frames, const cv::Mat &mask = {});

/** Temporal estimate from consecutive frame differences (needs 2 frames; else degenerate). */
NoiseEstimate estimate_noise_temporal(const std::vector<cv::Mat> &frames, const cv::Mat &mask = {});

}  // namespace pft::host
