/*
 * The flat-field step's rescale (pft_pre_flat_config_t.rescale, docs/algorithms.md 9.10 [E]):
 * off by default, its workspace macro, and the known answer: a residual whose spread is
 * 0.6 .. 1.0 times the whitening's unit (a sd that falls linearly across the frame, the
 * under-dispersion that an inflated tile sigma leaves) comes out at the unit spread with
 * rescale and at its own spread without; the offset map is the same with and without it;
 * masked pixels stay masked; the multiplication's known answer for every residual value at
 * fixed multipliers; refused input leaves instance, workspace and frame unchanged.
 * 128 x 96 frames, 16 x 16 blocks, integer residuals made per pixel (every target).
 */
#include <math.h>
#include <stdio.h>
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
#define FRAMES 100
#define FIRST 60 /* frames FIRST..FRAMES are measured */
#define RESCALE_HASH 0xc67410d00b77de96u /* test_rescale_bit_exact */

static int16_t g_res[NPIX];
static int16_t g_ref[NPIX];
static uint64_t g_work[PFT_PRE_FLAT_WORKSPACE_BYTES_RESCALE(W, H, B) / 8 + 1];
static uint64_t g_work2[PFT_PRE_FLAT_WORKSPACE_BYTES_RESCALE(W, H, B) / 8 + 1];
static uint64_t g_copy[sizeof(g_work) / 8];
static uint16_t g_scale[W]; /* the residual's spread per column, Q16 (made once) */
static uint32_t g_hist[3][W / B][512]; /* |value| histograms per block column, Q8.8 / 4 bins */

static pft_frame_t res_frame(int16_t *buf, uint32_t seq)
{
    return pft_test_res16_frame(buf, W, H, seq, 0u);
}

static void init(pft_pre_flat_t *fl, void *work, size_t len, bool rescale)
{
    pft_pre_flat_config_t cfg;
    pft_pre_flat_config_default(&cfg);
    cfg.width = W;
    cfg.height = H;
    cfg.block = B;
    cfg.rescale = rescale;
    TEST_ASSERT_EQUAL(PFT_OK, pft_pre_flat_init(fl, &cfg, work, len));
}

/* 1.4826 x the median of a histogram's |value| (bins of 4 Q8.8 units), in sigma */
static double robust_sd(const uint32_t *h)
{
    uint64_t n = 0u, c = 0u;
    for (int i = 0; i < 512; ++i) {
        n += h[i];
    }
    for (int i = 0; i < 512; ++i) {
        if (2u * (c + h[i]) >= n) {
            const double f = h[i] > 0u ? (double)(n / 2u - c) / (double)h[i] : 0.0;
            return 1.4826 * 4.0 * ((double)i + f) / 256.0;
        }
        c += h[i];
    }
    return 0.0;
}

static void book(int which, const int16_t *r)
{
    for (int y = 0; y < H; ++y) {
        for (int x = 0; x < W; ++x) {
            const int v = r[y * W + x];
            if (v == PFT_RES16_MASKED) {
                continue;
            }
            int b = abs(v) / 4;
            b = b > 511 ? 511 : b;
            g_hist[which][x / B][b] += 1u;
        }
    }
}

static void test_defaults_and_workspace(void)
{
    pft_pre_flat_config_t cfg;
    pft_pre_flat_config_default(&cfg);
    TEST_ASSERT_FALSE(cfg.rescale); /* off by default */
    TEST_ASSERT_EQUAL(PFT_PRE_FLAT_WORKSPACE_BYTES(384, 288, 16), pft_pre_flat_workspace_size(&cfg));
    cfg.rescale = true;
    const size_t n = pft_pre_flat_workspace_size(&cfg);
    TEST_ASSERT_EQUAL(PFT_PRE_FLAT_WORKSPACE_BYTES_RESCALE(384, 288, 16), n);
    /* four more 4-byte values per block and a row: 16 / 256 B/px more at 16 x 16 */
    TEST_ASSERT_TRUE(n > PFT_PRE_FLAT_WORKSPACE_BYTES(384, 288, 16));
    TEST_ASSERT_TRUE(n < 384u * 288u / 5u);
    pft_pre_flat_t fl;
    TEST_ASSERT_EQUAL(PFT_ERR_NOMEM,
                      pft_pre_flat_init(&fl, &cfg, g_work, PFT_PRE_FLAT_WORKSPACE_BYTES(384, 288, 16)));
}

/*
 * The known answer. Each frame: unit noise n (pft_test_noise_q88: a sum of four uniforms,
 * Q8.8) times the column's spread s(x) = 0.6 + 0.4 x / 127, plus an offset of 0.5 sigma, a
 * masked pixel at (40, 50). The reference is the same noise unscaled (g_ref). Over frames
 * 60-100, per block column:
 * - with rescale the output's robust sd (1.4826 x median |v|, the stage's own measure of
 *   sigma, 9.6) is within 0.04 of 1. From the
 *   estimator's error: per frame a block's count below the threshold (256 pixels) has sd
 *   0.5 / 16, a Newton step on log s of sd 0.073; the running weight 0.05 keeps
 *   sqrt(0.05 / 1.95) = 0.16 of it: 0.012 per block, the column's 6 blocks average to 0.005;
 *   the bilinear multiplier between block centres of a linear s errs by under 0.001;
 *   0.04 is 3 times the one-block sd, with room for the histograms' bins (4 units in 150+);
 * - without it the output's robust sd over the reference's is the column's mean s (0.62 in
 *   the first block column), and its own robust sd far outside the bound above: the test
 *   fails if the option does nothing;
 * - the offset map (pft_pre_flat_at) is the same with and without rescale (it learns from
 *   the corrected values before the multiplication), and the masked pixel stays masked.
 */
static void test_spread_known_answer(void)
{
    pft_pre_flat_t on, off;
    init(&on, g_work, sizeof g_work, true);
    init(&off, g_work2, sizeof g_work2, false);
    for (int x = 0; x < W; ++x) {
        g_scale[x] = (uint16_t)lround((0.6 + 0.4 * x / 127.0) * 65535.0);
    }
    memset(g_hist, 0, sizeof g_hist);
    static int16_t buf_off[NPIX];
    uint32_t rs = 2463534242u;
    for (uint32_t f = 1; f <= FRAMES; ++f) {
        for (int p = 0; p < NPIX; ++p) {
            const int32_t n = pft_test_noise_q88(&rs);
            const int32_t v = (int32_t)(((int64_t)n * g_scale[p % W]) / 65536) + 128;
            g_ref[p] = (int16_t)n;
            g_res[p] = (int16_t)v;
        }
        g_res[50 * W + 40] = PFT_RES16_MASKED;
        memcpy(buf_off, g_res, sizeof g_res);
        pft_frame_t a = res_frame(g_res, f), b = res_frame(buf_off, f);
        TEST_ASSERT_EQUAL(PFT_OK, pft_pre_flat_update(&on, &a, g_res, NULL, true));
        TEST_ASSERT_EQUAL(PFT_OK, pft_pre_flat_update(&off, &b, buf_off, NULL, true));
        TEST_ASSERT_EQUAL_INT16(PFT_RES16_MASKED, g_res[50 * W + 40]);
        if (f >= FIRST) {
            book(0, g_res);
            book(1, buf_off);
            book(2, g_ref);
        }
    }
    for (uint32_t y = 0; y < H; y += 7u) {
        for (uint32_t x = 0; x < W; x += 5u) {
            TEST_ASSERT_EQUAL_INT32(pft_pre_flat_at(&off, x, y), pft_pre_flat_at(&on, x, y));
        }
    }
    for (int c = 0; c < W / B; ++c) {
        const double ref = robust_sd(g_hist[2][c]);
        const double r_on = robust_sd(g_hist[0][c]), r_off = robust_sd(g_hist[1][c]) / ref;
        double sm = 0.0;
        for (int x = c * B; x < (c + 1) * B; ++x) {
            sm += g_scale[x] / 65536.0;
        }
        sm /= B;
        char msg[160];
        snprintf(msg, sizeof msg, "block column %d: robust sd with rescale %.3f; off, over the reference's %.3f (its spread %.3f)",
                 c, r_on, r_off, sm);
        UnityPrint(msg);
        UNITY_PRINT_EOL();
        TEST_ASSERT_DOUBLE_WITHIN_MESSAGE(0.04, 1.0, r_on, msg);
        /* without the option the output keeps the input's spread (0.02: the bins, the offset) */
        TEST_ASSERT_DOUBLE_WITHIN_MESSAGE(0.02, sm, r_off, msg);
    }
}

/*
 * Bit-exact across targets: 40 frames with rescale on and learning, the outputs folded into
 * a 64-bit FNV-1a hash against a constant. The frames mix the known answer's noise with a
 * sparse set of large values (about +-20000 and +-30000: the multiplication's clamp at
 * +-32767 once the multipliers exceed 1) and masked pixels. x86-64 and AArch64 (NEON) run the
 * rescale's 16-bit product form (pre_flat.c, FL_SCALE_SPLIT_), the Cortex-M presets the 64-bit
 * product: the same constant on every preset is the proof that the two forms give the same
 * integers, half-way values and clamps included. Any change to the flat step's integers
 * changes the hash; a deliberate change regenerates the constant (the printed value) and says
 * why in its commit.
 */
static void test_rescale_bit_exact(void)
{
    pft_pre_flat_t fl;
    init(&fl, g_work, sizeof g_work, true);
    uint32_t rs = 20261206u;
    uint64_t h = 14695981039346656037u;
    uint32_t clamped = 0u, masked = 0u;
    for (uint32_t f = 1; f <= 40u; ++f) {
        for (int p = 0; p < NPIX; ++p) {
            const int32_t n = pft_test_noise_q88(&rs);
            const int32_t s = 40000 + (int32_t)((uint32_t)(p % W) * 200u);
            int32_t v = (int32_t)(((int64_t)n * s) / 65536) - 64;
            if ((rs & 511u) == 7u) {
                v = (rs & 1024u) != 0u ? 20000 + (n & 0x3FFF) / 2 : -20000 - (n & 0x3FFF) / 2;
            } else if ((rs & 1023u) == 9u) {
                v = (rs & 2048u) != 0u ? 30000 : -30000;
            } else if ((rs & 2047u) == 11u) {
                v = PFT_RES16_MASKED;
            }
            g_res[p] = (int16_t)v;
        }
        pft_frame_t a = res_frame(g_res, f);
        TEST_ASSERT_EQUAL(PFT_OK, pft_pre_flat_update(&fl, &a, g_res, NULL, true));
        for (int p = 0; p < NPIX; ++p) {
            const uint16_t u = (uint16_t)g_res[p];
            clamped += (g_res[p] == 32767 || g_res[p] == -32767) ? 1u : 0u;
            masked += g_res[p] == PFT_RES16_MASKED ? 1u : 0u;
            h = (h ^ (u & 0xFFu)) * 1099511628211u;
            h = (h ^ (u >> 8)) * 1099511628211u;
        }
    }
    char msg[120];
    snprintf(msg, sizeof msg, "hash 0x%08lx%08lx, %lu clamped, %lu masked", (unsigned long)(h >> 32),
             (unsigned long)(h & 0xFFFFFFFFu), (unsigned long)clamped, (unsigned long)masked);
    UnityPrint(msg);
    UNITY_PRINT_EOL();
    TEST_ASSERT_TRUE_MESSAGE(clamped > 0u, "the frames must reach the clamp");
    TEST_ASSERT_TRUE_MESSAGE(masked > 0u, "the frames must hold masked pixels");
    TEST_ASSERT_TRUE_MESSAGE(h == RESCALE_HASH, msg);
}

/*
 * The multiplication's known answer, every residual value: with the offset map 0 and every
 * block's multiplier q set to one value (the instance's layout, pft_pre_types.h), the
 * interpolation gives q at every pixel, and a frame without evidence must come out as
 * v q / 2^16 rounded half away from zero, clamped to +-32767 (masked pixels unchanged), for
 * every v in -32767..32767 and q at the clamps of 1/s (2^12, 2^20), about 1 and between.
 * pre_flat.c's 16-bit product form (FL_SCALE_SPLIT_: x86-64, AArch64) splits q at 2^16 and the
 * product's low part at 2^15: q = 65535, 65536, 65537 and v near +-2^15 are its edges; the
 * Cortex-M presets run the 64-bit product (fl_mulq_). Both must give these integers.
 */
static void test_multiply_known_answer(void)
{
    static const int32_t qs[] = {4096, 4097, 32767, 32768, 49151, 65535, 65536, 65537, 98304,
                                 131071, 524289, 1048575, 1048576};
    uint32_t n_clamped = 0u, n_half = 0u;
    for (size_t qi = 0u; qi < sizeof qs / sizeof qs[0]; ++qi) {
        const int32_t q = qs[qi];
        pft_pre_flat_t fl;
        init(&fl, g_work, sizeof g_work, true);
        for (uint32_t b = 0u; b < fl.nbx * fl.nby; ++b) {
            fl.sq[b] = q;
        }
        /* v = -32767 .. 32767 in frame order, a masked pixel every 997th */
        int32_t v = -32767;
        uint32_t seq = 1u;
        while (v <= 32767) {
            for (int p = 0; p < NPIX; ++p) {
                g_ref[p] = (p % 997) == 5 ? (int16_t)PFT_RES16_MASKED : (int16_t)(v <= 32767 ? v : 0);
                v += (p % 997) == 5 ? 0 : 1;
            }
            memcpy(g_res, g_ref, sizeof g_res);
            pft_frame_t a = res_frame(g_res, seq++);
            TEST_ASSERT_EQUAL(PFT_OK, pft_pre_flat_update(&fl, &a, g_res, NULL, false));
            for (int p = 0; p < NPIX; ++p) {
                int32_t want = PFT_RES16_MASKED;
                if (g_ref[p] != PFT_RES16_MASKED) {
                    const int64_t prod = (int64_t)g_ref[p] * q;
                    const int64_t mag = (prod < 0 ? -prod : prod) + 32768;
                    int64_t o = prod < 0 ? -(mag / 65536) : mag / 65536;
                    n_half += ((prod < 0 ? -prod : prod) % 65536) == 32768 ? 1u : 0u;
                    n_clamped += (o > 32767 || o < -32767) ? 1u : 0u;
                    o = o > 32767 ? 32767 : (o < -32767 ? -32767 : o);
                    want = (int32_t)o;
                }
                if (want != g_res[p]) {
                    char msg[96];
                    snprintf(msg, sizeof msg, "q %ld, v %d: %d, want %ld", (long)q, (int)g_ref[p],
                             (int)g_res[p], (long)want);
                    TEST_FAIL_MESSAGE(msg);
                }
            }
        }
    }
    TEST_ASSERT_TRUE_MESSAGE(n_clamped > 0u, "the values must reach the clamp");
    TEST_ASSERT_TRUE_MESSAGE(n_half > 0u, "the values must hold half-way products");
}

/* Refused input with rescale: nothing changes (instance, workspace, frame buffer). */
static void test_refused_input(void)
{
    pft_pre_flat_t fl;
    init(&fl, g_work, sizeof g_work, true);
    uint32_t rs = 99u;
    for (int p = 0; p < NPIX; ++p) {
        g_res[p] = (int16_t)pft_test_noise_q88(&rs);
    }
    pft_frame_t a = res_frame(g_res, 1u);
    TEST_ASSERT_EQUAL(PFT_OK, pft_pre_flat_update(&fl, &a, g_res, NULL, true));
    static unsigned char before[sizeof(pft_pre_flat_t)];
    memcpy(before, &fl, sizeof fl);
    memcpy(g_copy, g_work, sizeof g_work);
    memcpy(g_ref, g_res, sizeof g_res);
    pft_frame_t bad = pft_test_res16_frame(g_res, W - 1u, H, 2u, 0u);
    TEST_ASSERT_NOT_EQUAL(PFT_OK, pft_pre_flat_update(&fl, &bad, g_res, NULL, true));
    pft_frame_t other = res_frame(g_ref, 2u);
    TEST_ASSERT_EQUAL(PFT_ERR_INVAL, pft_pre_flat_update(&fl, &other, g_res, NULL, true));
    TEST_ASSERT_EQUAL_MEMORY(before, &fl, sizeof fl);
    TEST_ASSERT_EQUAL_MEMORY(g_copy, g_work, sizeof g_work);
    TEST_ASSERT_EQUAL_MEMORY(g_ref, g_res, sizeof g_res);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_defaults_and_workspace);
    RUN_TEST(test_spread_known_answer);
    RUN_TEST(test_rescale_bit_exact);
    RUN_TEST(test_multiply_known_answer);
    RUN_TEST(test_refused_input);
    return UNITY_END();
}
