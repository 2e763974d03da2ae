/* tests/eva/drv_terminal.c -- EVA driver of ogk_terminal_* (ogk/terminal.h):
 * the default configuration, three steps inside the navigation envelope
 * (radius from 1 m) with any finite prediction and law command angles, then
 * one on any finite state (the envelope rejections). */
#include "eva_driver.h"
#include "ogk/terminal.h"

void eva_terminal(void)
{
    ogk_terminal_config_t cfg;
    ogk_terminal_t ctx;
    ogk_thrust_cmd_t law;
    ogk_thrust_cmd_t out;
    ogk_nav_state_t nav;
    int i;

    (void)ogk_terminal_config_default(&cfg);
    if (ogk_terminal_init(&ctx, &cfg) != OGK_OK) {
        return;
    }
    for (i = 0; i < 3; ++i) {
        nav = eva_nav_in_envelope(1.0);
        law.t_s = nav.t_s;
        law.alpha_rad = eva_any_finite();
        law.beta_rad = eva_any_finite();
        law.flags = OGK_THRUST_FLAG_ENGINE_ON;
        law.law_flags = 0u;
        law.frame = OGK_FRAME_RTN;
        law.u[0] = 0.0;
        law.u[1] = 1.0;
        law.u[2] = 0.0;
        law.throttle = 1.0;
        (void)ogk_terminal_step(&ctx, &nav, eva_any_finite(), &law, &out);
    }
    for (i = 0; i < EVA_N_OUTSIDE; ++i) {
        nav = eva_nav_outside(i);
        law.t_s = nav.t_s;
        (void)ogk_terminal_step(&ctx, &nav, eva_any_finite(), &law, &out);
    }
    (void)ogk_terminal_reset(&ctx);
    (void)ogk_terminal_step(&ctx, NULL, 0.0, &law, &out);
    (void)ogk_terminal_init(&ctx, NULL);
}
