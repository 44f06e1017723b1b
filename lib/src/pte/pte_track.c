/* PTE-TBD, Step 3 (docs/algorithms.md 5.3): one track at one frame. Operator geometry from
 * the predicted state, matched operators along L directions (EXACT taps, or reads of the
 * TABLE responses), direction likelihoods, per-direction Kalman updates, fusion, detection
 * and maintenance. */
#include "pte_int.h"
#include "../core/q16_int.h"

#define SV_ PFT_PTE_SV_
#define SA_ PFT_PTE_SA_
/* TABLE: the age at which a float build sums a slope entry afresh, and the lines a slope
 * entry holds beyond the scan interval on each side (see the slope bank) */
#define RENEW_ 256u
#define MARGIN_ 6
/* TABLE: cells per block of lazily computed responses */
#define YBLK_ 8
/* line_budget's currency (docs/algorithms.md 5.8): units of one line x frame sum. A response
 * block computed costs BLK_UNITS_ units and each frame of a line set's edge correction
 * (bank_g_) EDGE_ROW_UNITS_ units plus 1 per point corrected: their instructions over the
 * mean instructions of one line x frame sum of the bank (callgrind, the soak's pte work
 * sample; docs/results/pte.md "Branch ptework4"). */
#ifdef PFT_NUMERIC_Q16
#define BLK_UNITS_ 116u
#define EDGE_ROW_UNITS_ 4u
#else
#define BLK_UNITS_ 47u
#define EDGE_ROW_UNITS_ 4u
#endif

/* v as a signed 16.16 fixed-point integer (any range of pft_real_t, both builds). */
static int64_t fix16_(pft_real_t v)
{
    int32_t ip = pft_floor_int(v);
    pft_real_t fr = pft_sub(v, pft_from_int(ip));
    return (int64_t)ip * 65536 + 2 * (int64_t)pft_round_int(pft_mul_i(fr, 32768));
}

/* A signed 16.16 fixed-point integer as a real (q16: the same bits, saturated). */
static pft_real_t from_fix16_(int64_t v)
{
#ifdef PFT_NUMERIC_Q16
    return v > (int64_t)PFT_REAL_MAX ? PFT_REAL_MAX
                                     : (v < (int64_t)PFT_REAL_MIN ? PFT_REAL_MIN : (pft_real_t)v);
#else
    return (pft_real_t)v * (1.0f / 65536.0f);
#endif
}

/* ------------------------------------------------------------ square root, divisions, exp */

#ifdef PFT_NUMERIC_Q16
/* The number layer's q16 kernels inline (lib/src/core/q16_int.h: the same bits as pft_sqrt,
 * pft_div, pft_recip, pft_div_i and pft_exp, without the calls): the track step divides about
 * 20 times per step and takes a square root and exps per direction. docs/fixed_point.md,
 * "PTE-TBD Kalman algebra and square root". */
static inline pft_real_t sqrt_(pft_real_t a) { return pft_q16_sqrt_(a); }
static inline pft_real_t div_(pft_real_t a, pft_real_t b) { return pft_q16_div_(a, b); }
static inline pft_real_t recip_(pft_real_t a) { return pft_q16_div_(PFT_REAL_ONE, a); }
static inline pft_real_t div_i_(pft_real_t a, int32_t k) { return pft_q16_div_i_(a, k); }
/* exp(x) for -12 < x <= 0 (the direction scan's terms and the fusion weights; both callers
 * prove the domain) as a product of three tables: u = -x < 12 2^16 < 2^20 splits into
 * u = 2^13 a + 2^6 b + c (a < 96, b < 128, c < 64) and exp(-u 2^-16) = exp(-a/8) exp(-b/1024)
 * exp(-c/65536), each entry round(2^31 exp(-i step)) (host_tools/scripts/pte_exp_tables.py);
 * the first product rounded to Q32, the second to Q16. Error: at most 0.50003 LSB from exp;
 * against pft_exp (Horner of degree 11) the result differs on 6 of the 786,432 arguments of
 * the domain, by 1 LSB, each within 2.1e-5 LSB of a rounding tie (docs/fixed_point.md,
 * "PTE-TBD exp by three tables"). About 15 instructions instead of about 80. */
static inline pft_real_t exp_neg_(pft_real_t x)
{
    static const uint32_t exp_hi_[96] = {
        2147483648u, 1895147668u, 1672461947u, 1475942488u, 1302514674u, 1149465165u,
        1014399448u, 895204371u, 790015084u, 697185865u, 615264366u, 542968898u,
        479168370u, 422864603u, 373176702u, 329327284u, 290630308u, 256480346u,
        226343111u, 199747095u, 176276192u, 155563194u, 137284037u, 121152737u,
        106916915u, 94353846u, 83266977u, 73482850u, 64848387u, 57228501u,
        50503975u, 44569601u, 39332535u, 34710840u, 30632209u, 27032830u,
        23856388u, 21053189u, 18579374u, 16396240u, 14469631u, 12769405u,
        11268960u, 9944822u, 8776275u, 7745035u, 6834970u, 6031840u,
        5323080u, 4697601u, 4145619u, 3658496u, 3228611u, 2849239u,
        2514445u, 2218990u, 1958252u, 1728151u, 1525088u, 1345885u,
        1187740u, 1048177u, 925013u, 816321u, 720401u, 635751u,
        561048u, 495124u, 436945u, 385603u, 340293u, 300308u,
        265021u, 233880u, 206398u, 182146u, 160743u, 141855u,
        125187u, 110477u, 97496u, 86040u, 75930u, 67008u,
        59134u, 52186u, 46054u, 40642u, 35867u, 31652u,
        27933u, 24651u, 21754u, 19198u, 16942u, 14951u,
    };
    static const uint32_t exp_mid_[128] = {
        2147483648u, 2145387520u, 2143293437u, 2141201399u, 2139111403u, 2137023446u,
        2134937528u, 2132853646u, 2130771798u, 2128691982u, 2126614195u, 2124538438u,
        2122464706u, 2120392998u, 2118323312u, 2116255647u, 2114190000u, 2112126369u,
        2110064753u, 2108005148u, 2105947554u, 2103891969u, 2101838390u, 2099786815u,
        2097737243u, 2095689671u, 2093644098u, 2091600522u, 2089558940u, 2087519352u,
        2085481754u, 2083446144u, 2081412522u, 2079380885u, 2077351231u, 2075323558u,
        2073297864u, 2071274147u, 2069252406u, 2067232638u, 2065214841u, 2063199014u,
        2061185155u, 2059173262u, 2057163332u, 2055155364u, 2053149356u, 2051145306u,
        2049143212u, 2047143072u, 2045144885u, 2043148648u, 2041154360u, 2039162018u,
        2037171621u, 2035183166u, 2033196653u, 2031212079u, 2029229441u, 2027248739u,
        2025269970u, 2023293133u, 2021318225u, 2019345245u, 2017374191u, 2015405061u,
        2013437852u, 2011472564u, 2009509194u, 2007547741u, 2005588202u, 2003630576u,
        2001674861u, 1999721054u, 1997769155u, 1995819161u, 1993871070u, 1991924881u,
        1989980591u, 1988038199u, 1986097703u, 1984159101u, 1982222392u, 1980287573u,
        1978354642u, 1976423598u, 1974494439u, 1972567163u, 1970641768u, 1968718253u,
        1966796615u, 1964876853u, 1962958964u, 1961042948u, 1959128802u, 1957216524u,
        1955306112u, 1953397566u, 1951490882u, 1949586060u, 1947683096u, 1945781990u,
        1943882740u, 1941985344u, 1940089800u, 1938196105u, 1936304260u, 1934414261u,
        1932526106u, 1930639795u, 1928755325u, 1926872694u, 1924991901u, 1923112944u,
        1921235820u, 1919360529u, 1917487069u, 1915615437u, 1913745632u, 1911877652u,
        1910011495u, 1908147160u, 1906284645u, 1904423947u, 1902565066u, 1900707999u,
        1898852745u, 1896999302u,
    };
    static const uint32_t exp_lo_[64] = {
        2147483648u, 2147450880u, 2147418113u, 2147385346u, 2147352580u, 2147319814u,
        2147287049u, 2147254284u, 2147221520u, 2147188756u, 2147155993u, 2147123230u,
        2147090468u, 2147057706u, 2147024945u, 2146992184u, 2146959424u, 2146926664u,
        2146893905u, 2146861146u, 2146828388u, 2146795630u, 2146762873u, 2146730116u,
        2146697360u, 2146664604u, 2146631849u, 2146599094u, 2146566340u, 2146533586u,
        2146500833u, 2146468080u, 2146435328u, 2146402576u, 2146369825u, 2146337074u,
        2146304324u, 2146271574u, 2146238825u, 2146206076u, 2146173328u, 2146140580u,
        2146107833u, 2146075086u, 2146042340u, 2146009594u, 2145976849u, 2145944104u,
        2145911360u, 2145878616u, 2145845873u, 2145813130u, 2145780388u, 2145747646u,
        2145714905u, 2145682164u, 2145649424u, 2145616684u, 2145583945u, 2145551206u,
        2145518468u, 2145485730u, 2145452993u, 2145420256u,
    };
    const uint32_t u = (uint32_t)(-x); /* x > -12: 0 <= u < 786432 */
    uint64_t v = (uint64_t)exp_hi_[u >> 13] * exp_mid_[(u >> 6) & 127u]; /* Q62 */
    v = (v + ((uint64_t)1 << 29)) >> 30;                                 /* Q32, < 2^33 */
    v = v * exp_lo_[u & 63u];                                            /* Q63, < 2^64 */
    return (pft_real_t)((v + ((uint64_t)1 << 46)) >> 47);
}
#else
static inline pft_real_t exp_neg_(pft_real_t x) { return pft_exp(x); }
static inline pft_real_t sqrt_(pft_real_t a) { return pft_sqrt(a); }
static inline pft_real_t div_(pft_real_t a, pft_real_t b) { return pft_div(a, b); }
static inline pft_real_t recip_(pft_real_t a) { return pft_recip(a); }
static inline pft_real_t div_i_(pft_real_t a, int32_t k) { return pft_div_i(a, k); }
#endif

/* ------------------------------------------------------------ wide accumulation */

/* Sums of products rounded once (q16: exact Q32.32 products in int64; float: float), for the
 * small Kalman algebra of a track step. q16: aadd_ is a plain int64 sum. Every call site
 * adds terms whose magnitudes are bounded so that no partial sum can reach 2^63 (operands
 * are pft_real_t in [-INT32_MAX, INT32_MAX], so a product is below 2^62; the bound of each
 * site is stated there and in docs/fixed_point.md, "PTE-TBD Kalman algebra and square
 * root"): the same values as the saturating sum it replaces. aadd_sat_ saturates, for the one sum that has no
 * such bound (the fusion's covariance start). */
#ifdef PFT_NUMERIC_Q16
typedef int64_t acc_t;
static inline acc_t amul_(pft_real_t a, pft_real_t b) { return (int64_t)a * b; }
static inline acc_t afrom_(pft_real_t a) { return (int64_t)a * 65536; }
static inline acc_t aadd_(acc_t x, acc_t y) { return x + y; }
static inline acc_t aadd_sat_(acc_t x, acc_t y)
{
    if (y > 0 && x > INT64_MAX - y) {
        return INT64_MAX;
    }
    if (y < 0 && x < -INT64_MAX - y) {
        return -INT64_MAX;
    }
    return x + y;
}
/* to Q16.16, rounded to nearest (ties as pft_mul), saturated */
static inline pft_real_t ato_(acc_t v)
{
    int64_t r = (v >= 0 ? v + 32768 : v + 32767) >> 16;
    return r > INT32_MAX ? PFT_REAL_MAX : (r < -INT32_MAX ? PFT_REAL_MIN : (pft_real_t)r);
}
/* num / den for den > 0 (both accumulators), rounded, saturated */
static inline pft_real_t adiv_(acc_t num, acc_t den)
{
    const int64_t lim = (int64_t)1 << 46;
    int64_t q;
    if (num < lim && num > -lim) {
        int64_t n = num * 65536;
        q = (n >= 0 ? n + den / 2 : n - den / 2) / den;
    } else {
        q = num / den;
        q = q > ((int64_t)1 << 16) ? ((int64_t)1 << 32) : (q < -((int64_t)1 << 16) ? -((int64_t)1 << 32) : q * 65536);
    }
    return q > INT32_MAX ? PFT_REAL_MAX : (q < -INT32_MAX ? PFT_REAL_MIN : (pft_real_t)q);
}
/* max(e, 0)^2 / g (0 when g <= 0), clamped at 22500 = 150^2: the squared operator statistic */
static inline pft_real_t sq_over_(pft_real_t e, pft_real_t g)
{
    if (e <= 0 || g <= 0) {
        return 0;
    }
    int64_t q = ((int64_t)e * e + g / 2) / g;
    return q > (int64_t)22500 * 65536 ? (pft_real_t)(22500 * 65536) : (pft_real_t)q;
}
/* A response of the TABLE operators (yblock_): the exact Q32 products of its taps summed in
 * int64 and rounded once, half up (docs/fixed_point.md, "PTE-TBD response blocks rounded
 * once") */
typedef int64_t yacc_t;
static inline yacc_t yterm_(pft_real_t w, pft_real_t z) { return (int64_t)w * z; }
static inline pft_real_t yround_(yacc_t v) { return (pft_real_t)((v + 32768) >> 16); }
/* pft_mul(t2, 0.5) for 0 <= t2 <= 22500 (sq_over_'s range): (32768 t2 + 32768) >> 16 =
 * (t2 + 1) >> 1, never near saturation; the same bits without the 64-bit product */
static inline pft_real_t half_t2_(pft_real_t t2) { return (t2 + 1) >> 1; }
#else
static inline pft_real_t half_t2_(pft_real_t t2) { return t2 * 0.5f; }
static inline pft_real_t mul_nb_(pft_real_t a, pft_real_t b) { return a * b; }
typedef float yacc_t;
static inline yacc_t yterm_(pft_real_t w, pft_real_t z) { return w * z; }
static inline pft_real_t yround_(yacc_t v) { return v; }
typedef float acc_t;
static inline acc_t amul_(pft_real_t a, pft_real_t b) { return a * b; }
static inline acc_t afrom_(pft_real_t a) { return a; }
static inline acc_t aadd_(acc_t x, acc_t y) { return x + y; }
static inline acc_t aadd_sat_(acc_t x, acc_t y) { return x + y; }
static inline pft_real_t ato_(acc_t v) { return v; }
static inline pft_real_t adiv_(acc_t num, acc_t den) { return num / den; }
static inline pft_real_t sq_over_(pft_real_t e, pft_real_t g)
{
    if (!(e > 0.0f) || !(g > 0.0f)) {
        return 0.0f;
    }
    return pft_min(e * e / g, 22500.0f);
}
/* v when c is 1, +0 when c is 0, by a mask of its bits (selects of a float on the sign of
 * another one keep gcc from vectorising a loop under the default -ftrapping-math) */
static inline pft_real_t keep_if_(pft_real_t v, int c)
{
    uint32_t u;
    memcpy(&u, &v, sizeof(u));
    u &= 0u - (uint32_t)c;
    memcpy(&v, &u, sizeof(v));
    return v;
}
/* sq_over_ without branches, the same value for every input (the quotient is formed always and
 * kept only when e > 0 and g > 0; otherwise +0 as sq_over_'s 0.0f), for loops gcc vectorises */
static inline pft_real_t sq_over_v_(pft_real_t e, pft_real_t g)
{
    const pft_real_t t = e * e / g;
    return keep_if_(t < 22500.0f ? t : 22500.0f, (e > 0.0f) & (g > 0.0f));
}
/* out[j] = half_t2_(sq_over_v_(E[j], G[j])) for j < n; restrict parameters (sL, the E sums and
 * G are distinct arrays), so the vector loop needs no run-time overlap test */
static inline void half_t2_rows_(pft_real_t *restrict out, const pft_real_t *restrict E,
                                 const pft_real_t *restrict G, int32_t n)
{
    for (int32_t j = 0; j < n; ++j) {
        out[j] = half_t2_(sq_over_v_(E[j], G[j]));
    }
}
#endif

/* ----------------------------------------------------------------- TABLE operators */

/* TABLE operators: tap weights of each grid phase (width sigma_y = sigma_r, clamped) and the
 * normaliser sum g^2 of every response point (edges included). */
void pft_pte_ytable_setup_(pft_pte_t *p)
{
    const int32_t q = p->yq;
    const int32_t nr = p->cfg.in.n_range;
    p->sigma_y = pft_min(p->cfg.sigma_r[0], p->cfg.sigma_w_max);
    /* slope lattice: dtheta_min cells per frame, in 1/65536 grid points per frame and as a
     * scaled slope (exact when yq divides SV) */
    p->lat_u = fix16_(pft_mul_i(p->cfg.dtheta_min, q));
    p->lat_u = p->lat_u < 1 ? 1 : p->lat_u;
    /* block of a response point: a shift when YBLK_ q is a power of two */
    p->yblk_shift = 0u;
    for (uint32_t k = 1; k < 12u; ++k) {
        if (((int32_t)1 << k) == YBLK_ * q) {
            p->yblk_shift = (uint8_t)k;
        }
    }
    p->lat_t = (p->lat_u * SV_ + q / 2) / q;
    p->lat_t = p->lat_t < 1 ? 1 : p->lat_t;
    pft_real_t inv = recip_(p->sigma_y);
    pft_real_t reach = pft_mul_i(p->sigma_y, 3);
    for (int32_t ph = 0; ph < q; ++ph) {
        pft_real_t f = pft_ratio(ph, q);
        int32_t lo = -pft_floor_int(pft_neg(pft_sub(f, reach)));
        int32_t hi = pft_floor_int(pft_add(f, reach));
        if (hi - lo + 1 > (int32_t)PFT_PTE_MAX_TAPS) {
            hi = lo + (int32_t)PFT_PTE_MAX_TAPS - 1;
        }
        int32_t n = hi >= lo ? hi - lo + 1 : 0;
        for (int32_t k = 0; k < n; ++k) {
            pft_real_t t = pft_mul(pft_abs(pft_sub(pft_from_int(lo + k), f)), inv);
            int32_t idx = pft_round_int(pft_mul_i(t, 64));
            p->ytap[ph][k] = idx < (int32_t)PFT_PTE_GTAB_SIZE ? p->gtab[idx] : PFT_C(0.0);
        }
        p->ytap_lo[ph] = (int16_t)lo;
        p->ytap_n[ph] = (uint8_t)n;
    }
    /* the same taps padded to 4 per phase from the smallest first offset, when they fit */
    int32_t lo4 = 0;
    int32_t hi4 = -1;
    for (int32_t ph = 0; ph < q; ++ph) {
        lo4 = ph == 0 || p->ytap_lo[ph] < lo4 ? p->ytap_lo[ph] : lo4;
        hi4 = ph == 0 || p->ytap_lo[ph] + p->ytap_n[ph] - 1 > hi4 ? p->ytap_lo[ph] + p->ytap_n[ph] - 1 : hi4;
    }
    p->ytap4 = (uint8_t)(hi4 - lo4 + 1 <= 4 ? 1 : 0);
    p->ytap4_lo = (int16_t)lo4;
    memset(p->ytap4_w, 0, sizeof(p->ytap4_w));
    for (int32_t ph = 0; ph < q && p->ytap4; ++ph) {
        for (int32_t k = 0; k < p->ytap_n[ph]; ++k) {
            p->ytap4_w[ph][p->ytap_lo[ph] - lo4 + k] = p->ytap[ph][k];
        }
    }
    /* the normaliser of a point whose taps all lie on the profile, per phase, and the range of
     * such points (the slope bank's G per residue holds there) */
    for (int32_t ph = 0; ph < q; ++ph) {
        pft_real_t g2 = PFT_C(0.0);
        for (int32_t k = 0; k < p->ytap_n[ph]; ++k) {
            g2 = pft_add(g2, pft_sq(p->ytap[ph][k]));
        }
        p->gfull[ph] = g2;
        p->gfull[ph + q] = g2; /* a second period: gfull[r + o] for r, o < q needs no wrap */
    }
    /* per response point, its own normaliser minus the interior one of its phase (0 in the
     * interior): the correction bank_g_ adds where a line leaves the interior. Plain
     * difference: |g2|, |gfull| <= 6.9, no saturation. */
    for (uint32_t i = 0; i < p->ny; ++i) {
        int32_t ph = (int32_t)i % q;
        int32_t u0 = (int32_t)i / q - (int32_t)PFT_PTE_YPAD + p->ytap_lo[ph];
        pft_real_t g2 = PFT_C(0.0);
        for (int32_t k = 0; k < p->ytap_n[ph]; ++k) {
            if (u0 + k >= 0 && u0 + k < nr) {
                g2 = pft_add(g2, pft_sq(p->ytap[ph][k]));
            }
        }
        p->gq[i] = g2 - p->gfull[ph];
    }
    p->yin_lo = (int32_t)p->ny;
    p->yin_hi = -1;
    for (int32_t i = 0; i < (int32_t)p->ny; ++i) {
        int32_t ph = i % q;
        int32_t u0 = i / q - (int32_t)PFT_PTE_YPAD + p->ytap_lo[ph];
        if (u0 >= 0 && u0 + p->ytap_n[ph] <= nr) {
            p->yin_lo = i < p->yin_lo ? i : p->yin_lo;
            p->yin_hi = i;
        }
    }
}

/* TABLE operators: responses are computed lazily, one block of 8 cells at a time, the first
 * time an operator reads them, and kept beside the frame in the ring; only the neighbourhood
 * of live tracks is ever computed. */

/* Marks block blk of ring slot `slot` computed (one bit per block). */
static inline void yflag_set_(pft_pte_t *p, uint32_t slot, int32_t blk)
{
    uint8_t *f = p->yflag + (size_t)slot * p->nyblk + (size_t)(blk >> 3);
    *f = (uint8_t)(*f | (1u << (uint32_t)(blk & 7)));
}

static void yblock_(pft_pte_t *p, uint32_t slot, uint32_t back, int32_t blk)
{
    const int32_t q = p->yq;
    const int32_t nr = p->cfg.in.n_range;
    const pft_real_t *z = pft_pte_ring_get_(&p->ring, back);
    pft_real_t *y = p->yring + (size_t)slot * p->ny;
    const int32_t ncell = (int32_t)(p->ny / (uint32_t)q);
    int32_t c1 = (blk + 1) * YBLK_ < ncell ? (blk + 1) * YBLK_ : ncell;
    int32_t cell = blk * YBLK_;
    if (p->ytap4 && cell - (int32_t)PFT_PTE_YPAD + p->ytap4_lo >= 0 &&
        c1 - 1 - (int32_t)PFT_PTE_YPAD + p->ytap4_lo + 4 <= nr) {
        /* interior block, at most 4 taps per phase (sigma_y <= ~0.6 cells): the taps of every
         * phase padded to 4 from one common first offset; the zero weights add exact zeros,
         * so the sums are those of the general loop below (plain sums, bounded there) */
        if (q == 4) {
            /* the common 4 phases per cell: the four responses of a cell side by side, each
             * the same sum in the same order as in the loop below (a form the compiler
             * vectorises across the phases) */
            const pft_real_t *w0 = p->ytap4_w[0];
            const pft_real_t *w1 = p->ytap4_w[1];
            const pft_real_t *w2 = p->ytap4_w[2];
            const pft_real_t *w3 = p->ytap4_w[3];
            const pft_real_t *zz = z + cell - (int32_t)PFT_PTE_YPAD + p->ytap4_lo;
            pft_real_t *yy = y + cell * 4;
#ifdef PFT_NUMERIC_Q16
            /* each response the exact sum of its four Q32 products, rounded once (half up):
             * |z| <= zeta_clip <= 64 (2^22) and 0 <= w <= 1 (2^16), so every sum is below
             * 2^40 and the result below 2^24 (docs/fixed_point.md, "PTE-TBD response blocks
             * rounded once") */
            const int64_t a00 = w0[0], a01 = w0[1], a02 = w0[2], a03 = w0[3];
            const int64_t a10 = w1[0], a11 = w1[1], a12 = w1[2], a13 = w1[3];
            const int64_t a20 = w2[0], a21 = w2[1], a22 = w2[2], a23 = w2[3];
            const int64_t a30 = w3[0], a31 = w3[1], a32 = w3[2], a33 = w3[3];
            for (int32_t k = 0; k < c1 - cell; ++k) {
                const int64_t z0 = zz[k];
                const int64_t z1 = zz[k + 1];
                const int64_t z2 = zz[k + 2];
                const int64_t z3 = zz[k + 3];
                yy[4 * k] = (pft_real_t)((a00 * z0 + a01 * z1 + a02 * z2 + a03 * z3 + 32768) >> 16);
                yy[4 * k + 1] = (pft_real_t)((a10 * z0 + a11 * z1 + a12 * z2 + a13 * z3 + 32768) >> 16);
                yy[4 * k + 2] = (pft_real_t)((a20 * z0 + a21 * z1 + a22 * z2 + a23 * z3 + 32768) >> 16);
                yy[4 * k + 3] = (pft_real_t)((a30 * z0 + a31 * z1 + a32 * z2 + a33 * z3 + 32768) >> 16);
            }
#else
            for (int32_t k = 0; k < c1 - cell; ++k) {
                const pft_real_t z0 = zz[k];
                const pft_real_t z1 = zz[k + 1];
                const pft_real_t z2 = zz[k + 2];
                const pft_real_t z3 = zz[k + 3];
                yy[4 * k] = mul_nb_(w0[0], z0) + mul_nb_(w0[1], z1) + mul_nb_(w0[2], z2) + mul_nb_(w0[3], z3);
                yy[4 * k + 1] = mul_nb_(w1[0], z0) + mul_nb_(w1[1], z1) + mul_nb_(w1[2], z2) + mul_nb_(w1[3], z3);
                yy[4 * k + 2] = mul_nb_(w2[0], z0) + mul_nb_(w2[1], z1) + mul_nb_(w2[2], z2) + mul_nb_(w2[3], z3);
                yy[4 * k + 3] = mul_nb_(w3[0], z0) + mul_nb_(w3[1], z1) + mul_nb_(w3[2], z2) + mul_nb_(w3[3], z3);
            }
#endif
            yflag_set_(p, slot, blk);
            return;
        }
        for (int32_t ph = 0; ph < q; ++ph) {
            const pft_real_t *w = p->ytap4_w[ph];
            const pft_real_t *zz = z + cell - (int32_t)PFT_PTE_YPAD + p->ytap4_lo;
            pft_real_t *yy = y + cell * q + ph;
            for (int32_t k = 0; k < c1 - cell; ++k) {
                yy[k * q] = yround_(yterm_(w[0], zz[k]) + yterm_(w[1], zz[k + 1]) +
                                    yterm_(w[2], zz[k + 2]) + yterm_(w[3], zz[k + 3]));
            }
        }
        yflag_set_(p, slot, blk);
        return;
    }
    for (; cell < c1; ++cell) {
        for (int32_t ph = 0; ph < q; ++ph) {
            int32_t u0 = cell - (int32_t)PFT_PTE_YPAD + p->ytap_lo[ph];
            int32_t n = p->ytap_n[ph];
            const pft_real_t *w = p->ytap[ph];
            /* plain sums: |zeta| <= zeta_clip <= 64 (TABLE), 0 <= w <= 1 and at most
             * PFT_PTE_MAX_TAPS taps, so |acc| <= 960 (q16: exact Q32 products, below 2^42 in
             * all, rounded once) */
            yacc_t acc = 0;
            if (u0 >= 0 && u0 + n <= nr) {
                const pft_real_t *zz = z + u0;
                for (int32_t k = 0; k < n; ++k) {
                    acc = acc + yterm_(w[k], zz[k]);
                }
            } else {
                for (int32_t k = 0; k < n; ++k) {
                    if (u0 + k >= 0 && u0 + k < nr) {
                        acc = acc + yterm_(w[k], z[u0 + k]);
                    }
                }
            }
            y[cell * q + ph] = yround_(acc);
        }
    }
    yflag_set_(p, slot, blk);
}

/* ------------------------------------------------------------------- operator geometry */

/* Per-axis operator parameters of one track at one frame. The operators are straight lines
 * over the last M frames; their best end position c* and slope theta* are the least-squares
 * line of the path, so for a state [r, v, a] they measure r + hc a and v + hv a with
 * hc = -(M-1)(M-2)/12 and hv = -(M-1)/2 (zero in the CV model, where a = 0). */
static void axis_setup_(const pft_pte_t *p, const pft_real_t x[4], const pft_real_t P[16],
                        uint32_t a, int32_t M, pft_pte_axis_t *ap)
{
    const pft_pte_config_t *c = &p->cfg;
    memset(ap->H, 0, sizeof(ap->H));
    ap->H[0] = PFT_C(1.0);
    ap->H[5] = PFT_C(1.0);
    if (c->motion == PFT_PTE_MOTION_CA) {
        /* hc / SA and hv SV / SA on the scaled acceleration */
        ap->H[2] = pft_neg(pft_ratio((M - 1) * (M - 2), 12 * SA_));
        ap->H[6] = pft_neg(pft_ratio((M - 1) * SV_, 2 * SA_));
    }
    ap->zc = pft_add(x[0], pft_mul(ap->H[2], x[2]));
    ap->zt = pft_add(x[1], pft_mul(ap->H[6], x[2]));
    /* S = H P H' (rows [1 0 h2 0], [0 1 h6 0]) */
    pft_real_t h2 = ap->H[2];
    pft_real_t h6 = ap->H[6];
    pft_real_t scc = pft_add(pft_add(P[0], pft_mul_i(pft_mul(h2, P[2]), 2)), pft_mul(pft_sq(h2), P[10]));
    pft_real_t stt = pft_add(pft_add(P[5], pft_mul_i(pft_mul(h6, P[6]), 2)), pft_mul(pft_sq(h6), P[10]));
    scc = pft_max(scc, PFT_C(0.0));
    stt = pft_max(stt, PFT_C(0.0));
    ap->stt = stt;
    pft_real_t sr2 = pft_sq(c->sigma_r[a]);
    ap->sw2 = pft_add(sr2, scc);
    ap->sw = p->yq > 0u ? p->sigma_y : pft_min(sqrt_(ap->sw2), c->sigma_w_max);
    ap->sw2 = pft_sq(ap->sw);
    ap->inv_sw = recip_(ap->sw);
    ap->reach = pft_mul_i(ap->sw, 3);
    ap->L = (int32_t)c->n_dir[a];
    ap->dth = pft_mul_i(c->dtheta_min, SV_);
    if (ap->L > 1) {
        ap->dth = pft_max(div_i_(pft_mul_i(sqrt_(stt), 4), ap->L - 1), ap->dth);
    }
    /* dth^2 / (2 (S_tt + dth^2/12)) = 1 / (2 (S_tt/dth^2 + 1/12)) (scale-free) */
    pft_real_t rho = div_(stt, pft_sq(ap->dth));
    ap->prior_k = recip_(pft_mul_i(pft_add(rho, PFT_C(0.0833333333333)), 2));
    ap->sc2 = pft_add(scc, sr2);
    ap->lck = recip_(pft_mul_i(ap->sc2, 2));
    /* P H' on the effective state [r, SV r', SA r''], and the off-diagonal of H P H' (q16
     * plain sums: M <= PFT_PTE_MAX_FRAMES = 64, so |h2| <= 63 62 / 3072 and |h6| <= 63 16 /
     * 512 are below 2 (2^17) and each sum is below 2^47 + 2^48) */
    for (uint32_t i = 0; i < 3u; ++i) {
        ap->pht[2u * i] = ato_(aadd_(afrom_(P[4u * i]), amul_(P[4u * i + 2u], h2)));
        ap->pht[2u * i + 1u] = ato_(aadd_(afrom_(P[4u * i + 1u]), amul_(P[4u * i + 2u], h6)));
    }
    ap->s01 = ato_(aadd_(afrom_(ap->pht[1]), amul_(h2, ap->pht[5])));
    int32_t half = pft_floor_int(div_(pft_mul(c->scan_sigmas, sqrt_(ap->sc2)), c->c_step));
    if (half < 1) {
        half = 1;
    }
    if (half > (int32_t)c->scan_steps) {
        half = (int32_t)c->scan_steps;
    }
    ap->ns = 2 * half + 1;
    ap->c0 = pft_sub(ap->zc, pft_mul_i(c->c_step, half));
    ap->ncell = a == 0u ? (int32_t)c->in.n_range : (int32_t)c->in.n_doppler;
}

/* floor(x / 64) for any sign */
static int32_t fdiv64_(int32_t x)
{
    return x >= 0 ? x / 64 : -((-x + 63) / 64);
}

/* Per-frame weight table of one axis: gw[k] = g(k / (64 sigma_w)) for k = 0 .. R, R the
 * reach 3 sigma_w in 1/64 cells; path positions are quantised to 1/64 cell (error <= 1/128
 * cell), so every tap is an integer distance and a table read, identical in both builds. */
static int32_t gw_setup_(const pft_pte_t *p, uint32_t a, const pft_pte_axis_t *ap)
{
    pft_real_t *gw = p->gw[a];
    int32_t R = pft_floor_int(pft_mul_i(ap->reach, 64));
    if (R > (int32_t)PFT_PTE_GW_SIZE - 1) {
        R = (int32_t)PFT_PTE_GW_SIZE - 1;
    }
    for (int32_t k = 0; k <= R; ++k) {
        int32_t idx = pft_round_int(pft_mul_i(ap->inv_sw, k));
        gw[k] = idx < (int32_t)PFT_PTE_GTAB_SIZE ? p->gtab[idx] : PFT_C(0.0);
    }
    return R;
}

/* The taps of one scan phase: first cell, count, sum of the squared weights. */
typedef struct {
    int32_t lo, cnt;
    pft_real_t g2;
} phase_taps_t_;

/* Taps of scan phase ph of one axis (weight table gw, reach R in 1/64 cells) for a path
 * displaced by -shift cells at this frame; the weights go to w[]. */
static inline phase_taps_t_ phase_taps_(const pft_pte_t *p, const pft_real_t *gw,
                                        const pft_pte_axis_t *ap, int32_t R, pft_real_t shift,
                                        int32_t ph, pft_real_t *w)
{
    phase_taps_t_ t;
    pft_real_t pos = pft_sub(pft_add(ap->c0, pft_mul_i(p->cfg.c_step, ph)), shift);
    int32_t q = pft_round_int(pft_mul_i(pft_clamp(pos, PFT_C(-30000.0), PFT_C(30000.0)), 64));
    int32_t hi = fdiv64_(q + R);
    t.lo = -fdiv64_(R - q); /* ceil((q - R) / 64) */
    if (hi - t.lo + 1 > (int32_t)PFT_PTE_MAX_TAPS) {
        hi = t.lo + (int32_t)PFT_PTE_MAX_TAPS - 1;
    }
    t.cnt = hi >= t.lo ? hi - t.lo + 1 : 0;
    const int32_t lo = t.lo;
    const int32_t cnt = t.cnt;
    pft_real_t g2 = PFT_C(0.0);
    for (int32_t i = 0; i < cnt; ++i) {
        int32_t k = (lo + i) * 64 - q;
        pft_real_t g = gw[k < 0 ? -k : k];
        w[i] = g;
        g2 = pft_add(g2, pft_sq(g));
    }
    t.g2 = g2;
    return t;
}

/* Scan phases of an axis: positions one cell apart have the same weights, so when
 * c_step = 1/period only `period` phases are computed. */
static int32_t phases_(const pft_pte_t *p, const pft_pte_axis_t *ap)
{
    return (p->period == 0u || (int32_t)p->period > ap->ns) ? ap->ns : (int32_t)p->period;
}

/* Tap lists of every scan position of one axis for a path displaced by -shift cells at this
 * frame; writes the sums of squared weights into gs[]. The phases are computed once and the
 * other positions reuse them shifted by whole cells (clipped at the image edges). tlo[4j..]:
 * first cell, count, offset of the first weight in tw. */
static void taps_(const pft_pte_t *p, uint32_t a, const pft_pte_axis_t *ap, int32_t R,
                  pft_real_t shift, pft_real_t *gs)
{
    pft_real_t *tw = p->tw[a];
    int16_t *tl = p->tlo[a];
    pft_pte_scratch_t *s = p->scr;
    int32_t np = phases_(p, ap);
    for (int32_t ph = 0; ph < np; ++ph) {
        phase_taps_t_ t = phase_taps_(p, p->gw[a], ap, R, shift, ph, tw + (size_t)ph * PFT_PTE_MAX_TAPS);
        s->blo[ph] = t.lo;
        s->bcnt[ph] = t.cnt;
        s->bg[ph] = t.g2;
    }
    for (int32_t j = 0; j < ap->ns; ++j) {
        int32_t ph = j % np;
        int32_t lo = s->blo[ph] + j / np;
        int32_t cnt = s->bcnt[ph];
        int32_t off = 0;
        if (lo < 0) {
            off = -lo;
            cnt -= off;
            lo = 0;
        }
        if (lo + cnt > ap->ncell) {
            cnt = ap->ncell - lo;
        }
        if (cnt < 0) {
            cnt = 0;
            lo = 0;
            off = 0;
        }
        const pft_real_t *w = tw + (size_t)ph * PFT_PTE_MAX_TAPS + off;
        pft_real_t g2 = s->bg[ph];
        if (cnt != s->bcnt[ph]) {
            g2 = PFT_C(0.0);
            for (int32_t i = 0; i < cnt; ++i) {
                g2 = pft_add(g2, pft_sq(w[i]));
            }
        }
        tl[4 * j] = (int16_t)lo;
        tl[4 * j + 1] = (int16_t)cnt;
        tl[4 * j + 2] = (int16_t)((size_t)ph * PFT_PTE_MAX_TAPS + (size_t)off);
        gs[j] = g2;
    }
}

/* Range-time operator sums of one frame: for every scan position j, E[j] += sum g zeta and
 * G[j] += sum g^2 along the path displaced by -shift cells (taps as in taps_, fused with the
 * multiply-accumulate). */
static void accum_1d_(const pft_pte_t *p, const pft_pte_axis_t *ap, int32_t R, pft_real_t shift,
                      const pft_real_t *zf)
{
    const pft_real_t *gw = p->gw[0];
    pft_real_t w[PFT_PTE_MAX_TAPS];
    int32_t np = phases_(p, ap);
    for (int32_t ph = 0; ph < np; ++ph) {
        phase_taps_t_ t = phase_taps_(p, gw, ap, R, shift, ph, w);
        const int32_t lo = t.lo;
        const int32_t cnt = t.cnt;
        const pft_real_t g2 = t.g2;
        for (int32_t j = ph, u = lo; j < ap->ns; j += np, ++u) {
            pft_real_t e = PFT_C(0.0);
            pft_real_t g = g2;
            if (u >= 0 && u + cnt <= ap->ncell) {
                for (int32_t i = 0; i < cnt; ++i) {
                    e = pft_add(e, pft_mul(w[i], zf[u + i]));
                }
            } else {
                g = PFT_C(0.0);
                for (int32_t i = 0; i < cnt; ++i) {
                    if (u + i >= 0 && u + i < ap->ncell) {
                        e = pft_add(e, pft_mul(w[i], zf[u + i]));
                        g = pft_add(g, pft_sq(w[i]));
                    }
                }
            }
            p->sE[j] = pft_add(p->sE[j], e);
            p->sG[j] = pft_add(p->sG[j], g);
        }
    }
}

pft_real_t pft_pte_shift_(pft_real_t th, pft_real_t acc, int32_t tau)
{
    pft_real_t v = div_i_(pft_mul_i(th, tau), SV_);
    pft_real_t q = div_i_(pft_mul_i(acc, tau * tau), 2 * SA_);
    return pft_sub(v, q);
}

/* Displacement of a straight operator path (scaled slope). */
static pft_real_t line_shift_(pft_real_t th, int32_t tau)
{
    return div_i_(pft_mul_i(th, tau), SV_);
}

/* Transition and process noise of the scaled state (T = 1 frame). The noise intensity is
 * q = q_sd^2; it is formed as (q_sd SV)^2 and (q_sd SA)^2 so that it stays representable in
 * q16 (q itself, e.g. 4e-6, is below the q16 LSB). */
static void model_(const pft_pte_config_t *c, uint32_t a, pft_real_t F[16], pft_real_t Q[16])
{
    pft_real_t qv = pft_sq(pft_mul_i(c->q_sd[a], SV_)); /* SV^2 q */
    memset(F, 0, 16u * sizeof(pft_real_t));
    memset(Q, 0, 16u * sizeof(pft_real_t));
    F[0] = PFT_C(1.0);
    F[1] = pft_ratio(1, SV_);
    F[5] = PFT_C(1.0);
    F[10] = PFT_C(1.0);
    F[15] = PFT_C(1.0);
    if (c->motion == PFT_PTE_MOTION_CA) {
        pft_real_t qa = pft_sq(pft_mul_i(c->q_sd[a], SA_)); /* SA^2 q */
        F[2] = pft_ratio(1, 2 * SA_);
        F[6] = pft_ratio(SV_, SA_);
        /* white jerk: q [[1/20, 1/8, 1/6], [1/8, 1/3, 1/2], [1/6, 1/2, 1]], scaled by S Q S */
        Q[0] = div_i_(qv, SV_ * SV_ * 20);
        Q[1] = div_i_(qv, SV_ * 8);
        Q[2] = div_i_(qv, 6);             /* SA q / 6 = SV^2 q / 6 (SA = SV^2) */
        Q[5] = div_i_(qv, 3);
        Q[6] = div_i_(qa, 2 * SV_);       /* SV SA q / 2 */
        Q[10] = qa;
    } else {
        /* white acceleration: q [[1/3, 1/2], [1/2, 1]] */
        Q[0] = div_i_(qv, SV_ * SV_ * 3);
        Q[1] = div_i_(qv, SV_ * 2);
        Q[5] = qv;
    }
    Q[4] = Q[1];
    Q[8] = Q[2];
    Q[9] = Q[6];
}

/* ------------------------------------------------------- TABLE operators: slope bank */

/* The TABLE operators of a track are straight lines on the response grid, one family per
 * slope of a lattice (step dtheta_min). For each slope the track keeps an entry of
 * line sums over the last M frames (docs/algorithms.md 5.3, library extension "sliding
 * sums"): at each frame the newest response is added and the one leaving the window
 * subtracted, so an operator costs O(1) reads per frame instead of M. Entries of slopes no
 * longer wanted are dropped; a new slope is summed once in full. The normaliser G of a line
 * that stays inside the profile depends only on its grid phases, so an entry keeps it per
 * residue of the line index modulo yq instead of per line. In the q16 build the sums are
 * integers and sliding them is exact; in the float build an entry is summed afresh every
 * RENEW_ frames so rounding cannot drift. */

/* Line offset at frame k of slope entry e: round(s U (k - k0) / 2^16) grid points. */
static inline int32_t bank_off_(const pft_pte_t *p, const pft_pte_bank_t *e, uint32_t k)
{
    int64_t v = (int64_t)e->s * p->lat_u * (int64_t)(int32_t)(k - e->k0);
    return (int32_t)((v + 32768) >> 16);
}

/* E sums of entry bi of track ti, window w (one per line). */
static inline pft_real_t *bank_e_(const pft_pte_t *p, uint32_t ti, uint32_t bi, uint32_t w)
{
    return p->bsum + (((size_t)ti * p->nbank + bi) * PFT_PTE_NWIN_ + w) * p->nline;
}

/* Computes the blocks [b0, b1] of ring slot `slot` (back frames ago) not yet computed. */
static void yrow_fill_(pft_pte_t *p, uint32_t slot, uint32_t back, int32_t b0, int32_t b1)
{
    const uint8_t *fl = p->yflag + (size_t)slot * p->nyblk;
    for (int32_t blk = b0; blk <= b1; ++blk) {
        if ((fl[blk >> 3] & (1u << (uint32_t)(blk & 7))) == 0u) {
            yblock_(p, slot, back, blk);
            p->n_line_ops += BLK_UNITS_; /* line_budget's units */
        }
    }
}

/* The points [lo, hi) of a ring slot whose blocks are all computed (a span that grows with
 * the reads), kept as two uint16 in the last 4 of the slot's nyblk flag bytes when
 * nyblk >= YSPAN_MIN_: the bits and yrow_'s two-byte read use at most (nyblk - 1) / 8 + 2 of
 * them. Cleared with the flags (lo = hi = 0: empty, since every read has i1 >= 1). Points
 * are below (PFT_CFG_MAX_IMAGE_SIDE + 2 PFT_PTE_YPAD + 7) 8 yq <= 65535 (yq <= 8). */
#define YSPAN_MIN_ 6u

/* yrow_ when [i0, i1) is not inside the slot's span: the bit test of its blocks (computing
 * the missing ones), then the span extended by them (or replaced when they do not touch). */
static void yrow_blocks_(pft_pte_t *p, uint32_t slot, uint32_t back, int32_t i0, int32_t i1)
{
    const int32_t sh = p->yblk_shift;
    uint8_t *fl = p->yflag + (size_t)slot * p->nyblk;
    const int32_t bs = YBLK_ * (int32_t)p->yq;
    const int32_t b0 = sh > 0 ? i0 >> sh : i0 / bs;
    const int32_t b1 = sh > 0 ? (i1 - 1) >> sh : (i1 - 1) / bs;
    /* one bit per block (bit blk & 7 of byte blk >> 3): up to 8 blocks tested at once in the
     * two bytes from b0's (the bits use (nyblk + 7) / 8 of the nyblk >= 2 bytes of a slot, so
     * the second byte is always inside the slot; bits of other blocks are masked off) */
    const int32_t w0 = b0 >> 3;
    const uint32_t bits = (uint32_t)fl[w0] | ((uint32_t)fl[w0 + 1] << 8);
    const uint32_t m = ((2u << ((uint32_t)(b1 - b0) & 7u)) - 1u) << (uint32_t)(b0 & 7);
    if (b1 - b0 >= 8 || (bits & m) != m) {
        yrow_fill_(p, slot, back, b0, b1);
    }
    if (p->nyblk >= YSPAN_MIN_) {
        uint16_t lo;
        uint16_t hi;
        memcpy(&lo, fl + p->nyblk - 4u, sizeof(lo));
        memcpy(&hi, fl + p->nyblk - 2u, sizeof(hi));
        int32_t c0 = b0 * bs;
        int32_t c1 = (b1 + 1) * bs;
        if (hi > lo && c0 <= (int32_t)hi && c1 >= (int32_t)lo) {
            c0 = c0 < (int32_t)lo ? c0 : (int32_t)lo;
            c1 = c1 > (int32_t)hi ? c1 : (int32_t)hi;
        }
        lo = (uint16_t)c0;
        hi = (uint16_t)c1;
        memcpy(fl + p->nyblk - 4u, &lo, sizeof(lo));
        memcpy(fl + p->nyblk - 2u, &hi, sizeof(hi));
    }
}

/* Response row of ring slot `slot` (back frames ago), its blocks over [i0, i1) computed. */
static inline const pft_real_t *yrow_(pft_pte_t *p, uint32_t slot, uint32_t back, int32_t i0,
                                      int32_t i1)
{
    const uint8_t *fl = p->yflag + (size_t)slot * p->nyblk;
    uint16_t lo = 0u;
    uint16_t hi = 0u;
    if (p->nyblk >= YSPAN_MIN_) {
        memcpy(&lo, fl + p->nyblk - 4u, sizeof(lo));
        memcpy(&hi, fl + p->nyblk - 2u, sizeof(hi));
    }
    if (i0 < (int32_t)lo || i1 > (int32_t)hi) {
        yrow_blocks_(p, slot, back, i0, i1);
    }
    return p->yring + (size_t)slot * p->ny;
}

/* s[j] += y[j], s[j] -= y[j] and s[j] += yn[j] - yo[j] for j < n: the loops of the line sums,
 * with restrict parameters so that gcc vectorises them without a run-time overlap test (the
 * sums and the response rows are distinct arrays of the instance) */
static inline void rows_add_(pft_real_t *restrict s, const pft_real_t *restrict y, int32_t n)
{
    for (int32_t j = 0; j < n; ++j) {
        s[j] = s[j] + y[j];
    }
}
static inline void rows_sub_(pft_real_t *restrict s, const pft_real_t *restrict y, int32_t n)
{
    for (int32_t j = 0; j < n; ++j) {
        s[j] = s[j] - y[j];
    }
}
static inline void rows_slide_(pft_real_t *restrict s, const pft_real_t *restrict yn,
                               const pft_real_t *restrict yo, int32_t n)
{
    for (int32_t j = 0; j < n; ++j) {
        s[j] = s[j] + yn[j] - yo[j];
    }
}

/* Adds (sign 1) or subtracts (sign -1) the responses of the frames kn - tau, tau in
 * [tau0, tau1), along the lines [j0, j1) of entry bi (local indices from its jlo) to its E
 * sums of window w. Points off the response grid count 0. q16: plain integer sums, so adding
 * and subtracting is exact: every partial sum is a sum over at most PFT_PTE_MAX_FRAMES + 1
 * frames of |y| <= zeta_clip * sum g <= 64 * 6.9 (TABLE requires zeta_clip <= 64), so
 * |E| < 28800 stays inside the q16 range. */
static void bank_lines_(pft_pte_t *p, uint32_t ti, uint32_t bi, uint32_t w, int32_t j0,
                        int32_t j1, uint32_t kn, int32_t tau0, int32_t tau1, int32_t sign)
{
    const pft_pte_bank_t *e = &p->bank[(size_t)ti * p->nbank + bi];
    const int32_t ny = (int32_t)p->ny;
    const int32_t len = p->ring.len;
    const int64_t step = (int64_t)e->s * p->lat_u;
    int64_t acc = step * (int64_t)(int32_t)(kn - (uint32_t)tau0 - e->k0) + 32768;
    int32_t slot = (int32_t)p->ring.head - tau0 % len;
    slot = slot < 0 ? slot + len : slot;
    pft_real_t *restrict se = bank_e_(p, ti, bi, w);
    for (int32_t tau = tau0; tau < tau1; ++tau) {
        const int32_t d = (int32_t)(acc >> 16) + e->jlo;
        const int32_t a = j0 + d < 0 ? -d : j0;
        const int32_t b = j1 + d > ny ? ny - d : j1;
        if (a < b) {
            p->n_line_ops += (uint32_t)(b - a);
            const pft_real_t *restrict y = yrow_(p, (uint32_t)slot, (uint32_t)tau, a + d, b + d) + d;
            if (sign > 0) {
                rows_add_(se + a, y + a, b - a);
            } else {
                rows_sub_(se + a, y + a, b - a);
            }
        }
        acc -= step;
        slot = slot == 0 ? len - 1 : slot - 1;
    }
}

/* Adds (sign 1) or subtracts the interior normaliser terms of the frames kn - tau, tau in
 * [tau0, tau1), to the residues of window w of entry e: residue r holds the sum over the
 * window of gfull[(r + offset) mod yq]. */
static inline void bank_gres_(const pft_pte_t *p, pft_pte_bank_t *e, uint32_t w, uint32_t kn,
                       int32_t tau0, int32_t tau1, int32_t sign)
{
    const int32_t q = p->yq;
    const int64_t step = (int64_t)e->s * p->lat_u;
    int64_t acc = step * (int64_t)(int32_t)(kn - (uint32_t)tau0 - e->k0) + 32768;
    pft_real_t *gr = e->gres[w];
    for (int32_t tau = tau0; tau < tau1; ++tau) {
        int32_t o = (int32_t)(acc >> 16) % q;
        o = o < 0 ? o + q : o;
        acc -= step;
        if (pft_pte_missing_(p, (uint32_t)tau) != 0u) {
            continue; /* a lost frame: no term */
        }
        const pft_real_t *gf = p->gfull + o;
        if (q == 4 && sign > 0) { /* the common 4 phases per cell, unrolled: the same sums */
            gr[0] = gr[0] + gf[0];
            gr[1] = gr[1] + gf[1];
            gr[2] = gr[2] + gf[2];
            gr[3] = gr[3] + gf[3];
            continue;
        }
        for (int32_t r = 0; r < q; ++r) {
            gr[r] = sign > 0 ? gr[r] + gf[r] : gr[r] - gf[r];
        }
    }
}

/* One slide of window w (m frames) of entry bi over its lines [j0, j1): the newest frame in,
 * the frame m back out, in one pass, E and the G residues. False (nothing done) when a line
 * leaves the response grid at either frame (then bank_lines_ handles the edges). */
static bool bank_slide_(pft_pte_t *p, uint32_t ti, uint32_t bi, uint32_t w, int32_t j0,
                        int32_t j1, uint32_t kn, int32_t m)
{
    pft_pte_bank_t *e = &p->bank[(size_t)ti * p->nbank + bi];
    const int32_t ny = (int32_t)p->ny;
    const int32_t on = bank_off_(p, e, kn);
    const int32_t oo = bank_off_(p, e, kn - (uint32_t)m);
    const int32_t dn = on + e->jlo;
    const int32_t dold = oo + e->jlo;
    if (j0 >= j1 || j0 + dn < 0 || j1 + dn > ny || j0 + dold < 0 || j1 + dold > ny) {
        return false;
    }
    p->n_line_ops += 2u * (uint32_t)(j1 - j0);
    const int32_t len = p->ring.len;
    int32_t so = (int32_t)p->ring.head - m;
    so = so < 0 ? so + len : so;
    const pft_real_t *restrict yn = yrow_(p, p->ring.head, 0u, j0 + dn, j1 + dn) + dn;
    const pft_real_t *restrict yo = yrow_(p, (uint32_t)so, (uint32_t)m, j0 + dold, j1 + dold) + dold;
    pft_real_t *restrict se = bank_e_(p, ti, bi, w);
    rows_slide_(se + j0, yn + j0, yo + j0, j1 - j0); /* plain sums, bounded as in bank_lines_ */
    const int32_t q = p->yq;
    int32_t rn = on % q;
    int32_t ro = oo % q;
    rn = rn < 0 ? rn + q : rn;
    ro = ro < 0 ? ro + q : ro;
    if (p->miss[so] != 0u) {
        /* the frame leaving the window was lost: it had no term (the newest frame is never
         * lost: tracks step on received frames only) */
        pft_real_t *gr = e->gres[w];
        for (int32_t r = 0; r < q; ++r) {
            gr[r] = gr[r] + p->gfull[r + rn];
        }
    } else if (rn != ro) {
        pft_real_t *gr = e->gres[w];
        const pft_real_t *gn = p->gfull + rn;
        const pft_real_t *go = p->gfull + ro;
        if (q == 4) { /* the common 4 phases per cell, unrolled: the same sums */
            gr[0] = gr[0] + gn[0] - go[0];
            gr[1] = gr[1] + gn[1] - go[1];
            gr[2] = gr[2] + gn[2] - go[2];
            gr[3] = gr[3] + gn[3] - go[3];
        } else {
            for (int32_t r = 0; r < q; ++r) {
                gr[r] = gr[r] + gn[r] - go[r];
            }
        }
    } else {
        /* the same residue in and out: the terms cancel */
    }
    return true;
}

/* The sums of W (a constant where gcc specialises it) lines from local line j of slope entry e
 * over its last m frames at frame kn, kept in a local array across the frames and stored once
 * into se: per line the additions of bank_lines_ from 0 in the same order (tau = 0, 1, ...,
 * m - 1), so the same values in both builds; the loads and stores of the sums per frame are
 * saved. Every line is inside the response grid at every frame and the frames' blocks are
 * computed (bank_fresh_). Few arguments, so that a caller's frame holds none on the stack
 * (the M3 stack bound, docs/size.md). */
#define FRESH_W_ 16
static void fresh_cols_(const pft_pte_t *p, const pft_pte_bank_t *e, pft_real_t *restrict se,
                        uint32_t kn, int32_t j, int32_t m, int32_t W)
{
    const int64_t step = (int64_t)e->s * p->lat_u;
    const size_t ny = p->ny;
    const pft_real_t *restrict yr = p->yring + (e->jlo + j);
    pft_real_t s[FRESH_W_];
    for (int32_t k = 0; k < W; ++k) {
        s[k] = PFT_C(0.0);
    }
    int64_t acc = step * (int64_t)(int32_t)(kn - e->k0) + 32768;
    const pft_real_t *row = yr + (size_t)p->ring.head * ny;
    const pft_real_t *const last = yr + (size_t)(p->ring.len - 1u) * ny;
    for (int32_t tau = 0; tau < m; ++tau) {
        const pft_real_t *restrict y = row + (int32_t)(acc >> 16);
        for (int32_t k = 0; k < W; ++k) {
            s[k] = s[k] + y[k];
        }
        acc -= step;
        row = row == yr ? last : row - ny;
    }
    for (int32_t k = 0; k < W; ++k) {
        se[j + k] = s[k];
    }
}

/* Window w of entry bi summed afresh over lines [j0, j1) and its last m frames, as zeroing
 * the sums and bank_lines_ (tau 0 .. m - 1, sign 1) do, with the same values, response blocks
 * and line_budget units, when every line stays inside the response grid at every frame
 * (false, nothing done, otherwise): a line's offset is monotone in tau, so the first and last
 * frames bound it. First the frames' blocks (yrow_, in bank_lines_'s order), then the sums by
 * groups of lines held across the frames (fresh_cols_). */
static bool bank_fresh_(pft_pte_t *p, uint32_t ti, uint32_t bi, uint32_t w, int32_t j0,
                        int32_t j1, uint32_t kn, int32_t m)
{
    const pft_pte_bank_t *e = &p->bank[(size_t)ti * p->nbank + bi];
    const int32_t ny = (int32_t)p->ny;
    const int32_t len = p->ring.len;
    const int64_t step = (int64_t)e->s * p->lat_u;
    const int64_t acc0 = step * (int64_t)(int32_t)(kn - e->k0) + 32768;
    const int32_t da = (int32_t)(acc0 >> 16) + e->jlo;
    const int32_t db = (int32_t)((acc0 - step * (m - 1)) >> 16) + e->jlo;
    if (m < 1 || j0 >= j1 || j0 + da < 0 || j0 + db < 0 || j1 + da > ny || j1 + db > ny) {
        return false;
    }
    int64_t acc = acc0;
    int32_t slot = (int32_t)p->ring.head;
    for (int32_t tau = 0; tau < m; ++tau) {
        const int32_t d = (int32_t)(acc >> 16) + e->jlo;
        p->n_line_ops += (uint32_t)(j1 - j0);
        (void)yrow_(p, (uint32_t)slot, (uint32_t)tau, j0 + d, j1 + d);
        acc -= step;
        slot = slot == 0 ? len - 1 : slot - 1;
    }
    pft_real_t *restrict se = bank_e_(p, ti, bi, w);
    int32_t j = j0;
    for (; j + FRESH_W_ <= j1; j += FRESH_W_) {
        fresh_cols_(p, e, se, kn, j, m, FRESH_W_);
    }
    if (j + 8 <= j1) {
        fresh_cols_(p, e, se, kn, j, m, 8);
        j += 8;
    }
    if (j + 4 <= j1) {
        fresh_cols_(p, e, se, kn, j, m, 4);
        j += 4;
    }
    for (; j < j1; ++j) {
        fresh_cols_(p, e, se, kn, j, m, 1);
    }
    return true;
}

/* Sums the lines [j0, j1) of entry bi afresh over the last m[w] frames of every window. */
static void bank_fill_(pft_pte_t *p, uint32_t ti, uint32_t bi, int32_t j0, int32_t j1,
                       uint32_t kn)
{
    const pft_pte_bank_t *e = &p->bank[(size_t)ti * p->nbank + bi];
    for (uint32_t w = 0; w < PFT_PTE_NWIN_; ++w) {
        if (bank_fresh_(p, ti, bi, w, j0, j1, kn, (int32_t)e->m[w])) {
            continue;
        }
        pft_real_t *se = bank_e_(p, ti, bi, w);
        for (int32_t j = j0; j < j1; ++j) {
            se[j] = PFT_C(0.0);
        }
        bank_lines_(p, ti, bi, w, j0, j1, kn, 0, (int32_t)e->m[w], 1);
    }
}

/* Brings entry bi of track ti to lines [jlo, jlo + n) and windows m[] at frame kn. A kept
 * entry (its sums are at frame kn - 1) slides the lines it already holds: the newest frame
 * in, the frames beyond each window out (the frame leaving a window of m frames is m frames
 * back, still in the ring, which holds max_len + 1 frames); every other line is summed
 * afresh. jlo is counted from the entry's anchor (set by the caller). */
static void bank_sync_(pft_pte_t *p, uint32_t ti, uint32_t bi, int32_t jlo, int32_t n,
                       const uint8_t m[PFT_PTE_NWIN_], uint32_t kn, bool keep)
{
    pft_pte_bank_t *e = &p->bank[(size_t)ti * p->nbank + bi];
    /* the common case first: a kept entry one frame on, its lines and one window (no short
     * one) unchanged, slid in one pass; what the general path below does for it, and the
     * same state after (lines, windows, frame) */
    if (keep && jlo == e->jlo && n == (int32_t)e->n && e->kl + 1u == kn && m[1] == 0u &&
        e->m[1] == 0u && m[0] != 0u && m[0] == e->m[0] &&
        bank_slide_(p, ti, bi, 0u, 0, n, kn, (int32_t)m[0])) {
        e->kl = kn;
        return;
    }
    int32_t k0 = 0; /* held lines kept: [k0, k1) in the new local indices */
    int32_t k1 = 0;
    const int32_t a = jlo > e->jlo ? jlo : e->jlo;
    const int32_t b = jlo + n < e->jlo + (int32_t)e->n ? jlo + n : e->jlo + (int32_t)e->n;
    if (keep) {
        if (a < b) {
            k0 = a - jlo;
            k1 = b - jlo;
            const int32_t sh = a - e->jlo - k0; /* old local index = new local index + sh */
            for (uint32_t w = 0; w < PFT_PTE_NWIN_ && sh != 0; ++w) {
                if (e->m[w] > 0u) {
                    pft_real_t *v = bank_e_(p, ti, bi, w);
                    memmove(v + k0, v + k0 + sh, (size_t)(k1 - k0) * sizeof(pft_real_t));
                }
            }
        }
        e->jlo = jlo;
        for (uint32_t w = 0; w < PFT_PTE_NWIN_; ++w) {
            const int32_t mo = e->m[w];
            const int32_t mn = m[w];
            if (mn == 0) {
                continue; /* window unused */
            }
            if (mo == 0) { /* a window taken into use: summed in full */
                pft_real_t *se = bank_e_(p, ti, bi, w);
                for (int32_t j = k0; j < k1; ++j) {
                    se[j] = PFT_C(0.0);
                }
                for (int32_t r = 0; r < (int32_t)p->yq; ++r) {
                    e->gres[w][r] = PFT_C(0.0);
                }
                bank_lines_(p, ti, bi, w, k0, k1, kn, 0, mn, 1);
                bank_gres_(p, e, w, kn, 0, mn, 1);
                continue;
            }
            /* dk frames since the entry's last frame (above 1 only under step_budget) */
            const int32_t dk = (int32_t)(kn - e->kl);
            if (dk == 1 && mn == mo && bank_slide_(p, ti, bi, w, k0, k1, kn, mn)) {
                continue; /* the common case: one frame in, one out */
            }
            /* the dk newest frames in; then the far end from mo + dk frames to mn frames */
            bank_lines_(p, ti, bi, w, k0, k1, kn, 0, dk, 1);
            bank_gres_(p, e, w, kn, 0, dk, 1);
            if (mn <= mo + dk - 1) {
                bank_lines_(p, ti, bi, w, k0, k1, kn, mn, mo + dk, -1);
                bank_gres_(p, e, w, kn, mn, mo + dk, -1);
            } else {
                bank_lines_(p, ti, bi, w, k0, k1, kn, mo + dk, mn, 1);
                bank_gres_(p, e, w, kn, mo + dk, mn, 1);
            }
        }
    } else {
        for (uint32_t w = 0; w < PFT_PTE_NWIN_; ++w) {
            for (int32_t r = 0; r < (int32_t)p->yq; ++r) {
                e->gres[w][r] = PFT_C(0.0);
            }
            bank_gres_(p, e, w, kn, 0, (int32_t)m[w], 1);
        }
    }
    e->jlo = jlo;
    e->n = (uint16_t)n;
    for (uint32_t w = 0; w < PFT_PTE_NWIN_; ++w) {
        e->m[w] = m[w];
    }
    e->kl = kn;
    e->live = 1u;
    if (k0 > 0) {
        bank_fill_(p, ti, bi, 0, k0, kn);
    }
    if (k1 < n) {
        bank_fill_(p, ti, bi, k1, n, kn);
    }
}

/* line_budget: the response blocks not yet computed under lines [jlo, jlo + n) of entry e
 * (anchored as it will be summed) at the frames kn - tau, tau in [tau0, tau1), in units. */
static uint32_t blk_units_(const pft_pte_t *p, const pft_pte_bank_t *e, int32_t jlo, int32_t n,
                           uint32_t kn, int32_t tau0, int32_t tau1)
{
    const int32_t ny = (int32_t)p->ny;
    const int32_t sh = p->yblk_shift;
    const int32_t bp = YBLK_ * (int32_t)p->yq;
    const int32_t len = p->ring.len;
    const int64_t step = (int64_t)e->s * p->lat_u; /* offsets as bank_lines_ steps them */
    int64_t acc = step * (int64_t)(int32_t)(kn - (uint32_t)tau0 - e->k0) + 32768;
    int32_t slot = (int32_t)p->ring.head - tau0 % len;
    slot = slot < 0 ? slot + len : slot;
    uint32_t c = 0u;
    for (int32_t tau = tau0; tau < tau1; ++tau) {
        int32_t a = (int32_t)(acc >> 16) + jlo;
        int32_t b = a + n;
        a = a < 0 ? 0 : a;
        b = b > ny ? ny : b;
        if (a < b) {
            const uint8_t *fl = p->yflag + (size_t)slot * p->nyblk;
            const int32_t b1 = sh > 0 ? (b - 1) >> sh : (b - 1) / bp;
            for (int32_t b0 = sh > 0 ? a >> sh : a / bp; b0 <= b1; b0 += 8) {
                /* up to 8 blocks' bits in the two bytes from b0's, as yrow_ tests them */
                const int32_t w0 = b0 >> 3;
                const int32_t nb = b1 - b0 < 7 ? b1 - b0 : 7;
                const uint32_t bits = (uint32_t)fl[w0] | ((uint32_t)fl[w0 + 1] << 8);
                uint32_t x = ~bits & (((2u << (uint32_t)nb) - 1u) << (uint32_t)(b0 & 7));
                while (x != 0u) { /* at most 8 bits */
                    x &= x - 1u;
                    c += BLK_UNITS_;
                }
            }
        }
        acc -= step;
        slot = slot == 0 ? len - 1 : slot - 1;
    }
    return c;
}

/* line_budget: an upper bound of the units bank_sync_ spends for these arguments (the lines
 * kept slide or catch up over dk frames, the others are summed in full; the response blocks
 * of the frames read, not yet computed). */
static uint32_t sync_cost_(const pft_pte_t *p, const pft_pte_bank_t *e, int32_t jlo, int32_t n,
                           const uint8_t m[PFT_PTE_NWIN_], uint32_t kn, bool keep)
{
    int32_t kept = 0;
    if (keep) {
        const int32_t a = jlo > e->jlo ? jlo : e->jlo;
        const int32_t b = jlo + n < e->jlo + (int32_t)e->n ? jlo + n : e->jlo + (int32_t)e->n;
        kept = a < b ? b - a : 0;
    }
    const int32_t dk = (int32_t)(kn - e->kl);
    uint32_t c = 0u;
    for (uint32_t w = 0; w < PFT_PTE_NWIN_; ++w) {
        const int32_t mn = m[w];
        const int32_t mo = e->m[w];
        int32_t f = mo + dk - mn;
        f = f < 0 ? -f : f;
        c += (uint32_t)(n - kept) * (uint32_t)mn; /* lines summed in full */
        if (kept > 0 && mn > 0) {
            c += (uint32_t)kept * (uint32_t)(mo == 0 ? mn : dk + f);
        }
    }
    /* the frames read: all of the windows' when a line or a window is summed in full, else
     * the dk newest and each window's far end */
    int32_t hi = 0;
    bool full = false;
    for (uint32_t w = 0; w < PFT_PTE_NWIN_; ++w) {
        const int32_t mn = m[w];
        const int32_t mo = keep ? (int32_t)e->m[w] + dk : 0;
        if (mn > 0) {
            full = full || n > kept || e->m[w] == 0u;
            hi = mn > hi ? mn : hi;
            hi = mo > hi ? mo : hi;
        }
    }
    if (full) {
        return c + blk_units_(p, e, jlo, n, kn, 0, hi);
    }
    c += blk_units_(p, e, jlo, n, kn, 0, dk);
    for (uint32_t w = 0; w < PFT_PTE_NWIN_; ++w) {
        const int32_t mn = m[w];
        const int32_t mo = (int32_t)e->m[w] + dk;
        if (mn > 0) {
            c += blk_units_(p, e, jlo, n, kn, mn < mo ? mn : mo, mn < mo ? mo : mn);
        }
    }
    return c;
}

/* line_budget: brings entry bi as far towards lines [jlo, jlo + n) and windows m[] at frame
 * kn as the budget left in this update allows, one frame of all its lines at a time (the
 * frames after its last one first, oldest first; then each window's far end). An entry that
 * holds other lines, or whose frames would leave the ring, starts empty at frame kn. Returns
 * true when the entry is complete (then the step may use it). */
static bool bank_part_(pft_pte_t *p, uint32_t ti, uint32_t bi, int32_t jlo, int32_t n,
                       const uint8_t m[PFT_PTE_NWIN_], uint32_t kn, bool keep)
{
    pft_pte_bank_t *e = &p->bank[(size_t)ti * p->nbank + bi];
    const uint32_t mx = e->m[0] > e->m[1] ? e->m[0] : e->m[1];
    if (!keep || jlo != e->jlo || n != (int32_t)e->n || mx + (kn - e->kl) > p->ring.count) {
        e->jlo = jlo;
        e->n = (uint16_t)n;
        e->kl = kn;
        e->m[0] = 0u;
        e->m[1] = 0u;
    }
    uint32_t nw = 0u;
    for (uint32_t w = 0; w < PFT_PTE_NWIN_; ++w) {
        if (m[w] == 0u) {
            e->m[w] = 0u; /* a window no longer used */
        } else {
            nw++;
        }
        if (e->m[w] == 0u) { /* empty: its sums start at 0 */
            pft_real_t *se = bank_e_(p, ti, bi, w);
            for (int32_t j = 0; j < n; ++j) {
                se[j] = PFT_C(0.0);
            }
            for (int32_t r = 0; r < (int32_t)p->yq; ++r) {
                e->gres[w][r] = PFT_C(0.0);
            }
        }
    }
    e->live = 1u;
    const uint32_t one = (uint32_t)n * nw; /* one frame of every line of every window used */
    while (e->kl != kn) {
        const int32_t tau = (int32_t)(kn - e->kl) - 1;
        const uint32_t cost = one + blk_units_(p, e, jlo, n, kn, tau, tau + 1);
        if (p->line_used + cost > p->cfg.line_budget) {
            break;
        }
        const uint32_t before = p->n_line_ops;
        for (uint32_t w = 0; w < PFT_PTE_NWIN_; ++w) {
            if (m[w] != 0u) {
                bank_lines_(p, ti, bi, w, 0, n, kn, tau, tau + 1, 1);
                bank_gres_(p, e, w, kn, tau, tau + 1, 1);
                e->m[w]++;
            }
        }
        e->kl++;
        p->line_used += p->n_line_ops - before;
    }
    bool done = e->kl == kn;
    for (uint32_t w = 0; w < PFT_PTE_NWIN_ && e->kl == kn; ++w) {
        const int32_t mo = e->m[w];
        const int32_t mn = m[w];
        const int32_t need = mo > mn ? mo - mn : mn - mo;
        int32_t f = 0; /* the frames whose lines and blocks fit in what is left */
        uint32_t cost = 0u;
        while (f < need) {
            const int32_t tau = mo > mn ? mo - 1 - f : mo + f;
            const uint32_t cf = (uint32_t)n + blk_units_(p, e, jlo, n, kn, tau, tau + 1);
            if (p->line_used + cost + cf > p->cfg.line_budget) {
                break;
            }
            cost += cf;
            f++;
        }
        const uint32_t before = p->n_line_ops;
        if (mo > mn) { /* the oldest frames out */
            bank_lines_(p, ti, bi, w, 0, n, kn, mo - f, mo, -1);
            bank_gres_(p, e, w, kn, mo - f, mo, -1);
            e->m[w] = (uint8_t)(mo - f);
        } else { /* older frames in */
            bank_lines_(p, ti, bi, w, 0, n, kn, mo, mo + f, 1);
            bank_gres_(p, e, w, kn, mo, mo + f, 1);
            e->m[w] = (uint8_t)(mo + f);
        }
        p->line_used += p->n_line_ops - before;
        done = done && e->m[w] == m[w];
    }
    return done;
}

/* line_budget: true when bank_sync_ for these arguments fits in the budget left (the caller
 * then runs it and charges what it spent, at most its cost; else bank_part_ brings the entry
 * as far as the budget goes). Kept apart from bank_sync_'s call so that the frames of the
 * cost and of bank_part_ are not on the stack under bank_sync_. */
static bool sync_fits_(const pft_pte_t *p, uint32_t ti, uint32_t bi, int32_t jlo, int32_t n,
                       const uint8_t m[PFT_PTE_NWIN_], uint32_t kn, bool keep)
{
    const pft_pte_bank_t *e = &p->bank[(size_t)ti * p->nbank + bi];
    return p->line_used + sync_cost_(p, e, jlo, n, m, kn, keep) <= p->cfg.line_budget;
}

/* Subtracts the interior normaliser gfull of its phase from G[j], j in [j0, j1), for the
 * points j + d off the response grid (their own normaliser is 0). */
static void g_off_(const pft_pte_t *p, pft_real_t *restrict G, int32_t j0, int32_t j1, int32_t d)
{
    const int32_t q = p->yq;
    int32_t ph = (j0 + d) % q;
    ph = ph < 0 ? ph + q : ph;
    for (int32_t j = j0; j < j1; ++j) {
        G[j] = G[j] - p->gfull[ph]; /* |gfull| <= 6.9: no saturation */
        ph = ph + 1 == q ? 0 : ph + 1;
    }
}

/* G of the lines of entry bi (window w) at frame kn into G[0..n): the residues, corrected at
 * the points of lines that leave the interior of the response grid over the window. */
static void bank_g_(pft_pte_t *p, uint32_t ti, uint32_t bi, uint32_t w, uint32_t kn,
                    int32_t j0, int32_t n, pft_real_t *restrict G)
{
    const pft_pte_bank_t *e = &p->bank[(size_t)ti * p->nbank + bi];
    const int32_t q = p->yq;
    const int32_t m = e->m[w];
    const int32_t jl = e->jlo + j0;
    int32_t d0 = bank_off_(p, e, kn) + jl;
    int32_t d1 = bank_off_(p, e, kn - (uint32_t)(m > 0 ? m - 1 : 0)) + jl;
    int32_t lo = d0 < d1 ? d0 : d1;
    int32_t hi = (d0 > d1 ? d0 : d1) + n - 1;
    int32_t r = jl % q;
    r = r < 0 ? r + q : r;
    if (q == 4) {
        /* the common 4 phases per cell: the period held in four values and stored four at a
         * time (the same values as the loops below) */
        const pft_real_t *gr = e->gres[w];
        const pft_real_t g4[4] = {gr[r], gr[(r + 1) & 3], gr[(r + 2) & 3], gr[(r + 3) & 3]};
        int32_t j = 0;
        for (; j + 4 <= n; j += 4) {
            G[j] = g4[0];
            G[j + 1] = g4[1];
            G[j + 2] = g4[2];
            G[j + 3] = g4[3];
        }
        for (int32_t k = 0; j + k < n; ++k) {
            G[j + k] = g4[k];
        }
    } else {
        for (int32_t k = 0; k < q && k < n; ++k) { /* one period, then copies of it */
            G[k] = e->gres[w][r];
            r = r + 1 == q ? 0 : r + 1;
        }
        for (int32_t j = q; j < n; ++j) {
            G[j] = G[j - q];
        }
    }
    if (lo >= p->yin_lo && hi <= p->yin_hi) {
        return; /* every point of every line on the interior: the residues are G */
    }
    /* Lines that leave the interior: the residues count every point as interior (gfull of its
     * phase); each point outside the interior [yin_lo, yin_hi] is replaced by its own
     * normaliser gq (0 off the response grid). Those points are a prefix and a suffix of the
     * lines at each frame, so this costs O(m + outside points) instead of O(m n). q16: integer
     * sums, the same bits as summing gq over every point; bounded as the E sums. */
    const pft_real_t *restrict cq = p->gq; /* gq - gfull of the phase, per grid point */
    const int32_t ny = (int32_t)p->ny;
    for (int32_t tau = 0; tau < m; ++tau) {
        const int32_t d = bank_off_(p, e, kn - (uint32_t)tau) + jl;
        if (pft_pte_missing_(p, (uint32_t)tau) != 0u) {
            continue; /* a lost frame: no term in the residues either */
        }
        int32_t ja = p->yin_lo - d; /* lines [0, ja) below the interior */
        int32_t jb = p->yin_hi - d + 1; /* lines [jb, n) above it */
        ja = ja > n ? n : ja;
        jb = jb < 0 ? 0 : jb;
        jb = jb < ja ? ja : jb;
        if (ja > 0 || jb < n) { /* line_budget's units: the row and its points */
            p->n_line_ops += EDGE_ROW_UNITS_ + (uint32_t)(ja > 0 ? ja : 0) + (uint32_t)(jb < n ? n - jb : 0);
        }
        if (ja > 0) {
            int32_t jo = -d; /* lines [0, jo) off the grid, [jo, ja) on its edge band */
            jo = jo < 0 ? 0 : (jo > ja ? ja : jo);
            g_off_(p, G, 0, jo, d);
            for (int32_t j = jo; j < ja; ++j) {
                G[j] = G[j] + cq[j + d];
            }
        }
        if (jb < n) {
            int32_t jg = ny - d; /* lines [jb, jg) on the edge band, [jg, n) off the grid */
            jg = jg < jb ? jb : (jg > n ? n : jg);
            for (int32_t j = jb; j < jg; ++j) {
                G[j] = G[j] + cq[j + d];
            }
            g_off_(p, G, jg, n, d);
        }
    }
}

/* line_budget: an upper bound of the units bank_g_ spends on window w of entry e for its
 * lines [j0, j0 + n) at frame kn: every frame of the window a row, each with at most the
 * points of the lines' span over the window outside the interior. */
static uint32_t edge_units_(const pft_pte_t *p, const pft_pte_bank_t *e, uint32_t w,
                            uint32_t kn, int32_t j0, int32_t n)
{
    const int32_t m = e->m[w];
    const int32_t jl = e->jlo + j0;
    const int32_t d0 = bank_off_(p, e, kn) + jl;
    const int32_t d1 = bank_off_(p, e, kn - (uint32_t)(m > 0 ? m - 1 : 0)) + jl;
    const int32_t lo = d0 < d1 ? d0 : d1;
    const int32_t hi = (d0 > d1 ? d0 : d1) + n - 1;
    if (lo >= p->yin_lo && hi <= p->yin_hi) {
        return 0u;
    }
    int32_t out = (p->yin_lo > lo ? p->yin_lo - lo : 0) + (hi > p->yin_hi ? hi - p->yin_hi : 0);
    out = out > n ? n : out;
    return (uint32_t)m * (EDGE_ROW_UNITS_ + (uint32_t)out);
}

/* ------------------------------------------------------------------------ track step */

/* What the directions of one track step share. */
typedef struct {
    int32_t M;          /* operator length, frames */
    int32_t mm;         /* max(M, 2)^2 - 1 */
    int32_t n0, n1;     /* scan positions per axis (n1 = 1 for range-time) */
    int32_t nsc;        /* n0 * n1 */
    int32_t ndir;       /* L0 * L1 */
    int32_t reach64[2]; /* EXACT: reach of the per-frame weight table, 1/64 cells */
    pft_real_t dprior;  /* TABLE: 1 / (2 (S_tt + dth^2/12)), scaled slopes */
} step_geom_;

/* One operator direction: slopes per axis (scaled) and the log prior of its index. */
typedef struct {
    pft_real_t th[2];
    pft_real_t prior;
} dir_slope_;

/* Best scan position of one direction. */
typedef struct {
    int32_t jb;          /* index of the best summand */
    pft_real_t lmax;     /* the best summand's log */
    pft_real_t ssum;     /* sum over scan positions of exp(log summand - lmax), >= 1 */
    pft_real_t cstar[2]; /* best end position per axis, parabola refined */
    pft_real_t t2s;      /* T^2 at the best position with the sign of T (0 when G = 0) */
    pft_real_t e, g;     /* E and G at the best position */
} dir_best_;

/* Transition and process noise of the effective state [r, SV r', SA r''] of each axis (the
 * 4th state of the track layout stays 0), from model_ (at init). */
void pft_pte_model_setup_(pft_pte_t *p)
{
    for (uint32_t a = 0; a < 2u; ++a) {
        pft_real_t F[16];
        pft_real_t Q[16];
        model_(&p->cfg, a, F, Q);
        for (uint32_t i = 0; i < 3u; ++i) {
            for (uint32_t j = 0; j < 3u; ++j) {
                p->kF[a][3u * i + j] = F[4u * i + j];
                p->kQ[a][3u * i + j] = Q[4u * i + j];
            }
        }
    }
}

/* 1. Kalman prediction of the state (x = F x, P = F P F' + Q, products summed wide and
 * rounded once) and of the amplitude. q16 plain sums: every entry of F is at most 1 (2^16),
 * so each product with F is below 2^47 and Q 2^16 below 2^47: sums of four stay below 2^49. */
static inline void step_predict_(const pft_pte_t *p, pft_pte_track_t *t)
{
    for (uint32_t a = 0; a < p->naxes; ++a) {
        const pft_real_t *F = p->kF[a];
        const pft_real_t *Q = p->kQ[a];
        pft_real_t *x = t->x[a];
        pft_real_t *P = t->P[a];
        pft_real_t xn[3];
        pft_real_t fp[9];
        for (uint32_t i = 0; i < 3u; ++i) {
            acc_t v = 0;
            for (uint32_t l = 0; l < 3u; ++l) {
                v = aadd_(v, amul_(F[3u * i + l], x[l]));
            }
            xn[i] = ato_(v);
            for (uint32_t j = 0; j < 3u; ++j) {
                acc_t w = 0;
                for (uint32_t l = 0; l < 3u; ++l) {
                    w = aadd_(w, amul_(F[3u * i + l], P[4u * l + j]));
                }
                fp[3u * i + j] = ato_(w);
            }
        }
        for (uint32_t i = 0; i < 3u; ++i) {
            x[i] = xn[i];
            for (uint32_t j = i; j < 3u; ++j) {
                acc_t w = afrom_(Q[3u * i + j]);
                for (uint32_t l = 0; l < 3u; ++l) {
                    w = aadd_(w, amul_(fp[3u * i + l], F[3u * j + l]));
                }
                P[4u * i + j] = ato_(w);
                P[4u * j + i] = P[4u * i + j];
            }
        }
    }
    t->amp_var = pft_add(t->amp_var, p->cfg.q_amp);
}

/* Log prior -d^2 / (2 sc2) of the scan positions of axis a, d = off + j c_step their distance
 * from the predicted end position (off: that of the first position), as a recurrence:
 * -(off + j cs)^2 k has the constant second difference dd = -2 cs^2 k, so lc_{j+1} =
 * lc_j + dl_j with lc_0 = -off^2 k, dl_0 = -(2 off cs + cs^2) k and dl_{j+1} = dl_j + dd. */
typedef struct {
    pft_real_t lc, dl, dd;
} prior_rec_;

static prior_rec_ prior_rec_of_(const pft_pte_t *p, uint32_t a, pft_real_t off)
{
    const pft_pte_axis_t *ap = &p->scr->ap[a];
    const pft_real_t cs = p->cfg.c_step;
    prior_rec_ r;
    r.lc = pft_neg(pft_mul(pft_sq(off), ap->lck));
    r.dd = pft_neg(pft_mul_i(pft_mul(pft_sq(cs), ap->lck), 2));
    r.dl = pft_neg(pft_mul(pft_add(pft_mul_i(pft_mul(off, cs), 2), pft_sq(cs)), ap->lck));
    return r;
}

#ifdef PFT_NUMERIC_Q16
/* True when the recurrence of r over n steps, and each value plus half a squared statistic
 * (half_t2_, at most 737280000 < 2^30), stays inside the q16 range without saturating: with
 * exact sums dl_j = dl_0 + j dd and lc_j = lc_0 + sum_{i<j} dl_i, so for j <= n
 * |dl_j|, |lc_j| <= B = |lc_0| + n |dl_0| + n^2 |dd|; B < 2^30 keeps every partial sum and
 * lc_j + half_t2_ below 2^31 - 1 in magnitude (docs/fixed_point.md, "PTE-TBD Kalman algebra
 * and square root"). Then plain sums give the bits of pft_add. */
static inline bool prior_small_(const prior_rec_ *r, int32_t n)
{
    const int64_t lc = r->lc < 0 ? -(int64_t)r->lc : (int64_t)r->lc;
    const int64_t dl = r->dl < 0 ? -(int64_t)r->dl : (int64_t)r->dl;
    const int64_t dd = r->dd < 0 ? -(int64_t)r->dd : (int64_t)r->dd;
    return lc + (int64_t)n * dl + (int64_t)n * n * dd < ((int64_t)1 << 30);
}
#endif

#ifdef PFT_NUMERIC_Q16
/* prior_rec_of_ for the axis ap with c_step cs, given cs2 = cs^2 and its dd (the same
 * expressions, so the same bits) */
static inline prior_rec_ prior_rec_off_(const pft_pte_axis_t *ap, pft_real_t cs,
                                        pft_real_t cs2, pft_real_t dd, pft_real_t off)
{
    prior_rec_ r;
    r.lc = pft_neg(pft_mul(pft_sq(off), ap->lck));
    r.dd = dd;
    r.dl = pft_neg(pft_mul(pft_add(pft_mul_i(pft_mul(off, cs), 2), cs2), ap->lck));
    return r;
}
#endif

/* The log prior of every scan position of axis a into lc[a] (EXACT; TABLE runs the recurrence
 * inside the direction scan). */
static void scan_prior_(const pft_pte_t *p, uint32_t a, pft_real_t off)
{
    pft_pte_scratch_t *s = p->scr;
    const pft_pte_axis_t *ap = &s->ap[a];
    prior_rec_ r = prior_rec_of_(p, a, off);
    pft_real_t lc = r.lc;
    pft_real_t dl = r.dl;
    for (int32_t j = 0; j < ap->ns; ++j) {
        s->lc[a][j] = lc;
        lc = pft_add(lc, dl);
        dl = pft_add(dl, r.dd);
    }
}

/* TABLE: the directions of this step on the slope lattice (step dtheta_min): the lattice
 * point nearest to the predicted slope and (L - 1) / 2 more on each side, `mult` lattice
 * steps apart. The spacing is dtheta_min while the wanted spacing dth (5.3 step 2) is at
 * most 2.5 dtheta_min, else dth rounded to a multiple of dtheta_min [A]: a fine, fixed
 * spacing keeps the direction set from snapping the slope estimate to a coarse lattice, a
 * wide one keeps an uncertain slope (a cue, a young track) covered. The bank entries of the
 * directions are brought to this frame (entries of slopes no longer wanted are freed first;
 * a direction set moving by one lattice point costs one new entry at spacing dtheta_min).
 * Also the first scan line of each direction in its entry and its end position. */
static bool step_bank_(pft_pte_t *p, const pft_pte_track_t *t, step_geom_ *g)
{
    pft_pte_scratch_t *s = p->scr;
    pft_pte_axis_t *ap = &s->ap[0];
    const uint32_t ti = (uint32_t)(t - p->tracks);
    pft_pte_bank_t *bank = p->bank + (size_t)ti * p->nbank;
    const uint32_t kn = p->frames_in;
    const int32_t L = ap->L;
    const int32_t h = (L - 1) / 2;
    const int32_t q = p->yq;
    const pft_real_t lat = from_fix16_(p->lat_t);
    int32_t mult = 1;
    if (ap->dth > pft_mul(lat, PFT_C(2.5))) {
        mult = pft_round_int(div_(ap->dth, lat));
        mult = mult > 4096 ? 4096 : mult;
    }
    ap->dth = pft_mul_i(lat, mult);
    g->dprior = recip_(pft_mul_i(pft_add(ap->stt, div_i_(pft_sq(ap->dth), 12)), 2));
    /* lattice point nearest to the predicted slope */
    const int64_t lt = p->lat_t;
    const int64_t num = 2 * fix16_(ap->zt) + lt;
    int64_t c = num >= 0 ? num / (2 * lt) : -((-num + 2 * lt - 1) / (2 * lt));
    const int64_t cmax = (int64_t)1 << 24; /* |slope| far beyond any track */
    c = c > cmax ? cmax : (c < -cmax ? -cmax : c);
    /* slope_hold = hh: when the previous step's entries (at frame kn - 1) are the L consecutive
     * lattice slopes of spacing 1 centred on cp, one lattice step from c, and this step's
     * spacing is 1 too, the centre stays cp while |zt - cp lat| <= (1/2 + hh) lat (in 16.16:
     * |zt - cp lt| 2^16 <= (2^15 + hh 2^16) lt; |zt - cp lt| < 3/2 lt, so no overflow) */
    if (p->cfg.slope_hold > PFT_C(0.0) && mult == 1) {
        int64_t slo = 2147483647; /* above every int32 slope */
        int64_t shi = -2147483647 - 1;
        int32_t nl = 0;
        for (uint32_t b = 0; b < p->nbank; ++b) {
            if (bank[b].live && bank[b].kl + 1u == kn) {
                nl++;
                slo = bank[b].s < slo ? bank[b].s : slo;
                shi = bank[b].s > shi ? bank[b].s : shi;
            }
        }
        const int64_t cp = slo + h;
        if (nl == L && shi - slo == L - 1 && (cp - c == 1 || c - cp == 1)) {
            int64_t dz = fix16_(ap->zt) - cp * lt;
            dz = dz < 0 ? -dz : dz;
            if (dz * 65536 <= (32768 + fix16_(p->cfg.slope_hold)) * lt) {
                c = cp;
            }
        }
    }
    /* the slope wanted for direction i: c + (i - h) mult (formed where it is used, so that
     * no array of them sits on the stack of the track step) */
    const int32_t nw = L;
    int32_t sel[PFT_PTE_MAX_DIRS];
    for (uint32_t b = 0; b < p->nbank; ++b) {
        bank[b].used = 0u;
    }
    for (int32_t i = 0; i < nw; ++i) {
        sel[i] = -1;
        for (uint32_t b = 0; b < p->nbank; ++b) {
            if (bank[b].live && !bank[b].used && bank[b].s == (int32_t)(c + (i - h) * mult)) {
                sel[i] = (int32_t)b;
                bank[b].used = 1u;
                break;
            }
        }
    }
    for (uint32_t b = 0; b < p->nbank; ++b) {
        if (!bank[b].used) {
            bank[b].live = 0u;
        }
    }
    for (int32_t i = 0; i < nw; ++i) {
        for (uint32_t b = 0; sel[i] < 0 && b < p->nbank; ++b) {
            if (!bank[b].used) {
                sel[i] = (int32_t)b;
                bank[b].used = 1u;
                bank[b].s = (int32_t)(c + (i - h) * mult);
            }
        }
    }
    /* window lengths: max_len (or fewer frames while the track is young) and the short one */
    uint8_t m[PFT_PTE_NWIN_];
    m[0] = (uint8_t)g->M;
    m[1] = (uint8_t)(p->short_len == 0u ? 0 : (g->M < p->short_len ? g->M : p->short_len));
    /* lines whose end points cover the scan interval around the predicted end position zc */
    const int32_t half = (ap->ns - 1) / 2;
    const int64_t zg = (fix16_(ap->zc) + (int64_t)PFT_PTE_YPAD * 65536) * q;
    /* an entry holds up to MARGIN_ lines more on each side than the scan needs, so that scan
     * intervals moving back and forth cost nothing and new lines are summed a few at a time */
    int32_t margin = ((int32_t)p->nline - ap->ns) / 2;
    margin = margin > MARGIN_ ? MARGIN_ : margin;
    bool any = false; /* an entry complete (every one without line_budget) */
    const bool lb = p->cfg.line_budget != 0u;
    for (int32_t k = 0; k < nw; ++k) {
        /* line_budget: the entry of the predicted slope first, then outwards (h, h - 1,
         * h + 1, ...), so that a track steps on its central directions first */
        const int32_t i = lb ? h + ((k + 1) / 2) * ((k & 1) != 0 ? -1 : 1) : k;
        pft_pte_bank_t *e = &bank[sel[i]];
        bool ok;
        /* step_budget, line_budget: an entry also slides over the frames its track waited
         * (the frames leaving its windows still in the ring) */
        bool keep = e->live && (e->kl + 1u == kn ||
                                ((p->cfg.step_budget != 0u || lb) && kn - e->kl > 1u &&
                                 (uint32_t)(e->m[0] > e->m[1] ? e->m[0] : e->m[1]) + (kn - e->kl) <=
                                     (uint32_t)p->ring.count)) &&
                    kn - e->k0 < RENEW_;
        if (!keep) {
            e->k0 = kn; /* a fresh entry is anchored at this frame */
        }
        int64_t sh = (int64_t)e->s * p->lat_u * (int64_t)(int32_t)(kn - e->k0);
        int64_t jc = (zg - sh + 32768) >> 16;
        int32_t jlo = (int32_t)(jc - half);
        if (!lb) { /* without line_budget: every entry is brought to the frame */
            if (keep && jlo >= e->jlo && jlo + ap->ns <= e->jlo + (int32_t)e->n) {
                bank_sync_(p, ti, (uint32_t)sel[i], e->jlo, e->n, m, kn, keep);
            } else {
                bank_sync_(p, ti, (uint32_t)sel[i], jlo - margin, ap->ns + 2 * margin, m, kn, keep);
            }
            ok = true;
        } else {
            /* line_budget: in full when its cost fits in the budget left, else as far as it
             * goes (bank_part_) */
            const bool held = keep && jlo >= e->jlo && jlo + ap->ns <= e->jlo + (int32_t)e->n;
            const int32_t sj = held ? e->jlo : jlo - margin;
            const int32_t sn = held ? (int32_t)e->n : ap->ns + 2 * margin;
            if (sync_fits_(p, ti, (uint32_t)sel[i], sj, sn, m, kn, keep)) {
                const uint32_t before = p->n_line_ops;
                bank_sync_(p, ti, (uint32_t)sel[i], sj, sn, m, kn, keep);
                p->line_used += p->n_line_ops - before; /* what it spent, at most its cost */
                ok = true;
            } else {
                ok = bank_part_(p, ti, (uint32_t)sel[i], sj, sn, m, kn, keep);
            }
        }
        if (lb && ok) {
            /* line_budget: the edge correction of the lines the step reads (bank_g_, the
             * window and the short one when the manoeuvre test runs) is reserved here; when
             * it does not fit the direction waits as an incomplete one */
            const bool mt = p->short_len > 0u && g->M > (int32_t)p->short_len;
            const uint32_t ec = edge_units_(p, e, 0u, kn, jlo - e->jlo, ap->ns) +
                                (mt ? edge_units_(p, e, 1u, kn, jlo - e->jlo, ap->ns) : 0u);
            ok = p->line_used + ec <= p->cfg.line_budget;
            p->line_used += ok ? ec : 0u;
        }
        any = any || ok;
        /* i < L in either order (L odd) */
        s->bok[i] = ok ? 1u : 0u;
        s->bsel[i] = sel[i];
        s->bj0[i] = jlo - e->jlo;
        /* first scan position minus zc, cells: ((jc - half) 2^16 + sh - zg) / (2^16 q) */
        int64_t d16 = (jc - half) * 65536 + sh - zg;
        s->boff[i] = from_fix16_(d16 >= 0 ? (d16 + q / 2) / q : -((-d16 + q / 2) / q));
    }
    return any;
}

/* 2. Operator parameters of both axes, the log prior of every scan position, the EXACT
 * weight tables or the TABLE slope entries (computed once per step). False when line_budget
 * left every slope entry incomplete. */
static bool step_geometry_(pft_pte_t *p, const pft_pte_track_t *t, step_geom_ *g)
{
    const pft_pte_config_t *c = &p->cfg;
    const uint32_t na = p->naxes;
    pft_pte_scratch_t *s = p->scr;
    pft_pte_axis_t *ap = s->ap;
    int32_t M = t->n_acc;
    if (M > (int32_t)c->max_len) {
        M = (int32_t)c->max_len;
    }
    if (M > (int32_t)p->ring.count) {
        M = (int32_t)p->ring.count;
    }
    if (M < 1) {
        M = 1;
    }
    memset(ap, 0, 2u * sizeof(*ap));
    for (uint32_t a = 0; a < na; ++a) {
        axis_setup_(p, t->x[a], t->P[a], a, M, &ap[a]);
        if (p->yq == 0u) { /* TABLE: per direction, in the direction scan */
            scan_prior_(p, a, pft_neg(pft_mul_i(c->c_step, (ap[a].ns - 1) / 2)));
        }
    }
    /* steady_dirs (TABLE, one axis): a steady track whose n_dir[0] directions would sit at
     * the lattice step (step_bank_'s spacing dtheta_min) scans only the steady_dirs around
     * its predicted slope, at that step */
    if (c->steady_dirs != 0u && t->steady != 0u &&
        ap[0].dth <= pft_mul(from_fix16_(p->lat_t), PFT_C(2.5))) {
        ap[0].L = (int32_t)c->steady_dirs;
    }
    g->reach64[0] = 0;
    g->reach64[1] = 0;
    for (uint32_t a = 0; a < na && p->yq == 0u; ++a) {
        g->reach64[a] = gw_setup_(p, a, &ap[a]);
    }
    if (na == 1u) {
        ap[1].ns = 1;
        ap[1].L = 1;
        s->lc[1][0] = PFT_C(0.0);
    }
    g->M = M;
    g->n0 = ap[0].ns;
    g->n1 = ap[1].ns;
    g->ndir = ap[0].L * ap[1].L;
    g->nsc = g->n0 * g->n1;
    int32_t m1 = M > 1 ? M : 2;
    g->mm = m1 * m1 - 1;
    g->dprior = PFT_C(0.0);
    const bool ok = p->yq > 0u ? step_bank_(p, t, g) : true;
#ifdef PFT_NUMERIC_Q16
    /* q16: the terms of each direction's measurement noise and innovation covariance that do
     * not depend on the direction (dir_update_), once per step (after step_bank_, which sets
     * dth for TABLE); the float build forms them per direction (cheaper there: measured) */
    for (uint32_t a = 0; a < na; ++a) {
        ap[a].r0c = div_i_(pft_sq(c->c_step), 12);
        ap[a].r3c = div_i_(pft_sq(ap[a].dth), 12);
        ap[a].sw12 = pft_mul_i(ap[a].sw2, 12 * SV_ * SV_);
        ap[a].s00c = pft_sub(ap[a].sc2, pft_sq(c->sigma_r[a]));
    }
#endif
    return ok;
}

/* Slopes and log prior of direction li (index l0 + L0 l1). */
static dir_slope_ dir_slope_of_(const pft_pte_t *p, const step_geom_ *g, int32_t li)
{
    const pft_pte_axis_t *ap = p->scr->ap;
    dir_slope_ d;
    int32_t l[2];
    l[0] = li % ap[0].L;
    l[1] = li / ap[0].L;
    d.th[0] = PFT_C(0.0);
    d.th[1] = PFT_C(0.0);
    d.prior = PFT_C(0.0);
    if (p->yq > 0u) {
        /* TABLE: the direction's lattice slope */
        const pft_pte_bank_t *e = &p->bank[(size_t)(p->scr->ti) * p->nbank + (size_t)p->scr->bsel[li]];
        d.th[0] = from_fix16_((int64_t)e->s * p->lat_t);
        d.prior = pft_neg(pft_mul(pft_sq(pft_sub(d.th[0], ap[0].zt)), g->dprior));
        return d;
    }
    for (uint32_t a = 0; a < p->naxes; ++a) {
        int32_t k = l[a] - (ap[a].L - 1) / 2;
        d.th[a] = pft_add(ap[a].zt, pft_mul_i(ap[a].dth, k));
        d.prior = pft_sub(d.prior, pft_mul_i(ap[a].prior_k, k * k));
    }
    return d;
}

/* EXACT range-Doppler: adds frame zf (tau frames back) along slopes th to the operator sums
 * of the 2-D scan grid (separable weights). */
static void accum_2d_(pft_pte_t *p, const step_geom_ *g, const pft_real_t th[2], int32_t tau,
                      const pft_real_t *zf)
{
    pft_pte_scratch_t *s = p->scr;
    const size_t nr = p->cfg.in.n_range;
    taps_(p, 0u, &s->ap[0], g->reach64[0], line_shift_(th[0], tau), s->gs[0]);
    taps_(p, 1u, &s->ap[1], g->reach64[1], line_shift_(th[1], tau), s->gs[1]);
    for (int32_t j1 = 0; j1 < g->n1; ++j1) {
        int32_t lo1 = p->tlo[1][4 * j1];
        int32_t cnt1 = p->tlo[1][4 * j1 + 1];
        const pft_real_t *w1 = p->tw[1] + p->tlo[1][4 * j1 + 2];
        for (int32_t j0 = 0; j0 < g->n0; ++j0) {
            int32_t lo0 = p->tlo[0][4 * j0];
            int32_t cnt0 = p->tlo[0][4 * j0 + 1];
            const pft_real_t *w0 = p->tw[0] + p->tlo[0][4 * j0 + 2];
            pft_real_t e = PFT_C(0.0);
            for (int32_t i1 = 0; i1 < cnt1; ++i1) {
                const pft_real_t *zr = zf + (size_t)(lo1 + i1) * nr + (size_t)lo0;
                pft_real_t sum = PFT_C(0.0);
                for (int32_t i0 = 0; i0 < cnt0; ++i0) {
                    sum = pft_add(sum, pft_mul(w0[i0], zr[i0]));
                }
                e = pft_add(e, pft_mul(w1[i1], sum));
            }
            int32_t j = j1 * g->n0 + j0;
            p->sE[j] = pft_add(p->sE[j], e);
            p->sG[j] = pft_add(p->sG[j], pft_mul(s->gs[0][j0], s->gs[1][j1]));
        }
    }
}

/* 3. Operator sums E, G of one direction at every scan position, over the last M frames:
 * TABLE reads them from the direction's slope entry (window w); EXACT sums the taps. */
static void dir_sums_(pft_pte_t *p, const step_geom_ *g, const dir_slope_ *d, int32_t li,
                      uint32_t w, const pft_real_t **E, const pft_real_t **G)
{
    if (p->yq > 0u) {
        const int32_t j0 = p->scr->bj0[li];
        *E = bank_e_(p, p->scr->ti, (uint32_t)p->scr->bsel[li], w) + j0;
        bank_g_(p, p->scr->ti, (uint32_t)p->scr->bsel[li], w, p->frames_in, j0, g->n0, p->sG);
        *G = p->sG;
        return;
    }
    for (int32_t j = 0; j < g->nsc; ++j) {
        p->sE[j] = PFT_C(0.0);
        p->sG[j] = PFT_C(0.0);
    }
    const pft_pte_axis_t *ap0 = &p->scr->ap[0];
    const int32_t R0 = g->reach64[0];
    const pft_real_t th0 = d->th[0];
    const bool one = p->naxes == 1u;
    for (int32_t tau = 0; tau < g->M; ++tau) {
        if (pft_pte_missing_(p, (uint32_t)tau) != 0u) {
            continue; /* a lost frame: a missing stage, no E or G term */
        }
        const pft_real_t *zf = pft_pte_ring_get_(&p->ring, (uint32_t)tau);
        if (one) {
            accum_1d_(p, ap0, R0, line_shift_(th0, tau), zf);
        } else {
            accum_2d_(p, g, d->th, tau, zf);
        }
    }
    *E = p->sE;
    *G = p->sG;
}

/* 4. Test statistic and log summand of every scan position (into sL), the best one, its E,
 * G and T^2 (dir_finish_ adds the sum of the others relative to it and the refined best
 * position, which only a direction with a weight in the fusion needs). */
static dir_best_ dir_scan_(pft_pte_t *p, const step_geom_ *g, const pft_real_t *E,
                           const pft_real_t *G, const prior_rec_ *pr)
{
    const pft_pte_scratch_t *s = p->scr;
    const int32_t n0 = g->n0;
    dir_best_ r;
    pft_real_t lmax = PFT_REAL_MIN;
    r.jb = 0;
    if (pr != NULL) {
        /* TABLE (range-time): the log prior by its recurrence (the same additions as
         * scan_prior_; the Doppler term lc[1][0] is 0 and adding it changes no bit) */
        pft_real_t lc = pr->lc;
        pft_real_t dl = pr->dl;
#ifdef PFT_NUMERIC_Q16
        if (prior_small_(pr, n0)) {
            /* the same recurrence with plain sums: prior_small_ proves that no sum saturates */
            for (int32_t j = 0; j < n0; ++j) {
                const pft_real_t ls = lc + half_t2_(sq_over_(E[j], G[j]));
                lc = lc + dl;
                dl = dl + pr->dd;
                p->sL[j] = ls;
                if (ls > lmax) {
                    lmax = ls;
                    r.jb = j;
                }
            }
        } else
#endif
#ifndef PFT_NUMERIC_Q16
        if (n0 > 0) {
            /* float: the same sums in two passes, so that the first one (half the squared
             * statistic of every position, no loop-carried value) is vectorised; the second
             * adds the prior by its recurrence (the same sums in the same order) and finds
             * the first largest term, as the loop below does */
            pft_real_t *restrict sl = p->sL;
            half_t2_rows_(sl, E, G, n0);
            for (int32_t j = 0; j < n0; ++j) {
                const pft_real_t ls = lc + sl[j];
                lc = lc + dl;
                dl = dl + pr->dd;
                sl[j] = ls;
                if (ls > lmax) {
                    lmax = ls;
                    r.jb = j;
                }
            }
        } else
#endif
        {
            for (int32_t j = 0; j < n0; ++j) {
                pft_real_t t2 = sq_over_(E[j], G[j]);
                pft_real_t ls = pft_add(lc, half_t2_(t2));
                lc = pft_add(lc, dl);
                dl = pft_add(dl, pr->dd);
                p->sL[j] = ls;
                if (ls > lmax) {
                    lmax = ls;
                    r.jb = j;
                }
            }
        }
    } else if (g->n1 == 1) {
        /* one scan axis (range-time): the same sums without the index split */
        const pft_real_t lc1 = s->lc[1][0];
        for (int32_t j = 0; j < n0; ++j) {
            pft_real_t t2 = sq_over_(E[j], G[j]);
            pft_real_t ls = pft_add(pft_add(s->lc[0][j], lc1), half_t2_(t2));
            p->sL[j] = ls;
            if (ls > lmax) {
                lmax = ls;
                r.jb = j;
            }
        }
    } else {
        for (int32_t j = 0; j < g->nsc; ++j) {
            /* max(T, 0)^2 = E (E / G) for E > 0, clamped at 150^2 (no square root here; q16:
             * the product saturates at 32768 before the clamp, with the same result) */
            pft_real_t t2 = sq_over_(E[j], G[j]);
            pft_real_t ls = pft_add(pft_add(s->lc[0][j % n0], s->lc[1][j / n0]), half_t2_(t2));
            p->sL[j] = ls;
            if (ls > lmax) {
                lmax = ls;
                r.jb = j;
            }
        }
    }
    r.lmax = lmax;
    r.ssum = PFT_C(0.0);
    r.cstar[0] = PFT_C(0.0);
    r.cstar[1] = PFT_C(0.0);
    r.e = E[r.jb];
    r.g = G[r.jb];
    /* T^2 = E^2 / G clamped at 150^2 as T is; negative when E is */
    r.t2s = r.e < PFT_C(0.0) ? pft_neg(sq_over_(pft_neg(r.e), r.g)) : sq_over_(r.e, r.g);
    return r;
}

/* 4, the rest for a direction of the fusion: the sum of the terms of the scan positions
 * relative to the best one (the direction likelihood is their log-sum; the fusion needs no
 * logarithm) and the best position, parabola refined per axis (sL as dir_scan_ left it).
 * c0: first scan position per axis. */
static void dir_finish_(const pft_pte_t *p, const step_geom_ *g, const pft_real_t c0[2],
                        dir_best_ *rb)
{
    const int32_t n0 = g->n0;
    dir_best_ *r = rb;
    const pft_real_t lmax = r->lmax;
    /* terms below exp(-12) are skipped (q16: pft_exp rounds them to 0 anyway); the best
     * position's term is exp(0) = 1 exactly (both builds), added in its place without the call */
    pft_real_t ssum = PFT_C(0.0);
    const pft_real_t lcut = pft_sub(lmax, PFT_C(12.0));
    for (int32_t j = 0; j < g->nsc; ++j) {
        if (p->sL[j] > lcut) {
            /* lcut < sL[j] <= lmax: the difference is in (-12, 0] (pft_sub would not
             * saturate) and ssum, at most nsc <= 33^2 terms of at most 1, stays below 2^27 */
            ssum = ssum + (j == r->jb ? PFT_C(1.0) : exp_neg_(p->sL[j] - lmax));
        }
    }
    r->ssum = ssum;
    const int32_t jb = r->jb;
    for (uint32_t a = 0; a < p->naxes; ++a) {
        int32_t ja = a == 0u ? jb % n0 : jb / n0;
        int32_t na_ = a == 0u ? n0 : g->n1;
        int32_t stride = a == 0u ? 1 : n0;
        pft_real_t off = PFT_C(0.0);
        if (ja > 0 && ja < na_ - 1) {
            off = pft_pte_parabola_(p->sL[jb - stride], p->sL[jb], p->sL[jb + stride]);
        }
        r->cstar[a] = pft_add(c0[a], pft_mul(p->cfg.c_step, pft_add(pft_from_int(ja), off)));
    }
}

/* 5. Kalman update of the track's prediction with the direction's measurement [c*, theta]
 * per axis (H = [1 0 hc; 0 1 hv], R = diag(sigma_c^2, sigma_theta^2) of docs/algorithms.md
 * 5.3 step 5): the gain K = P H' S^-1 and the state change K nu, with P H' and H P H' shared
 * by the directions (step geometry); the covariance is formed once, at the fusion. The
 * amplitude gets a scalar update with E/G (variance 1/G). On a singular S the direction
 * leaves the prediction unchanged. */
static void dir_update_(const pft_pte_t *p, const pft_pte_track_t *t, const step_geom_ *g,
                        const dir_slope_ *d, const dir_best_ *b, pft_pte_dir_t *out)
{
    const pft_pte_axis_t *ap = p->scr->ap;
    const pft_real_t itc = recip_(pft_max(pft_abs(b->t2s), PFT_C(1.0)));
    memset(out->dx, 0, sizeof(out->dx));
    memset(out->K, 0, sizeof(out->K));
    for (uint32_t a = 0; a < p->naxes; ++a) {
        const pft_pte_axis_t *x = &ap[a];
        /* R: sigma_w^2 / T^2 + c_step^2 / 12 and dth^2 / 12 + 12 sigma_w^2 / ((M^2 - 1) T^2),
         * the latter scaled by SV^2 */
#ifdef PFT_NUMERIC_Q16
        pft_real_t r0 = pft_add(pft_mul(x->sw2, itc), x->r0c);
        pft_real_t r3 = pft_add(x->r3c, div_i_(pft_mul(x->sw12, itc), g->mm));
        pft_real_t s00 = pft_add(x->s00c, r0);
#else
        pft_real_t r0 = pft_add(pft_mul(x->sw2, itc), div_i_(pft_sq(p->cfg.c_step), 12));
        pft_real_t r3 = pft_add(div_i_(pft_sq(x->dth), 12),
                                div_i_(pft_mul(pft_mul_i(x->sw2, 12 * SV_ * SV_), itc), g->mm));
        pft_real_t s00 = pft_add(pft_sub(x->sc2, pft_sq(p->cfg.sigma_r[a])), r0);
#endif
        pft_real_t s11 = pft_add(x->stt, r3);
        /* q16 plain sums of two products, each below 2^62 in magnitude: below 2^63 */
        acc_t det = aadd_(amul_(s00, s11), -amul_(x->s01, x->s01));
        if (!(s00 > PFT_C(0.0)) || !(det > 0)) {
            continue;
        }
        pft_real_t nu0 = pft_sub(b->cstar[a], x->zc);
        pft_real_t nu1 = pft_sub(d->th[a], x->zt);
        for (uint32_t i = 0; i < 3u; ++i) {
            /* K = P H' adj(S) / det, each entry summed exactly and rounded once */
            const pft_real_t h0 = x->pht[2u * i];
            const pft_real_t h1 = x->pht[2u * i + 1u];
            pft_real_t k0 = adiv_(aadd_(amul_(h0, s11), -amul_(h1, x->s01)), det);
            pft_real_t k1 = adiv_(aadd_(amul_(h1, s00), -amul_(h0, x->s01)), det);
            out->K[a][2u * i] = k0;
            out->K[a][2u * i + 1u] = k1;
            out->dx[a][i] = ato_(aadd_(amul_(k0, nu0), amul_(k1, nu1)));
        }
    }
    /* amplitude: measurement E/G with variance 1/G: gain av G / (av G + 1) */
    pft_real_t am = t->amp;
    pft_real_t av = t->amp_var;
    if (b->g > PFT_C(0.0)) {
        pft_real_t inv = recip_(pft_add(pft_mul(av, b->g), PFT_C(1.0)));
        am = pft_add(am, pft_mul(pft_mul(av, pft_sub(b->e, pft_mul(am, b->g))), inv));
        av = pft_mul(av, inv);
    }
    out->amp = am;
    out->amp_var = av;
    out->logw = pft_add(d->prior, b->lmax);
    out->ssum = b->ssum;
}

/* Start of covariance sum (i, j) of the fusion: P_ij - kw_i0 pht_j0 - kw_i1 pht_j1, summed
 * saturating (the only wide sum of the track step without a bound on its terms). Reads the
 * upper triangle of P only (j >= i). */
#ifdef PFT_NUMERIC_Q16
static inline acc_t fuse_start_(const pft_real_t *P, const pft_real_t kw[6],
                                const pft_real_t pht[6], uint32_t i, uint32_t j)
{
    acc_t v = afrom_(P[4u * i + j]);
    v = aadd_sat_(v, -amul_(kw[2u * i], pht[2u * j]));
    return aadd_sat_(v, -amul_(kw[2u * i + 1u], pht[2u * j + 1u]));
}
#endif

/* q16: a direction of weight 0 is left out of the fusion's sums: each of its terms is an
 * integer product with w = 0, exactly 0 (directions skipped in the scan have w = 0 and no
 * state change or gain). float: every direction is summed, as before (0 times a value is
 * not always +0 there). */
#ifdef PFT_NUMERIC_Q16
#define W0_SKIP_ 1
#else
#define W0_SKIP_ 0
#endif

/* 6. Fusion of the directions with their normalised likelihoods W:
 * X = X_pred + sum W K nu and P = P_pred - (sum W K) H P_pred + sum W (dx - dX)(dx - dX)',
 * which is sum W (P_l + (X_l - X)(X_l - X)') when the weights sum to 1. Deviations from the
 * prediction are fused so that weights summing to 1 - epsilon after rounding (q16) cannot
 * bias the state. */
static void step_fuse_(pft_pte_t *p, pft_pte_track_t *t, int32_t ndir)
{
    const uint32_t na = p->naxes;
    const pft_pte_axis_t *ap = p->scr->ap;
    /* W_l proportional to exp(logw_l) ssum_l: prior times the sum over scan positions (in
     * dir[].w: 81 weights on the stack would put the update above the 1 KiB bound) */
    pft_pte_dir_t *dir = p->dir;
    pft_real_t lx = PFT_REAL_MIN;
    for (int32_t li = 0; li < ndir; ++li) {
        lx = pft_max(lx, p->dir[li].logw);
    }
    pft_real_t tot = PFT_C(0.0);
    for (int32_t li = 0; li < ndir; ++li) {
        pft_real_t dl = pft_sub(p->dir[li].logw, lx);
        /* the best direction: exp(0) = 1 exactly and 1 * ssum = ssum, without the calls */
        dir[li].w = dl > PFT_C(-12.0)
                        ? (dl == PFT_C(0.0) ? p->dir[li].ssum : pft_mul(exp_neg_(dl), p->dir[li].ssum))
                        : PFT_C(0.0);
        tot = pft_add(tot, dir[li].w);
    }
    const pft_real_t itot = recip_(tot); /* tot >= 1: the best direction's ssum */
    for (int32_t li = 0; li < ndir; ++li) {
        dir[li].w = pft_mul(dir[li].w, itot);
    }
    /* q16 bounds of the sums below: tot >= 2^16 (the best direction's ssum includes its exact
     * 1), so itot <= 2^16; each w before the product is at most tot, so w <= (w tot^-1 2^32 +
     * w / 2) / 2^16 + 1 < 2^17. A term w x of a pft_real_t x is then below 2^48, and a sum of
     * at most PFT_PTE_MAX_DIRS^2 = 81 of them below 2^55: plain sums (aadd_). */
    for (uint32_t a = 0; a < na; ++a) {
        pft_real_t df[3];
        pft_real_t kw[6];
        /* the nine weighted sums in one pass over the directions: each sum adds the same
         * terms in the same order (li ascending) as a loop of its own */
        acc_t v9[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0}; /* dX sums, then K W sums */
        for (int32_t li = 0; li < ndir; ++li) {
            const pft_real_t w = dir[li].w;
            if (W0_SKIP_ && w == 0) {
                continue; /* q16: its terms are 0 exactly (see W0_SKIP_) */
            }
            for (uint32_t i = 0; i < 3u; ++i) {
                v9[i] = aadd_(v9[i], amul_(w, p->dir[li].dx[a][i]));
            }
            for (uint32_t i = 0; i < 6u; ++i) {
                v9[3u + i] = aadd_(v9[3u + i], amul_(w, p->dir[li].K[a][i]));
            }
        }
        for (uint32_t i = 0; i < 3u; ++i) {
            df[i] = ato_(v9[i]);
        }
        for (uint32_t i = 0; i < 6u; ++i) {
            kw[i] = ato_(v9[3u + i]);
        }
        pft_real_t *P = t->P[a];
        /* the six covariance sums (i, j >= i) in one pass over the directions; the deviations
         * dx - dX once per direction (the same values); in v9[0..6) (its sums are read).
         * q16: the start P - kw pht has two products of unbounded pft_real_t values and is
         * summed saturating (aadd_sat_); the terms of the directions (below 2^55 in all, see
         * above) are summed plain from 0 and added to the start once, at the end. The same
         * value after ato_ as adding them to the start one at a time with saturation: when
         * |start| < 2^62 nothing saturates either way (|partial sums| < 2^62 + 2^55);
         * otherwise both sums keep the start's sign and a magnitude above 2^61, which ato_
         * saturates alike. float: the terms added to the start one at a time, as before. */
        acc_t *vp = v9;
        uint32_t k = 0u;
        for (uint32_t i = 0; i < 3u; ++i) {
            for (uint32_t j = i; j < 3u; ++j) {
#ifdef PFT_NUMERIC_Q16
                vp[k] = 0;
#else
                acc_t v = afrom_(P[4u * i + j]);
                v = aadd_(v, -amul_(kw[2u * i], ap[a].pht[2u * j]));
                vp[k] = aadd_(v, -amul_(kw[2u * i + 1u], ap[a].pht[2u * j + 1u]));
#endif
                k++;
            }
        }
        for (int32_t li = 0; li < ndir; ++li) {
            const pft_real_t w = dir[li].w;
            if (W0_SKIP_ && w == 0) {
                continue;
            }
            pft_real_t dv[3];
            for (uint32_t i = 0; i < 3u; ++i) {
                dv[i] = pft_sub(dir[li].dx[a][i], df[i]);
            }
            k = 0u;
            for (uint32_t i = 0; i < 3u; ++i) {
                for (uint32_t j = i; j < 3u; ++j) {
                    vp[k] = aadd_(vp[k], amul_(w, pft_mul(dv[i], dv[j])));
                    k++;
                }
            }
        }
        k = 0u;
        for (uint32_t i = 0; i < 3u; ++i) {
            for (uint32_t j = i; j < 3u; ++j) {
#ifdef PFT_NUMERIC_Q16
                P[4u * i + j] = ato_(aadd_sat_(fuse_start_(P, kw, ap[a].pht, i, j), vp[k]));
#else
                P[4u * i + j] = ato_(vp[k]);
#endif
                P[4u * j + i] = P[4u * i + j];
                k++;
            }
            t->x[a][i] = pft_add(t->x[a][i], df[i]);
        }
        P[0] = pft_max(P[0], PFT_REAL_EPS);
        P[5] = pft_max(P[5], PFT_REAL_EPS);
    }
    acc_t as = 0;
    for (int32_t li = 0; li < ndir; ++li) {
        if (!(W0_SKIP_ && dir[li].w == 0)) {
            as = aadd_(as, amul_(dir[li].w, pft_sub(p->dir[li].amp, t->amp)));
        }
    }
    pft_real_t amp = pft_add(t->amp, ato_(as));
    acc_t avs = 0;
    for (int32_t li = 0; li < ndir; ++li) {
        if (!(W0_SKIP_ && dir[li].w == 0)) {
            avs = aadd_(avs, amul_(dir[li].w, pft_add(p->dir[li].amp_var, pft_sq(pft_sub(p->dir[li].amp, amp)))));
        }
    }
    t->amp = amp;
    t->amp_var = pft_max(ato_(avs), PFT_REAL_EPS);
}

/* 7. Detection test, misses, termination (also when the track left the image). */
static void step_maintain_(const pft_pte_t *p, pft_pte_track_t *t, pft_real_t tmax)
{
    const pft_pte_config_t *c = &p->cfg;
    t->score = tmax;
    t->detected = tmax >= c->eta_t;
    t->misses = t->detected ? 0u : (uint8_t)(t->misses + 1u);
    if (t->n_acc < c->max_len) {
        t->n_acc++;
    }
    t->age++;
    if (t->misses >= c->max_misses) {
        t->live = false;
    }
    /* a track that left the image has no data left */
    for (uint32_t a = 0; a < p->naxes; ++a) {
        int32_t n = a == 0u ? (int32_t)c->in.n_range : (int32_t)c->in.n_doppler;
        if (t->x[a][0] < PFT_C(-2.0) || t->x[a][0] > pft_from_int(n + 1)) {
            t->live = false;
        }
    }
}

/* Signed T from a signed T^2. */
static pft_real_t signed_t_(pft_real_t t2s)
{
    pft_real_t v = sqrt_(pft_abs(t2s));
    return t2s < PFT_C(0.0) ? pft_neg(v) : v;
}

/* Manoeuvre test: |Z| > man_z with Z = (T_S sqrt(M) - T_L sqrt(Ms)) / sqrt(M - Ms) (M > Ms),
 * from the largest signed T^2 of the long (M frames) and the short (Ms frames) operators. */
static bool manoeuvre_(const pft_pte_t *p, int32_t M, pft_real_t t2l, pft_real_t t2s)
{
    const int32_t ms = (int32_t)p->short_len;
    pft_real_t num = pft_sub(pft_mul(signed_t_(t2s), pft_sqrt(pft_from_int(M))),
                             pft_mul(signed_t_(t2l), pft_sqrt(pft_from_int(ms))));
    return pft_abs(num) > pft_mul(p->cfg.man_z, pft_sqrt(pft_from_int(M - ms)));
}

void pft_pte_track_waited_(const pft_pte_t *p, pft_pte_track_t *t)
{
    for (uint32_t a = 0; a < p->naxes; ++a) {
        const int32_t n = a == 0u ? (int32_t)p->cfg.in.n_range : (int32_t)p->cfg.in.n_doppler;
        if (t->x[a][0] < PFT_C(-2.0) || t->x[a][0] > pft_from_int(n + 1)) {
            t->live = false; /* as in step 7 */
        }
    }
    if (t->wait >= p->cfg.max_len) {
        t->live = false;
    }
}

void pft_pte_track_coast_(pft_pte_t *p, pft_pte_track_t *t)
{
    step_predict_(p, t);
    if (t->n_acc < p->cfg.max_len) {
        t->n_acc++;
    }
    t->age++;
}

bool pft_pte_track_step_(pft_pte_t *p, pft_pte_track_t *t)
{
    step_geom_ g;
    pft_pte_scratch_t *s = p->scr;
    s->ti = (uint32_t)(t - p->tracks);
    step_predict_(p, t);
    if (!step_geometry_(p, t, &g)) {
        /* line_budget: every entry is still being summed; the frame is predicted over as a
         * lost one (pft_pte_track_coast_ after its prediction) */
        if (t->n_acc < p->cfg.max_len) {
            t->n_acc++;
        }
        t->age++;
        pft_pte_track_waited_(p, t);
        return false;
    }
    /* manoeuvre test when the template is longer than the short one (TABLE) */
    const bool mt = p->short_len > 0u && g.M > (int32_t)p->short_len;
    pft_real_t t2short = PFT_REAL_MIN;
    pft_real_t t2max = PFT_REAL_MIN;
#ifdef PFT_NUMERIC_Q16
    /* prior_rec_of_'s c_step^2 and dd of axis 0 (the same for every direction) */
    const pft_real_t pcs2 = pft_sq(p->cfg.c_step);
    const pft_real_t pdd = pft_neg(pft_mul_i(pft_mul(pcs2, s->ap[0].lck), 2));
#endif
    /* q16: a direction whose log weight is 12 or more below that of a direction already
     * scanned gets the fusion weight 0 (its dl there is at most the one tested here, so
     * dl <= -12), and every term it adds to the fusion is 0 exactly (integer products with
     * w = 0): it skips the rest of step 4 and step 5 (the same values; docs/fixed_point.md,
     * "PTE-TBD direction scan"). The central direction first, usually the most likely. The
     * order changes no value: each direction's results go to its own dir[li], and t2max and
     * t2short are maxima. The float build runs every direction in full, as before. */
#ifdef PFT_NUMERIC_Q16
    const bool lazy = true;
#else
    const bool lazy = false;
#endif
    const int32_t hc = (g.ndir - 1) / 2;
    pft_real_t lx_seen = PFT_REAL_MIN;
    bool seen = false;
    bool cin = false;
    for (int32_t k = 0; k < g.ndir; ++k) {
        /* q16: hc, 0, 1, ..., hc - 1, hc + 1, ..., ndir - 1; float: in index order */
        const int32_t li = !lazy ? k : (k == 0 ? hc : (k <= hc ? k - 1 : k));
        if (p->yq > 0u && s->bok[li] == 0u) {
            /* line_budget: an incomplete entry; the direction gets no weight in the fusion */
            pft_pte_dir_t *o = &p->dir[li];
            memset(o, 0, sizeof(*o));
            o->amp = t->amp;
            o->amp_var = t->amp_var;
            o->logw = PFT_REAL_MIN;
            continue;
        }
        dir_slope_ d = dir_slope_of_(p, &g, li);
        const pft_real_t *E;
        const pft_real_t *G;
        dir_sums_(p, &g, &d, li, 0u, &E, &G);
        pft_real_t c0[2] = {s->ap[0].c0, s->ap[1].c0};
        prior_rec_ pr;
        const prior_rec_ *prp = NULL;
        if (p->yq > 0u) {
            /* TABLE: the scan positions of the direction's lines at this frame */
            c0[0] = pft_add(s->ap[0].zc, s->boff[li]);
#ifdef PFT_NUMERIC_Q16
            /* prior_rec_of_ with its direction-independent terms formed once per step */
            pr = prior_rec_off_(&s->ap[0], p->cfg.c_step, pcs2, pdd, s->boff[li]);
#else
            pr = prior_rec_of_(p, 0u, s->boff[li]);
#endif
            prp = &pr;
        }
        dir_best_ b = dir_scan_(p, &g, E, G, prp);
        t2max = pft_max(t2max, b.t2s);
        const pft_real_t logw = pft_add(d.prior, b.lmax);
        if (lazy && seen && pft_sub(logw, lx_seen) <= PFT_C(-12.0)) {
            p->dir[li].logw = logw; /* weight 0 in the fusion (step_fuse_) */
        } else {
            dir_finish_(p, &g, c0, &b);
            /* steady_dirs' gate: the central direction's end position within one standard
             * deviation of the predicted one, (c* - zc)^2 <= P_cc + sigma_R^2 (q16: the
             * central direction is scanned first, so it always gets here) */
            if (p->cfg.steady_dirs != 0u && li == hc) {
                cin = pft_sq(pft_sub(b.cstar[0], s->ap[0].zc)) <= s->ap[0].sc2;
            }
            dir_update_(p, t, &g, &d, &b, &p->dir[li]);
            lx_seen = seen ? pft_max(lx_seen, logw) : logw;
            seen = true;
        }
        if (mt) {
            /* the same lines over the short window (the slope entry's second window): only
             * its T^2 is used */
            dir_sums_(p, &g, &d, li, 1u, &E, &G);
            dir_best_ bs = dir_scan_(p, &g, E, G, prp);
            t2short = pft_max(t2short, bs.t2s);
        }
    }
    step_fuse_(p, t, g.ndir);
    /* max_l T_l* from the largest signed T^2 */
    step_maintain_(p, t, signed_t_(t2max));
    if (p->cfg.steady_dirs != 0u) {
        /* steady_dirs: steady when detected with the central direction the likeliest (the
         * first largest fusion weight) */
        int32_t lb = 0;
        for (int32_t li = 1; li < g.ndir; ++li) {
            lb = p->dir[li].w > p->dir[lb].w ? li : lb;
        }
        t->steady = (t->detected && lb == hc && cin) ? 1u : 0u;
    }
    if (mt && manoeuvre_(p, g.M, t2max, t2short)) {
        t->n_acc = p->short_len; /* the next step's template: the last Ms frames */
        /* CA: man_acc_sd^2 more on r'' (scaled by SA^2); CV: (Ms man_acc_sd)^2 on r' (SV^2) */
        const bool ca = p->cfg.motion == PFT_PTE_MOTION_CA;
        uint32_t k = 1u;
        if (ca) {
            k = 2u;
        }
        const pft_real_t sd = ca ? pft_mul_i(p->cfg.man_acc_sd, SA_)
                                 : pft_mul_i(p->cfg.man_acc_sd, SV_ * (int32_t)p->short_len);
        for (uint32_t a = 0; a < p->naxes; ++a) {
            t->P[a][5u * k] = pft_add(t->P[a][5u * k], pft_sq(sd));
        }
    }
    return true;
}
