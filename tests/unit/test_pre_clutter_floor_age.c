/*
 * The clutter map's floor by age (pft_pre_clutter_config_t.floor_age, docs/algorithms.md 9.9):
 * the configuration check names the field (needs mean_floor); the default is 0; the workspace
 * grows by PFT_PRE_CLUTTER_WORKSPACE_BYTES_AGE; with floor_age K every output is r - mu where
 * the cell is younger than K frames (the smaller of its column's and its row's age), and where
 * it is older r - mu only if |mu| (rounded to Q8.8) exceeds the floor, else r: bit for bit
 * against a reference that reads mu before the frame and keeps its own column and row ages
 * (moved with the map: whole-pixel shifts of the carry, and the anchored map's moves; the
 * columns and rows that enter at 0). The counts check that both kinds of cell were met where
 * the two rules differ (0 < |mu| <= floor), so the test fails if the age test were skipped (the
 * young ones), if the ages never reached K (the old ones), or if the ages did not move with the
 * map (the young columns and rows at the entering edges). 64 x 48 frames, thr at its largest
 * (the output is c exactly).
 */
#include <string.h>

#include "pft_test_support.h"
#include "pft/pft_pre.h"

void setUp(void) {}
void tearDown(void) {}

#define W 64
#define H 48
#define NPIX (W * H)
#define K 6u

static int16_t g_res[NPIX];
static uint16_t g_mu0[NPIX];
static uint16_t g_muv[NPIX];
static uint64_t g_work[(PFT_PRE_CLUTTER_WORKSPACE_BYTES(W, H, 1, PFT_PRE_CLUTTER_MAX_BLUR, 1) +
                        PFT_PRE_CLUTTER_WORKSPACE_BYTES_AGE(W, H)) / 8 + 1];
static uint32_t g_rs = 2463534242u;

static pft_frame_t res_frame(uint32_t seq)
{
    return pft_test_res16_frame(g_res, W, H, seq, 1000u * seq);
}

static void test_config(void)
{
    pft_pre_clutter_config_t cfg;
    pft_pre_clutter_config_default(&cfg);
    TEST_ASSERT_EQUAL_UINT8(0u, cfg.floor_age);
    cfg.mean = true;
    const char *field = "x";
    /* without a floor the age gates nothing: refused, named */
    cfg.floor_age = 10u;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_pre_clutter_config_check(&cfg, &field));
    TEST_ASSERT_EQUAL_STRING("floor_age", field);
    TEST_ASSERT_EQUAL_UINT32(0u, (uint32_t)pft_pre_clutter_workspace_size(&cfg));
    /* with one: accepted, the ages' bytes more */
    cfg.mean_floor = 256u;
    field = "x";
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_config_check(&cfg, &field));
    TEST_ASSERT_NULL(field);
    cfg.width = W;
    cfg.height = H;
    pft_pre_clutter_config_t off = cfg;
    off.floor_age = 0u;
    TEST_ASSERT_EQUAL_UINT32((uint32_t)(pft_pre_clutter_workspace_size(&off) + PFT_PRE_CLUTTER_WORKSPACE_BYTES_AGE(W, H)),
                             (uint32_t)pft_pre_clutter_workspace_size(&cfg));
    pft_pre_clutter_t c;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_NOMEM, pft_pre_clutter_init(&c, &cfg, g_work, pft_pre_clutter_workspace_size(&off)));
    /* the floor's own refusals still come first (the floor needs mean) */
    cfg.mean = false;
    field = "x";
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_pre_clutter_config_check(&cfg, &field));
    TEST_ASSERT_EQUAL_STRING("mean_floor", field);
}

/* out(i) = v(i - d), fill 0 where the source is outside (n values) */
static void move_ages(uint8_t *a, int n, int d)
{
    uint8_t t[W > H ? W : H];
    for (int i = 0; i < n; ++i) {
        const int s = i - d;
        t[i] = s >= 0 && s < n ? a[s] : 0u;
    }
    memcpy(a, t, (size_t)n);
}

/* rounded Q16.16 position, halves upwards (floor((a + 2^15) / 2^16)) */
static int64_t round16(int64_t a)
{
    const int64_t t = a + 32768;
    return t >= 0 ? t / 65536 : -((-t + 65535) / 65536);
}

typedef struct {
    uint32_t young_diff; /* young cells where 0 < |mu| <= floor (the plain mean taken off) */
    uint32_t old_diff;   /* old cells where 0 < |mu| <= floor (r kept) */
    uint32_t young_edge; /* of young_diff: after frame K, in a column or row that entered */
} counts_t;

/* 40 frames of unit noise with a scene-fixed 3 x 3 blob of 1 sigma, the scene moving (sx, sy)
 * Q16.16 px per frame; anchor or the carry (whole pixels only: the carry's copy is then exact).
 * Every output against the reference. */
static counts_t run_case(bool anchor, int32_t sx, int32_t sy)
{
    pft_pre_clutter_config_t cfg;
    pft_pre_clutter_config_default(&cfg);
    cfg.mean = true;
    cfg.thr = 65535u;
    cfg.anchor = anchor;
    cfg.mean_floor = 128u; /* 0.5 sigma */
    cfg.floor_age = (uint8_t)K;
    pft_pre_clutter_t c;
    pft_test_clutter_init(&c, &cfg, W, H, g_work, sizeof g_work);
    uint8_t ca[W], ra[H]; /* the reference's ages */
    memset(ca, 0, sizeof ca);
    memset(ra, 0, sizeof ra);
    counts_t n = {0u, 0u, 0u};
    int64_t ax = 0, ay = 0, px = 0, py = 0; /* scene position: summed shifts, rounded */
    for (uint32_t k = 0; k < 40u; ++k) {
        ax += sx;
        ay += sy;
        int dx, dy;
        if (anchor) {
            const int64_t nx = round16(ax), ny = round16(ay);
            dx = k == 0u ? 0 : (int)(nx - px);
            dy = k == 0u ? 0 : (int)(ny - py);
            px = nx;
            py = ny;
        } else {
            dx = k == 0u ? 0 : (int)(sx / 65536);
            dy = k == 0u ? 0 : (int)(sy / 65536);
            px = ax / 65536;
            py = ay / 65536;
        }
        for (int i = 0; i < NPIX; ++i) {
            g_res[i] = (int16_t)pft_test_noise_q88(&g_rs);
        }
        for (int y = 20; y < 23; ++y) {
            for (int x = 20; x < 23; ++x) {
                const int64_t yy = y + py, xx = x + px; /* the scene-fixed blob, in frame pixels */
                if (yy >= 0 && yy < H && xx >= 0 && xx < W) {
                    g_res[yy * W + xx] = (int16_t)(g_res[yy * W + xx] + 256);
                }
            }
        }
        /* the mean and the ages as the map moves them before the frame */
        memcpy(g_mu0, c.mu, sizeof g_mu0);
        for (int y = 0; y < H; ++y) {
            for (int x = 0; x < W; ++x) {
                const int sxp = x - dx, syp = y - dy;
                const bool in = sxp >= 0 && sxp < W && syp >= 0 && syp < H;
                g_muv[y * W + x] = in ? g_mu0[syp * W + sxp] : (uint16_t)32768u;
            }
        }
        move_ages(ca, W, dx);
        move_ages(ra, H, dy);
        pft_frame_t f = res_frame(k + 1u);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_update(&c, &f, sx, sy, true));
        const int16_t *o = pft_test_clutter_out(&c);
        for (int y = 0; y < H; ++y) {
            for (int x = 0; x < W; ++x) {
                const int i = y * W + x;
                const int32_t mq = pft_test_clutter_mu_q88(g_muv[i]);
                const int32_t am = mq < 0 ? -mq : mq;
                const uint8_t age = ca[x] < ra[y] ? ca[x] : ra[y];
                const bool young = age < K;
                const bool take = young ? true : am > (int32_t)cfg.mean_floor;
                if (am > 0 && am <= (int32_t)cfg.mean_floor) {
                    n.young_diff += young ? 1u : 0u;
                    n.old_diff += young ? 0u : 1u;
                    n.young_edge += young && k > K ? 1u : 0u;
                }
                TEST_ASSERT_EQUAL_INT16((int16_t)(g_res[i] - (take ? mq : 0)), o[i]);
            }
        }
        for (int x = 0; x < W; ++x) {
            ca[x] = ca[x] < K ? (uint8_t)(ca[x] + 1u) : (uint8_t)K;
        }
        for (int y = 0; y < H; ++y) {
            ra[y] = ra[y] < K ? (uint8_t)(ra[y] + 1u) : (uint8_t)K;
        }
    }
    return n;
}

/* The carry, 1 px per frame in x and -1 px in y: the columns on the left and the rows at the
 * bottom enter every frame (ages 0, 1, ... inwards). */
static void test_young_cells_take_the_plain_mean_carry(void)
{
    const counts_t n = run_case(false, 65536, -65536);
    /* frames 1..K every cell is young (about NPIX K of them, most with 0 < |mu| <= floor);
     * afterwards the K left columns and K bottom rows */
    TEST_ASSERT_TRUE(n.young_diff > (uint32_t)NPIX * (K - 1u) / 2u);
    TEST_ASSERT_TRUE(n.young_edge > (uint32_t)(K * (W + H)) * 10u);
    TEST_ASSERT_TRUE(n.old_diff > (uint32_t)NPIX * 20u);
}

/* The anchored map, 0.6 px per frame in x and -0.4 px in y: whole-pixel moves of the rounded
 * position, the columns and rows that enter at age 0. */
static void test_young_cells_take_the_plain_mean_anchor(void)
{
    const counts_t n = run_case(true, 39322, -26214);
    TEST_ASSERT_TRUE(n.young_diff > (uint32_t)NPIX * (K - 1u) / 2u);
    TEST_ASSERT_TRUE(n.young_edge > (uint32_t)(K * (W + H)) * 3u);
    TEST_ASSERT_TRUE(n.old_diff > (uint32_t)NPIX * 20u);
}

/* reset: every column and row young again */
static void test_reset_makes_every_cell_young(void)
{
    pft_pre_clutter_config_t cfg;
    pft_pre_clutter_config_default(&cfg);
    cfg.mean = true;
    cfg.thr = 65535u;
    cfg.mean_floor = 128u;
    cfg.floor_age = (uint8_t)K;
    pft_pre_clutter_t c;
    pft_test_clutter_init(&c, &cfg, W, H, g_work, sizeof g_work);
    for (uint32_t k = 0; k < 2u * K; ++k) {
        for (int i = 0; i < NPIX; ++i) {
            g_res[i] = (int16_t)pft_test_noise_q88(&g_rs);
        }
        pft_frame_t f = res_frame(k + 1u);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_update(&c, &f, 0, 0, true));
    }
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_reset(&c));
    uint32_t nd = 0u;
    for (uint32_t k = 0; k < 3u; ++k) {
        for (int i = 0; i < NPIX; ++i) {
            g_res[i] = (int16_t)pft_test_noise_q88(&g_rs);
        }
        memcpy(g_mu0, c.mu, sizeof g_mu0);
        pft_frame_t f = res_frame(100u + k);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_update(&c, &f, 0, 0, true));
        const int16_t *o = pft_test_clutter_out(&c);
        for (int i = 0; i < NPIX; ++i) {
            const int32_t mq = pft_test_clutter_mu_q88(g_mu0[i]);
            nd += (mq != 0 && (mq < 0 ? -mq : mq) <= 128) ? 1u : 0u;
            TEST_ASSERT_EQUAL_INT16((int16_t)(g_res[i] - mq), o[i]);
        }
    }
    /* frames 2 and 3 after the reset: |mu| <= 0.5 sigma on about 38 % and 52 % of the cells */
    TEST_ASSERT_TRUE(nd > (uint32_t)NPIX / 2u);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_config);
    RUN_TEST(test_young_cells_take_the_plain_mean_carry);
    RUN_TEST(test_young_cells_take_the_plain_mean_anchor);
    RUN_TEST(test_reset_makes_every_cell_young);
    return UNITY_END();
}
