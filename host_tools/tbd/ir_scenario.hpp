// Scenario files of kind "tbd_ir": semi-synthetic infrared sequences (a real or procedural
// background drifting with the platform, scaled to the sensor's bit depth, with temporal and
// column noise, dead and saturated pixels, vignetting and injected dim point targets) and the
// settings of the IR pipeline that tracks them. Every field, its unit and default:
// docs/host_tools.md, "IR scenario files".
#pragma once
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "../common/frame_loss.hpp"

namespace pft::host::tbd_ir {

/** Built-in procedural sky (levels are fractions of the sensor's full scale). */
struct Procedural {
    double sky_top = 0.22, sky_horizon = 0.34;  ///< sky level at the top row and at the horizon
    double cloud_cover = 0.35;                  ///< fraction of the sky under cloud
    double cloud_scale_px = 96;                 ///< size of the largest cloud structures
    double cloud_level = 0.16;                  ///< cloud level above the sky
    double cloud_texture = 0.35;                ///< relative texture inside the clouds
    double cloud_edge_px = 4;                   ///< width of the cloud edges
    std::optional<double> horizon = 0.8;        ///< horizon row / frame height (none: all sky)
    double ground_level = 0.5, ground_texture = 0.04;
    int structures = 3;                         ///< towers/buildings standing on the horizon
};

struct Background {
    std::string source = "procedural";          ///< "procedural" | "folder"
    Procedural proc;
    std::string folder;                         ///< folder of background images (source folder)
    std::vector<std::string> files;             ///< subset of the folder (empty: all images)
    std::optional<int> index;                   ///< fixed image; absent: (seed - 1) mod count
    bool labels = true;                         ///< read YOLO label files beside the images
    double scale = 0;                           ///< counts per image unit (0: 2^(bits - image bits))
    double smooth_px = 0;                       ///< Gaussian sigma (image px) applied to a folder image before scaling: takes out its quantisation steps and frozen pixel noise (0: off)
};

struct Platform {
    std::array<double, 2> drift_px{0.3, 0.1};   ///< scene motion in px per frame (x, y)
    double jitter_px = 0.1;                     ///< white jitter, sigma per axis, px
    /// how a frame is cut out of the scene at the platform's sub-pixel position:
    /// "opencv" (default, every sequence so far): cv::warpAffine, INTER_CUBIC (Keys a = -0.75),
    /// the position rounded to 1/32 px; its phase error moves low frequencies by
    /// g(t) = 0.5 t (1 - t)(1 - 2t) px at the position's fraction t, up to 0.048 px at t = 0.21
    /// and 0.79 (docs/results/ir_clutter.md, "Branch irreg"), so the frames are not at
    /// platform.csv's positions to better than that.
    /// "bspline": the exact position, cubic B-spline interpolation (the scene prefiltered once);
    /// "catmull_rom": the exact position, Catmull-Rom cubic (Keys a = -0.5, the stage's own warp).
    std::string warp = "opencv";
};

struct Sensor {
    int bit_depth = 14;
    double noise_sigma = 20;                    ///< temporal noise, counts
    double column_fpn_sigma = 6;                ///< column fixed-pattern offsets, counts
    double dead_fraction = 2e-4;                ///< pixels stuck at 0
    double saturated_fraction = 1e-4;           ///< pixels stuck at full scale
    double vignetting = 0.2;                    ///< relative fall-off at the corners (0: none)
    double full_scale() const { return static_cast<double>((1u << bit_depth) - 1u); }
};

/** An explicitly placed target (frames 1-based, positions 0-based pixels at birth_frame). */
struct TargetSpec {
    int id = 0;
    int birth = 1, death = 0;                   ///< death 0: until it leaves the frame or the end
    double x = 0, y = 0, vx = 0, vy = 0;
    double turn_deg = 0;                        ///< heading change per frame
    double snr_db = 9;
};

struct Targets {
    std::array<int, 2> count{4, 4};             ///< random targets (uniform in the range per run)
    std::array<double, 2> snr_db{9, 9};         ///< SNR range (dB), uniform per target
    double psf_sigma = 0.7;
    std::array<double, 2> speed_px{0.3, 1.2};   ///< px per frame
    double turn_deg = 1.0;                      ///< max |heading change| per frame, degrees
    double enter_fraction = 0.5;                ///< random targets entering at a border
    int min_life = 15;                          ///< frames
    int crossings = 1;                          ///< extra pairs made to cross each other
    std::vector<TargetSpec> list;
};

/** Settings of the IR pipeline (the library's preprocessing stage + its TBD manager). */
struct TrackerSettings {
    std::string preprocess = "temporal";        ///< pft_pre background: "temporal" | "spatial"
    double bg_alpha = 0.15;                     ///< temporal background update weight
    double col_alpha = 1.0 / 16.0;              ///< update weight of the stage's column offsets (pft_pre col_alpha; 0: off)
    std::string preset = "recommended";         ///< pft_tbd preset to start from
    uint32_t particles = 6000, track_particles = 500;
    uint32_t max_targets = 8;
    double snr_min_db = 6, snr_max_db = 18;     ///< intensity prior over the whitened residual
    int background_radius = 5, guard_radius = 2;///< spatial: local-mean window and its guard (half-sizes)
    int tile = 32;                              ///< noise-estimate tile side, px
    double edge_k = 0;                          ///< temporal: the stage's edge term (pft_pre edge_k), px; 0: off (docs/results/ir_clutter.md: 0.08 px measured, no gain)
    // the stage's cost levers (pft_pre.h; docs/results/ir_clutter.md, "Branch ircost6"); the library's defaults
    int reg_step = 2;                           ///< temporal: registration on every reg_step-th pixel of every reg_step-th row (pft_pre reg_step, 1..8)
    int reg_iters = 2;                          ///< temporal: Lucas-Kanade iterations (pft_pre reg_iters, 0..8)
    bool warp_cubic = true;                     ///< temporal: cubic (true) or bilinear (false) warp of the background (pft_pre warp_cubic)
    int sigma_step = 1;                         ///< tile sigmas from every sigma_step-th pixel of every sigma_step-th row (pft_pre sigma_step, 1..4)
    bool sigma_interp = true;                   ///< 1/sigma interpolated between tile centres (true) or held per tile (false) (pft_pre sigma_interp)
    int sigma_every = 1;                        ///< tile sigmas of each tile row estimated every sigma_every-th frame (pft_pre sigma_every, 1..8)
    bool reg_bin = false;                       ///< temporal: registration sums on 2 x 2 boxes of pixels (pft_pre reg_bin; reg_step at least 2)
    bool sigma_current = true;                  ///< whiten each frame with its own tile sigmas (true) or with the last frame's (pft_pre sigma_current)
    bool sigma_bracket = false;                 ///< tile sigmas from counts around the last median instead of histograms (pft_pre sigma_bracket)
    bool sigma_level = false;                   ///< tile sigmas taken about each tile's level (the mean of its clipped residual in the last frame) instead of about zero (pft_pre sigma_level, docs/algorithms.md 9.6)
    bool bg_anchor = false;                     ///< temporal background kept on a scene-anchored grid (pft_pre bg_anchor; the stage then runs without inplace)
    double bg_gate = 0.0;                       ///< with bg_anchor: the background's update innovation clipped to +-bg_gate tile sigmas (pft_pre bg_gate, 0 off or 0.25..16)
    int bg_gate_shift = 0;                      ///< with bg_gate: 0 clips the innovation beyond the gate; 1..15 updates those cells with alpha / 2^shift (pft_pre bg_gate_shift)
    int bg_gate_young = 0;                      ///< with bg_gate: frames a grid cell that entered the scene is updated without the gate (pft_pre bg_gate_young, 0 off or 1..255)
    double bg_young_clip = 0.0;                 ///< with bg_gate_young: a cell that enters the scene starts within this many tile sigmas of the nearest cell held so far, and young cells are updated with this clip instead of no gate (pft_pre bg_young_clip, 0 off or 0.25..16)
    std::string bg_gate_local = "off";          ///< with bg_gate: "mean" or "relative" gates the innovation less its tile's part from the last frame (pft_pre bg_gate_local), "off"
    std::string bg_masked_taps = "off";         ///< with bg_anchor: "young" (needs bg_gate_young) or "all" updates a grid cell with a masked horizontal tap from its valid taps renormalised (pft_pre bg_masked_taps), "off" keeps it
    bool bg_young_scale = false;                ///< with bg_gate_young: the residual of pixels on young grid cells divided by sqrt(1 + (1 - alpha)^(2 age + 1)), their background's own error (pft_pre bg_young_scale, docs/algorithms.md 9.13)
    bool bg_edge_narrow = false;                ///< with bg_anchor: the entering band narrowed from about 3 to 1-2 px by 3-tap (quadratic) reads and updates where the cubic taps are not all held (pft_pre bg_edge_narrow, docs/algorithms.md 9.12)
    int bg_stale_reinit = 0;                    ///< temporal: a background value not learnt for more than N frames (or never) because its pixel was masked restarts from the frame, the residual reading it masked (pft_pre bg_stale_reinit, 0 off or 1..126)
    uint64_t seed_offset = 0;
    // full-frame options of the TBD manager (pft_tbd_config_t fields of the same names,
    // docs/algorithms.md 2.11), tuned on the shipped sweep (docs/results/ir_clutter.md, "Full-frame
    // TBD in the pipeline"); the optional ones, absent, keep the preset's value
    int birth_peaks = 256;                      ///< births from the K strongest PSF-matched peaks (0: B_k, the paper)
    int peak_tile = 0, peak_quota = 0;          ///< at most peak_quota birth peaks per peak_tile x peak_tile tile (0: off)
    double birth_share = 0.5;                   ///< Bernoulli search layer (0: the paper's per-particle existence)
    bool birth_correction = true;               ///< importance correction of the births
    int confirm_frames = 2;                     ///< consecutive frames with P > theta1 to confirm
    std::optional<double> peak_gamma, theta1, pb, theta_end;
    std::optional<double> sprt_accept, sprt_reject; ///< sequential confirmation (pft_tbd sprt_*; absent: the library default, off)
    std::optional<double> shape_ring;               ///< PSF shape test at the hand-over (pft_tbd shape_ring; absent: off)
    std::optional<double> integ_alpha;              ///< multi-frame integration of the birth peaks (pft_tbd integ_alpha; absent: off)
    int end_grace_frames = 0;                       ///< a young track's existence test uses theta_end_grace for its first end_grace_frames frames (pft_tbd end_grace_frames; 0: off)
    std::optional<double> theta_end_grace;          ///< the young tracks' existence threshold (pft_tbd theta_end_grace; absent: the library default, 0)
    std::optional<double> q2;                       ///< intensity process noise of every layer (pft_tbd q2; absent: the preset's, 0.01)
    int end_persist = 0;                            ///< a track ends on its existence probability only after this many end tests in a row below its threshold (pft_tbd end_persist; 0 or 1: the first)
    std::optional<double> handover_in_scale;        ///< a new track layer's intensities times this factor at the hand-over (pft_tbd handover_in_scale; absent: the library default, 0: off)
    std::optional<double> split_px;                 ///< a track layer whose particles part into two groups this far apart (px) hands the smaller to a new layer (pft_tbd split_px; absent: the library default, 0: off; else 0.5..16)
    std::optional<double> split_share;              ///< the smaller group's least share of the layer's live particles (pft_tbd split_share, (0, 0.5]; needed with split_px)
    std::optional<double> resid_split;              ///< a second target beside a track layer: the matched residual's threshold (pft_tbd resid_split; absent: the library default, 0: off; else 1..50)
    int resid_split_frames = 0;                     ///< its frames in a row (pft_tbd resid_split_frames; 0 or 1: one)
    int resid_split_age = 0;                        ///< only layers with at most this many updates since their hand-over (pft_tbd resid_split_age; 0: every layer)
    int search_layers = 0;                          ///< search layers H (pft_tbd search_layers; 0 or 1: one)
    std::optional<double> search_sep;               ///< with search_layers >= 2: births barred within this many px of another layer's estimate (pft_tbd search_sep, 1..16; absent: 3)
    std::optional<double> search_hold;              ///< ... while that layer's existence probability is above this (pft_tbd search_hold, 0..1; absent: 0.5)
    bool integ_shift = false;                       ///< give the manager the stage's measured shift per frame (pft_tbd_set_shift) for the integration
    int sprt_start = 0;                             ///< what the sequential test starts from (pft_tbd sprt_start: 0 zero, 1 the search layer's ratios over its confirmation, 2 its log odds)
    // clutter map (the library's pft_pre_clutter_*, called by ir_pipeline.cpp): per-pixel mean square of the whitened residual,
    // registered to the scene (warped by the stage's measured shift every frame); both trackers
    // see the residual of clutter pixels in the map's sigma (ir_pipeline.cpp, clutter_step)
    double clutter_alpha = 0.1;                 ///< map update weight (0: no map)
    // scene-motion test (the library's pft_tbd_scene_*, lib/include/pft/pft_tbd_scene.h): a TBD track whose displacement over the last scene_frames
    // frames is within scene_gate_px per frame of the scene's (the stage's measured shift) is
    // clutter drifting with the platform: never reported, and the clutter map is raised where it
    // is; a track is reported once it has scene_frames frames and has not failed the test
    int scene_frames = 5;                       ///< frames of the test (0: off)
    double scene_gate_px = 0.15;                ///< px per frame
    double scene_fit_px = 0.2;                  ///< report a track only while its last scene_frames + 1 positions fit a straight line at constant speed within this rms (px; 0: off)
    bool scene_tentative = false;               ///< with sprt_accept: the test also counts a track's tentative frames (from the frame after its hand-over), not only its reported ones (docs/results/ir_clutter.md, "Branch irseq2")
    double scene_early_px = 0.5;                ///< report a track from its 4th estimate when it moved against the scene by more than this per frame over its last 3 frames (and fits the line); 0: off (docs/results/ir_clutter.md, "Clear sky: why targets are missed")
    double clutter_thr = 2;                     ///< map value (sigma^2) above which a pixel is clutter
    double clutter_veto = 0;                    ///< map value (sigma^2) above which the residual is 0 (no births there; 0: off)
    bool clutter_box = true;                    ///< read the map as its mean over the square (false: its largest value)
    bool clutter_mean = false;                  ///< subtract the map's mean residual too
    int clutter_persist = 0;                    ///< map's persistence gate (frames; 0: off): a residual beyond clutter_excess is learnt only once it has held this long at the same scene position
    double clutter_excess = 1.5;                ///< level of the persistence gate (sigma)
    double clutter_mean_floor = 0;              ///< with clutter_mean: the mean is subtracted only where its magnitude exceeds this (sigma; pft_pre_clutter_config_t.mean_floor; 0: off)
    int clutter_floor_age = 0;                  ///< with clutter_mean_floor: the floor only where the map's cell has learnt this many frames, younger cells take the plain mean (pft_pre_clutter_config_t.floor_age; 0: off)
    int clutter_block = 0;                      ///< map held on B x B blocks of the scene (pft_pre_clutter_config_t.block): 0 (per pixel), 2 or 4
    bool clutter_map8 = false;                  ///< map held in 8 bits per pixel (pft_pre_clutter_config_t.map8; per pixel only: clutter_block 0)
    bool clutter_anchor = false;                ///< map held on an integer grid of the scene, moved by whole pixels, instead of carried by a bilinear warp (pft_pre_clutter_config_t.anchor; per pixel only: clutter_block 0)
    int clutter_blur = 1;                       ///< half-size of the square the map is read over (0: the pixel)
    // residual high-pass (host prototype, docs/results/ir_clutter.md "Branch irdet"): the stage's residual less its
    // mean over the (2 residual_hp + 1)^2 square (masked pixels left out), before the clutter map and both trackers
    int residual_hp = 0;                        ///< half-size of the square, px (0: off)
    // flat-field offset correction (the library's pft_pre_flat_*, docs/algorithms.md 9.10): the
    // stage's residual less a running mean per block of the SENSOR (bilinear between block
    // centres, gated at flat_gate), before residual_hp, the clutter map and both trackers
    int flat_block = 0;                         ///< block side, px, a power of two 4..64 (0: off)
    double flat_alpha = 0.05;                   ///< update weight of the block means
    double flat_gate = 2.0;                     ///< a pixel enters its block's mean only within this many sigma of the current offset
    bool flat_relative = false;                 ///< the offset is a sensor-fixed factor times the raw frame's level (the form a sensor-fixed gain leaves under a drifting scene)
    bool flat_rescale = false;                  ///< the flat-field step divides its output by a running robust sd per block (pft_pre_flat_config_t.rescale): the stage's tile sigma is inflated by the offset the step removes (docs/algorithms.md 9.10)
    bool flat_level_blocks = false;             ///< host experiment: with flat_relative, the level frame at the blocks' resolution (block means, bilinear) instead of the raw frame
    double scene_spread_px = 0.0;               ///< spread-dependent report hold (pft_tbd_scene_config_t.spread_px; 0: off): a track passing the test with a position spread sqrt(xx + yy) of at most this (px) is reported from its scene_spread_hold-th pass instead of its scene_hold-th (docs/results/ir_clutter.md, "Branch irfit")
    int scene_spread_hold = 1;                  ///< the hold of such frames (pft_tbd_scene_config_t.spread_hold): 1..scene_hold; needed with scene_spread_px
    double scene_spread_exist = 0.0;            ///< existence bound of the short hold (pft_tbd_scene_config_t.spread_exist; 0: off; needs scene_spread_px > 0): a frame takes scene_spread_hold only if the track layer's existence probability is at least this (docs/results/ir_clutter.md, "Branch irshort")
    int scene_slow_frames = 0;                  ///< the scene-motion test's longer look (pft_tbd_scene_config_t.slow_frames; 0: off): a track failing the gate over scene_frames frames with a displacement of at least scene_frames * scene_slow_low_px is undecided instead of clutter, and tested again over its longest window m (2 scene_frames..this) against sqrt(m scene_frames) * scene_slow_gate_px (docs/results/ir_clutter.md, "Branch irslow2")
    double scene_slow_low_px = 0.0;             ///< px per frame (pft_tbd_scene_config_t.slow_low_px): below it over scene_frames frames a track is clutter at once; 0..scene_gate_px
    double scene_slow_gate_px = 0.15;           ///< px (pft_tbd_scene_config_t.slow_gate_px): the longer windows' gate, sqrt(m scene_frames) times this
    double scene_edge_px = 0.0;                 ///< the entering-edge hold (pft_tbd_scene_config_t.edge_px; 0: off; needs scene_frames > 0): a track within this (px) of the border the scene's drift brings new content in from, still in the frame while the scene moves, is held (docs/algorithms.md 9.11 step 6); 0..256
    double scene_edge_still_px = 0.1;           ///< px per frame (pft_tbd_scene_config_t.edge_still_px): still in the frame below m times this over its last m frames; 0..256
    double scene_edge_shift_px = 0.2;           ///< px per frame (pft_tbd_scene_config_t.edge_shift_px): an axis's entering side needs the scene's shift over those m frames to be at least m times this; 0..256
    double scene_move_px = 0.0;                 ///< speed bound of the short hold (pft_tbd_scene_config_t.move_px; 0: off; needs scene_spread_px > 0): a frame takes scene_spread_hold only if the track moved at least m times this (px per frame) against the scene over its last m frames (docs/algorithms.md 9.11 step 5); 0..256
    int scene_move_hold = 0;                    ///< the hold of a slower track's compact frames (pft_tbd_scene_config_t.move_hold; 0: scene_hold): 0 or scene_spread_hold..scene_hold
    int scene_hold = 1;                         ///< report hold of the scene-motion test (pft_tbd_scene_config_t.hold_frames, needs scene_frames > 0): a track is reported from the k-th frame it passes the test on (1: no hold; docs/results/ir_clutter.md, "Branch irhold")
};

/** The tracker block's fields that set the preprocessing (the stage, the flat-field step,
 *  residual_hp and the clutter map): the only fields dbt.preprocess takes. */
extern const char *const kPreprocessFields[];
/** The tracker block's fields of the TBD manager and its scene-motion test, refused in
 *  dbt.preprocess with a message that says so. */
extern const char *const kTrackerOnlyFields[];

/** The detect-before-track baseline (ir_dbt.hpp), section "dbt" of the scenario. */
struct DbtSettings {
    /// dbt.preprocess: DBT's own preprocessing (a second stage + flat-field step + clutter map
    /// with their own workspaces, fed the same frames), read by the tracker block's code with
    /// only the preprocessing fields allowed; the fields it does not give take the defaults of a
    /// tracker block that sets nothing (never the scenario's tracker block). Absent: DBT reads
    /// the TBD pipeline's residual ("shared").
    std::optional<TrackerSettings> preprocess;
    double pfa = 1e-5;          ///< per-pixel false-alarm rate of the threshold (Gaussian residual)
    int m = 3, n = 5;           ///< M-of-N confirmation
    int max_misses = 3;         ///< frames in a row without a detection that end a confirmed track
    double gate_chi2 = 9.21;    ///< gate on the normalised innovation squared (99 % for 2 dof)
    double gate_max_px = 4.0;   ///< largest gate radius, px
    double meas_sigma_px = 0.5; ///< detection position noise, px
    double accel_sigma = 0.05;  ///< white acceleration noise, px/frame^2
    double vel_sigma0 = 1.0;    ///< initial velocity sd of a new track, px/frame
    int max_detections = 500;   ///< detections kept per frame (highest peaks)
};

struct EvalSettings {
    unsigned runs = 20;
    uint64_t base_seed = 1;
    double d_c = 1.0, d_assoc = 3.0;            ///< correct / association distances, px
    FrameLoss loss;                             ///< drop_prob, drop_frames: frames lost in a run
};

struct IrScenario {
    std::string file, name, description;
    int width = 384, height = 288;              ///< sensor frame
    bool size_given = false;                    ///< "image" present (else folder: from the image)
    int frames = 100;
    double optics_blur_px = 0.7;
    Background background;
    Platform platform;
    Sensor sensor;
    Targets targets;
    TrackerSettings tracker;
    DbtSettings dbt;
    EvalSettings eval;
    std::string output_format = "pgm";          ///< "pgm" (16-bit PGM) | "raw" (frames.u16)
    nlohmann::json raw;                         ///< the file as read

    /** Temporal-noise SNR (dB) of a peak amplitude in counts, and back. */
    double amplitude(double snr_db) const;
};

/** Parses and validates; InputError naming the bad field. `backgrounds` (--backgrounds)
 *  replaces background.folder and selects source "folder". */
IrScenario parse_ir_scenario(const nlohmann::json &j, const std::string &file,
                             const std::string &backgrounds = "");

}  // namespace pft::host::tbd_ir
