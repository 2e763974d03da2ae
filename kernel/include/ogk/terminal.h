/* ogk/terminal.h -- terminal steering along the velocity to be gained, for
 * the last seconds of an injection burn into a circular orbit (beyond
 * Pontani & Celani 2021; docs/design/vtd-nog.md, "End-game").
 *
 * Near cut-off the VTD-NOG gains grow like 1/time-to-go^3 and, in long burns,
 * the variable time domain reaches tau = 1 while real time is left: the last
 * corrections swing the commanded direction by up to 120 deg in 2-3 s, more
 * than the attitude loop can follow, and the injection velocity misses by
 * tens of m/s. In its last window_s seconds (time to go as predicted by the
 * guidance law) this stage replaces the law's command by the direction of
 * the velocity to be gained, v_go = v_target - v, with v_target the circular
 * velocity of the target orbit in the local r-t-n frame (0, sqrt(mu/R_f), 0):
 * thrust along v_go shrinks v_go along its own direction, so the command
 * barely turns, and the energy cut-off (ogk/cutoff.h) ends the burn. With
 * shape_gain = 0 the radius and the out-of-plane position are not steered in
 * the window (their errors then grow by about v_r, v_n times half the window).
 *
 * Position shaping (shape_gain k for the radius, shape_gain_normal for the
 * plane-normal position, each in [0, 1], either > 0; both 0: pure v_go
 * steering): the radial and out-of-plane components of the command follow the linear-acceleration plan that nulls
 * the velocity and k times the position miss that pure v_go steering would
 * leave (E-guidance; k = 1 nulls both), re-planned at every step while the
 * time to go T exceeds shape_hold_s:
 *   a(T) = -(1 + 3 k) x'/T - 6 k x / T^2,  x = r - R_f or z = r sin(phi),
 * thrust acceleration a - g (g: the radial gravity-minus-centrifugal term,
 * the plane-normal gravity -mu z / r^3), tangential (v_c - v_t) / T. The
 * plane is the r-t-n frame's equator (phi = 0), as for the target velocity.
 * T is the time to the energy cut-off at the energy rate of the last control
 * period, (E_f - E) / (dE/dt), E = v^2 / 2 - mu / r, E_f = -mu / (2 R_f): the
 * cut-off ogk_cutoff makes (the law's prediction, which decides when the
 * window opens, is late or early by a sample interval or more); the law's
 * predicted time to go when no rate is known yet or it is not positive.
 * The command is the plan's direction shape_lead_s after its start (at most
 * at its end): the attitude loop's lag, which otherwise makes the vehicle
 * overshoot a planned turn it cannot reverse in time. The gains grow like
 * 1 / T^2 and the plan's turn at the end is more than an attitude loop
 * follows, so from T = shape_hold_s on the window steers along v_go (latched;
 * the position miss left is then about x' shape_hold_s / 2, with x' small).
 * Measured against flying the frozen plan open loop to its end: docs/design/vtd-nog.md.
 *
 * Turn limit (turn_accel_rad_s2 > 0; beyond the paper, docs/design/vtd-nog.md,
 * "Terminal steering within the vehicle's turn rate"). Thrust along v_go asks
 * for no turn (above); only the shaping does: the plan's direction leaves v_go
 * by the tilt whose tangent is k |Q| / |v_go|, Q = 3 x' + 6 x / T per axis (the
 * position part of the plan, -k Q / T at its start and +k Q / T at its end,
 * against the velocity part |v_go| / T), and must come back to v_go at the
 * hold. A vehicle whose thrust direction turns at an angular acceleration of
 * at most a (the TVC command limit times T l / I) turns through an angle th
 * from rest to rest in 2 sqrt(th / a) at best, so out and back within the
 * shaped part of the window, window_s - shape_hold_s = S, only for
 *   th <= a S^2 / 16.
 * Each plan's gains are scaled down, both axes alike, until its tilt is within
 * that bound (shape_tilt_max_rad; at most OGK_TERMINAL_TILT_MAX_RAD): a short
 * window on a slow-turning vehicle flies v_go, with the position miss that
 * leaves, instead of a plan it cannot follow. 0 (the default): no bound.
 *
 * Use: once per control period, after the guidance law's command:
 * ogk_terminal_step(ctx, nav, t_predicted, &law_cmd, &cmd); fly cmd. Once
 * engaged, the stage stays engaged for the burn (a later prediction that
 * moves the cut-off does not hand the last seconds back to the law; latches
 * by design, ogk_terminal_reset for a new burn). A rejected call (NaN, a
 * value outside the envelope) leaves the context unchanged and outputs the
 * law's command with OGK_THRUST_FLAG_SAFE set, or its last terminal command
 * when engaged.
 *
 * Static memory, no globals; many contexts side by side. */
#ifndef OGK_TERMINAL_H
#define OGK_TERMINAL_H

#include <stdbool.h>
#include <stdint.h>
#include "ogk/status.h"
#include "ogk/types.h"
#include "ogk/real.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Envelope of the navigation input (OGK_E_RANGE outside). */
#define OGK_TERMINAL_R_MAX_M OGK_R(1.0e10)   /* [m] radius, (0, 1e10] */
#define OGK_TERMINAL_V_MAX_MPS OGK_R(1.0e5)  /* [m/s] |v_r|, |v_t|, |v_n| */
#define OGK_TERMINAL_T_MAX_S OGK_R(1.0e7)    /* [s] times, [0, 1e7] */
/* Below this |v_go| the direction is held (it is not defined at v_go = 0). */
#define OGK_TERMINAL_VGO_MIN_MPS OGK_R(1.0e-3)
/* Smallest shape_hold_s: the plan's gains grow like 1 / hold^3. */
#define OGK_TERMINAL_HOLD_MIN_S OGK_R(1.0e-3)
/* [rad/s^2] Largest turn_accel_rad_s2 (a bound far above any vehicle's; keeps a S^2 / 16 finite). */
#define OGK_TERMINAL_TURN_ACCEL_MAX_RAD_S2 OGK_R(1.0e4)
/* [rad] Largest tilt bound: at or beyond it the turn limit does not bind (tan stays finite). */
#define OGK_TERMINAL_TILT_MAX_RAD OGK_R(1.5)

/* law_flags of the output command while engaged (the law's own flags are
 * replaced: the command is not the law's). */
#define OGK_TERMINAL_FLAG_ENGAGED 0x100u

typedef struct {
    ogk_real_t mu_m3_s2;        /* [m^3/s^2] gravitational parameter, > 0 */
    ogk_real_t target_radius_m; /* [m] radius of the circular target orbit, (0, R_MAX] */
    ogk_real_t window_s;        /* [s] engaged when the predicted time to go is at most this, [0, T_MAX] (0: never) */
    ogk_real_t shape_gain;      /* [-] k of the radius miss steered out in the window, [0, 1] (0: not steered) */
    ogk_real_t shape_gain_normal; /* [-] k of the plane-normal position miss, [0, 1] (0: not steered) */
    ogk_real_t shape_lead_s;    /* [s] the command is the plan's direction this long ahead (attitude-loop lag), [0, T_MAX] (0: none) */
    ogk_real_t shape_hold_s;    /* [s] time to go below which v_go steering takes over, [HOLD_MIN, window_s] when shape_gain > 0 */
    ogk_real_t turn_accel_rad_s2; /* [rad/s^2] the vehicle's angular acceleration at its TVC command limit in the window (turn limit), [0, TURN_ACCEL_MAX] (0: no limit) */
} ogk_terminal_config_t;

/* The last linear-acceleration plan of the shaped window (r-t-n). */
typedef struct {
    ogk_real_t t0_s;            /* [s] time at which it was made */
    ogk_real_t duration_s;      /* [s] time to go at t0_s, > shape_hold_s */
    ogk_real_t accel_r0_mps2;   /* [m/s^2] radial thrust acceleration at t0_s */
    ogk_real_t accel_r1_mps3;   /* [m/s^3] its rate */
    ogk_real_t accel_n0_mps2;   /* [m/s^2] plane-normal thrust acceleration at t0_s */
    ogk_real_t accel_n1_mps3;   /* [m/s^3] its rate */
    ogk_real_t accel_t_mps2;    /* [m/s^2] tangential thrust acceleration, held */
    ogk_real_t gain_scale;      /* [-] scale on both shape gains that kept the plan within the turn limit, [0, 1] */
    bool in_hold;           /* [-] past the hold: v_go steering (latched) */
} ogk_terminal_plan_t;

typedef struct {
    ogk_terminal_config_t cfg;
    ogk_real_t v_target_mps;    /* [m/s] circular speed of the target orbit, sqrt(mu / R_f) */
    ogk_real_t alpha_rad;       /* [rad] last terminal command, in-plane angle */
    ogk_real_t beta_rad;        /* [rad] last terminal command, out-of-plane angle */
    bool engaged;           /* [-] in the terminal window (latched) */
    ogk_terminal_plan_t plan; /* [-] shaped window only */
    ogk_real_t shape_tilt_max_rad; /* [rad] largest tilt of a plan from v_go (turn limit), set by init */
    ogk_real_t shape_tilt_max_tan; /* [-] its tangent */
    bool tilt_limited;      /* [-] the turn limit binds (turn_accel_rad_s2 > 0, bound below TILT_MAX, shaped) */
    ogk_real_t last_t_s;        /* [s] time of the last accepted step */
    ogk_real_t last_energy_j_kg; /* [J/kg] specific orbital energy at last_t_s */
    bool has_last;          /* [-] last_t_s, last_energy_j_kg are set */
#if OGK_REAL_SINGLE
    ogk_real_t r_lo_m;      /* [m] float build: low part of the radius of the step in progress (ogk_terminal_step_split), 0 otherwise */
#endif
    uint32_t init_marker;   /* [-] set by ogk_terminal_init */
} ogk_terminal_t;

/* Defaults: mu of the Earth, target 42164 km, window 3 s, no shaping
 * (shape_gain = shape_gain_normal = 0, shape_hold_s 1 s), no turn limit
 * (turn_accel_rad_s2 = 0). */
/*@ requires cfg_valid: cfg == \null || \valid(cfg); */
ogk_status ogk_terminal_config_default(ogk_terminal_config_t *cfg);

/* OGK_E_CONFIG for a non-finite or out-of-range field (context untouched). */
/*@ requires ctx_valid: ctx == \null || \valid(ctx);
    requires cfg_valid: cfg == \null || \valid_read(cfg);
*/
ogk_status ogk_terminal_init(ogk_terminal_t *ctx, const ogk_terminal_config_t *cfg);

/* Back to the state after init (a new burn). */
/*@ requires ctx_valid: ctx == \null || \valid(ctx); */
ogk_status ogk_terminal_reset(ogk_terminal_t *ctx);

/* One control period: nav at nav->t_s (t, r, phi, v_r, v_t, v_n read; xi
 * not), the guidance's predicted cut-off t_predicted_s and its command
 * law_cmd, an r-t-n command (OGK_FRAME_RTN; only its t_s, alpha, beta --
 * finite -- and flags are read, so a command set field by field works too).
 * *out is law_cmd as it is while not engaged, else the terminal direction
 * (v_go, or the shaped plan's) as a complete r-t-n command (ogk/types.h: the
 * angles, their unit vector, throttle 1 with the engine on; same t_s and
 * OGK_THRUST_FLAG_ENGINE_ON bit as law_cmd, law_flags ENGAGED). OGK_E_NONFINITE
 * (any of those values) / OGK_E_RANGE: context unchanged; *out as described in
 * the header comment. */
/*@ requires ctx_valid: ctx == \null || \valid(ctx);
    requires nav_valid: nav == \null || \valid_read(nav);
    requires law_cmd_valid: law_cmd == \null || \valid_read(law_cmd);
    requires out_valid: out == \null || \valid(out);
*/
ogk_status ogk_terminal_step(ogk_terminal_t *ctx, const ogk_nav_state_t *nav, ogk_real_t t_predicted_s,
                             const ogk_thrust_cmd_t *law_cmd, ogk_thrust_cmd_t *out);

#if OGK_REAL_SINGLE
/* Float build only: ogk_terminal_step with the radius in two parts, r = nav->r_m
 * + r_lo_m, r_lo_m the part a float r_m cannot hold (a navigation source of
 * higher precision: r_lo_m = r - (float)r; |r_lo_m| <= OGK_REAL_EPSILON |r_m|).
 * At the target radius (42164 km) a float radius is 4 m apart from the next
 * one, and the shaped plan's radius miss x = r - R_f, whose gain grows like
 * 6 k / T^2, turns that step into direction noise: (r_m - R_f) + r_lo_m (exact
 * difference, Sterbenz) keeps x to its own resolution (docs/design/vtd-nog.md,
 * "Single precision"). Everything else reads r_m. OGK_E_NONFINITE for a
 * non-finite r_lo_m, OGK_E_RANGE for a larger one, as ogk_terminal_step's. */
/*@ requires ctx_valid: ctx == \null || \valid(ctx);
    requires nav_valid: nav == \null || \valid_read(nav);
    requires law_cmd_valid: law_cmd == \null || \valid_read(law_cmd);
    requires out_valid: out == \null || \valid(out);
*/
ogk_status ogk_terminal_step_split(ogk_terminal_t *ctx, const ogk_nav_state_t *nav, ogk_real_t r_lo_m,
                                   ogk_real_t t_predicted_s, const ogk_thrust_cmd_t *law_cmd,
                                   ogk_thrust_cmd_t *out);
#endif

#ifdef __cplusplus
}
#endif

#endif /* OGK_TERMINAL_H */
