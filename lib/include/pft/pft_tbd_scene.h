/**
 * @file pft_tbd_scene.h
 * @brief The scene-motion test of the IR pipeline (pft_tbd_scene_*): which of the TBD
 *        manager's tracks to report, which to hold, and which move with the scene (clutter).
 *
 * A step after the manager (pft_tbd.h) in the IR pipeline (docs/porting.md, "The IR pipeline
 * on a target"; docs/algorithms.md 9.11). Clutter that the background keeps missing (a cloud
 * edge, the horizon, a structure) drifts with the platform, while a target moves across the
 * scene. Per track id the module keeps the track's last n + 1 positions (n = cfg.frames) and
 * the scene's cumulative shift at each (the sum of the preprocessing stage's measured shifts,
 * pft_pre_stats_t.shift), and decides per track and frame:
 *
 * - CLUTTER: its displacement over the last n frames less the scene's is below n * gate_px
 *   (tested once the track has n + 1 positions; a track found so stays CLUTTER for good). The
 *   caller drops it from the report and, with the clutter map (pft_pre.h), raises the map's
 *   3 x 3 entries around (px, py) (pft_pre_clutter_raise; the host raises to 16 sigma^2) so
 *   that its evidence fades and the manager ends it.
 * - REPORT: a track with n + 1 positions that is not CLUTTER, or from its 4th position on a
 *   track whose displacement against the scene over its last 3 frames is at least
 *   3 * early_px (early_px > 0, n >= 4); either way only while its positions (up to n + 1) fit
 *   a straight line at constant speed within an rms of fit_px (fit_px > 0).
 * - With hold_frames k > 1 a track that passes the above is reported only from the k-th frame
 *   it passes them on (the report hold); with spread_px > 0, at a frame it passes with a
 *   position spread sqrt(pos_var) of at most spread_px, from its spread_hold-th pass instead
 *   (a layer concentrated on a point is reported sooner; docs/algorithms.md 9.11 step 5);
 *   with spread_exist > 0 ([E]) such a frame takes the short hold only if the track's
 *   existence probability p_exist is at least spread_exist.
 * - With edge_px > 0 (the entering-edge hold, [E]; docs/algorithms.md 9.11 step 6) a track that
 *   passes the above is HOLD instead (and the frame is not counted as a pass of the hold) when,
 *   over its last m = min(positions - 1, n) frames, along an axis (x or y) its displacement in
 *   frame coordinates is below m * edge_still_px in magnitude while the scene's cumulative shift
 *   along that axis is at least m * edge_shift_px in magnitude and its newest position lies
 *   within edge_px of the border that shift brings new content in from (x: shift < 0, x >=
 *   width - 1 - edge_px; shift > 0, x <= edge_px; y alike with height). A track still in the
 *   frame elsewhere (a constant bearing) is not held.
 * - With slow_frames L > 0 (the longer look, [E]; docs/algorithms.md 9.11 step 1) a track that
 *   fails the gate over n frames is CLUTTER only if its displacement there is below
 *   n * slow_low_px; otherwise it is undecided (HOLD, not CLUTTER; it does not count as a pass of
 *   the hold) and is tested again, on every frame, over the longest window it holds,
 *   m = min(positions - 1, L) frames from m = 2n on: at least sqrt(m n) * slow_gate_px against the
 *   scene, it passes the gate at that frame (it goes on to the fit and the hold); below it with
 *   m = L, it is CLUTTER. The history then keeps L + 1 positions per slot (the fit and the early
 *   report still read the last n + 1).
 * - HOLD: neither yet (too few positions, the line fit fails, or undecided); tentative tracks (with the
 *   manager's sequential test, fed with tentative = true) are never reported, but their
 *   positions count and they can be found CLUTTER.
 * - NO_SLOT: the table is full (see below); the track is not tested.
 *
 * The history of an id is forgotten forget_frames frames after the last frame it was fed
 * (64 by default: the host's rule). Table: max_tracks slots. A new id takes a free slot; if
 * there is none, the slot of the id fed least recently (not in this frame's list; on a tie
 * the lowest slot) is taken over and its history lost; if every slot holds an id of this
 * frame's list, the new id gets NO_SLOT, is not remembered, and the call counts it
 * (pft_tbd_scene_overflows). Only a list of more than max_tracks tracks can meet a table
 * whose every slot holds an id of the list, so with max_tracks >= the manager's max_targets
 * no track gets NO_SLOT (the manager never holds more ids at once, reported and tentative).
 *
 * Arithmetic: integers only, the same bits in the float and q16 builds. Positions are taken
 * to Q16.16 px (exact in the q16 build; float positions rounded to the nearest 2^-16 px,
 * |x|, |y| saturated at 32768 px), the scene's cumulative shift is an int64 Q16.16 sum (exact),
 * gate_px, early_px and fit_px are taken to Q16.16 at init. The gate and early tests compare
 * squared displacements in Q32.32 exactly; the line fit's residuals are exact rationals
 * rounded to 2^-16 px (|residual| saturated at 1024 px), summed squared in Q32.32 and compared
 * with k fit_px^2 (k the positions held). Against the host's former 64-bit floating-point arithmetic a
 * decision can differ only where a displacement lies within the thresholds' rounding to
 * Q16.16 (gate 0.15 px is 0.149994 px, fit 0.2 px is 0.199997 px), or within about 1e-5 px of
 * a threshold (the fit's residuals rounded to 2^-16 px; in the float build also the
 * positions) (docs/results/ir_clutter.md, "Branch irscene").
 *
 * Use, per frame, after pft_tbd_update: list the manager's reported tracks (pft_tbd_tracks;
 * tentative = false) and, if wanted, its tentative ones (tentative = true), call
 * pft_tbd_scene_update with the frame's scene shift (pft_pre_stats_t.shift of the frame, or
 * 0, 0 for a frame without detection evidence: flags CONSTANT, ALL_MASKED or REG_LOST), then
 * report the tracks whose decision is REPORT and raise the clutter map under the CLUTTER
 * ones. Call it on every frame, with an empty list when there is no track: the frame count
 * and the scene's shift advance with each call.
 */
#ifndef PFT_TBD_SCENE_H
#define PFT_TBD_SCENE_H

#include "pft/pft_types.h"
#include "pft/pft_real.h"
#include "pft/pft_workspace.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Largest cfg.frames (the test's n). */
#define PFT_TBD_SCENE_MAX_FRAMES 31u
/** Largest cfg.hold_frames. */
#define PFT_TBD_SCENE_MAX_HOLD 64u
/** Largest cfg.max_tracks. */
#define PFT_TBD_SCENE_MAX_TRACKS 1024u

/** Configuration of the scene-motion test (defaults: the host pipeline's). */
typedef struct {
    uint32_t frames;        /**< n, frames of the test (default 5): 1..PFT_TBD_SCENE_MAX_FRAMES */
    uint32_t max_tracks;    /**< history slots (default 16): 1..PFT_TBD_SCENE_MAX_TRACKS; at least the manager's max_targets */
    pft_real_t gate_px;     /**< px per frame (default 0.15): CLUTTER below n * gate_px against the scene (0: no track is CLUTTER); [0, 256] */
    pft_real_t fit_px;      /**< rms of the straight-line fit, px (default 0.2; 0: off); [0, 256] */
    pft_real_t early_px;    /**< px per frame (default 0.5; 0: off): early report from the 4th position; [0, 256] */
    uint32_t forget_frames; /**< frames after its last one that an id's history is kept (default 64): 1..2^30 */
    uint32_t width;         /**< frame width, px (default 384): clamps px; 1..PFT_CFG_MAX_IMAGE_SIDE */
    uint32_t height;        /**< frame height, px (default 288): clamps py; 1..PFT_CFG_MAX_IMAGE_SIDE */
    uint32_t hold_frames;   /**< report hold k (default 1: none): a track is reported from the k-th frame it passes the tests on; 1..PFT_TBD_SCENE_MAX_HOLD */
    pft_real_t spread_px;   /**< [E] spread-dependent hold (default 0: off): at a frame a track passes the tests with its position spread sqrt(pos_var) at most spread_px, it needs only spread_hold passes instead of hold_frames (docs/algorithms.md 9.11 step 5); [0, 256] px */
    uint32_t spread_hold;   /**< the hold of such frames (default 1; read only with spread_px > 0): 1..hold_frames */
    uint32_t slow_frames;   /**< [E] the longer look's longest window L (default 0: off, a track failing the gate is CLUTTER at once): 2 * frames..PFT_TBD_SCENE_MAX_FRAMES; the history keeps max(frames, L) + 1 positions (docs/algorithms.md 9.11 step 1) */
    pft_real_t slow_low_px; /**< px per frame (default 0; read only with slow_frames > 0): a track failing the gate with a displacement below n * slow_low_px is CLUTTER at once; [0, gate_px] */
    pft_real_t slow_gate_px; /**< px (default 0.15; read only with slow_frames > 0): the gate over a window of m frames (2n <= m <= L) is sqrt(m n) * slow_gate_px; (0, 256] */
    pft_real_t spread_exist; /**< [E] existence bound of the spread-dependent hold (default 0: off; read only with spread_px > 0): a frame takes the short hold (spread_hold) only if the track's existence probability p_exist is at least spread_exist, compared in Q16.16; otherwise the frame needs hold_frames passes as a wide track's (docs/algorithms.md 9.11 step 5); [0, 1] */
    pft_real_t edge_px;      /**< [E] the entering-edge hold (default 0: off): a track within edge_px of the frame border on the side the scene's motion brings new content in from, still in the frame while the scene moves, is HOLD (docs/algorithms.md 9.11 step 6; see edge_still_px, edge_shift_px); [0, 256] px */
    pft_real_t edge_still_px; /**< px per frame (default 0.1; read only with edge_px > 0): a track is still in the frame along an axis when its frame displacement along it over its last m = min(positions - 1, frames) frames is below m * edge_still_px in magnitude; [0, 256] */
    pft_real_t edge_shift_px; /**< px per frame (default 0.2; read only with edge_px > 0): an axis has an entering side when the scene's cumulative shift along it over those m frames is at least m * edge_shift_px in magnitude (its sign gives the side: a negative shift brings content in at the far border, width - 1 or height - 1); [0, 256] */
    pft_real_t move_px;       /**< [E] speed bound of the short hold (default 0: off; read only with spread_px > 0): a frame that would take the short hold (spread_hold: compact, and with spread_exist at that existence) takes it only if the track's displacement against the scene over its last m = min(positions - 1, frames) frames is at least m * move_px; a slower track needs move_hold passes there (docs/algorithms.md 9.11 step 5); [0, 256] px per frame */
    uint32_t move_hold;       /**< the hold of such slow compact frames (default 0: hold_frames; read only with move_px > 0 and spread_px > 0): 0 or spread_hold..hold_frames */
} pft_tbd_scene_config_t;

/** A track fed to the test. */
typedef struct {
    uint32_t id;      /**< the manager's track id (not 0; distinct within one call) */
    pft_real_t x;     /**< column position, px */
    pft_real_t y;     /**< row position, px */
    bool tentative;   /**< a tentative track (sequential test running): never REPORT */
    pft_real_t pos_var; /**< the estimate's position variance xx + yy, px^2 (pft_tbd_track_t pos_cov[0] + pos_cov[2]); read only with cfg.spread_px > 0, then >= 0 (and not NaN) */
    pft_real_t p_exist; /**< the track layer's existence probability (pft_tbd_track_t p_exist); read only with cfg.spread_px > 0 and cfg.spread_exist > 0, then not NaN (any other value is taken as it is) */
} pft_tbd_scene_track_t;

/** The decision on one track. */
typedef enum {
    PFT_TBD_SCENE_HOLD = 0,    /**< not reported (yet): too few positions, the line fit failed, or tentative */
    PFT_TBD_SCENE_REPORT = 1,  /**< report the track */
    PFT_TBD_SCENE_CLUTTER = 2, /**< moves with the scene: drop it, raise the clutter map at (px, py) */
    PFT_TBD_SCENE_NO_SLOT = 3  /**< the history table is full: not tested (not reported by the host) */
} pft_tbd_scene_decision_t;

/** What the test says about one track (out[i] for tracks[i]). */
typedef struct {
    uint32_t id;                       /**< the track's id */
    pft_tbd_scene_decision_t decision; /**< see pft_tbd_scene_decision_t */
    uint32_t px;                       /**< the track's pixel: round(x) clamped to [0, width - 1] */
    uint32_t py;                       /**< round(y) clamped to [0, height - 1] */
    uint32_t positions;                /**< positions in its history after this frame (0 with NO_SLOT; at most max(frames, slow_frames) + 1) */
} pft_tbd_scene_out_t;

/** The scene-motion test's instance (declare it statically; its layout is not API). */
typedef struct pft_tbd_scene_s pft_tbd_scene_t;

/** @cond internal */
#define PFT_TBD_SCENE_SLOT_BYTES_ sizeof(pft_tbd_scene_slot_t)
#define PFT_TBD_SCENE_POS_BYTES_ sizeof(pft_tbd_scene_pos_t)
/** @endcond */

/** Workspace bytes for max_tracks slots of frames + 1 positions (the same as
 *  pft_tbd_scene_workspace_size; with cfg.slow_frames > 0 pass max(cfg.frames, cfg.slow_frames)
 *  as frames). */
#define PFT_TBD_SCENE_WORKSPACE_BYTES(max_tracks, frames)                                          \
    ((size_t)PFT_WS_ALIGN - 1u + PFT_WS_ROUND((size_t)(max_tracks) * PFT_TBD_SCENE_SLOT_BYTES_) +   \
     PFT_WS_ROUND((size_t)(max_tracks) * ((size_t)(frames) + 1u) * PFT_TBD_SCENE_POS_BYTES_))

/** Fills every field with its default (n 5, 16 slots, gate 0.15, fit 0.2, early 0.5 px,
 *  forget 64 frames, 384 x 288, hold 1 frame: no hold, spread_px 0: off, spread_hold 1,
 *  slow_frames 0: off, slow_low_px 0, slow_gate_px 0.15, spread_exist 0: off, edge_px 0: off,
 *  edge_still_px 0.1, edge_shift_px 0.2, move_px 0: off, move_hold 0: hold_frames). */
void pft_tbd_scene_config_default(pft_tbd_scene_config_t *cfg);
/** PFT_OK, PFT_ERR_INVAL (NULL) or PFT_ERR_CONFIG with *field (if field is not NULL) naming
 *  the first refused field ("frames", "max_tracks", "gate_px", "fit_px", "early_px",
 *  "forget_frames", "width", "height", "hold_frames", "spread_px", "spread_hold",
 *  "slow_frames", "slow_low_px", "slow_gate_px", "spread_exist", "edge_px", "edge_still_px",
 *  "edge_shift_px", "move_px", "move_hold"); NULL on success. */
pft_status_t pft_tbd_scene_config_check(const pft_tbd_scene_config_t *cfg, const char **field);
/** Exact workspace bytes for cfg; 0 for a NULL or refused cfg. */
size_t pft_tbd_scene_workspace_size(const pft_tbd_scene_config_t *cfg);
/** Initialises s in work[0..work_len): PFT_ERR_INVAL (NULL), PFT_ERR_CONFIG, PFT_ERR_NOMEM
 *  (then s is not written). The config is copied. */
pft_status_t pft_tbd_scene_init(pft_tbd_scene_t *s, const pft_tbd_scene_config_t *cfg, void *work,
                                size_t work_len);
/** Back to the state right after init (no history, frame 0, scene shift 0). PFT_ERR_INVAL for
 *  NULL. */
pft_status_t pft_tbd_scene_reset(pft_tbd_scene_t *s);
/**
 * One frame. tracks[0..n): the manager's tracks of this frame (n may be 0, tracks then may be
 * NULL); shift_x, shift_y: the scene's shift of this frame, Q16.16 px (pft_pre_stats_t.shift;
 * 0, 0 for a frame without detection evidence or the spatial method); out[0..n): the decisions,
 * in the order of tracks (may be NULL when n is 0). Refused, with nothing written (instance,
 * workspace and out unchanged): PFT_ERR_INVAL for a NULL s, a NULL tracks or out with n > 0,
 * an id 0, an id given twice in the list, (float build) a NaN position, with cfg.spread_px > 0
 * a negative (float build: or NaN) pos_var, or (float build) with cfg.spread_px > 0 and
 * cfg.spread_exist > 0 a NaN p_exist. n may exceed
 * max_tracks: the tracks that find no slot get NO_SLOT. Work: O(n max_tracks) to find the
 * slots, O(n frames) for the tests.
 */
pft_status_t pft_tbd_scene_update(pft_tbd_scene_t *s, const pft_tbd_scene_track_t *tracks, size_t n,
                                  int32_t shift_x, int32_t shift_y, pft_tbd_scene_out_t *out);
/** Positions held for id (0..max(frames, slow_frames) + 1; 0 for NULL or an id without history). */
uint32_t pft_tbd_scene_positions(const pft_tbd_scene_t *s, uint32_t id);
/** Whether id was found moving with the scene (false for NULL or an id without history). */
bool pft_tbd_scene_is_clutter(const pft_tbd_scene_t *s, uint32_t id);
/** Tracks given NO_SLOT since init/reset (0 for NULL). */
uint32_t pft_tbd_scene_overflows(const pft_tbd_scene_t *s);
/** Updates since init/reset (0 for NULL). */
uint32_t pft_tbd_scene_frame(const pft_tbd_scene_t *s);

#ifdef __cplusplus
}
#endif

#include "pft/internal/pft_tbd_scene_types.h"

#endif /* PFT_TBD_SCENE_H */
