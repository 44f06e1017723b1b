/*
 * Background-weighted target model (config bg_ring, docs/algorithms.md 4.3; issue #10): a
 * 12 x 12 target, left half colour A = (230, 30, 30), right half colour B = (30, 230, 230), on a
 * background of colour A with one 4 x 4 patch of colour C = (130, 130, 130) inside the ring.
 * Per channel the three colours fall in three different bins ((v * 10) >> 8: 8, 1 and 5), so the
 * ring's histogram has, per channel, o_C = 16 = o* (the rarest bin) and a large o_A, so A's bin
 * (a colour the target shares with its surroundings) gets v_A = 16 / o_A. Known answer, from the
 * unweighted template q of the same kernel (bg_ring 0) and the ring counted from the image:
 * q'_u = T v_u q_u / sum_w v_w q_w per channel, T the template's total.
 */
#include <math.h>
#include <string.h>
#include "pft_test_support.h"
#include "pft/pft_tsa.h"

void setUp(void) {}
void tearDown(void) {}

#define W 96
#define H 96
#define T0 42 /* the target's first column and row */
#define TS 12 /* its side */
#define NP 20
#define MAXT 32
#define PTS 24

static uint8_t img[H][W][3];
static uint8_t work[PFT_TSA_WORKSPACE_BYTES(NP, MAXT, MAXT, PTS, 6, 48)];
static pft_tsa_t trk;
static pft_tsa_kpix_t kpix[2][MAXT * MAXT]; /* storage for the two kernels copied out */

static void paint(int x, int y, uint8_t r, uint8_t g, uint8_t b)
{
    img[y][x][0] = r;
    img[y][x][1] = g;
    img[y][x][2] = b;
}

static void render(void)
{
    for (int y = 0; y < H; ++y) {
        for (int x = 0; x < W; ++x) {
            paint(x, y, 230, 30, 30); /* A */
        }
    }
    for (int y = T0; y < T0 + TS; ++y) {
        for (int x = T0 + TS / 2; x < T0 + TS; ++x) {
            paint(x, y, 30, 230, 230); /* B: the target's right half */
        }
    }
    for (int y = 32; y < 36; ++y) {
        for (int x = 32; x < 36; ++x) {
            paint(x, y, 130, 130, 130); /* C: inside the ring of bg_ring 3 (below) */
        }
    }
}

/* Starts a tracker with bg_ring ring on the target's box; its template, kernel and origin. */
static void start(double ring, double alpha, pft_tsa_hist_t *q, pft_tsa_kernel_t *k, int *ox, int *oy)
{
    k->pix = kpix[ring > 0.0 ? 1 : 0];
    k->cap = MAXT * MAXT;
    pft_tsa_config_t c;
    pft_test_tsa_config(&c, W, H, MAXT, NP, PTS);
    c.init_passes = 0; /* the kernel is the given box */
    c.bg_ring = pft_from_f32((float)ring);
    c.bg_alpha = pft_from_f32((float)alpha);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_init(&trk, &c, work, sizeof work));
    render();
    pft_frame_t f = pft_test_rgb_frame(img, W, H);
    pft_tsa_pt_t b[4];
    pft_test_box_corners(b, T0, T0, T0 + TS - 1, T0 + TS - 1);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_start(&trk, &f, b, 4));
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_template(&trk, q));
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_kernel(&trk, k));
    pft_tsa_estimate_t e;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_estimate(&trk, &e));
    *ox = (int)lround((double)pft_to_float(e.x));
    *oy = (int)lround((double)pft_to_float(e.y));
}

/* The bins of colours A, B, C in channel ch (0 R, 1 G, 2 B). */
static int bin_a(int ch) { return 10 * ch + (ch == 0 ? 8 : 1); }
static int bin_b(int ch) { return 10 * ch + (ch == 0 ? 1 : 8); }

static void test_shared_colour_weighs_less(void)
{
    pft_tsa_hist_t q0, q;
    pft_tsa_kernel_t k0, k;
    int ox0, oy0, ox, oy;
    start(0.0, 1.0, &q0, &k0, &ox0, &oy0);
    start(3.0, 1.0, &q, &k, &ox, &oy);
    /* the same kernel at the same place: only the weighting differs */
    TEST_ASSERT_EQUAL_INT(ox0, ox);
    TEST_ASSERT_EQUAL_INT(oy0, oy);
    TEST_ASSERT_EQUAL_UINT32(k0.sum, k.sum);
    TEST_ASSERT_EQUAL_UINT32(q0.total, q.total);
    /* the ring in frame coordinates: the kernel's box grown by (3 - 1) w / 2 and (3 - 1) h / 2 */
    const int x0 = ox + k.x0, x1 = ox + k.x1, y0 = oy + k.y0, y1 = oy + k.y1;
    const int mx = x1 - x0 + 1, my = y1 - y0 + 1; /* (3 - 1) w / 2, (3 - 1) h / 2 */
    TEST_ASSERT_TRUE(x0 - mx >= 0 && y0 - my >= 0 && x1 + mx < W && y1 + my < H); /* no clip */
    TEST_ASSERT_TRUE(x0 - mx <= 32 && y0 - my <= 32 && x0 > 35 && y0 > 35); /* C in the ring */
    /* the ring's histogram o, counted here from the image (the kernel's box may be a pixel
     * inside the given box, so the ring can hold the target's edge too) */
    double o[30] = {0};
    for (int y = y0 - my; y <= y1 + my; ++y) {
        for (int x = x0 - mx; x <= x1 + mx; ++x) {
            if (x >= x0 && x <= x1 && y >= y0 && y <= y1) {
                continue;
            }
            for (int ch = 0; ch < 3; ++ch) {
                o[10 * ch + ((img[y][x][ch] * 10) >> 8)] += 1.0;
            }
        }
    }
    const double T = (double)q.total;
    for (int ch = 0; ch < 3; ++ch) {
        double ostar = 0.0;
        for (int u = 0; u < 10; ++u) {
            const double v = o[10 * ch + u];
            ostar = v > 0.0 && (ostar == 0.0 || v < ostar) ? v : ostar;
        }
        TEST_ASSERT_EQUAL_DOUBLE(16.0, ostar); /* the C patch is the rarest colour of the ring */
        double wv[10], wsum = 0.0;
        int nz = 0;
        for (int u = 0; u < 10; ++u) {
            const double ou = o[10 * ch + u];
            wv[u] = (ou > ostar ? ostar / ou : 1.0) * (double)q0.bin[10 * ch + u];
            wsum += wv[u];
            nz += q0.bin[10 * ch + u] != 0u;
        }
        /* tolerance: the integer weighting rounds each v_u q_u down (< 1 unit each, scaled by
         * T / wsum), rounds each renormalised bin down (< 1) and gives the remainder (< nz
         * units) to the largest bin */
        const double tol = (double)nz * T / wsum + 1.0 + (double)nz;
        for (int u = 0; u < 10; ++u) {
            TEST_ASSERT_DOUBLE_WITHIN(tol, T * wv[u] / wsum, (double)q.bin[10 * ch + u]);
        }
        /* the shared colour A counts less than without the weighting, the colour B (absent
         * from the ring but for the target's edge) more */
        TEST_ASSERT_TRUE(o[bin_a(ch)] > 10.0 * o[bin_b(ch)]);
        TEST_ASSERT_TRUE(q.bin[bin_a(ch)] < q0.bin[bin_a(ch)]);
        TEST_ASSERT_TRUE(q.bin[bin_b(ch)] > q0.bin[bin_b(ch)]);
    }
    /* so a candidate of colour B alone now matches better than one of colour A alone */
    pft_tsa_hist_t pa, pb;
    memset(&pa, 0, sizeof pa);
    memset(&pb, 0, sizeof pb);
    pa.total = pb.total = 100u;
    for (int ch = 0; ch < 3; ++ch) {
        pa.bin[bin_a(ch)] = 100u;
        pb.bin[bin_b(ch)] = 100u;
    }
    TEST_ASSERT_TRUE(pft_to_float(pft_tsa_bhattacharyya(&pb, &q)) >
                     pft_to_float(pft_tsa_bhattacharyya(&pa, &q)));
}

/* bg_alpha 0.5: half the weighted template, half the unweighted one, bin by bin */
static void test_alpha_mixes(void)
{
    pft_tsa_hist_t q0, q1, qh;
    pft_tsa_kernel_t k;
    int ox, oy;
    start(0.0, 1.0, &q0, &k, &ox, &oy);
    start(3.0, 1.0, &q1, &k, &ox, &oy);
    start(3.0, 0.5, &qh, &k, &ox, &oy);
    uint32_t sum[3] = {0u, 0u, 0u};
    for (int u = 0; u < 30; ++u) {
        /* tolerance: the mix of the two integer bins is rounded down (< 1) and the channel's
         * rounding remainder (< 10 units, one per bin) goes to one bin */
        TEST_ASSERT_DOUBLE_WITHIN(11.0, 0.5 * ((double)q0.bin[u] + (double)q1.bin[u]),
                                  (double)qh.bin[u]);
        sum[u / 10] += qh.bin[u];
    }
    for (int ch = 0; ch < 3; ++ch) {
        TEST_ASSERT_EQUAL_UINT32(qh.total, sum[ch]);
    }
    TEST_ASSERT_TRUE(qh.bin[bin_a(0)] < q0.bin[bin_a(0)] && qh.bin[bin_a(0)] > q1.bin[bin_a(0)]);
}

static void test_config_range(void)
{
    pft_tsa_config_t c;
    pft_tsa_config_default(&c);
    c.width = W;
    c.height = H;
    const char *field = NULL;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_config_check(&c, &field)); /* default 0: off */
    const float bad[] = {-1.0f, 0.5f, 1.0f, 8.5f};
    for (unsigned i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
        c.bg_ring = pft_from_f32(bad[i]);
        TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_tsa_config_check(&c, &field));
        TEST_ASSERT_EQUAL_STRING("bg_ring", field);
    }
    c.bg_ring = pft_from_f32(2.0f);
    const float bad_alpha[] = {0.0f, -0.5f, 1.5f};
    for (unsigned i = 0; i < sizeof bad_alpha / sizeof bad_alpha[0]; ++i) {
        c.bg_alpha = pft_from_f32(bad_alpha[i]);
        TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_tsa_config_check(&c, &field));
        TEST_ASSERT_EQUAL_STRING("bg_alpha", field);
    }
    c.bg_alpha = PFT_REAL_ONE;
    c.bg_ring = pft_from_f32(2.5f);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_config_check(&c, &field));
    c.bg_ring = pft_from_f32(8.0f);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_config_check(&c, &field));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_shared_colour_weighs_less);
    RUN_TEST(test_alpha_mixes);
    RUN_TEST(test_config_range);
    return UNITY_END();
}
