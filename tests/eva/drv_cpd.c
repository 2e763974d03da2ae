/* tests/eva/drv_cpd.c -- EVA driver of ogk_cpd_* (ogk/cpd.h): the default
 * configuration in each pointing mode, three steps on any finite angles (the
 * kernel range-checks them) with body rates within 1e3 rad/s (the rates are
 * not range-checked: beyond that the PD products may overflow, and the final
 * finite check answers OGK_E_SAFE_COMMAND, unit-tested), and the geometry
 * functions on any finite angles. */
#include "eva_driver.h"
#include "ogk/cpd.h"

static ogk_cpd_input_t any_input(void)
{
    ogk_cpd_input_t in;
    in.psi = eva_any_finite();
    in.theta = eva_any_finite();
    in.phi_roll = eva_any_finite();
    in.rate_p = eva_in(-1.0e3, 1.0e3);
    in.rate_q = eva_in(-1.0e3, 1.0e3);
    in.rate_r = eva_in(-1.0e3, 1.0e3);
    in.alpha_c = eva_any_finite();
    in.beta_c = eva_any_finite();
    in.xi = eva_any_finite();
    in.phi = eva_any_finite();
    return in;
}

void eva_cpd(void)
{
    ogk_cpd_config_t cfg;
    ogk_cpd_t ctx;
    ogk_cpd_input_t in;
    ogk_cpd_output_t out;
    double a;
    double b;
    int i;

    (void)ogk_cpd_config_default(&cfg);
    if (Frama_C_nondet(0, 1) != 0) {
        cfg.pointing = OGK_CPD_POINTING_BODY;
    }
    if (ogk_cpd_init(&ctx, &cfg) == OGK_OK) {
        for (i = 0; i < 3; ++i) {
            in = any_input();
            (void)ogk_cpd_step(&ctx, &in, &out);
        }
        (void)ogk_cpd_reset(&ctx);
    }
    (void)ogk_cpd_commanded_attitude(eva_any_finite(), eva_any_finite(), eva_any_finite(),
                                     eva_any_finite(), &a, &b);
    (void)ogk_cpd_thrust_angles(eva_any_finite(), eva_any_finite(), eva_any_finite(),
                                eva_any_finite(), eva_any_finite(), eva_any_finite(),
                                eva_any_finite(), &a, &b);
    (void)ogk_cpd_pointing_error_body(eva_any_finite(), eva_any_finite(), eva_any_finite(),
                                      eva_any_finite(), eva_any_finite(), eva_any_finite(),
                                      eva_any_finite(), &a, &b);
    (void)ogk_cpd_step(&ctx, NULL, &out);
    (void)ogk_cpd_init(&ctx, NULL);
}
