/* Shared by the libFuzzer harnesses of tests/fuzz (host only, clang -fsanitize=fuzzer):
 * a reader that turns the fuzzer's bytes into values (zeros once the input is used up), a
 * frame maker that gives valid and hostile frame descriptors over memory it owns, snapshots
 * for the "refused input changes nothing" check, and FZ_CHECK, which aborts (a crash for
 * libFuzzer) when a documented property of the library does not hold.
 *
 * Only public headers are used, so the harnesses keep working while the trackers' internals
 * change. Known open defects that the harnesses would otherwise hit at once are stepped
 * around by FZ_KNOWN blocks, each naming the defect; build with -DPFT_FUZZ_NO_KNOWN_GUARDS to
 * turn them off (docs/reliability.md lists them). */
#ifndef PFT_FUZZ_COMMON_H
#define PFT_FUZZ_COMMON_H

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#if !defined(PFT_NUMERIC_Q16)
#include <math.h>
#endif

#include "pft/pft.h"

#if defined(PFT_FUZZ_NO_KNOWN_GUARDS)
#define FZ_KNOWN 0
#else
#define FZ_KNOWN 1
#endif

#define FZ_CHECK(cond)                                                                        \
    do {                                                                                      \
        if (!(cond)) {                                                                        \
            fprintf(stderr, "pft fuzz: property violated at %s:%d: %s\n", __FILE__, __LINE__,  \
                    #cond);                                                                   \
            abort();                                                                          \
        }                                                                                     \
    } while (0)

/* ------------------------------------ input reader ---------------------------------------- */
typedef struct {
    const uint8_t *p;
    size_t n;
} fz_t;

static inline uint8_t fz_u8(fz_t *f)
{
    if (f->n == 0u) {
        return 0u;
    }
    f->n--;
    return *f->p++;
}
static inline uint16_t fz_u16(fz_t *f)
{
    uint16_t a = fz_u8(f);
    return (uint16_t)(a | (uint16_t)(fz_u8(f) << 8));
}
static inline uint32_t fz_u32(fz_t *f)
{
    uint32_t a = fz_u16(f);
    return a | ((uint32_t)fz_u16(f) << 16);
}
static inline uint64_t fz_u64(fz_t *f)
{
    uint64_t a = fz_u32(f);
    return a | ((uint64_t)fz_u32(f) << 32);
}
static inline bool fz_bool(fz_t *f) { return (fz_u8(f) & 1u) != 0u; }
/* lo..hi inclusive */
static inline uint32_t fz_range(fz_t *f, uint32_t lo, uint32_t hi)
{
    uint32_t span = hi - lo + 1u;
    return (span == 0u) ? fz_u32(f) : lo + fz_u32(f) % span;
}
/* copies up to n bytes; what the input does not have is zero */
static inline void fz_bytes(fz_t *f, void *dst, size_t n)
{
    size_t k = (f->n < n) ? f->n : n;
    memcpy(dst, f->p, k);
    memset((uint8_t *)dst + k, 0, n - k);
    f->p += k;
    f->n -= k;
}
/* a real in input units: a small integer + fraction most of the time, raw bits otherwise (in
 * the float build that includes NaN, infinities and subnormals) */
static inline pft_real_t fz_real(fz_t *f)
{
    uint8_t m = fz_u8(f);
    if (m < 200u) {
        int32_t i = (int32_t)(int8_t)fz_u8(f);
        return pft_add(pft_from_int(i), pft_div(pft_from_int(fz_u8(f)), pft_from_int(256)));
    }
    pft_real_t r;
    uint32_t bits = fz_u32(f);
    memcpy(&r, &bits, sizeof r);
    return r;
}

static inline bool fz_finite(pft_real_t v)
{
#if defined(PFT_NUMERIC_Q16)
    (void)v;
    return true;
#else
    return isfinite(v) != 0;
#endif
}

/* |v| <= 32767 and not NaN: inside the range both builds can represent */
static inline bool fz_small(pft_real_t v)
{
    return v >= PFT_C(-32767.0) && v <= PFT_C(32767.0);
}

/* A real a configuration could sensibly hold: in the float build finite, 0 or at least 1e-6
 * in magnitude, and at most 1e6; always true in q16. Used by FZ_KNOWN guards. */
static inline bool fz_sane(pft_real_t v)
{
#if defined(PFT_NUMERIC_Q16)
    (void)v;
    return true;
#else
    float a = fabsf(v);
    return isfinite(v) && (a == 0.0f || a >= 1e-6f) && a <= 1e6f;
#endif
}

/* fz_sane for n consecutive reals (a config struct made only of reals) */
static inline bool fz_sane_all(const pft_real_t *v, size_t n)
{
    for (size_t i = 0; i < n; ++i) {
        if (!fz_sane(v[i])) {
            return !FZ_KNOWN;
        }
    }
    return true;
}

/* Applies up to max_patches (offset, length, bytes) patches to a struct: the fuzzer changes a
 * few fields of a valid default and keeps the rest, whatever the struct's layout. */
static inline void fz_patch(fz_t *f, void *obj, size_t size, uint32_t max_patches)
{
    uint32_t n = fz_u8(f) % (max_patches + 1u);
    for (uint32_t i = 0; i < n && f->n > 0u; ++i) {
        size_t off = fz_u16(f) % size;
        size_t len = 1u + fz_u8(f) % 8u;
        if (len > size - off) {
            len = size - off;
        }
        fz_bytes(f, (uint8_t *)obj + off, len);
    }
}

/* -------------------------------------- frames -------------------------------------------- */
/* Pixel memory of every frame a harness makes; a descriptor never points outside it. */
#define FZ_PIX_BYTES (128u * 128u * 4u + 64u)
extern uint8_t fz_pix[FZ_PIX_BYTES];

static inline uint32_t fz_xorshift(uint32_t *s)
{
    uint32_t x = *s;
    x ^= x << 13;
    x ^= x >> 17;
    x ^= x << 5;
    *s = x;
    return x;
}

/* Fills bytes of pixel memory: a noise pattern seeded from the input, a flat level plus the
 * input's own bytes on top (so the fuzzer can draw a target), or raw input bytes. */
static inline void fz_fill(fz_t *f, uint8_t *p, size_t n)
{
    uint8_t mode = fz_u8(f) % 3u;
    uint32_t s = fz_u32(f) | 1u;
    uint8_t level = fz_u8(f);
    for (size_t i = 0; i < n; ++i) {
        p[i] = (mode == 0u) ? (uint8_t)fz_xorshift(&s) : level;
    }
    if (mode != 0u) {
        size_t k = fz_u16(f);
        k = (k > n) ? n : k;
        size_t at = (n > k) ? fz_u32(f) % (n - k + 1u) : 0u;
        fz_bytes(f, p + at, k);
    }
}

/* Float pixels in the float build: finite values most of the time (uniform noise around
 * `level`), so F32 frames are not all refused for NaN. */
static inline void fz_fill_f32(fz_t *f, uint8_t *p, size_t n_px, bool keep_raw)
{
    if (keep_raw) {
        return;
    }
    uint32_t s = fz_u32(f) | 1u;
    float level = (float)(int8_t)fz_u8(f);
    float amp = (float)fz_u8(f) / 16.0f;
    for (size_t i = 0; i < n_px; ++i) {
        float v = level + amp * ((float)(fz_xorshift(&s) & 0xFFFFu) / 65536.0f - 0.5f);
        memcpy(p + 4u * i, &v, 4u);
    }
}

/*
 * A frame for a consumer that expects w x h pixels in one of the formats of `fmt_mask`: most
 * of the time a well-formed one (packed or padded rows, any accepted format, a valid bit
 * depth), otherwise a hostile one (another size, an unknown or refused format, a short
 * stride, a bit depth above 16, NULL data). Pixels always lie inside fz_pix.
 */
static inline pft_frame_t fz_frame(fz_t *f, uint16_t w, uint16_t h, uint32_t fmt_mask)
{
    static const pft_pixfmt_t fmts[5] = {PFT_PIX_U8, PFT_PIX_U16, PFT_PIX_F32, PFT_PIX_RGB888,
                                         PFT_PIX_BGR888};
    pft_frame_t fr;
    memset(&fr, 0, sizeof fr);
    uint8_t kind = fz_u8(f);
    pft_pixfmt_t fmt = fmts[fz_u8(f) % 5u];
    if (kind < 224u) {
        for (uint32_t k = 0; k < 5u && (fmt_mask & PFT_FMT_BIT(fmt)) == 0u; ++k) {
            fmt = fmts[(uint32_t)fmt % 5u]; /* next format in the list */
        }
    }
    fr.format = fmt;
    fr.width = w;
    fr.height = h;
    uint32_t bpp = pft_pixfmt_bytes(fmt);
    fr.stride_bytes = (uint32_t)w * bpp + (fz_u8(f) % 4u) * bpp;
    fr.bit_depth = (fmt == PFT_PIX_U16) ? (uint8_t)(fz_u8(f) % 17u) : 0u;
    fr.seq = fz_u32(f);
    fr.timestamp_us = fz_u32(f);
    if (kind >= 224u) { /* hostile */
        switch (kind % 8u) {
        case 0: fr.width = (uint16_t)(w + 1u - 2u * (fz_u8(f) & 1u)); break;
        case 1: fr.height = (uint16_t)(h + 1u - 2u * (fz_u8(f) & 1u)); break;
        case 2: fr.format = (pft_pixfmt_t)(fz_u8(f) % 8u); break;
        case 3: fr.stride_bytes = (fr.stride_bytes > 0u) ? fr.stride_bytes - 1u : 0u; break;
        case 4: fr.bit_depth = (uint8_t)(17u + fz_u8(f) % 239u); break;
        case 5: fr.width = 0u; break;
        case 6: fr.stride_bytes = fz_u32(f); break;
        default: fr.data = NULL; return fr;
        }
    }
    /* the memory the descriptor claims must exist: shrink what does not fit */
    uint32_t fbpp = pft_pixfmt_bytes(fr.format);
    uint64_t need = (fr.height == 0u) ? 0u
                    : (uint64_t)fr.stride_bytes * (fr.height - 1u) + (uint64_t)fr.width * fbpp;
    if (need > FZ_PIX_BYTES) {
        fr.data = NULL;
        return fr;
    }
    size_t bytes = (size_t)need;
    fz_fill(f, fz_pix, bytes);
    if (fr.format == PFT_PIX_F32 && fr.stride_bytes % 4u == 0u && fr.stride_bytes > 0u) {
        fz_fill_f32(f, fz_pix, bytes / 4u, fz_u8(f) >= 240u);
    }
    fr.data = fz_pix;
    return fr;
}

/* ------------------------------------- snapshots ------------------------------------------ */
/* Instance and workspace copies taken before a call that may be refused. */
#define FZ_SNAP_BYTES (4u << 20)
extern uint8_t fz_snap_ws[FZ_SNAP_BYTES];
extern uint8_t fz_snap_inst[1u << 16];

static inline void fz_snap(const void *inst, size_t isz, const void *ws, size_t wsz)
{
    FZ_CHECK(isz <= sizeof fz_snap_inst && wsz <= sizeof fz_snap_ws);
    memcpy(fz_snap_inst, inst, isz);
    if (ws != NULL) {
        memcpy(fz_snap_ws, ws, wsz);
    }
}
static inline bool fz_same(const void *inst, size_t isz, const void *ws, size_t wsz)
{
    return memcmp(fz_snap_inst, inst, isz) == 0 && (ws == NULL || memcmp(fz_snap_ws, ws, wsz) == 0);
}

/* Statuses a refused call may return (anything but OK). */
static inline bool fz_refused(pft_status_t st) { return st != PFT_OK; }

/* ---------------------------- preprocessing (pft_pre_*) helpers --------------------------- */
/* Largest frame side of the preprocessing inputs whose updates run (docs/reliability.md,
 * "Per-input work"): 64 x 64 pixels, a few passes each, plus the registration's integer search
 * (2 reg_search + 1)(w + h) <= 65 x 128 sums. */
#define FZ_PRE_SIDE 64u

/* Raw frame kinds of the preprocessing inputs. */
enum { FZ_PRE_NOISE = 0, FZ_PRE_CONST = 1, FZ_PRE_ZERO = 2, FZ_PRE_SAT = 3, FZ_PRE_KINDS = 4 };

/* A raw U8 or U16 frame of w x h packed pixels (bit_depth bits, 0 reads as 16) in buf: noise
 * around a quarter of full scale with a bright blob and a drift of k px per frame (kind
 * FZ_PRE_NOISE), a constant, all zero or all saturated (every bit of bit_depth set). */
static inline pft_frame_t fz_pre_raw(uint8_t *buf, uint32_t seed, uint32_t k, uint16_t w,
                                     uint16_t h, pft_pixfmt_t fmt, uint8_t bit_depth,
                                     uint32_t kind)
{
    pft_frame_t fr;
    memset(&fr, 0, sizeof fr);
    uint32_t bits = (fmt == PFT_PIX_U8) ? 8u : (bit_depth == 0u ? 16u : bit_depth);
    uint32_t full = (bits >= 16u) ? 65535u : (1u << bits) - 1u;
    uint32_t bpp = (fmt == PFT_PIX_U8) ? 1u : 2u;
    fr.width = w;
    fr.height = h;
    fr.format = fmt;
    fr.bit_depth = (fmt == PFT_PIX_U16) ? bit_depth : 0u;
    fr.stride_bytes = (uint32_t)w * bpp;
    fr.seq = k;
    fr.timestamp_us = 1000u * (uint64_t)k;
    fr.data = buf;
    uint32_t s = (seed * 2654435761u + k) | 1u;
    uint32_t cx = seed % (w + 1u), cy = (seed >> 8) % (h + 1u);
    uint32_t amp = (full >> 6) + 1u;
    for (uint32_t y = 0; y < h; ++y) {
        for (uint32_t x = 0; x < w; ++x) {
            uint32_t v;
            if (kind == FZ_PRE_CONST) {
                v = (seed % full) + 1u;
            } else if (kind == FZ_PRE_ZERO) {
                v = 0u;
            } else if (kind == FZ_PRE_SAT) {
                v = full;
            } else {
                /* a smooth scene (drifting with k), noise, and a 3 x 3 target */
                uint32_t sx = x + k, scene = ((sx * 7u + y * 3u) % 64u) * (full >> 8);
                v = (full >> 2) + scene / 4u + fz_xorshift(&s) % amp;
                uint32_t dx = x > cx ? x - cx : cx - x, dy = y > cy ? y - cy : cy - y;
                if (dx < 2u && dy < 2u) {
                    v += full >> 3;
                }
                v = (v > full) ? full : v;
            }
            if (bpp == 1u) {
                buf[(size_t)y * w + x] = (uint8_t)v;
            } else {
                uint16_t u = (uint16_t)v;
                memcpy(buf + 2u * ((size_t)y * w + x), &u, 2u);
            }
        }
    }
    return fr;
}

/* The descriptor of a packed w x h PFT_PIX_RES16 plane in buf, frame seq. */
static inline pft_frame_t fz_res16_frame(const int16_t *buf, uint16_t w, uint16_t h, uint32_t seq)
{
    pft_frame_t fr;
    memset(&fr, 0, sizeof fr);
    fr.width = w;
    fr.height = h;
    fr.format = PFT_PIX_RES16;
    fr.stride_bytes = 2u * (uint32_t)w;
    fr.seq = seq;
    fr.data = buf;
    return fr;
}

/* A whitened residual (PFT_PIX_RES16) of w x h packed pixels in buf: Q8.8 noise of about one
 * sigma, a bright 3 x 3 point, and every 16th pixel (from the seed) masked. */
static inline pft_frame_t fz_pre_res(int16_t *buf, uint32_t seed, uint32_t k, uint16_t w,
                                     uint16_t h)
{
    pft_frame_t fr = fz_res16_frame(buf, w, h, k);
    uint32_t s = (seed * 2654435761u + k) | 1u;
    uint32_t cx = (seed + k) % (w + 1u), cy = (seed >> 8) % (h + 1u);
    for (uint32_t y = 0; y < h; ++y) {
        for (uint32_t x = 0; x < w; ++x) {
            uint32_t r = fz_xorshift(&s);
            int32_t v = (int32_t)(r & 1023u) - 512;
            uint32_t dx = x > cx ? x - cx : cx - x, dy = y > cy ? y - cy : cy - y;
            if (dx < 2u && dy < 2u) {
                v += 2048;
            }
            buf[(size_t)y * w + x] = ((r >> 16) % 16u == 0u) ? (int16_t)PFT_RES16_MASKED : (int16_t)v;
        }
    }
    return fr;
}

/* Sane statistics of an accepted pft_pre update of a w x h frame with peak_max pk. */
static inline void fz_pre_check_stats(const pft_pre_t *p, uint16_t w, uint16_t h, uint16_t pk,
                                      int16_t thr)
{
    pft_pre_stats_t st;
    FZ_CHECK(pft_pre_stats(p, &st) == PFT_OK);
    uint32_t n = (uint32_t)w * h;
    FZ_CHECK(st.n_masked <= n && st.n_saturated <= n && st.n_dead <= n && st.n_bad <= n);
    FZ_CHECK(st.n_saturated + st.n_dead + st.n_bad <= n);
    FZ_CHECK((st.flags & ~0x1FFu) == 0u);
    FZ_CHECK(st.n_peaks <= pk && st.n_peaks <= st.n_candidates && st.n_candidates <= n);
    FZ_CHECK(st.sigma_min <= st.sigma_mean && st.sigma_mean <= st.sigma_max);
    /* ALL_MASKED: no pixel passed the mask, so every residual is masked (the converse does not
     * hold: the border band of LOCAL and the first frame of TEMPORAL mask valid pixels too) */
    FZ_CHECK((st.flags & PFT_PRE_FLAG_ALL_MASKED) == 0u || st.n_masked == n);
    static pft_pre_peak_t pks[PFT_PRE_MAX_PEAKS];
    size_t np = pft_pre_peaks(p, pks, PFT_PRE_MAX_PEAKS);
    FZ_CHECK(np == st.n_peaks);
    for (size_t i = 0; i < np; ++i) {
        FZ_CHECK(pks[i].x < w && pks[i].y < h && pks[i].value >= thr);
        FZ_CHECK(i == 0u || pks[i].value <= pks[i - 1u].value);
    }
    pft_frame_t out;
    FZ_CHECK(pft_pre_frame(p, &out) == PFT_OK);
    FZ_CHECK(out.format == PFT_PIX_RES16 && out.width == w && out.height == h &&
             out.data != NULL && out.stride_bytes >= 2u * (uint32_t)w);
}


#endif
