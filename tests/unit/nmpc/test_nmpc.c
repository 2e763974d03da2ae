/* test_nmpc.c -- the receding-horizon NMPC (ogk/nmpc.h, docs/design/nmpc.md):
 *   - configuration defaults and every init rejection;
 *   - the predictive model against eq. (11) written out here, and its third
 *     bodies against a Cartesian computation (inertial vectors rotated into
 *     the spacecraft's polar axes);
 *   - the sensitivities of one shooting interval against central finite
 *     differences (solar-electric engine, two third bodies: every column);
 *   - its second derivatives weighted by a multiplier (the exact SQP
 *     Hessian's block) against central differences of w . dF/dp, for that
 *     model and for the constant engine without bodies;
 *   - the SQP on a problem with a known solution: the near-field-free radial
 *     minimum-time transfer, t* = 2 sqrt(D / a) (accelerate, then brake), the
 *     discrete optimum above it and closer with more nodes; with the exact
 *     Hessian too (fewer iterations), and its Earth-to-Mars open loop and
 *     replans at BFGS's fully converged optimum;
 *   - a coast rendezvous (minimum fuel, the target on the spacecraft's own
 *     orbit): zero fuel;
 *   - the strategies (SNNS drop, CNCN regrid), the command, a failed solve
 *     flying the previous plan with the SAFE flag, bad inputs, reset. */
#include "ogk_test.h"

/* Central differences in float (ogk_test.h): the step FD_STEP_F = 4e-3 balances the differences'
 * round-off, eps |f| / h (3e-5 for |f| ~ 1), against the truncation h^2 |f'''| / 6 (3e-6); their
 * sum, with values up to about 10 (thrust terms over the mass), is bounded by FD_TOL_F = 1e-3. */
#define FD_STEP_F 4.0e-3
#define FD_TOL_F 1.0e-3

#include <string.h>

#include "nmpc_fixture.h"
#include "ogk/internal/nmpc_test.h" /* ogk_nmpc_model_rhs, ogk_nmpc_interval */
#include "ogk/nmpc.h"
#include "ogk/types.h"

#define NX OGK_NMPC_NX
#define PI 3.14159265358979323846

static ogk_nmpc_t ctx;
static ogk_nmpc_t ctx2;
static ogk_nmpc_plan_t plan;
static ogk_nmpc_plan_t plan2;

static void mars_config(ogk_nmpc_config_t *c, uint32_t nodes)
{
    nmpc_fx_mars(c, nodes);
}

/* The solar-electric, throttled engine with Earth- and Mars-like bodies: every term of eqs. (11)-(14). */
static void solar_two_bodies_config(ogk_nmpc_config_t *c)
{
    mars_config(c, 8u);
    c->engine = OGK_NMPC_ENGINE_THROTTLED;
    nmpc_fx_solar(c, 1.0000000002, 0.05);
    c->n_bodies = 2u;
    nmpc_fx_body(c, 0u, 3.0e-6, 1.0, -0.1, 1.0);
    nmpc_fx_body(c, 1u, 3.2e-7, 1.52, 2.27, 0.53);
}

static void mars_guess(const ogk_nmpc_config_t *c, uint32_t nodes, double t_f, ogk_nmpc_plan_t *p)
{
    nmpc_fx_mars_guess(c, nodes, t_f, p);
}

/* req: OGK-NMPC-008 */
static void test_config_default_and_init(void **state)
{
    ogk_nmpc_config_t c;
    (void)state;
    OGK_ASSERT_STATUS(ogk_nmpc_config_default(NULL), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_nmpc_config_default(&c), OGK_OK);
    OGK_ASSERT_NEAR(c.mu, 1.0, 0.0);
    assert_int_equal((int)c.nodes, 30);
    assert_int_equal((int)c.rk4_steps, 8);
    assert_int_equal((int)c.strategy, (int)OGK_NMPC_SNNS);
    assert_int_equal((int)c.objective, (int)OGK_NMPC_MIN_TIME);
    /* the mission data are unset: rejected */
    OGK_ASSERT_STATUS(ogk_nmpc_init(&ctx, &c), OGK_E_CONFIG);
    OGK_ASSERT_STATUS(ogk_nmpc_reset(&ctx), OGK_E_NOT_INIT);
    mars_config(&c, 8u);
    OGK_ASSERT_STATUS(ogk_nmpc_init(NULL, &c), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_nmpc_init(&ctx, NULL), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_nmpc_init(&ctx, &c), OGK_OK);
    {
        ogk_nmpc_config_t bad = c;
        bad.target_rate = NAN;
        OGK_ASSERT_STATUS(ogk_nmpc_init(&ctx2, &bad), OGK_E_NONFINITE);
        bad = c;
        bad.nodes = OGK_NMPC_MAX_NODES + 1u;
        OGK_ASSERT_STATUS(ogk_nmpc_init(&ctx2, &bad), OGK_E_CONFIG);
        bad = c;
        bad.rk4_steps = 0u;
        OGK_ASSERT_STATUS(ogk_nmpc_init(&ctx2, &bad), OGK_E_CONFIG);
        bad = c;
        bad.horizon_max = bad.horizon_min;
        OGK_ASSERT_STATUS(ogk_nmpc_init(&ctx2, &bad), OGK_E_CONFIG);
        bad = c;
        bad.strategy = 7u;
        OGK_ASSERT_STATUS(ogk_nmpc_init(&ctx2, &bad), OGK_E_CONFIG);
        bad = c;
        bad.doubling_max_nodes = OGK_NMPC_MAX_NODES;
        OGK_ASSERT_STATUS(ogk_nmpc_init(&ctx2, &bad), OGK_E_CONFIG);
        bad = c;
        bad.n_bodies = 1u;
        bad.body_radius[0] = 0.0;
        OGK_ASSERT_STATUS(ogk_nmpc_init(&ctx2, &bad), OGK_E_CONFIG);
        /* a rejected init leaves the context unusable */
        OGK_ASSERT_STATUS(ogk_nmpc_reset(&ctx2), OGK_E_NOT_INIT);
    }
}

/* req: OGK-NMPC-001 */
static void test_model_closed_form(void **state)
{
    ogk_nmpc_config_t c;
    const ogk_real_t x[NX] = { 1.2, 0.3, 0.05, 0.9, 0.8 };
    const ogk_real_t u[1] = { 0.7 };
    ogk_real_t xdot[NX];
    const double acc = 0.05621056 / 0.8;
    (void)state;
    mars_config(&c, 8u);
    OGK_ASSERT_STATUS(ogk_nmpc_init(&ctx, &c), OGK_OK);
    OGK_ASSERT_STATUS(ogk_nmpc_model_rhs(&ctx, 0.0, x, u, xdot), OGK_OK);
    /* eq. (11) and (13) with mu = 1 */
    /* float: measured worst 7.5e-10 on M4F and host */
    OGK_ASSERT_NEAR(xdot[0], 0.05, OGK_TEST_TOL(1e-15, 1e-8));
    /* float: measured worst 6e-8 on M4F and host */
    OGK_ASSERT_NEAR(xdot[1], 0.9 / 1.2, OGK_TEST_TOL(1e-15, 1e-6));
    /* float: measured worst 2.5e-8 on M4F and host */
    OGK_ASSERT_NEAR(xdot[2], 0.81 / 1.2 - 1.0 / 1.44 + acc * cos(0.7), OGK_TEST_TOL(1e-15, 5e-7));
    /* float: measured worst 1.5e-9 on M4F and host */
    OGK_ASSERT_NEAR(xdot[3], -0.9 * 0.05 / 1.2 + acc * sin(0.7), OGK_TEST_TOL(1e-15, 2e-8));
    /* float: measured worst 1.1e-9 on M4F and host */
    OGK_ASSERT_NEAR(xdot[4], -0.05690745, OGK_TEST_TOL(1e-15, 2e-8));
    {
        const ogk_real_t bad[NX] = { -1.0, 0.0, 0.0, 1.0, 1.0 };
        OGK_ASSERT_STATUS(ogk_nmpc_model_rhs(&ctx, 0.0, bad, u, xdot), OGK_E_NONFINITE);
    }
}

/* req: OGK-NMPC-001 */
static void test_third_bodies_cartesian(void **state)
{
    ogk_nmpc_config_t c;
    /* 0.014 LU from the first body at t (its phase 0.1 + 0.37) */
    const ogk_real_t x[NX] = { 1.01, 0.46, 0.0, 1.0, 1.0 };
    const ogk_real_t u[1] = { 0.0 };
    ogk_real_t with_b[NX];
    ogk_real_t without_b[NX];
    const double t = 0.37;
    double ax = 0.0;
    double ay = 0.0;
    uint32_t b;
    (void)state;
    mars_config(&c, 8u);
    OGK_ASSERT_STATUS(ogk_nmpc_init(&ctx, &c), OGK_OK);
    OGK_ASSERT_STATUS(ogk_nmpc_model_rhs(&ctx, t, x, u, without_b), OGK_OK);
    c.n_bodies = 2u;
    nmpc_fx_body(&c, 0u, 3.0e-6, 1.0, 0.1, 1.0);
    nmpc_fx_body(&c, 1u, 3.2e-7, 1.52, 2.27, 0.53);
    OGK_ASSERT_STATUS(ogk_nmpc_init(&ctx, &c), OGK_OK);
    OGK_ASSERT_STATUS(ogk_nmpc_model_rhs(&ctx, t, x, u, with_b), OGK_OK);
    /* inertial vectors: spacecraft, bodies; direct and indirect terms */
    for (b = 0u; b < 2u; ++b) {
        const double phi = c.body_phase0[b] + c.body_rate[b] * t;
        const double bx = c.body_radius[b] * cos(phi);
        const double by = c.body_radius[b] * sin(phi);
        const double dx = x[0] * cos(x[1]) - bx;
        const double dy = x[0] * sin(x[1]) - by;
        const double d3 = pow(dx * dx + dy * dy, 1.5);
        const double r3 = pow(c.body_radius[b], 3.0);
        ax += -c.body_mu[b] * dx / d3 - c.body_mu[b] * bx / r3;
        ay += -c.body_mu[b] * dy / d3 - c.body_mu[b] * by / r3;
    }
    /* float: measured worst relative 1.9e-7 on M4F and host */
    OGK_ASSERT_REL(with_b[2] - without_b[2], ax * cos(x[1]) + ay * sin(x[1]), OGK_TEST_TOL(1e-9, 2e-6), 1e-12);
    /* float: measured worst relative 1.1e-6 on M4F and host */
    OGK_ASSERT_REL(with_b[3] - without_b[3], -ax * sin(x[1]) + ay * cos(x[1]), OGK_TEST_TOL(1e-9, 2e-5), 1e-12);
    /* Earth's pull at 0.01 LU dominates the field there: the check is not vacuous */
    assert_true(fabs(ax) > 1.0e-2);
}

/* req: OGK-NMPC-002 */
static void test_interval_sensitivities(void **state)
{
    ogk_nmpc_config_t c;
    const ogk_real_t x0[NX] = { 1.01, 0.05, 0.02, 0.98, 0.9 };
    const ogk_real_t u0[2] = { 0.7, 0.6 };
    const ogk_real_t u1[2] = { 1.9, 0.3 };
    const double t0 = 0.3;
    const double h = 0.2;
    const double eps = OGK_TEST_PICK(1.0e-6, FD_STEP_F);
    ogk_real_t x1[NX];
    ogk_real_t fx[NX * NX];
    ogk_real_t fu0[NX * 2];
    ogk_real_t fu1[NX * 2];
    ogk_real_t fh[NX];
    ogk_real_t ft[NX];
    double worst = 0.0;
    int col;
    (void)state;
    solar_two_bodies_config(&c);
    OGK_ASSERT_STATUS(ogk_nmpc_init(&ctx, &c), OGK_OK);
    OGK_ASSERT_STATUS(ogk_nmpc_interval(&ctx, t0, h, x0, u0, u1, x1, fx, fu0, fu1, fh, ft), OGK_OK);
    for (col = 0; col < 11; ++col) {
        ogk_real_t xp[NX], xm[NX], u0p[2], u0m[2], u1p[2], u1m[2], a[NX], bm[NX];
        double tp = t0, tm = t0, hp = h, hm = h;
        int i;
        (void)memcpy(xp, x0, sizeof xp);
        (void)memcpy(xm, x0, sizeof xm);
        (void)memcpy(u0p, u0, sizeof u0p);
        (void)memcpy(u0m, u0, sizeof u0m);
        (void)memcpy(u1p, u1, sizeof u1p);
        (void)memcpy(u1m, u1, sizeof u1m);
        if (col < 5) { xp[col] += eps; xm[col] -= eps; }
        else if (col < 7) { u0p[col - 5] += eps; u0m[col - 5] -= eps; }
        else if (col < 9) { u1p[col - 7] += eps; u1m[col - 7] -= eps; }
        else if (col == 9) { hp += eps; hm -= eps; }
        else { tp += eps; tm -= eps; }
        OGK_ASSERT_STATUS(ogk_nmpc_interval(&ctx, tp, hp, xp, u0p, u1p, a, NULL, NULL, NULL, NULL, NULL), OGK_OK);
        OGK_ASSERT_STATUS(ogk_nmpc_interval(&ctx, tm, hm, xm, u0m, u1m, bm, NULL, NULL, NULL, NULL, NULL), OGK_OK);
        for (i = 0; i < (int)NX; ++i) {
            const double fd = (a[i] - bm[i]) / (2.0 * eps);
            double an;
            if (col < 5) { an = fx[i * 5 + col]; }
            else if (col < 7) { an = fu0[i * 2 + col - 5]; }
            else if (col < 9) { an = fu1[i * 2 + col - 7]; }
            else if (col == 9) { an = fh[i]; }
            else { an = ft[i]; }
            OGK_ASSERT_NEAR(an, fd, OGK_TEST_TOL(2e-8, FD_TOL_F));
            worst = fmax(worst, fabs(an));
        }
    }
    assert_true(worst > 0.1); /* the columns are not all zero */
}

/* g = w . dF/dp at p = (x0, u0, u1, h, t0) (5 + 2 nu + 2 entries). */
static void interval_gradient(ogk_real_t t0, ogk_real_t h, const ogk_real_t *x0, const ogk_real_t *u0, const ogk_real_t *u1, /* NOLINT(bugprone-easily-swappable-parameters): the order of ogk_nmpc_interval */
                              const ogk_real_t *w, uint32_t nu, double *g)
{
    ogk_real_t x1[NX];
    ogk_real_t fx[NX * NX];
    ogk_real_t fu0[NX * 2];
    ogk_real_t fu1[NX * 2];
    ogk_real_t fh[NX];
    ogk_real_t ft[NX];
    size_t j;
    size_t i;
    OGK_ASSERT_STATUS(ogk_nmpc_interval(&ctx, t0, h, x0, u0, u1, x1, fx, fu0, fu1, fh, ft), OGK_OK);
    for (j = 0u; j < (NX + (2u * nu) + 2u); ++j) {
        double acc = 0.0;
        for (i = 0u; i < NX; ++i) {
            double d;
            if (j < NX) { d = fx[i * NX + j]; }
            else if (j < NX + nu) { d = fu0[i * nu + (j - NX)]; }
            else if (j < NX + 2u * nu) { d = fu1[i * nu + (j - NX - nu)]; }
            else if (j == NX + 2u * nu) { d = fh[i]; }
            else { d = ft[i]; }
            acc += w[i] * d;
        }
        g[j] = acc;
    }
}

/* The weighted second derivatives of the interval in ctx against central
 * differences of its gradient; returns the largest |entry|. */
static ogk_real_t check_interval_hess(uint32_t nu, const ogk_real_t *u0, const ogk_real_t *u1)
{
    const ogk_real_t x0[NX] = { 1.01, 0.05, 0.02, 0.98, 0.9 };
    const ogk_real_t w[NX] = { 0.7, -1.3, 2.1, 0.4, -0.9 };
    const double t0 = 0.3;
    const double h = 0.2;
    const double eps = OGK_TEST_PICK(1.0e-5, FD_STEP_F);
    const size_t nd = NX + (2u * nu) + 2u;
    ogk_real_t hess[11 * 11];
    double worst = 0.0;
    size_t col;
    OGK_ASSERT_STATUS(ogk_nmpc_interval_hess(&ctx, t0, h, x0, u0, u1, w, hess), OGK_OK);
    for (col = 0u; col < nd; ++col) {
        ogk_real_t p_plus[11];
        ogk_real_t p_minus[11];
        double gp[11];
        double gm[11];
        size_t i;
        (void)memcpy(p_plus, x0, sizeof x0);
        (void)memcpy(&p_plus[NX], u0, nu * sizeof(ogk_real_t));
        (void)memcpy(&p_plus[NX + nu], u1, nu * sizeof(ogk_real_t));
        p_plus[NX + 2u * nu] = h;
        p_plus[NX + 2u * nu + 1u] = t0;
        (void)memcpy(p_minus, p_plus, sizeof p_plus);
        p_plus[col] += eps;
        p_minus[col] -= eps;
        interval_gradient(p_plus[nd - 1u], p_plus[nd - 2u], p_plus, &p_plus[NX], &p_plus[NX + nu], w, nu, gp);
        interval_gradient(p_minus[nd - 1u], p_minus[nd - 2u], p_minus, &p_minus[NX], &p_minus[NX + nu], w, nu, gm);
        for (i = 0u; i < nd; ++i) {
            const double fd = (gp[i] - gm[i]) / (2.0 * eps);
            OGK_ASSERT_NEAR(hess[i * nd + col], fd, OGK_TEST_TOL(1e-7, FD_TOL_F) * (1.0 + fabs(fd)));
            assert_true(hess[i * nd + col] == hess[col * nd + i]); /* symmetric */
            worst = fmax(worst, fabs(hess[i * nd + col]));
        }
    }
    return worst;
}

/* req: OGK-NMPC-002 */
static void test_interval_second_derivatives(void **state)
{
    ogk_nmpc_config_t c;
    const ogk_real_t u0[2] = { 0.7, 0.6 };
    const ogk_real_t u1[2] = { 1.9, 0.3 };
    const ogk_real_t x0[NX] = { 1.01, 0.05, 0.02, 0.98, 0.9 };
    ogk_real_t hess[11 * 11];
    (void)state;
    /* solar-electric, throttled, two third bodies: every entry of eq. (11)-(14)'s Hessian */
    solar_two_bodies_config(&c);
    c.body_softening[1] = 0.01;
    OGK_ASSERT_STATUS(ogk_nmpc_init(&ctx, &c), OGK_OK);
    assert_true(check_interval_hess(2u, u0, u1) > 0.1);
    /* the constant engine without bodies (the benchmark's model) */
    mars_config(&c, 8u);
    OGK_ASSERT_STATUS(ogk_nmpc_init(&ctx, &c), OGK_OK);
    assert_true(check_interval_hess(1u, u0, u1) > 0.1);
    /* bad input */
    OGK_ASSERT_STATUS(ogk_nmpc_interval_hess(&ctx, 0.0, 0.2, NULL, u0, u1, x0, hess), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_nmpc_interval_hess(&ctx, 0.0, 0.0, x0, u0, u1, x0, hess), OGK_E_RANGE);
    OGK_ASSERT_STATUS(ogk_nmpc_interval_hess(&ctx, NAN, 0.2, x0, u0, u1, x0, hess), OGK_E_NONFINITE);
}

/* Radial minimum-time transfer in a near-field-free region: the continuous
 * optimum is t* = 2 sqrt(D / a); the discrete one (piecewise-linear angle)
 * lies above it by O(h^2). */
static double radial_transfer(uint32_t nodes, uint32_t hessian, uint32_t *iterations)
{
    ogk_nmpc_config_t c;
    ogk_nmpc_input_t in;
    ogk_nmpc_report_t rep;
    nmpc_fx_radial(&c, nodes, 4u, 200u);
    c.hessian = hessian;
    if (ogk_nmpc_init(&ctx, &c) != OGK_OK) {
        return -1.0;
    }
    nmpc_fx_radial_guess(nodes, 5.0, &plan);
    if (ogk_nmpc_load_plan(&ctx, &plan) != OGK_OK) {
        return -1.0;
    }
    in.t = 0.0;
    (void)memcpy(in.x, plan.x, sizeof in.x);
    if (ogk_nmpc_solve(&ctx, &in, &rep) != OGK_OK) {
        return -1.0;
    }
    *iterations = rep.sqp_iterations;
    OGK_ASSERT_LE(rep.feas, OGK_TEST_TOL(1.0e-10, NMPC_FX_TOL_F));
    return rep.t_f;
}

/* req: OGK-NMPC-003 */
static void test_sqp_known_solution(void **state)
{
    const double t_star = 2.0 * sqrt(0.5 / 0.1);
    uint32_t it10 = 0u;
    uint32_t it20 = 0u;
    const double t10 = radial_transfer(10u, OGK_NMPC_HESSIAN_BFGS, &it10);
    const double t20 = radial_transfer(20u, OGK_NMPC_HESSIAN_BFGS, &it20);
    (void)state;
    print_message("radial transfer: t* = %.6f, N = 10: %.6f (%u SQP iterations), N = 20: %.6f (%u)\n",
                  t_star, t10, (unsigned)it10, t20, (unsigned)it20);
    assert_true(t10 >= t_star * (1.0 - 1.0e-6));
    assert_true(t20 >= t_star * (1.0 - 1.0e-6));
    assert_true(t10 <= t_star * 1.01);
    assert_true(t20 <= t_star * 1.003);
    /* more nodes, closer: the excess shrinks about fourfold when h halves */
    assert_true((t20 - t_star) < 0.5 * (t10 - t_star));
}

/* The exact Hessian on the same known solution: the same bounds on the
 * discrete optimum, in fewer SQP iterations than BFGS; then the Earth-to-Mars
 * open loop and an SNNS and a CNCN replan (the warm starts) reach BFGS's
 * converged optimum (tol_obj = 0) within 1e-8 TU (0.05 s). */
/* One replan at the plan's first node, the state 1e-4 off the plan's, made
 * by ctx (into rep, whose t_next it reads) and by the reference ctx2. */
static void replan_both_off_plan(ogk_nmpc_input_t *in, ogk_nmpc_report_t *rep, ogk_nmpc_report_t *rep_ref)
{
    OGK_ASSERT_STATUS(ogk_nmpc_get_plan(&ctx, &plan2), OGK_OK);
    in->t = rep->t_next;
    (void)memcpy(in->x, &plan2.x[NX], sizeof in->x);
    in->x[0] += 1.0e-4;
    in->x[3] += 1.0e-4;
    OGK_ASSERT_STATUS(ogk_nmpc_replan(&ctx, in, rep), OGK_OK);
    OGK_ASSERT_STATUS(ogk_nmpc_replan(&ctx2, in, rep_ref), OGK_OK);
}

/* req: OGK-NMPC-003 */
static void test_sqp_exact_hessian(void **state)
{
    const double t_star = 2.0 * sqrt(0.5 / 0.1);
    uint32_t it_bfgs = 0u;
    uint32_t it_exact = 0u;
    ogk_nmpc_config_t c;
    ogk_nmpc_input_t in;
    ogk_nmpc_report_t rep;
    ogk_nmpc_report_t rep_ref;
    double t_exact;
    double t_bfgs;
    uint32_t strategy;
    (void)state;
    t_bfgs = radial_transfer(10u, OGK_NMPC_HESSIAN_BFGS, &it_bfgs);
    t_exact = radial_transfer(10u, OGK_NMPC_HESSIAN_EXACT, &it_exact);
    print_message("radial N = 10: BFGS %.8f (%u SQP iterations), exact %.8f (%u)\n", t_bfgs, (unsigned)it_bfgs,
                  t_exact, (unsigned)it_exact);
    assert_true(t_exact >= t_star * (1.0 - 1.0e-6));
    assert_true(t_exact <= t_star * 1.01);
    assert_true(it_exact < it_bfgs);
    for (strategy = OGK_NMPC_SNNS; strategy <= OGK_NMPC_CNCN; ++strategy) {
        /* the reference: BFGS to the stationarity test alone */
        mars_config(&c, 8u);
        c.strategy = strategy;
        c.tol_obj = 0.0;
        c.tol_stat = OGK_TEST_TOL(1.0e-9, NMPC_FX_TOL_F);
        OGK_ASSERT_STATUS(ogk_nmpc_init(&ctx2, &c), OGK_OK);
        c.tol_obj = 1.0e-7;
        c.tol_stat = OGK_TEST_TOL(1.0e-7, NMPC_FX_TOL_F);
        c.hessian = OGK_NMPC_HESSIAN_EXACT;
        OGK_ASSERT_STATUS(ogk_nmpc_init(&ctx, &c), OGK_OK);
        mars_guess(&c, 8u, 6.4, &plan);
        OGK_ASSERT_STATUS(ogk_nmpc_load_plan(&ctx, &plan), OGK_OK);
        OGK_ASSERT_STATUS(ogk_nmpc_load_plan(&ctx2, &plan), OGK_OK);
        in.t = 0.0;
        (void)memcpy(in.x, plan.x, sizeof in.x);
        OGK_ASSERT_STATUS(ogk_nmpc_solve(&ctx, &in, &rep), OGK_OK);
        OGK_ASSERT_STATUS(ogk_nmpc_solve(&ctx2, &in, &rep_ref), OGK_OK);
        /* float: two solves each stopped at the float SQP's floor (nmpc_sqp.c, OBJ_FLOOR);
         * measured worst 6.2e-6 on the host */
        OGK_ASSERT_NEAR(rep.t_f, rep_ref.t_f, OGK_TEST_TOL(1.0e-8, 1e-4));
        assert_true(rep.feas <= c.tol_feas);
        assert_true(rep.sqp_iterations < rep_ref.sqp_iterations);
        /* one replan at the first node, the state 1e-4 off the plan's */
        replan_both_off_plan(&in, &rep, &rep_ref);
        print_message("%s replan: exact t_f %.12f (%u SQP iterations), BFGS tol_obj 0 %.12f (%u)\n",
                      (strategy == OGK_NMPC_SNNS) ? "SNNS" : "CNCN", rep.t_f, (unsigned)rep.sqp_iterations,
                      rep_ref.t_f, (unsigned)rep_ref.sqp_iterations);
        assert_true((rep.flags & OGK_NMPC_FLAG_CONVERGED) != 0u);
        OGK_ASSERT_NEAR(rep.t_f, rep_ref.t_f, OGK_TEST_TOL(1.0e-8, 1e-4)); /* float: as above */
        assert_true(rep.feas <= c.tol_feas);
        assert_true(rep.sqp_iterations <= rep_ref.sqp_iterations);
    }
}

/* Earth to Mars on `nodes` subintervals, CNCN, the exact Hessian at tol_obj 1e-7: its open loop
 * solved in ctx (from in, into rep), and ctx2 the same context with tol_obj 0 (the stationarity test
 * alone, 1e-9) for the replans: the never-held reference. */
static void exact_cncn_open_loop(uint32_t nodes, ogk_nmpc_input_t *in, ogk_nmpc_report_t *rep)
{
    ogk_nmpc_config_t c;
    mars_config(&c, nodes);
    c.strategy = OGK_NMPC_CNCN;
    c.tol_obj = 1.0e-7;
    c.tol_stat = OGK_TEST_TOL(1.0e-7, NMPC_FX_TOL_F);
    c.hessian = OGK_NMPC_HESSIAN_EXACT;
    OGK_ASSERT_STATUS(ogk_nmpc_init(&ctx, &c), OGK_OK);
    mars_guess(&c, nodes, 6.4, &plan);
    OGK_ASSERT_STATUS(ogk_nmpc_load_plan(&ctx, &plan), OGK_OK);
    in->t = 0.0;
    (void)memcpy(in->x, plan.x, sizeof in->x);
    OGK_ASSERT_STATUS(ogk_nmpc_solve(&ctx, in, rep), OGK_OK);
    (void)memcpy(&ctx2, &ctx, sizeof ctx2);
    ctx2.cfg.tol_obj = 0.0;
    ctx2.cfg.tol_stat = OGK_TEST_TOL(1.0e-9, NMPC_FX_TOL_F);
}

/* The exact Hessian held for the last step (nmpc_sqp.c, HESS_HOLD) at the
 * default tol_obj: from the same open loop and the same perturbed state, the
 * CNCN replan (which holds it once) lands on the t_f of the replan that never
 * holds it (tol_obj = 0: every iteration's Hessian exact, stopped by
 * stationarity alone) within 1e-9 TU, feasible, in no more SQP iterations. */
/* req: OGK-NMPC-003 */
static void test_sqp_exact_hessian_held(void **state)
{
    ogk_nmpc_input_t in;
    ogk_nmpc_report_t rep;
    ogk_nmpc_report_t rep_ref;
    (void)state;
    exact_cncn_open_loop(8u, &in, &rep);
    replan_both_off_plan(&in, &rep, &rep_ref);
    print_message("exact replan: held t_f %.12f (%u SQP iterations), never held %.12f (%u)\n", rep.t_f,
                  (unsigned)rep.sqp_iterations, rep_ref.t_f, (unsigned)rep_ref.sqp_iterations);
    assert_true((rep.flags & OGK_NMPC_FLAG_CONVERGED) != 0u);
    assert_true((rep_ref.flags & OGK_NMPC_FLAG_CONVERGED) != 0u);
    /* float: measured worst 2.3e-5 on M4F and host */
    OGK_ASSERT_NEAR(rep.t_f, rep_ref.t_f, OGK_TEST_TOL(1.0e-9, 2e-4));
    assert_true(rep.feas <= ctx.cfg.tol_feas);
    assert_true(rep.sqp_iterations <= rep_ref.sqp_iterations);
}

/* x moved by k ulps (k > 0 up, k < 0 down). */
static double move_ulps(double x, int k)
{
    int i;
    for (i = 0; i < k; ++i) {
        x = OGK_TEST_NEXTAFTER(x, INFINITY);
    }
    for (i = 0; i > k; --i) {
        x = OGK_TEST_NEXTAFTER(x, -INFINITY);
    }
    return x;
}

/* The exact Hessian held through a warm solve's Newton phase (nmpc_sqp.c,
 * HESS_HOLD_RATE; issue 32). Earth-to-Mars N = 12, the CNCN replan of
 * test_sqp_exact_hessian_held's start: (a) it lands within 1e-9 TU of the
 * never-held replan (tol_obj = 0) and holds the Hessian while each step's
 * predicted |dJ| contracts, so it needs at least 3 SQP iterations fewer
 * (4 against 7; with the rule of session 12, which held it only for a last
 * step within 100 times the stop, 6: this assertion fails there); (b) its
 * SQP count, and its t_f within 1e-12 TU, are the same when any component
 * of the start (x, t) moves by 1, 2, 5 or 20 ulps either way (the bench's
 * scan, `make bench-nmpc-scan`, on a smaller case; the rule of session 12
 * passes (b) too: no ulp move was found that flips it). */
/* req: OGK-NMPC-003 */
static void test_sqp_exact_hessian_held_contracting(void **state)
{
    static const int moves[8] = { -20, -5, -2, -1, 1, 2, 5, 20 };
    ogk_nmpc_input_t in;
    ogk_nmpc_input_t start;
    ogk_nmpc_report_t rep;
    ogk_nmpc_report_t rep_ref;
    uint32_t comp;
    uint32_t m;
    (void)state;
    exact_cncn_open_loop(12u, &in, &rep);
    /* ctx2 first: the never-held reference; ctx (held) is then the saved context of the moves */
    OGK_ASSERT_STATUS(ogk_nmpc_get_plan(&ctx, &plan2), OGK_OK);
    start.t = rep.t_next;
    (void)memcpy(start.x, &plan2.x[NX], sizeof start.x);
    start.x[0] += 1.0e-4;
    start.x[3] += 1.0e-4;
    OGK_ASSERT_STATUS(ogk_nmpc_replan(&ctx2, &start, &rep_ref), OGK_OK);
    (void)memcpy(&ctx2, &ctx, sizeof ctx2);
    OGK_ASSERT_STATUS(ogk_nmpc_replan(&ctx, &start, &rep), OGK_OK);
    print_message("exact CNCN replan N = 12: held t_f %.13f (%u SQP iterations), never held %.13f (%u)\n", rep.t_f,
                  (unsigned)rep.sqp_iterations, rep_ref.t_f, (unsigned)rep_ref.sqp_iterations);
    assert_true((rep.flags & OGK_NMPC_FLAG_CONVERGED) != 0u);
    /* float: measured worst 1.9e-4 on M4F and host */
    OGK_ASSERT_NEAR(rep.t_f, rep_ref.t_f, OGK_TEST_TOL(1.0e-9, 2e-3));
    assert_true(rep.feas <= ctx.cfg.tol_feas);
    assert_true((rep.sqp_iterations + 3u) <= rep_ref.sqp_iterations);
    for (comp = 0u; comp <= NX; ++comp) {
        for (m = 0u; m < 8u; ++m) {
            ogk_nmpc_report_t rep_m;
            in = start;
            if (comp < NX) {
                in.x[comp] = move_ulps(start.x[comp], moves[m]);
            } else {
                in.t = move_ulps(start.t, moves[m]);
            }
            (void)memcpy(&ctx, &ctx2, sizeof ctx);
            OGK_ASSERT_STATUS(ogk_nmpc_replan(&ctx, &in, &rep_m), OGK_OK);
            assert_int_equal(rep_m.sqp_iterations, rep.sqp_iterations);
            /* float: the moved starts stop at other iterates within the float SQP's floor
             * (OBJ_FLOOR); measured worst 6.7e-6 on the host: the same bound as the held replan's
             * t_f above */
            OGK_ASSERT_NEAR(rep_m.t_f, rep.t_f, OGK_TEST_TOL(1.0e-12, 2e-3));
        }
    }
}

/* Minimum fuel with the target on the spacecraft's own circular orbit and
 * phase: coasting is optimal, fuel 0. */
/* req: OGK-NMPC-003 */
static void test_coast_rendezvous_zero_fuel(void **state)
{
    ogk_nmpc_config_t c;
    ogk_nmpc_input_t in;
    ogk_nmpc_report_t rep;
    const uint32_t nodes = 6u;
    uint32_t k;
    (void)state;
    mars_config(&c, nodes);
    c.engine = OGK_NMPC_ENGINE_THROTTLED;
    c.objective = OGK_NMPC_MIN_FUEL;
    c.target_radius = 1.0;
    c.target_phase0 = 0.0;
    c.target_rate = 1.0;
    c.horizon_min = 1.0;
    c.horizon_max = 2.0;
    c.tol_obj = 0.0; /* stationarity only (1e-7, mars_config) */
    OGK_ASSERT_STATUS(ogk_nmpc_init(&ctx, &c), OGK_OK);
    (void)memset(&plan, 0, sizeof plan);
    plan.horizon = 1.5;
    plan.nodes = nodes;
    plan.nu = 2u;
    for (k = 0u; k <= nodes; ++k) {
        const double t = 1.5 * (double)k / (double)nodes;
        plan.x[k * NX + 0u] = 1.0;
        plan.x[k * NX + 1u] = t;
        plan.x[k * NX + 3u] = 1.0;
        plan.x[k * NX + 4u] = 1.0;
        plan.u[2u * k] = 1.0;
        plan.u[2u * k + 1u] = 0.5; /* the guess burns: the solve must learn to coast */
    }
    OGK_ASSERT_STATUS(ogk_nmpc_load_plan(&ctx, &plan), OGK_OK);
    in.t = 0.0;
    (void)memcpy(in.x, plan.x, sizeof in.x);
    OGK_ASSERT_STATUS(ogk_nmpc_solve(&ctx, &in, &rep), OGK_OK);
    /* float: the fuel m_0 - m_N of masses near 1, the mass defects held to the float tol_feas */
    OGK_ASSERT_NEAR(rep.objective, 0.0, OGK_TEST_TOL(1.0e-9, NMPC_FX_TOL_F));
    OGK_ASSERT_STATUS(ogk_nmpc_get_plan(&ctx, &plan2), OGK_OK);
    for (k = 0u; k <= nodes; ++k) {
        /* float: node k's throttle u burns about mass_flow_max u h / 2 (an end node of the
         * trapezoid; h = T / nodes); the fuel is resolved to NMPC_FX_TOL_F (the mass defects'
         * tolerance), a node's throttle to that over mass_flow_max horizon_min / (2 nodes)
         * (measured 4.4e-6 on the host, 3.8e-4 on the M4F) */
        OGK_ASSERT_NEAR(plan2.u[2u * k + 1u], 0.0,
                        OGK_TEST_TOL(1.0e-7, NMPC_FX_TOL_F * 2.0 * nodes / (c.mass_flow_max * c.horizon_min)));
    }
    /* with a time weight the coast is as short as allowed: T = horizon_min,
     * J = 0 fuel + w T */
    c.time_weight = 0.01;
    OGK_ASSERT_STATUS(ogk_nmpc_init(&ctx, &c), OGK_OK);
    OGK_ASSERT_STATUS(ogk_nmpc_load_plan(&ctx, &plan), OGK_OK);
    OGK_ASSERT_STATUS(ogk_nmpc_solve(&ctx, &in, &rep), OGK_OK);
    /* float: T enters J as 0.01 T, J is resolved to NMPC_FX_TOL_F (as above): T to that over 0.01
     * (measured 2.4e-6 on the M4F, 0 on the host) */
    OGK_ASSERT_NEAR(rep.t_f, c.horizon_min, OGK_TEST_TOL(1.0e-9, NMPC_FX_TOL_F / 0.01));
    OGK_ASSERT_NEAR(rep.objective, 0.01 * c.horizon_min, OGK_TEST_TOL(1.0e-9, NMPC_FX_TOL_F)); /* float: as above */
}

/* Earth-to-Mars N = 8: the open loop, then one SNNS and one CNCN replan. */
/* req: OGK-NMPC-004 OGK-NMPC-009 */
static void test_strategies_and_command(void **state)
{
    ogk_nmpc_config_t c;
    ogk_nmpc_input_t in;
    ogk_nmpc_report_t rep;
    ogk_nmpc_command_t cmd;
    double h;
    double t_f;
    (void)state;
    mars_config(&c, 8u);
    OGK_ASSERT_STATUS(ogk_nmpc_init(&ctx, &c), OGK_OK);
    /* no plan yet: the safe command and OGK_E_RANGE */
    OGK_ASSERT_STATUS(ogk_nmpc_command(&ctx, 0.0, &cmd), OGK_E_RANGE);
    assert_int_equal((int)cmd.flags, (int)OGK_THRUST_FLAG_SAFE);
    OGK_ASSERT_NEAR(cmd.throttle, 0.0, 0.0);
    mars_guess(&c, 8u, 6.4, &plan);
    OGK_ASSERT_STATUS(ogk_nmpc_load_plan(&ctx, &plan), OGK_OK);
    in.t = 0.0;
    (void)memcpy(in.x, plan.x, sizeof in.x);
    OGK_ASSERT_STATUS(ogk_nmpc_solve(&ctx, &in, &rep), OGK_OK);
    assert_true((rep.flags & OGK_NMPC_FLAG_CONVERGED) != 0u);
    OGK_ASSERT_LE(rep.feas, OGK_TEST_TOL(1.0e-9, NMPC_FX_TOL_F));
    OGK_ASSERT_STATUS(ogk_nmpc_get_plan(&ctx, &plan), OGK_OK);
    h = plan.horizon / 8.0;
    t_f = plan.t0 + plan.horizon;
    OGK_ASSERT_NEAR(rep.t_next, h, 1e-14);
    /* the command interpolates the node controls */
    OGK_ASSERT_STATUS(ogk_nmpc_command(&ctx, 0.25 * h, &cmd), OGK_OK);
    /* float: measured worst 6e-8 on M4F and host */
    OGK_ASSERT_NEAR(cmd.alpha, 0.75 * plan.u[0] + 0.25 * plan.u[1], OGK_TEST_TOL(1e-14, 1e-6));
    OGK_ASSERT_NEAR(cmd.throttle, 1.0, 0.0);
    assert_true((cmd.flags & OGK_THRUST_FLAG_ENGINE_ON) != 0u);
    OGK_ASSERT_STATUS(ogk_nmpc_command(&ctx, t_f + 1.0, &cmd), OGK_OK);
    assert_true((cmd.law_flags & OGK_NMPC_FLAG_END_OF_PLAN) != 0u);
    OGK_ASSERT_NEAR(cmd.alpha, plan.u[8], 0.0);

    /* SNNS replan at the first node on the plan's own state: N - 1 nodes and
     * a t_f no later (node 1's control no longer shapes the flown interval,
     * one more freedom: the SNNS gain over the open loop), nearly the same */
    in.t = h;
    (void)memcpy(in.x, &plan.x[NX], sizeof in.x);
    OGK_ASSERT_STATUS(ogk_nmpc_replan(&ctx, &in, &rep), OGK_OK);
    assert_int_equal((int)rep.nodes, 7);
    assert_true(rep.t_f <= t_f + 1e-9);
    OGK_ASSERT_NEAR(rep.t_f, t_f, 1e-3);
    assert_true(rep.sqp_iterations <= 30u);

    /* CNCN from the same open loop keeps N and regrids */
    c.strategy = OGK_NMPC_CNCN;
    OGK_ASSERT_STATUS(ogk_nmpc_init(&ctx2, &c), OGK_OK);
    OGK_ASSERT_STATUS(ogk_nmpc_load_plan(&ctx2, &plan), OGK_OK);
    OGK_ASSERT_STATUS(ogk_nmpc_replan(&ctx2, &in, &rep), OGK_OK);
    assert_int_equal((int)rep.nodes, 8);
    assert_true((rep.flags & OGK_NMPC_FLAG_REGRIDDED) != 0u);
    /* float: measured worst 3.7e-8 on M4F and host */
    OGK_ASSERT_NEAR(rep.t_next, h + (rep.t_f - h) / 8.0, OGK_TEST_TOL(1e-12, 5e-7));
    /* another grid, another discrete optimum: within 0.3 d here */
    OGK_ASSERT_NEAR(rep.t_f, t_f, 5e-3);
}

/* The warm start's kept sensitivities (nmpc_sens_cache.c) change no bit: each replan equals the same
 * replan from a copy of the context with every kept sensitivity forgotten (all keys 0: every interval
 * swept again), in status, iterations and plan; for BFGS and the exact Hessian, one and two subintervals
 * dropped, an attracting body (its keys hold t_start), and the model changed between the solves (the kept
 * sensitivities are then of another model and must not be used). */
/* req: OGK-NMPC-004 */
static void test_warm_sensitivities_exact(void **state)
{
    enum { CASES = 6 };
    static const uint32_t hessian[CASES] = { OGK_NMPC_HESSIAN_BFGS, OGK_NMPC_HESSIAN_EXACT, OGK_NMPC_HESSIAN_BFGS,
                                             OGK_NMPC_HESSIAN_BFGS, OGK_NMPC_HESSIAN_BFGS, OGK_NMPC_HESSIAN_BFGS };
    static const uint32_t drop[CASES] = { 1u, 1u, 2u, 1u, 1u, 1u };
    static const uint32_t bodies[CASES] = { 0u, 0u, 0u, 1u, 0u, 0u };
    /* 1: the thrust 1 % up; 2: an unused field's +0 made -0 (another bit, the same value) */
    static const int model_change[CASES] = { 0, 0, 0, 0, 1, 2 };
    ogk_nmpc_config_t c;
    ogk_nmpc_input_t in;
    ogk_nmpc_report_t rep;
    ogk_nmpc_report_t rep_ref;
    uint32_t i;
    (void)state;
    for (i = 0u; i < (uint32_t)CASES; ++i) {
        ogk_status st;
        ogk_status st_ref;
        mars_config(&c, 8u);
        c.hessian = hessian[i];
        c.n_bodies = bodies[i];
        nmpc_fx_body(&c, 0u, 3.0e-6, 1.0, -0.1, 1.0);
        OGK_ASSERT_STATUS(ogk_nmpc_init(&ctx, &c), OGK_OK);
        mars_guess(&c, 8u, 6.4, &plan);
        OGK_ASSERT_STATUS(ogk_nmpc_load_plan(&ctx, &plan), OGK_OK);
        in.t = 0.0;
        (void)memcpy(in.x, plan.x, sizeof in.x);
        OGK_ASSERT_STATUS(ogk_nmpc_solve(&ctx, &in, &rep), OGK_OK);
        OGK_ASSERT_STATUS(ogk_nmpc_get_plan(&ctx, &plan), OGK_OK);
        /* at node drop[i], its state 1e-4 off */
        in.t = plan.t0 + ((double)drop[i] * (plan.horizon / (double)plan.nodes));
        (void)memcpy(in.x, &plan.x[drop[i] * NX], sizeof in.x);
        in.x[0] += 1.0e-4;
        in.x[3] += 1.0e-4;
        if (model_change[i] == 1) {
            /* as a test or a benchmark may set the context's configuration between solves */
            ctx.cfg.thrust_max *= 1.01;
        } else if (model_change[i] == 2) {
            ctx.cfg.body_softening[1] = -0.0;
        }
        (void)memcpy(&ctx2, &ctx, sizeof ctx2);
        (void)memset(ctx2.sens_key, 0, sizeof ctx2.sens_key);
        st = ogk_nmpc_replan(&ctx, &in, &rep);
        st_ref = ogk_nmpc_replan(&ctx2, &in, &rep_ref);
        print_message("case %u: status %d, t_f %.17g, %u SQP iterations (recomputed: %d, %.17g, %u)\n",
                      (unsigned)i, (int)st, rep.t_f, (unsigned)rep.sqp_iterations, (int)st_ref, rep_ref.t_f,
                      (unsigned)rep_ref.sqp_iterations);
        OGK_ASSERT_STATUS(st, OGK_OK);
        OGK_ASSERT_STATUS(st_ref, OGK_OK);
        assert_int_equal((int)rep.nodes, (int)(8u - drop[i]));
        assert_int_equal((int)rep.sqp_iterations, (int)rep_ref.sqp_iterations);
        assert_int_equal((int)rep.qp_iterations, (int)rep_ref.qp_iterations);
        assert_true(memcmp(&rep.t_f, &rep_ref.t_f, sizeof rep.t_f) == 0);
        OGK_ASSERT_STATUS(ogk_nmpc_get_plan(&ctx, &plan), OGK_OK);
        OGK_ASSERT_STATUS(ogk_nmpc_get_plan(&ctx2, &plan2), OGK_OK);
        assert_true(memcmp(&plan, &plan2, sizeof plan) == 0);
    }
}

/* A solve that cannot finish flies the previous plan, says so, and leaves
 * the context usable. */
/* req: OGK-NMPC-005 OGK-NMPC-008 */
static void test_failure_and_bad_input(void **state)
{
    ogk_nmpc_config_t c;
    ogk_nmpc_input_t in;
    ogk_nmpc_report_t rep;
    ogk_nmpc_command_t cmd;
    double alpha_before;
    (void)state;
    mars_config(&c, 8u);
    c.max_iter = 2u;
    c.max_iter_cold = 2u; /* too few from this guess */
    OGK_ASSERT_STATUS(ogk_nmpc_init(&ctx, &c), OGK_OK);
    mars_guess(&c, 8u, 6.4, &plan);
    OGK_ASSERT_STATUS(ogk_nmpc_load_plan(&ctx, &plan), OGK_OK);
    in.t = 0.0;
    (void)memcpy(in.x, plan.x, sizeof in.x);
    OGK_ASSERT_STATUS(ogk_nmpc_solve(&ctx, &in, &rep), OGK_E_ITER_LIMIT);
    assert_true((rep.flags & OGK_NMPC_FLAG_STALE) != 0u);
    OGK_ASSERT_STATUS(ogk_nmpc_command(&ctx, 0.1, &cmd), OGK_OK);
    assert_true((cmd.flags & OGK_THRUST_FLAG_SAFE) != 0u);
    /* float: measured worst 6e-9 on M4F and host */
    OGK_ASSERT_NEAR(cmd.alpha, 0.75 * PI, OGK_TEST_TOL(1e-15, 1e-7)); /* the guess, still flown */
    alpha_before = cmd.alpha;

    /* bad inputs: specific codes, the plan untouched */
    in.x[2] = NAN;
    OGK_ASSERT_STATUS(ogk_nmpc_replan(&ctx, &in, &rep), OGK_E_NONFINITE);
    in.x[2] = 0.0;
    in.x[4] = -1.0;
    OGK_ASSERT_STATUS(ogk_nmpc_replan(&ctx, &in, &rep), OGK_E_RANGE);
    OGK_ASSERT_STATUS(ogk_nmpc_replan(&ctx, NULL, &rep), OGK_E_NULL);
    in.x[4] = 1.0;
    in.t = 2.0 * OGK_NMPC_T_ABS_MAX; /* t + horizon_min would round to t */
    OGK_ASSERT_STATUS(ogk_nmpc_replan(&ctx, &in, &rep), OGK_E_RANGE);
    OGK_ASSERT_STATUS(ogk_nmpc_solve(&ctx, &in, &rep), OGK_E_RANGE);
    in.t = 0.0;
    OGK_ASSERT_STATUS(ogk_nmpc_command(&ctx, NAN, &cmd), OGK_E_NONFINITE);
    assert_int_equal((int)cmd.flags, (int)OGK_THRUST_FLAG_SAFE);
    OGK_ASSERT_STATUS(ogk_nmpc_command(&ctx, 0.1, &cmd), OGK_OK);
    OGK_ASSERT_NEAR(cmd.alpha, alpha_before, 0.0);
    plan.nodes = 0u;
    OGK_ASSERT_STATUS(ogk_nmpc_load_plan(&ctx, &plan), OGK_E_DIM);
    plan.nodes = 8u;
    plan.nu = 2u;
    OGK_ASSERT_STATUS(ogk_nmpc_load_plan(&ctx, &plan), OGK_E_DIM);
    plan.nu = 1u;
    plan.horizon = 1.0e3;
    OGK_ASSERT_STATUS(ogk_nmpc_load_plan(&ctx, &plan), OGK_E_RANGE);
    plan.horizon = 6.4;
    plan.u[3] = INFINITY;
    OGK_ASSERT_STATUS(ogk_nmpc_load_plan(&ctx, &plan), OGK_E_NONFINITE);
}

/* Keep-out: a body (ephemeris only) sits on the radial path; with a keep-out
 * radius every interior node stays that far from it, and the detour costs
 * time against the unconstrained optimum. */
static void keepout_detour(uint32_t hessian)
{
    ogk_nmpc_config_t c;
    ogk_nmpc_input_t in;
    ogk_nmpc_report_t rep;
    double t_free;
    uint32_t k;
    const double radius = 0.08;
    nmpc_fx_radial(&c, 12u, 4u, 300u);
    c.hessian = hessian;
    c.n_bodies = 1u;
    nmpc_fx_body(&c, 0u, 0.0, 1.25, 0.03, 0.0);  /* 0.0375 LU off the radial line */
    OGK_ASSERT_STATUS(ogk_nmpc_init(&ctx, &c), OGK_OK);
    nmpc_fx_radial_guess(12u, 5.0, &plan);
    OGK_ASSERT_STATUS(ogk_nmpc_load_plan(&ctx, &plan), OGK_OK);
    in.t = 0.0;
    (void)memcpy(in.x, plan.x, sizeof in.x);
    OGK_ASSERT_STATUS(ogk_nmpc_solve(&ctx, &in, &rep), OGK_OK);
    t_free = rep.t_f;
    OGK_ASSERT_STATUS(ogk_nmpc_get_plan(&ctx, &plan2), OGK_OK);
    {
        /* without the keep-out the path runs through the body's position */
        double closest = 1.0e9;
        for (k = 1u; k < 12u; ++k) {
            const double r = plan2.x[k * NX];
            const double th = plan2.x[k * NX + 1u];
            closest = fmin(closest, sqrt(r * r + 1.5625 - 2.5 * r * cos(th - 0.03)));
        }
        assert_true(closest < radius);
    }
    c.keepout_radius[0] = radius;
    OGK_ASSERT_STATUS(ogk_nmpc_init(&ctx, &c), OGK_OK);
    OGK_ASSERT_STATUS(ogk_nmpc_load_plan(&ctx, &plan), OGK_OK);
    OGK_ASSERT_STATUS(ogk_nmpc_solve(&ctx, &in, &rep), OGK_OK);
    OGK_ASSERT_STATUS(ogk_nmpc_get_plan(&ctx, &plan2), OGK_OK);
    for (k = 1u; k < 12u; ++k) {
        const double r = plan2.x[k * NX];
        const double th = plan2.x[k * NX + 1u];
        assert_true(sqrt(r * r + 1.5625 - 2.5 * r * cos(th - 0.03)) >= radius - OGK_TEST_TOL(1.0e-8, NMPC_FX_TOL_F));
    }
    print_message("keep-out detour (%s Hessian): t_f %.8f against %.8f unconstrained, %u SQP iterations\n",
                  (hessian == OGK_NMPC_HESSIAN_EXACT) ? "exact" : "BFGS", rep.t_f, t_free,
                  (unsigned)rep.sqp_iterations);
    assert_true(rep.t_f > t_free);
}

/* With both Hessians (the exact one leaves the keep-out's curvature out). */
/* req: OGK-NMPC-007 */
static void test_keepout_detour(void **state)
{
    (void)state;
    keepout_detour(OGK_NMPC_HESSIAN_BFGS);
    keepout_detour(OGK_NMPC_HESSIAN_EXACT);
}

/* The terminal set (terminal_box): the radial transfer to |r - 1.5| <= delta
 * with |v_r| <= nu. Its continuous optimum accelerates, then brakes, and
 * arrives at r = 1.5 - delta still moving out at v_r = nu: a (t1^2) -
 * nu^2 / (2 a) = D - delta and T* = 2 t1 - nu / a; the discrete optimum lies
 * above it by O(h^2), with both Hessians, and below the exact eq. (5)'s. */
static void terminal_set_radial(uint32_t hessian)
{
    ogk_nmpc_config_t c;
    ogk_nmpc_input_t in;
    ogk_nmpc_report_t rep;
    const double a = 0.1;
    const double delta = 0.05;
    const double nu = 0.02;
    const double t1 = sqrt(((0.5 - delta) + ((nu * nu) / (2.0 * a))) / a);
    const double t_star = (2.0 * t1) - (nu / a);
    nmpc_fx_radial(&c, 20u, 4u, 300u);
    c.hessian = hessian;
    c.terminal_box[0] = delta;
    c.terminal_box[1] = 1.0e-3;
    c.terminal_box[2] = nu;
    c.terminal_box[3] = 1.0e-3;
    OGK_ASSERT_STATUS(ogk_nmpc_init(&ctx, &c), OGK_OK);
    nmpc_fx_radial_guess(20u, 5.0, &plan);
    OGK_ASSERT_STATUS(ogk_nmpc_load_plan(&ctx, &plan), OGK_OK);
    in.t = 0.0;
    (void)memcpy(in.x, plan.x, sizeof in.x);
    OGK_ASSERT_STATUS(ogk_nmpc_solve(&ctx, &in, &rep), OGK_OK);
    OGK_ASSERT_STATUS(ogk_nmpc_get_plan(&ctx, &plan2), OGK_OK);
    print_message("terminal set (%s Hessian): t_f %.6f against T* %.6f (exact eq. 5: %.6f), r_N %.8f, v_r,N %.8f, "
                  "%u SQP iterations\n", (hessian == OGK_NMPC_HESSIAN_EXACT) ? "exact" : "BFGS", rep.t_f, t_star,
                  2.0 * sqrt(0.5 / a), plan2.x[20u * NX], plan2.x[20u * NX + 2u], (unsigned)rep.sqp_iterations);
    assert_true(rep.t_f >= t_star * (1.0 - 1.0e-6));
    assert_true(rep.t_f <= t_star * 1.003);
    assert_true(rep.t_f < 2.0 * sqrt(0.5 / a));
    /* it arrives on the box: the near face in r, moving out at nu */
    /* float: measured worst 4.8e-8 on M4F and host */
    OGK_ASSERT_NEAR(plan2.x[20u * NX], 1.5 - delta, OGK_TEST_TOL(1.0e-9, 5e-7));
    /* float: the box's face in v_r, a terminal row held to the float tol_feas (NMPC_FX_TOL_F) */
    OGK_ASSERT_NEAR(plan2.x[20u * NX + 2u], nu, OGK_TEST_TOL(1.0e-9, NMPC_FX_TOL_F));
    OGK_ASSERT_LE(rep.feas, OGK_TEST_TOL(1.0e-10, NMPC_FX_TOL_F));
}

/* req: OGK-NMPC-013 */
static void test_terminal_set(void **state)
{
    (void)state;
    terminal_set_radial(OGK_NMPC_HESSIAN_BFGS);
    terminal_set_radial(OGK_NMPC_HESSIAN_EXACT);
}

/* The propellant limit (mass_min): Earth to Mars at constant thrust, m_N =
 * 1 - mdot T. Below the open loop's final mass it changes nothing; above it
 * no plan meets it (minimum time is the least burn), so the solve fails, the
 * loaded plan stays flown (STALE), and the context stays usable. */
/* req: OGK-NMPC-013 OGK-NMPC-005 */
static void test_propellant_limit(void **state)
{
    ogk_nmpc_config_t c;
    ogk_nmpc_input_t in;
    ogk_nmpc_report_t rep;
    double t_free;
    double m_free;
    (void)state;
    mars_config(&c, 8u);
    c.tol_obj = 0.0; /* converged optima (stationarity 1e-7), comparable to 1e-6 TU */
    mars_guess(&c, 8u, 6.4, &plan);
    in.t = 0.0;
    (void)memcpy(in.x, plan.x, sizeof in.x);
    OGK_ASSERT_STATUS(ogk_nmpc_init(&ctx, &c), OGK_OK);
    OGK_ASSERT_STATUS(ogk_nmpc_load_plan(&ctx, &plan), OGK_OK);
    OGK_ASSERT_STATUS(ogk_nmpc_solve(&ctx, &in, &rep), OGK_OK);
    t_free = rep.t_f;
    OGK_ASSERT_STATUS(ogk_nmpc_get_plan(&ctx, &plan2), OGK_OK);
    m_free = plan2.x[8u * NX + 4u];
    /* float: the final mass is held by the mass defects to the SQP's feasibility tolerance NMPC_FX_TOL_F */
    OGK_ASSERT_NEAR(m_free, 1.0 - (c.mass_flow_max * t_free), OGK_TEST_TOL(1.0e-9, NMPC_FX_TOL_F));
    c.mass_min = m_free - 0.01;
    OGK_ASSERT_STATUS(ogk_nmpc_init(&ctx, &c), OGK_OK);
    OGK_ASSERT_STATUS(ogk_nmpc_load_plan(&ctx, &plan), OGK_OK);
    OGK_ASSERT_STATUS(ogk_nmpc_solve(&ctx, &in, &rep), OGK_OK);
    /* float: stationarity NMPC_FX_TOL_F, t_f comparable to ten times that (as 1e-6 to 1e-7 in double) */
    OGK_ASSERT_NEAR(rep.t_f, t_free, OGK_TEST_TOL(1.0e-6, 10.0 * NMPC_FX_TOL_F));
    c.mass_min = m_free + 0.01;
    OGK_ASSERT_STATUS(ogk_nmpc_init(&ctx, &c), OGK_OK);
    OGK_ASSERT_STATUS(ogk_nmpc_load_plan(&ctx, &plan), OGK_OK);
    assert_true(ogk_nmpc_solve(&ctx, &in, &rep) != OGK_OK);
    assert_true((rep.flags & OGK_NMPC_FLAG_STALE) != 0u);
    OGK_ASSERT_STATUS(ogk_nmpc_get_plan(&ctx, &plan2), OGK_OK);
    assert_true(plan2.horizon == plan.horizon);
    assert_true(memcmp(plan2.u, plan.u, sizeof plan.u) == 0);
}

/* The keep-out along the arcs: a body almost on the radial path, between
 * the optimum's nodes 5 and 6 (r = 1.175 and 1.250, 0.039 and 0.041 LU from
 * it), so that every node of that plan stays outside a 0.03 LU radius while
 * its arc between them passes 0.013 LU from the body. Every RK4 step end of every subinterval (the
 * kernel's own sweep, redone here from the node by ogk_nmpc_interval over
 * the fraction j / M of the subinterval, the control interpolated to match)
 * stays outside the radius, not only the nodes. */
/* req: OGK-NMPC-013 OGK-NMPC-007 */
static void test_keepout_along_arcs(void **state)
{
    ogk_nmpc_config_t c;
    ogk_nmpc_input_t in;
    ogk_nmpc_report_t rep;
    uint32_t k;
    uint32_t j;
    const uint32_t nodes = 12u;
    const uint32_t steps = 4u;
    const double radius = 0.03;
    const double r_b = 1.212;
    const double phase = 0.002;
    double closest = 1.0e9;
    double closest_node = 1.0e9;
    (void)state;
    nmpc_fx_radial(&c, nodes, steps, 300u);
    c.n_bodies = 1u;
    nmpc_fx_body(&c, 0u, 0.0, r_b, phase, 0.0);
    /* the straight optimum first (no keep-out), then re-solved from it with the keep-out: its nodes
     * all satisfy it, its arc does not */
    OGK_ASSERT_STATUS(ogk_nmpc_init(&ctx, &c), OGK_OK);
    nmpc_fx_radial_guess(nodes, 5.0, &plan);
    OGK_ASSERT_STATUS(ogk_nmpc_load_plan(&ctx, &plan), OGK_OK);
    in.t = 0.0;
    (void)memcpy(in.x, plan.x, sizeof in.x);
    OGK_ASSERT_STATUS(ogk_nmpc_solve(&ctx, &in, &rep), OGK_OK);
    OGK_ASSERT_STATUS(ogk_nmpc_get_plan(&ctx, &plan), OGK_OK);
    c.keepout_radius[0] = radius;
    OGK_ASSERT_STATUS(ogk_nmpc_init(&ctx, &c), OGK_OK);
    OGK_ASSERT_STATUS(ogk_nmpc_load_plan(&ctx, &plan), OGK_OK);
    OGK_ASSERT_STATUS(ogk_nmpc_solve(&ctx, &in, &rep), OGK_OK);
    OGK_ASSERT_STATUS(ogk_nmpc_get_plan(&ctx, &plan2), OGK_OK);
    for (k = 0u; k < nodes; ++k) {
        const double h = plan2.horizon / (double)nodes;
        const double rn = plan2.x[k * NX];
        const double thn = plan2.x[k * NX + 1u];
        closest_node = fmin(closest_node, sqrt(rn * rn + r_b * r_b - 2.0 * rn * r_b * cos(thn - phase)));
        for (j = 1u; j < steps; ++j) {
            const double frac = (double)j / (double)steps;
            const ogk_real_t u1 = plan2.u[k] + (frac * (plan2.u[k + 1u] - plan2.u[k]));
            ogk_real_t xs[NX];
            double r;
            double th;
            OGK_ASSERT_STATUS(ogk_nmpc_interval(&ctx, plan2.t0 + ((double)k * h), frac * h, &plan2.x[k * NX],
                                                &plan2.u[k], &u1, xs, NULL, NULL, NULL, NULL, NULL), OGK_OK);
            r = xs[0];
            th = xs[1];
            closest = fmin(closest, sqrt(r * r + r_b * r_b - 2.0 * r * r_b * cos(th - phase)));
        }
    }
    print_message("keep-out along the arcs: closest step end %.9f, closest node %.9f, radius %.9f, t_f %.6f\n",
                  closest, closest_node, radius, rep.t_f);
    /* float: the keep-out's violation (radius - distance) is held to the SQP's feasibility tolerance
     * NMPC_FX_TOL_F, 1e-5 of distance, 3.3e-4 of the radius */
    OGK_ASSERT_LE(radius * (1.0 - OGK_TEST_TOL(1.0e-5, NMPC_FX_TOL_F / radius)), closest);
    assert_true(closest_node > radius);
}

/* body_release: a body in the predictive model while the measured state is
 * within its release radius or bound to it (moving with it), out of it for
 * good from the first call beyond on an escape orbit (FLAG_RELEASED once),
 * back after reset. */
/* req: OGK-NMPC-013 OGK-NMPC-008 */
static void test_body_release(void **state)
{
    ogk_nmpc_config_t c;
    ogk_nmpc_input_t in;
    ogk_nmpc_report_t rep;
    const ogk_real_t x_near[NX] = { 1.0, 0.0, 0.0, 1.0, 1.0 };
    const ogk_real_t u[2] = { 1.0, 1.0 };
    ogk_real_t f_on[NX];
    ogk_real_t f_off[NX];
    ogk_real_t f_none[NX];
    (void)state;
    mars_config(&c, 8u);
    c.n_bodies = 1u;
    nmpc_fx_body(&c, 0u, 3.0e-6, 1.0, -0.01, 1.0); /* Earth-like, 0.01 LU from the start */
    c.body_release[0] = 0.05;
    OGK_ASSERT_STATUS(ogk_nmpc_init(&ctx, &c), OGK_OK);
    OGK_ASSERT_STATUS(ogk_nmpc_model_rhs(&ctx, 0.0, x_near, u, f_on), OGK_OK);
    mars_guess(&c, 8u, 6.4, &plan);
    OGK_ASSERT_STATUS(ogk_nmpc_load_plan(&ctx, &plan), OGK_OK);
    in.t = 0.0;
    (void)memcpy(in.x, plan.x, sizeof in.x);
    (void)ogk_nmpc_solve(&ctx, &in, &rep);
    assert_true((rep.flags & OGK_NMPC_FLAG_RELEASED) == 0u);
    OGK_ASSERT_STATUS(ogk_nmpc_model_rhs(&ctx, 0.0, x_near, u, f_off), OGK_OK);
    assert_true(memcmp(f_on, f_off, sizeof f_on) == 0);
    /* 0.1 rad ahead (0.11 LU from the body, beyond 0.05) but moving with it: bound, kept */
    in.x[1] = 0.1;
    in.x[2] = sin(0.11);
    in.x[3] = cos(0.11);
    (void)ogk_nmpc_solve(&ctx, &in, &rep);
    assert_true((rep.flags & OGK_NMPC_FLAG_RELEASED) == 0u);
    OGK_ASSERT_STATUS(ogk_nmpc_model_rhs(&ctx, 0.0, x_near, u, f_off), OGK_OK);
    assert_true(memcmp(f_on, f_off, sizeof f_on) == 0);
    /* on the spacecraft's own circular orbit: 0.11 away at about 0.1 LU/TU, escaping */
    in.x[2] = plan.x[2];
    in.x[3] = plan.x[3];
    (void)ogk_nmpc_solve(&ctx, &in, &rep);
    assert_true((rep.flags & OGK_NMPC_FLAG_RELEASED) != 0u);
    OGK_ASSERT_STATUS(ogk_nmpc_model_rhs(&ctx, 0.0, x_near, u, f_off), OGK_OK);
    c.n_bodies = 0u;
    OGK_ASSERT_STATUS(ogk_nmpc_init(&ctx2, &c), OGK_OK);
    OGK_ASSERT_STATUS(ogk_nmpc_model_rhs(&ctx2, 0.0, x_near, u, f_none), OGK_OK);
    assert_true(memcmp(f_off, f_none, sizeof f_off) == 0);
    assert_true(fabs(f_on[3] - f_none[3]) > 1.0e-3); /* the body pulled */
    /* back inside: released for good */
    in.x[1] = 0.0;
    (void)ogk_nmpc_solve(&ctx, &in, &rep);
    assert_true((rep.flags & OGK_NMPC_FLAG_RELEASED) == 0u);
    OGK_ASSERT_STATUS(ogk_nmpc_model_rhs(&ctx, 0.0, x_near, u, f_off), OGK_OK);
    assert_true(memcmp(f_off, f_none, sizeof f_off) == 0);
    /* reset: in the model again */
    OGK_ASSERT_STATUS(ogk_nmpc_reset(&ctx), OGK_OK);
    OGK_ASSERT_STATUS(ogk_nmpc_model_rhs(&ctx, 0.0, x_near, u, f_off), OGK_OK);
    assert_true(memcmp(f_on, f_off, sizeof f_on) == 0);
}

/* reset gives back the context of a fresh init: the same open loop bit for bit */
/* req: OGK-NMPC-008 */
static void test_reset_equals_init(void **state)
{
    ogk_nmpc_config_t c;
    ogk_nmpc_input_t in;
    ogk_nmpc_report_t rep_a;
    ogk_nmpc_report_t rep_b;
    (void)state;
    mars_config(&c, 6u);
    mars_guess(&c, 6u, 6.4, &plan);
    in.t = 0.0;
    (void)memcpy(in.x, plan.x, sizeof in.x);
    OGK_ASSERT_STATUS(ogk_nmpc_init(&ctx, &c), OGK_OK);
    OGK_ASSERT_STATUS(ogk_nmpc_load_plan(&ctx, &plan), OGK_OK);
    OGK_ASSERT_STATUS(ogk_nmpc_solve(&ctx, &in, &rep_a), OGK_OK);
    OGK_ASSERT_STATUS(ogk_nmpc_reset(&ctx), OGK_OK);
    OGK_ASSERT_STATUS(ogk_nmpc_command(&ctx, 0.0, NULL), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_nmpc_get_plan(&ctx, &plan2), OGK_E_RANGE);
    OGK_ASSERT_STATUS(ogk_nmpc_load_plan(&ctx, &plan), OGK_OK);
    OGK_ASSERT_STATUS(ogk_nmpc_solve(&ctx, &in, &rep_b), OGK_OK);
    assert_int_equal((int)rep_a.sqp_iterations, (int)rep_b.sqp_iterations);
    assert_true(rep_a.t_f == rep_b.t_f);
    assert_true(rep_a.objective == rep_b.objective);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_config_default_and_init),
        cmocka_unit_test(test_model_closed_form),
        cmocka_unit_test(test_third_bodies_cartesian),
        cmocka_unit_test(test_interval_sensitivities),
        cmocka_unit_test(test_interval_second_derivatives),
        cmocka_unit_test(test_sqp_known_solution),
        cmocka_unit_test(test_sqp_exact_hessian),
        cmocka_unit_test(test_sqp_exact_hessian_held),
        cmocka_unit_test(test_sqp_exact_hessian_held_contracting),
        cmocka_unit_test(test_coast_rendezvous_zero_fuel),
        cmocka_unit_test(test_strategies_and_command),
        cmocka_unit_test(test_warm_sensitivities_exact),
        cmocka_unit_test(test_failure_and_bad_input),
        cmocka_unit_test(test_keepout_detour),
        cmocka_unit_test(test_terminal_set),
        cmocka_unit_test(test_propellant_limit),
        cmocka_unit_test(test_keepout_along_arcs),
        cmocka_unit_test(test_body_release),
        cmocka_unit_test(test_reset_equals_init),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
