/* mpsp_loop.c -- MPSP (ogk/mpsp.h) on a small normalised two-body transfer (mu = 1, t in [0, 2], a
 * 3rd-order Fourier basis): the nominal's own end state is the target and MPSP first makes the
 * nominal consistent (lambda_m(t_f) = 0); then the engine delivers 5 % less thrust than planned and
 * MPSP must find weights that still meet the target within its tolerances. Their command is flown
 * over the transfer (ogk_mpsp_thrust_cmd: a unit direction, engine on or off by segment). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include <ogk/mpsp.h>

#include "consumer.h"

static const double w_nom[21] = {
    2.0, 0.05, 0.02, 0.6, 0.03, -0.02, 0.01,   /* lambda_v,x */
    0.6, 0.0, 0.2, 0.01, -0.02, 0.0, 0.01,     /* lambda_v,y */
    0.0, 0.05, 0.0, 0.01, 0.0, 0.0, -0.01};    /* lambda_v,z */
static const double x0[7] = {1.0, 0.0, 0.01, 0.0, 1.0, 0.02, 1.0}; /* r, v [LU, LU/TU], m [MU] */

static ogk_mpsp_t mpsp;
static ogk_mpsp_config_t cfg;
static ogk_mpsp_result_t res;

int fly_mpsp(void)
{
    ogk_mpsp_prop_t prop;
    ogk_thrust_cmd_t cmd;
    char detail[160];
    unsigned k;
    unsigned burning = 0u;
    size_t i;
    int ok = ogk_mpsp_config_default(&cfg) == OGK_OK;
    cfg.mu = 1.0;
    cfg.t_max = 0.1;
    cfg.c_exhaust = 1.0;
    cfg.t0 = 0.0;
    cfg.tf = 2.0;
    (void)memcpy(cfg.x0_nom, x0, sizeof x0);
    cfg.fourier_order = 3u;
    cfg.fourier_period = 4.0;
    cfg.h_max = 2.0 / 200.0;
    for (i = 0u; i < 21u; ++i) {
        cfg.r_eps[i] = 1.0;
    }
    cfg.tol_r = 1e-10;
    cfg.tol_v = 1e-10;
    cfg.tol_lambda_m = 1e-10;
    cfg.max_newton = 20u;
    cfg.max_outer = 30u;
    (void)memcpy(cfg.weights_nom, w_nom, sizeof w_nom);
    /* the nominal's end state is the target; MPSP makes the nominal consistent */
    ok = ok && (ogk_mpsp_init(&mpsp, &cfg) == OGK_OK) &&
         (ogk_mpsp_propagate(&mpsp, w_nom, 0.0, x0, 1.0, &prop) == OGK_OK);
    (void)memcpy(cfg.r_f, prop.x_f, sizeof cfg.r_f);
    (void)memcpy(cfg.v_f, &prop.x_f[3], sizeof cfg.v_f);
    ok = ok && (ogk_mpsp_init(&mpsp, &cfg) == OGK_OK) && (ogk_mpsp_solve(&mpsp, x0, 1.0, NULL, &res) == OGK_OK);
    (void)memcpy(cfg.weights_nom, res.weights, sizeof res.weights);
    cfg.lambda_m0_nom = res.lambda_m0;
    /* in flight: 5 % less thrust */
    ok = ok && (ogk_mpsp_init(&mpsp, &cfg) == OGK_OK) && (ogk_mpsp_solve(&mpsp, x0, 0.95, NULL, &res) == OGK_OK);
    ok = ok && (res.converged == 1u) && (res.err_r <= cfg.tol_r) && (res.err_v <= cfg.tol_v);
    for (k = 0u; ok && (k <= 100u); ++k) {
        const double t = cfg.t0 + ((cfg.tf - cfg.t0) * (double)k / 100.0);
        ok = ogk_mpsp_thrust_cmd(&mpsp, t, &cmd) == OGK_OK;
        ok = ok && (fabs(sqrt((cmd.u[0] * cmd.u[0]) + (cmd.u[1] * cmd.u[1]) + (cmd.u[2] * cmd.u[2])) - 1.0) < 1e-12);
        burning += ((cmd.flags & OGK_THRUST_FLAG_ENGINE_ON) != 0u) ? 1u : 0u;
    }
    ok = ok && (burning > 0u) && (burning < 101u);
    (void)snprintf(detail, sizeof detail,
                   "thrust -5 %%: converged in %u Newton iterations, |dr| %.1e, |dv| %.1e, %u thrust arcs",
                   (unsigned)res.newton_iterations, res.err_r, res.err_v, (unsigned)res.n_thrust_arcs);
    return consumer_verdict("mpsp", ok, detail);
}
