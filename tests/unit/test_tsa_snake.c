/*
 * Greedy snake: on a drawn rectangle (bright on a darker background) a contour started 4 px
 * inside (a k_b = 0.8 balloon inflates it, clean image) and, on a textured image with the
 * default weights, contours started 2 px outside and 1 px inside all end with every point
 * within 2 px of the rectangle's edges, in a bounded number of passes; the
 * perimeter resampler; argument errors and the work-size check.
 */
#include <math.h>
#include <string.h>
#include "pft_test_support.h"
#include "pft/pft_tsa.h"

void setUp(void) {}
void tearDown(void) {}

#define W 72
#define H 56
static uint8_t img[H][W][3];
static uint8_t work[PFT_TSA_SNAKE_WORK_BYTES(64, 64, 6)];
/* the rectangle covers pixels x 22..45, y 18..35: its edges lie at x 21.5 / 45.5, y 17.5 / 35.5 */
#define RX0 22
#define RX1 45
#define RY0 18
#define RY1 35

static int texture = 1;
static void draw(void)
{
    uint32_t s = 7u;
    for (int y = 0; y < H; ++y) {
        for (int x = 0; x < W; ++x) {
            const int in = x >= RX0 && x <= RX1 && y >= RY0 && y <= RY1;
            s = s * 1664525u + 1013904223u;
            const int n = texture ? (int)(s >> 28) - 8 : 0; /* +-8 texture */
            img[y][x][0] = (uint8_t)((in ? 210 : 60) + n);
            img[y][x][1] = (uint8_t)((in ? 170 : 70) + n);
            img[y][x][2] = (uint8_t)((in ? 60 : 50) + n);
        }
    }
}

static double edge_dist(double x, double y)
{
    const double x0 = RX0 - 0.5, x1 = RX1 + 0.5, y0 = RY0 - 0.5, y1 = RY1 + 0.5;
    const double dx = x < x0 ? x0 - x : (x > x1 ? x - x1 : 0.0);
    const double dy = y < y0 ? y0 - y : (y > y1 ? y - y1 : 0.0);
    if (dx > 0 || dy > 0) {
        return sqrt(dx * dx + dy * dy);
    }
    return fmin(fmin(x - x0, x1 - x), fmin(y - y0, y1 - y));
}

static void run_from_box(int x0, int y0, int x1, int y1, double kb, const char *label)
{
    pft_frame_t f;
    pft_tsa_snake_params_t prm;
    const pft_tsa_pt_t box[4] = {{(int16_t)x0, (int16_t)y0}, {(int16_t)x1, (int16_t)y0},
                                 {(int16_t)x1, (int16_t)y1}, {(int16_t)x0, (int16_t)y1}};
    pft_tsa_pt_t pts[40];
    uint8_t flags[40];
    uint32_t done = 0;
    double worst = 0;
    memset(&f, 0, sizeof f);
    f.data = img;
    f.width = W;
    f.height = H;
    f.stride_bytes = 3 * W;
    f.format = PFT_PIX_RGB888;
    pft_tsa_snake_params_default(&prm, 64, 64);
    prm.kb = pft_test_from_double(kb);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_poly_resample(box, 4, pts, 40));
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_snake(&f, pts, 40, &prm, 60, flags, work, sizeof work, &done));
    for (int i = 0; i < 40; ++i) {
        const double d = edge_dist(pts[i].x, pts[i].y);
        worst = d > worst ? d : worst;
    }
    UnityPrint(label);
    UnityPrint(": passes ");
    UnityPrintNumber((UNITY_INT)done);
    UnityPrint(", worst edge distance ");
    UnityPrintFloat(worst);
    UNITY_PRINT_EOL();
    TEST_ASSERT_TRUE(done >= 1 && done <= 60);
    TEST_ASSERT_TRUE_MESSAGE(worst <= 2.0, "a snake point is more than 2 px from the rectangle's edges");
}

static void test_snake_inflates_onto_rectangle(void)
{
    texture = 0;
    draw();
    texture = 1;
    /* Inflating from inside needs k_b above the normalised curvature cost of a one-pixel
     * kink on a straight side (1/2 of the neighbourhood maximum), so k_b / sqrt(2) > 0.5. */
    run_from_box(RX0 + 4, RY0 + 4, RX1 - 4, RY1 - 4, 0.8, "from 4 px inside, k_b 0.8");
}

static void test_snake_from_loose_box(void)
{
    draw();
    /* the default k_b = 0.3 from a box 2 px around the textured target (the greedy snake only
     * sees a 3x3 neighbourhood: it is a local refinement, not a detector) */
    run_from_box(RX0 - 2, RY0 - 2, RX1 + 2, RY1 + 2, 0.3, "from 2 px outside, default k_b");
    run_from_box(RX0 + 1, RY0 + 1, RX1 - 1, RY1 - 1, 0.3, "from 1 px inside, default k_b");
}

static void test_resample_and_errors(void)
{
    const pft_tsa_pt_t sq[4] = {{0, 0}, {40, 0}, {40, 40}, {0, 40}};
    pft_tsa_pt_t out[16];
    uint8_t flags[16];
    pft_tsa_snake_params_t prm;
    pft_frame_t f;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_poly_resample(sq, 4, out, 16));
    for (int i = 0; i < 16; ++i) { /* every 10 px along the perimeter */
        const int s = 10 * i;
        const int ex = s <= 40 ? s : (s <= 80 ? 40 : (s <= 120 ? 120 - s : 0));
        const int ey = s <= 40 ? 0 : (s <= 80 ? s - 40 : (s <= 120 ? 40 : 160 - s));
        TEST_ASSERT_EQUAL_INT(ex, out[i].x);
        TEST_ASSERT_EQUAL_INT(ey, out[i].y);
    }
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tsa_poly_resample(sq, 2, out, 16));
    memset(&f, 0, sizeof f);
    f.data = img;
    f.width = W;
    f.height = H;
    f.stride_bytes = 3 * W;
    f.format = PFT_PIX_RGB888;
    pft_tsa_snake_params_default(&prm, 64, 64);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tsa_snake(&f, out, 4, &prm, 5, flags, work, sizeof work, NULL));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_NOMEM, pft_tsa_snake(&f, out, 16, &prm, 5, flags, work, sizeof work - 1, NULL));
    f.format = PFT_PIX_F32;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_FORMAT, pft_tsa_snake(&f, out, 16, &prm, 5, flags, work, sizeof work, NULL));
    f.format = PFT_PIX_RGB888;
    prm.max_w = 20; /* contour box 41 wide: larger than the box the work is laid out for */
    TEST_ASSERT_EQUAL_INT(PFT_ERR_NOMEM, pft_tsa_snake(&f, out, 16, &prm, 5, flags, work, sizeof work, NULL));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_snake_inflates_onto_rectangle);
    RUN_TEST(test_snake_from_loose_box);
    RUN_TEST(test_resample_and_errors);
    return UNITY_END();
}
