/* TBD configuration: defaults, the recommended preset, the check, constraint windows. */
#include <string.h>

#include "tbd_int.h"
#include "../core/config_int.h"
#include "../core/num_int.h"

void pft_tbd_config_default(pft_tbd_config_t *cfg)
{
    if (cfg == NULL) {
        return;
    }
    memset(cfg, 0, sizeof(*cfg));
    cfg->width = 20u;
    cfg->height = 20u;
    cfg->dx = PFT_C(1.0);
    cfg->dy = PFT_C(1.0);
    cfg->psf_sigma = PFT_C(0.7);
    cfg->noise_sigma = PFT_C(3.2);
    cfg->pixel_gain = PFT_C(1.0);
    cfg->pixel_offset = PFT_C(0.0);
    cfg->window = 1u;
    cfg->T = PFT_C(1.0);
    cfg->q1 = PFT_C(0.005);
    cfg->q2 = PFT_C(0.01);
    cfg->pb = PFT_C(0.05);
    cfg->pd = PFT_C(0.05);
    cfg->eta = PFT_C(0.05);
    cfg->gamma = PFT_C(2.0);
    cfg->i_min = PFT_C(10.0);
    cfg->i_max = PFT_C(30.0);
    cfg->vel_mean[0] = PFT_C(0.0);
    cfg->vel_mean[1] = PFT_C(0.0);
    cfg->vel_var[0] = PFT_C(0.333333333333);
    cfg->vel_var[1] = PFT_C(0.333333333333);
    cfg->birth_correction = false;
    cfg->birth_peaks = 0u;
    cfg->peak_gamma = PFT_C(1.0);
    cfg->peak_tile = 0u;
    cfg->peak_quota = 0u;
    cfg->birth_share = PFT_C(0.0);
    cfg->theta1 = PFT_C(0.6);
    cfg->confirm_frames = 1u;
    cfg->dis_r = 2u;
    cfg->dis_prev = 5u;
    cfg->dis_ratio = PFT_C(0.8);
    cfg->dis_ratio_test = true;
    cfg->theta_end = PFT_C(0.0);
    cfg->d_margin = 0u;
    cfg->d_current = false;
    cfg->force_constraint = true;
    cfg->d_region = PFT_TBD_D_WINDOW;
    cfg->residual_search = false;
    cfg->residual_tracks = false;
    cfg->residual_margin = 1u;
    cfg->handover_gate = 0u;
    cfg->end_lr_frames = 0u;
    cfg->end_lr_max = PFT_C(0.0);
    cfg->n_search = 6000u;
    cfg->n_track = 500u;
    cfg->max_targets = 4u;
    cfg->kind = PFT_TBD_RBPF;
    cfg->kf_variant = PFT_TBD_KF_EXACT;
    cfg->seed = 1u;
    cfg->seq_mode = PFT_SEQ_IGNORE;
    cfg->max_gap = (uint16_t)PFT_SEQ_DEFAULT_GAP;
    cfg->frame_format = (pft_pixfmt_t)0;
    cfg->sprt_accept = PFT_C(0.0);
    cfg->sprt_reject = PFT_C(-5.0);
    cfg->shape_ring = PFT_C(0.0);
    cfg->sprt_start = 0u;
    cfg->integ_alpha = PFT_C(0.0);
    cfg->end_grace_frames = 0u;
    cfg->theta_end_grace = PFT_C(0.0);
    cfg->end_persist = 0u;
    cfg->handover_in_scale = PFT_C(0.0);
    cfg->split_px = PFT_C(0.0);
    cfg->split_share = PFT_C(0.0);
    cfg->resid_split = PFT_C(0.0);
    cfg->resid_split_frames = 0u;
    cfg->resid_split_age = 0u;
    cfg->search_layers = 0u;
    cfg->search_sep = PFT_C(0.0);
    cfg->search_hold = PFT_C(0.0);
}

void pft_tbd_config_recommended(pft_tbd_config_t *cfg)
{
    if (cfg == NULL) {
        return;
    }
    pft_tbd_config_default(cfg);
    cfg->dis_ratio_test = false;
    cfg->theta_end = PFT_C(0.5);
    cfg->d_current = true;
    cfg->d_margin = 1u;
    cfg->residual_search = true;
    cfg->residual_tracks = true;
    cfg->d_region = PFT_TBD_D_NONE;
    cfg->handover_gate = 2u;
}

void pft_tbd_config_bounded(pft_tbd_config_t *cfg)
{
    if (cfg == NULL) {
        return;
    }
    pft_tbd_config_recommended(cfg);
    cfg->birth_share = PFT_C(0.5);
    cfg->theta1 = PFT_C(0.475);
    cfg->n_search = 3000u;
}

static bool in01_(pft_real_t p) { return p >= PFT_C(0.0) && p <= PFT_C(1.0); }

/* The first refused field of the image, sensor and dynamics settings, NULL if none. */
static const char *refused_model_(const pft_tbd_config_t *c)
{
    if (c->width < 1u || c->width > PFT_CFG_MAX_IMAGE_SIDE) {
        return "width";
    }
    if (c->height < 1u || c->height > PFT_CFG_MAX_IMAGE_SIDE) {
        return "height";
    }
    /* positions must stay well inside the number range (q16) */
    if (!pft_cfg_real_pos_(c->dx) || !pft_span_ok_(c->width, c->dx)) {
        return "dx";
    }
    if (!pft_cfg_real_pos_(c->dy) || !pft_span_ok_(c->height, c->dy)) {
        return "dy";
    }
    /* reals in the configuration domain shared by both builds (core/config_int.h): in float a
     * subnormal psf_sigma or noise_sigma made every estimate NaN (reliability.md F4) */
    if (!pft_cfg_real_pos_(c->psf_sigma)) {
        return "psf_sigma";
    }
    if (!pft_cfg_real_pos_(c->noise_sigma)) {
        return "noise_sigma";
    }
    if (!pft_cfg_real_ok_(c->pixel_gain)) {
        return "pixel_gain";
    }
    if (!pft_cfg_real_ok_(c->pixel_offset)) {
        return "pixel_offset";
    }
    if (c->window > PFT_TBD_MAX_WINDOW) {
        return "window";
    }
    if (!pft_cfg_real_pos_(c->T)) {
        return "T";
    }
    if (!(c->q1 >= PFT_C(0.0)) || !pft_cfg_real_ok_(c->q1)) {
        return "q1";
    }
    if (!(c->q2 >= PFT_C(0.0)) || !pft_cfg_real_ok_(c->q2)) {
        return "q2";
    }
    return NULL;
}

/* The first refused field of the birth prior, NULL if none (fields checked first). The ranges
 * keep every state a birth can start from inside the number range (docs/fixed_point.md,
 * "Particle kernels"): intensities in [0, i_max] with the PSF peak i_max c0 and its whitened
 * value i_max c0 / sigma below 32767, and a velocity prior that crosses at most the image
 * (span = width dx, height dy) per frame period: |vel_mean| T <= span, sqrt(vel_var) T <= span. */
static const char *refused_birth_(const pft_tbd_config_t *c)
{
    static const char *const vm[2] = {"vel_mean[0]", "vel_mean[1]"};
    static const char *const vv[2] = {"vel_var[0]", "vel_var[1]"};
    const pft_real_t span[2] = {pft_mul_i(c->dx, (int32_t)c->width),
                                pft_mul_i(c->dy, (int32_t)c->height)};
    const pft_real_t c0 =
        pft_div(pft_mul(c->dx, c->dy), pft_mul(PFT_TWO_PI, pft_sq(c->psf_sigma)));
    if (!(c->i_min >= PFT_C(0.0))) {
        return "i_min";
    }
    if (!(c->i_min <= c->i_max) || !(pft_mul(c->i_max, c0) < PFT_C(32767.0)) ||
        !(pft_mul(c->i_max, pft_div(c0, c->noise_sigma)) < PFT_C(32767.0))) {
        return "i_max";
    }
    for (int a = 0; a < 2; ++a) {
        if (!(pft_mul(pft_abs(c->vel_mean[a]), c->T) <= span[a])) {
            return vm[a];
        }
    }
    for (int a = 0; a < 2; ++a) {
        if (!(c->vel_var[a] >= PFT_C(0.0)) || !(pft_mul(pft_sqrt(c->vel_var[a]), c->T) <= span[a])) {
            return vv[a];
        }
    }
    return NULL;
}

/* v == 0, written without an equality test of reals (NaN is not 0). */
static bool is_off_(pft_real_t v) { return v >= PFT_C(0.0) && v <= PFT_C(0.0); }

/* The first refused field of the existence, birth and decision settings, NULL if none. */
static const char *refused_decisions_(const pft_tbd_config_t *c)
{
    const pft_real_t probs[6] = {c->pb, c->pd, c->eta, c->theta1, c->theta_end, c->theta_end_grace};
    static const char *const names[6] = {"pb", "pd", "eta", "theta1", "theta_end", "theta_end_grace"};
    for (int k = 0; k < 6; ++k) {
        if (!in01_(probs[k])) {
            return names[k];
        }
    }
    const char *bad = refused_birth_(c);
    if (bad != NULL) {
        return bad;
    }
    if (c->dis_r > PFT_TBD_MAX_DIS_R) {
        return "dis_r";
    }
    if (c->dis_prev < 1u || c->dis_prev > PFT_TBD_MAX_DIS_PREV) {
        return "dis_prev";
    }
    if (!(c->dis_ratio > PFT_C(0.0) && c->dis_ratio <= PFT_C(1.0))) {
        return "dis_ratio";
    }
    if (c->d_margin > 16u) {
        return "d_margin";
    }
    if (c->d_region != PFT_TBD_D_WINDOW && c->d_region != PFT_TBD_D_PIXEL &&
        c->d_region != PFT_TBD_D_NONE) {
        return "d_region";
    }
    if ((uint32_t)c->window + c->residual_margin > PFT_TBD_MAX_PSF_HALF) {
        return "residual_margin";
    }
    if (c->end_lr_frames > PFT_TBD_MAX_DIS_R + 1u) {
        return "end_lr_frames";
    }
    if (!pft_cfg_real_ok_(c->end_lr_max)) {
        return "end_lr_max";
    }
    if (!pft_cfg_real_ok_(c->gamma)) {
        return "gamma";
    }
    if (c->handover_gate > 64u) {
        return "handover_gate";
    }
    if (c->birth_peaks > PFT_TBD_MAX_PEAKS) {
        return "birth_peaks";
    }
    if (!pft_cfg_real_ok_(c->peak_gamma)) {
        return "peak_gamma";
    }
    if (c->peak_quota > 0u && c->peak_tile < 4u) {
        return "peak_tile";
    }
    if (c->peak_quota > 0u && c->peak_tile > 0u) {
        const uint32_t nt = (((uint32_t)c->width + c->peak_tile - 1u) / c->peak_tile) *
                            (((uint32_t)c->height + c->peak_tile - 1u) / c->peak_tile);
        if ((uint32_t)c->birth_peaks + nt > (uint32_t)c->width * c->height) {
            return "peak_quota";
        }
    }
    if (!(c->birth_share >= PFT_C(0.0) && c->birth_share <= PFT_C(0.95))) {
        return "birth_share";
    }
    if (c->confirm_frames > PFT_TBD_MAX_DIS_R + 1u) {
        return "confirm_frames";
    }
    if (!(c->sprt_accept >= PFT_C(0.0) && c->sprt_accept <= PFT_C(10000.0))) {
        return "sprt_accept";
    }
    if (!(c->sprt_reject <= PFT_C(0.0) && c->sprt_reject >= PFT_C(-10000.0))) {
        return "sprt_reject";
    }
    if (!(c->shape_ring >= PFT_C(0.0) && c->shape_ring <= PFT_C(100.0))) {
        return "shape_ring";
    }
    if (c->sprt_start > 2u) {
        return "sprt_start";
    }
    if (c->end_persist > PFT_TBD_MAX_END_PERSIST) {
        return "end_persist";
    }
    if (!(c->handover_in_scale >= PFT_C(0.0) && c->handover_in_scale <= PFT_REAL_ONE)) {
        return "handover_in_scale";
    }
    if (!(is_off_(c->split_px) || (c->split_px >= PFT_C(0.5) && c->split_px <= PFT_C(16.0)))) {
        return "split_px";
    }
    if (!(c->split_share >= PFT_C(0.0) && c->split_share <= PFT_C(0.5)) ||
        (!is_off_(c->split_px) && !(c->split_share > PFT_C(0.0)))) {
        return "split_share";
    }
    if (!(is_off_(c->resid_split) ||
          (c->resid_split >= PFT_REAL_ONE && c->resid_split <= PFT_C(50.0)))) {
        return "resid_split";
    }
    if (c->resid_split_frames > 8u) {
        return "resid_split_frames";
    }
    if (!(c->integ_alpha >= PFT_C(0.0) && c->integ_alpha < PFT_REAL_ONE) ||
        (c->integ_alpha > PFT_C(0.0) && (c->birth_peaks == 0u || c->peak_quota > 0u))) {
        return "integ_alpha";
    }
    if (c->search_layers > PFT_TBD_MAX_SEARCH ||
        (c->search_layers >= 2u &&
         (!(c->birth_share > PFT_C(0.0)) || c->n_search < 4u * (uint32_t)c->search_layers))) {
        return "search_layers";
    }
    if (c->search_layers >= 2u ? !(c->search_sep >= PFT_REAL_ONE && c->search_sep <= PFT_C(16.0))
                               : !is_off_(c->search_sep)) {
        return "search_sep";
    }
    if (!(c->search_hold >= PFT_C(0.0) && c->search_hold < PFT_REAL_ONE) ||
        (c->search_layers < 2u && !is_off_(c->search_hold))) {
        return "search_hold";
    }
    return NULL;
}

/* a == b, written without an equality test of reals. */
static bool is_value_(pft_real_t a, pft_real_t b) { return !(a < b) && !(a > b); }

/* The first refused size or algorithm choice, NULL if none. */
static const char *refused_sizes_(const pft_tbd_config_t *c)
{
    if (c->n_search < 1u || c->n_search > PFT_CFG_MAX_PARTICLES) {
        return "n_search";
    }
    if (c->n_track < 1u || c->n_track > PFT_CFG_MAX_PARTICLES) {
        return "n_track";
    }
    if (c->max_targets < 1u) {
        return "max_targets";
    }
    if (c->kind != PFT_TBD_RBPF && c->kind != PFT_TBD_PF) {
        return "kind";
    }
    if (c->kf_variant != PFT_TBD_KF_EXACT && c->kf_variant != PFT_TBD_KF_PAPER) {
        return "kf_variant";
    }
    if (c->seq_mode != PFT_SEQ_IGNORE && c->seq_mode != PFT_SEQ_USE) {
        return "seq_mode";
    }
    if (c->max_gap < 1u || c->max_gap > PFT_SEQ_MAX_GAP) {
        return "max_gap";
    }
    /* the frame read in place: its values are res / 256 only with gain 1, offset 0, sigma 1 */
    if (c->frame_format != (pft_pixfmt_t)0 &&
        (c->frame_format != PFT_PIX_RES16 || !is_value_(c->pixel_gain, PFT_REAL_ONE) ||
         !is_value_(c->pixel_offset, PFT_C(0.0)) || !is_value_(c->noise_sigma, PFT_REAL_ONE))) {
        return "frame_format";
    }
    return NULL;
}

pft_status_t pft_tbd_config_check(const pft_tbd_config_t *cfg, const char **field)
{
    const char *bad = NULL;
    if (cfg != NULL) {
        bad = refused_model_(cfg);
        if (bad == NULL) {
            bad = refused_decisions_(cfg);
        }
        if (bad == NULL) {
            bad = refused_sizes_(cfg);
        }
    }
    return pft_config_verdict_(cfg != NULL, bad, field);
}

pft_tbd_region_t pft_tbd_window_int_(const pft_tbd_config_t *cfg, pft_real_t x, pft_real_t y)
{
    /* the window centre pixel (i0, j0) of the internal frame is column i0 - 1, row j0 - 1 */
    int32_t c0 = pft_tbd_pix_(x, pft_recip(cfg->dx)) - 1;
    int32_t r0 = pft_tbd_pix_(y, pft_recip(cfg->dy)) - 1;
    int32_t p = (int32_t)cfg->window;
    pft_tbd_region_t r = {c0 - p, c0 + p, r0 - p, r0 + p};
    return r;
}

pft_tbd_region_t pft_tbd_window_region(const pft_tbd_config_t *cfg, pft_real_t x, pft_real_t y)
{
    if (cfg == NULL || !(cfg->dx > PFT_C(0.0)) || !(cfg->dy > PFT_C(0.0))) {
        pft_tbd_region_t empty = {0, -1, 0, -1};
        return empty;
    }
    return pft_tbd_window_int_(cfg, pft_tbd_x_int_(x, cfg->dx), pft_tbd_x_int_(y, cfg->dy));
}
