/* qp_blas.c -- the dense loops of ogk_qp_solve (kernel/src/qp.c), blocked by
 * four rows (two for the update) so that the shared vector is read once per
 * block and the loop overhead is shared: each element still sees the same
 * operations in the same order as the one-row loop, so the results are the
 * same to the bit (docs/design/qp.md, "Cost"). */
#include "qp_internal.h"
#include "../chol_internal.h"

#include <math.h>
#include <stdbool.h>
#include <stddef.h>

#include "ogk/qp.h"

/* Columns of rows ..end-1 that can be nonzero: end for a lower triangular
 * matrix (capped at n), n otherwise. */
static size_t qp_row_end(bool lower, size_t n, size_t end)
{
    size_t len = n;
    if (lower && (end < n)) {
        len = end;
    }
    return len;
}

void ogk_i_qp_mat_vec(const ogk_real_t *J, size_t m, size_t n, bool lower, const ogk_real_t *a, ogk_real_t sign, ogk_real_t *d) /* NOLINT(bugprone-easily-swappable-parameters): internal, every call in qp.c */
{
    size_t k = 0u;
    size_t i;
    /* four rows per pass over a; each row's sum in two halves (even and odd
     * columns), added at the end: a SIMD pair on SSE2 */
    for (; (k + 4u) <= m; k += 4u) {
        const ogk_real_t *j0 = &J[k * n];
        const ogk_real_t *j1 = &j0[n];
        const ogk_real_t *j2 = &j1[n];
        const ogk_real_t *j3 = &j2[n];
        ogk_real_t s0a = OGK_R(0.0);
        ogk_real_t s0b = OGK_R(0.0);
        ogk_real_t s1a = OGK_R(0.0);
        ogk_real_t s1b = OGK_R(0.0);
        ogk_real_t s2a = OGK_R(0.0);
        ogk_real_t s2b = OGK_R(0.0);
        ogk_real_t s3a = OGK_R(0.0);
        ogk_real_t s3b = OGK_R(0.0);
        /* a lower triangular J: rows k..k+3 end at column k+3 */
        const size_t len = qp_row_end(lower, n, k + 4u);
        for (i = 0u; (i + 2u) <= len; i += 2u) {
            const ogk_real_t aa = a[i];
            const ogk_real_t ab = a[i + 1u];
            s0a += j0[i] * aa;
            s0b += j0[i + 1u] * ab;
            s1a += j1[i] * aa;
            s1b += j1[i + 1u] * ab;
            s2a += j2[i] * aa;
            s2b += j2[i + 1u] * ab;
            s3a += j3[i] * aa;
            s3b += j3[i + 1u] * ab;
        }
        if (i < len) {
            s0a += j0[i] * a[i];
            s1a += j1[i] * a[i];
            s2a += j2[i] * a[i];
            s3a += j3[i] * a[i];
        }
        d[k] = sign * (s0a + s0b);
        d[k + 1u] = sign * (s1a + s1b);
        d[k + 2u] = sign * (s2a + s2b);
        d[k + 3u] = sign * (s3a + s3b);
    }
    for (; k < m; ++k) {
        const ogk_real_t *jk = &J[k * n];
        ogk_real_t s = OGK_R(0.0);
        const size_t len = qp_row_end(lower, n, k + 1u);
        for (i = 0u; i < len; ++i) {
            s += jk[i] * a[i];
        }
        d[k] = sign * s;
    }
}

void ogk_i_qp_rows_combine(const ogk_real_t *J, size_t n, bool lower, size_t k0, const ogk_real_t *d, ogk_real_t *z) /* NOLINT(bugprone-easily-swappable-parameters): internal, every call in qp.c */
{
    size_t k = k0;
    size_t i;
    for (i = 0u; i < n; ++i) {
        z[i] = OGK_R(0.0);
    }
    for (; (k + 4u) <= n; k += 4u) {
        const ogk_real_t *j0 = &J[k * n];
        const ogk_real_t *j1 = &j0[n];
        const ogk_real_t *j2 = &j1[n];
        const ogk_real_t *j3 = &j2[n];
        const ogk_real_t d0 = d[k];
        const ogk_real_t d1 = d[k + 1u];
        const ogk_real_t d2 = d[k + 2u];
        const ogk_real_t d3 = d[k + 3u];
        /* a lower triangular J: rows k..k+3 end at column k+3 */
        const size_t len = qp_row_end(lower, n, k + 4u);
        /* two columns per step: the pair is one SIMD operation where the
         * target has one (SSE2), two scalar ones elsewhere */
        for (i = 0u; (i + 2u) <= len; i += 2u) {
            const ogk_real_t za = (((z[i] + (j0[i] * d0)) + (j1[i] * d1)) + (j2[i] * d2)) + (j3[i] * d3);
            const ogk_real_t zb = (((z[i + 1u] + (j0[i + 1u] * d0)) + (j1[i + 1u] * d1)) + (j2[i + 1u] * d2)) +
                              (j3[i + 1u] * d3);
            z[i] = za;
            z[i + 1u] = zb;
        }
        if (i < len) {
            z[i] = (((z[i] + (j0[i] * d0)) + (j1[i] * d1)) + (j2[i] * d2)) + (j3[i] * d3);
        }
    }
    for (; k < n; ++k) {
        const ogk_real_t *jk = &J[k * n];
        const ogk_real_t dk = d[k];
        const size_t len = qp_row_end(lower, n, k + 1u);
        for (i = 0u; i < len; ++i) {
            z[i] += jk[i] * dk;
        }
    }
}

void ogk_i_qp_rank1_rows(ogk_real_t *J, size_t n, size_t k0, const ogk_real_t *v, const ogk_real_t *w) /* NOLINT(bugprone-easily-swappable-parameters): internal, its one call in qp_add; a swap fails the unit tests */
{
    size_t k = k0;
    size_t i;
    for (; (k + 4u) <= n; k += 4u) {
        ogk_real_t *j0 = &J[k * n];
        ogk_real_t *j1 = &j0[n];
        ogk_real_t *j2 = &j1[n];
        ogk_real_t *j3 = &j2[n];
        const ogk_real_t v0 = v[k];
        const ogk_real_t v1 = v[k + 1u];
        const ogk_real_t v2 = v[k + 2u];
        const ogk_real_t v3 = v[k + 3u];
        /* four rows per pass over w, two columns per step (one SIMD pair on SSE2) */
        for (i = 0u; (i + 2u) <= n; i += 2u) {
            const ogk_real_t wa = w[i];
            const ogk_real_t wb = w[i + 1u];
            const ogk_real_t a0 = j0[i] - (v0 * wa);
            const ogk_real_t b0 = j0[i + 1u] - (v0 * wb);
            const ogk_real_t a1 = j1[i] - (v1 * wa);
            const ogk_real_t b1 = j1[i + 1u] - (v1 * wb);
            const ogk_real_t a2 = j2[i] - (v2 * wa);
            const ogk_real_t b2 = j2[i + 1u] - (v2 * wb);
            const ogk_real_t a3 = j3[i] - (v3 * wa);
            const ogk_real_t b3 = j3[i + 1u] - (v3 * wb);
            j0[i] = a0;
            j0[i + 1u] = b0;
            j1[i] = a1;
            j1[i + 1u] = b1;
            j2[i] = a2;
            j2[i + 1u] = b2;
            j3[i] = a3;
            j3[i + 1u] = b3;
        }
        if (i < n) {
            j0[i] -= v0 * w[i];
            j1[i] -= v1 * w[i];
            j2[i] -= v2 * w[i];
            j3[i] -= v3 * w[i];
        }
    }
    for (; k < n; ++k) {
        ogk_i_row_axpy_sub(&J[k * n], v[k], w, n);
    }
}

ogk_status ogk_i_qp_cholesky(const ogk_real_t *H, size_t n, ogk_real_t *U)
{
    static const ogk_i_chol_rule_t rule = {OGK_QP_PIVOT_TOL, OGK_R(0.0), false, false};
    ogk_status st;
    ogk_real_t hmax = OGK_R(0.0);
    ogk_real_t asym = OGK_R(0.0);
    size_t i;
    size_t k;
    /* the upper triangle of (H + H^T)/2; the pairs H(i, k), H(k, i) also
     * give max |H| and the asymmetry */
    for (k = 0u; k < n; ++k) {
        const ogk_real_t hkk = OGK_FABS(H[(k * n) + k]);
        hmax = (hkk > hmax) ? hkk : hmax;
        U[(k * n) + k] = H[(k * n) + k];
        for (i = k + 1u; i < n; ++i) {
            const ogk_real_t up = H[(k * n) + i];
            const ogk_real_t lo = H[(i * n) + k];
            const ogk_real_t big = (OGK_FABS(lo) > OGK_FABS(up)) ? OGK_FABS(lo) : OGK_FABS(up);
            hmax = (big > hmax) ? big : hmax;
            asym = (OGK_FABS(lo - up) > asym) ? OGK_FABS(lo - up) : asym;
            U[(k * n) + i] = OGK_R(0.5) * (lo + up);
        }
    }
    /* H = U^T U by the kernel's one Cholesky (chol.c): a pivot must exceed
     * OGK_QP_PIVOT_TOL H_kk */
    st = ogk_i_chol_upper(U, H, n, &rule);
    if ((st == OGK_OK) && (asym > (OGK_QP_SYM_TOL * hmax))) {
        st = OGK_E_NOT_POSDEF;
    }
    return st;
}

void ogk_i_qp_inverse_lower(const ogk_real_t *U, size_t n, ogk_real_t *Li)
{
    size_t c;
    size_t i;
    for (i = 0u; i < (n * n); ++i) {
        Li[i] = OGK_R(0.0);
    }
    for (i = 0u; i < n; ++i) {
        ogk_real_t *row = &Li[i * n];
        const ogk_real_t inv = OGK_R(1.0) / U[(i * n) + i];
        size_t k = 0u;
        /* four rows k of Li per pass over row i; Li(k, c) = 0 for c > k, so
         * the block's columns 0..k+3 take the same values as one row at a
         * time. L(i, k) = U(k, i). */
        for (; (k + 4u) <= i; k += 4u) {
            const ogk_real_t *r0 = &Li[k * n];
            const ogk_real_t *r1 = &r0[n];
            const ogk_real_t *r2 = &r1[n];
            const ogk_real_t *r3 = &r2[n];
            const ogk_real_t l0 = U[(k * n) + i];
            const ogk_real_t l1 = U[((k + 1u) * n) + i];
            const ogk_real_t l2 = U[((k + 2u) * n) + i];
            const ogk_real_t l3 = U[((k + 3u) * n) + i];
            /* columns 0..k+3 (an even count), two per step (one SIMD pair on SSE2) */
            for (c = 0u; c <= (k + 3u); c += 2u) {
                const ogk_real_t ra = (((row[c] - (l0 * r0[c])) - (l1 * r1[c])) - (l2 * r2[c])) - (l3 * r3[c]);
                const ogk_real_t rb = (((row[c + 1u] - (l0 * r0[c + 1u])) - (l1 * r1[c + 1u])) - (l2 * r2[c + 1u])) -
                                  (l3 * r3[c + 1u]);
                row[c] = ra;
                row[c + 1u] = rb;
            }
        }
        for (; k < i; ++k) {
            ogk_i_row_axpy_sub(row, U[(k * n) + i], &Li[k * n], k + 1u);
        }
        row[i] = OGK_R(1.0);
        for (c = 0u; c <= i; ++c) {
            row[c] *= inv;
        }
    }
}
