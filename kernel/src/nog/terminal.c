/* terminal.c -- terminal steering along the velocity to be gained (ogk/terminal.h). */
#include "ogk/terminal.h"

#include <math.h>
#include <stddef.h>

#include "../ogk_checks.h"
#include "../thrust_cmd_internal.h"

#define OGK_TERMINAL_INIT_MARKER 0x54524d30u /* "TRM0" */

ogk_status ogk_terminal_config_default(ogk_terminal_config_t *cfg)
{
    ogk_status st = OGK_OK;

    if (cfg == NULL) {
        st = OGK_E_NULL;
    } else {
        cfg->mu_m3_s2 = OGK_R(3.986004e14);
        cfg->target_radius_m = OGK_R(42164.0e3);
        cfg->window_s = OGK_R(3.0);
        cfg->shape_gain = OGK_R(0.0);
        cfg->shape_gain_normal = OGK_R(0.0);
        cfg->shape_hold_s = OGK_R(1.0);
        cfg->shape_lead_s = OGK_R(0.0);
        cfg->turn_accel_rad_s2 = OGK_R(0.0);
    }
    return st;
}

static bool terminal_shaped(const ogk_terminal_config_t *cfg)
{
    return (cfg->shape_gain > OGK_R(0.0)) || (cfg->shape_gain_normal > OGK_R(0.0));
}

/* Shaping off, or gains in [0, 1] with a hold in [HOLD_MIN, window]. */
static bool terminal_shape_valid(const ogk_terminal_config_t *cfg)
{
    return (cfg->shape_gain >= OGK_R(0.0)) && (cfg->shape_gain <= OGK_R(1.0)) && (cfg->shape_gain_normal >= OGK_R(0.0)) &&
           (cfg->shape_gain_normal <= OGK_R(1.0)) &&
           (!terminal_shaped(cfg) ||
            ((cfg->shape_hold_s >= OGK_TERMINAL_HOLD_MIN_S) && (cfg->shape_hold_s <= cfg->window_s)));
}

static bool terminal_config_valid(const ogk_terminal_config_t *cfg)
{
    const ogk_real_t v[8] = {cfg->mu_m3_s2, cfg->target_radius_m, cfg->window_s, cfg->shape_gain,
                         cfg->shape_gain_normal, cfg->shape_hold_s, cfg->shape_lead_s, cfg->turn_accel_rad_s2};

    return ogk_i_all_finite(v, 8u) && (cfg->turn_accel_rad_s2 >= OGK_R(0.0)) &&
           (cfg->turn_accel_rad_s2 <= OGK_TERMINAL_TURN_ACCEL_MAX_RAD_S2) && (cfg->shape_lead_s >= OGK_R(0.0)) && (cfg->shape_lead_s <= OGK_TERMINAL_T_MAX_S) && (cfg->mu_m3_s2 > OGK_R(0.0)) && (cfg->target_radius_m > OGK_R(0.0)) &&
           (cfg->target_radius_m <= OGK_TERMINAL_R_MAX_M) && (cfg->window_s >= OGK_R(0.0)) &&
           (cfg->window_s <= OGK_TERMINAL_T_MAX_S) &&
           isfinite(OGK_SQRT(cfg->mu_m3_s2 / cfg->target_radius_m)) && terminal_shape_valid(cfg);
}

static void terminal_clear(ogk_terminal_t *ctx)
{
    ctx->alpha_rad = OGK_R(0.0);
    ctx->beta_rad = OGK_R(0.0);
    ctx->engaged = false;
    ctx->plan.t0_s = OGK_R(0.0);
    ctx->plan.duration_s = OGK_R(0.0);
    ctx->plan.accel_r0_mps2 = OGK_R(0.0);
    ctx->plan.accel_r1_mps3 = OGK_R(0.0);
    ctx->plan.accel_n0_mps2 = OGK_R(0.0);
    ctx->plan.accel_n1_mps3 = OGK_R(0.0);
    ctx->plan.accel_t_mps2 = OGK_R(0.0);
    ctx->plan.gain_scale = OGK_R(1.0);
    ctx->plan.in_hold = false;
    ctx->last_t_s = OGK_R(0.0);
    ctx->last_energy_j_kg = OGK_R(0.0);
    ctx->has_last = false;
#if OGK_REAL_SINGLE
    ctx->r_lo_m = OGK_R(0.0);
#endif
}

/* The turn limit (terminal.h, "Turn limit"): the largest tilt th from v_go
 * that a vehicle turning at an angular acceleration of at most a can leave
 * and regain within the shaped part of the window S = window - hold, two
 * rest-to-rest turns of 2 sqrt(th / a) each: th = a S^2 / 16. It binds only
 * with shaping, a > 0 and th below OGK_TERMINAL_TILT_MAX_RAD. S >= 0: the
 * hold is at most the window when shaped (terminal_shape_valid). */
static void terminal_turn_limit(ogk_terminal_t *ctx)
{
    const ogk_real_t shaped_s = ctx->cfg.window_s - ctx->cfg.shape_hold_s;
    const ogk_real_t tilt = OGK_R(0.0625) * ctx->cfg.turn_accel_rad_s2 * shaped_s * shaped_s;

    ctx->tilt_limited = terminal_shaped(&ctx->cfg) && (ctx->cfg.turn_accel_rad_s2 > OGK_R(0.0)) &&
                        (tilt < OGK_TERMINAL_TILT_MAX_RAD);
    ctx->shape_tilt_max_rad = ctx->tilt_limited ? tilt : OGK_TERMINAL_TILT_MAX_RAD;
    ctx->shape_tilt_max_tan = OGK_TAN(ctx->shape_tilt_max_rad);
}

ogk_status ogk_terminal_init(ogk_terminal_t *ctx, const ogk_terminal_config_t *cfg)
{
    ogk_status st = OGK_OK;

    if ((ctx == NULL) || (cfg == NULL)) {
        st = OGK_E_NULL;
    } else if (!terminal_config_valid(cfg)) {
        st = OGK_E_CONFIG;
    } else {
        ctx->cfg = *cfg;
        ctx->v_target_mps = OGK_SQRT(cfg->mu_m3_s2 / cfg->target_radius_m); /* eq. (20): v_tf */
        terminal_turn_limit(ctx);
        terminal_clear(ctx);
        ctx->init_marker = OGK_TERMINAL_INIT_MARKER;
    }
    return st;
}

ogk_status ogk_terminal_reset(ogk_terminal_t *ctx)
{
    ogk_status st = OGK_OK;

    if (ctx == NULL) {
        st = OGK_E_NULL;
    } else if (ctx->init_marker != OGK_TERMINAL_INIT_MARKER) {
        st = OGK_E_NOT_INIT;
    } else {
        terminal_clear(ctx);
    }
    return st;
}

static bool terminal_nav_in_envelope(const ogk_nav_state_t *nav, ogk_real_t t_predicted_s)
{
    return (nav->r_m > OGK_R(0.0)) && (nav->r_m <= OGK_TERMINAL_R_MAX_M) &&
           (OGK_FABS(nav->v_r_mps) <= OGK_TERMINAL_V_MAX_MPS) && (OGK_FABS(nav->v_t_mps) <= OGK_TERMINAL_V_MAX_MPS) &&
           (OGK_FABS(nav->v_n_mps) <= OGK_TERMINAL_V_MAX_MPS) && (nav->t_s >= OGK_R(0.0)) &&
           (nav->t_s <= OGK_TERMINAL_T_MAX_S) && (t_predicted_s >= OGK_R(0.0)) &&
           (t_predicted_s <= OGK_TERMINAL_T_MAX_S);
}

/* The command in force: the terminal one when engaged (a complete r-t-n
 * command, full thrust while the law's engine is on), else the law's as it
 * is. Only t_s, the angles and the flags of law_cmd are read. */
static void terminal_output(const ogk_terminal_t *ctx, const ogk_thrust_cmd_t *law_cmd, ogk_thrust_cmd_t *out)
{
    if (ctx->engaged) {
        ogk_i_thrust_cmd_angles(out, law_cmd->t_s, ctx->alpha_rad, ctx->beta_rad, OGK_R(1.0),
                                law_cmd->flags & OGK_THRUST_FLAG_ENGINE_ON, OGK_TERMINAL_FLAG_ENGAGED);
    } else {
        *out = *law_cmd;
    }
}

/* The v_go direction in r-t-n, thrust along (cos b sin a, cos b cos a, sin b)
 * (ogk/types.h); held while |v_go| is below OGK_TERMINAL_VGO_MIN_MPS. */
static void steer_along_vgo(ogk_terminal_t *ctx, const ogk_nav_state_t *nav)
{
    const ogk_real_t vgo_r = -nav->v_r_mps;
    const ogk_real_t vgo_t = ctx->v_target_mps - nav->v_t_mps;
    const ogk_real_t vgo_n = -nav->v_n_mps;
    const ogk_real_t vgo_in_plane = OGK_HYPOT(vgo_r, vgo_t);

    if (OGK_HYPOT(vgo_in_plane, vgo_n) >= OGK_TERMINAL_VGO_MIN_MPS) {
        ctx->alpha_rad = OGK_ATAN2(vgo_r, vgo_t);
        ctx->beta_rad = OGK_ATAN2(vgo_n, vgo_in_plane);
    }
}

/* Initial value and rate of the acceleration, linear in time over duration_s,
 * that takes x' to 0 and x + x' duration_s / 2 (the miss of a decay of x' at
 * constant rate) to (1 - k) times itself: terminal.h, "Position shaping". */
static void plan_axis(ogk_real_t x, ogk_real_t x_dot, ogk_real_t duration_s, ogk_real_t k, ogk_real_t *accel0, ogk_real_t *accel1)
{
    const ogk_real_t t2 = duration_s * duration_s;

    *accel0 = (-((OGK_R(1.0) + (OGK_R(3.0) * k)) * x_dot) / duration_s) - ((OGK_R(6.0) * k * x) / t2);
    *accel1 = ((OGK_R(12.0) * k * x) / (t2 * duration_s)) + ((OGK_R(6.0) * k * x_dot) / t2);
}

/* The position misses a shaped plan steers out. */
typedef struct {
    ogk_real_t x;     /* [m] radius miss, r - R_f */
    ogk_real_t z;     /* [m] plane-normal position, r sin(phi) */
    ogk_real_t z_dot; /* [m/s] its rate */
} plan_miss_t;

/* The scale on both shape gains that keeps the plan's tilt from v_go within
 * the turn limit (terminal.h, "Turn limit"): the position part of the plan
 * is k Q / T per axis, Q = 3 x' + 6 x / T, at most in size at the plan's
 * start and end, against |v_go| / T along v_go, so its tilt is
 * atan(|(k_r Q_r, k_n Q_n)| / |v_go|). 1 when the limit does not bind;
 * 0 (v_go steering) when |v_go| is 0 and the plan has a position part. */
static ogk_real_t plan_gain_scale(const ogk_terminal_t *ctx, const ogk_nav_state_t *nav, const plan_miss_t *miss,
                              ogk_real_t duration_s)
{
    const ogk_real_t q_r = ctx->cfg.shape_gain * ((OGK_R(3.0) * nav->v_r_mps) + ((OGK_R(6.0) * miss->x) / duration_s));
    const ogk_real_t q_n = ctx->cfg.shape_gain_normal * ((OGK_R(3.0) * miss->z_dot) + ((OGK_R(6.0) * miss->z) / duration_s));
    const ogk_real_t q = OGK_HYPOT(q_r, q_n);
    const ogk_real_t vgo = OGK_HYPOT(OGK_HYPOT(nav->v_r_mps, ctx->v_target_mps - nav->v_t_mps), nav->v_n_mps);
    const ogk_real_t allowed = ctx->shape_tilt_max_tan * vgo;
    ogk_real_t scale = OGK_R(1.0);

    if (ctx->tilt_limited && (q > allowed)) {
        scale = allowed / q; /* q > allowed >= 0: in [0, 1) */
    }
    return scale;
}

/* The shaped plan from the state at nav->t_s with duration_s to go; false
 * (plan unchanged) if a term overflows (a radius near 0 in the envelope). */
static bool plan_from(ogk_terminal_t *ctx, const ogk_nav_state_t *nav, ogk_real_t duration_s)
{
    const ogk_real_t r = nav->r_m;
#if OGK_REAL_SINGLE
    /* r - R_f exact (both near R_f), then the radius's low part (terminal.h) */
    const plan_miss_t miss = {(r - ctx->cfg.target_radius_m) + ctx->r_lo_m, r * OGK_SIN(nav->phi_rad),
#else
    const plan_miss_t miss = {r - ctx->cfg.target_radius_m, r * OGK_SIN(nav->phi_rad),
#endif
                              (nav->v_r_mps * OGK_SIN(nav->phi_rad)) + (nav->v_n_mps * OGK_COS(nav->phi_rad))};
    const ogk_real_t z = miss.z;
    const ogk_real_t z_dot = miss.z_dot;
    const ogk_real_t mu_r2 = ctx->cfg.mu_m3_s2 / (r * r);
    const ogk_real_t g_r = (((nav->v_t_mps * nav->v_t_mps) + (nav->v_n_mps * nav->v_n_mps)) / r) - mu_r2;
    const ogk_real_t g_n = -(mu_r2 * z) / r;
    const ogk_real_t scale = plan_gain_scale(ctx, nav, &miss, duration_s);
    ogk_real_t a_r0 = OGK_R(0.0);
    ogk_real_t a_r1 = OGK_R(0.0);
    ogk_real_t a_n0 = OGK_R(0.0);
    ogk_real_t a_n1 = OGK_R(0.0);
    bool finite;

    plan_axis(miss.x, nav->v_r_mps, duration_s, scale * ctx->cfg.shape_gain, &a_r0, &a_r1);
    plan_axis(z, z_dot, duration_s, scale * ctx->cfg.shape_gain_normal, &a_n0, &a_n1);
    {
        const ogk_real_t v[6] = {a_r0 - g_r, a_r1, a_n0 - g_n, a_n1, (ctx->v_target_mps - nav->v_t_mps) / duration_s,
                             scale};
        finite = ogk_i_all_finite(v, 6u);
        if (finite) {
            ctx->plan.t0_s = nav->t_s;
            ctx->plan.duration_s = duration_s;
            ctx->plan.accel_r0_mps2 = v[0];
            ctx->plan.accel_r1_mps3 = v[1];
            ctx->plan.accel_n0_mps2 = v[2];
            ctx->plan.accel_n1_mps3 = v[3];
            ctx->plan.accel_t_mps2 = v[4];
            ctx->plan.gain_scale = scale;
        }
    }
    return finite;
}

/* The plan's thrust direction shape_lead_s after its start (at most at its
 * end); v_go's (steer_along_vgo has just set it) if the plan asks for no
 * acceleration. */
static void steer_along_plan(ogk_terminal_t *ctx)
{
    const ogk_real_t lead = OGK_FMIN(ctx->cfg.shape_lead_s, ctx->plan.duration_s);
    const ogk_real_t a_r = ctx->plan.accel_r0_mps2 + (ctx->plan.accel_r1_mps3 * lead);
    const ogk_real_t a_n = ctx->plan.accel_n0_mps2 + (ctx->plan.accel_n1_mps3 * lead);
    const ogk_real_t a_t = ctx->plan.accel_t_mps2;
    const ogk_real_t a_in_plane = OGK_HYPOT(a_r, a_t);

    if (OGK_HYPOT(a_in_plane, a_n) > OGK_R(0.0)) {
        ctx->alpha_rad = OGK_ATAN2(a_r, a_t);
        ctx->beta_rad = OGK_ATAN2(a_n, a_in_plane);
    }
}

static ogk_real_t specific_energy(const ogk_terminal_t *ctx, const ogk_nav_state_t *nav)
{
    const ogk_real_t v2 = (nav->v_r_mps * nav->v_r_mps) + (nav->v_t_mps * nav->v_t_mps) + (nav->v_n_mps * nav->v_n_mps);

    return (OGK_R(0.5) * v2) - (ctx->cfg.mu_m3_s2 / nav->r_m);
}

/* Time to the energy cut-off at the last period's energy rate (terminal.h),
 * else the law's predicted time to go. */
static ogk_real_t time_to_cutoff(const ogk_terminal_t *ctx, const ogk_nav_state_t *nav, ogk_real_t t_predicted_s)
{
    const ogk_real_t energy = specific_energy(ctx, nav);
    ogk_real_t time_to_go = t_predicted_s - nav->t_s;

    if (ctx->has_last && (nav->t_s > ctx->last_t_s)) {
        const ogk_real_t energy_rate = (energy - ctx->last_energy_j_kg) / (nav->t_s - ctx->last_t_s);
        if (energy_rate > OGK_R(0.0)) {
            const ogk_real_t energy_target = -ctx->cfg.mu_m3_s2 / (OGK_R(2.0) * ctx->cfg.target_radius_m);
            const ogk_real_t t_energy = (energy_target - energy) / energy_rate;
            time_to_go = isfinite(t_energy) ? t_energy : time_to_go;
        }
    }
    return time_to_go;
}

/* Shaped window: re-plan at every step while the time to go exceeds the
 * hold, then v_go steering for the rest of the window (latched). A plan that
 * overflows is not made: v_go steering for this step. */
static void steer_shaped(ogk_terminal_t *ctx, const ogk_nav_state_t *nav, ogk_real_t t_predicted_s)
{
    const ogk_real_t time_to_go = time_to_cutoff(ctx, nav, t_predicted_s);

    ctx->plan.in_hold = ctx->plan.in_hold || (time_to_go <= ctx->cfg.shape_hold_s);
    steer_along_vgo(ctx, nav);
    if ((!ctx->plan.in_hold) && plan_from(ctx, nav, time_to_go)) {
        steer_along_plan(ctx);
    }
}

#if OGK_REAL_SINGLE
/* The float build's step reads the radius's low part from ctx->r_lo_m, set by
 * its two entry points below (0 by ogk_terminal_step). */
static ogk_status terminal_step(ogk_terminal_t *ctx, const ogk_nav_state_t *nav, ogk_real_t t_predicted_s,
                                const ogk_thrust_cmd_t *law_cmd, ogk_thrust_cmd_t *out)
#else
ogk_status ogk_terminal_step(ogk_terminal_t *ctx, const ogk_nav_state_t *nav, ogk_real_t t_predicted_s,
                             const ogk_thrust_cmd_t *law_cmd, ogk_thrust_cmd_t *out)
#endif
{
    ogk_status st = OGK_OK;

    if ((ctx == NULL) || (nav == NULL) || (law_cmd == NULL) || (out == NULL)) {
        st = OGK_E_NULL;
    } else if (ctx->init_marker != OGK_TERMINAL_INIT_MARKER) {
        st = OGK_E_NOT_INIT;
    } else {
        const ogk_real_t v[9] = {nav->t_s, nav->r_m, nav->phi_rad, nav->v_r_mps, nav->v_t_mps, nav->v_n_mps,
                             t_predicted_s, law_cmd->alpha_rad, law_cmd->beta_rad};
#if OGK_REAL_SINGLE
        if ((!ogk_i_all_finite(v, 9u)) || (!isfinite(ctx->r_lo_m))) {
            st = OGK_E_NONFINITE;
        } else if ((!terminal_nav_in_envelope(nav, t_predicted_s)) ||
                   (OGK_FABS(ctx->r_lo_m) > (OGK_REAL_EPSILON * nav->r_m))) {
            st = OGK_E_RANGE;
        } else {
#else
        if (!ogk_i_all_finite(v, 9u)) {
            st = OGK_E_NONFINITE;
        } else if (!terminal_nav_in_envelope(nav, t_predicted_s)) {
            st = OGK_E_RANGE;
        } else {
#endif
            if ((!ctx->engaged) && ((t_predicted_s - nav->t_s) <= ctx->cfg.window_s) && (ctx->cfg.window_s > OGK_R(0.0))) {
                ctx->engaged = true;
                ctx->alpha_rad = law_cmd->alpha_rad; /* held if v_go is already ~0 */
                ctx->beta_rad = law_cmd->beta_rad;
            }
            if (!ctx->engaged) {
                /* the law's command is flown */
            } else if (terminal_shaped(&ctx->cfg)) {
                steer_shaped(ctx, nav, t_predicted_s);
            } else {
                steer_along_vgo(ctx, nav);
            }
            ctx->last_t_s = nav->t_s;
            ctx->last_energy_j_kg = specific_energy(ctx, nav);
            ctx->has_last = isfinite(ctx->last_energy_j_kg);
        }
        if ((st != OGK_OK) && ((!isfinite(law_cmd->alpha_rad)) || (!isfinite(law_cmd->beta_rad)))) {
            /* No usable law command either: the last terminal one (zeros before). */
            ogk_i_thrust_cmd_angles(out, law_cmd->t_s, ctx->alpha_rad, ctx->beta_rad, OGK_R(1.0),
                                    (law_cmd->flags & OGK_THRUST_FLAG_ENGINE_ON) | OGK_THRUST_FLAG_SAFE,
                                    ctx->engaged ? OGK_TERMINAL_FLAG_ENGAGED : 0u);
        } else {
            terminal_output(ctx, law_cmd, out);
            if (st != OGK_OK) {
                out->flags |= OGK_THRUST_FLAG_SAFE;
            }
        }
    }
    return st;
}

#if OGK_REAL_SINGLE
ogk_status ogk_terminal_step(ogk_terminal_t *ctx, const ogk_nav_state_t *nav, ogk_real_t t_predicted_s,
                             const ogk_thrust_cmd_t *law_cmd, ogk_thrust_cmd_t *out)
{
    return ogk_terminal_step_split(ctx, nav, OGK_R(0.0), t_predicted_s, law_cmd, out);
}

ogk_status ogk_terminal_step_split(ogk_terminal_t *ctx, const ogk_nav_state_t *nav, ogk_real_t r_lo_m,
                                   ogk_real_t t_predicted_s, const ogk_thrust_cmd_t *law_cmd,
                                   ogk_thrust_cmd_t *out)
{
    ogk_status st;

    if ((ctx != NULL) && (ctx->init_marker == OGK_TERMINAL_INIT_MARKER)) {
        ctx->r_lo_m = r_lo_m;
        st = terminal_step(ctx, nav, t_predicted_s, law_cmd, out);
        ctx->r_lo_m = OGK_R(0.0);
    } else {
        st = terminal_step(ctx, nav, t_predicted_s, law_cmd, out);
    }
    return st;
}
#endif
