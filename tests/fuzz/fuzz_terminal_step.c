/* fuzz_terminal_step.c -- ogk_terminal_step with arbitrary navigation inputs, predictions and law
 * commands. Input: one mode byte (bits 0-3: position-shaping gain in sixteenths, 0 = pure v_go;
 * bit 4: hold = the whole window; bit 5: 0.5 s lead; bit 6: radius only, no plane-normal shaping;
 * bit 7: the turn limit of a slow-turning vehicle, 0.2 rad/s^2), then up to 64
 * steps of 9 raw doubles (t, r, phi, v_r, v_t, v_n, t_predicted, alpha, beta); a step whose first
 * byte is odd is a plausible end-of-burn state instead (one-byte offsets).
 * Oracle (terminal.h): the output angles are finite whenever the law's are, or the context has a
 * terminal command; once engaged the output carries OGK_TERMINAL_FLAG_ENGAGED on every call; a
 * rejected call (status != OGK_OK) leaves the context byte-identical and sets OGK_THRUST_FLAG_SAFE. */
#include "fuzz_common.h"

#include "ogk/terminal.h"

static ogk_terminal_t term;

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fz_reader_t r;
    ogk_terminal_config_t cfg;
    bool engaged = false;
    int steps = 0;
    r.p = data;
    r.n = size;
    FZ_CHECK(ogk_terminal_config_default(&cfg) == OGK_OK);
    if (r.n > 0u) {
        const uint8_t mode = fz_u8(&r);
        cfg.shape_gain = (double)(mode & 0x0fu) / 15.0;
        cfg.shape_gain_normal = ((mode & 0x40u) != 0u) ? 0.0 : cfg.shape_gain;
        cfg.shape_hold_s = 0.5;
        cfg.shape_hold_s = ((mode & 0x10u) != 0u) ? cfg.window_s : cfg.shape_hold_s;
        cfg.shape_lead_s = ((mode & 0x20u) != 0u) ? 0.5 : 0.0;
        cfg.turn_accel_rad_s2 = ((mode & 0x80u) != 0u) ? 0.2 : 0.0;
    }
    FZ_CHECK(ogk_terminal_init(&term, &cfg) == OGK_OK);
    while (r.n > 0u && steps < 64) {
        ogk_nav_state_t nav;
        ogk_thrust_cmd_t law;
        ogk_thrust_cmd_t out;
        ogk_terminal_t before;
        double t_pred;
        ogk_status st;
        ++steps;
        (void)memset(&nav, 0, sizeof nav);
        (void)memset(&law, 0, sizeof law);
        if ((r.p[0] & 1u) != 0u) {
            (void)fz_u8(&r);
            nav.t_s = 100.0 + 0.02 * steps;
            nav.r_m = 42164.0e3 + fz_small(&r, 1.0e3);
            nav.phi_rad = fz_small(&r, 1.0e-5);
            nav.v_r_mps = fz_small(&r, 50.0);
            nav.v_t_mps = 3074.66 + fz_small(&r, 60.0);
            nav.v_n_mps = fz_small(&r, 50.0);
            t_pred = nav.t_s + fz_small(&r, 6.0);
            law.alpha_rad = fz_small(&r, 1.0);
            law.beta_rad = fz_small(&r, 1.0);
        } else {
            nav.t_s = fz_f64(&r);
            nav.r_m = fz_f64(&r);
            nav.phi_rad = fz_f64(&r);
            nav.v_r_mps = fz_f64(&r);
            nav.v_t_mps = fz_f64(&r);
            nav.v_n_mps = fz_f64(&r);
            t_pred = fz_f64(&r);
            law.alpha_rad = fz_f64(&r);
            law.beta_rad = fz_f64(&r);
        }
        law.flags = OGK_THRUST_FLAG_ENGINE_ON;
        before = term;
        st = ogk_terminal_step(&term, &nav, t_pred, &law, &out);
        if (st != OGK_OK) {
            FZ_CHECK(memcmp(&before, &term, sizeof term) == 0);
            FZ_CHECK((out.flags & OGK_THRUST_FLAG_SAFE) != 0u);
        }
        if ((isfinite(law.alpha_rad) && isfinite(law.beta_rad)) || engaged) {
            FZ_CHECK(isfinite(out.alpha_rad) && isfinite(out.beta_rad));
        }
        if (engaged) {
            FZ_CHECK((out.law_flags & OGK_TERMINAL_FLAG_ENGAGED) != 0u);
        }
        engaged = term.engaged;
    }
    return 0;
}
