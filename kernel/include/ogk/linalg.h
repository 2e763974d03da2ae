/* ogk/linalg.h -- fixed-size dense linear algebra on row-major ogk_real_t arrays.
 *
 * Matrices are plain row-major arrays: element (i, j) of an r x c matrix A is
 * A[i * c + j]. Dimensions are checked against OGK_LA_MAX_N / OGK_LA_MAX_LONG
 * (ogk/config.h); a zero or too-large dimension gives OGK_E_DIM. Outputs must
 * not alias inputs unless a function says so (OGK_E_RANGE otherwise). Inputs
 * are not checked for NaN/Inf by the products (cost); the factorizations do
 * check and return OGK_E_NONFINITE. Factorizations keep their result in a
 * caller-owned struct, so no memory is allocated and several run side by side. */
#ifndef OGK_LINALG_H
#define OGK_LINALG_H

#include <stddef.h>
#include "ogk/config.h"
#include "ogk/status.h"
#include "ogk/real.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Reciprocal 1-norm condition number below which a factorization reports
 * OGK_E_ILL_CONDITIONED (its factors are still stored and usable).
 * It must lie above what the pivot tests imply, so that OGK_E_SINGULAR never
 * hides a matrix ILL_CONDITIONED would have accepted: an LU pivot at or below
 * eps |A|_1 implies rcond <= n eps, a QR diagonal entry at or below long_dim
 * eps max_j |a_j|_2 implies rcond(R) <= long_dim eps, so at most
 * OGK_LA_MAX_LONG eps (ogk/config.h). Double: 1e-13, 3.5 times that bound
 * (128 eps = 2.8e-14), where cond eps = 2e-3 (a solve keeps about three
 * digits). Float: 1e-13 is below any rcond float can compute without a pivot
 * falling below eps |A| first (LU: n eps >= 2.4e-7), so ILL_CONDITIONED was
 * unreachable and every such matrix SINGULAR; 4 OGK_LA_MAX_LONG eps (512 eps
 * = 6.1e-5) keeps the double value's ratio to the bound and its meaning
 * (cond eps = 2e-3 at the threshold). */
#if OGK_REAL_SINGLE
#define OGK_LA_RCOND_MIN (OGK_R(4.0) * OGK_R(OGK_LA_MAX_LONG) * OGK_REAL_EPSILON)
#else
#define OGK_LA_RCOND_MIN OGK_R(1.0e-13)
#endif

/* Absolute floor of the pivots: an LU pivot, a Cholesky Schur-complement pivot
 * d_i or a diagonal entry of R (QR) at or below it counts as zero, giving
 * OGK_E_SINGULAR (LU, QR) or OGK_E_NOT_POSDEF (Cholesky), as the relative tests
 * (|pivot| <= eps |A|) already do for any matrix whose norm exceeds
 * 1e-300 / eps (about 4.5e-285; float build: 1e-30 / eps, about 8.4e-24).
 * It bounds every division of the factorizations, which lets a non-relational
 * analysis prove them finite (docs/evidence/eva.md). OGK_REAL_TINY: 1e-300 in
 * double, 1e-30 in float (ogk/real.h). */
#define OGK_LA_PIVOT_MIN OGK_REAL_TINY

/* Magnitude bound of the inputs: an entry of a matrix handed to a
 * factorization or of a right-hand side above it gives OGK_E_RANGE (NaN or Inf
 * still OGK_E_NONFINITE). The products do not check it (cost): their callers
 * must keep their operands within it (the ACSL requires below), and then no
 * product can overflow (at most OGK_LA_MAX_LONG terms of 1e300 each; float
 * build: 1e30 each). OGK_REAL_ROOT_BIG: 1e150 in double, 1e15 in float. */
#define OGK_LA_VALUE_MAX OGK_REAL_ROOT_BIG

/* Magnitude bound of every entry of a solution (the solves, ogk_lstsq,
 * ogk_minnorm, ogk_lu_inverse) and of every intermediate of the substitutions.
 * Each division is checked before it is made: a quotient beyond this bound
 * gives OGK_E_OVERFLOW and no output (x is left unwritten). With inputs within
 * OGK_LA_VALUE_MAX every sum of the substitutions is below 1e306 (at most 15
 * products of a factor entry, <= 2^15 OGK_LA_VALUE_MAX with LU's growth, and
 * a solution entry), so no operation of the solves can overflow
 * (docs/design/linalg.md, docs/evidence/eva.md); in the float build, 1e15 each,
 * every sum is below 15 2^15 1e30 (4.9e35 < FLT_MAX). The rcond of ogk_lu_factor and of the QR rank
 * test is computed on A^-1 |A|_1 e_j, whose entries stay below this bound for
 * any rcond >= n / OGK_LA_SOLVE_MAX; a smaller rcond is reported as 0
 * (OGK_E_ILL_CONDITIONED either way). */
#define OGK_LA_SOLVE_MAX OGK_REAL_ROOT_BIG

/* y = A x,  A: rows x cols,  rows, cols <= OGK_LA_MAX_LONG. The entries of A
 * and x must be within OGK_LA_VALUE_MAX (not checked: cost), so y is finite. */
/*@ requires A_valid: A == \null || \valid_read(A + (0 .. rows * cols - 1));
    requires x_valid: x == \null || \valid_read(x + (0 .. cols - 1));
    requires y_valid: y == \null || \valid(y + (0 .. rows - 1));
    requires A_bounded: A == \null || rows > OGK_LA_MAX_LONG || cols > OGK_LA_MAX_LONG ||
        (\forall integer i; 0 <= i < rows * cols ==> -OGK_LA_VALUE_MAX <= A[i] <= OGK_LA_VALUE_MAX);
    requires x_bounded: x == \null || cols > OGK_LA_MAX_LONG ||
        (\forall integer i; 0 <= i < cols ==> -OGK_LA_VALUE_MAX <= x[i] <= OGK_LA_VALUE_MAX);
*/
ogk_status ogk_mat_vec(const ogk_real_t *A, size_t rows, size_t cols,
                       const ogk_real_t *x, ogk_real_t *y);

/* y = A^T x,  A: rows x cols,  y has cols entries; operands within
 * OGK_LA_VALUE_MAX as for ogk_mat_vec. */
/*@ requires A_valid: A == \null || \valid_read(A + (0 .. rows * cols - 1));
    requires x_valid: x == \null || \valid_read(x + (0 .. rows - 1));
    requires y_valid: y == \null || \valid(y + (0 .. cols - 1));
    requires A_bounded: A == \null || rows > OGK_LA_MAX_LONG || cols > OGK_LA_MAX_LONG ||
        (\forall integer i; 0 <= i < rows * cols ==> -OGK_LA_VALUE_MAX <= A[i] <= OGK_LA_VALUE_MAX);
    requires x_bounded: x == \null || rows > OGK_LA_MAX_LONG ||
        (\forall integer i; 0 <= i < rows ==> -OGK_LA_VALUE_MAX <= x[i] <= OGK_LA_VALUE_MAX);
*/
ogk_status ogk_mat_t_vec(const ogk_real_t *A, size_t rows, size_t cols,
                         const ogk_real_t *x, ogk_real_t *y);

/* C = A B,  A: r x k, B: k x c, C: r x c; each dimension <= OGK_LA_MAX_LONG.
 * The entries of the operands of all products must be within OGK_LA_VALUE_MAX. */
ogk_status ogk_mat_mul(const ogk_real_t *A, size_t r, size_t k,
                       const ogk_real_t *B, size_t c, ogk_real_t *C);

/* C = A^T B,  A: k x r, B: k x c, C: r x c. */
ogk_status ogk_mat_mul_at_b(const ogk_real_t *A, size_t k, size_t r,
                            const ogk_real_t *B, size_t c, ogk_real_t *C);

/* C = A B^T,  A: r x k, B: c x k, C: r x c. */
ogk_status ogk_mat_mul_a_bt(const ogk_real_t *A, size_t r, size_t k,
                            const ogk_real_t *B, size_t c, ogk_real_t *C);

/* At = A^T,  A: rows x cols. */
ogk_status ogk_mat_transpose(const ogk_real_t *A, size_t rows, size_t cols,
                             ogk_real_t *At);

/* LU factorization with partial pivoting, P A = L U. */
typedef struct {
    ogk_real_t lu[OGK_LA_MAX_N * OGK_LA_MAX_N]; /* [-] L (unit lower, below diag) and U, row-major n x n */
    size_t perm[OGK_LA_MAX_N];              /* [-] row i of P A is row perm[i] of A */
    size_t n;                               /* [-] order; 0 when no valid factorization is held */
    ogk_real_t anorm1;                          /* [units of A] 1-norm of A */
    ogk_real_t rcond;                           /* [-] reciprocal 1-norm condition number, 1/(|A|_1 |A^-1|_1) */
} ogk_lu_t;

/* Factors the n x n matrix A (entries within OGK_LA_VALUE_MAX, OGK_E_RANGE
 * otherwise). OGK_E_SINGULAR when a pivot is zero to working
 * precision or at most OGK_LA_PIVOT_MIN (lu->n is then 0); OGK_E_ILL_CONDITIONED
 * when rcond < OGK_LA_RCOND_MIN (factors kept, solves allowed). */
/*@ requires lu_valid: lu == \null || \valid(lu);
    requires A_valid: A == \null || n > OGK_LA_MAX_N || \valid_read(A + (0 .. n * n - 1));
*/
ogk_status ogk_lu_factor(ogk_lu_t *lu, const ogk_real_t *A, size_t n);

/* Solves A x = b with a held factorization; x may alias b. b within
 * OGK_LA_VALUE_MAX (OGK_E_RANGE); OGK_E_OVERFLOW, x unwritten, when an entry
 * of x or of the substitution's intermediates would exceed OGK_LA_SOLVE_MAX. */
ogk_status ogk_lu_solve(const ogk_lu_t *lu, const ogk_real_t *b, ogk_real_t *x);

/* Ainv = A^-1 (n x n) with a held factorization; OGK_E_OVERFLOW (Ainv
 * partly written) when an entry would exceed OGK_LA_SOLVE_MAX. */
ogk_status ogk_lu_inverse(const ogk_lu_t *lu, ogk_real_t *Ainv);

/* Cholesky factorization A = L L^T of a symmetric positive definite matrix. */
typedef struct {
    ogk_real_t l[OGK_LA_MAX_N * OGK_LA_MAX_N]; /* [sqrt(units of A)] lower factor, row-major n x n, zero above diag */
    size_t n;                              /* [-] order; 0 when no valid factorization is held */
} ogk_chol_t;

/* Factors A (entries within OGK_LA_VALUE_MAX, OGK_E_RANGE otherwise; only its
 * lower triangle is read; symmetry is checked to
 * 1e-12 relative). OGK_E_NOT_POSDEF when not positive definite or not symmetric
 * (a pivot d_i at or below eps a_ii or OGK_LA_PIVOT_MIN). */
/*@ requires ch_valid: ch == \null || \valid(ch);
    requires A_valid: A == \null || n > OGK_LA_MAX_N || \valid_read(A + (0 .. n * n - 1));
*/
ogk_status ogk_chol_factor(ogk_chol_t *ch, const ogk_real_t *A, size_t n);

/* Solves A x = b with a held factorization; x may alias b. b within
 * OGK_LA_VALUE_MAX (OGK_E_RANGE); OGK_E_OVERFLOW, x unwritten, as ogk_lu_solve. */
ogk_status ogk_chol_solve(const ogk_chol_t *ch, const ogk_real_t *b, ogk_real_t *x);

/* Householder QR workspace for least-squares and minimum-norm problems. */
typedef struct {
    ogk_real_t qr[OGK_LA_MAX_LONG * OGK_LA_MAX_N]; /* [-] Householder vectors and R, row-major long x short */
    ogk_real_t tau[OGK_LA_MAX_N];                  /* [-] Householder scalars */
    size_t long_dim;                           /* [-] long side of the factored matrix */
    size_t short_dim;                          /* [-] short side (rank) */
} ogk_qr_t;

/* Least squares: x = argmin |A x - b|_2 for A: m x n with m >= n, full column
 * rank (n <= OGK_LA_MAX_N, m <= OGK_LA_MAX_LONG). ws is caller-owned scratch.
 * OGK_E_SINGULAR / OGK_E_ILL_CONDITIONED on (near) rank deficiency (a diagonal
 * entry of R at or below OGK_LA_PIVOT_MIN is singular). A and b within
 * OGK_LA_VALUE_MAX (OGK_E_RANGE); OGK_E_OVERFLOW when an entry of x would
 * exceed OGK_LA_SOLVE_MAX (x then unwritten). */
ogk_status ogk_lstsq(ogk_qr_t *ws, const ogk_real_t *A, size_t m, size_t n,
                     const ogk_real_t *b, ogk_real_t *x);

/* Minimum norm: x = argmin |x|_2 subject to A x = b for A: m x n with m <= n,
 * full row rank (m <= OGK_LA_MAX_N, n <= OGK_LA_MAX_LONG), computed from a QR
 * factorization of A^T (equal to A^T (A A^T)^-1 b without forming A A^T).
 * Bounds and OGK_E_OVERFLOW as ogk_lstsq. */
ogk_status ogk_minnorm(ogk_qr_t *ws, const ogk_real_t *A, size_t m, size_t n,
                       const ogk_real_t *b, ogk_real_t *x);

#ifdef __cplusplus
}
#endif

#endif /* OGK_LINALG_H */
