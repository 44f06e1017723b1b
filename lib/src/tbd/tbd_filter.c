/* One TBD filter: RBPF-TBD (docs/algorithms.md 2.3-2.5) and the bootstrap PF-TBD (2.9). */
#include <string.h>

#include "tbd_int.h"

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
    pft_tbd_meas_setup_(&f->model, cfg);
    f->log_n = pft_log_count_(n);
    f->log_ratio = pft_log(cfg->dis_ratio);
    pft_real_t T = cfg->T;
    f->kf_qpos = pft_div(pft_mul(cfg->q1, pft_mul(pft_sq(T), T)), PFT_C(3.0)); /* q1 T^3 / 3 */
    pft_real_t q1T = pft_mul(cfg->q1, T);
    f->kf_qvel = cfg->kf_variant == PFT_TBD_KF_EXACT ? pft_mul(q1T, PFT_C(0.25)) : q1T;
    pft_tbd_dyn_setup_(&f->dyn, cfg);
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

/* The kinematic state of particle s of P. */
static pft_tbd_kin_t kin_(pft_tbd_particles_t *P, uint32_t s)
{
    pft_tbd_kin_t k = {&P->x[s], &P->y[s], &P->mx[s], &P->my[s], &P->in[s]};
    return k;
}

/* b[s] = a[k] (the RBPF's Kalman variances too). */
static void copy_particle_(pft_tbd_particles_t *b, uint32_t s, const pft_tbd_particles_t *a,
                           uint32_t k, bool rb)
{
    b->x[s] = a->x[k];
    b->y[s] = a->y[k];
    b->in[s] = a->in[k];
    b->mx[s] = a->mx[k];
    b->my[s] = a->my[k];
    if (rb) {
        b->px[s] = a->px[k];
        b->py[s] = a->py[k];
    }
}

/* ---------------------------------- statistics -------------------------------------------- */

static void estimate_(pft_tbd_filter_t *f)
{
    const pft_tbd_particles_t *P = &f->cur;
    const pft_weight_t *w = f->w;
    pft_tbd_wsum_t a;
    pft_tbd_wsum_init_(&a);
    for (uint32_t s = 0; s < f->n; ++s) {
        const pft_real_t v[5] = {P->x[s], P->y[s], P->mx[s], P->my[s], P->in[s]};
        pft_tbd_wsum_add_(&a, w[s], P->e[s] != 0u, v);
    }
    pft_tbd_estimate_t *e = &f->est;
    e->p_exist = pft_tbd_wsum_p_(&a);
    e->n_eff = pft_ess(w, f->n);
    pft_real_t m[5];
    if (!pft_tbd_wsum_mean_(&a, m)) {
        return;
    }
    e->x = m[0];
    e->y = m[1];
    e->vx = m[2];
    e->vy = m[3];
    e->intensity = m[4];
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
    e->pos_cov[0] = pft_acc_div_(cxx, a.we);
    e->pos_cov[1] = pft_acc_div_(cxy, a.we);
    e->pos_cov[2] = pft_acc_div_(cyy, a.we);
    e->valid = true;
}

/* Windowed log likelihood ratio and the disappearance test (docs/algorithms.md 2.6). lr_hist[0]
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
    bool rb = f->kind == PFT_TBD_RBPF;
    for (uint32_t s = 0; s < f->n; ++s) {
        copy_particle_(b, s, a, f->idx[s], rb);
        b->e[s] = a->e[f->idx[s]];
    }
    pft_tbd_particles_t t = *a;
    *a = *b;
    *b = t;
}

/* ---------------------------------- one iteration ----------------------------------------- */

/* What one step needs beyond the filter: the scene, the Kalman constants and memos, the birth
 * and constraint switches of this frame. */
typedef struct {
    const pft_tbd_scene_t_ *sc;
    kf_consts_t kc;
    kf_memo_t mx, my;
    uint32_t p_birth;
    bool can_birth;
    const uint8_t *mask; /* exclusion mask applied to window centres (NULL: none) */
} step_ctx_t;

/* Steps 1-2 for particle s: existence, then the survivor's move (RBPF or PF) or a birth; a
 * particle whose window centre leaves the image, or enters the exclusion mask, gets E = 0.
 * Returns the new E; *born for a birth at this step. */
static uint8_t move_particle_(pft_tbd_filter_t *f, step_ctx_t *x, uint32_t s, bool *born)
{
    pft_tbd_particles_t *P = &f->cur;
    pft_tbd_kin_t k = kin_(P, s);
    uint32_t u = pft_tbd_exist_draw_(&f->rng); /* one draw per particle */
    uint8_t e = P->e[s];
    *born = false;
    if (e != 0u) {
        if (u < f->dyn.p16_d) {
            return 0u;
        }
        if (f->kind == PFT_TBD_RBPF) {
            /* RBPF sampling of (x, y, I) and the velocity Kalman filter */
            pft_real_t gx = pft_rng_gauss(&f->rng);
            pft_real_t gy = pft_rng_gauss(&f->rng);
            pft_real_t gi = pft_rng_gauss(&f->rng);
            kf_axis_(&x->kc, &x->mx, &P->x[s], &P->mx[s], &P->px[s], gx);
            kf_axis_(&x->kc, &x->my, &P->y[s], &P->my[s], &P->py[s], gy);
            P->in[s] = pft_add(P->in[s], pft_mul(f->dyn.ch_int, gi));
        } else {
            pft_tbd_pf_move_(&f->dyn, f->cfg.T, &f->rng, &k);
        }
    } else if (x->can_birth && u < x->p_birth) {
        bool rb = f->kind == PFT_TBD_RBPF;
        pft_tbd_birth_(&f->cfg, &f->dyn, x->sc->cand, x->sc->n_cand, !rb, &f->rng, &k);
        if (rb) {
            P->px[s] = f->cfg.vel_var[0];
            P->py[s] = f->cfg.vel_var[1];
        }
        e = 1u;
        *born = true;
    } else {
        return e;
    }
    /* [A] leaving the image ends the target; a window centre inside a confirmed target's
     * region forces E = 0 (the constraint) */
    size_t pix = 0;
    if (!pft_tbd_centre_(&f->model, P->x[s], P->y[s], &pix) ||
        (x->mask != NULL && x->mask[pix] != 0u)) {
        e = 0u;
    }
    return e;
}

void pft_tbd_filter_step_(pft_tbd_filter_t *f, const pft_tbd_scene_t_ *sc)
{
    const pft_tbd_config_t *c = &f->cfg;
    pft_tbd_particles_t *P = &f->cur;
    step_ctx_t x;
    memset(&x, 0, sizeof x);
    x.sc = sc;
    x.p_birth = pft_tbd_p_birth_(&f->dyn, f->frames == 0u);
    x.can_birth = f->births && sc->n_cand > 0u;
    x.mask = f->constrain ? sc->mask : NULL;
    x.kc.T = c->T;
    x.kc.T2 = pft_sq(c->T);
    x.kc.c32T = pft_div(PFT_C(1.5), c->T);
    x.kc.qpos = f->kf_qpos;
    x.kc.qvel = f->kf_qvel;
    x.kc.exact = c->kf_variant == PFT_TBD_KF_EXACT;
    f->birth_lw = x.can_birth ? pft_tbd_birth_lw_(c, sc) : PFT_C(0.0);
    for (uint32_t s = 0; s < f->n; ++s) {
        /* 1-2. existence, move or birth */
        bool born;
        uint8_t e = move_particle_(f, &x, s, &born);
        P->e[s] = e;
        /* 3. log-weight (eq. 20; E = 0 particles have likelihood ratio 1) */
        pft_real_t lw = PFT_C(0.0);
        if (e != 0u) {
            lw = pft_tbd_meas_llr_int_(&f->model, sc->img, P->x[s], P->y[s], P->in[s]);
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
            size_t pix = 0;
            a = pft_tbd_centre_(&src->model, src->cur.x[s], src->cur.y[s], &pix) && gate[pix] != 0u;
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
        copy_particle_(b, s, a, dst->idx[s], rb);
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

void pft_tbd_est_pub_(const pft_tbd_meas_t *m, const pft_tbd_estimate_t *in,
                      pft_tbd_estimate_t *out)
{
    *out = *in;
    if (in->valid) {
        out->x = pft_tbd_x_pub_(in->x, m->dx);
        out->y = pft_tbd_x_pub_(in->y, m->dy);
    }
}

pft_status_t pft_tbd_filter_estimate(const pft_tbd_filter_t *f, pft_tbd_estimate_t *out)
{
    if (f == NULL || out == NULL) {
        return PFT_ERR_INVAL;
    }
    pft_tbd_est_pub_(&f->model, &f->est, out);
    return PFT_OK;
}
