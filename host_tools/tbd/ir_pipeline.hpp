// The IR pipeline of kind tbd_ir: one raw sensor frame in, tracks out.
//
// Today it is a host stand-in for the preprocessing stage (OpenCV: a local-mean background
// with a guard ring, dead and saturated pixels masked, the border band of the box's half-size
// not scored, the residual whitened by a per-tile robust sigma) followed by the library's multi-target TBD manager (pft_tbd_*) on the whitened
// residual (noise sigma 1). IrPipeline::step() is the one function to change when the
// library's preprocessing stage (lib/src/pre) and the full-frame TBD replace them: it takes
// the frame as the sensor gives it and returns the frame's tracks and events.
#pragma once
#include <cstdint>
#include <memory>

#include <opencv2/core.hpp>

extern "C" {
#include "pft/pft_types.h"
}

#include "ir_scenario.hpp"
#include "tracker.hpp"

namespace pft::host::tbd_ir {

class IrPipeline {
public:
    /** width x height frames; bit_depth: pixels at 0 or at 2^bit_depth - 1 are masked. */
    IrPipeline(const TrackerSettings &t, double psf_sigma, int width, int height, int bit_depth,
               uint64_t seed);

    /** The tracker step: preprocessing, then the TBD manager. frame: U8, U16 or F32 of the
     *  configured size; its seq numbers the output. InputError on a refused frame. */
    tbd::FrameOut step(const pft_frame_t &frame);

    const cv::Mat &residual() const { return resid_; }  ///< last whitened residual (CV_32F)
    double sigma() const { return sigma_; }              ///< last frame's median tile sigma
    int masked() const { return masked_; }               ///< last frame's masked pixels
    std::size_t workspace_bytes() const { return tracker_->workspace_bytes(); }
    const pft_tbd_config_t &config() const { return tracker_->config(); }

private:
    /** Host stand-in for the preprocessing stage: counts -> whitened residual. */
    void preprocess(const cv::Mat &counts);

    TrackerSettings T_;
    int w_, h_;
    double sat_;
    std::unique_ptr<tbd::Tracker> tracker_;
    cv::Mat resid_;
    double sigma_ = 0;
    int masked_ = 0;
};

/** The pft_tbd configuration of the pipeline (noise sigma 1 on the whitened residual; the
 *  intensity prior from the tracker's SNR range). */
pft_tbd_config_t pipeline_config(const TrackerSettings &t, double psf_sigma, int width, int height,
                                 uint64_t seed);

/** Bits of a sequence from its frames: the container's (frame bit depth), lowered to the
 *  smallest of 8..16 that holds the largest value seen. */
int detect_bit_depth(int container_bits, const std::vector<cv::Mat> &head);

}  // namespace pft::host::tbd_ir
