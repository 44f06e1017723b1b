/*
 * TBD manager, a track layer that splits (cfg.split_px, split_share), docs/algorithms.md 2.7.
 *
 * Known answers on one 32 x 32 scene of two still targets of intensity 22 at (10, 16) and
 * (16, 16), rendered without noise (the configuration's noise sigma 2): a manager with one track (id 1) whose layer is set by hand before the
 * first frame (the internal layout, pft/internal/pft_tbd_types.h), with its live particles in
 * two groups, one on each target. Both targets weigh alike, so after the frame's update each
 * group keeps about its share of the particles:
 * - half and half, split_px 2, split_share 0.2: after frame 1 two tracks, id 1 and id 2 (one
 *   CONFIRMED event, id 2), one within 0.5 px of each target; without the option (0, the
 *   default) one track between the two (more than 2 px from both);
 * - a tenth on the second target: no split with split_share 0.2; with 0.05 the new track is on
 *   the second target (the smaller group) and id 1 on the first;
 * - one group (every live particle on the first target): no split, and the tracks of the run
 *   with the option are those of the run without it, bit for bit, over 6 frames;
 * - half and half with a second track already at (16, 16): no split (the smaller group's
 *   centroid within split_px of another track);
 * - fields out of range refused by name (split_px in (0, 0.5) or above 16; split_share 0 with
 *   split_px > 0, or above 0.5), and a refused configuration leaves an initialised manager and its
 *   workspace byte-identical.
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

static pft_real_t R(double v) { return pft_test_from_double(v); }
static double D(pft_real_t v) { return pft_test_to_double(v); }

#define WS_BYTES PFT_TBD_WORKSPACE_BYTES_PEAKS(NS, NT, MAXT, PFT_TBD_RBPF, IMG, IMG, KP)
static uint8_t g_ws[WS_BYTES + 64];
static uint8_t g_snap[WS_BYTES + 64];
static uint16_t g_raw[IMG * IMG];
static pft_tbd_t g_t;

static const double AX = 10.0, BX = 16.0, Y0 = 16.0;

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

/* Slot `slot` holds track `id` with its live particles at the first target (share 1 - share_b)
 * and at the second (share_b), each within +-0.1 px in a fixed pattern; no dead particle. */
static void put_track(uint32_t slot, uint32_t id, double share_b, double x_a)
{
    pft_tbd_filter_t *tf = &g_t.tracks[slot];
    const pft_real_t d = g_t.cfg.dx; /* internal positions: public + dx (dx = dy = 1) */
    const uint32_t nb = (uint32_t)(share_b * (double)tf->n + 0.5);
    double sx = 0.0;
    for (uint32_t s = 0; s < tf->n; ++s) {
        const double jx = 0.1 * (double)((int)(s % 5u) - 2) / 2.0;
        const double jy = 0.1 * (double)((int)((s / 5u) % 5u) - 2) / 2.0;
        const double x = (s < nb ? BX : x_a) + jx;
        sx += x;
        tf->cur.x[s] = pft_add(R(x), d);
        tf->cur.y[s] = pft_add(R(Y0 + jy), d);
        tf->cur.vx[s] = R(0.0);
        tf->cur.vy[s] = R(0.0);
        tf->cur.in[s] = R(22.0);
        tf->cur.e[s] = 3u;
    }
    pft_test_tbd_put_record(&g_t, slot, id, pft_add(R(sx / (double)tf->n), d), pft_add(R(Y0), d), R(22.0));
}

typedef struct {
    size_t n[FRAMES];                       /* tracks listed after frame k */
    pft_tbd_track_t tk[FRAMES][MAXT];       /* by id */
    int confirmed2;                         /* CONFIRMED events of id 2 after frame 1 */
} run_t;

/* share_b: the second group's share of track 1; other: a track (id 7) on the second target. */
static void run(const pft_tbd_config_t *c, double share_b, bool other, int frames, run_t *o)
{
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_init(&g_t, c, g_ws, sizeof g_ws));
    put_track(0u, 1u, share_b, AX);
    if (other) {
        put_track(1u, 7u, 0.0, BX);
    }
    memset(o, 0, sizeof *o);
    pft_rng_t sim;
    pft_rng_seed(&sim, 9u);
    const pft_sim_truth_t tr[2] = {{1, FRAMES, AX, Y0, 0.0, 0.0, 22.0},
                                   {1, FRAMES, BX, Y0, 0.0, 0.0, 22.0}};
    for (int k = 1; k <= frames; ++k) {
        pft_frame_t fr;
        /* noise-free frames (the sensor's sigma 2 is the configuration's): the two targets
         * weigh exactly alike at the same offsets */
        pft_sim_render_u16(&sim, tr, 2, k, 0.0, IMG, IMG, g_raw, &fr);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_update(&g_t, &fr));
        o->n[k - 1] = pft_tbd_tracks(&g_t, o->tk[k - 1], MAXT);
        if (k == 1) {
            pft_tbd_event_t ev[MAXT + 1u];
            const size_t ne = pft_tbd_events(&g_t, ev, MAXT + 1u);
            for (size_t i = 0; i < ne && i < MAXT + 1u; ++i) {
                o->confirmed2 += ev[i].kind == PFT_TBD_EV_CONFIRMED && ev[i].id == 2u ? 1 : 0;
            }
        }
    }
}

static double dist_to(const pft_tbd_track_t *t, double x, double y)
{
    return hypot(D(t->x) - x, D(t->y) - y);
}

static void test_default_is_off(void)
{
    pft_tbd_config_t c;
    pft_tbd_config_default(&c);
    TEST_ASSERT_TRUE(D(c.split_px) == 0.0);
    TEST_ASSERT_TRUE(D(c.split_share) == 0.0);
    pft_tbd_config_recommended(&c);
    TEST_ASSERT_TRUE(D(c.split_px) == 0.0);
}

static void test_two_groups_split_into_two_tracks(void)
{
    static run_t off, on;
    pft_tbd_config_t c;
    cfg_of(&c);
    run(&c, 0.5, false, 1, &off);
    TEST_ASSERT_EQUAL_UINT(1u, (unsigned)off.n[0]);
    TEST_ASSERT_EQUAL_UINT32(1u, off.tk[0][0].id);
    TEST_ASSERT_TRUE_MESSAGE(dist_to(&off.tk[0][0], AX, Y0) > 2.0 && dist_to(&off.tk[0][0], BX, Y0) > 2.0,
                             "without the option the track sits between the two groups");
    cfg_of(&c);
    c.split_px = R(2.0);
    c.split_share = R(0.2);
    run(&c, 0.5, false, 1, &on);
    TEST_ASSERT_EQUAL_UINT(2u, (unsigned)on.n[0]);
    TEST_ASSERT_EQUAL_UINT32(1u, on.tk[0][0].id);
    TEST_ASSERT_EQUAL_UINT32(2u, on.tk[0][1].id);
    TEST_ASSERT_EQUAL_INT(1, on.confirmed2);
    const double a0 = dist_to(&on.tk[0][0], AX, Y0), b0 = dist_to(&on.tk[0][0], BX, Y0);
    const double a1 = dist_to(&on.tk[0][1], AX, Y0), b1 = dist_to(&on.tk[0][1], BX, Y0);
    TEST_ASSERT_TRUE_MESSAGE((a0 < 0.5 && b1 < 0.5) || (b0 < 0.5 && a1 < 0.5),
                             "one track on each target");
    /* the new track takes the layer's existence probability */
    TEST_ASSERT_TRUE(on.tk[0][1].p_exist == on.tk[0][0].p_exist);
    /* no search layer handed it over: its record says so */
    TEST_ASSERT_EQUAL_UINT8(PFT_TBD_LAYER_NONE, on.tk[0][1].search_layer);
}

static void test_smaller_share_needs_split_share(void)
{
    static run_t r;
    pft_tbd_config_t c;
    cfg_of(&c);
    c.split_px = R(2.0);
    c.split_share = R(0.2);
    run(&c, 0.1, false, 1, &r);
    TEST_ASSERT_EQUAL_UINT(1u, (unsigned)r.n[0]);
    cfg_of(&c);
    c.split_px = R(2.0);
    c.split_share = R(0.05);
    run(&c, 0.1, false, 1, &r);
    TEST_ASSERT_EQUAL_UINT(2u, (unsigned)r.n[0]);
    TEST_ASSERT_EQUAL_UINT32(2u, r.tk[0][1].id);
    TEST_ASSERT_TRUE_MESSAGE(dist_to(&r.tk[0][1], BX, Y0) < 0.5, "the smaller group is the new track");
    TEST_ASSERT_TRUE_MESSAGE(dist_to(&r.tk[0][0], AX, Y0) < 0.5, "the layer keeps the larger group");
}

static void test_one_group_does_not_split_and_runs_as_off(void)
{
    static run_t off, on;
    pft_tbd_config_t c;
    cfg_of(&c);
    run(&c, 0.0, false, FRAMES, &off);
    cfg_of(&c);
    c.split_px = R(2.0);
    c.split_share = R(0.2);
    run(&c, 0.0, false, FRAMES, &on);
    for (int k = 0; k < FRAMES; ++k) {
        TEST_ASSERT_EQUAL_UINT((unsigned)off.n[k], (unsigned)on.n[k]);
        for (size_t i = 0; i < off.n[k] && i < MAXT; ++i) {
            TEST_ASSERT_EQUAL_UINT32(off.tk[k][i].id, on.tk[k][i].id);
            TEST_ASSERT_TRUE(off.tk[k][i].x == on.tk[k][i].x && off.tk[k][i].y == on.tk[k][i].y);
            TEST_ASSERT_TRUE(off.tk[k][i].intensity == on.tk[k][i].intensity);
            TEST_ASSERT_TRUE(off.tk[k][i].p_exist == on.tk[k][i].p_exist);
        }
    }
}

static void test_no_split_onto_another_track(void)
{
    static run_t r;
    pft_tbd_config_t c;
    cfg_of(&c);
    c.split_px = R(2.0);
    c.split_share = R(0.2);
    run(&c, 0.5, true, 1, &r);
    TEST_ASSERT_EQUAL_UINT(2u, (unsigned)r.n[0]); /* ids 1 and 7 only */
    TEST_ASSERT_EQUAL_UINT32(1u, r.tk[0][0].id);
    TEST_ASSERT_EQUAL_UINT32(7u, r.tk[0][1].id);
}

static void test_out_of_range_refused_by_name_and_state_kept(void)
{
    pft_tbd_config_t c;
    const char *field = NULL;
    const double bad_px[3] = {0.3, 16.5, -1.0};
    for (int i = 0; i < 3; ++i) {
        cfg_of(&c);
        c.split_px = R(bad_px[i]);
        c.split_share = R(0.2);
        TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_tbd_config_check(&c, &field));
        TEST_ASSERT_EQUAL_STRING("split_px", field);
    }
    const double bad_share[3] = {0.0, 0.6, -0.1};
    for (int i = 0; i < 3; ++i) {
        cfg_of(&c);
        c.split_px = R(2.0);
        c.split_share = R(bad_share[i]);
        TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_tbd_config_check(&c, &field));
        TEST_ASSERT_EQUAL_STRING("split_share", field);
    }
    cfg_of(&c);
    c.split_px = R(0.5);
    c.split_share = R(0.5);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_config_check(&c, &field));
    c.split_px = R(16.0);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_config_check(&c, &field));
    c.split_px = R(0.0);
    c.split_share = R(0.3); /* a share without the option: allowed, unused */
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_config_check(&c, &field));
    /* a refused configuration leaves a running manager and its workspace as they were */
    static run_t r;
    cfg_of(&c);
    c.split_px = R(2.0);
    c.split_share = R(0.2);
    run(&c, 0.5, false, 2, &r);
    static pft_tbd_t snap;
    memcpy(&snap, &g_t, sizeof snap);
    memcpy(g_snap, g_ws, sizeof g_ws);
    pft_tbd_config_t bad = c;
    bad.split_px = R(0.2);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_tbd_init(&g_t, &bad, g_ws, sizeof g_ws));
    bad = c;
    bad.split_share = R(0.0);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_tbd_init(&g_t, &bad, g_ws, sizeof g_ws));
    TEST_ASSERT_EQUAL_MEMORY(&snap, &g_t, sizeof snap);
    TEST_ASSERT_EQUAL_MEMORY(g_snap, g_ws, sizeof g_ws);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_default_is_off);
    RUN_TEST(test_two_groups_split_into_two_tracks);
    RUN_TEST(test_smaller_share_needs_split_share);
    RUN_TEST(test_one_group_does_not_split_and_runs_as_off);
    RUN_TEST(test_no_split_onto_another_track);
    RUN_TEST(test_out_of_range_refused_by_name_and_state_kept);
    return UNITY_END();
}
