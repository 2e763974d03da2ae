/* fuzz_blt_solve.c -- ogk_blt_init / _solve / _evaluate / _command with fuzzed configurations and
 * transfers (raw NaN/Inf included), their cost clamped (time_max 0.3 TU, step_max >= 0.03 TU: at
 * most 10 RK4 steps a segment; max_iter <= 2, ls_trials, lm_trials <= 3, impact_halvings <= 3: at
 * most about 3 500 RK4 steps an input, the worst case 23 unknowns by central differences).
 * Input:
 *   byte 0: bit 0 LM, bit 1 variational Jacobian, bits 2-3 layout (0 a single burn, 1 burn-coast-burn
 *           forward, 2 the same with a free node at interface 2 and the first arc meeting at 1,
 *           3 as 2 with the last arc backward from the target), bit 4 normalise_ab off, bit 5 the
 *           point-mass model (else every term of blt_fixture.h's Moshup-like one), bit 6 x0's x and
 *           vy free, bit 7 only x, y, z targeted (when the last arc meets at the end);
 *   byte 1: bit 0 max_iter - 1 (1..2), bit 1 unused, bits 2-3 ls_trials - 1, bits 4-5 impact_halvings,
 *           bits 6-7 lm_trials - 1;
 *   byte 2: bits 0-1 step_max (0.03, 0.04, 0.06, 0.1 TU), bits 2-4 tol 10^-(3 + n), bit 5 four raw
 *           model doubles follow (mu, c20[1], srp_accel, sun_tidal: init may reject them), bit 6
 *           fd_step 1e-3 (else 1e-6);
 *   then the transfer: one byte; >= 128: raw doubles for t0, mass0, x0, xf, each segment's A, B, T
 *   and the node; else blt_fixture.h's transfer with durations of 0.12-0.2 TU, displaced by one byte
 *   per parameter, its target its own end displaced, its node its own state at interface 2;
 *   then up to 4 command times (one byte: >= 128 a raw double, else a fraction of the flight).
 * Oracle (ogk/blt.h): init OK, CONFIG or NONFINITE, and a rejected context answers NOT_INIT with the
 * output = the guess; solve returns OK, NONFINITE, RANGE, NOT_CONVERGED or ITER_LIMIT; OK: CONVERGED,
 * not SAFE, |e| <= tol, the solution finite and evaluated again to the same |e|; NONFINITE / RANGE:
 * the output = the guess, flags SAFE only, no iteration; otherwise SAFE, |e| no larger than the
 * guess's, the output finite unless it is the guess; the held solution only after OK; a command is
 * OK (finite, unit direction when the engine is on, segment <= n_segments) or the safe command;
 * the guess evaluated before and after the solve gives the same report (the context's state does
 * not leak into an evaluation). */
#include "fuzz_common.h"

#include <stdbool.h>

#include "blt_fixture.h"
#include "ogk/blt.h"

#define NXB OGK_BLT_NX
#define NPB OGK_BLT_NP

static ogk_blt_t blt;
static ogk_blt_transfer_t guess;
static ogk_blt_transfer_t sol;
static ogk_blt_report_t rep;
static ogk_blt_report_t ev_before;
static ogk_blt_report_t ev_after;

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static bool transfer_finite(const ogk_blt_config_t *c, const ogk_blt_transfer_t *t)
{
    bool ok = isfinite(t->t0) && isfinite(t->mass0);
    uint32_t i;
    uint32_t k;
    for (i = 0u; i < NXB; ++i) {
        ok = ok && isfinite(t->x0[i]) && isfinite(t->xf[i]);
    }
    for (k = 0u; k < c->n_segments; ++k) {
        for (i = 0u; i < NPB; ++i) {
            ok = ok && isfinite(t->seg[k][i]);
        }
    }
    for (k = 0u; k < c->n_free_nodes; ++k) {
        for (i = 0u; i < NXB; ++i) {
            ok = ok && isfinite(t->node[k][i]);
        }
    }
    return ok;
}

static void check_safe_command(const ogk_blt_command_t *cmd)
{
    FZ_CHECK(cmd->engine_on == 0u);
    FZ_CHECK(cmd->flags == OGK_BLT_FLAG_SAFE);
    FZ_CHECK(cmd->u_hat[0] == 0.0 && cmd->u_hat[1] == 0.0 && cmd->u_hat[2] == 0.0);
}

static void build_config(fz_reader_t *r, ogk_blt_config_t *c)
{
    static const double steps[4] = {0.03, 0.04, 0.06, 0.1};
    const uint8_t m0 = fz_u8(r);
    const uint8_t m1 = fz_u8(r);
    const uint8_t m2 = fz_u8(r);
    const uint32_t layout = (m0 >> 2) & 3u;
    int i;
    if ((m0 & 0x20u) != 0u) {
        blt_fx_lyapunov_config(c); /* the point-mass Earth-Moon model */
        c->segment_kind[0] = OGK_BLT_SEG_BURN;
        c->segment_free[0] = OGK_BLT_FREE_ALL;
        c->start_free_mask = 0u;
        c->target_mask = 0x3Fu;
    } else {
        blt_fx_moshup(c);
    }
    if (layout != 0u) {
        c->n_segments = 3u;
        c->segment_kind[1] = OGK_BLT_SEG_COAST;
        c->segment_free[1] = OGK_BLT_FREE_T;
        c->meet_interface[0] = 3u;
        if (layout >= 2u) {
            c->n_free_nodes = 1u;
            c->free_node_interface[0] = 2u;
            c->meet_interface[0] = 1u;
            c->meet_interface[1] = (layout == 3u) ? 2u : 3u;
        }
    }
    c->corrector = ((m0 & 1u) != 0u) ? OGK_BLT_CORR_LM : OGK_BLT_CORR_NRPC;
    c->jacobian = ((m0 & 2u) != 0u) ? OGK_BLT_JAC_VARIATIONAL : OGK_BLT_JAC_CENTRAL;
    c->normalise_ab = ((m0 & 0x10u) != 0u) ? 0u : 1u;
    c->start_free_mask = ((m0 & 0x40u) != 0u) ? ((1u << 0) | (1u << 4)) : 0u;
    if (((m0 & 0x80u) != 0u) && (layout != 3u)) {
        c->target_mask = 0x07u;
    }
    c->max_iter = 1u + (m1 & 1u);
    c->ls_trials = 1u + ((m1 >> 2) & 3u) % 3u;
    c->impact_halvings = (m1 >> 4) & 3u;
    c->lm_trials = 1u + ((m1 >> 6) & 3u) % 3u;
    c->model.step_max = steps[m2 & 3u];
    c->tol = 1.0e-3;
    for (i = 0; i < (int)((m2 >> 2) & 7u); ++i) {
        c->tol *= 0.1;
    }
    c->fd_step = ((m2 & 0x40u) != 0u) ? 1.0e-3 : 1.0e-6;
    c->burn_time_min = 1.0e-3;
    c->time_max = 0.3;
    if ((m2 & 0x20u) != 0u) {
        c->model.mu = fz_f64(r);
        c->model.c20[1] = fz_f64(r);
        c->model.srp_accel = fz_f64(r);
        c->model.sun_tidal = fz_f64(r);
    }
}

/* blt_fixture.h's transfer shortened to the clamp, displaced; its own end as the target. */
static void build_structured(fz_reader_t *r, const ogk_blt_config_t *c)
{
    ogk_blt_config_t fwd = *c;
    ogk_blt_report_t pr;
    uint32_t i;
    uint32_t k;
    if (c->n_segments == 1u) {
        blt_fx_single_burn(&guess);
        guess.seg[0][6] = 0.2;
    } else {
        blt_fx_bcb(&guess);
        guess.seg[0][6] = 0.15;
        guess.seg[1][6] = 0.12;
        guess.seg[2][6] = 0.13;
    }
    for (i = 0u; i < NXB; ++i) {
        guess.x0[i] += fz_small(r, 0.05);
    }
    guess.mass0 = 0.5 + ((double)fz_u8(r) / 510.0);
    /* the exact transfer's end and node (the point-mass or the full model, forward) */
    fwd.n_free_nodes = 0u;
    fwd.meet_interface[0] = c->n_segments;
    fwd.target_mask = 0x3Fu;
    fwd.start_free_mask = 0u;
    if (ogk_blt_init(&blt, &fwd) == OGK_OK) {
        (void)ogk_blt_propagate(&blt, &guess, guess.xf, &pr);
        if (c->n_free_nodes > 0u) {
            fwd.n_segments = 2u;
            fwd.meet_interface[0] = 2u;
            if (ogk_blt_init(&blt, &fwd) == OGK_OK) {
                (void)ogk_blt_propagate(&blt, &guess, guess.node[0], &pr);
            }
        }
    }
    for (i = 0u; i < NXB; ++i) {
        guess.xf[i] += fz_small(r, 0.02);
    }
    for (k = 0u; k < c->n_segments; ++k) {
        for (i = 0u; i < 6u; ++i) {
            guess.seg[k][i] += fz_small(r, 0.5);
        }
        guess.seg[k][6] *= 1.0 + fz_small(r, 0.5);
    }
}

static void build_raw(fz_reader_t *r, const ogk_blt_config_t *c)
{
    uint32_t i;
    uint32_t k;
    (void)memset(&guess, 0, sizeof(guess));
    guess.t0 = fz_f64(r);
    guess.mass0 = fz_f64(r);
    for (i = 0u; i < NXB; ++i) {
        guess.x0[i] = fz_f64(r);
        guess.xf[i] = fz_f64(r);
    }
    for (k = 0u; k < c->n_segments; ++k) {
        for (i = 0u; i < NPB; ++i) {
            guess.seg[k][i] = fz_f64(r);
        }
    }
    for (i = 0u; i < NXB; ++i) {
        guess.node[0][i] = fz_f64(r);
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fz_reader_t r;
    ogk_blt_config_t cfg;
    ogk_blt_command_t cmd;
    ogk_status st_init;
    ogk_status st;
    ogk_status st_ev;
    uint8_t mode;
    int exact_guess;
    int ops = 0;
    r.p = data;
    r.n = size;
    build_config(&r, &cfg);
    mode = fz_u8(&r);
    if (mode >= 128u) {
        build_raw(&r, &cfg);
    } else {
        build_structured(&r, &cfg);
    }
    /* without normalise_ab, solve corrects the guess itself: its first |e| is evaluate's, bit for
     * bit (with it, [A; B] is scaled first, which moves the last bits and, at a grazing impact or an
     * RK4 stage exactly at A + B tau = 0, can change the verdict) */
    exact_guess = (cfg.normalise_ab == 0u) ? 1 : 0;
    st_init = ogk_blt_init(&blt, &cfg);
    FZ_CHECK(st_init == OGK_OK || st_init == OGK_E_CONFIG || st_init == OGK_E_NONFINITE);
    if (st_init != OGK_OK) {
        (void)memset(&sol, 0xA5, sizeof(sol));
        FZ_CHECK(ogk_blt_solve(&blt, &guess, &sol, &rep) == OGK_E_NOT_INIT);
        FZ_CHECK(memcmp(&sol, &guess, sizeof(sol)) == 0);
        FZ_CHECK(rep.flags == OGK_BLT_FLAG_SAFE);
        FZ_CHECK(ogk_blt_command(&blt, 0.0, &cmd) == OGK_E_NOT_INIT);
        check_safe_command(&cmd);
        return 0;
    }

    st_ev = ogk_blt_evaluate(&blt, &guess, &ev_before);
    FZ_CHECK(st_ev == OGK_OK || st_ev == OGK_E_NONFINITE || st_ev == OGK_E_RANGE || st_ev == OGK_E_NOT_CONVERGED);
    (void)memset(&sol, 0xA5, sizeof(sol));
    st = ogk_blt_solve(&blt, &guess, &sol, &rep);
    FZ_CHECK(st == OGK_OK || st == OGK_E_NONFINITE || st == OGK_E_RANGE || st == OGK_E_NOT_CONVERGED ||
             st == OGK_E_ITER_LIMIT);
    FZ_CHECK(rep.iterations <= cfg.max_iter);
    if (st == OGK_E_NONFINITE || st == OGK_E_RANGE) {
        FZ_CHECK(st_ev == st);
        FZ_CHECK(!transfer_finite(&cfg, &guess) == (st == OGK_E_NONFINITE));
        FZ_CHECK(memcmp(&sol, &guess, sizeof(sol)) == 0);
        FZ_CHECK(rep.flags == OGK_BLT_FLAG_SAFE);
        FZ_CHECK(rep.iterations == 0u);
    } else if (st == OGK_OK) {
        ogk_blt_report_t again;
        FZ_CHECK(st_ev == OGK_OK || exact_guess == 0);
        FZ_CHECK((rep.flags & OGK_BLT_FLAG_CONVERGED) != 0u);
        FZ_CHECK((rep.flags & (OGK_BLT_FLAG_SAFE | OGK_BLT_FLAG_GUESS_IMPACT)) == 0u);
        FZ_CHECK(rep.err_norm <= cfg.tol);
        FZ_CHECK(transfer_finite(&cfg, &sol));
        FZ_CHECK(ogk_blt_evaluate(&blt, &sol, &again) == OGK_OK);
        FZ_CHECK(again.err_norm == rep.err_norm);
    } else {
        FZ_CHECK(st_ev == OGK_OK || st_ev == OGK_E_NOT_CONVERGED);
        FZ_CHECK((rep.flags & OGK_BLT_FLAG_SAFE) != 0u);
        FZ_CHECK((rep.flags & OGK_BLT_FLAG_CONVERGED) == 0u);
        FZ_CHECK((st == OGK_E_ITER_LIMIT) == ((rep.flags & OGK_BLT_FLAG_ITER_LIMIT) != 0u));
        if ((rep.flags & OGK_BLT_FLAG_GUESS_IMPACT) != 0u) {
            FZ_CHECK(st_ev == OGK_E_NOT_CONVERGED || exact_guess == 0);
            FZ_CHECK(rep.iterations == 0u);
            FZ_CHECK(memcmp(&sol, &guess, sizeof(sol)) == 0);
        } else {
            FZ_CHECK(st_ev == OGK_OK || exact_guess == 0);
            FZ_CHECK(rep.err_norm <= rep.err_norm0);
            FZ_CHECK(rep.err_norm0 == ev_before.err_norm || exact_guess == 0);
            FZ_CHECK(transfer_finite(&cfg, &sol));
        }
    }
    /* the context's state (held solution, frozen steps, damping) does not leak into an evaluation */
    FZ_CHECK(ogk_blt_evaluate(&blt, &guess, &ev_after) == st_ev);
    FZ_CHECK(memcmp(ev_before.err, ev_after.err, sizeof(ev_before.err)) == 0);
    FZ_CHECK(ev_before.flags == ev_after.flags);

    while ((r.n > 0u) && (ops < 4)) {
        const uint8_t op = fz_u8(&r);
        double t;
        ogk_status sc;
        ++ops;
        if (op >= 128u) {
            t = fz_f64(&r);
        } else {
            t = sol.t0 + ((rep.flight_time * (double)op) / 100.0);
        }
        sc = ogk_blt_command(&blt, t, &cmd);
        FZ_CHECK(sc == OGK_OK || sc == OGK_E_SAFE_COMMAND || sc == OGK_E_RANGE || sc == OGK_E_NONFINITE);
        if (st != OGK_OK) {
            FZ_CHECK(sc == OGK_E_SAFE_COMMAND || sc == OGK_E_NONFINITE);
        }
        if (sc == OGK_OK) {
            FZ_CHECK(cmd.flags == 0u);
            FZ_CHECK(cmd.segment <= cfg.n_segments);
            if (cmd.engine_on != 0u) {
                const double n = sqrt((cmd.u_hat[0] * cmd.u_hat[0]) + (cmd.u_hat[1] * cmd.u_hat[1]) +
                                      (cmd.u_hat[2] * cmd.u_hat[2]));
                FZ_CHECK(cmd.segment < cfg.n_segments);
                FZ_CHECK(cfg.segment_kind[cmd.segment] == OGK_BLT_SEG_BURN);
                FZ_CHECK(fabs(n - 1.0) <= 1.0e-12);
            } else {
                FZ_CHECK(cmd.u_hat[0] == 0.0 && cmd.u_hat[1] == 0.0 && cmd.u_hat[2] == 0.0);
            }
        } else {
            check_safe_command(&cmd);
        }
    }
    FZ_CHECK(ogk_blt_reset(&blt) == OGK_OK);
    FZ_CHECK(ogk_blt_command(&blt, sol.t0, &cmd) == OGK_E_SAFE_COMMAND || !isfinite(sol.t0));
    return 0;
}
