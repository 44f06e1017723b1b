// C++ wrapper over the library's TBD API: the multi-target manager (pft_tbd_*) or one
// single-target filter (pft_tbd_filter_*), with its workspace, giving per-frame results in
// double precision. In single mode a "track" is a maximal run of frames with P > theta1
// (the paper's Exp. 1 decision rule), numbered 1, 2, ... in order.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

extern "C" {
#include "pft/pft_tbd.h"
}

#include "../common/real.hpp"
#include "scenario.hpp"

namespace pft::host::tbd {

using ::pft::host::from_real;
using ::pft::host::numeric_name;
using ::pft::host::to_real;

struct TrackOut {
    uint32_t id = 0;
    double x = 0, y = 0, vx = 0, vy = 0, intensity = 0, p_exist = 0;
    double pos_var = 0;  ///< the position spread xx + yy (pft_tbd_track_t pos_cov[0] + pos_cov[2]), px^2
    uint32_t first_frame = 0;
};

struct EventOut {
    int kind = 0;  ///< PFT_TBD_EV_CONFIRMED or PFT_TBD_EV_ENDED
    uint32_t id = 0, frame = 0;
    double x = 0, y = 0;
};

struct FrameOut {
    uint32_t frame = 0;
    int width = 0, height = 0;  ///< multi: the image size (for births below)
    std::vector<TrackOut> tracks;
    std::vector<EventOut> events;
    /// multi with cfg.sprt_accept > 0: the tentative tracks of the sequential test (not reported,
    /// docs/algorithms.md 2.12), id, position and velocity from the hand-over on; first_frame 0
    std::vector<TrackOut> tentative;
    double search_p = 0;  ///< multi: search layer P; single: the filter's P
    double search_x = 0, search_y = 0;
    bool search_valid = false;
    /// multi: the search layer's birth candidates of the frame (pixel indices row * width +
    /// column, pft_tbd_birth_candidates), when listed (births from peaks or B_k; empty otherwise)
    std::vector<uint32_t> births;
};

/** Library configuration from a scenario (filter settings, model, sigma, image size). */
/** The library preset named by a scenario's "preset" ("paper", "recommended", "bounded"). */
void preset_config(const std::string &preset, pft_tbd_config_t *c);

pft_tbd_config_t make_config(const Scenario &s, uint64_t seed);
/** The scenario's overrides of the preset (every field the file gives) into c. */
void apply_overrides(const FilterSettings &F, pft_tbd_config_t &c);
/** Every field of a configuration (reals as doubles), for summaries. */
nlohmann::json config_to_json(const pft_tbd_config_t &c);

class Tracker {
public:
    /** single: one filter with `particles`, kind from cfg.kind; else the manager. */
    Tracker(const pft_tbd_config_t &cfg, bool single);
    Tracker(const Tracker &) = delete;
    Tracker &operator=(const Tracker &) = delete;

    /** Pushes one frame; InputError with the library's status on refusal. */
    FrameOut update(const pft_frame_t &frame);
    /** The manager's pft_tbd_set_shift for the next update (pixels); the single filter ignores it. */
    void set_shift(double dx, double dy);
    /** Same, for an F32 image of the configured size. */
    FrameOut update_f32(const float *img, uint32_t seq);

    std::size_t workspace_bytes() const { return ws_bytes_; }
    bool single() const { return single_; }
    const pft_tbd_config_t &config() const { return cfg_; }
    /** Particles updated at the last frame (multi: n_search + n_track per track layer live
     *  before the frame, reported or tentative (cfg.sprt_accept > 0)). */
    uint64_t active_particles() const { return active_; }
    /** The manager (not the single filter): for host diagnostics (ir_trace.hpp) only. */
    const pft_tbd_t &manager() const { return mgr_; }

private:
    FrameOut update_single(const pft_frame_t &frame);
    FrameOut update_multi(const pft_frame_t &frame);

    pft_tbd_config_t cfg_;
    bool single_;
    std::vector<uint64_t> work_;  // 8-byte aligned workspace
    std::size_t ws_bytes_ = 0;
    pft_tbd_t mgr_{};
    pft_tbd_filter_t flt_{};
    // single-mode track bookkeeping
    bool present_ = false;
    uint32_t next_id_ = 1, cur_id_ = 0, cur_first_ = 0, frame_ = 0;
    uint64_t active_ = 0;
};

}  // namespace pft::host::tbd
