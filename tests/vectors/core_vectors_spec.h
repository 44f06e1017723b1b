/*
 * The calls behind the golden vectors, shared by the generator (host) and the replay test
 * (every target), so both run exactly the same code. Inputs are integer patterns only, so they
 * are identical everywhere; pft_gv_compute() runs the library and fills the results.
 */
#ifndef PFT_CORE_VECTORS_SPEC_H
#define PFT_CORE_VECTORS_SPEC_H
#include <string.h>
#include "pft/pft.h"

#define PFT_GV_N_RNG 64u
#define PFT_GV_N_GRID 96u
#define PFT_GV_N_W 40u
#define PFT_GV_N_IDX 50u
#define PFT_GV_SEED 0x5EEDC0DEull
/* ziggurat: the first draws raw, and over a long run (its tails and wedges included) an FNV-1a
 * hash of the raw values and the next 32-bit word (equal in both builds: same decisions) */
#define PFT_GV_N_ZIG 96u
#define PFT_GV_N_ZIG_RUN 200000u

typedef struct {
    uint32_t rng_u32[PFT_GV_N_RNG];
    int32_t rng_uniform[PFT_GV_N_RNG];
    int32_t rng_gauss[PFT_GV_N_RNG];
    uint32_t rng_below[PFT_GV_N_RNG];
    int32_t mul[PFT_GV_N_GRID], div[PFT_GV_N_GRID], recip[PFT_GV_N_GRID], sqrt_[PFT_GV_N_GRID];
    int32_t exp_[PFT_GV_N_GRID], log_[PFT_GV_N_GRID], atan2_[PFT_GV_N_GRID];
    int32_t sin_[PFT_GV_N_GRID], cos_[PFT_GV_N_GRID], from_f32[PFT_GV_N_GRID];
    uint32_t wexp[PFT_GV_N_GRID];
    uint32_t lognorm_w[PFT_GV_N_W];
    int32_t lognorm_ret, ess;
    uint32_t idx[4][PFT_GV_N_IDX];
    int32_t kf4[20];
    int32_t rng_zig[PFT_GV_N_ZIG];
    uint32_t zig_run[2]; /* hash of the raw values, the next word */
} pft_gv_results_t;

/* Grid inputs: raw Q16.16 patterns spread over each function's domain (integer arithmetic). */
static inline int32_t pft_gv_lin(int32_t lo, int32_t hi, uint32_t i, uint32_t n)
{
    return (int32_t)(lo + (int32_t)(((int64_t)hi - lo) * (int64_t)i / (int64_t)(n - 1u)));
}

#ifdef PFT_NUMERIC_Q16
#define PFT_GV_REAL(raw) ((pft_real_t)(raw))
#define PFT_GV_RAW(v) ((int32_t)(v))
#define PFT_GV_WRAW(w) ((uint32_t)(w))
#else
#define PFT_GV_REAL(raw) ((pft_real_t)(raw) / 65536.0f)
/* float results in Q16.16 raw units, saturated like the q16 build, rounded to nearest */
static inline int32_t pft_gv_raw_f(float v)
{
    float s = v * 65536.0f;
    if (s >= 2147483520.0f) return INT32_MAX;
    if (s <= -2147483520.0f) return -INT32_MAX;
    return (int32_t)(s >= 0.0f ? s + 0.5f : s - 0.5f);
}
#define PFT_GV_RAW(v) pft_gv_raw_f(v)
#define PFT_GV_WRAW(w) ((uint32_t)((w) * 1073741824.0f + 0.5f))
#endif

/* Raw IEEE bit patterns for pft_from_f32: integers, halves, tiny, huge, negative. */
static inline uint32_t pft_gv_f32_bits(uint32_t i)
{
    static const uint32_t base[8] = {0x3F800000u, 0xBFC00000u, 0x40490FDBu, 0x3E99999Au,
                                     0x46FFFE00u, 0xC2F6E979u, 0x38D1B717u, 0x00000000u};
    return base[i % 8u] + (i / 8u) * 0x00012345u;
}

static inline void pft_gv_compute(pft_gv_results_t *r)
{
    pft_rng_t rng;
    pft_rng_seed(&rng, PFT_GV_SEED);
    for (uint32_t i = 0; i < PFT_GV_N_RNG; ++i) r->rng_u32[i] = pft_rng_u32(&rng);
    for (uint32_t i = 0; i < PFT_GV_N_RNG; ++i) r->rng_uniform[i] = PFT_GV_RAW(pft_rng_uniform(&rng));
    for (uint32_t i = 0; i < PFT_GV_N_RNG; ++i) r->rng_gauss[i] = PFT_GV_RAW(pft_rng_gauss(&rng));
    for (uint32_t i = 0; i < PFT_GV_N_RNG; ++i) r->rng_below[i] = pft_rng_below(&rng, 1000u + i);

    const uint32_t n = PFT_GV_N_GRID;
    for (uint32_t i = 0; i < n; ++i) {
        pft_real_t a = PFT_GV_REAL(pft_gv_lin(-200 * 65536, 200 * 65536, i, n));
        pft_real_t b = PFT_GV_REAL(pft_gv_lin(-3 * 65536 - 777, 5 * 65536 + 333, n - 1u - i, n));
        r->mul[i] = PFT_GV_RAW(pft_mul(a, b));
        r->div[i] = PFT_GV_RAW(pft_div(a, b));
        r->recip[i] = PFT_GV_RAW(pft_recip(b));
        r->sqrt_[i] = PFT_GV_RAW(pft_sqrt(PFT_GV_REAL(pft_gv_lin(1, 30000 * 65536, i, n))));
        r->exp_[i] = PFT_GV_RAW(pft_exp(PFT_GV_REAL(pft_gv_lin(-10 * 65536, 10 * 65536, i, n))));
        r->log_[i] = PFT_GV_RAW(pft_log(PFT_GV_REAL(pft_gv_lin(7, 30000 * 65536, i, n))));
        r->atan2_[i] = PFT_GV_RAW(pft_atan2(PFT_GV_REAL(pft_gv_lin(-5 * 65536, 5 * 65536, i, n)),
                                            PFT_GV_REAL(pft_gv_lin(-3 * 65536, 4 * 65536, (i * 7u) % n, n))));
        r->sin_[i] = PFT_GV_RAW(pft_sin(PFT_GV_REAL(pft_gv_lin(-20 * 65536, 20 * 65536, i, n))));
        r->cos_[i] = PFT_GV_RAW(pft_cos(PFT_GV_REAL(pft_gv_lin(-20 * 65536, 20 * 65536, i, n))));
        float f;
        uint32_t bits = pft_gv_f32_bits(i);
        memcpy(&f, &bits, sizeof f);
        r->from_f32[i] = PFT_GV_RAW(pft_from_f32(f));
        r->wexp[i] = PFT_GV_WRAW(pft_wexp(PFT_GV_REAL(pft_gv_lin(-25 * 65536, 0, i, n))));
    }

    pft_real_t lw[PFT_GV_N_W];
    pft_weight_t w[PFT_GV_N_W];
    for (uint32_t i = 0; i < PFT_GV_N_W; ++i) {
        lw[i] = PFT_GV_REAL((int32_t)((pft_rng_u32(&rng) >> 12) & 0x7FFFFu) - 6 * 65536);
    }
    r->lognorm_ret = PFT_GV_RAW(pft_lognormalize(lw, w, PFT_GV_N_W));
    for (uint32_t i = 0; i < PFT_GV_N_W; ++i) r->lognorm_w[i] = PFT_GV_WRAW(w[i]);
    r->ess = PFT_GV_RAW(pft_ess(w, PFT_GV_N_W));

    static uint32_t scratch[4 * PFT_GV_N_IDX + 4 * PFT_GV_N_W + 64];
    for (uint32_t s = 0; s < 4u; ++s) {
        pft_rng_seed(&rng, PFT_GV_SEED + s);
        (void)pft_resample((pft_resample_scheme_t)s, w, PFT_GV_N_W, r->idx[s], PFT_GV_N_IDX, &rng,
                           scratch, sizeof scratch);
    }

    pft_real_t x[4] = {PFT_C(1.0), PFT_C(0.5), PFT_C(-2.0), PFT_C(0.25)};
    pft_real_t P[16] = {0};
    pft_real_t F[16] = {0}, Q[16] = {0}, H[8] = {0}, R[4] = {PFT_C(0.3), 0, 0, PFT_C(0.3)};
    for (uint32_t i = 0; i < 4u; ++i) {
        P[i * 5u] = PFT_C(2.0);
        F[i * 5u] = PFT_C(1.0);
        Q[i * 5u] = PFT_C(0.01);
    }
    F[1] = PFT_C(1.0);
    F[11] = PFT_C(1.0);
    H[0] = PFT_C(1.0);
    H[6] = PFT_C(1.0);
    pft_real_t z[2] = {PFT_C(1.7), PFT_C(-1.6)};
    pft_kf4_predict(x, P, F, Q);
    (void)pft_kf4_update2(x, P, H, z, R);
    for (uint32_t i = 0; i < 4u; ++i) r->kf4[i] = PFT_GV_RAW(x[i]);
    for (uint32_t i = 0; i < 16u; ++i) r->kf4[4u + i] = PFT_GV_RAW(P[i]);

    /* a generator of its own, so the streams above are those of the earlier vectors */
    pft_rng_seed(&rng, PFT_GV_SEED + 100u);
    for (uint32_t i = 0; i < PFT_GV_N_ZIG; ++i) r->rng_zig[i] = PFT_GV_RAW(pft_rng_gauss_zig(&rng));
    uint32_t h = 2166136261u;
    for (uint32_t i = 0; i < PFT_GV_N_ZIG_RUN; ++i) {
        h = (h ^ (uint32_t)PFT_GV_RAW(pft_rng_gauss_zig(&rng))) * 16777619u;
    }
    r->zig_run[0] = h;
    r->zig_run[1] = pft_rng_u32(&rng);
}
#endif
