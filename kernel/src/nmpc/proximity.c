/* proximity.c -- the proximity approach's API (ogk/proximity.h): the model
 * validated and held in the context, the NMPC's solver and strategies
 * (ogk/nmpc.h) run on it through ogk_prox_problem (prox_model.c). */
#include "ogk/proximity.h"

#include <math.h>
#include <string.h>

#include "../ogk_checks.h"

ogk_status ogk_prox_config_default(ogk_prox_config_t *cfg)
{
    ogk_status st = OGK_OK;
    if (cfg == NULL) {
        st = OGK_E_NULL;
    } else {
        (void)memset(&cfg->model, 0, sizeof(cfg->model));
        /* normalised units: TU = 1 / n (docs/design/nmpc-problem.md) */
        cfg->model.mean_motion = OGK_R(1.0);
        st = ogk_nmpc_config_default(&cfg->solver);
        cfg->solver.engine = OGK_NMPC_ENGINE_THROTTLED;
        cfg->solver.objective = OGK_NMPC_MIN_FUEL;
    }
    return st;
}

/* Every double of the model finite (the discs beyond n_keepout too: the
 * defaults zero them). */
static bool prox_model_finite(const ogk_prox_model_t *m)
{
    return isfinite(m->mean_motion) && isfinite(m->thrust_max) && isfinite(m->mass_flow_max)
        && ogk_i_all_finite(m->hold, 2u)
        && ogk_i_all_finite(m->keepout_centre, 2u * (size_t)OGK_PROX_MAX_KEEPOUT)
        && ogk_i_all_finite(m->keepout_radius, OGK_PROX_MAX_KEEPOUT);
}

/* The model's ranges (ogk/proximity.h), its doubles finite. */
static bool prox_model_valid(const ogk_prox_model_t *m)
{
    bool ok = (m->mean_motion > OGK_R(0.0)) && (m->thrust_max > OGK_R(0.0)) && (m->mass_flow_max >= OGK_R(0.0))
        && (m->n_keepout <= OGK_PROX_MAX_KEEPOUT);
    size_t j;
    for (j = 0u; j < OGK_PROX_MAX_KEEPOUT; ++j) {
        ok = ok && (m->keepout_radius[j] >= OGK_R(0.0));
    }
    return ok;
}

ogk_status ogk_prox_init(ogk_prox_t *ctx, const ogk_prox_config_t *cfg)
{
    ogk_status st = OGK_OK;
    if ((ctx == NULL) || (cfg == NULL)) {
        st = OGK_E_NULL;
    } else {
        /* as ogk_nmpc_init: a rejected configuration leaves the context uninitialised */
        ctx->init_marker = 0u;
        if (!prox_model_finite(&cfg->model)) {
            st = OGK_E_NONFINITE;
        } else if (!prox_model_valid(&cfg->model)) {
            st = OGK_E_CONFIG;
        } else {
            ogk_nmpc_config_t solver;
            (void)memcpy(&solver, &cfg->solver, sizeof(solver));
            /* the throttle is a control of this problem whatever the caller left there */
            solver.engine = OGK_NMPC_ENGINE_THROTTLED;
            (void)memcpy(&ctx->model, &cfg->model, sizeof(ctx->model));
            st = ogk_nmpc_init_problem(&ctx->nmpc, &solver, &ogk_prox_problem, &ctx->model);
            if (st == OGK_OK) {
                ctx->init_marker = OGK_PROX_INIT_MARKER;
            }
        }
    }
    return st;
}

/* The context's solver, its problem re-bound to the context's own model (a
 * context copied by value keeps pointing at its own copy), or NULL with the
 * status saying why. */
static ogk_nmpc_t *prox_bind(ogk_prox_t *ctx, ogk_status *st)
{
    ogk_nmpc_t *nmpc = NULL;
    if (ctx == NULL) {
        *st = OGK_E_NULL;
    } else if (ctx->init_marker != OGK_PROX_INIT_MARKER) {
        *st = OGK_E_NOT_INIT;
    } else {
        ctx->nmpc.problem_data = &ctx->model;
        nmpc = &ctx->nmpc;
        *st = OGK_OK;
    }
    return nmpc;
}

/* The same check for the calls that only read the plan (the problem is not called). */
static const ogk_nmpc_t *prox_solver(const ogk_prox_t *ctx, ogk_status *st)
{
    const ogk_nmpc_t *nmpc = NULL;
    if (ctx == NULL) {
        *st = OGK_E_NULL;
    } else if (ctx->init_marker != OGK_PROX_INIT_MARKER) {
        *st = OGK_E_NOT_INIT;
    } else {
        nmpc = &ctx->nmpc;
        *st = OGK_OK;
    }
    return nmpc;
}

ogk_status ogk_prox_reset(ogk_prox_t *ctx)
{
    ogk_status st;
    ogk_nmpc_t *nmpc = prox_bind(ctx, &st);
    if (nmpc != NULL) {
        st = ogk_nmpc_reset(nmpc);
    }
    return st;
}

ogk_status ogk_prox_set_horizon_bounds(ogk_prox_t *ctx, ogk_real_t horizon_min, ogk_real_t horizon_max)
{
    ogk_status st;
    ogk_nmpc_t *nmpc = prox_bind(ctx, &st);
    if (nmpc != NULL) {
        st = ogk_nmpc_set_horizon_bounds(nmpc, horizon_min, horizon_max);
    }
    return st;
}

ogk_status ogk_prox_set_hessian_init(ogk_prox_t *ctx, ogk_real_t hessian_init)
{
    ogk_status st;
    ogk_nmpc_t *nmpc = prox_bind(ctx, &st);
    if (nmpc != NULL) {
        st = ogk_nmpc_set_hessian_init(nmpc, hessian_init);
    }
    return st;
}

ogk_status ogk_prox_load_plan(ogk_prox_t *ctx, const ogk_nmpc_plan_t *plan)
{
    ogk_status st;
    ogk_nmpc_t *nmpc = prox_bind(ctx, &st);
    if (nmpc != NULL) {
        st = ogk_nmpc_load_plan(nmpc, plan);
    }
    return st;
}

ogk_status ogk_prox_get_plan(const ogk_prox_t *ctx, ogk_nmpc_plan_t *plan)
{
    ogk_status st;
    const ogk_nmpc_t *nmpc = prox_solver(ctx, &st);
    if (nmpc != NULL) {
        st = ogk_nmpc_get_plan(nmpc, plan);
    }
    return st;
}

ogk_status ogk_prox_solve(ogk_prox_t *ctx, const ogk_nmpc_input_t *in, ogk_nmpc_report_t *rep)
{
    ogk_status st;
    ogk_nmpc_t *nmpc = prox_bind(ctx, &st);
    if (nmpc != NULL) {
        st = ogk_nmpc_solve(nmpc, in, rep);
    }
    return st;
}

ogk_status ogk_prox_replan(ogk_prox_t *ctx, const ogk_nmpc_input_t *in, ogk_nmpc_report_t *rep)
{
    ogk_status st;
    ogk_nmpc_t *nmpc = prox_bind(ctx, &st);
    if (nmpc != NULL) {
        st = ogk_nmpc_replan(nmpc, in, rep);
    }
    return st;
}

ogk_status ogk_prox_command(const ogk_prox_t *ctx, ogk_real_t t, ogk_nmpc_command_t *cmd)
{
    ogk_status st;
    const ogk_nmpc_t *nmpc = prox_solver(ctx, &st);
    /* called with NULL for a rejected context too: it then writes the safe command into cmd */
    const ogk_status st_cmd = ogk_nmpc_command(nmpc, t, cmd);
    if (st == OGK_OK) {
        st = st_cmd;
    }
    return st;
}

ogk_status ogk_prox_thrust_cmd(const ogk_prox_t *ctx, ogk_real_t t, ogk_thrust_cmd_t *cmd)
{
    ogk_status st;
    const ogk_nmpc_t *nmpc = prox_solver(ctx, &st);
    /* as ogk_prox_command: the safe command (in r-t-n) for a rejected context. The Hill frame's
     * (x radial, y along-track) is r-t-n's (r, t) and alpha is measured from the radial axis as the
     * heliocentric model's, so ogk_nmpc_thrust_cmd's conversion is this problem's too */
    const ogk_status st_cmd = ogk_nmpc_thrust_cmd(nmpc, t, cmd);
    if (st == OGK_OK) {
        st = st_cmd;
    }
    return st;
}
