/* DP-TBD core shared by the DP-TBD tracker and the PTE-TBD initiation: the merit recursion
 * with a velocity gate, backtracking, cancellation, sub-cell refinement, the line fit of a
 * path and the noise-only Monte Carlo threshold. */
#include <string.h>

#include "pte_int.h"

pft_real_t pft_pte_parabola_(pft_real_t ym, pft_real_t y0, pft_real_t yp)
{
    pft_real_t den = pft_add(pft_sub(ym, y0), pft_sub(yp, y0));
    if (!(den < PFT_C(0.0))) {
        return PFT_C(0.0);
    }
    pft_real_t d = pft_div(pft_sub(ym, yp), pft_mul_i(den, 2));
    return pft_clamp(d, PFT_C(-0.5), PFT_C(0.5));
}

static inline pft_real_t ell_(const pft_pte_core_t_ *c, const pft_real_t *zf, const uint8_t *mk,
                              uint32_t i)
{
    if (mk != NULL && mk[i] != 0u) {
        return PFT_PTE_NEG_;
    }
    if (c->amp > PFT_C(0.0)) {
        return pft_mul(c->amp, pft_sub(zf[i], pft_mul(c->amp, PFT_C(0.5))));
    }
    return zf[i];
}

/* The best of prev[r - g0 .. r + g0] (clipped to the row) and its offset in the gate (psi):
 * the first maximum in index order. */
static inline pft_real_t gate_max_(const pft_real_t *prev, int32_t r, int32_t nr, int32_t g0,
                                   int32_t *bo)
{
    int32_t rlo = r - g0 < 0 ? 0 : r - g0;
    int32_t rhi = r + g0 > nr - 1 ? nr - 1 : r + g0;
    pft_real_t best = prev[rlo];
    int32_t bu = rlo;
    for (int32_t rr = rlo + 1; rr <= rhi; ++rr) {
        if (prev[rr] > best) {
            best = prev[rr];
            bu = rr;
        }
    }
    *bo = bu - r + g0;
    return best;
}

/* The cancelled cells of one stage, after its cells were formed as if none was: cur[i] =
 * NEG + prev[i + psi[i] - g0] (the gate's best, whose offset psi[i] does not depend on the
 * mask; j == 0, prev NULL: NEG), the merit the test inside the cell loop gave. The mask is
 * read 8 cells at a time (a stage has a few cancelled cells or none). */
static void patch_(const uint8_t *mk, uint32_t n, const pft_real_t *prev, const uint8_t *psi,
                   int32_t g0, pft_real_t *cur)
{
    uint32_t i0 = 0u;
    while (i0 < n) {
        uint32_t i1 = i0 + 8u <= n ? i0 + 8u : n;
        uint64_t w = 0u;
        if (i1 - i0 == 8u) {
            memcpy(&w, mk + i0, sizeof(w));
        } else {
            w = 1u; /* the tail: cell by cell */
        }
        if (w != 0u) {
            for (uint32_t i = i0; i < i1; ++i) {
                if (mk[i] != 0u) {
                    cur[i] = prev == NULL
                                 ? PFT_PTE_NEG_
                                 : pft_add(PFT_PTE_NEG_,
                                           prev[(int32_t)i + (int32_t)psi[i] - g0]);
                }
            }
        }
        i0 = i1;
    }
}

/* One range-time step of the recursion: cur[r] = l(r) + max over |r - r'| <= g0 of prev[r'],
 * psi[r] the offset of the maximum (a sliding maximum). The cells are formed without the
 * mask and its cancelled cells patched after (patch_): the same merits as testing the mask in
 * the loop, whose test cost every cell although few are cancelled (docs/results/pte.md,
 * "Branch pte13"). */
static void step_rt_(const pft_pte_core_t_ *c, const pft_real_t *zf, const uint8_t *mk,
                     const pft_real_t *prev, pft_real_t *cur, uint8_t *psi)
{
    const int32_t nr = (int32_t)c->nr;
    const int32_t g0 = (int32_t)c->g0;
    const bool known = c->amp > PFT_C(0.0);
    /* cells whose gate is the common one cell per frame inside the row: unrolled */
    const int32_t ulo = g0 == 1 ? 1 : nr;
    const int32_t uhi = g0 == 1 ? nr - 1 : nr;
    int32_t r = 0;
    for (; r < ulo; ++r) {
        int32_t bo;
        pft_real_t best = gate_max_(prev, r, nr, g0, &bo);
        cur[r] = pft_add(known ? ell_(c, zf, NULL, (uint32_t)r) : zf[r], best);
        psi[r] = (uint8_t)bo;
    }
    for (; r < uhi; ++r) {
        pft_real_t best = prev[r - 1];
        uint8_t bo = 0u;
        if (prev[r] > best) {
            best = prev[r];
            bo = 1u;
        }
        if (prev[r + 1] > best) {
            best = prev[r + 1];
            bo = 2u;
        }
        cur[r] = pft_add(known ? ell_(c, zf, NULL, (uint32_t)r) : zf[r], best);
        psi[r] = bo;
    }
    for (; r < nr; ++r) {
        int32_t bo;
        pft_real_t best = gate_max_(prev, r, nr, g0, &bo);
        cur[r] = pft_add(known ? ell_(c, zf, NULL, (uint32_t)r) : zf[r], best);
        psi[r] = (uint8_t)bo;
    }
    if (mk != NULL) {
        patch_(mk, (uint32_t)nr, prev, psi, g0, cur);
    }
}

/* One range-Doppler step: the maximum over the (2 g0 + 1) x (2 g1 + 1) gate. */
static void step_rd_(const pft_pte_core_t_ *c, const pft_real_t *zf, const uint8_t *mk,
                     const pft_real_t *prev, pft_real_t *cur, uint8_t *psi)
{
    const int32_t nr = (int32_t)c->nr;
    const int32_t nd = (int32_t)c->nd;
    const int32_t g0 = (int32_t)c->g0;
    const int32_t g1 = (int32_t)c->g1;
    const int32_t w0 = 2 * g0 + 1;
    for (int32_t d = 0; d < nd; ++d) {
        int32_t dlo = d - g1 < 0 ? 0 : d - g1;
        int32_t dhi = d + g1 > nd - 1 ? nd - 1 : d + g1;
        for (int32_t r = 0; r < nr; ++r) {
            int32_t rlo = r - g0 < 0 ? 0 : r - g0;
            int32_t rhi = r + g0 > nr - 1 ? nr - 1 : r + g0;
            pft_real_t best = PFT_REAL_MIN;
            int32_t bi = 0;
            for (int32_t dd = dlo; dd <= dhi; ++dd) {
                const pft_real_t *pr = prev + (size_t)dd * (size_t)nr;
                for (int32_t rr = rlo; rr <= rhi; ++rr) {
                    if (pr[rr] > best) {
                        best = pr[rr];
                        bi = (rr - r + g0) + w0 * (dd - d + g1);
                    }
                }
            }
            uint32_t i = (uint32_t)d * (uint32_t)nr + (uint32_t)r;
            cur[i] = pft_add(ell_(c, zf, mk, i), best);
            psi[i] = (uint8_t)bi;
        }
    }
}

pft_real_t *pft_pte_core_stage_(const pft_pte_core_t_ *c, uint32_t j, const pft_real_t *zf)
{
    const uint32_t cells = (uint32_t)c->nr * c->nd;
    const uint8_t *mk = c->mask != NULL ? c->mask + (size_t)j * cells : NULL;
    /* stage j writes ma (j even) or mb (j odd) from the other */
    pft_real_t *cur = (j & 1u) == 0u ? c->ma : c->mb;
    const pft_real_t *prev = (j & 1u) == 0u ? c->mb : c->ma;
    uint8_t *psi = c->psi + (size_t)j * cells;
    if (j == 0u) {
        for (uint32_t i = 0; i < cells; ++i) {
            cur[i] = ell_(c, zf, NULL, i);
        }
        if (mk != NULL) {
            patch_(mk, cells, NULL, psi, 0, cur);
        }
    } else if (c->nd == 1u) {
        step_rt_(c, zf, mk, prev, cur, psi);
    } else {
        step_rd_(c, zf, mk, prev, cur, psi);
    }
    return cur;
}

pft_real_t pft_pte_core_best_(const pft_pte_core_t_ *c, const pft_real_t *merit, int32_t *cell)
{
    const uint32_t cells = (uint32_t)c->nr * c->nd;
    const uint8_t *mk = c->mask != NULL ? c->mask + (size_t)(c->k - 1u) * cells : NULL;
    pft_real_t best = PFT_REAL_MIN;
    int32_t bc = -1;
    for (uint32_t i = 0; i < cells; ++i) {
        if ((mk == NULL || mk[i] == 0u) && (bc < 0 || merit[i] > best)) {
            best = merit[i];
            bc = (int32_t)i;
        }
    }
    *cell = bc;
    return bc < 0 ? PFT_REAL_MIN : best;
}

pft_real_t pft_pte_core_run_(const pft_pte_core_t_ *c, int32_t *cell)
{
    const pft_real_t *merit = c->ma;
    for (uint32_t j = 0; j < c->k; ++j) {
        merit = pft_pte_core_stage_(c, j, pft_pte_ring_get_(c->ring, (uint32_t)c->k - 1u - j));
    }
    /* best final cell outside the cancelled set */
    return pft_pte_core_best_(c, merit, cell);
}

bool pft_pte_core_clear_(const pft_pte_core_t_ *c, const int16_t *path)
{
    const uint32_t cells = (uint32_t)c->nr * c->nd;
    if (c->mask == NULL) {
        return true;
    }
    for (uint32_t j = 0; j < c->k; ++j) {
        int32_t i = (int32_t)path[2u * j + 1u] * (int32_t)c->nr + path[2u * j];
        if (c->mask[(size_t)j * cells + (uint32_t)i] != 0u) {
            return false;
        }
    }
    return true;
}

void pft_pte_core_backtrack_(const pft_pte_core_t_ *c, int32_t cell, int16_t *path)
{
    const int32_t nr = (int32_t)c->nr;
    const uint32_t cells = (uint32_t)c->nr * c->nd;
    const int32_t g0 = (int32_t)c->g0;
    const int32_t g1 = c->nd > 1u ? (int32_t)c->g1 : 0;
    const int32_t w0 = 2 * g0 + 1;
    int32_t r = cell % nr;
    int32_t d = cell / nr;
    for (uint32_t jj = c->k; jj > 0u; --jj) {
        uint32_t j = jj - 1u;
        path[2u * j] = (int16_t)r;
        path[2u * j + 1u] = (int16_t)d;
        if (j > 0u) {
            int32_t bi = (int32_t)c->psi[(size_t)j * cells + (uint32_t)(d * nr + r)];
            r += bi % w0 - g0;
            d += bi / w0 - g1;
        }
    }
}

void pft_pte_core_cancel_(const pft_pte_core_t_ *c, const int16_t *path, int32_t h0,
                          int32_t h1)
{
    const int32_t nr = (int32_t)c->nr;
    const int32_t nd = (int32_t)c->nd;
    const uint32_t cells = (uint32_t)c->nr * c->nd;
    if (c->mask == NULL) {
        return;
    }
    if (nd == 1) {
        h1 = 0;
    }
    for (uint32_t j = 0; j < c->k; ++j) {
        uint8_t *mk = c->mask + (size_t)j * cells;
        int32_t r0 = path[2u * j];
        int32_t d0 = path[2u * j + 1u];
        int32_t dlo = d0 - h1 < 0 ? 0 : d0 - h1;
        int32_t dhi = d0 + h1 > nd - 1 ? nd - 1 : d0 + h1;
        int32_t rlo = r0 - h0 < 0 ? 0 : r0 - h0;
        int32_t rhi = r0 + h0 > nr - 1 ? nr - 1 : r0 + h0;
        for (int32_t d = dlo; d <= dhi; ++d) {
            for (int32_t r = rlo; r <= rhi; ++r) {
                mk[d * nr + r] = 1u;
            }
        }
    }
}

pft_real_t pft_pte_core_refine_(const pft_pte_core_t_ *c, const int16_t *path, uint32_t j,
                                uint32_t axis)
{
    const int32_t nr = (int32_t)c->nr;
    const int32_t n = axis == 0u ? nr : (int32_t)c->nd;
    const int32_t stride = axis == 0u ? 1 : nr;
    const pft_real_t *zf = pft_pte_ring_get_(c->ring, (uint32_t)c->k - 1u - j);
    int32_t r = path[2u * j];
    int32_t d = path[2u * j + 1u];
    int32_t u = axis == 0u ? r : d;
    pft_real_t pos = pft_from_int(u);
    if (u <= 0 || u >= n - 1) {
        return pos;
    }
    int32_t i = d * nr + r;
    pft_real_t y0 = zf[i];
    pft_real_t ym = zf[i - stride];
    pft_real_t yp = zf[i + stride];
    if (ym > y0 || yp > y0) {
        return pos;
    }
    return pft_add(pos, pft_pte_parabola_(ym, y0, yp));
}

void pft_pte_core_fit_(const pft_pte_core_t_ *c, const int16_t *path, uint32_t axis,
                       pft_real_t *pos, pft_real_t *vel)
{
    const uint32_t k = c->k;
    /* positions relative to the newest cell keep q16 sums small */
    int32_t ref = path[2u * (k - 1u) + axis];
    pft_real_t rel[PFT_PTE_MAX_FRAMES];
    pft_real_t sum = PFT_C(0.0);
    for (uint32_t j = 0; j < k; ++j) {
        rel[j] = pft_sub(pft_pte_core_refine_(c, path, j, axis), pft_from_int(ref));
        sum = pft_add(sum, rel[j]);
    }
    pft_real_t mean = pft_div_i(sum, (int32_t)k);
    /* slope = sum d_j (p_j - mean) / (k (k^2 - 1) / 6), d_j = 2j - (k - 1) */
    pft_real_t s = PFT_C(0.0);
    for (uint32_t j = 0; j < k; ++j) {
        int32_t dj = 2 * (int32_t)j - ((int32_t)k - 1);
        s = pft_add(s, pft_mul_i(pft_sub(rel[j], mean), dj));
    }
    int32_t den = (int32_t)(k * (k * k - 1u) / 6u);
    pft_real_t slope = pft_div_i(s, den);
    *vel = slope;
    *pos = pft_add(pft_from_int(ref),
                   pft_add(mean, pft_div_i(pft_mul_i(slope, (int32_t)k - 1), 2)));
}

pft_real_t pft_pte_core_amp_(const pft_pte_core_t_ *c, const int16_t *path)
{
    pft_real_t s = PFT_C(0.0);
    for (uint32_t j = 0; j < c->k; ++j) {
        const pft_real_t *zf = pft_pte_ring_get_(c->ring, (uint32_t)c->k - 1u - j);
        s = pft_add(s, zf[(int32_t)path[2u * j + 1u] * (int32_t)c->nr + path[2u * j]]);
    }
    return pft_div_i(s, (int32_t)c->k);
}

pft_status_t pft_pte_core_mc_(const pft_pte_input_t *in, pft_pte_core_t_ *c,
                              pft_pte_ring_t *ring, pft_real_t *row, pft_real_t pfa,
                              uint32_t runs, uint64_t seed, pft_real_t *vt)
{
    if (vt == NULL || runs == 0u || !(pfa > PFT_C(0.0)) || !(pfa < PFT_C(1.0))) {
        return PFT_ERR_INVAL;
    }
    pft_real_t kr = pft_mul_i(pfa, (int32_t)(runs > 0x7FFFFFFFu ? 0x7FFFFFFFu : runs));
    int32_t kk = pft_floor_int(kr) + 1;
    if (kk < 1 || kk > (int32_t)PFT_PTE_MC_TOPK) {
        return PFT_ERR_INVAL;
    }
    pft_real_t top[PFT_PTE_MC_TOPK];
    uint32_t ntop = 0u;
    pft_rng_t rng;
    pft_rng_seed(&rng, seed);
    pft_real_t sig = in->noise == PFT_PTE_NOISE_CFAR ? pft_mul_i(in->noise_sigma, 16)
                                                      : in->noise_sigma;
    uint8_t *mask = c->mask;
    c->mask = NULL;
    for (uint32_t run = 0; run < runs; ++run) {
        ring->count = 0u;
        for (uint32_t j = 0; j < c->k; ++j) {
            pft_real_t *dst = pft_pte_ring_next_(ring);
            for (uint32_t d = 0; d < in->n_doppler; ++d) {
                for (uint32_t u = 0; u < in->n_range; ++u) {
                    row[u] = pft_clamp(pft_mul(pft_rng_gauss(&rng), sig), PFT_C(-32767.0),
                                       PFT_C(32767.0));
                }
                pft_pte_norm_row_(in, row, dst + (size_t)d * in->n_range);
            }
            pft_pte_ring_commit_(ring);
        }
        int32_t cell;
        pft_real_t best = pft_pte_core_run_(c, &cell);
        /* keep the kk largest, descending */
        uint32_t pos = ntop;
        while (pos > 0u && top[pos - 1u] < best) {
            pos--;
        }
        if (pos < (uint32_t)kk) {
            uint32_t last = ntop < (uint32_t)kk ? ntop : (uint32_t)kk - 1u;
            for (uint32_t i = last; i > pos; --i) {
                top[i] = top[i - 1u];
            }
            top[pos] = best;
            if (ntop < (uint32_t)kk) {
                ntop++;
            }
        }
    }
    c->mask = mask;
    ring->count = 0u;
    *vt = top[ntop - 1u < (uint32_t)kk - 1u ? ntop - 1u : (uint32_t)kk - 1u];
    return PFT_OK;
}
