/**
 * @file pft_tsa.h
 * @brief Motion models of the TSA-AK tracker (Song, Zhang & Yin 2014; ALGORITHMS.md 4.1, 4.2,
 *        4.4 step 6): Kristan's free model with parameter beta (NCV at beta = 0), the
 *        conservative weighted least-squares fit over the last K reference points (constant
 *        velocity for Kristan's TS model, constant acceleration for TSA), the pioneer
 *        prediction, the beta adaptation and the reference-point rule.
 *
 * Time unit: one frame (Delta t = 1). Positions in pixels, velocities in pixels per frame.
 * Every function works on one axis; the tracker calls it for x and for y.
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
 * ALGORITHMS.md 4.2 (tests/unit/test_tsa_motion.c checks both against a 64-bit floating-point solve), but with
 * no determinant to cancel, so the Q16.16 build keeps sub-millipixel accuracy. Positions are
 * taken relative to the newest point; sums that can exceed the Q16.16 range (tau^4 moments,
 * projections) accumulate in 64 bits in the q16 build.
 * Fallbacks (ALGORITHMS.md 4.2): fewer than 3 points, max_order < 2, or
 * det / (A0 A2 A4) = (N1 / A2)(N2 / A4) < 2^-10 gives the weighted constant-velocity fit (a = 0);
 * one point (or N1 / A2 < 2^-10: all weight on one point) gives v = a = 0.
 */
#ifndef PFT_TSA_H
#define PFT_TSA_H

#include "pft/pft_real.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Largest number K of reference points of the conservative fit. */
#define PFT_MOTION_MAX_K 16u

/** Dynamics of the visual tracker. */
typedef enum {
    PFT_MOTION_NCV = 0, /**< near constant velocity: the free model at beta = 0 (no pioneer) */
    PFT_MOTION_TS = 1,  /**< Kristan's two-stage model: fixed beta, vbar from a constant-velocity fit of the estimates */
    PFT_MOTION_TSA = 2  /**< two-stage acceleration: constant-acceleration fit, pioneer particle, adaptive beta */
} pft_motion_kind_t;

/** Coefficients of the free model for one beta and q (Delta t = 1). */
typedef struct {
    pft_real_t beta;
    pft_real_t phi12, phi22;   /**< transition */
    pft_real_t gamma1, gamma2; /**< input gains of vbar */
    pft_real_t q11, q12, q22;  /**< process-noise covariance */
    pft_real_t l11, l21, l22;  /**< its lower Cholesky factor (l22 = 0 if Q is singular) */
} pft_motion_free_t;

/**
 * Coefficients for beta in [0, 64] and q >= 0 (PFT_ERR_INVAL otherwise, c untouched).
 * q16: the series branch (beta < 1) is accurate to a few LSB; closed forms use pft_exp.
 */
pft_status_t pft_motion_free_coef(pft_motion_free_t *c, pft_real_t beta, pft_real_t q);

/**
 * One free-model step of one axis: x += phi12 v + gamma1 vbar + l11 g1,
 * v = phi22 v + gamma2 vbar + l21 g1 + l22 g2, with g1, g2 standard normal draws.
 */
void pft_motion_free_step(const pft_motion_free_t *c, pft_real_t *x, pft_real_t *v,
                          pft_real_t vbar, pft_real_t g1, pft_real_t g2);

/** Result of the conservative fit of one axis. */
typedef struct {
    pft_real_t s, v, a;  /**< X(tau) = s + v tau + a tau^2, tau = 0 at the newest point */
    pft_real_t v_pred;   /**< conservative velocity at tau = 1: v + 2a (eq. 15) */
    pft_real_t x_pred;   /**< pioneer position at tau = 1: s + v + a (eq. 16) */
    uint8_t order;       /**< 2 quadratic, 1 constant-velocity fallback, 0 single point */
} pft_motion_fit_t;

/**
 * Weighted least-squares fit of o[0..n) (oldest first, o[n-1] at tau = 0).
 * @param pi        per-point weights pi_i >= 0 (NULL: all 1)
 * @param sigma_g   width of the Gaussian time weighting (> 0), in frames
 * @param max_order 2 for TSA (constant acceleration), 1 for TS (constant velocity)
 * PFT_ERR_INVAL for NULL o/out, n == 0, n > PFT_MOTION_MAX_K, sigma_g <= 0, max_order > 2 or
 * all weights zero. |o_i - o_{n-1}| should stay below 2048 px (q16 range of the sums).
 */
pft_status_t pft_motion_fit(const pft_real_t *o, const pft_real_t *pi, uint32_t n,
                            pft_real_t sigma_g, uint8_t max_order, pft_motion_fit_t *out);

/**
 * Bounds on a conservative fit (not in the paper [A]). With only a few reference points, or
 * when the reference points follow the pioneer where the likelihood is flat, the fitted a and
 * v_hat can grow from frame to frame without limit (docs/results/tsa_ak.md, "Real videos").
 * a_max > 0: a is clamped to [-a_max, a_max] (a as fitted, i.e. half the physical
 * acceleration, px/frame^2) and v_pred, x_pred are recomputed from the clamped a.
 * v_max > 0: v_pred and the pioneer step x_pred - s are clamped to [-v_max, v_max] (px/frame).
 * A bound of 0 is off; a fit inside its bounds is left bit-for-bit unchanged. NULL: no-op.
 */
void pft_motion_fit_bound(pft_motion_fit_t *f, pft_real_t a_max, pft_real_t v_max);

/**
 * Beta adaptation (eq. 24): beta_{k+1} = beta_max * rho_p / (rho_e + rho_p) from the
 * similarities of the pioneer (rho_p) and of the estimate (rho_e). Both zero: beta_prev.
 */
pft_real_t pft_motion_beta_adapt(pft_real_t rho_e, pft_real_t rho_p, pft_real_t beta_max,
                                 pft_real_t beta_prev);

/** Reference-point rule (eq. 25): true when the estimate is the next reference point, false
 *  when the pioneer is. Eq. 25 takes the estimate when rho(pioneer) < rho(estimate); on a tie
 *  it would take the pioneer, which lets a pioneer that left the target (both rho 0) feed the
 *  fit with its own extrapolation: here a tie keeps the estimate [C]. */
static inline bool pft_motion_ref_is_estimate(pft_real_t rho_e, pft_real_t rho_p)
{
    return !(rho_p > rho_e);
}

#ifdef __cplusplus
}
#endif
#endif
