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
 * float: T_k = (W / N)(k + u), as pft_resample's float walk; the targets below a cumulative
 * weight c are those k < min(N, c N / W - u), counted one by one against k held as an exact
 * float (the same counts as min(N, ceil(c N / W - u)) at one comparison per target).
 *
 * pft_sys_take_(s, c): the targets below the cumulative weight c not taken yet (the
 * replication count of the particle whose range ends at c), in order of c.
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
    uint32_t k, n;
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
    s->k = 0u;
    s->n = n;
}

/* The next target (exact: T_k = t + fr / d throughout). fr, rr < d, so fr + rr < 2 d and one
 * carry c (0 or 1) brings it back below d; c is formed as a value and a mask, not a branch. */
static inline void pft_sys_next_(pft_sys_t *s)
{
    const uint64_t fr = s->fr + s->rr;
    const uint64_t c = fr >= s->d ? (uint64_t)1 : (uint64_t)0;
    s->k += 1u;
    s->fr = fr - (s->d & (0u - c));
    s->t += s->q + c;
}

/* c_j > T_k exactly when c_j > floor(T_k) (c_j an integer). Ends: T_n = W (1 + u / (N 2^32))
 * >= W, so floor(T_n) >= W >= c for every cumulative weight c of the walk (the callers' last
 * c is W itself): the loop stops at k = n at the latest, without a test of k. */
static inline uint32_t pft_sys_take_(pft_sys_t *s, pft_wacc_t c)
{
    const uint32_t k0 = s->k;
    while (c > s->t) {
        pft_sys_next_(s);
    }
    return s->k - k0;
}

/* Targets not taken by the walk (float rounding only; 0 here). */
static inline uint32_t pft_sys_left_(const pft_sys_t *s) { return s->n - s->k; }

#else

typedef struct {
    float inv_step; /* N / W */
    float u;        /* u / 2^32 */
    float lim;      /* N */
    float fk;       /* k, exact (k <= N <= 2^22 < 2^24) */
    uint32_t k, n;
} pft_sys_t;

static inline void pft_sys_init_(pft_sys_t *s, pft_wacc_t total, uint32_t n, uint32_t u)
{
    s->inv_step = total > 0.0f ? (float)n / total : 0.0f;
    s->u = pft_from_u32_frac(u);
    s->lim = (float)n;
    s->fk = 0.0f;
    s->k = 0u;
    s->n = n;
}

/* T_k < c exactly when k < q = c N / W - u: the targets k, k + 1, ... below min(q, N) are
 * taken one by one (about one per particle), as many as min(n, ceil(q)) - k when that is
 * positive. fk < q <= N bounds the loop by N - k. */
static inline uint32_t pft_sys_take_(pft_sys_t *s, pft_wacc_t c)
{
    const float q0 = c * s->inv_step - s->u;
    const float q = q0 < s->lim ? q0 : s->lim;
    const uint32_t k0 = s->k;
    while (s->fk < q) {
        s->fk += 1.0f;
        s->k += 1u;
    }
    return s->k - k0;
}

static inline uint32_t pft_sys_left_(const pft_sys_t *s) { return s->n - s->k; }

#endif

#endif
