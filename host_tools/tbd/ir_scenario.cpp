#include "ir_scenario.hpp"

#include <cmath>
#include <set>

#include "../common/json_field.hpp"
#include "pft/pft_tbd.h"
#include "pft/pft_tbd_scene.h"

namespace pft::host::tbd_ir {

double IrScenario::amplitude(double snr_db) const
{
    return sensor.noise_sigma * std::pow(10.0, snr_db / 20.0);
}

const char *const kPreprocessFields[] = {
    "preprocess", "bg_alpha", "col_alpha", "background_radius", "guard_radius", "tile", "edge_k",
    "reg_step", "reg_iters", "warp_cubic", "sigma_step", "sigma_interp", "sigma_every", "reg_bin",
    "sigma_current", "sigma_bracket", "sigma_level", "bg_anchor", "bg_gate", "bg_gate_shift", "bg_gate_young",
    "bg_young_clip", "bg_young_scale", "bg_edge_narrow", "bg_stale_reinit", "bg_gate_local", "bg_masked_taps", "flat_block", "flat_alpha", "flat_gate", "flat_relative",
    "flat_rescale", "flat_level_blocks", "residual_hp", "clutter_alpha", "clutter_blur", "clutter_mean", "clutter_thr",
    "clutter_veto", "clutter_box", "clutter_persist", "clutter_excess", "clutter_mean_floor",
    "clutter_floor_age", "clutter_block", "clutter_map8", "clutter_anchor", "note", nullptr};

const char *const kTrackerOnlyFields[] = {
    "preset", "particles", "track_particles", "max_targets", "snr_min_db", "snr_max_db", "seed_offset",
    "birth_peaks", "peak_gamma", "peak_tile", "peak_quota", "birth_share", "theta1", "pb", "theta_end",
    "confirm_frames", "birth_correction", "scene_frames", "scene_gate_px", "scene_fit_px",
    "scene_early_px", "scene_tentative", "sprt_accept", "sprt_reject", "shape_ring", "sprt_start",
    "integ_alpha", "integ_shift", "scene_hold", "scene_spread_px", "scene_spread_hold", "scene_spread_exist",
    "scene_slow_frames", "scene_slow_low_px", "scene_slow_gate_px", "scene_edge_px", "scene_edge_still_px", "scene_edge_shift_px", "scene_move_px", "scene_move_hold", "end_grace_frames", "theta_end_grace", "end_persist",
    "handover_in_scale", "q2", "split_px", "split_share", "resid_split", "resid_split_frames",
    "resid_split_age", "search_layers", "search_sep", "search_hold", nullptr};

namespace {

std::array<double, 2> pair_or(const Field &f, const char *key, std::array<double, 2> dflt,
                              double lo, double hi)
{
    if (!f.has(key))
        return dflt;
    Field v = f.at(key);
    std::array<double, 2> r{};
    if (v.node().is_number()) {
        r[0] = r[1] = v.as_number();
    } else {
        auto n = f.numbers(key, 2);
        r = {n[0], n[1]};
    }
    for (double x : r)
        if (!(x >= lo && x <= hi))
            v.fail("values must be within " + std::to_string(lo) + ".." + std::to_string(hi));
    return r;
}

void parse_background(const Field &b, IrScenario &s)
{
    b.only({"source", "folder", "files", "index", "labels", "scale", "smooth_px", "sky_top", "sky_horizon",
            "cloud_cover", "cloud_scale_px", "cloud_level", "cloud_texture", "cloud_edge_px",
            "horizon", "ground_level", "ground_texture", "structures", "note"});
    Background &B = s.background;
    B.source = b.choice_or("source", "procedural", {"procedural", "folder"});
    B.folder = b.string_or("folder", "");
    if (b.has("files")) {
        Field fl = b.at("files");
        for (std::size_t i = 0; i < fl.size(); ++i)
            B.files.push_back(fl.at(i).as_string());
    }
    if (b.has("index") && !b.at("index").node().is_null())
        B.index = static_cast<int>(b.integer_in("index", 0, 0, 1000000));
    B.labels = b.boolean_or("labels", true);
    B.scale = b.number_in("scale", 0.0, 0.0, 1e6);
    B.smooth_px = b.number_in("smooth_px", 0.0, 0.0, 20.0);
    Procedural &P = B.proc;
    P.sky_top = b.number_in("sky_top", P.sky_top, 0.0, 1.0);
    P.sky_horizon = b.number_in("sky_horizon", P.sky_horizon, 0.0, 1.0);
    P.cloud_cover = b.number_in("cloud_cover", P.cloud_cover, 0.0, 1.0);
    P.cloud_scale_px = b.number_in("cloud_scale_px", P.cloud_scale_px, 4.0, 4096.0);
    P.cloud_level = b.number_in("cloud_level", P.cloud_level, -1.0, 1.0);
    P.cloud_texture = b.number_in("cloud_texture", P.cloud_texture, 0.0, 2.0);
    P.cloud_edge_px = b.number_in("cloud_edge_px", P.cloud_edge_px, 0.5, 256.0);
    if (b.node().contains("horizon") && (b.node()["horizon"].is_null() ||
                                         b.node()["horizon"] == false))
        P.horizon.reset();  // null or false: all sky
    else if (b.has("horizon"))
        P.horizon = b.number_in("horizon", 0.8, 0.05, 1.0);
    P.ground_level = b.number_in("ground_level", P.ground_level, 0.0, 1.0);
    P.ground_texture = b.number_in("ground_texture", P.ground_texture, 0.0, 1.0);
    P.structures = static_cast<int>(b.integer_in("structures", P.structures, 0, 100));
}

void parse_targets(const Field &t, IrScenario &s)
{
    t.only({"count", "snr_db", "psf_sigma", "speed_px", "turn_deg", "enter_fraction", "min_life",
            "crossings", "list", "note"});
    Targets &T = s.targets;
    if (t.has("count")) {
        auto c = pair_or(t, "count", {0, 0}, 0.0, 256.0);
        if (c[0] != std::floor(c[0]) || c[1] != std::floor(c[1]) || c[1] < c[0])
            t.at("count").fail("expected an integer or [min, max] integers, min <= max");
        T.count = {static_cast<int>(c[0]), static_cast<int>(c[1])};
    }
    T.snr_db = pair_or(t, "snr_db", T.snr_db, -20.0, 60.0);
    if (T.snr_db[1] < T.snr_db[0])
        t.at("snr_db").fail("the second value must not be below the first");
    T.psf_sigma = t.number_in("psf_sigma", T.psf_sigma, 0.2, 10.0);
    T.speed_px = pair_or(t, "speed_px", T.speed_px, 0.0, 100.0);
    if (T.speed_px[1] < T.speed_px[0])
        t.at("speed_px").fail("the second value must not be below the first");
    T.turn_deg = t.number_in("turn_deg", T.turn_deg, 0.0, 45.0);
    T.enter_fraction = t.number_in("enter_fraction", T.enter_fraction, 0.0, 1.0);
    T.min_life = static_cast<int>(t.integer_in("min_life", T.min_life, 1, s.frames));
    T.crossings = static_cast<int>(t.integer_in("crossings", T.crossings, 0, 64));
    if (!t.has("list"))
        return;
    Field l = t.at("list");
    std::set<int> ids;
    for (std::size_t i = 0; i < l.size(); ++i) {
        Field e = l.at(i);
        e.only({"id", "birth_frame", "death_frame", "x", "y", "vx", "vy", "turn_deg", "snr_db", "note"});
        TargetSpec ts;
        ts.id = static_cast<int>(e.integer_in("id", static_cast<int64_t>(i) + 1, 1, 499));
        if (!ids.insert(ts.id).second)
            e.at("id").fail("duplicate target id " + std::to_string(ts.id));
        ts.birth = static_cast<int>(e.integer_in("birth_frame", 1, 1, s.frames));
        ts.death = static_cast<int>(e.integer_in("death_frame", 0, 0, s.frames));
        if (ts.death && ts.death < ts.birth)
            e.at("death_frame").fail("must be >= birth_frame");
        ts.x = e.number_req_in("x", -1e4, 1e4);
        ts.y = e.number_req_in("y", -1e4, 1e4);
        ts.vx = e.number_in("vx", 0.0, -100.0, 100.0);
        ts.vy = e.number_in("vy", 0.0, -100.0, 100.0);
        ts.turn_deg = e.number_in("turn_deg", 0.0, -45.0, 45.0);
        ts.snr_db = e.number_in("snr_db", T.snr_db[0], -20.0, 60.0);
        T.list.push_back(ts);
    }
}

void parse_tracker(const Field &t, TrackerSettings &T)
{
    // the tracker block's names are exactly the two lists' (kPreprocessFields: also read in
    // dbt.preprocess; kTrackerOnlyFields: the manager's), so a new field is in one of them
    t.only({kPreprocessFields, kTrackerOnlyFields});
    T.preprocess = t.choice_or("preprocess", T.preprocess, {"temporal", "spatial"});
    T.bg_alpha = t.number_in("bg_alpha", T.bg_alpha, 1.0 / 65536.0, 65535.0 / 65536.0);
    T.col_alpha = t.number_in("col_alpha", T.col_alpha, 0.0, 65535.0 / 65536.0);
    T.edge_k = t.number_in("edge_k", T.edge_k, 0.0, 1.0);
    T.preset = t.choice_or("preset", T.preset, {"paper", "recommended", "bounded"});
    if (T.preset == "bounded" && !t.has("particles")) {
        pft_tbd_config_t b;
        pft_tbd_config_bounded(&b);
        T.particles = b.n_search;  // the preset's own search-layer size
    }
    T.particles = static_cast<uint32_t>(t.integer_in("particles", T.particles, 1, 4194304));
    T.track_particles = static_cast<uint32_t>(t.integer_in("track_particles", T.track_particles, 1, 4194304));
    T.max_targets = static_cast<uint32_t>(t.integer_in("max_targets", T.max_targets, 1, 64));
    T.snr_min_db = t.number_in("snr_min_db", T.snr_min_db, -20.0, 60.0);
    T.snr_max_db = t.number_in("snr_max_db", T.snr_max_db, -20.0, 60.0);
    if (T.snr_max_db <= T.snr_min_db)
        t.at("snr_max_db").fail("must exceed snr_min_db");
    T.guard_radius = static_cast<int>(t.integer_in("guard_radius", T.guard_radius, 0, 6));
    T.background_radius = static_cast<int>(t.integer_in("background_radius", T.background_radius, 1, 7));
    if (T.background_radius <= T.guard_radius)
        t.at("background_radius").fail("must exceed guard_radius");
    T.tile = static_cast<int>(t.integer_in("tile", T.tile, 8, 255));
    T.seed_offset = static_cast<uint64_t>(t.integer_in("seed_offset", 0, 0, INT64_MAX));
    T.birth_peaks = static_cast<int>(t.integer_in("birth_peaks", T.birth_peaks, 0, 4096));  // PFT_TBD_MAX_PEAKS
    auto num = [&](const char *k, double lo, double hi, std::optional<double> &dst) {
        if (t.has(k))
            dst = t.number_req_in(k, lo, hi);
    };
    num("peak_gamma", -1e4, 1e4, T.peak_gamma);
    T.peak_tile = static_cast<int>(t.integer_in("peak_tile", T.peak_tile, 0, 255));
    T.peak_quota = static_cast<int>(t.integer_in("peak_quota", T.peak_quota, 0, 255));
    if (T.peak_quota > 0 && T.peak_tile < 4)
        t.at("peak_quota").fail("needs peak_tile of at least 4 px");
    T.birth_share = t.number_in("birth_share", T.birth_share, 0.0, 0.95);
    num("theta1", 0.0, 1.0, T.theta1);
    num("pb", 0.0, 1.0, T.pb);
    num("theta_end", 0.0, 1.0, T.theta_end);
    num("sprt_accept", 0.0, 10000.0, T.sprt_accept);
    num("sprt_reject", -10000.0, 0.0, T.sprt_reject);
    num("shape_ring", 0.0, 100.0, T.shape_ring);
    T.sprt_start = static_cast<int>(t.integer_in("sprt_start", T.sprt_start, 0, 2));
    num("integ_alpha", 0.0, 0.99, T.integ_alpha);
    T.end_grace_frames = static_cast<int>(t.integer_in("end_grace_frames", T.end_grace_frames, 0, 255));
    num("theta_end_grace", 0.0, 1.0, T.theta_end_grace);
    num("q2", 0.0, 100.0, T.q2);
    num("handover_in_scale", 0.0, 1.0, T.handover_in_scale);  // the library's range (pft_tbd.h)
    num("split_px", 0.0, 16.0, T.split_px);                    // the library's range (pft_tbd.h)
    num("split_share", 0.0, 0.5, T.split_share);
    if (T.split_px && *T.split_px > 0.0 && *T.split_px < 0.5)
        t.at("split_px").fail("must be 0 (off) or within 0.5..16 px");
    if (T.split_px && *T.split_px > 0.0 && !(T.split_share && *T.split_share > 0.0))
        t.at("split_px").fail("needs split_share above 0 (at most 0.5)");
    num("resid_split", 0.0, 50.0, T.resid_split);  // the library's range (pft_tbd.h)
    if (T.resid_split && *T.resid_split > 0.0 && *T.resid_split < 1.0)
        t.at("resid_split").fail("must be 0 (off) or within 1..50 sigmas");
    T.resid_split_frames = static_cast<int>(t.integer_in("resid_split_frames", T.resid_split_frames, 0, 8));
    T.resid_split_age = static_cast<int>(t.integer_in("resid_split_age", T.resid_split_age, 0, 255));
    T.search_layers = static_cast<int>(t.integer_in("search_layers", T.search_layers, 0, PFT_TBD_MAX_SEARCH));
    num("search_sep", 1.0, 16.0, T.search_sep);   // the library's range (pft_tbd.h)
    num("search_hold", 0.0, 0.999, T.search_hold);
    if ((T.search_sep || T.search_hold) && T.search_layers < 2)
        t.at(T.search_sep ? "search_sep" : "search_hold").fail("needs search_layers of at least 2");
    if (T.search_layers >= 2 && !(T.birth_share > 0.0))
        t.at("search_layers").fail("needs birth_share above 0 (the Bernoulli search layer)");
    T.end_persist = static_cast<int>(t.integer_in("end_persist", T.end_persist, 0, PFT_TBD_MAX_END_PERSIST));  // the library's bound (pft_tbd.h)
    if (T.theta_end_grace && T.end_grace_frames == 0)
        t.at("theta_end_grace").fail("needs end_grace_frames of at least 1");
    if (t.has("integ_shift"))
        T.integ_shift = t.at("integ_shift").as_bool();
    T.confirm_frames = static_cast<int>(t.integer_in("confirm_frames", T.confirm_frames, 0, 16));
    if (t.has("birth_correction"))
        T.birth_correction = t.at("birth_correction").as_bool();
    T.clutter_alpha = t.number_in("clutter_alpha", T.clutter_alpha, 0.0, 1.0);
    T.scene_frames = static_cast<int>(t.integer_in("scene_frames", T.scene_frames, 0, PFT_TBD_SCENE_MAX_FRAMES));  // the library's bound (pft_tbd_scene.h)
    T.scene_gate_px = t.number_in("scene_gate_px", T.scene_gate_px, 0.0, 10.0);
    T.scene_fit_px = t.number_in("scene_fit_px", T.scene_fit_px, 0.0, 100.0);
    T.scene_early_px = t.number_in("scene_early_px", T.scene_early_px, 0.0, 100.0);
    T.scene_hold = static_cast<int>(t.integer_in("scene_hold", T.scene_hold, 1, PFT_TBD_SCENE_MAX_HOLD));  // the library's bound (pft_tbd_scene.h)
    T.scene_spread_px = t.number_in("scene_spread_px", T.scene_spread_px, 0.0, 256.0);  // the library's bound
    T.scene_spread_hold = static_cast<int>(t.integer_in("scene_spread_hold", T.scene_spread_hold, 1, PFT_TBD_SCENE_MAX_HOLD));
    if (T.scene_spread_px > 0 && !t.has("scene_spread_hold"))
        t.at("scene_spread_px").fail("needs scene_spread_hold (1..scene_hold)");
    if (T.scene_spread_px > 0 && T.scene_spread_hold > T.scene_hold)
        t.at("scene_spread_hold").fail("must be at most scene_hold");
    T.scene_spread_exist = t.number_in("scene_spread_exist", T.scene_spread_exist, 0.0, 1.0);  // the library's bound
    if (T.scene_spread_exist > 0 && T.scene_spread_px <= 0)
        t.at("scene_spread_exist").fail("needs scene_spread_px > 0");
    T.scene_slow_frames = static_cast<int>(t.integer_in("scene_slow_frames", T.scene_slow_frames, 0, PFT_TBD_SCENE_MAX_FRAMES));  // the library's bound
    T.scene_slow_low_px = t.number_in("scene_slow_low_px", T.scene_slow_low_px, 0.0, 10.0);
    T.scene_slow_gate_px = t.number_in("scene_slow_gate_px", T.scene_slow_gate_px, 0.001, 256.0);  // the library's (0, 256]
    T.scene_edge_px = t.number_in("scene_edge_px", T.scene_edge_px, 0.0, 256.0);  // the library's bound
    T.scene_edge_still_px = t.number_in("scene_edge_still_px", T.scene_edge_still_px, 0.0, 256.0);
    T.scene_edge_shift_px = t.number_in("scene_edge_shift_px", T.scene_edge_shift_px, 0.0, 256.0);
    T.scene_move_px = t.number_in("scene_move_px", T.scene_move_px, 0.0, 256.0);  // the library's bound
    if (T.scene_move_px > 0 && T.scene_spread_px <= 0)
        t.at("scene_move_px").fail("needs scene_spread_px > 0");
    T.scene_move_hold = static_cast<int>(t.integer_in("scene_move_hold", T.scene_move_hold, 0, PFT_TBD_SCENE_MAX_HOLD));
    if (T.scene_move_hold > 0 && T.scene_move_px <= 0)
        t.at("scene_move_hold").fail("needs scene_move_px > 0");
    if (T.scene_move_hold > 0 && (T.scene_move_hold < T.scene_spread_hold || T.scene_move_hold > T.scene_hold))
        t.at("scene_move_hold").fail("must be 0 or scene_spread_hold..scene_hold");
    if (T.scene_slow_frames > 0 && T.scene_slow_frames < 2 * T.scene_frames)
        t.at("scene_slow_frames").fail("must be 0 or at least twice scene_frames");
    if (T.scene_slow_frames > 0 && T.scene_slow_low_px > T.scene_gate_px)
        t.at("scene_slow_low_px").fail("must be at most scene_gate_px");
    if (t.has("scene_tentative"))
        T.scene_tentative = t.at("scene_tentative").as_bool();
    T.clutter_thr = t.number_in("clutter_thr", T.clutter_thr, 1.0, 64.0);
    T.clutter_veto = t.number_in("clutter_veto", T.clutter_veto, 0.0, 64.0);
    if (T.clutter_veto > 0 && T.clutter_veto < T.clutter_thr)
        t.at("clutter_veto").fail("must be 0 (off) or at least clutter_thr");
    if (t.has("clutter_box"))
        T.clutter_box = t.at("clutter_box").as_bool();
    if (t.has("clutter_mean"))
        T.clutter_mean = t.at("clutter_mean").as_bool();
    T.clutter_blur = static_cast<int>(t.integer_in("clutter_blur", T.clutter_blur, 0, 4));
    T.residual_hp = static_cast<int>(t.integer_in("residual_hp", T.residual_hp, 0, 64));
    T.reg_step = static_cast<int>(t.integer_in("reg_step", T.reg_step, 1, 8));
    T.reg_iters = static_cast<int>(t.integer_in("reg_iters", T.reg_iters, 0, 8));
    if (t.has("warp_cubic"))
        T.warp_cubic = t.at("warp_cubic").as_bool();
    T.sigma_step = static_cast<int>(t.integer_in("sigma_step", T.sigma_step, 1, 4));
    if (t.has("sigma_interp"))
        T.sigma_interp = t.at("sigma_interp").as_bool();
    T.sigma_every = static_cast<int>(t.integer_in("sigma_every", T.sigma_every, 1, 8));
    if (t.has("reg_bin"))
        T.reg_bin = t.at("reg_bin").as_bool();
    if (t.has("sigma_current"))
        T.sigma_current = t.at("sigma_current").as_bool();
    if (t.has("sigma_bracket"))
        T.sigma_bracket = t.at("sigma_bracket").as_bool();
    if (t.has("sigma_level"))
        T.sigma_level = t.at("sigma_level").as_bool();
    if (T.sigma_level && (T.sigma_step > 1 || T.sigma_every > 1 || T.sigma_bracket))
        t.at("sigma_level").fail("takes the tile sigma about the tile's level in the histogram of every pixel: needs sigma_step 1, sigma_every 1 and sigma_bracket false");
    if (t.has("bg_anchor"))
        T.bg_anchor = t.at("bg_anchor").as_bool();
    if (T.bg_anchor && T.preprocess != "temporal")
        t.at("bg_anchor").fail("anchors the temporal background: needs preprocess \"temporal\"");
    T.bg_gate = t.number_in("bg_gate", T.bg_gate, 0.0, 16.0);
    if (T.bg_gate != 0.0 && T.bg_gate < 0.25)
        t.at("bg_gate").fail("must be 0 (off) or 0.25..16 (sigma)");
    if (T.bg_gate != 0.0 && !T.bg_anchor)
        t.at("bg_gate").fail("clips the anchored background's update: needs bg_anchor");
    T.bg_gate_shift = static_cast<int>(t.integer_in("bg_gate_shift", T.bg_gate_shift, 0, 15));
    if (T.bg_gate_shift != 0 && T.bg_gate == 0.0)
        t.at("bg_gate_shift").fail("the weight of the cells beyond bg_gate: needs bg_gate");
    T.bg_gate_young = static_cast<int>(t.integer_in("bg_gate_young", T.bg_gate_young, 0, 255));
    if (T.bg_gate_young != 0 && T.bg_gate == 0.0)
        t.at("bg_gate_young").fail("the frames a new cell is updated without bg_gate: needs bg_gate");
    T.bg_young_clip = t.number_in("bg_young_clip", T.bg_young_clip, 0.0, 16.0);
    if (T.bg_young_clip != 0.0 && T.bg_young_clip < 0.25)
        t.at("bg_young_clip").fail("must be 0 (off) or 0.25..16 (sigma)");
    if (T.bg_young_clip != 0.0 && T.bg_gate_young == 0)
        t.at("bg_young_clip").fail("clips the start and update of bg_gate_young's young cells: needs bg_gate_young");
    T.bg_gate_local = t.choice_or("bg_gate_local", T.bg_gate_local, {"off", "mean", "relative"});
    if (T.bg_gate_local != "off" && T.bg_gate == 0.0)
        t.at("bg_gate_local").fail("takes the tile's part off bg_gate's innovation: needs bg_gate");
    T.bg_masked_taps = t.choice_or("bg_masked_taps", T.bg_masked_taps, {"off", "young", "all"});
    T.bg_stale_reinit = static_cast<int>(t.integer_in("bg_stale_reinit", T.bg_stale_reinit, 0, 126));
    if (T.bg_stale_reinit != 0 && T.preprocess != "temporal")
        t.at("bg_stale_reinit").fail("restarts stale values of the temporal background: needs preprocess \"temporal\"");
    if (T.bg_masked_taps != "off" && !T.bg_anchor)
        t.at("bg_masked_taps").fail("renormalises the anchored background's update taps: needs bg_anchor");
    if (T.bg_masked_taps == "young" && T.bg_gate_young == 0)
        t.at("bg_masked_taps").fail("young acts in bg_gate_young's young columns: needs bg_gate_young");
    if (t.has("bg_young_scale"))
        T.bg_young_scale = t.at("bg_young_scale").as_bool();
    if (T.bg_young_scale && T.bg_gate_young == 0)
        t.at("bg_young_scale").fail("scales the residual of bg_gate_young's young cells: needs bg_gate_young");
    if (t.has("bg_edge_narrow"))
        T.bg_edge_narrow = t.at("bg_edge_narrow").as_bool();
    if (T.bg_edge_narrow && !T.bg_anchor)
        t.at("bg_edge_narrow").fail("narrows the anchored background's entering band: needs bg_anchor");
    T.flat_block = static_cast<int>(t.integer_in("flat_block", T.flat_block, 0, 64));
    if (T.flat_block != 0 && (T.flat_block < 4 || (T.flat_block & (T.flat_block - 1)) != 0))
        t.at("flat_block").fail("must be 0 (off) or a power of two 4..64");
    T.flat_alpha = t.number_in("flat_alpha", T.flat_alpha, 1.0 / 65536.0, 65535.0 / 65536.0);
    T.flat_gate = t.number_in("flat_gate", T.flat_gate, 1.0 / 256.0, 127.0);
    if (t.has("flat_relative"))
        T.flat_relative = t.at("flat_relative").as_bool();
    if (t.has("flat_rescale"))
        T.flat_rescale = t.at("flat_rescale").as_bool();
    if (T.flat_rescale && T.flat_block == 0)
        t.at("flat_rescale").fail("rescales the flat-field step's output: needs flat_block");
    if (t.has("flat_level_blocks"))
        T.flat_level_blocks = t.at("flat_level_blocks").as_bool();
    T.clutter_persist = static_cast<int>(t.integer_in("clutter_persist", T.clutter_persist, 0, 32));
    T.clutter_excess = t.number_in("clutter_excess", T.clutter_excess, 0.01, 127.0);
    if (T.clutter_persist > 0 && !T.clutter_mean)
        t.at("clutter_persist").fail("gates the map's mean: needs clutter_mean true");
    T.clutter_mean_floor = t.number_in("clutter_mean_floor", T.clutter_mean_floor, 0.0, 8.0);
    if (T.clutter_mean_floor > 0 && !T.clutter_mean)
        t.at("clutter_mean_floor").fail("a floor of the map's mean: needs clutter_mean true");
    T.clutter_floor_age = static_cast<int>(t.integer_in("clutter_floor_age", T.clutter_floor_age, 0, 255));
    if (T.clutter_floor_age > 0 && !(T.clutter_mean_floor > 0))
        t.at("clutter_floor_age").fail("the age from which the mean's floor applies: needs clutter_mean_floor > 0");
    T.clutter_block = static_cast<int>(t.integer_in("clutter_block", T.clutter_block, 0, 4));
    if (T.clutter_block != 0 && T.clutter_block != 2 && T.clutter_block != 4)
        t.at("clutter_block").fail("must be 0 (per pixel), 2 or 4");
    if (t.has("clutter_map8"))
        T.clutter_map8 = t.at("clutter_map8").as_bool();
    if (T.clutter_map8 && T.clutter_block != 0)
        t.at("clutter_map8").fail("the 8-bit map is per pixel: needs clutter_block 0");
    if (t.has("clutter_anchor"))
        T.clutter_anchor = t.at("clutter_anchor").as_bool();
    if (T.clutter_anchor && T.clutter_block != 0)
        t.at("clutter_anchor").fail("the anchored map is per pixel: needs clutter_block 0");
}

void parse_dbt(const Field &d, DbtSettings &D)
{
    d.only({"pfa", "m", "n", "max_misses", "gate_chi2", "gate_max_px", "meas_sigma_px",
            "accel_sigma", "vel_sigma0", "max_detections", "preprocess", "note"});
    if (d.has("preprocess")) {
        // DBT's own preprocessing: the tracker block's reader over a block that sets nothing
        // else (the library's defaults, never the scenario's tracker block); the TBD manager's
        // fields are refused by name, any other name not a preprocessing field as unknown (the list
        // of allowed names gives only the preprocessing fields)
        const Field p = d.at("preprocess");
        if (!p.is_object())
            p.fail("expected an object of preprocessing fields (those of the tracker block that set the stage, the flat-field step and the clutter map)");
        std::string allowed;
        for (const char *const *f = kPreprocessFields; *f != nullptr; ++f)
            allowed += (allowed.empty() ? "" : ", ") + std::string(*f);
        for (auto it = p.node().begin(); it != p.node().end(); ++it) {
            bool known = false;
            for (const char *const *f = kTrackerOnlyFields; *f != nullptr; ++f)
                if (it.key() == *f)
                    p.at(it.key()).fail("a field of the TBD manager, not of the preprocessing: set it in the tracker block (dbt.preprocess takes only the stage, flat-field, residual_hp and clutter map fields)");
            for (const char *const *f = kPreprocessFields; *f != nullptr; ++f)
                known = known || it.key() == *f;
            if (!known)
                p.at(it.key()).fail("unknown field (allowed here: " + allowed + ")");
        }
        TrackerSettings t;
        parse_tracker(p, t);
        D.preprocess = t;
    }
    D.pfa = d.number_in("pfa", D.pfa, 1e-12, 0.5);
    D.n = static_cast<int>(d.integer_in("n", D.n, 1, 31));
    D.m = static_cast<int>(d.integer_in("m", D.m, 1, 31));
    if (D.m > D.n)
        d.at("m").fail("must not exceed n");
    D.max_misses = static_cast<int>(d.integer_in("max_misses", D.max_misses, 1, 1000));
    D.gate_chi2 = d.number_in("gate_chi2", D.gate_chi2, 1e-3, 1e3);
    D.gate_max_px = d.number_in("gate_max_px", D.gate_max_px, 0.1, 1e3);
    D.meas_sigma_px = d.number_in("meas_sigma_px", D.meas_sigma_px, 1e-3, 1e2);
    D.accel_sigma = d.number_in("accel_sigma", D.accel_sigma, 0.0, 1e2);
    D.vel_sigma0 = d.number_in("vel_sigma0", D.vel_sigma0, 0.0, 1e3);
    D.max_detections = static_cast<int>(d.integer_in("max_detections", D.max_detections, 1, 1000000));
}

}  // namespace

IrScenario parse_ir_scenario(const nlohmann::json &j, const std::string &file,
                             const std::string &backgrounds)
{
    IrScenario s;
    s.file = file;
    s.raw = j;
    Field root(j, file);
    root.only({"kind", "name", "description", "image", "frames", "background", "optics_blur_px",
               "platform", "sensor", "targets", "tracker", "dbt", "eval", "output", "note"});
    if (root.string("kind") != "tbd_ir")
        root.at("kind").fail("expected \"tbd_ir\"");
    s.name = root.string_or("name", "");
    s.description = root.string_or("description", "");
    if (root.has("image")) {
        Field im = root.at("image");
        im.only({"width", "height"});
        s.width = static_cast<int>(im.integer_in("width", 384, 16, 8192));
        s.height = static_cast<int>(im.integer_in("height", 288, 16, 8192));
        check_frame_area(file + ": image", static_cast<std::uint64_t>(s.width),
                         static_cast<std::uint64_t>(s.height));
        s.size_given = true;
    }
    s.frames = static_cast<int>(root.integer_in("frames", 100, 1, 1000000));
    s.optics_blur_px = root.number_in("optics_blur_px", 0.7, 0.0, 20.0);
    if (root.has("background"))
        parse_background(root.at("background"), s);
    if (!backgrounds.empty()) {
        s.background.source = "folder";
        s.background.folder = backgrounds;
    }
    if (s.background.source == "folder" && s.background.folder.empty())
        root.fail("background.folder: required for source \"folder\" (or give --backgrounds DIR)");
    if (root.has("platform")) {
        Field p = root.at("platform");
        p.only({"drift_px", "jitter_px", "warp", "note"});
        s.platform.drift_px = pair_or(p, "drift_px", s.platform.drift_px, -50.0, 50.0);
        s.platform.jitter_px = p.number_in("jitter_px", s.platform.jitter_px, 0.0, 50.0);
        s.platform.warp = p.choice_or("warp", s.platform.warp, {"opencv", "bspline", "catmull_rom"});
    }
    if (root.has("sensor")) {
        Field se = root.at("sensor");
        se.only({"bit_depth", "noise_sigma", "column_fpn_sigma", "dead_fraction",
                 "saturated_fraction", "vignetting", "note"});
        Sensor &S = s.sensor;
        S.bit_depth = static_cast<int>(se.integer_in("bit_depth", S.bit_depth, 8, 16));
        S.noise_sigma = se.number_in("noise_sigma", S.noise_sigma, 1e-3, 1e5);
        S.column_fpn_sigma = se.number_in("column_fpn_sigma", S.column_fpn_sigma, 0.0, 1e5);
        S.dead_fraction = se.number_in("dead_fraction", S.dead_fraction, 0.0, 0.1);
        S.saturated_fraction = se.number_in("saturated_fraction", S.saturated_fraction, 0.0, 0.1);
        S.vignetting = se.number_in("vignetting", S.vignetting, 0.0, 0.9);
    }
    if (root.has("targets"))
        parse_targets(root.at("targets"), s);
    if (root.has("tracker"))
        parse_tracker(root.at("tracker"), s.tracker);
    if (root.has("dbt"))
        parse_dbt(root.at("dbt"), s.dbt);
    if (root.has("eval")) {
        Field e = root.at("eval");
        e.only({"runs", "base_seed", "d_c", "d_assoc", "drop_prob", "drop_frames"});
        s.eval.runs = static_cast<unsigned>(e.integer_in("runs", s.eval.runs, 1, 10000000));
        s.eval.base_seed = static_cast<uint64_t>(e.integer_in("base_seed", 1, 0, INT64_MAX));
        s.eval.d_c = e.number_in("d_c", 1.0, 1e-6, 1e4);
        s.eval.d_assoc = e.number_in("d_assoc", 3.0, 1e-6, 1e4);
        s.eval.loss = parse_frame_loss(e);
    }
    if (root.has("output")) {
        Field o = root.at("output");
        o.only({"format"});
        s.output_format = o.choice_or("format", "pgm", {"pgm", "raw"});
    }
    return s;
}

}  // namespace pft::host::tbd_ir
