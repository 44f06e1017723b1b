#include "ir_pipeline.hpp"

#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>

#include "../common/errors.hpp"
#include "../common/noise_estimate.hpp"
#include "../common/sequence_input.hpp"

namespace pft::host::tbd_ir {

pft_tbd_config_t pipeline_config(const TrackerSettings &t, double psf_sigma, int width, int height,
                                 uint64_t seed)
{
    pft_tbd_config_t c;
    if (t.preset == "recommended")
        pft_tbd_config_recommended(&c);
    else
        pft_tbd_config_default(&c);
    c.width = static_cast<uint16_t>(width);
    c.height = static_cast<uint16_t>(height);
    c.psf_sigma = to_real(psf_sigma);
    c.noise_sigma = to_real(1.0);
    c.pixel_gain = to_real(1.0);
    c.pixel_offset = to_real(0.0);
    // intensity I = 2 pi S^2 A for a peak A = 10^(SNR/20) noise sigmas (dx = dy = 1)
    const double area = 2.0 * M_PI * psf_sigma * psf_sigma;
    c.i_min = to_real(area * std::pow(10.0, t.snr_min_db / 20.0));
    c.i_max = to_real(area * std::pow(10.0, t.snr_max_db / 20.0));
    c.n_search = t.particles;
    c.n_track = t.track_particles;
    c.max_targets = static_cast<uint16_t>(t.max_targets);
    c.kind = PFT_TBD_RBPF;
    c.seed = seed + t.seed_offset;
    return c;
}

int detect_bit_depth(int container_bits, const std::vector<cv::Mat> &head)
{
    double mx = 0;
    for (const cv::Mat &m : head) {
        double v;
        cv::minMaxLoc(m, nullptr, &v);
        mx = std::max(mx, v);
    }
    int bits = container_bits > 0 ? container_bits : 16;
    for (int b = 8; b < bits; ++b)
        if (mx <= std::ldexp(1.0, b) - 1.0)
            return b;
    return bits;
}

IrPipeline::IrPipeline(const TrackerSettings &t, double psf_sigma, int width, int height,
                       int bit_depth, uint64_t seed)
    : T_(t), w_(width), h_(height), sat_(std::ldexp(1.0, bit_depth) - 1.0)
{
    tracker_ = std::make_unique<tbd::Tracker>(pipeline_config(t, psf_sigma, width, height, seed), false);
}

void IrPipeline::preprocess(const cv::Mat &z)
{
    // usable pixels: not dead (0), not saturated
    cv::Mat valid = (z > 0.0) & (z < sat_);
    masked_ = static_cast<int>(z.total()) - cv::countNonZero(valid);
    cv::Mat vf;
    valid.convertTo(vf, CV_32F, 1.0 / 255.0);
    cv::Mat zv = z.mul(vf);
    // local mean over the (2R+1)^2 box without the (2G+1)^2 guard box, usable pixels only
    const int R = T_.background_radius, G = T_.guard_radius;
    cv::Mat so, si, no, ni;
    auto box = [](const cv::Mat &in, cv::Mat &out, int r) {
        cv::boxFilter(in, out, CV_32F, cv::Size(2 * r + 1, 2 * r + 1), cv::Point(-1, -1), false,
                      cv::BORDER_CONSTANT);
    };
    box(zv, so, R);
    box(zv, si, G);
    box(vf, no, R);
    box(vf, ni, G);
    cv::Mat n = no - ni, bg;
    cv::divide(so - si, cv::max(n, 0.5), bg);
    cv::Mat r = (z - bg).mul(vf);
    r.setTo(0.0, n < 0.5);
    // the outer band, where the box is cut by the border, is not scored: a one-sided mean of a
    // gradient is biased by the gradient times the shift of the box's centre
    cv::Mat band(h_, w_, CV_8U, cv::Scalar(255));
    band(cv::Rect(R, R, std::max(0, w_ - 2 * R), std::max(0, h_ - 2 * R))).setTo(0);
    r.setTo(0.0, band);
    valid.setTo(0, band);
    // per-tile robust sigma (usable pixels), empty or flat tiles take the median of the others
    const int ts = T_.tile;
    const int tx = (w_ + ts - 1) / ts, ty = (h_ + ts - 1) / ts;
    cv::Mat sig(ty, tx, CV_32F);
    std::vector<float> v, all;
    for (int j = 0; j < ty; ++j)
        for (int i = 0; i < tx; ++i) {
            v.clear();
            for (int rr = j * ts; rr < std::min(h_, (j + 1) * ts); ++rr) {
                const float *p = r.ptr<float>(rr);
                const uint8_t *m = valid.ptr<uint8_t>(rr);
                for (int c = i * ts; c < std::min(w_, (i + 1) * ts); ++c)
                    if (m[c])
                        v.push_back(p[c]);
            }
            double s = v.size() >= 16 ? robust_sigma(v) : 0.0;
            sig.at<float>(j, i) = static_cast<float>(s);
            if (s > 0)
                all.push_back(static_cast<float>(s));
        }
    double med = 1.0;
    if (!all.empty()) {
        std::nth_element(all.begin(), all.begin() + static_cast<std::ptrdiff_t>(all.size() / 2), all.end());
        med = all[all.size() / 2];
    }
    sigma_ = all.empty() ? 0.0 : med;
    for (int j = 0; j < ty; ++j)
        for (int i = 0; i < tx; ++i)
            if (!(sig.at<float>(j, i) > 0))
                sig.at<float>(j, i) = static_cast<float>(med);
    cv::Mat sigmap;
    cv::resize(sig, sigmap, cv::Size(w_, h_), 0, 0, cv::INTER_LINEAR);
    cv::divide(r, sigmap, resid_);
}

tbd::FrameOut IrPipeline::step(const pft_frame_t &frame)
{
    if (frame.width != w_ || frame.height != h_)
        throw InputError("frame " + std::to_string(frame.seq) + " is " + std::to_string(frame.width) +
                         "x" + std::to_string(frame.height) + ", the pipeline was set up for " +
                         std::to_string(w_) + "x" + std::to_string(h_));
    preprocess(frame_to_mat(frame, 1.0, 0.0));
    if (!resid_.isContinuous())
        resid_ = resid_.clone();
    tbd::FrameOut out = tracker_->update_f32(resid_.ptr<float>(0), frame.seq);
    if (frame.seq)
        out.frame = frame.seq;
    return out;
}

}  // namespace pft::host::tbd_ir
