/* The random stream's hot paths, inline for the particle loops (private, not installed).
 *
 * pft_rng_next_: one xoshiro128** step (pft_rng_u32 is this, called); pft_rng_below_ and
 * pft_rng_uniform_range_: pft_rng_below and pft_rng_uniform_range (which call them).
 *
 * pft_rng_zig_: a standard normal draw by the ziggurat of Marsaglia & Tsang (2000) in integer
 * arithmetic only, the same in both builds and on every target. 128 layers of equal area
 * under f(x) = exp(-x^2/2) (tables in pft_rng_tables.c, made by
 * host_tools/scripts/gen_rng_tables.py). One 32-bit word w gives the layer i (bits 0-6), the
 * sign (bit 7) and a 24-bit position m (bits 8-31); when m < k[i] (98.8 % of words) the draw is
 * |x| = m w[i] / 2^48 (the product exact in 64 bits), under the density, and the word is all
 * it consumes (the fast path reads k and the signed edge by the low byte, layer and sign at
 * once, and forms the signed product). The rest (the wedges beside each layer and the tail
 * beyond r = 3.4426) goes to pft_rng_zig_slow_ in pft_rng.c, which draws more words and forms
 * Q24 magnitudes. The q16 build rounds the exact value to Q16.16 once, the float build to a
 * float once, so both builds draw the same Gaussians up to that last rounding
 * (docs/fixed_point.md, "RNG and resampling").
 */
#ifndef PFT_CORE_RNG_INT_H
#define PFT_CORE_RNG_INT_H

#include <string.h>

#include "pft/pft_rng.h"

#define PFT_ZIG_LAYERS 128u

extern const uint32_t pft_zig_kw[PFT_ZIG_LAYERS][2]; /* k[i] (fast acceptance), w[i] (Q24 edge) */
/* by the word's low byte j (layer j mod 128, sign bit 7): k, and w negated for j >= 128 */
extern const int32_t pft_zig_ksw[2u * PFT_ZIG_LAYERS][2];
extern const uint32_t pft_zig_f[PFT_ZIG_LAYERS + 1u];
extern const uint32_t pft_zig_r_q24;
extern const uint32_t pft_zig_inv_r_q32;

static inline uint32_t pft_rng_rotl_(uint32_t x, unsigned k) { return (x << k) | (x >> (32u - k)); }

static inline uint32_t pft_rng_next_(pft_rng_t *rng)
{
    uint32_t *s = rng->s;
    const uint32_t result = pft_rng_rotl_(s[1] * 5u, 7u) * 9u;
    const uint32_t t = s[1] << 9;
    s[2] ^= s[0];
    s[3] ^= s[1];
    s[1] ^= s[2];
    s[0] ^= s[3];
    s[2] ^= t;
    s[3] = pft_rng_rotl_(s[3], 11u);
    return result;
}

/* Upper bound on Lemire rejection rounds. One round is rejected with probability
 * (2^32 mod n) / 2^32 < 1/2, so reaching the bound has probability below 2^-64; the loop is
 * bounded anyway (rule: every loop bounded), and the last candidate is then used as is. */
#define PFT_RNG_MAX_REJECT 64u

/* pft_rng_below inline (the births' pixel draw): Lemire 2019, "Fast random integer generation
 * in an interval": the high word of the 64-bit product x*n is uniform on [0, n) once products
 * whose low word falls below 2^32 mod n are rejected. */
static inline uint32_t pft_rng_below_(pft_rng_t *rng, uint32_t n)
{
    uint64_t m;
    uint32_t lo;
    if (n <= 1u) {
        return 0u;
    }
    m = (uint64_t)pft_rng_next_(rng) * n;
    lo = (uint32_t)m;
    if (lo < n) {
        const uint32_t thresh = (uint32_t)(0u - n) % n; /* 2^32 mod n */
        uint32_t round = 0u;
        while (lo < thresh && round < PFT_RNG_MAX_REJECT) {
            m = (uint64_t)pft_rng_next_(rng) * n;
            lo = (uint32_t)m;
            ++round;
        }
    }
    return (uint32_t)(m >> 32);
}

/* pft_rng_uniform_range inline (the births' intensity draw). */
static inline pft_real_t pft_rng_uniform_range_(pft_rng_t *rng, pft_real_t lo, pft_real_t hi)
{
    const uint32_t u = pft_rng_next_(rng);
    if (!(lo < hi)) {
        return lo;
    }
#ifdef PFT_NUMERIC_Q16
    {
        /* Exact: lo + floor((hi - lo) * u16 / 2^16) with a 64-bit span, so the result is in
         * [lo, hi) even when hi - lo does not fit in Q16.16. */
        const int64_t span = (int64_t)hi - (int64_t)lo; /* in (0, 2^32) */
        const int64_t off = (span * (int64_t)(u >> 16)) >> 16;
        return (pft_real_t)((int64_t)lo + off);
    }
#else
    {
        const pft_real_t f = pft_from_u32_frac(u);
        const pft_real_t span = pft_sub(hi, lo);
        /* hi - lo may overflow to infinity (inf * 0 would be NaN): then use the convex form,
         * whose two terms have opposite signs. */
        const pft_real_t r = span <= PFT_REAL_MAX
                                 ? pft_add(lo, pft_mul(span, f))
                                 : pft_add(pft_mul(lo, pft_sub(PFT_REAL_ONE, f)), pft_mul(hi, f));
        /* Rounding may land on hi: step back inside. */
        return r < hi ? (r < lo ? lo : r) : nextafterf(hi, lo);
    }
#endif
}

/* A Q24 magnitude and a sign as the build's real (q16: rounded to Q16.16; float: exact
 * scaling of a value below 2^28, rounded to 24 bits). The slow path's draws. */
static inline pft_real_t pft_zig_real_(uint32_t mag_q24, bool neg)
{
#ifdef PFT_NUMERIC_Q16
    const int32_t v = (int32_t)((mag_q24 + 128u) >> 8);
    const int32_t sg = -(int32_t)neg; /* 0 or -1: v or -v without a branch */
    return (v ^ sg) - sg;
#else
    const float v = (float)(int32_t)mag_q24 * 5.9604644775390625e-8f;
    return neg ? -v : v;
#endif
}

/* The fast path's draws from the exact product p = m w (Q48, below 2^50) and the sign bit:
 * q16 rounds p to Q16.16 once, float converts it once and scales by +-2^-48. */
static inline pft_real_t pft_zig_fast_(uint64_t p, uint32_t sign_bit)
{
#ifdef PFT_NUMERIC_Q16
    const int32_t v = (int32_t)((p + 0x80000000u) >> 32);
    const int32_t sg = -(int32_t)sign_bit;
    return (v ^ sg) - sg;
#else
    static const float scale[2] = {3.5527136788005009e-15f, -3.5527136788005009e-15f};
    return (float)(int64_t)p * scale[sign_bit];
#endif
}

/* pft_zig_fast_ of a signed product p = +-m w (the sign in the product): the same value.
 * q16: floor((p + 2^31 - [p < 0]) / 2^32) is -floor((|p| + 2^31) / 2^32) for p < 0 (round
 * half away from zero, as the magnitude's rounding and negation); float: the conversion
 * rounds symmetrically, so (float)(-a) = -(float)a. */
static inline pft_real_t pft_zig_sfast_(int64_t p)
{
#ifdef PFT_NUMERIC_Q16
    return (pft_real_t)((p + (int64_t)0x80000000u - (p < 0 ? 1 : 0)) >> 32);
#else
    return (float)p * 3.5527136788005009e-15f;
#endif
}

/* The draws that word u does not settle at once (pft_rng.c): the generator's words go in as
 * scalars and come back in the result, so that a caller's generator kept in a local never has
 * its address taken (and is never assembled in memory on the fast path). */
typedef struct {
    pft_real_t v;
    uint32_t s[4];
} pft_zig_slow_t;
pft_zig_slow_t pft_rng_zig_slow_(uint32_t s0, uint32_t s1, uint32_t s2, uint32_t s3, uint32_t u);

/* The fast path inline; the rest by value (above). */
static inline pft_real_t pft_rng_zig_(pft_rng_t *rng)
{
    const uint32_t u = pft_rng_next_(rng);
    const uint32_t m = u >> 8;
    const int32_t *kw = pft_zig_ksw[u & (2u * PFT_ZIG_LAYERS - 1u)]; /* layer and sign */
    if (m < (uint32_t)kw[0]) {
        return pft_zig_sfast_((int64_t)m * kw[1]);
    }
    {
        const pft_zig_slow_t r = pft_rng_zig_slow_(rng->s[0], rng->s[1], rng->s[2], rng->s[3], u);
        rng->s[0] = r.s[0];
        rng->s[1] = r.s[1];
        rng->s[2] = r.s[2];
        rng->s[3] = r.s[3];
        return r.v;
    }
}

#endif
