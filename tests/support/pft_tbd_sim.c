#include "pft_tbd_sim.h"
#include <math.h>
#include <string.h>

#define PFT_SIM_PI 3.14159265358979323846
#define PFT_SIM_S2 0.49

int pft_sim_alive(const pft_sim_truth_t *t, int k) { return k >= t->first && k <= t->last; }
double pft_sim_x(const pft_sim_truth_t *t, int k) { return t->x0 + t->vx * (k - t->first); }
double pft_sim_y(const pft_sim_truth_t *t, int k) { return t->y0 + t->vy * (k - t->first); }

double pft_sim_gauss(pft_rng_t *r)
{
    double u1 = ((double)pft_rng_u32(r) + 1.0) / 4294967297.0;
    double u2 = (double)pft_rng_u32(r) / 4294967296.0;
    return sqrt(-2.0 * log(u1)) * cos(2.0 * PFT_SIM_PI * u2);
}

void pft_sim_render_u16(pft_rng_t *r, const pft_sim_truth_t *t, int nt, int k, double sigma,
                        int w, int h, uint16_t *buf, pft_frame_t *f)
{
    for (int row = 0; row < h; ++row) {
        for (int col = 0; col < w; ++col) {
            double z = sigma * pft_sim_gauss(r);
            for (int q = 0; q < nt; ++q) {
                if (pft_sim_alive(&t[q], k)) {
                    double dx = col - pft_sim_x(&t[q], k), dy = row - pft_sim_y(&t[q], k);
                    z += t[q].I / (2.0 * PFT_SIM_PI * PFT_SIM_S2) *
                         exp(-(dx * dx + dy * dy) / (2.0 * PFT_SIM_S2));
                }
            }
            double raw = floor((z + 64.0) * 256.0 + 0.5);
            raw = raw < 0.0 ? 0.0 : (raw > 65535.0 ? 65535.0 : raw);
            buf[row * w + col] = (uint16_t)raw;
        }
    }
    memset(f, 0, sizeof(*f));
    f->data = buf;
    f->width = (uint16_t)w;
    f->height = (uint16_t)h;
    f->stride_bytes = 2u * (uint32_t)w;
    f->format = PFT_PIX_U16;
    f->bit_depth = 16;
    f->seq = (uint32_t)k;
}
