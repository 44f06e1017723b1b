/* The PF-TBD pieces written once (docs/algorithms.md 2.1, 2.2, 2.9): existence chain, births
 * and the estimate sums (the full-state CV step and the leave-image test are inline in
 * tbd_int.h), and the tables every filter of a workspace shares. Used by the tbd filters
 * (tbd_filter.c) and by the pf engine's TBD model (lib/src/pf/pf_model_tbd.c), which draws
 * exactly as the tbd module's PF-TBD does (test_pf_models.c). */
#include <string.h>

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

void pft_tbd_birth_pix_(const pft_tbd_config_t *c, const pft_tbd_dyn_t *d, uint32_t p,
                        bool sample_vel, pft_rng_t *rng, pft_tbd_kin_t *k)
{
    const pft_tbd_birth_inv_t b = pft_tbd_birth_inv_(c, d);
    pft_tbd_birth_pix_v_(&b, p, sample_vel, rng, k);
}

void pft_tbd_birth_(const pft_tbd_config_t *c, const pft_tbd_dyn_t *d, const uint32_t *cand,
                    uint32_t n_cand, bool sample_vel, pft_rng_t *rng, pft_tbd_kin_t *k)
{
    pft_tbd_birth_pix_(c, d, cand[pft_rng_below(rng, n_cand)], sample_vel, rng, k);
}

/* The RBPF's velocity filter per axis as a function of age (docs/algorithms.md 2.3): from
 * P_0 = vel_var, N_a = T^2 P_a + q1 T^3/3, K_a = T P_a / N_a, P+ = P_a - K_a T P_a, and
 * P_{a+1} = P+/4 + q1 T/4 (exact) or P+ + q1 T (paper). A survivor of age a moves by
 * T m + sd_a g and its mean by G_a sd_a g, with G_a = 3/(2T) - K_a/2 (exact: the time update
 * -m+/2 + 3/(2T) y written with y = T m + sd_a g) or K_a (paper). The recursion contracts by at
 * least 4 per frame after the first, so entry PFT_TBD_KF_AGES - 1 is its fixed point. */
static void kf_axis_table_(const pft_tbd_config_t *cfg, pft_real_t p0, pft_real_t *sd,
                           pft_real_t *gsd)
{
    const pft_real_t T = cfg->T;
    const pft_real_t T2 = pft_sq(T);
    const pft_real_t qpos = pft_div(pft_mul(cfg->q1, pft_mul(T2, T)), PFT_C(3.0));
    const pft_real_t q1T = pft_mul(cfg->q1, T);
    const bool exact = cfg->kf_variant == PFT_TBD_KF_EXACT;
    const pft_real_t qvel = exact ? pft_mul(q1T, PFT_C(0.25)) : q1T;
    const pft_real_t c32 = pft_div(PFT_C(1.5), T);
    pft_real_t p = p0;
    for (uint32_t a = 0; a < PFT_TBD_KF_AGES; ++a) {
        pft_real_t nv = pft_add(pft_mul(T2, p), qpos);
        pft_real_t k = nv > PFT_C(0.0) ? pft_div(pft_mul(T, p), nv) : PFT_C(0.0);
        pft_real_t pplus = pft_max(pft_sub(p, pft_mul(pft_mul(k, T), p)), PFT_C(0.0));
        pft_real_t g = exact ? pft_sub(c32, pft_mul(k, PFT_C(0.5))) : k;
        sd[a] = pft_sqrt(nv);
        gsd[a] = pft_mul(g, sd[a]);
        p = exact ? pft_add(pft_mul(pplus, PFT_C(0.25)), qvel) : pft_add(pplus, qvel);
    }
}

void pft_tbd_tab_setup_(pft_tbd_tab_t *t, const pft_tbd_config_t *cfg)
{
    pft_tbd_meas_t m;
    memset(t, 0, sizeof(*t));
    pft_tbd_meas_setup_(&m, cfg);
    pft_tbd_taps_setup_(t, &m);
    kf_axis_table_(cfg, cfg->vel_var[0], t->kf_sd[0], t->kf_gsd[0]);
    kf_axis_table_(cfg, cfg->vel_var[1], t->kf_sd[1], t->kf_gsd[1]);
    t->age_cap = (uint8_t)(PFT_TBD_KF_AGES - 1u);
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
