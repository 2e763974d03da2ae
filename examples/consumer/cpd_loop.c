/* cpd_loop.c -- CPD attitude control (ogk/cpd.h) with the paper's printed gains, fed by a thrust
 * command as any law gives it (ogk/thrust_cmd.h), on the pitch axis of a linearised vehicle
 * (Pontani & Celani 2021, eqs. 42-44: theta'' = G delta_y, G = 0.83 1/s^2; the TVC actuator a first-
 * order lag of tau_y, its deflection limited). The vehicle starts 1 deg off the commanded pitch: the
 * saturated loop must bring it back within 1e-6 rad and to rest in 40 s. */
#include <math.h>
#include <stdio.h>

#include <ogk/cpd.h>
#include <ogk/thrust_cmd.h>

#include "consumer.h"

#define G_TVC 0.83    /* [1/s^2] T l / I_y */
#define ALPHA_C 0.3   /* [rad] commanded in-plane thrust angle: theta_c at xi = phi = 0 */
#define DEG 0.017453292519943295

static ogk_cpd_t cpd;

int fly_cpd(void)
{
    ogk_cpd_config_t cfg;
    ogk_thrust_cmd_t cmd;
    ogk_nav_state_t nav = {0.0, 7.0e6, 0.0, 0.0, 0.0, 7500.0, 0.0};
    ogk_cpd_input_t in = {0};
    ogk_cpd_output_t out;
    double theta = ALPHA_C - DEG;
    double q = 0.0;       /* [rad/s] pitch rate */
    double act = 0.0;     /* [rad] deflection the actuator holds */
    unsigned saturated = 0u;
    unsigned k;
    unsigned j;
    char detail[160];
    int ok = (ogk_cpd_config_default(&cfg) == OGK_OK) && (ogk_cpd_init(&cpd, &cfg) == OGK_OK) &&
             (ogk_thrust_cmd_from_angles(0.0, OGK_R(ALPHA_C), 0.0, 1.0, OGK_THRUST_FLAG_ENGINE_ON, 0u, &cmd) == OGK_OK);
    for (k = 0u; ok && (k < 4000u); ++k) { /* 100 Hz control, the vehicle at 1 ms */
        ok = ogk_cpd_input_from_thrust_cmd(&in, &cmd, &nav) == OGK_OK;
        in.theta = (ogk_real_t)theta; /* the vehicle's double, as its sensors hand it over */
        in.rate_q = (ogk_real_t)q;
        ok = ok && (ogk_cpd_step(&cpd, &in, &out) == OGK_OK);
        saturated += ((out.flags & OGK_CPD_FLAG_SAT_Y) != 0u) ? 1u : 0u;
        for (j = 0u; j < 10u; ++j) {
            const double delta = fmax(-(double)cfg.delta_yc_max, fmin((double)cfg.delta_yc_max, act));
            theta += 1e-3 * q;
            q += 1e-3 * G_TVC * delta;
            act += 1e-3 * ((double)out.delta_yc - act) / (double)cfg.tau_y;
        }
    }
    ok = ok && (saturated > 0u) && (fabs(theta - ALPHA_C) < 1e-6) && (fabs(q) < 1e-6);
    (void)snprintf(detail, sizeof detail, "pitch error 1 deg -> %.1e rad after 40 s (%u saturated steps)",
                   theta - ALPHA_C, saturated);
    return consumer_verdict("cpd", ok, detail);
}
