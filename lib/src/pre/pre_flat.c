/* Flat-field offset correction of the whitened residual, in sensor coordinates (pft_pre.h,
 * pft_pre_flat_*; docs/algorithms.md 9.10). Integer arithmetic only: the block map in sigma
 * Q16 (65536 = 1 sigma; relative: sigma per count Q24), residuals in Q8.8 sigma. */
#include <string.h>

#include "pre_int.h"

#if defined(__SSE2__)
#include <emmintrin.h> /* fl_l16_run_ below (FL_LEV_SPLIT_) */
#elif defined(__aarch64__) && defined(__ARM_NEON) && defined(__BYTE_ORDER__) && \
    (__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__)
#include <arm_neon.h> /* fl_l16_run_ below (FL_LEV_NEON_) */
#endif

#define FL_MMAX_ (8 * 65536)      /* the map's clamp: 8 sigma in Q16 (relative: 1/32 sigma per count) */
#define FL_BIAS_ 1073741824       /* 2^30: a bias that makes a shifted value non-negative */
#define FL_QBIAS_ ((int64_t)1099511627776) /* 2^40: the same for a level product (|k l| < 2^39) */
#define FL_QBIAS16_ 16777216       /* FL_QBIAS_ / 2^16 */
#define FL_S1_ 65536              /* rescale: sd 1 sigma, Q16 */
#define FL_SMIN_ 4096             /* rescale: the sd's clamp, 1/16 .. 16 sigma (Q16) */
#define FL_SMAX_ 1048576
#define FL_MADQ_ 44204            /* rescale: 0.6745 (the median of |N(0, 1)|), Q16 */
#define FL_Q32_ ((int64_t)4294967296) /* rescale: 2^32, the multiplier's numerator (Q16 / Q16 -> Q16) */
#define FL_NEWTON_ 76437          /* rescale: 1 / (2 * 0.4287), Q16 (0.4287 = d P(|x| <= q s) / d log s at the median) */

void pft_pre_flat_config_default(pft_pre_flat_config_t *cfg)
{
    if (cfg == NULL) {
        return;
    }
    memset(cfg, 0, sizeof(*cfg));
    cfg->width = 384u;
    cfg->height = 288u;
    cfg->block = 16u;
    cfg->alpha = 3277u;
    cfg->gate = 512u;
    cfg->relative = false;
    cfg->rescale = false;
}

pft_status_t pft_pre_flat_config_check(const pft_pre_flat_config_t *cfg, const char **field)
{
    const char *bad = NULL;
    if (field != NULL) {
        *field = NULL;
    }
    if (cfg == NULL) {
        return PFT_ERR_INVAL;
    }
    const uint32_t b = cfg->block;
    if (cfg->width < 8u || cfg->width > PFT_CFG_MAX_IMAGE_SIDE) {
        bad = "width";
    } else if (cfg->height < 8u || cfg->height > PFT_CFG_MAX_IMAGE_SIDE) {
        bad = "height";
    } else if (b < PFT_PRE_FLAT_MIN_BLOCK || b > PFT_PRE_FLAT_MAX_BLOCK || (b & (b - 1u)) != 0u) {
        bad = "block";
    } else if (cfg->alpha == 0u) {
        bad = "alpha";
    } else if (cfg->gate == 0u || cfg->gate > 32767u) {
        bad = "gate";
    } else {
        /* accepted */
    }
    if (bad != NULL) {
        if (field != NULL) {
            *field = bad;
        }
        return PFT_ERR_CONFIG;
    }
    return PFT_OK;
}

size_t pft_pre_flat_workspace_size(const pft_pre_flat_config_t *cfg)
{
    if (pft_pre_flat_config_check(cfg, NULL) != PFT_OK) {
        return 0u;
    }
    return cfg->rescale ? PFT_PRE_FLAT_WORKSPACE_BYTES_RESCALE(cfg->width, cfg->height, cfg->block)
                        : PFT_PRE_FLAT_WORKSPACE_BYTES(cfg->width, cfg->height, cfg->block);
}

pft_status_t pft_pre_flat_init(pft_pre_flat_t *fl, const pft_pre_flat_config_t *cfg, void *work,
                               size_t work_len)
{
    if (fl == NULL || cfg == NULL || work == NULL) {
        return PFT_ERR_INVAL;
    }
    if (pft_pre_flat_config_check(cfg, NULL) != PFT_OK) {
        return PFT_ERR_CONFIG;
    }
    const size_t nbx = PFT_PRE_FLAT_NB_(cfg->width, cfg->block);
    const size_t nby = PFT_PRE_FLAT_NB_(cfg->height, cfg->block);
    pft_ws_t ws;
    pft_ws_init(&ws, work, work_len);
    int32_t *m = pft_ws_take(&ws, nbx * nby * 4u);
    int32_t *sum = pft_ws_take(&ws, nbx * nby * 4u);
    uint32_t *cnt = pft_ws_take(&ws, nbx * nby * 4u);
    uint32_t *lsum = pft_ws_take(&ws, nbx * nby * 4u);
    int32_t *rowv = pft_ws_take(&ws, nbx * 4u);
    int32_t *sc = NULL, *sq = NULL, *rowq = NULL;
    uint32_t *nall = NULL, *nlo = NULL;
    if (cfg->rescale) {
        sc = pft_ws_take(&ws, nbx * nby * 4u);
        sq = pft_ws_take(&ws, nbx * nby * 4u);
        nall = pft_ws_take(&ws, nbx * nby * 4u);
        nlo = pft_ws_take(&ws, nbx * nby * 4u);
        rowq = pft_ws_take(&ws, nbx * 4u);
    }
    if (pft_ws_status(&ws) != PFT_OK) {
        return PFT_ERR_NOMEM;
    }
    memset(fl, 0, sizeof(*fl));
    fl->cfg = *cfg;
    fl->m = m;
    fl->sum = sum;
    fl->cnt = cnt;
    fl->lsum = lsum;
    fl->rowv = rowv;
    fl->sc = sc;
    fl->sq = sq;
    fl->nall = nall;
    fl->nlo = nlo;
    fl->rowq = rowq;
    fl->nbx = (uint32_t)nbx;
    fl->nby = (uint32_t)nby;
    fl->lb = pft_pre_log2_((uint32_t)cfg->block); /* block: a power of two */
    return pft_pre_flat_reset(fl);
}

pft_status_t pft_pre_flat_reset(pft_pre_flat_t *fl)
{
    if (fl == NULL || fl->m == NULL) {
        return PFT_ERR_INVAL;
    }
    const size_t nb = (size_t)fl->nbx * fl->nby;
    memset(fl->m, 0, nb * 4u);
    memset(fl->sum, 0, nb * 4u);
    memset(fl->cnt, 0, nb * 4u);
    memset(fl->lsum, 0, nb * 4u);
    memset(fl->rowv, 0, (size_t)fl->nbx * 4u);
    if (fl->sc != NULL) {
        for (size_t k = 0u; k < nb; ++k) {
            fl->sc[k] = FL_S1_;
            fl->sq[k] = FL_S1_;
        }
        memset(fl->nall, 0, nb * 4u);
        memset(fl->nlo, 0, nb * 4u);
        memset(fl->rowq, 0, (size_t)fl->nbx * 4u);
    }
    fl->frames = 0u;
    return PFT_OK;
}

/* v / 2^k rounded half up, for |v| < 2^29 and 1 <= k <= 29 (no shift of a negative value). */
static int32_t fl_shr_(int32_t v, uint32_t k)
{
    const uint32_t u = (uint32_t)(v + FL_BIAS_) + (1u << (k - 1u));
    return (int32_t)(u >> k) - (int32_t)((uint32_t)FL_BIAS_ >> k);
}

/* Doubled coordinate of the centre of block i (block side 2^lb): 2 i b + b - 1. */
static int32_t fl_c2_(uint32_t i, uint32_t lb)
{
    const uint32_t c = (2u * i + 1u) << lb;
    return (int32_t)c - 1;
}

/* (a0 (d - t) + a1 t) / 2^k rounded half up: the blend of two block values at weight t of d. */
static int32_t fl_mix_(int32_t a0, int32_t a1, int32_t t, int32_t d, uint32_t k)
{
    return fl_shr_(a0 * (d - t) + a1 * t, k);
}

/* Lower block index j0 and the weight t of block j0 + 1 (0..2b - 1; 0 also where held) of the
 * doubled coordinate p2 between the centres of n blocks. */
static void fl_locate_(uint32_t p2, uint32_t n, uint32_t lb, uint32_t *j0, uint32_t *j1,
                       uint32_t *t)
{
    const uint32_t b = 1u << lb;
    if (n == 1u || (int32_t)p2 <= fl_c2_(0u, lb)) {
        *j0 = 0u;
        *j1 = 0u;
        *t = 0u;
    } else if ((int32_t)p2 >= fl_c2_(n - 1u, lb)) {
        *j0 = n - 1u;
        *j1 = n - 1u;
        *t = 0u;
    } else {
        const uint32_t j = (p2 - (b - 1u)) >> (lb + 1u);
        *j0 = j;
        *j1 = j + 1u;
        *t = p2 - (uint32_t)fl_c2_(j, lb);
    }
}

/* The map interpolated to row y at every block column (sigma Q16) into fl->rowv. */
static void fl_rowv_(pft_pre_flat_t *fl, uint32_t y)
{
    uint32_t j0, j1, t;
    fl_locate_(2u * y, fl->nby, fl->lb, &j0, &j1, &t);
    const uint32_t d2 = 2u << fl->lb;
    const int32_t d = (int32_t)d2;
    const int32_t *a = fl->m + (size_t)j0 * fl->nbx, *b = fl->m + (size_t)j1 * fl->nbx;
    for (uint32_t i = 0u; i < fl->nbx; ++i) {
        fl->rowv[i] = fl_mix_(a[i], b[i], (int32_t)t, d, fl->lb + 1u);
    }
}

int32_t pft_pre_flat_at(const pft_pre_flat_t *fl, uint32_t x, uint32_t y)
{
    if (fl == NULL || fl->m == NULL || x >= fl->cfg.width || y >= fl->cfg.height) {
        return 0;
    }
    uint32_t j0, j1, t, i0, i1, u;
    fl_locate_(2u * y, fl->nby, fl->lb, &j0, &j1, &t);
    fl_locate_(2u * x, fl->nbx, fl->lb, &i0, &i1, &u);
    const uint32_t d2 = 2u << fl->lb;
    const int32_t d = (int32_t)d2;
    const int32_t *a = fl->m + (size_t)j0 * fl->nbx, *b = fl->m + (size_t)j1 * fl->nbx;
    const int32_t r0 = fl_mix_(a[i0], b[i0], (int32_t)t, d, fl->lb + 1u);
    const int32_t r1 = fl_mix_(a[i1], b[i1], (int32_t)t, d, fl->lb + 1u);
    return fl_mix_(r0, r1, (int32_t)u, d, fl->lb + (fl->cfg.relative ? 1u : 9u));
}

/* Sums of the gated corrected values of one span (corrected value, count, level). */
typedef struct {
    int32_t sum;
    uint32_t cnt;
    uint32_t lsum;
} fl_acc_t;

/* k * l / 2^16 rounded half away from zero (relative offset: k sigma per count Q24, |k| <=
 * FL_MMAX_ = 2^19, the map's values and their interpolations; l <= 65535 counts), that is
 * floor((k l + 2^15 - [k l < 0]) / 2^16), in 32-bit arithmetic: with k = kh 2^16 + kl (kh =
 * floor(k / 2^16), from the non-negative k + 2^19; kl in 0 .. 65535), k l = kh l 2^16 + kl l,
 * so the value is kh l + ((kl l + 2^15 - [k l < 0]) >> 16): kl l + 2^15 < 2^32, |kh l| <= 8 *
 * 65535; k l < 0 exactly when k < 0 and l > 0 (the sign bits of k and of -l, l < 2^31). */
static inline int32_t fl_lev32_(int32_t k, uint32_t l)
{
    const int32_t kh = (int32_t)((uint32_t)(k + FL_MMAX_) >> 16) - 8; /* k >> 16: k + 2^19 >= 0 */
    const uint32_t kl = (uint32_t)k & 0xFFFFu;
    const uint32_t neg = ((uint32_t)k >> 31) & ((0u - l) >> 31);
    const int32_t lo = (int32_t)((kl * l + 32768u - neg) >> 16);
    return (kh * (int32_t)l) + lo;
}

#if defined(__SSE2__)
/* Where the compiler has SSE2 (x86-64), the relative form's 16-bit level row takes fl_lev32_'s
 * products as 16 x 16-bit products (pmullw, pmulhw) instead of 32 x 32-bit ones, which SSE2
 * lacks (pmuludq and shuffles), and rescale's per-pixel multiplication (fl_mulq_, a 64-bit
 * product in a loop with a branch, not vectorised) becomes a vectorised loop of 16 x 16-bit
 * products (fl_scale_span_; AArch64 takes that loop too, FL_SCALE_SPLIT_ below). Other targets
 * keep fl_lev32_ and fl_mulq_ (a scalar core pays one 32-bit multiply, or one 32 x 32 -> 64-bit
 * multiply, per product): their object code is as before. */
#define FL_LEV_SPLIT_ 1
#endif

#if defined(FL_LEV_SPLIT_) || (defined(__aarch64__) && defined(__ARM_NEON))
/* rescale's branch-free loop of 16 x 16-bit products (fl_scale_span_) where the compiler
 * vectorises it: x86-64 (SSE2, with FL_LEV_SPLIT_) and AArch64 with NEON (Advanced SIMD), where
 * gcc leaves the loop of fl_mulq_ (a 64-bit product and a branch per pixel) scalar. AArch64
 * keeps fl_lev32_ (NEON has a 32 x 32-bit product). Other targets (a scalar core) keep
 * fl_mulq_'s loop: their object code as before. */
#define FL_SCALE_SPLIT_ 1
#endif

#if !defined(FL_LEV_SPLIT_) && defined(__aarch64__) && defined(__ARM_NEON) && defined(__BYTE_ORDER__) && \
    (__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__)
/* Where the compiler has AArch64's Advanced SIMD (NEON; little-endian), the relative form with a
 * 16-bit level row takes 8 pixels at a time in NEON's forms (fl_l16_run_ below): gcc's loop of
 * fl_lev32_ and fl_px_bf_ works in 32-bit lanes throughout. Other targets: object code as
 * before. */
#define FL_LEV_NEON_ 1
#endif

#if defined(FL_LEV_SPLIT_) || defined(FL_LEV_NEON_)
/* The relative form's 16-bit level row 8 pixels at a time (x86-64 with SSE2, AArch64 with NEON),
 * the same integers as fl_px_bf_ with fl_lev32_ (or fl_lev16_): with u the interpolation's
 * biased numerator at a pixel, kv = (u >> k) - cb (|kv| <= 2^19) is kh 2^16 + kl, kh = kv >> 16
 * (-8 .. 8) and kl its lower 16 bits, both in 16-bit lanes; fl_lev32_(kv, l) = kh l + lo with
 * lo = (kl l + 32768 - [kv < 0 and l > 0]) >> 16 (kl l + 32768 < 2^32; lo <= 65535); then
 * o = v - (kh l + lo) in 32-bit lanes (|o| < 2^21), clamped to +-32767 by a saturating
 * narrowing and a max; a masked pixel (v = INT16_MIN) is stored back unchanged and booked
 * nowhere; the gate is |o| <= gate (o >= -32767, gate <= 32767). The sums go to vector lanes
 * (fl_l16a_t) that fl_l16_sum_ adds up once per span or block, the same totals modulo 2^32.
 * fl_l16_run_ takes n groups of 8 pixels from column x, the interpolation u0 at x stepped by
 * st per pixel (modulo 2^32: u0 + i st, as the plain loop). */
#define FL_LEV_VEC_ 1
#endif

#ifdef FL_LEV_NEON_
/* NEON: kl and kh are the lower and upper 16-bit halves of the 32-bit lanes (uzp1, uzp2); kl l
 * a widening product (umull) and lo its high half after one add (addhn) of 32768 - neg;
 * kh l = (kh + 8) l - 8 l as unsigned widening products subtracted and added to v - lo
 * (usubw, umlsl, umlal, modulo 2^32); the clamp sqxtn and a max; the gate |o| (abs) <= gate;
 * the sums pairwise widening adds (sadalp, uadalp) and the count 16-bit lanes (at most 8 per
 * lane per block of at most 64 pixels). */
typedef struct {
    int32x4_t nk, cb, c15;
    int16x8_t h8, omin, msk;
    uint16x8_t g;
} fl_l16c_t;
typedef struct {
    int32x4_t s;
    uint32x4_t l;
    uint16x8_t n;
} fl_l16a_t;

static inline void fl_l16_init_(fl_l16c_t *c, uint32_t k, int32_t cb, int32_t gate)
{
    c->nk = vdupq_n_s32(-(int32_t)k);
    c->cb = vdupq_n_s32(cb);
    c->c15 = vdupq_n_s32(32768);
    c->h8 = vdupq_n_s16(8);
    c->omin = vdupq_n_s16(-32767);
    c->msk = vdupq_n_s16(PFT_RES16_MASKED);
    c->g = vdupq_n_u16((uint16_t)gate);
}

static inline void fl_l16_zero_(fl_l16a_t *a)
{
    a->s = vdupq_n_s32(0);
    a->l = vdupq_n_u32(0u);
    a->n = vdupq_n_u16(0u);
}

static inline void fl_l16_run_(int16_t *r, const uint8_t *lrow, uint32_t x, uint32_t n,
                               uint32_t u0, uint32_t st, const fl_l16c_t *c, fl_l16a_t *a)
{
    static const uint32_t i03[4] = {0u, 1u, 2u, 3u};
    uint32x4_t ua = vmlaq_n_u32(vdupq_n_u32(u0), vld1q_u32(i03), st);
    uint32x4_t ub = vaddq_u32(ua, vdupq_n_u32(4u * st));
    const uint32x4_t st8 = vdupq_n_u32(8u * st);
    int32x4_t as = a->s;
    uint32x4_t al = a->l;
    uint16x8_t an = a->n;
    int16_t *rx = r + x;
    const uint8_t *lx = lrow + 2u * x;
    for (uint32_t i = 0u; i < n; ++i) {
        const int32x4_t ka = vsubq_s32(vreinterpretq_s32_u32(vshlq_u32(ua, c->nk)), c->cb);
        const int32x4_t kb = vsubq_s32(vreinterpretq_s32_u32(vshlq_u32(ub, c->nk)), c->cb);
        ua = vaddq_u32(ua, st8);
        ub = vaddq_u32(ub, st8);
        const uint16x8_t kl = vuzp1q_u16(vreinterpretq_u16_s32(ka), vreinterpretq_u16_s32(kb));
        const int16x8_t kh = vuzp2q_s16(vreinterpretq_s16_s32(ka), vreinterpretq_s16_s32(kb));
        const uint16x8_t l = vreinterpretq_u16_u8(vld1q_u8(lx));
        const int16x8_t v = vld1q_s16(rx);
        /* 32768 - [kv < 0] per 32-bit lane (where l = 0, kl l = 0 and the term changes nothing) */
        const int16x8_t ng = vreinterpretq_s16_u16(vcltzq_s16(kh));
        const uint32x4_t ca = vreinterpretq_u32_s32(vaddw_s16(c->c15, vget_low_s16(ng)));
        const uint32x4_t cc = vreinterpretq_u32_s32(vaddw_high_s16(c->c15, ng));
        const uint16x4_t loa = vaddhn_u32(vmull_u16(vget_low_u16(kl), vget_low_u16(l)), ca);
        const uint16x8_t lo = vaddhn_high_u32(loa, vmull_high_u16(kl, l), cc);
        const uint16x8_t kh8 = vreinterpretq_u16_s16(vaddq_s16(kh, c->h8));
        uint32x4_t oa = vreinterpretq_u32_s32(vmovl_s16(vget_low_s16(v)));
        oa = vsubw_u16(oa, vget_low_u16(lo));
        oa = vmlsl_u16(oa, vget_low_u16(kh8), vget_low_u16(l));
        oa = vmlal_n_u16(oa, vget_low_u16(l), 8u);
        uint32x4_t ob = vreinterpretq_u32_s32(vmovl_high_s16(v));
        ob = vsubw_high_u16(ob, lo);
        ob = vmlsl_high_u16(ob, kh8, l);
        ob = vmlal_high_n_u16(ob, l, 8u);
        const int16x8_t o = vmaxq_s16(
            vqmovn_high_s32(vqmovn_s32(vreinterpretq_s32_u32(oa)), vreinterpretq_s32_u32(ob)), c->omin);
        const uint16x8_t ms = vceqq_s16(v, c->msk);
        vst1q_s16(rx, vbslq_s16(ms, v, o));
        const uint16x8_t in = vbicq_u16(vcleq_u16(vreinterpretq_u16_s16(vabsq_s16(o)), c->g), ms);
        as = vpadalq_s16(as, vandq_s16(o, vreinterpretq_s16_u16(in)));
        al = vpadalq_u16(al, vandq_u16(l, in));
        an = vsubq_u16(an, in);
        rx += 8;
        lx += 16;
    }
    a->s = as;
    a->l = al;
    a->n = an;
}

/* The lanes' totals added to acc (np: the pixels the lanes took, not needed here). */
static inline void fl_l16_sum_(const fl_l16a_t *a, uint32_t np, fl_acc_t *acc)
{
    (void)np;
    acc->sum += vaddvq_s32(a->s);
    acc->cnt += vaddlvq_u16(a->n);
    acc->lsum += vaddvq_u32(a->l);
}
#endif

#ifdef FL_LEV_SPLIT_
/* SSE2: the interpolation less FL_BIAS_ (the signed numerator plus 2^(k-1), |.| < 2^27) times
 * 2^(7 - k) (k = lb + 1 <= 7: |.| < 2^29), so that kv (fl_shr_'s floor) is its arithmetic shift
 * by 7, kh = kv >> 16 its shift by 23 and kl (kv's lower 16 bits, sign-extended so that the
 * signed pack keeps its bits) its shift left by 9 and right by 16, all by constants; kl l =
 * 2^16 ph + pl (pmulhuw, pmullw), so lo = ph + [pl >= 32768 + neg] (one signed compare of neg
 * with pl - 32768: where l = 0, pl = 0 and neg changes nothing, so neg = [kh < 0]). Then
 * o = v - kh l - lo in 32-bit lanes as two multiply-adds (pmaddwd) of 16-bit pairs:
 * (kh, kh + 1) . (32767 - l, -32767) = -kh (l - 32767) - 32767 kh - 32767 = -kh l - 32767 and
 * (v, lo - 32767) . (1, -1) = v - lo + 32767 (kh + 1 in -7 .. 9; 32767 - l and lo - 32767 in
 * -32768 .. 32767: lo <= 65534); the clamp packssdw and a max; the store min(o, 32767 or
 * INT16_MIN); out of the gate (|o| > gate) as o + gate - 32768 > 2 gate - 32768 in 16-bit lanes
 * (o + gate in -32767 .. 65534: a negative one wraps to at least 1 > 2 gate - 32768 - 65536);
 * the sums o in pairs (pmaddwd), l - 32768 in pairs (every lane, 0 out of the gate: 32768 per
 * pixel taken back in fl_l16_sum_) and the count as 16-bit lanes of -1 per pixel out of the
 * gate or masked (np - those). */
typedef struct {
    __m128i ones, h8, omin, o7f, gx, g2x, m1, c2;
    uint32_t sh;
} fl_l16c_t;
typedef struct {
    __m128i s, l, n;
} fl_l16a_t;

static inline void fl_l16_init_(fl_l16c_t *c, uint32_t k, int32_t cb, int32_t gate)
{
    (void)cb;
    c->sh = 7u - k;
    c->ones = _mm_set1_epi16(1);
    c->h8 = _mm_set1_epi16(PFT_RES16_MASKED);
    c->omin = _mm_set1_epi16(-32767);
    c->o7f = _mm_set1_epi16(32767);
    c->gx = _mm_set1_epi16((int16_t)(gate - 32768));
    c->g2x = _mm_set1_epi16((int16_t)(2 * gate - 32768));
    c->m1 = _mm_set1_epi32(-65535); /* the 16-bit pair (1, -1) */
    c->c2 = _mm_set1_epi16(-32766);
}

static inline void fl_l16_zero_(fl_l16a_t *a)
{
    a->s = _mm_setzero_si128();
    a->l = _mm_setzero_si128();
    a->n = _mm_setzero_si128();
}

/* The interpolation's lanes of 8 pixels from u0 (fl_shr_'s biased numerator, stepped by st per
 * pixel): pixels 0 .. 3 in ua, 4 .. 7 in ub, both stepped by st8 per group of 8. */
typedef struct {
    __m128i ua, ub, st8;
} fl_l16u_t;

static inline fl_l16u_t fl_l16_uv_(uint32_t u0, uint32_t st, const fl_l16c_t *c)
{
    const uint32_t s0 = (u0 - (uint32_t)FL_BIAS_) << c->sh, s1 = st << c->sh;
    fl_l16u_t q;
    q.ua = _mm_add_epi32(_mm_set1_epi32((int32_t)s0),
                         _mm_set_epi32((int32_t)(3u * s1), (int32_t)(2u * s1), (int32_t)s1, 0));
    q.ub = _mm_add_epi32(q.ua, _mm_set1_epi32((int32_t)(4u * s1)));
    q.st8 = _mm_set1_epi32((int32_t)(8u * s1));
    return q;
}

/* n groups of 8 pixels from column x with the lanes q (left at the next group's). */
static inline void fl_l16_grps_(int16_t *r, const uint8_t *lrow, uint32_t x, uint32_t n,
                                fl_l16u_t *q, const fl_l16c_t *c, fl_l16a_t *a)
{
    __m128i ua = q->ua, ub = q->ub;
    const __m128i st8 = q->st8;
    __m128i as = a->s, al = a->l, an = a->n;
    int16_t *rx = r + x;
    const uint8_t *lx = lrow + 2u * x;
    for (uint32_t i = 0u; i < n; ++i) {
        const __m128i kl = _mm_packs_epi32(_mm_srai_epi32(_mm_slli_epi32(ua, 9), 16),
                                           _mm_srai_epi32(_mm_slli_epi32(ub, 9), 16));
        const __m128i kh = _mm_packs_epi32(_mm_srai_epi32(ua, 23), _mm_srai_epi32(ub, 23));
        ua = _mm_add_epi32(ua, st8);
        ub = _mm_add_epi32(ub, st8);
        const __m128i l = _mm_loadu_si128((const __m128i *)(const void *)lx);
        const __m128i v = _mm_loadu_si128((const __m128i *)(const void *)rx);
        const __m128i pl = _mm_mullo_epi16(kl, l), ph = _mm_mulhi_epu16(kl, l);
        /* -1 where no carry: pl - 32768 < neg */
        const __m128i nc = _mm_cmpgt_epi16(_mm_srli_epi16(kh, 15), _mm_xor_si128(pl, c->h8));
        const __m128i lo = _mm_add_epi16(_mm_add_epi16(ph, nc), c->c2); /* lo - 32767 */
        const __m128i nl = _mm_xor_si128(l, c->o7f);                     /* 32767 - l */
        const __m128i k1 = _mm_add_epi16(kh, c->ones);                   /* kh + 1 */
        const __m128i qa = _mm_madd_epi16(_mm_unpacklo_epi16(kh, k1), _mm_unpacklo_epi16(nl, c->omin));
        const __m128i qb = _mm_madd_epi16(_mm_unpackhi_epi16(kh, k1), _mm_unpackhi_epi16(nl, c->omin));
        const __m128i oa = _mm_add_epi32(qa, _mm_madd_epi16(_mm_unpacklo_epi16(v, lo), c->m1));
        const __m128i ob = _mm_add_epi32(qb, _mm_madd_epi16(_mm_unpackhi_epi16(v, lo), c->m1));
        const __m128i o = _mm_max_epi16(_mm_packs_epi32(oa, ob), c->omin);
        const __m128i ms = _mm_cmpeq_epi16(v, c->h8);
        _mm_storeu_si128((__m128i *)(void *)rx, _mm_min_epi16(o, _mm_xor_si128(ms, c->o7f)));
        const __m128i out = _mm_or_si128(_mm_cmpgt_epi16(_mm_add_epi16(o, c->gx), c->g2x), ms);
        as = _mm_add_epi32(as, _mm_madd_epi16(_mm_andnot_si128(out, o), c->ones));
        al = _mm_add_epi32(al, _mm_madd_epi16(_mm_xor_si128(_mm_andnot_si128(out, l), c->h8), c->ones));
        an = _mm_add_epi16(an, out);
        rx += 8;
        lx += 16;
    }
    q->ua = ua;
    q->ub = ub;
    a->s = as;
    a->l = al;
    a->n = an;
}

static inline void fl_l16_run_(int16_t *r, const uint8_t *lrow, uint32_t x, uint32_t n,
                               uint32_t u0, uint32_t st, const fl_l16c_t *c, fl_l16a_t *a)
{
    fl_l16u_t q = fl_l16_uv_(u0, st, c);
    fl_l16_grps_(r, lrow, x, n, &q, c, a);
}

/* The lanes' totals added to acc; np: the pixels the lanes took (the count's and the level
 * sum's bias). The sum and the level sum side by side: (s0 + s2, l0 + l2, s1 + s3, l1 + l3). */
static inline void fl_l16_sum_(const fl_l16a_t *a, uint32_t np, fl_acc_t *acc)
{
    __m128i t = _mm_add_epi32(_mm_unpacklo_epi32(a->s, a->l), _mm_unpackhi_epi32(a->s, a->l));
    t = _mm_add_epi32(t, _mm_shuffle_epi32(t, 0x4E));
    __m128i m = _mm_madd_epi16(a->n, _mm_set1_epi16(1));
    m = _mm_add_epi32(m, _mm_shuffle_epi32(m, 0x4E));
    m = _mm_add_epi32(m, _mm_shuffle_epi32(m, 0xB1));
    acc->sum += _mm_cvtsi128_si32(t);
    acc->lsum += (uint32_t)_mm_cvtsi128_si32(_mm_shuffle_epi32(t, 0x55)) + 32768u * np;
    acc->cnt += np - (uint32_t)-_mm_cvtsi128_si32(m);
}
#endif

#ifdef FL_LEV_SPLIT_
/* fl_lev32_ with 16 x 16-bit products: kl l from the unsigned 16-bit kl and l; kh l as
 * kh (l - 32768) + 32768 kh, kh in [-8, 8] and l - 32768 in [-32768, 32767] (int16),
 * |32768 kh| <= 2^18: the same integers. */
static inline int32_t fl_lev16_(int32_t kv, uint16_t l16)
{
    const uint32_t l = l16;
    const int16_t kh = (int16_t)((int32_t)((uint32_t)(kv + FL_MMAX_) >> 16) - 8);
    const uint16_t kl = (uint16_t)((uint32_t)kv & 0xFFFFu);
    const uint32_t neg = ((uint32_t)kv >> 31) & ((0u - l) >> 31);
    const uint32_t pl = (uint32_t)kl * l;
    const int16_t ls = (int16_t)((int32_t)l16 - 32768);
    const int32_t ph = (int32_t)kh * (int32_t)ls + 32768 * (int32_t)kh;
    return ph + (int32_t)((pl + 32768u - neg) >> 16);
}
#endif

/* One pixel of a span without a branch: v (the residual) less off, clamped, written to *rx and
 * booked into the sums when within the gate; a masked pixel left as it is and not booked. */
static inline void fl_px_bf_(int16_t *rx, int32_t v, int32_t off, uint32_t l, int32_t gate,
                             int32_t *sum, uint32_t *cnt, uint32_t *lsum)
{
    int32_t o = v - off;
    o = o > 32767 ? 32767 : (o < -32767 ? -32767 : o);
    const uint32_t ok = (uint32_t)((v != PFT_RES16_MASKED) ? 1u : 0u);
    *rx = (int16_t)(ok != 0u ? o : v);
    const uint32_t in = ok & (((uint32_t)(o + gate) <= (2u * (uint32_t)gate)) ? 1u : 0u);
    *sum += (int32_t)((uint32_t)o & (0u - in));
    *cnt += in;
    *lsum += l & (0u - in);
}

/* Pixels x0..x1-1 of row r (one block, between two block centres). *u is the block values'
 * interpolation at x0 as fl_shr_ takes it: (numerator + FL_BIAS_) + 2^(k-1), so that
 * (*u >> k) - (FL_BIAS_ >> k) is the value; it steps by st per pixel (modulo 2^32, exact as
 * every value is in range) and is left at x1. lrow: the level row (NULL: offset form). Each
 * form is one branch-free loop (fl_px_bf_, fl_lev32_), the interpolation's value at x from u0
 * and x - x0, the sums in locals: a form the compiler vectorises. */
static void fl_span_(int16_t *r, const uint8_t *lrow, bool u8, uint32_t x0, uint32_t x1,
                     uint32_t *u, uint32_t st, uint32_t k, int32_t gate, fl_acc_t *acc)
{
    const int32_t cb = (int32_t)((uint32_t)FL_BIAS_ >> k);
    const uint32_t u0 = *u;
    int32_t sum = acc->sum;
    uint32_t cnt = acc->cnt;
    uint32_t lsum = acc->lsum;
    if (lrow == NULL) {
        for (uint32_t x = x0; x < x1; ++x) {
            const int32_t off = (int32_t)((u0 + (x - x0) * st) >> k) - cb;
            fl_px_bf_(&r[x], r[x], off, 0u, gate, &sum, &cnt, &lsum);
        }
    } else if (u8) {
        for (uint32_t x = x0; x < x1; ++x) {
            const int32_t kv = (int32_t)((u0 + (x - x0) * st) >> k) - cb;
            const uint32_t l = lrow[x];
            fl_px_bf_(&r[x], r[x], fl_lev32_(kv, l), l, gate, &sum, &cnt, &lsum);
        }
    } else {
#ifdef FL_LEV_VEC_
        /* 8 pixels at a time (fl_l16_run_), the rest per pixel (fl_lev16_ for fl_lev32_ with
         * SSE2); the interpolation stepped by st per pixel (modulo 2^32: u0 + (x - x0) st) */
        fl_l16c_t c;
        fl_l16a_t va;
        fl_l16_init_(&c, k, cb, gate);
        fl_l16_zero_(&va);
        const uint32_t n8 = (x1 - x0) / 8u, xs = x0 + 8u * n8;
        fl_l16_run_(r, lrow, x0, n8, u0, st, &c, &va);
        fl_acc_t vacc = {sum, cnt, lsum};
        fl_l16_sum_(&va, 8u * n8, &vacc);
        sum = vacc.sum;
        cnt = vacc.cnt;
        lsum = vacc.lsum;
        for (uint32_t x = xs; x < x1; ++x) {
            const int32_t kv = (int32_t)((u0 + (x - x0) * st) >> k) - cb;
            uint16_t l16;
            memcpy(&l16, lrow + 2u * x, 2u);
#ifdef FL_LEV_SPLIT_
            fl_px_bf_(&r[x], r[x], fl_lev16_(kv, l16), l16, gate, &sum, &cnt, &lsum);
#else
            fl_px_bf_(&r[x], r[x], fl_lev32_(kv, l16), l16, gate, &sum, &cnt, &lsum);
#endif
        }
#else
        for (uint32_t x = x0; x < x1; ++x) {
            const int32_t kv = (int32_t)((u0 + (x - x0) * st) >> k) - cb;
            uint16_t l16;
            memcpy(&l16, lrow + 2u * x, 2u);
            const uint32_t l = l16;
            fl_px_bf_(&r[x], r[x], fl_lev32_(kv, l), l, gate, &sum, &cnt, &lsum);
        }
#endif
    }
    *u = u0 + (x1 - x0) * st;
    acc->sum = sum;
    acc->cnt = cnt;
    acc->lsum = lsum;
}

/* Corrects row r (w pixels) with the offsets of the row's block values fl->rowv; with learn,
 * books the gated corrected values into the sums of block row jb. The columns are walked
 * segment by segment between block centres (the weight t steps by 2 per pixel, so the
 * interpolation's numerator a0 (d - t) + a1 t by 2 (a1 - a0)), each segment in its two block
 * spans, whose sums are booked once per span. */
/* Segment s of a row walk between block centres (columns from x up to the centre of block s;
 * s == nbx: to the row's end w): its end xe and, when it holds a column (x < xe), the biased
 * numerator u of fl_shr_(fl_mix_(a0, a1, t, d, k)) at x and its step st per pixel (0 where the
 * value is held: before the first centre and after the last). */
typedef struct {
    uint32_t xe, u, st;
} fl_seg_t;

static inline fl_seg_t fl_seg_(const int32_t *rv, uint32_t s, uint32_t x, uint32_t nbx, uint32_t lb,
                               uint32_t w, int32_t d, uint32_t k)
{
    fl_seg_t g = {s < nbx ? (s << lb) + ((1u << lb) / 2u) : w, 0u, 0u};
    g.xe = g.xe > w ? w : g.xe;
    if (x < g.xe) {
        const int32_t a0 = rv[s == 0u ? 0u : s - 1u], a1 = rv[s < nbx ? s : nbx - 1u];
        const bool held = (s == 0u) || (s == nbx);
        const int32_t t = held ? 0 : (int32_t)(2u * x) - fl_c2_(s - 1u, lb);
        g.u = (uint32_t)(a0 * (d - t) + a1 * t + FL_BIAS_) + (1u << (k - 1u));
        g.st = held ? 0u : (uint32_t)(2 * (a1 - a0));
    }
    return g;
}

/* The end of block blk's span in a segment ending at xe: the next block's first column or xe. */
static inline uint32_t fl_blk_end_(uint32_t blk, uint32_t lb, uint32_t xe)
{
    const uint32_t xb = (blk + 1u) << lb;
    return xb > xe ? xe : xb;
}

#ifdef FL_LEV_VEC_
/* fl_row_ for the relative form with a 16-bit level row and blocks of 16 pixels or more
 * (FL_LEV_VEC_): block by block, each whole block in view as 2 runs of 8-pixel groups (its
 * halves before and after its centre lie in two segments: the second run's interpolation from
 * fl_seg_ at its first column, the first run's the last block's second segment stepped on by
 * b / 2 pixels: the same numerators as the walk's steps modulo 2^32), its sums added up once; a block the row's end cuts, the walk of fl_row_ with fl_span_. The same
 * values and sums as fl_row_. */
static void fl_row_l16_(pft_pre_flat_t *fl, int16_t *r, const uint8_t *lrow, bool learn,
                        uint32_t jb)
{
    const uint32_t w = fl->cfg.width, lb = fl->lb, nbx = fl->nbx, hb = (1u << lb) / 2u;
    const uint32_t k = lb + 1u;
    const int32_t d = (int32_t)(2u << lb), gate = (int32_t)fl->cfg.gate;
    const int32_t cb = (int32_t)((uint32_t)FL_BIAS_ >> k);
    int32_t *sum = fl->sum + (size_t)jb * nbx;
    uint32_t *cnt = fl->cnt + (size_t)jb * nbx;
    uint32_t *lsum = fl->lsum + (size_t)jb * nbx;
    const int32_t *rv = fl->rowv;
    fl_l16c_t c;
    fl_l16_init_(&c, k, cb, gate);
    uint32_t blk = 0u;
    /* the block's first half continues the segment of the last block's second half */
    fl_seg_t ga = fl_seg_(rv, 0u, 0u, nbx, lb, w, d, k);
#ifdef FL_LEV_SPLIT_
    /* SSE2: the lanes of the block's first half carried on from the last block's second half */
    fl_l16u_t q = fl_l16_uv_(ga.u, ga.st, &c);
#endif
    for (; blk < nbx && ((blk + 1u) << lb) <= w; ++blk) {
        const uint32_t x0 = blk << lb;
        const fl_seg_t gb = fl_seg_(rv, blk + 1u, x0 + hb, nbx, lb, w, d, k);
        fl_l16a_t va;
        fl_l16_zero_(&va);
#ifdef FL_LEV_SPLIT_
        fl_l16_grps_(r, lrow, x0, hb / 8u, &q, &c, &va);
        q = fl_l16_uv_(gb.u, gb.st, &c);
        fl_l16_grps_(r, lrow, x0 + hb, hb / 8u, &q, &c, &va);
#else
        fl_l16_run_(r, lrow, x0, hb / 8u, ga.u, ga.st, &c, &va);
        fl_l16_run_(r, lrow, x0 + hb, hb / 8u, gb.u, gb.st, &c, &va);
#endif
        ga.u = gb.u + hb * gb.st;
        ga.st = gb.st;
        if (learn) {
            fl_acc_t acc = {0, 0u, 0u};
            fl_l16_sum_(&va, 2u * hb, &acc);
            sum[blk] += acc.sum;
            cnt[blk] += acc.cnt;
            lsum[blk] += acc.lsum;
        }
    }
    uint32_t x = blk << lb;
    for (uint32_t s = blk; s <= nbx && x < w; ++s) {
        const fl_seg_t g = fl_seg_(rv, s, x, nbx, lb, w, d, k);
        const uint32_t xe = g.xe, st = g.st;
        uint32_t u = g.u;
        while (x < xe) {
            const uint32_t bk = x >> lb, xb = fl_blk_end_(bk, lb, xe);
            fl_acc_t acc = {0, 0u, 0u};
            fl_span_(r, lrow, false, x, xb, &u, st, k, gate, &acc);
            if (learn) {
                sum[bk] += acc.sum;
                cnt[bk] += acc.cnt;
                lsum[bk] += acc.lsum;
            }
            x = xb;
        }
    }
}
#endif

static void fl_row_(pft_pre_flat_t *fl, int16_t *r, const uint8_t *lrow, bool u8, bool learn,
                    uint32_t jb)
{
#ifdef FL_LEV_VEC_
    if (lrow != NULL && !u8 && fl->lb >= 4u) {
        fl_row_l16_(fl, r, lrow, learn, jb);
        return;
    }
#endif
    const uint32_t w = fl->cfg.width, lb = fl->lb, nbx = fl->nbx;
    const uint32_t d2 = 2u << lb;
    const uint32_t k = lrow != NULL ? lb + 1u : lb + 9u;
    const int32_t d = (int32_t)d2, gate = (int32_t)fl->cfg.gate;
    int32_t *sum = fl->sum + (size_t)jb * nbx;
    uint32_t *cnt = fl->cnt + (size_t)jb * nbx;
    uint32_t *lsum = fl->lsum + (size_t)jb * nbx;
    const int32_t *rv = fl->rowv;
    uint32_t x = 0u;
    for (uint32_t s = 0u; s <= nbx; ++s) {
        /* segment s: columns up to the centre of block s (s == nbx: to the end) */
        const fl_seg_t g = fl_seg_(rv, s, x, nbx, lb, w, d, k);
        const uint32_t xe = g.xe, st = g.st;
        uint32_t u = g.u;
        while (x < xe) {
            const uint32_t blk = x >> lb, xb = fl_blk_end_(blk, lb, xe);
            fl_acc_t acc = {0, 0u, 0u};
            fl_span_(r, lrow, u8, x, xb, &u, st, k, gate, &acc);
            if (learn) {
                sum[blk] += acc.sum;
                cnt[blk] += acc.cnt;
                lsum[blk] += acc.lsum;
            }
            x = xb;
        }
    }
}

/* The blocks' means of this frame into the map, with weight a (Q0.16). */
static void fl_learn_(pft_pre_flat_t *fl, uint32_t a)
{
    const uint32_t w = fl->cfg.width, h = fl->cfg.height, lb = fl->lb, b = 1u << lb;
    for (uint32_t j = 0u; j < fl->nby; ++j) {
        const uint32_t bh = (j + 1u) * b > h ? h - j * b : b;
        for (uint32_t i = 0u; i < fl->nbx; ++i) {
            const uint32_t bw = (i + 1u) * b > w ? w - i * b : b;
            const size_t k = (size_t)j * fl->nbx + i;
            const uint32_t n = fl->cnt[k];
            if (n == 0u || 4u * n < bw * bh) {
                continue;
            }
            /* the mean of the corrected values, sigma Q16, is the map's error; relative: their
             * sum over the sum of the levels, sigma per count Q24 */
            int64_t mean;
            if (fl->cfg.relative) {
                if (fl->lsum[k] == 0u) {
                    continue;
                }
                mean = pft_pre_div_rnd_((int64_t)fl->sum[k] * 65536, (int64_t)fl->lsum[k]);
            } else {
                mean = pft_pre_div_rnd_((int64_t)fl->sum[k] * 256, (int64_t)n);
            }
            int64_t m = (int64_t)fl->m[k] + pft_pre_div_rnd_(mean * (int64_t)a, 65536);
            m = m > FL_MMAX_ ? FL_MMAX_ : (m < -FL_MMAX_ ? -FL_MMAX_ : m);
            fl->m[k] = (int32_t)m;
        }
    }
}

#ifndef FL_SCALE_SPLIT_
/* v q / 2^16 rounded half away from zero (|v| <= 2^15, 0 < q <= 2^20: |v q| < 2^39), the
 * floor taken on the product biased to a non-negative value, as fl_lev_ (the same integers as
 * a rounded division). */
static int32_t fl_mulq_(int32_t v, int32_t q)
{
    const int64_t p = (int64_t)v * (int64_t)q;
    const uint64_t u = (uint64_t)(p + (FL_QBIAS_ + 32768)) - (p < 0 ? 1u : 0u);
    return (int32_t)(u >> 16u) - FL_QBIAS16_;
}
#endif

#ifdef FL_SCALE_SPLIT_
/* rescale: pixels x0 .. x1 - 1 of row r, the multiplier's interpolation u0 stepped by st, as
 * the loop of fl_scale_row_ below; fl_mulq_ in 16 x 16-bit products, branch-free: q = 65536 qh
 * + ql with qh = q >> 16 in [0, 16] and ql in [0, 65535]; v in [-32767, 32767] (an unmasked
 * pixel). v q = 65536 v qh + v ql, and v ql = v (ql - 32768) + 32768 v (int16 products;
 * |v ql| <= 32767 * 65535 < 2^31 - 32768), so floor((v q + 32768 - [v < 0]) / 2^16) =
 * v qh + ((v ql + 32768 - [v < 0]) >> 16), the same integer as fl_mulq_ (q > 0: v q < 0 exactly
 * when v < 0). A masked pixel is stored back unchanged and counted nowhere. */
static void fl_scale_span_(int16_t *r, uint32_t x0, uint32_t x1, uint32_t u0, uint32_t st,
                           uint32_t k, int32_t cb, int32_t thr, uint32_t *na, uint32_t *nl)
{
    uint32_t u = u0, a = 0u, n = 0u;
    int16_t *rx = r + x0;
    const uint32_t m = x1 - x0;
    for (uint32_t i = 0u; i < m; ++i) { /* vectorisable */
        const int32_t q = (int32_t)(u >> k) - cb;
        u += st;
        const int16_t v = rx[i];
        const uint32_t ok = v != PFT_RES16_MASKED ? 1u : 0u;
        a += ok;
        /* |v| <= thr (0 <= thr < 2^12) as one unsigned compare: the loop vectorises so */
        n += ok & ((uint32_t)((int32_t)v + thr) <= 2u * (uint32_t)thr ? 1u : 0u);
        const int16_t qh = (int16_t)((uint32_t)q >> 16);
        const int16_t qs = (int16_t)((int32_t)((uint32_t)q & 0xFFFFu) - 32768);
        const int32_t pl = (int32_t)v * (int32_t)qs + 32768 * (int32_t)v;
        int32_t o = (int32_t)v * (int32_t)qh + ((pl + 32768 - (v < 0 ? 1 : 0)) >> 16);
        o = o > 32767 ? 32767 : (o < -32767 ? -32767 : o);
        rx[i] = (int16_t)(ok != 0u ? o : v);
    }
    *na = a;
    *nl = n;
}
#endif

/* rescale: row r (w pixels, corrected) times the multipliers 1/s interpolated bilinearly (the
 * block rows' values in fl->rowq, then per pixel between the block columns, walked segment by
 * segment between block centres as fl_row_), rounded half away from zero and clamped; with
 * learn, counts per block of row jb its unmasked pixels and those with |v| <= 0.6745 s of the
 * block's own s (before the multiplication). */
static void fl_scale_row_(pft_pre_flat_t *fl, int16_t *r, uint32_t y, bool learn, uint32_t jb)
{
    const uint32_t w = fl->cfg.width, lb = fl->lb, nbx = fl->nbx;
    const int32_t d = (int32_t)(2u << lb);
    uint32_t j0, j1, t0;
    fl_locate_(2u * y, fl->nby, lb, &j0, &j1, &t0);
    const int32_t *qa = fl->sq + (size_t)j0 * nbx, *qb = fl->sq + (size_t)j1 * nbx;
    for (uint32_t i = 0u; i < nbx; ++i) {
        fl->rowq[i] = fl_mix_(qa[i], qb[i], (int32_t)t0, d, lb + 1u);
    }
    const int32_t *sc = fl->sc + (size_t)jb * nbx;
    uint32_t *nall = fl->nall + (size_t)jb * nbx, *nlo = fl->nlo + (size_t)jb * nbx;
    const int32_t *rq = fl->rowq;
    const uint32_t k = lb + 1u;
    const int32_t cb = (int32_t)((uint32_t)FL_BIAS_ >> k);
    uint32_t x = 0u;
    for (uint32_t sg = 0u; sg <= nbx; ++sg) {
        const fl_seg_t g = fl_seg_(rq, sg, x, nbx, lb, w, d, k);
        const uint32_t xe = g.xe, st = g.st;
        uint32_t u = g.u;
        while (x < xe) {
            const uint32_t blk = x >> lb, xb = fl_blk_end_(blk, lb, xe);
            /* the block's median threshold 0.6745 s in Q8.8 (0 < s Q16 <= 2^20: the product < 2^36) */
            const int32_t thr = (int32_t)(((uint64_t)(uint32_t)sc[blk] * (uint64_t)FL_MADQ_ + 8388608u) >> 24u);
            uint32_t na = 0u, nl = 0u;
#ifdef FL_SCALE_SPLIT_
            fl_scale_span_(r, x, xb, u, st, k, cb, thr, &na, &nl);
            u += (xb - x) * st;
            x = xb;
#else
            for (; x < xb; ++x) {
                const int32_t q = (int32_t)(u >> k) - cb;
                u += st;
                const int32_t v = r[x];
                if (v == PFT_RES16_MASKED) {
                    continue;
                }
                na += 1u;
                nl += (v <= thr && v >= -thr) ? 1u : 0u;
                int32_t o = fl_mulq_(v, q);
                o = o > 32767 ? 32767 : (o < -32767 ? -32767 : o);
                r[x] = (int16_t)o;
            }
#endif
            if (learn) {
                nall[blk] += na;
                nlo[blk] += nl;
            }
        }
    }
}

/* rescale: the blocks' sd from this frame's counts, one damped Newton step on log s towards
 * the median of |v| per block (weight a, Q0.16; the step before the weight within +-1/2). */
static void fl_learn_scale_(pft_pre_flat_t *fl, uint32_t a)
{
    const uint32_t w = fl->cfg.width, h = fl->cfg.height, lb = fl->lb, b = 1u << lb;
    for (uint32_t j = 0u; j < fl->nby; ++j) {
        const uint32_t bh = (j + 1u) * b > h ? h - j * b : b;
        for (uint32_t i = 0u; i < fl->nbx; ++i) {
            const uint32_t bw = (i + 1u) * b > w ? w - i * b : b;
            const size_t k = (size_t)j * fl->nbx + i;
            const uint32_t n = fl->nall[k];
            if (n == 0u || 4u * n < bw * bh) {
                continue;
            }
            /* e > 0: more than half of |v| below the threshold, s too large */
            const int64_t e = 2 * (int64_t)fl->nlo[k] - (int64_t)n;
            int64_t st = pft_pre_div_rnd_(e * FL_NEWTON_, (int64_t)n);
            st = st > 32768 ? 32768 : (st < -32768 ? -32768 : st);
            st = pft_pre_div_rnd_(st * (int64_t)a, 65536);
            int64_t s = (int64_t)fl->sc[k] - pft_pre_div_rnd_((int64_t)fl->sc[k] * st, 65536);
            s = s > FL_SMAX_ ? FL_SMAX_ : (s < FL_SMIN_ ? FL_SMIN_ : s);
            fl->sc[k] = (int32_t)s;
            fl->sq[k] = (int32_t)pft_pre_div_rnd_(FL_Q32_, s);
        }
    }
}

pft_status_t pft_pre_flat_update(pft_pre_flat_t *fl, const pft_frame_t *res, int16_t *pixels,
                                 const pft_frame_t *level, bool evidence)
{
    if (fl == NULL || fl->m == NULL || res == NULL || pixels == NULL) {
        return PFT_ERR_INVAL;
    }
    if (res->data != (const void *)pixels) {
        return PFT_ERR_INVAL;
    }
    const pft_status_t s =
        pft_frame_check(res, fl->cfg.width, fl->cfg.height, PFT_FMT_BIT(PFT_PIX_RES16));
    if (s != PFT_OK) {
        return s;
    }
    if ((res->stride_bytes & 1u) != 0u) {
        return PFT_ERR_FORMAT; /* rows of int16 at odd addresses (as the clutter map refuses) */
    }
    if (fl->cfg.relative) {
        if (level == NULL) {
            return PFT_ERR_INVAL;
        }
        const pft_status_t sl = pft_frame_check(level, fl->cfg.width, fl->cfg.height,
                                                PFT_FMT_BIT(PFT_PIX_U16) | PFT_FMT_BIT(PFT_PIX_U8));
        if (sl != PFT_OK) {
            return sl;
        }
    }
    const bool rel = fl->cfg.relative, u8 = rel && level->format == PFT_PIX_U8;
    const uint32_t h = fl->cfg.height, nb = fl->nbx * fl->nby;
    if (evidence) {
        memset(fl->sum, 0, (size_t)nb * 4u);
        memset(fl->cnt, 0, (size_t)nb * 4u);
        memset(fl->lsum, 0, (size_t)nb * 4u);
        if (fl->sc != NULL) {
            memset(fl->nall, 0, (size_t)nb * 4u);
            memset(fl->nlo, 0, (size_t)nb * 4u);
        }
    }
    for (uint32_t y = 0u; y < h; ++y) {
        fl_rowv_(fl, y);
        int16_t *r = (int16_t *)(void *)((uint8_t *)(void *)pixels + (size_t)y * res->stride_bytes);
        fl_row_(fl, r, rel ? pft_frame_row(level, y) : NULL, u8, evidence, y >> fl->lb);
        if (fl->sc != NULL) {
            fl_scale_row_(fl, r, y, evidence, y >> fl->lb);
        }
    }
    if (evidence) {
        fl->frames = fl->frames < 0xFFFFFFFFu ? fl->frames + 1u : fl->frames;
        const uint32_t run = fl->frames >= 65536u ? 1u : 65536u / fl->frames;
        const uint32_t a = run > (uint32_t)fl->cfg.alpha ? run : (uint32_t)fl->cfg.alpha;
        fl_learn_(fl, a);
        if (fl->sc != NULL) {
            fl_learn_scale_(fl, a);
        }
    }
    return PFT_OK;
}
