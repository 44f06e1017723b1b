/**
 * @file pft_tsa.h
 * @brief TSA-AK visual tracker (Song, Zhang & Yin 2014; docs/algorithms.md 4) with its NCV and TS
 *        baselines: the tracker (docs/algorithms.md 4.4), its appearance model (greedy snake with
 *        balloon force and corner relaxation, polygon rasterisation and distance to the
 *        contour, the asymmetric kernel, the 30-bin kernel-weighted RGB histogram and the
 *        Bhattacharyya coefficient, docs/algorithms.md 4.3) and its motion models
 *        (docs/algorithms.md 4.1, 4.2, 4.4 step 6).
 *
 * Use (the calls every pftrack tracker has, in this order):
 *   pft_tsa_config_default(&cfg); cfg.width = W; cfg.height = H; ...change what differs...
 *   pft_tsa_config_check(&cfg, &field);            (PFT_ERR_CONFIG names the field)
 *   static uint8_t work[PFT_TSA_WORKSPACE_BYTES(...)], or pft_tsa_workspace_size(&cfg) bytes
 *   pft_tsa_init(&t, &cfg, work, sizeof work);
 *   pft_tsa_start(&t, &frame1, box, 4);              (the initial box or contour)
 *   per frame: pft_tsa_update(&t, &frame); pft_tsa_estimate(&t, &est);
 *   pft_tsa_reset(&t) goes back to the state right after init (same seed).
 * Results are copied into caller memory (pft_tsa_estimate, pft_tsa_particles,
 * pft_tsa_contour, pft_tsa_template, pft_tsa_kernel); refused input (a bad frame, a bad
 * initial polygon) returns a status and leaves the tracker unchanged.
 *
 * Pixel coordinates (docs/design.md): 0-based, x the column to the right, y the row down; the
 * centre of the pixel in column c and row r is the point (c, r), so a W x H frame covers
 * [-0.5, W - 0.5] x [-0.5, H - 0.5] (OpenCV's convention). Polygon and contour points are
 * integer points, i.e. pixel centres (the greedy snake moves on the pixel grid); a pixel
 * belongs to a polygon when its centre is inside (even-odd rule). The tracked state (x, y) is
 * the position of the kernel origin, the rounded area centroid of the contour's interior when
 * the kernel was built; its pixel is (round(x), round(y)), and the estimate leaves the view when
 * that pixel is outside the frame.
 *
 * Frames: PFT_PIX_RGB888 and PFT_PIX_BGR888 (the histogram is R, G, B in that order either
 * way), and PFT_PIX_U8 grey, which degrades gracefully: the grey value stands for all three
 * channels (the 30 bins hold three copies of a 10-bin grey histogram, rho is the 10-bin grey
 * Bhattacharyya coefficient). Other formats get PFT_ERR_FORMAT.
 *
 * Integer arithmetic (both builds, so float and q16 agree exactly here): grey conversion
 * (77 R + 150 G + 29 B) >> 8, Sobel magnitude isqrt(gx^2 + gy^2) / 4 clamped to 255, every snake
 * energy (Q16 fractions), the distance transform (exact rational comparison, one square root per
 * pixel), kernel weights (Q4: round(16 (c + d))) and histograms (uint32 sums). The
 * Bhattacharyya coefficient: q16 from table square roots of the bins normalised by the total
 * (within 2^-12 of the exact value), float with the FPU's square root. Only the dynamics, the
 * estimates and the configuration use pft_real_t.
 *
 * Speed: per frame the tracker codes once the region its particles' kernels cover (a 16-bit
 * code per pixel: the joint (R, G) bin and the B bin), walks the kernel as row spans adding each
 * weight to two bins, and evaluates each distinct kernel position once; histograms and
 * similarities equal those of pft_tsa_hist and pft_tsa_bhattacharyya (tests/unit/
 * test_tsa_fast.c).
 *
 * Memory: pft_tsa_workspace_size(cfg) / PFT_TSA_WORKSPACE_BYTES(...) bytes of caller
 * workspace, sized by the particle count, the largest target box and the snake's point count
 * and margin. No malloc; the instance struct is the caller's (its layout is in
 * pft/internal/pft_tsa_types.h, for sizeof only).
 *
 * Motion models. Time unit: one frame (Delta t = 1). Positions in pixels, velocities in pixels
 * per frame. Every function works on one axis; the tracker calls it for x and for y.
 *
 * Free model (per axis, state [x, v]):
 *   x_k = x_{k-1} + phi12 v_{k-1} + gamma1 vbar + w_x,   v_k = phi22 v_{k-1} + gamma2 vbar + w_v
 *   phi12 = (1 - e^-b)/b, phi22 = e^-b, gamma1 = 1 - phi12, gamma2 = 1 - phi22   (b = beta)
 * with the integrated Ornstein-Uhlenbeck noise of spectral density q:
 *   Q11 = q/b^2 (1 - 2 phi12(b) + phi12(2b)),  Q12 = q/2 phi12(b)^2,  Q22 = q phi12(2b).
 * For b < 1 every coefficient is evaluated from its power series (so beta -> 0 is exact NCV:
 * phi12 = 1, Q11 = q/3, Q12 = q/2, Q22 = q, and q16 loses no precision to cancellation);
 * for b >= 1 from the closed forms.
 *
 * Conservative fit: X(tau) = s + v tau + a tau^2 over centred frame offsets
 * tau = i - (k-1) in {-(n-1) .. 0}, weights G_i = pi_i exp(-tau^2 / (2 sigma_G^2)). The normal
 * equations are solved by weighted orthogonal polynomials in tau (P0 = 1, P1 = tau - alpha1,
 * P2 = (tau - alpha2) P1 - b1): the same least-squares solution as the adjugate of
 * docs/algorithms.md 4.2 (tests/unit/test_tsa_motion.c checks both against a 64-bit floating-point
 * solve), but with no determinant to cancel, so the Q16.16 build keeps sub-millipixel
 * accuracy. Positions are taken relative to the newest point; sums that can exceed the Q16.16
 * range (tau^4 moments, projections) accumulate in 64 bits in the q16 build.
 * Fallbacks (docs/algorithms.md 4.2): fewer than 3 points, max_order < 2, or
 * det / (A0 A2 A4) = (N1 / A2)(N2 / A4) < 2^-10 gives the weighted constant-velocity fit (a = 0);
 * one point (or N1 / A2 < 2^-10: all weight on one point) gives v = a = 0.
 */
#ifndef PFT_TSA_H
#define PFT_TSA_H

#include "pft/pft_real.h"
#include "pft/pft_rng.h"
#include "pft/pft_workspace.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Histogram bins: 10 per channel, R then G then B. */
#define PFT_TSA_BINS 30u
/** Largest side of the target box: kernel weights (Q4, < 2^16) and histogram sums (uint32) are
 *  sized for it. */
#define PFT_TSA_MAX_SIDE 255u
/** Fewest snake points. */
#define PFT_TSA_MIN_POINTS 8u
/** Most snake points. */
#define PFT_TSA_MAX_POINTS 255u
/** Largest number K of reference points of the conservative fit. */
#define PFT_TSA_MOTION_MAX_K 16u

/** An integer pixel position (a pixel centre). */
typedef struct {
    int16_t x; /**< column (0-based) */
    int16_t y; /**< row (0-based) */
} pft_tsa_pt_t;

/* ======================================== tracker ========================================= */

/** Dynamics of the visual tracker. */
typedef enum {
    /** near constant velocity: the free model at beta = 0 (no pioneer) */
    PFT_TSA_MOTION_NCV = 0,
    /** Kristan's two-stage model: fixed beta, vbar from a constant-velocity fit of the
     *  estimates */
    PFT_TSA_MOTION_TS = 1,
    /** two-stage acceleration: constant-acceleration fit, pioneer particle, adaptive beta */
    PFT_TSA_MOTION_TSA = 2
} pft_tsa_motion_kind_t;

/** Greedy snake parameters (Williams & Shah 1992, balloon of Cohen 1991). */
typedef struct {
    pft_real_t alpha;    /**< continuity weight (default 1) */
    pft_real_t beta;     /**< curvature weight (default 1; 0 at detected corners) */
    pft_real_t gamma;    /**< image (edge) weight (default 1.2) */
    pft_real_t kb;       /**< balloon weight k_b (default 0.3; negative shrinks) */
    pft_real_t corner_c; /**< corner curvature threshold (default 0.25) */
    uint8_t corner_g;    /**< corner edge-strength threshold (default 100) */
    uint8_t margin;      /**< gradient patch margin around the contour box (default 6, >= 3) */
    uint16_t max_w;      /**< largest contour box width the work buffer was sized for */
    uint16_t max_h;      /**< largest contour box height the work buffer was sized for */
} pft_tsa_snake_params_t;

/** Tracker configuration; pft_tsa_config_default() fills the documented defaults. */
typedef struct {
    /** frame width, 8..PFT_CFG_MAX_IMAGE_SIDE (required: the default 0 is refused) */
    uint16_t width;
    /** frame height, 8..PFT_CFG_MAX_IMAGE_SIDE (required: the default 0 is refused) */
    uint16_t height;
    uint16_t max_target_w;        /**< largest contour box width (default 64, 4..255) */
    uint16_t max_target_h;        /**< largest contour box height (default 64, 4..255) */
    uint32_t n_particles;         /**< N normal particles (default 100); TSA adds the pioneer */
    pft_tsa_motion_kind_t motion; /**< TSA (default), TS or NCV */
    pft_real_t beta0;             /**< TSA: beta_1; TS: the fixed beta (default 2) [A] */
    pft_real_t beta_max;          /**< eq. 24 scale (default 6) [P] */
    /** OU spectral density (default 4.07: sqrt(Q22) = 1 px/frame at beta 2) [A] */
    pft_real_t q;
    pft_real_t pos_sd;            /**< extra isotropic position diffusion, px (default 2) [A] */
    /** the diffusion of an axis widens to spread_gain |innovation| (up to spread_max px) when
     *  that exceeds pos_sd; the innovation is the last frame's estimate minus the mean of its
     *  propagated particles [E] (default 1.5; 0: pos_sd always) */
    pft_real_t spread_gain;
    pft_real_t spread_max;        /**< px (default 8) [E] */
    /** K reference points, 1..PFT_TSA_MOTION_MAX_K (default 4 [E]: a fit over 10 points, sigma_G
     *  5, lagged a sudden reversal by several frames and lost the target at 15 px/frame,
     *  5 px/frame^2; docs/results/tsa.md) */
    uint8_t fit_k;
    pft_real_t fit_sigma;         /**< sigma_G (default K/2 = 2) [E] */
    /** pi_i = rho of the reference point (default false: pi_i = 1) [A] */
    bool fit_rho_weights;
    /** TSA/TS: bound on |a| of the conservative fit per axis, px/frame^2 (a as fitted: half the
     *  physical acceleration); 0 = off, the paper's unbounded fit (default 0.5: a physical
     *  1 px/frame^2, the synthetic swing's camera acceleration) [A] */
    pft_real_t fit_a_max;
    /** TSA/TS: bound on |v_hat| and on the pioneer step per axis, px/frame; 0 = off (default 12:
     *  above accel_exp2's 10.6 px/frame) [A]. See pft_tsa_motion_fit_bound() and
     *  docs/results/tsa.md "Real videos" */
    pft_real_t fit_v_max;
    pft_real_t rho_min;           /**< particles with rho below are discarded (default 0.75) [A] */
    /** weight of a kept particle: 0 = rho itself (eq. 22, the paper's linear weight); > 0 =
     *  exp(lik_lambda (rho - rho_best)) (Perez et al. 2002). The 30-bin histogram gives rho
     *  0.8-0.95 on aerial background and 0.99+ within 10 px of the target, so w = rho hardly
     *  localises and TS/TSA's fit of their own estimates drifts or oscillates; see
     *  docs/results/tsa.md (default 300) [A] */
    pft_real_t lik_lambda;
    /** template update when rho(estimate) < theta_u (the paper: 0.9 [A]; default 0 = no update
     *  [E]: under 5% gain flicker every update learned a flicker-shifted histogram and the
     *  tracker drifted off, docs/results/tsa.md) */
    pft_real_t theta_u;
    /** ... but only when rho(estimate) >= this: a misaligned estimate would teach the template
     *  the background (default 0.85) [A] */
    pft_real_t update_rho_min;
    /** ... and only when the new template keeps rho >= this against the first one (stops drift
     *  onto the background; 0: off; default 0.8) [A] */
    pft_real_t anchor_rho_min;
    /** N_iter = min(ceil(k_s / rho), update_max_passes) (default 1.5) [A] */
    pft_real_t k_s;
    uint8_t update_max_passes;    /**< (default 3) [P] */
    /** snake passes on the initial contour, 0 = none: the kernel is the given polygon (default
     *  0 [E]: on the swing sequences 50 passes grew the contour up to 50 % beyond the target,
     *  whose background then shared the template; without them the centre error was lower at
     *  every level and fewer frames failed, docs/results/tsa_ak.md; before: 50 [A]) */
    uint8_t init_passes;
    uint8_t snake_points;         /**< contour points n (default 40, >= PFT_TSA_MIN_POINTS) */
    /** snake weights (defaults of pft_tsa_snake_params_default); max_w / max_h are set from
     *  max_target_w / max_target_h by pft_tsa_init */
    pft_tsa_snake_params_t snake;
    pft_real_t kernel_c;          /**< kernel value c on the contour (default 1) [A] */
    /** a snake result whose area changes by more than this factor (or its inverse) is rejected
     *  (default 2) [A] */
    pft_real_t max_area_change;
    /** loss_search: frames of search (no particle kept) reported WEAK before LOST; without
     *  loss_search: frames with rho(estimate) < rho_min before LOST (default 10) */
    uint16_t lost_frames;
    /** loss handling [E] (default true; docs/algorithms.md 4.4): when no particle (nor TSA's
     *  pioneer) reaches rho_min, the estimate stops at the last good position (no
     *  extrapolation) and the particles search a window around it whose half-size grows by
     *  search_growth px per frame up to the whole frame, one particle per cell of a grid over
     *  it; the best particle, when it reaches rho_min, climbs to its local best (a pattern
     *  search of at most 48 placements); a search particle with rho >= rho_acquire is a
     *  candidate, confirmed when a particle within reacq_radius px of it (placed and refined
     *  the same way) reaches rho_acquire on the next frame: the target is then re-acquired (state
     *  PFT_TSA_REACQUIRED) and tracking restarts there. Every particle, and so every estimate,
     *  stays within the frame enlarged by the target's box on each side. false: the paper's
     *  behaviour (pioneer-only frames, WEAK fallback weights, extrapolation of the fit) */
    bool loss_search;
    /** gain selection [E] (default true; docs/algorithms.md 4.4): the template is kept under
     *  seven camera gains 0.85 .. 1.15 (step 0.05, channel values scaled and clamped to 255);
     *  each tracking frame weighs its particles with the one that best matches the histograms
     *  at the prediction (the prior mean) and at four placements a quarter of the kernel away
     *  from it, gain 1 unless another matches better and reaches rho_min. Under 5 % per-frame gain flicker a white vehicle's body moved between two
     *  bins and the template matched the background better than the target
     *  (docs/results/tsa_ak.md). Search frames use gain 1. false: one template */
    bool gain_select;
    /** candidate and confirmation threshold (default 0.88 [E]: under 5 % gain flicker the
     *  best rho on the target after a forced loss varied over 0.85-0.97 from frame to frame,
     *  so 0.9 needed two good frames in a row; 0.86 re-acquired a background patch;
     *  docs/results/tsa_ak.md) */
    pft_real_t rho_acquire;
    /** background-weighted target model [E] (docs/algorithms.md 4.3): 0 = off (the paper's
     *  template; tsa_paper); else 1 < bg_ring <= 8 (default 2.5 [E]: with bg_alpha 0.5 no
     *  failed frame at 8/3 and 15/5 where the plain template failed 2 and 11, mean centre
     *  error halved, docs/results/tsa_ak.md "Branch tsa14"), the scale of a box around the kernel's box
     *  (its width and height times bg_ring, the same centre): whenever the template is built
     *  (start, template update), the unit-weight histogram o of the ring between the two boxes
     *  (clipped to the frame) weighs each template bin u by v_u = min(o* / o_u, 1), o* the
     *  smallest nonzero bin of o in that channel (1 where o_u = 0), and each channel is
     *  renormalised to the template's total; the same under every gain of gain_select (the
     *  ring read under that gain). Candidates are not weighted. Every rho the tracker uses
     *  (weights, rho_min, rho_acquire) is multiplied by 1 / rho0, rho0 the weighted
     *  template's similarity to the unweighted histogram it was built from (at most 16 times;
     *  not clamped, so the order of placements is kept: pft_tsa_particles reports these
     *  values; the rho and rho_pioneer of pft_tsa_estimate are clamped to 1): the target as
     *  first seen scores 1. Colours
     *  the target shares with its surroundings count less in rho (docs/algorithms.md 4.3) */
    pft_real_t bg_ring;
    /** bg_ring > 0: the share of the weighted template in the one used, 0 < bg_alpha <= 1
     *  (default 0.5 [E]); the rest is the unweighted template (bin by bin, alpha v_u q_u
     *  renormalised + (1 - alpha) q_u), which keeps the target's whole colour distribution in
     *  the model beside its distinctive colours: the weighted template alone (1) slipped 7-16
     *  px off for tens of frames on some 15/5 runs (docs/results/tsa_ak.md "Branch tsa14") */
    pft_real_t bg_alpha;
    /** bg_ring > 0: the similarities a search candidate and its confirmation must bring to
     *  rho_acquire [E] (docs/algorithms.md 4.4): 0 = the tracker's rho alone (scaled by
     *  1 / rho0; branch tsa14); 1 = that and also the rho of the unweighted template (gain 1)
     *  at the best placement (default 1 [E]); 2 = that and also the unscaled rho (the weighted
     *  template's, times rho0). The 1 / rho0 scale lifts background of the target's
     *  distinctive colours too: on vtest.avi with 0 a dark window scored 0.90 and was
     *  re-acquired and held to the end; with 1 TSA-AK re-acquires on people, and the forced
     *  loss of the swing levels re-acquires 50/50 at every level as with 0 (2: 47/50 at 8/3;
     *  docs/results/tsa_ak.md "Branch tsa15"). Without bg_ring: ignored */
    uint8_t acquire_on;
    pft_real_t search_growth;     /**< px per frame (default 16) [A] */
    pft_real_t reacq_radius;      /**< px (default 24: above the largest step expected) [A] */
    /** margin (px) of the per-frame code map around the largest target box: the map holds
     *  (max_target_w + 2 map_margin)(max_target_h + 2 map_margin) 16-bit codes; placements
     *  outside the mapped region read the frame (the same result, slower). 0: no map
     *  (default 48) */
    uint16_t map_margin;
    uint64_t seed;                /**< RNG seed (default 1) */
    /** PFT_SEQ_IGNORE (default: every frame one period after the previous) or PFT_SEQ_USE
     *  (docs/design.md, "Time, sequence numbers and lost frames"): the start frame sets the
     *  reference; a repeated or past seq is refused with PFT_ERR_SEQ (nothing changed); a
     *  frame k periods on, 1 < k <= max_gap, first runs the motion model k - 1 times without a
     *  frame (the conservative fit, the free model's propagation with its noise, so the cloud
     *  widens, and the fit's prediction appended as the reference point of each lost frame);
     *  k > max_gap enters the loss search at the last good position with loss_search, else
     *  is predicted over max_gap periods */
    pft_seq_mode_t seq_mode;
    uint16_t max_gap;             /**< 1..PFT_SEQ_MAX_GAP (default PFT_SEQ_DEFAULT_GAP) */
} pft_tsa_config_t;

/** Tracker state reported with each estimate. */
typedef enum {
    PFT_TSA_IDLE = 0,         /**< initialised, not started */
    PFT_TSA_TRACKING = 1,     /**< some normal particle has rho >= rho_min */
    PFT_TSA_PIONEER_ONLY = 2, /**< every normal particle discarded, the pioneer carried the frame */
    PFT_TSA_WEAK = 3,         /**< no particle (nor the pioneer) reached rho_min: loss_search
                                   holds the estimate at the last good position and searches;
                                   without, weights fall back to rho itself */
    PFT_TSA_LOST = 4,         /**< loss_search: searching for lost_frames frames or more; without:
                                   rho(estimate) < rho_min for lost_frames frames */
    PFT_TSA_OUT_OF_VIEW = 5,  /**< the estimate's pixel is outside the frame */
    PFT_TSA_REACQUIRED = 6    /**< loss_search: the search found the target again this frame */
} pft_tsa_state_t;

/** Results of the last frame. */
typedef struct {
    pft_tsa_state_t state;          /**< tracking / weak / lost / out of view / re-acquired */
    uint32_t frame;                 /**< frames consumed, the start frame included */
    pft_real_t x;                   /**< estimate X_hat (kernel origin), column */
    pft_real_t y;                   /**< estimate X_hat (kernel origin), row */
    pft_real_t vx;                  /**< mean velocity, columns per frame */
    pft_real_t vy;                  /**< mean velocity, rows per frame */
    pft_real_t pioneer_x;           /**< pioneer X_tilde, column (TSA; TS: the fit's prediction) */
    pft_real_t pioneer_y;           /**< pioneer X_tilde, row */
    pft_real_t pioneer_vx;          /**< conservative velocity v_hat, columns per frame */
    pft_real_t pioneer_vy;          /**< conservative velocity v_hat, rows per frame */
    pft_real_t rho;                 /**< rho(X_hat) */
    pft_real_t rho_pioneer;         /**< rho(X_tilde) (TSA) */
    pft_real_t beta;                /**< beta used for this frame's propagation */
    pft_real_t beta_next;           /**< beta for the next frame (eq. 24) */
    uint32_t n_alive;               /**< normal particles with rho >= rho_min */
    bool ref_is_estimate;           /**< eq. 25 took X_hat (else X_tilde) as reference point */
    bool template_updated;          /**< the template was rebuilt this frame */
    uint8_t snake_passes;           /**< snake passes run this frame */
    uint8_t fit_order;              /**< order of the conservative fit (x axis) */
    int16_t box_x0;                 /**< contour bounding box at the estimate: first column */
    int16_t box_y0;                 /**< first row */
    int16_t box_x1;                 /**< last column (inclusive) */
    int16_t box_y1;                 /**< last row (inclusive) */
    uint32_t last_seq;              /**< seq of the frame of the last update (or of the start) */
    uint32_t gap;                   /**< frame periods from the previous accepted frame to this one: the seq difference k with PFT_SEQ_USE (k - 1 frames lost), 1 with PFT_SEQ_IGNORE, 0 on the start frame */
    uint64_t last_timestamp_us;     /**< timestamp_us of that frame */
} pft_tsa_estimate_t;

/** One particle of the last frame. */
typedef struct {
    pft_real_t x;    /**< position (kernel origin), column */
    pft_real_t y;    /**< position (kernel origin), row */
    pft_real_t rho;  /**< its similarity to the template (with bg_ring scaled by 1 / rho0, up to 16) */
} pft_tsa_particle_t;

/** Kernel-weighted colour histogram: bin[b] sums the Q4 kernel weights of the pixels whose
 *  channel value falls in bin b ((v * 10) >> 8 per channel); total sums the weights of the
 *  in-image pixels (so the bins sum to 3 * total). Normalisation is implicit. */
typedef struct {
    uint32_t bin[PFT_TSA_BINS]; /**< summed Q4 kernel weights per bin (10 bins per channel) */
    uint32_t total;             /**< summed Q4 weights of the in-image pixels */
} pft_tsa_hist_t;

/** One kernel pixel: offset from the kernel origin and Q4 weight round(16 (c + d)). */
typedef struct {
    int16_t dx;  /**< column offset from the kernel origin */
    int16_t dy;  /**< row offset from the kernel origin */
    uint16_t w;  /**< Q4 weight */
} pft_tsa_kpix_t;

/** Asymmetric kernel (eqs. 19-20): pixels of the contour's interior R with weight c + d(p). */
typedef struct {
    pft_tsa_kpix_t *pix;  /**< caller storage, cap entries, row-major order */
    uint32_t n;           /**< pixels in R */
    uint32_t cap;         /**< capacity of pix */
    uint32_t sum;         /**< sum of the weights */
    int16_t x0;           /**< bounding box of the offsets: smallest dx */
    int16_t y0;           /**< smallest dy */
    int16_t x1;           /**< largest dx (inclusive) */
    int16_t y1;           /**< largest dy (inclusive) */
} pft_tsa_kernel_t;

/* The instance layout pft_tsa_t (for sizeof; not API). */
#include "pft/internal/pft_tsa_types.h"

/** Work bytes of pft_tsa_snake for boxes up to max_w x max_h and the given margin: a grey
 *  patch and a gradient patch, (max_w + 2 margin + 2)(max_h + 2 margin + 2) + (max_w + 2
 *  margin)(max_h + 2 margin). */
#define PFT_TSA_SNAKE_WORK_BYTES(max_w, max_h, margin)                                        \
    ((size_t)((max_w) + 2u * (margin) + 2u) * (size_t)((max_h) + 2u * (margin) + 2u) +        \
     (size_t)((max_w) + 2u * (margin)) * (size_t)((max_h) + 2u * (margin)))

/**
 * Workspace bytes, as a constant expression: N particles, box max_w x max_h, n_pts snake
 * points, snake margin m, code-map margin map_m (cfg.map_margin). Equal to
 * pft_tsa_workspace_size() for the same values.
 */
#define PFT_TSA_WORKSPACE_BYTES(N, max_w, max_h, n_pts, m, map_m)                              \
    ((size_t)(PFT_WS_ALIGN - 1u) +                                                            \
     4u * PFT_WS_ROUND(((size_t)(N) + 1u) * sizeof(pft_real_t)) +                             \
     4u * PFT_WS_ROUND((size_t)(N) * sizeof(pft_real_t)) +                                    \
     PFT_WS_ROUND(((size_t)(N) + 1u) * sizeof(pft_real_t)) +                                  \
     PFT_WS_ROUND(((size_t)(N) + 1u) * sizeof(pft_weight_t)) +                                \
     PFT_WS_ROUND((size_t)(N) * sizeof(uint32_t)) +                                           \
     2u * PFT_WS_ROUND((size_t)(max_w) * (size_t)(max_h) * sizeof(pft_tsa_kpix_t)) +          \
     PFT_WS_ROUND((size_t)(n_pts) * sizeof(int32_t)) +                                        \
     2u * PFT_WS_ROUND((size_t)(n_pts) * sizeof(pft_tsa_pt_t)) + PFT_WS_ROUND((size_t)(n_pts)) + \
     PFT_WS_ROUND(PFT_TSA_SNAKE_WORK_BYTES(max_w, max_h, m)) +                                \
     2u * PFT_WS_ROUND(PFT_TSA_SPAN_CAP(max_w, max_h, n_pts) * sizeof(pft_tsa_span_t)) +     \
     2u * PFT_WS_ROUND((size_t)(max_w) * (size_t)(max_h) * sizeof(uint16_t)) +                \
     ((map_m) > 0u ? PFT_WS_ROUND(((size_t)(max_w) + 2u * (size_t)(map_m)) *                  \
                                  ((size_t)(max_h) + 2u * (size_t)(map_m)) * sizeof(uint16_t)) \
                   : (size_t)0) +                                                             \
     PFT_WS_ROUND((2u * (size_t)(N) + 4u) * sizeof(uint32_t)) +                               \
     PFT_WS_ROUND((2u * (size_t)(N) + 4u) * sizeof(pft_real_t)))

/** Fills every field of cfg with the default listed in pft_tsa_config_t (width and height 0:
 *  the caller sets them). NULL: no-op. */
void pft_tsa_config_default(pft_tsa_config_t *cfg);

/**
 * PFT_OK if cfg is usable (*field = NULL); PFT_ERR_INVAL for a NULL cfg; PFT_ERR_CONFIG for a
 * refused value, and then *field (when field is not NULL) names the first offending field as
 * written in the struct ("width", "n_particles", "snake.margin").
 */
pft_status_t pft_tsa_config_check(const pft_tsa_config_t *cfg, const char **field);

/** Exact workspace bytes pft_tsa_init needs for cfg; 0 for a NULL or refused cfg. */
size_t pft_tsa_workspace_size(const pft_tsa_config_t *cfg);

/** Checks cfg (copied: it need not outlive the call), carves the workspace and seeds the RNG;
 *  the tracker is IDLE until pft_tsa_start. PFT_ERR_INVAL (NULL), PFT_ERR_CONFIG (refused
 *  cfg), PFT_ERR_NOMEM (work_len below pft_tsa_workspace_size). */
pft_status_t pft_tsa_init(pft_tsa_t *t, const pft_tsa_config_t *cfg, void *work, size_t work_len);

/** Back to the state right after pft_tsa_init (IDLE, the RNG reseeded with cfg.seed), reusing
 *  the workspace. PFT_ERR_INVAL for NULL or an instance that was never initialised. */
pft_status_t pft_tsa_reset(pft_tsa_t *t);

/**
 * Starts (or restarts) tracking on frame 1 from the closed polygon poly[0..n) (a box is its 4
 * corners; pixel-centre coordinates): resamples it to snake_points points, runs init_passes
 * snake passes (a result whose area changed by more than max_area_change, or which outgrew
 * the box limit, is replaced by the resampled polygon), builds the kernel and the template,
 * and places all particles at the kernel origin with zero velocity.
 * Refusals leave instance and workspace byte-identical: PFT_ERR_INVAL for NULL, n < 3, a
 * polygon whose bounding box is not inside the frame or is larger than max_target_w x
 * max_target_h; PFT_ERR_FORMAT for a bad frame (size or format); PFT_ERR_DEGENERATE for a
 * zero-area polygon, a bounding box spanning fewer than 3 px either way (a 1 x 1 or 2 x 2
 * box), or a resampled polygon with no pixel centre inside. Every refusal is decided before
 * the snake runs; a snake result that would give an empty kernel is replaced by the resampled
 * polygon, so nothing fails after it.
 */
pft_status_t pft_tsa_start(pft_tsa_t *t, const pft_frame_t *frame, const pft_tsa_pt_t *poly,
                           uint32_t n);

/**
 * One frame (docs/algorithms.md 4.4 steps 1-7), after k - 1 predictions without a frame across
 * a seq gap of k (cfg.seq_mode). PFT_ERR_INVAL (NULL, not initialised), PFT_ERR_STATE before
 * pft_tsa_start, PFT_ERR_FORMAT for a bad frame, PFT_ERR_SEQ for a repeated or past seq
 * (PFT_SEQ_USE); refusals leave instance and workspace unchanged. Losing the target is not an error: see pft_tsa_estimate_t.state.
 */
pft_status_t pft_tsa_update(pft_tsa_t *t, const pft_frame_t *frame);

/** Copies the results of the last frame (state PFT_TSA_IDLE before pft_tsa_start) into *out.
 *  PFT_ERR_INVAL on NULL. */
pft_status_t pft_tsa_estimate(const pft_tsa_t *t, pft_tsa_estimate_t *out);

/** The particles of the last frame (N, and the pioneer last for TSA): returns how many exist
 *  (0 before pft_tsa_start) and copies at most max of them into out (out may be NULL with
 *  max 0 to ask the count). */
size_t pft_tsa_particles(const pft_tsa_t *t, pft_tsa_particle_t *out, size_t max);

/** The contour placed at the estimate, in frame coordinates: returns how many points exist
 *  (snake_points; 0 before pft_tsa_start) and copies at most max of them into out. */
size_t pft_tsa_contour(const pft_tsa_t *t, pft_tsa_pt_t *out, size_t max);

/** Copies the template histogram in use into *out. PFT_ERR_INVAL on NULL, PFT_ERR_STATE
 *  before pft_tsa_start (out untouched). */
pft_status_t pft_tsa_template(const pft_tsa_t *t, pft_tsa_hist_t *out);

/** Copies the kernel in use into *out, whose pix and cap the caller sets (out->pix receives
 *  out->n pixels; the other fields are overwritten). PFT_ERR_INVAL on NULL, PFT_ERR_STATE
 *  before pft_tsa_start, PFT_ERR_NOMEM when out->cap is below the kernel's pixel count (out
 *  untouched). */
pft_status_t pft_tsa_kernel(const pft_tsa_t *t, pft_tsa_kernel_t *out);

/* ============================ building blocks: appearance ================================= */

/**
 * Histogram of the kernel placed with its origin at pixel (cx, cy). Pixels outside the frame
 * are dropped (a kernel wholly outside gives total 0). PFT_ERR_INVAL on NULL,
 * PFT_ERR_FORMAT for a frame that is not RGB888 / BGR888 / U8 (h untouched).
 */
pft_status_t pft_tsa_hist(const pft_frame_t *frame, const pft_tsa_kernel_t *k, int32_t cx,
                          int32_t cy, pft_tsa_hist_t *h);

/**
 * Bhattacharyya coefficient rho = sum_u sqrt(p_u q_u) of the normalised histograms (eq. 21),
 * in [0, 1]; 0 when either histogram is empty. q16: sum_u s_u(P) s_u(Q) / (3 r(P) r(Q)), where
 * with the even shift s that puts the total T into [2^30, 2^32), r = sqrt(T 2^s) and
 * s_u = sqrt(bin_u 2^s) from a 193-entry table (within 2 of the exact root, so within 2^-12 of
 * the exact coefficient; identical histograms give 1 within 2^-12); float: the same coefficient
 * with the FPU's square root. Bins above the total are taken as the total.
 */
pft_real_t pft_tsa_bhattacharyya(const pft_tsa_hist_t *p, const pft_tsa_hist_t *q);

/** Twice the signed area of a closed polygon (positive when counter-clockwise in x-right,
 *  y-up axes; i.e. clockwise on screen). */
int64_t pft_tsa_poly_area2(const pft_tsa_pt_t *poly, uint32_t n);

/** Even-odd test of pixel centre (x, y) against the closed polygon (half-open in y, so
 *  adjacent polygons never both claim a pixel). */
bool pft_tsa_poly_inside(const pft_tsa_pt_t *poly, uint32_t n, int32_t x, int32_t y);

/** Euclidean distance from (x, y) to the nearest edge of the closed polygon, in 1/16 px,
 *  rounded down (exact integer comparison of squared distances, one 64-bit square root). */
uint32_t pft_tsa_poly_dist_q4(const pft_tsa_pt_t *poly, uint32_t n, int32_t x, int32_t y);

/** Resamples the closed polygon in[0..n_in) to n_out points equally spaced along its
 *  perimeter (rounded to pixels). PFT_ERR_INVAL on NULL, n_in < 3 or zero perimeter. */
pft_status_t pft_tsa_poly_resample(const pft_tsa_pt_t *in, uint32_t n_in, pft_tsa_pt_t *out,
                                   uint32_t n_out);

/**
 * Builds the asymmetric kernel of polygon poly[0..n): rasterises the interior (pixel centres,
 * even-odd rule), weights each pixel c + d(p) (c = c_q4 / 16), and stores the offsets from
 * the rounded area centroid of R, which is returned in *origin (frame coordinates).
 * @param k      the kernel; k->pix and k->cap give its caller storage
 * @param poly   the contour polygon, frame coordinates
 * @param n      its point count, 3..PFT_TSA_MAX_POINTS
 * @param c_q4   the constant part c of the weights, Q4 (16 = 1.0)
 * @param cross  scratch of n int32 (row crossings)
 * @param origin the rounded area centroid of R, frame coordinates (output)
 * PFT_ERR_INVAL: NULL, n < 3 or n > PFT_TSA_MAX_POINTS; PFT_ERR_DEGENERATE: zero area or an
 * empty interior (no pixel centre inside); PFT_ERR_RANGE: a bounding box wider or taller than
 * PFT_TSA_MAX_SIDE (the weight sums are sized for it); PFT_ERR_NOMEM: more pixels than k->cap.
 * On error k is left unchanged.
 */
pft_status_t pft_tsa_kernel_build(pft_tsa_kernel_t *k, const pft_tsa_pt_t *poly, uint32_t n,
                                  uint16_t c_q4, int32_t *cross, pft_tsa_pt_t *origin);

/** Fills the snake defaults listed in pft_tsa_snake_params_t for a work buffer sized for
 *  max_w x max_h boxes. NULL: no-op. */
void pft_tsa_snake_params_default(pft_tsa_snake_params_t *p, uint16_t max_w, uint16_t max_h);

/** PFT_TSA_SNAKE_WORK_BYTES as a function. */
size_t pft_tsa_snake_work_size(uint16_t max_w, uint16_t max_h, uint8_t margin);

/**
 * Runs up to max_passes greedy passes on the closed contour pts[0..n) (frame coordinates,
 * updated in place). Per pass every point moves to the best of its 3x3 neighbourhood under
 * alpha e_cont + beta_i e_curv + gamma e_img + kb e_bal (docs/algorithms.md 4.3); then corners
 * (local maxima of the turning |u_i/|u_i| - u_{i+1}/|u_{i+1}||^2 above corner_c on an edge
 * above corner_g) get beta_i = 0. Stops early when fewer than 10% of the points moved.
 * Points stay inside the frame (1 px from its border). The gradient is recomputed around the
 * contour every margin - 2 passes. The weights are used as Q16.16 integers (rounded).
 * @param frame  the frame (grey or colour; its gradient drives e_img)
 * @param pts    the contour, updated in place
 * @param n      its point count
 * @param prm    the weights and limits (pft_tsa_snake_params_default)
 * @param max_passes most passes to run
 * @param bflags scratch of n bytes (per-point curvature switch)
 * @param work   scratch of pft_tsa_snake_work_size(prm->max_w, prm->max_h, prm->margin) bytes
 * @param work_len its length in bytes
 * @param passes_done passes run (may be NULL)
 * PFT_ERR_INVAL: NULL or n < PFT_TSA_MIN_POINTS or n > PFT_TSA_MAX_POINTS or margin < 3;
 * PFT_ERR_FORMAT: bad frame; PFT_ERR_NOMEM: work shorter than
 * pft_tsa_snake_work_size(max_w, max_h, margin), or a contour box larger than the max_w x max_h
 * the work is laid out for (at the start, or grown by a pass: pts then holds the last pass
 * that fitted).
 */
pft_status_t pft_tsa_snake(const pft_frame_t *frame, pft_tsa_pt_t *pts, uint32_t n,
                           const pft_tsa_snake_params_t *prm, uint32_t max_passes,
                           uint8_t *bflags, void *work, size_t work_len, uint32_t *passes_done);

/* ============================== building blocks: motion =================================== */

/** Coefficients of the free model for one beta and q (Delta t = 1). */
typedef struct {
    pft_real_t beta;   /**< the beta these coefficients are for */
    pft_real_t phi12;  /**< transition: position from velocity */
    pft_real_t phi22;  /**< transition: velocity from velocity */
    pft_real_t gamma1; /**< input gain of vbar into the position */
    pft_real_t gamma2; /**< input gain of vbar into the velocity */
    pft_real_t q11;    /**< process-noise covariance: position variance */
    pft_real_t q12;    /**< process-noise covariance: position-velocity */
    pft_real_t q22;    /**< process-noise covariance: velocity variance */
    pft_real_t l11;    /**< its lower Cholesky factor, (1, 1) */
    pft_real_t l21;    /**< (2, 1) */
    pft_real_t l22;    /**< (2, 2); 0 if Q is singular */
} pft_tsa_motion_free_t;

/**
 * Coefficients for beta in [0, 64] and q in [0, 10000] (PFT_ERR_INVAL otherwise, c
 * untouched). q16: the series branch (beta < 1) is accurate to a few LSB; closed forms use
 * pft_exp.
 */
pft_status_t pft_tsa_motion_free_coef(pft_tsa_motion_free_t *c, pft_real_t beta, pft_real_t q);

/**
 * One free-model step of one axis: x += phi12 v + gamma1 vbar + l11 g1,
 * v = phi22 v + gamma2 vbar + l21 g1 + l22 g2, with g1, g2 standard normal draws.
 */
void pft_tsa_motion_free_step(const pft_tsa_motion_free_t *c, pft_real_t *x, pft_real_t *v,
                              pft_real_t vbar, pft_real_t g1, pft_real_t g2);

/** Result of the conservative fit of one axis. */
typedef struct {
    pft_real_t s;        /**< X(tau) = s + v tau + a tau^2, tau = 0 at the newest point: s */
    pft_real_t v;        /**< v of that fit */
    pft_real_t a;        /**< a of that fit */
    pft_real_t v_pred;   /**< conservative velocity at tau = 1: v + 2a (eq. 15) */
    pft_real_t x_pred;   /**< pioneer position at tau = 1: s + v + a (eq. 16) */
    uint8_t order;       /**< 2 quadratic, 1 constant-velocity fallback, 0 single point */
} pft_tsa_motion_fit_t;

/**
 * Weighted least-squares fit of o[0..n) (oldest first, o[n-1] at tau = 0).
 * @param o         the reference positions of one axis
 * @param n         their count, 1..PFT_TSA_MOTION_MAX_K
 * @param out       the fit (output)
 * @param pi        per-point weights pi_i >= 0 (NULL: all 1)
 * @param sigma_g   width of the Gaussian time weighting (> 0), in frames
 * @param max_order 2 for TSA (constant acceleration), 1 for TS (constant velocity)
 * PFT_ERR_INVAL for NULL o/out, n == 0, n > PFT_TSA_MOTION_MAX_K, sigma_g <= 0, max_order > 2
 * or all weights zero. |o_i - o_{n-1}| should stay below 2048 px (q16 range of the sums).
 */
pft_status_t pft_tsa_motion_fit(const pft_real_t *o, const pft_real_t *pi, uint32_t n,
                                pft_real_t sigma_g, uint8_t max_order, pft_tsa_motion_fit_t *out);

/**
 * Bounds on a conservative fit (not in the paper [A]). With only a few reference points, or
 * when the reference points follow the pioneer where the likelihood is flat, the fitted a and
 * v_hat can grow from frame to frame without limit (docs/results/tsa.md, "Real videos").
 * a_max > 0: a is clamped to [-a_max, a_max] (a as fitted, i.e. half the physical
 * acceleration, px/frame^2) and v_pred, x_pred are recomputed from the clamped a.
 * v_max > 0: v_pred and the pioneer step x_pred - s are clamped to [-v_max, v_max] (px/frame).
 * A bound of 0 is off; a fit inside its bounds is left bit-for-bit unchanged. NULL: no-op.
 */
void pft_tsa_motion_fit_bound(pft_tsa_motion_fit_t *f, pft_real_t a_max, pft_real_t v_max);

/**
 * Beta adaptation (eq. 24): beta_{k+1} = beta_max * rho_p / (rho_e + rho_p) from the
 * similarities of the pioneer (rho_p) and of the estimate (rho_e). Both zero: beta_prev.
 */
pft_real_t pft_tsa_motion_beta_adapt(pft_real_t rho_e, pft_real_t rho_p, pft_real_t beta_max,
                                     pft_real_t beta_prev);

/** Reference-point rule (eq. 25): true when the estimate is the next reference point, false
 *  when the pioneer is. Eq. 25 takes the estimate when rho(pioneer) < rho(estimate); on a tie
 *  it would take the pioneer, which lets a pioneer that left the target (both rho 0) feed the
 *  fit with its own extrapolation: here a tie keeps the estimate [C]. */
static inline bool pft_tsa_motion_ref_is_estimate(pft_real_t rho_e, pft_real_t rho_p)
{
    return !(rho_p > rho_e);
}

#ifdef __cplusplus
}
#endif
#endif
