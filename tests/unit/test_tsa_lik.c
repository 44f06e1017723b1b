/*
 * Particle weights of the TSA-AK tracker (pft_tsa_config_t.lik_lambda):
 * - the estimate is exactly the weighted mean of the particles (pioneer included for TSA)
 *   with w = rho (lik_lambda = 0, the paper's eq. 22) or w = exp(lambda (rho - rho_best))
 *   (lik_lambda > 0), particles below rho_min discarded; checked against a double
 *   recomputation from the particles and similarities the tracker reports;
 * - on a low-contrast scene (a grey target on grey texture: background placements reach
 *   rho 0.8-0.95 against the template, the situation of the aerial sequences in
 *   docs/results/tsa.md) TSA with the default lik_lambda = 300 follows a target that
 *   cruises at 1 px/frame and then accelerates at 1 px/frame^2, in at least 6 of 8 seeds,
 *   every frame within 7 px. With the paper's w = rho the same runs are printed for reference
 *   (on the aerial sequences that variant lost the target in every run).
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
#define FRAMES 18
#define ACC_START 10
#define TRACK_TOL 7.0
#define SEEDS 8
#define MIN_OK 6
#ifdef PFT_NUMERIC_Q16
#define EST_TOL 0.05 /* weights on a 2^-16 scale, Q16.16 positions */
#else
#define EST_TOL 1e-3
#endif

static uint8_t img[H][W][3];
static uint8_t bg[H][W][3];
static uint8_t work[PFT_TSA_WORKSPACE_BYTES(NP, 32, 32, 24, 6, 48)];
static pft_tsa_t trk;
static pft_tsa_particle_t part[NP + 1];

static double truth_x(int k)
{
    const double x0 = 20.0;
    if (k <= ACC_START) {
        return x0 + k;
    }
    return x0 + k + 0.5 * (k - ACC_START) * (k - ACC_START);
}

static void make_background(void)
{
    uint32_t s = 77u;
    for (int y = 0; y < H; ++y) {
        for (int x = 0; x < W; ++x) {
            s = s * 1664525u + 1013904223u;
            const uint8_t g = (uint8_t)(80 + (s >> 27) * 4); /* grey texture 80..204 */
            bg[y][x][0] = g;
            bg[y][x][1] = g;
            bg[y][x][2] = g;
        }
    }
}

/* low contrast: a light grey body with a darker grey nose, colours the background also has */
static void render(double cx, double cy, bool low_contrast)
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
            if (low_contrast) {
                const uint8_t g = (uint8_t)(front ? 110 : 185);
                img[Y][X][0] = g;
                img[Y][X][1] = g;
                img[Y][X][2] = g;
            } else {
                img[Y][X][0] = front ? 230 : 200;
                img[Y][X][1] = front ? 40 : 190;
                img[Y][X][2] = 40;
            }
        }
    }
}

static pft_frame_t frame(void) { return pft_test_rgb_frame(img, W, H); }

static void config(pft_tsa_config_t *c, pft_tsa_motion_kind_t m, double lambda, uint64_t seed)
{
    pft_tsa_config_default(c);
    c->width = W;
    c->height = H;
    c->max_target_w = 32;
    c->max_target_h = 32;
    c->n_particles = NP;
    c->snake_points = 24;
    c->motion = m;
    c->seed = seed;
    c->lik_lambda = pft_test_from_double(lambda);
    pft_tsa_snake_params_default(&c->snake, 32, 32);
}

static void box_at(double cx, double cy, pft_tsa_pt_t *b)
{
    const int x0 = (int)floor(cx - TW / 2.0 + 0.5), y0 = (int)floor(cy - TH / 2.0 + 0.5);
    b[0].x = (int16_t)(x0 - 1); b[0].y = (int16_t)(y0 - 1);
    b[1].x = (int16_t)(x0 + TW); b[1].y = (int16_t)(y0 - 1);
    b[2].x = (int16_t)(x0 + TW); b[2].y = (int16_t)(y0 + TH);
    b[3].x = (int16_t)(x0 - 1); b[3].y = (int16_t)(y0 + TH);
}

/* Recomputes the estimate of the last update from the reported particles and similarities. */
static void check_estimate(double lambda, double rho_min, const char *what)
{
    const size_t n = pft_tsa_particles(&trk, part, NP + 1);
    pft_tsa_estimate_t e;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_estimate(&trk, &e));
    double best = 0, sw = 0, sx = 0, sy = 0, ex, ey;
    uint32_t kept = 0;
    TEST_ASSERT_TRUE(n >= NP && n <= NP + 1);
    for (size_t i = 0; i < n; ++i) {
        const double r = pft_test_to_double(part[i].rho);
        if (r >= rho_min && r > best) {
            best = r;
        }
    }
    for (size_t i = 0; i < n; ++i) {
        const double r = pft_test_to_double(part[i].rho);
        double w;
        if (r < rho_min || r <= 0) {
            continue;
        }
        w = lambda > 0 ? exp(lambda * (r - best)) : r;
        sw += w;
        sx += w * pft_test_to_double(part[i].x);
        sy += w * pft_test_to_double(part[i].y);
        ++kept;
    }
    TEST_ASSERT_TRUE_MESSAGE(kept > 1u, what);
    ex = sx / sw;
    ey = sy / sw;
    TEST_ASSERT_DOUBLE_WITHIN_MESSAGE(EST_TOL, ex, pft_test_to_double(e.x), what);
    TEST_ASSERT_DOUBLE_WITHIN_MESSAGE(EST_TOL, ey, pft_test_to_double(e.y), what);
}

static void test_estimate_is_the_weighted_mean(void)
{
    static const double lambdas[3] = {0.0, 30.0, 300.0};
    static const pft_tsa_motion_kind_t kinds[2] = {PFT_TSA_MOTION_NCV, PFT_TSA_MOTION_TSA};
    make_background();
    for (int m = 0; m < 2; ++m) {
        for (int l = 0; l < 3; ++l) {
            pft_tsa_config_t c;
            pft_tsa_pt_t b[4];
            pft_frame_t f = frame();
            config(&c, kinds[m], lambdas[l], 3u);
            TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_init(&trk, &c, work, sizeof work));
            render(truth_x(0), 24.0, false);
            box_at(truth_x(0), 24.0, b);
            TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_start(&trk, &f, b, 4));
            for (int k = 1; k <= 3; ++k) {
                render(truth_x(k) + 1.0, 24.0, false);
                TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_update(&trk, &f));
                check_estimate(lambdas[l], pft_test_to_double(c.rho_min),
                               m == 0 ? "NCV estimate != weighted mean" : "TSA estimate != weighted mean");
            }
        }
    }
}

static double run(double lambda, uint64_t seed)
{
    pft_tsa_config_t c;
    pft_tsa_pt_t b[4];
    pft_frame_t f = frame();
    double worst = 0, off_x, off_y;
    config(&c, PFT_TSA_MOTION_TSA, lambda, seed);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_init(&trk, &c, work, sizeof work));
    render(truth_x(0), 24.0, true);
    box_at(truth_x(0), 24.0, b);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_start(&trk, &f, b, 4));
    {
        pft_tsa_estimate_t e0;
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_estimate(&trk, &e0));
        off_x = pft_test_to_double(e0.x) - truth_x(0);
        off_y = pft_test_to_double(e0.y) - 24.0;
    }
    for (int k = 1; k < FRAMES; ++k) {
        pft_tsa_estimate_t e;
        double ex, ey, err;
        render(truth_x(k), 24.0, true);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_update(&trk, &f));
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_estimate(&trk, &e));
        ex = pft_test_to_double(e.x) - off_x - truth_x(k);
        ey = pft_test_to_double(e.y) - off_y - 24.0;
        err = sqrt(ex * ex + ey * ey);
        worst = err > worst ? err : worst;
    }
    return worst;
}

static void test_low_contrast_acceleration(void)
{
    int ok_exp = 0, ok_lin = 0;
    make_background();
    for (uint64_t seed = 1; seed <= SEEDS; ++seed) {
        const double we = run(300.0, seed), wl = run(0.0, seed);
        ok_exp += we <= TRACK_TOL;
        ok_lin += wl <= TRACK_TOL;
        UnityPrint("seed ");
        UnityPrintNumber((UNITY_INT)seed);
        UnityPrint(": TSA worst error, lambda 300: ");
        UnityPrintFloat(we);
        UnityPrint(", w = rho: ");
        UnityPrintFloat(wl);
        UNITY_PRINT_EOL();
    }
    UnityPrint("successes lambda 300: ");
    UnityPrintNumber(ok_exp);
    UnityPrint(", w = rho: ");
    UnityPrintNumber(ok_lin);
    UNITY_PRINT_EOL();
    TEST_ASSERT_TRUE_MESSAGE(ok_exp >= MIN_OK, "TSA (lik_lambda 300) lost the low-contrast target too often");
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_estimate_is_the_weighted_mean);
    RUN_TEST(test_low_contrast_acceleration);
    return UNITY_END();
}
