/*
 * Kristan's liberal ("free") model (docs/algorithms.md 4.1) with beta = 0 giving NCV, its noise
 * covariance (integrated Ornstein-Uhlenbeck) and the beta adaptation of TSA (eq. 24).
 * Small beta uses power series so the limits are exact and q16 has no cancellation.
 */
#include "tsa_int.h"

/* f(b) = (1 - e^-b)/b = sum_n (-b)^n / (n+1)!  (series for b < 1; closed form beyond). */
static pft_real_t phi_f_(pft_real_t b)
{
    if (b < PFT_REAL_ONE) {
        pft_real_t term = PFT_REAL_ONE;
        pft_real_t sum = PFT_REAL_ONE;
        for (int32_t n = 1; n <= 12; ++n) {
            term = pft_div_i(pft_mul(term, pft_neg(b)), n + 1);
            sum = pft_add(sum, term);
        }
        return sum;
    }
    return pft_div(pft_sub(PFT_REAL_ONE, pft_exp(pft_neg(b))), b);
}

/* Q11 / q = (1 - 2 f(b) + f(2b)) / b^2 = sum_m (-b)^m (2^(m+2) - 2) / (m+3)!  (b < 1). */
static pft_real_t q11_series_(pft_real_t b)
{
    static const pft_real_t c[11] = {
        PFT_C(0.333333333333), PFT_C(0.25), PFT_C(0.116666666667), PFT_C(0.041666666667),
        PFT_C(0.012301587302), PFT_C(0.003125), PFT_C(0.000699955908), PFT_C(0.000140542328),
        PFT_C(0.0000256032), PFT_C(0.00000427139), PFT_C(0.00000065746)};
    pft_real_t acc = c[10];
    for (int32_t m = 9; m >= 0; --m) {
        acc = pft_sub(c[m], pft_mul(b, acc)); /* Horner with alternating signs */
    }
    return acc;
}

pft_status_t pft_tsa_motion_free_coef(pft_tsa_motion_free_t *c, pft_real_t beta, pft_real_t q)
{
    if (c == NULL || !(beta >= PFT_C(0.0)) || beta > PFT_C(64.0) || !(q >= PFT_C(0.0)) ||
        q > PFT_C(10000.0)) {
        return PFT_ERR_INVAL;
    }
    const pft_real_t f1 = phi_f_(beta);
    const pft_real_t f2 = phi_f_(pft_add(beta, beta));
    c->beta = beta;
    c->phi12 = f1;
    c->phi22 = pft_sub(PFT_REAL_ONE, pft_mul(beta, f1)); /* e^-b = 1 - b f(b) */
    c->gamma1 = pft_sub(PFT_REAL_ONE, f1);
    c->gamma2 = pft_sub(PFT_REAL_ONE, c->phi22);
    /* Q11 / q */
    const pft_real_t g11 =
        beta < PFT_REAL_ONE
            ? q11_series_(beta)
            : pft_div(pft_add(pft_sub(PFT_REAL_ONE, pft_add(f1, f1)), f2), pft_sq(beta));
    c->q11 = pft_mul(q, g11);
    c->q12 = pft_mul(pft_div_i(q, 2), pft_sq(f1));
    c->q22 = pft_mul(q, f2);
    c->l11 = pft_sqrt(c->q11);
    c->l21 = c->l11 > PFT_C(0.0) ? pft_div(c->q12, c->l11) : PFT_C(0.0);
    c->l22 = pft_sqrt(pft_max(pft_sub(c->q22, pft_sq(c->l21)), PFT_C(0.0)));
    return PFT_OK;
}

void pft_tsa_motion_free_step(const pft_tsa_motion_free_t *c, pft_real_t *x, pft_real_t *v,
                              pft_real_t vbar, pft_real_t g1, pft_real_t g2)
{
    const pft_real_t v0 = *v;
    *x = pft_add(*x, pft_add(pft_add(pft_mul(c->phi12, v0), pft_mul(c->gamma1, vbar)),
                             pft_mul(c->l11, g1)));
    *v = pft_add(pft_add(pft_mul(c->phi22, v0), pft_mul(c->gamma2, vbar)),
                 pft_add(pft_mul(c->l21, g1), pft_mul(c->l22, g2)));
}

pft_real_t pft_tsa_motion_beta_adapt(pft_real_t rho_e, pft_real_t rho_p, pft_real_t beta_max,
                                     pft_real_t beta_prev)
{
    rho_e = pft_max(rho_e, PFT_C(0.0));
    rho_p = pft_max(rho_p, PFT_C(0.0));
    const pft_real_t den = pft_add(rho_e, rho_p);
    if (!(den > PFT_C(0.0))) {
        return beta_prev;
    }
    return pft_clamp(pft_mul(beta_max, pft_div(rho_p, den)), PFT_C(0.0), beta_max);
}
