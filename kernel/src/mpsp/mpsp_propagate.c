/* mpsp_propagate.c -- the MPSP trajectory: integration of eq. (16) with
 * switching detection (ogk_rk4_propagate, dense output kept in the context),
 * segment counting (N_seg of section 3.4), read-out and pchip interpolation
 * inside a segment ("interpolate the trajectory", Algorithm 1 line 4). */
#include "mpsp_internal.h"

#include <math.h>
#include <string.h>

#include "ogk/interp.h"
#include "../thrust_cmd_internal.h"

#define NX OGK_MPSP_NX

ogk_status ogk_i_mpsp_propagate_ctx(ogk_mpsp_t *ctx, const ogk_real_t *weights, ogk_real_t lambda_m0,
                              const ogk_real_t *x0, ogk_real_t thrust, ogk_mpsp_prop_t *out)
{
    ogk_i_mpsp_dyn_t dyn;
    ogk_rk4_problem_t prob;
    ogk_rk4_result_t res;
    ogk_rk4_dense_t dense;
    ogk_real_t xs[NX];
    ogk_real_t xf[NX];
    ogk_real_t u0[3];
    size_t i;
    int mode0;
    ogk_status st;

    ctx->traj_valid = 0u;
    ctx->sens_valid = 0u;
    ctx->n_nodes = 0u;
    ctx->n_switch_nodes = 0u;
    if (weights != ctx->weights) {
        (void)memcpy(ctx->weights, weights, ctx->n_weights * sizeof weights[0]);
    }
    (void)memcpy(ctx->x0, x0, sizeof ctx->x0);
    ctx->lambda_m0 = lambda_m0;
    ctx->thrust = thrust;

    (void)memcpy(xs, x0, OGK_MPSP_NX0 * sizeof xs[0]);
    xs[7] = lambda_m0;
    ogk_i_mpsp_dyn_setup(&dyn, ctx, ctx->weights, thrust);
#if defined(__SSE2__)
    /* U made two at a time is kept for the sweep (empty slots: a time no
     * node or midpoint has) */
    for (i = 0u; i < OGK_MPSP_KEEP_U_SLOTS; ++i) {
        ctx->keep_t[i] = -OGK_REAL_HUGE_VAL;
    }
    dyn.pairing = true;
    dyn.keep_t = ctx->keep_t;
    dyn.keep_u = ctx->keep_u;
#endif
    ogk_i_mpsp_rk4_problem(&prob, ctx, &dyn);
    /* Initial mode from the sign of S(t0) (eq. 11; S = 0 taken as coast). */
    ogk_i_mpsp_control_at(&dyn, ctx->cfg.t0, u0);
    if (ogk_i_mpsp_switch_value(&dyn, xs, u0) < OGK_R(0.0)) {
        mode0 = 1;
    } else {
        mode0 = 0;
    }

    dense.t = ctx->traj_t;
    dense.x = ctx->traj_x;
    dense.mode = ctx->traj_mode;
    dense.capacity = OGK_MPSP_MAX_NODES;
    dense.count = 0u;
    (void)memset(&res, 0, sizeof res);
    st = ogk_rk4_propagate(&prob, ctx->cfg.t0, xs, mode0, ctx->cfg.tf, &res, xf, &dense);
    ctx->n_nodes = dense.count;
    if ((st == OGK_OK) && (res.n_switches > OGK_MPSP_MAX_SWITCHES)) {
        st = OGK_E_SWITCH_OVERFLOW;
    }
    if ((st == OGK_OK) || (st == OGK_E_SWITCH_OVERFLOW)) {
        ctx->n_switch_nodes = res.n_switches;
        for (i = 0u; i < res.n_switches; ++i) {
            ctx->switch_node[i] = res.sw[i].dense_index;
        }
    }
    if (out != NULL) {
        (void)memset(out, 0, sizeof *out);
        (void)memcpy(out->x_f, xf, sizeof out->x_f);
        out->n_switches = (uint32_t)res.n_switches;
        for (i = 0u; (i < res.n_switches) && (i < OGK_MPSP_MAX_SWITCHES); ++i) {
            out->t_switch[i] = res.sw[i].t;
        }
        out->n_segments = (uint32_t)res.n_switches + 1u;
        /* Segments alternate starting from mode0. */
        out->n_thrust_arcs = (mode0 == 1) ? ((out->n_segments + 1u) / 2u) : (out->n_segments / 2u);
        out->mode0 = mode0;
        out->n_nodes = dense.count;
    }
    if (st == OGK_OK) {
        ctx->traj_valid = 1u;
    }
    return st;
}

static ogk_status check_inputs(const ogk_mpsp_t *ctx, const ogk_real_t *x0, ogk_real_t thrust_scale)
{
    ogk_status st = OGK_OK;

    if ((ctx == NULL) || (x0 == NULL)) {
        st = OGK_E_NULL;
    } else if (ctx->init_marker != OGK_MPSP_INIT_MARKER) {
        st = OGK_E_NOT_INIT;
    } else if (!ogk_i_all_finite(x0, OGK_MPSP_NX0) || !isfinite(thrust_scale)) {
        st = OGK_E_NONFINITE;
    } else if (!(x0[6] > OGK_R(0.0)) || !(thrust_scale > OGK_R(0.0))) {
        st = OGK_E_RANGE;
    } else {
        /* usable initial state and thrust scale */
    }
    return st;
}

ogk_status ogk_mpsp_propagate(ogk_mpsp_t *ctx, const ogk_real_t *weights, ogk_real_t lambda_m0,
                              const ogk_real_t *x0, ogk_real_t thrust_scale,
                              ogk_mpsp_prop_t *out)
{
    ogk_status st = check_inputs(ctx, x0, thrust_scale);
    if (st != OGK_OK) {
        /* the input check's status */
    } else if (weights == NULL) {
        st = OGK_E_NULL;
    } else if (!ogk_i_all_finite(weights, ctx->n_weights) || !isfinite(lambda_m0)) {
        st = OGK_E_NONFINITE;
    } else {
        st = ogk_i_mpsp_propagate_ctx(ctx, weights, lambda_m0, x0, ctx->cfg.t_max * thrust_scale, out);
    }
    return st;
}

ogk_status ogk_mpsp_trajectory(const ogk_mpsp_t *ctx, ogk_real_t *t, ogk_real_t *x,
                               uint8_t *mode, size_t capacity, size_t *count)
{
    ogk_status st = OGK_OK;

    if ((ctx == NULL) || (count == NULL)) {
        st = OGK_E_NULL;
    } else if (ctx->init_marker != OGK_MPSP_INIT_MARKER) {
        st = OGK_E_NOT_INIT;
    } else {
        *count = ctx->n_nodes;
        if (capacity < ctx->n_nodes) {
            st = OGK_E_DIM;
        } else {
            if (t != NULL) {
                (void)memcpy(t, ctx->traj_t, ctx->n_nodes * sizeof t[0]);
            }
            if (x != NULL) {
                (void)memcpy(x, ctx->traj_x, ctx->n_nodes * NX * sizeof x[0]);
            }
            if (mode != NULL) {
                (void)memcpy(mode, ctx->traj_mode, ctx->n_nodes * sizeof mode[0]);
            }
        }
    }
    return st;
}

/* The pchip state at t inside interval k of the held trajectory. */
static ogk_status state_in_interval(const ogk_mpsp_t *ctx, ogk_real_t t, size_t k, ogk_real_t *x) /* NOLINT(bugprone-easily-swappable-parameters): internal helper, its only caller (ogk_mpsp_state_at) is in this file and unit-tested */
{
    ogk_real_t slopes[4u * NX];
    size_t seg_lo = 0u;
    size_t seg_hi;
    size_t lo;
    size_t hi;
    size_t i;
    ogk_status st;

    /* The segment [seg_lo, seg_hi] holding interval k: the state's derivative
     * jumps at switch nodes, so the interpolant never reaches across one. */
    seg_hi = ctx->n_nodes - 1u;
    for (i = 0u; i < ctx->n_switch_nodes; ++i) {
        const size_t s = ctx->switch_node[i];
        /* switch nodes increase and are never node 0 (ogk_rk4_propagate), so
         * s > seg_lo holds whenever s <= k: the last such s is the lower end */
        if (s <= k) {
            seg_lo = s;
        }
        if ((s >= (k + 1u)) && (s < seg_hi)) {
            seg_hi = s;
        }
    }
    /* pchip slopes are local (a node's slope uses its two neighbours, an end
     * slope the first three nodes), so the window k-1 .. k+2 clipped to the
     * segment gives the segment-wide pchip exactly on [t_k, t_k+1]. */
    if (k > seg_lo) {
        lo = k - 1u;
    } else {
        lo = k;
    }
    if ((k + 2u) <= seg_hi) {
        hi = k + 2u;
    } else {
        hi = seg_hi;
    }
    st = ogk_interp_pchip_slopes(&ctx->traj_t[lo], hi - lo + 1u, &ctx->traj_x[lo * NX], NX,
                                 slopes);
    if (st == OGK_OK) {
        st = ogk_interp_pchip(&ctx->traj_t[lo], hi - lo + 1u, &ctx->traj_x[lo * NX], slopes,
                              NX, t, x);
    }
    return st;
}

ogk_status ogk_mpsp_state_at(const ogk_mpsp_t *ctx, ogk_real_t t, ogk_real_t *x)
{
    ogk_status st;

    if ((ctx == NULL) || (x == NULL)) {
        st = OGK_E_NULL;
    } else if ((ctx->init_marker != OGK_MPSP_INIT_MARKER) ||
               /* no trajectory held (a valid one has t0 and tf: n_nodes >= 2) */
               (ctx->traj_valid == 0u)) {
        st = OGK_E_NOT_INIT;
    } else if (!isfinite(t)) {
        st = OGK_E_NONFINITE;
    } else {
        size_t k;
        st = ogk_interp_locate(ctx->traj_t, ctx->n_nodes, t, &k);
        if (st == OGK_OK) {
            st = state_in_interval(ctx, t, k, x);
        }
    }
    return st;
}

ogk_status ogk_mpsp_control(const ogk_mpsp_t *ctx, const ogk_real_t *weights, ogk_real_t t,
                            ogk_real_t *lambda_v, ogk_real_t *lambda_v_dot)
{
    ogk_status st = OGK_OK;

    if ((ctx == NULL) || (weights == NULL) || (lambda_v == NULL)) {
        st = OGK_E_NULL;
    } else if (ctx->init_marker != OGK_MPSP_INIT_MARKER) {
        st = OGK_E_NOT_INIT;
    } else if (!isfinite(t) || !ogk_i_all_finite(weights, ctx->n_weights)) {
        st = OGK_E_NONFINITE;
    } else {
        ogk_i_mpsp_dyn_t dyn;
        ogk_real_t h[OGK_MPSP_MAX_BASIS];
        ogk_real_t hdot[OGK_MPSP_MAX_BASIS];
        ogk_i_mpsp_dyn_setup(&dyn, ctx, weights, ctx->cfg.t_max);
        ogk_i_mpsp_basis(&dyn, t, h, hdot);
        ogk_i_mpsp_control_from_basis(&dyn, h, 1u, lambda_v);
        if (lambda_v_dot != NULL) {
            ogk_i_mpsp_control_from_basis(&dyn, hdot, 1u, lambda_v_dot);
        }
        /* Finite weights can still overflow the sum, and a time far from t_ref the phase (found by
         * tests/fuzz/fuzz_mpsp_init.c): never OGK_OK with a non-finite output. */
        if ((!ogk_i_all_finite(lambda_v, OGK_MPSP_NU)) ||
            ((lambda_v_dot != NULL) && (!ogk_i_all_finite(lambda_v_dot, OGK_MPSP_NU)))) {
            st = OGK_E_NONFINITE;
        }
    }
    return st;
}

/* ogk_mpsp_thrust_cmd on a context holding a trajectory and a finite t (cmd
 * holds the safe command). */
static ogk_status thrust_cmd_held(const ogk_mpsp_t *ctx, ogk_real_t t, ogk_thrust_cmd_t *cmd)
{
    size_t k;
    ogk_status st = ogk_interp_locate(ctx->traj_t, ctx->n_nodes, t, &k);
    if (st == OGK_OK) {
        ogk_i_mpsp_dyn_t dyn;
        ogk_real_t h[OGK_MPSP_MAX_BASIS];
        ogk_real_t lv[3];
        ogk_real_t norm;
        ogk_i_mpsp_dyn_setup(&dyn, ctx, ctx->weights, ctx->thrust);
        ogk_i_mpsp_basis(&dyn, t, h, NULL);
        ogk_i_mpsp_control_from_basis(&dyn, h, 1u, lv);
        norm = OGK_HYPOT(OGK_HYPOT(lv[0], lv[1]), lv[2]);
        if (!(norm > OGK_R(0.0)) || !isfinite(norm)) {
            st = OGK_E_SAFE_COMMAND; /* no primer direction */
        } else {
            /* eq. (16) thrusts along -lambda_v; u of the segment holding t (eq. 11) */
            const ogk_real_t u[3] = {-lv[0] / norm, -lv[1] / norm, -lv[2] / norm};
            const bool thrust = ctx->traj_mode[k] != 0u;
            ogk_i_thrust_cmd_unit(cmd, t, OGK_FRAME_INERTIAL, u, thrust ? OGK_R(1.0) : OGK_R(0.0),
                                  thrust ? OGK_THRUST_FLAG_ENGINE_ON : 0u, 0u);
        }
    }
    return st;
}

ogk_status ogk_mpsp_thrust_cmd(const ogk_mpsp_t *ctx, ogk_real_t t, ogk_thrust_cmd_t *cmd)
{
    ogk_status st;

    if (cmd == NULL) {
        st = OGK_E_NULL;
    } else {
        ogk_i_thrust_cmd_safe(cmd, t, OGK_FRAME_INERTIAL, 0u);
        if (ctx == NULL) {
            st = OGK_E_NULL;
        } else if ((ctx->init_marker != OGK_MPSP_INIT_MARKER) || (ctx->traj_valid == 0u)) {
            /* no context, or no trajectory held (a held one reached tf: >= 2 nodes) */
            st = OGK_E_NOT_INIT;
        } else if (!isfinite(t)) {
            st = OGK_E_NONFINITE;
        } else {
            st = thrust_cmd_held(ctx, t, cmd);
        }
    }
    return st;
}
