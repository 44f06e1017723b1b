/*
 * The clutter map held in 8 bits per pixel (pft_pre_clutter_config_t.map8, pft_pre.h "8-bit
 * map"; docs/algorithms.md 9.9): the code's known answers, its round trip (every code decodes
 * to a value that encodes back to it, with any rounding offset) and its error bound (every
 * Q6.10 value v within max(8, v / 64) of its nearest code's value); the dither's expectation
 * (over the 256 offsets, within 1/256 of a step of v); the configuration (map8 with block
 * refused, named "map8"; the workspace PFT_PRE_CLUTTER_WORKSPACE_BYTES_MAP8, W H - 12 W bytes
 * less than the 16-bit map's at blur 1); a persistent blob learnt at the documented rate and a
 * constant residual learnt in expectation (the dither's point: with the nearest code the map
 * would stop about 10 % short); the 8-bit map against the 16-bit one on drifting noise; the
 * raise; a refused call changes nothing; the update with a shift (the warp fused with it, row
 * by row) bit for bit against a plain reference, shifts of both signs, whole and fractional. 64 x 48 frames, integer residuals: every target.
 * The code functions are internal to the library (lib/src/pre/pre_int.h); the test declares
 * them itself.
 */
#include <math.h>
#include <string.h>

#include "pft_test_support.h"
#include "pft/pft_pre.h"

uint32_t pft_pre_clutter_enc8_(uint32_t v, uint32_t dz);
uint32_t pft_pre_clutter_dec8_(uint32_t c);
uint32_t pft_pre_sqrt_q10_(uint32_t mm);

void setUp(void) {}
void tearDown(void) {}

#define W 64
#define H 48
#define NPIX (W * H)

static int16_t g_res[NPIX];
static uint64_t g_work[PFT_PRE_CLUTTER_WORKSPACE_BYTES(W, H, 1, PFT_PRE_CLUTTER_MAX_BLUR, 1) / 8 + 1];
static uint64_t g_work2[sizeof(g_work) / 8];
static uint64_t g_copy[sizeof(g_work) / 8];
static uint32_t g_rs = 7654321u;

static pft_frame_t res_frame(uint32_t seq)
{
    return pft_test_res16_frame(g_res, W, H, seq, 0u);
}

/* the step of the code around v (Q6.10): 16 below 1024, else 2^(e + 3) for 2^(e + 8) <= v */
static uint32_t step_of(uint32_t v)
{
    uint32_t s = 16u;
    for (uint32_t lo = 1024u; lo <= v && lo <= 32768u; lo *= 2u) {
        s *= 2u;
    }
    return s;
}

static void test_code_known_answers_and_round_trip(void)
{
    TEST_ASSERT_EQUAL_UINT32(0u, pft_pre_clutter_dec8_(0u));
    TEST_ASSERT_EQUAL_UINT32(512u, pft_pre_clutter_dec8_(32u));
    TEST_ASSERT_EQUAL_UINT32(1024u, pft_pre_clutter_dec8_(64u)); /* 1 sigma^2 exactly */
    TEST_ASSERT_EQUAL_UINT32(2048u, pft_pre_clutter_dec8_(96u));
    TEST_ASSERT_EQUAL_UINT32(8192u, pft_pre_clutter_dec8_(160u));
    TEST_ASSERT_EQUAL_UINT32(16384u, pft_pre_clutter_dec8_(192u)); /* the raise's 16 sigma^2 */
    TEST_ASSERT_EQUAL_UINT32(64512u, pft_pre_clutter_dec8_(255u)); /* 63 sigma^2, the largest */
    TEST_ASSERT_EQUAL_UINT32(64u, pft_pre_clutter_enc8_(1024u, 128u));
    TEST_ASSERT_EQUAL_UINT32(65u, pft_pre_clutter_enc8_(1040u, 128u)); /* 1040 + 16 = 33 steps of 32 */
    TEST_ASSERT_EQUAL_UINT32(64u, pft_pre_clutter_enc8_(1039u, 128u));
    TEST_ASSERT_EQUAL_UINT32(64u, pft_pre_clutter_enc8_(1016u, 128u)); /* 1016 + 8 = 64 steps of 16 */
    TEST_ASSERT_EQUAL_UINT32(255u, pft_pre_clutter_enc8_(65535u, 128u));
    TEST_ASSERT_EQUAL_UINT32(255u, pft_pre_clutter_enc8_(65535u, 0u));
    TEST_ASSERT_EQUAL_UINT32(0u, pft_pre_clutter_enc8_(7u, 128u));
    TEST_ASSERT_EQUAL_UINT32(1u, pft_pre_clutter_enc8_(8u, 128u));
    uint32_t prev = 0u;
    for (uint32_t c = 0u; c < 256u; ++c) {
        const uint32_t v = pft_pre_clutter_dec8_(c);
        if (c > 0u) {
            TEST_ASSERT_TRUE(v > prev); /* strictly increasing */
        }
        prev = v;
        for (uint32_t dz = 0u; dz < 256u; ++dz) {
            TEST_ASSERT_EQUAL_UINT32(c, pft_pre_clutter_enc8_(v, dz));
        }
    }
}

/* The code's definition written plainly (pft_pre_clutter.c: c = 32 (e - 1) + floor((v + d) /
 * 2^(e + 3)), d = floor(dz 2^(e + 3) / 256), v clamped to 64512; the value 16 c below 64, else
 * (32 + c mod 32) 2^(c / 32 + 3)): the library's 16-bit-lane arithmetic gives exactly these codes
 * and values, for every value with eight offsets and every offset on a stride of values. */
static uint32_t ref_enc(uint32_t v0, uint32_t dz)
{
    const uint32_t v = v0 > 64512u ? 64512u : v0;
    const uint32_t s = step_of(v);
    uint32_t base = 0u;
    for (uint32_t t = 16u; t < s; t *= 2u) {
        base += 32u;
    }
    return base + (v + (dz * s) / 256u) / s;
}

static void test_code_against_definition(void)
{
    for (uint32_t c = 0u; c < 256u; ++c) {
        const uint32_t ref = c < 64u ? 16u * c : (32u + c % 32u) << (c / 32u + 3u);
        TEST_ASSERT_EQUAL_UINT32(ref, pft_pre_clutter_dec8_(c));
    }
    static const uint32_t dzs[8] = {0u, 1u, 64u, 127u, 128u, 129u, 200u, 255u};
    uint32_t bad = 0u;
    for (uint32_t v = 0u; v <= 65535u; ++v) {
        for (uint32_t k = 0u; k < 8u; ++k) {
            bad += pft_pre_clutter_enc8_(v, dzs[k]) != ref_enc(v, dzs[k]) ? 1u : 0u;
        }
    }
    for (uint32_t v = 0u; v <= 65535u; v += 53u) {
        for (uint32_t dz = 0u; dz < 256u; ++dz) {
            bad += pft_pre_clutter_enc8_(v, dz) != ref_enc(v, dz) ? 1u : 0u;
        }
    }
    TEST_ASSERT_EQUAL_UINT32(0u, bad);
}

static void test_code_error_bound_every_value(void)
{
    uint32_t bad = 0u, worst_v = 0u;
    double worst = 0.0;
    for (uint32_t v = 0u; v <= 65535u; ++v) {
        const double err = fabs((double)pft_pre_clutter_dec8_(pft_pre_clutter_enc8_(v, 128u)) - (double)v);
        /* the bound of pft_pre.h: half a step, 8 below 1024 and v / 64 above (the clamp at code
         * 255 included: 65535 - 64512 = 1023 <= 65535 / 64) */
        const double bound = v < 512u ? 8.0 : (double)v / 64.0;
        if (err > bound) {
            ++bad;
        }
        if (err / (v < 512u ? 512.0 : (double)v) > worst) {
            worst = err / (v < 512u ? 512.0 : (double)v);
            worst_v = v;
        }
    }
    TEST_ASSERT_EQUAL_UINT32(0u, bad);
    TEST_ASSERT_TRUE(worst <= 1.0 / 64.0);
    TEST_ASSERT_TRUE(worst_v > 0u);
}

static void test_dither_expectation(void)
{
    for (uint32_t v = 0u; v < 64512u; v += 37u) {
        double sum = 0.0;
        for (uint32_t dz = 0u; dz < 256u; ++dz) {
            sum += (double)pft_pre_clutter_dec8_(pft_pre_clutter_enc8_(v, dz));
        }
        /* floor((v + d) / s) over d = floor(dz s / 256): the mean of the decoded values is v
         * within s / 256 (the offsets are uniform in steps of s / 256, or exactly s / 16 ones
         * when s = 16) */
        const double s = (double)step_of(v);
        TEST_ASSERT_DOUBLE_WITHIN(s / 256.0 + 1e-9, (double)v, sum / 256.0);
    }
}

static void test_config_and_workspace(void)
{
    pft_pre_clutter_config_t cfg;
    pft_pre_clutter_config_default(&cfg);
    TEST_ASSERT_FALSE(cfg.map8);
    cfg.width = W;
    cfg.height = H;
    cfg.map8 = true;
    for (uint8_t k = 2u; k <= 4u; k = (uint8_t)(k + 2u)) {
        pft_pre_clutter_config_t b = cfg;
        b.block = k;
        const char *field = NULL;
        TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_pre_clutter_config_check(&b, &field));
        TEST_ASSERT_EQUAL_STRING("map8", field);
        TEST_ASSERT_EQUAL_UINT32(0u, (uint32_t)pft_pre_clutter_workspace_size(&b));
        pft_pre_clutter_t c;
        memset(&c, 0x5A, sizeof c);
        const pft_pre_clutter_t before = c;
        TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_pre_clutter_init(&c, &b, g_work, sizeof g_work));
        TEST_ASSERT_EQUAL_MEMORY(&before, &c, sizeof c);
    }
    for (int mean = 0; mean < 2; ++mean) {
        for (int inplace = 0; inplace < 2; ++inplace) {
            for (uint8_t blur = 0u; blur <= PFT_PRE_CLUTTER_MAX_BLUR; ++blur) {
                cfg.mean = mean != 0;
                cfg.persist = mean != 0 ? 4u : 0u;
                cfg.inplace = inplace != 0;
                cfg.blur = blur;
                cfg.map8 = true;
                const size_t n8 = pft_pre_clutter_workspace_size(&cfg);
                TEST_ASSERT_EQUAL_UINT32((uint32_t)PFT_PRE_CLUTTER_WORKSPACE_BYTES_MAP8(W, H, mean, blur, mean, inplace),
                                         (uint32_t)n8);
                cfg.map8 = false;
                const size_t n16 = pft_pre_clutter_workspace_size(&cfg);
                /* the map's plane W H bytes less; the ring 2 blur + 1 rows instead of blur + 1
                 * and the updated row: (blur + 1) 2 W bytes more; the warp's two rows of
                 * horizontal passes 8 W more (W 2 is a multiple of the workspace's alignment
                 * here) */
                TEST_ASSERT_EQUAL_UINT32((uint32_t)(NPIX - ((size_t)blur + 1u) * 2u * W - 8u * W), (uint32_t)(n16 - n8));
                cfg.map8 = true;
                pft_pre_clutter_t c;
                TEST_ASSERT_EQUAL_INT(PFT_ERR_NOMEM, pft_pre_clutter_init(&c, &cfg, g_work, n8 - 8u));
                TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_init(&c, &cfg, g_work, n8));
                TEST_ASSERT_EQUAL_UINT32(1024u, pft_pre_clutter_at(&c, W - 1u, H - 1u));
            }
        }
    }
}

static void test_persistent_blob_learnt_at_rate(void)
{
    pft_pre_clutter_config_t cfg;
    pft_pre_clutter_config_default(&cfg); /* alpha 0.1, blur 1, thr 2 */
    cfg.width = W;
    cfg.height = H;
    cfg.map8 = true;
    pft_pre_clutter_t c;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_init(&c, &cfg, g_work, sizeof g_work));
    /* settle on a zero residual (the first frame sets m = 0; from the 11th frame on a =
     * alpha, 1 / n being smaller) */
    memset(g_res, 0, sizeof g_res);
    for (uint32_t n = 1u; n <= 10u; ++n) {
        pft_frame_t f = res_frame(n);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_update(&c, &f, 0, 0, true));
    }
    /* a 4 sigma blob on x, y 16..47 (whole columns 16..47, rows 16..47 of 48) */
    for (int y = 16; y < H; ++y) {
        for (int x = 16; x < 48; ++x) {
            g_res[y * W + x] = 1024;
        }
    }
    const double a = 6554.0 / 65536.0;
    for (int n = 1; n <= 20; ++n) {
        pft_frame_t f = res_frame(100u + (uint32_t)n);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_update(&c, &f, 0, 0, true));
        const double m = 16.0 * (1.0 - pow(1.0 - a, n));
        /* the mean over the blob's 24 x 24 inner pixels (each with its own dither): the
         * expectation is the 16-bit map's (within its 1 % of Q6.10 roundings, as in
         * test_pre_clutter_block); the spread of one pixel is a few steps of 1/32 at most, of
         * the mean over 576 pixels a tenth of that: 2 % */
        double sum = 0.0;
        for (uint32_t y = 20u; y < 44u; ++y) {
            for (uint32_t x = 20u; x < 44u; ++x) {
                sum += pft_pre_clutter_at(&c, x, y) / 1024.0;
            }
        }
        TEST_ASSERT_DOUBLE_WITHIN(0.02 * m, m, sum / 576.0);
    }
}

static void test_constant_residual_learnt_in_expectation(void)
{
    pft_pre_clutter_config_t cfg;
    pft_pre_clutter_config_default(&cfg);
    cfg.width = W;
    cfg.height = H;
    cfg.map8 = true;
    pft_pre_clutter_t c;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_init(&c, &cfg, g_work, sizeof g_work));
    /* 1.2 sigma everywhere: t = (307^2 + 32) >> 6 = 1473 (Q6.10); the map starts at 1024 (the
     * first frame sets m = t, so two frames of 1 sigma first) */
    for (int i = 0; i < NPIX; ++i) {
        g_res[i] = 256;
    }
    for (uint32_t n = 1u; n <= 2u; ++n) {
        pft_frame_t f = res_frame(n);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_update(&c, &f, 0, 0, true));
    }
    for (int i = 0; i < NPIX; ++i) {
        g_res[i] = 307;
    }
    double sum = 0.0;
    for (uint32_t n = 3u; n <= 202u; ++n) {
        pft_frame_t f = res_frame(n);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_update(&c, &f, 0, 0, true));
        if (n > 102u) {
            for (uint32_t y = 0u; y < H; ++y) {
                for (uint32_t x = 0u; x < W; ++x) {
                    sum += (double)pft_pre_clutter_at(&c, x, y);
                }
            }
        }
    }
    /* a = 0.1: the nearest code (steps of 32 here) would stop where a (t - m) < 16, m <= 1313,
     * 11 % short; the dither's expectation is t within the 16-bit map's own rounding (a
     * unit or two) and the pixels' spread averages out over 100 frames x 3072 pixels: 1 % */
    TEST_ASSERT_DOUBLE_WITHIN(0.01 * 1473.0, 1473.0, sum / (100.0 * NPIX));
}

static void test_against_16_bit_map_on_drifting_noise(void)
{
    pft_pre_clutter_config_t cfg;
    pft_pre_clutter_config_default(&cfg);
    cfg.width = W;
    cfg.height = H;
    cfg.mean = true;
    cfg.persist = 3u;
    cfg.alpha = 13107u;
    pft_pre_clutter_t c16, c8;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_init(&c16, &cfg, g_work2, sizeof g_work2));
    cfg.map8 = true;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_init(&c8, &cfg, g_work, sizeof g_work));
    double worst = 0.0;
    for (uint32_t n = 1u; n <= 40u; ++n) {
        /* unit noise, 3 sigma on the left third (clutter); the scene drifts by (0.3, -0.2) px */
        for (int y = 0; y < H; ++y) {
            for (int x = 0; x < W; ++x) {
                const int32_t v = pft_test_noise_q88(&g_rs) * (x < W / 3 ? 3 : 1);
                g_res[y * W + x] = (int16_t)(v > 32767 ? 32767 : (v < -32767 ? -32767 : v));
            }
        }
        pft_frame_t f = res_frame(n);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_update(&c16, &f, 19661, -13107, true));
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_update(&c8, &f, 19661, -13107, true));
        double s16 = 0.0, s8 = 0.0;
        for (uint32_t y = 0u; y < H; ++y) {
            for (uint32_t x = 0u; x < W; ++x) {
                s16 += pft_pre_clutter_at(&c16, x, y);
                s8 += pft_pre_clutter_at(&c8, x, y);
            }
        }
        const double rel = fabs(s8 - s16) / s16;
        worst = rel > worst ? rel : worst;
    }
    /* the frame's mean map: the update's dither keeps the expectation, the warp's nearest
     * code is unbiased on spread values; per pixel the codes differ by a few steps of 1/32,
     * over 3072 pixels the mean by well under 1 % */
    TEST_ASSERT_TRUE(worst < 0.01);
}

static void test_raise_and_refused_input(void)
{
    pft_pre_clutter_config_t cfg;
    pft_pre_clutter_config_default(&cfg);
    cfg.width = W;
    cfg.height = H;
    cfg.mean = true;
    cfg.persist = 2u;
    cfg.map8 = true;
    pft_pre_clutter_t c;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_init(&c, &cfg, g_work, sizeof g_work));
    for (uint32_t n = 1u; n <= 3u; ++n) {
        for (int i = 0; i < NPIX; ++i) {
            g_res[i] = (int16_t)pft_test_noise_q88(&g_rs);
        }
        pft_frame_t f = res_frame(n);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_update(&c, &f, 40000, -70000, true));
    }
    const pft_pre_clutter_t saved = c;
    memcpy(g_copy, g_work, sizeof g_work);
    pft_frame_t f = res_frame(9u);
    f.width = W + 1;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_FORMAT, pft_pre_clutter_update(&c, &f, 0, 0, true));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_STATE, pft_pre_clutter_update_inplace(&c, &f, g_res, 0, 0, true));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_pre_clutter_raise(&c, W, 0u, 16384u));
    TEST_ASSERT_EQUAL_MEMORY(&saved, &c, sizeof c);
    TEST_ASSERT_EQUAL_MEMORY(g_copy, g_work, sizeof g_work);
    /* the raise: at least the level on the 3 x 3 (16 sigma^2 is a code; 20000 is not: the
     * next code up, 20480), nothing beyond it raised to it */
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_raise(&c, 8u, 8u, 16384u));
    TEST_ASSERT_EQUAL_UINT32(16384u, pft_pre_clutter_at(&c, 7u, 9u));
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_raise(&c, 20u, 20u, 20000u));
    TEST_ASSERT_EQUAL_UINT32(20480u, pft_pre_clutter_at(&c, 21u, 19u));
    TEST_ASSERT_TRUE(pft_pre_clutter_at(&c, 22u, 20u) < 16384u);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_raise(&c, 30u, 30u, 65535u));
    TEST_ASSERT_EQUAL_UINT32(64512u, pft_pre_clutter_at(&c, 30u, 30u)); /* the largest code */
}

/* The plain reference of map8's update with a shift (pft_pre.h "8-bit map", the formulas of the
 * per-pixel map without the mean): the whole plane decoded and warped first (bilinear, 1
 * sigma^2 outside, each value rounded to its nearest code's), then every pixel read (the box
 * sum over the (2 blur + 1)^2 square of the warped map, edges replicated), scored and updated,
 * and stored with the dither's offset (o + 167 x) mod 256, o the library's hash of the row and
 * the frame count (pre_clutter.c, cl_row8_end_). */
static uint8_t g_ref8[NPIX];
static uint16_t g_refw[NPIX];
static int16_t g_refo[NPIX];

static int32_t floor_div(int32_t n, int32_t d)
{
    return n / d - ((n % d) != 0 && (n < 0) ? 1 : 0);
}

static uint32_t ref_warped(int32_t sx, int32_t sy, int32_t ix, uint32_t fx)
{
    /* the horizontal pass of source row sy at output column sx */
    if (sy < 0 || sy >= H) {
        return 1024u * 256u;
    }
    const int32_t x1 = sx - ix, x0 = x1 - 1;
    const uint32_t v1 = x1 >= 0 && x1 < W ? pft_pre_clutter_dec8_(g_ref8[sy * W + x1]) : 1024u;
    const uint32_t v0 = x0 >= 0 && x0 < W ? pft_pre_clutter_dec8_(g_ref8[sy * W + x0]) : 1024u;
    return v1 * (256u - fx) + v0 * fx;
}

static void ref_frame(uint32_t frames, uint8_t blur, int32_t shx, int32_t shy)
{
    if (frames > 0u && (shx != 0 || shy != 0)) {
        /* the shift in Q8 px (its Q16.16 value a multiple of 256 here: exact) */
        const int32_t qx = floor_div(shx + 128, 256), qy = floor_div(shy + 128, 256);
        int32_t ix = floor_div(qx, 256), iy = floor_div(qy, 256);
        const uint32_t fx = (uint32_t)(qx - 256 * ix), fy = (uint32_t)(qy - 256 * iy);
        ix = ix > W ? W : (ix < -W ? -W : ix);
        iy = iy > H ? H : (iy < -H ? -H : iy);
        for (int32_t y = 0; y < H; ++y) {
            for (int32_t x = 0; x < W; ++x) {
                const uint64_t s = (uint64_t)ref_warped(x, y - iy, ix, fx) * (256u - fy) +
                                   (uint64_t)ref_warped(x, y - iy - 1, ix, fx) * fy + 32768u;
                g_refw[y * W + x] = (uint16_t)pft_pre_clutter_dec8_(pft_pre_clutter_enc8_((uint32_t)(s >> 16), 128u));
            }
        }
    } else {
        for (int i = 0; i < NPIX; ++i) {
            g_refw[i] = (uint16_t)pft_pre_clutter_dec8_(g_ref8[i]);
        }
    }
    const uint32_t n = frames + 1u;
    const uint32_t a1 = (65536u + n / 2u) / n, a = a1 > 6554u ? a1 : 6554u;
    const int32_t b = blur;
    const uint32_t area = (2u * blur + 1u) * (2u * blur + 1u), thr = 2048u * area;
    for (int32_t y = 0; y < H; ++y) {
        uint32_t z = ((uint32_t)y * 0x85EBCA77u) ^ (n * 0xC2B2AE3Du);
        z ^= z >> 15;
        z *= 0x2C1B3C6Du;
        z ^= z >> 13;
        const uint32_t o = z >> 24;
        for (int32_t x = 0; x < W; ++x) {
            uint32_t hs = 0u;
            for (int32_t dy = -b; dy <= b; ++dy) {
                for (int32_t dx = -b; dx <= b; ++dx) {
                    const int32_t yy = y + dy < 0 ? 0 : (y + dy >= H ? H - 1 : y + dy);
                    const int32_t xx = x + dx < 0 ? 0 : (x + dx >= W ? W - 1 : x + dx);
                    hs += g_refw[yy * W + xx];
                }
            }
            const int32_t v = g_res[y * W + x];
            int32_t out = v;
            if (hs > thr && v != PFT_RES16_MASKED) {
                const int32_t s = (int32_t)pft_pre_sqrt_q10_((hs + area / 2u) / area);
                const int32_t mag = ((v < 0 ? -v : v) * 1024 + s / 2) / s;
                out = v < 0 ? -mag : mag;
                out = out > 32767 ? 32767 : (out < -32767 ? -32767 : out);
            }
            g_refo[y * W + x] = (int16_t)out;
            const int32_t m = g_refw[y * W + x];
            int32_t nm = m;
            if (v != PFT_RES16_MASKED) {
                const uint32_t ac = (uint32_t)(v < 0 ? -v : v);
                const uint32_t t0 = (ac * ac + 32u) >> 6;
                const int32_t d = (int32_t)(t0 > 65535u ? 65535u : t0) - m;
                const int32_t q = (int32_t)(((uint64_t)a * (uint64_t)(d < 0 ? -d : d) + 32768u) >> 16);
                nm = m + (d < 0 ? -q : q);
            }
            g_ref8[y * W + x] = (uint8_t)pft_pre_clutter_enc8_((uint32_t)nm, (o + 167u * (uint32_t)x) & 255u);
        }
    }
}

/* The library's map8 (the warp fused with the update, row by row in the warp's order) against
 * the plain reference above, bit for bit (every code and every output value), over a run of
 * shifts of both signs, whole and fractional pixels, each axis alone and beyond the frame, at
 * blur 0, 1 and 2; the residual unit noise, 3 sigma on the left third (the map's read above
 * thr there), a few pixels masked. */
static void test_fused_warp_against_plain_reference(void)
{
    /* shifts in 1/256 px (x, y): (0, 0) frames first, then 0.3 and 0.1; -0.7 and -1.2; whole
     * pixels (2, -1), (-3, 2); x alone (1.5, 0) and y alone (0, -0.25); (-0.5, 0.5); beyond the
     * frame (70, 3) and (0, -50); (0, 1) whole y only; (-1, 0) whole x only */
    static const int32_t sh[][2] = {{0, 0},     {0, 0},      {0, 0},      {77, 26},  {-179, -307},
                                    {512, -256}, {-768, 512}, {384, 0},    {0, -64},  {-128, 128},
                                    {77, 26},   {17920, 768}, {0, -12800}, {0, 256}, {-256, 0},
                                    {-179, -307}, {230, 51},  {0, 0}};
    const uint32_t nsh = (uint32_t)(sizeof sh / sizeof sh[0]);
    for (uint8_t blur = 0u; blur <= 2u; ++blur) {
        pft_pre_clutter_config_t cfg;
        pft_pre_clutter_config_default(&cfg);
        cfg.width = W;
        cfg.height = H;
        cfg.blur = blur;
        cfg.map8 = true;
        pft_pre_clutter_t c;
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_init(&c, &cfg, g_work, sizeof g_work));
        memset(g_ref8, 64, sizeof g_ref8);
        uint32_t rs = 24681357u;
        for (uint32_t n = 0u; n < nsh; ++n) {
            for (int y = 0; y < H; ++y) {
                for (int x = 0; x < W; ++x) {
                    const int32_t v = pft_test_noise_q88(&rs) * (x < W / 3 ? 3 : 1);
                    g_res[y * W + x] = (int16_t)(v > 32767 ? 32767 : (v < -32767 ? -32767 : v));
                }
            }
            g_res[(int)((n * 7u + 5u) % (uint32_t)NPIX)] = PFT_RES16_MASKED;
            g_res[(int)((n * 131u + 1000u) % (uint32_t)NPIX)] = PFT_RES16_MASKED;
            ref_frame(n, blur, sh[n][0] * 256, sh[n][1] * 256);
            pft_frame_t f = res_frame(n + 1u);
            TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_update(&c, &f, sh[n][0] * 256, sh[n][1] * 256, true));
            pft_frame_t out;
            TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_frame(&c, &out));
            TEST_ASSERT_EQUAL_INT16_ARRAY(g_refo, (const int16_t *)out.data, NPIX);
            for (uint32_t y = 0u; y < H; ++y) {
                for (uint32_t x = 0u; x < W; ++x) {
                    /* a code's value is the code (the decode is one to one) */
                    TEST_ASSERT_EQUAL_UINT32(pft_pre_clutter_dec8_(g_ref8[y * W + x]), pft_pre_clutter_at(&c, x, y));
                }
            }
        }
    }
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_code_known_answers_and_round_trip);
    RUN_TEST(test_code_against_definition);
    RUN_TEST(test_code_error_bound_every_value);
    RUN_TEST(test_dither_expectation);
    RUN_TEST(test_config_and_workspace);
    RUN_TEST(test_persistent_blob_learnt_at_rate);
    RUN_TEST(test_constant_residual_learnt_in_expectation);
    RUN_TEST(test_against_16_bit_map_on_drifting_noise);
    RUN_TEST(test_raise_and_refused_input);
    RUN_TEST(test_fused_warp_against_plain_reference);
    return UNITY_END();
}
