/*
 * Conservative weighted least-squares fit of TS (constant velocity) and TSA (constant
 * acceleration), ALGORITHMS.md 4.2, solved with weighted orthogonal polynomials in the
 * centred time tau (see pft_tsa.h). Sums that may leave the Q16.16 range are accumulated by
 * the macc_* helpers: exact 64-bit products (Q32) in the q16 build, floats in the float build.
 */
#include "pft/pft_tsa.h"

#ifdef PFT_NUMERIC_Q16
typedef int64_t macc_t;
static inline macc_t macc_mul(pft_real_t a, pft_real_t b) { return (int64_t)a * b; } /* Q32 */
/* num (Q32) / den (Q32) as Q16.16, rounded, saturating; den <= 0 gives 0. */
static pft_real_t macc_div(macc_t num, macc_t den)
{
    int64_t d = den >> 16, q; /* Q16 in 64 bits */
    if (d <= 0) {
        return 0;
    }
    q = (num >= 0 ? num + d / 2 : num - d / 2) / d;
    return pft_sat64_(q);
}
#else
typedef float macc_t;
static inline macc_t macc_mul(pft_real_t a, pft_real_t b) { return a * b; }
static pft_real_t macc_div(macc_t num, macc_t den) { return den > 0.0f ? num / den : 0.0f; }
#endif

/* 2^-10: the det / (A0 A2 A4) and N1 / A2 thresholds of the fallbacks. */
#define FIT_EPS PFT_C(0.0009765625)

pft_status_t pft_tsa_motion_fit(const pft_real_t *o, const pft_real_t *pi, uint32_t n,
                            pft_real_t sigma_g, uint8_t max_order, pft_tsa_motion_fit_t *out)
{
    pft_real_t g[PFT_TSA_MOTION_MAX_K], tau[PFT_TSA_MOTION_MAX_K], p1[PFT_TSA_MOTION_MAX_K];
    pft_real_t p2[PFT_TSA_MOTION_MAX_K], d[PFT_TSA_MOTION_MAX_K];
    pft_real_t inv2s2, n0 = 0, st = 0, n1 = 0, a2 = 0, stp = 0, alpha1, alpha2 = 0, b1 = 0;
    pft_real_t c0, c1 = 0, c2 = 0, last;
    macc_t a4 = 0, n2 = 0, s0 = 0, s1 = 0, s2 = 0;
    uint8_t order;
    uint32_t i;

    if (o == NULL || out == NULL || n == 0u || n > PFT_TSA_MOTION_MAX_K || !(sigma_g > 0) ||
        max_order > 2u) {
        return PFT_ERR_INVAL;
    }
    last = o[n - 1u];
    inv2s2 = pft_recip(pft_mul_i(pft_sq(sigma_g), 2));
    for (i = 0; i < n; ++i) {
        tau[i] = pft_from_int((int32_t)i - (int32_t)(n - 1u));
        g[i] = pft_exp(pft_neg(pft_mul(pft_sq(tau[i]), inv2s2)));
        if (pi != NULL) {
            g[i] = pft_mul(g[i], pft_max(pi[i], 0));
        }
        d[i] = pft_sub(o[i], last);
        n0 = pft_add(n0, g[i]);
        st = pft_add(st, pft_mul(g[i], tau[i]));
        a2 = pft_add(a2, pft_mul(g[i], pft_sq(tau[i])));
        a4 += macc_mul(g[i], pft_sq(pft_sq(tau[i])));
        s0 += macc_mul(g[i], d[i]);
    }
    if (!(n0 > 0)) {
        return PFT_ERR_INVAL;
    }
    alpha1 = pft_div(st, n0);
    for (i = 0; i < n; ++i) {
        p1[i] = pft_sub(tau[i], alpha1);
        n1 = pft_add(n1, pft_mul(g[i], pft_sq(p1[i])));
        stp = pft_add(stp, pft_mul(pft_mul(g[i], tau[i]), pft_sq(p1[i])));
        s1 += macc_mul(g[i], pft_mul(d[i], p1[i]));
    }
    c0 = macc_div(s0, macc_mul(n0, PFT_REAL_ONE));
    order = 0;
    if (n >= 2u && max_order >= 1u && a2 > 0 && pft_div(n1, a2) >= FIT_EPS) {
        order = 1;
        c1 = macc_div(s1, macc_mul(n1, PFT_REAL_ONE));
        if (n >= 3u && max_order >= 2u) {
            alpha2 = pft_div(stp, n1);
            b1 = pft_div(n1, n0);
            for (i = 0; i < n; ++i) {
                p2[i] = pft_sub(pft_mul(pft_sub(tau[i], alpha2), p1[i]), b1);
                n2 += macc_mul(g[i], pft_sq(p2[i]));
                s2 += macc_mul(g[i], pft_mul(d[i], p2[i]));
            }
            /* det / (A0 A2 A4) = (N1 / A2) (N2 / A4), since det = N0 N1 N2 and A0 = N0 */
            if (pft_mul(pft_div(n1, a2), macc_div(n2, a4)) >= FIT_EPS) {
                order = 2;
                c2 = macc_div(s2, n2);
            }
        }
    }
    if (order < 2u) {
        alpha2 = 0;
        b1 = 0;
        c2 = 0;
    }
    if (order < 1u) {
        c1 = 0;
        alpha1 = 0;
    }
    /* f(tau) = last + c0 + c1 (tau - alpha1) + c2 ((tau - alpha2)(tau - alpha1) - b1) */
    out->order = order;
    out->a = c2;
    out->v = pft_sub(c1, pft_mul(c2, pft_add(alpha1, alpha2)));
    out->s = pft_add(pft_add(last, c0),
                     pft_add(pft_neg(pft_mul(c1, alpha1)),
                             pft_mul(c2, pft_sub(pft_mul(alpha1, alpha2), b1))));
    out->v_pred = pft_add(out->v, pft_add(out->a, out->a));
    out->x_pred = pft_add(pft_add(out->s, out->v), out->a);
    return PFT_OK;
}

void pft_tsa_motion_fit_bound(pft_tsa_motion_fit_t *f, pft_real_t a_max, pft_real_t v_max)
{
    if (f == NULL) {
        return;
    }
    if (a_max > 0 && (f->a > a_max || f->a < pft_neg(a_max))) {
        f->a = pft_clamp(f->a, pft_neg(a_max), a_max);
        f->v_pred = pft_add(f->v, pft_add(f->a, f->a));
        f->x_pred = pft_add(pft_add(f->s, f->v), f->a);
    }
    if (v_max > 0) {
        const pft_real_t step = pft_sub(f->x_pred, f->s);
        if (step > v_max || step < pft_neg(v_max)) {
            f->x_pred = pft_add(f->s, pft_clamp(step, pft_neg(v_max), v_max));
        }
        if (f->v_pred > v_max || f->v_pred < pft_neg(v_max)) {
            f->v_pred = pft_clamp(f->v_pred, pft_neg(v_max), v_max);
        }
    }
}
