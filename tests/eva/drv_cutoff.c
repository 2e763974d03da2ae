/* tests/eva/drv_cutoff.c -- EVA driver of ogk_cutoff_* (ogk/cutoff.h): a
 * configuration over the physical ranges (mu in [1, 1e21] m^3/s^2: the Sun's
 * is 1.3e20; target semi-major axis in [1, 1e10] m; the times over their
 * accepted [0, 1e7] s), three steps inside the navigation envelope with any
 * finite prediction, then states outside it (the envelope rejections). */
#include "eva_driver.h"
#include "ogk/cutoff.h"

void eva_cutoff(void)
{
    ogk_cutoff_config_t cfg;
    ogk_cutoff_t ctx;
    ogk_cutoff_out_t out;
    ogk_nav_state_t nav;
    int i;

    (void)ogk_cutoff_config_default(&cfg);
    cfg.mu_m3_s2 = eva_in(1.0, 1.0e21);
    cfg.target_sma_m = eva_in(1.0, 1.0e10);
    cfg.arm_before_s = eva_in(0.0, 1.0e7);
    cfg.extend_max_s = eva_in(0.0, 1.0e7);
    cfg.control_period_s = eva_in(1.0e-6, 1.0e7);
    if (ogk_cutoff_init(&ctx, &cfg) != OGK_OK) {
        return;
    }
    for (i = 0; i < 3; ++i) {
        nav = eva_nav_in_envelope(1.0);
        (void)ogk_cutoff_step(&ctx, &nav, eva_any_finite(), &out);
    }
    for (i = 0; i < EVA_N_OUTSIDE; ++i) {
        nav = eva_nav_outside(i);
        (void)ogk_cutoff_step(&ctx, &nav, eva_any_finite(), &out);
    }
    nav.r_m = -1.0;
    (void)ogk_cutoff_step(&ctx, &nav, 100.0, &out);
    (void)ogk_cutoff_step(&ctx, &nav, -1.0, &out);
    (void)ogk_cutoff_step(&ctx, NULL, 100.0, &out);
    (void)ogk_cutoff_reset(&ctx);
    (void)ogk_cutoff_init(&ctx, NULL);
}
