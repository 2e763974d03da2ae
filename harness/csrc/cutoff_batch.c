/* cutoff_batch.c -- SIL batch loops for the energy cut-off (not flight code; cutoff_batch.h). */
#include "cutoff_batch.h"

ogk_status ogk_sil_cutoff_init_batch(ogk_cutoff_t *ctx, size_t n_runs,
                                     const ogk_cutoff_config_t *cfg, int32_t *status)
{
    ogk_status first = OGK_OK;
    size_t i;
    if (ctx == NULL || cfg == NULL || status == NULL) {
        return OGK_E_NULL;
    }
    for (i = 0u; i < n_runs; ++i) {
        const ogk_status st = ogk_cutoff_init(&ctx[i], cfg);
        status[i] = (int32_t)st;
        if (st != OGK_OK && first == OGK_OK) {
            first = st;
        }
    }
    return first;
}

ogk_status ogk_sil_cutoff_step_batch(ogk_cutoff_t *ctx, size_t n_runs, const uint8_t *active,
                                     const double *t, const double *nav,
                                     const double *t_predicted, double *t_cutoff,
                                     uint32_t *flags, int32_t *status)
{
    ogk_status first = OGK_OK;
    size_t i;
    if (ctx == NULL || active == NULL || t == NULL || nav == NULL || t_predicted == NULL ||
        t_cutoff == NULL || flags == NULL || status == NULL) {
        return OGK_E_NULL;
    }
    for (i = 0u; i < n_runs; ++i) {
        ogk_nav_state_t in;
        ogk_cutoff_out_t out;
        ogk_status st;
        if (active[i] == 0u) {
            continue;
        }
        in.t_s = t[i];
        in.r_m = nav[6u * i];
        in.xi_rad = nav[6u * i + 1u];
        in.phi_rad = nav[6u * i + 2u];
        in.v_r_mps = nav[6u * i + 3u];
        in.v_t_mps = nav[6u * i + 4u];
        in.v_n_mps = nav[6u * i + 5u];
        st = ogk_cutoff_step(&ctx[i], &in, t_predicted[i], &out);
        t_cutoff[i] = out.t_cutoff_s;
        flags[i] = out.flags;
        status[i] = (int32_t)st;
        if (st != OGK_OK && first == OGK_OK) {
            first = st;
        }
    }
    return first;
}
