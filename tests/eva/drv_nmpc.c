/* tests/eva/drv_nmpc.c -- EVA driver of ogk_nmpc_* (ogk/nmpc.h) at small
 * compile-time sizes (eva_gate.py: at most 2 nodes, 2 RK4 steps per
 * subinterval, the QP's limits cut to what 2 nodes need). The mission is the
 * Earth-to-Mars rendezvous of scenarios/rendezvous_*.toml in the normalised
 * units of docs/design/nmpc.md (mu = 1, T_0 = 0.0562, mdot = 0.0569, R_T = 1.5237,
 * theta_T0 = 130 deg), constant engine, minimum time, BFGS, SNNS. The plan
 * has 2 nodes over a horizon in [8, 9] TU with node states within the
 * phase-matched guess's envelope (r in [1, 1.53], v_r in +-0.2, v_theta in
 * [0.8, 1], m in [0.5, 1]), angles in +-3.2 rad and multipliers in +-10.
 * Gated calls: init, load_plan, get_plan, command and thrust_cmd at any
 * finite time, reset, the bad inputs. -DEVA_NMPC_SOLVE adds solve and replan
 * from a measured state of that envelope (one SQP iteration): it did not
 * finish in 200 s (docs/evidence/eva.md). */
#include "eva_driver.h"
#include "ogk/nmpc.h"

#define N_NODES 2u

static void state_in(double *x)
{
    x[0] = eva_in(1.0, 1.53);
    x[1] = eva_in(0.0, 7.0);
    x[2] = eva_in(-0.2, 0.2);
    x[3] = eva_in(0.8, 1.0);
    x[4] = eva_in(0.5, 1.0);
}

void eva_nmpc(void)
{
    static ogk_nmpc_t ctx;
    static ogk_nmpc_plan_t plan;
    static ogk_nmpc_plan_t back;
    ogk_nmpc_config_t cfg;
    ogk_nmpc_input_t in;
    ogk_nmpc_report_t rep;
    ogk_nmpc_command_t cmd;
    ogk_thrust_cmd_t tcmd;
    uint32_t k;

    (void)ogk_nmpc_config_default(&cfg);
    cfg.thrust_max = 0.05621056;
    cfg.mass_flow_max = 0.05690745;
    cfg.target_radius = 1.52367877;
    cfg.target_phase0 = 2.2689280275926285;
    cfg.target_rate = 0.5316984;
    cfg.nodes = N_NODES;
    cfg.rk4_steps = 2u;
    cfg.max_iter = 1u;
    cfg.max_iter_cold = 1u;
    cfg.min_nodes = 1u;
    cfg.doubling_max_nodes = 1u;
    if (ogk_nmpc_init(&ctx, &cfg) != OGK_OK) {
        return;
    }
    plan.t0 = 0.0;
    plan.horizon = eva_in(8.0, 9.0);
    plan.nodes = N_NODES;
    plan.nu = 1u;
    for (k = 0u; k <= N_NODES; ++k) {
        state_in(&plan.x[k * OGK_NMPC_NX]);
        plan.u[k] = eva_in(-3.2, 3.2);
    }
    for (k = 0u; k < OGK_NMPC_NC; ++k) {
        plan.lambda[k] = eva_in(-10.0, 10.0);
    }
    if (ogk_nmpc_load_plan(&ctx, &plan) != OGK_OK) {
        return;
    }
    (void)ogk_nmpc_get_plan(&ctx, &back);
    (void)ogk_nmpc_command(&ctx, eva_any_finite(), &cmd);
    (void)ogk_nmpc_thrust_cmd(&ctx, eva_any_finite(), &tcmd);
#ifdef EVA_NMPC_SOLVE
    in.t = 0.0;
    state_in(in.x);
    (void)ogk_nmpc_solve(&ctx, &in, &rep);
    in.t = eva_in(0.0, 0.5);
    state_in(in.x);
    (void)ogk_nmpc_replan(&ctx, &in, &rep);
    (void)ogk_nmpc_thrust_cmd(&ctx, eva_any_finite(), &tcmd);
#endif
    (void)ogk_nmpc_reset(&ctx);
    (void)ogk_nmpc_command(&ctx, 0.0, &cmd);
    (void)ogk_nmpc_solve(&ctx, NULL, &rep);
    (void)ogk_nmpc_init(&ctx, NULL);
}
