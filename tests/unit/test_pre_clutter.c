/*
 * Clutter map of the whitened residual (pft_pre.h, pft_pre_clutter_*): configuration check
 * naming the refused field, workspace size, refused input leaves instance and workspace byte
 * for byte unchanged, and known answers: a persistent blob is learnt at the documented rate
 * (m_k = 16 (1 - (1 - a)^k) for a 4 sigma blob after a zero history, the output 4 / sqrt(m_{k-1})
 * once m_{k-1} > thr), a moving point on unit noise keeps its value exactly, the running mean
 * removes a persistent offset, the map moves with the scene (integer and half-pixel shifts), a
 * frame without evidence changes nothing, masked pixels stay masked, the veto zeroes a learnt
 * blob from the documented frame on, the persistence gate learns a blob that stays put in the
 * scene and not a point that moves against it, and the running mean with and without the gate
 * matches a reference of its formulas on every pixel of 12 frames, and the warp of the map,
 * the mean and the counter matches the bilinear formula on every cell, and floor_age's runs of
 * old and young columns take the floor where the reference does. 64 x 48 frames, integer
 * residuals made per pixel, so that it runs on every target.
 */
#include <math.h>
#include <string.h>

#include "pft_test_support.h"
#include "pft/pft_pre.h"

void setUp(void) {}
void tearDown(void) {}

#define W 64
#define H 48
#define NPIX (W * H)

static int16_t g_res[NPIX];
static uint64_t g_work[PFT_PRE_CLUTTER_WORKSPACE_BYTES(W, H, 1, PFT_PRE_CLUTTER_MAX_BLUR, 1) / 8 + 1];
static uint64_t g_copy[sizeof(g_work) / 8];
static uint32_t g_rs = 2463534242u;

/* about N(0, 1) in Q8.8: a sum of four uniforms, sd 256 */
static int16_t noise_q88(void)
{
    return (int16_t)pft_test_noise_q88(&g_rs);
}

static pft_frame_t res_frame(uint32_t seq)
{
    return pft_test_res16_frame(g_res, W, H, seq, 1000u * seq);
}

static void test_config_and_workspace(void)
{
    pft_pre_clutter_config_t cfg;
    pft_pre_clutter_config_default(&cfg);
    const char *field = "x";
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_config_check(&cfg, &field));
    TEST_ASSERT_NULL(field);
    TEST_ASSERT_EQUAL_UINT16(6554u, cfg.alpha);
    TEST_ASSERT_EQUAL_UINT16(2048u, cfg.thr);
    TEST_ASSERT_EQUAL_UINT8(1u, cfg.blur);
    TEST_ASSERT_TRUE(cfg.box);
    TEST_ASSERT_FALSE(cfg.mean);
    TEST_ASSERT_EQUAL_UINT16(0u, cfg.veto);
    TEST_ASSERT_EQUAL_UINT8(0u, cfg.persist);
    TEST_ASSERT_EQUAL_UINT16(384u, cfg.excess);
    {
        pft_pre_clutter_config_t e = cfg; /* excess is not read without persist */
        e.excess = 0u;
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_config_check(&e, &field));
    }
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_pre_clutter_config_check(NULL, &field));
    static const struct {
        const char *name;
        int which;
    } bad[] = {{"width", 0}, {"height", 1}, {"alpha", 2}, {"blur", 3}, {"thr", 4}, {"veto", 6}, {"width", 5},
               {"persist", 7}, {"excess", 8}, {"excess", 9}, {"persist", 10}};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
        pft_pre_clutter_config_t b = cfg;
        switch (bad[i].which) {
        case 0: b.width = 7u; break;
        case 1: b.height = 7u; break;
        case 2: b.alpha = 0u; break;
        case 3: b.blur = (uint8_t)(PFT_PRE_CLUTTER_MAX_BLUR + 1u); break;
        case 4: b.thr = 1023u; break;
        case 6: b.veto = (uint16_t)(b.thr - 1u); break;
        case 7: b.mean = true; b.persist = (uint8_t)(PFT_PRE_CLUTTER_MAX_PERSIST + 1u); break;
        case 8: b.mean = true; b.persist = 4u; b.excess = 0u; break;
        case 9: b.mean = true; b.persist = 4u; b.excess = 32768u; break;
        case 10: b.persist = 4u; break; /* the gate is the mean's: refused without it */
        default: b.width = (uint16_t)(PFT_CFG_MAX_IMAGE_SIDE + 1u); break;
        }
        TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_pre_clutter_config_check(&b, &field));
        TEST_ASSERT_EQUAL_STRING(bad[i].name, field);
        TEST_ASSERT_EQUAL_UINT32((uint32_t)(0u), (uint32_t)pft_pre_clutter_workspace_size(&b));
        pft_pre_clutter_t c;
        TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_pre_clutter_init(&c, &b, g_work, sizeof g_work));
    }
    cfg.width = W;
    cfg.height = H;
    TEST_ASSERT_EQUAL_UINT32((uint32_t)(PFT_PRE_CLUTTER_WORKSPACE_BYTES(W, H, 0, 1, 0)), (uint32_t)pft_pre_clutter_workspace_size(&cfg));
    cfg.mean = true;
    cfg.blur = 3u;
    TEST_ASSERT_EQUAL_UINT32((uint32_t)(PFT_PRE_CLUTTER_WORKSPACE_BYTES(W, H, 1, 3, 0)), (uint32_t)pft_pre_clutter_workspace_size(&cfg));
    cfg.persist = 4u;
    TEST_ASSERT_EQUAL_UINT32((uint32_t)(PFT_PRE_CLUTTER_WORKSPACE_BYTES(W, H, 1, 3, 1)), (uint32_t)pft_pre_clutter_workspace_size(&cfg));
    TEST_ASSERT_EQUAL_UINT32((uint32_t)(PFT_PRE_CLUTTER_WORKSPACE_BYTES(W, H, 1, 3, 0) + (size_t)W * H * 2u), (uint32_t)pft_pre_clutter_workspace_size(&cfg));
    pft_pre_clutter_t c;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_NOMEM, pft_pre_clutter_init(&c, &cfg, g_work,
                                                              pft_pre_clutter_workspace_size(&cfg) - 8u));
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_init(&c, &cfg, g_work,
                                                       pft_pre_clutter_workspace_size(&cfg)));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_pre_clutter_init(NULL, &cfg, g_work, sizeof g_work));
    pft_frame_t o;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_STATE, pft_pre_clutter_frame(&c, &o));
    TEST_ASSERT_EQUAL_UINT32(1024u, pft_pre_clutter_at(&c, 3u, 4u));
    TEST_ASSERT_EQUAL_UINT32(0u, pft_pre_clutter_at(&c, W, 4u));
}

static void test_refused_input_changes_nothing(void)
{
    pft_pre_clutter_config_t cfg;
    pft_pre_clutter_config_default(&cfg);
    cfg.mean = true;
    cfg.persist = 3u; /* every buffer of the workspace in use */
    pft_pre_clutter_t c;
    pft_test_clutter_init(&c, &cfg, W, H, g_work, sizeof g_work);
    for (uint32_t k = 0; k < 5u; ++k) {
        for (int i = 0; i < NPIX; ++i) {
            g_res[i] = noise_q88();
        }
        g_res[10 * W + 10] = 1024;
        pft_frame_t f = res_frame(k + 1u);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_update(&c, &f, 19661, -6554, true));
    }
    pft_pre_clutter_t saved = c;
    memcpy(g_copy, g_work, sizeof g_work);
    pft_frame_t f = res_frame(9u);
    pft_frame_t b = f;
    b.format = PFT_PIX_U16;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_FORMAT, pft_pre_clutter_update(&c, &b, 0, 0, true));
    b = f;
    b.width = W - 1;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_FORMAT, pft_pre_clutter_update(&c, &b, 0, 0, true));
    b = f;
    b.height = H + 1;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_FORMAT, pft_pre_clutter_update(&c, &b, 0, 0, true));
    b = f;
    b.stride_bytes = 2u * W - 2u;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_FORMAT, pft_pre_clutter_update(&c, &b, 0, 0, true));
    b = f;
    b.stride_bytes = 2u * W + 1u;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_FORMAT, pft_pre_clutter_update(&c, &b, 0, 0, true));
    b = f;
    b.data = NULL;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_pre_clutter_update(&c, &b, 0, 0, true));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_pre_clutter_update(&c, NULL, 0, 0, true));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_pre_clutter_raise(&c, W, 0u, 16384u));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_pre_clutter_raise(&c, 0u, H, 16384u));
    TEST_ASSERT_EQUAL_MEMORY(&saved, &c, sizeof c);
    TEST_ASSERT_EQUAL_MEMORY(g_copy, g_work, sizeof g_work);
    /* reset is init */
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_reset(&c));
    saved = c;
    memcpy(g_copy, g_work, sizeof g_work);
    pft_pre_clutter_t c2;
    memset(g_work, 0xA5, sizeof g_work);
    pft_test_clutter_init(&c2, &cfg, W, H, g_work, sizeof g_work);
    TEST_ASSERT_EQUAL_MEMORY(&saved, &c2, sizeof c2);
    TEST_ASSERT_EQUAL_MEMORY(g_copy, g_work, pft_pre_clutter_workspace_size(&c2.cfg) - (PFT_WS_ALIGN - 1u));
}

/* Twelve all-zero residual frames (seq 1..12): the map settles at 0 everywhere. */
static void settle_on_zero(pft_pre_clutter_t *c)
{
    memset(g_res, 0, sizeof g_res);
    for (uint32_t k = 0; k < 12u; ++k) {
        pft_frame_t f = res_frame(k + 1u);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_update(c, &f, 0, 0, true));
    }
}

/* Frame k (seq 100 + k) of a 4 sigma 3 x 3 blob at (bx, by) on the zero residual; returns the
 * map value the default alpha 0.1 learns there after it, 16 (1 - 0.9^k) sigma^2. */
static double blob_frame(pft_pre_clutter_t *c, int k, int bx, int by)
{
    for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
            g_res[(by + dy) * W + bx + dx] = 1024; /* 4 sigma */
        }
    }
    pft_frame_t f = res_frame(100u + (uint32_t)k);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_update(c, &f, 0, 0, true));
    double pw = 1.0;
    for (int i = 0; i < k; ++i) {
        pw *= 0.9;
    }
    return 16.0 * (1.0 - pw);
}

/* A 3 x 3 blob of 4 sigma at a fixed place of a still scene, after 12 zero frames: its centre's
 * map follows m_k = 16 (1 - 0.9^k) (alpha 0.1; the 1/n weight of the start is below 0.1 by
 * then) and its output is 4 sigma while the map read before the frame is <= 2, then
 * 4 / sqrt(m_{k-1}). */
static void test_persistent_blob_learnt_at_rate(void)
{
    pft_pre_clutter_config_t cfg;
    pft_pre_clutter_config_default(&cfg);
    pft_pre_clutter_t c;
    pft_test_clutter_init(&c, &cfg, W, H, g_work, sizeof g_work);
    settle_on_zero(&c);
    TEST_ASSERT_EQUAL_UINT32(0u, pft_pre_clutter_at(&c, 20u, 20u));
    const int bx = 20, by = 20;
    double m_prev = 0.0;
    for (int k = 1; k <= 40; ++k) {
        const double m = blob_frame(&c, k, bx, by);
        const double got = pft_pre_clutter_at(&c, bx, by) / 1024.0;
        TEST_ASSERT_DOUBLE_WITHIN(0.01 * m + 0.01, m, got);
        const double want = m_prev > 2.0 ? 4.0 / sqrt(m_prev) : 4.0;
        const double out = pft_test_clutter_out(&c)[by * W + bx] / 256.0;
        TEST_ASSERT_DOUBLE_WITHIN(0.01 * want + 0.01, want, out);
        m_prev = m;
    }
    /* after 40 frames the blob is scored near its own sigma (4 / sqrt(15.8) = 1.01) */
    TEST_ASSERT_TRUE(pft_test_clutter_out(&c)[by * W + bx] < 270);
    /* far from it, the zero residual stays zero */
    TEST_ASSERT_EQUAL_INT16(0, pft_test_clutter_out(&c)[5 * W + 50]);
}

/* The veto (8 sigma^2): the 4 sigma blob of the test above, learnt at the same rate, comes
 * out as 4 / sqrt(m_{k-1}) while the map read is at most 8 and as 0 from the frame after the
 * one where m_{k-1} > 8 (k >= 8: 16 (1 - 0.9^7) = 8.35); the zero residual elsewhere stays 0. */
static void test_veto_zeroes_learnt_clutter(void)
{
    pft_pre_clutter_config_t cfg;
    pft_pre_clutter_config_default(&cfg);
    cfg.veto = 8192u;
    pft_pre_clutter_t c;
    pft_test_clutter_init(&c, &cfg, W, H, g_work, sizeof g_work);
    settle_on_zero(&c);
    const int bx = 20, by = 20;
    double m_prev = 0.0;
    uint32_t vetoed = 0u;
    for (int k = 1; k <= 20; ++k) {
        const double m = blob_frame(&c, k, bx, by);
        const double out = pft_test_clutter_out(&c)[by * W + bx] / 256.0;
        if (m_prev > 8.05) {
            TEST_ASSERT_EQUAL_INT16(0, pft_test_clutter_out(&c)[by * W + bx]);
            ++vetoed;
        } else if (m_prev < 7.95) {
            const double want = m_prev > 2.0 ? 4.0 / sqrt(m_prev) : 4.0;
            TEST_ASSERT_DOUBLE_WITHIN(0.01 * want + 0.01, want, out);
        } else {
            /* within the rounding of the threshold: either answer */
        }
        TEST_ASSERT_EQUAL_INT16(0, pft_test_clutter_out(&c)[5 * W + 5]);
        m_prev = m;
    }
    TEST_ASSERT_EQUAL_UINT32(13u, vetoed); /* k = 8 .. 20 */
}

/* Unit noise and a point of 4 sigma moving 1 px per frame along a row: after the start (20
 * frames) the map stays near 1 (below thr 2 read as a 3 x 3 mean): the point, read over a
 * square that holds its trail's last pixel, and the noise away from the trail's rows come out
 * bit for bit as they went in. */
static void test_moving_point_keeps_snr(void)
{
    pft_pre_clutter_config_t cfg;
    pft_pre_clutter_config_default(&cfg);
    pft_pre_clutter_t c;
    pft_test_clutter_init(&c, &cfg, W, H, g_work, sizeof g_work);
    uint32_t changed = 0u;
    for (uint32_t k = 0; k < 40u; ++k) {
        for (int i = 0; i < NPIX; ++i) {
            g_res[i] = noise_q88();
        }
        const int px = 10 + (int)k, py = 24;
        g_res[py * W + px] = (int16_t)(g_res[py * W + px] + 1024);
        const int16_t in = g_res[py * W + px];
        pft_frame_t f = res_frame(k + 1u);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_update(&c, &f, 0, 0, true));
        if (k < 20u) { /* the start: a running mean of few frames, noisy */
            continue;
        }
        const int16_t *o = pft_test_clutter_out(&c);
        TEST_ASSERT_EQUAL_INT16(in, o[py * W + px]);
        for (int i = 0; i < NPIX; ++i) {
            /* the trail's rows excepted: its raised map reaches the noise next to it */
            const int y = i / W;
            changed += (y < py - 1 || y > py + 1) && o[i] != g_res[i] ? 1u : 0u;
        }
    }
    TEST_ASSERT_EQUAL_UINT32(0u, changed);
    /* the noise's map is about 1 (mean square of unit noise) */
    uint64_t s = 0u;
    for (uint32_t y = 30u; y < 40u; ++y) {
        for (uint32_t x = 0u; x < W; ++x) {
            s += pft_pre_clutter_at(&c, x, y);
        }
    }
    TEST_ASSERT_DOUBLE_WITHIN(0.1, 1.0, (double)s / (10.0 * W) / 1024.0);
}

/* With mean: a persistent offset of +3 sigma on unit noise is learnt and removed (output mean
 * near 0 after 60 frames), the noise elsewhere passes unchanged in distribution. With the mean's
 * floor (mean_floor, Q8.8 sigma) the same: the floor's share of a converged mean is none once
 * |mu| exceeds it, and the tolerance covers the mean's noise at alpha 0.1. */
static void mean_removes_offset_(uint16_t floor)
{
    pft_pre_clutter_config_t cfg;
    pft_pre_clutter_config_default(&cfg);
    cfg.mean = true;
    cfg.mean_floor = floor;
    pft_pre_clutter_t c;
    pft_test_clutter_init(&c, &cfg, W, H, g_work, sizeof g_work);
    double sum = 0.0;
    int n = 0;
    for (uint32_t k = 0; k < 60u; ++k) {
        for (int i = 0; i < NPIX; ++i) {
            g_res[i] = noise_q88();
        }
        for (int y = 10; y < 20; ++y) {
            for (int x = 30; x < 34; ++x) {
                g_res[y * W + x] = (int16_t)(g_res[y * W + x] + 768);
            }
        }
        pft_frame_t f = res_frame(k + 1u);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_update(&c, &f, 0, 0, true));
        if (k >= 40u) {
            const int16_t *o = pft_test_clutter_out(&c);
            for (int y = 11; y < 19; ++y) {
                for (int x = 31; x < 33; ++x) {
                    sum += o[y * W + x] / 256.0;
                    ++n;
                }
            }
        }
    }
    TEST_ASSERT_DOUBLE_WITHIN(0.25, 0.0, sum / n);
}

static void test_mean_removes_offset(void)
{
    mean_removes_offset_(0u);
}

/* The same with the floor at 1 sigma (docs/algorithms.md 9.9, mean_floor). */
static void test_mean_removes_offset_with_floor(void)
{
    mean_removes_offset_(256u);
}

/* The map moves with the scene: a learnt blob, then frames of zero residual with the scene
 * shifted by (+2, -1) px (integer) and then +0.5 px along x. */
static void test_map_moves_with_scene(void)
{
    pft_pre_clutter_config_t cfg;
    pft_pre_clutter_config_default(&cfg);
    cfg.alpha = 6554u;
    pft_pre_clutter_t c;
    pft_test_clutter_init(&c, &cfg, W, H, g_work, sizeof g_work);
    memset(g_res, 0, sizeof g_res);
    for (uint32_t k = 0; k < 12u; ++k) {
        g_res[20 * W + 20] = (k >= 2u) ? 1024 : 0;
        pft_frame_t f = res_frame(k + 1u);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_update(&c, &f, 0, 0, true));
    }
    const uint32_t m0 = pft_pre_clutter_at(&c, 20u, 20u);
    TEST_ASSERT_TRUE(m0 > 8000u);
    memset(g_res, 0, sizeof g_res);
    pft_frame_t f = res_frame(50u);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_update(&c, &f, 2 * 65536, -65536, true));
    /* warped to (22, 19), then updated with a zero residual: m0 (1 - 0.1) */
    const uint32_t m1 = pft_pre_clutter_at(&c, 22u, 19u);
    TEST_ASSERT_UINT32_WITHIN(2u, (m0 * 9u + 5u) / 10u, m1);
    TEST_ASSERT_TRUE(pft_pre_clutter_at(&c, 20u, 20u) < 100u);
    const uint32_t e0 = pft_pre_clutter_at(&c, 0u, 30u);
    f = res_frame(51u);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_update(&c, &f, 32768, 0, true));
    /* half a pixel: shared by (22, 19) and (23, 19), each m1 / 2 then (1 - 0.1) */
    const uint32_t half = (m1 + 1u) / 2u * 9u / 10u;
    TEST_ASSERT_UINT32_WITHIN(3u, half, pft_pre_clutter_at(&c, 22u, 19u));
    TEST_ASSERT_UINT32_WITHIN(3u, half, pft_pre_clutter_at(&c, 23u, 19u));
    /* column 0: half of it entered the frame with the shift, at 1 sigma^2 */
    TEST_ASSERT_UINT32_WITHIN(3u, (e0 + 1024u + 1u) / 2u * 9u / 10u, pft_pre_clutter_at(&c, 0u, 30u));
}

/* The persistence gate (persist 4, excess 1.5 sigma) with the running mean (alpha 0.1, thr at
 * its largest so that the output is r - mu exactly), after the settle on zero, 30 frames of a
 * zero residual holding a 3 x 3 blob of 3 sigma that stays put in the scene and a point of
 * 3 sigma that moves against it: (a) a still scene, the point moving 1 px every second frame
 * (0.5 px per frame); (b) the scene moving +1 px per frame in x (shift 65536), the blob with
 * it, the point fixed in the image (1 px per frame against the scene). Known answers: the
 * point comes out as it went in, bit for bit, in every frame (its map and mean are never
 * taken: no pixel of the scene holds it for 4 frames); the blob's centre comes out at 3 sigma
 * until its 4th frame, then 3 (0.9)^(k - 4): learnt from the frame its counter reaches 4.
 * Without the gate (persist 0) the point is learnt from its second frame at a pixel (case a)
 * and the blob from its first frame (both checked to fail then). */
static void test_persistence_gate_learns_what_stays_put(void)
{
    for (int cs = 0; cs < 2; ++cs) {
        pft_pre_clutter_config_t cfg;
        pft_pre_clutter_config_default(&cfg);
        cfg.mean = true;
        cfg.thr = 65535u;
        cfg.persist = 4u;
        pft_pre_clutter_t c;
        pft_test_clutter_init(&c, &cfg, W, H, g_work, sizeof g_work);
        settle_on_zero(&c);
        const int32_t sx = cs == 0 ? 0 : 65536;
        uint32_t point_same = 0u;
        for (int k = 1; k <= 30; ++k) {
            memset(g_res, 0, sizeof g_res);
            const int bx = 10 + (cs == 0 ? 0 : k), by = 12;
            for (int dy = -1; dy <= 1; ++dy) {
                for (int dx = -1; dx <= 1; ++dx) {
                    g_res[(by + dy) * W + bx + dx] = 768; /* 3 sigma */
                }
            }
            const int px = cs == 0 ? 20 + k / 2 : 40, py = 32;
            g_res[py * W + px] = 768;
            pft_frame_t f = res_frame(100u + (uint32_t)k);
            TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_update(&c, &f, sx, 0, true));
            const int16_t *o = pft_test_clutter_out(&c);
            point_same += o[py * W + px] == 768 ? 1u : 0u;
            double want = 3.0;
            for (int i = 4; i < k; ++i) {
                want *= 0.9;
            }
            TEST_ASSERT_DOUBLE_WITHIN(0.01 * want + 0.01, want, o[by * W + bx] / 256.0);
        }
        TEST_ASSERT_EQUAL_UINT32(30u, point_same);
        /* where the point has been, the mean is still 0: nothing of it was learnt */
        TEST_ASSERT_EQUAL_UINT16(32768u, c.mu[32 * W + (cs == 0 ? 25 : 40)]);
    }
}

/* A frame without evidence: all masked out, map unchanged; masked input pixels pass masked and
 * keep their map; raise sets a 3 x 3 floor. */
static void test_no_evidence_masked_and_raise(void)
{
    pft_pre_clutter_config_t cfg;
    pft_pre_clutter_config_default(&cfg);
    pft_pre_clutter_t c;
    pft_test_clutter_init(&c, &cfg, W, H, g_work, sizeof g_work);
    for (int i = 0; i < NPIX; ++i) {
        g_res[i] = noise_q88();
    }
    pft_frame_t f = res_frame(1u);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_update(&c, &f, 0, 0, true));
    memcpy(g_copy, g_work, sizeof g_work);
    const uint16_t *m = c.m;
    uint16_t before = m[5 * W + 5];
    f = res_frame(2u);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_update(&c, &f, 65536, 0, false));
    const int16_t *o = pft_test_clutter_out(&c);
    for (int i = 0; i < NPIX; ++i) {
        TEST_ASSERT_EQUAL_INT16(PFT_RES16_MASKED, o[i]);
    }
    TEST_ASSERT_EQUAL_MEMORY(g_copy, c.m, (size_t)NPIX * 2u);
    TEST_ASSERT_EQUAL_UINT16(before, m[5 * W + 5]);
    g_res[5 * W + 5] = PFT_RES16_MASKED;
    f = res_frame(3u);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_update(&c, &f, 0, 0, true));
    TEST_ASSERT_EQUAL_INT16(PFT_RES16_MASKED, pft_test_clutter_out(&c)[5 * W + 5]);
    TEST_ASSERT_EQUAL_UINT16(before, m[5 * W + 5]);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_raise(&c, 0u, 0u, 16384u));
    TEST_ASSERT_EQUAL_UINT32(16384u, pft_pre_clutter_at(&c, 1u, 1u));
    TEST_ASSERT_TRUE(pft_pre_clutter_at(&c, 2u, 2u) < 16384u);
    /* the next frame at (0, 0) is read over its 3 x 3 (replicated edge): scored at
     * r / sqrt(M) with M about 16 */
    g_res[0] = 1024;
    g_res[5 * W + 5] = 0;
    f = res_frame(4u);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_update(&c, &f, 0, 0, true));
    TEST_ASSERT_INT16_WITHIN(10, 256, pft_test_clutter_out(&c)[0]);
}

/* Reference of one update without the running mean, written from docs/algorithms.md 9.9 with
 * plain loops: the square's sum over the former map with the edges replicated, the output
 * r / sqrt(mean) where the sum exceeds thr times the area, the map moved towards the square of
 * the residual by a rounded a (t - m). */
static uint32_t ref_isqrt(uint64_t v)
{
    uint64_t r = 0u;
    while ((r + 1u) * (r + 1u) <= v) {
        r += 1u;
    }
    return (uint32_t)r;
}

static int32_t ref_div(int32_t n, int32_t d)
{
    const int32_t q = ((n < 0 ? -n : n) + d / 2) / d;
    return n < 0 ? -q : q;
}

static uint16_t g_m0[NPIX];

static void test_row_passes_match_reference(void)
{
    static const uint8_t blurs[3] = {0u, 2u, PFT_PRE_CLUTTER_MAX_BLUR};
    for (uint32_t bi = 0u; bi < 3u; ++bi) {
        pft_pre_clutter_config_t cfg;
        pft_pre_clutter_config_default(&cfg);
        cfg.blur = blurs[bi];
        pft_pre_clutter_t c;
        pft_test_clutter_init(&c, &cfg, W, H, g_work, sizeof g_work);
        for (int i = 0; i < NPIX; ++i) {
            g_res[i] = noise_q88();
        }
        pft_frame_t f = res_frame(1u);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_update(&c, &f, 0, 0, true));
        /* clutter at the corners, on the edges and inside */
        static const uint32_t px[7][2] = {{0u, 0u},  {W - 1u, H - 1u}, {W - 1u, 0u}, {20u, 0u},
                                          {0u, 30u}, {30u, 20u},       {W - 2u, 25u}};
        for (uint32_t k = 0u; k < 7u; ++k) {
            TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_raise(&c, px[k][0], px[k][1], 30000u));
        }
        memcpy(g_m0, c.m, sizeof g_m0);
        for (int i = 0; i < NPIX; ++i) {
            g_res[i] = (int16_t)(((i * 7919) % 8001) - 4000); /* -4000 .. 4000: up to 15.6 sigma */
        }
        g_res[3 * W + 1] = PFT_RES16_MASKED;
        g_res[0] = PFT_RES16_MASKED + 1; /* the most negative residual */
        f = res_frame(2u);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_update(&c, &f, 0, 0, true));
        const int16_t *o = pft_test_clutter_out(&c);
        const int32_t b = (int32_t)cfg.blur;
        const uint32_t area = (uint32_t)((2 * b + 1) * (2 * b + 1));
        const uint32_t a = 32768u; /* max(alpha, 1/2) at the second frame */
        uint32_t n_scored = 0u;
        for (int32_t y = 0; y < H; ++y) {
            for (int32_t x = 0; x < W; ++x) {
                uint32_t sum = 0u;
                for (int32_t dy = -b; dy <= b; ++dy) {
                    for (int32_t dx = -b; dx <= b; ++dx) {
                        const int32_t yy = y + dy < 0 ? 0 : (y + dy >= H ? H - 1 : y + dy);
                        const int32_t xx = x + dx < 0 ? 0 : (x + dx >= W ? W - 1 : x + dx);
                        sum += g_m0[yy * W + xx];
                    }
                }
                const int32_t v = g_res[y * W + x];
                const uint16_t m0 = g_m0[y * W + x];
                if (v == PFT_RES16_MASKED) {
                    TEST_ASSERT_EQUAL_INT16(PFT_RES16_MASKED, o[y * W + x]);
                    TEST_ASSERT_EQUAL_UINT16(m0, c.m[y * W + x]);
                    continue;
                }
                int32_t want = v;
                if (sum > 2048u * area) {
                    const uint32_t mm = (sum + area / 2u) / area;
                    want = ref_div(v * 1024, (int32_t)ref_isqrt((uint64_t)mm << 10));
                    ++n_scored;
                }
                TEST_ASSERT_EQUAL_INT16((int16_t)want, o[y * W + x]);
                const int64_t sq = (int64_t)v * v;
                const int64_t t = (sq + 32) / 64 > 65535 ? 65535 : (sq + 32) / 64;
                const int64_t d = t - (int64_t)m0;
                const int64_t q = ((int64_t)a * (d < 0 ? -d : d) + 32768) / 65536;
                TEST_ASSERT_EQUAL_UINT16((uint16_t)(m0 + (d < 0 ? -q : q)), c.m[y * W + x]);
            }
        }
        TEST_ASSERT_TRUE(n_scored > 7u); /* the clutter squares were scored */
    }
}

/* Known answers of the running mean with and without the persistence gate (mean, persist;
 * docs/algorithms.md 9.9), every pixel of every frame against a reference written from the
 * formulas: thr at its largest, so that the output is clamp(c, +-32767), c = r - mu (mu read
 * before the frame, Q8.8 rounded half away from zero); m <- m + a (min(c^2, 64) - m) and mu <-
 * mu + a (clamp(r, -8, 8) - mu), products rounded half away from zero, a = max(alpha, 1/n) (the
 * first frame: a = 1, m = t and mu = the target); with the gate p <- min(p + 1, 2k) where |r| >
 * excess, else max(p - 1/2, 0), and mu learns where |r| <= excess or p >= k; a masked pixel
 * changes nothing. Residuals: unit noise, a 4 sigma blob that stays (its counter reaches the
 * cap), values at and just over excess, near the mean's clamp (8 sigma), large ones (31 sigma
 * and 32767, whose c and t clamp) and masked pixels. Persist 0 and 2; frames 1 (a = 1) to 12. */
static uint16_t g_mu0[NPIX], g_p0[NPIX];

static int64_t ref_step(int64_t x, int64_t target, uint32_t a)
{
    if (a >= 65536u) {
        return target;
    }
    const int64_t d = target - x;
    const int64_t q = ((int64_t)a * (d < 0 ? -d : d) + 32768) / 65536;
    return x + (d < 0 ? -q : q);
}

/* One case of the known answers below: frames w x H (w <= W), the gate's persist, the mean's
 * floor mfl (mean_floor, Q8.8 sigma; 0: off; floor_age 0, so it applies to every cell: c = r - mu
 * where |mu| > mfl, else c = r). */
static void gated_mean_case(int w, uint8_t persist, uint16_t mfl)
{
    pft_pre_clutter_config_t cfg;
    pft_pre_clutter_config_default(&cfg);
    cfg.mean = true;
    cfg.thr = 65535u; /* nothing scored: the output is clamp(c) */
    cfg.alpha = 13107u;
    cfg.persist = persist;
    cfg.mean_floor = mfl;
    pft_pre_clutter_t c;
    pft_test_clutter_init(&c, &cfg, (uint16_t)w, H, g_work, sizeof g_work);
    /* the same with scoring (thr 1 sigma^2): a masked pixel must stay masked where its read
     * exceeds thr (the mean pass marks it for the scoring pass) */
    pft_pre_clutter_config_t cfg2 = cfg;
    cfg2.thr = 1024u;
    pft_pre_clutter_t c2;
    pft_test_clutter_init(&c2, &cfg2, (uint16_t)w, H, g_copy, sizeof g_copy);
    uint32_t n_scored = 0u;
    const int32_t pk = (int32_t)cfg.persist * 256, exc = (int32_t)cfg.excess;
    uint32_t n_cap = 0u, n_held = 0u, n_tclamp = 0u, n_big1 = 0u, n_big = 0u, n_mask = 0u;
    uint32_t n_floor = 0u, n_over = 0u;
    for (uint32_t k = 0u; k < 12u; ++k) {
        const int32_t sg = (k & 1u) != 0u ? -1 : 1;
        for (int i = 0; i < w * H; ++i) {
            int32_t v = noise_q88();
            if (i % 101 == 0) {
                v = PFT_RES16_MASKED;
            } else if (i % 97 == 0) {
                v = (k & 1u) == 0u ? 8000 + 3 * (int32_t)k : 0; /* m swings by 2^15 and more */
            } else if (i % 89 == 0) {
                v = sg * 32767;
            } else if (i % 83 == 0) {
                v = sg * (exc + (int32_t)(k & 1u));
            } else if (i % 79 == 0) {
                v = -sg * (2047 + (int32_t)(k % 3u));
            } else if ((i / w) >= 10 && (i / w) < 13 && (i % w) >= 10 && (i % w) < 13) {
                v += 1024; /* the blob: 4 sigma, over excess every frame */
            }
            g_res[i] = (int16_t)v;
        }
        memcpy(g_m0, c.m, sizeof g_m0);
        memcpy(g_mu0, c.mu, sizeof g_mu0);
        if (c.pc != NULL) {
            memcpy(g_p0, c.pc, sizeof g_p0);
        }
        pft_frame_t f = pft_test_res16_frame(g_res, (uint16_t)w, H, k + 1u, 1000u * (k + 1u));
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_update(&c, &f, 0, 0, true));
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_update(&c2, &f, 0, 0, true));
        const int16_t *o = pft_test_clutter_out(&c);
        const int16_t *o2 = pft_test_clutter_out(&c2);
        const uint32_t n = k + 1u, a1 = (65536u + n / 2u) / n;
        const uint32_t a = a1 > cfg.alpha ? a1 : cfg.alpha;
        for (int i = 0; i < w * H; ++i) {
            const int32_t v = g_res[i];
            if (v == PFT_RES16_MASKED) {
                ++n_mask;
                TEST_ASSERT_EQUAL_INT16(PFT_RES16_MASKED, o[i]);
                TEST_ASSERT_EQUAL_INT16(PFT_RES16_MASKED, o2[i]);
                TEST_ASSERT_EQUAL_UINT16(g_m0[i], c.m[i]);
                TEST_ASSERT_EQUAL_UINT16(g_mu0[i], c.mu[i]);
                if (c.pc != NULL) {
                    TEST_ASSERT_EQUAL_UINT16(g_p0[i], c.pc[i]);
                }
                continue;
            }
            const int32_t muq = pft_test_clutter_mu_q88(g_mu0[i]);
            const int32_t cv = v - ((muq < 0 ? -muq : muq) > (int32_t)mfl ? muq : 0);
            n_floor += muq != 0 && (muq < 0 ? -muq : muq) <= (int32_t)mfl ? 1u : 0u;
            n_over += (muq < 0 ? -muq : muq) > (int32_t)mfl ? 1u : 0u;
            TEST_ASSERT_EQUAL_INT16((int16_t)(cv > 32767 ? 32767 : (cv < -32767 ? -32767 : cv)), o[i]);
            n_scored += o2[i] != o[i] ? 1u : 0u;
            const int64_t sq = (int64_t)cv * cv;
            const int64_t t = (sq + 32) / 64 > 65535 ? 65535 : (sq + 32) / 64;
            n_tclamp += t == 65535 ? 1u : 0u;
            const bool big = t - (int64_t)g_m0[i] >= 32768 || (int64_t)g_m0[i] - t >= 32768;
            n_big1 += big && k == 0u ? 1u : 0u;
            n_big += big && k > 0u ? 1u : 0u;
            TEST_ASSERT_EQUAL_UINT16((uint16_t)ref_step(g_m0[i], t, a), c.m[i]);
            bool learn = true;
            if (c.pc != NULL) {
                const int32_t p0 = g_p0[i];
                const bool ex = (v < 0 ? -v : v) > exc;
                const int32_t p1 = ex ? (p0 + 256 > 2 * pk ? 2 * pk : p0 + 256) : (p0 > 128 ? p0 - 128 : 0);
                TEST_ASSERT_EQUAL_UINT16((uint16_t)p1, c.pc[i]);
                n_cap += p1 == 2 * pk ? 1u : 0u;
                learn = !ex || p1 >= pk;
            }
            const int32_t mv0 = (int32_t)g_mu0[i] - 32768;
            const int32_t tv = 8 * (v > 2048 ? 2048 : (v < -2048 ? -2048 : v));
            const int64_t mv = learn ? ref_step(mv0, tv, a) : mv0;
            n_held += learn ? 0u : 1u;
            TEST_ASSERT_EQUAL_UINT16((uint16_t)(mv + 32768), c.mu[i]);
        }
    }
    /* the cases were met: masked pixels, the t clamp, steps of m of 2^15 or more (on the
     * first frame and after), and with the gate the counter's cap and a held mean */
    TEST_ASSERT_TRUE(n_mask > 0u);
    TEST_ASSERT_TRUE(n_scored > 0u);
    TEST_ASSERT_TRUE(n_over > 0u);
    TEST_ASSERT_TRUE(mfl == 0u || n_floor > 0u);
    TEST_ASSERT_TRUE(n_tclamp > 0u);
    TEST_ASSERT_TRUE(n_big1 > (uint32_t)(w * H) / 100u); /* 30 at W x H */
    TEST_ASSERT_TRUE(n_big > (uint32_t)(w * H) / 100u);
    if (cfg.persist != 0u) {
        TEST_ASSERT_TRUE(n_cap >= 9u * 8u);
        TEST_ASSERT_TRUE(n_held > 0u);
    }
}

static void test_gated_mean_matches_reference(void)
{
    gated_mean_case(W, 0u, 0u);
    gated_mean_case(W, 2u, 0u);
}

/* The same known answers at widths that leave columns over a vector's 8 (AArch64's NEON form
 * of the mean pass, pre_clutter.c CL_NEON_, and x86-64's SSE2 form, CL_SSE2_'s cl_mean8_sse2_,
 * take whole blocks of 8 columns and the per-pixel form the rest; the Cortex-M targets run one
 * form) and with the mean's floor (1 sigma, and 1/16 sigma so that most of the learnt means
 * pass it). */
static void test_gated_mean_widths_and_floor(void)
{
    gated_mean_case(61, 2u, 256u);
    gated_mean_case(59, 0u, 16u);
    gated_mean_case(13, 2u, 0u);
}


/* Known answers of the warp (a shift with evidence; docs/algorithms.md 9.9): every residual
 * masked, so that the update keeps the warped map, mean and counter; each plane filled with
 * pseudo-random values over the whole 16-bit range before the shift, then compared on every
 * cell with the bilinear formula out(x, y) = (sum of v(x - ix - i, y - iy - j) wx_i wy_j +
 * 2^15) >> 16 (i, j in 0..1, weights 256 - f and f in Q8, a source outside the frame counting
 * the plane's fill: 1 sigma^2 for m, the offset 2^15 for mu, 0 for the counter). Shifts in
 * whole Q8 steps (the split exact) with fx 0, fy 0, both fractional, both signs, sources
 * beyond every edge and a source row that is the output row itself (iy 0 and -1), the last
 * shift with values only 0, 2^15 - 1, 2^15 and 65535; widths 64 and 61 (columns over a
 * multiple of 8). The x86-64 build runs the one-pass SSE2 form of pre_clutter.c (pmaddwd), the
 * other targets its two-pass 32-bit form. */
static uint16_t ref_warp_at(const uint16_t *v, int w, int x, int y, int32_t ix, uint32_t fx, int32_t iy,
                            uint32_t fy, uint32_t b)
{
    uint64_t sum = 0u;
    for (int32_t j = 0; j < 2; ++j) {
        for (int32_t i = 0; i < 2; ++i) {
            const int32_t sx = x - ix - i, sy = y - iy - j;
            const uint64_t val = sx >= 0 && sx < w && sy >= 0 && sy < H ? v[sy * w + sx] : b;
            const uint64_t wx = i != 0 ? fx : 256u - fx, wy = j != 0 ? fy : 256u - fy;
            sum += val * wx * wy;
        }
    }
    return (uint16_t)((sum + 32768u) >> 16);
}

static void warp_case(int w)
{
    /* shifts in Q8 px (x, y): the Q16.16 shift is 256 times them */
    static const int32_t sh[9][2] = {{77, -300}, {0, 133},  {-600, 0},   {517, 1018},
                                     {-1, 1},    {-4000, 2900}, {15000, -11000}, {300, -100},
                                     {-200, 77}};
    pft_pre_clutter_config_t cfg;
    pft_pre_clutter_config_default(&cfg);
    cfg.mean = true;
    cfg.persist = 2u;
    pft_pre_clutter_t c;
    pft_test_clutter_init(&c, &cfg, (uint16_t)w, H, g_work, sizeof g_work);
    for (int i = 0; i < w * H; ++i) {
        g_res[i] = PFT_RES16_MASKED;
    }
    pft_frame_t f = pft_test_res16_frame(g_res, (uint16_t)w, H, 1u, 1000u);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_update(&c, &f, 0, 0, true));
    uint32_t n_edge = 0u, n_in = 0u;
    for (uint32_t k = 0u; k < 9u; ++k) {
        uint16_t *pl[3] = {c.m, c.mu, c.pc};
        static const uint32_t fill[3] = {1024u, 32768u, 0u};
        /* the last shift: only the range's ends and the middle (sums at their largest) */
        static const uint16_t ends[4] = {0u, 32767u, 32768u, 65535u};
        for (uint32_t p = 0u; p < 3u; ++p) {
            for (int i = 0; i < w * H; ++i) {
                g_rs = g_rs * 1664525u + 1013904223u;
                pl[p][i] = k == 8u ? ends[g_rs >> 30] : (uint16_t)(g_rs >> 16);
            }
        }
        memcpy(g_m0, c.m, sizeof(uint16_t) * (size_t)(w * H));
        memcpy(g_mu0, c.mu, sizeof(uint16_t) * (size_t)(w * H));
        memcpy(g_p0, c.pc, sizeof(uint16_t) * (size_t)(w * H));
        const uint16_t *before[3] = {g_m0, g_mu0, g_p0};
        f = pft_test_res16_frame(g_res, (uint16_t)w, H, k + 2u, 1000u * (k + 2u));
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_update(&c, &f, sh[k][0] * 256, sh[k][1] * 256, true));
        /* the split: whole grid steps (floor) and the Q8 fraction */
        const int32_t ix = sh[k][0] >= 0 ? sh[k][0] / 256 : -((-sh[k][0] + 255) / 256);
        const int32_t iy = sh[k][1] >= 0 ? sh[k][1] / 256 : -((-sh[k][1] + 255) / 256);
        const uint32_t fx = (uint32_t)(sh[k][0] - ix * 256), fy = (uint32_t)(sh[k][1] - iy * 256);
        for (uint32_t p = 0u; p < 3u; ++p) {
            for (int y = 0; y < H; ++y) {
                for (int x = 0; x < w; ++x) {
                    const uint16_t want = ref_warp_at(before[p], w, x, y, ix, fx, iy, fy, fill[p]);
                    TEST_ASSERT_EQUAL_UINT16(want, pl[p][y * w + x]);
                    const bool edge = x - ix - 1 < 0 || x - ix >= w || y - iy - 1 < 0 || y - iy >= H;
                    n_edge += edge ? 1u : 0u;
                    n_in += edge ? 0u : 1u;
                }
            }
        }
    }
    TEST_ASSERT_TRUE(n_edge > 0u);
    TEST_ASSERT_TRUE(n_in > 0u);
}

static void test_warp_matches_reference(void)
{
    warp_case(W);
    warp_case(61);
}

/* floor_age's runs of columns (pre_clutter.c cl_age_run_end_: an old run passed 4 columns at a
 * time for floor_age <= 128, per column otherwise): the columns' and rows' ages set before each
 * of 10 frames to a pattern of old (floor_age, 255) and young (0, floor_age - 1) runs of 1 to
 * 31 columns, shifted each frame, a few young rows; the mean (mean_floor 1 sigma, thr at its
 * largest, no shift) on unit noise must give c = r where the cell is old (column and row) and
 * |mu| <= the floor, else c = r - mu, on every pixel. floor_age 15, 128 (the word test's
 * largest) and 200 (per column only); widths 64 and 61. */
static void floor_age_runs_case(int w, uint8_t ka)
{
    static const int32_t runs[10] = {1, 2, 3, 4, 5, 7, 8, 9, 13, 31};
    pft_pre_clutter_config_t cfg;
    pft_pre_clutter_config_default(&cfg);
    cfg.mean = true;
    cfg.thr = 65535u; /* nothing scored: the output is clamp(c) */
    cfg.alpha = 13107u;
    cfg.mean_floor = 256u;
    cfg.floor_age = ka;
    pft_pre_clutter_t c;
    pft_test_clutter_init(&c, &cfg, (uint16_t)w, H, g_work, sizeof g_work);
    uint32_t n_kept = 0u, n_off = 0u;
    for (uint32_t k = 0u; k < 10u; ++k) {
        int32_t x = 0, r = (int32_t)k;
        bool old = (k & 1u) != 0u;
        while (x < w) {
            const int32_t n = runs[r % 10];
            for (int32_t i = 0; i < n && x < w; ++i, ++x) {
                c.age[x] = old ? (i % 3 == 1 ? 255u : ka) : (i % 2 == 1 ? 0u : (uint8_t)(ka - 1u));
            }
            old = !old;
            r += 3;
        }
        for (int32_t y = 0; y < H; ++y) {
            c.age[w + y] = y % 11 == 5 ? (uint8_t)(ka - 1u) : ka;
        }
        memcpy(g_p0, c.age, (size_t)(w + H)); /* the ages this frame reads */
        const uint8_t *ages = (const uint8_t *)g_p0;
        for (int i = 0; i < w * H; ++i) {
            g_res[i] = noise_q88();
        }
        memcpy(g_mu0, c.mu, sizeof(uint16_t) * (size_t)(w * H));
        pft_frame_t f = pft_test_res16_frame(g_res, (uint16_t)w, H, k + 1u, 1000u * (k + 1u));
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_update(&c, &f, 0, 0, true));
        const int16_t *o = pft_test_clutter_out(&c);
        for (int i = 0; i < w * H; ++i) {
            const bool cold = ages[i % w] >= ka && ages[w + i / w] >= ka;
            const int32_t muq = pft_test_clutter_mu_q88(g_mu0[i]);
            const bool floor = cold && (muq < 0 ? -muq : muq) <= (int32_t)cfg.mean_floor;
            const int32_t cv = g_res[i] - (floor ? 0 : muq);
            TEST_ASSERT_EQUAL_INT16((int16_t)cv, o[i]);
            n_kept += floor && muq != 0 ? 1u : 0u;
            n_off += !cold && muq != 0 ? 1u : 0u;
        }
    }
    /* both sides met where it matters: a mean kept by the floor, a young cell's taken off */
    TEST_ASSERT_TRUE(n_kept > (uint32_t)(w * H));
    TEST_ASSERT_TRUE(n_off > (uint32_t)(w * H));
}

static void test_floor_age_runs_match_reference(void)
{
    floor_age_runs_case(W, 15u);
    floor_age_runs_case(61, 128u);
    floor_age_runs_case(W, 200u);
    floor_age_runs_case(61, 15u);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_config_and_workspace);
    RUN_TEST(test_refused_input_changes_nothing);
    RUN_TEST(test_persistent_blob_learnt_at_rate);
    RUN_TEST(test_veto_zeroes_learnt_clutter);
    RUN_TEST(test_moving_point_keeps_snr);
    RUN_TEST(test_mean_removes_offset);
    RUN_TEST(test_mean_removes_offset_with_floor);
    RUN_TEST(test_map_moves_with_scene);
    RUN_TEST(test_no_evidence_masked_and_raise);
    RUN_TEST(test_row_passes_match_reference);
    RUN_TEST(test_persistence_gate_learns_what_stays_put);
    RUN_TEST(test_gated_mean_matches_reference);
    RUN_TEST(test_gated_mean_widths_and_floor);
    RUN_TEST(test_warp_matches_reference);
    RUN_TEST(test_floor_age_runs_match_reference);
    return UNITY_END();
}
