/*
 * TBD measurement model (docs/algorithms.md 1): PSF contribution h and the windowed per-pixel log
 * likelihood ratio against a double reference (0-based pixels: column c, row r centred at
 * (c dx, r dy)); frame conversion (U8/U16 gain, offset, bit
 * depth; F32), window regions and configuration checks.
 *
 * Tolerances: float: 1e-5 relative (+1e-5 absolute). q16: h within 2e-4 + 1e-3 relative (exp is
 * good to a few LSB, the products round each step); the 3x3 LLR sums 9 such terms times z of a
 * few tens over sigma^2 ~ 10: within 3e-3 + 2e-3 relative.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "pft_test_support.h"
#include "pft/pft_tbd.h"

void setUp(void) {}
void tearDown(void) {}

#define W 10
#define H 8
#define PI_D 3.14159265358979323846

/* h of a target at (x, y) in the pixel of column c, row r (0-based, centred at (c dx, r dy)) */
static double ref_h(double dx, double dy, double S, int c, int r, double x, double y, double I)
{
    double r2 = (c * dx - x) * (c * dx - x) + (r * dy - y) * (r * dy - y);
    return dx * dy * I / (2.0 * PI_D * S * S) * exp(-r2 / (2.0 * S * S));
}

static double ref_llr(const double *img, int w, int h, int p, double dx, double dy, double S,
                      double sn, double x, double y, double I)
{
    int c0 = (int)floor(x / dx + 0.5);
    int r0 = (int)floor(y / dy + 0.5);
    double acc = 0.0;
    for (int r = r0 - p; r <= r0 + p; ++r) {
        for (int c = c0 - p; c <= c0 + p; ++c) {
            if (c < 0 || r < 0 || c >= w || r >= h) {
                continue;
            }
            double hv = ref_h(dx, dy, S, c, r, x, y, I);
            double z = img[r * w + c];
            acc += hv * (2.0 * z - hv) / (2.0 * sn * sn);
        }
    }
    return acc;
}

static double tol_h(double v)
{
#ifdef PFT_NUMERIC_Q16
    return 2e-4 + 1e-3 * fabs(v);
#else
    return 1e-5 + 1e-5 * fabs(v);
#endif
}
static double tol_llr(double v)
{
#ifdef PFT_NUMERIC_Q16
    return 3e-3 + 2e-3 * fabs(v);
#else
    return 1e-4 + 1e-5 * fabs(v);
#endif
}

static pft_real_t R(double v) { return pft_test_from_double(v); }
static double D(pft_real_t v) { return pft_test_to_double(v); }

static void base_cfg(pft_tbd_config_t *c)
{
    pft_tbd_config_default(c);
    c->width = W;
    c->height = H;
}

static void test_defaults_are_the_papers(void)
{
    pft_tbd_config_t c;
    pft_tbd_config_default(&c);
    TEST_ASSERT_EQUAL_UINT(20, c.width);
    TEST_ASSERT_EQUAL_UINT(1, c.window);
    TEST_ASSERT_DOUBLE_WITHIN(1e-4, 0.7, D(c.psf_sigma));
    TEST_ASSERT_DOUBLE_WITHIN(1e-4, 0.005, D(c.q1));
    TEST_ASSERT_DOUBLE_WITHIN(1e-4, 0.01, D(c.q2));
    TEST_ASSERT_DOUBLE_WITHIN(1e-4, 0.05, D(c.pb));
    TEST_ASSERT_DOUBLE_WITHIN(1e-4, 0.6, D(c.theta1));
    TEST_ASSERT_DOUBLE_WITHIN(1e-4, 0.8, D(c.dis_ratio));
    TEST_ASSERT_EQUAL_UINT(6000, c.n_search);
    TEST_ASSERT_EQUAL_UINT(500, c.n_track);
    TEST_ASSERT_EQUAL_UINT(2, c.dis_r);
    TEST_ASSERT_EQUAL_UINT(5, c.dis_prev);
    TEST_ASSERT_EQUAL_INT(PFT_TBD_RBPF, c.kind);
    TEST_ASSERT_EQUAL_INT(PFT_TBD_KF_EXACT, c.kf_variant);
    /* the multi-target extensions are off: the paper's single-target likelihood and D = C(x) */
    TEST_ASSERT_EQUAL_INT(PFT_TBD_D_WINDOW, c.d_region);
    TEST_ASSERT_FALSE(c.residual_search);
    TEST_ASSERT_FALSE(c.residual_tracks);
    TEST_ASSERT_EQUAL_UINT(0, c.handover_gate);
    TEST_ASSERT_EQUAL_UINT(0, c.end_lr_frames);
    TEST_ASSERT_TRUE(c.dis_ratio_test);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_config_check(&c, NULL));
    pft_tbd_config_recommended(&c);
    TEST_ASSERT_TRUE(c.residual_search && c.residual_tracks);
    TEST_ASSERT_EQUAL_INT(PFT_TBD_D_NONE, c.d_region);
    TEST_ASSERT_EQUAL_UINT(2, c.handover_gate);
    TEST_ASSERT_FALSE(c.dis_ratio_test);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_config_check(&c, NULL));
}

/* Every refused value gives PFT_ERR_CONFIG and names its field; NULL is PFT_ERR_INVAL. */
static void expect_refused(const pft_tbd_config_t *c, const char *name)
{
    const char *field = "unset";
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_tbd_config_check(c, &field));
    TEST_ASSERT_EQUAL_STRING(name, field);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_tbd_config_check(c, NULL));
    TEST_ASSERT_EQUAL_UINT(0u, (unsigned)pft_tbd_workspace_size(c));
    TEST_ASSERT_EQUAL_UINT(0u, (unsigned)pft_tbd_filter_workspace_size(c));
    pft_tbd_meas_t m;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_tbd_meas_init(&m, c));
}

static void test_config_check_rejects(void)
{
    pft_tbd_config_t c;
    const char *field = "unset";
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tbd_config_check(NULL, &field));
    TEST_ASSERT_NULL(field);
    base_cfg(&c);
    field = "unset";
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_config_check(&c, &field));
    TEST_ASSERT_NULL(field);
    base_cfg(&c); c.width = 0;
    expect_refused(&c, "width");
    base_cfg(&c); c.psf_sigma = R(0.0);
    expect_refused(&c, "psf_sigma");
    base_cfg(&c); c.noise_sigma = R(-1.0);
    expect_refused(&c, "noise_sigma");
#ifndef PFT_NUMERIC_Q16
    /* the configuration domain of both builds (reliability.md F4): subnormal sigmas made every
     * estimate NaN in float; huge reals are outside the q16 range */
    base_cfg(&c); c.psf_sigma = 1e-39f;
    expect_refused(&c, "psf_sigma");
    base_cfg(&c); c.noise_sigma = 1e-39f;
    expect_refused(&c, "noise_sigma");
    base_cfg(&c); c.pixel_gain = 1e30f;
    expect_refused(&c, "pixel_gain");
    base_cfg(&c); c.q2 = 1e30f;
    expect_refused(&c, "q2");
    base_cfg(&c); c.gamma = -1e30f;
    expect_refused(&c, "gamma");
#endif
    base_cfg(&c); c.window = PFT_TBD_MAX_WINDOW + 1u;
    expect_refused(&c, "window");
    base_cfg(&c); c.pb = R(1.5);
    expect_refused(&c, "pb");
    base_cfg(&c); c.theta_end = R(-0.5);
    expect_refused(&c, "theta_end");
    base_cfg(&c); c.i_min = R(40.0);
    expect_refused(&c, "i_max");
    base_cfg(&c); c.vel_var[1] = R(-0.1);
    expect_refused(&c, "vel_var[1]");
    base_cfg(&c); c.i_min = R(-1.0);
    expect_refused(&c, "i_min");
    base_cfg(&c); c.dis_prev = 0;
    expect_refused(&c, "dis_prev");
    base_cfg(&c); c.dis_ratio = R(0.0);
    expect_refused(&c, "dis_ratio");
    base_cfg(&c); c.n_search = 0;
    expect_refused(&c, "n_search");
    base_cfg(&c); c.max_targets = 0;
    expect_refused(&c, "max_targets");
    base_cfg(&c); c.kind = (pft_tbd_kind_t)7;
    expect_refused(&c, "kind");
    base_cfg(&c); c.d_region = (pft_tbd_dregion_t)3;
    expect_refused(&c, "d_region");
    base_cfg(&c); c.window = PFT_TBD_MAX_WINDOW; c.residual_margin = PFT_TBD_MAX_WINDOW + 1u;
    expect_refused(&c, "residual_margin");
    base_cfg(&c); c.end_lr_frames = PFT_TBD_MAX_DIS_R + 2u;
    expect_refused(&c, "end_lr_frames");
    base_cfg(&c); c.handover_gate = 65u;
    expect_refused(&c, "handover_gate");
    /* the first refused field in the struct's order is named */
    base_cfg(&c); c.height = 0; c.n_track = 0;
    expect_refused(&c, "height");
}

/* Issue #12: the birth prior is bounded so that every state stays inside the number range
 * (q16 accepted any vel_mean before: thousands of px/frame saturated the positions and, in
 * the hand-over, overflowed the int64 estimate sums). Each bound names its field; the
 * largest accepted values run through the manager (the sanitizer presets would flag any
 * overflow) and give estimates inside the image. */
static uint8_t g_mws[PFT_TBD_WORKSPACE_BYTES(300u, 100u, 2u, PFT_TBD_RBPF, W, H)];

static void test_config_check_bounds_birth_prior(void)
{
    pft_tbd_config_t c;
    base_cfg(&c); c.vel_mean[0] = R(5000.0);
    expect_refused(&c, "vel_mean[0]");
    base_cfg(&c); c.vel_mean[1] = R(-8.01); /* height 8, dy 1, T 1: span 8 */
    expect_refused(&c, "vel_mean[1]");
    base_cfg(&c); c.vel_mean[1] = R(-8.0);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_config_check(&c, NULL));
    base_cfg(&c); c.vel_mean[0] = R(5.0); c.T = R(2.5); /* 12.5 > span 10 */
    expect_refused(&c, "vel_mean[0]");
    base_cfg(&c); c.vel_var[0] = R(100.5); /* sqrt > 10 */
    expect_refused(&c, "vel_var[0]");
    base_cfg(&c); c.vel_var[1] = R(64.5);
    expect_refused(&c, "vel_var[1]");
    base_cfg(&c); c.i_max = R(30000.0); /* peak 30000/(2 pi 0.49) = 9745, but /sigma 3.2 fine */
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_config_check(&c, NULL));
    base_cfg(&c); c.i_max = R(30000.0); c.psf_sigma = R(0.3); /* peak 53052 */
    expect_refused(&c, "i_max");
    base_cfg(&c); c.i_max = R(30000.0); c.noise_sigma = R(0.25); /* peak / sigma 38981 */
    expect_refused(&c, "i_max");

    /* the extremes that are accepted, through the manager */
    base_cfg(&c);
    c.vel_mean[0] = R(10.0);
    c.vel_mean[1] = R(-8.0);
    c.vel_var[0] = R(100.0);
    c.vel_var[1] = R(64.0);
    c.i_min = R(0.0);
    c.i_max = R(20000.0);
    c.eta = R(1.0);
    c.pb = R(0.5);
    c.theta1 = R(0.3);
    c.n_search = 300u;
    c.n_track = 100u;
    c.max_targets = 2u;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_config_check(&c, NULL));
    static pft_tbd_t t;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_init(&t, &c, g_mws, sizeof g_mws));
    static float img[H][W];
    int confirmed = 0;
    for (int k = 1; k <= 12; ++k) {
        for (int r = 0; r < H; ++r) {
            for (int q = 0; q < W; ++q) {
                img[r][q] = (r == 3 && q == (k % W)) ? 3000.0f : 0.0f;
            }
        }
        pft_frame_t fr = {img, W, H, 4 * W, PFT_PIX_F32, 0, 0, (uint32_t)k};
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_update(&t, &fr));
        pft_tbd_track_t tr[2];
        size_t n = pft_tbd_tracks(&t, tr, 2);
        for (size_t i = 0; i < n && i < 2u; ++i) {
            TEST_ASSERT_TRUE(D(tr[i].x) > -0.5 && D(tr[i].x) < W - 0.5);
            TEST_ASSERT_TRUE(D(tr[i].y) > -0.5 && D(tr[i].y) < H - 0.5);
            TEST_ASSERT_TRUE(fabs(D(tr[i].vx)) < 1000.0 && fabs(D(tr[i].vy)) < 1000.0);
        }
        confirmed += pft_tbd_events(&t, NULL, 0) > 0u;
    }
    TEST_ASSERT_TRUE(confirmed > 0);
}

/* pft_tbd_meas_add_psf with a negative intensity subtracts h exactly on its window (and
 * nowhere else, clipped at the borders); the LLR of a second target s on the result is the
 * joint log likelihood ratio log p(z | s, t) - log p(z | t) = sum over C(s) of
 * h_s (2 (z - h_t) - h_s) / (2 sigma^2), when C(s) lies inside the subtracted window. */
static void test_add_psf_and_joint_llr(void)
{
    static double dimg[W * H];
    static pft_real_t img[W * H];
    static pft_real_t res[W * H];
    pft_rng_t rng;
    pft_rng_seed(&rng, 7u);
    for (int k = 0; k < W * H; ++k) {
        double u = (double)pft_rng_u32(&rng) / 4294967296.0;
        img[k] = R(12.0 * u - 3.0);
        dimg[k] = D(img[k]);
    }
    pft_tbd_config_t c;
    base_cfg(&c);
    c.noise_sigma = R(3.256);
    pft_tbd_meas_t m;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_meas_init(&m, &c));
    const double sn = D(R(3.256));
    int checked = 0;
    for (int k = 0; k < 24; ++k) {
        /* t walks over the image including its borders; s sits within 1 px of t */
        double xt = -0.3 + 0.41 * k, yt = -0.1 + 0.29 * k, It = 15.0 + 0.5 * k;
        double xs = xt + 0.9 * cos(0.7 * k), ys = yt + 0.9 * sin(0.7 * k), Is = 20.0;
        xt = D(R(xt)); yt = D(R(yt)); xs = D(R(xs)); ys = D(R(ys));
        memcpy(res, img, sizeof img);
        pft_tbd_meas_add_psf(&m, res, R(xt), R(yt), R(-It), 2u);
        int ct0 = (int)floor(xt + 0.5), rt0 = (int)floor(yt + 0.5);
        for (int r = 0; r < H; ++r) {
            for (int cc = 0; cc < W; ++cc) {
                int in = abs(cc - ct0) <= 2 && abs(r - rt0) <= 2;
                double want = dimg[r * W + cc] - (in ? ref_h(1.0, 1.0, 0.7, cc, r, xt, yt, It) : 0.0);
                TEST_ASSERT_DOUBLE_WITHIN(tol_h(want), want, D(res[r * W + cc]));
            }
        }
        /* joint LLR reference in double, over C(s) clipped (p = 1) */
        int cs0 = (int)floor(xs + 0.5), rs0 = (int)floor(ys + 0.5);
        double ref = 0.0;
        for (int r = rs0 - 1; r <= rs0 + 1; ++r) {
            for (int cc = cs0 - 1; cc <= cs0 + 1; ++cc) {
                if (cc < 0 || r < 0 || cc >= W || r >= H) {
                    continue;
                }
                double z = dimg[r * W + cc];
                double ht = ref_h(1.0, 1.0, 0.7, cc, r, xt, yt, It);
                double hs = ref_h(1.0, 1.0, 0.7, cc, r, xs, ys, Is);
                /* log p(z | s, t) - log p(z | t) */
                ref += ((z - ht) * (z - ht) - (z - ht - hs) * (z - ht - hs)) / (2.0 * sn * sn);
            }
        }
        double got = D(pft_tbd_meas_llr(&m, res, R(xs), R(ys), R(Is)));
        TEST_ASSERT_DOUBLE_WITHIN(tol_llr(ref), ref, got);
        /* and it differs from the single-target LLR on z when the PSFs overlap */
        double single = D(pft_tbd_meas_llr(&m, img, R(xs), R(ys), R(Is)));
        if (fabs(single - ref) > 0.5) {
            ++checked;
        }
    }
    TEST_ASSERT_TRUE_MESSAGE(checked > 12, "the subtraction changes the LLR");
    /* a window entirely outside the image leaves it untouched */
    memcpy(res, img, sizeof img);
    pft_tbd_meas_add_psf(&m, res, R(-5.0), R(3.0), R(-20.0), 2u);
    TEST_ASSERT_EQUAL_MEMORY(img, res, sizeof img);
}

static void test_psf_h_matches_reference(void)
{
    static const double S[] = {0.7, 1.3};
    static const double dxs[] = {1.0, 0.5};
    for (int a = 0; a < 2; ++a) {
        pft_tbd_config_t c;
        base_cfg(&c);
        c.psf_sigma = R(S[a]);
        c.dx = R(dxs[a]);
        c.dy = R(1.0);
        pft_tbd_meas_t m;
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_meas_init(&m, &c));
        for (int k = 0; k < 40; ++k) {
            double x = 2.0 + 0.137 * k, y = 3.0 + 0.071 * k, I = 10.0 + 0.5 * k;
            int i = (int)floor(x / dxs[a] + 0.5) + (k % 3) - 1;
            int j = (int)floor(y + 0.5) + (k % 2);
            double ref = ref_h(dxs[a], 1.0, S[a], i, j, D(R(x)), D(R(y)), D(R(I)));
            double got = D(pft_tbd_meas_h(&m, i, j, R(x), R(y), R(I)));
            TEST_ASSERT_DOUBLE_WITHIN(tol_h(ref), ref, got);
        }
    }
    /* the peak amplitude of the paper's target: I = 20, Sigma = 0.7 gives A = 6.4961 */
    pft_tbd_config_t c;
    base_cfg(&c);
    pft_tbd_meas_t m;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_meas_init(&m, &c));
    TEST_ASSERT_DOUBLE_WITHIN(tol_h(6.4961), 6.4961,
                              D(pft_tbd_meas_h(&m, 3, 4, R(3.0), R(4.0), R(20.0))));
}

static void test_llr_matches_reference(void)
{
    static double dimg[W * H];
    static pft_real_t img[W * H];
    pft_rng_t rng;
    pft_rng_seed(&rng, 99u);
    for (int k = 0; k < W * H; ++k) {
        double u = (double)pft_rng_u32(&rng) / 4294967296.0;
        dimg[k] = 12.0 * u - 3.0; /* pixels in [-3, 9) */
        img[k] = R(dimg[k]);
        dimg[k] = D(img[k]);
    }
    for (int p = 0; p <= 2; ++p) {
        pft_tbd_config_t c;
        base_cfg(&c);
        c.window = (uint8_t)p;
        c.noise_sigma = R(2.586);
        pft_tbd_meas_t m;
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_meas_init(&m, &c));
        for (int k = 0; k < 60; ++k) {
            /* includes windows clipped at every border and fully outside */
            double x = -0.8 + 0.197 * k, y = -0.4 + 0.163 * k, I = 8.0 + 0.4 * k;
            double ref = ref_llr(dimg, W, H, p, 1.0, 1.0, 0.7, D(R(2.586)), D(R(x)), D(R(y)),
                                 D(R(I)));
            double got = D(pft_tbd_meas_llr(&m, img, R(x), R(y), R(I)));
            TEST_ASSERT_DOUBLE_WITHIN(tol_llr(ref), ref, got);
        }
    }
    /* Sign: a target on a bright pixel has a positive LLR, on a dark one negative. */
    pft_tbd_config_t c;
    base_cfg(&c);
    pft_tbd_meas_t m;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_meas_init(&m, &c));
    for (int k = 0; k < W * H; ++k) {
        img[k] = R(0.0);
    }
    img[3 * W + 4] = R(7.0); /* column 4, row 3 */
    TEST_ASSERT_TRUE(D(pft_tbd_meas_llr(&m, img, R(4.0), R(3.0), R(20.0))) > 1.0);
    TEST_ASSERT_TRUE(D(pft_tbd_meas_llr(&m, img, R(1.0), R(6.0), R(20.0))) < -1.0);
}

/* The filters' own kernel (pft_tbd_filter_llr: the whitened frame, tabulated taps for p = 1,
 * exact taps otherwise) against the double reference, windows clipped at every border, pixel
 * pitches 1 and 0.5, Sigma 0.7 and 1.3. The bound is the tap table's interpolation error
 * (64 steps per pixel: at most d^2 / (8 64^2 S^2) per tap, 6.2e-5 for S = 0.7, d = 1) carried
 * through the window sums for these pixel values (|z| < 9, sigma 2.586, I < 32): measured 1.2e-3
 * (float) and 2.1e-3 (q16), asserted 3e-3, plus
 * the q16 rounding of the reference bound above. */
static uint8_t g_kws[PFT_TBD_FILTER_WORKSPACE_BYTES(16, PFT_TBD_RBPF, W, H)];

static void test_filter_kernel_matches_reference(void)
{
    static double dimg[W * H];
    static float fimg[W * H];
    pft_rng_t rng;
    pft_rng_seed(&rng, 98u);
    for (int k = 0; k < W * H; ++k) {
        double u = (double)pft_rng_u32(&rng) / 4294967296.0;
        fimg[k] = (float)(12.0 * u - 3.0); /* pixels in [-3, 9) */
        dimg[k] = D(R((double)fimg[k]));
    }
    static const double S[] = {0.7, 1.3, 0.7};
    static const double dxs[] = {1.0, 1.0, 0.5};
    double worst = 0.0;
    for (int p = 0; p <= 2; ++p) {
        for (int v = 0; v < 3; ++v) {
            pft_tbd_config_t c;
            base_cfg(&c);
            c.window = (uint8_t)p;
            c.noise_sigma = R(2.586);
            c.psf_sigma = R(S[v]);
            c.dx = R(dxs[v]);
            c.n_search = 16u;
            pft_tbd_filter_t f;
            TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_filter_init(&f, &c, g_kws, sizeof g_kws));
            TEST_ASSERT_EQUAL_INT(0, pft_tbd_filter_llr(&f, R(3.0), R(3.0), R(20.0)) != 0);
            pft_frame_t fr = {fimg, W, H, 4 * W, PFT_PIX_F32, 0, 0, 0};
            TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_filter_update(&f, &fr));
            for (int k = 0; k < 90; ++k) {
                double x = (-0.45 + 0.1123 * k) * dxs[v], y = -0.45 + 0.0911 * k,
                       I = 8.0 + 0.27 * k;
                double xr = D(R(x)), yr = D(R(y));
                double got = D(pft_tbd_filter_llr(&f, R(x), R(y), R(I)));
                if (floor(xr / D(c.dx) + 0.5) >= W || floor(yr + 0.5) >= H) {
                    TEST_ASSERT_EQUAL_INT(0, got != 0.0); /* centre outside: 0 */
                    continue;
                }
                double ref = ref_llr(dimg, W, H, p, D(c.dx), 1.0, S[v], D(R(2.586)), xr, yr,
                                     D(R(I)));
                double err = fabs(got - ref);
                worst = err > worst ? err : worst;
                TEST_ASSERT_DOUBLE_WITHIN(3e-3 + tol_llr(ref), ref, got);
            }
        }
    }
    UnityPrint("measured filter kernel: max |llr - reference| = ");
    UnityPrintFloat(worst);
    UNITY_PRINT_EOL();
}

static void test_window_region(void)
{
    pft_tbd_config_t c;
    base_cfg(&c);
    /* 0-based: (4.4, 6.6) is in column 4, row 7 */
    pft_tbd_region_t r = pft_tbd_window_region(&c, R(4.4), R(6.6));
    TEST_ASSERT_EQUAL_INT(3, r.col_lo);
    TEST_ASSERT_EQUAL_INT(5, r.col_hi);
    TEST_ASSERT_EQUAL_INT(6, r.row_lo);
    TEST_ASSERT_EQUAL_INT(8, r.row_hi);
    /* pixel edges: x = -0.5 is column 0 (ties up), x = 9.49 column 9 */
    r = pft_tbd_window_region(&c, R(-0.5), R(9.49));
    TEST_ASSERT_EQUAL_INT(-1, r.col_lo);
    TEST_ASSERT_EQUAL_INT(1, r.col_hi);
    TEST_ASSERT_EQUAL_INT(8, r.row_lo);
    TEST_ASSERT_EQUAL_INT(10, r.row_hi);
    c.window = 2;
    r = pft_tbd_window_region(&c, R(1.0), R(1.0));
    TEST_ASSERT_EQUAL_INT(-1, r.col_lo);
    TEST_ASSERT_EQUAL_INT(3, r.col_hi);
    r = pft_tbd_window_region(NULL, R(1.0), R(1.0));
    TEST_ASSERT_TRUE(r.col_lo > r.col_hi);
}

/* Frame conversion, observed through a standalone filter's converted image: whitened
 * (z / sigma, sigma = 3.2 here, whose reciprocal 0.3125 is exact in both builds), stored with a
 * border of one zero pixel (internal pixel (i, j) at j (W + 2) + i). */
static uint8_t g_ws[PFT_TBD_FILTER_WORKSPACE_BYTES(16, PFT_TBD_RBPF, W, H)];

static double img_at(const pft_tbd_filter_t *f, int r, int k)
{
    return D(f->img[(r + 1) * (W + 2) + k + 1]);
}

static void check_border(const pft_tbd_filter_t *f)
{
    for (int r = 0; r < H + 2; ++r) {
        for (int k = 0; k < W + 2; ++k) {
            if (r == 0 || k == 0 || r == H + 1 || k == W + 1) {
                TEST_ASSERT_EQUAL_INT(0, (int)(f->img[r * (W + 2) + k] != PFT_C(0.0)));
            }
        }
    }
}

static void test_frame_conversion(void)
{
    pft_tbd_config_t c;
    base_cfg(&c);
    c.pixel_gain = R(0.5);
    c.pixel_offset = R(-3.0);
    c.n_search = 16u;
    const double sn = 3.2;
    TEST_ASSERT_EQUAL_INT(PFT_C(3.2), c.noise_sigma);
    pft_tbd_filter_t f;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_filter_init(&f, &c, g_ws, sizeof g_ws));

    static uint8_t u8[H][W + 3]; /* stride larger than the width */
    static uint16_t u16[H][W];
    for (int r = 0; r < H; ++r) {
        for (int k = 0; k < W; ++k) {
            u8[r][k] = (uint8_t)(r * 31 + k * 7);
            u16[r][k] = (uint16_t)(0xC000u | (unsigned)(r * 1000 + k * 3)); /* junk above bit 14 */
        }
    }
    pft_frame_t fr = {u8, W, H, W + 3, PFT_PIX_U8, 0, 0, 0};
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_filter_update(&f, &fr));
    for (int r = 0; r < H; ++r) {
        for (int k = 0; k < W; ++k) {
            double want = (0.5 * u8[r][k] - 3.0) / sn;
            TEST_ASSERT_DOUBLE_WITHIN(1e-6 + pft_test_lsb(want), want, img_at(&f, r, k));
        }
    }
    check_border(&f);
    pft_frame_t f16 = {u16, W, H, 2 * W, PFT_PIX_U16, 14, 0, 0};
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_filter_update(&f, &f16));
    for (int r = 0; r < H; ++r) {
        for (int k = 0; k < W; ++k) {
            double want = (0.5 * (double)(u16[r][k] & 0x3FFFu) - 3.0) / sn;
            TEST_ASSERT_DOUBLE_WITHIN(1e-6 * fabs(want) + pft_test_lsb(want), want,
                                      img_at(&f, r, k));
        }
    }
    /* gain large enough to exceed the q16 range: z clamped to 32767 in both builds (q16
     * saturates gain*raw before the offset is added, so the offset is 0 here), then whitened */
    c.pixel_gain = R(4.0);
    c.pixel_offset = R(0.0);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_filter_init(&f, &c, g_ws, sizeof g_ws));
    u16[0][0] = 0xFFFFu;
    f16.bit_depth = 0;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_filter_update(&f, &f16));
    TEST_ASSERT_DOUBLE_WITHIN(1e-3, 32767.0 / sn, img_at(&f, 0, 0));
    /* a sigma below 1 would take whitened pixels out of range: clamped to 32767 */
    c.noise_sigma = R(0.5);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_filter_init(&f, &c, g_ws, sizeof g_ws));
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_filter_update(&f, &f16));
    TEST_ASSERT_DOUBLE_WITHIN(1e-3, 32767.0, img_at(&f, 0, 0));
    c.noise_sigma = R(3.2);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_filter_init(&f, &c, g_ws, sizeof g_ws));

    static float f32[H][W];
    for (int r = 0; r < H; ++r) {
        for (int k = 0; k < W; ++k) {
            f32[r][k] = (float)(r - k) * 0.25f;
        }
    }
    pft_frame_t ff = {f32, W, H, 4 * W, PFT_PIX_F32, 0, 0, 0};
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_filter_update(&f, &ff));
    for (int r = 0; r < H; ++r) {
        for (int k = 0; k < W; ++k) {
            double want = (double)f32[r][k] / sn;
            TEST_ASSERT_DOUBLE_WITHIN(1e-6 + pft_test_lsb(want), want, img_at(&f, r, k));
        }
    }
    check_border(&f);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_defaults_are_the_papers);
    RUN_TEST(test_config_check_rejects);
    RUN_TEST(test_config_check_bounds_birth_prior);
    RUN_TEST(test_psf_h_matches_reference);
    RUN_TEST(test_llr_matches_reference);
    RUN_TEST(test_add_psf_and_joint_llr);
    RUN_TEST(test_filter_kernel_matches_reference);
    RUN_TEST(test_window_region);
    RUN_TEST(test_frame_conversion);
    return UNITY_END();
}
