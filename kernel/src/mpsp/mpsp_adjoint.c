/* mpsp_adjoint.c -- the adjoint of one RK4 step of eq. (16) (Appendix A,
 * transposed) for the backward recursion of mpsp_sensitivity.c: the stage
 * partials and the rows w -> w dX_next/dX with their control sensitivities,
 * one row at a time (every target) or two rows per pass (x86-64, where gcc
 * -O2 carries the pair in SSE2 registers). Derivation and costs: docs/design/mpsp.md,
 * sections 3 and 8. */
#include "mpsp_internal.h"
#include "../rk4_internal.h"

#include <string.h>

#define NX ((size_t)OGK_MPSP_NX)

/* The partials of eq. (16) at the four stage states of the RK4 step from x
 * (ogk_rk4_step's stages, same arithmetic); uv[0..2] is U at t, t + dt/2,
 * t + dt, used by stages 1, 2-3 and 4. */
static ogk_status stage_partials(const ogk_i_mpsp_dyn_t *dyn, const ogk_real_t *x, ogk_real_t dt, int mode, /* NOLINT(bugprone-easily-swappable-parameters): order of eqs. (16)/(25); FD-checked by the unit tests */
                                 const ogk_i_mpsp_uval_t *uv, ogk_i_mpsp_stage_t *sd)
{
    static const size_t stage_u[4] = {0u, 1u, 1u, 2u};
    ogk_real_t xs[NX];
    ogk_real_t k[NX];
    const ogk_real_t half = OGK_R(0.5) * dt;
    size_t s;
    ogk_status st = OGK_OK;

    (void)memcpy(xs, x, sizeof xs);
    for (s = 0u; (s < 4u) && (st == OGK_OK); ++s) {
        if (s < 3u) {
            const ogk_real_t step = (s == 2u) ? dt : half;
            st = ogk_i_mpsp_stage_eval(dyn, xs, &uv[stage_u[s]], mode, k, &sd[s]);
            ogk_i_rk4_stage_state(x, step, k, NX, xs);
        } else {
            st = ogk_i_mpsp_stage_eval(dyn, xs, &uv[stage_u[s]], mode, NULL, &sd[s]);
        }
    }
    return st;
}

/* Stage s of the reverse sweep for one row, z = bK_s with z_v = zv and
 * z_lm = zl: bx = (z A_s)_r = G z_v, b = z D_s (thrust only); returns
 * (z A_s)_m = a_vm z_v.e + a_lm z_lm, 0 in coast (a_vm = a_lm = 0 there).
 * A and D as in reverse_row; lane 0 of the partials (ogk_i_mpsp_stage_t). */
static inline ogk_real_t stage_back(const ogk_i_mpsp_stage_t *p, const ogk_real_t *zv, ogk_real_t zl, bool thrust, /* NOLINT(bugprone-easily-swappable-parameters): order of eqs. (16)/(25); FD-checked by the unit tests */
                         ogk_real_t *bx, ogk_real_t *b)
{
    const ogk_real_t *g = p->g;
    ogk_real_t ret = OGK_R(0.0);
    bx[0] = (zv[0] * g[0]) + (zv[1] * g[MPSP_SL]) + (zv[2] * g[2u * MPSP_SL]);
    bx[1] = (zv[0] * g[MPSP_SL]) + (zv[1] * g[3u * MPSP_SL]) + (zv[2] * g[4u * MPSP_SL]);
    bx[2] = (zv[0] * g[2u * MPSP_SL]) + (zv[1] * g[4u * MPSP_SL]) + (zv[2] * g[5u * MPSP_SL]);
    if (thrust) {
        const ogk_real_t *e = p->e;
        const ogk_real_t ze = (zv[0] * e[0]) + (zv[1] * e[MPSP_SL]) + (zv[2] * e[2u * MPSP_SL]);
        const ogk_real_t alpha = (p->d_l[0] * zl) - (p->d_v[0] * ze);
        b[0] = (p->d_v[0] * zv[0]) + (alpha * e[0]);
        b[1] = (p->d_v[0] * zv[1]) + (alpha * e[MPSP_SL]);
        b[2] = (p->d_v[0] * zv[2]) + (alpha * e[2u * MPSP_SL]);
        ret = (p->a_vm[0] * ze) + (p->a_lm[0] * zl);
    }
    return ret;
}

/* One adjoint row w through the reverse sweep of a step with stage partials
 * sd (X_next = X + dt/6 (K1 + 2 K2 + 2 K3 + K4)):
 *   bK4 = dt/6 w,            bX4 = bK4 A4
 *   bK3 = dt/3 w + dt bX4,   bX3 = bK3 A3
 *   bK2 = dt/3 w + dt/2 bX3, bX2 = bK2 A2
 *   bK1 = dt/6 w + dt/2 bX2, bX1 = bK1 A1
 *   w dX_next/dX = w + bX1 + bX2 + bX3 + bX4,  w dX_next/dU_i = bKi Di,
 * with A = d f/d X and D = d f/d U of ogk_i_mpsp_stage_t; for z = bK,
 *   (z A)_r = z_v G,  (z A)_v = z_r,  (z A)_m = a_vm z_v.e + a_lm z_lm,  (z A)_lm = 0,
 *   z D = d_v z_v + (d_l z_lm - d_v z_v.e) e.
 * f_m is constant and no f depends on lambda_m, so z_m never enters and the
 * lambda_m component of w passes unchanged (z_lm = (dt/6 or dt/3) w_lm); with
 * (bX)_v = (bK)_r the sweep needs only z_v and bX_r per stage:
 *   (bK4)_v = dt/6 w_v,  (bK3)_v = dt/3 w_v + dt (dt/6 w_r),
 *   (bK2)_v = dt/3 w_v + dt/2 (dt/3 w_r + dt (bX4)_r),
 *   (bK1)_v = dt/6 w_v + dt/2 (dt/3 w_r + dt/2 (bX3)_r).
 * b_start, b_mid, b_end (3 each) receive w dX_next/dU at t, t + dt/2 and
 * t + dt in thrust. w_out may be w. */
static void reverse_row(const ogk_i_mpsp_stage_t *sd, ogk_real_t dt, bool thrust, const ogk_real_t *w, /* NOLINT(bugprone-easily-swappable-parameters): order of eqs. (16)/(25); FD-checked by the unit tests */
                        ogk_real_t *w_out, ogk_real_t *b_start, ogk_real_t *b_mid, ogk_real_t *b_end) /* NOLINT(bugprone-easily-swappable-parameters): order of eqs. (16)/(25); FD-checked by the unit tests */
{
    const ogk_real_t half = OGK_R(0.5) * dt;
    const ogk_real_t c6 = dt / OGK_R(6.0);
    const ogk_real_t c3 = dt / OGK_R(3.0);
    ogk_real_t zv[3];
    ogk_real_t bx4[3];
    ogk_real_t bx3[3];
    ogk_real_t bx[3];
    ogk_real_t b[3];
#if OGK_REAL_SINGLE
    /* Written by stage 3 and read at stage 2, both only in thrust: gcc 12's
     * -O2 of the float build (x86-64) does not see it (-Wmaybe-uninitialized).
     * Not in the double build, whose object code stays as it was. */
    ogk_real_t bm[3] = {OGK_R(0.0), OGK_R(0.0), OGK_R(0.0)};
#else
    ogk_real_t bm[3];
#endif
    ogk_real_t ar[3];
    ogk_real_t av[3];
    ogk_real_t zr2[3];
    ogk_real_t am;

    /* stage 4: (bK4)_v = dt/6 w_v */
    zv[0] = c6 * w[3];
    zv[1] = c6 * w[4];
    zv[2] = c6 * w[5];
    am = w[6] + stage_back(&sd[3], zv, c6 * w[7], thrust, bx4, b);
    if (thrust) {
        b_end[0] = b[0];
        b_end[1] = b[1];
        b_end[2] = b[2];
    }
    /* stage 3: (bK3)_v = dt/3 w_v + dt (bK4)_r, (bK4)_r = dt/6 w_r */
    zv[0] = (c3 * w[3]) + (dt * (c6 * w[0]));
    zv[1] = (c3 * w[4]) + (dt * (c6 * w[1]));
    zv[2] = (c3 * w[5]) + (dt * (c6 * w[2]));
    am += stage_back(&sd[2], zv, c3 * w[7], thrust, bx3, bm);
    /* stage 2: (bK3)_r = dt/3 w_r + dt (bX4)_r, (bK2)_v = dt/3 w_v + dt/2 (bK3)_r */
    zv[0] = (c3 * w[0]) + (dt * bx4[0]);
    zv[1] = (c3 * w[1]) + (dt * bx4[1]);
    zv[2] = (c3 * w[2]) + (dt * bx4[2]);
    av[0] = (w[3] + (c6 * w[0])) + zv[0];
    av[1] = (w[4] + (c6 * w[1])) + zv[1];
    av[2] = (w[5] + (c6 * w[2])) + zv[2];
    zv[0] = (c3 * w[3]) + (half * zv[0]);
    zv[1] = (c3 * w[4]) + (half * zv[1]);
    zv[2] = (c3 * w[5]) + (half * zv[2]);
    ar[0] = (w[0] + bx4[0]) + bx3[0];
    ar[1] = (w[1] + bx4[1]) + bx3[1];
    ar[2] = (w[2] + bx4[2]) + bx3[2];
    am += stage_back(&sd[1], zv, c3 * w[7], thrust, bx, b);
    if (thrust) {
        b_mid[0] = bm[0] + b[0];
        b_mid[1] = bm[1] + b[1];
        b_mid[2] = bm[2] + b[2];
    }
    /* stage 1: (bK2)_r = dt/3 w_r + dt/2 (bX3)_r, (bK1)_v = dt/6 w_v + dt/2 (bK2)_r,
     * (bK1)_r = dt/6 w_r + dt/2 (bX2)_r */
    zr2[0] = (c3 * w[0]) + (half * bx3[0]);
    zr2[1] = (c3 * w[1]) + (half * bx3[1]);
    zr2[2] = (c3 * w[2]) + (half * bx3[2]);
    av[0] = (av[0] + zr2[0]) + ((c6 * w[0]) + (half * bx[0]));
    av[1] = (av[1] + zr2[1]) + ((c6 * w[1]) + (half * bx[1]));
    av[2] = (av[2] + zr2[2]) + ((c6 * w[2]) + (half * bx[2]));
    ar[0] += bx[0];
    ar[1] += bx[1];
    ar[2] += bx[2];
    zv[0] = (c6 * w[3]) + (half * zr2[0]);
    zv[1] = (c6 * w[4]) + (half * zr2[1]);
    zv[2] = (c6 * w[5]) + (half * zr2[2]);
    am += stage_back(&sd[0], zv, c6 * w[7], thrust, bx, b);
    if (thrust) {
        b_start[0] = b[0];
        b_start[1] = b[1];
        b_start[2] = b[2];
    }
    /* w dX_next/dX = w + bX1 + bX2 + bX3 + bX4, (bX)_v = (bK)_r; lambda_m passes */
    w_out[7] = w[7];
    w_out[0] = ar[0] + bx[0];
    w_out[1] = ar[1] + bx[1];
    w_out[2] = ar[2] + bx[2];
    w_out[3] = av[0];
    w_out[4] = av[1];
    w_out[5] = av[2];
    w_out[6] = am;
}

/* reverse_row for a row with w_r = w_v = 0 (the row of lambda_m(tf): switches
 * change only its m and lambda_m components, S_X = [0_6, ., .]): z_v = 0 at
 * every stage, so bX_r = 0, the row keeps w_r = w_v = 0 and
 *   (w dX_next/dX)_m = w_m + sum_s a_lm,s z_lm,s,   w dX_next/dU_s = d_l,s z_lm,s e_s,
 * the same numbers as reverse_row gives with z_v = 0. */
static void reverse_row_mass(const ogk_i_mpsp_stage_t *sd, ogk_real_t dt, bool thrust, const ogk_real_t *w, /* NOLINT(bugprone-easily-swappable-parameters): order of eqs. (16)/(25); FD-checked by the unit tests */
                             ogk_real_t *w_out, ogk_real_t *b_start, ogk_real_t *b_mid, ogk_real_t *b_end) /* NOLINT(bugprone-easily-swappable-parameters): order of eqs. (16)/(25); FD-checked by the unit tests */
{
    const ogk_real_t z6 = (dt / OGK_R(6.0)) * w[7];
    const ogk_real_t z3 = (dt / OGK_R(3.0)) * w[7];
    ogk_real_t am = w[6] + (sd[3].a_lm[0] * z6);

    am += sd[2].a_lm[0] * z3;
    am += sd[1].a_lm[0] * z3;
    am += sd[0].a_lm[0] * z6;
    if (thrust) {
        size_t i;
        for (i = 0u; i < 3u; ++i) {
            const size_t j = i * MPSP_SL;
            b_end[i] = (sd[3].d_l[0] * z6) * sd[3].e[j];
            b_mid[i] = ((sd[2].d_l[0] * z3) * sd[2].e[j]) + ((sd[1].d_l[0] * z3) * sd[1].e[j]);
            b_start[i] = (sd[0].d_l[0] * z6) * sd[0].e[j];
        }
    }
    w_out[0] = OGK_R(0.0);
    w_out[1] = OGK_R(0.0);
    w_out[2] = OGK_R(0.0);
    w_out[3] = OGK_R(0.0);
    w_out[4] = OGK_R(0.0);
    w_out[5] = OGK_R(0.0);
    w_out[6] = am;
    w_out[7] = w[7];
}

#if defined(__SSE2__)
/* stage_back for two rows (lanes l = 0, 1; component i of lane l at
 * [i * 2 + l]), the same arithmetic in the same order per lane; ret[l] is
 * stage_back's return value. Every input is read into locals before any
 * output is written (no aliasing to assume), and each statement is a loop
 * over the lanes, so that gcc -O2 on x86-64 carries a pair in one SSE2
 * register (SLP); the partials are read as pairs (MPSP_SL = 2). */
static void stage_back2(const ogk_i_mpsp_stage_t *p, const ogk_real_t *zv_in, const ogk_real_t *zl_in, /* NOLINT(bugprone-easily-swappable-parameters): order of eqs. (16)/(25); FD-checked by the unit tests */
                        bool thrust, ogk_real_t *bx_out, ogk_real_t *b_out, ogk_real_t *ret) /* NOLINT(bugprone-easily-swappable-parameters): order of eqs. (16)/(25); FD-checked by the unit tests */
{
    const ogk_real_t *g = p->g;
    ogk_real_t zv[6];
    ogk_real_t bx[6];
    size_t l;

    for (l = 0u; l < 2u; ++l) {
        zv[l] = zv_in[l];
        zv[2u + l] = zv_in[2u + l];
        zv[4u + l] = zv_in[4u + l];
    }
    for (l = 0u; l < 2u; ++l) {
        bx[l] = (zv[l] * g[l]) + (zv[2u + l] * g[2u + l]) + (zv[4u + l] * g[4u + l]);
        bx[2u + l] = (zv[l] * g[2u + l]) + (zv[2u + l] * g[6u + l]) + (zv[4u + l] * g[8u + l]);
        bx[4u + l] = (zv[l] * g[4u + l]) + (zv[2u + l] * g[8u + l]) + (zv[4u + l] * g[10u + l]);
    }
    if (thrust) {
        const ogk_real_t *e = p->e;
        ogk_real_t zl[2];
        ogk_real_t ze[2];
        ogk_real_t r[2];
        ogk_real_t b[6];
        for (l = 0u; l < 2u; ++l) {
            zl[l] = zl_in[l];
        }
        for (l = 0u; l < 2u; ++l) {
            ogk_real_t alpha;
            ze[l] = (zv[l] * e[l]) + (zv[2u + l] * e[2u + l]) + (zv[4u + l] * e[4u + l]);
            alpha = (p->d_l[l] * zl[l]) - (p->d_v[l] * ze[l]);
            b[l] = (p->d_v[l] * zv[l]) + (alpha * e[l]);
            b[2u + l] = (p->d_v[l] * zv[2u + l]) + (alpha * e[2u + l]);
            b[4u + l] = (p->d_v[l] * zv[4u + l]) + (alpha * e[4u + l]);
            r[l] = (p->a_vm[l] * ze[l]) + (p->a_lm[l] * zl[l]);
        }
        (void)memcpy(b_out, b, sizeof b);
        ret[0] = r[0];
        ret[1] = r[1];
    } else { /* a_vm = a_lm = 0 in coast */
        ret[0] = OGK_R(0.0);
        ret[1] = OGK_R(0.0);
    }
    (void)memcpy(bx_out, bx, sizeof bx);
}

/* Two adjoint rows w_in[0..7], w_in[8..15] into lanes: component i of row l
 * at w[i * 2 + l], the layout of the paired passes below. */
static inline void rows2_to_lanes(const ogk_real_t *w_in, ogk_real_t *w)
{
    size_t l;

    for (l = 0u; l < 2u; ++l) {
        const ogk_real_t *wl = &w_in[l * NX];
        w[l] = wl[0];
        w[2u + l] = wl[1];
        w[4u + l] = wl[2];
        w[6u + l] = wl[3];
        w[8u + l] = wl[4];
        w[10u + l] = wl[5];
        w[12u + l] = wl[6];
        w[14u + l] = wl[7];
    }
}

/* reverse_row for the two rows w_in[0..7] and w_in[8..15] (both with nonzero
 * r or v components): the same arithmetic in the same order per row, so the
 * same numbers to the bit. w_out (2 rows, may be w_in) and b_start, b_mid,
 * b_end (2 rows of 3 each) are written after every input is read. Component
 * i of row l is held at [i * 2 + l]; each loop runs over the two lanes. */
static void reverse_rows2(const ogk_i_mpsp_stage_t *sd, ogk_real_t dt, bool thrust, const ogk_real_t *w_in, /* NOLINT(bugprone-easily-swappable-parameters): order of eqs. (16)/(25); FD-checked by the unit tests */
                          ogk_real_t *w_out, ogk_real_t *b_start, ogk_real_t *b_mid, ogk_real_t *b_end) /* NOLINT(bugprone-easily-swappable-parameters): order of eqs. (16)/(25); FD-checked by the unit tests */
{
    const ogk_real_t half = OGK_R(0.5) * dt;
    const ogk_real_t c6 = dt / OGK_R(6.0);
    const ogk_real_t c3 = dt / OGK_R(3.0);
    ogk_real_t w[NX * 2u];
    ogk_real_t zv[6];
    ogk_real_t zl[2];
    ogk_real_t bx4[6];
    ogk_real_t bx3[6];
    ogk_real_t bx[6];
    ogk_real_t b[6];
    ogk_real_t bm[6];
    ogk_real_t bs[6];
    ogk_real_t be[6];
    ogk_real_t ar[6];
    ogk_real_t av[6];
    ogk_real_t zr2[6];
    ogk_real_t am[2];
    ogk_real_t ret[2];
    size_t l;

    rows2_to_lanes(w_in, w);
    /* stage 4: (bK4)_v = dt/6 w_v */
    for (l = 0u; l < 2u; ++l) {
        zv[l] = c6 * w[6u + l];
        zv[2u + l] = c6 * w[8u + l];
        zv[4u + l] = c6 * w[10u + l];
        zl[l] = c6 * w[14u + l];
    }
    stage_back2(&sd[3], zv, zl, thrust, bx4, be, ret);
    for (l = 0u; l < 2u; ++l) {
        am[l] = w[12u + l] + ret[l];
    }
    /* stage 3: (bK3)_v = dt/3 w_v + dt (bK4)_r, (bK4)_r = dt/6 w_r */
    for (l = 0u; l < 2u; ++l) {
        zv[l] = (c3 * w[6u + l]) + (dt * (c6 * w[l]));
        zv[2u + l] = (c3 * w[8u + l]) + (dt * (c6 * w[2u + l]));
        zv[4u + l] = (c3 * w[10u + l]) + (dt * (c6 * w[4u + l]));
        zl[l] = c3 * w[14u + l];
    }
    stage_back2(&sd[2], zv, zl, thrust, bx3, bm, ret);
    /* stage 2: (bK3)_r = dt/3 w_r + dt (bX4)_r, (bK2)_v = dt/3 w_v + dt/2 (bK3)_r */
    for (l = 0u; l < 2u; ++l) {
        am[l] += ret[l];
        zv[l] = (c3 * w[l]) + (dt * bx4[l]);
        zv[2u + l] = (c3 * w[2u + l]) + (dt * bx4[2u + l]);
        zv[4u + l] = (c3 * w[4u + l]) + (dt * bx4[4u + l]);
        av[l] = (w[6u + l] + (c6 * w[l])) + zv[l];
        av[2u + l] = (w[8u + l] + (c6 * w[2u + l])) + zv[2u + l];
        av[4u + l] = (w[10u + l] + (c6 * w[4u + l])) + zv[4u + l];
        zv[l] = (c3 * w[6u + l]) + (half * zv[l]);
        zv[2u + l] = (c3 * w[8u + l]) + (half * zv[2u + l]);
        zv[4u + l] = (c3 * w[10u + l]) + (half * zv[4u + l]);
        ar[l] = (w[l] + bx4[l]) + bx3[l];
        ar[2u + l] = (w[2u + l] + bx4[2u + l]) + bx3[2u + l];
        ar[4u + l] = (w[4u + l] + bx4[4u + l]) + bx3[4u + l];
    }
    stage_back2(&sd[1], zv, zl, thrust, bx, b, ret);
    /* stage 1: (bK2)_r = dt/3 w_r + dt/2 (bX3)_r, (bK1)_v = dt/6 w_v + dt/2 (bK2)_r,
     * (bK1)_r = dt/6 w_r + dt/2 (bX2)_r */
    if (thrust) { /* b, bm only set in thrust */
        for (l = 0u; l < 2u; ++l) {
            bm[l] += b[l];
            bm[2u + l] += b[2u + l];
            bm[4u + l] += b[4u + l];
        }
    }
    for (l = 0u; l < 2u; ++l) {
        am[l] += ret[l];
        zr2[l] = (c3 * w[l]) + (half * bx3[l]);
        zr2[2u + l] = (c3 * w[2u + l]) + (half * bx3[2u + l]);
        zr2[4u + l] = (c3 * w[4u + l]) + (half * bx3[4u + l]);
        av[l] = (av[l] + zr2[l]) + ((c6 * w[l]) + (half * bx[l]));
        av[2u + l] = (av[2u + l] + zr2[2u + l]) + ((c6 * w[2u + l]) + (half * bx[2u + l]));
        av[4u + l] = (av[4u + l] + zr2[4u + l]) + ((c6 * w[4u + l]) + (half * bx[4u + l]));
        ar[l] += bx[l];
        ar[2u + l] += bx[2u + l];
        ar[4u + l] += bx[4u + l];
        zv[l] = (c6 * w[6u + l]) + (half * zr2[l]);
        zv[2u + l] = (c6 * w[8u + l]) + (half * zr2[2u + l]);
        zv[4u + l] = (c6 * w[10u + l]) + (half * zr2[4u + l]);
        zl[l] = c6 * w[14u + l];
    }
    stage_back2(&sd[0], zv, zl, thrust, bx, bs, ret);
    /* w dX_next/dX = w + bX1 + bX2 + bX3 + bX4, (bX)_v = (bK)_r; lambda_m passes */
    for (l = 0u; l < 2u; ++l) {
        ogk_real_t *wo = &w_out[l * NX];
        wo[0] = ar[l] + bx[l];
        wo[1] = ar[2u + l] + bx[2u + l];
        wo[2] = ar[4u + l] + bx[4u + l];
        wo[3] = av[l];
        wo[4] = av[2u + l];
        wo[5] = av[4u + l];
        wo[6] = am[l] + ret[l];
        wo[7] = w[14u + l];
    }
    if (thrust) { /* bm, bs, be are only set in thrust */
        for (l = 0u; l < 2u; ++l) {
            b_start[(l * 3u)] = bs[l];
            b_start[(l * 3u) + 1u] = bs[2u + l];
            b_start[(l * 3u) + 2u] = bs[4u + l];
            b_mid[(l * 3u)] = bm[l];
            b_mid[(l * 3u) + 1u] = bm[2u + l];
            b_mid[(l * 3u) + 2u] = bm[4u + l];
            b_end[(l * 3u)] = be[l];
            b_end[(l * 3u) + 1u] = be[2u + l];
            b_end[(l * 3u) + 2u] = be[4u + l];
        }
    }
}

#endif /* __SSE2__ */

/* A row of m and lambda_m only (that of lambda_m(tf)): it stays so. */
static bool mass_only_row(const ogk_real_t *w)
{
    return (w[0] == OGK_R(0.0)) && (w[1] == OGK_R(0.0)) && (w[2] == OGK_R(0.0)) && (w[3] == OGK_R(0.0)) && (w[4] == OGK_R(0.0)) &&
           (w[5] == OGK_R(0.0));
}

ogk_status ogk_i_mpsp_step_adjoint(const ogk_i_mpsp_dyn_t *dyn, const ogk_real_t *x, ogk_real_t dt, int mode, /* NOLINT(bugprone-easily-swappable-parameters): order of eqs. (16)/(25); FD-checked by the unit tests */
                             const ogk_i_mpsp_uval_t *uv, bool pair_rows, size_t n_rows,
                             const ogk_real_t *adj_in, ogk_real_t *adj_out, ogk_real_t *bu_start, /* NOLINT(bugprone-easily-swappable-parameters): order of eqs. (16)/(25); FD-checked by the unit tests */
                             ogk_real_t *bu_mid, ogk_real_t *bu_end)
{
    ogk_i_mpsp_stage_t sd[4];
    const ogk_status st = stage_partials(dyn, x, dt, mode, uv, sd);

    if (st == OGK_OK) {
        const bool thrust = (mode == 1);
        size_t r = 0u;
        while (r < n_rows) {
            const ogk_real_t *w = &adj_in[r * NX];
            size_t n_done = 1u;
            if (mass_only_row(w)) {
                reverse_row_mass(sd, dt, thrust, w, &adj_out[r * NX], &bu_start[r * 3u],
                                 &bu_mid[r * 3u], &bu_end[r * 3u]);
#if defined(__SSE2__)
            } else if (pair_rows && ((r + 1u) < n_rows) && !mass_only_row(&w[NX])) {
                reverse_rows2(sd, dt, thrust, w, &adj_out[r * NX], &bu_start[r * 3u],
                              &bu_mid[r * 3u], &bu_end[r * 3u]);
                n_done = 2u;
#endif
            } else {
                reverse_row(sd, dt, thrust, w, &adj_out[r * NX], &bu_start[r * 3u],
                            &bu_mid[r * 3u], &bu_end[r * 3u]);
            }
            r += n_done;
        }
#if !defined(__SSE2__)
        (void)pair_rows; /* one row at a time: no 2-lane double SIMD */
#endif
    }
    return st;
}

/* One row of the second-order sweep (OGK_MPSP_SWEEP_MID2) with the partials p
 * at the step midpoint: w Phi with Phi = I + dt J + dt^2/2 J^2, J = d f/d X
 * there, applied as two row-times-J products without forming Phi:
 *   p1 = w J:  (p1)_r = G w_v,  (p1)_v = w_r,  (p1)_m = a_vm w_v.e + a_lm w_lm,  (p1)_lm = 0
 *   p2 = p1 J: (p2)_r = G w_r,  (p2)_v = G w_v, (p2)_m = a_vm w_r.e,             (p2)_lm = 0
 * and the control sensitivity of the step by the midpoint rule,
 *   b = dt (w + dt/2 p1) D = z D,  z_v = dt (w_v + dt/2 w_r),  z_lm = dt w_lm,
 *   z D = d_v z_v + (d_l z_lm - d_v z_v.e) e            (thrust only).
 * Phi agrees with the step's transition to O(dt^3) (Magnus at the midpoint)
 * and b with the step's integral of w Phi(t_next, s) D(s) dU(s) to O(dt^3):
 * O(dt^2) over the arc. w_out may be w. */
static void mid2_row(const ogk_i_mpsp_stage_t *p, ogk_real_t dt, bool thrust, const ogk_real_t *w, /* NOLINT(bugprone-easily-swappable-parameters): order of eqs. (16)/(25) */
                     ogk_real_t *w_out, ogk_real_t *b) /* NOLINT(bugprone-easily-swappable-parameters): row out, its control sensitivity; unit-tested against the exact sweep */
{
    const ogk_real_t *g = p->g;
    const ogk_real_t hh = OGK_R(0.5) * dt * dt;
    ogk_real_t gv[3];
    ogk_real_t gr[3];
    ogk_real_t wm = w[6];
    const ogk_real_t wlm = w[7];

    gv[0] = (w[3] * g[0]) + (w[4] * g[MPSP_SL]) + (w[5] * g[2u * MPSP_SL]);
    gv[1] = (w[3] * g[MPSP_SL]) + (w[4] * g[3u * MPSP_SL]) + (w[5] * g[4u * MPSP_SL]);
    gv[2] = (w[3] * g[2u * MPSP_SL]) + (w[4] * g[4u * MPSP_SL]) + (w[5] * g[5u * MPSP_SL]);
    gr[0] = (w[0] * g[0]) + (w[1] * g[MPSP_SL]) + (w[2] * g[2u * MPSP_SL]);
    gr[1] = (w[0] * g[MPSP_SL]) + (w[1] * g[3u * MPSP_SL]) + (w[2] * g[4u * MPSP_SL]);
    gr[2] = (w[0] * g[2u * MPSP_SL]) + (w[1] * g[4u * MPSP_SL]) + (w[2] * g[5u * MPSP_SL]);
    if (thrust) {
        const ogk_real_t *e = p->e;
        const ogk_real_t half = OGK_R(0.5) * dt;
        const ogk_real_t ve = (w[3] * e[0]) + (w[4] * e[MPSP_SL]) + (w[5] * e[2u * MPSP_SL]);
        const ogk_real_t re = (w[0] * e[0]) + (w[1] * e[MPSP_SL]) + (w[2] * e[2u * MPSP_SL]);
        const ogk_real_t zl = dt * wlm;
        const ogk_real_t ze = dt * (ve + (half * re));
        const ogk_real_t alpha = (p->d_l[0] * zl) - (p->d_v[0] * ze);
        const ogk_real_t dvd = p->d_v[0] * dt;
        wm += (dt * ((p->a_vm[0] * ve) + (p->a_lm[0] * wlm))) + (hh * (p->a_vm[0] * re));
        b[0] = (dvd * (w[3] + (half * w[0]))) + (alpha * e[0]);
        b[1] = (dvd * (w[4] + (half * w[1]))) + (alpha * e[MPSP_SL]);
        b[2] = (dvd * (w[5] + (half * w[2]))) + (alpha * e[2u * MPSP_SL]);
    }
    {
        const ogk_real_t v0 = w[3] + (dt * w[0]) + (hh * gv[0]);
        const ogk_real_t v1 = w[4] + (dt * w[1]) + (hh * gv[1]);
        const ogk_real_t v2 = w[5] + (dt * w[2]) + (hh * gv[2]);
        w_out[0] = w[0] + (dt * gv[0]) + (hh * gr[0]);
        w_out[1] = w[1] + (dt * gv[1]) + (hh * gr[1]);
        w_out[2] = w[2] + (dt * gv[2]) + (hh * gr[2]);
        w_out[3] = v0;
        w_out[4] = v1;
        w_out[5] = v2;
        w_out[6] = wm;
        w_out[7] = wlm;
    }
}

#if defined(__SSE2__)
/* mid2_row for the two rows w_in[0..7] and w_in[8..15] (lanes l = 0, 1;
 * component i of lane l at [i * 2 + l]): the same arithmetic in the same
 * order per row, each statement a loop over the lanes (gcc -O2 carries a pair
 * in one SSE2 register), the partials read as pairs (MPSP_SL = 2); w_out (may
 * be w_in) and b (2 rows of 3) written after every input is read. */
static void mid2_rows2(const ogk_i_mpsp_stage_t *p, ogk_real_t dt, bool thrust, const ogk_real_t *w_in, /* NOLINT(bugprone-easily-swappable-parameters): order of eqs. (16)/(25) */
                       ogk_real_t *w_out, ogk_real_t *b_out) /* NOLINT(bugprone-easily-swappable-parameters): rows out, their control sensitivities; unit-tested against the exact sweep */
{
    const ogk_real_t *g = p->g;
    const ogk_real_t hh = OGK_R(0.5) * dt * dt;
    ogk_real_t w[NX * 2u];
    ogk_real_t gv[6];
    ogk_real_t gr[6];
    ogk_real_t wo[NX * 2u];
    ogk_real_t b[6];
    size_t l;

    rows2_to_lanes(w_in, w);
    for (l = 0u; l < 2u; ++l) {
        gv[l] = (w[6u + l] * g[l]) + (w[8u + l] * g[2u + l]) + (w[10u + l] * g[4u + l]);
        gv[2u + l] = (w[6u + l] * g[2u + l]) + (w[8u + l] * g[6u + l]) + (w[10u + l] * g[8u + l]);
        gv[4u + l] = (w[6u + l] * g[4u + l]) + (w[8u + l] * g[8u + l]) + (w[10u + l] * g[10u + l]);
        gr[l] = (w[l] * g[l]) + (w[2u + l] * g[2u + l]) + (w[4u + l] * g[4u + l]);
        gr[2u + l] = (w[l] * g[2u + l]) + (w[2u + l] * g[6u + l]) + (w[4u + l] * g[8u + l]);
        gr[4u + l] = (w[l] * g[4u + l]) + (w[2u + l] * g[8u + l]) + (w[4u + l] * g[10u + l]);
        wo[12u + l] = w[12u + l];
    }
    if (thrust) {
        const ogk_real_t *e = p->e;
        const ogk_real_t half = OGK_R(0.5) * dt;
        for (l = 0u; l < 2u; ++l) {
            const ogk_real_t ve = (w[6u + l] * e[l]) + (w[8u + l] * e[2u + l]) + (w[10u + l] * e[4u + l]);
            const ogk_real_t re = (w[l] * e[l]) + (w[2u + l] * e[2u + l]) + (w[4u + l] * e[4u + l]);
            const ogk_real_t zl = dt * w[14u + l];
            const ogk_real_t ze = dt * (ve + (half * re));
            const ogk_real_t alpha = (p->d_l[l] * zl) - (p->d_v[l] * ze);
            const ogk_real_t dvd = p->d_v[l] * dt;
            wo[12u + l] += (dt * ((p->a_vm[l] * ve) + (p->a_lm[l] * w[14u + l]))) +
                           (hh * (p->a_vm[l] * re));
            b[l] = (dvd * (w[6u + l] + (half * w[l]))) + (alpha * e[l]);
            b[2u + l] = (dvd * (w[8u + l] + (half * w[2u + l]))) + (alpha * e[2u + l]);
            b[4u + l] = (dvd * (w[10u + l] + (half * w[4u + l]))) + (alpha * e[4u + l]);
        }
        for (l = 0u; l < 2u; ++l) {
            b_out[l * 3u] = b[l];
            b_out[(l * 3u) + 1u] = b[2u + l];
            b_out[(l * 3u) + 2u] = b[4u + l];
        }
    }
    for (l = 0u; l < 2u; ++l) {
        wo[l] = w[l] + (dt * gv[l]) + (hh * gr[l]);
        wo[2u + l] = w[2u + l] + (dt * gv[2u + l]) + (hh * gr[2u + l]);
        wo[4u + l] = w[4u + l] + (dt * gv[4u + l]) + (hh * gr[4u + l]);
        wo[6u + l] = w[6u + l] + (dt * w[l]) + (hh * gv[l]);
        wo[8u + l] = w[8u + l] + (dt * w[2u + l]) + (hh * gv[2u + l]);
        wo[10u + l] = w[10u + l] + (dt * w[4u + l]) + (hh * gv[4u + l]);
    }
    for (l = 0u; l < 2u; ++l) {
        ogk_real_t *o = &w_out[l * NX];
        o[0] = wo[l];
        o[1] = wo[2u + l];
        o[2] = wo[4u + l];
        o[3] = wo[6u + l];
        o[4] = wo[8u + l];
        o[5] = wo[10u + l];
        o[6] = wo[12u + l];
        o[7] = w[14u + l];
    }
}
#endif /* __SSE2__ */

ogk_status ogk_i_mpsp_step_adjoint_mid2(const ogk_i_mpsp_dyn_t *dyn, const ogk_real_t *x_lo, const ogk_real_t *x_hi, /* NOLINT(bugprone-easily-swappable-parameters): the step's two nodes; unit-tested against the exact sweep */
                                  ogk_real_t dt, int mode, const ogk_i_mpsp_uval_t *uv_mid, size_t n_rows, /* NOLINT(bugprone-easily-swappable-parameters): order of eqs. (16)/(25); unit-tested against the exact sweep */
                                  ogk_real_t *adj, ogk_real_t *bu_mid)
{
    ogk_i_mpsp_stage_t sd;
    ogk_real_t xm[NX];
    size_t i;
    ogk_status st;

    /* the midpoint state as the mean of the nodes: O(dt^2) from the
     * trajectory's, which moves Phi and b by O(dt^3) per step */
    for (i = 0u; i < NX; ++i) {
        xm[i] = OGK_R(0.5) * (x_lo[i] + x_hi[i]);
    }
    st = ogk_i_mpsp_stage_eval(dyn, xm, uv_mid, mode, NULL, &sd);
    if (st == OGK_OK) {
        const bool thrust = (mode == 1);
        size_t r = 0u;
#if defined(__SSE2__)
        for (; (r + 1u) < n_rows; r += 2u) { /* two rows per pass */
            mid2_rows2(&sd, dt, thrust, &adj[r * NX], &adj[r * NX], &bu_mid[r * 3u]);
        }
#endif
        for (; r < n_rows; ++r) {
            mid2_row(&sd, dt, thrust, &adj[r * NX], &adj[r * NX], &bu_mid[r * 3u]);
        }
    }
    return st;
}
