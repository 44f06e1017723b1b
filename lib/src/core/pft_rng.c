/*
 * Deterministic per-instance random numbers: xoshiro128** (Blackman & Vigna 2018) seeded by
 * splitmix64. Everything up to the 32-bit draw is integer arithmetic, so the stream is the
 * same in the float and the q16 build and on every target; reals are derived from it through
 * pft_from_u32_frac (q16: top 16 bits; float: top 24 bits).
 */
#include <string.h>

#include "pft/pft_rng.h"
#include "rng_int.h"
#include "kern_int.h"

static uint64_t pft_splitmix64_(uint64_t *state)
{
    uint64_t z;
    *state += 0x9E3779B97F4A7C15ull;
    z = *state;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

void pft_rng_seed(pft_rng_t *rng, uint64_t seed)
{
    uint64_t sm = seed;
    uint64_t a = pft_splitmix64_(&sm);
    uint64_t b = pft_splitmix64_(&sm);
    rng->s[0] = (uint32_t)a;
    rng->s[1] = (uint32_t)(a >> 32);
    rng->s[2] = (uint32_t)b;
    rng->s[3] = (uint32_t)(b >> 32);
    /* splitmix64's output function is a bijection and its two inputs differ, so a and b are
     * never both zero; keep the all-zero guard anyway (xoshiro must not start from zero). */
    if ((rng->s[0] | rng->s[1] | rng->s[2] | rng->s[3]) == 0u) {
        rng->s[0] = 1u;
    }
    rng->spare = PFT_C(0.0);
    rng->has_spare = 0u;
}

uint32_t pft_rng_u32(pft_rng_t *rng) { return pft_rng_next_(rng); }

uint32_t pft_rng_below(pft_rng_t *rng, uint32_t n) { return pft_rng_below_(rng, n); }

pft_real_t pft_rng_uniform(pft_rng_t *rng)
{
    return pft_from_u32_frac(pft_rng_u32(rng));
}

pft_real_t pft_rng_uniform_range(pft_rng_t *rng, pft_real_t lo, pft_real_t hi)
{
    return pft_rng_uniform_range_(rng, lo, hi);
}

pft_real_t pft_rng_gauss(pft_rng_t *rng)
{
    uint32_t a;
    uint32_t b;
    pft_real_t u1;
    pft_real_t theta;
    pft_real_t r;
    if (rng->has_spare != 0u) {
        rng->has_spare = 0u;
        return rng->spare;
    }
    a = pft_rng_u32(rng);
    b = pft_rng_u32(rng);
    /* u1 = 1 - frac(a) lies in (0, 1] (never 0, so log is finite): smallest value 2^-16 in
     * q16 and 2^-24 in float, which truncates |g| at sqrt(-2 ln u1min) = 4.71 and 5.77. */
    u1 = pft_sub(PFT_REAL_ONE, pft_from_u32_frac(a));
    theta = pft_mul(PFT_TWO_PI, pft_from_u32_frac(b));
    r = pft_sqrt(pft_mul_i(pft_neg(pft_log(u1)), 2));
    rng->spare = pft_mul(r, pft_sin(theta));
    rng->has_spare = 1u;
    return pft_mul(r, pft_cos(theta));
}

/* ---------------------------------------------------------------------------------------- */
/* Ziggurat normal draws (rng_int.h): the wedges and the tail, in integer arithmetic.         */

/* 2^-y for y in Q28, y >= 0, as Q31 (y = 0 gives 2^31): 2^-frac from the Q30 table of
 * 2^(-j/128) with linear interpolation (relative error below 4e-6), then the integer shift. */
static uint32_t pft_zig_exp2_q31_(uint64_t y_q28)
{
    const uint64_t k = y_q28 >> 28;
    const uint32_t fr = (uint32_t)(y_q28 & 0x0FFFFFFFu); /* Q28 fraction */
    const uint32_t j = fr >> 21;                          /* 7 bits: table step */
    const uint32_t r = (fr >> 12) & 0x1FFu;               /* 9 bits within the step */
    const uint32_t d = pft_kexp2_tab[j] - pft_kexp2_tab[j + 1u]; /* < 2^23 */
    const uint32_t v = pft_kexp2_tab[j] - ((d * r) >> 9);        /* Q30 */
    return k >= 31u ? 0u : (v << 1) >> (uint32_t)k;
}

/* f(x) = exp(-x^2/2) in Q31 for x in Q24, 0 <= x < 2^26: x^2/2 in Q28 times log2(e). */
static uint32_t pft_zig_f_q31_(uint32_t x_q24)
{
    const uint64_t t_q28 = ((uint64_t)x_q24 * x_q24) >> 21;            /* Q48 / 2 -> Q28 */
    const uint64_t y_q28 = (t_q28 * 1549082005u) >> 30;                /* log2(e) in Q30 */
    return pft_zig_exp2_q31_(y_q28);
}

/* -ln((u + 1/2) / 2^32) in Q24, in (0, 22.9): log2 of v = 2u + 1 by repeated squaring of
 * its mantissa (24 fraction bits), then times ln 2. */
static uint32_t pft_zig_neglog_q24_(uint32_t u)
{
    uint64_t v = 2u * (uint64_t)u + 1u; /* in [1, 2^33) */
    int32_t e = 0;                      /* v = m 2^e with m in [2^30, 2^31) */
    uint32_t step;
    uint64_t m;
    uint32_t y = 0;
    for (step = 0; step < 34u && v >= ((uint64_t)1 << 31); ++step) {
        v >>= 1;
        ++e;
    }
    for (step = 0; step < 31u && v < ((uint64_t)1 << 30); ++step) {
        v <<= 1;
        --e;
    }
    m = v; /* Q30 mantissa in [1, 2) */
    for (step = 0; step < 24u; ++step) {
        m = (m * m) >> 30; /* < 2^32 */
        y <<= 1;
        if (m >= ((uint64_t)1 << 31)) {
            m >>= 1;
            y |= 1u;
        }
    }
    /* log2 v = 30 + e + y 2^-24, and -ln U = ln 2 (33 - log2 v) = ln 2 (3 - e - y 2^-24) */
    {
        const uint64_t l = ((uint64_t)(uint32_t)(3 - e) << 24) - y; /* Q24, >= 0 since e <= 2 */
        return (uint32_t)((l * 2977044472u) >> 32);                 /* ln 2 in Q32 */
    }
}

/* Marsaglia's tail beyond r: a = -ln(U1) / r, b = -ln(U2), accepted when 2b > a^2; the draw is
 * r + a (Q24). Bounded: after 64 rejections (probability below 10^-60) the last a is used. */
static uint32_t pft_zig_tail_q24_(pft_rng_t *rng)
{
    uint32_t a = 0;
    uint32_t round;
    for (round = 0; round < 64u; ++round) {
        const uint32_t l1 = pft_zig_neglog_q24_(pft_rng_next_(rng));
        const uint32_t l2 = pft_zig_neglog_q24_(pft_rng_next_(rng));
        a = (uint32_t)(((uint64_t)l1 * pft_zig_inv_r_q32) >> 32); /* < 6.7 2^24 */
        if (2u * (uint64_t)l2 > (((uint64_t)a * a) >> 24)) {
            break;
        }
    }
    return pft_zig_r_q24 + a;
}

static pft_real_t zig_slow_(pft_rng_t *rng, uint32_t u)
{
    uint32_t w = u;
    uint32_t round;
    /* every round either returns or draws a new word; after 64 rounds (probability below
     * 0.02^64) the last candidate is returned */
    uint32_t mag = 0;
    for (round = 0; round < 64u; ++round) {
        const uint32_t i = w & (PFT_ZIG_LAYERS - 1u);
        const uint32_t m = w >> 8;
        const bool neg = (w & 128u) != 0u;
        mag = (uint32_t)(((uint64_t)m * pft_zig_kw[i][1]) >> 24);
        if (m < pft_zig_kw[i][0]) {
            return pft_zig_fast_((uint64_t)m * pft_zig_kw[i][1], neg ? 1u : 0u);
        }
        if (i == 0u) {
            return pft_zig_real_(pft_zig_tail_q24_(rng), neg);
        }
        {
            /* the wedge of layer i: a uniform height between f(x[i]) and f(x[i+1]) */
            const uint32_t lo = pft_zig_f[i];
            const uint32_t hi = pft_zig_f[i + 1u];
            const uint32_t y =
                lo + (uint32_t)(((uint64_t)(hi - lo) * pft_rng_next_(rng)) >> 32);
            if (y < pft_zig_f_q31_(mag)) {
                return pft_zig_real_(mag, neg);
            }
        }
        w = pft_rng_next_(rng);
    }
    return pft_zig_real_(mag, (w & 128u) != 0u);
}

pft_zig_slow_t pft_rng_zig_slow_(uint32_t s0, uint32_t s1, uint32_t s2, uint32_t s3, uint32_t u)
{
    pft_zig_slow_t r;
    pft_rng_t g;
    memset(&g, 0, sizeof g);
    g.s[0] = s0;
    g.s[1] = s1;
    g.s[2] = s2;
    g.s[3] = s3;
    r.v = zig_slow_(&g, u);
    memcpy(r.s, g.s, sizeof r.s);
    return r;
}

pft_real_t pft_rng_gauss_zig(pft_rng_t *rng) { return pft_rng_zig_(rng); }
