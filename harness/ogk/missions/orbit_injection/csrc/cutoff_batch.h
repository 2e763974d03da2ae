/* cutoff_batch.h -- SIL harness batch loops over Monte Carlo runs for the
 * energy cut-off monitor (NOT flight code; ogk/cutoff.h): one Python -> C
 * crossing per control step for all runs. Each run owns one ogk_cutoff_t.
 * Used by ogk.missions.orbit_injection.cutoff. */
#ifndef OGK_CUTOFF_BATCH_H
#define OGK_CUTOFF_BATCH_H

#include <stddef.h>
#include <stdint.h>

#include "ogk/cutoff.h"
#include "ogk/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ogk_cutoff_init(&ctx[i], cfg) for every run; status[i] per run. Returns
 * the first non-OK status, else OGK_OK. */
ogk_status ogk_sil_cutoff_init_batch(ogk_cutoff_t *ctx, size_t n_runs,
                                     const ogk_cutoff_config_t *cfg, int32_t *status);

/* ogk_cutoff_step for every run with active[i] != 0, at t[i] with
 * nav[6 i .. 6 i + 5] = r, xi, phi, v_r, v_t, v_n (run-major) and the
 * guidance's predicted cut-off t_predicted[i]. Writes the cut-off time in
 * force, the flags and the status per run (inactive runs untouched). Returns
 * the first non-OK status, else OGK_OK. */
ogk_status ogk_sil_cutoff_step_batch(ogk_cutoff_t *ctx, size_t n_runs, const uint8_t *active,
                                     const double *t, const double *nav,
                                     const double *t_predicted, double *t_cutoff,
                                     uint32_t *flags, int32_t *status);

#ifdef __cplusplus
}
#endif

#endif /* OGK_CUTOFF_BATCH_H */
