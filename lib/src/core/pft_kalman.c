/*
 * Small Kalman algebra for 2-D and 4-D states.
 *
 * Dot products go through a wide accumulator and are rounded once (q16: exact Q32.32 products
 * summed in int64 with saturation, then rounded to nearest; float: plain float). Covariance
 * results are computed on the upper triangle and mirrored, so they are exactly symmetric.
 * The 2x2 determinant is exact in q16 (Q32.32 in int64), so positive definiteness is decided
 * without rounding, and the inverse divides by it in 64-bit (one rounding per entry).
 * Every function computes into locals and writes its outputs last: on an error nothing is
 * written, and outputs may alias inputs.
 */
#include "pft/pft_kalman.h"

#define PFT_KF_NMAX 4u

/* ------------------------------- wide accumulator ----------------------------------------- */
#ifdef PFT_NUMERIC_Q16
typedef int64_t pft_kacc_t; /* Q32.32 */
#define PFT_KACC_LIM ((int64_t)1 << 62)

static inline pft_kacc_t pft_kacc_clamp_(pft_kacc_t a)
{
    return a > PFT_KACC_LIM ? PFT_KACC_LIM : (a < -PFT_KACC_LIM ? -PFT_KACC_LIM : a);
}
/* a + b*c; |a| <= 2^62 and |b c| < 2^62, so the sum cannot overflow before the clamp. */
static inline pft_kacc_t pft_kacc_mac_(pft_kacc_t a, pft_real_t b, pft_real_t c)
{
    return pft_kacc_clamp_(a + (int64_t)b * c);
}
static inline pft_kacc_t pft_kacc_from_(pft_real_t a)
{
    return (int64_t)a * 65536;
}
/* Round to nearest (ties away from zero, as pft_mul) and saturate. */
static inline pft_real_t pft_kacc_to_(pft_kacc_t a)
{
    const int64_t p = a + (a >= 0 ? (int64_t)32768 : (int64_t)32767);
    return pft_sat64_(p >> 16);
}
#else
typedef float pft_kacc_t;
static inline pft_kacc_t pft_kacc_mac_(pft_kacc_t a, pft_real_t b, pft_real_t c)
{
    return a + b * c;
}
static inline pft_kacc_t pft_kacc_from_(pft_real_t a)
{
    return a;
}
static inline pft_real_t pft_kacc_to_(pft_kacc_t a)
{
    return a;
}
#endif

/* ------------------------------- 2x2 symmetric -------------------------------------------- */
/* Determinant of [[a, b], [b, d]] as an accumulator (q16: exact Q32.32, each product below
 * 2^62 in magnitude). PFT_OK if the matrix is positive definite (a > 0 and det > 0),
 * PFT_ERR_SINGULAR if it is not, PFT_ERR_RANGE if (float) the determinant overflowed. */
static pft_status_t pft_det2_pd_(pft_real_t a, pft_real_t b, pft_real_t d, pft_kacc_t *det)
{
#ifdef PFT_NUMERIC_Q16
    *det = (int64_t)a * d - (int64_t)b * b;
    return a > 0 && *det > 0 ? PFT_OK : PFT_ERR_SINGULAR;
#else
    *det = a * d - b * b;
    if (!(a > 0.0f && *det > 0.0f)) {
        return PFT_ERR_SINGULAR;
    }
    return *det <= PFT_REAL_MAX ? PFT_OK : PFT_ERR_RANGE;
#endif
}

/* num / det as a real, det > 0 (both accumulators). False if the quotient is not
 * representable (q16: |q| > PFT_REAL_MAX, which then saturates; float: infinite or NaN). */
static bool pft_kdiv_(pft_kacc_t num, pft_kacc_t det, pft_real_t *out)
{
#ifdef PFT_NUMERIC_Q16
    /* Q32.32 / Q32.32 -> Q16.16 raw = num 2^16 / det, by long division (num 2^16 could
     * overflow): integer part first, then 16 quotient bits; r < det <= 2^62 so 2 r fits. */
    const uint64_t n = num < 0 ? (uint64_t)0 - (uint64_t)num : (uint64_t)num;
    const uint64_t d = (uint64_t)det;
    uint64_t q = n / d;
    uint64_t r = n % d;
    unsigned i;
    bool ok = true;
    if (q >= ((uint64_t)1 << 15)) {
        q = (uint64_t)INT32_MAX;
        ok = false;
    } else {
        for (i = 0u; i < 16u; ++i) {
            r <<= 1;
            q <<= 1;
            if (r >= d) {
                r -= d;
                q |= 1u;
            }
        }
        if (r >= d - r) {
            ++q; /* round half away from zero */
        }
        if (q > (uint64_t)INT32_MAX) {
            q = (uint64_t)INT32_MAX;
            ok = false;
        }
    }
    *out = num < 0 ? -(pft_real_t)q : (pft_real_t)q;
    return ok;
#else
    *out = num / det;
    return *out <= PFT_REAL_MAX && *out >= PFT_REAL_MIN;
#endif
}

/* Inverse of [[a, b], [b, d]]: PFT_ERR_SINGULAR if not positive definite, PFT_ERR_RANGE if an
 * entry is not representable; out untouched then. */
static pft_status_t pft_inv2_(pft_real_t a, pft_real_t b, pft_real_t d, pft_real_t out[4])
{
    pft_kacc_t det;
    pft_real_t r[3];
    pft_status_t st = pft_det2_pd_(a, b, d, &det);
    if (st != PFT_OK) {
        return st;
    }
    if (!pft_kdiv_(pft_kacc_from_(d), det, &r[0]) || !pft_kdiv_(pft_kacc_from_(pft_neg(b)), det, &r[1]) ||
        !pft_kdiv_(pft_kacc_from_(a), det, &r[2])) {
        return PFT_ERR_RANGE;
    }
    out[0] = r[0];
    out[1] = r[1];
    out[2] = r[1];
    out[3] = r[2];
    return PFT_OK;
}

pft_status_t pft_mat2_inv_sym(const pft_real_t A[4], pft_real_t Ainv[4])
{
    pft_real_t r[4];
    unsigned i;
    if (A == NULL || Ainv == NULL) {
        return PFT_ERR_INVAL;
    }
    pft_status_t st = pft_inv2_(A[0], A[1], A[3], r);
    if (st != PFT_OK) {
        return st;
    }
    for (i = 0u; i < 4u; ++i) {
        Ainv[i] = r[i];
    }
    return PFT_OK;
}

pft_status_t pft_mat2_chol(const pft_real_t A[4], pft_real_t L[4])
{
    pft_real_t l00;
    pft_real_t l10;
    pft_real_t l11;
    if (A == NULL || L == NULL) {
        return PFT_ERR_INVAL;
    }
    {
        pft_kacc_t det;
        pft_real_t schur;
        pft_status_t st = pft_det2_pd_(A[0], A[1], A[3], &det);
        if (st != PFT_OK) {
            return st;
        }
        /* Schur complement a11 - a01^2 / a00 = det / a00, in (0, a11]: one rounding. */
        (void)pft_kdiv_(det, pft_kacc_from_(A[0]), &schur);
        l00 = pft_sqrt(A[0]);
        l10 = pft_div(A[1], l00);
        l11 = pft_sqrt(schur);
    }
    L[0] = l00;
    L[1] = PFT_C(0.0);
    L[2] = l10;
    L[3] = l11;
    return PFT_OK;
}

/* ------------------------------- generic n <= 4 ------------------------------------------- */
static void pft_kf_predict_(unsigned n, pft_real_t *x, pft_real_t *P, const pft_real_t *F,
                            const pft_real_t *Q)
{
    pft_real_t xn[PFT_KF_NMAX];
    pft_real_t fp[PFT_KF_NMAX * PFT_KF_NMAX];
    pft_real_t pn[PFT_KF_NMAX * PFT_KF_NMAX];
    unsigned i;
    unsigned j;
    unsigned l;
    for (i = 0u; i < n; ++i) {
        pft_kacc_t acc = 0;
        for (l = 0u; l < n; ++l) {
            acc = pft_kacc_mac_(acc, F[i * n + l], x[l]);
        }
        xn[i] = pft_kacc_to_(acc);
    }
    /* fp = F P */
    for (i = 0u; i < n; ++i) {
        for (j = 0u; j < n; ++j) {
            pft_kacc_t acc = 0;
            for (l = 0u; l < n; ++l) {
                acc = pft_kacc_mac_(acc, F[i * n + l], P[l * n + j]);
            }
            fp[i * n + j] = pft_kacc_to_(acc);
        }
    }
    /* pn = fp F' + Q, upper triangle, mirrored */
    for (i = 0u; i < n; ++i) {
        for (j = i; j < n; ++j) {
            pft_kacc_t acc = pft_kacc_from_(Q[i * n + j]);
            for (l = 0u; l < n; ++l) {
                acc = pft_kacc_mac_(acc, fp[i * n + l], F[j * n + l]);
            }
            pn[i * n + j] = pft_kacc_to_(acc);
            pn[j * n + i] = pn[i * n + j];
        }
    }
    for (i = 0u; i < n; ++i) {
        x[i] = xn[i];
    }
    for (i = 0u; i < n * n; ++i) {
        P[i] = pn[i];
    }
}

/* P H' (n x 2) and S = H P H' + R (upper: s00, s01, s11) for a 2 x n H (NULL: H = I, n = 2). */
static void pft_kf_innov_cov_(unsigned n, const pft_real_t *P, const pft_real_t *H,
                              const pft_real_t R[4], pft_real_t *pht, pft_real_t s[3])
{
    static const unsigned sa[3] = {0u, 0u, 1u};
    static const unsigned sb[3] = {0u, 1u, 1u};
    unsigned i;
    unsigned a;
    unsigned l;
    for (i = 0u; i < n; ++i) {
        for (a = 0u; a < 2u; ++a) {
            if (H == NULL) {
                pht[i * 2u + a] = P[i * n + a];
            } else {
                pft_kacc_t acc = 0;
                for (l = 0u; l < n; ++l) {
                    acc = pft_kacc_mac_(acc, P[i * n + l], H[a * n + l]);
                }
                pht[i * 2u + a] = pft_kacc_to_(acc);
            }
        }
    }
    for (i = 0u; i < 3u; ++i) {
        pft_kacc_t acc = pft_kacc_from_(R[sa[i] * 2u + sb[i]]);
        if (H == NULL) {
            acc = pft_kacc_mac_(acc, pht[sa[i] * 2u + sb[i]], PFT_REAL_ONE);
        } else {
            for (l = 0u; l < n; ++l) {
                acc = pft_kacc_mac_(acc, H[sa[i] * n + l], pht[l * 2u + sb[i]]);
            }
        }
        s[i] = pft_kacc_to_(acc);
    }
}

/* K = P H' adj(S) / det (n x 2): the numerator is one exact accumulation, then one rounding
 * (q16: better than rounding S^-1 first, whose entries have few significant bits when S is
 * large). A gain beyond the real range saturates. */
static void pft_kf_gain_(unsigned n, const pft_real_t *pht, const pft_real_t s[3], pft_kacc_t det,
                         pft_real_t *k)
{
    pft_real_t adj[4];
    unsigned i;
    unsigned a;
    adj[0] = s[2];
    adj[1] = pft_neg(s[1]);
    adj[2] = adj[1];
    adj[3] = s[0];
    for (i = 0u; i < n; ++i) {
        for (a = 0u; a < 2u; ++a) {
            pft_kacc_t acc = 0;
            acc = pft_kacc_mac_(acc, pht[i * 2u + 0u], adj[0u * 2u + a]);
            acc = pft_kacc_mac_(acc, pht[i * 2u + 1u], adj[1u * 2u + a]);
            (void)pft_kdiv_(acc, det, &k[i * 2u + a]);
        }
    }
}

/* x += K (z - H x), P -= K (P H')' (upper triangle, mirrored). */
static void pft_kf_apply_(unsigned n, pft_real_t *x, pft_real_t *P, const pft_real_t *H,
                          const pft_real_t z[2], const pft_real_t *k, const pft_real_t *pht)
{
    pft_real_t y[2];
    pft_real_t xn[PFT_KF_NMAX];
    pft_real_t pn[PFT_KF_NMAX * PFT_KF_NMAX];
    unsigned i;
    unsigned j;
    unsigned a;
    unsigned l;
    for (a = 0u; a < 2u; ++a) {
        pft_kacc_t acc = pft_kacc_from_(z[a]);
        if (H == NULL) {
            acc = pft_kacc_mac_(acc, x[a], pft_neg(PFT_REAL_ONE));
        } else {
            for (l = 0u; l < n; ++l) {
                acc = pft_kacc_mac_(acc, H[a * n + l], pft_neg(x[l]));
            }
        }
        y[a] = pft_kacc_to_(acc);
    }
    for (i = 0u; i < n; ++i) {
        pft_kacc_t acc = pft_kacc_from_(x[i]);
        acc = pft_kacc_mac_(acc, k[i * 2u + 0u], y[0]);
        acc = pft_kacc_mac_(acc, k[i * 2u + 1u], y[1]);
        xn[i] = pft_kacc_to_(acc);
    }
    for (i = 0u; i < n; ++i) {
        for (j = i; j < n; ++j) {
            pft_kacc_t acc = pft_kacc_from_(P[i * n + j]);
            acc = pft_kacc_mac_(acc, k[i * 2u + 0u], pft_neg(pht[j * 2u + 0u]));
            acc = pft_kacc_mac_(acc, k[i * 2u + 1u], pft_neg(pht[j * 2u + 1u]));
            pn[i * n + j] = pft_kacc_to_(acc);
            pn[j * n + i] = pn[i * n + j];
        }
    }
    for (i = 0u; i < n; ++i) {
        x[i] = xn[i];
    }
    for (i = 0u; i < n * n; ++i) {
        P[i] = pn[i];
    }
}

/* Update with a 2-D measurement z = H x + v, H 2 x n (H == NULL means H = I, n = 2). A refused
 * update (S not positive definite) changes nothing. */
static pft_status_t pft_kf_update2_(unsigned n, pft_real_t *x, pft_real_t *P, const pft_real_t *H,
                                    const pft_real_t z[2], const pft_real_t R[4])
{
    pft_real_t pht[PFT_KF_NMAX * 2u]; /* P H', n x 2 */
    pft_real_t s[3];                  /* S upper: s00, s01, s11 */
    pft_real_t k[PFT_KF_NMAX * 2u];   /* gain, n x 2 */
    pft_kacc_t det;
    pft_status_t st;
    pft_kf_innov_cov_(n, P, H, R, pht, s);
    st = pft_det2_pd_(s[0], s[1], s[2], &det);
    if (st != PFT_OK) {
        return st;
    }
    pft_kf_gain_(n, pht, s, det, k);
    pft_kf_apply_(n, x, P, H, z, k, pht);
    return PFT_OK;
}

/* ------------------------------- public ---------------------------------------------------- */
void pft_kf2_predict(pft_real_t x[2], pft_real_t P[4], const pft_real_t F[4], const pft_real_t Q[4])
{
    if (x == NULL || P == NULL || F == NULL || Q == NULL) {
        return;
    }
    pft_kf_predict_(2u, x, P, F, Q);
}

void pft_kf4_predict(pft_real_t x[4], pft_real_t P[16], const pft_real_t F[16], const pft_real_t Q[16])
{
    if (x == NULL || P == NULL || F == NULL || Q == NULL) {
        return;
    }
    pft_kf_predict_(4u, x, P, F, Q);
}

pft_status_t pft_kf2_update(pft_real_t x[2], pft_real_t P[4], const pft_real_t z[2], const pft_real_t R[4])
{
    if (x == NULL || P == NULL || z == NULL || R == NULL) {
        return PFT_ERR_INVAL;
    }
    return pft_kf_update2_(2u, x, P, NULL, z, R);
}

pft_status_t pft_kf4_update2(pft_real_t x[4], pft_real_t P[16], const pft_real_t H[8], const pft_real_t z[2], const pft_real_t R[4])
{
    if (x == NULL || P == NULL || H == NULL || z == NULL || R == NULL) {
        return PFT_ERR_INVAL;
    }
    return pft_kf_update2_(4u, x, P, H, z, R);
}

pft_status_t pft_kf2_update_scalar(pft_real_t x[2], pft_real_t P[4], const pft_real_t h[2], pft_real_t z, pft_real_t r)
{
    pft_real_t ph[2];
    pft_real_t s;
    pft_real_t k[2];
    pft_real_t y;
    pft_real_t xn[2];
    pft_real_t pn[4];
    pft_kacc_t acc;
    unsigned i;
    if (x == NULL || P == NULL || h == NULL) {
        return PFT_ERR_INVAL;
    }
    for (i = 0u; i < 2u; ++i) {
        acc = pft_kacc_mac_(0, P[i * 2u + 0u], h[0]);
        acc = pft_kacc_mac_(acc, P[i * 2u + 1u], h[1]);
        ph[i] = pft_kacc_to_(acc);
    }
    acc = pft_kacc_from_(r);
    acc = pft_kacc_mac_(acc, h[0], ph[0]);
    acc = pft_kacc_mac_(acc, h[1], ph[1]);
    s = pft_kacc_to_(acc);
    if (!(s > PFT_C(0.0))) {
        return PFT_ERR_SINGULAR; /* the innovation variance is not positive */
    }
#ifdef PFT_NUMERIC_FLOAT
    if (!(s <= PFT_REAL_MAX)) {
        return PFT_ERR_RANGE;
    }
#endif
    k[0] = pft_div(ph[0], s);
    k[1] = pft_div(ph[1], s);
    acc = pft_kacc_from_(z);
    acc = pft_kacc_mac_(acc, h[0], pft_neg(x[0]));
    acc = pft_kacc_mac_(acc, h[1], pft_neg(x[1]));
    y = pft_kacc_to_(acc);
    for (i = 0u; i < 2u; ++i) {
        acc = pft_kacc_mac_(pft_kacc_from_(x[i]), k[i], y);
        xn[i] = pft_kacc_to_(acc);
    }
    /* P - k (P h)' (upper, mirrored) */
    pn[0] = pft_kacc_to_(pft_kacc_mac_(pft_kacc_from_(P[0]), k[0], pft_neg(ph[0])));
    pn[1] = pft_kacc_to_(pft_kacc_mac_(pft_kacc_from_(P[1]), k[0], pft_neg(ph[1])));
    pn[2] = pn[1];
    pn[3] = pft_kacc_to_(pft_kacc_mac_(pft_kacc_from_(P[3]), k[1], pft_neg(ph[1])));
    for (i = 0u; i < 2u; ++i) {
        x[i] = xn[i];
    }
    for (i = 0u; i < 4u; ++i) {
        P[i] = pn[i];
    }
    return PFT_OK;
}
