/*
 * A sudden reversal (issue #10): a textured target (14 x 10 px) speeds up to 12 px/frame at
 * 2 px/frame^2, cruises, reverses at 5 px/frame^2 to -13 px/frame and cruises back, over a
 * textured background (320 x 64 RGB). With the default dynamics (fit over K = 4 reference
 * points with sigma_G = 2, position diffusion 2 px widened by the innovation up to 8 px) TSA
 * keeps every frame within 7 px (half the target's length) in at least 7 of 8 seeds, and so
 * does TS. The paper's settings as the library had them before (K = 10, sigma_G = 5, a fixed
 * diffusion of 2 px) are run on the same frames and printed: their fit lags the reversal by
 * several frames and the narrow cloud cannot reach the target (docs/results/tsa.md).
 */
#include <math.h>
#include <string.h>
#include "pft_test_support.h"
#include "pft/pft_tsa.h"

void setUp(void) {}
void tearDown(void) {}

#define W 320
#define H 64
#define TW 14
#define TH 10
#define NP 100
#define MAXT 32
#define PTS 24
#define FRAMES 34
#define TRACK_TOL 7.0
#define SEEDS 8
#define MIN_OK 7

static uint8_t img[H][W][3];
static uint8_t bg[H][W][3];
static uint8_t work[PFT_TSA_WORKSPACE_BYTES(NP, MAXT, MAXT, PTS, 6, 48)];
static pft_tsa_t trk;
static double truth[FRAMES];

/* Speeds: 0, 2, .., 12 (2 px/frame^2), 12 for 8 frames, 7, 2, -3, -8, -13 (5 px/frame^2), -13. */
static void make_truth(void)
{
    double x = 70.0, v = 0.0;
    for (int k = 0; k < FRAMES; ++k) {
        truth[k] = x;
        if (k < 6) {
            v += 2.0;
        } else if (k >= 14 && k < 19) {
            v -= 5.0;
        }
        x += v;
    }
}

static void make_background(void)
{
    uint32_t s = 31u;
    for (int y = 0; y < H; ++y) {
        for (int x = 0; x < W; ++x) {
            s = s * 1664525u + 1013904223u;
            bg[y][x][0] = (uint8_t)(70 + (s >> 26));
            bg[y][x][1] = (uint8_t)(90 + ((s >> 20) & 63u));
            bg[y][x][2] = (uint8_t)(60 + ((s >> 14) & 63u));
        }
    }
}

static void render(double cx)
{
    memcpy(img, bg, sizeof img);
    const int x0 = (int)floor(cx - TW / 2.0 + 0.5), y0 = 32 - TH / 2;
    for (int y = 0; y < TH; ++y) {
        for (int x = 0; x < TW; ++x) {
            const int X = x0 + x;
            if (X < 0 || X >= W) {
                continue;
            }
            const int front = x >= TW / 2;
            img[y0 + y][X][0] = (uint8_t)(front ? 235 : 200);
            img[y0 + y][X][1] = (uint8_t)(front ? 205 : 50 + 30 * (y & 1));
            img[y0 + y][X][2] = (uint8_t)(front ? 40 : 45);
        }
    }
}

/* Worst centre error over the run; paper = the settings before issue #10. */
static double run(pft_tsa_motion_kind_t m, uint64_t seed, bool paper)
{
    pft_tsa_config_t c;
    pft_frame_t f;
    pft_tsa_estimate_t e;
    pft_test_tsa_config(&c, W, H, MAXT, NP, PTS);
    c.motion = m;
    c.seed = seed;
    if (paper) {
        c.fit_k = 10;
        c.fit_sigma = pft_test_from_double(5.0);
        c.spread_gain = 0;
    }
    memset(&f, 0, sizeof f);
    f.data = img;
    f.width = W;
    f.height = H;
    f.stride_bytes = 3 * W;
    f.format = PFT_PIX_RGB888;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_init(&trk, &c, work, sizeof work));
    render(truth[0]);
    {
        const int x0 = (int)floor(truth[0] - TW / 2.0 + 0.5), y0 = 32 - TH / 2;
        const pft_tsa_pt_t b[4] = {{(int16_t)(x0 - 1), (int16_t)(y0 - 1)},
                                   {(int16_t)(x0 + TW), (int16_t)(y0 - 1)},
                                   {(int16_t)(x0 + TW), (int16_t)(y0 + TH)},
                                   {(int16_t)(x0 - 1), (int16_t)(y0 + TH)}};
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_start(&trk, &f, b, 4));
    }
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_estimate(&trk, &e));
    const double off_x = pft_test_to_double(e.x) - truth[0];
    const double off_y = pft_test_to_double(e.y) - 32.0;
    double worst = 0.0;
    for (int k = 1; k < FRAMES; ++k) {
        render(truth[k]);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_update(&trk, &f));
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_estimate(&trk, &e));
        const double err = hypot(pft_test_to_double(e.x) - off_x - truth[k],
                                 pft_test_to_double(e.y) - off_y - 32.0);
        worst = err > worst ? err : worst;
    }
    return worst;
}

static void test_sudden_reversal(void)
{
    int ok_tsa = 0, ok_ts = 0, ok_paper = 0;
    make_truth();
    make_background();
    for (uint64_t seed = 1; seed <= SEEDS; ++seed) {
        const double w_tsa = run(PFT_TSA_MOTION_TSA, seed, false);
        const double w_ts = run(PFT_TSA_MOTION_TS, seed, false);
        const double w_paper = run(PFT_TSA_MOTION_TSA, seed, true);
        ok_tsa += w_tsa <= TRACK_TOL;
        ok_ts += w_ts <= TRACK_TOL;
        ok_paper += w_paper <= TRACK_TOL;
        UnityPrint("seed ");
        UnityPrintNumber((UNITY_INT)seed);
        UnityPrint(": worst centre error TSA ");
        UnityPrintFloat(w_tsa);
        UnityPrint(", TS ");
        UnityPrintFloat(w_ts);
        UnityPrint(", TSA with K = 10, sigma_G = 5, fixed 2 px diffusion ");
        UnityPrintFloat(w_paper);
        UNITY_PRINT_EOL();
    }
    UnityPrint("within 7 px on every frame: TSA ");
    UnityPrintNumber(ok_tsa);
    UnityPrint(", TS ");
    UnityPrintNumber(ok_ts);
    UnityPrint(", the earlier settings ");
    UnityPrintNumber(ok_paper);
    UnityPrint(" of 8");
    UNITY_PRINT_EOL();
    TEST_ASSERT_TRUE_MESSAGE(ok_tsa >= MIN_OK, "TSA lost the reversal too often");
    TEST_ASSERT_TRUE_MESSAGE(ok_ts >= MIN_OK, "TS lost the reversal too often");
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_sudden_reversal);
    return UNITY_END();
}
