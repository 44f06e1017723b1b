/*
 * TBD manager, the options of a track layer's start and end, on one scene and one run helper:
 * the existence test of young tracks (cfg.end_grace_frames, theta_end_grace) and the end test
 * over several frames in a row (cfg.end_persist), docs/algorithms.md 2.6; the intensity a new
 * track layer starts from (cfg.handover_in_scale), docs/algorithms.md 2.7.
 *
 * Known answers, from a run of the same manager with the option off: an option changes only
 * whether a track ends at an end test, so on the same frames the two runs are the same, frame
 * by frame and bit for bit, up to the first frame at which the run with the option keeps a
 * track that the run without it ends. A target is present in frames 1..LAST and then gone.
 * - Grace: with theta_end_grace equal to the run without the option's theta_end and a
 *   theta_end of 1 (every track whose P is below 1 ends), the track lives exactly as without
 *   the option for its first end_grace_frames end tests (after its hand-over at frame h, the
 *   frames h + 1 .. h + K), and ends at the first frame after them at which its P, read from
 *   the run without the option, is below 1 (or at the frame the run without the option ends
 *   it, if that comes first).
 * - Persist 2 (the target fading to intensity 6 after LAST instead of leaving, so that the
 *   layer keeps live particles below theta_end): the run without the option ends the track at
 *   frame e, after LAST; with the option the track is still listed at e with end_below 1 and P below
 *   theta_end, the runs are the same before e, and from e on the track ends exactly at the
 *   second frame in a row with P below theta_end (end_below counts them; never 2 on a listed
 *   track).
 * - The default (0) leaves end_below 0; fields out of range are refused by name, and the
 *   refused configuration leaves an initialised manager and its workspace byte-identical.
 *
 * Hand-over scale. Known answers, from a run of the same manager with the option off (0): the
 * option acts only at a hand-over, so the two runs are the same, frame by frame and bit for bit,
 * before the first hand-over at frame h; at h the new track has the same position and existence
 * probability and k times the intensity (one multiplication: within one rounding of the number
 * type); from h + 1 on its layer carries the scaled particles, so its intensity stays below the
 * run without the option's (with only the estimate scaled, the layers, and so these values,
 * would be the same). The value 1 is off too (the same run as 0 on every frame); values outside
 * [0, 1] are refused by name, and the refused configuration leaves an initialised manager and
 * its workspace byte-identical.
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
#define LAST 12

static pft_real_t R(double v) { return pft_test_from_double(v); }
static double D(pft_real_t v) { return pft_test_to_double(v); }

#define WS_BYTES PFT_TBD_WORKSPACE_BYTES_PEAKS(NS, NT, MAXT, PFT_TBD_RBPF, IMG, IMG, KP)
static uint8_t g_ws[WS_BYTES + 64];
static uint8_t g_snap[WS_BYTES + 64];
static uint16_t g_raw[IMG * IMG];
static pft_tbd_t g_t;
static double g_dim = 0.0; /* the target's intensity after LAST (0: gone) */

/* The recommended preset on 32 x 32 U16 frames of sigma 2 (z = raw / 256 - 64). */
static void cfg_of(pft_tbd_config_t *c)
{
    pft_test_tbd_u16_config(c, IMG, 2.0);
    c->n_search = NS;
    c->n_track = NT;
    c->max_targets = MAXT;
    c->birth_peaks = KP;
    c->theta1 = R(0.6);
    c->seed = 3u;
}

/* What one run saw of track id 1 per frame (index k - 1). */
typedef struct {
    int has1[FRAMES];      /* listed by pft_tbd_tracks */
    double x[FRAMES], y[FRAMES], p[FRAMES], in[FRAMES];
    uint32_t age[FRAMES];
    uint8_t below[FRAMES]; /* its end_below */
    int confirmed1[FRAMES]; /* CONFIRMED event of id 1 */
    int ended1[FRAMES];    /* ENDED event of id 1 */
    double lp[FRAMES];     /* the P of id 1's layer read after this frame, also when it ended
                              (internal layout, pft/internal/pft_tbd_types.h); -1: no layer
                              (or another track's, if a hand-over took the slot at once) */
    uint32_t live[FRAMES]; /* and its live particles */
} run_t;

/* One target present in frames 1..LAST at (12, 14) + k (0.3, 0.2), intensity 22, sigma 2. */
static void run(const pft_tbd_config_t *c, run_t *o)
{
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_init(&g_t, c, g_ws, sizeof g_ws));
    memset(o, 0, sizeof(*o));
    pft_rng_t sim;
    pft_rng_seed(&sim, 21u);
    /* after LAST the target goes on at intensity g_dim (0: gone) */
    const pft_sim_truth_t tr[2] = {{1, LAST, 12.0, 14.0, 0.3, 0.2, 22.0},
                                   {LAST + 1, FRAMES, 12.0 + 0.3 * LAST, 14.0 + 0.2 * LAST, 0.3, 0.2, g_dim}};
    int slot = -1; /* id 1's slot */
    for (int k = 1; k <= FRAMES; ++k) {
        pft_frame_t fr;
        pft_sim_render_u16(&sim, tr, g_dim > 0.0 ? 2 : 1, k, 2.0, IMG, IMG, g_raw, &fr);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_update(&g_t, &fr));
        o->lp[k - 1] = -1.0;
        if (slot >= 0 && (g_t.records[slot].id == 0u || g_t.records[slot].id == 1u)) {
            const pft_tbd_filter_t *tf = &g_t.tracks[slot];
            uint32_t live = 0u;
            for (uint32_t s = 0; s < tf->n; ++s) {
                live += tf->cur.e[s] != 0u ? 1u : 0u;
            }
            o->lp[k - 1] = D(tf->est.p_exist);
            o->live[k - 1] = live;
        }
        slot = -1;
        for (uint32_t u = 0; u < MAXT; ++u) {
            slot = g_t.records[u].id == 1u ? (int)u : slot;
        }
        pft_tbd_track_t tk[MAXT];
        const size_t n = pft_tbd_tracks(&g_t, tk, MAXT);
        for (size_t i = 0; i < n && i < MAXT; ++i) {
            if (tk[i].id == 1u) {
                o->has1[k - 1] = 1;
                o->x[k - 1] = D(tk[i].x);
                o->y[k - 1] = D(tk[i].y);
                o->p[k - 1] = D(tk[i].p_exist);
                o->in[k - 1] = D(tk[i].intensity);
                o->age[k - 1] = tk[i].age;
                o->below[k - 1] = tk[i].end_below;
            }
        }
        pft_tbd_event_t ev[MAXT + 1u];
        const size_t ne = pft_tbd_events(&g_t, ev, MAXT + 1u);
        for (size_t i = 0; i < ne; ++i) {
            o->confirmed1[k - 1] += ev[i].kind == PFT_TBD_EV_CONFIRMED && ev[i].id == 1u ? 1 : 0;
            o->ended1[k - 1] += ev[i].kind == PFT_TBD_EV_ENDED && ev[i].id == 1u ? 1 : 0;
        }
    }
}

static int first_frame_of(const int *v)
{
    for (int k = 1; k <= FRAMES; ++k) {
        if (v[k - 1] != 0) {
            return k;
        }
    }
    return -1;
}

/* Frames 1..upto of two runs the same (the values as reported, so exactly equal). */
static void assert_same_until(const run_t *a, const run_t *b, int upto)
{
    for (int k = 1; k <= upto && k <= FRAMES; ++k) {
        TEST_ASSERT_EQUAL_INT(a->has1[k - 1], b->has1[k - 1]);
        TEST_ASSERT_EQUAL_INT(a->confirmed1[k - 1], b->confirmed1[k - 1]);
        TEST_ASSERT_EQUAL_INT(a->ended1[k - 1], b->ended1[k - 1]);
        TEST_ASSERT_TRUE(a->x[k - 1] == b->x[k - 1] && a->y[k - 1] == b->y[k - 1]);
        TEST_ASSERT_TRUE(a->p[k - 1] == b->p[k - 1] && a->in[k - 1] == b->in[k - 1]);
    }
}

static void test_default_is_off(void)
{
    pft_tbd_config_t c;
    pft_tbd_config_default(&c);
    TEST_ASSERT_EQUAL_UINT8(0u, c.end_grace_frames);
    TEST_ASSERT_TRUE(D(c.theta_end_grace) == 0.0);
    TEST_ASSERT_EQUAL_UINT8(0u, c.end_persist);
    static run_t off;
    cfg_of(&c);
    run(&c, &off);
    for (int k = 1; k <= FRAMES; ++k) {
        TEST_ASSERT_EQUAL_UINT8(0u, off.below[k - 1]);
    }
}

static void test_grace_keeps_a_young_track_for_k_end_tests(void)
{
    static run_t off, on;
    pft_tbd_config_t c;
    cfg_of(&c);
    run(&c, &off); /* theta_end 0.5 */
    const int h = first_frame_of(off.confirmed1);
    const int e = first_frame_of(off.ended1);
    TEST_ASSERT_TRUE_MESSAGE(h > 0 && h < LAST - 4, "the bright target is handed over early");
    TEST_ASSERT_TRUE_MESSAGE(e > LAST, "and ended after it has gone");
    for (uint8_t K = 1u; K <= 3u; ++K) {
        cfg_of(&c);
        c.end_grace_frames = K;
        c.theta_end_grace = c.theta_end;
        c.theta_end = R(1.0);
        run(&c, &on);
        /* the known end: the first frame after the grace (h + K + 1 on) at which the run
         * without the option has P below 1, or that run's own end if it comes first */
        int want = -1;
        for (int k = h + (int)K + 1; k < e && want < 0; ++k) {
            TEST_ASSERT_EQUAL_INT(1, off.has1[k - 1]);
            if (off.p[k - 1] < 1.0) {
                want = k;
            }
        }
        if (want < 0) {
            want = e;
        }
        TEST_ASSERT_TRUE_MESSAGE(want > h + (int)K, "the grace covers K end tests");
        assert_same_until(&off, &on, want - 1);
        TEST_ASSERT_EQUAL_INT(1, on.ended1[want - 1]);
        TEST_ASSERT_EQUAL_INT(0, on.has1[want - 1]);
    }
    /* without the grace, theta_end 1 ends the track at its first end test with P below 1 */
    cfg_of(&c);
    c.theta_end = R(1.0);
    run(&c, &on);
    int want = -1;
    for (int k = h + 1; k < e && want < 0; ++k) {
        if (off.p[k - 1] < 1.0) {
            want = k;
        }
    }
    if (want < 0) {
        want = e;
    }
    assert_same_until(&off, &on, want - 1);
    TEST_ASSERT_EQUAL_INT(1, on.ended1[want - 1]);
}

static void test_persist_ends_on_the_second_frame_in_a_row(void)
{
    static run_t off, on;
    pft_tbd_config_t c;
    /* the target fades to intensity 6 after LAST (0.27 of its 22): the track's P falls below
     * theta_end while its layer keeps live particles, so end tests in a row are seen */
    g_dim = 6.0;
    cfg_of(&c);
    run(&c, &off);
    const int e = first_frame_of(off.ended1);
    TEST_ASSERT_TRUE_MESSAGE(e > LAST && e < FRAMES - 2, "the track ends after its target has faded");
    cfg_of(&c);
    c.end_persist = 2u;
    run(&c, &on);
    const double th = D(c.theta_end);
    assert_same_until(&off, &on, e - 1);
    TEST_ASSERT_EQUAL_INT_MESSAGE(1, on.has1[e - 1], "kept at the first frame below theta_end");
    TEST_ASSERT_EQUAL_UINT8(1u, on.below[e - 1]);
    TEST_ASSERT_TRUE(on.p[e - 1] < th);
    const int end = first_frame_of(on.ended1);
    TEST_ASSERT_TRUE(end > e);
    for (int k = e + 1; k < end; ++k) {
        /* listed: the count follows P, and never reaches 2 on a listed track */
        TEST_ASSERT_EQUAL_INT(1, on.has1[k - 1]);
        const uint8_t want = on.p[k - 1] < th ? (uint8_t)(on.below[k - 2] + 1u) : 0u;
        TEST_ASSERT_EQUAL_UINT8(want, on.below[k - 1]);
        TEST_ASSERT_TRUE(on.below[k - 1] < 2u);
    }
    /* it ends the frame after one below theta_end (the second in a row), or with no live
     * particle left (its layer read after the end, unless a hand-over took the slot at once) */
    TEST_ASSERT_EQUAL_INT(0, on.has1[end - 1]);
    TEST_ASSERT_TRUE(on.below[end - 2] == 1u || (on.lp[end - 1] >= 0.0 && on.live[end - 1] == 0u));
    /* persist 3 on the same frames: kept at e and e + 1 while its layer has live particles */
    cfg_of(&c);
    c.end_persist = 3u;
    static run_t on3;
    run(&c, &on3);
    assert_same_until(&off, &on3, e - 1);
    const int end3 = first_frame_of(on3.ended1);
    TEST_ASSERT_TRUE(end3 > e);
    for (int k = e; k < end3; ++k) {
        TEST_ASSERT_EQUAL_INT(1, on3.has1[k - 1]);
        const uint8_t prev = k > e ? on3.below[k - 2] : 0u;
        TEST_ASSERT_EQUAL_UINT8(on3.p[k - 1] < th ? (uint8_t)(prev + 1u) : 0u, on3.below[k - 1]);
        TEST_ASSERT_TRUE(on3.below[k - 1] < 3u);
    }
    /* at its end: the third frame in a row below theta_end, or no live particle left (read
     * from its layer unless a hand-over took the slot at once) */
    TEST_ASSERT_TRUE(on3.below[end3 - 2] == 2u || on3.lp[end3 - 1] < 0.0 || on3.live[end3 - 1] == 0u);
    g_dim = 0.0;
}

static void test_fields_refused_by_name_and_state_kept(void)
{
    pft_tbd_config_t c;
    const char *field = NULL;
    cfg_of(&c);
    c.end_persist = (uint8_t)PFT_TBD_MAX_END_PERSIST;
    c.end_grace_frames = 255u;
    c.theta_end_grace = R(1.0);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_config_check(&c, &field));
    c.end_persist = (uint8_t)(PFT_TBD_MAX_END_PERSIST + 1u);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_tbd_config_check(&c, &field));
    TEST_ASSERT_EQUAL_STRING("end_persist", field);
    cfg_of(&c);
    c.theta_end_grace = R(-0.1);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_tbd_config_check(&c, &field));
    TEST_ASSERT_EQUAL_STRING("theta_end_grace", field);
    c.theta_end_grace = R(1.5);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_tbd_config_check(&c, &field));
    TEST_ASSERT_EQUAL_STRING("theta_end_grace", field);
    /* a refused configuration leaves a running manager and its workspace as they were */
    static run_t r;
    cfg_of(&c);
    c.end_persist = 2u;
    run(&c, &r);
    static pft_tbd_t snap;
    memcpy(&snap, &g_t, sizeof snap);
    memcpy(g_snap, g_ws, sizeof g_ws);
    pft_tbd_config_t bad = c;
    bad.end_persist = (uint8_t)(PFT_TBD_MAX_END_PERSIST + 1u);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_tbd_init(&g_t, &bad, g_ws, sizeof g_ws));
    bad = c;
    bad.theta_end_grace = R(2.0);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_tbd_init(&g_t, &bad, g_ws, sizeof g_ws));
    TEST_ASSERT_EQUAL_MEMORY(&snap, &g_t, sizeof snap);
    TEST_ASSERT_EQUAL_MEMORY(g_snap, g_ws, sizeof g_ws);
}

static void test_default_and_one_are_off(void)
{
    pft_tbd_config_t c;
    pft_tbd_config_default(&c);
    TEST_ASSERT_TRUE(D(c.handover_in_scale) == 0.0);
    static run_t off, one;
    cfg_of(&c);
    run(&c, &off);
    TEST_ASSERT_TRUE_MESSAGE(first_frame_of(off.confirmed1) > 0, "the target is handed over");
    cfg_of(&c);
    c.handover_in_scale = R(1.0);
    run(&c, &one);
    assert_same_until(&off, &one, FRAMES);
}

static void test_new_layer_starts_from_k_times_the_intensity(void)
{
    static run_t off, on;
    pft_tbd_config_t c;
    cfg_of(&c);
    run(&c, &off);
    const int h = first_frame_of(off.confirmed1);
    TEST_ASSERT_TRUE_MESSAGE(h > 0 && h < LAST - 2, "the bright target is handed over early");
    TEST_ASSERT_EQUAL_INT(1, off.has1[h]);
    const double ks[2] = {0.8, 0.5};
    for (int i = 0; i < 2; ++i) {
        cfg_of(&c);
        c.handover_in_scale = R(ks[i]);
        const double k = D(c.handover_in_scale); /* the factor as the number type holds it */
        run(&c, &on);
        assert_same_until(&off, &on, h - 1);
        TEST_ASSERT_EQUAL_INT(h, first_frame_of(on.confirmed1));
        TEST_ASSERT_TRUE(on.x[h - 1] == off.x[h - 1] && on.y[h - 1] == off.y[h - 1]);
        TEST_ASSERT_TRUE(on.p[h - 1] == off.p[h - 1]);
        /* tolerance: one multiplication, rounded once: 2^-16 in q16 (its resolution), a
         * relative 2^-24 in float (1e-6 of the value covers it) */
        TEST_ASSERT_DOUBLE_WITHIN(1.0 / 65536.0 + 1e-6 * off.in[h - 1], k * off.in[h - 1],
                                  on.in[h - 1]);
        /* the next frame: the layer itself started lower */
        TEST_ASSERT_EQUAL_INT(1, on.has1[h]);
        TEST_ASSERT_TRUE_MESSAGE(on.in[h] < off.in[h], "the layer's particles were scaled");
    }
}

static void test_out_of_range_refused_by_name_and_state_kept(void)
{
    pft_tbd_config_t c;
    const char *field = NULL;
    cfg_of(&c);
    c.handover_in_scale = R(1.0);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_config_check(&c, &field));
    c.handover_in_scale = R(-0.1);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_tbd_config_check(&c, &field));
    TEST_ASSERT_EQUAL_STRING("handover_in_scale", field);
    c.handover_in_scale = R(1.5);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_tbd_config_check(&c, &field));
    TEST_ASSERT_EQUAL_STRING("handover_in_scale", field);
    /* a refused configuration leaves a running manager and its workspace as they were */
    static run_t r;
    cfg_of(&c);
    c.handover_in_scale = R(0.8);
    run(&c, &r);
    static pft_tbd_t snap;
    memcpy(&snap, &g_t, sizeof snap);
    memcpy(g_snap, g_ws, sizeof g_ws);
    pft_tbd_config_t bad = c;
    bad.handover_in_scale = R(1.5);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_tbd_init(&g_t, &bad, g_ws, sizeof g_ws));
    bad.handover_in_scale = R(-0.5);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_tbd_init(&g_t, &bad, g_ws, sizeof g_ws));
    TEST_ASSERT_EQUAL_MEMORY(&snap, &g_t, sizeof snap);
    TEST_ASSERT_EQUAL_MEMORY(g_snap, g_ws, sizeof g_ws);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_default_is_off);
    RUN_TEST(test_grace_keeps_a_young_track_for_k_end_tests);
    RUN_TEST(test_persist_ends_on_the_second_frame_in_a_row);
    RUN_TEST(test_fields_refused_by_name_and_state_kept);
    RUN_TEST(test_default_and_one_are_off);
    RUN_TEST(test_new_layer_starts_from_k_times_the_intensity);
    RUN_TEST(test_out_of_range_refused_by_name_and_state_kept);
    return UNITY_END();
}
