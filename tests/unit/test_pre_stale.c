/*
 * Stale background values under a masked block fixed to the sensor
 * (pft_pre_config_t.bg_stale_reinit, docs/algorithms.md 9.14): a textured scene on a gradient
 * drifts by 0.3 / 0.1 px per frame under a saturated block of 12 x 9 pixels that stays at the
 * same place in the frame. The scene that comes out from under the block's trailing edge (its
 * right side) meets a background that was never learnt there (the first frame filled it from
 * the last unmasked pixel of its row) or kept from before it went under; without the option
 * the residual beside that edge holds the difference, with it the values restart from the
 * frame as at the frame's entering edge. Both the re-warped background and the anchored one
 * (bg_anchor, also with the gate and young cells). Without a block, and with a single dead
 * pixel, the outputs are those of the option off, byte for byte. Configuration check and
 * refused input. Frames are 96 x 72 (every target, Cortex-M under QEMU included).
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "pft_test_support.h"
#include "pft/pft_pre.h"

void setUp(void) {}
void tearDown(void) {}

#define W 96
#define H 72
#define NPIX (W * H)
#define TILE 24
#define SIGMA_T 16.0 /* temporal noise, counts */
/* the block: columns BX0 .. BX1 - 1, rows BY0 .. BY1 - 1, saturated on every frame */
#define BX0 30
#define BX1 42
#define BY0 30
#define BY1 39
#define NFR 60u

#define WS_A (PFT_PRE_WORKSPACE_BYTES_ANCHOR(W, H, 4, TILE, 64) + PFT_PRE_YOUNG_BYTES(W, H))
#define WS_T PFT_PRE_WORKSPACE_BYTES(W, H, PFT_PRE_BG_TEMPORAL, 4, TILE, 64)
static uint16_t g_img[NPIX];
static uint64_t g_work[((WS_A > WS_T ? WS_A : WS_T) + PFT_PRE_STALE_BYTES(W, H)) / 8 + 8];
static uint64_t g_copy[sizeof(g_work) / 8];
static int16_t g_res0[NPIX];
static uint32_t g_rs = 2463534242u;

/* The frame of a smooth texture on a gradient of 12 counts per px along x, shifted by
 * (sx, sy) (pixel p shows the scene at p - s), plus noise of SIGMA_T; with `block` the block
 * saturated (16383), with `dead` pixel (60, 20) dead (0). */
static void render(double sx, double sy, bool block, bool dead)
{
    const double pi2 = 6.283185307179586;
    for (int y = 0; y < H; ++y) {
        for (int x = 0; x < W; ++x) {
            const double u = x - sx, v = y - sy;
            double z = 4000.0 + 12.0 * u + 600.0 * sin(pi2 * u / 23.0) + 400.0 * sin(pi2 * v / 17.0 + 0.5) +
                       300.0 * sin(pi2 * u / 13.0) * sin(pi2 * v / 19.0 + 2.0);
            z += SIGMA_T * pft_test_noise_sum4(&g_rs) / 2365.0;
            const double r = floor(z + 0.5);
            g_img[y * W + x] = (uint16_t)(r < 1.0 ? 1.0 : (r > 16382.0 ? 16382.0 : r));
            if (block && x >= BX0 && x < BX1 && y >= BY0 && y < BY1) {
                g_img[y * W + x] = 16383u;
            }
        }
    }
    if (dead) {
        g_img[20 * W + 60] = 0u;
    }
}

static void config(pft_pre_config_t *c, bool anchor, bool gate, uint8_t stale)
{
    pft_pre_config_default(c);
    c->width = W;
    c->height = H;
    c->tile = TILE;
    c->bit_depth = 14u;
    c->sigma_interp = false; /* sigma held per tile: the residual in counts is exact */
    c->bg_anchor = anchor;
    c->bg_gate = gate ? 64u : 0u;
    c->bg_gate_young = gate ? 16u : 0u;
    c->bg_stale_reinit = stale;
}

static void init(pft_pre_t *p, const pft_pre_config_t *c)
{
    pft_test_pre_init(p, c, g_work, sizeof(g_work));
}

/* The residual of pixel (x, y) in units of SIGMA_T; NAN when masked. */
static double res_t(const pft_pre_t *p, int x, int y)
{
    return pft_test_pre_res_counts(p, x, y) / SIGMA_T;
}

/* Runs NFR frames with the block; from frame 21 on, the rms residual (SIGMA_T units) of the
 * unmasked pixels of the 8 columns right of the block (BX1 .. BX1 + 7, its rows) and of a
 * control area of the same shape 24 rows below (rows BY0 + 24 .. BY1 + 23), and the share of
 * those beside the block that were unmasked. */
static void trailing_edge(bool anchor, bool gate, uint8_t stale, double *edge, double *ctl, double *seen)
{
    pft_pre_config_t c;
    config(&c, anchor, gate, stale);
    pft_pre_t p;
    init(&p, &c);
    g_rs = 2463534242u;
    double se = 0.0, sc = 0.0;
    int ne = 0, nc = 0, nall = 0;
    for (uint32_t k = 0; k < NFR; ++k) {
        render(0.3 * k, 0.1 * k, true, false);
        pft_frame_t f = pft_test_u16_frame(g_img, W, H, 14u, k + 1u);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_update(&p, &f));
        if (k < 20u) {
            continue;
        }
        for (int y = BY0; y < BY1; ++y) {
            for (int x = BX1; x < BX1 + 8; ++x) {
                const double r = res_t(&p, x, y), q = res_t(&p, x, y + 24);
                nall++;
                if (!isnan(r)) {
                    se += r * r;
                    ne++;
                }
                if (!isnan(q)) {
                    sc += q * q;
                    nc++;
                }
            }
        }
    }
    TEST_ASSERT_TRUE(ne > 0 && nc > nall / 2);
    *edge = sqrt(se / ne);
    *ctl = sqrt(sc / nc);
    *seen = (double)ne / nall;
}

static void check_edge(bool anchor, bool gate)
{
    double e0 = 0.0, c0 = 0.0, s0 = 0.0, e1 = 0.0, c1 = 0.0, s1 = 0.0;
    trailing_edge(anchor, gate, 0u, &e0, &c0, &s0);
    trailing_edge(anchor, gate, 16u, &e1, &c1, &s1);
    char msg[240];
    snprintf(msg, sizeof msg, "%s%s: rms residual beside the trailing edge / control, sigma_t: off %.2f / %.2f "
             "(%.0f %% unmasked), bg_stale_reinit 16 %.2f / %.2f (%.0f %% unmasked)",
             anchor ? "anchored" : "re-warped", gate ? " with gate and young cells" : "", e0, c0,
             100.0 * s0, e1, c1, 100.0 * s1);
    UnityPrint(msg);
    UNITY_PRINT_EOL();
    /* the stage is integer code: the same values in both builds. Bounds: the control's rms is
     * about 1 (the residual's sd, 1 to 1.5 sigma_t on this texture); off, the stale values
     * leave the edge more than 3 times that; on, within 0.5 sigma_t of the control (each rms
     * over about 1500 pixel-frames: a standard error of a few hundredths, plus the one-frame
     * noise of the restarted values near the edge), with at least half the pixels unmasked
     * (the band that reads stale values is 2 to 3 px of the 8). */
    TEST_ASSERT_TRUE_MESSAGE(e0 > 3.0 * c0, msg);
    TEST_ASSERT_TRUE_MESSAGE(e1 < c1 + 0.5, msg);
    TEST_ASSERT_TRUE_MESSAGE(s1 > 0.5, msg);
}

static void test_trailing_edge_rewarped(void) { check_edge(false, false); }
static void test_trailing_edge_anchored(void) { check_edge(true, false); }
static void test_trailing_edge_anchored_gated(void) { check_edge(true, true); }

/* Without a block (a single dead pixel or none) the option changes nothing: the residual of
 * every frame is the same as without it, byte for byte. */
static void same_without_block(bool anchor, bool dead)
{
    pft_pre_config_t c0, c1;
    config(&c0, anchor, anchor, 0u);
    config(&c1, anchor, anchor, 16u);
    static pft_pre_t p0, p1;
    static uint64_t work0[sizeof(g_work) / 8];
    const char *field = NULL;
    TEST_ASSERT_EQUAL_INT_MESSAGE(PFT_OK, pft_pre_config_check(&c0, &field), field);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_init(&p0, &c0, work0, pft_pre_workspace_size(&c0)));
    init(&p1, &c1);
    g_rs = 2463534242u;
    for (uint32_t k = 0; k < 40u; ++k) {
        render(0.3 * k, 0.1 * k, false, dead);
        pft_frame_t f = pft_test_u16_frame(g_img, W, H, 14u, k + 1u);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_update(&p0, &f));
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_update(&p1, &f));
        pft_frame_t r0, r1;
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_frame(&p0, &r0));
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_frame(&p1, &r1));
        memcpy(g_res0, r0.data, sizeof g_res0);
        TEST_ASSERT_EQUAL_MEMORY(g_res0, r1.data, sizeof g_res0);
    }
}

static void test_same_rewarped(void) { same_without_block(false, false); }
static void test_same_rewarped_dead(void) { same_without_block(false, true); }
static void test_same_anchored(void) { same_without_block(true, false); }
static void test_same_anchored_dead(void) { same_without_block(true, true); }

/* The anchored grid's ages under the block, known answers: a still scene (the registration
 * off: shift 0, the grid on the frame), so that cell (j, y) reads pixel (j, y). On the first
 * frame a masked cell's age is its distance to the last unmasked pixel of its row (cell BX0 + i:
 * i + 1); each later frame adds one to a cell whose tap is masked, at most 127 (never learnt),
 * and the largest age of the row (srow) follows; a cell without a masked tap stays 0. The
 * frames past 118 take the inner cells across 127 one by one. (stale_anchor_urow_'s age update
 * and its row maximum: in byte lanes on x86-64 and AArch64, in 32-bit form on Cortex-M; the
 * same answers on every target.) */
static void test_anchored_ages_known(void)
{
    pft_pre_config_t c;
    config(&c, true, false, 16u);
    c.reg_search = 0u;
    c.reg_iters = 0u;
    pft_pre_t p;
    init(&p, &c);
    g_rs = 2463534242u;
    const int sw = W + 3, y = BY0 + 4;
    const uint8_t *ar = NULL;
    for (uint32_t k = 1u; k <= 131u; ++k) {
        render(0.0, 0.0, true, false);
        pft_frame_t f = pft_test_u16_frame(g_img, W, H, 14u, k);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_update(&p, &f));
        ar = p.sage + (size_t)(y + 1) * (size_t)sw + 1u; /* ar[j]: cell j of grid row y */
        if (k != 1u && k != 2u && k != 60u && k != 118u && k != 121u && k != 124u && k != 131u) {
            continue;
        }
        for (int i = 2; i <= BX1 - BX0 - 3; ++i) { /* the inner cells: every tap masked */
            const uint32_t want = i + k > 127u ? 127u : (uint32_t)i + k;
            TEST_ASSERT_EQUAL_UINT32_MESSAGE(want, ar[BX0 + i], "age of an inner cell of the block");
        }
        TEST_ASSERT_EQUAL_UINT8(0u, ar[10]); /* the block's row, left of it */
        TEST_ASSERT_EQUAL_UINT8(0u, ar[BX1 + 6]);
        TEST_ASSERT_EQUAL_UINT8(0u, p.sage[(size_t)(10 + 1) * (size_t)sw + 1u + 50u]); /* row 10 */
        TEST_ASSERT_EQUAL_UINT8(0u, p.srow[10 + 1]);
        uint32_t mx = 0u; /* the row's largest age, as srow */
        for (int j = -1; j <= W + 1; ++j) {
            mx = ar[j] > mx ? ar[j] : mx;
        }
        TEST_ASSERT_EQUAL_UINT32(mx, p.srow[y + 1]);
        TEST_ASSERT_TRUE(mx >= (BX1 - BX0 - 3u + k > 127u ? 127u : BX1 - BX0 - 3u + k));
    }
    TEST_ASSERT_EQUAL_UINT8(127u, ar[BX0 + 2]); /* the last frame: all at 127 */
    TEST_ASSERT_EQUAL_UINT8(127u, p.srow[y + 1]);
}

static void test_config(void)
{
    pft_pre_config_t c;
    pft_pre_config_default(&c);
    TEST_ASSERT_EQUAL_UINT8(0u, c.bg_stale_reinit); /* off by default */
    const char *field = NULL;
    for (int a = 0; a < 2; ++a) {
        config(&c, a != 0, false, 0u);
        const size_t base = pft_pre_workspace_size(&c);
        c.bg_stale_reinit = PFT_PRE_MAX_BG_STALE;
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_config_check(&c, &field));
        TEST_ASSERT_EQUAL_UINT64(base + PFT_PRE_STALE_BYTES(W, H), pft_pre_workspace_size(&c));
        c.bg_stale_reinit = PFT_PRE_MAX_BG_STALE + 1u;
        TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_pre_config_check(&c, &field));
        TEST_ASSERT_EQUAL_STRING("bg_stale_reinit", field);
    }
    config(&c, false, false, 16u);
    c.method = PFT_PRE_BG_LOCAL; /* a temporal background's ages */
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_pre_config_check(&c, &field));
    TEST_ASSERT_EQUAL_STRING("bg_stale_reinit", field);
    config(&c, false, false, 16u);
    c.inplace = true; /* the re-warped background in place: allowed */
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_config_check(&c, &field));
}

static void refused_changes_nothing(bool anchor)
{
    pft_pre_config_t c;
    config(&c, anchor, anchor, 16u);
    pft_pre_t p;
    init(&p, &c);
    const size_t need = pft_pre_workspace_size(&c);
    g_rs = 2463534242u;
    for (uint32_t k = 0; k < 6u; ++k) { /* a state worth protecting: ages under the block */
        render(0.3 * k, 0.1 * k, true, false);
        pft_frame_t f = pft_test_u16_frame(g_img, W, H, 14u, k + 1u);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_update(&p, &f));
    }
    pft_test_pre_bad_frames_refused(&p, pft_test_u16_frame(g_img, W, H, 14u, 9u), g_work, need, g_copy);
    pft_pre_config_t d = c;
    d.bg_stale_reinit = PFT_PRE_MAX_BG_STALE + 1u;
    pft_test_pre_init_refused(&p, &d, g_work, need, g_copy);
}

static void test_refused_changes_nothing(void)
{
    refused_changes_nothing(false);
    refused_changes_nothing(true);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_config);
    RUN_TEST(test_trailing_edge_rewarped);
    RUN_TEST(test_trailing_edge_anchored);
    RUN_TEST(test_trailing_edge_anchored_gated);
    RUN_TEST(test_same_rewarped);
    RUN_TEST(test_same_rewarped_dead);
    RUN_TEST(test_same_anchored);
    RUN_TEST(test_same_anchored_dead);
    RUN_TEST(test_refused_changes_nothing);
    RUN_TEST(test_anchored_ages_known);
    return UNITY_END();
}
