/*
 * TBD manager, a second target beside a track layer from the residual (cfg.resid_split,
 * resid_split_frames, resid_split_age), docs/algorithms.md 2.7.
 *
 * Known answers on a 32 x 32 scene of two still point targets of intensity 60 at (10, 16) and
 * (13, 16), 3 px apart, rendered without noise (the configuration's noise sigma 2): a manager
 * with one track (id 1) whose layer is set by hand before the first frame (the internal layout,
 * pft/internal/pft_tbd_types.h) with every particle on the first target. The search layer hands
 * over no earlier than frame 4 (confirm_frames 4), so in frames 1-3 a second track can come only
 * from the option:
 * - resid_split 3, resid_split_frames 2: one track after frame 1, two after frame 2 (id 2, one
 *   CONFIRMED event, within 0.5 px of the second target; id 1 stays on the first); without the
 *   option (0, the default) one track in each of frames 1-3;
 * - resid_split_frames 3: the second track after frame 3, not after frame 2;
 * - the first target alone: no second track, and the tracks of the run with the option are
 *   those of the run without it, bit for bit, over 3 frames;
 * - a second track (id 7) already on the second target: no new track (the peak within 3 px of
 *   another track);
 * - resid_split_age 2 (the hand-set layer has 3 updates before frame 1): no new track;
 *   resid_split_age 10: the new track as above;
 * - fields out of range refused by name (resid_split in (0, 1), above 50 or negative;
 *   resid_split_frames above 8), and a refused configuration leaves an initialised manager and
 *   its workspace byte-identical.
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
#define FRAMES 3

static pft_real_t R(double v) { return pft_test_from_double(v); }
static double D(pft_real_t v) { return pft_test_to_double(v); }

#define WS_BYTES PFT_TBD_WORKSPACE_BYTES_PEAKS(NS, NT, MAXT, PFT_TBD_RBPF, IMG, IMG, KP)
static uint8_t g_ws[WS_BYTES + 64];
static uint8_t g_snap[WS_BYTES + 64];
static uint16_t g_raw[IMG * IMG];
static pft_tbd_t g_t;

static const double AX = 10.0, BX = 13.0, Y0 = 16.0, IN = 60.0;

static void cfg_of(pft_tbd_config_t *c)
{
    pft_test_tbd_u16_config(c, IMG, 2.0);
    c->n_search = NS;
    c->n_track = NT;
    c->max_targets = MAXT;
    c->birth_peaks = KP;
    c->theta1 = R(0.6);
    c->confirm_frames = 4u; /* no hand-over from the search layer in the first 3 frames */
    c->seed = 5u;
}

/* Slot `slot` holds track `id` with every particle at (x, Y0), within +-0.1 px in a fixed
 * pattern, alive, 3 updates old. */
static void put_track(uint32_t slot, uint32_t id, double x)
{
    pft_tbd_filter_t *tf = &g_t.tracks[slot];
    const pft_real_t d = g_t.cfg.dx; /* internal positions: public + dx (dx = dy = 1) */
    for (uint32_t s = 0; s < tf->n; ++s) {
        const double jx = 0.1 * (double)((int)(s % 5u) - 2) / 2.0;
        const double jy = 0.1 * (double)((int)((s / 5u) % 5u) - 2) / 2.0;
        tf->cur.x[s] = pft_add(R(x + jx), d);
        tf->cur.y[s] = pft_add(R(Y0 + jy), d);
        tf->cur.vx[s] = R(0.0);
        tf->cur.vy[s] = R(0.0);
        tf->cur.in[s] = R(IN);
        tf->cur.e[s] = 3u;
    }
    pft_test_tbd_put_record(&g_t, slot, id, pft_add(R(x), d), pft_add(R(Y0), d), R(IN));
}

typedef struct {
    size_t n[FRAMES];                 /* tracks listed after frame k */
    pft_tbd_track_t tk[FRAMES][MAXT]; /* by id */
    int confirmed2[FRAMES];           /* CONFIRMED events of id 2 after frame k */
} run_t;

/* two: the second target is in the scene; other: a track (id 7) on it. */
static void run(const pft_tbd_config_t *c, bool two, bool other, run_t *o)
{
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_init(&g_t, c, g_ws, sizeof g_ws));
    put_track(0u, 1u, AX);
    if (other) {
        put_track(1u, 7u, BX);
    }
    memset(o, 0, sizeof *o);
    pft_rng_t sim;
    pft_rng_seed(&sim, 9u);
    const pft_sim_truth_t tr[2] = {{1, FRAMES, AX, Y0, 0.0, 0.0, IN},
                                   {1, FRAMES, BX, Y0, 0.0, 0.0, IN}};
    for (int k = 1; k <= FRAMES; ++k) {
        pft_frame_t fr;
        pft_sim_render_u16(&sim, tr, two ? 2 : 1, k, 0.0, IMG, IMG, g_raw, &fr);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_update(&g_t, &fr));
        o->n[k - 1] = pft_tbd_tracks(&g_t, o->tk[k - 1], MAXT);
        pft_tbd_event_t ev[MAXT + 1u];
        const size_t ne = pft_tbd_events(&g_t, ev, MAXT + 1u);
        for (size_t i = 0; i < ne && i < MAXT + 1u; ++i) {
            o->confirmed2[k - 1] += ev[i].kind == PFT_TBD_EV_CONFIRMED && ev[i].id == 2u ? 1 : 0;
        }
    }
}

static double dist_to(const pft_tbd_track_t *t, double x, double y)
{
    return hypot(D(t->x) - x, D(t->y) - y);
}

static void on_cfg(pft_tbd_config_t *c, uint8_t frames)
{
    cfg_of(c);
    c->resid_split = R(3.0);
    c->resid_split_frames = frames;
}

static void test_default_is_off(void)
{
    pft_tbd_config_t c;
    pft_tbd_config_default(&c);
    TEST_ASSERT_TRUE(D(c.resid_split) == 0.0);
    TEST_ASSERT_EQUAL_UINT(0u, c.resid_split_frames);
    TEST_ASSERT_EQUAL_UINT(0u, c.resid_split_age);
    pft_tbd_config_recommended(&c);
    TEST_ASSERT_TRUE(D(c.resid_split) == 0.0);
}

static void test_second_target_gets_a_track(void)
{
    static run_t off, on;
    pft_tbd_config_t c;
    cfg_of(&c);
    run(&c, true, false, &off);
    for (int k = 0; k < FRAMES; ++k) {
        TEST_ASSERT_EQUAL_UINT_MESSAGE(1u, (unsigned)off.n[k], "without the option one track");
    }
    on_cfg(&c, 2u);
    run(&c, true, false, &on);
    TEST_ASSERT_EQUAL_UINT(1u, (unsigned)on.n[0]);
    TEST_ASSERT_EQUAL_UINT(2u, (unsigned)on.n[1]);
    TEST_ASSERT_EQUAL_UINT32(1u, on.tk[1][0].id);
    TEST_ASSERT_EQUAL_UINT32(2u, on.tk[1][1].id);
    TEST_ASSERT_EQUAL_INT(0, on.confirmed2[0]);
    TEST_ASSERT_EQUAL_INT(1, on.confirmed2[1]);
    TEST_ASSERT_TRUE_MESSAGE(dist_to(&on.tk[1][1], BX, Y0) < 0.5, "the new track on the second target");
    TEST_ASSERT_TRUE_MESSAGE(dist_to(&on.tk[1][0], AX, Y0) < 0.5, "id 1 stays on the first");
    TEST_ASSERT_TRUE(on.tk[1][1].p_exist == on.tk[1][0].p_exist);
    TEST_ASSERT_EQUAL_UINT(2u, (unsigned)on.n[2]);
    TEST_ASSERT_TRUE(dist_to(&on.tk[2][1], BX, Y0) < 0.5);
}

static void test_frames_in_a_row(void)
{
    static run_t r;
    pft_tbd_config_t c;
    on_cfg(&c, 3u);
    run(&c, true, false, &r);
    TEST_ASSERT_EQUAL_UINT(1u, (unsigned)r.n[1]);
    TEST_ASSERT_EQUAL_UINT(2u, (unsigned)r.n[2]);
    TEST_ASSERT_EQUAL_INT(1, r.confirmed2[2]);
    TEST_ASSERT_TRUE(dist_to(&r.tk[2][1], BX, Y0) < 0.5);
}

static void test_one_target_runs_as_off(void)
{
    static run_t off, on;
    pft_tbd_config_t c;
    cfg_of(&c);
    run(&c, false, false, &off);
    on_cfg(&c, 1u);
    run(&c, false, false, &on);
    for (int k = 0; k < FRAMES; ++k) {
        TEST_ASSERT_EQUAL_UINT(1u, (unsigned)on.n[k]);
        TEST_ASSERT_EQUAL_UINT((unsigned)off.n[k], (unsigned)on.n[k]);
        for (size_t i = 0; i < off.n[k] && i < MAXT; ++i) {
            TEST_ASSERT_EQUAL_UINT32(off.tk[k][i].id, on.tk[k][i].id);
            TEST_ASSERT_TRUE(off.tk[k][i].x == on.tk[k][i].x && off.tk[k][i].y == on.tk[k][i].y);
            TEST_ASSERT_TRUE(off.tk[k][i].intensity == on.tk[k][i].intensity);
            TEST_ASSERT_TRUE(off.tk[k][i].p_exist == on.tk[k][i].p_exist);
        }
    }
}

static void test_no_track_beside_another_track(void)
{
    static run_t r;
    pft_tbd_config_t c;
    on_cfg(&c, 1u);
    run(&c, true, true, &r);
    for (int k = 0; k < FRAMES; ++k) {
        TEST_ASSERT_EQUAL_UINT(2u, (unsigned)r.n[k]); /* ids 1 and 7 only */
        TEST_ASSERT_EQUAL_UINT32(1u, r.tk[k][0].id);
        TEST_ASSERT_EQUAL_UINT32(7u, r.tk[k][1].id);
    }
}

static void test_age_limit(void)
{
    static run_t r;
    pft_tbd_config_t c;
    on_cfg(&c, 2u);
    c.resid_split_age = 2u;
    run(&c, true, false, &r);
    TEST_ASSERT_EQUAL_UINT_MESSAGE(1u, (unsigned)r.n[2], "a layer older than resid_split_age is not tested");
    on_cfg(&c, 2u);
    c.resid_split_age = 10u;
    run(&c, true, false, &r);
    TEST_ASSERT_EQUAL_UINT(2u, (unsigned)r.n[1]);
    TEST_ASSERT_TRUE(dist_to(&r.tk[1][1], BX, Y0) < 0.5);
}

static void test_out_of_range_refused_by_name_and_state_kept(void)
{
    pft_tbd_config_t c;
    const char *field = NULL;
    const double bad[4] = {0.5, 50.5, -1.0, 0.99};
    for (int i = 0; i < 4; ++i) {
        cfg_of(&c);
        c.resid_split = R(bad[i]);
        TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_tbd_config_check(&c, &field));
        TEST_ASSERT_EQUAL_STRING("resid_split", field);
    }
    cfg_of(&c);
    c.resid_split = R(3.0);
    c.resid_split_frames = 9u;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_tbd_config_check(&c, &field));
    TEST_ASSERT_EQUAL_STRING("resid_split_frames", field);
    c.resid_split_frames = 8u;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_config_check(&c, &field));
    c.resid_split = R(1.0);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_config_check(&c, &field));
    c.resid_split = R(50.0);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_config_check(&c, &field));
    /* a refused configuration leaves a running manager and its workspace as they were */
    static run_t r;
    on_cfg(&c, 2u);
    run(&c, true, false, &r);
    static pft_tbd_t snap;
    memcpy(&snap, &g_t, sizeof snap);
    memcpy(g_snap, g_ws, sizeof g_ws);
    pft_tbd_config_t b = c;
    b.resid_split = R(0.5);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_tbd_init(&g_t, &b, g_ws, sizeof g_ws));
    b = c;
    b.resid_split_frames = 200u;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_tbd_init(&g_t, &b, g_ws, sizeof g_ws));
    TEST_ASSERT_EQUAL_MEMORY(&snap, &g_t, sizeof snap);
    TEST_ASSERT_EQUAL_MEMORY(g_snap, g_ws, sizeof g_ws);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_default_is_off);
    RUN_TEST(test_second_target_gets_a_track);
    RUN_TEST(test_frames_in_a_row);
    RUN_TEST(test_one_target_runs_as_off);
    RUN_TEST(test_no_track_beside_another_track);
    RUN_TEST(test_age_limit);
    RUN_TEST(test_out_of_range_refused_by_name_and_state_kept);
    return UNITY_END();
}
