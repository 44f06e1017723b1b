/* Accumulators shared by the filters (private, not installed): the one place where a sum that
 * may leave the Q16.16 range is kept wider, and the one log-count.
 *
 * Weighted sums (pft_acc_t_): q16: weight (Q2.30, uint32) times value (Q16.16, int32) is Q46
 * in int64; normalised weights sum to 2^30, so a sum over all particles (at most 2^22, see
 * PFT_CFG_MAX_PARTICLES) stays below 2^61 in magnitude. The quotient by a weight sum (Q2.30 in
 * uint64) is Q16.16 again, rounded once to nearest, saturated. float: plain float sums.
 *
 * Products of two reals (pft_macc_t_): q16: exact Q32 products in int64 (|a b| < 2^62);
 * the quotient of two such sums is Q16.16 rounded to nearest, saturated. float: floats.
 */
#ifndef PFT_CORE_ACC_INT_H
#define PFT_CORE_ACC_INT_H

#include "pft/pft_real.h"

#ifdef PFT_NUMERIC_Q16
typedef int64_t pft_acc_t_;
typedef int64_t pft_macc_t_;
#define PFT_ACC_ZERO_ ((pft_acc_t_)0)
static inline pft_acc_t_ pft_acc_wx_(pft_weight_t w, pft_real_t v) { return (int64_t)w * (int64_t)v; }
/* num / den as a real (den a weight sum); den == 0 gives 0. */
static inline pft_real_t pft_acc_div_(pft_acc_t_ num, pft_wacc_t den)
{
    int64_t d, q;
    if (den == 0u) {
        return 0;
    }
    d = (int64_t)den;
    q = (num >= 0 ? num + d / 2 : num - d / 2) / d;
    return pft_sat64_(q);
}
/* a / b for 0 <= a <= b (weight sums) as a real in [0, 1]; b == 0 gives 0. */
static inline pft_real_t pft_wratio_(pft_wacc_t a, pft_wacc_t b)
{
    if (b == 0u) {
        return 0;
    }
    return (pft_real_t)(((a << 16) + b / 2u) / b);
}
/* a * b exactly (Q32). */
static inline pft_macc_t_ pft_macc_mul_(pft_real_t a, pft_real_t b) { return (int64_t)a * b; }
/* num (Q32) / den (Q32) as Q16.16, rounded, saturating; den <= 0 gives 0. */
static inline pft_real_t pft_macc_div_(pft_macc_t_ num, pft_macc_t_ den)
{
    int64_t d = den >> 16, q; /* Q16 in 64 bits */
    if (d <= 0) {
        return 0;
    }
    q = (num >= 0 ? num + d / 2 : num - d / 2) / d;
    return pft_sat64_(q);
}
#else
typedef float pft_acc_t_;
typedef float pft_macc_t_;
#define PFT_ACC_ZERO_ 0.0f
static inline pft_acc_t_ pft_acc_wx_(pft_weight_t w, pft_real_t v) { return w * v; }
static inline pft_real_t pft_acc_div_(pft_acc_t_ num, pft_wacc_t den) { return den > 0.0f ? num / den : 0.0f; }
static inline pft_real_t pft_wratio_(pft_wacc_t a, pft_wacc_t b) { return b > 0.0f ? a / b : 0.0f; }
static inline pft_macc_t_ pft_macc_mul_(pft_real_t a, pft_real_t b) { return a * b; }
static inline pft_real_t pft_macc_div_(pft_macc_t_ num, pft_macc_t_ den) { return den > 0.0f ? num / den : 0.0f; }
#endif

/* log n for a particle count n >= 1: log(n / 2^s) + s log 2 with n / 2^s < 2^14, so the ratio
 * is representable in Q16.16 without truncating the shifted-out bits. */
static inline pft_real_t pft_log_count_(uint32_t n)
{
    uint32_t s = 0;
    while (s < 31u && (n >> s) >= 16384u) {
        ++s;
    }
    pft_real_t frac = pft_ratio((int32_t)n, (int32_t)(1u << s));
    return pft_add(pft_log(frac), pft_mul_i(PFT_C(0.693147180559945), (int32_t)s));
}

#endif
