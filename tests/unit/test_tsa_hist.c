/*
 * Appearance primitives: polygon area / inside / distance, the asymmetric kernel of a
 * rectangle (pixel count and c + d weights by hand), the 30-bin histogram of known patches in
 * RGB888, BGR888 and U8, pixels outside the frame dropped, and the Bhattacharyya coefficient
 * (identical = 1, disjoint = 0, a hand-computed mixture).
 */
#include <math.h>
#include <string.h>
#include "pft_test_support.h"
#include "pft/pft_tsa.h"

void setUp(void) {}
void tearDown(void) {}

#define W 48
#define H 40
static uint8_t rgb[H][W][3], bgr[H][W][3], grey[H][W];
static pft_tsa_kpix_t kpix[64 * 64];
static int32_t cross[64];

static pft_frame_t frame_of(const void *data, pft_pixfmt_t fmt)
{
    pft_frame_t f;
    memset(&f, 0, sizeof f);
    f.data = data;
    f.width = W;
    f.height = H;
    f.format = fmt;
    f.stride_bytes = W * pft_pixfmt_bytes(fmt);
    return f;
}

static void fill(uint8_t r, uint8_t g, uint8_t b)
{
    for (int y = 0; y < H; ++y) {
        for (int x = 0; x < W; ++x) {
            rgb[y][x][0] = r; rgb[y][x][1] = g; rgb[y][x][2] = b;
            bgr[y][x][0] = b; bgr[y][x][1] = g; bgr[y][x][2] = r;
            grey[y][x] = r;
        }
    }
}

static const pft_tsa_pt_t rect[4] = {{10, 10}, {20, 10}, {20, 16}, {10, 16}};

static void test_polygon_geometry(void)
{
    TEST_ASSERT_EQUAL_INT64(2 * 60, pft_tsa_poly_area2(rect, 4));
    TEST_ASSERT_TRUE(pft_tsa_poly_inside(rect, 4, 15, 13));
    TEST_ASSERT_TRUE(pft_tsa_poly_inside(rect, 4, 10, 10));  /* half-open: left/top edges in */
    TEST_ASSERT_FALSE(pft_tsa_poly_inside(rect, 4, 20, 13)); /* right edge out */
    TEST_ASSERT_FALSE(pft_tsa_poly_inside(rect, 4, 15, 16)); /* bottom edge out */
    TEST_ASSERT_FALSE(pft_tsa_poly_inside(rect, 4, 25, 13));
    /* distances in 1/16 px */
    TEST_ASSERT_EQUAL_UINT32(3 * 16, pft_tsa_poly_dist_q4(rect, 4, 15, 13));
    TEST_ASSERT_EQUAL_UINT32(0, pft_tsa_poly_dist_q4(rect, 4, 10, 12));
    TEST_ASSERT_EQUAL_UINT32(5 * 16, pft_tsa_poly_dist_q4(rect, 4, 25, 13));
    TEST_ASSERT_EQUAL_UINT32((uint32_t)floor(16 * sqrt(3 * 3 + 4 * 4)), pft_tsa_poly_dist_q4(rect, 4, 23, 20));
    {   /* slanted edge: distance from (0, 0) to the line x + y = 10 is 10/sqrt(2) */
        const pft_tsa_pt_t tri[3] = {{10, 0}, {0, 10}, {10, 10}};
        TEST_ASSERT_EQUAL_UINT32((uint32_t)floor(16 * 10 / sqrt(2.0)), pft_tsa_poly_dist_q4(tri, 3, 0, 0));
    }
}

static void test_kernel_of_rectangle(void)
{
    pft_tsa_kernel_t k = {kpix, 0, sizeof kpix / sizeof kpix[0], 0, 0, 0, 0, 0};
    pft_tsa_pt_t o;
    uint32_t sum = 0;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_kernel_build(&k, rect, 4, 16, cross, &o));
    TEST_ASSERT_EQUAL_UINT32(60, k.n); /* x 10..19, y 10..15 */
    TEST_ASSERT_EQUAL_INT(15, o.x);    /* centroid (14.5, 12.5) rounded up */
    TEST_ASSERT_EQUAL_INT(13, o.y);
    TEST_ASSERT_EQUAL_INT(-5, k.x0);
    TEST_ASSERT_EQUAL_INT(4, k.x1);
    TEST_ASSERT_EQUAL_INT(-3, k.y0);
    TEST_ASSERT_EQUAL_INT(2, k.y1);
    for (uint32_t i = 0; i < k.n; ++i) {
        const int x = o.x + k.pix[i].dx, y = o.y + k.pix[i].dy;
        int d = x - 10;
        d = 20 - x < d ? 20 - x : d;
        d = y - 10 < d ? y - 10 : d;
        d = 16 - y < d ? 16 - y : d;
        TEST_ASSERT_EQUAL_UINT16(16 + 16 * d, k.pix[i].w); /* c + d, c = 1 */
        TEST_ASSERT_TRUE(pft_tsa_poly_inside(rect, 4, x, y));
        sum += k.pix[i].w;
    }
    TEST_ASSERT_EQUAL_UINT32(sum, k.sum);
    /* errors: degenerate, empty, too many pixels */
    {
        const pft_tsa_pt_t line[3] = {{0, 0}, {5, 5}, {10, 10}};
        const pft_tsa_pt_t sliver[3] = {{10, 10}, {11, 10}, {10, 10}};
        const pft_tsa_pt_t tiny[3] = {{10, 10}, {10, 10}, {11, 10}};
        pft_tsa_kpix_t small[8];
        pft_tsa_kernel_t ks = {small, 0, 8, 0, 0, 0, 0, 0};
        const pft_tsa_pt_t thin[3] = {{5, 5}, {6, 6}, {5, 6}};
        TEST_ASSERT_EQUAL_INT(PFT_ERR_DEGENERATE, pft_tsa_kernel_build(&k, line, 3, 16, cross, &o));
        TEST_ASSERT_EQUAL_INT(PFT_ERR_DEGENERATE, pft_tsa_kernel_build(&k, sliver, 3, 16, cross, &o));
        TEST_ASSERT_EQUAL_INT(PFT_ERR_DEGENERATE, pft_tsa_kernel_build(&k, tiny, 3, 16, cross, &o));
        TEST_ASSERT_EQUAL_INT(PFT_ERR_DEGENERATE, pft_tsa_kernel_build(&k, thin, 3, 16, cross, &o)); /* no centre inside */
        TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tsa_kernel_build(&k, rect, 2, 16, cross, &o));
        TEST_ASSERT_EQUAL_INT(PFT_ERR_NOMEM, pft_tsa_kernel_build(&ks, rect, 4, 16, cross, &o));
        TEST_ASSERT_EQUAL_UINT32(60, k.n); /* unchanged by the failures */
    }
}

static void test_histogram_of_known_patches(void)
{
    pft_tsa_kernel_t k = {kpix, 0, sizeof kpix / sizeof kpix[0], 0, 0, 0, 0, 0};
    pft_tsa_pt_t o;
    pft_tsa_hist_t h, hb, hg;
    pft_frame_t fr = frame_of(rgb, PFT_PIX_RGB888), fb = frame_of(bgr, PFT_PIX_BGR888);
    pft_frame_t fg = frame_of(grey, PFT_PIX_U8);
    uint32_t left = 0, right = 0;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_kernel_build(&k, rect, 4, 16, cross, &o));
    /* uniform (200, 100, 30): bins 7, 10 + 3, 20 + 1 */
    fill(200, 100, 30);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_hist(&fr, &k, o.x, o.y, &h));
    TEST_ASSERT_EQUAL_UINT32(k.sum, h.total);
    for (uint32_t b = 0; b < PFT_TSA_BINS; ++b) {
        TEST_ASSERT_EQUAL_UINT32((b == 7 || b == 13 || b == 21) ? k.sum : 0u, h.bin[b]);
    }
    /* two halves: x < 15 pure red (255, 0, 0), x >= 15 (0, 25, 255) */
    for (int y = 0; y < H; ++y) {
        for (int x = 0; x < W; ++x) {
            const uint8_t r = x < 15 ? 255 : 0, g = x < 15 ? 0 : 25, b = x < 15 ? 0 : 255;
            rgb[y][x][0] = r; rgb[y][x][1] = g; rgb[y][x][2] = b;
            bgr[y][x][0] = b; bgr[y][x][1] = g; bgr[y][x][2] = r;
            grey[y][x] = x < 15 ? 26 : 255; /* bins 1 and 9 */
        }
    }
    for (uint32_t i = 0; i < k.n; ++i) {
        if (o.x + k.pix[i].dx < 15) {
            left += k.pix[i].w;
        } else {
            right += k.pix[i].w;
        }
    }
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_hist(&fr, &k, o.x, o.y, &h));
    TEST_ASSERT_EQUAL_UINT32(left, h.bin[9]);       /* R 255 */
    TEST_ASSERT_EQUAL_UINT32(right, h.bin[0]);      /* R 0 */
    TEST_ASSERT_EQUAL_UINT32(left + right, h.bin[10 + 0]); /* G 0 and G 25 both in bin 0 */
    TEST_ASSERT_EQUAL_UINT32(left, h.bin[20 + 0]);
    TEST_ASSERT_EQUAL_UINT32(right, h.bin[20 + 9]);
    /* BGR888 of the same picture: the same histogram */
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_hist(&fb, &k, o.x, o.y, &hb));
    TEST_ASSERT_EQUAL_MEMORY(&h, &hb, sizeof h);
    /* U8 grey: three copies of the grey histogram */
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_hist(&fg, &k, o.x, o.y, &hg));
    for (uint32_t c = 0; c < 3; ++c) {
        TEST_ASSERT_EQUAL_UINT32(left, hg.bin[10 * c + 1]);
        TEST_ASSERT_EQUAL_UINT32(right, hg.bin[10 * c + 9]);
    }
    /* partly outside: only the in-frame pixels count; wholly outside: empty */
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_hist(&fr, &k, 2, o.y, &h)); /* dx >= -2 kept: x 0..6 */
    {
        uint32_t in = 0;
        for (uint32_t i = 0; i < k.n; ++i) {
            in += (2 + k.pix[i].dx >= 0) ? k.pix[i].w : 0u;
        }
        TEST_ASSERT_EQUAL_UINT32(in, h.total);
        TEST_ASSERT_EQUAL_UINT32(in, h.bin[9]); /* all red */
    }
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_hist(&fr, &k, -20, o.y, &h));
    TEST_ASSERT_EQUAL_UINT32(0, h.total);
    TEST_ASSERT_TRUE(pft_tsa_bhattacharyya(&h, &hb) == 0);
    /* a U16 frame is refused */
    {
        pft_frame_t f16 = frame_of(rgb, PFT_PIX_U16);
        TEST_ASSERT_EQUAL_INT(PFT_ERR_FORMAT, pft_tsa_hist(&f16, &k, o.x, o.y, &h));
    }
}

static void test_bhattacharyya(void)
{
    pft_tsa_hist_t p, q;
    double rho;
    memset(&p, 0, sizeof p);
    memset(&q, 0, sizeof q);
    /* identical (uneven) histograms: exactly 1 */
    for (uint32_t c = 0; c < 3; ++c) {
        p.bin[10 * c + 2] = 1234567;
        p.bin[10 * c + 5] = 89;
        p.bin[10 * c + 9] = 4321;
    }
    p.total = 1234567 + 89 + 4321;
    TEST_ASSERT_TRUE(pft_tsa_bhattacharyya(&p, &p) == PFT_REAL_ONE);
    /* disjoint: 0 */
    for (uint32_t c = 0; c < 3; ++c) {
        q.bin[10 * c + 0] = 500;
    }
    q.total = 500;
    TEST_ASSERT_TRUE(pft_tsa_bhattacharyya(&p, &q) == 0);
    /* q: every channel all in bin 2 -> rho = sqrt(p_2) per channel, averaged */
    memset(&q, 0, sizeof q);
    for (uint32_t c = 0; c < 3; ++c) {
        q.bin[10 * c + 2] = 777;
    }
    q.total = 777;
    rho = sqrt(1234567.0 / (1234567 + 89 + 4321));
    TEST_ASSERT_DOUBLE_WITHIN(1.0 / 4096, rho, pft_test_to_double(pft_tsa_bhattacharyya(&p, &q)));
    /* half/half against all-in-one: sqrt(0.5) */
    memset(&p, 0, sizeof p);
    for (uint32_t c = 0; c < 3; ++c) {
        p.bin[10 * c + 2] = 1000;
        p.bin[10 * c + 3] = 1000;
    }
    p.total = 2000;
    TEST_ASSERT_DOUBLE_WITHIN(1.0 / 4096, sqrt(0.5), pft_test_to_double(pft_tsa_bhattacharyya(&p, &q)));
    TEST_ASSERT_TRUE(pft_tsa_bhattacharyya(NULL, &q) == 0);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_polygon_geometry);
    RUN_TEST(test_kernel_of_rectangle);
    RUN_TEST(test_histogram_of_known_patches);
    RUN_TEST(test_bhattacharyya);
    return UNITY_END();
}
