/* test_nmpc_edge_cases.c -- NMPC paths test_nmpc.c leaves unrun (make coverage, docs/evidence/coverage.md):
 *   - every init rejection, one configuration field at a time (NaN and Inf of every double, each
 *     range bound), and the context left unusable after each;
 *   - every bad input of every public function (NULL, not initialised, NaN/Inf, ranges), each with
 *     its specific code, the safe command where there is an output, and the context usable after;
 *   - the model's branches against closed forms: the throttle, the solar-electric eq. (14), a
 *     right-hand side that overflows, the spacecraft at a third body's centre;
 *   - solves with the solar-electric engine and two third bodies (a coast: zero fuel), with the
 *     sweep bound (every |alpha_{k+1} - alpha_k| within it, t_f no earlier than without it), an
 *     elastic QP (the target out of reach), a guess that leaves the model's domain;
 *   - the strategies: SNNS drop, the min_nodes regrid (to min_nodes and to the plan's own N), the
 *     doubling test adopting 2N (threshold 0) and not adopting it, the subdivision budget, a stale
 *     plan after a failure (with and without the doubling test), the plan stretched when t >= t_f;
 *   - the command before t0, after t_f, on a stale plan and with the engine off.
 * Runs on the host and on the Cortex-M7 (QEMU): one context, two plans. */
#include "ogk_test.h"

#include <float.h>
#include <string.h>

#include "nmpc_fixture.h"
#include "ogk/internal/nmpc_test.h" /* ogk_nmpc_model_rhs, ogk_nmpc_interval */
#include "ogk/nmpc.h"
#include "ogk/types.h"

#define NX OGK_NMPC_NX
#define PI 3.14159265358979323846

static ogk_nmpc_t ctx;
static ogk_nmpc_plan_t plan;
static ogk_nmpc_plan_t plan2;

/* The radial transfer of nmpc_fixture.h, 2 RK4 steps, no doubling test unless asked. */
static void radial_config(ogk_nmpc_config_t *c, uint32_t nodes)
{
    nmpc_fx_radial(c, nodes, 2u, 100u);
    c->min_nodes = 1u;
    c->doubling_max_nodes = 0u; /* no doubling test unless asked */
}

static void radial_guess(uint32_t nodes, double t_guess, ogk_nmpc_plan_t *p)
{
    nmpc_fx_radial_guess(nodes, t_guess, p);
}

static void input_at(ogk_real_t t, const ogk_real_t *x, ogk_nmpc_input_t *in)
{
    in->t = t;
    (void)memcpy(in->x, x, sizeof in->x);
}

/* Coast on the unit circle with the target on it (min fuel, throttled): the optimum burns nothing. */
static void coast_config(ogk_nmpc_config_t *c, uint32_t nodes)
{
    (void)ogk_nmpc_config_default(c);
    c->engine = OGK_NMPC_ENGINE_THROTTLED;
    c->objective = OGK_NMPC_MIN_FUEL;
    c->thrust_max = 0.05;
    c->mass_flow_max = 0.05;
    c->target_radius = 1.0;
    c->target_phase0 = 0.0;
    c->target_rate = 1.0;
    c->nodes = nodes;
    c->rk4_steps = 4u;
    c->horizon_min = 1.0;
    c->horizon_max = 2.0;
    c->max_iter = 100u;
    c->max_iter_cold = 100u;
    c->doubling_max_nodes = 0u;
#if OGK_REAL_SINGLE
    c->tol_feas = NMPC_FX_TOL_F; /* the default 1e-9 is below float's resolution (as nmpc_fx_mars) */
#endif
}

static void coast_guess(uint32_t nodes, double horizon, double w, ogk_nmpc_plan_t *p)
{
    uint32_t k;
    (void)memset(p, 0, sizeof *p);
    p->horizon = horizon;
    p->nodes = nodes;
    p->nu = 2u;
    for (k = 0u; k <= nodes; ++k) {
        const double t = horizon * (double)k / (double)nodes;
        p->x[k * NX + 0u] = 1.0;
        p->x[k * NX + 1u] = t;
        p->x[k * NX + 3u] = 1.0;
        p->x[k * NX + 4u] = 1.0;
        p->u[2u * k] = 1.0;
        p->u[2u * k + 1u] = w;
    }
}

/* ------------------------------------------------------------------ init */

typedef struct {
    const char *name;
    void (*apply)(ogk_nmpc_config_t *c);
    ogk_status expected;
} config_case_t;

#define BAD_RANGE(fn, body) static void fn(ogk_nmpc_config_t *c) { body; }
BAD_RANGE(mu_zero, c->mu = 0.0)
BAD_RANGE(radius_zero, c->target_radius = 0.0)
BAD_RANGE(engine_bad, c->engine = 2u)
BAD_RANGE(power_bad, c->power = 2u)
BAD_RANGE(objective_bad, c->objective = 2u)
BAD_RANGE(strategy_bad, c->strategy = 2u)
BAD_RANGE(nodes_zero, c->nodes = 0u)
BAD_RANGE(nodes_big, c->nodes = OGK_NMPC_MAX_NODES + 1u)
BAD_RANGE(rk4_zero, c->rk4_steps = 0u)
BAD_RANGE(rk4_big, c->rk4_steps = OGK_NMPC_MAX_RK4_STEPS + 1u)
BAD_RANGE(hmin_zero, c->horizon_min = 0.0)
BAD_RANGE(hmax_low, c->horizon_max = 0.5 * c->horizon_min)
BAD_RANGE(sweep_neg, c->max_sweep = OGK_TEST_PICK(-1.0e-300, -1.0e-30))
BAD_RANGE(iter_zero, c->max_iter = 0u)
BAD_RANGE(iter_big, c->max_iter = OGK_NMPC_MAX_SQP_ITER + 1u)
BAD_RANGE(iter_cold_zero, c->max_iter_cold = 0u)
BAD_RANGE(iter_cold_big, c->max_iter_cold = OGK_NMPC_MAX_SQP_ITER + 1u)
BAD_RANGE(keepout_neg, c->n_bodies = 2u; c->keepout_radius[1] = -1.0e-9)
BAD_RANGE(feas_zero, c->tol_feas = 0.0)
BAD_RANGE(stat_zero, c->tol_stat = 0.0)
BAD_RANGE(obj_neg, c->tol_obj = -1.0e-9)
BAD_RANGE(hess_zero, c->hessian_init = 0.0)
BAD_RANGE(hessian_bad, c->hessian = OGK_NMPC_HESSIAN_EXACT + 1u)
BAD_RANGE(step_alpha_zero, c->step_max_alpha = 0.0)
BAD_RANGE(step_h_zero, c->step_max_horizon = 0.0)
BAD_RANGE(elastic_zero, c->elastic_weight = 0.0)
BAD_RANGE(min_nodes_zero, c->min_nodes = 0u)
BAD_RANGE(min_nodes_big, c->min_nodes = OGK_NMPC_MAX_NODES + 1u)
BAD_RANGE(threshold_neg, c->doubling_threshold = -0.01)
BAD_RANGE(dbl_nodes_big, c->doubling_max_nodes = OGK_NMPC_MAX_NODES / 2u + 1u)
BAD_RANGE(bodies_big, c->n_bodies = OGK_NMPC_MAX_BODIES + 1u)
BAD_RANGE(solar_unit_zero, c->power = OGK_NMPC_POWER_SOLAR; c->solar_length_unit = 0.0)
BAD_RANGE(thrust_zero, c->thrust_max = 0.0)
BAD_RANGE(flow_neg, c->mass_flow_max = -1.0e-12)
BAD_RANGE(body0_mu_neg, c->n_bodies = 2u; c->body_mu[0] = -1.0e-9)
BAD_RANGE(body0_radius_zero, c->n_bodies = 2u; c->body_radius[0] = 0.0)
BAD_RANGE(body0_soft_neg, c->n_bodies = 2u; c->body_softening[0] = -1.0e-9)
BAD_RANGE(body1_mu_neg, c->n_bodies = 2u; c->body_mu[1] = -1.0e-9)
BAD_RANGE(body1_radius_zero, c->n_bodies = 2u; c->body_radius[1] = 0.0)
BAD_RANGE(body1_soft_neg, c->n_bodies = 2u; c->body_softening[1] = -1.0e-9)
BAD_RANGE(release0_neg, c->n_bodies = 2u; c->body_release[0] = -1.0e-9)
BAD_RANGE(release1_neg, c->n_bodies = 2u; c->body_release[1] = -1.0e-9)
BAD_RANGE(mass_min_neg, c->mass_min = -1.0e-12)
BAD_RANGE(box0_neg, c->terminal_box[0] = -1.0e-12)
BAD_RANGE(box1_neg, c->terminal_box[1] = -1.0e-12)
BAD_RANGE(box2_neg, c->terminal_box[2] = -1.0e-12)
BAD_RANGE(box3_neg, c->terminal_box[3] = -1.0e-12)

static const config_case_t range_cases[] = {
    { "mu", mu_zero, OGK_E_CONFIG },
    { "hessian", hessian_bad, OGK_E_CONFIG },
    { "target_radius", radius_zero, OGK_E_CONFIG },
    { "engine", engine_bad, OGK_E_CONFIG },
    { "power", power_bad, OGK_E_CONFIG },
    { "objective", objective_bad, OGK_E_CONFIG },
    { "strategy", strategy_bad, OGK_E_CONFIG },
    { "nodes 0", nodes_zero, OGK_E_CONFIG },
    { "nodes max+1", nodes_big, OGK_E_CONFIG },
    { "rk4_steps 0", rk4_zero, OGK_E_CONFIG },
    { "rk4_steps max+1", rk4_big, OGK_E_CONFIG },
    { "horizon_min", hmin_zero, OGK_E_CONFIG },
    { "horizon_max", hmax_low, OGK_E_CONFIG },
    { "max_sweep", sweep_neg, OGK_E_CONFIG },
    { "max_iter 0", iter_zero, OGK_E_CONFIG },
    { "max_iter max+1", iter_big, OGK_E_CONFIG },
    { "max_iter_cold 0", iter_cold_zero, OGK_E_CONFIG },
    { "max_iter_cold max+1", iter_cold_big, OGK_E_CONFIG },
    { "keepout_radius[1]", keepout_neg, OGK_E_CONFIG },
    { "tol_feas", feas_zero, OGK_E_CONFIG },
    { "tol_stat", stat_zero, OGK_E_CONFIG },
    { "tol_obj", obj_neg, OGK_E_CONFIG },
    { "hessian_init", hess_zero, OGK_E_CONFIG },
    { "step_max_alpha", step_alpha_zero, OGK_E_CONFIG },
    { "step_max_horizon", step_h_zero, OGK_E_CONFIG },
    { "elastic_weight", elastic_zero, OGK_E_CONFIG },
    { "min_nodes 0", min_nodes_zero, OGK_E_CONFIG },
    { "min_nodes max+1", min_nodes_big, OGK_E_CONFIG },
    { "doubling_threshold", threshold_neg, OGK_E_CONFIG },
    { "doubling_max_nodes", dbl_nodes_big, OGK_E_CONFIG },
    { "n_bodies", bodies_big, OGK_E_CONFIG },
    { "solar_length_unit", solar_unit_zero, OGK_E_CONFIG },
    { "thrust_max", thrust_zero, OGK_E_CONFIG },
    { "mass_flow_max", flow_neg, OGK_E_CONFIG },
    { "body_mu[0]", body0_mu_neg, OGK_E_CONFIG },
    { "body_radius[0]", body0_radius_zero, OGK_E_CONFIG },
    { "body_softening[0]", body0_soft_neg, OGK_E_CONFIG },
    { "body_mu[1]", body1_mu_neg, OGK_E_CONFIG },
    { "body_radius[1]", body1_radius_zero, OGK_E_CONFIG },
    { "body_softening[1]", body1_soft_neg, OGK_E_CONFIG },
    { "body_release[0]", release0_neg, OGK_E_CONFIG },
    { "body_release[1]", release1_neg, OGK_E_CONFIG },
    { "mass_min", mass_min_neg, OGK_E_CONFIG },
    { "terminal_box[0]", box0_neg, OGK_E_CONFIG },
    { "terminal_box[1]", box1_neg, OGK_E_CONFIG },
    { "terminal_box[2]", box2_neg, OGK_E_CONFIG },
    { "terminal_box[3]", box3_neg, OGK_E_CONFIG },
};

/* A valid configuration with two bodies, so that the per-body checks are reached. */
static void valid_config(ogk_nmpc_config_t *c)
{
    radial_config(c, 4u);
    c->body_radius[0] = 1.0;
    c->body_radius[1] = 1.5;
}

static void check_rejected(const ogk_nmpc_config_t *c, ogk_status expected, const char *what)
{
    ogk_nmpc_config_t good;
    valid_config(&good);
    OGK_ASSERT_STATUS(ogk_nmpc_init(&ctx, &good), OGK_OK);
    if (ogk_nmpc_init(&ctx, c) != expected) {
        print_error("init with bad %s: not rejected with %d\n", what, (int)expected);
        fail();
    }
    /* a rejected init after a good one leaves the context unusable */
    OGK_ASSERT_STATUS(ogk_nmpc_reset(&ctx), OGK_E_NOT_INIT);
    OGK_ASSERT_STATUS(ogk_nmpc_load_plan(&ctx, &plan), OGK_E_NOT_INIT);
}

/* req: OGK-NMPC-008 */
static void test_init_rejects_every_field(void **state)
{
    ogk_nmpc_config_t c;
    size_t i;
    (void)state;
    valid_config(&c);
    OGK_ASSERT_STATUS(ogk_nmpc_init(&ctx, &c), OGK_OK);
    radial_guess(4u, 5.0, &plan);
    for (i = 0u; i < sizeof range_cases / sizeof range_cases[0]; ++i) {
        valid_config(&c);
        range_cases[i].apply(&c);
        check_rejected(&c, range_cases[i].expected, range_cases[i].name);
    }
    /* every double of the configuration, NaN and then Inf (the per-body arrays whatever n_bodies) */
    {
        ogk_real_t *fields[64];
        size_t n = 0u;
        size_t b;
        ogk_nmpc_config_t *p = &c;
        const double bad[2] = { NAN, -INFINITY };
        size_t v;
        valid_config(&c);
        fields[n++] = &p->mu;
        fields[n++] = &p->thrust_max;
        fields[n++] = &p->mass_flow_max;
        fields[n++] = &p->solar_length_unit;
        for (b = 0u; b < 4u; ++b) {
            fields[n++] = &p->solar_a[b];
        }
        for (b = 0u; b < 2u; ++b) {
            fields[n++] = &p->solar_thrust[b];
            fields[n++] = &p->solar_flow[b];
        }
        for (b = 0u; b < OGK_NMPC_MAX_BODIES; ++b) {
            fields[n++] = &p->body_mu[b];
            fields[n++] = &p->body_radius[b];
            fields[n++] = &p->body_phase0[b];
            fields[n++] = &p->body_rate[b];
            fields[n++] = &p->body_softening[b];
            fields[n++] = &p->keepout_radius[b];
            fields[n++] = &p->body_release[b];
        }
        for (b = 0u; b < OGK_NMPC_NC; ++b) {
            fields[n++] = &p->terminal_box[b];
        }
        fields[n++] = &p->mass_min;
        fields[n++] = &p->target_radius;
        fields[n++] = &p->target_phase0;
        fields[n++] = &p->target_rate;
        fields[n++] = &p->horizon_min;
        fields[n++] = &p->horizon_max;
        fields[n++] = &p->max_sweep;
        fields[n++] = &p->tol_feas;
        fields[n++] = &p->tol_stat;
        fields[n++] = &p->tol_obj;
        fields[n++] = &p->hessian_init;
        fields[n++] = &p->step_max_alpha;
        fields[n++] = &p->step_max_horizon;
        fields[n++] = &p->elastic_weight;
        fields[n++] = &p->doubling_threshold;
        for (i = 0u; i < n; ++i) {
            for (v = 0u; v < 2u; ++v) {
                const double keep = *fields[i];
                *fields[i] = bad[v];
                check_rejected(&c, OGK_E_NONFINITE, "double (NaN/Inf)");
                *fields[i] = keep;
            }
        }
        OGK_ASSERT_STATUS(ogk_nmpc_init(&ctx, &c), OGK_OK);
    }
    /* accepted: the solar-electric engine needs no thrust_max; a zero mass flow; no bodies with
     * garbage (finite) body fields; tol_obj 0 */
    valid_config(&c);
    c.power = OGK_NMPC_POWER_SOLAR;
    c.thrust_max = 0.0;
    c.mass_flow_max = -1.0;
    OGK_ASSERT_STATUS(ogk_nmpc_init(&ctx, &c), OGK_OK);
    valid_config(&c);
    c.mass_flow_max = 0.0;
    c.n_bodies = 0u;
    c.body_radius[0] = -1.0;
    c.tol_obj = 0.0;
    c.doubling_max_nodes = OGK_NMPC_MAX_NODES / 2u;
    OGK_ASSERT_STATUS(ogk_nmpc_init(&ctx, &c), OGK_OK);
}

/* ------------------------------------------------------------------ bad inputs */

static void assert_safe(const ogk_nmpc_command_t *cmd, double t)
{
    assert_int_equal((int)cmd->flags, (int)OGK_THRUST_FLAG_SAFE);
    OGK_ASSERT_NEAR(cmd->throttle, 0.0, 0.0);
    OGK_ASSERT_NEAR(cmd->alpha, 0.0, 0.0);
    assert_int_equal((int)cmd->law_flags, 0);
    if (isfinite(t)) {
        OGK_ASSERT_NEAR(cmd->t, t, 0.0);
    }
}

/* req: OGK-NMPC-008 */
static void test_bad_inputs_every_function(void **state)
{
    static ogk_nmpc_t zeroed; /* never initialised */
    ogk_nmpc_config_t c;
    ogk_nmpc_input_t in;
    ogk_nmpc_report_t rep;
    ogk_nmpc_command_t cmd;
    const ogk_real_t x[NX] = { 1.2, 0.3, 0.05, 0.9, 0.8 };
    const ogk_real_t u[2] = { 0.7, 0.5 };
    ogk_real_t xdot[NX];
    ogk_real_t x1[NX];
    ogk_real_t x1_ref[NX];
    ogk_real_t fx[NX * NX];
    ogk_real_t fx_ref[NX * NX];
    ogk_real_t fu0[NX * 2];
    ogk_real_t fu1[NX * 2];
    ogk_real_t fh[NX];
    ogk_real_t ft[NX];
    ogk_real_t fu1_ref[NX * 2];
    size_t i;
    (void)state;
    radial_config(&c, 4u);
    OGK_ASSERT_STATUS(ogk_nmpc_init(&ctx, &c), OGK_OK);

    /* reset */
    OGK_ASSERT_STATUS(ogk_nmpc_reset(NULL), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_nmpc_reset(&zeroed), OGK_E_NOT_INIT);

    /* before any plan: get_plan, solve, replan and command say OGK_E_RANGE */
    OGK_ASSERT_STATUS(ogk_nmpc_get_plan(&ctx, &plan2), OGK_E_RANGE);
    input_at(0.0, x, &in);
    OGK_ASSERT_STATUS(ogk_nmpc_solve(&ctx, &in, &rep), OGK_E_RANGE);
    OGK_ASSERT_STATUS(ogk_nmpc_replan(&ctx, &in, &rep), OGK_E_RANGE);
    OGK_ASSERT_STATUS(ogk_nmpc_command(&ctx, 0.5, &cmd), OGK_E_RANGE);
    assert_safe(&cmd, 0.5);

    /* load_plan */
    radial_guess(4u, 5.0, &plan);
    OGK_ASSERT_STATUS(ogk_nmpc_load_plan(NULL, &plan), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_nmpc_load_plan(&zeroed, &plan), OGK_E_NOT_INIT);
    OGK_ASSERT_STATUS(ogk_nmpc_load_plan(&ctx, NULL), OGK_E_NULL);
    plan2 = plan;
    plan2.nodes = OGK_NMPC_MAX_NODES + 1u;
    OGK_ASSERT_STATUS(ogk_nmpc_load_plan(&ctx, &plan2), OGK_E_DIM);
    plan2 = plan;
    plan2.t0 = NAN;
    OGK_ASSERT_STATUS(ogk_nmpc_load_plan(&ctx, &plan2), OGK_E_NONFINITE);
    plan2 = plan;
    plan2.horizon = INFINITY;
    OGK_ASSERT_STATUS(ogk_nmpc_load_plan(&ctx, &plan2), OGK_E_NONFINITE);
    plan2 = plan;
    plan2.x[4u * NX + 4u] = NAN; /* last node */
    OGK_ASSERT_STATUS(ogk_nmpc_load_plan(&ctx, &plan2), OGK_E_NONFINITE);
    plan2 = plan;
    plan2.lambda[3] = -INFINITY;
    OGK_ASSERT_STATUS(ogk_nmpc_load_plan(&ctx, &plan2), OGK_E_NONFINITE);
    plan2 = plan;
    plan2.horizon = 0.5 * c.horizon_min;
    OGK_ASSERT_STATUS(ogk_nmpc_load_plan(&ctx, &plan2), OGK_E_RANGE);
    plan2 = plan;
    plan2.x[2u * NX + 0u] = 0.0; /* r = 0 at node 2 */
    OGK_ASSERT_STATUS(ogk_nmpc_load_plan(&ctx, &plan2), OGK_E_RANGE);
    plan2 = plan;
    plan2.x[4u * NX + 4u] = -1.0; /* m < 0 at the last node */
    OGK_ASSERT_STATUS(ogk_nmpc_load_plan(&ctx, &plan2), OGK_E_RANGE);
    plan2 = plan;
    plan2.x[4u * NX + 4u] = 0.0; /* m = 0 */
    OGK_ASSERT_STATUS(ogk_nmpc_load_plan(&ctx, &plan2), OGK_E_RANGE);
    /* nothing was loaded by the rejected calls */
    OGK_ASSERT_STATUS(ogk_nmpc_get_plan(&ctx, &plan2), OGK_E_RANGE);
    OGK_ASSERT_STATUS(ogk_nmpc_load_plan(&ctx, &plan), OGK_OK);

    /* get_plan */
    OGK_ASSERT_STATUS(ogk_nmpc_get_plan(NULL, &plan2), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_nmpc_get_plan(&zeroed, &plan2), OGK_E_NOT_INIT);
    OGK_ASSERT_STATUS(ogk_nmpc_get_plan(&ctx, NULL), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_nmpc_get_plan(&ctx, &plan2), OGK_OK);
    assert_true(memcmp(&plan, &plan2, sizeof plan) == 0);

    /* solve and replan: NULL, not initialised, non-finite, outside the model's domain */
    input_at(0.0, plan.x, &in);
    OGK_ASSERT_STATUS(ogk_nmpc_solve(NULL, &in, &rep), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_nmpc_solve(&zeroed, &in, &rep), OGK_E_NOT_INIT);
    OGK_ASSERT_STATUS(ogk_nmpc_solve(&ctx, NULL, &rep), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_nmpc_solve(&ctx, &in, NULL), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_nmpc_replan(&ctx, &in, NULL), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_nmpc_replan(&zeroed, &in, &rep), OGK_E_NOT_INIT);
    in.t = INFINITY;
    OGK_ASSERT_STATUS(ogk_nmpc_solve(&ctx, &in, &rep), OGK_E_NONFINITE);
    OGK_ASSERT_STATUS(ogk_nmpc_replan(&ctx, &in, &rep), OGK_E_NONFINITE);
    in.t = 0.0;
    in.x[1] = NAN;
    OGK_ASSERT_STATUS(ogk_nmpc_solve(&ctx, &in, &rep), OGK_E_NONFINITE);
    assert_int_equal((int)rep.flags, 0); /* the report is zeroed, not left stale */
    in.x[1] = 0.0;
    in.x[0] = 0.0;
    OGK_ASSERT_STATUS(ogk_nmpc_solve(&ctx, &in, &rep), OGK_E_RANGE);
    in.x[0] = -1.0;
    OGK_ASSERT_STATUS(ogk_nmpc_replan(&ctx, &in, &rep), OGK_E_RANGE);
    in.x[0] = 1.0;
    in.x[4] = 0.0;
    OGK_ASSERT_STATUS(ogk_nmpc_solve(&ctx, &in, &rep), OGK_E_RANGE);
    /* the plan was not touched */
    OGK_ASSERT_STATUS(ogk_nmpc_get_plan(&ctx, &plan2), OGK_OK);
    assert_true(memcmp(&plan, &plan2, sizeof plan) == 0);

    /* command: the safe command whenever cmd is usable */
    OGK_ASSERT_STATUS(ogk_nmpc_command(NULL, 0.5, &cmd), OGK_E_NULL);
    assert_safe(&cmd, 0.5);
    OGK_ASSERT_STATUS(ogk_nmpc_command(&zeroed, 0.5, &cmd), OGK_E_NOT_INIT);
    assert_safe(&cmd, 0.5);
    OGK_ASSERT_STATUS(ogk_nmpc_command(NULL, 0.5, NULL), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_nmpc_command(&ctx, 0.5, NULL), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_nmpc_command(&ctx, INFINITY, &cmd), OGK_E_NONFINITE);
    assert_safe(&cmd, INFINITY);
    OGK_ASSERT_STATUS(ogk_nmpc_command(&ctx, NAN, &cmd), OGK_E_NONFINITE);
    assert_safe(&cmd, NAN);
    /* ... and the context still gives the plan's command */
    OGK_ASSERT_STATUS(ogk_nmpc_command(&ctx, 0.0, &cmd), OGK_OK);
    OGK_ASSERT_NEAR(cmd.alpha, plan.u[0], 0.0);

    /* model_rhs (constant engine: one control) */
    OGK_ASSERT_STATUS(ogk_nmpc_model_rhs(NULL, 0.0, x, u, xdot), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_nmpc_model_rhs(&zeroed, 0.0, x, u, xdot), OGK_E_NOT_INIT);
    OGK_ASSERT_STATUS(ogk_nmpc_model_rhs(&ctx, 0.0, NULL, u, xdot), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_nmpc_model_rhs(&ctx, 0.0, x, NULL, xdot), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_nmpc_model_rhs(&ctx, 0.0, x, u, NULL), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_nmpc_model_rhs(&ctx, NAN, x, u, xdot), OGK_E_NONFINITE);
    {
        ogk_real_t xb[NX];
        ogk_real_t ub[1] = { NAN };
        (void)memcpy(xb, x, sizeof xb);
        xb[4] = 0.0; /* m = 0 */
        OGK_ASSERT_STATUS(ogk_nmpc_model_rhs(&ctx, 0.0, xb, u, xdot), OGK_E_NONFINITE);
        xb[4] = 0.8;
        xb[3] = INFINITY;
        OGK_ASSERT_STATUS(ogk_nmpc_model_rhs(&ctx, 0.0, xb, u, xdot), OGK_E_NONFINITE);
        OGK_ASSERT_STATUS(ogk_nmpc_model_rhs(&ctx, 0.0, x, ub, xdot), OGK_E_NONFINITE);
    }
    OGK_ASSERT_STATUS(ogk_nmpc_model_rhs(&ctx, 0.0, x, u, xdot), OGK_OK);

    /* interval: NULL inputs, non-finite or non-positive times, a state outside the domain */
    OGK_ASSERT_STATUS(ogk_nmpc_interval(NULL, 0.0, 0.1, x, u, u, x1, NULL, NULL, NULL, NULL, NULL), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_nmpc_interval(&zeroed, 0.0, 0.1, x, u, u, x1, NULL, NULL, NULL, NULL, NULL), OGK_E_NOT_INIT);
    OGK_ASSERT_STATUS(ogk_nmpc_interval(&ctx, 0.0, 0.1, NULL, u, u, x1, NULL, NULL, NULL, NULL, NULL), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_nmpc_interval(&ctx, 0.0, 0.1, x, NULL, u, x1, NULL, NULL, NULL, NULL, NULL), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_nmpc_interval(&ctx, 0.0, 0.1, x, u, NULL, x1, NULL, NULL, NULL, NULL, NULL), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_nmpc_interval(&ctx, 0.0, 0.1, x, u, u, NULL, NULL, NULL, NULL, NULL, NULL), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_nmpc_interval(&ctx, NAN, 0.1, x, u, u, x1, NULL, NULL, NULL, NULL, NULL), OGK_E_NONFINITE);
    OGK_ASSERT_STATUS(ogk_nmpc_interval(&ctx, 0.0, INFINITY, x, u, u, x1, NULL, NULL, NULL, NULL, NULL), OGK_E_NONFINITE);
    OGK_ASSERT_STATUS(ogk_nmpc_interval(&ctx, 0.0, 0.0, x, u, u, x1, NULL, NULL, NULL, NULL, NULL), OGK_E_RANGE);
    OGK_ASSERT_STATUS(ogk_nmpc_interval(&ctx, 0.0, -0.1, x, u, u, x1, NULL, NULL, NULL, NULL, NULL), OGK_E_RANGE);
    {
        /* falling through the centre within the interval: the state leaves the domain */
        const ogk_real_t fall[NX] = { 0.01, 0.0, -10.0, 0.0, 1.0 };
        OGK_ASSERT_STATUS(ogk_nmpc_interval(&ctx, 0.0, 0.1, fall, u, u, x1, fx, NULL, NULL, NULL, NULL), OGK_E_NONFINITE);
    }
    /* the optional outputs: any subset gives the same numbers as all of them */
    c.engine = OGK_NMPC_ENGINE_THROTTLED;
    c.mass_flow_max = 0.02;
    OGK_ASSERT_STATUS(ogk_nmpc_init(&ctx, &c), OGK_OK);
    OGK_ASSERT_STATUS(ogk_nmpc_interval(&ctx, 0.2, 0.3, x, u, u, x1_ref, fx_ref, fu0, fu1_ref, fh, ft), OGK_OK);
    OGK_ASSERT_STATUS(ogk_nmpc_interval(&ctx, 0.2, 0.3, x, u, u, x1, NULL, NULL, NULL, NULL, NULL), OGK_OK);
    assert_true(memcmp(x1, x1_ref, sizeof x1) == 0);
    OGK_ASSERT_STATUS(ogk_nmpc_interval(&ctx, 0.2, 0.3, x, u, u, x1, fx, NULL, fu1, NULL, NULL), OGK_OK);
    assert_true(memcmp(fx, fx_ref, sizeof fx) == 0);
    assert_true(memcmp(fu1, fu1_ref, sizeof fu1) == 0);
    /* d x1 / d h is xdot at the end for a constant control; m' = -w mdot_max exactly */
    for (i = 0u; i < NX; ++i) {
        assert_true(isfinite(fh[i]) && isfinite(ft[i]));
    }
    OGK_ASSERT_NEAR(fh[4], -u[1] * c.mass_flow_max, 1e-15);
    /* float: measured worst 2.1e-8 on M4F and host */
    OGK_ASSERT_NEAR(x1_ref[4], x[4] - 0.3 * u[1] * c.mass_flow_max, OGK_TEST_TOL(1e-15, 5e-7));
}

/* ------------------------------------------------------------------ model branches */

/* req: OGK-NMPC-001 */
static void test_model_throttle_solar_overflow_and_body_centre(void **state)
{
    ogk_nmpc_config_t c;
    const ogk_real_t x[NX] = { 1.3, 0.2, 0.01, 0.85, 0.9 };
    const ogk_real_t u[2] = { 0.4, 0.25 };
    ogk_real_t xdot[NX];
    (void)state;
    /* throttled, constant power: acc = w T / m, m' = -w mdot_max */
    radial_config(&c, 4u);
    c.mu = 1.0;
    c.engine = OGK_NMPC_ENGINE_THROTTLED;
    c.mass_flow_max = 0.03;
    OGK_ASSERT_STATUS(ogk_nmpc_init(&ctx, &c), OGK_OK);
    OGK_ASSERT_STATUS(ogk_nmpc_model_rhs(&ctx, 0.0, x, u, xdot), OGK_OK);
    /* float: measured worst 2e-8 on M4F and host */
    OGK_ASSERT_NEAR(xdot[2], 0.85 * 0.85 / 1.3 - 1.0 / (1.3 * 1.3) + 0.25 * 0.1 / 0.9 * cos(0.4), OGK_TEST_TOL(1e-15, 5e-7));
    /* float: measured worst 1.3e-10 on M4F and host */
    OGK_ASSERT_NEAR(xdot[3], -0.85 * 0.01 / 1.3 + 0.25 * 0.1 / 0.9 * sin(0.4), OGK_TEST_TOL(1e-15, 2e-9));
    /* float: measured worst 1.7e-10 on M4F and host */
    OGK_ASSERT_NEAR(xdot[4], -0.25 * 0.03, OGK_TEST_TOL(1e-17, 2e-9));

    /* solar-electric, eq. (14): p(s) = (a1 s^2 + a2 s + a3) / (s^4 (1 + a4 s)), s = r / unit */
    nmpc_fx_solar(&c, 1.1, 0.04);
    OGK_ASSERT_STATUS(ogk_nmpc_init(&ctx, &c), OGK_OK);
    OGK_ASSERT_STATUS(ogk_nmpc_model_rhs(&ctx, 0.0, x, u, xdot), OGK_OK);
    {
        const double s = 1.3 / 1.1;
        const double p = (1.1063 * s * s + 0.1495 * s - 0.299) / (pow(s, 4.0) * (1.0 - 0.0423 * s));
        const double thrust = -2.0e-4 + 0.05 * p;
        const double flow = 5.0e-3 + 0.04 * p;
        /* float: measured worst relative 7.8e-8 on M4F and host */
        OGK_ASSERT_REL(xdot[4], -0.25 * flow, OGK_TEST_TOL(1e-14, 1e-6), 1e-300);
        /* float: measured worst relative 1.6e-7 on M4F and host */
        OGK_ASSERT_REL(xdot[3], -0.85 * 0.01 / 1.3 + 0.25 * thrust / 0.9 * sin(0.4), OGK_TEST_TOL(1e-13, 2e-6), 1e-300);
        assert_true(p > 0.3 && p < 1.0); /* a real power law, not a vacuous zero */
    }

    /* a right-hand side that overflows: OGK_E_NONFINITE, not an infinite xdot */
    radial_config(&c, 4u);
    c.thrust_max = OGK_TEST_PICK(1.0e300, 1.0e30); /* float: T / m = 1e60 overflows as well */
    OGK_ASSERT_STATUS(ogk_nmpc_init(&ctx, &c), OGK_OK);
    {
        const ogk_real_t tiny_m[NX] = { 1.0, 0.0, 0.0, 1.0, OGK_TEST_PICK(1.0e-300, 1.0e-30) };
        const ogk_real_t u1[1] = { 0.0 };
        OGK_ASSERT_STATUS(ogk_nmpc_model_rhs(&ctx, 0.0, tiny_m, u1, xdot), OGK_E_NONFINITE);
    }

    /* the spacecraft at a point-mass body's centre (softening 0): OGK_E_NONFINITE; with a
     * softening length the same point is regular and the body's own pull vanishes there (only
     * the indirect term -mu_b r_b / R^3 is left: along -r_hat here) */
    radial_config(&c, 4u);
    c.mu = 1.0;
    c.n_bodies = 1u;
    c.body_mu[0] = 1.0e-3;
    c.body_radius[0] = 1.3;
    c.body_phase0[0] = 0.2;
    c.body_rate[0] = 0.0;
    OGK_ASSERT_STATUS(ogk_nmpc_init(&ctx, &c), OGK_OK);
    {
        const ogk_real_t u1[1] = { 0.0 };
        ogk_real_t xdot_free[NX];
        OGK_ASSERT_STATUS(ogk_nmpc_model_rhs(&ctx, 0.0, x, u1, xdot), OGK_E_NONFINITE);
        c.body_softening[0] = 0.01;
        OGK_ASSERT_STATUS(ogk_nmpc_init(&ctx, &c), OGK_OK);
        OGK_ASSERT_STATUS(ogk_nmpc_model_rhs(&ctx, 0.0, x, u1, xdot), OGK_OK);
        c.n_bodies = 0u;
        OGK_ASSERT_STATUS(ogk_nmpc_init(&ctx, &c), OGK_OK);
        OGK_ASSERT_STATUS(ogk_nmpc_model_rhs(&ctx, 0.0, x, u1, xdot_free), OGK_OK);
        /* float: measured worst 1.7e-9 on M4F and host */
        OGK_ASSERT_NEAR(xdot[2] - xdot_free[2], -1.0e-3 / (1.3 * 1.3), OGK_TEST_TOL(1e-15, 2e-8));
        OGK_ASSERT_NEAR(xdot[3] - xdot_free[3], 0.0, 1e-15);
    }
}

/* ------------------------------------------------------------------ solves */

/* Solar-electric engine and two third bodies inside a solve: a coast on the target's own orbit
 * is still the minimum-fuel solution up to the bodies' pull, which is tiny here. With both
 * Hessians (the exact one, with a throttle, goes on BFGS at its first non-convex iteration; the
 * BFGS path's first QP is elastic there, the flag says so). */
static void solve_solar_engine_and_bodies(uint32_t hessian)
{
    ogk_nmpc_config_t c;
    ogk_nmpc_input_t in;
    ogk_nmpc_report_t rep;
    uint32_t k;
    coast_config(&c, 4u);
    c.hessian = hessian;
    nmpc_fx_solar(&c, 1.0, 0.05);
    c.n_bodies = 2u;
    nmpc_fx_body(&c, 0u, 1.0e-10, 3.0, 0.0, 0.2);
    nmpc_fx_body(&c, 1u, 1.0e-10, 4.0, 2.0, 0.1);
    c.body_softening[1] = 0.01;
    OGK_ASSERT_STATUS(ogk_nmpc_init(&ctx, &c), OGK_OK);
    coast_guess(4u, 1.5, 0.3, &plan);
    OGK_ASSERT_STATUS(ogk_nmpc_load_plan(&ctx, &plan), OGK_OK);
    input_at(0.0, plan.x, &in);
    OGK_ASSERT_STATUS(ogk_nmpc_solve(&ctx, &in, &rep), OGK_OK);
    assert_int_equal((int)(rep.flags & ~(uint32_t)OGK_NMPC_FLAG_ELASTIC), (int)OGK_NMPC_FLAG_CONVERGED);
    assert_true(rep.feas <= c.tol_feas);
    /* the bodies' pull (1e-10 at 2-3 LU) needs a burn of that order, no more */
    /* float: the fuel m_0 - m_N of masses near 1 is resolved to NMPC_FX_TOL_F (the mass defects'
     * tolerance), a node's throttle to that over mass_flow_max T / (2 nodes) (as test_nmpc.c's coast) */
    assert_true(rep.objective >= -OGK_TEST_TOL(1.0e-12, NMPC_FX_TOL_F));
    assert_true(rep.objective <= OGK_TEST_TOL(1.0e-7, NMPC_FX_TOL_F));
    OGK_ASSERT_STATUS(ogk_nmpc_get_plan(&ctx, &plan2), OGK_OK);
    for (k = 0u; k <= 4u; ++k) {
        assert_true(plan2.u[2u * k + 1u] >= 0.0
                    && plan2.u[2u * k + 1u] <= OGK_TEST_TOL(1.0e-4, NMPC_FX_TOL_F * 8.0 / (c.mass_flow_max * rep.t_f)));
    }
    OGK_ASSERT_NEAR(rep.objective, plan2.x[4] - plan2.x[4u * NX + 4u], 0.0);
}

/* req: OGK-NMPC-001 OGK-NMPC-003 */
static void test_solve_solar_engine_and_bodies(void **state)
{
    (void)state;
    solve_solar_engine_and_bodies(OGK_NMPC_HESSIAN_BFGS);
    solve_solar_engine_and_bodies(OGK_NMPC_HESSIAN_EXACT);
}

/* The sweep bound: no |alpha_{k+1} - alpha_k| above max_sweep, and t_f no earlier than the
 * unconstrained optimum (a constraint cannot shorten a minimum-time transfer). */
/* req: OGK-NMPC-007 */
static void test_solve_sweep_bound(void **state)
{
    ogk_nmpc_config_t c;
    ogk_nmpc_input_t in;
    ogk_nmpc_report_t rep;
    double t_free;
    const double sweep = 1.5;
    uint32_t k;
    (void)state;
    radial_config(&c, 6u);
    OGK_ASSERT_STATUS(ogk_nmpc_init(&ctx, &c), OGK_OK);
    radial_guess(6u, 5.0, &plan);
    OGK_ASSERT_STATUS(ogk_nmpc_load_plan(&ctx, &plan), OGK_OK);
    input_at(0.0, plan.x, &in);
    OGK_ASSERT_STATUS(ogk_nmpc_solve(&ctx, &in, &rep), OGK_OK);
    t_free = rep.t_f;

    c.max_sweep = sweep;
    OGK_ASSERT_STATUS(ogk_nmpc_init(&ctx, &c), OGK_OK);
    /* a guess that already satisfies the bound: alpha ramps from 0 to pi */
    for (k = 0u; k <= 6u; ++k) {
        plan.u[k] = PI * (double)k / 6.0;
    }
    OGK_ASSERT_STATUS(ogk_nmpc_load_plan(&ctx, &plan), OGK_OK);
    OGK_ASSERT_STATUS(ogk_nmpc_solve(&ctx, &in, &rep), OGK_OK);
    assert_true(rep.feas <= c.tol_feas);
    OGK_ASSERT_STATUS(ogk_nmpc_get_plan(&ctx, &plan2), OGK_OK);
    for (k = 0u; k < 6u; ++k) {
        /* float: a linear row of the SQP, held to its feasibility tolerance (NMPC_FX_TOL_F) */
        OGK_ASSERT_LE(fabs(plan2.u[k + 1u] - plan2.u[k]), sweep + OGK_TEST_TOL(1.0e-9, NMPC_FX_TOL_F));
    }
    assert_true(rep.t_f >= t_free * (1.0 - 1.0e-9));
    print_message("sweep bound %.2f rad: t_f %.6f (free %.6f)\n", sweep, rep.t_f, t_free);
}

/* The target out of reach (thrust too weak for the fixed horizon): every QP is infeasible, with
 * the step box opened too, so the elastic QP runs; the solve fails and the previous plan flies.
 * With a terminal set the same target is priced, not required (its rows always elastic): the solve
 * converges outside the set (OUTSIDE_SET), as close to it as the engine allows. */
/* req: OGK-NMPC-006 OGK-NMPC-013 */
static void test_solve_elastic_qp(void **state)
{
    ogk_nmpc_config_t c;
    ogk_nmpc_input_t in;
    ogk_nmpc_report_t rep;
    ogk_nmpc_command_t cmd;
    int pass;
    double miss_exact = 0.0;
    (void)state;
    for (pass = 0; pass < 3; ++pass) {
        ogk_status st;
        coast_config(&c, 3u);
        c.thrust_max = 1.0e-3;
        c.target_radius = 1.5;
        c.horizon_min = 1.0;
        c.horizon_max = 1.0 + 1.0e-6;
        c.max_iter = (pass == 2) ? 200u : 3u;
        c.max_iter_cold = c.max_iter;
        c.max_sweep = (pass == 1) ? 0.5 : 0.0; /* with and without inequality rows */
        if (pass == 2) {
            c.terminal_box[0] = 1.0e-3;
            c.terminal_box[2] = 1.0e-3;
        }
        OGK_ASSERT_STATUS(ogk_nmpc_init(&ctx, &c), OGK_OK);
        coast_guess(3u, 1.0, 0.5, &plan);
        OGK_ASSERT_STATUS(ogk_nmpc_load_plan(&ctx, &plan), OGK_OK);
        input_at(0.0, plan.x, &in);
        st = ogk_nmpc_solve(&ctx, &in, &rep);
        if (pass == 2) {
            OGK_ASSERT_STATUS(st, OGK_OK);
            assert_true((rep.flags & OGK_NMPC_FLAG_OUTSIDE_SET) != 0u);
            assert_true((rep.flags & OGK_NMPC_FLAG_STALE) == 0u);
            OGK_ASSERT_STATUS(ogk_nmpc_get_plan(&ctx, &plan2), OGK_OK);
            /* outward as far as the engine takes it: the radius short of 1.5 - 1e-3 */
            assert_true(plan2.x[3u * NX] < 1.5 - 1.0e-3);
            assert_true(plan2.x[3u * NX] > plan.x[3u * NX]);
            miss_exact = 1.5 - plan2.x[3u * NX];
            print_message("target out of reach, terminal set: r_N short of the set by %.6f LU, %u SQP iterations\n",
                          miss_exact - 1.0e-3, (unsigned)rep.sqp_iterations);
            continue;
        }
        assert_int_not_equal((int)st, (int)OGK_OK);
        assert_int_equal((int)rep.solve_status, (int)st);
        assert_true((rep.flags & OGK_NMPC_FLAG_ELASTIC) != 0u);
        assert_true((rep.flags & OGK_NMPC_FLAG_STALE) != 0u);
        assert_true(rep.sqp_iterations >= 1u);
        /* the loaded plan still flies, marked SAFE */
        OGK_ASSERT_STATUS(ogk_nmpc_get_plan(&ctx, &plan2), OGK_OK);
        assert_true(memcmp(&plan, &plan2, sizeof plan) == 0);
        OGK_ASSERT_STATUS(ogk_nmpc_command(&ctx, 0.5, &cmd), OGK_OK);
        assert_true((cmd.flags & OGK_THRUST_FLAG_SAFE) != 0u);
        assert_true((cmd.law_flags & OGK_NMPC_FLAG_STALE) != 0u);
    }
}

/* A sweep bound the radial transfer can hardly meet on 4 subintervals (0.6 rad each: the thrust
 * cannot turn round to brake in time): the QPs go elastic, then no step is accepted even after
 * the BFGS/filter restarts; the line search failure is reported (LS_FAILED, OGK_E_NOT_CONVERGED)
 * and the loaded plan is kept. */
/* req: OGK-NMPC-005 */
static void test_solve_line_search_failure(void **state)
{
    ogk_nmpc_config_t c;
    ogk_nmpc_input_t in;
    ogk_nmpc_report_t rep;
    uint32_t k;
    (void)state;
    radial_config(&c, 4u);
    c.max_sweep = 0.6;
    OGK_ASSERT_STATUS(ogk_nmpc_init(&ctx, &c), OGK_OK);
    radial_guess(4u, 5.0, &plan);
    for (k = 0u; k <= 4u; ++k) {
        plan.u[k] = PI * (double)k / 4.0;
    }
    OGK_ASSERT_STATUS(ogk_nmpc_load_plan(&ctx, &plan), OGK_OK);
    input_at(0.0, plan.x, &in);
    OGK_ASSERT_STATUS(ogk_nmpc_solve(&ctx, &in, &rep), OGK_E_NOT_CONVERGED);
    assert_true((rep.flags & (OGK_NMPC_FLAG_LS_FAILED | OGK_NMPC_FLAG_STALE))
                == (OGK_NMPC_FLAG_LS_FAILED | OGK_NMPC_FLAG_STALE));
    assert_true(rep.feas > c.tol_feas);
    OGK_ASSERT_STATUS(ogk_nmpc_get_plan(&ctx, &plan2), OGK_OK);
    assert_true(memcmp(&plan, &plan2, sizeof plan) == 0);
}

/* A guess whose first interval falls through the centre: the first evaluation fails
 * (OGK_E_NONFINITE), no QP is solved, the plan is kept. */
/* req: OGK-NMPC-005 */
static void test_solve_guess_outside_domain(void **state)
{
    ogk_nmpc_config_t c;
    ogk_nmpc_input_t in;
    ogk_nmpc_report_t rep;
    (void)state;
    radial_config(&c, 4u);
    OGK_ASSERT_STATUS(ogk_nmpc_init(&ctx, &c), OGK_OK);
    radial_guess(4u, 5.0, &plan);
    OGK_ASSERT_STATUS(ogk_nmpc_load_plan(&ctx, &plan), OGK_OK);
    input_at(0.0, plan.x, &in);
    in.x[2] = -2.0; /* 1 LU inwards in half the first interval */
    OGK_ASSERT_STATUS(ogk_nmpc_solve(&ctx, &in, &rep), OGK_E_NONFINITE);
    assert_int_equal((int)rep.sqp_iterations, 0);
    assert_int_equal((int)rep.solves, 1);
    assert_int_equal((int)rep.flags, (int)OGK_NMPC_FLAG_STALE);
    OGK_ASSERT_STATUS(ogk_nmpc_get_plan(&ctx, &plan2), OGK_OK);
    assert_true(memcmp(&plan, &plan2, sizeof plan) == 0);
}

/* ------------------------------------------------------------------ strategies */

static double solve_radial_open_loop(ogk_nmpc_config_t *c, uint32_t nodes, ogk_nmpc_report_t *rep)
{
    ogk_nmpc_input_t in;
    OGK_ASSERT_STATUS(ogk_nmpc_init(&ctx, c), OGK_OK);
    radial_guess(nodes, 5.0, &plan);
    OGK_ASSERT_STATUS(ogk_nmpc_load_plan(&ctx, &plan), OGK_OK);
    input_at(0.0, plan.x, &in);
    OGK_ASSERT_STATUS(ogk_nmpc_solve(&ctx, &in, rep), OGK_OK);
    OGK_ASSERT_STATUS(ogk_nmpc_get_plan(&ctx, &plan), OGK_OK);
    return plan.horizon / (double)nodes;
}

/* SNNS below min_nodes: the rest of the plan is regridded to min_nodes (or kept at its own N when
 * that is smaller), over [t, t_f]. */
/* req: OGK-NMPC-004 */
static void test_snns_min_nodes_regrid(void **state)
{
    ogk_nmpc_config_t c;
    ogk_nmpc_input_t in;
    ogk_nmpc_report_t rep;
    double h;
    double t_f;
    (void)state;
    /* N = 3, min_nodes = 3: one subinterval flown leaves 2 < 3, so 3 nodes over [h, t_f] */
    radial_config(&c, 3u);
    c.min_nodes = 3u;
    h = solve_radial_open_loop(&c, 3u, &rep);
    t_f = rep.t_f;
    input_at(h, &plan.x[NX], &in);
    OGK_ASSERT_STATUS(ogk_nmpc_replan(&ctx, &in, &rep), OGK_OK);
    assert_int_equal((int)rep.nodes, 3);
    assert_true((rep.flags & OGK_NMPC_FLAG_REGRIDDED) != 0u);
    assert_true((rep.flags & OGK_NMPC_FLAG_CONVERGED) != 0u);
    /* float: measured worst 1.1e-7 on M4F and host */
    OGK_ASSERT_NEAR(rep.t_next, h + (rep.t_f - h) / 3.0, OGK_TEST_TOL(1e-12, 2e-6));
    /* on the open loop's own trajectory: the same final time up to the new grid's discretisation */
    OGK_ASSERT_NEAR(rep.t_f, t_f, 0.05 * t_f);

    /* N = 3, min_nodes = 2, two subintervals flown: 1 < 2 left, regridded to 2 nodes */
    c.min_nodes = 2u;
    h = solve_radial_open_loop(&c, 3u, &rep);
    input_at(2.0 * h, &plan.x[2u * NX], &in);
    OGK_ASSERT_STATUS(ogk_nmpc_replan(&ctx, &in, &rep), OGK_OK);
    assert_int_equal((int)rep.nodes, 2);
    assert_true((rep.flags & OGK_NMPC_FLAG_REGRIDDED) != 0u);

    /* min_nodes above the plan's N: N kept, regridded over [t, t_f] */
    c.min_nodes = 5u;
    h = solve_radial_open_loop(&c, 3u, &rep);
    input_at(h, &plan.x[NX], &in);
    OGK_ASSERT_STATUS(ogk_nmpc_replan(&ctx, &in, &rep), OGK_OK);
    assert_int_equal((int)rep.nodes, 3);
    assert_true((rep.flags & OGK_NMPC_FLAG_REGRIDDED) != 0u);

    /* a replan before the first node is reached: nothing dropped, the same N re-solved */
    c.min_nodes = 1u;
    h = solve_radial_open_loop(&c, 3u, &rep);
    input_at(0.25 * h, plan.x, &in);
    {
        ogk_nmpc_command_t cmd;
        OGK_ASSERT_STATUS(ogk_nmpc_command(&ctx, 0.25 * h, &cmd), OGK_OK);
        OGK_ASSERT_STATUS(ogk_nmpc_replan(&ctx, &in, &rep), OGK_OK);
        (void)cmd;
    }
    assert_int_equal((int)rep.nodes, 3);
    assert_int_equal((int)(rep.flags & OGK_NMPC_FLAG_REGRIDDED), 0);
}

/* The doubling test (sec. 2.3.3) on the radial transfer, whose discrete optimum improves with N:
 * threshold 0 adopts 2N (SUBDIVIDED, a t_f no later than with N); a huge threshold keeps N; the
 * subdivision budget stops it. */
/* req: OGK-NMPC-004 */
static void test_snns_doubling(void **state)
{
    ogk_nmpc_config_t c;
    ogk_nmpc_input_t in;
    ogk_nmpc_report_t rep;
    ogk_nmpc_report_t rep_keep;
    double h;
    (void)state;
    radial_config(&c, 4u);
    c.min_nodes = 1u;
    c.doubling_max_nodes = 8u;
    c.max_subdivisions = 1u;
    c.doubling_threshold = 1.0e9; /* never worth it */
    h = solve_radial_open_loop(&c, 4u, &rep);
    input_at(h, &plan.x[NX], &in);
    OGK_ASSERT_STATUS(ogk_nmpc_replan(&ctx, &in, &rep_keep), OGK_OK);
    assert_int_equal((int)rep_keep.nodes, 3);
    assert_int_equal((int)rep_keep.solves, 2); /* N and 2N solved, N kept */
    assert_int_equal((int)(rep_keep.flags & OGK_NMPC_FLAG_SUBDIVIDED), 0);

    c.doubling_threshold = 0.0; /* any gain */
    h = solve_radial_open_loop(&c, 4u, &rep);
    input_at(h, &plan.x[NX], &in);
    OGK_ASSERT_STATUS(ogk_nmpc_replan(&ctx, &in, &rep), OGK_OK);
    assert_int_equal((int)rep.nodes, 6);
    assert_int_equal((int)rep.solves, 2);
    assert_true((rep.flags & OGK_NMPC_FLAG_SUBDIVIDED) != 0u);
    assert_true((rep.flags & OGK_NMPC_FLAG_CONVERGED) != 0u);
    assert_true(rep.feas <= c.tol_feas);
    assert_true(rep.t_f < rep_keep.t_f); /* 2N is better: that is why it was adopted */
    /* float: measured worst 9.9e-8 on M4F and host */
    OGK_ASSERT_NEAR(rep.t_next, h + (rep.t_f - h) / 6.0, OGK_TEST_TOL(1e-12, 1e-6));
    print_message("doubling: t_f with N = 3: %.6f, with 2N = 6: %.6f\n", rep_keep.t_f, rep.t_f);
    /* the budget (max_subdivisions = 1) is spent: the next replan does not double */
    OGK_ASSERT_STATUS(ogk_nmpc_get_plan(&ctx, &plan), OGK_OK);
    input_at(rep.t_next, &plan.x[NX], &in);
    OGK_ASSERT_STATUS(ogk_nmpc_replan(&ctx, &in, &rep), OGK_OK);
    assert_int_equal((int)rep.nodes, 5);
    assert_int_equal((int)rep.solves, 1);
    /* after reset the budget is back */
    OGK_ASSERT_STATUS(ogk_nmpc_reset(&ctx), OGK_OK);
    assert_int_equal((int)ctx.subdivisions, 0);
}

/* A replan that fails flies the shifted previous plan (STALE, SAFE), with and without the doubling
 * test, and the status says why; then the plan is stretched when t >= t_f. */
/* req: OGK-NMPC-005 */
static void test_stale_and_stretched_plans(void **state)
{
    ogk_nmpc_config_t c;
    ogk_nmpc_input_t in;
    ogk_nmpc_report_t rep;
    ogk_nmpc_command_t cmd;
    double h;
    double t_f;
    ogk_status st;
    (void)state;
    /* max_iter 1: no replan from a perturbed state converges */
    radial_config(&c, 4u);
    c.min_nodes = 1u;
    h = solve_radial_open_loop(&c, 4u, &rep);
    t_f = rep.t_f;
    c.max_iter = 1u;
    c.max_iter_cold = 1u;
    c.doubling_max_nodes = 8u;
    c.doubling_threshold = 0.0;
    OGK_ASSERT_STATUS(ogk_nmpc_init(&ctx, &c), OGK_OK);
    OGK_ASSERT_STATUS(ogk_nmpc_load_plan(&ctx, &plan), OGK_OK);
    input_at(h, &plan.x[NX], &in);
    in.x[2] += 1.0e-3;
    st = ogk_nmpc_replan(&ctx, &in, &rep);
    OGK_ASSERT_STATUS(st, OGK_E_ITER_LIMIT);
    assert_int_equal((int)rep.solve_status, (int)OGK_E_ITER_LIMIT);
    assert_int_equal((int)rep.solves, 2); /* N failed, 2N tried from the shifted plan, failed too */
    assert_true((rep.flags & OGK_NMPC_FLAG_STALE) != 0u);
    assert_int_equal((int)(rep.flags & OGK_NMPC_FLAG_SUBDIVIDED), 0);
    assert_int_equal((int)rep.nodes, 3); /* the shifted plan: the flown subinterval dropped */
    OGK_ASSERT_NEAR(rep.t_f, t_f, 1e-12 * t_f);
    OGK_ASSERT_STATUS(ogk_nmpc_command(&ctx, h + 0.1, &cmd), OGK_OK);
    assert_true((cmd.flags & OGK_THRUST_FLAG_SAFE) != 0u);
    assert_true((cmd.flags & OGK_THRUST_FLAG_ENGINE_ON) != 0u);
    assert_true((cmd.law_flags & OGK_NMPC_FLAG_STALE) != 0u);
    OGK_ASSERT_STATUS(ogk_nmpc_get_plan(&ctx, &plan2), OGK_OK);
    OGK_ASSERT_NEAR(plan2.t0, h, 1e-12);
    OGK_ASSERT_NEAR(plan2.u[0], plan.u[1], 0.0);

    /* t past t_f: the plan is stretched to end horizon_min after t (REGRIDDED); whatever the
     * solve does, the plan flown ends no earlier than that */
    in.t = t_f + 0.5;
    st = ogk_nmpc_replan(&ctx, &in, &rep);
    assert_true((rep.flags & OGK_NMPC_FLAG_REGRIDDED) != 0u);
    /* float: the plan's end is rounded at the ulp of t (8 eps t, relative to horizon_min) */
    assert_true(rep.t_f >= in.t + c.horizon_min * (1.0 - OGK_TEST_TOL(1e-12, 8.0 * FLT_EPSILON * in.t / c.horizon_min)));
    if (st != OGK_OK) {
        assert_true((rep.flags & OGK_NMPC_FLAG_STALE) != 0u);
        /* float: as above, the plan's end rounded at the ulp of t (8 eps t) */
        OGK_ASSERT_NEAR(rep.t_f, in.t + c.horizon_min, OGK_TEST_TOL(1e-12, 8.0 * FLT_EPSILON) * in.t);
    }
    /* the command past the (old) end of plan holds the last node and says so */
    OGK_ASSERT_STATUS(ogk_nmpc_get_plan(&ctx, &plan2), OGK_OK);
    OGK_ASSERT_STATUS(ogk_nmpc_command(&ctx, rep.t_f + 1.0, &cmd), OGK_OK);
    assert_true((cmd.law_flags & OGK_NMPC_FLAG_END_OF_PLAN) != 0u);
    OGK_ASSERT_NEAR(cmd.alpha, plan2.u[plan2.nodes], 0.0);
}

/* CNCN after a failed solve: the regridded previous plan is flown (STALE) and has the same N. */
/* req: OGK-NMPC-005 OGK-NMPC-004 */
static void test_cncn_stale(void **state)
{
    ogk_nmpc_config_t c;
    ogk_nmpc_input_t in;
    ogk_nmpc_report_t rep;
    double h;
    (void)state;
    radial_config(&c, 4u);
    c.strategy = OGK_NMPC_CNCN;
    h = solve_radial_open_loop(&c, 4u, &rep);
    c.max_iter = 1u;
    c.max_iter_cold = 1u;
    OGK_ASSERT_STATUS(ogk_nmpc_init(&ctx, &c), OGK_OK);
    OGK_ASSERT_STATUS(ogk_nmpc_load_plan(&ctx, &plan), OGK_OK);
    input_at(0.5 * h, plan.x, &in);
    in.x[0] += 1.0e-3;
    OGK_ASSERT_STATUS(ogk_nmpc_replan(&ctx, &in, &rep), OGK_E_ITER_LIMIT);
    assert_int_equal((int)rep.nodes, 4);
    assert_true((rep.flags & (OGK_NMPC_FLAG_STALE | OGK_NMPC_FLAG_REGRIDDED))
                == (OGK_NMPC_FLAG_STALE | OGK_NMPC_FLAG_REGRIDDED));
    /* float: measured worst 4.5e-8 on M4F and host */
    OGK_ASSERT_NEAR(rep.t_next, 0.5 * h + (rep.t_f - 0.5 * h) / 4.0, OGK_TEST_TOL(1e-12, 5e-7));
}

/* Throttled plans: the throttle of every node in [0, 1], r > 0 checked before it. */
/* req: OGK-NMPC-008 */
static void test_load_plan_throttle_range(void **state)
{
    ogk_nmpc_config_t c;
    (void)state;
    coast_config(&c, 3u);
    OGK_ASSERT_STATUS(ogk_nmpc_init(&ctx, &c), OGK_OK);
    coast_guess(3u, 1.5, 0.5, &plan);
    plan2 = plan;
    plan2.nu = 1u;
    OGK_ASSERT_STATUS(ogk_nmpc_load_plan(&ctx, &plan2), OGK_E_DIM);
    plan2 = plan;
    plan2.u[2u * 3u + 1u] = OGK_TEST_PICK(-1.0e-300, -1.0e-30); /* last node */
    OGK_ASSERT_STATUS(ogk_nmpc_load_plan(&ctx, &plan2), OGK_E_RANGE);
    plan2 = plan;
    plan2.u[2u * 1u + 1u] = 1.0 + OGK_REAL_EPSILON;
    OGK_ASSERT_STATUS(ogk_nmpc_load_plan(&ctx, &plan2), OGK_E_RANGE);
    plan2 = plan;
    plan2.x[1u * NX + 0u] = -1.0; /* r < 0 and a good throttle at node 1 */
    OGK_ASSERT_STATUS(ogk_nmpc_load_plan(&ctx, &plan2), OGK_E_RANGE);
    OGK_ASSERT_STATUS(ogk_nmpc_get_plan(&ctx, &plan2), OGK_E_RANGE);
    plan.u[1] = 0.0;
    plan.u[7] = 1.0; /* both ends of the range */
    OGK_ASSERT_STATUS(ogk_nmpc_load_plan(&ctx, &plan), OGK_OK);
}

/* A replan before the plan's t0: nothing is flown, the horizon t_f - t is above horizon_max by
 * more than one step, so the first QP's bound on dT is the single point horizon_max - T (its
 * upper bound clipped to its lower one); the plan flown ends within horizon_max of t. */
/* req: OGK-NMPC-008 */
static void test_replan_before_t0(void **state)
{
    ogk_nmpc_config_t c;
    ogk_nmpc_input_t in;
    ogk_nmpc_report_t rep;
    ogk_status st;
    (void)state;
    radial_config(&c, 4u);
    c.horizon_max = 5.0;
    (void)solve_radial_open_loop(&c, 4u, &rep);
    input_at(-2.0, plan.x, &in);
    st = ogk_nmpc_replan(&ctx, &in, &rep);
    assert_int_equal((int)rep.nodes, 4);
    assert_int_equal((int)(rep.flags & OGK_NMPC_FLAG_REGRIDDED), 0);
    if (st == OGK_OK) {
        assert_true(rep.t_f - in.t <= c.horizon_max * (1.0 + 1e-12));
        assert_true(rep.feas <= c.tol_feas);
    } else {
        assert_true((rep.flags & OGK_NMPC_FLAG_STALE) != 0u);
    }
    print_message("replan 2 TU before t0: status %d, t_f - t = %.6f\n", (int)st, rep.t_f - in.t);
}

/* The doubling test after a failed N solve: the 2N plan is built from the shifted plan anchored
 * at the measured state; here that state falls through the centre, so the N solve fails
 * (OGK_E_NONFINITE) and so does the subdivision's midpoint propagation: no 2N solve. */
/* req: OGK-NMPC-004 OGK-NMPC-005 */
static void test_doubling_after_failure_subdivision_fails(void **state)
{
    ogk_nmpc_config_t c;
    ogk_nmpc_input_t in;
    ogk_nmpc_report_t rep;
    double h;
    (void)state;
    radial_config(&c, 4u);
    c.doubling_max_nodes = 8u;
    c.doubling_threshold = 0.0;
    h = solve_radial_open_loop(&c, 4u, &rep);
    input_at(h, &plan.x[NX], &in);
    in.x[2] = -50.0;
    OGK_ASSERT_STATUS(ogk_nmpc_replan(&ctx, &in, &rep), OGK_E_NONFINITE);
    assert_int_equal((int)rep.solves, 1);
    assert_int_equal((int)rep.sqp_iterations, 0);
    assert_int_equal((int)rep.nodes, 3);
    assert_true((rep.flags & OGK_NMPC_FLAG_STALE) != 0u);
    assert_int_equal((int)(rep.flags & OGK_NMPC_FLAG_SUBDIVIDED), 0);
}

/* The doubling test with J_N = 0 (a coast, minimum fuel): the relative gain is taken against
 * 1e-12 instead of |J_N|; 2N cannot burn less than nothing, so N is kept. */
/* req: OGK-NMPC-004 */
static void test_doubling_zero_objective(void **state)
{
    ogk_nmpc_config_t c;
    ogk_nmpc_input_t in;
    ogk_nmpc_report_t rep;
    (void)state;
    coast_config(&c, 3u);
    c.doubling_max_nodes = 8u;
    c.min_nodes = 1u;
    c.tol_stat = OGK_TEST_TOL(1.0e-10, NMPC_FX_TOL_F);
    OGK_ASSERT_STATUS(ogk_nmpc_init(&ctx, &c), OGK_OK);
    coast_guess(3u, 1.5, 0.0, &plan);
    OGK_ASSERT_STATUS(ogk_nmpc_load_plan(&ctx, &plan), OGK_OK);
    input_at(0.5, &plan.x[NX], &in);
    OGK_ASSERT_STATUS(ogk_nmpc_replan(&ctx, &in, &rep), OGK_OK);
    assert_int_equal((int)rep.solves, 2);
    assert_int_equal((int)rep.nodes, 2);
    assert_int_equal((int)(rep.flags & OGK_NMPC_FLAG_SUBDIVIDED), 0);
    OGK_ASSERT_NEAR(rep.objective, 0.0, 1.0e-12);
}

/* ------------------------------------------------------------------ command */

/* req: OGK-NMPC-009 */
static void test_command_edges(void **state)
{
    ogk_nmpc_config_t c;
    ogk_nmpc_command_t cmd;
    ogk_nmpc_input_t in;
    ogk_nmpc_report_t rep;
    (void)state;
    /* a throttled plan whose throttle is 0 at the start and 1 at the end */
    coast_config(&c, 2u);
    OGK_ASSERT_STATUS(ogk_nmpc_init(&ctx, &c), OGK_OK);
    coast_guess(2u, 1.5, 0.0, &plan);
    plan.t0 = 10.0;
    plan.u[0] = 0.3;
    plan.u[4] = -0.2;
    plan.u[5] = 1.0;
    OGK_ASSERT_STATUS(ogk_nmpc_load_plan(&ctx, &plan), OGK_OK);
    /* before t0: the first node's control; the engine off (no ENGINE_ON, no SAFE) */
    OGK_ASSERT_STATUS(ogk_nmpc_command(&ctx, 9.0, &cmd), OGK_OK);
    /* float: measured worst 1.2e-8 on M4F and host */
    OGK_ASSERT_NEAR(cmd.alpha, 0.3, OGK_TEST_TOL(0.0, 2e-7));
    OGK_ASSERT_NEAR(cmd.throttle, 0.0, 0.0);
    assert_int_equal((int)cmd.flags, 0);
    assert_int_equal((int)cmd.law_flags, 0);
    OGK_ASSERT_NEAR(cmd.t, 9.0, 0.0);
    /* inside: linear between the nodes */
    OGK_ASSERT_STATUS(ogk_nmpc_command(&ctx, 10.0 + 0.75 + 0.375, &cmd), OGK_OK);
    /* float: measured worst 6e-9 on M4F and host */
    OGK_ASSERT_NEAR(cmd.alpha, 0.5 * 1.0 + 0.5 * -0.2, OGK_TEST_TOL(1e-15, 1e-7));
    OGK_ASSERT_NEAR(cmd.throttle, 0.5, 1e-15);
    assert_int_equal((int)cmd.flags, (int)OGK_THRUST_FLAG_ENGINE_ON);
    /* exactly at t_f: the last node, not yet past the end */
    OGK_ASSERT_STATUS(ogk_nmpc_command(&ctx, 11.5, &cmd), OGK_OK);
    /* float: measured worst 3e-9 on M4F and host */
    OGK_ASSERT_NEAR(cmd.alpha, -0.2, OGK_TEST_TOL(0.0, 5e-8));
    assert_int_equal((int)(cmd.law_flags & OGK_NMPC_FLAG_END_OF_PLAN), 0);
    /* after t_f: held, END_OF_PLAN */
    OGK_ASSERT_STATUS(ogk_nmpc_command(&ctx, 1.0e6, &cmd), OGK_OK);
    /* float: measured worst 3e-9 on M4F and host */
    OGK_ASSERT_NEAR(cmd.alpha, -0.2, OGK_TEST_TOL(0.0, 5e-8));
    OGK_ASSERT_NEAR(cmd.throttle, 1.0, 0.0);
    assert_int_equal((int)cmd.law_flags, (int)OGK_NMPC_FLAG_END_OF_PLAN);
    /* a failed solve: the same plan, now SAFE and STALE (a state outside the domain on the way) */
    input_at(10.0, plan.x, &in);
    in.x[2] = -20.0;
    OGK_ASSERT_STATUS(ogk_nmpc_solve(&ctx, &in, &rep), OGK_E_NONFINITE);
    OGK_ASSERT_STATUS(ogk_nmpc_command(&ctx, 1.0e6, &cmd), OGK_OK);
    assert_int_equal((int)cmd.flags, (int)(OGK_THRUST_FLAG_ENGINE_ON | OGK_THRUST_FLAG_SAFE));
    assert_int_equal((int)cmd.law_flags, (int)(OGK_NMPC_FLAG_END_OF_PLAN | OGK_NMPC_FLAG_STALE));
    OGK_ASSERT_STATUS(ogk_nmpc_command(&ctx, 9.0, &cmd), OGK_OK);
    assert_int_equal((int)cmd.flags, (int)OGK_THRUST_FLAG_SAFE); /* engine off, still SAFE */
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_init_rejects_every_field),
        cmocka_unit_test(test_bad_inputs_every_function),
        cmocka_unit_test(test_model_throttle_solar_overflow_and_body_centre),
        cmocka_unit_test(test_solve_solar_engine_and_bodies),
        cmocka_unit_test(test_solve_sweep_bound),
        cmocka_unit_test(test_solve_elastic_qp),
        cmocka_unit_test(test_solve_line_search_failure),
        cmocka_unit_test(test_solve_guess_outside_domain),
        cmocka_unit_test(test_snns_min_nodes_regrid),
        cmocka_unit_test(test_snns_doubling),
        cmocka_unit_test(test_stale_and_stretched_plans),
        cmocka_unit_test(test_cncn_stale),
        cmocka_unit_test(test_load_plan_throttle_range),
        cmocka_unit_test(test_replan_before_t0),
        cmocka_unit_test(test_doubling_after_failure_subdivision_fails),
        cmocka_unit_test(test_doubling_zero_objective),
        cmocka_unit_test(test_command_edges),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
