/* nmpc_shoot_hess.c -- second derivatives of one multiple-shooting interval
 * (nmpc_shoot.c), weighted by the continuity multipliers: the exact SQP
 * Hessian's per-interval block W = sum_i w_i d2F_i/dp2,
 * p = (X_k, U_k, U_{k+1}, h[, t_start]).
 *
 * Forward over adjoint: the adjoint of w . F runs backwards through the RK4
 * recursion recorded by the forward sweep (its stage states, Jacobians and
 * the sensitivities S, K of the forward sweep), and every nonlinear operation
 * adds (its output's adjoint) x (its second derivative) applied to its
 * inputs' forward sensitivities:
 *   - a stage k_j = f(z_j), z_j = (y_j, u_j, t_j): Z_j^T (sum_i kbar_j,i
 *     d2f_i/dz2) Z_j, Z_j = dz_j/dp (u_j and t_j are linear in p);
 *   - the products of h with a stage derivative, y_{j+1} = x_n + c_{j+1}
 *     (h / M) k_j and x_{n+1} = x_n + (h / 6M) sum_j b_j k_j: their cross
 *     terms in h and p.
 * The adjoints: kbar_j = (h b_j / 6M) lambda_{n+1} + (c_{j+1} h / M)
 * ybar_{j+1}, ybar_j = f_x(z_j)^T kbar_j, lambda_n = lambda_{n+1}
 * + sum_j ybar_j, lambda_M = w. Checked against central differences of
 * w . dF/dp (test_nmpc.c). */
#include "nmpc_internal.h"
#include "../rk4_internal.h"

#include <stdbool.h>
#include <string.h>

#define NX ((size_t)OGK_NMPC_NX)
#define NCOL OGK_I_NMPC_NCOL_Z
#define NZ OGK_I_NMPC_NZ_Z

/* The column loops below go by pairs (c, c + 1) over ncol rounded up to
 * even (ncol_e; the row stride NCOL is even and the tape's padding column is
 * 0): every array they write is a local of ogk_i_nmpc_shoot_hess or its
 * output, and the helpers are inlined there, so gcc -O2 computes each pair
 * with one packed operation on x86-64, the arithmetic of each entry
 * unchanged. (The triangle's rows, 1 to ncol entries long, stay scalar: by
 * pairs they cost more, x86-64 and Cortex-M7 alike; docs/design/nmpc-flight.md 2d.) */

/* out = jx^T a over the Jacobian's structural nonzeros (13 of 25, those of
 * jx_column in nmpc_shoot.c; jx[2] = dr'/dv_r = 1). */
static void jx_transpose_times(const ogk_real_t *jx, const ogk_real_t *a, ogk_real_t *out)
{
    out[0] = (jx[5] * a[1]) + (jx[10] * a[2]) + (jx[15] * a[3]) + (jx[20] * a[4]);
    out[1] = (jx[11] * a[2]) + (jx[16] * a[3]);
    out[2] = a[0] + (jx[17] * a[3]);
    out[3] = (jx[8] * a[1]) + (jx[13] * a[2]) + (jx[18] * a[3]);
    out[4] = (jx[14] * a[2]) + (jx[19] * a[3]);
}

/* The cross term of a product of h with a stage derivative k (K = dk/dp):
 * hess[h][c] and hess[c][h] += scale (K^T a)_c. Every such term lands in
 * h's row and column, so they are summed in g_h over the interval and added
 * to the upper triangle once (the diagonal entry twice). */
static void add_h_cross(const ogk_real_t *k_sens, const ogk_real_t *a, ogk_real_t scale, /* NOLINT(bugprone-easily-swappable-parameters): internal helper, (K, adjoint, factor) in the order of the product; callers in this file */
                        size_t ncol_e, ogk_real_t *g_h)
{
    size_t c;
    for (c = 0u; c < ncol_e; c += 2u) {
        const size_t l = c + 1u;
        g_h[c] += scale * ((k_sens[c] * a[0]) + (k_sens[NCOL + c] * a[1]) + (k_sens[(2u * NCOL) + c] * a[2])
                           + (k_sens[(3u * NCOL) + c] * a[3]) + (k_sens[(4u * NCOL) + c] * a[4]));
        g_h[l] += scale * ((k_sens[l] * a[0]) + (k_sens[NCOL + l] * a[1]) + (k_sens[(2u * NCOL) + l] * a[2])
                           + (k_sens[(3u * NCOL) + l] * a[3]) + (k_sens[(4u * NCOL) + l] * a[4]));
    }
}

/* Column l of m_a = (hz Z)_a for the state arguments r, v_r, v_theta and m
 * (hz's structural nonzeros without theta, t and the controls). */
static inline void stage_m_column(const ogk_real_t *hz, const ogk_real_t *y_sens, size_t l, /* NOLINT(bugprone-easily-swappable-parameters): internal helper, its only caller is add_stage_curvature */
                                  ogk_real_t *m_r, ogk_real_t *m_vr, ogk_real_t *m_vt, ogk_real_t *m_m) /* NOLINT(bugprone-easily-swappable-parameters): as above */
{
    const ogk_real_t z_r = y_sens[(0u * NCOL) + l];
    const ogk_real_t z_vr = y_sens[(2u * NCOL) + l];
    const ogk_real_t z_vt = y_sens[(3u * NCOL) + l];
    const ogk_real_t z_m = y_sens[(4u * NCOL) + l];
    m_r[l] = (hz[(0u * NZ) + 0u] * z_r) + (hz[(0u * NZ) + 2u] * z_vr) + (hz[(0u * NZ) + 3u] * z_vt)
        + (hz[(0u * NZ) + 4u] * z_m);
    m_vr[l] = (hz[(0u * NZ) + 2u] * z_r) + (hz[(2u * NZ) + 3u] * z_vt);
    m_vt[l] = (hz[(0u * NZ) + 3u] * z_r) + (hz[(2u * NZ) + 3u] * z_vr) + (hz[(3u * NZ) + 3u] * z_vt);
    m_m[l] = (hz[(0u * NZ) + 4u] * z_r) + (hz[(4u * NZ) + 4u] * z_m);
}

/* hess (upper triangle) += Z^T hz Z for one stage. Z = dz/dp has the state
 * rows y_sens (5 x ncol, row stride NCOL), the control rows (1 - s) at U_k
 * and s at U_{k+1}, the time row s at h and 1 at t_start; hz is the upper
 * triangle of the model's Hessian (ogk_i_nmpc_rhs_hess), whose structural
 * nonzeros are written out: m_a = (hz Z)_a for each argument a, then
 * sum_a Z_a^T m_a (the mass row's terms only where that row is not 0 when
 * sparse_m). theta and t have curvature only with attracting bodies. */
static void add_stage_curvature(const ogk_real_t *hz, const ogk_real_t *y_sens, uint32_t nu, /* NOLINT(bugprone-easily-swappable-parameters): internal helper, (model Hessian, state sensitivities, nu) as in the stage; its only caller is ogk_i_nmpc_shoot_hess */
                                ogk_real_t s_frac, bool bodies, bool sparse_m, size_t ncol, /* NOLINT(bugprone-easily-swappable-parameters): as above */
                                ogk_real_t *hess)
{
    const size_t ncol_e = ncol + (ncol % 2u);
    const size_t i_a = NX;                        /* alpha's z index and U_k's column */
    const size_t i_t = NX + (size_t)nu;           /* t's z index */
    const size_t col_h = NX + (2u * (size_t)nu);
    const ogk_real_t *row_r = &y_sens[0u * NCOL];
    const ogk_real_t *row_th = &y_sens[1u * NCOL];
    const ogk_real_t *row_vr = &y_sens[2u * NCOL];
    const ogk_real_t *row_vt = &y_sens[3u * NCOL];
    const ogk_real_t *row_m = &y_sens[4u * NCOL];
    ogk_real_t m_r[NCOL];
    ogk_real_t m_vr[NCOL];
    ogk_real_t m_vt[NCOL];
    ogk_real_t m_m[NCOL];
    ogk_real_t m_ctl[OGK_NMPC_MAX_NU][NCOL];
    ogk_real_t m_th[NCOL];
    ogk_real_t m_t[NCOL];
    size_t a;
    size_t c;
    size_t j;

    (void)memset(m_r, 0, sizeof(m_r));
    (void)memset(m_m, 0, sizeof(m_m));
    (void)memset(m_ctl, 0, sizeof(m_ctl));
    /* by pairs up to ncol (the last pair of an odd ncol writes its padding
     * column too): m_vr, m_vt are read below only in the columns < ncol that
     * this loop sets, which the analyser follows with the bound ncol */
    for (c = 0u; c < ncol; c += 2u) {
        stage_m_column(hz, y_sens, c, m_r, m_vr, m_vt, m_m);
        stage_m_column(hz, y_sens, c + 1u, m_r, m_vr, m_vt, m_m);
    }
    for (j = 0u; j < (size_t)nu; ++j) {
        const ogk_real_t h_r = hz[(0u * NZ) + (i_a + j)];
        const ogk_real_t h_m = hz[(4u * NZ) + (i_a + j)];
        for (c = 0u; c < ncol_e; c += 2u) {
            m_ctl[j][c] = (h_r * row_r[c]) + (h_m * row_m[c]);
            m_ctl[j][c + 1u] = (h_r * row_r[c + 1u]) + (h_m * row_m[c + 1u]);
        }
    }
    /* the control rows' entries: (1 - s) in column NX + j, s in column NX + nu + j */
    for (j = 0u; j < (size_t)nu; ++j) {
        size_t l;
        const ogk_real_t lo = OGK_R(1.0) - s_frac;
        m_r[i_a + j] += hz[(0u * NZ) + (i_a + j)] * lo;
        m_r[i_a + (size_t)nu + j] += hz[(0u * NZ) + (i_a + j)] * s_frac;
        m_m[i_a + j] += hz[(4u * NZ) + (i_a + j)] * lo;
        m_m[i_a + (size_t)nu + j] += hz[(4u * NZ) + (i_a + j)] * s_frac;
        for (l = 0u; l < (size_t)nu; ++l) {
            const ogk_real_t h_jl = (j <= l) ? hz[((i_a + j) * NZ) + (i_a + l)] : hz[((i_a + l) * NZ) + (i_a + j)];
            m_ctl[j][i_a + l] += h_jl * lo;
            m_ctl[j][i_a + (size_t)nu + l] += h_jl * s_frac;
        }
    }
    if (bodies) {
        /* theta and t: hz(0,1), (1,1), (0,t), (1,t), (t,t) */
        for (c = 0u; c < ncol; ++c) {
            m_r[c] += hz[(0u * NZ) + 1u] * row_th[c];
            m_th[c] = (hz[(0u * NZ) + 1u] * row_r[c]) + (hz[(1u * NZ) + 1u] * row_th[c]);
            m_t[c] = (hz[(0u * NZ) + i_t] * row_r[c]) + (hz[(1u * NZ) + i_t] * row_th[c]);
        }
        m_r[col_h] += hz[(0u * NZ) + i_t] * s_frac;
        m_r[col_h + 1u] += hz[(0u * NZ) + i_t];
        m_th[col_h] += hz[(1u * NZ) + i_t] * s_frac;
        m_th[col_h + 1u] += hz[(1u * NZ) + i_t];
        m_t[col_h] += hz[(i_t * NZ) + i_t] * s_frac;
        m_t[col_h + 1u] += hz[(i_t * NZ) + i_t];
    }
    /* hess += sum_a Z_a^T m_a, upper triangle */
    for (a = 0u; a < ncol; ++a) {
        ogk_real_t *hrow = &hess[a * NCOL];
        const ogk_real_t z_r = row_r[a];
        const ogk_real_t z_vr = row_vr[a];
        const ogk_real_t z_vt = row_vt[a];
        const ogk_real_t z_m = row_m[a];
        /* without attracting bodies the model does not depend on theta: Z's
         * theta column (a = 1) is 0 in the rows r, v_r, v_theta and m (the
         * forward sweep propagates exact zeros), so its row adds nothing */
        const bool theta_zero = (a == 1u) && !bodies;
        if (theta_zero) {
            /* row 1 of the triangle: no state term */
        } else if (sparse_m) {
            for (c = a; c < ncol; ++c) {
                hrow[c] += (z_r * m_r[c]) + (z_vr * m_vr[c]) + (z_vt * m_vt[c]);
            }
            if (z_m != OGK_R(0.0)) {
                for (c = a; c < ncol; ++c) {
                    hrow[c] += z_m * m_m[c];
                }
            }
        } else {
            for (c = a; c < ncol; ++c) {
                hrow[c] += (z_r * m_r[c]) + (z_vr * m_vr[c]) + (z_vt * m_vt[c]) + (z_m * m_m[c]);
            }
        }
        if (bodies) {
            const ogk_real_t z_th = row_th[a];
            for (c = a; c < ncol; ++c) {
                hrow[c] += z_th * m_th[c];
            }
        }
    }
    for (j = 0u; j < (size_t)nu; ++j) {
        const size_t c0 = i_a + j;
        const size_t c1 = i_a + (size_t)nu + j;
        for (c = c0; c < ncol; ++c) {
            hess[(c0 * NCOL) + c] += (OGK_R(1.0) - s_frac) * m_ctl[j][c];
        }
        for (c = c1; c < ncol; ++c) {
            hess[(c1 * NCOL) + c] += s_frac * m_ctl[j][c];
        }
    }
    if (bodies) {
        for (c = col_h; c < ncol; ++c) {
            hess[(col_h * NCOL) + c] += s_frac * m_t[c];
        }
        hess[((col_h + 1u) * NCOL) + col_h + 1u] += m_t[col_h + 1u];
    }
}

void ogk_i_nmpc_shoot_hess(const ogk_i_ocp_t *ocp, uint32_t nu, /* NOLINT(bugprone-easily-swappable-parameters): internal, the order of ogk_i_nmpc_shoot; checked by central differences (test_nmpc.c) */
                           ogk_real_t t_start, ogk_real_t h, const ogk_real_t *u0, /* NOLINT(bugprone-easily-swappable-parameters): as above */
                           const ogk_real_t *u1, const ogk_real_t *tape, /* NOLINT(bugprone-easily-swappable-parameters): as above */
                           const ogk_real_t *w, ogk_real_t *hess)
{
    const uint32_t steps = ocp->cfg->rk4_steps;
    const ogk_real_t dt = h / (ogk_real_t)steps;
    const ogk_real_t inv_steps = OGK_R(1.0) / (ogk_real_t)steps;
    const size_t ncol = ogk_i_nmpc_ncol(ocp, nu);
    const size_t col_h = NX + (2u * (size_t)nu);
    const size_t ncol_e = ncol + (ncol % 2u);
    ogk_real_t lambda[NX];
    ogk_real_t ybar[NX];
    ogk_real_t kbar[NX];
    ogk_real_t kb[NX];
    ogk_real_t y_sens[NX * NCOL];
    ogk_real_t hz[NZ * NZ];
    ogk_real_t g_h[NCOL];
    ogk_real_t u[OGK_NMPC_MAX_NU];
    const bool bodies = ncol > (col_h + 1u);
    /* a constant engine without a throttle: m' = -mdot_max does not depend on
     * z, so the mass row of Z is e_m plus its column h (m_0 - mdot t): the
     * triangle adds its row only where it is not 0 */
    const bool sparse_m = ((ocp->ops->structure(ocp->data, nu) & OGK_OCP_FLOW_FIXED) != 0u) && (nu == 1u);
    /* steps <= OGK_NMPC_MAX_RK4_STEPS (ogk_nmpc_init): the start of the backward
     * sweep bounded once (0, no step, beyond it as before) so the loop keeps a fixed bound */
    const uint32_t n_top = (steps <= OGK_NMPC_MAX_RK4_STEPS) ? steps : 0u;
    uint32_t n;
    size_t i;
    size_t c;

    (void)memset(hess, 0, NCOL * NCOL * sizeof(ogk_real_t));
    (void)memcpy(lambda, w, sizeof(lambda));
    (void)memset(g_h, 0, sizeof(g_h));
    for (n = n_top; n > 0u; --n) {
        const ogk_real_t *rec_step = &tape[((size_t)n - 1u) * OGK_I_NMPC_TAPE_STEP_Z];
        const ogk_real_t *s_mat = rec_step;
        ogk_real_t lambda_next[NX];
        uint32_t j;

        (void)memcpy(lambda_next, lambda, sizeof(lambda));
        (void)memset(ybar, 0, sizeof(ybar));
        for (j = 4u; j > 0u; --j) {
            const uint32_t js = j - 1u;
            const ogk_real_t *rec = &rec_step[OGK_I_NMPC_TAPE_STAGE0 + ((size_t)js * OGK_I_NMPC_TAPE_STAGE)];
            const ogk_real_t s_frac = (((ogk_real_t)n - OGK_R(1.0)) + ogk_i_rk4_c(js)) * inv_steps;
            const ogk_real_t t_stage = t_start + (s_frac * h);
            /* k_j enters x_{n+1} = x_n + (h / 6M) sum b_j k_j and y_{j+1} =
             * x_n + c_{j+1} (h / M) k_j (ybar holds ybar_{j+1}): with
             * kb = (b_j / 6) lambda_{n+1} + c_{j+1} ybar_{j+1}, its adjoint is
             * kbar_j = (h / M) kb and both products' h cross terms are
             * (1 / M) K_j^T kb */
            for (i = 0u; i < NX; ++i) {
                kb[i] = (ogk_i_rk4_w6(js) / OGK_R(6.0)) * lambda_next[i];
            }
            if (js < 3u) {
                for (i = 0u; i < NX; ++i) {
                    kb[i] += ogk_i_rk4_c(js + 1u) * ybar[i];
                }
            }
            for (i = 0u; i < NX; ++i) {
                kbar[i] = dt * kb[i];
            }
            add_h_cross(&rec[OGK_I_NMPC_TAPE_KS], kb, inv_steps, ncol_e, g_h);
            /* Z_j's state rows: Y_j = S_n + c_j dt K_{j-1} (+ c_j / M k_{j-1} in column h), the
             * forward sweep's stage state again (rk4_internal.h) */
            if (js == 0u) {
                (void)memcpy(y_sens, s_mat, sizeof(y_sens));
            } else {
                const ogk_real_t *prev = &rec_step[OGK_I_NMPC_TAPE_STAGE0 + (((size_t)js - 1u) * OGK_I_NMPC_TAPE_STAGE)];
                const ogk_real_t c_dt = ogk_i_rk4_c(js) * dt;
                for (i = 0u; i < NX; ++i) {
                    const size_t row = i * NCOL;
                    ogk_i_rk4_stage_state_pairs(s_mat, c_dt, &prev[OGK_I_NMPC_TAPE_KS], row, ncol_e, y_sens);
                    y_sens[(i * NCOL) + col_h] += ogk_i_rk4_c(js) * inv_steps * prev[OGK_I_NMPC_TAPE_K + i];
                }
            }
            for (i = 0u; i < (size_t)nu; ++i) {
                u[i] = u0[i] + ((u1[i] - u0[i]) * s_frac);
            }
            /* the problem writes the structural nonzeros of its triangle only (ogk/ocp.h) */
            (void)memset(hz, 0, sizeof(hz));
            ocp->ops->dynamics_hess(ocp->data, nu, t_stage, &rec[OGK_I_NMPC_TAPE_X], u, &rec[OGK_I_NMPC_TAPE_TRIG], kbar, hz);
            add_stage_curvature(hz, y_sens, nu, s_frac, bodies, sparse_m, ncol, hess);
            jx_transpose_times(&rec[OGK_I_NMPC_TAPE_JX], kbar, ybar);
            for (i = 0u; i < NX; ++i) {
                lambda[i] += ybar[i];
            }
        }
    }
    /* the h cross terms into h's row and column (upper triangle) */
    for (c = 0u; c < ncol; ++c) {
        if (c < col_h) {
            hess[(c * NCOL) + col_h] += g_h[c];
        } else if (c > col_h) {
            hess[(col_h * NCOL) + c] += g_h[c];
        } else {
            hess[(col_h * NCOL) + col_h] += OGK_R(2.0) * g_h[c];
        }
    }
    /* the lower triangle mirrored */
    for (i = 0u; i < ncol; ++i) {
        for (c = 0u; c < i; ++c) {
            hess[(i * NCOL) + c] = hess[(c * NCOL) + i];
        }
    }
}
