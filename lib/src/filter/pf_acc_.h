/* Weighted accumulation helpers shared by the PF engine and its models (not installed).
 *
 * q16: weight (Q2.30, uint32) times state (Q16.16, int32) is Q46 in int64; normalised weights
 * sum to 2^30, so a sum over all particles stays below 2^61 in magnitude. A quotient by a
 * weight sum (Q2.30 in uint64) gives Q16.16 again, rounded once to nearest.
 * float: plain float sums (the weights are normalised, the states moderate). */
#ifndef PFT_PF_ACC_H_
#define PFT_PF_ACC_H_

#include "pft/pft_real.h"

#ifdef PFT_NUMERIC_Q16
typedef int64_t pft_pf_acc_t_;
#define PFT_PF_ACC_ZERO_ ((pft_pf_acc_t_)0)
static inline pft_pf_acc_t_ pft_pf_acc_wx_(pft_weight_t w, pft_real_t v)
{
    return (int64_t)w * (int64_t)v;
}
/* num / den as a real (den a weight sum); den == 0 gives 0. */
static inline pft_real_t pft_pf_acc_div_(pft_pf_acc_t_ num, pft_wacc_t den)
{
    int64_t d, q;
    if (den == 0u) {
        return 0;
    }
    d = (int64_t)den;
    q = (num >= 0 ? num + d / 2 : num - d / 2) / d;
    return pft_sat64_(q);
}
/* a / b for 0 <= a <= b as a real in [0, 1]. */
static inline pft_real_t pft_pf_wratio_(pft_wacc_t a, pft_wacc_t b)
{
    if (b == 0u) {
        return 0;
    }
    return (pft_real_t)(((a << 16) + b / 2u) / b);
}
#else
typedef float pft_pf_acc_t_;
#define PFT_PF_ACC_ZERO_ 0.0f
static inline pft_pf_acc_t_ pft_pf_acc_wx_(pft_weight_t w, pft_real_t v) { return w * v; }
static inline pft_real_t pft_pf_acc_div_(pft_pf_acc_t_ num, pft_wacc_t den)
{
    return den > 0.0f ? num / den : 0.0f;
}
static inline pft_real_t pft_pf_wratio_(pft_wacc_t a, pft_wacc_t b)
{
    return b > 0.0f ? a / b : 0.0f;
}
#endif

#endif
