/*
 * The anchored clutter map (pft_pre_clutter_config_t.anchor; pft_pre.h "Anchored map",
 * docs/algorithms.md 9.9): the configuration (default off, refused with blocks, the same
 * workspace), refused input leaves instance and workspace byte for byte unchanged, and known
 * answers:
 * - a scene that drifts by sub-pixel steps (with a frame without evidence among them), its
 *   residual rendered at the scene's rounded position, gives the map of the same scene held
 *   still, moved by that position, value for value (m, and the output where the read's square
 *   lies in cells that never left the frame), with the running mean and the persistence gate:
 *   the whole-pixel moves keep the stored values exactly and the shifts are summed exactly;
 * - a 3 x 3 clutter blob fixed in that scene is suppressed at its centre while a point three
 *   pixels from the centre (two cells beyond the blob) comes out as it went in, bit for bit,
 *   16-bit and 8-bit map; the cells that enter hold a new pixel's value (m 1 sigma^2);
 * - inplace gives the same outputs;
 * - the golden vectors of tests/vectors/clutan_vectors_spec.h, bit for bit on every preset.
 * 64 x 48 frames, integer residuals, so that it runs on every target.
 */
#include <math.h>
#include <string.h>

#include "pft_test_support.h"
#include "pft/pft_pre.h"
#include "clutan_vectors_spec.h"
#include "clutan_q16_vectors.h"

void setUp(void) {}
void tearDown(void) {}

#define W 64
#define H 48
#define NPIX (W * H)
#define NF 24

static int16_t g_res[NPIX];
static int16_t g_res2[NPIX];
static uint64_t g_work[PFT_PRE_CLUTTER_WORKSPACE_BYTES(W, H, 1, PFT_PRE_CLUTTER_MAX_BLUR, 1) / 8 + 1];
static uint64_t g_work2[sizeof(g_work) / 8];
static uint64_t g_copy[sizeof(g_work) / 8];
static int16_t g_out[NPIX];

static pft_frame_t res_frame(int16_t *px, uint32_t seq)
{
    return pft_test_res16_frame(px, W, H, seq, 1000u * seq);
}

/* The drift of the known-answer tests: frame k's shift (Q16.16 px), sub-pixel steps of both
 * signs and one jump of 3.3 px. */
static void drift(int k, int32_t *sx, int32_t *sy)
{
    *sx = k == 0 ? 0 : (k == 13 ? 216269 : 19661 + 3277 * (k % 3));  /* 0.3..0.4 px; 3.3 px */
    *sy = k == 0 ? 0 : (k == 13 ? -98304 : -13107 + 6554 * (k % 2)); /* -0.2 / -0.1 px; -1.5 px */
}

/* The scene's rounded position, computed here in floating point (nearest, halves upwards). */
static int32_t nearest(int64_t q16)
{
    return (int32_t)floor((double)q16 / 65536.0 + 0.5);
}

/* The scene's residual at scene point (sx, sy) on frame k: noise about 0.75 sigma fixed in the
 * scene, a 3 x 3 blob of 4 sigma at (30, 20), and a part drawn anew each frame. */
static int16_t scene_res(int32_t sx, int32_t sy, int32_t x, int32_t y, int k)
{
    if (sx >= 29 && sx <= 31 && sy >= 19 && sy <= 21) {
        return 1024;
    }
    return (int16_t)((int32_t)(clan_gv_lattice(sx, sy, 0) % 385u) - 192 +
                     (int32_t)(clan_gv_lattice(x, y, k + 1) % 257u) - 128);
}

static void test_config(void)
{
    pft_pre_clutter_config_t cfg;
    pft_pre_clutter_config_default(&cfg);
    TEST_ASSERT_FALSE(cfg.anchor);
    const size_t plain = pft_pre_clutter_workspace_size(&cfg);
    cfg.anchor = true;
    const char *field = "x";
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_config_check(&cfg, &field));
    TEST_ASSERT_NULL(field);
    TEST_ASSERT_EQUAL_UINT64((uint64_t)(plain), (uint64_t)(pft_pre_clutter_workspace_size(&cfg)));
    /* with every other option of the per-pixel map */
    pft_pre_clutter_config_t a = cfg;
    a.mean = true;
    a.persist = 4u;
    a.veto = 8192u;
    a.inplace = true;
    a.map8 = true;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_config_check(&a, &field));
    a.map8 = false;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_config_check(&a, &field));
    /* blocks are refused, naming the field; without anchor they are accepted */
    for (uint8_t b = 2u; b <= 4u; b = (uint8_t)(b + 2u)) {
        pft_pre_clutter_config_t bad = cfg;
        bad.block = b;
        TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_pre_clutter_config_check(&bad, &field));
        TEST_ASSERT_EQUAL_STRING("anchor", field);
        TEST_ASSERT_EQUAL_UINT64((uint64_t)(0u), (uint64_t)(pft_pre_clutter_workspace_size(&bad)));
        pft_pre_clutter_t c;
        bad.width = W;
        bad.height = H;
        TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_pre_clutter_init(&c, &bad, g_work, sizeof g_work));
        bad.anchor = false;
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_config_check(&bad, &field));
    }
}

static void test_refused_input_changes_nothing(void)
{
    pft_pre_clutter_config_t cfg;
    pft_pre_clutter_config_default(&cfg);
    cfg.anchor = true;
    cfg.mean = true;
    cfg.persist = 3u;
    pft_pre_clutter_t c;
    pft_test_clutter_init(&c, &cfg, W, H, g_work, sizeof g_work);
    int64_t ax = 0, ay = 0;
    for (int k = 0; k < 6; ++k) {
        int32_t sx, sy;
        drift(k, &sx, &sy);
        ax += sx;
        ay += sy;
        for (int32_t y = 0; y < H; ++y) {
            for (int32_t x = 0; x < W; ++x) {
                g_res[y * W + x] = scene_res(x - nearest(ax), y - nearest(ay), x, y, k);
            }
        }
        pft_frame_t f = res_frame(g_res, (uint32_t)k + 1u);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_update(&c, &f, sx, sy, true));
    }
    pft_pre_clutter_t saved = c;
    memcpy(g_copy, g_work, sizeof g_work);
    pft_frame_t f = res_frame(g_res, 9u);
    pft_frame_t b = f;
    b.format = PFT_PIX_U16;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_FORMAT, pft_pre_clutter_update(&c, &b, 5 * 65536, 65536, true));
    b = f;
    b.width = W - 1;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_FORMAT, pft_pre_clutter_update(&c, &b, 5 * 65536, 65536, true));
    b = f;
    b.stride_bytes = 2u * W + 1u;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_FORMAT, pft_pre_clutter_update(&c, &b, -65536, 32768, false));
    b = f;
    b.data = NULL;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_pre_clutter_update(&c, &b, 65536, 0, true));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_pre_clutter_update(&c, NULL, 65536, 0, true));
    /* the in-place call on an instance without inplace */
    TEST_ASSERT_EQUAL_INT(PFT_ERR_STATE, pft_pre_clutter_update_inplace(&c, &f, g_res, 65536, 0, true));
    TEST_ASSERT_EQUAL_MEMORY(&saved, &c, sizeof c);
    TEST_ASSERT_EQUAL_MEMORY(g_copy, g_work, sizeof g_work);
    /* reset is init: the summed shifts and the position too */
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_reset(&c));
    saved = c;
    memcpy(g_copy, g_work, sizeof g_work);
    pft_pre_clutter_t c2;
    memset(g_work, 0xA5, sizeof g_work);
    pft_test_clutter_init(&c2, &cfg, W, H, g_work, sizeof g_work);
    TEST_ASSERT_EQUAL_MEMORY(&saved, &c2, sizeof c2);
    TEST_ASSERT_EQUAL_MEMORY(g_copy, g_work, pft_pre_clutter_workspace_size(&c2.cfg) - (PFT_WS_ALIGN - 1u));
}

/* The drifting scene against the same scene held still (shift 0, the residual at scene
 * coordinates), gated running mean (persist 3, alpha 0.1, thr 2): NF frames, frame 9 without
 * evidence (its shift is summed all the same). With P_k the rounded sum of the shifts and
 * [lo, hi) the frame pixels whose scene cell stayed inside the frame on every frame, the
 * anchored map at p equals the still one at p - P, bit for bit, and so does the output where
 * the read's 3 x 3 square lies inside [lo, hi). Exact: no tolerance (integer arithmetic, the
 * same operations on the same values). */
static void test_drifting_scene_equals_still_scene(void)
{
    pft_pre_clutter_config_t cfg;
    pft_pre_clutter_config_default(&cfg);
    cfg.mean = true;
    cfg.persist = 3u;
    pft_pre_clutter_t ca, cs;
    cfg.anchor = true;
    pft_test_clutter_init(&ca, &cfg, W, H, g_work, sizeof g_work);
    cfg.anchor = false;
    pft_test_clutter_init(&cs, &cfg, W, H, g_work2, sizeof g_work2);
    int64_t ax = 0, ay = 0;
    int32_t pxmin = 0, pxmax = 0, pymin = 0, pymax = 0;
    int compared = 0;
    for (int k = 0; k < NF; ++k) {
        int32_t sx, sy;
        drift(k, &sx, &sy);
        ax += sx;
        ay += sy;
        const int32_t px = nearest(ax), py = nearest(ay);
        const bool ev = k != 9;
        if (ev) {
            pxmin = px < pxmin ? px : pxmin;
            pxmax = px > pxmax ? px : pxmax;
            pymin = py < pymin ? py : pymin;
            pymax = py > pymax ? py : pymax;
        }
        for (int32_t y = 0; y < H; ++y) {
            for (int32_t x = 0; x < W; ++x) {
                /* the same scene point and the same fresh part in both */
                g_res[y * W + x] = scene_res(x - px, y - py, x - px, y - py, k);
                g_res2[y * W + x] = scene_res(x, y, x, y, k);
            }
        }
        pft_frame_t fa = res_frame(g_res, (uint32_t)k + 1u);
        pft_frame_t fs = res_frame(g_res2, (uint32_t)k + 1u);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_update(&ca, &fa, sx, sy, ev));
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_update(&cs, &fs, 0, 0, ev));
        /* the frame pixels whose scene cell never left: p - P + P_j in [0, W) for every j */
        const int32_t xlo = px - pxmin, xhi = W + px - pxmax;
        const int32_t ylo = py - pymin, yhi = H + py - pymax;
        if (!ev) {
            continue; /* the arrays move at the next frame with evidence */
        }
        const int16_t *oa = pft_test_clutter_out(&ca), *os = pft_test_clutter_out(&cs);
        for (int32_t y = ylo; y < yhi; ++y) {
            for (int32_t x = xlo; x < xhi; ++x) {
                const uint32_t ma = pft_pre_clutter_at(&ca, (uint32_t)x, (uint32_t)y);
                const uint32_t ms = pft_pre_clutter_at(&cs, (uint32_t)(x - px), (uint32_t)(y - py));
                if (ma != ms) {
                    TEST_FAIL_MESSAGE("anchored map differs from the still scene's");
                }
                if (y > ylo && y < yhi - 1 && x > xlo && x < xhi - 1 &&
                    oa[y * W + x] != os[(y - py) * W + (x - px)]) {
                    TEST_FAIL_MESSAGE("anchored output differs from the still scene's");
                }
                compared++;
            }
        }
    }
    /* the drift went somewhere: more than 8 px right and 3 px up, and a good part compared */
    TEST_ASSERT_TRUE(nearest(ax) > 8 && nearest(ay) < -3);
    TEST_ASSERT_TRUE(compared > NF * NPIX / 2);
    /* the cells that entered last (the left columns, right of the moves) started at 1 sigma^2:
     * the still map learnt the scene's noise there (well below 1 sigma^2 after NF frames), the
     * anchored one holds more than a new pixel's 1 sigma^2 decayed by the frames since */
    TEST_ASSERT_TRUE(pft_pre_clutter_at(&cs, 0u, 24u) < 700u);
    TEST_ASSERT_TRUE(pft_pre_clutter_at(&ca, 0u, 24u) > 700u);
}

/* The blob fixed in the drifting scene (default map: 3 x 3 mean, alpha 0.1, thr 2), 16-bit
 * and 8-bit: after NF frames its centre comes out suppressed (below 2 sigma: 4 / sqrt(M) with
 * M near 16 (1 - 0.9^n) > 8 sigma^2), while a probe of 4 sigma three pixels right of the centre
 * (its 3 x 3 read two cells beyond the blob's cells: the scene's noise only, M < thr) comes out
 * as it went in, bit for bit. Without anchor the same frames are carried by the bilinear warp:
 * the map at the blob's centre is then below the anchored one (smeared over its neighbours by
 * the sub-pixel steps while the blob is rendered at whole pixels). */
static void run_blob(bool map8, bool anchor, int32_t *centre_out, int32_t *probe_out, uint32_t *centre_m)
{
    pft_pre_clutter_config_t cfg;
    pft_pre_clutter_config_default(&cfg);
    cfg.map8 = map8;
    cfg.anchor = anchor;
    pft_pre_clutter_t c;
    pft_test_clutter_init(&c, &cfg, W, H, g_work, sizeof g_work);
    int64_t ax = 0, ay = 0;
    for (int k = 0; k < NF; ++k) {
        int32_t sx, sy;
        drift(k, &sx, &sy);
        ax += sx;
        ay += sy;
        const int32_t px = nearest(ax), py = nearest(ay);
        for (int32_t y = 0; y < H; ++y) {
            for (int32_t x = 0; x < W; ++x) {
                g_res[y * W + x] = scene_res(x - px, y - py, x, y, k);
            }
        }
        if (k == NF - 1) {
            g_res[(20 + py) * W + 33 + px] = 1024; /* the probe */
        }
        pft_frame_t f = res_frame(g_res, (uint32_t)k + 1u);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_update(&c, &f, sx, sy, true));
        if (k == NF - 1) {
            const int16_t *o = pft_test_clutter_out(&c);
            *centre_out = o[(20 + py) * W + 30 + px];
            *probe_out = o[(20 + py) * W + 33 + px];
            *centre_m = pft_pre_clutter_at(&c, (uint32_t)(30 + px), (uint32_t)(20 + py));
        }
    }
}

static void test_blob_suppressed_probe_kept(void)
{
    int32_t co, po, co8, po8, cc, pc;
    uint32_t cm, cm8, ccm;
    run_blob(false, true, &co, &po, &cm);
    run_blob(true, true, &co8, &po8, &cm8);
    run_blob(false, false, &cc, &pc, &ccm);
    TEST_ASSERT_TRUE(co < 512);
    TEST_ASSERT_TRUE(co8 < 512);
    TEST_ASSERT_EQUAL_INT32(1024, po);
    TEST_ASSERT_EQUAL_INT32(1024, po8);
    /* the centre's m: the blob's 16 sigma^2 learnt at 0.1 a frame over NF frames,
     * 16 (1 - 0.9^(NF - 10)) at the least (the 1/n start only raises it) */
    TEST_ASSERT_TRUE(cm > (uint32_t)(16384.0 * (1.0 - pow(0.9, NF - 10))));
    /* map8 within its code's precision (1/64 relative) plus the dither's step */
    TEST_ASSERT_UINT32_WITHIN(cm / 32u + 64u, cm, cm8);
    TEST_ASSERT_TRUE(ccm < cm);
}

/* inplace with anchor: the same outputs as the map that writes its own buffer. */
static void test_inplace_same_values(void)
{
    pft_pre_clutter_config_t cfg;
    pft_pre_clutter_config_default(&cfg);
    cfg.anchor = true;
    cfg.mean = true;
    cfg.persist = 2u;
    pft_pre_clutter_t c, ci;
    pft_test_clutter_init(&c, &cfg, W, H, g_work, sizeof g_work);
    cfg.inplace = true;
    pft_test_clutter_init(&ci, &cfg, W, H, g_work2, sizeof g_work2);
    int64_t ax = 0, ay = 0;
    for (int k = 0; k < 12; ++k) {
        int32_t sx, sy;
        drift(k, &sx, &sy);
        ax += sx;
        ay += sy;
        for (int32_t y = 0; y < H; ++y) {
            for (int32_t x = 0; x < W; ++x) {
                g_res[y * W + x] = scene_res(x - nearest(ax), y - nearest(ay), x, y, k);
            }
        }
        memcpy(g_res2, g_res, sizeof g_res);
        pft_frame_t f = res_frame(g_res, (uint32_t)k + 1u);
        pft_frame_t fi = res_frame(g_res2, (uint32_t)k + 1u);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_update(&c, &f, sx, sy, true));
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_update_inplace(&ci, &fi, g_res2, sx, sy, true));
        memcpy(g_out, pft_test_clutter_out(&c), sizeof g_out);
        TEST_ASSERT_EQUAL_INT16_ARRAY(g_out, g_res2, NPIX);
    }
}

static clan_gv_results_t got;

static void test_golden_bit_exact(void)
{
    clan_gv_compute(&got);
    for (uint32_t j = 0; j < CLAN_GV_CASES; ++j) {
        for (uint32_t k = 0; k < CLAN_GV_FRAMES; ++k) {
            TEST_ASSERT_EQUAL_INT32(PFT_OK, got.rec[j][k][0]);
            TEST_ASSERT_EQUAL_INT32((int32_t)(200u + k), got.rec[j][k][4]);
        }
    }
    TEST_ASSERT_EQUAL_INT32_ARRAY_MESSAGE(clan_gv_rec, &got.rec[0][0][0],
                                          CLAN_GV_CASES * CLAN_GV_FRAMES * CLAN_GV_NF, "anchored map");
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_config);
    RUN_TEST(test_refused_input_changes_nothing);
    RUN_TEST(test_drifting_scene_equals_still_scene);
    RUN_TEST(test_blob_suppressed_probe_kept);
    RUN_TEST(test_inplace_same_values);
    RUN_TEST(test_golden_bit_exact);
    return UNITY_END();
}
