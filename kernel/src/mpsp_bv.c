/* mpsp_bv.c -- B_v of eq. (40) from the sensitivity samples of the backward
 * sweep (mpsp_sensitivity.c): the blocked product sum_b bU(t_b) h(t_b)^T and
 * the unpacking into the row-major 7 x n_weights matrix. Layout and costs:
 * docs/mpsp.md, sections 3 and 8. */
#include "mpsp_internal.h"

#define NY ((size_t)OGK_MPSP_NY)
/* Coefficients of one sensitivity sample: bU(t), row r, component c at r * 3 + c. */
#define NYU (NY * 3u)
#define MB OGK_MPSP_MAX_BASIS

/* acc[q][j] += sum_b h_b[q] c_b[j] over the n samples held (eq. 40 with
 * dU = P dW: B_v += bU h^T per sample), j < NYU. Register tiles of 3 basis
 * functions x 3 coefficients, two samples per pass: each product costs about
 * one multiply-add and two thirds of a load, where a product added straight
 * into acc costs a load, a multiply-add and a store. */
void mpsp_bv_block_product(double *acc, size_t n_basis, const double *hb, const double *cb, /* NOLINT(bugprone-easily-swappable-parameters): order of eqs. (16)/(25); FD-checked by the unit tests */
                           size_t n)
{
    size_t q;
    size_t j;
    size_t b;

    for (q = 0u; (q + 3u) <= n_basis; q += 3u) {
        for (j = 0u; j < NYU; j += 3u) {
            const size_t i0 = (q * NYU) + j;
            const size_t i1 = i0 + NYU;
            const size_t i2 = i1 + NYU;
            double a00 = acc[i0];
            double a01 = acc[i0 + 1u];
            double a02 = acc[i0 + 2u];
            double a10 = acc[i1];
            double a11 = acc[i1 + 1u];
            double a12 = acc[i1 + 2u];
            double a20 = acc[i2];
            double a21 = acc[i2 + 1u];
            double a22 = acc[i2 + 2u];
            double h0;
            double h1;
            double h2;
            double c0;
            double c1;
            double c2;
            for (b = 0u; (b + 1u) < n; b += 2u) { /* two samples per pass */
                h0 = hb[(b * MB) + q];
                h1 = hb[(b * MB) + q + 1u];
                h2 = hb[(b * MB) + q + 2u];
                c0 = cb[(b * NYU) + j];
                c1 = cb[(b * NYU) + j + 1u];
                c2 = cb[(b * NYU) + j + 2u];
                a00 += h0 * c0;
                a01 += h0 * c1;
                a02 += h0 * c2;
                a10 += h1 * c0;
                a11 += h1 * c1;
                a12 += h1 * c2;
                a20 += h2 * c0;
                a21 += h2 * c1;
                a22 += h2 * c2;
                h0 = hb[((b + 1u) * MB) + q];
                h1 = hb[((b + 1u) * MB) + q + 1u];
                h2 = hb[((b + 1u) * MB) + q + 2u];
                c0 = cb[((b + 1u) * NYU) + j];
                c1 = cb[((b + 1u) * NYU) + j + 1u];
                c2 = cb[((b + 1u) * NYU) + j + 2u];
                a00 += h0 * c0;
                a01 += h0 * c1;
                a02 += h0 * c2;
                a10 += h1 * c0;
                a11 += h1 * c1;
                a12 += h1 * c2;
                a20 += h2 * c0;
                a21 += h2 * c1;
                a22 += h2 * c2;
            }
            if (b < n) {
                h0 = hb[(b * MB) + q];
                h1 = hb[(b * MB) + q + 1u];
                h2 = hb[(b * MB) + q + 2u];
                c0 = cb[(b * NYU) + j];
                c1 = cb[(b * NYU) + j + 1u];
                c2 = cb[(b * NYU) + j + 2u];
                a00 += h0 * c0;
                a01 += h0 * c1;
                a02 += h0 * c2;
                a10 += h1 * c0;
                a11 += h1 * c1;
                a12 += h1 * c2;
                a20 += h2 * c0;
                a21 += h2 * c1;
                a22 += h2 * c2;
            }
            acc[i0] = a00;
            acc[i0 + 1u] = a01;
            acc[i0 + 2u] = a02;
            acc[i1] = a10;
            acc[i1 + 1u] = a11;
            acc[i1 + 2u] = a12;
            acc[i2] = a20;
            acc[i2 + 1u] = a21;
            acc[i2 + 2u] = a22;
        }
    }
    for (; q < n_basis; ++q) { /* the basis functions left over (2 n + 1 is odd) */
        for (j = 0u; j < NYU; j += 3u) {
            double a0 = acc[(q * NYU) + j];
            double a1 = acc[(q * NYU) + j + 1u];
            double a2 = acc[(q * NYU) + j + 2u];
            for (b = 0u; b < n; ++b) {
                const double hq = hb[(b * MB) + q];
                const size_t ic = (b * NYU) + j;
                a0 += hq * cb[ic];
                a1 += hq * cb[ic + 1u];
                a2 += hq * cb[ic + 2u];
            }
            acc[(q * NYU) + j] = a0;
            acc[(q * NYU) + j + 1u] = a1;
            acc[(q * NYU) + j + 2u] = a2;
        }
    }
}

/* out[r][c n_basis + q] = acc[q][r * 3 + c]: B_v row-major, NY x 3 n_basis. */
void mpsp_bv_unpack(const double *acc, size_t n_basis, double *out) /* NOLINT(bugprone-easily-swappable-parameters): order of eqs. (16)/(25); FD-checked by the unit tests */
{
    const size_t n_weights = 3u * n_basis;
    size_t r;
    size_t c;
    size_t q;
    for (r = 0u; r < NY; ++r) {
        for (c = 0u; c < 3u; ++c) {
            for (q = 0u; q < n_basis; ++q) {
                out[(r * n_weights) + (c * n_basis) + q] = acc[(q * NYU) + (r * 3u) + c];
            }
        }
    }
}
