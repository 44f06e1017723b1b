/*
 * The acceptance of a re-acquisition with the background-weighted template (config acquire_on,
 * docs/algorithms.md 4.4; issue #10, branch tsa15). A 12 x 12 target, left half colour
 * A = (230, 30, 30), right half B = (30, 230, 230), on a background of colour A with one 4 x 4
 * patch of colour C = (130, 130, 130) in the ring (bg_ring 3, bg_alpha 1): the weighting keeps
 * B's bins and nearly drops A's (A fills the ring), so the weighted template is almost all B.
 * From frame 2 the target is gone and a 12 x 12 decoy of colour B alone stands elsewhere, like
 * the dark window of vtest.avi that shares the dark clothes' colour. Per channel the decoy's
 * similarity to the weighted template q_w is about sqrt(q_w(B)) ~ 0.99, and rho0 (q_w against
 * the half-A half-B target) about sqrt(q_w(A) / 2) + sqrt(q_w(B) / 2) ~ 0.79, so the scaled rho
 * is ~1.26 >= rho_acquire 0.88; against the unweighted template (half A, half B) the decoy has
 * sqrt(1 / 2) ~ 0.71 < 0.88 (the margins, not the exact figures, are what the asserts rely on).
 * - acquire_on 0 (the tracker's scaled rho alone): the decoy is re-acquired;
 * - acquire_on 1 (and the unweighted template's rho): it is not, and the estimate stays at the
 *   last good position; the target's own look (half A, half B) at the decoy's place, the
 *   decoy gone, is then re-acquired.
 */
#include <math.h>
#include <string.h>
#include "pft_test_support.h"
#include "pft/pft_tsa.h"

void setUp(void) {}
void tearDown(void) {}

#define W 96
#define H 96
#define T0 42 /* the target's first column and row at the start */
#define TS 12 /* its side */
#define DX 8  /* the decoy's first column and row */
#define DY 70
#define NP 40
#define MAXT 32
#define PTS 24
#define FRAMES 30
#define TOL 6.0 /* px: half the target's side */

static uint8_t img[H][W][3];
static uint8_t work[PFT_TSA_WORKSPACE_BYTES(NP, MAXT, MAXT, PTS, 6, 48)];
static pft_tsa_t trk;

static void paint(int x, int y, uint8_t r, uint8_t g, uint8_t b)
{
    img[y][x][0] = r;
    img[y][x][1] = g;
    img[y][x][2] = b;
}

/* background A with the C patch; the target with its first column and row at tx, ty (tx < 0:
 * none); the decoy when decoy is set */
static void render(int tx, int ty, bool decoy)
{
    for (int y = 0; y < H; ++y) {
        for (int x = 0; x < W; ++x) {
            paint(x, y, 230, 30, 30); /* A */
        }
    }
    for (int y = 32; y < 36; ++y) {
        for (int x = 32; x < 36; ++x) {
            paint(x, y, 130, 130, 130); /* C: inside the ring of the start */
        }
    }
    if (tx >= 0) {
        for (int y = ty; y < ty + TS; ++y) {
            for (int x = tx + TS / 2; x < tx + TS; ++x) {
                paint(x, y, 30, 230, 230); /* B: the target's right half */
            }
        }
    }
    if (decoy) {
        for (int y = DY; y < DY + TS; ++y) {
            for (int x = DX; x < DX + TS; ++x) {
                paint(x, y, 30, 230, 230); /* B alone */
            }
        }
    }
}

static void start(uint8_t acquire_on)
{
    pft_tsa_config_t c;
    pft_test_tsa_config(&c, W, H, MAXT, NP, PTS);
    c.init_passes = 0;
    c.bg_ring = PFT_C(3.0);
    c.bg_alpha = PFT_C(1.0);
    c.acquire_on = acquire_on;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_init(&trk, &c, work, sizeof work));
    render(T0, T0, false);
    pft_frame_t f = pft_test_rgb_frame(img, W, H);
    pft_tsa_pt_t b[4];
    pft_test_box_corners(b, T0, T0, T0 + TS - 1, T0 + TS - 1);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_start(&trk, &f, b, 4));
}

/* Runs frames of (tx, ty, decoy); returns how many reported REACQUIRED, the last estimate in
 * *e. */
static int run(int n, int tx, int ty, bool decoy, pft_tsa_estimate_t *e)
{
    int reacq = 0;
    render(tx, ty, decoy);
    pft_frame_t f = pft_test_rgb_frame(img, W, H);
    for (int i = 0; i < n; ++i) {
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_update(&trk, &f));
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_estimate(&trk, e));
        reacq += e->state == PFT_TSA_REACQUIRED;
    }
    return reacq;
}

static double dist(const pft_tsa_estimate_t *e, double x, double y)
{
    return hypot((double)pft_to_float(e->x) - x, (double)pft_to_float(e->y) - y);
}

static const double decoy_cx = DX + (TS - 1) / 2.0, decoy_cy = DY + (TS - 1) / 2.0;

/* acquire_on 0: the scaled rho alone takes the decoy */
static void test_scaled_rho_takes_the_decoy(void)
{
    pft_tsa_estimate_t e;
    start(0u);
    const int reacq = run(FRAMES, -1, 0, true, &e);
    TEST_ASSERT_TRUE(reacq >= 1);
    TEST_ASSERT_TRUE(dist(&e, decoy_cx, decoy_cy) < TOL);
}

/* acquire_on 1: the decoy is refused, the estimate held at the last good position; the
 * target's own look at the decoy's place is re-acquired */
static void test_unweighted_rho_refuses_the_decoy(void)
{
    pft_tsa_estimate_t e;
    start(1u);
    const double cx = T0 + (TS - 1) / 2.0, cy = T0 + (TS - 1) / 2.0;
    TEST_ASSERT_EQUAL_INT(0, run(FRAMES, -1, 0, true, &e));
    TEST_ASSERT_TRUE(e.state == PFT_TSA_LOST);
    TEST_ASSERT_TRUE(dist(&e, decoy_cx, decoy_cy) > 2.0 * TS); /* 44 px apart */
    TEST_ASSERT_TRUE(dist(&e, cx, cy) < TOL);
    /* the target's own look (half A, half B) where the decoy stood, the decoy gone: it passes
     * both similarities and is re-acquired (the search found that place above) */
    const int reacq = run(FRAMES, DX, DY, false, &e);
    TEST_ASSERT_TRUE(reacq >= 1);
    TEST_ASSERT_TRUE(e.state == PFT_TSA_TRACKING);
    TEST_ASSERT_TRUE(dist(&e, decoy_cx, decoy_cy) < TOL);
}

static void test_config_range(void)
{
    pft_tsa_config_t c;
    pft_tsa_config_default(&c);
    c.width = W;
    c.height = H;
    const char *field = NULL;
    for (uint8_t v = 0u; v <= 2u; ++v) {
        c.acquire_on = v;
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_config_check(&c, &field));
    }
    c.acquire_on = 3u;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_tsa_config_check(&c, &field));
    TEST_ASSERT_EQUAL_STRING("acquire_on", field);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_scaled_rho_takes_the_decoy);
    RUN_TEST(test_unweighted_rho_refuses_the_decoy);
    RUN_TEST(test_config_range);
    return UNITY_END();
}
