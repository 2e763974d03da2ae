/* nmpc.c -- public API of ogk_nmpc (ogk/nmpc.h): configuration, plans, the
 * receding-horizon strategies of Starek & Kolmanovsky (2012) sec. 2.3 around
 * the SQP of nmpc_sqp.c, and the command. */
#include "ogk/nmpc.h"

#include <math.h>
#include <string.h>

#include "nmpc_internal.h"
#include "ogk/internal/nmpc_test.h"
#include "ogk/types.h"
#include "../ogk_checks.h"
#include "../thrust_cmd_internal.h"

#define NX OGK_NMPC_NX

/* Relative slack when counting the subintervals already flown. */
#define FLOWN_EPS OGK_R(1.0e-9)

ogk_status ogk_nmpc_config_default(ogk_nmpc_config_t *cfg)
{
    ogk_status st = OGK_OK;
    if (cfg == NULL) {
        st = OGK_E_NULL;
    } else {
        (void)memset(cfg, 0, sizeof(*cfg));
        cfg->mu = OGK_R(1.0);
        cfg->engine = OGK_NMPC_ENGINE_CONSTANT;
        cfg->power = OGK_NMPC_POWER_CONSTANT;
        cfg->thrust_max = OGK_R(0.0);      /* must be set */
        cfg->mass_flow_max = OGK_R(0.0);   /* must be set */
        cfg->solar_length_unit = OGK_R(1.0);
        cfg->n_bodies = 0u;
        cfg->target_radius = OGK_R(0.0);   /* must be set */
        cfg->objective = OGK_NMPC_MIN_TIME;
        cfg->nodes = 30u;
        cfg->rk4_steps = 8u;
        cfg->horizon_min = OGK_R(1.0e-3);
        cfg->horizon_max = OGK_R(30.0);
        cfg->max_sweep = OGK_R(0.0);
        cfg->max_iter = 100u;
        cfg->max_iter_cold = 200u;
        cfg->tol_feas = OGK_R(1.0e-9);
        cfg->tol_stat = OGK_R(1.0e-7);
        cfg->tol_obj = OGK_R(1.0e-7);
        cfg->hessian = OGK_NMPC_HESSIAN_BFGS;
        cfg->hessian_init = OGK_R(1.0);
        cfg->step_max_alpha = OGK_R(1.0);
        cfg->step_max_horizon = OGK_R(1.0);
        cfg->elastic_weight = OGK_R(1000.0);
        cfg->strategy = OGK_NMPC_SNNS;
        cfg->min_nodes = 2u;
        cfg->max_subdivisions = 2u;
        cfg->doubling_threshold = OGK_R(0.01);
        cfg->doubling_max_nodes = 8u;
    }
    return st;
}

/* The solver's settings (transcription, SQP, strategy): every problem's. */
static bool settings_finite(const ogk_nmpc_config_t *c)
{
    const ogk_real_t scalars[] = {
        c->horizon_min, c->horizon_max, c->max_sweep, c->time_weight, c->tol_feas, c->tol_stat, c->tol_obj,
        c->hessian_init, c->step_max_alpha, c->step_max_horizon, c->elastic_weight, c->doubling_threshold,
        c->mass_min
    };
    return ogk_i_all_finite(scalars, sizeof(scalars) / sizeof(scalars[0]))
        && ogk_i_all_finite(c->terminal_box, OGK_NMPC_NC);
}

static bool settings_valid(const ogk_nmpc_config_t *c)
{
    return (c->engine <= OGK_NMPC_ENGINE_THROTTLED)
        && (c->objective <= OGK_NMPC_MIN_FUEL) && (c->strategy <= OGK_NMPC_CNCN)
        && (c->hessian <= OGK_NMPC_HESSIAN_EXACT)
        && (c->nodes >= 1u) && (c->nodes <= OGK_NMPC_MAX_NODES)
        && (c->rk4_steps >= 1u) && (c->rk4_steps <= OGK_NMPC_MAX_RK4_STEPS)
        && (c->horizon_min > OGK_R(0.0)) && (c->horizon_max > c->horizon_min)
        && (c->max_sweep >= OGK_R(0.0)) && (c->time_weight >= OGK_R(0.0)) && (c->mass_min >= OGK_R(0.0))
        && (c->terminal_box[0] >= OGK_R(0.0)) && (c->terminal_box[1] >= OGK_R(0.0))
        && (c->terminal_box[2] >= OGK_R(0.0)) && (c->terminal_box[3] >= OGK_R(0.0))
        && (c->max_iter >= 1u) && (c->max_iter <= OGK_NMPC_MAX_SQP_ITER)
        && (c->max_iter_cold >= 1u) && (c->max_iter_cold <= OGK_NMPC_MAX_SQP_ITER)
        && (c->tol_feas > OGK_R(0.0)) && (c->tol_stat > OGK_R(0.0)) && (c->tol_obj >= OGK_R(0.0)) && (c->hessian_init > OGK_R(0.0))
        && (c->step_max_alpha > OGK_R(0.0)) && (c->step_max_horizon > OGK_R(0.0)) && (c->elastic_weight > OGK_R(0.0))
        && (c->min_nodes >= 1u) && (c->min_nodes <= OGK_NMPC_MAX_NODES)
        && (c->doubling_threshold >= OGK_R(0.0))
        && (c->doubling_max_nodes <= (OGK_NMPC_MAX_NODES / 2u));
}

/* The heliocentric problem's model and target fields. */
static bool helio_finite(const ogk_nmpc_config_t *c)
{
    const ogk_real_t scalars[] = {
        c->mu, c->thrust_max, c->mass_flow_max, c->solar_length_unit,
        c->target_radius, c->target_phase0, c->target_rate
    };
    return ogk_i_all_finite(scalars, sizeof(scalars) / sizeof(scalars[0]))
        && ogk_i_all_finite(c->solar_a, 4u) && ogk_i_all_finite(c->solar_thrust, 2u)
        && ogk_i_all_finite(c->solar_flow, 2u)
        && ogk_i_all_finite(c->body_mu, OGK_NMPC_MAX_BODIES)
        && ogk_i_all_finite(c->body_radius, OGK_NMPC_MAX_BODIES)
        && ogk_i_all_finite(c->body_phase0, OGK_NMPC_MAX_BODIES)
        && ogk_i_all_finite(c->body_rate, OGK_NMPC_MAX_BODIES)
        && ogk_i_all_finite(c->body_softening, OGK_NMPC_MAX_BODIES)
        && ogk_i_all_finite(c->keepout_radius, OGK_NMPC_MAX_BODIES)
        && ogk_i_all_finite(c->body_release, OGK_NMPC_MAX_BODIES);
}

static bool helio_valid(const ogk_nmpc_config_t *c)
{
    bool ok = (c->mu > OGK_R(0.0)) && (c->target_radius > OGK_R(0.0)) && (c->power <= OGK_NMPC_POWER_SOLAR)
        && (c->n_bodies <= OGK_NMPC_MAX_BODIES);
    /* clamped so the loop has a fixed bound; n_bodies > MAX has made ok false above */
    const uint32_t n_bodies = ogk_i_min_u32(c->n_bodies, OGK_NMPC_MAX_BODIES);
    uint32_t b;
    if (ok && (c->power == OGK_NMPC_POWER_SOLAR)) {
        ok = c->solar_length_unit > OGK_R(0.0);
    } else if (ok) {
        ok = (c->thrust_max > OGK_R(0.0)) && (c->mass_flow_max >= OGK_R(0.0));
    } else {
        /* already rejected */
    }
    for (b = 0u; ok && (b < n_bodies); ++b) {
        ok = (c->body_mu[b] >= OGK_R(0.0)) && (c->body_radius[b] > OGK_R(0.0)) && (c->body_softening[b] >= OGK_R(0.0))
            && (c->keepout_radius[b] >= OGK_R(0.0)) && (c->body_release[b] >= OGK_R(0.0));
    }
    return ok;
}

static void nmpc_prepare(ogk_nmpc_t *ctx)
{
    /* every third body back in the predictive model */
    (void)memcpy(ctx->cfg.body_mu, ctx->body_mu_init, sizeof(ctx->cfg.body_mu));
    if (ctx->cfg.engine == OGK_NMPC_ENGINE_THROTTLED) {
        ctx->nu = 2u;
    } else {
        ctx->nu = 1u;
    }
    ctx->subdivisions = 0u;
    ctx->plan_flags = 0u;
    ctx->have_plan = 0u;
    ctx->hess_valid = 0u;
    (void)memset(&ctx->plan, 0, sizeof(ctx->plan));
    (void)memset(&ctx->work, 0, sizeof(ctx->work));
    /* no sensitivities kept: every key 0 (none matches), for this model */
    ogk_i_nmpc_cache_reset(ctx);
}

/* init's common part: cfg copied, the problem bound, the context prepared. */
static void nmpc_start(ogk_nmpc_t *ctx, const ogk_nmpc_config_t *cfg, const ogk_ocp_problem_t *problem,
                       void *data)
{
    (void)memcpy(&ctx->cfg, cfg, sizeof(*cfg));
    (void)memcpy(ctx->body_mu_init, cfg->body_mu, sizeof(ctx->body_mu_init));
    ctx->problem = problem;
    ctx->problem_data = data;
    nmpc_prepare(ctx);
    ctx->init_marker = OGK_NMPC_INIT_MARKER;
}

ogk_status ogk_nmpc_init(ogk_nmpc_t *ctx, const ogk_nmpc_config_t *cfg)
{
    ogk_status st = OGK_OK;
    if ((ctx == NULL) || (cfg == NULL)) {
        st = OGK_E_NULL;
    } else {
        ctx->init_marker = 0u;
        if (!settings_finite(cfg) || !helio_finite(cfg)) {
            st = OGK_E_NONFINITE;
        } else if (!settings_valid(cfg) || !helio_valid(cfg)) {
            st = OGK_E_CONFIG;
        } else {
            nmpc_start(ctx, cfg, &ogk_i_nmpc_helio_problem, NULL);
        }
    }
    return st;
}

ogk_status ogk_nmpc_init_problem(ogk_nmpc_t *ctx, const ogk_nmpc_config_t *cfg,
                                 const ogk_ocp_problem_t *problem, void *data)
{
    ogk_status st = OGK_OK;
    if ((ctx == NULL) || (cfg == NULL) || (problem == NULL) || (data == NULL)) {
        st = OGK_E_NULL;
    } else {
        ctx->init_marker = 0u;
        if (!settings_finite(cfg)) {
            st = OGK_E_NONFINITE;
        } else if (!settings_valid(cfg) || (problem->structure == NULL) || (problem->dynamics == NULL)
                   || (problem->dynamics_hess == NULL) || (problem->target == NULL)
                   || (problem->keepout_radius == NULL) || (problem->keepout_distance == NULL)
                   || (problem->model_key == NULL) || (problem->state_valid == NULL)) {
            st = OGK_E_CONFIG;
        } else {
            nmpc_start(ctx, cfg, problem, data);
        }
    }
    return st;
}

static ogk_status nmpc_check_ctx(const ogk_nmpc_t *ctx)
{
    ogk_status st = OGK_OK;
    if (ctx == NULL) {
        st = OGK_E_NULL;
    } else if (ctx->init_marker != OGK_NMPC_INIT_MARKER) {
        st = OGK_E_NOT_INIT;
    } else {
        /* usable */
    }
    return st;
}

ogk_status ogk_nmpc_reset(ogk_nmpc_t *ctx)
{
    ogk_status st = nmpc_check_ctx(ctx);
    if (st == OGK_OK) {
        nmpc_prepare(ctx);
    }
    return st;
}

ogk_status ogk_nmpc_set_horizon_bounds(ogk_nmpc_t *ctx, ogk_real_t horizon_min, ogk_real_t horizon_max)
{
    ogk_status st = nmpc_check_ctx(ctx);
    if (st != OGK_OK) {
        /* st says why */
    } else if (!isfinite(horizon_min) || !isfinite(horizon_max)) {
        st = OGK_E_NONFINITE;
    } else if (!((horizon_min > OGK_R(0.0)) && (horizon_max > horizon_min))) {
        st = OGK_E_CONFIG;   /* the configuration's own rule (settings_valid) */
    } else {
        ctx->cfg.horizon_min = horizon_min;
        ctx->cfg.horizon_max = horizon_max;
    }
    return st;
}

ogk_status ogk_nmpc_set_hessian_init(ogk_nmpc_t *ctx, ogk_real_t hessian_init)
{
    ogk_status st = nmpc_check_ctx(ctx);
    if (st != OGK_OK) {
        /* st says why */
    } else if (!isfinite(hessian_init)) {
        st = OGK_E_NONFINITE;
    } else if (!(hessian_init > OGK_R(0.0))) {
        st = OGK_E_CONFIG;
    } else {
        ctx->cfg.hessian_init = hessian_init;
    }
    return st;
}

ogk_status ogk_nmpc_load_plan(ogk_nmpc_t *ctx, const ogk_nmpc_plan_t *plan)
{
    ogk_status st = nmpc_check_ctx(ctx);
    if ((st == OGK_OK) && (plan == NULL)) {
        st = OGK_E_NULL;
    }
    if (st == OGK_OK) {
        if ((plan->nodes < 1u) || (plan->nodes > OGK_NMPC_MAX_NODES) || (plan->nu != ctx->nu)) {
            st = OGK_E_DIM;
        } else if (!isfinite(plan->t0) || !isfinite(plan->horizon)
                   || !ogk_i_all_finite(plan->x, ((size_t)plan->nodes + 1u) * NX)
                   || !ogk_i_all_finite(plan->u, ((size_t)plan->nodes + 1u) * plan->nu)
                   || !ogk_i_all_finite(plan->lambda, OGK_NMPC_NC)) {
            st = OGK_E_NONFINITE;
        } else if ((plan->horizon < ctx->cfg.horizon_min) || (plan->horizon > ctx->cfg.horizon_max)) {
            st = OGK_E_RANGE;
        } else {
            const ogk_i_ocp_t ocp = ogk_i_nmpc_problem(ctx);
            if (!ocp.ops->state_valid(ocp.data, plan->x, (size_t)plan->nodes + 1u)) {
                st = OGK_E_RANGE;
            }
            if (ctx->nu > 1u) {
                uint32_t k;
                /* the throttle in [0, 1] at every node (nodes <= OGK_NMPC_MAX_NODES: checked above) */
                for (k = 0u; k <= plan->nodes; ++k) {
                    const ogk_real_t w = plan->u[(2u * k) + 1u];
                    if (!((w >= OGK_R(0.0)) && (w <= OGK_R(1.0)))) {
                        st = OGK_E_RANGE;
                    }
                }
            }
        }
    }
    if (st == OGK_OK) {
        (void)memcpy(&ctx->plan, plan, sizeof(*plan));
        ctx->have_plan = 1u;
        ctx->hess_valid = 0u;
        ctx->plan_flags = 0u;
    }
    return st;
}

ogk_status ogk_nmpc_get_plan(const ogk_nmpc_t *ctx, ogk_nmpc_plan_t *plan)
{
    ogk_status st = nmpc_check_ctx(ctx);
    if ((st == OGK_OK) && (plan == NULL)) {
        st = OGK_E_NULL;
    }
    if ((st == OGK_OK) && (ctx->have_plan == 0u)) {
        st = OGK_E_RANGE;
    }
    if (st == OGK_OK) {
        (void)memcpy(plan, &ctx->plan, sizeof(*plan));
    }
    return st;
}

/* x inside the problem's domain (the heliocentric: r > 0 and m > 0). */
static bool state_valid(const ogk_nmpc_t *ctx, const ogk_real_t *x)
{
    const ogk_i_ocp_t ocp = ogk_i_nmpc_problem(ctx);
    return ocp.ops->state_valid(ocp.data, x, 1u);
}

static ogk_status check_input(const ogk_nmpc_t *ctx, const ogk_nmpc_input_t *in,
                              ogk_nmpc_report_t *rep)
{
    ogk_status st = nmpc_check_ctx(ctx);
    if ((st == OGK_OK) && ((in == NULL) || (rep == NULL))) {
        st = OGK_E_NULL;
    }
    if (st == OGK_OK) {
        (void)memset(rep, 0, sizeof(*rep));
        if (!isfinite(in->t) || !ogk_i_all_finite(in->x, NX)) {
            st = OGK_E_NONFINITE;
        } else if ((ctx->have_plan == 0u) || !state_valid(ctx, in->x) || !(OGK_FABS(in->t) <= OGK_NMPC_T_ABS_MAX)) {
            st = OGK_E_RANGE; /* no plan, outside the model's domain, or a time the plan's arithmetic cannot resolve */
        } else {
            /* usable */
        }
    }
    return st;
}

static void fill_report(const ogk_nmpc_t *ctx, ogk_nmpc_report_t *rep)
{
    const ogk_nmpc_plan_t *p = &ctx->plan;
    rep->flags |= ctx->plan_flags;
    rep->nodes = p->nodes;
    rep->t_next = p->t0 + (p->horizon / (ogk_real_t)p->nodes);
    rep->t_f = p->t0 + p->horizon;
    rep->objective = ogk_i_nmpc_objective(&ctx->cfg, p);
}

/* The problem's own update from the measured state (the heliocentric
 * problem: a departure planet's release, body_release), its flags in rep. */
static void update_problem(ogk_nmpc_t *ctx, const ogk_nmpc_input_t *in, ogk_nmpc_report_t *rep)
{
    if (ctx->problem->update != NULL) {
        void *data = (ctx->problem_data != NULL) ? ctx->problem_data : (void *)&ctx->cfg;
        rep->flags |= ctx->problem->update(data, in->t, in->x);
    }
}

/* work := plan re-anchored at (t, x): node 0 measured, same t_f. */
static void anchor_work(ogk_nmpc_t *ctx, const ogk_nmpc_input_t *in)
{
    const ogk_real_t t_f = ctx->plan.t0 + ctx->plan.horizon;
    (void)memcpy(&ctx->work, &ctx->plan, sizeof(ctx->work));
    ctx->work.t0 = in->t;
    ctx->work.horizon = t_f - in->t;
    if (ctx->work.horizon < ctx->cfg.horizon_min) {
        ctx->work.horizon = ctx->cfg.horizon_min;
    }
    (void)memcpy(ctx->work.x, in->x, NX * sizeof(ogk_real_t));
}

/* Runs the SQP on work; on success it becomes the plan. */
static ogk_status solve_work(ogk_nmpc_t *ctx, ogk_nmpc_report_t *rep)
{
    const bool cold = (ctx->hess_valid == 0u);
    ogk_status st = ogk_i_nmpc_sqp(ctx, ctx->hess, cold, rep);
    rep->solve_status = st;
    if (st == OGK_OK) {
        (void)memcpy(&ctx->plan, &ctx->work, sizeof(ctx->plan));
        ctx->hess_valid = 1u;
        ctx->plan_flags = OGK_NMPC_FLAG_CONVERGED;
    } else {
        ctx->hess_valid = 0u;
        ctx->plan_flags = OGK_NMPC_FLAG_STALE;
    }
    return st;
}

ogk_status ogk_nmpc_solve(ogk_nmpc_t *ctx, const ogk_nmpc_input_t *in,
                          ogk_nmpc_report_t *rep)
{
    ogk_status st = check_input(ctx, in, rep);
    if (st == OGK_OK) {
        update_problem(ctx, in, rep);
        anchor_work(ctx, in);
        st = solve_work(ctx, rep);
        fill_report(ctx, rep);
    }
    return st;
}

/* Rows and columns [drop, nv) of the BFGS matrix, moved to the top left. */
static void hessian_drop(ogk_real_t *hess, size_t nv, size_t drop)
{
    const size_t nv_new = nv - drop;
    size_t i;
    size_t j;
    for (i = 0u; i < nv_new; ++i) {
        for (j = 0u; j < nv_new; ++j) {
            hess[(i * nv_new) + j] = hess[((i + drop) * nv) + (j + drop)];
        }
    }
}

/* The strategy's shift of the plan to time t (sec. 2.3). */
static void shift_plan(ogk_nmpc_t *ctx, ogk_real_t t)
{
    ogk_nmpc_plan_t *p = &ctx->plan;
    const ogk_real_t h = p->horizon / (ogk_real_t)p->nodes;
    const size_t nv = (((size_t)p->nodes + 1u) * ctx->nu) + 1u;
    ogk_real_t flown = (t - p->t0) / h;
    uint32_t count = 0u;

    if (flown > OGK_R(0.0)) {
        flown += FLOWN_EPS;
    } else {
        flown = OGK_R(0.0);
    }
    if (flown < (ogk_real_t)p->nodes) {
        count = (uint32_t)flown;
    } else {
        count = p->nodes;
    }
    if (ctx->cfg.strategy == OGK_NMPC_SNNS) {
        /* count <= nodes, and nodes - count >= min_nodes >= 1 (ogk_nmpc_init) gives count < nodes */
        if ((count >= 1u) && ((p->nodes - count) >= ctx->cfg.min_nodes)) {
            /* SNN: the flown subintervals leave the plan, the rest is the guess */
            ogk_i_nmpc_cache_drop(ctx, p->nodes, count, ctx->nu);
            ogk_i_nmpc_plan_drop(p, count);
            if (ctx->hess_valid != 0u) {
                hessian_drop(ctx->hess, nv, (size_t)count * ctx->nu);
            }
        } else if (count >= 1u) {
            /* fewer than min_nodes would remain: keep min_nodes over [t, t_f] */
            const uint32_t n_keep = (ctx->cfg.min_nodes < p->nodes) ? ctx->cfg.min_nodes : p->nodes;
            const uint32_t n_before = p->nodes;
            ogk_i_nmpc_plan_regrid(p, t, n_keep, &ctx->trial);
            (void)memcpy(p, &ctx->trial, sizeof(*p));
            ctx->plan_flags |= OGK_NMPC_FLAG_REGRIDDED;
            /* another node count: the BFGS matrix no longer fits the unknowns */
            ctx->hess_valid = (n_keep == n_before) ? ctx->hess_valid : 0u;
        } else {
            /* nothing flown yet: re-solve the same plan */
        }
    } else {
        /* CNCN: the same N over [t, t_f] */
        ogk_i_nmpc_plan_regrid(p, t, p->nodes, &ctx->trial);
        (void)memcpy(p, &ctx->trial, sizeof(*p));
        ctx->plan_flags |= OGK_NMPC_FLAG_REGRIDDED;
    }
}

/* SNNS doubling test (sec. 2.3.3): solve with 2N from the N result (or the
 * shifted plan when N failed); adopt 2N when it improves J by more than the
 * threshold (the paper's "less than" is a typo) or when only 2N converged. */
static ogk_status doubling_test(ogk_nmpc_t *ctx, const ogk_nmpc_input_t *in,
                                ogk_status st_n, ogk_nmpc_report_t *rep)
{
    ogk_status st = st_n;
    const ogk_nmpc_config_t *cfg = &ctx->cfg;
    const ogk_i_ocp_t ocp = ogk_i_nmpc_problem(ctx);
    const uint32_t n = ctx->plan.nodes;

    if ((cfg->strategy == OGK_NMPC_SNNS) && (ctx->subdivisions < cfg->max_subdivisions)
        && (n <= cfg->doubling_max_nodes)) { /* 2 n <= OGK_NMPC_MAX_NODES: doubling_max_nodes <= MAX / 2 (init) */
        ogk_status st_sub;
        if (st_n != OGK_OK) {
            anchor_work(ctx, in);
            st_sub = ogk_i_nmpc_plan_subdivide(&ocp, &ctx->work, &ctx->alt);
        } else {
            st_sub = ogk_i_nmpc_plan_subdivide(&ocp, &ctx->plan, &ctx->alt);
        }
        if (st_sub == OGK_OK) {
            ogk_nmpc_report_t rep_alt;
            (void)memset(&rep_alt, 0, sizeof(rep_alt));
            (void)memcpy(&ctx->work, &ctx->alt, sizeof(ctx->work));
            st_sub = ogk_i_nmpc_sqp(ctx, ctx->hess_alt, true, &rep_alt);
            rep->sqp_iterations += rep_alt.sqp_iterations;
            rep->qp_iterations += rep_alt.qp_iterations;
            rep->solves += rep_alt.solves;
            if (st_sub == OGK_OK) {
                const ogk_real_t j_n = ogk_i_nmpc_objective(cfg, &ctx->plan);
                const ogk_real_t j_2n = ogk_i_nmpc_objective(cfg, &ctx->work);
                const ogk_real_t gain = (j_n - j_2n) / ((OGK_FABS(j_n) > OGK_R(1.0e-12)) ? OGK_FABS(j_n) : OGK_R(1.0e-12));
                if ((st_n != OGK_OK) || (gain > cfg->doubling_threshold)) {
                    const size_t nv = (((size_t)ctx->work.nodes + 1u) * ctx->nu) + 1u;
                    (void)memcpy(&ctx->plan, &ctx->work, sizeof(ctx->plan));
                    (void)memcpy(ctx->hess, ctx->hess_alt, nv * nv * sizeof(ogk_real_t));
                    ctx->hess_valid = 1u;
                    ctx->subdivisions += 1u;
                    ctx->plan_flags = OGK_NMPC_FLAG_CONVERGED | OGK_NMPC_FLAG_SUBDIVIDED;
                    rep->feas = rep_alt.feas;
                    rep->stat = rep_alt.stat;
                    rep->solve_status = OGK_OK;
                    st = OGK_OK;
                }
            }
        }
    }
    return st;
}

ogk_status ogk_nmpc_replan(ogk_nmpc_t *ctx, const ogk_nmpc_input_t *in,
                           ogk_nmpc_report_t *rep)
{
    ogk_status st = check_input(ctx, in, rep);
    if (st == OGK_OK) {
        update_problem(ctx, in, rep);
        ctx->plan_flags = 0u;
        if (((ctx->plan.t0 + ctx->plan.horizon) - in->t) < ctx->cfg.horizon_min) {
            /* t_f reached before the target: the plan is stretched to end
             * horizon_min after t (its nodes scaled in time) */
            ctx->plan.horizon = (in->t + ctx->cfg.horizon_min) - ctx->plan.t0;
            ctx->plan_flags |= OGK_NMPC_FLAG_REGRIDDED;
        }
        shift_plan(ctx, in->t);
        {
            const uint32_t shift_flags = ctx->plan_flags;
            anchor_work(ctx, in);
            st = solve_work(ctx, rep);
            ctx->plan_flags |= shift_flags;
        }
        st = doubling_test(ctx, in, st, rep);
        fill_report(ctx, rep);
    }
    return st;
}

/* ogk_nmpc_command (also behind ogk_nmpc_thrust_cmd). */
static ogk_status nmpc_command(const ogk_nmpc_t *ctx, ogk_real_t t, ogk_nmpc_command_t *cmd)
{
    ogk_status st = nmpc_check_ctx(ctx);
    if ((st == OGK_OK) && (cmd == NULL)) {
        st = OGK_E_NULL;
    }
    if (cmd != NULL) {
        /* the safe command: engine off */
        cmd->t = t;
        cmd->alpha = OGK_R(0.0);
        cmd->throttle = OGK_R(0.0);
        cmd->flags = OGK_THRUST_FLAG_SAFE;
        cmd->law_flags = 0u;
    }
    if (st == OGK_OK) {
        if (!isfinite(t)) {
            st = OGK_E_NONFINITE;
        } else if (ctx->have_plan == 0u) {
            st = OGK_E_RANGE;
        } else {
            ogk_real_t u[OGK_NMPC_MAX_NU] = { OGK_R(0.0), OGK_R(1.0) };
            ogk_i_nmpc_plan_control(&ctx->plan, t, u);
            cmd->alpha = u[0];
            cmd->throttle = (ctx->nu > 1u) ? u[1] : OGK_R(1.0);
            cmd->throttle = (cmd->throttle < OGK_R(0.0)) ? OGK_R(0.0) : ((cmd->throttle > OGK_R(1.0)) ? OGK_R(1.0) : cmd->throttle);
            if (cmd->throttle > OGK_R(0.0)) {
                cmd->flags = OGK_THRUST_FLAG_ENGINE_ON;
            } else {
                cmd->flags = 0u;
            }
            cmd->law_flags = ctx->plan_flags;
            if ((ctx->plan_flags & OGK_NMPC_FLAG_STALE) != 0u) {
                cmd->flags |= OGK_THRUST_FLAG_SAFE;
            }
            if (t > (ctx->plan.t0 + ctx->plan.horizon)) {
                cmd->law_flags |= OGK_NMPC_FLAG_END_OF_PLAN;
            }
        }
    }
    return st;
}

ogk_status ogk_nmpc_command(const ogk_nmpc_t *ctx, ogk_real_t t, ogk_nmpc_command_t *cmd)
{
    return nmpc_command(ctx, t, cmd);
}

ogk_status ogk_nmpc_thrust_cmd(const ogk_nmpc_t *ctx, ogk_real_t t, ogk_thrust_cmd_t *cmd)
{
    ogk_status st;
    if (cmd == NULL) {
        st = OGK_E_NULL;
    } else {
        ogk_nmpc_command_t nc;
        /* fills nc whatever the status (the safe command on a rejection) */
        st = nmpc_command(ctx, t, &nc);
        {
            /* thrust (cos alpha, sin alpha) along (r_hat, theta_hat) = (r, t) of r-t-n */
            const ogk_real_t u[3] = {OGK_COS(nc.alpha), OGK_SIN(nc.alpha), OGK_R(0.0)};
            ogk_i_thrust_cmd_unit(cmd, isfinite(nc.t) ? nc.t : OGK_R(0.0), OGK_FRAME_RTN, u, nc.throttle,
                                  nc.flags, nc.law_flags);
        }
    }
    return st;
}

ogk_status ogk_nmpc_model_rhs(const ogk_nmpc_t *ctx, ogk_real_t t, const ogk_real_t *x,
                              const ogk_real_t *u, ogk_real_t *xdot)
{
    ogk_status st = nmpc_check_ctx(ctx);
    if ((st == OGK_OK) && ((x == NULL) || (u == NULL) || (xdot == NULL))) {
        st = OGK_E_NULL;
    }
    if ((st == OGK_OK) && (!isfinite(t) || !ogk_i_all_finite(x, NX) || !ogk_i_all_finite(u, ctx->nu))) {
        st = OGK_E_NONFINITE;
    }
    if (st == OGK_OK) {
        const ogk_i_ocp_t ocp = ogk_i_nmpc_problem(ctx);
        st = ocp.ops->dynamics(ocp.data, ctx->nu, t, x, u, NULL, xdot, NULL, NULL, NULL);
    }
    return st;
}

ogk_status ogk_nmpc_interval(const ogk_nmpc_t *ctx, ogk_real_t t0, ogk_real_t h,
                             const ogk_real_t *x0, const ogk_real_t *u0,
                             const ogk_real_t *u1, ogk_real_t *x1, ogk_real_t *dfdx, /* NOLINT(bugprone-easily-swappable-parameters): order of the test header (ogk/internal/nmpc_test.h) and the bindings; every output is checked by central differences (test_nmpc.c) */
                             ogk_real_t *dfdu0, ogk_real_t *dfdu1, ogk_real_t *dfdh, /* NOLINT(bugprone-easily-swappable-parameters): as above */
                             ogk_real_t *dfdt0)
{
    ogk_status st = nmpc_check_ctx(ctx);
    ogk_real_t sens[OGK_NMPC_NX * OGK_I_NMPC_MAX_COLS];
    if ((st == OGK_OK) && ((x0 == NULL) || (u0 == NULL) || (u1 == NULL) || (x1 == NULL))) {
        st = OGK_E_NULL;
    }
    if ((st == OGK_OK) && (!isfinite(t0) || !isfinite(h) || !ogk_i_all_finite(x0, NX)
                           || !ogk_i_all_finite(u0, ctx->nu) || !ogk_i_all_finite(u1, ctx->nu))) {
        st = OGK_E_NONFINITE;
    }
    if ((st == OGK_OK) && !(h > OGK_R(0.0))) {
        st = OGK_E_RANGE;
    }
    if (st == OGK_OK) {
        const ogk_i_ocp_t ocp = ogk_i_nmpc_problem(ctx);
        st = ogk_i_nmpc_shoot(&ocp, ctx->nu, t0, h, x0, u0, u1, x1, sens, NULL);
    }
    if (st == OGK_OK) {
        const uint32_t nu = ctx->nu;
        const size_t col_h = NX + (2u * (size_t)nu);
        size_t i;
        size_t j;
        for (i = 0u; i < NX; ++i) {
            for (j = 0u; j < NX; ++j) {
                if (dfdx != NULL) {
                    dfdx[(i * NX) + j] = sens[(i * OGK_I_NMPC_MAX_COLS) + j];
                }
            }
            for (j = 0u; j < nu; ++j) {
                if (dfdu0 != NULL) {
                    dfdu0[(i * nu) + j] = sens[(i * OGK_I_NMPC_MAX_COLS) + NX + j];
                }
                if (dfdu1 != NULL) {
                    dfdu1[(i * nu) + j] = sens[(i * OGK_I_NMPC_MAX_COLS) + NX + nu + j];
                }
            }
            if (dfdh != NULL) {
                dfdh[i] = sens[(i * OGK_I_NMPC_MAX_COLS) + col_h];
            }
            if (dfdt0 != NULL) {
                dfdt0[i] = sens[(i * OGK_I_NMPC_MAX_COLS) + col_h + 1u];
            }
        }
    }
    return st;
}

ogk_status ogk_nmpc_interval_hess(ogk_nmpc_t *ctx, ogk_real_t t0, ogk_real_t h, /* NOLINT(bugprone-easily-swappable-parameters): order of the test header (ogk/internal/nmpc_test.h), as ogk_nmpc_interval; checked by central differences (test_nmpc.c) */
                                  const ogk_real_t *x0, const ogk_real_t *u0,
                                  const ogk_real_t *u1, const ogk_real_t *w,
                                  ogk_real_t *hess)
{
    ogk_status st = nmpc_check_ctx(ctx);
    if ((st == OGK_OK) && ((x0 == NULL) || (u0 == NULL) || (u1 == NULL) || (w == NULL) || (hess == NULL))) {
        st = OGK_E_NULL;
    }
    if ((st == OGK_OK) && (!isfinite(t0) || !isfinite(h) || !ogk_i_all_finite(x0, NX)
                           || !ogk_i_all_finite(u0, ctx->nu) || !ogk_i_all_finite(u1, ctx->nu)
                           || !ogk_i_all_finite(w, NX))) {
        st = OGK_E_NONFINITE;
    }
    if ((st == OGK_OK) && !(h > OGK_R(0.0))) {
        st = OGK_E_RANGE;
    }
    if (st == OGK_OK) {
        ogk_real_t sens[OGK_NMPC_NX * OGK_I_NMPC_MAX_COLS];
        ogk_real_t x1[OGK_NMPC_NX];
        const ogk_i_ocp_t ocp = ogk_i_nmpc_problem(ctx);
        st = ogk_i_nmpc_shoot(&ocp, ctx->nu, t0, h, x0, u0, u1, x1, sens, ctx->tape);
    }
    if (st == OGK_OK) {
        ogk_real_t w_int[OGK_I_NMPC_MAX_COLS * OGK_I_NMPC_MAX_COLS];
        const size_t nd = NX + (2u * (size_t)ctx->nu) + 2u;
        const ogk_i_ocp_t ocp = ogk_i_nmpc_problem(ctx);
        const size_t ncol = ogk_i_nmpc_ncol(&ocp, ctx->nu);
        size_t i;
        size_t j;
        ogk_i_nmpc_shoot_hess(&ocp, ctx->nu, t0, h, u0, u1, ctx->tape, w, w_int);
        for (i = 0u; i < nd; ++i) {
            for (j = 0u; j < nd; ++j) {
                /* the t0 column is not propagated for an autonomous model: its second derivatives are 0 */
                hess[(i * nd) + j] = ((i < ncol) && (j < ncol)) ? w_int[(i * OGK_I_NMPC_MAX_COLS) + j] : OGK_R(0.0);
            }
        }
    }
    return st;
}
