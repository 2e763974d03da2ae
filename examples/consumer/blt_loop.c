/* blt_loop.c -- BLT guidance about a binary asteroid (ogk/blt.h): a Moshup-like binary with every
 * perturbation of the model on (degree-2 terms, solar pressure and tide, mass flow), one burn of
 * 0.61 TU far from both bodies. The burn's own end state is the target; the corrector starts from
 * its parameters perturbed by 10 % and must bring the terminal error under 1e-10. Its command is then
 * flown through the burn (synodic frame, engine on, a unit direction) and off after it. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include <ogk/blt.h>

#include "consumer.h"

static ogk_blt_t blt;
static ogk_blt_transfer_t burn;
static ogk_blt_transfer_t guess;
static ogk_blt_transfer_t solution;

static void binary(ogk_blt_config_t *c)
{
    (void)ogk_blt_config_default(c);
    c->model.mu = 0.0544;
    c->model.body_radius[0] = 0.26;
    c->model.body_radius[1] = 0.089;
    c->model.ref_radius[0] = 0.26;
    c->model.ref_radius[1] = 0.089;
    c->model.c20[0] = -0.05;
    c->model.c20[1] = -0.09;
    c->model.c22[1] = 0.03;
    c->model.srp_accel = 0.02;
    c->model.sun_angle0 = 0.3;
    c->model.sun_rate = -0.99;
    c->model.sun_tidal = 0.01;
    c->model.thrust_accel = 1.0;
    c->model.mass_flow = 0.05;
    c->model.step_max = 5.0e-3;
    c->time_max = 5.0;
    c->tol = 1.0e-10;
}

int fly_blt(void)
{
    static const double x0[OGK_BLT_NX] = {0.30, 0.80, 0.05, -0.30, 0.20, 0.01};
    static const double p[OGK_BLT_NP] = {0.6, 0.5, 0.1, -0.4, 0.8, 0.3, 0.6123};
    static const double pattern[3] = {1.0, -1.0, 0.5};
    ogk_blt_config_t cfg;
    ogk_blt_report_t rep;
    ogk_thrust_cmd_t cmd;
    char detail[160];
    unsigned k;
    int ok;
    binary(&cfg);
    (void)memset(&burn, 0, sizeof burn);
    burn.t0 = 0.25;
    burn.mass0 = 0.9;
    (void)memcpy(burn.x0, x0, sizeof x0);
    (void)memcpy(burn.seg[0], p, sizeof p);
    ok = (ogk_blt_init(&blt, &cfg) == OGK_OK) && (ogk_blt_propagate(&blt, &burn, burn.xf, &rep) == OGK_OK);
    guess = burn;
    for (k = 0u; k < OGK_BLT_NP; ++k) {
        guess.seg[0][k] *= 1.0 + (0.1 * pattern[k % 3u]);
    }
    ok = ok && (ogk_blt_solve(&blt, &guess, &solution, &rep) == OGK_OK) &&
         (rep.flags == OGK_BLT_FLAG_CONVERGED) && (rep.err_norm <= cfg.tol) &&
         (fabs(solution.seg[0][6] - p[6]) < 1e-9);
    for (k = 0u; ok && (k < 10u); ++k) { /* through the burn */
        const double t = burn.t0 + (0.1 * (double)k * p[6]);
        ok = (ogk_blt_thrust_cmd(&blt, t, &cmd) == OGK_OK) && (cmd.frame == OGK_FRAME_SYNODIC) &&
             ((cmd.flags & OGK_THRUST_FLAG_ENGINE_ON) != 0u) &&
             (fabs(sqrt((cmd.u[0] * cmd.u[0]) + (cmd.u[1] * cmd.u[1]) + (cmd.u[2] * cmd.u[2])) - 1.0) < 1e-12);
    }
    ok = ok && (ogk_blt_thrust_cmd(&blt, burn.t0 + p[6] + 0.1, &cmd) == OGK_OK) &&
         ((cmd.flags & OGK_THRUST_FLAG_ENGINE_ON) == 0u);
    (void)snprintf(detail, sizeof detail, "burn corrected from a 10 %% perturbed guess: |e| %.1e -> %.1e in %u iterations",
                   rep.err_norm0, rep.err_norm, (unsigned)rep.iterations);
    return consumer_verdict("blt", ok, detail);
}
