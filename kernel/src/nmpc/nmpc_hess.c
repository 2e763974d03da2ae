/* nmpc_hess.c -- the QP Hessian of the NMPC's SQP (nmpc_sqp.c): the exact
 * reduced Hessian of the Lagrangian and its regularisation, or the damped
 * BFGS approximation (docs/design/nmpc-flight.md, "Hessian").
 *
 * Exact: with L = J - y^T c(X_N, T) and the continuity X_{k+1} = F_k - d_k
 * condensed away, the Hessian of L in the QP unknowns v = (dU, dT) is
 *   sum_k Gt_k^T W_k Gt_k,  W_k = sum_i w_k,i d2F_k,i / d(X_k, U_k, U_k+1, T)2,
 * Gt_k = d(X_k, U_k, U_k+1, T)/dv (X_k's rows are the condensing's G_k), the
 * weights w_{N-1} = dJ/dX_N - dc/dX_N^T y, w_{k-1} = A_k^T w_k (the
 * continuity multipliers; J and c are linear). It need not be positive
 * definite: it is convexified along the normals of eq. (5) (H + rho A^T A
 * leaves the QP's solution unchanged on A v = b, the multipliers shift by
 * rho b), then shifted (H + delta I) when still not positive definite, and
 * *shifted says so (the SQP then takes the scaled identity instead). */
#include "nmpc_internal.h"
#include "../chol_internal.h"
#include "../ogk_checks.h"

#include <math.h>
#include <string.h>

#define NX ((size_t)OGK_NMPC_NX)
#define NC ((size_t)OGK_NMPC_NC)
#define NCOL OGK_I_NMPC_NCOL_Z
#define NDIR OGK_I_NMPC_NDIR_Z
#define MAXV OGK_I_NMPC_MAXV_Z

/* Convexification: rho from RHO_FIRST max|H_ii| / max|A_i|^2 up by
 * RHO_GROWTH, then a shift delta from DELTA_FIRST max|H_ii| up by
 * DELTA_GROWTH; a Cholesky pivot must exceed PIVOT_MIN max|H_ii|. */
#define RHO_FIRST OGK_R(1.0e-2)
#define RHO_GROWTH OGK_R(100.0)
#define RHO_TRIES 4u
#define DELTA_FIRST OGK_R(1.0e-8)
#define DELTA_GROWTH OGK_R(4.0)
#define DELTA_TRIES 24u
#define PIVOT_MIN OGK_R(1.0e-12)

void ogk_i_nmpc_hess_block(uint32_t nu, size_t ncol, size_t k, uint32_t nodes, /* NOLINT(bugprone-easily-swappable-parameters): internal, (nu, columns, interval, N) as nmpc_internal.h states; checked through the SQP tests */
                           const ogk_real_t *w_int, ogk_real_t *blk)
{
    /* h = T / N and t_start = t0 + k T / N: the T direction is
     * (e_h + k e_ts) / N (e_ts only when propagated) */
    const size_t col_h = NX + (2u * (size_t)nu);
    const size_t nb = col_h + 1u;
    const ogk_real_t kk = (ogk_real_t)k;
    const ogk_real_t inv_n = OGK_R(1.0) / (ogk_real_t)nodes;
    const bool with_ts = ncol > nb;
    ogk_real_t t_col[NCOL];
    /* ncol <= NCOL (ogk_i_nmpc_ncol): clamped once so the loop keeps a fixed bound */
    const size_t ncol_b = ogk_i_min_size(ncol, NCOL);
    size_t a;
    size_t b;

    (void)memset(t_col, 0, sizeof(t_col));
    for (a = 0u; a < ncol_b; ++a) {
        t_col[a] = w_int[(a * NCOL) + col_h];
        if (with_ts) {
            t_col[a] += kk * w_int[(a * NCOL) + col_h + 1u];
        }
        t_col[a] *= inv_n;
    }
    for (a = 0u; a < col_h; ++a) {
        for (b = 0u; b < col_h; ++b) {
            blk[(a * NDIR) + b] = w_int[(a * NCOL) + b];
        }
        blk[(a * NDIR) + col_h] = t_col[a];
        blk[(col_h * NDIR) + a] = t_col[a];
    }
    blk[(col_h * NDIR) + col_h] = (t_col[col_h] + (with_ts ? (kk * t_col[col_h + 1u]) : OGK_R(0.0))) * inv_n;
}

void ogk_i_nmpc_hess_add(ogk_real_t *hess, size_t nv, uint32_t nu, size_t k, /* NOLINT(bugprone-easily-swappable-parameters): internal, (H, its order, nu, interval) as nmpc_internal.h states; checked through the SQP tests */
                         const ogk_real_t *g, const ogk_real_t *blk, ogk_real_t *scratch) /* NOLINT(bugprone-easily-swappable-parameters): as above */
{
    /* Gt over the columns interval k can touch (U_0 .. U_{k+1}, then T):
     * five dense rows (G's) and unit rows for U_k, U_{k+1}, T */
    const size_t nb = NX + (2u * (size_t)nu) + 1u;
    const size_t na = ((k + 2u) * (size_t)nu) + 1u;
    const size_t c_u0 = k * (size_t)nu;
    const size_t c_u1 = (k + 1u) * (size_t)nu;
    ogk_real_t *gx = scratch;                /* 5 x na: G's rows */
    ogk_real_t *bm = &scratch[NDIR * MAXV];  /* nb x na: blk Gt */
    size_t a;
    size_t c;
    size_t x;
    size_t j;

    for (x = 0u; x < NX; ++x) {
        (void)memcpy(&gx[x * na], &g[x * nv], (na - 1u) * sizeof(ogk_real_t));
        gx[(x * na) + (na - 1u)] = g[(x * nv) + (nv - 1u)];
    }
    for (a = 0u; a < nb; ++a) {
        const ogk_real_t *brow = &blk[a * NDIR];
        ogk_real_t *bmrow = &bm[a * na];
        for (c = 0u; c < na; ++c) {
            bmrow[c] = (brow[0] * gx[c]) + (brow[1] * gx[na + c]) + (brow[2] * gx[(2u * na) + c])
                + (brow[3] * gx[(3u * na) + c]) + (brow[4] * gx[(4u * na) + c]);
        }
        for (j = 0u; j < (size_t)nu; ++j) {
            bmrow[c_u0 + j] += brow[NX + j];
            bmrow[c_u1 + j] += brow[NX + (size_t)nu + j];
        }
        bmrow[na - 1u] += brow[nb - 1u];
    }
    /* hess (upper triangle; the caller mirrors) += Gt^T bm */
    for (a = 0u; a < na; ++a) {
        size_t ra = a;
        ogk_real_t *hrow;
        if (a == (na - 1u)) {
            ra = nv - 1u; /* the T column of Gt is v's last */
        }
        hrow = &hess[ra * nv];
        for (c = a; c < (na - 1u); ++c) {
            hrow[c] += (gx[a] * bm[c]) + (gx[na + a] * bm[na + c]) + (gx[(2u * na) + a] * bm[(2u * na) + c])
                + (gx[(3u * na) + a] * bm[(3u * na) + c]) + (gx[(4u * na) + a] * bm[(4u * na) + c]);
        }
        hrow[nv - 1u] += (gx[a] * bm[na - 1u]) + (gx[na + a] * bm[(2u * na) - 1u])
            + (gx[(2u * na) + a] * bm[(3u * na) - 1u]) + (gx[(3u * na) + a] * bm[(4u * na) - 1u])
            + (gx[(4u * na) + a] * bm[(5u * na) - 1u]);
    }
    /* the unit rows of Gt: row U_k,j adds bm's row NX + j to hess's row c_u0 + j (upper part) */
    for (j = 0u; j < (size_t)nu; ++j) {
        const ogk_real_t *b0 = &bm[(NX + j) * na];
        const ogk_real_t *b1 = &bm[(NX + (size_t)nu + j) * na];
        for (c = c_u0 + j; c < (na - 1u); ++c) {
            hess[((c_u0 + j) * nv) + c] += b0[c];
        }
        hess[((c_u0 + j) * nv) + (nv - 1u)] += b0[na - 1u];
        for (c = c_u1 + j; c < (na - 1u); ++c) {
            hess[((c_u1 + j) * nv) + c] += b1[c];
        }
        hess[((c_u1 + j) * nv) + (nv - 1u)] += b1[na - 1u];
    }
    hess[((nv - 1u) * nv) + (nv - 1u)] += bm[((nb - 1u) * na) + (na - 1u)];
}

void ogk_i_nmpc_hess_mirror(ogk_real_t *hess, size_t nv)
{
    size_t i;
    size_t j;
    for (i = 0u; i < nv; ++i) {
        for (j = 0u; j < i; ++j) {
            hess[(i * nv) + j] = hess[(j * nv) + i];
        }
    }
}

/* True when the n x n matrix a factors by the kernel's one Cholesky
 * (chol.c) with every pivot above pivot_min; its lower triangle is read (a
 * need not be symmetric to the bit), as the upper triangle of work. */
static bool cholesky_ok(const ogk_real_t *a, size_t n, ogk_real_t pivot_min, ogk_real_t *work) /* NOLINT(bugprone-easily-swappable-parameters): internal helper, (matrix, order, pivot floor, scratch); its only caller is try_shift */
{
    ogk_i_chol_rule_t rule;
    size_t i;
    size_t j;
    for (i = 0u; i < n; ++i) {
        for (j = 0u; j <= i; ++j) {
            work[(j * n) + i] = a[(i * n) + j];
        }
    }
    rule.rel = OGK_R(0.0);
    rule.floor = pivot_min;
    rule.bounded = false;
    rule.divide = true;
    return ogk_i_chol_upper(work, a, n, &rule) == OGK_OK;
}

/* try := hess + rho A^T A + delta I; true when it factors. */
static bool try_shift(const ogk_real_t *hess, size_t nv, const ogk_real_t *a_eq, ogk_real_t rho, /* NOLINT(bugprone-easily-swappable-parameters): internal helper, (H, order, A, rho, delta) in the formula's order; its only caller is ogk_i_nmpc_hess_convexify */
                      ogk_real_t delta, ogk_real_t pivot_min, ogk_real_t *out, ogk_real_t *work)
{
    size_t i;
    size_t j;
    size_t r;
    for (i = 0u; i < nv; ++i) {
        for (j = 0u; j < nv; ++j) {
            ogk_real_t acc = hess[(i * nv) + j];
            for (r = 0u; r < NC; ++r) {
                acc += rho * a_eq[(r * nv) + i] * a_eq[(r * nv) + j];
            }
            out[(i * nv) + j] = acc + ((i == j) ? delta : OGK_R(0.0));
        }
    }
    return cholesky_ok(out, nv, pivot_min, work);
}

ogk_real_t ogk_i_nmpc_hess_convexify(ogk_real_t *hess, size_t nv, const ogk_real_t *a_eq, /* NOLINT(bugprone-easily-swappable-parameters): internal, (H, order, A_eq, fallback scale, last rho) as nmpc_internal.h states; checked through the SQP tests */
                                 ogk_real_t fallback, ogk_real_t rho_hint, ogk_real_t *out, ogk_real_t *work, /* NOLINT(bugprone-easily-swappable-parameters): as above */
                                 bool *shifted)
{
    ogk_real_t scale = OGK_R(0.0);
    ogk_real_t a_norm = OGK_R(0.0);
    ogk_real_t rho;
    ogk_real_t rho_used = OGK_R(0.0);
    bool ok;
    uint32_t n;
    size_t i;
    size_t r;

    for (i = 0u; i < nv; ++i) {
        scale = (OGK_FABS(hess[(i * nv) + i]) > scale) ? OGK_FABS(hess[(i * nv) + i]) : scale;
    }
    for (r = 0u; r < NC; ++r) {
        ogk_real_t acc = OGK_R(0.0);
        for (i = 0u; i < nv; ++i) {
            acc += a_eq[(r * nv) + i] * a_eq[(r * nv) + i];
        }
        a_norm = (acc > a_norm) ? acc : a_norm;
    }
    /* rho A^T A changes neither the QP's step nor (once corrected) its
     * multipliers: it is always added, and most Hessians factor with the
     * first rho (measured: the benchmark's re-solve never needs more) */
    ok = false;
    *shifted = false;
    rho = (a_norm > OGK_REAL_TINY) ? ((RHO_FIRST * scale) / a_norm) : OGK_R(0.0);
    /* the last iteration's rho usually fits again: start there */
    rho = (rho_hint > rho) ? rho_hint : rho;
    for (n = 0u; (n < RHO_TRIES) && !ok; ++n) {
        if ((rho > OGK_R(0.0)) && isfinite(scale) && (scale > OGK_REAL_TINY)) {
            rho_used = rho;
            ok = try_shift(hess, nv, a_eq, rho, OGK_R(0.0), PIVOT_MIN * scale, out, work);
            rho *= RHO_GROWTH;
        }
    }
    if (!ok) {
        /* not convex on the null space of eq. (5) either: the first rho and
         * a growing shift */
        ogk_real_t delta = DELTA_FIRST * scale;
        rho_used = (a_norm > OGK_REAL_TINY) ? ((RHO_FIRST * scale) / a_norm) : OGK_R(0.0);
        *shifted = true;
        for (n = 0u; (n < DELTA_TRIES) && !ok; ++n) {
            if (isfinite(scale) && (scale > OGK_REAL_TINY)) {
                ok = try_shift(hess, nv, a_eq, rho_used, delta, PIVOT_MIN * scale, out, work);
                delta *= DELTA_GROWTH;
            }
        }
    }
    if (!ok) {
        /* nothing factored (a non-finite entry): the scaled identity */
        rho_used = OGK_R(0.0);
        ogk_i_nmpc_identity(out, nv, fallback);
    }
    (void)memcpy(hess, out, nv * nv * sizeof(ogk_real_t));
    return rho_used;
}

void ogk_i_nmpc_hess_reshift(ogk_real_t *hess, size_t nv, const ogk_real_t *a_old, const ogk_real_t *a_new, /* NOLINT(bugprone-easily-swappable-parameters): internal, (H, order, old rows, new rows, rho) in the formula's order; its only caller is ogk_i_nmpc_sqp */
                             ogk_real_t rho)
{
    /* H0 + rho A_old^T A_old -> H0 + rho A_new^T A_new: the QP's step on
     * A_new v = b and its multipliers' correction (y - rho b) stay exact
     * for the held H0 */
    size_t i;
    size_t j;
    size_t r;
    for (i = 0u; i < nv; ++i) {
        for (j = 0u; j < nv; ++j) {
            ogk_real_t acc = OGK_R(0.0);
            for (r = 0u; r < NC; ++r) {
                acc += (a_new[(r * nv) + i] * a_new[(r * nv) + j]) - (a_old[(r * nv) + i] * a_old[(r * nv) + j]);
            }
            hess[(i * nv) + j] += rho * acc;
        }
    }
}

/* Damped BFGS update of H with the step s and the gradient change y. */
void ogk_i_nmpc_bfgs_update(ogk_real_t *hess, size_t nv, const ogk_real_t *s, ogk_real_t *y, bool first)
{
    ogk_real_t hs[MAXV];
    ogk_real_t s_hs = OGK_R(0.0);
    ogk_real_t s_y = OGK_R(0.0);
    ogk_real_t y_y = OGK_R(0.0);
    size_t i;
    size_t j;

    for (i = 0u; i < nv; ++i) {
        s_y += s[i] * y[i];
        y_y += y[i] * y[i];
    }
    if (first && (s_y > OGK_R(0.0)) && (y_y > OGK_R(0.0))) {
        /* Shanno-Phua scaling of the initial matrix */
        const ogk_real_t scale = y_y / s_y;
        for (i = 0u; i < nv; ++i) {
            for (j = 0u; j < nv; ++j) {
                hess[(i * nv) + j] = (i == j) ? scale : OGK_R(0.0);
            }
        }
    }
    for (i = 0u; i < nv; ++i) {
        ogk_real_t acc = OGK_R(0.0);
        for (j = 0u; j < nv; ++j) {
            acc += hess[(i * nv) + j] * s[j];
        }
        hs[i] = acc;
        s_hs += s[i] * acc;
    }
    if (s_hs > OGK_REAL_TINY) {
        if (s_y < (OGK_I_NMPC_POWELL_DAMP * s_hs)) {
            const ogk_real_t theta = (OGK_R(1.0) - OGK_I_NMPC_POWELL_DAMP) * s_hs / (s_hs - s_y);
            s_y = OGK_R(0.0);
            for (i = 0u; i < nv; ++i) {
                y[i] = (theta * y[i]) + ((OGK_R(1.0) - theta) * hs[i]);
                s_y += s[i] * y[i];
            }
        }
        if (s_y > OGK_R(0.0)) {
            for (i = 0u; i < nv; ++i) {
                for (j = 0u; j < nv; ++j) {
                    hess[(i * nv) + j] += ((y[i] * y[j]) / s_y) - ((hs[i] * hs[j]) / s_hs);
                }
            }
        }
    }
}

void ogk_i_nmpc_identity(ogk_real_t *hess, size_t nv, ogk_real_t scale)
{
    size_t i;
    size_t j;
    for (i = 0u; i < nv; ++i) {
        for (j = 0u; j < nv; ++j) {
            hess[(i * nv) + j] = (i == j) ? scale : OGK_R(0.0);
        }
    }
}
