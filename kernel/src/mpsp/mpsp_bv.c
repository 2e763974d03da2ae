/* mpsp_bv.c -- B_v of eq. (40) from the sensitivity samples of the backward
 * sweep (mpsp_sensitivity.c): the blocked product sum_b bU(t_b) h(t_b)^T and
 * the unpacking into the row-major 7 x n_weights matrix. Layout and costs:
 * docs/design/mpsp.md, sections 3 and 8. */
#include "mpsp_internal.h"

#define NY ((size_t)OGK_MPSP_NY)
/* Coefficients of one sensitivity sample: bU(t), row r, component c at r * 3 + c. */
#define NYU (NY * 3u)
#define MB OGK_MPSP_MAX_BASIS
/* h_q of sample b at hb[b * HR + q * HL] (OGK_MPSP_H_LANES entries each). */
#define HL ((size_t)OGK_MPSP_H_LANES)
#define HR (MB * HL)

/* acc[q + i][j] += sum_b h_b[q + i] c_b[j], i < 3, for one coefficient j:
 * the column that the 4-wide tiles of ogk_i_mpsp_bv_block_product leave over
 * (NYU = 21). */
static void block_cols_3x1(ogk_real_t *acc, size_t q, size_t j, const ogk_real_t *hb, const ogk_real_t *cb, /* NOLINT(bugprone-easily-swappable-parameters): order of eqs. (16)/(25); FD-checked by the unit tests */
                           size_t n)
{
    const size_t i0 = (q * NYU) + j;
    ogk_real_t a0 = acc[i0];
    ogk_real_t a1 = acc[i0 + NYU];
    ogk_real_t a2 = acc[i0 + (2u * NYU)];
    size_t b;

    for (b = 0u; b < n; ++b) {
        const ogk_real_t c0 = cb[(b * NYU) + j];
        a0 += hb[(b * HR) + (q * HL)] * c0;
        a1 += hb[(b * HR) + ((q + 1u) * HL)] * c0;
        a2 += hb[(b * HR) + ((q + 2u) * HL)] * c0;
    }
    acc[i0] = a0;
    acc[i0 + NYU] = a1;
    acc[i0 + (2u * NYU)] = a2;
}

#if defined(__SSE2__)
/* acc[q + i][j + p] += sum_b h_b[q + i] c_b[j + p], i < 3, p < 6: 18
 * accumulators, the coefficient pairs (j + 2 m, j + 2 m + 1) adjacent in acc
 * and in cb and h_b[q + i] held twice in hb, so that gcc -O2 on x86-64 adds
 * each pair with one SSE2 multiply and add (SLP) and reads every operand as a
 * pair: 18 multiply-adds for 6 loads per sample. */
static void tile_3x6(ogk_real_t *acc, size_t q, size_t j, const ogk_real_t *hb, const ogk_real_t *cb, /* NOLINT(bugprone-easily-swappable-parameters): order of eqs. (16)/(25); FD-checked by the unit tests */
                     size_t n)
{
    const size_t i0 = (q * NYU) + j;
    const size_t i1 = i0 + NYU;
    const size_t i2 = i1 + NYU;
    ogk_real_t a00 = acc[i0];
    ogk_real_t a01 = acc[i0 + 1u];
    ogk_real_t a02 = acc[i0 + 2u];
    ogk_real_t a03 = acc[i0 + 3u];
    ogk_real_t a04 = acc[i0 + 4u];
    ogk_real_t a05 = acc[i0 + 5u];
    ogk_real_t a10 = acc[i1];
    ogk_real_t a11 = acc[i1 + 1u];
    ogk_real_t a12 = acc[i1 + 2u];
    ogk_real_t a13 = acc[i1 + 3u];
    ogk_real_t a14 = acc[i1 + 4u];
    ogk_real_t a15 = acc[i1 + 5u];
    ogk_real_t a20 = acc[i2];
    ogk_real_t a21 = acc[i2 + 1u];
    ogk_real_t a22 = acc[i2 + 2u];
    ogk_real_t a23 = acc[i2 + 3u];
    ogk_real_t a24 = acc[i2 + 4u];
    ogk_real_t a25 = acc[i2 + 5u];
    size_t b;

    for (b = 0u; b < n; ++b) {
        const ogk_real_t *c = &cb[(b * NYU) + j];
        const ogk_real_t *h = &hb[(b * HR) + (q * HL)];
        a00 += h[0] * c[0];
        a01 += h[1] * c[1];
        a02 += h[0] * c[2];
        a03 += h[1] * c[3];
        a04 += h[0] * c[4];
        a05 += h[1] * c[5];
        a10 += h[2] * c[0];
        a11 += h[3] * c[1];
        a12 += h[2] * c[2];
        a13 += h[3] * c[3];
        a14 += h[2] * c[4];
        a15 += h[3] * c[5];
        a20 += h[4] * c[0];
        a21 += h[5] * c[1];
        a22 += h[4] * c[2];
        a23 += h[5] * c[3];
        a24 += h[4] * c[4];
        a25 += h[5] * c[5];
    }
    acc[i0] = a00;
    acc[i0 + 1u] = a01;
    acc[i0 + 2u] = a02;
    acc[i0 + 3u] = a03;
    acc[i0 + 4u] = a04;
    acc[i0 + 5u] = a05;
    acc[i1] = a10;
    acc[i1 + 1u] = a11;
    acc[i1 + 2u] = a12;
    acc[i1 + 3u] = a13;
    acc[i1 + 4u] = a14;
    acc[i1 + 5u] = a15;
    acc[i2] = a20;
    acc[i2 + 1u] = a21;
    acc[i2 + 2u] = a22;
    acc[i2 + 3u] = a23;
    acc[i2 + 4u] = a24;
    acc[i2 + 5u] = a25;
}

/* tile_3x6 for one coefficient pair (j, j + 1). */
static void tile_3x2(ogk_real_t *acc, size_t q, size_t j, const ogk_real_t *hb, const ogk_real_t *cb, /* NOLINT(bugprone-easily-swappable-parameters): order of eqs. (16)/(25); FD-checked by the unit tests */
                     size_t n)
{
    const size_t i0 = (q * NYU) + j;
    const size_t i1 = i0 + NYU;
    const size_t i2 = i1 + NYU;
    ogk_real_t a00 = acc[i0];
    ogk_real_t a01 = acc[i0 + 1u];
    ogk_real_t a10 = acc[i1];
    ogk_real_t a11 = acc[i1 + 1u];
    ogk_real_t a20 = acc[i2];
    ogk_real_t a21 = acc[i2 + 1u];
    size_t b;

    for (b = 0u; b < n; ++b) {
        const ogk_real_t *c = &cb[(b * NYU) + j];
        const ogk_real_t *h = &hb[(b * HR) + (q * HL)];
        a00 += h[0] * c[0];
        a01 += h[1] * c[1];
        a10 += h[2] * c[0];
        a11 += h[3] * c[1];
        a20 += h[4] * c[0];
        a21 += h[5] * c[1];
    }
    acc[i0] = a00;
    acc[i0 + 1u] = a01;
    acc[i1] = a10;
    acc[i1 + 1u] = a11;
    acc[i2] = a20;
    acc[i2 + 1u] = a21;
}

/* acc[q][j] += sum_b h_b[q] c_b[j], j < NYU, for one basis function q (the
 * one the 3-row tiles leave over): 10 coefficient pairs and a column, each
 * pair with one SSE2 multiply and add per sample (h_q held twice); the
 * samples in the order b = 0, 1, ..., as every tile: the same numbers as the
 * one-lane loop of the other targets. */
static void tile_1x21(ogk_real_t *acc, size_t q, const ogk_real_t *hb, const ogk_real_t *cb, size_t n) /* NOLINT(bugprone-easily-swappable-parameters): order of eqs. (16)/(25); FD-checked by the unit tests */
{
    ogk_real_t *ar = &acc[q * NYU];
    ogk_real_t a00 = ar[0];
    ogk_real_t a01 = ar[1];
    ogk_real_t a02 = ar[2];
    ogk_real_t a03 = ar[3];
    ogk_real_t a04 = ar[4];
    ogk_real_t a05 = ar[5];
    ogk_real_t a06 = ar[6];
    ogk_real_t a07 = ar[7];
    ogk_real_t a08 = ar[8];
    ogk_real_t a09 = ar[9];
    ogk_real_t a10 = ar[10];
    ogk_real_t a11 = ar[11];
    ogk_real_t a12 = ar[12];
    ogk_real_t a13 = ar[13];
    ogk_real_t a14 = ar[14];
    ogk_real_t a15 = ar[15];
    ogk_real_t a16 = ar[16];
    ogk_real_t a17 = ar[17];
    ogk_real_t a18 = ar[18];
    ogk_real_t a19 = ar[19];
    ogk_real_t a20 = ar[20];
    size_t b;

    for (b = 0u; b < n; ++b) {
        const ogk_real_t *c = &cb[b * NYU];
        const ogk_real_t *h = &hb[(b * HR) + (q * HL)];
        a00 += h[0] * c[0];
        a01 += h[1] * c[1];
        a02 += h[0] * c[2];
        a03 += h[1] * c[3];
        a04 += h[0] * c[4];
        a05 += h[1] * c[5];
        a06 += h[0] * c[6];
        a07 += h[1] * c[7];
        a08 += h[0] * c[8];
        a09 += h[1] * c[9];
        a10 += h[0] * c[10];
        a11 += h[1] * c[11];
        a12 += h[0] * c[12];
        a13 += h[1] * c[13];
        a14 += h[0] * c[14];
        a15 += h[1] * c[15];
        a16 += h[0] * c[16];
        a17 += h[1] * c[17];
        a18 += h[0] * c[18];
        a19 += h[1] * c[19];
        a20 += h[0] * c[20];
    }
    ar[0] = a00;
    ar[1] = a01;
    ar[2] = a02;
    ar[3] = a03;
    ar[4] = a04;
    ar[5] = a05;
    ar[6] = a06;
    ar[7] = a07;
    ar[8] = a08;
    ar[9] = a09;
    ar[10] = a10;
    ar[11] = a11;
    ar[12] = a12;
    ar[13] = a13;
    ar[14] = a14;
    ar[15] = a15;
    ar[16] = a16;
    ar[17] = a17;
    ar[18] = a18;
    ar[19] = a19;
    ar[20] = a20;
}

/* acc[q][j] += sum_b h_b[q] c_b[j] over the n samples held (eq. 40 with
 * dU = P dW: B_v += bU h^T per sample), j < NYU: register tiles of 3 basis
 * functions x 6 coefficients (tile_3x6), the 3 coefficients left over (NYU =
 * 21) as a pair and a column. Every accumulator adds the samples in the
 * order b = 0, 1, ..., as the one-lane tiles below: the same numbers. */
void ogk_i_mpsp_bv_block_product(ogk_real_t *acc, size_t n_basis, const ogk_real_t *hb, const ogk_real_t *cb, /* NOLINT(bugprone-easily-swappable-parameters): order of eqs. (16)/(25); FD-checked by the unit tests */
                           size_t n)
{
    size_t q;
    size_t j;
    size_t b;

    for (q = 0u; (q + 3u) <= n_basis; q += 3u) {
        for (j = 0u; (j + 6u) <= NYU; j += 6u) {
            tile_3x6(acc, q, j, hb, cb, n);
        }
        tile_3x2(acc, q, j, hb, cb, n); /* NYU = 21: coefficients 18, 19 */
        block_cols_3x1(acc, q, j + 2u, hb, cb, n); /* and 20 */
    }
    if (q < n_basis) { /* a basis function left over (2 n + 1 is odd) */
        tile_1x21(acc, q, hb, cb, n);
        q += 1u;
    }
#else
/* acc[q][j] += sum_b h_b[q] c_b[j] over the n samples held (eq. 40 with
 * dU = P dW: B_v += bU h^T per sample), j < NYU. Register tiles of 3 basis
 * functions x 4 coefficients: 12 multiply-adds for 7 loads per sample, and
 * the coefficient pairs (j, j + 1), (j + 2, j + 3) are adjacent in acc and in
 * cb, so gcc -O2 on x86-64 adds them two per SSE2 instruction (SLP). */
void ogk_i_mpsp_bv_block_product(ogk_real_t *acc, size_t n_basis, const ogk_real_t *hb, const ogk_real_t *cb, /* NOLINT(bugprone-easily-swappable-parameters): order of eqs. (16)/(25); FD-checked by the unit tests */
                           size_t n)
{
    size_t q;
    size_t j;
    size_t b;

    for (q = 0u; (q + 3u) <= n_basis; q += 3u) {
        for (j = 0u; (j + 4u) <= NYU; j += 4u) {
            const size_t i0 = (q * NYU) + j;
            const size_t i1 = i0 + NYU;
            const size_t i2 = i1 + NYU;
            ogk_real_t a00 = acc[i0];
            ogk_real_t a01 = acc[i0 + 1u];
            ogk_real_t a02 = acc[i0 + 2u];
            ogk_real_t a03 = acc[i0 + 3u];
            ogk_real_t a10 = acc[i1];
            ogk_real_t a11 = acc[i1 + 1u];
            ogk_real_t a12 = acc[i1 + 2u];
            ogk_real_t a13 = acc[i1 + 3u];
            ogk_real_t a20 = acc[i2];
            ogk_real_t a21 = acc[i2 + 1u];
            ogk_real_t a22 = acc[i2 + 2u];
            ogk_real_t a23 = acc[i2 + 3u];
            for (b = 0u; b < n; ++b) {
                const ogk_real_t *c = &cb[(b * NYU) + j];
                const ogk_real_t *h = &hb[(b * HR) + q];
                const ogk_real_t h0 = h[0];
                const ogk_real_t h1 = h[1];
                const ogk_real_t h2 = h[2];
                const ogk_real_t c0 = c[0];
                const ogk_real_t c1 = c[1];
                const ogk_real_t c2 = c[2];
                const ogk_real_t c3 = c[3];
                a00 += h0 * c0;
                a01 += h0 * c1;
                a02 += h0 * c2;
                a03 += h0 * c3;
                a10 += h1 * c0;
                a11 += h1 * c1;
                a12 += h1 * c2;
                a13 += h1 * c3;
                a20 += h2 * c0;
                a21 += h2 * c1;
                a22 += h2 * c2;
                a23 += h2 * c3;
            }
            acc[i0] = a00;
            acc[i0 + 1u] = a01;
            acc[i0 + 2u] = a02;
            acc[i0 + 3u] = a03;
            acc[i1] = a10;
            acc[i1 + 1u] = a11;
            acc[i1 + 2u] = a12;
            acc[i1 + 3u] = a13;
            acc[i2] = a20;
            acc[i2 + 1u] = a21;
            acc[i2 + 2u] = a22;
            acc[i2 + 3u] = a23;
        }
        for (; j < NYU; ++j) { /* NYU = 21: one column left over */
            block_cols_3x1(acc, q, j, hb, cb, n);
        }
    }
#endif
    for (; q < n_basis; ++q) { /* the basis functions left over */
        for (j = 0u; j < NYU; j += 3u) {
            ogk_real_t a0 = acc[(q * NYU) + j];
            ogk_real_t a1 = acc[(q * NYU) + j + 1u];
            ogk_real_t a2 = acc[(q * NYU) + j + 2u];
            for (b = 0u; b < n; ++b) {
                const ogk_real_t hq = hb[(b * HR) + (q * HL)];
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
void ogk_i_mpsp_bv_unpack(const ogk_real_t *acc, size_t n_basis, ogk_real_t *out) /* NOLINT(bugprone-easily-swappable-parameters): order of eqs. (16)/(25); FD-checked by the unit tests */
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
