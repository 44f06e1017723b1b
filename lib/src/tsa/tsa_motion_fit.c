/*
 * Conservative weighted least-squares fit of TS (constant velocity) and TSA (constant
 * acceleration), docs/algorithms.md 4.2, solved with weighted orthogonal polynomials in the
 * centred time tau (see pft_tsa.h). Sums that may leave the Q16.16 range are accumulated with
 * the core's pft_macc_* helpers: exact 64-bit products (Q32) in the q16 build, floats in the
 * float build.
 */
#include "../core/acc_int.h"
#include "tsa_int.h"

/* 2^-10: the det / (A0 A2 A4) and N1 / A2 thresholds of the fallbacks. */
#define FIT_EPS_ PFT_C(0.0009765625)

/* The fit's per-point terms and sums; d are the positions relative to the newest one. */
typedef struct {
    pft_real_t g[PFT_TSA_MOTION_MAX_K], tau[PFT_TSA_MOTION_MAX_K], d[PFT_TSA_MOTION_MAX_K];
    pft_real_t p1[PFT_TSA_MOTION_MAX_K];
    pft_real_t n0, st, a2, n1, stp; /* sum g, g tau, g tau^2, g P1^2, g tau P1^2 */
    pft_macc_t_ a4, s0, s1;         /* sum g tau^4, g d, g d P1 */
} fit_sums_t_;

/* Weights G_i = pi_i exp(-tau^2 / (2 sigma^2)) and the moments of order 0. */
static void fit_moments_(fit_sums_t_ *m, const pft_real_t *o, const pft_real_t *pi, uint32_t n,
                         pft_real_t sigma_g)
{
    const pft_real_t last = o[n - 1u];
    const pft_real_t inv2s2 = pft_recip(pft_mul_i(pft_sq(sigma_g), 2));
    m->n0 = PFT_C(0.0);
    m->st = PFT_C(0.0);
    m->a2 = PFT_C(0.0);
    m->a4 = 0;
    m->s0 = 0;
    for (uint32_t i = 0; i < n; ++i) {
        m->tau[i] = pft_from_int((int32_t)i - (int32_t)(n - 1u));
        m->g[i] = pft_exp(pft_neg(pft_mul(pft_sq(m->tau[i]), inv2s2)));
        if (pi != NULL) {
            m->g[i] = pft_mul(m->g[i], pft_max(pi[i], PFT_C(0.0)));
        }
        m->d[i] = pft_sub(o[i], last);
        m->n0 = pft_add(m->n0, m->g[i]);
        m->st = pft_add(m->st, pft_mul(m->g[i], m->tau[i]));
        m->a2 = pft_add(m->a2, pft_mul(m->g[i], pft_sq(m->tau[i])));
        m->a4 += pft_macc_mul_(m->g[i], pft_sq(pft_sq(m->tau[i])));
        m->s0 += pft_macc_mul_(m->g[i], m->d[i]);
    }
}

/* P1 = tau - alpha1 and its moments. */
static void fit_first_order_(fit_sums_t_ *m, uint32_t n, pft_real_t alpha1)
{
    m->n1 = PFT_C(0.0);
    m->stp = PFT_C(0.0);
    m->s1 = 0;
    for (uint32_t i = 0; i < n; ++i) {
        m->p1[i] = pft_sub(m->tau[i], alpha1);
        m->n1 = pft_add(m->n1, pft_mul(m->g[i], pft_sq(m->p1[i])));
        m->stp = pft_add(m->stp, pft_mul(pft_mul(m->g[i], m->tau[i]), pft_sq(m->p1[i])));
        m->s1 += pft_macc_mul_(m->g[i], pft_mul(m->d[i], m->p1[i]));
    }
}

/* P2 = (tau - alpha2) P1 - b1: its norm N2 into *n2 and the projection of d into *s2. */
static void fit_second_order_(const fit_sums_t_ *m, uint32_t n, pft_real_t alpha2, pft_real_t b1,
                              pft_macc_t_ *n2, pft_macc_t_ *s2)
{
    *n2 = 0;
    *s2 = 0;
    for (uint32_t i = 0; i < n; ++i) {
        const pft_real_t p2 = pft_sub(pft_mul(pft_sub(m->tau[i], alpha2), m->p1[i]), b1);
        *n2 += pft_macc_mul_(m->g[i], pft_sq(p2));
        *s2 += pft_macc_mul_(m->g[i], pft_mul(m->d[i], p2));
    }
}

pft_status_t pft_tsa_motion_fit(const pft_real_t *o, const pft_real_t *pi, uint32_t n,
                                pft_real_t sigma_g, uint8_t max_order, pft_tsa_motion_fit_t *out)
{
    if (o == NULL || out == NULL || n == 0u || n > PFT_TSA_MOTION_MAX_K ||
        !(sigma_g > PFT_C(0.0)) || max_order > 2u) {
        return PFT_ERR_INVAL;
    }
    fit_sums_t_ m;
    fit_moments_(&m, o, pi, n, sigma_g);
    if (!(m.n0 > PFT_C(0.0))) {
        return PFT_ERR_INVAL;
    }
    pft_real_t alpha1 = pft_div(m.st, m.n0);
    fit_first_order_(&m, n, alpha1);
    const pft_real_t c0 = pft_macc_div_(m.s0, pft_macc_mul_(m.n0, PFT_REAL_ONE));
    pft_real_t c1 = PFT_C(0.0);
    pft_real_t c2 = PFT_C(0.0);
    pft_real_t alpha2 = PFT_C(0.0);
    pft_real_t b1 = PFT_C(0.0);
    uint8_t order = 0u;
    if (n >= 2u && max_order >= 1u && m.a2 > PFT_C(0.0) && pft_div(m.n1, m.a2) >= FIT_EPS_) {
        order = 1u;
        c1 = pft_macc_div_(m.s1, pft_macc_mul_(m.n1, PFT_REAL_ONE));
        if (n >= 3u && max_order >= 2u) {
            alpha2 = pft_div(m.stp, m.n1);
            b1 = pft_div(m.n1, m.n0);
            pft_macc_t_ n2;
            pft_macc_t_ s2;
            fit_second_order_(&m, n, alpha2, b1, &n2, &s2);
            /* det / (A0 A2 A4) = (N1 / A2) (N2 / A4), since det = N0 N1 N2 and A0 = N0 */
            if (pft_mul(pft_div(m.n1, m.a2), pft_macc_div_(n2, m.a4)) >= FIT_EPS_) {
                order = 2u;
                c2 = pft_macc_div_(s2, n2);
            }
        }
    }
    if (order < 2u) {
        alpha2 = PFT_C(0.0);
        b1 = PFT_C(0.0);
        c2 = PFT_C(0.0);
    }
    if (order < 1u) {
        c1 = PFT_C(0.0);
        alpha1 = PFT_C(0.0);
    }
    /* f(tau) = last + c0 + c1 (tau - alpha1) + c2 ((tau - alpha2)(tau - alpha1) - b1) */
    out->order = order;
    out->a = c2;
    out->v = pft_sub(c1, pft_mul(c2, pft_add(alpha1, alpha2)));
    out->s = pft_add(pft_add(o[n - 1u], c0),
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
    if (a_max > PFT_C(0.0) && (f->a > a_max || f->a < pft_neg(a_max))) {
        f->a = pft_clamp(f->a, pft_neg(a_max), a_max);
        f->v_pred = pft_add(f->v, pft_add(f->a, f->a));
        f->x_pred = pft_add(pft_add(f->s, f->v), f->a);
    }
    if (v_max > PFT_C(0.0)) {
        const pft_real_t step = pft_sub(f->x_pred, f->s);
        if (step > v_max || step < pft_neg(v_max)) {
            f->x_pred = pft_add(f->s, pft_clamp(step, pft_neg(v_max), v_max));
        }
        if (f->v_pred > v_max || f->v_pred < pft_neg(v_max)) {
            f->v_pred = pft_clamp(f->v_pred, pft_neg(v_max), v_max);
        }
    }
}
