// Overlay video of a TBD run: frames upscaled (nearest neighbour) to a viewable size, truth
// as green circles with target ids, tracks as coloured crosses with track ids and their recent
// path, frame number and search-layer existence probability in the corner.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/videoio.hpp>

#include "../common/output.hpp"
#include "sim.hpp"
#include "tracker.hpp"

namespace pft::host::tbd {

class OverlayWriter {
public:
    /** path: .avi (MJPG); scale 0 picks one that makes the frame about 480 px. lo/hi:
     *  intensity mapped to black/white (hi <= lo: per-frame min/max). dx/dy: pixel size. */
    OverlayWriter(const std::string &path, int width, int height, int scale, double lo, double hi,
                  double dx, double dy, double fps = 5.0);
    /** Adds one frame; truth may be empty (no truth drawn). */
    void add(const cv::Mat &intensity, const std::vector<TruthState> &truth,
             const std::vector<int> &truth_ids, const FrameOut &out);
    /** Finishes the file and renames it into place. */
    void close();
    int scale() const { return scale_; }

private:
    std::unique_ptr<AtomicPath> ap_;
    cv::VideoWriter vw_;
    int w_, h_, scale_;
    double lo_, hi_, dx_, dy_;
    std::vector<std::vector<cv::Point2d>> paths_;  // by track id
    bool closed_ = false;
    cv::Point to_px(double x, double y) const;
};

}  // namespace pft::host::tbd
