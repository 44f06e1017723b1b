/*
 * TBD manager: births from peaks (cfg.birth_peaks, docs/algorithms.md 2.11) and the sequential
 * confirmation (cfg.confirm_frames).
 *
 * Known answers: on a frame of isolated bright pixels over a zero background the birth
 * candidates are exactly the pixels brighter than the threshold (each is the strict maximum of
 * its 3 x 3 neighbourhood of the PSF-correlated frame), capped at the K strongest; a plateau of
 * two equal pixels gives one peak (the first in raster order); peaks on the image border count.
 * The workspace formula with peaks equals the function and init needs every byte of it. A
 * refused frame leaves the manager (with peaks) and its workspace byte-identical. New fields
 * out of range are refused by name. confirm_frames = 3 confirms on the first frame that ends a
 * run of three with P > theta1 of the same search layer (the search layer does not depend on
 * the setting until the first confirmation). birth_share (the Bernoulli search layer): the
 * existence probability on an empty frame and on a bright point, and its range check; its share
 * of the per-frame particle budget with 0, 1 and 2 track layers; the bounded preset.
 */
#include <math.h>
#include <string.h>

#include "pft_test_support.h"
#include "pft_tbd_sim.h"
#include "pft/pft_tbd.h"

void setUp(void) {}
void tearDown(void) {}

#define IMG 32
#define NS 300u
#define NT 100u
#define MAXT 2u
#define KMAX 16u

static pft_real_t R(double v) { return pft_test_from_double(v); }
static double D(pft_real_t v) { return pft_test_to_double(v); }

#define WS_BYTES PFT_TBD_WORKSPACE_BYTES_PEAKS(NS, NT, MAXT, PFT_TBD_RBPF, IMG, IMG, KMAX)
/* the tests run the manager with and without peaks in one buffer: B_k's list holds one index
 * per pixel, the peaks' K only */
#define WS_BK PFT_TBD_WORKSPACE_BYTES(NS, NT, MAXT, PFT_TBD_RBPF, IMG, IMG)
#define WS_ANY (WS_BYTES > WS_BK ? WS_BYTES : WS_BK)
static uint8_t g_ws[WS_ANY + 64];
static uint8_t g_snap[WS_ANY + 64];
static uint16_t g_raw[IMG * IMG];

/* U16 frames: z = raw / 256 - 64 (zero background at raw 16384), sigma 1 so z is whitened. */
static void cfg_peaks(pft_tbd_config_t *c, uint16_t k)
{
    pft_test_tbd_u16_config(c, IMG, 1.0);
    c->n_search = NS;
    c->n_track = NT;
    c->max_targets = MAXT;
    c->birth_peaks = k;
    c->peak_gamma = R(1.0);
    c->theta1 = R(1.0); /* no confirmation (a hand-over reuses the candidate buffer) */
    c->seed = 3u;
}

static void clear_raw(void)
{
    for (int i = 0; i < IMG * IMG; ++i) {
        g_raw[i] = 16384u;
    }
}

static void set_px(int col, int row, double z) { g_raw[row * IMG + col] = (uint16_t)(16384.0 + z * 256.0); }

/* Isolated points, 4 px or more apart: (col, row, z). The last one is below the threshold
 * (peak_gamma 1 times the correlation's noise sigma, sqrt((1 + 2 g^2)^2) = 1.26 with
 * g = exp(-1 / (2 0.49)) for Sigma = 0.7; a lone pixel's correlation is its own value). */
#define NPTS 8
static const int g_pts[NPTS][2] = {{0, 0}, {31, 31}, {10, 5}, {20, 5}, {5, 15}, {15, 15}, {25, 25}, {10, 25}};
static const double g_val[NPTS] = {6.0, 9.0, 12.0, 15.0, 18.0, 21.0, 24.0, 1.0};

static bool has(const uint32_t *c, size_t n, uint32_t k)
{
    for (size_t i = 0; i < n; ++i) {
        if (c[i] == k) {
            return true;
        }
    }
    return false;
}

/* one update on the frame of the NPTS known points */
static void update_on_points(pft_tbd_t *t)
{
    clear_raw();
    for (int p = 0; p < NPTS; ++p) {
        set_px(g_pts[p][0], g_pts[p][1], g_val[p]);
    }
    pft_frame_t f = pft_test_u16_frame(g_raw, IMG, IMG, 16u, 1u);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_update(t, &f));
}

static void test_peaks_are_the_bright_points_capped_at_k(void)
{
    static pft_tbd_t t;
    const uint16_t ks[3] = {16u, 7u, 3u};
    for (int q = 0; q < 3; ++q) {
        pft_tbd_config_t c;
        cfg_peaks(&c, ks[q]);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_init(&t, &c, g_ws, sizeof g_ws));
        TEST_ASSERT_EQUAL_UINT(0u, (unsigned)pft_tbd_birth_candidates(&t, NULL, 0u));
        update_on_points(&t);
        TEST_ASSERT_EQUAL_UINT(0u, (unsigned)pft_tbd_tracks(&t, NULL, 0u));
        uint32_t cand[KMAX];
        size_t n = pft_tbd_birth_candidates(&t, cand, KMAX);
        /* seven points above the threshold; the K strongest of them are the last K */
        size_t want = ks[q] < 7u ? ks[q] : 7u;
        TEST_ASSERT_EQUAL_UINT((unsigned)want, (unsigned)n);
        for (int p = 0; p < NPTS; ++p) {
            uint32_t k = (uint32_t)(g_pts[p][1] * IMG + g_pts[p][0]);
            bool expect = p < 7 && p >= 7 - (int)want;
            TEST_ASSERT_EQUAL_INT_MESSAGE(expect ? 1 : 0, has(cand, n, k) ? 1 : 0, "peak set");
        }
    }
}

static void test_plateau_gives_one_peak_and_threshold_counts(void)
{
    static pft_tbd_t t;
    pft_tbd_config_t c;
    cfg_peaks(&c, KMAX);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_init(&t, &c, g_ws, sizeof g_ws));
    clear_raw();
    set_px(12, 12, 10.0);
    set_px(13, 12, 10.0); /* equal neighbour: one peak, the first in raster order */
    set_px(3, 20, 10.0);
    set_px(3, 21, 10.0);
    pft_frame_t f = pft_test_u16_frame(g_raw, IMG, IMG, 16u, 1u);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_update(&t, &f));
    uint32_t cand[KMAX];
    size_t n = pft_tbd_birth_candidates(&t, cand, KMAX);
    TEST_ASSERT_EQUAL_UINT(2u, (unsigned)n);
    TEST_ASSERT_TRUE(has(cand, n, 12u * IMG + 12u));
    TEST_ASSERT_TRUE(has(cand, n, 20u * IMG + 3u));
    /* a higher threshold removes both (correlation 10 (1 + g) = 13.6 < 20 noise sigmas * 1.26) */
    c.peak_gamma = R(20.0);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_init(&t, &c, g_ws, sizeof g_ws));
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_update(&t, &f));
    /* no peak: every pixel is proposed (as with an empty B_k) */
    TEST_ASSERT_EQUAL_UINT((unsigned)(IMG * IMG), (unsigned)pft_tbd_birth_candidates(&t, NULL, 0u));
}

/* Tile quota (cfg.peak_tile, cfg.peak_quota): the points of g_pts in 16 x 16 tiles are
 * tile 0: 6, 12, 18, 21; tile 1: 15; tile 3: 9, 24 (tile 2 only the point below the
 * threshold). With at most Q per tile the candidates are the K strongest of each tile's Q
 * strongest; without the quota they are the 7 (test above). */
static void test_tile_quota_keeps_the_strongest_per_tile(void)
{
    static pft_tbd_t t;
    const struct {
        uint16_t k;
        uint8_t q;
        int n;
        int pts[5];
    } cs[4] = {{KMAX, 1u, 3, {5, 3, 6, 0, 0}},
               {KMAX, 2u, 5, {5, 4, 3, 6, 1}},
               {3u, 2u, 3, {6, 5, 4, 0, 0}},
               {2u, 1u, 2, {6, 5, 0, 0, 0}}};
    for (int q = 0; q < 4; ++q) {
        pft_tbd_config_t c;
        cfg_peaks(&c, cs[q].k);
        c.peak_tile = 16u;
        c.peak_quota = cs[q].q;
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_init(&t, &c, g_ws, sizeof g_ws));
        update_on_points(&t);
        uint32_t cand[KMAX];
        size_t n = pft_tbd_birth_candidates(&t, cand, KMAX);
        TEST_ASSERT_EQUAL_UINT((unsigned)cs[q].n, (unsigned)n);
        for (int p = 0; p < cs[q].n; ++p) {
            const int j = cs[q].pts[p];
            TEST_ASSERT_TRUE_MESSAGE(has(cand, n, (uint32_t)(g_pts[j][1] * IMG + g_pts[j][0])),
                                     "quota peak set");
        }
    }
    /* a tile side of 0 leaves the quota off: the 7 points */
    pft_tbd_config_t c;
    cfg_peaks(&c, KMAX);
    c.peak_quota = 1u;
    c.peak_tile = 0u;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_tbd_config_check(&c, NULL));
    c.peak_quota = 0u;
    c.peak_tile = 16u;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_init(&t, &c, g_ws, sizeof g_ws));
    pft_frame_t f = pft_test_u16_frame(g_raw, IMG, IMG, 16u, 1u);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_update(&t, &f));
    TEST_ASSERT_EQUAL_UINT(7u, (unsigned)pft_tbd_birth_candidates(&t, NULL, 0u));
}

/* With peaks off the candidates are B_k = {z > gamma} as before. */
static void test_without_peaks_candidates_are_b(void)
{
    static pft_tbd_t t;
    pft_tbd_config_t c;
    cfg_peaks(&c, 0u);
    c.gamma = R(2.0);
    TEST_ASSERT_EQUAL_UINT((unsigned)PFT_TBD_WORKSPACE_BYTES(NS, NT, MAXT, PFT_TBD_RBPF, IMG, IMG),
                           (unsigned)pft_tbd_workspace_size(&c));
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_init(&t, &c, g_ws, sizeof g_ws));
    clear_raw();
    set_px(12, 12, 10.0);
    set_px(13, 12, 10.0);
    set_px(4, 4, 1.5);
    pft_frame_t f = pft_test_u16_frame(g_raw, IMG, IMG, 16u, 1u);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_update(&t, &f));
    uint32_t cand[4];
    TEST_ASSERT_EQUAL_UINT(2u, (unsigned)pft_tbd_birth_candidates(&t, cand, 4u));
    TEST_ASSERT_EQUAL_UINT(12u * IMG + 12u, cand[0]);
    TEST_ASSERT_EQUAL_UINT(12u * IMG + 13u, cand[1]);
}

/* Offset so that g_ws + off is 1 mod the alignment: the start needs every pad byte. */
static size_t misalign(const uint8_t *buf)
{
    size_t a = (size_t)((uintptr_t)buf % PFT_WS_ALIGN);
    return (1u + PFT_WS_ALIGN - a) % PFT_WS_ALIGN;
}

static void test_workspace_with_peaks_is_exact(void)
{
    static pft_tbd_t t;
    pft_tbd_config_t c;
    cfg_peaks(&c, KMAX);
    size_t need = pft_tbd_workspace_size(&c);
    TEST_ASSERT_EQUAL_UINT((unsigned)WS_BYTES, (unsigned)need);
    /* the candidate list holds K indices, not one per pixel (issue #9's memory goal): the
     * workspace is smaller than with B_k's list by at least (IMG^2 - K) indices less the peak
     * scan's six rows and K values (exact sizes: the macro, above) */
    TEST_ASSERT_TRUE(need + ((size_t)IMG * IMG - KMAX) * sizeof(uint32_t) -
                         (6u * IMG + KMAX) * sizeof(pft_real_t) - 2u * PFT_WS_ALIGN <=
                     PFT_TBD_WORKSPACE_BYTES(NS, NT, MAXT, PFT_TBD_RBPF, IMG, IMG));
    size_t off = misalign(g_ws);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_NOMEM, pft_tbd_init(&t, &c, g_ws + off, need - 1u));
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_init(&t, &c, g_ws + off, need));
    /* the last peak value is written by a frame with K peaks (a write past the end would be
     * caught by the sanitizer builds) */
    clear_raw();
    for (int p = 0; p < 4; ++p) {
        for (int q = 0; q < 4; ++q) {
            set_px(2 + 7 * p, 2 + 7 * q, 5.0 + p + 4 * q);
        }
    }
    pft_frame_t f = pft_test_u16_frame(g_raw, IMG, IMG, 16u, 1u);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_update(&t, &f));
    TEST_ASSERT_EQUAL_UINT(KMAX, (unsigned)pft_tbd_birth_candidates(&t, NULL, 0u));
}

static void test_new_fields_refused_by_name(void)
{
    pft_tbd_config_t c;
    const char *field = NULL;
    cfg_peaks(&c, (uint16_t)(PFT_TBD_MAX_PEAKS + 1u));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_tbd_config_check(&c, &field));
    TEST_ASSERT_EQUAL_STRING("birth_peaks", field);
    TEST_ASSERT_EQUAL_UINT(0u, (unsigned)pft_tbd_workspace_size(&c));
    cfg_peaks(&c, (uint16_t)PFT_TBD_MAX_PEAKS);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_config_check(&c, &field));
    c.confirm_frames = (uint8_t)(PFT_TBD_MAX_DIS_R + 2u);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_tbd_config_check(&c, &field));
    TEST_ASSERT_EQUAL_STRING("confirm_frames", field);
    cfg_peaks(&c, KMAX);
    c.peak_quota = 1u;
    c.peak_tile = 3u; /* a quota needs tiles of 4 px or more */
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_tbd_config_check(&c, &field));
    TEST_ASSERT_EQUAL_STRING("peak_tile", field);
    c.peak_tile = 4u; /* 64 tiles: K + 64 counters must fit the 1024 pixels */
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_config_check(&c, &field));
    c.birth_peaks = 961u;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_tbd_config_check(&c, &field));
    TEST_ASSERT_EQUAL_STRING("peak_quota", field);
    c.birth_peaks = 960u;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_config_check(&c, &field));
#ifndef PFT_NUMERIC_Q16
    cfg_peaks(&c, 4u);
    c.peak_gamma = NAN;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_tbd_config_check(&c, &field));
    TEST_ASSERT_EQUAL_STRING("peak_gamma", field);
#endif
    static pft_tbd_t t;
    cfg_peaks(&c, (uint16_t)(PFT_TBD_MAX_PEAKS + 1u));
    memset(g_ws, 0xA5, sizeof g_ws);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_tbd_init(&t, &c, g_ws, sizeof g_ws));
    for (size_t i = 0; i < sizeof g_ws; ++i) {
        TEST_ASSERT_EQUAL_UINT8(0xA5, g_ws[i]);
    }
}

static void test_refused_frame_leaves_state_untouched(void)
{
    static pft_tbd_t t, t_snap;
    pft_tbd_config_t c;
    cfg_peaks(&c, KMAX);
    c.noise_sigma = R(2.0);
    size_t need = pft_tbd_workspace_size(&c);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_init(&t, &c, g_ws, need));
    pft_rng_t sim;
    pft_rng_seed(&sim, 9u);
    const pft_sim_truth_t tr = {1, 20, 8.0, 9.0, 0.3, 0.2, 30.0};
    for (int k = 1; k <= 6; ++k) {
        pft_frame_t fr;
        pft_sim_render_u16(&sim, &tr, 1, k, 2.0, IMG, IMG, g_raw, &fr);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_update(&t, &fr));
    }
    t_snap = t;
    memcpy(g_snap, g_ws, need);
    pft_frame_t bad = pft_test_u16_frame(g_raw, IMG, IMG, 16u, 1u);
    bad.width = IMG - 1; /* wrong size */
    TEST_ASSERT_NOT_EQUAL(PFT_OK, pft_tbd_update(&t, &bad));
    bad = pft_test_u16_frame(g_raw, IMG, IMG, 16u, 1u);
    bad.stride_bytes = 3u; /* stride too small */
    TEST_ASSERT_NOT_EQUAL(PFT_OK, pft_tbd_update(&t, &bad));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tbd_update(&t, NULL));
    TEST_ASSERT_EQUAL_MEMORY(&t_snap, &t, sizeof t);
    TEST_ASSERT_EQUAL_MEMORY(g_snap, g_ws, need);
}

/* confirm_frames: the same search layer (same seed, same frames) until the first confirmation,
 * so m = 3 confirms at the first frame k with P > theta1 at k - 2, k - 1 and k of the m = 1
 * run's P sequence, provided the m = 1 run's confirmation did not change the frames before. */
#define CF_FRAMES 16
static void run_confirm(uint8_t m, double *p, int *first)
{
    static pft_tbd_t t;
    pft_tbd_config_t c;
    cfg_peaks(&c, 8u);
    c.noise_sigma = R(2.0);
    c.confirm_frames = m;
    c.theta1 = R(0.6);
    c.max_targets = 1u; /* NS, NT and MAXT = 2 fit: one layer fewer */
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_init(&t, &c, g_ws, sizeof g_ws));
    pft_rng_t sim;
    pft_rng_seed(&sim, 21u);
    const pft_sim_truth_t tr = {3, 16, 12.0, 14.0, 0.3, 0.2, 22.0};
    *first = -1;
    for (int k = 1; k <= CF_FRAMES; ++k) {
        pft_frame_t fr;
        pft_sim_render_u16(&sim, &tr, 1, k, 2.0, IMG, IMG, g_raw, &fr);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_update(&t, &fr));
        pft_tbd_estimate_t e;
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_search_estimate(&t, &e));
        p[k - 1] = D(e.p_exist);
        pft_tbd_event_t ev[2];
        size_t ne = pft_tbd_events(&t, ev, 2u);
        for (size_t i = 0; i < ne; ++i) {
            if (ev[i].kind == PFT_TBD_EV_CONFIRMED && *first < 0) {
                *first = k;
            }
        }
    }
}

static void test_confirm_frames_waits_for_a_run(void)
{
    double p1[CF_FRAMES], p3[CF_FRAMES];
    int f1 = -1, f3 = -1;
    run_confirm(1u, p1, &f1);
    run_confirm(3u, p3, &f3);
    TEST_ASSERT_TRUE_MESSAGE(f1 > 0, "m = 1 confirms the bright target");
    TEST_ASSERT_TRUE_MESSAGE(f3 > 0, "m = 3 confirms it too");
    /* identical search layers up to m = 1's confirmation frame */
    for (int k = 0; k < f1; ++k) {
        TEST_ASSERT_TRUE(p1[k] == p3[k]);
    }
    /* m = 3 confirms at the end of the first run of three frames above theta1 */
    int want = -1;
    for (int k = 3; k <= CF_FRAMES && want < 0; ++k) {
        if (p3[k - 3] > 0.6 && p3[k - 2] > 0.6 && p3[k - 1] > 0.6) {
            want = k;
        }
    }
    TEST_ASSERT_EQUAL_INT(want, f3);
    TEST_ASSERT_TRUE(f3 >= f1 + 2);
}

/* birth_share (Bernoulli form, docs/algorithms.md 2.11): on an empty frame (every pixel 0) the
 * existence probability of the first frame falls below its prior eta (every birth's likelihood
 * ratio is below 1); a bright point target then takes it above 0.99 within three frames, with
 * the estimate within half a pixel; the field is refused above 0.95 by name. */
static void test_birth_share_existence(void)
{
    static pft_tbd_t t;
    pft_tbd_config_t c;
    const char *field = NULL;
    cfg_peaks(&c, 0u);
    c.birth_share = R(0.96);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_tbd_config_check(&c, &field));
    TEST_ASSERT_EQUAL_STRING("birth_share", field);
    for (int kind = 0; kind < 2; ++kind) {
        cfg_peaks(&c, kind == 0 ? 0u : 8u); /* PF: births from peaks */
        c.birth_share = R(0.5);
        c.kind = (pft_tbd_kind_t)kind;
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_init(&t, &c, g_ws, sizeof g_ws));
        clear_raw();
        pft_frame_t f = pft_test_u16_frame(g_raw, IMG, IMG, 16u, 1u);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_update(&t, &f));
        pft_tbd_estimate_t e;
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_search_estimate(&t, &e));
        TEST_ASSERT_TRUE(D(e.p_exist) < 0.05 && D(e.p_exist) > 0.0);
        /* a point of peak 20 noise sigmas at (10, 12) (the PSF of an intensity above i_max:
         * the likelihood still favours the births on it) */
        for (int k = 0; k < 3; ++k) {
            clear_raw();
            for (int dr = -1; dr <= 1; ++dr) {
                for (int dc = -1; dc <= 1; ++dc) {
                    set_px(10 + dc, 12 + dr, 20.0 * exp(-(dc * dc + dr * dr) / 0.98));
                }
            }
            TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_update(&t, &f));
        }
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_search_estimate(&t, &e));
        TEST_ASSERT_TRUE_MESSAGE(D(e.p_exist) > 0.99, "existence on a bright point");
        /* RBPF within half a pixel; the PF samples velocities (variance 1/3 px^2 per frame,
         * about 0.6 px of spread per frame for 300 particles): within 1 px (measured when
         * written, largest coordinate error: 0.10 px RBPF, 0.15 / 0.69 px PF float / q16) */
        {
            const double tol = kind == 0 ? 0.5 : 1.0;
            TEST_ASSERT_TRUE(fabs(D(e.x) - 10.0) < tol && fabs(D(e.y) - 12.0) < tol);
        }
    }
}

/* The standalone filter in Bernoulli form: the same existence on an empty frame, and a
 * refused frame leaves it byte-identical. */
static void test_birth_share_standalone(void)
{
    static pft_tbd_filter_t f, f_snap;
    pft_tbd_config_t c;
    cfg_peaks(&c, 0u);
    c.birth_share = R(0.25);
    size_t need = pft_tbd_filter_workspace_size(&c);
    TEST_ASSERT_TRUE(need > 0u && need <= sizeof g_ws);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_filter_init(&f, &c, g_ws, need));
    clear_raw();
    pft_frame_t fr = pft_test_u16_frame(g_raw, IMG, IMG, 16u, 1u);
    for (int k = 0; k < 3; ++k) {
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_filter_update(&f, &fr));
    }
    pft_tbd_estimate_t e;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_filter_estimate(&f, &e));
    TEST_ASSERT_TRUE(D(e.p_exist) < 0.05);
    f_snap = f;
    memcpy(g_snap, g_ws, need);
    pft_frame_t bad = fr;
    bad.height = IMG + 1;
    TEST_ASSERT_NOT_EQUAL(PFT_OK, pft_tbd_filter_update(&f, &bad));
    TEST_ASSERT_EQUAL_MEMORY(&f_snap, &f, sizeof f);
    TEST_ASSERT_EQUAL_MEMORY(g_snap, g_ws, need);
}

/* Bright points of peak 20 noise sigmas at the first np of (10, 12) and (24, 20). */
static void points(int np)
{
    static const int pt[2][2] = {{10, 12}, {24, 20}};
    clear_raw();
    for (int i = 0; i < np; ++i) {
        for (int dr = -1; dr <= 1; ++dr) {
            for (int dc = -1; dc <= 1; ++dc) {
                set_px(pt[i][0] + dc, pt[i][1] + dr, 20.0 * exp(-(dc * dc + dr * dr) / 0.98));
            }
        }
    }
}

/* Frames without peaks and a constraint region: the uniform proposal over the allowed pixels
 * (drawn from per-row counts without a list) puts every birth outside the region, spreads
 * them over the frame, and pft_tbd_birth_candidates lists exactly the allowed pixels in
 * raster order. No frame has a peak (peak_gamma 1000); force_constraint off, so that a birth
 * inside the region would survive the weighing and be seen; Bernoulli form, so that about half
 * of the NS particles are born at every frame (a pick that ignored the mask would put each
 * birth in the 25-pixel region with probability 25/1024, so that none of ~150 births lands
 * there with probability (1 - 0.024)^150 = 0.03; the spread tests below catch a pick confined
 * to the first rows). */
static void test_uniform_births_skip_region(void)
{
    static pft_tbd_t t;
    static uint32_t cand[IMG * IMG];
    pft_tbd_config_t c;
    pft_frame_t f;
    cfg_peaks(&c, KMAX);
    c.peak_gamma = R(1000.0);
    c.theta1 = R(0.6);
    c.birth_share = R(0.5);
    c.theta_end = R(0.0);           /* the track is not ended by a low P at the next frame */
    c.d_region = PFT_TBD_D_WINDOW;  /* 3 x 3 window grown by d_margin 1: 5 x 5 pixels */
    c.force_constraint = false;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_init(&t, &c, g_ws, sizeof g_ws));
    f = pft_test_u16_frame(g_raw, IMG, IMG, 16u, 1u);
    points(1);
    for (int k = 0; k < 30 && pft_tbd_tracks(&t, NULL, 0u) == 0u; ++k) {
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_update(&t, &f));
    }
    TEST_ASSERT_EQUAL_UINT32_MESSAGE(1u, (uint32_t)pft_tbd_tracks(&t, NULL, 0u), "confirmed");
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_update(&t, &f)); /* a frame with the region */
    pft_tbd_track_t tr;
    TEST_ASSERT_EQUAL_UINT32(1u, (uint32_t)pft_tbd_tracks(&t, &tr, 1u));
    pft_tbd_region_t r = pft_tbd_window_region(&c, tr.x, tr.y);
    r.col_lo -= 1;
    r.col_hi += 1;
    r.row_lo -= 1;
    r.row_hi += 1;
    TEST_ASSERT_TRUE(r.col_lo >= 0 && r.col_hi < IMG && r.row_lo >= 0 && r.row_hi < IMG);
    const uint32_t area = (uint32_t)((r.col_hi - r.col_lo + 1) * (r.row_hi - r.row_lo + 1));
    const size_t n = pft_tbd_birth_candidates(&t, cand, IMG * IMG);
    TEST_ASSERT_EQUAL_UINT32(IMG * IMG - area, (uint32_t)n);
    for (size_t i = 0; i < n; ++i) {
        const int32_t col = (int32_t)(cand[i] % IMG);
        const int32_t row = (int32_t)(cand[i] / IMG);
        TEST_ASSERT_FALSE(col >= r.col_lo && col <= r.col_hi && row >= r.row_lo && row <= r.row_hi);
        TEST_ASSERT_TRUE(i == 0u || cand[i] > cand[i - 1u]);
    }
    uint32_t born = 0u, below = 0u, beside = 0u;
    for (uint32_t s = 0; s < t.search.n; ++s) {
        if (t.search.cur.e[s] != 1u) {
            continue; /* not born at this frame */
        }
        /* 0-based window centre: round(x) of the internal 1-based position, less 1 */
        const int32_t col = (int32_t)floor(D(t.search.cur.x[s]) + 0.5) - 1;
        const int32_t row = (int32_t)floor(D(t.search.cur.y[s]) + 0.5) - 1;
        TEST_ASSERT_FALSE(col >= r.col_lo && col <= r.col_hi && row >= r.row_lo && row <= r.row_hi);
        ++born;
        below += row > r.row_hi ? 1u : 0u;
        beside += row >= r.row_lo && row <= r.row_hi ? 1u : 0u;
    }
    /* about NS / 2 births (binomial, sd ~9) spread uniformly: rows below the region hold
     * (IMG - 1 - row_hi) / IMG of them, at least 1/4 here, so expecting 10 or more is safe;
     * the region's rows 5/32 of them (expect ~23: at least 3) */
    TEST_ASSERT_TRUE_MESSAGE(born >= 100u, "births at the frame without peaks");
    TEST_ASSERT_TRUE_MESSAGE(below >= 10u, "births below the region");
    TEST_ASSERT_TRUE_MESSAGE(beside >= 3u, "births beside the region, in its rows");
}

/* The Bernoulli search layer's share of the particle budget (issue #12, docs/algorithms.md
 * 2.11): at a frame that steps k track layers it moves and weighs n_search - k n_track
 * particles, at least n_search / 4; the paper's form keeps all n_search. With n_search 200 and
 * n_track 100: 200, then 100 after the first confirmation, then 50 (the floor) after the
 * second; back to 200 once the tracks have ended. */
static void test_birth_share_budget(void)
{
    static pft_tbd_t t;
    pft_tbd_config_t c;
    pft_frame_t f;
    cfg_peaks(&c, 0u);
    c.n_search = 200u;
    c.theta1 = R(0.6);
    c.birth_share = R(0.5);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_init(&t, &c, g_ws, sizeof g_ws));
    f = pft_test_u16_frame(g_raw, IMG, IMG, 16u, 1u);
    uint32_t seen[3] = {0u, 0u, 0u}; /* frames seen with 0, 1, 2 layers stepped */
    for (int k = 0; k < 40; ++k) {
        points(k < 8 ? 1 : (k < 20 ? 2 : 0));
        const size_t before = pft_tbd_tracks(&t, NULL, 0u);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_update(&t, &f));
        TEST_ASSERT_TRUE(before <= 2u);
        const uint32_t want = before == 0u ? 200u : (before == 1u ? 100u : 50u);
        TEST_ASSERT_EQUAL_UINT32(want, t.search.n);
        ++seen[before];
    }
    TEST_ASSERT_TRUE_MESSAGE(seen[1] > 0u && seen[2] > 0u, "one and two tracks were reached");
    TEST_ASSERT_EQUAL_UINT32(200u, t.search.n);
    TEST_ASSERT_EQUAL_UINT32(0u, (uint32_t)pft_tbd_tracks(&t, NULL, 0u));
    /* the paper's form: every search particle at every frame */
    c.birth_share = R(0.0);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_init(&t, &c, g_ws, sizeof g_ws));
    size_t most = 0u;
    for (int k = 0; k < 12; ++k) {
        points(1);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_update(&t, &f));
        TEST_ASSERT_EQUAL_UINT32(200u, t.search.n);
        const size_t n = pft_tbd_tracks(&t, NULL, 0u);
        most = n > most ? n : most;
    }
    TEST_ASSERT_TRUE_MESSAGE(most >= 1u, "the paper's form confirmed the point");
}

/* pft_tbd_config_bounded: the recommended preset with the Bernoulli search layer (birth_share
 * 0.5), theta1 0.475 and n_search 3000, nothing else changed; it passes the check and NULL is
 * ignored. */
static void test_bounded_preset(void)
{
    pft_tbd_config_t r, b;
    pft_tbd_config_recommended(&r);
    pft_tbd_config_bounded(&b);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_config_check(&b, NULL));
    TEST_ASSERT_TRUE(D(b.birth_share) == 0.5);
    TEST_ASSERT_TRUE(fabs(D(b.theta1) - 0.475) < 1e-4);
    TEST_ASSERT_EQUAL_UINT32(3000u, b.n_search);
    r.birth_share = b.birth_share;
    r.theta1 = b.theta1;
    r.n_search = b.n_search;
    TEST_ASSERT_EQUAL_MEMORY(&r, &b, sizeof r);
    pft_tbd_config_bounded(NULL);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_peaks_are_the_bright_points_capped_at_k);
    RUN_TEST(test_plateau_gives_one_peak_and_threshold_counts);
    RUN_TEST(test_tile_quota_keeps_the_strongest_per_tile);
    RUN_TEST(test_without_peaks_candidates_are_b);
    RUN_TEST(test_workspace_with_peaks_is_exact);
    RUN_TEST(test_new_fields_refused_by_name);
    RUN_TEST(test_refused_frame_leaves_state_untouched);
    RUN_TEST(test_confirm_frames_waits_for_a_run);
    RUN_TEST(test_birth_share_existence);
    RUN_TEST(test_birth_share_standalone);
    RUN_TEST(test_birth_share_budget);
    RUN_TEST(test_uniform_births_skip_region);
    RUN_TEST(test_bounded_preset);
    return UNITY_END();
}
