/*
 * Deterministic per-instance random numbers: xoshiro128** (Blackman & Vigna 2018) seeded by
 * splitmix64. Everything up to the 32-bit draw is integer arithmetic, so the stream is the
 * same in the float and the q16 build and on every target; reals are derived from it through
 * pft_from_u32_frac (q16: top 16 bits; float: top 24 bits).
 */
#include "pft/pft_rng.h"

/* Upper bound on Lemire rejection rounds. One round is rejected with probability
 * (2^32 mod n) / 2^32 < 1/2, so reaching the bound has probability below 2^-64; the loop is
 * bounded anyway (rule: every loop bounded), and the last candidate is then used as is. */
#define PFT_RNG_MAX_REJECT 64u

static uint64_t pft_splitmix64_(uint64_t *state)
{
    uint64_t z;
    *state += 0x9E3779B97F4A7C15ull;
    z = *state;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

static inline uint32_t pft_rotl32_(uint32_t x, unsigned k)
{
    return (x << k) | (x >> (32u - k));
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

uint32_t pft_rng_u32(pft_rng_t *rng)
{
    uint32_t *s = rng->s;
    const uint32_t result = pft_rotl32_(s[1] * 5u, 7u) * 9u;
    const uint32_t t = s[1] << 9;
    s[2] ^= s[0];
    s[3] ^= s[1];
    s[1] ^= s[2];
    s[0] ^= s[3];
    s[2] ^= t;
    s[3] = pft_rotl32_(s[3], 11u);
    return result;
}

uint32_t pft_rng_below(pft_rng_t *rng, uint32_t n)
{
    /* Lemire 2019, "Fast random integer generation in an interval": the high word of the
     * 64-bit product x*n is uniform on [0, n) once products whose low word falls below
     * 2^32 mod n are rejected. */
    uint64_t m;
    uint32_t lo;
    if (n <= 1u) {
        return 0u;
    }
    m = (uint64_t)pft_rng_u32(rng) * n;
    lo = (uint32_t)m;
    if (lo < n) {
        const uint32_t thresh = (uint32_t)(0u - n) % n; /* 2^32 mod n */
        uint32_t round = 0u;
        while (lo < thresh && round < PFT_RNG_MAX_REJECT) {
            m = (uint64_t)pft_rng_u32(rng) * n;
            lo = (uint32_t)m;
            ++round;
        }
    }
    return (uint32_t)(m >> 32);
}

pft_real_t pft_rng_uniform(pft_rng_t *rng)
{
    return pft_from_u32_frac(pft_rng_u32(rng));
}

pft_real_t pft_rng_uniform_range(pft_rng_t *rng, pft_real_t lo, pft_real_t hi)
{
    const uint32_t u = pft_rng_u32(rng);
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
