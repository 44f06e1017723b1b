/*
 * Flat-field offset correction of the whitened residual (pft_pre.h, pft_pre_flat_*): the
 * configuration check naming the refused field, the workspace size, refused input leaving
 * instance, workspace and frame buffer byte for byte unchanged, and known answers: a
 * sensor-fixed offset plane under unit noise is learnt to within its derived error while a
 * bright blob moves across it (the gate keeps the blob out), the output is the input less the
 * offset that pft_pre_flat_at reports, masked pixels stay masked, a frame without evidence
 * is corrected but leaves the map; with relative, an offset proportional to a drifting scene's
 * level times a sensor-fixed factor is learnt to within its derived error. 128 x 96 frames, 16 x 16 blocks, integer residuals made
 * per pixel, so that it runs on every target.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "pft_test_support.h"
#include "pft/pft_pre.h"

void setUp(void) {}
void tearDown(void) {}

#define W 128
#define H 96
#define B 16
#define NPIX (W * H)

static int16_t g_res[NPIX];
static int16_t g_in[NPIX];
static uint16_t g_lev[NPIX];
static int16_t g_plane[NPIX]; /* plane(x, y) in Q8.8, made once (soft-float targets) */
static uint64_t g_work[PFT_PRE_FLAT_WORKSPACE_BYTES(W, H, PFT_PRE_FLAT_MIN_BLOCK) / 8 + 1];
static uint64_t g_copy[sizeof(g_work) / 8];
static uint32_t g_rs = 2463534242u;

/* about N(0, 1) in Q8.8: a sum of four uniforms, sd 256 */
static int32_t noise_q88(void)
{
    return pft_test_noise_q88(&g_rs);
}

/* the sensor-fixed offset plane, sigma: 0.5 at the centre, slopes 0.004 and -0.003 per px */
static double plane(int x, int y)
{
    return 0.5 + 0.004 * (x - 64) - 0.003 * (y - 48);
}

static pft_frame_t res_frame(uint32_t seq)
{
    return pft_test_res16_frame(g_res, W, H, seq, 0u);
}

/* The residual frame (seq 1) cut to w x h, rows packed. */
static pft_frame_t res_frame_wh(int w, int h)
{
    pft_frame_t f = res_frame(1u);
    f.width = (uint16_t)w;
    f.height = (uint16_t)h;
    f.stride_bytes = 2u * (uint32_t)w;
    return f;
}

/* A w x h level frame over data, rows packed, U8 (u8) or U16. */
static pft_frame_t lev_frame(const void *data, bool u8, int w, int h)
{
    pft_frame_t lev;
    memset(&lev, 0, sizeof lev);
    lev.data = data;
    lev.width = (uint16_t)w;
    lev.height = (uint16_t)h;
    lev.stride_bytes = (u8 ? 1u : 2u) * (uint32_t)w;
    lev.format = u8 ? PFT_PIX_U8 : PFT_PIX_U16;
    return lev;
}

static void init_flat(pft_pre_flat_t *fl)
{
    pft_pre_flat_config_t cfg;
    pft_pre_flat_config_default(&cfg);
    cfg.width = W;
    cfg.height = H;
    cfg.block = B;
    TEST_ASSERT_EQUAL(PFT_OK, pft_pre_flat_init(fl, &cfg, g_work, sizeof g_work));
}

/* frame k: plane + unit noise + a 3 x 3 blob of 6 sigma at (20 + k / 4, 40) (0.25 px per
 * frame: it stays about 64 frames in each block it crosses), into g_res and g_in */
static void make_frame(int k)
{
    const int bx = 20 + k / 4, by = 40;
    if (g_plane[0] == 0) {
        for (int y = 0; y < H; ++y) {
            for (int x = 0; x < W; ++x) {
                g_plane[y * W + x] = (int16_t)lround(256.0 * plane(x, y));
            }
        }
    }
    for (int y = 0; y < H; ++y) {
        for (int x = 0; x < W; ++x) {
            int32_t v = (int32_t)g_plane[y * W + x] + noise_q88();
            if (abs(x - bx) <= 1 && abs(y - by) <= 1) {
                v += 6 * 256;
            }
            g_res[y * W + x] = (int16_t)v;
        }
    }
    memcpy(g_in, g_res, sizeof g_res);
}

static void test_config(void)
{
    pft_pre_flat_config_t cfg;
    const char *field = "x";
    pft_pre_flat_config_default(&cfg);
    TEST_ASSERT_EQUAL(PFT_OK, pft_pre_flat_config_check(&cfg, &field));
    TEST_ASSERT_NULL(field);
    TEST_ASSERT_EQUAL(PFT_ERR_INVAL, pft_pre_flat_config_check(NULL, &field));
    const struct {
        uint8_t block;
        uint16_t alpha, gate;
        const char *name;
    } bad[] = {{2u, 3277u, 512u, "block"},  {12u, 3277u, 512u, "block"},
               {128u, 3277u, 512u, "block"}, {16u, 0u, 512u, "alpha"},
               {16u, 3277u, 0u, "gate"},     {16u, 3277u, 40000u, "gate"}};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
        pft_pre_flat_config_default(&cfg);
        cfg.block = bad[i].block;
        cfg.alpha = bad[i].alpha;
        cfg.gate = bad[i].gate;
        TEST_ASSERT_EQUAL(PFT_ERR_CONFIG, pft_pre_flat_config_check(&cfg, &field));
        TEST_ASSERT_EQUAL_STRING(bad[i].name, field);
        TEST_ASSERT_EQUAL(0u, pft_pre_flat_workspace_size(&cfg));
    }
    pft_pre_flat_config_default(&cfg);
    cfg.width = 4u;
    TEST_ASSERT_EQUAL(PFT_ERR_CONFIG, pft_pre_flat_config_check(&cfg, &field));
    TEST_ASSERT_EQUAL_STRING("width", field);
    /* 384 x 288, 16 x 16 blocks: 24 x 18 blocks of 12 bytes and a row of 24 values, well
     * under 1 byte per pixel */
    pft_pre_flat_config_default(&cfg);
    const size_t n = pft_pre_flat_workspace_size(&cfg);
    TEST_ASSERT_EQUAL(PFT_PRE_FLAT_WORKSPACE_BYTES(384, 288, 16), n);
    TEST_ASSERT_TRUE(n < 384u * 288u / 10u);
    pft_pre_flat_t fl;
    TEST_ASSERT_EQUAL(PFT_ERR_NOMEM, pft_pre_flat_init(&fl, &cfg, g_work, 64u));
}

/* The known answer: after 200 frames the map equals the plane. Tolerance 0.05 sigma, from the
 * map's error: a block's mean of the gated noise per frame has sd 0.88 / sqrt(244) = 0.056
 * (244 of 256 pixels within +-2 sigma, truncated sd 0.88), the running mean with alpha 0.05
 * keeps sqrt(0.05 / 1.95) = 0.16 of it: 0.009 sigma; an interpolated value is a convex mix of
 * block values (sd <= 0.009); the plane is linear, so its block means are its values at the
 * block centres and the bilinear interpolation between centres is exact (Q8.8 rounding:
 * 0.004). 0.05 is 5 sd, for 48 blocks. The blob, 6 sigma over 9 px, would add 0.21 sigma to
 * the mean of a block it sits in if it entered (its 64 frames there are about 3 time
 * constants of the running mean): the gate keeps it out. */
static void test_plane_learnt_blob_kept_out(void)
{
    pft_pre_flat_t fl;
    init_flat(&fl);
    for (int k = 0; k < 200; ++k) {
        make_frame(k);
        pft_frame_t f = res_frame((uint32_t)k + 1u);
        /* the output is the input less the offset pft_pre_flat_at reports before the update */
        const int32_t off = pft_pre_flat_at(&fl, 77u, 13u);
        TEST_ASSERT_EQUAL(PFT_OK, pft_pre_flat_update(&fl, &f, g_res, NULL, true));
        TEST_ASSERT_EQUAL_INT32(g_in[13 * W + 77] - off, g_res[13 * W + 77]);
    }
    double worst = 0.0;
    for (int y = B / 2; y < H - B / 2; ++y) {
        for (int x = B / 2; x < W - B / 2; ++x) {
            const double e = pft_pre_flat_at(&fl, (uint32_t)x, (uint32_t)y) / 256.0 - plane(x, y);
            worst = fabs(e) > worst ? fabs(e) : worst;
        }
    }
    TEST_ASSERT_DOUBLE_WITHIN(0.05, 0.0, worst);
    /* the blob comes out at its value: 6 sigma over the corrected noise (+-4 sigma of noise
     * at most for a sum of four uniforms: 3.46 sigma) */
    const int bx = 20 + 199 / 4;
    TEST_ASSERT_TRUE(g_res[40 * W + bx] > (int16_t)(2 * 256));
    /* outside the centres the map is held: pixel (0, 0) reads the corner block's value */
    TEST_ASSERT_EQUAL_INT32(pft_pre_flat_at(&fl, 7u, 7u), pft_pre_flat_at(&fl, 0u, 0u));
    TEST_ASSERT_EQUAL_INT32(0, pft_pre_flat_at(&fl, W, 0u));
}

/* relative: the sensor-fixed factor, sigma per count, and the drifting scene, counts */
static double kfac(int x, int y)
{
    return 1e-4 + 4e-7 * (x - 64) - 3e-7 * (y - 48);
}

static double scene(int x, int y, int k)
{
    return 3000.0 + 1000.0 * sin(6.2832 * (x + 0.3 * k) / 200.0) * cos(6.2832 * (y + 0.1 * k) / 150.0);
}

/* The relative known answer: residual kfac(x, y) scene(x, y, k) + unit noise, level frame the
 * scene: after 200 frames the map (sigma per count Q24) equals kfac. Tolerance: 0.05 sigma of
 * offset at the pixel's level, |m - kfac| scene <= 0.05, from the map's error: a block's ratio
 * sum(v) / sum(l) per frame has sd 0.056 / l_mean sigma per count (the noise of the offset
 * mode's mean over the block's mean level), the running mean keeps 0.16 of it: 0.009 sigma at
 * the block's level; the level varies by at most 8 % over a block (a gradient of at most 31
 * counts per px), so the ratio of sums weighs kfac by at most a 0.2 px shift of the block's
 * centre (8e-8 sigma per count: 0.0003 sigma), and kfac is linear (bilinear interpolation
 * exact); 0.05 is 5 sd. */
static void test_relative_learnt(void)
{
    pft_pre_flat_config_t cfg;
    pft_pre_flat_config_default(&cfg);
    cfg.width = W;
    cfg.height = H;
    cfg.block = B;
    cfg.relative = true;
    pft_pre_flat_t fl;
    TEST_ASSERT_EQUAL(PFT_OK, pft_pre_flat_init(&fl, &cfg, g_work, sizeof g_work));
    pft_frame_t lev;
    memset(&lev, 0, sizeof lev);
    lev.data = g_lev;
    lev.width = W;
    lev.height = H;
    lev.stride_bytes = 2u * W;
    lev.format = PFT_PIX_U16;
    lev.bit_depth = 14u;
    pft_frame_t f = res_frame(1u);
    TEST_ASSERT_EQUAL(PFT_ERR_INVAL, pft_pre_flat_update(&fl, &f, g_res, NULL, true));
    /* kfac in sigma per count Q24, and the scene's separable factors per frame, as integers
     * (the frames are made in integer arithmetic: soft-float targets under QEMU) */
    static int32_t kq[NPIX];
    static int32_t sx[W], cy[H];
    for (int y = 0; y < H; ++y) {
        for (int x = 0; x < W; ++x) {
            kq[y * W + x] = (int32_t)lround(16777216.0 * kfac(x, y));
        }
    }
    for (int k = 0; k < 200; ++k) {
        for (int x = 0; x < W; ++x) {
            sx[x] = (int32_t)lround(1000.0 * sin(6.2832 * (x + 0.3 * k) / 200.0));
        }
        for (int y = 0; y < H; ++y) {
            cy[y] = (int32_t)lround(1024.0 * cos(6.2832 * (y + 0.1 * k) / 150.0));
        }
        for (int y = 0; y < H; ++y) {
            for (int x = 0; x < W; ++x) {
                const int32_t l = 3000 + sx[x] * cy[y] / 1024; /* scene(x, y, k) within 1 count */
                g_lev[y * W + x] = (uint16_t)l;
                g_res[y * W + x] = (int16_t)((kq[y * W + x] * l + 32768) / 65536 + noise_q88());
            }
        }
        f = res_frame((uint32_t)k + 1u);
        TEST_ASSERT_EQUAL(PFT_OK, pft_pre_flat_update(&fl, &f, g_res, &lev, true));
    }
    double worst = 0.0;
    for (int y = B / 2; y < H - B / 2; ++y) {
        for (int x = B / 2; x < W - B / 2; ++x) {
            const double m = pft_pre_flat_at(&fl, (uint32_t)x, (uint32_t)y) / 16777216.0;
            const double e = fabs(m - kfac(x, y)) * scene(x, y, 199);
            worst = e > worst ? e : worst;
        }
    }
    TEST_ASSERT_DOUBLE_WITHIN(0.05, 0.0, worst);
}

/* Masked pixels stay masked; a frame without evidence is corrected and leaves the map. */
static void test_masked_and_no_evidence(void)
{
    pft_pre_flat_t fl;
    init_flat(&fl);
    for (int k = 0; k < 30; ++k) {
        make_frame(k);
        pft_frame_t f = res_frame((uint32_t)k + 1u);
        TEST_ASSERT_EQUAL(PFT_OK, pft_pre_flat_update(&fl, &f, g_res, NULL, true));
    }
    make_frame(30);
    g_res[5 * W + 9] = (int16_t)PFT_RES16_MASKED;
    memcpy(g_in, g_res, sizeof g_res);
    memcpy(g_copy, g_work, sizeof g_work);
    const int32_t off = pft_pre_flat_at(&fl, 50u, 50u);
    TEST_ASSERT_TRUE(off > 64); /* about 0.5 sigma learnt by now */
    pft_frame_t f = res_frame(31u);
    TEST_ASSERT_EQUAL(PFT_OK, pft_pre_flat_update(&fl, &f, g_res, NULL, false));
    TEST_ASSERT_EQUAL_INT16((int16_t)PFT_RES16_MASKED, g_res[5 * W + 9]);
    TEST_ASSERT_EQUAL_INT32(g_in[50 * W + 50] - off, g_res[50 * W + 50]);
    /* the map (first part of the workspace after alignment) is unchanged: the offset too */
    TEST_ASSERT_EQUAL_INT32(off, pft_pre_flat_at(&fl, 50u, 50u));
    TEST_ASSERT_EQUAL(PFT_OK, pft_pre_flat_reset(&fl));
    TEST_ASSERT_EQUAL_INT32(0, pft_pre_flat_at(&fl, 50u, 50u));
}

/* The sums a learning update books (fl->sum, cnt, lsum per block, this frame's), from the
 * input g_in and the output g_res of a w-wide frame: every unmasked pixel whose corrected
 * value o lies within +-gate, o and (relative) its level into its block. */
static void check_sums(const pft_pre_flat_t *fl, int w, int h, const uint16_t *lev16,
                       const uint8_t *lev8)
{
    static int32_t sum[1024];
    static uint32_t cnt[1024], lsum[1024];
    const uint32_t nb = fl->nbx * fl->nby, b = fl->cfg.block;
    TEST_ASSERT_TRUE(nb <= 1024u);
    memset(sum, 0, sizeof sum);
    memset(cnt, 0, sizeof cnt);
    memset(lsum, 0, sizeof lsum);
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const int i = y * w + x;
            const int32_t o = g_res[i];
            if (g_in[i] == PFT_RES16_MASKED || o > (int32_t)fl->cfg.gate || o < -(int32_t)fl->cfg.gate) {
                continue;
            }
            const uint32_t k = ((uint32_t)y / b) * fl->nbx + (uint32_t)x / b;
            sum[k] += o;
            cnt[k] += 1u;
            lsum[k] += lev16 != NULL ? lev16[i] : (lev8 != NULL ? lev8[i] : 0u);
        }
    }
    for (uint32_t k = 0u; k < nb; ++k) {
        TEST_ASSERT_EQUAL_INT32(sum[k], fl->sum[k]);
        TEST_ASSERT_EQUAL_UINT32(cnt[k], fl->cnt[k]);
        TEST_ASSERT_EQUAL_UINT32(lsum[k], fl->lsum[k]);
    }
}

/* Every pixel of one update against the per-pixel definition: the output is r less the
 * offset pft_pre_flat_at reports at (x, y) (offset form: Q8.8; relative: the factor, Q24,
 * times the level, rounded half away from zero), clamped to +-32767; masked pixels stay
 * masked. A frame of 123 x 90 (not whole blocks), blocks 4, 16 and 64, the offset form and
 * the relative form with U16 and U8 levels, a map of random values up to the clamp set
 * through the instance's layout (pft_pre_types.h), random residuals (some masked, some at
 * +-32767) and levels. Exact: the update and pft_pre_flat_at compute the same integers (the
 * update steps the interpolation along the row, pft_pre_flat_at computes it per pixel), so
 * the tolerance is 0. */
static void test_every_pixel_against_at(void)
{
    static const uint8_t blocks[3] = {4u, 16u, 64u};
    static uint8_t lev8[NPIX];
    const int w = 123, h = 90;
    for (int bi = 0; bi < 3; ++bi) {
        for (int form = 0; form < 3; ++form) { /* 0 offset, 1 relative U16, 2 relative U8 */
            pft_pre_flat_config_t cfg;
            pft_pre_flat_config_default(&cfg);
            cfg.width = (uint16_t)w;
            cfg.height = (uint16_t)h;
            cfg.block = blocks[bi];
            cfg.relative = form != 0;
            pft_pre_flat_t fl;
            TEST_ASSERT_EQUAL(PFT_OK, pft_pre_flat_init(&fl, &cfg, g_work, sizeof g_work));
            const uint32_t nb = fl.nbx * fl.nby;
            for (uint32_t i = 0u; i < nb; ++i) {
                (void)pft_test_xorshift32(&g_rs);
                fl.m[i] = (int32_t)(g_rs % 1048577u) - 524288; /* +-8 sigma (Q16), +-2^19 */
            }
            for (int i = 0; i < w * h; ++i) {
                (void)pft_test_xorshift32(&g_rs);
                int32_t v = (int32_t)(g_rs % 8193u) - 4096;
                v = (g_rs >> 24) == 0u ? PFT_RES16_MASKED : v;
                v = (g_rs >> 24) == 1u ? 32767 : ((g_rs >> 24) == 2u ? -32767 : v);
                g_res[i] = (int16_t)v;
                g_lev[i] = (uint16_t)(g_rs >> 8);
                lev8[i] = (uint8_t)(g_rs >> 13);
            }
            memcpy(g_in, g_res, sizeof g_res);
            pft_frame_t f = res_frame_wh(w, h);
            pft_frame_t lev = lev_frame(form == 2 ? (const void *)lev8 : (const void *)g_lev, form == 2, w, h);
            static int32_t want[NPIX];
            for (int y = 0; y < h; ++y) {
                for (int x = 0; x < w; ++x) {
                    const int i = y * w + x;
                    const int32_t a = pft_pre_flat_at(&fl, (uint32_t)x, (uint32_t)y);
                    int64_t off = a;
                    if (form != 0) {
                        const int64_t q = (int64_t)a * (form == 2 ? lev8[i] : g_lev[i]);
                        const int64_t mag = (q < 0 ? -q : q) + 32768;
                        off = q < 0 ? -(mag / 65536) : mag / 65536;
                    }
                    int64_t o = (int64_t)g_in[i] - off;
                    o = o > 32767 ? 32767 : (o < -32767 ? -32767 : o);
                    want[i] = g_in[i] == PFT_RES16_MASKED ? PFT_RES16_MASKED : (int32_t)o;
                }
            }
            TEST_ASSERT_EQUAL(PFT_OK, pft_pre_flat_update(&fl, &f, g_res, form != 0 ? &lev : NULL, true));
            for (int i = 0; i < w * h; ++i) {
                TEST_ASSERT_EQUAL_INT32(want[i], g_res[i]);
            }
            check_sums(&fl, w, h, form == 1 ? g_lev : NULL, form == 2 ? lev8 : NULL);
        }
    }
}

/* Known answers of the relative form with a 16-bit level row (on AArch64 its spans take 8
 * pixels at a time in NEON's forms, the rest per pixel; elsewhere the plain or SSE2 loop):
 * every block's factor set to one value k (the interpolation is then k at every pixel) for 22
 * values of k over -2^19 .. 2^19 (0, +-1, +-32768, +-65535, +-65536, +-3 2^15 among them) and
 * levels l from a list of edge values (0, 1, 32767, 32768, 65535, ...) and random ones, so that
 * the product k l / 2^16 is rounded half away from zero at exact halves of both signs (counted)
 * and the clamp at +-32767 occurs; each pixel's output and each block's sums against the
 * integers computed here. Widths 128 (spans of 8 and 16 pixels: whole groups of 8) and 123 (a
 * last span of 11: the per-pixel rest), blocks 16 and 32. */
static void test_relative_u16_known_answer(void)
{
    static const int32_t ks[22] = {0, 1, -1, 32768, -32768, 65535, -65535, 65536, -65536,
                                   98304, -98304, 12345, -12345, 131071, -131073, 300001,
                                   -300001, 524287, -524287, 524288, -524288, -2};
    static const uint16_t ls[10] = {0u, 1u, 2u, 3u, 32767u, 32768u, 32769u, 65534u, 65535u, 4096u};
    static const int ws[2] = {128, 123};
    static const uint8_t bs[2] = {16u, 32u};
    const int h = 16;
    uint32_t halves_neg = 0u, halves_pos = 0u, clamped = 0u;
    for (int c = 0; c < 2; ++c) {
        const int w = ws[c];
        pft_pre_flat_config_t cfg;
        pft_pre_flat_config_default(&cfg);
        cfg.width = (uint16_t)w;
        cfg.height = (uint16_t)h;
        cfg.block = bs[c];
        cfg.relative = true;
        for (int ki = 0; ki < 22; ++ki) {
            pft_pre_flat_t fl;
            TEST_ASSERT_EQUAL(PFT_OK, pft_pre_flat_init(&fl, &cfg, g_work, sizeof g_work));
            const int32_t kv = ks[ki];
            for (uint32_t i = 0u; i < fl.nbx * fl.nby; ++i) {
                fl.m[i] = kv;
            }
            for (int i = 0; i < w * h; ++i) {
                (void)pft_test_xorshift32(&g_rs);
                int32_t v = (int32_t)(g_rs % 2049u) - 1024;
                v = (g_rs >> 26) == 0u ? PFT_RES16_MASKED : v;
                v = (g_rs >> 26) == 1u ? 32767 : ((g_rs >> 26) == 2u ? -32767 : v);
                g_res[i] = (int16_t)v;
                g_lev[i] = (i % 3) == 0 ? ls[(i / 3) % 10] : (uint16_t)(g_rs >> 7);
            }
            memcpy(g_in, g_res, sizeof g_res);
            static int32_t want[NPIX];
            for (int i = 0; i < w * h; ++i) {
                const int64_t q = (int64_t)kv * g_lev[i];
                const int64_t mag = (q < 0 ? -q : q) + 32768;
                const int64_t off = q < 0 ? -(mag / 65536) : mag / 65536;
                if ((q < 0 ? -q : q) % 65536 == 32768) {
                    halves_neg += q < 0 ? 1u : 0u;
                    halves_pos += q > 0 ? 1u : 0u;
                }
                int64_t o = (int64_t)g_in[i] - off;
                const bool masked = g_in[i] == PFT_RES16_MASKED;
                clamped += !masked && (o > 32767 || o < -32767) ? 1u : 0u;
                o = o > 32767 ? 32767 : (o < -32767 ? -32767 : o);
                want[i] = masked ? PFT_RES16_MASKED : (int32_t)o;
            }
            pft_frame_t f = res_frame_wh(w, h);
            pft_frame_t lev = lev_frame(g_lev, false, w, h);
            TEST_ASSERT_EQUAL(PFT_OK, pft_pre_flat_update(&fl, &f, g_res, &lev, true));
            for (int i = 0; i < w * h; ++i) {
                TEST_ASSERT_EQUAL_INT32(want[i], g_res[i]);
            }
            check_sums(&fl, w, h, g_lev, NULL);
        }
    }
    TEST_ASSERT_TRUE(halves_neg > 100u);
    TEST_ASSERT_TRUE(halves_pos > 100u);
    TEST_ASSERT_TRUE(clamped > 1000u);
}

/* The gate's edges in the relative form with a 16-bit level row (on x86-64 its SSE2 form tests
 * |o| > gate as one wrapped 16-bit compare, o + gate - 32768 > 2 gate - 32768, and the count
 * from the pixels out of the gate or masked): a map of 0, so that every offset is 0 and o = v;
 * residuals gate - 1, gate, gate + 1 and their negatives, +-32767, 0 and masked pixels over
 * levels 0 .. 65535; gates 1, 512, 16384 and 32767 (2 gate - 32768 at both ends of the 16-bit
 * range); each pixel unchanged, and each block's sums against those counted here (check_sums),
 * with pixels both within and out of the gate (gate 32767: every unmasked pixel within). */
static void test_relative_u16_gate_edges(void)
{
    static const uint16_t gates[4] = {1u, 512u, 16384u, 32767u};
    const int w = 64, h = 16;
    for (int gi = 0; gi < 4; ++gi) {
        pft_pre_flat_config_t cfg;
        pft_pre_flat_config_default(&cfg);
        cfg.width = (uint16_t)w;
        cfg.height = (uint16_t)h;
        cfg.block = 16u;
        cfg.relative = true;
        cfg.gate = gates[gi];
        pft_pre_flat_t fl;
        TEST_ASSERT_EQUAL(PFT_OK, pft_pre_flat_init(&fl, &cfg, g_work, sizeof g_work));
        const int32_t g = (int32_t)gates[gi];
        const int32_t vals[10] = {g - 1, g, g + 1, 1 - g, -g, -g - 1, 32767, -32767, 0,
                                  PFT_RES16_MASKED};
        uint32_t in = 0u, out = 0u;
        for (int i = 0; i < w * h; ++i) {
            int32_t v = vals[(i * 7 + i / w) % 10];
            v = v > 32767 ? 32767 : v;
            g_res[i] = (int16_t)v;
            g_lev[i] = (uint16_t)((uint32_t)i * 1031u);
            if (v != PFT_RES16_MASKED) {
                in += (v <= g && v >= -g) ? 1u : 0u;
                out += (v > g || v < -g) ? 1u : 0u;
            }
        }
        TEST_ASSERT_TRUE(in > 100u && (g < 32767 ? out > 100u : out == 0u)); /* 32767: all in */
        memcpy(g_in, g_res, sizeof g_res);
        pft_frame_t f = res_frame_wh(w, h);
        pft_frame_t lev = lev_frame(g_lev, false, w, h);
        TEST_ASSERT_EQUAL(PFT_OK, pft_pre_flat_update(&fl, &f, g_res, &lev, true));
        for (int i = 0; i < w * h; ++i) {
            TEST_ASSERT_EQUAL_INT16(g_in[i], g_res[i]);
        }
        uint32_t cnt = 0u;
        for (uint32_t k = 0u; k < fl.nbx * fl.nby; ++k) {
            cnt += fl.cnt[k];
        }
        TEST_ASSERT_EQUAL_UINT32(in, cnt);
        check_sums(&fl, w, h, g_lev, NULL);
    }
}

/* Refused input: NULL, a foreign buffer, a wrong frame: nothing changes. */
static void test_refused_input(void)
{
    pft_pre_flat_t fl;
    init_flat(&fl);
    for (int k = 0; k < 5; ++k) {
        make_frame(k);
        pft_frame_t f = res_frame((uint32_t)k + 1u);
        TEST_ASSERT_EQUAL(PFT_OK, pft_pre_flat_update(&fl, &f, g_res, NULL, true));
    }
    make_frame(5);
    pft_pre_flat_t inst = fl;
    memcpy(g_copy, g_work, sizeof g_work);
    pft_frame_t f = res_frame(6u);
    TEST_ASSERT_EQUAL(PFT_ERR_INVAL, pft_pre_flat_update(NULL, &f, g_res, NULL, true));
    TEST_ASSERT_EQUAL(PFT_ERR_INVAL, pft_pre_flat_update(&fl, NULL, g_res, NULL, true));
    TEST_ASSERT_EQUAL(PFT_ERR_INVAL, pft_pre_flat_update(&fl, &f, NULL, NULL, true));
    TEST_ASSERT_EQUAL(PFT_ERR_INVAL, pft_pre_flat_update(&fl, &f, g_in, NULL, true));
    f.width = W - 1;
    TEST_ASSERT_EQUAL(PFT_ERR_FORMAT, pft_pre_flat_update(&fl, &f, g_res, NULL, true));
    f = res_frame(6u);
    f.format = PFT_PIX_U16;
    TEST_ASSERT_EQUAL(PFT_ERR_FORMAT, pft_pre_flat_update(&fl, &f, g_res, NULL, true));
    /* an odd stride puts rows of int16 at odd addresses: refused, the buffer unchanged (was
     * accepted and read misaligned before the fuzz finding F9, docs/reliability.md) */
    static int16_t odd[NPIX + H];
    memcpy(odd, g_in, sizeof g_in);
    f = res_frame(6u);
    f.data = odd;
    f.stride_bytes = 2u * W + 1u;
    TEST_ASSERT_EQUAL(PFT_ERR_FORMAT, pft_pre_flat_update(&fl, &f, odd, NULL, true));
    TEST_ASSERT_EQUAL_MEMORY(g_in, odd, sizeof g_in);
    TEST_ASSERT_EQUAL_MEMORY(&inst, &fl, sizeof fl);
    TEST_ASSERT_EQUAL_MEMORY(g_copy, g_work, sizeof g_work);
    TEST_ASSERT_EQUAL_MEMORY(g_in, g_res, sizeof g_res);
    TEST_ASSERT_EQUAL(PFT_ERR_INVAL, pft_pre_flat_reset(NULL));
    TEST_ASSERT_EQUAL_INT32(0, pft_pre_flat_at(NULL, 0u, 0u));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_config);
    RUN_TEST(test_plane_learnt_blob_kept_out);
    RUN_TEST(test_relative_learnt);
    RUN_TEST(test_masked_and_no_evidence);
    RUN_TEST(test_every_pixel_against_at);
    RUN_TEST(test_relative_u16_known_answer);
    RUN_TEST(test_relative_u16_gate_edges);
    RUN_TEST(test_refused_input);
    return UNITY_END();
}
