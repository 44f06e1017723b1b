/*
 * TBD manager, a second target leaving a track layer along a line (cfg.resid_fan with
 * resid_split), docs/algorithms.md 2.7.
 *
 * Known answers on a 32 x 32 scene rendered without noise (the configuration's noise sigma 2):
 * a still target A of intensity 60 at (16, 16), and a weak target B of intensity 11 that starts
 * on A at frame 1 and moves at (+0.75, 0) px per frame (at (19, 16) in frame 5). A manager with
 * one track (id 1) whose layer is set by hand on A before the first frame (the internal layout,
 * pft/internal/pft_tbd_types.h). The search layer hands over no earlier than frame 8
 * (confirm_frames 8), so in frames 1-6 a second track can come only from the option. B's matched
 * residual beside the layer is about 2.2 sigmas per frame (0.205 of its intensity at a pixel
 * centre), its sum along its line over 4 frames about 8, 4 sigmas of the sum's own noise:
 * - resid_split 3 without the fan: one track in each of frames 1-6 (no frame's peak reaches 3);
 * - resid_split 3 with resid_fan 4: one track in frames 1-4 (the fan anchored at frame 1 first
 *   completes at frame 5), two after frame 5: id 2 (one CONFIRMED event) within 1 px of B, id 1
 *   within 0.5 px of A, id 2's layer with a column velocity estimate above 0.4 (started with the
 *   line's 0.75, not vel_mean's 0); a fan that used only one frame of the four (2.2 / 2) would
 *   not reach 3. (Id 2's layer carries A's intensities, pft_tbd_filter_seed_at_, and ends on the
 *   existence test at frame 6: not asserted here);
 * - A alone with the fan: the tracks of the run without the option, bit for bit, over 6 frames;
 * - resid_fan 1, 7, or without resid_split refused by name, and the option off by default;
 * - over 10 frames, id 2 with the parent's start carries A's intensities and is gone from frame
 *   6 on; with resid_fan_in 1 (the line's own intensity estimate, about 9 for B's 11) it lives
 *   from frame 5 to 10 on B with its intensity within half of B's and its existence above 0.9;
 * - resid_fan_exist 0.9 (0.25) leaves 180 (50) of id 2's 200 particles live at its start (its
 *   existence 0.9), the parent's start all 200;
 * - resid_fan_vtol 0.5 starts id 2 as without it (B's line, |w| 0.75, is a candidate); 1.25
 *   refuses B's line and no faster line reaches 3: one track in frames 1-6;
 * - the three new fields refused by name out of range or without resid_fan, off by default.
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
#define NT 200u
#define MAXT 3u
#define KP 8u
#define FRAMES 6
#define FR_MAX 10

static pft_real_t R(double v) { return pft_test_from_double(v); }
static double D(pft_real_t v) { return pft_test_to_double(v); }

#define WS_BYTES                                                                               \
    (PFT_TBD_WORKSPACE_BYTES_PEAKS(NS, NT, MAXT, PFT_TBD_RBPF, IMG, IMG, KP) +                \
     PFT_TBD_FAN_BYTES(MAXT, 6u))
static uint8_t g_ws[WS_BYTES + 64];
static uint16_t g_raw[IMG * IMG];
static pft_tbd_t g_t;

static const double AX = 16.0, Y0 = 16.0, IA = 60.0, IB = 11.0, VB = 0.75;

static void cfg_of(pft_tbd_config_t *c)
{
    pft_test_tbd_u16_config(c, IMG, 2.0);
    c->n_search = NS;
    c->n_track = NT;
    c->max_targets = MAXT;
    c->birth_peaks = KP;
    c->theta1 = R(0.6);
    c->confirm_frames = 8u; /* no hand-over from the search layer in frames 1-6 */
    c->seed = 5u;
}

/* Slot 0 holds track 1 with every particle at (AX, Y0), within +-0.1 px in a fixed pattern,
 * alive, 3 updates old. */
static void put_track(void)
{
    pft_tbd_filter_t *tf = &g_t.tracks[0];
    const pft_real_t d = g_t.cfg.dx; /* internal positions: public + dx (dx = dy = 1) */
    for (uint32_t s = 0; s < tf->n; ++s) {
        const double jx = 0.1 * (double)((int)(s % 5u) - 2) / 2.0;
        const double jy = 0.1 * (double)((int)((s / 5u) % 5u) - 2) / 2.0;
        tf->cur.x[s] = pft_add(R(AX + jx), d);
        tf->cur.y[s] = pft_add(R(Y0 + jy), d);
        tf->cur.vx[s] = R(0.0);
        tf->cur.vy[s] = R(0.0);
        tf->cur.in[s] = R(IA);
        tf->cur.e[s] = 3u;
    }
    pft_test_tbd_put_record(&g_t, 0u, 1u, pft_add(R(AX), d), pft_add(R(Y0), d), R(IA));
}

typedef struct {
    size_t n[FR_MAX];                 /* tracks listed after frame k */
    pft_tbd_track_t tk[FR_MAX][MAXT]; /* by id */
    int confirmed2[FR_MAX];           /* CONFIRMED events of id 2 after frame k */
    double vx2[FR_MAX];               /* the column velocity estimate of id 2's layer (0: none) */
    double in2[FR_MAX];               /* the intensity estimate of id 2's layer (0: none) */
    uint32_t live2[FR_MAX];           /* the live particles of id 2's layer (0: none) */
} run_t;

static void run_n(const pft_tbd_config_t *c, bool two, run_t *o, int frames)
{
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_init(&g_t, c, g_ws, sizeof g_ws));
    put_track();
    memset(o, 0, sizeof *o);
    pft_rng_t sim;
    pft_rng_seed(&sim, 9u);
    const pft_sim_truth_t tr[2] = {{1, frames, AX, Y0, 0.0, 0.0, IA},
                                   {1, frames, AX, Y0, VB, 0.0, IB}};
    for (int k = 1; k <= frames; ++k) {
        pft_frame_t fr;
        pft_sim_render_u16(&sim, tr, two ? 2 : 1, k, 0.0, IMG, IMG, g_raw, &fr);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_update(&g_t, &fr));
        o->n[k - 1] = pft_tbd_tracks(&g_t, o->tk[k - 1], MAXT);
        for (uint32_t u = 0; u < MAXT; ++u) {
            if (g_t.records[u].id == 2u) {
                o->vx2[k - 1] = D(g_t.tracks[u].est.vx);
                o->in2[k - 1] = D(g_t.tracks[u].est.intensity);
                for (uint32_t s = 0; s < g_t.tracks[u].n; ++s) {
                    o->live2[k - 1] += g_t.tracks[u].cur.e[s] != 0u ? 1u : 0u;
                }
            }
        }
        pft_tbd_event_t ev[MAXT + 1u];
        const size_t ne = pft_tbd_events(&g_t, ev, MAXT + 1u);
        for (size_t i = 0; i < ne && i < MAXT + 1u; ++i) {
            o->confirmed2[k - 1] += ev[i].kind == PFT_TBD_EV_CONFIRMED && ev[i].id == 2u ? 1 : 0;
        }
    }
}

static void run(const pft_tbd_config_t *c, bool two, run_t *o) { run_n(c, two, o, FRAMES); }

static double dist_to(const pft_tbd_track_t *t, double x, double y)
{
    return hypot(D(t->x) - x, D(t->y) - y);
}

/* B's position in frame k (public frame) */
static double bx(int k) { return AX + VB * (double)(k - 1); }

static void test_default_is_off(void)
{
    pft_tbd_config_t c;
    pft_tbd_config_default(&c);
    TEST_ASSERT_EQUAL_UINT(0u, c.resid_fan);
    pft_tbd_config_recommended(&c);
    TEST_ASSERT_EQUAL_UINT(0u, c.resid_fan);
}

static void test_per_frame_peak_misses_b(void)
{
    static run_t off, peak;
    pft_tbd_config_t c;
    cfg_of(&c);
    run(&c, true, &off);
    c.resid_split = R(3.0);
    run(&c, true, &peak);
    for (int k = 0; k < FRAMES; ++k) {
        TEST_ASSERT_EQUAL_UINT_MESSAGE(1u, (unsigned)off.n[k], "without the option one track");
        TEST_ASSERT_EQUAL_UINT_MESSAGE(1u, (unsigned)peak.n[k], "the per-frame peak stays below 3");
    }
}

static void test_fan_finds_b_on_its_line(void)
{
    static run_t r;
    pft_tbd_config_t c;
    cfg_of(&c);
    c.resid_split = R(3.0);
    c.resid_fan = 4u;
    run(&c, true, &r);
    for (int k = 0; k < 4; ++k) {
        TEST_ASSERT_EQUAL_UINT_MESSAGE(1u, (unsigned)r.n[k], "no line completes before frame 5");
    }
    TEST_ASSERT_EQUAL_UINT(2u, (unsigned)r.n[4]);
    TEST_ASSERT_EQUAL_UINT32(1u, r.tk[4][0].id);
    TEST_ASSERT_EQUAL_UINT32(2u, r.tk[4][1].id);
    TEST_ASSERT_EQUAL_INT(1, r.confirmed2[4]);
    TEST_ASSERT_TRUE_MESSAGE(dist_to(&r.tk[4][1], bx(5), Y0) < 1.0, "the new track on B");
    TEST_ASSERT_TRUE_MESSAGE(dist_to(&r.tk[4][0], AX, Y0) < 0.5, "id 1 stays on A");
    TEST_ASSERT_TRUE_MESSAGE(r.vx2[4] > 0.4, "started with the line's velocity, not vel_mean's 0");
}

static void test_one_target_runs_as_off(void)
{
    static run_t off, on;
    pft_tbd_config_t c;
    cfg_of(&c);
    run(&c, false, &off);
    c.resid_split = R(3.0);
    c.resid_fan = 4u;
    run(&c, false, &on);
    for (int k = 0; k < FRAMES; ++k) {
        TEST_ASSERT_EQUAL_UINT(1u, (unsigned)on.n[k]);
        TEST_ASSERT_EQUAL_UINT((unsigned)off.n[k], (unsigned)on.n[k]);
        TEST_ASSERT_EQUAL_UINT32(off.tk[k][0].id, on.tk[k][0].id);
        TEST_ASSERT_TRUE(off.tk[k][0].x == on.tk[k][0].x && off.tk[k][0].y == on.tk[k][0].y);
        TEST_ASSERT_TRUE(off.tk[k][0].intensity == on.tk[k][0].intensity);
        TEST_ASSERT_TRUE(off.tk[k][0].p_exist == on.tk[k][0].p_exist);
    }
}

static void test_out_of_range_refused_by_name(void)
{
    pft_tbd_config_t c;
    const char *field = NULL;
    const uint8_t bad[3] = {1u, 7u, 255u};
    for (int i = 0; i < 3; ++i) {
        cfg_of(&c);
        c.resid_split = R(3.0);
        c.resid_fan = bad[i];
        TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_tbd_config_check(&c, &field));
        TEST_ASSERT_EQUAL_STRING("resid_fan", field);
        TEST_ASSERT_TRUE((0u) == pft_tbd_workspace_size(&c));
    }
    cfg_of(&c);
    c.resid_fan = 4u; /* without resid_split */
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_tbd_config_check(&c, &field));
    TEST_ASSERT_EQUAL_STRING("resid_fan", field);
    for (uint8_t k = 2u; k <= 6u; ++k) {
        c.resid_split = R(3.0);
        c.resid_fan = k;
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_config_check(&c, &field));
        cfg_of(&c);
        c.resid_split = R(3.0);
        const size_t off = pft_tbd_workspace_size(&c);
        c.resid_fan = k;
        TEST_ASSERT_TRUE((off + PFT_TBD_FAN_BYTES(MAXT, k)) == pft_tbd_workspace_size(&c));
    }
}

/* id 2 in the list of frame k (0-based), or NULL */
static const pft_tbd_track_t *id2(const run_t *r, int k)
{
    for (size_t i = 0; i < r->n[k]; ++i) {
        if (r->tk[k][i].id == 2u) {
            return &r->tk[k][i];
        }
    }
    return NULL;
}

static void test_new_start_from_the_line_lives(void)
{
    static run_t par, own;
    pft_tbd_config_t c;
    cfg_of(&c);
    c.resid_split = R(3.0);
    c.resid_fan = 4u;
    run_n(&c, true, &par, FR_MAX);
    c.resid_fan_in = 1u;
    run_n(&c, true, &own, FR_MAX);
    /* the parent's start: id 2 on B at frame 5 with A's intensity, gone from frame 6 on */
    TEST_ASSERT_NOT_NULL(id2(&par, 4));
    TEST_ASSERT_TRUE_MESSAGE(D(id2(&par, 4)->intensity) > 0.8 * IA, "the parent's intensities");
    for (int k = 5; k < FR_MAX; ++k) {
        TEST_ASSERT_NULL_MESSAGE(id2(&par, k), "with the parent's intensities id 2 ends");
    }
    /* the line's start: id 2 from frame 5 to the last, on B, with about B's intensity, and no
     * other new id (the layer is not started again) */
    for (int k = 4; k < FR_MAX; ++k) {
        const pft_tbd_track_t *b = id2(&own, k);
        TEST_ASSERT_NOT_NULL_MESSAGE(b, "id 2 lives with the line's intensities");
        TEST_ASSERT_TRUE_MESSAGE(dist_to(b, bx(k + 1), Y0) < 1.0, "id 2 on B");
        TEST_ASSERT_TRUE_MESSAGE(D(b->intensity) > 0.5 * IB && D(b->intensity) < 1.5 * IB,
                                 "id 2's intensity near B's");
        TEST_ASSERT_EQUAL_UINT(2u, (unsigned)own.n[k]);
        TEST_ASSERT_TRUE_MESSAGE(D(b->p_exist) > 0.9, "id 2's existence stays high");
    }
    TEST_ASSERT_EQUAL_INT(1, own.confirmed2[4]);
    TEST_ASSERT_TRUE(dist_to(&own.tk[FR_MAX - 1][0], AX, Y0) < 0.5);
}

static void test_existence_start(void)
{
    static run_t r;
    pft_tbd_config_t c;
    cfg_of(&c);
    c.resid_split = R(3.0);
    c.resid_fan = 4u;
    c.resid_fan_in = 1u;
    run_n(&c, true, &r, FRAMES);
    TEST_ASSERT_EQUAL_UINT32_MESSAGE(NT, r.live2[4], "the parent's particles, all live");
    c.resid_fan_exist = R(0.9);
    run_n(&c, true, &r, FRAMES);
    TEST_ASSERT_EQUAL_UINT32(180u, r.live2[4]); /* round(0.9 x 200) */
    TEST_ASSERT_NOT_NULL(id2(&r, 4));
    TEST_ASSERT_TRUE(id2(&r, 4)->p_exist == R(0.9));
    c.resid_fan_exist = R(0.25);
    run_n(&c, true, &r, FRAMES);
    TEST_ASSERT_EQUAL_UINT32(50u, r.live2[4]);
}

static void test_velocity_tolerance(void)
{
    static run_t off, lo, hi;
    pft_tbd_config_t c;
    cfg_of(&c);
    c.resid_split = R(3.0);
    c.resid_fan = 4u;
    run(&c, true, &off);
    c.resid_fan_vtol = R(0.5); /* B's line, |w| 0.75, stays a candidate */
    run(&c, true, &lo);
    c.resid_fan_vtol = R(1.25); /* B's line is no candidate, and no faster line reaches 3 */
    run(&c, true, &hi);
    TEST_ASSERT_NOT_NULL(id2(&lo, 4));
    TEST_ASSERT_TRUE(id2(&off, 4)->x == id2(&lo, 4)->x && id2(&off, 4)->y == id2(&lo, 4)->y);
    for (int k = 0; k < FRAMES; ++k) {
        TEST_ASSERT_EQUAL_UINT((unsigned)off.n[k], (unsigned)lo.n[k]);
        TEST_ASSERT_EQUAL_UINT_MESSAGE(1u, (unsigned)hi.n[k], "B's line refused");
    }
}

static void test_new_fields_refused_by_name(void)
{
    pft_tbd_config_t c;
    const char *field = NULL;
    pft_tbd_config_default(&c);
    TEST_ASSERT_EQUAL_UINT(0u, c.resid_fan_in);
    TEST_ASSERT_TRUE(c.resid_fan_exist == R(0.0) && c.resid_fan_vtol == R(0.0));
    cfg_of(&c);
    c.resid_split = R(3.0);
    c.resid_fan_in = 1u; /* without resid_fan */
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_tbd_config_check(&c, &field));
    TEST_ASSERT_EQUAL_STRING("resid_fan_in", field);
    c.resid_fan = 4u;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_config_check(&c, &field));
    c.resid_fan_in = 2u;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_tbd_config_check(&c, &field));
    TEST_ASSERT_EQUAL_STRING("resid_fan_in", field);
    c.resid_fan_in = 0u;
    c.resid_fan_exist = R(1.5);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_tbd_config_check(&c, &field));
    TEST_ASSERT_EQUAL_STRING("resid_fan_exist", field);
    c.resid_fan_exist = R(-0.1);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_tbd_config_check(&c, &field));
    TEST_ASSERT_EQUAL_STRING("resid_fan_exist", field);
    c.resid_fan_exist = R(1.0);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_config_check(&c, &field));
    c.resid_fan_vtol = R(1.6);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_tbd_config_check(&c, &field));
    TEST_ASSERT_EQUAL_STRING("resid_fan_vtol", field);
    c.resid_fan_vtol = R(1.5);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_config_check(&c, &field));
    c.resid_fan = 0u; /* the three need the fan */
    c.resid_fan_exist = R(0.0);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_tbd_config_check(&c, &field));
    TEST_ASSERT_EQUAL_STRING("resid_fan_vtol", field);
    c.resid_fan_vtol = R(0.0);
    c.resid_fan_exist = R(0.5);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_tbd_config_check(&c, &field));
    TEST_ASSERT_EQUAL_STRING("resid_fan_exist", field);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_default_is_off);
    RUN_TEST(test_per_frame_peak_misses_b);
    RUN_TEST(test_fan_finds_b_on_its_line);
    RUN_TEST(test_one_target_runs_as_off);
    RUN_TEST(test_out_of_range_refused_by_name);
    RUN_TEST(test_new_start_from_the_line_lives);
    RUN_TEST(test_existence_start);
    RUN_TEST(test_velocity_tolerance);
    RUN_TEST(test_new_fields_refused_by_name);
    return UNITY_END();
}
