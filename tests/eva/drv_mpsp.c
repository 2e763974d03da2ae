/* tests/eva/drv_mpsp.c -- EVA driver of ogk_mpsp_* (ogk/mpsp.h) at small
 * compile-time sizes (eva_gate.py: Fourier order 1, 2 RK4 grid steps, 2
 * switches, sensitivity blocks of 3, a log of 4). The mission is the Apophis
 * transfer of scenarios/apophis_cubesat.toml in its normalised units (mu = 1;
 * T_max = 1.5 mN / (25 kg LU/TU^2) = 0.0101; c = 3000 s g0 / VU = 0.988;
 * t_f = 1156 d = 19.89 TU; Table 2's boundary states), basis period 2 t_f.
 * Ranges: nominal weights of lambda_v in +-2 and lambda_m(t0) in [-1, 1],
 * any finite time for the control, command and state queries; the initial
 * state within 1e-3 LU and LU/TU of Table 2's, mass in [0.9, 1] MU,
 * thrust_scale in [0.9, 1.1] (Table 6: eta up to +-10 %).
 * Gated calls: init (nominal segment count given), control, thrust_cmd and
 * state_at with no trajectory held, reset, the bad inputs. Behind macros,
 * not gated: -DEVA_MPSP_PROPAGATE (propagate, trajectory, state_at and
 * thrust_cmd on it) and -DEVA_MPSP_SOLVE (sensitivity, newton_update, one
 * Newton step of solve): the RK4 switch bisection did not finish in 300 s
 * (docs/evidence/eva.md, as rk4 with a switching function). */
#include "eva_driver.h"
#include "ogk/mpsp.h"

#define TF_TU 19.886

static void config_apophis(ogk_mpsp_config_t *c)
{
    static const double x0[OGK_MPSP_NX0] = {1.001367, 0.140622, -6.594513e-6, -0.155386, 0.986258,
                                            -4.827818e-5, 1.0};
    static const double rf[3] = {-1.044138, -0.122918, -0.018183};
    static const double vf[3] = {0.222668, -0.875235, 0.051944};
    size_t i;

    (void)ogk_mpsp_config_default(c);
    c->mu = 1.0;
    c->t_max = 0.0101;
    c->c_exhaust = 0.988;
    c->t0 = 0.0;
    c->tf = TF_TU;
    for (i = 0u; i < OGK_MPSP_NX0; ++i) {
        c->x0_nom[i] = x0[i];
    }
    for (i = 0u; i < 3u; ++i) {
        c->r_f[i] = rf[i];
        c->v_f[i] = vf[i];
    }
    c->fourier_order = 1u;
    c->fourier_period = 2.0 * TF_TU;
    c->fourier_t_ref = 0.0;
    c->h_max = TF_TU / 2.0;
    for (i = 0u; i < OGK_MPSP_MAX_WEIGHTS; ++i) {
        c->r_eps[i] = 1.0;
        c->weights_nom[i] = eva_in(-2.0, 2.0);
    }
    c->lambda_m0_nom = eva_in(-1.0, 1.0);
    c->tol_r = 1.0e-6;
    c->tol_v = 1.0e-6;
    c->tol_lambda_m = 1.0e-6;
    c->max_newton = 1u;
    c->max_outer = 1u;
    c->n_seg_nom = 3u;
}

static void x0_in(const ogk_mpsp_config_t *c, double *x0)
{
    size_t i;
    for (i = 0u; i < 6u; ++i) {
        x0[i] = eva_in(c->x0_nom[i] - 1.0e-3, c->x0_nom[i] + 1.0e-3);
    }
    x0[6] = eva_in(0.9, 1.0);
}

void eva_mpsp(void)
{
    static ogk_mpsp_t ctx;
    static ogk_mpsp_result_t res;
    static double traj_t[OGK_MPSP_MAX_NODES];
    static double traj_x[OGK_MPSP_MAX_NODES * OGK_MPSP_NX];
    static uint8_t traj_mode[OGK_MPSP_MAX_NODES];
    ogk_mpsp_config_t cfg;
    ogk_mpsp_prop_t prop;
    ogk_thrust_cmd_t cmd;
    double w[OGK_MPSP_MAX_WEIGHTS];
    double x0[OGK_MPSP_NX0];
    double lv[3];
    double lvd[3];
    double x[OGK_MPSP_NX];
    double dy[OGK_MPSP_NY];
    double lm0;
    size_t count;
    size_t i;

    config_apophis(&cfg);
    if (ogk_mpsp_init(&ctx, &cfg) != OGK_OK) {
        return;
    }
    for (i = 0u; i < OGK_MPSP_MAX_WEIGHTS; ++i) {
        w[i] = eva_in(-2.0, 2.0);
    }
    (void)ogk_mpsp_control(&ctx, w, eva_any_finite(), lv, lvd);
    (void)ogk_mpsp_thrust_cmd(&ctx, eva_any_finite(), &cmd);
    (void)ogk_mpsp_state_at(&ctx, eva_any_finite(), x);
    x0_in(&cfg, x0);
    lm0 = eva_in(-1.0, 1.0);
#ifdef EVA_MPSP_PROPAGATE
    (void)ogk_mpsp_propagate(&ctx, w, lm0, x0, eva_in(0.9, 1.1), &prop);
    (void)ogk_mpsp_trajectory(&ctx, traj_t, traj_x, traj_mode, OGK_MPSP_MAX_NODES, &count);
    (void)ogk_mpsp_state_at(&ctx, eva_any_finite(), x);
    (void)ogk_mpsp_thrust_cmd(&ctx, eva_any_finite(), &cmd);
#endif
#ifdef EVA_MPSP_SOLVE
    if (ogk_mpsp_sensitivity(&ctx, NULL, NULL) == OGK_OK) {
        for (i = 0u; i < OGK_MPSP_NY; ++i) {
            dy[i] = eva_in(-1.0, 1.0);
        }
        (void)ogk_mpsp_newton_update(&ctx, dy, w, &lm0);
    }
    (void)ogk_mpsp_solve(&ctx, x0, eva_in(0.9, 1.1), NULL, &res);
    (void)ogk_mpsp_thrust_cmd(&ctx, eva_any_finite(), &cmd);
#endif
    (void)ogk_mpsp_reset(&ctx);
    (void)ogk_mpsp_solve(&ctx, NULL, 1.0, NULL, &res);
    (void)ogk_mpsp_init(&ctx, NULL);
}
