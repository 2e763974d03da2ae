/* nmpc_pil.c -- the rendezvous NMPC flight program on the PIL link (docs/guides/flight-integration-nmpc.md):
 * the host's closed loop sends the measured state at every replan time, the program re-solves with
 * ogk_nmpc_flight_step (nmpc_flight.c), which is the flight software itself, and answers the
 * report, the command at the replan time and the plan flown (its controls; the node states on
 * request, from the copy the step made: no kernel call).
 *
 * Frames (payloads of binary64 values, ogk_pil.h for the common ones):
 *   NMPC_INIT   (32) host -> target: nothing; reply: [action, nu, guesses]
 *   NMPC_REPLAN (33) host -> target: [t TU, r LU, theta rad, v_r, v_theta LU/TU, m MU]
 *                    reply: [action, status, flags, sqp_iterations, solves, nodes, t_next TU,
 *                            t_f TU, objective, cmd alpha rad, cmd throttle, cmd flags,
 *                            cmd law_flags, cmd status, plan t0 TU, plan horizon TU, plan nodes,
 *                            plan nu, plan status, pre_iterations, guesses tried,
 *                            the step's solves, the step's failed solve calls,
 *                            controls ((nodes + 1) x nu, row-major), lambda (4)]
 *   NMPC_PLAN_X (34) host -> target: [first row]; reply: node states of rows first ..
 *                    min(first + 25, nodes + 1) - 1 (5 each, row-major)
 *   RUN_END     (16) the run's stack per entry point (ogk_pil.h). */
#include <string.h>

#include "nmpc_flight.h"
#include "ogk_pil.h"

#define NMPC_INIT 32u
#define NMPC_REPLAN 33u
#define NMPC_PLAN_X 34u
#define NMPC_HEAD 23u                   /* reply values before the controls */
#define NMPC_ROWS_PER_FRAME 25u         /* node states per NMPC_PLAN_X reply (125 values) */
#define NMPC_MAX_OUT (OGK_LINK_MAX_PAYLOAD / 8u)

ogk_pil_stack_t ogk_pil_probe;
static ogk_nmpc_flight_t g_flight;
static ogk_real_t g_out[NMPC_MAX_OUT];   /* the reply: its values widened to binary64 as sent */

static uint16_t replan_reply(const ogk_nmpc_flight_t *f, ogk_nmpc_action a)
{
    const uint32_t nodes = (f->plan_status == OGK_OK) ? f->plan.nodes : 0u;
    const uint32_t nu = (f->plan_status == OGK_OK) ? f->plan.nu : 0u;
    const uint32_t nc = (nodes + 1u) * nu;
    uint32_t i;
    ogk_real_t *r = g_out;
    r[0] = (ogk_real_t)a;
    r[1] = (ogk_real_t)f->status;
    r[2] = (ogk_real_t)f->rep.flags;
    r[3] = (ogk_real_t)f->rep.sqp_iterations;
    r[4] = (ogk_real_t)f->rep.solves;
    r[5] = (ogk_real_t)f->rep.nodes;
    r[6] = f->rep.t_next;
    r[7] = f->rep.t_f;
    r[8] = f->rep.objective;
    r[9] = f->cmd.alpha;
    r[10] = f->cmd.throttle;
    r[11] = (ogk_real_t)f->cmd.flags;
    r[12] = (ogk_real_t)f->cmd.law_flags;
    r[13] = (ogk_real_t)f->cmd_status;
    r[14] = f->plan.t0;
    r[15] = f->plan.horizon;
    r[16] = (ogk_real_t)nodes;
    r[17] = (ogk_real_t)nu;
    r[18] = (ogk_real_t)f->plan_status;
    r[19] = (ogk_real_t)f->pre_iterations;
    r[20] = (ogk_real_t)f->guesses_tried;
    r[21] = (ogk_real_t)f->step_solves;
    r[22] = (ogk_real_t)f->step_failed;
    for (i = 0u; (i < nc) && (i < (OGK_NMPC_MAX_NODES + 1u) * OGK_NMPC_MAX_NU); ++i) {
        r[NMPC_HEAD + i] = f->plan.u[i];
    }
    for (i = 0u; i < OGK_NMPC_NC; ++i) {
        r[NMPC_HEAD + nc + i] = f->plan.lambda[i];
    }
    return (uint16_t)(NMPC_HEAD + nc + OGK_NMPC_NC);
}

static int handle(uint16_t type, const uint8_t *in, uint16_t length, uint16_t *reply_type,
                  uint8_t *out, uint16_t *reply_length)
{
    ogk_real_t v[1u + OGK_NMPC_NX];   /* the frame's values at the kernel's precision */
    uint16_t n;
    if (type == NMPC_INIT) {
        const ogk_nmpc_action a = ogk_nmpc_flight_init(&g_flight);
        g_out[0] = (ogk_real_t)a;
        g_out[1] = (ogk_real_t)g_flight.ctx.nu;
        g_out[2] = (ogk_real_t)g_flight.n_guesses;
        n = 3u;
    } else if (type == NMPC_REPLAN && length == 8u * (1u + OGK_NMPC_NX)) {
        ogk_nmpc_input_t meas;
        ogk_nmpc_action a;
        uint32_t i;
        ogk_pil_get_reals(in, v, 1u + OGK_NMPC_NX);
        meas.t = v[0];
        for (i = 0u; i < OGK_NMPC_NX; ++i) {
            meas.x[i] = v[1u + i];
        }
        a = ogk_nmpc_flight_step(&g_flight, &meas);
        ogk_pil_tick_mark();    /* one step = one replan (its solves, plan and command) */
        n = replan_reply(&g_flight, a);
    } else if (type == NMPC_PLAN_X && length == 8u) {
        uint32_t first;
        uint32_t rows;
        ogk_pil_get_reals(in, v, 1u);
        if (!(v[0] >= OGK_R(0.0)) || !(v[0] <= (ogk_real_t)OGK_NMPC_MAX_NODES) ||
            g_flight.plan_status != OGK_OK) {
            return OGK_PIL_UNKNOWN;   /* unknown frame or wrong length */
        }
        first = (uint32_t)v[0];
        rows = (g_flight.plan.nodes + 1u > first) ? (g_flight.plan.nodes + 1u - first) : 0u;
        rows = (rows > NMPC_ROWS_PER_FRAME) ? NMPC_ROWS_PER_FRAME : rows;
        (void)memcpy(g_out, &g_flight.plan.x[first * OGK_NMPC_NX],
                     sizeof(ogk_real_t) * rows * OGK_NMPC_NX);
        n = (uint16_t)(rows * OGK_NMPC_NX);
    } else {
        return OGK_PIL_UNKNOWN;   /* unknown frame or wrong length */
    }
    ogk_pil_put_reals(out, g_out, n);
    *reply_type = type;
    *reply_length = (uint16_t)(8u * n);
    return 0;
}

int main(void)
{
    return ogk_pil_serve(handle, &ogk_pil_probe, OGK_NMPC_FL_N_ENTRIES);
}
