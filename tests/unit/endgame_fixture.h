/* endgame_fixture.h -- the end-game problem shared by the cut-off and terminal-steering tests
 * (test_cutoff.c, test_terminal.c and their MC/DC files): a GEO target about the Earth, the cut-off
 * configuration, the terminal-steering configuration and the law's command they pass through. */
#ifndef OGK_TEST_ENDGAME_FIXTURE_H
#define OGK_TEST_ENDGAME_FIXTURE_H

#include <string.h>

#include "ogk/cutoff.h"
#include "ogk/terminal.h"

#define MU 3.986004e14     /* [m^3/s^2] Earth */
#define R_F 42164.0e3      /* [m] GEO radius: the terminal target */
#define A_TARGET R_F       /* [m] the cut-off's target semi-major axis (circular GEO) */

/* The cut-off at the end of a burn sampled every dt_s. */
static inline ogk_cutoff_config_t cutoff_config(double dt_s)
{
    ogk_cutoff_config_t cfg;
    (void)ogk_cutoff_config_default(&cfg);
    cfg.mu_m3_s2 = MU;
    cfg.target_sma_m = A_TARGET;
    cfg.arm_before_s = 2.0;
    cfg.extend_max_s = 10.0;
    cfg.control_period_s = dt_s;
    return cfg;
}

static inline ogk_terminal_config_t terminal_config(void)
{
    ogk_terminal_config_t cfg;
    (void)ogk_terminal_config_default(&cfg);
    cfg.mu_m3_s2 = MU;
    cfg.target_radius_m = R_F;
    cfg.window_s = 3.0;
    return cfg;
}

/* The guidance law's command that terminal steering passes through or replaces. */
static inline ogk_thrust_cmd_t law_command(double t_s)
{
    ogk_thrust_cmd_t cmd;
    (void)memset(&cmd, 0, sizeof cmd);
    cmd.t_s = t_s;
    cmd.alpha_rad = 0.5;
    cmd.beta_rad = -0.25;
    cmd.flags = OGK_THRUST_FLAG_ENGINE_ON;
    cmd.law_flags = 0x2u;
    return cmd;
}

#endif
