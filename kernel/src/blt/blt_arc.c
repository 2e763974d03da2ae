/* blt_arc.c -- the prediction of NRPC (sec. III.D): the unknown vector, RK4 propagation of the
 * segments forward and backward with impact detection, the arcs' errors at their meeting points
 * (eqs. 65 and 70) and, optionally, their sensitivities by the variational equations. */
#include "blt_internal.h"
#include "../rk4_internal.h"

#include <float.h>
#include <math.h>
#include <string.h>

#define NX OGK_BLT_NX

/* ------------------------------------------------------------------ unknowns */

static bool seg_param_free(const ogk_blt_config_t *cfg, uint32_t k, uint32_t p)
{
    bool is_free = (cfg->segment_free[k] & (1u << p)) != 0u;
    if ((cfg->segment_kind[k] != OGK_BLT_SEG_BURN) && (p != 6u)) {
        is_free = false; /* a coast has its duration only */
    }
    return is_free;
}

uint32_t ogk_i_blt_count_unknowns(const ogk_blt_config_t *cfg)
{
    uint32_t n = 0u;
    uint32_t i;
    uint32_t k;
    for (i = 0u; i < NX; ++i) {
        n += ((cfg->start_free_mask >> i) & 1u);
    }
    for (k = 0u; k < cfg->n_segments; ++k) {
        for (i = 0u; i < OGK_BLT_NP; ++i) {
            n += seg_param_free(cfg, k, i) ? 1u : 0u;
        }
    }
    return n + (NX * cfg->n_free_nodes);
}

uint32_t ogk_i_blt_count_errors(const ogk_blt_config_t *cfg)
{
    const uint32_t last = cfg->n_free_nodes;
    uint32_t n = NX * last;
    if (cfg->meet_interface[last] == cfg->n_segments) {
        uint32_t i;
        for (i = 0u; i < NX; ++i) {
            n += ((cfg->target_mask >> i) & 1u);
        }
    } else {
        n += NX;
    }
    return n;
}

void ogk_i_blt_pack(const ogk_blt_config_t *cfg, const ogk_blt_transfer_t *tr, ogk_real_t *u)
{
    uint32_t n = 0u;
    uint32_t i;
    uint32_t k;
    for (i = 0u; i < NX; ++i) {
        if (((cfg->start_free_mask >> i) & 1u) != 0u) {
            u[n] = tr->x0[i];
            ++n;
        }
    }
    for (k = 0u; k < cfg->n_segments; ++k) {
        for (i = 0u; i < OGK_BLT_NP; ++i) {
            if (seg_param_free(cfg, k, i)) {
                u[n] = tr->seg[k][i];
                ++n;
            }
        }
    }
    for (k = 0u; k < cfg->n_free_nodes; ++k) {
        for (i = 0u; i < NX; ++i) {
            u[n] = tr->node[k][i];
            ++n;
        }
    }
}

void ogk_i_blt_unpack(const ogk_blt_config_t *cfg, const ogk_real_t *u, ogk_blt_transfer_t *tr)
{
    uint32_t n = 0u;
    uint32_t i;
    uint32_t k;
    for (i = 0u; i < NX; ++i) {
        if (((cfg->start_free_mask >> i) & 1u) != 0u) {
            tr->x0[i] = u[n];
            ++n;
        }
    }
    for (k = 0u; k < cfg->n_segments; ++k) {
        for (i = 0u; i < OGK_BLT_NP; ++i) {
            if (seg_param_free(cfg, k, i)) {
                tr->seg[k][i] = u[n];
                ++n;
            }
        }
    }
    for (k = 0u; k < cfg->n_free_nodes; ++k) {
        for (i = 0u; i < NX; ++i) {
            tr->node[k][i] = u[n];
            ++n;
        }
    }
}

uint32_t ogk_i_blt_steps_for(const ogk_blt_config_t *cfg, ogk_real_t duration)
{
    const ogk_real_t ratio = OGK_FABS(duration) / cfg->model.step_max;
    uint32_t n;
    if (!(ratio < (ogk_real_t)OGK_BLT_MAX_SEGMENT_STEPS)) {
        n = OGK_BLT_MAX_SEGMENT_STEPS;
    } else {
        n = (uint32_t)OGK_CEIL(ratio);
        if (n == 0u) {
            n = 1u;
        }
    }
    return n;
}

/* ------------------------------------------------------------------ propagation */

static void track_bodies(const ogk_blt_model_t *m, const ogk_real_t x[NX], ogk_i_blt_eval_t *ev)
{
    const ogk_real_t body_x[2] = {-m->mu, OGK_R(1.0) - m->mu};
    size_t b;
    for (b = 0u; b < 2u; ++b) {
        const ogk_real_t dx = x[0] - body_x[b];
        const ogk_real_t d = OGK_SQRT((dx * dx) + (x[1] * x[1]) + (x[2] * x[2]));
        if (!(d >= ev->min_distance[b])) {
            ev->min_distance[b] = d;
        }
        if (!(d > m->body_radius[b])) {
            ev->impact = true;
        }
    }
}

/* The slot of column col in var (OGK_BLT_NO_COLUMN when the column is not carried: it is zero). */
static uint32_t blt_slot_of(const ogk_blt_t *ctx, uint32_t col)
{
    return (col == OGK_BLT_NO_COLUMN) ? OGK_BLT_NO_COLUMN : ctx->slot[col];
}

/* Starts carrying column col (a zero column) when it is not carried yet. */
static void blt_activate(ogk_blt_t *ctx, ogk_real_t *y, uint32_t col)
{
    if ((col != OGK_BLT_NO_COLUMN) && (ctx->slot[col] == OGK_BLT_NO_COLUMN)) {
        ctx->slot[col] = ctx->n_live;
        (void)memset(&y[NX + ((size_t)ctx->n_live * NX)], 0, sizeof(ogk_real_t) * NX);
        ctx->n_live += 1u;
    }
}

/* The columns segment k can make non-zero: its own A, B (a burn) and T, and every earlier T. */
static void blt_activate_segment(ogk_blt_t *ctx, ogk_real_t *y, uint32_t k)
{
    uint32_t p;
    uint32_t j;
    for (p = 0u; p < OGK_BLT_NP; ++p) {
        blt_activate(ctx, y, ctx->col_seg[k][p]);
    }
    for (j = 0u; j < k; ++j) {
        blt_activate(ctx, y, ctx->col_seg[j][6]);
    }
}

/* Right-hand side of the state and, when nu > 0, of the nu carried sensitivity columns (6 entries
 * each, after the state in y; ctx->slot maps J's columns to them): S' = F S + G (docs/design/blt.md,
 * "Variational equations"). A column no segment has forced yet is zero and not carried. */
static bool rhs_aug(const ogk_blt_t *ctx, const ogk_i_blt_seg_t *seg, uint32_t k, ogk_real_t tau, const ogk_real_t *y, /* NOLINT(bugprone-easily-swappable-parameters): segment index, then its time */
                    ogk_real_t *dy, uint32_t nu)
{
    const ogk_blt_config_t *cfg = &ctx->cfg;
    ogk_i_blt_rhs_parts_t parts;
    bool ok = ogk_i_blt_rhs(&cfg->model, seg, tau, y, dy, (nu > 0u) ? &parts : NULL);
    if (ok && (nu > 0u)) {
        const ogk_real_t *S = &y[NX];
        ogk_real_t *dS = &dy[NX];
        ogk_real_t dadt[3];
        ogk_real_t dadm[3];
        uint32_t c;
        uint32_t i;
        uint32_t j;
        const ogk_real_t sr = (parts.s_hat[0] * y[0]) + (parts.s_hat[1] * y[1]);
        const ogk_real_t dsr = (parts.ds_hat[0] * y[0]) + (parts.ds_hat[1] * y[1]);
        for (i = 0u; i < 3u; ++i) {
            /* explicit time dependence (the Sun's direction): SRP and tide */
            dadt[i] = (-parts.srp * parts.ds_hat[i]) +
                      (cfg->model.sun_tidal * OGK_R(3.0) * ((parts.ds_hat[i] * sr) + (parts.s_hat[i] * dsr)));
            /* d a / d m: thrust / m and SRP / m */
            dadm[i] = (parts.srp * parts.s_hat[i]) / parts.mass;
            if (seg->burn) {
                dadm[i] -= (parts.thrust * parts.u_hat[i]) / parts.mass;
            }
        }
        for (c = 0u; c < nu; ++c) {
            const ogk_real_t *Sc = &S[(size_t)c * NX];
            ogk_real_t *dSc = &dS[(size_t)c * NX];
            for (i = 0u; i < 3u; ++i) {
                dSc[i] = Sc[3u + i];
                dSc[3u + i] = (parts.grad[(size_t)i * 3u] * Sc[0]) + (parts.grad[(i * 3u) + 1u] * Sc[1]) +
                              (parts.grad[(i * 3u) + 2u] * Sc[2]);
            }
            dSc[3] += OGK_R(2.0) * Sc[4]; /* Coriolis */
            dSc[4] -= OGK_R(2.0) * Sc[3];
        }
        /* G: the direct dependence on the parameters */
        if (seg->burn) {
            for (j = 0u; j < 3u; ++j) {
                const uint32_t ca = blt_slot_of(ctx, ctx->col_seg[k][j]);
                const uint32_t cb = blt_slot_of(ctx, ctx->col_seg[k][3u + j]);
                for (i = 0u; i < 3u; ++i) {
                    /* d u_hat / d w = (I - u u^T) / |w|, w = A + B tau */
                    const ogk_real_t d = (parts.thrust / parts.w_norm) *
                                     (((i == j) ? OGK_R(1.0) : OGK_R(0.0)) - (parts.u_hat[i] * parts.u_hat[j]));
                    if (ca != OGK_BLT_NO_COLUMN) {
                        dS[(ca * NX) + 3u + i] += d;
                    }
                    if (cb != OGK_BLT_NO_COLUMN) {
                        dS[(cb * NX) + 3u + i] += d * tau;
                    }
                }
            }
        }
        for (j = 0u; j < k; ++j) {
            /* an earlier duration shifts this segment's time and (a burn) lowers its mass */
            const uint32_t ct = blt_slot_of(ctx, ctx->col_seg[j][6]);
            if (ct != OGK_BLT_NO_COLUMN) {
                const ogk_real_t mass_rate = (cfg->segment_kind[j] == OGK_BLT_SEG_BURN) ? -cfg->model.mass_flow : OGK_R(0.0);
                for (i = 0u; i < 3u; ++i) {
                    dS[(ct * NX) + 3u + i] += dadt[i] + (dadm[i] * mass_rate);
                }
            }
        }
    }
    return ok;
}

/* Propagates segment k over its duration T in n RK4 steps, forward (tau 0 -> T) or backward
 * (T -> 0); y = state (+ sensitivities when nu > 0). Stops at an impact. */
static void prop_segment(ogk_blt_t *ctx, const ogk_i_blt_seg_t *seg, uint32_t k, ogk_real_t duration, uint32_t n, /* NOLINT(bugprone-easily-swappable-parameters): index, duration, steps */
                         bool backward, ogk_real_t *y, uint32_t nu, ogk_i_blt_eval_t *ev)
{
    const size_t dim = (size_t)NX * ((size_t)nu + 1u);
    ogk_real_t *k1 = &ctx->var_k[0];
    ogk_real_t *k2 = &ctx->var_k[dim];
    ogk_real_t *k3 = &ctx->var_k[2u * dim];
    ogk_real_t *k4 = &ctx->var_k[3u * dim];
    ogk_real_t *tmp = &ctx->var_k[4u * dim];
    const ogk_real_t h = (backward ? -duration : duration) / (ogk_real_t)n;
    uint32_t s;
    bool go = true;

    ev->propagations += 1u;
    for (s = 0u; (s < n) && go; ++s) {
        const ogk_real_t tau = backward ? (duration - (((ogk_real_t)s) * (duration / (ogk_real_t)n)))
                                    : (((ogk_real_t)s) * (duration / (ogk_real_t)n));
        bool ok;
        ok = rhs_aug(ctx, seg, k, tau, y, k1, nu);
        ogk_i_rk4_stage_state(y, OGK_R(0.5) * h, k1, dim, tmp);
        ok = ok && rhs_aug(ctx, seg, k, tau + (OGK_R(0.5) * h), tmp, k2, nu);
        ogk_i_rk4_stage_state(y, OGK_R(0.5) * h, k2, dim, tmp);
        ok = ok && rhs_aug(ctx, seg, k, tau + (OGK_R(0.5) * h), tmp, k3, nu);
        ogk_i_rk4_stage_state(y, h, k3, dim, tmp);
        ok = ok && rhs_aug(ctx, seg, k, tau + h, tmp, k4, nu);
        if (!ok) {
            ev->bad_rhs = true;
            go = false;
        } else {
            ogk_i_rk4_accumulate(y, k1, k2, k3, k4, h / OGK_R(6.0), dim);
            track_bodies(&ctx->cfg.model, y, ev);
            go = !ev->impact && ogk_i_all_finite(y, NX);
            if (!ogk_i_all_finite(y, NX)) {
                ev->bad_rhs = true;
            }
        }
    }
}

static uint32_t steps_of(const ogk_blt_t *ctx, const ogk_blt_transfer_t *tr, uint32_t k)
{
    return (ctx->steps_frozen != 0u) ? ctx->seg_steps[k] : ogk_i_blt_steps_for(&ctx->cfg, tr->seg[k][6]);
}

/* Adds sign * f(x at tau) of segment k to the sensitivity column of its duration. */
static void duration_jump(ogk_blt_t *ctx, const ogk_i_blt_seg_t *seg, uint32_t k, ogk_real_t tau, ogk_real_t *y, bool sens, /* NOLINT(bugprone-easily-swappable-parameters): as prop_segment */
                          ogk_real_t sign, ogk_i_blt_eval_t *ev)
{
    const uint32_t ct = ctx->col_seg[k][6];
    if (sens && (ct != OGK_BLT_NO_COLUMN)) {
        ogk_real_t f[NX];
        uint32_t i;
        if (!ogk_i_blt_rhs(&ctx->cfg.model, seg, tau, y, f, NULL)) {
            ev->bad_rhs = true;
        }
        for (i = 0u; i < NX; ++i) {
            y[NX + ((size_t)ctx->slot[ct] * NX) + i] += sign * f[i];
        }
    }
}

/* Carries exactly the columns of the anchor's free components (unit vectors). */
static void init_sens(ogk_blt_t *ctx, ogk_real_t *y, bool sens, const uint32_t *cols, uint32_t ncols)
{
    if (sens) {
        uint32_t i;
        for (i = 0u; i < ctx->n_unknowns; ++i) {
            ctx->slot[i] = OGK_BLT_NO_COLUMN;
        }
        ctx->n_live = 0u;
        for (i = 0u; i < ncols; ++i) {
            if (cols[i] != OGK_BLT_NO_COLUMN) {
                blt_activate(ctx, y, cols[i]);
                y[NX + ((size_t)ctx->slot[cols[i]] * NX) + i] = OGK_R(1.0);
            }
        }
    }
}

/* Entry (i, col) of the carried sensitivities s (slots as in slot[]). */
static ogk_real_t sens_at(const ogk_real_t *s, const uint32_t *slot, uint32_t i, uint32_t col)
{
    return (slot[col] == OGK_BLT_NO_COLUMN) ? OGK_R(0.0) : s[((size_t)slot[col] * NX) + i];
}

void ogk_i_blt_errors(ogk_blt_t *ctx, const ogk_blt_transfer_t *tr, ogk_real_t *e, ogk_real_t *sens, ogk_i_blt_eval_t *ev) /* NOLINT(bugprone-easily-swappable-parameters): errors, then their sensitivities (NULL) */
{
    const ogk_blt_config_t *cfg = &ctx->cfg;
    const bool with_sens = sens != NULL;
    const uint32_t nu = ctx->n_unknowns;
    const uint32_t last = cfg->n_free_nodes;
    ogk_real_t *y = ctx->var;
    uint32_t row = 0u;
    uint32_t a;

    ev->impact = false;
    ev->bad_rhs = false;
    /* DBL_MAX, not HUGE_VAL: track_bodies replaces it by the first finite distance, and
     * no infinity is ever computed (docs/evidence/eva.md, BLT) */
    ev->min_distance[0] = OGK_REAL_MAX;
    ev->min_distance[1] = OGK_REAL_MAX;
    for (a = 0u; (a <= last) && !ev->impact && !ev->bad_rhs; ++a) {
        const uint32_t lo = ctx->anchor[a];
        const uint32_t hi = ctx->anchor[a + 1u];
        const uint32_t meet = cfg->meet_interface[a];
        ogk_real_t x_fwd[NX];
        uint32_t k;
        uint32_t i;
        uint32_t c;

        /* forward from the left anchor to the meeting interface */
        if (a == 0u) {
            (void)memcpy(y, tr->x0, sizeof(ogk_real_t) * NX);
            init_sens(ctx, y, with_sens, ctx->col_start, NX);
        } else {
            (void)memcpy(y, tr->node[a - 1u], sizeof(ogk_real_t) * NX);
            init_sens(ctx, y, with_sens, ctx->col_node[a - 1u], NX);
        }
        track_bodies(&cfg->model, y, ev);
        for (k = lo; (k < meet) && !ev->impact && !ev->bad_rhs; ++k) {
            ogk_i_blt_seg_t seg;
            ogk_i_blt_segment(cfg, tr, k, &seg);
            if (with_sens) {
                blt_activate_segment(ctx, y, k);
            }
            prop_segment(ctx, &seg, k, tr->seg[k][6], steps_of(ctx, tr, k), false, y, with_sens ? ctx->n_live : 0u, ev);
            duration_jump(ctx, &seg, k, tr->seg[k][6], y, with_sens, OGK_R(1.0), ev);
        }
        (void)memcpy(x_fwd, y, sizeof(x_fwd));
        if (with_sens) {
            (void)memcpy(ctx->s_fwd, &y[NX], sizeof(ogk_real_t) * NX * ctx->n_live);
            (void)memcpy(ctx->slot_fwd, ctx->slot, sizeof(uint32_t) * nu);
        }
        if ((meet == hi) && (a == last)) {
            /* eq. (65): the target's constrained components */
            for (i = 0u; i < NX; ++i) {
                if (((cfg->target_mask >> i) & 1u) != 0u) {
                    e[row] = x_fwd[i] - tr->xf[i];
                    if (with_sens) {
                        for (c = 0u; c < nu; ++c) {
                            sens[(row * nu) + c] = sens_at(ctx->s_fwd, ctx->slot_fwd, i, c);
                        }
                    }
                    ++row;
                }
            }
        } else {
            /* backward from the right anchor to the meeting interface (eq. 70) */
            if (a == last) {
                (void)memcpy(y, tr->xf, sizeof(ogk_real_t) * NX);
                init_sens(ctx, y, with_sens, ctx->col_node[0], 0u);
            } else {
                (void)memcpy(y, tr->node[a], sizeof(ogk_real_t) * NX);
                init_sens(ctx, y, with_sens, ctx->col_node[a], NX);
            }
            for (k = hi; (k > meet) && !ev->impact && !ev->bad_rhs; --k) {
                ogk_i_blt_seg_t seg;
                ogk_i_blt_segment(cfg, tr, k - 1u, &seg);
                if (with_sens) {
                    blt_activate_segment(ctx, y, k - 1u);
                }
                duration_jump(ctx, &seg, k - 1u, tr->seg[k - 1u][6], y, with_sens, -OGK_R(1.0), ev);
                prop_segment(ctx, &seg, k - 1u, tr->seg[k - 1u][6], steps_of(ctx, tr, k - 1u), true, y,
                             with_sens ? ctx->n_live : 0u, ev);
            }
            for (i = 0u; i < NX; ++i) {
                e[row] = x_fwd[i] - y[i];
                if (with_sens) {
                    for (c = 0u; c < nu; ++c) {
                        sens[(row * nu) + c] = sens_at(ctx->s_fwd, ctx->slot_fwd, i, c) - sens_at(&y[NX], ctx->slot, i, c);
                    }
                }
                ++row;
            }
        }
    }
}

void ogk_i_blt_chain(ogk_blt_t *ctx, const ogk_blt_transfer_t *tr, ogk_real_t x_end[OGK_BLT_NX], ogk_i_blt_eval_t *ev)
{
    const ogk_blt_config_t *cfg = &ctx->cfg;
    ogk_real_t *y = ctx->var;
    uint32_t k;

    ev->impact = false;
    ev->bad_rhs = false;
    /* DBL_MAX, not HUGE_VAL: track_bodies replaces it by the first finite distance, and
     * no infinity is ever computed (docs/evidence/eva.md, BLT) */
    ev->min_distance[0] = OGK_REAL_MAX;
    ev->min_distance[1] = OGK_REAL_MAX;
    (void)memcpy(y, tr->x0, sizeof(ogk_real_t) * NX);
    track_bodies(&cfg->model, y, ev);
    for (k = 0u; (k < cfg->n_segments) && !ev->impact && !ev->bad_rhs; ++k) {
        ogk_i_blt_seg_t seg;
        ogk_i_blt_segment(cfg, tr, k, &seg);
        prop_segment(ctx, &seg, k, tr->seg[k][6], steps_of(ctx, tr, k), false, y, 0u, ev);
    }
    (void)memcpy(x_end, y, sizeof(ogk_real_t) * NX);
}
