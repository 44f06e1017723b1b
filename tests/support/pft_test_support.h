/* Helpers shared by the unit tests (host, qemu-user and bare metal alike). */
#ifndef PFT_TEST_SUPPORT_H
#define PFT_TEST_SUPPORT_H
#include "unity.h"
#include "pft/pft.h"

/* Real <-> double for assertions (tests may use double; the library never does). */
double pft_test_to_double(pft_real_t v);
pft_real_t pft_test_from_double(double v);
/* An RGB888 frame over w x h packed pixels at data (stride 3 w, every other field 0). */
pft_frame_t pft_test_rgb_frame(const void *data, uint16_t w, uint16_t h);
/* A PFT_PIX_U16 frame of the given bit depth (rows of 2 w bytes) over px, with seq and
 * timestamp_us 1000 seq (the preprocessing tests' frames). */
pft_frame_t pft_test_u16_frame(const uint16_t *px, uint16_t w, uint16_t h, uint8_t bits, uint32_t seq);
/* A PFT_PIX_RES16 frame (bit depth 16, rows of 2 w bytes) over px, with seq and timestamp_us. */
pft_frame_t pft_test_res16_frame(const int16_t *px, uint16_t w, uint16_t h, uint32_t seq,
                                 uint64_t timestamp_us);
/* A TSA-AK configuration for the unit tests: the defaults, a w x h frame, targets up to
 * maxt x maxt, n particles, pts snake points, and the snake parameters for that target size. */
/* The four corners of the box x0..x1, y0..y1 (inclusive), clockwise from the top left. */
void pft_test_box_corners(pft_tsa_pt_t b[4], int x0, int y0, int x1, int y1);
/* The stage's tests: check c (the refused field named on failure), then init p with exactly its
 * workspace size from work (cap bytes, asserted enough). */
void pft_test_pre_init(pft_pre_t *p, const pft_pre_config_t *c, void *work, size_t cap);
/* The stage's refusal of three frames made from the valid frame f (data NULL: PFT_ERR_INVAL;
 * width one less, bit depth 12 where f's is not: PFT_ERR_FORMAT): each leaves p and its
 * workspace (need bytes at work; copy: need bytes of scratch) byte-identical. */
void pft_test_pre_bad_frames_refused(pft_pre_t *p, pft_frame_t f, const void *work, size_t need,
                                     void *copy);
/* The stage's last residual at pixel (x, y) in counts: the whitened value times the sigma of its
 * tile (exact with sigma_interp false); NAN where masked. */
double pft_test_pre_res_counts(const pft_pre_t *p, int x, int y);
/* pft_pre_init refuses the configuration d (PFT_ERR_CONFIG) given need bytes at work, and leaves
 * p and the workspace byte-identical (copy: need bytes of scratch). */
void pft_test_pre_init_refused(pft_pre_t *p, const pft_pre_config_t *d, void *work, size_t need,
                               void *copy);
/* The real-frame block's anchored background for the stage tests (test_pre_edge_narrow,
 * test_pre_young_clip): the defaults with a w x h frame, tiles of `tile`, sigma held per tile
 * (sigma_interp false: the residual in counts is exact), bg_anchor, bg_gate 0.25 sigma and
 * bg_gate_young 16. */
void pft_test_pre_gated_config(pft_pre_config_t *c, uint16_t w, uint16_t h, uint8_t tile);
/* The stage's last residual squared in units of sd counts over rows y0 .. y1 - 1 of a frame w
 * wide: columns x < xe added to *se (count *ne), columns x >= xi to *si (count *ni); masked
 * pixels skipped (the entering-edge strip tests). */
void pft_test_pre_strip_acc(const pft_pre_t *p, int y0, int y1, int xe, int xi, int w, double sd,
                            double *se, int *ne, double *si, int *ni);
/* The stage tests' drifting scene (test_pre_gate, test_pre_young_clip): a smooth texture
 * (wavelengths 11 to 23 px, 60 to 110 sd of 16 counts) about 6000 + level counts, shifted by
 * (sx, sy) (pixel p shows the scene at p - s), plus a Gaussian point (sd 0.7 px, peak amp
 * counts) at scene position (tx, ty), plus patch counts over the scene square [60, 68) x
 * [20, 28), plus noise of sd sigma (pft_test_noise_sum4 on *rs), rounded and clipped to 14 bits. */
typedef struct {
    double sx, sy, level, tx, ty, amp, patch, sigma;
} pft_test_texture_t;
/* Renders t into img (w x h); cx, sxr (w doubles) and cy, syr (h doubles) are scratch. */
void pft_test_texture(uint16_t *img, int w, int h, const pft_test_texture_t *t, uint32_t *rs, double *cx,
                      double *sxr, double *cy, double *syr);
/* The clutter map's tests: init for a w x h residual (cfg's size set) and assert PFT_OK; the
 * map's last output (PFT_PIX_RES16 asserted). */
void pft_test_clutter_init(pft_pre_clutter_t *c, pft_pre_clutter_config_t *cfg, uint16_t w, uint16_t h,
                           void *work, size_t len);
const int16_t *pft_test_clutter_out(const pft_pre_clutter_t *c);
/* The clutter map's running mean mu as stored (Q4.11 + 2^15) to the Q8.8 value that c = r - mu
 * takes off: round half away from 0. */
int32_t pft_test_clutter_mu_q88(uint16_t s);

void pft_test_tsa_config(pft_tsa_config_t *c, uint16_t w, uint16_t h, uint16_t maxt, uint32_t n,
                         uint8_t pts);
/* The recommended TBD preset on side x side PFT_PIX_U16 frames read as z = raw / 256 - 64 (zero
 * background at raw 16384) with noise sd sigma (the TBD manager tests' frames). */
void pft_test_tbd_u16_config(pft_tbd_config_t *c, uint16_t side, double sigma);
/* pft_test_tbd_u16_config with a Bernoulli search layer (birth_share 0.5) drawing its births from
 * `peaks` peaks, theta1 0.6 over confirm_frames 2, and the given sizes and seed (the search
 * layer tests' scene: test_tbd_bern_move, test_tbd_layers). */
void pft_test_tbd_bern_config(pft_tbd_config_t *c, uint16_t side, double sigma, uint32_t n_search,
                              uint32_t n_track, uint32_t max_targets, uint16_t peaks, uint32_t seed);
/* A TBD manager test's planted track: slot `slot` of t holds track `id`, its layer's estimate at
 * (x, y) (internal coordinates) with intensity `in`, existence 1, valid, 3 updates old, and
 * its record from that estimate, confirmed at frame 1 (next_id moved past id). The layer's
 * particles are the caller's. */
void pft_test_tbd_put_record(pft_tbd_t *t, uint32_t slot, uint32_t id, pft_real_t x, pft_real_t y,
                             pft_real_t in);
/* Size of one LSB of pft_real_t around v (q16: 2^-16; float: ulp of v). */
double pft_test_lsb(double v);

/* Deterministic N(0,1) from a xorshift64 state (Box-Muller on two 53-bit uniforms); the
 * state must be non-zero. Independent of the library's RNG, for test inputs. */
double pft_test_gauss(uint64_t *state);

/* One step of a 32-bit xorshift (13, 17, 5) on a non-zero state; returns the new state. */
uint32_t pft_test_xorshift32(uint32_t *state);

/* The sum of four uniforms from the top 12 bits of four pft_test_xorshift32 steps, centred:
 * about N(0, 2365^2) (sd 1182 each). */
int32_t pft_test_noise_sum4(uint32_t *state);
/* About N(0, 1) in Q8.8 (sd 256): pft_test_noise_sum4 scaled by 256 / 2365. */
int32_t pft_test_noise_q88(uint32_t *state);

/* Compares two tables of rows x cols uint32 values bit for bit; on the first difference prints
 * "name <row_name> r column c: expected .. got .." (rows counted from 1) and fails the test. */
void pft_test_check_rows(const char *name, const char *row_name, const uint32_t *ref,
                         const uint32_t *val, size_t rows, size_t cols);

/* Guard words around a workspace: fill, then check nothing outside [lo, hi) changed. */
#define PFT_TEST_GUARD 0xA5u
void pft_test_guard_fill(uint8_t *buf, size_t len);
int pft_test_guard_intact(const uint8_t *buf, size_t len, size_t lo, size_t hi);
#endif
