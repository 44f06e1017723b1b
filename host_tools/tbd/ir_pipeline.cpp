#include "ir_pipeline.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

#include <opencv2/imgproc.hpp>

#include "../common/errors.hpp"
#include "../common/sequence_input.hpp"
#include "tracker.hpp"

namespace pft::host::tbd_ir {

pft_tbd_config_t pipeline_config(const TrackerSettings &t, double psf_sigma, int width, int height,
                                 uint64_t seed)
{
    pft_tbd_config_t c;
    pft::host::tbd::preset_config(t.preset, &c);
    c.width = static_cast<uint16_t>(width);
    c.height = static_cast<uint16_t>(height);
    c.psf_sigma = to_real(psf_sigma);
    c.noise_sigma = to_real(1.0);
    c.pixel_gain = to_real(1.0);
    c.pixel_offset = to_real(0.0);
    // the manager takes only the stage's residual (PFT_PIX_RES16, gain 1, offset 0, sigma 1)
    // and reads it in place: its workspace holds no real-valued frame
    c.frame_format = PFT_PIX_RES16;
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
    set_real_if(t.peak_gamma, c.peak_gamma);
    c.peak_tile = static_cast<uint8_t>(t.peak_tile);
    c.peak_quota = static_cast<uint8_t>(t.peak_quota);
    set_real_if(t.theta1, c.theta1);
    set_real_if(t.pb, c.pb);
    set_real_if(t.theta_end, c.theta_end);
    set_real_if(t.sprt_accept, c.sprt_accept);
    set_real_if(t.sprt_reject, c.sprt_reject);
    set_real_if(t.shape_ring, c.shape_ring);
    c.sprt_start = static_cast<uint8_t>(t.sprt_start);
    set_real_if(t.integ_alpha, c.integ_alpha);
    c.end_grace_frames = static_cast<uint8_t>(t.end_grace_frames);
    set_real_if(t.theta_end_grace, c.theta_end_grace);
    c.end_persist = static_cast<uint8_t>(t.end_persist);
    set_real_if(t.handover_in_scale, c.handover_in_scale);
    set_real_if(t.split_px, c.split_px);
    set_real_if(t.split_share, c.split_share);
    set_real_if(t.resid_split, c.resid_split);
    c.resid_split_frames = static_cast<uint8_t>(t.resid_split_frames);
    c.resid_split_age = static_cast<uint8_t>(t.resid_split_age);
    c.search_layers = static_cast<uint8_t>(t.search_layers);
    if (t.search_layers >= 2) {
        c.search_sep = to_real(t.search_sep.value_or(3.0));
        c.search_hold = to_real(t.search_hold.value_or(0.5));
    }
    set_real_if(t.q2, c.q2);
    c.birth_share = to_real(t.birth_share);
    c.confirm_frames = static_cast<uint8_t>(t.confirm_frames);
    c.birth_correction = t.birth_correction;
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
    c.col_alpha = static_cast<uint16_t>(std::clamp(std::lround(t.col_alpha * 65536.0), 0L, 65535L));
    c.tile = static_cast<uint8_t>(t.tile);
    // the edge term is the temporal background's (its gradient); the spatial method has none
    c.edge_k = c.method == PFT_PRE_BG_TEMPORAL ? static_cast<uint16_t>(std::lround(t.edge_k * 4096.0)) : 0u;
    c.peak_max = 0;  // the TBD manager here draws its births itself; the DBT thresholds the residual
    c.reg_step = static_cast<uint8_t>(t.reg_step);
    c.reg_iters = static_cast<uint8_t>(t.reg_iters);
    c.warp_cubic = t.warp_cubic;
    c.sigma_step = static_cast<uint8_t>(t.sigma_step);
    c.sigma_interp = t.sigma_interp;
    c.sigma_every = static_cast<uint8_t>(t.sigma_every);
    c.reg_bin = t.reg_bin;
    c.sigma_current = t.sigma_current;
    c.sigma_bracket = t.sigma_bracket;
    c.sigma_level = t.sigma_level;
    c.bg_gate = static_cast<uint16_t>(std::lround(t.bg_gate * 256.0));  // 0 (off) or 64..4096: the scenario reader's range
    c.bg_gate_shift = static_cast<uint8_t>(t.bg_gate_shift);
    c.bg_gate_young = static_cast<uint8_t>(t.bg_gate_young);
    c.bg_young_clip = static_cast<uint16_t>(std::lround(t.bg_young_clip * 256.0));  // 0 (off) or 64..4096: the scenario reader's range
    c.bg_gate_local = t.bg_gate_local == "mean"       ? static_cast<uint8_t>(PFT_PRE_GATE_LOCAL_MEAN)
                      : t.bg_gate_local == "relative" ? static_cast<uint8_t>(PFT_PRE_GATE_LOCAL_RELATIVE)
                                                      : uint8_t{0};
    c.bg_masked_taps = t.bg_masked_taps == "young" ? static_cast<uint8_t>(PFT_PRE_MASKED_TAPS_YOUNG)
                       : t.bg_masked_taps == "all" ? static_cast<uint8_t>(PFT_PRE_MASKED_TAPS_ALL)
                                                   : uint8_t{0};
    c.bg_stale_reinit = static_cast<uint8_t>(t.bg_stale_reinit);
    c.bg_edge_narrow = t.bg_edge_narrow ? uint8_t{1} : uint8_t{0};
    c.bg_young_scale = t.bg_young_scale;
    c.bg_anchor = t.bg_anchor;  // with the spatial method refused: by the scenario reader, else by pft_pre_config_check
    // the residual over the pipeline's own copy of the frame (pft_pre_update_inplace): the
    // stage's workspace holds no residual (docs/porting.md); bg_anchor has no in-place form
    // (the library refuses the pair): its residual has its own buffer
    c.inplace = !u8 && !c.bg_anchor;
    return c;
}

IrPipeline::IrPipeline(const TrackerSettings &t, const DbtSettings &d, double psf_sigma, int width,
                       int height, int bit_depth, uint64_t seed)
    : IrPipeline(t, d, psf_sigma, width, height, bit_depth, seed, false)
{
}

IrPipeline::IrPipeline(const TrackerSettings &t, const DbtSettings &d, double psf_sigma, int width,
                       int height, int bit_depth, uint64_t seed, bool pre_only)
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
    if (!pre_only)
        tracker_ = std::make_unique<tbd::Tracker>(pipeline_config(t, psf_sigma, width, height, seed), false);
    resid_.create(h_, w_, CV_32F);
    if (!pre_only && d.preprocess) {
        // DBT's own preprocessing: a pipeline of the stage, the flat-field step, residual_hp and
        // the clutter map only (no manager, no scene-motion test), with its own workspaces
        TrackerSettings dp = *d.preprocess;
        dp.scene_frames = 0;
        dbt_pre_.reset(new IrPipeline(dp, d, psf_sigma, width, height, bit_depth, seed, true));
    }
    if (t.flat_block > 0) {
        const pft_pre_flat_config_t fc = make_flat_config(t, width, height);
        if (pft_pre_flat_config_check(&fc, &field) != PFT_OK)
            throw InputError(std::string("flat-field configuration refused (field ") + (field ? field : "?") + ")");
        flat_bytes_ = pft_pre_flat_workspace_size(&fc);
        flat_work_.assign((flat_bytes_ + 7) / 8, 0);
        st = pft_pre_flat_init(&flat_, &fc, flat_work_.data(), flat_work_.size() * 8);
        if (st != PFT_OK)
            throw InputError(std::string("pft_pre_flat_init: ") + pft_status_str(st));
    }
    if (!pre_only && t.scene_frames > 0) {
        const pft_tbd_scene_config_t sc = make_scene_config(t, width, height);
        if (pft_tbd_scene_config_check(&sc, &field) != PFT_OK)
            throw InputError(std::string("scene-motion test configuration refused (pft_tbd_scene_config_check: field ") +
                             (field ? field : "?") + ")");
        scene_bytes_ = pft_tbd_scene_workspace_size(&sc);
        scene_work_.assign((scene_bytes_ + 7) / 8, 0);
        st = pft_tbd_scene_init(&scene_, &sc, scene_work_.data(), scene_work_.size() * 8);
        if (st != PFT_OK)
            throw InputError(std::string("pft_tbd_scene_init: ") + pft_status_str(st));
    }
}

pft_pre_flat_config_t make_flat_config(const TrackerSettings &t, int width, int height)
{
    pft_pre_flat_config_t c;
    pft_pre_flat_config_default(&c);
    c.width = static_cast<uint16_t>(width);
    c.height = static_cast<uint16_t>(height);
    c.block = static_cast<uint8_t>(t.flat_block);
    c.alpha = static_cast<uint16_t>(std::clamp(std::lround(t.flat_alpha * 65536.0), 1L, 65535L));
    c.gate = static_cast<uint16_t>(std::clamp(std::lround(t.flat_gate * 256.0), 1L, 32767L));
    c.relative = t.flat_relative;
    c.rescale = t.flat_rescale;
    return c;
}

// The clutter map: the library's pft_pre_clutter_* (pft_pre.h, docs/algorithms.md 9.9): per
// pixel of the scene the running mean square of the whitened residual (and its mean with
// clutter_mean), carried along with the scene by the stage's shift; a pixel whose map, read
// over the (2 clutter_blur + 1)^2 square (mean, or largest value), exceeds clutter_thr is
// scored in that sigma. It was host code (float, OpenCV warps) with the same formulas until
// 2026-12-02; the library's is integer (docs/results/ir_clutter.md compares the two).
pft_pre_clutter_config_t make_clutter_config(const TrackerSettings &t, int width, int height)
{
    pft_pre_clutter_config_t c;
    pft_pre_clutter_config_default(&c);
    c.width = static_cast<uint16_t>(width);
    c.height = static_cast<uint16_t>(height);
    c.alpha = static_cast<uint16_t>(std::clamp(std::lround(t.clutter_alpha * 65536.0), 1L, 65535L));
    c.blur = static_cast<uint8_t>(t.clutter_blur);
    c.box = t.clutter_box;
    c.mean = t.clutter_mean;
    c.thr = static_cast<uint16_t>(std::clamp(std::lround(t.clutter_thr * 1024.0), 1024L, 65535L));
    c.veto = t.clutter_veto > 0 ? static_cast<uint16_t>(std::clamp(std::lround(t.clutter_veto * 1024.0), static_cast<long>(c.thr), 65535L)) : 0u;
    c.persist = static_cast<uint8_t>(t.clutter_persist);
    c.excess = static_cast<uint16_t>(std::clamp(std::lround(t.clutter_excess * 256.0), 1L, 32767L));
    c.mean_floor = static_cast<uint16_t>(std::clamp(std::lround(t.clutter_mean_floor * 256.0), 0L, 2048L));
    c.floor_age = static_cast<uint8_t>(t.clutter_floor_age);
    c.block = static_cast<uint8_t>(t.clutter_block);
    c.map8 = t.clutter_map8;
    c.anchor = t.clutter_anchor;
    return c;
}

IrPipeline::ProbeSetup IrPipeline::probe_setup() const
{
    if (T_.residual_hp > 0)
        throw InputError("--probe-out: residual_hp is a host step (OpenCV) between the library calls; ir_probe has none");
    if (T_.flat_block > 0 && T_.flat_relative && T_.flat_level_blocks)
        throw InputError("--probe-out: flat_level_blocks is a host experiment; ir_probe has none");
    ProbeSetup p;
    p.pre = pre_cfg_;
    p.flat = T_.flat_block > 0;
    if (p.flat)
        p.flat_cfg = make_flat_config(T_, w_, h_);
    p.flat_relative = p.flat && T_.flat_relative;
    p.clutter = T_.clutter_alpha > 0;
    if (p.clutter) {
        p.clutter_cfg = make_clutter_config(T_, w_, h_);
        p.clutter_cfg.inplace = pre_cfg_.inplace;  // as preprocess() calls clutter_step
    }
    p.tbd = tracker_->config();
    p.scene = T_.scene_frames > 0;
    if (p.scene)
        p.scene_cfg = make_scene_config(T_, w_, h_);
    p.scene_tentative = T_.scene_tentative;
    p.integ_shift = T_.integ_shift;
    p.bits = bits_;
    return p;
}

void clutter_step(ClutterMap &c, const TrackerSettings &T_, const int16_t *res, std::size_t stride, bool ev,
                  double sx, double sy, cv::Mat &resid_, bool inplace)
{
    const int w_ = resid_.cols, h_ = resid_.rows;
    if (c.work.empty()) {
        pft_pre_clutter_config_t cfg = make_clutter_config(T_, w_, h_);
        cfg.inplace = inplace;
        const char *field = nullptr;
        if (pft_pre_clutter_config_check(&cfg, &field) != PFT_OK)
            throw InputError(std::string("clutter map configuration refused (field ") + (field ? field : "?") + ")");
        c.bytes = pft_pre_clutter_workspace_size(&cfg);
        c.work.assign((c.bytes + 7) / 8, 0);
        const pft_status_t st = pft_pre_clutter_init(&c.c, &cfg, c.work.data(), c.work.size() * 8);
        if (st != PFT_OK)
            throw InputError(std::string("pft_pre_clutter_init: ") + pft_status_str(st));
    }
    pft_frame_t f{};
    f.data = res;
    f.width = static_cast<uint16_t>(w_);
    f.height = static_cast<uint16_t>(h_);
    f.stride_bytes = static_cast<uint32_t>(stride * sizeof(int16_t));
    f.format = PFT_PIX_RES16;
    f.bit_depth = 16u;
    const auto q16 = [](double v) { return static_cast<int32_t>(std::lround(v * 65536.0)); };
    // inplace: res is the pipeline's own buffer (the stage's residual written over its copy of
    // the frame) and nothing reads that residual after the map
    pft_status_t st = inplace ? pft_pre_clutter_update_inplace(&c.c, &f, const_cast<int16_t *>(res), q16(sx),
                                                               q16(sy), ev)
                              : pft_pre_clutter_update(&c.c, &f, q16(sx), q16(sy), ev);
    pft_frame_t o{};
    if (st == PFT_OK)
        st = pft_pre_clutter_frame(&c.c, &o);
    if (st != PFT_OK)
        throw InputError(std::string("pft_pre_clutter_update: ") + pft_status_str(st));
    c.out = static_cast<const int16_t *>(o.data);
    for (int y = 0; y < h_; ++y) {
        const int16_t *q = c.out + static_cast<std::size_t>(y) * static_cast<std::size_t>(w_);
        float *r = resid_.ptr<float>(y);
        for (int x = 0; x < w_; ++x)
            r[x] = q[x] == PFT_RES16_MASKED ? 0.0f : static_cast<float>(q[x]) / 256.0f;
    }
}

// residual_hp (TrackerSettings): the residual less its mean over the (2R + 1)^2 square around
// each pixel, masked pixels left out of the mean and kept masked. It takes off the slowly varying
// offset that the temporal background leaves where a sensor-fixed gain (vignetting) meets a
// drifting bright scene (docs/results/ir_clutter.md, "Branch irdet").
void residual_highpass(const int16_t *res, std::size_t stride, int w, int h, int R, cv::Mat &out)
{
    cv::Mat v(h, w, CV_32F), m(h, w, CV_32F), vs, ms;
    for (int y = 0; y < h; ++y) {
        const int16_t *r = res + static_cast<std::size_t>(y) * stride;
        float *pv = v.ptr<float>(y), *pm = m.ptr<float>(y);
        for (int x = 0; x < w; ++x) {
            const bool ok = r[x] != PFT_RES16_MASKED;
            pv[x] = ok ? static_cast<float>(r[x]) : 0.0f;
            pm[x] = ok ? 1.0f : 0.0f;
        }
    }
    const cv::Size box(2 * R + 1, 2 * R + 1);
    cv::boxFilter(v, vs, CV_32F, box, cv::Point(-1, -1), false, cv::BORDER_CONSTANT);
    cv::boxFilter(m, ms, CV_32F, box, cv::Point(-1, -1), false, cv::BORDER_CONSTANT);
    out.create(h, w, CV_16S);
    for (int y = 0; y < h; ++y) {
        const int16_t *r = res + static_cast<std::size_t>(y) * stride;
        const float *s = vs.ptr<float>(y), *n = ms.ptr<float>(y);
        int16_t *o = out.ptr<int16_t>(y);
        for (int x = 0; x < w; ++x) {
            if (r[x] == PFT_RES16_MASKED) {
                o[x] = PFT_RES16_MASKED;
                continue;
            }
            const double mean = n[x] > 0.5f ? static_cast<double>(s[x]) / static_cast<double>(n[x]) : 0.0;
            o[x] = static_cast<int16_t>(std::clamp(std::lround(r[x] - mean), -32767L, 32767L));
        }
    }
}

// The scene-motion test (TrackerSettings::scene_frames), the library's pft_tbd_scene_*
// (pft_tbd_scene.h, docs/algorithms.md 9.11). A track's displacement over its last
// n = scene_frames frames, less the scene's (the sum of the stage's shifts over those frames), is
// the track's motion against the scene: below n * scene_gate_px, the track is taken for
// clutter that drifts with the platform (a cloud edge, the horizon, a structure) for good. Such
// a track is dropped from the output, and with the clutter map on its map entries (3 x 3 around
// it) are raised to at least 16 (4 sigma), so that its evidence fades from the next frame and
// the manager ends it. The other tracks are reported from their n-th frame on (or early, and
// only while they fit a straight line: scene_early_px, scene_fit_px). With the
// library's sequential test (sprt_accept > 0) a track is tentative for some frames after its
// hand-over; with scene_tentative its positions count from the frame after the hand-over on
// (FrameOut::tentative), so that both tests run over the same frames, and a tentative track found
// moving with the scene raises the map too (off by default: measured, it delays the reports,
// docs/results/ir_clutter.md "Branch irseq2").
pft_tbd_scene_config_t make_scene_config(const TrackerSettings &t, int width, int height)
{
    pft_tbd_scene_config_t c;
    pft_tbd_scene_config_default(&c);
    c.frames = static_cast<uint32_t>(t.scene_frames);
    c.max_tracks = static_cast<uint32_t>(t.max_targets);  // the manager holds at most max_targets ids (reported and tentative)
    c.gate_px = to_real(t.scene_gate_px);
    c.fit_px = to_real(t.scene_fit_px);
    c.early_px = to_real(t.scene_early_px);
    c.width = static_cast<uint32_t>(width);
    c.height = static_cast<uint32_t>(height);
    c.hold_frames = static_cast<uint32_t>(t.scene_hold);
    c.spread_px = to_real(t.scene_spread_px);
    c.spread_hold = static_cast<uint32_t>(t.scene_spread_px > 0 ? t.scene_spread_hold : 1);
    c.spread_exist = to_real(t.scene_spread_exist);
    c.slow_frames = static_cast<uint32_t>(t.scene_slow_frames);
    c.slow_low_px = to_real(t.scene_slow_low_px);
    c.slow_gate_px = to_real(t.scene_slow_gate_px);
    c.edge_px = to_real(t.scene_edge_px);
    c.edge_still_px = to_real(t.scene_edge_still_px);
    c.edge_shift_px = to_real(t.scene_edge_shift_px);
    c.move_px = to_real(t.scene_move_px);
    c.move_hold = static_cast<uint32_t>(t.scene_move_hold);
    return c;
}

void IrPipeline::scene_test(tbd::FrameOut &out, int32_t shift_x, int32_t shift_y)
{
    const std::size_t n_rep = out.tracks.size();
    const std::size_t n_all = n_rep + (T_.scene_tentative ? out.tentative.size() : 0u);
    std::vector<pft_tbd_scene_track_t> in(n_all);
    for (std::size_t i = 0; i < n_all; ++i) {
        const bool tentative = i >= n_rep;
        const tbd::TrackOut &t = tentative ? out.tentative[i - n_rep] : out.tracks[i];
        in[i].id = t.id;
        in[i].x = to_real(t.x);  // exact: t.x is the manager's pft_real_t
        in[i].y = to_real(t.y);
        in[i].tentative = tentative;
        in[i].pos_var = to_real(t.pos_var);  // exact: the manager's pos_cov[0] + pos_cov[2] (tracker.cpp)
        in[i].p_exist = to_real(t.p_exist);  // exact: the manager's p_exist (tracker.cpp)
    }
    std::vector<pft_tbd_scene_out_t> dec(n_all);
    const pft_status_t st = pft_tbd_scene_update(&scene_, in.data(), n_all, shift_x, shift_y, dec.data());
    if (st != PFT_OK)
        throw InputError(std::string("pft_tbd_scene_update: ") + pft_status_str(st));
    std::vector<tbd::TrackOut> kept;
    scene_dec_.clear();
    for (std::size_t i = 0; i < n_all; ++i) {
        scene_dec_.emplace_back(dec[i].id, static_cast<int>(dec[i].decision));
        if (dec[i].decision == PFT_TBD_SCENE_CLUTTER && !cm_.work.empty())
            (void)pft_pre_clutter_raise(&cm_.c, dec[i].px, dec[i].py, 16u * 1024u);  // 16 sigma^2 (4 sigma)
        if (i < n_rep && dec[i].decision == PFT_TBD_SCENE_REPORT)
            kept.push_back(out.tracks[i]);
    }
    out.tracks.swap(kept);
}

bool IrPipeline::evidence() const
{
    return (stats_.flags & (PFT_PRE_FLAG_CONSTANT | PFT_PRE_FLAG_ALL_MASKED | PFT_PRE_FLAG_REG_LOST)) == 0u;
}

const int16_t *IrPipeline::preprocess(const pft_frame_t &frame, std::size_t &stride_out, bool &ev_out)
{
    if (frame.width != w_ || frame.height != h_)
        throw InputError("frame " + std::to_string(frame.seq) + " is " + std::to_string(frame.width) +
                         "x" + std::to_string(frame.height) + ", the pipeline was set up for " +
                         std::to_string(w_) + "x" + std::to_string(h_));
    // the stage takes U16 frames of the pipeline's bit depth: others are converted (rounded,
    // clipped to the bit depth)
    // With inplace (make_pre_config) the stage writes its residual over the frame it is given:
    // the pipeline gives it its own copy, u16_, since the caller's frame stays the caller's
    // (shown in the video, read again by the caller); the copy is the host's memory, as a
    // sensor's frame buffer would be on a target.
    pft_frame_t in = frame;
    const bool convert = frame.format != PFT_PIX_U16 || (frame.bit_depth ? frame.bit_depth : 16) != bits_;
    if (convert) {
        cv::Mat z = frame_to_mat(frame, 1.0, 0.0);
        cv::Mat c = cv::min(cv::max(z, 0.0), std::ldexp(1.0, bits_) - 1.0);
        c.convertTo(u16_, CV_16U);
    } else if (pre_cfg_.inplace) {
        u16_.create(h_, w_, CV_16U);
        for (int y = 0; y < h_; ++y)
            std::memcpy(u16_.ptr<uint16_t>(y), pft_frame_row(&frame, static_cast<uint32_t>(y)),
                        static_cast<std::size_t>(w_) * 2u);
    }
    // flat_relative: the level frame is the raw frame the stage takes (the caller's, or a copy
    // of the converted one, since the stage writes its residual over u16_)
    pft_frame_t lev = frame;
    if (T_.flat_block > 0 && T_.flat_relative && (convert || T_.flat_level_blocks)) {
        if (convert)
            u16_.copyTo(level_);
        else
            frame_to_mat(frame, 1.0, 0.0).convertTo(level_, CV_16U);
        if (T_.flat_level_blocks) {
            // host experiment: the level at the blocks' resolution only (the frame's mean per
            // block, bilinear between block centres), what a workspace of O(blocks) could hold
            const int b = T_.flat_block, nbx = (w_ + b - 1) / b, nby = (h_ + b - 1) / b;
            cv::Mat f, small;
            level_.convertTo(f, CV_32F);
            cv::resize(f, small, cv::Size(nbx, nby), 0, 0, cv::INTER_AREA);
            cv::resize(small, f, cv::Size(nbx * b, nby * b), 0, 0, cv::INTER_LINEAR);
            f(cv::Rect(0, 0, w_, h_)).convertTo(level_, CV_16U);
        }
        lev.data = level_.data;
        lev.stride_bytes = static_cast<uint32_t>(level_.step[0]);
        lev.format = PFT_PIX_U16;
        lev.bit_depth = static_cast<uint8_t>(bits_);
    }
    if (convert || pre_cfg_.inplace) {
        in.data = u16_.data;
        in.stride_bytes = static_cast<uint32_t>(u16_.step[0]);
        in.format = PFT_PIX_U16;
        in.bit_depth = static_cast<uint8_t>(bits_);
    }
    pft_status_t st = pre_cfg_.inplace ? pft_pre_update_inplace(&pre_, &in, u16_.ptr<uint16_t>(0))
                                       : pft_pre_update(&pre_, &in);
    if (st != PFT_OK)
        throw InputError("frame " + std::to_string(frame.seq) + " refused by pft_pre_update: " + pft_status_str(st));
    pft_pre_stats(&pre_, &stats_);
    pft_frame_t rf{};
    pft_pre_frame(&pre_, &rf);
    masked_ = static_cast<int>(stats_.n_masked);
    sigma_ = stats_.sigma_mean / 65536.0;
    std::size_t stride = rf.stride_bytes / sizeof(int16_t);
    const int16_t *res = static_cast<const int16_t *>(rf.data);
    const bool ev = evidence();
    if (T_.flat_block > 0) {
        // the stage's residual is the pipeline's own buffer with inplace (u16_): corrected
        // there; otherwise in a copy
        int16_t *px;
        if (pre_cfg_.inplace) {
            px = reinterpret_cast<int16_t *>(u16_.ptr<uint16_t>(0));
        } else {
            flat_res_.create(h_, w_, CV_16S);
            for (int y = 0; y < h_; ++y)
                std::memcpy(flat_res_.ptr<int16_t>(y), res + static_cast<std::size_t>(y) * stride,
                            static_cast<std::size_t>(w_) * 2u);
            px = flat_res_.ptr<int16_t>(0);
            stride = static_cast<std::size_t>(w_);
        }
        pft_frame_t ff = rf;
        ff.data = px;
        ff.stride_bytes = static_cast<uint32_t>(stride * sizeof(int16_t));
        st = pft_pre_flat_update(&flat_, &ff, px, T_.flat_relative ? &lev : nullptr, ev);
        if (st != PFT_OK)
            throw InputError(std::string("pft_pre_flat_update: ") + pft_status_str(st));
        res = px;
    }
    if (keep_stage_) {
        stage_resid_.create(h_, w_, CV_32F);
        for (int y = 0; y < h_; ++y) {
            const int16_t *r = res + static_cast<std::size_t>(y) * stride;
            float *o = stage_resid_.ptr<float>(y);
            for (int x = 0; x < w_; ++x)
                o[x] = !ev || r[x] == PFT_RES16_MASKED ? 0.0f : static_cast<float>(r[x]) / 256.0f;
        }
    }
    if (T_.residual_hp > 0 && ev) {
        residual_highpass(res, stride, w_, h_, T_.residual_hp, hp_);
        res = hp_.ptr<int16_t>(0);
        stride = static_cast<std::size_t>(w_);
    }
    if (T_.clutter_alpha > 0) {
        // With the stage in place (pre_cfg_.inplace) the residual is the pipeline's own buffer
        // (u16_, or hp_ with residual_hp), rows packed, and nothing reads it after the map
        // (DBT, the manager and --residual-out read the map's output): the map writes its
        // output over it and its workspace holds no output buffer
        clutter_step(cm_, T_, res, stride, ev, stats_.shift[0] / 65536.0, stats_.shift[1] / 65536.0, resid_,
                     pre_cfg_.inplace);
        res = cm_.out;
        stride = static_cast<std::size_t>(w_);
    } else {
        for (int y = 0; y < h_; ++y) {
            const int16_t *r = res + static_cast<std::size_t>(y) * stride;
            float *o = resid_.ptr<float>(y);
            for (int x = 0; x < w_; ++x)
                o[x] = !ev || r[x] == PFT_RES16_MASKED ? 0.0f : static_cast<float>(r[x]) / 256.0f;
        }
    }
    stride_out = stride;
    ev_out = ev;
    return res;
}

PipelineOut IrPipeline::step(const pft_frame_t &frame)
{
    std::size_t stride = 0;
    bool ev = false;
    const int16_t *res = preprocess(frame, stride, ev);
    // the manager takes the residual as it is (PFT_PIX_RES16, masked pixels read as 0); a frame
    // without evidence goes as an all-masked frame
    pft_frame_t tf{};
    if (ev) {
        tf.data = res;
        tf.stride_bytes = static_cast<uint32_t>(stride * sizeof(int16_t));
    } else {
        if (blank_.empty()) {
            blank_.create(h_, w_, CV_16S);
            blank_.setTo(PFT_RES16_MASKED);
        }
        tf.data = blank_.ptr<int16_t>(0);
        tf.stride_bytes = static_cast<uint32_t>(blank_.step[0]);
    }
    tf.width = static_cast<uint16_t>(w_);
    tf.height = static_cast<uint16_t>(h_);
    tf.format = PFT_PIX_RES16;
    tf.bit_depth = 16u;
    tf.seq = frame.seq;
    tf.timestamp_us = static_cast<uint64_t>(frame.seq) * 1000000u;
    PipelineOut out;
    if (T_.integ_shift && ev)
        tracker_->set_shift(stats_.shift[0] / 65536.0, stats_.shift[1] / 65536.0);
    out.tbd = tracker_->update(tf);
    if (ev) {
        scene_x_ += stats_.shift[0] / 65536.0;
        scene_y_ += stats_.shift[1] / 65536.0;
    }
    if (T_.scene_frames > 0)
        scene_test(out.tbd, ev ? stats_.shift[0] : 0, ev ? stats_.shift[1] : 0);
    // DBT reads the TBD pipeline's residual (shared), or with dbt.preprocess the residual of its
    // own preprocessing fed the same frame (own)
    if (dbt_pre_)
        res = dbt_pre_->preprocess(frame, stride, ev);
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
