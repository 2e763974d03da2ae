/* linalg.c -- fixed-size dense linear algebra on row-major double arrays.
 *
 * Algorithms (Golub & Van Loan, Matrix Computations, 4th ed., sections cited):
 *   LU      Gaussian elimination with partial pivoting (Sec. 3.4); rcond is
 *           exact: 1 / (|A|_1 |A^-1|_1) with A^-1 built column by column from
 *           the factors (n <= OGK_LA_MAX_N bounds the O(n^3) cost).
 *   Chol    the kernel's one Cholesky (chol.c): right-looking, by rows of
 *           U = L^T (Sec. 4.2, Algorithm 4.2.2), shared with the QP.
 *   QR      Householder reflectors in LAPACK dlarfg form (Sec. 5.1, 5.2):
 *           H = I - tau v v^T, v(0) = 1, R on and above the diagonal, v below it.
 *   lstsq   x = R^-1 (Q^T b)(0:n-1)                      (Sec. 5.3)
 *   minnorm A^T = Q R,  z = R^-T b,  x = Q [z; 0]         (Sec. 5.6)
 * Design note with thresholds, error codes and stack use: docs/design/linalg.md. */
#include "ogk/linalg.h"
#include "../chol_internal.h"

#include <float.h>
#include <math.h>
#include <stdbool.h>
#include <stdint.h>
#include <string.h>

/* Symmetry tolerance of the Cholesky input, relative to max |A_ij| (ogk/linalg.h). */
#define OGK_CHOL_SYM_TOL OGK_R(1.0e-12)

/* ------------------------------------------------------------------ helpers */

/* True when the byte ranges [p, p + p_bytes) and [q, q + q_bytes) overlap.
 * Compared as integers: the objects may be unrelated, so relational operators
 * on the pointers themselves would be undefined. */
static bool la_overlap(const void *p, size_t p_bytes, const void *q, size_t q_bytes)
{
    const uintptr_t p_lo = (uintptr_t)p;
    const uintptr_t q_lo = (uintptr_t)q;
    return (p_lo < (q_lo + (uintptr_t)q_bytes)) && (q_lo < (p_lo + (uintptr_t)p_bytes));
}

/* Bytes of an array of `count` doubles (count <= OGK_LA_MAX_LONG^2, no overflow). */
static size_t la_bytes(size_t count)
{
    return count * sizeof(ogk_real_t);
}

static bool la_dim_ok(size_t dim, size_t dim_max)
{
    return (dim > 0u) && (dim <= dim_max);
}

/* OGK_OK when every v[i] is within OGK_LA_VALUE_MAX (ogk/linalg.h),
 * OGK_E_NONFINITE at a NaN or infinity, else OGK_E_RANGE; one pass, one
 * compare per entry (NaN fails it too) as the finite check it replaces. */
static ogk_status la_all_bounded(const ogk_real_t *v, size_t count)
{
    ogk_status st = OGK_OK;
    size_t i;
    for (i = 0u; (i < count) && (st != OGK_E_NONFINITE); ++i) {
        if (!(OGK_FABS(v[i]) <= OGK_LA_VALUE_MAX)) {
            st = isfinite(v[i]) ? OGK_E_RANGE : OGK_E_NONFINITE;
        }
    }
    return st;
}

/* 2^-512 and 2^512, the square root of double's range: la_div's band for its
 * smallest divisors. The float build takes the square root of float's range,
 * 2^-64 and 2^64 (below, with OGK_LA_SOLVE_MAX = 1e15 and OGK_LA_PIVOT_MIN =
 * 1e-30: the middle band's quotient is at most 1e15 2^64 = 1.8e34, the lowest
 * band's scaled divisor at least 1e-30 2^64, normal). */
#if OGK_REAL_SINGLE
#define OGK_LA_DIV_LOW OGK_R(0x1p-64)
#define OGK_LA_DIV_UP OGK_R(0x1p64)
#else
#define OGK_LA_DIV_LOW OGK_R(0x1p-512)
#define OGK_LA_DIV_UP OGK_R(0x1p512)
#endif

/* *q = num / den when |num / den| <= OGK_LA_SOLVE_MAX (ogk/linalg.h) and
 * |den| > OGK_LA_PIVOT_MIN; false, *q unwritten, otherwise (NaN operands too).
 * The quotient is decided before it is formed, on three bands of |den|
 * whose bounds are constants, so that a non-relational analysis (Frama-C
 * EVA, docs/evidence/eva.md) bounds it from the operands' own ranges:
 *   |den| >= 1:          |num / den| <= |num|, finite;
 *   2^-512 <= |den| < 1: |q| <= MAX needs |num| <= MAX, then |num / den| <= MAX 2^512 (1.3e304);
 *   below 2^-512:        |q| <= MAX needs |num| <= MAX 2^-512; both scaled by 2^512
 *                        (exact: the same real quotient, the same rounding).
 * The sign is restored after dividing the magnitudes (IEEE 754 division is
 * sign-symmetric): *q is num / den bit for bit. One compare and one branch
 * more than a bare division for |den| >= 1. */
static bool la_div(ogk_real_t num, ogk_real_t den, ogk_real_t *q) /* NOLINT(bugprone-easily-swappable-parameters): num / den, the order of the quotient written */
{
    const ogk_real_t ad = OGK_FABS(den);
    ogk_real_t t = OGK_R(0.0);
    bool ok = false;

    if (ad >= OGK_R(1.0)) {
        t = num / ad;
        ok = true;
    } else if (ad >= OGK_LA_DIV_LOW) {
        if ((num <= OGK_LA_SOLVE_MAX) && (num >= -OGK_LA_SOLVE_MAX)) {
            t = num / ad;
            ok = true;
        }
    } else if ((ad > OGK_LA_PIVOT_MIN) && (num <= (OGK_LA_SOLVE_MAX * OGK_LA_DIV_LOW)) &&
               (num >= -(OGK_LA_SOLVE_MAX * OGK_LA_DIV_LOW))) {
        t = (num * OGK_LA_DIV_UP) / (ad * OGK_LA_DIV_UP);
        ok = true;
    } else {
        /* a pivot at or below the floor (an overwritten factorization), a
         * quotient too large, or NaN: not divided */
    }
    if (ok && (t <= OGK_LA_SOLVE_MAX) && (t >= -OGK_LA_SOLVE_MAX)) {
        *q = (den < OGK_R(0.0)) ? -t : t;
    } else {
        ok = false;
    }
    return ok;
}

/* 2^-400 and 2^400: below 2^-400, la_norm2 scales its quotients up. The float
 * build's 2^-50 and 2^50 keep the same two properties in float's range: the
 * smallest subnormal (2^-149) scaled up is normal (2^-99), and |v_i| 2^50 has a
 * finite square for |v_i| < 2^14 (double: 2^-674 and 2^112). */
#if OGK_REAL_SINGLE
#define OGK_LA_SCALE_DOWN OGK_R(0x1p-50)
#define OGK_LA_SCALE_UP OGK_R(0x1p50)
#else
#define OGK_LA_SCALE_DOWN OGK_R(0x1p-400)
#define OGK_LA_SCALE_UP OGK_R(0x1p400)
#endif

/* Euclidean norm of v[0], v[stride], ..., v[(count-1) stride], scaled by the
 * largest magnitude so that squares neither overflow nor underflow. Each
 * quotient t = v_i / scale is in [-1, 1]. For scale >= 2^-400 it is bounded
 * without a relation between v_i and scale by |v_i| 2^400, whose square is
 * finite for |v_i| < 2^112, what a non-relational analysis (Frama-C EVA,
 * docs/evidence/eva.md) can use; below, both are scaled by 2^400 (exact: the same
 * correctly rounded t) and t <= 1 restated, and the sum of squares is
 * restated to be at most count. */
static ogk_real_t la_norm2(const ogk_real_t *v, size_t count, size_t stride) /* NOLINT(bugprone-easily-swappable-parameters): dimension order of the header, crossed with Eigen */
{
    ogk_real_t scale = OGK_R(0.0);
    ogk_real_t norm = OGK_R(0.0);
    size_t i;

    for (i = 0u; i < count; ++i) {
        const ogk_real_t a = OGK_FABS(v[i * stride]);
        if (a > scale) {
            scale = a;
        }
    }
    if (scale > OGK_R(0.0)) {
        ogk_real_t ssq = OGK_R(0.0);
        if (scale >= OGK_LA_SCALE_DOWN) {
            for (i = 0u; i < count; ++i) {
                const ogk_real_t t = v[i * stride] / scale;
                ssq += t * t;
            }
        } else {
            const ogk_real_t scale_up = scale * OGK_LA_SCALE_UP;
            for (i = 0u; i < count; ++i) {
                const ogk_real_t t = OGK_FMIN((OGK_FMIN(OGK_FABS(v[i * stride]), OGK_LA_SCALE_DOWN) *
                                       OGK_LA_SCALE_UP) / scale_up, OGK_R(1.0));
                ssq += t * t;
            }
        }
        /* every t^2 <= 1: the fmin restates ssq <= count */
        norm = scale * OGK_SQRT(OGK_FMIN(ssq, (ogk_real_t)count));
    }
    return norm;
}

/* Common checks of the products: NULL, dimensions, output overlapping an input. */
static ogk_status la_product_check(const ogk_real_t *in1, size_t in1_count,
                                   const ogk_real_t *in2, size_t in2_count,
                                   const ogk_real_t *out, size_t out_count, /* NOLINT(bugprone-easily-swappable-parameters): dimension order of the header, crossed with Eigen */
                                   size_t d1, size_t d2, size_t d3)
{
    ogk_status st;
    if ((in1 == NULL) || (in2 == NULL) || (out == NULL)) {
        st = OGK_E_NULL;
    } else if (!la_dim_ok(d1, OGK_LA_MAX_LONG) || !la_dim_ok(d2, OGK_LA_MAX_LONG) ||
               !la_dim_ok(d3, OGK_LA_MAX_LONG)) {
        st = OGK_E_DIM;
    } else if (la_overlap(out, la_bytes(out_count), in1, la_bytes(in1_count)) ||
               la_overlap(out, la_bytes(out_count), in2, la_bytes(in2_count))) {
        st = OGK_E_RANGE;
    } else {
        st = OGK_OK;
    }
    return st;
}

/* Common checks of the factorizations of an n x n matrix A into a
 * caller-owned struct of fact_bytes bytes at fact: NULL, dimension, A
 * overlapping the struct, non-finite entries. */
static ogk_status la_square_check(const ogk_real_t *A, size_t n, const void *fact,
                                  size_t fact_bytes)
{
    ogk_status st;
    if (A == NULL) {
        st = OGK_E_NULL;
    } else if (!la_dim_ok(n, OGK_LA_MAX_N)) {
        st = OGK_E_DIM;
    } else if (la_overlap(A, la_bytes(n * n), fact, fact_bytes)) {
        st = OGK_E_RANGE;
    } else {
        st = la_all_bounded(A, n * n);
    }
    return st;
}

/* ------------------------------------------------------------------ products */

/* C (r x c, row-major) = sum_p A(i, p) B(p, j), where A(i, p) = A[i a_i + p a_p] and
 * B(p, j) = B[p b_p + j b_j]: one loop nest for
 * A x, A^T x, A B, A^T B and A B^T. */
static void product_strided(const ogk_real_t *A, size_t a_i, size_t a_p, const ogk_real_t *B,
                            size_t b_p, size_t b_j, size_t r, size_t k, size_t c, ogk_real_t *C) /* NOLINT(bugprone-easily-swappable-parameters): dimension order of the header, crossed with Eigen */
{
    size_t i;
    size_t j;
    size_t p;
    for (i = 0u; i < r; ++i) {
        for (j = 0u; j < c; ++j) {
            ogk_real_t sum = OGK_R(0.0);
            for (p = 0u; p < k; ++p) {
                sum += A[(i * a_i) + (p * a_p)] * B[(p * b_p) + (j * b_j)];
            }
            C[(i * c) + j] = sum;
        }
    }
}

ogk_status ogk_mat_vec(const ogk_real_t *A, size_t rows, size_t cols,
                       const ogk_real_t *x, ogk_real_t *y)
{
    const ogk_status st = la_product_check(A, rows * cols, x, cols, y, rows,
                                           rows, cols, 1u);
    if (st == OGK_OK) {
        product_strided(A, cols, 1u, x, 1u, 0u, rows, cols, 1u, y);
    }
    return st;
}

ogk_status ogk_mat_t_vec(const ogk_real_t *A, size_t rows, size_t cols,
                         const ogk_real_t *x, ogk_real_t *y)
{
    const ogk_status st = la_product_check(A, rows * cols, x, rows, y, cols,
                                           rows, cols, 1u);
    if (st == OGK_OK) {
        product_strided(A, 1u, cols, x, 1u, 0u, cols, rows, 1u, y);
    }
    return st;
}

ogk_status ogk_mat_mul(const ogk_real_t *A, size_t r, size_t k,
                       const ogk_real_t *B, size_t c, ogk_real_t *C)
{
    const ogk_status st = la_product_check(A, r * k, B, k * c, C, r * c, r, k, c);
    if (st == OGK_OK) {
        product_strided(A, k, 1u, B, c, 1u, r, k, c, C);
    }
    return st;
}

ogk_status ogk_mat_mul_at_b(const ogk_real_t *A, size_t k, size_t r,
                            const ogk_real_t *B, size_t c, ogk_real_t *C)
{
    const ogk_status st = la_product_check(A, k * r, B, k * c, C, r * c, r, k, c);
    if (st == OGK_OK) {
        product_strided(A, 1u, r, B, c, 1u, r, k, c, C);
    }
    return st;
}

ogk_status ogk_mat_mul_a_bt(const ogk_real_t *A, size_t r, size_t k,
                            const ogk_real_t *B, size_t c, ogk_real_t *C)
{
    const ogk_status st = la_product_check(A, r * k, B, c * k, C, r * c, r, k, c);
    if (st == OGK_OK) {
        product_strided(A, k, 1u, B, 1u, k, r, k, c, C);
    }
    return st;
}

ogk_status ogk_mat_transpose(const ogk_real_t *A, size_t rows, size_t cols,
                             ogk_real_t *At)
{
    /* A is passed twice: la_product_check wants two inputs. */
    const ogk_status st = la_product_check(A, rows * cols, A, rows * cols,
                                           At, rows * cols, rows, cols, 1u);
    if (st == OGK_OK) {
        size_t i;
        size_t j;
        for (i = 0u; i < rows; ++i) {
            for (j = 0u; j < cols; ++j) {
                At[(j * rows) + i] = A[(i * cols) + j];
            }
        }
    }
    return st;
}

/* ------------------------------------------------------------------ LU */

static void lu_invalidate(ogk_lu_t *lu)
{
    lu->n = 0u;
    lu->anorm1 = OGK_R(0.0);
    lu->rcond = OGK_R(0.0);
}

/* Checks that lu holds a factorization that can be used without reading out
 * of bounds (guards against a never-factored or overwritten struct). */
static ogk_status lu_check_held(const ogk_lu_t *lu)
{
    ogk_status st;
    size_t i;
    if (lu->n == 0u) {
        st = OGK_E_NOT_INIT;
    } else if (lu->n > OGK_LA_MAX_N) {
        st = OGK_E_DIM;
    } else {
        st = OGK_OK;
        for (i = 0u; (i < lu->n) && (st == OGK_OK); ++i) {
            if (lu->perm[i] >= lu->n) {
                st = OGK_E_NOT_INIT;
            }
        }
    }
    return st;
}

/* Solves L U y_out = y_in in place, y_in already permuted (= P b); false
 * (y partly overwritten) when a quotient would exceed OGK_LA_SOLVE_MAX (la_div). */
static bool lu_substitute(const ogk_lu_t *lu, ogk_real_t *y)
{
    const size_t n = lu->n;
    const ogk_real_t *f = lu->lu;
    bool ok = true;
    size_t i;
    size_t j;
    size_t ii;

    /* Forward: L unit lower triangular. */
    for (i = 1u; i < n; ++i) {
        ogk_real_t sum = y[i];
        for (j = 0u; j < i; ++j) {
            sum -= f[(i * n) + j] * y[j];
        }
        y[i] = sum;
    }
    /* Backward: U upper triangular, |u_kk| > OGK_LA_PIVOT_MIN (checked at
     * factor time, and again by la_div); every x_j <= OGK_LA_SOLVE_MAX. */
    for (ii = 0u; (ii < n) && ok; ++ii) {
        const size_t row = n - 1u - ii;
        ogk_real_t sum = y[row];
        for (j = row + 1u; j < n; ++j) {
            sum -= f[(row * n) + j] * y[j];
        }
        ok = la_div(sum, f[(row * n) + row], &y[row]);
    }
    return ok;
}

/* Column j of A^-1 times s into col[0..n-1]: solves A z = s e_j, i.e.
 * L U z = P s e_j; false as lu_substitute. */
static bool lu_inverse_column(const ogk_lu_t *lu, size_t j, ogk_real_t s, ogk_real_t *col)
{
    size_t i;
    for (i = 0u; i < lu->n; ++i) {
        col[i] = (lu->perm[i] == j) ? s : OGK_R(0.0);
    }
    return lu_substitute(lu, col);
}

/* Loads A (n x n, checked) into lu: copy, 1-norm (largest absolute column
 * sum), identity permutation. */
static void lu_load(ogk_lu_t *lu, const ogk_real_t *A, size_t n)
{
    size_t i;
    size_t j;
    ogk_real_t anorm1 = OGK_R(0.0);

    for (j = 0u; j < n; ++j) {
        ogk_real_t colsum = OGK_R(0.0);
        for (i = 0u; i < n; ++i) {
            colsum += OGK_FABS(A[(i * n) + j]);
        }
        if (colsum > anorm1) {
            anorm1 = colsum;
        }
    }
    (void)memcpy(lu->lu, A, la_bytes(n * n));
    lu->anorm1 = anorm1;
    for (i = 0u; i < n; ++i) {
        lu->perm[i] = i;
    }
}

/* Gaussian elimination with partial pivoting of the n x n matrix loaded in
 * lu (lu_load). OGK_E_SINGULAR at the first pivot at or below eps |A|_1 or
 * OGK_LA_PIVOT_MIN (ogk/linalg.h).
 *
 * A pivot at or below eps |A|_1 is zero to working precision. Any such
 * pivot implies rcond <= n eps < OGK_LA_RCOND_MIN (the trailing block of
 * (PA)^-1 is the inverse of the Schur complement S, and |S^-1|_1 >=
 * 1 / |S e_1|_1 >= 1 / (n |pivot|)), so SINGULAR never hides a
 * matrix that ILL_CONDITIONED would have accepted; a larger threshold
 * (n eps |A|_1) would already reject the 12 x 12 Hilbert matrix. */
static ogk_status lu_eliminate(ogk_lu_t *lu, size_t n)
{
    const ogk_real_t pivot_tol = OGK_REAL_EPSILON * lu->anorm1;
    ogk_status st = OGK_OK;
    ogk_real_t *f = lu->lu;
    size_t i;
    size_t j;
    size_t k;

    for (k = 0u; (k < n) && (st == OGK_OK); ++k) {
        size_t p = k;
        ogk_real_t pmax = OGK_FABS(f[(k * n) + k]);
        bool negative = f[(k * n) + k] < OGK_R(0.0);
        for (i = k + 1u; i < n; ++i) {
            const ogk_real_t a = OGK_FABS(f[(i * n) + k]);
            if (a > pmax) {
                pmax = a;
                p = i;
                negative = f[(i * n) + k] < OGK_R(0.0);
            }
        }
        if (!(pmax > pivot_tol) || !(pmax > OGK_LA_PIVOT_MIN)) {
            st = OGK_E_SINGULAR;
        } else {
            if (p != k) {
                const size_t tp = lu->perm[k];
                lu->perm[k] = lu->perm[p];
                lu->perm[p] = tp;
                for (j = 0u; j < n; ++j) {
                    const ogk_real_t t = f[(k * n) + j];
                    f[(k * n) + j] = f[(p * n) + j];
                    f[(p * n) + j] = t;
                }
            }
            for (i = k + 1u; i < n; ++i) {
                /* f_ik / f_kk as +-(f_ik / pmax): the same quotient, with a
                 * divisor the analysis knows is above OGK_LA_PIVOT_MIN; |l_ik| <= 1
                 * by the pivot choice, so the clamp only restates it. */
                const ogk_real_t q = OGK_FMIN(OGK_FMAX(f[(i * n) + k] / pmax, -OGK_R(1.0)), OGK_R(1.0));
                const ogk_real_t l_ik = negative ? -q : q;
                f[(i * n) + k] = l_ik;
                for (j = k + 1u; j < n; ++j) {
                    f[(i * n) + j] -= l_ik * f[(k * n) + j];
                }
            }
        }
    }
    return st;
}

/* lu->rcond of a held factorization, with the exact |A^-1|_1 from the
 * factors (largest absolute column sum), computed as |A_1 A^-1|_1 from the
 * columns A^-1 (|A|_1 e_j): scale-free, each entry at most 1 / rcond, so
 * within OGK_LA_SOLVE_MAX for any rcond worth reporting; rcond = 0 when a
 * column exceeds it (rcond < 1e-150: ill-conditioned either way). The
 * product |A|_1 |A^-1|_1 is at least 1 (|A A^-1|_1 = 1): the fmax only
 * restates it against rounding and bounds the reciprocal for the analysis. */
static void lu_set_rcond(ogk_lu_t *lu)
{
    size_t i;
    size_t j;
    ogk_real_t cond1 = OGK_R(0.0);
    bool ok = true;
    ogk_real_t col[OGK_LA_MAX_N];

    for (j = 0u; (j < lu->n) && ok; ++j) {
        ogk_real_t colsum = OGK_R(0.0);
        ok = lu_inverse_column(lu, j, lu->anorm1, col);
        for (i = 0u; (i < lu->n) && ok; ++i) {
            colsum += OGK_FABS(col[i]);
        }
        if (colsum > cond1) {
            cond1 = colsum;
        }
    }
    lu->rcond = ok ? (OGK_R(1.0) / OGK_FMAX(cond1, OGK_R(1.0))) : OGK_R(0.0);
}

ogk_status ogk_lu_factor(ogk_lu_t *lu, const ogk_real_t *A, size_t n)
{
    ogk_status st;

    if (lu == NULL) {
        st = OGK_E_NULL;
    } else {
        lu_invalidate(lu);
        st = la_square_check(A, n, lu, sizeof *lu);
    }
    if (st == OGK_OK) {
        lu_load(lu, A, n);
        st = lu_eliminate(lu, n);
        if (st == OGK_OK) {
            lu->n = n;
            lu_set_rcond(lu);
            if (!(lu->rcond >= OGK_LA_RCOND_MIN)) {
                st = OGK_E_ILL_CONDITIONED;
            }
        } else {
            lu_invalidate(lu);
        }
    }
    return st;
}

ogk_status ogk_lu_solve(const ogk_lu_t *lu, const ogk_real_t *b, ogk_real_t *x)
{
    ogk_status st;

    if ((lu == NULL) || (b == NULL) || (x == NULL)) {
        st = OGK_E_NULL;
    } else {
        st = lu_check_held(lu);
    }
    if (st == OGK_OK) {
        if (la_overlap(x, la_bytes(lu->n), lu, sizeof *lu)) {
            st = OGK_E_RANGE;
        } else {
            st = la_all_bounded(b, lu->n);
        }
        if (st == OGK_OK) {
            size_t i;
            ogk_real_t y[OGK_LA_MAX_N];
            /* b is read completely before x is written, so x may alias b. */
            for (i = 0u; i < lu->n; ++i) {
                y[i] = b[lu->perm[i]];
            }
            if (lu_substitute(lu, y)) {
                (void)memcpy(x, y, la_bytes(lu->n));
            } else {
                st = OGK_E_OVERFLOW;
            }
        }
    }
    return st;
}

ogk_status ogk_lu_inverse(const ogk_lu_t *lu, ogk_real_t *Ainv)
{
    ogk_status st;

    if ((lu == NULL) || (Ainv == NULL)) {
        st = OGK_E_NULL;
    } else {
        st = lu_check_held(lu);
    }
    if (st == OGK_OK) {
        if (la_overlap(Ainv, la_bytes(lu->n * lu->n), lu, sizeof *lu)) {
            st = OGK_E_RANGE;
        } else {
            size_t i;
            size_t j;
            ogk_real_t col[OGK_LA_MAX_N];
            for (j = 0u; (j < lu->n) && (st == OGK_OK); ++j) {
                if (lu_inverse_column(lu, j, OGK_R(1.0), col)) {
                    for (i = 0u; i < lu->n; ++i) {
                        Ainv[(i * lu->n) + j] = col[i];
                    }
                } else {
                    st = OGK_E_OVERFLOW;
                }
            }
        }
    }
    return st;
}

/* ------------------------------------------------------------------ Cholesky */

/* OGK_E_NOT_POSDEF unless the n x n matrix A is symmetric to OGK_CHOL_SYM_TOL
 * relative to the matrix scale max |A_ij| (an element-wise relative test would
 * reject round-off in entries that should be zero). */
static ogk_status chol_symmetry_check(const ogk_real_t *A, size_t n)
{
    size_t i;
    size_t j;
    ogk_real_t scale = OGK_R(0.0);
    bool symmetric = true;

    for (i = 0u; i < (n * n); ++i) {
        const ogk_real_t a = OGK_FABS(A[i]);
        if (a > scale) {
            scale = a;
        }
    }
    for (i = 1u; (i < n) && symmetric; ++i) {
        for (j = 0u; (j < i) && symmetric; ++j) {
            if (OGK_FABS(A[(i * n) + j] - A[(j * n) + i]) > (OGK_CHOL_SYM_TOL * scale)) {
                symmetric = false;
            }
        }
    }
    return symmetric ? OGK_OK : OGK_E_NOT_POSDEF;
}

/* A = L L^T (A n x n, checked) into ch->l by the kernel's one Cholesky
 * (chol.c) on A's lower triangle, read as the upper triangle of U = L^T and
 * factored in ch->l, then transposed in place; on OGK_E_NOT_POSDEF ch->l is
 * left zero. */
static ogk_status chol_decompose(ogk_chol_t *ch, const ogk_real_t *A, size_t n)
{
    ogk_status st;
    size_t i;
    size_t j;
    ogk_i_chol_rule_t rule;

    (void)memset(ch->l, 0, la_bytes(n * n));
    for (i = 0u; i < n; ++i) {
        for (j = 0u; j <= i; ++j) {
            ch->l[(j * n) + i] = A[(i * n) + j];
        }
    }
    /* a pivot d_i must exceed eps a_ii and the absolute floor
     * OGK_LA_PIVOT_MIN (ogk/linalg.h) */
    rule.rel = OGK_REAL_EPSILON;
    rule.floor = OGK_LA_PIVOT_MIN;
    /* |l_ij| <= sqrt(a_ii) for A = L L^T (row i of L has norm sqrt(a_ii));
     * twice that bound is never reached by an accepted factorization (an
     * l_ij beyond it makes d_i negative), so its clamp only bounds the
     * products for the analysis (docs/evidence/eva.md) */
    rule.bounded = true;
    rule.divide = true;
    st = ogk_i_chol_upper(ch->l, A, n, &rule);
    if (st == OGK_OK) {
        /* U = L^T to L: row-major lower, zero above the diagonal */
        for (i = 1u; i < n; ++i) {
            for (j = 0u; j < i; ++j) {
                ch->l[(i * n) + j] = ch->l[(j * n) + i];
                ch->l[(j * n) + i] = OGK_R(0.0);
            }
        }
    } else {
        (void)memset(ch->l, 0, la_bytes(n * n));
    }
    return st;
}

ogk_status ogk_chol_factor(ogk_chol_t *ch, const ogk_real_t *A, size_t n)
{
    ogk_status st;

    if (ch == NULL) {
        st = OGK_E_NULL;
    } else {
        ch->n = 0u;
        st = la_square_check(A, n, ch, sizeof *ch);
    }
    if (st == OGK_OK) {
        st = chol_symmetry_check(A, n);
    }
    if (st == OGK_OK) {
        st = chol_decompose(ch, A, n);
    }
    if (st == OGK_OK) {
        ch->n = n;
    }
    return st;
}

/* L y = b, then L^T x = y with a held factorization of order n; b is read
 * completely before x is written; false, x unwritten, when a quotient would
 * exceed OGK_LA_SOLVE_MAX (la_div). */
static bool chol_substitute(const ogk_chol_t *ch, const ogk_real_t *b, ogk_real_t *x)
{
    const size_t n = ch->n;
    bool ok = true;
    size_t i;
    size_t j;
    size_t ii;
    ogk_real_t y[OGK_LA_MAX_N];

    for (i = 0u; (i < n) && ok; ++i) {
        ogk_real_t sum = b[i];
        for (j = 0u; j < i; ++j) {
            sum -= ch->l[(i * n) + j] * y[j];
        }
        ok = la_div(sum, ch->l[(i * n) + i], &y[i]);
    }
    for (ii = 0u; (ii < n) && ok; ++ii) {
        const size_t row = n - 1u - ii;
        ogk_real_t sum = y[row];
        for (j = row + 1u; j < n; ++j) {
            sum -= ch->l[(j * n) + row] * y[j];
        }
        ok = la_div(sum, ch->l[(row * n) + row], &y[row]);
    }
    if (ok) {
        (void)memcpy(x, y, la_bytes(n));
    }
    return ok;
}

ogk_status ogk_chol_solve(const ogk_chol_t *ch, const ogk_real_t *b, ogk_real_t *x)
{
    ogk_status st;

    if ((ch == NULL) || (b == NULL) || (x == NULL)) {
        st = OGK_E_NULL;
    } else if (ch->n == 0u) {
        st = OGK_E_NOT_INIT;
    } else if (ch->n > OGK_LA_MAX_N) {
        st = OGK_E_DIM;
    } else if (la_overlap(x, la_bytes(ch->n), ch, sizeof *ch)) {
        st = OGK_E_RANGE;
    } else {
        st = la_all_bounded(b, ch->n);
    }
    if ((st == OGK_OK) && !chol_substitute(ch, b, x)) {
        st = OGK_E_OVERFLOW;
    }
    return st;
}

/* ------------------------------------------------------------------ Householder QR */

static void qr_invalidate(ogk_qr_t *ws)
{
    ws->long_dim = 0u;
    ws->short_dim = 0u;
}

/* Factors ws->qr (long_dim x short_dim, already loaded) in place. */
static void qr_factor(ogk_qr_t *ws)
{
    const size_t rows = ws->long_dim;
    const size_t cols = ws->short_dim;
    ogk_real_t *a = ws->qr;
    size_t i;
    size_t j;
    size_t k;

    for (k = 0u; k < cols; ++k) {
        const ogk_real_t alpha = a[(k * cols) + k];
        const ogk_real_t xnorm = la_norm2(&a[((k + 1u) * cols) + k], rows - k - 1u, cols);
        const ogk_real_t r = OGK_HYPOT(alpha, xnorm);
        ogk_real_t beta;
        ogk_real_t tau;
        ogk_real_t v_scale;

        if ((!(xnorm > OGK_R(0.0))) || (!(r > OGK_LA_PIVOT_MIN))) {
            /* Column already upper triangular: H = I (dlarfg convention); or
             * its norm r is at or below OGK_LA_PIVOT_MIN: H = I too, and
             * R_kk = alpha (|alpha| <= r) makes the rank test answer
             * OGK_E_SINGULAR (qr_r_norm1). */
            ws->tau[k] = OGK_R(0.0);
            continue;
        }
        beta = -OGK_COPYSIGN(r, alpha);
        /* (beta - alpha) / beta and 1 / (alpha - beta) with beta = -sign(alpha) r,
         * written on magnitudes (the same operations, bit for bit): the divisors
         * r and |alpha| + r exceed OGK_LA_PIVOT_MIN. tau lies in [1, 2] and
         * |v_i| <= xnorm / (|alpha| + r) <= 1: the clamps only catch rounding. */
        tau = OGK_FMIN((r + OGK_FABS(alpha)) / r, OGK_R(2.0));
        v_scale = OGK_COPYSIGN(OGK_R(1.0) / (OGK_FABS(alpha) + r), alpha);
        for (i = k + 1u; i < rows; ++i) {
            a[(i * cols) + k] = OGK_FMIN(OGK_FMAX(a[(i * cols) + k] * v_scale, -OGK_R(1.0)), OGK_R(1.0));
        }
        a[(k * cols) + k] = beta;
        ws->tau[k] = tau;
        /* Apply H_k = I - tau v v^T to the trailing columns. */
        for (j = k + 1u; j < cols; ++j) {
            ogk_real_t w = a[(k * cols) + j];
            for (i = k + 1u; i < rows; ++i) {
                w += a[(i * cols) + k] * a[(i * cols) + j];
            }
            w *= tau;
            a[(k * cols) + j] -= w;
            for (i = k + 1u; i < rows; ++i) {
                a[(i * cols) + j] -= w * a[(i * cols) + k];
            }
        }
    }
}

/* y <- H_k y for a vector y of long_dim entries. */
static void qr_apply_reflector(const ogk_qr_t *ws, size_t k, ogk_real_t *y)
{
    const size_t rows = ws->long_dim;
    const size_t cols = ws->short_dim;
    const ogk_real_t *a = ws->qr;

    if (ws->tau[k] != OGK_R(0.0)) {
        size_t i;
        ogk_real_t w = y[k];
        for (i = k + 1u; i < rows; ++i) {
            w += a[(i * cols) + k] * y[i];
        }
        w *= ws->tau[k];
        y[k] -= w;
        for (i = k + 1u; i < rows; ++i) {
            y[i] -= w * a[(i * cols) + k];
        }
    }
}

/* *rnorm1 = |R|_1; OGK_E_SINGULAR (and *rnorm1 unspecified) at the first
 * diagonal entry of R at or below tol or OGK_LA_PIVOT_MIN. */
static ogk_status qr_r_norm1(const ogk_qr_t *ws, ogk_real_t tol, ogk_real_t *rnorm1)
{
    const size_t cols = ws->short_dim;
    const ogk_real_t *a = ws->qr;
    ogk_status st = OGK_OK;
    size_t i;
    size_t j;

    *rnorm1 = OGK_R(0.0);
    for (j = 0u; (j < cols) && (st == OGK_OK); ++j) {
        if ((!(OGK_FABS(a[(j * cols) + j]) > tol)) ||
            (!(OGK_FABS(a[(j * cols) + j]) > OGK_LA_PIVOT_MIN))) {
            st = OGK_E_SINGULAR;
        } else {
            ogk_real_t colsum = OGK_R(0.0);
            for (i = 0u; i <= j; ++i) {
                colsum += OGK_FABS(a[(i * cols) + j]);
            }
            if (colsum > *rnorm1) {
                *rnorm1 = colsum;
            }
        }
    }
    return st;
}

/* |R|_1 |R^-1|_1 = max_j |R^-1 (s e_j)|_1 with s = |R|_1, column j by back
 * substitution on s e_j (nonzero in rows 0..j only): scale-free, each entry at
 * most 1 / rcond(R) (as lu_set_rcond). false when an entry would exceed
 * OGK_LA_SOLVE_MAX (la_div): rcond(R) below 1e-150. */
static bool qr_r_cond1(const ogk_qr_t *ws, ogk_real_t s, ogk_real_t *cond1)
{
    const size_t cols = ws->short_dim;
    const ogk_real_t *a = ws->qr;
    bool ok = true;
    ogk_real_t z[OGK_LA_MAX_N];
    size_t j;
    size_t p;
    size_t ii;

    *cond1 = OGK_R(0.0);
    for (j = 0u; (j < cols) && ok; ++j) {
        ogk_real_t colsum = OGK_R(0.0);
        ok = la_div(s, a[(j * cols) + j], &z[j]);
        for (ii = 0u; (ii < j) && ok; ++ii) {
            const size_t row = j - 1u - ii;
            ogk_real_t sum = OGK_R(0.0);
            for (p = row + 1u; p <= j; ++p) {
                sum += a[(row * cols) + p] * z[p];
            }
            ok = la_div(-sum, a[(row * cols) + row], &z[row]);
        }
        for (ii = 0u; (ii <= j) && ok; ++ii) {
            colsum += OGK_FABS(z[ii]);
        }
        if (colsum > *cond1) {
            *cond1 = colsum;
        }
    }
    return ok;
}

/* Rank test on R: SINGULAR when a diagonal entry is at or below
 * long_dim eps max_j |a_j|_2 (the numerical-rank tolerance of LAPACK/numpy;
 * it implies rcond(R) <= long_dim eps < OGK_LA_RCOND_MIN because
 * |R|_1 >= max_j |a_j|_2 and |R^-1|_1 >= 1/|r_kk|), ILL_CONDITIONED when
 * the exact 1-norm rcond of R (= that of A up to a factor short_dim in
 * the 2-norm sense) is below OGK_LA_RCOND_MIN. */
static ogk_status qr_rank_check(const ogk_qr_t *ws, ogk_real_t colnorm_max)
{
    const ogk_real_t tol = (ogk_real_t)ws->long_dim * OGK_REAL_EPSILON * colnorm_max;
    ogk_real_t rnorm1;
    ogk_status st = qr_r_norm1(ws, tol, &rnorm1);

    if (st == OGK_OK) {
        /* cond1 >= 1 (|R R^-1|_1 = 1): the fmax only restates it */
        ogk_real_t cond1;
        if ((!qr_r_cond1(ws, rnorm1, &cond1)) ||
            (!((OGK_R(1.0) / OGK_FMAX(cond1, OGK_R(1.0))) >= OGK_LA_RCOND_MIN))) {
            st = OGK_E_ILL_CONDITIONED;
        }
    }
    return st;
}

/* Common checks of ogk_lstsq and ogk_minnorm (A: m x n, b: m, x: n) in the
 * order of the header: NULL, dimensions (dims_ok, the caller's test, read only
 * once the pointers are known good), overlaps, non-finite inputs. */
static ogk_status qr_problem_check(const ogk_qr_t *ws, const ogk_real_t *A, size_t m, size_t n, /* NOLINT(bugprone-easily-swappable-parameters): dimension order of the header */
                                   const ogk_real_t *b, const ogk_real_t *x, bool dims_ok)
{
    ogk_status st;
    if ((A == NULL) || (b == NULL) || (x == NULL)) {
        st = OGK_E_NULL;
    } else if (!dims_ok) {
        st = OGK_E_DIM;
    } else if (la_overlap(A, la_bytes(m * n), ws, sizeof *ws) ||
               la_overlap(b, la_bytes(m), ws, sizeof *ws) ||
               la_overlap(x, la_bytes(n), ws, sizeof *ws) ||
               la_overlap(x, la_bytes(n), A, la_bytes(m * n)) ||
               la_overlap(x, la_bytes(n), b, la_bytes(m))) {
        st = OGK_E_RANGE;
    } else {
        /* NaN or Inf anywhere first, then magnitudes (la_all_bounded) */
        const ogk_status st_a = la_all_bounded(A, m * n);
        const ogk_status st_b = la_all_bounded(b, m);
        if ((st_a == OGK_E_NONFINITE) || (st_b == OGK_E_NONFINITE)) {
            st = OGK_E_NONFINITE;
        } else if (st_a != OGK_OK) {
            st = st_a;
        } else {
            st = st_b;
        }
    }
    return st;
}

/* x = R^-1 (Q^T b)(0:n-1) with the factors of ogk_lstsq in ws (m x n);
 * false, x unwritten, when an entry would exceed OGK_LA_SOLVE_MAX (la_div). */
static bool qr_lstsq_solve(const ogk_qr_t *ws, const ogk_real_t *b, ogk_real_t *x)
{
    const size_t m = ws->long_dim;
    const size_t n = ws->short_dim;
    bool ok = true;
    size_t i;
    size_t k;
    size_t ii;
    /* Q^T b needs all m entries: 1 KiB at the default OGK_LA_MAX_LONG. */
    ogk_real_t y[OGK_LA_MAX_LONG];

    /* y = Q^T b = H_{n-1} ... H_0 b, then R x = y(0:n-1). */
    (void)memcpy(y, b, la_bytes(m));
    for (k = 0u; k < n; ++k) {
        qr_apply_reflector(ws, k, y);
    }
    for (ii = 0u; (ii < n) && ok; ++ii) {
        const size_t row = n - 1u - ii;
        ogk_real_t sum = y[row];
        for (i = row + 1u; i < n; ++i) {
            sum -= ws->qr[(row * n) + i] * y[i];
        }
        ok = la_div(sum, ws->qr[(row * n) + row], &y[row]);
    }
    if (ok) {
        (void)memcpy(x, y, la_bytes(n));
    }
    return ok;
}

ogk_status ogk_lstsq(ogk_qr_t *ws, const ogk_real_t *A, size_t m, size_t n,
                     const ogk_real_t *b, ogk_real_t *x)
{
    ogk_status st;

    if (ws == NULL) {
        st = OGK_E_NULL;
    } else {
        qr_invalidate(ws);
        st = qr_problem_check(ws, A, m, n, b, x,
                              la_dim_ok(n, OGK_LA_MAX_N) && la_dim_ok(m, OGK_LA_MAX_LONG) &&
                                  (m >= n));
    }
    if (st == OGK_OK) {
        size_t j;
        ogk_real_t colnorm_max = OGK_R(0.0);
        (void)memcpy(ws->qr, A, la_bytes(m * n));
        ws->long_dim = m;
        ws->short_dim = n;
        for (j = 0u; j < n; ++j) {
            const ogk_real_t c = la_norm2(&A[j], m, n);
            if (c > colnorm_max) {
                colnorm_max = c;
            }
        }
        qr_factor(ws);
        st = qr_rank_check(ws, colnorm_max);
        if (st == OGK_E_SINGULAR) {
            qr_invalidate(ws);
        } else if (!qr_lstsq_solve(ws, b, x)) {
            st = OGK_E_OVERFLOW;
        } else {
            /* OGK_OK or OGK_E_ILL_CONDITIONED: x is computed either way. */
        }
    }
    return st;
}

/* x = Q [z; 0] with R^T z = b, the factors of A^T (ogk_minnorm) in ws
 * (n x m); b is read completely before x is written; false, x unwritten, when
 * an entry of z would exceed OGK_LA_SOLVE_MAX (la_div; |x|_2 = |z|_2). */
static bool qr_minnorm_solve(const ogk_qr_t *ws, const ogk_real_t *b, ogk_real_t *x)
{
    const size_t n = ws->long_dim;
    const size_t m = ws->short_dim;
    bool ok = true;
    size_t i;
    size_t j;
    ogk_real_t z[OGK_LA_MAX_N];

    /* A = R^T Q^T: R^T z = b (forward substitution), then x = Q [z; 0]. */
    for (i = 0u; (i < m) && ok; ++i) {
        ogk_real_t sum = b[i];
        for (j = 0u; j < i; ++j) {
            sum -= ws->qr[(j * m) + i] * z[j];
        }
        ok = la_div(sum, ws->qr[(i * m) + i], &z[i]);
    }
    if (ok) {
        size_t kk;
        for (i = 0u; i < m; ++i) {
            x[i] = z[i];
        }
        for (i = m; i < n; ++i) {
            x[i] = OGK_R(0.0);
        }
        /* Q = H_0 H_1 ... H_{m-1}: apply the last reflector first. */
        for (kk = 0u; kk < m; ++kk) {
            qr_apply_reflector(ws, m - 1u - kk, x);
        }
    }
    return ok;
}

ogk_status ogk_minnorm(ogk_qr_t *ws, const ogk_real_t *A, size_t m, size_t n,
                       const ogk_real_t *b, ogk_real_t *x)
{
    ogk_status st;

    if (ws == NULL) {
        st = OGK_E_NULL;
    } else {
        qr_invalidate(ws);
        st = qr_problem_check(ws, A, m, n, b, x,
                              la_dim_ok(m, OGK_LA_MAX_N) && la_dim_ok(n, OGK_LA_MAX_LONG) &&
                                  (m <= n));
    }
    if (st == OGK_OK) {
        size_t i;
        size_t j;
        ogk_real_t rownorm_max = OGK_R(0.0);
        /* ws->qr = A^T (n x m): the long side is A's column count. */
        for (i = 0u; i < n; ++i) {
            for (j = 0u; j < m; ++j) {
                ws->qr[(i * m) + j] = A[(j * n) + i];
            }
        }
        ws->long_dim = n;
        ws->short_dim = m;
        for (j = 0u; j < m; ++j) {
            const ogk_real_t r = la_norm2(&A[j * n], n, 1u);
            if (r > rownorm_max) {
                rownorm_max = r;
            }
        }
        qr_factor(ws);
        st = qr_rank_check(ws, rownorm_max);
        if (st == OGK_E_SINGULAR) {
            qr_invalidate(ws);
        } else if (!qr_minnorm_solve(ws, b, x)) {
            st = OGK_E_OVERFLOW;
        } else {
            /* OGK_OK or OGK_E_ILL_CONDITIONED: x is computed either way. */
        }
    }
    return st;
}
