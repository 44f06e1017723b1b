/**
 * @file pft_tbd.h
 * @brief Track-before-detect of dim infrared point targets: RBPF-TBD (Li & Ji 2009) and the
 *        bootstrap PF-TBD baseline (Ristic ch. 11), as a single-target filter and as the
 *        multi-target two-layer manager (one search layer plus one track layer per target).
 *
 * The implementable reading of the algorithms, with its corrections, is docs/algorithms.md
 * sections 1, 2 and 6; this header states the choices a user sees.
 *
 * Coordinates (docs/design.md, "Pixel coordinates"): 0-based, x along the columns, y down the
 * rows; the centre of the pixel in column c and row r is at (c*dx, r*dy), so a target centred on
 * frame pixel (c, r) has x = c*dx, y = r*dy and the image covers [-dx/2, (W - 1/2) dx] x
 * [-dy/2, (H - 1/2) dy]. Estimates, tracks, events, regions and the measurement-model calls
 * all use it. (The paper indexes pixels from 1; the library keeps that frame inside, where the
 * change is an exact shift in q16, and converts at this boundary.) Velocities are in position
 * units per frame period T.
 *
 * Measurement model (per frame, per filter): z(c,r) = h(c,r; x) + noise, with
 *   h(c,r; x) = dx*dy*I/(2*pi*S^2) * exp(-((c*dx - x)^2 + (r*dy - y)^2)/(2*S^2))   (S = psf_sigma)
 * and the per-pixel log likelihood ratio lambda = h*(2z - h)/(2*noise_sigma^2), summed over
 * the (2p+1)^2 window around the window centre pixel (round(x/dx), round(y/dy)) clipped to the
 * image.
 *
 * Pixels: U8 and U16 frames are converted as z = pixel_gain*raw + pixel_offset (U16: only the
 * low bit_depth bits are significant; higher bits are ignored). F32 frames are taken as
 * intensities as they are (no gain/offset); in the q16 build F32 is converted with
 * pft_from_f32 (meant for host or FPU targets). PFT_PIX_RES16 frames (the whitened residual of
 * pft_pre.h, Q8.8 sigma units) are converted as z = pixel_gain*(raw/256) + pixel_offset, exact
 * in both builds, a masked pixel as a zero residual (pixel_offset): with noise_sigma 1, gain 1
 * and offset 0 the stage's output goes to the trackers as it is, no float frame in between;
 * with cfg.frame_format = PFT_PIX_RES16 the manager also keeps no real-valued frame of its own
 * and reads the frame's pixels in place (the same values, the same results).
 * Converted pixel values are clamped to [-32767, 32767] in both builds (the q16 range).
 *
 * Bad input (NULL, wrong size, unsupported format, NaN/Inf in an F32 frame) is refused with
 * a status code before any state is touched: a refused update leaves the instance and its
 * workspace byte-for-byte unchanged.
 *
 * Time and lost frames (docs/design.md, "Time, sequence numbers and lost frames"): with
 * cfg.seq_mode = PFT_SEQ_USE the filters read frame->seq. A frame k periods after the last
 * accepted one (1 < k <= cfg.max_gap) is a frame preceded by k - 1 lost frames: every particle
 * makes k - 1 moves of the dynamics and of the existence chain (deaths with pd; no births,
 * because births are drawn from a frame's pixels) before the usual update, which is the k-step
 * prediction of the model (the RBPF's Kalman velocity takes those moves as its measurements);
 * the manager's residual likelihood predicts the other tracks over k T. k > cfg.max_gap
 * restarts (the standalone filter as after reset, the manager ends every track with an ENDED
 * event and restarts its search layer; track ids stay unique). A repeated seq or one from the
 * past is refused with PFT_ERR_SEQ, state untouched. Estimates, tracks and events carry the seq
 * and timestamp of the frame of their last update. The default PFT_SEQ_IGNORE keeps the
 * behaviour of a source that does not number its frames (seq is recorded only).
 *
 * Determinism: each filter owns a pft_rng_t seeded from cfg.seed (+ layer index in the
 * manager). Random decisions are made on integers (probabilities are quantised to 1/65536 in
 * both builds), so float and q16 builds consume the same integer stream.
 *
 * Memory: everything lives in a caller workspace; see the *_WORKSPACE_BYTES macros, which
 * equal the *_workspace_size functions exactly.
 *
 * Calls, in the order of use (docs/design.md, "One API pattern for every tracker"), for the
 * manager pft_tbd_* and the standalone filter pft_tbd_filter_* alike (they share
 * pft_tbd_config_t): pft_tbd_config_default (or _recommended), change fields,
 * pft_tbd_config_check, *_workspace_size, *_init, *_update per frame, results copied out
 * (pft_tbd_tracks, pft_tbd_events, pft_tbd_search_estimate, pft_tbd_filter_estimate), *_reset
 * to start over. The standalone filter runs cfg.n_search particles of cfg.kind.
 */
#ifndef PFT_TBD_H
#define PFT_TBD_H

#include "pft/pft_real.h"
#include "pft/pft_rng.h"
#include "pft/pft_workspace.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Instances: declared by the caller, layouts in pft/internal/pft_tbd_types.h (not API; included
 * at the end of this header so that sizeof works). */
typedef struct pft_tbd_meas_s pft_tbd_meas_t;     /**< measurement model constants */
typedef struct pft_tbd_filter_s pft_tbd_filter_t; /**< one filter (standalone, or a layer) */
typedef struct pft_tbd_s pft_tbd_t;               /**< the multi-target manager */

/** Largest window half-size p accepted (window (2p+1)^2 pixels). */
#define PFT_TBD_MAX_WINDOW 4u
/** Largest disappearance window length r (the window holds r + 1 frames). */
#define PFT_TBD_MAX_DIS_R 15u
/** Largest number of previous windows compared against in the disappearance test. */
#define PFT_TBD_MAX_DIS_PREV 15u
/** Largest number of end tests in a row that cfg.end_persist can ask for. */
#define PFT_TBD_MAX_END_PERSIST 16u
/** Largest number of search layers (cfg.search_layers). */
#define PFT_TBD_MAX_SEARCH 4u
/** Largest number of birth peaks (cfg.birth_peaks). */
#define PFT_TBD_MAX_PEAKS 4096u

/** Filter algorithm. */
typedef enum {
    PFT_TBD_RBPF = 0, /**< Rao-Blackwellized: particles on (x, y, I), a Kalman filter on velocity */
    PFT_TBD_PF = 1    /**< bootstrap PF-TBD baseline: the full 5-D state is sampled */
} pft_tbd_kind_t;

/** Kalman time-update variant of the RBPF (docs/algorithms.md 2.3 step 3). */
typedef enum {
    PFT_TBD_KF_EXACT = 0, /**< decorrelated, calibrated (default) */
    PFT_TBD_KF_PAPER = 1  /**< as printed: ignores the position/velocity noise correlation */
} pft_tbd_kf_variant_t;

/** Shape of a confirmed track's constraint region D (docs/algorithms.md 2.4, 2.7), before it is
 *  grown by d_margin pixels on each side. */
typedef enum {
    PFT_TBD_D_WINDOW = 0, /**< the (2p+1)^2 window C(x) around the estimate (the paper) */
    PFT_TBD_D_PIXEL = 1,  /**< the estimate's pixel only */
    PFT_TBD_D_NONE = 2    /**< no constraint regions (d_margin ignored); with the residual
                               likelihood the search layer explains a confirmed target away
                               instead of being barred from it */
} pft_tbd_dregion_t;

/**
 * Every parameter of the TBD filters. pft_tbd_config_default() fills the paper's values
 * ([P] in docs/algorithms.md 2.8) and the documented defaults of the assumptions ([A]).
 */
typedef struct {
    /* image and sensor */
    uint16_t width;          /**< image columns (default 20) */
    uint16_t height;         /**< image rows (default 20) */
    pft_real_t dx;           /**< pixel size along x (default 1) */
    pft_real_t dy;           /**< pixel size along y (default 1) */
    pft_real_t psf_sigma;    /**< PSF spread Sigma, position units (default 0.7) */
    pft_real_t noise_sigma;  /**< pixel noise standard deviation sigma (default 3.2, i.e. 6.15 dB) */
    pft_real_t pixel_gain;   /**< U8/U16 conversion z = gain*raw + offset (default 1) */
    pft_real_t pixel_offset; /**< (default 0) */
    uint8_t window;          /**< likelihood window half-size p, 0..PFT_TBD_MAX_WINDOW (default 1: 3x3) */
    /* dynamics */
    pft_real_t T;            /**< frame period (default 1) */
    pft_real_t q1;           /**< position/velocity process noise intensity (default 0.005) */
    pft_real_t q2;           /**< intensity process noise (default 0.01) */
    /* existence */
    pft_real_t pb;           /**< birth probability Pb (default 0.05) */
    pft_real_t pd;           /**< death probability Pd (default 0.05) */
    pft_real_t eta;          /**< initial existence probability P(E_1 = 1) (default 0.05) */
    /* births */
    pft_real_t gamma;        /**< birth candidate threshold on z (default 2) */
    pft_real_t i_min;        /**< birth intensity ~ U[i_min, i_max] (default 10); i_min >= 0 */
    pft_real_t i_max;        /**< (default 30); i_min <= i_max, and the PSF peak i_max*dx*dy/(2 pi S^2) and its ratio to noise_sigma below 32767 */
    pft_real_t vel_mean[2];  /**< birth velocity prior mean (vx, vy) (default 0, 0) [A]; |vel_mean| * T at most the image span (width*dx, height*dy) */
    pft_real_t vel_var[2];   /**< birth velocity prior variances, diagonal P0 (default 1/3 each) [A]; >= 0, sqrt(vel_var) * T at most the image span */
    bool birth_correction;   /**< add log(|B_k|/A_allow) to born particles' log-weights [A] (default false: the paper's eq. 20); with birth_peaks, |B_k| is the number of peaks kept */
    uint16_t birth_peaks;    /**< manager's search layer only: 0 (default) draws births from B_k = {z > gamma} (the paper); K >= 1 draws them uniformly from the K strongest local maxima (3 x 3) of the frame correlated with the PSF's 3 x 3 taps above peak_gamma, so that the births do not spread over the image area (docs/algorithms.md 2.11); 0..PFT_TBD_MAX_PEAKS. The standalone filter ignores it [A] */
    pft_real_t peak_gamma;   /**< threshold of the peaks above, in noise sigmas of the PSF-matched frame (the correlation normalised to unit noise variance) (default 1) */
    uint8_t peak_tile;       /**< with birth_peaks and peak_quota: side (pixels) of the square tiles of the peak quota, from the top left corner; 0 (default) or 1..255; with peak_quota > 0 at least 4, and birth_peaks plus the number of tiles at most width * height [A] */
    uint8_t peak_quota;      /**< 0 (default: off): the K = birth_peaks peaks are the K strongest of the frame. Q >= 1 with peak_tile: the K strongest with at most Q in any tile, so that the peaks of a few cluttered tiles (cloud edges) do not crowd out the rest of the frame (docs/algorithms.md 2.11) [A] */
    pft_real_t birth_share;  /**< 0 (default): a layer with births keeps the existence variable E in every particle (the paper). In (0, 0.95]: Bernoulli form (docs/algorithms.md 2.11): the existence probability is one number updated in closed form, every particle is a position hypothesis of an existing target, and this share of them is replaced by births each frame (weighted by the birth prior pb (1 - P), with the importance correction of the proposal); applies to the search layer and the standalone filter. In the manager the Bernoulli search layer shares a budget of n_search particles per frame with the track layers: with k track layers stepped it runs on max(n_search - k n_track, n_search / 4) of its particles [A] */
    /* decisions */
    pft_real_t theta1;       /**< appearance threshold on the existence probability (default 0.6) */
    uint8_t confirm_frames;  /**< the manager confirms a track when the search layer's P > theta1 on this many consecutive frames (default 1: the paper's single crossing; 0 counts as 1), at most PFT_TBD_MAX_DIS_R + 1 [A] */
    uint8_t dis_r;           /**< disappearance window: r + 1 frames (default r = 2), 0..PFT_TBD_MAX_DIS_R */
    uint8_t dis_prev;        /**< previous windows compared against (default 5), 1..PFT_TBD_MAX_DIS_PREV */
    pft_real_t dis_ratio;    /**< gone when L(W_k) < dis_ratio * L_max (default 0.8, i.e. theta2 = L_max/5); in (0, 1] */
    bool dis_ratio_test;     /**< apply the windowed likelihood-ratio test above (default true, the paper) */
    pft_real_t theta_end;    /**< a track also ends when its layer's existence probability falls below this [A] (default 0: off; the paper uses only the ratio test, which is a hair-trigger at 6 dB, see docs/algorithms.md 2.6) */
    uint8_t d_margin;        /**< constraint region D = C(x) grown by this many pixels on each side [A] (default 0: the paper's C(x)) */
    bool d_current;          /**< build D from the track estimates of the current frame (true) or of the previous one (false, docs/algorithms.md 2.7, default) [A] */
    bool force_constraint;   /**< force E = 0 for search particles whose window centre enters a constraint region [A] (default true) */
    pft_tbd_dregion_t d_region; /**< shape of D (default PFT_TBD_D_WINDOW, the paper) [A] */
    bool residual_search;    /**< joint likelihood in the search layer: its particles are weighed on the frame minus the PSF h of every confirmed track at its current estimate (position and intensity) [A] (default false: the paper's single-target likelihood) */
    bool residual_tracks;    /**< joint likelihood in the track layers: track t is weighed on the frame minus the PSF of every other track at its predicted position x + v T (estimates of the previous frame) [A] (default false) */
    uint8_t residual_margin; /**< the subtracted PSF covers the window C(x) grown by this many pixels, half-size p + margin <= 2 PFT_TBD_MAX_WINDOW (default 1) */
    uint8_t handover_gate;   /**< hand over to a new track layer only the search particles within this many pixels (square half-size, window centres) of the densest (2p+1)^2 block of E = 1 particles; 0 hands over every E = 1 particle (default, docs/algorithms.md 2.7) [A] */
    uint8_t end_lr_frames;   /**< a track also ends when the frame log likelihood ratio of its layer (log_mean_lr) was below end_lr_max in each of the last end_lr_frames frames; 0 turns it off (default), at most PFT_TBD_MAX_DIS_R + 1 [A] */
    pft_real_t end_lr_max;   /**< threshold of the test above (default 0: the frame favours absence) */
    /* sizes */
    uint32_t n_search;       /**< search-layer particles Ns, and the particles of a standalone filter (default 6000) */
    uint32_t n_track;        /**< particles per track layer Nt (default 500) */
    uint16_t max_targets;    /**< track layers available (default 4) */
    pft_tbd_kind_t kind;     /**< RBPF (default) or PF baseline, for every layer and the standalone filter */
    pft_tbd_kf_variant_t kf_variant; /**< RBPF Kalman variant (default exact) */
    uint64_t seed;           /**< RNG seed; layer l of the manager uses seed + l (default 1) */
    /* time */
    pft_seq_mode_t seq_mode; /**< PFT_SEQ_IGNORE (default: every frame is one period T after the previous one) or PFT_SEQ_USE: a frame k > 1 periods after the last accepted one (frame seq numbers) first moves every particle k - 1 times without a frame (existence and dynamics, no births, no weighting), then updates as usual; see "Time and lost frames" above */
    uint16_t max_gap;        /**< PFT_SEQ_USE: a gap of more than max_gap periods restarts the filter or manager on that frame (the manager ends every track: ENDED events) (default PFT_SEQ_DEFAULT_GAP), 1..PFT_SEQ_MAX_GAP */
    /* input */
    pft_pixfmt_t frame_format; /**< 0 (default): frames of any supported format, converted into a real-valued frame that the workspace holds (one real per pixel and a one-pixel border). PFT_PIX_RES16 (needs pixel_gain 1, pixel_offset 0, noise_sigma 1: the stage's residual as it is): only RES16 frames are accepted (others PFT_ERR_FORMAT) and the manager reads them in place, with the same values (res / 256, a masked pixel 0) and the same results, so its workspace holds no frame (PFT_TBD_WORKSPACE_BYTES_RES16; the tracks' PSFs subtracted by the residual likelihood are real-valued patches over the frame); the standalone filter still converts (docs/algorithms.md 2.7) [E] */
    /* sequential confirmation (manager) */
    pft_real_t sprt_accept;  /**< 0 (default): off, a track is reported from its hand-over (the paper). > 0: Wald's sequential probability ratio test on each new track (docs/algorithms.md 2.12): the track layer is tentative after the hand-over, its frame log likelihood ratios (log_mean_lr) are summed from the next frame on, and it is confirmed (reported, CONFIRMED event) when the sum reaches sprt_accept = log((1 - beta)/alpha); a tentative track that ends or whose sum falls to sprt_reject is dropped without being reported (no event). At most 10000 [E] */
    pft_real_t sprt_reject;  /**< lower bound log(beta/(1 - alpha)) of the test above, <= 0, at least -10000 (default -5); only with sprt_accept > 0 [E] */
    /* shape test at the hand-over (manager) */
    pft_real_t shape_ring;   /**< 0 (default): off. > 0: a hand-over needs the search layer's estimate to look like a point on the frame (docs/algorithms.md 2.12): the mean of the 16 pixels at distance 2 (Chebyshev) around the estimate's pixel at most shape_ring times the PSF amplitude fitted to its 3 x 3 pixels; otherwise the search layer's hypothesis is dropped (its particles cleared, as at a hand-over) and no track is made. At most 100 [E] */
    /* start of the sequential test (manager) */
    uint8_t sprt_start;      /**< with sprt_accept > 0, the sum the sequential test starts from at a hand-over (docs/algorithms.md 2.12): 0 (default): 0 (Wald's test on the track layer alone); 1: the search layer's frame log likelihood ratios summed over the frames of its confirmation (the last confirm_frames frames, at most PFT_TBD_MAX_DIS_R + 1), floored at 0; 2: the search layer's log odds of existence at the hand-over, log(P / (1 - P)) with P and 1 - P at least 1e-4, floored at 0. At most 2 [E] */
    /* multi-frame integration of the birth peaks (manager) */
    pft_real_t integ_alpha;  /**< 0 (default): off, the birth peaks are those of the current frame. In (0, 1) (needs birth_peaks > 0 and peak_quota 0): the manager's search layer draws its births from the peaks of a recursive max-filter sum over frames instead (docs/algorithms.md 2.13): on 2 x 2 bins of pixels, S_t(b) = max(0, m_t(b) + integ_alpha max S_{t-1}(q)), m_t(b) the largest value of the PSF-matched unit-noise frame in bin b and q the 3 x 3 bins around b less the platform's shift (pft_tbd_set_shift, 0 by default); the K = birth_peaks strongest 3 x 3 local maxima of S above its frame mean plus peak_gamma of its frame standard deviations are the peaks, each at the pixel of its bin that is largest in the current frame. The factor is used in steps of 1/256; S is kept in 1/64 noise sigmas as two 16-bit sums per bin (PFT_TBD_INTEG_BYTES). The particle filters are unchanged [E] */
    /* existence test of young tracks (manager) */
    uint8_t end_grace_frames; /**< 0 (default): off, every track is ended on theta_end. k >= 1: the existence test of a track whose record age is below k (its first k end tests after the hand-over, or after its confirmation by the sequential test) compares its layer's existence probability with theta_end_grace instead of theta_end (docs/algorithms.md 2.6); the other end tests are unchanged [E] */
    pft_real_t theta_end_grace; /**< the existence threshold of the young tracks above, in [0, 1] (default 0: a young track is not ended on its existence probability); only with end_grace_frames > 0 [E] */
    uint8_t end_persist;     /**< 0 or 1 (default): a track ends at the first end test with its layer's existence probability below its threshold (theta_end, or theta_end_grace while young). k >= 2: only once it has been below it on k end tests in a row (docs/algorithms.md 2.6); the other end tests are unchanged. At most PFT_TBD_MAX_END_PERSIST [E] */
    /* intensity of a new track layer (manager) */
    pft_real_t handover_in_scale; /**< 0 (default) or 1: off, a new track layer starts from the intensities of the search particles handed over to it (the paper). In (0, 1): each handed-over particle's intensity, and the layer's first estimate of it, is multiplied by this factor at the hand-over (docs/algorithms.md 2.7): the confirming frames are the strongest of the target's, so the intensity they hand over is above the target's own. At most 1 [E] */
    /* a track layer that splits (manager) */
    pft_real_t split_px;     /**< 0 (default): off. In [0.5, 16] (px): after the end tests, each live track layer whose particle cloud has parted into two groups (two-means on the live particles' positions: the groups' centroids at least split_px apart, at least twice as far apart squared as the sum of the groups' mean squared spreads, and the smaller group at least split_share of the live particles) hands the smaller group to a new track layer in a free slot, with the layer's dead particles, existence probability and frame log likelihood ratio copied, unless the smaller group's centroid lies within split_px of another track; the layer keeps the larger group, each group refilling the other's slots by systematic resampling (docs/algorithms.md 2.7). At most one split per track and frame; a new layer does not split at the frame it is made [E] */
    pft_real_t split_share;  /**< with split_px > 0: the smallest share of a layer's live particles the smaller group needs, in (0, 0.5]; 0 (default) otherwise, at most 0.5 [E] */
    /* a second target beside a track layer, from the residual (manager) */
    pft_real_t resid_split;  /**< 0 (default): off. In [1, 50] (matched unit-noise sigmas): after the end tests (and split_px's splits), around each track layer that lived before this frame (with resid_split_age > 0 only those with at most resid_split_age updates since their hand-over), the frame minus that layer's own PSF (its intensity at its estimate, untruncated) is filtered with the PSF's 3 x 3 taps (m = sum g z / sqrt(sum g^2) at each pixel centre) on the pixels 1.5 to 5 px from the layer's estimate and at least 3 px from every other track's; when the largest m is at least resid_split in resid_split_frames frames in a row (each frame's peak within 2 px of the last one's), a new track layer starts there in a free slot: the layer's particles copied, moved by the peak's offset from the layer's estimate, born anew (age 0: the velocity mean at vel_mean and its variance at vel_var, as a birth), the layer's existence probability and frame log likelihood ratio copied; a new id, confirmed (or tentative with sprt_accept > 0) as at a hand-over (docs/algorithms.md 2.7). The layer's count restarts after it [E] */
    uint8_t resid_split_frames; /**< with resid_split > 0: the frames in a row the residual peak needs, 1..8 (0, the default, counts as 1); at most 8 [E] */
    uint8_t resid_split_age; /**< with resid_split > 0: only track layers with at most this many updates since their hand-over (or since they were started beside another) are tested; 0 (default): every track layer [E] */
    /* a search layer of several hypotheses (manager) */
    uint8_t search_layers;   /**< 0 or 1 (default): one search layer (one Bernoulli hypothesis for the whole frame). H in 2..PFT_TBD_MAX_SEARCH (needs birth_share > 0 and n_search >= 4 H): H Bernoulli search layers share the n_search particle budget (each runs on a 1/H share of the search layer's particles of that frame, see birth_share), each with its own existence probability and confirmation count; a layer draws its births only from the birth candidates farther than search_sep from the estimate of every other search layer whose existence probability is above search_hold (the layers are stepped from the lowest existence probability of the last frame up, and the estimates of those stepped before a layer are this frame's, the others' the last frame's), so that the layers hold different spots; a layer that passes the hand-over tests (confirm_frames frames above theta1, shape_ring, handover_gate) hands over as the one search layer does, the one with the largest existence probability when several pass at a frame (one hand-over per frame), and it and every other layer whose estimate lies within search_sep of it start over (docs/algorithms.md 2.14). pft_tbd_search_estimate then copies the estimate of the layer with the largest existence probability; pft_tbd_search_layer_estimate copies one layer's [E] */
    pft_real_t search_sep;   /**< with search_layers >= 2: the distance (position units) within which another layer's estimate bars a birth candidate, in [1, 16] (default 0: only with search_layers < 2) [E] */
    pft_real_t search_hold;  /**< with search_layers >= 2: a layer's estimate bars the candidates near it only while its existence probability is above this level, in [0, 1) (default 0) [E] */
} pft_tbd_config_t;

/**
 * Fills cfg with the defaults listed in pft_tbd_config_t: the paper's values.
 *
 * Note (measured by tests/scenario/test_tbd_scenario.c, two targets at 6 dB): the paper's
 * disappearance test (ratio 0.8 on 3-frame windows) ends tracks that are still present, and
 * D = C(x_{k-1}) lets the search layer re-detect a confirmed target at the edge of its region
 * while it blocks births of a target spawned on a confirmed one.
 * pft_tbd_config_recommended() changes [A] options that fix these.
 */
void pft_tbd_config_default(pft_tbd_config_t *cfg);
/**
 * The defaults with the multi-target decisions made robust [A]: dis_ratio_test = false
 * (tracks end on the existence probability instead), theta_end = 0.5; the joint (residual)
 * likelihood in the search and track layers (residual_search, residual_tracks, margin 1)
 * instead of constraint regions (d_region = PFT_TBD_D_NONE: a confirmed target is explained
 * away by subtracting its PSF, so a target spawned on or next to it can be born at once);
 * handover_gate = 2 (the new track starts from the 5x5 block of search particles around the
 * densest 3x3 block, not from clutter particles elsewhere). d_current = true and d_margin = 1
 * are kept for users who switch D back on. docs/results/tbd.md measures each step (two
 * targets at 6 dB, 100 runs).
 */
void pft_tbd_config_recommended(pft_tbd_config_t *cfg);
/**
 * The recommended preset with the search layer's work per frame bounded near its typical frame
 * [A] (issue #12; docs/reliability.md, "Work per frame"): the search layer in Bernoulli form
 * (birth_share = 0.5: every search particle is moved and weighed at every frame, whatever the
 * existence probability, and shares the fixed budget of n_search particles with the track
 * layers, docs/algorithms.md 2.11), half the particles (n_search = 3000, so that its largest
 * frame is not above the recommended preset's) and theta1 = 0.475 (the recommended preset's
 * false-track rate on white noise). docs/results/tbd.md compares its detection with the
 * recommended preset's (100 runs).
 */
void pft_tbd_config_bounded(pft_tbd_config_t *cfg);

/**
 * PFT_OK if cfg is usable; PFT_ERR_INVAL for NULL cfg; PFT_ERR_CONFIG for a refused value, and
 * then *field (when field is not NULL) names the first refused field as written in the struct
 * ("width", "vel_var[1]", "n_search", ...); *field is NULL on success.
 */
pft_status_t pft_tbd_config_check(const pft_tbd_config_t *cfg, const char **field);

/** A pixel box: 0-based frame columns col_lo..col_hi and rows row_lo..row_hi, inclusive.
 *  Parts outside the image are ignored. */
typedef struct {
    int32_t col_lo; /**< first column */
    int32_t col_hi; /**< last column (inclusive) */
    int32_t row_lo; /**< first row */
    int32_t row_hi; /**< last row (inclusive) */
} pft_tbd_region_t;

/** The (2p+1)^2 window C(x) around position (x, y) (not clipped to the image): the
 *  constraint region D of a target estimated at (x, y). An empty region (col_lo > col_hi) for
 *  a NULL cfg or non-positive pixel pitch. */
pft_tbd_region_t pft_tbd_window_region(const pft_tbd_config_t *cfg, pft_real_t x, pft_real_t y);

/** Estimates of one filter at the last frame, from the normalised weights before resampling. */
typedef struct {
    pft_real_t p_exist;     /**< existence probability sum_s w_s E_s */
    pft_real_t x;           /**< weighted mean column position of the E = 1 particles (0-based, see above) */
    pft_real_t y;           /**< weighted mean row position of the E = 1 particles */
    pft_real_t vx;          /**< weighted mean column velocity (RBPF: of the Kalman means) */
    pft_real_t vy;          /**< weighted mean row velocity */
    pft_real_t intensity;   /**< weighted mean intensity */
    pft_real_t pos_cov[3];  /**< weighted spread of the E = 1 positions: xx, xy, yy */
    pft_real_t log_mean_lr; /**< log of the mean unnormalised weight (frame likelihood ratio) */
    pft_real_t n_eff;       /**< effective sample size of the weights */
    bool valid;             /**< false until some particle had E = 1 (x..pos_cov keep their last values) */
    uint32_t last_seq;      /**< seq of the frame of the last update (0 before the first) */
    uint32_t gap;           /**< frame periods from the previous accepted frame to this one: the seq difference k with PFT_SEQ_USE (k - 1 frames lost), 1 with PFT_SEQ_IGNORE, 0 on the first frame after init or reset and on a restart (a gap above max_gap) */
    uint64_t last_timestamp_us; /**< timestamp_us of that frame */
} pft_tbd_estimate_t;

/* ---------------------------------- measurement model -------------------------------------- */

/** Derived constants of the measurement model for cfg, so that it can be evaluated on its own.
 *  PFT_ERR_INVAL for NULL, PFT_ERR_CONFIG for a refused cfg (m untouched). */
pft_status_t pft_tbd_meas_init(pft_tbd_meas_t *m, const pft_tbd_config_t *cfg);

/** PSF contribution h(c, r; x, y, I) of a target at (x, y) with intensity I to the pixel in
 *  column c, row r (0-based; 0 for a NULL m). */
pft_real_t pft_tbd_meas_h(const pft_tbd_meas_t *m, int32_t c, int32_t r, pft_real_t x,
                          pft_real_t y, pft_real_t intensity);

/**
 * Log likelihood ratio of a target (x, y, I) against noise only: sum over the window C(x),
 * clipped to the image, of h*(2z - h)/(2 sigma^2). img is the converted frame, row-major,
 * width*height intensities (img[r*width + c] is the pixel in column c, row r). The Gaussian is
 * evaluated separably: 2(2p+1) exponentials per call. Q16: pixel sums saturate at +-32768.
 */
pft_real_t pft_tbd_meas_llr(const pft_tbd_meas_t *m, const pft_real_t *img, pft_real_t x,
                            pft_real_t y, pft_real_t intensity);

/** Largest half-size accepted by pft_tbd_meas_add_psf. */
#define PFT_TBD_MAX_PSF_HALF (2u * PFT_TBD_MAX_WINDOW)
/** @cond internal */
/* Reals the manager saves per track while its PSF is subtracted from the frame in place. */
#define PFT_TBD_PSF_SAVE_REALS_ ((2u * PFT_TBD_MAX_PSF_HALF + 1u) * (2u * PFT_TBD_MAX_PSF_HALF + 1u))
/** @endcond */

/**
 * img += h(c, r; x, y, intensity) over the (2 half + 1)^2 pixels around (round(x/dx),
 * round(y/dy)), clipped to the image (half is capped at PFT_TBD_MAX_PSF_HALF). A negative
 * intensity subtracts the target: the log likelihood ratio of a second target s on the result,
 * pft_tbd_meas_llr(img - h_t), is the joint log likelihood ratio log p(z | s, t) - log p(z | t)
 * of the pixels where h_t was subtracted. Q16: pixels saturate at +-32768.
 */
void pft_tbd_meas_add_psf(const pft_tbd_meas_t *m, pft_real_t *img, pft_real_t x, pft_real_t y,
                          pft_real_t intensity, uint8_t half);

/* --------------------------------- standalone filter --------------------------------------- */

/** @cond internal */
#define PFT_TBD_PARTICLE_BYTES_(n, kind)                                                        \
    (5u * PFT_WS_ROUND((size_t)(n) * sizeof(pft_real_t)) + PFT_WS_ROUND((size_t)(n)) +         \
     PFT_WS_ROUND((size_t)(n) * sizeof(pft_tbd_slot_t)) + 0u * (size_t)(kind))
/* The constraint mask: one bit per pixel, each row in whole 32-bit words. */
#define PFT_TBD_MASK_BYTES_(w, h)                                                               \
    PFT_WS_ROUND((size_t)(h) * (((size_t)(w) + 31u) / 32u) * sizeof(uint32_t))
#define PFT_TBD_IMAGE_BYTES_(w, h)                                                              \
    (PFT_WS_ROUND(((size_t)(w) + 2u) * ((size_t)(h) + 2u) * sizeof(pft_real_t)) +                \
     PFT_TBD_MASK_BYTES_(w, h) + PFT_WS_ROUND((size_t)(w) * (size_t)(h) * sizeof(uint32_t)))
#define PFT_TBD_TAB_BYTES_ PFT_WS_ROUND(sizeof(pft_tbd_tab_t))
/** @endcond */

/** Workspace bytes of a standalone filter with n particles of the given kind on a w x h image
 *  (constant expression; with n = cfg.n_search, kind = cfg.kind, w x h = cfg.width x
 *  cfg.height it equals pft_tbd_filter_workspace_size). */
#define PFT_TBD_FILTER_WORKSPACE_BYTES(n, kind, w, h)                                           \
    ((size_t)(PFT_WS_ALIGN - 1u) + PFT_TBD_IMAGE_BYTES_(w, h) + PFT_TBD_TAB_BYTES_ +             \
     PFT_TBD_PARTICLE_BYTES_(n, kind))

/** Workspace bytes pft_tbd_filter_init needs for cfg (cfg.n_search particles of cfg.kind);
 *  0 for a NULL or refused cfg. */
size_t pft_tbd_filter_workspace_size(const pft_tbd_config_t *cfg);

/**
 * Initialises a standalone filter with births: cfg.n_search particles of cfg.kind (the other
 * manager sizes are not used). All particles start with E = 0; the first update draws births
 * with probability eta. The config is copied.
 * @return PFT_ERR_INVAL for NULL arguments, PFT_ERR_CONFIG for a refused cfg, PFT_ERR_NOMEM
 *         when work_len is short (a refusal writes nothing: instance and workspace unchanged).
 */
pft_status_t pft_tbd_filter_init(pft_tbd_filter_t *f, const pft_tbd_config_t *cfg, void *work,
                                 size_t work_len);

/** Back to the state right after pft_tbd_filter_init (same seed, workspace reused).
 *  PFT_ERR_INVAL for NULL, PFT_ERR_STATE for a filter that is not a standalone one. */
pft_status_t pft_tbd_filter_reset(pft_tbd_filter_t *f);

/** One frame: existence prediction, propagation and births, weighting, estimates,
 *  systematic resampling (after k - 1 moves without a frame across a seq gap of k, see "Time
 *  and lost frames"). Same as pft_tbd_filter_update_ex with no exclusion regions. */
pft_status_t pft_tbd_filter_update(pft_tbd_filter_t *f, const pft_frame_t *frame);

/**
 * One frame with exclusion regions: births are not drawn inside any region (the importance
 * correction counts only allowed pixels) and, when cfg.force_constraint is set, particles
 * whose window centre falls inside a region get E = 0. regions may be NULL when n_regions
 * is 0. Refused input (PFT_ERR_INVAL / PFT_ERR_FORMAT / PFT_ERR_SEQ for a repeated or past seq
 * with PFT_SEQ_USE) leaves the filter untouched.
 */
pft_status_t pft_tbd_filter_update_ex(pft_tbd_filter_t *f, const pft_frame_t *frame,
                                      const pft_tbd_region_t *regions, size_t n_regions);

/** Copies the estimates of the last update (all zero and valid == false before the first). */
pft_status_t pft_tbd_filter_estimate(const pft_tbd_filter_t *f, pft_tbd_estimate_t *out);

/**
 * The log likelihood ratio the filter weighs a particle with, for a target (x, y, intensity)
 * (0-based position) on the frame of the last accepted update: the windowed sum of
 * pft_tbd_meas_llr as the filter evaluates it (on the whitened frame; for window 1 with
 * tabulated PSF taps, docs/fixed_point.md "Particle kernels"). 0 for a NULL filter, before the
 * first update, for a layer of a manager and for a window centre outside the image.
 */
pft_real_t pft_tbd_filter_llr(const pft_tbd_filter_t *f, pft_real_t x, pft_real_t y,
                              pft_real_t intensity);

/* --------------------------------- multi-target manager ------------------------------------ */

/** A confirmed track. */
typedef struct {
    uint32_t id;            /**< 1, 2, ...: stable for the track's life, never reused */
    pft_real_t x;           /**< column position estimate at the last frame */
    pft_real_t y;           /**< row position estimate at the last frame */
    pft_real_t vx;          /**< column velocity estimate */
    pft_real_t vy;          /**< row velocity estimate */
    pft_real_t intensity;   /**< intensity estimate */
    pft_real_t pos_cov[3];  /**< position spread xx, xy, yy */
    pft_real_t p_exist;     /**< track layer existence probability */
    pft_real_t log_mean_lr; /**< track layer frame log likelihood ratio */
    uint32_t first_frame;   /**< frame number at which it was confirmed */
    uint32_t age;           /**< frames since confirmation (0 at the confirmation frame) */
    uint32_t last_seq;      /**< seq of the frame of its last update */
    uint64_t last_timestamp_us; /**< timestamp_us of that frame */
    pft_real_t sprt_llr;    /**< with cfg.sprt_accept > 0: the sum of the layer's frame log likelihood ratios from the frame after its hand-over to its confirmation (then kept), started from the value cfg.sprt_start gives (0 by default); 0 otherwise */
    uint8_t end_below;      /**< with cfg.end_persist >= 2: the end tests in a row, up to this frame, at which its layer's existence probability was below its threshold; 0 otherwise */
    uint8_t search_layer;   /**< the search layer that handed the track over: 0 .. cfg.search_layers - 1 (0 with one search layer; docs/algorithms.md 2.14); PFT_TBD_LAYER_NONE for a track made by a split of a track layer (cfg.split_px, cfg.resid_split) */
} pft_tbd_track_t;

/** pft_tbd_track_t.search_layer of a track that no search layer handed over (a split). */
#define PFT_TBD_LAYER_NONE 255u

/** What an event reports. */
typedef enum {
    PFT_TBD_EV_CONFIRMED = 1, /**< the search layer's P > theta1: a new track (with cfg.sprt_accept > 0: its sequential test accepted it) */
    PFT_TBD_EV_ENDED = 2      /**< disappearance declared: the track was removed */
} pft_tbd_event_kind_t;

/** Something that happened during the last update. */
typedef struct {
    pft_tbd_event_kind_t kind; /**< confirmed or ended */
    uint32_t id;            /**< track id */
    uint32_t frame;         /**< frame number of the update */
    pft_real_t x;           /**< column position at the event (ENDED: the last estimate) */
    pft_real_t y;           /**< row position at the event */
    uint32_t last_seq;      /**< seq of the track's last update: this frame, or the previous accepted frame for a track ended by a gap restart */
    uint64_t last_timestamp_us; /**< timestamp_us of that frame */
} pft_tbd_event_t;

/** @cond internal */
#define PFT_TBD_EVENT_BYTES_(maxt) PFT_WS_ROUND((size_t)((maxt) + 1u) * sizeof(pft_tbd_event_t))
/** @endcond */

/** @cond internal */
/* The manager's birth candidate slots: every pixel (B_k, peaks = 0), or min(peaks, w h). */
#define PFT_TBD_CAND_N_(w, h, peaks)                                                            \
    ((size_t)(peaks) > 0u && (size_t)(peaks) < (size_t)(w) * (size_t)(h)                        \
         ? (size_t)(peaks)                                                                      \
         : (size_t)(w) * (size_t)(h))
/* The peak scan: six image rows of scratch and one real per peak. */
#define PFT_TBD_PEAK_BYTES_(w, peaks)                                                           \
    ((size_t)(peaks) > 0u ? PFT_WS_ROUND(6u * (size_t)(w) * sizeof(pft_real_t)) +                \
                                PFT_WS_ROUND((size_t)(peaks) * sizeof(pft_real_t))             \
                          : 0u)
/* The manager's real-valued frame with its border (none when the frame is read in place), and
 * what reading it in place needs instead: the patches' rectangles, per-row flags, one row with
 * its border and the exact kernel's (2 PFT_TBD_MAX_WINDOW + 1)^2 window. */
#define PFT_TBD_FRAME_BYTES_(w, h)                                                              \
    PFT_WS_ROUND(((size_t)(w) + 2u) * ((size_t)(h) + 2u) * sizeof(pft_real_t))
#define PFT_TBD_INPLACE_BYTES_(max_targets, w, h)                                               \
    (PFT_WS_ROUND(4u * (size_t)(max_targets) * sizeof(int32_t)) + PFT_WS_ROUND((size_t)(h)) +   \
     PFT_WS_ROUND(((size_t)(w) + 2u + (2u * PFT_TBD_MAX_WINDOW + 1u) *                          \
                                         (2u * PFT_TBD_MAX_WINDOW + 1u)) *                      \
                  sizeof(pft_real_t)))
#define PFT_TBD_MGR_BYTES_(n_search, n_track, max_targets, kind, w, h, peaks)                  \
    (PFT_TBD_FRAME_BYTES_(w, h) + PFT_TBD_MGR_REST_(n_search, n_track, max_targets, kind, w, h, peaks))
#define PFT_TBD_MGR_REST_(n_search, n_track, max_targets, kind, w, h, peaks)                   \
    ((size_t)(PFT_WS_ALIGN - 1u) +                                                              \
     PFT_TBD_MASK_BYTES_(w, h) + PFT_WS_ROUND(PFT_TBD_CAND_N_(w, h, peaks) * sizeof(uint32_t)) + \
     PFT_TBD_TAB_BYTES_ + PFT_TBD_PARTICLE_BYTES_(n_search, kind) +                             \
     (size_t)(max_targets) * PFT_TBD_PARTICLE_BYTES_(n_track, kind) +                           \
     PFT_WS_ROUND((size_t)(max_targets) * sizeof(pft_tbd_filter_t)) +                           \
     PFT_WS_ROUND((size_t)(max_targets) * sizeof(pft_tbd_track_t)) +                            \
     PFT_TBD_EVENT_BYTES_(max_targets) +                                                        \
     PFT_WS_ROUND((size_t)(max_targets) * PFT_TBD_PSF_SAVE_REALS_ * sizeof(pft_real_t)) +       \
     PFT_WS_ROUND(((size_t)(w) + (size_t)(h) + 1u) * sizeof(uint32_t)) +                        \
     PFT_TBD_PEAK_BYTES_(w, peaks))
/** @endcond */

/** Workspace bytes of the manager with cfg.birth_peaks = 0 (constant expression; with the
 *  sizes, kind and image of cfg it equals pft_tbd_workspace_size). Per pixel: the whitened
 *  frame with its one-pixel border (one real), the constraint mask and the birth candidate list
 *  B_k (one index per pixel); per image line, the hand-over gate's counts. */
#define PFT_TBD_WORKSPACE_BYTES(n_search, n_track, max_targets, kind, w, h)                    \
    PFT_TBD_MGR_BYTES_(n_search, n_track, max_targets, kind, w, h, 0u)

/** Workspace bytes of the manager with cfg.birth_peaks = peaks (constant expression; with the
 *  sizes, kind, image and birth_peaks of cfg it equals pft_tbd_workspace_size). With peaks = 0
 *  it equals PFT_TBD_WORKSPACE_BYTES. With peaks = K >= 1 the candidate list holds K pixel
 *  indices instead of one per pixel (the uniform proposal of a frame without peaks draws the
 *  n-th allowed pixel from per-row counts instead of a list), and the peak scan adds six image
 *  rows and one real per peak. */
#define PFT_TBD_WORKSPACE_BYTES_PEAKS(n_search, n_track, max_targets, kind, w, h, peaks)       \
    PFT_TBD_MGR_BYTES_(n_search, n_track, max_targets, kind, w, h, peaks)

/** Workspace bytes of the manager with cfg.frame_format = PFT_PIX_RES16 and cfg.birth_peaks =
 *  peaks (constant expression; with the sizes, kind, image and birth_peaks of cfg it equals
 *  pft_tbd_workspace_size): PFT_TBD_WORKSPACE_BYTES_PEAKS without the real-valued frame (one
 *  real per pixel and the border), plus per line one row of reals and one flag byte, per
 *  track slot one patch rectangle, and one (2 PFT_TBD_MAX_WINDOW + 1)^2 window of reals. */
#define PFT_TBD_WORKSPACE_BYTES_RES16(n_search, n_track, max_targets, kind, w, h, peaks)       \
    (PFT_TBD_MGR_REST_(n_search, n_track, max_targets, kind, w, h, peaks) +                     \
     PFT_TBD_INPLACE_BYTES_(max_targets, w, h))

/** Workspace bytes that cfg.integ_alpha > 0 adds to the PFT_TBD_WORKSPACE_BYTES* figure of a
 *  w x h image (constant expression): two 16-bit sums per 2 x 2 bin of pixels (1 byte per
 *  pixel). */
#define PFT_TBD_INTEG_BYTES(w, h)                                                               \
    (2u * PFT_WS_ROUND((((size_t)(w) + 1u) / 2u) * (((size_t)(h) + 1u) / 2u) * sizeof(uint16_t)))

/** Workspace bytes that cfg.search_layers = layers >= 2 adds to the PFT_TBD_WORKSPACE_BYTES*
 *  (and PFT_TBD_INTEG_BYTES) figure of a w x h image with cfg.birth_peaks = peaks (constant
 *  expression): the layers beyond the first (one filter record each; their particles are
 *  slices of the n_search particles) and one list of the birth candidates a layer may draw
 *  from. 0 for layers < 2. */
#define PFT_TBD_SEARCH_BYTES(layers, w, h, peaks)                                               \
    ((size_t)(layers) >= 2u                                                                     \
         ? PFT_WS_ROUND(((size_t)(layers) - 1u) * sizeof(pft_tbd_filter_t)) +                   \
               PFT_WS_ROUND(PFT_TBD_CAND_N_(w, h, peaks) * sizeof(uint32_t))                    \
         : 0u)

/** Workspace bytes pft_tbd_init needs for cfg; 0 for a NULL or refused cfg. */
size_t pft_tbd_workspace_size(const pft_tbd_config_t *cfg);

/**
 * Initialises the manager (docs/algorithms.md 2.7): one search layer (cfg.n_search particles,
 * births outside the constraint regions) and up to cfg.max_targets track layers (cfg.n_track
 * particles each, no births); no tracks, the search layer all E = 0. The config is copied.
 * PFT_ERR_INVAL for NULL arguments, PFT_ERR_CONFIG for a refused cfg, PFT_ERR_NOMEM for a
 * short workspace.
 */
pft_status_t pft_tbd_init(pft_tbd_t *t, const pft_tbd_config_t *cfg, void *work, size_t work_len);

/** Back to the state right after pft_tbd_init (same seeds, no tracks, ids from 1 again,
 *  workspace reused). PFT_ERR_INVAL for NULL, PFT_ERR_STATE for an uninitialised manager. */
pft_status_t pft_tbd_reset(pft_tbd_t *t);

/**
 * One frame (docs/algorithms.md 2.7): update every track layer (with residual_tracks, each on the
 * frame minus the other tracks' PSFs at their predicted positions) and test disappearance,
 * rebuild the constraint regions from the remaining tracks' estimates, update the search
 * layer (with residual_search, on the frame minus every remaining track's PSF at its current
 * estimate; births from B_k or, with birth_peaks, from peaks), and confirm a new track when its
 * existence probability has exceeded theta1 on confirm_frames consecutive frames (if a track
 * slot is free; otherwise the search layer keeps running without confirming). With
 * PFT_SEQ_USE, a seq gap of k <= max_gap first moves every layer k - 1 times without a frame; a
 * gap above max_gap ends every track (ENDED events) and restarts the search layer first.
 * Refused input (PFT_ERR_INVAL, PFT_ERR_FORMAT, PFT_ERR_SEQ) leaves everything untouched.
 */
pft_status_t pft_tbd_update(pft_tbd_t *t, const pft_frame_t *frame);

/**
 * The platform's shift of the scene from the last accepted frame to the next frame given to
 * pft_tbd_update, in pixels (dx along the columns, dy down the rows: a fixed point of the scene
 * at (x, y) in the last frame is at (x + dx, y + dy) in the next). Only the multi-frame
 * integration of the birth peaks (cfg.integ_alpha > 0, docs/algorithms.md 2.13) reads it: the
 * sum of the last frames is moved by the shift, in whole 2 x 2 bins (the remainder is carried
 * to the next frame). It holds for the next accepted update only (0 when not set: a sensor
 * that does not move). PFT_ERR_INVAL for NULL t, or |dx| > width or |dy| > height (NaN
 * included; nothing changed); PFT_ERR_STATE for an uninitialised manager.
 */
pft_status_t pft_tbd_set_shift(pft_tbd_t *t, pft_real_t dx, pft_real_t dy);

/** Copies up to max confirmed tracks (ordered by id) into out; returns how many exist (out may
 *  be NULL with max 0 to ask the count). Tentative tracks of the sequential test
 *  (cfg.sprt_accept > 0) are not reported, so their ids may be missing from the sequence. */
size_t pft_tbd_tracks(const pft_tbd_t *t, pft_tbd_track_t *out, size_t max);

/** Copies up to max tentative tracks of the sequential test (cfg.sprt_accept > 0: handed over
 *  to a track layer, not yet confirmed; first_frame 0) into out, ordered by id, in the same
 *  coordinates as pft_tbd_tracks; returns how many exist (out may be NULL with max 0 to ask the
 *  count). A track's hand-over frame has age 0 and the search layer's estimate as its position.
 *  0 when the test is off or t is NULL. A flight pipeline feeds these to the scene-motion test
 *  with its tentative flag (pft_tbd_scene.h). */
size_t pft_tbd_tentative(const pft_tbd_t *t, pft_tbd_track_t *out, size_t max);

/** Copies up to max events of the last update into out; returns how many happened. */
size_t pft_tbd_events(const pft_tbd_t *t, pft_tbd_event_t *out, size_t max);

/** Copies the search layer's estimate at the last frame (p_exist is the appearance
 *  statistic). With cfg.search_layers = H >= 2: the estimate of the layer with the largest
 *  existence probability (the first such layer). */
pft_status_t pft_tbd_search_estimate(const pft_tbd_t *t, pft_tbd_estimate_t *out);

/** Copies search layer h's estimate at the last frame (h < cfg.search_layers, or h = 0 with
 *  one search layer). PFT_ERR_INVAL for NULL arguments or h out of range. */
pft_status_t pft_tbd_search_layer_estimate(const pft_tbd_t *t, uint32_t h, pft_tbd_estimate_t *out);

/**
 * Copies up to max birth candidate pixels of the search layer at the last update into out
 * (0-based row-major indices, row * width + column) and returns how many there were: with
 * cfg.birth_peaks = K, the peaks kept (at most K; ordered by the scan's heap, not by value);
 * otherwise the pixels of B_k = {z > gamma}; every allowed pixel in raster order when there was
 * no peak or B_k was empty. 0 before the first update, after an update that confirmed a track
 * with cfg.handover_gate > 0, and for NULL t. out may be NULL with max 0 to ask the count.
 */
size_t pft_tbd_birth_candidates(const pft_tbd_t *t, uint32_t *out, size_t max);

/** Frame number of the last accepted update (1-based; 0 before the first and for NULL). */
uint32_t pft_tbd_frame(const pft_tbd_t *t);

#ifdef __cplusplus
}
#endif

#include "pft/internal/pft_tbd_types.h"
#endif
