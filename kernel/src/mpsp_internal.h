/* mpsp_internal.h -- shared internals of the MPSP module (mpsp*.c only). */
#ifndef OGK_MPSP_INTERNAL_H
#define OGK_MPSP_INTERNAL_H

#include <stdbool.h>
#include <stddef.h>
#include "ogk/mpsp.h"
#include "ogk/rk4.h"
#include "ogk_checks.h"

/* Compile-time checks of the limits against the solvers used (all plain
 * integer constants, so the preprocessor evaluates them). */
#if OGK_MPSP_MAX_UNKNOWNS > OGK_LA_MAX_LONG
#error "OGK_MPSP_MAX_UNKNOWNS exceeds OGK_LA_MAX_LONG (ogk_minnorm)"
#endif
#if OGK_MPSP_NY > OGK_LA_MAX_N
#error "OGK_MPSP_NY exceeds OGK_LA_MAX_N (ogk_minnorm)"
#endif
#if OGK_MPSP_NX > OGK_RK4_MAX_STATE
#error "OGK_MPSP_NX exceeds OGK_RK4_MAX_STATE"
#endif
#if OGK_MPSP_MAX_STEPS > OGK_RK4_MAX_STEPS
#error "OGK_MPSP_MAX_STEPS exceeds OGK_RK4_MAX_STEPS"
#endif
#if OGK_MPSP_MAX_SWITCHES > OGK_RK4_MAX_SWITCHES
#error "OGK_MPSP_MAX_SWITCHES exceeds OGK_RK4_MAX_SWITCHES"
#endif

/* Everything the right-hand side of eq. (16) needs; passed to the RK4
 * callbacks as `user`. The control cache holds U at the last time asked
 * (RK4 stages 2-3 and the end of one step / start of the next share times). */
typedef struct {
    double mu;          /* [LU^3/TU^2] */
    double thrust;      /* [MU LU/TU^2] T of this propagation */
    double c_exhaust;   /* [LU/TU] */
    const double *w;    /* [-] weights, 3 blocks of n_basis */
    size_t n_basis;     /* [-] 2 n + 1 */
    uint32_t kind;      /* [-] OGK_MPSP_BASIS_* */
    double omega;       /* [rad/TU] */
    double t_ref;       /* [TU] */
    double cache_t;     /* [TU] time of cache_u */
    double cache_u[3];  /* [-] U(cache_t) */
    bool cache_ok;
} mpsp_dyn_t;

/* Partial derivatives of eq. (16) at one point (derived in docs/mpsp.md;
 * Appendix A's dF/dU block is garbled in the paper):
 *   d f_v/d r = G(r),  d f_v/d m = a_vm e,  d f_lm/d m = a_lm,
 *   d f_v/d U = d_v (I - e e^T),  d f_lm/d U = d_l e^T,
 * with e = U/|U|, a_vm = u T/m^2, a_lm = 2 u T |U|/m^3, d_v = -u T/(m |U|),
 * d_l = -u T/m^2. All thrust terms are 0 in coast. */
typedef struct {
    double g[9];        /* [1/TU^2] G(r), row-major, symmetric */
    double e[3];        /* [-] U/|U| (0 in coast when |U| = 0) */
    double a_vm;
    double a_lm;
    double d_v;
    double d_l;
    bool thrust;
} mpsp_jac_t;

/* ---- mpsp_dynamics.c */
void mpsp_dyn_setup(mpsp_dyn_t *dyn, const ogk_mpsp_t *ctx, const double *weights,
                    double thrust);
/* h(t) (n_basis) and optionally dh/dt. */
void mpsp_basis(const mpsp_dyn_t *dyn, double t, double *h, double *hdot);
/* U = P(t) W from a basis vector. */
void mpsp_control_from_basis(const mpsp_dyn_t *dyn, const double *h, double *u);
/* U(t) through the cache. */
void mpsp_control_at(mpsp_dyn_t *dyn, double t, double *u);
/* Eq. (16) with U given; OGK_E_CALLBACK on m <= 0 or |U| = 0 while thrusting. */
ogk_status mpsp_rhs(const mpsp_dyn_t *dyn, const double *x, const double *u, int mode,
                    double *xdot);
/* Eq. (10). */
double mpsp_switch_value(const mpsp_dyn_t *dyn, const double *x, const double *u);
ogk_status mpsp_jacobian(const mpsp_dyn_t *dyn, const double *x, const double *u,
                         int mode, mpsp_jac_t *jac);
/* The RK4 problem of eq. (16) on dyn (its callbacks take user = dyn). */
void mpsp_rk4_problem(ogk_rk4_problem_t *p, const ogk_mpsp_t *ctx, mpsp_dyn_t *dyn);

/* ---- mpsp_sensitivity.c */
/* Adjoint row vectors are held "lane-major": up to MPSP_LANES row vectors w_r
 * (rows of d(.)/dX) stored as a[i * MPSP_LANES + r] for component i of row r,
 * so every operation is a fixed-length loop over the rows (unrolled and
 * vectorised by the compiler). Control sensitivities likewise as
 * bu[c * MPSP_LANES + r]. Unused lanes are zero. */
#define MPSP_LANES 8u

/* Adjoint of one RK4 step (Appendix A, transposed): for the row vectors
 * adj_in (NX x MPSP_LANES, lane-major) of d(.)/dX_next, writes w dX_next/dX to
 * adj_out and ADDS w dX_next/dU_stage to bu_start (U at t), bu_mid (t + dt/2,
 * stages 2 and 3) and bu_end (t + dt), each 3 x MPSP_LANES. u_start, u_mid,
 * u_end are U at those times (not read in coast). */
ogk_status mpsp_step_adjoint(const mpsp_dyn_t *dyn, const double *x, double dt, int mode,
                             const double *u_start, const double *u_mid,
                             const double *u_end, const double *adj_in,
                             double *adj_out, double *bu_start, double *bu_mid,
                             double *bu_end);

/* Terms of the switching compensation at (t_s, x_s) (eqs. 24-25, B.2):
 * dX+ = dX- + dxdot (s_x dX- + s_u dU) / s_dot; dt_s = -(s_x dX- + s_u dU) / s_dot. */
typedef struct {
    double dxdot[OGK_MPSP_NX]; /* Xdot+ - Xdot- */
    double s_x[OGK_MPSP_NX];   /* dS/dX */
    double s_u[3];             /* dS/dU */
    double s_dot;              /* dS/dt along the trajectory, eq. (15) */
} mpsp_jump_t;

ogk_status mpsp_jump_terms(mpsp_dyn_t *dyn, double t_s, const double *x_s,
                           int mode_before, mpsp_jump_t *jump);

/* ---- mpsp_propagate.c */
/* Propagates into ctx; t_max_eff is T (already scaled). */
ogk_status mpsp_propagate_ctx(ogk_mpsp_t *ctx, const double *weights, double lambda_m0,
                              const double *x0, double thrust, ogk_mpsp_prop_t *out);

#endif /* OGK_MPSP_INTERNAL_H */
