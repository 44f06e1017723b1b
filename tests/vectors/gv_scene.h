/*
 * Integer-only pieces shared by the tracker-level golden-vector specs (tbd_vectors_spec.h,
 * pf_vectors_spec.h): a small simulated TBD scene rendered with integer arithmetic only (so
 * every target draws exactly the same frames, no libm involved), a 32-bit FNV-1a hash of
 * values, and the raw-value conversions of results.
 *
 * Scene: frame columns c and rows r are 0-based array indices. A target at column position
 * cx16 / 16 and row position ry16 / 16 adds amp256 / 256 * g(c - cx) * g(r - ry) to the pixel,
 * g(d) = exp(-d^2 / (2 * 0.49)) tabulated in Q12 at 1/16 pixel steps (PSF sigma 0.7). Noise
 * is an Irwin-Hall sum of 12 uniform 16-bit draws of the library RNG (mean 0, variance 1),
 * times sigma256 / 256. Pixels are U16, raw = 256 * (z + 64), so pixel_gain 1/256 and
 * pixel_offset -64 give back z.
 */
#ifndef PFT_GV_SCENE_INC_H
#define PFT_GV_SCENE_INC_H
#include <string.h>
#include "pft/pft.h"

#define PFT_GV_SCENE_W 20
#define PFT_GV_SCENE_H 20

/* g(k / 16) in Q12, k = 0..48; 0 beyond */
static const int32_t pft_gv_psf_q12[49] = {
    4096, 4080, 4031, 3952, 3843, 3708, 3548, 3369, 3174, 2966, 2749, 2529, 2307,
    2088, 1875, 1671, 1476, 1294, 1126, 971,  832,  706,  595,  497,  412,  339,
    277,  224,  180,  143,  113,  89,   69,   53,   41,   31,   23,   17,   13,
    10,   7,    5,    4,    3,    2,    1,    1,    1,    0};

static inline int32_t pft_gv_psf_at(int32_t d16)
{
    int32_t a = d16 < 0 ? -d16 : d16;
    return a > 48 ? 0 : pft_gv_psf_q12[a];
}

/** A straight-line target in 1/16 pixel units, present in frames first..last (1-based). */
typedef struct {
    int32_t first, last;
    int32_t c16, r16;   /* position at `first` */
    int32_t vc16, vr16; /* per frame */
    int32_t amp256;     /* peak amplitude times 256 */
} pft_gv_target_t;

/** Renders frame k (1-based) of nt targets into raw (W*H U16) and describes it in f. */
static inline void pft_gv_render(pft_rng_t *rng, const pft_gv_target_t *t, int nt, int32_t k,
                                 int32_t sigma256, uint16_t *raw, pft_frame_t *f)
{
    for (int32_t r = 0; r < PFT_GV_SCENE_H; ++r) {
        for (int32_t c = 0; c < PFT_GV_SCENE_W; ++c) {
            int64_t n = 0;
            for (int q = 0; q < 12; ++q) {
                n += (int64_t)(pft_rng_u32(rng) >> 16);
            }
            n -= 6 * 65536; /* ~ N(0, 1) * 65536 */
            int64_t z256 = (n * sigma256) / 65536; /* noise, times 256 */
            for (int q = 0; q < nt; ++q) {
                if (k < t[q].first || k > t[q].last) {
                    continue;
                }
                int32_t cx = t[q].c16 + t[q].vc16 * (k - t[q].first);
                int32_t ry = t[q].r16 + t[q].vr16 * (k - t[q].first);
                int64_t g = (int64_t)pft_gv_psf_at(c * 16 - cx) * pft_gv_psf_at(r * 16 - ry);
                z256 += ((int64_t)t[q].amp256 * g) / (4096 * 4096);
            }
            int64_t v = z256 + 64 * 256;
            raw[r * PFT_GV_SCENE_W + c] = (uint16_t)(v < 0 ? 0 : v > 65535 ? 65535 : v);
        }
    }
    memset(f, 0, sizeof(*f));
    f->data = raw;
    f->width = PFT_GV_SCENE_W;
    f->height = PFT_GV_SCENE_H;
    f->stride_bytes = 2u * PFT_GV_SCENE_W;
    f->format = PFT_PIX_U16;
    f->bit_depth = 16;
    f->seq = (uint32_t)k;
}

/* ---- hashing and raw values ---- */
#define PFT_GV_FNV0 2166136261u
static inline uint32_t pft_gv_fnv(uint32_t h, uint32_t v)
{
    for (int b = 0; b < 4; ++b) {
        h ^= (v >> (8 * b)) & 0xFFu;
        h *= 16777619u;
    }
    return h;
}

/* The reference of a replay test: the q16 header in q16 builds, a second replay otherwise. */
#define PFT_GV_REF(q16, again) (PFT_GV_EXACT ? (q16) : (again))

#ifdef PFT_NUMERIC_Q16
#define PFT_GV_EXACT 1
static inline uint32_t pft_gv_r(pft_real_t v) { return (uint32_t)v; }
static inline uint32_t pft_gv_w(pft_weight_t w) { return (uint32_t)w; }
#else
#define PFT_GV_EXACT 0
/* float results in Q16.16 raw units (saturated like q16, rounded to nearest) */
static inline uint32_t pft_gv_r(pft_real_t v)
{
    float s = v * 65536.0f;
    if (!(s == s)) return 0x80000000u; /* NaN */
    if (s >= 2147483520.0f) return (uint32_t)INT32_MAX;
    if (s <= -2147483520.0f) return (uint32_t)(-INT32_MAX);
    return (uint32_t)(int32_t)(s >= 0.0f ? s + 0.5f : s - 0.5f);
}
static inline uint32_t pft_gv_w(pft_weight_t w) { return (uint32_t)(w * 1073741824.0f + 0.5f); }
#endif

#endif
