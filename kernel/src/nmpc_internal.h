/* nmpc_internal.h -- internal interfaces of ogk_nmpc (not public API):
 * the predictive model (nmpc_model.c), one shooting interval with its
 * sensitivities (nmpc_shoot.c), the SQP (nmpc_sqp.c) and the strategies'
 * plan operations (nmpc_plan.c). */
#ifndef OGK_NMPC_INTERNAL_H
#define OGK_NMPC_INTERNAL_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include "ogk/nmpc.h"

/* Columns of the sensitivity matrix of one interval, in this order:
 * X_k (5), U_k (nu), U_{k+1} (nu), h (1), t_start (1): the directions of
 * ogk/nmpc.h (h standing for T) and t_start. */
#define OGK_I_NMPC_MAX_COLS (OGK_NMPC_MAX_DIR + 1u)

/* xdot = f(t, x, u) and, when jx is not NULL, its Jacobians: jx (5 x 5,
 * row-major), ju (5 x nu), jt (5). trig: cos and sin of u[0] when the caller
 * has them, NULL to compute them here. OGK_E_NONFINITE when x leaves the
 * model's domain (r <= 0, m <= 0, a third body hit) or a value is not finite. */
ogk_status ogk_i_nmpc_rhs(const ogk_nmpc_config_t *cfg, uint32_t nu, double t,
                          const double *x, const double *u, const double *trig,
                          double *xdot, double *jx, double *ju, double *jt);

/* k = jx y for the first ncol columns of y and k (row stride `stride`),
 * jx a Jacobian of ogk_i_nmpc_rhs: only its structural nonzeros are used
 * (13 of 25; the sensitivity sweep's inner product). */
void ogk_i_nmpc_jx_times(const double *jx, const double *y, size_t stride,
                         size_t ncol, double *k);

/* F = x at the end of one interval [t_start, t_start + h] from x0 with the
 * control linear from u0 to u1. When sens is not NULL it receives the
 * 5 x OGK_I_NMPC_MAX_COLS sensitivity matrix (columns above; unused control
 * columns zero). */
ogk_status ogk_i_nmpc_shoot(const ogk_nmpc_config_t *cfg, uint32_t nu,
                            double t_start, double h, const double *x0,
                            const double *u0, const double *u1, double *xf,
                            double *sens);

/* Terminal residual c = (r - R_T, theta - theta_T(t_f), v_r, v_theta - v_T)
 * of eq. (5) at state x and time t_f. */
void ogk_i_nmpc_terminal(const ogk_nmpc_config_t *cfg, const double *x,
                         double t_f, double *c);

/* The SQP on ctx->work (node 0 and t0 already set) with the BFGS matrix
 * hess (nv x nv), restarted from the scaled identity when cold. Adds its
 * iterations to rep and sets rep->feas, rep->stat. */
ogk_status ogk_i_nmpc_sqp(ogk_nmpc_t *ctx, double *hess, bool cold,
                          ogk_nmpc_report_t *rep);

/* Objective of a plan: T or m_0 - m_N. */
double ogk_i_nmpc_objective(const ogk_nmpc_config_t *cfg,
                            const ogk_nmpc_plan_t *p);

/* Plan operations of the strategies (nmpc_plan.c). */
void ogk_i_nmpc_plan_control(const ogk_nmpc_plan_t *p, double t, double *u);
void ogk_i_nmpc_plan_drop(ogk_nmpc_plan_t *p, uint32_t count);
void ogk_i_nmpc_plan_regrid(const ogk_nmpc_plan_t *src, double t0,
                            uint32_t nodes, ogk_nmpc_plan_t *dst);
ogk_status ogk_i_nmpc_plan_subdivide(const ogk_nmpc_config_t *cfg,
                                     const ogk_nmpc_plan_t *src,
                                     ogk_nmpc_plan_t *dst);

#endif /* OGK_NMPC_INTERNAL_H */
