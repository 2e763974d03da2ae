/* terminal.c -- terminal steering along the velocity to be gained (ogk/terminal.h). */
#include "ogk/terminal.h"

#include <math.h>
#include <stddef.h>

#include "ogk_checks.h"

#define OGK_TERMINAL_INIT_MARKER 0x54524d30u /* "TRM0" */

ogk_status ogk_terminal_config_default(ogk_terminal_config_t *cfg)
{
    ogk_status st = OGK_OK;

    if (cfg == NULL) {
        st = OGK_E_NULL;
    } else {
        cfg->mu_m3_s2 = 3.986004e14;
        cfg->target_radius_m = 42164.0e3;
        cfg->window_s = 3.0;
    }
    return st;
}

static bool terminal_config_valid(const ogk_terminal_config_t *cfg)
{
    const double v[3] = {cfg->mu_m3_s2, cfg->target_radius_m, cfg->window_s};

    return ogk_i_all_finite(v, 3u) && (cfg->mu_m3_s2 > 0.0) && (cfg->target_radius_m > 0.0) &&
           (cfg->target_radius_m <= OGK_TERMINAL_R_MAX_M) && (cfg->window_s >= 0.0) &&
           (cfg->window_s <= OGK_TERMINAL_T_MAX_S) &&
           isfinite(sqrt(cfg->mu_m3_s2 / cfg->target_radius_m));
}

static void terminal_clear(ogk_terminal_t *ctx)
{
    ctx->alpha_rad = 0.0;
    ctx->beta_rad = 0.0;
    ctx->engaged = false;
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
        ctx->v_target_mps = sqrt(cfg->mu_m3_s2 / cfg->target_radius_m); /* eq. (20): v_tf */
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

static bool terminal_nav_in_envelope(const ogk_nav_state_t *nav, double t_predicted_s)
{
    return (nav->r_m > 0.0) && (nav->r_m <= OGK_TERMINAL_R_MAX_M) &&
           (fabs(nav->v_r_mps) <= OGK_TERMINAL_V_MAX_MPS) && (fabs(nav->v_t_mps) <= OGK_TERMINAL_V_MAX_MPS) &&
           (fabs(nav->v_n_mps) <= OGK_TERMINAL_V_MAX_MPS) && (nav->t_s >= 0.0) &&
           (nav->t_s <= OGK_TERMINAL_T_MAX_S) && (t_predicted_s >= 0.0) &&
           (t_predicted_s <= OGK_TERMINAL_T_MAX_S);
}

/* The command in force: the terminal one when engaged, else the law's. */
static void terminal_output(const ogk_terminal_t *ctx, const ogk_thrust_cmd_t *law_cmd, ogk_thrust_cmd_t *out)
{
    *out = *law_cmd;
    if (ctx->engaged) {
        out->alpha_rad = ctx->alpha_rad;
        out->beta_rad = ctx->beta_rad;
        out->flags = law_cmd->flags & OGK_THRUST_FLAG_ENGINE_ON;
        out->law_flags = OGK_TERMINAL_FLAG_ENGAGED;
    }
}

/* The v_go direction in r-t-n, thrust along (cos b sin a, cos b cos a, sin b)
 * (ogk/types.h); held while |v_go| is below OGK_TERMINAL_VGO_MIN_MPS. */
static void steer_along_vgo(ogk_terminal_t *ctx, const ogk_nav_state_t *nav)
{
    const double vgo_r = -nav->v_r_mps;
    const double vgo_t = ctx->v_target_mps - nav->v_t_mps;
    const double vgo_n = -nav->v_n_mps;
    const double vgo_in_plane = hypot(vgo_r, vgo_t);

    if (hypot(vgo_in_plane, vgo_n) >= OGK_TERMINAL_VGO_MIN_MPS) {
        ctx->alpha_rad = atan2(vgo_r, vgo_t);
        ctx->beta_rad = atan2(vgo_n, vgo_in_plane);
    }
}

ogk_status ogk_terminal_step(ogk_terminal_t *ctx, const ogk_nav_state_t *nav, double t_predicted_s,
                             const ogk_thrust_cmd_t *law_cmd, ogk_thrust_cmd_t *out)
{
    ogk_status st = OGK_OK;

    if ((ctx == NULL) || (nav == NULL) || (law_cmd == NULL) || (out == NULL)) {
        st = OGK_E_NULL;
    } else if (ctx->init_marker != OGK_TERMINAL_INIT_MARKER) {
        st = OGK_E_NOT_INIT;
    } else {
        const double v[8] = {nav->t_s, nav->r_m, nav->v_r_mps, nav->v_t_mps, nav->v_n_mps, t_predicted_s,
                             law_cmd->alpha_rad, law_cmd->beta_rad};
        if (!ogk_i_all_finite(v, 8u)) {
            st = OGK_E_NONFINITE;
        } else if (!terminal_nav_in_envelope(nav, t_predicted_s)) {
            st = OGK_E_RANGE;
        } else {
            if ((!ctx->engaged) && ((t_predicted_s - nav->t_s) <= ctx->cfg.window_s) &&
                (ctx->cfg.window_s > 0.0)) {
                ctx->engaged = true;
                ctx->alpha_rad = law_cmd->alpha_rad; /* held if v_go is already ~0 */
                ctx->beta_rad = law_cmd->beta_rad;
            }
            if (ctx->engaged) {
                steer_along_vgo(ctx, nav);
            }
        }
        if ((st != OGK_OK) && ((!isfinite(law_cmd->alpha_rad)) || (!isfinite(law_cmd->beta_rad)))) {
            /* No usable law command either: the last terminal one (zeros before). */
            out->t_s = law_cmd->t_s;
            out->alpha_rad = ctx->alpha_rad;
            out->beta_rad = ctx->beta_rad;
            out->flags = (law_cmd->flags & OGK_THRUST_FLAG_ENGINE_ON) | OGK_THRUST_FLAG_SAFE;
            out->law_flags = ctx->engaged ? OGK_TERMINAL_FLAG_ENGAGED : 0u;
        } else {
            terminal_output(ctx, law_cmd, out);
            if (st != OGK_OK) {
                out->flags |= OGK_THRUST_FLAG_SAFE;
            }
        }
    }
    return st;
}
