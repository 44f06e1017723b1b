/* Configuration of the TSA-AK tracker: defaults, the check that names the refused field, and
 * the workspace size. */
#include <string.h>

#include "tsa_int.h"

void pft_tsa_config_default(pft_tsa_config_t *cfg)
{
    if (cfg == NULL) {
        return;
    }
    memset(cfg, 0, sizeof(*cfg));
    cfg->width = 0u; /* required */
    cfg->height = 0u;
    cfg->max_target_w = 64u;
    cfg->max_target_h = 64u;
    cfg->n_particles = 100u;
    cfg->motion = PFT_TSA_MOTION_TSA;
    cfg->beta0 = PFT_C(2.0);
    cfg->beta_max = PFT_C(6.0);
    cfg->q = PFT_C(4.07);
    cfg->pos_sd = PFT_C(2.0);
    cfg->spread_gain = PFT_C(1.5);
    cfg->spread_max = PFT_C(8.0);
    cfg->fit_k = 4u;
    cfg->fit_sigma = PFT_C(2.0);
    cfg->fit_rho_weights = false;
    cfg->fit_a_max = PFT_C(0.5);
    cfg->fit_v_max = PFT_C(12.0);
    cfg->rho_min = PFT_C(0.75);
    cfg->lik_lambda = PFT_C(300.0);
    cfg->theta_u = PFT_C(0.0);
    cfg->update_rho_min = PFT_C(0.85);
    cfg->anchor_rho_min = PFT_C(0.8);
    cfg->k_s = PFT_C(1.5);
    cfg->update_max_passes = 3u;
    cfg->init_passes = 0u;
    cfg->snake_points = 40u;
    pft_tsa_snake_params_default(&cfg->snake, cfg->max_target_w, cfg->max_target_h);
    cfg->kernel_c = PFT_C(1.0);
    cfg->max_area_change = PFT_C(2.0);
    cfg->lost_frames = 10u;
    cfg->loss_search = true;
    cfg->gain_select = true;
    cfg->rho_acquire = PFT_C(0.88);
    cfg->bg_ring = PFT_C(2.5);
    cfg->bg_alpha = PFT_C(0.5);
    cfg->acquire_on = 1u;
    cfg->search_growth = PFT_C(16.0);
    cfg->reacq_radius = PFT_C(24.0);
    cfg->map_margin = 48u;
    cfg->seed = 1u;
    cfg->seq_mode = PFT_SEQ_IGNORE;
    cfg->max_gap = (uint16_t)PFT_SEQ_DEFAULT_GAP;
}

/* lo <= v <= hi (false for NaN in the float build). */
static bool in_range_(pft_real_t v, pft_real_t lo, pft_real_t hi)
{
    return v >= lo && v <= hi;
}

/* Name of the first refused field of c, NULL when c is usable. */
static const char *refused_field_(const pft_tsa_config_t *c)
{
    if (c->width < 8u || c->width > PFT_CFG_MAX_IMAGE_SIDE) {
        return "width";
    }
    if (c->height < 8u || c->height > PFT_CFG_MAX_IMAGE_SIDE) {
        return "height";
    }
    if (c->max_target_w < 4u || c->max_target_w > PFT_TSA_MAX_SIDE) {
        return "max_target_w";
    }
    if (c->max_target_h < 4u || c->max_target_h > PFT_TSA_MAX_SIDE) {
        return "max_target_h";
    }
    if (c->n_particles == 0u || c->n_particles > 65535u ||
        c->n_particles > PFT_CFG_MAX_PARTICLES - 1u) {
        return "n_particles";
    }
    if ((unsigned)c->motion > (unsigned)PFT_TSA_MOTION_TSA) {
        return "motion";
    }
    if (!in_range_(c->beta0, PFT_C(0.0), PFT_C(64.0))) {
        return "beta0";
    }
    if (!(c->beta_max > PFT_C(0.0)) || c->beta_max > PFT_C(64.0)) {
        return "beta_max";
    }
    if (!in_range_(c->q, PFT_C(0.0), PFT_C(10000.0))) {
        return "q";
    }
    if (!in_range_(c->pos_sd, PFT_C(0.0), PFT_C(1000.0))) {
        return "pos_sd";
    }
    if (!in_range_(c->spread_gain, PFT_C(0.0), PFT_C(100.0))) {
        return "spread_gain";
    }
    if (!in_range_(c->spread_max, PFT_C(0.0), PFT_C(1000.0))) {
        return "spread_max";
    }
    if (c->fit_k == 0u || c->fit_k > PFT_TSA_MOTION_MAX_K) {
        return "fit_k";
    }
    if (!(c->fit_sigma > PFT_C(0.0))) {
        return "fit_sigma";
    }
    if (!in_range_(c->fit_a_max, PFT_C(0.0), PFT_C(1000.0))) {
        return "fit_a_max";
    }
    if (!in_range_(c->fit_v_max, PFT_C(0.0), PFT_C(1000.0))) {
        return "fit_v_max";
    }
    if (!in_range_(c->rho_min, PFT_C(0.0), PFT_REAL_ONE)) {
        return "rho_min";
    }
    if (!in_range_(c->lik_lambda, PFT_C(0.0), PFT_C(1000.0))) {
        return "lik_lambda";
    }
    if (!in_range_(c->theta_u, PFT_C(0.0), PFT_REAL_ONE)) {
        return "theta_u";
    }
    if (!in_range_(c->update_rho_min, PFT_C(0.0), PFT_REAL_ONE)) {
        return "update_rho_min";
    }
    if (!in_range_(c->anchor_rho_min, PFT_C(0.0), PFT_REAL_ONE)) {
        return "anchor_rho_min";
    }
    if (!(c->k_s > PFT_C(0.0)) || c->k_s > PFT_C(100.0)) {
        return "k_s";
    }
    if (c->snake_points < PFT_TSA_MIN_POINTS) {
        return "snake_points";
    }
    if (c->snake.margin < 3u) {
        return "snake.margin";
    }
    if (!in_range_(c->kernel_c, PFT_C(0.0), PFT_C(1000.0))) {
        return "kernel_c";
    }
    if (!in_range_(c->max_area_change, PFT_REAL_ONE, PFT_C(1000.0))) {
        return "max_area_change";
    }
    if (!in_range_(c->rho_acquire, PFT_C(0.0), PFT_REAL_ONE)) {
        return "rho_acquire";
    }
    /* 0 (off) or 1 < bg_ring <= 8 */
    if (!(in_range_(c->bg_ring, PFT_C(0.0), PFT_C(0.0)) ||
          (c->bg_ring > PFT_REAL_ONE && c->bg_ring <= PFT_C(8.0)))) {
        return "bg_ring";
    }
    if (!(c->bg_alpha > PFT_C(0.0) && c->bg_alpha <= PFT_REAL_ONE)) {
        return "bg_alpha";
    }
    if (c->acquire_on > 2u) {
        return "acquire_on";
    }
    if (!in_range_(c->search_growth, PFT_C(0.0), PFT_C(4096.0))) {
        return "search_growth";
    }
    if (!in_range_(c->reacq_radius, PFT_C(0.0), PFT_C(4096.0))) {
        return "reacq_radius";
    }
    if (c->map_margin > 4096u) {
        return "map_margin";
    }
    if (c->seq_mode != PFT_SEQ_IGNORE && c->seq_mode != PFT_SEQ_USE) {
        return "seq_mode";
    }
    if (c->max_gap < 1u || c->max_gap > PFT_SEQ_MAX_GAP) {
        return "max_gap";
    }
    return NULL;
}

pft_status_t pft_tsa_config_check(const pft_tsa_config_t *cfg, const char **field)
{
    if (field != NULL) {
        *field = NULL;
    }
    if (cfg == NULL) {
        return PFT_ERR_INVAL;
    }
    const char *bad = refused_field_(cfg);
    if (bad != NULL) {
        if (field != NULL) {
            *field = bad;
        }
        return PFT_ERR_CONFIG;
    }
    return PFT_OK;
}

size_t pft_tsa_workspace_size(const pft_tsa_config_t *cfg)
{
    if (pft_tsa_config_check(cfg, NULL) != PFT_OK) {
        return 0u;
    }
    return PFT_TSA_WORKSPACE_BYTES((size_t)cfg->n_particles, (size_t)cfg->max_target_w,
                                   (size_t)cfg->max_target_h, (size_t)cfg->snake_points,
                                   (size_t)cfg->snake.margin, (size_t)cfg->map_margin);
}
