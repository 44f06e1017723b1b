/*
 * Gain selection (docs/algorithms.md 4.4 step 4, field gain_select; issue #10): a white target
 * (channel value 236, 6 above the edge 230.4 of the top bin) on a grey textured background
 * under a camera gain that alternates between 1 and 0.95 from frame to frame (236 -> 224, the
 * next bin down), as the swing scenarios' gain flicker did to a white vehicle.
 * - gain_select on: every frame is TRACKING, the centre error stays below 2 px and rho at the
 *   estimate at least 0.9, for TSA and TS (NCV is not checked: on this small target at
 *   1 px/frame it leaves TRACKING on a few frames even without flicker);
 * - gain_select off (one template): on the dimmed frames the whole body changes bin, rho at
 *   the target falls below rho_min and the tracker leaves TRACKING (the failure the selection
 *   removes; if this stops happening the first part no longer tests anything).
 */
#include <math.h>
#include <string.h>
#include "pft_test_support.h"
#include "pft/pft_tsa.h"

void setUp(void) {}
void tearDown(void) {}

#define W 160
#define H 48
#define TW 14
#define TH 10
#define NP 60
#define MAXT 32
#define PTS 24
#define FRAMES 40

static uint8_t img[H][W][3];
static uint8_t work[PFT_TSA_WORKSPACE_BYTES(NP, MAXT, MAXT, PTS, 6, 48)];
static pft_tsa_t trk;

/* The scene at frame k (target's left column x0) under the gain g256 / 256. */
static void render(int x0, uint32_t g256)
{
    uint32_t s = 7u;
    const int y0 = (H - TH) / 2;
    for (int y = 0; y < H; ++y) {
        for (int x = 0; x < W; ++x) {
            s = s * 1664525u + 1013904223u;
            uint32_t v[3] = {80u + (s >> 26), 90u + (s >> 26), 70u + (s >> 26)};
            if (x >= x0 && x < x0 + TW && y >= y0 && y < y0 + TH) {
                const uint32_t body = y < y0 + 3 && x > x0 + 2 && x < x0 + TW - 3 ? 40u : 236u;
                v[0] = body;
                v[1] = body;
                v[2] = body;
            }
            for (int c = 0; c < 3; ++c) {
                const uint32_t u = (v[c] * g256 + 128u) >> 8;
                img[y][x][c] = (uint8_t)(u > 255u ? 255u : u);
            }
        }
    }
}

static pft_frame_t frame(void) { return pft_test_rgb_frame(img, W, H); }

/* Initialises the tracker (motion m, gain selection on or off, the kernel the given box) and
 * starts it on the target's box at left column x0, gain 1; *ox, *oy: the estimate's offset from
 * the box's top-left corner, which the error measures keep. */
static void start_at(pft_tsa_motion_kind_t m, bool gain_select, int x0, double *ox, double *oy)
{
    pft_tsa_config_t c;
    pft_test_tsa_config(&c, W, H, MAXT, NP, PTS);
    c.init_passes = 0; /* the kernel is the given box */
    c.motion = m;
    c.gain_select = gain_select;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_init(&trk, &c, work, sizeof work));
    const int y0 = (H - TH) / 2;
    render(x0, 256u);
    pft_frame_t f = frame();
    pft_tsa_pt_t b[4];
    pft_test_box_corners(b, x0, y0, x0 + TW - 1, y0 + TH - 1);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_start(&trk, &f, b, 4));
    pft_tsa_estimate_t e;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_estimate(&trk, &e));
    *ox = (double)pft_to_float(e.x) - x0;
    *oy = (double)pft_to_float(e.y) - y0;
}

/* Tracks FRAMES frames (target moving right 1 px/frame, gain 1 and 0.95 alternately); returns
 * the frames not TRACKING, the largest centre error and the smallest rho at the estimate. */
static int run(pft_tsa_motion_kind_t m, bool gain_select, double *max_err, double *min_rho)
{
    const int y0 = (H - TH) / 2;
    int x0 = 20;
    double ox, oy;
    start_at(m, gain_select, x0, &ox, &oy);
    pft_frame_t f = frame();
    pft_tsa_estimate_t e;
    int not_tracking = 0;
    *max_err = 0.0;
    *min_rho = 1.0;
    for (int k = 1; k < FRAMES; ++k) {
        ++x0;
        render(x0, (k & 1) ? 243u : 256u);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_update(&trk, &f));
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_estimate(&trk, &e));
        not_tracking += e.state != PFT_TSA_TRACKING;
        const double err = hypot((double)pft_to_float(e.x) - ox - x0, (double)pft_to_float(e.y) - oy - y0);
        *max_err = err > *max_err ? err : *max_err;
        const double r = (double)pft_to_float(e.rho);
        *min_rho = r < *min_rho ? r : *min_rho;
    }
    return not_tracking;
}

static void check_on(pft_tsa_motion_kind_t m)
{
    double err, rho;
    const int bad = run(m, true, &err, &rho);
    TEST_ASSERT_EQUAL_INT(0, bad);
    TEST_ASSERT_TRUE(err < 2.0);
    TEST_ASSERT_TRUE(rho >= 0.9);
}

static void test_gain_select_tracks_tsa(void) { check_on(PFT_TSA_MOTION_TSA); }
static void test_gain_select_tracks_ts(void) { check_on(PFT_TSA_MOTION_TS); }

static void test_one_template_loses_the_dimmed_frames(void)
{
    double err, rho;
    const int bad = run(PFT_TSA_MOTION_TSA, false, &err, &rho);
    TEST_ASSERT_TRUE(bad > 0);
    TEST_ASSERT_TRUE(rho < 0.75);
}

/* Sudden steps under flicker: the target moves 1 px/frame and steps JUMP px more every STEP_EVERY
 * frames, the gain changes on every frame (0.85-1.1); every frame must be TRACKING with the centre
 * within 3 px (the frames of a step excepted). A regression check of the gain choice at several
 * placements (gain_select_), not a test that tells it from the choice at the prediction alone:
 * this scene passes with both (the swing sequences' off-target matches of a darker template,
 * docs/results/tsa_ak.md, are not reproduced by this two-colour target). Returns the largest
 * centre error over the frames after the first step, the frames of a step excepted. */
#define JUMP 4
#define STEP_EVERY 6
static double run_steps(pft_tsa_motion_kind_t m, int *not_tracking)
{
    static const uint32_t gains[8] = {256u, 230u, 269u, 218u, 243u, 282u, 224u, 262u};
    const int y0 = (H - TH) / 2;
    int x0 = 12;
    double ox, oy;
    start_at(m, true, x0, &ox, &oy);
    pft_frame_t f = frame();
    pft_tsa_estimate_t e;
    double worst = 0.0;
    *not_tracking = 0;
    for (int k = 1; k < FRAMES * 2 && x0 + TW + 2 * JUMP < W; ++k) {
        x0 += 1 + (k % STEP_EVERY == 0 ? JUMP : 0);
        render(x0, gains[k % 8]);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_update(&trk, &f));
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_estimate(&trk, &e));
        *not_tracking += e.state != PFT_TSA_TRACKING;
        const double err = hypot((double)pft_to_float(e.x) - ox - x0, (double)pft_to_float(e.y) - oy - y0);
        if (k % STEP_EVERY != 0 && k > STEP_EVERY) {
            worst = err > worst ? err : worst;
        }
    }
    return worst;
}

static void test_gain_select_at_steps(void)
{
    int bad = 0;
    const double err = run_steps(PFT_TSA_MOTION_TSA, &bad);
    TEST_ASSERT_EQUAL_INT(0, bad);
    TEST_ASSERT_TRUE(err < 3.0);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_gain_select_tracks_tsa);
    RUN_TEST(test_gain_select_tracks_ts);
    RUN_TEST(test_one_template_loses_the_dimmed_frames);
    RUN_TEST(test_gain_select_at_steps);
    return UNITY_END();
}
