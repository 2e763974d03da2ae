/* terminal_batch.h -- SIL harness batch loop over Monte Carlo runs for the
 * terminal steering stage (NOT flight code; ogk/terminal.h): one Python -> C
 * crossing per control step for all runs. Each run owns one ogk_terminal_t.
 * Used by ogk.missions.orbit_injection.terminal. */
#ifndef OGK_TERMINAL_BATCH_H
#define OGK_TERMINAL_BATCH_H

#include <stddef.h>
#include <stdint.h>

#include "ogk/status.h"
#include "ogk/terminal.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ogk_terminal_init(&ctx[i], cfg) for every run; status[i] per run. */
ogk_status ogk_sil_terminal_init_batch(ogk_terminal_t *ctx, size_t n_runs,
                                       const ogk_terminal_config_t *cfg, int32_t *status);

/* ogk_terminal_step for every run with active[i] != 0: nav[6 i .. 6 i + 5] =
 * r, xi, phi, v_r, v_t, v_n at t[i], the predicted cut-off t_predicted[i] and
 * the law's command alpha[i], beta[i] (engine on), which are replaced in place
 * by the command to fly; engaged[i] and status[i] per run. */
ogk_status ogk_sil_terminal_step_batch(ogk_terminal_t *ctx, size_t n_runs, const uint8_t *active,
                                       const double *t, const double *nav,
                                       const double *t_predicted, double *alpha, double *beta,
                                       uint8_t *engaged, int32_t *status);

#ifdef __cplusplus
}
#endif

#endif /* OGK_TERMINAL_BATCH_H */
