/* blt_pil.c -- the binary-asteroid BLT flight program on the PIL link (docs/guides/pil.md,
 * docs/guides/flight-integration-blt.md): the host sends each corrector call (a guess, or a new
 * configuration), the program makes it with blt_flight.c, which is the flight software itself,
 * and answers its outputs. The host keeps the truth, the dispersions, the DOP853 check and the
 * judging.
 *
 * Frames (payloads of binary64 values; the structs flattened in declaration order, arrays at
 * their full compile-time length; integers as exact doubles):
 *   BLT_INIT  (32) host -> target: [slot]: configure context `slot` from the generated flight
 *                  configuration (ogk_blt_flight_config.h, slot order nrpc, lm, hybrid)
 *                  reply: [action, status]
 *   BLT_LOAD  (33) host -> target: [slot, ogk_blt_config_t (BLT_CFG_N values)]: an uplinked
 *                  configuration (the ground's continuation re-scales the model per solve)
 *                  reply: [action, status]
 *   BLT_SOLVE (34) host -> target: [slot, ogk_blt_transfer_t (BLT_TR_N values)]: one correction
 *                  reply: [status, action, ogk_blt_report_t (BLT_REP_N), ogk_blt_transfer_t]
 *   RUN_END   (16) the run's stack per entry point (ogk_pil.h). */
#include <math.h>
#include <string.h>

#include "blt_flight.h"
#include "ogk_blt_flight_config.h"
#include "ogk_pil.h"

#define BLT_INIT 32u
#define BLT_LOAD 33u
#define BLT_SOLVE 34u

#define BLT_MS OGK_BLT_MAX_SEGMENTS
#define BLT_MF OGK_BLT_MAX_FREE_NODES
/* values of a flattened ogk_blt_config_t, ogk_blt_transfer_t, ogk_blt_report_t */
#define BLT_CFG_N (16u + 1u + 2u * BLT_MS + 1u + BLT_MF + OGK_BLT_MAX_ARCS + 4u + 2u + 1u + 1u + 2u + 3u + 1u + 2u + 1u)
#define BLT_TR_N (2u + 2u * OGK_BLT_NX + BLT_MS * OGK_BLT_NP + BLT_MF * OGK_BLT_NX)
#define BLT_REP_N (7u + OGK_BLT_MAX_ERRORS + 3u + 2u)
#define BLT_MAX_IN (1u + BLT_CFG_N + BLT_TR_N)
#define BLT_SOLVE_OUT (2u + BLT_REP_N + BLT_TR_N)

#if BLT_SOLVE_OUT > 128u || (1u + BLT_CFG_N) > 128u || (1u + BLT_TR_N) > 128u
#error "a BLT frame exceeds the link's 128 values: raise OGK_LINK payload or shrink the limits"
#endif

ogk_pil_stack_t ogk_pil_probe;
static ogk_blt_flight_t g_flight;
static ogk_blt_config_t g_uplink;        /* the last uplinked configuration */
static ogk_blt_transfer_t g_guess;

/* ------------------------------------------------------------------ flattening */
typedef struct {
    const double *v;
    unsigned i;
    int bad;                             /* an integer field that is not an exact uint32 */
} reader_t;

/* The frame's double, unconverted (integer fields: exact in binary64, not always in binary32). */
static double rd_f64(reader_t *r)
{
    double x = r->v[r->i];
    r->i++;
    return x;
}

/* A real field: the program's precision boundary (ogk_pil.h), a float kernel's value rounded here. */
static ogk_real_t rd(reader_t *r)
{
    return OGK_PIL_REAL(rd_f64(r));
}

static uint32_t rd_u32(reader_t *r)
{
    const double x = rd_f64(r);
    if (!(x >= 0.0 && x <= 4294967295.0) || floor(x) != x) {
        r->bad = 1;
        return 0u;
    }
    return (uint32_t)x;
}

static void rd_f64s(reader_t *r, ogk_real_t *dst, unsigned n)
{
    unsigned k;
    for (k = 0u; k < n; k++) {
        dst[k] = rd(r);
    }
}

static void rd_u32s(reader_t *r, uint32_t *dst, unsigned n)
{
    unsigned k;
    for (k = 0u; k < n; k++) {
        dst[k] = rd_u32(r);
    }
}

static int config_from(const double *v, ogk_blt_config_t *c)
{
    reader_t r;
    ogk_blt_model_t *m = &c->model;
    r.v = v;
    r.i = 0u;
    r.bad = 0;
    m->mu = rd(&r);
    rd_f64s(&r, m->body_radius, 2u);
    rd_f64s(&r, m->ref_radius, 2u);
    rd_f64s(&r, m->c20, 2u);
    rd_f64s(&r, m->c22, 2u);
    m->srp_accel = rd(&r);
    m->sun_angle0 = rd(&r);
    m->sun_rate = rd(&r);
    m->sun_tidal = rd(&r);
    m->thrust_accel = rd(&r);
    m->mass_flow = rd(&r);
    m->step_max = rd(&r);
    c->n_segments = rd_u32(&r);
    rd_u32s(&r, c->segment_kind, BLT_MS);
    rd_u32s(&r, c->segment_free, BLT_MS);
    c->n_free_nodes = rd_u32(&r);
    rd_u32s(&r, c->free_node_interface, BLT_MF);
    rd_u32s(&r, c->meet_interface, OGK_BLT_MAX_ARCS);
    c->start_free_mask = rd_u32(&r);
    c->target_mask = rd_u32(&r);
    c->corrector = rd_u32(&r);
    c->jacobian = rd_u32(&r);
    c->fd_step = rd(&r);
    c->tol = rd(&r);
    c->max_iter = rd_u32(&r);
    c->ls_factor = rd(&r);
    c->ls_trials = rd_u32(&r);
    c->impact_halvings = rd_u32(&r);
    c->lm_lambda0 = rd(&r);
    c->lm_up = rd(&r);
    c->lm_down = rd(&r);
    c->lm_trials = rd_u32(&r);
    c->burn_time_min = rd(&r);
    c->time_max = rd(&r);
    c->normalise_ab = rd_u32(&r);
    return (r.bad == 0 && r.i == BLT_CFG_N) ? 0 : -1;
}

static void transfer_from(const double *v, ogk_blt_transfer_t *t)
{
    reader_t r;
    unsigned k;
    r.v = v;
    r.i = 0u;
    r.bad = 0;
    t->t0 = rd(&r);
    t->mass0 = rd(&r);
    rd_f64s(&r, t->x0, OGK_BLT_NX);
    rd_f64s(&r, t->xf, OGK_BLT_NX);
    for (k = 0u; k < BLT_MS; k++) {
        rd_f64s(&r, t->seg[k], OGK_BLT_NP);
    }
    for (k = 0u; k < BLT_MF; k++) {
        rd_f64s(&r, t->node[k], OGK_BLT_NX);
    }
}

static unsigned put_f64s(double *dst, unsigned at, const ogk_real_t *src, unsigned n)
{
    unsigned k;
    for (k = 0u; k < n; k++) {
        dst[at + k] = (double)src[k];
    }
    return at + n;
}

static unsigned transfer_to(const ogk_blt_transfer_t *t, double *o, unsigned at)
{
    unsigned k;
    o[at] = (double)t->t0;
    o[at + 1u] = (double)t->mass0;
    at = put_f64s(o, at + 2u, t->x0, OGK_BLT_NX);
    at = put_f64s(o, at, t->xf, OGK_BLT_NX);
    for (k = 0u; k < BLT_MS; k++) {
        at = put_f64s(o, at, t->seg[k], OGK_BLT_NP);
    }
    for (k = 0u; k < BLT_MF; k++) {
        at = put_f64s(o, at, t->node[k], OGK_BLT_NX);
    }
    return at;
}

static unsigned report_to(const ogk_blt_report_t *p, double *o, unsigned at)
{
    o[at] = (double)p->flags;
    o[at + 1u] = (double)p->iterations;
    o[at + 2u] = (double)p->propagations;
    o[at + 3u] = (double)p->n_unknowns;
    o[at + 4u] = (double)p->n_errors;
    o[at + 5u] = (double)p->err_norm0;
    o[at + 6u] = (double)p->err_norm;
    at = put_f64s(o, at + 7u, p->err, OGK_BLT_MAX_ERRORS);
    o[at] = (double)p->burn_time;
    o[at + 1u] = (double)p->flight_time;
    o[at + 2u] = (double)p->mass_final;
    return put_f64s(o, at + 3u, p->min_distance, 2u);
}

/* ------------------------------------------------------------------ link handler */
static int handle(uint16_t type, const uint8_t *in, uint16_t length, uint16_t *reply_type,
                  uint8_t *out, uint16_t *reply_length)
{
    static double v[BLT_MAX_IN];
    static double r[BLT_SOLVE_OUT];
    uint32_t slot;
    unsigned n = (unsigned)length / 8u;
    if (length % 8u != 0u || n < 1u || n > BLT_MAX_IN) {
        return OGK_PIL_UNKNOWN;   /* unknown frame, wrong length or bad slot */
    }
    ogk_pil_get_f64s(in, v, n);
    if (!(v[0] >= 0.0 && v[0] < (double)OGK_BLT_FLIGHT_N_SLOTS)) {
        return OGK_PIL_UNKNOWN;   /* unknown frame, wrong length or bad slot */
    }
    slot = (uint32_t)v[0];
    if (type == BLT_INIT && n == 1u) {
        r[0] = (double)ogk_blt_flight_init(&g_flight, slot, &ogk_blt_flight_configs[slot]);
        r[1] = (double)g_flight.status[OGK_BLT_FLIGHT_INIT];
        ogk_pil_tick_mark();
    } else if (type == BLT_LOAD && n == 1u + BLT_CFG_N) {
        memset(&g_uplink, 0, sizeof g_uplink);
        if (config_from(&v[1], &g_uplink) != 0) {
            /* an integer field that is no uint32: refused before the kernel sees it */
            g_flight.ready[slot] = 0u;
            r[0] = (double)OGK_BLT_FLIGHT_ABORT;
            r[1] = (double)OGK_E_RANGE;
        } else {
            r[0] = (double)ogk_blt_flight_init(&g_flight, slot, &g_uplink);
            r[1] = (double)g_flight.status[OGK_BLT_FLIGHT_INIT];
        }
        ogk_pil_tick_mark();
    } else if (type == BLT_SOLVE && n == 1u + BLT_TR_N) {
        ogk_blt_flight_action a;
        unsigned at;
        transfer_from(&v[1], &g_guess);
        a = ogk_blt_flight_correct(&g_flight, slot, &g_guess);
        ogk_pil_tick_mark();
        r[0] = (double)g_flight.status[OGK_BLT_FLIGHT_SOLVE];
        r[1] = (double)a;
        at = report_to(&g_flight.report, r, 2u);
        at = transfer_to(&g_flight.solution, r, at);
        ogk_pil_put_f64s(out, r, at);
        *reply_type = BLT_SOLVE;
        *reply_length = (uint16_t)(8u * at);
        return 0;
    } else {
        return OGK_PIL_UNKNOWN;   /* unknown frame, wrong length or bad slot */
    }
    ogk_pil_put_f64s(out, r, 2u);
    *reply_type = type;
    *reply_length = 16u;
    return 0;
}

int main(void)
{
    return ogk_pil_serve(handle, &ogk_pil_probe, OGK_BLT_FLIGHT_N_ENTRIES);
}
