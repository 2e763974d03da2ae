/* fuzz_nmpc_step.c -- ogk_nmpc with configurations clamped to their valid range, then plan loads,
 * solves, replans and commands with arbitrary inputs (NaN and Inf included).
 * Input: two configuration bytes
 *   byte 0: bit 0 throttled engine, bit 1 minimum fuel, bit 2 CNCN, bit 3 solar-electric,
 *           bits 4-5 third bodies (0..2; 3 = 2 with softening), bit 6 sweep bound, bit 7 tol_obj 0;
 *   byte 1: bits 0-1 N - 1 (1..4), bit 2 rk4_steps - 1 (1..2), bits 3-4 max_iter - 1 (1..4),
 *           bit 5 min_nodes - 1, bits 6-7 doubling_max_nodes (0..3, threshold 0 when odd);
 * then the guess: one byte of horizon scale and one byte per node state and control (small
 * displacements of a phase-matched Earth-Mars guess), then up to 12 operations of one byte each
 * (op % 6: 0 solve, 1 replan, 2 command, 3 reload the guess, 4 reset, 5 get_plan); a solve or replan
 * reads (t, x) as 6 raw doubles when its op byte is >= 128, else as small displacements of the
 * plan's next node; a command reads a raw double time (op >= 128) or one byte of the horizon.
 * Oracle (ogk/nmpc.h): a rejected command is the safe command (engine off, alpha 0, SAFE); an
 * accepted one has a finite alpha, a throttle in [0, 1] and ENGINE_ON exactly when it is > 0; a
 * non-finite measured state gives OGK_E_NONFINITE and leaves the plan byte-identical; a solve or
 * replan that returns OGK_OK flies a plan starting at the measured (t, x), CONVERGED, within
 * tol_feas; the plan flown is finite, with 1..OGK_NMPC_MAX_NODES nodes and a positive horizon
 * (at |t0| up to 1e6 TU: see check_plan_sane). */
#include "fuzz_common.h"

#include <stdbool.h>

#include "nmpc_fixture.h"
#include "ogk/nmpc.h"
#include "ogk/types.h"

#define NXF OGK_NMPC_NX

static ogk_nmpc_t nm;
static ogk_nmpc_plan_t guess;
static ogk_nmpc_plan_t before;
static ogk_nmpc_plan_t after;

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static void check_plan_sane(const ogk_nmpc_t *ctx)
{
    if (ogk_nmpc_get_plan(ctx, &after) == OGK_OK) {
        size_t i;
        FZ_CHECK(after.nodes >= 1u && after.nodes <= OGK_NMPC_MAX_NODES);
        FZ_CHECK(isfinite(after.t0) && isfinite(after.horizon));
        /* a positive horizon at mission-like times; at |t| >> horizon_min / DBL_EPSILON the
         * stretch past t_f (t + horizon_min) rounds to t and a stale plan of horizon 0 (or -1 ulp)
         * is kept: finite, and the command still holds a node's control (docs/evidence/coverage.md) */
        FZ_CHECK((after.horizon > 0.0) || (fabs(after.t0) > 1.0e6));
        for (i = 0u; i < ((size_t)after.nodes + 1u) * NXF; ++i) {
            FZ_CHECK(isfinite(after.x[i]));
        }
        for (i = 0u; i < ((size_t)after.nodes + 1u) * after.nu; ++i) {
            FZ_CHECK(isfinite(after.u[i]));
        }
    }
}

static void build_guess(fz_reader_t *r, const ogk_nmpc_config_t *c, uint32_t nu)
{
    const double t_f = 6.4 * (1.0 + fz_small(r, 0.5));
    uint32_t k;
    (void)memset(&guess, 0, sizeof guess);
    guess.horizon = t_f;
    guess.nodes = c->nodes;
    guess.nu = nu;
    for (k = 0u; k <= c->nodes; ++k) {
        const double tau = (double)k / (double)c->nodes;
        const double rr = 1.0 + (c->target_radius - 1.0) * (3.0 * tau * tau - 2.0 * tau * tau * tau);
        guess.x[k * NXF + 0u] = rr * (1.0 + fz_small(r, 0.05));
        guess.x[k * NXF + 1u] = (c->target_phase0 + c->target_rate * t_f) * tau;
        guess.x[k * NXF + 2u] = (c->target_radius - 1.0) * (6.0 * tau - 6.0 * tau * tau) / t_f;
        guess.x[k * NXF + 3u] = 1.0 / sqrt(rr);
        guess.x[k * NXF + 4u] = 1.0 - 0.05 * t_f * tau;
        guess.u[k * nu] = 0.75 * 3.14159265358979323846 + fz_small(r, 1.0);
        if (nu > 1u) {
            guess.u[k * nu + 1u] = (double)fz_u8(r) / 255.0;
        }
    }
}

static void read_input(fz_reader_t *r, uint8_t op, ogk_nmpc_input_t *in)
{
    size_t i;
    if (op >= 128u) {
        in->t = fz_f64(r);
        for (i = 0u; i < NXF; ++i) {
            in->x[i] = fz_f64(r);
        }
    } else {
        ogk_nmpc_plan_t *p = &before;
        uint32_t k = 0u;
        if (ogk_nmpc_get_plan(&nm, p) != OGK_OK) {
            p = &guess;
        }
        k = (p->nodes > 1u) ? 1u : 0u;
        in->t = p->t0 + p->horizon * (double)k / (double)p->nodes + fz_small(r, 0.05);
        for (i = 0u; i < NXF; ++i) {
            in->x[i] = p->x[k * NXF + i] * (1.0 + fz_small(r, 0.01));
        }
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fz_reader_t r;
    ogk_nmpc_config_t cfg;
    uint8_t m0;
    uint8_t m1;
    uint32_t nu;
    int ops = 0;
    r.p = data;
    r.n = size;
    m0 = fz_u8(&r);
    m1 = fz_u8(&r);
    /* Earth to Mars, normalised (docs/design/nmpc.md; tests/unit/nmpc_fixture.h) */
    nmpc_fx_mars(&cfg, 30u);
    cfg.engine = ((m0 & 0x01u) != 0u) ? OGK_NMPC_ENGINE_THROTTLED : OGK_NMPC_ENGINE_CONSTANT;
    cfg.objective = ((m0 & 0x02u) != 0u) ? OGK_NMPC_MIN_FUEL : OGK_NMPC_MIN_TIME;
    cfg.strategy = ((m0 & 0x04u) != 0u) ? OGK_NMPC_CNCN : OGK_NMPC_SNNS;
    if ((m0 & 0x08u) != 0u) {
        nmpc_fx_solar(&cfg, 1.0, 0.05);
    }
    cfg.n_bodies = ((m0 >> 4) & 0x03u) > 2u ? 2u : ((m0 >> 4) & 0x03u);
    nmpc_fx_body(&cfg, 0u, 3.0e-6, 1.0, 0.0, 1.0);
    nmpc_fx_body(&cfg, 1u, 3.2e-7, 1.52, 2.27, 0.53);
    if (((m0 >> 4) & 0x03u) == 3u) {
        cfg.body_softening[0] = 0.006;
        cfg.body_softening[1] = 0.004;
    }
    cfg.max_sweep = ((m0 & 0x40u) != 0u) ? 1.0 : 0.0;
    cfg.tol_obj = ((m0 & 0x80u) != 0u) ? 0.0 : cfg.tol_obj;
    cfg.nodes = 1u + (m1 & 0x03u);
    cfg.rk4_steps = 1u + ((m1 >> 2) & 0x01u);
    cfg.max_iter = 1u + ((m1 >> 3) & 0x03u);
    cfg.max_iter_cold = 1u + ((m1 >> 3) & 0x03u);
    cfg.min_nodes = 1u + ((m1 >> 5) & 0x01u);
    cfg.doubling_max_nodes = (m1 >> 6) & 0x03u;
    cfg.doubling_threshold = ((cfg.doubling_max_nodes & 1u) != 0u) ? 0.0 : 0.01;
    FZ_CHECK(ogk_nmpc_init(&nm, &cfg) == OGK_OK);
    nu = (cfg.engine == OGK_NMPC_ENGINE_THROTTLED) ? 2u : 1u;
    build_guess(&r, &cfg, nu);
    (void)ogk_nmpc_load_plan(&nm, &guess);
    check_plan_sane(&nm);

    while ((r.n > 0u) && (ops < 12)) {
        const uint8_t op = fz_u8(&r);
        ogk_nmpc_input_t in;
        ogk_nmpc_report_t rep;
        ogk_nmpc_command_t cmd;
        ogk_status st;
        ++ops;
        switch (op % 6u) {
        case 0u:
        case 1u: {
            const int had_plan = (ogk_nmpc_get_plan(&nm, &before) == OGK_OK);
            bool finite_in;
            size_t i;
            read_input(&r, op, &in);
            finite_in = isfinite(in.t);
            for (i = 0u; i < NXF; ++i) {
                finite_in = finite_in && isfinite(in.x[i]);
            }
            st = ((op % 6u) == 0u) ? ogk_nmpc_solve(&nm, &in, &rep) : ogk_nmpc_replan(&nm, &in, &rep);
            if (!finite_in) {
                FZ_CHECK(st == OGK_E_NONFINITE);
            }
            if (!finite_in || !had_plan) {
                FZ_CHECK(st != OGK_OK);
                if (had_plan) {
                    FZ_CHECK(ogk_nmpc_get_plan(&nm, &after) == OGK_OK);
                    FZ_CHECK(memcmp(&before, &after, sizeof before) == 0);
                }
            }
            if (st == OGK_OK) {
                FZ_CHECK(ogk_nmpc_get_plan(&nm, &after) == OGK_OK);
                FZ_CHECK((rep.flags & OGK_NMPC_FLAG_CONVERGED) != 0u);
                FZ_CHECK(rep.solve_status == OGK_OK);
                FZ_CHECK(rep.feas <= cfg.tol_feas);
                FZ_CHECK(after.t0 == in.t);
                FZ_CHECK(memcmp(after.x, in.x, sizeof in.x) == 0);
                FZ_CHECK(rep.nodes == after.nodes);
                FZ_CHECK(rep.t_f == after.t0 + after.horizon);
            }
            break;
        }
        case 2u: {
            double t;
            if (op >= 128u) {
                t = fz_f64(&r);
            } else {
                t = (ogk_nmpc_get_plan(&nm, &before) == OGK_OK)
                    ? before.t0 + before.horizon * ((double)fz_u8(&r) / 200.0) : 0.0;
            }
            st = ogk_nmpc_command(&nm, t, &cmd);
            if (st != OGK_OK) {
                FZ_CHECK(cmd.flags == OGK_THRUST_FLAG_SAFE);
                FZ_CHECK(cmd.alpha == 0.0 && cmd.throttle == 0.0 && cmd.law_flags == 0u);
                FZ_CHECK(!isfinite(t) || ogk_nmpc_get_plan(&nm, &before) != OGK_OK);
            } else {
                FZ_CHECK(isfinite(cmd.alpha));
                FZ_CHECK(cmd.throttle >= 0.0 && cmd.throttle <= 1.0);
                FZ_CHECK(((cmd.flags & OGK_THRUST_FLAG_ENGINE_ON) != 0u) == (cmd.throttle > 0.0));
                FZ_CHECK(((cmd.flags & OGK_THRUST_FLAG_SAFE) != 0u)
                         == ((cmd.law_flags & OGK_NMPC_FLAG_STALE) != 0u));
            }
            break;
        }
        case 3u:
            (void)ogk_nmpc_load_plan(&nm, &guess);
            break;
        case 4u:
            FZ_CHECK(ogk_nmpc_reset(&nm) == OGK_OK);
            FZ_CHECK(ogk_nmpc_get_plan(&nm, &after) == OGK_E_RANGE);
            break;
        default:
            (void)ogk_nmpc_get_plan(&nm, &after);
            break;
        }
        check_plan_sane(&nm);
    }
    return 0;
}
