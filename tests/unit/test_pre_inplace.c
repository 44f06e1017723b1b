/*
 * The stage with inplace set (pft_pre.h, "Memory"): the residual written over the caller's
 * frame buffer must be the residual that pft_pre_update writes into the workspace, byte for
 * byte, frame after frame, with the same statistics, peaks and tile sigmas. The frames are
 * those of the golden vectors (pre_vectors_spec.h: a drifting 14-bit scene, dead and saturated
 * pixels, a target, a jump, a constant frame), as rendered and flipped upside down (the
 * vertical drift reversed, so the temporal row pass walks the rows the other way), for the
 * temporal and the local method, whitening with this frame's or the last frame's sigma, with
 * the edge term and with a bad-pixel map. No tolerance: the stage is integer arithmetic and the
 * two paths must give the same bits. A row read after it was overwritten changes the result
 * (checked: the masked pixels of a temporal row counted by cause from the raw row after the
 * fused loop has written the residual over it gives other n_saturated counts and fails here on
 * frame 1 of case 0; the same count after the row is written in the rows without the fused
 * loop fails on frame 1 of case 4).
 */
#include "pft_test_support.h"
#include "pre_vectors_spec.h"

void setUp(void) {}
void tearDown(void) {}

#define IW PRE_GV_W
#define IH PRE_GV_H
#define INPIX (IW * IH)
#define IWS (PFT_PRE_WORKSPACE_BYTES(IW, IH, PFT_PRE_BG_TEMPORAL, 4, 16, 8) / 8u + 1u)

static uint64_t g_wa[IWS], g_wb[IWS], g_copy[IWS];
static uint16_t g_raw[INPIX], g_buf[INPIX], g_buf_copy[INPIX];
static uint8_t g_map[((IW + 7) / 8) * IH];

#define NCASE 6

/* Case c: 0 temporal (defaults), 1 temporal with the last frame's sigma and the edge term,
 * 2 local (9 x 9, the last frame's sigma), 3 local 3 x 3 without guard, 4 temporal with a
 * bad-pixel map (rows without the fused loop), 5 temporal without sub-pixel steps. */
static void config_(pft_pre_config_t *cfg, int c, bool inplace)
{
    pft_pre_config_default(cfg);
    cfg->width = IW;
    cfg->height = IH;
    cfg->tile = 16;
    cfg->peak_max = 8;
    cfg->method = (c == 2 || c == 3) ? PFT_PRE_BG_LOCAL : PFT_PRE_BG_TEMPORAL;
    if (c == 1) {
        cfg->sigma_current = false;
        cfg->edge_k = 655u;
    }
    if (c == 2) {
        cfg->sigma_current = false;
    }
    if (c == 3) {
        cfg->local_outer = 1u;
        cfg->local_guard = 0u;
    }
    if (c == 4) {
        memset(g_map, 0, sizeof g_map);
        g_map[10 * ((IW + 7) / 8) + 2] = 0x24u; /* (18, 10), (21, 10) */
        g_map[31 * ((IW + 7) / 8) + 5] = 0x01u; /* (40, 31) */
        cfg->bad_map = g_map;
    }
    if (c == 5) {
        cfg->reg_iters = 0u;
    }
    cfg->inplace = inplace;
}

/* Frame k, flipped upside down when flip is set. */
static void render_(uint32_t k, bool flip)
{
    pre_gv_render(k, g_raw);
    if (flip) {
        for (int y = 0; y < IH / 2; ++y) {
            for (int x = 0; x < IW; ++x) {
                const uint16_t t = g_raw[y * IW + x];
                g_raw[y * IW + x] = g_raw[(IH - 1 - y) * IW + x];
                g_raw[(IH - 1 - y) * IW + x] = t;
            }
        }
    }
}

static pft_frame_t frame_(const uint16_t *data, uint32_t k)
{
    pft_frame_t f;
    memset(&f, 0, sizeof f);
    f.data = data;
    f.width = IW;
    f.height = IH;
    f.stride_bytes = 2u * IW;
    f.format = PFT_PIX_U16;
    f.bit_depth = 14;
    f.seq = 100u + k;
    f.timestamp_us = 40000u * k;
    return f;
}

static void test_inplace_gives_the_same_residual(void)
{
    char msg[96];
    for (int c = 0; c < NCASE; ++c) {
        for (int flip = 0; flip < 2; ++flip) {
            pft_pre_config_t ca, cb;
            config_(&ca, c, false);
            config_(&cb, c, true);
            pft_pre_t a, b;
            TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_init(&a, &ca, g_wa, sizeof g_wa));
            TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_init(&b, &cb, g_wb, sizeof g_wb));
            for (uint32_t k = 0; k < PRE_GV_FRAMES; ++k) {
                snprintf(msg, sizeof msg, "case %d flip %d frame %u", c, flip, (unsigned)k);
                if (flip != 0 && k == 10u) { /* a reset part-way: both start again */
                    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_reset(&a));
                    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_reset(&b));
                    pft_frame_t none;
                    TEST_ASSERT_EQUAL_INT_MESSAGE(PFT_ERR_STATE, pft_pre_frame(&b, &none), msg);
                }
                render_(k, flip != 0);
                memcpy(g_buf, g_raw, sizeof g_buf);
                const pft_frame_t fa = frame_(g_raw, k), fb = frame_(g_buf, k);
                TEST_ASSERT_EQUAL_INT_MESSAGE(PFT_OK, pft_pre_update(&a, &fa), msg);
                TEST_ASSERT_EQUAL_INT_MESSAGE(PFT_OK, pft_pre_update_inplace(&b, &fb, g_buf), msg);
                pft_frame_t ra, rb;
                TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_frame(&a, &ra));
                TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_frame(&b, &rb));
                TEST_ASSERT_TRUE_MESSAGE(rb.data == (const void *)g_buf, msg);
                TEST_ASSERT_EQUAL_MEMORY_MESSAGE(&ra.width, &rb.width,
                                                 sizeof ra - offsetof(pft_frame_t, width), msg);
                TEST_ASSERT_EQUAL_MEMORY_MESSAGE(ra.data, g_buf, sizeof g_buf, msg);
                pft_pre_stats_t sa, sb;
                TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_stats(&a, &sa));
                TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_stats(&b, &sb));
                TEST_ASSERT_EQUAL_MEMORY_MESSAGE(&sa, &sb, sizeof sa, msg);
                pft_pre_peak_t pa[8], pb[8];
                memset(pa, 0, sizeof pa);
                memset(pb, 0, sizeof pb);
                TEST_ASSERT_EQUAL_UINT32(pft_pre_peaks(&a, pa, 8), pft_pre_peaks(&b, pb, 8));
                TEST_ASSERT_EQUAL_MEMORY_MESSAGE(pa, pb, sizeof pa, msg);
                uint32_t ga[16], gb[16];
                memset(ga, 0, sizeof ga);
                memset(gb, 0, sizeof gb);
                TEST_ASSERT_EQUAL_UINT32(pft_pre_sigma(&a, ga, 16), pft_pre_sigma(&b, gb, 16));
                TEST_ASSERT_EQUAL_MEMORY_MESSAGE(ga, gb, sizeof ga, msg);
            }
        }
    }
}

/* The sequence reaches what the comparison needs: masked input pixels counted by cause in
 * rows made by the temporal pass's fused loop, both row directions, peaks. */
static void test_sequence_exercises_the_paths(void)
{
    pft_pre_config_t cb;
    config_(&cb, 0, true);
    pft_pre_t b;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_init(&b, &cb, g_wb, sizeof g_wb));
    uint32_t dead = 0u, sat = 0u, peaks = 0u, up = 0u, down = 0u;
    for (uint32_t k = 0; k < PRE_GV_FRAMES; ++k) {
        render_(k, false);
        memcpy(g_buf, g_raw, sizeof g_buf);
        const pft_frame_t fb = frame_(g_buf, k);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_update_inplace(&b, &fb, g_buf));
        pft_pre_stats_t s;
        (void)pft_pre_stats(&b, &s);
        if (k > 0u && (s.flags & PFT_PRE_FLAG_CONSTANT) == 0u) {
            dead += s.n_dead;
            sat += s.n_saturated;
            peaks += s.n_peaks;
            up += s.shift[1] < 0 ? 1u : 0u;
            down += s.shift[1] > 0 ? 1u : 0u;
        }
    }
    TEST_ASSERT_TRUE(dead >= 10u);
    TEST_ASSERT_TRUE(sat >= 5u);
    TEST_ASSERT_TRUE(peaks > 0u);
    TEST_ASSERT_TRUE(up + down >= 5u);
}

static void test_config_workspace_and_refusals(void)
{
    pft_pre_config_t c;
    const char *field = NULL;
    for (int m = 0; m < 2; ++m) {
        config_(&c, m == 0 ? 0 : 2, true);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_config_check(&c, &field));
        const size_t in = pft_pre_workspace_size(&c);
        c.inplace = false;
        const size_t out = pft_pre_workspace_size(&c);
        /* the residual (2 bytes per pixel) is all the difference */
        TEST_ASSERT_EQUAL_UINT32(out - in, PFT_WS_ROUND((size_t)INPIX * 2u));
        TEST_ASSERT_EQUAL_UINT32(in, PFT_PRE_WORKSPACE_BYTES_INPLACE(IW, IH, c.method, c.local_outer,
                                                                     c.tile, c.peak_max));
    }
    config_(&c, 2, true);
    c.format = PFT_PIX_U8;
    c.bit_depth = 8;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_pre_config_check(&c, &field));
    TEST_ASSERT_EQUAL_STRING("inplace", field);
    TEST_ASSERT_EQUAL_UINT32(0u, pft_pre_workspace_size(&c));

    /* refused calls change neither the instance, nor its workspace, nor the frame buffer */
    pft_pre_config_t cb, ca;
    config_(&cb, 0, true);
    config_(&ca, 0, false);
    pft_pre_t b, a;
    const size_t need = pft_pre_workspace_size(&cb);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_init(&b, &cb, g_wb, need));
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_init(&a, &ca, g_wa, sizeof g_wa));
    for (uint32_t k = 0; k < 4u; ++k) { /* a state worth protecting */
        render_(k, false);
        memcpy(g_buf, g_raw, sizeof g_buf);
        const pft_frame_t fb = frame_(g_buf, k);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_update_inplace(&b, &fb, g_buf));
    }
    render_(4u, false);
    memcpy(g_buf, g_raw, sizeof g_buf);
    memcpy(g_buf_copy, g_buf, sizeof g_buf);
    const pft_pre_t before = b;
    memcpy(g_copy, g_wb, need);
    pft_frame_t bad[6];
    for (int i = 0; i < 6; ++i) {
        bad[i] = frame_(g_buf, 4u);
    }
    bad[0].width = IW - 1;              /* wrong size */
    bad[1].bit_depth = 12;              /* wrong bit depth */
    bad[2].stride_bytes = 2u * IW + 2u; /* rows not packed (refused before any read) */
    bad[3].bit_depth = 0;               /* reads as 16 bits: not the configured 14 */
    bad[4].data = g_raw;                /* not the buffer given */
    bad[5].format = PFT_PIX_RES16;
    const pft_status_t want[6] = {PFT_ERR_FORMAT, PFT_ERR_FORMAT, PFT_ERR_FORMAT,
                                  PFT_ERR_FORMAT, PFT_ERR_INVAL, PFT_ERR_FORMAT};
    for (int i = 0; i < 6; ++i) {
        TEST_ASSERT_EQUAL_INT_MESSAGE(want[i], pft_pre_update_inplace(&b, &bad[i], g_buf), "bad frame");
        TEST_ASSERT_EQUAL_MEMORY(&before, &b, sizeof b);
        TEST_ASSERT_EQUAL_MEMORY(g_copy, g_wb, need);
        TEST_ASSERT_EQUAL_MEMORY(g_buf_copy, g_buf, sizeof g_buf);
    }
    const pft_frame_t good = frame_(g_buf, 4u);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_pre_update_inplace(&b, &good, NULL));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_pre_update_inplace(&b, NULL, g_buf));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_pre_update_inplace(NULL, &good, g_buf));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_pre_update_inplace(&b, &good, g_buf + 1));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_STATE, pft_pre_update(&b, &good)); /* needs the buffer */
    TEST_ASSERT_EQUAL_MEMORY(&before, &b, sizeof b);
    TEST_ASSERT_EQUAL_MEMORY(g_copy, g_wb, need);
    TEST_ASSERT_EQUAL_MEMORY(g_buf_copy, g_buf, sizeof g_buf);
    /* an instance without inplace does not write over the frame */
    const pft_pre_t abefore = a;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_STATE, pft_pre_update_inplace(&a, &good, g_buf));
    TEST_ASSERT_EQUAL_MEMORY(&abefore, &a, sizeof a);
    TEST_ASSERT_EQUAL_MEMORY(g_buf_copy, g_buf, sizeof g_buf);
    /* the good call is accepted and does write the residual over the frame */
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_update_inplace(&b, &good, g_buf));
    TEST_ASSERT_TRUE(memcmp(g_buf_copy, g_buf, sizeof g_buf) != 0);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_inplace_gives_the_same_residual);
    RUN_TEST(test_sequence_exercises_the_paths);
    RUN_TEST(test_config_workspace_and_refusals);
    return UNITY_END();
}
