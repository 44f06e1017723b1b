/*
 * The calls behind the tsa golden vectors (TSA-AK tracker with its NCV / TS baselines),
 * shared by the generator (host q16) and the replay test (every target). The scene is made by
 * integer code only, so the frames are identical everywhere: a 12 x 10 textured box (red body
 * with stripes, yellow nose) that cruises, accelerates to 4 px/frame, reverses and comes back,
 * over a textured background, 64 x 40 RGB888 (and its U8 grey version).
 * tsa_gv_compute() runs the building blocks (polygon, kernel, histogram, Bhattacharyya, snake,
 * motion model, conservative fit) and five trackers over TSA_GV_FRAMES frames, and fills the
 * results in Q16.16 raw units (PFT_GV_RAW of core_vectors_spec.h).
 */
#ifndef PFT_TSA_VECTORS_SPEC_H
#define PFT_TSA_VECTORS_SPEC_H
#include <string.h>
#include "pft/pft.h"
#include "pft/pft_tsa.h"
#include "core_vectors_spec.h"

#define TSA_GV_W 64
#define TSA_GV_H 40
#define TSA_GV_TW 12 /* target box */
#define TSA_GV_TH 10
#define TSA_GV_FRAMES 24u
#define TSA_GV_CASES 6u
#define TSA_GV_NP 32u
#define TSA_GV_MAXT 24u
#define TSA_GV_PTS 24u
#define TSA_GV_NF 22u /* values per tracker frame, see tsa_gv_record */
#define TSA_GV_NKERN 2u
#define TSA_GV_NHIST 7u
#define TSA_GV_NRHO 5u
#define TSA_GV_NSNAKE 2u
#define TSA_GV_NDIST 24u
#define TSA_GV_NBETA 6u
#define TSA_GV_NFIT 7u
#define TSA_GV_NBOUND 3u
#define TSA_GV_NADAPT 6u

typedef struct {
    /* building blocks */
    int32_t kern[TSA_GV_NKERN][10]; /* status, n, sum, x0, y0, x1, y1, origin x, y, hash of pix */
    int32_t hist[TSA_GV_NHIST][3];  /* status, total, hash of the bins */
    int32_t rho[TSA_GV_NRHO];
    int32_t resample[2][2];         /* status, hash of the points */
    int32_t snake[TSA_GV_NSNAKE][3];/* status, passes, hash of the points */
    int32_t poly[TSA_GV_NDIST][3];  /* distance (1/16 px), inside, area2 (low 32 bits) */
    int32_t coef[TSA_GV_NBETA][12]; /* status, beta, phi12, phi22, gamma1, gamma2, q11, q12, q22,
                                       l11, l21, l22 */
    int32_t step[TSA_GV_NBETA][2];  /* x, v after one free step */
    int32_t fit[TSA_GV_NFIT][7];    /* status, s, v, a, v_pred, x_pred, order */
    int32_t bound[TSA_GV_NBOUND][5];/* s, v, a, v_pred, x_pred */
    int32_t adapt[TSA_GV_NADAPT][2];/* beta_adapt, ref_is_estimate */
    /* trackers: per case, the start (frame 0) and every update */
    int32_t status[TSA_GV_CASES][TSA_GV_FRAMES];
    int32_t trk[TSA_GV_CASES][TSA_GV_FRAMES][TSA_GV_NF];
} tsa_gv_results_t;

/* FNV-1a over 32-bit words. */
static inline uint32_t tsa_gv_hash(uint32_t h, int32_t v)
{
    const uint32_t u = (uint32_t)v;
    for (uint32_t b = 0; b < 4u; ++b) {
        h ^= (u >> (8u * b)) & 0xFFu;
        h *= 16777619u;
    }
    return h;
}
#define TSA_GV_HASH0 2166136261u

/* Target centre (integer pixels) at frame k: cruise 1 px/frame, accelerate to 4 px/frame,
 * reverse at frame 15, come back at 3 px/frame; a small vertical wobble. */
static inline void tsa_gv_truth(uint32_t k, int32_t *cx, int32_t *cy)
{
    static const int8_t xs[TSA_GV_FRAMES] = {14, 15, 16, 17, 18, 19, 21, 24, 28, 32, 36, 40,
                                             43, 45, 46, 46, 45, 43, 40, 37, 34, 31, 28, 25};
    static const int8_t ys[TSA_GV_FRAMES] = {0, 0, 1, 1, 1, 0, 0, -1, -1, -1, 0, 0,
                                             1, 1, 1, 0, 0, -1, -1, -1, 0, 0, 1, 1};
    *cx = xs[k % TSA_GV_FRAMES];
    *cy = 20 + ys[k % TSA_GV_FRAMES];
}

/* Frames of case 5 with the target hidden (only the background): the loss handling searches
 * and re-acquires. */
#define TSA_GV_HIDE0 10u
#define TSA_GV_HIDE1 14u

/* Frame k: rgb (TSA_GV_H x TSA_GV_W x 3) and its grey version (77 R + 150 G + 29 B) >> 8; with
 * hide set the target is not drawn. */
static inline void tsa_gv_render_ex(uint32_t k, uint8_t *rgb, uint8_t *grey, int hide)
{
    int32_t cx, cy;
    uint32_t s = 12345u;
    tsa_gv_truth(k, &cx, &cy);
    for (int32_t y = 0; y < TSA_GV_H; ++y) {
        for (int32_t x = 0; x < TSA_GV_W; ++x) {
            uint8_t *p = &rgb[3 * (y * TSA_GV_W + x)];
            const int32_t tx = x - (cx - TSA_GV_TW / 2), ty = y - (cy - TSA_GV_TH / 2);
            s = s * 1664525u + 1013904223u;
            if (!hide && tx >= 0 && tx < TSA_GV_TW && ty >= 0 && ty < TSA_GV_TH) {
                const int32_t nose = tx >= TSA_GV_TW - 4;
                p[0] = (uint8_t)(nose ? 235 : 200);
                p[1] = (uint8_t)(nose ? 205 : 50 + 30 * (ty & 1));
                p[2] = (uint8_t)(nose ? 40 : 45);
            } else {
                const uint32_t t = s >> 26; /* 0..63 */
                p[0] = (uint8_t)(70 + t);
                p[1] = (uint8_t)(90 + (t ^ 21u));
                p[2] = (uint8_t)(60 + ((t * 7u) & 63u));
            }
            grey[y * TSA_GV_W + x] = (uint8_t)((77u * p[0] + 150u * p[1] + 29u * p[2]) >> 8);
        }
    }
}

static inline void tsa_gv_render(uint32_t k, uint8_t *rgb, uint8_t *grey)
{
    tsa_gv_render_ex(k, rgb, grey, 0);
}

static inline pft_frame_t tsa_gv_frame(const uint8_t *data, pft_pixfmt_t fmt)
{
    pft_frame_t f;
    memset(&f, 0, sizeof f);
    f.data = data;
    f.width = TSA_GV_W;
    f.height = TSA_GV_H;
    f.format = fmt;
    f.stride_bytes = (uint32_t)TSA_GV_W * (fmt == PFT_PIX_U8 ? 1u : 3u);
    return f;
}

/* The initial box of the target at frame k: one pixel around it. */
static inline void tsa_gv_box(uint32_t k, pft_tsa_pt_t *b)
{
    int32_t cx, cy;
    tsa_gv_truth(k, &cx, &cy);
    const int32_t x0 = cx - TSA_GV_TW / 2 - 1, y0 = cy - TSA_GV_TH / 2 - 1;
    const int32_t x1 = cx - TSA_GV_TW / 2 + TSA_GV_TW, y1 = cy - TSA_GV_TH / 2 + TSA_GV_TH;
    b[0].x = (int16_t)x0; b[0].y = (int16_t)y0;
    b[1].x = (int16_t)x1; b[1].y = (int16_t)y0;
    b[2].x = (int16_t)x1; b[2].y = (int16_t)y1;
    b[3].x = (int16_t)x0; b[3].y = (int16_t)y1;
}

static inline int32_t tsa_gv_hash_pts(const pft_tsa_pt_t *p, uint32_t n)
{
    uint32_t h = TSA_GV_HASH0;
    for (uint32_t i = 0; i < n; ++i) {
        h = tsa_gv_hash(h, p[i].x);
        h = tsa_gv_hash(h, p[i].y);
    }
    return (int32_t)h;
}

static inline int32_t tsa_gv_hash_hist(const pft_tsa_hist_t *hh)
{
    uint32_t h = TSA_GV_HASH0;
    for (uint32_t b = 0; b < PFT_TSA_BINS; ++b) {
        h = tsa_gv_hash(h, (int32_t)hh->bin[b]);
    }
    return (int32_t)tsa_gv_hash(h, (int32_t)hh->total);
}

static inline int32_t tsa_gv_hash_kernel(const pft_tsa_kernel_t *k)
{
    uint32_t h = TSA_GV_HASH0;
    for (uint32_t i = 0; i < k->n; ++i) {
        h = tsa_gv_hash(h, k->pix[i].dx);
        h = tsa_gv_hash(h, k->pix[i].dy);
        h = tsa_gv_hash(h, k->pix[i].w);
    }
    return (int32_t)h;
}

/* ------------------------------------------------------------------------ building blocks */
static inline void tsa_gv_blocks(tsa_gv_results_t *r, const uint8_t *rgb0, const uint8_t *grey0,
                                 const uint8_t *rgb5)
{
    static pft_tsa_kpix_t kpix[TSA_GV_NKERN][TSA_GV_MAXT * TSA_GV_MAXT];
    static uint8_t bgr0[TSA_GV_W * TSA_GV_H * 3];
    static uint8_t snake_work[PFT_TSA_SNAKE_WORK_BYTES(TSA_GV_MAXT, TSA_GV_MAXT, 6)];
    int32_t cross[TSA_GV_PTS];
    pft_tsa_kernel_t k[TSA_GV_NKERN];
    pft_tsa_pt_t origin[TSA_GV_NKERN];
    pft_tsa_pt_t box[4];
    /* a non-convex polygon (an L with a slanted edge) */
    static const pft_tsa_pt_t ell[7] = {{20, 8}, {34, 8}, {34, 14}, {27, 16}, {27, 26}, {20, 26}, {18, 17}};
    const pft_tsa_pt_t *polys[TSA_GV_NKERN] = {box, ell};
    const uint32_t npoly[TSA_GV_NKERN] = {4u, 7u};
    pft_frame_t f0 = tsa_gv_frame(rgb0, PFT_PIX_RGB888);
    pft_frame_t fb = tsa_gv_frame(bgr0, PFT_PIX_BGR888);
    pft_frame_t fg = tsa_gv_frame(grey0, PFT_PIX_U8);
    pft_frame_t f5 = tsa_gv_frame(rgb5, PFT_PIX_RGB888);
    pft_tsa_hist_t h[TSA_GV_NHIST];

    tsa_gv_box(0u, box);
    for (uint32_t i = 0; i < (uint32_t)(TSA_GV_W * TSA_GV_H); ++i) {
        bgr0[3u * i] = rgb0[3u * i + 2u];
        bgr0[3u * i + 1u] = rgb0[3u * i + 1u];
        bgr0[3u * i + 2u] = rgb0[3u * i];
    }
    for (uint32_t j = 0; j < TSA_GV_NKERN; ++j) {
        memset(&k[j], 0, sizeof k[j]);
        k[j].pix = kpix[j];
        k[j].cap = TSA_GV_MAXT * TSA_GV_MAXT;
        r->kern[j][0] = (int32_t)pft_tsa_kernel_build(&k[j], polys[j], npoly[j], (uint16_t)(16u + 8u * j),
                                                      cross, &origin[j]);
        r->kern[j][1] = (int32_t)k[j].n;
        r->kern[j][2] = (int32_t)k[j].sum;
        r->kern[j][3] = k[j].x0;
        r->kern[j][4] = k[j].y0;
        r->kern[j][5] = k[j].x1;
        r->kern[j][6] = k[j].y1;
        r->kern[j][7] = origin[j].x;
        r->kern[j][8] = origin[j].y;
        r->kern[j][9] = tsa_gv_hash_kernel(&k[j]);
    }
    {
        const pft_frame_t *fr[TSA_GV_NHIST] = {&f0, &f0, &f0, &f0, &fb, &fg, &f5};
        const uint32_t kj[TSA_GV_NHIST] = {0u, 0u, 0u, 0u, 0u, 0u, 1u};
        const int32_t dx[TSA_GV_NHIST] = {0, 3, 0, 0, 0, 0, 2};
        const int32_t dy[TSA_GV_NHIST] = {0, -2, 0, 0, 0, 0, 1};
        for (uint32_t i = 0; i < TSA_GV_NHIST; ++i) {
            int32_t cx = origin[kj[i]].x + dx[i], cy = origin[kj[i]].y + dy[i];
            if (i == 2u) {
                cx = 2; /* partly outside */
                cy = 1;
            } else if (i == 3u) {
                cx = -30; /* wholly outside */
            }
            memset(&h[i], 0, sizeof h[i]);
            r->hist[i][0] = (int32_t)pft_tsa_hist(fr[i], &k[kj[i]], cx, cy, &h[i]);
            r->hist[i][1] = (int32_t)h[i].total;
            r->hist[i][2] = tsa_gv_hash_hist(&h[i]);
        }
    }
    r->rho[0] = PFT_GV_RAW(pft_tsa_bhattacharyya(&h[0], &h[0]));
    r->rho[1] = PFT_GV_RAW(pft_tsa_bhattacharyya(&h[0], &h[1]));
    r->rho[2] = PFT_GV_RAW(pft_tsa_bhattacharyya(&h[0], &h[2]));
    r->rho[3] = PFT_GV_RAW(pft_tsa_bhattacharyya(&h[0], &h[5]));
    r->rho[4] = PFT_GV_RAW(pft_tsa_bhattacharyya(&h[6], &h[1]));
    {
        pft_tsa_pt_t pts[TSA_GV_PTS];
        uint8_t flags[TSA_GV_PTS];
        pft_tsa_snake_params_t prm;
        uint32_t done = 0u;
        r->resample[0][0] = (int32_t)pft_tsa_poly_resample(box, 4u, pts, TSA_GV_PTS);
        r->resample[0][1] = tsa_gv_hash_pts(pts, TSA_GV_PTS);
        pft_tsa_snake_params_default(&prm, TSA_GV_MAXT, TSA_GV_MAXT);
        r->snake[0][0] = (int32_t)pft_tsa_snake(&f0, pts, TSA_GV_PTS, &prm, 30u, flags, snake_work,
                                                sizeof snake_work, &done);
        r->snake[0][1] = (int32_t)done;
        r->snake[0][2] = tsa_gv_hash_pts(pts, TSA_GV_PTS);
        r->resample[1][0] = (int32_t)pft_tsa_poly_resample(ell, 7u, pts, 17u);
        r->resample[1][1] = tsa_gv_hash_pts(pts, 17u);
        prm.alpha = PFT_GV_REAL(32768);   /* 0.5 */
        prm.kb = PFT_GV_REAL(-13107);     /* -0.2 */
        prm.corner_c = PFT_GV_REAL(6554); /* 0.1 */
        prm.corner_g = 40u;
        done = 0u;
        r->snake[1][0] = (int32_t)pft_tsa_snake(&f5, pts, 17u, &prm, 12u, flags, snake_work,
                                                sizeof snake_work, &done);
        r->snake[1][1] = (int32_t)done;
        r->snake[1][2] = tsa_gv_hash_pts(pts, 17u);
    }
    for (uint32_t i = 0; i < TSA_GV_NDIST; ++i) {
        const int32_t x = 14 + (int32_t)((i * 7u) % 26u), y = 4 + (int32_t)((i * 5u) % 27u);
        r->poly[i][0] = (int32_t)pft_tsa_poly_dist_q4(ell, 7u, x, y);
        r->poly[i][1] = pft_tsa_poly_inside(ell, 7u, x, y) ? 1 : 0;
        r->poly[i][2] = (int32_t)pft_tsa_poly_area2(i % 2u ? ell : box, i % 2u ? 7u : 4u);
    }
}

static inline void tsa_gv_motion(tsa_gv_results_t *r)
{
    static const int32_t betas[TSA_GV_NBETA] = {0, 19661, 65470, 65536, 163840, 393216};
    const pft_real_t q = PFT_GV_REAL(266731); /* 4.07 */
    for (uint32_t i = 0; i < TSA_GV_NBETA; ++i) {
        pft_tsa_motion_free_t c;
        pft_real_t x = PFT_GV_REAL(10 * 65536), v = PFT_GV_REAL(65536);
        memset(&c, 0, sizeof c);
        r->coef[i][0] = (int32_t)pft_tsa_motion_free_coef(&c, PFT_GV_REAL(betas[i]), q);
        r->coef[i][1] = PFT_GV_RAW(c.beta);
        r->coef[i][2] = PFT_GV_RAW(c.phi12);
        r->coef[i][3] = PFT_GV_RAW(c.phi22);
        r->coef[i][4] = PFT_GV_RAW(c.gamma1);
        r->coef[i][5] = PFT_GV_RAW(c.gamma2);
        r->coef[i][6] = PFT_GV_RAW(c.q11);
        r->coef[i][7] = PFT_GV_RAW(c.q12);
        r->coef[i][8] = PFT_GV_RAW(c.q22);
        r->coef[i][9] = PFT_GV_RAW(c.l11);
        r->coef[i][10] = PFT_GV_RAW(c.l21);
        r->coef[i][11] = PFT_GV_RAW(c.l22);
        pft_tsa_motion_free_step(&c, &x, &v, PFT_GV_REAL(2 * 65536), PFT_GV_REAL(45875), PFT_GV_REAL(-85197));
        r->step[i][0] = PFT_GV_RAW(x);
        r->step[i][1] = PFT_GV_RAW(v);
    }
    {
        /* o(tau) = 100 + 3 tau + 0.4 tau^2 plus a fixed integer disturbance, tau = -9..0 */
        static const int32_t noise[10] = {9830, -6554, 3277, 0, -13107, 16384, -3277, 6554, -9830, 1311};
        static const int32_t piw[10] = {65536, 32768, 65536, 0, 65536, 49152, 65536, 16384, 65536, 65536};
        static const int32_t lone[10] = {0, 0, 0, 0, 0, 0, 0, 0, 0, 65536};
        pft_real_t o[10], pi[10], pz[10];
        pft_tsa_motion_fit_t f[TSA_GV_NFIT];
        for (int32_t i = 0; i < 10; ++i) {
            const int32_t t = i - 9;
            o[i] = PFT_GV_REAL(100 * 65536 + 3 * 65536 * t + 26214 * t * t + noise[i]);
            pi[i] = PFT_GV_REAL(piw[i]);
            pz[i] = PFT_GV_REAL(lone[i]);
        }
        memset(f, 0, sizeof f);
        r->fit[0][0] = (int32_t)pft_tsa_motion_fit(o, NULL, 10u, PFT_GV_REAL(5 * 65536), 2u, &f[0]);
        r->fit[1][0] = (int32_t)pft_tsa_motion_fit(o, NULL, 10u, PFT_GV_REAL(5 * 65536), 1u, &f[1]);
        r->fit[2][0] = (int32_t)pft_tsa_motion_fit(o, pi, 10u, PFT_GV_REAL(163840), 2u, &f[2]);
        r->fit[3][0] = (int32_t)pft_tsa_motion_fit(&o[8], NULL, 2u, PFT_GV_REAL(5 * 65536), 2u, &f[3]);
        r->fit[4][0] = (int32_t)pft_tsa_motion_fit(&o[9], NULL, 1u, PFT_GV_REAL(5 * 65536), 2u, &f[4]);
        r->fit[5][0] = (int32_t)pft_tsa_motion_fit(o, pz, 10u, PFT_GV_REAL(5 * 65536), 2u, &f[5]);
        r->fit[6][0] = (int32_t)pft_tsa_motion_fit(&o[4], NULL, 6u, PFT_GV_REAL(98304), 2u, &f[6]);
        for (uint32_t i = 0; i < TSA_GV_NFIT; ++i) {
            r->fit[i][1] = PFT_GV_RAW(f[i].s);
            r->fit[i][2] = PFT_GV_RAW(f[i].v);
            r->fit[i][3] = PFT_GV_RAW(f[i].a);
            r->fit[i][4] = PFT_GV_RAW(f[i].v_pred);
            r->fit[i][5] = PFT_GV_RAW(f[i].x_pred);
            r->fit[i][6] = f[i].order;
        }
        {
            static const int32_t amax[TSA_GV_NBOUND] = {32768, 13107, 0};
            static const int32_t vmax[TSA_GV_NBOUND] = {12 * 65536, 2 * 65536, 0};
            for (uint32_t i = 0; i < TSA_GV_NBOUND; ++i) {
                pft_tsa_motion_fit_t g = f[0];
                pft_tsa_motion_fit_bound(&g, PFT_GV_REAL(amax[i]), PFT_GV_REAL(vmax[i]));
                r->bound[i][0] = PFT_GV_RAW(g.s);
                r->bound[i][1] = PFT_GV_RAW(g.v);
                r->bound[i][2] = PFT_GV_RAW(g.a);
                r->bound[i][3] = PFT_GV_RAW(g.v_pred);
                r->bound[i][4] = PFT_GV_RAW(g.x_pred);
            }
        }
    }
    {
        static const int32_t re[TSA_GV_NADAPT] = {62259, 52429, 0, 65536, 45875, 58982};
        static const int32_t rp[TSA_GV_NADAPT] = {32768, 62259, 0, 65536, 0, 58982};
        for (uint32_t i = 0; i < TSA_GV_NADAPT; ++i) {
            r->adapt[i][0] = PFT_GV_RAW(pft_tsa_motion_beta_adapt(PFT_GV_REAL(re[i]), PFT_GV_REAL(rp[i]),
                                                              PFT_GV_REAL(6 * 65536), PFT_GV_REAL(131072)));
            r->adapt[i][1] = pft_tsa_motion_ref_is_estimate(PFT_GV_REAL(re[i]), PFT_GV_REAL(rp[i])) ? 1 : 0;
        }
    }
}

/* ------------------------------------------------------------------------------- trackers */
#define TSA_GV_WORK_BYTES PFT_TSA_WORKSPACE_BYTES(TSA_GV_NP, TSA_GV_MAXT, TSA_GV_MAXT, TSA_GV_PTS, 6, 48)

/* Case c: 0 TSA with exponential weights (lik_lambda 300), 1 TSA with w = rho, 2 TS, 3 NCV,
 * 4 TSA on the grey frames with rho-weighted reference points, the paper's unbounded fit and
 * no loss handling, 5 TSA (defaults, no template update) with the target hidden on frames
 * TSA_GV_HIDE0 .. TSA_GV_HIDE1 - 1 (search, re-acquisition). Cases 0-4: theta_u 1 updates the
 * template (snake passes) on most frames. */
static inline void tsa_gv_config(pft_tsa_config_t *c, uint32_t cs)
{
    pft_tsa_config_default(c);
    c->width = TSA_GV_W;
    c->height = TSA_GV_H;
    c->max_target_w = TSA_GV_MAXT;
    c->max_target_h = TSA_GV_MAXT;
    pft_tsa_snake_params_default(&c->snake, TSA_GV_MAXT, TSA_GV_MAXT);
    c->n_particles = TSA_GV_NP;
    c->snake_points = TSA_GV_PTS;
    c->init_passes = 20u;
    c->theta_u = PFT_GV_REAL(65536); /* 1: update whenever rho < 1 */
    c->fit_k = 8u;
    c->fit_sigma = PFT_GV_REAL(163840); /* 2.5 */
    /* case 3 (NCV, template update every frame) uses seed 110: see the comment of TRK_TOL_PX in
     * tests/unit/test_tsa_golden.c */
    c->seed = cs == 3u ? 110u : 7u + cs;
    c->motion = cs == 2u ? PFT_TSA_MOTION_TS : (cs == 3u ? PFT_TSA_MOTION_NCV : PFT_TSA_MOTION_TSA);
    if (cs == 1u) {
        c->lik_lambda = 0;
    }
    if (cs == 4u) {
        c->fit_rho_weights = true;
        c->fit_a_max = 0;
        c->fit_v_max = 0;
        c->lost_frames = 3u;
        c->loss_search = false;
        /* the paper's behaviour, as pft's tsa_paper: one template. With gain selection the
         * float tracker of this case (unbounded fit) left the target on frames 21-23 (7-20 px,
         * q16 on it) */
        c->gain_select = false;
    }
    if (cs == 5u) {
        c->theta_u = 0;
        c->lost_frames = 2u;
    }
}

/* One frame's results: the estimate, a hash of the particles (x, y, rho) and a hash of the
 * shape (contour at the estimate, template histogram, kernel). */
static inline void tsa_gv_record(const pft_tsa_t *t, int32_t *v)
{
    static pft_tsa_pt_t contour[TSA_GV_PTS];
    static pft_tsa_particle_t part[TSA_GV_NP + 1u];
    static pft_tsa_kpix_t kpix[TSA_GV_MAXT * TSA_GV_MAXT];
    pft_tsa_estimate_t e;
    pft_tsa_hist_t q;
    pft_tsa_kernel_t k;
    memset(&e, 0, sizeof e);
    memset(&q, 0, sizeof q);
    memset(&k, 0, sizeof k);
    k.pix = kpix;
    k.cap = TSA_GV_MAXT * TSA_GV_MAXT;
    (void)pft_tsa_estimate(t, &e);
    (void)pft_tsa_template(t, &q);
    (void)pft_tsa_kernel(t, &k);
    const uint32_t n = (uint32_t)pft_tsa_particles(t, part, TSA_GV_NP + 1u);
    const uint32_t nc = (uint32_t)pft_tsa_contour(t, contour, TSA_GV_PTS);
    uint32_t hp = TSA_GV_HASH0;
    uint32_t hs = (uint32_t)tsa_gv_hash_pts(contour, nc);
    v[0] = (int32_t)e.state;
    v[1] = (int32_t)e.frame;
    v[2] = PFT_GV_RAW(e.x);
    v[3] = PFT_GV_RAW(e.y);
    v[4] = PFT_GV_RAW(e.vx);
    v[5] = PFT_GV_RAW(e.vy);
    v[6] = PFT_GV_RAW(e.pioneer_x);
    v[7] = PFT_GV_RAW(e.pioneer_y);
    v[8] = PFT_GV_RAW(e.pioneer_vx);
    v[9] = PFT_GV_RAW(e.pioneer_vy);
    v[10] = PFT_GV_RAW(e.rho);
    v[11] = PFT_GV_RAW(e.rho_pioneer);
    v[12] = PFT_GV_RAW(e.beta);
    v[13] = PFT_GV_RAW(e.beta_next);
    v[14] = (int32_t)e.n_alive;
    v[15] = (e.ref_is_estimate ? 1 : 0) | (e.template_updated ? 2 : 0) | ((int32_t)e.snake_passes << 8) |
            ((int32_t)e.fit_order << 16);
    v[16] = e.box_x0;
    v[17] = e.box_y0;
    v[18] = e.box_x1;
    v[19] = e.box_y1;
    for (uint32_t i = 0; i < n; ++i) {
        hp = tsa_gv_hash(hp, PFT_GV_RAW(part[i].x));
        hp = tsa_gv_hash(hp, PFT_GV_RAW(part[i].y));
        hp = tsa_gv_hash(hp, PFT_GV_RAW(part[i].rho));
    }
    v[20] = (int32_t)tsa_gv_hash(hp, (int32_t)n);
    hs = tsa_gv_hash(hs, tsa_gv_hash_hist(&q));
    v[21] = (int32_t)tsa_gv_hash(hs, tsa_gv_hash_kernel(&k));
}

static inline void tsa_gv_compute(tsa_gv_results_t *r)
{
    static uint8_t rgb[TSA_GV_FRAMES][TSA_GV_W * TSA_GV_H * 3];
    static uint8_t grey[TSA_GV_FRAMES][TSA_GV_W * TSA_GV_H];
    static uint8_t hidden[TSA_GV_HIDE1 - TSA_GV_HIDE0][TSA_GV_W * TSA_GV_H * 3];
    static uint8_t hidden_grey[TSA_GV_W * TSA_GV_H];
    static uint8_t work[TSA_GV_WORK_BYTES];
    static pft_tsa_t trk;
    for (uint32_t k = 0; k < TSA_GV_FRAMES; ++k) {
        tsa_gv_render(k, rgb[k], grey[k]);
    }
    for (uint32_t k = TSA_GV_HIDE0; k < TSA_GV_HIDE1; ++k) {
        tsa_gv_render_ex(k, hidden[k - TSA_GV_HIDE0], hidden_grey, 1);
    }
    tsa_gv_blocks(r, rgb[0], grey[0], rgb[5]);
    tsa_gv_motion(r);
    for (uint32_t cs = 0; cs < TSA_GV_CASES; ++cs) {
        pft_tsa_config_t c;
        pft_tsa_pt_t box[4];
        const pft_pixfmt_t fmt = cs == 4u ? PFT_PIX_U8 : PFT_PIX_RGB888;
        tsa_gv_config(&c, cs);
        tsa_gv_box(0u, box);
        memset(&trk, 0, sizeof trk);
        if (pft_tsa_init(&trk, &c, work, sizeof work) != PFT_OK) {
            r->status[cs][0] = -1000;
            continue;
        }
        for (uint32_t k = 0; k < TSA_GV_FRAMES; ++k) {
            const int hide = cs == 5u && k >= TSA_GV_HIDE0 && k < TSA_GV_HIDE1;
            const pft_frame_t f = tsa_gv_frame(
                fmt == PFT_PIX_U8 ? grey[k] : (hide ? hidden[k - TSA_GV_HIDE0] : rgb[k]), fmt);
            r->status[cs][k] = (int32_t)(k == 0u ? pft_tsa_start(&trk, &f, box, 4u) : pft_tsa_update(&trk, &f));
            tsa_gv_record(&trk, r->trk[cs][k]);
        }
    }
}
#endif
