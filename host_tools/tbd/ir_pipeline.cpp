#include "ir_pipeline.hpp"

#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>

#include "../common/errors.hpp"
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
    c.birth_peaks = static_cast<uint16_t>(t.birth_peaks);
    auto R = [](const std::optional<double> &v, pft_real_t &dst) {
        if (v)
            dst = to_real(*v);
    };
    R(t.peak_gamma, c.peak_gamma);
    R(t.birth_share, c.birth_share);
    R(t.theta1, c.theta1);
    R(t.pb, c.pb);
    R(t.theta_end, c.theta_end);
    if (t.confirm_frames)
        c.confirm_frames = static_cast<uint8_t>(*t.confirm_frames);
    if (t.birth_correction)
        c.birth_correction = *t.birth_correction;
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

pft_pre_config_t make_pre_config(const TrackerSettings &t, int width, int height, int bit_depth, bool u8)
{
    pft_pre_config_t c;
    pft_pre_config_default(&c);
    c.width = static_cast<uint16_t>(width);
    c.height = static_cast<uint16_t>(height);
    c.format = u8 ? PFT_PIX_U8 : PFT_PIX_U16;
    c.bit_depth = static_cast<uint8_t>(u8 ? 8 : bit_depth);
    c.method = t.preprocess == "spatial" ? PFT_PRE_BG_LOCAL : PFT_PRE_BG_TEMPORAL;
    c.local_outer = static_cast<uint8_t>(t.background_radius);
    c.local_guard = static_cast<uint8_t>(t.guard_radius);
    c.bg_alpha = static_cast<uint16_t>(std::clamp(std::lround(t.bg_alpha * 65536.0), 1L, 65535L));
    c.tile = static_cast<uint8_t>(t.tile);
    c.peak_max = 0;  // the TBD manager here draws its births itself; the DBT thresholds the residual
    return c;
}

IrPipeline::IrPipeline(const TrackerSettings &t, const DbtSettings &d, double psf_sigma, int width,
                       int height, int bit_depth, uint64_t seed)
    : T_(t), w_(width), h_(height), bits_(bit_depth), dbt_(d), dbt_thr_(dbt_threshold(d.pfa)),
      max_det_(d.max_detections)
{
    pre_cfg_ = make_pre_config(t, width, height, bit_depth, false);
    const char *field = nullptr;
    pft_status_t st = pft_pre_config_check(&pre_cfg_, &field);
    if (st != PFT_OK)
        throw InputError(std::string("preprocessing configuration refused (pft_pre_config_check: ") +
                         pft_status_str(st) + (field ? std::string(", field ") + field : std::string()) + ")");
    pre_ws_bytes_ = pft_pre_workspace_size(&pre_cfg_);
    pre_work_.assign((pre_ws_bytes_ + 7) / 8, 0);
    st = pft_pre_init(&pre_, &pre_cfg_, pre_work_.data(), pre_work_.size() * 8);
    if (st != PFT_OK)
        throw InputError(std::string("pft_pre_init: ") + pft_status_str(st));
    tracker_ = std::make_unique<tbd::Tracker>(pipeline_config(t, psf_sigma, width, height, seed), false);
    resid_.create(h_, w_, CV_32F);
}

bool IrPipeline::evidence() const
{
    return (stats_.flags & (PFT_PRE_FLAG_CONSTANT | PFT_PRE_FLAG_ALL_MASKED | PFT_PRE_FLAG_REG_LOST)) == 0u;
}

PipelineOut IrPipeline::step(const pft_frame_t &frame)
{
    if (frame.width != w_ || frame.height != h_)
        throw InputError("frame " + std::to_string(frame.seq) + " is " + std::to_string(frame.width) +
                         "x" + std::to_string(frame.height) + ", the pipeline was set up for " +
                         std::to_string(w_) + "x" + std::to_string(h_));
    // the stage takes U16 frames of the pipeline's bit depth: others are converted (rounded,
    // clipped to the bit depth)
    pft_frame_t in = frame;
    if (frame.format != PFT_PIX_U16 || (frame.bit_depth ? frame.bit_depth : 16) != bits_) {
        cv::Mat z = frame_to_mat(frame, 1.0, 0.0);
        cv::Mat c = cv::min(cv::max(z, 0.0), std::ldexp(1.0, bits_) - 1.0);
        c.convertTo(u16_, CV_16U);
        in.data = u16_.data;
        in.stride_bytes = static_cast<uint32_t>(u16_.step[0]);
        in.format = PFT_PIX_U16;
        in.bit_depth = static_cast<uint8_t>(bits_);
    }
    pft_status_t st = pft_pre_update(&pre_, &in);
    if (st != PFT_OK)
        throw InputError("frame " + std::to_string(frame.seq) + " refused by pft_pre_update: " + pft_status_str(st));
    pft_pre_stats(&pre_, &stats_);
    pft_frame_t rf{};
    pft_pre_frame(&pre_, &rf);
    masked_ = static_cast<int>(stats_.n_masked);
    sigma_ = stats_.sigma_mean / 65536.0;
    const std::size_t stride = rf.stride_bytes / sizeof(int16_t);
    const int16_t *res = static_cast<const int16_t *>(rf.data);
    const bool ev = evidence();
    for (int y = 0; y < h_; ++y) {
        const int16_t *r = res + static_cast<std::size_t>(y) * stride;
        float *o = resid_.ptr<float>(y);
        for (int x = 0; x < w_; ++x)
            o[x] = !ev || r[x] == PFT_RES16_MASKED ? 0.0f : static_cast<float>(r[x]) / 256.0f;
    }
    PipelineOut out;
    out.tbd = tracker_->update_f32(resid_.ptr<float>(0), frame.seq);
    std::vector<Detection> dets;
    if (ev)
        dets = dbt_detect(res, w_, h_, static_cast<int>(stride), dbt_thr_, max_det_);
    out.detections = static_cast<int>(dets.size());
    out.dbt = dbt_.step(dets, frame.seq ? frame.seq : out.tbd.frame);
    if (frame.seq)
        out.tbd.frame = frame.seq;
    return out;
}

}  // namespace pft::host::tbd_ir
