#include "tracker.hpp"

#include <cmath>
#include <string>

#include "../common/errors.hpp"

namespace pft::host::tbd {

void preset_config(const std::string &preset, pft_tbd_config_t *c)
{
    if (preset == "recommended")
        pft_tbd_config_recommended(c);
    else if (preset == "bounded")
        pft_tbd_config_bounded(c);
    else
        pft_tbd_config_default(c);
}

pft_tbd_config_t make_config(const Scenario &s, uint64_t seed)
{
    const FilterSettings &F = s.filter;
    pft_tbd_config_t c;
    preset_config(F.preset, &c);
    // the scenario's sensor and model
    c.width = static_cast<uint16_t>(s.width);
    c.height = static_cast<uint16_t>(s.height);
    c.dx = to_real(s.dx);
    c.dy = to_real(s.dy);
    c.psf_sigma = to_real(s.psf_sigma);
    c.noise_sigma = to_real(F.noise_sigma.value_or(s.noise_sigma));
    c.pixel_gain = to_real(1.0);
    c.pixel_offset = to_real(0.0);
    c.T = to_real(s.T);
    c.q1 = to_real(F.q1.value_or(s.q1));
    c.q2 = to_real(F.q2.value_or(s.q2));
    // sizes and algorithm
    c.n_search = F.particles;
    c.n_track = F.track_particles;
    c.max_targets = static_cast<uint16_t>(F.max_targets);
    c.kind = F.kind == "pf" ? PFT_TBD_PF : PFT_TBD_RBPF;
    c.seed = seed + F.seed_offset;
    apply_overrides(F, c);
    return c;
}

void apply_overrides(const FilterSettings &F, pft_tbd_config_t &c)
{
    set_real_if(F.pb, c.pb);
    set_real_if(F.pd, c.pd);
    set_real_if(F.eta, c.eta);
    set_real_if(F.gamma, c.gamma);
    set_real_if(F.i_min, c.i_min);
    set_real_if(F.i_max, c.i_max);
    set_real_if(F.theta1, c.theta1);
    set_real_if(F.dis_ratio, c.dis_ratio);
    set_real_if(F.theta_end, c.theta_end);
    if (F.vel_mean) {
        c.vel_mean[0] = to_real((*F.vel_mean)[0]);
        c.vel_mean[1] = to_real((*F.vel_mean)[1]);
    }
    if (F.vel_var) {
        c.vel_var[0] = to_real((*F.vel_var)[0]);
        c.vel_var[1] = to_real((*F.vel_var)[1]);
    }
    if (F.birth_correction)
        c.birth_correction = *F.birth_correction;
    if (F.dis_ratio_test)
        c.dis_ratio_test = *F.dis_ratio_test;
    if (F.d_current)
        c.d_current = *F.d_current;
    if (F.force_constraint)
        c.force_constraint = *F.force_constraint;
    if (F.dis_r)
        c.dis_r = static_cast<uint8_t>(*F.dis_r);
    if (F.dis_prev)
        c.dis_prev = static_cast<uint8_t>(*F.dis_prev);
    if (F.d_margin)
        c.d_margin = static_cast<uint8_t>(*F.d_margin);
    if (F.window)
        c.window = static_cast<uint8_t>(*F.window);
    if (F.kf_variant)
        c.kf_variant = *F.kf_variant == "paper" ? PFT_TBD_KF_PAPER : PFT_TBD_KF_EXACT;
    if (F.d_region)
        c.d_region = *F.d_region == "none"    ? PFT_TBD_D_NONE
                     : *F.d_region == "pixel" ? PFT_TBD_D_PIXEL
                                              : PFT_TBD_D_WINDOW;
    if (F.residual_search)
        c.residual_search = *F.residual_search;
    if (F.residual_tracks)
        c.residual_tracks = *F.residual_tracks;
    if (F.residual_margin)
        c.residual_margin = static_cast<uint8_t>(*F.residual_margin);
    if (F.handover_gate)
        c.handover_gate = static_cast<uint8_t>(*F.handover_gate);
    if (F.end_lr_frames)
        c.end_lr_frames = static_cast<uint8_t>(*F.end_lr_frames);
    set_real_if(F.end_lr_max, c.end_lr_max);
    if (F.birth_peaks)
        c.birth_peaks = static_cast<uint16_t>(*F.birth_peaks);
    set_real_if(F.peak_gamma, c.peak_gamma);
    set_real_if(F.birth_share, c.birth_share);
    if (F.confirm_frames)
        c.confirm_frames = static_cast<uint8_t>(*F.confirm_frames);
    if (F.seq_mode)
        c.seq_mode = *F.seq_mode == "use" ? PFT_SEQ_USE : PFT_SEQ_IGNORE;
    if (F.max_gap)
        c.max_gap = static_cast<uint16_t>(*F.max_gap);
}

nlohmann::json config_to_json(const pft_tbd_config_t &c)
{
    return {{"width", c.width}, {"height", c.height}, {"dx", from_real(c.dx)}, {"dy", from_real(c.dy)},
            {"psf_sigma", from_real(c.psf_sigma)}, {"noise_sigma", from_real(c.noise_sigma)},
            {"pixel_gain", from_real(c.pixel_gain)}, {"pixel_offset", from_real(c.pixel_offset)},
            {"window", c.window}, {"T", from_real(c.T)}, {"q1", from_real(c.q1)}, {"q2", from_real(c.q2)},
            {"pb", from_real(c.pb)}, {"pd", from_real(c.pd)}, {"eta", from_real(c.eta)},
            {"gamma", from_real(c.gamma)}, {"i_min", from_real(c.i_min)}, {"i_max", from_real(c.i_max)},
            {"vel_mean", {from_real(c.vel_mean[0]), from_real(c.vel_mean[1])}},
            {"vel_var", {from_real(c.vel_var[0]), from_real(c.vel_var[1])}},
            {"birth_correction", c.birth_correction}, {"theta1", from_real(c.theta1)},
            {"dis_r", c.dis_r}, {"dis_prev", c.dis_prev}, {"dis_ratio", from_real(c.dis_ratio)},
            {"dis_ratio_test", c.dis_ratio_test}, {"theta_end", from_real(c.theta_end)},
            {"d_margin", c.d_margin}, {"d_current", c.d_current},
            {"force_constraint", c.force_constraint},
            {"d_region", c.d_region == PFT_TBD_D_NONE    ? "none"
                         : c.d_region == PFT_TBD_D_PIXEL ? "pixel"
                                                         : "window"},
            {"residual_search", c.residual_search}, {"residual_tracks", c.residual_tracks},
            {"residual_margin", c.residual_margin}, {"end_lr_frames", c.end_lr_frames}, {"handover_gate", c.handover_gate},
            {"end_lr_max", from_real(c.end_lr_max)}, {"birth_peaks", c.birth_peaks},
            {"peak_gamma", from_real(c.peak_gamma)}, {"birth_share", from_real(c.birth_share)}, {"confirm_frames", c.confirm_frames},
            {"n_search", c.n_search},
            {"n_track", c.n_track}, {"max_targets", c.max_targets},
            {"kind", c.kind == PFT_TBD_PF ? "pf" : "rbpf"},
            {"kf_variant", c.kf_variant == PFT_TBD_KF_PAPER ? "paper" : "exact"},
            {"seq_mode", c.seq_mode == PFT_SEQ_USE ? "use" : "ignore"}, {"max_gap", c.max_gap},
            {"integ_alpha", from_real(c.integ_alpha)}};
}

namespace {
[[noreturn]] void lib_error(const std::string &what, pft_status_t st)
{
    throw InputError(what + ": " + pft_status_str(st) + " (" +
                     std::to_string(static_cast<int>(st)) + ")");
}
}  // namespace

Tracker::Tracker(const pft_tbd_config_t &cfg, bool single) : cfg_(cfg), single_(single)
{
    const char *field = nullptr;
    pft_status_t st = pft_tbd_config_check(&cfg_, &field);
    if (st != PFT_OK)
        lib_error(std::string("filter configuration rejected by pft_tbd_config_check (field ") +
                      (field != nullptr ? field : "?") + ")",
                  st);
    // single: a standalone filter of cfg.n_search particles of cfg.kind
    ws_bytes_ = single_ ? pft_tbd_filter_workspace_size(&cfg_) : pft_tbd_workspace_size(&cfg_);
    work_.assign((ws_bytes_ + 7) / 8, 0);
    st = single_ ? pft_tbd_filter_init(&flt_, &cfg_, work_.data(), ws_bytes_)
                 : pft_tbd_init(&mgr_, &cfg_, work_.data(), ws_bytes_);
    if (st != PFT_OK)
        lib_error(single_ ? "pft_tbd_filter_init" : "pft_tbd_init", st);
}

FrameOut Tracker::update_f32(const float *img, uint32_t seq)
{
    pft_frame_t f{};
    f.data = img;
    f.width = cfg_.width;
    f.height = cfg_.height;
    f.stride_bytes = static_cast<uint32_t>(cfg_.width * sizeof(float));
    f.format = PFT_PIX_F32;
    f.seq = seq;
    f.timestamp_us = static_cast<uint64_t>(seq) * 1000000u;
    return update(f);
}

void Tracker::set_shift(double dx, double dy)
{
    if (single_)
        return;
    pft_status_t st = pft_tbd_set_shift(&mgr_, to_real(dx), to_real(dy));
    if (st != PFT_OK)
        lib_error("pft_tbd_set_shift", st);
}

FrameOut Tracker::update(const pft_frame_t &frame)
{
    return single_ ? update_single(frame) : update_multi(frame);
}

// single: a track is a maximal run of frames with P > theta1 (the paper's Exp. 1 rule)
FrameOut Tracker::update_single(const pft_frame_t &frame)
{
    FrameOut out;
    pft_status_t st = pft_tbd_filter_update(&flt_, &frame);
    if (st != PFT_OK)
        lib_error("pft_tbd_filter_update", st);
    // frame numbers: the source's seq when the tracker reads it (lost frames leave holes)
    frame_ = cfg_.seq_mode == PFT_SEQ_USE ? frame.seq : frame_ + 1;
    out.frame = frame_;
    active_ = cfg_.n_search;
    pft_tbd_estimate_t e;
    pft_tbd_filter_estimate(&flt_, &e);
    out.search_p = from_real(e.p_exist);
    out.search_x = from_real(e.x);
    out.search_y = from_real(e.y);
    out.search_valid = e.valid;
    bool now = e.valid && e.p_exist > cfg_.theta1;
    if (now && !present_) {
        cur_id_ = next_id_++;
        cur_first_ = frame_;
        out.events.push_back({PFT_TBD_EV_CONFIRMED, cur_id_, frame_, out.search_x, out.search_y});
    } else if (!now && present_) {
        out.events.push_back({PFT_TBD_EV_ENDED, cur_id_, frame_, out.search_x, out.search_y});
    }
    present_ = now;
    if (now) {
        TrackOut t;
        t.id = cur_id_;
        t.x = out.search_x;
        t.y = out.search_y;
        t.vx = from_real(e.vx);
        t.vy = from_real(e.vy);
        t.intensity = from_real(e.intensity);
        t.p_exist = out.search_p;
        t.first_frame = cur_first_;
        out.tracks.push_back(t);
    }
    return out;
}

FrameOut Tracker::update_multi(const pft_frame_t &frame)
{
    FrameOut out;
    // the layers stepped at this frame are those live before it: reported tracks and, with the
    // sequential test (cfg.sprt_accept > 0), tentative ones, which pft_tbd_tracks and the events
    // do not show; a hand-over of this frame comes after the step
    const uint64_t live = mgr_.n_tracks;
    pft_status_t st = pft_tbd_update(&mgr_, &frame);
    if (st != PFT_OK)
        lib_error("pft_tbd_update", st);
    const bool by_seq = cfg_.seq_mode == PFT_SEQ_USE;  // frame numbers: the source's seq
    out.frame = by_seq ? frame.seq : pft_tbd_frame(&mgr_);
    pft_tbd_estimate_t e;
    pft_tbd_search_estimate(&mgr_, &e);
    out.search_p = from_real(e.p_exist);
    out.search_x = from_real(e.x);
    out.search_y = from_real(e.y);
    out.search_valid = e.valid;
    out.width = cfg_.width;
    out.height = cfg_.height;
    if (cfg_.birth_peaks > 0) {
        const std::size_t nb = pft_tbd_birth_candidates(&mgr_, nullptr, 0);
        if (nb <= cfg_.birth_peaks) {
            out.births.resize(nb);
            pft_tbd_birth_candidates(&mgr_, out.births.data(), nb);
        }
    }
    std::vector<pft_tbd_track_t> tr(cfg_.max_targets);
    std::size_t n = pft_tbd_tracks(&mgr_, tr.data(), tr.size());
    if (n > tr.size())
        n = tr.size();
    active_ = cfg_.n_search + live * cfg_.n_track;
    for (std::size_t i = 0; i < n; ++i) {
        TrackOut t;
        t.id = tr[i].id;
        t.x = from_real(tr[i].x);
        t.y = from_real(tr[i].y);
        t.vx = from_real(tr[i].vx);
        t.vy = from_real(tr[i].vy);
        t.intensity = from_real(tr[i].intensity);
        t.p_exist = from_real(tr[i].p_exist);
        t.pos_var = from_real(pft_add(tr[i].pos_cov[0], tr[i].pos_cov[2]));
        t.first_frame = tr[i].first_frame;
        out.tracks.push_back(t);
    }
    std::vector<pft_tbd_track_t> tent(cfg_.max_targets);
    std::size_t n_tent = pft_tbd_tentative(&mgr_, tent.data(), tent.size());
    if (n_tent > tent.size())
        n_tent = tent.size();
    for (std::size_t k = 0; k < n_tent; ++k) {
        const pft_tbd_track_t &r = tent[k];  // the sequential test's tentative tracks (public coordinates)
        if (r.age == 0u)
            continue;  // age 0: the hand-over frame, whose position is the search layer's estimate
        TrackOut t;
        t.id = r.id;
        t.x = from_real(r.x);
        t.y = from_real(r.y);
        t.vx = from_real(r.vx);
        t.vy = from_real(r.vy);
        t.intensity = from_real(r.intensity);
        t.p_exist = from_real(r.p_exist);
        t.pos_var = from_real(pft_add(r.pos_cov[0], r.pos_cov[2]));
        out.tentative.push_back(t);
    }
    std::vector<pft_tbd_event_t> ev(static_cast<std::size_t>(cfg_.max_targets) + 1u);
    std::size_t ne = pft_tbd_events(&mgr_, ev.data(), ev.size());
    if (ne > ev.size())
        ne = ev.size();
    for (std::size_t i = 0; i < ne; ++i) {
        out.events.push_back({static_cast<int>(ev[i].kind), ev[i].id, by_seq ? frame.seq : ev[i].frame,
                              from_real(ev[i].x), from_real(ev[i].y)});
    }
    return out;
}

}  // namespace pft::host::tbd
