/* fuzz_cpd_step.c -- ogk_cpd_step (and ogk_cpd_input_from_thrust_cmd) with arbitrary inputs.
 * Input: one set-up byte (bit 0: feed-forward on; bits 1-2: pointing mode), then up to 32 steps of
 * 10 raw doubles (psi, theta, phi_roll, p, q, r, alpha_c, beta_c, xi, phi); a step whose first
 * byte is odd is taken near level flight instead (one-byte angles and rates).
 * Oracle (cpd.h): on OGK_OK every output is finite and within its limits (|m_xc| <= m_xc_max,
 * |delta_yc| <= delta_yc_max, |delta_zc| <= delta_zc_max, theta_c in [-pi/2, pi/2], psi_c in
 * (-pi, pi]); otherwise out is the safe command (zeros, OGK_CPD_FLAG_SAFE); the context stays
 * usable. */
#include "fuzz_common.h"

#include "ogk/cpd.h"

static ogk_cpd_t cpd;

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fz_reader_t r;
    ogk_cpd_config_t cfg;
    uint8_t setup;
    int steps = 0;
    r.p = data;
    r.n = size;
    setup = fz_u8(&r);
    FZ_CHECK(ogk_cpd_config_default(&cfg) == OGK_OK);
    if ((setup & 1u) != 0u) {
        cfg.ff_period_s = 0.1;
        cfg.ff_rate_max = 0.2;
    }
    if ((setup & 6u) != 0u) {
        cfg.pointing = (ogk_cpd_pointing_t)(((setup >> 1) & 3u) - 1u); /* 0, 1, 2 (unknown) */
    }
    if (ogk_cpd_init(&cpd, &cfg) != OGK_OK) {
        return 0;
    }
    while (r.n > 0u && steps < 32) {
        ogk_cpd_input_t in;
        ogk_cpd_output_t out;
        ogk_status st;
        ++steps;
        if ((r.p[0] & 1u) != 0u) {
            (void)fz_u8(&r);
            in.psi = fz_small(&r, 3.2);
            in.theta = fz_small(&r, 1.6);
            in.phi_roll = fz_small(&r, 3.2);
            in.rate_p = fz_small(&r, 0.5);
            in.rate_q = fz_small(&r, 0.5);
            in.rate_r = fz_small(&r, 0.5);
            in.alpha_c = fz_small(&r, 3.2);
            in.beta_c = fz_small(&r, 1.6);
            in.xi = fz_small(&r, 3.2);
            in.phi = fz_small(&r, 1.6);
        } else {
            in.psi = fz_f64(&r);
            in.theta = fz_f64(&r);
            in.phi_roll = fz_f64(&r);
            in.rate_p = fz_f64(&r);
            in.rate_q = fz_f64(&r);
            in.rate_r = fz_f64(&r);
            in.alpha_c = fz_f64(&r);
            in.beta_c = fz_f64(&r);
            in.xi = fz_f64(&r);
            in.phi = fz_f64(&r);
        }
        if ((steps & 7) == 0) {
            ogk_thrust_cmd_t cmd;
            ogk_nav_state_t nav;
            memset(&cmd, 0, sizeof cmd);
            memset(&nav, 0, sizeof nav);
            cmd.alpha_rad = in.alpha_c;
            cmd.beta_rad = in.beta_c;
            nav.xi_rad = in.xi;
            nav.phi_rad = in.phi;
            st = ogk_cpd_input_from_thrust_cmd(&in, &cmd, &nav);
            FZ_CHECK(st == OGK_OK || st == OGK_E_NONFINITE);
        }
        memset(&out, 0x5A, sizeof out);
        st = ogk_cpd_step(&cpd, &in, &out);
        if (st == OGK_OK) {
            FZ_CHECK(isfinite(out.m_xc) && isfinite(out.delta_yc) && isfinite(out.delta_zc) &&
                     isfinite(out.psi_c) && isfinite(out.theta_c) && isfinite(out.phi_c) &&
                     isfinite(out.err_x) && isfinite(out.err_y) && isfinite(out.err_z));
            FZ_CHECK(fabs(out.m_xc) <= cfg.m_xc_max);
            FZ_CHECK(fabs(out.delta_yc) <= cfg.delta_yc_max);
            FZ_CHECK(fabs(out.delta_zc) <= cfg.delta_zc_max);
            FZ_CHECK(out.theta_c >= -1.5707963267948966 && out.theta_c <= 1.5707963267948966);
            FZ_CHECK(out.psi_c > -3.141592653589794 && out.psi_c <= 3.141592653589794);
            FZ_CHECK((out.flags & OGK_CPD_FLAG_SAFE) == 0u);
        } else {
            FZ_CHECK(st == OGK_E_NONFINITE || st == OGK_E_RANGE);
            FZ_CHECK(out.m_xc == 0.0 && out.delta_yc == 0.0 && out.delta_zc == 0.0);
            FZ_CHECK((out.flags & OGK_CPD_FLAG_SAFE) != 0u);
        }
    }
    FZ_CHECK(ogk_cpd_reset(&cpd) == OGK_OK);
    return 0;
}
