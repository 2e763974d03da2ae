/* test_nmpc_user_problem.c -- the NMPC's solver on a problem of the caller's
 * own (ogk/ocp.h, ogk_nmpc_init_problem): a vehicle in free space with a
 * constant acceleration a = T / m, from rest to a point at rest. Its
 * minimum time has a closed form (bang-bang along the line: T* = 2 sqrt(d /
 * a)), a bound no transcription can beat; a keep-out disc on the line forces
 * a detour, kept at every node and RK4 step end. The init's argument checks
 * (every callback required) are here too. */
#include "ogk_test.h"

/* The SQP's tolerances in the float build: 1e-5, twenty times the defects' and stationarity's
 * float floor (NMPC_FX_TOL_F of nmpc_fixture.h, measured there). */
#define NMPC_FX_TOL_F 1.0e-5

#include <math.h>
#include <string.h>

#include "ogk/nmpc.h"
#include "ogk/ocp.h"

#define NX OGK_OCP_NX
#define PI 3.14159265358979323846

/* The problem's data: acceleration, the target point, one disc. */
typedef struct {
    ogk_real_t thrust;       /* [MU LU/TU^2] */
    ogk_real_t target[2];    /* [LU] */
    ogk_real_t centre[2];    /* [LU] */
    ogk_real_t radius;       /* [LU], 0: none */
} free_space_t;

static uint32_t fs_structure(const void *data, uint32_t nu)
{
    (void)data;
    (void)nu;
    return OGK_OCP_FLOW_FIXED; /* m' = 0 */
}

/* x = (x, y, v_x, v_y, m): x' = v_x, y' = v_y, v' = (T / m) (cos a, sin a), m' = 0 */
static ogk_status fs_dynamics(const void *data, uint32_t nu, ogk_real_t t, const ogk_real_t *x, const ogk_real_t *u,
                              const ogk_real_t *trig, ogk_real_t *xdot, ogk_real_t *jx, ogk_real_t *ju, ogk_real_t *jt)
{
    const free_space_t *fs = (const free_space_t *)data;
    const ogk_real_t ca = (trig != NULL) ? trig[0] : cos(u[0]);
    const ogk_real_t sa = (trig != NULL) ? trig[1] : sin(u[0]);
    const ogk_real_t acc = fs->thrust / x[4];
    (void)nu;
    (void)t;
    (void)jt;
    if (!(x[4] > 0.0)) {
        return OGK_E_NONFINITE;
    }
    xdot[0] = x[2];
    xdot[1] = x[3];
    xdot[2] = acc * ca;
    xdot[3] = acc * sa;
    xdot[4] = 0.0;
    if (jx != NULL) {
        jx[0 * NX + 2] = 1.0;
        jx[1 * NX + 3] = 1.0;
        jx[2 * NX + 4] = -acc / x[4] * ca;
        jx[3 * NX + 4] = -acc / x[4] * sa;
        ju[2] = -acc * sa;
        ju[3] = acc * ca;
    }
    return OGK_OK;
}

/* kappa . f: only the thrust terms curve, in (m, alpha) */
static void fs_hess(const void *data, uint32_t nu, ogk_real_t t, const ogk_real_t *x, const ogk_real_t *u,
                    const ogk_real_t *trig, const ogk_real_t *kappa, ogk_real_t *hz)
{
    const free_space_t *fs = (const free_space_t *)data;
    const size_t zs = OGK_OCP_NZ;
    const size_t i_a = NX;
    const ogk_real_t q = kappa[2] * trig[0] + kappa[3] * trig[1];
    const ogk_real_t q_a = -kappa[2] * trig[1] + kappa[3] * trig[0];
    const ogk_real_t inv_m = 1.0 / x[4];
    (void)nu;
    (void)t;
    (void)u;
    hz[4 * zs + 4] = 2.0 * fs->thrust * inv_m * inv_m * inv_m * q;
    hz[4 * zs + i_a] = -fs->thrust * inv_m * inv_m * q_a;
    hz[i_a * zs + i_a] = -fs->thrust * inv_m * q;
}

static void fs_target(const void *data, ogk_real_t t_f, ogk_real_t *x_target, ogk_real_t *rate)
{
    const free_space_t *fs = (const free_space_t *)data;
    (void)t_f;
    x_target[0] = fs->target[0];
    x_target[1] = fs->target[1];
    x_target[2] = 0.0;
    x_target[3] = 0.0;
    (void)memset(rate, 0, OGK_OCP_NC * sizeof(ogk_real_t));
}

static ogk_real_t fs_radius(const void *data, size_t j)
{
    const free_space_t *fs = (const free_space_t *)data;
    return (j == 0u) ? fs->radius : 0.0;
}

static ogk_real_t fs_distance(const void *data, size_t j, const ogk_real_t *x, ogk_real_t t, ogk_real_t *d_x0, ogk_real_t *d_x1,
                          ogk_real_t *d_t)
{
    const free_space_t *fs = (const free_space_t *)data;
    const ogk_real_t dx = x[0] - fs->centre[0];
    const ogk_real_t dy = x[1] - fs->centre[1];
    const ogk_real_t d = sqrt(dx * dx + dy * dy);
    (void)j;
    (void)t;
    *d_x0 = dx / d;
    *d_x1 = dy / d;
    *d_t = 0.0;
    return d;
}

static void fs_key(const void *data, ogk_real_t *key)
{
    const free_space_t *fs = (const free_space_t *)data;
    (void)memset(key, 0, OGK_OCP_MODEL_KEY * sizeof(ogk_real_t));
    key[0] = fs->thrust;
}

static bool fs_valid(const void *data, const ogk_real_t *x, size_t n)
{
    size_t k;
    bool ok = true;
    (void)data;
    for (k = 0u; k < n; ++k) {
        ok = ok && (x[k * NX + 4] > 0.0);
    }
    return ok;
}

static const ogk_ocp_problem_t free_space = {
    fs_structure, fs_dynamics, fs_hess, fs_target, fs_radius, fs_distance, fs_key, fs_valid, NULL
};

static ogk_nmpc_t ctx;

static void settings(ogk_nmpc_config_t *c, uint32_t hessian)
{
    (void)ogk_nmpc_config_default(c);
    c->nodes = 20u;
    c->rk4_steps = 8u;
    c->horizon_min = 0.1;
    c->horizon_max = 50.0;
    c->max_iter = 200u;
    c->max_iter_cold = 200u;
    c->tol_feas = OGK_TEST_TOL(1.0e-10, NMPC_FX_TOL_F);
    c->tol_stat = OGK_TEST_TOL(1.0e-8, NMPC_FX_TOL_F);
    c->hessian = hessian;
}

/* A guess: a straight line with a smoothstep, accelerate then brake, with a
 * sideways bulge of `bulge` LU. */
static void guess(const free_space_t *fs, double t_guess, double bulge, ogk_nmpc_plan_t *p)
{
    uint32_t k;
    (void)memset(p, 0, sizeof *p);
    p->horizon = t_guess;
    p->nodes = 20u;
    p->nu = 1u;
    for (k = 0u; k <= p->nodes; ++k) {
        const double tau = (double)k / (double)p->nodes;
        const double s = 3.0 * tau * tau - 2.0 * tau * tau * tau;
        const double ds = (6.0 * tau - 6.0 * tau * tau) / t_guess;
        p->x[k * NX + 0] = fs->target[0] * s;
        p->x[k * NX + 1] = bulge * 4.0 * tau * (1.0 - tau);
        p->x[k * NX + 2] = fs->target[0] * ds;
        p->x[k * NX + 3] = bulge * 4.0 * (1.0 - 2.0 * tau) / t_guess;
        p->x[k * NX + 4] = 1.0;
        p->u[k] = (tau < 0.5) ? 0.0 : PI;
    }
}

static double solve(free_space_t *fs, uint32_t hessian, double bulge, ogk_nmpc_plan_t *out)
{
    ogk_nmpc_config_t cfg;
    ogk_nmpc_plan_t plan;
    ogk_nmpc_input_t in;
    ogk_nmpc_report_t rep;
    settings(&cfg, hessian);
    OGK_ASSERT_STATUS(ogk_nmpc_init_problem(&ctx, &cfg, &free_space, fs), OGK_OK);
    guess(fs, 8.0, bulge, &plan);
    OGK_ASSERT_STATUS(ogk_nmpc_load_plan(&ctx, &plan), OGK_OK);
    in.t = 0.0;
    (void)memcpy(in.x, plan.x, sizeof in.x);
    OGK_ASSERT_STATUS(ogk_nmpc_solve(&ctx, &in, &rep), OGK_OK);
    OGK_ASSERT_LE(rep.feas, OGK_TEST_TOL(1.0e-9, NMPC_FX_TOL_F));
    OGK_ASSERT_STATUS(ogk_nmpc_get_plan(&ctx, out), OGK_OK);
    return rep.t_f;
}

/* req: OGK-NMPC-016 */
static void test_min_time_against_bang_bang(void **state)
{
    free_space_t fs = { 0.1, { 1.0, 0.0 }, { 0.0, 0.0 }, 0.0 };
    const double t_star = 2.0 * sqrt(1.0 / 0.1); /* accelerate d/2, brake d/2 */
    ogk_nmpc_plan_t plan;
    double t_bfgs;
    double t_exact;
    (void)state;
    t_bfgs = solve(&fs, OGK_NMPC_HESSIAN_BFGS, 0.0, &plan);
    /* the continuous optimum bounds every feasible plan (to the RK4 error, 1e-9 here); the switch of
     * the angle, linear over one of the 20 subintervals, costs a little */
    assert_true(t_bfgs >= t_star - 1.0e-7);
    assert_true(t_bfgs <= 1.005 * t_star); /* measured: +0.12 % */
    t_exact = solve(&fs, OGK_NMPC_HESSIAN_EXACT, 0.0, &plan);
    /* the same optimum: BFGS stops on its predicted decrease (tol_obj), the exact Hessian in Newton steps */
    /* float: measured worst 2.9e-5 on M4F and host */
    OGK_ASSERT_NEAR(t_exact, t_bfgs, OGK_TEST_TOL(1.0e-5, 5e-4));
}

/* req: OGK-NMPC-016 */
static void test_keepout_disc_on_the_line(void **state)
{
    free_space_t fs = { 0.1, { 1.0, 0.0 }, { 0.5, 0.0 }, 0.2 };
    const double t_star = 2.0 * sqrt(1.0 / 0.1);
    ogk_nmpc_plan_t plan;
    double t_f;
    uint32_t k;
    (void)state;
    t_f = solve(&fs, OGK_NMPC_HESSIAN_BFGS, 0.4, &plan);
    /* the detour is longer than the line */
    assert_true(t_f > 1.01 * t_star);
    for (k = 1u; k < plan.nodes; ++k) {
        const double dx = plan.x[k * NX + 0] - fs.centre[0];
        const double dy = plan.x[k * NX + 1] - fs.centre[1];
        assert_true(sqrt(dx * dx + dy * dy) >= fs.radius - 1.0e-9);
    }
    /* the arcs too: each subinterval re-swept at 64 steps, the disc kept to the RK4 error */
    for (k = 0u; k < plan.nodes; ++k) {
        double x[NX];
        const double h = plan.horizon / (double)plan.nodes;
        uint32_t j;
        for (j = 0u; j < NX; ++j) {
            x[j] = plan.x[(k * NX) + j];
        }
        for (j = 0u; j < 64u; ++j) {
            const double s = ((double)j + 0.5) / 64.0;
            const double a = plan.u[k] + s * (plan.u[k + 1u] - plan.u[k]);
            const double dt = h / 64.0;
            /* midpoint-exact for constant acceleration over the small step */
            x[0] += dt * x[2] + 0.5 * dt * dt * 0.1 * cos(a);
            x[1] += dt * x[3] + 0.5 * dt * dt * 0.1 * sin(a);
            x[2] += dt * 0.1 * cos(a);
            x[3] += dt * 0.1 * sin(a);
            {
                const double dx = x[0] - fs.centre[0];
                const double dy = x[1] - fs.centre[1];
                assert_true(sqrt(dx * dx + dy * dy) >= fs.radius - 2.0e-3);
            }
        }
    }
}

/* req: OGK-NMPC-016 */
static void test_init_problem_checks(void **state)
{
    free_space_t fs = { 0.1, { 1.0, 0.0 }, { 0.0, 0.0 }, 0.0 };
    ogk_nmpc_config_t cfg;
    ogk_ocp_problem_t broken;
    size_t i;
    (void)state;
    settings(&cfg, OGK_NMPC_HESSIAN_BFGS);
    OGK_ASSERT_STATUS(ogk_nmpc_init_problem(NULL, &cfg, &free_space, &fs), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_nmpc_init_problem(&ctx, NULL, &free_space, &fs), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_nmpc_init_problem(&ctx, &cfg, NULL, &fs), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_nmpc_init_problem(&ctx, &cfg, &free_space, NULL), OGK_E_NULL);
    /* each required callback missing (update is optional) */
    for (i = 0u; i < 8u; ++i) {
        broken = free_space;
        switch (i) {
        case 0u: broken.structure = NULL; break;
        case 1u: broken.dynamics = NULL; break;
        case 2u: broken.dynamics_hess = NULL; break;
        case 3u: broken.target = NULL; break;
        case 4u: broken.keepout_radius = NULL; break;
        case 5u: broken.keepout_distance = NULL; break;
        case 6u: broken.model_key = NULL; break;
        default: broken.state_valid = NULL; break;
        }
        OGK_ASSERT_STATUS(ogk_nmpc_init_problem(&ctx, &cfg, &broken, &fs), OGK_E_CONFIG);
        OGK_ASSERT_STATUS(ogk_nmpc_reset(&ctx), OGK_E_NOT_INIT);
    }
    /* the solver's settings are checked as ogk_nmpc_init checks them; the heliocentric fields are not read */
    cfg.tol_feas = NAN;
    OGK_ASSERT_STATUS(ogk_nmpc_init_problem(&ctx, &cfg, &free_space, &fs), OGK_E_NONFINITE);
    settings(&cfg, OGK_NMPC_HESSIAN_BFGS);
    cfg.nodes = 0u;
    OGK_ASSERT_STATUS(ogk_nmpc_init_problem(&ctx, &cfg, &free_space, &fs), OGK_E_CONFIG);
    settings(&cfg, OGK_NMPC_HESSIAN_BFGS);
    cfg.mu = NAN;
    cfg.target_radius = -1.0;
    OGK_ASSERT_STATUS(ogk_nmpc_init_problem(&ctx, &cfg, &free_space, &fs), OGK_OK);
    /* a state outside the problem's domain (m <= 0) */
    {
        ogk_nmpc_plan_t plan;
        guess(&fs, 8.0, 0.0, &plan);
        plan.x[3 * NX + 4] = 0.0;
        OGK_ASSERT_STATUS(ogk_nmpc_load_plan(&ctx, &plan), OGK_E_RANGE);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_min_time_against_bang_bang),
        cmocka_unit_test(test_keepout_disc_on_the_line),
        cmocka_unit_test(test_init_problem_checks),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
