/* nog_batch.h -- SIL harness batch loops over Monte Carlo runs for the
 * VTD-NOG guidance (NOT flight code): one Python -> C crossing per sampling
 * or command time for all runs. Each run owns one ogk_nog_t; all share one
 * read-only ogk_nog_table_t. Used by ogk.missions.orbit_injection.nog_guidance. */
#ifndef OGK_NOG_BATCH_H
#define OGK_NOG_BATCH_H

#include <stddef.h>
#include <stdint.h>

#include "ogk/nog.h"
#include "ogk/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ogk_nog_init(&ctx[i], cfg) for every run; status[i] per run. Returns the
 * first non-OK status, else OGK_OK. */
ogk_status ogk_sil_nog_init_batch(ogk_nog_t *ctx, size_t n_runs,
                                  const ogk_nog_config_t *cfg, int32_t *status);

/* ogk_nog_sample for every run with active[i] != 0, at t[i] with
 * nav[6 i .. 6 i + 5] = r, xi, phi, v_r, v_t, v_n (run-major). Writes the
 * predicted cut-off time, t_f^(k), tau_k, the flags and the status per run
 * (inactive runs untouched). Returns the first non-OK status, else OGK_OK. */
ogk_status ogk_sil_nog_sample_batch(ogk_nog_t *ctx, size_t n_runs, const uint8_t *active,
                                    const double *t, const double *nav, double *t_cutoff,
                                    double *t_f, double *tau_k, uint32_t *flags,
                                    int32_t *status);

/* ogk_nog_thrust_cmd for every run at t[i]: alpha[i], beta[i] [rad], flags (the
 * command's law_flags, OGK_NOG_FLAG_*) and status per run. Returns the first non-OK status, else OGK_OK. */
ogk_status ogk_sil_nog_command_batch(const ogk_nog_t *ctx, size_t n_runs, const double *t,
                                     double *alpha, double *beta, uint32_t *flags,
                                     int32_t *status);

#ifdef __cplusplus
}
#endif

#endif /* OGK_NOG_BATCH_H */
