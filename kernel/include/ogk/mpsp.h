/* ogk/mpsp.h -- Model Predictive Static Programming (MPSP) for bang-off-bang
 * low-thrust guidance, Wang & Topputo, Acta Astronautica 176 (2020),
 * sections 2.3 and 3.1-3.4, appendices A-C, with the errata listed in
 * docs/design/mpsp.md. Design, derivations and limits: docs/design/mpsp.md.
 *
 * Dynamics (eq. 16), normalised units (e.g. the paper's LU, TU, MU of Table 1):
 *   X = [r(3), v(3), m, lambda_m],  U = lambda_v(t) = P(t) W      (eqs. 36-37)
 *   r' = v,  v' = g(r) - u T/m lambda_v/|lambda_v|,  m' = -u T/c,
 *   lambda_m' = -u T |lambda_v| / m^2,
 *   S = 1 - lambda_m - |lambda_v| c / m,  u = 1 if S < 0 else 0     (eqs. 10-11)
 * The MPSP unknowns are the Fourier weights W (3 blocks of 2 n + 1, one per
 * component of lambda_v) and lambda_m(t0); the outputs are
 *   Y = [r(t_f), v(t_f), lambda_m(t_f)]  with target [r_f, v_f, 0].
 *
 * Fourier basis (Appendix C with a configurable period, see the erratum):
 *   theta = 2 pi (t - t_ref) / period,
 *   OGK_MPSP_BASIS_FOURIER: h(t) = [1/2, cos theta, sin theta, cos 2 theta,
 *                                   sin 2 theta, ..., cos n theta, sin n theta]
 *   OGK_MPSP_BASIS_COSINE:  h(t) = [1/2, cos theta, cos 2 theta, ..., cos 2n theta]
 *   lambda_v,i(t) = h(t)^T W[i (2 n + 1) .. (i + 1)(2 n + 1) - 1],  i = 0, 1, 2.
 * The paper's printed basis cos(n pi eta), eta in [-pi, pi] over [t0, tf], is
 * FOURIER with period = (tf - t0) / pi and t_ref = (t0 + tf) / 2.
 *
 * Integration: ogk_rk4_propagate (ogk/rk4.h) on the grid t0 + k h_max with
 * switching detection by bisection (|S(t_s)| <= s_tol); the control U is
 * evaluated at the RK4 stage times (erratum of Appendix A). Sensitivities are
 * those of this discrete map: a backward sweep through each RK4 step
 * (Appendix A, transposed), with the switching compensation of eqs. (22)-(25)
 * at each switch node (eqs. 28-35).
 *
 * Memory: everything lives in ogk_mpsp_t (199 KiB with the default limits);
 * no heap, no globals, every loop bounded. Stack: about 4.5 KiB worst case
 * (docs/design/mpsp.md). */
#ifndef OGK_MPSP_H
#define OGK_MPSP_H

#include <stddef.h>
#include <stdint.h>
#include "ogk/config.h"
#include "ogk/linalg.h"
#include "ogk/status.h"
#include "ogk/types.h"
#include "ogk/real.h"

#ifdef __cplusplus
extern "C" {
#endif

#define OGK_MPSP_NX 8u   /* MPSP state X = [r, v, m, lambda_m] (eq. 16) */
#define OGK_MPSP_NX0 7u  /* physical initial state x0 = [r, v, m] */
#define OGK_MPSP_NU 3u   /* MPSP control U = lambda_v */
#define OGK_MPSP_NY 7u   /* output Y = [r_f, v_f, lambda_mf] */

/* Largest Fourier order n_x (eq. C.1). */
#ifndef OGK_MPSP_MAX_ORDER
#define OGK_MPSP_MAX_ORDER 15u
#endif
/* Largest number of RK4 grid steps, ceil((tf - t0) / h_max). */
#ifndef OGK_MPSP_MAX_STEPS
#define OGK_MPSP_MAX_STEPS 2048u
#endif
/* Largest number of switches of an accepted trajectory (and of the switch
 * times reported); a trajectory with more is rejected (OGK_E_SWITCH_OVERFLOW
 * from ogk_mpsp_propagate, a failed inner loop inside ogk_mpsp_solve). */
#ifndef OGK_MPSP_MAX_SWITCHES
#define OGK_MPSP_MAX_SWITCHES 16u
#endif
/* Sensitivity samples (basis row and its 7 x 3 coefficients) gathered
 * before they are added to B_v in one blocked product, >= 3. */
#ifndef OGK_MPSP_SENS_BLOCK
#define OGK_MPSP_SENS_BLOCK 32u
#endif
/* Entries per basis function in the sample block: 2 where gcc -O2 has
 * 2-lane double SIMD without options (SSE2: every x86-64), each h value held
 * twice so that B_v's blocked product reads it as a pair; 1 elsewhere (the
 * Cortex-M7's FPU is scalar). */
#if defined(__SSE2__)
#define OGK_MPSP_H_LANES 2u
#else
#define OGK_MPSP_H_LANES 1u
#endif
/* U = lambda_v and |U| kept by the propagation for the sensitivity sweep
 * where the paired passes run (SSE2), one slot per half grid step (node k:
 * slot 2 k, the midpoint of step k: 2 k + 1); host memory, not kept on the
 * Cortex-M7 (the sweep makes U there again). */
#if defined(__SSE2__)
#define OGK_MPSP_KEEP_U_SLOTS ((2u * OGK_MPSP_MAX_STEPS) + 2u)
#endif
/* Entries of the Newton history kept in the result. */
#ifndef OGK_MPSP_MAX_LOG
#define OGK_MPSP_MAX_LOG 64u
#endif

#define OGK_MPSP_MAX_BASIS ((2u * OGK_MPSP_MAX_ORDER) + 1u)
#define OGK_MPSP_MAX_WEIGHTS (OGK_MPSP_NU * OGK_MPSP_MAX_BASIS)
#define OGK_MPSP_MAX_UNKNOWNS (OGK_MPSP_MAX_WEIGHTS + 1u)
/* Dense-output nodes: every grid node, t0 and tf, and every switch node the
 * integrator may record (OGK_RK4_MAX_SWITCHES, so the dense output never runs
 * out before the integrator's own switch limit). */
#define OGK_MPSP_MAX_NODES (OGK_MPSP_MAX_STEPS + OGK_RK4_MAX_SWITCHES + 1u)

/* Value of ogk_mpsp_t.init_marker in a usable context (any other: not initialised). */
#define OGK_MPSP_INIT_MARKER 0x4D505350u /* "MPSP" */

/* Basis kinds (ogk_mpsp_config_t.fourier_kind); 2 n + 1 functions either way. */
#define OGK_MPSP_BASIS_FOURIER 0u /* 1/2, cos k theta, sin k theta, k = 1..n (eq. C.1) */
#define OGK_MPSP_BASIS_COSINE 1u  /* 1/2, cos k theta, k = 1..2n (even extension) */

/* Sensitivity sweeps (ogk_mpsp_config_t.sens_sweep): how ogk_mpsp_sensitivity
 * carries dY/dX back over one RK4 step (docs/design/mpsp.md, sections 3 and 8).
 * The residual is always that of the exact propagation, so the sweep only
 * sets Newton's rate of convergence, not the accuracy of the solution. */
#define OGK_MPSP_SWEEP_RK4 0u  /* exact derivative of the RK4 step (four stages; B_v sampled at nodes and midpoints) */
#define OGK_MPSP_SWEEP_MID2 1u /* second-order transition I + h J + h^2/2 J^2, J at the step midpoint; B_v one midpoint sample per step (O(h^2)) */

/* Configuration, read-only after ogk_mpsp_init (copied into the context).
 * Units: any consistent normalised set (LU, TU, MU); [T] = MU LU / TU^2. */
typedef struct {
    ogk_real_t mu;                  /* [LU^3/TU^2] gravitational parameter, >= 0 (0: field-free) */
    ogk_real_t t_max;               /* [MU LU/TU^2] nominal maximum thrust T_max, > 0 */
    ogk_real_t c_exhaust;           /* [LU/TU] exhaust velocity c = Isp g0, > 0 */
    ogk_real_t t0;                  /* [TU] initial time */
    ogk_real_t tf;                  /* [TU] final time, > t0 */
    ogk_real_t x0_nom[OGK_MPSP_NX0]; /* [LU, LU/TU, MU] nominal r0, v0, m0 (C_nom of eq. 51), m0 > 0 */
    ogk_real_t r_f[3];              /* [LU] nominal target position */
    ogk_real_t v_f[3];              /* [LU/TU] nominal target velocity */
    uint32_t fourier_order;     /* [-] n_x of eq. (C.1), 1..OGK_MPSP_MAX_ORDER */
    uint32_t fourier_kind;      /* [-] OGK_MPSP_BASIS_FOURIER or OGK_MPSP_BASIS_COSINE */
    ogk_real_t fourier_period;      /* [TU] fundamental period of the basis, > 0 (erratum: 2 (tf - t0) fits the Apophis nominal) */
    ogk_real_t fourier_t_ref;       /* [TU] time of zero phase of the basis */
    ogk_real_t h_max;               /* [TU] RK4 grid step, ceil((tf - t0)/h_max) <= OGK_MPSP_MAX_STEPS */
    ogk_real_t delta_max;           /* [mixed] Newton only while ||Delta Y||_2 <= Delta_max (Alg. 1), > 0 */
    ogk_real_t delta_tau_0;         /* [-] initial continuation step (Alg. 2), (0, 1] */
    ogk_real_t delta_tau_min;       /* [-] continuation fails when a step <= this is needed (paper 0.1), [0, delta_tau_0) */
    ogk_real_t r_eps[OGK_MPSP_MAX_WEIGHTS]; /* [-] diagonal of R_eps (eq. 41), first n_weights entries > 0 */
    ogk_real_t r_lambda;            /* [-] R_lambda (eq. 41), > 0 */
    ogk_real_t tol_r;               /* [LU] convergence: ||r(tf) - r_f|| <= tol_r, > 0 */
    ogk_real_t tol_v;               /* [LU/TU] convergence: ||v(tf) - v_f|| <= tol_v, > 0 */
    ogk_real_t tol_lambda_m;        /* [-] convergence: |lambda_m(tf)| <= tol_lambda_m, > 0 */
    ogk_real_t s_tol;               /* [-] switch accepted when |S(t_s)| <= s_tol (paper 1e-12), > 0 */
    uint32_t max_newton;        /* [-] Newton iterations per inner loop, >= 1 */
    uint32_t max_outer;         /* [-] inner loops run by the continuation (Alg. 2), >= 1 */
    uint32_t n_seg_tol;         /* [-] initial N_seg,tol (paper 0) */
    uint32_t n_seg_tol_step;    /* [-] increase of N_seg,tol after a failed continuation (paper 2), >= 1 */
    ogk_real_t weights_nom[OGK_MPSP_MAX_WEIGHTS]; /* [-] nominal weights epsilon_0 (eq. 50), first n_weights used */
    ogk_real_t lambda_m0_nom;       /* [-] nominal lambda_m(t0) */
    uint32_t n_seg_nom;         /* [-] N_seg,nom = thrust + coast segments of the nominal; 0: counted at init
                                   by propagating the nominal weights from x0_nom */
    uint32_t sens_sweep;        /* [-] OGK_MPSP_SWEEP_RK4 (exact) or OGK_MPSP_SWEEP_MID2 (cheaper, O(h^2)) */
} ogk_mpsp_config_t;

/* Summary of one propagation (the trajectory itself stays in the context). */
typedef struct {
    ogk_real_t x_f[OGK_MPSP_NX];    /* [LU, LU/TU, MU, -] X(tf) */
    uint32_t n_switches;        /* [-] switches found */
    ogk_real_t t_switch[OGK_MPSP_MAX_SWITCHES]; /* [TU] switch times (first OGK_MPSP_MAX_SWITCHES) */
    uint32_t n_segments;        /* [-] N_seg = thrust + coast segments = n_switches + 1 */
    uint32_t n_thrust_arcs;     /* [-] segments flown with u = 1 */
    int mode0;                  /* [-] u on the first segment (0 coast, 1 thrust) */
    size_t n_nodes;             /* [-] dense-output nodes held */
} ogk_mpsp_prop_t;

typedef struct {
    uint8_t converged;          /* [-] 1: terminal tolerances met with the returned weights */
    uint32_t newton_iterations; /* [-] evaluations of eq. (45) over all inner loops (the paper's NI) */
    uint32_t inner_loops;       /* [-] inner loops run (Alg. 1), the direct one included */
    uint32_t outer_steps;       /* [-] continuation inner loops (Alg. 2); 0 when the direct loop converged */
    uint32_t n_seg_tol;         /* [-] N_seg,tol in force at the end */
    ogk_real_t tau_reached;         /* [-] largest continuation parameter solved (1 on success) */
    ogk_real_t dy[OGK_MPSP_NY];     /* [mixed] Y(tf) - Y_d with the returned weights, perturbed conditions */
    ogk_real_t err_r;               /* [LU] ||r(tf) - r_f|| */
    ogk_real_t err_v;               /* [LU/TU] ||v(tf) - v_f|| */
    ogk_real_t lambda_mf;           /* [-] lambda_m(tf) */
    ogk_real_t m_f;                 /* [MU] final mass */
    uint32_t n_segments;        /* [-] thrust + coast segments */
    uint32_t n_thrust_arcs;     /* [-] thrust segments */
    uint32_t n_switches;        /* [-] switches */
    ogk_real_t t_switch[OGK_MPSP_MAX_SWITCHES]; /* [TU] switch times */
    size_t n_weights;           /* [-] 3 (2 n + 1) */
    ogk_real_t weights[OGK_MPSP_MAX_WEIGHTS]; /* [-] updated weights: the command (safe command on failure) */
    ogk_real_t lambda_m0;           /* [-] updated lambda_m(t0) */
    uint32_t n_log;             /* [-] entries of dy_norm_log */
    ogk_real_t dy_norm_log[OGK_MPSP_MAX_LOG]; /* [mixed] ||Delta Y||_2 before each Newton step, in order */
} ogk_mpsp_result_t;

/* Context: configuration, the last trajectory, its sensitivities and the
 * Newton workspace. Treat as opaque; read it through the functions below. */
typedef struct {
    ogk_mpsp_config_t cfg;
    size_t n_basis;             /* [-] 2 n + 1 */
    size_t n_weights;           /* [-] 3 n_basis */
    size_t n_steps;             /* [-] RK4 grid steps */
    uint32_t n_seg_nom;         /* [-] N_seg,nom in use */
    ogk_real_t omega;               /* [rad/TU] 2 pi / period */
    ogk_real_t inv_sqrt_r_eps[OGK_MPSP_MAX_WEIGHTS]; /* [-] R_eps^-1/2 */
    ogk_real_t inv_sqrt_r_lambda;   /* [-] R_lambda^-1/2 */
    /* Conditions and parameters of the trajectory held. */
    ogk_real_t thrust;              /* [MU LU/TU^2] T of the trajectory held */
    ogk_real_t x0[OGK_MPSP_NX0];    /* [LU, LU/TU, MU] its initial state */
    ogk_real_t weights[OGK_MPSP_MAX_WEIGHTS]; /* [-] its weights */
    ogk_real_t lambda_m0;           /* [-] its lambda_m(t0) */
    /* Dense trajectory (ogk_rk4_propagate's dense output). */
    ogk_real_t traj_t[OGK_MPSP_MAX_NODES];
    ogk_real_t traj_x[OGK_MPSP_MAX_NODES * OGK_MPSP_NX];
    uint8_t traj_mode[OGK_MPSP_MAX_NODES];
    size_t n_nodes;
    size_t n_switch_nodes;
    size_t switch_node[OGK_RK4_MAX_SWITCHES]; /* [-] node index of each switch */
    uint8_t traj_valid;
    uint8_t sens_valid;
    /* Sensitivities of the trajectory held (eqs. 33 and 40). */
    ogk_real_t dy_dw[OGK_MPSP_NY * OGK_MPSP_MAX_WEIGHTS]; /* B_v, row-major 7 x n_weights */
    ogk_real_t dy_dlm0[OGK_MPSP_NY];                      /* A_lambda */
    /* B_v being accumulated, basis-major: bv_acc[q][r * 3 + c] (eq. 40), and
     * the samples not yet added to it: basis rows h(t) and their 7 x 3
     * control sensitivities bU(t), added OGK_MPSP_SENS_BLOCK at a time. */
    ogk_real_t bv_acc[OGK_MPSP_MAX_BASIS * OGK_MPSP_NY * OGK_MPSP_NU];
    ogk_real_t sens_h[OGK_MPSP_SENS_BLOCK * OGK_MPSP_MAX_BASIS * OGK_MPSP_H_LANES];
    ogk_real_t sens_c[OGK_MPSP_SENS_BLOCK * OGK_MPSP_NY * OGK_MPSP_NU];
#if defined(__SSE2__)
    /* U and |U| of the trajectory held at the times the propagation made them
     * two at a time: keep_u[4 j .. 4 j + 3] = U(keep_t[j]), |U|, in the slot j
     * of the half grid step nearest keep_t[j] (NaN: empty). */
    ogk_real_t keep_t[OGK_MPSP_KEEP_U_SLOTS];      /* [TU] */
    ogk_real_t keep_u[OGK_MPSP_KEEP_U_SLOTS * 4u]; /* [-] */
#endif
    /* Newton workspace (eqs. 44-45 as a minimum-norm problem). */
    ogk_real_t newton_m[OGK_MPSP_NY * OGK_MPSP_MAX_UNKNOWNS];
    ogk_real_t newton_z[OGK_MPSP_MAX_UNKNOWNS];
    ogk_qr_t qr;
    /* Loop workspace: weights of the last solved tau (eps_k of Alg. 2), the
     * inner loop's current iterate (eps_j of Alg. 1) and its Newton trial. */
    ogk_real_t w_cont[OGK_MPSP_MAX_WEIGHTS];
    ogk_real_t w_iter[OGK_MPSP_MAX_WEIGHTS];
    ogk_real_t w_trial[OGK_MPSP_MAX_WEIGHTS];
    uint32_t init_marker;       /* [-] OGK_MPSP_INIT_MARKER once initialised */
} ogk_mpsp_t;

/* Fills every field with its default: the algorithm settings as in the
 * paper (delta_max 1, delta_tau_0 0.5, delta_tau_min 0.1, R_eps = I,
 * R_lambda = 1, s_tol 1e-12, max_newton 100, max_outer 50, n_seg_tol 0,
 * n_seg_tol_step 2, n_seg_nom 0 = counted at init, FOURIER basis, t_ref 0,
 * sens_sweep OGK_MPSP_SWEEP_MID2);
 * the mission data (mu, t_max, c_exhaust, t0, tf, x0_nom, r_f, v_f,
 * fourier_order, fourier_period, h_max, tol_r, tol_v, tol_lambda_m,
 * weights_nom, lambda_m0_nom) is 0 and must be set before ogk_mpsp_init
 * (which rejects the zeros, OGK_E_CONFIG). OGK_E_NULL. */
ogk_status ogk_mpsp_config_default(ogk_mpsp_config_t *cfg);

/* Validates cfg (OGK_E_NULL, OGK_E_NONFINITE for NaN/Inf, OGK_E_CONFIG for
 * anything out of range or over a compile-time limit) and prepares ctx. With
 * cfg->n_seg_nom == 0 the nominal is propagated to count N_seg,nom (OGK_E_CONFIG
 * if that propagation fails). On failure ctx is left uninitialised. */
ogk_status ogk_mpsp_init(ogk_mpsp_t *ctx, const ogk_mpsp_config_t *cfg);

/* Back to the state right after ogk_mpsp_init (the nominal propagated again
 * when cfg.n_seg_nom == 0, no sensitivities held), configuration kept.
 * OGK_E_NULL, OGK_E_NOT_INIT. */
ogk_status ogk_mpsp_reset(ogk_mpsp_t *ctx);

/* Two-loop MPSP (Algorithms 1 and 2) from the nominal weights for the perturbed
 * conditions C_per: initial state x0 (r, v, m at t0), thrust T_max * thrust_scale
 * (Table 6: thrust_scale = 1 + eta), target target_rv = [r_f, v_f] (NULL: the
 * configured target). Returns OGK_OK with res->converged = 1, or
 * OGK_E_NOT_CONVERGED with res->weights / lambda_m0 holding the safe command:
 * the weights solved at the largest continuation parameter reached, the nominal
 * ones if none; res->dy etc. then describe that command flown from x0. Bad
 * input: OGK_E_NULL, OGK_E_NOT_INIT, OGK_E_NONFINITE, OGK_E_RANGE (m0 <= 0,
 * thrust_scale <= 0). */
ogk_status ogk_mpsp_solve(ogk_mpsp_t *ctx, const ogk_real_t *x0, ogk_real_t thrust_scale,
                          const ogk_real_t *target_rv, ogk_mpsp_result_t *res);

/* Integrates eq. (16) from (t0, [x0, lambda_m0]) to tf with the given weights
 * and thrust T_max * thrust_scale; the dense trajectory replaces the one in
 * ctx (and invalidates its sensitivities). out may be NULL. Errors:
 * OGK_E_SWITCH_OVERFLOW (more than OGK_MPSP_MAX_SWITCHES switches; trajectory
 * kept), OGK_E_CALLBACK (mass <= 0, or lambda_v = 0 while thrusting),
 * OGK_E_NONFINITE, and the input errors of ogk_mpsp_solve. */
ogk_status ogk_mpsp_propagate(ogk_mpsp_t *ctx, const ogk_real_t *weights, ogk_real_t lambda_m0,
                              const ogk_real_t *x0, ogk_real_t thrust_scale,
                              ogk_mpsp_prop_t *out);

/* Copies the dense trajectory held: t (count), x (count x 8, row-major), mode
 * (count; u of the step leaving each node). OGK_E_DIM if capacity is short. */
ogk_status ogk_mpsp_trajectory(const ogk_mpsp_t *ctx, ogk_real_t *t, ogk_real_t *x,
                               uint8_t *mode, size_t capacity, size_t *count);

/* X(t) of the trajectory held by pchip (ogk/interp.h) over the nodes of the
 * segment containing t (never across a switch). OGK_E_RANGE outside [t0, tf]. */
ogk_status ogk_mpsp_state_at(const ogk_mpsp_t *ctx, ogk_real_t t, ogk_real_t *x);

/* lambda_v(t) = P(t) W (eqs. 36-37) for any weights (3 values); lambda_v_dot
 * (3, may be NULL) receives d lambda_v / dt. OGK_E_NONFINITE (outputs not to be used) when
 * the weights make a non-finite control: never OGK_OK with a non-finite output. */
ogk_status ogk_mpsp_control(const ogk_mpsp_t *ctx, const ogk_real_t *weights, ogk_real_t t,
                            ogk_real_t *lambda_v, ogk_real_t *lambda_v_dot);

/* Sensitivities of the trajectory held (eqs. 28-35 with eqs. 22-25 at each
 * switch): dy_dw = dY/dW (7 x n_weights, B_v of eq. 40) and dy_dlm0 = dY/d
 * lambda_m0 (7, A_lambda of eq. 33). Either output may be NULL (they are kept
 * in ctx for ogk_mpsp_newton_update). OGK_E_NOT_INIT without a trajectory;
 * OGK_E_SINGULAR at a tangential switch (dS/dt = 0). */
ogk_status ogk_mpsp_sensitivity(ogk_mpsp_t *ctx, ogk_real_t *dy_dw, ogk_real_t *dy_dlm0);

/* Newton update of eqs. (44)-(46) from the sensitivities held: weights and
 * *lambda_m0 (in/out) are decreased by the minimum-R-norm correction that
 * cancels dy (7) to first order, solved as ogk_minnorm of
 * [B_v R_eps^-1/2, A_lambda R_lambda^-1/2]. OGK_E_SINGULAR when the 7 x 7
 * matrix of eq. (44) is singular (nothing changed). */
ogk_status ogk_mpsp_newton_update(ogk_mpsp_t *ctx, const ogk_real_t *dy, ogk_real_t *weights,
                                  ogk_real_t *lambda_m0);

/* MPSP's contract call for the one command of every law (ogk/types.h): the
 * command of the trajectory held (after ogk_mpsp_solve: the converged one,
 * else the safe command's; or the last ogk_mpsp_propagate) at time t [TU],
 * in OGK_FRAME_INERTIAL (the frame of r, v): u = -lambda_v / |lambda_v|, the
 * primer-vector direction along which eq. (16) thrusts, with lambda_v(t) =
 * P(t) W of the held weights; throttle = the bang-off-bang u of eq. (11) on
 * the held trajectory's segment containing t (1: S < 0, thrust; 0: coast),
 * flags ENGINE_ON with it; law_flags 0 (MPSP has no flags). Otherwise the
 * safe command of ogk/thrust_cmd.h in OGK_FRAME_INERTIAL (engine off, u =
 * (1, 0, 0), flags SAFE) and: OGK_E_NULL (cmd NULL; ctx NULL),
 * OGK_E_NOT_INIT (no context, or no trajectory held), OGK_E_NONFINITE (t),
 * OGK_E_RANGE (t outside [t0, tf]), OGK_E_SAFE_COMMAND (lambda_v(t) = 0 or
 * not finite: no direction). */
ogk_status ogk_mpsp_thrust_cmd(const ogk_mpsp_t *ctx, ogk_real_t t, ogk_thrust_cmd_t *cmd);

/* Test entry points (one RK4 step's Jacobians, the switching compensation):
 * ogk/internal/mpsp_test.h. */

#ifdef __cplusplus
}
#endif

#endif /* OGK_MPSP_H */
