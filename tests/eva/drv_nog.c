/* tests/eva/drv_nog.c -- EVA driver of ogk_nog_* (ogk/nog.h): a validated
 * three-node view (the state ogk_nog_table_view leaves it in: grid 0, 0.5, 1,
 * every entry finite, here any value in [-1e9, 1e9], t_f* in [100, 1e5] s:
 * init rejects t_f* below twice the default dtf_max of 40 s),
 * the default configuration bound to it, three samples inside the
 * navigation envelope of ogk/nog.h and commands at any finite time, then
 * samples outside the envelope. */
#include "eva_driver.h"
#include "ogk/nog.h"

#define N_GRID 3u

void eva_nog(void)
{
    static const double tau[N_GRID] = {0.0, 0.5, 1.0};
    static double entry[N_GRID * OGK_NOG_ENTRY_LEN];
    ogk_nog_table_view_t view;
    ogk_nog_config_t cfg;
    ogk_nog_t ctx;
    ogk_nog_sample_t smp;
    ogk_thrust_cmd_t cmd;
    ogk_nav_state_t nav;
    double t;
    size_t i;
    int k;

    for (i = 0u; i < N_GRID * OGK_NOG_ENTRY_LEN; ++i) {
        entry[i] = eva_in(-1.0e9, 1.0e9);
    }
    view.tau = tau;
    view.entry = entry;
    view.n_grid = N_GRID;
    view.t_f_star_s = eva_in(100.0, 1.0e5);
    view.init_marker = OGK_NOG_VIEW_MARKER;
    view.generation = 0u;
    (void)ogk_nog_config_default(&cfg);
    cfg.view = &view;
    if (ogk_nog_init(&ctx, &cfg) != OGK_OK) {
        return;
    }
    for (k = 0; k < 3; ++k) {
        nav = eva_nav_in_envelope(1.0);
        nav.r_m = eva_in(1.0, OGK_NOG_R_MAX_M);
        nav.phi_rad = eva_in(-1.5, 1.5);
        (void)ogk_nog_sample(&ctx, &nav, &smp);
        (void)ogk_nog_thrust_cmd(&ctx, eva_any_finite(), &cmd);
        (void)ogk_nog_tau_at(&ctx, eva_any_finite(), &t);
    }
    for (k = 0; k < EVA_N_OUTSIDE; ++k) {
        nav = eva_nav_outside(k);
        (void)ogk_nog_sample(&ctx, &nav, &smp);
    }
    (void)ogk_nog_reset(&ctx);
    (void)ogk_nog_sample(&ctx, NULL, &smp);
    (void)ogk_nog_init(&ctx, NULL);
}
