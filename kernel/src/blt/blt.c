/* blt.c -- ogk_blt: configuration, the NRPC corrector of sec. III.D (eq. 64 with the paper's
 * step-length search and impact back-off) and the damped corrector beyond the paper
 * (Levenberg-Marquardt on the same minimum-norm problem), evaluation and the thrust command.
 * Design notes: docs/design/blt.md. */
#include "blt_internal.h"
#include "../newton_internal.h"
#include "ogk/internal/blt_test.h"
#include "../thrust_cmd_internal.h"

#include <math.h>
#include <string.h>

#define NX OGK_BLT_NX

/* The defaults of fd_step and tol (ogk/blt.h), per precision of ogk_real_t (ogk/real.h).
 * Double: the central-difference step 1e-6 and the paper's tolerance 1e-6 (normalised units).
 * Float: a step of 1e-6 makes the central difference's round-off eps |e| / h = 0.1 of each
 * Jacobian entry; the step that balances round-off eps / h against truncation h^2 is about
 * eps^(1/3) = 4.9e-3, and 2^-8 = 3.9e-3 (the power of two below it) is the measured best:
 * |central - variational| 4e-5 to 7e-5 of max|J| on the unit tests' transfers, against 2e-4 to
 * 3e-4 at 1e-3 and 1.6e-3 at 1e-4 (docs/design/blt.md). The tolerance 1e-6 is at the float
 * corrector's floor (|e| stalls between 1e-7 and 2.8e-6 on the unit tests' problems, about
 * 1 to 24 eps of their unit-size states: the rounding of a state over a few hundred RK4 steps),
 * so the float build's default is 128 eps = 1.5e-5, five times the worst floor measured. */
#if OGK_REAL_SINGLE
#define BLT_FD_STEP_DEFAULT OGK_R(0.00390625)
#define BLT_TOL_DEFAULT (OGK_R(128.0) * OGK_REAL_EPSILON)
#else
#define BLT_FD_STEP_DEFAULT OGK_R(1.0e-6)
#define BLT_TOL_DEFAULT OGK_R(1.0e-6)
#endif

/* ------------------------------------------------------------------ configuration */

ogk_status ogk_blt_config_default(ogk_blt_config_t *cfg)
{
    ogk_status st = OGK_E_NULL;
    if (cfg != NULL) {
        uint32_t k;
        (void)memset(cfg, 0, sizeof(*cfg));
        cfg->model.mu = OGK_R(0.0);              /* must be set */
        cfg->model.body_radius[0] = OGK_R(0.0);  /* must be set */
        cfg->model.body_radius[1] = OGK_R(0.0);
        cfg->model.ref_radius[0] = OGK_R(1.0);
        cfg->model.ref_radius[1] = OGK_R(1.0);
        cfg->model.sun_rate = -OGK_R(1.0);
        cfg->model.thrust_accel = OGK_R(0.0);    /* must be set */
        cfg->model.step_max = OGK_R(2.0e-3);
        cfg->n_segments = 1u;
        for (k = 0u; k < OGK_BLT_MAX_SEGMENTS; ++k) {
            cfg->segment_kind[k] = OGK_BLT_SEG_BURN;
            cfg->segment_free[k] = OGK_BLT_FREE_ALL;
        }
        cfg->n_free_nodes = 0u;
        cfg->meet_interface[0] = 1u;
        cfg->start_free_mask = 0u;
        cfg->target_mask = 0x3Fu;
        cfg->corrector = OGK_BLT_CORR_NRPC;
        cfg->jacobian = OGK_BLT_JAC_CENTRAL;
        cfg->fd_step = BLT_FD_STEP_DEFAULT;
        cfg->tol = BLT_TOL_DEFAULT;
        cfg->max_iter = 40u;
        cfg->ls_factor = OGK_R(0.1);
        cfg->ls_trials = 4u;
        cfg->impact_halvings = 10u;
        cfg->lm_lambda0 = OGK_R(1.0e-3);
        cfg->lm_up = OGK_R(10.0);
        cfg->lm_down = OGK_R(0.3);
        cfg->lm_trials = 12u;
        cfg->burn_time_min = OGK_R(1.0e-4);
        cfg->time_max = OGK_R(30.0);
        cfg->normalise_ab = 1u;
        st = OGK_OK;
    }
    return st;
}

static bool model_finite(const ogk_blt_model_t *m)
{
    const ogk_real_t s[] = {m->mu, m->srp_accel, m->sun_angle0, m->sun_rate, m->sun_tidal,
                        m->thrust_accel, m->mass_flow, m->step_max};
    return ogk_i_all_finite(s, sizeof(s) / sizeof(s[0])) && ogk_i_all_finite(m->body_radius, 2u) &&
           ogk_i_all_finite(m->ref_radius, 2u) && ogk_i_all_finite(m->c20, 2u) && ogk_i_all_finite(m->c22, 2u);
}

static bool model_ranges_ok(const ogk_blt_model_t *m)
{
    return (m->mu > OGK_R(0.0)) && (m->mu <= OGK_R(0.5)) && (m->body_radius[0] > OGK_R(0.0)) && (m->body_radius[1] > OGK_R(0.0)) &&
           (m->ref_radius[0] > OGK_R(0.0)) && (m->ref_radius[1] > OGK_R(0.0)) && (m->c22[0] == OGK_R(0.0)) &&
           (m->srp_accel >= OGK_R(0.0)) && (m->sun_tidal >= OGK_R(0.0)) && (m->thrust_accel > OGK_R(0.0)) &&
           (m->mass_flow >= OGK_R(0.0)) && (m->step_max > OGK_R(0.0));
}

static bool structure_ok(const ogk_blt_config_t *c)
{
    bool ok = (c->n_segments >= 1u) && (c->n_segments <= OGK_BLT_MAX_SEGMENTS) &&
              (c->n_free_nodes <= OGK_BLT_MAX_FREE_NODES) && (c->start_free_mask <= 0x3Fu) &&
              (c->target_mask <= 0x3Fu);
    uint32_t k;
    for (k = 0u; ok && (k < c->n_segments); ++k) {
        ok = ((c->segment_kind[k] == OGK_BLT_SEG_BURN) || (c->segment_kind[k] == OGK_BLT_SEG_COAST)) &&
             (c->segment_free[k] <= OGK_BLT_FREE_ALL);
    }
    if (ok) {
        uint32_t lo = 0u;
        uint32_t a;
        for (a = 0u; ok && (a <= c->n_free_nodes); ++a) {
            const uint32_t hi = (a < c->n_free_nodes) ? c->free_node_interface[a] : c->n_segments;
            ok = (hi > lo) && (hi <= c->n_segments) && (c->meet_interface[a] >= lo) && (c->meet_interface[a] <= hi);
            lo = hi;
        }
    }
    if (ok) {
        const uint32_t last_meet = c->meet_interface[c->n_free_nodes];
        ok = (last_meet == c->n_segments) ? (c->target_mask != 0u) : (c->target_mask == 0x3Fu);
    }
    return ok;
}

static ogk_status blt_check_config(const ogk_blt_config_t *c)
{
    ogk_status st = OGK_OK;
    const ogk_real_t s[] = {c->fd_step, c->tol, c->ls_factor, c->lm_lambda0, c->lm_up, c->lm_down,
                        c->burn_time_min, c->time_max};
    if (!model_finite(&c->model) || !ogk_i_all_finite(s, sizeof(s) / sizeof(s[0]))) {
        st = OGK_E_NONFINITE;
    } else if (!model_ranges_ok(&c->model) || !structure_ok(c) ||
               (c->corrector > OGK_BLT_CORR_HYBRID) ||
               ((c->jacobian != OGK_BLT_JAC_CENTRAL) && (c->jacobian != OGK_BLT_JAC_VARIATIONAL)) ||
               !(c->fd_step > OGK_R(0.0)) || !(c->tol > OGK_R(0.0)) || (c->max_iter < 1u) ||
               (c->max_iter > OGK_BLT_MAX_ITER) || !(c->ls_factor > OGK_R(0.0)) || !(c->ls_factor < OGK_R(1.0)) ||
               (c->ls_trials < 1u) || (c->ls_trials > OGK_BLT_MAX_TRIALS) ||
               (c->impact_halvings > OGK_BLT_MAX_TRIALS) || !(c->lm_lambda0 > OGK_R(0.0)) || !(c->lm_up > OGK_R(1.0)) ||
               !(c->lm_down > OGK_R(0.0)) || !(c->lm_down <= OGK_R(1.0)) || (c->lm_trials < 1u) ||
               (c->lm_trials > OGK_BLT_MAX_TRIALS) || !(c->burn_time_min > OGK_R(0.0)) ||
               !(c->time_max > c->burn_time_min) ||
               !((c->time_max / c->model.step_max) <= (ogk_real_t)OGK_BLT_MAX_SEGMENT_STEPS) ||
               (c->normalise_ab > 1u)) {
        st = OGK_E_CONFIG;
    } else {
        const uint32_t nu = ogk_i_blt_count_unknowns(c);
        const uint32_t ne = ogk_i_blt_count_errors(c);
        if ((nu < 1u) || (ne > nu)) {
            st = OGK_E_CONFIG; /* eq. (64) needs at least as many unknowns as errors */
        }
    }
    return st;
}

/* Derived quantities: counts, anchors and the column of every unknown (ogk_i_blt_pack's order). */
static void blt_prepare(ogk_blt_t *ctx)
{
    const ogk_blt_config_t *c = &ctx->cfg;
    uint32_t col = 0u;
    uint32_t i;
    uint32_t k;

    ctx->n_unknowns = ogk_i_blt_count_unknowns(c);
    ctx->n_errors = ogk_i_blt_count_errors(c);
    ctx->anchor[0] = 0u;
    for (k = 0u; k < OGK_BLT_MAX_FREE_NODES; ++k) {
        ctx->anchor[k + 1u] = (k < c->n_free_nodes) ? c->free_node_interface[k] : c->n_segments;
    }
    ctx->anchor[OGK_BLT_MAX_ARCS] = c->n_segments; /* every entry defined: reset == a fresh init */
    for (i = 0u; i < NX; ++i) {
        ctx->col_start[i] = OGK_BLT_NO_COLUMN;
        if (((c->start_free_mask >> i) & 1u) != 0u) {
            ctx->col_start[i] = col;
            ++col;
        }
    }
    for (k = 0u; k < OGK_BLT_MAX_SEGMENTS; ++k) {
        for (i = 0u; i < OGK_BLT_NP; ++i) {
            ctx->col_seg[k][i] = OGK_BLT_NO_COLUMN;
            if ((k < c->n_segments) && ((c->segment_free[k] & (1u << i)) != 0u) &&
                ((c->segment_kind[k] == OGK_BLT_SEG_BURN) || (i == 6u))) {
                ctx->col_seg[k][i] = col;
                ++col;
            }
        }
    }
    for (k = 0u; k < OGK_BLT_MAX_FREE_NODES; ++k) {
        for (i = 0u; i < NX; ++i) {
            ctx->col_node[k][i] = OGK_BLT_NO_COLUMN;
            if (k < c->n_free_nodes) {
                ctx->col_node[k][i] = col;
                ++col;
            }
        }
    }
    (void)memset(&ctx->held, 0, sizeof(ctx->held));
    ctx->held_valid = 0u;
    ctx->steps_frozen = 0u;
    (void)memset(ctx->seg_steps, 0, sizeof(ctx->seg_steps));
    ctx->lm_lambda = OGK_R(0.0);
}

ogk_status ogk_blt_init(ogk_blt_t *ctx, const ogk_blt_config_t *cfg)
{
    ogk_status st;
    if ((ctx == NULL) || (cfg == NULL)) {
        st = OGK_E_NULL;
    } else {
        ctx->init_marker = 0u;
        st = blt_check_config(cfg);
        if (st == OGK_OK) {
            (void)memcpy(&ctx->cfg, cfg, sizeof(*cfg));
            blt_prepare(ctx);
            ctx->init_marker = OGK_BLT_INIT_MARKER;
        }
    }
    return st;
}

ogk_status ogk_blt_reset(ogk_blt_t *ctx)
{
    ogk_status st = OGK_OK;
    if (ctx == NULL) {
        st = OGK_E_NULL;
    } else if (ctx->init_marker != OGK_BLT_INIT_MARKER) {
        st = OGK_E_NOT_INIT;
    } else {
        blt_prepare(ctx);
    }
    return st;
}

/* ------------------------------------------------------------------ transfers */

static ogk_status check_transfer(const ogk_blt_config_t *c, const ogk_blt_transfer_t *tr)
{
    ogk_status st = OGK_OK;
    uint32_t k;
    bool finite = isfinite(tr->t0) && isfinite(tr->mass0) && ogk_i_all_finite(tr->x0, NX) &&
                  ogk_i_all_finite(tr->xf, NX);
    for (k = 0u; finite && (k < c->n_segments); ++k) {
        finite = ogk_i_all_finite(tr->seg[k], OGK_BLT_NP);
    }
    for (k = 0u; finite && (k < c->n_free_nodes); ++k) {
        finite = ogk_i_all_finite(tr->node[k], NX);
    }
    if (!finite) {
        st = OGK_E_NONFINITE;
    } else if (!(OGK_FABS(tr->t0) <= BLT_T_ABS_MAX) || !(tr->mass0 > OGK_R(0.0)) || !(tr->mass0 <= OGK_R(1.0))) {
        st = OGK_E_RANGE;
    } else {
        ogk_real_t burned = OGK_R(0.0);
        for (k = 0u; (k < c->n_segments) && (st == OGK_OK); ++k) {
            const ogk_real_t T = tr->seg[k][6];
            if (!(T >= c->burn_time_min) || !(T <= c->time_max)) {
                st = OGK_E_RANGE;
            } else if (c->segment_kind[k] == OGK_BLT_SEG_BURN) {
                burned += T;
            } else {
                /* a coast burns nothing */
            }
        }
        if ((st == OGK_OK) && !((tr->mass0 - (c->model.mass_flow * burned)) > OGK_R(0.0))) {
            st = OGK_E_RANGE; /* the burns would need more than the spacecraft's mass */
        }
    }
    return st;
}

static ogk_real_t norm2(const ogk_real_t *v, uint32_t n)
{
    ogk_real_t s = OGK_R(0.0);
    uint32_t i;
    for (i = 0u; i < n; ++i) {
        s += v[i] * v[i];
    }
    return OGK_SQRT(s);
}

/* |[A; B]| = 1 for every burn (the law is invariant to the scale) and durations kept in range. */
static void tidy(const ogk_blt_config_t *c, ogk_blt_transfer_t *tr)
{
    uint32_t k;
    for (k = 0u; k < c->n_segments; ++k) {
        ogk_real_t *p = tr->seg[k];
        if ((c->normalise_ab != 0u) && (c->segment_kind[k] == OGK_BLT_SEG_BURN)) {
            const ogk_real_t n = norm2(p, 6u);
            if (n > OGK_R(0.0)) {
                uint32_t i;
                for (i = 0u; i < 6u; ++i) {
                    p[i] /= n;
                }
            }
        }
        p[6] = OGK_FMIN(OGK_FMAX(p[6], c->burn_time_min), c->time_max);
    }
}

static void blt_fill_report(const ogk_blt_t *ctx, const ogk_blt_transfer_t *tr, const ogk_real_t *e,
                        const ogk_i_blt_eval_t *ev, ogk_blt_report_t *rep)
{
    const ogk_blt_config_t *c = &ctx->cfg;
    uint32_t k;
    rep->n_unknowns = ctx->n_unknowns;
    rep->n_errors = ctx->n_errors;
    (void)memset(rep->err, 0, sizeof(rep->err));
    if (e != NULL) {
        (void)memcpy(rep->err, e, sizeof(ogk_real_t) * ctx->n_errors);
        rep->err_norm = norm2(e, ctx->n_errors);
    }
    rep->burn_time = OGK_R(0.0);
    rep->flight_time = OGK_R(0.0);
    for (k = 0u; k < c->n_segments; ++k) {
        rep->flight_time += tr->seg[k][6];
        if (c->segment_kind[k] == OGK_BLT_SEG_BURN) {
            rep->burn_time += tr->seg[k][6];
        }
    }
    rep->mass_final = tr->mass0 - (c->model.mass_flow * rep->burn_time);
    rep->min_distance[0] = ev->min_distance[0];
    rep->min_distance[1] = ev->min_distance[1];
}

static ogk_status check_call(const ogk_blt_t *ctx, const void *a, const void *b)
{
    ogk_status st = OGK_OK;
    if ((ctx == NULL) || (a == NULL) || (b == NULL)) {
        st = OGK_E_NULL;
    } else if (ctx->init_marker != OGK_BLT_INIT_MARKER) {
        st = OGK_E_NOT_INIT;
    } else {
        /* usable */
    }
    return st;
}

ogk_status ogk_blt_evaluate(ogk_blt_t *ctx, const ogk_blt_transfer_t *tr, ogk_blt_report_t *rep)
{
    ogk_status st = check_call(ctx, tr, rep);
    if (rep != NULL) {
        (void)memset(rep, 0, sizeof(*rep));
    }
    if (st == OGK_OK) {
        st = check_transfer(&ctx->cfg, tr);
    }
    if (st == OGK_OK) {
        ogk_i_blt_eval_t ev;
        (void)memset(&ev, 0, sizeof(ev));
        ctx->steps_frozen = 0u;
        ogk_i_blt_errors(ctx, tr, ctx->e_trial, NULL, &ev);
        rep->propagations = ev.propagations;
        blt_fill_report(ctx, tr, ctx->e_trial, &ev, rep);
        rep->err_norm0 = rep->err_norm;
        if (ev.impact || ev.bad_rhs) {
            rep->flags |= ev.impact ? OGK_BLT_FLAG_IMPACT : OGK_BLT_FLAG_SINGULAR;
            st = OGK_E_NOT_CONVERGED;
        } else if (rep->err_norm <= ctx->cfg.tol) {
            rep->flags |= OGK_BLT_FLAG_CONVERGED;
        } else {
            /* an evaluation only */
        }
    }
    return st;
}

ogk_status ogk_blt_propagate(ogk_blt_t *ctx, const ogk_blt_transfer_t *tr, ogk_real_t x_end[OGK_BLT_NX],
                             ogk_blt_report_t *rep)
{
    ogk_status st = check_call(ctx, tr, rep);
    if ((st == OGK_OK) && (x_end == NULL)) {
        st = OGK_E_NULL;
    }
    if (rep != NULL) {
        (void)memset(rep, 0, sizeof(*rep));
    }
    if (st == OGK_OK) {
        st = check_transfer(&ctx->cfg, tr);
    }
    if (st == OGK_OK) {
        ogk_i_blt_eval_t ev;
        (void)memset(&ev, 0, sizeof(ev));
        ctx->steps_frozen = 0u;
        ogk_i_blt_chain(ctx, tr, x_end, &ev);
        rep->propagations = ev.propagations;
        blt_fill_report(ctx, tr, NULL, &ev, rep);
        if (ev.impact || ev.bad_rhs) {
            rep->flags |= ev.impact ? OGK_BLT_FLAG_IMPACT : OGK_BLT_FLAG_SINGULAR;
            st = OGK_E_NOT_CONVERGED;
        }
    }
    return st;
}

/* ------------------------------------------------------------------ Jacobian */

/* J at tr into ctx->jac (n_errors x n_unknowns) with the RK4 step counts frozen at tr's, so
 * that a perturbed duration does not change the grid. false when a perturbed trajectory hits a
 * body or has no finite right-hand side. */
static bool jacobian_at(ogk_blt_t *ctx, const ogk_blt_transfer_t *tr, uint32_t *propagations)
{
    const ogk_blt_config_t *c = &ctx->cfg;
    const uint32_t nu = ctx->n_unknowns;
    const uint32_t ne = ctx->n_errors;
    ogk_i_blt_eval_t ev;
    bool ok = true;
    uint32_t k;

    (void)memset(&ev, 0, sizeof(ev));
    for (k = 0u; k < c->n_segments; ++k) {
        ctx->seg_steps[k] = ogk_i_blt_steps_for(c, tr->seg[k][6]);
    }
    ctx->steps_frozen = 1u;
    if (c->jacobian == OGK_BLT_JAC_VARIATIONAL) {
        ogk_i_blt_errors(ctx, tr, ctx->e_trial, ctx->jac, &ev);
        ok = !ev.impact && !ev.bad_rhs;
    } else {
        ogk_blt_transfer_t pert;
        uint32_t j;
        ogk_i_blt_pack(c, tr, ctx->u_trial);
        (void)memcpy(&pert, tr, sizeof(pert));
        for (j = 0u; ok && (j < nu); ++j) {
            const ogk_real_t uj = ctx->u_trial[j];
            const ogk_real_t h = c->fd_step;
            uint32_t i;
            ctx->u_trial[j] = uj + h; /* eq. (62) */
            ogk_i_blt_unpack(c, ctx->u_trial, &pert);
            ogk_i_blt_errors(ctx, &pert, ctx->e_plus, NULL, &ev);
            ok = !ev.impact && !ev.bad_rhs;
            ctx->u_trial[j] = uj - h;
            ogk_i_blt_unpack(c, ctx->u_trial, &pert);
            ogk_i_blt_errors(ctx, &pert, ctx->e_trial, NULL, &ev);
            ok = ok && !ev.impact && !ev.bad_rhs;
            ctx->u_trial[j] = uj;
            for (i = 0u; i < ne; ++i) {
                ctx->jac[(i * nu) + j] = (ctx->e_plus[i] - ctx->e_trial[i]) / (OGK_R(2.0) * h);
            }
        }
    }
    ctx->steps_frozen = 0u;
    *propagations += ev.propagations;
    return ok && ogk_i_all_finite(ctx->jac, (size_t)ne * nu);
}

ogk_status ogk_blt_jacobian(ogk_blt_t *ctx, const ogk_blt_transfer_t *tr, ogk_real_t *jac, size_t jac_len)
{
    ogk_status st = check_call(ctx, tr, jac);
    if ((st == OGK_OK) && (jac_len < ((size_t)ctx->n_errors * ctx->n_unknowns))) {
        st = OGK_E_DIM;
    }
    if (st == OGK_OK) {
        st = check_transfer(&ctx->cfg, tr);
    }
    if (st == OGK_OK) {
        uint32_t props = 0u;
        if (jacobian_at(ctx, tr, &props)) {
            (void)memcpy(jac, ctx->jac, sizeof(ogk_real_t) * ctx->n_errors * ctx->n_unknowns);
        } else {
            st = OGK_E_NOT_CONVERGED;
        }
    }
    return st;
}

/* ------------------------------------------------------------------ corrector */

/* du = the minimum-norm solution of [J, sqrt(lambda) I] [du; s] = -e: eq. (64) for lambda = 0,
 * the Levenberg-Marquardt step -J^T (J J^T + lambda I)^-1 e otherwise (newton.c). */
static bool corrector_step(ogk_blt_t *ctx, ogk_real_t lambda)
{
    const uint32_t nu = ctx->n_unknowns;
    const uint32_t ne = ctx->n_errors;
    ogk_real_t rhs[OGK_BLT_MAX_ERRORS];
    uint32_t i;

    for (i = 0u; i < ne; ++i) {
        rhs[i] = -ctx->e[i];
    }
    return ogk_i_newton_minnorm(&ctx->qr, ctx->jac, ne, nu, lambda, rhs, ctx->jaug, ctx->step_aug, ctx->du) ==
           OGK_OK;
}

/* trial = cur + alpha du, tidied; its errors into ctx->e_trial. */
static void try_step(ogk_blt_t *ctx, const ogk_blt_transfer_t *cur, ogk_real_t alpha, ogk_blt_transfer_t *trial,
                     ogk_i_blt_eval_t *ev)
{
    const uint32_t nu = ctx->n_unknowns;
    uint32_t j;
    ogk_i_blt_pack(&ctx->cfg, cur, ctx->u);
    for (j = 0u; j < nu; ++j) {
        ctx->u_trial[j] = ctx->u[j] + (alpha * ctx->du[j]);
    }
    (void)memcpy(trial, cur, sizeof(*trial));
    ogk_i_blt_unpack(&ctx->cfg, ctx->u_trial, trial);
    tidy(&ctx->cfg, trial);
    ogk_i_blt_errors(ctx, trial, ctx->e_trial, NULL, ev);
}

/* The paper's line search: step lengths 1, f, f^2, ... (f = 1/10) until |e| decreases; a step
 * whose trajectory hits a body is halved (up to impact_halvings times) first. */
static bool nrpc_search(ogk_blt_t *ctx, const ogk_blt_transfer_t *cur, ogk_real_t e_norm, ogk_blt_transfer_t *trial,
                        ogk_i_blt_eval_t *ev, uint32_t *flags, uint32_t *propagations) /* NOLINT(bugprone-easily-swappable-parameters): the solve's two accumulators, in its order */
{
    const ogk_blt_config_t *c = &ctx->cfg;
    ogk_real_t alpha = OGK_R(1.0);
    bool accepted = false;
    uint32_t trial_no;
    uint32_t halvings = 0u;

    for (trial_no = 0u; (trial_no < c->ls_trials) && !accepted; ++trial_no) {
        bool hit = true;
        while (hit && (halvings <= c->impact_halvings)) {
            try_step(ctx, cur, alpha, trial, ev);
            *propagations += ev->propagations;
            ev->propagations = 0u;
            hit = ev->impact || ev->bad_rhs;
            if (hit) {
                *flags |= OGK_BLT_FLAG_IMPACT;
                alpha *= OGK_R(0.5);
                ++halvings;
            }
        }
        if (!hit && (norm2(ctx->e_trial, ctx->n_errors) < e_norm)) {
            accepted = true;
        } else {
            alpha *= c->ls_factor;
        }
    }
    return accepted;
}

/* Levenberg-Marquardt: raise lambda until the step decreases |e| without impact. */
static bool lm_search(ogk_blt_t *ctx, const ogk_blt_transfer_t *cur, ogk_real_t e_norm, ogk_blt_transfer_t *trial,
                      ogk_i_blt_eval_t *ev, uint32_t *flags, uint32_t *propagations) /* NOLINT(bugprone-easily-swappable-parameters): as nrpc_search */
{
    const ogk_blt_config_t *c = &ctx->cfg;
    bool accepted = false;
    uint32_t trial_no;

    for (trial_no = 0u; (trial_no < c->lm_trials) && !accepted; ++trial_no) {
        if (!corrector_step(ctx, ctx->lm_lambda)) {
            *flags |= OGK_BLT_FLAG_SINGULAR;
        } else {
            bool hit;
            try_step(ctx, cur, OGK_R(1.0), trial, ev);
            *propagations += ev->propagations;
            ev->propagations = 0u;
            hit = ev->impact || ev->bad_rhs;
            if (hit) {
                *flags |= OGK_BLT_FLAG_IMPACT;
            }
            accepted = !hit && (norm2(ctx->e_trial, ctx->n_errors) < e_norm);
        }
        if (accepted) {
            ctx->lm_lambda *= c->lm_down;
        } else {
            ctx->lm_lambda *= c->lm_up;
        }
    }
    return accepted;
}

/* lambda_0 relative to the mean diagonal of J J^T (the squared row norms of J). */
static ogk_real_t lm_scale(const ogk_blt_t *ctx)
{
    ogk_real_t s = OGK_R(0.0);
    uint32_t i;
    for (i = 0u; i < ctx->n_errors; ++i) {
        const ogk_real_t r = norm2(&ctx->jac[(size_t)i * ctx->n_unknowns], ctx->n_unknowns);
        s += r * r;
    }
    return s / (ogk_real_t)ctx->n_errors;
}

/* One corrector iteration from cur (J held): the Newton step of eq. (64) with the paper's search (NRPC,
 * and HYBRID first), the Levenberg-Marquardt search (LM, and HYBRID when the Newton search found no
 * decrease). true with the accepted transfer in trial and its errors in ctx->e_trial. */
static bool blt_iterate(ogk_blt_t *ctx, const ogk_blt_transfer_t *cur, ogk_real_t e_norm, ogk_blt_transfer_t *trial,
                        ogk_i_blt_eval_t *ev, uint32_t *flags, uint32_t *propagations, uint32_t iteration)
{
    const uint32_t kind = ctx->cfg.corrector;
    bool accepted = false;
    if ((kind != OGK_BLT_CORR_NRPC) && (iteration == 1u)) {
        ctx->lm_lambda = ctx->cfg.lm_lambda0 * lm_scale(ctx);
    }
    if (kind != OGK_BLT_CORR_LM) {
        if (!corrector_step(ctx, OGK_R(0.0))) {
            *flags |= OGK_BLT_FLAG_SINGULAR;
        } else {
            accepted = nrpc_search(ctx, cur, e_norm, trial, ev, flags, propagations);
            if (!accepted && (kind == OGK_BLT_CORR_NRPC)) {
                *flags |= OGK_BLT_FLAG_STALLED;
            }
        }
    }
    if (!accepted && (kind != OGK_BLT_CORR_NRPC)) {
        accepted = lm_search(ctx, cur, e_norm, trial, ev, flags, propagations);
        if (!accepted) {
            *flags |= OGK_BLT_FLAG_STALLED;
        }
    }
    return accepted;
}

ogk_status ogk_blt_solve(ogk_blt_t *ctx, const ogk_blt_transfer_t *guess, ogk_blt_transfer_t *solution,
                         ogk_blt_report_t *rep)
{
    ogk_status st = check_call(ctx, guess, solution);
    ogk_blt_transfer_t cur;
    ogk_blt_transfer_t trial;
    ogk_i_blt_eval_t ev;
    uint32_t flags = 0u;
    uint32_t iterations = 0u;
    uint32_t propagations = 0u;
    bool have_e = false; /* an error vector exists (its norms below) */
    ogk_real_t e_norm = OGK_R(0.0);
    ogk_real_t e_norm0 = OGK_R(0.0);

    (void)memset(&ev, 0, sizeof(ev));
    if (rep == NULL) {
        st = OGK_E_NULL;
    } else {
        (void)memset(rep, 0, sizeof(*rep));
    }
    if ((guess != NULL) && (solution != NULL) && (guess != solution)) {
        (void)memcpy(solution, guess, sizeof(*solution)); /* the safe output: the guess unchanged */
    }
    if (st == OGK_OK) {
        ctx->held_valid = 0u;
        st = check_transfer(&ctx->cfg, guess);
    }
    if (st == OGK_OK) {
        (void)memcpy(&cur, guess, sizeof(cur));
        tidy(&ctx->cfg, &cur);
        ctx->steps_frozen = 0u;
        ogk_i_blt_errors(ctx, &cur, ctx->e, NULL, &ev);
        propagations += ev.propagations;
        ev.propagations = 0u;
        if (ev.impact || ev.bad_rhs) {
            flags |= OGK_BLT_FLAG_GUESS_IMPACT | (ev.impact ? OGK_BLT_FLAG_IMPACT : OGK_BLT_FLAG_SINGULAR);
            blt_fill_report(ctx, &cur, NULL, &ev, rep); /* durations, mass, where it hit; no error vector */
            st = OGK_E_NOT_CONVERGED;
        }
    }
    if (st == OGK_OK) {
        bool go = true;
        ogk_i_blt_eval_t ev_cur = ev;
        have_e = true;
        e_norm = norm2(ctx->e, ctx->n_errors);
        e_norm0 = e_norm;
        while (go) {
            if (e_norm <= ctx->cfg.tol) {
                flags |= OGK_BLT_FLAG_CONVERGED;
                go = false;
            } else if (iterations >= ctx->cfg.max_iter) {
                flags |= OGK_BLT_FLAG_ITER_LIMIT;
                go = false;
            } else if (!jacobian_at(ctx, &cur, &propagations)) {
                flags |= OGK_BLT_FLAG_SINGULAR;
                go = false;
            } else {
                bool accepted;
                ++iterations;
                accepted = blt_iterate(ctx, &cur, e_norm, &trial, &ev, &flags, &propagations, iterations);
                if (accepted) {
                    (void)memcpy(&cur, &trial, sizeof(cur));
                    (void)memcpy(ctx->e, ctx->e_trial, sizeof(ogk_real_t) * ctx->n_errors);
                    e_norm = norm2(ctx->e, ctx->n_errors);
                    ev_cur = ev;
                } else {
                    go = false;
                }
            }
        }
        (void)memcpy(solution, &cur, sizeof(cur));
        blt_fill_report(ctx, &cur, ctx->e, &ev_cur, rep);
        if ((flags & OGK_BLT_FLAG_CONVERGED) != 0u) {
            (void)memcpy(&ctx->held, &cur, sizeof(cur));
            ctx->held_valid = 1u;
        } else {
            st = ((flags & OGK_BLT_FLAG_ITER_LIMIT) != 0u) ? OGK_E_ITER_LIMIT : OGK_E_NOT_CONVERGED;
        }
    }
    if (rep != NULL) {
        rep->flags = flags | (((flags & OGK_BLT_FLAG_CONVERGED) == 0u) ? OGK_BLT_FLAG_SAFE : 0u);
        rep->iterations = iterations;
        rep->propagations = propagations;
        /* HUGE_VAL when no error vector exists (bad input, guess hits a body): the
         * infinity is made only on that path (docs/evidence/eva.md, BLT) */
        rep->err_norm0 = have_e ? e_norm0 : OGK_REAL_HUGE_VAL;
        if (st != OGK_OK) {
            rep->err_norm = have_e ? e_norm : OGK_REAL_HUGE_VAL;
        }
    }
    return st;
}

/* ------------------------------------------------------------------ command */

/* ogk_blt_command (also behind ogk_blt_thrust_cmd). */
static ogk_status blt_command(const ogk_blt_t *ctx, ogk_real_t t, ogk_blt_command_t *cmd)
{
    ogk_status st = OGK_OK;
    if ((ctx == NULL) || (cmd == NULL)) {
        st = OGK_E_NULL;
    } else {
        (void)memset(cmd, 0, sizeof(*cmd));
        cmd->t = t;
        cmd->flags = OGK_BLT_FLAG_SAFE; /* engine off until proven otherwise */
        if (ctx->init_marker != OGK_BLT_INIT_MARKER) {
            st = OGK_E_NOT_INIT;
        } else if (!isfinite(t)) {
            st = OGK_E_NONFINITE;
        } else if (ctx->held_valid == 0u) {
            st = OGK_E_SAFE_COMMAND;
        } else if (t < ctx->held.t0) {
            st = OGK_E_RANGE;
        } else {
            const ogk_blt_config_t *c = &ctx->cfg;
            ogk_real_t t_seg = ctx->held.t0;
            uint32_t k = 0u;
            uint32_t j;
            bool found = false;
            cmd->flags = 0u;
            for (j = 0u; j < c->n_segments; ++j) {
                if (!found) {
                    if (t >= (t_seg + ctx->held.seg[j][6])) {
                        t_seg += ctx->held.seg[j][6];
                        k = j + 1u;
                    } else {
                        found = true;
                    }
                }
            }
            cmd->segment = k;
            if ((k < c->n_segments) && (c->segment_kind[k] == OGK_BLT_SEG_BURN)) {
                const ogk_real_t *p = ctx->held.seg[k];
                const ogk_real_t tau = t - t_seg;
                const ogk_real_t w[3] = {p[0] + (p[3] * tau), p[1] + (p[4] * tau), p[2] + (p[5] * tau)};
                const ogk_real_t wn = norm2(w, 3u);
                if (wn > OGK_R(0.0)) {
                    uint32_t i;
                    for (i = 0u; i < 3u; ++i) {
                        cmd->u_hat[i] = w[i] / wn; /* eq. (22) */
                    }
                    cmd->engine_on = 1u;
                } else {
                    cmd->flags = OGK_BLT_FLAG_SAFE;
                    st = OGK_E_SAFE_COMMAND;
                }
            }
        }
    }
    return st;
}

ogk_status ogk_blt_command(const ogk_blt_t *ctx, ogk_real_t t, ogk_blt_command_t *cmd)
{
    return blt_command(ctx, t, cmd);
}

/* The direction to hold while the engine is off in segment k (a coast, or k =
 * n_segments after the end): the next burn's at its start, eq. (22) at tau =
 * 0, A / |A|; (1, 0, 0) when no burn follows (or its A is zero). The segments
 * after k are visited last to first, so the first burn after k is the one
 * that stays. */
static void hold_direction(const ogk_blt_t *ctx, uint32_t k, ogk_real_t u[3])
{
    const ogk_blt_config_t *c = &ctx->cfg;
    uint32_t j;
    u[0] = OGK_R(1.0);
    u[1] = OGK_R(0.0);
    u[2] = OGK_R(0.0);
    for (j = c->n_segments; j > (k + 1u); --j) {
        if (c->segment_kind[j - 1u] == OGK_BLT_SEG_BURN) {
            const ogk_real_t *a = ctx->held.seg[j - 1u];
            const ogk_real_t an = norm2(a, 3u);
            if (an > OGK_R(0.0)) {
                u[0] = a[0] / an;
                u[1] = a[1] / an;
                u[2] = a[2] / an;
            } else {
                u[0] = OGK_R(1.0);
                u[1] = OGK_R(0.0);
                u[2] = OGK_R(0.0);
            }
        }
    }
}

ogk_status ogk_blt_thrust_cmd(const ogk_blt_t *ctx, ogk_real_t t, ogk_thrust_cmd_t *cmd)
{
    ogk_status st;
    if (cmd == NULL) {
        st = OGK_E_NULL;
    } else {
        ogk_blt_command_t bc;
        ogk_i_thrust_cmd_safe(cmd, t, OGK_FRAME_SYNODIC, OGK_BLT_FLAG_SAFE);
        st = blt_command(ctx, t, &bc); /* OGK_E_NULL for a NULL ctx */
        if (st != OGK_OK) {
            /* the safe command */
        } else if (bc.engine_on != 0u) {
            ogk_i_thrust_cmd_unit(cmd, t, OGK_FRAME_SYNODIC, bc.u_hat, OGK_R(1.0), OGK_THRUST_FLAG_ENGINE_ON,
                                  bc.flags);
        } else {
            ogk_real_t u[3];
            hold_direction(ctx, bc.segment, u);
            ogk_i_thrust_cmd_unit(cmd, t, OGK_FRAME_SYNODIC, u, OGK_R(0.0), 0u, bc.flags);
        }
    }
    return st;
}
