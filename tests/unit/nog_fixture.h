/* nog_fixture.h -- the synthetic VTD-NOG problem shared by test_nog.c and test_nog_input_checks.c: a
 * straight-line nominal x(tau) = x0 + tau x', a constant nominal costate with thrust angle ALPHA0
 * over t_f* = TF_STAR, and the configuration both fly. Each test file writes its own table from it
 * (test_nog.c: the five-node table with the gains its closed forms need; test_nog_input_checks.c: n nodes). */
#ifndef OGK_TEST_NOG_FIXTURE_H
#define OGK_TEST_NOG_FIXTURE_H

#include <stddef.h>
#include <string.h>

#include "ogk/nog.h"

#define TF_STAR 100.0
#define ALPHA0 0.3
#define K_L6_VN 0.01 /* dlam_vn = K_L6_VN dv_n */

static const double x0[7] = {7.0e6, 0.0, 0.0, 10.0, 9000.0, 0.0, 0.0};
static const double x_rate[7] = {2.0e6, 0.5, 0.0, -5.0, 2000.0, 0.0, TF_STAR}; /* d/dtau */

static void nominal_state(double tau, double *x)
{
    size_t i;
    for (i = 0u; i < 7u; ++i) {
        x[i] = x0[i] + tau * x_rate[i];
    }
}

/* Defaults, then Delta t_S = 2 s, |dt_f| <= 10 s, du_max 0.5 rad, no freeze; bound to `table`. */
static ogk_nog_config_t nog_fixture_config(const ogk_nog_table_t *table)
{
    ogk_nog_config_t cfg;
    (void)ogk_nog_config_default(&cfg);
    cfg.table = table;
    cfg.sample_interval_s = 2.0;
    cfg.dtf_max_s = 10.0;
    cfg.du_max_rad = 0.5;
    cfg.tau_freeze = 0.0;
    return cfg;
}

/* The navigation state on the nominal at tau, time-tagged t. */
static ogk_nog_nav_t nog_fixture_nav_at(double t, double tau)
{
    double x[7];
    ogk_nog_nav_t nav;
    nominal_state(tau, x);
    (void)memset(&nav, 0, sizeof nav);
    nav.t_s = t;
    nav.r_m = x[0];
    nav.xi_rad = x[1];
    nav.phi_rad = x[2];
    nav.v_r_mps = x[3];
    nav.v_t_mps = x[4];
    nav.v_n_mps = x[5];
    return nav;
}

#endif /* OGK_TEST_NOG_FIXTURE_H */
