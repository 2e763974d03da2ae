/* mpsp.c -- MPSP guidance loops: configuration, the Newton update
 * (eqs. 44-46), the inner loop with the thrust-sequence check (Algorithm 1)
 * and the continuation outer loop (Algorithm 2, with the missing `else`
 * restored). Design notes: docs/design/mpsp.md. */
#include "mpsp_internal.h"
#include "../newton_internal.h"

#include <math.h>
#include <stddef.h>
#include <string.h>

#define NX OGK_MPSP_NX
#define NY OGK_MPSP_NY
#define MPSP_TWO_PI OGK_R(6.283185307179586476925286766559)
/* Same rule as ogk_rk4_propagate: a step count within this slop of an integer is that integer. */
#define MPSP_STEP_SLOP OGK_R(1.0e-9)
/* N_seg,tol levels tried by Algorithm 2 at most (N_seg,nom <= switches + 1, step >= 1). */
#define MPSP_MAX_TOL_LEVELS (OGK_RK4_MAX_SWITCHES + 4u)

/* Boundary conditions and parameters C of eq. (51). */
typedef struct {
    ogk_real_t x0[OGK_MPSP_NX0];
    ogk_real_t r_f[3];
    ogk_real_t v_f[3];
    ogk_real_t thrust;
} mpsp_cond_t;

/* ------------------------------------------------------------------ configuration */

static bool cfg_scalars_finite(const ogk_mpsp_config_t *cfg)
{
    const ogk_real_t s[] = {cfg->mu, cfg->t_max, cfg->c_exhaust, cfg->t0, cfg->tf,
                        cfg->fourier_period, cfg->fourier_t_ref, cfg->h_max, cfg->delta_max,
                        cfg->delta_tau_0, cfg->delta_tau_min, cfg->r_lambda, cfg->tol_r,
                        cfg->tol_v, cfg->tol_lambda_m, cfg->s_tol, cfg->lambda_m0_nom};
    return ogk_i_all_finite(s, sizeof(s) / sizeof(s[0])) &&
           ogk_i_all_finite(cfg->x0_nom, OGK_MPSP_NX0) && ogk_i_all_finite(cfg->r_f, 3u) &&
           ogk_i_all_finite(cfg->v_f, 3u);
}

static size_t mpsp_grid_steps(ogk_real_t span, ogk_real_t h)
{
    const ogk_real_t ratio = span / h;
    size_t n;
    if (!(ratio <= (ogk_real_t)OGK_MPSP_MAX_STEPS + OGK_R(1.0))) {
        n = OGK_MPSP_MAX_STEPS + 1u;
    } else {
        n = (size_t)OGK_FLOOR(ratio);
        if (((ratio - (ogk_real_t)n) > (MPSP_STEP_SLOP * OGK_FMAX(OGK_R(1.0), ratio))) || (n == 0u)) {
            n += 1u;
        }
    }
    return n;
}

/* The weight checks of check_config (basis order already checked). */
static ogk_status check_config_weights(const ogk_mpsp_config_t *cfg)
{
    size_t n_weights;
    ogk_status st = OGK_OK;

    n_weights = OGK_MPSP_NU * (2u * (size_t)cfg->fourier_order + 1u);
    if (!ogk_i_all_finite(cfg->weights_nom, n_weights) || !ogk_i_all_finite(cfg->r_eps, n_weights)) {
        st = OGK_E_NONFINITE;
    } else {
        size_t i;
        for (i = 0u; (i < n_weights) && (st == OGK_OK); ++i) {
            if (!(cfg->r_eps[i] > OGK_R(0.0))) {
                st = OGK_E_CONFIG;
            }
        }
    }
    return st;
}

/* The range checks of check_config (every value already finite). */
static ogk_status check_config_ranges(const ogk_mpsp_config_t *cfg)
{
    ogk_real_t r2;
    ogk_status st = OGK_OK;

    r2 = (cfg->x0_nom[0] * cfg->x0_nom[0]) + (cfg->x0_nom[1] * cfg->x0_nom[1]) +
         (cfg->x0_nom[2] * cfg->x0_nom[2]);
    if ((cfg->mu < OGK_R(0.0)) || !(cfg->t_max > OGK_R(0.0)) || !(cfg->c_exhaust > OGK_R(0.0)) ||
        !(cfg->tf > cfg->t0) || !(cfg->fourier_period > OGK_R(0.0)) || !(cfg->h_max > OGK_R(0.0)) ||
        !(cfg->delta_max > OGK_R(0.0)) || !(cfg->delta_tau_0 > OGK_R(0.0)) || (cfg->delta_tau_0 > OGK_R(1.0)) ||
        (cfg->delta_tau_min < OGK_R(0.0)) || !(cfg->delta_tau_min < cfg->delta_tau_0) ||
        !(cfg->r_lambda > OGK_R(0.0)) || !(cfg->tol_r > OGK_R(0.0)) || !(cfg->tol_v > OGK_R(0.0)) ||
        !(cfg->tol_lambda_m > OGK_R(0.0)) || !(cfg->s_tol > OGK_R(0.0)) || (cfg->max_newton < 1u) ||
        (cfg->max_outer < 1u) || (cfg->n_seg_tol_step < 1u) || !(cfg->x0_nom[6] > OGK_R(0.0)) ||
        ((cfg->mu > OGK_R(0.0)) && (!(r2 > OGK_R(0.0)))) ||
        /* the dense trajectory would not fit */
        (mpsp_grid_steps(cfg->tf - cfg->t0, cfg->h_max) > OGK_MPSP_MAX_STEPS)) {
        st = OGK_E_CONFIG;
    } else {
        /* The basis phase omega (t - t_ref) must be finite over [t0, tf]: a period near the
         * smallest double or a far t_ref overflows it and the basis would be NaN (found by
         * tests/fuzz/fuzz_mpsp_init.c). */
        const ogk_real_t omega = MPSP_TWO_PI / cfg->fourier_period;
        if (!isfinite(omega) || !isfinite(omega * (cfg->t0 - cfg->fourier_t_ref)) ||
            !isfinite(omega * (cfg->tf - cfg->fourier_t_ref))) {
            st = OGK_E_CONFIG;
        }
    }
    return st;
}

static ogk_status check_config(const ogk_mpsp_config_t *cfg)
{
    ogk_status st;

    if (!cfg_scalars_finite(cfg)) {
        st = OGK_E_NONFINITE;
    } else if ((cfg->fourier_order < 1u) || (cfg->fourier_order > OGK_MPSP_MAX_ORDER) ||
               ((cfg->fourier_kind != OGK_MPSP_BASIS_FOURIER) &&
                (cfg->fourier_kind != OGK_MPSP_BASIS_COSINE)) ||
               ((cfg->sens_sweep != OGK_MPSP_SWEEP_RK4) && (cfg->sens_sweep != OGK_MPSP_SWEEP_MID2))) {
        st = OGK_E_CONFIG;
    } else {
        st = check_config_weights(cfg);
    }
    if (st == OGK_OK) {
        st = check_config_ranges(cfg);
    }
    return st;
}

/* The defaults of ogk_mpsp_config_default into a non-NULL cfg. */
static void config_defaults(ogk_mpsp_config_t *cfg)
{
    size_t i;

    /* Mission data (mu, thrust, exhaust velocity, times, states, target,
     * basis order and period, nominal weights, step, tolerances) is 0: it
     * must be set, and ogk_mpsp_init rejects it left at 0. */
    (void)memset(cfg, 0, sizeof *cfg);
    cfg->fourier_kind = OGK_MPSP_BASIS_FOURIER;
    cfg->fourier_t_ref = OGK_R(0.0);
    cfg->sens_sweep = OGK_MPSP_SWEEP_MID2; /* the second-order sweep: the same Newton iterations (+-1) on the 23 Apophis cases, 0.58x the instructions per iteration (docs/design/mpsp.md, section 8) */
    cfg->delta_max = OGK_R(1.0);       /* Delta_max of Alg. 1 */
    cfg->delta_tau_0 = OGK_R(0.5);     /* first continuation step of Alg. 2 */
    cfg->delta_tau_min = OGK_R(0.1);   /* the paper's 0.1 */
    for (i = 0u; i < (sizeof cfg->r_eps / sizeof cfg->r_eps[0]); ++i) {
        cfg->r_eps[i] = OGK_R(1.0);    /* R_eps = I (eq. 41) */
    }
    cfg->r_lambda = OGK_R(1.0);        /* R_lambda = 1 (eq. 41) */
    cfg->s_tol = OGK_R(1.0e-12);       /* the paper's switch tolerance */
    cfg->max_newton = 100u;
    cfg->max_outer = 50u;
    cfg->n_seg_tol = 0u;        /* the paper's initial N_seg,tol */
    cfg->n_seg_tol_step = 2u;   /* the paper's increase */
    cfg->n_seg_nom = 0u;        /* counted at init from the nominal */
}

ogk_status ogk_mpsp_config_default(ogk_mpsp_config_t *cfg)
{
    ogk_status st = OGK_OK;

    if (cfg == NULL) {
        st = OGK_E_NULL;
    } else {
        config_defaults(cfg);
    }
    return st;
}

/* Everything ogk_mpsp_init derives from ctx->cfg (already checked and
 * copied); also the whole of ogk_mpsp_reset. */
static ogk_status prepare(ogk_mpsp_t *ctx)
{
    const ogk_mpsp_config_t *cfg = &ctx->cfg;
    const size_t kept = offsetof(ogk_mpsp_t, n_basis); /* bytes of the configuration */
    size_t i;
    ogk_status st = OGK_OK;

    /* Everything after the configuration back to zero. */
    (void)memset(&((unsigned char *)ctx)[kept], 0, sizeof *ctx - kept);
    ctx->n_basis = 2u * (size_t)cfg->fourier_order + 1u;
    ctx->n_weights = OGK_MPSP_NU * ctx->n_basis;
    ctx->n_steps = mpsp_grid_steps(cfg->tf - cfg->t0, cfg->h_max);
    ctx->omega = MPSP_TWO_PI / cfg->fourier_period;
    for (i = 0u; i < ctx->n_weights; ++i) {
        ctx->inv_sqrt_r_eps[i] = OGK_R(1.0) / OGK_SQRT(cfg->r_eps[i]);
    }
    ctx->inv_sqrt_r_lambda = OGK_R(1.0) / OGK_SQRT(cfg->r_lambda);
    ctx->init_marker = OGK_MPSP_INIT_MARKER;
    if (cfg->n_seg_nom == 0u) {
        ogk_mpsp_prop_t prop;
        const ogk_status pst = ogk_i_mpsp_propagate_ctx(ctx, cfg->weights_nom, cfg->lambda_m0_nom, cfg->x0_nom,
                                cfg->t_max, &prop);
        if (pst != OGK_OK) {
            ctx->init_marker = 0u;
            st = OGK_E_CONFIG;
        } else {
            ctx->n_seg_nom = prop.n_segments;
        }
    } else {
        ctx->n_seg_nom = cfg->n_seg_nom;
    }
    return st;
}

ogk_status ogk_mpsp_init(ogk_mpsp_t *ctx, const ogk_mpsp_config_t *cfg)
{
    ogk_status st;

    if ((ctx == NULL) || (cfg == NULL)) {
        st = OGK_E_NULL;
    } else {
        ctx->init_marker = 0u;
        st = check_config(cfg);
        if (st == OGK_OK) {
            (void)memset(ctx, 0, sizeof *ctx);
            ctx->cfg = *cfg;
            st = prepare(ctx);
        }
    }
    return st;
}

ogk_status ogk_mpsp_reset(ogk_mpsp_t *ctx)
{
    ogk_status st;

    if (ctx == NULL) {
        st = OGK_E_NULL;
    } else if (ctx->init_marker != OGK_MPSP_INIT_MARKER) {
        st = OGK_E_NOT_INIT;
    } else {
        st = prepare(ctx);
    }
    return st;
}

/* ------------------------------------------------------------------ Newton update */

/* ogk_mpsp_newton_update on checked arguments. */
static ogk_status newton_step(ogk_mpsp_t *ctx, const ogk_real_t *dy, ogk_real_t *weights, /* NOLINT(bugprone-easily-swappable-parameters): internal helper, the argument order of ogk_mpsp_newton_update, its only caller */
                              ogk_real_t *lambda_m0)
{
    size_t nw;
    size_t nu;
    size_t r;
    size_t i;
    ogk_status st;

    nw = ctx->n_weights;
    nu = nw + 1u;
    /* With z = [R_eps^1/2 dW; R_lambda^1/2 dlambda_m0], eq. (41) is |z|^2 / 2 and
     * eq. (40) reads M z = dY, M = [B_v R_eps^-1/2, A_lambda R_lambda^-1/2]; the
     * minimum-norm z = M^T (M M^T)^-1 dY is eqs. (44)-(45), since
     * M M^T = A_lambda A_lambda^T / R_lambda + B_v R_eps^-1 B_v^T. */
    for (r = 0u; r < NY; ++r) {
        for (i = 0u; i < nw; ++i) {
            ctx->newton_m[(r * nu) + i] = ctx->dy_dw[(r * nw) + i] * ctx->inv_sqrt_r_eps[i];
        }
        ctx->newton_m[(r * nu) + nw] = ctx->dy_dlm0[r] * ctx->inv_sqrt_r_lambda;
    }
    /* ill-conditioned still gives the least-norm step: taken (newton.c) */
    st = ogk_i_newton_minnorm(&ctx->qr, ctx->newton_m, NY, nu, OGK_R(0.0), dy, NULL, ctx->newton_z, NULL);
    if (st == OGK_OK) {
        /* Eq. (46): epsilon_{j+1} = epsilon_j - d epsilon_j, same for lambda_m0. */
        for (i = 0u; i < nw; ++i) {
            weights[i] -= ctx->newton_z[i] * ctx->inv_sqrt_r_eps[i];
        }
        *lambda_m0 -= ctx->newton_z[nw] * ctx->inv_sqrt_r_lambda;
    }
    return st;
}

ogk_status ogk_mpsp_newton_update(ogk_mpsp_t *ctx, const ogk_real_t *dy, ogk_real_t *weights,
                                  ogk_real_t *lambda_m0)
{
    ogk_status st;

    if ((ctx == NULL) || (dy == NULL) || (weights == NULL) || (lambda_m0 == NULL)) {
        st = OGK_E_NULL;
    } else if ((ctx->init_marker != OGK_MPSP_INIT_MARKER) || (ctx->sens_valid == 0u)) {
        st = OGK_E_NOT_INIT;
    } else if (!ogk_i_all_finite(dy, NY) || !ogk_i_all_finite(weights, ctx->n_weights) ||
               !isfinite(*lambda_m0)) {
        st = OGK_E_NONFINITE;
    } else {
        st = newton_step(ctx, dy, weights, lambda_m0);
    }
    return st;
}

/* ------------------------------------------------------------------ loops */

static ogk_real_t norm_n(const ogk_real_t *v, size_t n)
{
    ogk_real_t s = OGK_R(0.0);
    size_t i;
    for (i = 0u; i < n; ++i) {
        s += v[i] * v[i];
    }
    return OGK_SQRT(s);
}

/* Delta Y = Y(tf) - Y_d, Y_d = [r_f, v_f, 0]. */
static void terminal_error(const mpsp_cond_t *cond, const ogk_real_t *x_f, ogk_real_t *dy)
{
    size_t i;
    for (i = 0u; i < 3u; ++i) {
        dy[i] = x_f[i] - cond->r_f[i];
        dy[3u + i] = x_f[3u + i] - cond->v_f[i];
    }
    dy[6] = x_f[7];
}

static bool terminal_ok(const ogk_mpsp_config_t *cfg, const ogk_real_t *dy)
{
    return (norm_n(dy, 3u) <= cfg->tol_r) && (norm_n(&dy[3], 3u) <= cfg->tol_v) &&
           (OGK_FABS(dy[6]) <= cfg->tol_lambda_m);
}

static uint32_t abs_diff_u32(uint32_t a, uint32_t b)
{
    uint32_t d;
    if (a > b) {
        d = a - b;
    } else {
        d = b - a;
    }
    return d;
}

/* Algorithm 1. weights / *lambda_m0 (in/out) end as the last accepted
 * iterate; returns true (Sign = 1) when the terminal tolerances are met with
 * them (the trajectory held in ctx is then theirs, summarised in *prop). */
/* Lines 6-14 of Algorithm 1 from the iterate weights / *lambda_m0 (in/out)
 * with terminal error dy of norm dy_norm: true when the updated iterate is
 * accepted (and taken), false when the inner loop gives up. */
static bool newton_iteration(ogk_mpsp_t *ctx, const mpsp_cond_t *cond, ogk_real_t *weights, /* NOLINT(bugprone-easily-swappable-parameters): internal helper, argument order of inner_loop, its only caller, which is unit-tested */
                             ogk_real_t *lambda_m0, const ogk_real_t *dy, ogk_real_t dy_norm, /* NOLINT(bugprone-easily-swappable-parameters): internal helper, argument order of inner_loop, its only caller, which is unit-tested */
                             uint32_t n_seg_tol, ogk_mpsp_prop_t *prop, ogk_mpsp_result_t *res)
{
    ogk_real_t lm_new = *lambda_m0;
    bool accepted = false;
    ogk_status st;

    if (res->n_log < OGK_MPSP_MAX_LOG) {
        res->dy_norm_log[res->n_log] = dy_norm;
        res->n_log += 1u;
    }
    /* line 8: A_lambda, B_v, p, the update (eqs. 33, 40, 44-46) */
    st = ogk_mpsp_sensitivity(ctx, NULL, NULL);
    if (st == OGK_OK) {
        (void)memcpy(ctx->w_trial, weights, ctx->n_weights * sizeof weights[0]);
        st = ogk_mpsp_newton_update(ctx, dy, ctx->w_trial, &lm_new);
    }
    if (st == OGK_OK) {
        res->newton_iterations += 1u;
        /* line 9: integrate with the update, count N_seg */
        st = ogk_i_mpsp_propagate_ctx(ctx, ctx->w_trial, lm_new, cond->x0, cond->thrust, prop);
    }
    /* lines 10-14: accept only a thrust sequence close to the nominal one */
    if ((st == OGK_OK) && (abs_diff_u32(prop->n_segments, ctx->n_seg_nom) <= n_seg_tol)) {
        (void)memcpy(weights, ctx->w_trial, ctx->n_weights * sizeof weights[0]);
        *lambda_m0 = lm_new;
        accepted = true;
    }
    return accepted;
}

static bool inner_loop(ogk_mpsp_t *ctx, const mpsp_cond_t *cond, ogk_real_t *weights,
                       ogk_real_t *lambda_m0, uint32_t n_seg_tol, ogk_mpsp_prop_t *prop,
                       ogk_mpsp_result_t *res)
{
    ogk_real_t dy[NY];
    uint32_t j;
    bool converged = false;
    bool stop;
    ogk_status st;

    res->inner_loops += 1u;
    st = ogk_i_mpsp_propagate_ctx(ctx, weights, *lambda_m0, cond->x0, cond->thrust, prop);
    stop = (st != OGK_OK);
    for (j = 0u; (!stop) && (j <= ctx->cfg.max_newton); ++j) {
        terminal_error(cond, prop->x_f, dy);
        if (terminal_ok(&ctx->cfg, dy)) {
            converged = true;
            stop = true;
        } else {
            const ogk_real_t dy_norm = norm_n(dy, NY);
            if ((j == ctx->cfg.max_newton) || (!(dy_norm <= ctx->cfg.delta_max))) {
                stop = true; /* line 5: too far for a Newton step */
            } else {
                stop = !newton_iteration(ctx, cond, weights, lambda_m0, dy, dy_norm, n_seg_tol,
                                         prop, res);
            }
        }
    }
    return converged;
}

/* C_tau = (1 - tau) C_nom + tau C_per (eq. 51). */
static void blend(const mpsp_cond_t *nom, const mpsp_cond_t *per, ogk_real_t tau, mpsp_cond_t *out)
{
    size_t i;
    const ogk_real_t a = OGK_R(1.0) - tau;
    for (i = 0u; i < OGK_MPSP_NX0; ++i) {
        out->x0[i] = (a * nom->x0[i]) + (tau * per->x0[i]);
    }
    for (i = 0u; i < 3u; ++i) {
        out->r_f[i] = (a * nom->r_f[i]) + (tau * per->r_f[i]);
        out->v_f[i] = (a * nom->v_f[i]) + (tau * per->v_f[i]);
    }
    out->thrust = (a * nom->thrust) + (tau * per->thrust);
}

static void fill_result(const ogk_mpsp_t *ctx, const mpsp_cond_t *cond,
                        const ogk_mpsp_prop_t *prop, bool prop_ok, ogk_mpsp_result_t *res)
{
    size_t i;
    if (prop_ok) {
        terminal_error(cond, prop->x_f, res->dy);
        res->err_r = norm_n(res->dy, 3u);
        res->err_v = norm_n(&res->dy[3], 3u);
        res->lambda_mf = prop->x_f[7];
        res->m_f = prop->x_f[6];
        res->n_segments = prop->n_segments;
        res->n_thrust_arcs = prop->n_thrust_arcs;
        res->n_switches = prop->n_switches;
        for (i = 0u; i < OGK_MPSP_MAX_SWITCHES; ++i) {
            res->t_switch[i] = prop->t_switch[i];
        }
    } else {
        for (i = 0u; i < NY; ++i) {
            res->dy[i] = OGK_REAL_HUGE_VAL;
        }
        res->err_r = OGK_REAL_HUGE_VAL;
        res->err_v = OGK_REAL_HUGE_VAL;
        res->lambda_mf = OGK_REAL_HUGE_VAL;
        res->m_f = OGK_R(0.0);
    }
    res->n_weights = ctx->n_weights;
}

/* ogk_mpsp_solve on checked arguments. */
static ogk_status solve_checked(ogk_mpsp_t *ctx, const ogk_real_t *x0, ogk_real_t thrust_scale,
                                const ogk_real_t *target_rv, ogk_mpsp_result_t *res)
{
    mpsp_cond_t per;
    mpsp_cond_t nom;
    mpsp_cond_t cur;
    ogk_mpsp_prop_t prop;
    ogk_real_t lm_iter;
    uint32_t n_seg_tol;
    uint32_t level;
    bool solved;
    size_t nw;
    size_t i;
    ogk_status st;

    (void)memset(res, 0, sizeof *res);
    nw = ctx->n_weights;
    (void)memcpy(per.x0, x0, sizeof per.x0);
    (void)memcpy(nom.x0, ctx->cfg.x0_nom, sizeof nom.x0);
    for (i = 0u; i < 3u; ++i) {
        nom.r_f[i] = ctx->cfg.r_f[i];
        nom.v_f[i] = ctx->cfg.v_f[i];
        per.r_f[i] = (target_rv != NULL) ? target_rv[i] : ctx->cfg.r_f[i];
        per.v_f[i] = (target_rv != NULL) ? target_rv[3u + i] : ctx->cfg.v_f[i];
    }
    nom.thrust = ctx->cfg.t_max;
    per.thrust = ctx->cfg.t_max * thrust_scale;

    /* Safe command until something better is solved: the nominal. */
    (void)memcpy(res->weights, ctx->cfg.weights_nom, nw * sizeof res->weights[0]);
    res->lambda_m0 = ctx->cfg.lambda_m0_nom;
    n_seg_tol = ctx->cfg.n_seg_tol;

    /* Algorithm 2, line 4: the inner loop straight at C_per. */
    (void)memcpy(ctx->w_iter, ctx->cfg.weights_nom, nw * sizeof ctx->w_iter[0]);
    lm_iter = ctx->cfg.lambda_m0_nom;
    solved = inner_loop(ctx, &per, ctx->w_iter, &lm_iter, n_seg_tol, &prop, res);
    if (solved) {
        (void)memcpy(res->weights, ctx->w_iter, nw * sizeof res->weights[0]);
        res->lambda_m0 = lm_iter;
        res->tau_reached = OGK_R(1.0);
    }

    /* Lines 6-27: continuation from C_nom, restarted from the nominal weights
     * with N_seg,tol widened by n_seg_tol_step after each failed continuation
     * (the `else` the printed pseudo-code lacks). Bounded by the number of
     * tolerance levels and by max_outer inner loops in all. */
    for (level = 0u; (!solved) && (level < MPSP_MAX_TOL_LEVELS) &&
                     (((int64_t)ctx->n_seg_nom - (int64_t)n_seg_tol) >= -1) &&
                     (res->outer_steps < ctx->cfg.max_outer);
         ++level) {
        ogk_real_t tau_old = OGK_R(0.0);
        ogk_real_t dtau = ctx->cfg.delta_tau_0;
        ogk_real_t tau = tau_old + dtau;
        ogk_real_t lm_cont;
        /* The continuation ends when dtau reaches 0 (tau = 1 reached) or at
         * the give-up rule of lines 17-19. */
        bool cont_done = !(dtau > OGK_R(0.0));

        (void)memcpy(ctx->w_cont, ctx->cfg.weights_nom, nw * sizeof ctx->w_cont[0]);
        lm_cont = ctx->cfg.lambda_m0_nom;
        while ((!cont_done) && (res->outer_steps < ctx->cfg.max_outer)) {
            bool ok;
            blend(&nom, &per, tau, &cur);
            (void)memcpy(ctx->w_iter, ctx->w_cont, nw * sizeof ctx->w_iter[0]);
            lm_iter = lm_cont;
            res->outer_steps += 1u;
            ok = inner_loop(ctx, &cur, ctx->w_iter, &lm_iter, n_seg_tol, &prop, res);
            if (!ok) {
                dtau *= OGK_R(0.5); /* line 12 */
            } else {
                /* line 14 */
                (void)memcpy(ctx->w_cont, ctx->w_iter, nw * sizeof ctx->w_cont[0]);
                lm_cont = lm_iter;
                tau_old = tau;
                dtau = OGK_FMIN(OGK_R(1.0) - tau, OGK_R(2.0) * dtau);
                if (tau > res->tau_reached) {
                    /* best safe command so far */
                    res->tau_reached = tau;
                    (void)memcpy(res->weights, ctx->w_cont, nw * sizeof res->weights[0]);
                    res->lambda_m0 = lm_cont;
                }
            }
            /* line 16 (landing exactly on 1 for the closing step) */
            tau = (dtau >= (OGK_R(1.0) - tau_old)) ? OGK_R(1.0) : (tau_old + dtau);
            /* lines 17-19: give up when the step needed is too small; a closing
             * step (dtau = 1 - tau_old) below delta_tau_min is still taken,
             * which is the paper's rule for delta_tau_0 = 0.5, whose tau are
             * multiples of 0.125. */
            cont_done = ((dtau <= ctx->cfg.delta_tau_min) && (tau_old != OGK_R(1.0)) && (dtau < (OGK_R(1.0) - tau_old))) ||
                        (!(dtau > OGK_R(0.0)));
        }
        if (tau_old == OGK_R(1.0)) {
            solved = true; /* lines 21-22: continuation reached C_per */
        } else {
            n_seg_tol += ctx->cfg.n_seg_tol_step; /* line 24 */
        }
    }

    if (solved) {
        /* The trajectory held is the converged one at C_per (inner_loop
         * returned right after checking it). */
        fill_result(ctx, &per, &prop, true, res);
        st = OGK_OK;
    } else {
        /* Report what the safe command does when flown from x0. */
        bool ok = ogk_i_mpsp_propagate_ctx(ctx, res->weights, res->lambda_m0, per.x0, per.thrust,
                                     &prop) == OGK_OK;
        fill_result(ctx, &per, &prop, ok, res);
        st = OGK_E_NOT_CONVERGED;
    }
    res->converged = solved ? 1u : 0u;
    res->n_seg_tol = n_seg_tol;
    return st;
}

ogk_status ogk_mpsp_solve(ogk_mpsp_t *ctx, const ogk_real_t *x0, ogk_real_t thrust_scale,
                          const ogk_real_t *target_rv, ogk_mpsp_result_t *res)
{
    ogk_status st;

    if ((ctx == NULL) || (x0 == NULL) || (res == NULL)) {
        st = OGK_E_NULL;
    } else if (ctx->init_marker != OGK_MPSP_INIT_MARKER) {
        st = OGK_E_NOT_INIT;
    } else if (!ogk_i_all_finite(x0, OGK_MPSP_NX0) || !isfinite(thrust_scale) ||
               ((target_rv != NULL) && (!ogk_i_all_finite(target_rv, 6u)))) {
        st = OGK_E_NONFINITE;
    } else if (!(x0[6] > OGK_R(0.0)) || !(thrust_scale > OGK_R(0.0))) {
        st = OGK_E_RANGE;
    } else {
        st = solve_checked(ctx, x0, thrust_scale, target_rv, res);
    }
    return st;
}
