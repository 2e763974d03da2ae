/* oi_pil.c -- the orbit-injection flight program on the PIL link (docs/guides/pil.md): the host's truth
 * model sends the navigation and attitude state at every control tick, the program answers with
 * the tick's commands from ogk_oi_flight_tick (oi_flight.c), which is the flight software itself.
 *
 * Frames (payloads of binary64 values, ogk_pil.h for the common ones; a single-precision build
 * converts each value to ogk_real_t here, OGK_PIL_REAL, and each reply value back, (double)):
 *   OI_INIT  (32) host -> target: nothing; reply: [action, t_f* s]
 *   OI_TICK  (33) host -> target: [k, t s, r m, xi rad, phi rad, v_r, v_t, v_n m/s,
 *                                  psi, theta, phi_roll rad, p, q, r rad/s]
 *                 reply: [failure, t_predicted s, t_cutoff s, alpha, beta rad, M_xc N m,
 *                         delta_yc, delta_zc, psi_c, theta_c rad, engaged, sampled]
 *   RUN_END  (16) the run's stack per entry point (ogk_pil.h). */
#include <math.h>
#include <string.h>

#include "ogk_nog_bundle.h"
#include "ogk_pil.h"
#include "oi_flight.h"

#define OI_INIT 32u
#define OI_TICK 33u
#define OI_TICK_IN 14u
#define OI_TICK_OUT 12u

ogk_pil_stack_t ogk_pil_probe;
static ogk_oi_flight_t g_flight;

static int handle(uint16_t type, const uint8_t *in, uint16_t length, uint16_t *reply_type,
                  uint8_t *out, uint16_t *reply_length)
{
    double v[OI_TICK_IN];
    double r[OI_TICK_OUT];
    if (type == OI_INIT) {
        const ogk_flight_action a = ogk_oi_flight_init(&g_flight, ogk_nog_bundle,
                                                       ogk_nog_bundle_len);
        r[0] = (double)a;
        r[1] = (double)g_flight.base.table.t_f_star_s;
        ogk_pil_put_f64s(out, r, 2u);
        *reply_type = OI_INIT;
        *reply_length = 16u;
        return 0;
    }
    if (type == OI_TICK && length == 8u * OI_TICK_IN) {
        ogk_nav_state_t nav;
        ogk_flight_att_t att;
        ogk_oi_failure fail;
        ogk_pil_get_f64s(in, v, OI_TICK_IN);
        nav.t_s = OGK_PIL_REAL(v[1]);
        nav.r_m = OGK_PIL_REAL(v[2]);
        nav.xi_rad = OGK_PIL_REAL(v[3]);
        nav.phi_rad = OGK_PIL_REAL(v[4]);
        nav.v_r_mps = OGK_PIL_REAL(v[5]);
        nav.v_t_mps = OGK_PIL_REAL(v[6]);
        nav.v_n_mps = OGK_PIL_REAL(v[7]);
        att.psi = OGK_PIL_REAL(v[8]);
        att.theta = OGK_PIL_REAL(v[9]);
        att.phi_roll = OGK_PIL_REAL(v[10]);
        att.rate_p = OGK_PIL_REAL(v[11]);
        att.rate_q = OGK_PIL_REAL(v[12]);
        att.rate_r = OGK_PIL_REAL(v[13]);
#if OGK_REAL_SINGLE
        /* the navigation's radius in two floats (the low part in double arithmetic, here at the
         * boundary only, as the other conversions) */
        g_flight.r_lo_m = (ogk_real_t)(v[2] - (double)nav.r_m);
#endif
        fail = ogk_oi_flight_tick(&g_flight, (uint32_t)v[0], &nav, &att);
        ogk_pil_tick_mark();
        r[0] = (double)fail;
        r[1] = (double)g_flight.t_predicted_s;
        r[2] = (double)g_flight.t_cutoff_s;
        r[3] = (double)g_flight.base.cmd.alpha_rad;
        r[4] = (double)g_flight.base.cmd.beta_rad;
        r[5] = (double)g_flight.base.act.m_xc;
        r[6] = (double)g_flight.base.act.delta_yc;
        r[7] = (double)g_flight.base.act.delta_zc;
        r[8] = (double)g_flight.base.act.psi_c;
        r[9] = (double)g_flight.base.act.theta_c;
        r[10] = (double)g_flight.engaged;
        r[11] = (double)g_flight.sampled;
        ogk_pil_put_f64s(out, r, OI_TICK_OUT);
        *reply_type = OI_TICK;
        *reply_length = (uint16_t)(8u * OI_TICK_OUT);
        return 0;
    }
    return OGK_PIL_UNKNOWN;   /* an unknown frame or a wrong length: the loop answers ERROR 255 */
}

int main(void)
{
    return ogk_pil_serve(handle, &ogk_pil_probe, OGK_OI_N_ENTRIES);
}
