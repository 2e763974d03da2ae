/* test_linalg.c -- unit tests of kernel/src/core/linalg.c against closed forms.
 *
 * Truths used: hand-computed products; residuals |A x - b| of LU / Cholesky /
 * least-squares solutions (backward error, independent of the solver); the
 * closed-form integer inverse of the Hilbert matrix; rcond of a diagonal
 * matrix = min|d| / max|d|; the normal equations of a 4-point line fit solved
 * by hand; the minimum-norm characterisation (A x = b and x in range(A^T)).
 * Random matrices come from a fixed-seed LCG so every run is identical on the
 * host and on the Cortex-M7 target. Large structs are static (target stack).
 *
 * Both precisions of ogk_real_t (ogk_test.h): the matrices handed to the
 * kernel are ogk_real_t, the references (products, residuals, closed forms)
 * are computed here in double from those same entries. A single-precision
 * tolerance is the double one's multiple of the unit round-off in float's
 * (written c * FLT_EPSILON: 1e-15 is 4.5 DBL_EPSILON, 1e-14 45, 1e-13 450,
 * 1e-12 4500), or a bound of its own where the text says so: round-off
 * bounds are linear in the unit round-off. The range tests (pivot floor,
 * input and solution bounds, the division bands, the norm's scaling) take the
 * float build's magnitudes (RANGE_* below: ogk/real.h, linalg.c). */
#include "ogk_test.h"

#include <float.h>
#include <string.h>

#include "ogk/linalg.h"

/* The magnitudes of the range tests in the build's type. Double: the pivot
 * floor OGK_REAL_TINY 1e-300, the input and solution bound OGK_REAL_ROOT_BIG
 * 1e150, la_div's bands 1 and 2^-512, la_norm2's scaling below 2^-400. Float:
 * 1e-30, 1e15, 1 and 2^-64, 2^-50 (ogk/real.h, linalg.c); each value below
 * stands where its double one does, on the same side of the same limit. */
#if OGK_REAL_SINGLE
#define R_BELOW_FLOOR 1e-35  /* under the floor */
#define R_ABOVE_FLOOR 2e-30  /* twice the floor */
#define R_ABOVE_FLOOR_2 4e-30
#define R_SCALE_MID 0x1p-30  /* norms scaled above 2^-50 */
#define R_SCALE_LOW 0x1p-70  /* ... and below, the entries still above the floor */
#define R_BEYOND 1e20        /* an input beyond the bound 1e15 */
#define R_BEYOND_2 2e15
#define R_HUGE 1.5e38        /* near FLT_MAX */
#define R_PIVOT 1e-25        /* a pivot above the floor, below 2^-64 */
#define R_B_OVER 1e-3        /* b / R_PIVOT beyond the bound */
#define R_B_IN 1e-11         /* b / R_PIVOT = 1e14 within it */
#define R_X_IN 1e14
#define R_INV_S 2e-25        /* test_inverse_overflow's s and c */
#define R_INV_C 3e4
#define R_UPPER_C 1e4        /* test_rcond_beyond_bound's off-diagonal */
#define R_BAND 1e15          /* test_division_bands: the bound ... */
#define R_BAND_IN 1e14       /* ... and a tenth of it */
#define R_TINY_D 1e-25       /* a divisor below 2^-64 */
#define R_B_TINY_IN 1e-11    /* and numerators whose quotients are within the bound */
#define R_B_TINY_IN_3 3e-11
#else
#define R_BELOW_FLOOR 1e-305
#define R_ABOVE_FLOOR 2e-300
#define R_ABOVE_FLOOR_2 4e-300
#define R_SCALE_MID 0x1p-300
#define R_SCALE_LOW 0x1p-660
#define R_BEYOND 1e200
#define R_BEYOND_2 2e150
#define R_HUGE 1.5e308
#define R_PIVOT 1e-250
#define R_B_OVER 1e100
#define R_B_IN 1e-110
#define R_X_IN 1e140
#define R_INV_S 2e-300
#define R_INV_C 1e6
#define R_UPPER_C 1e13
#define R_BAND 1e150
#define R_BAND_IN 1e149
#define R_TINY_D 1e-200
#define R_B_TINY_IN 1e-60
#define R_B_TINY_IN_3 3e-60
#endif

/* ------------------------------------------------------------------ helpers */

/* Knuth MMIX LCG; the top 53 bits give a uniform double in [-1, 1). */
static double lcg_uniform(uint64_t *state)
{
    *state = *state * 6364136223846793005ull + 1442695040888963407ull;
    return (double)(*state >> 11) * (2.0 / 9007199254740992.0) - 1.0;
}

static void fill_random(ogk_real_t *a, size_t count, uint64_t *state)
{
    size_t i;
    for (i = 0; i < count; ++i) {
        a[i] = lcg_uniform(state);
    }
}

/* Well-conditioned square matrix: uniform [-1, 1) entries plus n on the diagonal
 * (strictly diagonally dominant, so rcond is far above OGK_LA_RCOND_MIN). */
static void fill_dominant(ogk_real_t *a, size_t n, uint64_t *state)
{
    size_t i;
    fill_random(a, n * n, state);
    for (i = 0; i < n; ++i) {
        a[i * n + i] += (double)n;
    }
}

/* Infinity norm of A (rows x cols), computed here without the kernel. */
static double norm_inf(const ogk_real_t *A, size_t rows, size_t cols)
{
    double m = 0.0;
    size_t i;
    size_t j;
    for (i = 0; i < rows; ++i) {
        double s = 0.0;
        for (j = 0; j < cols; ++j) {
            s += fabs(A[i * cols + j]);
        }
        if (s > m) {
            m = s;
        }
    }
    return m;
}

/* |A x - b|_inf with the product done here (not by the kernel under test). */
static double residual_inf(const ogk_real_t *A, size_t rows, size_t cols,
                           const ogk_real_t *x, const ogk_real_t *b)
{
    double m = 0.0;
    size_t i;
    size_t j;
    for (i = 0; i < rows; ++i) {
        double s = -b[i];
        for (j = 0; j < cols; ++j) {
            s += A[i * cols + j] * x[j];
        }
        if (fabs(s) > m) {
            m = fabs(s);
        }
    }
    return m;
}

static void fill_hilbert(ogk_real_t *H, size_t n)
{
    size_t i;
    size_t j;
    for (i = 0; i < n; ++i) {
        for (j = 0; j < n; ++j) {
            H[i * n + j] = 1.0 / (double)(i + j + 1);
        }
    }
}

static double binomial(unsigned n, unsigned k)
{
    double c = 1.0;
    unsigned i;
    for (i = 1; i <= k; ++i) {
        c = c * (double)(n - k + i) / (double)i;
    }
    return c;
}

/* Closed-form inverse of the n x n Hilbert matrix (1-based i, j):
 * (-1)^(i+j) (i+j-1) C(n+i-1, n-j) C(n+j-1, n-i) C(i+j-2, i-1)^2. */
static void fill_hilbert_inverse(double *Hinv, unsigned n)
{
    unsigned i;
    unsigned j;
    for (i = 1; i <= n; ++i) {
        for (j = 1; j <= n; ++j) {
            const double c = binomial(i + j - 2, i - 1);
            const double sign = ((i + j) % 2u == 0u) ? 1.0 : -1.0;
            Hinv[(i - 1) * n + (j - 1)] = sign * (double)(i + j - 1) *
                                          binomial(n + i - 1, n - j) *
                                          binomial(n + j - 1, n - i) * c * c;
        }
    }
}

/* ------------------------------------------------------------------ products */

/* req: OGK-CORE-010 */
static void test_products_hand(void **state)
{
    /* A = [1 2 3; 4 5 6], B = [7 8; 9 10; 11 12], A B = [58 64; 139 154]. */
    static const ogk_real_t A[6] = {1, 2, 3, 4, 5, 6};
    static const ogk_real_t At[6] = {1, 4, 2, 5, 3, 6};
    static const ogk_real_t B[6] = {7, 8, 9, 10, 11, 12};
    static const ogk_real_t Bt[6] = {7, 9, 11, 8, 10, 12};
    static const double AB[4] = {58, 64, 139, 154};
    const ogk_real_t x3[3] = {1, 0, -1};
    const ogk_real_t x2[2] = {1, 1};
    ogk_real_t y[3];
    ogk_real_t C[4];
    ogk_real_t T[6];
    size_t i;
    (void)state;

    OGK_ASSERT_STATUS(ogk_mat_vec(A, 2, 3, x3, y), OGK_OK);
    OGK_ASSERT_NEAR(y[0], -2.0, 0.0);
    OGK_ASSERT_NEAR(y[1], -2.0, 0.0);

    OGK_ASSERT_STATUS(ogk_mat_t_vec(A, 2, 3, x2, y), OGK_OK);
    OGK_ASSERT_NEAR(y[0], 5.0, 0.0);
    OGK_ASSERT_NEAR(y[1], 7.0, 0.0);
    OGK_ASSERT_NEAR(y[2], 9.0, 0.0);

    OGK_ASSERT_STATUS(ogk_mat_mul(A, 2, 3, B, 2, C), OGK_OK);
    for (i = 0; i < 4; ++i) {
        OGK_ASSERT_NEAR(C[i], AB[i], 0.0);
    }
    /* A^T B with the 3 x 2 matrix At (so At^T = A). */
    memset(C, 0, sizeof C);
    OGK_ASSERT_STATUS(ogk_mat_mul_at_b(At, 3, 2, B, 2, C), OGK_OK);
    for (i = 0; i < 4; ++i) {
        OGK_ASSERT_NEAR(C[i], AB[i], 0.0);
    }
    /* A B^T with the 2 x 3 matrix Bt (so Bt^T = B). */
    memset(C, 0, sizeof C);
    OGK_ASSERT_STATUS(ogk_mat_mul_a_bt(A, 2, 3, Bt, 2, C), OGK_OK);
    for (i = 0; i < 4; ++i) {
        OGK_ASSERT_NEAR(C[i], AB[i], 0.0);
    }

    OGK_ASSERT_STATUS(ogk_mat_transpose(A, 2, 3, T), OGK_OK);
    for (i = 0; i < 6; ++i) {
        OGK_ASSERT_NEAR(T[i], At[i], 0.0);
    }
    /* 1 x 1 edge case. */
    OGK_ASSERT_STATUS(ogk_mat_mul(&A[1], 1, 1, &B[1], 1, C), OGK_OK);
    OGK_ASSERT_NEAR(C[0], 16.0, 0.0);
}

/* Largest allowed sizes, compared with sums written out here. */
/* req: OGK-CORE-010 OGK-CORE-005 */
static void test_products_max_size(void **state)
{
    enum { L = OGK_LA_MAX_LONG, S = OGK_LA_MAX_N };
    static ogk_real_t A[L * S];
    static ogk_real_t B[L * S];
    static ogk_real_t C[L * L];
    static ogk_real_t x[L];
    static ogk_real_t y[L];
    uint64_t seed = 11u;
    size_t i;
    size_t j;
    size_t p;
    (void)state;

    fill_random(A, L * S, &seed);
    fill_random(B, L * S, &seed);
    fill_random(x, L, &seed);

    /* C = A B^T: L x L from two L x S matrices. In float each entry is a sum
     * of S products of magnitude < 1, whose rounding errs by at most
     * gamma_S sum|a b| <= S u S (u = eps / 2: Higham, Accuracy and Stability,
     * 3.1): S^2 eps / 2; a sum of L terms, L S eps / 2 for the long inner
     * dimension (mat_vec, S terms of |A y| < S: S^2 S eps / 2). */
    OGK_ASSERT_STATUS(ogk_mat_mul_a_bt(A, L, S, B, L, C), OGK_OK);
    for (i = 0; i < L; i += 7) {
        for (j = 0; j < L; j += 5) {
            double s = 0.0;
            for (p = 0; p < S; ++p) {
                s += A[i * S + p] * B[j * S + p];
            }
            OGK_ASSERT_NEAR(C[i * L + j], s, OGK_TEST_TOL(1e-14, 0.5 * S * S * FLT_EPSILON));
        }
    }
    /* C = A^T B: S x S from two L x S matrices (long inner dimension). */
    OGK_ASSERT_STATUS(ogk_mat_mul_at_b(A, L, S, B, S, C), OGK_OK);
    for (i = 0; i < S; ++i) {
        for (j = 0; j < S; ++j) {
            double s = 0.0;
            for (p = 0; p < L; ++p) {
                s += A[p * S + i] * B[p * S + j];
            }
            OGK_ASSERT_NEAR(C[i * S + j], s, OGK_TEST_TOL(1e-13, 0.5 * L * L * FLT_EPSILON));
        }
    }
    /* y = A^T x and A (A^T x) through mat_vec. */
    OGK_ASSERT_STATUS(ogk_mat_t_vec(A, L, S, x, y), OGK_OK);
    for (j = 0; j < S; ++j) {
        double s = 0.0;
        for (p = 0; p < L; ++p) {
            s += A[p * S + j] * x[p];
        }
        OGK_ASSERT_NEAR(y[j], s, OGK_TEST_TOL(1e-13, 0.5 * L * L * FLT_EPSILON));
    }
    OGK_ASSERT_STATUS(ogk_mat_vec(A, L, S, y, x), OGK_OK);
    for (i = 0; i < L; ++i) {
        double s = 0.0;
        for (p = 0; p < S; ++p) {
            s += A[i * S + p] * y[p];
        }
        OGK_ASSERT_NEAR(x[i], s, OGK_TEST_TOL(1e-13, 0.5 * S * S * S * FLT_EPSILON));
    }
    /* Transpose twice is the identity. */
    OGK_ASSERT_STATUS(ogk_mat_transpose(A, L, S, C), OGK_OK);
    OGK_ASSERT_STATUS(ogk_mat_transpose(C, S, L, B), OGK_OK);
    for (i = 0; i < L * S; ++i) {
        OGK_ASSERT_NEAR(B[i], A[i], 0.0);
    }
}

/* req: OGK-CORE-010 OGK-CORE-021 */
static void test_products_errors(void **state)
{
    ogk_real_t A[4] = {1, 2, 3, 4};
    ogk_real_t B[4] = {5, 6, 7, 8};
    ogk_real_t C[4];
    ogk_real_t big[2];
    (void)state;

    OGK_ASSERT_STATUS(ogk_mat_vec(NULL, 2, 2, B, C), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_mat_vec(A, 2, 2, NULL, C), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_mat_vec(A, 2, 2, B, NULL), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_mat_t_vec(A, 2, 2, B, NULL), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_mat_mul(A, 2, 2, NULL, 2, C), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_mat_mul_at_b(NULL, 2, 2, B, 2, C), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_mat_mul_a_bt(A, 2, 2, B, 2, NULL), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_mat_transpose(NULL, 2, 2, C), OGK_E_NULL);

    OGK_ASSERT_STATUS(ogk_mat_vec(A, 0, 2, B, C), OGK_E_DIM);
    OGK_ASSERT_STATUS(ogk_mat_vec(A, 2, 0, B, C), OGK_E_DIM);
    OGK_ASSERT_STATUS(ogk_mat_t_vec(A, OGK_LA_MAX_LONG + 1u, 1, B, C), OGK_E_DIM);
    OGK_ASSERT_STATUS(ogk_mat_mul(A, 2, 0, B, 2, C), OGK_E_DIM);
    OGK_ASSERT_STATUS(ogk_mat_mul(A, 1, 1, B, OGK_LA_MAX_LONG + 1u, C), OGK_E_DIM);
    OGK_ASSERT_STATUS(ogk_mat_mul_at_b(A, OGK_LA_MAX_LONG + 1u, 1, B, 1, C), OGK_E_DIM);
    OGK_ASSERT_STATUS(ogk_mat_mul_a_bt(A, 1, 1, B, 0, C), OGK_E_DIM);
    OGK_ASSERT_STATUS(ogk_mat_transpose(A, 0, 0, C), OGK_E_DIM);

    /* Output overlapping an input (whole or partial) is rejected untouched. */
    OGK_ASSERT_STATUS(ogk_mat_vec(A, 2, 2, B, B), OGK_E_RANGE);
    OGK_ASSERT_STATUS(ogk_mat_vec(A, 2, 2, B, &A[3]), OGK_E_RANGE);
    OGK_ASSERT_STATUS(ogk_mat_t_vec(A, 2, 2, B, &B[1]), OGK_E_RANGE);
    OGK_ASSERT_STATUS(ogk_mat_mul(A, 2, 2, B, 2, A), OGK_E_RANGE);
    OGK_ASSERT_STATUS(ogk_mat_mul(A, 2, 2, B, 2, B), OGK_E_RANGE);
    OGK_ASSERT_STATUS(ogk_mat_mul_at_b(A, 2, 2, B, 2, &B[2]), OGK_E_RANGE);
    OGK_ASSERT_STATUS(ogk_mat_mul_a_bt(A, 2, 2, B, 2, &A[1]), OGK_E_RANGE);
    OGK_ASSERT_STATUS(ogk_mat_transpose(A, 2, 2, A), OGK_E_RANGE);
    OGK_ASSERT_NEAR(A[0], 1.0, 0.0);
    OGK_ASSERT_NEAR(A[1], 2.0, 0.0);
    OGK_ASSERT_NEAR(B[2], 7.0, 0.0);
    /* Adjacent but not overlapping is fine: y = A[0:2] x into A[2:4]. */
    big[0] = 1.0;
    big[1] = 1.0;
    OGK_ASSERT_STATUS(ogk_mat_vec(A, 1, 2, big, &A[2]), OGK_OK);
    OGK_ASSERT_NEAR(A[2], 3.0, 0.0);
}

/* ------------------------------------------------------------------ LU */

/* req: OGK-CORE-011 */
static void test_lu_random_solve_inverse(void **state)
{
    static const size_t sizes[] = {1, 2, 3, 5, 8, 13, 16};
    static ogk_lu_t lu;
    static ogk_real_t A[OGK_LA_MAX_N * OGK_LA_MAX_N];
    static ogk_real_t Ainv[OGK_LA_MAX_N * OGK_LA_MAX_N];
    ogk_real_t b[OGK_LA_MAX_N];
    ogk_real_t x[OGK_LA_MAX_N];
    uint64_t seed = 20261121u;
    size_t s;
    size_t trial;
    (void)state;

    for (s = 0; s < sizeof sizes / sizeof sizes[0]; ++s) {
        const size_t n = sizes[s];
        for (trial = 0; trial < 5; ++trial) {
            size_t i;
            size_t j;
            size_t p;
            double res;
            fill_dominant(A, n, &seed);
            fill_random(b, n, &seed);
            OGK_ASSERT_STATUS(ogk_lu_factor(&lu, A, n), OGK_OK);
            assert_int_equal(lu.n, n);
            assert_true(lu.rcond > 0.1 && lu.rcond <= 1.0);
            OGK_ASSERT_STATUS(ogk_lu_solve(&lu, b, x), OGK_OK);
            /* Backward error: |A x - b| <= c n eps (|A| |x| + |b|). */
            res = residual_inf(A, n, n, x, b);
            assert_true(res <= 16.0 * (double)n * OGK_TEST_EPS *
                                   (norm_inf(A, n, n) * ogk_test_max_abs(x, n) + ogk_test_max_abs(b, n)));
            /* x may alias b. */
            OGK_ASSERT_STATUS(ogk_lu_solve(&lu, b, b), OGK_OK);
            for (i = 0; i < n; ++i) {
                OGK_ASSERT_NEAR(b[i], x[i], 0.0);
            }
            /* A^-1 A = I. */
            OGK_ASSERT_STATUS(ogk_lu_inverse(&lu, Ainv), OGK_OK);
            for (i = 0; i < n; ++i) {
                for (j = 0; j < n; ++j) {
                    double s_ij = 0.0;
                    for (p = 0; p < n; ++p) {
                        s_ij += Ainv[i * n + p] * A[p * n + j];
                    }
                    OGK_ASSERT_NEAR(s_ij, (i == j) ? 1.0 : 0.0, OGK_TEST_TOL(1e-13, 450.0 * FLT_EPSILON));
                }
            }
        }
    }
}

/* rcond of diag(d) = min|d| / max|d| exactly; |A|_1 = max|d|; perm from pivoting. */
/* req: OGK-CORE-011 */
static void test_lu_rcond_closed_form(void **state)
{
    static ogk_lu_t lu;
    const ogk_real_t D[16] = {3, 0, 0, 0, 0, -0.25, 0, 0, 0, 0, 8, 0, 0, 0, 0, 1.5};
    const ogk_real_t U[4] = {1, 2, 0, 4};
    const ogk_real_t M3[9] = {1, 2, 3, 4, 5, 6, 7, 8, 10};
    const ogk_real_t P[4] = {0, 1, 1, 0}; /* needs a row swap */
    const ogk_real_t b[2] = {2, 5};
    ogk_real_t x[2];
    (void)state;

    OGK_ASSERT_STATUS(ogk_lu_factor(&lu, D, 4), OGK_OK);
    OGK_ASSERT_NEAR(lu.anorm1, 8.0, 0.0);
    OGK_ASSERT_REL(lu.rcond, 0.25 / 8.0, OGK_TEST_TOL(1e-15, 4.5 * FLT_EPSILON), 0.0);

    /* Non-symmetric closed form: A = [1 2; 0 4], |A|_1 = 6, A^-1 = [1 -0.5; 0 0.25],
     * |A^-1|_1 = 1, so rcond = 1/6 (an infinity-norm slip would give 1/4.5). */
    OGK_ASSERT_STATUS(ogk_lu_factor(&lu, U, 2), OGK_OK);
    OGK_ASSERT_NEAR(lu.anorm1, 6.0, 0.0);
    OGK_ASSERT_REL(lu.rcond, 1.0 / 6.0, OGK_TEST_TOL(1e-15, 4.5 * FLT_EPSILON), 0.0);

    /* Partial pivoting picks the largest |a_ik| of each column: for
     * [1 2 3; 4 5 6; 7 8 10] the first pivot row is 2; after elimination the
     * second column holds 2 - 8/7 = 6/7 (row 0) and 5 - 32/7 = 3/7 (row 1),
     * so row 0 comes next: perm = [2, 0, 1]. */
    OGK_ASSERT_STATUS(ogk_lu_factor(&lu, M3, 3), OGK_OK);
    assert_int_equal(lu.perm[0], 2);
    assert_int_equal(lu.perm[1], 0);
    assert_int_equal(lu.perm[2], 1);
    /* one rounding each: 1e-16 is 0.45 eps (half an ulp of 4/7 and less) */
    OGK_ASSERT_NEAR(lu.lu[3], 1.0 / 7.0, OGK_TEST_TOL(1e-16, 0.45 * FLT_EPSILON));  /* l_10 = 1/7 */
    OGK_ASSERT_NEAR(lu.lu[6], 4.0 / 7.0, OGK_TEST_TOL(1e-16, 0.45 * FLT_EPSILON));  /* l_20 = 4/7 */
    OGK_ASSERT_NEAR(lu.lu[7], 0.5, OGK_TEST_TOL(1e-15, 4.5 * FLT_EPSILON));        /* l_21 = (3/7)/(6/7) */

    OGK_ASSERT_STATUS(ogk_lu_factor(&lu, P, 2), OGK_OK);
    OGK_ASSERT_NEAR(lu.rcond, 1.0, OGK_TEST_TOL(1e-15, 4.5 * FLT_EPSILON));
    assert_int_equal(lu.perm[0], 1);
    assert_int_equal(lu.perm[1], 0);
    OGK_ASSERT_STATUS(ogk_lu_solve(&lu, b, x), OGK_OK);
    OGK_ASSERT_NEAR(x[0], 5.0, 0.0);
    OGK_ASSERT_NEAR(x[1], 2.0, 0.0);
}

/* Hilbert matrices against the closed-form integer inverse. */
/* req: OGK-CORE-011 */
static void test_lu_hilbert(void **state)
{
    static ogk_lu_t lu;
    static ogk_real_t H[OGK_LA_MAX_N * OGK_LA_MAX_N];
    static double Hinv_exact[OGK_LA_MAX_N * OGK_LA_MAX_N];
    static ogk_real_t Hinv[OGK_LA_MAX_N * OGK_LA_MAX_N];
    ogk_real_t b[OGK_LA_MAX_N];
    ogk_real_t x[OGK_LA_MAX_N];
    double hnorm1 = 0.0;
    double hinv_norm1 = 0.0;
    size_t i;
    size_t j;
    /* n = 5: cond_1 = 9.4e5, so the computed inverse and rcond carry
     * relative errors near cond * eps = 2e-10 (tolerance 1e-8: 50 cond eps).
     * In float, cond eps would be 0.11 (and H's entries rounded to float are
     * themselves a relative perturbation of eps / 2): n = 3, cond_1 = 748
     * (|H|_1 = 11/6, |H^-1|_1 = 408), the same 50 cond eps. */
#if OGK_REAL_SINGLE
    const unsigned hn = 3u;
#else
    const unsigned hn = 5u;
#endif
    (void)state;

    fill_hilbert(H, hn);
    fill_hilbert_inverse(Hinv_exact, hn);
    for (j = 0; j < hn; ++j) {
        double colsum = 0.0;
        for (i = 0; i < hn; ++i) {
            colsum += fabs(Hinv_exact[i * hn + j]);
        }
        hinv_norm1 = fmax(hinv_norm1, colsum);
    }
    for (i = 0; i < hn; ++i) {
        hnorm1 += 1.0 / (double)(i + 1); /* first column has the largest sum */
    }
    OGK_ASSERT_STATUS(ogk_lu_factor(&lu, H, hn), OGK_OK);
    OGK_ASSERT_REL(lu.anorm1, hnorm1, OGK_TEST_TOL(1e-15, 4.5 * FLT_EPSILON), 0.0);
    OGK_ASSERT_REL(lu.rcond, 1.0 / (hnorm1 * hinv_norm1), OGK_TEST_TOL(1e-8, 50.0 * 748.0 * FLT_EPSILON), 0.0);
    OGK_ASSERT_STATUS(ogk_lu_inverse(&lu, Hinv), OGK_OK);
    for (i = 0; i < hn * hn; ++i) {
        OGK_ASSERT_REL(Hinv[i], Hinv_exact[i], OGK_TEST_TOL(1e-8, 50.0 * 748.0 * FLT_EPSILON), 0.0);
    }

    /* n = 12: cond_1 ~ 4e16 -> ill-conditioned, factors kept and usable. In
     * float a pivot falls below eps |A|_1 first (from n = 7 on): singular to
     * working precision, the factorization refused (lu.n = 0), as documented
     * for OGK_E_SINGULAR. A float matrix that is ill-conditioned, not
     * singular, is test_rcond_beyond_bound's. */
    fill_hilbert(H, 12);
#if OGK_REAL_SINGLE
    OGK_ASSERT_STATUS(ogk_lu_factor(&lu, H, 12), OGK_E_SINGULAR);
    assert_int_equal(lu.n, 0);
    (void)b;
    (void)x;
#else
    OGK_ASSERT_STATUS(ogk_lu_factor(&lu, H, 12), OGK_E_ILL_CONDITIONED);
    assert_int_equal(lu.n, 12);
    assert_true(lu.rcond < OGK_LA_RCOND_MIN);
    assert_true(lu.rcond > 0.0);
    for (i = 0; i < 12; ++i) {
        x[i] = 1.0;
    }
    for (i = 0; i < 12; ++i) {
        b[i] = 0.0;
        for (j = 0; j < 12; ++j) {
            b[i] += H[i * 12 + j];
        }
    }
    OGK_ASSERT_STATUS(ogk_lu_solve(&lu, b, x), OGK_OK);
    /* Solution is inaccurate, but the backward error stays at round-off. */
    assert_true(residual_inf(H, 12, 12, x, b) <=
                1e3 * DBL_EPSILON * (norm_inf(H, 12, 12) * ogk_test_max_abs(x, 12) + ogk_test_max_abs(b, 12)));
    OGK_ASSERT_STATUS(ogk_lu_inverse(&lu, Hinv), OGK_OK);
#endif
}

/* req: OGK-CORE-011 */
static void test_lu_singular(void **state)
{
    static ogk_lu_t lu;
    static const ogk_real_t A_good[4] = {2, 1, 1, 3};
    /* Elimination is exact in binary for these, so the zero pivot is exact. */
    static const ogk_real_t S2[4] = {1, 2, 2, 4};
    static const ogk_real_t S3[9] = {2, 1, 1, 4, 2, 2, 1, 1, 1};
    static const ogk_real_t Z3[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
    /* A pivot below eps |A|_1 and one above (float: eps = 1.2e-7). */
#if OGK_REAL_SINGLE
    static const ogk_real_t tiny17[4] = {1, 0, 0, 1e-8};
    static const ogk_real_t tiny15[4] = {1, 0, 0, 1e-6};
#else
    static const ogk_real_t tiny17[4] = {1, 0, 0, 1e-17};
    static const ogk_real_t tiny15[4] = {1, 0, 0, 1e-15};
#endif
    const ogk_real_t b[3] = {1, 1, 1};
    ogk_real_t x[3];
    (void)state;

    OGK_ASSERT_STATUS(ogk_lu_factor(&lu, A_good, 2), OGK_OK);
    assert_int_equal(lu.n, 2);
    OGK_ASSERT_STATUS(ogk_lu_factor(&lu, S2, 2), OGK_E_SINGULAR);
    assert_int_equal(lu.n, 0);
    OGK_ASSERT_NEAR(lu.rcond, 0.0, 0.0);
    /* A failed factorization cannot be used. */
    OGK_ASSERT_STATUS(ogk_lu_solve(&lu, b, x), OGK_E_NOT_INIT);
    OGK_ASSERT_STATUS(ogk_lu_inverse(&lu, x), OGK_E_NOT_INIT);

    /* Pivot threshold eps |A|_1: a 1e-17 pivot under a unit pivot is zero to
     * working precision; 1e-15 is not (rcond = 1e-15: ill-conditioned). In
     * float 1e-8 is zero and 1e-6 is not; its rcond 1e-6 is below the float
     * OGK_LA_RCOND_MIN (512 eps = 6.1e-5, ogk/linalg.h): ill-conditioned, as
     * in double. */
    OGK_ASSERT_STATUS(ogk_lu_factor(&lu, tiny17, 2), OGK_E_SINGULAR);
    assert_int_equal(lu.n, 0);
#if OGK_REAL_SINGLE
    OGK_ASSERT_STATUS(ogk_lu_factor(&lu, tiny15, 2), OGK_E_ILL_CONDITIONED);
    assert_int_equal(lu.n, 2);
    OGK_ASSERT_REL(lu.rcond, 1e-6, 4.5 * FLT_EPSILON, 0.0);
#else
    OGK_ASSERT_STATUS(ogk_lu_factor(&lu, tiny15, 2), OGK_E_ILL_CONDITIONED);
    assert_int_equal(lu.n, 2);
    OGK_ASSERT_REL(lu.rcond, 1e-15, 1e-15, 0.0);
#endif

    OGK_ASSERT_STATUS(ogk_lu_factor(&lu, S3, 3), OGK_E_SINGULAR);
    assert_int_equal(lu.n, 0);
    OGK_ASSERT_STATUS(ogk_lu_factor(&lu, Z3, 3), OGK_E_SINGULAR);
    assert_int_equal(lu.n, 0);
}

/* req: OGK-CORE-011 OGK-CORE-021 */
static void test_lu_errors(void **state)
{
    static ogk_lu_t lu;
    static ogk_lu_t lu2;
    ogk_real_t A[4] = {4, 1, 1, 3};
    ogk_real_t b[2] = {1, 2};
    ogk_real_t x[2];
    (void)state;

    OGK_ASSERT_STATUS(ogk_lu_factor(NULL, A, 2), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_lu_factor(&lu, A, 2), OGK_OK);
    OGK_ASSERT_STATUS(ogk_lu_factor(&lu, NULL, 2), OGK_E_NULL);
    assert_int_equal(lu.n, 0);

    OGK_ASSERT_STATUS(ogk_lu_factor(&lu, A, 2), OGK_OK);
    OGK_ASSERT_STATUS(ogk_lu_factor(&lu, A, 0), OGK_E_DIM);
    assert_int_equal(lu.n, 0);
    OGK_ASSERT_STATUS(ogk_lu_factor(&lu, A, OGK_LA_MAX_N + 1u), OGK_E_DIM);

    A[3] = NAN;
    OGK_ASSERT_STATUS(ogk_lu_factor(&lu, A, 2), OGK_E_NONFINITE);
    assert_int_equal(lu.n, 0);
    A[3] = -INFINITY;
    OGK_ASSERT_STATUS(ogk_lu_factor(&lu, A, 2), OGK_E_NONFINITE);
    A[3] = 3.0;

    /* Factoring the struct's own storage is aliasing. */
    OGK_ASSERT_STATUS(ogk_lu_factor(&lu2, A, 2), OGK_OK);
    OGK_ASSERT_STATUS(ogk_lu_factor(&lu2, lu2.lu, 2), OGK_E_RANGE);
    assert_int_equal(lu2.n, 0);

    OGK_ASSERT_STATUS(ogk_lu_factor(&lu, A, 2), OGK_OK);
    OGK_ASSERT_STATUS(ogk_lu_solve(NULL, b, x), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_lu_solve(&lu, NULL, x), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_lu_solve(&lu, b, NULL), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_lu_inverse(NULL, x), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_lu_inverse(&lu, NULL), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_lu_solve(&lu, b, lu.lu), OGK_E_RANGE);
    OGK_ASSERT_STATUS(ogk_lu_inverse(&lu, lu.lu), OGK_E_RANGE);
    b[1] = NAN;
    OGK_ASSERT_STATUS(ogk_lu_solve(&lu, b, x), OGK_E_NONFINITE);
    b[1] = 2.0;
    /* A held factorization still solves after all those rejected calls:
     * [4 1; 1 3] x = [1 2] -> x = [1/11, 7/11]. */
    OGK_ASSERT_STATUS(ogk_lu_solve(&lu, b, x), OGK_OK);
    OGK_ASSERT_NEAR(x[0], 1.0 / 11.0, OGK_TEST_TOL(1e-16, 0.45 * FLT_EPSILON));
    OGK_ASSERT_NEAR(x[1], 7.0 / 11.0, OGK_TEST_TOL(1e-16, 0.45 * FLT_EPSILON));
}

/* ------------------------------------------------------------------ Cholesky */

/* req: OGK-CORE-011 */
static void test_chol_closed_form(void **state)
{
    static ogk_chol_t ch;
    /* [4 2; 2 2] = L L^T with L = [2 0; 1 1]. */
    const ogk_real_t A[4] = {4, 2, 2, 2};
    const ogk_real_t b[2] = {2, 0};
    ogk_real_t x[2];
    (void)state;

    OGK_ASSERT_STATUS(ogk_chol_factor(&ch, A, 2), OGK_OK);
    assert_int_equal(ch.n, 2);
    OGK_ASSERT_NEAR(ch.l[0], 2.0, 0.0);
    OGK_ASSERT_NEAR(ch.l[1], 0.0, 0.0);
    OGK_ASSERT_NEAR(ch.l[2], 1.0, 0.0);
    OGK_ASSERT_NEAR(ch.l[3], 1.0, 0.0);
    /* [4 2; 2 2] x = [2 0] -> x = [1, -1]. */
    OGK_ASSERT_STATUS(ogk_chol_solve(&ch, b, x), OGK_OK);
    OGK_ASSERT_NEAR(x[0], 1.0, OGK_TEST_TOL(1e-15, 4.5 * FLT_EPSILON));
    OGK_ASSERT_NEAR(x[1], -1.0, OGK_TEST_TOL(1e-15, 4.5 * FLT_EPSILON));
}

/* req: OGK-CORE-011 */
static void test_chol_random_spd(void **state)
{
    static ogk_chol_t ch;
    static ogk_real_t M[OGK_LA_MAX_N * OGK_LA_MAX_N];
    static ogk_real_t A[OGK_LA_MAX_N * OGK_LA_MAX_N];
    ogk_real_t b[OGK_LA_MAX_N];
    ogk_real_t x[OGK_LA_MAX_N];
    uint64_t seed = 7u;
    size_t n;
    (void)state;

    for (n = 1; n <= OGK_LA_MAX_N; n += 3) {
        size_t i;
        size_t j;
        size_t p;
        /* A = M M^T + I is SPD with eigenvalues >= 1. */
        fill_random(M, n * n, &seed);
        for (i = 0; i < n; ++i) {
            for (j = 0; j < n; ++j) {
                double s = (i == j) ? 1.0 : 0.0;
                for (p = 0; p < n; ++p) {
                    s += M[i * n + p] * M[j * n + p];
                }
                A[i * n + j] = s;
            }
        }
        fill_random(b, n, &seed);
        OGK_ASSERT_STATUS(ogk_chol_factor(&ch, A, n), OGK_OK);
        for (i = 0; i < n; ++i) {
            for (j = 0; j < n; ++j) {
                double s = 0.0;
                if (j > i) {
                    OGK_ASSERT_NEAR(ch.l[i * n + j], 0.0, 0.0);
                }
                for (p = 0; p < n; ++p) {
                    s += ch.l[i * n + p] * ch.l[j * n + p];
                }
                OGK_ASSERT_NEAR(s, A[i * n + j], OGK_TEST_TOL(1e-13, 450.0 * FLT_EPSILON) * norm_inf(A, n, n));
            }
        }
        OGK_ASSERT_STATUS(ogk_chol_solve(&ch, b, x), OGK_OK);
        assert_true(residual_inf(A, n, n, x, b) <=
                    16.0 * (double)n * OGK_TEST_EPS *
                        (norm_inf(A, n, n) * ogk_test_max_abs(x, n) + ogk_test_max_abs(b, n)));
        OGK_ASSERT_STATUS(ogk_chol_solve(&ch, b, b), OGK_OK); /* x may alias b */
        for (i = 0; i < n; ++i) {
            OGK_ASSERT_NEAR(b[i], x[i], 0.0);
        }
    }
}

/* req: OGK-CORE-011 */
static void test_chol_rejects(void **state)
{
    static ogk_chol_t ch;
    const ogk_real_t spd[4] = {4, 2, 2, 2};
    const ogk_real_t indefinite[4] = {1, 2, 2, 1};      /* eigenvalues 3, -1 */
    const ogk_real_t semidefinite[4] = {1, 1, 1, 1};    /* eigenvalues 2, 0 */
    const ogk_real_t negative[4] = {-1, 0, 0, -1};
#if OGK_REAL_SINGLE
    /* float: d = 2^-23 = eps is refused, d = 2^-20 = 8 eps (sqrt 2^-10, exact) passes */
    const ogk_real_t dep52[4] = {1, 1, 1, 1.0 + FLT_EPSILON};
    const ogk_real_t dep50[4] = {1, 1, 1, 1.0 + 8.0 * FLT_EPSILON};
#else
    const ogk_real_t dep52[4] = {1, 1, 1, 1.0 + DBL_EPSILON};
    const ogk_real_t dep50[4] = {1, 1, 1, 1.0 + 4.0 * DBL_EPSILON};
#endif
    const ogk_real_t tiny_diag[4] = {1, 0, 0, 1e-17};
    const ogk_real_t nonsymmetric[4] = {4, 1, 0, 3};    /* SPD lower part, upper differs */
    const ogk_real_t nearly_sym[4] = {4, 2.0 + 1e-14, 2, 2}; /* within 1e-12 relative */
    ogk_real_t A[4] = {4, 2, 2, 2};
    const ogk_real_t b[2] = {1, 1};
    ogk_real_t x[2];
    (void)state;

    OGK_ASSERT_STATUS(ogk_chol_factor(&ch, spd, 2), OGK_OK);
    OGK_ASSERT_STATUS(ogk_chol_factor(&ch, indefinite, 2), OGK_E_NOT_POSDEF);
    assert_int_equal(ch.n, 0);
    OGK_ASSERT_STATUS(ogk_chol_solve(&ch, b, x), OGK_E_NOT_INIT);
    OGK_ASSERT_STATUS(ogk_chol_factor(&ch, semidefinite, 2), OGK_E_NOT_POSDEF);
    OGK_ASSERT_STATUS(ogk_chol_factor(&ch, negative, 2), OGK_E_NOT_POSDEF);
    /* Pivot threshold d_i > eps a_ii (exact arithmetic here): [1 1; 1 1+2^-52]
     * leaves d = 2^-52 < eps (1 + 2^-52): not positive definite to working
     * precision; with 1+2^-50, d = 4 eps passes. A tiny but independent
     * diagonal (diag(1, 1e-17)) is fine. */
    OGK_ASSERT_STATUS(ogk_chol_factor(&ch, dep52, 2), OGK_E_NOT_POSDEF);
    OGK_ASSERT_STATUS(ogk_chol_factor(&ch, dep50, 2), OGK_OK);
    OGK_ASSERT_NEAR(ch.l[3], OGK_TEST_TOL(0.5 * ldexp(1.0, -24), ldexp(1.0, -10)), 0.0); /* sqrt(2^-50), float sqrt(2^-20) */
    OGK_ASSERT_STATUS(ogk_chol_factor(&ch, tiny_diag, 2), OGK_OK);
    OGK_ASSERT_STATUS(ogk_chol_factor(&ch, spd, 2), OGK_OK);
    OGK_ASSERT_STATUS(ogk_chol_factor(&ch, nonsymmetric, 2), OGK_E_NOT_POSDEF);
    assert_int_equal(ch.n, 0);
    OGK_ASSERT_STATUS(ogk_chol_factor(&ch, nearly_sym, 2), OGK_OK);
#if OGK_REAL_SINGLE
    /* In float 2 + 1e-14 is 2 (the check above is of a symmetric matrix). The
     * symmetry tolerance OGK_CHOL_SYM_TOL (1e-12 relative, both builds) is
     * below float's resolution: one ulp of asymmetry (2 + 2^-22) is refused,
     * the documented answer for a matrix not symmetric to that tolerance. */
    {
        const ogk_real_t one_ulp[4] = {4, 2.0 + ldexp(1.0, -22), 2, 2};
        OGK_ASSERT_STATUS(ogk_chol_factor(&ch, one_ulp, 2), OGK_E_NOT_POSDEF);
    }
#endif

    OGK_ASSERT_STATUS(ogk_chol_factor(NULL, spd, 2), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_chol_factor(&ch, NULL, 2), OGK_E_NULL);
    assert_int_equal(ch.n, 0);
    OGK_ASSERT_STATUS(ogk_chol_factor(&ch, spd, 0), OGK_E_DIM);
    OGK_ASSERT_STATUS(ogk_chol_factor(&ch, spd, OGK_LA_MAX_N + 1u), OGK_E_DIM);
    A[2] = INFINITY;
    OGK_ASSERT_STATUS(ogk_chol_factor(&ch, A, 2), OGK_E_NONFINITE);
    OGK_ASSERT_STATUS(ogk_chol_factor(&ch, ch.l, 1), OGK_E_RANGE);
    OGK_ASSERT_STATUS(ogk_chol_factor(&ch, spd, 2), OGK_OK);
    OGK_ASSERT_STATUS(ogk_chol_solve(NULL, b, x), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_chol_solve(&ch, NULL, x), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_chol_solve(&ch, b, NULL), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_chol_solve(&ch, b, ch.l), OGK_E_RANGE);
}

/* ------------------------------------------------------------------ least squares */

/* Line fit y = c0 + c1 t through (0,1) (1,2) (2,2) (3,5): the normal equations
 * [4 6; 6 14] c = [10; 21] give c = [0.7; 1.2] by hand (det 20). */
/* req: OGK-CORE-012 */
static void test_lstsq_line_fit(void **state)
{
    static ogk_qr_t ws;
    const ogk_real_t A[8] = {1, 0, 1, 1, 1, 2, 1, 3};
    const ogk_real_t b[4] = {1, 2, 2, 5};
    ogk_real_t c[2];
    (void)state;

    OGK_ASSERT_STATUS(ogk_lstsq(&ws, A, 4, 2, b, c), OGK_OK);
    OGK_ASSERT_NEAR(c[0], 0.7, OGK_TEST_TOL(1e-15, 4.5 * FLT_EPSILON));
    OGK_ASSERT_NEAR(c[1], 1.2, OGK_TEST_TOL(1e-15, 4.5 * FLT_EPSILON));
    assert_int_equal(ws.long_dim, 4);
    assert_int_equal(ws.short_dim, 2);
}

/* req: OGK-CORE-012 */
static void test_lstsq_random(void **state)
{
    static ogk_qr_t ws;
    static ogk_real_t A[OGK_LA_MAX_LONG * OGK_LA_MAX_N];
    static ogk_real_t b[OGK_LA_MAX_LONG];
    static double r[OGK_LA_MAX_LONG];
    static const size_t shapes[][2] = {{1, 1}, {3, 3}, {5, 3}, {20, 7}, {64, 16}, {128, 16}, {128, 1}};
    ogk_real_t x_true[OGK_LA_MAX_N];
    ogk_real_t x[OGK_LA_MAX_N];
    uint64_t seed = 99u;
    size_t s;
    (void)state;

    for (s = 0; s < sizeof shapes / sizeof shapes[0]; ++s) {
        const size_t m = shapes[s][0];
        const size_t n = shapes[s][1];
        size_t i;
        size_t j;
        fill_random(A, m * n, &seed);
        fill_random(x_true, n, &seed);

        /* Exactly consistent system b = A x_true: x = x_true. */
        for (i = 0; i < m; ++i) {
            b[i] = 0.0;
            for (j = 0; j < n; ++j) {
                b[i] += A[i * n + j] * x_true[j];
            }
        }
        OGK_ASSERT_STATUS(ogk_lstsq(&ws, A, m, n, b, x), OGK_OK);
        for (j = 0; j < n; ++j) {
            OGK_ASSERT_NEAR(x[j], x_true[j], OGK_TEST_TOL(1e-12, 4500.0 * FLT_EPSILON));
        }

        /* Inconsistent system: the residual is orthogonal to range(A),
         * i.e. the normal equations A^T (b - A x) = 0 hold. */
        fill_random(b, m, &seed);
        OGK_ASSERT_STATUS(ogk_lstsq(&ws, A, m, n, b, x), OGK_OK);
        for (i = 0; i < m; ++i) {
            r[i] = b[i];
            for (j = 0; j < n; ++j) {
                r[i] -= A[i * n + j] * x[j];
            }
        }
        for (j = 0; j < n; ++j) {
            double g = 0.0;
            for (i = 0; i < m; ++i) {
                g += A[i * n + j] * r[i];
            }
            OGK_ASSERT_NEAR(g, 0.0, OGK_TEST_TOL(1e-12, 4500.0 * FLT_EPSILON));
        }
    }
}

/* req: OGK-CORE-012 */
static void test_lstsq_rank_deficient(void **state)
{
    static ogk_qr_t ws;
    /* Zero second column: exactly rank 1. */
    const ogk_real_t zero_col[6] = {1, 0, 2, 0, 3, 0};
    /* Second column = 2 x first: rank 1 up to Householder round-off. */
    const ogk_real_t dup_col[6] = {1, 2, 2, 4, 3, 6};
    /* Columns differ by 1e-15 relative: cond ~ 1e15. */
    ogk_real_t near_col[6] = {1, 1, 2, 2, 3, 3};
    const ogk_real_t b[3] = {1, 2, 3};
    ogk_real_t x[2] = {-7.0, -7.0};
    ogk_status st;
    (void)state;

    OGK_ASSERT_STATUS(ogk_lstsq(&ws, zero_col, 3, 2, b, x), OGK_E_SINGULAR);
    assert_int_equal(ws.long_dim, 0);
    assert_int_equal(ws.short_dim, 0);
    OGK_ASSERT_NEAR(x[0], -7.0, 0.0); /* untouched */

    st = ogk_lstsq(&ws, dup_col, 3, 2, b, x);
    assert_true(st == OGK_E_SINGULAR || st == OGK_E_ILL_CONDITIONED);

    near_col[5] = 3.0 * (1.0 + 1e-15 * 8.0);
    st = ogk_lstsq(&ws, near_col, 3, 2, b, x);
    assert_true(st == OGK_E_SINGULAR || st == OGK_E_ILL_CONDITIONED);

    /* Minimum norm: second row = 2 x first (round-off rank 1), then a zero row
     * (exactly rank 1). */
    {
        const ogk_real_t dep_rows[6] = {1, 2, 3, 2, 4, 6};
        const ogk_real_t zero_row[6] = {1, 2, 3, 0, 0, 0};
        ogk_real_t x3[3] = {-7.0, -7.0, -7.0};
        st = ogk_minnorm(&ws, dep_rows, 2, 3, b, x3);
        assert_true(st == OGK_E_SINGULAR || st == OGK_E_ILL_CONDITIONED);
        OGK_ASSERT_STATUS(ogk_minnorm(&ws, zero_row, 2, 3, b, x3), OGK_E_SINGULAR);
        assert_int_equal(ws.long_dim, 0);
        OGK_ASSERT_NEAR(x3[2], -7.0, 0.0); /* untouched */
    }
}

/* ------------------------------------------------------------------ minimum norm */

/* req: OGK-CORE-012 */
static void test_minnorm_hand(void **state)
{
    static ogk_qr_t ws;
    const ogk_real_t A1[2] = {1, 1};
    const ogk_real_t b1[1] = {2};
    /* x1 = 3; x2 + x3 = 4 -> x = [3, 2, 2]. */
    const ogk_real_t A2[6] = {1, 0, 0, 0, 1, 1};
    const ogk_real_t b2[2] = {3, 4};
    ogk_real_t x[3];
    (void)state;

    OGK_ASSERT_STATUS(ogk_minnorm(&ws, A1, 1, 2, b1, x), OGK_OK);
    OGK_ASSERT_NEAR(x[0], 1.0, OGK_TEST_TOL(1e-15, 4.5 * FLT_EPSILON));
    OGK_ASSERT_NEAR(x[1], 1.0, OGK_TEST_TOL(1e-15, 4.5 * FLT_EPSILON));
    OGK_ASSERT_STATUS(ogk_minnorm(&ws, A2, 2, 3, b2, x), OGK_OK);
    OGK_ASSERT_NEAR(x[0], 3.0, OGK_TEST_TOL(1e-15, 4.5 * FLT_EPSILON));
    OGK_ASSERT_NEAR(x[1], 2.0, OGK_TEST_TOL(1e-15, 4.5 * FLT_EPSILON));
    OGK_ASSERT_NEAR(x[2], 2.0, OGK_TEST_TOL(1e-15, 4.5 * FLT_EPSILON));
    assert_int_equal(ws.long_dim, 3);
    assert_int_equal(ws.short_dim, 2);
}

/* req: OGK-CORE-012 */
static void test_minnorm_random(void **state)
{
    static ogk_qr_t ws;
    static ogk_lu_t lu;
    static ogk_real_t A[OGK_LA_MAX_N * OGK_LA_MAX_LONG];
    static ogk_real_t x[OGK_LA_MAX_LONG];
    static ogk_real_t AAt[OGK_LA_MAX_N * OGK_LA_MAX_N];
    static const size_t shapes[][2] = {{1, 1}, {1, 5}, {3, 3}, {3, 8}, {7, 40}, {16, 128}};
    ogk_real_t b[OGK_LA_MAX_N];
    ogk_real_t Ax[OGK_LA_MAX_N];
    ogk_real_t w[OGK_LA_MAX_N];
    uint64_t seed = 4242u;
    size_t s;
    (void)state;

    for (s = 0; s < sizeof shapes / sizeof shapes[0]; ++s) {
        const size_t m = shapes[s][0];
        const size_t n = shapes[s][1];
        size_t i;
        size_t j;
        size_t p;
        double xnorm2 = 0.0;
        fill_random(A, m * n, &seed);
        fill_random(b, m, &seed);
        OGK_ASSERT_STATUS(ogk_minnorm(&ws, A, m, n, b, x), OGK_OK);
        /* Feasible: A x = b. */
        assert_true(residual_inf(A, m, n, x, b) <= OGK_TEST_TOL(1e-13, 450.0 * FLT_EPSILON));
        /* x in range(A^T), i.e. orthogonal to null(A): with w solving
         * (A A^T) w = A x = b (Gram matrix formed here, solved by LU),
         * x - A^T w must vanish. */
        for (i = 0; i < m; ++i) {
            for (j = 0; j < m; ++j) {
                double g = 0.0;
                for (p = 0; p < n; ++p) {
                    g += A[i * n + p] * A[j * n + p];
                }
                AAt[i * m + j] = g;
            }
            Ax[i] = 0.0;
            for (p = 0; p < n; ++p) {
                Ax[i] += A[i * n + p] * x[p];
            }
        }
        OGK_ASSERT_STATUS(ogk_lu_factor(&lu, AAt, m), OGK_OK);
        OGK_ASSERT_STATUS(ogk_lu_solve(&lu, Ax, w), OGK_OK);
        for (p = 0; p < n; ++p) {
            double atw = 0.0;
            for (i = 0; i < m; ++i) {
                atw += A[i * n + p] * w[i];
            }
            OGK_ASSERT_NEAR(x[p], atw, OGK_TEST_TOL(1e-12, 4500.0 * FLT_EPSILON));
            xnorm2 += x[p] * x[p];
        }
        /* Minimality: adding a null-space direction increases |x|. For n > m,
         * d = e_0 - A^T (A A^T)^-1 A e_0 lies in null(A); |x + d|^2 =
         * |x|^2 + |d|^2 because x is orthogonal to d. */
        if (n > m) {
            ogk_real_t col0[OGK_LA_MAX_N];
            double d2 = 0.0;
            double xd2 = 0.0;
            for (i = 0; i < m; ++i) {
                col0[i] = A[i * n];
            }
            OGK_ASSERT_STATUS(ogk_lu_solve(&lu, col0, w), OGK_OK);
            for (p = 0; p < n; ++p) {
                double d = (p == 0) ? 1.0 : 0.0;
                for (i = 0; i < m; ++i) {
                    d -= A[i * n + p] * w[i];
                }
                d2 += d * d;
                xd2 += (x[p] + d) * (x[p] + d);
            }
            assert_true(d2 > 1e-6);
            OGK_ASSERT_REL(xd2, xnorm2 + d2, OGK_TEST_TOL(1e-12, 4500.0 * FLT_EPSILON), 1.0);
        }
    }
}

/* Square case: the minimum-norm solution is the unique solution. */
/* req: OGK-CORE-012 */
static void test_minnorm_square_matches_lu(void **state)
{
    static ogk_qr_t ws;
    static ogk_lu_t lu;
    static ogk_real_t A[OGK_LA_MAX_N * OGK_LA_MAX_N];
    ogk_real_t b[OGK_LA_MAX_N];
    ogk_real_t x_qr[OGK_LA_MAX_N];
    ogk_real_t x_lu[OGK_LA_MAX_N];
    uint64_t seed = 5u;
    size_t i;
    (void)state;

    fill_dominant(A, 10, &seed);
    fill_random(b, 10, &seed);
    OGK_ASSERT_STATUS(ogk_minnorm(&ws, A, 10, 10, b, x_qr), OGK_OK);
    OGK_ASSERT_STATUS(ogk_lu_factor(&lu, A, 10), OGK_OK);
    OGK_ASSERT_STATUS(ogk_lu_solve(&lu, b, x_lu), OGK_OK);
    for (i = 0; i < 10; ++i) {
        OGK_ASSERT_NEAR(x_qr[i], x_lu[i], OGK_TEST_TOL(1e-14, 45.0 * FLT_EPSILON));
    }
    OGK_ASSERT_STATUS(ogk_lstsq(&ws, A, 10, 10, b, x_qr), OGK_OK);
    for (i = 0; i < 10; ++i) {
        OGK_ASSERT_NEAR(x_qr[i], x_lu[i], OGK_TEST_TOL(1e-14, 45.0 * FLT_EPSILON));
    }
}

/* req: OGK-CORE-012 OGK-CORE-021 */
static void test_qr_errors(void **state)
{
    static ogk_qr_t ws;
    ogk_real_t A[6] = {1, 0, 0, 1, 1, 1};
    ogk_real_t b[3] = {1, 2, 3};
    ogk_real_t x[3];
    (void)state;

    OGK_ASSERT_STATUS(ogk_lstsq(NULL, A, 3, 2, b, x), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_lstsq(&ws, NULL, 3, 2, b, x), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_lstsq(&ws, A, 3, 2, NULL, x), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_lstsq(&ws, A, 3, 2, b, NULL), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_minnorm(NULL, A, 2, 3, b, x), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_minnorm(&ws, NULL, 2, 3, b, x), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_minnorm(&ws, A, 2, 3, NULL, x), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_minnorm(&ws, A, 2, 3, b, NULL), OGK_E_NULL);

    /* m < n for lstsq, m > n for minnorm, zero and over-limit sizes. */
    OGK_ASSERT_STATUS(ogk_lstsq(&ws, A, 2, 3, b, x), OGK_E_DIM);
    OGK_ASSERT_STATUS(ogk_lstsq(&ws, A, 3, 0, b, x), OGK_E_DIM);
    OGK_ASSERT_STATUS(ogk_lstsq(&ws, A, OGK_LA_MAX_LONG + 1u, 2, b, x), OGK_E_DIM);
    OGK_ASSERT_STATUS(ogk_lstsq(&ws, A, OGK_LA_MAX_LONG, OGK_LA_MAX_N + 1u, b, x), OGK_E_DIM);
    OGK_ASSERT_STATUS(ogk_minnorm(&ws, A, 3, 2, b, x), OGK_E_DIM);
    OGK_ASSERT_STATUS(ogk_minnorm(&ws, A, 0, 3, b, x), OGK_E_DIM);
    OGK_ASSERT_STATUS(ogk_minnorm(&ws, A, 2, OGK_LA_MAX_LONG + 1u, b, x), OGK_E_DIM);
    OGK_ASSERT_STATUS(ogk_minnorm(&ws, A, OGK_LA_MAX_N + 1u, OGK_LA_MAX_LONG, b, x), OGK_E_DIM);

    /* Aliasing: x over A or b, inputs inside the workspace. */
    OGK_ASSERT_STATUS(ogk_lstsq(&ws, A, 3, 2, b, b), OGK_E_RANGE);
    OGK_ASSERT_STATUS(ogk_lstsq(&ws, A, 3, 2, b, &A[4]), OGK_E_RANGE);
    OGK_ASSERT_STATUS(ogk_lstsq(&ws, ws.qr, 3, 2, b, x), OGK_E_RANGE);
    OGK_ASSERT_STATUS(ogk_minnorm(&ws, A, 2, 3, b, &b[1]), OGK_E_RANGE);
    OGK_ASSERT_STATUS(ogk_minnorm(&ws, A, 2, 3, ws.tau, x), OGK_E_RANGE);

    b[2] = NAN;
    OGK_ASSERT_STATUS(ogk_lstsq(&ws, A, 3, 2, b, x), OGK_E_NONFINITE);
    b[2] = 3.0;
    A[1] = INFINITY;
    OGK_ASSERT_STATUS(ogk_minnorm(&ws, A, 2, 3, b, x), OGK_E_NONFINITE);
    assert_int_equal(ws.long_dim, 0);
    assert_int_equal(ws.short_dim, 0);
}

/* The absolute floor OGK_LA_PIVOT_MIN (ogk/linalg.h): a matrix whose pivots
 * are at or below 1e-300 is singular (LU), not positive definite (Cholesky)
 * or rank deficient (QR), though its relative tests alone accepted it (each
 * of these calls answered OGK_OK before the floor); just above the floor the
 * factorizations still solve exactly. */
/* req: OGK-CORE-011 OGK-CORE-012 */
static void test_absolute_pivot_floor(void **state)
{
    static ogk_lu_t lu;
    static ogk_chol_t ch;
    static ogk_qr_t qr;
    static const ogk_real_t below[4] = {R_BELOW_FLOOR, 0, 0, R_BELOW_FLOOR};
    static const ogk_real_t above[4] = {R_ABOVE_FLOOR, 0, 0, R_ABOVE_FLOOR};
    static const ogk_real_t tall[6] = {R_BELOW_FLOOR, 0, R_BELOW_FLOOR, R_BELOW_FLOOR, 0, R_BELOW_FLOOR};
    static const ogk_real_t wide[6] = {R_BELOW_FLOOR, R_BELOW_FLOOR, 0, 0, R_BELOW_FLOOR, R_BELOW_FLOOR};
    const ogk_real_t b[3] = {R_ABOVE_FLOOR, R_ABOVE_FLOOR_2, 0};
    ogk_real_t x[3];
    (void)state;

    OGK_ASSERT_STATUS(ogk_lu_factor(&lu, below, 2), OGK_E_SINGULAR);
    assert_int_equal(lu.n, 0);
    OGK_ASSERT_STATUS(ogk_chol_factor(&ch, below, 2), OGK_E_NOT_POSDEF);
    assert_int_equal(ch.n, 0);
    OGK_ASSERT_STATUS(ogk_lstsq(&qr, tall, 3, 2, b, x), OGK_E_SINGULAR);
    OGK_ASSERT_STATUS(ogk_minnorm(&qr, wide, 2, 3, b, x), OGK_E_SINGULAR);

    OGK_ASSERT_STATUS(ogk_lu_factor(&lu, above, 2), OGK_OK);
    OGK_ASSERT_STATUS(ogk_lu_solve(&lu, b, x), OGK_OK);
    OGK_ASSERT_REL(x[0], 1.0, OGK_TEST_TOL(1e-15, 4.5 * FLT_EPSILON), 0.0);
    OGK_ASSERT_REL(x[1], 2.0, OGK_TEST_TOL(1e-15, 4.5 * FLT_EPSILON), 0.0);
    OGK_ASSERT_STATUS(ogk_chol_factor(&ch, above, 2), OGK_OK);
    OGK_ASSERT_STATUS(ogk_chol_solve(&ch, b, x), OGK_OK);
    OGK_ASSERT_REL(x[0], 1.0, OGK_TEST_TOL(1e-15, 4.5 * FLT_EPSILON), 0.0);
    OGK_ASSERT_REL(x[1], 2.0, OGK_TEST_TOL(1e-15, 4.5 * FLT_EPSILON), 0.0);
}

/* lstsq and minnorm are scale-invariant down to tiny matrices: A s x = b s has
 * the solution of A x = b for s = 1, 2^-300 and 2^-660 (exact scalings; the
 * norms then take both branches of la_norm2, scale above and below 2^-400). Solutions by hand: the consistent system
 * [[1,0],[1,1],[0,1]] x = (2, 1, -1) has x = (2, -1); the minimum-norm
 * solution of [[1,1,0],[0,1,1]] x = (1, 1) is (1, 2, 1) / 3. A column that is
 * already triangular (H = I) solves as well. */
/* req: OGK-CORE-012 */
static void test_qr_tiny_scales(void **state)
{
    static ogk_qr_t qr;
    static const ogk_real_t tall[6] = {1, 0, 1, 1, 0, 1};
    static const double tall_b[3] = {2, 1, -1};
    static const ogk_real_t wide[6] = {1, 1, 0, 0, 1, 1};
    static const double wide_b[2] = {1, 1};
    static const ogk_real_t upper[6] = {2, 1, 0, 1, 0, 0};
    static const ogk_real_t upper_b[3] = {3, 1, 5};
    const double scales[3] = {1.0, R_SCALE_MID, R_SCALE_LOW};
    ogk_real_t a[6];
    ogk_real_t b[3];
    ogk_real_t x[3];
    size_t k;
    size_t i;
    (void)state;

    for (k = 0u; k < 3u; ++k) {
        for (i = 0u; i < 6u; ++i) {
            a[i] = tall[i] * scales[k];
        }
        for (i = 0u; i < 3u; ++i) {
            b[i] = tall_b[i] * scales[k];
        }
        OGK_ASSERT_STATUS(ogk_lstsq(&qr, a, 3, 2, b, x), OGK_OK);
        OGK_ASSERT_REL(x[0], 2.0, OGK_TEST_TOL(1e-14, 45.0 * FLT_EPSILON), 0.0);
        OGK_ASSERT_REL(x[1], -1.0, OGK_TEST_TOL(1e-14, 45.0 * FLT_EPSILON), 0.0);
        for (i = 0u; i < 6u; ++i) {
            a[i] = wide[i] * scales[k];
        }
        for (i = 0u; i < 2u; ++i) {
            b[i] = wide_b[i] * scales[k];
        }
        OGK_ASSERT_STATUS(ogk_minnorm(&qr, a, 2, 3, b, x), OGK_OK);
        OGK_ASSERT_REL(x[0], 1.0 / 3.0, OGK_TEST_TOL(1e-14, 45.0 * FLT_EPSILON), 0.0);
        OGK_ASSERT_REL(x[1], 2.0 / 3.0, OGK_TEST_TOL(1e-14, 45.0 * FLT_EPSILON), 0.0);
        OGK_ASSERT_REL(x[2], 1.0 / 3.0, OGK_TEST_TOL(1e-14, 45.0 * FLT_EPSILON), 0.0);
    }
    /* [[2,1],[0,1],[0,0]] x = (3, 1, 5): x = (1, 1), the third row a residual */
    OGK_ASSERT_STATUS(ogk_lstsq(&qr, upper, 3, 2, upper_b, x), OGK_OK);
    OGK_ASSERT_REL(x[0], 1.0, OGK_TEST_TOL(1e-15, 4.5 * FLT_EPSILON), 0.0);
    OGK_ASSERT_REL(x[1], 1.0, OGK_TEST_TOL(1e-15, 4.5 * FLT_EPSILON), 0.0);
}

/* Inputs are bounded by OGK_LA_VALUE_MAX (1e150, ogk/linalg.h): a larger
 * finite entry of A or b gives OGK_E_RANGE, a NaN or Inf anywhere (even after
 * a large entry) OGK_E_NONFINITE. Before the bound, 0.5 I with b = 1.5e308
 * solved to x = 3e308 = inf with OGK_OK (the EVA finding of docs/evidence/eva.md). */
/* req: OGK-CORE-025 */
static void test_input_bound(void **state)
{
    static ogk_lu_t lu;
    static ogk_chol_t ch;
    static ogk_qr_t qr;
    static const ogk_real_t half[4] = {0.5, 0, 0, 0.5};
    static const ogk_real_t big[4] = {R_BEYOND, 0, 0, 1};
    static const ogk_real_t big_nan[4] = {R_BEYOND, NAN, 0, 1};
    static const ogk_real_t tall[6] = {1, 0, 0, 1, 0, 0};
    static const ogk_real_t tall_big[6] = {1, 0, 0, R_BEYOND_2, 0, 0};
    static const ogk_real_t tall_nan[6] = {1, 0, 0, NAN, 0, 0};
    const ogk_real_t b_huge[3] = {R_HUGE, 1.0, 0.0};
    const ogk_real_t b_ok[3] = {1.0, 2.0, 0.0};
    ogk_real_t x[3] = {7.0, 7.0, 7.0};
    (void)state;

    OGK_ASSERT_STATUS(ogk_lu_factor(&lu, half, 2), OGK_OK);
    OGK_ASSERT_STATUS(ogk_lu_solve(&lu, b_huge, x), OGK_E_RANGE);
    OGK_ASSERT_NEAR(x[0], 7.0, 0.0);
    OGK_ASSERT_STATUS(ogk_chol_factor(&ch, half, 2), OGK_OK);
    OGK_ASSERT_STATUS(ogk_chol_solve(&ch, b_huge, x), OGK_E_RANGE);
    OGK_ASSERT_NEAR(x[0], 7.0, 0.0);
    OGK_ASSERT_STATUS(ogk_lu_factor(&lu, big, 2), OGK_E_RANGE);
    assert_int_equal(lu.n, 0);
    OGK_ASSERT_STATUS(ogk_chol_factor(&ch, big, 2), OGK_E_RANGE);
    assert_int_equal(ch.n, 0);
    OGK_ASSERT_STATUS(ogk_lu_factor(&lu, big_nan, 2), OGK_E_NONFINITE);
    /* lstsq / minnorm: A or b out of bound; NaN in either wins */
    OGK_ASSERT_STATUS(ogk_lstsq(&qr, tall, 3, 2, b_huge, x), OGK_E_RANGE);
    OGK_ASSERT_STATUS(ogk_lstsq(&qr, tall_big, 3, 2, b_ok, x), OGK_E_RANGE);
    OGK_ASSERT_STATUS(ogk_lstsq(&qr, tall_nan, 3, 2, b_huge, x), OGK_E_NONFINITE);
    OGK_ASSERT_STATUS(ogk_minnorm(&qr, tall, 2, 3, b_huge, x), OGK_E_RANGE);
    OGK_ASSERT_NEAR(x[0], 7.0, 0.0);
    OGK_ASSERT_STATUS(ogk_lstsq(&qr, tall, 3, 2, b_ok, x), OGK_OK);
    OGK_ASSERT_NEAR(x[0], 1.0, OGK_TEST_TOL(1e-15, 4.5 * FLT_EPSILON));
    OGK_ASSERT_NEAR(x[1], 2.0, OGK_TEST_TOL(1e-15, 4.5 * FLT_EPSILON));
}

/* Every quotient of the substitutions is bounded by OGK_LA_SOLVE_MAX (1e150,
 * ogk/linalg.h): a solution beyond it gives OGK_E_OVERFLOW and x unwritten.
 * Truth by hand: A = s I has x = b / s. With s = 1e-250 (pivots above the
 * floor 1e-300, rcond 1) and b_0 = 1e100, x_0 = 1e350: each of these calls
 * returned OGK_OK with x_0 = inf before the bound. x = 1e140 is still solved. */
/* req: OGK-CORE-025 */
static void test_solves_overflow(void **state)
{
    static ogk_lu_t lu;
    static ogk_chol_t ch;
    static ogk_qr_t qr;
    static const ogk_real_t tiny2[4] = {R_PIVOT, 0, 0, R_PIVOT};
    static const ogk_real_t tall[6] = {R_PIVOT, 0, 0, R_PIVOT, 0, 0};
    static const ogk_real_t wide[6] = {R_PIVOT, 0, 0, 0, R_PIVOT, 0};
    const ogk_real_t b_over[3] = {R_B_OVER, 1.0, 0.0};
    const ogk_real_t b_in[3] = {R_B_IN, -R_B_IN, 0.0};
    ogk_real_t x[3] = {7.0, 7.0, 7.0};
    (void)state;

    OGK_ASSERT_STATUS(ogk_lu_factor(&lu, tiny2, 2), OGK_OK);
    OGK_ASSERT_REL(lu.rcond, 1.0, OGK_TEST_TOL(1e-15, 4.5 * FLT_EPSILON), 0.0);
    OGK_ASSERT_STATUS(ogk_lu_solve(&lu, b_over, x), OGK_E_OVERFLOW);
    OGK_ASSERT_NEAR(x[0], 7.0, 0.0);
    OGK_ASSERT_NEAR(x[1], 7.0, 0.0);
    OGK_ASSERT_STATUS(ogk_lu_solve(&lu, b_in, x), OGK_OK);
    OGK_ASSERT_REL(x[0], R_X_IN, OGK_TEST_TOL(1e-15, 4.5 * FLT_EPSILON), 0.0);
    OGK_ASSERT_REL(x[1], -R_X_IN, OGK_TEST_TOL(1e-15, 4.5 * FLT_EPSILON), 0.0);

    x[0] = 7.0;
    x[1] = 7.0;
    OGK_ASSERT_STATUS(ogk_chol_factor(&ch, tiny2, 2), OGK_OK);
    OGK_ASSERT_STATUS(ogk_chol_solve(&ch, b_over, x), OGK_E_OVERFLOW);
    OGK_ASSERT_NEAR(x[0], 7.0, 0.0);
    OGK_ASSERT_NEAR(x[1], 7.0, 0.0);
    OGK_ASSERT_STATUS(ogk_chol_solve(&ch, b_in, x), OGK_OK);
    OGK_ASSERT_REL(x[0], R_X_IN, OGK_TEST_TOL(1e-15, 4.5 * FLT_EPSILON), 0.0);
    OGK_ASSERT_REL(x[1], -R_X_IN, OGK_TEST_TOL(1e-15, 4.5 * FLT_EPSILON), 0.0);

    x[0] = 7.0;
    x[1] = 7.0;
    OGK_ASSERT_STATUS(ogk_lstsq(&qr, tall, 3, 2, b_over, x), OGK_E_OVERFLOW);
    OGK_ASSERT_NEAR(x[0], 7.0, 0.0);
    OGK_ASSERT_NEAR(x[1], 7.0, 0.0);
    OGK_ASSERT_STATUS(ogk_lstsq(&qr, tall, 3, 2, b_in, x), OGK_OK);
    OGK_ASSERT_REL(x[0], R_X_IN, OGK_TEST_TOL(1e-15, 4.5 * FLT_EPSILON), 0.0);
    OGK_ASSERT_REL(x[1], -R_X_IN, OGK_TEST_TOL(1e-15, 4.5 * FLT_EPSILON), 0.0);

    x[0] = 7.0;
    x[1] = 7.0;
    x[2] = 7.0;
    OGK_ASSERT_STATUS(ogk_minnorm(&qr, wide, 2, 3, b_over, x), OGK_E_OVERFLOW);
    OGK_ASSERT_NEAR(x[0], 7.0, 0.0);
    OGK_ASSERT_NEAR(x[2], 7.0, 0.0);
    OGK_ASSERT_STATUS(ogk_minnorm(&qr, wide, 2, 3, b_in, x), OGK_OK);
    OGK_ASSERT_REL(x[0], R_X_IN, OGK_TEST_TOL(1e-15, 4.5 * FLT_EPSILON), 0.0);
    OGK_ASSERT_REL(x[1], -R_X_IN, OGK_TEST_TOL(1e-15, 4.5 * FLT_EPSILON), 0.0);
    OGK_ASSERT_NEAR(x[2], 0.0, 0.0);
}

/* The inverse and rcond of a matrix whose inverse overflows: A = s U with U
 * unit upper bidiagonal (-c above the diagonal), s = 2e-300, c = 1e6.
 * By hand, A^-1 = (1/s) [[1, c, c^2], [0, 1, c], [0, 0, 1]], so |A|_1 =
 * s (1 + c), |A^-1|_1 = (1 + c + c^2) / s and rcond = 1 / ((1 + c)(1 + c +
 * c^2)) = 1e-18; the corner c^2 / s = 5e311 is beyond DBL_MAX. Before the
 * bound, ogk_lu_inverse returned OGK_OK with that entry infinite, and rcond
 * was 0 (its column sum overflowed); now rcond is computed scale-free (on
 * A^-1 |A|_1 e_j) and the inverse gives OGK_E_OVERFLOW. */
/* req: OGK-CORE-025 OGK-CORE-011 */
static void test_inverse_overflow(void **state)
{
    static ogk_lu_t lu;
    /* float: s = 2e-25, c = 3e4: rcond = 3.7e-14 (below OGK_LA_RCOND_MIN, above
     * n / OGK_LA_SOLVE_MAX = 3e-15, so computed), the pivots above eps |A|_1,
     * the corner c^2 / s = 4.5e33 beyond OGK_LA_SOLVE_MAX (1e15) */
    const double s = R_INV_S;
    const double c = R_INV_C;
    ogk_real_t A[9] = {0};
    ogk_real_t Ainv[9];
    (void)state;

    A[0] = s;
    A[1] = -c * s;
    A[4] = s;
    A[5] = -c * s;
    A[8] = s;
    OGK_ASSERT_STATUS(ogk_lu_factor(&lu, A, 3), OGK_E_ILL_CONDITIONED);
    OGK_ASSERT_REL(lu.rcond, 1.0 / ((1.0 + c) * (1.0 + c + (c * c))), OGK_TEST_TOL(1e-12, 4500.0 * FLT_EPSILON), 0.0);
    OGK_ASSERT_STATUS(ogk_lu_inverse(&lu, Ainv), OGK_E_OVERFLOW);
}

/* rcond is reported 0 once |A|_1 |A^-1|_1 passes OGK_LA_SOLVE_MAX: the 16 x 16
 * unit upper triangular matrix with -1e13 above the diagonal has pivots 1
 * (no row exchange; each above eps |A|_1 = 0.033). By hand, A x = e_k has
 * x_k = 1, x_{k-1} = c and x_i = (1 + c) x_{i+1} above: x_0 = c (1 + c)^(k-1),
 * so A^-1 e_15 has the entry 1e195 (the solve gives OGK_E_OVERFLOW too). */
/* req: OGK-CORE-025 OGK-CORE-011 */
static void test_rcond_beyond_bound(void **state)
{
    static ogk_lu_t lu;
    static ogk_real_t A[16 * 16];
    ogk_real_t b[16] = {0};
    ogk_real_t x[16];
    size_t i;
    size_t j;
    (void)state;

    for (i = 0; i < 16u; ++i) {
        for (j = 0; j < 16u; ++j) {
            A[(i * 16u) + j] = (i == j) ? 1.0 : ((j > i) ? -R_UPPER_C : 0.0);
        }
    }
    OGK_ASSERT_STATUS(ogk_lu_factor(&lu, A, 16), OGK_E_ILL_CONDITIONED);
    OGK_ASSERT_NEAR(lu.rcond, 0.0, 0.0);
    b[15] = 1.0;
    OGK_ASSERT_STATUS(ogk_lu_solve(&lu, b, x), OGK_E_OVERFLOW);
    /* k = 3: x_0 = c (1 + c)^2 = 1e39, within the bound (float: c = 1e4, whose
     * |A|_1 = 1.5e5 keeps the unit pivots above eps |A|_1 = 0.018; x_0 = 1e12
     * within 1e15, and k = 15 gives 1e60) */
    for (i = 0; i < 16u; ++i) {
        b[i] = 0.0;
    }
    b[3] = 1.0;
    OGK_ASSERT_STATUS(ogk_lu_solve(&lu, b, x), OGK_OK);
    OGK_ASSERT_REL(x[0], R_UPPER_C * (1.0 + R_UPPER_C) * (1.0 + R_UPPER_C), OGK_TEST_TOL(1e-14, 45.0 * FLT_EPSILON), 0.0);
    OGK_ASSERT_REL(x[2], R_UPPER_C, OGK_TEST_TOL(1e-15, 4.5 * FLT_EPSILON), 0.0);
    /* The same matrix through ogk_lstsq (m = n = 16): upper triangular, so R = A
     * (every reflector H = I), |r_kk| = 1 passes the rank test, and cond_1(R)
     * past the bound makes it ill-conditioned, x still solved (k = 3) ... */
    {
        static ogk_qr_t qr;
        OGK_ASSERT_STATUS(ogk_lstsq(&qr, A, 16, 16, b, x), OGK_E_ILL_CONDITIONED);
        OGK_ASSERT_REL(x[0], R_UPPER_C * (1.0 + R_UPPER_C) * (1.0 + R_UPPER_C), OGK_TEST_TOL(1e-14, 45.0 * FLT_EPSILON), 0.0);
        /* ... and k = 15 beyond OGK_LA_SOLVE_MAX */
        b[3] = 0.0;
        b[15] = 1.0;
        OGK_ASSERT_STATUS(ogk_lstsq(&qr, A, 16, 16, b, x), OGK_E_OVERFLOW);
    }
}

/* Each band of the checked division (linalg.c, la_div) at its edge, through
 * the public solves; truths by hand. A = [[d, 0], [d, d]] factors as L =
 * [[1, 0], [1, 1]], U = d I (no exchange), so with b = (p, -p) the forward
 * pass gives y = (p, -2p) and x = (p / d, -2p / d): a numerator of 2p, of
 * either sign, in the backward pass. */
/* req: OGK-CORE-025 */
static void test_division_bands(void **state)
{
    static ogk_lu_t lu;
    static ogk_chol_t ch;
    ogk_real_t A[4];
    ogk_real_t b[2];
    ogk_real_t x[2];
    const double d_values[2] = {1.0, 0.5};
    size_t k;
    (void)state;

    for (k = 0u; k < 2u; ++k) {
        const double d = d_values[k];
        A[0] = d;
        A[1] = 0.0;
        A[2] = d;
        A[3] = d;
        OGK_ASSERT_STATUS(ogk_lu_factor(&lu, A, 2), OGK_OK);
        /* x = (1e150 / d, -2e150 / d) is beyond the bound, with either sign first */
        b[0] = R_BAND;
        b[1] = -R_BAND;
        OGK_ASSERT_STATUS(ogk_lu_solve(&lu, b, x), OGK_E_OVERFLOW);
        b[0] = -R_BAND;
        b[1] = R_BAND;
        OGK_ASSERT_STATUS(ogk_lu_solve(&lu, b, x), OGK_E_OVERFLOW);
        /* x = (p / d, -2p / d) within it */
        b[0] = R_BAND_IN;
        b[1] = -R_BAND_IN;
        OGK_ASSERT_STATUS(ogk_lu_solve(&lu, b, x), OGK_OK);
        OGK_ASSERT_REL(x[0], R_BAND_IN / d, OGK_TEST_TOL(1e-15, 4.5 * FLT_EPSILON), 0.0);
        OGK_ASSERT_REL(x[1], -2.0 * R_BAND_IN / d, OGK_TEST_TOL(1e-15, 4.5 * FLT_EPSILON), 0.0);
    }
    /* 0.5 I: a numerator within the bound whose quotient is not (2e150) */
    A[0] = 0.5;
    A[1] = 0.0;
    A[2] = 0.0;
    A[3] = 0.5;
    OGK_ASSERT_STATUS(ogk_lu_factor(&lu, A, 2), OGK_OK);
    b[0] = R_BAND;
    b[1] = 0.0;
    OGK_ASSERT_STATUS(ogk_lu_solve(&lu, b, x), OGK_E_OVERFLOW);
    b[0] = -R_BAND;
    OGK_ASSERT_STATUS(ogk_lu_solve(&lu, b, x), OGK_E_OVERFLOW);
    /* below 2^-512: d = 1e-200, numerators above and below +-1e150 2^-512
     * (7.5e-5), and one within it whose quotient is not (1e-5 / 1e-200).
     * Float: below 2^-64, d = 1e-25, the limit 1e15 2^-64 = 5.4e-5 */
    A[0] = R_TINY_D;
    A[3] = R_TINY_D;
    OGK_ASSERT_STATUS(ogk_lu_factor(&lu, A, 2), OGK_OK);
    b[0] = 1e-4;
    OGK_ASSERT_STATUS(ogk_lu_solve(&lu, b, x), OGK_E_OVERFLOW);
    b[0] = -1e-4;
    OGK_ASSERT_STATUS(ogk_lu_solve(&lu, b, x), OGK_E_OVERFLOW);
    b[0] = 1e-5;
    OGK_ASSERT_STATUS(ogk_lu_solve(&lu, b, x), OGK_E_OVERFLOW);
    b[0] = -R_B_TINY_IN;
    b[1] = R_B_TINY_IN_3;
    OGK_ASSERT_STATUS(ogk_lu_solve(&lu, b, x), OGK_OK);
    OGK_ASSERT_REL(x[0], -R_B_TINY_IN / R_TINY_D, OGK_TEST_TOL(1e-15, 4.5 * FLT_EPSILON), 0.0);
    OGK_ASSERT_REL(x[1], R_B_TINY_IN_3 / R_TINY_D, OGK_TEST_TOL(1e-15, 4.5 * FLT_EPSILON), 0.0);
    /* a factorization overwritten with a zero pivot (the struct is the
     * caller's): the division is refused, not made (it gave inf before) */
    OGK_ASSERT_STATUS(ogk_chol_factor(&ch, A, 2), OGK_OK);
    ch.l[3] = 0.0;
    OGK_ASSERT_STATUS(ogk_chol_solve(&ch, b, x), OGK_E_OVERFLOW);
    lu.lu[0] = 0.0;
    OGK_ASSERT_STATUS(ogk_lu_solve(&lu, b, x), OGK_E_OVERFLOW);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_products_hand),
        cmocka_unit_test(test_products_max_size),
        cmocka_unit_test(test_products_errors),
        cmocka_unit_test(test_lu_random_solve_inverse),
        cmocka_unit_test(test_lu_rcond_closed_form),
        cmocka_unit_test(test_lu_hilbert),
        cmocka_unit_test(test_lu_singular),
        cmocka_unit_test(test_lu_errors),
        cmocka_unit_test(test_chol_closed_form),
        cmocka_unit_test(test_chol_random_spd),
        cmocka_unit_test(test_chol_rejects),
        cmocka_unit_test(test_lstsq_line_fit),
        cmocka_unit_test(test_lstsq_random),
        cmocka_unit_test(test_lstsq_rank_deficient),
        cmocka_unit_test(test_minnorm_hand),
        cmocka_unit_test(test_minnorm_random),
        cmocka_unit_test(test_minnorm_square_matches_lu),
        cmocka_unit_test(test_qr_errors),
        cmocka_unit_test(test_absolute_pivot_floor),
        cmocka_unit_test(test_qr_tiny_scales),
        cmocka_unit_test(test_input_bound),
        cmocka_unit_test(test_solves_overflow),
        cmocka_unit_test(test_inverse_overflow),
        cmocka_unit_test(test_rcond_beyond_bound),
        cmocka_unit_test(test_division_bands),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
