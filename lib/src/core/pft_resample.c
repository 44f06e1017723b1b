/*
 * Resampling: systematic, stratified, residual and multinomial over M weights of any scale,
 * drawing N indices.
 *
 * Every scheme reduces to one walk: for non-decreasing targets T_0 <= T_1 <= ... in
 * [0, W) (W the total weight), output k gets the smallest j with c_j > T_k, where
 * c_j = w_0 + ... + w_j. Then c_{j-1} <= T_k < c_j, so a zero weight is never selected and
 * j < M always. The walk advances j and k only forward (at most M + N steps).
 *
 * q16: weights are uint32 and the cumulative sums uint64, so they are exact. The targets are
 * rationals T_k = W (k + u_k / 2^32) / N; since c_j is an integer, c_j > T_k exactly when
 * c_j > floor(T_k), and floor(T_k) is computed exactly with 64-bit integers (see pft_tgt_*).
 * The q16 path therefore selects exactly the index real arithmetic would.
 *
 * float: weights, sums and targets are float. The total W is accumulated in the same order as
 * the walk's running sum, so the last cumulative equals W bit for bit; targets that round up
 * to W are caught by clamping to the last index with a positive weight.
 */
#include "pft/pft_resample.h"

/* ----------------------------------------------------------------------------------------- */
/* Uniform source: explicit array or the instance RNG.                                        */
typedef struct {
    const uint32_t *u;
    pft_rng_t *rng;
} pft_usrc_t;

static uint32_t pft_usrc_next_(pft_usrc_t *src, size_t k)
{
    return src->u != NULL ? src->u[k] : pft_rng_u32(src->rng);
}

/* ----------------------------------------------------------------------------------------- */
/* Numeric layer of the walk.                                                                 */
#ifdef PFT_NUMERIC_Q16

static pft_wacc_t pft_wpos_(pft_weight_t w)
{
    return (pft_wacc_t)w;
}

/* Exact floor(T) for T = W (k + u/2^32) / N, kept incrementally over k.
 * With W = q N + r (r < N) and q = qh 2^32 + ql:
 *   W k / N      = q k + r k / N                 (base, kept as bi + br/N, br < N)
 *   W u / (N 2^32) = qh u + (ql u) / 2^32 + r u / (N 2^32)
 * All fractional parts are brought over the denominator D = N 2^32 (< 2^54), summed (< 3 D),
 * and carried into the integer part with at most two subtractions. */
typedef struct {
    uint64_t q;
    uint64_t n;
    uint64_t r;
    uint64_t d;
    uint64_t bi; /* integer part of W k / N */
    uint64_t br; /* remainder (over N) of W k / N */
} pft_tgt_t;

static void pft_tgt_init_(pft_tgt_t *t, pft_wacc_t total, size_t n)
{
    t->n = (uint64_t)n;
    t->q = total / t->n;
    t->r = total % t->n;
    t->d = t->n << 32;
    t->bi = 0u;
    t->br = 0u;
}

static void pft_tgt_step_(pft_tgt_t *t)
{
    t->bi += t->q;
    t->br += t->r;
    if (t->br >= t->n) {
        t->br -= t->n;
        t->bi += 1u;
    }
}

/* floor(W (k + u/2^32) / N) for the current k. */
static pft_wacc_t pft_tgt_floor_(const pft_tgt_t *t, uint32_t u)
{
    const uint64_t qh = t->q >> 32;
    const uint64_t ql = t->q & 0xFFFFFFFFull;
    const uint64_t qlu = ql * u;
    uint64_t ipart = t->bi + qh * u + (qlu >> 32);
    uint64_t frac = (t->br << 32) + (qlu & 0xFFFFFFFFull) * t->n + t->r * u;
    unsigned i;
    for (i = 0u; i < 2u && frac >= t->d; ++i) {
        frac -= t->d;
        ipart += 1u;
    }
    return ipart;
}

/* floor(W u / 2^32), exact (multinomial and the residual fallback). */
static pft_wacc_t pft_tgt_scaled_(pft_wacc_t total, uint32_t u)
{
    return (total >> 32) * u + (((total & 0xFFFFFFFFull) * u) >> 32);
}

#else /* float */

static pft_wacc_t pft_wpos_(pft_weight_t w)
{
    /* Negative and NaN weights count as zero (a NaN fails the comparison). */
    return w > 0.0f ? w : 0.0f;
}

typedef struct {
    float step; /* W / N */
    float k;    /* current output index as a float */
} pft_tgt_t;

static void pft_tgt_init_(pft_tgt_t *t, pft_wacc_t total, size_t n)
{
    t->step = total / (float)n;
    t->k = 0.0f;
}

static void pft_tgt_step_(pft_tgt_t *t)
{
    t->k += 1.0f; /* exact: k < 2^22 */
}

static pft_wacc_t pft_tgt_floor_(const pft_tgt_t *t, uint32_t u)
{
    return t->step * t->k + t->step * pft_from_u32_frac(u);
}

static pft_wacc_t pft_tgt_scaled_(pft_wacc_t total, uint32_t u)
{
    return total * pft_from_u32_frac(u);
}

#endif

/* Total weight and index of the last positive weight. Returns false when nothing is positive
 * (or, in float, when the total is not finite). */
/* Total of the positive weights and the index of the last positive one. PFT_ERR_DEGENERATE
 * when there is none (or m == 0), PFT_ERR_RANGE when (float) the total overflowed. */
static pft_status_t pft_total_(const pft_weight_t *w, size_t m, pft_wacc_t *total, size_t *last)
{
    pft_wacc_t sum = 0;
    size_t j;
    size_t lastpos = 0u;
    bool any = false;
    for (j = 0u; j < m; ++j) {
        const pft_wacc_t wj = pft_wpos_(w[j]);
        if (wj > 0) {
            any = true;
            lastpos = j;
        }
        sum += wj;
    }
#ifdef PFT_NUMERIC_FLOAT
    if (!(sum <= PFT_REAL_MAX)) {
        return PFT_ERR_RANGE; /* overflowed to infinity */
    }
#endif
    *total = sum;
    *last = lastpos;
    return any && sum > 0 ? PFT_OK : PFT_ERR_DEGENERATE;
}

/* The walk with a running cumulative sum c (c == c_j). */
typedef struct {
    const pft_weight_t *w;
    size_t j;
    size_t last;
    pft_wacc_t c;
} pft_walk_t;

static void pft_walk_init_(pft_walk_t *wk, const pft_weight_t *w, size_t last)
{
    wk->w = w;
    wk->j = 0u;
    wk->last = last;
    wk->c = pft_wpos_(w[0]);
}

static uint32_t pft_walk_to_(pft_walk_t *wk, pft_wacc_t target)
{
    while (wk->j < wk->last && !(wk->c > target)) {
        wk->j += 1u;
        wk->c += pft_wpos_(wk->w[wk->j]);
    }
    return (uint32_t)wk->j;
}

static bool pft_args_ok_(const pft_weight_t *w, size_t m, const uint32_t *idx, size_t n)
{
    return w != NULL && idx != NULL && m <= (size_t)PFT_CFG_MAX_PARTICLES &&
           n <= (size_t)PFT_CFG_MAX_PARTICLES;
}

/* ----------------------------------------------------------------------------------------- */
/* Systematic (u_k all equal) and stratified (u_k independent).                               */
static void pft_strat_walk_(const pft_weight_t *w, pft_wacc_t total, size_t last, uint32_t *idx,
                            size_t n, pft_usrc_t *src, bool systematic)
{
    pft_tgt_t t;
    pft_walk_t wk;
    size_t k;
    uint32_t u = 0u;
    pft_tgt_init_(&t, total, n);
    pft_walk_init_(&wk, w, last);
    for (k = 0u; k < n; ++k) {
        if (!systematic || k == 0u) {
            u = pft_usrc_next_(src, systematic ? 0u : k);
        }
        idx[k] = pft_walk_to_(&wk, pft_tgt_floor_(&t, u));
        pft_tgt_step_(&t);
    }
}

pft_status_t pft_resample_systematic_u(const pft_weight_t *w, size_t m, uint32_t *idx, size_t n,
                                       uint32_t u0)
{
    pft_wacc_t total;
    pft_status_t st;
    size_t last;
    pft_usrc_t src;
    if (!pft_args_ok_(w, m, idx, n)) {
        return PFT_ERR_INVAL;
    }
    if (m == 0u) {
        return PFT_ERR_DEGENERATE;
    }
    st = pft_total_(w, m, &total, &last);
    if (st != PFT_OK) {
        return st;
    }
    if (n == 0u) {
        return PFT_OK;
    }
    src.u = &u0;
    src.rng = NULL;
    pft_strat_walk_(w, total, last, idx, n, &src, true);
    return PFT_OK;
}

pft_status_t pft_resample_stratified_u(const pft_weight_t *w, size_t m, uint32_t *idx, size_t n,
                                       const uint32_t *u)
{
    pft_wacc_t total;
    pft_status_t st;
    size_t last;
    pft_usrc_t src;
    if (!pft_args_ok_(w, m, idx, n) || (u == NULL && n > 0u)) {
        return PFT_ERR_INVAL;
    }
    if (m == 0u) {
        return PFT_ERR_DEGENERATE;
    }
    st = pft_total_(w, m, &total, &last);
    if (st != PFT_OK) {
        return st;
    }
    if (n == 0u) {
        return PFT_OK;
    }
    src.u = u;
    src.rng = NULL;
    pft_strat_walk_(w, total, last, idx, n, &src, false);
    return PFT_OK;
}

/* ----------------------------------------------------------------------------------------- */
/* Multinomial: the n uniforms are sorted in place in idx (heap sort: no recursion, no
 * scratch, O(n log n), loops bounded by n log2 n), then mapped through one walk. Sorting the
 * given uniforms keeps the integer path exact in q16, where transcendental order-statistic
 * generators (exponential spacings, u^(1/k)) would quantise the draws. */
static void pft_sift_down_(uint32_t *a, size_t start, size_t end)
{
    size_t root = start;
    /* Each pass moves root to a child index >= 2 root + 1, so at most log2(end) passes. */
    while (2u * root + 1u < end) {
        size_t child = 2u * root + 1u;
        size_t top = root;
        if (a[top] < a[child]) {
            top = child;
        }
        if (child + 1u < end && a[top] < a[child + 1u]) {
            top = child + 1u;
        }
        if (top == root) {
            return;
        }
        {
            const uint32_t tmp = a[root];
            a[root] = a[top];
            a[top] = tmp;
        }
        root = top;
    }
}

static void pft_heap_sort_(uint32_t *a, size_t n)
{
    size_t i;
    if (n < 2u) {
        return;
    }
    for (i = n / 2u; i > 0u; --i) {
        pft_sift_down_(a, i - 1u, n);
    }
    for (i = n - 1u; i > 0u; --i) {
        const uint32_t tmp = a[0];
        a[0] = a[i];
        a[i] = tmp;
        pft_sift_down_(a, 0u, i);
    }
}

/* idx[0..n) holds sorted uniforms on entry and indices on exit (each slot read, then written). */
static void pft_multi_walk_(const pft_weight_t *w, pft_wacc_t total, size_t last, uint32_t *idx,
                            size_t n)
{
    pft_walk_t wk;
    size_t k;
    pft_walk_init_(&wk, w, last);
    for (k = 0u; k < n; ++k) {
        idx[k] = pft_walk_to_(&wk, pft_tgt_scaled_(total, idx[k]));
    }
}

pft_status_t pft_resample_multinomial_u(const pft_weight_t *w, size_t m, uint32_t *idx, size_t n,
                                        const uint32_t *u)
{
    pft_wacc_t total;
    pft_status_t st;
    size_t last;
    size_t k;
    if (!pft_args_ok_(w, m, idx, n) || (u == NULL && n > 0u)) {
        return PFT_ERR_INVAL;
    }
    if (m == 0u) {
        return PFT_ERR_DEGENERATE;
    }
    st = pft_total_(w, m, &total, &last);
    if (st != PFT_OK) {
        return st;
    }
    for (k = 0u; k < n; ++k) {
        idx[k] = u[k];
    }
    pft_heap_sort_(idx, n);
    pft_multi_walk_(w, total, last, idx, n);
    return PFT_OK;
}

/* ----------------------------------------------------------------------------------------- */
/* Residual: output k gets floor(N w_k / W) deterministic copies; the R = N - sum of copies
 * remaining draws are systematic over the residual weights N w_k / W - copies_k, stored as
 * pft_weight_t in the scratch (q16: 32-bit fractions of one, i.e. residual * 2^32, truncated;
 * float: the residual itself). The deterministic copies come first in idx (index order), the
 * residual draws after them. */
static size_t pft_residual_copies_(const pft_weight_t *w, size_t m, pft_wacc_t total,
                                   uint32_t *idx, size_t n, pft_weight_t *res)
{
    size_t j;
    size_t filled = 0u;
#ifdef PFT_NUMERIC_Q16
    /* Scale so that the total fits in 32 bits for the fraction division (the residual
     * fractions lose only the shifted-out low bits, a relative 2^-31 at worst). */
    unsigned sh = 0u;
    uint64_t tot_s;
    while (sh < 32u && (total >> sh) >= 0x100000000ull) {
        ++sh;
    }
    tot_s = total >> sh;
#endif
    for (j = 0u; j < m; ++j) {
        const pft_wacc_t wj = pft_wpos_(w[j]);
        size_t copies;
        size_t c;
#ifdef PFT_NUMERIC_Q16
        {
            const uint64_t nw = (uint64_t)n * wj; /* < 2^22 2^32 */
            const uint64_t cp = nw / total;
            const uint64_t rem = nw - cp * total; /* < total */
            const uint64_t fr = ((rem >> sh) << 32) / tot_s; /* 2^32 only if rem >> sh == tot_s */
            copies = (size_t)cp;
            res[j] = fr > 0xFFFFFFFFull ? (pft_weight_t)0xFFFFFFFFu : (pft_weight_t)fr;
        }
#else
        {
            const float x = ((float)n * wj) / total;
            float fl = floorf(x);
            if (!(fl >= 0.0f)) {
                fl = 0.0f;
            }
            if (fl > (float)n) {
                fl = (float)n;
            }
            copies = (size_t)fl;
            res[j] = x - fl > 0.0f ? x - fl : 0.0f;
        }
#endif
        /* Rounding (float) can only push the sum of copies past n by a few: cap it. */
        if (copies > n - filled) {
            copies = n - filled;
        }
        for (c = 0u; c < copies; ++c) {
            idx[filled + c] = (uint32_t)j;
        }
        filled += copies;
    }
    return filled;
}

static pft_status_t pft_residual_(const pft_weight_t *w, size_t m, pft_wacc_t total, size_t last,
                                  uint32_t *idx, size_t n, pft_rng_t *rng, void *scratch)
{
    pft_weight_t *res = (pft_weight_t *)scratch;
    pft_wacc_t rtotal;
    size_t rlast;
    size_t filled = pft_residual_copies_(w, m, total, idx, n, res);
    pft_usrc_t src;
    src.u = NULL;
    src.rng = rng;
    if (filled < n) {
        if (pft_total_(res, m, &rtotal, &rlast) == PFT_OK) {
            pft_strat_walk_(res, rtotal, rlast, idx + filled, n - filled, &src, true);
        } else {
            /* Cannot happen in exact arithmetic (the residuals sum to n - filled > 0); after
             * float rounding, fall back to systematic over the original weights. */
            pft_strat_walk_(w, total, last, idx + filled, n - filled, &src, true);
        }
    }
    return PFT_OK;
}

/* ----------------------------------------------------------------------------------------- */
size_t pft_resample_scratch_size(pft_resample_scheme_t scheme, size_t m, size_t n)
{
    (void)n;
    return scheme == PFT_RESAMPLE_RESIDUAL ? m * sizeof(pft_weight_t) : 0u;
}

pft_status_t pft_resample(pft_resample_scheme_t scheme, const pft_weight_t *w, size_t m,
                          uint32_t *idx, size_t n, pft_rng_t *rng, void *scratch,
                          size_t scratch_len)
{
    pft_wacc_t total;
    pft_status_t st;
    size_t last;
    pft_usrc_t src;
    size_t k;
    if (!pft_args_ok_(w, m, idx, n) || rng == NULL) {
        return PFT_ERR_INVAL;
    }
    if ((unsigned)scheme > (unsigned)PFT_RESAMPLE_MULTINOMIAL) {
        return PFT_ERR_INVAL;
    }
    if (scheme == PFT_RESAMPLE_RESIDUAL) {
        if (scratch == NULL || scratch_len < pft_resample_scratch_size(scheme, m, n)) {
            return PFT_ERR_NOMEM;
        }
        if (((uintptr_t)scratch % sizeof(pft_weight_t)) != 0u) {
            return PFT_ERR_INVAL;
        }
    }
    if (m == 0u) {
        return PFT_ERR_DEGENERATE;
    }
    st = pft_total_(w, m, &total, &last);
    if (st != PFT_OK) {
        return st;
    }
    if (n == 0u) {
        return PFT_OK;
    }
    src.u = NULL;
    src.rng = rng;
    switch (scheme) {
    case PFT_RESAMPLE_SYSTEMATIC:
        pft_strat_walk_(w, total, last, idx, n, &src, true);
        break;
    case PFT_RESAMPLE_STRATIFIED:
        pft_strat_walk_(w, total, last, idx, n, &src, false);
        break;
    case PFT_RESAMPLE_RESIDUAL:
        return pft_residual_(w, m, total, last, idx, n, rng, scratch);
    default: /* PFT_RESAMPLE_MULTINOMIAL */
        for (k = 0u; k < n; ++k) {
            idx[k] = pft_rng_u32(rng);
        }
        pft_heap_sort_(idx, n);
        pft_multi_walk_(w, total, last, idx, n);
        break;
    }
    return PFT_OK;
}
