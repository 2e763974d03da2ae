/* fuzz_cutoff_step.c -- ogk_cutoff_step with arbitrary navigation inputs and predictions.
 * Input: up to 64 steps; a step whose first byte is odd is a plausible end-of-burn state (radius
 * near 42164 km, transverse speed near circular, time near 106 s, small one-byte offsets), else
 * 6 raw doubles (t, r, v_r, v_t, v_n, t_predicted).
 * Oracle (cutoff.h): every output time is finite; on OGK_OK the energy is finite; once DECIDED,
 * the cut-off time never changes (it latches) and every later call reports it; a rejected call
 * (status != OGK_OK) leaves the context byte-identical. */
#include "fuzz_common.h"

#include "ogk/cutoff.h"

static ogk_cutoff_t cut;

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fz_reader_t r;
    ogk_cutoff_config_t cfg;
    bool decided = false;
    double t_decided = 0.0;
    double t_plausible = 100.0;
    int steps = 0;
    r.p = data;
    r.n = size;
    FZ_CHECK(ogk_cutoff_config_default(&cfg) == OGK_OK);
    FZ_CHECK(ogk_cutoff_init(&cut, &cfg) == OGK_OK);
    while (r.n > 0u && steps < 64) {
        ogk_nav_state_t nav;
        ogk_cutoff_out_t out;
        ogk_cutoff_t before;
        double t_pred;
        ogk_status st;
        ++steps;
        (void)memset(&nav, 0, sizeof nav);
        if ((r.p[0] & 1u) != 0u) {
            (void)fz_u8(&r);
            t_plausible += 0.02;
            nav.t_s = t_plausible;
            nav.r_m = 42164.0e3 + fz_small(&r, 1.0e3);
            nav.v_r_mps = fz_small(&r, 50.0);
            nav.v_t_mps = 3074.66 + fz_small(&r, 20.0);
            nav.v_n_mps = fz_small(&r, 50.0);
            t_pred = 106.0 + fz_small(&r, 3.0);
        } else {
            nav.t_s = fz_f64(&r);
            nav.r_m = fz_f64(&r);
            nav.v_r_mps = fz_f64(&r);
            nav.v_t_mps = fz_f64(&r);
            nav.v_n_mps = fz_f64(&r);
            t_pred = fz_f64(&r);
        }
        before = cut;
        st = ogk_cutoff_step(&cut, &nav, t_pred, &out);
        FZ_CHECK(isfinite(out.t_cutoff_s));
        if (st != OGK_OK) {
            FZ_CHECK(memcmp(&before, &cut, sizeof cut) == 0);
        } else {
            FZ_CHECK(isfinite(out.energy_j_kg) && isfinite(out.energy_rate_w_kg));
        }
        if (decided) {
            FZ_CHECK((out.flags & OGK_CUTOFF_FLAG_DECIDED) != 0u);
            FZ_CHECK(out.t_cutoff_s == t_decided);
        } else if ((out.flags & OGK_CUTOFF_FLAG_DECIDED) != 0u) {
            decided = true;
            t_decided = out.t_cutoff_s;
        }
    }
    return 0;
}
