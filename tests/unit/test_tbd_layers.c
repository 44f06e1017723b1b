/*
 * TBD manager, search layers (cfg.search_layers, docs/algorithms.md 2.14): with two search
 * layers a dim target is confirmed while a brighter recurring spot holds the other layer; with
 * one search layer the spot takes the one hypothesis at every frame and the target is never
 * confirmed. In q16 as in float.
 *
 * Scene (32 x 32, noise sigma 2, the recommended preset with the Bernoulli search layer:
 * birth_share 0.5, theta1 0.6, confirm_frames 2, 8 birth peaks, the shape test shape_ring
 * 0.15, 800 search particles): a still blob at A = (8, 8), 25 point sources of intensity 20 on
 * a 5 x 5 grid of 1 px pitch (wider than the PSF, so the shape test refuses its hand-over and
 * the search layer that holds it starts over: recurring clutter), and a still point target of
 * intensity 30 at B = (24, 24), both in every frame.
 */
#include <math.h>
#include <string.h>

#include "pft_test_support.h"
#include "pft_tbd_sim.h"
#include "pft/pft_tbd.h"

void setUp(void) {}
void tearDown(void) {}

#define IMG 32
#define NS 800u
#define NT 200u
#define MAXT 3u
#define KP 8u
#define FRAMES 12
#define NSRC 26

static pft_real_t R(double v) { return pft_test_from_double(v); }
static double D(pft_real_t v) { return pft_test_to_double(v); }

#define WS_BYTES                                                                                \
    (PFT_TBD_WORKSPACE_BYTES_PEAKS(NS, NT, MAXT, PFT_TBD_RBPF, IMG, IMG, KP) +                  \
     PFT_TBD_SEARCH_BYTES(PFT_TBD_MAX_SEARCH, IMG, IMG, KP))
static uint8_t g_ws[WS_BYTES + 64];
static uint16_t g_raw[IMG * IMG];
static pft_tbd_t g_t;

static const double AX = 8.0, AY = 8.0, BX = 24.0, BY = 24.0;

static void cfg_of(pft_tbd_config_t *c, uint32_t seed, uint8_t layers)
{
    pft_test_tbd_bern_config(c, IMG, 2.0, NS, NT, MAXT, KP, seed);
    c->shape_ring = R(0.15);
    c->search_layers = layers;
    if (layers >= 2u) {
        c->search_sep = R(3.0);
        c->search_hold = R(0.5);
    }
}

static double dist(double x, double y, double x0, double y0) { return hypot(x - x0, y - y0); }

typedef struct {
    int first_b;    /* first frame with a track within 1.5 px of B (0: none) */
    int tracks_a;   /* frames with a track within 3 px of A */
    int a_held;     /* frames (from frame 2) at which some layer's estimate is within 3 px of A with P > 0.5 */
    size_t n[FRAMES];
    pft_tbd_track_t tk[FRAMES][MAXT];
    double p[FRAMES];
    unsigned near_b[FRAMES]; /* bit h: layer h's estimate within 1.5 px of B with P > theta1 */
} run_t;

static void scene(pft_sim_truth_t *t)
{
    int q = 0;
    for (int a = -2; a <= 2; ++a) {
        for (int b = -2; b <= 2; ++b) {
            const pft_sim_truth_t s = {1, FRAMES, AX + a, AY + b, 0.0, 0.0, 20.0};
            t[q++] = s;
        }
    }
    const pft_sim_truth_t tb = {1, FRAMES, BX, BY, 0.0, 0.0, 30.0};
    t[q] = tb;
}

static void run(uint32_t seed, uint8_t layers, run_t *o)
{
    pft_tbd_config_t c;
    cfg_of(&c, seed, layers);
    TEST_ASSERT_TRUE(pft_tbd_workspace_size(&c) <= sizeof g_ws);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_init(&g_t, &c, g_ws, sizeof g_ws));
    memset(o, 0, sizeof *o);
    pft_sim_truth_t src[NSRC];
    scene(src);
    pft_rng_t sim;
    pft_rng_seed(&sim, 9u);
    const uint32_t nl = layers >= 2u ? layers : 1u;
    for (int k = 1; k <= FRAMES; ++k) {
        pft_frame_t fr;
        pft_sim_render_u16(&sim, src, NSRC, k, 2.0, IMG, IMG, g_raw, &fr);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_update(&g_t, &fr));
        const size_t n = pft_tbd_tracks(&g_t, o->tk[k - 1], MAXT);
        o->n[k - 1] = n;
        bool on_a = false;
        for (size_t i = 0; i < n && i < MAXT; ++i) {
            const double x = D(o->tk[k - 1][i].x), y = D(o->tk[k - 1][i].y);
            if (o->first_b == 0 && dist(x, y, BX, BY) < 1.5) {
                o->first_b = k;
            }
            on_a = on_a || dist(x, y, AX, AY) < 3.0;
        }
        o->tracks_a += on_a ? 1 : 0;
        pft_tbd_estimate_t se;
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_search_estimate(&g_t, &se));
        o->p[k - 1] = D(se.p_exist);
        bool held = false;
        double pmax = 0.0;
        for (uint32_t h = 0; h < nl; ++h) {
            pft_tbd_estimate_t le;
            TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_search_layer_estimate(&g_t, h, &le));
            pmax = D(le.p_exist) > pmax ? D(le.p_exist) : pmax;
            held = held || (D(le.p_exist) > 0.5 && dist(D(le.x), D(le.y), AX, AY) < 3.0);
            if (le.valid && D(le.p_exist) > 0.6 && dist(D(le.x), D(le.y), BX, BY) < 1.5) {
                o->near_b[k - 1] |= 1u << h;
            }
        }
        /* pft_tbd_search_estimate: the layer of the largest existence probability */
        TEST_ASSERT_EQUAL_DOUBLE(pmax, o->p[k - 1]);
        o->a_held += k >= 2 && held ? 1 : 0;
        pft_tbd_estimate_t bad;
        TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tbd_search_layer_estimate(&g_t, nl, &bad));
    }
}

/* Manager seeds 1-4: one search layer never confirms B in 12 frames (the blob takes its
 * hypothesis at every frame and is refused by the shape test); two layers confirm B by frame 8
 * with no track on the blob, and some layer holds the blob on most frames. */
static void test_two_layers_confirm_the_dim_target(void)
{
    for (uint32_t seed = 1u; seed <= 4u; ++seed) {
        static run_t one, two;
        run(seed, 0u, &one);
        run(seed, 2u, &two);
        TEST_ASSERT_EQUAL_INT_MESSAGE(0, one.first_b, "one layer: B not confirmed");
        TEST_ASSERT_EQUAL_INT_MESSAGE(0, one.tracks_a, "one layer: no track on the blob");
        TEST_ASSERT_TRUE_MESSAGE(two.first_b >= 1 && two.first_b <= 8, "two layers: B confirmed");
        TEST_ASSERT_EQUAL_INT_MESSAGE(0, two.tracks_a, "two layers: no track on the blob");
        TEST_ASSERT_TRUE_MESSAGE(two.a_held >= FRAMES / 2, "two layers: the blob holds a layer");
        /* the B track's record names the layer that handed it over: one that held B above
         * theta1 at the frame before (confirm_frames 2); with one layer every record says 0 */
        const int kb = two.first_b - 1;
        const pft_tbd_track_t *b = NULL;
        for (size_t i = 0; i < two.n[kb] && i < MAXT; ++i) {
            if (dist(D(two.tk[kb][i].x), D(two.tk[kb][i].y), BX, BY) < 1.5) {
                b = &two.tk[kb][i];
            }
        }
        TEST_ASSERT_NOT_NULL(b);
        TEST_ASSERT_TRUE_MESSAGE(kb >= 1, "hand-over after two frames above theta1");
        TEST_ASSERT_TRUE_MESSAGE(b->search_layer < 2u, "a layer of the two");
        TEST_ASSERT_TRUE_MESSAGE(((two.near_b[kb - 1] >> b->search_layer) & 1u) != 0u,
                                 "the named layer held B the frame before");
        for (int k = 0; k < FRAMES; ++k) {
            for (size_t i = 0; i < one.n[k] && i < MAXT; ++i) {
                TEST_ASSERT_EQUAL_UINT8(0u, one.tk[k][i].search_layer);
            }
        }
    }
}

/* search_layers 1 is the one search layer: bit-identical tracks and P over the frames. */
static void test_one_layer_is_the_default(void)
{
    static run_t a, b;
    run(1u, 0u, &a);
    run(1u, 1u, &b);
    for (int k = 0; k < FRAMES; ++k) {
        TEST_ASSERT_EQUAL_UINT(a.n[k], b.n[k]);
        TEST_ASSERT_EQUAL_MEMORY(&a.p[k], &b.p[k], sizeof a.p[k]);
        for (size_t i = 0; i < a.n[k] && i < MAXT; ++i) {
            TEST_ASSERT_EQUAL_MEMORY(&a.tk[k][i], &b.tk[k][i], sizeof a.tk[k][i]);
        }
    }
}

/* The fields' refusals, by name, and the workspace figure. */
static void test_refusals(void)
{
    pft_tbd_config_t c;
    const char *f = NULL;
    cfg_of(&c, 1u, 2u);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_config_check(&c, &f));
    TEST_ASSERT_EQUAL_UINT64((uint64_t)PFT_TBD_WORKSPACE_BYTES_PEAKS(NS, NT, MAXT, PFT_TBD_RBPF, IMG, IMG, KP) +
                                 PFT_TBD_SEARCH_BYTES(2u, IMG, IMG, KP),
                             (uint64_t)pft_tbd_workspace_size(&c));
    c.search_layers = (uint8_t)(PFT_TBD_MAX_SEARCH + 1u);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_tbd_config_check(&c, &f));
    TEST_ASSERT_EQUAL_STRING("search_layers", f);
    cfg_of(&c, 1u, 2u);
    c.birth_share = R(0.0);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_tbd_config_check(&c, &f));
    TEST_ASSERT_EQUAL_STRING("search_layers", f);
    cfg_of(&c, 1u, 2u);
    c.search_sep = R(0.5);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_tbd_config_check(&c, &f));
    TEST_ASSERT_EQUAL_STRING("search_sep", f);
    cfg_of(&c, 1u, 2u);
    c.search_hold = R(1.0);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_tbd_config_check(&c, &f));
    TEST_ASSERT_EQUAL_STRING("search_hold", f);
    cfg_of(&c, 1u, 0u);
    c.search_sep = R(3.0);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_tbd_config_check(&c, &f));
    TEST_ASSERT_EQUAL_STRING("search_sep", f);
    cfg_of(&c, 1u, 0u);
    TEST_ASSERT_EQUAL_UINT64((uint64_t)PFT_TBD_WORKSPACE_BYTES_PEAKS(NS, NT, MAXT, PFT_TBD_RBPF, IMG, IMG, KP),
                             (uint64_t)pft_tbd_workspace_size(&c));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_refusals);
    RUN_TEST(test_one_layer_is_the_default);
    RUN_TEST(test_two_layers_confirm_the_dim_target);
    return UNITY_END();
}
