/* chol.c -- the kernel's one Cholesky factorisation (chol_internal.h): the
 * QP's blocked right-looking form, which every user shares (docs/design/qp.md,
 * "Cost"; docs/design/linalg.md). */
#include "../chol_internal.h"
#include "../ogk_checks.h"

#include <math.h>
#include <stddef.h>

/* Row i of the trailing matrix (columns i..n-1) minus the outer products of
 * the four pivot rows k..k+3, in that order (the order of four one-row
 * updates), two columns per step (one SIMD pair on SSE2). */
static void chol_trailing_rank4(ogk_real_t *U, size_t n, size_t k, size_t i) /* NOLINT(bugprone-easily-swappable-parameters): pivot block k, row i; a swap fails the unit tests */
{
    const ogk_real_t *u0 = &U[k * n];
    const ogk_real_t *u1 = &u0[n];
    const ogk_real_t *u2 = &u1[n];
    const ogk_real_t *u3 = &u2[n];
    const ogk_real_t a0 = u0[i];
    const ogk_real_t a1 = u1[i];
    const ogk_real_t a2 = u2[i];
    const ogk_real_t a3 = u3[i];
    ogk_real_t *row = &U[i * n];
    size_t c = i;
    for (; (c + 2u) <= n; c += 2u) {
        const ogk_real_t ra = (((row[c] - (a0 * u0[c])) - (a1 * u1[c])) - (a2 * u2[c])) - (a3 * u3[c]);
        const ogk_real_t rb = (((row[c + 1u] - (a0 * u0[c + 1u])) - (a1 * u1[c + 1u])) - (a2 * u2[c + 1u])) -
                          (a3 * u3[c + 1u]);
        row[c] = ra;
        row[c + 1u] = rb;
    }
    if (c < n) {
        row[c] = (((row[c] - (a0 * u0[c])) - (a1 * u1[c])) - (a2 * u2[c])) - (a3 * u3[c]);
    }
}

/* Row k of U over its pivot u_kk: U(k, i) for i > k, by the division or by
 * the reciprocal inv = 1 / u_kk (rule->divide), within +-2 sqrt(|a_ii|) when
 * the rule is bounded (linalg.c's, with the division). */
static void chol_scale_row(ogk_real_t *uk, const ogk_real_t *a, size_t k, size_t n, const ogk_i_chol_rule_t *rule) /* NOLINT(bugprone-easily-swappable-parameters): row, the matrix, its pivot index, order; its only caller is ogk_i_chol_upper */
{
    const ogk_real_t ukk = uk[k];
    size_t i;
    if (rule->bounded) {
        for (i = k + 1u; i < n; ++i) {
            const ogk_real_t bound = OGK_R(2.0) * OGK_SQRT(OGK_FABS(a[(i * n) + i]));
            uk[i] = OGK_FMIN(OGK_FMAX(uk[i] / ukk, -bound), bound);
        }
    } else if (rule->divide) {
        for (i = k + 1u; i < n; ++i) {
            uk[i] /= ukk;
        }
    } else {
        const ogk_real_t inv = OGK_R(1.0) / ukk;
        for (i = k + 1u; i < n; ++i) {
            uk[i] *= inv;
        }
    }
}

ogk_status ogk_i_chol_upper(ogk_real_t *U, const ogk_real_t *a, size_t n, const ogk_i_chol_rule_t *rule)
{
    ogk_status st = OGK_OK;
    size_t i;
    size_t k;
    size_t kb;
    for (kb = 0u; (kb < n) && (st == OGK_OK); kb += 4u) {
        const size_t kend = ogk_i_min_size(kb + 4u, n); /* the panel's end */
        for (k = kb; (k < kend) && (st == OGK_OK); ++k) {
            const ogk_real_t akk = a[(k * n) + k];
            const ogk_real_t piv = U[(k * n) + k];
            /* d_k = a_kk - |U(0..k-1, k)|^2 is the Schur-complement pivot; for
             * SPD A, cond_2(A) >= a_kk / d_k, so d_k <= rel a_kk means A is not
             * positive definite to the user's precision; floor is an absolute
             * one (linalg.c: OGK_LA_PIVOT_MIN; NMPC: its pivot_min) */
            if ((!(akk > OGK_R(0.0))) || (!(piv > (rule->rel * akk))) || (!(piv > rule->floor))) {
                st = OGK_E_NOT_POSDEF;
            } else {
                ogk_real_t *uk = &U[k * n];
                uk[k] = OGK_SQRT(piv);
                chol_scale_row(uk, a, k, n, rule);
                /* inside the panel row by row */
                for (i = k + 1u; i < kend; ++i) {
                    ogk_i_row_axpy_sub(&U[(i * n) + i], uk[i], &uk[i], n - i);
                }
            }
        }
        if ((st == OGK_OK) && (kend == (kb + 4u))) {
            /* below the panel: its four outer products in one pass per row */
            for (i = kend; i < n; ++i) {
                chol_trailing_rank4(U, n, kb, i);
            }
        }
    }
    return st;
}
