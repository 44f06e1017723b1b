/*
 * The peak scan's products on a RES16 frame read in place (lib/src/tbd/tbd_meas.c,
 * peak_hrow_r16_ and peak_vrow_, docs/algorithms.md 2.11) against the arithmetic they replace.
 *
 * Known answer: pft_kmul_r16_(pft_kr16_tap_(t), a, b) is pft_kmula_(t, z) for z = the sum of
 * the two converted pixels pft_kres16_(a) + pft_kres16_(b) (what the scan computed on the
 * converted row), and pft_kmul_u_(t, z) is pft_kmula_(t, z) for taps in [0, 1] and |z| < 2^14;
 * pft_kmula_(1, z) is z. Equality bit for bit, no tolerance: the scan's peaks are chosen by
 * comparisons and ties of these values, so any other rounding could change the births. Every
 * int16 value a but the masked code is tried with several b (0, its neighbour, extremes) and
 * taps: 0, 1, the taps of PSF sigmas 0.5, 0.7, 1.0 and 2.0 at offset 0 (exp(-1 / (2 s^2))),
 * 2^-8 and 1 - 2^-16, odd values; pft_kmul_u_ over z spread through +-2^14 (both signs, the
 * values just below and above each multiple of 2^-16 boundary in q16, i.e. every 16-bit low
 * half near 0 and 2^15).
 *
 * The scan's rows on x86-64 (SSE2) and AArch64 (NEON; the hook pft_tbd_hrow_r16_ exists on
 * x86-64 and AArch64 q16, pft_tbd_integ_row_ on both in both builds, elsewhere the tests are
 * ignored): the horizontal sums of a RES16 row
 * (peak_hrow_r16_, in q16 by 16-bit multiply-adds) are peak_hrow_'s of the converted row bit for
 * bit, the vertical sums (peak_vrow_; the hook pft_tbd_vrow_ in q16 only, the centre tap 1's
 * rows from 16-bit products of the halves) are pft_kmula_'s, and the integration's bin row
 * (integ_row_, the inner bins eight at a time) is its general
 * form's (every bin by integ_bin_) word for word, with its sums: random rows with extremes, the
 * masked code, ties, the rounding's halves, values beyond the clamp (float: NaN, infinities,
 * both zeros).
 *
 * The particle kernel on a RES16 window (lib/src/tbd/tbd_int.h, pft_tbd_llr3_r16_):
 * pft_kspot3_r16_ on the frame's int16 pixels is pft_kspot3_ on the converted window (each
 * pixel pft_kres16_, a masked one 0) bit for bit, no tolerance (the log-weights decide
 * resampling, so any other rounding would change the tracks): 6000 windows of random pixels
 * (extremes, the masked code, small and large values) with separable PSF taps of sigma 0.5,
 * 0.7, 1.0 and 2.0 at window offsets across [-1/2, 1/2] (all of which pass
 * pft_kr16_sum_ok_, the float condition) and amplitudes 0.5 to 200. In float with 16-byte
 * vectors (SSE2, NEON) pft_kspot3_r16_ reads the window's first eight pixels in 16-bit lanes.
 * pft_kspot3_r16t_ (the taps and the window in one, in vector lanes; float with SSE2 or AArch64
 * NEON only) is pft_ktaps_ and then pft_kspot3_r16_ bit for bit on random windows and tap
 * tables (below).
 *
 * The weights' pass (tbd_filter.c, weights_) in float with 16-byte vectors: pft_kwexp_lanes_
 * is pft_kwexp_ of every value bit for bit (below).
 *
 * The search layer's births (lib/src/tbd/tbd_int.h): pft_tbd_birth_pix_v_ with the pass's
 * locals (pft_tbd_birth_inv_) gives the per-call form's (birth_pix_ref_ below: the config read
 * through its pointer, the intensity by pft_rng_uniform_range_) position, intensity and velocity
 * bits and leaves the generator in the same state, for 4000 random births: frame widths 1 to
 * 512, pitches, intensity ranges of equal ends, the default (10, 30), wide and narrow spans
 * (float: spans of one to three ulps, so that draws round up to i_max and take the float
 * below it), velocities drawn and not.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "pft_test_support.h"
#include "pft/pft_real.h"
#include "../../lib/src/core/kern_int.h"
#include "../../lib/src/tbd/tbd_int.h"

void setUp(void) {}
void tearDown(void) {}

static pft_real_t taps_[12];
static char msg_[160];
static uint32_t n_taps_;

/* The per-call birth, the reference of test_birth_pix_v_is_birth_pix_in: every value read
 * through the config, the intensity drawn by pft_rng_uniform_range_ with its own range tests. */
static void birth_pix_ref_(const pft_tbd_config_t *c, const pft_tbd_dyn_t *d, uint32_t p,
                           bool sample_vel, pft_rng_t *rng, const pft_tbd_kin_t *k)
{
    const uint32_t col = p % c->width;
    const uint32_t row = p / c->width;
    const pft_real_t ux = pft_from_u32_frac(pft_rng_next_(rng));
    const pft_real_t uy = pft_from_u32_frac(pft_rng_next_(rng));
    *k->x = pft_tbd_birth_coord_(col, ux, c->dx);
    *k->y = pft_tbd_birth_coord_(row, uy, c->dy);
    *k->in = pft_rng_uniform_range_(rng, c->i_min, c->i_max);
    if (sample_vel) {
        *k->vx = pft_kmad1_(c->vel_mean[0], d->vel_sd[0], pft_rng_zig_(rng));
        *k->vy = pft_kmad1_(c->vel_mean[1], d->vel_sd[1], pft_rng_zig_(rng));
    } else {
        *k->vx = c->vel_mean[0];
        *k->vy = c->vel_mean[1];
    }
}

static void make_taps_(void)
{
    static const double sig[4] = {0.5, 0.7, 1.0, 2.0};
    n_taps_ = 0u;
    taps_[n_taps_++] = PFT_C(0.0);
    taps_[n_taps_++] = PFT_REAL_ONE;
    for (int k = 0; k < 4; ++k) {
        taps_[n_taps_++] = pft_test_from_double(exp(-1.0 / (2.0 * sig[k] * sig[k])));
    }
    taps_[n_taps_++] = pft_test_from_double(1.0 / 256.0);
    taps_[n_taps_++] = pft_test_from_double(1.0 - 1.0 / 65536.0);
    taps_[n_taps_++] = pft_test_from_double(0.123456);
    taps_[n_taps_++] = pft_test_from_double(0.5);
    taps_[n_taps_++] = pft_test_from_double(0.999);
}

static void test_kmul_r16_is_kmula_of_the_converted_pixels(void)
{
    make_taps_();
    uint32_t bad = 0u;
    for (uint32_t k = 0; k < n_taps_; ++k) {
        const pft_real_t t = taps_[k];
        TEST_ASSERT_TRUE(pft_kr16_tap_ok_(t));
        const pft_real_t tp = pft_kr16_tap_(t);
        for (int32_t a = -32767; a <= 32767; ++a) {
            const int32_t bs[5] = {0, a > -32767 ? a - 1 : a, 32767, -32767, (a * 7) % 32768};
            for (int q = 0; q < 5; ++q) {
                const int16_t aa = (int16_t)a;
                const int16_t bb = (int16_t)bs[q];
                const pft_real_t want =
                    pft_kmula_(t, pft_kaddr_(pft_kres16_(aa), pft_kres16_(bb)));
                const pft_real_t got = pft_kmul_r16_(tp, aa, bb);
                if (memcmp(&want, &got, sizeof want) != 0 && bad++ == 0u) {
                    snprintf(msg_, sizeof msg_, "t %.9g a %d b %d: %.9g, pft_kmula_ %.9g",
                             pft_test_to_double(t), (int)aa, (int)bb, pft_test_to_double(got),
                             pft_test_to_double(want));
                }
            }
        }
    }
    TEST_ASSERT_EQUAL_UINT32_MESSAGE(0u, bad, msg_);
}

#if defined(__SSE2__) || (defined(PFT_NUMERIC_Q16) && defined(__aarch64__) && defined(__ARM_NEON))
/* A RES16 pixel for the row test: extremes, the masked code, 0, small and full-range values. */
static int16_t hrow_pix_(uint32_t *st)
{
    *st = *st * 1664525u + 1013904223u;
    const uint32_t r = *st >> 8;
    switch (r % 8u) {
    case 0u: return (int16_t)32767;
    case 1u: return (int16_t)-32767;
    case 2u: return PFT_RES16_MASKED;
    case 3u: return (int16_t)0;
    case 4u: return (int16_t)((int32_t)((r >> 3) % 1025u) - 512);
    default: return (int16_t)((int32_t)((r >> 3) % 65535u) - 32767);
    }
}

#endif

/* pft_tbd_hrow_r16_ (peak_hrow_r16_: the scan's horizontal sums on a RES16 row read in place;
 * in q16 with SSE2 the centre tap 1's columns eight at a time by 16-bit multiply-adds, with
 * AArch64 NEON by a widened pair sum and 32-bit multiply-adds) is
 * peak_hrow_ of the converted row bit for bit: hs[c] = pft_kaddr_(pft_kmula_(t1, z(c)),
 * pft_kmula_(t0, pft_kaddr_(z(c - 1), z(c + 1)))), z = pft_kres16_ of the pixel, a masked pixel
 * and the pixels outside the row 0. Widths 1 to 41 and 64 (whole eight-pixel steps, the tail,
 * rows shorter than a step), every tap as t0, t1 = 1 (the centre tap at offset 0, the fast
 * columns) and t1 = the tap of sigma 1 (the general columns), 60 random rows each. */
static void test_hrow_r16_is_peak_hrow_of_the_converted_row(void)
{
#if !(defined(__SSE2__) || (defined(PFT_NUMERIC_Q16) && defined(__aarch64__) && defined(__ARM_NEON)))
    TEST_IGNORE_MESSAGE("the hook pft_tbd_hrow_r16_ is built on x86-64 (SSE2) and AArch64 q16 only");
#else
    make_taps_();
    static uint8_t src[2u * 64u];
    static pft_real_t z[64];
    static pft_real_t got[64];
    uint32_t st = 12345u;
    uint32_t bad = 0u;
    uint32_t rows = 0u;
    const pft_real_t t1s[2] = {PFT_REAL_ONE, pft_test_from_double(exp(-0.5))};
    for (uint32_t w = 1u; w <= 64u; w = w < 41u ? w + 1u : 64u) {
        for (uint32_t k = 0; k < n_taps_; ++k) {
            for (uint32_t q = 0; q < 2u; ++q) {
                const pft_real_t t0 = taps_[k];
                const pft_real_t t1 = t1s[q];
                for (uint32_t n = 0; n < 60u; ++n) {
                    for (uint32_t c = 0; c < w; ++c) {
                        const int16_t v = hrow_pix_(&st);
                        memcpy(src + 2u * c, &v, 2u);
                        z[c] = v == PFT_RES16_MASKED ? PFT_C(0.0) : pft_kres16_(v);
                    }
                    pft_tbd_hrow_r16_(src, w, pft_kr16_tap_(t0), pft_kr16_tap_(t1), got);
                    ++rows;
                    for (uint32_t c = 0; c < w; ++c) {
                        const pft_real_t zl = c > 0u ? z[c - 1u] : PFT_C(0.0);
                        const pft_real_t zr = c + 1u < w ? z[c + 1u] : PFT_C(0.0);
                        const pft_real_t want =
                            pft_kaddr_(pft_kmula_(t1, z[c]), pft_kmula_(t0, pft_kaddr_(zl, zr)));
                        if (memcmp(&want, &got[c], sizeof want) != 0 && bad++ == 0u) {
                            snprintf(msg_, sizeof msg_, "w %u c %u t0 %.9g t1 %.9g: %.9g, want %.9g",
                                     (unsigned)w, (unsigned)c, pft_test_to_double(t0),
                                     pft_test_to_double(t1), pft_test_to_double(got[c]),
                                     pft_test_to_double(want));
                        }
                    }
                }
            }
        }
        if (w == 64u) {
            break;
        }
    }
    TEST_ASSERT_EQUAL_UINT32_MESSAGE(0u, bad, msg_);
    TEST_ASSERT_EQUAL_UINT32(42u * 2u * 60u * n_taps_, rows);
#endif
}

#if defined(__SSE2__) || (defined(__aarch64__) && defined(__ARM_NEON))
/* A PSF-matched value for the integration's row test: ties, halves of 1/64 (the rounding's
 * ties), values beyond the clamp at 257 sigmas, extremes, zeros (float: both signs, NaN). */
static pft_real_t integ_val_(uint32_t *st, const pft_real_t *prev)
{
    *st = *st * 1664525u + 1013904223u;
    const uint32_t r = *st >> 8;
    const double u = (double)((r >> 4) % 100000u) / 100000.0;
    switch (r % 12u) {
    case 0u: return prev != NULL ? *prev : PFT_C(0.0); /* a tie with the pixel before */
    case 1u: return pft_test_from_double((double)((int32_t)((r >> 4) % 2001u) - 1000) / 64.0 + 1.0 / 128.0);
    case 2u: return pft_test_from_double((u - 0.5) * 700.0); /* beyond +-257 sigmas now and then */
    case 3u: return pft_test_from_double(u < 0.5 ? 256.99 + u : -257.01 - u);
#ifdef PFT_NUMERIC_Q16
    case 4u: return u < 0.5 ? (pft_real_t)INT32_MAX : (pft_real_t)(INT32_MIN + 1);
    case 5u: return PFT_C(0.0);
#else
    case 4u: return u < 0.3 ? 1e30f : (u < 0.6 ? -1e30f : (u < 0.8 ? NAN : INFINITY));
    case 5u: return u < 0.5 ? 0.0f : -0.0f;
#endif
    default: return pft_test_from_double((u - 0.5) * 40.0);
    }
}

#endif

/* pft_tbd_integ_row_ (integ_row_: the inner bins through a branch-free loop, in float and q16
 * with SSE2 or NEON eight at a time, the word in 16-bit lanes) is its general form (every bin by integ_bin_) word
 * for word, sums and squares included: 3000 bin rows of random PSF-matched rows (widths 1 to
 * 70, odd and even), last-frame sums (the whole 16-bit range), shifts -4 .. 4 bins either way,
 * every bin row of a 5-row grid (the last without its second pixel row when the height is
 * odd), a_q 0, 1, 77, 128, 255 and 256, and 257 and 1000, above the fast form's bound (the
 * general path must be taken there: the 16-bit addend wraps from a_q mx >= 2^23). */
static void test_integ_row_is_its_general_form(void)
{
#if !(defined(__SSE2__) || (defined(__aarch64__) && defined(__ARM_NEON)))
    TEST_IGNORE_MESSAGE("the eight-bin form and the hook pft_tbd_integ_row_ are x86-64 (SSE2) and AArch64 (NEON) only");
#else
    static pft_real_t r0[72], r1[72];
    static uint16_t prev[36 * 5], cur_a[36 * 5], cur_b[36 * 5];
    static uint32_t vm_a[40], vm_b[40];
    static const uint32_t aqs[8] = {0u, 1u, 77u, 128u, 255u, 256u, 257u, 1000u};
    uint32_t st = 777u;
    uint32_t bad = 0u;
    uint32_t fast = 0u;
    for (uint32_t n = 0; n < 3000u; ++n) {
        st = st * 1664525u + 1013904223u;
        const uint32_t w = 1u + (st >> 8) % 70u;
        const uint32_t bw = (w + 1u) / 2u;
        pft_tbd_integ_t_ ig;
        ig.prev = prev;
        ig.cur = cur_a;
        ig.bw = bw;
        ig.bh = 5u;
        ig.sx = (int32_t)((st >> 16) % 9u) - 4;
        ig.sy = (int32_t)((st >> 20) % 9u) - 4;
        ig.a_q = aqs[(st >> 24) % 8u];
        const uint32_t br = (st >> 27) % 5u;
        const bool last_alone = br == 4u && ((st >> 3) & 1u) != 0u;
        for (uint32_t i = 0; i < bw * 5u; ++i) {
            st = st * 1664525u + 1013904223u;
            prev[i] = (uint16_t)(st >> 16);
        }
        for (uint32_t c = 0; c < w; ++c) {
            r0[c] = integ_val_(&st, c > 0u ? &r0[c - 1u] : NULL);
            r1[c] = integ_val_(&st, &r0[c]);
        }
        memset(cur_a, 0, sizeof cur_a);
        memset(cur_b, 0, sizeof cur_b);
        uint64_t sa[2] = {5u, 7u};
        uint64_t sb[2] = {5u, 7u};
        pft_tbd_integ_row_(&ig, br, r0, last_alone ? NULL : r1, w, vm_a, sa, false);
        ig.cur = cur_b;
        pft_tbd_integ_row_(&ig, br, r0, last_alone ? NULL : r1, w, vm_b, sb, true);
        /* the sums and squares added: the known answer from the row's stored words */
        uint64_t k0 = 5u;
        uint64_t k1 = 7u;
        for (uint32_t c = 0; c < bw; ++c) {
            const uint64_t v = (uint64_t)(cur_a[br * bw + c] >> 2);
            k0 += v;
            k1 += v * v;
        }
        if ((sa[0] != k0 || sa[1] != k1) && bad++ == 0u) {
            snprintf(msg_, sizeof msg_, "row %u w %u: sums %llu %llu, known %llu %llu", (unsigned)n,
                     (unsigned)w, (unsigned long long)sa[0], (unsigned long long)sa[1],
                     (unsigned long long)k0, (unsigned long long)k1);
        }
        fast += (!last_alone && bw >= 8u) ? 1u : 0u;
        if ((memcmp(cur_a, cur_b, sizeof cur_a) != 0 || sa[0] != sb[0] || sa[1] != sb[1]) &&
            bad++ == 0u) {
            uint32_t c = 0u;
            while (c + 1u < bw && cur_a[br * bw + c] == cur_b[br * bw + c]) {
                ++c;
            }
            snprintf(msg_, sizeof msg_, "row %u w %u bin %u sx %d a_q %u: %u, general %u",
                     (unsigned)n, (unsigned)w, (unsigned)c, (int)ig.sx, (unsigned)ig.a_q,
                     (unsigned)cur_a[br * bw + c], (unsigned)cur_b[br * bw + c]);
        }
    }
    TEST_ASSERT_EQUAL_UINT32_MESSAGE(0u, bad, msg_);
    TEST_ASSERT_TRUE(fast > 1000u); /* rows long enough for eight inner bins at a time */
#endif
}

/* pft_tbd_integ_skip_ (integ_scan_'s skip of the bins under the threshold; on AArch64 and
 * x86-64 eight 16-bit words per step) is the first bin from bc on whose word is above bound,
 * or bw, as the plain loop finds it: 20000 rows (widths 1 to 100) of words mostly at or below
 * the bound with a few above it (the bound's own value, one above it, the 16-bit range's ends),
 * bounds -1, 3, 65535 and random 4 l + 3, start bins anywhere in the row. */
static void test_integ_skip_is_the_plain_skip(void)
{
#if !(defined(__SSE2__) || (defined(__aarch64__) && defined(__ARM_NEON)))
    TEST_IGNORE_MESSAGE("the hook pft_tbd_integ_skip_ is built on x86-64 (SSE2) and AArch64 (NEON) only");
#else
    static uint16_t row[100];
    uint32_t st = 4242u;
    uint32_t bad = 0u;
    uint32_t far = 0u;
    uint32_t found = 0u;
    for (uint32_t n = 0; n < 20000u; ++n) {
        st = st * 1664525u + 1013904223u;
        const uint32_t bw = 1u + (st >> 8) % 100u;
        const uint32_t kind = (st >> 16) % 8u;
        const int32_t bound = kind == 0u ? -1 : (kind == 1u ? 3 : (kind == 2u ? 65535 :
                              4 * (int32_t)((st >> 4) % 16384u) + 3));
        const uint32_t rare = 1u + (st >> 20) % 64u; /* about one word in rare above */
        for (uint32_t c = 0; c < bw; ++c) {
            st = st * 1664525u + 1013904223u;
            const uint32_t r = st >> 8;
            int32_t v;
            if (r % rare == 0u) {
                v = (r >> 8) % 3u == 0u ? bound + 1 : ((r >> 8) % 3u == 1u ? 65535 : bound + 1 + (int32_t)((r >> 12) % 1000u));
            } else {
                v = (r >> 8) % 4u == 0u ? bound : ((r >> 8) % 4u == 1u ? 0 : bound - (int32_t)((r >> 12) % 70000u));
            }
            v = v < 0 ? 0 : (v > 65535 ? 65535 : v);
            row[c] = (uint16_t)v;
        }
        st = st * 1664525u + 1013904223u;
        const uint32_t bc = (st >> 8) % (bw + 1u);
        uint32_t want = bc;
        while (want < bw && (int32_t)row[want] <= bound) {
            ++want;
        }
        const uint32_t got = pft_tbd_integ_skip_(row, bc, bw, bound);
        far += want >= bc + 8u ? 1u : 0u;
        found += want < bw ? 1u : 0u;
        if (got != want && bad++ == 0u) {
            snprintf(msg_, sizeof msg_, "row %u bw %u bc %u bound %d: %u, plain %u", (unsigned)n,
                     (unsigned)bw, (unsigned)bc, (int)bound, (unsigned)got, (unsigned)want);
        }
    }
    TEST_ASSERT_EQUAL_UINT32_MESSAGE(0u, bad, msg_);
    TEST_ASSERT_TRUE(far > 2000u);   /* skips of eight words and more */
    TEST_ASSERT_TRUE(found > 2000u); /* a word above the bound found inside the row */
#endif
}

/* pft_tbd_vrow_ (peak_vrow_: the scan's vertical sums; in q16 with SSE2 the centre tap 1's rows
 * four columns at a time from 16-bit products of the values' halves: taps below 1/2, from 1/2
 * and 1 itself take three different corrections) is
 * pft_kaddr_(pft_kmula_(u1, mid), pft_kmula_(u0, pft_kaddr_(up, dn))) bit for bit: every tap
 * as u0 with u1 = 1 (the fast rows) and u1 = the tap of sigma 1 (the general rows), widths 1 to
 * 41, 40 random rows each with |up + dn| < 2^30 (q16: values below 2^14): both signs, zeros,
 * the products' halves (u0 z = 2^15 mod 2^16 for u0 = 1/2), the range's ends. */
static void test_vrow_is_kmula(void)
{
#if !(defined(__SSE2__) && defined(PFT_NUMERIC_Q16))
    TEST_IGNORE_MESSAGE("the hook pft_tbd_vrow_ is built in q16 on x86-64 (SSE2) only");
#else
    make_taps_();
    static pft_real_t up[48], mid[48], dn[48], got[48];
    const pft_real_t u1s[2] = {PFT_REAL_ONE, pft_test_from_double(exp(-0.5))};
    uint32_t st = 99u;
    uint32_t bad = 0u;
    for (uint32_t w = 1u; w <= 41u; ++w) {
        for (uint32_t k = 0; k < n_taps_; ++k) {
            for (uint32_t q = 0; q < 2u; ++q) {
                const pft_real_t u0 = taps_[k];
                const pft_real_t u1 = u1s[q];
                for (uint32_t n = 0; n < 40u; ++n) {
                    for (uint32_t c = 0; c < w; ++c) {
                        pft_real_t v[3];
                        for (uint32_t i = 0; i < 3u; ++i) {
                            st = st * 1664525u + 1013904223u;
                            const int32_t r = (int32_t)(st >> 2) - (int32_t)(1u << 29); /* +-2^29 */
                            switch ((st >> 27) % 6u) {
                            case 0u: v[i] = 0; break;
                            case 1u: v[i] = (pft_real_t)(((r >> 1) & ~65535) | 32768); break;
                            case 2u: v[i] = r < 0 ? -(pft_real_t)((1 << 29) - 1) : (pft_real_t)((1 << 29) - 1); break;
                            case 3u: v[i] = r % 70000; break;
                            default: v[i] = r; break;
                            }
                        }
                        up[c] = v[0];
                        mid[c] = v[1] / 4;
                        dn[c] = v[2];
                    }
                    pft_tbd_vrow_(up, mid, dn, w, u0, u1, got);
                    for (uint32_t c = 0; c < w; ++c) {
                        const pft_real_t want = pft_kaddr_(pft_kmula_(u1, mid[c]),
                                                           pft_kmula_(u0, pft_kaddr_(up[c], dn[c])));
                        if (want != got[c] && bad++ == 0u) {
                            snprintf(msg_, sizeof msg_, "w %u c %u u0 %d u1 %d z %d: %d, want %d",
                                     (unsigned)w, (unsigned)c, (int)u0, (int)u1,
                                     (int)(up[c] + dn[c]), (int)got[c], (int)want);
                        }
                    }
                }
            }
        }
    }
    TEST_ASSERT_EQUAL_UINT32_MESSAGE(0u, bad, msg_);
#endif
}

static void test_kmul_u_is_kmula(void)
{
    make_taps_();
    uint32_t bad = 0u;
    for (uint32_t k = 0; k < n_taps_; ++k) {
        const pft_real_t t = taps_[k];
        TEST_ASSERT_TRUE(pft_kmul_u_ok_(t));
        for (int32_t i = -40000; i <= 40000; ++i) {
            /* spread over +-2^14 (i 2^14 / 40000 in q16 bits, plus low halves near 0 and 2^15
             * in q16) */
            const double zd = (double)i * (16383.0 / 40000.0) + (double)(i % 7) * (1.0 / 65536.0);
            const pft_real_t z = pft_test_from_double(zd);
            const pft_real_t want = pft_kmula_(t, z);
            const pft_real_t got = pft_kmul_u_(t, z);
            if (memcmp(&want, &got, sizeof want) != 0 && bad++ == 0u) {
                snprintf(msg_, sizeof msg_, "t %.9g z %.9g: %.9g, pft_kmula_ %.9g",
                         pft_test_to_double(t), zd, pft_test_to_double(got),
                         pft_test_to_double(want));
            }
        }
        /* the centre tap 1: pft_kmula_(1, z) is z (peak_vrow_ adds the value itself) */
        for (int32_t i = -1000; i <= 1000; ++i) {
            const pft_real_t z = pft_test_from_double((double)i * 16.383 + 1.0 / 65536.0 * (i % 3));
            const pft_real_t one = pft_kmula_(PFT_REAL_ONE, z);
            TEST_ASSERT_EQUAL_MEMORY(&z, &one, sizeof z);
        }
    }
    TEST_ASSERT_EQUAL_UINT32_MESSAGE(0u, bad, msg_);
}

/* The three taps g((k - 1 - f)) of a unit-pitch PSF of sigma sg at offset f, and their sum
 * of squares, as the tap table holds them (lane 3). */
static void psf_taps_(double sg, double f, pft_real_t t[4])
{
    double ss = 0.0;
    for (int k = 0; k < 3; ++k) {
        const double d = (double)(k - 1) - f;
        const double g = exp(-d * d / (2.0 * sg * sg));
        t[k] = pft_test_from_double(g);
        ss += g * g;
    }
    t[3] = pft_test_from_double(ss);
}

static uint32_t lcg_(uint32_t *st)
{
    *st = *st * 1664525u + 1013904223u;
    return *st >> 8;
}

/* a random RES16 pixel from the draw r: masked, the clamp's +-32767, small, zero (with zeros;
 * else the wide case), or within +-3000 */
static int16_t rand_res16_(uint32_t r, bool zeros)
{
    switch (r % 8u) {
    case 0u: return INT16_MIN; /* PFT_RES16_MASKED */
    case 1u: return (r & 256u) != 0u ? (int16_t)32767 : (int16_t)-32767;
    case 2u: return (int16_t)((int32_t)(r >> 9) % 64 - 32);
    case 3u:
        if (zeros) {
            return 0;
        }
        break;
    default: break;
    }
    return (int16_t)((int32_t)(r >> 4) % 6000 - 3000);
}

static void test_kspot3_r16_is_kspot3_of_the_converted_window(void)
{
    enum { W = 5, H = 3 };
    static const double sig[4] = {0.5, 0.7, 1.0, 2.0};
    static const double amp[5] = {0.5, 3.0, 11.7, 47.25, 200.0};
    uint8_t frame[2u * W * H];
    pft_real_t z[9];
    uint32_t st = 12345u;
    uint32_t bad = 0u;
    for (uint32_t rep = 0; rep < 6000u; ++rep) {
        for (uint32_t q = 0; q < (uint32_t)(W * H); ++q) {
            const int16_t v = rand_res16_(lcg_(&st), false);
            memcpy(frame + 2u * q, &v, 2u);
        }
        pft_real_t tx[4], ty[4];
        const double sg = sig[rep % 4u];
        psf_taps_(sg, -0.5 + (double)(lcg_(&st) % 1024u) / 1024.0, tx);
        psf_taps_(sg, -0.5 + (double)(lcg_(&st) % 1024u) / 1024.0, ty);
        for (int k = 0; k < 3; ++k) {
            TEST_ASSERT_TRUE(pft_kr16_sum_ok_(tx[k], PFT_C(0.0)));
            TEST_ASSERT_TRUE(pft_kr16_sum_ok_(ty[k], PFT_C(0.0)));
        }
        const pft_real_t a = pft_test_from_double(amp[rep % 5u]);
        /* the window at column 1 of the three rows, rows 2 W bytes apart */
        const uint8_t *p = frame + 2u;
        for (uint32_t b = 0; b < 3u; ++b) {
            for (uint32_t c = 0; c < 3u; ++c) {
                int16_t v;
                memcpy(&v, p + (size_t)b * 2u * W + 2u * c, 2u);
                z[3u * b + c] = v != INT16_MIN ? pft_kres16_(v) : PFT_C(0.0);
            }
        }
        const pft_real_t want = pft_kspot3_(z, 3u, tx, ty, a);
        const pft_real_t got = pft_kspot3_r16_(p, 2u * W, tx, ty, a);
        if (memcmp(&want, &got, sizeof want) != 0 && bad++ == 0u) {
            snprintf(msg_, sizeof msg_, "window %u sigma %.1f a %.2f: %.9g, pft_kspot3_ %.9g",
                     (unsigned)rep, sg, amp[rep % 5u], pft_test_to_double(got),
                     pft_test_to_double(want));
        }
    }
    TEST_ASSERT_EQUAL_UINT32_MESSAGE(0u, bad, msg_);
}

/* pft_kspot3_r16t_ (the weighing loop's kernel in float with SSE2 or AArch64 NEON: the taps of
 * both axes and the window in one, the taps as vectors, the window's rows as lanes; ignored
 * elsewhere) is pft_ktaps_ of both tables' rows and then pft_kspot3_r16_ bit for bit, no
 * tolerance: 6000 windows of random pixels (the masked code, extremes, 0, small and large
 * values) at random row strides, random tables (64 rows; values in [0, 1.2), differences in
 * +-0.05, some 0) at random rows and fractions (0, 1 and between), amplitudes 0 and -5 to 35;
 * then windows whose every row sum is -0 (zero taps, pixels below 0 or masked), where a form
 * that added a +0 for an unused lane would give +0 (the NEON form's pairwise sums add -0). */
static void test_kspot3_r16t_is_taps_then_kspot3_r16(void)
{
#if defined(PFT_KSPOT3_R16T_LANES_)
    enum { W = 30, H = 3, ROWS = 64 };
    static pft_real_t tab[2][ROWS][8];
    uint8_t frame[2u * W * H];
    uint32_t st = 4242u;
    uint32_t bad = 0u, masked = 0u, negz = 0u;
    for (uint32_t rep = 0; rep < 6000u; ++rep) {
        for (uint32_t t = 0; t < 2u; ++t) {
            for (uint32_t r = 0; r < (uint32_t)ROWS; ++r) {
                for (uint32_t k = 0; k < 8u; ++k) {
                    const uint32_t u = lcg_(&st);
                    const double x = (double)(u % 65536u) / 65536.0;
                    tab[t][r][k] = (u >> 16) % 8u == 0u ? PFT_C(0.0)
                                   : k < 4u         ? pft_test_from_double(1.2 * x)
                                                    : pft_test_from_double(0.1 * (x - 0.5));
                }
            }
        }
        for (uint32_t q = 0; q < (uint32_t)(W * H); ++q) {
            const int16_t v = rand_res16_(lcg_(&st), true);
            memcpy(frame + 2u * q, &v, 2u);
        }
        pft_kfrac_t g[2];
        for (uint32_t t = 0; t < 2u; ++t) {
            const uint32_t u = lcg_(&st);
            g[t].n = (int32_t)(u % (uint32_t)ROWS);
            g[t].r = (u >> 6) % 4u == 0u ? (float)((u >> 8) % 2u) : (float)((u >> 8) % 1024u) / 1024.0f;
        }
        const uint32_t ua = lcg_(&st);
        const pft_real_t a = ua % 5u == 0u ? PFT_C(0.0)
                                           : pft_test_from_double((double)(ua % 4000u) / 100.0 - 5.0);
        const size_t stride = 2u * (3u + lcg_(&st) % (uint32_t)(W - 3)); /* 6 to 2 (W - 1) bytes */
        const uint8_t *p = frame + 2u * (lcg_(&st) % 3u);
        pft_real_t tx[4], ty[4];
        for (uint32_t b = 0; b < 3u; ++b) {
            for (uint32_t c = 0; c < 3u; ++c) {
                int16_t v;
                memcpy(&v, p + (size_t)b * stride + 2u * c, 2u);
                masked += v == INT16_MIN ? 1u : 0u;
            }
        }
        pft_ktaps_((const pft_real_t(*)[8])tab[0], g[0], tx);
        pft_ktaps_((const pft_real_t(*)[8])tab[1], g[1], ty);
        const pft_real_t want = pft_kspot3_r16_(p, stride, tx, ty, a);
        const pft_real_t got = pft_kspot3_r16t_(p, stride, (const pft_real_t(*)[8])tab[0], g[0],
                                                (const pft_real_t(*)[8])tab[1], g[1], a);
        if (memcmp(&want, &got, sizeof want) != 0 && bad++ == 0u) {
            snprintf(msg_, sizeof msg_, "window %u: %.9g, pft_ktaps_ and pft_kspot3_r16_ %.9g",
                     (unsigned)rep, pft_test_to_double(got), pft_test_to_double(want));
        }
    }
    TEST_ASSERT_TRUE(masked > 1000u);
    TEST_ASSERT_EQUAL_UINT32_MESSAGE(0u, bad, msg_);
    /* every tap 0: each product tx v of a pixel v < 0 is -0, so is each row sum, the window
     * sum and the result (a (s1 - 0): -0 for a >= 0); a masked pixel's +0 times 0 is +0, and a
     * row with one keeps -0 only where another product is -0 (-0 + +0 is +0) */
    memset(tab, 0, sizeof tab);
    for (uint32_t rep = 0; rep < 64u; ++rep) {
        for (uint32_t q = 0; q < (uint32_t)(W * H); ++q) {
            const uint32_t u = lcg_(&st);
            const int16_t v = u % 16u == 0u ? INT16_MIN : (int16_t)(-1 - (int32_t)((u >> 8) % 32767u));
            memcpy(frame + 2u * q, &v, 2u);
        }
        pft_kfrac_t g[2];
        for (uint32_t t = 0; t < 2u; ++t) {
            g[t].n = (int32_t)(lcg_(&st) % (uint32_t)ROWS);
            g[t].r = (float)(rep % 3u) / 2.0f;
        }
        const pft_real_t a = rep % 2u == 0u ? PFT_C(0.0) : PFT_C(1.5);
        const size_t stride = 2u * (3u + lcg_(&st) % (uint32_t)(W - 3));
        const uint8_t *p = frame + 2u * (lcg_(&st) % 3u);
        pft_real_t tx[4], ty[4];
        pft_ktaps_((const pft_real_t(*)[8])tab[0], g[0], tx);
        pft_ktaps_((const pft_real_t(*)[8])tab[1], g[1], ty);
        const pft_real_t want = pft_kspot3_r16_(p, stride, tx, ty, a);
        const pft_real_t got = pft_kspot3_r16t_(p, stride, (const pft_real_t(*)[8])tab[0], g[0],
                                                (const pft_real_t(*)[8])tab[1], g[1], a);
        negz += signbit(want) ? 1u : 0u;
        if (memcmp(&want, &got, sizeof want) != 0 && bad++ == 0u) {
            snprintf(msg_, sizeof msg_, "zero taps, window %u: %.9g (sign %d), want %.9g (sign %d)",
                     (unsigned)rep, pft_test_to_double(got), signbit(got) ? 1 : 0,
                     pft_test_to_double(want), signbit(want) ? 1 : 0);
        }
    }
    TEST_ASSERT_TRUE(negz > 16u);
    TEST_ASSERT_EQUAL_UINT32_MESSAGE(0u, bad, msg_);
#else
    TEST_IGNORE_MESSAGE("pft_kspot3_r16t_ is built in float with SSE2 or AArch64 NEON only");
#endif
}

/* The weights' pass in 16-byte vectors (float with SSE2 or NEON; tbd_filter.c, weights_):
 * pft_kwexp_lanes_ of a row is pft_kwexp_ of each value bit for bit, no tolerance (the weights
 * drive the resampling): rows of 0 and -0 (an E = 0 particle's log-weight), the maximum itself,
 * values above it, just inside and outside (-87, 0) from it, the Bernoulli form's drop value,
 * -infinity, and spread values, for maxima 0, positive, negative and the drop value; rows of
 * odd lengths, so that the vector loop's remainder runs too. */
static void test_kwexp_lanes_is_kwexp(void)
{
#if defined(PFT_KWEXP_LANES_)
    static const float ms[5] = {0.0f, 12.625f, -3.5f, 61.0f, -30000.0f};
    float row[67];
    float want[67];
    uint32_t st = 777u;
    uint32_t bad = 0u;
    uint32_t ones = 0u, zeros = 0u, mids = 0u;
    for (uint32_t rep = 0; rep < 3000u; ++rep) {
        const float m = ms[rep % 5u];
        const uint32_t n = 1u + lcg_(&st) % 67u;
        for (uint32_t s = 0; s < n; ++s) {
            const uint32_t r = lcg_(&st);
            const float u = (float)(r >> 8) / 16777216.0f; /* [0, 1) */
            float v;
            switch (r % 11u) {
            case 0u: v = 0.0f; break;
            case 1u: v = -0.0f; break;
            case 2u: v = m; break;
            case 3u: v = m + 1.0f + u; break;
            case 4u: v = m - 87.0f + (u - 0.5f) * 1e-3f; break;
            case 5u: v = m - 87.0f; break;
            case 6u: v = -30000.0f; break;
            case 7u: v = -INFINITY; break;
            case 8u: v = m - u * 1e-5f; break;
            default: v = m - u * 100.0f; break;
            }
            row[s] = v;
            want[s] = pft_kwexp_(v, m);
            ones += want[s] == 1.0f ? 1u : 0u;
            zeros += want[s] == 0.0f ? 1u : 0u;
            mids += want[s] > 0.0f && want[s] < 1.0f ? 1u : 0u;
        }
        pft_kwexp_lanes_(row, n, m);
        for (uint32_t s = 0; s < n; ++s) {
            if (memcmp(&row[s], &want[s], sizeof want[s]) != 0 && bad++ == 0u) {
                snprintf(msg_, sizeof msg_, "row %u value %u (max %.3f): %.9g, pft_kwexp_ %.9g",
                         (unsigned)rep, (unsigned)s, (double)m, (double)row[s], (double)want[s]);
            }
        }
    }
    TEST_ASSERT_EQUAL_UINT32_MESSAGE(0u, bad, msg_);
    /* every outcome of the tests was met */
    TEST_ASSERT_TRUE(ones > 1000u && zeros > 1000u && mids > 1000u);
#else
    TEST_IGNORE_MESSAGE("no vector form of the weights in this build");
#endif
}

void test_birth_pix_v_is_birth_pix_in(void)
{
    uint32_t st = 4242u;
    uint32_t bad = 0u;
    uint32_t tops = 0u; /* float: draws at the float below i_max (rounded up to it, or on it) */
    for (uint32_t rep = 0; rep < 4000u; ++rep) {
        pft_tbd_config_t c;
        pft_tbd_dyn_t d;
        pft_real_t o[2][5];
        pft_rng_t r0, r1;
        memset(&c, 0, sizeof c);
        memset(&d, 0, sizeof d);
        c.width = 1u + lcg_(&st) % 512u;
        const uint32_t h = 1u + lcg_(&st) % 512u;
        c.dx = pft_test_from_double(0.25 + (double)(lcg_(&st) % 1000u) / 256.0);
        c.dy = pft_test_from_double(0.25 + (double)(lcg_(&st) % 1000u) / 256.0);
        switch (lcg_(&st) % 5u) {
        case 0u: c.i_min = PFT_C(10.0); c.i_max = PFT_C(30.0); break;
        case 1u: c.i_min = pft_test_from_double((double)(lcg_(&st) % 400u) / 8.0); c.i_max = c.i_min; break;
        case 2u: c.i_min = PFT_C(0.0); c.i_max = pft_test_from_double((double)(1u + lcg_(&st) % 30000u)); break;
        case 3u:
            c.i_min = pft_test_from_double((double)(lcg_(&st) % 4000u) / 16.0);
#ifdef PFT_NUMERIC_Q16
            c.i_max = c.i_min + (pft_real_t)(1u + lcg_(&st) % 3u);
#else
            c.i_max = c.i_min;
            for (uint32_t q = 1u + lcg_(&st) % 3u; q > 0u; --q) {
                c.i_max = nextafterf(c.i_max, INFINITY);
            }
#endif
            break;
        default: c.i_min = pft_test_from_double((double)(lcg_(&st) % 400u) / 8.0);
                 c.i_max = pft_test_from_double((double)(lcg_(&st) % 400u) / 8.0); break;
        }
        c.vel_mean[0] = pft_test_from_double((double)(lcg_(&st) % 600u) / 100.0 - 3.0);
        c.vel_mean[1] = pft_test_from_double((double)(lcg_(&st) % 600u) / 100.0 - 3.0);
        d.vel_sd[0] = pft_test_from_double((double)(lcg_(&st) % 200u) / 100.0);
        d.vel_sd[1] = pft_test_from_double((double)(lcg_(&st) % 200u) / 100.0);
        {
            const bool sv = (lcg_(&st) & 1u) != 0u;
            const uint32_t p = lcg_(&st) % (c.width * h);
            pft_tbd_kin_t k0 = {&o[0][0], &o[0][1], &o[0][2], &o[0][3], &o[0][4]};
            pft_tbd_kin_t k1 = {&o[1][0], &o[1][1], &o[1][2], &o[1][3], &o[1][4]};
            pft_tbd_birth_inv_t b;
            memset(o, 0x55, sizeof o);
            pft_rng_seed(&r0, lcg_(&st));
            r1 = r0;
            birth_pix_ref_(&c, &d, p, sv, &r0, &k0);
            b = pft_tbd_birth_inv_(&c, &d);
            pft_tbd_birth_pix_v_(&b, p, sv, &r1, &k1);
        }
        if ((memcmp(o[0], o[1], sizeof o[0]) != 0 || memcmp(&r0, &r1, sizeof r0) != 0) &&
            bad++ == 0u) {
            snprintf(msg_, sizeof msg_, "birth %u: x %.9g %.9g, intensity %.9g %.9g", (unsigned)rep,
                     (double)o[0][0], (double)o[1][0], (double)o[0][4], (double)o[1][4]);
        }
#ifndef PFT_NUMERIC_Q16
        tops += c.i_min < c.i_max && o[0][4] == nextafterf(c.i_max, c.i_min) ? 1u : 0u;
#endif
    }
    TEST_ASSERT_EQUAL_UINT32_MESSAGE(0u, bad, msg_);
#ifndef PFT_NUMERIC_Q16
    TEST_ASSERT_TRUE(tops > 50u); /* the narrow spans were met */
#else
    (void)tops;
#endif
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_kmul_r16_is_kmula_of_the_converted_pixels);
    RUN_TEST(test_kmul_u_is_kmula);
    RUN_TEST(test_hrow_r16_is_peak_hrow_of_the_converted_row);
    RUN_TEST(test_integ_row_is_its_general_form);
    RUN_TEST(test_integ_skip_is_the_plain_skip);
    RUN_TEST(test_vrow_is_kmula);
    RUN_TEST(test_kspot3_r16_is_kspot3_of_the_converted_window);
    RUN_TEST(test_kspot3_r16t_is_taps_then_kspot3_r16);
    RUN_TEST(test_kwexp_lanes_is_kwexp);
    RUN_TEST(test_birth_pix_v_is_birth_pix_in);
    return UNITY_END();
}
