/*
 * Particle weights: log-sum-exp normalisation and effective sample size, in both builds.
 *
 * q16: unnormalised weights are pft_wexp(lw - max) in Q2.30 (pft_wexp and pft_wacc_log live in
 * pft_real_q16.c next to the exp/log cores they share); their sum goes into a uint64
 * accumulator (at most 2^22 * 2^30 = 2^52). Normalised weights are Q2.30 summing to exactly
 * PFT_W_ONE. Sums of squares of normalised weights are exact in uint64 (<= (2^30 + n)^2).
 * float: sums are compensated (Kahan) so that 2^18 particles lose no more than a few ulps.
 */
#include "pft/pft_real.h"

pft_real_t pft_real_max_n(const pft_real_t *v, size_t n)
{
    pft_real_t m;
    size_t i;
    if (n == 0) {
        return PFT_REAL_MIN;
    }
    m = v[0];
    for (i = 1; i < n; ++i) {
        if (v[i] > m) {
            m = v[i];
        }
    }
    return m;
}

#ifdef PFT_NUMERIC_Q16

pft_real_t pft_weight_to_real(pft_weight_t w)
{
    return (pft_real_t)(w >> 14);
}

pft_real_t pft_lognormalize(const pft_real_t *lw, pft_weight_t *w, size_t n)
{
    pft_real_t m;
    pft_wacc_t sum = 0, carry, num, q;
    size_t i;
    if (n == 0) {
        return PFT_REAL_MIN;
    }
    m = pft_real_max_n(lw, n);
    for (i = 0; i < n; ++i) {
        w[i] = pft_wexp(pft_sub(lw[i], m)); /* the max gives exactly PFT_W_ONE */
        sum += w[i];                         /* <= n 2^30 <= 2^52 */
    }
    /* w[i] = e[i] 2^30 / sum by long division, carrying the remainder (started at sum/2) from
     * one weight to the next: every partial sum of the w is round(partial e 2^30 / sum), so the
     * total is exactly 2^30 and each w[i] is within 1 LSB of its quotient.
     * num < 2^60 + sum fits; quotient <= 2^30. */
    carry = sum >> 1;
    for (i = 0; i < n; ++i) {
        num = ((pft_wacc_t)w[i] << 30) + carry;
        q = num / sum;
        carry = num - q * sum;
        w[i] = (pft_weight_t)q;
    }
    return pft_add(m, pft_wacc_log(sum));
}

/* floor(2^(76+24) / s2): the ESS in Q16.16 with 24 more fraction bits (2^60 / s2 with s2 in
 * Q60), so that the ESS and ESS / n can both be rounded once from it. At most 2^62. */
#define PFT_ESS_XBITS_ 24
static uint64_t pft_ess_scaled_(const pft_weight_t *w, size_t n)
{
    uint64_t s2 = 0, sq, q, r;
    size_t i;
    int k;
    for (i = 0; i < n; ++i) {
        sq = (uint64_t)w[i] * w[i];
        s2 = s2 > UINT64_MAX - sq ? UINT64_MAX : s2 + sq;
    }
    if (s2 == 0) {
        return 0;
    }
    if (s2 >= ((uint64_t)1 << 62)) { /* not normalised; keep the shifts below from overflowing */
        return (((uint64_t)1 << 63) / (s2 >> 13)) << PFT_ESS_XBITS_;
    }
    if (s2 < ((uint64_t)1 << 38)) { /* below (2^30)^2 / 2^22: not normalised, clamp */
        s2 = (uint64_t)1 << 38;
    }
    q = ((uint64_t)1 << 63) / s2; /* <= 2^25 */
    r = ((uint64_t)1 << 63) % s2;
    for (k = 0; k < 13 + PFT_ESS_XBITS_; ++k) { /* long division, one quotient bit a step */
        r <<= 1;                                /* r < s2 < 2^62 */
        q <<= 1;
        if (r >= s2) {
            r -= s2;
            q |= 1u;
        }
    }
    return q;
}

pft_real_t pft_ess(const pft_weight_t *w, size_t n)
{
    uint64_t q = pft_ess_scaled_(w, n);
    q = (q + ((uint64_t)1 << (PFT_ESS_XBITS_ - 1))) >> PFT_ESS_XBITS_;
    return q > (uint64_t)INT32_MAX ? PFT_REAL_MAX : (pft_real_t)q;
}

pft_real_t pft_ess_ratio(const pft_weight_t *w, size_t n)
{
    uint64_t q, d;
    if (n == 0) {
        return 0;
    }
    q = pft_ess_scaled_(w, n);
    d = (uint64_t)n << PFT_ESS_XBITS_; /* <= 2^46 */
    q = (q + (d >> 1)) / d;
    return q > (uint64_t)INT32_MAX ? PFT_REAL_MAX : (pft_real_t)q;
}

#else /* PFT_NUMERIC_FLOAT */

pft_weight_t pft_wexp(pft_real_t x)
{
    return x >= 0.0f ? 1.0f : expf(x);
}

pft_real_t pft_weight_to_real(pft_weight_t w)
{
    return w;
}

/* Kahan step: *s + *c carries the running sum. */
static void pft_kahan_add_(float *s, float *c, float v)
{
    float y = v - *c;
    float t = *s + y;
    *c = (t - *s) - y;
    *s = t;
}

pft_real_t pft_lognormalize(const pft_real_t *lw, pft_weight_t *w, size_t n)
{
    float m, sum = 0.0f, comp = 0.0f;
    size_t i;
    if (n == 0) {
        return PFT_REAL_MIN;
    }
    m = pft_real_max_n(lw, n);
    for (i = 0; i < n; ++i) {
        w[i] = pft_wexp(lw[i] - m);
        pft_kahan_add_(&sum, &comp, w[i]);
    }
    for (i = 0; i < n; ++i) {
        w[i] = w[i] / sum; /* sum >= 1: the max contributes exactly 1 */
    }
    return m + logf(sum);
}

static float pft_sumsq_(const pft_weight_t *w, size_t n)
{
    float s = 0.0f, c = 0.0f;
    size_t i;
    for (i = 0; i < n; ++i) {
        pft_kahan_add_(&s, &c, w[i] * w[i]);
    }
    return s;
}

pft_real_t pft_ess(const pft_weight_t *w, size_t n)
{
    float s = pft_sumsq_(w, n);
    return s > 0.0f ? 1.0f / s : 0.0f;
}

pft_real_t pft_ess_ratio(const pft_weight_t *w, size_t n)
{
    float s = pft_sumsq_(w, n);
    return (s > 0.0f && n > 0) ? 1.0f / (s * (float)n) : 0.0f;
}

#endif
