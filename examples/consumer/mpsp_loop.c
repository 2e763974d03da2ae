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

#define R(x) OGK_R(x)
static const ogk_real_t w_nom[21] = {
    R(2.0), R(0.05), R(0.02), R(0.6), R(0.03), R(-0.02), R(0.01), /* lambda_v,x */
    R(0.6), R(0.0), R(0.2), R(0.01), R(-0.02), R(0.0), R(0.01),   /* lambda_v,y */
    R(0.0), R(0.05), R(0.0), R(0.01), R(0.0), R(0.0), R(-0.01)};  /* lambda_v,z */
static const ogk_real_t x0[7] = {R(1.0), R(0.0), R(0.01), R(0.0), R(1.0), R(0.02), R(1.0)}; /* r, v [LU, LU/TU], m [MU] */

/* The terminal tolerances: 1e-10 in double; in float 1e-5, as tests/unit/mpsp_fixture.h's MPSP_TOL_F
 * (float's Newton stalls near 1e-6 on unit-scale states). */
#define MPSP_LOOP_TOL CONSUMER_TOL(1e-10, 1e-5)

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
    cfg.t_max = OGK_R(0.1);
    cfg.c_exhaust = 1.0;
    cfg.t0 = 0.0;
    cfg.tf = 2.0;
    (void)memcpy(cfg.x0_nom, x0, sizeof x0);
    cfg.fourier_order = 3u;
    cfg.fourier_period = 4.0;
    cfg.h_max = OGK_R(2.0 / 200.0);
    for (i = 0u; i < 21u; ++i) {
        cfg.r_eps[i] = 1.0;
    }
    cfg.tol_r = OGK_R(MPSP_LOOP_TOL);
    cfg.tol_v = OGK_R(MPSP_LOOP_TOL);
    cfg.tol_lambda_m = OGK_R(MPSP_LOOP_TOL);
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
    ok = ok && (ogk_mpsp_init(&mpsp, &cfg) == OGK_OK) && (ogk_mpsp_solve(&mpsp, x0, OGK_R(0.95), NULL, &res) == OGK_OK);
    ok = ok && (res.converged == 1u) && (res.err_r <= cfg.tol_r) && (res.err_v <= cfg.tol_v);
    for (k = 0u; ok && (k <= 100u); ++k) {
        const ogk_real_t t = cfg.t0 + ((cfg.tf - cfg.t0) * (ogk_real_t)k / OGK_R(100.0));
        ok = ogk_mpsp_thrust_cmd(&mpsp, t, &cmd) == OGK_OK;
        ok = ok && (consumer_unit_error(&cmd) < CONSUMER_UNIT_TOL);
        burning += ((cmd.flags & OGK_THRUST_FLAG_ENGINE_ON) != 0u) ? 1u : 0u;
    }
    ok = ok && (burning > 0u) && (burning < 101u);
    (void)snprintf(detail, sizeof detail,
                   "thrust -5 %%: converged in %u Newton iterations, |dr| %.1e, |dv| %.1e, %u thrust arcs",
                   (unsigned)res.newton_iterations, (double)res.err_r, (double)res.err_v, (unsigned)res.n_thrust_arcs);
    return consumer_verdict("mpsp", ok, detail);
}
