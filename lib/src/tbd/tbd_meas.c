/* TBD measurement model (PSF, windowed LLR) and frame preparation. */
#include <string.h>

#include "tbd_int.h"

#if defined(__SSE2__)
/* Where the compiler has SSE2 (x86-64): q16's scene scan takes a RES16 row's horizontal sums
 * (peak_hrow_r16_, the centre tap 1) as 16-bit multiply-adds (pmaddwd) of each pixel's two
 * neighbours, eight pixels per step (peak_hrow_r16_madd_), instead of the widening products
 * the compiler makes of pft_kmul_r16_; both builds take the integration's inner bins
 * (integ_row_) eight per step with the sums' rounding, clamps and the bin word in 16-bit lanes
 * (integ_fast8_); q16's vertical sums (peak_vrow_, the centre tap 1) take each product of a
 * tap and a 32-bit value from 16-bit products of its halves (peak_vrow_mul_: one multiply-add
 * and two 16 x 16-bit products) instead of two 32-bit products, which SSE2 lacks. The same
 * values; the Cortex-M builds keep the plain loops, and AArch64 has NEON
 * forms of the bins and of q16's row sums (below). */
#include <emmintrin.h>
#define PFT_TBD_INTEG_FAST8_ 1
#if defined(PFT_NUMERIC_Q16)
#define PFT_TBD_HROW_MADD_ 1
#define PFT_TBD_VROW_MUL_ 1
#endif
#define PFT_TBD_INTEG_AQ_MAX_ 256u
#elif defined(__aarch64__) && defined(__ARM_NEON)
/* AArch64 with NEON: both builds take the integration's inner bins eight per step
 * (integ_fast8_'s NEON form: the rounding as one conversion toward minus infinity in float and
 * one rounding shift in q16, the bin word's sum and clamps in 16-bit lanes); q16 takes the
 * RES16 row sums with the centre tap 1 eight pixels per step in 32-bit lanes
 * (peak_hrow_r16_madd_'s NEON form: the pair sum widened, a multiply-add by th and the rounded
 * product by tl) instead of gcc's widening products of pft_kmul_r16_; both builds skip the
 * bins under the peak scan's threshold eight at a time (integ_skip8_) and take a bin row's
 * sums and squares eight words per step (integ_sums8_). The same values; the
 * vertical sums keep the plain loop here. */
#include <arm_neon.h>
#define PFT_TBD_INTEG_FAST8_ 1
#define PFT_TBD_INTEG_AQ_MAX_ 256u
#if defined(PFT_NUMERIC_Q16)
#define PFT_TBD_HROW_MADD_ 1
#endif
#endif

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
    m->inv_sn = pft_recip(cfg->noise_sigma);
    m->kc = pft_div(m->c0, cfg->noise_sigma);
    m->hi_x = pft_add(pft_from_int((int32_t)cfg->width), PFT_C(0.5));
    m->hi_y = pft_add(pft_from_int((int32_t)cfg->height), PFT_C(0.5));
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

void pft_tbd_psf_add_(const pft_tbd_meas_t *m, pft_real_t *img, size_t origin, uint32_t stride,
                      pft_real_t x, pft_real_t y, pft_real_t coef, uint8_t half)
{
    int32_t p = half > PFT_TBD_MAX_PSF_HALF ? (int32_t)PFT_TBD_MAX_PSF_HALF : (int32_t)half;
    win_t w;
    if (!window_(m, x, y, p, &w)) {
        return;
    }
    pft_real_t ax[2u * PFT_TBD_MAX_PSF_HALF + 1u];
    psf_columns_(m, &w, x, coef, ax);
    for (int32_t j = w.jlo; j <= w.jhi; ++j) {
        pft_real_t g = psf_row_(m, j, y);
        pft_real_t *row = img + origin + (size_t)(j - 1) * stride;
        for (int32_t i = w.ilo; i <= w.ihi; ++i) {
            row[i - 1] = pft_add(row[i - 1], pft_mul(ax[i - w.ilo], g));
        }
    }
}

/* The exact kernel's window around cell c, clipped to the image (internal 1-based ranges), and
 * its taps. */
static void exact_taps_(const pft_tbd_meas_t *m, const pft_tbd_cell_t *c, win_t *w,
                        pft_real_t *tx, pft_real_t *ty)
{
    const int32_t p = (int32_t)m->p;
    w->ilo = c->i - p < 1 ? 1 : c->i - p;
    w->ihi = c->i + p > (int32_t)m->width ? (int32_t)m->width : c->i + p;
    w->jlo = c->j - p < 1 ? 1 : c->j - p;
    w->jhi = c->j + p > (int32_t)m->height ? (int32_t)m->height : c->j + p;
    /* offsets from the particle in pixels: (i - u) for u = i0 + f */
    for (int32_t i = w->ilo; i <= w->ihi; ++i) {
        pft_real_t d = pft_mul(pft_sub(pft_from_int(i - c->i), pft_kfrac_off_(c->fx)), m->dx);
        tx[i - w->ilo] = pft_exp(pft_neg(pft_mul(pft_sq(d), m->inv_2s2)));
    }
    for (int32_t j = w->jlo; j <= w->jhi; ++j) {
        pft_real_t d = pft_mul(pft_sub(pft_from_int(j - c->j), pft_kfrac_off_(c->fy)), m->dy);
        ty[j - w->jlo] = pft_exp(pft_neg(pft_mul(pft_sq(d), m->inv_2s2)));
    }
}

pft_real_t pft_tbd_llr_exact_(const pft_tbd_meas_t *m, const pft_real_t *img,
                              const pft_tbd_cell_t *c, pft_real_t intensity)
{
    const size_t stride = (size_t)m->width + 2u;
    pft_real_t tx[2u * PFT_TBD_MAX_WINDOW + 1u];
    pft_real_t ty[2u * PFT_TBD_MAX_WINDOW + 1u];
    win_t w;
    exact_taps_(m, c, &w, tx, ty);
    return pft_kspot_(img + (size_t)w.jlo * stride + (size_t)w.ilo, stride, tx,
                      (uint32_t)(w.ihi - w.ilo + 1), ty, (uint32_t)(w.jhi - w.jlo + 1),
                      pft_mul(intensity, m->kc));
}

pft_real_t pft_tbd_llr3_r16_call_(const pft_tbd_meas_t *m, const pft_tbd_tab_t *tab,
                                  const pft_tbd_scene_t_ *sc, const pft_tbd_cell_t *c,
                                  pft_real_t intensity)
{
    return pft_tbd_llr3_r16_(m, tab, sc, c, intensity);
}

pft_real_t pft_tbd_llr3_r16_out_(const pft_tbd_meas_t *m, const pft_tbd_tab_t *tab,
                                 const pft_tbd_scene_t_ *sc, int32_t i, int32_t j, pft_kfrac_t fx,
                                 pft_kfrac_t fy, pft_real_t amp)
{
    pft_real_t tx[4], ty[4];
    pft_real_t z[9];
    const bool ex = (uint32_t)(i - 2) >= (uint32_t)m->width - 2u;
    const bool ey = (uint32_t)(j - 2) >= (uint32_t)m->height - 2u;
    pft_ktaps_(tab->taps[0], fx, tx);
    pft_ktaps_(tab->taps[1], fy, ty);
    if (ex) {
        pft_tbd_clip_(tx, i, (int32_t)m->width);
    }
    if (ey) {
        pft_tbd_clip_(ty, j, (int32_t)m->height);
    }
    if (ex || ey) {
        pft_tbd_fetch_(sc, i - 2, j - 2, 3u, 3u, z);
    } else {
        const size_t st = sc->r16_stride;
        const uint8_t *p = sc->r16 + (size_t)(j - 2) * st + 2u * (size_t)(i - 2);
        for (uint32_t b = 0; b < 3u; ++b) {
            z[3u * b] = pft_tbd_r16_(p + (size_t)b * st);
            z[3u * b + 1u] = pft_tbd_r16_(p + (size_t)b * st + 2u);
            z[3u * b + 2u] = pft_tbd_r16_(p + (size_t)b * st + 4u);
        }
        if (sc->n_patch > 0u && sc->pflag[j - 1] != 0u) {
            pft_tbd_patch_over_(sc, i - 2, j - 2, 3u, 3u, z);
        }
    }
    return pft_kspot3_(z, 3u, tx, ty, amp);
}

pft_real_t pft_tbd_llr_exact_r16_(const pft_tbd_meas_t *m, const pft_tbd_scene_t_ *sc,
                                  const pft_tbd_cell_t *c, pft_real_t intensity)
{
    pft_real_t tx[2u * PFT_TBD_MAX_WINDOW + 1u];
    pft_real_t ty[2u * PFT_TBD_MAX_WINDOW + 1u];
    win_t w;
    exact_taps_(m, c, &w, tx, ty);
    const uint32_t nx = (uint32_t)(w.ihi - w.ilo + 1);
    const uint32_t ny = (uint32_t)(w.jhi - w.jlo + 1);
    pft_real_t *z = sc->rowbuf + (size_t)m->width + 2u; /* the window scratch */
    pft_tbd_fetch_(sc, w.ilo - 1, w.jlo - 1, nx, ny, z);
    return pft_kspot_(z, nx, tx, nx, ty, ny, pft_mul(intensity, m->kc));
}

/* The tap table of pitch d: row n holds g((k - 1 - f_n) d), k = 0..2, and their sum of squares
 * at f_n = -1/2 + n / PFT_TBD_TAP_STEPS, then the differences to row n + 1. */
static void taps_fill_(const pft_tbd_meas_t *m, pft_real_t d, pft_real_t (*rows)[8])
{
    pft_real_t prev[4] = {0, 0, 0, 0};
    for (uint32_t n = 0; n <= PFT_TBD_TAP_STEPS; ++n) {
        pft_real_t f = pft_sub(pft_ratio((int32_t)n, (int32_t)PFT_TBD_TAP_STEPS), PFT_C(0.5));
        pft_real_t v[4];
        v[3] = PFT_C(0.0);
        for (int32_t k = 0; k < 3; ++k) {
            pft_real_t t = pft_mul(pft_sub(pft_from_int(k - 1), f), d);
            v[k] = pft_exp(pft_neg(pft_mul(pft_sq(t), m->inv_2s2)));
            v[3] = pft_add(v[3], pft_sq(v[k]));
        }
        for (int k = 0; k < 4; ++k) {
            if (n > 0u) {
                rows[n - 1u][k + 4] = pft_sub(v[k], prev[k]);
            }
            if (n < PFT_TBD_TAP_STEPS) {
                rows[n][k] = v[k];
            }
            prev[k] = v[k];
        }
    }
}

void pft_tbd_taps_setup_(pft_tbd_tab_t *t, const pft_tbd_meas_t *m)
{
    bool ok = true;
    taps_fill_(m, m->dx, t->taps[0]);
    taps_fill_(m, m->dy, t->taps[1]);
    /* every tap pft_ktaps_ can give (lanes 0-2, each between a row's value and the next's) */
    for (uint32_t a = 0; a < 2u; ++a) {
        for (uint32_t n = 0; n < PFT_TBD_TAP_STEPS; ++n) {
            for (uint32_t k = 0; k < 3u; ++k) {
                ok = ok && pft_kr16_sum_ok_(t->taps[a][n][k], t->taps[a][n][k + 4u]);
            }
        }
    }
    t->r16_sum = ok ? 1u : 0u;
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
    pft_tbd_psf_add_(m, img, 0u, m->width, pft_tbd_x_int_(x, m->dx), pft_tbd_x_int_(y, m->dy),
                     pft_mul(intensity, m->c0), half);
}

/* ------------------------------------ frames ---------------------------------------------- */

pft_status_t pft_tbd_frame_check_(const pft_tbd_config_t *cfg, const pft_frame_t *frame)
{
    /* cfg.frame_format PFT_PIX_RES16: the manager reads the frame in place, no other format */
    uint32_t fmts = cfg->frame_format == PFT_PIX_RES16
                        ? PFT_FMT_BIT(PFT_PIX_RES16)
                        : PFT_FMT_BIT(PFT_PIX_U8) | PFT_FMT_BIT(PFT_PIX_U16) |
                              PFT_FMT_BIT(PFT_PIX_F32) | PFT_FMT_BIT(PFT_PIX_RES16);
    pft_status_t st = pft_frame_check(frame, cfg->width, cfg->height, fmts);
    if (st != PFT_OK) {
        return st;
    }
    return pft_frame_check_finite(frame);
}

/* One RES16 row (w pixels from src) as reals: res / 256, a masked pixel 0. The index is a
 * size_t: with a 32-bit one 2 c could wrap, and GCC did not vectorise the loop (14 instead of
 * about 2 instructions per pixel, callgrind, x86-64). */
static void r16_row_(const uint8_t *src, uint32_t w, pft_real_t *row)
{
    for (size_t c = 0; c < (size_t)w; ++c) {
        int16_t v;
        memcpy(&v, src + 2u * c, 2u);
        /* a masked pixel reads 0: the value times 1 or 0 (no branch, so the loop vectorises
         * in both builds) */
        const int32_t keep = v != PFT_RES16_MASKED ? (int32_t)1 : (int32_t)0;
        row[c] = pft_kres16_((int16_t)((int32_t)v * keep));
    }
}

void pft_tbd_frame_convert_(const pft_tbd_config_t *cfg, const pft_tbd_meas_t *m,
                            const pft_frame_t *frame, pft_real_t *img)
{
    const size_t stride = pft_tbd_stride_(cfg->width);
    if (frame->format == PFT_PIX_F32) {
        /* the same values as below in one pass: pft_frame_row_to_real reads an F32 pixel as
         * pft_from_f32 of it, clamped, with no gain or offset */
        const pft_real_t inv_sn = m->inv_sn;
        const uint32_t w = cfg->width;
        for (uint32_t r = 0; r < cfg->height; ++r) {
            pft_real_t *row = img + (size_t)(r + 1u) * stride + 1u;
            const uint8_t *src = pft_frame_row(frame, r);
            for (uint32_t c = 0; c < w; ++c) {
                float f;
                memcpy(&f, src + 4u * c, 4u);
                row[c] = pft_clamp(pft_mul(pft_clamp(pft_kfrom_f32_(f), PFT_C(-32767.0),
                                                     PFT_C(32767.0)),
                                           inv_sn),
                                   PFT_C(-32767.0), PFT_C(32767.0));
            }
        }
        return;
    }
    const bool unit_sn = !(m->inv_sn < PFT_C(1.0)) && !(m->inv_sn > PFT_C(1.0));
    const bool unit_px = !(cfg->pixel_gain < PFT_REAL_ONE) && !(cfg->pixel_gain > PFT_REAL_ONE) &&
                         !(cfg->pixel_offset < PFT_C(0.0)) && !(cfg->pixel_offset > PFT_C(0.0));
    if (frame->format == PFT_PIX_RES16 && unit_sn && unit_px) {
        /* the stage's residual as it is (gain 1, offset 0, sigma 1): pft_frame_row_to_real's
         * values (res / 256, |res / 256| < 128 needs no clamp; a masked pixel reads 0) in a
         * loop without products */
        for (uint32_t r = 0; r < cfg->height; ++r) {
            r16_row_(pft_frame_row(frame, r), cfg->width, img + (size_t)(r + 1u) * stride + 1u);
        }
        return;
    }
    for (uint32_t r = 0; r < cfg->height; ++r) {
        pft_real_t *row = img + (size_t)(r + 1u) * stride + 1u;
        pft_frame_row_to_real(frame, r, cfg->width, cfg->pixel_gain, cfg->pixel_offset, row);
        /* noise sigma 1 (a whitened input such as the stage's RES16 residual): the product is
         * the value itself in both builds and the row is clamped already */
        if (!unit_sn) {
            for (uint32_t c = 0; c < cfg->width; ++c) {
                row[c] = pft_clamp(pft_mul(row[c], m->inv_sn), PFT_C(-32767.0), PFT_C(32767.0));
            }
        }
    }
}

/* ------------------------- the RES16 frame read in place (cfg.frame_format) ---------------- */

void pft_tbd_fetch_(const pft_tbd_scene_t_ *sc, int32_t col0, int32_t row0, uint32_t nx,
                    uint32_t ny, pft_real_t *z)
{
    /* called on a RES16 scene only (sc->img NULL) */
    const int32_t w = (int32_t)sc->width;
    const int32_t h = (int32_t)sc->height;
    for (uint32_t b = 0; b < ny; ++b) {
        const int32_t row = row0 + (int32_t)b;
        pft_real_t *zr = z + (size_t)b * nx;
        if (row < 0 || row >= h) {
            for (uint32_t a = 0; a < nx; ++a) {
                zr[a] = PFT_C(0.0);
            }
            continue;
        }
        const uint8_t *src = sc->r16 + (size_t)row * sc->r16_stride;
        for (uint32_t a = 0; a < nx; ++a) {
            const int32_t col = col0 + (int32_t)a;
            zr[a] = col < 0 || col >= w ? PFT_C(0.0) : pft_tbd_r16_(src + 2u * (uint32_t)col);
        }
    }
    pft_tbd_patch_over_(sc, col0, row0, nx, ny, z);
}

void pft_tbd_patch_over_(const pft_tbd_scene_t_ *sc, int32_t col0, int32_t row0, uint32_t nx,
                         uint32_t ny, pft_real_t *z)
{
    /* the patches in their order: a later one holds the value of a pixel two of them cover */
    const int32_t c1 = col0 + (int32_t)nx - 1;
    const int32_t r1 = row0 + (int32_t)ny - 1;
    for (uint32_t k = 0; k < sc->n_patch; ++k) {
        const int32_t *pr = sc->prect + 4u * k;
        const int32_t clo = pr[0] > col0 ? pr[0] : col0;
        const int32_t chi = pr[1] < c1 ? pr[1] : c1;
        const int32_t rlo = pr[2] > row0 ? pr[2] : row0;
        const int32_t rhi = pr[3] < r1 ? pr[3] : r1;
        const uint32_t pw = (uint32_t)(pr[1] - pr[0] + 1);
        const pft_real_t *pv = sc->pval + (size_t)k * PFT_TBD_PSF_SAVE_REALS_;
        for (int32_t row = rlo; row <= rhi; ++row) {
            for (int32_t col = clo; col <= chi; ++col) {
                z[(size_t)(row - row0) * nx + (size_t)(col - col0)] =
                    pv[(size_t)(row - pr[2]) * pw + (size_t)(col - pr[0])];
            }
        }
    }
}

bool pft_tbd_patch_in_win_(const pft_tbd_scene_t_ *sc, int32_t col0, int32_t row0)
{
    /* patch_over_'s rectangles: an empty one (col_hi < col_lo) may count as covering, which
     * only sends the window to the general form (the same values) */
    for (uint32_t k = 0; k < sc->n_patch; ++k) {
        const int32_t *pr = sc->prect + 4u * k;
        if (!(pr[1] < col0 || pr[0] > col0 + 2 || pr[3] < row0 || pr[2] > row0 + 2)) {
            return true;
        }
    }
    return false;
}

const pft_real_t *pft_tbd_row_(const pft_tbd_scene_t_ *sc, uint32_t r)
{
    const uint32_t w = sc->width;
    if (sc->img != NULL) {
        return sc->img + (size_t)(r + 1u) * pft_tbd_stride_(w);
    }
    pft_real_t *row = sc->rowbuf;
    const uint8_t *src = sc->r16 + (size_t)r * sc->r16_stride;
    r16_row_(src, w, row + 1);
    row[0] = PFT_C(0.0);
    row[w + 1u] = PFT_C(0.0);
    if (sc->n_patch > 0u && sc->pflag[r] != 0u) {
        for (uint32_t k = 0; k < sc->n_patch; ++k) {
            const int32_t *pr = sc->prect + 4u * k;
            if ((int32_t)r < pr[2] || (int32_t)r > pr[3]) {
                continue;
            }
            const uint32_t pw = (uint32_t)(pr[1] - pr[0] + 1);
            const pft_real_t *pv =
                sc->pval + (size_t)k * PFT_TBD_PSF_SAVE_REALS_ + (size_t)((int32_t)r - pr[2]) * pw;
            for (int32_t col = pr[0]; col <= pr[1]; ++col) {
                row[col + 1] = pv[col - pr[0]];
            }
        }
    }
    return row;
}

void pft_tbd_psf_patch_(const pft_tbd_meas_t *m, const pft_tbd_scene_t_ *sc, int32_t *rect,
                        pft_real_t *val, pft_real_t x, pft_real_t y, pft_real_t coef,
                        uint8_t half)
{
    int32_t p = half > PFT_TBD_MAX_PSF_HALF ? (int32_t)PFT_TBD_MAX_PSF_HALF : (int32_t)half;
    win_t w;
    if (!window_(m, x, y, p, &w)) {
        rect[0] = 0;
        rect[1] = -1;
        rect[2] = 0;
        rect[3] = -1;
        return;
    }
    rect[0] = w.ilo - 1;
    rect[1] = w.ihi - 1;
    rect[2] = w.jlo - 1;
    rect[3] = w.jhi - 1;
    const uint32_t nx = (uint32_t)(w.ihi - w.ilo + 1);
    const uint32_t ny = (uint32_t)(w.jhi - w.jlo + 1);
    pft_tbd_fetch_(sc, rect[0], rect[2], nx, ny, val);
    /* pft_tbd_psf_add_'s arithmetic on these values */
    pft_real_t ax[2u * PFT_TBD_MAX_PSF_HALF + 1u];
    psf_columns_(m, &w, x, coef, ax);
    for (int32_t j = w.jlo; j <= w.jhi; ++j) {
        pft_real_t g = psf_row_(m, j, y);
        pft_real_t *row = val + (size_t)(j - w.jlo) * nx;
        for (int32_t i = w.ilo; i <= w.ihi; ++i) {
            row[i - w.ilo] = pft_add(row[i - w.ilo], pft_mul(ax[i - w.ilo], g));
        }
    }
}

void pft_tbd_mask_add_(const pft_tbd_config_t *cfg, uint32_t *mask, const pft_tbd_region_t *r)
{
    int32_t clo = r->col_lo < 0 ? 0 : r->col_lo;
    int32_t chi = r->col_hi > (int32_t)cfg->width - 1 ? (int32_t)cfg->width - 1 : r->col_hi;
    int32_t rlo = r->row_lo < 0 ? 0 : r->row_lo;
    int32_t rhi = r->row_hi > (int32_t)cfg->height - 1 ? (int32_t)cfg->height - 1 : r->row_hi;
    const uint32_t words = pft_tbd_mask_words_(cfg->width);
    for (int32_t row = rlo; row <= rhi; ++row) {
        uint32_t *mrow = mask + (size_t)row * words;
        for (int32_t col = clo; col <= chi; ++col) {
            mrow[(uint32_t)col >> 5u] |= 1u << ((uint32_t)col & 31u);
        }
    }
}

/* Set bits of a word (the usual parallel count). */
static uint32_t popcount32_(uint32_t v)
{
    uint32_t x = v - ((v >> 1u) & 0x55555555u);
    x = (x & 0x33333333u) + ((x >> 2u) & 0x33333333u);
    x = (x + (x >> 4u)) & 0x0F0F0F0Fu;
    return (x * 0x01010101u) >> 24u;
}

uint32_t pft_tbd_mask_row_free_(const uint32_t *mask, uint32_t width, uint32_t row)
{
    const uint32_t words = pft_tbd_mask_words_(width);
    const uint32_t *mrow = mask + (size_t)row * words;
    uint32_t set = 0u;
    for (uint32_t k = 0; k < words; ++k) {
        set += popcount32_(mrow[k]); /* the bits past the width are never set */
    }
    return width - set;
}

/* The pixel source of a scene: img, or (img NULL) the RES16 source already in sc. */
static void scene_source_(pft_tbd_scene_t_ *sc, const pft_real_t *img, uint32_t w, uint32_t h)
{
    if (img != NULL) {
        sc->img = img;
        sc->r16 = NULL;
        sc->r16_stride = 0u;
        sc->prect = NULL;
        sc->pval = NULL;
        sc->pflag = NULL;
        sc->rowbuf = NULL;
        sc->n_patch = 0u;
    }
    sc->width = w;
    sc->height = h;
}

void pft_tbd_scene_build_(const pft_tbd_config_t *cfg, pft_real_t gamma_w, const pft_real_t *img,
                          const uint32_t *mask, uint32_t *cand, pft_tbd_scene_t_ *sc)
{
    const uint32_t w = cfg->width;
    const uint32_t words = pft_tbd_mask_words_(w);
    uint32_t npix = w * cfg->height;
    uint32_t nb = 0;
    uint32_t na = 0;
    scene_source_(sc, img, w, cfg->height);
    for (uint32_t r = 0, k = 0; r < cfg->height; ++r) {
        const pft_real_t *row = pft_tbd_row_(sc, r) + 1;
        for (uint32_t c = 0; c < w; ++c, ++k) {
            if (mask != NULL && pft_tbd_masked_(mask, words, c, r)) {
                continue;
            }
            ++na;
            if (row[c] > gamma_w) {
                cand[nb++] = k;
            }
        }
    }
    sc->mask = mask;
    sc->cand = cand;
    sc->row_pre = NULL;
    sc->width = w;
    sc->height = cfg->height;
    sc->n_allowed = na;
    sc->cand_is_b = nb > 0u;
    if (nb == 0u && na > 0u) {
        /* No pixel above gamma: propose uniformly over the allowed pixels, correction 0. */
        for (uint32_t k = 0; k < npix; ++k) {
            if (mask == NULL || !pft_tbd_masked_(mask, words, k % w, k / w)) {
                cand[nb++] = k;
            }
        }
    }
    sc->n_cand = nb;
}

/* ------------------------------- birth peaks (docs/algorithms.md 2.11) --------------------- */

/* Heap order of the kept peaks: a is weaker than b (smaller value; on a tie, the later pixel). */
static bool weaker_(pft_real_t va, uint32_t ka, pft_real_t vb, uint32_t kb)
{
    return va < vb || (va == vb && ka > kb);
}

static void heap_swap_(uint32_t *key, pft_real_t *val, uint32_t a, uint32_t b)
{
    const uint32_t k = key[a];
    const pft_real_t v = val[a];
    key[a] = key[b];
    val[a] = val[b];
    key[b] = k;
    val[b] = v;
}

/* Min-heap of n entries, the weakest at 0: moves entry i down (i at least doubles each step). */
static void sift_down_(uint32_t *key, pft_real_t *val, uint32_t n, uint32_t i)
{
    uint32_t a = i;
    while (2u * a + 1u < n) {
        uint32_t c = 2u * a + 1u;
        if (c + 1u < n && weaker_(val[c + 1u], key[c + 1u], val[c], key[c])) {
            ++c;
        }
        if (!weaker_(val[c], key[c], val[a], key[a])) {
            break;
        }
        heap_swap_(key, val, a, c);
        a = c;
    }
}

/* Moves entry i up (i at least halves each step). */
static void sift_up_(uint32_t *key, pft_real_t *val, uint32_t i)
{
    uint32_t a = i;
    while (a > 0u) {
        const uint32_t p = (a - 1u) / 2u;
        if (!weaker_(val[a], key[a], val[p], key[p])) {
            break;
        }
        heap_swap_(key, val, a, p);
        a = p;
    }
}

/* Pixels beyond this many noise sigmas count as this many in the peak scan, so that the q16
 * sums of the 3 x 3 correlation (at most 9 such values with taps <= 1) stay in range. */
#define PEAK_CLIP_ PFT_C(2048.0)

/* hs[c] = t1 z(c) + t0 (z(c - 1) + z(c + 1)) along a row of the bordered whitened image
 * (pft_tbd_row_): row[0] and row[w + 1] are the zero border, so every column is the same
 * expression (one loop without a carried value, which compilers vectorise). */
static inline void peak_hrow_(const pft_real_t *row, uint32_t w, pft_real_t t0, pft_real_t t1,
                       pft_real_t *hs)
{
    const pft_real_t lo = pft_neg(PEAK_CLIP_);
    for (uint32_t c = 0; c < w; ++c) {
        /* row[c + 1] is pixel c; row[0] and row[w + 1] the zero border */
        const pft_real_t zl = pft_clamp(row[c], lo, PEAK_CLIP_);
        const pft_real_t zc = pft_clamp(row[c + 1u], lo, PEAK_CLIP_);
        const pft_real_t zr = pft_clamp(row[c + 2u], lo, PEAK_CLIP_);
        /* |z| <= 2^11 and taps <= 1: every sum stays below 2^13 (no saturation), so the
         * unsaturated helpers give pft_add / pft_mul's bits */
        hs[c] = pft_kaddr_(pft_kmula_(t1, zc), pft_kmula_(t0, pft_kaddr_(zl, zr)));
    }
}

/* Pixel c of a RES16 row as the integer the converted frame holds times 256: a masked pixel 0. */
static inline int16_t r16_int_(const uint8_t *src, size_t c)
{
    int16_t v;
    memcpy(&v, src + 2u * c, 2u);
    return v != PFT_RES16_MASKED ? v : (int16_t)0;
}

/* The inner columns of peak_hrow_r16_ (1 .. w - 2; w >= 2). one: t1 is pft_kr16_tap_ of the
 * centre tap 1 (the taps at offset 0), where pft_kmul_r16_(t1, v, 0) is pft_kres16_(v) in both
 * builds (q16: 256 v + (128 - [v < 0]) >> 8 = 256 v; float: v 2^-8 exactly), so that column's
 * products are skipped (q16: two widening multiplies per pixel; float keeps one form,
 * pft_kr16_one_pays_). The same values either way; the caller passes a constant, so each form
 * is its own loop. */
static inline void peak_hrow_r16_in_(const uint8_t *src, size_t c0, uint32_t w, pft_real_t t0,
                                     pft_real_t t1, bool one, pft_real_t *hs)
{
    for (size_t c = c0; c + 1u < (size_t)w; ++c) {
        /* a masked pixel reads 0: the value times 1 or 0 (no branch, so the loop vectorises) */
        int16_t a, b, d;
        memcpy(&a, src + 2u * (c - 1u), 2u);
        memcpy(&b, src + 2u * c, 2u);
        memcpy(&d, src + 2u * (c + 1u), 2u);
        const int16_t zl = (int16_t)((int32_t)a * (a != PFT_RES16_MASKED ? 1 : 0));
        const int16_t zc = (int16_t)((int32_t)b * (b != PFT_RES16_MASKED ? 1 : 0));
        const int16_t zr = (int16_t)((int32_t)d * (d != PFT_RES16_MASKED ? 1 : 0));
        const pft_real_t mc = one ? pft_kres16_(zc) : pft_kmul_r16_(t1, zc, 0);
        hs[c] = pft_kaddr_(mc, pft_kmul_r16_(t0, zl, zr));
    }
}

#if defined(__SSE2__)
/* The RES16 row's pixels c - 1 .., c .. and c + 1 .. (eight each) in a, b and d, a masked pixel
 * (the only PFT_RES16_MASKED, as masked's lanes) read as 0 (peak_hrow_r16_madd_'s and
 * peak_hrow_r16_f8_'s SSE2 forms). */
static inline void r16_ld3_(const uint8_t *src, size_t c, __m128i masked, __m128i *a, __m128i *b, __m128i *d)
{
    const __m128i va = _mm_loadu_si128((const __m128i *)(const void *)(src + 2u * (c - 1u)));
    const __m128i vb = _mm_loadu_si128((const __m128i *)(const void *)(src + 2u * c));
    const __m128i vd = _mm_loadu_si128((const __m128i *)(const void *)(src + 2u * (c + 1u)));
    *a = _mm_andnot_si128(_mm_cmpeq_epi16(va, masked), va);
    *b = _mm_andnot_si128(_mm_cmpeq_epi16(vb, masked), vb);
    *d = _mm_andnot_si128(_mm_cmpeq_epi16(vd, masked), vd);
}
#endif

#if defined(PFT_TBD_HROW_MADD_) && defined(__SSE2__)
/* peak_hrow_r16_in_'s columns 1 .. with the centre tap 1 (one), eight at a time while a whole
 * step lies inside 1 .. w - 2; returns the first column not done. Per pixel: pft_kres16_(zc) =
 * 256 zc (zc in a 32-bit lane's high half, shifted down by 8), and pft_kmul_r16_(t0, zl, zr) =
 * th (zl + zr) + (tl (zl + zr) + 128 - [zl + zr < 0]) >> 8 (t0 = 256 th + tl) with the two
 * products of each pair (zl, zr) as one multiply-add of the pair with (th, th) and with
 * (tl, tl): th <= 256, tl <= 255 and |zl|, |zr| <= 32767 (a masked pixel, the only -32768,
 * reads 0), so each sum is exact in 32 bits. The sign of tl (zl + zr) is that of zl + zr when
 * tl > 0; when tl = 0 the rounded term is 0 with either sign. */
static size_t peak_hrow_r16_madd_(const uint8_t *src, uint32_t w, pft_real_t t0, pft_real_t *hs)
{
    const uint32_t tu = (uint32_t)t0; /* 0 .. 65536 (pft_kr16_tap_ok_) */
    const uint32_t th = tu >> 8;
    const uint32_t tl = tu & 255u;
    const __m128i wh = _mm_set1_epi32((int32_t)((th << 16) | th));
    const __m128i wl = _mm_set1_epi32((int32_t)((tl << 16) | tl));
    const __m128i masked = _mm_set1_epi16(PFT_RES16_MASKED);
    const __m128i half = _mm_set1_epi32(128);
    const __m128i zero = _mm_setzero_si128();
    size_t c = 1u;
    for (; c + 8u < (size_t)w; c += 8u) {
        __m128i a, b, d;
        r16_ld3_(src, c, masked, &a, &b, &d);
        const __m128i plo = _mm_unpacklo_epi16(a, d); /* (zl, zr) of pixels c .. c + 3 */
        const __m128i phi = _mm_unpackhi_epi16(a, d); /* and of c + 4 .. c + 7 */
        const __m128i llo = _mm_madd_epi16(plo, wl);
        const __m128i lhi = _mm_madd_epi16(phi, wl);
        const __m128i rlo = _mm_srai_epi32(
            _mm_add_epi32(_mm_add_epi32(llo, half), _mm_srai_epi32(llo, 31)), 8);
        const __m128i rhi = _mm_srai_epi32(
            _mm_add_epi32(_mm_add_epi32(lhi, half), _mm_srai_epi32(lhi, 31)), 8);
        const __m128i clo = _mm_srai_epi32(_mm_unpacklo_epi16(zero, b), 8); /* 256 zc */
        const __m128i chi = _mm_srai_epi32(_mm_unpackhi_epi16(zero, b), 8);
        const __m128i olo = _mm_add_epi32(_mm_add_epi32(clo, _mm_madd_epi16(plo, wh)), rlo);
        const __m128i ohi = _mm_add_epi32(_mm_add_epi32(chi, _mm_madd_epi16(phi, wh)), rhi);
        _mm_storeu_si128((__m128i *)(void *)(hs + c), olo);
        _mm_storeu_si128((__m128i *)(void *)(hs + c + 4u), ohi);
    }
    return c;
}
#elif defined(PFT_TBD_HROW_MADD_)
/* The NEON form of the above (AArch64, q16): the same values per pixel, 256 zc + th s +
 * (tl s + 128 - [s < 0]) >> 8 with s = zl + zr widened to 32 bits (|s| <= 65534, so every
 * product and sum is exact in 32 bits); the rounding as a rounding shift (+ 128, >> 8) of
 * tl s - [tl s < 0], whose sign is that of s when tl > 0 (when tl = 0 the term is 0 either
 * way). The rows are read as bytes (no alignment asked of src). */
static size_t peak_hrow_r16_madd_(const uint8_t *src, uint32_t w, pft_real_t t0, pft_real_t *hs)
{
    const uint32_t tu = (uint32_t)t0; /* 0 .. 65536 (pft_kr16_tap_ok_) */
    const int32x4_t th = vdupq_n_s32((int32_t)(tu >> 8));
    const int32x4_t tl = vdupq_n_s32((int32_t)(tu & 255u));
    const int16x8_t masked = vdupq_n_s16(PFT_RES16_MASKED);
    size_t c = 1u;
    for (; c + 8u < (size_t)w; c += 8u) {
        int16x8_t a = vreinterpretq_s16_u8(vld1q_u8(src + 2u * (c - 1u)));
        int16x8_t b = vreinterpretq_s16_u8(vld1q_u8(src + 2u * c));
        int16x8_t d = vreinterpretq_s16_u8(vld1q_u8(src + 2u * (c + 1u)));
        a = vbicq_s16(a, vreinterpretq_s16_u16(vceqq_s16(a, masked)));
        b = vbicq_s16(b, vreinterpretq_s16_u16(vceqq_s16(b, masked)));
        d = vbicq_s16(d, vreinterpretq_s16_u16(vceqq_s16(d, masked)));
        const int32x4_t slo = vaddl_s16(vget_low_s16(a), vget_low_s16(d)); /* pixels c .. c + 3 */
        const int32x4_t shi = vaddl_high_s16(a, d);                       /* c + 4 .. c + 7 */
        const int32x4_t llo = vmulq_s32(slo, tl);
        const int32x4_t lhi = vmulq_s32(shi, tl);
        const int32x4_t rlo = vrshrq_n_s32(vsraq_n_s32(llo, llo, 31), 8);
        const int32x4_t rhi = vrshrq_n_s32(vsraq_n_s32(lhi, lhi, 31), 8);
        const int32x4_t clo = vshll_n_s16(vget_low_s16(b), 8); /* 256 zc */
        const int32x4_t chi = vshll_high_n_s16(b, 8);
        vst1q_s32(hs + c, vmlaq_s32(vaddq_s32(clo, rlo), slo, th));
        vst1q_s32(hs + c + 4u, vmlaq_s32(vaddq_s32(chi, rhi), shi, th));
    }
    return c;
}
#endif

#if defined(__SSE2__) && !defined(PFT_NUMERIC_Q16)
/* float, x86-64 (SSE2): peak_hrow_r16_in_'s columns 1 .. with any centre tap (one false),
 * eight at a time while a whole step lies inside 1 .. w - 2; returns the first column not
 * done. Per pixel as the plain loop: t1 (float)zc + t0 (float)(zl + zr), a masked pixel 0;
 * the pair sum zl + zr in 32 bits by one multiply-add of the interleaved pair with (1, 1)
 * (exact), zc widened by an interleave with itself and an arithmetic shift, each integer
 * converted exactly, the products and the sum rounded as the scalar float operations (no
 * fused multiply-add on baseline x86-64). */
static size_t peak_hrow_r16_f8_(const uint8_t *src, uint32_t w, pft_real_t t0, pft_real_t t1,
                                pft_real_t *hs)
{
    const __m128 v0 = _mm_set1_ps(t0);
    const __m128 v1 = _mm_set1_ps(t1);
    const __m128i masked = _mm_set1_epi16(PFT_RES16_MASKED);
    const __m128i one = _mm_set1_epi16(1);
    size_t c = 1u;
    for (; c + 8u < (size_t)w; c += 8u) {
        __m128i a, b, d;
        r16_ld3_(src, c, masked, &a, &b, &d);
        const __m128i slo = _mm_madd_epi16(_mm_unpacklo_epi16(a, d), one); /* c .. c + 3 */
        const __m128i shi = _mm_madd_epi16(_mm_unpackhi_epi16(a, d), one); /* c + 4 .. c + 7 */
        const __m128i zlo = _mm_srai_epi32(_mm_unpacklo_epi16(b, b), 16);
        const __m128i zhi = _mm_srai_epi32(_mm_unpackhi_epi16(b, b), 16);
        _mm_storeu_ps(hs + c, _mm_add_ps(_mm_mul_ps(v1, _mm_cvtepi32_ps(zlo)),
                                         _mm_mul_ps(v0, _mm_cvtepi32_ps(slo))));
        _mm_storeu_ps(hs + c + 4u, _mm_add_ps(_mm_mul_ps(v1, _mm_cvtepi32_ps(zhi)),
                                              _mm_mul_ps(v0, _mm_cvtepi32_ps(shi))));
    }
    return c;
}
#endif

/* peak_hrow_ of a RES16 row without a patch, from the integers: z = v / 256 with |z| < 128,
 * so the clamp at PEAK_CLIP_ never acts, z(c - 1) + z(c + 1) is (v(c - 1) + v(c + 1)) / 256
 * exactly, and pft_kmul_r16_ gives pft_kmula_'s bits (kern_int.h); t0, t1 prepared by
 * pft_kr16_tap_. The same values as peak_hrow_ on pft_tbd_row_ in both builds, without the
 * row's conversion. */
static inline void peak_hrow_r16_(const uint8_t *src, uint32_t w, pft_real_t t0, pft_real_t t1,
                           pft_real_t *hs)
{
    if (w < 2u) {
        hs[0] = pft_kmul_r16_(t1, r16_int_(src, 0u), 0);
        return;
    }
    hs[0] = pft_kaddr_(pft_kmul_r16_(t1, r16_int_(src, 0u), 0),
                       pft_kmul_r16_(t0, r16_int_(src, 1u), 0));
    if (pft_kr16_one_pays_() && t1 == pft_kr16_tap_(PFT_REAL_ONE)) {
        size_t c0 = 1u;
#if defined(PFT_TBD_HROW_MADD_)
        c0 = peak_hrow_r16_madd_(src, w, t0, hs);
#endif
        peak_hrow_r16_in_(src, c0, w, t0, t1, true, hs);
    } else {
#if defined(__SSE2__) && !defined(PFT_NUMERIC_Q16)
        peak_hrow_r16_in_(src, peak_hrow_r16_f8_(src, w, t0, t1, hs), w, t0, t1, false, hs);
#else
        peak_hrow_r16_in_(src, 1u, w, t0, t1, false, hs);
#endif
    }
    hs[w - 1u] = pft_kaddr_(pft_kmul_r16_(t1, r16_int_(src, (size_t)w - 1u), 0),
                            pft_kmul_r16_(t0, r16_int_(src, (size_t)w - 2u), 0));
}

#if defined(__SSE2__) || (defined(PFT_NUMERIC_Q16) && defined(__aarch64__) && defined(__ARM_NEON))
void pft_tbd_hrow_r16_(const uint8_t *src, uint32_t w, pft_real_t t0, pft_real_t t1,
                       pft_real_t *hs)
{
    peak_hrow_r16_(src, w, t0, t1, hs);
}
#endif

#if defined(PFT_TBD_VROW_MUL_)
/* peak_vrow_'s columns with the centre tap 1, four at a time from column 0 while a whole step
 * lies inside the row; returns the first column not done. mf = mid + pft_kmul_u_(u0, z), z =
 * up + dn (0 <= u0 <= 2^16, |z| < 2^30): u0 zh + (u0 zl + 32768 - [z < 0]) >> 16 with z's
 * 32-bit lane read as its 16-bit halves zl (unsigned) and zh (z >> 16). With u0 = 2^16 uh +
 * ul16 (ul16 its lower 16 bits, us = ul16 read as signed, us = ul16 - 2^16 [ul16 >= 2^15]):
 * u0 zh = us zh + 2^16 zh ([ul16 >= 2^15] + uh) as one multiply-add of the halves with
 * (0, us) (pmaddwd) and z's upper half where that bracket is 1; u0 zl = 2^16 uh zl + ul16 zl,
 * whose rounded shift is uh zl + ph + ((pl + 32768 - [z < 0]) >> 16) (ph, pl: the halves of
 * ul16 zl, pmulhuw and pmullw with (ul16, 0); pl + 32768 - 1 >= 0), uh zl = z's lower half
 * where uh = 1 (u0 = 2^16, ul16 = 0). So r = that multiply-add + (z & msk) + ph +
 * ((pl + 32768 + (z >> 31)) >> 16), msk = 0xFFFF0000 where ul16 >= 2^15, 0xFFFFFFFF where u0 =
 * 2^16, 0 otherwise: the same integers in 32-bit lanes (|u0 zh| <= 2^30). */
static uint32_t peak_vrow_mul_(const pft_real_t *up, const pft_real_t *mid, const pft_real_t *dn,
                               uint32_t w, pft_real_t u0, pft_real_t *restrict mf)
{
    const uint32_t tu = (uint32_t)u0;
    const uint32_t ul = tu & 0xFFFFu;
    const uint32_t mk = (tu >> 16) != 0u ? 0xFFFFFFFFu : (ul >= 32768u ? 0xFFFF0000u : 0u);
    const __m128i th = _mm_set1_epi32((int32_t)(ul << 16)); /* (0, us) */
    const __m128i tl = _mm_set1_epi32((int32_t)ul);         /* (ul16, 0) */
    const __m128i msk = _mm_set1_epi32((int32_t)mk);
    const __m128i half = _mm_set1_epi32(32768);
    uint32_t c = 0u;
    for (; c + 4u <= w; c += 4u) {
        const __m128i z = _mm_add_epi32(_mm_loadu_si128((const __m128i *)(const void *)(up + c)),
                                        _mm_loadu_si128((const __m128i *)(const void *)(dn + c)));
        const __m128i hi = _mm_add_epi32(_mm_madd_epi16(z, th), _mm_and_si128(z, msk));
        const __m128i cy = _mm_srli_epi32(
            _mm_add_epi32(_mm_add_epi32(_mm_mullo_epi16(z, tl), half), _mm_srai_epi32(z, 31)), 16);
        const __m128i r = _mm_add_epi32(_mm_add_epi32(hi, _mm_mulhi_epu16(z, tl)), cy);
        _mm_storeu_si128((__m128i *)(void *)(mf + c),
                         _mm_add_epi32(_mm_loadu_si128((const __m128i *)(const void *)(mid + c)), r));
    }
    return c;
}
#endif

/* mf[c] = u1 hs(r, c) + u0 (hs(r - 1, c) + hs(r + 1, c)); a NULL row is zero (outside). mf is
 * none of the three rows (scene_scan_rows_: ss->mf and ss->hs are apart). */
static inline void peak_vrow_(const pft_real_t *up, const pft_real_t *mid, const pft_real_t *dn,
                       uint32_t w, pft_real_t u0, pft_real_t u1, pft_real_t *restrict mf)
{
    if (up != NULL && dn != NULL && pft_kmul_u_ok_(u0) && pft_kmul_u_ok_(u1)) {
        /* every row but the first and the last: one plain loop; pft_kmul_u_ is pft_kmula_
         * for taps in [0, 1] and |values| < 2^14 (q16: in 32-bit arithmetic) */
        /* the row in two halves, a pixel of each per iteration: the two are independent, so
         * the vectorised loop has two chains to overlap on an in-order core (one chain of
         * dependent SIMD results per iteration otherwise); each pixel's value is the same */
        const uint32_t h = w / 2u;
        if (u1 == PFT_REAL_ONE) {
            /* the centre tap at offset 0 is exp(0) = 1: pft_kmula_(1, v) is v in both builds */
#if defined(PFT_TBD_VROW_MUL_)
            for (uint32_t c = peak_vrow_mul_(up, mid, dn, w, u0, mf); c < w; ++c) {
                mf[c] = pft_kaddr_(mid[c], pft_kmul_u_(u0, pft_kaddr_(up[c], dn[c])));
            }
#else
            for (uint32_t c = 0; c < h; ++c) {
                const uint32_t d = c + h;
                mf[c] = pft_kaddr_(mid[c], pft_kmul_u_(u0, pft_kaddr_(up[c], dn[c])));
                mf[d] = pft_kaddr_(mid[d], pft_kmul_u_(u0, pft_kaddr_(up[d], dn[d])));
            }
            for (uint32_t c = 2u * h; c < w; ++c) {
                mf[c] = pft_kaddr_(mid[c], pft_kmul_u_(u0, pft_kaddr_(up[c], dn[c])));
            }
#endif
            return;
        }
        for (uint32_t c = 0; c < h; ++c) {
            const uint32_t d = c + h;
            mf[c] = pft_kaddr_(pft_kmul_u_(u1, mid[c]), pft_kmul_u_(u0, pft_kaddr_(up[c], dn[c])));
            mf[d] = pft_kaddr_(pft_kmul_u_(u1, mid[d]), pft_kmul_u_(u0, pft_kaddr_(up[d], dn[d])));
        }
        for (uint32_t c = 2u * h; c < w; ++c) {
            mf[c] = pft_kaddr_(pft_kmul_u_(u1, mid[c]), pft_kmul_u_(u0, pft_kaddr_(up[c], dn[c])));
        }
    } else if (up != NULL && dn != NULL) {
        for (uint32_t c = 0; c < w; ++c) {
            /* |hs| < 3 2^11 and taps <= 1: sums below 2^14 (see peak_hrow_) */
            mf[c] = pft_kaddr_(pft_kmula_(u1, mid[c]), pft_kmula_(u0, pft_kaddr_(up[c], dn[c])));
        }
    } else {
        for (uint32_t c = 0; c < w; ++c) {
            const pft_real_t a = up != NULL ? up[c] : PFT_C(0.0);
            const pft_real_t b = dn != NULL ? dn[c] : PFT_C(0.0);
            mf[c] = pft_add(pft_mul(u1, mid[c]), pft_mul(u0, pft_add(a, b)));
        }
    }
}

#if defined(PFT_TBD_VROW_MUL_)
void pft_tbd_vrow_(const pft_real_t *up, const pft_real_t *mid, const pft_real_t *dn, uint32_t w,
                   pft_real_t u0, pft_real_t u1, pft_real_t *mf)
{
    peak_vrow_(up, mid, dn, w, u0, u1, mf);
}
#endif

/* A strict local maximum of its 3 x 3 neighbourhood (neighbours outside the image ignored); on
 * a plateau the first pixel in raster order wins: v > the neighbours before it, >= after. */
static bool peak_is_max_(const pft_real_t *up, const pft_real_t *mid, const pft_real_t *dn,
                         uint32_t w, uint32_t c)
{
    if (up != NULL && dn != NULL && c > 0u && c + 1u < w) { /* interior: the 8 neighbours */
        const pft_real_t v = mid[c];
        return v > up[c - 1u] && v > up[c] && v > up[c + 1u] && v > mid[c - 1u] &&
               v >= mid[c + 1u] && v >= dn[c - 1u] && v >= dn[c] && v >= dn[c + 1u];
    }
    const uint32_t lo = c > 0u ? c - 1u : 0u;
    const uint32_t hi = c + 1u < w ? c + 1u : c;
    const pft_real_t v = mid[c];
    bool ok = true;
    for (uint32_t k = lo; k <= hi; ++k) {
        ok = ok && (up == NULL || v > up[k]) && (dn == NULL || v >= dn[k]);
    }
    ok = ok && (c == lo || v > mid[lo]) && (c == hi || v >= mid[hi]);
    return ok;
}

/* What the scan of one row needs. With a tile quota (quota > 0) cnt[c] counts the kept peaks
 * of tile column c of the current tile row (tiles of tile x tile pixels, ntx per tile row,
 * tile row trow): the scan is in raster order, so a new peak always falls in the current tile
 * row, and the counts of the tile rows above are never read again. row_pre[q + 1] gets the
 * allowed pixels of rows 0 .. q. */
typedef struct {
    const uint32_t *mask;
    uint32_t *key;
    pft_real_t *val;
    uint32_t *cnt;
    uint32_t *row_pre;
    pft_real_t thr;
    uint32_t w, k_max, n, na, tile, ntx, quota, trow;
} peak_scan_t;

/* The tile of pixel k (quota on). */
static uint32_t peak_tile_of_(const peak_scan_t *ps, uint32_t k)
{
    return ((k / ps->w) / ps->tile) * ps->ntx + (k % ps->w) / ps->tile;
}

/* Tile quota (cfg.peak_quota): pixel k (value v) of tile tk, which holds quota kept peaks
 * already, replaces the weakest of them if it is stronger (the heap's weakest only grows). */
static void peak_keep_full_tile_(peak_scan_t *ps, uint32_t tk, uint32_t k, pft_real_t v)
{
    uint32_t iw = ps->n;
    for (uint32_t i = 0; i < ps->n; ++i) {
        if (peak_tile_of_(ps, ps->key[i]) == tk &&
            (iw == ps->n || weaker_(ps->val[i], ps->key[i], ps->val[iw], ps->key[iw]))) {
            iw = i;
        }
    }
    if (iw < ps->n && weaker_(ps->val[iw], ps->key[iw], v, k)) {
        ps->key[iw] = k;
        ps->val[iw] = v;
        sift_down_(ps->key, ps->val, ps->n, iw);
    }
}

/* Pixel c of row q (value v, above the threshold, a local maximum) into the heap of the K
 * strongest (with a tile quota: of the K strongest with at most quota per tile). */
static inline void peak_keep_(peak_scan_t *ps, uint32_t k, pft_real_t v)
{
    const bool full = ps->n >= ps->k_max;
    if (full && !weaker_(ps->val[0], ps->key[0], v, k)) {
        return; /* weaker than the K kept: not a candidate */
    }
    if (ps->quota > 0u) {
        const uint32_t tk = peak_tile_of_(ps, k);
        const uint32_t tc = (k % ps->w) / ps->tile;
        if (ps->cnt[tc] >= ps->quota) {
            peak_keep_full_tile_(ps, tk, k, v);
            return;
        }
        ++ps->cnt[tc];
        if (full && (ps->key[0] / ps->w) / ps->tile == ps->trow) {
            --ps->cnt[(ps->key[0] % ps->w) / ps->tile]; /* the evicted peak's tile, this tile row */
        }
    }
    if (!full) {
        ps->key[ps->n] = k;
        ps->val[ps->n] = v;
        sift_up_(ps->key, ps->val, ps->n);
        ++ps->n;
    } else {
        ps->key[0] = k;
        ps->val[0] = v;
        sift_down_(ps->key, ps->val, ps->n, 0u);
    }
}

/* The scan's threshold: thr, and once the heap is full the weakest kept value when larger. */
static pft_real_t peak_te_(const peak_scan_t *ps)
{
    return ps->n >= ps->k_max ? pft_max(ps->thr, ps->val[0]) : ps->thr;
}

/* Columns per block of the scan's skip test (32: 10.22 M per 384 x 288 frame float, 16: 10.47 M,
 * 64: 10.29 M; callgrind ir.json). */
#define PEAK_BLOCK_ 32u

/* The peaks of row q (mf rows up, mid, dn) into the heap; counts the allowed pixels. The
 * threshold comes first (most pixels fail it), the mask and the 3 x 3 test after; the allowed
 * pixels are counted in a loop of their own. */
static void peak_scan_row_(peak_scan_t *ps, uint32_t q, const pft_real_t *up,
                           const pft_real_t *mid, const pft_real_t *dn)
{
    const uint32_t *mrow =
        ps->mask != NULL ? ps->mask + (size_t)q * pft_tbd_mask_words_(ps->w) : NULL;
    ps->na += mrow == NULL ? ps->w : pft_tbd_mask_row_free_(ps->mask, ps->w, q);
    ps->row_pre[q + 1u] = ps->na;
    if (ps->quota > 0u && q % ps->tile == 0u) {
        /* a new tile row: none of its tiles holds a kept peak yet */
        ps->trow = q / ps->tile;
        for (uint32_t t = 0; t < ps->ntx; ++t) {
            ps->cnt[t] = 0u;
        }
    }
    /* Once the heap holds K peaks a pixel can only enter it when stronger than the weakest
     * kept one, val[0] (peak_keep_'s first test; key[0] is an earlier pixel, so "stronger" is
     * v > val[0]): the threshold te = max(thr, val[0]) comes first, the same pixels pass all
     * the (side-effect free) tests. Blocks of PEAK_BLOCK_ columns with no value above te are
     * skipped after one branch-free pass (te only grows, so no pixel of a skipped block could
     * have passed later in the row). */
    pft_real_t te = peak_te_(ps);
    uint32_t c = 0u;
    while (c < ps->w) {
        const uint32_t end = c + PEAK_BLOCK_ <= ps->w ? c + PEAK_BLOCK_ : ps->w;
        if (end - c == PEAK_BLOCK_) {
            uint32_t any = 0u;
            for (uint32_t k = 0; k < PEAK_BLOCK_; ++k) {
                any |= mid[c + k] > te ? 1u : 0u;
            }
            if (any == 0u) {
                c = end;
                continue;
            }
        }
        for (; c < end; ++c) {
            const pft_real_t v = mid[c];
            if (!(v > te) || (mrow != NULL && pft_tbd_masked_(mrow, 0u, c, 0u)) ||
                !peak_is_max_(up, mid, dn, ps->w, c)) {
                continue;
            }
            peak_keep_(ps, q * ps->w + c, v);
            te = peak_te_(ps);
        }
    }
}

/* Largest stored sum of the integration (1/64 noise sigmas): S << 2 fits 16 bits. */
#define INTEG_MAX_ 16383

/* The largest last-frame sum of the 3 x 3 bins around column pc = bc - sx: vm[pc .. pc + 2]
 * (vm padded by one zero column on each side), 0 outside. */
static inline uint32_t integ_mx_(const uint32_t *vm, int32_t pc, int32_t bw)
{
    uint32_t mx = 0u;
    if (pc >= -1 && pc <= bw) {
        const uint32_t a = pc >= 0 ? vm[pc] : 0u;
        const uint32_t b = vm[pc + 1];
        const uint32_t d = pc + 2 <= bw + 1 ? vm[pc + 2] : 0u;
        mx = a > b ? a : b;
        mx = d > mx ? d : mx;
    }
    return mx;
}

/* A bin's stored sum: its largest pixel best in 1/64 sigmas (rounded; pft_kround64_ is
 * pft_round_int(pft_mul_i(pft_clamp(best, -257, 257), 64))) plus a_q / 256 times mx, floored
 * at 0 and capped at INTEG_MAX_ (-257 .. 257: INTEG_MAX_ / 64 + 1 either way). */
static inline uint32_t integ_sq_(pft_real_t best, uint32_t mx, uint32_t a_q)
{
    int32_t sq = pft_kround64_(best);
    sq += (int32_t)((a_q * mx + 128u) >> 8);
    return (uint32_t)(sq < 0 ? 0 : (sq > INTEG_MAX_ ? INTEG_MAX_ : sq));
}

#if defined(PFT_TBD_INTEG_FAST8_) && defined(__SSE2__)
/* Four bins' largest pixel of x0 .. x3 (ties to the earlier) as pft_kround64_ of it, or a
 * value beyond +-16448 of the same sign where pft_kround64_ gives +-16448 (the caller's clamp
 * of the sum to 0 .. INTEG_MAX_ then gives the same bin); g[k] the lanes where x(k + 1) was
 * taken (the index's masks). q16: the compares and selections in 32-bit lanes; the rounding
 * floor((a + 512) / 1024) = (a >> 10) + bit 9 of a, pft_kround64_'s (64 a + 2^15) >> 16 for
 * the clamped a (the clamp moves a only beyond it, where the result keeps its side). */
#if defined(PFT_NUMERIC_Q16)
static inline __m128i integ_pick_(__m128i x, __m128i b, __m128i *g)
{
    *g = _mm_cmpgt_epi32(x, b);
    return _mm_or_si128(_mm_and_si128(*g, x), _mm_andnot_si128(*g, b));
}

static inline __m128i integ_best4_(__m128i x0, __m128i x1, __m128i x2, __m128i x3, __m128i *g)
{
    __m128i b = integ_pick_(x1, x0, &g[0]);
    b = integ_pick_(x2, b, &g[1]);
    b = integ_pick_(x3, b, &g[2]);
    return _mm_add_epi32(_mm_srai_epi32(b, 10),
                         _mm_and_si128(_mm_srai_epi32(b, 9), _mm_set1_epi32(1)));
}

static inline __m128i integ_ld_(const pft_real_t *p)
{
    return _mm_loadu_si128((const __m128i *)(const void *)p);
}

/* The even (sel 0x88) or odd (0xDD) elements of a then b. */
static inline __m128i integ_half_(__m128i a, __m128i b, bool odd)
{
    const __m128 fa = _mm_castsi128_ps(a);
    const __m128 fb = _mm_castsi128_ps(b);
    return _mm_castps_si128(odd ? _mm_shuffle_ps(fa, fb, 0xDD) : _mm_shuffle_ps(fa, fb, 0x88));
}
typedef __m128i integ_v_;
#else
/* float: maxps(x, b) is x > b ? x : b (b on a tie or a NaN), the selection of integ_bin_; then
 * pft_kround64_: x = 64 best, a NaN 0, clamped to +-16448 (min/max, no NaN left), and
 * floor(x + 1/2) (exact: |x| < 2^22) as the truncation less 1 where it exceeds x + 1/2. */
static inline __m128i integ_best4_(__m128 x0, __m128 x1, __m128 x2, __m128 x3, __m128i *g)
{
    g[0] = _mm_castps_si128(_mm_cmpgt_ps(x1, x0));
    __m128 b = _mm_max_ps(x1, x0);
    g[1] = _mm_castps_si128(_mm_cmpgt_ps(x2, b));
    b = _mm_max_ps(x2, b);
    g[2] = _mm_castps_si128(_mm_cmpgt_ps(x3, b));
    b = _mm_max_ps(x3, b);
    const __m128 x = _mm_mul_ps(b, _mm_set1_ps(64.0f));
    const __m128 xn = _mm_and_ps(x, _mm_cmpeq_ps(x, x));
    const __m128 xc = _mm_min_ps(_mm_max_ps(xn, _mm_set1_ps(-16448.0f)), _mm_set1_ps(16448.0f));
    const __m128 y = _mm_add_ps(xc, _mm_set1_ps(0.5f));
    const __m128i t = _mm_cvttps_epi32(y);
    return _mm_add_epi32(t, _mm_castps_si128(_mm_cmplt_ps(y, _mm_cvtepi32_ps(t))));
}

static inline __m128 integ_ld_(const pft_real_t *p) { return _mm_loadu_ps(p); }

static inline __m128 integ_half_(__m128 a, __m128 b, bool odd)
{
    return odd ? _mm_shuffle_ps(a, b, 0xDD) : _mm_shuffle_ps(a, b, 0x88);
}
typedef __m128 integ_v_;
#endif

/* integ_row_'s inner bins bc = b0 .. eight at a time while bc + 8 <= b1 (r1 not NULL, vm[bc -
 * sx .. bc - sx + 2] inside); returns the first bin not done. Per bin as the plain loop: the
 * largest pixel and its index (ties to the earlier), m = pft_kround64_ of it (integ_best4_),
 * mx the largest of the three vm words (< 2^14), sq = m + (a_q mx + 128) >> 8 clamped to 0 ..
 * INTEG_MAX_, the word sq << 2 | idx. In 16-bit lanes after m: m packed with saturation (a
 * value beyond +-16448 stays beyond it), (a_q mx + 128) >> 8 (a_q <= 256) as
 * (floor(a_q mx / 128) + 1) >> 1, below 2^14; m plus it with
 * saturation then clamped: the same as in 32 bits, since beyond +-16448 the sum is below 0 or
 * above INTEG_MAX_ either way. */
static int32_t integ_fast8_(const pft_real_t *r0, const pft_real_t *r1, const uint32_t *vm,
                            int32_t sx, int32_t b0, int32_t b1, uint32_t a_q, uint16_t *out)
{
    const __m128i aq0 = _mm_shufflelo_epi16(_mm_cvtsi32_si128((int32_t)(a_q << 7)), 0);
    const __m128i aq = _mm_unpacklo_epi64(aq0, aq0); /* 128 a_q in every 16-bit lane */
    const __m128i zero = _mm_setzero_si128();
    const __m128i top = _mm_set1_epi16(INTEG_MAX_);
    const __m128i one = _mm_set1_epi16(1);
    const __m128i two = _mm_set1_epi16(2);
    const __m128i three = _mm_set1_epi16(3);
    int32_t bc = b0;
    for (; bc + 8 <= b1; bc += 8) {
        const pft_real_t *p0 = r0 + 2 * bc;
        const pft_real_t *p1 = r1 + 2 * bc;
        const integ_v_ a0 = integ_ld_(p0);
        const integ_v_ a1 = integ_ld_(p0 + 4);
        const integ_v_ a2 = integ_ld_(p0 + 8);
        const integ_v_ a3 = integ_ld_(p0 + 12);
        const integ_v_ c0 = integ_ld_(p1);
        const integ_v_ c1 = integ_ld_(p1 + 4);
        const integ_v_ c2 = integ_ld_(p1 + 8);
        const integ_v_ c3 = integ_ld_(p1 + 12);
        __m128i glo[3];
        __m128i ghi[3];
        const __m128i mlo = integ_best4_(integ_half_(a0, a1, false), integ_half_(a0, a1, true),
                                         integ_half_(c0, c1, false), integ_half_(c0, c1, true),
                                         glo);
        const __m128i mhi = integ_best4_(integ_half_(a2, a3, false), integ_half_(a2, a3, true),
                                         integ_half_(c2, c3, false), integ_half_(c2, c3, true),
                                         ghi);
        /* the index: 1, then 2, then 3 where that pixel was taken (masks 0 / -1 pack exactly) */
        const __m128i g1 = _mm_packs_epi32(glo[0], ghi[0]);
        const __m128i g2 = _mm_packs_epi32(glo[1], ghi[1]);
        const __m128i g3 = _mm_packs_epi32(glo[2], ghi[2]);
        /* (the last pixel taken has the largest index of those taken: their largest) */
        const __m128i idx = _mm_max_epi16(
            _mm_max_epi16(_mm_and_si128(g1, one), _mm_and_si128(g2, two)), _mm_and_si128(g3, three));
        /* mx: the three vm words (< 2^14, packed exactly) */
        const uint32_t *v = vm + (bc - sx);
        const __m128i v0 = _mm_packs_epi32(_mm_loadu_si128((const __m128i *)(const void *)v),
                                           _mm_loadu_si128((const __m128i *)(const void *)(v + 4)));
        const __m128i v1 = _mm_packs_epi32(_mm_loadu_si128((const __m128i *)(const void *)(v + 1)),
                                           _mm_loadu_si128((const __m128i *)(const void *)(v + 5)));
        const __m128i v2 = _mm_packs_epi32(_mm_loadu_si128((const __m128i *)(const void *)(v + 2)),
                                           _mm_loadu_si128((const __m128i *)(const void *)(v + 6)));
        const __m128i mx = _mm_max_epi16(_mm_max_epi16(v0, v1), v2);
        /* (a_q mx + 128) >> 8 = (floor(a_q mx / 128) + 1) >> 1: the high half of 4 mx (below
         * 2^16) times 128 a_q (at most 2^15), then the rounding average with 0 */
        const __m128i add = _mm_avg_epu16(_mm_mulhi_epu16(_mm_slli_epi16(mx, 2), aq), zero);
        __m128i sq = _mm_adds_epi16(_mm_packs_epi32(mlo, mhi), add);
        sq = _mm_min_epi16(_mm_max_epi16(sq, zero), top);
        _mm_storeu_si128((__m128i *)(void *)(out + bc), _mm_or_si128(_mm_slli_epi16(sq, 2), idx));
    }
    return bc;
}
#elif defined(PFT_TBD_INTEG_FAST8_)
/* The NEON form (AArch64): four bins' largest pixel of x0 .. x3 (ties to the earlier; g[k] the
 * lanes where x(k + 1) was taken) as m, which is pft_kround64_ of it where that lies inside
 * +-16448 and beyond +-16448 on the same side where pft_kround64_ gives +-16448: with a_q <= 256
 * the bin's addend (a_q mx + 128) >> 8 is at most 16383 (mx < 2^14), so the caller's clamp of
 * the sum to 0 .. INTEG_MAX_ gives the same bin either way. q16: m = (a + 512) >> 10 (a
 * rounding shift, no overflow), pft_kround64_'s (64 a + 2^15) >> 16 for the clamped a. */
#if defined(PFT_NUMERIC_Q16)
typedef int32x4_t integ_v_;
typedef int32x4x2_t integ_v2_;
static inline integ_v2_ integ_ld2_(const pft_real_t *p) { return vld2q_s32(p); }

static inline int32x4_t integ_best4_(int32x4_t x0, int32x4_t x1, int32x4_t x2, int32x4_t x3,
                                     uint32x4_t *g)
{
    g[0] = vcgtq_s32(x1, x0);
    int32x4_t b = vmaxq_s32(x1, x0);
    g[1] = vcgtq_s32(x2, b);
    b = vmaxq_s32(x2, b);
    g[2] = vcgtq_s32(x3, b);
    b = vmaxq_s32(x3, b);
    return vrshrq_n_s32(b, 10);
}
#else
typedef float32x4_t integ_v_;
typedef float32x4x2_t integ_v2_;
static inline integ_v2_ integ_ld2_(const pft_real_t *p) { return vld2q_f32(p); }

/* float: the selection x > b ? x : b by the compare's mask (b on a tie or a NaN, the bits
 * kept), then m = floor(64 b + 1/2) by a conversion toward minus infinity (fcvtms): 64 b is
 * exact (an infinity on overflow), and so is 64 b + 1/2 for |64 b| <= 16448, where this is
 * pft_round_int's value; beyond, on the side of 64 b, it stays beyond +-16448 (saturated at the
 * 32-bit range); a NaN converts to 0, pft_kround64_'s 0. */
static inline int32x4_t integ_best4_(float32x4_t x0, float32x4_t x1, float32x4_t x2,
                                     float32x4_t x3, uint32x4_t *g)
{
    g[0] = vcgtq_f32(x1, x0);
    float32x4_t b = vbslq_f32(g[0], x1, x0);
    g[1] = vcgtq_f32(x2, b);
    b = vbslq_f32(g[1], x2, b);
    g[2] = vcgtq_f32(x3, b);
    b = vbslq_f32(g[2], x3, b);
    return vcvtmq_s32_f32(vaddq_f32(vmulq_f32(b, vdupq_n_f32(64.0f)), vdupq_n_f32(0.5f)));
}
#endif

/* integ_row_'s inner bins bc = b0 .. eight at a time while bc + 8 <= b1 (r1 not NULL, vm[bc -
 * sx .. bc - sx + 2] inside, a_q <= 256); returns the first bin not done. The pixels read
 * deinterleaved (val[0] the bins' left pixels, val[1] their right ones), m per bin by
 * integ_best4_, mx the largest of the three vm words in 32-bit lanes, (a_q mx + 128) >> 8 by a
 * rounding narrowing shift (below 2^14); m narrowed with saturation (beyond +-16448 it stays
 * beyond), the sum with saturation, clamped to 0 .. INTEG_MAX_, and the word sq << 2 | idx by
 * a shift and insert. */
static int32_t integ_fast8_(const pft_real_t *r0, const pft_real_t *r1, const uint32_t *vm,
                            int32_t sx, int32_t b0, int32_t b1, uint32_t a_q, uint16_t *out)
{
    const uint32x4_t aq = vdupq_n_u32(a_q);
    const int16x8_t zero = vdupq_n_s16(0);
    const int16x8_t top = vdupq_n_s16(INTEG_MAX_);
    const uint16x8_t one = vdupq_n_u16(1u);
    const uint16x8_t two = vdupq_n_u16(2u);
    const uint16x8_t three = vdupq_n_u16(3u);
    int32_t bc = b0;
    for (; bc + 8 <= b1; bc += 8) {
        const integ_v2_ a0 = integ_ld2_(r0 + 2 * bc); /* bins bc .. bc + 3 */
        const integ_v2_ a1 = integ_ld2_(r0 + 2 * bc + 8);
        const integ_v2_ c0 = integ_ld2_(r1 + 2 * bc);
        const integ_v2_ c1 = integ_ld2_(r1 + 2 * bc + 8);
        uint32x4_t glo[3];
        uint32x4_t ghi[3];
        const int32x4_t mlo = integ_best4_(a0.val[0], a0.val[1], c0.val[0], c0.val[1], glo);
        const int32x4_t mhi = integ_best4_(a1.val[0], a1.val[1], c1.val[0], c1.val[1], ghi);
        /* the index: 1, then 2, then 3 where that pixel was taken (the masks' low halves) */
        const uint16x8_t g1 = vuzp1q_u16(vreinterpretq_u16_u32(glo[0]), vreinterpretq_u16_u32(ghi[0]));
        const uint16x8_t g2 = vuzp1q_u16(vreinterpretq_u16_u32(glo[1]), vreinterpretq_u16_u32(ghi[1]));
        const uint16x8_t g3 = vuzp1q_u16(vreinterpretq_u16_u32(glo[2]), vreinterpretq_u16_u32(ghi[2]));
        uint16x8_t idx = vandq_u16(g1, one);
        idx = vbslq_u16(g2, two, idx);
        idx = vbslq_u16(g3, three, idx);
        /* mx: the largest of the three vm words (< 2^14) */
        const uint32_t *v = vm + (bc - sx);
        const uint32x4_t xlo = vmaxq_u32(vmaxq_u32(vld1q_u32(v), vld1q_u32(v + 1)), vld1q_u32(v + 2));
        const uint32x4_t xhi =
            vmaxq_u32(vmaxq_u32(vld1q_u32(v + 4), vld1q_u32(v + 5)), vld1q_u32(v + 6));
        const uint16x8_t add =
            vrshrn_high_n_u32(vrshrn_n_u32(vmulq_u32(xlo, aq), 8), vmulq_u32(xhi, aq), 8);
        int16x8_t sq = vqaddq_s16(vqmovn_high_s32(vqmovn_s32(mlo), mhi), vreinterpretq_s16_u16(add));
        sq = vminq_s16(vmaxq_s16(sq, zero), top);
        vst1q_u16(out + bc, vsliq_n_u16(idx, vreinterpretq_u16_s16(sq), 2));
    }
    return bc;
}
#endif

#if defined(__SSE2__)
/* x86-64 (SSE2): the sums of a bin row's values sq = word >> 2 (below 2^14) and of their
 * squares, eight words per step, into *s0 and *s1; returns the first bin not done. The values
 * pairwise by a multiply-add with 1 into four 32-bit lanes (each below 2^15 per step, a row at
 * most PFT_CFG_MAX_IMAGE_SIDE / 16 steps: below 2^24), the squares pairwise by a multiply-add
 * of the values with themselves (below 2^29, exact in a signed 32-bit lane) widened into two
 * 64-bit lanes; the same integers as the plain loop's. */
static uint32_t integ_sums8_(const uint16_t *out, uint32_t n, uint64_t *s0, uint64_t *s1)
{
    const __m128i one = _mm_set1_epi16(1);
    const __m128i zero = _mm_setzero_si128();
    __m128i a0 = zero;
    __m128i a1 = zero;
    const uint16_t *p = out;
    for (uint32_t k = n / 8u; k > 0u; --k) {
        const __m128i q = _mm_srli_epi16(_mm_loadu_si128((const __m128i *)(const void *)p), 2);
        const __m128i qq = _mm_madd_epi16(q, q);
        a0 = _mm_add_epi32(a0, _mm_madd_epi16(q, one));
        a1 = _mm_add_epi64(a1, _mm_add_epi64(_mm_unpacklo_epi32(qq, zero),
                                             _mm_unpackhi_epi32(qq, zero)));
        p += 8;
    }
    uint32_t l0[4];
    uint64_t l1[2];
    _mm_storeu_si128((__m128i *)(void *)l0, a0);
    _mm_storeu_si128((__m128i *)(void *)l1, a1);
    *s0 += (uint64_t)l0[0] + l0[1] + l0[2] + l0[3];
    *s1 += l1[0] + l1[1];
    return n & ~7u;
}
#elif defined(__aarch64__) && defined(__ARM_NEON)
/* AArch64 (NEON): the sums of a bin row's values sq = word >> 2 and of their squares, eight
 * words per step, into *s0 and *s1; returns the first bin not done. The values' sums pairwise
 * into four 32-bit lanes (each below 2^15 per step, a row at most PFT_CFG_MAX_IMAGE_SIDE / 16
 * steps: below 2^24), the squares (below 2^28) pairwise into two 64-bit lanes; the same
 * integers as the plain loop's. */
static uint32_t integ_sums8_(const uint16_t *out, uint32_t n, uint64_t *s0, uint64_t *s1)
{
    uint32x4_t a0 = vdupq_n_u32(0u);
    uint64x2_t a1 = vdupq_n_u64(0u);
    const uint16_t *p = out;
    for (uint32_t k = n / 8u; k > 0u; --k) {
        const uint16x8_t q = vshrq_n_u16(vld1q_u16(p), 2);
        a0 = vpadalq_u16(a0, q);
        a1 = vpadalq_u32(a1, vmull_u16(vget_low_u16(q), vget_low_u16(q)));
        a1 = vpadalq_u32(a1, vmull_high_u16(q, q));
        p += 8;
    }
    *s0 += vaddlvq_u32(a0);
    *s1 += vaddvq_u64(a1);
    return n & ~7u;
}
#endif

/* Bin bc of row br in general (any column, r1 NULL past the last row). */
static void integ_bin_(const pft_tbd_integ_t_ *ig, const pft_real_t *r0, const pft_real_t *r1,
                       uint32_t w, const uint32_t *vm, uint32_t bc, uint16_t *out)
{
    const uint32_t c0 = 2u * bc;
    pft_real_t best = r0[c0];
    uint32_t idx = 0u;
    if (c0 + 1u < w && r0[c0 + 1u] > best) {
        best = r0[c0 + 1u];
        idx = 1u;
    }
    if (r1 != NULL && r1[c0] > best) {
        best = r1[c0];
        idx = 2u;
    }
    if (r1 != NULL && c0 + 1u < w && r1[c0 + 1u] > best) {
        best = r1[c0 + 1u];
        idx = 3u;
    }
    const uint32_t mx = integ_mx_(vm, (int32_t)bc - ig->sx, (int32_t)ig->bw);
    out[bc] = (uint16_t)((integ_sq_(best, mx, ig->a_q) << 2) | idx);
}

/* One bin row br of the integration (docs/algorithms.md 2.13) from the PSF-matched rows r0 and
 * r1 (pixel rows 2 br and 2 br + 1; r1 NULL past the last row): per bin the largest of its
 * pixels, m in 1/64 sigmas (rounded), plus a_q / 256 times the largest last-frame sum of the
 * 3 x 3 bins around the bin less the shift, floored at 0 and capped at INTEG_MAX_; the sums and
 * squares added to sum[0], sum[1]. vm is bw + 2 words of scratch: the largest last-frame sum
 * of the three rows per column, with a zero column on each side. Integer arithmetic after m:
 * the same in both builds. The bins with both pixel rows and columns whose 3 x 3 neighbourhood
 * lies inside the last frame's row (bc - sx in 0 .. bw - 1) go through one branch-free loop
 * (the same selections as integ_bin_, ties to the earlier pixel), the others through
 * integ_bin_; the sums after the row, over its stored values. */
#if defined(PFT_TBD_INTEG_FAST8_)
/* general: every bin by integ_bin_ (pft_tbd_integ_row_, the unit tests' hook) */
static void integ_row_(const pft_tbd_integ_t_ *ig, uint32_t br, const pft_real_t *r0,
                       const pft_real_t *r1, uint32_t w, uint32_t *vm, uint64_t *sum,
                       bool general)
{
#else
static void integ_row_(const pft_tbd_integ_t_ *ig, uint32_t br, const pft_real_t *r0,
                       const pft_real_t *r1, uint32_t w, uint32_t *vm, uint64_t *sum)
{
    const bool general = false;
#endif
    const int32_t pr = (int32_t)br - ig->sy;
    const int32_t bw = (int32_t)ig->bw;
    const int32_t bh = (int32_t)ig->bh;
    const int32_t rlo = pr - 1 < 0 ? 0 : pr - 1;
    const int32_t rhi = pr + 1 > bh - 1 ? bh - 1 : pr + 1;
    const uint32_t bwu = ig->bw; /* a local: vm's stores could alias ig->bw otherwise */
    vm[0] = 0u;
    vm[bwu + 1u] = 0u;
    if (rhi < rlo) {
        for (uint32_t c = 0; c < bwu; ++c) {
            vm[c + 1u] = 0u;
        }
    } else {
        /* the largest of rows rlo .. rhi (one to three; a row repeated when fewer) in one
         * pass: max(a, b) >> 2 = max(a >> 2, b >> 2) */
        const uint16_t *p0 = ig->prev + (size_t)rlo * bwu;
        const uint16_t *p1 = ig->prev + (size_t)(rlo + 1 <= rhi ? rlo + 1 : rlo) * bwu;
        const uint16_t *p2 = ig->prev + (size_t)rhi * bwu;
        for (uint32_t c = 0; c < bwu; ++c) {
            const uint16_t a = p0[c];
            const uint16_t b = p1[c];
            const uint16_t d = p2[c];
            const uint16_t m = a > b ? a : b;
            vm[c + 1u] = (uint32_t)(d > m ? d : m) >> 2;
        }
    }
    uint16_t *out = ig->cur + (size_t)br * bwu;
    /* the fast bins: bc in [b0, b1) with sx <= bc < sx + bw and 2 bc + 1 < w, r1 not NULL */
    const int32_t sx = ig->sx;
    const int32_t nfull = (int32_t)(w / 2u);
    int32_t b0 = sx < 0 ? 0 : (sx > bw ? bw : sx);
    int32_t b1 = sx > nfull - bw ? nfull : sx + bw;
    b1 = r1 == NULL || b1 < b0 || general ? b0 : b1; /* general: every bin by integ_bin_ */
    for (int32_t bc = 0; bc < b0; ++bc) {
        integ_bin_(ig, r0, r1, w, vm, (uint32_t)bc, out);
    }
    if (r1 != NULL) { /* always when b0 < b1 (b1 = b0 without r1) */
        const uint32_t a_q = ig->a_q;
        int32_t bf = b0;
#if defined(PFT_TBD_INTEG_FAST8_)
        if (a_q <= PFT_TBD_INTEG_AQ_MAX_) {
            bf = integ_fast8_(r0, r1, vm, sx, b0, b1, a_q, out);
        }
#endif
        for (int32_t bc = bf; bc < b1; ++bc) {
            const pft_real_t x0 = r0[2 * bc];
            const pft_real_t x1 = r0[2 * bc + 1];
            const pft_real_t x2 = r1[2 * bc];
            const pft_real_t x3 = r1[2 * bc + 1];
            /* idx by masks from the same compares (a form the compiler vectorises) */
            pft_real_t best = x0;
            uint32_t idx = 0u;
            const uint32_t g1 = (x1 > best) ? 0xFFFFFFFFu : 0u;
            best = x1 > best ? x1 : best;
            idx = (idx & ~g1) | (1u & g1);
            const uint32_t g2 = (x2 > best) ? 0xFFFFFFFFu : 0u;
            best = x2 > best ? x2 : best;
            idx = (idx & ~g2) | (2u & g2);
            const uint32_t g3 = (x3 > best) ? 0xFFFFFFFFu : 0u;
            best = x3 > best ? x3 : best;
            idx = (idx & ~g3) | (3u & g3);
            /* pc = bc - sx in 0 .. bw - 1: vm[pc .. pc + 2] inside */
            const uint32_t a = vm[bc - sx];
            const uint32_t b = vm[bc - sx + 1];
            const uint32_t d = vm[bc - sx + 2];
            uint32_t mx = a > b ? a : b;
            mx = d > mx ? d : mx;
            out[bc] = (uint16_t)((integ_sq_(best, mx, a_q) << 2) | idx);
        }
    }
    for (int32_t bc = b1; bc < bw; ++bc) {
        integ_bin_(ig, r0, r1, w, vm, (uint32_t)bc, out);
    }
    uint64_t s0 = 0u;
    uint64_t s1 = 0u;
#if defined(__SSE2__) || (defined(__aarch64__) && defined(__ARM_NEON))
    for (uint32_t bc = integ_sums8_(out, bwu, &s0, &s1); bc < bwu; ++bc) {
#else
    for (uint32_t bc = 0; bc < bwu; ++bc) {
#endif
        const uint32_t sq = (uint32_t)out[bc] >> 2;
        s0 += sq;
        s1 += (uint64_t)sq * sq;
    }
    sum[0] += s0;
    sum[1] += s1;
}

#if defined(PFT_TBD_INTEG_FAST8_)
void pft_tbd_integ_row_(const pft_tbd_integ_t_ *ig, uint32_t br, const pft_real_t *r0,
                        const pft_real_t *r1, uint32_t w, uint32_t *vm, uint64_t *sum,
                        bool general)
{
    integ_row_(ig, br, r0, r1, w, vm, sum, general);
}
#endif

/* floor(sqrt(v)), bit by bit (32 steps). */
static uint32_t isqrt64_(uint64_t v)
{
    uint64_t r = 0u;
    for (int32_t b = 31; b >= 0; --b) {
        const uint64_t t = r | ((uint64_t)1u << (uint32_t)b);
        if (t * t <= v) {
            r = t;
        }
    }
    return (uint32_t)r;
}

/* Sum of bin (br, bc) of the integration (0 outside). */
static uint32_t integ_at_(const pft_tbd_integ_t_ *ig, int32_t br, int32_t bc)
{
    if (br < 0 || bc < 0 || br >= (int32_t)ig->bh || bc >= (int32_t)ig->bw) {
        return 0u;
    }
    return (uint32_t)ig->cur[(size_t)br * ig->bw + (size_t)bc] >> 2;
}

/* The peaks of the integration into the heap: the 3 x 3 local maxima of the bins' sums (a
 * plateau's first bin in raster order, as peak_is_max_) above ps->thr, each at its bin's
 * largest pixel of this frame, when that pixel is allowed. */
/* The threshold te of integ_scan_ as a bound on a bin's 16-bit word: a bin's v = word >> 2
 * (below 2^14) has pft_from_int(v) > te exactly when word > the returned bound. v is an
 * integer, exact in both builds: float, v > te holds for every v when te < 0 (or -inf), for
 * none when te is NaN or at least 2^14 (bound 4 16383 + 3 = 65535), and else exactly when
 * v > floor(te); q16, v 2^16 > te exactly when v > floor(te / 2^16), every v when te < 0. v >
 * L is word > 4 L + 3 (the word's low two bits are its pixel's index). */
static int32_t integ_bound_(pft_real_t te)
{
    int32_t l;
#ifdef PFT_NUMERIC_Q16
    l = te < 0 ? -1 : te / 65536;
#else
    if (te < 0.0f) {
        l = -1;
    } else if (te < 16384.0f) {
        l = (int32_t)te; /* floor: te >= 0 */
    } else {
        l = 16383; /* te >= 2^14, +inf or NaN: no v is above it */
    }
#endif
    return 4 * (l < 16383 ? l : 16383) + 3;
}

#if defined(__SSE2__)
/* x86-64 (SSE2): the first bin from bc on whose word is above bound, or the first of eight
 * that holds one, or the last whole step's end: integ_scan_'s skip of the bins under the
 * threshold eight words per step, the rest by the plain loop after it. SSE2 has no unsigned
 * 16-bit compare: a word is above bound exactly where the saturated difference word - bound
 * is not 0 (one subtraction, one compare with 0, the byte mask all ones when none is above).
 * bound < 0: every word is above it, nothing skipped; bound <= 65535 (integ_bound_), so its
 * low 16 bits compare as bound does. */
static uint32_t integ_skip8_(const uint16_t *row, uint32_t bc, uint32_t bw, int32_t bound)
{
    if (bound >= 0 && bc < bw) {
        const __m128i b0 = _mm_shufflelo_epi16(_mm_cvtsi32_si128(bound), 0);
        const __m128i b = _mm_unpacklo_epi64(b0, b0); /* bound in every 16-bit lane */
        const __m128i zero = _mm_setzero_si128();
        const uint16_t *p = row + bc;
        uint32_t k = (bw - bc) / 8u;
        while (k > 0u &&
               _mm_movemask_epi8(_mm_cmpeq_epi16(
                   _mm_subs_epu16(_mm_loadu_si128((const __m128i *)(const void *)p), b), zero)) ==
                   0xFFFF) {
            p += 8;
            --k;
        }
        bc = bw - 8u * k - (bw - bc) % 8u;
    }
    return bc;
}
#elif defined(__aarch64__) && defined(__ARM_NEON)
/* AArch64 (NEON): the first bin from bc on whose word is above bound, or the first of eight
 * that holds one, or the last whole step's end: integ_scan_'s skip of the bins under the
 * threshold eight words per step (one compare of eight unsigned 16-bit lanes), the rest by the
 * plain loop after it. bound < 0: every word is above it, nothing skipped; bound
 * <= 65535 (integ_bound_), so (uint16_t)bound compares as bound does. */
static uint32_t integ_skip8_(const uint16_t *row, uint32_t bc, uint32_t bw, int32_t bound)
{
    if (bound >= 0 && bc < bw) {
        const uint16x8_t b = vdupq_n_u16((uint16_t)bound);
        const uint16_t *p = row + bc;
        uint32_t k = (bw - bc) / 8u;
        /* the eight lanes' masks narrowed to bytes: one 64-bit word, 0 when none is above */
        while (k > 0u &&
               vget_lane_u64(vreinterpret_u64_u8(vmovn_u16(vcgtq_u16(vld1q_u16(p), b))), 0) == 0u) {
            p += 8;
            --k;
        }
        bc = bw - 8u * k - (bw - bc) % 8u;
    }
    return bc;
}
#endif

#if defined(__SSE2__) || (defined(__aarch64__) && defined(__ARM_NEON))
uint32_t pft_tbd_integ_skip_(const uint16_t *row, uint32_t bc, uint32_t bw, int32_t bound)
{
    bc = integ_skip8_(row, bc, bw, bound);
    while (bc < bw && (int32_t)row[bc] <= bound) {
        ++bc;
    }
    return bc;
}
#endif

static void integ_scan_(peak_scan_t *ps, const pft_tbd_integ_t_ *ig)
{
    pft_real_t te = peak_te_(ps);
    int32_t bound = integ_bound_(te); /* a bin passes the threshold when its word is above it */
    for (uint32_t br = 0; br < ig->bh; ++br) {
        const uint16_t *row = ig->cur + (size_t)br * ig->bw;
        const uint32_t bw = ig->bw;
        for (uint32_t bc = 0; bc < bw; ++bc) {
            /* the bins whose pft_from_int(word >> 2) > te fails (integ_bound_), in a loop of
             * their own (most bins fail it) */
#if defined(__SSE2__) || (defined(__aarch64__) && defined(__ARM_NEON))
            bc = integ_skip8_(row, bc, bw, bound);
#endif
            while (bc < bw && (int32_t)row[bc] <= bound) {
                ++bc;
            }
            if (bc >= bw) {
                break;
            }
            const uint32_t v = (uint32_t)row[bc] >> 2;
            const pft_real_t vr = pft_from_int((int32_t)v);
            bool is_max = true;
            if (br >= 1u && br + 1u < ig->bh && bc >= 1u && bc + 1u < bw) {
                /* an inner bin: its eight neighbours read in place (integ_at_'s values), the
                 * same tests as the general form below */
                const uint16_t *up = row - bw;
                const uint16_t *dn = row + bw;
                is_max = v > ((uint32_t)up[bc - 1u] >> 2) && v > ((uint32_t)up[bc] >> 2) &&
                         v > ((uint32_t)up[bc + 1u] >> 2) && v > ((uint32_t)row[bc - 1u] >> 2) &&
                         v >= ((uint32_t)row[bc + 1u] >> 2) &&
                         v >= ((uint32_t)dn[bc - 1u] >> 2) && v >= ((uint32_t)dn[bc] >> 2) &&
                         v >= ((uint32_t)dn[bc + 1u] >> 2);
            } else {
                for (int32_t a = -1; a <= 1 && is_max; ++a) {
                    for (int32_t b = -1; b <= 1 && is_max; ++b) {
                        const uint32_t n = integ_at_(ig, (int32_t)br + a, (int32_t)bc + b);
                        const bool before = a < 0 || (a == 0 && b < 0);
                        is_max = (a == 0 && b == 0) || (before ? v > n : v >= n);
                    }
                }
            }
            if (!is_max) {
                continue;
            }
            const uint32_t idx = (uint32_t)row[bc] & 3u;
            const uint32_t pr = 2u * br + (idx >> 1);
            const uint32_t pc = 2u * bc + (idx & 1u);
            if (ps->mask != NULL &&
                pft_tbd_masked_(ps->mask, pft_tbd_mask_words_(ps->w), pc, pr)) {
                continue;
            }
            peak_keep_(ps, pr * ps->w + pc, vr);
            te = peak_te_(ps);
            bound = integ_bound_(te);
        }
    }
}

/* What both scene scans (pft_tbd_scene_peaks_, pft_tbd_scene_integ_) hold: the taps at offset
 * 0, the RES16 path's prepared taps, the rolling rows (hs: horizontal sums, mf: PSF-matched)
 * and the peak scan. */
typedef struct {
    const pft_real_t *tx;
    const pft_real_t *ty;
    pft_real_t *hs[3];
    pft_real_t *mf[3];
    pft_real_t t0p, t1p;
    bool r16;
} scene_scan_t;

/* Sets up a scene scan: returns the rows and taps, fills the peak scan *ps (kept apart, so
 * that the returned value stays in registers in the callers' loops). */
static inline scene_scan_t scene_scan_init_(peak_scan_t *ps, const pft_tbd_config_t *cfg,
                                     const pft_tbd_tab_t *tab, const pft_real_t *img,
                                     const uint32_t *mask, pft_real_t *rows, pft_real_t *val,
                                     uint32_t *cand, uint32_t *lines, pft_tbd_scene_t_ *sc)
{
    const uint32_t w = cfg->width;
    const uint32_t h = cfg->height;
    const uint32_t mid = PFT_TBD_TAP_STEPS / 2u; /* tap row of offset f = 0 */
    scene_scan_t ss;
    ss.tx = tab->taps[0][mid];
    ss.ty = tab->taps[1][mid];
    for (uint32_t s = 0; s < 3u; ++s) {
        ss.hs[s] = rows + (size_t)s * w;
        ss.mf[s] = rows + (size_t)(s + 3u) * w;
    }
    scene_source_(sc, img, w, h);
    /* a RES16 scene's rows without a patch go through the integers (peak_hrow_r16_) when the
     * prepared taps are exact (always in q16; in float unless a tap is below 2^-118) */
    ss.t0p = pft_kr16_tap_(ss.tx[0]);
    ss.t1p = pft_kr16_tap_(ss.tx[1]);
    ss.r16 = img == NULL && pft_kr16_tap_ok_(ss.tx[0]) && pft_kr16_tap_ok_(ss.tx[1]);
    ps->mask = mask;
    ps->key = cand;
    ps->val = val;
    /* noise of the correlation: variance (sum tx^2)(sum ty^2) in whitened units */
    ps->thr = pft_mul(cfg->peak_gamma, pft_sqrt(pft_mul(ss.tx[3], ss.ty[3])));
    ps->w = w;
    ps->k_max = (uint32_t)cfg->birth_peaks < w * h ? (uint32_t)cfg->birth_peaks : w * h;
    ps->n = 0u;
    ps->na = 0u;
    ps->quota = cfg->peak_tile > 0u ? cfg->peak_quota : 0u;
    ps->tile = cfg->peak_tile > 0u ? cfg->peak_tile : 1u;
    ps->ntx = (w + ps->tile - 1u) / ps->tile;
    ps->row_pre = lines;           /* h + 1 entries */
    ps->cnt = lines + h + 1u;      /* ntx <= w entries */
    ps->trow = 0u;
    lines[0] = 0u;
    return ss;
}

/* Rolling step rr (0 .. h + 1) of a scene scan: the horizontal sums of row rr and the
 * PSF-matched row rr - 1. */
static inline void scene_scan_rows_(scene_scan_t *ss, const pft_tbd_scene_t_ *sc,
                                    uint32_t rr, uint32_t w, uint32_t h)
{
    if (rr < h && ss->r16 && (sc->n_patch == 0u || sc->pflag[rr] == 0u)) {
        peak_hrow_r16_(sc->r16 + (size_t)rr * sc->r16_stride, w, ss->t0p, ss->t1p,
                       ss->hs[rr % 3u]);
    } else if (rr < h) {
        peak_hrow_(pft_tbd_row_(sc, rr), w, ss->tx[0], ss->tx[1], ss->hs[rr % 3u]);
    } else {
        /* rows h and h + 1 of the rolling steps: no new row */
    }
    if (rr >= 1u && rr <= h) {
        const uint32_t r = rr - 1u;
        peak_vrow_(r >= 1u ? ss->hs[(r + 2u) % 3u] : NULL, ss->hs[r % 3u],
                   r + 1u < h ? ss->hs[(r + 1u) % 3u] : NULL, w, ss->ty[0], ss->ty[1],
                   ss->mf[r % 3u]);
    }
}

/* The scene's candidates after a scan: the kept peaks, or with none every allowed pixel. */
static void scene_scan_done_(pft_tbd_scene_t_ *sc, const peak_scan_t *ps, const uint32_t *mask,
                             uint32_t *cand, uint32_t *lines, uint32_t w, uint32_t h)
{
    sc->mask = mask;
    sc->cand = cand;
    sc->row_pre = lines;
    sc->width = w;
    sc->height = h;
    sc->n_allowed = ps->na;
    sc->cand_is_b = ps->n > 0u;
    sc->n_cand = ps->n;
    if (ps->n == 0u && ps->na > 0u) {
        /* No peak above the threshold: propose uniformly over the allowed pixels, the n-th
         * of them found from the per-row counts (pft_tbd_scene_pick_) instead of a list. */
        sc->cand = NULL;
        sc->n_cand = ps->na;
    }
}

void pft_tbd_scene_peaks_(const pft_tbd_config_t *cfg, const pft_tbd_tab_t *tab,
                          const pft_real_t *img, const uint32_t *mask, pft_real_t *rows,
                          pft_real_t *val, uint32_t *cand, uint32_t *lines, pft_tbd_scene_t_ *sc)
{
    const uint32_t w = cfg->width;
    const uint32_t h = cfg->height;
    peak_scan_t ps;
    scene_scan_t ss = scene_scan_init_(&ps, cfg, tab, img, mask, rows, val, cand, lines, sc);
    /* rolling rows: at step rr the horizontal sums of row rr, the correlation of row rr - 1
     * and the scan of row rr - 2 */
    for (uint32_t rr = 0; rr < h + 2u; ++rr) {
        scene_scan_rows_(&ss, sc, rr, w, h);
        if (rr >= 2u) {
            const uint32_t q = rr - 2u;
            peak_scan_row_(&ps, q, q >= 1u ? ss.mf[(q + 2u) % 3u] : NULL, ss.mf[q % 3u],
                           q + 1u < h ? ss.mf[(q + 1u) % 3u] : NULL);
        }
    }
    scene_scan_done_(sc, &ps, mask, cand, lines, w, h);
}

/* pft_tbd_scene_peaks_ with the integration (docs/algorithms.md 2.13): the same PSF-matched
 * rows, folded into the bins' sums instead of scanned. */
void pft_tbd_scene_integ_(const pft_tbd_config_t *cfg, const pft_tbd_tab_t *tab,
                          const pft_real_t *img, const uint32_t *mask, pft_real_t *rows,
                          pft_real_t *val, uint32_t *cand, uint32_t *lines, pft_tbd_scene_t_ *sc,
                          const pft_tbd_integ_t_ *ig)
{
    const uint32_t w = cfg->width;
    const uint32_t h = cfg->height;
    peak_scan_t ps;
    scene_scan_t ss = scene_scan_init_(&ps, cfg, tab, img, mask, rows, val, cand, lines, sc);
    uint64_t isum[2] = {0u, 0u};
    for (uint32_t rr = 0; rr < h + 2u; ++rr) {
        scene_scan_rows_(&ss, sc, rr, w, h);
        if (rr >= 1u && rr <= h) {
            /* the integration's bin row of PSF-matched rows r - 1 and r (r odd), or of the last
             * row alone (h odd) */
            const uint32_t r = rr - 1u;
            if (r % 2u == 1u) {
#if defined(PFT_TBD_INTEG_FAST8_)
                integ_row_(ig, r / 2u, ss.mf[(r + 2u) % 3u], ss.mf[r % 3u], w, lines, isum, false);
#else
                integ_row_(ig, r / 2u, ss.mf[(r + 2u) % 3u], ss.mf[r % 3u], w, lines, isum);
#endif
            } else if (r + 1u == h) {
#if defined(PFT_TBD_INTEG_FAST8_)
                integ_row_(ig, r / 2u, ss.mf[r % 3u], NULL, w, lines, isum, false);
#else
                integ_row_(ig, r / 2u, ss.mf[r % 3u], NULL, w, lines, isum);
#endif
            } else {
                /* the first row of a pair: its bin row comes with the next row */
            }
        }
    }
    {
        /* (lines was the integration's scratch) the allowed pixels per row, then the peaks of the sums above their frame mean plus
         * peak_gamma frame standard deviations (1/64 sigmas) */
        lines[0] = 0u;
        for (uint32_t q = 0; q < h; ++q) {
            ps.na += mask == NULL ? w : pft_tbd_mask_row_free_(mask, w, q);
            lines[q + 1u] = ps.na;
        }
        const uint64_t nb = (uint64_t)ig->bw * ig->bh;
        const uint64_t mean = isum[0] / nb;
        const uint64_t msq = isum[1] / nb;
        const uint32_t sd = isqrt64_(msq > mean * mean ? msq - mean * mean : 0u);
        ps.thr = pft_add(pft_from_int((int32_t)mean),
                            pft_mul(cfg->peak_gamma, pft_from_int((int32_t)sd)));
        integ_scan_(&ps, ig);
    }
    scene_scan_done_(sc, &ps, mask, cand, lines, w, h);
}

uint32_t pft_tbd_scene_pick_(const pft_tbd_scene_t_ *sc, uint32_t n)
{
    const uint32_t w = sc->width;
    if (sc->mask == NULL || sc->n_allowed == w * sc->height) {
        return n; /* nothing masked: the n-th pixel */
    }
    /* the row r with row_pre[r] <= n < row_pre[r + 1]: row_pre[0] = 0 <= n < row_pre[h] */
    uint32_t lo = 0u;
    uint32_t hi = sc->height;
    while (hi - lo > 1u) {
        const uint32_t mid = lo + (hi - lo) / 2u;
        if (sc->row_pre[mid] <= n) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    uint32_t left = n - sc->row_pre[lo];
    const uint32_t *mrow = sc->mask + (size_t)lo * pft_tbd_mask_words_(w);
    for (uint32_t c = 0; c < w; ++c) {
        if (!pft_tbd_masked_(mrow, 0u, c, 0u)) {
            if (left == 0u) {
                return lo * w + c;
            }
            --left;
        }
    }
    return lo * w; /* cannot happen: row lo holds more than left allowed pixels */
}
