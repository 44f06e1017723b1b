/**
 * @file pft_pte.h
 * @brief Multi-frame track-before-detect on radar range-time (or range-Doppler) images:
 *        PTE-TBD (He, Liao, Yang & Sun 2015, parameterized track enhancement) with its two
 *        baselines, DP-TBD (dynamic programming, Yi et al. 2013 style; batch and sliding) and
 *        the Kalman detect-before-track (DBT).
 *
 * The implementable reading of the paper is docs/algorithms.md section 5 (the paper's
 * equations did not survive; section 5.3 is a reconstruction) and section 6 (measures). This
 * header states the choices a user sees. The three trackers share the input stage
 * (pft_pte_input_t) and the report type (pft_pte_report_t).
 *
 * Calls. Every tracker (prefixes pft_pte_, pft_pte_dp_, pft_pte_dbt_) has the same calls in
 * the same order: config_default, config_check (names the offending field), workspace_size
 * (0 for a refused configuration) and its constant-expression macro, init, reset, update /
 * update_real (one frame), and results copied out into caller memory.
 *
 * Coordinates. One frame is one range profile: a 1-row pft_frame_t of n_range cells
 * (range-time image, the paper's experiments), or an n_range x n_doppler range-Doppler map
 * whose rows are Doppler cells. Range cells are the image columns, Doppler cells (or, in a
 * range-time image, frames) the rows, with the library's one pixel convention: 0-based, the
 * centre of cell u is at coordinate u, so a profile covers [-0.5, n_range - 0.5]. Positions
 * are reported in these cell coordinates (axis 0 range, axis 1 Doppler; axis 1 is 0 for
 * range-time); velocities are cells per frame.
 *
 * Input stage (pft_pte_input_t). U8/U16 pixels become z = pixel_gain*raw + pixel_offset
 * (U16: low bit_depth bits), F32 pixels are taken as z (q16 build: pft_from_f32, integer
 * only). Every algorithm then works on the normalised profile zeta = z/sigma, with
 *  - PFT_PTE_NOISE_FIXED: sigma = noise_sigma (Gaussian background);
 *  - PFT_PTE_NOISE_CFAR: sigma per cell from a cell-averaging CFAR along range (one row at a
 *    time): sigma^ = sqrt(pi/2) * mean |z| over cfar_ref reference cells on each side beyond
 *    cfar_guard guard cells (a side that leaves the profile is dropped, the other side kept),
 *    floored at noise_sigma. This is the sea-clutter mode (K-distributed clutter is modelled
 *    host-side, docs/algorithms.md 5.3 [A]). Under Gaussian noise sigma^ is unbiased.
 * zeta is clamped to +-zeta_clip (default 20). The zero-mean data model of
 * docs/algorithms.md 5.1 is assumed: remove any mean level with pixel_offset.
 *
 * Fixed point (q16 build). zeta and every merit are Q16.16. DP merits accumulate at most
 * PFT_PTE_MAX_FRAMES frames of |zeta| <= zeta_clip (default: 64 * 20 = 1280, far inside
 * +-32768); all sums use the saturating pft_add, so a pathological configuration saturates
 * instead of wrapping. Operator sums E stay below M_max * sum(g) * zeta_clip (1-D: about
 * 40 * 5 * 20 = 4000). The test statistic T is clamped to +-PFT_PTE_T_CLIP so that T^2/2
 * fits. The Gaussian operator weights g = exp(-t^2/2) are tabulated at init for
 * t = 0, 1/64, ..., 3 (nearest entry: |error| <= 0.005); operator paths are quantised to 1/64
 * cell, so each tap is an integer distance looked up in a per-frame table (same in both
 * builds). Very small velocity variances (1e-5 cells^2/frame^2 is 0.66 LSB) are coarse in
 * q16; the defaults keep them >= 2e-4.
 *
 * Memory: everything lives in a caller workspace (ring of the last frames, DP scratch, track
 * table, operator scratch); the *_WORKSPACE_BYTES macros equal the *_workspace_size
 * functions. Per-frame work is bounded by the configuration (see each update function).
 *
 * Refused input (NULL, wrong frame size or format, NaN/Inf in an F32 frame, bad arguments)
 * returns a status code before anything changes: the instance and its workspace stay
 * byte-for-byte as they were.
 */
#ifndef PFT_PTE_H
#define PFT_PTE_H

#include "pft/pft_real.h"
#include "pft/pft_rng.h"
#include "pft/pft_workspace.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Longest frame memory (ring length, DP batch K, initiation batch N, operator length M). */
#define PFT_PTE_MAX_FRAMES 64u
/** Largest per-frame DP velocity gate |du| (cells per frame, per axis). */
#define PFT_PTE_MAX_GATE 7u
/** Largest number of operator directions L per axis (odd). */
#define PFT_PTE_MAX_DIRS 9u
/** Largest scan half-width in steps (scan positions per axis <= 2*16 + 1). */
#define PFT_PTE_MAX_SCAN_STEPS 16u
/** Largest operator width: taps per axis (sigma_w is clamped to (TAPS - 1)/6 cells). */
#define PFT_PTE_MAX_TAPS 15u
/** Largest number of tracks / targets per PTE-TBD or DP-TBD instance. */
#define PFT_PTE_MAX_TRACKS 16u
/** Largest CFAR reference window per side. */
#define PFT_PTE_MAX_CFAR_REF 32u
/** Clamp of the operator test statistic T (T^2/2 stays in Q16.16). */
#define PFT_PTE_T_CLIP 150
/** Largest k = floor(pfa * runs) + 1 of the threshold Monte Carlo (top-k kept). */
#define PFT_PTE_MC_TOPK 64u
/** Entries of the tabulated Gaussian exp(-t^2/2), t = 0 .. 3 in steps of 1/64. */
#define PFT_PTE_GTAB_SIZE 193u
/** Entries of a per-frame weight table in 1/64 cells up to 3 sigma_w (sigma_w <= 7/3). */
#define PFT_PTE_GW_SIZE 449u
/** TABLE operators: cells of response kept beyond each end of the profile. */
#define PFT_PTE_YPAD 4u
/** DBT: largest number of plots kept per frame. */
#define PFT_PTE_DBT_MAX_DETS 256u
/** DBT: largest number of tracks (tentative and confirmed). */
#define PFT_PTE_DBT_MAX_TRACKS 64u
/** DBT: chi-square gate (99%) of one axis (range-time), the default there. */
#define PFT_PTE_DBT_GATE_1AXIS PFT_C(6.63)
/** DBT: chi-square gate (99%) of two axes (range-Doppler), the default there. */
#define PFT_PTE_DBT_GATE_2AXES PFT_C(9.21)

/* Instances (layouts in pft/internal/pft_pte_types.h, not API: read them through the calls). */
typedef struct pft_pte_s pft_pte_t;         /**< PTE-TBD instance */
typedef struct pft_pte_dp_s pft_pte_dp_t;   /**< DP-TBD instance */
typedef struct pft_pte_dbt_s pft_pte_dbt_t; /**< Kalman DBT instance */

/* ====================================== shared input stage ==================================== */

/** Noise level estimate of the input stage. */
typedef enum {
    PFT_PTE_NOISE_FIXED = 0, /**< known sigma (Gaussian background) */
    PFT_PTE_NOISE_CFAR = 1   /**< cell-averaging CFAR along range (clutter) */
} pft_pte_noise_t;

/** Input stage shared by PTE-TBD, DP-TBD and the DBT. */
typedef struct {
    uint16_t n_range;        /**< range cells per frame (frame width), 2..PFT_CFG_MAX_IMAGE_SIDE (default 150) */
    uint16_t n_doppler;      /**< Doppler cells (frame height), 1..PFT_CFG_MAX_IMAGE_SIDE: 1 for range-time profiles (default 1) */
    pft_real_t pixel_gain;   /**< U8/U16: z = gain * raw + offset (default 1) */
    pft_real_t pixel_offset; /**< (default 0) */
    pft_pte_noise_t noise;   /**< FIXED (default) or CFAR */
    pft_real_t noise_sigma;  /**< FIXED: sigma; CFAR: floor of sigma^ (default 1), > 0 */
    uint8_t cfar_ref;        /**< CFAR reference cells per side, 1..PFT_PTE_MAX_CFAR_REF (default 16) */
    uint8_t cfar_guard;      /**< CFAR guard cells per side (default 2) */
    pft_real_t zeta_clip;    /**< |zeta| clamp, in (0, 1000] (default 20) */
    pft_seq_mode_t seq_mode; /**< PFT_SEQ_IGNORE (default: every frame one period after the previous) or PFT_SEQ_USE: pft_frame_t.seq numbers the frames (docs/design.md, "Time, sequence numbers and lost frames"): a repeated or past seq is refused with PFT_ERR_SEQ (nothing changed); a gap of k periods, 1 < k <= max_gap, predicts the DBT's Kalman tracks and PTE-TBD's live tracks over k periods (the windows of PTE-TBD and DP-TBD hold the k - 1 lost frames as missing frames, zeta = 0: a missing stage adds nothing to a merit); k > max_gap restarts every method. The *_update_real calls carry no seq: they count as the next frame */
    uint16_t max_gap;        /**< largest gap predicted across, 1..PFT_SEQ_MAX_GAP (default PFT_SEQ_DEFAULT_GAP) */
} pft_pte_input_t;

/** Fills the input stage defaults (150 x 1 range-time profiles: set n_range, n_doppler after). */
void pft_pte_input_default(pft_pte_input_t *in);
/**
 * PFT_OK if the input stage is usable; PFT_ERR_INVAL for NULL; PFT_ERR_CONFIG for a refused
 * value, and then *field (when field is not NULL) names it ("n_range", "noise_sigma", ...).
 */
pft_status_t pft_pte_input_check(const pft_pte_input_t *in, const char **field);
/**
 * Normalises one frame: zeta[d*n_range + r] = z/sigma (see the file comment).
 * scratch: n_range reals (CFAR only; may be NULL in FIXED mode). PFT_ERR_INVAL (NULL),
 * PFT_ERR_CONFIG (refused input stage), PFT_ERR_FORMAT (frame): nothing written.
 */
pft_status_t pft_pte_normalize(const pft_pte_input_t *in, const pft_frame_t *frame,
                               pft_real_t *zeta, pft_real_t *scratch);
/** Same from values already in input units (z, n_range * n_doppler; z and zeta distinct). */
pft_status_t pft_pte_normalize_real(const pft_pte_input_t *in, const pft_real_t *z,
                                    pft_real_t *zeta);

/** One reported track (or DP detection) at the last frame; same type for PTE, DP and DBT. */
typedef struct {
    uint16_t id;          /**< track id within the instance (1, 2, ...; wraps after 65535 to 1) */
    bool detected;        /**< the method's detection test passed at this frame */
    pft_real_t pos[2];    /**< range cell, Doppler cell (cell centres at integers, 0-based) */
    pft_real_t vel[2];    /**< cells per frame */
    pft_real_t var[2];    /**< position variance per axis (DP: 0) */
    pft_real_t amplitude; /**< amplitude estimate in sigma units (A / sigma; DBT: 0) */
    pft_real_t score;     /**< PTE: max_l T_l*; DP: path merit; DBT: peak zeta of the detection */
    uint32_t age;         /**< frames since the track started (0 at its first report) */
    uint32_t last_seq;    /**< seq of the frame of the report (its last update; the last pft_frame_t seq + 1 per *_update_real call after it, 0 before any numbered frame) */
    uint32_t gap;         /**< frame periods from the previous accepted frame to this one: the seq difference k with PFT_SEQ_USE (k - 1 frames lost), 1 with PFT_SEQ_IGNORE, 0 on the first frame after init or reset and on a restart (a gap above max_gap) (an *_update_real call: 1) */
    uint64_t last_timestamp_us; /**< timestamp_us of the last pft_frame_t fed */
} pft_pte_report_t;

/* ========================================== PTE-TBD ========================================= */

/** How PTE-TBD evaluates its operators. */
typedef enum {
    PFT_PTE_OP_EXACT = 0, /**< Gaussian taps of width sigma_w = sqrt(sigma_r^2 + P_rr) evaluated per
                               direction, scan position and frame (docs/algorithms.md 5.3 as written) */
    PFT_PTE_OP_TABLE = 1, /**< range-time only: each frame's matched response
                               y(p) = sum_u g((u - p)/sigma_r) zeta(u) is computed on a grid of
                               c_step cells (c_step = 1/Q, Q integer <= 8), lazily in blocks of
                               8 cells the first time an operator needs it, and kept beside zeta
                               in the ring; an operator is a straight line on that grid (path
                               position rounded to the grid, error <= c_step/2). The directions
                               lie on a lattice of slopes of step dtheta_min (the one nearest the
                               predicted slope and (L-1)/2 on each side, spaced dtheta_min, or
                               dth rounded to a multiple of dtheta_min when dth > 2.5 dtheta_min)
                               and each track keeps, per direction slope, the sums of its lines
                               over the window and slides them (newest frame in, the frame
                               leaving the window out): O(1) reads per line and frame instead of
                               M [A]. The width is sigma_r (the covariance part of sigma_w is
                               dropped) [A]. Requires zeta_clip <= 64 (the operator sums then
                               cannot overflow q16 and use plain additions; sliding them is exact
                               in q16, and the float build sums an entry afresh every 256
                               frames). Memory: see PFT_PTE_WORKSPACE_BYTES */
    PFT_PTE_OP_AUTO = 2   /**< TABLE for range-time frames (n_doppler 1), EXACT for range-Doppler */
} pft_pte_op_t;

/** Motion model of a PTE-TBD track, per axis. */
typedef enum {
    PFT_PTE_MOTION_CV = 0, /**< constant velocity, white acceleration of intensity q (docs/algorithms.md 5.1) */
    PFT_PTE_MOTION_CA = 1  /**< constant acceleration, white jerk of intensity q; the operators'
                                measurement model accounts for the acceleration (docs/algorithms.md 5.3 step 3) */
} pft_pte_motion_t;

/**
 * PTE-TBD (docs/algorithms.md 5.2-5.3). Per track the state is [r, r', r''] per axis (Kalman;
 * r'' stays 0 in the CV model) plus the amplitude (random walk, scalar Kalman). Per frame:
 *  1. predict; 2. operator parameters: length M = min(n_acc, max_len), width
 *     sigma_w = sqrt(sigma_r^2 + P_rr), directions theta_l = r' + (l - (L+1)/2) * dtheta with
 *     dtheta = max(4 sqrt(P_vv)/(L-1), dtheta_min);
 *  3. for each direction, matched operators ending at scan positions
 *     c = r +- scan_sigmas * sqrt(P_rr + sigma_r^2) (step c_step, at most scan_steps steps)
 *     along the straight path u(tau) = c + theta*tau (tau = 0, -1, .., -(M-1)):
 *     E = sum over the last M frames of g * zeta, G = sum g^2,
 *     T = E / sqrt(G) (N(0,1) under noise);
 *  4. direction likelihood W_l proportional to N(theta_l; r', P_vv + dtheta^2/12) times
 *     sum_c N(c; r, P_rr + sigma_r^2) exp(max(T, 0)^2 / 2); c_l* the best summand (parabola
 *     refined), T_l* its T;
 *  5. per direction a Kalman update with the measurement [c_l*, theta_l] (R from sigma_w,
 *     T_l*, M; docs/algorithms.md 5.3 step 5) and an amplitude update with E/G;
 *  6. fusion X = sum W_l X_l, P = sum W_l (P_l + spread);
 *  7. detection if max_l T_l* >= eta_t, else a miss; max_misses consecutive misses end the
 *     track. The fused state sets the next frame's operators (closed loop).
 * A straight operator over M = 40 frames measures the velocity averaged over its window, so a
 * CV track lags a manoeuvre by about M/2 frames of acceleration (measured: 1.4 cells in the
 * turn of the air scenario at 15 dB); in the CA model the measurement of a straight operator
 * is modelled as the least-squares line of the quadratic path (end position r - a(M-1)(M-2)/12,
 * slope v - a(M-1)/2), which removes that lag (docs/results/pte.md) [A].
 * A turn sharper than the template's window bends the path away from every straight line of
 * M frames. Manoeuvre test (short_len = Ms > 0, TABLE operators): every step also evaluates
 * the directions over the last Ms frames (the slope entries slide a second window, no extra
 * memory); with T_L, T_S the largest signed T of the M- and the Ms-frame operators,
 * Z = (T_S sqrt(M) - T_L sqrt(Ms)) / sqrt(M - Ms) is N(0, 1)-like on a straight path (the
 * amplitude estimates of two nested windows differ by noise only). In a turn the recent frames
 * leave the predicted lines while the older part of the long window still supports them
 * (Z < 0: the track would run straight on), or the long window stops fitting (Z > 0);
 * |Z| > man_z restarts the track's template at Ms frames (n_acc = Ms; it grows again by one
 * frame per step up to max_len) and adds man_acc_sd^2 to the variance of r'' (CV:
 * (Ms man_acc_sd)^2 to r'), so that the directions and the scan widen and the state can
 * follow the turn. The low default threshold makes it fire often on straight paths too,
 * which shortens the template on average (docs/results/radar_multi.md) [A].
 * Range-Doppler frames use the same operator over both axes: L0 x L1 directions, a 2-D scan
 * grid and separable weights g0*g1; the axes are filtered independently (block-diagonal P,
 * cross-axis terms of the fusion spread dropped [A]).
 *
 * Internally the state per axis is scaled to [r, 16 r', 256 r'', 0] so that the small
 * velocity and acceleration variances stay well above the q16 LSB; reports are in cells and
 * cells per frame.
 *
 * Initiation (Step 2) is a DP-TBD batch over the last init_frames frames (gate init_gate, no
 * motion model) with threshold init_threshold; the backtracked path is refined to sub-cell
 * positions (3-point parabola on zeta) and fitted by least squares, giving [r, r'] and
 * P = sigma_r^2 (H'H)^-1 (r'' = 0 with standard deviation acc_sd0); the amplitude is the mean
 * zeta along the path; n_acc = N. Cells within +-3 sigma_w of live tracks (their state
 * extrapolated back over the batch) are cancelled, and further targets are extracted after
 * cancelling each new path. With init_spread = 0 the initiation runs at every frame while no
 * track is live, else every init_period frames while a track slot is free. With init_spread
 * = S >= 1 (default 4) it is spread over the updates, at most S DP stages per update: a
 * search holds the DP merits between updates and gives each frame its stage (the cells of
 * the tracks live at that update cancelled, their position +-3 sigma_w), oldest first; it
 * ends at the newest frame, its batch being the last N frames. While tracks are live a search
 * starts on the newest frame (one stage per update) so that searches end every
 * max(init_period, N) frames; with no live track it starts on the frames already held and
 * ends ceil(N / S) updates later. A further target of the same search is extracted only
 * when the backtracked path of the best remaining final cell crosses no cancelled cell (the
 * path a re-run would find); otherwise the next search finds it. Two live tracks closer than
 * dup_cells (axis 0, and axis 1 when 2-D) are duplicates: the one with the lower score ends [A].
 *
 * Step budget (step_budget = B >= 1; default 0: off): at most B track steps per update, the
 * live tracks that waited longest first; the others predict over the frame as over a lost
 * frame and take its data in at their next step, their TABLE line sums slid over the frames
 * they missed (templates capped at max_len + 1 - ceil(max_tracks / B) frames so the frames
 * leaving a window are still in the ring). This bounds the steps per frame, not the work of
 * a step (docs/algorithms.md 5.8).
 *
 * Line budget (line_budget = W >= 1; default 0: off; TABLE operators only): at most W units
 * of the slope entries' work per update, in one currency: one line x frame sum (one response
 * added to or removed from one line sum) is 1 unit, one response block computed for them
 * (8 cells) 47 units in the float build and 116 in the q16 build, and each frame of the edge
 * correction of a direction's normaliser (lines leaving the interior of the response grid)
 * 4 units plus 1 per point corrected (the weights are measured instruction ratios:
 * docs/algorithms.md 5.8). Every part is charged from an upper bound before it is done
 * (the blocks not yet computed under the lines it reads; the edge correction of the lines a
 * step reads is reserved per direction after its entry, and when it does not fit the direction
 * waits as one whose entry is incomplete). The live tracks try to
 * step in the order of the frames they waited (every live one, or the step_budget ones);
 * an entry is brought to the frame in full when that fits in what is left, else one frame of
 * all its lines at a time as far as the budget goes (the frames it missed first, then the
 * far end of each window), and the rest is carried to the next update: a direction whose
 * entry is incomplete takes no part in the step (no weight in the fusion, no say in the
 * detection test); a track none of whose entries is complete predicts over the frame as over
 * a lost one and steps when one is (it ends when it left the image or has waited max_len
 * frames). So a new entry is summed over its whole template a few frames at a time before the
 * track steps with it. W >= 2 (2 scan_steps + 1) n_dir[0] (2 with short_len, else 1): the
 * line x frame sums of one slide of every entry of one track; a W below what a track's slides
 * and their response blocks cost per frame (median 344 units float, 482-582 q16 in the soak's
 * scene) makes tracks wait often (docs/algorithms.md 5.8).
 */
typedef struct {
    pft_pte_input_t in;        /**< input stage */
    /* Step 2: initiation */
    uint8_t init_frames;       /**< N, 2..PFT_PTE_MAX_FRAMES (default 10) */
    uint8_t init_gate[2];      /**< DP gate per axis, 0..PFT_PTE_MAX_GATE (default 1, 1) */
    pft_real_t init_threshold; /**< V_T of the N-frame DP (default 18.9: 1e-3 per batch for 150 range cells, see pft_pte_threshold) */
    uint8_t init_period;       /**< search period while tracks are live, >= 1 (default 10) */
    uint8_t init_spread;       /**< S: at most S initiation DP stages per update (bounded work per frame; S >= init_frames: a whole search in one update while no track is live); 0: the whole N-frame DP at the search's frame (default 4) */
    /* Step 3: track enhancement */
    uint8_t max_len;           /**< M_max, 2..PFT_PTE_MAX_FRAMES (default 40: the paper's template) */
    uint8_t n_dir[2];          /**< L per axis, odd, 1..PFT_PTE_MAX_DIRS (default 5, 5) */
    pft_pte_motion_t motion;   /**< CV or CA (default CA) */
    pft_real_t sigma_r[2];     /**< measurement error sigma_R per axis, cells, in (0, 100] (default 0.5) */
    pft_real_t q_sd[2];        /**< process noise per axis as sqrt of its intensity q, in [0, 1]: CV white acceleration (q in cells^2/frame^3) or CA white jerk (cells^2/frame^5) (default CA: 0.002, q = 4e-6; given as a square root because q is below the q16 LSB) */
    pft_real_t acc_sd0[2];     /**< CA: initial acceleration standard deviation, cells/frame^2, in [0, 0.1] (default 0.003) */
    pft_real_t q_amp;          /**< amplitude random-walk variance per frame, >= 0 (default 0.01) */
    pft_real_t dtheta_min;     /**< smallest direction step, cells/frame, > 0 (default 0.02) */
    pft_real_t c_step;         /**< scan step, cells, in (0, 4] (default 0.25) */
    uint8_t scan_steps;        /**< largest scan half-width in steps, 1..PFT_PTE_MAX_SCAN_STEPS (default 16) */
    pft_real_t scan_sigmas;    /**< scan half-width in standard deviations, > 0 (default 3) */
    pft_real_t sigma_w_max;    /**< operator width clamp, in (0, (PFT_PTE_MAX_TAPS - 1)/6] (default 2) */
    pft_real_t eta_t;          /**< detection threshold on max_l T_l* (default 3.5) */
    uint8_t max_misses;        /**< consecutive misses that end a track, >= 1 (default 3) */
    uint8_t max_tracks;        /**< 1..PFT_PTE_MAX_TRACKS (default 4) */
    pft_real_t dup_cells;      /**< duplicate-track distance, >= 0 (default 1.0; 0 disables) */
    pft_pte_op_t op;           /**< operator evaluation (default AUTO: TABLE for range-time, EXACT for range-Doppler) */
    /* Manoeuvre test (TABLE operators only) */
    uint8_t short_len;         /**< Ms: frames of the short template of the manoeuvre test, 0 (off) or 2..max_len - 1; needs TABLE operators (default 0: off) */
    pft_real_t man_z;          /**< threshold of |Z|, the manoeuvre statistic, in (0, 100] (default 1.25) */
    pft_real_t man_acc_sd;     /**< on a manoeuvre, acceleration standard deviation added to the track's covariance (CA: to r''; CV: Ms times it to r'), cells/frame^2, in [0, 0.1] (default 0.03) */
    /* Per-frame work bound */
    uint8_t step_budget;       /**< B: at most B track steps per update, 0..max_tracks (default 0: off, every live track steps at every frame). With B >= 1 the live tracks that waited longest step (ties: lower slot), the others predict over the frame as over a lost one and step later over the frames they missed; templates are at most max_len + 1 - ceil(max_tracks / B) frames, which must be >= 2 and above short_len (docs/algorithms.md 5.8) */
    uint16_t line_budget;      /**< W: at most W units of the TABLE slope entries' work per update (line x frame sums 1 each, response blocks 47 float / 116 q16, edge-correction rows 4 plus 1 per point; default 0: off). TABLE only, W >= 2 (2 scan_steps + 1) n_dir[0] (twice that with short_len); a direction whose entry the budget left incomplete takes no part in the step, a track with no complete entry predicts over the frame (see "Line budget" above; docs/algorithms.md 5.8) */
    /* Steady tracks (TABLE) */
    uint8_t steady_dirs;       /**< Ls: directions of a steady track's step, odd, 3..n_dir[0] - 2; TABLE only (default 0: off, every step scans n_dir[0] directions). A track is steady when its previous step detected (max_l T_l* >= eta_t), gave the central direction the largest fusion weight and found the central direction's end position within one standard deviation of the predicted one ((c* - zc)^2 <= P_cc + sigma_R^2), and its direction spacing is the smallest one (the n_dir[0]-direction spacing 4 sqrt(P_tt) / (n_dir[0] - 1) at most 2.5 dtheta_min, so that the lattice step dtheta_min is used): then the step scans only the Ls directions around the predicted slope, at spacing dtheta_min (the slope entries of the others are dropped and summed afresh when the track leaves the steady state). A library extension [E] that trades the outer directions of a track that keeps to its predicted slope for fewer line sums, scans and Kalman updates (measured at 150 cells, n_dir 5, Ls 3: 16 % (float) and 9 % (q16) fewer instructions per frame, RMSE up by 0.003-0.025 cells, beyond Monte Carlo error, hence off; docs/algorithms.md 5.3, docs/tuning.md, docs/results/pte.md) */
    /* Slope hysteresis (TABLE) */
    pft_real_t slope_hold;     /**< h, lattice steps, in [0, 0.5]; TABLE only (default 0: off, the directions of a step are centred on the lattice slope nearest the predicted one). With h > 0 a step whose directions sit at the lattice step dtheta_min (as did the previous step's) keeps the previous step's central slope while the predicted slope is within 1/2 + h lattice steps of it, instead of moving the direction set by one lattice point and back as the prediction wavers about the midpoint between two lattice slopes (each move drops one slope entry and sums another afresh over the whole window). A library extension [E] that changes values (docs/tuning.md, docs/results/pte.md "Branch pte16") */
} pft_pte_config_t;

/** Fills every field of cfg with its default (150 x 1 range-time profiles: set cfg->in sizes after). */
void pft_pte_config_default(pft_pte_config_t *cfg);
/**
 * PFT_OK if cfg is usable; PFT_ERR_INVAL for NULL; PFT_ERR_CONFIG for a refused value, and
 * then *field (when field is not NULL) names the first offending field as written in the
 * struct ("in.n_range", "n_dir[1]", "op", ...). *field is NULL on success.
 */
pft_status_t pft_pte_config_check(const pft_pte_config_t *cfg, const char **field);

/* ============================================ DP-TBD ======================================== */

/**
 * DP-TBD (docs/algorithms.md 5.4): merit I_1(u) = l_1(u), I_k(u) = l_k(u) + max over the gate
 * |u - u'| <= gate of I_{k-1}(u') (each axis), with l = zeta (unknown amplitude) or the
 * known-amplitude log-likelihood ratio a*zeta - a^2/2. A target is declared when the best
 * final merit exceeds V_T; its path is backtracked; cells within +-cancel of the path are
 * cancelled in every frame and the DP repeated for the next target (up to max_targets).
 * Sliding mode: pft_pte_dp_update re-runs the batch over the last K frames at every frame
 * and reports the last state of each path; batch mode: call pft_pte_dp_reset every K frames.
 */
typedef struct {
    pft_pte_input_t in;   /**< input stage */
    uint8_t frames;       /**< batch length K, 2..PFT_PTE_MAX_FRAMES (default 10) */
    uint8_t gate[2];      /**< velocity gate per axis, 0..PFT_PTE_MAX_GATE (default 1, 1; axis 1 unused for range-time) */
    pft_real_t amplitude; /**< known normalised amplitude a for l = a*zeta - a^2/2, in [0, 100]; 0: unknown, l = zeta (default 0) */
    pft_real_t threshold; /**< V_T on the final merit (default 17.0; the measured 1e-3 per-batch value for 150 range-time cells, K = 10, gate 1 is 18.9: set it with pft_pte_dp_threshold for the geometry and false-alarm probability at hand) */
    uint8_t max_targets;  /**< paths per batch, 1..PFT_PTE_MAX_TRACKS (default 4) */
    uint8_t cancel;       /**< cancellation half-width d in cells (default 3) */
} pft_pte_dp_config_t;

/** Fills every field of cfg with its default (150 x 1 range-time profiles: set cfg->in sizes after). */
void pft_pte_dp_config_default(pft_pte_dp_config_t *cfg);
/** As pft_pte_config_check ("in.n_range", "frames", "gate[0]", ...). */
pft_status_t pft_pte_dp_config_check(const pft_pte_dp_config_t *cfg, const char **field);

/* ========================================= Kalman DBT ======================================= */

/**
 * Kalman detect-before-track baseline (docs/algorithms.md 5.5): per-frame threshold, centroid
 * plots, CV Kalman filters, nearest-neighbour gating, M-of-N confirmation, deletion after
 * missed frames. Per frame:
 *  1. plots: cells with zeta > threshold (default Q^-1(1e-2) = 2.326). Range-time: each run
 *     of adjacent cells above the threshold is one plot at its zeta-weighted centroid.
 *     Range-Doppler [A]: each local maximum (8-neighbourhood) above the threshold is one plot
 *     at the centroid of the cells above the threshold in its 3x3 block. At most max_dets
 *     plots are kept (the strongest).
 *  2. predict every track (CV per axis, T = 1 frame, noise q: Q = q [[1/3, 1/2], [1/2, 1]]);
 *  3. gate: d^2 = sum over axes of nu^2 / S <= gate (chi-square); global nearest neighbour,
 *     greedy by d^2, confirmed tracks first;
 *  4. update (R = sigma_r^2 per axis) or count a miss;
 *  5. a tentative track is confirmed with confirm_m hits in its first confirm_n frames
 *     (default 2 of 3), else deleted; a confirmed track is deleted after max_misses
 *     consecutive misses (default 3);
 *  6. every plot left over starts a tentative track at the plot with velocity 0 and
 *     covariance diag(sigma_r^2, vel_var0) while slots are free.
 * Reports are the confirmed tracks (ids given at confirmation); `detected` says whether the
 * track was updated with a plot at this frame, `score` is that plot's peak zeta.
 * Per-frame work: one pass over the cells plus max_tracks * max_dets gating tests and at most
 * min(max_tracks, max_dets) greedy selection rounds over them.
 */
typedef struct {
    pft_pte_input_t in;     /**< input stage */
    pft_real_t threshold;   /**< plot threshold on zeta (default 2.3263, P_fa = 1e-2 per cell) */
    pft_real_t sigma_r[2];  /**< measurement standard deviation per axis, cells, > 0 (default 0.5) */
    pft_real_t q[2];        /**< CV process noise intensity per axis, >= 0 (default 2e-4) */
    pft_real_t vel_var0[2]; /**< initial velocity variance per axis, > 0 (default 0.04) */
    pft_real_t gate;        /**< chi-square gate, >= 0; 0 (default): PFT_PTE_DBT_GATE_1AXIS (6.63) for range-time, PFT_PTE_DBT_GATE_2AXES (9.21) for range-Doppler */
    uint8_t confirm_m;      /**< hits needed, 1..confirm_n ... (default 2) */
    uint8_t confirm_n;      /**< ... within the first n frames, 1..8 (default 3) */
    uint8_t max_misses;     /**< consecutive misses deleting a confirmed track, >= 1 (default 3) */
    uint8_t max_tracks;     /**< track slots, 1..PFT_PTE_DBT_MAX_TRACKS (default 32) */
    uint16_t max_dets;      /**< plots kept per frame, 1..PFT_PTE_DBT_MAX_DETS (default 64) */
} pft_pte_dbt_config_t;

/** One plot of the current frame. */
typedef struct {
    pft_real_t pos[2]; /**< centroid (range, Doppler), cell coordinates */
    pft_real_t peak;   /**< largest zeta of the plot */
} pft_pte_dbt_plot_t;

/** Fills every field of cfg with its default (150 x 1 range-time profiles: set cfg->in sizes after). */
void pft_pte_dbt_config_default(pft_pte_dbt_config_t *cfg);
/** As pft_pte_config_check ("in.noise_sigma", "confirm_m", "q[1]", ...). */
pft_status_t pft_pte_dbt_config_check(const pft_pte_dbt_config_t *cfg, const char **field);

#ifdef __cplusplus
}
#endif

/* Layouts of the instances, for sizeof and the workspace macros (not API). */
#include "pft/internal/pft_pte_types.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ===================================== PTE-TBD: workspace and calls ========================== */

/**
 * Workspace bytes of a PTE-TBD instance: frames n_range x n_doppler, max_len M_max,
 * init_frames N, max_tracks, scan_steps, n_dir[0], n_dir[1], and yq = 1/c_step in TABLE mode
 * (0 in EXACT mode; AUTO is TABLE for n_doppler 1). The ring holds max(M_max + 1, N) frames
 * (the frame leaving an operator window is subtracted from the sliding sums); TABLE adds
 * the response ring and, per track, n_dir[0] slope entries of 2 windows x (2 scan_steps + 1)
 * line sums.
 */
#define PFT_PTE_WORKSPACE_BYTES(nr, nd, mlen, ninit, tmax, steps, l0, l1, yq)                   \
    ((size_t)(PFT_WS_ALIGN - 1u) +                                                              \
     PFT_WS_ROUND(PFT_PTE_RING_(mlen, ninit) * PFT_PTE_CELLS_(nr, nd) * sizeof(pft_real_t)) +    \
     PFT_WS_ROUND((size_t)(nr) * sizeof(pft_real_t)) + PFT_PTE_DPCORE_BYTES_(nr, nd, ninit) +   \
     PFT_WS_ROUND((size_t)(ninit) * 2u * sizeof(int16_t)) +                                     \
     PFT_WS_ROUND((size_t)PFT_PTE_GTAB_SIZE * sizeof(pft_real_t)) +                            \
     ((nd) > 1 ? 2u : 1u) * PFT_WS_ROUND((size_t)PFT_PTE_GW_SIZE * sizeof(pft_real_t)) +        \
     PFT_WS_ROUND((size_t)(tmax) * sizeof(pft_pte_track_t)) +                                   \
     PFT_WS_ROUND((size_t)(tmax) * sizeof(pft_pte_report_t)) +                                  \
     3u * PFT_WS_ROUND(PFT_PTE_NSCAN_(nd, steps, 0) * PFT_PTE_NSCAN_(nd, steps, 1) *            \
                       sizeof(pft_real_t)) +                                                    \
     PFT_WS_ROUND(PFT_PTE_NSCAN_(nd, steps, 0) * PFT_PTE_MAX_TAPS * sizeof(pft_real_t)) +       \
     PFT_WS_ROUND(PFT_PTE_NSCAN_(nd, steps, 1) * PFT_PTE_MAX_TAPS * sizeof(pft_real_t)) +       \
     PFT_WS_ROUND(PFT_PTE_NSCAN_(nd, steps, 0) * 4u * sizeof(int16_t)) +                        \
     PFT_WS_ROUND(PFT_PTE_NSCAN_(nd, steps, 1) * 4u * sizeof(int16_t)) +                        \
     PFT_WS_ROUND((size_t)(l0) * PFT_PTE_NDIR_(nd, l1) * sizeof(pft_pte_dir_t)) +              \
     PFT_WS_ROUND(sizeof(pft_pte_scratch_t)) +                                                  \
     (PFT_WS_ROUND(PFT_PTE_RING_(mlen, ninit) * ((size_t)(nr) + 2u * PFT_PTE_YPAD) *             \
                   (size_t)(yq) * sizeof(pft_real_t)) +                                         \
      PFT_WS_ROUND(((size_t)(nr) + 2u * PFT_PTE_YPAD) * (size_t)(yq) * sizeof(pft_real_t)) +     \
      ((yq) > 0 ? PFT_WS_ROUND(PFT_PTE_RING_(mlen, ninit) *                                     \
                               (((size_t)(nr) + 2u * PFT_PTE_YPAD + 7u) / 8u)) +                \
                      PFT_WS_ROUND((size_t)(tmax) * PFT_PTE_NBANK_(l0) *                        \
                                   sizeof(pft_pte_bank_t)) +                                    \
                      PFT_WS_ROUND((size_t)(tmax) * PFT_PTE_NBANK_(l0) * PFT_PTE_NWIN_ *         \
                                   (2u * (size_t)(steps) + 1u) * sizeof(pft_real_t))            \
                : 0u)))

/** Exact workspace bytes for cfg (0 if cfg is NULL or refused). */
size_t pft_pte_workspace_size(const pft_pte_config_t *cfg);
/**
 * Initialises pte in work[0..work_len): PFT_ERR_INVAL (NULL), PFT_ERR_CONFIG (refused cfg),
 * PFT_ERR_NOMEM (short work). The configuration is copied (AUTO resolved).
 */
pft_status_t pft_pte_init(pft_pte_t *pte, const pft_pte_config_t *cfg, void *work,
                          size_t work_len);
/** Back to the state right after init: frames and tracks forgotten, ids restart at 1. */
pft_status_t pft_pte_reset(pft_pte_t *pte);
/**
 * Pushes one frame: updates every live track (Step 3), then runs the initiation when due.
 * Work per frame is bounded by max_tracks * L0*L1 * M_max * (2*scan_steps+1)^naxes *
 * TAPS^naxes operator taps plus (max_tracks + 1) DP passes of N * cells * gate steps.
 * With in.seq_mode = PFT_SEQ_USE: PFT_ERR_SEQ for a repeated or past seq (nothing changed);
 * a gap of k periods, 1 < k <= in.max_gap: the k - 1 lost frames take ring slots marked
 * missing (no operator term; missing stages of an initiation batch), every live track
 * predicts over them (no miss counted) and the running initiation search ends
 * (docs/algorithms.md 5.7); k > in.max_gap restarts the window on this frame (tracks end, ids
 * go on).
 */
pft_status_t pft_pte_update(pft_pte_t *pte, const pft_frame_t *frame);
/** Same with a frame given as n_range * n_doppler values in input units. */
pft_status_t pft_pte_update_real(pft_pte_t *pte, const pft_real_t *z);
/**
 * Live tracks after the last update, in slot order: copies at most max of them into out and
 * returns how many there are (out may be NULL with max 0 to ask the count; 0 for NULL pte).
 */
size_t pft_pte_reports(const pft_pte_t *pte, pft_pte_report_t *out, size_t max);
/**
 * Starts a track by hand (a cue from another sensor, or a test), as if initiated now:
 * state pos/vel per axis, diagonal covariance pos_var/vel_var (> 0), amplitude amp, n_acc
 * (>= 1, capped at max_len). Returns the new id in *id. PFT_ERR_INVAL on bad arguments,
 * PFT_ERR_STATE if every track slot is live (nothing changed in either case).
 */
pft_status_t pft_pte_start(pft_pte_t *pte, const pft_real_t pos[2], const pft_real_t vel[2],
                           const pft_real_t pos_var[2], const pft_real_t vel_var[2],
                           pft_real_t amp, uint8_t n_acc, uint16_t *id);
/**
 * Noise-only Monte Carlo threshold of the initiation DP (N frames, init_gate), as
 * pft_pte_dp_threshold. Resets the instance (frames and tracks forgotten).
 */
pft_status_t pft_pte_threshold(pft_pte_t *pte, pft_real_t pfa, uint32_t runs, uint64_t seed,
                               pft_real_t *vt);

/* ===================================== DP-TBD: workspace and calls =========================== */

/** Workspace bytes of a DP-TBD instance (n_range, n_doppler, frames K, max_targets). */
#define PFT_PTE_DP_WORKSPACE_BYTES(nr, nd, k, tmax)                                             \
    ((size_t)(PFT_WS_ALIGN - 1u) +                                                              \
     PFT_WS_ROUND((size_t)(k) * PFT_PTE_CELLS_(nr, nd) * sizeof(pft_real_t)) +                 \
     PFT_WS_ROUND((size_t)(nr) * sizeof(pft_real_t)) + PFT_PTE_DPCORE_BYTES_(nr, nd, k) +       \
     PFT_WS_ROUND((size_t)(tmax) * (size_t)(k) * 2u * sizeof(int16_t)) +                        \
     2u * PFT_WS_ROUND((size_t)(tmax) * sizeof(pft_pte_report_t)))

/** Exact workspace bytes for cfg (0 if cfg is NULL or refused). */
size_t pft_pte_dp_workspace_size(const pft_pte_dp_config_t *cfg);
/** As pft_pte_init. */
pft_status_t pft_pte_dp_init(pft_pte_dp_t *dp, const pft_pte_dp_config_t *cfg, void *work,
                             size_t work_len);
/** Back to the state right after init: frames and reports forgotten, ids restart at 1. */
pft_status_t pft_pte_dp_reset(pft_pte_dp_t *dp);
/**
 * Pushes one frame; once K frames are held, runs the batch over the last K frames and
 * replaces the reports (ids follow a path whose last cell stays within +-cancel cells of a
 * previous report). Work per frame: at most (max_targets + 1) DP passes of
 * K * cells * (2*gate0 + 1) * (2*gate1 + 1) steps. With in.seq_mode = PFT_SEQ_USE:
 * PFT_ERR_SEQ for a repeated or past seq (nothing changed); a gap of k periods,
 * 1 < k <= in.max_gap: the k - 1 lost frames take window slots with zeta = 0 (missing stages:
 * a path moves over their periods and its merit gains nothing from them), then the batch runs
 * as usual; k > in.max_gap restarts the batch on this frame (ids go on).
 */
pft_status_t pft_pte_dp_update(pft_pte_dp_t *dp, const pft_frame_t *frame);
/** Same with a frame given as n_range * n_doppler values in input units. */
pft_status_t pft_pte_dp_update_real(pft_pte_dp_t *dp, const pft_real_t *z);
/**
 * Reports of the last frame (declared targets, best merit first): copies at most max into
 * out, returns how many there are (out may be NULL with max 0; 0 for NULL dp).
 */
size_t pft_pte_dp_reports(const pft_pte_dp_t *dp, pft_pte_report_t *out, size_t max);
/**
 * Backtracked path of report i of the last batch: cells[2*k + a] for frame k = 0 (oldest of
 * the batch) .. K-1 (newest), axis a. Copies at most max values and returns 2 K, the number
 * of values of the path (0 if dp is NULL or i is not a report of the last frame).
 */
size_t pft_pte_dp_path(const pft_pte_dp_t *dp, size_t i, int16_t *cells, size_t max);
/**
 * Best final merit of the last batch, declared or not, into *peak (PFT_REAL_MIN before the
 * first batch). PFT_ERR_INVAL for NULL arguments.
 */
pft_status_t pft_pte_dp_peak(const pft_pte_dp_t *dp, pft_real_t *peak);
/**
 * Noise-only Monte Carlo threshold: runs batches of K frames of Gaussian noise through the
 * input stage and the DP (first extraction only) and returns in *vt the k-th largest best
 * merit, k = floor(pfa * runs) + 1, so that a fraction pfa of the runs exceeded it.
 * FIXED mode draws noise of sigma = noise_sigma; CFAR mode draws sigma = 16 * noise_sigma (the
 * floor then rarely binds). Uses dp's workspace: the instance is reset (frames forgotten).
 * PFT_ERR_INVAL if pfa is not in (0, 1), runs == 0 or k > PFT_PTE_MC_TOPK.
 * Work: runs * (K frames of draws + one DP pass).
 */
pft_status_t pft_pte_dp_threshold(pft_pte_dp_t *dp, pft_real_t pfa, uint32_t runs,
                                  uint64_t seed, pft_real_t *vt);

/* ===================================== DBT: workspace and calls ============================== */

/** Workspace bytes of a DBT instance (n_range, n_doppler, max_tracks, max_dets). */
#define PFT_PTE_DBT_WORKSPACE_BYTES(nr, nd, tmax, dmax)                                         \
    ((size_t)(PFT_WS_ALIGN - 1u) +                                                              \
     PFT_WS_ROUND((size_t)(nr) * (size_t)(nd) * sizeof(pft_real_t)) +                           \
     PFT_WS_ROUND((size_t)(nr) * sizeof(pft_real_t)) +                                          \
     PFT_WS_ROUND((size_t)(dmax) * sizeof(pft_pte_dbt_plot_t)) +                                \
     PFT_WS_ROUND((size_t)(tmax) * sizeof(pft_pte_dbt_track_t)) +                               \
     PFT_WS_ROUND((size_t)(tmax) * sizeof(pft_pte_report_t)) +                                  \
     PFT_WS_ROUND((size_t)(tmax) * (size_t)(dmax) * sizeof(pft_real_t)))

/** Exact workspace bytes for cfg (0 if cfg is NULL or refused). */
size_t pft_pte_dbt_workspace_size(const pft_pte_dbt_config_t *cfg);
/** As pft_pte_init (gate 0 resolved). */
pft_status_t pft_pte_dbt_init(pft_pte_dbt_t *dbt, const pft_pte_dbt_config_t *cfg, void *work,
                              size_t work_len);
/** Back to the state right after init: tracks forgotten, ids restart at 1. */
pft_status_t pft_pte_dbt_reset(pft_pte_dbt_t *dbt);
/** Processes one frame (steps 1-6 above). With in.seq_mode = PFT_SEQ_USE: PFT_ERR_SEQ for a
 *  repeated or past seq (nothing changed); a gap of k <= in.max_gap periods first predicts
 *  every live track over k - 1 periods (no miss counted); a larger gap restarts on this frame
 *  (tracks end, ids go on). */
pft_status_t pft_pte_dbt_update(pft_pte_dbt_t *dbt, const pft_frame_t *frame);
/** Same with a frame given as n_range * n_doppler values in input units. */
pft_status_t pft_pte_dbt_update_real(pft_pte_dbt_t *dbt, const pft_real_t *z);
/**
 * Confirmed tracks after the last update: copies at most max into out, returns how many
 * there are (out may be NULL with max 0; 0 for NULL dbt).
 */
size_t pft_pte_dbt_reports(const pft_pte_dbt_t *dbt, pft_pte_report_t *out, size_t max);
/** Plots of the last frame, copied out as pft_pte_dbt_reports. */
size_t pft_pte_dbt_plots(const pft_pte_dbt_t *dbt, pft_pte_dbt_plot_t *out, size_t max);

#ifdef __cplusplus
}
#endif
#endif
