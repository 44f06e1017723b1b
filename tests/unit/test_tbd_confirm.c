/*
 * TBD manager: the sequential confirmation test of a new track (cfg.sprt_accept, sprt_reject;
 * Wald's SPRT on the track layer's frame log likelihood ratios) and the PSF shape test at the
 * hand-over (cfg.shape_ring), docs/algorithms.md 2.12.
 *
 * Known answers, from a run of the same manager with the test off: the test changes no layer
 * (the tentative track runs and explains its target away as a reported one would), so on the
 * same frames the run with the test hands over at the same frame h, reports nothing until the
 * first frame k > h at which the sum of the track's log_mean_lr over frames h + 1 .. k (read
 * from the run without the test) reaches sprt_accept, then reports the track with a CONFIRMED
 * event at frame k, first_frame k and that sum as sprt_llr. A target that disappears before the
 * sum reaches the bound leaves no report and no event at all, while the run without the test
 * reports it and ends it. With sprt_reject halfway between 0 and the sum at its first negative
 * value the tentative track is dropped at that frame, unreported (its layer is freed: the
 * instance's layer count, read from the internal layout). Fields out of range are refused by
 * name, and a refused frame leaves the manager with a tentative track and its workspace
 * byte-identical. Shape test, on noise-free frames: a point (the PSF, peak 8) is handed over
 * with shape_ring 0.25; a blob wider than the PSF (a Gaussian of sigma 3 px: ring mean
 * 0.40 of the fitted amplitude) is handed over without the test and never with it (the
 * search layer is cleared instead).
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
#define KP 8u
#define FRAMES 24

static pft_real_t R(double v) { return pft_test_from_double(v); }
static double D(pft_real_t v) { return pft_test_to_double(v); }

#define WS_BYTES PFT_TBD_WORKSPACE_BYTES_PEAKS(NS, NT, MAXT, PFT_TBD_RBPF, IMG, IMG, KP)
static uint8_t g_ws[WS_BYTES + 64];
static uint8_t g_snap[WS_BYTES + 64];
static uint16_t g_raw[IMG * IMG];

/* The recommended preset on 32 x 32 U16 frames of sigma 2 (z = raw / 256 - 64). */
static uint8_t g_start; /* cfg.sprt_start of the next run */

static void cfg_of(pft_tbd_config_t *c, double accept, double reject)
{
    pft_test_tbd_u16_config(c, IMG, 2.0);
    c->n_search = NS;
    c->n_track = NT;
    c->max_targets = MAXT;
    c->birth_peaks = KP;
    c->theta1 = R(0.6);
    c->seed = 3u;
    c->sprt_accept = R(accept);
    c->sprt_reject = R(reject);
    c->sprt_start = g_start;
}

/* What one run saw per frame (index k - 1). */
typedef struct {
    int n_tracks[FRAMES];       /* pft_tbd_tracks' count */
    int has1[FRAMES];           /* track id 1 (the first hand-over) reported */
    double llr[FRAMES];         /* its log_mean_lr */
    double sprt[FRAMES];        /* its sprt_llr */
    uint32_t first[FRAMES];     /* its first_frame */
    int confirmed[FRAMES];      /* CONFIRMED events */
    int ended[FRAMES];          /* ENDED events */
    int layers[FRAMES];         /* track layers running, tentative ones included (the
                                   instance's n_tracks, pft/internal/pft_tbd_types.h) */
    int start_seen[FRAMES];     /* track id 1 tentative at its hand-over frame (age 0) */
    double start[FRAMES];       /* then its sprt_llr (the start of its sum) */
    double start1[FRAMES];      /* and what sprt_start 1 and 2 give, from the search layer */
    double start2[FRAMES];      /* (internal layout), in double */
    double rx[FRAMES], ry[FRAMES]; /* track id 1's position from pft_tbd_tracks */
    int tent1[FRAMES];          /* track id 1 listed by pft_tbd_tentative */
    int n_tent[FRAMES];         /* pft_tbd_tentative's count */
    double tx[FRAMES], ty[FRAMES]; /* then its position */
    uint32_t tage[FRAMES];      /* and its age */
} run_t;

static pft_tbd_t g_t;

/* One target present in frames 1..last at (12, 14) + k (0.3, 0.2), intensity 22, sigma 2. */
static void run(double accept, double reject, int last, double theta_end, run_t *o)
{
    pft_tbd_config_t c;
    cfg_of(&c, accept, reject);
    c.theta_end = R(theta_end);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_init(&g_t, &c, g_ws, sizeof g_ws));
    memset(o, 0, sizeof(*o));
    pft_rng_t sim;
    pft_rng_seed(&sim, 21u);
    const pft_sim_truth_t tr = {1, last, 12.0, 14.0, 0.3, 0.2, 22.0};
    for (int k = 1; k <= FRAMES; ++k) {
        pft_frame_t fr;
        pft_sim_render_u16(&sim, &tr, 1, k, 2.0, IMG, IMG, g_raw, &fr);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_update(&g_t, &fr));
        pft_tbd_track_t tk[MAXT];
        size_t n = pft_tbd_tracks(&g_t, tk, MAXT);
        o->n_tracks[k - 1] = (int)n;
        o->layers[k - 1] = (int)g_t.n_tracks;
        for (uint32_t u = 0; u < MAXT; ++u) {
            const pft_tbd_track_t *rec = &g_t.records[u];
            if (rec->id == 1u && rec->first_frame == 0u && rec->age == 0u) {
                const pft_tbd_filter_t *sf = &g_t.search;
                const uint32_t need = c.confirm_frames > 1u ? c.confirm_frames : 1u;
                double s1 = 0.0;
                for (uint32_t q = 0; q < need && q < sf->n_lr; ++q) {
                    s1 += D(sf->lr_hist[q]);
                }
                const double p = D(sf->est.p_exist);
                const double s2 = log(fmax(p, 1e-4) / fmax(1.0 - p, 1e-4));
                o->start_seen[k - 1] = 1;
                o->start[k - 1] = D(rec->sprt_llr);
                o->start1[k - 1] = fmax(s1, 0.0);
                o->start2[k - 1] = fmax(s2, 0.0);
            }
        }
        for (size_t i = 0; i < n && i < MAXT; ++i) {
            if (tk[i].id == 1u) {
                o->has1[k - 1] = 1;
                o->llr[k - 1] = D(tk[i].log_mean_lr);
                o->sprt[k - 1] = D(tk[i].sprt_llr);
                o->first[k - 1] = tk[i].first_frame;
                o->rx[k - 1] = D(tk[i].x);
                o->ry[k - 1] = D(tk[i].y);
            }
        }
        pft_tbd_track_t tt[MAXT];
        const size_t nt = pft_tbd_tentative(&g_t, tt, MAXT);
        o->n_tent[k - 1] = (int)nt;
        for (size_t i = 0; i < nt && i < MAXT; ++i) {
            TEST_ASSERT_EQUAL_UINT32(0u, tt[i].first_frame);
            if (tt[i].id == 1u) {
                o->tent1[k - 1] = 1;
                o->tx[k - 1] = D(tt[i].x);
                o->ty[k - 1] = D(tt[i].y);
                o->tage[k - 1] = tt[i].age;
            }
        }
        pft_tbd_event_t ev[MAXT + 1u];
        size_t ne = pft_tbd_events(&g_t, ev, MAXT + 1u);
        for (size_t i = 0; i < ne; ++i) {
            o->confirmed[k - 1] += ev[i].kind == PFT_TBD_EV_CONFIRMED ? 1 : 0;
            o->ended[k - 1] += ev[i].kind == PFT_TBD_EV_ENDED ? 1 : 0;
        }
    }
}

/* The hand-over frame of a run without the test: its first CONFIRMED event. */
static int handover(const run_t *o)
{
    for (int k = 1; k <= FRAMES; ++k) {
        if (o->confirmed[k - 1] > 0) {
            return k;
        }
    }
    return -1;
}

/* Tolerance of the sums: float adds the same float values in the same order (exact up to the
 * rounding of the test's double sum, about 1e-5 relative here); q16 adds Q16.16 values exactly,
 * and the reported values convert exactly. 1e-3 covers both. */
#define SUM_TOL 1e-3

static void test_accepts_at_the_bound_with_the_known_sum(void)
{
    static run_t off, on;
    run(0.0, -5.0, FRAMES, 0.5, &off);
    const int h = handover(&off);
    TEST_ASSERT_TRUE_MESSAGE(h > 0 && h < FRAMES - 6, "the bright target is handed over early");
    /* the bound: the sum of the first four frames after the hand-over less a little, so the
     * test accepts at h + 4 if no earlier partial sum reaches it */
    double s = 0.0, bound = 0.0;
    for (int k = h + 1; k <= h + 4; ++k) {
        TEST_ASSERT_EQUAL_INT(1, off.has1[k - 1]);
        s += off.llr[k - 1];
    }
    bound = s - 0.01;
    TEST_ASSERT_TRUE_MESSAGE(bound > 0.0, "a target's frames favour it");
    int want = -1;
    double want_sum = 0.0;
    s = 0.0;
    for (int k = h + 1; k <= FRAMES && want < 0 && off.has1[k - 1]; ++k) {
        s += off.llr[k - 1];
        if (s >= bound) {
            want = k;
            want_sum = s;
        }
    }
    run(bound, -5.0, FRAMES, 0.5, &on);
    TEST_ASSERT_TRUE_MESSAGE(want > h, "the bound is reached while the track lives");
    for (int k = 1; k < want; ++k) {
        TEST_ASSERT_EQUAL_INT_MESSAGE(0, on.has1[k - 1], "tentative: not reported");
    }
    TEST_ASSERT_EQUAL_INT(1, on.has1[want - 1]);
    TEST_ASSERT_TRUE(on.confirmed[want - 1] >= 1);
    TEST_ASSERT_EQUAL_UINT32((uint32_t)want, on.first[want - 1]);
    TEST_ASSERT_DOUBLE_WITHIN(SUM_TOL * (1.0 + fabs(want_sum)), want_sum, on.sprt[want - 1]);
    /* after acceptance it is the same track as without the test: the layers are the same */
    for (int k = 1; k <= FRAMES; ++k) {
        TEST_ASSERT_EQUAL_INT(off.layers[k - 1], on.layers[k - 1]);
        if (k >= want) {
            TEST_ASSERT_EQUAL_INT(off.has1[k - 1], on.has1[k - 1]);
            TEST_ASSERT_TRUE(off.llr[k - 1] == on.llr[k - 1]);
        }
    }
}

static void test_a_short_track_is_never_reported(void)
{
    static run_t off, on;
    run(0.0, -5.0, 8, 0.5, &off); /* the target leaves after frame 8 */
    const int h = handover(&off);
    TEST_ASSERT_TRUE_MESSAGE(h > 0 && h <= 8, "handed over while present");
    int ended_off = 0, ended_on = 0, conf_on = 0, rep_on = 0;
    for (int k = 1; k <= FRAMES; ++k) {
        ended_off += off.ended[k - 1];
    }
    TEST_ASSERT_TRUE_MESSAGE(ended_off >= 1, "without the test the track is reported and ended");
    /* a bound the sum cannot reach over the target's few frames (at most ~25 per frame here) */
    run(1000.0, -1000.0, 8, 0.5, &on);
    for (int k = 1; k <= FRAMES; ++k) {
        ended_on += on.ended[k - 1];
        conf_on += on.confirmed[k - 1];
        rep_on += on.n_tracks[k - 1];
    }
    TEST_ASSERT_EQUAL_INT(0, conf_on);
    TEST_ASSERT_EQUAL_INT(0, ended_on);
    TEST_ASSERT_EQUAL_INT(0, rep_on);
}

/* pft_tbd_tentative lists the tentative track at the position, in the coordinates of
 * pft_tbd_tracks, that the run without the test reports for it: the same layer on the same
 * frames. With the test off it lists nothing. */
static void test_tentative_tracks_listed_where_reported_without_the_test(void)
{
    static run_t off, on;
    run(0.0, -5.0, FRAMES, 0.5, &off);
    const int h = handover(&off);
    TEST_ASSERT_TRUE_MESSAGE(h > 0 && h < FRAMES - 6, "the bright target is handed over early");
    run(1000.0, -1000.0, FRAMES, 0.5, &on); /* never accepted, never rejected */
    int seen = 0;
    for (int k = 1; k <= FRAMES; ++k) {
        TEST_ASSERT_EQUAL_INT(0, off.n_tent[k - 1]);
        TEST_ASSERT_EQUAL_INT(0, on.n_tracks[k - 1]);
        TEST_ASSERT_EQUAL_INT(off.has1[k - 1], on.tent1[k - 1]);
        if (on.tent1[k - 1]) {
            TEST_ASSERT_EQUAL_UINT32((uint32_t)(k - h), on.tage[k - 1]);
            TEST_ASSERT_TRUE(on.tx[k - 1] == off.rx[k - 1]);
            TEST_ASSERT_TRUE(on.ty[k - 1] == off.ry[k - 1]);
            /* and near the target ((12, 14) + k (0.3, 0.2) in 0-based pixels) */
            TEST_ASSERT_DOUBLE_WITHIN(1.0, 12.0 + 0.3 * k, on.tx[k - 1]);
            TEST_ASSERT_DOUBLE_WITHIN(1.0, 14.0 + 0.2 * k, on.ty[k - 1]);
            ++seen;
        }
    }
    TEST_ASSERT_TRUE_MESSAGE(seen >= 6, "the tentative track lives for several frames");
    TEST_ASSERT_EQUAL_UINT32(0u, (uint32_t)pft_tbd_tentative(NULL, NULL, 0u));
    TEST_ASSERT_EQUAL_UINT32((uint32_t)on.n_tent[FRAMES - 1], (uint32_t)pft_tbd_tentative(&g_t, NULL, 0u));
}

static void test_reject_bound_drops_the_tentative_track(void)
{
    static run_t off, on;
    /* theta_end low, so that the track outlives its target by a few frames of noise */
    run(0.0, -5.0, 1, 0.01, &off); /* the target is there on the first frame only */
    const int h = handover(&off);
    TEST_ASSERT_TRUE(h > 0);
    /* the first frame after the hand-over at which the running sum is negative */
    double s = 0.0;
    int drop = -1;
    for (int k = h + 1; k <= FRAMES && drop < 0 && off.has1[k - 1]; ++k) {
        s += off.llr[k - 1];
        if (s < 0.0) {
            drop = k;
        }
    }
    TEST_ASSERT_TRUE_MESSAGE(drop > 0, "the sum turns negative after the target has left");
    TEST_ASSERT_TRUE(off.layers[drop - 1] >= 1); /* kept without the bound */
    /* the bound halfway between that sum and 0: every earlier partial sum is >= 0 above it */
    run(1000.0, s / 2.0, 1, 0.01, &on);
    for (int k = 1; k < drop; ++k) {
        TEST_ASSERT_EQUAL_INT(off.layers[k - 1], on.layers[k - 1]);
    }
    TEST_ASSERT_EQUAL_INT_MESSAGE(off.layers[drop - 1] - 1, on.layers[drop - 1],
                                  "dropped at the first negative sum");
    for (int k = 1; k <= FRAMES; ++k) {
        TEST_ASSERT_EQUAL_INT(0, on.n_tracks[k - 1]);
        TEST_ASSERT_EQUAL_INT(0, on.confirmed[k - 1]);
        TEST_ASSERT_EQUAL_INT(0, on.ended[k - 1]);
    }
}

static void test_fields_refused_by_name(void)
{
    pft_tbd_config_t c;
    const char *field = NULL;
    pft_tbd_config_default(&c);
    TEST_ASSERT_TRUE(D(c.sprt_accept) == 0.0); /* off */
    TEST_ASSERT_TRUE(D(c.sprt_reject) == -5.0);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_config_check(&c, &field));
    c.sprt_accept = R(-0.5);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_tbd_config_check(&c, &field));
    TEST_ASSERT_EQUAL_STRING("sprt_accept", field);
    c.sprt_accept = R(10001.0);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_tbd_config_check(&c, &field));
    TEST_ASSERT_EQUAL_STRING("sprt_accept", field);
    c.sprt_accept = R(4.6);
    c.sprt_reject = R(0.5);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_tbd_config_check(&c, &field));
    TEST_ASSERT_EQUAL_STRING("sprt_reject", field);
    c.sprt_reject = R(-10001.0);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_tbd_config_check(&c, &field));
    TEST_ASSERT_EQUAL_STRING("sprt_reject", field);
    c.sprt_reject = R(-5.0);
    TEST_ASSERT_EQUAL_INT(0, c.sprt_start); /* default: from 0 */
    c.sprt_start = 3u;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_tbd_config_check(&c, &field));
    TEST_ASSERT_EQUAL_STRING("sprt_start", field);
}

/* cfg.sprt_start: the tentative track's sum at its hand-over frame is 0 (mode 0), the search
 * layer's ratios over the confirm_frames frames of its confirmation (1) or its log odds (2),
 * floored at 0, read from the search layer at that frame; on this bright target both are
 * positive (the sum does start higher), so that the bound is reached no later than from 0, and
 * the layers are those of the run from 0 (the start changes the sum only). Tolerance SUM_TOL:
 * the same values added in the same order; in q16 pft_div and pft_log are within 1 step of
 * 2^-16 (test_real), far inside 1e-3 for the ratios below 1e4 met here. */
static void test_start_from_the_search_layer(void)
{
    static run_t r0, r1, r2;
    const double accept = 12.0;
    g_start = 0u;
    run(accept, -5.0, FRAMES, 0.5, &r0);
    g_start = 1u;
    run(accept, -5.0, FRAMES, 0.5, &r1);
    g_start = 2u;
    run(accept, -5.0, FRAMES, 0.5, &r2);
    g_start = 0u;
    int h = -1;
    for (int k = 1; k <= FRAMES; ++k) {
        if (r0.start_seen[k - 1]) {
            h = k;
            break;
        }
    }
    TEST_ASSERT_TRUE_MESSAGE(h > 0, "the bright target is handed over");
    TEST_ASSERT_TRUE(r1.start_seen[h - 1] && r2.start_seen[h - 1]);
    TEST_ASSERT_DOUBLE_WITHIN(SUM_TOL, 0.0, r0.start[h - 1]);
    TEST_ASSERT_TRUE(r1.start1[h - 1] > 0.5 && r2.start2[h - 1] > 0.5);
    TEST_ASSERT_DOUBLE_WITHIN(SUM_TOL, r1.start1[h - 1], r1.start[h - 1]);
    TEST_ASSERT_DOUBLE_WITHIN(SUM_TOL, r2.start2[h - 1], r2.start[h - 1]);
    int a0 = -1, a1 = -1, a2 = -1;
    for (int k = FRAMES; k >= 1; --k) {
        a0 = r0.confirmed[k - 1] ? k : a0;
        a1 = r1.confirmed[k - 1] ? k : a1;
        a2 = r2.confirmed[k - 1] ? k : a2;
        TEST_ASSERT_EQUAL_INT(r0.layers[k - 1], r1.layers[k - 1]);
        TEST_ASSERT_EQUAL_INT(r0.layers[k - 1], r2.layers[k - 1]);
    }
    TEST_ASSERT_TRUE_MESSAGE(a0 > h, "accepted from 0 after the hand-over");
    TEST_ASSERT_TRUE(a1 > h && a1 <= a0 && a2 > h && a2 <= a0);
    TEST_ASSERT_TRUE_MESSAGE(a1 < a0 || a2 < a0, "a head start accepts earlier");
}

static void test_refused_frame_leaves_a_tentative_track_untouched(void)
{
    static run_t off;
    static pft_tbd_t snap;
    run(0.0, -5.0, FRAMES, 0.5, &off);
    const int h = handover(&off);
    TEST_ASSERT_TRUE(h > 0);
    pft_tbd_config_t c;
    cfg_of(&c, 1000.0, -1000.0);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_init(&g_t, &c, g_ws, sizeof g_ws));
    pft_rng_t sim;
    pft_rng_seed(&sim, 21u);
    const pft_sim_truth_t tr = {1, FRAMES, 12.0, 14.0, 0.3, 0.2, 22.0};
    pft_frame_t fr;
    for (int k = 1; k <= h + 1; ++k) {
        pft_sim_render_u16(&sim, &tr, 1, k, 2.0, IMG, IMG, g_raw, &fr);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_update(&g_t, &fr));
    }
    TEST_ASSERT_EQUAL_UINT(0u, pft_tbd_tracks(&g_t, NULL, 0u)); /* tentative */
    const size_t need = pft_tbd_workspace_size(&c);
    memcpy(&snap, &g_t, sizeof snap);
    memcpy(g_snap, g_ws, need);
    pft_frame_t bad = fr;
    bad.width = IMG - 1;
    TEST_ASSERT_NOT_EQUAL(PFT_OK, pft_tbd_update(&g_t, &bad));
    bad = fr;
    bad.data = NULL;
    TEST_ASSERT_NOT_EQUAL(PFT_OK, pft_tbd_update(&g_t, &bad));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tbd_update(&g_t, NULL));
    TEST_ASSERT_EQUAL_MEMORY(&snap, &g_t, sizeof snap);
    TEST_ASSERT_EQUAL_MEMORY(g_snap, g_ws, need);
}

/* Noise-free U16 frames (z = raw / 256 - 64, sigma 1): a point (the PSF of peak 8 centred on
 * pixel (15, 15)) or a blob wider than the PSF (a Gaussian of sigma 3 px, peak 8) there. At
 * the centre the blob's ring mean is 5.8 against a fitted amplitude of 14.5 (ratio 0.40); one
 * pixel off, 0.37 or more: above 0.25 wherever the search layer's estimate falls near it. */
static int shape_run(double ring, bool blob)
{
    pft_tbd_config_t c;
    cfg_of(&c, 0.0, -5.0);
    c.noise_sigma = R(1.0);
    c.shape_ring = R(ring);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_init(&g_t, &c, g_ws, sizeof g_ws));
    for (int r = 0; r < IMG; ++r) {
        for (int q = 0; q < IMG; ++q) {
            double z = 0.0;
            if (blob) {
                z = 8.0 * exp(-((q - 15.0) * (q - 15.0) + (r - 15.0) * (r - 15.0)) / (2.0 * 9.0));
            } else {
                z = 8.0 * exp(-((q - 15.0) * (q - 15.0) + (r - 15.0) * (r - 15.0)) / (2.0 * 0.49));
            }
            g_raw[r * IMG + q] = (uint16_t)lround((z + 64.0) * 256.0);
        }
    }
    int confirmed = 0;
    for (int k = 1; k <= 6; ++k) {
        pft_frame_t f;
        memset(&f, 0, sizeof f);
        f.data = g_raw;
        f.width = IMG;
        f.height = IMG;
        f.stride_bytes = IMG * 2u;
        f.format = PFT_PIX_U16;
        f.bit_depth = 16u;
        f.seq = (uint32_t)k;
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_update(&g_t, &f));
        pft_tbd_event_t ev[MAXT + 1u];
        size_t ne = pft_tbd_events(&g_t, ev, MAXT + 1u);
        for (size_t i = 0; i < ne; ++i) {
            confirmed += ev[i].kind == PFT_TBD_EV_CONFIRMED ? 1 : 0;
        }
    }
    return confirmed;
}

static void test_shape_test_passes_a_point_and_stops_a_blob(void)
{
    TEST_ASSERT_TRUE_MESSAGE(shape_run(0.0, false) >= 1, "the point is confirmed without the test");
    TEST_ASSERT_TRUE_MESSAGE(shape_run(0.25, false) >= 1, "and with it (ring 0 against 8)");
    TEST_ASSERT_TRUE_MESSAGE(shape_run(0.0, true) >= 1, "the blob is confirmed without the test");
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, shape_run(0.25, true), "the blob never with it");
    pft_tbd_config_t c;
    const char *field = NULL;
    pft_tbd_config_default(&c);
    TEST_ASSERT_TRUE(D(c.shape_ring) == 0.0);
    c.shape_ring = R(-0.1);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_tbd_config_check(&c, &field));
    TEST_ASSERT_EQUAL_STRING("shape_ring", field);
    c.shape_ring = R(101.0);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_tbd_config_check(&c, &field));
    TEST_ASSERT_EQUAL_STRING("shape_ring", field);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_fields_refused_by_name);
    RUN_TEST(test_accepts_at_the_bound_with_the_known_sum);
    RUN_TEST(test_a_short_track_is_never_reported);
    RUN_TEST(test_tentative_tracks_listed_where_reported_without_the_test);
    RUN_TEST(test_reject_bound_drops_the_tentative_track);
    RUN_TEST(test_refused_frame_leaves_a_tentative_track_untouched);
    RUN_TEST(test_shape_test_passes_a_point_and_stops_a_blob);
    RUN_TEST(test_start_from_the_search_layer);
    return UNITY_END();
}
