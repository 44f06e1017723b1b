// Detect-before-track baseline of the IR pipeline (host-side C++, not part of the library): it
// runs on the same whitened residual as the TBD manager (the library's preprocessing stage,
// pft_pre_*), so that every summary shows TBD beside DBT.
//
// Per frame: (1) threshold the whitened residual at t = Phi^-1(1 - pfa), the level a Gaussian
// residual of sigma 1 exceeds with probability pfa per pixel; masked pixels never exceed;
// (2) 8-connected components of the exceeding pixels, each one detection at its
// residual-weighted centroid (at most max_detections per frame, the highest peaks kept);
// (3) association: every track (confirmed first, then tentative, each class by increasing
// distance) takes the nearest unused detection within its gate, a chi-square 2-dof gate on the
// innovation of a constant-velocity Kalman filter per track, capped at gate_max_px;
// (4) M-of-N confirmation: a tentative track is confirmed when m of its last n frames had a
// detection, dropped once that can no longer happen; a confirmed track ends after max_misses
// frames in a row without one. Detections no track took start tentative tracks.
// Confirmed tracks are reported every frame they live (coasting on the prediction while missed),
// numbered 1, 2, ... in order of confirmation, with CONFIRMED and ENDED events.
#pragma once
#include <cstdint>
#include <vector>

#include "ir_scenario.hpp"
#include "tracker.hpp"

namespace pft::host::tbd_ir {


/** Threshold in residual sigmas for a per-pixel false-alarm rate (Gaussian tail). */
double dbt_threshold(double pfa);

struct Detection {
    double x = 0, y = 0;  ///< residual-weighted centroid, 0-based px
    double peak = 0;      ///< largest whitened residual of the component
    int pixels = 0;
};

/** Detections of a whitened residual in Q8.8 sigma units (PFT_PIX_RES16, PFT_RES16_MASKED
 *  skipped), rows stride_px int16 apart. */
std::vector<Detection> dbt_detect(const int16_t *res, int width, int height, int stride_px,
                                  double threshold, int max_detections);

class DbtTracker {
public:
    explicit DbtTracker(const DbtSettings &s);
    /** One frame's detections (an empty list for a frame without evidence). */
    tbd::FrameOut step(const std::vector<Detection> &dets, uint32_t frame);
    const DbtSettings &settings() const { return S_; }
    std::size_t live_tracks() const { return tracks_.size(); }

private:
    struct Track {
        double x[4];      // x, y, vx, vy
        double P[2][3];   // per axis: var pos, cov pos-vel, var vel
        uint32_t hits;    // bit k: a detection k frames ago
        int age = 0, misses = 0;
        bool confirmed = false;
        uint32_t id = 0, first_frame = 0;
        double peak = 0;
    };
    DbtSettings S_;
    std::vector<Track> tracks_;
    uint32_t next_id_ = 1;
};

}  // namespace pft::host::tbd_ir
