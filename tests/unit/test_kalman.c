/*
 * Kalman algebra against a double reference (the reference sees the library's own inputs
 * converted to double, so only the library's arithmetic error is measured), exact symmetry of
 * every covariance output, and refusal of non-positive-definite innovation covariances with
 * the state left untouched.
 *
 * Tolerance: |lib - ref| <= TOL_ABS + TOL_REL |ref| + TOL_SCALE s. In updates the gain K
 * carries an absolute rounding error, multiplied by the innovation in x + K y and by P H' in
 * P - K (P H')': s is the largest |y| entry for x and the largest |P H'| entry for P; s = 0 in
 * predictions. q16: TOL_ABS = 8 LSB, TOL_REL = 2e-5, TOL_SCALE = 2 LSB
 * per unit; float: TOL_ABS = 1e-5, TOL_REL = 2e-5, TOL_SCALE = 5e-7 (a few ulp).
 */
#include <math.h>
#include <string.h>
#include "pft_test_support.h"

void setUp(void) {}
void tearDown(void) {}

#ifdef PFT_NUMERIC_Q16
#define TOL_ABS (8.0 / 65536.0)
#define TOL_REL 2e-5
#define TOL_SCALE (2.0 / 65536.0)
#else
#define TOL_ABS 1e-5
#define TOL_REL 2e-5
#define TOL_SCALE 5e-7
#endif

static double worst_ratio; /* largest |err| / tolerance seen */
static const char *stage = "";
static double cur_scale; /* s in the tolerance */

static void note_begin(const char *label)
{
    UnityPrint(label);
    UnityPrint(":");
}
static void note(const char *name, double v)
{
    UnityPrint(" ");
    UnityPrint(name);
    UnityPrint("=");
    UnityPrintFloat(v);
}

static pft_real_t R_(double v)
{
    return pft_test_from_double(v);
}
static double D_(pft_real_t v)
{
    return pft_test_to_double(v);
}

static void check_close(const pft_real_t *got, const double *ref, int n)
{
    for (int i = 0; i < n; ++i) {
        const double tol = TOL_ABS + TOL_REL * fabs(ref[i]) + TOL_SCALE * cur_scale;
        const double err = fabs(D_(got[i]) - ref[i]);
        worst_ratio = err / tol > worst_ratio ? err / tol : worst_ratio;
        TEST_ASSERT_DOUBLE_WITHIN_MESSAGE(tol, ref[i], D_(got[i]), stage);
    }
}

static void check_symmetric(const pft_real_t *P, int n)
{
    for (int i = 0; i < n; ++i) {
        for (int j = i + 1; j < n; ++j) {
            TEST_ASSERT_TRUE(memcmp(&P[i * n + j], &P[j * n + i], sizeof(pft_real_t)) == 0);
        }
    }
}

/* ---------------------------------- double reference -------------------------------------- */
static void ref_matmul(const double *A, const double *B, double *C, int r, int k, int c)
{
    for (int i = 0; i < r; ++i) {
        for (int j = 0; j < c; ++j) {
            double s = 0.0;
            for (int l = 0; l < k; ++l) {
                s += A[i * k + l] * B[l * c + j];
            }
            C[i * c + j] = s;
        }
    }
}

static void ref_transpose(const double *A, double *At, int r, int c)
{
    for (int i = 0; i < r; ++i) {
        for (int j = 0; j < c; ++j) {
            At[j * r + i] = A[i * c + j];
        }
    }
}

static void ref_predict(int n, double *x, double *P, const double *F, const double *Q)
{
    double xn[4], FP[16], Ft[16], Pn[16];
    ref_matmul(F, x, xn, n, n, 1);
    ref_matmul(F, P, FP, n, n, n);
    ref_transpose(F, Ft, n, n);
    ref_matmul(FP, Ft, Pn, n, n, n);
    for (int i = 0; i < n * n; ++i) {
        P[i] = Pn[i] + Q[i];
    }
    memcpy(x, xn, sizeof(double) * (size_t)n);
}

/* largest |z - H x| entry */
static double max_innov(int n, int m, const double *x, const double *H, const double *z)
{
    double mx = 0.0;
    for (int a = 0; a < m; ++a) {
        double s = z[a];
        for (int l = 0; l < n; ++l) {
            s -= H[a * n + l] * x[l];
        }
        mx = fabs(s) > mx ? fabs(s) : mx;
    }
    return mx;
}

/* largest |P H'| entry (H m x n) */
static double max_pht(int n, int m, const double *P, const double *H)
{
    double mx = 0.0;
    for (int i = 0; i < n; ++i) {
        for (int a = 0; a < m; ++a) {
            double s = 0.0;
            for (int l = 0; l < n; ++l) {
                s += P[i * n + l] * H[a * n + l];
            }
            mx = fabs(s) > mx ? fabs(s) : mx;
        }
    }
    return mx;
}

/* general update with m-dim measurement, m <= 2 */
static void ref_update(int n, int m, double *x, double *P, const double *H, const double *z,
                       const double *R)
{
    double Ht[8], PHt[8], S[4], Si[4], K[8], y[2], KHP[16], HP[8];
    ref_transpose(H, Ht, m, n);
    ref_matmul(P, Ht, PHt, n, n, m);
    ref_matmul(H, PHt, S, m, n, m);
    for (int i = 0; i < m * m; ++i) {
        S[i] += R[i];
    }
    if (m == 1) {
        Si[0] = 1.0 / S[0];
    } else {
        const double det = S[0] * S[3] - S[1] * S[2];
        Si[0] = S[3] / det;
        Si[1] = -S[1] / det;
        Si[2] = -S[2] / det;
        Si[3] = S[0] / det;
    }
    ref_matmul(PHt, Si, K, n, m, m);
    ref_matmul(H, x, y, m, n, 1);
    for (int a = 0; a < m; ++a) {
        y[a] = z[a] - y[a];
    }
    for (int i = 0; i < n; ++i) {
        for (int a = 0; a < m; ++a) {
            x[i] += K[i * m + a] * y[a];
        }
    }
    ref_matmul(H, P, HP, m, n, n);
    ref_matmul(K, HP, KHP, n, m, n);
    for (int i = 0; i < n * n; ++i) {
        P[i] -= KHP[i];
    }
}

/* ---------------------------------- random inputs ----------------------------------------- */
static uint32_t lcg_state = 12345u;
static double rnd(void) /* uniform in [-1, 1) */
{
    lcg_state = lcg_state * 1664525u + 1013904223u;
    return (double)(lcg_state >> 8) / 8388608.0 - 1.0;
}

/* Symmetric positive definite n x n matrix with entries of size ~scale, exactly symmetric in
 * pft_real_t; Pd receives its exact double value. */
static void make_spd(int n, double scale, pft_real_t *P, double *Pd)
{
    double L[16] = {0};
    for (int i = 0; i < n; ++i) {
        for (int j = 0; j <= i; ++j) {
            L[i * n + j] = i == j ? 0.5 + fabs(rnd()) : 0.6 * rnd();
        }
    }
    for (int i = 0; i < n; ++i) {
        for (int j = i; j < n; ++j) {
            double s = 0.0;
            for (int l = 0; l < n; ++l) {
                s += L[i * n + l] * L[j * n + l];
            }
            P[i * n + j] = P[j * n + i] = R_(scale * s);
            Pd[i * n + j] = Pd[j * n + i] = D_(P[i * n + j]);
        }
    }
}

/* Adds v I (measurement noise of at least v keeps S well conditioned, as in a tracker). */
static void add_diag(int n, double v, pft_real_t *A, double *Ad)
{
    for (int i = 0; i < n; ++i) {
        A[i * n + i] = R_(Ad[i * n + i] + v);
        Ad[i * n + i] = D_(A[i * n + i]);
    }
}

static void to_real(const double *d, pft_real_t *r, int n, double *back)
{
    for (int i = 0; i < n; ++i) {
        r[i] = R_(d[i]);
        back[i] = D_(r[i]);
    }
}

/* ---------------------------------- tests ------------------------------------------------- */
static void test_kf2_predict_update_vs_reference(void)
{
    static const double I2[4] = {1.0, 0.0, 0.0, 1.0};
    for (int trial = 0; trial < 200; ++trial) {
        pft_real_t x[2], P[4], F[4], Q[4], z[2], R[4];
        double xd[2], Pd[4], Fd[4], Qd[4], zd[2], Rd[4];
        const double dt = 0.5 + 0.5 * fabs(rnd());
        const double Fs[4] = {1.0, dt, 0.05 * rnd(), 0.9 + 0.1 * rnd()};
        const double xs[2] = {20.0 * rnd(), 3.0 * rnd()};
        to_real(Fs, F, 4, Fd);
        to_real(xs, x, 2, xd);
        make_spd(2, 2.0, P, Pd);
        make_spd(2, 0.1, Q, Qd);
        make_spd(2, 0.5, R, Rd);
        add_diag(2, 0.5, R, Rd);
        stage = "kf2 predict";
        cur_scale = 0.0;
        pft_kf2_predict(x, P, F, Q);
        ref_predict(2, xd, Pd, Fd, Qd);
        check_close(x, xd, 2);
        check_close(P, Pd, 4);
        check_symmetric(P, 2);
        /* re-sync the reference to the library's state so the update error is measured alone */
        for (int i = 0; i < 4; ++i) {
            Pd[i] = D_(P[i]);
        }
        xd[0] = D_(x[0]);
        xd[1] = D_(x[1]);
        const double zs[2] = {xd[0] + 2.0 * rnd(), xd[1] + 2.0 * rnd()};
        to_real(zs, z, 2, zd);
        stage = "kf2 update";
        const double ys2 = max_innov(2, 2, xd, I2, zd), ps2 = max_pht(2, 2, Pd, I2);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_kf2_update(x, P, z, R));
        ref_update(2, 2, xd, Pd, I2, zd, Rd);
        cur_scale = ys2;
        check_close(x, xd, 2);
        cur_scale = ps2;
        check_close(P, Pd, 4);
        check_symmetric(P, 2);
        /* scalar update */
        for (int i = 0; i < 4; ++i) {
            Pd[i] = D_(P[i]);
        }
        xd[0] = D_(x[0]);
        xd[1] = D_(x[1]);
        const double hs[2] = {rnd(), rnd()};
        pft_real_t h[2];
        double hd[2], zz, rr;
        to_real(hs, h, 2, hd);
        const pft_real_t zr = R_(5.0 * rnd()), rr_ = R_(0.5 + fabs(rnd()));
        zz = D_(zr);
        rr = D_(rr_);
        stage = "kf2 scalar update";
        const double ys1 = max_innov(2, 1, xd, hd, &zz), ps1 = max_pht(2, 1, Pd, hd);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_kf2_update_scalar(x, P, h, zr, rr_));
        ref_update(2, 1, xd, Pd, hd, &zz, &rr);
        cur_scale = ys1;
        check_close(x, xd, 2);
        cur_scale = ps1;
        check_close(P, Pd, 4);
        check_symmetric(P, 2);
    }
}

static void test_kf4_predict_update_vs_reference(void)
{
    for (int trial = 0; trial < 200; ++trial) {
        pft_real_t x[4], P[16], F[16], Q[16], H[8], z[2], R[4];
        double xd[4], Pd[16], Fd[16], Qd[16], Hd[8], zd[2], Rd[4];
        const double dt = 1.0;
        /* constant velocity, state (px, vx, py, vy) */
        const double Fs[16] = {1, dt, 0, 0, 0, 1, 0, 0, 0, 0, 1, dt, 0, 0, 0, 1};
        const double Hs[8] = {1, 0, 0, 0, 0, 0, 1, 0};
        const double xs[4] = {50.0 * rnd(), 2.0 * rnd(), 50.0 * rnd(), 2.0 * rnd()};
        to_real(Fs, F, 16, Fd);
        to_real(Hs, H, 8, Hd);
        to_real(xs, x, 4, xd);
        make_spd(4, 1.5, P, Pd);
        make_spd(4, 0.05, Q, Qd);
        make_spd(2, 0.5, R, Rd);
        add_diag(2, 0.5, R, Rd);
        if (trial % 2 == 1) {
            /* a general (dense) measurement matrix */
            for (int i = 0; i < 8; ++i) {
                H[i] = R_(rnd());
                Hd[i] = D_(H[i]);
            }
        }
        stage = "kf4 predict";
        cur_scale = 0.0;
        pft_kf4_predict(x, P, F, Q);
        ref_predict(4, xd, Pd, Fd, Qd);
        check_close(x, xd, 4);
        check_close(P, Pd, 16);
        check_symmetric(P, 4);
        for (int i = 0; i < 16; ++i) {
            Pd[i] = D_(P[i]);
        }
        for (int i = 0; i < 4; ++i) {
            xd[i] = D_(x[i]);
        }
        const double zs[2] = {xd[0] + 2.0 * rnd(), xd[2] + 2.0 * rnd()};
        to_real(zs, z, 2, zd);
        stage = trial % 2 ? "kf4 update dense H" : "kf4 update";
        const double ys4 = max_innov(4, 2, xd, Hd, zd), ps4 = max_pht(4, 2, Pd, Hd);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_kf4_update2(x, P, H, z, R));
        ref_update(4, 2, xd, Pd, Hd, zd, Rd);
        cur_scale = ys4;
        check_close(x, xd, 4);
        cur_scale = ps4;
        check_close(P, Pd, 16);
        check_symmetric(P, 4);
    }
    note_begin("kalman");
    note("worst_err_over_tolerance", worst_ratio);
    UNITY_PRINT_EOL();
}

/* A long run stays symmetric and positive definite (no drift from rounding). */
static void test_long_run_stays_symmetric_pd(void)
{
    pft_real_t x[4] = {0}, P[16], F[16], Q[16], H[8], R[4], z[2];
    static const double Fs[16] = {1, 1, 0, 0, 0, 1, 0, 0, 0, 0, 1, 1, 0, 0, 0, 1};
    static const double Hs[8] = {1, 0, 0, 0, 0, 0, 1, 0};
    double tmp[16];
    to_real(Fs, F, 16, tmp);
    to_real(Hs, H, 8, tmp);
    memset(P, 0, sizeof P);
    memset(Q, 0, sizeof Q);
    for (int i = 0; i < 4; ++i) {
        P[i * 5] = R_(10.0);
        Q[i * 5] = R_(i % 2 ? 1e-4 : 0.0);
    }
    R[0] = R[3] = R_(0.5);
    R[1] = R[2] = R_(0.0);
    for (int k = 0; k < 500; ++k) {
        pft_kf4_predict(x, P, F, Q);
        z[0] = R_(0.5 * k + rnd());
        z[1] = R_(-0.25 * k + rnd());
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_kf4_update2(x, P, H, z, R));
        check_symmetric(P, 4);
        for (int i = 0; i < 4; ++i) {
            TEST_ASSERT_TRUE(P[i * 5] > 0);
        }
    }
    /* tracks the constant-velocity truth: velocity estimates near 0.5 and -0.25 */
    TEST_ASSERT_DOUBLE_WITHIN(0.1, 0.5, D_(x[1]));
    TEST_ASSERT_DOUBLE_WITHIN(0.1, -0.25, D_(x[3]));
}

static void test_non_pd_refused_state_untouched(void)
{
    pft_real_t x[4] = {R_(1.0), R_(2.0), R_(3.0), R_(4.0)};
    pft_real_t P[16] = {0};
    pft_real_t x0[4], P0[16];
    const pft_real_t z[2] = {R_(1.5), R_(2.5)};
    const pft_real_t H[8] = {R_(1.0), 0, 0, 0, 0, 0, R_(1.0), 0};
    for (int i = 0; i < 4; ++i) {
        P[i * 5] = R_(0.5);
    }
    P[1] = P[4] = R_(0.1);
    memcpy(x0, x, sizeof x);
    memcpy(P0, P, sizeof P);
    /* negative definite R: S = 0.5 I - 5 I */
    const pft_real_t Rneg[4] = {R_(-5.0), 0, 0, R_(-5.0)};
    /* indefinite R: S = [[1.5, 3], [3, 1.5]], det < 0 */
    const pft_real_t Rind[4] = {R_(1.0), R_(3.0), R_(3.0), R_(1.0)};
    /* singular S: P2 + R = [[1, 1], [1, 1]] (exact in both builds) */
    const pft_real_t Rsing[4] = {R_(0.5), R_(0.875), R_(0.875), R_(0.5)};
    TEST_ASSERT_EQUAL_INT(PFT_ERR_SINGULAR, pft_kf4_update2(x, P, H, z, Rneg));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_SINGULAR, pft_kf4_update2(x, P, H, z, Rind));
    TEST_ASSERT_EQUAL_MEMORY(x0, x, sizeof x);
    TEST_ASSERT_EQUAL_MEMORY(P0, P, sizeof P);
    /* 2-D: P2 = [[0.5, 0.125], [0.125, 0.5]] */
    pft_real_t x2[2] = {R_(1.0), R_(2.0)};
    pft_real_t P2[4] = {R_(0.5), R_(0.125), R_(0.125), R_(0.5)};
    pft_real_t x2c[2], P2c[4];
    memcpy(x2c, x2, sizeof x2);
    memcpy(P2c, P2, sizeof P2);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_SINGULAR, pft_kf2_update(x2, P2, z, Rneg));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_SINGULAR, pft_kf2_update(x2, P2, z, Rind));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_SINGULAR, pft_kf2_update(x2, P2, z, Rsing));
    const pft_real_t h[2] = {R_(1.0), R_(1.0)};
    /* h' P h = 1.25, r = -1.25 -> S = 0 exactly; r = -5 -> S < 0 */
    TEST_ASSERT_EQUAL_INT(PFT_ERR_SINGULAR, pft_kf2_update_scalar(x2, P2, h, R_(1.0), R_(-1.25)));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_SINGULAR, pft_kf2_update_scalar(x2, P2, h, R_(1.0), R_(-5.0)));
    TEST_ASSERT_EQUAL_MEMORY(x2c, x2, sizeof x2);
    TEST_ASSERT_EQUAL_MEMORY(P2c, P2, sizeof P2);
    /* and a valid update does change them */
    const pft_real_t Rok[4] = {R_(1.0), 0, 0, R_(1.0)};
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_kf2_update(x2, P2, z, Rok));
    TEST_ASSERT_FALSE(memcmp(x2c, x2, sizeof x2) == 0);
}

static void test_mat2_inverse_and_cholesky(void)
{
    cur_scale = 0.0;
    stage = "mat2";
    pft_real_t Ai[4], L[4];
    /* exact cases */
    const pft_real_t A[4] = {R_(2.0), R_(1.0), R_(1.0), R_(1.0)};
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_mat2_inv_sym(A, Ai));
    const double Aie[4] = {1.0, -1.0, -1.0, 2.0};
    check_close(Ai, Aie, 4);
    check_symmetric(Ai, 2);
    const pft_real_t B[4] = {R_(4.0), R_(2.0), R_(2.0), R_(5.0)};
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_mat2_chol(B, L));
    const double Le[4] = {2.0, 0.0, 1.0, 2.0};
    check_close(L, Le, 4);
    /* random SPD: L L' == A and A Ainv == I */
    for (int t = 0; t < 200; ++t) {
        pft_real_t S[4];
        double Sd[4];
        make_spd(2, 0.2 + 5.0 * fabs(rnd()), S, Sd);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_mat2_chol(S, L));
        const double l0 = D_(L[0]), l2 = D_(L[2]), l3 = D_(L[3]);
        TEST_ASSERT_EQUAL_INT(0, memcmp(&L[1], &(pft_real_t){0}, sizeof(pft_real_t)));
        TEST_ASSERT_DOUBLE_WITHIN(TOL_ABS * 8 + TOL_REL * 4 * Sd[0], Sd[0], l0 * l0);
        TEST_ASSERT_DOUBLE_WITHIN(TOL_ABS * 8 + TOL_REL * 4 * fabs(Sd[1]), Sd[1], l0 * l2);
        TEST_ASSERT_DOUBLE_WITHIN(TOL_ABS * 8 + TOL_REL * 4 * Sd[3], Sd[3], l2 * l2 + l3 * l3);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_mat2_inv_sym(S, Ai));
        const double det = Sd[0] * Sd[3] - Sd[1] * Sd[1];
        const double ref[4] = {Sd[3] / det, -Sd[1] / det, -Sd[1] / det, Sd[0] / det};
        check_close(Ai, ref, 4);
        check_symmetric(Ai, 2);
    }
    /* singular and indefinite: refused (PFT_ERR_SINGULAR), outputs untouched */
    const pft_real_t Sg[4] = {R_(1.0), R_(1.0), R_(1.0), R_(1.0)};
    const pft_real_t Id[4] = {R_(1.0), R_(2.0), R_(2.0), R_(1.0)};
    const pft_real_t Ng[4] = {R_(-1.0), 0, 0, R_(-1.0)};
    for (int i = 0; i < 4; ++i) {
        Ai[i] = L[i] = R_(7.0);
    }
    TEST_ASSERT_EQUAL_INT(PFT_ERR_SINGULAR, pft_mat2_inv_sym(Sg, Ai));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_SINGULAR, pft_mat2_inv_sym(Id, Ai));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_SINGULAR, pft_mat2_inv_sym(Ng, Ai));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_SINGULAR, pft_mat2_chol(Sg, L));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_SINGULAR, pft_mat2_chol(Id, L));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_SINGULAR, pft_mat2_chol(Ng, L));
    for (int i = 0; i < 4; ++i) {
        TEST_ASSERT_TRUE(Ai[i] == R_(7.0) && L[i] == R_(7.0));
    }
#ifdef PFT_NUMERIC_Q16
    /* q16: the determinant is exact, so a one-LSB margin is positive definite for Cholesky;
     * its inverse (~65536) is not representable and is refused (PFT_ERR_RANGE). */
    const pft_real_t E[4] = {R_(1.0) + 1, R_(1.0), R_(1.0), R_(1.0)};
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_mat2_chol(E, L));
    TEST_ASSERT_INT_WITHIN(2, 256, L[3]); /* sqrt(2^-16) = 2^-8 */
    TEST_ASSERT_EQUAL_INT(PFT_ERR_RANGE, pft_mat2_inv_sym(E, Ai));
#endif
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_kf2_predict_update_vs_reference);
    RUN_TEST(test_kf4_predict_update_vs_reference);
    RUN_TEST(test_long_run_stays_symmetric_pd);
    RUN_TEST(test_non_pd_refused_state_untouched);
    RUN_TEST(test_mat2_inverse_and_cholesky);
    return UNITY_END();
}
