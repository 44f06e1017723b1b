/* One TBD filter: RBPF-TBD (docs/algorithms.md 2.3-2.5) and the bootstrap PF-TBD (2.9).
 *
 * One update is four passes over the particles, each a plain loop over the SoA arrays:
 *   1. existence, the move (RBPF: three ziggurat draws and the velocity filter's quantities
 *      for the particle's age from the tables; PF: five draws) or a birth, the window centre
 *      (leave-image and constraint tests) and the log-weight from the tabulated 3 x 3 kernel;
 *      the largest log-weight and its particle;
 *   2. the unnormalised weights exp(lw - max) and their sum;
 *   3. normalised weights by one reciprocal, the estimates, the effective sample size and the
 *      systematic resampling walk, which leaves each particle's replication count;
 *   4. resampling in place: each particle with r > 1 copies goes into r - 1 slots of
 *      particles with none (no second particle set).
 * Number formats and the ranges behind every rounding: docs/fixed_point.md ("Particle
 * kernels"); the kernels themselves are in lib/src/core/kern_int.h and tbd_int.h. */
#include <string.h>

#include "tbd_int.h"
#include "../core/seq_int.h"
#include "../core/num_int.h"
#include "../core/resample_int.h"

/* ---------------------------------- layout ------------------------------------------------ */

size_t pft_tbd_particle_bytes_(uint32_t n, pft_tbd_kind_t kind)
{
    return PFT_TBD_PARTICLE_BYTES_(n, kind);
}

void pft_tbd_particles_carve_(pft_tbd_filter_t *f, pft_ws_t *ws)
{
    pft_tbd_particles_t *p = &f->cur;
    size_t rb = (size_t)f->n * sizeof(pft_real_t);
    p->x = (pft_real_t *)pft_ws_take(ws, rb);
    p->y = (pft_real_t *)pft_ws_take(ws, rb);
    p->in = (pft_real_t *)pft_ws_take(ws, rb);
    p->vx = (pft_real_t *)pft_ws_take(ws, rb);
    p->vy = (pft_real_t *)pft_ws_take(ws, rb);
    p->e = (uint8_t *)pft_ws_take(ws, f->n);
    p->w = (pft_tbd_slot_t *)pft_ws_take(ws, (size_t)f->n * sizeof(pft_tbd_slot_t));
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
    f->bq = PFT_C(0.0);
    f->resid_n = 0u;
    f->resid_m = PFT_C(0.0);
    f->resid_x = PFT_C(0.0);
    f->resid_y = PFT_C(0.0);
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
    f->gamma_w = pft_mul(cfg->gamma, f->model.inv_sn);
    pft_tbd_dyn_setup_(&f->dyn, cfg);
    pft_rng_seed(&f->rng, seed);
    pft_tbd_filter_reset_stats_(f);
}

void pft_tbd_filter_clear_(pft_tbd_filter_t *f)
{
    pft_tbd_particles_t *p = &f->cur;
    size_t rb = (size_t)f->n * sizeof(pft_real_t);
    memset(p->x, 0, rb);
    memset(p->y, 0, rb);
    memset(p->in, 0, rb);
    memset(p->vx, 0, rb);
    memset(p->vy, 0, rb);
    memset(p->e, 0, f->n);
    memset(p->w, 0, (size_t)f->n * sizeof(pft_tbd_slot_t));
}

/* b[s] = a[k], the state byte (existence and age) included. */
static void copy_particle_(pft_tbd_particles_t *b, uint32_t s, const pft_tbd_particles_t *a,
                           uint32_t k)
{
    b->x[s] = a->x[k];
    b->y[s] = a->y[k];
    b->in[s] = a->in[k];
    b->vx[s] = a->vx[k];
    b->vy[s] = a->vy[k];
    b->e[s] = a->e[k];
}

/* ---------------------------------- pass 1: move and weigh -------------------------------- */

/* What one step needs beyond the filter: the scene, the tables, the birth and constraint
 * switches of this frame. */
typedef struct {
    const pft_tbd_scene_t_ *sc;
    const pft_tbd_tab_t *tab;
    const uint32_t *mask; /* exclusion mask applied to window centres (NULL: none) */
    pft_real_t T;
    uint32_t p_birth;
    uint8_t e_max; /* largest state byte: 1 + the age cap */
    bool can_birth;
    bool rb;
} step_ctx_t;

/* RBPF survivor of state byte e (age e - 1): the position is sampled from N(x + T m, N_a)
 * per axis, the velocity mean takes the Kalman update of that step (tbd_dyn.c), the intensity
 * a random walk. k points at the particle's state, the tables are tab's for that age. */
static inline void rbpf_move_(const pft_tbd_kin_t *k, const pft_tbd_tab_t *tab, pft_real_t T,
                              pft_real_t ch_int, uint32_t age, pft_rng_t *rng)
{
    const pft_real_t gx = pft_rng_zig_(rng);
    const pft_real_t gy = pft_rng_zig_(rng);
    const pft_real_t gi = pft_rng_zig_(rng);
    const pft_real_t vx = *k->vx;
    const pft_real_t vy = *k->vy;
    *k->x = pft_kmad2_(*k->x, T, vx, tab->kf_sd[0][age], gx);
    *k->vx = pft_kmad1_(vx, tab->kf_gsd[0][age], gx);
    *k->y = pft_kmad2_(*k->y, T, vy, tab->kf_sd[1][age], gy);
    *k->vy = pft_kmad1_(vy, tab->kf_gsd[1][age], gy);
    *k->in = pft_kmad1_(*k->in, ch_int, gi);
}

/* The loop invariants of the move passes, read once per pass into locals: no store of the
 * loops can reach them (in q16 the particle arrays hold int32_t, as many fields of f do), so
 * none is reloaded per particle, and the passes compile the same whether they are inlined or
 * called (they have two callers: the update and the lost-frames coast). */
typedef struct {
    pft_real_t *x, *y, *in, *vx, *vy;
    uint8_t *e;
    pft_tbd_dyn_t dyn;
    const pft_tbd_tab_t *tab;
    pft_real_t T;
    uint32_t p_birth; /* 0 when no birth is possible (u < 0 never holds) */
    uint32_t e_max;
    uint32_t n;
    /* the births': the scene's candidates (NULL and 0 without births: x->sc is not read then)
     * and the configuration (pft_tbd_birth_inv_t) */
    const uint32_t *cand;
    uint32_t n_cand;
    pft_tbd_birth_inv_t birth;
    bool sample_vel; /* PF births draw their velocity (!x->rb) */
} move_inv_t;

static inline move_inv_t move_inv_(const pft_tbd_filter_t *f, const step_ctx_t *x)
{
    move_inv_t v;
    v.x = f->cur.x;
    v.y = f->cur.y;
    v.in = f->cur.in;
    v.vx = f->cur.vx;
    v.vy = f->cur.vy;
    v.e = f->cur.e;
    v.dyn = f->dyn;
    v.tab = x->tab;
    v.T = x->T;
    v.p_birth = x->can_birth ? x->p_birth : 0u;
    v.e_max = x->e_max;
    v.n = f->n;
    v.cand = x->can_birth ? x->sc->cand : NULL;
    v.n_cand = x->can_birth ? x->sc->n_cand : 0u;
    v.birth = pft_tbd_birth_inv_(&f->cfg, &f->dyn);
    v.sample_vel = !x->rb;
    return v;
}

/* A birth into particle s with the pass's generator; the scene's candidates and the
 * configuration from the pass's locals v (pft_tbd_birth_pix_v_). Inline with every draw
 * inline (the ziggurat's slow path takes the words by value), so the generator, a local of
 * the pass, stays in registers: no copy of it is made (a copy passed in and returned by value
 * went through the stack at every birth on AArch64). */
static inline void move_birth_(const step_ctx_t *x, const move_inv_t *v, uint32_t s,
                               pft_rng_t *rng)
{
    pft_tbd_kin_t k = {&v->x[s], &v->y[s], &v->vx[s], &v->vy[s], &v->in[s]};
    const uint32_t n = pft_rng_below_(rng, v->n_cand); /* the pixel's draw comes first */
    const uint32_t p = v->cand != NULL ? v->cand[n] : pft_tbd_scene_pick_(x->sc, n);
    pft_tbd_birth_pix_v_(&v->birth, p, v->sample_vel, rng, &k);
}

/* Steps 1-2 of docs/algorithms.md 2.5 for every particle: existence, then the survivor's move
 * or a birth. The new state byte: 0 (no target), 1 (born now), 1 + age. One loop per kind (the
 * two differ in the survivor's move only), so the kind is not tested per particle. */
static void move_rbpf_(pft_tbd_filter_t *f, const step_ctx_t *x)
{
    const move_inv_t v = move_inv_(f, x);
    pft_rng_t rng = f->rng;
    for (uint32_t s = 0; s < v.n; ++s) {
        const uint32_t u = pft_tbd_exist_draw_(&rng); /* one draw per particle */
        uint32_t e = v.e[s];
        if (e != 0u) {
            if (u < v.dyn.p16_d) {
                e = 0u;
            } else {
                const pft_tbd_kin_t k = {&v.x[s], &v.y[s], &v.vx[s], &v.vy[s], &v.in[s]};
                rbpf_move_(&k, v.tab, v.T, v.dyn.ch_int, e - 1u, &rng);
                e = e < v.e_max ? e + 1u : e;
            }
        } else if (u < v.p_birth) {
            move_birth_(x, &v, s, &rng);
            e = 1u;
        } else {
            /* an empty slot without a birth stays empty */
        }
        v.e[s] = (uint8_t)e;
    }
    f->rng = rng;
}

static void move_pf_(pft_tbd_filter_t *f, const step_ctx_t *x)
{
    const move_inv_t v = move_inv_(f, x);
    pft_rng_t rng = f->rng;
    for (uint32_t s = 0; s < v.n; ++s) {
        const uint32_t u = pft_tbd_exist_draw_(&rng); /* one draw per particle */
        uint32_t e = v.e[s];
        if (e != 0u) {
            if (u < v.dyn.p16_d) {
                e = 0u;
            } else {
                const pft_tbd_kin_t k = {&v.x[s], &v.y[s], &v.vx[s], &v.vy[s], &v.in[s]};
                pft_tbd_pf_move_(&v.dyn, v.T, &rng, &k);
                e = e < v.e_max ? e + 1u : e;
            }
        } else if (u < v.p_birth) {
            move_birth_(x, &v, s, &rng);
            e = 1u;
        } else {
            /* an empty slot without a birth stays empty */
        }
        v.e[s] = (uint8_t)e;
    }
    f->rng = rng;
}

static void move_(pft_tbd_filter_t *f, const step_ctx_t *x)
{
    if (x->rb) {
        move_rbpf_(f, x);
    } else {
        move_pf_(f, x);
    }
}

/* Step 3 for every particle: a particle whose window centre leaves the image, or enters the
 * exclusion mask, gets E = 0 [A]; the others get the log-weight of eq. 20 (E = 0: likelihood
 * ratio 1), births (state byte 1) plus the birth correction. Returns the largest log-weight. */
static pft_real_t weigh_any_(pft_tbd_filter_t *f, const step_ctx_t *x)
{
    const pft_tbd_particles_t *P = &f->cur;
    /* a local copy that no store of the loop can reach: its fields (pitch, size, window) stay
     * loop invariants */
    const pft_tbd_meas_t mm = f->model;
    const pft_tbd_meas_t *m = &mm;
    const pft_tbd_scene_t_ *sc = x->sc;
    const pft_tbd_tab_t *tab = x->tab;
    const uint32_t *mask = x->mask;
    const uint32_t mwords = pft_tbd_mask_words_(m->width);
    uint8_t *restrict pe = P->e;
    pft_tbd_slot_t *restrict pw = P->w;
    const pft_real_t *restrict px = P->x;
    const pft_real_t *restrict py = P->y;
    const pft_real_t *restrict pin = P->in;
    const pft_real_t birth_lw = f->birth_lw;
    const uint32_t n = f->n;
    pft_real_t lmax = PFT_REAL_MIN;
    for (uint32_t s = 0; s < n; ++s) {
        pft_real_t lw = PFT_C(0.0);
        const uint32_t e = pe[s];
        if (e != 0u) {
            pft_tbd_cell_t c;
            if (!pft_tbd_cell_(m, px[s], py[s], &c) ||
                (mask != NULL &&
                 pft_tbd_masked_(mask, mwords, (uint32_t)(c.i - 1), (uint32_t)(c.j - 1)))) {
                pe[s] = 0u;
            } else {
                lw = pft_tbd_llr_sc_(m, tab, sc, &c, pin[s]);
                if (e == 1u) {
                    lw = pft_add(lw, birth_lw);
                }
            }
        }
        pw[s].lw = lw;
        lmax = pft_max(lmax, lw);
    }
    return lmax;
}

/* The same for the common case, the 3 x 3 window on the real-valued frame without a mask and
 * with unit pixel pitches, none of them tested per particle: the same values as weigh_any_. */
static pft_real_t weigh_3x3_(pft_tbd_filter_t *f, const step_ctx_t *x)
{
    const pft_tbd_particles_t *P = &f->cur;
    const pft_tbd_meas_t mm = f->model;
    const pft_tbd_meas_t *m = &mm;
    const pft_tbd_scene_t_ *sc = x->sc;
    const pft_real_t *img = sc->img;
    const pft_tbd_tab_t *tab = x->tab;
    uint8_t *restrict pe = P->e;
    pft_tbd_slot_t *restrict pw = P->w;
    const pft_real_t *restrict px = P->x;
    const pft_real_t *restrict py = P->y;
    const pft_real_t *restrict pin = P->in;
    const pft_real_t birth_lw = f->birth_lw;
    const uint32_t n = f->n;
    pft_real_t lmax = PFT_REAL_MIN;
    for (uint32_t s = 0; s < n; ++s) {
        pft_real_t lw = PFT_C(0.0);
        const uint32_t e = pe[s];
        if (e != 0u) {
            pft_tbd_cell_t c;
            /* pft_tbd_cell_ with dx = dy = 1 */
            if (!(pft_kcell_(px[s], m->hi_x, (int32_t)m->width, &c.i, &c.fx) &&
                  pft_kcell_(py[s], m->hi_y, (int32_t)m->height, &c.j, &c.fy))) {
                pe[s] = 0u;
            } else {
                lw = pft_tbd_llr3_(m, tab, img, &c, pin[s]);
                if (e == 1u) {
                    lw = pft_add(lw, birth_lw);
                }
            }
        }
        pw[s].lw = lw;
        lmax = pft_max(lmax, lw);
    }
    return lmax;
}

/* The Bernoulli form (docs/algorithms.md 2.11, below): log-weight of a particle dropped from the position density (left the image or entered the
 * exclusion mask): its weight underflows to 0 (pft_kwexp_). */
#define BERN_DROP_ PFT_C(-30000.0)

/* The IR pipeline's case (cfg.frame_format PFT_PIX_RES16): the 3 x 3 window on the frame
 * read in place, unit pixel pitches. */
static bool weigh_r16_case_(const pft_tbd_filter_t *f, const step_ctx_t *x)
{
    const pft_tbd_meas_t *m = &f->model;
    return m->p == 1u && x->sc->img == NULL && m->dx == PFT_REAL_ONE && m->dy == PFT_REAL_ONE;
}

/* Whether the window of cell c is summed in place by pft_tbd_llr3_r16_v_ without a call:
 * inside the edges (wi, hj) on a row that no patch may cover. The other windows (the edges,
 * a flagged row: pft_tbd_patch_in_win_, pft_tbd_llr3_r16_out_) call out of line. */
static inline bool r16_no_call_(const pft_tbd_r16_inv_t *v, const pft_tbd_cell_t *c)
{
    return (uint32_t)(c->i - 2) < v->wi && (uint32_t)(c->j - 2) < v->hj &&
           (v->pflag == NULL || v->pflag[c->j - 1] == 0u);
}

/* A live particle's log-weight from its likelihood ratio llr and state byte e: births (e = 1)
 * add l1, survivors of the Bernoulli form lp, survivors of the paper's form nothing. */
static inline pft_real_t group_lw_(pft_real_t llr, uint32_t e, bool bern, pft_real_t l1,
                                   pft_real_t lp)
{
    pft_real_t lw = llr;
    if (e == 1u) {
        lw = pft_add(lw, l1);
    } else if (bern) {
        lw = pft_add(lw, lp);
    } else {
        /* a survivor of the paper's form: the likelihood ratio alone */
    }
    return lw;
}

/* Whether weigh_r16_ runs its particles in a loop that makes no call (AArch64 float): the inner
 * loop stops at a window that needs a call (r16_no_call_ false: the image's edges and the
 * rows a patch may cover, about one window in nine on the real file), which the outer loop
 * weighs with the kernel's full form before the inner loop goes on from the next particle;
 * the particles in their order, each with the same operations, so the same values. The loop
 * invariants then need not survive a call in the inner loop: on AArch64 float gcc keeps them
 * in registers there instead of the stack (weigh_r16_ 3.48 -> 3.23 M instructions per frame
 * on the real file; docs/results/ir_clutter.md, "Branch ircost40"). q16 on AArch64 got
 * dearer (4.40 -> 4.49 M: its plain window leaves no registers free); x86-64 and the
 * Cortex-M builds keep the one loop. test_tbd_inplace compares this path with the
 * converting manager's (edges, patches, masked pixels) on every preset. */
#if !defined(PFT_NUMERIC_Q16) && defined(__aarch64__)
#define WEIGH_SPLIT_ 1
#else
#define WEIGH_SPLIT_ 0
#endif

/* weigh_any_ (bern false) and weigh_bern_any_ (bern true, the group log prior weights lb and
 * lp) in that case, the mask tested when set: one loop for both forms (WEIGH_SPLIT_: two
 * nested), so that the kernel (pft_tbd_llr3_r16_) has one call site and is inlined in both
 * builds, with the loop invariants in locals. The same values as those two. */
static pft_real_t weigh_r16_(pft_tbd_filter_t *f, const step_ctx_t *x, bool bern, pft_real_t lb,
                             pft_real_t lp)
{
    const pft_tbd_particles_t *P = &f->cur;
    const pft_tbd_meas_t mm = f->model;
    const pft_tbd_meas_t *m = &mm;
    const pft_tbd_scene_t_ *sc = x->sc;
    const pft_tbd_tab_t *tab = x->tab;
    const uint32_t *mask = x->mask;
    const uint32_t mwords = pft_tbd_mask_words_(m->width);
    uint8_t *restrict pe = P->e;
    pft_tbd_slot_t *restrict pw = P->w;
    const pft_real_t *restrict px = P->x;
    const pft_real_t *restrict py = P->y;
    const pft_real_t *restrict pin = P->in;
    /* the paper's form: E = 0 and dropped particles have log-weight 0, births the correction */
    const pft_real_t dead = bern ? BERN_DROP_ : PFT_C(0.0);
    const pft_real_t l1 = bern ? lb : f->birth_lw;
    const uint32_t n = f->n;
    const pft_tbd_r16_inv_t rv = pft_tbd_llr3_r16_inv_(m, tab, sc);
    pft_real_t lmax = bern ? BERN_DROP_ : PFT_REAL_MIN;
#if WEIGH_SPLIT_
    /* the inner loop's copy of the model: its address goes to no call (the stopped slot's
     * kernel takes m), so its fields stay in registers */
    const pft_tbd_meas_t mi = f->model;
    const pft_real_t hi_x = mi.hi_x, hi_y = mi.hi_y;
    const int32_t wd = (int32_t)mi.width, ht = (int32_t)mi.height;
    uint32_t s = 0u;
    while (s < n) {
        uint32_t e = 0u;
        pft_tbd_cell_t c;
        pft_real_t lw;
        for (; s < n; ++s) {
            lw = dead;
            e = pe[s];
            if (e != 0u) {
                /* pft_tbd_cell_ with dx = dy = 1 */
                if (pft_kcell2_(px[s], py[s], hi_x, hi_y, wd, ht, &c.i, &c.fx, &c.j, &c.fy) &&
                    (mask == NULL ||
                     !pft_tbd_masked_(mask, mwords, (uint32_t)(c.i - 1), (uint32_t)(c.j - 1)))) {
                    if (!r16_no_call_(&rv, &c)) {
                        break; /* slot s: weighed below */
                    }
                    lw = group_lw_(pft_tbd_llr3_r16_v_(&mi, tab, sc, &rv, &c, pin[s]), e, bern,
                                   l1, lp);
                } else {
                    pe[s] = 0u;
                }
            }
            pw[s].lw = lw;
            lmax = pft_max(lmax, lw);
        }
        if (s < n) {
            /* the slot the inner loop stopped at: live, its cell c inside and not masked */
            lw = group_lw_(pft_tbd_llr3_r16_v_(m, tab, sc, &rv, &c, pin[s]), e, bern, l1, lp);
            pw[s].lw = lw;
            lmax = pft_max(lmax, lw);
            ++s;
        }
    }
#else
    for (uint32_t s = 0; s < n; ++s) {
        pft_real_t lw = dead;
        const uint32_t e = pe[s];
        pft_tbd_cell_t c;
        if (e != 0u) {
            /* pft_tbd_cell_ with dx = dy = 1 */
            if (pft_kcell2_(px[s], py[s], m->hi_x, m->hi_y, (int32_t)m->width,
                            (int32_t)m->height, &c.i, &c.fx, &c.j, &c.fy) &&
                (mask == NULL ||
                 !pft_tbd_masked_(mask, mwords, (uint32_t)(c.i - 1), (uint32_t)(c.j - 1)))) {
                lw = group_lw_(pft_tbd_llr3_r16_v_(m, tab, sc, &rv, &c, pin[s]), e, bern, l1, lp);
            } else {
                pe[s] = 0u;
            }
        }
        pw[s].lw = lw;
        lmax = pft_max(lmax, lw);
    }
#endif
    return lmax;
}

static pft_real_t weigh_(pft_tbd_filter_t *f, const step_ctx_t *x)
{
    const pft_tbd_meas_t *m = &f->model;
    if (weigh_r16_case_(f, x)) {
        return weigh_r16_(f, x, false, PFT_C(0.0), PFT_C(0.0));
    }
    if (m->p == 1u && x->mask == NULL && m->dx == PFT_REAL_ONE && m->dy == PFT_REAL_ONE) {
        return weigh_3x3_(f, x);
    }
    return weigh_any_(f, x);
}

/* ---------------------------------- pass 2: weights --------------------------------------- */

/* w = exp(lw - max) (the largest is exactly PFT_W_ONE), in place; returns their sum
 * (q16: <= n 2^30 <= 2^52). Every E = 0 particle has lw = 0, so their common weight is
 * computed once. */
static pft_wacc_t weights_(pft_tbd_filter_t *f, pft_real_t lmax)
{
    pft_tbd_slot_t *restrict w = f->cur.w;
    const uint32_t n = f->n;
    pft_wacc_t sum = 0;
    uint32_t s = 0u;
#if defined(PFT_KWEXP_LANES_)
    /* float with 16-byte vectors: the weights in one vectorised pass (pft_kwexp_lanes_, the
     * same bits; an E = 0 particle's lw = 0 gets pft_kwexp_(0, lmax), the e0 below), then
     * their sum in the particles' order (the same sum) */
    pft_kwexp_lanes_(w, n, lmax);
    for (; s < n; ++s) {
        sum += w[s].w;
    }
    return sum;
#else
    const pft_weight_t e0 = pft_kwexp_(PFT_C(0.0), lmax);
    /* two particles at a time (pft_kwexp2_: in the float build their two exponentials
     * overlap), summed in the particles' order: the same bits */
    for (; s + 1u < n; s += 2u) {
        const pft_real_t la = w[s].lw;
        const pft_real_t lb = w[s + 1u].lw;
        pft_weight_t ea, eb;
        if (la != PFT_C(0.0) && lb != PFT_C(0.0)) {
            pft_kwexp2_(la, lb, lmax, &ea, &eb);
        } else {
            ea = la == PFT_C(0.0) ? e0 : pft_kwexp_(la, lmax);
            eb = lb == PFT_C(0.0) ? e0 : pft_kwexp_(lb, lmax);
        }
        w[s].w = ea;
        w[s + 1u].w = eb;
        sum += ea;
        sum += eb;
    }
    if (s < n) {
        const pft_real_t lw = w[s].lw;
        const pft_weight_t e = lw == PFT_C(0.0) ? e0 : pft_kwexp_(lw, lmax);
        w[s].w = e;
        sum += e;
    }
    return sum;
#endif
}

/* ---------------------------------- pass 3: estimates and counts -------------------------- */

/* The sums of pass 3: total normalised weight and its square, the weight of the E = 1
 * particles and their weighted x, y, vx, vy, I, and second moments of the position about a
 * reference point r (the previous estimate, or the image centre). */
typedef struct {
    pft_wacc_t w, w2, we;
    pft_acc_t_ s[5];
    pft_acc_t_ cxx, cxy, cyy;
    pft_real_t rx, ry;
} est_sums_t;

static void est_finish_(pft_tbd_estimate_t *e, const est_sums_t *a)
{
    e->p_exist = pft_wratio_(a->we, a->w);
    e->n_eff = pft_kess_(a->w, a->w2);
    if (!(a->we > 0)) {
        return; /* no E = 1 weight: the kinematic estimate keeps its last value */
    }
    e->x = pft_acc_div_(a->s[0], a->we);
    e->y = pft_acc_div_(a->s[1], a->we);
    e->vx = pft_acc_div_(a->s[2], a->we);
    e->vy = pft_acc_div_(a->s[3], a->we);
    e->intensity = pft_acc_div_(a->s[4], a->we);
    /* spread about the mean from the moments about the reference: E[d d'] - E[d] E[d'] */
    {
        const pft_real_t mx = pft_sub(e->x, a->rx);
        const pft_real_t my = pft_sub(e->y, a->ry);
        e->pos_cov[0] = pft_max(pft_sub(pft_acc_div_(a->cxx, a->we), pft_sq(mx)), PFT_C(0.0));
        e->pos_cov[1] = pft_sub(pft_acc_div_(a->cxy, a->we), pft_mul(mx, my));
        e->pos_cov[2] = pft_max(pft_sub(pft_acc_div_(a->cyy, a->we), pft_sq(my)), PFT_C(0.0));
    }
    e->valid = true;
}

/* The count slot of a particle the walk did not draw: this flag and the index of the next such
 * slot (n after the last one). Counts are at most n <= 2^22, so the flag tells them apart. */
#define SLOT_EMPTY_ 0x80000000u

/* Whether pass 3 runs its sums and its walk as two loops over the particles. q16: in one loop
 * their live values (eleven 64-bit sums, the walk's state, seven arrays) do not fit the
 * registers and spill; two loops read the weights twice and spill nothing. float: the sums
 * live in FP registers, and in one loop the walk's serial chain overlaps them. The same
 * values either way (every sum adds the same terms in the same order). */
#ifdef PFT_NUMERIC_Q16
#define EST_TWO_LOOPS_ 1
#else
#define EST_TWO_LOOPS_ 0
#endif

/* Whether pass 3's eight weighted sums of an E = 1 particle (x, y, vx, vy, I and the three
 * second moments) go through one array of eight floats, so that gcc adds them as two 4-lane
 * vectors (float where the compiler has 16-byte vectors: SSE2, NEON). Each lane is one sum
 * with its own terms in the particles' order and each term is the same product (wn v, the
 * moments wn (dx dx), wn (dx dy), wn (dy dy)), so every sum has the scalar form's bits. Without
 * vectors (Cortex-M) the array would go through memory: the scalar form. */
#if !defined(PFT_NUMERIC_Q16) && (defined(__SSE2__) || defined(__ARM_NEON))
#define EST_LANES_ 1
#else
#define EST_LANES_ 0
#endif
/* The lanes form runs the walk in its loop (one loop, as the float build does). */
#if EST_LANES_ && EST_TWO_LOOPS_
#error "EST_LANES_ has no two-loop form: set one of EST_LANES_ and EST_TWO_LOOPS_"
#endif

/* One step of pass 3's walk: slot s (weight e; cum: the weights before it, then with it)
 * takes its replication count, and when that is 0 joins the chain of empty slots after the
 * one link names; returns where the next empty slot's index goes. */
static inline uint32_t *walk_slot_(pft_tbd_slot_t *w, uint32_t s, pft_weight_t e, pft_sys_t *sys,
                                   pft_wacc_t *cum, uint32_t *link)
{
    uint32_t *next = link;
    *cum += e;
    w[s].n = pft_sys_take_(sys, *cum);
    if (w[s].n == 0u) {
        *link = SLOT_EMPTY_ | s;
        next = &w[s].n;
    }
    return next;
}

/* Step 4 of docs/algorithms.md 2.5 from the weights of pass 2 (sum sum), fused with the walk
 * of systematic resampling (step 5): each slot ends holding its particle's replication count,
 * or SLOT_EMPTY_ and the next empty slot (returns the first: the chain replicate_ follows).
 * The walk runs over the unnormalised weights, whose total is exact. Every E = 0 particle has
 * the same weight e0 (pass 2 gave them all the same log-weight), so their share of the total
 * and of the sum of squares is added once for all of them. */
static uint32_t estimate_and_count_(pft_tbd_filter_t *f, pft_wacc_t sum, pft_weight_t e0)
{
    pft_tbd_particles_t *P = &f->cur;
    pft_tbd_slot_t *restrict w = P->w;
    const uint8_t *restrict pe = P->e;
    const pft_real_t *restrict px = P->x;
    const pft_real_t *restrict py = P->y;
    const pft_real_t *restrict pvx = P->vx;
    const pft_real_t *restrict pvy = P->vy;
    const pft_real_t *restrict pin = P->in;
    const uint32_t n = f->n;
    const pft_krecip_t r = pft_krecip_(sum);
    est_sums_t a;
    pft_sys_t sys;
    pft_wacc_t cum = 0;
    uint32_t n0 = 0u;
    uint32_t head = SLOT_EMPTY_ | n; /* the first empty slot */
    uint32_t *link = &head;         /* where the next empty slot's index goes */
    memset(&a, 0, sizeof a);
    for (int c = 0; c < 5; ++c) {
        a.s[c] = PFT_ACC_ZERO_;
    }
    a.cxx = PFT_ACC_ZERO_;
    a.cxy = PFT_ACC_ZERO_;
    a.cyy = PFT_ACC_ZERO_;
    /* the reference: inside the image, as every E = 1 position is, so the differences below
     * stay within the image span (< 2^14) and need no saturation */
    if (f->est.valid) {
        a.rx = f->est.x;
        a.ry = f->est.y;
    } else {
        a.rx = pft_mul(f->model.hi_x, pft_mul(f->model.dx, PFT_C(0.5)));
        a.ry = pft_mul(f->model.hi_y, pft_mul(f->model.dy, PFT_C(0.5)));
    }
    pft_sys_init_(&sys, sum, n, pft_rng_next_(&f->rng));
#if EST_LANES_
    {
        /* lanes 0-4: x, y, vx, vy, I; 5-7: the moments xx, xy, yy (a.s, a.cxx, a.cxy, a.cyy) */
        float acc[8] = {0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f};
        for (uint32_t s = 0; s < n; ++s) {
            const pft_weight_t e = w[s].w;
            link = walk_slot_(w, s, e, &sys, &cum, link);
            if (pe[s] == 0u) {
                ++n0; /* weight e0 (pass 2): its terms are added once below */
            } else {
                const pft_weight_t wn = pft_kwnorm_(e, r);
                const float dx = px[s] - a.rx;
                const float dy = py[s] - a.ry;
                float t[8];
                a.w += wn;
                a.w2 += wn * wn;
                a.we += wn;
                t[0] = px[s];
                t[1] = py[s];
                t[2] = pvx[s];
                t[3] = pvy[s];
                t[4] = pin[s];
                t[5] = dx * dx;
                t[6] = dx * dy;
                t[7] = dy * dy;
                PFT_KLANES_LOOP_
                for (int c = 0; c < 8; ++c) {
                    acc[c] += wn * t[c];
                }
            }
        }
        for (int c = 0; c < 5; ++c) {
            a.s[c] = acc[c];
        }
        a.cxx = acc[5];
        a.cxy = acc[6];
        a.cyy = acc[7];
    }
#else
    for (uint32_t s = 0; s < n; ++s) {
        const pft_weight_t e = w[s].w;
#if !EST_TWO_LOOPS_
        link = walk_slot_(w, s, e, &sys, &cum, link);
#endif
        if (pe[s] == 0u) {
            ++n0; /* weight e0 (pass 2): its terms are added once below */
        } else {
            const pft_weight_t wn = pft_kwnorm_(e, r);
            /* a normalised weight of 0 (q16: e r < 2^32, e.g. e = 0 from pft_kwexp_ 22 or more
             * below the largest log-weight) adds 0 to every sum below, which leaves each as it
             * is (q16: integers; float: a sum of finite terms that starts at +0 is never -0,
             * so adding +0 or -0 keeps its bits): its terms are skipped */
            if (wn > (pft_weight_t)0) {
                a.w += wn;
                a.w2 += (pft_wacc_t)wn * wn;
                /* |x - r| < 2^14 (above); q16: limited to 181 px so that the products below
                 * stay inside the number range (a particle beyond 181 px counts as 181 px
                 * away) */
                const pft_real_t dx = pft_kspread_(px[s] - a.rx);
                const pft_real_t dy = pft_kspread_(py[s] - a.ry);
                a.we += wn;
                a.s[0] += pft_acc_wx_(wn, px[s]);
                a.s[1] += pft_acc_wx_(wn, py[s]);
                a.s[2] += pft_acc_wx_(wn, pvx[s]);
                a.s[3] += pft_acc_wx_(wn, pvy[s]);
                a.s[4] += pft_acc_wx_(wn, pin[s]);
                a.cxx += pft_acc_wx_(wn, pft_kmulr_(dx, dx));
                a.cxy += pft_acc_wx_(wn, pft_kmulr_(dx, dy));
                a.cyy += pft_acc_wx_(wn, pft_kmulr_(dy, dy));
            }
        }
    }
#endif
    {
        /* every E = 0 particle has weight e0, so the same normalised weight wn0: n0 wn0 <=
         * 2^30 and n0 wn0^2 <= 2^60 (q16), the same sums as particle by particle */
        const pft_weight_t wn0 = pft_kwnorm_(e0, r);
        a.w += (pft_wacc_t)n0 * wn0;
        a.w2 += (pft_wacc_t)n0 * ((pft_wacc_t)wn0 * wn0);
    }
#if EST_TWO_LOOPS_
    /* the walk after the sums: it overwrites the weights with the counts */
    for (uint32_t s = 0; s < n; ++s) {
        link = walk_slot_(w, s, w[s].w, &sys, &cum, link);
    }
#endif
    *link = SLOT_EMPTY_ | n;
    if (pft_sys_left_(&sys) > 0u) {
        /* float only: targets that round up to the total go to the last particle drawn
         * (q16 walks are exact and take every target) */
        uint32_t last = n - 1u;
        while (last > 0u && w[last].n >= SLOT_EMPTY_) {
            --last;
        }
        w[last].n = (w[last].n >= SLOT_EMPTY_ ? 0u : w[last].n) + pft_sys_left_(&sys);
    }
    est_finish_(&f->est, &a);
    return head;
}

/* ---------------------------------- pass 4: resampling in place --------------------------- */

/* Particle s with count r > 1 is copied into the next r - 1 empty slots of the chain that
 * pass 3 left (head: the first, each empty slot's count holds SLOT_EMPTY_ and the next one's
 * index); the outer loop skips the empty slots, also those filled already. The counts sum to
 * n, so there are exactly as many empty slots as extra copies, each taken once, in increasing
 * order (the same slots as a forward scan for count 0 would take). */
static void replicate_(pft_tbd_filter_t *f, uint32_t head)
{
    /* the arrays in locals: the state byte's store (a char) could otherwise reach them */
    pft_real_t *const px = f->cur.x;
    pft_real_t *const py = f->cur.y;
    pft_real_t *const pin = f->cur.in;
    pft_real_t *const pvx = f->cur.vx;
    pft_real_t *const pvy = f->cur.vy;
    uint8_t *const pe = f->cur.e;
    const pft_tbd_slot_t *const w = f->cur.w;
    const uint32_t n = f->n;
    uint32_t j = head & ~SLOT_EMPTY_;
    for (uint32_t s = 0; s < n; ++s) {
        const uint32_t r = w[s].n;
        if (r - 2u < SLOT_EMPTY_ - 2u) { /* 2 <= r < SLOT_EMPTY_ */
            const pft_real_t xs = px[s], ys = py[s], is = pin[s], vxs = pvx[s], vys = pvy[s];
            const uint8_t es = pe[s];
            for (uint32_t c = r; c > 1u; --c) {
                if (j >= n) {
                    return; /* cannot happen: the counts sum to n */
                }
                px[j] = xs;
                py[j] = ys;
                pin[j] = is;
                pvx[j] = vxs;
                pvy[j] = vys;
                pe[j] = es;
                j = w[j].n & ~SLOT_EMPTY_;
            }
        }
    }
}

/* ---------------------------------- statistics -------------------------------------------- */

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

/* ---------------------------------- Bernoulli form (docs/algorithms.md 2.11) -------------- */

/* Whether move_bern_ runs its particles in a loop that makes no call (AArch64, x86-64 float): the
 * inner loop stops at the first ziggurat word that needs the slow path and at a birth's
 * intensity that needs nextafterf, and the outer loop finishes that particle from there (the
 * slow path with that word, the particle's later draws in the general form) before the inner
 * loop goes on. The particles in their order, each with the same words and the same
 * operations, so the same values. Without a call in the inner loop its invariants and the
 * generator need not survive one there (AArch64, the real file's flight build, frames 14-40:
 * the manager 13.21 -> 13.05 M instructions per frame in q16, 10.24 -> 10.03 in float;
 * docs/results/ir_clutter.md, "Branch ircost59"). x86-64 q16 (slightly dearer split) and the
 * Cortex-M builds keep the one loop. test_tbd_filter compares the two forms
 * (pft_tbd_move_bern_hook_). */
#if defined(__aarch64__) || (defined(__x86_64__) && !defined(PFT_NUMERIC_Q16))
#define MOVE_SPLIT_ 1
#else
#define MOVE_SPLIT_ 0
#endif

#if MOVE_SPLIT_
/* One particle of move_bern_ in its general form (every draw whole): draws
 * its existence word, writes its state and byte; returns the byte, counts a birth in *b. */
static inline uint32_t bern_one_(const step_ctx_t *x, const move_inv_t *v, uint32_t s,
                                 uint32_t p16_share, bool rb, bool can_birth, pft_rng_t *rng,
                                 uint32_t *b)
{
    const uint32_t u = pft_tbd_exist_draw_(rng);
    uint32_t e = v->e[s];
    if ((e == 0u || u < p16_share) && !can_birth) {
        e = 0u; /* no pixel to be born in: the slot stays empty */
    } else if (e == 0u || u < p16_share) {
        move_birth_(x, v, s, rng);
        e = 1u;
        ++*b;
    } else {
        const pft_tbd_kin_t k = {&v->x[s], &v->y[s], &v->vx[s], &v->vy[s], &v->in[s]};
        if (rb) {
            rbpf_move_(&k, v->tab, v->T, v->dyn.ch_int, e - 1u, rng);
        } else {
            pft_tbd_pf_move_(&v->dyn, v->T, rng, &k);
        }
        e = e < v->e_max ? e + 1u : e;
    }
    v->e[s] = (uint8_t)e;
    return e;
}

/* rbpf_move_ with its three draws made (gx, gy, gi). */
static inline void rbpf_move_g_(const pft_tbd_kin_t *k, const pft_tbd_tab_t *tab, pft_real_t T,
                                pft_real_t ch_int, uint32_t age, pft_real_t gx, pft_real_t gy,
                                pft_real_t gi)
{
    const pft_real_t vx = *k->vx;
    const pft_real_t vy = *k->vy;
    *k->x = pft_kmad2_(*k->x, T, vx, tab->kf_sd[0][age], gx);
    *k->vx = pft_kmad1_(vx, tab->kf_gsd[0][age], gx);
    *k->y = pft_kmad2_(*k->y, T, vy, tab->kf_sd[1][age], gy);
    *k->vy = pft_kmad1_(vy, tab->kf_gsd[1][age], gy);
    *k->in = pft_kmad1_(*k->in, ch_int, gi);
}

/* pft_rng_zig_'s fast path alone: true with its draw in *g; false when its word (*w) needs the slow
 * path (zig_rest_). */
static inline bool zig_fast_only_(pft_rng_t *rng, pft_real_t *g, uint32_t *w)
{
    const uint32_t u = pft_rng_next_(rng);
    const uint32_t m = u >> 8;
    const int32_t *kw = pft_zig_ksw[u & (2u * PFT_ZIG_LAYERS - 1u)];
    *w = u;
    *g = pft_zig_sfast_((int64_t)m * kw[1]);
    return m < (uint32_t)kw[0];
}

/* The rest of pft_rng_zig_ for its word u when the fast path did not take it. */
static pft_real_t zig_rest_(pft_rng_t *rng, uint32_t u)
{
    const pft_zig_slow_t r = pft_rng_zig_slow_(rng->s[0], rng->s[1], rng->s[2], rng->s[3], u);
    rng->s[0] = r.s[0];
    rng->s[1] = r.s[1];
    rng->s[2] = r.s[2];
    rng->s[3] = r.s[3];
    return r.v;
}

/* An RBPF birth's state (pft_tbd_birth_pix_v_ without velocity draws) in pixel p at the
 * offsets ux, uy with the intensity in. */
static inline void bern_birth_put_(const move_inv_t *v, const pft_tbd_birth_inv_t *bi, uint32_t s,
                                   uint32_t p, pft_real_t ux, pft_real_t uy, pft_real_t in)
{
    v->x[s] = pft_tbd_birth_coord_(p % bi->width, ux, bi->dx);
    v->y[s] = pft_tbd_birth_coord_(p / bi->width, uy, bi->dy);
    v->in[s] = in;
    v->vx[s] = bi->vel_mean[0];
    v->vy[s] = bi->vel_mean[1];
}

/* Counts the births and the survivors. Loop invariants in locals (move_inv_t; two callers
 * here too: the update and the coast). split: MOVE_SPLIT_'s loops where they apply (RBPF
 * moves, births from a candidate list, float: an intensity range of pft_tbd_birth_inv_'s
 * i_fast); false: the general loop (the test hook's reference). */
static void move_bern_form_(pft_tbd_filter_t *f, const step_ctx_t *x, uint32_t p16_share,
                            uint32_t *nb, uint32_t *np, bool split)
{
    const move_inv_t v = move_inv_(f, x);
    const bool rb = x->rb;
    const bool can_birth = x->can_birth;
    pft_rng_t rng = f->rng;
    uint32_t b = 0u;
    uint32_t surv = 0u;
    uint32_t s = 0u;
#ifdef PFT_NUMERIC_Q16
    const bool in_fast = true;
#else
    const bool in_fast = v.birth.i_fast;
#endif
    if (split && rb && (!can_birth || (v.cand != NULL && in_fast))) {
        const pft_tbd_birth_inv_t bi = v.birth;
        while (s < v.n) {
            /* where the inner loop stopped: the draw k (0-2: a survivor's gx, gy, gi; 3: a
             * birth's intensity) with word w, the draws before it */
            uint32_t k = 0u;
            uint32_t w = 0u;
            uint32_t e = 0u;
            uint32_t p = 0u;
            pft_real_t g0 = PFT_C(0.0);
            pft_real_t g1 = PFT_C(0.0);
            pft_real_t g2 = PFT_C(0.0);
            for (; s < v.n; ++s) {
                const uint32_t u = pft_tbd_exist_draw_(&rng);
                e = v.e[s];
                if ((e == 0u || u < p16_share) && !can_birth) {
                    e = 0u;
                } else if (e == 0u || u < p16_share) {
                    /* move_birth_ with RBPF's velocity (vel_mean) */
                    p = v.cand[pft_rng_below_(&rng, v.n_cand)];
                    g0 = pft_from_u32_frac(pft_rng_next_(&rng));
                    g1 = pft_from_u32_frac(pft_rng_next_(&rng));
#ifdef PFT_NUMERIC_Q16
                    g2 = pft_tbd_birth_in_draw_(&bi, &rng);
#else
                    g2 = pft_add(bi.i_lo,
                                 pft_mul(bi.i_span, pft_from_u32_frac(pft_rng_next_(&rng))));
                    if (!(g2 < bi.i_hi)) {
                        k = 3u; /* rounded up to i_max */
                        break;
                    }
#endif
                    bern_birth_put_(&v, &bi, s, p, g0, g1, g2);
                    e = 1u;
                    ++b;
                } else {
                    if (!zig_fast_only_(&rng, &g0, &w)) {
                        k = 0u;
                        break;
                    }
                    if (!zig_fast_only_(&rng, &g1, &w)) {
                        k = 1u;
                        break;
                    }
                    if (!zig_fast_only_(&rng, &g2, &w)) {
                        k = 2u;
                        break;
                    }
                    {
                        const pft_tbd_kin_t kn = {&v.x[s], &v.y[s], &v.vx[s], &v.vy[s],
                                                  &v.in[s]};
                        rbpf_move_g_(&kn, v.tab, v.T, v.dyn.ch_int, e - 1u, g0, g1, g2);
                    }
                    e = e < v.e_max ? e + 1u : e;
                }
                v.e[s] = (uint8_t)e;
                surv += e > 1u ? 1u : 0u;
            }
            if (s < v.n) {
                /* particle s from its stopped draw on */
#ifndef PFT_NUMERIC_Q16
                if (k == 3u) {
                    bern_birth_put_(&v, &bi, s, p, g0, g1, nextafterf(bi.i_hi, bi.i_lo));
                    e = 1u;
                    ++b;
                } else
#endif
                {
                    const pft_tbd_kin_t kn = {&v.x[s], &v.y[s], &v.vx[s], &v.vy[s], &v.in[s]};
                    g0 = k == 0u ? zig_rest_(&rng, w) : g0;
                    g1 = k == 1u ? zig_rest_(&rng, w) : (k < 1u ? pft_rng_zig_(&rng) : g1);
                    g2 = k == 2u ? zig_rest_(&rng, w) : pft_rng_zig_(&rng);
                    rbpf_move_g_(&kn, v.tab, v.T, v.dyn.ch_int, e - 1u, g0, g1, g2);
                    e = e < v.e_max ? e + 1u : e;
                }
                v.e[s] = (uint8_t)e;
                surv += e > 1u ? 1u : 0u;
                ++s;
            }
        }
    }
    for (; s < v.n; ++s) {
        surv += bern_one_(x, &v, s, p16_share, rb, can_birth, &rng, &b) > 1u ? 1u : 0u;
    }
    f->rng = rng;
    *nb = b;
    *np = surv;
}

static void move_bern_(pft_tbd_filter_t *f, const step_ctx_t *x, uint32_t p16_share, uint32_t *nb,
                       uint32_t *np)
{
    move_bern_form_(f, x, p16_share, nb, np, true);
}

void pft_tbd_move_bern_hook_(pft_tbd_filter_t *f, const pft_tbd_scene_t_ *sc, uint32_t p16_share,
                             bool split, uint32_t *nb, uint32_t *np)
{
    step_ctx_t x;
    memset(&x, 0, sizeof x);
    x.sc = sc;
    x.tab = f->tab;
    x.T = f->cfg.T;
    x.p_birth = pft_tbd_p_birth_(&f->dyn, f->frames == 0u);
    x.e_max = (uint8_t)(f->tab->age_cap + 1u);
    x.can_birth = sc->n_cand > 0u;
    x.rb = f->kind == PFT_TBD_RBPF;
    move_bern_form_(f, &x, p16_share, nb, np, split);
}
#else
/* Every particle is a position hypothesis: a share of them (and every empty slot) become births,
 * the others move. Counts the births and the survivors. Loop invariants in locals (move_inv_t;
 * two callers here too: the update and the coast). */
static void move_bern_(pft_tbd_filter_t *f, const step_ctx_t *x, uint32_t p16_share, uint32_t *nb,
                       uint32_t *np)
{
    const move_inv_t v = move_inv_(f, x);
    const bool rb = x->rb;
    const bool can_birth = x->can_birth;
    pft_rng_t rng = f->rng;
    uint32_t b = 0u;
    uint32_t surv = 0u;
    for (uint32_t s = 0; s < v.n; ++s) {
        const uint32_t u = pft_tbd_exist_draw_(&rng);
        uint32_t e = v.e[s];
        if ((e == 0u || u < p16_share) && !can_birth) {
            e = 0u; /* no pixel to be born in: the slot stays empty */
        } else if (e == 0u || u < p16_share) {
            move_birth_(x, &v, s, &rng);
            e = 1u;
            ++b;
        } else {
            const pft_tbd_kin_t k = {&v.x[s], &v.y[s], &v.vx[s], &v.vy[s], &v.in[s]};
            if (rb) {
                rbpf_move_(&k, v.tab, v.T, v.dyn.ch_int, e - 1u, &rng);
            } else {
                pft_tbd_pf_move_(&v.dyn, v.T, &rng, &k);
            }
            e = e < v.e_max ? e + 1u : e;
        }
        v.e[s] = (uint8_t)e;
        surv += e > 1u ? 1u : 0u;
    }
    f->rng = rng;
    *nb = b;
    *np = surv;
}
#endif

/* Log-weights: the likelihood ratio plus the log prior weight of the particle's group (lb for
 * births, lp for survivors); dropped particles get BERN_DROP_ and E = 0 (a birth slot next
 * frame). Returns the largest. */
static pft_real_t weigh_bern_any_(pft_tbd_filter_t *f, const step_ctx_t *x, pft_real_t lb,
                                  pft_real_t lp)
{
    const pft_tbd_particles_t *P = &f->cur;
    const pft_tbd_meas_t *m = &f->model;
    uint8_t *restrict pe = P->e;
    pft_tbd_slot_t *restrict pw = P->w;
    pft_real_t lmax = BERN_DROP_;
    for (uint32_t s = 0; s < f->n; ++s) {
        pft_real_t lw = BERN_DROP_;
        pft_tbd_cell_t c;
        if (pe[s] != 0u && pft_tbd_cell_(m, P->x[s], P->y[s], &c) &&
            (x->mask == NULL || !pft_tbd_masked_(x->mask, pft_tbd_mask_words_(m->width),
                                                 (uint32_t)(c.i - 1), (uint32_t)(c.j - 1)))) {
            lw = pft_add(pft_tbd_llr_sc_(m, x->tab, x->sc, &c, P->in[s]), pe[s] == 1u ? lb : lp);
        } else {
            pe[s] = 0u;
        }
        pw[s].lw = lw;
        lmax = pft_max(lmax, lw);
    }
    return lmax;
}

static pft_real_t weigh_bern_(pft_tbd_filter_t *f, const step_ctx_t *x, pft_real_t lb,
                              pft_real_t lp)
{
    if (weigh_r16_case_(f, x)) {
        return weigh_r16_(f, x, true, lb, lp);
    }
    return weigh_bern_any_(f, x, lb, lp);
}

/* log(a) for a > 0, else the drop value. */
static pft_real_t log_or_drop_(pft_real_t a) { return a > PFT_C(0.0) ? pft_log(a) : BERN_DROP_; }

/* log(m c) with m the predicted birth mass (eta on the first frame, pb (1 - q) after) and c the
 * share of it counted, num / den of the allowed pixels (the proposal's candidates, or the rest;
 * share, that ratio as a real); the drop value when it is 0. float: the log of the rounded
 * products, as written. q16: the sum of the logs of the factors (the counts' logs by
 * pft_log_count_), because the products and the ratio fall below or near the LSB where they
 * matter: at the existence probability's ceiling 1 / (1 + e^-10) (1 - q = 3 LSB),
 * pb (1 - q) is 0.15 LSB for pb = 0.05 and rounded to 0, which took every birth's weight away
 * (the search layer could not move to a new target while q sat there; test_tbd_bern_move);
 * pb c is 0.4 LSB at 256 x 256 with 8 peaks. */
static pft_real_t log_birth_mass_(const pft_tbd_config_t *c, bool first, pft_real_t q,
                                  pft_real_t share, uint32_t num, uint32_t den)
{
#ifdef PFT_NUMERIC_Q16
    const pft_real_t a = first ? c->eta : c->pb;
    const pft_real_t b = pft_sub(PFT_C(1.0), q);
    (void)share;
    if (!(a > PFT_C(0.0) && num > 0u && den > 0u && (first || b > PFT_C(0.0)))) {
        return BERN_DROP_;
    }
    const pft_real_t l = pft_add(pft_log(a), pft_sub(pft_log_count_(num), pft_log_count_(den)));
    return first ? l : pft_add(l, pft_log(b));
#else
    const pft_real_t mb = first ? c->eta : pft_mul(c->pb, pft_sub(PFT_C(1.0), q));
    (void)num;
    (void)den;
    return log_or_drop_(pft_mul(mb, share));
#endif
}

/* log(e^a + e^b), the larger first. */
static pft_real_t log_add_(pft_real_t a, pft_real_t b)
{
    const pft_real_t hi = pft_max(a, b);
    const pft_real_t d = pft_max(pft_sub(pft_min(a, b), hi), PFT_C(-20.0));
    return pft_add(hi, pft_log(pft_add(PFT_C(1.0), pft_exp(d))));
}

/* One iteration of the Bernoulli form: q_pred = pb (1 - q) + (1 - pd) q (eta on the first
 * frame); births carry the prior mass pb (1 - q) times the proposal's share c = n_cand / A of
 * the allowed pixels (1 without the correction's candidates), the rest of that mass, (1 - c),
 * counts with likelihood ratio 1; survivors carry (1 - pd) q. P = L / (L + 1 - q_pred) with L
 * the total weighted likelihood ratio. */
static uint32_t step_bern_(pft_tbd_filter_t *f, const step_ctx_t *x)
{
    const pft_tbd_config_t *c = &f->cfg;
    const bool first = f->frames == 0u;
    const pft_real_t q = f->bq;
    const pft_real_t mb = first ? c->eta : pft_mul(c->pb, pft_sub(PFT_C(1.0), q));
    const pft_real_t ms = first ? PFT_C(0.0) : pft_mul(pft_sub(PFT_C(1.0), c->pd), q);
    const pft_real_t qp = pft_min(pft_add(mb, ms), PFT_C(1.0));
    pft_real_t share = PFT_C(1.0);
    uint32_t nb = 0u, np = 0u, head;
    uint32_t num = 1u, den = 1u; /* share = num / den */
    if (x->sc->cand_is_b && x->sc->n_allowed > 0u) {
        share = pft_ratio((int32_t)x->sc->n_cand, (int32_t)x->sc->n_allowed);
        num = x->sc->n_cand;
        den = x->sc->n_allowed;
    }
    move_bern_(f, x, pft_p16_(c->birth_share), &nb, &np);
    {
        const pft_real_t lb = nb > 0u ? pft_sub(log_birth_mass_(c, first, q, share, num, den),
                                                pft_log_count_(nb))
                                      : BERN_DROP_;
        const pft_real_t lp = np > 0u ? pft_sub(log_or_drop_(ms), pft_log_count_(np)) : BERN_DROP_;
        const pft_real_t lmax = weigh_bern_(f, x, lb, lp);
        const pft_wacc_t sum = weights_(f, lmax);
        pft_real_t ll = pft_add(lmax, pft_wacc_log(sum));
        const pft_real_t l0 = log_birth_mass_(c, first, q, pft_sub(PFT_C(1.0), share),
                                              num <= den ? den - num : 0u, den);
        if (l0 > BERN_DROP_) {
            ll = log_add_(ll, l0);
        }
        f->est.log_mean_lr = pft_sub(ll, log_or_drop_(qp));
        /* E = 0 particles have lw = BERN_DROP_ */
        head = estimate_and_count_(f, sum, pft_kwexp_(BERN_DROP_, lmax));
        /* P = 1 / (1 + (1 - q_pred) e^-L), the exponent limited to +-10 */
        {
            const pft_real_t d = pft_clamp(pft_sub(log_or_drop_(pft_sub(PFT_C(1.0), qp)), ll),
                                           PFT_C(-10.0), PFT_C(10.0));
            f->bq = pft_div(PFT_C(1.0), pft_add(PFT_C(1.0), pft_exp(d)));
        }
        f->est.p_exist = f->bq;
    }
    return head;
}

/* ---------------------------------- one iteration ----------------------------------------- */

void pft_tbd_filter_step_(pft_tbd_filter_t *f, const pft_tbd_scene_t_ *sc)
{
    const pft_tbd_config_t *c = &f->cfg;
    step_ctx_t x;
    memset(&x, 0, sizeof x);
    x.sc = sc;
    x.tab = f->tab;
    x.mask = f->constrain ? sc->mask : NULL;
    x.T = c->T;
    x.p_birth = pft_tbd_p_birth_(&f->dyn, f->frames == 0u);
    x.e_max = (uint8_t)(f->tab->age_cap + 1u);
    x.can_birth = f->births && sc->n_cand > 0u;
    x.rb = f->kind == PFT_TBD_RBPF;
    f->birth_lw = x.can_birth ? pft_tbd_birth_lw_(c, sc) : PFT_C(0.0);
    if (f->births && c->birth_share > PFT_C(0.0)) {
        const uint32_t head = step_bern_(f, &x);
        disappearance_(f);
        replicate_(f, head);
        if (f->frames < UINT32_MAX) {
            ++f->frames;
        }
        return;
    }
    /* 1-3. existence, move or birth, log-weights */
    move_(f, &x);
    pft_real_t lmax = weigh_(f, &x);
    pft_wacc_t sum = weights_(f, lmax);
    f->est.log_mean_lr = pft_sub(pft_add(lmax, pft_wacc_log(sum)), f->log_n);
    /* 4. estimates from the normalised weights, before resampling; the walk of step 5 */
    /* E = 0 particles have lw = 0 */
    const uint32_t head = estimate_and_count_(f, sum, pft_kwexp_(PFT_C(0.0), lmax));
    disappearance_(f);
    /* 5. systematic resampling, in place */
    replicate_(f, head);
    if (f->frames < UINT32_MAX) {
        ++f->frames;
    }
}

void pft_tbd_filter_coast_(pft_tbd_filter_t *f, uint32_t periods)
{
    const pft_tbd_config_t *c = &f->cfg;
    const bool bern = f->births && c->birth_share > PFT_C(0.0);
    step_ctx_t x;
    memset(&x, 0, sizeof x);
    x.tab = f->tab;
    x.T = c->T;
    x.e_max = (uint8_t)(f->tab->age_cap + 1u);
    x.can_birth = false; /* x.sc is never read then */
    x.rb = f->kind == PFT_TBD_RBPF;
    for (uint32_t i = 0; i < periods; ++i) {
        if (bern) {
            uint32_t nb = 0u, np = 0u;
            const pft_real_t q = f->bq;
            move_bern_(f, &x, 0u, &nb, &np);
            f->bq = pft_min(pft_add(pft_mul(c->pb, pft_sub(PFT_C(1.0), q)),
                                    pft_mul(pft_sub(PFT_C(1.0), c->pd), q)),
                            PFT_C(1.0));
        } else {
            move_(f, &x);
        }
    }
}

/* Offsets of particle s from (rx, ry), each clamped to +-32 px (q16: squares stay < 2^10). */
static void split_off_(const pft_tbd_particles_t *P, uint32_t s, pft_real_t rx, pft_real_t ry,
                       pft_real_t *dx, pft_real_t *dy)
{
    *dx = pft_clamp(pft_sub(P->x[s], rx), PFT_C(-32.0), PFT_C(32.0));
    *dy = pft_clamp(pft_sub(P->y[s], ry), PFT_C(-32.0), PFT_C(32.0));
}

/* Estimates of a set with equal weights: means, then the spread about them. `live_only` takes
 * the particles with E = 1 only and clamps the offsets of the spread (split_off_); otherwise
 * every particle, offsets unclamped (the handed-over set, all live). p_exist, log_mean_lr and
 * n_eff are left to the caller. False, with the estimate untouched, when no particle counts.
 * Sums of n <= 2^22 values (q16: each < 2^31, so < 2^53). */
static bool equal_estimate_(pft_tbd_filter_t *f, bool live_only)
{
    const pft_tbd_particles_t *P = &f->cur;
    const pft_weight_t one = (pft_weight_t)1;
    pft_acc_t_ s[5] = {PFT_ACC_ZERO_, PFT_ACC_ZERO_, PFT_ACC_ZERO_, PFT_ACC_ZERO_, PFT_ACC_ZERO_};
    pft_acc_t_ cxx = PFT_ACC_ZERO_, cxy = PFT_ACC_ZERO_, cyy = PFT_ACC_ZERO_;
    pft_tbd_estimate_t *e = &f->est;
    uint32_t nl = 0u;
    for (uint32_t i = 0; i < f->n; ++i) {
        if (!live_only || P->e[i] != 0u) {
            ++nl;
            s[0] += pft_acc_wx_(one, P->x[i]);
            s[1] += pft_acc_wx_(one, P->y[i]);
            s[2] += pft_acc_wx_(one, P->vx[i]);
            s[3] += pft_acc_wx_(one, P->vy[i]);
            s[4] += pft_acc_wx_(one, P->in[i]);
        }
    }
    if (nl == 0u) {
        return false;
    }
    const pft_wacc_t nw = (pft_wacc_t)nl;
    e->x = pft_acc_div_(s[0], nw);
    e->y = pft_acc_div_(s[1], nw);
    e->vx = pft_acc_div_(s[2], nw);
    e->vy = pft_acc_div_(s[3], nw);
    e->intensity = pft_acc_div_(s[4], nw);
    for (uint32_t i = 0; i < f->n; ++i) {
        pft_real_t dx, dy;
        if (live_only) {
            if (P->e[i] == 0u) {
                continue;
            }
            split_off_(P, i, e->x, e->y, &dx, &dy);
        } else {
            dx = pft_sub(P->x[i], e->x);
            dy = pft_sub(P->y[i], e->y);
        }
        cxx += pft_acc_wx_(one, pft_sq(dx));
        cxy += pft_acc_wx_(one, pft_mul(dx, dy));
        cyy += pft_acc_wx_(one, pft_sq(dy));
    }
    e->pos_cov[0] = pft_acc_div_(cxx, nw);
    e->pos_cov[1] = pft_acc_div_(cxy, nw);
    e->pos_cov[2] = pft_acc_div_(cyy, nw);
    e->valid = true;
    return true;
}

/* Whether particle s of src may be handed over: E = 1 and, with a gate, its window-centre pixel
 * inside the gate region. */
static bool qualifies_(const pft_tbd_filter_t *src, uint32_t s, const pft_tbd_region_t *gate)
{
    if (src->cur.e[s] == 0u) {
        return false;
    }
    if (gate == NULL) {
        return true;
    }
    size_t pix = 0u;
    if (!pft_tbd_centre_(&src->model, src->cur.x[s], src->cur.y[s], &pix)) {
        return false;
    }
    const int32_t col = (int32_t)(pix % src->model.width);
    const int32_t row = (int32_t)(pix / src->model.width);
    return col >= gate->col_lo && col <= gate->col_hi && row >= gate->row_lo &&
           row <= gate->row_hi;
}

bool pft_tbd_filter_handover_(pft_tbd_filter_t *dst, pft_tbd_filter_t *src,
                              const pft_tbd_region_t *gate)
{
    /* one qualification test per particle: its result replaces the pixel in src's weight slot
     * for the walk below */
    pft_tbd_slot_t *q = src->cur.w;
    uint32_t alive = 0;
    for (uint32_t s = 0; s < src->n; ++s) {
        q[s].n = qualifies_(src, s, gate) ? 1u : 0u;
        alive += q[s].n;
    }
    if (alive == 0u || dst->kind != src->kind) {
        return false;
    }
    /* systematic resampling of `alive` equal weights into dst->n slots */
    pft_sys_t sys;
    uint32_t k = 0;
    pft_wacc_t cum = 0;
    pft_sys_init_(&sys, (pft_wacc_t)alive, dst->n, pft_rng_next_(&dst->rng));
    for (uint32_t s = 0; s < src->n && k < dst->n; ++s) {
        if (q[s].n == 0u) {
            continue;
        }
        cum += (pft_wacc_t)1;
        for (uint32_t c = pft_sys_take_(&sys, cum); c > 0u && k < dst->n; --c) {
            copy_particle_(&dst->cur, k, &src->cur, s);
            ++k;
        }
    }
    for (; k > 0u && k < dst->n; ++k) {
        copy_particle_(&dst->cur, k, &dst->cur, k - 1u); /* float rounding only */
    }
    pft_real_t lmlr = src->est.log_mean_lr;
    pft_real_t pex = src->est.p_exist;
    (void)equal_estimate_(dst, false); /* dst->n > 0 particles, every one counted */
    dst->est.n_eff = pft_from_int(dst->n > 32767u ? 32767 : (int32_t)dst->n);
    dst->est.log_mean_lr = lmlr;
    dst->est.p_exist = pex;
    return true;
}

/* ---------------------------------- split (docs/algorithms.md 2.7 [E]) -------------------- */

/* Offset of particle s from (rx, ry), each axis limited to +-32 px (q16: the squares and
 * their sums below stay under 2^14). */

static pft_real_t split_d2_(pft_real_t ax, pft_real_t ay, pft_real_t bx, pft_real_t by)
{
    return pft_add(pft_sq(pft_sub(ax, bx)), pft_sq(pft_sub(ay, by)));
}

/* Two-means: every live particle labelled 1 or 2 (its nearer centroid; 0 dead) in w[s].n, the
 * centroids moved to their groups' means; false when a group is empty. */
static bool split_assign_(pft_tbd_filter_t *f, pft_real_t rx, pft_real_t ry, pft_real_t c[4],
                          uint32_t cnt[2])
{
    const pft_tbd_particles_t *P = &f->cur;
    pft_tbd_slot_t *w = f->cur.w;
    const pft_weight_t one = (pft_weight_t)1;
    pft_acc_t_ sm[4] = {PFT_ACC_ZERO_, PFT_ACC_ZERO_, PFT_ACC_ZERO_, PFT_ACC_ZERO_};
    cnt[0] = 0u;
    cnt[1] = 0u;
    for (uint32_t s = 0; s < f->n; ++s) {
        w[s].n = 0u;
        if (P->e[s] == 0u) {
            continue;
        }
        pft_real_t dx, dy;
        split_off_(P, s, rx, ry, &dx, &dy);
        uint32_t g = 0u; /* the nearer centroid's group */
        if (split_d2_(dx, dy, c[0], c[1]) > split_d2_(dx, dy, c[2], c[3])) {
            g = 1u;
        }
        w[s].n = g + 1u;
        ++cnt[g];
        sm[2u * g] += pft_acc_wx_(one, dx);
        sm[2u * g + 1u] += pft_acc_wx_(one, dy);
    }
    if (cnt[0] == 0u || cnt[1] == 0u) {
        return false;
    }
    for (uint32_t k = 0; k < 4u; ++k) {
        c[k] = pft_acc_div_(sm[k], (pft_wacc_t)cnt[k / 2u]);
    }
    return true;
}

bool pft_tbd_filter_parts_(pft_tbd_filter_t *f, pft_real_t min_sep, pft_real_t min_share,
                           pft_real_t *sx, pft_real_t *sy)
{
    const pft_tbd_particles_t *P = &f->cur;
    pft_tbd_slot_t *w = f->cur.w;
    const pft_real_t rx = f->est.x;
    const pft_real_t ry = f->est.y;
    /* seeds: the live particle farthest from the estimate, then the one farthest from it */
    uint32_t a = f->n;
    uint32_t nl = 0u;
    pft_real_t best = PFT_C(-1.0);
    for (uint32_t s = 0; s < f->n; ++s) {
        if (P->e[s] != 0u) {
            pft_real_t dx, dy;
            split_off_(P, s, rx, ry, &dx, &dy);
            const pft_real_t d2 = split_d2_(dx, dy, PFT_C(0.0), PFT_C(0.0));
            ++nl;
            if (d2 > best) {
                best = d2;
                a = s;
            }
        }
    }
    if (nl < 2u || !f->est.valid) {
        return false;
    }
    pft_real_t c[4];
    split_off_(P, a, rx, ry, &c[0], &c[1]);
    best = PFT_C(-1.0);
    for (uint32_t s = 0; s < f->n; ++s) {
        if (P->e[s] != 0u) {
            pft_real_t dx, dy;
            split_off_(P, s, rx, ry, &dx, &dy);
            const pft_real_t d2 = split_d2_(dx, dy, c[0], c[1]);
            if (d2 > best) {
                best = d2;
                c[2] = dx;
                c[3] = dy;
            }
        }
    }
    uint32_t cnt[2];
    for (int it = 0; it < 3; ++it) {
        if (!split_assign_(f, rx, ry, c, cnt)) {
            return false;
        }
    }
    /* the groups' mean squared spreads about their centroids (the labels of the last pass,
     * whose means the centroids are) */
    const pft_weight_t one = (pft_weight_t)1;
    pft_acc_t_ sp[2] = {PFT_ACC_ZERO_, PFT_ACC_ZERO_};
    for (uint32_t s = 0; s < f->n; ++s) {
        const uint32_t g = w[s].n;
        if (g != 0u) {
            pft_real_t dx, dy;
            split_off_(P, s, rx, ry, &dx, &dy);
            sp[g - 1u] += pft_acc_wx_(one, split_d2_(dx, dy, c[2u * (g - 1u)], c[2u * (g - 1u) + 1u]));
        }
    }
    const pft_real_t s1 = pft_acc_div_(sp[0], (pft_wacc_t)cnt[0]);
    const pft_real_t s2 = pft_acc_div_(sp[1], (pft_wacc_t)cnt[1]);
    const pft_real_t sep2 = split_d2_(c[0], c[1], c[2], c[3]);
    uint32_t small = 2u; /* the smaller group's label */
    if (cnt[0] < cnt[1]) {
        small = 1u;
    }
    const uint32_t n_small = cnt[small - 1u];
    if (!(pft_ratio((int32_t)n_small, (int32_t)nl) >= min_share) ||
        !(sep2 >= pft_sq(min_sep)) || !(sep2 >= pft_mul_i(pft_add(s1, s2), 2))) {
        return false;
    }
    if (small == 1u) {
        /* the larger group takes label 1 */
        for (uint32_t s = 0; s < f->n; ++s) {
            w[s].n = w[s].n == 0u ? 0u : 3u - w[s].n;
        }
    }
    *sx = pft_add(rx, c[2u * (small - 1u)]);
    *sy = pft_add(ry, c[2u * (small - 1u) + 1u]);
    return true;
}

/* The slots of P labelled `into` (in w) refilled with copies of those labelled `from`, equal
 * weights, by systematic resampling with rng; the `from` particles and every other slot
 * untouched. */
static void split_refill_(pft_tbd_particles_t *P, const pft_tbd_slot_t *w, uint32_t n,
                          uint32_t from, uint32_t into, pft_rng_t *rng)
{
    uint32_t n_from = 0u;
    uint32_t n_into = 0u;
    for (uint32_t s = 0; s < n; ++s) {
        n_from += w[s].n == from ? 1u : 0u;
        n_into += w[s].n == into ? 1u : 0u;
    }
    if (n_from == 0u || n_into == 0u) {
        return;
    }
    pft_sys_t sys;
    pft_wacc_t cum = 0;
    uint32_t j = 0u;
    uint32_t last = n;
    pft_sys_init_(&sys, (pft_wacc_t)n_from, n_into, pft_rng_next_(rng));
    for (uint32_t s = 0; s < n && j < n; ++s) {
        if (w[s].n != from) {
            continue;
        }
        last = s;
        cum += (pft_wacc_t)1;
        for (uint32_t c = pft_sys_take_(&sys, cum); c > 0u; --c) {
            while (j < n && w[j].n != into) {
                ++j;
            }
            if (j >= n) {
                break;
            }
            copy_particle_(P, j, P, s);
            ++j;
        }
    }
    for (; j < n && last < n; ++j) {
        if (w[j].n == into) {
            copy_particle_(P, j, P, last); /* float rounding only */
        }
    }
}

void pft_tbd_filter_split_(pft_tbd_filter_t *f, pft_tbd_filter_t *d)
{
    const pft_tbd_slot_t *w = f->cur.w;
    const uint32_t n = f->n < d->n ? f->n : d->n;
    for (uint32_t s = 0; s < n; ++s) {
        copy_particle_(&d->cur, s, &f->cur, s);
    }
    split_refill_(&d->cur, w, n, 2u, 1u, &d->rng);
    split_refill_(&f->cur, w, f->n, 1u, 2u, &f->rng);
    d->est = f->est;
    (void)equal_estimate_(d, true); /* no live particle: the estimate is kept */
    (void)equal_estimate_(f, true);
}

/* ---------------------------------- a layer started beside another (cfg.resid_split) ------ */

void pft_tbd_filter_seed_at_(const pft_tbd_filter_t *f, pft_tbd_filter_t *d, pft_real_t ox,
                             pft_real_t oy)
{
    const uint32_t n = f->n < d->n ? f->n : d->n;
    const bool rb = d->kind == PFT_TBD_RBPF;
    for (uint32_t s = 0; s < n; ++s) {
        copy_particle_(&d->cur, s, &f->cur, s);
        if (d->cur.e[s] == 0u) {
            continue;
        }
        d->cur.x[s] = pft_add(d->cur.x[s], ox);
        d->cur.y[s] = pft_add(d->cur.y[s], oy);
        d->cur.e[s] = 1u; /* born now: age 0 */
        if (rb) {
            d->cur.vx[s] = d->cfg.vel_mean[0];
            d->cur.vy[s] = d->cfg.vel_mean[1];
        } else {
            d->cur.vx[s] = pft_kmad1_(d->cfg.vel_mean[0], d->dyn.vel_sd[0], pft_rng_zig_(&d->rng));
            d->cur.vy[s] = pft_kmad1_(d->cfg.vel_mean[1], d->dyn.vel_sd[1], pft_rng_zig_(&d->rng));
        }
    }
    for (uint32_t s = n; s < d->n; ++s) {
        d->cur.e[s] = 0u;
    }
    d->est = f->est;
    (void)equal_estimate_(d, true); /* no live particle: the parent's estimate is kept */
    d->est.p_exist = f->est.p_exist;
    d->est.log_mean_lr = f->est.log_mean_lr;
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
    size_t nimg = pft_tbd_img_len_(cfg->width, cfg->height);
    pft_real_t *img = (pft_real_t *)pft_ws_take(&ws, nimg * sizeof(pft_real_t));
    size_t nmask = pft_tbd_mask_len_(cfg->width, cfg->height);
    uint32_t *mask = (uint32_t *)pft_ws_take(&ws, nmask * sizeof(uint32_t));
    uint32_t *cand = (uint32_t *)pft_ws_take(&ws, npix * sizeof(uint32_t));
    pft_tbd_tab_t *tab = (pft_tbd_tab_t *)pft_ws_take(&ws, sizeof(pft_tbd_tab_t));
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
    pft_tbd_tab_setup_(tab, cfg);
    f->tab = tab;
    memset(img, 0, nimg * sizeof(pft_real_t));
    memset(mask, 0, nmask * sizeof(uint32_t));
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
    /* Refuse a short workspace before writing the instance (a live filter stays as it was):
     * every carve is a multiple of PFT_WS_ALIGN, so one take of the whole size formula less its
     * start padding fits exactly when all of filter_build_'s takes do. */
    pft_ws_t ws;
    pft_ws_init(&ws, work, work_len);
    (void)pft_ws_take(&ws, pft_tbd_filter_workspace_size(cfg) - (PFT_WS_ALIGN - 1u));
    if (pft_ws_status(&ws) != PFT_OK) {
        return PFT_ERR_NOMEM;
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
    uint32_t gap = 1u;
    if (st == PFT_OK) {
        st = pft_seq_gap_(f->cfg.seq_mode, f->cfg.max_gap, f->seq_set, f->last_seq, frame->seq,
                          &gap);
    }
    if (st != PFT_OK) {
        return st;
    }
    uint32_t seen = f->seq_set ? gap : 0u;
    if (gap == 0u) {
        /* a gap above max_gap: start over on this frame, as after pft_tbd_filter_reset */
        (void)pft_tbd_filter_reset(f);
        gap = 1u;
    }
    f->seq_set = true;
    f->last_seq = frame->seq;
    if (gap > 1u) {
        pft_tbd_filter_coast_(f, gap - 1u);
    }
    pft_tbd_frame_convert_(&f->cfg, &f->model, frame, f->img);
    memset(f->mask, 0, pft_tbd_mask_len_(f->cfg.width, f->cfg.height) * sizeof(uint32_t));
    for (size_t r = 0; r < n_regions; ++r) {
        pft_tbd_mask_add_(&f->cfg, f->mask, &regions[r]);
    }
    pft_tbd_scene_t_ sc;
    pft_tbd_scene_build_(&f->cfg, f->gamma_w, f->img, n_regions > 0u ? f->mask : NULL, f->cand,
                         &sc);
    pft_tbd_filter_step_(f, &sc);
    f->est.last_seq = frame->seq;
    f->est.last_timestamp_us = frame->timestamp_us;
    f->est.gap = seen;
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

pft_real_t pft_tbd_filter_llr(const pft_tbd_filter_t *f, pft_real_t x, pft_real_t y,
                              pft_real_t intensity)
{
    pft_tbd_cell_t c;
    if (f == NULL || f->img == NULL || f->tab == NULL || f->frames == 0u ||
        !pft_tbd_cell_(&f->model, pft_tbd_x_int_(x, f->model.dx), pft_tbd_x_int_(y, f->model.dy),
                       &c)) {
        return PFT_C(0.0);
    }
    return pft_tbd_llr_(&f->model, f->tab, f->img, &c, intensity);
}
