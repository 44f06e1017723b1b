/* One TBD filter: RBPF-TBD (ALGORITHMS.md 2.3-2.5) and the bootstrap PF-TBD (2.9). */
#include <string.h>

#include "tbd_int.h"
#include "../core/acc_int.h"
#include "../core/num_int.h"

/* ---------------------------------- layout ------------------------------------------------ */

size_t pft_tbd_particle_bytes_(uint32_t n, pft_tbd_kind_t kind)
{
    return PFT_TBD_PARTICLE_BYTES_(n, kind);
}

static void carve_set_(pft_tbd_particles_t *p, pft_tbd_kind_t kind, uint32_t n, pft_ws_t *ws)
{
    size_t rb = (size_t)n * sizeof(pft_real_t);
    p->x = (pft_real_t *)pft_ws_take(ws, rb);
    p->y = (pft_real_t *)pft_ws_take(ws, rb);
    p->in = (pft_real_t *)pft_ws_take(ws, rb);
    p->mx = (pft_real_t *)pft_ws_take(ws, rb);
    p->my = (pft_real_t *)pft_ws_take(ws, rb);
    if (kind == PFT_TBD_RBPF) {
        p->px = (pft_real_t *)pft_ws_take(ws, rb);
        p->py = (pft_real_t *)pft_ws_take(ws, rb);
    } else {
        p->px = NULL;
        p->py = NULL;
    }
    p->e = (uint8_t *)pft_ws_take(ws, n);
}

void pft_tbd_particles_carve_(pft_tbd_filter_t *f, pft_ws_t *ws)
{
    carve_set_(&f->cur, f->kind, f->n, ws);
    carve_set_(&f->nxt, f->kind, f->n, ws);
    f->lw = (pft_real_t *)pft_ws_take(ws, (size_t)f->n * sizeof(pft_real_t));
    f->w = (pft_weight_t *)pft_ws_take(ws, (size_t)f->n * sizeof(pft_weight_t));
    f->idx = (uint32_t *)pft_ws_take(ws, (size_t)f->n * sizeof(uint32_t));
}

void pft_tbd_filter_reset_stats_(pft_tbd_filter_t *f)
{
    memset(&f->est, 0, sizeof(f->est));
    memset(f->lr_hist, 0, sizeof(f->lr_hist));
    memset(f->win_hist, 0, sizeof(f->win_hist));
    f->n_lr = 0;
    f->n_win = 0;
    f->gone = false;
    f->birth_lw = PFT_C(0.0);
}

void pft_tbd_filter_setup_(pft_tbd_filter_t *f, const pft_tbd_config_t *cfg, uint32_t n,
                           pft_tbd_kind_t kind, bool births, bool constrain, uint64_t seed)
{
    memset(f, 0, sizeof(*f));
    f->cfg = *cfg;
    f->kind = kind;
    f->n = n;
    f->births = births;
    f->constrain = constrain;
    pft_tbd_meas_init(&f->model, cfg);
    f->log_n = pft_log_count_(n);
    f->log_ratio = pft_log(cfg->dis_ratio);
    pft_real_t T = cfg->T;
    pft_real_t T3 = pft_mul(pft_sq(T), T);
    f->kf_qpos = pft_div(pft_mul(cfg->q1, T3), PFT_C(3.0));
    pft_real_t q1T = pft_mul(cfg->q1, T);
    f->kf_qvel = cfg->kf_variant == PFT_TBD_KF_EXACT ? pft_mul(q1T, PFT_C(0.25)) : q1T;
    /* chol of q1 [[T^3/3, T^2/2], [T^2/2, T]]: L11 = sqrt(q1T^3/3), L21 = q1T^2/2 / L11,
     * L22 = sqrt(q1T/4). */
    f->ch_pos = pft_sqrt(f->kf_qpos);
    f->ch_cross = f->ch_pos > PFT_C(0.0)
                      ? pft_div(pft_mul(pft_mul(cfg->q1, pft_sq(T)), PFT_C(0.5)), f->ch_pos)
                      : PFT_C(0.0);
    f->ch_vel = pft_sqrt(pft_mul(q1T, PFT_C(0.25)));
    f->ch_int = pft_sqrt(pft_mul(cfg->q2, T));
    f->vel_sd[0] = pft_sqrt(cfg->vel_var[0]);
    f->vel_sd[1] = pft_sqrt(cfg->vel_var[1]);
    f->p16_b = pft_p16_(cfg->pb);
    f->p16_d = pft_p16_(cfg->pd);
    f->p16_eta = pft_p16_(cfg->eta);
    pft_rng_seed(&f->rng, seed);
    pft_tbd_filter_reset_stats_(f);
}

static void clear_set_(pft_tbd_particles_t *p, pft_tbd_kind_t kind, uint32_t n)
{
    size_t rb = (size_t)n * sizeof(pft_real_t);
    memset(p->x, 0, rb);
    memset(p->y, 0, rb);
    memset(p->in, 0, rb);
    memset(p->mx, 0, rb);
    memset(p->my, 0, rb);
    if (kind == PFT_TBD_RBPF) {
        memset(p->px, 0, rb);
        memset(p->py, 0, rb);
    }
    memset(p->e, 0, n);
}

void pft_tbd_filter_clear_(pft_tbd_filter_t *f)
{
    clear_set_(&f->cur, f->kind, f->n);
    clear_set_(&f->nxt, f->kind, f->n);
    memset(f->lw, 0, (size_t)f->n * sizeof(pft_real_t));
    memset(f->w, 0, (size_t)f->n * sizeof(pft_weight_t));
    memset(f->idx, 0, (size_t)f->n * sizeof(uint32_t));
}

/* ---------------------------------- propagation ------------------------------------------- */

/* Per-axis Kalman quantities depend only on the incoming variance p (the Riccati recursion
 * does not see the data), and after resampling most particles share p: a one-entry memo. */
typedef struct {
    pft_real_t p_in, sd, k, p_out;
    bool valid;
} kf_memo_t;

typedef struct {
    pft_real_t T, T2, c32T, qpos, qvel;
    bool exact;
} kf_consts_t;

static void kf_axis_(const kf_consts_t *kc, kf_memo_t *mm, pft_real_t *pos, pft_real_t *m,
                     pft_real_t *p, pft_real_t g)
{
    if (!mm->valid || mm->p_in != *p) {
        pft_real_t pin = *p;
        pft_real_t nv = pft_add(pft_mul(kc->T2, pin), kc->qpos); /* N = T^2 P + q1 T^3/3 */
        pft_real_t k = nv > PFT_C(0.0) ? pft_div(pft_mul(kc->T, pin), nv) : PFT_C(0.0);
        pft_real_t pplus = pft_sub(pin, pft_mul(pft_mul(k, kc->T), pin)); /* P - K N K' */
        pplus = pft_max(pplus, PFT_C(0.0));
        mm->p_in = pin;
        mm->sd = pft_sqrt(nv);
        mm->k = k;
        mm->p_out = kc->exact ? pft_add(pft_mul(pplus, PFT_C(0.25)), kc->qvel)
                              : pft_add(pplus, kc->qvel);
        mm->valid = true;
    }
    /* 1. sample the position: y = zeta_k - zeta_{k-1} = T m + sqrt(N) g */
    pft_real_t innov = pft_mul(mm->sd, g);
    pft_real_t dpos = pft_add(pft_mul(kc->T, *m), innov);
    *pos = pft_add(*pos, dpos);
    /* 2. measurement update with y: m+ = m + K (y - T m) */
    pft_real_t mplus = pft_add(*m, pft_mul(mm->k, innov));
    /* 3. time update */
    *m = kc->exact ? pft_sub(pft_mul(kc->c32T, dpos), pft_mul(mplus, PFT_C(0.5))) : mplus;
    *p = mm->p_out;
}

static void birth_(pft_tbd_filter_t *f, const pft_tbd_scene_t_ *sc, uint32_t s)
{
    pft_tbd_particles_t *P = &f->cur;
    const pft_tbd_config_t *c = &f->cfg;
    uint32_t k = sc->cand[pft_rng_below(&f->rng, sc->n_cand)];
    uint32_t col = k % c->width;
    uint32_t row = k / c->width;
    pft_real_t ux = pft_rng_uniform(&f->rng);
    pft_real_t uy = pft_rng_uniform(&f->rng);
    /* pixel i = col + 1 covers [(i - 0.5) dx, (i + 0.5) dx) */
    P->x[s] = pft_mul(pft_add(pft_add(pft_from_int((int32_t)col), PFT_C(0.5)), ux), c->dx);
    P->y[s] = pft_mul(pft_add(pft_add(pft_from_int((int32_t)row), PFT_C(0.5)), uy), c->dy);
    P->in[s] = pft_rng_uniform_range(&f->rng, c->i_min, c->i_max);
    if (f->kind == PFT_TBD_RBPF) {
        P->mx[s] = c->vel_mean[0];
        P->my[s] = c->vel_mean[1];
        P->px[s] = c->vel_var[0];
        P->py[s] = c->vel_var[1];
    } else {
        P->mx[s] = pft_add(c->vel_mean[0], pft_mul(f->vel_sd[0], pft_rng_gauss(&f->rng)));
        P->my[s] = pft_add(c->vel_mean[1], pft_mul(f->vel_sd[1], pft_rng_gauss(&f->rng)));
    }
}

static void pf_axis_(const pft_tbd_filter_t *f, pft_real_t T, pft_real_t *pos, pft_real_t *v,
                     pft_real_t g1, pft_real_t g2)
{
    *pos = pft_add(*pos, pft_add(pft_mul(T, *v), pft_mul(f->ch_pos, g1)));
    *v = pft_add(*v, pft_add(pft_mul(f->ch_cross, g1), pft_mul(f->ch_vel, g2)));
}

/* ---------------------------------- statistics -------------------------------------------- */

static void estimate_(pft_tbd_filter_t *f)
{
    const pft_tbd_particles_t *P = &f->cur;
    const pft_weight_t *w = f->w;
    pft_wacc_t wt = 0;
    pft_wacc_t we = 0;
    pft_acc_t_ sx = PFT_ACC_ZERO_, sy = PFT_ACC_ZERO_, svx = PFT_ACC_ZERO_, svy = PFT_ACC_ZERO_,
               si = PFT_ACC_ZERO_;
    for (uint32_t s = 0; s < f->n; ++s) {
        wt += w[s];
        if (P->e[s] != 0u) {
            we += w[s];
            sx += pft_acc_wx_(w[s], P->x[s]);
            sy += pft_acc_wx_(w[s], P->y[s]);
            svx += pft_acc_wx_(w[s], P->mx[s]);
            svy += pft_acc_wx_(w[s], P->my[s]);
            si += pft_acc_wx_(w[s], P->in[s]);
        }
    }
    pft_tbd_estimate_t *e = &f->est;
    e->p_exist = pft_wratio_(we, wt);
    e->n_eff = pft_ess(w, f->n);
    if (we > 0) {
        e->x = pft_acc_div_(sx, we);
        e->y = pft_acc_div_(sy, we);
        e->vx = pft_acc_div_(svx, we);
        e->vy = pft_acc_div_(svy, we);
        e->intensity = pft_acc_div_(si, we);
        pft_acc_t_ cxx = PFT_ACC_ZERO_, cxy = PFT_ACC_ZERO_, cyy = PFT_ACC_ZERO_;
        for (uint32_t s = 0; s < f->n; ++s) {
            if (P->e[s] != 0u) {
                pft_real_t ddx = pft_sub(P->x[s], e->x);
                pft_real_t ddy = pft_sub(P->y[s], e->y);
                cxx += pft_acc_wx_(w[s], pft_sq(ddx));
                cxy += pft_acc_wx_(w[s], pft_mul(ddx, ddy));
                cyy += pft_acc_wx_(w[s], pft_sq(ddy));
            }
        }
        e->pos_cov[0] = pft_acc_div_(cxx, we);
        e->pos_cov[1] = pft_acc_div_(cxy, we);
        e->pos_cov[2] = pft_acc_div_(cyy, we);
        e->valid = true;
    }
}

/* Windowed log likelihood ratio and the disappearance test (ALGORITHMS.md 2.6). lr_hist[0]
 * and win_hist[0] are the newest entries. */
static void disappearance_(pft_tbd_filter_t *f)
{
    uint32_t r1 = (uint32_t)f->cfg.dis_r + 1u;
    uint32_t np = f->cfg.dis_prev;
    /* the whole history is kept: the manager's end_lr_frames test reads it too */
    for (uint32_t q = PFT_TBD_MAX_DIS_R; q > 0u; --q) {
        f->lr_hist[q] = f->lr_hist[q - 1u];
    }
    f->lr_hist[0] = f->est.log_mean_lr;
    if (f->n_lr < PFT_TBD_MAX_DIS_R + 1u) {
        ++f->n_lr;
    }
    f->gone = false;
    if (f->n_lr < r1) {
        return;
    }
    pft_real_t win = PFT_C(0.0);
    for (uint32_t q = 0; q < r1; ++q) {
        win = pft_add(win, f->lr_hist[q]);
    }
    if (f->n_win > 0u && f->cfg.dis_ratio_test) {
        pft_real_t lmax = f->win_hist[0];
        for (uint32_t q = 1; q < f->n_win; ++q) {
            lmax = pft_max(lmax, f->win_hist[q]);
        }
        /* L(W) < ratio * L_max, in logs */
        f->gone = win < pft_add(lmax, f->log_ratio);
    }
    for (uint32_t q = np - 1u; q > 0u; --q) {
        f->win_hist[q] = f->win_hist[q - 1u];
    }
    f->win_hist[0] = win;
    if (f->n_win < np) {
        ++f->n_win;
    }
}

static void resample_(pft_tbd_filter_t *f)
{
    if (pft_resample(PFT_RESAMPLE_SYSTEMATIC, f->w, f->n, f->idx, f->n, &f->rng, NULL, 0u) !=
        PFT_OK) {
        return; /* cannot happen after log-normalisation (the largest weight is 1) */
    }
    pft_tbd_particles_t *a = &f->cur;
    pft_tbd_particles_t *b = &f->nxt;
    const uint32_t *idx = f->idx;
    bool rb = f->kind == PFT_TBD_RBPF;
    for (uint32_t s = 0; s < f->n; ++s) {
        uint32_t k = idx[s];
        b->x[s] = a->x[k];
        b->y[s] = a->y[k];
        b->in[s] = a->in[k];
        b->mx[s] = a->mx[k];
        b->my[s] = a->my[k];
        if (rb) {
            b->px[s] = a->px[k];
            b->py[s] = a->py[k];
        }
        b->e[s] = a->e[k];
    }
    pft_tbd_particles_t t = *a;
    *a = *b;
    *b = t;
}

/* ---------------------------------- one iteration ----------------------------------------- */

void pft_tbd_filter_step_(pft_tbd_filter_t *f, const pft_tbd_scene_t_ *sc)
{
    const pft_tbd_config_t *c = &f->cfg;
    pft_tbd_particles_t *P = &f->cur;
    uint32_t p_birth = f->frames == 0u ? f->p16_eta : f->p16_b;
    bool can_birth = f->births && sc->n_cand > 0u;
    f->birth_lw = PFT_C(0.0);
    if (can_birth && c->birth_correction && sc->cand_is_b && sc->n_allowed > 0u) {
        f->birth_lw = pft_log(pft_ratio((int32_t)sc->n_cand, (int32_t)sc->n_allowed));
    }
    kf_consts_t kc;
    kc.T = c->T;
    kc.T2 = pft_sq(c->T);
    kc.c32T = pft_div(PFT_C(1.5), c->T);
    kc.qpos = f->kf_qpos;
    kc.qvel = f->kf_qvel;
    kc.exact = c->kf_variant == PFT_TBD_KF_EXACT;
    kf_memo_t mx = {0, 0, 0, 0, false};
    kf_memo_t my = {0, 0, 0, 0, false};
    bool rb = f->kind == PFT_TBD_RBPF;
    const uint8_t *mask = f->constrain ? sc->mask : NULL;

    for (uint32_t s = 0; s < f->n; ++s) {
        /* 1. existence (one draw per particle, decided on its top 16 bits) */
        uint32_t u = pft_rng_u32(&f->rng) >> 16;
        uint8_t e = P->e[s];
        bool born = false;
        if (e != 0u) {
            if (u < f->p16_d) {
                e = 0u;
            } else if (rb) {
                /* 2. survivors: RBPF sampling of (x, y, I) and the velocity Kalman filter */
                pft_real_t gx = pft_rng_gauss(&f->rng);
                pft_real_t gy = pft_rng_gauss(&f->rng);
                pft_real_t gi = pft_rng_gauss(&f->rng);
                kf_axis_(&kc, &mx, &P->x[s], &P->mx[s], &P->px[s], gx);
                kf_axis_(&kc, &my, &P->y[s], &P->my[s], &P->py[s], gy);
                P->in[s] = pft_add(P->in[s], pft_mul(f->ch_int, gi));
            } else {
                /* PF: X = F X + chol(V) n on the full state */
                pft_real_t g1 = pft_rng_gauss(&f->rng);
                pft_real_t g2 = pft_rng_gauss(&f->rng);
                pft_real_t g3 = pft_rng_gauss(&f->rng);
                pft_real_t g4 = pft_rng_gauss(&f->rng);
                pft_real_t g5 = pft_rng_gauss(&f->rng);
                pf_axis_(f, c->T, &P->x[s], &P->mx[s], g1, g2);
                pf_axis_(f, c->T, &P->y[s], &P->my[s], g3, g4);
                P->in[s] = pft_add(P->in[s], pft_mul(f->ch_int, g5));
            }
        } else if (can_birth && u < p_birth) {
            birth_(f, sc, s);
            e = 1u;
            born = true;
        }
        /* A particle whose window centre leaves the image leaves the surveillance region: E = 0
         * [A]. The constraint: a window centre inside a confirmed target's region forces E = 0. */
        if (e != 0u) {
            int32_t i0 = pft_tbd_pix_(P->x[s], f->model.inv_dx);
            int32_t j0 = pft_tbd_pix_(P->y[s], f->model.inv_dy);
            if (i0 < 1 || j0 < 1 || i0 > (int32_t)c->width || j0 > (int32_t)c->height) {
                e = 0u;
            } else if (mask != NULL &&
                       mask[(size_t)(j0 - 1) * c->width + (size_t)(i0 - 1)] != 0u) {
                e = 0u;
            }
        }
        P->e[s] = e;
        /* 3. log-weight (eq. 20; E = 0 particles have likelihood ratio 1) */
        pft_real_t lw = PFT_C(0.0);
        if (e != 0u) {
            lw = pft_tbd_meas_llr(&f->model, sc->img, P->x[s], P->y[s], P->in[s]);
            if (born) {
                lw = pft_add(lw, f->birth_lw);
            }
        }
        f->lw[s] = lw;
    }
    pft_real_t lse = pft_lognormalize(f->lw, f->w, f->n);
    f->est.log_mean_lr = pft_sub(lse, f->log_n);
    /* 4. estimates from the normalised weights, before resampling */
    estimate_(f);
    disappearance_(f);
    /* 5. systematic resampling */
    resample_(f);
    if (f->frames < UINT32_MAX) {
        ++f->frames;
    }
}

bool pft_tbd_filter_handover_(pft_tbd_filter_t *dst, pft_tbd_filter_t *src, const uint8_t *gate)
{
    uint32_t alive = 0;
    for (uint32_t s = 0; s < src->n; ++s) {
        bool a = src->cur.e[s] != 0u;
        if (a && gate != NULL) {
            int32_t i0 = pft_tbd_pix_(src->cur.x[s], src->model.inv_dx);
            int32_t j0 = pft_tbd_pix_(src->cur.y[s], src->model.inv_dy);
            a = i0 >= 1 && j0 >= 1 && i0 <= (int32_t)src->cfg.width &&
                j0 <= (int32_t)src->cfg.height &&
                gate[(size_t)(j0 - 1) * src->cfg.width + (size_t)(i0 - 1)] != 0u;
        }
        src->w[s] = a ? PFT_W_ONE : (pft_weight_t)0;
        alive += a ? 1u : 0u;
    }
    if (alive == 0u || dst->kind != src->kind) {
        return false;
    }
    if (pft_resample(PFT_RESAMPLE_SYSTEMATIC, src->w, src->n, dst->idx, dst->n, &dst->rng, NULL,
                     0u) != PFT_OK) {
        return false;
    }
    const pft_tbd_particles_t *a = &src->cur;
    pft_tbd_particles_t *b = &dst->cur;
    bool rb = dst->kind == PFT_TBD_RBPF;
    for (uint32_t s = 0; s < dst->n; ++s) {
        uint32_t k = dst->idx[s];
        b->x[s] = a->x[k];
        b->y[s] = a->y[k];
        b->in[s] = a->in[k];
        b->mx[s] = a->mx[k];
        b->my[s] = a->my[k];
        if (rb) {
            b->px[s] = a->px[k];
            b->py[s] = a->py[k];
        }
        b->e[s] = 1u;
    }
    /* estimates of the handed-over set (equal weights) */
    for (uint32_t s = 0; s < dst->n; ++s) {
        dst->w[s] = PFT_W_ONE;
    }
    pft_real_t lmlr = src->est.log_mean_lr;
    pft_real_t pex = src->est.p_exist;
    estimate_(dst);
    dst->est.log_mean_lr = lmlr;
    dst->est.p_exist = pex;
    return true;
}

/* ---------------------------------- public API -------------------------------------------- */

size_t pft_tbd_filter_workspace_size(const pft_tbd_config_t *cfg)
{
    if (pft_tbd_config_check(cfg, NULL) != PFT_OK) {
        return 0u;
    }
    return PFT_TBD_FILTER_WORKSPACE_BYTES(cfg->n_search, cfg->kind, cfg->width, cfg->height);
}

/* Sets up f (cfg checked) with its buffers carved from work; false (f zeroed) when short. */
static bool filter_build_(pft_tbd_filter_t *f, const pft_tbd_config_t *cfg, void *work,
                          size_t work_len)
{
    pft_ws_t ws;
    pft_ws_init(&ws, work, work_len);
    size_t npix = (size_t)cfg->width * cfg->height;
    pft_real_t *img = (pft_real_t *)pft_ws_take(&ws, npix * sizeof(pft_real_t));
    uint8_t *mask = (uint8_t *)pft_ws_take(&ws, npix);
    uint32_t *cand = (uint32_t *)pft_ws_take(&ws, npix * sizeof(uint32_t));
    pft_tbd_filter_setup_(f, cfg, cfg->n_search, cfg->kind, true, cfg->force_constraint,
                          cfg->seed);
    pft_tbd_particles_carve_(f, &ws);
    if (pft_ws_status(&ws) != PFT_OK) {
        memset(f, 0, sizeof(*f));
        return false;
    }
    f->img = img;
    f->mask = mask;
    f->cand = cand;
    memset(img, 0, npix * sizeof(pft_real_t));
    memset(mask, 0, npix);
    memset(cand, 0, npix * sizeof(uint32_t));
    pft_tbd_filter_clear_(f);
    return true;
}

pft_status_t pft_tbd_filter_init(pft_tbd_filter_t *f, const pft_tbd_config_t *cfg, void *work,
                                 size_t work_len)
{
    if (f == NULL || cfg == NULL || work == NULL) {
        return PFT_ERR_INVAL;
    }
    if (pft_tbd_config_check(cfg, NULL) != PFT_OK) {
        return PFT_ERR_CONFIG;
    }
    return filter_build_(f, cfg, work, work_len) ? PFT_OK : PFT_ERR_NOMEM;
}

pft_status_t pft_tbd_filter_reset(pft_tbd_filter_t *f)
{
    if (f == NULL) {
        return PFT_ERR_INVAL;
    }
    if (f->img == NULL || f->n == 0u) {
        return PFT_ERR_STATE; /* not initialised, or a layer owned by a pft_tbd_t */
    }
    /* the workspace starts at the (aligned) image buffer: carve it again from there */
    pft_tbd_config_t cfg = f->cfg;
    size_t len = PFT_TBD_FILTER_WORKSPACE_BYTES(cfg.n_search, cfg.kind, cfg.width, cfg.height) -
                 (PFT_WS_ALIGN - 1u);
    return filter_build_(f, &cfg, f->img, len) ? PFT_OK : PFT_ERR_NOMEM;
}

pft_status_t pft_tbd_filter_update(pft_tbd_filter_t *f, const pft_frame_t *frame)
{
    return pft_tbd_filter_update_ex(f, frame, NULL, 0u);
}

pft_status_t pft_tbd_filter_update_ex(pft_tbd_filter_t *f, const pft_frame_t *frame,
                                      const pft_tbd_region_t *regions, size_t n_regions)
{
    if (f == NULL || frame == NULL || (regions == NULL && n_regions > 0u)) {
        return PFT_ERR_INVAL;
    }
    if (f->img == NULL || f->n == 0u) {
        return PFT_ERR_STATE; /* not initialised, or a layer owned by a pft_tbd_t */
    }
    pft_status_t st = pft_tbd_frame_check_(&f->cfg, frame);
    if (st != PFT_OK) {
        return st;
    }
    pft_tbd_frame_convert_(&f->cfg, frame, f->img);
    size_t npix = (size_t)f->cfg.width * f->cfg.height;
    memset(f->mask, 0, npix);
    for (size_t r = 0; r < n_regions; ++r) {
        pft_tbd_mask_add_(&f->cfg, f->mask, &regions[r]);
    }
    pft_tbd_scene_t_ sc;
    pft_tbd_scene_build_(&f->cfg, f->img, n_regions > 0u ? f->mask : NULL, f->cand, &sc);
    pft_tbd_filter_step_(f, &sc);
    return PFT_OK;
}

pft_status_t pft_tbd_filter_estimate(const pft_tbd_filter_t *f, pft_tbd_estimate_t *out)
{
    if (f == NULL || out == NULL) {
        return PFT_ERR_INVAL;
    }
    *out = f->est;
    return PFT_OK;
}
