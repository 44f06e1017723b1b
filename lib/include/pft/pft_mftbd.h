/**
 * @file pft_mftbd.h
 * @brief Multi-frame track-before-detect on radar range-time (or range-Doppler) images:
 *        PTE-TBD (He, Liao, Yang & Sun 2015, parameterized track enhancement) and its batch
 *        baseline DP-TBD (dynamic programming, Yi et al. 2013 style), batch and sliding.
 *
 * The implementable reading of the paper is ALGORITHMS.md section 5 (the paper's equations did
 * not survive; section 5.3 is a reconstruction) and section 6 (measures). This header states
 * the choices a user sees. The Kalman detect-before-track baseline is in pft_dbt.h and shares
 * the input stage and report type declared here.
 *
 * Frames. One frame is one range profile: a 1-row pft_frame_t of n_range cells (range-time
 * image, the paper's experiments), or an n_range x n_doppler range-Doppler map (rows are
 * Doppler cells). Cell u (0-based) has its centre at coordinate u; positions are reported in
 * these cell coordinates (axis 0 range, axis 1 Doppler; axis 1 is 0 for range-time).
 * Velocities are cells per frame.
 *
 * Input stage (pft_mftbd_input_t). U8/U16 pixels become z = pixel_gain*raw + pixel_offset
 * (U16: low bit_depth bits), F32 pixels are taken as z (q16 build: pft_from_f32, integer
 * only). Every algorithm then works on the normalised profile zeta = z/sigma, with
 *  - PFT_MFTBD_NOISE_FIXED: sigma = noise_sigma (Gaussian background);
 *  - PFT_MFTBD_NOISE_CFAR: sigma per cell from a cell-averaging CFAR along range (one row at a
 *    time): sigma^ = sqrt(pi/2) * mean |z| over cfar_ref reference cells on each side beyond
 *    cfar_guard guard cells (a side that leaves the profile is dropped, the other side kept),
 *    floored at noise_sigma. This is the sea-clutter mode (K-distributed clutter is modelled
 *    host-side, ALGORITHMS.md 5.3 [A]). Under Gaussian noise sigma^ is unbiased.
 * zeta is clamped to +-zeta_clip (default 20). The zero-mean data model of ALGORITHMS.md 5.1
 * is assumed: remove any mean level with pixel_offset.
 *
 * Fixed point (q16 build). zeta and every merit are Q16.16. DP merits accumulate at most
 * PFT_MFTBD_MAX_FRAMES frames of |zeta| <= zeta_clip (default: 64 * 20 = 1280, far inside
 * +-32768); all sums use the saturating pft_add, so a pathological configuration saturates
 * instead of wrapping. Operator sums E stay below M_max * sum(g) * zeta_clip (1-D: about
 * 40 * 5 * 20 = 4000). The test statistic T is clamped to +-PFT_MFTBD_T_CLIP so that T^2/2
 * fits. The Gaussian operator weights g = exp(-t^2/2) are tabulated at init for
 * t = 0, 1/64, ..., 3 (nearest entry: |error| <= 0.005); operator paths are quantised to 1/64
 * cell, so each tap is an integer distance looked up in a per-frame table (same in both
 * builds). Very small velocity variances
 * (1e-5 cells^2/frame^2 is 0.66 LSB) are coarse in q16; the defaults keep them >= 2e-4.
 *
 * Memory: everything lives in a caller workspace (ring of the last frames, DP scratch, track
 * table, operator scratch); the *_WORKSPACE_BYTES macros equal the *_workspace_size
 * functions. Per-frame work is bounded by the configuration (see each update function).
 *
 * Bad input (NULL, wrong frame size or format, NaN/Inf in an F32 frame) is refused with a
 * status code before anything changes: the instance and its workspace stay byte-for-byte as
 * they were.
 */
#ifndef PFT_MFTBD_H
#define PFT_MFTBD_H

#include "pft/pft_real.h"
#include "pft/pft_rng.h"
#include "pft/pft_workspace.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Longest frame memory (ring length, DP batch K, initiation batch N, operator length M). */
#define PFT_MFTBD_MAX_FRAMES 64u
/** Largest per-frame DP velocity gate |du| (cells per frame, per axis). */
#define PFT_MFTBD_MAX_GATE 7u
/** Largest number of operator directions L per axis (odd). */
#define PFT_MFTBD_MAX_DIRS 9u
/** Largest scan half-width in steps (scan positions per axis <= 2*16 + 1). */
#define PFT_MFTBD_MAX_SCAN_STEPS 16u
/** Largest operator width: taps per axis (sigma_w is clamped to (TAPS - 1)/6 cells). */
#define PFT_MFTBD_MAX_TAPS 15u
/** Largest number of tracks / targets per instance. */
#define PFT_MFTBD_MAX_TRACKS 16u
/** Largest CFAR reference window per side. */
#define PFT_MFTBD_MAX_CFAR_REF 32u
/** Clamp of the operator test statistic T (T^2/2 stays in Q16.16). */
#define PFT_MFTBD_T_CLIP 150
/** Largest k = floor(pfa * runs) + 1 of the threshold Monte Carlo (top-k kept). */
#define PFT_MFTBD_MC_TOPK 64u
/** Entries of the tabulated Gaussian exp(-t^2/2), t = 0 .. 3 in steps of 1/64. */
#define PFT_MFTBD_GTAB_SIZE 193u
/** Entries of a per-frame weight table in 1/64 cells up to 3 sigma_w (sigma_w <= 7/3). */
#define PFT_MFTBD_GW_SIZE 449u
/** TABLE operators: cells of response kept beyond each end of the profile. */
#define PFT_MFTBD_YPAD 4u

/** Noise level estimate of the input stage. */
typedef enum {
    PFT_MFTBD_NOISE_FIXED = 0, /**< known sigma (Gaussian background) */
    PFT_MFTBD_NOISE_CFAR = 1   /**< cell-averaging CFAR along range (clutter) */
} pft_mftbd_noise_t;

/** Input stage shared by PTE-TBD, DP-TBD and the DBT baseline. */
typedef struct {
    uint16_t n_range;        /**< range cells per frame (frame width), 2..PFT_CFG_MAX_IMAGE_SIDE */
    uint16_t n_doppler;      /**< Doppler cells (frame height): 1 for range-time profiles */
    pft_real_t pixel_gain;   /**< U8/U16: z = gain * raw + offset (default 1) */
    pft_real_t pixel_offset; /**< (default 0) */
    pft_mftbd_noise_t noise; /**< FIXED (default) or CFAR */
    pft_real_t noise_sigma;  /**< FIXED: sigma; CFAR: floor of sigma^ (default 1), > 0 */
    uint8_t cfar_ref;        /**< CFAR reference cells per side, 1..PFT_MFTBD_MAX_CFAR_REF (default 16) */
    uint8_t cfar_guard;      /**< CFAR guard cells per side (default 2) */
    pft_real_t zeta_clip;    /**< |zeta| clamp, > 0 (default 20) */
} pft_mftbd_input_t;

/** Fills the input stage defaults for n_range x n_doppler frames. */
void pft_mftbd_input_default(pft_mftbd_input_t *in, uint16_t n_range, uint16_t n_doppler);
/** PFT_OK if the input stage is usable, PFT_ERR_INVAL otherwise. */
pft_status_t pft_mftbd_input_check(const pft_mftbd_input_t *in);
/**
 * Normalises one frame: zeta[d*n_range + r] = z/sigma (see the file comment).
 * scratch: n_range reals (CFAR only; may be NULL in FIXED mode). Checks the frame first
 * (PFT_ERR_INVAL / PFT_ERR_FORMAT, nothing written).
 */
pft_status_t pft_mftbd_normalize(const pft_mftbd_input_t *in, const pft_frame_t *frame,
                                 pft_real_t *zeta, pft_real_t *scratch);
/** Same from values already in input units (z, n_range * n_doppler; z and zeta distinct). */
pft_status_t pft_mftbd_normalize_real(const pft_mftbd_input_t *in, const pft_real_t *z,
                                      pft_real_t *zeta);

/** Ring of the last frames (normalised). Internal layout; read through the trackers. */
typedef struct {
    pft_real_t *buf; /**< len * cells */
    uint32_t cells;  /**< n_range * n_doppler */
    uint16_t len;    /**< capacity in frames */
    uint16_t count;  /**< frames held (<= len) */
    uint16_t head;   /**< slot of the newest frame */
} pft_mftbd_ring_t;

/** One reported track (or DP detection) at the last frame; same type for PTE, DP and DBT. */
typedef struct {
    uint16_t id;          /**< track id within the instance (1, 2, ...; wraps after 65535 to 1) */
    bool detected;        /**< the method's detection test passed at this frame */
    pft_real_t pos[2];    /**< range cell, Doppler cell (cell centres at integers) */
    pft_real_t vel[2];    /**< cells per frame */
    pft_real_t var[2];    /**< position variance per axis (DP: 0) */
    pft_real_t amplitude; /**< amplitude estimate in sigma units (A / sigma) */
    pft_real_t score;     /**< PTE: max_l T_l*; DP: path merit; DBT: peak zeta of the detection */
    uint32_t age;         /**< frames since the track started (0 at its first report) */
} pft_mftbd_report_t;

/* =========================================== DP-TBD ======================================= */

/**
 * DP-TBD (ALGORITHMS.md 5.4): merit I_1(u) = l_1(u), I_k(u) = l_k(u) + max over the gate
 * |u - u'| <= gate of I_{k-1}(u') (each axis), with l = zeta (unknown amplitude) or the
 * known-amplitude log-likelihood ratio a*zeta - a^2/2. A target is declared when the best
 * final merit exceeds V_T; its path is backtracked; cells within +-cancel of the path are
 * cancelled in every frame and the DP repeated for the next target (up to max_targets).
 * Sliding mode: pft_mftbd_dp_update re-runs the batch over the last K frames at every frame
 * and reports the last state of each path.
 */
typedef struct {
    pft_mftbd_input_t in;  /**< input stage */
    uint8_t frames;        /**< batch length K, 2..PFT_MFTBD_MAX_FRAMES (default 10) */
    uint8_t gate[2];       /**< velocity gate per axis, 0..PFT_MFTBD_MAX_GATE (default 1, 1; axis 1 unused for range-time) */
    pft_real_t amplitude;  /**< known normalised amplitude a for l = a*zeta - a^2/2; 0: unknown, l = zeta (default 0) */
    pft_real_t threshold;  /**< V_T on the final merit (default: Monte Carlo value for the defaults, see pft_mftbd_dp_config_default) */
    uint8_t max_targets;   /**< paths per batch, 1..PFT_MFTBD_MAX_TRACKS (default 4) */
    uint8_t cancel;        /**< cancellation half-width d in cells (default 3) */
} pft_mftbd_dp_config_t;

/**
 * Defaults for n_range x n_doppler frames. threshold is the 1e-3 per-batch false-alarm
 * threshold measured by pft_mftbd_dp_threshold for n_range = 150 range-time profiles
 * (K = 10, gate 1, 20000 runs): 18.9. It grows slowly (about log) with the image size: set
 * it with pft_mftbd_dp_threshold for another geometry or false-alarm probability.
 */
void pft_mftbd_dp_config_default(pft_mftbd_dp_config_t *cfg, uint16_t n_range, uint16_t n_doppler);
/** PFT_OK if cfg is usable, PFT_ERR_INVAL otherwise. */
pft_status_t pft_mftbd_dp_config_check(const pft_mftbd_dp_config_t *cfg);

/** DP-TBD instance (fields private). */
typedef struct {
    pft_mftbd_dp_config_t cfg;
    pft_mftbd_ring_t ring;
    pft_real_t *row;              /**< input scratch (one range row) */
    pft_real_t *ma, *mb;          /**< merit rows */
    uint8_t *psi;                 /**< back-pointers, K * cells (neighbour index) */
    uint8_t *mask;                /**< cancelled cells, K * cells */
    int16_t *paths;               /**< max_targets * K * 2 cells */
    pft_mftbd_report_t *rep;      /**< reports of the last frame */
    pft_mftbd_report_t *prev;     /**< reports of the frame before (id association) */
    uint32_t frames_in;           /**< accepted frames */
    uint16_t next_id;
    uint8_t n_rep, n_prev;
    pft_real_t peak;              /**< best merit of the last batch (first extraction) */
} pft_mftbd_dp_t;

/** @cond internal */
#define PFT_MFTBD_CELLS_(nr, nd) ((size_t)(nr) * (size_t)(nd))
#define PFT_MFTBD_DPCORE_BYTES_(nr, nd, k)                                                      \
    (2u * PFT_WS_ROUND(PFT_MFTBD_CELLS_(nr, nd) * sizeof(pft_real_t)) +                         \
     2u * PFT_WS_ROUND((size_t)(k) * PFT_MFTBD_CELLS_(nr, nd)))
/** @endcond */

/** Workspace bytes of a DP-TBD instance (n_range, n_doppler, frames K, max_targets). */
#define PFT_MFTBD_DP_WORKSPACE_BYTES(nr, nd, k, tmax)                                           \
    ((size_t)(PFT_WS_ALIGN - 1u) +                                                              \
     PFT_WS_ROUND((size_t)(k) * PFT_MFTBD_CELLS_(nr, nd) * sizeof(pft_real_t)) +               \
     PFT_WS_ROUND((size_t)(nr) * sizeof(pft_real_t)) + PFT_MFTBD_DPCORE_BYTES_(nr, nd, k) +     \
     PFT_WS_ROUND((size_t)(tmax) * (size_t)(k) * 2u * sizeof(int16_t)) +                        \
     2u * PFT_WS_ROUND((size_t)(tmax) * sizeof(pft_mftbd_report_t)))

/** Exact workspace bytes for cfg (0 if cfg is invalid). */
size_t pft_mftbd_dp_workspace_size(const pft_mftbd_dp_config_t *cfg);
/** Initialises dp in work[0..len): PFT_ERR_INVAL (bad cfg), PFT_ERR_NOMEM (short work). */
pft_status_t pft_mftbd_dp_init(pft_mftbd_dp_t *dp, const pft_mftbd_dp_config_t *cfg, void *work,
                               size_t len);
/** Forgets all frames and reports (configuration kept). */
void pft_mftbd_dp_reset(pft_mftbd_dp_t *dp);
/**
 * Pushes one frame; once K frames are held, runs the batch over the last K frames and
 * replaces the reports (ids follow a path whose last cell stays within +-cancel cells of a
 * previous report). Work per frame: at most (max_targets + 1) DP passes of
 * K * cells * (2*gate0 + 1) * (2*gate1 + 1) steps.
 */
pft_status_t pft_mftbd_dp_update(pft_mftbd_dp_t *dp, const pft_frame_t *frame);
/** Same with a frame given as n_range * n_doppler values in input units. */
pft_status_t pft_mftbd_dp_update_real(pft_mftbd_dp_t *dp, const pft_real_t *z);
/** Reports of the last frame (declared targets, best merit first); returns their count. */
uint32_t pft_mftbd_dp_reports(const pft_mftbd_dp_t *dp, const pft_mftbd_report_t **out);
/**
 * Backtracked path of report i of the last batch: cells[2*k + a] for frame k = 0 (oldest of
 * the batch) .. K-1 (newest), axis a. NULL if i is out of range.
 */
const int16_t *pft_mftbd_dp_path(const pft_mftbd_dp_t *dp, uint32_t i);
/** Best final merit of the last batch, declared or not (PFT_REAL_MIN before the first batch). */
pft_real_t pft_mftbd_dp_peak(const pft_mftbd_dp_t *dp);
/**
 * Noise-only Monte Carlo threshold: runs batches of K frames of Gaussian noise through the
 * input stage and the DP (first extraction only) and returns in *vt the k-th largest best
 * merit, k = floor(pfa * runs) + 1, so that a fraction pfa of the runs exceeded it.
 * FIXED mode draws noise of sigma = noise_sigma; CFAR mode draws sigma = 16 * noise_sigma (the
 * floor then rarely binds). Uses dp's workspace: the instance is reset (frames forgotten).
 * PFT_ERR_INVAL if pfa is not in (0, 1), runs == 0 or k > PFT_MFTBD_MC_TOPK.
 * Work: runs * (K frames of draws + one DP pass).
 */
pft_status_t pft_mftbd_dp_threshold(pft_mftbd_dp_t *dp, pft_real_t pfa, uint32_t runs,
                                    uint64_t seed, pft_real_t *vt);

/* ========================================== PTE-TBD ======================================= */

/** How PTE-TBD evaluates its operators. */
typedef enum {
    PFT_MFTBD_OP_EXACT = 0, /**< Gaussian taps of width sigma_w = sqrt(sigma_r^2 + P_rr) evaluated per
                                 direction, scan position and frame (ALGORITHMS.md 5.3 as written) */
    PFT_MFTBD_OP_TABLE = 1  /**< range-time only: each frame's matched response
                                 y(p) = sum_u g((u - p)/sigma_r) zeta(u) is computed on a grid of
                                 c_step cells (c_step = 1/Q, Q integer <= 8), lazily in blocks of
                                 8 cells the first time an operator needs it, and kept beside zeta
                                 in the ring; an operator is then one table read per frame (path position rounded to the
                                 grid, error <= c_step/2). The width is sigma_r (the covariance
                                 part of sigma_w is dropped) [A]. Requires zeta_clip <= 64 (the
                                 operator sums then cannot overflow q16 and use plain additions).
                                 Memory: ring.len * (n_range + 8) * Q more reals than EXACT */
} pft_mftbd_op_t;

/** Motion model of a PTE-TBD track, per axis. */
typedef enum {
    PFT_MFTBD_MOTION_CV = 0, /**< constant velocity, white acceleration of intensity q (ALGORITHMS.md 5.1) */
    PFT_MFTBD_MOTION_CA = 1  /**< constant acceleration, white jerk of intensity q; operator paths
                                  curve with the estimated acceleration (ALGORITHMS.md 5.3 step 3) */
} pft_mftbd_motion_t;

/**
 * PTE-TBD (ALGORITHMS.md 5.2-5.3). Per track the state is [r, r', r''] per axis (Kalman; r''
 * stays 0 in the CV model) plus the amplitude (random walk, scalar Kalman). Per frame:
 *  1. predict; 2. operator parameters: length M = min(n_acc, max_len), width
 *     sigma_w = sqrt(sigma_r^2 + P_rr), directions theta_l = r' + (l - (L+1)/2) * dtheta with
 *     dtheta = max(4 sqrt(P_vv)/(L-1), dtheta_min);
 *  3. for each direction, matched operators ending at scan positions
 *     c = r +- scan_sigmas * sqrt(P_rr + sigma_r^2) (step c_step, at most scan_steps steps)
 *     along u(tau) = c + theta*tau + r''*tau^2/2 (tau = 0, -1, .., -(M-1)):
 *     E = sum over the last M frames of g * zeta, G = sum g^2,
 *     T = E / sqrt(G) (N(0,1) under noise);
 *  4. direction likelihood W_l proportional to N(theta_l; r', P_vv + dtheta^2/12) times
 *     sum_c N(c; r, P_rr + sigma_r^2) exp(max(T, 0)^2 / 2); c_l* the best summand (parabola
 *     refined), T_l* its T;
 *  5. per direction a Kalman update with the measurement [c_l*, theta_l] (R from sigma_w,
 *     T_l*, M; ALGORITHMS.md 5.3 step 5) and an amplitude update with E/G;
 *  6. fusion X = sum W_l X_l, P = sum W_l (P_l + spread);
 *  7. detection if max_l T_l* >= eta_t, else a miss; max_misses consecutive misses end the
 *     track. The fused state sets the next frame's operators (closed loop).
 * A straight operator over M = 40 frames measures the velocity averaged over its window, so a
 * CV track lags a manoeuvre by about M/2 frames of acceleration (measured: 1.4 cells in the
 * turn of the air scenario at 15 dB); the CA model curves the operators with the estimated
 * acceleration and removes that lag (docs/results/pte_tbd.md) [A].
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
 * P = sigma_r^2 (H'H)^-1 (r'' = 0 with standard deviation acc_sd0); the amplitude is the mean zeta
 * along the path; n_acc = N. Cells within +-3 sigma_w of live tracks (their state
 * extrapolated back over the batch) are cancelled, and further targets are extracted after
 * cancelling each new path. The initiation runs at every frame while no track is live, else
 * every init_period frames while a track slot is free. Two live tracks closer than dup_cells
 * (axis 0, and axis 1 when 2-D) are duplicates: the one with the lower score ends [A].
 */
typedef struct {
    pft_mftbd_input_t in;      /**< input stage */
    /* Step 2: initiation */
    uint8_t init_frames;       /**< N, 2..PFT_MFTBD_MAX_FRAMES (default 10) */
    uint8_t init_gate[2];      /**< DP gate per axis (default 1, 1) */
    pft_real_t init_threshold; /**< V_T of the N-frame DP (default 18.9: 1e-3 per batch for 150 range cells, see pft_mftbd_dp_config_default) */
    uint8_t init_period;       /**< search period while tracks are live, >= 1 (default 10) */
    /* Step 3: track enhancement */
    uint8_t max_len;           /**< M_max, 2..PFT_MFTBD_MAX_FRAMES (default 40: the paper's template) */
    uint8_t n_dir[2];          /**< L per axis, odd, 1..PFT_MFTBD_MAX_DIRS (default 5, 5) */
    pft_mftbd_motion_t motion; /**< CV or CA (default CA) */
    pft_real_t sigma_r[2];     /**< measurement error sigma_R per axis, cells (default 0.5) */
    pft_real_t q_sd[2];        /**< process noise per axis as sqrt of its intensity q: CV white acceleration (q in cells^2/frame^3) or CA white jerk (cells^2/frame^5) (default CA: 0.002, q = 4e-6; given as a square root because q is below the q16 LSB) */
    pft_real_t acc_sd0[2];     /**< CA: initial acceleration standard deviation, cells/frame^2 (default 0.003) */
    pft_real_t q_amp;          /**< amplitude random-walk variance per frame (default 0.01) */
    pft_real_t dtheta_min;     /**< smallest direction step, cells/frame (default 0.02) */
    pft_real_t c_step;         /**< scan step, cells (default 0.25) */
    uint8_t scan_steps;        /**< largest scan half-width in steps, 1..PFT_MFTBD_MAX_SCAN_STEPS (default 16) */
    pft_real_t scan_sigmas;    /**< scan half-width in standard deviations (default 3) */
    pft_real_t sigma_w_max;    /**< operator width clamp, <= (PFT_MFTBD_MAX_TAPS - 1)/6 (default 2) */
    pft_real_t eta_t;          /**< detection threshold on max_l T_l* (default 3.5) */
    uint8_t max_misses;        /**< consecutive misses that end a track, >= 1 (default 3) */
    uint8_t max_tracks;        /**< 1..PFT_MFTBD_MAX_TRACKS (default 4) */
    pft_real_t dup_cells;      /**< duplicate-track distance (default 1.0; 0 disables) */
    pft_mftbd_op_t op;         /**< operator evaluation (default TABLE for range-time, EXACT for range-Doppler) */
} pft_mftbd_pte_config_t;

/** Defaults of pft_mftbd_pte_config_t for n_range x n_doppler frames. */
void pft_mftbd_pte_config_default(pft_mftbd_pte_config_t *cfg, uint16_t n_range, uint16_t n_doppler);
/** PFT_OK if cfg is usable, PFT_ERR_INVAL otherwise. */
pft_status_t pft_mftbd_pte_config_check(const pft_mftbd_pte_config_t *cfg);

/** One PTE track (internal; read tracks through pft_mftbd_pte_reports). */
typedef struct {
    pft_real_t x[2][4];  /**< per axis [r, 16 r', 256 r'', 0] (scaled, see above) */
    pft_real_t P[2][16]; /**< per axis 4x4 covariance of the scaled state, row-major */
    pft_real_t amp, amp_var;
    pft_real_t score;    /**< max_l T_l* of the last frame */
    uint32_t age;
    uint16_t id;
    uint8_t n_acc;       /**< accumulation count (capped at max_len) */
    uint8_t misses;
    bool live;
    bool detected;
} pft_mftbd_pte_track_t;

/** PTE-TBD instance (fields private). */
typedef struct {
    pft_mftbd_pte_config_t cfg;
    pft_mftbd_ring_t ring;
    pft_real_t *row;
    pft_real_t *ma, *mb;
    uint8_t *psi, *mask;
    int16_t *path;               /**< init_frames * 2 */
    pft_real_t *gtab;            /**< PFT_MFTBD_GTAB_SIZE */
    pft_real_t *gw[2];           /**< per-axis weight tables, PFT_MFTBD_GW_SIZE each (axis 1 only for range-Doppler) */
    pft_real_t *yring;           /**< TABLE: matched responses, ring.len * ny */
    pft_real_t *gq;              /**< TABLE: sum of g^2 of each response point, ny */
    uint8_t *yflag;              /**< TABLE: computed blocks of 8 cells, ring.len * nyblk */
    uint16_t nyblk;              /**< TABLE: blocks per response row */
    pft_real_t ytap[8][PFT_MFTBD_MAX_TAPS]; /**< TABLE: tap weights per grid phase */
    int16_t ytap_lo[8];          /**< TABLE: first tap offset per phase (cells from floor(p)) */
    uint8_t ytap_n[8];           /**< TABLE: taps per phase */
    pft_real_t sigma_y;          /**< TABLE: operator width */
    uint32_t ny;                 /**< TABLE: response points (n_range + 2 PFT_MFTBD_YPAD) * yq */
    uint8_t yq;                  /**< TABLE: grid points per cell (0: EXACT mode) */
    pft_mftbd_pte_track_t *tracks;
    pft_mftbd_report_t *rep;
    pft_real_t *sE, *sG, *sL;    /**< scan accumulators (n_scan0 * n_scan1) */
    pft_real_t *tw[2];           /**< tap weights per axis (n_scan * TAPS) */
    int16_t *tlo[2];             /**< first tap cell, count, weight offset per axis (n_scan * 4) */
    pft_real_t *dres;            /**< per-direction results (n_dir0 * n_dir1 * PFT_MFTBD_DRES_) */
    pft_weight_t *dw;            /**< per-direction weights */
    uint32_t frames_in;
    uint16_t next_id;
    uint16_t since_search;
    uint8_t n_rep;
    uint8_t naxes;
    uint8_t period;              /**< 1/c_step when an integer <= 8 (tap reuse), else 0 */
} pft_mftbd_pte_t;

/** @cond internal */
#define PFT_MFTBD_DRES_ 44u /* reals per direction result: x[2][4], P[2][16], amp, var, logW, T */
#define PFT_MFTBD_MAXU_(a, b) ((a) > (b) ? (a) : (b))
#define PFT_MFTBD_NSCAN_(nd, steps, axis) ((axis) == 0 || (nd) > 1 ? 2u * (size_t)(steps) + 1u : 1u)
#define PFT_MFTBD_NDIR_(nd, l1) ((nd) > 1 ? (size_t)(l1) : 1u)
/** @endcond */

/**
 * Workspace bytes of a PTE-TBD instance: frames n_range x n_doppler, max_len M_max,
 * init_frames N, max_tracks, scan_steps, n_dir[0], n_dir[1], and yq = 1/c_step in TABLE mode
 * (0 in EXACT mode).
 */
#define PFT_MFTBD_PTE_WORKSPACE_BYTES(nr, nd, mlen, ninit, tmax, steps, l0, l1, yq)             \
    ((size_t)(PFT_WS_ALIGN - 1u) +                                                              \
     PFT_WS_ROUND((size_t)PFT_MFTBD_MAXU_(mlen, ninit) * PFT_MFTBD_CELLS_(nr, nd) *             \
                  sizeof(pft_real_t)) +                                                         \
     PFT_WS_ROUND((size_t)(nr) * sizeof(pft_real_t)) + PFT_MFTBD_DPCORE_BYTES_(nr, nd, ninit) + \
     PFT_WS_ROUND((size_t)(ninit) * 2u * sizeof(int16_t)) +                                     \
     PFT_WS_ROUND((size_t)PFT_MFTBD_GTAB_SIZE * sizeof(pft_real_t)) +                          \
     ((nd) > 1 ? 2u : 1u) * PFT_WS_ROUND((size_t)PFT_MFTBD_GW_SIZE * sizeof(pft_real_t)) +      \
     PFT_WS_ROUND((size_t)(tmax) * sizeof(pft_mftbd_pte_track_t)) +                             \
     PFT_WS_ROUND((size_t)(tmax) * sizeof(pft_mftbd_report_t)) +                                \
     3u * PFT_WS_ROUND(PFT_MFTBD_NSCAN_(nd, steps, 0) * PFT_MFTBD_NSCAN_(nd, steps, 1) *        \
                       sizeof(pft_real_t)) +                                                    \
     PFT_WS_ROUND(PFT_MFTBD_NSCAN_(nd, steps, 0) * PFT_MFTBD_MAX_TAPS * sizeof(pft_real_t)) +   \
     PFT_WS_ROUND(PFT_MFTBD_NSCAN_(nd, steps, 1) * PFT_MFTBD_MAX_TAPS * sizeof(pft_real_t)) +   \
     PFT_WS_ROUND(PFT_MFTBD_NSCAN_(nd, steps, 0) * 4u * sizeof(int16_t)) +                      \
     PFT_WS_ROUND(PFT_MFTBD_NSCAN_(nd, steps, 1) * 4u * sizeof(int16_t)) +                      \
     PFT_WS_ROUND((size_t)(l0) * PFT_MFTBD_NDIR_(nd, l1) * PFT_MFTBD_DRES_ * sizeof(pft_real_t)) + \
     PFT_WS_ROUND((size_t)(l0) * PFT_MFTBD_NDIR_(nd, l1) * sizeof(pft_weight_t)) +              \
     (PFT_WS_ROUND((size_t)PFT_MFTBD_MAXU_(mlen, ninit) * ((size_t)(nr) + 2u * PFT_MFTBD_YPAD) *  \
                   (size_t)(yq) * sizeof(pft_real_t)) +                                         \
      PFT_WS_ROUND(((size_t)(nr) + 2u * PFT_MFTBD_YPAD) * (size_t)(yq) * sizeof(pft_real_t)) +   \
      ((yq) > 0 ? PFT_WS_ROUND((size_t)PFT_MFTBD_MAXU_(mlen, ninit) *                           \
                               (((size_t)(nr) + 2u * PFT_MFTBD_YPAD + 7u) / 8u)) : 0u)))

/** Exact workspace bytes for cfg (0 if cfg is invalid). */
size_t pft_mftbd_pte_workspace_size(const pft_mftbd_pte_config_t *cfg);
/** Initialises pte in work[0..len): PFT_ERR_INVAL (bad cfg), PFT_ERR_NOMEM (short work). */
pft_status_t pft_mftbd_pte_init(pft_mftbd_pte_t *pte, const pft_mftbd_pte_config_t *cfg,
                                void *work, size_t len);
/** Forgets frames and tracks (configuration kept; ids restart at 1). */
void pft_mftbd_pte_reset(pft_mftbd_pte_t *pte);
/**
 * Pushes one frame: updates every live track (Step 3), then runs the initiation when due.
 * Work per frame is bounded by max_tracks * L0*L1 * M_max * (2*scan_steps+1)^naxes *
 * TAPS^naxes operator taps plus (max_tracks + 1) DP passes of N * cells * gate steps.
 */
pft_status_t pft_mftbd_pte_update(pft_mftbd_pte_t *pte, const pft_frame_t *frame);
/** Same with a frame given as n_range * n_doppler values in input units. */
pft_status_t pft_mftbd_pte_update_real(pft_mftbd_pte_t *pte, const pft_real_t *z);
/** Live tracks after the last update (in slot order); returns their count. */
uint32_t pft_mftbd_pte_reports(const pft_mftbd_pte_t *pte, const pft_mftbd_report_t **out);
/**
 * Starts a track by hand (a cue from another sensor, or a test), as if initiated now:
 * state pos/vel per axis, diagonal covariance pos_var/vel_var (> 0), amplitude amp, n_acc.
 * Returns the new id in *id. PFT_ERR_INVAL on bad arguments, PFT_ERR_RANGE if no slot is
 * free.
 */
pft_status_t pft_mftbd_pte_start(pft_mftbd_pte_t *pte, const pft_real_t pos[2],
                                 const pft_real_t vel[2], const pft_real_t pos_var[2],
                                 const pft_real_t vel_var[2], pft_real_t amp, uint8_t n_acc,
                                 uint16_t *id);
/**
 * Noise-only Monte Carlo threshold of the initiation DP (N frames, init_gate), as
 * pft_mftbd_dp_threshold. Resets the instance (frames and tracks forgotten).
 */
pft_status_t pft_mftbd_pte_threshold(pft_mftbd_pte_t *pte, pft_real_t pfa, uint32_t runs,
                                     uint64_t seed, pft_real_t *vt);

#ifdef __cplusplus
}
#endif
#endif
