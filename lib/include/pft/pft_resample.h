/**
 * @file pft_resample.h
 * @brief Resampling schemes over weights of any scale (need not be normalised), taking the
 *        input size M and the output size N separately.
 *
 * Uniforms are 32-bit fractions u/2^32, drawn from the instance RNG or given explicitly (the
 * `_u` variants) so tests can check exact indices. Cumulative sums use pft_wacc_t (64-bit
 * integer in q16, exact).
 */
#ifndef PFT_RESAMPLE_H
#define PFT_RESAMPLE_H

#include "pft/pft_rng.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum {
    PFT_RESAMPLE_SYSTEMATIC = 0,
    PFT_RESAMPLE_STRATIFIED = 1,
    PFT_RESAMPLE_RESIDUAL = 2,
    PFT_RESAMPLE_MULTINOMIAL = 3
} pft_resample_scheme_t;

/** Scratch bytes a scheme needs for M inputs and N outputs (0 for systematic/stratified). */
size_t pft_resample_scratch_size(pft_resample_scheme_t scheme, size_t m, size_t n);

/**
 * Draws N indices into idx[0..n) from weights w[0..m). All weights zero (or m == 0) gives
 * PFT_ERR_RANGE and leaves idx untouched. scratch may be NULL when its size is 0.
 * Output indices are non-decreasing for systematic, stratified and multinomial.
 */
pft_status_t pft_resample(pft_resample_scheme_t scheme, const pft_weight_t *w, size_t m,
                          uint32_t *idx, size_t n, pft_rng_t *rng, void *scratch,
                          size_t scratch_len);

/** Systematic with an explicit offset u0 (fraction of 1/N as u0/2^32). */
pft_status_t pft_resample_systematic_u(const pft_weight_t *w, size_t m, uint32_t *idx, size_t n,
                                       uint32_t u0);
/** Stratified with explicit uniforms u[0..n) (each a fraction of its stratum, /2^32). */
pft_status_t pft_resample_stratified_u(const pft_weight_t *w, size_t m, uint32_t *idx, size_t n,
                                       const uint32_t *u);
/** Multinomial with explicit uniforms u[0..n) (fractions of the total, /2^32; sorted inside
 *  by generating order statistics, so u need not be sorted). scratch: n uint32_t. */
pft_status_t pft_resample_multinomial_u(const pft_weight_t *w, size_t m, uint32_t *idx, size_t n,
                                        const uint32_t *u);

#ifdef __cplusplus
}
#endif
#endif
