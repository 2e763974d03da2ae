/* mpsp_internal.h -- shared internals of the MPSP module (mpsp*.c only). */
#ifndef OGK_MPSP_INTERNAL_H
#define OGK_MPSP_INTERNAL_H

#include <stdbool.h>
#include <stddef.h>
#include "ogk/mpsp.h"
#include "ogk/rk4.h"
#include "../ogk_checks.h"

/* Compile-time checks of the limits against the solvers used (all plain
 * integer constants, so the preprocessor evaluates them). */
#if OGK_MPSP_MAX_UNKNOWNS > OGK_LA_MAX_LONG
#error "OGK_MPSP_MAX_UNKNOWNS exceeds OGK_LA_MAX_LONG (ogk_minnorm)"
#endif
#if OGK_MPSP_NY > OGK_LA_MAX_N
#error "OGK_MPSP_NY exceeds OGK_LA_MAX_N (ogk_minnorm)"
#endif
#if OGK_MPSP_SENS_BLOCK < 3
#error "OGK_MPSP_SENS_BLOCK must hold the 3 samples of one RK4 step"
#endif
#if OGK_MPSP_NX > OGK_RK4_MAX_STATE
#error "OGK_MPSP_NX exceeds OGK_RK4_MAX_STATE"
#endif
#if OGK_MPSP_MAX_STEPS > OGK_RK4_MAX_STEPS
#error "OGK_MPSP_MAX_STEPS exceeds OGK_RK4_MAX_STEPS"
#endif
#if OGK_MPSP_MAX_SWITCHES > OGK_RK4_MAX_SWITCHES
#error "OGK_MPSP_MAX_SWITCHES exceeds OGK_RK4_MAX_SWITCHES"
#endif

/* Everything the right-hand side of eq. (16) needs; passed to the RK4
 * callbacks as `user`. The control cache holds U at the last time asked
 * (RK4 stages 2-3 and the end of one step / start of the next share times). */
typedef struct {
    ogk_real_t mu;          /* [LU^3/TU^2] */
    ogk_real_t thrust;      /* [MU LU/TU^2] T of this propagation */
    ogk_real_t c_exhaust;   /* [LU/TU] */
    ogk_real_t mdot_thrust; /* [MU/TU] -T/c, m' in thrust (eq. 16) */
    const ogk_real_t *w;    /* [-] weights, 3 blocks of n_basis */
    size_t n_basis;     /* [-] 2 n + 1 */
    uint32_t kind;      /* [-] OGK_MPSP_BASIS_* */
    ogk_real_t omega;       /* [rad/TU] */
    ogk_real_t t_ref;       /* [TU] */
    ogk_real_t cache_t;     /* [TU] time of cache_u */
    ogk_real_t cache_u[3];  /* [-] U(cache_t) */
    bool cache_ok;
    ogk_real_t anchor_t;    /* [TU] last time whose phase was taken from cos() and sin() */
    ogk_real_t anchor_c;    /* [-] cos(omega (anchor_t - t_ref)) */
    ogk_real_t anchor_s;    /* [-] sin(omega (anchor_t - t_ref)) */
    bool anchor_ok;
#if defined(__SSE2__)
    /* U at two times per pass (mpsp_control.c): the weights with each entry
     * twice, w2[2 i + l] = w[i], so that lane l of a 2-lane product reads its
     * own copy (gcc -O2 then multiplies both lanes in one SSE2 instruction). */
    ogk_real_t w2[2u * OGK_MPSP_MAX_WEIGHTS];
    /* The propagation's grid (ogk_rk4_propagate's t0 + k h, last node tf), to
     * tell the end of an RK4 step from its midpoint, and U there, computed
     * with the midpoint's (ogk_i_mpsp_control_at). */
    ogk_real_t grid_t0;     /* [TU] */
    ogk_real_t grid_h;      /* [TU] */
    ogk_real_t grid_tf;     /* [TU] */
    ogk_real_t next_t;      /* [TU] time of next_u */
    ogk_real_t next_u[3];   /* [-] U(next_t) */
    bool next_ok;
    /* The anchor before next_u's phase was taken: restored when next_u is
     * not asked for, so the phases are those of the one-time path. */
    ogk_real_t undo_t;      /* [TU] */
    ogk_real_t undo_c;      /* [-] */
    ogk_real_t undo_s;      /* [-] */
    bool undo_ok;
    /* The propagation's own: U at a midpoint and the step's end made in one
     * pass, and kept in keep_t / keep_u (ogk_mpsp_t's) for the sweep. Set by
     * ogk_i_mpsp_propagate_ctx only (other callers of ogk_i_mpsp_control_at, such as the
     * test entry points' ogk_rk4_step, take U one time at a time). */
    bool pairing;
    ogk_real_t keep_scale;  /* [1/TU] 2 / h: half grid steps per TU */
    ogk_real_t *keep_t;     /* [TU] */
    ogk_real_t *keep_u;     /* [-] */
#endif
} ogk_i_mpsp_dyn_t;

/* Partial derivatives of eq. (16) at one RK4 stage state (derived in
 * docs/design/mpsp.md; Appendix A's dF/dU block is garbled in the paper):
 *   d f_v/d r = G(r),  d f_v/d m = a_vm e,  d f_lm/d m = a_lm,
 *   d f_v/d U = d_v (I - e e^T),  d f_lm/d U = d_l e^T,
 * with e = U/|U|, a_vm = u T/m^2, a_lm = 2 u T |U|/m^3, d_v = -u T/(m |U|),
 * d_l = -u T/m^2. All thrust terms are 0 in coast. G is symmetric: only its
 * upper triangle is kept. */
/* Each value is held MPSP_SL times in a row (entry i of g at g[i * MPSP_SL
 * + l], l < MPSP_SL): 2 where the adjoint rows go two per pass (SSE2), so
 * that a pair reads its partial with one load instead of a load and a
 * broadcast per pass (made once here, read three times per stage by the six
 * rows); 1 elsewhere. */
#if defined(__SSE2__)
#define MPSP_SL ((size_t)2u)
#else
#define MPSP_SL ((size_t)1u)
#endif
typedef struct {
    ogk_real_t g[6u * MPSP_SL]; /* [1/TU^2] G(r): g_xx, g_xy, g_xz, g_yy, g_yz, g_zz */
    ogk_real_t e[3u * MPSP_SL]; /* [-] U/|U| (0 in coast) */
    ogk_real_t a_vm[MPSP_SL];
    ogk_real_t a_lm[MPSP_SL];
    ogk_real_t d_v[MPSP_SL];
    ogk_real_t d_l[MPSP_SL];
} ogk_i_mpsp_stage_t;

/* U = lambda_v at one time and its norm |U| (eq. 16 needs both). */
typedef struct {
    ogk_real_t u[3];        /* [-] U(t) */
    ogk_real_t lam;         /* [-] |U(t)| */
} ogk_i_mpsp_uval_t;

/* ---- mpsp_dynamics.c */
void ogk_i_mpsp_dyn_setup(ogk_i_mpsp_dyn_t *dyn, const ogk_mpsp_t *ctx, const ogk_real_t *weights,
                    ogk_real_t thrust);
/* h(t) (n_basis) and optionally dh/dt. */
void ogk_i_mpsp_basis(const ogk_i_mpsp_dyn_t *dyn, ogk_real_t t, ogk_real_t *h, ogk_real_t *hdot);
/* U = P(t) W from a basis vector, h_q at h[q * stride]. */
void ogk_i_mpsp_control_from_basis(const ogk_i_mpsp_dyn_t *dyn, const ogk_real_t *h, size_t stride, ogk_real_t *u);
/* cos and sin of the basis phase theta = omega (t - t_ref): rotated from the
 * last phase taken from cos() and sin() (the anchor, kept in dyn) when theta
 * is within MPSP_PHASE_REACH of it, else from cos() and sin() (new anchor). */
void ogk_i_mpsp_phase(ogk_i_mpsp_dyn_t *dyn, ogk_real_t t, ogk_real_t *c1, ogk_real_t *s1);
/* h(t) and U(t) = P(t) W, |U|, in one pass (phase from ogk_i_mpsp_phase). */
void ogk_i_mpsp_basis_control(ogk_i_mpsp_dyn_t *dyn, ogk_real_t t, ogk_real_t *h, ogk_i_mpsp_uval_t *uv);
/* U(t) through the cache. */
void ogk_i_mpsp_control_at(ogk_i_mpsp_dyn_t *dyn, ogk_real_t t, ogk_real_t *u);
#if defined(__SSE2__)
/* The basis rows h(t[0]) into h_a and h(t[1]) into h_b, each entry twice
 * (OGK_MPSP_H_LANES), in one pass: the harmonics of ogk_i_mpsp_basis_control,
 * phases taken in the order t[0], t[1]. */
void ogk_i_mpsp_basis2(ogk_i_mpsp_dyn_t *dyn, const ogk_real_t *t, ogk_real_t *h_a, ogk_real_t *h_b);
/* U and |U| at t (t0 <= t <= tf) from ctx->keep_u: false if they were not
 * kept for t. */
bool ogk_i_mpsp_keep_find(const ogk_mpsp_t *ctx, const ogk_i_mpsp_dyn_t *dyn, ogk_real_t t, ogk_i_mpsp_uval_t *uv);
#endif
/* Eq. (16) with U given; OGK_E_CALLBACK on m <= 0 or |U| = 0 while thrusting. */
ogk_status ogk_i_mpsp_rhs(const ogk_i_mpsp_dyn_t *dyn, const ogk_real_t *x, const ogk_real_t *u, int mode,
                    ogk_real_t *xdot);
/* Eq. (10). */
ogk_real_t ogk_i_mpsp_switch_value(const ogk_i_mpsp_dyn_t *dyn, const ogk_real_t *x, const ogk_real_t *u);
/* One RK4 stage of the sensitivity sweep at state x with control uv: the
 * partials of eq. (16) into sd and, when xdot is not NULL, eq. (16) itself
 * with the arithmetic of ogk_i_mpsp_rhs (so the stage states are those of
 * ogk_rk4_step). Errors as ogk_i_mpsp_rhs. */
ogk_status ogk_i_mpsp_stage_eval(const ogk_i_mpsp_dyn_t *dyn, const ogk_real_t *x, const ogk_i_mpsp_uval_t *uv,
                           int mode, ogk_real_t *xdot, ogk_i_mpsp_stage_t *sd);
/* The RK4 problem of eq. (16) on dyn (its callbacks take user = dyn). */
void ogk_i_mpsp_rk4_problem(ogk_rk4_problem_t *p, const ogk_mpsp_t *ctx, ogk_i_mpsp_dyn_t *dyn);

/* ---- mpsp_adjoint.c */
/* Adjoint rows: row vectors w_r (rows of d(.)/dX), row-major,
 * w[r * OGK_MPSP_NX + i]. Control sensitivities of row r at one time:
 * bu[r * 3 + c]. */

/* Two adjoint rows per pass where the target has 2-lane double SIMD that gcc
 * -O2 uses without options (SSE2: every x86-64); one row at a time elsewhere
 * (the Cortex-M7's FPU is scalar: lane arrays would only cost it loads and
 * stores). Both give the same numbers to the bit (docs/design/mpsp.md, section 8). */
#if defined(__SSE2__)
#define MPSP_PAIR_ROWS true
#else
#define MPSP_PAIR_ROWS false
#endif

/* Adjoint of one RK4 step (Appendix A, transposed): for the n_rows rows
 * adj_in of d(.)/dX_next, writes w dX_next/dX to adj_out (may be adj_in) and,
 * in thrust, w dX_next/dU at the stage times into bu_start (U at t), bu_mid
 * (t + dt/2, stages 2 and 3) and bu_end (t + dt), each n_rows x 3
 * (overwritten; left untouched in coast, where U does not enter eq. 16).
 * uv[0..2] is U at t, t + dt/2, t + dt (not read in coast). pair_rows: two
 * adjacent rows with r or v components per pass (MPSP_PAIR_ROWS), else one. */
ogk_status ogk_i_mpsp_step_adjoint(const ogk_i_mpsp_dyn_t *dyn, const ogk_real_t *x, ogk_real_t dt, int mode,
                             const ogk_i_mpsp_uval_t *uv, bool pair_rows, size_t n_rows,
                             const ogk_real_t *adj_in, ogk_real_t *adj_out, ogk_real_t *bu_start,
                             ogk_real_t *bu_mid, ogk_real_t *bu_end);

/* The step's adjoint of the second-order sweep (OGK_MPSP_SWEEP_MID2): the
 * n_rows rows of adj (in place) times I + dt J + dt^2/2 J^2 with J = d f/d X
 * at the mean of the nodes x_lo, x_hi and U = uv_mid (the midpoint's; not
 * read in coast); in thrust, bu_mid (n_rows x 3, overwritten) receives the
 * control sensitivity of the whole step at its midpoint (weight dt). */
ogk_status ogk_i_mpsp_step_adjoint_mid2(const ogk_i_mpsp_dyn_t *dyn, const ogk_real_t *x_lo, const ogk_real_t *x_hi,
                                  ogk_real_t dt, int mode, const ogk_i_mpsp_uval_t *uv_mid, size_t n_rows,
                                  ogk_real_t *adj, ogk_real_t *bu_mid);

/* ---- mpsp_sensitivity.c */
/* Terms of the switching compensation at (t_s, x_s) (eqs. 24-25, B.2):
 * dX+ = dX- + dxdot (s_x dX- + s_u dU) / s_dot; dt_s = -(s_x dX- + s_u dU) / s_dot. */
typedef struct {
    ogk_real_t dxdot[OGK_MPSP_NX]; /* Xdot+ - Xdot- */
    ogk_real_t s_x[OGK_MPSP_NX];   /* dS/dX */
    ogk_real_t s_u[3];             /* dS/dU */
    ogk_real_t s_dot;              /* dS/dt along the trajectory, eq. (15) */
} ogk_i_mpsp_jump_t;

ogk_status ogk_i_mpsp_jump_terms(ogk_i_mpsp_dyn_t *dyn, ogk_real_t t_s, const ogk_real_t *x_s,
                           int mode_before, ogk_i_mpsp_jump_t *jump);

/* ---- mpsp_bv.c */
/* acc[q][r * 3 + c] += sum_b hb[b][q] cb[b][r * 3 + c] over the n samples b
 * (hb rows OGK_MPSP_MAX_BASIS * OGK_MPSP_H_LANES apart, h_q at [q *
 * OGK_MPSP_H_LANES] and, with 2 lanes, again at the next entry; cb rows 21
 * apart): B_v += bU h^T. */
void ogk_i_mpsp_bv_block_product(ogk_real_t *acc, size_t n_basis, const ogk_real_t *hb, const ogk_real_t *cb,
                           size_t n);
/* B_v row-major (7 x 3 n_basis) from the basis-major accumulator. */
void ogk_i_mpsp_bv_unpack(const ogk_real_t *acc, size_t n_basis, ogk_real_t *out);

/* ---- mpsp_propagate.c */
/* Propagates into ctx; t_max_eff is T (already scaled). */
ogk_status ogk_i_mpsp_propagate_ctx(ogk_mpsp_t *ctx, const ogk_real_t *weights, ogk_real_t lambda_m0,
                              const ogk_real_t *x0, ogk_real_t thrust, ogk_mpsp_prop_t *out);

#endif /* OGK_MPSP_INTERNAL_H */
