/* nmpc_condense.c -- the condensing of the NMPC's multiple-shooting QP
 * (docs/design/nmpc.md, "Flight solver"; split out of nmpc_sqp.c, unchanged): the
 * state corrections eliminated by the linearised continuity
 *   dX_{k+1} = A_k dX_k + B0_k dU_k + B1_k dU_{k+1} + t_k dT + d_k, dX_0 = 0
 * (d_k = F_k - X_{k+1}), so that the QP unknowns are v = (dU_0 .. dU_N, dT):
 * G_N = dX_N/dv and e_N = dX_N(v = 0) forward, with the exact Hessian's
 * per-interval terms (nmpc_hess.c) and the keep-out rows on the way; the
 * objective gradient and eq. (5)'s rows in v; and the expansion of a QP
 * step v back to the state corrections. */
#include "nmpc_internal.h"

#include <string.h>

#include "../ogk_checks.h"

#define NX ((size_t)OGK_NMPC_NX)
#define NC ((size_t)OGK_NMPC_NC)
#define MAXV OGK_NMPC_MAX_VARS

/* G_N = dX_N/dv and e_N = dX_N(v = 0) by the forward recursion. */
void ogk_i_nmpc_condense(ogk_nmpc_t *ctx, const ogk_nmpc_plan_t *p, size_t nv, ogk_real_t *hess)
{
    const uint32_t nu = p->nu;
    const size_t col_t = nv - 1u;
    ogk_real_t g_next[NX * MAXV];
    ogk_real_t e_next[NX];
    /* nodes <= OGK_NMPC_MAX_NODES (ogk_nmpc_init, load_plan): clamped once, a fixed bound */
    const size_t nodes = ogk_i_min_size(p->nodes, OGK_NMPC_MAX_NODES);
    size_t k;
    size_t i;
    size_t j;
    size_t c;

    (void)memset(ctx->cond_g, 0, NX * nv * sizeof(ogk_real_t));
    (void)memset(ctx->cond_e, 0, sizeof(ctx->cond_e));
    ctx->ko_rows = 0u;
    if (hess != NULL) {
        (void)memset(hess, 0, nv * nv * sizeof(ogk_real_t));
    }
    for (k = 0u; k < nodes; ++k) {
        const ogk_real_t *a = &ctx->sens_a[k * NX * NX];
        /* the keep-out along interval k's arc, with cond_g = dX_k/dv, cond_e = e_k */
        ogk_i_nmpc_keepout_arc_rows(ctx, p, nv, k, ctx->cond_g, ctx->cond_e);
        if (hess != NULL) {
            /* the exact Hessian's interval k, with cond_g = dX_k/dv */
            ogk_i_nmpc_hess_add(hess, nv, nu, k, ctx->cond_g,
                                &ctx->hess_blk[k * OGK_NMPC_MAX_DIR * OGK_NMPC_MAX_DIR], ctx->hess_tmp);
        }
        /* columns that can be nonzero after interval k: U_0..U_{k+1}, T */
        const size_t n_used = (k + 2u) * nu;
        for (i = 0u; i < NX; ++i) {
            ogk_real_t acc_e = OGK_R(0.0);
            /* by pairs (packed on x86-64); an odd n_used's extra column is 0
             * (U_{k+2}) or T's (set below), and is not copied back */
            for (c = 0u; c < n_used; c += 2u) {
                ogk_real_t acc0 = OGK_R(0.0);
                ogk_real_t acc1 = OGK_R(0.0);
                for (j = 0u; j < NX; ++j) {
                    acc0 += a[(i * NX) + j] * ctx->cond_g[(j * nv) + c];
                    acc1 += a[(i * NX) + j] * ctx->cond_g[(j * nv) + c + 1u];
                }
                g_next[(i * nv) + c] = acc0;
                g_next[(i * nv) + c + 1u] = acc1;
            }
            {
                ogk_real_t acc = OGK_R(0.0);
                for (j = 0u; j < NX; ++j) {
                    acc += a[(i * NX) + j] * ctx->cond_g[(j * nv) + col_t];
                    acc_e += a[(i * NX) + j] * ctx->cond_e[j];
                }
                g_next[(i * nv) + col_t] = acc + ctx->sens_t[(k * NX) + i];
            }
            for (j = 0u; j < nu; ++j) {
                g_next[(i * nv) + (k * nu) + j] += ctx->sens_b0[(k * NX * nu) + (i * nu) + j];
                g_next[(i * nv) + ((k + 1u) * nu) + j] += ctx->sens_b1[(k * NX * nu) + (i * nu) + j];
            }
            e_next[i] = acc_e + (ctx->sens_f[(k * NX) + i] - p->x[((k + 1u) * NX) + i]);
        }
        for (i = 0u; i < NX; ++i) {
            for (c = 0u; c < n_used; ++c) {
                ctx->cond_g[(i * nv) + c] = g_next[(i * nv) + c];
            }
            ctx->cond_g[(i * nv) + col_t] = g_next[(i * nv) + col_t];
        }
        (void)memcpy(ctx->cond_e, e_next, sizeof(e_next));
        if ((k + 1u) < p->nodes) {
            ogk_i_nmpc_keepout_rows(ctx, p, nv, k + 1u, ctx->cond_g, ctx->cond_e);
        }
    }
    if (hess != NULL) {
        ogk_i_nmpc_hess_mirror(hess, nv);
    }
}

/* Objective gradient in v and the QP's equality rows (linearised eq. 5). */
void ogk_i_nmpc_linear_terms(ogk_nmpc_t *ctx, const ogk_nmpc_plan_t *p,
                               size_t nv, const ogk_real_t *c_term, ogk_real_t *g_obj)
{
    const size_t col_t = nv - 1u;
    const ogk_i_ocp_t ocp = ogk_i_nmpc_problem(ctx);
    ogk_real_t x_target[NC];
    ogk_real_t rate[NC];
    size_t i;
    size_t c;

    /* the target's rate dx_T/dt_f at this plan's t_f */
    ocp.ops->target(ocp.data, p->t0 + p->horizon, x_target, rate);
    (void)memset(g_obj, 0, nv * sizeof(ogk_real_t));
    if (ctx->cfg.objective == OGK_NMPC_MIN_FUEL) {
        for (c = 0u; c < nv; ++c) {
            g_obj[c] = -ctx->cond_g[(4u * nv) + c]; /* J = m_0 - m_N (+ time_weight T) */
        }
        g_obj[col_t] += ctx->cfg.time_weight;
    } else {
        g_obj[col_t] = OGK_R(1.0); /* J = T */
    }
    for (i = 0u; i < NC; ++i) {
        for (c = 0u; c < nv; ++c) {
            ctx->qp_aeq[(i * nv) + c] = ctx->cond_g[(i * nv) + c];
        }
        ctx->qp_beq[i] = -(c_term[i] + ctx->cond_e[i]);
    }
    /* the target x_T(t_f) moves with T (the heliocentric problem: theta_T, eq. 6) */
    for (i = 0u; i < NC; ++i) {
        ctx->qp_aeq[(i * nv) + col_t] -= rate[i];
    }
}

/* State part of the step: dX_{k+1} = A_k dX_k + B0 dU_k + B1 dU_{k+1} + t_k dT + d_k. */
void ogk_i_nmpc_expand_step(ogk_nmpc_t *ctx, const ogk_nmpc_plan_t *p, const ogk_real_t *v, size_t nv)
{
    const uint32_t nu = p->nu;
    /* nodes <= OGK_NMPC_MAX_NODES (ogk_nmpc_init, load_plan): clamped once, a fixed bound */
    const size_t nodes = ogk_i_min_size(p->nodes, OGK_NMPC_MAX_NODES);
    size_t k;
    size_t i;
    size_t j;

    (void)memset(ctx->dx, 0, NX * sizeof(ogk_real_t));
    for (k = 0u; k < nodes; ++k) {
        for (i = 0u; i < NX; ++i) {
            ogk_real_t acc = ctx->sens_f[(k * NX) + i] - p->x[((k + 1u) * NX) + i];
            for (j = 0u; j < NX; ++j) {
                acc += ctx->sens_a[(k * NX * NX) + (i * NX) + j] * ctx->dx[(k * NX) + j];
            }
            for (j = 0u; j < nu; ++j) {
                acc += ctx->sens_b0[(k * NX * nu) + (i * nu) + j] * v[(k * nu) + j];
                acc += ctx->sens_b1[(k * NX * nu) + (i * nu) + j] * v[((k + 1u) * nu) + j];
            }
            acc += ctx->sens_t[(k * NX) + i] * v[nv - 1u];
            ctx->dx[((k + 1u) * NX) + i] = acc;
        }
    }
}
