/* mpsp_sensitivity.c -- sensitivity matrices of the MPSP trajectory:
 * RK4 step Jacobians (Appendix A, with U at the RK4 stage times), the
 * switching compensation (eqs. 22-25, Appendix B) and the backward recursion
 * (eqs. 28-35) that accumulates B_v = sum_k B_k P_k (eq. 40) and A_lambda
 * (eq. 33). Derivations in docs/mpsp.md.
 *
 * The recursion propagates row vectors backwards (B_{k,0} of eq. 35 is
 * d Y / d X_k); each RK4 step is differentiated in reverse through its four
 * stages, which is eq. (A.3)-(A.4) transposed: the same numbers as forming the
 * 8 x 8 step matrices and multiplying, at a fraction of the cost. */
#include "mpsp_internal.h"
#include "ogk/internal/mpsp_test.h"

#include <math.h>
#include <string.h>

#define NX ((size_t)OGK_MPSP_NX)
#define NY OGK_MPSP_NY

#define L ((size_t)MPSP_LANES)

/* Re-runs the stages of ogk_rk4_step (same arithmetic) from x to get the
 * Jacobians at the stage states X_{n,i}; u[0..2] is U at t, t + dt/2, t + dt. */
static ogk_status stage_jacobians(const mpsp_dyn_t *dyn, const double *x, double dt, int mode, /* NOLINT(bugprone-easily-swappable-parameters): order of eqs. (16)/(25); FD-checked by the unit tests */
                                  const double *const *u, mpsp_jac_t *jac)
{
    /* Stage s uses U at t, t + dt/2, t + dt/2, t + dt (u index 0, 1, 1, 2). */
    static const size_t stage_u[4] = {0u, 1u, 1u, 2u};
    double xs[NX];
    double k[NX];
    const double half = 0.5 * dt;
    size_t i;
    size_t s;
    ogk_status st = OGK_OK;

    (void)memcpy(xs, x, sizeof xs);
    for (s = 0u; (s < 4u) && (st == OGK_OK); ++s) {
        const size_t ui = stage_u[s];
        st = mpsp_jacobian(dyn, xs, u[ui], mode, &jac[s]);
        if ((st == OGK_OK) && (s < 3u)) {
            st = mpsp_rhs(dyn, xs, u[ui], mode, k);
        }
        if ((st == OGK_OK) && (s < 3u)) {
            const double step = (s == 2u) ? dt : half;
            for (i = 0u; i < NX; ++i) {
                xs[i] = x[i] + (step * k[i]);
            }
        }
    }
    return st;
}

/* The reverse sweep of mpsp_step_adjoint through the stage Jacobians jac. */
static void reverse_sweep(const mpsp_jac_t *jac, double dt, const double *adj_in, double *adj_out, /* NOLINT(bugprone-easily-swappable-parameters): order of eqs. (16)/(25); FD-checked by the unit tests */
                          double *bu_start, double *bu_mid, double *bu_end) /* NOLINT(bugprone-easily-swappable-parameters): order of eqs. (16)/(25); FD-checked by the unit tests */
{
    double bk[NX * L];
    double bx[NX * L];
    double acc[NX * L];
    const double half = 0.5 * dt;
    const double c6 = dt / 6.0;
    const double c3 = dt / 3.0;
    size_t i;
    size_t r;
    size_t n;

    /* Reverse sweep, all rows w at once (X_next = X + dt/6 (K1 + 2 K2 + 2 K3 + K4)):
     *   bK4 = dt/6 w,            bX4 = bK4 A4
     *   bK3 = dt/3 w + dt bX4,   bX3 = bK3 A3
     *   bK2 = dt/3 w + dt/2 bX3, bX2 = bK2 A2
     *   bK1 = dt/6 w + dt/2 bX2, bX1 = bK1 A1
     *   w dX_next/dX = w + bX1 + bX2 + bX3 + bX4,  w dX_next/dU_i = bKi Di,
     * with A = d f/d X and D = d f/d U of mpsp_jac_t:
     *   (z A)_r = z_v G,  (z A)_v = z_r,  (z A)_m = a_vm z_v.e + a_lm z_lm,  (z A)_lm = 0
     *   (z D) = d_v (z_v - (z_v.e) e) + d_l z_lm e. */
    for (i = 0u; i < NX * L; ++i) {
        bk[i] = c6 * adj_in[i];
        acc[i] = adj_in[i];
    }
    for (n = 0u; n < 4u; ++n) {
        const size_t s = 3u - n; /* stages 4, 3, 2, 1 */
        const mpsp_jac_t *jc = &jac[s];
        const double *g = jc->g;
        for (r = 0u; r < L; ++r) {
            const double zv0 = bk[3u * L + r];
            const double zv1 = bk[4u * L + r];
            const double zv2 = bk[5u * L + r];
            const double ze = (zv0 * jc->e[0]) + (zv1 * jc->e[1]) + (zv2 * jc->e[2]);
            bx[(0u * L) + r] = (zv0 * g[0]) + (zv1 * g[3]) + (zv2 * g[6]);
            bx[(1u * L) + r] = (zv0 * g[1]) + (zv1 * g[4]) + (zv2 * g[7]);
            bx[(2u * L) + r] = (zv0 * g[2]) + (zv1 * g[5]) + (zv2 * g[8]);
            bx[3u * L + r] = bk[0u * L + r];
            bx[4u * L + r] = bk[1u * L + r];
            bx[5u * L + r] = bk[2u * L + r];
            bx[(6u * L) + r] = (jc->a_vm * ze) + (jc->a_lm * bk[(7u * L) + r]);
            bx[7u * L + r] = 0.0;
        }
        if (jc->thrust) {
            double *dst = (s == 0u) ? bu_start : ((s == 3u) ? bu_end : bu_mid);
            size_t c;
            for (c = 0u; c < 3u; ++c) {
                const double ec = jc->e[c];
                for (r = 0u; r < L; ++r) {
                    const double ze = (bk[(3u * L) + r] * jc->e[0]) + (bk[(4u * L) + r] * jc->e[1]) +
                                      (bk[(5u * L) + r] * jc->e[2]);
                    dst[(c * L) + r] += (jc->d_v * (bk[((3u + c) * L) + r] - (ze * ec))) +
                                      (jc->d_l * bk[(7u * L) + r] * ec);
                }
            }
        }
        for (i = 0u; i < NX * L; ++i) {
            acc[i] += bx[i];
        }
        if (s > 0u) {
            /* stage s-1 feeds X_{n,s} = X + cx K_{s-1}: cx = dt for s = 3, dt/2 else */
            const double cx = (s == 3u) ? dt : half;
            const double cw = (s == 1u) ? c6 : c3;
            for (i = 0u; i < NX * L; ++i) {
                bk[i] = (cw * adj_in[i]) + (cx * bx[i]);
            }
        }
    }
    (void)memcpy(adj_out, acc, sizeof acc);
}

ogk_status mpsp_step_adjoint(const mpsp_dyn_t *dyn, const double *x, double dt, int mode, /* NOLINT(bugprone-easily-swappable-parameters): order of eqs. (16)/(25); FD-checked by the unit tests */
                             const double *u_start, const double *u_mid, /* NOLINT(bugprone-easily-swappable-parameters): order of eqs. (16)/(25); FD-checked by the unit tests */
                             const double *u_end, const double *adj_in,
                             double *adj_out, double *bu_start, double *bu_mid, /* NOLINT(bugprone-easily-swappable-parameters): order of eqs. (16)/(25); FD-checked by the unit tests */
                             double *bu_end)
{
    mpsp_jac_t jac[4];
    static const double u_zero[3] = {0.0, 0.0, 0.0};
    const double *u[3];
    ogk_status st;

    u[0] = (mode == 1) ? u_start : u_zero;
    u[1] = (mode == 1) ? u_mid : u_zero;
    u[2] = (mode == 1) ? u_end : u_zero;
    st = stage_jacobians(dyn, x, dt, mode, u, jac);
    if (st == OGK_OK) {
        reverse_sweep(jac, dt, adj_in, adj_out, bu_start, bu_mid, bu_end);
    }
    return st;
}

ogk_status mpsp_jump_terms(mpsp_dyn_t *dyn, double t_s, const double *x_s,
                           int mode_before, mpsp_jump_t *jump)
{
    double h[OGK_MPSP_MAX_BASIS];
    double hdot[OGK_MPSP_MAX_BASIS];
    double u[3];
    double udot[3];
    double f_before[NX];
    double f_after[NX];
    const double m = x_s[6];
    ogk_status st;

    mpsp_basis(dyn, t_s, h, hdot);
    mpsp_control_from_basis(dyn, h, u);
    mpsp_control_from_basis(dyn, hdot, udot);
    st = mpsp_rhs(dyn, x_s, u, mode_before, f_before);
    if (st == OGK_OK) {
        st = mpsp_rhs(dyn, x_s, u, 1 - mode_before, f_after);
    }
    if (st == OGK_OK) {
        double lam;
        double e_udot;
        size_t i;
        lam = sqrt((u[0] * u[0]) + (u[1] * u[1]) + (u[2] * u[2]));
        for (i = 0u; i < NX; ++i) {
            jump->dxdot[i] = f_after[i] - f_before[i];
            jump->s_x[i] = 0.0;
        }
        /* S_X = [0_6, c lambda_v / m^2, -1], S_U = -c/(m lambda_v) lambda_v^T (eq. 25) */
        jump->s_x[6] = dyn->c_exhaust * lam / (m * m);
        jump->s_x[7] = -1.0;
        for (i = 0u; i < 3u; ++i) {
            jump->s_u[i] = -dyn->c_exhaust * u[i] / (m * lam);
        }
        /* Eq. (15): dS/dt = S_U dU/dt (S_X Xdot vanishes identically). */
        e_udot = (jump->s_u[0] * udot[0]) + (jump->s_u[1] * udot[1]) + (jump->s_u[2] * udot[2]);
        jump->s_dot = e_udot;
        if (!isfinite(jump->s_dot) || !(fabs(jump->s_dot) > 0.0)) {
            st = OGK_E_SINGULAR; /* tangential switch: t_s not differentiable */
        }
    }
    return st;
}

/* Columns of the basis-major accumulator: component c of row r at c L + r
 * (the lane-major bu layout). The fixed inner length lets the compiler
 * unroll and vectorise the hottest loop of the sweep. */
#define ACC_W (3u * L)

/* acc[q][j] += h[q] coef[j], q < n_basis, j < ACC_W (eq. 40: dU = P dW). */
static void accumulate_basis(double *acc, size_t n_basis,
                             const double *coef, const double *h) /* NOLINT(bugprone-easily-swappable-parameters): order of eqs. (16)/(25); FD-checked by the unit tests */
{
    size_t q;
    size_t j;
    for (q = 0u; q < n_basis; ++q) {
        const double hq = h[q];
        double *dst = &acc[q * ACC_W];
        for (j = 0u; j < ACC_W; ++j) {
            dst[j] += hq * coef[j];
        }
    }
}

/* acc[q][j] += ha[q] coef_a[j] + hb[q] coef_b[j]: two times in one pass. */
static void accumulate_basis2(double *acc, size_t n_basis,
                              const double *coef_a, const double *ha, /* NOLINT(bugprone-easily-swappable-parameters): order of eqs. (16)/(25); FD-checked by the unit tests */
                              const double *coef_b, const double *hb) /* NOLINT(bugprone-easily-swappable-parameters): order of eqs. (16)/(25); FD-checked by the unit tests */
{
    size_t q;
    size_t j;
    for (q = 0u; q < n_basis; ++q) {
        const double hqa = ha[q];
        const double hqb = hb[q];
        double *dst = &acc[q * ACC_W];
        for (j = 0u; j < ACC_W; ++j) {
            dst[j] += (hqa * coef_a[j]) + (hqb * coef_b[j]);
        }
    }
}

/* out[r][c n_basis + q] += coef[c L + r] h[q], row-major rows x 3 n_basis
 * (the one-step Jacobian; not on the hot path). */
static void accumulate_rows(double *out, size_t n_basis, size_t rows, const double *coef, /* NOLINT(bugprone-easily-swappable-parameters): order of eqs. (16)/(25); FD-checked by the unit tests */
                            const double *h)
{
    const size_t n_weights = 3u * n_basis;
    size_t r;
    size_t c;
    size_t q;
    for (r = 0u; r < rows; ++r) {
        for (c = 0u; c < 3u; ++c) {
            for (q = 0u; q < n_basis; ++q) {
                out[(r * n_weights) + (c * n_basis) + q] += coef[(c * L) + r] * h[q];
            }
        }
    }
}

/* out[r][c n_basis + q] = acc[q][c L + r] for r < rows. */
static void unpack_basis(const double *acc, size_t n_basis, size_t rows, double *out) /* NOLINT(bugprone-easily-swappable-parameters): order of eqs. (16)/(25); FD-checked by the unit tests */
{
    const size_t n_weights = 3u * n_basis;
    size_t r;
    size_t c;
    size_t q;
    for (r = 0u; r < rows; ++r) {
        for (c = 0u; c < 3u; ++c) {
            for (q = 0u; q < n_basis; ++q) {
                out[(r * n_weights) + (c * n_basis) + q] = acc[(q * ACC_W) + (c * L) + r];
            }
        }
    }
}

static ogk_status check_ctx(const ogk_mpsp_t *ctx)
{
    ogk_status st;

    if (ctx == NULL) {
        st = OGK_E_NULL;
    } else {
        st = (ctx->init_marker == OGK_MPSP_INIT_MARKER) ? OGK_OK : OGK_E_NOT_INIT;
    }
    return st;
}

static ogk_status check_mode_scale(double thrust_scale, int mode)
{
    ogk_status st = OGK_OK;

    if (!isfinite(thrust_scale)) {
        st = OGK_E_NONFINITE;
    } else if ((!(thrust_scale > 0.0)) || ((mode != 0) && (mode != 1))) {
        st = OGK_E_RANGE;
    } else {
        /* a usable scale and mode */
    }
    return st;
}

/* The partials of the RK4 step of ogk_mpsp_step_jacobian (x_next already
 * taken): dF/dX and dF/dW through the adjoint of the step, each if asked. */
static ogk_status step_partials(const ogk_mpsp_t *ctx, const mpsp_dyn_t *dyn, double t, /* NOLINT(bugprone-easily-swappable-parameters): order of eqs. (16)/(25); FD-checked by the unit tests */
                                const double *x, double dt, int mode, double *dfdx, /* NOLINT(bugprone-easily-swappable-parameters): order of eqs. (16)/(25); FD-checked by the unit tests */
                                double *dfdw)
{
    double h0[OGK_MPSP_MAX_BASIS];
    double hm[OGK_MPSP_MAX_BASIS];
    double h1[OGK_MPSP_MAX_BASIS];
    double eye[NX * L];
    double adj[NX * L];
    double b0[ACC_W];
    double bm[ACC_W];
    double b1[ACC_W];
    size_t i;
    ogk_status st;

    mpsp_basis(dyn, t, h0, NULL);
    mpsp_basis(dyn, t + (0.5 * dt), hm, NULL);
    mpsp_basis(dyn, t + dt, h1, NULL);
    (void)memset(eye, 0, sizeof eye);
    (void)memset(b0, 0, sizeof b0);
    (void)memset(bm, 0, sizeof bm);
    (void)memset(b1, 0, sizeof b1);
    for (i = 0u; i < NX; ++i) {
        eye[i * L + i] = 1.0; /* row i seeds d X_next[i] */
    }
    {
        double u0[3];
        double um[3];
        double u1[3];
        mpsp_control_from_basis(dyn, h0, u0);
        mpsp_control_from_basis(dyn, hm, um);
        mpsp_control_from_basis(dyn, h1, u1);
        st = mpsp_step_adjoint(dyn, x, dt, mode, u0, um, u1, eye, adj, b0, bm, b1);
    }
    if ((st == OGK_OK) && (dfdx != NULL)) {
        size_t j;
        for (i = 0u; i < NX; ++i) {
            for (j = 0u; j < NX; ++j) {
                dfdx[i * NX + j] = adj[j * L + i];
            }
        }
    }
    if ((st == OGK_OK) && (dfdw != NULL)) {
        (void)memset(dfdw, 0, NX * ctx->n_weights * sizeof dfdw[0]);
        accumulate_rows(dfdw, ctx->n_basis, NX, b0, h0);
        accumulate_rows(dfdw, ctx->n_basis, NX, bm, hm);
        accumulate_rows(dfdw, ctx->n_basis, NX, b1, h1);
    }
    return st;
}

ogk_status ogk_mpsp_step_jacobian(const ogk_mpsp_t *ctx, const double *weights,
                                  double thrust_scale, double t, const double *x, /* NOLINT(bugprone-easily-swappable-parameters): order of eqs. (16)/(25); FD-checked by the unit tests */
                                  double dt, int mode, double *x_next, /* NOLINT(bugprone-easily-swappable-parameters): order of eqs. (16)/(25); FD-checked by the unit tests */
                                  double *dfdx, double *dfdw)
{
    ogk_status st = check_ctx(ctx);

    if ((st == OGK_OK) && ((weights == NULL) || (x == NULL) || (x_next == NULL))) {
        st = OGK_E_NULL;
    }
    if (st == OGK_OK) {
        st = check_mode_scale(thrust_scale, mode);
    }
    if ((st == OGK_OK) && (!isfinite(t) || !isfinite(dt) || !ogk_i_all_finite(x, NX) ||
                           !ogk_i_all_finite(weights, ctx->n_weights))) {
        st = OGK_E_NONFINITE;
    }
    if ((st == OGK_OK) && (dt == 0.0)) {
        st = OGK_E_RANGE;
    }
    if (st == OGK_OK) {
        mpsp_dyn_t dyn;
        ogk_rk4_problem_t prob;
        mpsp_dyn_setup(&dyn, ctx, weights, ctx->cfg.t_max * thrust_scale);
        mpsp_rk4_problem(&prob, ctx, &dyn);
        prob.sw = NULL;
        st = ogk_rk4_step(&prob, t, x, dt, mode, x_next);
        if ((st == OGK_OK) && ((dfdx != NULL) || (dfdw != NULL))) {
            st = step_partials(ctx, &dyn, t, x, dt, mode, dfdx, dfdw);
        }
    }
    return st;
}

/* The argument checks of ogk_mpsp_switch_jump, in their order. */
static ogk_status check_jump_args(const ogk_mpsp_t *ctx, const double *weights, double thrust_scale, /* NOLINT(bugprone-easily-swappable-parameters): order of eqs. (16)/(25); FD-checked by the unit tests */
                                  double t_s, const double *x_s, int mode_before)
{
    ogk_status st = check_ctx(ctx);

    if ((st == OGK_OK) && ((weights == NULL) || (x_s == NULL))) {
        st = OGK_E_NULL;
    }
    if (st == OGK_OK) {
        st = check_mode_scale(thrust_scale, mode_before);
    }
    if ((st == OGK_OK) && (!isfinite(t_s) || !ogk_i_all_finite(x_s, NX) ||
                           !ogk_i_all_finite(weights, ctx->n_weights))) {
        st = OGK_E_NONFINITE;
    }
    return st;
}

ogk_status ogk_mpsp_switch_jump(const ogk_mpsp_t *ctx, const double *weights,
                                double thrust_scale, double t_s, const double *x_s, /* NOLINT(bugprone-easily-swappable-parameters): order of eqs. (16)/(25); FD-checked by the unit tests */
                                int mode_before, double *jx, double *jw, /* NOLINT(bugprone-easily-swappable-parameters): order of eqs. (16)/(25); FD-checked by the unit tests */
                                double *dts_dx, double *dts_dw)
{
    mpsp_dyn_t dyn;
    mpsp_jump_t jump;
    double h[OGK_MPSP_MAX_BASIS];
    ogk_status st = check_jump_args(ctx, weights, thrust_scale, t_s, x_s, mode_before);

    if (st == OGK_OK) {
        mpsp_dyn_setup(&dyn, ctx, weights, ctx->cfg.t_max * thrust_scale);
        st = mpsp_jump_terms(&dyn, t_s, x_s, mode_before, &jump);
    }
    if (st == OGK_OK) {
        size_t i;
        size_t j;
        size_t c;
        size_t q;
        mpsp_basis(&dyn, t_s, h, NULL);
        /* Eq. (24): I + dxdot S_X / Sdot;  eq. (25) with dU = P(t_s) dW. */
        for (i = 0u; i < NX; ++i) {
            const double a = jump.dxdot[i] / jump.s_dot;
            if (jx != NULL) {
                for (j = 0u; j < NX; ++j) {
                    jx[(i * NX) + j] = ((i == j) ? 1.0 : 0.0) + (a * jump.s_x[j]);
                }
            }
            if (jw != NULL) {
                for (c = 0u; c < 3u; ++c) {
                    for (q = 0u; q < ctx->n_basis; ++q) {
                        jw[(i * ctx->n_weights) + (c * ctx->n_basis) + q] = a * jump.s_u[c] * h[q];
                    }
                }
            }
        }
        /* Eq. (B.2): dt_s = -(S_X dX- + S_U dU) / Sdot. */
        if (dts_dx != NULL) {
            for (j = 0u; j < NX; ++j) {
                dts_dx[j] = -jump.s_x[j] / jump.s_dot;
            }
        }
        if (dts_dw != NULL) {
            for (c = 0u; c < 3u; ++c) {
                for (q = 0u; q < ctx->n_basis; ++q) {
                    dts_dw[(c * ctx->n_basis) + q] = -jump.s_u[c] * h[q] / jump.s_dot;
                }
            }
        }
    }
    return st;
}

/* Eqs. (22)-(25) at the switch node k + 1 (time t_hi, state x_hi) of the
 * backward recursion: the rows adj compensated and the S_U part added to
 * pend (bU at t_hi). */
static ogk_status switch_compensation(mpsp_dyn_t *dyn, double t_hi, const double *x_hi, int mode, /* NOLINT(bugprone-easily-swappable-parameters): order of eqs. (16)/(25); FD-checked by the unit tests */
                                      double *adj, double *pend) /* NOLINT(bugprone-easily-swappable-parameters): order of eqs. (16)/(25); FD-checked by the unit tests */
{
    mpsp_jump_t jump;
    const ogk_status st = mpsp_jump_terms(dyn, t_hi, x_hi, mode, &jump);

    if (st == OGK_OK) {
        size_t r;
        size_t i;
        for (r = 0u; r < NY; ++r) {
            double a = 0.0;
            for (i = 0u; i < NX; ++i) {
                a += adj[i * L + r] * jump.dxdot[i];
            }
            a /= jump.s_dot;
            for (i = 0u; i < 3u; ++i) {
                pend[i * L + r] += a * jump.s_u[i];
            }
            for (i = 0u; i < NX; ++i) {
                adj[i * L + r] += a * jump.s_x[i];
            }
        }
    }
    return st;
}

/* The backward recursion of ogk_mpsp_sensitivity over the trajectory held
 * (at least 2 nodes): ctx->dy_dw and ctx->dy_dlm0, both left as they were
 * when a step or switch fails. */
static ogk_status backward_recursion(ogk_mpsp_t *ctx)
{
    mpsp_dyn_t dyn;
    double adj[NX * L];
    double adj_next[NX * L];
    double pend[ACC_W];
    double bu0[ACC_W];
    double bum[ACC_W];
    double bu1[ACC_W];
    double h_hi[OGK_MPSP_MAX_BASIS];
    double h_lo[OGK_MPSP_MAX_BASIS];
    double h_mid[OGK_MPSP_MAX_BASIS];
    double u_hi[3] = {0.0, 0.0, 0.0};
    double u_lo[3] = {0.0, 0.0, 0.0};
    double u_mid[3] = {0.0, 0.0, 0.0};
    bool h_hi_ok = false;
    bool pend_nonzero = false;
    size_t nodes;
    size_t kk;
    size_t r;
    size_t i;
    ogk_status st = OGK_OK;

    mpsp_dyn_setup(&dyn, ctx, ctx->weights, ctx->thrust);
    nodes = ctx->n_nodes;

    /* dY/dX(tf): Y = [r, v, lambda_m] */
    (void)memset(adj, 0, sizeof adj);
    for (r = 0u; r < 6u; ++r) {
        adj[r * L + r] = 1.0;
    }
    adj[7u * L + 6u] = 1.0;
    (void)memset(pend, 0, sizeof pend);
    (void)memset(ctx->bv_acc, 0, ctx->n_basis * ACC_W * sizeof ctx->bv_acc[0]);

    for (kk = 1u; (kk < nodes) && (st == OGK_OK); ++kk) {
        const size_t k = nodes - 1u - kk; /* step k: node k -> k + 1 */
        const double t_lo = ctx->traj_t[k];
        const double t_hi = ctx->traj_t[k + 1u];
        const double dt = t_hi - t_lo;
        const int mode = (int)ctx->traj_mode[k];

        /* Switch at node k + 1 (mode changes there): eqs. (22)-(25). */
        if (ctx->traj_mode[k + 1u] != ctx->traj_mode[k]) {
            st = switch_compensation(&dyn, t_hi, &ctx->traj_x[(k + 1u) * NX], mode, adj, pend);
            pend_nonzero = true;
        }
        if (st == OGK_OK) {
            if (((mode == 1) || pend_nonzero) && (!h_hi_ok)) {
                mpsp_basis(&dyn, t_hi, h_hi, NULL);
                mpsp_control_from_basis(&dyn, h_hi, u_hi);
            }
            if (mode == 1) {
                mpsp_basis(&dyn, t_lo + (0.5 * dt), h_mid, NULL);
                mpsp_basis(&dyn, t_lo, h_lo, NULL);
                mpsp_control_from_basis(&dyn, h_mid, u_mid);
                mpsp_control_from_basis(&dyn, h_lo, u_lo);
            }
            (void)memset(bu0, 0, sizeof bu0);
            (void)memset(bum, 0, sizeof bum);
            (void)memset(bu1, 0, sizeof bu1);
            st = mpsp_step_adjoint(&dyn, &ctx->traj_x[k * NX], dt, mode, u_lo, u_mid, u_hi,
                                   adj, adj_next, bu0, bum, bu1);
        }
        if (st == OGK_OK) {
            (void)memcpy(adj, adj_next, sizeof adj);
            if (mode == 1) {
                /* t_hi gathers stage 4 of this step, stage 1 of the step above
                 * and a switch there; t_lo + dt/2 gathers stages 2 and 3. */
                for (i = 0u; i < ACC_W; ++i) {
                    pend[i] += bu1[i];
                }
                accumulate_basis2(ctx->bv_acc, ctx->n_basis, pend, h_hi, bum, h_mid);
                (void)memcpy(pend, bu0, sizeof pend);
                pend_nonzero = true;
                (void)memcpy(h_hi, h_lo, sizeof h_hi);
                (void)memcpy(u_hi, u_lo, sizeof u_hi);
                h_hi_ok = true;
            } else {
                if (pend_nonzero) {
                    accumulate_basis(ctx->bv_acc, ctx->n_basis, pend, h_hi);
                }
                (void)memset(pend, 0, sizeof pend);
                pend_nonzero = false;
                h_hi_ok = false;
            }
        }
    }
    if (st == OGK_OK) {
        if (pend_nonzero) {
            if (!h_hi_ok) {
                mpsp_basis(&dyn, ctx->traj_t[0], h_hi, NULL);
            }
            accumulate_basis(ctx->bv_acc, ctx->n_basis, pend, h_hi);
        }
        unpack_basis(ctx->bv_acc, ctx->n_basis, NY, ctx->dy_dw);
        /* Eq. (33): A_lambda is the lambda_m column of dY/dX(t0). */
        for (r = 0u; r < NY; ++r) {
            ctx->dy_dlm0[r] = adj[7u * L + r];
        }
    }
    return st;
}

/* Backward recursion over the dense trajectory held (eqs. 28-35):
 *   w = dY/dX(tf) (selection of r, v, lambda_m);
 *   for each node k+1 (from the end): at a switch node
 *     bU(t_s) += (w dxdot / Sdot) S_U,  w := w + (w dxdot / Sdot) S_X  (eqs. 22-25);
 *   step k (node k -> k+1) in reverse, giving w := w dF/dX and bU at the
 *   stage times; B_v += bU(t) h(t)^T per block (eq. 40: dU = P dW).
 *   bU at a node time gathers stage 4 of the step below, stage 1 of the step
 *   above and any switch there, so h is evaluated once per node and once per
 *   step midpoint, and not at all in coast (U does not enter eq. 16 there). */
ogk_status ogk_mpsp_sensitivity(ogk_mpsp_t *ctx, double *dy_dw, double *dy_dlm0)
{
    ogk_status st = check_ctx(ctx);

    if ((st == OGK_OK) && ((ctx->traj_valid == 0u) || (ctx->n_nodes < 2u))) {
        st = OGK_E_NOT_INIT;
    }
    if (st == OGK_OK) {
        ctx->sens_valid = 0u;
        st = backward_recursion(ctx);
    }
    if (st == OGK_OK) {
        if (!ogk_i_all_finite(ctx->dy_dw, NY * ctx->n_weights) ||
            !ogk_i_all_finite(ctx->dy_dlm0, NY)) {
            st = OGK_E_NONFINITE;
        } else {
            ctx->sens_valid = 1u;
            if (dy_dw != NULL) {
                (void)memcpy(dy_dw, ctx->dy_dw, NY * ctx->n_weights * sizeof dy_dw[0]);
            }
            if (dy_dlm0 != NULL) {
                (void)memcpy(dy_dlm0, ctx->dy_dlm0, sizeof ctx->dy_dlm0);
            }
        }
    }
    return st;
}
