/* mpsp_sensitivity.c -- sensitivity matrices of the MPSP trajectory:
 * RK4 step Jacobians (Appendix A, with U at the RK4 stage times), the
 * switching compensation (eqs. 22-25, Appendix B) and the backward recursion
 * (eqs. 28-35) that accumulates B_v = sum_k B_k P_k (eq. 40) and A_lambda
 * (eq. 33). Derivations and costs in docs/design/mpsp.md (sections 3 and 8).
 *
 * The recursion propagates the 7 rows of B_{k,0} = d Y / d X_k (eq. 35)
 * backwards; each RK4 step is differentiated in reverse through its four
 * stages, which is eq. (A.3)-(A.4) transposed: the same numbers as forming the
 * 8 x 8 step matrices and multiplying, at a fraction of the cost. */
#include "mpsp_internal.h"
#include "ogk/internal/mpsp_test.h"

#include <math.h>
#include <string.h>

#define NX ((size_t)OGK_MPSP_NX)
#define NY ((size_t)OGK_MPSP_NY)
/* Coefficients of one sensitivity sample: bU(t), row r, component c at r * 3 + c. */
#define NYU (NY * 3u)
#define MB OGK_MPSP_MAX_BASIS
/* A basis row of the sample block: OGK_MPSP_H_LANES entries per function. */
#define HR (MB * (size_t)OGK_MPSP_H_LANES)
#define SB ((size_t)OGK_MPSP_SENS_BLOCK)

ogk_status ogk_i_mpsp_jump_terms(ogk_i_mpsp_dyn_t *dyn, ogk_real_t t_s, const ogk_real_t *x_s,
                           int mode_before, ogk_i_mpsp_jump_t *jump)
{
    ogk_real_t h[OGK_MPSP_MAX_BASIS];
    ogk_real_t hdot[OGK_MPSP_MAX_BASIS];
    ogk_real_t u[3];
    ogk_real_t udot[3];
    ogk_real_t f_before[NX];
    ogk_real_t f_after[NX];
    const ogk_real_t m = x_s[6];
    ogk_status st;

    ogk_i_mpsp_basis(dyn, t_s, h, hdot);
    ogk_i_mpsp_control_from_basis(dyn, h, 1u, u);
    ogk_i_mpsp_control_from_basis(dyn, hdot, 1u, udot);
    st = ogk_i_mpsp_rhs(dyn, x_s, u, mode_before, f_before);
    if (st == OGK_OK) {
        st = ogk_i_mpsp_rhs(dyn, x_s, u, 1 - mode_before, f_after);
    }
    if (st == OGK_OK) {
        ogk_real_t lam;
        ogk_real_t e_udot;
        size_t i;
        lam = OGK_SQRT((u[0] * u[0]) + (u[1] * u[1]) + (u[2] * u[2]));
        for (i = 0u; i < NX; ++i) {
            jump->dxdot[i] = f_after[i] - f_before[i];
            jump->s_x[i] = OGK_R(0.0);
        }
        /* S_X = [0_6, c lambda_v / m^2, -1], S_U = -c/(m lambda_v) lambda_v^T (eq. 25) */
        jump->s_x[6] = dyn->c_exhaust * lam / (m * m);
        jump->s_x[7] = -OGK_R(1.0);
        for (i = 0u; i < 3u; ++i) {
            jump->s_u[i] = -dyn->c_exhaust * u[i] / (m * lam);
        }
        /* Eq. (15): dS/dt = S_U dU/dt (S_X Xdot vanishes identically). */
        e_udot = (jump->s_u[0] * udot[0]) + (jump->s_u[1] * udot[1]) + (jump->s_u[2] * udot[2]);
        jump->s_dot = e_udot;
        if (!isfinite(jump->s_dot) || !(OGK_FABS(jump->s_dot) > OGK_R(0.0))) {
            st = OGK_E_SINGULAR; /* tangential switch: t_s not differentiable */
        }
    }
    return st;
}

/* U and |U| from a basis row, h_q at h[q * stride] (1, or OGK_MPSP_H_LANES
 * for a row of the sample block: U not kept by the propagation). */
static void uval_from_basis(const ogk_i_mpsp_dyn_t *dyn, const ogk_real_t *h, size_t stride, ogk_i_mpsp_uval_t *uv)
{
    ogk_i_mpsp_control_from_basis(dyn, h, stride, uv->u);
    uv->lam = OGK_SQRT((uv->u[0] * uv->u[0]) + (uv->u[1] * uv->u[1]) + (uv->u[2] * uv->u[2]));
}

/* out[r][c n_basis + q] += coef[r * 3 + c] h[q], row-major rows x 3 n_basis
 * (the one-step Jacobian; not on the hot path). */
static void accumulate_rows(ogk_real_t *out, size_t n_basis, size_t rows, const ogk_real_t *coef, /* NOLINT(bugprone-easily-swappable-parameters): order of eqs. (16)/(25); FD-checked by the unit tests */
                            const ogk_real_t *h)
{
    const size_t n_weights = 3u * n_basis;
    size_t r;
    size_t c;
    size_t q;
    for (r = 0u; r < rows; ++r) {
        for (c = 0u; c < 3u; ++c) {
            for (q = 0u; q < n_basis; ++q) {
                out[(r * n_weights) + (c * n_basis) + q] += coef[(r * 3u) + c] * h[q];
            }
        }
    }
}

/* The partials of the RK4 step of ogk_mpsp_step_jacobian (x_next already
 * taken): dF/dX and dF/dW through the adjoint of the step, each if asked. */
static ogk_status step_partials(const ogk_mpsp_t *ctx, const ogk_i_mpsp_dyn_t *dyn, ogk_real_t t, /* NOLINT(bugprone-easily-swappable-parameters): order of eqs. (16)/(25); FD-checked by the unit tests */
                                const ogk_real_t *x, ogk_real_t dt, int mode, ogk_real_t *dfdx, /* NOLINT(bugprone-easily-swappable-parameters): order of eqs. (16)/(25); FD-checked by the unit tests */
                                ogk_real_t *dfdw)
{
    ogk_real_t h0[OGK_MPSP_MAX_BASIS];
    ogk_real_t hm[OGK_MPSP_MAX_BASIS];
    ogk_real_t h1[OGK_MPSP_MAX_BASIS];
    ogk_real_t adj[NX * NX];
    ogk_real_t b0[NX * 3u];
    ogk_real_t bm[NX * 3u];
    ogk_real_t b1[NX * 3u];
    ogk_i_mpsp_uval_t uv[3];
    size_t i;
    ogk_status st;

    ogk_i_mpsp_basis(dyn, t, h0, NULL);
    ogk_i_mpsp_basis(dyn, t + (OGK_R(0.5) * dt), hm, NULL);
    ogk_i_mpsp_basis(dyn, t + dt, h1, NULL);
    (void)memset(adj, 0, sizeof adj);
    (void)memset(b0, 0, sizeof b0);
    (void)memset(bm, 0, sizeof bm);
    (void)memset(b1, 0, sizeof b1);
    for (i = 0u; i < NX; ++i) {
        adj[(i * NX) + i] = OGK_R(1.0); /* row i seeds d X_next[i] */
    }
    uval_from_basis(dyn, h0, 1u, &uv[0]);
    uval_from_basis(dyn, hm, 1u, &uv[1]);
    uval_from_basis(dyn, h1, 1u, &uv[2]);
    /* one row at a time on every target: the paired rows of the sweep are
     * checked against this path by the unit tests */
    st = ogk_i_mpsp_step_adjoint(dyn, x, dt, mode, uv, false, NX, adj, adj, b0, bm, b1);
    if ((st == OGK_OK) && (dfdx != NULL)) {
        (void)memcpy(dfdx, adj, sizeof adj); /* row i of adj is d X_next[i] / dX */
    }
    if ((st == OGK_OK) && (dfdw != NULL)) {
        (void)memset(dfdw, 0, NX * ctx->n_weights * sizeof dfdw[0]);
        accumulate_rows(dfdw, ctx->n_basis, NX, b0, h0);
        accumulate_rows(dfdw, ctx->n_basis, NX, bm, hm);
        accumulate_rows(dfdw, ctx->n_basis, NX, b1, h1);
    }
    return st;
}

static ogk_status check_ctx(const ogk_mpsp_t *ctx)
{
    ogk_status st;

    if (ctx == NULL) {
        st = OGK_E_NULL;
    } else {
        st = (ctx->init_marker == OGK_MPSP_INIT_MARKER) ? OGK_OK : OGK_E_NOT_INIT;
    }
    return st;
}

static ogk_status check_mode_scale(ogk_real_t thrust_scale, int mode)
{
    ogk_status st = OGK_OK;

    if (!isfinite(thrust_scale)) {
        st = OGK_E_NONFINITE;
    } else if ((!(thrust_scale > OGK_R(0.0))) || ((mode != 0) && (mode != 1))) {
        st = OGK_E_RANGE;
    } else {
        /* a usable scale and mode */
    }
    return st;
}

ogk_status ogk_mpsp_step_jacobian(const ogk_mpsp_t *ctx, const ogk_real_t *weights,
                                  ogk_real_t thrust_scale, ogk_real_t t, const ogk_real_t *x, /* NOLINT(bugprone-easily-swappable-parameters): order of eqs. (16)/(25); FD-checked by the unit tests */
                                  ogk_real_t dt, int mode, ogk_real_t *x_next, /* NOLINT(bugprone-easily-swappable-parameters): order of eqs. (16)/(25); FD-checked by the unit tests */
                                  ogk_real_t *dfdx, ogk_real_t *dfdw)
{
    ogk_status st = check_ctx(ctx);

    if ((st == OGK_OK) && ((weights == NULL) || (x == NULL) || (x_next == NULL))) {
        st = OGK_E_NULL;
    }
    if (st == OGK_OK) {
        st = check_mode_scale(thrust_scale, mode);
    }
    if ((st == OGK_OK) && (!isfinite(t) || !isfinite(dt) || !ogk_i_all_finite(x, NX) ||
                           !ogk_i_all_finite(weights, ctx->n_weights))) {
        st = OGK_E_NONFINITE;
    }
    if ((st == OGK_OK) && (dt == OGK_R(0.0))) {
        st = OGK_E_RANGE;
    }
    if (st == OGK_OK) {
        ogk_i_mpsp_dyn_t dyn;
        ogk_rk4_problem_t prob;
        ogk_i_mpsp_dyn_setup(&dyn, ctx, weights, ctx->cfg.t_max * thrust_scale);
        ogk_i_mpsp_rk4_problem(&prob, ctx, &dyn);
        prob.sw = NULL;
        st = ogk_rk4_step(&prob, t, x, dt, mode, x_next);
        if ((st == OGK_OK) && ((dfdx != NULL) || (dfdw != NULL))) {
            st = step_partials(ctx, &dyn, t, x, dt, mode, dfdx, dfdw);
        }
    }
    return st;
}

/* The argument checks of ogk_mpsp_switch_jump, in their order. */
static ogk_status check_jump_args(const ogk_mpsp_t *ctx, const ogk_real_t *weights, ogk_real_t thrust_scale, /* NOLINT(bugprone-easily-swappable-parameters): order of eqs. (16)/(25); FD-checked by the unit tests */
                                  ogk_real_t t_s, const ogk_real_t *x_s, int mode_before)
{
    ogk_status st = check_ctx(ctx);

    if ((st == OGK_OK) && ((weights == NULL) || (x_s == NULL))) {
        st = OGK_E_NULL;
    }
    if (st == OGK_OK) {
        st = check_mode_scale(thrust_scale, mode_before);
    }
    if ((st == OGK_OK) && (!isfinite(t_s) || !ogk_i_all_finite(x_s, NX) ||
                           !ogk_i_all_finite(weights, ctx->n_weights))) {
        st = OGK_E_NONFINITE;
    }
    return st;
}

ogk_status ogk_mpsp_switch_jump(const ogk_mpsp_t *ctx, const ogk_real_t *weights,
                                ogk_real_t thrust_scale, ogk_real_t t_s, const ogk_real_t *x_s, /* NOLINT(bugprone-easily-swappable-parameters): order of eqs. (16)/(25); FD-checked by the unit tests */
                                int mode_before, ogk_real_t *jx, ogk_real_t *jw, /* NOLINT(bugprone-easily-swappable-parameters): order of eqs. (16)/(25); FD-checked by the unit tests */
                                ogk_real_t *dts_dx, ogk_real_t *dts_dw)
{
    ogk_i_mpsp_dyn_t dyn;
    ogk_i_mpsp_jump_t jump;
    ogk_real_t h[OGK_MPSP_MAX_BASIS];
    ogk_status st = check_jump_args(ctx, weights, thrust_scale, t_s, x_s, mode_before);

    if (st == OGK_OK) {
        ogk_i_mpsp_dyn_setup(&dyn, ctx, weights, ctx->cfg.t_max * thrust_scale);
        st = ogk_i_mpsp_jump_terms(&dyn, t_s, x_s, mode_before, &jump);
    }
    if (st == OGK_OK) {
        size_t i;
        size_t j;
        size_t c;
        size_t q;
        ogk_i_mpsp_basis(&dyn, t_s, h, NULL);
        /* Eq. (24): I + dxdot S_X / Sdot;  eq. (25) with dU = P(t_s) dW. */
        for (i = 0u; i < NX; ++i) {
            const ogk_real_t a = jump.dxdot[i] / jump.s_dot;
            if (jx != NULL) {
                for (j = 0u; j < NX; ++j) {
                    jx[(i * NX) + j] = ((i == j) ? OGK_R(1.0) : OGK_R(0.0)) + (a * jump.s_x[j]);
                }
            }
            if (jw != NULL) {
                for (c = 0u; c < 3u; ++c) {
                    for (q = 0u; q < ctx->n_basis; ++q) {
                        jw[(i * ctx->n_weights) + (c * ctx->n_basis) + q] = a * jump.s_u[c] * h[q];
                    }
                }
            }
        }
        /* Eq. (B.2): dt_s = -(S_X dX- + S_U dU) / Sdot. */
        if (dts_dx != NULL) {
            for (j = 0u; j < NX; ++j) {
                dts_dx[j] = -jump.s_x[j] / jump.s_dot;
            }
        }
        if (dts_dw != NULL) {
            for (c = 0u; c < 3u; ++c) {
                for (q = 0u; q < ctx->n_basis; ++q) {
                    dts_dw[(c * ctx->n_basis) + q] = -jump.s_u[c] * h[q] / jump.s_dot;
                }
            }
        }
    }
    return st;
}

/* Eqs. (22)-(25) at the switch node k + 1 (time t_hi, state x_hi) of the
 * backward recursion: the NY rows adj compensated and the S_U part added to
 * pend (bU at t_hi). */
static ogk_status switch_compensation(ogk_i_mpsp_dyn_t *dyn, ogk_real_t t_hi, const ogk_real_t *x_hi, int mode, /* NOLINT(bugprone-easily-swappable-parameters): order of eqs. (16)/(25); FD-checked by the unit tests */
                                      ogk_real_t *adj, ogk_real_t *pend) /* NOLINT(bugprone-easily-swappable-parameters): order of eqs. (16)/(25); FD-checked by the unit tests */
{
    ogk_i_mpsp_jump_t jump;
    const ogk_status st = ogk_i_mpsp_jump_terms(dyn, t_hi, x_hi, mode, &jump);

    if (st == OGK_OK) {
        size_t r;
        size_t i;
        for (r = 0u; r < NY; ++r) {
            ogk_real_t a = OGK_R(0.0);
            for (i = 0u; i < NX; ++i) {
                a += adj[(r * NX) + i] * jump.dxdot[i];
            }
            a /= jump.s_dot;
            for (i = 0u; i < 3u; ++i) {
                pend[(r * 3u) + i] += a * jump.s_u[i];
            }
            for (i = 0u; i < NX; ++i) {
                adj[(r * NX) + i] += a * jump.s_x[i];
            }
        }
    }
    return st;
}

/* Samples of B_v (eq. 40) on their way into ctx->bv_acc: slots 0..n-1 of
 * ctx->sens_h / sens_c are complete; when hi_held, slot n already holds
 * h(t_hi) and hi its U, for the node above the step being differentiated. */
typedef struct {
    ogk_mpsp_t *ctx;
    size_t n;
    bool hi_held;
    ogk_i_mpsp_uval_t hi;
} sens_block_t;

/* Adds the complete samples to B_v and moves a held h(t_hi) to slot 0. */
static void block_flush(sens_block_t *blk)
{
    ogk_mpsp_t *ctx = blk->ctx;
    ogk_i_mpsp_bv_block_product(ctx->bv_acc, ctx->n_basis, ctx->sens_h, ctx->sens_c, blk->n);
    if (blk->hi_held && (blk->n > 0u)) {
        (void)memcpy(ctx->sens_h, &ctx->sens_h[blk->n * HR],
                     ctx->n_basis * OGK_MPSP_H_LANES * sizeof ctx->sens_h[0]);
    }
    blk->n = 0u;
}

/* h(t_hi) and U(t_hi) into slot n unless already held. */
static void block_hold_hi(sens_block_t *blk, ogk_i_mpsp_dyn_t *dyn, ogk_real_t t_hi)
{
    if (!blk->hi_held) {
        ogk_real_t *row = &blk->ctx->sens_h[blk->n * HR];
#if defined(__SSE2__)
        ogk_real_t h[MB];
        size_t q;
        ogk_i_mpsp_basis_control(dyn, t_hi, h, &blk->hi);
        for (q = 0u; q < dyn->n_basis; ++q) { /* each value twice (OGK_MPSP_H_LANES) */
            row[2u * q] = h[q];
            row[(2u * q) + 1u] = h[q];
        }
#else
        ogk_i_mpsp_basis_control(dyn, t_hi, row, &blk->hi);
#endif
        blk->hi_held = true;
    }
}

/* One thrust step k (node k -> k + 1) of the recursion: U at the node below
 * and at the midpoint from new basis rows (slots n + 2 and n + 1), the step
 * differentiated, and the node above (slot n: its pending bU plus stage 4)
 * and the midpoint (stages 2 and 3) completed; the node below is held with
 * stage 1 as its pending bU. */
static ogk_status thrust_step(sens_block_t *blk, ogk_i_mpsp_dyn_t *dyn, size_t k, ogk_real_t *adj, /* NOLINT(bugprone-easily-swappable-parameters): order of eqs. (16)/(25); FD-checked by the unit tests */
                              ogk_real_t *pend)
{
    ogk_mpsp_t *ctx = blk->ctx;
    const ogk_real_t t_lo = ctx->traj_t[k];
    const ogk_real_t dt = ctx->traj_t[k + 1u] - t_lo;
    const size_t n = blk->n;
    ogk_real_t *h_mid = &ctx->sens_h[(n + 1u) * HR];
    ogk_real_t *h_lo = &ctx->sens_h[(n + 2u) * HR];
    ogk_real_t *c_hi = &ctx->sens_c[n * NYU];
    ogk_real_t *c_mid = &ctx->sens_c[(n + 1u) * NYU];
    ogk_real_t pend_lo[NYU];
    ogk_i_mpsp_uval_t uv[3];
    ogk_status st;

    block_hold_hi(blk, dyn, ctx->traj_t[k + 1u]);
#if defined(__SSE2__)
    {
        /* the midpoint, then t_lo: the phase order of the one-time path */
        const ogk_real_t t_pair[2] = {t_lo + (OGK_R(0.5) * dt), t_lo};
        ogk_i_mpsp_uval_t uv_pair[2];
        /* U kept by the propagation (made there for these very times), else
         * made here with h; either way the same phases in the same order */
        const bool kept_mid = ogk_i_mpsp_keep_find(ctx, dyn, t_pair[0], &uv_pair[0]);
        const bool kept_lo = ogk_i_mpsp_keep_find(ctx, dyn, t_pair[1], &uv_pair[1]);
        ogk_i_mpsp_basis2(dyn, t_pair, h_mid, h_lo);
        if (!kept_mid) { /* the last step before a switch (bisection's) */
            uval_from_basis(dyn, h_mid, OGK_MPSP_H_LANES, &uv_pair[0]);
        }
        if (!kept_lo) { /* a switch node or t0 */
            uval_from_basis(dyn, h_lo, OGK_MPSP_H_LANES, &uv_pair[1]);
        }
        uv[1] = uv_pair[0];
        uv[0] = uv_pair[1];
    }
#else
    ogk_i_mpsp_basis_control(dyn, t_lo + (OGK_R(0.5) * dt), h_mid, &uv[1]);
    ogk_i_mpsp_basis_control(dyn, t_lo, h_lo, &uv[0]);
#endif
    uv[2] = blk->hi;
    st = ogk_i_mpsp_step_adjoint(dyn, &ctx->traj_x[k * NX], dt, 1, uv, MPSP_PAIR_ROWS, NY, adj, adj,
                           pend_lo, c_mid, c_hi);
    if (st == OGK_OK) {
        size_t j;
        /* t_hi gathers stage 4 of this step, stage 1 of the step above and a
         * switch there; t_lo + dt/2 gathers stages 2 and 3. */
        for (j = 0u; j < NYU; ++j) {
            c_hi[j] += pend[j];
        }
        (void)memcpy(pend, pend_lo, sizeof pend_lo);
        /* two samples complete; h(t_lo), in slot n + 2, is the new held slot */
        blk->n = n + 2u;
        blk->hi = uv[0];
        blk->hi_held = true;
    }
    return st;
}

/* The end of both sweeps: the last samples into B_v, B_v unpacked into
 * dY/dw, and A_lambda, the lambda_m column of dY/dX(t0) (eq. 33). */
static void recursion_finish(ogk_mpsp_t *ctx, sens_block_t *blk, const ogk_real_t *adj)
{
    size_t r;

    blk->hi_held = false;
    block_flush(blk);
    ogk_i_mpsp_bv_unpack(ctx->bv_acc, ctx->n_basis, ctx->dy_dw);
    for (r = 0u; r < NY; ++r) {
        ctx->dy_dlm0[r] = adj[(r * NX) + 7u];
    }
}

/* The start of both sweeps: the dynamics of the current weights, an empty
 * sample block, dY/dX(tf) with Y = [r, v, lambda_m] (adj, NY x NX) and B_v's
 * accumulators cleared. */
static void recursion_start(ogk_mpsp_t *ctx, ogk_i_mpsp_dyn_t *dyn, sens_block_t *blk, ogk_real_t *adj)
{
    size_t r;

    ogk_i_mpsp_dyn_setup(dyn, ctx, ctx->weights, ctx->thrust);
    blk->ctx = ctx;
    blk->n = 0u;
    blk->hi_held = false;
    (void)memset(&blk->hi, 0, sizeof blk->hi);
    (void)memset(adj, 0, NY * NX * sizeof adj[0]);
    for (r = 0u; r < 6u; ++r) {
        adj[(r * NX) + r] = OGK_R(1.0);
    }
    adj[(6u * NX) + 7u] = OGK_R(1.0);
    (void)memset(ctx->bv_acc, 0, ctx->n_basis * NYU * sizeof ctx->bv_acc[0]);
}

/* The backward recursion of ogk_mpsp_sensitivity over the trajectory held
 * (at least 2 nodes): ctx->dy_dw and ctx->dy_dlm0, both left as they were
 * when a step or switch fails. */
static ogk_status backward_recursion(ogk_mpsp_t *ctx)
{
    ogk_i_mpsp_dyn_t dyn;
    sens_block_t blk;
    ogk_real_t adj[NY * NX];
    ogk_real_t pend[NYU];
    bool pend_nonzero = false;
    size_t kk;
    ogk_status st = OGK_OK;

    recursion_start(ctx, &dyn, &blk, adj);
    (void)memset(pend, 0, sizeof pend);

    for (kk = 1u; (kk < ctx->n_nodes) && (st == OGK_OK); ++kk) {
        const size_t k = ctx->n_nodes - 1u - kk; /* step k: node k -> k + 1 */
        const int mode = (int)ctx->traj_mode[k];

        if ((blk.n + 3u) > SB) {
            block_flush(&blk); /* room for the 3 samples of a step */
        }
        /* Switch at node k + 1 (mode changes there): eqs. (22)-(25). */
        if (ctx->traj_mode[k + 1u] != ctx->traj_mode[k]) {
            st = switch_compensation(&dyn, ctx->traj_t[k + 1u], &ctx->traj_x[(k + 1u) * NX], mode,
                                     adj, pend);
            pend_nonzero = true;
        }
        if ((st == OGK_OK) && (mode == 1)) {
            st = thrust_step(&blk, &dyn, k, adj, pend);
            pend_nonzero = true;
        } else if (st == OGK_OK) {
            ogk_i_mpsp_uval_t uv[3];
            ogk_real_t unused[NYU];
            (void)memset(uv, 0, sizeof uv);
            if (pend_nonzero) { /* the node above ends a thrust arc or is a switch */
                block_hold_hi(&blk, &dyn, ctx->traj_t[k + 1u]);
                (void)memcpy(&ctx->sens_c[blk.n * NYU], pend, sizeof pend);
                blk.n += 1u;
            }
            blk.hi_held = false;
            (void)memset(pend, 0, sizeof pend);
            pend_nonzero = false;
            st = ogk_i_mpsp_step_adjoint(&dyn, &ctx->traj_x[k * NX], ctx->traj_t[k + 1u] - ctx->traj_t[k],
                                   0, uv, MPSP_PAIR_ROWS, NY, adj, adj, unused, unused,
                                   unused);
        } else {
            /* the switch's status returned */
        }
    }
    if (st == OGK_OK) {
        if (pend_nonzero) { /* t0 in thrust */
            block_hold_hi(&blk, &dyn, ctx->traj_t[0]);
            (void)memcpy(&ctx->sens_c[blk.n * NYU], pend, sizeof pend);
            blk.n += 1u;
        }
        recursion_finish(ctx, &blk, adj);
    }
    return st;
}

/* The midpoint of step k (node k -> k + 1), as both sweeps compute it. */
static ogk_real_t step_mid(const ogk_mpsp_t *ctx, size_t k)
{
    const ogk_real_t t_lo = ctx->traj_t[k];
    return t_lo + (OGK_R(0.5) * (ctx->traj_t[k + 1u] - t_lo));
}

/* A switch's sample of B_v at t_s with coefficients coef (NYU) into slot n;
 * a basis row held there (blk->hi_held: the next midpoint's, SSE2) moves up
 * to slot n + 1 and stays held. */
static void mid2_push_switch(sens_block_t *blk, ogk_i_mpsp_dyn_t *dyn, ogk_real_t t_s, const ogk_real_t *coef)
{
    ogk_mpsp_t *ctx = blk->ctx;
    const bool held = blk->hi_held; /* its U is not held: mid2_row_at takes it anew */
    ogk_real_t *row = &ctx->sens_h[blk->n * HR];

    if (held) {
        (void)memcpy(&row[HR], row, dyn->n_basis * OGK_MPSP_H_LANES * sizeof row[0]);
    }
    blk->hi_held = false;
    block_hold_hi(blk, dyn, t_s);
    (void)memcpy(&ctx->sens_c[blk->n * NYU], coef, NYU * sizeof coef[0]);
    blk->n += 1u;
    blk->hi_held = held;
}

/* The basis row of thrust step k's midpoint in slot n and U there. On SSE2
 * the row is made two midpoints per pass (ogk_i_mpsp_basis2: this step's and step
 * k - 1's, which the sweep takes next), the second held in slot n + 1, and U
 * comes from the propagation (ogk_i_mpsp_keep_find) or else from the row; elsewhere
 * ogk_i_mpsp_basis_control makes the row and U. */
static void mid2_row_at(sens_block_t *blk, ogk_i_mpsp_dyn_t *dyn, size_t k, ogk_i_mpsp_uval_t *uv)
{
    const ogk_real_t t_mid = step_mid(blk->ctx, k);
#if defined(__SSE2__)
    ogk_mpsp_t *ctx = blk->ctx;
    ogk_real_t *row = &ctx->sens_h[blk->n * HR];
    const bool made = !blk->hi_held; /* else made with step k + 1's */
    if (made) {
        const ogk_real_t t_pair[2] = {t_mid, (k > 0u) ? step_mid(ctx, k - 1u) : t_mid};
        ogk_i_mpsp_basis2(dyn, t_pair, row, &row[HR]);
    }
    if (!ogk_i_mpsp_keep_find(ctx, dyn, t_mid, uv)) { /* the last step before a switch */
        uval_from_basis(dyn, row, OGK_MPSP_H_LANES, uv);
    }
    blk->hi_held = made && (k > 0u); /* slot n + 1: step k - 1's midpoint */
#else
    blk->hi_held = false;
    block_hold_hi(blk, dyn, t_mid);
    *uv = blk->hi;
    blk->hi_held = false;
#endif
}

/* The backward recursion of the second-order sweep (OGK_MPSP_SWEEP_MID2):
 * the switching compensation as in backward_recursion (exact, a sample of
 * B_v at each switch), each step by ogk_i_mpsp_step_adjoint_mid2 and, in thrust,
 * one sample of B_v at the step's midpoint; results as backward_recursion. */
static ogk_status backward_recursion_mid2(ogk_mpsp_t *ctx)
{
    ogk_i_mpsp_dyn_t dyn;
    sens_block_t blk;
    ogk_real_t adj[NY * NX];
    ogk_real_t pend[NYU];
    size_t kk;
    ogk_status st = OGK_OK;

    recursion_start(ctx, &dyn, &blk, adj);

    for (kk = 1u; (kk < ctx->n_nodes) && (st == OGK_OK); ++kk) {
        const size_t k = ctx->n_nodes - 1u - kk; /* step k: node k -> k + 1 */
        const int mode = (int)ctx->traj_mode[k];
        const ogk_real_t dt = ctx->traj_t[k + 1u] - ctx->traj_t[k];

        if ((blk.n + 3u) > SB) {
            block_flush(&blk); /* room for a switch, a midpoint and a held row */
        }
        if (ctx->traj_mode[k + 1u] != ctx->traj_mode[k]) { /* eqs. (22)-(25) */
            (void)memset(pend, 0, sizeof pend);
            st = switch_compensation(&dyn, ctx->traj_t[k + 1u], &ctx->traj_x[(k + 1u) * NX], mode,
                                     adj, pend);
            if (st == OGK_OK) {
                mid2_push_switch(&blk, &dyn, ctx->traj_t[k + 1u], pend);
            }
        }
        if ((st == OGK_OK) && (mode == 1)) {
            ogk_i_mpsp_uval_t uv;
            mid2_row_at(&blk, &dyn, k, &uv);
            st = ogk_i_mpsp_step_adjoint_mid2(&dyn, &ctx->traj_x[k * NX], &ctx->traj_x[(k + 1u) * NX], dt,
                                        1, &uv, NY, adj, &ctx->sens_c[blk.n * NYU]);
            blk.n += 1u;
        } else if (st == OGK_OK) {
            ogk_i_mpsp_uval_t uv;
            (void)memset(&uv, 0, sizeof uv);
            blk.hi_held = false; /* a held midpoint row is not needed in coast */
            st = ogk_i_mpsp_step_adjoint_mid2(&dyn, &ctx->traj_x[k * NX], &ctx->traj_x[(k + 1u) * NX], dt,
                                        0, &uv, NY, adj, pend);
        } else {
            /* the switch's status returned */
        }
    }
    if (st == OGK_OK) {
        recursion_finish(ctx, &blk, adj);
    }
    return st;
}

/* Backward recursion over the dense trajectory held (eqs. 28-35):
 *   w = dY/dX(tf) (selection of r, v, lambda_m);
 *   for each node k+1 (from the end): at a switch node
 *     bU(t_s) += (w dxdot / Sdot) S_U,  w := w + (w dxdot / Sdot) S_X  (eqs. 22-25);
 *   step k (node k -> k+1) in reverse, giving w := w dF/dX and bU at the
 *   stage times; B_v += bU(t) h(t)^T per block (eq. 40: dU = P dW).
 *   bU at a node time gathers stage 4 of the step below, stage 1 of the step
 *   above and any switch there, so h is evaluated once per node and once per
 *   step midpoint, and not at all in coast (U does not enter eq. 16 there). */
ogk_status ogk_mpsp_sensitivity(ogk_mpsp_t *ctx, ogk_real_t *dy_dw, ogk_real_t *dy_dlm0)
{
    ogk_status st = check_ctx(ctx);

    /* a valid trajectory has t0 and tf: n_nodes >= 2 */
    if ((st == OGK_OK) && (ctx->traj_valid == 0u)) {
        st = OGK_E_NOT_INIT;
    }
    if (st == OGK_OK) {
        ctx->sens_valid = 0u;
        st = (ctx->cfg.sens_sweep == OGK_MPSP_SWEEP_MID2) ? backward_recursion_mid2(ctx)
                                                          : backward_recursion(ctx);
    }
    if (st == OGK_OK) {
        if (!ogk_i_all_finite(ctx->dy_dw, NY * ctx->n_weights) ||
            !ogk_i_all_finite(ctx->dy_dlm0, NY)) {
            st = OGK_E_NONFINITE;
        } else {
            ctx->sens_valid = 1u;
            if (dy_dw != NULL) {
                (void)memcpy(dy_dw, ctx->dy_dw, NY * ctx->n_weights * sizeof dy_dw[0]);
            }
            if (dy_dlm0 != NULL) {
                (void)memcpy(dy_dlm0, ctx->dy_dlm0, sizeof ctx->dy_dlm0);
            }
        }
    }
    return st;
}
