#include "pft_test_support.h"
#include <math.h>
#include <string.h>

double pft_test_to_double(pft_real_t v)
{
#ifdef PFT_NUMERIC_Q16
    return (double)v / 65536.0;
#else
    return (double)v;
#endif
}

pft_real_t pft_test_from_double(double v)
{
#ifdef PFT_NUMERIC_Q16
    double s = floor(v * 65536.0 + 0.5);
    if (s > 2147483647.0) {
        s = 2147483647.0;
    }
    if (s < -2147483647.0) {
        s = -2147483647.0;
    }
    return (pft_real_t)s;
#else
    return (pft_real_t)v;
#endif
}

double pft_test_lsb(double v)
{
#ifdef PFT_NUMERIC_Q16
    (void)v;
    return 1.0 / 65536.0;
#else
    float f = (float)fabs(v);
    return (double)(nextafterf(f, INFINITY) - f);
#endif
}

void pft_test_guard_fill(uint8_t *buf, size_t len)
{
    memset(buf, (int)PFT_TEST_GUARD, len);
}

int pft_test_guard_intact(const uint8_t *buf, size_t len, size_t lo, size_t hi)
{
    for (size_t i = 0; i < len; ++i) {
        if ((i < lo || i >= hi) && buf[i] != PFT_TEST_GUARD) {
            return 0;
        }
    }
    return 1;
}

double pft_test_gauss(uint64_t *state)
{
    double u[2];
    for (int i = 0; i < 2; ++i) {
        *state ^= *state << 13;
        *state ^= *state >> 7;
        *state ^= *state << 17;
        u[i] = ((double)(*state >> 11) + 0.5) / 9007199254740992.0;
    }
    return sqrt(-2.0 * log(u[0])) * cos(6.283185307179586 * u[1]);
}

uint32_t pft_test_xorshift32(uint32_t *state)
{
    *state ^= *state << 13;
    *state ^= *state >> 17;
    *state ^= *state << 5;
    return *state;
}

void pft_test_tbd_u16_config(pft_tbd_config_t *c, uint16_t side, double sigma)
{
    pft_tbd_config_recommended(c);
    c->width = side;
    c->height = side;
    c->noise_sigma = pft_test_from_double(sigma);
    c->pixel_gain = pft_test_from_double(1.0 / 256.0);
    c->pixel_offset = pft_test_from_double(-64.0);
}

void pft_test_tbd_bern_config(pft_tbd_config_t *c, uint16_t side, double sigma, uint32_t n_search,
                              uint32_t n_track, uint32_t max_targets, uint16_t peaks, uint32_t seed)
{
    pft_test_tbd_u16_config(c, side, sigma);
    c->n_search = n_search;
    c->n_track = n_track;
    c->max_targets = max_targets;
    c->birth_peaks = peaks;
    c->birth_share = pft_test_from_double(0.5);
    c->theta1 = pft_test_from_double(0.6);
    c->confirm_frames = 2u;
    c->seed = seed;
}

void pft_test_tbd_put_record(pft_tbd_t *t, uint32_t slot, uint32_t id, pft_real_t x, pft_real_t y,
                             pft_real_t in)
{
    pft_tbd_filter_t *tf = &t->tracks[slot];
    memset(&tf->est, 0, sizeof tf->est);
    tf->est.x = x;
    tf->est.y = y;
    tf->est.intensity = in;
    tf->est.p_exist = PFT_REAL_ONE;
    tf->est.valid = true;
    tf->frames = 3u;
    pft_tbd_track_t *r = &t->records[slot];
    memset(r, 0, sizeof *r);
    r->id = id;
    r->x = tf->est.x;
    r->y = tf->est.y;
    r->intensity = tf->est.intensity;
    r->p_exist = tf->est.p_exist;
    r->first_frame = 1u;
    r->age = 3u;
    t->n_tracks += 1u;
    if (t->next_id <= id) {
        t->next_id = id + 1u;
    }
}

int32_t pft_test_noise_sum4(uint32_t *state)
{
    int32_t v = 0;
    for (int i = 0; i < 4; ++i) {
        v += (int32_t)(pft_test_xorshift32(state) >> 20) - 2048;
    }
    return v;
}

int32_t pft_test_noise_q88(uint32_t *state)
{
    return pft_test_noise_sum4(state) * 256 / 2365;
}

void pft_test_check_rows(const char *name, const char *row_name, const uint32_t *ref,
                         const uint32_t *val, size_t rows, size_t cols)
{
    for (size_t r = 0; r < rows; ++r) {
        for (size_t c = 0; c < cols; ++c) {
            if (ref[r * cols + c] != val[r * cols + c]) {
                UnityPrint(name);
                UnityPrint(" ");
                UnityPrint(row_name);
                UnityPrint(" ");
                UnityPrintNumber((UNITY_INT)(r + 1));
                UnityPrint(" column ");
                UnityPrintNumber((UNITY_INT)c);
                UnityPrint(": expected ");
                UnityPrintNumberUnsigned((UNITY_UINT)ref[r * cols + c]);
                UnityPrint(" got ");
                UnityPrintNumberUnsigned((UNITY_UINT)val[r * cols + c]);
                UNITY_PRINT_EOL();
                TEST_FAIL_MESSAGE(name);
            }
        }
    }
}

pft_frame_t pft_test_rgb_frame(const void *data, uint16_t w, uint16_t h)
{
    pft_frame_t f;
    memset(&f, 0, sizeof f);
    f.data = data;
    f.width = w;
    f.height = h;
    f.stride_bytes = 3u * (uint32_t)w;
    f.format = PFT_PIX_RGB888;
    return f;
}

pft_frame_t pft_test_u16_frame(const uint16_t *px, uint16_t w, uint16_t h, uint8_t bits, uint32_t seq)
{
    pft_frame_t f;
    memset(&f, 0, sizeof f);
    f.data = px;
    f.width = w;
    f.height = h;
    f.stride_bytes = 2u * (uint32_t)w;
    f.format = PFT_PIX_U16;
    f.bit_depth = bits;
    f.seq = seq;
    f.timestamp_us = 1000u * (uint64_t)seq;
    return f;
}

pft_frame_t pft_test_res16_frame(const int16_t *px, uint16_t w, uint16_t h, uint32_t seq,
                                 uint64_t timestamp_us)
{
    pft_frame_t f = pft_test_u16_frame((const uint16_t *)(const void *)px, w, h, 16u, seq);
    f.format = PFT_PIX_RES16;
    f.timestamp_us = timestamp_us;
    return f;
}

void pft_test_pre_init(pft_pre_t *p, const pft_pre_config_t *c, void *work, size_t cap)
{
    const char *field = NULL;
    TEST_ASSERT_EQUAL_INT_MESSAGE(PFT_OK, pft_pre_config_check(c, &field), field);
    const size_t need = pft_pre_workspace_size(c);
    TEST_ASSERT_TRUE(need > 0u && need <= cap);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_init(p, c, work, need));
}

void pft_test_pre_bad_frames_refused(pft_pre_t *p, pft_frame_t f, const void *work, size_t need,
                                     void *copy)
{
    const pft_pre_t before = *p;
    memcpy(copy, work, need);
    pft_frame_t bad[3] = {f, f, f};
    bad[0].data = NULL;
    bad[1].width = (uint16_t)(f.width - 1u);
    bad[2].bit_depth = f.bit_depth == 12u ? 14u : 12u;
    const pft_status_t want[3] = {PFT_ERR_INVAL, PFT_ERR_FORMAT, PFT_ERR_FORMAT};
    for (int i = 0; i < 3; ++i) {
        TEST_ASSERT_EQUAL_INT(want[i], pft_pre_update(p, &bad[i]));
        TEST_ASSERT_EQUAL_MEMORY(&before, p, sizeof *p);
        TEST_ASSERT_EQUAL_MEMORY(copy, work, need);
    }
}

void pft_test_texture(uint16_t *img, int w, int h, const pft_test_texture_t *t, uint32_t *rs, double *cx,
                      double *sxr, double *cy, double *syr)
{
    const double pi2 = 6.283185307179586;
    for (int x = 0; x < w; ++x) {
        const double u = x - t->sx;
        cx[x] = 1500.0 * sin(pi2 * u / 23.0) + 900.0 * sin(pi2 * u / 11.0 + 1.0);
        sxr[x] = sin(pi2 * u / 13.0);
    }
    for (int y = 0; y < h; ++y) {
        const double v = y - t->sy;
        cy[y] = 1200.0 * sin(pi2 * v / 17.0 + 0.5);
        syr[y] = 1000.0 * sin(pi2 * v / 19.0 + 2.0);
    }
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const double u = x - t->sx - t->tx, v = y - t->sy - t->ty;
            double z = 6000.0 + t->level + cx[x] + cy[y] + sxr[x] * syr[y];
            z += t->amp * exp(-(u * u + v * v) / (2.0 * 0.49));
            const double px = x - t->sx, py = y - t->sy;
            if (px >= 60.0 && px < 68.0 && py >= 20.0 && py < 28.0) {
                z += t->patch;
            }
            z += t->sigma * (pft_test_noise_sum4(rs) / 2365.0);
            const double r = floor(z + 0.5);
            img[y * w + x] = (uint16_t)(r < 0.0 ? 0.0 : (r > 16383.0 ? 16383.0 : r));
        }
    }
}

void pft_test_pre_gated_config(pft_pre_config_t *c, uint16_t w, uint16_t h, uint8_t tile)
{
    pft_pre_config_default(c);
    c->width = w;
    c->height = h;
    c->tile = tile;
    c->sigma_interp = false;
    c->bg_anchor = true;
    c->bg_gate = 64u;
    c->bg_gate_young = 16u;
}

void pft_test_pre_init_refused(pft_pre_t *p, const pft_pre_config_t *d, void *work, size_t need,
                               void *copy)
{
    const pft_pre_t before = *p;
    memcpy(copy, work, need);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_pre_init(p, d, work, need));
    TEST_ASSERT_EQUAL_MEMORY(&before, p, sizeof *p);
    TEST_ASSERT_EQUAL_MEMORY(copy, work, need);
}

void pft_test_pre_strip_acc(const pft_pre_t *p, int y0, int y1, int xe, int xi, int w, double sd,
                            double *se, int *ne, double *si, int *ni)
{
    for (int y = y0; y < y1; ++y) {
        for (int x = 0; x < w; ++x) {
            const double r = x < xe || x >= xi ? pft_test_pre_res_counts(p, x, y) : NAN;
            if (isnan(r)) {
                continue;
            }
            const double q = (r / sd) * (r / sd);
            if (x < xe) {
                *se += q;
                (*ne)++;
            } else {
                *si += q;
                (*ni)++;
            }
        }
    }
}

double pft_test_pre_res_counts(const pft_pre_t *p, int x, int y)
{
    pft_frame_t r;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_frame(p, &r));
    const int tile = (int)p->cfg.tile;
    const int ntx = ((int)r.width + tile - 1) / tile, nty = ((int)r.height + tile - 1) / tile;
    uint32_t sig[64];
    TEST_ASSERT_TRUE(ntx * nty <= 64);
    TEST_ASSERT_EQUAL_UINT32((uint32_t)(ntx * nty), (uint32_t)pft_pre_sigma(p, sig, 64));
    const int16_t q = ((const int16_t *)r.data)[y * (int)r.width + x];
    if (q == PFT_RES16_MASKED) {
        return NAN;
    }
    return q / 256.0 * (sig[(y / tile) * ntx + x / tile] / 65536.0);
}

void pft_test_clutter_init(pft_pre_clutter_t *c, pft_pre_clutter_config_t *cfg, uint16_t w, uint16_t h,
                           void *work, size_t len)
{
    cfg->width = w;
    cfg->height = h;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_init(c, cfg, work, len));
}

const int16_t *pft_test_clutter_out(const pft_pre_clutter_t *c)
{
    pft_frame_t o;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_clutter_frame(c, &o));
    TEST_ASSERT_EQUAL_INT(PFT_PIX_RES16, o.format);
    return (const int16_t *)o.data;
}

int32_t pft_test_clutter_mu_q88(uint16_t s)
{
    const int32_t mv = (int32_t)s - 32768;
    const int32_t a = ((mv < 0 ? -mv : mv) + 4) >> 3;
    return mv < 0 ? -a : a;
}

void pft_test_tsa_config(pft_tsa_config_t *c, uint16_t w, uint16_t h, uint16_t maxt, uint32_t n,
                         uint8_t pts)
{
    pft_tsa_config_default(c);
    c->width = w;
    c->height = h;
    c->max_target_w = maxt;
    c->max_target_h = maxt;
    c->n_particles = n;
    c->snake_points = pts;
    pft_tsa_snake_params_default(&c->snake, maxt, maxt);
}

void pft_test_box_corners(pft_tsa_pt_t b[4], int x0, int y0, int x1, int y1)
{
    b[0].x = (int16_t)x0;
    b[0].y = (int16_t)y0;
    b[1].x = (int16_t)x1;
    b[1].y = (int16_t)y0;
    b[2].x = (int16_t)x1;
    b[2].y = (int16_t)y1;
    b[3].x = (int16_t)x0;
    b[3].y = (int16_t)y1;
}
