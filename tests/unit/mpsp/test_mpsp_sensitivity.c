/* test_mpsp_sensitivity.c -- MPSP sensitivities (ogk/mpsp.h, docs/design/mpsp.md):
 *   - one RK4 step: dX_next/dX and dX_next/dW against central differences of
 *     the kernel's own step, in thrust and in coast;
 *   - a whole trajectory with gravity and two switches: dY/dW and dY/dlambda_m0
 *     against central differences of ogk_mpsp_propagate (1e-6 relative);
 *   - the switching compensation (eqs. 22-25) on a field-free problem whose
 *     switch time has a closed form, t_s = acos(q)/omega, and whose terminal
 *     r_x, v_x follow from the rocket equation: dt_s/dp and dY/dp exact;
 *     the cross-track sensitivities (the dF/dU block) against a quadrature;
 *   - the control (both basis kinds) and the pchip state read-out. */
#include "ogk_test.h"

#include <string.h>

#include "ogk/internal/mpsp_test.h" /* ogk_mpsp_step_jacobian, ogk_mpsp_switch_jump */
#include "ogk/mpsp.h"

#define PI 3.14159265358979323846
#define NX OGK_MPSP_NX
#define NY OGK_MPSP_NY

/* Grid of the whole-arc tests (the same on the host and on QEMU, where the
 * binary runs in about 0.3 s). */
#define ARC_STEPS 500.0

static ogk_mpsp_t ctx;
static ogk_mpsp_config_t cfg;
static ogk_real_t dydw[NY * OGK_MPSP_MAX_WEIGHTS];
static ogk_real_t fd_dydw[NY * OGK_MPSP_MAX_WEIGHTS];
static ogk_real_t dfdw[NX * OGK_MPSP_MAX_WEIGHTS];
static ogk_real_t fd_dfdw[NX * OGK_MPSP_MAX_WEIGHTS];
static ogk_real_t wpert[OGK_MPSP_MAX_WEIGHTS];

/* The solves' tolerances in float (ogk_test.h): the float solves stall near 3e-7 at unit scale
 * (measured: this file's problem and test_mpsp_solve.c's 400-step one converge to 3e-7 at most, not
 * to 1e-7, their terminal states carrying some 40 to 400 roundings); 1e-5 is thirty times that
 * floor. The terminal conditions flown again are checked to the same tolerance. */
#define MPSP_TOL_F 1e-5

/* ---------------------------------------------------------------- fixtures */

static void base_config(ogk_mpsp_config_t *c)
{
    size_t i;
    (void)memset(c, 0, sizeof *c);
    c->delta_max = 1.0;
    c->delta_tau_0 = 0.5;
    c->delta_tau_min = 0.1;
    for (i = 0u; i < OGK_MPSP_MAX_WEIGHTS; ++i) {
        c->r_eps[i] = 1.0;
    }
    c->r_lambda = 1.0;
    c->tol_r = OGK_TEST_TOL(1e-9, MPSP_TOL_F);
    c->tol_v = OGK_TEST_TOL(1e-9, MPSP_TOL_F);
    c->tol_lambda_m = OGK_TEST_TOL(1e-9, MPSP_TOL_F);
    c->s_tol = OGK_TEST_TOL(1e-13, 16.0 * FLT_EPSILON); /* float: 16 eps of |S| ~ 1 (test_rk4.c) */
    c->max_newton = 20u;
    c->max_outer = 20u;
    c->n_seg_tol = 0u;
    c->n_seg_tol_step = 2u;
}

/* Normalised two-body problem (mu = 1) over t in [0, 2], thrust 0.1, c = 1,
 * order-3 basis of period 2 tf: |lambda_v| ~ 1.6 at both ends and ~0.6 in
 * the middle, so the engine is on, off, on (two switches). */
static const ogk_real_t w3[21] = {
    2.0, 0.05, 0.02, 0.6, 0.03, -0.02, 0.01,   /* lambda_v,x */
    0.6, 0.0, 0.2, 0.01, -0.02, 0.0, 0.01,     /* lambda_v,y */
    0.0, 0.05, 0.0, 0.01, 0.0, 0.0, -0.01};    /* lambda_v,z */
static const ogk_real_t x0_3d[7] = {1.0, 0.0, 0.01, 0.0, 1.0, 0.02, 1.0};

static void orbit_config(ogk_mpsp_config_t *c, double steps)
{
    base_config(c);
    c->mu = 1.0;
    c->t_max = 0.1;
    c->c_exhaust = 1.0;
    c->t0 = 0.0;
    c->tf = 2.0;
    (void)memcpy(c->x0_nom, x0_3d, sizeof x0_3d);
    c->fourier_order = 3u;
    c->fourier_period = 4.0;
    c->fourier_t_ref = 0.0;
    c->h_max = 2.0 / steps;
    (void)memcpy(c->weights_nom, w3, sizeof w3);
    c->lambda_m0_nom = 0.0;
}

/* Field-free problem (mu = 0), order 1, period 2 (omega = pi), t in [0, 1]:
 * lambda_v = [a0/2 + a1 cos(pi t), 0, 0] rises from 0.4 to 1.0, the engine
 * is off until |lambda_v| c/m0 = 1 - lambda_m0 (eq. 10), then on. */
#define FF_A0 1.4
#define FF_A1 (-0.3)
#define FF_LM0 0.2
#define FF_T 0.5
#define FF_C 1.0
#define FF_M0 1.0

static void field_free_config(ogk_mpsp_config_t *c, double steps)
{
    base_config(c);
    c->mu = 0.0;
    c->t_max = FF_T;
    c->c_exhaust = FF_C;
    c->t0 = 0.0;
    c->tf = 1.0;
    c->x0_nom[0] = 1.0;
    c->x0_nom[3] = 0.1;
    c->x0_nom[6] = FF_M0;
    c->fourier_order = 1u;
    c->fourier_period = 2.0;
    c->fourier_t_ref = 0.0;
    c->h_max = 1.0 / steps;
    c->weights_nom[0] = FF_A0;
    c->weights_nom[1] = FF_A1;
    c->lambda_m0_nom = FF_LM0;
}

static double max_abs(const ogk_real_t *v, size_t n, size_t stride)
{
    double m = 0.0;
    size_t i;
    for (i = 0u; i < n; ++i) {
        m = fmax(m, fabs(v[i * stride]));
    }
    return m;
}

/* |a - e| <= rel * max(|e|, 1e-3 * scale) + floor: relative, with a floor of
 * 1e-3 of the largest entry of the same row for entries near zero and an
 * absolute floor (1e-11 in double) for the round-off of the differences
 * (|Y| ~ 1, d = 1e-3).
 * Float: FD_D = 1e-2 (the truncation d^4 stays far below the round-off). One
 * step: the round-off of a difference of values |Y| <= 2 over d, (1 + 8 + 8
 * + 1) / 12 eps 2 / d, FD_NOISE = 4 eps / d. A whole arc of ARC_STEPS steps:
 * the propagated Y carries a rounding noise that the differences amplify by
 * 1.5 / d; measured worst 3.7e-4 on M4F and host, ARC_FD_FLOOR ten times that. Two
 * kernel computations of the same derivative (sweep against step chain):
 * measured, CHAIN_REL ten times the worst relative difference. */
#define FD_D OGK_TEST_PICK(1e-3, 1e-2)
#define FD_NOISE (4.0 * FLT_EPSILON / 1e-2)
#define ARC_FD_FLOOR 4e-3
#define CHAIN_REL 1e-4
static void assert_matrix_rel(const ogk_real_t *a, const ogk_real_t *e, size_t rows, size_t cols,
                              double rel, double floor)
{
    size_t r;
    size_t c;
    for (r = 0u; r < rows; ++r) {
        const double scale = max_abs(&e[r * cols], cols, 1u);
        for (c = 0u; c < cols; ++c) {
            const double tol = rel * fmax(fabs(e[r * cols + c]), 1e-3 * scale) + floor;
            if (!(fabs(a[r * cols + c] - e[r * cols + c]) <= tol)) {
                print_error("entry (%u, %u): %.12g, expected %.12g\n", (unsigned)r,
                            (unsigned)c, a[r * cols + c], e[r * cols + c]);
            }
            OGK_ASSERT_LE(fabs(a[r * cols + c] - e[r * cols + c]), tol);
        }
    }
}

/* ---------------------------------------------------------------- one RK4 step */

/* Fourth-order central difference from f(-2d), f(-d), f(d), f(2d):
 * truncation O(d^4), so d = 1e-3 keeps both truncation and the round-off
 * and switch-location noise (|S| <= 1e-13) below 1e-9 relative. */
static double fd5(double fm2, double fm1, double fp1, double fp2, double d)
{
    return (fm2 - 8.0 * fm1 + 8.0 * fp1 - fp2) / (12.0 * d);
}

static const double fd_offsets[4] = {-2.0, -1.0, 1.0, 2.0};

static void check_step(int mode, uint32_t kind)
{
    static const ogk_real_t x[NX] = {1.0, 0.1, 0.02, -0.1, 0.95, 0.01, 0.9, 0.05};
    const double t = 0.3;
    const double dt = 0.05;
    const double d = FD_D;
    ogk_real_t xn[NX];
    ogk_real_t xs[4][NX];
    ogk_real_t xpert[NX];
    ogk_real_t dfdx[NX * NX];
    ogk_real_t fd_dfdx[NX * NX];
    size_t nw;
    size_t i;
    size_t j;
    size_t p;

    orbit_config(&cfg, 100.0);
    cfg.n_seg_nom = 3u;
    cfg.fourier_kind = kind;
    OGK_ASSERT_STATUS(ogk_mpsp_init(&ctx, &cfg), OGK_OK);
    nw = ctx.n_weights;
    OGK_ASSERT_STATUS(ogk_mpsp_step_jacobian(&ctx, w3, 1.0, t, x, dt, mode, xn, dfdx, dfdw),
                      OGK_OK);
    for (j = 0u; j < NX; ++j) {
        for (p = 0u; p < 4u; ++p) {
            (void)memcpy(xpert, x, sizeof xpert);
            xpert[j] = x[j] + fd_offsets[p] * d;
            OGK_ASSERT_STATUS(ogk_mpsp_step_jacobian(&ctx, w3, 1.0, t, xpert, dt, mode, xs[p],
                                                     NULL, NULL), OGK_OK);
        }
        for (i = 0u; i < NX; ++i) {
            fd_dfdx[i * NX + j] = fd5(xs[0][i], xs[1][i], xs[2][i], xs[3][i], d);
        }
    }
    assert_matrix_rel(dfdx, fd_dfdx, NX, NX, 1e-6, OGK_TEST_TOL(1e-11, FD_NOISE));
    for (j = 0u; j < nw; ++j) {
        for (p = 0u; p < 4u; ++p) {
            (void)memcpy(wpert, w3, sizeof w3);
            wpert[j] = w3[j] + fd_offsets[p] * d;
            OGK_ASSERT_STATUS(ogk_mpsp_step_jacobian(&ctx, wpert, 1.0, t, x, dt, mode, xs[p],
                                                     NULL, NULL), OGK_OK);
        }
        for (i = 0u; i < NX; ++i) {
            fd_dfdw[i * nw + j] = fd5(xs[0][i], xs[1][i], xs[2][i], xs[3][i], d);
        }
    }
    if (mode == 1) {
        assert_matrix_rel(dfdw, fd_dfdw, NX, nw, 1e-6, OGK_TEST_TOL(1e-11, FD_NOISE));
        /* U varies inside the step: the thrust rows depend on the harmonics. */
        assert_true(fabs(dfdw[4u * nw + 7u + 6u]) > 1e-6);
    } else {
        /* In coast the weights do not enter eq. (16). */
        for (i = 0u; i < NX * nw; ++i) {
            assert_true(dfdw[i] == 0.0);
            assert_true(fabs(fd_dfdw[i]) < OGK_TEST_TOL(1e-12, FD_NOISE));
        }
    }
}

/* req: OGK-MPSP-003 */
static void test_step_jacobian_thrust(void **state)
{
    (void)state;
    check_step(1, OGK_MPSP_BASIS_FOURIER);
    check_step(1, OGK_MPSP_BASIS_COSINE);
}

/* req: OGK-MPSP-003 */
static void test_step_jacobian_coast(void **state)
{
    (void)state;
    check_step(0, OGK_MPSP_BASIS_FOURIER);
}

/* ---------------------------------------------------------------- whole arc vs FD */

/* Switches of the trajectory the finite differences perturb (the same for
 * every perturbed one). */
static uint32_t arc_switches;

static void propagate_y(const ogk_real_t *w, double lm0, double *y)
{
    ogk_mpsp_prop_t prop;
    OGK_ASSERT_STATUS(ogk_mpsp_propagate(&ctx, w, lm0, x0_3d, 1.0, &prop), OGK_OK);
    assert_int_equal(prop.n_switches, arc_switches);
    {
        size_t i;
        for (i = 0u; i < 6u; ++i) {
            y[i] = prop.x_f[i];
        }
    }
    y[6] = prop.x_f[7];
}

/* dY/dW and dY/dlambda_m0 of the arc from x0_3d with weights w3, held in
 * ctx, against 4th-order central differences of ogk_mpsp_propagate. */
static void check_arc_against_fd(ogk_real_t lm0, ogk_real_t *dydl)
{
    const double d = FD_D;
    ogk_real_t fd_dydl[NY];
    double ys[4][NY];
    const size_t nw = ctx.n_weights;
    size_t i;
    size_t j;
    size_t p;

    OGK_ASSERT_STATUS(ogk_mpsp_sensitivity(&ctx, dydw, dydl), OGK_OK);

    for (j = 0u; j < nw; ++j) {
        for (p = 0u; p < 4u; ++p) {
            (void)memcpy(wpert, w3, sizeof w3);
            wpert[j] = w3[j] + fd_offsets[p] * d;
            propagate_y(wpert, lm0, ys[p]);
        }
        for (i = 0u; i < NY; ++i) {
            fd_dydw[i * nw + j] = fd5(ys[0][i], ys[1][i], ys[2][i], ys[3][i], d);
        }
    }
    for (p = 0u; p < 4u; ++p) {
        propagate_y(w3, lm0 + fd_offsets[p] * d, ys[p]);
    }
    for (i = 0u; i < NY; ++i) {
        fd_dydl[i] = fd5(ys[0][i], ys[1][i], ys[2][i], ys[3][i], d);
    }
    assert_matrix_rel(dydw, fd_dydw, NY, nw, 1e-6, OGK_TEST_TOL(1e-11, ARC_FD_FLOOR));
    assert_matrix_rel(dydl, fd_dydl, NY, 1u, 1e-6, OGK_TEST_TOL(1e-11, ARC_FD_FLOOR));
}

/* req: OGK-MPSP-003 */
static void test_whole_arc_with_switches_fd(void **state)
{
    const double lm0 = 0.0;
    ogk_real_t dydl[NY];
    ogk_mpsp_prop_t prop;
    (void)state;

    orbit_config(&cfg, ARC_STEPS);
    OGK_ASSERT_STATUS(ogk_mpsp_init(&ctx, &cfg), OGK_OK);
    assert_int_equal(ctx.n_seg_nom, 3); /* counted at init: on, off, on */
    OGK_ASSERT_STATUS(ogk_mpsp_propagate(&ctx, w3, lm0, x0_3d, 1.0, &prop), OGK_OK);
    assert_int_equal(prop.n_switches, 2);
    assert_int_equal(prop.mode0, 1);
    assert_int_equal(prop.n_thrust_arcs, 2);
    assert_true(prop.t_switch[0] > 0.3 && prop.t_switch[0] < 0.7);
    assert_true(prop.t_switch[1] > 1.3 && prop.t_switch[1] < 1.7);
    arc_switches = prop.n_switches;
    check_arc_against_fd(lm0, dydl);
    /* lambda_m0 moves both switches: A_lambda is not the no-switch value
     * [0, ..., 0, 1] that eq. (33) would give without eqs. (22)-(25). */
    assert_true(fabs(dydl[0]) > 1e-3);
}

/* The same arc with the cosine basis (1/2, cos k theta, k = 1..2n: the
 * Apophis scenario's default) and lambda_m0 = -0.2: on, off, on, off (three
 * switches), through the sweep's cosine harmonics. */
/* req: OGK-MPSP-003 OGK-MPSP-002 */
static void test_whole_arc_cosine_basis_fd(void **state)
{
    const double lm0 = -0.2;
    ogk_real_t dydl[NY];
    ogk_mpsp_prop_t prop;
    (void)state;

    orbit_config(&cfg, ARC_STEPS);
    cfg.fourier_kind = OGK_MPSP_BASIS_COSINE;
    OGK_ASSERT_STATUS(ogk_mpsp_init(&ctx, &cfg), OGK_OK);
    OGK_ASSERT_STATUS(ogk_mpsp_propagate(&ctx, w3, lm0, x0_3d, 1.0, &prop), OGK_OK);
    assert_int_equal(prop.n_switches, 3);
    assert_int_equal(prop.mode0, 1);
    arc_switches = prop.n_switches;
    check_arc_against_fd(lm0, dydl);
}

/* ---------------------------------------------------------------- sweep vs step chain */

static double chain_p[NY * NX];
static ogk_real_t chain_g[NY * OGK_MPSP_MAX_WEIGHTS];
static ogk_real_t chain_m[NX * OGK_MPSP_MAX_WEIGHTS];
static ogk_real_t chain_dfdx[NX * NX];
static double chain_tmp[NY * NX];

/* p (NY x NX) := p m and g (NY x nw) += p mw, for one step or switch with
 * Jacobians m = dX_after/dX_before (NX x NX) and mw = dX_after/dW. */
static void chain_apply(const ogk_real_t *m, const ogk_real_t *mw, size_t nw)
{
    size_t r;
    size_t c;
    size_t i;
    for (r = 0u; r < NY; ++r) {
        for (c = 0u; c < nw; ++c) {
            for (i = 0u; i < NX; ++i) {
                chain_g[r * nw + c] += chain_p[r * NX + i] * mw[i * nw + c];
            }
        }
        for (c = 0u; c < NX; ++c) {
            double a = 0.0;
            for (i = 0u; i < NX; ++i) {
                a += chain_p[r * NX + i] * m[i * NX + c];
            }
            chain_tmp[r * NX + c] = a;
        }
    }
    (void)memcpy(chain_p, chain_tmp, sizeof chain_p);
}

/* The backward sweep of ogk_mpsp_sensitivity (two adjoint rows per pass on
 * an SSE2 host, one at a time on the Cortex-M7) against the chain rule over
 * the held trajectory, built from the one-step Jacobians (one row at a time
 * on every target, FD-checked above) and the switch Jacobians of eqs.
 * (24)-(25): dY/dW = sum_k Phi(tf, t_k+1) dX_k+1/dW, A_lambda the lambda_m
 * column of Phi(tf, t0); thrust, coast and three switches. */
/* req: OGK-MPSP-003 */
static void test_sweep_matches_step_chain(void **state)
{
    const double lm0 = -0.2;
    ogk_real_t dydl[NY];
    ogk_real_t xn[NX];
    ogk_mpsp_prop_t prop;
    size_t nw;
    size_t kk;
    size_t r;
    (void)state;

    orbit_config(&cfg, 200.0);
    cfg.fourier_kind = OGK_MPSP_BASIS_COSINE;
    OGK_ASSERT_STATUS(ogk_mpsp_init(&ctx, &cfg), OGK_OK);
    OGK_ASSERT_STATUS(ogk_mpsp_propagate(&ctx, w3, lm0, x0_3d, 1.0, &prop), OGK_OK);
    assert_int_equal(prop.n_switches, 3);
    OGK_ASSERT_STATUS(ogk_mpsp_sensitivity(&ctx, dydw, dydl), OGK_OK);

    nw = ctx.n_weights;
    (void)memset(chain_p, 0, sizeof chain_p);
    (void)memset(chain_g, 0, sizeof chain_g);
    for (r = 0u; r < 6u; ++r) {
        chain_p[r * NX + r] = 1.0; /* Y = [r, v, lambda_m] */
    }
    chain_p[6u * NX + 7u] = 1.0;
    for (kk = 1u; kk < ctx.n_nodes; ++kk) {
        const size_t k = ctx.n_nodes - 1u - kk;
        const int mode = (int)ctx.traj_mode[k];
        if (ctx.traj_mode[k + 1u] != ctx.traj_mode[k]) {
            OGK_ASSERT_STATUS(ogk_mpsp_switch_jump(&ctx, w3, 1.0, ctx.traj_t[k + 1u],
                                                   &ctx.traj_x[(k + 1u) * NX], mode,
                                                   chain_dfdx, chain_m, NULL, NULL),
                              OGK_OK);
            chain_apply(chain_dfdx, chain_m, nw);
        }
        OGK_ASSERT_STATUS(ogk_mpsp_step_jacobian(&ctx, w3, 1.0, ctx.traj_t[k],
                                                 &ctx.traj_x[k * NX],
                                                 ctx.traj_t[k + 1u] - ctx.traj_t[k], mode, xn,
                                                 chain_dfdx, chain_m),
                          OGK_OK);
        chain_apply(chain_dfdx, chain_m, nw);
    }
    assert_matrix_rel(dydw, chain_g, NY, nw, OGK_TEST_TOL(1e-12, CHAIN_REL), OGK_TEST_TOL(1e-11, CHAIN_REL));
    for (r = 0u; r < NY; ++r) {
        OGK_ASSERT_LE(fabs(dydl[r] - chain_p[r * NX + 7u]),
                      OGK_TEST_TOL(1e-12, CHAIN_REL) * fmax(fabs(chain_p[r * NX + 7u]), 1.0));
    }
}

#if defined(__SSE2__)
/* Where the propagation keeps U for the sweep (SSE2 hosts, docs/design/mpsp.md
 * section 8): the sweep with the U kept (made two times per pass in the
 * propagation, from its own phase anchors) against the sweep with every U
 * made again from the sample rows (the kept slots emptied), on the arcs of
 * both basis kinds: the same B_v and A_lambda to rounding (the phases
 * differ by a few ulp). The kept path is taken: a slot per thrust step at
 * least is filled. */
/* req: OGK-MPSP-003 */
static void test_sweep_kept_u_matches_remade(void **state)
{
    static ogk_real_t dydw_kept[NY * OGK_MPSP_MAX_WEIGHTS];
    static const uint32_t kinds[2] = {OGK_MPSP_BASIS_FOURIER, OGK_MPSP_BASIS_COSINE};
    ogk_real_t dydl_kept[NY];
    ogk_real_t dydl[NY];
    ogk_mpsp_prop_t prop;
    size_t b;
    size_t i;
    (void)state;

    for (b = 0u; b < 2u; ++b) {
        size_t n_kept = 0u;
        size_t n_thrust = 0u;
        orbit_config(&cfg, 200.0);
        cfg.fourier_kind = kinds[b];
        OGK_ASSERT_STATUS(ogk_mpsp_init(&ctx, &cfg), OGK_OK);
        OGK_ASSERT_STATUS(ogk_mpsp_propagate(&ctx, w3, -0.2, x0_3d, 1.0, &prop), OGK_OK);
        assert_true(prop.n_switches >= 2u);
        for (i = 0u; i < OGK_MPSP_KEEP_U_SLOTS; ++i) {
            n_kept += (ctx.keep_t[i] >= cfg.t0) ? 1u : 0u;
        }
        for (i = 0u; (i + 1u) < ctx.n_nodes; ++i) {
            n_thrust += (ctx.traj_mode[i] == 1u) ? 1u : 0u;
        }
        assert_true(n_kept >= n_thrust);
        OGK_ASSERT_STATUS(ogk_mpsp_sensitivity(&ctx, dydw_kept, dydl_kept), OGK_OK);
        for (i = 0u; i < OGK_MPSP_KEEP_U_SLOTS; ++i) {
            ctx.keep_t[i] = -HUGE_VAL;
        }
        OGK_ASSERT_STATUS(ogk_mpsp_sensitivity(&ctx, dydw, dydl), OGK_OK);
        assert_matrix_rel(dydw_kept, dydw, NY, ctx.n_weights, OGK_TEST_TOL(1e-12, CHAIN_REL), OGK_TEST_TOL(1e-11, CHAIN_REL));
        assert_matrix_rel(dydl_kept, dydl, NY, 1u, OGK_TEST_TOL(1e-12, CHAIN_REL), OGK_TEST_TOL(1e-11, CHAIN_REL));
    }
}
#endif

/* ---------------------------------------------------------------- the second-order sweep */

/* Largest row-wise relative difference of a (rows x cols) from e: max over
 * rows of max_c |a - e| / max_c |e| (rows with e = 0 must match exactly). */
static double row_rel_diff(const ogk_real_t *a, const ogk_real_t *e, size_t rows, size_t cols)
{
    double worst = 0.0;
    size_t r;
    size_t c;
    for (r = 0u; r < rows; ++r) {
        const double scale = max_abs(&e[r * cols], cols, 1u);
        double d = 0.0;
        for (c = 0u; c < cols; ++c) {
            d = fmax(d, fabs(a[r * cols + c] - e[r * cols + c]));
        }
        worst = fmax(worst, (scale > 0.0) ? (d / scale) : ((d > 0.0) ? HUGE_VAL : 0.0));
    }
    return worst;
}

/* B_v and A_lambda of the second-order sweep against the exact one on the
 * same trajectory (the arc with three switches, cosine basis, and the
 * FOURIER one), at `steps` grid steps: the row-wise relative difference. */
static double mid2_error(double steps, uint32_t kind)
{
    static ogk_real_t dydw_mid2[NY * OGK_MPSP_MAX_WEIGHTS];
    ogk_real_t dydl[NY];
    ogk_real_t dydl_mid2[NY];
    ogk_mpsp_prop_t prop;
    double e;

    orbit_config(&cfg, steps);
    cfg.fourier_kind = kind;
    cfg.n_seg_nom = 4u;
    assert_int_equal(cfg.sens_sweep, OGK_MPSP_SWEEP_RK4);
    OGK_ASSERT_STATUS(ogk_mpsp_init(&ctx, &cfg), OGK_OK);
    OGK_ASSERT_STATUS(ogk_mpsp_propagate(&ctx, w3, -0.2, x0_3d, 1.0, &prop), OGK_OK);
    assert_true(prop.n_switches >= 2u);
    OGK_ASSERT_STATUS(ogk_mpsp_sensitivity(&ctx, dydw, dydl), OGK_OK);
    cfg.sens_sweep = OGK_MPSP_SWEEP_MID2;
    OGK_ASSERT_STATUS(ogk_mpsp_init(&ctx, &cfg), OGK_OK);
    OGK_ASSERT_STATUS(ogk_mpsp_propagate(&ctx, w3, -0.2, x0_3d, 1.0, &prop), OGK_OK);
    OGK_ASSERT_STATUS(ogk_mpsp_sensitivity(&ctx, dydw_mid2, dydl_mid2), OGK_OK);
    e = fmax(row_rel_diff(dydw_mid2, dydw, NY, ctx.n_weights),
             row_rel_diff(dydl_mid2, dydl, NY, 1u));
    print_message("mid2 sweep, %g steps, kind %u: row-wise relative difference %.3e\n", steps,
                  (unsigned)kind, e);
    return e;
}

/* OGK_MPSP_SWEEP_MID2 approximates each step's transition by I + h J + h^2/2
 * J^2 with J at the step midpoint and the step's control sensitivity by the
 * midpoint rule; both agree with the exact step to O(h^3) (the Magnus series
 * at the midpoint: the terms left out are h^3 (J^3/6 + J''/24 + [J, J']/12),
 * J' = dJ/dt), so over the arc the sensitivities differ from the exact
 * sweep's by O(h^2) per unit time: |dB| / |B| <= K h^2 (tf - t0), K of order
 * |J|^3 / 6 with |J| <= 3 here (|G| = 2 mu / r^3 for r >= 0.9, dr/dv = I):
 * K = 4.5. Checked: the difference is below that bound at 100 and 200 steps
 * and falls by the second order's factor 4 (within [2.8, 5.7], orders 1.5 to
 * 2.5) when h is halved, for both basis kinds. */
/* req: OGK-MPSP-003 */
static void test_mid2_sweep_second_order(void **state)
{
    static const uint32_t kinds[2] = {OGK_MPSP_BASIS_COSINE, OGK_MPSP_BASIS_FOURIER};
    const double k_bound = 4.5;
    size_t b;
    (void)state;

    for (b = 0u; b < 2u; ++b) {
        const double e1 = mid2_error(100.0, kinds[b]);
        const double e2 = mid2_error(200.0, kinds[b]);
        const double h1 = 2.0 / 100.0;
        assert_true(e1 > 0.0);
        assert_true(e1 <= k_bound * h1 * h1 * 2.0);
        assert_true(e2 <= k_bound * 0.25 * h1 * h1 * 2.0);
        assert_true((e1 / e2) >= 2.8 && (e1 / e2) <= 5.7);
    }
}

/* req: OGK-MPSP-007 */
static void test_sens_sweep_option_checked(void **state)
{
    ogk_mpsp_config_t c;
    (void)state;

    OGK_ASSERT_STATUS(ogk_mpsp_config_default(&c), OGK_OK);
    assert_true((c.sens_sweep == OGK_MPSP_SWEEP_RK4) || (c.sens_sweep == OGK_MPSP_SWEEP_MID2));
    orbit_config(&cfg, 100.0);
    cfg.sens_sweep = 2u;
    OGK_ASSERT_STATUS(ogk_mpsp_init(&ctx, &cfg), OGK_E_CONFIG);
    cfg.sens_sweep = 0xFFFFFFFFu;
    OGK_ASSERT_STATUS(ogk_mpsp_init(&ctx, &cfg), OGK_E_CONFIG);
    /* the context stays usable: a good value initialises it */
    cfg.sens_sweep = OGK_MPSP_SWEEP_MID2;
    OGK_ASSERT_STATUS(ogk_mpsp_init(&ctx, &cfg), OGK_OK);
    cfg.sens_sweep = OGK_MPSP_SWEEP_RK4;
    OGK_ASSERT_STATUS(ogk_mpsp_init(&ctx, &cfg), OGK_OK);
}

/* ---------------------------------------------------------------- closed form */

static double ff_q(double a0, double a1, double lm0, double m0)
{
    return ((1.0 - lm0) * m0 / FF_C - 0.5 * a0) / a1;
}

/* req: OGK-MPSP-003 */
static void test_switch_time_closed_form(void **state)
{
    /* Closed forms: t_s = acos(q)/pi, q = (lambda* - a0/2)/a1,
     * lambda* = (1 - lambda_m0) m0 / c. */
    const double q = ff_q(FF_A0, FF_A1, FF_LM0, FF_M0);
    const double ts = acos(q) / PI;
    const double dts_dq = -1.0 / (PI * sqrt(1.0 - q * q));
    const double theta_s = PI * ts;
    const double lam_dot = -FF_A1 * PI * sin(theta_s); /* d|lambda_v|/dt at t_s */
    ogk_real_t dts_dx[NX];
    ogk_real_t dts_dw[9];
    ogk_real_t jx[NX * NX];
    ogk_real_t x_s[NX];
    ogk_mpsp_prop_t prop;
    (void)state;

    field_free_config(&cfg, 100.0);
    OGK_ASSERT_STATUS(ogk_mpsp_init(&ctx, &cfg), OGK_OK);
    OGK_ASSERT_STATUS(ogk_mpsp_propagate(&ctx, cfg.weights_nom, FF_LM0, cfg.x0_nom, 1.0, &prop),
                      OGK_OK);
    assert_int_equal(prop.mode0, 0);
    assert_int_equal(prop.n_switches, 1);
    /* float: measured worst 4e-7 on M4F and host */
    OGK_ASSERT_NEAR(prop.t_switch[0], ts, OGK_TEST_TOL(1e-11, 5e-6));

    /* State at the switch: coast in field-free space. */
    (void)memcpy(x_s, cfg.x0_nom, 7u * sizeof x_s[0]);
    x_s[0] += cfg.x0_nom[3] * ts;
    x_s[7] = FF_LM0;
    OGK_ASSERT_STATUS(ogk_mpsp_switch_jump(&ctx, cfg.weights_nom, 1.0, ts, x_s, 0, jx, NULL,
                                           dts_dx, dts_dw), OGK_OK);
    /* eq. (B.2) against the closed form */
    /* float: measured worst relative 8.6e-8 on M4F and host */
    OGK_ASSERT_REL(dts_dw[0], dts_dq * (-0.5 / FF_A1), OGK_TEST_TOL(1e-9, 1e-6), 1e-12);
    /* float: measured worst relative 1.9e-7 on M4F and host */
    OGK_ASSERT_REL(dts_dw[1], dts_dq * (-q / FF_A1), OGK_TEST_TOL(1e-9, 2e-6), 1e-12);
    /* float: measured worst relative 5.9e-8 on M4F and host */
    OGK_ASSERT_REL(dts_dw[2], -sin(theta_s) / lam_dot, OGK_TEST_TOL(1e-9, 1e-6), 1e-12); /* implicit: b1 */
    /* float: measured worst relative 8.6e-8 on M4F and host */
    OGK_ASSERT_REL(dts_dx[7], dts_dq * (-FF_M0 / (FF_C * FF_A1)), OGK_TEST_TOL(1e-9, 1e-6), 1e-12);
    /* float: measured worst relative 8.6e-8 on M4F and host */
    OGK_ASSERT_REL(dts_dx[6], dts_dq * ((1.0 - FF_LM0) / (FF_C * FF_A1)), OGK_TEST_TOL(1e-9, 1e-6), 1e-12);
    OGK_ASSERT_NEAR(dts_dx[0], 0.0, 1e-15);
    OGK_ASSERT_NEAR(dts_dx[3], 0.0, 1e-15);
    /* eq. (24): v_x row picks up -(T/m) * (-dt_s) per unit d lambda_m. */
    OGK_ASSERT_REL(jx[3u * NX + 7u], (-FF_T / FF_M0) * (-dts_dx[7]), 1e-12, 1e-12);
    OGK_ASSERT_NEAR(jx[0u * NX + 0u], 1.0, 1e-15);
}

/* Eq. (25), the dX+/dW output (jw) of ogk_mpsp_switch_jump, on the same closed-form switch:
 * jw = (dxdot / Sdot) S_U P(t_s), i.e. jw[i][k] = -dxdot_i dts_dw[k] with dxdot_vx = -T/m (the
 * v_x row of eq. 24 above), and for every i, j, k the identity
 * jw[i][k] dts_dx[j] = (jx[i][j] - delta_ij) dts_dw[k] (both are dxdot_i S_x,j S_U,k h_k / Sdot^2).
 * Kills the sign mutant of the eq. (25) term (issue 8: no test passed jw before). */
/* req: OGK-MPSP-003 */
static void test_switch_jump_dw_closed_form(void **state)
{
    const double q = ff_q(FF_A0, FF_A1, FF_LM0, FF_M0);
    const double ts = acos(q) / PI;
    const double dts_dq = -1.0 / (PI * sqrt(1.0 - q * q));
    ogk_real_t dts_dx[NX];
    ogk_real_t dts_dw[9];
    ogk_real_t jx[NX * NX];
    ogk_real_t jw[NX * 9];
    ogk_real_t x_s[NX];
    size_t i;
    size_t j;
    size_t k;
    (void)state;

    field_free_config(&cfg, 100.0);
    OGK_ASSERT_STATUS(ogk_mpsp_init(&ctx, &cfg), OGK_OK);
    assert_int_equal(ctx.n_weights, 9u);
    (void)memcpy(x_s, cfg.x0_nom, 7u * sizeof x_s[0]);
    x_s[0] += cfg.x0_nom[3] * ts;
    x_s[7] = FF_LM0;
    OGK_ASSERT_STATUS(ogk_mpsp_switch_jump(&ctx, cfg.weights_nom, 1.0, ts, x_s, 0, jx, jw,
                                           dts_dx, dts_dw), OGK_OK);
    /* closed form of the v_x row: -T/m times -dt_s/dW, with dt_s/dW from eq. (B.2) */
    /* float: measured worst relative 8.6e-8 on M4F and host */
    OGK_ASSERT_REL(jw[3u * 9u + 0u], (-FF_T / FF_M0) * (-(dts_dq * (-0.5 / FF_A1))), OGK_TEST_TOL(1e-9, 1e-6), 1e-12);
    /* float: measured worst relative 1.1e-7 on M4F and host */
    OGK_ASSERT_REL(jw[3u * 9u + 1u], (-FF_T / FF_M0) * (-(dts_dq * (-q / FF_A1))), OGK_TEST_TOL(1e-9, 2e-6), 1e-12);
    assert_true(fabs(jw[3u * 9u + 0u]) > 1e-3); /* not trivially zero */
    /* position rows do not jump (dxdot_r = 0 at a switch) */
    for (k = 0u; k < 9u; ++k) {
        OGK_ASSERT_NEAR(jw[0u * 9u + k], 0.0, 1e-15);
    }
    for (i = 0u; i < NX; ++i) {
        for (j = 0u; j < NX; ++j) {
            for (k = 0u; k < 9u; ++k) {
                const double lhs = jw[i * 9u + k] * dts_dx[j];
                const double rhs = (jx[i * NX + j] - ((i == j) ? 1.0 : 0.0)) * dts_dw[k];
                /* float: measured worst 2.1e-8 on M4F and host */
                OGK_ASSERT_NEAR(lhs, rhs, OGK_TEST_TOL(1e-12, 5e-7) * fmax(1.0, fabs(rhs)));
            }
        }
    }
}

/* T / (m(t) lambda_x(t)) after the switch, for the cross-track quadrature. */
static double ff_cross(double t, double ts)
{
    const double m = FF_M0 - (FF_T / FF_C) * (t - ts);
    const double lam = 0.5 * FF_A0 + FF_A1 * cos(PI * t);
    return FF_T / (m * lam);
}

/* req: OGK-MPSP-003 OGK-MPSP-001 */
static void test_whole_arc_closed_form(void **state)
{
    const double q = ff_q(FF_A0, FF_A1, FF_LM0, FF_M0);
    const double ts = acos(q) / PI;
    const double dts_dq = -1.0 / (PI * sqrt(1.0 - q * q));
    const double m_f = FF_M0 - (FF_T / FF_C) * (1.0 - ts);
    const double dv_dts = FF_T / m_f;                 /* rocket equation */
    const double dr_dts = FF_C * log(FF_M0 / m_f);
    const double dts[3] = {dts_dq * (-0.5 / FF_A1), dts_dq * (-q / FF_A1),
                           dts_dq * (-FF_M0 / (FF_C * FF_A1))}; /* a0, a1, lambda_m0 */
    ogk_real_t dydl[NY];
    ogk_mpsp_prop_t prop;
    size_t nw;
    size_t qb;
    (void)state;

    field_free_config(&cfg, ARC_STEPS);
    OGK_ASSERT_STATUS(ogk_mpsp_init(&ctx, &cfg), OGK_OK);
    nw = ctx.n_weights;
    OGK_ASSERT_STATUS(ogk_mpsp_propagate(&ctx, cfg.weights_nom, FF_LM0, cfg.x0_nom, 1.0, &prop),
                      OGK_OK);
    /* float: measured worst relative 2e-7 on M4F and host */
    OGK_ASSERT_REL(prop.x_f[6], m_f, OGK_TEST_TOL(1e-12, 2e-6), 1.0);
    OGK_ASSERT_STATUS(ogk_mpsp_sensitivity(&ctx, dydw, dydl), OGK_OK);
    /* r_x (row 0) and v_x (row 3): only the switch time moves them. */
    /* float: measured worst relative 2.5e-6 on M4F and host */
    OGK_ASSERT_REL(dydw[0u * nw + 0u], dr_dts * dts[0], OGK_TEST_TOL(1e-6, 5e-5), 1e-9);
    /* float: measured worst relative 1.1e-5 on M4F and host */
    OGK_ASSERT_REL(dydw[0u * nw + 1u], dr_dts * dts[1], OGK_TEST_TOL(1e-6, 2e-4), 1e-9);
    /* float: measured worst relative 1e-6 on M4F and host */
    OGK_ASSERT_REL(dydw[3u * nw + 0u], dv_dts * dts[0], OGK_TEST_TOL(1e-6, 2e-5), 1e-9);
    /* float: measured worst relative 1.4e-5 on M4F and host */
    OGK_ASSERT_REL(dydw[3u * nw + 1u], dv_dts * dts[1], OGK_TEST_TOL(1e-6, 2e-4), 1e-9);
    /* float: measured worst relative 2.5e-6 on M4F and host */
    OGK_ASSERT_REL(dydl[0], dr_dts * dts[2], OGK_TEST_TOL(1e-6, 5e-5), 1e-9);
    /* float: measured worst relative 1e-6 on M4F and host */
    OGK_ASSERT_REL(dydl[3], dv_dts * dts[2], OGK_TEST_TOL(1e-6, 2e-5), 1e-9);

    /* Cross-track (dF/dU block): dv_y/dw_y,q = -int_ts^tf T/(m lambda_x) h_q dt,
     * dr_y/dw_y,q = -int (tf - t) T/(m lambda_x) h_q dt; Simpson, 2000 panels. */
    for (qb = 0u; qb < 3u; ++qb) {
        const size_t n = 2000u;
        const double hq = (1.0 - ts) / (double)n;
        double iv = 0.0;
        double ir = 0.0;
        size_t i;
        for (i = 0u; i <= n; ++i) {
            const double t = ts + hq * (double)i;
            const double wgt = (i == 0u || i == n) ? 1.0 : ((i % 2u) ? 4.0 : 2.0);
            const double basis = (qb == 0u) ? 0.5 : ((qb == 1u) ? cos(PI * t) : sin(PI * t));
            const double f = ff_cross(t, ts) * basis;
            iv += wgt * f;
            ir += wgt * (1.0 - t) * f;
        }
        iv *= -hq / 3.0;
        ir *= -hq / 3.0;
        /* float: measured worst relative 7.3e-6 on M4F and host */
        OGK_ASSERT_REL(dydw[4u * nw + 3u + qb], iv, OGK_TEST_TOL(1e-6, 1e-4), 1e-9);
        /* float: measured worst relative 1.2e-5 on M4F and host */
        OGK_ASSERT_REL(dydw[1u * nw + 3u + qb], ir, OGK_TEST_TOL(1e-6, 2e-4), 1e-9);
    }
}

/* ---------------------------------------------------------------- read-out */

/* req: OGK-MPSP-002 OGK-MPSP-009 */
static void test_control_and_state_readout(void **state)
{
    const double t = 0.77;
    const double th = 2.0 * PI * t / 4.0;
    ogk_real_t lv[3];
    ogk_real_t lvd[3];
    double expect[3];
    ogk_real_t x[NX];
    static ogk_real_t t_nodes[OGK_MPSP_MAX_NODES];
    static ogk_real_t x_nodes[OGK_MPSP_MAX_NODES * NX];
    static uint8_t mode_nodes[OGK_MPSP_MAX_NODES];
    size_t count;
    size_t i;
    size_t c;
    ogk_mpsp_prop_t prop;
    (void)state;

    orbit_config(&cfg, 100.0);
    OGK_ASSERT_STATUS(ogk_mpsp_init(&ctx, &cfg), OGK_OK);
    /* eq. (C.1) written out with libm */
    OGK_ASSERT_STATUS(ogk_mpsp_control(&ctx, w3, t, lv, lvd), OGK_OK);
    for (c = 0u; c < 3u; ++c) {
        const ogk_real_t *w = &w3[7u * c];
        expect[c] = 0.5 * w[0] + w[1] * cos(th) + w[2] * sin(th) + w[3] * cos(2.0 * th) +
                    w[4] * sin(2.0 * th) + w[5] * cos(3.0 * th) + w[6] * sin(3.0 * th);
        /* float: 7 terms |w| <= 2, each with its sine's rounding: 16 eps */
        OGK_ASSERT_NEAR(lv[c], expect[c], OGK_TEST_TOL(1e-14, 16.0 * FLT_EPSILON));
    }
    {
        const double om = 2.0 * PI / 4.0;
        const ogk_real_t *w = &w3[0];
        const double d = om * (-w[1] * sin(th) + w[2] * cos(th)) +
                         2.0 * om * (-w[3] * sin(2.0 * th) + w[4] * cos(2.0 * th)) +
                         3.0 * om * (-w[5] * sin(3.0 * th) + w[6] * cos(3.0 * th));
        /* float: times the harmonics' omega (up to 3 pi / 2): 64 eps */
        OGK_ASSERT_NEAR(lvd[0], d, OGK_TEST_TOL(1e-13, 64.0 * FLT_EPSILON));
    }
    /* The cosine kind: [1/2, cos th, cos 2 th, ..., cos 6 th]. */
    cfg.fourier_kind = OGK_MPSP_BASIS_COSINE;
    cfg.n_seg_nom = 3u;
    OGK_ASSERT_STATUS(ogk_mpsp_init(&ctx, &cfg), OGK_OK);
    OGK_ASSERT_STATUS(ogk_mpsp_control(&ctx, w3, t, lv, lvd), OGK_OK);
    for (c = 0u; c < 3u; ++c) {
        const ogk_real_t *w = &w3[7u * c];
        double d = 0.0;
        expect[c] = 0.5 * w[0];
        for (i = 1u; i <= 6u; ++i) {
            expect[c] += w[i] * cos((double)i * th);
            d -= w[i] * (double)i * (2.0 * PI / 4.0) * sin((double)i * th);
        }
        OGK_ASSERT_NEAR(lv[c], expect[c], OGK_TEST_TOL(1e-14, 16.0 * FLT_EPSILON));
        OGK_ASSERT_NEAR(lvd[c], d, OGK_TEST_TOL(1e-13, 64.0 * FLT_EPSILON));
    }
    cfg.fourier_kind = 7u;
    OGK_ASSERT_STATUS(ogk_mpsp_init(&ctx, &cfg), OGK_E_CONFIG);
    orbit_config(&cfg, 100.0);
    OGK_ASSERT_STATUS(ogk_mpsp_init(&ctx, &cfg), OGK_OK);
    OGK_ASSERT_STATUS(ogk_mpsp_propagate(&ctx, w3, 0.0, x0_3d, 1.0, &prop), OGK_OK);
    OGK_ASSERT_STATUS(ogk_mpsp_trajectory(&ctx, t_nodes, x_nodes, mode_nodes,
                                          OGK_MPSP_MAX_NODES, &count), OGK_OK);
    assert_int_equal(count, prop.n_nodes);
    assert_int_equal(count, 100 + 1 + 2);
    OGK_ASSERT_NEAR(t_nodes[count - 1u], 2.0, 1e-15);
    /* Nodes are reproduced; between nodes pchip is within O(h^3) of the orbit. */
    OGK_ASSERT_STATUS(ogk_mpsp_state_at(&ctx, t_nodes[37], x), OGK_OK);
    for (i = 0u; i < NX; ++i) {
        OGK_ASSERT_NEAR(x[i], x_nodes[37u * NX + i], 1e-14);
    }
    OGK_ASSERT_STATUS(ogk_mpsp_state_at(&ctx, 2.0, x), OGK_OK);
    OGK_ASSERT_NEAR(x[0], prop.x_f[0], 1e-14);
    {
        /* one RK4 step from node 37 to the midpoint as the reference */
        const double tm = 0.5 * (t_nodes[37] + t_nodes[38]);
        ogk_real_t xr[NX];
        OGK_ASSERT_STATUS(ogk_mpsp_step_jacobian(&ctx, w3, 1.0, t_nodes[37],
                                                 &x_nodes[37u * NX], tm - t_nodes[37],
                                                 (int)mode_nodes[37], xr, NULL, NULL),
                          OGK_OK);
        OGK_ASSERT_STATUS(ogk_mpsp_state_at(&ctx, tm, x), OGK_OK);
        for (i = 0u; i < 6u; ++i) {
            OGK_ASSERT_NEAR(x[i], xr[i], 1e-6);
        }
    }
    OGK_ASSERT_STATUS(ogk_mpsp_state_at(&ctx, OGK_TEST_PICK(2.0 + 1e-9, 2.0 + 4.0 * FLT_EPSILON), x), OGK_E_RANGE);
    OGK_ASSERT_STATUS(ogk_mpsp_trajectory(&ctx, t_nodes, NULL, NULL, 10u, &count), OGK_E_DIM);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_step_jacobian_thrust),
        cmocka_unit_test(test_step_jacobian_coast),
        cmocka_unit_test(test_whole_arc_with_switches_fd),
        cmocka_unit_test(test_whole_arc_cosine_basis_fd),
        cmocka_unit_test(test_sweep_matches_step_chain),
#if defined(__SSE2__)
        cmocka_unit_test(test_sweep_kept_u_matches_remade),
#endif
        cmocka_unit_test(test_mid2_sweep_second_order),
        cmocka_unit_test(test_sens_sweep_option_checked),
        cmocka_unit_test(test_switch_time_closed_form),
        cmocka_unit_test(test_switch_jump_dw_closed_form),
        cmocka_unit_test(test_whole_arc_closed_form),
        cmocka_unit_test(test_control_and_state_readout),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
