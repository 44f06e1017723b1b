/*
 * The tracker's fast appearance path (per-frame code map, kernel row spans, joint histogram,
 * similarity cache, table square roots) against the reference building blocks:
 * - every particle's reported rho equals pft_tsa_bhattacharyya(pft_tsa_hist(frame, kernel,
 *   round(x), round(y)), template) exactly, frame after frame, through the mapped path (the
 *   default map_margin), the direct path (map_margin 0) and the clipped path (the target
 *   leaves the frame and the particles' kernels hang over its edge), in RGB888 and U8 frames;
 * - pft_tsa_poly_dist_q4 (the kernel weights' square roots) equals floor(16 d) from exact
 *   integer arithmetic over 20000 points, near and far (square roots of 0 .. 2^32);
 * - pft_tsa_bhattacharyya is within 2^-12 of the coefficient computed in 64-bit floating
 *   point on random histograms (q16: integer square roots; float: the FPU's), identical
 *   histograms give 1 within 2^-12, disjoint ones 0.
 */
#include <math.h>
#include <string.h>
#include "pft_test_support.h"
#include "pft/pft_tsa.h"

void setUp(void) {}
void tearDown(void) {}

#define W 96
#define H 40
#define NP 40
#define PTS 20
#define MAXT 24

static uint8_t rgb[H][W][3];
static uint8_t grey[H][W];
static uint8_t work[PFT_TSA_WORKSPACE_BYTES(NP, MAXT, MAXT, PTS, 6, 48)];
static pft_tsa_t trk;
static pft_tsa_particle_t part[NP + 1];
static pft_tsa_kpix_t kpix[MAXT * MAXT];

/* A striped red-and-yellow 12 x 9 target at (cx, cy) over a coloured texture. */
static void render(int cx, int cy)
{
    uint32_t s = 4242u;
    for (int y = 0; y < H; ++y) {
        for (int x = 0; x < W; ++x) {
            uint8_t *p = rgb[y][x];
            s = s * 1664525u + 1013904223u;
            const int tx = x - (cx - 6), ty = y - (cy - 4);
            if (tx >= 0 && tx < 12 && ty >= 0 && ty < 9) {
                p[0] = (uint8_t)(tx < 8 ? 210 : 240);
                p[1] = (uint8_t)(tx < 8 ? 40 + 20 * (ty & 1) : 210);
                p[2] = 30;
            } else {
                p[0] = (uint8_t)(60 + (s >> 26));
                p[1] = (uint8_t)(80 + ((s >> 20) & 63u));
                p[2] = (uint8_t)(70 + ((s >> 14) & 63u));
            }
            grey[y][x] = (uint8_t)((77u * p[0] + 150u * p[1] + 29u * p[2]) >> 8);
        }
    }
}

static pft_frame_t frame(bool u8)
{
    pft_frame_t f;
    memset(&f, 0, sizeof f);
    f.data = u8 ? (const void *)grey : (const void *)rgb;
    f.width = W;
    f.height = H;
    f.format = u8 ? PFT_PIX_U8 : PFT_PIX_RGB888;
    f.stride_bytes = u8 ? W : 3 * W;
    return f;
}

/* Every particle's rho against the reference computation; returns the particles checked. */
static uint32_t check_particles(const pft_frame_t *f)
{
    pft_tsa_kernel_t k;
    pft_tsa_hist_t q, h;
    memset(&k, 0, sizeof k);
    k.pix = kpix;
    k.cap = MAXT * MAXT;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_kernel(&trk, &k));
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_template(&trk, &q));
    const uint32_t n = (uint32_t)pft_tsa_particles(&trk, part, NP + 1);
    for (uint32_t i = 0; i < n; ++i) {
        const int32_t x = (int32_t)floor(pft_test_to_double(part[i].x) + 0.5);
        const int32_t y = (int32_t)floor(pft_test_to_double(part[i].y) + 0.5);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_hist(f, &k, x, y, &h));
        const pft_real_t r = pft_tsa_bhattacharyya(&h, &q);
        TEST_ASSERT_TRUE_MESSAGE(r == part[i].rho, "fast-path rho differs from the reference");
    }
    return n;
}

static void run_and_check(uint16_t map_margin, bool u8, int dx, int frames)
{
    pft_tsa_config_t c;
    pft_tsa_pt_t b[4];
    pft_test_tsa_config(&c, W, H, MAXT, NP, PTS);
    c.gain_select = false; /* the reference below is the gain-1 template (pft_tsa_template) */
    c.bg_ring = 0;         /* ... and its rho unscaled (bg_ring scales rho by 1 / rho0) */
    c.map_margin = map_margin;
    c.seed = 3u;
    TEST_ASSERT_TRUE(pft_tsa_workspace_size(&c) <= sizeof work);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_init(&trk, &c, work, sizeof work));
    int cx = 40, cy = 20;
    render(cx, cy);
    b[0].x = (int16_t)(cx - 7);
    b[0].y = (int16_t)(cy - 5);
    b[1].x = (int16_t)(cx + 6);
    b[1].y = (int16_t)(cy - 5);
    b[2].x = (int16_t)(cx + 6);
    b[2].y = (int16_t)(cy + 5);
    b[3].x = (int16_t)(cx - 7);
    b[3].y = (int16_t)(cy + 5);
    pft_frame_t f = frame(u8);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_start(&trk, &f, b, 4));
    uint32_t checked = 0u;
    for (int k = 1; k <= frames; ++k) {
        cx += dx;
        render(cx, cy);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_update(&trk, &f));
        checked += check_particles(&f);
    }
    TEST_ASSERT_TRUE(checked >= (uint32_t)frames * NP);
}

static void test_mapped_path(void) { run_and_check(48u, false, 2, 10); }
static void test_direct_path(void) { run_and_check(0u, false, 2, 10); }
static void test_grey_frames(void) { run_and_check(48u, true, 2, 10); }

/* The target drives out of the left edge: kernels hang over it (clipped spans). */
static void test_clipped_path(void)
{
    run_and_check(48u, false, -4, 16);
    run_and_check(0u, false, -4, 16);
}

/* floor(sqrt(v)) in exact integer arithmetic (reference for the test). */
static uint64_t ref_isqrt(uint64_t v)
{
    uint64_t r = (uint64_t)sqrt((double)v);
    while (r * r > v) {
        --r;
    }
    while ((r + 1u) * (r + 1u) <= v) {
        ++r;
    }
    return r;
}

/* Squared distance times 256 (floor) from (x, y) to the segment a-b, as the library defines it. */
static uint64_t ref_seg_d2_q8(int64_t ax, int64_t ay, int64_t bx, int64_t by, int64_t x, int64_t y)
{
    const int64_t ex = bx - ax, ey = by - ay, wx = x - ax, wy = y - ay;
    const int64_t t = wx * ex + wy * ey, len2 = ex * ex + ey * ey;
    if (len2 == 0 || t <= 0) {
        return (uint64_t)(wx * wx + wy * wy) << 8;
    }
    if (t >= len2) {
        return (uint64_t)((x - bx) * (x - bx) + (y - by) * (y - by)) << 8;
    }
    const int64_t cr = wx * ey - wy * ex;
    return ((uint64_t)(cr * cr) << 8) / (uint64_t)len2;
}

static void test_distance_square_roots(void)
{
    /* a large quadrilateral: distances from 0 to about 4000 px, i.e. square roots of Q8
     * squares up to 2^32 and beyond */
    static const pft_tsa_pt_t quad[4] = {{-1500, -900}, {2600, -700}, {2300, 1800}, {-1200, 1500}};
    uint64_t s = 0x9E3779B97F4A7C15ull;
    for (int i = 0; i < 20000; ++i) {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        const int32_t x = (int32_t)(s % 9000u) - 4500;
        const int32_t y = (int32_t)((s >> 20) % 7000u) - 3500;
        uint64_t best = UINT64_MAX;
        for (int e = 0; e < 4; ++e) {
            const pft_tsa_pt_t *a = &quad[e], *b = &quad[(e + 1) % 4];
            const uint64_t d = ref_seg_d2_q8(a->x, a->y, b->x, b->y, x, y);
            best = d < best ? d : best;
        }
        TEST_ASSERT_EQUAL_UINT32((uint32_t)ref_isqrt(best), pft_tsa_poly_dist_q4(quad, 4, x, y));
    }
}

static double ref_rho(const pft_tsa_hist_t *p, const pft_tsa_hist_t *q)
{
    double num = 0.0;
    for (int u = 0; u < (int)PFT_TSA_BINS; ++u) {
        num += sqrt((double)p->bin[u] * (double)q->bin[u]);
    }
    return num / (3.0 * sqrt((double)p->total * (double)q->total));
}

/* A random histogram: three channels of 10 bins with the same total. */
static void random_hist(uint64_t *st, pft_tsa_hist_t *h, uint32_t scale)
{
    memset(h, 0, sizeof *h);
    uint32_t ch[3] = {0u, 0u, 0u};
    for (int c = 0; c < 3; ++c) {
        for (int i = 0; i < 10; ++i) {
            *st ^= *st << 13;
            *st ^= *st >> 7;
            *st ^= *st << 17;
            /* about half the bins empty, the rest spread over three decades */
            const uint32_t v = (*st & 1u) ? (uint32_t)((*st >> 8) % scale) >> ((*st >> 40) % 10u) : 0u;
            h->bin[c * 10 + i] = v;
            ch[c] += v;
        }
    }
    /* equal channel totals: pad the smaller channels' first bins */
    uint32_t tot = ch[0] > ch[1] ? ch[0] : ch[1];
    tot = tot > ch[2] ? tot : ch[2];
    tot = tot == 0u ? 1u : tot;
    for (int c = 0; c < 3; ++c) {
        h->bin[c * 10] += tot - ch[c];
    }
    h->total = tot;
}

static void test_bhattacharyya_accuracy(void)
{
    uint64_t st = 0x1234567u;
    static const uint32_t scales[4] = {100u, 20000u, 3000000u, 400000000u};
    for (int i = 0; i < 400; ++i) {
        pft_tsa_hist_t p, q;
        random_hist(&st, &p, scales[i % 4]);
        random_hist(&st, &q, scales[(i / 4) % 4]);
        const double r = pft_test_to_double(pft_tsa_bhattacharyya(&p, &q));
        TEST_ASSERT_DOUBLE_WITHIN(1.0 / 4096, ref_rho(&p, &q), r);
        TEST_ASSERT_DOUBLE_WITHIN(1.0 / 4096, 1.0, pft_test_to_double(pft_tsa_bhattacharyya(&p, &p)));
    }
    {
        pft_tsa_hist_t a, b;
        memset(&a, 0, sizeof a);
        memset(&b, 0, sizeof b);
        a.bin[0] = a.bin[10] = a.bin[20] = a.total = 777u;
        b.bin[9] = b.bin[19] = b.bin[29] = b.total = 555u;
        TEST_ASSERT_TRUE(pft_tsa_bhattacharyya(&a, &b) == 0);
    }
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_mapped_path);
    RUN_TEST(test_direct_path);
    RUN_TEST(test_grey_frames);
    RUN_TEST(test_clipped_path);
    RUN_TEST(test_distance_square_roots);
    RUN_TEST(test_bhattacharyya_accuracy);
    return UNITY_END();
}
