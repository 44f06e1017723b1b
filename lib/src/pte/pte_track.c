/* PTE-TBD, Step 3 (docs/algorithms.md 5.3): one track at one frame. Operator geometry from
 * the predicted state, matched operators along L directions (EXACT taps, or reads of the
 * TABLE responses), direction likelihoods, per-direction Kalman updates, fusion, detection
 * and maintenance. */
#include "pte_int.h"
#include "pft/pft_kalman.h"

#define SV_ PFT_PTE_SV_
#define SA_ PFT_PTE_SA_

/* ----------------------------------------------------------------- TABLE operators */

/* TABLE operators: tap weights of each grid phase (width sigma_y = sigma_r, clamped) and the
 * normaliser sum g^2 of every response point (edges included). */
void pft_pte_ytable_setup_(pft_pte_t *p)
{
    const int32_t q = p->yq;
    const int32_t nr = p->cfg.in.n_range;
    p->sigma_y = pft_min(p->cfg.sigma_r[0], p->cfg.sigma_w_max);
    pft_real_t inv = pft_recip(p->sigma_y);
    pft_real_t reach = pft_mul_i(p->sigma_y, 3);
    for (int32_t ph = 0; ph < q; ++ph) {
        pft_real_t f = pft_ratio(ph, q);
        int32_t lo = -pft_floor_int(pft_neg(pft_sub(f, reach)));
        int32_t hi = pft_floor_int(pft_add(f, reach));
        if (hi - lo + 1 > (int32_t)PFT_PTE_MAX_TAPS) {
            hi = lo + (int32_t)PFT_PTE_MAX_TAPS - 1;
        }
        int32_t n = hi >= lo ? hi - lo + 1 : 0;
        for (int32_t k = 0; k < n; ++k) {
            pft_real_t t = pft_mul(pft_abs(pft_sub(pft_from_int(lo + k), f)), inv);
            int32_t idx = pft_round_int(pft_mul_i(t, 64));
            p->ytap[ph][k] = idx < (int32_t)PFT_PTE_GTAB_SIZE ? p->gtab[idx] : PFT_C(0.0);
        }
        p->ytap_lo[ph] = (int16_t)lo;
        p->ytap_n[ph] = (uint8_t)n;
    }
    for (uint32_t i = 0; i < p->ny; ++i) {
        int32_t ph = (int32_t)i % q;
        int32_t u0 = (int32_t)i / q - (int32_t)PFT_PTE_YPAD + p->ytap_lo[ph];
        pft_real_t g2 = PFT_C(0.0);
        for (int32_t k = 0; k < p->ytap_n[ph]; ++k) {
            if (u0 + k >= 0 && u0 + k < nr) {
                g2 = pft_add(g2, pft_sq(p->ytap[ph][k]));
            }
        }
        p->gq[i] = g2;
    }
}

/* TABLE operators: responses are computed lazily, one block of 8 cells at a time, the first
 * time an operator reads them, and kept beside the frame in the ring; only the neighbourhood
 * of live tracks is ever computed. */
#define YBLK_ 8

static void yblock_(pft_pte_t *p, uint32_t slot, uint32_t back, int32_t blk)
{
    const int32_t q = p->yq;
    const int32_t nr = p->cfg.in.n_range;
    const pft_real_t *z = pft_pte_ring_get_(&p->ring, back);
    pft_real_t *y = p->yring + (size_t)slot * p->ny;
    const int32_t ncell = (int32_t)(p->ny / (uint32_t)q);
    int32_t c1 = (blk + 1) * YBLK_ < ncell ? (blk + 1) * YBLK_ : ncell;
    for (int32_t cell = blk * YBLK_; cell < c1; ++cell) {
        for (int32_t ph = 0; ph < q; ++ph) {
            int32_t u0 = cell - (int32_t)PFT_PTE_YPAD + p->ytap_lo[ph];
            int32_t n = p->ytap_n[ph];
            const pft_real_t *w = p->ytap[ph];
            pft_real_t acc = PFT_C(0.0);
            if (u0 >= 0 && u0 + n <= nr) {
                const pft_real_t *zz = z + u0;
                for (int32_t k = 0; k < n; ++k) {
                    acc = pft_add(acc, pft_mul(w[k], zz[k]));
                }
            } else {
                for (int32_t k = 0; k < n; ++k) {
                    if (u0 + k >= 0 && u0 + k < nr) {
                        acc = pft_add(acc, pft_mul(w[k], z[u0 + k]));
                    }
                }
            }
            y[cell * q + ph] = acc;
        }
    }
    p->yflag[(size_t)slot * p->nyblk + (size_t)blk] = 1u;
}

/* TABLE operators: response of the frame `back` frames ago, valid at points [i0, i1). */
static const pft_real_t *yframe_(pft_pte_t *p, uint32_t back, int32_t i0, int32_t i1)
{
    uint32_t len = p->ring.len;
    uint32_t slot = ((uint32_t)p->ring.head + len - (back % len)) % len;
    int32_t bp = YBLK_ * (int32_t)p->yq;
    i0 = i0 < 0 ? 0 : i0;
    i1 = i1 > (int32_t)p->ny ? (int32_t)p->ny : i1;
    for (int32_t blk = i0 / bp; i1 > i0 && blk <= (i1 - 1) / bp; ++blk) {
        if (p->yflag[(size_t)slot * p->nyblk + (size_t)blk] == 0u) {
            yblock_(p, slot, back, blk);
        }
    }
    return p->yring + (size_t)slot * p->ny;
}

/* ------------------------------------------------------------------- operator geometry */

/* Per-axis operator parameters of one track at one frame. The operators are straight lines
 * over the last M frames; their best end position c* and slope theta* are the least-squares
 * line of the path, so for a state [r, v, a] they measure r + hc a and v + hv a with
 * hc = -(M-1)(M-2)/12 and hv = -(M-1)/2 (zero in the CV model, where a = 0). */
static void axis_setup_(const pft_pte_t *p, const pft_real_t x[4], const pft_real_t P[16],
                        uint32_t a, int32_t M, pft_pte_axis_t *ap)
{
    const pft_pte_config_t *c = &p->cfg;
    memset(ap->H, 0, sizeof(ap->H));
    ap->H[0] = PFT_C(1.0);
    ap->H[5] = PFT_C(1.0);
    if (c->motion == PFT_PTE_MOTION_CA) {
        /* hc / SA and hv SV / SA on the scaled acceleration */
        ap->H[2] = pft_neg(pft_ratio((M - 1) * (M - 2), 12 * SA_));
        ap->H[6] = pft_neg(pft_ratio((M - 1) * SV_, 2 * SA_));
    }
    ap->zc = pft_add(x[0], pft_mul(ap->H[2], x[2]));
    ap->zt = pft_add(x[1], pft_mul(ap->H[6], x[2]));
    /* S = H P H' (rows [1 0 h2 0], [0 1 h6 0]) */
    pft_real_t h2 = ap->H[2];
    pft_real_t h6 = ap->H[6];
    pft_real_t scc = pft_add(pft_add(P[0], pft_mul_i(pft_mul(h2, P[2]), 2)), pft_mul(pft_sq(h2), P[10]));
    pft_real_t stt = pft_add(pft_add(P[5], pft_mul_i(pft_mul(h6, P[6]), 2)), pft_mul(pft_sq(h6), P[10]));
    scc = pft_max(scc, PFT_C(0.0));
    stt = pft_max(stt, PFT_C(0.0));
    pft_real_t sr2 = pft_sq(c->sigma_r[a]);
    ap->sw2 = pft_add(sr2, scc);
    ap->sw = p->yq > 0u ? p->sigma_y : pft_min(pft_sqrt(ap->sw2), c->sigma_w_max);
    ap->sw2 = pft_sq(ap->sw);
    ap->inv_sw = pft_recip(ap->sw);
    ap->reach = pft_mul_i(ap->sw, 3);
    ap->L = (int32_t)c->n_dir[a];
    ap->dth = pft_mul_i(c->dtheta_min, SV_);
    if (ap->L > 1) {
        ap->dth = pft_max(pft_div_i(pft_mul_i(pft_sqrt(stt), 4), ap->L - 1), ap->dth);
    }
    /* dth^2 / (2 (S_tt + dth^2/12)) = 1 / (2 (S_tt/dth^2 + 1/12)) (scale-free) */
    pft_real_t rho = pft_div(stt, pft_sq(ap->dth));
    ap->prior_k = pft_recip(pft_mul_i(pft_add(rho, PFT_C(0.0833333333333)), 2));
    ap->sc2 = pft_add(scc, sr2);
    int32_t half = pft_floor_int(pft_div(pft_mul(c->scan_sigmas, pft_sqrt(ap->sc2)), c->c_step));
    if (half < 1) {
        half = 1;
    }
    if (half > (int32_t)c->scan_steps) {
        half = (int32_t)c->scan_steps;
    }
    ap->ns = 2 * half + 1;
    ap->c0 = pft_sub(ap->zc, pft_mul_i(c->c_step, half));
    ap->ncell = a == 0u ? (int32_t)c->in.n_range : (int32_t)c->in.n_doppler;
}

/* floor(x / 64) for any sign */
static int32_t fdiv64_(int32_t x)
{
    return x >= 0 ? x / 64 : -((-x + 63) / 64);
}

/* Per-frame weight table of one axis: gw[k] = g(k / (64 sigma_w)) for k = 0 .. R, R the
 * reach 3 sigma_w in 1/64 cells; path positions are quantised to 1/64 cell (error <= 1/128
 * cell), so every tap is an integer distance and a table read, identical in both builds. */
static int32_t gw_setup_(const pft_pte_t *p, uint32_t a, const pft_pte_axis_t *ap)
{
    pft_real_t *gw = p->gw[a];
    int32_t R = pft_floor_int(pft_mul_i(ap->reach, 64));
    if (R > (int32_t)PFT_PTE_GW_SIZE - 1) {
        R = (int32_t)PFT_PTE_GW_SIZE - 1;
    }
    for (int32_t k = 0; k <= R; ++k) {
        int32_t idx = pft_round_int(pft_mul_i(ap->inv_sw, k));
        gw[k] = idx < (int32_t)PFT_PTE_GTAB_SIZE ? p->gtab[idx] : PFT_C(0.0);
    }
    return R;
}

/* The taps of one scan phase: first cell, count, sum of the squared weights. */
typedef struct {
    int32_t lo, cnt;
    pft_real_t g2;
} phase_taps_t_;

/* Taps of scan phase ph of one axis (weight table gw, reach R in 1/64 cells) for a path
 * displaced by -shift cells at this frame; the weights go to w[]. */
static inline phase_taps_t_ phase_taps_(const pft_pte_t *p, const pft_real_t *gw,
                                        const pft_pte_axis_t *ap, int32_t R, pft_real_t shift,
                                        int32_t ph, pft_real_t *w)
{
    phase_taps_t_ t;
    pft_real_t pos = pft_sub(pft_add(ap->c0, pft_mul_i(p->cfg.c_step, ph)), shift);
    int32_t q = pft_round_int(pft_mul_i(pft_clamp(pos, PFT_C(-30000.0), PFT_C(30000.0)), 64));
    int32_t hi = fdiv64_(q + R);
    t.lo = -fdiv64_(R - q); /* ceil((q - R) / 64) */
    if (hi - t.lo + 1 > (int32_t)PFT_PTE_MAX_TAPS) {
        hi = t.lo + (int32_t)PFT_PTE_MAX_TAPS - 1;
    }
    t.cnt = hi >= t.lo ? hi - t.lo + 1 : 0;
    const int32_t lo = t.lo;
    const int32_t cnt = t.cnt;
    pft_real_t g2 = PFT_C(0.0);
    for (int32_t i = 0; i < cnt; ++i) {
        int32_t k = (lo + i) * 64 - q;
        pft_real_t g = gw[k < 0 ? -k : k];
        w[i] = g;
        g2 = pft_add(g2, pft_sq(g));
    }
    t.g2 = g2;
    return t;
}

/* Scan phases of an axis: positions one cell apart have the same weights, so when
 * c_step = 1/period only `period` phases are computed. */
static int32_t phases_(const pft_pte_t *p, const pft_pte_axis_t *ap)
{
    return (p->period == 0u || (int32_t)p->period > ap->ns) ? ap->ns : (int32_t)p->period;
}

/* Tap lists of every scan position of one axis for a path displaced by -shift cells at this
 * frame; writes the sums of squared weights into gs[]. The phases are computed once and the
 * other positions reuse them shifted by whole cells (clipped at the image edges). tlo[4j..]:
 * first cell, count, offset of the first weight in tw. */
static void taps_(const pft_pte_t *p, uint32_t a, const pft_pte_axis_t *ap, int32_t R,
                  pft_real_t shift, pft_real_t *gs)
{
    pft_real_t *tw = p->tw[a];
    int16_t *tl = p->tlo[a];
    pft_pte_scratch_t *s = p->scr;
    int32_t np = phases_(p, ap);
    for (int32_t ph = 0; ph < np; ++ph) {
        phase_taps_t_ t = phase_taps_(p, p->gw[a], ap, R, shift, ph, tw + (size_t)ph * PFT_PTE_MAX_TAPS);
        s->blo[ph] = t.lo;
        s->bcnt[ph] = t.cnt;
        s->bg[ph] = t.g2;
    }
    for (int32_t j = 0; j < ap->ns; ++j) {
        int32_t ph = j % np;
        int32_t lo = s->blo[ph] + j / np;
        int32_t cnt = s->bcnt[ph];
        int32_t off = 0;
        if (lo < 0) {
            off = -lo;
            cnt -= off;
            lo = 0;
        }
        if (lo + cnt > ap->ncell) {
            cnt = ap->ncell - lo;
        }
        if (cnt < 0) {
            cnt = 0;
            lo = 0;
            off = 0;
        }
        const pft_real_t *w = tw + (size_t)ph * PFT_PTE_MAX_TAPS + off;
        pft_real_t g2 = s->bg[ph];
        if (cnt != s->bcnt[ph]) {
            g2 = PFT_C(0.0);
            for (int32_t i = 0; i < cnt; ++i) {
                g2 = pft_add(g2, pft_sq(w[i]));
            }
        }
        tl[4 * j] = (int16_t)lo;
        tl[4 * j + 1] = (int16_t)cnt;
        tl[4 * j + 2] = (int16_t)((size_t)ph * PFT_PTE_MAX_TAPS + (size_t)off);
        gs[j] = g2;
    }
}

/* Range-time operator sums of one frame: for every scan position j, E[j] += sum g zeta and
 * G[j] += sum g^2 along the path displaced by -shift cells (taps as in taps_, fused with the
 * multiply-accumulate). */
static void accum_1d_(const pft_pte_t *p, const pft_pte_axis_t *ap, int32_t R, pft_real_t shift,
                      const pft_real_t *zf)
{
    const pft_real_t *gw = p->gw[0];
    pft_real_t w[PFT_PTE_MAX_TAPS];
    int32_t np = phases_(p, ap);
    for (int32_t ph = 0; ph < np; ++ph) {
        phase_taps_t_ t = phase_taps_(p, gw, ap, R, shift, ph, w);
        const int32_t lo = t.lo;
        const int32_t cnt = t.cnt;
        const pft_real_t g2 = t.g2;
        for (int32_t j = ph, u = lo; j < ap->ns; j += np, ++u) {
            pft_real_t e = PFT_C(0.0);
            pft_real_t g = g2;
            if (u >= 0 && u + cnt <= ap->ncell) {
                for (int32_t i = 0; i < cnt; ++i) {
                    e = pft_add(e, pft_mul(w[i], zf[u + i]));
                }
            } else {
                g = PFT_C(0.0);
                for (int32_t i = 0; i < cnt; ++i) {
                    if (u + i >= 0 && u + i < ap->ncell) {
                        e = pft_add(e, pft_mul(w[i], zf[u + i]));
                        g = pft_add(g, pft_sq(w[i]));
                    }
                }
            }
            p->sE[j] = pft_add(p->sE[j], e);
            p->sG[j] = pft_add(p->sG[j], g);
        }
    }
}

pft_real_t pft_pte_shift_(pft_real_t th, pft_real_t acc, int32_t tau)
{
    pft_real_t v = pft_div_i(pft_mul_i(th, tau), SV_);
    pft_real_t q = pft_div_i(pft_mul_i(acc, tau * tau), 2 * SA_);
    return pft_sub(v, q);
}

/* Displacement of a straight operator path (scaled slope). */
static pft_real_t line_shift_(pft_real_t th, int32_t tau)
{
    return pft_div_i(pft_mul_i(th, tau), SV_);
}

/* Transition and process noise of the scaled state (T = 1 frame). The noise intensity is
 * q = q_sd^2; it is formed as (q_sd SV)^2 and (q_sd SA)^2 so that it stays representable in
 * q16 (q itself, e.g. 4e-6, is below the q16 LSB). */
static void model_(const pft_pte_config_t *c, uint32_t a, pft_real_t F[16], pft_real_t Q[16])
{
    pft_real_t qv = pft_sq(pft_mul_i(c->q_sd[a], SV_)); /* SV^2 q */
    memset(F, 0, 16u * sizeof(pft_real_t));
    memset(Q, 0, 16u * sizeof(pft_real_t));
    F[0] = PFT_C(1.0);
    F[1] = pft_ratio(1, SV_);
    F[5] = PFT_C(1.0);
    F[10] = PFT_C(1.0);
    F[15] = PFT_C(1.0);
    if (c->motion == PFT_PTE_MOTION_CA) {
        pft_real_t qa = pft_sq(pft_mul_i(c->q_sd[a], SA_)); /* SA^2 q */
        F[2] = pft_ratio(1, 2 * SA_);
        F[6] = pft_ratio(SV_, SA_);
        /* white jerk: q [[1/20, 1/8, 1/6], [1/8, 1/3, 1/2], [1/6, 1/2, 1]], scaled by S Q S */
        Q[0] = pft_div_i(qv, SV_ * SV_ * 20);
        Q[1] = pft_div_i(qv, SV_ * 8);
        Q[2] = pft_div_i(qv, 6);             /* SA q / 6 = SV^2 q / 6 (SA = SV^2) */
        Q[5] = pft_div_i(qv, 3);
        Q[6] = pft_div_i(qa, 2 * SV_);       /* SV SA q / 2 */
        Q[10] = qa;
    } else {
        /* white acceleration: q [[1/3, 1/2], [1/2, 1]] */
        Q[0] = pft_div_i(qv, SV_ * SV_ * 3);
        Q[1] = pft_div_i(qv, SV_ * 2);
        Q[5] = qv;
    }
    Q[4] = Q[1];
    Q[8] = Q[2];
    Q[9] = Q[6];
}

/* v as a signed 16.16 fixed-point integer (any range of pft_real_t, both builds). */
static int64_t fix16_(pft_real_t v)
{
    int32_t ip = pft_floor_int(v);
    pft_real_t fr = pft_sub(v, pft_from_int(ip));
    return (int64_t)ip * 65536 + 2 * (int64_t)pft_round_int(pft_mul_i(fr, 32768));
}

/* TABLE: grid index of the path ending at c0 (cfix = 16.16 of c0, times SV) with scaled
 * slope tfix (16.16), tau frames back: round(yq (c0 - theta tau)) + YPAD yq. */
static int32_t grid_index_(int64_t cfix, int64_t tfix, int32_t tau, int32_t yq)
{
    int64_t num = (cfix - tfix * tau) * yq + ((int64_t)1 << 19);
    int64_t f = num >= 0 ? num / ((int64_t)1 << 20) : -((-num + ((int64_t)1 << 20) - 1) / ((int64_t)1 << 20));
    return (int32_t)f + (int32_t)PFT_PTE_YPAD * yq;
}


/* ------------------------------------------------------------------------ track step */

/* What the directions of one track step share. */
typedef struct {
    int32_t M;          /* operator length, frames */
    int32_t mm;         /* max(M, 2)^2 - 1 */
    int32_t n0, n1;     /* scan positions per axis (n1 = 1 for range-time) */
    int32_t nsc;        /* n0 * n1 */
    int32_t ndir;       /* L0 * L1 */
    int32_t reach64[2]; /* EXACT: reach of the per-frame weight table, 1/64 cells */
    int64_t cfix;       /* TABLE: 16.16 of the first scan position, times SV */
} step_geom_;

/* One operator direction: slopes per axis (scaled) and the log prior of its index. */
typedef struct {
    pft_real_t th[2];
    pft_real_t prior;
} dir_slope_;

/* Best scan position of one direction. */
typedef struct {
    int32_t jb;          /* index of the best summand */
    pft_real_t lse;      /* log of the sum over scan positions */
    pft_real_t cstar[2]; /* best end position per axis, parabola refined */
    pft_real_t t;        /* T at the best position (0 when G = 0) */
} dir_best_;

/* 1. Kalman prediction of the state and the amplitude. */
static void step_predict_(const pft_pte_t *p, pft_pte_track_t *t)
{
    const pft_pte_config_t *c = &p->cfg;
    for (uint32_t a = 0; a < p->naxes; ++a) {
        pft_real_t F[16];
        pft_real_t Q[16];
        model_(c, a, F, Q);
        pft_kf4_predict(t->x[a], t->P[a], F, Q);
    }
    t->amp_var = pft_add(t->amp_var, c->q_amp);
}

/* 2. Operator parameters of both axes, the log prior of every scan position, the EXACT
 * weight tables or the TABLE response rows every direction may read (computed once). */
static void step_geometry_(pft_pte_t *p, const pft_pte_track_t *t, step_geom_ *g)
{
    const pft_pte_config_t *c = &p->cfg;
    const uint32_t na = p->naxes;
    pft_pte_scratch_t *s = p->scr;
    pft_pte_axis_t *ap = s->ap;
    int32_t M = t->n_acc;
    if (M > (int32_t)c->max_len) {
        M = (int32_t)c->max_len;
    }
    if (M > (int32_t)p->ring.count) {
        M = (int32_t)p->ring.count;
    }
    if (M < 1) {
        M = 1;
    }
    memset(ap, 0, 2u * sizeof(*ap));
    for (uint32_t a = 0; a < na; ++a) {
        axis_setup_(p, t->x[a], t->P[a], a, M, &ap[a]);
        for (int32_t j = 0; j < ap[a].ns; ++j) {
            pft_real_t d = pft_mul_i(c->c_step, j - (ap[a].ns - 1) / 2);
            s->lc[a][j] = pft_neg(pft_div(pft_sq(d), pft_mul_i(ap[a].sc2, 2)));
        }
    }
    g->reach64[0] = 0;
    g->reach64[1] = 0;
    for (uint32_t a = 0; a < na && p->yq == 0u; ++a) {
        g->reach64[a] = gw_setup_(p, a, &ap[a]);
    }
    if (na == 1u) {
        ap[1].ns = 1;
        ap[1].L = 1;
        s->lc[1][0] = PFT_C(0.0);
    }
    g->M = M;
    g->n0 = ap[0].ns;
    g->n1 = ap[1].ns;
    g->ndir = ap[0].L * ap[1].L;
    g->nsc = g->n0 * g->n1;
    int32_t m1 = M > 1 ? M : 2;
    g->mm = m1 * m1 - 1;
    g->cfix = 0;
    if (p->yq > 0u) {
        int32_t h = (ap[0].L - 1) / 2;
        g->cfix = fix16_(ap[0].c0) * SV_;
        int64_t tlo = fix16_(pft_sub(ap[0].zt, pft_mul_i(ap[0].dth, h)));
        int64_t thi = fix16_(pft_add(ap[0].zt, pft_mul_i(ap[0].dth, h)));
        for (int32_t tau = 0; tau < M; ++tau) {
            int32_t b0 = grid_index_(g->cfix, thi, tau, p->yq);
            int32_t b1 = grid_index_(g->cfix, tlo, tau, p->yq);
            s->yrow[tau] = yframe_(p, (uint32_t)tau, b0, b1 + g->n0);
        }
    }
}

/* Slopes and log prior of direction li (index l0 + L0 l1). */
static dir_slope_ dir_slope_of_(const pft_pte_t *p, int32_t li)
{
    const pft_pte_axis_t *ap = p->scr->ap;
    dir_slope_ d;
    int32_t l[2];
    l[0] = li % ap[0].L;
    l[1] = li / ap[0].L;
    d.th[0] = PFT_C(0.0);
    d.th[1] = PFT_C(0.0);
    d.prior = PFT_C(0.0);
    for (uint32_t a = 0; a < p->naxes; ++a) {
        int32_t k = l[a] - (ap[a].L - 1) / 2;
        d.th[a] = pft_add(ap[a].zt, pft_mul_i(ap[a].dth, k));
        d.prior = pft_sub(d.prior, pft_mul_i(ap[a].prior_k, k * k));
    }
    return d;
}

/* TABLE: adds frame tau's responses along the direction of scaled slope tfix (16.16) to the
 * operator sums: one read per scan position. */
static void accum_table_(pft_pte_t *p, const step_geom_ *g, int64_t tfix, int32_t tau)
{
    const int32_t n0 = g->n0;
    int32_t b = grid_index_(g->cfix, tfix, tau, p->yq);
    int32_t ny = (int32_t)p->ny;
    const pft_real_t *yv = p->scr->yrow[tau];
    if (b >= 0 && b + n0 <= ny) {
        pft_real_t *restrict se = p->sE;
        pft_real_t *restrict sg = p->sG;
        const pft_real_t *restrict yb = yv + b;
        const pft_real_t *restrict gb = p->gq + b;
        /* plain additions: |y| <= zeta_clip * sum g <= 64 * 6.9 and at most 64 frames are
         * summed, so |E| < 28300 and G < 64 * 4.2 never overflow the q16 range (TABLE mode
         * requires zeta_clip <= 64, see config_check) */
        for (int32_t j0 = 0; j0 < n0; ++j0) {
            se[j0] = se[j0] + yb[j0];
            sg[j0] = sg[j0] + gb[j0];
        }
        return;
    }
    for (int32_t j0 = 0; j0 < n0; ++j0) {
        if (b + j0 >= 0 && b + j0 < ny) {
            p->sE[j0] = pft_add(p->sE[j0], yv[b + j0]);
            p->sG[j0] = pft_add(p->sG[j0], p->gq[b + j0]);
        }
    }
}

/* EXACT range-Doppler: adds frame zf (tau frames back) along slopes th to the operator sums
 * of the 2-D scan grid (separable weights). */
static void accum_2d_(pft_pte_t *p, const step_geom_ *g, const pft_real_t th[2], int32_t tau,
                      const pft_real_t *zf)
{
    pft_pte_scratch_t *s = p->scr;
    const size_t nr = p->cfg.in.n_range;
    taps_(p, 0u, &s->ap[0], g->reach64[0], line_shift_(th[0], tau), s->gs[0]);
    taps_(p, 1u, &s->ap[1], g->reach64[1], line_shift_(th[1], tau), s->gs[1]);
    for (int32_t j1 = 0; j1 < g->n1; ++j1) {
        int32_t lo1 = p->tlo[1][4 * j1];
        int32_t cnt1 = p->tlo[1][4 * j1 + 1];
        const pft_real_t *w1 = p->tw[1] + p->tlo[1][4 * j1 + 2];
        for (int32_t j0 = 0; j0 < g->n0; ++j0) {
            int32_t lo0 = p->tlo[0][4 * j0];
            int32_t cnt0 = p->tlo[0][4 * j0 + 1];
            const pft_real_t *w0 = p->tw[0] + p->tlo[0][4 * j0 + 2];
            pft_real_t e = PFT_C(0.0);
            for (int32_t i1 = 0; i1 < cnt1; ++i1) {
                const pft_real_t *zr = zf + (size_t)(lo1 + i1) * nr + (size_t)lo0;
                pft_real_t sum = PFT_C(0.0);
                for (int32_t i0 = 0; i0 < cnt0; ++i0) {
                    sum = pft_add(sum, pft_mul(w0[i0], zr[i0]));
                }
                e = pft_add(e, pft_mul(w1[i1], sum));
            }
            int32_t j = j1 * g->n0 + j0;
            p->sE[j] = pft_add(p->sE[j], e);
            p->sG[j] = pft_add(p->sG[j], pft_mul(s->gs[0][j0], s->gs[1][j1]));
        }
    }
}

/* 3. Operator sums E, G of one direction at every scan position, over the last M frames. */
static void dir_accumulate_(pft_pte_t *p, const step_geom_ *g, const dir_slope_ *d)
{
    for (int32_t j = 0; j < g->nsc; ++j) {
        p->sE[j] = PFT_C(0.0);
        p->sG[j] = PFT_C(0.0);
    }
    const int32_t M = g->M;
    if (p->yq > 0u) {
        const int64_t tfix = fix16_(d->th[0]);
        for (int32_t tau = 0; tau < M; ++tau) {
            accum_table_(p, g, tfix, tau);
        }
        return;
    }
    const pft_pte_axis_t *ap0 = &p->scr->ap[0];
    const int32_t R0 = g->reach64[0];
    const pft_real_t th0 = d->th[0];
    const bool one = p->naxes == 1u;
    for (int32_t tau = 0; tau < M; ++tau) {
        const pft_real_t *zf = pft_pte_ring_get_(&p->ring, (uint32_t)tau);
        if (one) {
            accum_1d_(p, ap0, R0, line_shift_(th0, tau), zf);
        } else {
            accum_2d_(p, g, d->th, tau, zf);
        }
    }
}

/* 4. Test statistic and log summand of every scan position, their log-sum, the best position
 * (parabola refined per axis) and its T. */
static dir_best_ dir_best_of_(pft_pte_t *p, const step_geom_ *g)
{
    const pft_pte_scratch_t *s = p->scr;
    const int32_t n0 = g->n0;
    dir_best_ r;
    pft_real_t lmax = PFT_REAL_MIN;
    r.jb = 0;
    for (int32_t j = 0; j < g->nsc; ++j) {
        /* max(T, 0)^2 = E (E / G) for E > 0, clamped at 150^2 (no square root here; q16:
         * the product saturates at 32768 before the clamp, with the same result) */
        pft_real_t t2 = PFT_C(0.0);
        if (p->sE[j] > PFT_C(0.0) && p->sG[j] > PFT_C(0.0)) {
            t2 = pft_min(pft_mul(p->sE[j], pft_div(p->sE[j], p->sG[j])), PFT_C(22500.0));
        }
        pft_real_t ls = pft_add(pft_add(s->lc[0][j % n0], s->lc[1][j / n0]), pft_mul(t2, PFT_C(0.5)));
        p->sL[j] = ls;
        if (ls > lmax) {
            lmax = ls;
            r.jb = j;
        }
    }
    pft_real_t ssum = PFT_C(0.0);
    for (int32_t j = 0; j < g->nsc; ++j) {
        ssum = pft_add(ssum, pft_exp(pft_sub(p->sL[j], lmax)));
    }
    r.lse = pft_add(lmax, pft_log(ssum));
    const int32_t jb = r.jb;
    r.cstar[0] = PFT_C(0.0);
    r.cstar[1] = PFT_C(0.0);
    for (uint32_t a = 0; a < p->naxes; ++a) {
        int32_t ja = a == 0u ? jb % n0 : jb / n0;
        int32_t na_ = a == 0u ? n0 : g->n1;
        int32_t stride = a == 0u ? 1 : n0;
        pft_real_t off = PFT_C(0.0);
        if (ja > 0 && ja < na_ - 1) {
            off = pft_pte_parabola_(p->sL[jb - stride], p->sL[jb], p->sL[jb + stride]);
        }
        r.cstar[a] = pft_add(s->ap[a].c0, pft_mul(p->cfg.c_step, pft_add(pft_from_int(ja), off)));
    }
    r.t = PFT_C(0.0);
    if (p->sG[jb] > PFT_C(0.0)) {
        r.t = pft_clamp(pft_div(p->sE[jb], pft_sqrt(p->sG[jb])), PFT_C(-150.0), PFT_C(150.0));
    }
    return r;
}

/* 5. Kalman update of the track's prediction with the direction's measurement [c*, theta]
 * per axis, and of its amplitude with E/G, into out. */
static void dir_update_(const pft_pte_t *p, const pft_pte_track_t *t, const step_geom_ *g,
                        const dir_slope_ *d, const dir_best_ *b, pft_pte_dir_t *out)
{
    const pft_pte_config_t *c = &p->cfg;
    const pft_pte_axis_t *ap = p->scr->ap;
    pft_real_t tc = pft_max(pft_sq(b->t), PFT_C(1.0));
    for (uint32_t a = 0; a < 2u; ++a) {
        memcpy(out->x[a], t->x[a], 4u * sizeof(pft_real_t));
        memcpy(out->P[a], t->P[a], 16u * sizeof(pft_real_t));
        if (a >= p->naxes) {
            continue;
        }
        pft_real_t z[2] = {b->cstar[a], d->th[a]};
        pft_real_t R[4];
        R[0] = pft_add(pft_div(ap[a].sw2, tc), pft_div_i(pft_sq(c->c_step), 12));
        /* slope variance 12 sigma_w^2 / ((M^2 - 1) T^2), scaled by SV^2 */
        R[3] = pft_add(pft_div_i(pft_sq(ap[a].dth), 12),
                       pft_div_i(pft_div(pft_mul_i(ap[a].sw2, 12 * SV_ * SV_), tc), g->mm));
        R[1] = PFT_C(0.0);
        R[2] = PFT_C(0.0);
        (void)pft_kf4_update2(out->x[a], out->P[a], ap[a].H, z, R); /* on failure the prediction stays */
    }
    /* amplitude: measurement E/G with variance 1/G */
    const int32_t jb = b->jb;
    pft_real_t am = t->amp;
    pft_real_t av = t->amp_var;
    if (p->sG[jb] > PFT_C(0.0)) {
        pft_real_t meas = pft_div(p->sE[jb], p->sG[jb]);
        pft_real_t r = pft_recip(p->sG[jb]);
        pft_real_t k = pft_div(av, pft_add(av, r));
        am = pft_add(am, pft_mul(k, pft_sub(meas, am)));
        av = pft_sub(av, pft_mul(k, av));
    }
    out->amp = am;
    out->amp_var = av;
    out->logw = pft_add(d->prior, b->lse);
    out->t = b->t;
}

/* 6. Fusion of the directions with their normalised likelihoods. Deviations from the
 * prediction are fused (X = X_pred + sum W (X_l - X_pred)) so that weights summing to
 * 1 - epsilon after rounding (q16) cannot bias the state. */
static void step_fuse_(pft_pte_t *p, pft_pte_track_t *t, int32_t ndir)
{
    const uint32_t na = p->naxes;
    pft_pte_dir_t *f = &p->scr->fused;
    (void)pft_lognormalize(p->scr->lw, p->dw, (size_t)ndir);
    memset(f, 0, sizeof(*f));
    pft_real_t as = PFT_C(0.0);
    for (int32_t li = 0; li < ndir; ++li) {
        pft_real_t w = pft_weight_to_real(p->dw[li]);
        const pft_pte_dir_t *d = &p->dir[li];
        for (uint32_t a = 0; a < na; ++a) {
            for (uint32_t i = 0; i < 3u; ++i) {
                f->x[a][i] = pft_add(f->x[a][i], pft_mul(w, pft_sub(d->x[a][i], t->x[a][i])));
            }
        }
        as = pft_add(as, pft_mul(w, pft_sub(d->amp, t->amp)));
    }
    for (uint32_t a = 0; a < na; ++a) {
        for (uint32_t i = 0; i < 3u; ++i) {
            f->x[a][i] = pft_add(t->x[a][i], f->x[a][i]);
        }
    }
    as = pft_add(t->amp, as);
    pft_real_t avs = PFT_C(0.0);
    for (int32_t li = 0; li < ndir; ++li) {
        pft_real_t w = pft_weight_to_real(p->dw[li]);
        const pft_pte_dir_t *d = &p->dir[li];
        for (uint32_t a = 0; a < na; ++a) {
            pft_real_t dv[3];
            for (uint32_t i = 0; i < 3u; ++i) {
                dv[i] = pft_sub(d->x[a][i], f->x[a][i]);
            }
            for (uint32_t i = 0; i < 3u; ++i) {
                for (uint32_t j = i; j < 3u; ++j) {
                    f->P[a][i * 4u + j] = pft_add(f->P[a][i * 4u + j],
                                                  pft_mul(w, pft_add(d->P[a][i * 4u + j], pft_mul(dv[i], dv[j]))));
                }
            }
        }
        avs = pft_add(avs, pft_mul(w, pft_add(d->amp_var, pft_sq(pft_sub(d->amp, as)))));
    }
    for (uint32_t a = 0; a < na; ++a) {
        for (uint32_t i = 0; i < 3u; ++i) {
            t->x[a][i] = f->x[a][i];
            for (uint32_t j = i; j < 3u; ++j) {
                t->P[a][i * 4u + j] = f->P[a][i * 4u + j];
                t->P[a][j * 4u + i] = f->P[a][i * 4u + j];
            }
        }
        t->P[a][0] = pft_max(t->P[a][0], PFT_REAL_EPS);
        t->P[a][5] = pft_max(t->P[a][5], PFT_REAL_EPS);
    }
    t->amp = as;
    t->amp_var = pft_max(avs, PFT_REAL_EPS);
}

/* 7. Detection test, misses, termination (also when the track left the image). */
static void step_maintain_(const pft_pte_t *p, pft_pte_track_t *t, pft_real_t tmax)
{
    const pft_pte_config_t *c = &p->cfg;
    t->score = tmax;
    t->detected = tmax >= c->eta_t;
    t->misses = t->detected ? 0u : (uint8_t)(t->misses + 1u);
    if (t->n_acc < c->max_len) {
        t->n_acc++;
    }
    t->age++;
    if (t->misses >= c->max_misses) {
        t->live = false;
    }
    /* a track that left the image has no data left */
    for (uint32_t a = 0; a < p->naxes; ++a) {
        int32_t n = a == 0u ? (int32_t)c->in.n_range : (int32_t)c->in.n_doppler;
        if (t->x[a][0] < PFT_C(-2.0) || t->x[a][0] > pft_from_int(n + 1)) {
            t->live = false;
        }
    }
}

void pft_pte_track_step_(pft_pte_t *p, pft_pte_track_t *t)
{
    step_geom_ g;
    step_predict_(p, t);
    step_geometry_(p, t, &g);
    pft_real_t tmax = PFT_REAL_MIN;
    for (int32_t li = 0; li < g.ndir; ++li) {
        dir_slope_ d = dir_slope_of_(p, li);
        dir_accumulate_(p, &g, &d);
        dir_best_ b = dir_best_of_(p, &g);
        if (b.t > tmax) {
            tmax = b.t;
        }
        dir_update_(p, t, &g, &d, &b, &p->dir[li]);
        p->scr->lw[li] = p->dir[li].logw;
    }
    step_fuse_(p, t, g.ndir);
    step_maintain_(p, t, tmax);
}
