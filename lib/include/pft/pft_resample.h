/**
 * @file pft_resample.h
 * @brief Resampling schemes over weights of any scale (need not be normalised), taking the
 *        input size M and the output size N separately.
 *
 * Uniforms are 32-bit fractions u/2^32, drawn from the instance RNG or given explicitly (the
 * `_u` variants) so tests can check exact indices. Cumulative sums use pft_wacc_t (64-bit
 * integer in q16, exact).
 *
 * Every scheme maps targets T in [0, W) (W = sum of weights) to the index j with
 * c_{j-1} <= T < c_j, c_j = w_0 + ... + w_j; a zero weight is therefore never selected and
 * every index is < M. Targets: systematic T_k = W (k + u0) / N; stratified
 * T_k = W (k + u_k) / N; multinomial T = W u over the sorted uniforms. In q16 this selection
 * is exact (integer comparison against floor(T) of the exact rational target); in float the
 * targets are float products (24-bit resolution), the last cumulative sum equals the total
 * and a target rounding up to W selects the last positive weight.
 * Float weights that are negative or NaN count as zero. M and N are at most
 * PFT_CFG_MAX_PARTICLES (else PFT_ERR_INVAL). Random draws consumed: systematic and residual
 * one u32 (residual none when the deterministic copies fill N), stratified and multinomial N.
 */
#ifndef PFT_RESAMPLE_H
#define PFT_RESAMPLE_H

#include "pft/pft_rng.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Resampling scheme of pft_resample. */
typedef enum {
    PFT_RESAMPLE_SYSTEMATIC = 0,  /**< one draw: targets W (k + u0) / N */
    PFT_RESAMPLE_STRATIFIED = 1,  /**< N draws: targets W (k + u_k) / N */
    PFT_RESAMPLE_RESIDUAL = 2,    /**< floor(N w_i / W) copies, then systematic over the residuals (needs scratch) */
    PFT_RESAMPLE_MULTINOMIAL = 3  /**< N draws: targets W u over the sorted uniforms */
} pft_resample_scheme_t;

/** Scratch bytes a scheme needs for M inputs and N outputs: M * sizeof(pft_weight_t) for
 *  residual (the residual weights; the scratch must be aligned for pft_weight_t), 0 for the
 *  others. */
size_t pft_resample_scratch_size(pft_resample_scheme_t scheme, size_t m, size_t n);

/**
 * Draws N indices into idx[0..n) from weights w[0..m). All weights zero (or m == 0) gives
 * PFT_ERR_DEGENERATE and leaves idx untouched (float: an infinite weight total gives
 * PFT_ERR_RANGE). scratch may be NULL when its size is 0; a short or
 * missing residual scratch gives PFT_ERR_NOMEM. NULL w/idx/rng, an unknown scheme or
 * m, n > PFT_CFG_MAX_PARTICLES give PFT_ERR_INVAL. n == 0 is a no-op (PFT_OK).
 * Output indices are non-decreasing for systematic, stratified and multinomial. Residual
 * writes the floor(N w_i / W) deterministic copies first (index order, exact in q16), then
 * the remaining draws, systematic over the residual weights (each index then appears
 * floor(N w_i / W) or floor(N w_i / W) + 1 times).
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
/** Multinomial with explicit uniforms u[0..n) (fractions of the total, /2^32). u need not be
 *  sorted: it is copied into idx and heap-sorted there (O(n log n), no scratch, exact integer
 *  path in both builds), then each sorted uniform is replaced by its index. */
pft_status_t pft_resample_multinomial_u(const pft_weight_t *w, size_t m, uint32_t *idx, size_t n,
                                        const uint32_t *u);

#ifdef __cplusplus
}
#endif
#endif
