/*
 * Clutter map held on B x B blocks of the scene (pft_pre_clutter_config_t.block, pft_pre.h
 * "Blocks"; docs/algorithms.md 9.9): the configuration check names "block", the workspace is
 * PFT_PRE_CLUTTER_WORKSPACE_BYTES_BLOCK and the map's share of it falls by B^2; every output
 * pixel and every block of the map equal a plain reference of the documented formulas (the
 * square's sum over the former block map with replicated edges, the block means of the
 * pixels' terms, the running mean and the persistence gate on the block's mean residual) over
 * 10 frames without scene motion, B 2 and 4, with and without the mean; a persistent blob is
 * learnt at the documented rate at block resolution (m_k = 16 (1 - (1 - a)^k) within 1 %, the
 * output 4 / sqrt(M_{k-1}) once M_{k-1} > thr); a 5 sigma point moving one pixel per frame
 * across the blocks keeps its value, as the formula gives while its blocks' read stays below
 * thr; a refused call changes nothing. 64 x 48 frames, integer residuals: every target.
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
static uint32_t g_rs = 1234567u;

static int16_t noise_q88(void)
{
    return (int16_t)pft_test_noise_q88(&g_rs);
}

static pft_frame_t res_frame(uint32_t seq)
{
    return pft_test_res16_frame(g_res, W, H, seq, 0u);
}

static void test_config_and_workspace(void)
{
    pft_pre_clutter_config_t cfg;
    pft_pre_clutter_config_default(&cfg);
    TEST_ASSERT_EQUAL_UINT8(0u, cfg.block);
    cfg.width = W;
    cfg.height = H;
    static const uint8_t bad[] = {1u, 3u, 5u, 8u, 255u};
    for (size_t i = 0; i < sizeof bad; ++i) {
        pft_pre_clutter_config_t b = cfg;
        b.block = bad[i];
        const char *field = NULL;
        TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_pre_clutter_config_check(&b, &field));
        TEST_ASSERT_EQUAL_STRING("block", field);
        TEST_ASSERT_EQUAL_UINT32(0u, (uint32_t)pft_pre_clutter_workspace_size(&b));
        pft_pre_clutter_t c;
        TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_pre_clutter_init(&c, &b, g_work, sizeof g_work));
    }
    /* block 0: the per-pixel macros, unchanged */
    TEST_ASSERT_EQUAL_UINT32((uint32_t)PFT_PRE_CLUTTER_WORKSPACE_BYTES(W, H, 0, 1, 0),
                             (uint32_t)PFT_PRE_CLUTTER_WORKSPACE_BYTES_BLOCK(W, H, 0, 1, 0, 0, 0));
    TEST_ASSERT_EQUAL_UINT32((uint32_t)PFT_PRE_CLUTTER_WORKSPACE_BYTES_INPLACE(W, H, 1, 3, 1),
                             (uint32_t)PFT_PRE_CLUTTER_WORKSPACE_BYTES_BLOCK(W, H, 1, 3, 1, 0, 1));
    for (uint8_t k = 2u; k <= 4u; k = (uint8_t)(k + 2u)) {
        for (int mean = 0; mean < 2; ++mean) {
            cfg.block = k;
            cfg.mean = mean != 0;
            cfg.persist = mean != 0 ? 4u : 0u;
            cfg.inplace = true;
            const size_t n = pft_pre_clutter_workspace_size(&cfg);
            TEST_ASSERT_EQUAL_UINT32((uint32_t)PFT_PRE_CLUTTER_WORKSPACE_BYTES_BLOCK(W, H, mean, 1, mean, k, 1), (uint32_t)n);
            /* the map, mu and the counter take 2 bytes per block each (W and H are multiples
             * of k; W H 2 / k^2 is a multiple of PFT_WS_ALIGN here): the mean and its counter
             * add 2 planes of W H 2 / k^2 bytes, per pixel 2 of W H 2 */
            cfg.mean = false;
            cfg.persist = 0u;
            const size_t n0 = pft_pre_clutter_workspace_size(&cfg);
            if (mean != 0) {
                TEST_ASSERT_EQUAL_UINT32((uint32_t)(2u * (size_t)NPIX * 2u / ((size_t)k * k)), (uint32_t)(n - n0));
                TEST_ASSERT_EQUAL_UINT32((uint32_t)(2u * (size_t)NPIX * 2u),
                                         (uint32_t)(PFT_PRE_CLUTTER_WORKSPACE_BYTES_BLOCK(W, H, 1, 1, 1, 0, 1) -
                                                    PFT_PRE_CLUTTER_WORKSPACE_BYTES_BLOCK(W, H, 0, 1, 0, 0, 1)));
            }
            cfg.mean = mean != 0;
            cfg.persist = mean != 0 ? 4u : 0u;
            pft_pre_clutter_t c;
            TEST_ASSERT_EQUAL_INT(PFT_ERR_NOMEM, pft_pre_clutter_init(&c, &cfg, g_work, n - 8u));
            TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_init(&c, &cfg, g_work, n));
            TEST_ASSERT_EQUAL_UINT32(1024u, pft_pre_clutter_at(&c, W - 1u, H - 1u));
        }
    }
}

/* ---- the plain reference of the block formulas (no scene motion) ---- */
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

static int32_t ref_scale(uint32_t a, int32_t d)
{
    const int64_t mag = ((int64_t)a * (d < 0 ? -(int64_t)d : (int64_t)d) + 32768) >> 16;
    return d < 0 ? -(int32_t)mag : (int32_t)mag;
}

#define GMAX ((W / 2) * (H / 2))
static uint16_t r_m[GMAX], r_mu[GMAX], r_pc[GMAX], r_m0[GMAX];
static int16_t r_out[NPIX];

static void ref_init(void)
{
    for (int i = 0; i < GMAX; ++i) {
        r_m[i] = 1024u;
        r_mu[i] = 32768u;
        r_pc[i] = 0u;
    }
}

/* One frame n (1, 2, ...) of the reference: cfg's blur, box, thr, alpha, mean, persist, excess. */
static void ref_frame(const pft_pre_clutter_config_t *cfg, uint32_t n)
{
    const int k = cfg->block, gw = W / k, gh = H / k, b = cfg->blur;
    const uint32_t area = (uint32_t)((2 * b + 1) * (2 * b + 1));
    const uint32_t a1 = (65536u + n / 2u) / n, a = a1 > cfg->alpha ? a1 : cfg->alpha;
    memcpy(r_m0, r_m, sizeof r_m);
    for (int j = 0; j < gh; ++j) {
        for (int i = 0; i < gw; ++i) {
            uint32_t sum = 0u;
            for (int dy = -b; dy <= b; ++dy) {
                for (int dx = -b; dx <= b; ++dx) {
                    const int yy = j + dy < 0 ? 0 : (j + dy >= gh ? gh - 1 : j + dy);
                    const int xx = i + dx < 0 ? 0 : (i + dx >= gw ? gw - 1 : i + dx);
                    sum += r_m0[yy * gw + xx];
                }
            }
            const int gi = j * gw + i;
            const int32_t mu = cfg->mean ? ref_div((int32_t)r_mu[gi] - 32768, 8) : 0;
            uint64_t st = 0u;
            int32_t smu = 0, sv = 0;
            uint32_t cnt = 0u;
            for (int y = j * k; y < j * k + k; ++y) {
                for (int x = i * k; x < i * k + k; ++x) {
                    const int32_t v = g_res[y * W + x];
                    if (v == PFT_RES16_MASKED) {
                        r_out[y * W + x] = PFT_RES16_MASKED;
                        continue;
                    }
                    const int32_t cv = v - mu;
                    int32_t wv = cv;
                    if (sum > cfg->thr * area) {
                        const uint32_t mm = (sum + area / 2u) / area;
                        wv = ref_div(cv * 1024, (int32_t)ref_isqrt((uint64_t)mm << 10));
                    }
                    r_out[y * W + x] = (int16_t)(wv > 32767 ? 32767 : (wv < -32767 ? -32767 : wv));
                    const uint64_t sq = (uint64_t)((int64_t)cv * cv);
                    st += sq >= 4194304u ? 65535u : (sq + 32u) >> 6;
                    smu += v * 8 > 16384 ? 16384 : (v * 8 < -16384 ? -16384 : v * 8);
                    sv += v;
                    cnt++;
                }
            }
            if (cnt == 0u) {
                continue;
            }
            const int32_t t = (int32_t)((st + cnt / 2u) / cnt);
            const int32_t nm = (int32_t)r_m[gi] + ref_scale(a, t - (int32_t)r_m[gi]);
            r_m[gi] = (uint16_t)(nm < 0 ? 0 : (nm > 65535 ? 65535 : nm));
            if (!cfg->mean) {
                continue;
            }
            int learn = 1;
            if (cfg->persist != 0u) {
                const int32_t rb = ref_div(sv, (int32_t)cnt);
                const uint32_t av = (uint32_t)(rb < 0 ? -rb : rb), pk = cfg->persist * 256u;
                const uint32_t p0 = r_pc[gi];
                const uint32_t p1 = av > cfg->excess ? (p0 + 256u > 2u * pk ? 2u * pk : p0 + 256u)
                                                     : (p0 > 128u ? p0 - 128u : 0u);
                r_pc[gi] = (uint16_t)p1;
                learn = av <= cfg->excess || p1 >= pk;
            }
            if (learn) {
                const int32_t tv = ref_div(smu, (int32_t)cnt), mv = (int32_t)r_mu[gi] - 32768;
                r_mu[gi] = (uint16_t)(mv + ref_scale(a, tv - mv) + 32768);
            }
        }
    }
}

static void test_matches_reference(void)
{
    for (int v = 0; v < 4; ++v) {
        pft_pre_clutter_config_t cfg;
        pft_pre_clutter_config_default(&cfg);
        cfg.width = W;
        cfg.height = H;
        cfg.block = (uint8_t)(v % 2 == 0 ? 2u : 4u);
        cfg.alpha = 13107u;
        cfg.blur = v < 2 ? 1u : 2u;
        if (v >= 2) {
            cfg.mean = true;
            cfg.persist = 3u;
        }
        pft_pre_clutter_t c;
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_init(&c, &cfg, g_work, sizeof g_work));
        ref_init();
        int scored = 0;
        for (uint32_t n = 1u; n <= 10u; ++n) {
            for (int i = 0; i < NPIX; ++i) {
                g_res[i] = noise_q88();
            }
            for (int y = 10; y < 22; ++y) {
                for (int x = 20; x < 33; ++x) {
                    g_res[y * W + x] = (int16_t)(g_res[y * W + x] + 1024); /* a blob of +4 */
                }
            }
            g_res[30 * W + (int)n * 3] = 1536;              /* a moving point */
            for (int x = 40; x < 44; ++x) {                 /* a fully masked 4 x 4 block */
                for (int y = 4; y < 8; ++y) {
                    g_res[y * W + x] = PFT_RES16_MASKED;
                }
            }
            g_res[(int)(n * 7u) % NPIX] = PFT_RES16_MASKED;
            pft_frame_t f = res_frame(n);
            TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_update(&c, &f, 0, 0, true));
            ref_frame(&cfg, n);
            const int16_t *o = pft_test_clutter_out(&c);
            for (int i = 0; i < NPIX; ++i) {
                TEST_ASSERT_EQUAL_INT16(r_out[i], o[i]);
                scored += (o[i] != g_res[i] && cfg.mean == false) ? 1 : 0;
            }
            for (uint32_t y = 0; y < H; ++y) {
                for (uint32_t x = 0; x < W; ++x) {
                    TEST_ASSERT_EQUAL_UINT32(r_m[(y / cfg.block) * (W / cfg.block) + x / cfg.block],
                                             pft_pre_clutter_at(&c, x, y));
                }
            }
        }
        if (!cfg.mean) {
            TEST_ASSERT_GREATER_THAN_INT(0, scored); /* the blob was scored in its sigma */
        }
    }
}

/* Twelve zero frames: the map settles at 0 (the first frame's weight is 1). */
static void settle_on_zero(pft_pre_clutter_t *c)
{
    memset(g_res, 0, sizeof g_res);
    for (uint32_t k = 0; k < 12u; ++k) {
        pft_frame_t f = res_frame(k + 1u);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_update(c, &f, 0, 0, true));
    }
}

static void test_persistent_blob_learnt_at_rate(void)
{
    for (uint8_t k = 2u; k <= 4u; k = (uint8_t)(k + 2u)) {
        pft_pre_clutter_config_t cfg;
        pft_pre_clutter_config_default(&cfg); /* alpha 0.1, blur 1 (3 x 3 blocks), thr 2 */
        cfg.width = W;
        cfg.height = H;
        cfg.block = k;
        pft_pre_clutter_t c;
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_init(&c, &cfg, g_work, sizeof g_work));
        settle_on_zero(&c);
        /* a 4 sigma blob on x, y 16..31 (whole blocks); (24, 24) lies in a block whose 3 x 3
         * blocks are all inside it for k 2 and 4 */
        memset(g_res, 0, sizeof g_res);
        for (int y = 16; y < 32; ++y) {
            for (int x = 16; x < 32; ++x) {
                g_res[y * W + x] = 1024;
            }
        }
        const double a = 6554.0 / 65536.0;
        double m_prev = 0.0;
        for (int n = 1; n <= 20; ++n) {
            pft_frame_t f = res_frame(100u + (uint32_t)n);
            TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_update(&c, &f, 0, 0, true));
            const double m = 16.0 * (1.0 - pow(1.0 - a, n));
            /* tolerance 1 %: the Q6.10 rounding of each step, at most n / 2 units of 1/1024 */
            TEST_ASSERT_DOUBLE_WITHIN(0.01 * m, m, pft_pre_clutter_at(&c, 24u, 24u) / 1024.0);
            const double got = pft_test_clutter_out(&c)[24 * W + 24] / 256.0;
            if (m_prev > 2.0 * 1.01) {
                /* scored in its sigma: 4 / sqrt(m_{n-1}), within the Q8.8 and the map's 1 % */
                TEST_ASSERT_DOUBLE_WITHIN(0.01 * 4.0 / sqrt(m_prev) + 1.0 / 256.0, 4.0 / sqrt(m_prev), got);
            } else if (m_prev < 2.0 * 0.99) {
                TEST_ASSERT_EQUAL_DOUBLE(4.0, got); /* below thr: the residual as it is */
            }
            m_prev = m;
        }
    }
}

static void test_moving_point_keeps_value(void)
{
    for (uint8_t k = 2u; k <= 4u; k = (uint8_t)(k + 2u)) {
        pft_pre_clutter_config_t cfg;
        pft_pre_clutter_config_default(&cfg);
        cfg.width = W;
        cfg.height = H;
        cfg.block = k;
        pft_pre_clutter_t c;
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_init(&c, &cfg, g_work, sizeof g_work));
        settle_on_zero(&c);
        /* the formula on a zero background: a 5 sigma point adds 25 / k^2 to its block's mean
         * term while it is there; block maps in sigma^2 (double), read over 3 x 3 blocks */
        static double bm[(W / 2) * (H / 2)];
        const int gw = W / k, gh = H / k;
        for (int i = 0; i < gw * gh; ++i) {
            bm[i] = 0.0;
        }
        const double a = 6554.0 / 65536.0;
        for (int n = 0; n < 40; ++n) {
            const int x = 4 + n, y = 20;
            const int bi = (y / k) * gw + x / k;
            double read = 0.0;
            for (int dy = -1; dy <= 1; ++dy) {
                for (int dx = -1; dx <= 1; ++dx) {
                    read += bm[(y / k + dy) * gw + x / k + dx];
                }
            }
            read /= 9.0;
            TEST_ASSERT_TRUE(read < 2.0); /* the formula: below thr, the output is the input */
            memset(g_res, 0, sizeof g_res);
            g_res[y * W + x] = 1280;
            pft_frame_t f = res_frame(100u + (uint32_t)n);
            TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_update(&c, &f, 0, 0, true));
            TEST_ASSERT_EQUAL_INT16(1280, pft_test_clutter_out(&c)[y * W + x]);
            for (int i = 0; i < gw * gh; ++i) {
                bm[i] += a * ((i == bi ? 25.0 / (k * k) : 0.0) - bm[i]);
            }
            /* the map at the point's block: the formula within the Q6.10 rounding (at most half
             * a unit per step, which the filter sums to at most 1 / (2 a) = 5 units) */
            TEST_ASSERT_DOUBLE_WITHIN(6.0 / 1024.0, bm[bi],
                                      pft_pre_clutter_at(&c, (uint32_t)x, (uint32_t)y) / 1024.0);
        }
    }
}

/* The block map moves with the scene: a scene drifting by one block (B px) per frame, given
 * as the shift, against the same scene held still; the integer grid step makes the warp exact,
 * so the moving map at (x + n B, y) equals the still map at (x, y) bit for bit, and the outputs
 * too, wherever the block's history stayed inside the frame. Then a half-block shift moves a
 * learnt blob's map by half a block (bilinear between the two blocks). */
static pft_pre_clutter_t g_still;
static uint64_t g_work2[sizeof(g_work) / 8];
static int16_t g_scene[NPIX];

static void test_map_moves_with_scene(void)
{
    for (uint8_t k = 2u; k <= 4u; k = (uint8_t)(k + 2u)) {
        pft_pre_clutter_config_t cfg;
        pft_pre_clutter_config_default(&cfg);
        cfg.width = W;
        cfg.height = H;
        cfg.block = k;
        cfg.alpha = 13107u;
        cfg.mean = true;
        cfg.persist = 2u;
        pft_pre_clutter_t c;
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_init(&c, &cfg, g_work, sizeof g_work));
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_init(&g_still, &cfg, g_work2, sizeof g_work2));
        const int nf = 4;
        for (int n = 0; n < nf; ++n) {
            /* the scene: a blob of +5 and noise, fixed in scene coordinates; frame n shows it
             * moved right by n k px; the still run sees it unmoved */
            for (int i = 0; i < NPIX; ++i) {
                g_scene[i] = noise_q88();
            }
            for (int y = 12; y < 28; ++y) {
                for (int x = 8; x < 20; ++x) {
                    g_scene[y * W + x] = (int16_t)(g_scene[y * W + x] + 1280);
                }
            }
            memcpy(g_res, g_scene, sizeof g_res);
            pft_frame_t f = res_frame((uint32_t)n + 1u);
            TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_update(&g_still, &f, 0, 0, true));
            for (int y = 0; y < H; ++y) {
                for (int x = 0; x < W; ++x) {
                    const int xs = x - n * k;
                    g_res[y * W + x] = xs >= 0 ? g_scene[y * W + xs] : (int16_t)0;
                }
            }
            TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_update(&c, &f, n > 0 ? (int32_t)k * 65536 : 0, 0, true));
            const int16_t *om = pft_test_clutter_out(&c), *os = pft_test_clutter_out(&g_still);
            /* blocks whose history and whose 3 x 3 read stayed inside: still-scene columns
             * from k (one block) to W - (n + 1) k */
            for (int y = 0; y < H; ++y) {
                for (int x = k; x + (n + 1) * k < W; ++x) {
                    TEST_ASSERT_EQUAL_UINT32(pft_pre_clutter_at(&g_still, (uint32_t)x, (uint32_t)y),
                                             pft_pre_clutter_at(&c, (uint32_t)(x + n * k), (uint32_t)y));
                    TEST_ASSERT_EQUAL_INT16(os[y * W + x], om[y * W + x + n * k]);
                }
            }
        }
        /* half a block (k / 2 px): each block takes the mean of itself and its left
         * neighbour (bilinear, Q8 weights 128 / 128: floor((m_i + m_(i-1) + 1) / 2)), then the
         * update with a zero frame: m - round(a m) (t = 0, a = alpha after 5 frames) */
        cfg.mean = false;
        cfg.persist = 0u;
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_init(&c, &cfg, g_work, sizeof g_work));
        for (int n = 0; n < 4; ++n) {
            memcpy(g_res, g_scene, sizeof g_res);
            pft_frame_t f = res_frame((uint32_t)n + 1u);
            TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_update(&c, &f, 0, 0, true));
        }
        uint32_t before[W];
        for (uint32_t x = 0; x < W; x += k) {
            before[x / k] = pft_pre_clutter_at(&c, x, 20u);
        }
        memset(g_res, 0, sizeof g_res);
        pft_frame_t f = res_frame(5u);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_update(&c, &f, (int32_t)k * 32768, 0, true));
        int differ = 0;
        for (uint32_t i = 1u; i < W / k; ++i) {
            const uint32_t wv = (before[i] + before[i - 1u] + 1u) / 2u;
            const uint32_t want = wv - (uint32_t)((13107u * wv + 32768u) >> 16);
            TEST_ASSERT_EQUAL_UINT32(want, pft_pre_clutter_at(&c, i * k, 20u));
            differ += before[i] != before[i - 1u] ? 1 : 0;
        }
        TEST_ASSERT_GREATER_THAN_INT(1, differ); /* the blob's edges were in the row */
    }
}

static void test_refused_input_changes_nothing(void)
{
    pft_pre_clutter_config_t cfg;
    pft_pre_clutter_config_default(&cfg);
    cfg.width = W;
    cfg.height = H;
    cfg.block = 4u;
    cfg.mean = true;
    cfg.persist = 2u;
    pft_pre_clutter_t c;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_init(&c, &cfg, g_work, sizeof g_work));
    for (uint32_t n = 1u; n <= 3u; ++n) {
        for (int i = 0; i < NPIX; ++i) {
            g_res[i] = noise_q88();
        }
        pft_frame_t f = res_frame(n);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_update(&c, &f, 40000, -70000, true));
    }
    const pft_pre_clutter_t saved = c;
    memcpy(g_copy, g_work, sizeof g_work);
    pft_frame_t f = res_frame(9u);
    f.width = W + 1;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_FORMAT, pft_pre_clutter_update(&c, &f, 0, 0, true));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_pre_clutter_raise(&c, W, 0u, 16384u));
    TEST_ASSERT_EQUAL_MEMORY(&saved, &c, sizeof c);
    TEST_ASSERT_EQUAL_MEMORY(g_copy, g_work, sizeof g_work);
    /* the raise lifts the blocks of the 3 x 3 pixels: (7, 7) .. (9, 9) lie in blocks 1 and 2 */
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_raise(&c, 8u, 8u, 60000u));
    TEST_ASSERT_EQUAL_UINT32(60000u, pft_pre_clutter_at(&c, 4u, 4u));
    TEST_ASSERT_EQUAL_UINT32(60000u, pft_pre_clutter_at(&c, 11u, 11u));
    TEST_ASSERT_TRUE(pft_pre_clutter_at(&c, 12u, 8u) < 60000u);
    TEST_ASSERT_TRUE(pft_pre_clutter_at(&c, 3u, 8u) < 60000u);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_config_and_workspace);
    RUN_TEST(test_matches_reference);
    RUN_TEST(test_persistent_blob_learnt_at_rate);
    RUN_TEST(test_moving_point_keeps_value);
    RUN_TEST(test_map_moves_with_scene);
    RUN_TEST(test_refused_input_changes_nothing);
    return UNITY_END();
}
