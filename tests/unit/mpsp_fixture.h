/* mpsp_fixture.h -- the small MPSP problem shared by the coverage tests and the fuzzer: planar-ish
 * two-body transfer in normalised units (mu = 1), 3rd-order Fourier basis, coarse grid of 40 RK4
 * steps over [0, 2], the nominal weights W3 with N_seg,nom = 3 (cheap init, no propagation).
 * The parameters that differ between users (Newton and continuation budgets) are arguments. */
#ifndef OGK_TEST_MPSP_FIXTURE_H
#define OGK_TEST_MPSP_FIXTURE_H

#include <stdint.h>
#include <string.h>

#include "ogk/mpsp.h"

static const ogk_real_t w3[21] = {
    2.0, 0.05, 0.02, 0.6, 0.03, -0.02, 0.01,
    0.6, 0.0, 0.2, 0.01, -0.02, 0.0, 0.01,
    0.0, 0.05, 0.0, 0.01, 0.0, 0.0, -0.01};
static const ogk_real_t x0_3d[7] = {1.0, 0.0, 0.01, 0.0, 1.0, 0.02, 1.0};

/* The solve's tolerance on r(tf), v(tf) and lambda_m(tf): 1e-10, and in the float build 1e-5 (the
 * float solves stall near 3e-7 at this unit scale, measured: MPSP_TOL_F of the MPSP tests; written
 * here with #if, as ogk_test.h's OGK_TEST_TOL, because the fuzzer includes this file without it). */
#if OGK_REAL_SINGLE
#define MPSP_FX_TOL 1e-5
#else
#define MPSP_FX_TOL 1e-10
#endif

/* ogk_mpsp_config_default, then the fixture's mission data; returns config_default's status. */
static ogk_status mpsp_fixture_config(ogk_mpsp_config_t *c, uint32_t max_newton,
                                      uint32_t max_outer)
{
    size_t i;
    ogk_status st;
    (void)memset(c, 0, sizeof *c);
    st = ogk_mpsp_config_default(c);
    c->mu = 1.0;
    c->t_max = 0.1;
    c->c_exhaust = 1.0;
    c->t0 = 0.0;
    c->tf = 2.0;
    (void)memcpy(c->x0_nom, x0_3d, sizeof x0_3d);
    c->r_f[0] = 1.0;
    c->v_f[1] = 1.0;
    c->fourier_order = 3u;
    c->fourier_period = 4.0;
    c->h_max = 2.0 / 40.0;
    for (i = 0u; i < OGK_MPSP_MAX_WEIGHTS; ++i) {
        c->r_eps[i] = 1.0;
    }
    c->tol_r = MPSP_FX_TOL;
    c->tol_v = MPSP_FX_TOL;
    c->tol_lambda_m = MPSP_FX_TOL;
    c->max_newton = max_newton;
    c->max_outer = max_outer;
    (void)memcpy(c->weights_nom, w3, sizeof w3);
    c->n_seg_nom = 3u;
    return st;
}

#endif
