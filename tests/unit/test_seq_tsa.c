/*
 * Frame sequence numbers in TSA-AK (docs/design.md, "Time, sequence numbers and lost frames"):
 * a textured target cruising at 3 px/frame, frames 7..9 lost (it moves 12 px over the gap):
 * with PFT_SEQ_USE the estimate at frame 10 and after is within one frame's motion (V = 3 px)
 * of the truth (the same frames taken as consecutive give 5 px), the estimate says gap 4 and carries the frame's seq and timestamp; the error with
 * the same frames taken as consecutive is printed beside it. A repeated or past seq is refused
 * with PFT_ERR_SEQ, instance and workspace byte-identical. Same scene as test_tsa_tracker.c.
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
#define V 3.0

static uint8_t img[H][W][3];
static uint8_t bg[H][W][3];
static uint8_t work[PFT_TSA_WORKSPACE_BYTES(NP, 32, 32, 24, 6, 48)];
static uint8_t work_copy[sizeof work];
static pft_tsa_t trk, trk_copy;

static double truth_x(int k) { return 20.0 + V * k; }

static void make_background(void)
{
    uint32_t s = 99u;
    for (int y = 0; y < H; ++y) {
        for (int x = 0; x < W; ++x) {
            s = s * 1664525u + 1013904223u;
            const uint8_t g = (uint8_t)(90 + (s >> 27) * 3); /* grey texture 90..183 */
            bg[y][x][0] = g;
            bg[y][x][1] = g;
            bg[y][x][2] = (uint8_t)(g - 10);
        }
    }
}

static void render(double cx, double cy)
{
    memcpy(img, bg, sizeof img);
    const int x0 = (int)floor(cx - TW / 2.0 + 0.5), y0 = (int)floor(cy - TH / 2.0 + 0.5);
    for (int y = 0; y < TH; ++y) {
        for (int x = 0; x < TW; ++x) {
            const int X = x0 + x, Y = y0 + y;
            if (X < 0 || Y < 0 || X >= W || Y >= H) {
                continue;
            }
            const int front = x >= TW / 2;
            img[Y][X][0] = front ? 230 : 200;
            img[Y][X][1] = front ? 40 : 190;
            img[Y][X][2] = (uint8_t)(front ? 30 : 40 + 8 * (y & 1));
        }
    }
}

static pft_frame_t frame(uint32_t seq)
{
    pft_frame_t f;
    memset(&f, 0, sizeof f);
    f.data = img;
    f.width = W;
    f.height = H;
    f.stride_bytes = 3 * W;
    f.format = PFT_PIX_RGB888;
    f.seq = seq;
    f.timestamp_us = 33333u * (uint64_t)seq;
    return f;
}

static void config(pft_tsa_config_t *c, pft_seq_mode_t mode)
{
    pft_tsa_config_default(c);
    c->width = W;
    c->height = H;
    c->max_target_w = 32;
    c->max_target_h = 32;
    c->n_particles = NP;
    c->snake_points = 24;
    c->motion = PFT_TSA_MOTION_TSA;
    c->seed = 5;
    c->fit_k = 8;
    c->fit_sigma = pft_test_from_double(2.5);
    pft_tsa_snake_params_default(&c->snake, 32, 32);
    c->seq_mode = mode;
}

static void box_at(double cx, double cy, pft_tsa_pt_t *b)
{
    const int x0 = (int)floor(cx - TW / 2.0 + 0.5), y0 = (int)floor(cy - TH / 2.0 + 0.5);
    b[0].x = (int16_t)(x0 - 1); b[0].y = (int16_t)(y0 - 1);
    b[1].x = (int16_t)(x0 + TW); b[1].y = (int16_t)(y0 - 1);
    b[2].x = (int16_t)(x0 + TW); b[2].y = (int16_t)(y0 + TH);
    b[3].x = (int16_t)(x0 - 1); b[3].y = (int16_t)(y0 + TH);
}


static pft_tsa_estimate_t estimate(void)
{
    pft_tsa_estimate_t e;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_estimate(&trk, &e));
    return e;
}

/* Start at frame 0 (seq 100), frames 1..15 with 7..9 lost; error at frame 10 and worst after. */
static double run(pft_seq_mode_t mode, double *worst_after)
{
    pft_tsa_config_t c;
    config(&c, mode);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_init(&trk, &c, work, sizeof work));
    pft_tsa_pt_t b[4];
    render(truth_x(0), 24.0);
    box_at(truth_x(0), 24.0, b);
    pft_frame_t f = frame(100u);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_start(&trk, &f, b, 4));
    TEST_ASSERT_EQUAL_UINT32(100u, estimate().last_seq);
    double e10 = 1e9;
    *worst_after = 0.0;
    for (int k = 1; k <= 15; ++k) {
        if (k >= 7 && k <= 9) {
            continue;
        }
        render(truth_x(k), 24.0);
        f = frame(100u + (uint32_t)k);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_update(&trk, &f));
        const pft_tsa_estimate_t e = estimate();
        const double err = hypot(pft_test_to_double(e.x) - truth_x(k),
                                 pft_test_to_double(e.y) - 24.0);
        TEST_ASSERT_EQUAL_UINT32(100u + (uint32_t)k, e.last_seq);
        TEST_ASSERT_TRUE(e.last_timestamp_us == 33333u * (uint64_t)(100 + k));
        if (k == 10) {
            TEST_ASSERT_EQUAL_UINT32(mode == PFT_SEQ_USE ? 4u : 1u, e.gap);
            e10 = err;
        }
        if (k >= 10 && err > *worst_after) {
            *worst_after = err;
        }
    }
    return e10;
}

static void test_gap_predicts_over_k_periods(void)
{
    double wu = 0.0, wi = 0.0;
    const double use = run(PFT_SEQ_USE, &wu);
    const double ign = run(PFT_SEQ_IGNORE, &wi);
    UnityPrint(" err10_use=");
    UnityPrintFloat(use);
    UnityPrint(" worst_after_use=");
    UnityPrintFloat(wu);
    UnityPrint(" err10_ignore=");
    UnityPrintFloat(ign);
    UnityPrint(" worst_after_ignore=");
    UnityPrintFloat(wi);
    TEST_ASSERT_TRUE_MESSAGE(use < V, "estimate after the gap more than one frame's motion off");
    TEST_ASSERT_TRUE_MESSAGE(wu < V, "estimate after the gap more than one frame's motion off");
}

static void test_repeated_or_past_seq_refused_untouched(void)
{
    pft_tsa_config_t c;
    config(&c, PFT_SEQ_USE);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_init(&trk, &c, work, sizeof work));
    pft_tsa_pt_t b[4];
    render(truth_x(0), 24.0);
    box_at(truth_x(0), 24.0, b);
    pft_frame_t f = frame(UINT32_MAX);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_start(&trk, &f, b, 4));
    const uint32_t bad[2] = {UINT32_MAX, UINT32_MAX - 5u};
    render(truth_x(1), 24.0);
    for (int i = 0; i < 2; ++i) {
        f = frame(bad[i]);
        trk_copy = trk;
        memcpy(work_copy, work, sizeof work);
        TEST_ASSERT_EQUAL_INT(PFT_ERR_SEQ, pft_tsa_update(&trk, &f));
        TEST_ASSERT_EQUAL_MEMORY(&trk_copy, &trk, sizeof trk);
        TEST_ASSERT_EQUAL_MEMORY(work_copy, work, sizeof work);
    }
    f = frame(0u); /* wraps: the next frame */
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_update(&trk, &f));
    TEST_ASSERT_EQUAL_UINT32(1u, estimate().gap);
    c.max_gap = 0u;
    const char *field = NULL;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_tsa_config_check(&c, &field));
    TEST_ASSERT_EQUAL_STRING("max_gap", field);
}

int main(void)
{
    make_background();
    UNITY_BEGIN();
    RUN_TEST(test_gap_predicts_over_k_periods);
    RUN_TEST(test_repeated_or_past_seq_refused_untouched);
    return UNITY_END();
}
