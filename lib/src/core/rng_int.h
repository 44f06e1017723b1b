/* The random stream's hot paths, inline for the particle loops (private, not installed).
 *
 * pft_rng_next_: one xoshiro128** step (pft_rng_u32 is this, called).
 *
 * pft_rng_zig_: a standard normal draw by the ziggurat of Marsaglia & Tsang (2000) in integer
 * arithmetic only, the same in both builds and on every target. 128 layers of equal area
 * under f(x) = exp(-x^2/2) (tables in pft_rng_tables.c, made by
 * host_tools/scripts/gen_rng_tables.py). One 32-bit word w gives the layer i (bits 0-6), the
 * sign (bit 7) and a 24-bit position m (bits 8-31); when m < k[i] (98.8 % of words) the draw is
 * |x| = m w[i] / 2^24 in Q24, exactly under the density, and the word is all it consumes. The
 * rest (the wedges beside each layer and the tail beyond r = 3.4426) goes to
 * pft_rng_zig_slow_ in pft_rng.c, which draws more words. The magnitude is an integer in Q24;
 * the q16 build rounds it to Q16.16, the float build scales it by 2^-24, so both builds draw
 * the same Gaussians up to that last rounding (docs/fixed_point.md, "RNG and resampling").
 */
#ifndef PFT_CORE_RNG_INT_H
#define PFT_CORE_RNG_INT_H

#include <string.h>

#include "pft/pft_rng.h"

#define PFT_ZIG_LAYERS 128u

extern const uint32_t pft_zig_w[PFT_ZIG_LAYERS];
extern const uint32_t pft_zig_k[PFT_ZIG_LAYERS];
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

/* A Q24 magnitude and a sign as the build's real (q16: rounded to Q16.16; float: exact
 * scaling of a value below 2^28, rounded to 24 bits). */
static inline pft_real_t pft_zig_real_(uint32_t mag_q24, bool neg)
{
#ifdef PFT_NUMERIC_Q16
    const int32_t v = (int32_t)((mag_q24 + 128u) >> 8);
    const int32_t sg = -(int32_t)neg; /* 0 or -1: v or -v without a branch */
    return (v ^ sg) - sg;
#else
    const float v = (float)(int32_t)mag_q24 * 5.9604644775390625e-8f;
    uint32_t b;
    float r;
    memcpy(&b, &v, sizeof b);
    b ^= (uint32_t)neg << 31;
    memcpy(&r, &b, sizeof r);
    return r;
#endif
}

/* The draws that word u does not settle at once (pft_rng.c). */
pft_real_t pft_rng_zig_slow_(pft_rng_t *rng, uint32_t u);

/* The slow path works on a copy of the state, so that a caller's generator whose address
 * never escapes (a local copy in a particle loop) can live in registers. */
static inline pft_real_t pft_rng_zig_(pft_rng_t *rng)
{
    const uint32_t u = pft_rng_next_(rng);
    const uint32_t i = u & (PFT_ZIG_LAYERS - 1u);
    const uint32_t m = u >> 8;
    if (m < pft_zig_k[i]) {
        return pft_zig_real_((uint32_t)(((uint64_t)m * pft_zig_w[i]) >> 24), (u & 128u) != 0u);
    }
    {
        pft_rng_t t = *rng;
        const pft_real_t v = pft_rng_zig_slow_(&t, u);
        *rng = t;
        return v;
    }
}

#endif
