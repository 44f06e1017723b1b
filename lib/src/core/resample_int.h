/* Systematic resampling as a stream of targets, for walks fused into other passes (private,
 * not installed). The targets are those of pft_resample's systematic scheme,
 * T_k = W (k + u / 2^32) / N for k = 0, 1, ..., N - 1 over a total weight W; a particle whose
 * cumulative weight range [c_{j-1}, c_j) holds r targets is replicated r times.
 *
 * q16: exact, as in pft_resample.c. Since the cumulative sums c_j are integers, c_j > T_k
 * exactly when c_j > floor(T_k). floor(T_0) = floor(W u / (N 2^32)) is formed from
 * W = q N + r and q = qh 2^32 + ql with integer parts qh u + (ql u >> 32) and fractional
 * parts over D = N 2^32 (< 2^54); each further target adds q to the integer part and r 2^32
 * to the fraction (< 2 D), with one carry.
 * float: T_k = (W / N)(k + u), the same expression as pft_resample's float walk.
 */
#ifndef PFT_CORE_RESAMPLE_INT_H
#define PFT_CORE_RESAMPLE_INT_H

#include "pft/pft_real.h"

#ifdef PFT_NUMERIC_Q16

typedef struct {
    uint64_t t;  /* floor(T_k) */
    uint64_t fr; /* fraction of T_k over d */
    uint64_t q;  /* W / N, integer part */
    uint64_t rr; /* (W mod N) 2^32 */
    uint64_t d;  /* N 2^32 */
} pft_sys_t;

static inline void pft_sys_init_(pft_sys_t *s, pft_wacc_t total, uint32_t n, uint32_t u)
{
    const uint64_t q = total / n;
    const uint64_t r = total % n;
    const uint64_t qlu = (q & 0xFFFFFFFFu) * u;
    s->d = (uint64_t)n << 32;
    s->t = (q >> 32) * u + (qlu >> 32);
    s->fr = (qlu & 0xFFFFFFFFu) * n + r * u; /* < 2 d */
    if (s->fr >= s->d) {
        s->fr -= s->d;
        s->t += 1u;
    }
    s->q = q;
    s->rr = r << 32;
}

/* k is the index of the new target; after the last (k == n) the target is past every
 * cumulative weight, so a walk ends without testing k. */
static inline void pft_sys_next_(pft_sys_t *s, uint32_t k, uint32_t n)
{
    if (k >= n) {
        s->t = UINT64_MAX;
        return;
    }
    s->t += s->q;
    s->fr += s->rr;
    if (s->fr >= s->d) {
        s->fr -= s->d;
        s->t += 1u;
    }
}

/* The cumulative weight c lies above the current target. */
static inline bool pft_sys_below_(const pft_sys_t *s, pft_wacc_t c) { return c > s->t; }

#else

typedef struct {
    float step; /* W / N */
    float u;    /* u / 2^32 */
    float t;    /* T_k */
} pft_sys_t;

static inline void pft_sys_init_(pft_sys_t *s, pft_wacc_t total, uint32_t n, uint32_t u)
{
    s->step = total / (float)n;
    s->u = pft_from_u32_frac(u);
    s->t = s->step * s->u;
}

/* k is the index of the new target (exact as a float: k < 2^22); after the last (k == n) the
 * target is past every cumulative weight. */
static inline void pft_sys_next_(pft_sys_t *s, uint32_t k, uint32_t n)
{
    s->t = k >= n ? PFT_REAL_MAX : s->step * (float)k + s->step * s->u;
}

static inline bool pft_sys_below_(const pft_sys_t *s, pft_wacc_t c) { return c > s->t; }

#endif

#endif
