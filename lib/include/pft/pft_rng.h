/**
 * @file pft_rng.h
 * @brief Deterministic per-instance random numbers (xoshiro128**, seeded by splitmix).
 *
 * The integer stream is identical in float and q16 builds and on every target; uniform and
 * Gaussian reals are derived from it by the same integer path, so the two builds differ only
 * in arithmetic. Two Gaussian generators: pft_rng_gauss (Box-Muller on two 32-bit draws, the
 * second value cached) and pft_rng_gauss_zig (an integer ziggurat, about one 32-bit draw per
 * value, several times cheaper; the TBD filters use it).
 */
#ifndef PFT_RNG_H
#define PFT_RNG_H

#include "pft/pft_real.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Generator state: one per instance (no global state); seed it with pft_rng_seed. */
typedef struct {
    uint32_t s[4];      /**< xoshiro128** state */
    pft_real_t spare;   /**< cached second Box-Muller value */
    uint8_t has_spare;  /**< 1 when spare holds an unused Gaussian */
} pft_rng_t;

/** Seeds the generator (any seed, 0 included): two splitmix64 outputs a, b give the state
 *  s = {lo32(a), hi32(a), lo32(b), hi32(b)}; clears the cached Gaussian. */
void pft_rng_seed(pft_rng_t *rng, uint64_t seed);
/** Next 32-bit draw. */
uint32_t pft_rng_u32(pft_rng_t *rng);
/** Uniform integer in [0, n), n >= 1, without modulo bias (Lemire's multiply-shift with
 *  rejection; at most 64 rejection rounds, each taken with probability < 1/2). n == 0 gives 0. */
uint32_t pft_rng_below(pft_rng_t *rng, uint32_t n);
/** Uniform real in [0, 1): pft_from_u32_frac of one draw (q16: 2^-16 steps, float: 2^-24). */
pft_real_t pft_rng_uniform(pft_rng_t *rng);
/** Uniform real in [lo, hi) (one draw); returns lo when hi <= lo. */
pft_real_t pft_rng_uniform_range(pft_rng_t *rng, pft_real_t lo, pft_real_t hi);
/** Standard normal draw (Box-Muller: radius from u1 = 1 - frac(a) in (0, 1], angle from b).
 *  Tails are truncated where the uniform's resolution ends (q16: |g| <= sqrt(-2 ln 2^-16)
 *  = 4.71; float: |g| <= sqrt(-2 ln 2^-24) = 5.77), documented in docs/fixed_point.md. */
pft_real_t pft_rng_gauss(pft_rng_t *rng);
/** Standard normal draw by a 128-layer ziggurat (Marsaglia & Tsang 2000) in integer arithmetic
 *  only: identical decisions and draws in both builds and on every target; the value is an
 *  integer magnitude in Q24 with a sign (q16: rounded to Q16.16, float: scaled by 2^-24).
 *  98.8 % of values take exactly one 32-bit draw; the rest take a few more. The tail is exact
 *  up to the 32-bit uniforms it is made from (|g| <= 10.1). Independent of pft_rng_gauss's
 *  cached value. docs/fixed_point.md gives the measured statistics. */
pft_real_t pft_rng_gauss_zig(pft_rng_t *rng);

#ifdef __cplusplus
}
#endif
#endif
