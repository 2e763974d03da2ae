/* nmpc_internal.h -- internal interfaces of ogk_nmpc (not public API):
 * the predictive model (nmpc_model.c), one shooting interval with its
 * sensitivities (nmpc_shoot.c), the SQP (nmpc_sqp.c) with its condensing
 * (nmpc_condense.c) and the strategies' plan operations (nmpc_plan.c). */
#ifndef OGK_NMPC_INTERNAL_H
#define OGK_NMPC_INTERNAL_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include "ogk/nmpc.h"

/* Columns of the sensitivity matrix of one interval, in this order:
 * X_k (5), U_k (nu), U_{k+1} (nu), h (1), t_start (1): the directions of
 * ogk/nmpc.h (h standing for T) and t_start; the row stride rounded up to
 * an even count (OGK_NMPC_SENS_COLS), so that the forward sweep's column
 * loops go by pairs (nmpc_shoot.c). */
#define OGK_I_NMPC_MAX_COLS OGK_I_NMPC_NCOL_Z
/* Arguments of the model f(z): z = (x (5), u (nu), t), stored with this
 * stride (the largest nu). */
#define OGK_I_NMPC_NZ (OGK_NMPC_NX + OGK_NMPC_MAX_NU + 1u)
#if OGK_I_NMPC_NZ != OGK_OCP_NZ
#error "the model's argument stride differs from ogk/ocp.h's OGK_OCP_NZ"
#endif

/* The problem as the solver's internals see it (ogk/ocp.h): its callbacks,
 * their data, and the solver's settings (the context's configuration:
 * transcription, SQP, strategy). */
typedef struct {
    const ogk_ocp_problem_t *ops;
    const void *data;
    const ogk_nmpc_config_t *cfg;
} ogk_i_ocp_t;

/* ctx's problem: its table and data, the heliocentric problem over ctx->cfg
 * when the context has no data of its own (ogk_nmpc_init). Inline: it is
 * taken on every interval of every SQP iteration. */
static inline ogk_i_ocp_t ogk_i_nmpc_problem(const ogk_nmpc_t *ctx)
{
    ogk_i_ocp_t ocp;
    ocp.ops = ctx->problem;
    ocp.data = (ctx->problem_data != NULL) ? (const void *)ctx->problem_data : (const void *)&ctx->cfg;
    ocp.cfg = &ctx->cfg;
    return ocp;
}

/* The heliocentric problem of Starek & Kolmanovsky (nmpc_helio.c), its data
 * an ogk_nmpc_config_t. */
extern const ogk_ocp_problem_t ogk_i_nmpc_helio_problem;

/* Its model (nmpc_model.c), data an ogk_nmpc_config_t: the dynamics and
 * dynamics_hess callbacks of ogk/ocp.h (eqs. 11-14 with the third bodies). */
ogk_status ogk_i_nmpc_rhs(const void *data, uint32_t nu, ogk_real_t t,
                          const ogk_real_t *x, const ogk_real_t *u, const ogk_real_t *trig,
                          ogk_real_t *xdot, ogk_real_t *jx, ogk_real_t *ju, ogk_real_t *jt);
void ogk_i_nmpc_rhs_hess(const void *data, uint32_t nu, ogk_real_t t,
                         const ogk_real_t *x, const ogk_real_t *u, const ogk_real_t *trig,
                         const ogk_real_t *kappa, ogk_real_t *hz);

/* size_t forms of the limits (built from the atoms, so that no composite
 * expression is cast): sensitivity columns, model arguments, directions,
 * QP unknowns. */
#define OGK_I_NMPC_NCOL_Z (((((size_t)OGK_NMPC_NX + (2u * (size_t)OGK_NMPC_MAX_NU)) + 3u) / 2u) * 2u)
#define OGK_I_NMPC_NZ_Z (((size_t)OGK_NMPC_NX + (size_t)OGK_NMPC_MAX_NU) + 1u)
#define OGK_I_NMPC_NDIR_Z (((size_t)OGK_NMPC_NX + (2u * (size_t)OGK_NMPC_MAX_NU)) + 1u)
#define OGK_I_NMPC_MAXV_Z ((((size_t)OGK_NMPC_MAX_NODES + 1u) * (size_t)OGK_NMPC_MAX_NU) + 1u)
#define OGK_I_NMPC_MAX_KO_ROWS_Z (2u * (size_t)OGK_NMPC_MAX_NODES)

/* Layout of one RK4 step of the tape (OGK_NMPC_TAPE_STEP doubles): the
 * step's starting sensitivity matrix S, then four stage records of
 * OGK_I_NMPC_TAPE_STAGE doubles: stage state, stage derivative k, cos/sin of
 * the stage angle, the model's Jacobian, k's sensitivity matrix. */
#define OGK_I_NMPC_TAPE_STAGE0 ((size_t)OGK_NMPC_NX * OGK_I_NMPC_NCOL_Z)
#define OGK_I_NMPC_TAPE_X ((size_t)0u)
#define OGK_I_NMPC_TAPE_K ((size_t)OGK_NMPC_NX)
#define OGK_I_NMPC_TAPE_TRIG (2u * (size_t)OGK_NMPC_NX)
#define OGK_I_NMPC_TAPE_JX ((2u * (size_t)OGK_NMPC_NX) + 2u)
#define OGK_I_NMPC_TAPE_KS (OGK_I_NMPC_TAPE_JX + ((size_t)OGK_NMPC_NX * (size_t)OGK_NMPC_NX))
#define OGK_I_NMPC_TAPE_STAGE (OGK_I_NMPC_TAPE_KS + ((size_t)OGK_NMPC_NX * OGK_I_NMPC_NCOL_Z))
#define OGK_I_NMPC_TAPE_STEP_Z (OGK_I_NMPC_TAPE_STAGE0 + (4u * OGK_I_NMPC_TAPE_STAGE))
/* the same layout in the preprocessor's arithmetic, against ogk/nmpc.h's size */
#if OGK_NMPC_MAX_KO_ROWS != (2u * OGK_NMPC_MAX_NODES)
#error "OGK_I_NMPC_MAX_KO_ROWS_Z does not match OGK_NMPC_MAX_KO_ROWS (ogk/nmpc.h)"
#endif
#if ((OGK_NMPC_NX * OGK_NMPC_SENS_COLS) \
     + (4u * ((2u * OGK_NMPC_NX) + 2u + (OGK_NMPC_NX * OGK_NMPC_NX) + (OGK_NMPC_NX * OGK_NMPC_SENS_COLS)))) \
    != OGK_NMPC_TAPE_STEP
#error "OGK_NMPC_TAPE_STEP (ogk/nmpc.h) does not match the tape layout"
#endif

/* Sensitivity columns propagated for this model: X_k, U_k, U_{k+1}, h, and
 * t_start only when a third body attracts (the model then depends on t). */
size_t ogk_i_nmpc_ncol(const ogk_i_ocp_t *ocp, uint32_t nu);

/* The keep-out along one arc (the interior RK4 step ends of a subinterval):
 * r_start, set by the caller, the radius required at the arc's start (R, or
 * on the first subinterval a measured state's distance inside R: the
 * required radius then grows straight to R at its end); per disc j the step
 * ends within three radii (bit j: step j's end); the sum and the largest of
 * the violations max(0, R_required - d). */
typedef struct {
    ogk_real_t radius[OGK_OCP_MAX_KEEPOUT];  /* [LU] the discs' radii R_j (0: none) */
    uint32_t steps;                      /* [-] the arc's RK4 steps */
    ogk_real_t r_start[OGK_OCP_MAX_KEEPOUT]; /* [LU] */
    uint32_t mask[OGK_OCP_MAX_KEEPOUT];  /* [-] */
    ogk_real_t viol_sum;                     /* [LU] */
    ogk_real_t viol_max;                     /* [LU] */
} ogk_i_nmpc_arc_t;
/* Doubles recorded per step end by ogk_i_nmpc_shoot_arc's rec: the state and its sensitivities. */
#define OGK_I_NMPC_REC_STRIDE ((size_t)OGK_NMPC_NX + ((size_t)OGK_NMPC_NX * OGK_I_NMPC_NCOL_Z))

/* arc of subinterval k of plan p, before its sweep: no step end, no
 * violation, the radius required at the start (see ogk_i_nmpc_arc_t). */
void ogk_i_nmpc_arc_start(const ogk_i_ocp_t *ocp, const ogk_nmpc_plan_t *p, size_t k,
                          ogk_i_nmpc_arc_t *arc);

/* The sweep of ogk_i_nmpc_shoot with two additions: arc (or NULL): the
 * keep-out scan of the interior step ends (ogk_i_nmpc_keepout_scan); ends (or
 * NULL, with sens): the state and its sensitivities at each interior step
 * end j, at ends + (j - 1) OGK_I_NMPC_REC_STRIDE. */
ogk_status ogk_i_nmpc_shoot_arc(const ogk_i_ocp_t *ocp, uint32_t nu,
                                ogk_real_t t_start, ogk_real_t h, const ogk_real_t *x0,
                                const ogk_real_t *u0, const ogk_real_t *u1, ogk_real_t *xf,
                                ogk_real_t *sens, ogk_real_t *tape, ogk_i_nmpc_arc_t *arc, ogk_real_t *ends);

/* F = x at the end of one interval [t_start, t_start + h] from x0 with the
 * control linear from u0 to u1. When sens is not NULL it receives the
 * 5 x OGK_I_NMPC_MAX_COLS sensitivity matrix (columns above; unused control
 * columns zero); when tape is not NULL too, the sweep is recorded there
 * (ocp->cfg->rk4_steps steps of OGK_NMPC_TAPE_STEP). */
ogk_status ogk_i_nmpc_shoot(const ogk_i_ocp_t *ocp, uint32_t nu,
                            ogk_real_t t_start, ogk_real_t h, const ogk_real_t *x0,
                            const ogk_real_t *u0, const ogk_real_t *u1, ogk_real_t *xf,
                            ogk_real_t *sens, ogk_real_t *tape);

/* W (OGK_I_NMPC_MAX_COLS square, symmetric, the first ogk_i_nmpc_ncol
 * columns set) = sum_i w_i d2F_i / dp2 for the interval whose forward sweep
 * with sensitivities was recorded in tape (same ocp, nu, t_start, h, u0,
 * u1), p = (X_k, U_k, U_{k+1}, h[, t_start]): the RK4 recursion's adjoint
 * for the weights w, differentiated forward (docs/design/nmpc-flight.md). */
void ogk_i_nmpc_shoot_hess(const ogk_i_ocp_t *ocp, uint32_t nu,
                           ogk_real_t t_start, ogk_real_t h, const ogk_real_t *u0,
                           const ogk_real_t *u1, const ogk_real_t *tape,
                           const ogk_real_t *w, ogk_real_t *hess);

/* The sensitivities kept with their inputs (nmpc_sens_cache.c). reset:
 * every key zeroed (none matches) and the keys' model zeroed. begin: at the start
 * of an evaluation; when the problem's model key differs from the keys'
 * (ctx->sens_model), every key zeroed and this model kept.
 * key: interval k's key of plan p (OGK_NMPC_SENS_KEY doubles, the rest 0);
 * returns the doubles that count. hit: slot k's key is these bits. store:
 * slot k's key (its data written by the caller; key NULL: forgotten, 0). drop: the slots moved with
 * ogk_i_nmpc_plan_drop(p, count) of a plan of `nodes` subintervals. */
void ogk_i_nmpc_cache_reset(ogk_nmpc_t *ctx);
void ogk_i_nmpc_cache_begin(ogk_nmpc_t *ctx);
size_t ogk_i_nmpc_cache_key(const ogk_nmpc_t *ctx, const ogk_nmpc_plan_t *p, size_t k,
                            ogk_real_t t_start, ogk_real_t h, ogk_real_t *key);
bool ogk_i_nmpc_cache_hit(const ogk_nmpc_t *ctx, size_t k, const ogk_real_t *key, size_t n_key);
void ogk_i_nmpc_cache_store(ogk_nmpc_t *ctx, size_t k, const ogk_real_t *key);
void ogk_i_nmpc_cache_drop(ogk_nmpc_t *ctx, uint32_t nodes, uint32_t count, uint32_t nu);

/* Terminal residual c = x_0..3 - x_T(t_f) at state x and time t_f (the
 * heliocentric problem: eq. 5), and with rate != NULL dx_T/dt_f. */
void ogk_i_nmpc_terminal(const ogk_i_ocp_t *ocp, const ogk_real_t *x,
                         ogk_real_t t_f, ogk_real_t *c, ogk_real_t *rate);

/* The condensed QP (nmpc_condense.c), nv = (N + 1) nu + 1 unknowns.
 * condense: ctx->cond_g = G_N = dX_N/dv and ctx->cond_e = e_N from the
 * context's sensitivities, the keep-out rows, and with hess != NULL the
 * exact reduced Hessian (nv x nv, full) from ctx->hess_blk. linear_terms:
 * g_obj (nv) and eq. (5)'s rows qp_aeq, qp_beq (c_term: eq. 5's residual).
 * expand_step: ctx->dx = the state corrections of the QP step v. */
void ogk_i_nmpc_condense(ogk_nmpc_t *ctx, const ogk_nmpc_plan_t *p, size_t nv, ogk_real_t *hess);
void ogk_i_nmpc_linear_terms(ogk_nmpc_t *ctx, const ogk_nmpc_plan_t *p, size_t nv, const ogk_real_t *c_term,
                             ogk_real_t *g_obj);
void ogk_i_nmpc_expand_step(ogk_nmpc_t *ctx, const ogk_nmpc_plan_t *p, const ogk_real_t *v, size_t nv);

/* The SQP on ctx->work (node 0 and t0 already set) with the BFGS matrix
 * hess (nv x nv), restarted from the scaled identity when cold. Adds its
 * iterations to rep and sets rep->feas, rep->stat. */
ogk_status ogk_i_nmpc_sqp(ogk_nmpc_t *ctx, ogk_real_t *hess, bool cold,
                          ogk_nmpc_report_t *rep);

/* The QP Hessian (nmpc_hess.c). Powell damping: keep s^T y >= this s^T H s. */
#define OGK_I_NMPC_POWELL_DAMP OGK_R(0.2)

/* blk (OGK_NMPC_MAX_DIR square, the first 5 + 2 nu + 1 rows and columns
 * set) = interval k's second-order block w_int (ogk_i_nmpc_shoot_hess, ncol
 * columns) in (X_k, U_k, U_{k+1}, T): h = T / N, t_start = t0 + k T / N. */
void ogk_i_nmpc_hess_block(uint32_t nu, size_t ncol, size_t k, uint32_t nodes,
                           const ogk_real_t *w_int, ogk_real_t *blk);

/* The upper triangle of hess (nv x nv) += Gt^T blk Gt, Gt = d(X_k, U_k,
 * U_{k+1}, T)/dv with X_k's rows g (5 x nv, the condensing's dX_k/dv).
 * scratch: 2 OGK_NMPC_MAX_DIR OGK_NMPC_MAX_VARS doubles. */
void ogk_i_nmpc_hess_add(ogk_real_t *hess, size_t nv, uint32_t nu, size_t k,
                         const ogk_real_t *g, const ogk_real_t *blk, ogk_real_t *scratch);

/* The upper triangle of hess (nv x nv) copied into the lower one. */
void ogk_i_nmpc_hess_mirror(ogk_real_t *hess, size_t nv);

/* hess := hess + rho A^T A (+ delta I), the least of a few rho (from
 * rho_hint, the last one used, when larger) then delta that factors (a_eq:
 * the NC x nv rows of eq. 5); the scaled identity (fallback) when nothing
 * does. out and work: nv x nv scratch. Returns the rho used (the QP's
 * multipliers of eq. 5 are then y - rho b_eq); *shifted: a delta was needed
 * (H not convex on eq. 5's null space). */
ogk_real_t ogk_i_nmpc_hess_convexify(ogk_real_t *hess, size_t nv, const ogk_real_t *a_eq,
                                 ogk_real_t fallback, ogk_real_t rho_hint, ogk_real_t *out, ogk_real_t *work, bool *shifted);

/* hess (nv x nv, H0 + rho A_old^T A_old, A NC x nv) := H0 + rho A_new^T
 * A_new: the exact Hessian of the last iteration held (nmpc_sqp.c). */
void ogk_i_nmpc_hess_reshift(ogk_real_t *hess, size_t nv, const ogk_real_t *a_old, const ogk_real_t *a_new, ogk_real_t rho);

/* Damped BFGS (Powell) update of hess with step s and gradient change y (y
 * is damped in place); first: Shanno-Phua scaling of the initial matrix. */
void ogk_i_nmpc_bfgs_update(ogk_real_t *hess, size_t nv, const ogk_real_t *s, ogk_real_t *y, bool first);

/* hess := scale I (nv x nv). */
void ogk_i_nmpc_identity(ogk_real_t *hess, size_t nv, ogk_real_t scale);

/* Keep-out (nmpc_keepout.c), the problem's discs j (ogk/ocp.h): adds sum and largest of max(0, R_j - d_j) over
 * the interior nodes of p to *sum and *largest; appends to ctx->ko_a/ko_b
 * the linearised rows of interior node k (g: its 5 x nv condensed
 * sensitivities, e: its offsets). */
void ogk_i_nmpc_keepout_violation(const ogk_i_ocp_t *ocp, const ogk_nmpc_plan_t *p, ogk_real_t *sum,
                                  ogk_real_t *largest);
void ogk_i_nmpc_keepout_rows(ogk_nmpc_t *ctx, const ogk_nmpc_plan_t *p, size_t nv, size_t k,
                             const ogk_real_t *g, const ogk_real_t *e);
/* Along the arcs: scan: one step end x at time t (step index `step`) into
 * arc; arc_rows: the linearised rows of interval k's step ends in
 * ctx->arc_mask (g, e: node k's condensed sensitivities; the step ends'
 * from a sweep recorded in the context's tape, free during condensing). */
void ogk_i_nmpc_keepout_scan(const ogk_i_ocp_t *ocp, const ogk_real_t *x, ogk_real_t t, uint32_t step,
                             ogk_i_nmpc_arc_t *arc);
void ogk_i_nmpc_keepout_arc_rows(ogk_nmpc_t *ctx, const ogk_nmpc_plan_t *p, size_t nv, size_t k,
                                 const ogk_real_t *g, const ogk_real_t *e);

/* Objective of a plan: T or m_0 - m_N. */
ogk_real_t ogk_i_nmpc_objective(const ogk_nmpc_config_t *cfg,
                            const ogk_nmpc_plan_t *p);

/* Plan operations of the strategies (nmpc_plan.c). */
void ogk_i_nmpc_plan_control(const ogk_nmpc_plan_t *p, ogk_real_t t, ogk_real_t *u);
void ogk_i_nmpc_plan_drop(ogk_nmpc_plan_t *p, uint32_t count);
void ogk_i_nmpc_plan_regrid(const ogk_nmpc_plan_t *src, ogk_real_t t0,
                            uint32_t nodes, ogk_nmpc_plan_t *dst);
ogk_status ogk_i_nmpc_plan_subdivide(const ogk_i_ocp_t *ocp,
                                     const ogk_nmpc_plan_t *src,
                                     ogk_nmpc_plan_t *dst);

#endif /* OGK_NMPC_INTERNAL_H */
