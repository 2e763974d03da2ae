/* blt_fixture.h -- the BLT problems shared by test_blt.c, test_blt_failure_paths.c and
 * tests/fuzz/fuzz_blt_solve.c (ogk/blt.h, docs/design/blt.md):
 *   - a Moshup-like binary (mu = 0.0544, body radii 0.26 and 0.089 LU) with every term of the model
 *     switched on and exaggerated so that each one shows in the Jacobian: degree-2 terms of both
 *     bodies, SRP, the solar tide, mass flow;
 *   - the Earth-Moon point-mass CR3BP (mu = 0.01215058560962404) of the Lyapunov-orbit tests;
 *   - known transfers: a single burn and a burn-coast-burn in the Moshup-like field, far from both
 *     bodies, short (T ~ 0.3-0.6 TU) so that they also run on the Cortex-M7 under QEMU;
 *   - the collinear point L1 by bisection of the x-axis force balance, and the linearised planar
 *     Lyapunov frequency (Szebehely). */
#ifndef OGK_TEST_BLT_FIXTURE_H
#define OGK_TEST_BLT_FIXTURE_H

#include <math.h>
#include <string.h>

#include "ogk/blt.h"

#define BLT_FX_PI 3.14159265358979323846
#define BLT_FX_EM_MU 0.01215058560962404

/* The float build's corrector settings (as ogk_test.h's OGK_TEST_TOL; written with #if because the
 * fuzzer includes this header without it): the kernel's default fd_step 1e-6 makes the central-difference
 * Jacobian's round-off eps / h = 0.1 in float, so 1e-3 (eps / h = 1e-4 against a truncation h^2 = 1e-6);
 * the corrector's residual then stalls near 1e-7 (measured on the single burn, NRPC and LM, central and
 * variational), and BLT_TOL_F = 1e-5 is a hundred times that floor. */
#if OGK_REAL_SINGLE
#define BLT_FX_FD_STEP_F 1.0e-3
#define BLT_TOL_F 1.0e-5
#endif

/* The Moshup-like model: every perturbation on (values exaggerated, not the asteroid's). */
static inline void blt_fx_moshup(ogk_blt_config_t *c)
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
#if OGK_REAL_SINGLE
    c->fd_step = BLT_FX_FD_STEP_F;
#endif
}

/* The single burn: start well away from both bodies (0.8 LU from the primary, 1.0 from the
 * secondary), A, B not parallel (the direction turns by about 50 deg over the burn). */
static inline void blt_fx_single_burn(ogk_blt_transfer_t *tr)
{
    static const ogk_real_t x0[OGK_BLT_NX] = {0.30, 0.80, 0.05, -0.30, 0.20, 0.01};
    static const ogk_real_t p[OGK_BLT_NP] = {0.6, 0.5, 0.1, -0.4, 0.8, 0.3, 0.6123};
    (void)memset(tr, 0, sizeof(*tr));
    tr->t0 = 0.25;
    tr->mass0 = 0.9;
    (void)memcpy(tr->x0, x0, sizeof(x0));
    (void)memcpy(tr->seg[0], p, sizeof(p));
}

/* Burn-coast-burn: three segments, the second a coast. */
static inline void blt_fx_bcb(ogk_blt_transfer_t *tr)
{
    static const ogk_real_t x0[OGK_BLT_NX] = {0.30, 0.80, 0.05, -0.30, 0.20, 0.01};
    static const ogk_real_t p0[OGK_BLT_NP] = {0.6, 0.5, 0.1, -0.4, 0.8, 0.3, 0.3123};
    static const ogk_real_t p2[OGK_BLT_NP] = {-0.7, 0.2, -0.1, 0.5, 0.6, 0.2, 0.2871};
    (void)memset(tr, 0, sizeof(*tr));
    tr->t0 = 0.25;
    tr->mass0 = 0.9;
    (void)memcpy(tr->x0, x0, sizeof(x0));
    (void)memcpy(tr->seg[0], p0, sizeof(p0));
    tr->seg[1][6] = 0.4217;
    (void)memcpy(tr->seg[2], p2, sizeof(p2));
}

/* Burn-coast-burn configuration; free node at interface 2 (after the coast) when `node`, the first
 * arc meeting at interface 1 (the end of the first burn: the coast is propagated backward from
 * the node), the second arc forward to the target. */
static inline void blt_fx_bcb_config(ogk_blt_config_t *c, int node)
{
    blt_fx_moshup(c);
    c->n_segments = 3u;
    c->segment_kind[1] = OGK_BLT_SEG_COAST;
    c->segment_free[1] = OGK_BLT_FREE_T;
    if (node != 0) {
        c->n_free_nodes = 1u;
        c->free_node_interface[0] = 2u;
        c->meet_interface[0] = 1u;
        c->meet_interface[1] = 3u;
    } else {
        c->meet_interface[0] = 3u;
    }
}

/* The x-axis force balance of the CR3BP (d Omega / dx on y = z = 0). */
static inline double blt_fx_axis_force(double mu, double x)
{
    const double r1 = x + mu;
    const double r2 = x - 1.0 + mu;
    return x - ((1.0 - mu) * r1 / (fabs(r1) * r1 * r1)) - (mu * r2 / (fabs(r2) * r2 * r2));
}

/* L1 between the bodies by bisection (the force runs from -inf at the primary to +inf at the
 * secondary and is increasing between them): 200 halvings, to the last bit. */
static inline double blt_fx_x_l1(double mu)
{
    double lo = -mu + 1.0e-6;
    double hi = 1.0 - mu - 1.0e-6;
    int i;
    for (i = 0; i < 200; ++i) {
        const double mid = 0.5 * (lo + hi);
        if (blt_fx_axis_force(mu, mid) < 0.0) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    return 0.5 * (lo + hi);
}

/* Earth-Moon point-mass CR3BP: one coast segment with free T, x0's vy free, the target the
 * symmetric x-axis crossing y = 0, vx = 0 (a half period of a planar Lyapunov orbit). */
static inline void blt_fx_lyapunov_config(ogk_blt_config_t *c)
{
    (void)ogk_blt_config_default(c);
    c->model.mu = BLT_FX_EM_MU;
    c->model.body_radius[0] = 6378.0 / 384400.0;
    c->model.body_radius[1] = 1737.0 / 384400.0;
    c->model.thrust_accel = 1.0; /* unused in a coast */
    c->model.step_max = 5.0e-3;
    c->segment_kind[0] = OGK_BLT_SEG_COAST;
    c->segment_free[0] = OGK_BLT_FREE_T;
    c->start_free_mask = 1u << 4;
    c->target_mask = (1u << 1) | (1u << 3);
    c->time_max = 5.0;
#if OGK_REAL_SINGLE
    c->fd_step = BLT_FX_FD_STEP_F;
#endif
}

#ifdef OGK_TEST_H /* the cmocka helpers: only for the unit tests (the fuzzer includes this header too) */
/* tr->xf = the end of tr flown forward (the known solution's own target), with ctx. */
static inline void blt_fx_make_target(ogk_blt_t *ctx, const ogk_blt_config_t *c, ogk_blt_transfer_t *tr)
{
    ogk_blt_report_t rep;
    OGK_ASSERT_STATUS(ogk_blt_init(ctx, c), OGK_OK);
    OGK_ASSERT_STATUS(ogk_blt_propagate(ctx, tr, tr->xf, &rep), OGK_OK);
}

/* tr->node[0] = the state at interface `iface` of tr flown forward (no free node in c), with ctx. */
static inline void blt_fx_make_node(ogk_blt_t *ctx, const ogk_blt_config_t *c, uint32_t iface, ogk_blt_transfer_t *tr)
{
    ogk_blt_config_t part = *c;
    ogk_blt_report_t rep;
    part.n_segments = iface;
    part.n_free_nodes = 0u;
    part.meet_interface[0] = iface;
    part.target_mask = 0x3Fu;
    OGK_ASSERT_STATUS(ogk_blt_init(ctx, &part), OGK_OK);
    OGK_ASSERT_STATUS(ogk_blt_propagate(ctx, tr, tr->node[0], &rep), OGK_OK);
}
#endif

#endif /* OGK_TEST_BLT_FIXTURE_H */
