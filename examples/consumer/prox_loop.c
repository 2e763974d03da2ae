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

static ogk_prox_t prox;
static ogk_nmpc_plan_t plan;

static void mission(ogk_prox_config_t *cfg)
{
    const double tu = 1.0 / sqrt(3.986004418e14 / (6.9e6 * 6.9e6 * 6.9e6)); /* [s] 1 / mean motion */
    const double mu = 180.0;                                                /* [kg] initial mass */
    (void)ogk_prox_config_default(cfg);
    cfg->model.thrust_max = 0.8 / (mu * 1000.0 / (tu * tu)); /* 0.8 N */
    cfg->model.mass_flow_max = (0.8 / 2100.0) / (mu / tu);  /* exhaust speed 2,100 m/s */
    cfg->model.hold[1] = -0.25;
    cfg->model.n_keepout = 1u;
    cfg->model.keepout_centre[0] = 0.3;
    cfg->model.keepout_centre[1] = 0.62;
    cfg->model.keepout_radius[0] = 0.15;
    cfg->solver.nodes = NODES;
    cfg->solver.rk4_steps = 8u;
    cfg->solver.horizon_min = 1000.0 / tu;
    cfg->solver.horizon_max = 7000.0 / tu;
    cfg->solver.mass_min = 140.0 / mu;
    /* J = m_0 - m_N is small against MU: converge on stationarity, with the exact Hessian */
    cfg->solver.hessian = OGK_NMPC_HESSIAN_EXACT;
    cfg->solver.max_iter_cold = 500u;
    cfg->solver.tol_obj = 0.0;
    cfg->solver.tol_stat = 1.0e-9;
}

/* The guess: the straight line to the hold point bowed away from the disc, at rest at the end. */
static void guess(const ogk_prox_config_t *cfg, const double *x0)
{
    const double t_f = 0.5 * (cfg->solver.horizon_min + cfg->solver.horizon_max);
    const double cx = cfg->model.keepout_centre[0];
    const double cy = cfg->model.keepout_centre[1];
    const double mx = 0.5 * (x0[0] + cfg->model.hold[0]);
    const double my = 0.5 * (x0[1] + cfg->model.hold[1]);
    const double dist = hypot(mx - cx, my - cy);
    const double bulge = fmax(0.0, (1.5 * cfg->model.keepout_radius[0]) - dist);
    const double h = t_f / (double)NODES;
    uint32_t k;
    (void)memset(&plan, 0, sizeof plan);
    plan.horizon = t_f;
    plan.nodes = NODES;
    plan.nu = 2u;
    for (k = 0u; k <= NODES; ++k) {
        const double tau = (double)k / (double)NODES;
        plan.x[(k * NX) + 0u] = x0[0] + ((cfg->model.hold[0] - x0[0]) * tau) + (bulge * sin(PI * tau) * (mx - cx) / dist);
        plan.x[(k * NX) + 1u] = x0[1] + ((cfg->model.hold[1] - x0[1]) * tau) + (bulge * sin(PI * tau) * (my - cy) / dist);
        plan.x[(k * NX) + 4u] = 1.0;
    }
    for (k = 0u; k <= NODES; ++k) {
        const uint32_t a = (k == 0u) ? 0u : (k - 1u);
        const uint32_t b = (k == NODES) ? NODES : (k + 1u);
        if (k < NODES) {
            plan.x[(k * NX) + 2u] = (plan.x[(b * NX) + 0u] - plan.x[(a * NX) + 0u]) / ((double)(b - a) * h);
            plan.x[(k * NX) + 3u] = (plan.x[(b * NX) + 1u] - plan.x[(a * NX) + 1u]) / ((double)(b - a) * h);
        }
        plan.u[(k * 2u) + 0u] = atan2(plan.x[(k * NX) + 3u], plan.x[(k * NX) + 2u]);
        plan.u[(k * 2u) + 1u] = 0.5;
    }
}

int fly_prox(void)
{
    ogk_prox_config_t cfg;
    ogk_nmpc_input_t in = {0.0, {0.0, 1.5, 0.0, 0.0, 1.0}};
    ogk_nmpc_report_t rep;
    ogk_thrust_cmd_t cmd;
    const double *xf;
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
        clearance = fmin(clearance, hypot(plan.x[(k * NX) + 0u] - 0.3, plan.x[(k * NX) + 1u] - 0.62) - 0.15);
    }
    ok = ok && (fabs(xf[0] - cfg.model.hold[0]) < 1e-9) && (fabs(xf[1] - cfg.model.hold[1]) < 1e-9) &&
         (fabs(xf[2]) < 1e-9) && (fabs(xf[3]) < 1e-9) && (xf[4] >= cfg.solver.mass_min) && (clearance > -1e-9);
    for (k = 0u; ok && (k < NODES); ++k) {
        ok = (ogk_prox_thrust_cmd(&prox, (double)k * rep.t_f / (double)NODES, &cmd) == OGK_OK) &&
             (cmd.throttle >= 0.0) && (cmd.throttle <= 1.0);
    }
    (void)snprintf(detail, sizeof detail, "hold point at rest, %.2f m/s of delta-v, disc cleared by %.1f m, %u SQP iterations",
                   2100.0 * log(1.0 / xf[4]), 1000.0 * clearance, (unsigned)rep.sqp_iterations);
    return consumer_verdict("prox", ok, detail);
}
