// The IR pipeline of kind tbd_ir: one raw sensor frame in, tracks out.
//
// The library's preprocessing stage (pft_pre_*, lib/include/pft/pft_pre.h: a temporal
// registered background or a spatial local mean with a guard window, selected by the
// scenario's tracker.preprocess; column offsets; per-tile MAD sigma; dead and saturated pixels
// masked) turns the frame into a whitened residual (PFT_PIX_RES16, Q8.8 sigma units). Two
// trackers run on that same residual: the library's multi-target TBD manager (pft_tbd_*, noise
// sigma 1; the residual is handed over as it is, a PFT_PIX_RES16 frame whose masked pixels the
// manager reads as 0) and the host-side detect-before-track baseline (ir_dbt.hpp). With the
// scenario's dbt.preprocess the baseline reads instead the residual of a second preprocessing
// (stage, flat-field step, residual_hp, clutter map: its own settings and workspaces, no
// scene-motion test) fed the same frames; TBD's side is unchanged.
// step() takes the frame as the sensor gives it and returns both trackers' tracks and events.
#pragma once
#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <vector>

#include <opencv2/core.hpp>

extern "C" {
#include "pft/pft_pre.h"
#include "pft/pft_tbd_scene.h"
#include "pft/pft_types.h"
}

#include "ir_dbt.hpp"
#include "ir_scenario.hpp"
#include "tracker.hpp"

namespace pft::host::tbd_ir {

/** What one frame gives: the TBD manager's output and the DBT baseline's. */
struct PipelineOut {
    tbd::FrameOut tbd, dbt;
    int detections = 0;  ///< DBT detections of the frame
};

/** The scene-registered clutter map of the pipeline (TrackerSettings::clutter_*): the
 *  library's pft_pre_clutter_* (pft_pre.h) in a workspace of its own. */
struct ClutterMap {
    pft_pre_clutter_t c{};  ///< the map (its configuration is c.cfg)
    std::vector<uint64_t> work;
    const int16_t *out = nullptr;  ///< the last output residual (Q8.8 sigma units, masked pixels kept), stride = width
    std::size_t bytes = 0;         ///< workspace bytes
};

/** The pft_pre_clutter configuration of the pipeline's settings (width x height frames). */
/** TrackerSettings::residual_hp: out (CV_16S, Q8.8) = res less its mean over the (2R + 1)^2 square,
 *  masked pixels (PFT_RES16_MASKED) left out of the mean and kept masked. */
void residual_highpass(const int16_t *res, std::size_t stride, int w, int h, int R, cv::Mat &out);
pft_pre_clutter_config_t make_clutter_config(const TrackerSettings &t, int width, int height);

/** One frame of the clutter map: res (PFT_PIX_RES16 of stride px per row) in, resid (CV_32F of
 *  the frame's size, masked 0) and c.out out; (sx, sy) the scene's shift since the last frame
 *  (z(p) = b(p - shift)); ev false: a frame without evidence (all masked, map unchanged). The
 *  map is set up on the first call. With inplace (the same on every call) res is the caller's
 *  writable buffer with stride = width: the map is configured inplace and its output is written
 *  over res (pft_pre_clutter_update_inplace), c.out is then res; the same values. */
void clutter_step(ClutterMap &c, const TrackerSettings &t, const int16_t *res, std::size_t stride, bool ev,
                  double sx, double sy, cv::Mat &resid, bool inplace = false);

class IrPipeline {
public:
    /** width x height frames of bit_depth bits (8..16), given to the stage as U16. */
    IrPipeline(const TrackerSettings &t, const DbtSettings &d, double psf_sigma, int width,
               int height, int bit_depth, uint64_t seed);

    /** Preprocessing, then the TBD manager and the DBT baseline. frame: U8 or U16 of the
     *  configured size (F32 frames are rounded to counts); its seq numbers the output.
     *  InputError on a refused frame. */
    PipelineOut step(const pft_frame_t &frame);

    const cv::Mat &residual() const { return resid_; }  ///< last whitened residual (CV_32F, masked 0; in clutter sigmas with the clutter map)
    /** Diagnostics (ir_trace.hpp): keep a copy of the stage's residual after the flat-field
     *  correction and before the clutter map (stage_residual()); off by default (no cost). */
    void keep_stage_residual(bool on) { keep_stage_ = on; }
    /** The stage's residual of the last frame (CV_32F, sigma units, masked 0) when
     *  keep_stage_residual(true), else empty. */
    const cv::Mat &stage_residual() const { return stage_resid_; }
    std::size_t clutter_workspace_bytes() const { return cm_.bytes; } ///< the clutter map's workspace (0 without the map)
    std::size_t flat_workspace_bytes() const { return flat_bytes_; } ///< the flat-field correction's workspace (0 without it)
    double sigma() const { return sigma_; }              ///< last frame's mean tile sigma, counts
    int masked() const { return masked_; }               ///< last frame's masked pixels
    uint32_t flags() const { return stats_.flags; }      ///< last frame's PFT_PRE_FLAG_*
    const pft_pre_stats_t &stats() const { return stats_; }
    /** Whether the last frame carried detection evidence (not constant, all masked or a
     *  registration restart). */
    bool evidence() const;
    std::size_t workspace_bytes() const { return tracker_->workspace_bytes(); }
    std::size_t pre_workspace_bytes() const { return pre_ws_bytes_; }
    const pft_tbd_config_t &config() const { return tracker_->config(); }
    const tbd::Tracker &tracker() const { return *tracker_; }  ///< the TBD manager (diagnostics, ir_trace.hpp)
    /** Whether the scene-motion test has found TBD track `id` moving with the scene. */
    bool scene_flagged(uint32_t id) const { return T_.scene_frames > 0 && pft_tbd_scene_is_clutter(&scene_, id); }
    std::size_t scene_workspace_bytes() const { return scene_bytes_; } ///< the scene-motion test's workspace (0 without it)
    /** The scene's cumulative shift (the stage's measured shifts summed), px. */
    std::array<double, 2> scene_shift() const { return {scene_x_, scene_y_}; }
    /** The scene-motion test's decision on track `id` at the last frame (pft_tbd_scene_decision_t),
     *  -1 when it was not fed to the test (diagnostics, ir_trace.hpp). */
    int scene_decision(uint32_t id) const
    {
        for (const auto &d : scene_dec_)
            if (d.first == id)
                return d.second;
        return -1;
    }
    const pft_pre_config_t &pre_config() const { return pre_cfg_; }
    /** The library configurations this pipeline runs with and what it passes between the
     *  calls (tests/tools/ir_probe_fields.h; written by `pft bench --probe-out`, read by
     *  tests/tools/ir_probe -c): built by the same functions the pipeline's own calls use. */
    struct ProbeSetup {
        pft_pre_config_t pre{};
        bool flat = false;  ///< flat_block > 0: pft_pre_flat_update after the stage
        pft_pre_flat_config_t flat_cfg{};
        bool flat_relative = false;  ///< its level frame is the raw frame
        bool clutter = false;        ///< clutter_alpha > 0: the clutter map after the flat step
        pft_pre_clutter_config_t clutter_cfg{};
        pft_tbd_config_t tbd{};
        bool scene = false;  ///< scene_frames > 0: the scene-motion test after the manager
        pft_tbd_scene_config_t scene_cfg{};
        bool scene_tentative = false;
        bool integ_shift = false;
        int bits = 0;
    };
    /** The setup above; throws InputError for a pipeline with a host-only step between the
     *  calls (residual_hp, flat_level_blocks), which the probe does not reproduce. */
    ProbeSetup probe_setup() const;
    /** The clutter map's last output (the manager's input on a frame with evidence), stride =
     *  width; nullptr without the map. */
    const int16_t *clutter_output() const { return cm_.out; }
    double dbt_threshold_sigma() const { return dbt_thr_; }
    /** Whether DBT reads its own preprocessing (dbt.preprocess) instead of the TBD pipeline's
     *  residual. */
    bool dbt_own_preprocess() const { return dbt_pre_ != nullptr; }

private:
    /** pre_only: the preprocessing alone (no manager, no scene-motion test, no DBT pipeline of
     *  its own): DBT's own preprocessing. */
    IrPipeline(const TrackerSettings &t, const DbtSettings &d, double psf_sigma, int width, int height,
               int bit_depth, uint64_t seed, bool pre_only);
    /** The stage, the flat-field step, residual_hp and the clutter map on one frame: the
     *  residual the trackers read (stride px per row; ev false for a frame without evidence);
     *  residual() and stats() updated. */
    const int16_t *preprocess(const pft_frame_t &frame, std::size_t &stride, bool &ev);
    std::unique_ptr<IrPipeline> dbt_pre_;  // dbt.preprocess: DBT's own preprocessing
    TrackerSettings T_;
    int w_, h_, bits_;
    pft_pre_config_t pre_cfg_{};
    std::vector<uint64_t> pre_work_;
    std::size_t pre_ws_bytes_ = 0;
    pft_pre_t pre_{};
    pft_pre_stats_t stats_{};
    std::unique_ptr<tbd::Tracker> tracker_;
    DbtTracker dbt_;
    double dbt_thr_;
    int max_det_;
    cv::Mat resid_, u16_, blank_;
    bool keep_stage_ = false;  // keep_stage_residual
    cv::Mat stage_resid_;      // stage_residual
    cv::Mat hp_;  // residual_hp: the high-passed residual (CV_16S, Q8.8)
    ClutterMap cm_;
    // flat_block > 0: the flat-field offset correction (pft_pre_flat_*), on the residual
    pft_pre_flat_t flat_{};
    std::vector<uint64_t> flat_work_;
    std::size_t flat_bytes_ = 0;
    cv::Mat flat_res_;  // the residual's copy when the stage does not work in place (CV_16S)
    cv::Mat level_;     // flat_relative: the converted raw frame (the stage overwrites u16_)
    // scene-motion test (scene_frames > 0): the library's pft_tbd_scene_* (pft_tbd_scene.h)
    pft_tbd_scene_t scene_{};
    std::vector<uint64_t> scene_work_;
    std::size_t scene_bytes_ = 0;
    double scene_x_ = 0, scene_y_ = 0;  // the scene's cumulative shift (scene_shift)
    std::vector<std::pair<uint32_t, int>> scene_dec_;  // the last frame's decisions (scene_decision)
    void scene_test(tbd::FrameOut &out, int32_t shift_x, int32_t shift_y);
    double sigma_ = 0;
    int masked_ = 0;
};

/** The pft_tbd_scene configuration of the pipeline's settings (scene_frames > 0; width x
 *  height frames, max_targets slots). */
pft_tbd_scene_config_t make_scene_config(const TrackerSettings &t, int width, int height);

/** The pft_pre_flat configuration of the pipeline's settings (width x height frames). */
pft_pre_flat_config_t make_flat_config(const TrackerSettings &t, int width, int height);

/** The pft_pre configuration of the pipeline (method, windows, tile from the settings). */
pft_pre_config_t make_pre_config(const TrackerSettings &t, int width, int height, int bit_depth, bool u8);

/** The pft_tbd configuration of the pipeline (noise sigma 1 on the whitened residual; the
 *  intensity prior from the tracker's SNR range). */
pft_tbd_config_t pipeline_config(const TrackerSettings &t, double psf_sigma, int width, int height,
                                 uint64_t seed);

/** Bits of a sequence from its frames: the container's (frame bit depth), lowered to the
 *  smallest of 8..16 that holds the largest value seen. */
int detect_bit_depth(int container_bits, const std::vector<cv::Mat> &head);

}  // namespace pft::host::tbd_ir
