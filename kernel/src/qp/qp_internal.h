/* qp_internal.h -- the dense loops of ogk_qp_solve (kernel/src/qp_blas.c):
 * matrix-vector products and the rank-1 update of J^T (row-major, row
 * stride n), blocked over rows so that each pass over a vector serves
 * several rows. Every element is computed in the same order of operations
 * as the plain loop (no reassociation): the results are bit-identical to it.
 * Internal to the kernel. */
#ifndef OGK_QP_INTERNAL_H
#define OGK_QP_INTERNAL_H

#include <stdbool.h>
#include <stddef.h>

#include "ogk/status.h"
#include "ogk/real.h"

/* d[k] = sign * (J[k, :] . a) for k = 0..m-1 (J m x n, row stride n);
 * lower: J is lower triangular (its zeros above the diagonal are skipped). */
void ogk_i_qp_mat_vec(const ogk_real_t *J, size_t m, size_t n, bool lower, const ogk_real_t *a, ogk_real_t sign, ogk_real_t *d);

/* z = sum_{k = k0}^{n-1} d[k] J[k, :] (the rows k0..n-1 of J, combined);
 * lower: J is lower triangular (its zeros above the diagonal are skipped). */
void ogk_i_qp_rows_combine(const ogk_real_t *J, size_t n, bool lower, size_t k0, const ogk_real_t *d, ogk_real_t *z);

/* J[k, :] -= v[k] w for k = k0..n-1. */
void ogk_i_qp_rank1_rows(ogk_real_t *J, size_t n, size_t k0, const ogk_real_t *v, const ogk_real_t *w);

/* U (row-major, upper triangle; the strict lower triangle is not written)
 * with (H + H^T)/2 = U^T U, i.e. L = U^T. OGK_E_NOT_POSDEF when a pivot
 * d^2 <= OGK_QP_PIVOT_TOL H_jj or H_jj <= 0 (U then partly written), or when
 * H is not symmetric: |H_ij - H_ji| > OGK_QP_SYM_TOL max |H| (H finite). */
ogk_status ogk_i_qp_cholesky(const ogk_real_t *H, size_t n, ogk_real_t *U);

/* Li = L^-1 = U^-T (lower triangular, zero above the diagonal), row by row:
 * L(i,i) Li(i,:) = e_i - sum_{k<i} L(i,k) Li(k,:), L(i,k) = U(k,i). */
void ogk_i_qp_inverse_lower(const ogk_real_t *U, size_t n, ogk_real_t *Li);

#endif /* OGK_QP_INTERNAL_H */
