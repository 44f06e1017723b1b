/**
 * @file pft_pre.h
 * @brief Infrared preprocessing: background suppression, per-tile noise whitening, a mask of
 *        dead and saturated pixels and the peaks of the result, from raw U8/U16 sensor frames
 *        to a whitened residual frame (PFT_PIX_RES16) that any tracker of the library takes.
 *
 * The stage is family-neutral (prefix pft_pre_). docs/algorithms.md section 9 gives the
 * formulas; this header states what a user sees.
 *
 * Calls, in the order of use (the library's one API pattern): pft_pre_config_default,
 * pft_pre_config_check (names the refused field), pft_pre_workspace_size (0 for a refused
 * configuration) and PFT_PRE_WORKSPACE_BYTES, pft_pre_init, pft_pre_reset, pft_pre_update (one
 * frame), then the results: pft_pre_frame (the residual as a frame descriptor), pft_pre_stats,
 * pft_pre_peaks and pft_pre_sigma (copied out).
 *
 * Per frame z (raw counts, the low bit_depth bits of each pixel):
 *  1. mask: a pixel is masked when raw >= sat_level, raw <= dead_level or its bit is set in
 *     bad_map; a masked pixel never enters an estimate and its residual is PFT_RES16_MASKED;
 *  2. background b, by method:
 *     - PFT_PRE_BG_LOCAL: mean of the unmasked pixels of the (2 local_outer + 1)^2 window
 *       minus its (2 local_guard + 1)^2 guard window; the border band of local_outer pixels,
 *       where the window would be clipped (and off-centre), is masked;
 *     - PFT_PRE_BG_TEMPORAL: a recursive background registered to the scene: the global
 *       translation of the frame against the background is estimated (integer search on row
 *       and column projections with a two-dimensional check of jumps, then Lucas-Kanade
 *       sub-pixel steps), the background is warped by it (Catmull-Rom cubic) and updated,
 *       b <- (1 - alpha) warp(b) + alpha (z - c); pixels whose scene the background has not
 *       seen (a band of 1-2 px where the scene enters) are masked. The first frame only starts
 *       the background (all masked); a constant frame is masked whole and changes nothing;
 *  3. residual r = z - b - c(x) with c a per-column offset (column fixed-pattern noise),
 *     estimated recursively from the column means of the residual (clipped at 3 sigma,
 *     high-passed across columns);
 *  4. noise: per tile of tile x tile pixels, sigma = 1.4826 median |r| from a histogram
 *     (no sorting), floored at sigma_floor, 1/sigma interpolated bilinearly between tile
 *     centres or held per tile; TEMPORAL with edge_k > 0: per pixel, the tile sigma widened
 *     by an edge term, sqrt(sigma^2 + (edge_k |grad b|)^2);
 *  5. whitened residual w = r / sigma in Q8.8 (PFT_PIX_RES16), and its peaks: 3x3 local
 *     maxima of w at or above peak_threshold, the peak_max highest kept.
 *
 * What a tracker does with it: take the frame from pft_pre_frame (same seq and timestamp as
 * the input); skip pixels equal to PFT_RES16_MASKED (pft_frame_row_to_real reads them as a
 * zero residual); treat frames flagged CONSTANT, ALL_MASKED, WARMUP or REG_LOST as carrying no
 * detection evidence; propose births at pft_pre_peaks.
 *
 * Numbers. Everything is integer arithmetic (int32/int64), so the float and q16 builds give
 * bit-identical outputs on every target; configuration fields are integers with their scale
 * in the field's comment, and reported quantities are Q16.16 integers (value * 65536) in
 * pixels or raw counts. The residual r is held with 15 - bit_depth fraction bits (none for
 * 16-bit data, where |r| saturates at 32767 counts); the temporal background with
 * 16 - bit_depth fraction bits (U8: 8).
 *
 * Memory: the caller's workspace holds the residual (2 bytes per pixel), the temporal
 * background (2 bytes per pixel, PFT_PRE_BG_TEMPORAL only) and O(width + height + tiles) of
 * line, column and tile buffers; see PFT_PRE_WORKSPACE_BYTES. With inplace set the residual
 * is written over the input frame instead (the frame buffer is the caller's, not workspace):
 *  - call pft_pre_update_inplace(pre, frame, pixels) with pixels the frame's own buffer
 *    (pixels == frame->data, writable, U16, stride_bytes == 2 width); pft_pre_update refuses
 *    such an instance (PFT_ERR_STATE);
 *  - the frame buffer is overwritten: after an accepted call it holds the whitened residual
 *    (int16 per pixel, PFT_PIX_RES16, the same values as pft_pre_update writes into the
 *    workspace) and no longer the raw frame: copy the raw frame first if it is needed later
 *    (display, another detector); pft_pre_frame then describes that buffer, which the caller
 *    must keep unchanged for as long as a tracker reads the residual;
 *  - every row is overwritten only once nothing later in the call reads its raw values (the
 *    constancy scan and the registration read the whole frame before any write; the row pass
 *    reads raw row y, LOCAL rows up to y + local_outer, before it writes row y);
 *  - a refused call (NULL, a wrong frame, pixels != frame->data, a stride other than
 *    2 width) changes nothing: instance, workspace and frame buffer stay byte for byte.
 *
 * Refused input (NULL, a frame of the wrong size, format or bit depth, a stride too small)
 * returns a status before anything changes: the instance and its workspace stay byte for byte
 * as they were. Constant, all-saturated and all-zero frames are accepted: every estimate stays
 * finite and pft_pre_stats reports them (PFT_PRE_FLAG_*).
 */
#ifndef PFT_PRE_H
#define PFT_PRE_H

#include "pft/pft_types.h"
#include "pft/pft_workspace.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Largest local_outer (window 15 x 15: counts and sums then pack into 32 bits). */
#define PFT_PRE_MAX_OUTER 7u
/** Largest tile side (a tile's histogram counts fit 16 bits). */
#define PFT_PRE_MAX_TILE 255u
/** Smallest tile side. */
#define PFT_PRE_MIN_TILE 8u
/** Largest peak_max. */
#define PFT_PRE_MAX_PEAKS 256u
/** Largest reg_search (pixels). */
#define PFT_PRE_MAX_SEARCH 32u
/** Largest reg_iters. */
#define PFT_PRE_MAX_ITERS 8u
/** Largest edge_k (1 px, Q4.12). */
#define PFT_PRE_MAX_EDGE_K 4096u
/** Smallest non-zero bg_gate (0.25 sigma, Q8.8). */
#define PFT_PRE_MIN_BG_GATE 64u
/** Largest bg_gate (16 sigma, Q8.8). */
#define PFT_PRE_MAX_BG_GATE 4096u
/** Largest bg_gate_shift. */
#define PFT_PRE_MAX_BG_GATE_SHIFT 15u
/** bg_gate_local: the tile's mean innovation of the last frame. */
#define PFT_PRE_GATE_LOCAL_MEAN 1u
/** bg_gate_local: the tile's innovation relative to the level, times the cell's level. */
#define PFT_PRE_GATE_LOCAL_RELATIVE 2u
/** bg_masked_taps: the cells of young grid columns (bg_gate_young) only. */
#define PFT_PRE_MASKED_TAPS_YOUNG 1u
/** bg_masked_taps: every observed cell. */
#define PFT_PRE_MASKED_TAPS_ALL 2u
/** Largest bg_stale_reinit (frames). */
#define PFT_PRE_MAX_BG_STALE 126u
/** Largest sigma_step. */
#define PFT_PRE_MAX_SIGMA_STEP 4u
/** Largest sigma_every. */
#define PFT_PRE_MAX_SIGMA_EVERY 8u
/** Bins of the per-tile histogram of |r| (16 exact bins, then 8 per octave up to 2^15). */
#define PFT_PRE_BINS 104u

/** Background estimate. */
typedef enum {
    PFT_PRE_BG_LOCAL = 0,   /**< spatial: local mean with a guard window (one frame, no state) */
    PFT_PRE_BG_TEMPORAL = 1 /**< recursive background registered to the drifting scene */
} pft_pre_bg_t;

/** Statistics flags (pft_pre_stats_t.flags). */
enum {
    PFT_PRE_FLAG_CONSTANT = 1u << 0,      /**< every unmasked pixel has the same raw value (or none is unmasked) */
    PFT_PRE_FLAG_ALL_SATURATED = 1u << 1, /**< every pixel is at or above sat_level */
    PFT_PRE_FLAG_ALL_DEAD = 1u << 2,      /**< every pixel is at or below dead_level (an all-zero frame with the default dead_level 0) */
    PFT_PRE_FLAG_ALL_MASKED = 1u << 3,    /**< no unmasked pixel: every residual is PFT_RES16_MASKED */
    PFT_PRE_FLAG_WARMUP = 1u << 4,        /**< temporal: the background is still converging (a running mean while it holds fewer than 1/alpha frames; the first frame is all masked) */
    PFT_PRE_FLAG_REG_WEAK = 1u << 5,      /**< temporal: too little texture for sub-pixel registration (the shift is the integer search's) */
    PFT_PRE_FLAG_REG_LOST = 1u << 6,      /**< temporal: the integer search hit its limit: the background restarted from this frame */
    PFT_PRE_FLAG_SIGMA_FLOOR = 1u << 7,   /**< at least one tile's sigma was raised to sigma_floor */
    PFT_PRE_FLAG_HELD = 1u << 8           /**< temporal: constant or all-masked frame: background and column offsets not updated */
};

/** Configuration of the stage (integers only: the float and q16 builds behave identically). */
typedef struct {
    uint16_t width;          /**< frame width, 8..PFT_CFG_MAX_IMAGE_SIDE (default 384) */
    uint16_t height;         /**< frame height, 8..PFT_CFG_MAX_IMAGE_SIDE (default 288) */
    pft_pixfmt_t format;     /**< PFT_PIX_U16 (default) or PFT_PIX_U8 */
    uint8_t bit_depth;       /**< U16: significant bits 8..16, frames must carry the same (bit_depth 0 reads as 16) (default 14); U8: 8 */
    pft_pre_bg_t method;     /**< background estimate (default PFT_PRE_BG_TEMPORAL) */
    /* mask */
    uint16_t sat_level;      /**< raw >= sat_level is saturated; 0: 2^bit_depth - 1 (default 0) */
    uint16_t dead_level;     /**< raw <= dead_level is dead, < sat_level (default 0) */
    const uint8_t *bad_map;  /**< optional bad-pixel bitmap (NULL: none): (width + 7) / 8 bytes per row, pixel x of row y is bit (x & 7) of byte y * ((width + 7) / 8) + x / 8; set = bad. Not copied: it must outlive the instance (default NULL) */
    /* local background */
    uint8_t local_outer;     /**< LOCAL: window half-width r_o, 1..PFT_PRE_MAX_OUTER (default 4: 9 x 9) */
    uint8_t local_guard;     /**< LOCAL: guard half-width r_g < r_o (default 1: 3 x 3) */
    /* temporal background */
    uint16_t bg_alpha;       /**< TEMPORAL: update weight alpha, Q0.16 (65536 = 1), 1..65535 (default 9830 = 0.15) */
    uint8_t reg_search;      /**< TEMPORAL: integer search radius around the predicted shift, 0..PFT_PRE_MAX_SEARCH px (default 8; 0: integer step off) */
    uint8_t reg_iters;       /**< TEMPORAL: Lucas-Kanade iterations, 0..PFT_PRE_MAX_ITERS (default 2; 0: integer shifts only) */
    uint8_t reg_step;        /**< TEMPORAL: registration uses every reg_step-th pixel of every reg_step-th row, 1..8 (default 2) */
    bool warp_cubic;         /**< TEMPORAL: warp the background with Catmull-Rom cubic weights (true, default) or bilinear ones (false: same cost here; kept to measure the difference, docs/algorithms.md 9.4) */
    /* column fixed-pattern noise */
    uint16_t col_alpha;      /**< update weight of the column offsets, Q0.16, 0..65535; 0 disables (default 4096 = 1/16) */
    /* noise */
    uint8_t tile;            /**< tile side, PFT_PRE_MIN_TILE..PFT_PRE_MAX_TILE (default 32) */
    bool sigma_interp;       /**< true: 1/sigma interpolated bilinearly between tile centres; false: held per tile (default true) */
    bool sigma_current;      /**< true: each frame is whitened with its own tile sigmas, in a second pass over the residual (default); false: with the last frame's, as the rows are made (one pass over memory, the same instructions; a frame with no earlier estimate uses its own) (default true) */
    uint16_t sigma_floor;    /**< smallest sigma, raw counts Q12.4 (16 = 1 count), >= 1 (default 8 = 0.5 count) */
    uint16_t edge_k;         /**< TEMPORAL: edge term of the noise, px Q4.12 (4096 = 1 px), 0..4096; 0 disables (default 0). A pixel's sigma becomes sqrt(sigma_tile^2 + (edge_k |grad b|)^2), |grad b| the background's gradient there (counts per px): the residual that a registration and warp error of about edge_k px leaves on a cloud edge is scored in its own sigma (docs/algorithms.md 9.6). Must be 0 with PFT_PRE_BG_LOCAL */
    /* peaks */
    uint16_t peak_max;       /**< peaks kept per frame, 0..PFT_PRE_MAX_PEAKS; 0: no peak search (default 64) */
    int16_t peak_threshold;  /**< smallest whitened value of a peak, Q8.8 sigma units, >= 1 (default 768 = 3 sigma) */
    /* memory */
    bool inplace;            /**< U16 only: the residual is written over the caller's frame buffer by pft_pre_update_inplace (pft_pre_update is then refused) and the workspace holds no residual (PFT_PRE_WORKSPACE_BYTES_INPLACE: 2 bytes per pixel less); the same values as without it. Must be false with PFT_PIX_U8 (default false) */
    /* cost levers (docs/algorithms.md 9.5, docs/tuning.md "pre") */
    uint8_t sigma_step;      /**< the tile sigmas' histograms take every sigma_step-th pixel of every sigma_step-th row (columns and rows that are multiples of it), 0..PFT_PRE_MAX_SIGMA_STEP, 0 and 1: every pixel; tile must be at least 8 sigma_step. A tile's sigma then rests on 1/sigma_step^2 of its pixels (its standard error sigma_step times larger); the masked-pixel counts and the column offsets still see every pixel (default 1) */
    uint8_t sigma_every;     /**< the tile sigmas of tile row j are estimated on the frames n (counted from init or reset) with (n + j) % sigma_every == 0, and kept from the last estimate on the others, 0..PFT_PRE_MAX_SIGMA_EVERY, 0 and 1: every frame; every tile row is estimated until the first estimate exists. A tile's sigma is then up to sigma_every - 1 frames old; the masked-pixel counts and the column offsets still see every frame (default 1) */
    bool reg_bin;            /**< TEMPORAL: the Lucas-Kanade sums of the registration take 2 x 2 boxes of pixels (their sums) at the samples of reg_step, which must then be at least 2, instead of single pixels: a box sum has 4 times the gradient and twice the noise of a pixel, 4 times the information per sample where the noise sets the shift error. A cost lever with reg_step 4 (about 1.1 M instructions less per 384 x 288 frame than the defaults, the shift error of the defaults on smooth scenes, 1.4-1.7 times it on the real frames of docs/results/ir_clutter.md) and a precision lever with reg_step 2 (default false) */
    bool sigma_bracket;      /**< once a sigma is known, each tile's sigma comes from the counts of its |r| below 5 thresholds around the median of its last sigma (m / 2, m / sqrt 2, m, sqrt 2 m, 2 m), interpolated linearly between the two around the median, instead of a histogram of 104 bins (a cost lever: about 0.14 M instructions less per 384 x 288 frame, docs/results/ir_clutter.md "Branch ircost9"); a median outside m / 2 .. 2 m is read on the straight line from 0 through the nearest threshold's count, so the estimate falls at most 4 times a frame and reads a Gaussian's rise within 7 % up to 5 times (larger jumps followed over the next frames). Must be used with sigma_step and sigma_every at most 1 (default false) */
    bool bg_anchor;          /**< TEMPORAL: the background is kept on a grid of the scene, (width + 3) x (height + 3) cells anchored at the integer part of the accumulated scene position, instead of being re-warped into each frame's coordinates (docs/algorithms.md 9.12 [E]): each frame reads it once (Catmull-Rom at the position's fraction) for the residual and is interpolated once into it (at the inverse fraction) for the update, alpha and the warm-up as without it; a whole-pixel move of the anchor moves the stored cells by whole cells (exact), the cells that enter restart from the frame and the residual that reads them is masked. The registration estimates the step as without it, against the grid read at the last frame's position (written into the residual buffer before the residual). Changes values. Needs PFT_PRE_BG_TEMPORAL, inplace false and edge_k 0; workspace PFT_PRE_WORKSPACE_BYTES_ANCHOR (default false: the background re-warped at every frame, today's values) */
    uint16_t bg_gate;        /**< TEMPORAL with bg_anchor: the gate g of the background's update, Q8.8 sigma units (256 = 1 sigma), 0 or 64..4096 (docs/algorithms.md 9.13 [E]). A cell whose innovation e = z - B (the frame interpolated into the grid less the grid) exceeds g sigma in magnitude, sigma the last estimate of the tile of the cell's nearest pixel (no gate while that tile has none), is updated with e clipped to +-g sigma (bg_gate_shift 0) or with the weight alpha / 2^bg_gate_shift; the others as without it. A point that stays on the same few scene pixels (a target slow against the scene) then enters the background more slowly; a change of the scene of D sigma is still learnt: linearly at alpha g sigma per frame until it is within g sigma (clip), or with the time constant 2^bg_gate_shift / alpha frames (weight). Changes values; no workspace. Needs bg_anchor (default 0: off, today's values) */
    uint8_t bg_gate_shift;   /**< with bg_gate: 0 clips the innovation of a cell beyond the gate to +-bg_gate sigmas (default); 1..15 leaves it unclipped and updates such a cell with the weight alpha / 2^bg_gate_shift instead (a change of the scene beyond the gate is then learnt with the time constant 2^bg_gate_shift / alpha frames until it is within the gate) (default 0) */
    uint8_t bg_gate_young;   /**< with bg_gate: the grid cells that entered the scene in the last bg_gate_young frames (a grid column or row that the frame covers for the first time, counted per column and per row) are updated without the gate, 0..255 (docs/algorithms.md 9.13 [E]). Such a cell starts from one frame, noise included; gated, it would shed that error at only alpha g sigma per frame, and the strip of young cells along the frame edge where the scene enters would hold a residual of larger spread than the rest (false tracks fixed to that edge); ungated for N frames it converges at the rate alpha as without the gate. Workspace PFT_PRE_WORKSPACE_BYTES_ANCHOR_YOUNG (the ages, one byte per grid column and row). Changes values. Needs bg_gate (default 0: every cell gated, today's values) */
    uint8_t bg_gate_local;   /**< with bg_gate: the gate applied to the innovation less its local smooth part (docs/algorithms.md 9.13 [E]), so that a level change shared by a tile (sensor-fixed shading under a drifting scene, a global drift) is learnt at the full alpha while a point is still gated. 0: off (default, today's values); PFT_PRE_GATE_LOCAL_MEAN: m is the mean innovation of the cell's tile (the tile of its nearest pixel) in the last frame's update; PFT_PRE_GATE_LOCAL_RELATIVE: m = rho B, rho = (sum of e) / (sum of B) over that tile in the last frame's update (a gain fixed to the sensor changes each cell's level in proportion to it). The cell is updated with alpha m plus the gate's update of e - m (clip or weight, bg_gate_shift); a tile with no update in the last frame has m = 0. Changes values; workspace PFT_PRE_WORKSPACE_BYTES_ANCHOR_LOCAL (24 bytes per tile more, rounded). Needs bg_gate (default 0) */
    uint8_t bg_masked_taps;  /**< TEMPORAL with bg_anchor: what the background's update does with a grid cell one of whose horizontal update taps (the frame pixels it is interpolated from along x) is masked (docs/algorithms.md 9.13 [E]). 0: the cell is kept, not updated, on that frame (default, today's values); PFT_PRE_MASKED_TAPS_YOUNG: in the young grid columns (bg_gate_young; needs it) the frame is interpolated into the cell from the valid taps of its row with their weights renormalised to sum to 1, when those weights sum to at least 1/2 (else kept); PFT_PRE_MASKED_TAPS_ALL: the same for every observed cell. A cell that enters the scene next to a masked pixel fixed to the sensor is otherwise kept at its first value for most of its young frames (about 4 px of drift), and the residual there carries that value's error and the shading it missed (false tracks fixed to the frame). Changes values; no workspace */
    uint8_t bg_stale_reinit; /**< TEMPORAL: a background value that has not been learnt for more than bg_stale_reinit frames (or never) because its pixel was masked restarts from the first valid frame value it meets, and the residual of a pixel that reads it (any interpolation tap of non-zero weight) is masked on that frame, as at the frame border's entering edge (docs/algorithms.md 9.14 [E]); 0..PFT_PRE_MAX_BG_STALE. Without it, the part of the scene that comes out from under a masked block fixed to the sensor (a cluster of dead or saturated pixels, a glint, a saturated part of the airframe) meets a background kept from before it went under, or never learnt, and the residual beside the block's trailing edge holds the difference (tens of sigma on a gradient). Each background value carries its age (frames since learnt, 127: never): without bg_anchor the age is carried with the scene by the warp's bilinear weights, with bg_anchor it is kept per grid cell and moves with the anchor. A value never learnt (masked on the first frame) starts at its distance in pixels to the pixel the first frame filled it from. A single dead pixel in a scene drifting v px per frame keeps an age of about 1/v frames without bg_anchor (its neighbours' values drift over it) and about 4/v with it (a grid cell is kept while any of its 4 x 4 update taps is masked): N below that restarts cells around it too. Workspace PFT_PRE_STALE_BYTES more. Changes values. Needs PFT_PRE_BG_TEMPORAL (default 0: off, today's values) */
    uint16_t bg_young_clip;  /**< with bg_gate_young: the young cells' update clipped to +-bg_young_clip sigma (the form of bg_gate_shift, sigma that of the cell's tile as for bg_gate) instead of no gate, Q8.8 sigma units, 0 or 64..4096 (docs/algorithms.md 9.13 [E]). A point that enters the frame with the scene at the edge where the drift brings it in, slow against the scene, crosses young cells, which without it learn the point at the rate alpha; with it at most alpha bg_young_clip sigma per frame, while a new cell's one-frame noise (about 1 sigma) is still shed at nearly the rate alpha when bg_young_clip is about 1. A cell still starts from the frame value it enters with. Changes values; no workspace. Needs bg_gate_young (default 0: young cells ungated, today's values) */
    bool sigma_level;        /**< false (default): each tile's sigma is 1.4826 times the median of |r| (a MAD about zero, docs/algorithms.md 9.6), today's values; true: 1.4826 times the median of |r - c|, c the tile's level, the mean of its residual clipped at 3 sigma over every 4th row (the rows of the column sums) in the last frame that estimated the tile (0 until then), so that a slow offset shared by the tile (the shading's lag term that pft_pre_flat removes after the stage, docs/algorithms.md 9.10) does not inflate the sigma the residual is whitened with (docs/algorithms.md 9.6 [E]). The residual itself is not changed. Changes values; workspace PFT_PRE_LEVEL_BYTES more. Needs sigma_step 1, sigma_every 1 and sigma_bracket false */
    uint8_t bg_edge_narrow;  /**< TEMPORAL with bg_anchor: the entering band of the anchored background narrowed (docs/algorithms.md 9.12 [E]). 0: off (default, today's values): a pixel is read through the 4 Catmull-Rom taps of cells that must each be held, and a cell is updated only when its 4 update taps are in the frame, so the band at the edge where the drift brings the scene in is masked about 3 px wide (4 on a frame where the anchor moves). 1: a pixel whose cubic read taps reach a cell not held, but whose 3 taps without the missing end (nodes -1, 0, 1 at the high end, 0, 1, 2 at the low end) do not, is read along that axis with the 3-tap Lagrange (quadratic) weights; a cell whose cubic update taps leave the frame but whose 3 taps of that end do not is updated from the frame interpolated with those weights (and then held), with the gate, bg_gate_young's and bg_stale_reinit's ages as any cell; the band is 1-2 px. Only the pixels and cells at the ends of the held ranges take this path. Changes values; no workspace; values other than 0 and 1 refused */
    bool bg_young_scale;     /**< with bg_gate_young: the residual of a pixel that reads young grid cells divided by sqrt(1 + (1 - alpha)^(2a + 1)), a the cells' age (the frames their column or row has held the scene before this frame, bg_gate_young's ages), so that its spread is that of a pixel on old cells (docs/algorithms.md 9.13 [E]). A cell that entered the scene a frames ago and was updated without a gate since holds, under white noise of sd sigma, an error of variance sigma^2 (v + (1 - v)(1 - alpha)^(2a)), v = alpha / (2 - alpha) the variance of an old cell; the residual z - B then has the variance sigma^2 (1 + v)(1 + (1 - alpha)^(2a + 1)) against sigma^2 (1 + v) on old cells. Per pixel the excess (1 - alpha)^(2a + 1) is the mean of its 4 read taps' per axis, weighted by the squares of the read weights, and the larger of the column's and the row's is taken (a cell's age is the younger of its column's and row's); ages from 64 on, and an excess of 2/65536 or less (from age 34 at alpha 0.15), count as old; with bg_gate the interior's cells are gated and old cells hold somewhat less error than v (the scale is then slightly short of it at a = 0). Changes values; no workspace (a table of 129 values in the instance). Needs bg_gate_young (default false: the residual is not scaled, today's values) */
} pft_pre_config_t;

/** One peak of the whitened residual: a 3x3 local maximum at or above peak_threshold. */
typedef struct {
    uint16_t x;    /**< column (pixel centre at x) */
    uint16_t y;    /**< row */
    int16_t value; /**< whitened residual, Q8.8 sigma units */
} pft_pre_peak_t;

/** Statistics of the last accepted frame (copied out by pft_pre_stats). */
typedef struct {
    uint64_t timestamp_us;  /**< of the input frame */
    uint32_t seq;           /**< of the input frame */
    uint32_t frames;        /**< frames accepted since init or reset */
    uint32_t flags;         /**< PFT_PRE_FLAG_* */
    uint32_t n_masked;      /**< residual pixels set to PFT_RES16_MASKED */
    uint32_t n_saturated;   /**< pixels at or above sat_level */
    uint32_t n_dead;        /**< pixels at or below dead_level */
    uint32_t n_bad;         /**< pixels set in bad_map (and neither saturated nor dead) */
    int32_t shift[2];       /**< TEMPORAL: translation of the scene since the last frame, x and y, Q16.16 px: z(p) = b(p - shift) */
    int32_t shift_sd[2];    /**< TEMPORAL: predicted standard deviation of shift (fit residual and normal matrix), Q16.16 px; 0 when not estimated */
    int32_t shift_coarse[2];/**< TEMPORAL: the integer search's shift, px */
    uint32_t reg_rms;       /**< TEMPORAL: RMS of z - warp(b) over the unmasked pixels after registration, Q16.16 counts */
    uint32_t sigma_min;     /**< smallest tile sigma, Q16.16 counts */
    uint32_t sigma_mean;    /**< mean tile sigma, Q16.16 counts */
    uint32_t sigma_max;     /**< largest tile sigma, Q16.16 counts */
    uint32_t n_peaks;       /**< peaks kept (<= peak_max) */
    uint32_t n_candidates;  /**< local maxima at or above peak_threshold (before keeping peak_max) */
} pft_pre_stats_t;

/** Instance (layout in pft/internal/pft_pre_types.h, not API). */
typedef struct pft_pre_s pft_pre_t;

/** Fills every field with its default (384 x 288 U16 14-bit frames, temporal background). */
void pft_pre_config_default(pft_pre_config_t *cfg);
/**
 * PFT_OK if cfg is usable; PFT_ERR_INVAL for NULL; PFT_ERR_CONFIG for a refused value, and
 * then *field (when field is not NULL) names the first offending field as written in the
 * struct ("width", "local_guard", ...). *field is NULL on success.
 */
pft_status_t pft_pre_config_check(const pft_pre_config_t *cfg, const char **field);

/** Largest blur of the clutter map. */
#define PFT_PRE_CLUTTER_MAX_BLUR 4u
/** Largest persistence (frames) of the clutter map's gate. */
#define PFT_PRE_CLUTTER_MAX_PERSIST 32u

/** Configuration of the clutter map (integers only). */
typedef struct {
    uint16_t width;   /**< frame width, 8..PFT_CFG_MAX_IMAGE_SIDE (default 384) */
    uint16_t height;  /**< frame height, 8..PFT_CFG_MAX_IMAGE_SIDE (default 288) */
    uint16_t alpha;   /**< update weight a, Q0.16, 1..65535 (default 6554 = 0.1) */
    uint8_t blur;     /**< half-size of the square the map is read over, 0..PFT_PRE_CLUTTER_MAX_BLUR (0: the pixel) (default 1: 3 x 3) */
    bool box;         /**< read the map as its mean over the square (true, default) or its largest value (false) */
    bool mean;        /**< subtract the running mean of the residual too (default false) */
    uint16_t thr;     /**< map value above which a pixel is clutter, sigma^2 Q6.10 (1024 = 1), 1024..65535 (default 2048 = 2) */
    uint16_t veto;    /**< map value above which the output is 0 (no births, no evidence there), sigma^2 Q6.10; 0 (default) off, else thr..65535 */
    uint8_t persist;  /**< persistence gate of the running mean (needs mean): a residual beyond +-excess updates the mean only once such residuals have held at the same scene position for this many frames, so that a target moving across the scene is not learnt; 0 (default) off, else 1..PFT_PRE_CLUTTER_MAX_PERSIST */
    uint16_t excess;  /**< level of the persistence gate, Q8.8 sigma (256 = 1), 1..32767 (default 384 = 1.5); read only with persist */
    bool inplace;     /**< the output is written over the caller's residual buffer by pft_pre_clutter_update_inplace (pft_pre_clutter_update is then refused) and the workspace holds no output (PFT_PRE_CLUTTER_WORKSPACE_BYTES_INPLACE: 2 bytes per pixel less); the same values as without it (default false) */
    uint8_t block;    /**< side B of the blocks of the scene the map (m, mu, the counter) is held on, px: 0 (default: per pixel, the map of docs/algorithms.md 9.9 as before), 2 or 4: each pixel is scored with its block's map read over (2 blur + 1)^2 blocks, each block updated with the means of its unmasked pixels' terms (see "Blocks" below); the map's memory is divided by B^2. Changes values */
    bool map8;        /**< the map m held in 8 bits per pixel instead of 16: a code of sigma^2 with 3 exponent and 5 mantissa bits (value (32 + f) 2^(e + 3) in Q6.10 for code 32 e + f, e >= 1; code * 16 below 64), 1/64 relative precision from 0.5 sigma^2 up to 63 sigma^2, 1/64 sigma^2 absolute below; the map is decoded to Q6.10 to be read, warped and updated, and the update's result is stored with a deterministic dither so that its expected value is kept (see "8-bit map" below). Per pixel only (block must be 0). 1 byte per pixel less (PFT_PRE_CLUTTER_WORKSPACE_BYTES_MAP8). Changes values (default false: 16 bits, today's values) */
    bool anchor;      /**< the map (m, mu, the counter) held on an integer grid of the scene instead of carried by a bilinear warp every frame: the instance sums the shifts it is given (Q16.16, exactly, on every accepted update, with or without evidence) and each pixel of a frame reads and updates the cell under its position rounded to the nearest grid point; when the rounded position moves by whole pixels the stored arrays move by whole pixels (exact copies), the cells that enter holding a new pixel's values (m 1 sigma^2, mu 0, counter 0); no interpolation, so a cell's statistics are those of scene points up to 0.5 px from the pixel (see "Anchored map" below; docs/algorithms.md 9.9). Per pixel only (block must be 0); works with mean, mean_floor, persist, veto, inplace and map8. Same workspace. Changes values (default false: the bilinear carry, today's values) */
    uint16_t mean_floor; /**< with mean: the running mean is subtracted only where its magnitude (rounded to Q8.8) exceeds this, Q8.8 sigma (256 = 1), 0..2048; elsewhere c = r. A target's flanks (within excess, learnt at alpha every frame) and the mean's own noise leave |mu| mostly a few tenths of a sigma, while clutter that the mean is for holds it at a sigma or more: the floor keeps the first off the target and still subtracts the second (docs/algorithms.md 9.9 [E]). Per pixel only (block must be 0). Changes values (default 0: off, today's values) */
    uint8_t floor_age;   /**< with mean_floor: the floor applies only to cells whose map has learnt for at least this many frames with evidence (0..255); a younger cell takes its mean off as without the floor (c = r - mu). A cell's age is the smaller of its column's and its row's: every column and row starts at 0 at init/reset, adds 1 with each update with evidence (capped at floor_age), and moves with the map (the carry's two sources per axis: the younger one; the anchored move: whole pixels), the columns and rows that enter starting at 0. The floor's extra false tracks come where the map is young (the first frames, the entering border): there the mean has not yet reached the floor while clutter builds it, and the plain subtraction takes off what it has learnt (docs/algorithms.md 9.9 [E]). Per pixel only (block must be 0). PFT_PRE_CLUTTER_WORKSPACE_BYTES_AGE(w, h) more workspace. Changes values (default 0: off, today's values) */
} pft_pre_clutter_config_t;

/** Clutter map instance (layout in pft/internal/pft_pre_types.h, not API). */
typedef struct pft_pre_clutter_s pft_pre_clutter_t;

/* Flat-field offset correction (pft_pre_flat_*, described with its calls below). */

/** Smallest block side of the flat-field correction (px). */
#define PFT_PRE_FLAT_MIN_BLOCK 4u
/** Largest block side of the flat-field correction (px). */
#define PFT_PRE_FLAT_MAX_BLOCK 64u

/** Configuration of the flat-field offset correction (integers only). */
typedef struct {
    uint16_t width;   /**< frame width, 8..PFT_CFG_MAX_IMAGE_SIDE (default 384) */
    uint16_t height;  /**< frame height, 8..PFT_CFG_MAX_IMAGE_SIDE (default 288) */
    uint8_t block;    /**< block side, px, a power of two PFT_PRE_FLAT_MIN_BLOCK..PFT_PRE_FLAT_MAX_BLOCK (default 16) */
    uint16_t alpha;   /**< update weight a of the block means, Q0.16, 1..65535 (default 3277 = 0.05) */
    uint16_t gate;    /**< a pixel enters its block's mean only when |r - m| <= gate, Q8.8 sigma (256 = 1), 1..32767 (default 512 = 2) */
    bool relative;    /**< false (default): the map is an offset (sigma); true: the offset is proportional to the level of the pixel in a level frame given to each update (e.g. the raw frame): m is sigma per count and the pixel's offset m(x, y) l(x, y), the form of the residual that a sensor-fixed gain leaves under a drifting scene (docs/algorithms.md 9.10) */
    bool rescale;     /**< false (default): the corrected residual is written as it is; true: per block a running robust sd s of the corrected residual (its median |v| over 0.6745, followed with the map's weight a), and the output is v / s, the multiplier 1/s interpolated bilinearly between the block centres like the map: the stage's tile sigma, a MAD about zero taken before this step, is inflated by the offset this step removes (docs/algorithms.md 9.10 [E]); workspace PFT_PRE_FLAT_WORKSPACE_BYTES_RESCALE */
} pft_pre_flat_config_t;

/** Flat-field correction instance (layout in pft/internal/pft_pre_types.h, not API). */
typedef struct pft_pre_flat_s pft_pre_flat_t;

#ifdef __cplusplus
}
#endif

/* Layout of the instance, for sizeof and the workspace macro (not API). */
#include "pft/internal/pft_pre_types.h"

#ifdef __cplusplus
extern "C" {
#endif

/**
 * Workspace bytes for frames w x h, method m (pft_pre_bg_t), local_outer ro, tile side t and
 * peak_max k: the residual (2 w h), the temporal background (2 w h, TEMPORAL only), and
 * O(w + h + tiles): column offsets and sums, tile histograms of one tile row, tile sigmas,
 * LOCAL packed-row ring and column sums, TEMPORAL projections and a packed row, the peaks.
 */
#define PFT_PRE_WORKSPACE_BYTES(w, h, m, ro, t, k)                                              \
    ((size_t)(PFT_WS_ALIGN - 1u) + PFT_WS_ROUND((size_t)(w) * (size_t)(h) * 2u) +               \
     ((m) == PFT_PRE_BG_TEMPORAL ? PFT_WS_ROUND((size_t)(w) * (size_t)(h) * 2u) : 0u) +         \
     4u * PFT_WS_ROUND((size_t)(w) * 4u) +                                                      \
     PFT_WS_ROUND(PFT_PRE_NT_(w, t) * (PFT_PRE_BINS + 1u) * 2u) +                               \
     2u * PFT_WS_ROUND(PFT_PRE_NT_(w, t) * PFT_PRE_NT_(h, t) * 4u) +                           \
     PFT_WS_ROUND(PFT_PRE_NT_(w, t) * 4u) +                                                     \
     ((m) == PFT_PRE_BG_TEMPORAL                                                                \
          ? 4u * PFT_WS_ROUND((size_t)(w) * 4u) + PFT_WS_ROUND((size_t)(w) * 2u) +              \
                2u * PFT_WS_ROUND((size_t)(h) * 4u)                                              \
          : 2u * PFT_WS_ROUND(((size_t)(w) + 2u * (size_t)(ro) + 2u) * 4u) +                    \
                PFT_WS_ROUND((2u * (size_t)(ro) + 2u) * (size_t)(w) * 4u)) +                    \
     PFT_WS_ROUND((size_t)(k) * sizeof(pft_pre_peak_t)))

/** Workspace bytes with inplace set: PFT_PRE_WORKSPACE_BYTES without the residual (2 w h). */
#define PFT_PRE_WORKSPACE_BYTES_INPLACE(w, h, m, ro, t, k)                                      \
    (PFT_PRE_WORKSPACE_BYTES(w, h, m, ro, t, k) - PFT_WS_ROUND((size_t)(w) * (size_t)(h) * 2u))

/** Workspace bytes with bg_anchor set (TEMPORAL, not inplace): PFT_PRE_WORKSPACE_BYTES with the
 *  background on (w + 3) x (h + 3) cells instead of w x h, plus 4 rows of (w + 3) int32 (the
 *  frame's rows interpolated along x, for the update). */
#define PFT_PRE_WORKSPACE_BYTES_ANCHOR(w, h, ro, t, k)                                           \
    (PFT_PRE_WORKSPACE_BYTES(w, h, PFT_PRE_BG_TEMPORAL, ro, t, k) -                             \
     PFT_WS_ROUND((size_t)(w) * (size_t)(h) * 2u) +                                             \
     PFT_WS_ROUND(((size_t)(w) + 3u) * ((size_t)(h) + 3u) * 2u) +                               \
     PFT_WS_ROUND(4u * ((size_t)(w) + 3u) * 4u))

/** The bytes that bg_gate_young adds to the anchored workspace: the ages of the grid's (w + 3)
 *  columns and (h + 3) rows, one byte each. */
#define PFT_PRE_YOUNG_BYTES(w, h) PFT_WS_ROUND((size_t)(w) + (size_t)(h) + 6u)
/** The bytes that bg_gate_local adds to the anchored workspace: 24 bytes per tile (each tile's
 *  sums of the innovation and of the level, its m and its count; three buffers, each rounded to
 *  PFT_WS_ALIGN). */
#define PFT_PRE_LOCAL_BYTES(w, h, t)                                                            \
    (PFT_WS_ROUND(PFT_PRE_NT_(w, t) * PFT_PRE_NT_(h, t) * 16u) +                                \
     2u * PFT_WS_ROUND(PFT_PRE_NT_(w, t) * PFT_PRE_NT_(h, t) * 4u))
/** The bytes that bg_stale_reinit adds to the workspace (with or without bg_anchor): the age of
 *  every background value, one byte per grid cell ((w + 3) x (h + 3); w x h of them without
 *  bg_anchor), the largest age of each row (h + 3 bytes) and a scratch of 2 (w + 3) + h + 3
 *  bytes. */
#define PFT_PRE_STALE_BYTES(w, h)                                                               \
    (PFT_WS_ROUND(((size_t)(w) + 3u) * ((size_t)(h) + 3u)) +                                    \
     PFT_WS_ROUND(2u * ((size_t)(w) + 3u) + (size_t)(h) + 3u) + PFT_WS_ROUND((size_t)(h) + 3u))
/** The bytes that sigma_level adds to the workspace (with or without bg_anchor): each tile's
 *  level (4 bytes per tile) and the sums and counts of one tile row (8 bytes per tile column). */
#define PFT_PRE_LEVEL_BYTES(w, h, t)                                                            \
    (PFT_WS_ROUND(PFT_PRE_NT_(w, t) * PFT_PRE_NT_(h, t) * 4u) +                                 \
     PFT_WS_ROUND(PFT_PRE_NT_(w, t) * 8u))
/** Workspace bytes with bg_anchor and bg_gate_young set (bg_gate_local off). With both options
 *  the workspace is PFT_PRE_WORKSPACE_BYTES_ANCHOR + PFT_PRE_YOUNG_BYTES + PFT_PRE_LOCAL_BYTES. */
#define PFT_PRE_WORKSPACE_BYTES_ANCHOR_YOUNG(w, h, ro, t, k)                                     \
    (PFT_PRE_WORKSPACE_BYTES_ANCHOR(w, h, ro, t, k) + PFT_PRE_YOUNG_BYTES(w, h))
/** Workspace bytes with bg_anchor and bg_gate_local set (bg_gate_young off). */
#define PFT_PRE_WORKSPACE_BYTES_ANCHOR_LOCAL(w, h, ro, t, k)                                     \
    (PFT_PRE_WORKSPACE_BYTES_ANCHOR(w, h, ro, t, k) + PFT_PRE_LOCAL_BYTES(w, h, t))

/** Exact workspace bytes for cfg; 0 for a NULL or refused cfg. */
size_t pft_pre_workspace_size(const pft_pre_config_t *cfg);
/**
 * Initialises pre in work[0..work_len): PFT_ERR_INVAL (NULL), PFT_ERR_CONFIG (refused cfg),
 * PFT_ERR_NOMEM (work too short). The configuration is copied (sat_level 0 resolved); the
 * bad_map it points to is not.
 */
pft_status_t pft_pre_init(pft_pre_t *pre, const pft_pre_config_t *cfg, void *work,
                          size_t work_len);
/** Back to the state right after init: background, column offsets and tile sigmas forgotten. */
pft_status_t pft_pre_reset(pft_pre_t *pre);
/**
 * Processes one raw frame (format, size and bit depth of the configuration). PFT_ERR_INVAL for
 * NULL, PFT_ERR_FORMAT for a wrong frame: nothing changes. Work per frame is bounded by the
 * frame size (a few passes over the pixels; docs/results/ir_clutter.md gives the measured
 * instructions per pixel) plus (2 reg_search + 1)(w + h) for the integer search.
 */
pft_status_t pft_pre_update(pft_pre_t *pre, const pft_frame_t *frame);
/**
 * pft_pre_update for an instance configured with inplace: the whitened residual is written
 * over the frame's own pixels (see "Memory" above for the rules). pixels must be frame->data
 * (the same buffer, writable) and the frame U16 with stride_bytes == 2 width. PFT_ERR_INVAL
 * for NULL or pixels != frame->data, PFT_ERR_STATE for an instance without inplace,
 * PFT_ERR_FORMAT for a wrong frame or stride: nothing changes, the frame buffer included.
 */
pft_status_t pft_pre_update_inplace(pft_pre_t *pre, const pft_frame_t *frame, uint16_t *pixels);
/**
 * The whitened residual of the last update as a frame: PFT_PIX_RES16, the configured size,
 * the input frame's seq and timestamp_us. The descriptor lends the instance's residual buffer
 * (the one exception to copying results out, so that no frame-sized copy is needed): read-only,
 * valid until the next pft_pre_update, pft_pre_reset or pft_pre_init of this instance. With
 * inplace it describes the caller's frame buffer of the last pft_pre_update_inplace (valid
 * while the caller keeps that buffer unchanged, and until the next reset or init).
 * PFT_ERR_INVAL for NULL, PFT_ERR_STATE before the first update.
 */
pft_status_t pft_pre_frame(const pft_pre_t *pre, pft_frame_t *out);
/** Statistics of the last update (all zero before the first). PFT_ERR_INVAL for NULL. */
pft_status_t pft_pre_stats(const pft_pre_t *pre, pft_pre_stats_t *out);
/**
 * Peaks of the last update, highest first (equal values in raster order): copies at most max
 * into out and returns how many there are (out may be NULL with max 0; 0 for NULL pre).
 */
size_t pft_pre_peaks(const pft_pre_t *pre, pft_pre_peak_t *out, size_t max);
/**
 * Noise sigma of every tile after the last update, Q16.16 raw counts, row-major (tiles_x per
 * row): copies at most max values and returns the number of tiles (0 for NULL pre). The
 * number of tiles per row is (width + tile - 1) / tile.
 */
size_t pft_pre_sigma(const pft_pre_t *pre, uint32_t *out, size_t max);


/*
 * Clutter map (pft_pre_clutter_*): a second, optional step after the stage, on its whitened
 * residual (docs/algorithms.md 9.9). Per pixel of the scene it holds the running mean square
 * m of the whitened residual (and, with mean, its running mean mu), carried along with the
 * scene every frame by the stage's measured shift (bilinear, pixels entering the frame start
 * at m = 1, mu = 0). Per frame, with M the mean (box) or the largest value (not box) of m over
 * the (2 blur + 1)^2 square around the pixel (edges replicated), read before this frame's
 * update:
 *   c = r - mu (mean) or r;  w = c / sqrt(M) where M > thr, else c;  w = 0 where M > veto
 *   (veto not 0);
 *   m <- m + a (min(c^2, 64) - m);  mu <- mu + a (clamp(r, -8, 8) - mu);
 * a = max(alpha, 1 / n) after n frames (a running mean at the start). With mean and
 * persist = k > 0 a counter p per pixel of the scene (frames, Q8, carried along with the scene
 * like m, 0 where pixels enter) counts how long residuals beyond the gate's level have held
 * there:
 *   p <- min(p + 1, 2 k) where |r| > excess, else max(p - 1/2, 0);
 * the mean takes the frame's residual only where |r| <= excess or p >= k after this frame, and
 * keeps its value elsewhere (the map m is updated as above): a target that moves across the
 * scene leaves its counter behind and its mean is not learnt; clutter that stays put is, k
 * frames later. A cloud edge, the
 * horizon or a structure that the background keeps missing at the same scene position is then
 * scored in its own sigma after a few frames, while a target moving across the scene meets a
 * map it has not raised. A frame without detection evidence (update's evidence false) leaves
 * the map as it is and gives an all-masked output. Integer arithmetic only: the float and q16
 * builds give the same bits (m in Q6.10 sigma^2, mu in Q4.11 sigma, output Q8.8 sigma).
 * Memory: the map (2 bytes per pixel), the output (2), mu (2, with mean only), the counter
 * (2, with persist only), blur + 1 rows of the map and two rows of sums (4 bytes per pixel
 * each); see PFT_PRE_CLUTTER_WORKSPACE_BYTES. With inplace the output is written over the
 * caller's residual (pft_pre_clutter_update_inplace; PFT_PRE_CLUTTER_WORKSPACE_BYTES_INPLACE,
 * no output buffer): each residual row is read before its output is written and never after,
 * so the values are those of pft_pre_clutter_update; the caller's residual is gone afterwards
 * (e.g. the stage's residual written over the frame buffer with pft_pre_update_inplace, when
 * nothing reads it after the map). Refused input changes nothing.
 * Blocks (block = B, 2 or 4): the map is held on the grid of B x B blocks of the frame
 * (ceil(w / B) x ceil(h / B), the last blocks cut at the frame's edge) and carried by the
 * shift / B in grid steps (bilinear); the square of the read is (2 blur + 1)^2 blocks around
 * the pixel's block, M the same for every pixel of a block; per block, with n its unmasked
 * pixels this frame (a block with n = 0 keeps its values):
 *   m <- m + a (mean over the n pixels of min(c^2, 64) - m);
 *   mu <- mu + a (mean of clamp(r, -8, 8) - mu);  c = r - mu of the pixel's block;
 *   p <- min(p + 1, 2 k) where |mean of r| > excess, else max(p - 1/2, 0) (the gate reads the
 *   block's mean residual; the mean learns where it is <= excess or p >= k).
 * The map, mu and the counter take 2 / B^2 bytes per pixel each; the output (without inplace)
 * stays 2 bytes per pixel; pft_pre_clutter_raise raises the blocks that hold the 3 x 3
 * pixels, pft_pre_clutter_at reads the pixel's block. See
 * PFT_PRE_CLUTTER_WORKSPACE_BYTES_BLOCK.
 * 8-bit map (map8, per pixel only): m is stored as an 8-bit code c of its Q6.10 value v:
 * c = v / 16 (rounded) below v = 1024 (1 sigma^2), else 32 (e - 1) + v / 2^(e + 3) (rounded)
 * with e = 2..7 the octave of v (2^(e + 8) <= v < 2^(e + 9)), decoded as c * 16 (c < 64) or
 * (32 + c mod 32) 2^(c / 32 + 3); code 255 (63 sigma^2) is the largest. Every code decodes to
 * a value that encodes back to itself, and the decoded value of a rounded code is within
 * max(8, v / 64) of v. The map is decoded row by row to be read, warped and updated with the
 * formulas above; the warp's result is rounded to its nearest code's value (the warp runs row
 * by row within the update: one decode and one encode per pixel), the update's is stored with
 * a deterministic dither (the rounding offset of column x is (o + 167 x) mod 256 256ths of the
 * code's step, o from a hash of the row and the frame count), so that a small step a (t - m)
 * lands in expectation instead of never.
 * Workspace: PFT_PRE_CLUTTER_WORKSPACE_BYTES_MAP8.
 * Anchored map (anchor, per pixel only): the instance keeps the sum S of the shifts given to
 * every accepted update since init/reset (Q16.16, 64 bits, exact) and the position P at which
 * the stored arrays lie, P = S rounded per axis to the nearest integer (halves upwards),
 * taken at each update with evidence (set without a move at the first one). A frame's pixel p
 * reads and updates the stored cell p, which holds the scene's cell p - P; when P changes by
 * d the arrays (m or map8's codes, mu, the counter) are moved by d whole pixels first (out(p)
 * = v(p - d), row copies), the cells that enter taking m 1 sigma^2, mu 0 and counter 0, as a
 * pixel entering the frame does without anchor. Nothing is interpolated: no bilinear carry
 * and none of its smoothing of m, and no work on frames where P does not move. The read's
 * square, the formulas and the edges are those above.
 */

/** Workspace bytes of a clutter map for frames w x h, mean (0/1), blur b and persist (0/1), per pixel (block 0), not in place. */
#define PFT_PRE_CLUTTER_WORKSPACE_BYTES(w, h, mean, b, persist)                                \
    ((size_t)(PFT_WS_ALIGN - 1u) + 2u * PFT_WS_ROUND((size_t)(w) * (size_t)(h) * 2u) +          \
     ((mean) ? PFT_WS_ROUND((size_t)(w) * (size_t)(h) * 2u) : 0u) +                             \
     ((persist) ? PFT_WS_ROUND((size_t)(w) * (size_t)(h) * 2u) : 0u) +                          \
     PFT_WS_ROUND(((size_t)(b) + 1u) * (size_t)(w) * 2u) + 2u * PFT_WS_ROUND((size_t)(w) * 4u))

/** Workspace bytes with inplace set: PFT_PRE_CLUTTER_WORKSPACE_BYTES without the output (2 w h). */
#define PFT_PRE_CLUTTER_WORKSPACE_BYTES_INPLACE(w, h, mean, b, persist)                        \
    (PFT_PRE_CLUTTER_WORKSPACE_BYTES(w, h, mean, b, persist) -                                 \
     PFT_WS_ROUND((size_t)(w) * (size_t)(h) * 2u))

/** Workspace bytes that floor_age adds to every PFT_PRE_CLUTTER_WORKSPACE_BYTES* figure (the
 *  ages of the w columns and h rows, one byte each). */
#define PFT_PRE_CLUTTER_WORKSPACE_BYTES_AGE(w, h) (PFT_WS_ROUND((size_t)(w) + (size_t)(h)))

/** Map grid side for frames of n pixels and blocks of k (0: per pixel). */
#define PFT_PRE_CLUTTER_GRID_(n, k) (((size_t)(n) + ((k) > 1u ? (size_t)(k) : 1u) - 1u) / ((k) > 1u ? (size_t)(k) : 1u))
/** Workspace bytes of a clutter map for every configuration: frames w x h, mean (0/1), blur b,
 *  persist (0/1), block k (0, 2, 4) and inplace (0/1); with k 0 it is
 *  PFT_PRE_CLUTTER_WORKSPACE_BYTES (inplace 0) or PFT_PRE_CLUTTER_WORKSPACE_BYTES_INPLACE. */
#define PFT_PRE_CLUTTER_WORKSPACE_BYTES_BLOCK(w, h, mean, b, persist, k, inplace)                 \
    ((size_t)(PFT_WS_ALIGN - 1u) +                                                               \
     (1u + ((mean) ? 1u : 0u) + ((persist) ? 1u : 0u)) *                                         \
         PFT_WS_ROUND(PFT_PRE_CLUTTER_GRID_(w, k) * PFT_PRE_CLUTTER_GRID_(h, k) * 2u) +           \
     ((inplace) ? 0u : PFT_WS_ROUND((size_t)(w) * (size_t)(h) * 2u)) +                           \
     PFT_WS_ROUND(((size_t)(b) + 1u) * PFT_PRE_CLUTTER_GRID_(w, k) * 2u) +                        \
     2u * PFT_WS_ROUND(PFT_PRE_CLUTTER_GRID_(w, k) * 4u) +                                        \
     ((k) > 1u ? 2u * PFT_WS_ROUND(PFT_PRE_CLUTTER_GRID_(w, k) * 8u) : 0u))

/** Workspace bytes of a clutter map with map8 (per pixel): frames w x h, mean (0/1), blur b,
 *  persist (0/1), inplace (0/1): the map 1 byte per pixel, mu and the counter 2 each, the
 *  output 2 (not inplace), 2 b + 1 decoded rows of the map and one row being updated (2 bytes
 *  per column each), two rows of sums (4 bytes per column each) and the warp's two rows of
 *  horizontal passes (4 bytes per column each; the warp runs row by row within the update). */
#define PFT_PRE_CLUTTER_WORKSPACE_BYTES_MAP8(w, h, mean, b, persist, inplace)                    \
    ((size_t)(PFT_WS_ALIGN - 1u) + PFT_WS_ROUND((size_t)(w) * (size_t)(h)) +                     \
     (((mean) ? 1u : 0u) + ((persist) ? 1u : 0u) + ((inplace) ? 0u : 1u)) *                      \
         PFT_WS_ROUND((size_t)(w) * (size_t)(h) * 2u) +                                          \
     PFT_WS_ROUND((2u * (size_t)(b) + 1u) * (size_t)(w) * 2u) + PFT_WS_ROUND((size_t)(w) * 2u) + \
     2u * PFT_WS_ROUND((size_t)(w) * 4u) + PFT_WS_ROUND((size_t)(w) * 8u))

/** Fills every field with its default (384 x 288, alpha 0.1, 3 x 3 mean, thr 2, no veto, no
 *  persistence gate, excess 1.5, not in place, per pixel, the map in 16 bits). */
void pft_pre_clutter_config_default(pft_pre_clutter_config_t *cfg);
/** PFT_OK, PFT_ERR_INVAL (NULL) or PFT_ERR_CONFIG with *field (if field is not NULL) naming
 *  the first refused field ("width", "height", "alpha", "blur", "thr", "veto", "persist",
 *  "excess", "block", "map8": set with a block); NULL on success. */
pft_status_t pft_pre_clutter_config_check(const pft_pre_clutter_config_t *cfg, const char **field);
/** Exact workspace bytes for cfg; 0 for a NULL or refused cfg. */
size_t pft_pre_clutter_workspace_size(const pft_pre_clutter_config_t *cfg);
/** Initialises c in work[0..work_len): PFT_ERR_INVAL (NULL), PFT_ERR_CONFIG, PFT_ERR_NOMEM. */
pft_status_t pft_pre_clutter_init(pft_pre_clutter_t *c, const pft_pre_clutter_config_t *cfg,
                                  void *work, size_t work_len);
/** Back to the state right after init (map 1, mean 0, no frame). */
pft_status_t pft_pre_clutter_reset(pft_pre_clutter_t *c);
/**
 * One frame: res is the stage's residual (PFT_PIX_RES16 of the configured size, e.g. from
 * pft_pre_frame), (shift_x, shift_y) the scene's shift since the last frame in Q16.16 px
 * (pft_pre_stats_t.shift: z(p) = b(p - shift); 0 for a still scene or the spatial method),
 * evidence false for a frame without detection evidence (flags CONSTANT, ALL_MASKED or
 * REG_LOST). PFT_ERR_INVAL for NULL, PFT_ERR_FORMAT for a wrong frame: nothing changes.
 * Work: a few passes over the pixels (docs/results/ir_clutter.md gives the measured cost).
 */
pft_status_t pft_pre_clutter_update(pft_pre_clutter_t *c, const pft_frame_t *res,
                                    int32_t shift_x, int32_t shift_y, bool evidence);
/**
 * pft_pre_clutter_update for an instance configured with inplace: the output is written over
 * the residual's own pixels (see "Memory" above). pixels must be res->data (the same buffer,
 * writable) with stride_bytes == 2 width. PFT_ERR_INVAL for NULL or pixels != res->data,
 * PFT_ERR_STATE for an instance without inplace (and pft_pre_clutter_update on one with it),
 * PFT_ERR_FORMAT for a wrong frame or stride: nothing changes, the residual included.
 */
pft_status_t pft_pre_clutter_update_inplace(pft_pre_clutter_t *c, const pft_frame_t *res,
                                            int16_t *pixels, int32_t shift_x, int32_t shift_y,
                                            bool evidence);
/** The output of the last update (PFT_PIX_RES16, the input's seq and timestamp_us), lent as
 *  pft_pre_frame lends its residual (valid until the next update, reset or init; with inplace
 *  it describes the caller's buffer of the last pft_pre_clutter_update_inplace, valid while
 *  the caller keeps it unchanged). PFT_ERR_INVAL for NULL, PFT_ERR_STATE before the first
 *  update. */
pft_status_t pft_pre_clutter_frame(const pft_pre_clutter_t *c, pft_frame_t *out);
/** Raises the map to at least level (sigma^2 Q6.10) on the 3 x 3 pixels around (x, y)
 *  (clipped at the frame's edges), e.g. where a track was found to drift with the scene, so
 *  that its evidence fades from the next frame. PFT_ERR_INVAL for NULL or (x, y) outside the
 *  frame: nothing changes. */
pft_status_t pft_pre_clutter_raise(pft_pre_clutter_t *c, uint32_t x, uint32_t y, uint16_t level);
/** Map value m at (x, y), sigma^2 Q6.10; 0 for NULL or (x, y) outside the frame. */
uint32_t pft_pre_clutter_at(const pft_pre_clutter_t *c, uint32_t x, uint32_t y);

/*
 * Flat-field offset correction (pft_pre_flat_*): an optional step after the stage, on its
 * whitened residual, that removes a slowly varying offset fixed to the SENSOR (not to the
 * scene), e.g. the residual that a sensor-fixed gain such as vignetting leaves under a
 * drifting scene (docs/algorithms.md 9.10 [E]). The sensor is cut into blocks of
 * block x block pixels; per block it holds a running value m, read at any pixel bilinearly
 * between the block centres (held beyond the outermost centres). The pixel's offset is
 * o = m(x, y) (sigma), or with relative o = m(x, y) l(x, y), l the pixel's value in the level
 * frame of the update (counts; m in sigma per count). Per frame, for every unmasked pixel r:
 *   v = r - o                       (the output, written over r; masked pixels stay masked)
 * and, when the frame carries detection evidence, per block over its unmasked pixels with
 * |v| <= gate (a target, a bright residual or an outlier does not enter), with n of them:
 *   m <- m + a sum(v) / n           (relative: m <- m + a sum(v) / sum(l))
 * where n >= block^2 / 4 (else the block keeps its value), a = max(alpha, 1 / k) on the k-th
 * frame with evidence (a running mean at the start); m is clamped to +-8 sigma (relative:
 * +-1/32 sigma per count). The gate is centred on the current estimate, so that a Gaussian
 * residual gives an unbiased mean. The map is the one before this frame's update (one frame
 * behind). Integer arithmetic only: float and q16 builds give the same bits (m in sigma Q16,
 * relative sigma per count Q24). Memory: per block 16 bytes (the map, the frame's sums,
 * counts and level sums) and one row of interpolated values: 16 / block^2 bytes per pixel
 * (16 x 16 blocks: 0.063 B/px at 384 x 288); see PFT_PRE_FLAT_WORKSPACE_BYTES. With relative the caller
 * keeps the level frame (e.g. the raw frame) until the update: with a stage that writes its
 * residual over the raw frame (inplace) that is a copy of the frame. Refused input changes
 * nothing (instance, workspace, frame).
 */


/** Blocks along a side of n pixels for block side b (not API). */
#define PFT_PRE_FLAT_NB_(n, b) (((size_t)(n) + (size_t)(b) - 1u) / (size_t)(b))

/** Workspace bytes of a flat-field correction for frames w x h and block side b: the map, the
 *  sums, the counts and the level sums of the blocks (4 bytes each per block) and one row of
 *  block values. */
#define PFT_PRE_FLAT_WORKSPACE_BYTES(w, h, b)                                                   \
    ((size_t)(PFT_WS_ALIGN - 1u) +                                                              \
     4u * PFT_WS_ROUND(PFT_PRE_FLAT_NB_(w, b) * PFT_PRE_FLAT_NB_(h, b) * 4u) +                  \
     PFT_WS_ROUND(PFT_PRE_FLAT_NB_(w, b) * 4u))

/** Workspace bytes of a flat-field correction with rescale: PFT_PRE_FLAT_WORKSPACE_BYTES and,
 *  per block, the scale, its multiplier and the frame's two counts (4 bytes each), and one row
 *  of interpolated multipliers. */
#define PFT_PRE_FLAT_WORKSPACE_BYTES_RESCALE(w, h, b)                                           \
    (PFT_PRE_FLAT_WORKSPACE_BYTES(w, h, b) +                                                    \
     4u * PFT_WS_ROUND(PFT_PRE_FLAT_NB_(w, b) * PFT_PRE_FLAT_NB_(h, b) * 4u) +                  \
     PFT_WS_ROUND(PFT_PRE_FLAT_NB_(w, b) * 4u))

/** Fills every field with its default (384 x 288, 16 x 16 blocks, alpha 0.05, gate 2 sigma). */
void pft_pre_flat_config_default(pft_pre_flat_config_t *cfg);
/** PFT_OK, PFT_ERR_INVAL (NULL) or PFT_ERR_CONFIG with *field (if field is not NULL) naming
 *  the first refused field ("width", "height", "block", "alpha", "gate"); NULL on success. */
pft_status_t pft_pre_flat_config_check(const pft_pre_flat_config_t *cfg, const char **field);
/** Exact workspace bytes for cfg; 0 for a NULL or refused cfg. */
size_t pft_pre_flat_workspace_size(const pft_pre_flat_config_t *cfg);
/** Initialises fl in work[0..work_len): PFT_ERR_INVAL (NULL), PFT_ERR_CONFIG, PFT_ERR_NOMEM. */
pft_status_t pft_pre_flat_init(pft_pre_flat_t *fl, const pft_pre_flat_config_t *cfg, void *work,
                               size_t work_len);
/** Back to the state right after init (map 0, no frame). PFT_ERR_INVAL for NULL. */
pft_status_t pft_pre_flat_reset(pft_pre_flat_t *fl);
/**
 * One frame: res is a whitened residual (PFT_PIX_RES16 of the configured size, e.g. from
 * pft_pre_frame of a stage with inplace, whose buffer is the caller's), pixels its own buffer
 * (pixels == res->data, writable): the corrected residual is written over it. level: with
 * relative, the level frame (U16 or U8 of the configured size, its values as counts, e.g.
 * the raw frame the stage took); read only; ignored (may be NULL) without relative. evidence
 * false (a frame flagged CONSTANT, ALL_MASKED or REG_LOST) corrects the frame but leaves the
 * map. PFT_ERR_INVAL for NULL (level NULL with relative) or pixels != res->data,
 * PFT_ERR_FORMAT for a wrong frame (an odd stride_bytes of res among them): nothing changes,
 * the frame buffer included. Work: one
 * pass over the pixels plus O(blocks).
 */
pft_status_t pft_pre_flat_update(pft_pre_flat_t *fl, const pft_frame_t *res, int16_t *pixels,
                                 const pft_frame_t *level, bool evidence);
/** The map at pixel (x, y), interpolated: without relative the offset the next update
 *  subtracts there, Q8.8 sigma (rounded); with relative the factor of the level, sigma per
 *  count Q24. 0 for NULL or (x, y) outside the frame. */
int32_t pft_pre_flat_at(const pft_pre_flat_t *fl, uint32_t x, uint32_t y);

#ifdef __cplusplus
}
#endif
#endif
