/*
 * Clutter map written over its input (pft_pre_clutter_config_t.inplace,
 * pft_pre_clutter_update_inplace; pft_pre.h, "Memory" of the clutter map): the workspace is
 * PFT_PRE_CLUTTER_WORKSPACE_BYTES_INPLACE, 2 bytes per pixel less; a normal and an in-place
 * instance of the same configuration give the same output, map and frame descriptor after
 * every frame (7 configurations: the default plain rows, blur 0, blur 4, the largest value,
 * the veto, the running mean, the mean with the persistence gate; noise, a persistent blob, a
 * moving point, masked pixels, integer and sub-pixel shifts, a frame without evidence, the
 * raise); refused calls leave instance, workspace and buffer byte-identical. 64 x 48 frames,
 * integer residuals, so that it runs on every target.
 */
#include <stdio.h>
#include <string.h>

#include "pft_test_support.h"
#include "pft/pft_pre.h"

void setUp(void) {}
void tearDown(void) {}

#define W 64
#define H 48
#define NPIX (W * H)

static int16_t g_res[NPIX];  /* the frame's residual, input of the normal instance */
static int16_t g_buf[NPIX];  /* its copy, written over by the in-place instance */
static int16_t g_keep[NPIX]; /* g_res before the normal update (it must not change) */
static uint64_t g_work_a[PFT_PRE_CLUTTER_WORKSPACE_BYTES(W, H, 1, PFT_PRE_CLUTTER_MAX_BLUR, 1) / 8 + 1];
static uint64_t g_work_b[sizeof(g_work_a) / 8];
static uint64_t g_copy[sizeof(g_work_a) / 8];
static int16_t g_pad[(W + 1) * H];
static uint32_t g_rs = 88172645u;

static uint32_t rnd(void)
{
    return pft_test_xorshift32(&g_rs);
}

/* about N(0, 1) in Q8.8: a sum of four uniforms, sd 256 */
static int16_t noise_q88(void)
{
    return (int16_t)pft_test_noise_q88(&g_rs);
}

static pft_frame_t frame_of(int16_t *px, uint32_t seq)
{
    return pft_test_res16_frame(px, W, H, seq, 1000u * seq);
}

/* Frame k: noise, a 4 sigma blob fixed in the scene (the scene drifts, see shift_of), a 6 sigma
 * point moving 1 px per frame, some masked pixels, a few saturated values. */
static void make_frame(int k)
{
    for (int i = 0; i < NPIX; ++i) {
        g_res[i] = noise_q88();
    }
    for (int y = 20; y < 26; ++y) {
        for (int x = 10 + k / 2; x < 18 + k / 2 && x < W; ++x) {
            g_res[y * W + x] = (int16_t)(g_res[y * W + x] + 1024);
        }
    }
    g_res[(8 + k) * W + 30 + k] = 1536;
    for (int j = 0; j < 20; ++j) {
        g_res[rnd() % NPIX] = PFT_RES16_MASKED;
    }
    g_res[(rnd() % NPIX)] = 32767;
    g_res[(rnd() % NPIX)] = -32767;
}

/* The scene's shift of frame k, Q16.16: sub-pixel, integer, none, negative. */
static void shift_of(int k, int32_t *sx, int32_t *sy)
{
    static const int32_t xs[] = {0, 32768, 65536, 0, -19661, 6554, 131072, -65536};
    static const int32_t ys[] = {0, 0, -32768, 0, 13107, -65536, 0, 98304};
    *sx = xs[k % 8];
    *sy = ys[k % 8];
}

static void init_pair(pft_pre_clutter_t *a, pft_pre_clutter_t *b, pft_pre_clutter_config_t cfg)
{
    cfg.width = W;
    cfg.height = H;
    cfg.inplace = false;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_init(a, &cfg, g_work_a, sizeof g_work_a));
    cfg.inplace = true;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_init(b, &cfg, g_work_b, sizeof g_work_b));
}

static void test_workspace(void)
{
    pft_pre_clutter_config_t cfg;
    pft_pre_clutter_config_default(&cfg);
    TEST_ASSERT_FALSE(cfg.inplace);
    cfg.width = W;
    cfg.height = H;
    for (int mean = 0; mean < 2; ++mean) {
        for (uint8_t blur = 0u; blur <= PFT_PRE_CLUTTER_MAX_BLUR; ++blur) {
            cfg.mean = mean != 0;
            cfg.persist = mean != 0 ? 4u : 0u;
            cfg.blur = blur;
            cfg.inplace = false;
            const size_t full = pft_pre_clutter_workspace_size(&cfg);
            cfg.inplace = true;
            const size_t in = pft_pre_clutter_workspace_size(&cfg);
            TEST_ASSERT_EQUAL_UINT32((uint32_t)PFT_PRE_CLUTTER_WORKSPACE_BYTES_INPLACE(W, H, mean, blur, mean),
                                     (uint32_t)in);
            /* the output buffer, 2 bytes per pixel (W H 2 is a multiple of the alignment) */
            TEST_ASSERT_EQUAL_UINT32((uint32_t)(2u * NPIX), (uint32_t)(full - in));
            pft_pre_clutter_t c;
            TEST_ASSERT_EQUAL_INT(PFT_ERR_NOMEM, pft_pre_clutter_init(&c, &cfg, g_work_b, in - 8u));
            TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_init(&c, &cfg, g_work_b, in));
            pft_frame_t o;
            TEST_ASSERT_EQUAL_INT(PFT_ERR_STATE, pft_pre_clutter_frame(&c, &o));
        }
    }
}

static void check_same(const pft_pre_clutter_t *a, const pft_pre_clutter_t *b, int cfg_no, int k)
{
    pft_frame_t oa, ob;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_frame(a, &oa));
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_frame(b, &ob));
    TEST_ASSERT_TRUE(ob.data == (const void *)g_buf);
    TEST_ASSERT_EQUAL_UINT32(oa.width, ob.width);
    TEST_ASSERT_EQUAL_UINT32(oa.height, ob.height);
    TEST_ASSERT_EQUAL_UINT32(oa.stride_bytes, ob.stride_bytes);
    TEST_ASSERT_EQUAL_INT(oa.format, ob.format);
    TEST_ASSERT_EQUAL_UINT32(oa.seq, ob.seq);
    TEST_ASSERT_TRUE(oa.timestamp_us == ob.timestamp_us);
    const int16_t *pa = (const int16_t *)oa.data;
    for (int i = 0; i < NPIX; ++i) {
        if (pa[i] != g_buf[i]) {
            char msg[80];
            snprintf(msg, sizeof msg, "output, configuration %d, frame %d, pixel %d", cfg_no, k, i);
            TEST_ASSERT_EQUAL_INT16_MESSAGE(pa[i], g_buf[i], msg);
        }
    }
    for (uint32_t y = 0; y < H; ++y) {
        for (uint32_t x = 0; x < W; ++x) {
            if (pft_pre_clutter_at(a, x, y) != pft_pre_clutter_at(b, x, y)) {
                char msg[80];
                snprintf(msg, sizeof msg, "map, configuration %d, frame %d, (%u, %u)", cfg_no, k,
                         (unsigned)x, (unsigned)y);
                TEST_ASSERT_EQUAL_UINT32_MESSAGE(pft_pre_clutter_at(a, x, y), pft_pre_clutter_at(b, x, y), msg);
            }
        }
    }
}

static void test_same_values_as_normal(void)
{
    for (int n = 0; n < 7; ++n) {
        pft_pre_clutter_config_t cfg;
        pft_pre_clutter_config_default(&cfg);
        cfg.alpha = 13107u; /* 0.2: the map crosses thr within the 16 frames */
        switch (n) {
        case 1: cfg.blur = 0u; break;
        case 2: cfg.blur = PFT_PRE_CLUTTER_MAX_BLUR; break;
        case 3: cfg.box = false; cfg.blur = 2u; break;
        case 4: cfg.veto = 4096u; break;
        case 5: cfg.mean = true; break;
        case 6: cfg.mean = true; cfg.persist = 3u; break;
        default: break; /* the defaults: the plain rows */
        }
        pft_pre_clutter_t a, b;
        init_pair(&a, &b, cfg);
        for (int k = 0; k < 16; ++k) {
            make_frame(k);
            memcpy(g_buf, g_res, sizeof g_res);
            memcpy(g_keep, g_res, sizeof g_res);
            int32_t sx, sy;
            shift_of(k, &sx, &sy);
            const bool ev = k != 5; /* frame 5: no evidence */
            pft_frame_t fa = frame_of(g_res, (uint32_t)k + 1u), fb = frame_of(g_buf, (uint32_t)k + 1u);
            TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_update(&a, &fa, sx, sy, ev));
            TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_update_inplace(&b, &fb, g_buf, sx, sy, ev));
            TEST_ASSERT_EQUAL_MEMORY(g_keep, g_res, sizeof g_res); /* the normal call's input is kept */
            check_same(&a, &b, n, k);
            if (k == 9) {
                TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_raise(&a, 40u, 30u, 16384u));
                TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_raise(&b, 40u, 30u, 16384u));
            }
        }
        /* some output differs from the input (the map scored pixels), or the test would not
         * tell the two orders of reading and writing apart */
        int changed = 0;
        for (int i = 0; i < NPIX; ++i) {
            changed += g_buf[i] != g_res[i] ? 1 : 0;
        }
        TEST_ASSERT_GREATER_THAN_INT(0, changed);
        /* reset: the in-place instance lends nothing until its next update */
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_reset(&b));
        pft_frame_t o;
        TEST_ASSERT_EQUAL_INT(PFT_ERR_STATE, pft_pre_clutter_frame(&b, &o));
    }
}

static void test_refusals_change_nothing(void)
{
    pft_pre_clutter_config_t cfg;
    pft_pre_clutter_config_default(&cfg);
    cfg.mean = true;
    cfg.persist = 3u;
    pft_pre_clutter_t a, b;
    init_pair(&a, &b, cfg);
    for (int k = 0; k < 4; ++k) {
        make_frame(k);
        memcpy(g_buf, g_res, sizeof g_res);
        pft_frame_t fb = frame_of(g_buf, (uint32_t)k + 1u);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_update_inplace(&b, &fb, g_buf, 6554, 0, true));
        pft_frame_t fa = frame_of(g_res, (uint32_t)k + 1u);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_update(&a, &fa, 6554, 0, true));
    }
    make_frame(7);
    memcpy(g_buf, g_res, sizeof g_res);
    for (int i = 0; i < (W + 1) * H; ++i) {
        g_pad[i] = (int16_t)(i % 1000);
    }
    const pft_pre_clutter_t sa = a, sb = b;
    memcpy(g_copy, g_work_b, sizeof g_work_b);
    pft_frame_t f = frame_of(g_buf, 8u), x;
    /* the wrong call for each kind of instance */
    TEST_ASSERT_EQUAL_INT(PFT_ERR_STATE, pft_pre_clutter_update(&b, &f, 0, 0, true));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_STATE, pft_pre_clutter_update_inplace(&a, &f, g_buf, 0, 0, true));
    /* NULLs and a foreign buffer */
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_pre_clutter_update_inplace(NULL, &f, g_buf, 0, 0, true));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_pre_clutter_update_inplace(&b, NULL, g_buf, 0, 0, true));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_pre_clutter_update_inplace(&b, &f, NULL, 0, 0, true));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_pre_clutter_update_inplace(&b, &f, g_res, 0, 0, true));
    /* wrong frames: format, size, rows not packed (a padded buffer) */
    x = f;
    x.format = PFT_PIX_U16;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_FORMAT, pft_pre_clutter_update_inplace(&b, &x, g_buf, 0, 0, true));
    x = f;
    x.width = W - 1;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_FORMAT, pft_pre_clutter_update_inplace(&b, &x, g_buf, 0, 0, true));
    x = f;
    x.height = H + 1;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_FORMAT, pft_pre_clutter_update_inplace(&b, &x, g_buf, 0, 0, true));
    x = frame_of(g_pad, 8u);
    x.stride_bytes = 2u * (W + 1);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_FORMAT, pft_pre_clutter_update_inplace(&b, &x, g_pad, 0, 0, true));
    TEST_ASSERT_EQUAL_MEMORY(&sa, &a, sizeof a);
    TEST_ASSERT_EQUAL_MEMORY(&sb, &b, sizeof b);
    TEST_ASSERT_EQUAL_MEMORY(g_copy, g_work_b, sizeof g_work_b);
    TEST_ASSERT_EQUAL_MEMORY(g_res, g_buf, sizeof g_buf);
    for (int i = 0; i < (W + 1) * H; ++i) {
        TEST_ASSERT_EQUAL_INT16((int16_t)(i % 1000), g_pad[i]);
    }
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_workspace);
    RUN_TEST(test_same_values_as_normal);
    RUN_TEST(test_refusals_change_nothing);
    return UNITY_END();
}
