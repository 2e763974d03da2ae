/* prox_loop.c -- the proximity-approach NMPC (ogk/proximity.h): Clohessy-Wiltshire motion in the
 * target's Hill frame (normalised: LU = 1 km, TU = 1 / n, MU = m_0) on a 6,900 km orbit, 0.8 N at
 * 2,100 m/s on 180 kg, from 1.5 km ahead along-track to a hold point 250 m behind the target, around
 * a keep-out disc of 150 m centred at (300, 620) m. The minimum-fuel open loop must reach the hold
 * point at rest, keep every node out of the disc and stay within the propellant limit; its command is
 * then flown. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include <ogk/proximity.h>

#include "consumer.h"

#define NODES 16u
#define NX OGK_NMPC_NX
#define PI 3.14159265358979323846
/* The solver's stationarity tolerance and the terminal and keep-out bounds: 1e-9 in double; in float
 * 1e-5, as tests/unit/nmpc_fixture.h's NMPC_FX_TOL_F (the float SQP stops near 5e-7 at unit scales),
 * the feasibility tolerance the float kernel holds its constraints to. */
#define PROX_LOOP_TOL CONSUMER_TOL(1.0e-9, 1.0e-5)

static ogk_prox_t prox;
static ogk_nmpc_plan_t plan;

static void mission(ogk_prox_config_t *cfg)
{
    const double tu = 1.0 / sqrt(3.986004418e14 / (6.9e6 * 6.9e6 * 6.9e6)); /* [s] 1 / mean motion */
    const double mu = 180.0;                                                /* [kg] initial mass */
    (void)ogk_prox_config_default(cfg);
    cfg->model.thrust_max = (ogk_real_t)(0.8 / (mu * 1000.0 / (tu * tu))); /* 0.8 N */
    cfg->model.mass_flow_max = (ogk_real_t)((0.8 / 2100.0) / (mu / tu));  /* exhaust speed 2,100 m/s */
    cfg->model.hold[1] = -0.25;
    cfg->model.n_keepout = 1u;
    cfg->model.keepout_centre[0] = OGK_R(0.3);
    cfg->model.keepout_centre[1] = OGK_R(0.62);
    cfg->model.keepout_radius[0] = OGK_R(0.15);
    cfg->solver.nodes = NODES;
    cfg->solver.rk4_steps = 8u;
    cfg->solver.horizon_min = (ogk_real_t)(1000.0 / tu);
    cfg->solver.horizon_max = (ogk_real_t)(7000.0 / tu);
    cfg->solver.mass_min = (ogk_real_t)(140.0 / mu);
    /* J = m_0 - m_N is small against MU: converge on stationarity, with the exact Hessian */
    cfg->solver.hessian = OGK_NMPC_HESSIAN_EXACT;
    cfg->solver.max_iter_cold = 500u;
    cfg->solver.tol_obj = 0.0;
    cfg->solver.tol_stat = OGK_R(PROX_LOOP_TOL);
#if OGK_REAL_SINGLE
    cfg->solver.tol_feas = OGK_R(PROX_LOOP_TOL); /* the default 1e-9 is below float's resolution */
#endif
}

/* The guess: the straight line to the hold point bowed away from the disc, at rest at the end. */
static void guess(const ogk_prox_config_t *cfg, const ogk_real_t *x0)
{
    const double t_f = 0.5 * (double)(cfg->solver.horizon_min + cfg->solver.horizon_max);
    const double cx = (double)cfg->model.keepout_centre[0];
    const double cy = (double)cfg->model.keepout_centre[1];
    const double hx = (double)cfg->model.hold[0];
    const double hy = (double)cfg->model.hold[1];
    const double mx = 0.5 * ((double)x0[0] + hx);
    const double my = 0.5 * ((double)x0[1] + hy);
    const double dist = hypot(mx - cx, my - cy);
    const double bulge = fmax(0.0, (1.5 * (double)cfg->model.keepout_radius[0]) - dist);
    const double h = t_f / (double)NODES;
    uint32_t k;
    (void)memset(&plan, 0, sizeof plan);
    plan.horizon = (ogk_real_t)t_f;
    plan.nodes = NODES;
    plan.nu = 2u;
    for (k = 0u; k <= NODES; ++k) {
        const double tau = (double)k / (double)NODES;
        plan.x[(k * NX) + 0u] =
            (ogk_real_t)((double)x0[0] + ((hx - (double)x0[0]) * tau) + (bulge * sin(PI * tau) * (mx - cx) / dist));
        plan.x[(k * NX) + 1u] =
            (ogk_real_t)((double)x0[1] + ((hy - (double)x0[1]) * tau) + (bulge * sin(PI * tau) * (my - cy) / dist));
        plan.x[(k * NX) + 4u] = 1.0;
    }
    for (k = 0u; k <= NODES; ++k) {
        const uint32_t a = (k == 0u) ? 0u : (k - 1u);
        const uint32_t b = (k == NODES) ? NODES : (k + 1u);
        if (k < NODES) {
            plan.x[(k * NX) + 2u] =
                (ogk_real_t)((double)(plan.x[(b * NX) + 0u] - plan.x[(a * NX) + 0u]) / ((double)(b - a) * h));
            plan.x[(k * NX) + 3u] =
                (ogk_real_t)((double)(plan.x[(b * NX) + 1u] - plan.x[(a * NX) + 1u]) / ((double)(b - a) * h));
        }
        plan.u[(k * 2u) + 0u] = OGK_ATAN2(plan.x[(k * NX) + 3u], plan.x[(k * NX) + 2u]);
        plan.u[(k * 2u) + 1u] = 0.5;
    }
}

int fly_prox(void)
{
    ogk_prox_config_t cfg;
    ogk_nmpc_input_t in = {0.0, {0.0, 1.5, 0.0, 0.0, 1.0}};
    ogk_nmpc_report_t rep;
    ogk_thrust_cmd_t cmd;
    const ogk_real_t *xf;
    double clearance = 1.0e9;
    char detail[160];
    uint32_t k;
    int ok;
    mission(&cfg);
    guess(&cfg, in.x);
    ok = (ogk_prox_init(&prox, &cfg) == OGK_OK) && (ogk_prox_load_plan(&prox, &plan) == OGK_OK) &&
         (ogk_prox_solve(&prox, &in, &rep) == OGK_OK) && (ogk_prox_get_plan(&prox, &plan) == OGK_OK);
    xf = &plan.x[NODES * NX];
    for (k = 0u; k <= NODES; ++k) {
        clearance = fmin(clearance, hypot((double)plan.x[(k * NX) + 0u] - 0.3, (double)plan.x[(k * NX) + 1u] - 0.62) - 0.15);
    }
    ok = ok && (fabs((double)(xf[0] - cfg.model.hold[0])) < PROX_LOOP_TOL) &&
         (fabs((double)(xf[1] - cfg.model.hold[1])) < PROX_LOOP_TOL) && (fabs((double)xf[2]) < PROX_LOOP_TOL) &&
         (fabs((double)xf[3]) < PROX_LOOP_TOL) && (xf[4] >= cfg.solver.mass_min) && (clearance > -PROX_LOOP_TOL);
    for (k = 0u; ok && (k < NODES); ++k) {
        ok = (ogk_prox_thrust_cmd(&prox, (ogk_real_t)k * rep.t_f / (ogk_real_t)NODES, &cmd) == OGK_OK) &&
             (cmd.throttle >= OGK_R(0.0)) && (cmd.throttle <= OGK_R(1.0));
    }
    (void)snprintf(detail, sizeof detail, "hold point at rest, %.2f m/s of delta-v, disc cleared by %.1f m, %u SQP iterations",
                   2100.0 * log(1.0 / (double)xf[4]), 1000.0 * clearance, (unsigned)rep.sqp_iterations);
    return consumer_verdict("prox", ok, detail);
}
