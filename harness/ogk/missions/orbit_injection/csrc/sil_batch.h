/* sil_batch.h -- SIL harness batch loops over Monte Carlo runs (NOT flight code).
 *
 * One call steps the kernel's CPD attitude controller (ogk/cpd.h) for every run
 * of a batch, so a campaign pays one Python -> C crossing per control step, not
 * one per run. Per-run quantities are component-major arrays: component k of
 * run i is at [k * n_runs + i]. Each run owns one ogk_cpd_t (an array of
 * n_runs contexts allocated by the caller). Used by ogk.missions.orbit_injection.attitude;
 * docs/guides/sil.md. */
#ifndef OGK_SIL_BATCH_H
#define OGK_SIL_BATCH_H

#include <stddef.h>
#include <stdint.h>

#include "ogk/cpd.h"
#include "ogk/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Inputs per run, in this order: psi, theta, phi_roll [rad], rate_p, rate_q,
 * rate_r [rad/s], alpha_c, beta_c, xi, phi [rad] (the fields of
 * ogk_cpd_input_t). */
#define OGK_SIL_CPD_N_IN 10
/* Outputs per run, in this order: m_xc [N m], delta_yc, delta_zc, psi_c,
 * theta_c [rad] (fields of ogk_cpd_output_t). */
#define OGK_SIL_CPD_N_OUT 5

/* ogk_cpd_init(&ctx[i], cfg) for i < n_runs; status[i] receives each result.
 * Returns OGK_E_NULL for a NULL pointer, else the first non-OK per-run status,
 * else OGK_OK. */
ogk_status ogk_sil_cpd_init_batch(ogk_cpd_t *ctx, size_t n_runs,
                                  const ogk_cpd_config_t *cfg, int32_t *status);

/* ogk_cpd_step for every run with active[i] != 0. in: OGK_SIL_CPD_N_IN x
 * n_runs, out: OGK_SIL_CPD_N_OUT x n_runs (component-major), status[i] and
 * flags[i] per run. An inactive run's outputs, status and flags are left
 * untouched. On a per-run error the kernel's safe command (zeros) is written.
 * Returns OGK_E_NULL for a NULL pointer, else the first non-OK per-run status,
 * else OGK_OK. */
ogk_status ogk_sil_cpd_step_batch(ogk_cpd_t *ctx, size_t n_runs,
                                  const uint8_t *active, const double *in,
                                  double *out, int32_t *status,
                                  uint32_t *flags);

#ifdef __cplusplus
}
#endif

#endif /* OGK_SIL_BATCH_H */
