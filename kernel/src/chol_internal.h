/* chol_internal.h -- the kernel's one Cholesky factorisation (kernel/src/chol.c),
 * used by the QP (qp_blas.c, ogk_i_qp_cholesky), ogk_chol_factor (linalg.c)
 * and the NMPC's convexification test (nmpc_hess.c), and the row update
 * they share. Internal to the kernel. */
#ifndef OGK_CHOL_INTERNAL_H
#define OGK_CHOL_INTERNAL_H

#include <stdbool.h>
#include <stddef.h>

#include "ogk/status.h"
#include "ogk/real.h"

/* row[0..len-1] -= a * u[0..len-1], two columns per step (one SIMD pair on
 * SSE2); each entry sees one multiply and one subtract, as the plain loop.
 * static inline: the QP's loops (qp_blas.c) pay no call. */
static inline void ogk_i_row_axpy_sub(ogk_real_t *row, ogk_real_t a, const ogk_real_t *u, size_t len)
{
    size_t c = 0u;
    for (; (c + 2u) <= len; c += 2u) {
        const ogk_real_t ra = row[c] - (a * u[c]);
        const ogk_real_t rb = row[c + 1u] - (a * u[c + 1u]);
        row[c] = ra;
        row[c + 1u] = rb;
    }
    if (c < len) {
        row[c] -= a * u[c];
    }
}

/* What each user accepts as a pivot, how it scales a pivot row, and the
 * analysis bound of linalg.c. */
typedef struct {
    ogk_real_t rel;          /* [-] a reduced pivot d_k <= rel a_kk is not positive definite */
    ogk_real_t floor;        /* [units of A] nor is a d_k <= floor (nor an a_kk <= 0 or NaN) */
    bool bounded;        /* U(k, i) held within +-2 sqrt(|a_ii|) (row i of L has norm sqrt(a_ii)
                          * when A = L L^T: twice that is never reached by an accepted
                          * factorisation), a bound there for Frama-C EVA's ranges (linalg.c,
                          * docs/evidence/eva.md); it goes with divide */
    bool divide;         /* U(k, i) = reduced U(k, i) / u_kk, correctly rounded (ogk_chol_factor,
                          * the NMPC's test); false: times 1 / u_kk, one multiply per entry
                          * (the QP's cost, docs/design/qp.md) and up to an ulp apart */
} ogk_i_chol_rule_t;

/* Factors in place the upper triangle of U (row-major n x n, the matrix to
 * factor there on entry; the strict lower triangle is neither read nor
 * written) into U with A = U^T U (L = U^T); a is the matrix's own row-major
 * n x n storage, of which only the diagonal is read, for the pivot test.
 * OGK_E_NOT_POSDEF when a pivot fails the rule (U then partly written).
 * Right-looking (outer-product) Cholesky by panels of four pivot rows
 * (Golub & Van Loan, Algorithm 4.2.2 by rows): row k of U is its reduced
 * row over u_kk = sqrt(d_k), and every entry U(i, j)
 * receives its updates -U(k, i) U(k, j) in increasing k, so the blocking
 * changes no bit. */
ogk_status ogk_i_chol_upper(ogk_real_t *U, const ogk_real_t *a, size_t n, const ogk_i_chol_rule_t *rule);

#endif /* OGK_CHOL_INTERNAL_H */
