/*
 * The stage's scene-anchored temporal background (pft_pre_config_t.bg_anchor,
 * docs/algorithms.md 9.12): the configuration check and workspace; on a scene of sharp-edged
 * rectangles drifting by 0.3 / 0.2 px per frame with small noise, the anchored residual's
 * standard deviation over the noise's stays within a stated bound and below the re-warped
 * one's; an integer move of the anchor leaves the stored values unchanged (exact); constant,
 * all-dead and all-saturated frames stay finite and are reported; refused input leaves the
 * instance and the workspace byte-identical. The pass's residual row (pft_pre_ares_span_,
 * internal, declared here) in its plain and split forms (the split one 8 pixels at a time with
 * SSE2 on x86-64, NEON on AArch64) against known answers and a 64-bit reference, both k1; the
 * update's clipped gate (pft_pre_gate_clip_, internal) likewise in its plain and split forms;
 * the registration's view of the grid in its SSE2 (x86-64) and NEON (AArch64) forms. Frames are 96 x 72 (every target, Cortex-M under
 * QEMU included); scenes are made with per-column and per-row tables and integer products.
 */
#include <math.h>
#include <string.h>

#include "pft_test_support.h"
#include "pft/pft_pre.h"

int32_t pft_pre_vsplit_(int32_t v);
void pft_pre_ares_span_(const int32_t *v, const int32_t *zl, int16_t *r, int32_t x0, int32_t x1,
                        const int32_t wr[4], uint32_t k1, bool split);
void pft_pre_gate_clip_(const int32_t *const q[4], const int32_t w[4], const int32_t n[4], int32_t a15,
                        uint16_t *b, int32_t ja, int32_t jb, int32_t lim, bool split);

void setUp(void) {}
void tearDown(void) {}

#define W 96
#define H 72
#define NPIX (W * H)
#define TILE 24
#define NREC 14

static uint16_t g_img[NPIX];
static uint64_t g_work[PFT_PRE_WORKSPACE_BYTES_ANCHOR(W, H, 4, TILE, 64) / 8 + 8];
static uint64_t g_copy[sizeof(g_work) / 8];
static uint16_t g_grid[(W + 3) * (H + 3)];
static uint32_t g_rs = 2463534242u;

/* rectangles of the scene: x0, y0, x1, y1 (px, scene coordinates) and amplitude (counts) */
static const double k_rect[NREC][5] = {
    {5.0, 4.0, 30.0, 22.0, 1800.0},   {20.0, 15.0, 55.0, 40.0, -1200.0},
    {60.0, 5.0, 90.0, 30.0, 2500.0},  {70.0, 40.0, 110.0, 70.0, -900.0},
    {10.0, 45.0, 40.0, 80.0, 1500.0}, {45.0, 50.0, 52.0, 57.0, 3000.0},
    {33.2, 8.7, 37.9, 60.3, 1100.0},  {80.5, 20.2, 85.1, 26.9, -2000.0},
    {-10.0, 30.0, 25.0, 33.5, 700.0}, {50.3, 25.6, 66.8, 45.1, 1300.0},
    {15.5, 60.5, 18.5, 63.5, 2600.0}, {88.0, 50.0, 120.0, 56.0, 1700.0},
    {3.0, 35.0, 8.0, 75.0, -1500.0},  {40.0, -5.0, 44.0, 20.0, 2100.0}};
static int32_t g_ox[NREC][W], g_oy[NREC][H];

/* overlap of pixel [p - 0.5, p + 0.5) shifted by -s with [a, b), Q12 */
static int32_t overlap_q12(int p, double s, double a, double b)
{
    const double lo = p - 0.5 - s, hi = p + 0.5 - s;
    const double l = lo > a ? lo : a, r = hi < b ? hi : b;
    return r > l ? (int32_t)floor((r - l) * 4096.0 + 0.5) : 0;
}

/* xorshift noise, a sum of four uniforms: sd 4 * 4096 / sqrt(12) / 4096... scaled below */
static int32_t noise_unit_q10(void)
{
    return (pft_test_noise_sum4(&g_rs) * 1024) / 2365; /* sd 2365: N(0, 1) nearly, Q10 */
}

/* The rectangles area-integrated over each pixel (sharp edges: one pixel of transition), the
 * scene shifted by (sx, sy): pixel p shows the scene at p - s exactly; plus N(0, sigma). */
static void rects(double sx, double sy, int32_t sigma)
{
    for (int k = 0; k < NREC; ++k) {
        for (int x = 0; x < W; ++x) {
            g_ox[k][x] = overlap_q12(x, sx, k_rect[k][0], k_rect[k][2]);
        }
        for (int y = 0; y < H; ++y) {
            g_oy[k][y] = overlap_q12(y, sy, k_rect[k][1], k_rect[k][3]);
        }
    }
    for (int y = 0; y < H; ++y) {
        for (int x = 0; x < W; ++x) {
            int64_t v = (int64_t)6000 << 24; /* Q24 counts */
            for (int k = 0; k < NREC; ++k) {
                v += (int64_t)g_ox[k][x] * g_oy[k][y] * (int32_t)k_rect[k][4];
            }
            v += (int64_t)sigma * noise_unit_q10() * 16384; /* << 14, defined for negatives */
            const int64_t r = (v + ((int64_t)1 << 23)) >> 24;
            g_img[y * W + x] = (uint16_t)(r < 0 ? 0 : (r > 16383 ? 16383 : r));
        }
    }
}

static pft_frame_t frame_of(uint32_t seq)
{
    return pft_test_u16_frame(g_img, W, H, 14u, seq);
}

static void config(pft_pre_config_t *c, bool anchor)
{
    pft_pre_config_default(c);
    c->width = W;
    c->height = H;
    c->tile = TILE;
    c->sigma_interp = false; /* sigma held per tile: the residual in counts is exact */
    c->bg_anchor = anchor;
}

static void init(pft_pre_t *p, const pft_pre_config_t *c)
{
    pft_test_pre_init(p, c, g_work, sizeof(g_work));
}

/* Standard deviation of the unmasked residual in counts (whitened value times its tile's
 * sigma), over sigma_t; *n the unmasked pixels. */
static double res_sd_over(const pft_pre_t *p, double sigma_t, int *n_out)
{
    pft_frame_t r;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_frame(p, &r));
    uint32_t sig[16];
    const size_t nt = pft_pre_sigma(p, sig, 16);
    TEST_ASSERT_EQUAL_UINT32(12u, (uint32_t)nt); /* 4 x 3 tiles */
    const int16_t *v = r.data;
    double s = 0.0, s2 = 0.0;
    int n = 0;
    for (int y = 0; y < H; ++y) {
        for (int x = 0; x < W; ++x) {
            const int16_t q = v[y * W + x];
            if (q == PFT_RES16_MASKED) {
                continue;
            }
            const double c = q / 256.0 * (sig[(y / TILE) * 4 + x / TILE] / 65536.0);
            s += c;
            s2 += c * c;
            n++;
        }
    }
    *n_out = n;
    return n > 1 ? sqrt((s2 - s * s / n) / (n - 1)) / sigma_t : 0.0;
}

/* ------------------------------------------------------------------ configuration */

static void test_config_and_workspace(void)
{
    pft_pre_config_t c;
    pft_pre_config_default(&c);
    TEST_ASSERT_FALSE(c.bg_anchor);
    const char *field = NULL;
    config(&c, true);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_config_check(&c, &field));
    TEST_ASSERT_EQUAL_UINT64(PFT_PRE_WORKSPACE_BYTES_ANCHOR(W, H, c.local_outer, TILE, c.peak_max),
                             pft_pre_workspace_size(&c));
    pft_pre_config_t d = c;
    d.bg_anchor = false;
    /* the grid's margin: 3 (w + h + 3) cells of 2 bytes and the 4 rows of (w + 3) int32, each
     * rounded to the workspace alignment */
    const size_t extra = pft_pre_workspace_size(&c) - pft_pre_workspace_size(&d);
    TEST_ASSERT_TRUE(extra >= 2u * ((W + 3u) * (H + 3u) - W * H) + 16u * (W + 3u));
    TEST_ASSERT_TRUE(extra <= 2u * ((W + 3u) * (H + 3u) - W * H) + 16u * (W + 3u) + 3u * PFT_WS_ALIGN);
    const struct {
        int what;
    } refused[3] = {{0}, {1}, {2}};
    for (int i = 0; i < 3; ++i) {
        d = c;
        if (refused[i].what == 0) {
            d.method = PFT_PRE_BG_LOCAL;
        } else if (refused[i].what == 1) {
            d.inplace = true;
        } else {
            d.edge_k = 655u;
        }
        TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_pre_config_check(&d, &field));
        TEST_ASSERT_EQUAL_STRING("bg_anchor", field);
        TEST_ASSERT_EQUAL_UINT64(0u, pft_pre_workspace_size(&d));
    }
    pft_pre_t p;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_NOMEM, pft_pre_init(&p, &c, g_work, pft_pre_workspace_size(&c) / 2u));
}

/* ------------------------------------------------------------------ residual on sharp edges */

/* The rectangles drifting by (0.3, 0.2) px per frame, noise sigma_t 16 counts (edges of 700
 * to 3000 counts: 44 to 190 sigma_t), 40 frames, the same frames for both schemes. Over frames
 * 20..39 (after the warm-up) the mean of the residual's sd / sigma_t. On these edges the
 * registration's own error (about 0.11 px rms in x for both schemes, the same Lucas-Kanade
 * step) leaves most of the residual, so neither is near 1: measured 8.20 re-warped and 6.43
 * anchored (x86-64, float and q16 alike: the stage is integer). Bounds: the anchored one below
 * 8 (its measured value with 25 % margin) and below 0.9 times the re-warped one (measured
 * 0.78); the re-warp chain's error is what the anchored grid removes, and a grid that resampled
 * or misplaced the background would be worse than the chain, not better. */
static void test_sharp_edges_drifting(void)
{
    const int32_t sigma_t = 16;
    double mean_sd[2] = {0.0, 0.0};
    int n_min[2] = {NPIX, NPIX};
    double shift_err[2] = {0.0, 0.0}, max_sd[2] = {0.0, 0.0};
    for (int a = 0; a < 2; ++a) {
        pft_pre_config_t c;
        config(&c, a == 1);
        pft_pre_t p;
        init(&p, &c);
        g_rs = 2463534242u;
        for (uint32_t k = 0; k < 40u; ++k) {
            rects(0.3 * k, 0.2 * k, sigma_t);
            pft_frame_t f = frame_of(k);
            TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_update(&p, &f));
            pft_pre_stats_t st;
            TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_stats(&p, &st));
            TEST_ASSERT_EQUAL_UINT32(0u, st.flags & (PFT_PRE_FLAG_REG_LOST | PFT_PRE_FLAG_REG_WEAK));
            if (k >= 20u) {
                int n = 0;
                const double sd = res_sd_over(&p, sigma_t, &n);
                mean_sd[a] += sd / 20.0;
                max_sd[a] = sd > max_sd[a] ? sd : max_sd[a];
                n_min[a] = n < n_min[a] ? n : n_min[a];
                const double ex = st.shift[0] / 65536.0 - 0.3, ey = st.shift[1] / 65536.0 - 0.2;
                shift_err[a] += (ex * ex + ey * ey) / 20.0;
            }
        }
    }
    printf("largest single frame: rewarp %.3f anchor %.3f\n", max_sd[0], max_sd[1]);
    printf("sd / sigma_t: rewarp %.3f anchor %.3f; unmasked min %d %d; shift rms %.4f %.4f px\n",
           mean_sd[0], mean_sd[1], n_min[0], n_min[1], sqrt(shift_err[0]), sqrt(shift_err[1]));
    /* the anchored residual masks no more than the entering band and the borders (a band of
     * 3 pixels on the entering sides, 4 on the frames where the anchor moves: 4 (96 + 72) of
     * 6912; measured 6348 unmasked at least, the re-warped residual 6417) */
    TEST_ASSERT_TRUE(n_min[1] >= NPIX - 4 * (W + H));
    TEST_ASSERT_TRUE(mean_sd[1] < 8.0);
    TEST_ASSERT_TRUE(mean_sd[1] < 0.9 * mean_sd[0]);
}

/* ------------------------------------------------------------------ integer moves: exact */

/* Noise-free rectangles moving by whole pixels (1, -1) per frame, integer registration
 * (reg_iters 0): the fraction stays 0, so every anchor move is a whole-cell move; the cells
 * that stay in the grid must hold exactly the values they held before the move (one memmove,
 * no resampling), and the residual of every unmasked pixel is exactly 0. */
static void test_integer_move_exact(void)
{
    pft_pre_config_t c;
    config(&c, true);
    c.reg_iters = 0u;
    pft_pre_t p;
    init(&p, &c);
    for (uint32_t k = 0; k < 8u; ++k) {
        rects((double)k, -(double)k, 0);
        memcpy(g_grid, p.bg, sizeof g_grid);
        const int32_t lo[2] = {p.avlo[0], p.avlo[1]}, hi[2] = {p.avhi[0], p.avhi[1]};
        pft_frame_t f = frame_of(k);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_update(&p, &f));
        pft_pre_stats_t st;
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_stats(&p, &st));
        if (k == 0u) {
            continue;
        }
        TEST_ASSERT_EQUAL_INT32(65536, st.shift[0]);
        TEST_ASSERT_EQUAL_INT32(-65536, st.shift[1]);
        TEST_ASSERT_EQUAL_INT32(0, p.aphi[0]);
        TEST_ASSERT_EQUAL_INT32(0, p.aphi[1]);
        /* the anchor moved by -shift = (-1, +1): new cell (j, J) is old cell (j - 1, J + 1) */
        int checked = 0;
        for (int32_t jy = -1; jy <= H + 1; ++jy) {
            for (int32_t j = -1; j <= W + 1; ++j) {
                const int32_t oj = j - 1, ojy = jy + 1;
                if (oj < lo[0] || oj > hi[0] || ojy < lo[1] || ojy > hi[1] || oj < -1 || ojy > H + 1) {
                    continue;
                }
                TEST_ASSERT_EQUAL_UINT16(g_grid[(ojy + 1) * (W + 3) + oj + 1], p.bg[(jy + 1) * (W + 3) + j + 1]);
                checked++;
            }
        }
        TEST_ASSERT_TRUE(checked >= (W - 1) * (H - 1));
        pft_frame_t r;
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_frame(&p, &r));
        const int16_t *v = r.data;
        int n = 0;
        for (int i = 0; i < NPIX; ++i) {
            if (v[i] != PFT_RES16_MASKED) {
                TEST_ASSERT_EQUAL_INT16(0, v[i]);
                n++;
            }
        }
        TEST_ASSERT_TRUE(n >= (W - 2) * (H - 2)); /* only the entering row and column masked */
    }
}

/* ------------------------------------------------------------------ degenerate frames */

static void test_degenerate_frames_flagged(void)
{
    static const struct {
        uint16_t value;
        uint32_t flags;
    } cases[] = {{7000, PFT_PRE_FLAG_CONSTANT | PFT_PRE_FLAG_HELD},
                 {0, PFT_PRE_FLAG_CONSTANT | PFT_PRE_FLAG_ALL_DEAD | PFT_PRE_FLAG_ALL_MASKED |
                         PFT_PRE_FLAG_HELD},
                 {16383, PFT_PRE_FLAG_CONSTANT | PFT_PRE_FLAG_ALL_SATURATED |
                             PFT_PRE_FLAG_ALL_MASKED | PFT_PRE_FLAG_HELD}};
    for (size_t i = 0; i < 3; ++i) {
        pft_pre_config_t c;
        config(&c, true);
        pft_pre_t p;
        init(&p, &c);
        g_rs = 2463534242u;
        for (uint32_t k = 0; k < 8u; ++k) {
            rects(0.3 * k, 0.2 * k, 16);
            pft_frame_t f = frame_of(k);
            TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_update(&p, &f));
        }
        for (int n = 0; n < NPIX; ++n) {
            g_img[n] = cases[i].value;
        }
        pft_frame_t f = frame_of(20);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_update(&p, &f));
        pft_pre_stats_t st;
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_stats(&p, &st));
        TEST_ASSERT_EQUAL_UINT32(cases[i].flags, st.flags & cases[i].flags);
        TEST_ASSERT_EQUAL_UINT32(NPIX, st.n_masked); /* held: the residual is masked */
        TEST_ASSERT_EQUAL_UINT32(0u, st.n_peaks);
        TEST_ASSERT_TRUE(st.sigma_min >= ((uint32_t)c.sigma_floor << 12) && st.sigma_max >= st.sigma_min);
        /* the scene again, where the drift has taken it (frames 21..30) */
        for (uint32_t k = 21; k < 31u; ++k) {
            rects(0.3 * (k - 12u), 0.2 * (k - 12u), 16);
            pft_frame_t g = frame_of(k);
            TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_update(&p, &g));
            TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_stats(&p, &st));
            TEST_ASSERT_EQUAL_UINT32(0u, st.flags & (PFT_PRE_FLAG_REG_LOST | PFT_PRE_FLAG_CONSTANT |
                                                     PFT_PRE_FLAG_ALL_MASKED));
        }
        int n = 0;
        const double sd = res_sd_over(&p, 16.0, &n);
        printf("after value %u: sd / sigma_t %.3f, %d unmasked\n", cases[i].value, sd, n);
        /* finite and at the drifting test's level: one frame, not a mean; that test's largest
         * single frame is 9.35 (anchored), bound 12 with 25 % margin */
        TEST_ASSERT_TRUE(sd < 12.0);
        TEST_ASSERT_TRUE(n > NPIX / 2);
    }
}

/* ------------------------------------------------------------------ refused input */

static void test_refused_input_changes_nothing(void)
{
    pft_pre_config_t c;
    config(&c, true);
    pft_pre_t p;
    init(&p, &c);
    const size_t need = pft_pre_workspace_size(&c);
    g_rs = 2463534242u;
    for (uint32_t k = 0; k < 4u; ++k) { /* a state worth protecting: the anchor has moved */
        rects(0.3 * k, 0.2 * k, 16);
        pft_frame_t f = frame_of(k);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_update(&p, &f));
    }
    const pft_pre_t before = p;
    memcpy(g_copy, g_work, need);
    pft_frame_t bad[5];
    for (int i = 0; i < 5; ++i) {
        bad[i] = frame_of(9);
    }
    bad[0].data = NULL;
    bad[1].width = W - 1;
    bad[2].height = H + 1;
    bad[3].bit_depth = 12;
    bad[4].format = PFT_PIX_RES16;
    const pft_status_t want[5] = {PFT_ERR_INVAL, PFT_ERR_FORMAT, PFT_ERR_FORMAT, PFT_ERR_FORMAT,
                                  PFT_ERR_FORMAT};
    for (int i = 0; i < 5; ++i) {
        TEST_ASSERT_EQUAL_INT(want[i], pft_pre_update(&p, &bad[i]));
        TEST_ASSERT_EQUAL_MEMORY(&before, &p, sizeof p);
        TEST_ASSERT_EQUAL_MEMORY(g_copy, g_work, need);
    }
    uint16_t *px = g_img;
    pft_frame_t f = frame_of(9);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_STATE, pft_pre_update_inplace(&p, &f, px)); /* not inplace */
    TEST_ASSERT_EQUAL_MEMORY(&before, &p, sizeof p);
    TEST_ASSERT_EQUAL_MEMORY(g_copy, g_work, need);
}

/* The residual row of r[x] = ((zl - bx + k1) >> k1) clamped to +-32767 (masked: INT16_MIN), bx
 * the 4-tap blend of v (U * 16) rounded and clamped to [0, 65535], in 64 bits. */
static int16_t ares_ref(const int32_t *v, const int32_t *zl, int32_t x, const int32_t w[4], uint32_t k1)
{
    int64_t s = 2048;
    for (int32_t i = 0; i < 4; ++i) {
        s += (int64_t)w[i] * v[x + i];
    }
    s = s >= 0 ? s / 4096 : -((-s + 4095) / 4096); /* floor */
    const int64_t bx = s < 0 ? 0 : (s > 65535 ? 65535 : s);
    if (zl[x] < 0) {
        return INT16_MIN;
    }
    int64_t e = (int64_t)zl[x] - bx;
    if (k1 != 0u) {
        e = e >= 0 ? (e + 1) / 2 : -((-e) / 2); /* ceil(e / 2) = (e + 1) >> 1 */
    }
    return (int16_t)(e > 32767 ? 32767 : (e < -32767 ? -32767 : e));
}

static void test_residual_span_split_and_plain(void)
{
    enum { N = 27 }; /* three blocks of 8 and a remainder of 3 */
    int32_t v[N + 3], vs[N + 3], zl[N];
    int16_t rp[N], rs[N];
    /* known answers: the tap of weight 256 alone (fraction 0), v = 16 bx */
    {
        const int32_t w[4] = {0, 256, 0, 0};
        const int32_t vv[8] = {0, 16000, 0, 65535 * 16, 0, 16 * 100 + 8, 0, 0};
        const int32_t zz[6] = {1500, 0, 65535, -1, 101, 0};
        /* x 0: bx 1000, e 500; x 1: bx 0, e 0; x 2: bx 65535, e 0; x 3: masked; x 4: bx 101
         * (100.5 rounded up), e 0; x 5: bx 0 */
        const int16_t want0[6] = {500, 0, 0, INT16_MIN, 0, 0};
        for (int32_t i = 0; i < N + 3; ++i) {
            v[i] = i < 8 ? vv[i] : 0;
        }
        for (int32_t i = 0; i < N; ++i) {
            zl[i] = i < 6 ? zz[i] : 65535; /* bx 0: e 65535 */
        }
        zl[20] = 0;
        v[21] = 65535 * 16; /* x 20: bx 65535, e -65535 */
        for (int32_t i = 0; i < N + 3; ++i) {
            vs[i] = pft_pre_vsplit_(v[i]);
        }
        for (uint32_t k1 = 0u; k1 <= 1u; ++k1) {
            pft_pre_ares_span_(v, zl, rp, 0, N - 1, w, k1, false);
            pft_pre_ares_span_(vs, zl, rs, 0, N - 1, w, k1, true);
            for (int32_t x = 0; x < 6; ++x) {
                const int16_t want = k1 != 0u && want0[x] == 500 ? 250 : want0[x];
                TEST_ASSERT_EQUAL_INT16(want, rp[x]);
                TEST_ASSERT_EQUAL_INT16(want, rs[x]);
            }
            /* e 65535: 32767 clamped (k1 1: 32768 clamped); e -65535: -32767 (k1 1: -32767) */
            TEST_ASSERT_EQUAL_INT16(32767, rp[6]);
            TEST_ASSERT_EQUAL_INT16(32767, rs[6]);
            TEST_ASSERT_EQUAL_INT16(32767, rs[N - 1]);
            TEST_ASSERT_EQUAL_INT16(-32767, rp[20]);
            TEST_ASSERT_EQUAL_INT16(-32767, rs[20]);
        }
    }
    /* the cubic's negative lobes at the blends' extremes, and random rows: both forms against
     * the reference, both k1, spans starting at every offset of a block */
    {
        const int32_t wc[4][4] = {{-19, 147, 147, -19}, {0, 256, 0, 0}, {0, 77, 179, 0},
                                  {-9, 200, 72, -7}};
        uint32_t rng = 12345u;
        for (int32_t t = 0; t < 400; ++t) {
            const int32_t *w = wc[(t / 4) % 4];
            for (int32_t i = 0; i < N + 3; ++i) {
                rng = rng * 1664525u + 1013904223u;
                const uint32_t u = rng >> 8;
                v[i] = (t & 1) != 0 ? ((u & 1u) != 0u ? 1179630 : -131070)
                                    : (int32_t)(u % 1310701u) - 131070;
                vs[i] = pft_pre_vsplit_(v[i]);
            }
            for (int32_t i = 0; i < N; ++i) {
                rng = rng * 1664525u + 1013904223u;
                const uint32_t u = rng >> 8;
                zl[i] = u % 8u == 0u ? -1 : (u % 8u == 1u ? 65535 : (int32_t)((u >> 3) % 65536u));
            }
            const int32_t x0 = t % 8, x1 = N - 1 - (t / 8) % 4;
            const uint32_t k1 = (uint32_t)(t / 2) % 2u;
            memset(rp, 0, sizeof(rp));
            memset(rs, 0, sizeof(rs));
            pft_pre_ares_span_(v, zl, rp, x0, x1, w, k1, false);
            pft_pre_ares_span_(vs, zl, rs, x0, x1, w, k1, true);
            for (int32_t x = 0; x < N; ++x) {
                const int16_t want = x >= x0 && x <= x1 ? ares_ref(v, zl, x, w, k1) : 0;
                TEST_ASSERT_EQUAL_INT16(want, rp[x]);
                TEST_ASSERT_EQUAL_INT16(want, rs[x]);
            }
        }
    }
}

/* The clipped gate of one cell, in 64 bits: the blend of the 4 taps (kept when a tap equals its
 * marker), clamped, its innovation clipped to [-lim, lim] and weighted a15 / 2^15. */
static uint16_t gate_ref(const int32_t *const q[4], const int32_t w[4], const int32_t n[4], int32_t a15,
                         int32_t j, uint16_t bx, int32_t lim)
{
    int64_t s = 2048;
    bool inv = false;
    for (int32_t i = 0; i < 4; ++i) {
        inv = inv || q[i][j] == n[i];
        s += (int64_t)w[i] * q[i][j];
    }
    if (inv) {
        return bx;
    }
    const int64_t sv = s >= 0 ? s / 4096 : -((-s + 4095) / 4096); /* floor */
    const int64_t c = sv < 0 ? 0 : (sv > 65535 ? 65535 : sv);
    int64_t e = c - (int64_t)bx;
    e = e > lim ? lim : (e < -lim ? -lim : e);
    const int64_t d = e * a15 + 16384;
    return (uint16_t)((int64_t)bx + (d >= 0 ? d / 32768 : -((-d + 32767) / 32768)));
}

static void test_gate_clip_split_and_plain(void)
{
    enum { N = 19 }; /* two blocks of 8 and a remainder of 3 */
    const int32_t none = -4194304; /* the ring's invalid value */
    int32_t r[4][N];
    const int32_t *const q[4] = {r[0], r[1], r[2], r[3]};
    uint16_t bp[N + 2], bs[N + 2];
    /* known answers: the tap of weight 256 alone, v = 16 U, lim 50, a15 16384 */
    {
        const int32_t w[4] = {0, 256, 0, 0}, n[4] = {none + 1, none, none + 1, none + 1};
        memset(r, 0, sizeof(r));
        for (int32_t j = 0; j < N + 2; ++j) {
            bp[j] = 7u;
        }
        r[1][0] = 16000; /* U 1000, bx 900: e 100 clipped to 50, 900 + 25 */
        bp[1] = 900u;
        r[1][1] = -80; /* U -5 clamped to 0, bx 10: e -10, 10 + floor(-4.5) */
        bp[2] = 10u;
        r[1][2] = none; /* invalid: kept */
        bp[3] = 1234u;
        r[1][3] = 16 * 70000; /* clamped to 65535 = bx: kept */
        bp[4] = 65535u;
        r[1][17] = 16 * 60000; /* a remainder cell: bx 7, e clipped to 50 */
        memcpy(bs, bp, sizeof(bp));
        pft_pre_gate_clip_(q, w, n, 16384, bp, 0, N - 1, 50, false);
        pft_pre_gate_clip_(q, w, n, 16384, bs, 0, N - 1, 50, true);
        const uint16_t want[5] = {925u, 5u, 1234u, 65535u, 4u}; /* j 4: v 0, bx 7: e -7, 7 - 3 */
        for (int32_t j = 0; j < 5; ++j) {
            TEST_ASSERT_EQUAL_UINT16(want[j], bp[j + 1]);
            TEST_ASSERT_EQUAL_UINT16(want[j], bs[j + 1]);
        }
        TEST_ASSERT_EQUAL_UINT16(32u, bp[18]); /* 7 + ((50 * 16384 + 16384) >> 15) */
        TEST_ASSERT_EQUAL_UINT16(32u, bs[18]);
        TEST_ASSERT_EQUAL_UINT16(4u, bp[6]); /* v 0: e -7, 7 + (-98304 >> 15) */
        TEST_ASSERT_EQUAL_UINT16(4u, bs[6]);
        TEST_ASSERT_EQUAL_UINT16(7u, bs[0]); /* outside the span */
        TEST_ASSERT_EQUAL_UINT16(7u, bs[N + 1]);
    }
    /* known answers in one block of 8 (the vector form where it applies) with the cubic's
     * weights: ring values at both ends of [-2^21, 2^21), products of both signs in even and
     * odd lanes, a sum below 0, invalid first and last taps; lim 50, a15 16384 */
    {
        const int32_t w[4] = {-19, 147, 147, -19}, n[4] = {none, none, none, none};
        const int32_t v[8][4] = {{2097151, 2097151, 2097151, 2097151}, /* 65535: e 535 clipped */
                                 {-2097152, 16000, 16000, -2097152},   /* (84395776 + 2048) >> 12 */
                                 {1600, -800, 4800, 3200},             /* 121 */
                                 {16000, -16000, -16000, 16000},       /* below 0: 0 */
                                 {none, 16, 16, 16},                   /* kept */
                                 {16, 16, 16, none},                   /* kept */
                                 {0, 0, 0, 0},
                                 {0, 0, 0, 0}};
        const uint16_t bx[8] = {65000u, 20600u, 100u, 30u, 1234u, 4321u, 7u, 7u};
        /* 65000 + 25, 20600 + ((4 * 16384 + 16384) >> 15), 100 + ((21 * 16384 + 16384) >> 15),
         * 30 + ((-30 * 16384 + 16384) >> 15), kept, kept, 7 + (-98304 >> 15) */
        const uint16_t want[8] = {65025u, 20602u, 111u, 15u, 1234u, 4321u, 4u, 4u};
        memset(r, 0, sizeof(r));
        bp[0] = 9u;
        bp[9] = 9u;
        for (int32_t j = 0; j < 8; ++j) {
            for (int32_t i = 0; i < 4; ++i) {
                r[i][j] = v[j][i];
            }
            bp[j + 1] = bx[j];
        }
        memcpy(bs, bp, sizeof(bp));
        pft_pre_gate_clip_(q, w, n, 16384, bp, 0, 7, 50, false);
        pft_pre_gate_clip_(q, w, n, 16384, bs, 0, 7, 50, true);
        for (int32_t j = 0; j < 8; ++j) {
            TEST_ASSERT_EQUAL_UINT16(want[j], bp[j + 1]);
            TEST_ASSERT_EQUAL_UINT16(want[j], bs[j + 1]);
        }
        TEST_ASSERT_EQUAL_UINT16(9u, bs[0]); /* outside the span */
        TEST_ASSERT_EQUAL_UINT16(9u, bs[9]);
    }
    /* random rows (invalid taps, the cubic's lobes, values beyond the clamps), every offset of
     * a block, lims up to 65535 (no clip), a15 within [0, 32768] (0 and 32768 by the plain loop):
     * both forms against the reference */
    {
        const int32_t wc[4][4] = {{-19, 147, 147, -19}, {0, 256, 0, 0}, {0, 77, 179, 0},
                                  {-9, 200, 72, -7}};
        const int32_t lims[5] = {1, 300, 32767, 32768, 65535};
        const int32_t a15s[5] = {1, 9830, 32767, 32768, 0}; /* 32768, 0: the plain loop */
        uint32_t rng = 777u;
        for (int32_t t = 0; t < 400; ++t) {
            const int32_t *w = wc[t % 4];
            int32_t n[4];
            for (int32_t i = 0; i < 4; ++i) {
                n[i] = w[i] != 0 ? none : none + 1;
            }
            for (int32_t i = 0; i < 4; ++i) {
                for (int32_t j = 0; j < N; ++j) {
                    rng = rng * 1664525u + 1013904223u;
                    const uint32_t u = rng >> 8;
                    r[i][j] = u % 16u == 0u ? none
                                           : (u % 16u == 1u ? (int32_t)((u >> 4) % 262144u) - 262144
                                                            : (int32_t)((u >> 4) % 1114096u));
                }
            }
            for (int32_t j = 0; j < N + 2; ++j) {
                rng = rng * 1664525u + 1013904223u;
                const uint32_t u = rng >> 8;
                bp[j] = (uint16_t)(u % 8u == 0u ? 0u : (u % 8u == 1u ? 65535u : (u >> 3) % 65536u));
            }
            memcpy(bs, bp, sizeof(bp));
            uint16_t b0[N + 2];
            memcpy(b0, bp, sizeof(bp));
            const int32_t ja = t % 8, jb = N - 1 - (t / 8) % 4;
            const int32_t lim = lims[(t / 4) % 5], a15 = a15s[(t / 20) % 5];
            pft_pre_gate_clip_(q, w, n, a15, bp, ja, jb, lim, false);
            pft_pre_gate_clip_(q, w, n, a15, bs, ja, jb, lim, true);
            for (int32_t j = -1; j <= N; ++j) {
                const uint16_t want = j >= ja && j <= jb ? gate_ref(q, w, n, a15, j, b0[j + 1], lim) : b0[j + 1];
                TEST_ASSERT_EQUAL_UINT16(want, bp[j + 1]);
                TEST_ASSERT_EQUAL_UINT16(want, bs[j + 1]);
            }
        }
    }
}

#if defined(__SSE2__)
/* Internal to the library (lib/src/pre/pre_int.h, x86-64 only); the test declares them. */
void pft_pre_view_vrow_(const uint16_t *t0, const uint16_t *t1, const uint16_t *t2,
                        const uint16_t *t3, const int32_t w[4], int16_t *vh, int16_t *vl,
                        int32_t n);
void pft_pre_view_hrow_(const int16_t *vh, const int16_t *vl, int32_t sw, int32_t k,
                        const int32_t w[4], uint16_t *o, int32_t n);

#define VW 389 /* the longest row tested (storage columns) */

/* Catmull-Rom weights of fraction f / 256 in Q8 (docs/algorithms.md 9.12), summing to 256. */
static void view_cubic(int32_t f, int32_t w[4])
{
    const double t = f / 256.0, t2 = t * t, t3 = t2 * t;
    const double q[4] = {(-t3 + 2.0 * t2 - t) / 2.0, (3.0 * t3 - 5.0 * t2 + 2.0) / 2.0,
                         (-3.0 * t3 + 4.0 * t2 + t) / 2.0, (t3 - t2) / 2.0};
    int32_t sum = 0;
    for (int i = 0; i < 4; ++i) {
        w[i] = (int32_t)(q[i] >= 0.0 ? floor(q[i] * 256.0 + 0.5) : -floor(-q[i] * 256.0 + 0.5));
        sum += w[i];
    }
    w[f < 128 ? 1 : 2] += 256 - sum;
}

/* The registration's view of one row in the 32-bit form (the form of every other target):
 * vb = (sum of wy (t - 32768) + 256 * 32768 + 8) >> 4, then
 * (sum of wx vb[x + k + i] + 2048) >> 12 clamped to [0, 65535], taps past sw - 1 clamped. */
static void view_ref(const uint16_t *const t[4], const int32_t wy[4], const int32_t wx[4],
                     int32_t sw, int32_t k, int32_t n, uint16_t *o)
{
    static int32_t vb[VW];
    for (int32_t i = 0; i < sw; ++i) {
        int32_t v = 0;
        for (int j = 0; j < 4; ++j) {
            v += wy[j] * ((int32_t)t[j][i] - 32768);
        }
        vb[i] = (v + 256 * 32768 + 8) >> 4;
    }
    for (int32_t x = 0; x < n; ++x) {
        int32_t sv = 2048;
        for (int32_t i = 0; i < 4; ++i) {
            const int32_t c = x + k + i < sw - 1 ? x + k + i : sw - 1;
            sv += wx[i] * vb[c];
        }
        sv >>= 12;
        o[x] = (uint16_t)(sv < 0 ? 0 : (sv > 65535 ? 65535 : sv));
    }
}

/* One row through both kernels: vector body (8 pixels) and scalar rest. */
static void view_row(const uint16_t *const t[4], const int32_t wy[4], const int32_t wx[4],
                     int32_t sw, int32_t k, int32_t n, uint16_t *o)
{
    static int16_t vh[VW], vl[VW];
    pft_pre_view_vrow_(t[0], t[1], t[2], t[3], wy, vh, vl, sw);
    pft_pre_view_hrow_(vh, vl, sw, k, wx, o, n);
}
#endif

/* x86-64's view of the anchored grid (pft_pre_view_vrow_, pft_pre_view_hrow_: SSE2 lanes of 8
 * pixels, the last pixels of a row in the scalar form): known answers (the identity weights
 * return the grid; a constant 65535 stays 65535; the cubic's overshoot on 0, 65535, 65535, 0
 * clamps to 65535 and 0), then every row equal to the 32-bit form on random, extreme and
 * checkerboard grids, every fraction of both weight kinds, k 0 and 1, widths 1 .. 40 and 384
 * (rows shorter than 8 pixels take the scalar form only). */
static void test_view_rows_sse2(void)
{
#if defined(__SSE2__)
    static uint16_t rows[4][VW];
    static uint16_t o[VW], want[VW];
    const uint16_t *const t[4] = {rows[0], rows[1], rows[2], rows[3]};
    const int32_t id[4] = {0, 256, 0, 0}, cub[4] = {-16, 144, 144, -16};
    int32_t c2[4];
    view_cubic(128, c2);
    TEST_ASSERT_EQUAL_INT32_ARRAY(cub, c2, 4);
    for (int32_t i = 0; i < VW; ++i) {
        for (int j = 0; j < 4; ++j) {
            rows[j][i] = (uint16_t)(pft_test_xorshift32(&g_rs) & 65535u);
        }
    }
    view_row(t, id, id, 387, 0, 384, o); /* identity: pixel x is row 1's column x + 1 */
    TEST_ASSERT_EQUAL_UINT16_ARRAY(rows[1] + 1, o, 384);
    view_row(t, id, id, 387, 1, 384, o); /* k 1: column x + 2 (the last fourth tap clamped, weight 0) */
    TEST_ASSERT_EQUAL_UINT16_ARRAY(rows[1] + 2, o, 384);
    for (int32_t i = 0; i < VW; ++i) {
        for (int j = 0; j < 4; ++j) {
            rows[j][i] = 65535u;
        }
    }
    view_row(t, cub, cub, 387, 0, 384, o);
    for (int32_t x = 0; x < 384; ++x) {
        TEST_ASSERT_EQUAL_UINT16(65535u, o[x]);
    }
    for (int32_t i = 0; i < VW; ++i) { /* columns 0, 65535, 65535, 0, ... */
        for (int j = 0; j < 4; ++j) {
            rows[j][i] = (i & 3) == 1 || (i & 3) == 2 ? 65535u : 0u;
        }
    }
    view_row(t, cub, cub, 387, 0, 384, o); /* taps x .. x + 3 */
    for (int32_t x = 0; x < 380; ++x) {
        const uint16_t k_want[4] = {65535u, 32768u, 0u, 32768u};
        TEST_ASSERT_EQUAL_UINT16(k_want[x & 3], o[x]);
    }
    uint32_t cases = 0u;
    for (int32_t kind = 0; kind < 7; ++kind) {
        for (int32_t f = 0; f < 256; ++f) {
            int32_t wy[4], wx[4];
            if ((kind & 1) != 0) {
                view_cubic(f, wy);
                view_cubic((f * 37 + 11) & 255, wx);
            } else {
                wy[0] = 0; wy[1] = 256 - f; wy[2] = f; wy[3] = 0;
                wx[0] = 0; wx[1] = 256 - ((f * 37 + 11) & 255); wx[2] = (f * 37 + 11) & 255; wx[3] = 0;
            }
            const int32_t n = f < 200 ? 1 + f % 40 : 384, k = f & 1, sw = n + 3;
            for (int32_t i = 0; i < sw; ++i) {
                for (int j = 0; j < 4; ++j) {
                    const uint32_t r = pft_test_xorshift32(&g_rs);
                    uint32_t v = r & 65535u;
                    if (kind == 2 || kind == 3) { /* 0 / 65535 at random */
                        v = (r >> 16 & 1u) != 0u ? 65535u : 0u;
                    } else if (kind == 4 || kind == 5) { /* checkerboard */
                        v = ((i + j) & 1) != 0 ? 65535u : 0u;
                    } else if (kind == 6) { /* near 65535 and near 0 */
                        v = (r >> 16 & 1u) != 0u ? 65535u - (r >> 17 & 15u) : (r >> 17 & 15u);
                    }
                    rows[j][i] = (uint16_t)v;
                }
            }
            view_ref(t, wy, wx, sw, k, n, want);
            view_row(t, wy, wx, sw, k, n, o);
            TEST_ASSERT_EQUAL_UINT16_ARRAY(want, o, (uint32_t)n);
            cases++;
        }
    }
    TEST_ASSERT_EQUAL_UINT32(7u * 256u, cases);
#else
    TEST_IGNORE_MESSAGE("x86-64 (SSE2) only: the other targets keep the 32-bit form");
#endif
}

#if defined(__aarch64__) && defined(__ARM_NEON)
/* Internal to the library (lib/src/pre/pre_int.h, AArch64 with NEON only); the test declares it. */
int32_t pft_pre_view_h32_(const int32_t *v, const int32_t w[4], uint16_t *o, int32_t xe);
#endif

/* AArch64's horizontal pass of the view of the anchored grid (pft_pre_view_h32_: NEON lanes of 8
 * pixels on the 32-bit vertical blends, the pixels past the last whole block left to the
 * caller's loop): known answers (the identity weights return v / 16 rounded, clamped to 0 and
 * 65535), then every pixel equal to the 32-bit loop's (o[x] = (sum of w[i] v[x + i] + 2048) >> 12
 * clamped) on random and extreme blends (the range of anchor_view_'s vertical pass,
 * [-131070, 1179630], and beyond it), bilinear and cubic weights, rows of 0 .. 40 and 384
 * pixels; the pixels it leaves keep their values. */
static void test_view_h32_neon(void)
{
#if defined(__aarch64__) && defined(__ARM_NEON)
    enum { NX = 384 };
    static int32_t v[NX + 3];
    static uint16_t o[NX], want[NX];
    const int32_t id[4] = {0, 256, 0, 0};
    for (int32_t i = 0; i < NX + 3; ++i) {
        v[i] = 16 * 100 * i; /* pixel x: tap x + 1, 100 (x + 1) */
    }
    v[3] = 16 * 70000; /* x 2: clamped to 65535 */
    v[4] = -16 * 5;    /* x 3: clamped to 0 */
    v[5] = 8;          /* x 4: (256 * 8 + 2048) >> 12 = 1 */
    v[6] = 7;          /* x 5: (256 * 7 + 2048) >> 12 = 0 */
    v[7] = 16 * 65535; /* x 6: 65535 */
    memset(o, 0, sizeof(o));
    TEST_ASSERT_EQUAL_INT32(16, pft_pre_view_h32_(v, id, o, 21)); /* 2 blocks */
    const uint16_t k_want[8] = {100u, 200u, 65535u, 0u, 1u, 0u, 65535u, 800u};
    TEST_ASSERT_EQUAL_UINT16_ARRAY(k_want, o, 8);
    for (int32_t x = 8; x < 16; ++x) {
        TEST_ASSERT_EQUAL_UINT16((uint16_t)(100 * (x + 1)), o[x]);
    }
    for (int32_t x = 16; x < 22; ++x) {
        TEST_ASSERT_EQUAL_UINT16(0u, o[x]); /* the loop's pixels: left */
    }
    TEST_ASSERT_EQUAL_INT32(0, pft_pre_view_h32_(v, id, o + 32, 7)); /* fewer than 8: none */
    TEST_ASSERT_EQUAL_UINT16(0u, o[32]);
    const int32_t wc[6][4] = {{-19, 147, 147, -19}, {0, 256, 0, 0}, {0, 77, 179, 0},
                              {-9, 200, 72, -7}, {-16, 144, 144, -16}, {0, 0, 256, 0}};
    uint32_t cases = 0u;
    for (int32_t t = 0; t < 6 * 48; ++t) {
        const int32_t *w = wc[t % 6];
        const int32_t xe = t < 6 * 41 ? t / 6 : NX;
        for (int32_t i = 0; i < NX + 3; ++i) {
            const uint32_t r = pft_test_xorshift32(&g_rs);
            const int32_t kind = (t / 6) % 4;
            v[i] = kind == 0 ? (int32_t)(r % 1310701u) - 131070
                             : (kind == 1 ? ((r & 1u) != 0u ? 1179630 : -131070)
                                          : (kind == 2 ? ((r & 1u) != 0u ? 65535 * 16 : 0)
                                                       : (int32_t)(r % 4194304u) - 2097152));
        }
        for (int32_t x = 0; x < NX; ++x) {
            o[x] = 12345u;
            want[x] = 12345u;
        }
        const int32_t nd = xe / 8 * 8; /* the pixels it does */
        for (int32_t x = 0; x < nd; ++x) {
            const int32_t sv = (w[0] * v[x] + w[1] * v[x + 1] + w[2] * v[x + 2] + w[3] * v[x + 3] + 2048) >> 12;
            want[x] = (uint16_t)(sv < 0 ? 0 : (sv > 65535 ? 65535 : sv));
        }
        TEST_ASSERT_EQUAL_INT32(nd, pft_pre_view_h32_(v, w, o, xe));
        TEST_ASSERT_EQUAL_UINT16_ARRAY(want, o, NX);
        cases++;
    }
    TEST_ASSERT_EQUAL_UINT32(6u * 48u, cases);
#else
    TEST_IGNORE_MESSAGE("AArch64 (NEON) only: the other targets keep the 32-bit loop");
#endif
}

#if defined(__SSE2__) || (defined(__aarch64__) && defined(__ARM_NEON))
/* Internal to the library (lib/src/pre/pre_int.h, x86-64 with SSE2 and AArch64 with NEON only);
 * the test declares it. */
int32_t pft_pre_lk_rowv_(const uint8_t *rz, const int32_t *cz, const uint16_t *bm, int32_t bs,
                         const uint32_t par[6], int32_t st, int32_t n, int64_t sums[6], uint32_t *cnt);

/* The registration's plain loop (lk_loop_ on a U16 frame) over samples 0, st, ..., below ie of
 * one row, in 64-bit arithmetic. */
static void lk_row_ref(const uint16_t *z, const int32_t *cz, const uint16_t *bm, int32_t bs,
                       const uint32_t par[6], int32_t st, int32_t ie, int64_t sums[6], uint32_t *cnt)
{
    const uint16_t *b0 = bm + bs, *b1 = b0 + bs, *b2 = b1 + bs;
    const int64_t fx = par[4], fy = par[5];
    for (int32_t i = 0; i < ie; i += st) {
        const uint32_t v = z[i] & par[0];
        if (v - par[1] >= par[2]) {
            continue;
        }
        const int64_t h0 = b0[i + 1] * (256 - fx) + b0[i + 2] * fx, h1 = b1[i + 1] * (256 - fx) + b1[i + 2] * fx;
        const int64_t bw = (h0 * (256 - fy) + h1 * fy + 32768) >> 16;
        const int64_t e = ((int64_t)v << par[3]) - cz[i] - bw;
        const int64_t gx = ((int64_t)b0[i + 3] - b0[i]) + ((int64_t)b1[i + 3] - b1[i]);
        const int64_t gy = ((int64_t)b2[i + 1] - bm[i + 1]) + ((int64_t)b2[i + 2] - bm[i + 2]);
        sums[0] += gx * gx;
        sums[1] += gx * gy;
        sums[2] += gy * gy;
        sums[3] += gx * e;
        sums[4] += gy * e;
        sums[5] += e * e;
        (*cnt)++;
    }
}
#endif

/* The Lucas-Kanade sums of a row in NEON lanes on AArch64 and SSE2 lanes on x86-64
 * (pft_pre_lk_rowv_, steps 2 and 4: four samples of each whole block of 4 st pixels, an invalid
 * sample's terms 0; SSE2's signed products from unsigned ones and a correction): known answers
 * (a background 10 c + 1000 r, so gx 60 and gy 6000 everywhere, fx = fy = 0, with and without a
 * masked sample, the samples after the last whole block left; the background reversed, gx -60
 * and gy -6000, with colnow +-2^30, so e near +-2^30 of both signs in one block and products
 * beyond 2^32), then the sums, the count and the samples done equal to the plain loop's in
 * 64-bit arithmetic on 800 random rows, both steps (bit depths 12 .. 16 with their bf, random
 * lo, span, fractions 0 .. 255, colnow within +-2^20 or +-2^27, backgrounds random or at 0 and
 * 65535, rows of 0 .. 40 and 360 pixels). */
static void test_lk_rown_neon(void)
{
#if defined(__SSE2__) || (defined(__aarch64__) && defined(__ARM_NEON))
    enum { NX = 400, BS = 408 };
    static uint16_t z[NX], bg[4 * BS];
    static int32_t cz[NX];
    static uint8_t rz[2 * NX];
    for (int32_t r = 0; r < 4; ++r) {
        for (int32_t c = 0; c < BS; ++c) {
            bg[r * BS + c] = (uint16_t)(10 * c + 1000 * r);
        }
    }
    for (int32_t i = 0; i < NX; ++i) {
        z[i] = 5000u;
        cz[i] = 0;
    }
    memcpy(rz, z, sizeof(z));
    const uint32_t par[6] = {0xFFFFu, 1u, 65535u, 0u, 0u, 0u};
    int64_t s[6] = {0, 0, 0, 0, 0, 0};
    uint32_t n = 0u;
    /* n 14: samples 0 .. 6 in the block (8 + 7 > 14), e = 5000 - (1000 + 10 (i + 1)) */
    TEST_ASSERT_EQUAL_INT32(8, pft_pre_lk_rowv_(rz, cz, bg, BS, par, 2, 14, s, &n));
    const int64_t k_all[6] = {4 * 3600, 4 * 360000, 4 * 36000000, 60 * 15840, 6000 * 15840, 62728400};
    TEST_ASSERT_EQUAL_INT64_ARRAY(k_all, s, 6);
    TEST_ASSERT_EQUAL_UINT32(4u, n);
    z[2] = 0u; /* below lo: sample 2 (e 3970) masked */
    memcpy(rz, z, sizeof(z));
    memset(s, 0, sizeof(s));
    n = 7u; /* added to */
    TEST_ASSERT_EQUAL_INT32(8, pft_pre_lk_rowv_(rz, cz, bg, BS, par, 2, 14, s, &n));
    const int64_t k_one[6] = {3 * 3600, 3 * 360000, 3 * 36000000, 60 * 11870, 6000 * 11870, 46967500};
    TEST_ASSERT_EQUAL_INT64_ARRAY(k_one, s, 6);
    TEST_ASSERT_EQUAL_UINT32(10u, n);
    TEST_ASSERT_EQUAL_INT32(0, pft_pre_lk_rowv_(rz, cz, bg, BS, par, 2, 6, s, &n)); /* no block */
    TEST_ASSERT_EQUAL_UINT32(10u, n);
    /* step 4, n 30: samples 0, 4, 8, 12 (16 + 15 > 30; pixel 2, masked, is not a sample) */
    memset(s, 0, sizeof(s));
    n = 0u;
    TEST_ASSERT_EQUAL_INT32(16, pft_pre_lk_rowv_(rz, cz, bg, BS, par, 4, 30, s, &n));
    const int64_t k_st4[6] = {4 * 3600, 4 * 360000, 4 * 36000000, 60 * 15720, 6000 * 15720, 61787600};
    TEST_ASSERT_EQUAL_INT64_ARRAY(k_st4, s, 6);
    TEST_ASSERT_EQUAL_UINT32(4u, n);
    TEST_ASSERT_EQUAL_INT32(0, pft_pre_lk_rowv_(rz, cz, bg, BS, par, 4, 14, s, &n)); /* no block */
    TEST_ASSERT_EQUAL_UINT32(4u, n);
    /* negative gradients, e near +-2^30: bg 65535 - (10 c + 1000 r), z 5000, colnow -2^30 at
     * samples 0 and 4, 2^30 at 2 and 6, e = 5000 - colnow - (64535 - 10 (i + 1)) */
    for (int32_t r = 0; r < 4; ++r) {
        for (int32_t c = 0; c < BS; ++c) {
            bg[r * BS + c] = (uint16_t)(65535 - 10 * c - 1000 * r);
        }
    }
    for (int32_t i = 0; i < NX; ++i) {
        z[i] = 5000u;
        cz[i] = (i % 4 == 0 ? -1 : 1) * 1073741824;
    }
    memcpy(rz, z, sizeof(z));
    memset(s, 0, sizeof(s));
    n = 0u;
    TEST_ASSERT_EQUAL_INT32(8, pft_pre_lk_rowv_(rz, cz, bg, BS, par, 2, 14, s, &n));
    /* e = 1073682299, -1073801329, 1073682339, -1073801289 (sum -237980) */
    const int64_t k_neg[6] = {4 * 3600, 4 * 360000, 4 * 36000000, 60 * 237980, 6000 * 237980, 4611685946686664084};
    TEST_ASSERT_EQUAL_INT64_ARRAY(k_neg, s, 6);
    TEST_ASSERT_EQUAL_UINT32(4u, n);
    uint32_t cases = 0u, masked = 0u;
    for (int32_t t = 0; t < 800; ++t) {
        const int32_t st = t < 400 ? 2 : 4;
        const uint32_t bits = 12u + (uint32_t)t % 5u;
        const uint32_t lo = pft_test_xorshift32(&g_rs) % 64u, span = (1u << bits) - lo - pft_test_xorshift32(&g_rs) % 64u;
        const uint32_t pr[6] = {(1u << bits) - 1u, lo, span, 16u - bits, pft_test_xorshift32(&g_rs) % 256u,
                                pft_test_xorshift32(&g_rs) % 256u};
        const int32_t ns = t % 400 < 370 ? t % 41 : 360;
        const int32_t kind = (t / 5) % 3;
        for (int32_t i = 0; i < NX; ++i) {
            z[i] = (uint16_t)pft_test_xorshift32(&g_rs); /* bits above the depth too */
            cz[i] = t % 3 == 0 ? (int32_t)(pft_test_xorshift32(&g_rs) % 268435457u) - 134217728
                               : (int32_t)(pft_test_xorshift32(&g_rs) % 2097153u) - 1048576;
        }
        for (int32_t i = 0; i < 4 * BS; ++i) {
            const uint32_t r = pft_test_xorshift32(&g_rs);
            bg[i] = kind == 0 ? (uint16_t)r : (kind == 1 ? ((r & 1u) != 0u ? 65535u : 0u) : (uint16_t)(65535u - r % 8u));
        }
        memcpy(rz, z, sizeof(z));
        int64_t got[6] = {1, -2, 3, -4, 5, -6}, want[6] = {1, -2, 3, -4, 5, -6};
        uint32_t gn = 3u, wn = 3u;
        const int32_t ie = (ns + 1) / (4 * st) * (4 * st);
        lk_row_ref(z, cz, bg, BS, pr, st, ie, want, &wn);
        TEST_ASSERT_EQUAL_INT32(ie, pft_pre_lk_rowv_(rz, cz, bg, BS, pr, st, ns, got, &gn));
        TEST_ASSERT_EQUAL_INT64_ARRAY(want, got, 6);
        TEST_ASSERT_EQUAL_UINT32(wn, gn);
        masked += (uint32_t)(ie / st) - (wn - 3u);
        cases++;
    }
    TEST_ASSERT_EQUAL_UINT32(800u, cases);
    TEST_ASSERT_TRUE(masked > 0u); /* the invalid samples were reached */
#else
    TEST_IGNORE_MESSAGE("x86-64 (SSE2) and AArch64 (NEON) only: the other targets keep the plain loop");
#endif
}

#if defined(__aarch64__) && defined(__ARM_NEON)
/* Internal to the library (lib/src/pre/pre_int.h, AArch64 with NEON only); the test declares it. */
uint32_t pft_pre_count_rowv_(const uint8_t *row, uint32_t w, uint32_t mask, uint32_t lo, uint32_t span,
                             uint32_t cnt[2]);
#endif

/* AArch64's count of a row's masked pixels by cause in NEON lanes (pft_pre_count_rowv_, the
 * whole blocks of 8 pixels of a U16 row without a bad-pixel map): known answers (dead below lo,
 * saturated at lo + span and above, bits above the depth ignored, the pixels after the last
 * whole block left), then the counts and the pixels done equal to the plain rule (v - lo >=
 * span: dead if v < lo, else saturated) on 300 random rows (depths 12 .. 16, random lo and
 * span, rows of 0 .. 40 and 384 pixels, values near lo and lo + span). */
static void test_count_rown_neon(void)
{
#if defined(__aarch64__) && defined(__ARM_NEON)
    enum { NX = 384 };
    static uint16_t z[NX];
    static uint8_t rz[2 * NX];
    /* depth 14 (mask 16383), lo 100, span 16000: valid 100 .. 16099 */
    const uint16_t k_row[20] = {99u, 100u, 16099u, 16100u, 16383u, 0u, 16384u + 50u, 16384u + 500u,
                                5u, 16200u, 7u, 7u, 7u, 7u, 7u, 7u, 0u, 0u, 0u, 0u};
    memcpy(z, k_row, sizeof(k_row));
    memcpy(rz, z, sizeof(k_row));
    uint32_t cnt[2] = {10u, 20u}; /* added to */
    TEST_ASSERT_EQUAL_UINT32(16u, pft_pre_count_rowv_(rz, 20u, 16383u, 100u, 16000u, cnt));
    /* dead: 99, 0, 50 (16434 & 16383), 5, six 7s: 10; saturated: 16100, 16383, 16200: 3;
     * 100, 16099 and 500 (16884 & 16383) valid; pixels 16 .. 19 left */
    TEST_ASSERT_EQUAL_UINT32(20u, cnt[0]);
    TEST_ASSERT_EQUAL_UINT32(23u, cnt[1]);
    TEST_ASSERT_EQUAL_UINT32(0u, pft_pre_count_rowv_(rz, 7u, 16383u, 100u, 16000u, cnt)); /* no block */
    TEST_ASSERT_EQUAL_UINT32(20u, cnt[0]);
    uint32_t cases = 0u, nd = 0u, ns = 0u;
    for (int32_t t = 0; t < 300; ++t) {
        const uint32_t bits = 12u + (uint32_t)t % 5u, mask = (1u << bits) - 1u;
        const uint32_t lo = pft_test_xorshift32(&g_rs) % 300u;
        const uint32_t span = (1u << bits) - lo - pft_test_xorshift32(&g_rs) % 300u;
        const uint32_t w = t < 280 ? (uint32_t)t % 41u : NX;
        for (uint32_t i = 0; i < NX; ++i) {
            const uint32_t r = pft_test_xorshift32(&g_rs);
            z[i] = (uint16_t)((r & 3u) == 0u ? r >> 16 : ((r & 3u) == 1u ? lo + (r >> 8) % 5u - 2u : lo + span + (r >> 8) % 5u - 2u));
        }
        memcpy(rz, z, sizeof(z));
        uint32_t got[2] = {3u, 4u}, want[2] = {3u, 4u};
        const uint32_t xe = w / 8u * 8u;
        for (uint32_t i = 0; i < xe; ++i) {
            const uint32_t v = z[i] & mask;
            if (v - lo >= span) {
                want[v < lo ? 0 : 1]++;
            }
        }
        TEST_ASSERT_EQUAL_UINT32(xe, pft_pre_count_rowv_(rz, w, mask, lo, span, got));
        TEST_ASSERT_EQUAL_UINT32_ARRAY(want, got, 2);
        nd += want[0] - 3u;
        ns += want[1] - 4u;
        cases++;
    }
    TEST_ASSERT_EQUAL_UINT32(300u, cases);
    TEST_ASSERT_TRUE(nd > 0u && ns > 0u); /* both causes reached */
#else
    TEST_IGNORE_MESSAGE("AArch64 (NEON) only: the other targets keep the plain loop");
#endif
}

#if defined(__aarch64__) && defined(__ARM_NEON)
/* Internal to the library (lib/src/pre/pre_int.h, AArch64 with NEON only); the test declares it. */
void pft_pre_stale_res_n_(const uint8_t *const a[4], int32_t nr, int32_t sw, uint32_t n, uint8_t *hm,
                          int32_t k1, int32_t xlo, int32_t xhi, int32_t ca, int32_t cb, int16_t *r);

/* stale_anchor_res_'s loops as the library's plain form writes them (the clamped indices). */
static void stale_res_ref(const uint8_t *const a[4], int32_t nr, int32_t sw, uint32_t n, uint8_t *hm,
                          int32_t k1, int32_t xlo, int32_t xhi, int32_t ca, int32_t cb, int16_t *r)
{
    for (int32_t c = 0; c < sw; ++c) {
        uint32_t m = 0u;
        for (int32_t i = 0; i < nr; ++i) {
            m = a[i][c] > m ? a[i][c] : m;
        }
        hm[c] = (uint8_t)(m > n ? 1u : 0u);
    }
    for (int32_t x = ca; x <= cb; ++x) {
        bool st = false;
        for (int32_t i = xlo; i <= xhi; ++i) {
            const int32_t j = x + k1 + i;
            st = st || hm[j < 0 ? 0 : (j > sw - 1 ? sw - 1 : j)] != 0u;
        }
        r[x] = st ? PFT_RES16_MASKED : r[x];
    }
}
#endif

/* AArch64's stale columns of the anchored residual (pft_pre_stale_res_n_: the largest age of
 * up to four rows per column in byte lanes, the residual's pixels masked 8 at a time where no
 * tap index is clamped): known answers (one stale cell masks the pixels whose taps reach it, at
 * the row's start, inside and at its end, n 255 masks nothing), then hm and the residual row
 * equal to the plain loops' on 600 random cases (1 .. 4 rows, tap ranges -1 .. 2, shifts k1
 * -1 .. 2, rows of 1 .. 40 and 387 columns, ages 0 .. 127 and 255 around n). */
static void test_stale_res_neon(void)
{
#if defined(__aarch64__) && defined(__ARM_NEON)
    enum { SW = 387, RW = 384 };
    static uint8_t ag[4][SW], hm[SW], hw[SW];
    static int16_t r[RW], rw[RW];
    const uint8_t *a[4] = {ag[0], ag[1], ag[2], ag[3]};
    memset(ag, 0, sizeof(ag));
    ag[1][0] = 40u;   /* column 0: pixels x with x + 1 + i = 0: x = -1 - i, i.e. x 0 at i = -1 */
    ag[2][100] = 33u; /* column 100: x 97 .. 100 (taps -1 .. 2, k1 1) */
    ag[0][386] = 90u; /* the last column: x 383 (the row ends there) */
    ag[3][200] = 32u; /* not above n: none */
    for (int32_t x = 0; x < RW; ++x) {
        r[x] = (int16_t)x;
    }
    pft_pre_stale_res_n_(a, 4, SW, 32u, hm, 1, -1, 2, 0, RW - 1, r);
    for (int32_t x = 0; x < RW; ++x) {
        const bool st = x == 0 || (x >= 97 && x <= 100) || x >= 383;
        TEST_ASSERT_EQUAL_INT16(st ? PFT_RES16_MASKED : (int16_t)x, r[x]);
    }
    TEST_ASSERT_EQUAL_UINT8(1u, hm[100]);
    TEST_ASSERT_EQUAL_UINT8(0u, hm[200]);
    for (int32_t x = 0; x < RW; ++x) {
        r[x] = (int16_t)x;
    }
    pft_pre_stale_res_n_(a, 4, SW, 255u, hm, 1, -1, 2, 0, RW - 1, r); /* nothing above 255 */
    for (int32_t x = 0; x < RW; ++x) {
        TEST_ASSERT_EQUAL_INT16((int16_t)x, r[x]);
    }
    uint32_t cases = 0u, masked = 0u;
    for (int32_t t = 0; t < 600; ++t) {
        const int32_t nr = 1 + t % 4;
        const int32_t sw = t % 3 == 0 ? SW : 4 + (int32_t)(pft_test_xorshift32(&g_rs) % 37u);
        const int32_t w = sw - 3;
        const uint32_t n = (t / 4) % 5 == 4 ? 300u : 30u + pft_test_xorshift32(&g_rs) % 8u;
        const int32_t xlo = -(int32_t)(pft_test_xorshift32(&g_rs) % 2u);
        const int32_t xhi = xlo + (int32_t)(pft_test_xorshift32(&g_rs) % (uint32_t)(4 + xlo));
        const int32_t k1 = (int32_t)(pft_test_xorshift32(&g_rs) % 4u) - 1;
        const int32_t ca = (int32_t)(pft_test_xorshift32(&g_rs) % 3u);
        const int32_t cb = w - 1 - (int32_t)(pft_test_xorshift32(&g_rs) % 3u);
        for (int32_t i = 0; i < 4; ++i) {
            for (int32_t c = 0; c < SW; ++c) {
                const uint32_t v = pft_test_xorshift32(&g_rs);
                ag[i][c] = (uint8_t)((v & 31u) == 0u ? 30u + (v >> 8) % 10u : ((v & 255u) == 1u ? 255u : (v >> 8) % 30u));
            }
        }
        for (int32_t x = 0; x < RW; ++x) {
            r[x] = (int16_t)pft_test_xorshift32(&g_rs);
            rw[x] = r[x];
        }
        memset(hm, 7, sizeof(hm));
        memset(hw, 7, sizeof(hw));
        stale_res_ref(a, nr, sw, n, hw, k1, xlo, xhi, ca, cb, rw);
        pft_pre_stale_res_n_(a, nr, sw, n, hm, k1, xlo, xhi, ca, cb, r);
        TEST_ASSERT_EQUAL_UINT8_ARRAY(hw, hm, SW);
        TEST_ASSERT_EQUAL_INT16_ARRAY(rw, r, RW);
        for (int32_t x = ca; x <= cb; ++x) {
            masked += r[x] == PFT_RES16_MASKED ? 1u : 0u;
        }
        cases++;
    }
    TEST_ASSERT_EQUAL_UINT32(600u, cases);
    TEST_ASSERT_TRUE(masked > 0u);
#else
    TEST_IGNORE_MESSAGE("AArch64 (NEON) only: the other targets keep the plain loops");
#endif
}

#if defined(__SSE2__)
/* Internal to the library (lib/src/pre/pre_int.h, x86-64 only); the test declares them. */
int32_t pft_pre_hrow8_(const int32_t *zl, const int16_t *zs, int32_t ub, const int32_t w[4], int32_t ulo,
                       int32_t uhi, int32_t *hz, int32_t ja, int32_t jb);
int32_t pft_pre_vsplit8_(const uint16_t *const t[4], const int32_t w[4], int32_t *vb, int32_t i0, int32_t c1);
uint32_t pft_pre_zspan8_(const uint8_t *row, uint32_t mask, uint32_t lo, uint32_t span, uint32_t bf,
                         const int32_t *cn, int32_t *zl, uint32_t x0, uint32_t x1, uint32_t *ninv);

#define HN 200 /* frame columns of the update pass's rows tested */

/* anchor_hrow_'s cell j in its general form (hcell_): PFT_PRE_ANONE_ (-2^22) when one of the
 * taps ulo .. uhi is masked, else (sum of w zl + 8) >> 4 (the weights sum to 256). */
static int32_t hcell_ref(const int32_t *zl, int32_t ub, const int32_t w[4], int32_t ulo, int32_t uhi, int32_t j)
{
    int64_t sv = 0;
    for (int32_t i = -1; i <= 2; ++i) {
        const int32_t z = zl[j + ub + i];
        if (z < 0 && i >= ulo && i <= uhi) {
            return -4194304;
        }
        sv += (int64_t)w[i + 1] * (z < 0 ? 0 : z);
    }
    return (int32_t)((sv + 8) >> 4);
}
#endif

/* x86-64's blend of the anchored update's row (pft_pre_hrow8_: 8 cells per SSE2 block, the
 * rest left to the loop) against hcell_'s general form: known answers (a constant row; the
 * cubic on 0, 65535, 65535, 0; a masked pixel making the four cells that tap it, or the two
 * that test it with linear weights, PFT_PRE_ANONE_), then random rows with masked pixels,
 * extreme values, both tap offsets and every tested-tap set; and the residual's vertical
 * blends in the split form (pft_pre_vsplit8_) against pft_pre_vsplit_ of the blend of
 * 16 x 16-bit products, with known answers. */
static void test_update_rows_sse2(void)
{
#if defined(__SSE2__)
    static int32_t zl[HN], hz[HN + 3];
    static int16_t zs[HN];
    const int32_t cub[4] = {-16, 144, 144, -16};
    for (int32_t x = 0; x < HN; ++x) {
        zl[x] = 1000;
        zs[x] = (int16_t)(zl[x] - 32768);
    }
    TEST_ASSERT_EQUAL_INT32(2 + 8 * 24, pft_pre_hrow8_(zl, zs, -1, cub, -1, 2, hz, 2, 196));
    for (int32_t j = 2; j < 2 + 8 * 24; ++j) {
        TEST_ASSERT_EQUAL_INT32(16000, hz[j + 1]); /* (256 * 1000 + 8) >> 4 */
    }
    for (int32_t x = 0; x < HN; ++x) { /* 0, 65535, 65535, 0, ... */
        zl[x] = (x & 3) == 1 || (x & 3) == 2 ? 65535 : 0;
        zs[x] = (int16_t)(zl[x] - 32768);
    }
    TEST_ASSERT_EQUAL_INT32(10, pft_pre_hrow8_(zl, zs, -1, cub, -1, 2, hz, 2, 9));
    for (int32_t j = 2; j < 10; ++j) { /* taps j - 2 .. j + 1 */
        /* (288 65535 + 8) >> 4, (128 65535 + 8) >> 4, (-32 65535 + 8) >> 4 */
        const int32_t k_want[4] = {1179630, 524280, -131070, 524280};
        TEST_ASSERT_EQUAL_INT32(k_want[(j + 2) & 3], hz[j + 1]);
    }
    for (int32_t x = 0; x < HN; ++x) {
        zl[x] = 1000;
        zs[x] = (int16_t)(zl[x] - 32768);
    }
    zl[20] = -1; /* masked: its int16 copy 32767, as anchor_hrow_'s */
    zs[20] = 32767;
    TEST_ASSERT_EQUAL_INT32(34, pft_pre_hrow8_(zl, zs, -1, cub, -1, 2, hz, 10, 35));
    for (int32_t j = 10; j < 34; ++j) { /* cells 19 .. 22 tap column 20 */
        TEST_ASSERT_EQUAL_INT32(j >= 19 && j <= 22 ? -4194304 : 16000, hz[j + 1]);
    }
    const int32_t lin[4] = {0, 200, 56, 0}; /* taps 0 .. 1 tested: cells 20, 21 */
    TEST_ASSERT_EQUAL_INT32(34, pft_pre_hrow8_(zl, zs, -1, lin, 0, 1, hz, 10, 35));
    for (int32_t j = 10; j < 34; ++j) {
        TEST_ASSERT_EQUAL_INT32(j == 20 || j == 21 ? -4194304 : 16000, hz[j + 1]);
    }
    TEST_ASSERT_EQUAL_INT32(5, pft_pre_hrow8_(zl, zs, -1, cub, -1, 2, hz, 5, 11)); /* no block */
    uint32_t cases = 0u;
    for (int32_t it = 0; it < 600; ++it) {
        int32_t w[4];
        const int32_t f = (int32_t)(pft_test_xorshift32(&g_rs) & 255u);
        if ((it & 1) != 0) {
            view_cubic(f, w);
        } else {
            w[0] = 0; w[1] = 256 - f; w[2] = f; w[3] = 0;
        }
        const int32_t ulo = w[0] != 0 ? -1 : 0, uhi = w[3] != 0 ? 2 : (w[2] != 0 ? 1 : 0);
        const int32_t ub = (it & 2) != 0 ? -1 : -2;
        const uint32_t kind = (uint32_t)it % 3u;
        for (int32_t x = 0; x < HN; ++x) {
            const uint32_t r = pft_test_xorshift32(&g_rs);
            int32_t z = (int32_t)(r & 65535u);
            if (kind == 1u) {
                z = (r >> 16 & 1u) != 0u ? 65535 : 0;
            }
            if ((r >> 20 & 15u) == 0u) {
                z = -1;
            }
            zl[x] = z;
            zs[x] = (int16_t)((int32_t)((uint32_t)z & 0xFFFFu) - 32768);
        }
        const int32_t ja = 3 + (int32_t)(pft_test_xorshift32(&g_rs) % 20u);
        const int32_t jb = HN - 3 - (int32_t)(pft_test_xorshift32(&g_rs) % 40u);
        for (int32_t j = 0; j < HN + 3; ++j) {
            hz[j] = 12345;
        }
        const int32_t je = pft_pre_hrow8_(zl, zs, ub, w, ulo, uhi, hz, ja, jb);
        TEST_ASSERT_EQUAL_INT32(ja + 8 * ((jb - ja + 1) / 8), je);
        for (int32_t j = 0; j < HN + 2; ++j) {
            TEST_ASSERT_EQUAL_INT32(j >= ja && j < je ? hcell_ref(zl, ub, w, ulo, uhi, j) : 12345, hz[j + 1]);
        }
        cases++;
    }
    TEST_ASSERT_EQUAL_UINT32(600u, cases);

    static uint16_t rows[4][HN];
    static int32_t vb[HN];
    const uint16_t *const t[4] = {rows[0], rows[1], rows[2], rows[3]};
    for (int32_t i = 0; i < HN; ++i) {
        for (int j = 0; j < 4; ++j) {
            rows[j][i] = 65535u;
        }
    }
    TEST_ASSERT_EQUAL_INT32(192, pft_pre_vsplit8_(t, cub, vb, 0, 197));
    TEST_ASSERT_EQUAL_INT32(536805488, pft_pre_vsplit_(1048560)); /* 65535 * 16 = 128 * 8191 + 112 */
    for (int32_t i = 0; i < 192; ++i) {
        TEST_ASSERT_EQUAL_INT32(pft_pre_vsplit_(1048560), vb[i]);
    }
    for (int32_t i = 0; i < HN; ++i) {
        rows[0][i] = rows[3][i] = (i & 1) != 0 ? 65535u : 0u;
        rows[1][i] = rows[2][i] = (i & 1) != 0 ? 0u : 65535u;
    }
    TEST_ASSERT_EQUAL_INT32(17, pft_pre_vsplit8_(t, cub, vb, 1, 17));
    for (int32_t i = 1; i < 17; ++i) { /* 1179630 and -131070, as above */
        TEST_ASSERT_EQUAL_INT32(pft_pre_vsplit_((i & 1) != 0 ? -131070 : 1179630), vb[i]);
    }
    for (int32_t it = 0; it < 400; ++it) {
        int32_t w[4];
        view_cubic((int32_t)(pft_test_xorshift32(&g_rs) & 255u), w);
        for (int32_t i = 0; i < HN; ++i) {
            for (int j = 0; j < 4; ++j) {
                const uint32_t r = pft_test_xorshift32(&g_rs);
                rows[j][i] = (uint16_t)((it & 1) != 0 ? r & 65535u : ((r >> 16 & 1u) != 0u ? 65535u : 0u));
            }
        }
        const int32_t i0 = (int32_t)(pft_test_xorshift32(&g_rs) % 16u);
        const int32_t c1 = HN - 1 - (int32_t)(pft_test_xorshift32(&g_rs) % 16u);
        for (int32_t i = 0; i < HN; ++i) {
            vb[i] = 7;
        }
        const int32_t ie = pft_pre_vsplit8_(t, w, vb, i0, c1);
        TEST_ASSERT_EQUAL_INT32(i0 + 8 * ((c1 - i0 + 1) / 8), ie);
        for (int32_t i = 0; i < HN; ++i) {
            int32_t v = 0;
            for (int j = 0; j < 4; ++j) {
                v += w[j] * ((int32_t)rows[j][i] - 32768);
            }
            TEST_ASSERT_EQUAL_INT32(i >= i0 && i < ie ? pft_pre_vsplit_((v + 256 * 32768 + 8) >> 4) : 7, vb[i]);
        }
    }
#else
    TEST_IGNORE_MESSAGE("x86-64 (SSE2) only: the other targets keep the loops");
#endif
}

/* x86-64's conversion of a U16 frame row (pft_pre_zspan8_: 8 pixels per SSE2 block) against
 * zspan_'s loop: known answers (both clamps, dead, saturated and out-of-mask pixels), then
 * random rows, column offsets, masks, limits (span 0, lo above 65535, the widest span) and
 * shifts. */
static void test_zspan_sse2(void)
{
#if defined(__SSE2__)
    static uint16_t raw[HN];
    static int32_t cn[HN], zl[HN], want[HN];
    /* mask 16383, lo 100, span 16000 (valid 100 .. 16099), bf 2 */
    const uint16_t k_raw[8] = {100u, 99u, 16099u, 16100u, 5000u, 5000u, 16383u | 16384u, 0u};
    const int32_t k_cn[8] = {0, 0, 0, 0, 30000, -60000, 0, 0};
    const int32_t k_want[8] = {400, -1, 64396, -1, 0, 65535, -1, -1};
    memcpy(raw, k_raw, sizeof(k_raw));
    memcpy(cn, k_cn, sizeof(k_cn));
    uint32_t ninv = 3u;
    TEST_ASSERT_EQUAL_UINT32(8u, pft_pre_zspan8_((const uint8_t *)raw, 16383u, 100u, 16000u, 2u, cn, zl, 0u, 9u, &ninv));
    TEST_ASSERT_EQUAL_INT32_ARRAY(k_want, zl, 8);
    TEST_ASSERT_EQUAL_UINT32(3u + 4u, ninv);
    TEST_ASSERT_EQUAL_UINT32(1u, pft_pre_zspan8_((const uint8_t *)raw, 16383u, 100u, 16000u, 2u, cn, zl, 1u, 8u, &ninv));
    const uint32_t lims[5][2] = {{100u, 16000u}, {0u, 0u}, {70000u, 5u}, {0u, 0xFFFFFFFFu}, {1u, 65534u}};
    for (int32_t it = 0; it < 500; ++it) {
        const uint32_t mask = (it & 1) != 0 ? 16383u : 65535u, bf = (uint32_t)it % 3u;
        const uint32_t lo = lims[it % 5][0], span = lims[it % 5][1];
        for (int32_t x = 0; x < HN; ++x) {
            const uint32_t r = pft_test_xorshift32(&g_rs);
            raw[x] = (uint16_t)((r & 1u) != 0u ? (r >> 1 & 65535u) : ((r >> 1 & 1u) != 0u ? 65535u : (r >> 2 & 127u)));
            cn[x] = (int32_t)(pft_test_xorshift32(&g_rs) % 200001u) - 100000;
            zl[x] = 7;
        }
        const uint32_t x0 = pft_test_xorshift32(&g_rs) % 16u, x1 = HN - pft_test_xorshift32(&g_rs) % 16u;
        uint32_t nwant = 0u;
        const uint32_t xe = x0 + 8u * ((x1 - x0) / 8u);
        for (uint32_t x = 0u; x < (uint32_t)HN; ++x) {
            const uint32_t v = (uint32_t)raw[x] & mask;
            int32_t zu = (int32_t)(v << bf) - cn[x];
            zu = zu < 0 ? 0 : (zu > 65535 ? 65535 : zu);
            const bool ok = v - lo < span;
            want[x] = x < x0 || x >= xe ? 7 : (ok ? zu : -1);
            nwant += x >= x0 && x < xe && !ok ? 1u : 0u;
        }
        ninv = 0u;
        TEST_ASSERT_EQUAL_UINT32(xe, pft_pre_zspan8_((const uint8_t *)raw, mask, lo, span, bf, cn, zl, x0, x1, &ninv));
        TEST_ASSERT_EQUAL_INT32_ARRAY(want, zl, HN);
        TEST_ASSERT_EQUAL_UINT32(nwant, ninv);
    }
#else
    TEST_IGNORE_MESSAGE("x86-64 (SSE2) only: the other targets keep the loop");
#endif
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_config_and_workspace);
    RUN_TEST(test_sharp_edges_drifting);
    RUN_TEST(test_integer_move_exact);
    RUN_TEST(test_degenerate_frames_flagged);
    RUN_TEST(test_refused_input_changes_nothing);
    RUN_TEST(test_residual_span_split_and_plain);
    RUN_TEST(test_gate_clip_split_and_plain);
    RUN_TEST(test_view_rows_sse2);
    RUN_TEST(test_view_h32_neon);
    RUN_TEST(test_lk_rown_neon);
    RUN_TEST(test_count_rown_neon);
    RUN_TEST(test_stale_res_neon);
    RUN_TEST(test_update_rows_sse2);
    RUN_TEST(test_zspan_sse2);
    return UNITY_END();
}
