/* cutoff.c -- engine cut-off on the orbital energy (ogk/cutoff.h). */
#include "ogk/cutoff.h"

#include <math.h>
#include <stddef.h>

#include "../ogk_checks.h"

#define OGK_CUTOFF_INIT_MARKER 0x43555430u /* "CUT0" */

/* Shortest time between two accepted calls over which the energy rate is
 * measured [s]: closer calls (a malformed time tag; the control period is
 * milliseconds) give no rate, instead of a difference quotient over a
 * subnormal step that overflows. */
#define CUTOFF_DT_MIN_S OGK_R(1.0e-9)

/* Smallest energy rate extrapolated to the crossing [W/kg]: below it the
 * crossing is beyond any control period for any gap above 1e-100 J/kg, and
 * for physical energies (gap below 1e200 J/kg) gap / rate stays finite; with
 * an absurd mu an infinite t_cross only fails the comparison below. The float
 * build takes 1e-15 (OGK_REAL_ROOT_TINY): gaps above 1e-15 J/kg, and gap / rate
 * finite (at most 1e30) for gaps below 1e15 J/kg. */
#if OGK_REAL_SINGLE
#define CUTOFF_RATE_MIN_W_KG OGK_REAL_ROOT_TINY
#else
#define CUTOFF_RATE_MIN_W_KG OGK_R(1.0e-100)
#endif

ogk_status ogk_cutoff_config_default(ogk_cutoff_config_t *cfg)
{
    ogk_status st = OGK_OK;

    if (cfg == NULL) {
        st = OGK_E_NULL;
    } else {
        cfg->mu_m3_s2 = OGK_R(3.986004e14);
        cfg->target_sma_m = OGK_R(42164.0e3);
        cfg->arm_before_s = OGK_R(2.0);
        cfg->extend_max_s = OGK_R(10.0);
        cfg->control_period_s = OGK_R(0.02);
    }
    return st;
}

static bool config_valid(const ogk_cutoff_config_t *cfg)
{
    const ogk_real_t v[5] = {cfg->mu_m3_s2, cfg->target_sma_m, cfg->arm_before_s, cfg->extend_max_s,
                         cfg->control_period_s};

    return ogk_i_all_finite(v, 5u) && (cfg->mu_m3_s2 > OGK_R(0.0)) && (cfg->target_sma_m > OGK_R(0.0)) &&
           (cfg->target_sma_m <= OGK_CUTOFF_R_MAX_M) && (cfg->arm_before_s >= OGK_R(0.0)) &&
           (cfg->arm_before_s <= OGK_CUTOFF_T_MAX_S) && (cfg->extend_max_s >= OGK_R(0.0)) &&
           (cfg->extend_max_s <= OGK_CUTOFF_T_MAX_S) && (cfg->control_period_s > OGK_R(0.0)) &&
           (cfg->control_period_s <= OGK_CUTOFF_T_MAX_S);
}

static void clear_state(ogk_cutoff_t *ctx)
{
    ctx->energy_prev_j_kg = OGK_R(0.0);
    ctx->t_prev_s = OGK_R(0.0);
    ctx->t_cutoff_s = OGK_R(0.0);
    ctx->t_backstop_s = OGK_CUTOFF_T_MAX_S;
    ctx->have_prev = false;
    ctx->decided = false;
}

ogk_status ogk_cutoff_init(ogk_cutoff_t *ctx, const ogk_cutoff_config_t *cfg)
{
    ogk_status st = OGK_OK;

    if ((ctx == NULL) || (cfg == NULL)) {
        st = OGK_E_NULL;
    } else if (!config_valid(cfg)) {
        st = OGK_E_CONFIG;
    } else {
        ctx->cfg = *cfg;
        /* Specific energy of any orbit with semi-major axis a (vis-viva). */
        ctx->energy_target_j_kg = -cfg->mu_m3_s2 / (OGK_R(2.0) * cfg->target_sma_m);
        clear_state(ctx);
        ctx->init_marker = OGK_CUTOFF_INIT_MARKER;
    }
    return st;
}

ogk_status ogk_cutoff_reset(ogk_cutoff_t *ctx)
{
    ogk_status st = OGK_OK;

    if (ctx == NULL) {
        st = OGK_E_NULL;
    } else if (ctx->init_marker != OGK_CUTOFF_INIT_MARKER) {
        st = OGK_E_NOT_INIT;
    } else {
        clear_state(ctx);
    }
    return st;
}

static bool nav_in_envelope(const ogk_cutoff_t *ctx, const ogk_nav_state_t *nav)
{
    return (nav->r_m > OGK_R(0.0)) && (nav->r_m <= OGK_CUTOFF_R_MAX_M) &&
           (OGK_FABS(nav->v_r_mps) <= OGK_CUTOFF_V_MAX_MPS) && (OGK_FABS(nav->v_t_mps) <= OGK_CUTOFF_V_MAX_MPS) &&
           (OGK_FABS(nav->v_n_mps) <= OGK_CUTOFF_V_MAX_MPS) && (nav->t_s >= OGK_R(0.0)) &&
           (nav->t_s <= OGK_CUTOFF_T_MAX_S) && ((!ctx->have_prev) || (nav->t_s > ctx->t_prev_s));
}

static bool prediction_usable(ogk_real_t t_predicted_s)
{
    return isfinite(t_predicted_s) && (t_predicted_s >= OGK_R(0.0)) && (t_predicted_s <= OGK_CUTOFF_T_MAX_S);
}

/* The output of a rejected call: the cut-off in force, nothing moved. */
static void fill_rejected(const ogk_cutoff_t *ctx, ogk_real_t t_predicted_s, ogk_cutoff_out_t *out)
{
    out->energy_j_kg = OGK_R(0.0);
    out->energy_rate_w_kg = OGK_R(0.0);
    if (ctx->decided) {
        out->t_cutoff_s = ctx->t_cutoff_s;
        out->flags = OGK_CUTOFF_FLAG_DECIDED;
    } else if (prediction_usable(t_predicted_s)) {
        out->t_cutoff_s = t_predicted_s + ctx->cfg.extend_max_s;
        out->flags = OGK_CUTOFF_FLAG_BACKSTOP;
    } else {
        out->t_cutoff_s = ctx->t_backstop_s;
        out->flags = OGK_CUTOFF_FLAG_BACKSTOP;
    }
}

/* An accepted call: energy, its rate over the last period, the decision. */
static void accept(ogk_cutoff_t *ctx, const ogk_nav_state_t *nav, ogk_real_t t_predicted_s,
                   ogk_cutoff_out_t *out)
{
    const ogk_real_t v2 = (nav->v_r_mps * nav->v_r_mps) + (nav->v_t_mps * nav->v_t_mps) +
                      (nav->v_n_mps * nav->v_n_mps);
    /* Bounded by the envelope: |v| <= 1.8e5 m/s, r > 0 finite; mu / r may
     * still overflow for a subnormal r, hence the check below. */
    const ogk_real_t energy = (OGK_R(0.5) * v2) - (ctx->cfg.mu_m3_s2 / nav->r_m);
    const ogk_real_t backstop = t_predicted_s + ctx->cfg.extend_max_s;
    ogk_real_t rate = OGK_R(0.0);

    if (ctx->have_prev) {
        /* > 0 by the envelope (t_s after t_prev_s) */
        const ogk_real_t dt = nav->t_s - ctx->t_prev_s;
        if (dt >= CUTOFF_DT_MIN_S) {
            rate = (energy - ctx->energy_prev_j_kg) / dt;
        }
        if (!isfinite(rate)) {
            rate = OGK_R(0.0); /* an energy change beyond DBL_MAX (absurd mu): no extrapolation now */
        }
    }
    out->flags = 0u;
    if ((!ctx->decided) && (nav->t_s >= (t_predicted_s - ctx->cfg.arm_before_s))) {
        out->flags |= OGK_CUTOFF_FLAG_ARMED;
        if (energy >= ctx->energy_target_j_kg) {
            ctx->t_cutoff_s = nav->t_s; /* reached already: now */
            ctx->decided = true;
        } else if (rate >= CUTOFF_RATE_MIN_W_KG) {
            /* Linear extrapolation of the energy over the coming period. */
            const ogk_real_t t_cross = nav->t_s + ((ctx->energy_target_j_kg - energy) / rate);
            if (t_cross <= (nav->t_s + ctx->cfg.control_period_s)) {
                ctx->t_cutoff_s = t_cross;
                ctx->decided = true;
            }
        } else {
            /* No rate yet, or energy not increasing: wait for the backstop. */
        }
    }
    if ((!ctx->decided) && (nav->t_s >= backstop)) {
        ctx->t_cutoff_s = nav->t_s; /* the backstop reached: now */
        ctx->decided = true;
    }
    ctx->energy_prev_j_kg = energy;
    ctx->t_prev_s = nav->t_s;
    ctx->have_prev = true;
    ctx->t_backstop_s = backstop;
    out->energy_j_kg = energy;
    out->energy_rate_w_kg = rate;
    if (ctx->decided) {
        out->t_cutoff_s = ctx->t_cutoff_s;
        out->flags |= OGK_CUTOFF_FLAG_DECIDED;
    } else {
        out->t_cutoff_s = backstop;
        out->flags |= OGK_CUTOFF_FLAG_BACKSTOP;
    }
}

ogk_status ogk_cutoff_step(ogk_cutoff_t *ctx, const ogk_nav_state_t *nav, ogk_real_t t_predicted_s,
                           ogk_cutoff_out_t *out)
{
    ogk_status st = OGK_OK;

    if ((ctx == NULL) || (nav == NULL) || (out == NULL)) {
        st = OGK_E_NULL;
    } else if (ctx->init_marker != OGK_CUTOFF_INIT_MARKER) {
        st = OGK_E_NOT_INIT;
    } else {
        const ogk_real_t v[6] = {nav->t_s, nav->r_m, nav->v_r_mps, nav->v_t_mps, nav->v_n_mps, t_predicted_s};
        if (!ogk_i_all_finite(v, 6u)) {
            st = OGK_E_NONFINITE;
        } else if ((!nav_in_envelope(ctx, nav)) || (!prediction_usable(t_predicted_s)) ||
                   (!isfinite(ctx->cfg.mu_m3_s2 / nav->r_m))) {
            st = OGK_E_RANGE;
        } else {
            accept(ctx, nav, t_predicted_s, out);
        }
        if (st != OGK_OK) {
            fill_rejected(ctx, t_predicted_s, out);
        }
    }
    return st;
}
