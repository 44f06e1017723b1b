/*
 * The tile sigma taken about the tile's level (pft_pre_config_t.sigma_level, docs/algorithms.md
 * 9.6): the configuration check and workspace; a residual that is a steep plane plus noise of
 * known sigma gives that sigma within 5 % with the option and an inflated one without (a MAD
 * about zero); refused configuration and input leave the instance and the workspace
 * byte-identical. Frames are 96 x 72 (every target, Cortex-M under QEMU included); the scene is
 * made with integer arithmetic per pixel.
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
#define NT ((W / TILE) * (H / TILE))
#define SIGMA 10.0 /* noise, counts */

static uint16_t g_img[NPIX];
static uint64_t g_work[(PFT_PRE_WORKSPACE_BYTES(W, H, PFT_PRE_BG_LOCAL, 4, TILE, 64) +
                        PFT_PRE_LEVEL_BYTES(W, H, TILE)) / 8 + 8];
static uint64_t g_copy[sizeof(g_work) / 8];
static uint32_t g_sig[NT];
static uint32_t g_rs = 2463534242u;

/* The local background (9 x 9 window less its 3 x 3 guard, the border band masked), column
 * offsets off (the residual below is constant along each column), sigma held per tile. */
static void config(pft_pre_config_t *c, bool level)
{
    pft_pre_config_default(c);
    c->width = W;
    c->height = H;
    c->method = PFT_PRE_BG_LOCAL;
    c->tile = TILE;
    c->col_alpha = 0u;
    c->sigma_interp = false;
    c->sigma_level = level;
}

/* A cubic along x, K (x - X0)^3 (K = 0.009, X0 = -24: 124 .. 15552 counts) over 300 counts,
 * plus noise of sd SIGMA (pft_test_noise_sum4: the sum of four uniforms, whose 1.4826 median |x|
 * is 1.0342 times its sd, solved from the Irwin-Hall distribution's CDF), rounded to 14 bits. The local mean of a cubic
 * over a window symmetric about the pixel is the cubic plus 3 K E[dx^2] (x - X0), so the
 * residual is the plane -3 K E[dx^2] (x - X0) plus the noise, E[dx^2] = 534 / 72 over the 72
 * pixels of the ring: -0.200 (x - X0) counts, 0.72 to 2.16 SIGMA at the tile centres (a steep
 * plane: the offset of each tile is large against the noise), 0.48 SIGMA across one tile. */
#define K_CUBIC 0.009
#define X0 (-24.0)
static void render(void)
{
    static double col[W];
    for (int x = 0; x < W; ++x) {
        const double u = x - X0;
        col[x] = 300.0 + K_CUBIC * u * u * u;
    }
    for (int y = 0; y < H; ++y) {
        for (int x = 0; x < W; ++x) {
            const double v = floor(col[x] + SIGMA * pft_test_noise_sum4(&g_rs) / 2365.0 + 0.5);
            g_img[y * W + x] = (uint16_t)(v < 0.0 ? 0.0 : (v > 16383.0 ? 16383.0 : v));
        }
    }
}

/* ------------------------------------------------------------------ configuration */

static void test_config(void)
{
    pft_pre_config_t c;
    pft_pre_config_default(&c);
    TEST_ASSERT_FALSE(c.sigma_level); /* off by default */
    config(&c, true);
    const char *field = NULL;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_config_check(&c, &field));
    pft_pre_config_t d = c;
    d.sigma_level = false;
    TEST_ASSERT_EQUAL_UINT64(pft_pre_workspace_size(&d) + PFT_PRE_LEVEL_BYTES(W, H, TILE),
                             pft_pre_workspace_size(&c));
    TEST_ASSERT_TRUE(pft_pre_workspace_size(&c) <= sizeof(g_work));
    /* temporal and anchored: the same bytes more */
    pft_pre_config_t e = c;
    e.method = PFT_PRE_BG_TEMPORAL;
    e.bg_anchor = true;
    pft_pre_config_t f = e;
    f.sigma_level = false;
    TEST_ASSERT_EQUAL_UINT64(pft_pre_workspace_size(&f) + PFT_PRE_LEVEL_BYTES(W, H, TILE),
                             pft_pre_workspace_size(&e));
    for (int i = 0; i < 3; ++i) {
        d = c;
        if (i == 0) {
            d.sigma_step = 2u;
        } else if (i == 1) {
            d.sigma_every = 2u;
        } else {
            d.sigma_bracket = true;
        }
        TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_pre_config_check(&d, &field));
        TEST_ASSERT_EQUAL_STRING("sigma_level", field);
        TEST_ASSERT_EQUAL_UINT64(0u, pft_pre_workspace_size(&d));
    }
}

/* ------------------------------------------------------------------ known answer */

/* The mean of the tiles' sigmas (counts) over frames 3..5 (the level of frame k is the one of
 * frame k - 1), and the smallest and largest tile of frame 5 over its expected value. */
static double run(bool level, double expect, double *lo, double *hi)
{
    pft_pre_config_t c;
    config(&c, level);
    pft_pre_t p;
    pft_test_pre_init(&p, &c, g_work, sizeof(g_work));
    double sum = 0.0;
    int n = 0;
    for (uint32_t k = 0; k < 6u; ++k) {
        render();
        const pft_frame_t f = pft_test_u16_frame(g_img, W, H, 14u, k);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_update(&p, &f));
        TEST_ASSERT_EQUAL_UINT32(NT, (uint32_t)pft_pre_sigma(&p, g_sig, NT));
        *lo = 1e9;
        *hi = 0.0;
        for (int i = 0; i < NT; ++i) {
            const double s = g_sig[i] / 65536.0;
            if (k >= 3u) {
                sum += s;
                n++;
            }
            *lo = s / expect < *lo ? s / expect : *lo;
            *hi = s / expect > *hi ? s / expect : *hi;
        }
    }
    return sum / n;
}

/* A steep plane plus noise: with sigma_level the tiles' sigma is the noise's, 1.0342 SIGMA (the
 * MAD of the sum of four uniforms, above) times sqrt(1 + 1/72) (the local mean of 72 noisy
 * pixels) times sqrt(1 + 0.48^2 / 12 / 1.014) for
 * the plane's spread within a tile (a uniform of 0.48 SIGMA: +1.0 %), within 5 % for the mean
 * of 12 tiles over 3 frames (the MAD of 36 x 480 unmasked pixels: a standard error of about
 * 1 %) and within 20 % per tile (480 pixels: about 5 %); without it each tile's MAD about zero
 * reads the plane's offset (0.72 to 2.16 sigma at the tile centres; 1.4826 times the median of
 * |N(0.72, 1)| alone is 1.26) and the mean is at least 1.5 times the noise's (about twice). */
static void test_steep_plane_gives_sigma(void)
{
    const double expect = 1.0342 * SIGMA * sqrt(1.0 + 1.0 / 72.0) * sqrt(1.0 + 0.48 * 0.48 / 12.0 / 1.014);
    double lo_on, hi_on, lo_off, hi_off;
    g_rs = 2463534242u;
    const double on = run(true, expect, &lo_on, &hi_on);
    g_rs = 2463534242u;
    const double off = run(false, expect, &lo_off, &hi_off);
    char msg[160];
    snprintf(msg, sizeof msg, "mean tile sigma %.2f with sigma_level (tiles %.3f..%.3f), %.2f without "
             "(%.3f..%.3f), expected %.2f", on, lo_on, hi_on, off, lo_off, hi_off, expect);
    UnityPrint(msg);
    UNITY_PRINT_EOL();
    TEST_ASSERT_DOUBLE_WITHIN_MESSAGE(0.05 * expect, expect, on, msg);
    TEST_ASSERT_TRUE_MESSAGE(lo_on > 0.8 && hi_on < 1.2, msg);
    TEST_ASSERT_TRUE_MESSAGE(off > 1.5 * expect, msg);
}

/* ------------------------------------------------------------------ refused input */

static void test_refused_leaves_everything(void)
{
    pft_pre_config_t c;
    config(&c, true);
    pft_pre_t p;
    pft_test_pre_init(&p, &c, g_work, sizeof(g_work));
    render();
    const pft_frame_t f = pft_test_u16_frame(g_img, W, H, 14u, 0u);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_update(&p, &f));
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_update(&p, &f)); /* a level known */
    const size_t need = pft_pre_workspace_size(&c);
    /* a refused configuration */
    pft_pre_config_t d = c;
    d.sigma_bracket = true;
    pft_test_pre_init_refused(&p, &d, g_work, need, g_copy);
    /* a refused frame (wrong bit depth) */
    const pft_pre_t before = p;
    memcpy(g_copy, g_work, need);
    const pft_frame_t bad = pft_test_u16_frame(g_img, W, H, 12u, 2u);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_FORMAT, pft_pre_update(&p, &bad));
    TEST_ASSERT_EQUAL_MEMORY(&before, &p, sizeof p);
    TEST_ASSERT_EQUAL_MEMORY(g_copy, g_work, need);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_config);
    RUN_TEST(test_steep_plane_gives_sigma);
    RUN_TEST(test_refused_leaves_everything);
    return UNITY_END();
}
