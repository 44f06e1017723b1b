/*
 * TSA-AK tracker: configuration (the check names the refused field) and workspace formula
 * (macro = function, one byte short is refused), bad input (target outside the frame,
 * degenerate contour, wrong format or size, update before start) with clear codes and
 * instance and workspace byte-identical, reset (the same run again), the copied-out results
 * (particles, contour, template, kernel; counts before and after start), and tracking of
 * a synthetic textured target that cruises at 1 px/frame, then accelerates at 1 px/frame^2
 * (to 9 px/frame): over 8 seeds TSA (N = 60) and the NCV baseline each keep the centre
 * error within TRACK_TOL = 7 px (half the target's length) on every frame in at least 6 runs.
 * NOTE: the issue asked for a scenario where TSA follows and NCV fails; on these synthetic
 * scenes the NCV baseline (velocity noise sqrt(q) = 2 px/frame at beta = 0) was never worse
 * than TSA over the accelerations tried (1-6 px/frame^2, several q, sigma_G, rho_min), see
 * docs/results/tsa.md, so that claim is not asserted. Also checks that a lost target is
 * reported as a state, not an error.
 */
#include <math.h>
#ifdef TSA_DEBUG
#include <stdio.h>
#endif
#include <string.h>
#include "pft_test_support.h"
#include "pft/pft_tsa.h"

void setUp(void) {}
void tearDown(void) {}

#define W 160
#define H 48
#define TW 14 /* target box */
#define TH 10
#define NP 60
#define FRAMES 18
#define ACC_START 10
#define ACC 1.0
#define TRACK_TOL 7.0
#ifndef SEEDS
#define SEEDS 8
#endif
#define TSA_MIN_OK 6
#define NCV_MIN_OK 6

static uint8_t img[H][W][3];
static uint8_t bg[H][W][3];
static uint8_t work[PFT_TSA_WORKSPACE_BYTES(NP, 32, 32, 24, 6, 48)];
static pft_tsa_t trk;

static pft_tsa_estimate_t estimate(void)
{
    pft_tsa_estimate_t e;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_estimate(&trk, &e));
    return e;
}

static double truth_x(int k)
{
    /* cruise at 1 px/frame for ACC_START frames, then a sudden acceleration of ACC px/frame^2 */
    const double x0 = 20.0;
    if (k <= ACC_START) {
        return x0 + k;
    }
    return x0 + k + 0.5 * ACC * (k - ACC_START) * (k - ACC_START);
}

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

static pft_frame_t frame(void) { return pft_test_rgb_frame(img, W, H); }

static void config(pft_tsa_config_t *c, pft_tsa_motion_kind_t m)
{
    pft_tsa_config_default(c);
    c->width = W;
    c->height = H;
    c->max_target_w = 32;
    c->max_target_h = 32;
    c->n_particles = NP;
    c->snake_points = 24;
    c->motion = m;
    c->seed = 5;
    /* a shorter, sharper fit window than the K = 10, sigma_G = 5 defaults: measured 7/8
     * against 4/8 successes on this scenario (the default window lags the acceleration) */
    c->fit_k = 8;
    c->fit_sigma = pft_test_from_double(2.5);
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

/* Runs the sequence; returns the worst centre error, *last the final one. */
static double run(pft_tsa_motion_kind_t m, uint64_t seed, double *last, int *pioneer_only, double *beta_peak)
{
    pft_tsa_config_t c;
    pft_tsa_pt_t b[4];
    pft_frame_t f = frame();
    double worst = 0, off_x, off_y;
    config(&c, m);
    c.seed = seed;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_init(&trk, &c, work, sizeof work));
    render(truth_x(0), 24.0);
    box_at(truth_x(0), 24.0, b);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_start(&trk, &f, b, 4));
    /* the kernel origin is the contour's centroid: measure errors relative to its offset */
    off_x = pft_test_to_double(estimate().x) - truth_x(0);
    off_y = pft_test_to_double(estimate().y) - 24.0;
    TEST_ASSERT_TRUE(fabs(off_x) <= 1.5 && fabs(off_y) <= 1.5);
    *pioneer_only = 0;
    *beta_peak = 0;
    for (int k = 1; k < FRAMES; ++k) {
        pft_tsa_estimate_t e;
        double ex, ey, err;
        render(truth_x(k), 24.0);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_update(&trk, &f));
        e = estimate();
        ex = pft_test_to_double(e.x) - off_x - truth_x(k);
        ey = pft_test_to_double(e.y) - off_y - 24.0;
        err = sqrt(ex * ex + ey * ey);
        worst = err > worst ? err : worst;
        *last = err;
#ifdef TSA_DEBUG
        printf("k %d truth %.1f est %.1f pio %.1f rho %.2f rp %.2f beta %.2f alive %u st %d\n", k, truth_x(k), pft_test_to_double(e.x) - off_x, pft_test_to_double(e.pioneer_x) - off_x, pft_test_to_double(e.rho), pft_test_to_double(e.rho_pioneer), pft_test_to_double(e.beta), e.n_alive, e.state);
#endif
        *pioneer_only += e.state == PFT_TSA_PIONEER_ONLY;
        if (pft_test_to_double(e.beta_next) > *beta_peak) {
            *beta_peak = pft_test_to_double(e.beta_next);
        }
    }
    return worst;
}

static void test_tsa_and_ncv_follow_acceleration(void)
{
    int ok_tsa = 0, ok_ncv = 0;
    make_background();
    for (uint64_t seed = 1; seed <= SEEDS; ++seed) {
        double last_tsa, last_ncv, beta_tsa, beta_ncv, worst_tsa, worst_ncv;
        int po_tsa, po_ncv;
        worst_tsa = run(PFT_TSA_MOTION_TSA, seed, &last_tsa, &po_tsa, &beta_tsa);
        worst_ncv = run(PFT_TSA_MOTION_NCV, seed, &last_ncv, &po_ncv, &beta_ncv);
        ok_tsa += worst_tsa <= TRACK_TOL;
        ok_ncv += worst_ncv <= TRACK_TOL;
        UnityPrint("seed ");
        UnityPrintNumber((UNITY_INT)seed);
        UnityPrint(": TSA worst ");
        UnityPrintFloat(worst_tsa);
        UnityPrint(" beta peak ");
        UnityPrintFloat(beta_tsa);
        UnityPrint(" pioneer-only ");
        UnityPrintNumber(po_tsa);
        UnityPrint("; NCV worst ");
        UnityPrintFloat(worst_ncv);
        UNITY_PRINT_EOL();
    }
    UnityPrint("successes TSA ");
    UnityPrintNumber(ok_tsa);
    UnityPrint(" NCV ");
    UnityPrintNumber(ok_ncv);
    UNITY_PRINT_EOL();
#ifndef TSA_DEBUG
    TEST_ASSERT_TRUE_MESSAGE(ok_tsa >= TSA_MIN_OK, "TSA lost the accelerating target too often");
    TEST_ASSERT_TRUE_MESSAGE(ok_ncv >= NCV_MIN_OK, "the NCV baseline lost the target too often");
#endif
}

static void test_workspace_and_config(void)
{
    pft_tsa_config_t c;
    const char *field = "x";
    config(&c, PFT_TSA_MOTION_TSA);
    TEST_ASSERT_EQUAL_UINT64((uint64_t)(sizeof work), (uint64_t)(pft_tsa_workspace_size(&c)));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_NOMEM, pft_tsa_init(&trk, &c, work, sizeof work - 1));
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_init(&trk, &c, work, sizeof work));
    TEST_ASSERT_EQUAL_INT(PFT_TSA_IDLE, estimate().state);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_config_check(&c, &field));
    TEST_ASSERT_NULL(field);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tsa_config_check(NULL, &field));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tsa_init(NULL, &c, work, sizeof work));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tsa_init(&trk, NULL, work, sizeof work));
    c.n_particles = 0;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_tsa_config_check(&c, &field));
    TEST_ASSERT_EQUAL_STRING("n_particles", field);
    TEST_ASSERT_EQUAL_UINT64((uint64_t)(0), (uint64_t)(pft_tsa_workspace_size(&c)));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_tsa_init(&trk, &c, work, sizeof work));
    config(&c, PFT_TSA_MOTION_TSA);
    c.max_target_w = 300;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_tsa_config_check(&c, &field));
    TEST_ASSERT_EQUAL_STRING("max_target_w", field);
    config(&c, PFT_TSA_MOTION_TSA);
    c.fit_k = PFT_TSA_MOTION_MAX_K + 1;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_tsa_config_check(&c, NULL));
    config(&c, PFT_TSA_MOTION_TSA);
    c.snake.margin = 2;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_tsa_config_check(&c, &field));
    TEST_ASSERT_EQUAL_STRING("snake.margin", field);
    /* the frame size is required: the defaults alone are refused */
    pft_tsa_config_default(&c);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_tsa_config_check(&c, &field));
    TEST_ASSERT_EQUAL_STRING("width", field);
    c.width = W;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_tsa_config_check(&c, &field));
    TEST_ASSERT_EQUAL_STRING("height", field);
    c.height = H;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_config_check(&c, &field));
}

/* Snapshot of instance and workspace, to check that a refusal changed nothing. */
static pft_tsa_t trk_copy;
static uint8_t work_copy[sizeof work];
static void snapshot(void)
{
    memcpy(&trk_copy, &trk, sizeof trk);
    memcpy(work_copy, work, sizeof work);
}
static void assert_unchanged(const char *what)
{
    TEST_ASSERT_EQUAL_MEMORY_MESSAGE(&trk_copy, &trk, sizeof trk, what);
    TEST_ASSERT_EQUAL_MEMORY_MESSAGE(work_copy, work, sizeof work, what);
}

/* A refusal: the expected status, and instance and workspace byte-identical (issue #12). */
#define REFUSED(code, call, what)                                                             \
    do {                                                                                      \
        snapshot();                                                                           \
        TEST_ASSERT_EQUAL_INT_MESSAGE(code, call, what);                                      \
        assert_unchanged(what);                                                               \
    } while (0)

static void test_bad_input(void)
{
    pft_tsa_config_t c;
    pft_tsa_pt_t b[4];
    pft_frame_t f = frame();
    make_background();
    render(60, 24);
    config(&c, PFT_TSA_MOTION_TSA);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_init(&trk, &c, work, sizeof work));
    REFUSED(PFT_ERR_STATE, pft_tsa_update(&trk, &f), "update before start");
    box_at(60, 24, b);
    for (int round = 0; round < 2; ++round) { /* idle, then tracking: refusals change nothing */
        pft_tsa_pt_t o[4];
        memcpy(o, b, sizeof o);
        for (int i = 0; i < 4; ++i) { /* target outside the frame */
            o[i].x = (int16_t)(o[i].x + 200);
        }
        REFUSED(PFT_ERR_INVAL, pft_tsa_start(&trk, &f, o, 4), "box outside the frame");
        {   /* degenerate contour: collinear points; too few points */
            const pft_tsa_pt_t line[3] = {{10, 10}, {20, 20}, {30, 30}};
            REFUSED(PFT_ERR_DEGENERATE, pft_tsa_start(&trk, &f, line, 3), "collinear polygon");
            REFUSED(PFT_ERR_INVAL, pft_tsa_start(&trk, &f, line, 2), "two points");
        }
        {   /* too small: a 1 x 1 and a 2 x 2 box; a sliver whose resampled contour has no pixel
             * centre inside (its kernel would be empty): refused before anything is written,
             * the snake included (issue #12) */
            const pft_tsa_pt_t one[4] = {{60, 20}, {61, 20}, {61, 21}, {60, 21}};
            const pft_tsa_pt_t two[4] = {{60, 20}, {62, 20}, {62, 22}, {60, 22}};
            const pft_tsa_pt_t sliver[3] = {{10, 10}, {19, 16}, {20, 16}};
            REFUSED(PFT_ERR_DEGENERATE, pft_tsa_start(&trk, &f, one, 4), "1 x 1 box");
            REFUSED(PFT_ERR_DEGENERATE, pft_tsa_start(&trk, &f, two, 4), "2 x 2 box");
            REFUSED(PFT_ERR_DEGENERATE, pft_tsa_start(&trk, &f, sliver, 3), "empty sliver");
        }
        {   /* larger than the configured box */
            const pft_tsa_pt_t big[4] = {{10, 2}, {60, 2}, {60, 40}, {10, 40}};
            REFUSED(PFT_ERR_INVAL, pft_tsa_start(&trk, &f, big, 4), "box too large");
        }
        {   /* wrong format and size */
            pft_frame_t g = f;
            g.format = PFT_PIX_U16;
            g.stride_bytes = 2 * W;
            REFUSED(PFT_ERR_FORMAT, pft_tsa_start(&trk, &g, b, 4), "U16 frame");
            g = f;
            g.width = W - 1;
            REFUSED(PFT_ERR_FORMAT, pft_tsa_start(&trk, &g, b, 4), "narrow frame");
            REFUSED(PFT_ERR_INVAL, pft_tsa_start(&trk, NULL, b, 4), "NULL frame");
            REFUSED(PFT_ERR_INVAL, pft_tsa_start(&trk, &f, NULL, 4), "NULL polygon");
            g = f;
            g.format = PFT_PIX_F32;
            REFUSED(round == 0 ? PFT_ERR_STATE : PFT_ERR_FORMAT, pft_tsa_update(&trk, &g),
                    "F32 frame");
            g = f;
            g.height = H / 2;
            REFUSED(round == 0 ? PFT_ERR_STATE : PFT_ERR_FORMAT, pft_tsa_update(&trk, &g),
                    "short frame");
            REFUSED(round == 0 ? PFT_ERR_STATE : PFT_ERR_INVAL, pft_tsa_update(&trk, NULL),
                    "NULL frame (update)");
        }
        {   /* init refused on a live instance: a bad configuration, a short workspace */
            pft_tsa_config_t bad = c;
            bad.n_particles = 0;
            REFUSED(PFT_ERR_CONFIG, pft_tsa_init(&trk, &bad, work, sizeof work), "bad config");
            REFUSED(PFT_ERR_NOMEM, pft_tsa_init(&trk, &c, work, sizeof work - 1), "short work");
            REFUSED(PFT_ERR_INVAL, pft_tsa_init(&trk, &c, NULL, sizeof work), "NULL work");
        }
        {   /* results refused: out untouched, instance unchanged */
            pft_tsa_kernel_t k;
            memset(&k, 0, sizeof k);
            REFUSED(PFT_ERR_INVAL, pft_tsa_estimate(&trk, NULL), "estimate to NULL");
            REFUSED(PFT_ERR_INVAL, pft_tsa_template(&trk, NULL), "template to NULL");
            k.cap = 1u;
            REFUSED(PFT_ERR_INVAL, pft_tsa_kernel(&trk, &k), "kernel to NULL pixels");
        }
        if (round == 0) {
            TEST_ASSERT_EQUAL_INT(PFT_TSA_IDLE, estimate().state); /* still idle */
            TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_start(&trk, &f, b, 4));
            TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_update(&trk, &f));
        }
    }
    /* the target vanishes: reported as a state (WEAK / LOST), never an error */
    memcpy(img, bg, sizeof img);
    for (int k = 0; k < 14; ++k) {
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_update(&trk, &f));
    }
    TEST_ASSERT_TRUE(estimate().state == PFT_TSA_LOST || estimate().state == PFT_TSA_OUT_OF_VIEW);
    /* grey frames are accepted (graceful degradation) */
    {
        static uint8_t grey[H][W];
        pft_frame_t g;
        memset(&g, 0, sizeof g);
        for (int y = 0; y < H; ++y) {
            for (int x = 0; x < W; ++x) {
                grey[y][x] = bg[y][x][0];
            }
        }
        for (int y = 20; y < 30; ++y) {
            for (int x = 55; x < 69; ++x) {
                grey[y][x] = (uint8_t)(x < 62 ? 20 : 250);
            }
        }
        g.data = grey;
        g.width = W;
        g.height = H;
        g.stride_bytes = W;
        g.format = PFT_PIX_U8;
        {
            const pft_tsa_pt_t gb[4] = {{54, 19}, {69, 19}, {69, 30}, {54, 30}};
            TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_start(&trk, &g, gb, 4));
        }
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_update(&trk, &g));
        TEST_ASSERT_TRUE(pft_test_to_double(estimate().rho) > 0.9);
        TEST_ASSERT_EQUAL_INT(PFT_TSA_TRACKING, estimate().state);
    }
}

/* Runs start and 5 updates; copies the estimates out. */
static void short_run(pft_tsa_estimate_t *est)
{
    pft_tsa_pt_t b[4];
    pft_frame_t f = frame();
    render(truth_x(0), 24.0);
    box_at(truth_x(0), 24.0, b);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_start(&trk, &f, b, 4));
    for (int k = 1; k <= 5; ++k) {
        render(truth_x(k), 24.0);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_update(&trk, &f));
        est[k - 1] = estimate();
    }
}

static void test_reset_repeats_the_run(void)
{
    pft_tsa_config_t c;
    pft_tsa_estimate_t first[5], again[5];
    make_background();
    config(&c, PFT_TSA_MOTION_TSA);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tsa_reset(NULL));
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_init(&trk, &c, work, sizeof work));
    snapshot();
    short_run(first);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_reset(&trk));
    TEST_ASSERT_EQUAL_MEMORY_MESSAGE(&trk_copy, &trk, sizeof trk, "reset: not the state after init");
    TEST_ASSERT_EQUAL_INT(PFT_TSA_IDLE, estimate().state);
    {
        pft_frame_t f = frame();
        TEST_ASSERT_EQUAL_INT(PFT_ERR_STATE, pft_tsa_update(&trk, &f)); /* idle again */
    }
    short_run(again);
    TEST_ASSERT_EQUAL_MEMORY_MESSAGE(first, again, sizeof first, "reset: the run differs");
}

static void test_results_are_copied_out(void)
{
    pft_tsa_config_t c;
    pft_tsa_estimate_t est[5];
    static pft_tsa_particle_t part[NP + 1];
    static pft_tsa_kpix_t kpix[32 * 32];
    pft_tsa_pt_t ct[24];
    pft_tsa_hist_t q;
    pft_tsa_kernel_t k;
    make_background();
    config(&c, PFT_TSA_MOTION_TSA);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_init(&trk, &c, work, sizeof work));
    memset(&k, 0, sizeof k);
    k.pix = kpix;
    k.cap = 32 * 32;
    /* before start: nothing to copy */
    TEST_ASSERT_EQUAL_UINT64(0, pft_tsa_particles(&trk, part, NP + 1));
    TEST_ASSERT_EQUAL_UINT64(0, pft_tsa_contour(&trk, ct, 24));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_STATE, pft_tsa_template(&trk, &q));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_STATE, pft_tsa_kernel(&trk, &k));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tsa_estimate(&trk, NULL));
    short_run(est);
    /* counts: TSA has N particles and the pioneer; the count is returned with out = NULL */
    TEST_ASSERT_EQUAL_UINT64(NP + 1, pft_tsa_particles(&trk, NULL, 0));
    TEST_ASSERT_EQUAL_UINT64(NP + 1, pft_tsa_particles(&trk, part, 3));
    TEST_ASSERT_EQUAL_UINT64(NP + 1, pft_tsa_particles(&trk, part, NP + 1));
    for (int i = 0; i < NP + 1; ++i) {
        const double r = pft_test_to_double(part[i].rho);
        TEST_ASSERT_TRUE(r >= 0.0 && r <= 1.0);
        TEST_ASSERT_TRUE(fabs(pft_test_to_double(part[i].x) - pft_test_to_double(est[4].x)) < 40.0);
    }
    TEST_ASSERT_EQUAL_UINT64(24, pft_tsa_contour(&trk, NULL, 0));
    TEST_ASSERT_EQUAL_UINT64(24, pft_tsa_contour(&trk, ct, 24));
    for (int i = 0; i < 24; ++i) { /* the contour lies in the reported box */
        TEST_ASSERT_TRUE(ct[i].x >= est[4].box_x0 && ct[i].x <= est[4].box_x1);
        TEST_ASSERT_TRUE(ct[i].y >= est[4].box_y0 && ct[i].y <= est[4].box_y1);
    }
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_template(&trk, &q));
    TEST_ASSERT_TRUE(q.total > 0u);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_kernel(&trk, &k));
    TEST_ASSERT_TRUE(k.n > 0u && k.n <= k.cap);
    {   /* the copied weights add up to the copied sum */
        uint32_t sum = 0;
        for (uint32_t i = 0; i < k.n; ++i) {
            sum += k.pix[i].w;
        }
        TEST_ASSERT_EQUAL_UINT32(k.sum, sum);
    }
    {   /* a kernel buffer too short is refused and left untouched */
        pft_tsa_kernel_t small;
        memset(&small, 0, sizeof small);
        small.pix = kpix;
        small.cap = k.n - 1u;
        TEST_ASSERT_EQUAL_INT(PFT_ERR_NOMEM, pft_tsa_kernel(&trk, &small));
        TEST_ASSERT_EQUAL_UINT32(0, small.n);
    }
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_workspace_and_config);
    RUN_TEST(test_bad_input);
    RUN_TEST(test_reset_repeats_the_run);
    RUN_TEST(test_results_are_copied_out);
    RUN_TEST(test_tsa_and_ncv_follow_acceleration);
    return UNITY_END();
}
