/* sil_batch.c -- batch loops of the SIL harness (see sil_batch.h). */
#include "sil_batch.h"

ogk_status ogk_sil_cpd_init_batch(ogk_cpd_t *ctx, size_t n_runs,
                                  const ogk_cpd_config_t *cfg, int32_t *status)
{
    ogk_status first = OGK_OK;
    size_t i;
    if (ctx == NULL || cfg == NULL || status == NULL) {
        return OGK_E_NULL;
    }
    for (i = 0u; i < n_runs; ++i) {
        const ogk_status st = ogk_cpd_init(&ctx[i], cfg);
        status[i] = (int32_t)st;
        if (st != OGK_OK && first == OGK_OK) {
            first = st;
        }
    }
    return first;
}

ogk_status ogk_sil_cpd_step_batch(ogk_cpd_t *ctx, size_t n_runs,
                                  const uint8_t *active, const double *in,
                                  double *out, int32_t *status,
                                  uint32_t *flags)
{
    ogk_status first = OGK_OK;
    size_t i;
    if (ctx == NULL || active == NULL || in == NULL || out == NULL ||
        status == NULL || flags == NULL) {
        return OGK_E_NULL;
    }
    for (i = 0u; i < n_runs; ++i) {
        ogk_cpd_input_t u;
        ogk_cpd_output_t y;
        ogk_status st;
        if (active[i] == 0u) {
            continue;
        }
        u.psi = (ogk_real_t)in[0u * n_runs + i];
        u.theta = (ogk_real_t)in[1u * n_runs + i];
        u.phi_roll = (ogk_real_t)in[2u * n_runs + i];
        u.rate_p = (ogk_real_t)in[3u * n_runs + i];
        u.rate_q = (ogk_real_t)in[4u * n_runs + i];
        u.rate_r = (ogk_real_t)in[5u * n_runs + i];
        u.alpha_c = (ogk_real_t)in[6u * n_runs + i];
        u.beta_c = (ogk_real_t)in[7u * n_runs + i];
        u.xi = (ogk_real_t)in[8u * n_runs + i];
        u.phi = (ogk_real_t)in[9u * n_runs + i];
        st = ogk_cpd_step(&ctx[i], &u, &y);
        out[0u * n_runs + i] = (double)y.m_xc;
        out[1u * n_runs + i] = (double)y.delta_yc;
        out[2u * n_runs + i] = (double)y.delta_zc;
        out[3u * n_runs + i] = (double)y.psi_c;
        out[4u * n_runs + i] = (double)y.theta_c;
        status[i] = (int32_t)st;
        flags[i] = y.flags;
        if (st != OGK_OK && first == OGK_OK) {
            first = st;
        }
    }
    return first;
}
