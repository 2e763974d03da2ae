/* ogk/nmpc.h -- receding-horizon nonlinear MPC for planar low-thrust
 * rendezvous with a target on a circular orbit (Starek & Kolmanovsky 2012,
 * secs. 2-3: the CNCN and SNNS strategies), solved by an SQP of our own on a
 * direct multiple-shooting transcription. Design, derivations, errata and
 * measured costs: docs/design/nmpc.md (section "Flight solver").
 *
 * Units: a normalised set documented by the scenario (docs/design/nmpc.md: LU = r_E,
 * TU = sqrt(LU^3 / mu_sun), MU = m0); every field says which. Time is absolute
 * (t = 0 at departure), so the target and third bodies follow their circular
 * ephemerides phi(t) = phi_0 + rate t.
 *
 * Predictive model (eqs. 11-14), state x = (r, theta, v_r, v_theta, m):
 *   r' = v_r,  theta' = v_theta / r,
 *   v_r' = v_theta^2 / r - mu / r^2 + (w T_max(r) / m) cos(alpha) + p_r,
 *   v_theta' = -v_theta v_r / r + (w T_max(r) / m) sin(alpha) + p_theta,
 *   m' = -w mdot_max(r)
 * alpha: thrust angle from the local vertical (0 radially outward); w: the
 * throttle in [0, 1] (w = 1 with OGK_NMPC_ENGINE_CONSTANT); T_max, mdot_max
 * constant (nuclear-electric) or eq. (14) (solar-electric, duty-cycle
 * reading); p: optional point-mass third bodies on circular orbits (direct
 * and indirect terms), a beyond-the-paper option.
 *
 * Transcription (sec. 2.3): N equal subintervals of the free horizon
 * T = t_f - t0, node states X_0 (the measured state) .. X_N, node controls
 * U_0 .. U_N, piecewise linear in between; RK4 with rk4_steps steps per
 * subinterval, the control evaluated at the stage times. Constraints:
 * continuity X_{k+1} = F_k(X_k, U_k, U_{k+1}, T) and eq. (5) at t_f
 * (r = R_T, theta = theta_T(t_f), v_r = 0, v_theta = sqrt(mu / R_T)).
 * Objective: T (minimum time) or m_0 - m_N (minimum fuel; plus time_weight T,
 * a beyond-the-paper option: fuel alone is flat in T and a perturbed closed
 * loop can keep postponing the arrival).
 *
 * SQP: exact discrete sensitivities of F_k, the state deviations condensed
 * away (unknowns dU, dT: at most OGK_NMPC_MAX_VARS), the reduced Hessian of
 * the Lagrangian exact (second order of the RK4 map weighted by the
 * continuity multipliers, regularised) or damped BFGS (as the paper's ACADO
 * runs), the QP by ogk_qp_solve (ogk/qp.h), a filter line search on
 * (constraint violation, J).
 *
 * Memory: everything in ogk_nmpc_t (no heap, no globals, every loop bounded
 * by the OGK_NMPC_MAX_* limits below). */
#ifndef OGK_NMPC_H
#define OGK_NMPC_H

#include <stddef.h>
#include <stdint.h>
#include "ogk/ocp.h"
#include "ogk/qp.h"
#include "ogk/status.h"
#include "ogk/types.h"
#include "ogk/real.h"

#ifdef __cplusplus
extern "C" {
#endif

#define OGK_NMPC_NX 5u        /* state (r, theta, v_r, v_theta, m) */
#define OGK_NMPC_NC 4u        /* terminal conditions of eq. (5) */
#define OGK_NMPC_MAX_NU 2u    /* controls per node: alpha, and the throttle w */
#define OGK_NMPC_MAX_BODIES 2u /* third bodies of the predictive model */
#if (OGK_NMPC_NX != OGK_OCP_NX) || (OGK_NMPC_NC != OGK_OCP_NC) || (OGK_NMPC_MAX_NU != OGK_OCP_MAX_NU) \
    || (OGK_NMPC_MAX_BODIES > OGK_OCP_MAX_KEEPOUT)
#error "ogk/nmpc.h's dimensions do not fit ogk/ocp.h's"
#endif

/* Largest number of subintervals N of a plan (the SNNS doubling never
 * exceeds it). */
#ifndef OGK_NMPC_MAX_NODES
#define OGK_NMPC_MAX_NODES 32u
#endif
/* Largest number of RK4 steps per subinterval. */
#ifndef OGK_NMPC_MAX_RK4_STEPS
#define OGK_NMPC_MAX_RK4_STEPS 32u
#endif
/* Largest number of SQP iterations of one solve. */
#ifndef OGK_NMPC_MAX_SQP_ITER
#define OGK_NMPC_MAX_SQP_ITER 500u
#endif
/* Largest number of backtracking steps of one line search. */
#define OGK_NMPC_MAX_LINE_SEARCH 30u

/* Largest |time| a solve or replan accepts [TU] (OGK_E_RANGE beyond): far
 * past it t + horizon_min rounds to t (1e6 TU is 160,000 years). */
#define OGK_NMPC_T_ABS_MAX OGK_R(1.0e6)

/* QP unknowns: the node-control corrections and the horizon correction. */
#define OGK_NMPC_MAX_VARS (((OGK_NMPC_MAX_NODES + 1u) * OGK_NMPC_MAX_NU) + 1u)
/* Keep-out rows of the QP: nodes and the RK4 step ends of the arcs within
 * three radii of a body. */
#define OGK_NMPC_MAX_KO_ROWS (2u * OGK_NMPC_MAX_NODES)
/* General inequality rows of the QP: the sweep bound (2 per subinterval),
 * the keep-out, the terminal set (2 per condition of eq. 5) and the
 * propellant limit (1). */
#define OGK_NMPC_MAX_ROWS ((2u * OGK_NMPC_MAX_NODES) + OGK_NMPC_MAX_KO_ROWS + (2u * OGK_NMPC_NC) + 1u)
/* Unknowns of the elastic QP: v, the slacks s+, s- of eq. (5) and the
 * keep-out rows' one slack. */
#define OGK_NMPC_MAX_QP ((OGK_NMPC_MAX_VARS + (2u * OGK_NMPC_NC)) + 1u)
/* Sensitivity directions of one subinterval: X_k, U_k, U_{k+1}, T. */
#define OGK_NMPC_MAX_DIR (OGK_NMPC_NX + (2u * OGK_NMPC_MAX_NU) + 1u)
/* Row stride of one subinterval's sensitivity matrices: its directions and
 * the start time (OGK_NMPC_MAX_DIR + 1), rounded up to an even count (the
 * forward sweep goes through the columns by pairs). */
#define OGK_NMPC_SENS_COLS (((OGK_NMPC_MAX_DIR + 2u) / 2u) * 2u)
/* Doubles the exact Hessian records per RK4 step of one subinterval (the
 * forward sweep's tape, read back by the second-order adjoint sweep): the
 * step's sensitivity matrix (5 x OGK_NMPC_SENS_COLS) and, per stage, its
 * state (5), its derivative k (5), cos/sin of its angle (2), the model's
 * Jacobian (5 x 5) and k's sensitivities (5 x OGK_NMPC_SENS_COLS). */
#define OGK_NMPC_TAPE_STEP ((OGK_NMPC_NX * OGK_NMPC_SENS_COLS) \
    + (4u * ((2u * OGK_NMPC_NX) + 2u + (OGK_NMPC_NX * OGK_NMPC_NX) + (OGK_NMPC_NX * OGK_NMPC_SENS_COLS))))

/* ogk_nmpc_config_t.objective */
/* doubles of one subinterval's sensitivity key: X_k, U_k, U_k+1, h, t_start */
#define OGK_NMPC_SENS_KEY (OGK_NMPC_NX + (2u * OGK_NMPC_MAX_NU) + 2u)
/* doubles of the predictive model's fields (the configuration's mu .. body_softening and rk4_steps) */
#define OGK_NMPC_SENS_MODEL (16u + (5u * OGK_NMPC_MAX_BODIES))
#if OGK_NMPC_SENS_MODEL != OGK_OCP_MODEL_KEY
#error "OGK_NMPC_SENS_MODEL (the sensitivity cache's model key) differs from OGK_OCP_MODEL_KEY"
#endif

#define OGK_NMPC_MIN_TIME 0u
#define OGK_NMPC_MIN_FUEL 1u
/* ogk_nmpc_config_t.engine */
#define OGK_NMPC_ENGINE_CONSTANT 0u  /* w = 1: the control is alpha only (nu = 1) */
#define OGK_NMPC_ENGINE_THROTTLED 1u /* controls (alpha, w), 0 <= w <= 1 (nu = 2) */
/* ogk_nmpc_config_t.power */
#define OGK_NMPC_POWER_CONSTANT 0u   /* T_max = thrust_max, mdot_max = mass_flow_max (eqs. 12-13) */
#define OGK_NMPC_POWER_SOLAR 1u      /* eq. (14): T_max(r), mdot_max(r) from p(r) */
/* ogk_nmpc_config_t.hessian */
#define OGK_NMPC_HESSIAN_BFGS 0u     /* damped BFGS (Powell), carried from solve to solve (the default) */
#define OGK_NMPC_HESSIAN_EXACT 1u    /* second order of the discrete map, convexified (docs/design/nmpc-flight.md) */
/* ogk_nmpc_config_t.strategy */
#define OGK_NMPC_SNNS 0u             /* shrinking number of nodes with subdivision (sec. 2.3.3) */
#define OGK_NMPC_CNCN 1u             /* constant number of control nodes (sec. 2.3.1) */

/* ogk_nmpc_report_t.flags and ogk_nmpc_command_t.law_flags */
#define OGK_NMPC_FLAG_CONVERGED 0x01u   /* the solve met its tolerances; the plan is new */
#define OGK_NMPC_FLAG_STALE 0x02u       /* the solve failed: the previous plan, shifted, is flown */
#define OGK_NMPC_FLAG_SUBDIVIDED 0x04u  /* SNNS doubled the node count at this replan */
#define OGK_NMPC_FLAG_REGRIDDED 0x08u   /* nodes re-placed by interpolation (CNCN, or SNNS at min_nodes) */
#define OGK_NMPC_FLAG_LS_FAILED 0x10u   /* the line search found no acceptable step (solve failed) */
#define OGK_NMPC_FLAG_END_OF_PLAN 0x20u /* command asked past t_f: the last node's control is held */
#define OGK_NMPC_FLAG_ELASTIC 0x40u     /* a QP was infeasible and solved in elastic mode (eq. 5 relaxed) */
#define OGK_NMPC_FLAG_RELEASED 0x80u    /* a third body's gravity left the predictive model at this call (body_release) */
#define OGK_NMPC_FLAG_OUTSIDE_SET 0x100u /* converged outside the terminal set (terminal_box): the vehicle cannot reach it;
                                          * the plan ends as close to it as it can (l1, priced at elastic_weight) */

#define OGK_NMPC_INIT_MARKER 0x4E4D5043u /* "NMPC" */

/* Configuration, read-only after ogk_nmpc_init (copied into the context). */
typedef struct {
    /* predictive model */
    ogk_real_t mu;                  /* [LU^3/TU^2] central body (the Sun), > 0 (normalised: 1) */
    uint32_t engine;            /* [-] OGK_NMPC_ENGINE_CONSTANT or _THROTTLED */
    uint32_t power;             /* [-] OGK_NMPC_POWER_CONSTANT or _SOLAR */
    ogk_real_t thrust_max;          /* [MU LU/TU^2] T_0 (POWER_CONSTANT), > 0; must be set */
    ogk_real_t mass_flow_max;       /* [MU/TU] |dm/dt| at T_0 (POWER_CONSTANT), >= 0; must be set */
    ogk_real_t solar_length_unit;   /* [LU] unit of r in eq. (14) (1 AU), > 0 with POWER_SOLAR */
    ogk_real_t solar_a[4];          /* [-] a_1 .. a_4 of eq. (14): p = (a1 s^2 + a2 s + a3) / (s^4 (1 + a4 s)), s = r / unit */
    ogk_real_t solar_thrust[2];     /* [MU LU/TU^2] T_max(r) = solar_thrust[0] + solar_thrust[1] p (b_1, b_2 P_0) */
    ogk_real_t solar_flow[2];       /* [MU/TU] mdot_max(r) = solar_flow[0] + solar_flow[1] p (-c_1, -c_2 P_0), > 0 where flown */
    uint32_t n_bodies;          /* [-] third bodies in the predictive model, 0..OGK_NMPC_MAX_BODIES (paper: 0) */
    ogk_real_t body_mu[OGK_NMPC_MAX_BODIES];     /* [LU^3/TU^2] their gravitational parameters, >= 0 */
    ogk_real_t body_radius[OGK_NMPC_MAX_BODIES]; /* [LU] their circular-orbit radii, > 0 */
    ogk_real_t body_phase0[OGK_NMPC_MAX_BODIES]; /* [rad] their polar angles at t = 0 */
    ogk_real_t body_rate[OGK_NMPC_MAX_BODIES];   /* [rad/TU] their angular rates */
    ogk_real_t body_softening[OGK_NMPC_MAX_BODIES]; /* [LU] Plummer length eps, |d|^3 -> (|d|^2 + eps^2)^(3/2), >= 0 (0: point mass) */
    ogk_real_t keepout_radius[OGK_NMPC_MAX_BODIES]; /* [LU] nodes 1..N-1 and the arcs between the nodes (their interior RK4 step ends) stay this far from body b's centre (b < n_bodies; body_mu may be 0 for an ephemeris only), >= 0 (0: none) */
    ogk_real_t body_release[OGK_NMPC_MAX_BODIES];   /* [LU] body b's gravity leaves the predictive model for good at the first solve or replan
                                                 *      whose measured state is farther than this from its centre and on an escape orbit from
                                                 *      it (two-body energy >= 0; its ephemeris stays, for the keep-out): a departure planet
                                                 *      modelled only while it matters, inside its Hill sphere or bound to it
                                                 *      (docs/design/nmpc-flight.md, "Robustness"), >= 0 (0: never, the default) */
    /* target: circular orbit (eqs. 5-6) */
    ogk_real_t target_radius;       /* [LU] R_T, > 0; must be set */
    ogk_real_t target_phase0;       /* [rad] theta_T at t = 0 */
    ogk_real_t target_rate;         /* [rad/TU] theta_T' (sqrt(mu / R_T^3) on a Keplerian orbit) */
    ogk_real_t terminal_box[OGK_NMPC_NC]; /* [LU, rad, LU/TU, LU/TU] the terminal set: |r - R_T|, |theta - theta_T(t_f)|,
                                 *     |v_r|, |v_theta - v_T| at t_f within these half-widths, each >= 0; all 0
                                 *     (the default): eq. (5) exactly, as the paper. Beyond the paper: with eq. (5)
                                 *     exact a disturbed minimum-time plan has no slack near the end and its re-solve
                                 *     jumps to another branch (docs/design/nmpc-flight.md, "Robustness") */
    /* transcription */
    uint32_t objective;         /* [-] OGK_NMPC_MIN_TIME or OGK_NMPC_MIN_FUEL */
    ogk_real_t time_weight;         /* [MU/TU] minimum fuel only: J = m_0 - m_N + time_weight T, >= 0 (default 0: the paper's) */
    ogk_real_t mass_min;            /* [MU] the propellant limit: the final node's mass m_N >= mass_min (the dry mass;
                                 *     m decreases along every arc, so m_N bounds them all), >= 0 (default 0: none) */
    uint32_t nodes;             /* [-] N of the first plan, 1..OGK_NMPC_MAX_NODES (default 30) */
    uint32_t rk4_steps;         /* [-] RK4 steps per subinterval, 1..OGK_NMPC_MAX_RK4_STEPS (default 8) */
    ogk_real_t horizon_min;         /* [TU] lower bound of T, > 0 (default 1e-3) */
    ogk_real_t horizon_max;         /* [TU] upper bound of T, > horizon_min (default 30) */
    ogk_real_t max_sweep;           /* [rad] bound on |alpha_{k+1} - alpha_k|, 0: none (default 0) */
    /* SQP */
    uint32_t max_iter;          /* [-] SQP iterations per warm solve (a BFGS matrix carried), 1..OGK_NMPC_MAX_SQP_ITER (default 100) */
    uint32_t max_iter_cold;     /* [-] SQP iterations per cold solve (first plan, after a failure, doubling test), 1..OGK_NMPC_MAX_SQP_ITER (default 200) */
    ogk_real_t tol_feas;            /* [LU, LU/TU, MU] max |defect|, |terminal residual| at convergence, > 0 (default 1e-9) */
    ogk_real_t tol_stat;            /* [-] max |H dv| (reduced stationarity) at convergence, > 0 (default 1e-7) */
    ogk_real_t tol_obj;             /* [-] or converged when the QP step's predicted |dJ| <= tol_obj max(|J|, 1), >= 0 (default 1e-7) */
    uint32_t hessian;           /* [-] OGK_NMPC_HESSIAN_BFGS (default: damped BFGS of the reduced Hessian) or
                                 *     OGK_NMPC_HESSIAN_EXACT (sum_k mu_k^T d2F_k of the RK4 maps, condensed,
                                 *     convexified along the eq. (5) normals, the scaled identity for an
                                 *     iteration where that is not enough;
                                 *     converges in the interior-point peers' iterations: docs/design/nmpc-flight.md) */
    ogk_real_t hessian_init;        /* [-] scale of the first BFGS matrix (identity times it; also the QP's Hessian after a
                                 *     failed factorisation), > 0 (default 1) */
    ogk_real_t step_max_alpha;      /* [rad] bound on one SQP step of a node angle, > 0 (default 1) */
    ogk_real_t step_max_horizon;    /* [TU] bound on one SQP step of T, > 0 (default 1) */
    ogk_real_t elastic_weight;      /* [J units per residual unit] l1 weight of eq. (5)'s slacks in an elastic QP, > 0 (default 1000) */
    /* receding horizon (sec. 2.3) */
    uint32_t strategy;          /* [-] OGK_NMPC_SNNS or OGK_NMPC_CNCN */
    uint32_t min_nodes;         /* [-] SNNS: fewest subintervals; below it the plan is regridded to min_nodes (default 2) */
    uint32_t max_subdivisions;  /* [-] SNNS: doublings allowed over the flight (default 2) */
    ogk_real_t doubling_threshold;  /* [-] SNNS: double when (J_N - J_2N) / |J_N| > this (default 0.01 = 1 %) */
    uint32_t doubling_max_nodes;/* [-] SNNS: run the doubling test only when N <= this (<= MAX_NODES / 2; default 8) */
} ogk_nmpc_config_t;

/* A plan: what a solve returns and the next one starts from. */
typedef struct {
    ogk_real_t t0;                  /* [TU] absolute time of node 0 */
    ogk_real_t horizon;             /* [TU] T = t_f - t0 */
    uint32_t nodes;             /* [-] N, 1..OGK_NMPC_MAX_NODES */
    uint32_t nu;                /* [-] controls per node (1 or 2; set by the context's engine) */
    ogk_real_t x[(OGK_NMPC_MAX_NODES + 1u) * OGK_NMPC_NX];     /* [LU, rad, LU/TU, LU/TU, MU] node states, row k = node k */
    ogk_real_t u[(OGK_NMPC_MAX_NODES + 1u) * OGK_NMPC_MAX_NU]; /* [rad, -] node controls, row k = node k (nu used) */
    ogk_real_t lambda[OGK_NMPC_NC]; /* [-] multipliers of eq. (5) at the last solve (dual warm start) */
} ogk_nmpc_plan_t;

/* Measured state at the replan time. */
typedef struct {
    ogk_real_t t;                   /* [TU] absolute time */
    ogk_real_t x[OGK_NMPC_NX];      /* [LU, rad, LU/TU, LU/TU, MU] state */
} ogk_nmpc_input_t;

/* What one solve or replan did. */
typedef struct {
    uint32_t flags;             /* [-] OGK_NMPC_FLAG_* */
    ogk_status solve_status;    /* [-] outcome of the last SQP (OGK_OK when converged) */
    uint32_t sqp_iterations;    /* [-] SQP iterations, every solve of the call (the doubling test too) */
    uint32_t qp_iterations;     /* [-] active-set changes of the QPs, summed */
    uint32_t solves;            /* [-] SQP solves run by the call (2 with a doubling test) */
    uint32_t nodes;             /* [-] N of the plan now flown */
    ogk_real_t t_next;              /* [TU] end of the plan's first subinterval: the next replan time */
    ogk_real_t t_f;                 /* [TU] the plan's final time */
    ogk_real_t objective;           /* [TU or MU] J of the plan flown */
    ogk_real_t feas;                /* [mixed] max |defect or terminal residual| of the plan flown */
    ogk_real_t stat;                /* [-] last reduced stationarity |H dv|_inf */
} ogk_nmpc_report_t;

/* Command of the plan at one time. */
typedef struct {
    ogk_real_t t;                   /* [TU] time the command is for */
    ogk_real_t alpha;               /* [rad] thrust angle from the local vertical (paper's convention) */
    ogk_real_t throttle;            /* [-] w in [0, 1] (1 with OGK_NMPC_ENGINE_CONSTANT) */
    uint32_t flags;             /* [-] OGK_THRUST_FLAG_* of ogk/types.h (ENGINE_ON, SAFE) */
    uint32_t law_flags;         /* [-] OGK_NMPC_FLAG_* of the plan flown */
} ogk_nmpc_command_t;

/* Context. Treat as opaque; read it through the functions below. */
typedef struct {
    ogk_nmpc_config_t cfg;      /* the configuration; body_mu[b] is 0 once body b is released (body_release) */
    ogk_real_t body_mu_init[OGK_NMPC_MAX_BODIES]; /* [LU^3/TU^2] the configuration's body_mu, restored by reset */
    uint32_t nu;                /* [-] controls per node */
    uint32_t subdivisions;      /* [-] doublings made since init or reset */
    uint32_t plan_flags;        /* [-] OGK_NMPC_FLAG_* of the plan flown */
    uint8_t have_plan;          /* [-] 1 once a plan is loaded */
    ogk_nmpc_plan_t plan;       /* the plan flown */
    ogk_nmpc_plan_t work;       /* the SQP iterate */
    ogk_nmpc_plan_t trial;      /* the line-search point */
    ogk_nmpc_plan_t alt;        /* the doubled plan of the SNNS test */
    ogk_real_t hess[OGK_NMPC_MAX_VARS * OGK_NMPC_MAX_VARS];     /* [-] QP Hessian (BFGS: the matrix of the plan flown) */
    ogk_real_t hess_alt[OGK_NMPC_MAX_VARS * OGK_NMPC_MAX_VARS]; /* [-] BFGS matrix of the doubled plan */
    uint8_t hess_valid;         /* [-] 1: hess belongs to the plan flown (warm start) */
    /* sensitivities of the current iterate, per subinterval k */
    ogk_real_t sens_f[OGK_NMPC_MAX_NODES * OGK_NMPC_NX];                   /* F_k */
    ogk_real_t sens_a[OGK_NMPC_MAX_NODES * OGK_NMPC_NX * OGK_NMPC_NX];     /* dF_k/dX_k */
    ogk_real_t sens_b0[OGK_NMPC_MAX_NODES * OGK_NMPC_NX * OGK_NMPC_MAX_NU]; /* dF_k/dU_k */
    ogk_real_t sens_b1[OGK_NMPC_MAX_NODES * OGK_NMPC_NX * OGK_NMPC_MAX_NU]; /* dF_k/dU_k+1 */
    ogk_real_t sens_t[OGK_NMPC_MAX_NODES * OGK_NMPC_NX];                   /* dF_k/dT */
    ogk_real_t sens_h[OGK_NMPC_MAX_NODES * OGK_NMPC_NX];                   /* dF_k/dh (h = T / N) */
    ogk_real_t sens_ts[OGK_NMPC_MAX_NODES * OGK_NMPC_NX];                  /* dF_k/dt_start (0 without attracting bodies) */
    /* what subinterval k's sensitivities above were computed from (X_k, U_k, U_k+1, h, and t_start
     * with an attracting body) and the predictive model they used: an interval whose inputs are the
     * same bits is not swept again (a warm start's shifted intervals; docs/design/nmpc-flight.md, 2c) */
    ogk_real_t sens_key[OGK_NMPC_MAX_NODES * OGK_NMPC_SENS_KEY];
    ogk_real_t sens_model[OGK_NMPC_SENS_MODEL]; /* the model of every key (keys all 0, matching no interval, after a change) */
    /* the keep-out along subinterval k's arc, from the same sweep as its sensitivities: per body b the
     * interior RK4 step ends within three keep-out radii (bit j: step j's end), and the arc's violation */
    uint32_t arc_mask[OGK_NMPC_MAX_NODES * OGK_OCP_MAX_KEEPOUT]; /* [-] */
    ogk_real_t arc_viol[OGK_NMPC_MAX_NODES * 2u];   /* [LU] sum and largest of max(0, R - d) over the arc's step ends */
    /* exact Hessian: per subinterval k the block sum_i mu_k,i d2F_k,i in (X_k, U_k, U_k+1, T),
     * OGK_NMPC_MAX_DIR square, and the tape of the interval being swept */
    ogk_real_t hess_blk[OGK_NMPC_MAX_NODES * OGK_NMPC_MAX_DIR * OGK_NMPC_MAX_DIR];
    ogk_real_t tape[OGK_NMPC_MAX_RK4_STEPS * OGK_NMPC_TAPE_STEP];
    ogk_real_t hess_tmp[2u * OGK_NMPC_MAX_DIR * OGK_NMPC_MAX_VARS]; /* scratch: one interval's second derivatives, then the condensing's */
    /* condensed QP */
    ogk_real_t cond_g[OGK_NMPC_NX * OGK_NMPC_MAX_VARS]; /* dX_N / dv */
    ogk_real_t cond_e[OGK_NMPC_NX];                     /* dX_N at v = 0 (the defects carried) */
    ogk_real_t el_h[OGK_NMPC_MAX_QP * OGK_NMPC_MAX_QP];      /* elastic QP: Hessian */
    ogk_real_t el_g[OGK_NMPC_MAX_QP];
    ogk_real_t el_aeq[OGK_NMPC_NC * OGK_NMPC_MAX_QP];
    ogk_real_t el_ain[OGK_NMPC_MAX_ROWS * OGK_NMPC_MAX_QP];
    ogk_real_t el_lb[OGK_NMPC_MAX_QP];
    ogk_real_t el_ub[OGK_NMPC_MAX_QP];
    ogk_real_t qp_aeq[OGK_NMPC_NC * OGK_NMPC_MAX_VARS];
    ogk_real_t qp_beq[OGK_NMPC_NC];
    ogk_real_t qp_ain[OGK_NMPC_MAX_ROWS * OGK_NMPC_MAX_VARS];
    ogk_real_t qp_bin[OGK_NMPC_MAX_ROWS];
    ogk_real_t ko_a[OGK_NMPC_MAX_KO_ROWS * OGK_NMPC_MAX_VARS]; /* keep-out rows of the condensed QP */
    ogk_real_t ko_b[OGK_NMPC_MAX_KO_ROWS];
    size_t ko_rows;             /* [-] keep-out rows in use */
    ogk_real_t qp_lb[OGK_NMPC_MAX_VARS];
    ogk_real_t qp_ub[OGK_NMPC_MAX_VARS];
    ogk_real_t grad_lag[OGK_NMPC_MAX_VARS];  /* reduced Lagrangian gradient of the last iterate */
    ogk_real_t step_v[OGK_NMPC_MAX_VARS];    /* accepted step in the QP unknowns */
    ogk_real_t dx[(OGK_NMPC_MAX_NODES + 1u) * OGK_NMPC_NX]; /* state part of the step */
    ogk_qp_workspace_t qp_ws;
    ogk_qp_solution_t qp_sol;
    /* the problem (ogk/ocp.h): its callback table (a const table, in flash) and its data (NULL: the
     * heliocentric problem of this header over cfg, ogk_nmpc_init) */
    const ogk_ocp_problem_t *problem;
    void *problem_data;
    uint32_t init_marker;       /* [-] OGK_NMPC_INIT_MARKER once initialised */
} ogk_nmpc_t;

/* Fills every field with its default; the mission data (thrust_max,
 * mass_flow_max, target_radius) are 0 and must be set. */
ogk_status ogk_nmpc_config_default(ogk_nmpc_config_t *cfg);

/* Validates cfg (OGK_E_NULL, OGK_E_NONFINITE, OGK_E_CONFIG) and copies it. */
ogk_status ogk_nmpc_init(ogk_nmpc_t *ctx, const ogk_nmpc_config_t *cfg);

/* The same solver on another problem (ogk/ocp.h): cfg's transcription, SQP
 * and strategy fields and its engine (the throttle a control or not) are
 * validated and copied, its heliocentric model and target fields are not
 * read; problem (a table that outlives ctx) and data (the problem's, which
 * the caller validates and keeps alive and in place while ctx is used)
 * replace the heliocentric model. OGK_E_NULL, OGK_E_NONFINITE, OGK_E_CONFIG
 * (a callback missing). */
ogk_status ogk_nmpc_init_problem(ogk_nmpc_t *ctx, const ogk_nmpc_config_t *cfg,
                                 const ogk_ocp_problem_t *problem, void *data);

/* Back to the state right after init (no plan; configuration kept). */
ogk_status ogk_nmpc_reset(ogk_nmpc_t *ctx);

/* In-flight settings (the configuration's fields, validated as by init; a
 * rejected value leaves the context as it was): the bounds of T of the
 * solves and replans that follow, 0 < horizon_min < horizon_max [TU] (a
 * guidance that keeps a final time t_f* narrows them about t_f* - t before
 * each replan: docs/design/nmpc-problem.md, "Fixed final time"), and the scale of
 * the BFGS matrix the next cold solve starts from, > 0 [-]. The plan is
 * untouched: the next solve's step bounds move a plan's T into new bounds,
 * but from a converged plan a move beyond its accuracy fails the line
 * search (OGK_E_NOT_CONVERGED: the filter takes no step that raises J from
 * a feasible point), so narrow them about the held plan's T, or load a
 * plan scaled into them; reset keeps them, init restores the
 * configuration's.
 * OGK_E_NULL, OGK_E_NOT_INIT, OGK_E_NONFINITE, OGK_E_CONFIG. */
ogk_status ogk_nmpc_set_horizon_bounds(ogk_nmpc_t *ctx, ogk_real_t horizon_min, ogk_real_t horizon_max);
ogk_status ogk_nmpc_set_hessian_init(ogk_nmpc_t *ctx, ogk_real_t hessian_init);

/* Loads a plan (the ground's open-loop solution, or any guess): nodes in
 * 1..OGK_NMPC_MAX_NODES, nu equal to the engine's, horizon within its bounds,
 * everything finite, r and m > 0 (OGK_E_DIM, OGK_E_RANGE, OGK_E_NONFINITE).
 * The BFGS matrix restarts. */
ogk_status ogk_nmpc_load_plan(ogk_nmpc_t *ctx, const ogk_nmpc_plan_t *plan);

/* Copies the plan flown. OGK_E_RANGE when none is loaded. */
ogk_status ogk_nmpc_get_plan(const ogk_nmpc_t *ctx, ogk_nmpc_plan_t *plan);

/* Solves the OCP from in (t, x) with the plan held as the guess (same node
 * count; its node 0 becomes in->x and its horizon t_f - in->t): the open
 * loop, or one re-solve without a strategy. On success the plan is replaced;
 * on failure it is kept (flag STALE) and the status says why:
 * OGK_E_ITER_LIMIT, OGK_E_NOT_CONVERGED (line search), OGK_E_INFEASIBLE (QP),
 * OGK_E_NOT_POSDEF, OGK_E_NONFINITE (a trial state left the model's domain).
 * Bad input: OGK_E_NULL, OGK_E_NOT_INIT, OGK_E_NONFINITE, OGK_E_RANGE (no plan,
 * r or m not positive, |t| > OGK_NMPC_T_ABS_MAX), the plan untouched. */
ogk_status ogk_nmpc_solve(ogk_nmpc_t *ctx, const ogk_nmpc_input_t *in,
                          ogk_nmpc_report_t *rep);

/* One MPC replan at in->t (normally the previous report's t_next): the
 * strategy's shift (SNNS: the subintervals already flown dropped; CNCN: the
 * same N regridded over [t, t_f]), then a solve, then for SNNS the doubling
 * test. A failed solve keeps flying the shifted previous plan (flag STALE,
 * the solve's status returned); the context stays usable. */
ogk_status ogk_nmpc_replan(ogk_nmpc_t *ctx, const ogk_nmpc_input_t *in,
                           ogk_nmpc_report_t *rep);

/* The plan's control at absolute time t (piecewise linear; before t0 the
 * first node's, after t_f the last node's with FLAG_END_OF_PLAN). No plan:
 * OGK_E_RANGE with the safe command (engine off, alpha 0, FLAG SAFE). */
ogk_status ogk_nmpc_command(const ogk_nmpc_t *ctx, ogk_real_t t,
                            ogk_nmpc_command_t *cmd);

/* NMPC's contract call for the one command of every law (ogk/types.h): the
 * plan's command at absolute time t [TU] (ogk_nmpc_command) in
 * OGK_FRAME_RTN. The model's thrust (cos alpha, sin alpha) along (r_hat,
 * theta_hat), alpha from the local vertical, is the r-t-n unit vector
 * u = (cos alpha, sin alpha, 0) (theta_hat = t, the orbit normal = n), so
 * the kernel's angles are alpha_rad = pi/2 - alpha (wrapped into (-pi, pi]),
 * beta_rad = 0; throttle = w, flags and law_flags as ogk_nmpc_command. The
 * statuses of ogk_nmpc_command, with NMPC's safe command converted the same
 * way (engine off, along r_hat: alpha_rad = pi/2; t_s = 0 for a non-finite t);
 * OGK_E_NULL when cmd is NULL. */
ogk_status ogk_nmpc_thrust_cmd(const ogk_nmpc_t *ctx, ogk_real_t t, ogk_thrust_cmd_t *cmd);

/* Test entry points (the model's right-hand side, one shooting interval with
 * its sensitivities): ogk/internal/nmpc_test.h. */

#ifdef __cplusplus
}
#endif

#endif /* OGK_NMPC_H */
