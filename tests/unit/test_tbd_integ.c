/*
 * TBD manager: births from the peaks of a multi-frame integration (cfg.integ_alpha,
 * docs/algorithms.md 2.13) and the platform shift (pft_tbd_set_shift).
 *
 * Known answers: a dim point (peak 2 noise sigmas, PSF 0.7 px) moving 1 px per frame in white
 * Gaussian noise (64 x 64, unit sigma) is among the K = 4 birth peaks after 8 frames far more
 * often with the integration than with the current frame's peaks alone, over the same 32 seeds
 * and the same frames; a point moving 4 px per frame (outside the integration's 3 x 3 bin gate)
 * is found with pft_tbd_set_shift(4, 0) and not without. The peak scan of the sums on
 * noise-free frames: one lit pixel anywhere is the one candidate, two equal ones in
 * neighbouring bins give the first in raster order (inner and border bins). The workspace
 * formula with the integration equals the function and init needs every byte of it. Refused
 * config values (integ_alpha out of [0, 1), with no birth peaks or with a tile quota), a
 * refused frame and a refused shift leave everything byte-identical.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "pft_test_support.h"
#include "pft/pft_tbd.h"

void setUp(void) {}
void tearDown(void) {}

#define IMG 64
#define NS 100u
#define NT 20u
#define MAXT 1u
#define KMAX 4u
#define NSEED 32
#define LFR 8
#define AMP 2.0

static pft_real_t R(double v) { return pft_test_from_double(v); }

#define WS_BYTES                                                                               \
    (PFT_TBD_WORKSPACE_BYTES_PEAKS(NS, NT, MAXT, PFT_TBD_RBPF, IMG, IMG, KMAX) +               \
     PFT_TBD_INTEG_BYTES(IMG, IMG))
static uint64_t g_ws64[(WS_BYTES + 64) / 8 + 2];
static uint8_t g_snap[WS_BYTES + 64];
static uint16_t g_raw[IMG * IMG];

/* U16 frames: z = raw / 256 - 64 (zero at raw 16384), sigma 1 so z is whitened. */
static void cfg_integ(pft_tbd_config_t *c, double alpha)
{
    pft_test_tbd_u16_config(c, IMG, 1.0);
    c->n_search = NS;
    c->n_track = NT;
    c->max_targets = MAXT;
    c->birth_peaks = KMAX;
    c->peak_gamma = R(1.0);
    c->theta1 = R(1.0); /* no confirmation: the peaks depend on the frames alone */
    c->integ_alpha = R(alpha);
    c->seed = 5u;
}

/* The point's pixel-sampled PSF (sigma 0.7 px) times its peak, on the 7 x 7 pixels around it
 * (the point is always on a pixel centre; beyond 3 px the PSF is below 1e-4 of its peak). */
static double g_psf[7][7];

static void psf_table(double amp)
{
    for (int b = -3; b <= 3; ++b) {
        for (int a = -3; a <= 3; ++a) {
            g_psf[b + 3][a + 3] = amp * exp(-(double)(a * a + b * b) / (2.0 * 0.49));
        }
    }
}

/* xorshift64 */
static uint32_t rnd(uint64_t *st)
{
    *st ^= *st << 13;
    *st ^= *st >> 7;
    *st ^= *st << 17;
    return (uint32_t)(*st >> 32);
}

/* Frame k (1-based) from state st: unit-variance noise plus the point (g_psf) at
 * (x0 + v (k - 1), y0). The noise is the Irwin-Hall sum of 12 uniforms less 6 (mean 0,
 * variance 1, Gaussian to within 0.01 of its distribution function), drawn in integers
 * (raw units of 1/256: 12 uniforms on 0..255) so that it costs no floating-point operation on
 * the soft-float targets. */
static void render(uint64_t *st, int k, int x0, int y0, int v, pft_frame_t *f)
{
    const int x = x0 + v * (k - 1);
    for (int i = 0; i < IMG * IMG; ++i) {
        int32_t acc = 0;
        for (int q = 0; q < 3; ++q) {
            const uint32_t u = rnd(st);
            acc += (int32_t)(u & 255u) + (int32_t)((u >> 8) & 255u) + (int32_t)((u >> 16) & 255u) +
                   (int32_t)(u >> 24);
        }
        g_raw[i] = (uint16_t)(16384 + acc - 1530);
    }
    for (int b = -3; b <= 3; ++b) {
        for (int a = -3; a <= 3; ++a) {
            const int c = x + a;
            const int r = y0 + b;
            if (c >= 0 && c < IMG && r >= 0 && r < IMG) {
                g_raw[r * IMG + c] = (uint16_t)(g_raw[r * IMG + c] + (int)lround(g_psf[b + 3][a + 3] * 256.0));
            }
        }
    }
    *f = pft_test_u16_frame(g_raw, IMG, IMG, 16u, (uint32_t)k);
}

/* Runs LFR frames of seed s; true when a birth peak of the last frame is within 1 px
 * (Chebyshev) of the point's pixel at that frame. shift: given before every update. */
static bool found_after_l(double alpha, uint64_t s, int v, double shift)
{
    static pft_tbd_t t;
    pft_tbd_config_t c;
    cfg_integ(&c, alpha);
    const size_t need = pft_tbd_workspace_size(&c);
    TEST_ASSERT_TRUE(need > 0u && need <= sizeof g_ws64);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_init(&t, &c, g_ws64, need));
    uint64_t st = 0x9E3779B97F4A7C15ull * (s + 1u);
    const int x0 = 12;
    const int y0 = 31;
    psf_table(AMP);
    for (int k = 1; k <= LFR; ++k) {
        pft_frame_t f;
        render(&st, k, x0, y0, v, &f);
        if (k > 1 && shift != 0.0) {
            TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_set_shift(&t, R(shift), R(0.0)));
        }
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_update(&t, &f));
    }
    uint32_t cand[KMAX];
    const size_t n = pft_tbd_birth_candidates(&t, cand, KMAX);
    const long tc = (long)(x0 + v * (LFR - 1));
    const long tr = (long)y0;
    for (size_t i = 0; i < n && i < KMAX; ++i) {
        const long cc = (long)(cand[i] % IMG);
        const long rr = (long)(cand[i] / IMG);
        if (labs(cc - tc) <= 1 && labs(rr - tr) <= 1) {
            return true;
        }
    }
    return false;
}

static void test_integration_finds_a_dim_mover(void)
{
    int with = 0;
    int without = 0;
    for (uint64_t s = 1u; s <= NSEED; ++s) {
        with += found_after_l(0.7, s, 1, 0.0) ? 1 : 0;
        without += found_after_l(0.0, s, 1, 0.0) ? 1 : 0;
    }
    /* Tolerance: measured 28 of 32 with, 13 of 32 without (float and q16 alike). A 2-sigma
     * point's PSF-matched value is about 2.5 sigma, near the 4th largest of the ~800 noise
     * maxima of a 64 x 64 frame, so one frame finds it by chance. The bounds lie between the
     * two counts, each more than 2 binomial standard errors (sqrt(32 p (1 - p)): 1.9 and 2.8)
     * from its measured count; without the integration `with` would be the `without` count. */
    TEST_ASSERT_GREATER_OR_EQUAL_INT(22, with);
    TEST_ASSERT_LESS_OR_EQUAL_INT(19, without);
}

static void test_shift_follows_a_fast_mover(void)
{
    int with = 0;
    int without = 0;
    for (uint64_t s = 1u; s <= NSEED; ++s) {
        with += found_after_l(0.7, s, 4, 4.0) ? 1 : 0;
        without += found_after_l(0.7, s, 4, 0.0) ? 1 : 0;
    }
    /* 4 px per frame is two bins: outside the 3 x 3 bin gate unless the shift moves the sum.
     * Tolerance as above (measured 23 of 32 with the shift, 8 of 32 without, float and
     * q16 alike; standard errors 2.5 and 2.4). */
    TEST_ASSERT_GREATER_OR_EQUAL_INT(17, with);
    TEST_ASSERT_LESS_OR_EQUAL_INT(14, without);
}

static void test_workspace_with_integration_is_exact(void)
{
    static pft_tbd_t t;
    pft_tbd_config_t c;
    cfg_integ(&c, 0.7);
    const size_t need = pft_tbd_workspace_size(&c);
    TEST_ASSERT_EQUAL_UINT((unsigned)WS_BYTES, (unsigned)need);
    /* 2 x 2 bins of two 16-bit sums: one byte per pixel */
    TEST_ASSERT_EQUAL_UINT(IMG * IMG, (unsigned)PFT_TBD_INTEG_BYTES(IMG, IMG));
    /* a start one byte past an aligned address needs the whole alignment slack */
    uint8_t *w1 = (uint8_t *)g_ws64 + 1;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_NOMEM, pft_tbd_init(&t, &c, w1, need - 1u));
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_init(&t, &c, w1, need));
    cfg_integ(&c, 0.0);
    TEST_ASSERT_EQUAL_UINT((unsigned)PFT_TBD_WORKSPACE_BYTES_PEAKS(NS, NT, MAXT, PFT_TBD_RBPF,
                                                                   IMG, IMG, KMAX),
                           (unsigned)pft_tbd_workspace_size(&c));
}

static void test_integ_alpha_refused_by_name(void)
{
    pft_tbd_config_t c;
    const char *field = NULL;
    const double bad[3] = {-0.1, 1.0, 1.5};
    for (int i = 0; i < 3; ++i) {
        cfg_integ(&c, bad[i]);
        TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_tbd_config_check(&c, &field));
        TEST_ASSERT_EQUAL_STRING("integ_alpha", field);
    }
    cfg_integ(&c, 0.5);
    c.birth_peaks = 0u; /* the integration replaces the peaks' frame: it needs peaks */
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_tbd_config_check(&c, &field));
    TEST_ASSERT_EQUAL_STRING("integ_alpha", field);
    cfg_integ(&c, 0.5);
    c.peak_tile = 8u;
    c.peak_quota = 2u;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_tbd_config_check(&c, &field));
    TEST_ASSERT_EQUAL_STRING("integ_alpha", field);
    cfg_integ(&c, 0.99);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_config_check(&c, &field));
    pft_tbd_config_default(&c);
    TEST_ASSERT_TRUE(pft_test_to_double(c.integ_alpha) == 0.0);
}

static void test_refused_input_leaves_state_untouched(void)
{
    static pft_tbd_t t, t_snap;
    pft_tbd_config_t c;
    cfg_integ(&c, 0.7);
    const size_t need = pft_tbd_workspace_size(&c);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_init(&t, &c, g_ws64, need));
    uint64_t st = 77u;
    psf_table(3.0);
    for (int k = 1; k <= 4; ++k) {
        pft_frame_t f;
        render(&st, k, 20, 20, 1, &f);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_set_shift(&t, R(0.75), R(-0.25)));
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_update(&t, &f));
    }
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_set_shift(&t, R(1.5), R(0.5)));
    t_snap = t;
    memcpy(g_snap, g_ws64, need);
    pft_frame_t bad;
    render(&st, 5, 20, 20, 1, &bad);
    bad.width = IMG - 1; /* wrong size */
    TEST_ASSERT_EQUAL_INT(PFT_ERR_FORMAT, pft_tbd_update(&t, &bad));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tbd_set_shift(&t, R(IMG + 1.0), R(0.0)));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tbd_set_shift(&t, R(0.0), R(-IMG - 1.0)));
#ifndef PFT_NUMERIC_Q16
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tbd_set_shift(&t, NAN, R(0.0)));
#endif
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tbd_set_shift(NULL, R(0.0), R(0.0)));
    TEST_ASSERT_EQUAL_MEMORY(&t_snap, &t, sizeof t);
    TEST_ASSERT_EQUAL_MEMORY(g_snap, g_ws64, need);
}

/* One noise-free frame (z = 0) with amplitude a at the n pixels of px (0-based row-major), the
 * first update of a fresh manager: its birth candidates into cand, their count returned. */
static size_t peaks_of(const int *px, int n, double a, uint32_t *cand)
{
    static pft_tbd_t t;
    pft_tbd_config_t c;
    cfg_integ(&c, 0.7);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_init(&t, &c, g_ws64, pft_tbd_workspace_size(&c)));
    for (int i = 0; i < IMG * IMG; ++i) {
        g_raw[i] = 16384u;
    }
    for (int k = 0; k < n; ++k) {
        g_raw[px[k]] = (uint16_t)(16384 + (int)lround(a * 256.0));
    }
    pft_frame_t f = pft_test_u16_frame(g_raw, IMG, IMG, 16u, 1u);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_update(&t, &f));
    return pft_tbd_birth_candidates(&t, cand, KMAX);
}

/* Known answers of the integration's peak scan (the bins above the threshold, each a 3 x 3
 * local maximum of the bins' sums, at its largest pixel): one lit pixel anywhere in the frame
 * (every column of rows 0, 1, 30, 31 and 63, every row of columns 0, 17 and 63) is the one
 * candidate, so no bin is passed over; two equal lit pixels in neighbouring bins (across a
 * bin column, a bin row or a diagonal; inner bins and bins on the frame's border) give one
 * candidate, the first in raster order (a plateau's first bin wins: > the bins before it, >=
 * those after). Noise-free frames: the two pixels' PSF-matched values are the same sums in the
 * same order, so the two bins' sums are equal in both builds. */
static void test_integ_scan_every_bin_and_ties(void)
{
    uint32_t cand[KMAX];
    const int rows[5] = {0, 1, 30, 31, IMG - 1};
    for (int q = 0; q < 5; ++q) {
        for (int x = 0; x < IMG; ++x) {
            const int p = rows[q] * IMG + x;
            TEST_ASSERT_EQUAL_UINT_MESSAGE(1u, (unsigned)peaks_of(&p, 1, 6.0, cand), "row");
            TEST_ASSERT_EQUAL_UINT_MESSAGE((unsigned)p, cand[0], "row");
        }
    }
    const int cols[3] = {0, 17, IMG - 1};
    for (int q = 0; q < 3; ++q) {
        for (int y = 0; y < IMG; ++y) {
            const int p = y * IMG + cols[q];
            TEST_ASSERT_EQUAL_UINT_MESSAGE(1u, (unsigned)peaks_of(&p, 1, 6.0, cand), "column");
            TEST_ASSERT_EQUAL_UINT_MESSAGE((unsigned)p, cand[0], "column");
        }
    }
    /* pairs: (x, y) with x and y odd is a bin's last column and row, so (x + 1, y), (x, y + 1)
     * and (x + 1, y + 1) lie in the bins after its bin; (x + 1, y) and (x, y + 1) pair a bin
     * with the one below and to the left of it */
    const int at[4][2] = {{21, 25}, {1, 1}, {IMG - 3, IMG - 3}, {1, IMG - 3}};
    const int pair[4][4] = {{0, 0, 1, 0}, {0, 0, 0, 1}, {0, 0, 1, 1}, {1, 0, 0, 1}};
    for (int q = 0; q < 4; ++q) {
        for (int d = 0; d < 4; ++d) {
            const int x = at[q][0];
            const int y = at[q][1];
            const int px[2] = {(y + pair[d][1]) * IMG + x + pair[d][0],
                               (y + pair[d][3]) * IMG + x + pair[d][2]};
            const int first = px[0] < px[1] ? px[0] : px[1];
            TEST_ASSERT_EQUAL_UINT_MESSAGE(1u, (unsigned)peaks_of(px, 2, 6.0, cand), "pair");
            TEST_ASSERT_EQUAL_UINT_MESSAGE((unsigned)first, cand[0], "pair");
        }
    }
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_integration_finds_a_dim_mover);
    RUN_TEST(test_shift_follows_a_fast_mover);
    RUN_TEST(test_workspace_with_integration_is_exact);
    RUN_TEST(test_integ_alpha_refused_by_name);
    RUN_TEST(test_refused_input_leaves_state_untouched);
    RUN_TEST(test_integ_scan_every_bin_and_ties);
    return UNITY_END();
}
