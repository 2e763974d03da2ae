/* nmpc_fixture.h -- the NMPC problems shared by test_nmpc.c, test_nmpc_edge_cases.c and
 * tests/fuzz/fuzz_nmpc_step.c: Earth to Mars in the normalised units of docs/design/nmpc.md (Table A.1),
 * the phase-matched guess, the solar-electric engine's eq. (14) coefficients, a third body, and the
 * near-field-free radial minimum-time transfer whose optimum is t* = 2 sqrt(D / a). */
#ifndef OGK_TEST_NMPC_FIXTURE_H
#define OGK_TEST_NMPC_FIXTURE_H

#include <math.h>
#include <string.h>

#include "ogk/nmpc.h"

#define NMPC_FX_PI 3.14159265358979323846
#define NMPC_FX_NX OGK_NMPC_NX

/* The solver tolerances the tests set, in the float build (as ogk_test.h's OGK_TEST_TOL; written with
 * #if because the fuzzer includes this file without it): the float SQP's defects and stationarity stop
 * near 5e-7 at these unit scales (measured on the radial transfer and Earth to Mars: 1.2e-7 and 4.8e-7
 * reached, 1e-8 and 1e-10 never), so 1e-5, twenty times that floor, for tol_feas and tol_stat. */
#if OGK_REAL_SINGLE
#define NMPC_FX_TOL_F 1.0e-5
#define NMPC_FX_TOL(tol_double) NMPC_FX_TOL_F
#else
#define NMPC_FX_TOL(tol_double) (tol_double)
#endif

/* Earth to Mars, normalised: T_0, mdot, r_M, theta_M0, n_M; the tests' solver settings. */
static inline void nmpc_fx_mars(ogk_nmpc_config_t *c, uint32_t nodes)
{
    (void)ogk_nmpc_config_default(c);
    c->thrust_max = 0.05621056;
    c->mass_flow_max = 0.05690745;
    c->target_radius = 1.52367877;
    c->target_phase0 = 2.2689280275926285;
    c->target_rate = pow(1.52367877, -1.5);
    c->nodes = nodes;
    c->max_iter = 200u;
    c->max_iter_cold = 200u;
    c->tol_stat = NMPC_FX_TOL(1.0e-7);
#if OGK_REAL_SINGLE
    c->tol_feas = NMPC_FX_TOL_F; /* the default 1e-9 is below float's resolution */
#endif
}

/* The phase-matched guess of docs/design/nmpc.md (smoothstep radius, 135 deg). */
static inline void nmpc_fx_mars_guess(const ogk_nmpc_config_t *c, uint32_t nodes, double t_f,
                                      ogk_nmpc_plan_t *p)
{
    uint32_t k;
    const double r0 = 1.0;
    const double r1 = c->target_radius;
    (void)memset(p, 0, sizeof *p);
    p->t0 = 0.0;
    p->horizon = t_f;
    p->nodes = nodes;
    p->nu = 1u;
    for (k = 0u; k <= nodes; ++k) {
        const double tau = (double)k / (double)nodes;
        const double r = r0 + (r1 - r0) * (3.0 * tau * tau - 2.0 * tau * tau * tau);
        p->x[k * NMPC_FX_NX + 0u] = r;
        p->x[k * NMPC_FX_NX + 1u] = (c->target_phase0 + c->target_rate * t_f) * tau;
        p->x[k * NMPC_FX_NX + 2u] = (r1 - r0) * (6.0 * tau - 6.0 * tau * tau) / t_f;
        p->x[k * NMPC_FX_NX + 3u] = 1.0 / sqrt(r);
        p->x[k * NMPC_FX_NX + 4u] = 1.0 - c->mass_flow_max * t_f * tau;
        p->u[k] = 0.75 * NMPC_FX_PI;
    }
}

/* Eq. (14) with Table A.1's a_i and round b, c: T_max(r) = -2e-4 + 0.05 p, mdot_max = 5e-3 + flow_slope p. */
static inline void nmpc_fx_solar(ogk_nmpc_config_t *c, double length_unit, double flow_slope)
{
    c->power = OGK_NMPC_POWER_SOLAR;
    c->solar_length_unit = length_unit;
    c->solar_a[0] = 1.1063;
    c->solar_a[1] = 0.1495;
    c->solar_a[2] = -0.299;
    c->solar_a[3] = -0.0423;
    c->solar_thrust[0] = -2.0e-4;
    c->solar_thrust[1] = 0.05;
    c->solar_flow[0] = 5.0e-3;
    c->solar_flow[1] = flow_slope;
}

/* Third body b on a circular orbit (radius, phase at t = 0, rate). */
static inline void nmpc_fx_body(ogk_nmpc_config_t *c, uint32_t b, double mu, double radius, double phase0,
                                double rate)
{
    c->body_mu[b] = mu;
    c->body_radius[b] = radius;
    c->body_phase0[b] = phase0;
    c->body_rate[b] = rate;
}

/* Radial minimum-time transfer from r = 1 to 1.5 with a = 0.1 and mu = 1e-9 (near field-free). */
static inline void nmpc_fx_radial(ogk_nmpc_config_t *c, uint32_t nodes, uint32_t rk4_steps, uint32_t max_iter)
{
    (void)ogk_nmpc_config_default(c);
    c->mu = 1.0e-9;
    c->thrust_max = 0.1;
    c->mass_flow_max = 0.0;
    c->target_radius = 1.5;
    c->nodes = nodes;
    c->rk4_steps = rk4_steps;
    c->horizon_min = 0.1;
    c->horizon_max = 20.0;
    c->max_iter = max_iter;
    c->max_iter_cold = max_iter;
    c->tol_feas = NMPC_FX_TOL(1.0e-10);
    c->tol_stat = NMPC_FX_TOL(1.0e-8);
}

/* Its guess: smoothstep radius over t_guess, accelerate then brake. */
static inline void nmpc_fx_radial_guess(uint32_t nodes, double t_guess, ogk_nmpc_plan_t *p)
{
    uint32_t k;
    (void)memset(p, 0, sizeof *p);
    p->horizon = t_guess;
    p->nodes = nodes;
    p->nu = 1u;
    for (k = 0u; k <= nodes; ++k) {
        const double tau = (double)k / (double)nodes;
        p->x[k * NMPC_FX_NX + 0u] = 1.0 + 0.5 * (3.0 * tau * tau - 2.0 * tau * tau * tau);
        p->x[k * NMPC_FX_NX + 2u] = 0.5 * (6.0 * tau - 6.0 * tau * tau) / t_guess;
        p->x[k * NMPC_FX_NX + 3u] = sqrt(1.0e-9);
        p->x[k * NMPC_FX_NX + 4u] = 1.0;
        p->u[k] = ((tau < 0.5) ? 0.0 : NMPC_FX_PI) + 0.01;
    }
}

#endif /* OGK_TEST_NMPC_FIXTURE_H */
