/* nmpc_sqp.c -- the NMPC's SQP on the multiple-shooting transcription
 * (docs/design/nmpc.md, "Flight solver"):
 *   1. every interval F_k with its exact sensitivities (nmpc_shoot.c);
 *   2. the state corrections condensed away (nmpc_condense.c):
 *      dX_{k+1} = A_k dX_k + B0_k dU_k + B1_k dU_{k+1} + t_k dT + d_k,
 *      dX_0 = 0 (d_k = F_k - X_{k+1}), so the
 *      QP unknowns are v = (dU_0 .. dU_N, dT) and only dX_N enters it
 *      (no path constraints on the states);
 *   3. the QP  min g^T v + 1/2 v^T H v  s.t. the linearised eq. (5), throttle
 *      and horizon bounds, a box on each step, the optional sweep bound;
 *      H the exact reduced Hessian of the Lagrangian, convexified
 *      (nmpc_hess.c; its per-interval blocks computed with the
 *      sensitivities, the intervals swept from the last to the first so
 *      that each one's continuity multiplier is known), or a damped-BFGS
 *      (Powell) approximation carried from solve to solve;
 *   4. a filter line search (Waechter & Biegler, Math. Prog. 106, 2006,
 *      sec. 2.3, without its restoration phase) on the pair (theta, J),
 *      theta = sum |d_k|_1 + |c|_1: an l1 merit function with Armijo
 *      backtracking stalled on the Maratos effect (steps of 1/32 for
 *      hundreds of iterations near the solution; docs/design/nmpc.md).
 * Converged when every defect and terminal residual is within tol_feas and
 * either |H v|_inf (the reduced stationarity residual) is within tol_stat or
 * the step's predicted |dJ| within tol_obj max(|J|, 1): minimum-fuel
 * objectives are so flat in T that BFGS creeps for hundreds of iterations
 * at 1e-5 stationarity with J fixed to 1e-7 (docs/design/nmpc.md). */
#include "nmpc_internal.h"

#include <math.h>
#include <string.h>

#include "../ogk_checks.h"

#if (OGK_NMPC_MAX_QP > OGK_QP_MAX_N) || (OGK_NMPC_NC > OGK_QP_MAX_EQ) || (OGK_NMPC_MAX_ROWS > OGK_QP_MAX_IN)
#error "ogk/qp.h limits too small for ogk/nmpc.h (OGK_NMPC_MAX_QP unknowns, OGK_NMPC_MAX_ROWS inequality rows)"
#endif

#define NX ((size_t)OGK_NMPC_NX)
#define NC ((size_t)OGK_NMPC_NC)
#define NCOL OGK_I_NMPC_MAX_COLS
#define MAXV OGK_NMPC_MAX_VARS

/* Armijo constant and backtracking factor of the line search. */
#define ARMIJO_C1 OGK_R(1.0e-4)
#define BACKTRACK OGK_R(0.5)
/* Filter line search constants (Waechter & Biegler 2006, sec. 2.3). */
#define FILTER_SIZE 32u
#define FILTER_GAMMA OGK_R(1.0e-5)
#define FILTER_S_THETA OGK_R(1.1)
#define FILTER_S_PHI OGK_R(2.3)
/* Curvature of the elastic slacks, relative to elastic_weight. The QP (a dual
 * active-set method) starts from its unconstrained minimum, where each slack
 * is -1 / ELASTIC_CURVATURE: -1e6 in double. Float resolves x there to eps 1e6
 * = 0.12 absolute, and the step that removes a residual of the states' rounding
 * (1e-7) came out as full throttle (test_nmpc_edge_cases
 * solve_solar_engine_and_bodies: the QP's step burned 0.0255 where a slack of
 * 1e-7 costs 1e-4). In float the slacks start at -1: the slack's price at 0 is
 * w in both (the l1 penalty stays exact); a slack s > 0 costs w (s + s^2 / 2)
 * instead of w (s + 1e-6 s^2 / 2). */
#if OGK_REAL_SINGLE
#define ELASTIC_CURVATURE OGK_R(1.0)
#else
#define ELASTIC_CURVATURE OGK_R(1.0e-6)
#endif
/* Restarts (scaled-identity Hessian, empty filter) after a failed line search. */
#define MAX_RESTARTS 2u
/* Smallest step box (fraction of step_max_*) and the smallest step taken as
 * a BFGS pair. */
#define BOX_MIN OGK_R(1.0e-3)
#define BFGS_MIN_ALPHA OGK_R(0.1)
/* Feasibility steps per solve, and the largest violation they are tried at. */
#define MAX_RESTORES 3u
#define RESTORE_VIOL_MAX OGK_R(1.0e-4)
/* Factor on the step box of a QP retried after OGK_E_INFEASIBLE. */
#define BOX_OPEN OGK_R(1.0e3)
/* The exact Hessian is held (reused, its shift moved to the new rows of
 * eq. 5) for the next iteration while the solve is in its Newton phase: the
 * step of an exact Hessian (computed or held) that factored with its shift
 * alone was taken in full at its first trial, and either it is a warm solve's
 * first step or its QP's predicted |dJ| is at most HESS_HOLD_RATE times the
 * last iteration's. The test compares successive predictions, not the stop:
 * a converging Newton sequence contracts them quadratically (the benchmark's
 * re-solve: 1.1e-3, 2.8e-6: a ratio of 2.6e-3), far below the rate; a step
 * that does not contract gets a fresh Hessian at the next iteration. With
 * 0.1 the far-guess solve of test_mcdc_nmpc.c held at a ratio of 0.095
 * with its violation still at 2e-2, and took 20 iterations instead of 18
 * (docs/design/nmpc-flight.md, section 2e). */
#define HESS_HOLD_RATE OGK_R(0.03)

#if OGK_REAL_SINGLE
/* The float build's floors under the convergence tests (docs/design/nmpc-flight.md,
 * section 2g, "Single precision"). The default tolerances (tol_feas 1e-9, tol_obj 1e-7) are
 * at or below float's resolution: a defect of states of size 1.5 carries 2 to 4
 * ulps of rounding (measured 2.4e-7 to 4.8e-7 at every converged iterate of the
 * unit tests), and the QP's predicted |dJ| of a converged iterate 0.4 to 2.5 eps
 * |J| (its step moves the states by their rounding). Whether such a value passes
 * a test at its level is a coin flip of the rounding: the outcome (converged or
 * not, the iteration count) then differed between the host and the M4F.
 * FEAS_FLOOR  tol_feas is read as at least 32 eps max(1, |x|_inf of the start):
 *             8x the defects' measured rounding;
 * OBJ_FLOOR   a positive tol_obj as at least 16 eps (1.9e-6): 6x the predicted
 *             |dJ| of a converged iterate;
 * STEP_FLOOR  a feasible iterate whose QP step is within 16 ulps of every unknown
 *             (|v_i| <= 16 eps max(1, |w_i|), w the controls and T) and whose
 *             stationarity is what such a step gives on the first Hessian
 *             (|(H v)_i| <= hessian_init 16 eps max(1, |w_i|)) has converged: the
 *             step only undoes the rounding of the defects (float cannot resolve a
 *             smaller one; measured: the re-solve from test_proximity's float optimum,
 *             6.0 ulps and stat 7.2e-7 on H = I, then 7 steps of unchanged J). Both
 *             halves: a step of 50 ulps on a large BFGS curvature had stat 1.6e-3 at
 *             10 times that optimum's J, a stat of 6.7e-7 came with a step of 1.4e4 ulps;
 * and a line search that finds no acceptable trial from a feasible iterate
 * (viol <= tol_feas, T within its bounds) whose step predicts |dJ| within
 * float's noise (sqp_noise_floor) has met
 * float's resolution of the stationarity: converged (with tol_obj = 0 too: the
 * filter cannot rank trials whose theta and J differ by rounding alone). */
#define FEAS_FLOOR (OGK_R(32.0) * OGK_REAL_EPSILON)
#define OBJ_FLOOR (OGK_R(16.0) * OGK_REAL_EPSILON)
#define STOP_NOISE (OGK_R(2.0) * OGK_REAL_EPSILON)
#define STEP_FLOOR (OGK_R(16.0) * OGK_REAL_EPSILON)
#define SQP_TOL_FEAS tol_feas
#define SQP_TOL_OBJ tol_obj
#else
#define SQP_TOL_FEAS (cfg->tol_feas)
#define SQP_TOL_OBJ (cfg->tol_obj)
#endif


#if OGK_REAL_SINGLE
/* True when the step's predicted change dphi of the merit's J is within what
 * float resolves of it: STOP_NOISE max(|J|, 1) (2 ulps of J's operands, of
 * size 1 in the kernel's units: not OBJ_FLOOR, for a J much smaller than its
 * operands, the propellant m_0 - m_N of test_proximity, makes real progress in
 * steps of 1e-7: a trial with 16 eps stopped it at 10 times its optimum), plus
 * the change the QP's own
 * restoration of the rounded defects makes, to first order |y|_1 theta0 (the
 * multipliers of eq. 5 times the l1 violation; measured: the minimum-fuel coast
 * of test_nmpc.c, |y|_1 = 174, theta0 = 6e-7: dphi 3.4e-6 against 1.1e-4, and
 * J = 3.5e-6 unchanged to its last bit at every trial). */
static bool sqp_noise_floor(const ogk_nmpc_t *ctx, ogk_real_t dphi, ogk_real_t phi0, ogk_real_t theta0)
{
    ogk_real_t y1 = OGK_R(0.0);
    size_t i;
    for (i = 0u; i < NC; ++i) {
        y1 += OGK_FABS(ctx->qp_sol.y_eq[i]);
    }
    return OGK_FABS(dphi) <= ((STOP_NOISE * ((OGK_FABS(phi0) > OGK_R(1.0)) ? OGK_FABS(phi0) : OGK_R(1.0)))
                              + (y1 * theta0));
}
#endif

static size_t n_vars(const ogk_nmpc_plan_t *p)
{
    return ((size_t)p->nodes + 1u) * (size_t)p->nu + 1u;
}

/* True when eq. (5) is a terminal set (a half-width > 0): its rows are then
 * two inequalities each, not equalities (docs/design/nmpc-flight.md, "Robustness"). */
static bool terminal_set(const ogk_nmpc_config_t *cfg)
{
    return (cfg->terminal_box[0] > OGK_R(0.0)) || (cfg->terminal_box[1] > OGK_R(0.0))
        || (cfg->terminal_box[2] > OGK_R(0.0)) || (cfg->terminal_box[3] > OGK_R(0.0));
}

/* The merit's objective: J, plus with a terminal set its l1 excess priced at
 * elastic_weight (an exact penalty: the set is reached whenever the vehicle
 * can reach it, and otherwise the plan ends as close to it as it can). */
static ogk_real_t penalized(const ogk_nmpc_config_t *cfg, const ogk_nmpc_plan_t *p, ogk_real_t t_excess)
{
    return ogk_i_nmpc_objective(cfg, p) + (cfg->elastic_weight * t_excess);
}

/* How far terminal residual i lies outside its half-width (|c_i| for eq. 5
 * exactly: |c_i| - 0 is |c_i| to the bit). */
static ogk_real_t terminal_excess(const ogk_nmpc_config_t *cfg, const ogk_real_t *c, size_t i)
{
    const ogk_real_t e = OGK_FABS(c[i]) - cfg->terminal_box[i];
    return (e > OGK_R(0.0)) ? e : OGK_R(0.0);
}

/* Merit pieces of a plan: l1 and max norms of every defect and terminal
 * residual. Stores F_k and the sensitivities in ctx when with_sens. */
static ogk_status evaluate(ogk_nmpc_t *ctx, const ogk_nmpc_plan_t *p,
                           bool with_sens, const ogk_real_t *y, ogk_real_t *viol_l1, ogk_real_t *viol_max, /* NOLINT(bugprone-easily-swappable-parameters): internal helper, outputs in the order of the merit pair (l1, max) and c; every caller is in this file */
                           ogk_real_t *c_term, ogk_real_t *t_excess)
{
    ogk_status st = OGK_OK;
    const uint32_t nu = p->nu;
    const ogk_real_t h = p->horizon / (ogk_real_t)p->nodes;
    /* the exact Hessian's blocks come with the sensitivities, for the
     * multipliers y of eq. (5); the intervals then go from the last to the
     * first, carrying the continuity multiplier w backwards */
    const ogk_real_t *y_w = with_sens ? y : NULL; /* y != NULL only with the exact Hessian (both callers) */
    const bool second = y_w != NULL;
    ogk_real_t sens[NX * NCOL];
    ogk_real_t x1[NX];
    ogk_real_t w[NX];
    ogk_real_t l1 = OGK_R(0.0);
    ogk_real_t mx = OGK_R(0.0);
    /* nodes <= OGK_NMPC_MAX_NODES (ogk_nmpc_init, load_plan): clamped once, a fixed bound */
    const size_t nodes = ogk_i_min_size(p->nodes, OGK_NMPC_MAX_NODES);
    const ogk_i_ocp_t ocp = ogk_i_nmpc_problem(ctx);
    size_t n;
    size_t i;
    size_t j;

    (void)memset(sens, 0, sizeof(sens));
    if (with_sens) {
        ogk_i_nmpc_cache_begin(ctx);
    }
    if (second) {
        /* w_{N-1} = dJ/dX_N - dc/dX_N^T y (c of eq. 5: the first four states) */
        for (i = 0u; i < NC; ++i) {
            w[i] = -y_w[i];
        }
        w[4] = (ctx->cfg.objective == OGK_NMPC_MIN_FUEL) ? -OGK_R(1.0) : OGK_R(0.0);
    }
    for (n = 0u; (n < nodes) && (st == OGK_OK); ++n) {
        const size_t k = second ? ((size_t)p->nodes - 1u - n) : n;
        const ogk_real_t t_start = p->t0 + ((ogk_real_t)k * h);
        ogk_real_t key[OGK_NMPC_SENS_KEY];
        /* the same inputs as the slot's: its F_k and sensitivities are this
         * sweep's bits (nmpc_sens_cache.c); the exact Hessian needs the
         * sweep's tape, and its slots are only forgotten */
        const bool keyed = with_sens && !second;
        const size_t n_key = keyed ? ogk_i_nmpc_cache_key(ctx, p, k, t_start, h, key) : 0u;
        const bool hit = keyed && ogk_i_nmpc_cache_hit(ctx, k, key, n_key);
        ogk_i_nmpc_arc_t arc;
        ogk_i_nmpc_arc_start(&ocp, p, k, &arc);
        if (hit) {
            (void)memcpy(x1, &ctx->sens_f[k * NX], sizeof(x1));
            arc.viol_sum = ctx->arc_viol[2u * k];
            arc.viol_max = ctx->arc_viol[(2u * k) + 1u];
        } else {
            st = ogk_i_nmpc_shoot_arc(&ocp, nu, t_start, h, &p->x[k * NX], &p->u[k * nu],
                                      &p->u[(k + 1u) * nu], x1, with_sens ? sens : NULL,
                                      second ? ctx->tape : NULL, &arc, NULL);
        }
        if (st == OGK_OK) {
            /* the keep-out along the arc */
            l1 += arc.viol_sum;
            mx = (arc.viol_max > mx) ? arc.viol_max : mx;
            if (with_sens && !hit) {
                for (i = 0u; i < OGK_OCP_MAX_KEEPOUT; ++i) {
                    ctx->arc_mask[(k * OGK_OCP_MAX_KEEPOUT) + i] = arc.mask[i];
                }
                ctx->arc_viol[2u * k] = arc.viol_sum;
                ctx->arc_viol[(2u * k) + 1u] = arc.viol_max;
            }
            for (i = 0u; i < NX; ++i) {
                const ogk_real_t d = x1[i] - p->x[((k + 1u) * NX) + i];
                l1 += OGK_FABS(d);
                mx = (OGK_FABS(d) > mx) ? OGK_FABS(d) : mx;
            }
            if (with_sens && !hit) {
                const size_t col_h = NX + (2u * (size_t)nu);
                (void)memcpy(&ctx->sens_f[k * NX], x1, sizeof(x1));
                for (i = 0u; i < NX; ++i) {
                    for (j = 0u; j < NX; ++j) {
                        ctx->sens_a[(k * NX * NX) + (i * NX) + j] = sens[(i * NCOL) + j];
                    }
                    for (j = 0u; j < nu; ++j) {
                        ctx->sens_b0[(k * NX * nu) + (i * nu) + j] = sens[(i * NCOL) + NX + j];
                        ctx->sens_b1[(k * NX * nu) + (i * nu) + j] = sens[(i * NCOL) + NX + nu + j];
                    }
                    ctx->sens_h[(k * NX) + i] = sens[(i * NCOL) + col_h];
                    ctx->sens_ts[(k * NX) + i] = sens[(i * NCOL) + col_h + 1u];
                }
                ogk_i_nmpc_cache_store(ctx, k, keyed ? key : NULL);
            }
            if (with_sens) {
                /* h = T / N and t_start = t0 + k T / N */
                for (i = 0u; i < NX; ++i) {
                    ctx->sens_t[(k * NX) + i] = (ctx->sens_h[(k * NX) + i]
                        + ((ogk_real_t)k * ctx->sens_ts[(k * NX) + i])) / (ogk_real_t)p->nodes;
                }
            }
            if (second) {
                /* the interval's block in the context's scratch (free until condensing), not on the stack */
                ogk_real_t *w_int = ctx->hess_tmp;
                ogk_real_t w_prev[NX];
                ogk_i_nmpc_shoot_hess(&ocp, nu, t_start, h, &p->u[k * nu], &p->u[(k + 1u) * nu],
                                      ctx->tape, w, w_int);
                ogk_i_nmpc_hess_block(nu, ogk_i_nmpc_ncol(&ocp, nu), k, p->nodes, w_int,
                                      &ctx->hess_blk[k * OGK_NMPC_MAX_DIR * OGK_NMPC_MAX_DIR]);
                /* w_{k-1} = A_k^T w_k */
                for (j = 0u; j < NX; ++j) {
                    ogk_real_t acc = OGK_R(0.0);
                    for (i = 0u; i < NX; ++i) {
                        acc += sens[(i * NCOL) + j] * w[i];
                    }
                    w_prev[j] = acc;
                }
                (void)memcpy(w, w_prev, sizeof(w));
            }
        }
    }
    if (st == OGK_OK) {
        ogk_i_nmpc_terminal(&ocp, &p->x[(size_t)p->nodes * NX], p->t0 + p->horizon, c_term, NULL);
        *t_excess = OGK_R(0.0);
        for (i = 0u; i < NC; ++i) {
            const ogk_real_t e = terminal_excess(&ctx->cfg, c_term, i);
            if (terminal_set(&ctx->cfg)) {
                /* the terminal set is elastic: its excess is priced in the merit's
                 * objective (penalized), not in its violation */
                *t_excess += e;
            } else {
                l1 += e;
                mx = (e > mx) ? e : mx;
            }
        }
        if (ctx->cfg.mass_min > OGK_R(0.0)) {
            /* the propellant limit (m decreases along the arcs: the final node bounds them) */
            const ogk_real_t e = ctx->cfg.mass_min - p->x[((size_t)p->nodes * NX) + 4u];
            if (e > OGK_R(0.0)) {
                l1 += e;
                mx = (e > mx) ? e : mx;
            }
        }
        ogk_i_nmpc_keepout_violation(&ocp, p, &l1, &mx);
        *viol_l1 = l1;
        *viol_max = mx;
    }
    return st;
}

/* Bounds of the QP unknowns and its inequality rows: the sweep rows, the
 * keep-out rows, then (a terminal set) two rows per condition of eq. (5),
 * lower then upper, and the propellant row; returns the number of rows.
 * Needs the linear terms (qp_aeq, qp_beq) of the iterate. */
static size_t build_bounds(ogk_nmpc_t *ctx, const ogk_nmpc_plan_t *p, size_t nv, /* NOLINT(bugprone-easily-swappable-parameters): internal helper, nv and the box factor; every caller is in this file */
                           ogk_real_t box_scale)
{
    const uint32_t nu = p->nu;
    const ogk_nmpc_config_t *cfg = &ctx->cfg;
    size_t rows = 0u;
    /* nodes <= OGK_NMPC_MAX_NODES (ogk_nmpc_init, load_plan) and ko_rows <= OGK_NMPC_MAX_NODES
     * (ogk_i_nmpc_keepout_rows): clamped once so each loop keeps a fixed bound */
    const uint32_t nodes = ogk_i_min_u32(p->nodes, OGK_NMPC_MAX_NODES);
    const size_t ko_rows = ogk_i_min_size(ctx->ko_rows, OGK_I_NMPC_MAX_KO_ROWS_Z);
    uint32_t k;
    ogk_real_t lo;
    ogk_real_t hi;

    for (k = 0u; k <= nodes; ++k) {
        ctx->qp_lb[(size_t)k * nu] = -cfg->step_max_alpha * box_scale;
        ctx->qp_ub[(size_t)k * nu] = cfg->step_max_alpha * box_scale;
        if (nu > 1u) {
            const ogk_real_t w = p->u[((size_t)k * nu) + 1u];
            lo = -w;
            hi = OGK_R(1.0) - w;
            ctx->qp_lb[((size_t)k * nu) + 1u] = (lo < hi) ? lo : hi;
            ctx->qp_ub[((size_t)k * nu) + 1u] = hi;
        }
    }
    lo = cfg->horizon_min - p->horizon;
    hi = cfg->horizon_max - p->horizon;
    lo = (lo > (-cfg->step_max_horizon * box_scale)) ? lo : (-cfg->step_max_horizon * box_scale);
    hi = (hi < (cfg->step_max_horizon * box_scale)) ? hi : (cfg->step_max_horizon * box_scale);
    ctx->qp_lb[nv - 1u] = lo;
    ctx->qp_ub[nv - 1u] = (hi > lo) ? hi : lo;
    if (cfg->max_sweep > OGK_R(0.0)) {
        (void)memset(ctx->qp_ain, 0, 2u * (size_t)p->nodes * nv * sizeof(ogk_real_t));
        for (k = 0u; k < nodes; ++k) {
            const ogk_real_t sweep = p->u[((size_t)k + 1u) * nu] - p->u[(size_t)k * nu];
            /* -max <= sweep + da_{k+1} - da_k <= max */
            ctx->qp_ain[(rows * nv) + (((size_t)k + 1u) * nu)] = OGK_R(1.0);
            ctx->qp_ain[(rows * nv) + ((size_t)k * nu)] = -OGK_R(1.0);
            ctx->qp_bin[rows] = -cfg->max_sweep - sweep;
            ++rows;
            ctx->qp_ain[(rows * nv) + (((size_t)k + 1u) * nu)] = -OGK_R(1.0);
            ctx->qp_ain[(rows * nv) + ((size_t)k * nu)] = OGK_R(1.0);
            ctx->qp_bin[rows] = -cfg->max_sweep + sweep;
            ++rows;
        }
    }
    for (k = 0u; k < ko_rows; ++k) {
        (void)memcpy(&ctx->qp_ain[rows * nv], &ctx->ko_a[(size_t)k * nv], nv * sizeof(ogk_real_t));
        ctx->qp_bin[rows] = ctx->ko_b[k];
        ++rows;
    }
    if (terminal_set(cfg)) {
        size_t i;
        size_t c;
        for (i = 0u; i < NC; ++i) {
            /* b - half <= A_i v <= b + half, b = -(c_i + e_i): the linearised
             * residual c_i + e_i + A_i v within +-half */
            for (c = 0u; c < nv; ++c) {
                ctx->qp_ain[(rows * nv) + c] = ctx->qp_aeq[(i * nv) + c];
                ctx->qp_ain[((rows + 1u) * nv) + c] = -ctx->qp_aeq[(i * nv) + c];
            }
            ctx->qp_bin[rows] = ctx->qp_beq[i] - cfg->terminal_box[i];
            ctx->qp_bin[rows + 1u] = -ctx->qp_beq[i] - cfg->terminal_box[i];
            rows += 2u;
        }
    }
    if (cfg->mass_min > OGK_R(0.0)) {
        /* m_N + dm_N >= mass_min, dm_N = G_N[4] v + e_N[4] */
        (void)memcpy(&ctx->qp_ain[rows * nv], &ctx->cond_g[4u * nv], nv * sizeof(ogk_real_t));
        ctx->qp_bin[rows] = cfg->mass_min - p->x[((size_t)p->nodes * NX) + 4u] - ctx->cond_e[4];
        ++rows;
    }
    return rows;
}

/* Index of the first terminal-set row in the rows of build_bounds. */
static size_t terminal_row0(const ogk_nmpc_t *ctx, const ogk_nmpc_plan_t *p)
{
    const size_t sweep_rows = (ctx->cfg.max_sweep > OGK_R(0.0)) ? (2u * (size_t)p->nodes) : 0u;
    return sweep_rows + ogk_i_min_size(ctx->ko_rows, OGK_I_NMPC_MAX_KO_ROWS_Z);
}

/* With a terminal set, the QP's multipliers of eq. (5)'s conditions are
 * those of their two rows (y_lo - y_hi: the signed multiplier of c_i). */
static void terminal_multipliers(ogk_nmpc_t *ctx, size_t row0)
{
    if (terminal_set(&ctx->cfg)) {
        size_t i;
        for (i = 0u; i < NC; ++i) {
            ctx->qp_sol.y_eq[i] = ctx->qp_sol.y_in[row0 + (2u * i)] - ctx->qp_sol.y_in[row0 + (2u * i) + 1u];
        }
    }
}

/* The terminal set's excess after an elastic QP's step: the sum of its slacks. */
static ogk_real_t elastic_excess(const ogk_nmpc_t *ctx, size_t nv)
{
    ogk_real_t sum = OGK_R(0.0);
    size_t i;
    for (i = nv; i < (nv + (2u * NC)); ++i) {
        sum += ctx->qp_sol.x[i];
    }
    return sum;
}

/* trial = work + alpha * step */
static void take_step(const ogk_nmpc_t *ctx, const ogk_nmpc_plan_t *p, const ogk_real_t *v,
                      size_t nv, ogk_real_t alpha, ogk_nmpc_plan_t *trial)
{
    const uint32_t nu = p->nu;
    size_t i;
    (void)memcpy(trial, p, sizeof(*trial));
    for (i = NX; i < (((size_t)p->nodes + 1u) * NX); ++i) {
        trial->x[i] = p->x[i] + (alpha * ctx->dx[i]);
    }
    for (i = 0u; i < (((size_t)p->nodes + 1u) * nu); ++i) {
        trial->u[i] = p->u[i] + (alpha * v[i]);
    }
    if (nu > 1u) {
        /* the QP's throttle bounds are exact; clip rounding only */
        for (i = 0u; i <= (size_t)p->nodes; ++i) {
            ogk_real_t w = trial->u[(i * nu) + 1u];
            w = (w < OGK_R(0.0)) ? OGK_R(0.0) : w;
            trial->u[(i * nu) + 1u] = (w > OGK_R(1.0)) ? OGK_R(1.0) : w;
        }
    }
    trial->horizon = p->horizon + (alpha * v[nv - 1u]);
}

/* The elastic QP (SNOPT's elastic mode, on eq. 5 only): unknowns
 * (v, s+, s-), A_eq v + s+ - s- = b_eq, s+-  >= 0, cost + elastic_weight
 * (s+ + s-) and a small curvature on the slacks (the QP needs H > 0). With a
 * terminal set the slacks relax its rows instead (row0: the first), s+ the
 * lower and s- the upper one of each condition. ko_n > 0: the keep-out rows
 * ko_row0 .. ko_row0 + ko_n - 1 relaxed too, by one more slack s_ko >= 0
 * (a_j v + s_ko >= b_j, an l-infinity penalty priced as eq. 5's). */
static ogk_status solve_elastic_rows(ogk_nmpc_t *ctx, const ogk_real_t *hess, const ogk_real_t *g_obj, /* NOLINT(bugprone-easily-swappable-parameters): internal helper, the QP's (H, g) in order; its callers are in this file */
                                     size_t nv, size_t rows, size_t row0, /* NOLINT(bugprone-easily-swappable-parameters): as above, sizes (unknowns, inequality rows, first terminal row) */
                                     size_t ko_row0, size_t ko_n) /* NOLINT(bugprone-easily-swappable-parameters): the keep-out rows (first, count) */
{
    const size_t ne = (nv + (2u * NC)) + ((ko_n > 0u) ? 1u : 0u);
    const ogk_real_t w = ctx->cfg.elastic_weight;
    const bool eq5 = !terminal_set(&ctx->cfg);
    ogk_qp_problem_t qp;
    size_t i;
    size_t j;

    (void)memset(ctx->el_h, 0, ne * ne * sizeof(ogk_real_t));
    for (i = 0u; i < nv; ++i) {
        for (j = 0u; j < nv; ++j) {
            ctx->el_h[(i * ne) + j] = hess[(i * nv) + j];
        }
        ctx->el_g[i] = g_obj[i];
        ctx->el_lb[i] = ctx->qp_lb[i];
        ctx->el_ub[i] = ctx->qp_ub[i];
    }
    for (i = nv; i < ne; ++i) {
        ctx->el_h[(i * ne) + i] = ELASTIC_CURVATURE * w;
        ctx->el_g[i] = w;
        ctx->el_lb[i] = OGK_R(0.0);
        ctx->el_ub[i] = OGK_QP_INF;
    }
    for (i = 0u; i < NC; ++i) {
        for (j = 0u; j < nv; ++j) {
            ctx->el_aeq[(i * ne) + j] = ctx->qp_aeq[(i * nv) + j];
        }
        for (j = nv; j < ne; ++j) {
            ctx->el_aeq[(i * ne) + j] = OGK_R(0.0);
        }
        ctx->el_aeq[(i * ne) + nv + i] = OGK_R(1.0);
        ctx->el_aeq[(i * ne) + nv + NC + i] = -OGK_R(1.0);
    }
    for (i = 0u; i < rows; ++i) {
        for (j = 0u; j < nv; ++j) {
            ctx->el_ain[(i * ne) + j] = ctx->qp_ain[(i * nv) + j];
        }
        for (j = nv; j < ne; ++j) {
            ctx->el_ain[(i * ne) + j] = OGK_R(0.0);
        }
    }
    if (!eq5) {
        for (i = 0u; i < NC; ++i) {
            ctx->el_ain[((row0 + (2u * i)) * ne) + nv + i] = OGK_R(1.0);
            ctx->el_ain[((row0 + (2u * i) + 1u) * ne) + nv + NC + i] = OGK_R(1.0);
        }
    }
    {
        /* the keep-out rows within the rows built (clamped once: one bound for the loop) */
        const size_t ko_end = ogk_i_min_size(ko_row0 + ko_n, rows);
        for (i = ko_row0; i < ko_end; ++i) {
            ctx->el_ain[(i * ne) + (ne - 1u)] = OGK_R(1.0);
        }
    }
    qp.n = ne;
    qp.m_eq = eq5 ? NC : 0u;
    qp.m_in = rows;
    qp.H = ctx->el_h;
    qp.g = ctx->el_g;
    qp.A_eq = eq5 ? ctx->el_aeq : NULL;
    qp.b_eq = eq5 ? ctx->qp_beq : NULL;
    qp.A_in = (rows > 0u) ? ctx->el_ain : NULL;
    qp.b_in = (rows > 0u) ? ctx->qp_bin : NULL;
    qp.lb = ctx->el_lb;
    qp.ub = ctx->el_ub;
    return ogk_qp_solve(&ctx->qp_ws, &qp, &ctx->qp_sol);
}

/* The elastic QP on eq. (5) (or the terminal set's rows) only. */
static ogk_status solve_elastic(ogk_nmpc_t *ctx, const ogk_real_t *hess, const ogk_real_t *g_obj, /* NOLINT(bugprone-easily-swappable-parameters): as solve_elastic_rows */
                                size_t nv, size_t rows, size_t row0) /* NOLINT(bugprone-easily-swappable-parameters): as solve_elastic_rows */
{
    return solve_elastic_rows(ctx, hess, g_obj, nv, rows, row0, 0u, 0u);
}

/* Reduced gradient of the Lagrangian, g - A_eq^T y. */
static void lagrangian_gradient(const ogk_nmpc_t *ctx, size_t nv, const ogk_real_t *g_obj, /* NOLINT(bugprone-easily-swappable-parameters): internal helper, the order of g - A_eq^T y; every caller is in this file */
                                const ogk_real_t *y, ogk_real_t *out)
{
    size_t c;
    size_t i;
    for (c = 0u; c < nv; ++c) {
        ogk_real_t acc = g_obj[c];
        for (i = 0u; i < NC; ++i) {
            acc -= ctx->qp_aeq[(i * nv) + c] * y[i];
        }
        out[c] = acc;
    }
}

/* The step's QP on the context's linearised eq. (5), bounds and sweep rows,
 * with the Hessian and linear term given. */
static void step_qp(const ogk_nmpc_t *ctx, size_t nv, size_t rows, const ogk_real_t *hess, /* NOLINT(bugprone-easily-swappable-parameters): internal helper, the QP's sizes then its H and g; callers in this file only */
                    const ogk_real_t *g, ogk_qp_problem_t *qp)
{
    const bool eq5 = !terminal_set(&ctx->cfg);
    qp->n = nv;
    qp->m_eq = eq5 ? NC : 0u;
    qp->m_in = rows;
    qp->H = hess;
    qp->g = g;
    qp->A_eq = eq5 ? ctx->qp_aeq : NULL;
    qp->b_eq = eq5 ? ctx->qp_beq : NULL;
    qp->A_in = (rows > 0u) ? ctx->qp_ain : NULL;
    qp->b_in = (rows > 0u) ? ctx->qp_bin : NULL;
    qp->lb = ctx->qp_lb;
    qp->ub = ctx->qp_ub;
}

/* Minimum-norm feasibility step: the QP with H = I and g = 0 on the same
 * constraints, taken whole when it lowers the l1 violation. True when taken
 * (the iterate moved; the BFGS pair of this step is skipped). */
static bool feasibility_step(ogk_nmpc_t *ctx, ogk_nmpc_plan_t *p, size_t nv, size_t rows, /* NOLINT(bugprone-easily-swappable-parameters): internal helper, the sizes of the QP (unknowns, rows) and the violation to beat; its only caller is ogk_i_nmpc_sqp */
                             ogk_real_t viol_l1, ogk_nmpc_report_t *rep)
{
    ogk_qp_problem_t qp;
    ogk_real_t zero[MAXV];
    ogk_real_t t_l1 = OGK_R(0.0);
    ogk_real_t t_max = OGK_R(0.0);
    bool taken = false;
    (void)memset(zero, 0, sizeof(zero));
    ogk_i_nmpc_identity(ctx->el_h, nv, OGK_R(1.0));
    step_qp(ctx, nv, rows, ctx->el_h, zero, &qp);
    if (ogk_qp_solve(&ctx->qp_ws, &qp, &ctx->qp_sol) == OGK_OK) {
        ogk_real_t c_trial[NC];
        ogk_real_t t_exc = OGK_R(0.0);
        rep->qp_iterations += (uint32_t)ctx->qp_sol.iterations;
        ogk_i_nmpc_expand_step(ctx, p, ctx->qp_sol.x, nv);
        take_step(ctx, p, ctx->qp_sol.x, nv, OGK_R(1.0), &ctx->trial);
        if ((evaluate(ctx, &ctx->trial, false, NULL, &t_l1, &t_max, c_trial, &t_exc) == OGK_OK)
            && (t_l1 < viol_l1)) {
            (void)memcpy(p, &ctx->trial, sizeof(*p));
            taken = true;
        }
    }
    return taken;
}

ogk_status ogk_i_nmpc_sqp(ogk_nmpc_t *ctx, ogk_real_t *hess, bool cold,
                          ogk_nmpc_report_t *rep)
{
    ogk_nmpc_plan_t *p = &ctx->work;
    const ogk_nmpc_config_t *cfg = &ctx->cfg;
    const size_t nv = n_vars(p);
    /* max_iter, max_iter_cold <= OGK_NMPC_MAX_SQP_ITER (ogk_nmpc_init): clamped once so
     * the iteration loop keeps a fixed bound */
    const uint32_t iter_req = cold ? cfg->max_iter_cold : cfg->max_iter;
    const uint32_t iter_limit = ogk_i_min_u32(iter_req, OGK_NMPC_MAX_SQP_ITER);
    ogk_status st = OGK_OK;
    bool done = false;
    bool have_prev = false;
    bool first_update = cold;
    ogk_real_t g_obj[MAXV];
    ogk_real_t grad_new[MAXV];
    ogk_real_t c_term[NC];
    ogk_real_t c_trial[NC];
    ogk_real_t y_prev[NC];
    ogk_real_t filter_theta[FILTER_SIZE];
    ogk_real_t filter_phi[FILTER_SIZE];
    uint32_t n_filter = 0u;
    uint32_t filter_next = 0u;
    ogk_real_t theta_max = OGK_R(0.0);
    ogk_real_t theta_min = OGK_R(0.0);
    bool first_iter = true;
    bool flat = false;
    bool restored = false;
    uint32_t restarts = 0u;
    uint32_t restores = 0u;
    ogk_real_t box = OGK_R(1.0);
    bool have_eval = false;
    ogk_real_t first_l1 = OGK_R(0.0);
    ogk_real_t first_max = OGK_R(0.0);
    ogk_real_t viol_l1 = OGK_R(0.0);
    ogk_real_t viol_max = OGK_R(0.0);
    ogk_real_t t_excess = OGK_R(0.0);   /* l1 excess of the terminal set (elastic: priced in the merit) */
    ogk_real_t first_exc = OGK_R(0.0);
    const bool elastic_set = terminal_set(cfg);
    uint32_t iter;
    size_t i;
    size_t rows;
    ogk_qp_problem_t qp;
    /* the exact Hessian, until a failed line search falls back to BFGS */
    bool exact = (cfg->hessian == OGK_NMPC_HESSIAN_EXACT);
    ogk_real_t rho;
    ogk_real_t rho_last = OGK_R(0.0);
    /* the exact Hessian of the last iteration held for this one (HESS_HOLD_RATE) */
    bool hold_next = false;
    bool hold_ok = false;
    ogk_real_t pred_prev = OGK_R(0.0); /* |dJ| predicted by the last iteration's QP (0: none yet) */
#if OGK_REAL_SINGLE
    ogk_real_t tol_feas = cfg->tol_feas;
    ogk_real_t tol_obj = cfg->tol_obj;
    {
        /* the floors of float's resolution (FEAS_FLOOR, OBJ_FLOOR) */
        ogk_real_t xs = OGK_R(1.0);
        for (i = 0u; i < (((size_t)p->nodes + 1u) * NX); ++i) {
            xs = (OGK_FABS(p->x[i]) > xs) ? OGK_FABS(p->x[i]) : xs;
        }
        xs *= FEAS_FLOOR;
        tol_feas = (tol_feas > xs) ? tol_feas : xs;
        tol_obj = ((tol_obj > OGK_R(0.0)) && (tol_obj < OBJ_FLOOR)) ? OBJ_FLOOR : tol_obj;
    }
#endif

    if (cold) {
        ogk_i_nmpc_identity(hess, nv, cfg->hessian_init);
    }
    (void)memcpy(y_prev, p->lambda, sizeof(y_prev));
    rep->stat = OGK_R(0.0);
    for (iter = 0u; (iter < iter_limit) && !done; ++iter) {
        /* a cold solve has no multipliers for its first exact Hessian: that
         * iteration's QP gets the scaled identity */
        const bool second = exact && ((!cold) || (iter != 0u));
        /* held only after a full step of an exact iteration evaluated without
         * second derivatives (the line search below, which then also sets
         * have_eval; a restart, which ends exact, sets neither), as long as
         * the steps contract (HESS_HOLD_RATE) */
        const bool held = hold_next;
        hold_next = false;
        if (!have_eval) {
            st = evaluate(ctx, p, true, second ? y_prev : NULL, &viol_l1, &viol_max, c_term, &t_excess);
        }
        have_eval = false;
        if (st == OGK_OK) {
            if (held) {
                /* the last iteration's eq. (5) rows, for its shift (scratch free: no condensed Hessian) */
                (void)memcpy(ctx->hess_tmp, ctx->qp_aeq, NC * nv * sizeof(ogk_real_t));
            }
            ogk_i_nmpc_condense(ctx, p, nv, (second && !held) ? hess : NULL);
            ogk_i_nmpc_linear_terms(ctx, p, nv, c_term, g_obj);
            rho = OGK_R(0.0);
            if (held) {
                /* the last iteration's H + rho A^T A with its A replaced by this one's */
                ogk_i_nmpc_hess_reshift(hess, nv, ctx->hess_tmp, ctx->qp_aeq, rho_last);
                rho = rho_last;
            } else if (second) {
                bool shifted = false;
                rho = ogk_i_nmpc_hess_convexify(hess, nv, ctx->qp_aeq, cfg->hessian_init, rho_last, ctx->el_h,
                                                ctx->el_ain, &shifted);
                rho_last = rho;
                if (shifted) {
                    /* not convex on the null space of eq. (5): far from a minimum the
                     * exact model misleads (measured: closed loops with Earth in the
                     * model stalled at the iteration limit); this step on the scaled
                     * identity. With a throttle the rest of the solve goes on BFGS: the
                     * throttle enters the dynamics and the cost linearly, the exact
                     * Hessian is not convex there at any iterate, and a minimum-fuel open
                     * loop crept 500 identity steps from its guess (47 iterations on BFGS).
                     * Without one it turns convex near the minimum (the minimum-time open
                     * loop: more than 60 identity steps in a row, then exact steps) */
                    rho = OGK_R(0.0);
                    ogk_i_nmpc_identity(hess, nv, cfg->hessian_init);
                    if (p->nu > 1u) {
                        exact = false;
                        first_update = true;
                        have_prev = false;
                    }
                }
            } else if (have_prev) {
                /* not exact: with the exact Hessian second is false only in a cold
                 * solve's first iteration, where have_prev is still false */
                /* y = grad L(new iterate) - grad L(old iterate), both with the last QP's multipliers */
                lagrangian_gradient(ctx, nv, g_obj, y_prev, grad_new);
                for (i = 0u; i < nv; ++i) {
                    grad_new[i] -= ctx->grad_lag[i];
                }
                ogk_i_nmpc_bfgs_update(hess, nv, ctx->step_v, grad_new, first_update);
                first_update = false;
            } else {
                /* BFGS without a pair: the matrix carried; the first iteration of a
                 * cold exact solve: the scaled identity */
            }
            rows = build_bounds(ctx, p, nv, box);
            step_qp(ctx, nv, rows, hess, g_obj, &qp);
            if (elastic_set) {
                /* the terminal set's rows always elastic (their slacks priced at
                 * elastic_weight, as the merit prices the excess) */
                st = solve_elastic(ctx, hess, g_obj, nv, rows, terminal_row0(ctx, p));
            } else {
                st = ogk_qp_solve(&ctx->qp_ws, &qp, &ctx->qp_sol);
            }
            if (st == OGK_E_NOT_POSDEF) {
                ogk_i_nmpc_identity(hess, nv, cfg->hessian_init);
                first_update = true;
                rho = OGK_R(0.0);
                if (elastic_set) {
                    st = solve_elastic(ctx, hess, g_obj, nv, rows, terminal_row0(ctx, p));
                } else {
                    st = ogk_qp_solve(&ctx->qp_ws, &qp, &ctx->qp_sol);
                }
            }
            if ((st == OGK_E_INFEASIBLE) && elastic_set) {
                /* the other rows (keep-out, propellant, sweep) out of the step box's reach:
                 * once more with the box opened */
                rep->qp_iterations += (uint32_t)ctx->qp_sol.iterations;
                (void)build_bounds(ctx, p, nv, BOX_OPEN);
                st = solve_elastic(ctx, hess, g_obj, nv, rows, terminal_row0(ctx, p));
                rep->flags |= OGK_NMPC_FLAG_ELASTIC;
            } else if (st == OGK_E_INFEASIBLE) {
                /* the step box made the linearised eq. (5) unreachable: once more
                 * with the box opened (the physical bounds stay) */
                rep->qp_iterations += (uint32_t)ctx->qp_sol.iterations;
                (void)build_bounds(ctx, p, nv, BOX_OPEN);
                st = ogk_qp_solve(&ctx->qp_ws, &qp, &ctx->qp_sol);
                if (st == OGK_E_INFEASIBLE) {
                    rep->qp_iterations += (uint32_t)ctx->qp_sol.iterations;
                    (void)build_bounds(ctx, p, nv, box);
                    st = solve_elastic(ctx, hess, g_obj, nv, rows, terminal_row0(ctx, p));
                    rep->flags |= OGK_NMPC_FLAG_ELASTIC;
                    rho = OGK_R(0.0); /* the slacks take the residual: no shift to undo */
                }
            } else {
                /* solved, or a failure the step box does not cause */
            }
            if ((st == OGK_E_INFEASIBLE) && (ctx->ko_rows > 0u)) {
                /* the keep-out rows out of every step's reach: a node of a stale plan inside a
                 * disc that the linearisation cannot move out (at w = 0 the thrust angle moves
                 * nothing, the throttle only along its angle; with T kept no time scaling
                 * either). Once more with them elastic too, the box opened: the filter's theta
                 * prices the disc's violation, so the step is taken only when it reduces it or J */
                const size_t ko_row0 = (cfg->max_sweep > OGK_R(0.0)) ? (2u * (size_t)p->nodes) : 0u;
                rep->qp_iterations += (uint32_t)ctx->qp_sol.iterations;
                (void)build_bounds(ctx, p, nv, BOX_OPEN);
                st = solve_elastic_rows(ctx, hess, g_obj, nv, rows, terminal_row0(ctx, p), ko_row0,
                                        ogk_i_min_size(ctx->ko_rows, OGK_I_NMPC_MAX_KO_ROWS_Z));
                rep->flags |= OGK_NMPC_FLAG_ELASTIC;
                rho = OGK_R(0.0);
            }
            if (st == OGK_OK) {
                terminal_multipliers(ctx, terminal_row0(ctx, p));
            }
            if ((st == OGK_OK) && (rho > OGK_R(0.0))) {
                /* H + rho A^T A: the multipliers of eq. (5) are y - rho A v, and A v
                 * = b_eq with eq. (5) exactly */
                for (i = 0u; i < NC; ++i) {
                    if (terminal_set(cfg)) {
                        size_t c;
                        ogk_real_t av = OGK_R(0.0);
                        for (c = 0u; c < nv; ++c) {
                            av += ctx->qp_aeq[(i * nv) + c] * ctx->qp_sol.x[c];
                        }
                        ctx->qp_sol.y_eq[i] -= rho * av;
                    } else {
                        ctx->qp_sol.y_eq[i] -= rho * ctx->qp_beq[i];
                    }
                }
            }
            rep->qp_iterations += (uint32_t)ctx->qp_sol.iterations;
            rep->sqp_iterations += 1u;
        }
        done = (st != OGK_OK);
        if (!done) {
            /* reduced stationarity |H v|_inf = |g - A^T y - z|_inf */
            ogk_real_t stat = OGK_R(0.0);
            size_t j;
#if OGK_REAL_SINGLE
            /* float: the step and its stationarity at the unknowns' resolution (STEP_FLOOR) */
            bool at_res = true;
#endif
            for (i = 0u; i < nv; ++i) {
                ogk_real_t acc = OGK_R(0.0);
                for (j = 0u; j < nv; ++j) {
                    acc += hess[(i * nv) + j] * ctx->qp_sol.x[j];
                }
                stat = (OGK_FABS(acc) > stat) ? OGK_FABS(acc) : stat;
#if OGK_REAL_SINGLE
                {
                    /* the unknown's ulps: max(1, |w_i|), w the controls, then T */
                    const ogk_real_t w = OGK_FABS(((i + 1u) < nv) ? p->u[i] : p->horizon);
                    const ogk_real_t res = STEP_FLOOR * ((w > OGK_R(1.0)) ? w : OGK_R(1.0));
                    at_res = at_res && (OGK_FABS(ctx->qp_sol.x[i]) <= res)
                        && (OGK_FABS(acc) <= (cfg->hessian_init * res));
                }
#endif
            }
            rep->stat = stat;
            {
                /* predicted change of J by the QP step (its defect part included),
                 * with a terminal set of its priced excess too */
                ogk_real_t pred = (cfg->objective == OGK_NMPC_MIN_FUEL) ? -ctx->cond_e[4] : OGK_R(0.0);
                const ogk_real_t j_now = OGK_FABS(ogk_i_nmpc_objective(cfg, p));
                for (i = 0u; i < nv; ++i) {
                    pred += g_obj[i] * ctx->qp_sol.x[i];
                }
                if (elastic_set) {
                    pred += cfg->elastic_weight * (elastic_excess(ctx, nv) - t_excess);
                }
                const ogk_real_t stop = SQP_TOL_OBJ * ((j_now > OGK_R(1.0)) ? j_now : OGK_R(1.0));
                flat = (SQP_TOL_OBJ > OGK_R(0.0)) && (OGK_FABS(pred) <= stop);
                /* a step from an exact Hessian (computed or held) that factored with
                 * its shift alone (rho > 0 only then), contracting (HESS_HOLD_RATE):
                 * held when its full step is taken (below); never with tol_obj = 0
                 * (stop = 0: the never-held reference) */
                hold_ok = (stop > OGK_R(0.0)) && (rho > OGK_R(0.0))
                    && ((!cold && (iter == 0u)) || (OGK_FABS(pred) <= (HESS_HOLD_RATE * pred_prev)));
                pred_prev = OGK_FABS(pred);
            }
            /* a held Hessian's flat step is taken (newton_last below: its trial
             * evaluated without sensitivities, converged there when feasible): the
             * iterate of a lagged Newton step is less accurate than a Newton
             * step's, and the step is what is left of it */
#if OGK_REAL_SINGLE
            if ((viol_max <= SQP_TOL_FEAS) && ((stat <= cfg->tol_stat) || at_res || (flat && !held))) {
#else
            if ((viol_max <= SQP_TOL_FEAS) && ((stat <= cfg->tol_stat) || (flat && !held))) {
#endif
                (void)memcpy(p->lambda, ctx->qp_sol.y_eq, sizeof(p->lambda));
                done = true;
                if (t_excess > SQP_TOL_FEAS) {
                    /* the vehicle cannot reach the terminal set: the plan ends as close to it as it can */
                    rep->flags |= OGK_NMPC_FLAG_OUTSIDE_SET;
                }
            } else if (!exact && flat && (viol_max <= RESTORE_VIOL_MAX) && (restores < MAX_RESTORES)) {
                /* the step predicts no change of J, only feasibility is left:
                 * a minimum-norm step onto the linearised constraints (H = I,
                 * g = 0) converges quadratically where BFGS steps wander in
                 * the null space and keep the violation at 1e-8 (docs) */
                restores += 1u;
                restored = feasibility_step(ctx, p, nv, rows, viol_l1, rep);
                have_prev = have_prev && !restored;
            } else {
                /* an SQP step */
            }
        }
        if (!done && restored) {
            restored = false;
        } else if (!done) {
            /* filter line search (Waechter & Biegler 2006, without the
             * restoration phase): theta = l1 violation, phi = J */
            const ogk_real_t phi0 = penalized(cfg, p, t_excess);
            const ogk_real_t theta0 = viol_l1;
            /* an exact-Hessian step that predicts no change of J is the
             * last Newton step when its full step is feasible: that trial
             * is first evaluated without sensitivities */
            const bool newton_last = exact && flat;
            ogk_real_t dphi;
            ogk_real_t alpha = OGK_R(1.0);
            bool accepted = false;
            bool f_type = false;
            uint32_t ls;

            ogk_i_nmpc_expand_step(ctx, p, ctx->qp_sol.x, nv);
            dphi = (cfg->objective == OGK_NMPC_MIN_FUEL)
                ? (-ctx->dx[(p->nodes * NX) + 4u] + (cfg->time_weight * ctx->qp_sol.x[nv - 1u]))
                : ctx->qp_sol.x[nv - 1u];
            if (elastic_set) {
                dphi += cfg->elastic_weight * (elastic_excess(ctx, nv) - t_excess);
            }
            if (first_iter) {
                theta_max = OGK_R(1.0e4) * ((theta0 > OGK_R(1.0)) ? theta0 : OGK_R(1.0));
                theta_min = OGK_R(1.0e-4) * ((theta0 > OGK_R(1.0)) ? theta0 : OGK_R(1.0));
                first_iter = false;
            }
            for (ls = 0u; (ls < OGK_NMPC_MAX_LINE_SEARCH) && !accepted; ++ls) {
                ogk_real_t t_l1 = OGK_R(0.0);
                ogk_real_t t_max = OGK_R(0.0);
                ogk_real_t t_exc = OGK_R(0.0);
                ogk_status ts;
                take_step(ctx, p, ctx->qp_sol.x, nv, alpha, &ctx->trial);
                /* the full step is evaluated with its sensitivities: taken
                 * (the usual case near the solution), it is the next
                 * iteration's linearisation */
                ts = evaluate(ctx, &ctx->trial, (ls == 0u) && !newton_last,
                              (exact && !hold_ok) ? ctx->qp_sol.y_eq : NULL,
                              &t_l1, &t_max, c_trial, &t_exc);
                first_l1 = t_l1;
                first_max = t_max;
                first_exc = t_exc;
                if ((ts == OGK_OK) && (t_l1 <= theta_max)) {
                    const ogk_real_t phi_t = penalized(cfg, &ctx->trial, t_exc);
                    const ogk_real_t m_alpha = alpha * dphi;
                    f_type = (dphi < OGK_R(0.0)) && (theta0 <= theta_min)
                        && ((alpha * OGK_POW(-m_alpha, FILTER_S_PHI)) > OGK_POW(theta0, FILTER_S_THETA));
                    if (f_type) {
                        accepted = phi_t <= (phi0 + (ARMIJO_C1 * m_alpha));
                    } else {
                        accepted = (t_l1 <= ((OGK_R(1.0) - FILTER_GAMMA) * theta0))
                            || (phi_t <= (phi0 - (FILTER_GAMMA * theta0)));
                    }
                    if (accepted) {
                        /* n_filter <= FILTER_SIZE (an entry is added only below it):
                         * clamped once so the loop keeps a fixed bound */
                        const uint32_t n_f = ogk_i_min_u32(n_filter, FILTER_SIZE);
                        uint32_t f;
                        for (f = 0u; (f < n_f) && accepted; ++f) {
                            if ((t_l1 >= filter_theta[f]) && (phi_t >= filter_phi[f])) {
                                accepted = false;
                            }
                        }
                    }
                }
                if (!accepted) {
                    alpha *= BACKTRACK;
                }
            }
#if OGK_REAL_SINGLE
            if ((!accepted) && (viol_max <= tol_feas) && (p->horizon >= cfg->horizon_min)
                && (p->horizon <= cfg->horizon_max) && sqp_noise_floor(ctx, dphi, phi0, theta0)) {
                /* float's noise floor (sqp_noise_floor): converged at this iterate, which is
                 * feasible and within its horizon bounds (a plan loaded outside them, whose
                 * step to them fails the line search, is not: OGK_E_NOT_CONVERGED as in double) */
                (void)memcpy(p->lambda, ctx->qp_sol.y_eq, sizeof(p->lambda));
                done = true;
                if (t_excess > tol_feas) {
                    rep->flags |= OGK_NMPC_FLAG_OUTSIDE_SET;
                }
            } else
#endif
            if (!accepted && (restarts < MAX_RESTARTS)) {
                /* restart: a BFGS matrix that has drifted and a filter that
                 * blocks every step are the usual causes */
                restarts += 1u;
                box = OGK_R(1.0);
                /* the exact Hessian's step failed too: BFGS from here on */
                exact = false;
                ogk_i_nmpc_identity(hess, nv, cfg->hessian_init);
                first_update = true;
                have_prev = false;
                n_filter = 0u;
                filter_next = 0u;
            } else if (!accepted) {
                rep->flags |= OGK_NMPC_FLAG_LS_FAILED;
                st = OGK_E_NOT_CONVERGED;
                done = true;
            } else {
                if (!f_type) {
                    /* augment the filter (oldest entry replaced when full) */
                    const uint32_t slot = (n_filter < FILTER_SIZE) ? n_filter : (filter_next % FILTER_SIZE);
                    filter_theta[slot] = (OGK_R(1.0) - FILTER_GAMMA) * theta0;
                    filter_phi[slot] = phi0 - (FILTER_GAMMA * theta0);
                    if (n_filter < FILTER_SIZE) {
                        n_filter += 1u;
                    }
                    filter_next = (slot + 1u) % FILTER_SIZE;
                }
                (void)memcpy(p, &ctx->trial, sizeof(*p));
                lagrangian_gradient(ctx, nv, g_obj, ctx->qp_sol.y_eq, ctx->grad_lag);
                for (i = 0u; i < nv; ++i) {
                    ctx->step_v[i] = alpha * ctx->qp_sol.x[i];
                }
                (void)memcpy(y_prev, ctx->qp_sol.y_eq, sizeof(y_prev));
                (void)memcpy(p->lambda, ctx->qp_sol.y_eq, sizeof(p->lambda));
                /* the step box as a trust region: a cut step shrinks it (the
                 * next QP stays where the linearisation held), a full step
                 * regrows it; a much-cut step is no curvature sample */
                if (alpha < OGK_R(1.0)) {
                    box *= alpha;
                    if (!(box > BOX_MIN)) {
                        box = BOX_MIN;
                    }
                } else {
                    box *= OGK_R(2.0);
                    if (!(box < OGK_R(1.0))) {
                        box = OGK_R(1.0);
                    }
                }
                have_prev = alpha >= BFGS_MIN_ALPHA;
                if (newton_last && (alpha >= OGK_R(1.0)) && (first_max <= SQP_TOL_FEAS)) {
                    /* converged at the trial: a full Newton step predicting no
                     * change of J (|dJ| <= tol_obj max(|J|, 1)) landed feasible */
                    viol_max = first_max;
                    done = true;
                    if (first_exc > SQP_TOL_FEAS) {
                        rep->flags |= OGK_NMPC_FLAG_OUTSIDE_SET;
                    }
                } else if ((alpha >= OGK_R(1.0)) && !newton_last) {
                    have_eval = true;
                    hold_next = hold_ok;
                    viol_l1 = first_l1;
                    viol_max = first_max;
                    t_excess = first_exc;
                    (void)memcpy(c_term, c_trial, sizeof(c_term));
                } else {
                    /* evaluated again, with its sensitivities, next iteration */
                }
            }
        } else {
            /* done: converged or failed in this iteration */
        }
    }
    if ((st == OGK_OK) && !done) {
        st = OGK_E_ITER_LIMIT;
    }
    rep->feas = viol_max;
    rep->solves += 1u;
    return st;
}
