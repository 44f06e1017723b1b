#include "overlay.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <opencv2/imgproc.hpp>

#include "../common/errors.hpp"

namespace pft::host::tbd {

namespace {
const cv::Scalar kTrackColors[] = {{0, 0, 255},   {255, 128, 0}, {255, 0, 255},
                                   {0, 200, 255}, {255, 255, 0}, {128, 0, 255}};
}

OverlayWriter::OverlayWriter(const std::string &path, int width, int height, int scale, double lo,
                             double hi, double dx, double dy, double fps)
    : w_(width), h_(height), lo_(lo), hi_(hi), dx_(dx), dy_(dy)
{
    if (scale <= 0) {
        int side = std::max(width, height);
        scale = std::max(1, std::min(32, 480 / std::max(1, side)));
    }
    scale_ = scale;
    ap_ = std::make_unique<AtomicPath>(path);
    int fourcc = cv::VideoWriter::fourcc('M', 'J', 'P', 'G');
    if (!vw_.open(ap_->tmp(), fourcc, fps, cv::Size(w_ * scale_, h_ * scale_), true))
        throw InputError(path + ": OpenCV cannot open a video writer (MJPG .avi)");
}

cv::Point OverlayWriter::to_px(double x, double y) const
{
    // the pixel in column c, row r (0-based) has its centre at (c dx, r dy)
    double c = x / dx_, r = y / dy_;
    return cv::Point(static_cast<int>(std::lround((c + 0.5) * scale_)),
                     static_cast<int>(std::lround((r + 0.5) * scale_)));
}

void OverlayWriter::add(const cv::Mat &intensity, const std::vector<TruthState> &truth,
                        const std::vector<int> &truth_ids, const FrameOut &out)
{
    double lo = lo_, hi = hi_;
    if (!(hi > lo))
        cv::minMaxLoc(intensity, &lo, &hi);
    if (!(hi > lo))
        hi = lo + 1.0;
    cv::Mat g;
    intensity.convertTo(g, CV_8U, 255.0 / (hi - lo), -lo * 255.0 / (hi - lo));
    cv::Mat big;
    cv::resize(g, big, cv::Size(w_ * scale_, h_ * scale_), 0, 0, cv::INTER_NEAREST);
    cv::Mat img;
    cv::cvtColor(big, img, cv::COLOR_GRAY2BGR);
    const double fs = std::max(0.35, std::min(0.6, scale_ / 30.0));
    for (std::size_t i = 0; i < truth.size(); ++i) {
        if (!truth[i].present)
            continue;
        cv::Point p = to_px(truth[i].x, truth[i].y);
        cv::circle(img, p, std::max(4, scale_ / 2), cv::Scalar(0, 220, 0), 1, cv::LINE_AA);
        char buf[16];
        std::snprintf(buf, sizeof buf, "T%d", i < truth_ids.size() ? truth_ids[i] : static_cast<int>(i + 1));
        cv::putText(img, buf, p + cv::Point(scale_ / 2 + 2, scale_ / 2 + 8), cv::FONT_HERSHEY_SIMPLEX,
                    fs, cv::Scalar(0, 220, 0), 1, cv::LINE_AA);
    }
    for (const TrackOut &t : out.tracks) {
        if (paths_.size() <= t.id)
            paths_.resize(t.id + 1);
        paths_[t.id].push_back({t.x, t.y});
        cv::Scalar col = kTrackColors[t.id % 6];
        const auto &pth = paths_[t.id];
        for (std::size_t k = 1; k < pth.size(); ++k)
            cv::line(img, to_px(pth[k - 1].x, pth[k - 1].y), to_px(pth[k].x, pth[k].y), col, 1,
                     cv::LINE_AA);
        cv::Point p = to_px(t.x, t.y);
        int r = std::max(4, scale_ / 3);
        cv::line(img, p - cv::Point(r, 0), p + cv::Point(r, 0), col, 2, cv::LINE_AA);
        cv::line(img, p - cv::Point(0, r), p + cv::Point(0, r), col, 2, cv::LINE_AA);
        char buf[32];
        std::snprintf(buf, sizeof buf, "#%u %.2f", t.id, t.p_exist);
        cv::putText(img, buf, p + cv::Point(r + 2, -r - 2), cv::FONT_HERSHEY_SIMPLEX, fs, col, 1,
                    cv::LINE_AA);
    }
    char buf[64];
    std::snprintf(buf, sizeof buf, "frame %u  P=%.2f", out.frame, out.search_p);
    cv::putText(img, buf, {6, 18}, cv::FONT_HERSHEY_SIMPLEX, 0.5, cv::Scalar(0, 255, 255), 1, cv::LINE_AA);
    vw_.write(img);
}

void OverlayWriter::close()
{
    if (closed_)
        return;
    closed_ = true;
    vw_.release();
    ap_->commit();
}

}  // namespace pft::host::tbd
