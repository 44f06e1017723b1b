/*
 * TBD manager reading the stage's RES16 residual in place (cfg.frame_format = PFT_PIX_RES16,
 * docs/algorithms.md 2.7) against the same manager converting it into its real-valued frame.
 *
 * Known answer: the two read the same values (res / 256, a masked pixel 0, 0 outside the image;
 * the tracks' PSFs subtracted by the residual likelihood as patches with the arithmetic of the
 * in-place subtraction), so every output is bit for bit the same: tracks, events, the search
 * layer's estimate and the birth candidates after every frame (memcmp, no tolerance). The
 * frames have targets entering at the left border, along the bottom edge and two whose
 * subtracted PSFs overlap, masked pixels inside and on the border; four configurations: the
 * recommended preset with birth peaks (the 3 x 3 kernel and the peak scan), with B_k (births
 * above gamma), with window 2 (the exact kernel) and with peaks and a Bernoulli search layer
 * (birth_share 0.5, the groups' prior weights in every log-weight). The test requires two or more tracks at
 * once (so patches are built, overlap and are read). The workspace is PFT_TBD_WORKSPACE_BYTES_RES16
 * and smaller than the converted manager's by the frame less what reading in place adds; a
 * frame of another format is refused with the instance and the workspace byte-identical; a
 * frame_format the library cannot honour is refused by name; reset starts over identically.
 */
#include <stdio.h>
#include <string.h>

#include "pft_test_support.h"
#include "pft_tbd_sim.h"
#include "pft/pft_tbd.h"

void setUp(void) {}
void tearDown(void) {}

#define W 48
#define H 40
#define NS 600u
#define NT 150u
#define MAXT 4u
#define KMAX 24u
#define NFRAMES 24

static pft_real_t R(double v) { return pft_test_from_double(v); }

#define WS_CONV PFT_TBD_WORKSPACE_BYTES_PEAKS(NS, NT, MAXT, PFT_TBD_RBPF, W, H, 0u)
#define WS_IN PFT_TBD_WORKSPACE_BYTES_RES16(NS, NT, MAXT, PFT_TBD_RBPF, W, H, 0u)
static uint8_t g_ws_a[WS_CONV + 64];
static uint8_t g_ws_b[WS_IN + 64];
static uint8_t g_snap[WS_IN + 64];
static uint16_t g_u16[W * H];
static int16_t g_res[NFRAMES][W * H];

/* four targets (intensity 25: a peak of about 8 sigma): one entering at the left border, one
 * along the bottom edge, two whose subtracted PSFs (half-size p + margin) overlap */
static const pft_sim_truth_t g_truth[4] = {
    {1, NFRAMES, 0.2, 9.0, 0.7, 0.1, 25.0},
    {1, NFRAMES, 30.0, 39.0, -0.4, 0.0, 25.0},
    {1, NFRAMES, 20.0, 22.0, 0.1, 0.05, 25.0},
    {1, NFRAMES, 23.0, 23.0, 0.1, 0.0, 25.0},
};

/* The frames as the stage hands them over: Q8.8 sigma units (unit noise), masked pixels. */
static void make_frames(void)
{
    pft_rng_t rng;
    pft_rng_seed(&rng, 11u);
    for (int k = 1; k <= NFRAMES; ++k) {
        pft_frame_t f;
        pft_sim_render_u16(&rng, g_truth, 4, k, 1.0, W, H, g_u16, &f);
        int16_t *res = g_res[k - 1];
        for (int i = 0; i < W * H; ++i) {
            /* raw = round((z + 64) 256): res = raw - 16384 = round(256 z), kept off the
             * masked value */
            int32_t v = (int32_t)g_u16[i] - 16384;
            v = v < -32767 ? -32767 : (v > 32767 ? 32767 : v);
            res[i] = (int16_t)v;
        }
        /* masked pixels: a corner, a border pixel, one beside a target's path, a column run */
        res[0] = PFT_RES16_MASKED;
        res[W - 1 + 7 * W] = PFT_RES16_MASKED;
        res[22 + 22 * W] = PFT_RES16_MASKED;
        for (int r = 30; r < 36; ++r) {
            res[40 + r * W] = PFT_RES16_MASKED;
        }
        if (k % 5 == 0) {
            res[5 + 9 * W] = PFT_RES16_MASKED; /* on the first target's path now and then */
        }
    }
}

static void res_frame(pft_frame_t *f, int k)
{
    memset(f, 0, sizeof(*f));
    f->data = g_res[k - 1];
    f->width = W;
    f->height = H;
    f->stride_bytes = W * 2u;
    f->format = PFT_PIX_RES16;
    f->bit_depth = 16u;
    f->seq = (uint32_t)k;
}

static void cfg_of(pft_tbd_config_t *c, uint16_t peaks, uint8_t window)
{
    pft_tbd_config_recommended(c);
    c->width = W;
    c->height = H;
    c->noise_sigma = R(1.0);
    c->pixel_gain = R(1.0);
    c->pixel_offset = R(0.0);
    c->n_search = NS;
    c->n_track = NT;
    c->max_targets = MAXT;
    c->birth_peaks = peaks;
    c->window = window;
    c->residual_search = true;
    c->residual_tracks = true;
    c->residual_margin = 1u;
    c->seed = 5u;
}

/* Every output of a and b after an update is the same, bit for bit; returns the tracks. */
static size_t same_outputs(const pft_tbd_t *a, const pft_tbd_t *b, int k)
{
    static pft_tbd_track_t ta[MAXT], tb[MAXT];
    static pft_tbd_event_t ea[MAXT + 1u], eb[MAXT + 1u];
    static uint32_t ca[W * H], cb[W * H];
    char msg[64];
    memset(ta, 0, sizeof ta);
    memset(tb, 0, sizeof tb);
    memset(ea, 0, sizeof ea);
    memset(eb, 0, sizeof eb);
    snprintf(msg, sizeof msg, "frame %d", k);
    size_t na = pft_tbd_tracks(a, ta, MAXT);
    TEST_ASSERT_EQUAL_UINT_MESSAGE((unsigned)na, (unsigned)pft_tbd_tracks(b, tb, MAXT), msg);
    TEST_ASSERT_EQUAL_MEMORY_MESSAGE(ta, tb, sizeof ta, msg);
    size_t nea = pft_tbd_events(a, ea, MAXT + 1u);
    TEST_ASSERT_EQUAL_UINT_MESSAGE((unsigned)nea, (unsigned)pft_tbd_events(b, eb, MAXT + 1u), msg);
    TEST_ASSERT_EQUAL_MEMORY_MESSAGE(ea, eb, sizeof ea, msg);
    pft_tbd_estimate_t sa, sb;
    memset(&sa, 0, sizeof sa);
    memset(&sb, 0, sizeof sb);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_search_estimate(a, &sa));
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_search_estimate(b, &sb));
    TEST_ASSERT_EQUAL_MEMORY_MESSAGE(&sa, &sb, sizeof sa, msg);
    memset(ca, 0, sizeof ca);
    memset(cb, 0, sizeof cb);
    size_t nca = pft_tbd_birth_candidates(a, ca, W * H);
    TEST_ASSERT_EQUAL_UINT_MESSAGE((unsigned)nca, (unsigned)pft_tbd_birth_candidates(b, cb, W * H), msg);
    TEST_ASSERT_EQUAL_MEMORY_MESSAGE(ca, cb, sizeof ca, msg);
    return na;
}

/* share > 0: the search layer in the Bernoulli form (docs/algorithms.md 2.11) with that birth
 * share, as pft_tbd_config_bounded sets it (its log-weights add the groups' prior weights) */
static void run_pair_share(uint16_t peaks, uint8_t window, double share)
{
    static pft_tbd_t a, b;
    pft_tbd_config_t ca, cb;
    cfg_of(&ca, peaks, window);
    if (share > 0.0) {
        ca.birth_share = R(share);
        ca.theta1 = R(0.475);
    }
    cb = ca;
    cb.frame_format = PFT_PIX_RES16;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_config_check(&cb, NULL));
    TEST_ASSERT_TRUE(pft_tbd_workspace_size(&ca) <= sizeof g_ws_a);
    TEST_ASSERT_TRUE(pft_tbd_workspace_size(&cb) <= sizeof g_ws_b);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_init(&a, &ca, g_ws_a, sizeof g_ws_a));
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_init(&b, &cb, g_ws_b, sizeof g_ws_b));
    size_t most = 0u;
    for (int pass = 0; pass < 2; ++pass) {
        for (int k = 1; k <= NFRAMES; ++k) {
            pft_frame_t f;
            res_frame(&f, k);
            TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_update(&a, &f));
            TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_update(&b, &f));
            size_t n = same_outputs(&a, &b, k);
            most = n > most ? n : most;
        }
        /* reset: both start over (same seeds) */
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_reset(&a));
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_reset(&b));
    }
    /* the patches were built and read: two or more tracks at once */
    TEST_ASSERT_TRUE_MESSAGE(most >= 2u, "fewer than two tracks at once: the patches untested");
}

static void run_pair(uint16_t peaks, uint8_t window) { run_pair_share(peaks, window, 0.0); }

static void test_same_outputs_with_peaks(void) { run_pair(KMAX, 1u); }
static void test_same_outputs_with_bk(void) { run_pair(0u, 1u); }
static void test_same_outputs_exact_kernel(void) { run_pair(KMAX, 2u); }
/* the Bernoulli search layer: births and survivors weighed with their groups' prior weights,
 * also at the edges and on the patches' rows (on AArch64 float the windows that call out of
 * line are weighed outside weigh_r16_'s inner loop, tbd_filter.c WEIGH_SPLIT_) */
static void test_same_outputs_bernoulli(void) { run_pair_share(KMAX, 1u, 0.5); }

static void test_workspace_without_the_frame(void)
{
    pft_tbd_config_t c;
    cfg_of(&c, KMAX, 1u);
    const size_t conv = pft_tbd_workspace_size(&c);
    c.frame_format = PFT_PIX_RES16;
    const size_t inpl = pft_tbd_workspace_size(&c);
    TEST_ASSERT_EQUAL_UINT((unsigned)PFT_TBD_WORKSPACE_BYTES_RES16(NS, NT, MAXT, PFT_TBD_RBPF, W, H,
                                                                   KMAX),
                           (unsigned)inpl);
    /* the frame, (W + 2)(H + 2) reals, gone; added: 4 int32 per track slot, H row flags, a
     * row of W + 2 reals and the 9 x 9 window of the exact kernel */
    const size_t frame = PFT_WS_ROUND((size_t)(W + 2) * (H + 2) * sizeof(pft_real_t));
    const size_t added = PFT_WS_ROUND(4u * MAXT * sizeof(int32_t)) + PFT_WS_ROUND((size_t)H) +
                         PFT_WS_ROUND((W + 2u + 81u) * sizeof(pft_real_t));
    TEST_ASSERT_EQUAL_UINT((unsigned)(conv - frame + added), (unsigned)inpl);
    TEST_ASSERT_TRUE(inpl < conv);
    /* init needs every byte */
    static pft_tbd_t t;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_NOMEM, pft_tbd_init(&t, &c, g_ws_b, inpl - PFT_WS_ALIGN));
}

static void test_refusals(void)
{
    static pft_tbd_t t, t_snap;
    pft_tbd_config_t c;
    const char *field = NULL;
    cfg_of(&c, KMAX, 1u);
    c.frame_format = PFT_PIX_U16;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_tbd_config_check(&c, &field));
    TEST_ASSERT_EQUAL_STRING("frame_format", field);
    c.frame_format = PFT_PIX_RES16;
    c.noise_sigma = R(3.2); /* the values would not be res / 256 */
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_tbd_config_check(&c, &field));
    TEST_ASSERT_EQUAL_STRING("frame_format", field);
    cfg_of(&c, KMAX, 1u);
    c.frame_format = PFT_PIX_RES16;
    const size_t len = pft_tbd_workspace_size(&c);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_init(&t, &c, g_ws_b, len));
    pft_frame_t f;
    for (int k = 1; k <= 6; ++k) {
        res_frame(&f, k);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_update(&t, &f));
    }
    memcpy(&t_snap, &t, sizeof t);
    memcpy(g_snap, g_ws_b, len);
    /* a U16 frame of the right size: refused by format, nothing touched */
    pft_rng_t rng;
    pft_rng_seed(&rng, 2u);
    pft_sim_render_u16(&rng, g_truth, 4, 7, 1.0, W, H, g_u16, &f);
    f.seq = 7u;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_FORMAT, pft_tbd_update(&t, &f));
    TEST_ASSERT_EQUAL_MEMORY(&t_snap, &t, sizeof t);
    TEST_ASSERT_EQUAL_MEMORY(g_snap, g_ws_b, len);
    /* a RES16 frame of the wrong size */
    res_frame(&f, 7);
    f.width = W - 1;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_FORMAT, pft_tbd_update(&t, &f));
    TEST_ASSERT_EQUAL_MEMORY(&t_snap, &t, sizeof t);
    TEST_ASSERT_EQUAL_MEMORY(g_snap, g_ws_b, len);
}

int main(void)
{
    make_frames();
    UNITY_BEGIN();
    RUN_TEST(test_same_outputs_with_peaks);
    RUN_TEST(test_same_outputs_with_bk);
    RUN_TEST(test_same_outputs_exact_kernel);
    RUN_TEST(test_same_outputs_bernoulli);
    RUN_TEST(test_workspace_without_the_frame);
    RUN_TEST(test_refusals);
    return UNITY_END();
}
