/*
 * The clutter map's mean floor (pft_pre_clutter_config_t.mean_floor, docs/algorithms.md 9.9):
 * the configuration check names the field (needs mean, per pixel only, at most 8 sigma); the
 * default is 0; with the floor every output is r - mu where |mu| (rounded to Q8.8) exceeds the
 * floor and r elsewhere, bit for bit against a reference that reads mu before the frame
 * (thr at its largest, so that nothing is scored); the map m learns that c; refused input
 * leaves instance and workspace byte for byte unchanged (that a persistent offset is still
 * removed with the floor is test_pre_clutter's test_mean_removes_offset_with_floor). 64 x 48
 * frames, integer residuals made per pixel, so that it runs on every target.
 */
#include <string.h>

#include "pft_test_support.h"
#include "pft/pft_pre.h"

void setUp(void) {}
void tearDown(void) {}

#define W 64
#define H 48
#define NPIX (W * H)

static int16_t g_res[NPIX];
static uint16_t g_mu0[NPIX];
static uint16_t g_m0[NPIX];
static uint64_t g_work[PFT_PRE_CLUTTER_WORKSPACE_BYTES(W, H, 1, PFT_PRE_CLUTTER_MAX_BLUR, 1) / 8 + 1];
static uint64_t g_copy[sizeof(g_work) / 8];
static uint32_t g_rs = 88172645u;

static pft_frame_t res_frame(uint32_t seq)
{
    return pft_test_res16_frame(g_res, W, H, seq, 1000u * seq);
}

static void test_config(void)
{
    pft_pre_clutter_config_t cfg;
    pft_pre_clutter_config_default(&cfg);
    TEST_ASSERT_EQUAL_UINT16(0u, cfg.mean_floor);
    const char *field = NULL;
    static const struct {
        bool mean;
        uint8_t block;
        uint16_t floor;
        pft_status_t want;
    } cases[] = {{true, 0u, 128u, PFT_OK},           {true, 0u, 2048u, PFT_OK},
                 {false, 0u, 128u, PFT_ERR_CONFIG},  {true, 2u, 128u, PFT_ERR_CONFIG},
                 {true, 0u, 2049u, PFT_ERR_CONFIG},  {false, 2u, 0u, PFT_OK}};
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        pft_pre_clutter_config_t b = cfg;
        b.mean = cases[i].mean;
        b.block = cases[i].block;
        b.mean_floor = cases[i].floor;
        field = "x";
        TEST_ASSERT_EQUAL_INT(cases[i].want, pft_pre_clutter_config_check(&b, &field));
        if (cases[i].want == PFT_OK) {
            TEST_ASSERT_NULL(field);
        } else {
            TEST_ASSERT_EQUAL_STRING("mean_floor", field);
            TEST_ASSERT_EQUAL_UINT32(0u, (uint32_t)pft_pre_clutter_workspace_size(&b));
        }
    }
}

/* Frames of unit noise with a 3 x 3 blob of 1 sigma (its mean settles near 1 sigma, above a
 * floor of 0.5, while the noise's mean mostly stays under it); thr at its largest, so that the
 * output is c exactly: every pixel against the reference c = r - (|mu| > floor ? mu : 0), mu
 * read before the frame, and the map m against its update on that c. Floors 0 (the plain mean:
 * c = r - mu everywhere) and 128 (0.5 sigma). With the floor, pixels on both sides of it. */
static void test_output_is_r_less_mu_above_floor(void)
{
    static const uint16_t floors[2] = {0u, 128u};
    for (int fi = 0; fi < 2; ++fi) {
        pft_pre_clutter_config_t cfg;
        pft_pre_clutter_config_default(&cfg);
        cfg.mean = true;
        cfg.thr = 65535u;
        cfg.mean_floor = floors[fi];
        pft_pre_clutter_t c;
        pft_test_clutter_init(&c, &cfg, W, H, g_work, sizeof g_work);
        uint32_t n_above = 0u, n_below = 0u;
        for (uint32_t k = 0; k < 40u; ++k) {
            for (int i = 0; i < NPIX; ++i) {
                g_res[i] = (int16_t)pft_test_noise_q88(&g_rs);
            }
            for (int y = 20; y < 23; ++y) {
                for (int x = 30; x < 33; ++x) {
                    g_res[y * W + x] = (int16_t)(g_res[y * W + x] + 256);
                }
            }
            memcpy(g_mu0, c.mu, sizeof g_mu0);
            memcpy(g_m0, c.m, sizeof g_m0);
            pft_frame_t f = res_frame(k + 1u);
            TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_update(&c, &f, 0, 0, true));
            const int16_t *o = pft_test_clutter_out(&c);
            const uint32_t a = k + 1u < 10u ? (65536u + (k + 1u) / 2u) / (k + 1u) : 6554u; /* max(alpha, 1/n) */
            for (int i = 0; i < NPIX; ++i) {
                const int32_t mq = pft_test_clutter_mu_q88(g_mu0[i]);
                const int32_t am = mq < 0 ? -mq : mq;
                const bool take = am > (int32_t)floors[fi];
                if (k >= 10u) {
                    n_above += take ? 1u : 0u;
                    n_below += take ? 0u : 1u;
                }
                const int32_t cv = g_res[i] - (take ? mq : 0);
                TEST_ASSERT_EQUAL_INT16((int16_t)cv, o[i]);
                if (a >= 65536u) {
                    continue; /* the first frame: m takes c^2 whole */
                }
                const int64_t sq = (int64_t)cv * cv;
                const int64_t t = (sq + 32) / 64 > 65535 ? 65535 : (sq + 32) / 64;
                const int64_t d = t - (int64_t)g_m0[i];
                const int64_t q = ((int64_t)a * (d < 0 ? -d : d) + 32768) / 65536;
                TEST_ASSERT_EQUAL_UINT16((uint16_t)(g_m0[i] + (d < 0 ? -q : q)), c.m[i]);
            }
        }
        if (floors[fi] != 0u) {
            /* both sides of the floor were checked: the blob's 9 pixels above it in frames
             * 11..40 (its mean near 1 sigma), most noise pixels below it (the mean of unit
             * noise at alpha 0.1 has sd about 0.23 sigma: |mu| > 0.5 on about 3 % of them) */
            TEST_ASSERT_TRUE(n_above >= 9u * 30u);
            TEST_ASSERT_TRUE(n_below > (uint32_t)NPIX * 30u / 2u);
        }
    }
}

/* The floor with the anchored map (anchor, docs/algorithms.md 9.9): the scene moves 0.6 px per
 * frame in x and -0.4 px in y; the map's arrays move by whole pixels when the rounded position
 * of the summed shifts moves, the cells that enter holding mu 0; the floor then reads the moved
 * mean. The 3 x 3 blob of 1 sigma is fixed to the scene's grid (it moves with the rounded
 * position), so its cells' mean settles near 1 sigma, above the floor of 0.5 sigma. Every pixel
 * against the reference c = r - (|mu'| > floor ? mu' : 0), mu' the mean read before the frame
 * moved as the anchor moves it (out(x, y) = mu(x - dx, y - dy), 0 where the source is outside).
 * Fails if the floor were skipped on the anchored path (the blob's pixels) or read the mean
 * before its move (every pixel near the blob and the entering edges). */
static void test_floor_reads_the_anchored_mean(void)
{
    static uint16_t mv[NPIX];
    pft_pre_clutter_config_t cfg;
    pft_pre_clutter_config_default(&cfg);
    cfg.mean = true;
    cfg.thr = 65535u;
    cfg.anchor = true;
    cfg.mean_floor = 128u;
    pft_pre_clutter_t c;
    pft_test_clutter_init(&c, &cfg, W, H, g_work, sizeof g_work);
    const int32_t sx = 39322, sy = -26214; /* 0.6 and -0.4 px in Q16.16 */
    int64_t ax = 0, ay = 0, px = 0, py = 0;
    uint32_t n_above = 0u, n_below = 0u, n_moves = 0u;
    for (uint32_t k = 0; k < 40u; ++k) {
        ax += sx;
        ay += sy;
        /* the rounded position, halves upwards (floor((a + 2^15) / 2^16)) */
        const int64_t nx = (ax + 32768 >= 0) ? (ax + 32768) / 65536 : -((-(ax + 32768) + 65535) / 65536);
        const int64_t ny = (ay + 32768 >= 0) ? (ay + 32768) / 65536 : -((-(ay + 32768) + 65535) / 65536);
        const int32_t dx = k == 0u ? 0 : (int32_t)(nx - px), dy = k == 0u ? 0 : (int32_t)(ny - py);
        n_moves += (dx != 0 || dy != 0) ? 1u : 0u;
        px = nx;
        py = ny;
        for (int i = 0; i < NPIX; ++i) {
            g_res[i] = (int16_t)pft_test_noise_q88(&g_rs);
        }
        for (int y = 20; y < 23; ++y) {
            for (int x = 20; x < 23; ++x) {
                const int64_t yy = y + ny, xx = x + nx; /* the scene-fixed blob, in frame pixels */
                g_res[yy * W + xx] = (int16_t)(g_res[yy * W + xx] + 256);
            }
        }
        for (int y = 0; y < H; ++y) {
            for (int x = 0; x < W; ++x) {
                const int sxp = x - dx, syp = y - dy;
                const bool in = sxp >= 0 && sxp < W && syp >= 0 && syp < H;
                mv[y * W + x] = in ? c.mu[syp * W + sxp] : (uint16_t)32768u;
            }
        }
        pft_frame_t f = res_frame(k + 1u);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_update(&c, &f, sx, sy, true));
        const int16_t *o = pft_test_clutter_out(&c);
        for (int i = 0; i < NPIX; ++i) {
            const int32_t mq = pft_test_clutter_mu_q88(mv[i]);
            const bool take = (mq < 0 ? -mq : mq) > (int32_t)cfg.mean_floor;
            if (k >= 10u) {
                n_above += take ? 1u : 0u;
                n_below += take ? 0u : 1u;
            }
            TEST_ASSERT_EQUAL_INT16((int16_t)(g_res[i] - (take ? mq : 0)), o[i]);
        }
    }
    /* the anchor moved on most frames (0.6 px a frame in x), the blob's 9 cells above the floor
     * in frames 11..40, most noise cells below it */
    TEST_ASSERT_TRUE(n_moves >= 20u);
    TEST_ASSERT_TRUE(n_above >= 9u * 30u);
    TEST_ASSERT_TRUE(n_below > (uint32_t)NPIX * 30u / 2u);
}

static void test_refused_input_changes_nothing(void)
{
    pft_pre_clutter_config_t cfg;
    pft_pre_clutter_config_default(&cfg);
    cfg.mean = true;
    cfg.persist = 3u;
    cfg.mean_floor = 128u;
    pft_pre_clutter_t c;
    pft_test_clutter_init(&c, &cfg, W, H, g_work, sizeof g_work);
    for (uint32_t k = 0; k < 5u; ++k) {
        for (int i = 0; i < NPIX; ++i) {
            g_res[i] = (int16_t)pft_test_noise_q88(&g_rs);
        }
        pft_frame_t f = res_frame(k + 1u);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_update(&c, &f, 19661, -6554, true));
    }
    pft_pre_clutter_t saved = c;
    memcpy(g_copy, g_work, sizeof g_work);
    pft_frame_t b = res_frame(9u);
    b.width = W - 1;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_FORMAT, pft_pre_clutter_update(&c, &b, 0, 0, true));
    b = res_frame(9u);
    b.data = NULL;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_pre_clutter_update(&c, &b, 0, 0, true));
    TEST_ASSERT_EQUAL_MEMORY(&saved, &c, sizeof c);
    TEST_ASSERT_EQUAL_MEMORY(g_copy, g_work, sizeof g_work);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_config);
    RUN_TEST(test_output_is_r_less_mu_above_floor);
    RUN_TEST(test_floor_reads_the_anchored_mean);
    RUN_TEST(test_refused_input_changes_nothing);
    return UNITY_END();
}
