/**
 * @file pft_kalman.h
 * @brief Small Kalman algebra: 2-D and 4-D states with symmetric covariances.
 *
 * Covariances are stored full (row-major n*n) and every operation writes an exactly symmetric
 * result (the upper triangle is computed, the lower copied), so rounding never breaks symmetry.
 * Dot products accumulate exactly (q16: Q32.32 in int64) and round once. The 2x2 innovation
 * covariance S is checked for positive definiteness with an exact determinant in q16, and the
 * gain is computed as P H' adj(S) / det(S) with a single rounding. Outputs are written last,
 * so on an error nothing changes (and outputs may alias inputs). NULL arguments give
 * PFT_ERR_INVAL (the predictions, which return nothing, then do nothing).
 */
#ifndef PFT_KALMAN_H
#define PFT_KALMAN_H

#include "pft/pft_real.h"

#ifdef __cplusplus
extern "C" {
#endif

/** x <- F x, P <- F P F' + Q for n = 2. */
void pft_kf2_predict(pft_real_t x[2], pft_real_t P[4], const pft_real_t F[4], const pft_real_t Q[4]);
/** Update with a 2-D measurement z = x + v, v ~ N(0, R) (H = I). PFT_ERR_SINGULAR if S is not
 *  positive definite, PFT_ERR_RANGE (float) if its determinant overflows (state untouched either
 *  way). */
pft_status_t pft_kf2_update(pft_real_t x[2], pft_real_t P[4], const pft_real_t z[2], const pft_real_t R[4]);
/** Scalar-measurement update z = h' x + v, v ~ N(0, r), n = 2. PFT_ERR_SINGULAR if the
 *  innovation variance h' P h + r is not positive, PFT_ERR_RANGE (float) if it overflows (state
 *  untouched either way). */
pft_status_t pft_kf2_update_scalar(pft_real_t x[2], pft_real_t P[4], const pft_real_t h[2], pft_real_t z, pft_real_t r);
/** x <- F x, P <- F P F' + Q for n = 4. */
void pft_kf4_predict(pft_real_t x[4], pft_real_t P[16], const pft_real_t F[16], const pft_real_t Q[16]);
/** Update of a 4-D state with a 2-D measurement z = H x + v, v ~ N(0, R), H 2x4. Errors as
 *  pft_kf2_update. */
pft_status_t pft_kf4_update2(pft_real_t x[4], pft_real_t P[16], const pft_real_t H[8], const pft_real_t z[2], const pft_real_t R[4]);
/** Inverse of a symmetric positive definite 2x2 matrix (reads A[0], A[1], A[3]);
 *  PFT_ERR_SINGULAR if it is singular or not positive definite, PFT_ERR_RANGE if an inverse
 *  entry is beyond the real range; Ainv then untouched. */
pft_status_t pft_mat2_inv_sym(const pft_real_t A[4], pft_real_t Ainv[4]);
/** Lower Cholesky factor L = [[l00, 0], [l10, l11]] (row-major) of a symmetric positive
 *  definite 2x2 matrix (reads A[0], A[1], A[3]), L L' = A; PFT_ERR_SINGULAR (L untouched) if A
 *  is not positive definite. */
pft_status_t pft_mat2_chol(const pft_real_t A[4], pft_real_t L[4]);

#ifdef __cplusplus
}
#endif
#endif
