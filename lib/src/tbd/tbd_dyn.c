/* The PF-TBD pieces written once (docs/algorithms.md 2.1, 2.2, 2.9): existence chain, births,
 * the full-state CV step, the leave-image test and the estimate sums. Used by the tbd filters
 * (tbd_filter.c) and by the pf engine's TBD model (lib/src/pf/pf_model_tbd.c), which must stay
 * bit-identical to the tbd module's PF-TBD (test_pf_models.c). */
#include "tbd_int.h"
#include "../core/num_int.h"

void pft_tbd_dyn_setup_(pft_tbd_dyn_t *d, const pft_tbd_config_t *cfg)
{
    pft_real_t T = cfg->T;
    pft_real_t q1T = pft_mul(cfg->q1, T);
    /* chol of q1 [[T^3/3, T^2/2], [T^2/2, T]]: L11 = sqrt(q1 T^3/3), L21 = q1 T^2/2 / L11,
     * L22 = sqrt(q1 T/4). */
    d->ch_pos = pft_sqrt(pft_div(pft_mul(cfg->q1, pft_mul(pft_sq(T), T)), PFT_C(3.0)));
    d->ch_cross = d->ch_pos > PFT_C(0.0)
                      ? pft_div(pft_mul(pft_mul(cfg->q1, pft_sq(T)), PFT_C(0.5)), d->ch_pos)
                      : PFT_C(0.0);
    d->ch_vel = pft_sqrt(pft_mul(q1T, PFT_C(0.25)));
    d->ch_int = pft_sqrt(pft_mul(cfg->q2, T));
    d->vel_sd[0] = pft_sqrt(cfg->vel_var[0]);
    d->vel_sd[1] = pft_sqrt(cfg->vel_var[1]);
    d->p16_b = pft_p16_(cfg->pb);
    d->p16_d = pft_p16_(cfg->pd);
    d->p16_eta = pft_p16_(cfg->eta);
}

pft_real_t pft_tbd_birth_lw_(const pft_tbd_config_t *cfg, const pft_tbd_scene_t_ *sc)
{
    if (cfg->birth_correction && sc->cand_is_b && sc->n_allowed > 0u) {
        return pft_log(pft_ratio((int32_t)sc->n_cand, (int32_t)sc->n_allowed));
    }
    return PFT_C(0.0);
}

void pft_tbd_birth_(const pft_tbd_config_t *c, const pft_tbd_dyn_t *d, const uint32_t *cand,
                    uint32_t n_cand, bool sample_vel, pft_rng_t *rng, pft_tbd_kin_t *k)
{
    uint32_t p = cand[pft_rng_below(rng, n_cand)];
    uint32_t col = p % c->width;
    uint32_t row = p / c->width;
    pft_real_t ux = pft_rng_uniform(rng);
    pft_real_t uy = pft_rng_uniform(rng);
    /* pixel i = col + 1 covers [(i - 0.5) dx, (i + 0.5) dx) */
    *k->x = pft_mul(pft_add(pft_add(pft_from_int((int32_t)col), PFT_C(0.5)), ux), c->dx);
    *k->y = pft_mul(pft_add(pft_add(pft_from_int((int32_t)row), PFT_C(0.5)), uy), c->dy);
    *k->in = pft_rng_uniform_range(rng, c->i_min, c->i_max);
    if (sample_vel) {
        *k->vx = pft_add(c->vel_mean[0], pft_mul(d->vel_sd[0], pft_rng_gauss(rng)));
        *k->vy = pft_add(c->vel_mean[1], pft_mul(d->vel_sd[1], pft_rng_gauss(rng)));
    } else {
        *k->vx = c->vel_mean[0];
        *k->vy = c->vel_mean[1];
    }
}

/* One axis of X = F X + chol(V) n: position and velocity. */
static void axis_(const pft_tbd_dyn_t *d, pft_real_t T, pft_real_t *pos, pft_real_t *v,
                  pft_real_t g1, pft_real_t g2)
{
    *pos = pft_add(*pos, pft_add(pft_mul(T, *v), pft_mul(d->ch_pos, g1)));
    *v = pft_add(*v, pft_add(pft_mul(d->ch_cross, g1), pft_mul(d->ch_vel, g2)));
}

void pft_tbd_pf_move_(const pft_tbd_dyn_t *d, pft_real_t T, pft_rng_t *rng, pft_tbd_kin_t *k)
{
    pft_real_t g1 = pft_rng_gauss(rng);
    pft_real_t g2 = pft_rng_gauss(rng);
    pft_real_t g3 = pft_rng_gauss(rng);
    pft_real_t g4 = pft_rng_gauss(rng);
    pft_real_t g5 = pft_rng_gauss(rng);
    axis_(d, T, k->x, k->vx, g1, g2);
    axis_(d, T, k->y, k->vy, g3, g4);
    *k->in = pft_add(*k->in, pft_mul(d->ch_int, g5));
}

bool pft_tbd_centre_(const pft_tbd_meas_t *m, pft_real_t x, pft_real_t y, size_t *pix)
{
    int32_t i0 = pft_tbd_pix_(x, m->inv_dx);
    int32_t j0 = pft_tbd_pix_(y, m->inv_dy);
    if (i0 < 1 || j0 < 1 || i0 > (int32_t)m->width || j0 > (int32_t)m->height) {
        return false;
    }
    *pix = (size_t)(j0 - 1) * m->width + (size_t)(i0 - 1);
    return true;
}

bool pft_tbd_wsum_mean_(const pft_tbd_wsum_t *a, pft_real_t mean[5])
{
    if (!(a->we > 0)) {
        return false;
    }
    for (int c = 0; c < 5; ++c) {
        mean[c] = pft_acc_div_(a->s[c], a->we);
    }
    return true;
}
