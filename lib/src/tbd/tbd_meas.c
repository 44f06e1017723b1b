/* TBD measurement model (PSF, windowed LLR) and frame preparation. */
#include <string.h>

#include "tbd_int.h"

int32_t pft_tbd_pix_(pft_real_t v, pft_real_t inv_d)
{
    pft_real_t r = pft_clamp(pft_mul(v, inv_d), PFT_C(-30000.0), PFT_C(30000.0));
    return pft_round_int(r);
}

pft_status_t pft_tbd_meas_init(pft_tbd_meas_t *m, const pft_tbd_config_t *cfg)
{
    if (m == NULL || cfg == NULL) {
        return PFT_ERR_INVAL;
    }
    if (pft_tbd_config_check(cfg, NULL) != PFT_OK) {
        return PFT_ERR_CONFIG;
    }
    pft_tbd_meas_setup_(m, cfg);
    return PFT_OK;
}

void pft_tbd_meas_setup_(pft_tbd_meas_t *m, const pft_tbd_config_t *cfg)
{
    m->width = cfg->width;
    m->height = cfg->height;
    m->p = cfg->window;
    m->dx = cfg->dx;
    m->dy = cfg->dy;
    m->inv_dx = pft_recip(cfg->dx);
    m->inv_dy = pft_recip(cfg->dy);
    pft_real_t s2 = pft_sq(cfg->psf_sigma);
    m->c0 = pft_div(pft_mul(cfg->dx, cfg->dy), pft_mul(PFT_TWO_PI, s2));
    m->inv_2s2 = pft_recip(pft_mul_i(s2, 2));
    m->inv_s2n = pft_recip(pft_sq(cfg->noise_sigma));
}

pft_real_t pft_tbd_meas_h_int_(const pft_tbd_meas_t *m, int32_t i, int32_t j, pft_real_t x,
                              pft_real_t y, pft_real_t intensity)
{
    pft_real_t ddx = pft_sub(pft_mul_i(m->dx, i), x);
    pft_real_t ddy = pft_sub(pft_mul_i(m->dy, j), y);
    pft_real_t gx = pft_exp(pft_neg(pft_mul(pft_sq(ddx), m->inv_2s2)));
    pft_real_t gy = pft_exp(pft_neg(pft_mul(pft_sq(ddy), m->inv_2s2)));
    return pft_mul(pft_mul(pft_mul(intensity, m->c0), gx), gy);
}

/* The (2 half + 1)^2 pixels around the window centre of (x, y), clipped to the image: internal
 * 1-based pixel ranges ilo..ihi, jlo..jhi. False when nothing is left. */
typedef struct {
    int32_t ilo, ihi, jlo, jhi;
} win_t;

static bool window_(const pft_tbd_meas_t *m, pft_real_t x, pft_real_t y, int32_t half, win_t *w)
{
    int32_t i0 = pft_tbd_pix_(x, m->inv_dx);
    int32_t j0 = pft_tbd_pix_(y, m->inv_dy);
    w->ilo = i0 - half < 1 ? 1 : i0 - half;
    w->ihi = i0 + half > (int32_t)m->width ? (int32_t)m->width : i0 + half;
    w->jlo = j0 - half < 1 ? 1 : j0 - half;
    w->jhi = j0 + half > (int32_t)m->height ? (int32_t)m->height : j0 + half;
    return w->ilo <= w->ihi && w->jlo <= w->jhi;
}

/* ax[i - ilo] = amp gx(i) for the window's columns: the x factor of the separable PSF. */
static void psf_columns_(const pft_tbd_meas_t *m, const win_t *w, pft_real_t x, pft_real_t amp,
                         pft_real_t *ax)
{
    for (int32_t i = w->ilo; i <= w->ihi; ++i) {
        pft_real_t d = pft_sub(pft_mul_i(m->dx, i), x);
        ax[i - w->ilo] = pft_mul(amp, pft_exp(pft_neg(pft_mul(pft_sq(d), m->inv_2s2))));
    }
}

/* gy(j): the y factor of the separable PSF. */
static pft_real_t psf_row_(const pft_tbd_meas_t *m, int32_t j, pft_real_t y)
{
    pft_real_t d = pft_sub(pft_mul_i(m->dy, j), y);
    return pft_exp(pft_neg(pft_mul(pft_sq(d), m->inv_2s2)));
}

pft_real_t pft_tbd_meas_llr_int_(const pft_tbd_meas_t *m, const pft_real_t *img, pft_real_t x,
                                pft_real_t y, pft_real_t intensity)
{
    win_t w;
    if (!window_(m, x, y, (int32_t)m->p, &w)) {
        return PFT_C(0.0);
    }
    /* Separable PSF: h(i,j) = (I c0 gx(i)) * gy(j). */
    pft_real_t ax[2u * PFT_TBD_MAX_WINDOW + 1u];
    pft_real_t gy[2u * PFT_TBD_MAX_WINDOW + 1u];
    psf_columns_(m, &w, x, pft_mul(intensity, m->c0), ax);
    for (int32_t j = w.jlo; j <= w.jhi; ++j) {
        gy[j - w.jlo] = psf_row_(m, j, y);
    }
    /* sum h (z - h/2), then times 1/sigma^2 once. */
    pft_real_t acc = PFT_C(0.0);
    for (int32_t j = w.jlo; j <= w.jhi; ++j) {
        const pft_real_t *row = img + (size_t)(j - 1) * m->width;
        pft_real_t g = gy[j - w.jlo];
        for (int32_t i = w.ilo; i <= w.ihi; ++i) {
            pft_real_t h = pft_mul(ax[i - w.ilo], g);
            pft_real_t z = row[i - 1];
            acc = pft_add(acc, pft_mul(h, pft_sub(z, pft_mul(h, PFT_C(0.5)))));
        }
    }
    return pft_mul(acc, m->inv_s2n);
}

void pft_tbd_meas_add_psf_int_(const pft_tbd_meas_t *m, pft_real_t *img, pft_real_t x,
                               pft_real_t y, pft_real_t intensity, uint8_t half)
{
    int32_t p = half > PFT_TBD_MAX_PSF_HALF ? (int32_t)PFT_TBD_MAX_PSF_HALF : (int32_t)half;
    win_t w;
    if (!window_(m, x, y, p, &w)) {
        return;
    }
    pft_real_t ax[2u * PFT_TBD_MAX_PSF_HALF + 1u];
    psf_columns_(m, &w, x, pft_mul(intensity, m->c0), ax);
    for (int32_t j = w.jlo; j <= w.jhi; ++j) {
        pft_real_t g = psf_row_(m, j, y);
        pft_real_t *row = img + (size_t)(j - 1) * m->width;
        for (int32_t i = w.ilo; i <= w.ihi; ++i) {
            row[i - 1] = pft_add(row[i - 1], pft_mul(ax[i - w.ilo], g));
        }
    }
}

/* ---- public calls: 0-based coordinates (pixel column c, row r centred at (c dx, r dy)) ---- */

pft_real_t pft_tbd_meas_h(const pft_tbd_meas_t *m, int32_t c, int32_t r, pft_real_t x,
                          pft_real_t y, pft_real_t intensity)
{
    if (m == NULL) {
        return PFT_C(0.0);
    }
    return pft_tbd_meas_h_int_(m, c + 1, r + 1, pft_tbd_x_int_(x, m->dx), pft_tbd_x_int_(y, m->dy),
                               intensity);
}

pft_real_t pft_tbd_meas_llr(const pft_tbd_meas_t *m, const pft_real_t *img, pft_real_t x,
                            pft_real_t y, pft_real_t intensity)
{
    if (m == NULL || img == NULL) {
        return PFT_C(0.0);
    }
    return pft_tbd_meas_llr_int_(m, img, pft_tbd_x_int_(x, m->dx), pft_tbd_x_int_(y, m->dy),
                                 intensity);
}

void pft_tbd_meas_add_psf(const pft_tbd_meas_t *m, pft_real_t *img, pft_real_t x, pft_real_t y,
                          pft_real_t intensity, uint8_t half)
{
    if (m == NULL || img == NULL) {
        return;
    }
    pft_tbd_meas_add_psf_int_(m, img, pft_tbd_x_int_(x, m->dx), pft_tbd_x_int_(y, m->dy),
                              intensity, half);
}

/* ------------------------------------ frames ---------------------------------------------- */

pft_status_t pft_tbd_frame_check_(const pft_tbd_config_t *cfg, const pft_frame_t *frame)
{
    uint32_t fmts = PFT_FMT_BIT(PFT_PIX_U8) | PFT_FMT_BIT(PFT_PIX_U16) | PFT_FMT_BIT(PFT_PIX_F32);
    pft_status_t st = pft_frame_check(frame, cfg->width, cfg->height, fmts);
    if (st != PFT_OK) {
        return st;
    }
    return pft_frame_check_finite(frame);
}

void pft_tbd_frame_convert_(const pft_tbd_config_t *cfg, const pft_frame_t *frame,
                            pft_real_t *img)
{
    for (uint32_t r = 0; r < cfg->height; ++r) {
        pft_frame_row_to_real(frame, r, cfg->width, cfg->pixel_gain, cfg->pixel_offset,
                              img + (size_t)r * cfg->width);
    }
}

void pft_tbd_mask_add_(const pft_tbd_config_t *cfg, uint8_t *mask, const pft_tbd_region_t *r)
{
    int32_t clo = r->col_lo < 0 ? 0 : r->col_lo;
    int32_t chi = r->col_hi > (int32_t)cfg->width - 1 ? (int32_t)cfg->width - 1 : r->col_hi;
    int32_t rlo = r->row_lo < 0 ? 0 : r->row_lo;
    int32_t rhi = r->row_hi > (int32_t)cfg->height - 1 ? (int32_t)cfg->height - 1 : r->row_hi;
    for (int32_t row = rlo; row <= rhi; ++row) {
        for (int32_t col = clo; col <= chi; ++col) {
            mask[(size_t)row * cfg->width + (size_t)col] = 1u;
        }
    }
}

void pft_tbd_scene_build_(const pft_tbd_config_t *cfg, const pft_real_t *img,
                          const uint8_t *mask, uint32_t *cand, pft_tbd_scene_t_ *sc)
{
    uint32_t npix = (uint32_t)cfg->width * cfg->height;
    uint32_t nb = 0;
    uint32_t na = 0;
    for (uint32_t k = 0; k < npix; ++k) {
        if (mask != NULL && mask[k] != 0u) {
            continue;
        }
        ++na;
        if (img[k] > cfg->gamma) {
            cand[nb++] = k;
        }
    }
    sc->img = img;
    sc->mask = mask;
    sc->cand = cand;
    sc->n_allowed = na;
    sc->cand_is_b = nb > 0u;
    if (nb == 0u && na > 0u) {
        /* No pixel above gamma: propose uniformly over the allowed pixels, correction 0. */
        for (uint32_t k = 0; k < npix; ++k) {
            if (mask == NULL || mask[k] == 0u) {
                cand[nb++] = k;
            }
        }
    }
    sc->n_cand = nb;
}
