/* mpsp_pil.c -- the MPSP re-planning flight program on the PIL link (docs/guides/pil.md,
 * docs/guides/flight-integration-mpsp.md): the host sends each run's re-planning request (the perturbed
 * initial state, thrust scale and target the SIL's run_case gives ogk_mpsp_solve), the program
 * answers with the plan from ogk_mpsp_flight_replan (mpsp_flight.c, the flight software itself) and
 * the thrust command of that plan at the requested time.
 *
 * Frames (payloads of binary64 values, ogk_pil.h for the common ones; read into and answered from
 * ogk_real_t arrays, ogk_pil_get_reals / put_reals: the program's precision boundary, counts exact):
 *   MPSP_INIT   (32) host -> target: nothing; reply: [action, n_weights, t0 TU, tf TU]
 *   MPSP_REPLAN (33) host -> target: [x0: r LU (3), v LU/TU (3), m MU, thrust_scale,
 *                                     has_target (0/1), r_f LU (3), v_f LU/TU (3), t_cmd TU]
 *                    reply: [action, status, converged, newton_iterations, inner_loops,
 *                            outer_steps, n_seg_tol, tau_reached, dy (7), err_r LU, err_v LU/TU,
 *                            lambda_mf, m_f MU, n_segments, n_thrust_arcs, n_switches, lambda_m0,
 *                            command action, throttle, u (3, inertial), flags, n_weights,
 *                            weights (n_weights)]
 *   RUN_END     (16) the run's stack per entry point (ogk_pil.h). */
#include <string.h>

#include "mpsp_flight.h"
#include "ogk_pil.h"

#define MPSP_INIT 32u
#define MPSP_REPLAN 33u
#define MPSP_REPLAN_IN 16u
#define MPSP_REPLY_HEAD 30u
#define MPSP_REPLY_MAX (MPSP_REPLY_HEAD + OGK_MPSP_MAX_WEIGHTS)

#if MPSP_REPLY_MAX * 8u > OGK_LINK_MAX_PAYLOAD
#error "the MPSP_REPLAN reply does not fit a link frame"
#endif

ogk_pil_stack_t ogk_pil_probe;
static ogk_mpsp_flight_t g_flight;   /* 187 KiB of kernel context: static storage */
static ogk_real_t g_reply[MPSP_REPLY_MAX];

static unsigned replan(const ogk_real_t *v)
{
    ogk_mpsp_flight_action a;
    ogk_mpsp_flight_action c;
    const ogk_mpsp_result_t *p = &g_flight.plan;
    size_t nw;
    size_t i;
    a = ogk_mpsp_flight_replan(&g_flight, v, v[7], (v[8] != OGK_R(0.0)) ? &v[9] : NULL);
    c = ogk_mpsp_flight_command(&g_flight, v[15]);
    g_reply[0] = (ogk_real_t)a;
    g_reply[1] = (ogk_real_t)g_flight.status[OGK_MPSP_FLIGHT_SOLVE];
    g_reply[2] = (ogk_real_t)p->converged;
    g_reply[3] = (ogk_real_t)p->newton_iterations;
    g_reply[4] = (ogk_real_t)p->inner_loops;
    g_reply[5] = (ogk_real_t)p->outer_steps;
    g_reply[6] = (ogk_real_t)p->n_seg_tol;
    g_reply[7] = p->tau_reached;
    for (i = 0u; i < OGK_MPSP_NY; ++i) {
        g_reply[8u + i] = p->dy[i];
    }
    g_reply[15] = p->err_r;
    g_reply[16] = p->err_v;
    g_reply[17] = p->lambda_mf;
    g_reply[18] = p->m_f;
    g_reply[19] = (ogk_real_t)p->n_segments;
    g_reply[20] = (ogk_real_t)p->n_thrust_arcs;
    g_reply[21] = (ogk_real_t)p->n_switches;
    g_reply[22] = p->lambda_m0;
    g_reply[23] = (ogk_real_t)c;
    g_reply[24] = g_flight.cmd.throttle;
    g_reply[25] = g_flight.cmd.u[0];
    g_reply[26] = g_flight.cmd.u[1];
    g_reply[27] = g_flight.cmd.u[2];
    g_reply[28] = (ogk_real_t)g_flight.cmd.flags;
    nw = (p->n_weights <= OGK_MPSP_MAX_WEIGHTS) ? p->n_weights : 0u;
    g_reply[29] = (ogk_real_t)nw;
    for (i = 0u; i < nw; ++i) {
        g_reply[MPSP_REPLY_HEAD + i] = p->weights[i];
    }
    return (unsigned)(MPSP_REPLY_HEAD + nw);
}

static int handle(uint16_t type, const uint8_t *in, uint16_t length, uint16_t *reply_type,
                  uint8_t *out, uint16_t *reply_length)
{
    if (type == MPSP_INIT && length == 0u) {
        const ogk_mpsp_flight_action a = ogk_mpsp_flight_init(&g_flight);
        ogk_pil_tick_mark();
        g_reply[0] = (ogk_real_t)a;
        g_reply[1] = (ogk_real_t)g_flight.mpsp.n_weights;
        g_reply[2] = g_flight.mpsp.cfg.t0;
        g_reply[3] = g_flight.mpsp.cfg.tf;
        ogk_pil_put_reals(out, g_reply, 4u);
        *reply_type = MPSP_INIT;
        *reply_length = 32u;
        return 0;
    }
    if (type == MPSP_REPLAN && length == 8u * MPSP_REPLAN_IN) {
        ogk_real_t v[MPSP_REPLAN_IN];
        unsigned n;
        ogk_pil_get_reals(in, v, MPSP_REPLAN_IN);
        n = replan(v);
        ogk_pil_tick_mark();
        ogk_pil_put_reals(out, g_reply, n);
        *reply_type = MPSP_REPLAN;
        *reply_length = (uint16_t)(8u * n);
        return 0;
    }
    return OGK_PIL_UNKNOWN;   /* an unknown frame or a wrong length: the loop answers ERROR 255 */
}

int main(void)
{
    (void)memset(&ogk_pil_probe, 0, sizeof ogk_pil_probe);
    return ogk_pil_serve(handle, &ogk_pil_probe, OGK_MPSP_FLIGHT_N_ENTRIES);
}
