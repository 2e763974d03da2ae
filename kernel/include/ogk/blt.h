/* ogk/blt.h -- bilinear tangent (BLT) constant-thrust guidance with a Newton-Raphson
 * predictor-corrector (NRPC) about a binary asteroid: Xiong & Wang (seed 002), sec. II.B
 * (the model, eqs. 4-10 and 13), sec. III.A (the BLT law, eq. 22) and sec. III.D (NRPC, eqs.
 * 61-76). Model, units and the arc/meeting-point structure: docs/design/blt.md.
 *
 * Normalised units of eq. (13) (with the erratum: TU = T_o / 2 pi): LU = separation,
 * omega = 1, G (M1 + M2) = 1; masses are fractions of the spacecraft's initial mass m0. */
#ifndef OGK_BLT_H
#define OGK_BLT_H

#include <stddef.h>
#include <stdint.h>
#include "ogk/linalg.h"
#include "ogk/status.h"
#include "ogk/types.h"
#include "ogk/real.h"

#ifdef __cplusplus
extern "C" {
#endif

#define OGK_BLT_NX 6u /* [-] state: x, y, z [LU], vx, vy, vz [VU] in the synodic frame */
#define OGK_BLT_NP 7u /* [-] parameters of a segment: A (3) [-], B (3) [1/TU], T [TU] */

#ifndef OGK_BLT_MAX_SEGMENTS
#define OGK_BLT_MAX_SEGMENTS 5u /* [-] burns and coasts of one transfer */
#endif
#ifndef OGK_BLT_MAX_FREE_NODES
#define OGK_BLT_MAX_FREE_NODES 1u /* [-] unknown states at interior interfaces (free nodes) */
#endif
#define OGK_BLT_MAX_ARCS (OGK_BLT_MAX_FREE_NODES + 1u)
/* unknowns: free start components, every segment parameter, every free node */
#define OGK_BLT_MAX_UNKNOWNS (OGK_BLT_NX + (OGK_BLT_NP * OGK_BLT_MAX_SEGMENTS) + (OGK_BLT_NX * OGK_BLT_MAX_FREE_NODES))
#define OGK_BLT_MAX_ERRORS (OGK_BLT_NX * OGK_BLT_MAX_ARCS)
#ifndef OGK_BLT_MAX_SEGMENT_STEPS
#define OGK_BLT_MAX_SEGMENT_STEPS 20000u /* [-] RK4 steps of one segment (ceil(T / step_max)) */
#endif
#define OGK_BLT_MAX_ITER 500u        /* [-] bound of max_iter */
#define OGK_BLT_MAX_TRIALS 30u       /* [-] bound of the step-length and damping trials of one iteration */
#define OGK_BLT_NO_COLUMN 0xFFFFFFFFu /* [-] a fixed quantity has no column in J */

/* segment kinds */
#define OGK_BLT_SEG_COAST 0u /* engine off for T */
#define OGK_BLT_SEG_BURN 1u  /* constant thrust along eq. (22) for T */

/* segment_free bits: which of a segment's parameters the corrector may change */
#define OGK_BLT_FREE_A 0x07u   /* A_x, A_y, A_z */
#define OGK_BLT_FREE_B 0x38u   /* B_x, B_y, B_z */
#define OGK_BLT_FREE_T 0x40u   /* duration */
#define OGK_BLT_FREE_ALL 0x7Fu

/* correctors */
#define OGK_BLT_CORR_NRPC 0u /* eq. (64), minimum-norm Newton step, with the paper's line search */
#define OGK_BLT_CORR_LM 1u   /* damped minimum-norm step (Levenberg-Marquardt), beyond the paper */
#define OGK_BLT_CORR_HYBRID 2u /* eq. (64) with the paper's search first; the LM search when it finds no decrease */

/* Jacobians */
#define OGK_BLT_JAC_CENTRAL 0u     /* eq. (62): central differences */
#define OGK_BLT_JAC_VARIATIONAL 1u /* variational equations integrated beside the state */

/* report flags */
#define OGK_BLT_FLAG_CONVERGED 0x01u  /* |e|_2 <= tol */
#define OGK_BLT_FLAG_IMPACT 0x02u     /* a trial or the guess hit a body (a trial: backed off); also a trial
                                         step with no finite thrust direction (A + B tau = 0) or no mass left */
#define OGK_BLT_FLAG_SINGULAR 0x04u   /* J J^T singular (no Newton step), a Jacobian that could not be formed,
                                         or (guess, evaluate, propagate) no finite right-hand side */
#define OGK_BLT_FLAG_ITER_LIMIT 0x08u /* max_iter reached */
#define OGK_BLT_FLAG_STALLED 0x10u    /* no trial step decreased |e| */
#define OGK_BLT_FLAG_SAFE 0x20u       /* no solution held: the command is the safe command (engine off) */
#define OGK_BLT_FLAG_GUESS_IMPACT 0x40u /* the guess itself hits a body: nothing to correct */

/* The dynamical model (docs/design/blt.md, sec. 1); every term can be switched off with a zero. */
typedef struct {
    ogk_real_t mu;                /* [-] M2 / (M1 + M2), in (0, 0.5] (must be set) */
    ogk_real_t body_radius[2];    /* [LU] impact radius of the primary, the secondary, > 0 (must be set) */
    ogk_real_t ref_radius[2];     /* [LU] normalising radius of c20 / c22 of each body, > 0 (default 1) */
    ogk_real_t c20[2];            /* [-] unnormalised degree-2 zonal coefficient of each body (default 0) */
    ogk_real_t c22[2];            /* [-] unnormalised degree-2 sectoral coefficient in synodic axes; c22[0] = 0 (default 0) */
    ogk_real_t srp_accel;         /* [LU/TU^2] SRP acceleration at mass fraction 1, >= 0 (default 0) */
    ogk_real_t sun_angle0;        /* [rad] the Sun's direction from the barycentre, synodic frame, t = 0 (default 0) */
    ogk_real_t sun_rate;          /* [rad/TU] its rate in the synodic frame (n_helio - 1) (default -1) */
    ogk_real_t sun_tidal;         /* [1/TU^2] mu_sun / d_sun^3, >= 0 (default 0) */
    ogk_real_t thrust_accel;      /* [LU/TU^2] F / m0 during a burn, > 0 (must be set) */
    ogk_real_t mass_flow;         /* [1/TU] F / (Isp g0 m0), >= 0 (default 0) */
    ogk_real_t step_max;          /* [TU] longest RK4 step, > 0 (default 2e-3) */
} ogk_blt_model_t;

typedef struct {
    ogk_blt_model_t model;    /* the dynamics the corrector predicts with */
    uint32_t n_segments;      /* [-] 1..OGK_BLT_MAX_SEGMENTS (default 1) */
    uint32_t segment_kind[OGK_BLT_MAX_SEGMENTS];   /* [-] OGK_BLT_SEG_* (default burn) */
    uint32_t segment_free[OGK_BLT_MAX_SEGMENTS];   /* [-] OGK_BLT_FREE_* bits (default all; a coast uses T only) */
    uint32_t n_free_nodes;    /* [-] 0..OGK_BLT_MAX_FREE_NODES (default 0) */
    uint32_t free_node_interface[OGK_BLT_MAX_FREE_NODES]; /* [-] interface 1..n_segments-1 of each, increasing */
    uint32_t meet_interface[OGK_BLT_MAX_ARCS];  /* [-] meeting interface of each arc, in [left, right anchor] (default 1: the
                                                   right anchor of the default single segment; set it with n_segments) */
    uint32_t start_free_mask; /* [-] bits 0-5: components of x0 the corrector may change (default 0) */
    uint32_t target_mask;     /* [-] bits 0-5: constrained components of xf; all six when the last arc meets before the end (default 0x3F) */
    uint32_t corrector;       /* [-] OGK_BLT_CORR_* (default NRPC) */
    uint32_t jacobian;        /* [-] OGK_BLT_JAC_* (default central) */
    ogk_real_t fd_step;           /* [-] central-difference step on each unknown, normalised units (default 1e-6; float build 2^-8) */
    ogk_real_t tol;               /* [-] convergence: |e|_2 <= tol, normalised units (default 1e-6, the paper's; float build 128 eps) */
    uint32_t max_iter;        /* [-] 1..OGK_BLT_MAX_ITER (default 40, the paper's sec. V) */
    ogk_real_t ls_factor;         /* [-] NRPC line search: step lengths 1, f, f^2, ... (default 0.1, the paper's 1/10) */
    uint32_t ls_trials;       /* [-] step lengths tried per iteration, 1..OGK_BLT_MAX_TRIALS (default 4) */
    uint32_t impact_halvings; /* [-] halvings of a step whose trajectory hits a body, 0..OGK_BLT_MAX_TRIALS (default 10) */
    ogk_real_t lm_lambda0;        /* [-] LM: initial damping, relative to the mean diagonal of J J^T (default 1e-3) */
    ogk_real_t lm_up;             /* [-] LM: damping factor after a rejected step, > 1 (default 10) */
    ogk_real_t lm_down;           /* [-] LM: damping factor after an accepted step, in (0, 1] (default 0.3) */
    uint32_t lm_trials;       /* [-] LM: damping trials per iteration, 1..OGK_BLT_MAX_TRIALS (default 12) */
    ogk_real_t burn_time_min;     /* [TU] a segment's duration is kept >= this, > 0 (default 1e-4) */
    ogk_real_t time_max;          /* [TU] and <= this; time_max / step_max <= OGK_BLT_MAX_SEGMENT_STEPS (default 30) */
    uint32_t normalise_ab;    /* [-] 1: each burn's [A; B] scaled to unit norm after every update (default 1) */
} ogk_blt_config_t;

/* One transfer: where it starts and ends, and the corrector's unknowns (a guess on input, the
 * solution on output). */
typedef struct {
    ogk_real_t t0;                /* [TU] time of the start (sets the Sun's direction), |t0| <= 1e6 */
    ogk_real_t mass0;             /* [-] mass fraction at the start, (0, 1] */
    ogk_real_t x0[OGK_BLT_NX];    /* [LU, VU] start state (components in start_free_mask: a guess) */
    ogk_real_t xf[OGK_BLT_NX];    /* [LU, VU] target state (components outside target_mask unused, but must be finite) */
    ogk_real_t seg[OGK_BLT_MAX_SEGMENTS][OGK_BLT_NP];  /* A [-], B [1/TU], T [TU] of each segment (coast: T only) */
    ogk_real_t node[OGK_BLT_MAX_FREE_NODES][OGK_BLT_NX]; /* [LU, VU] free-node states */
} ogk_blt_transfer_t;

typedef struct {
    uint32_t flags;           /* [-] OGK_BLT_FLAG_* */
    uint32_t iterations;      /* [-] corrector iterations (Jacobians) */
    uint32_t propagations;    /* [-] segment propagations (the cost unit) */
    uint32_t n_unknowns;      /* [-] length of the unknown vector */
    uint32_t n_errors;        /* [-] length of the error vector */
    ogk_real_t err_norm0;         /* [-] |e|_2 of the guess */
    ogk_real_t err_norm;          /* [-] |e|_2 of the returned transfer (HUGE_VAL when it has none: bad input, guess hits a body) */
    ogk_real_t err[OGK_BLT_MAX_ERRORS];  /* [LU, VU] the returned transfer's error vector (eqs. 65, 70) */
    ogk_real_t burn_time;         /* [TU] total burn time */
    ogk_real_t flight_time;       /* [TU] total duration */
    ogk_real_t mass_final;        /* [-] mass fraction at the end */
    ogk_real_t min_distance[2];   /* [LU] closest approach to the primary's, the secondary's centre */
} ogk_blt_report_t;

/* Thrust command at a time of the held solution. */
typedef struct {
    ogk_real_t t;                 /* [TU] time of the command */
    ogk_real_t u_hat[3];          /* [-] unit thrust direction, synodic frame (zeros when off) */
    uint32_t engine_on;       /* [-] 1 during a burn */
    uint32_t segment;         /* [-] segment index (n_segments after the end) */
    uint32_t flags;           /* [-] OGK_BLT_FLAG_SAFE when no converged solution is held */
} ogk_blt_command_t;

#define OGK_BLT_INIT_MARKER 0x424C5431u /* "BLT1" */

typedef struct {
    ogk_blt_config_t cfg;         /* accepted configuration */
    ogk_blt_transfer_t held;      /* last converged solution (what ogk_blt_command flies) */
    uint32_t held_valid;          /* [-] 1 when held is a converged solution */
    uint32_t n_unknowns;          /* [-] derived from cfg */
    uint32_t n_errors;            /* [-] derived from cfg */
    uint32_t col_start[OGK_BLT_NX];            /* [-] column of each start component (OGK_BLT_NO_COLUMN: fixed) */
    uint32_t col_seg[OGK_BLT_MAX_SEGMENTS][OGK_BLT_NP]; /* [-] column of each segment parameter */
    uint32_t col_node[OGK_BLT_MAX_FREE_NODES][OGK_BLT_NX]; /* [-] column of each free-node component */
    uint32_t anchor[OGK_BLT_MAX_ARCS + 1u];    /* [-] anchor interfaces: 0, the free nodes', n_segments */
    uint32_t seg_steps[OGK_BLT_MAX_SEGMENTS]; /* [-] RK4 steps of each segment, frozen per Jacobian */
    uint32_t steps_frozen;        /* [-] 1 while seg_steps is frozen */
    ogk_real_t u[OGK_BLT_MAX_UNKNOWNS];       /* [-] current unknowns */
    ogk_real_t u_trial[OGK_BLT_MAX_UNKNOWNS]; /* [-] trial unknowns */
    ogk_real_t du[OGK_BLT_MAX_UNKNOWNS];      /* [-] Newton / LM step */
    ogk_real_t e[OGK_BLT_MAX_ERRORS];         /* [-] current errors */
    ogk_real_t e_trial[OGK_BLT_MAX_ERRORS];   /* [-] trial errors */
    ogk_real_t e_plus[OGK_BLT_MAX_ERRORS];    /* [-] central-difference work */
    ogk_real_t jac[OGK_BLT_MAX_ERRORS * OGK_BLT_MAX_UNKNOWNS]; /* [-] J = de/du, row-major */
    ogk_real_t jaug[OGK_BLT_MAX_ERRORS * (OGK_BLT_MAX_UNKNOWNS + OGK_BLT_MAX_ERRORS)]; /* [-] [J, sqrt(lambda) I] */
    ogk_real_t step_aug[OGK_BLT_MAX_UNKNOWNS + OGK_BLT_MAX_ERRORS];  /* [-] minimum-norm solution of it */
    ogk_qr_t qr;                  /* [-] QR workspace of the minimum-norm step (eq. 64) */
    ogk_real_t var[OGK_BLT_NX * (1u + OGK_BLT_MAX_UNKNOWNS)];      /* [-] state + sensitivities (variational) */
    ogk_real_t var_k[5u * OGK_BLT_NX * (1u + OGK_BLT_MAX_UNKNOWNS)]; /* [-] RK4 stages of it */
    ogk_real_t s_fwd[OGK_BLT_NX * OGK_BLT_MAX_UNKNOWNS];           /* [-] forward sensitivities at a meeting point */
    uint32_t slot[OGK_BLT_MAX_UNKNOWNS];     /* [-] where each column of J lives in var while propagating
                                                (OGK_BLT_NO_COLUMN: still zero, not carried) */
    uint32_t slot_fwd[OGK_BLT_MAX_UNKNOWNS]; /* [-] the same for s_fwd */
    uint32_t n_live;                         /* [-] columns carried in var */
    ogk_real_t lm_lambda;             /* [-] current LM damping (absolute) */
    uint32_t init_marker;         /* [-] OGK_BLT_INIT_MARKER once initialised */
} ogk_blt_t;

ogk_status ogk_blt_config_default(ogk_blt_config_t *cfg);
ogk_status ogk_blt_init(ogk_blt_t *ctx, const ogk_blt_config_t *cfg);
ogk_status ogk_blt_reset(ogk_blt_t *ctx);

/* Corrects `guess` until |e|_2 <= tol (OGK_OK) with the configured corrector and Jacobian.
 * `solution` receives the best transfer found (the smallest |e| without impact; the guess when
 * none), `rep` the figures of that transfer. OGK_E_ITER_LIMIT when max_iter is reached,
 * OGK_E_NOT_CONVERGED when the corrector stalled, hit J J^T singular or the guess hits a body;
 * then the held solution is dropped and ogk_blt_command returns the safe command.
 * solution may alias guess. */
ogk_status ogk_blt_solve(ogk_blt_t *ctx, const ogk_blt_transfer_t *guess,
                         ogk_blt_transfer_t *solution, ogk_blt_report_t *rep);

/* The error vector of `tr` (eqs. 65, 70) and its figures, without correcting (rep->iterations 0).
 * OGK_E_NOT_CONVERGED when the trajectory hits a body (rep->flags has OGK_BLT_FLAG_IMPACT). */
ogk_status ogk_blt_evaluate(ogk_blt_t *ctx, const ogk_blt_transfer_t *tr, ogk_blt_report_t *rep);

/* J = de/du: a test entry point, ogk_blt_jacobian in ogk/internal/blt_test.h. */

/* Forward propagation of the whole chain from tr->x0 (free nodes ignored) to the end:
 * x_end [LU, VU], rep (errors not filled). OGK_E_NOT_CONVERGED on impact. */
ogk_status ogk_blt_propagate(ogk_blt_t *ctx, const ogk_blt_transfer_t *tr,
                             ogk_real_t x_end[OGK_BLT_NX], ogk_blt_report_t *rep);

/* The BLT direction (eq. 22) of the held converged solution at time t [TU] (absolute, the
 * solution's t0 based). Engine off (the safe command, OGK_E_SAFE_COMMAND) when none is held. */
ogk_status ogk_blt_command(const ogk_blt_t *ctx, ogk_real_t t, ogk_blt_command_t *cmd);

/* BLT's contract call for the one command of every law (ogk/types.h): the
 * held solution's command at time t [TU] (ogk_blt_command) in
 * OGK_FRAME_SYNODIC: during a burn u = u_hat of eq. (22), throttle 1, flags
 * ENGINE_ON; during a coast, and after the last segment, the engine is off
 * (throttle 0) and u is the direction to hold: the next burn's at its start
 * (A / |A|), (1, 0, 0) when no burn follows; law_flags = the command's
 * OGK_BLT_FLAG_* (SAFE). The statuses of ogk_blt_command; with any of them
 * cmd holds the safe command of ogk/thrust_cmd.h in OGK_FRAME_SYNODIC
 * (engine off, u = (1, 0, 0), flags SAFE, law_flags OGK_BLT_FLAG_SAFE; t_s =
 * 0 for a non-finite t). OGK_E_NULL when cmd is NULL. CPD needs it inertial:
 * ogk_thrust_cmd_synodic_to_inertial with the binary's phase at t. */
ogk_status ogk_blt_thrust_cmd(const ogk_blt_t *ctx, ogk_real_t t, ogk_thrust_cmd_t *cmd);

#ifdef __cplusplus
}
#endif

#endif /* OGK_BLT_H */
