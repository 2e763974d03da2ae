/* nmpc_loop.c -- the heliocentric NMPC (ogk/nmpc.h) on a transfer whose optimum is known: minimum
 * time from r = 1 to r = 1.5 in a nearly field-free region (mu = 1e-9) with a thrust acceleration of
 * 0.1, t* = 2 sqrt(0.5 / 0.1). The open loop must land within 1 % above t*; then the law replans at
 * each plan's next node from the state the plan predicts there (SNNS: the flown subinterval dropped,
 * the node count doubled when that pays), and every replan must converge on an arrival between t*
 * and the open loop's (a finer grid can only come closer to t*). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include <ogk/nmpc.h>

#include "consumer.h"

#define NODES 10u
#define PI 3.14159265358979323846
/* The solver's tolerances: tol_feas 1e-10 and tol_stat 1e-8 in double; in float 1e-5, as
 * tests/unit/nmpc_fixture.h's NMPC_FX_TOL_F (the float SQP's defects and stationarity stop near 5e-7
 * at these unit scales). Two solves agree on t_f to that tolerance. */
#define NMPC_LOOP_TOL_F 1.0e-5

static ogk_nmpc_t nmpc;
static ogk_nmpc_plan_t plan;

/* The guess: a smoothstep in radius over 5 TU, accelerating outward then braking. */
static void radial_guess(ogk_nmpc_plan_t *p)
{
    const double t_guess = 5.0;
    uint32_t k;
    (void)memset(p, 0, sizeof *p);
    p->horizon = (ogk_real_t)t_guess;
    p->nodes = NODES;
    p->nu = 1u;
    for (k = 0u; k <= NODES; ++k) {
        const double tau = (double)k / (double)NODES;
        p->x[(k * OGK_NMPC_NX) + 0u] = (ogk_real_t)(1.0 + (0.5 * ((3.0 * tau * tau) - (2.0 * tau * tau * tau))));
        p->x[(k * OGK_NMPC_NX) + 2u] = (ogk_real_t)(0.5 * ((6.0 * tau) - (6.0 * tau * tau)) / t_guess);
        p->x[(k * OGK_NMPC_NX) + 3u] = (ogk_real_t)sqrt(1.0e-9);
        p->x[(k * OGK_NMPC_NX) + 4u] = 1.0;
        p->u[k] = (ogk_real_t)(((tau < 0.5) ? 0.0 : PI) + 0.01);
    }
}

int fly_nmpc(void)
{
    const double t_star = 2.0 * sqrt(0.5 / 0.1);
    ogk_nmpc_config_t cfg;
    ogk_nmpc_input_t in;
    ogk_nmpc_report_t rep;
    ogk_thrust_cmd_t cmd;
    double t_f_open;
    char detail[160];
    unsigned replans = 0u;
    int ok = ogk_nmpc_config_default(&cfg) == OGK_OK;
    cfg.mu = OGK_R(1.0e-9);
    cfg.thrust_max = OGK_R(0.1);
    cfg.mass_flow_max = 0.0;
    cfg.target_radius = 1.5;
    cfg.nodes = NODES;
    cfg.rk4_steps = 4u;
    cfg.horizon_min = OGK_R(0.1);
    cfg.horizon_max = 20.0;
    cfg.max_iter = 200u;
    cfg.max_iter_cold = 200u;
    cfg.tol_feas = OGK_R(CONSUMER_TOL(1.0e-10, NMPC_LOOP_TOL_F));
    cfg.tol_stat = OGK_R(CONSUMER_TOL(1.0e-8, NMPC_LOOP_TOL_F));
    radial_guess(&plan);
    ok = ok && (ogk_nmpc_init(&nmpc, &cfg) == OGK_OK) && (ogk_nmpc_load_plan(&nmpc, &plan) == OGK_OK);
    in.t = 0.0;
    (void)memcpy(in.x, plan.x, sizeof in.x);
    ok = ok && (ogk_nmpc_solve(&nmpc, &in, &rep) == OGK_OK);
    t_f_open = (double)rep.t_f;
    ok = ok && (t_f_open >= t_star * (1.0 - 1e-6)) && (t_f_open <= t_star * 1.01);
    /* receding horizon: the measured state is the plan's prediction at its next node */
    while (ok && (replans < 4u)) {
        ok = (ogk_nmpc_get_plan(&nmpc, &plan) == OGK_OK) && (plan.nodes > 2u);
        in.t = rep.t_next;
        (void)memcpy(in.x, &plan.x[OGK_NMPC_NX], sizeof in.x);
        ok = ok && (ogk_nmpc_replan(&nmpc, &in, &rep) == OGK_OK) &&
             ((rep.flags & OGK_NMPC_FLAG_CONVERGED) != 0u);
        ok = ok && (ogk_nmpc_thrust_cmd(&nmpc, in.t, &cmd) == OGK_OK) &&
             ((cmd.flags & OGK_THRUST_FLAG_ENGINE_ON) != 0u);
        ok = ok && ((double)rep.t_f >= t_star * (1.0 - 1e-6)) &&
             ((double)rep.t_f <= t_f_open + CONSUMER_TOL(1e-9, NMPC_LOOP_TOL_F));
        ++replans;
    }
    (void)snprintf(detail, sizeof detail, "t_f %.6f TU (t* %.6f), %.6f TU after %u replans",
                   t_f_open, t_star, (double)rep.t_f, replans);
    return consumer_verdict("nmpc", ok, detail);
}
