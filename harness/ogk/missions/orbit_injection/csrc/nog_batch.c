/* nog_batch.c -- SIL batch loops for VTD-NOG (not flight code; nog_batch.h). */
#include "nog_batch.h"

#include "nav_batch.h"

ogk_status ogk_sil_nog_init_batch(ogk_nog_t *ctx, size_t n_runs,
                                  const ogk_nog_config_t *cfg, int32_t *status)
{
    ogk_status first = OGK_OK;
    size_t i;
    if (ctx == NULL || cfg == NULL || status == NULL) {
        return OGK_E_NULL;
    }
    for (i = 0u; i < n_runs; ++i) {
        const ogk_status st = ogk_nog_init(&ctx[i], cfg);
        status[i] = (int32_t)st;
        (void)ogk_sil_keep_first_error(&first, st);
    }
    return first;
}

ogk_status ogk_sil_nog_sample_batch(ogk_nog_t *ctx, size_t n_runs, const uint8_t *active,
                                    const double *t, const double *nav, double *t_cutoff,
                                    double *t_f, double *tau_k, uint32_t *flags,
                                    int32_t *status)
{
    ogk_status first = OGK_OK;
    size_t i;
    if (ctx == NULL || active == NULL || t == NULL || nav == NULL || t_cutoff == NULL ||
        t_f == NULL || tau_k == NULL || flags == NULL || status == NULL) {
        return OGK_E_NULL;
    }
    for (i = 0u; i < n_runs; ++i) {
        ogk_nav_state_t in;
        ogk_nog_sample_t out;
        ogk_status st;
        if (active[i] == 0u) {
            continue;
        }
        (void)ogk_sil_nav_of_run(t, nav, i, &in); /* pointers checked above */
        st = ogk_nog_sample(&ctx[i], &in, &out);
        t_cutoff[i] = (double)out.t_cutoff_s;
        t_f[i] = (double)out.t_f_s;
        tau_k[i] = (double)out.tau_k;
        flags[i] = out.flags;
        status[i] = (int32_t)st;
        (void)ogk_sil_keep_first_error(&first, st);
    }
    return first;
}

ogk_status ogk_sil_nog_command_batch(const ogk_nog_t *ctx, size_t n_runs, const double *t,
                                     double *alpha, double *beta, uint32_t *flags,
                                     int32_t *status)
{
    ogk_status first = OGK_OK;
    size_t i;
    if (ctx == NULL || t == NULL || alpha == NULL || beta == NULL || flags == NULL ||
        status == NULL) {
        return OGK_E_NULL;
    }
    for (i = 0u; i < n_runs; ++i) {
        ogk_thrust_cmd_t out;
        const ogk_status st = ogk_nog_thrust_cmd(&ctx[i], (ogk_real_t)t[i], &out);
        alpha[i] = (double)out.alpha_rad;
        beta[i] = (double)out.beta_rad;
        flags[i] = out.law_flags;
        status[i] = (int32_t)st;
        (void)ogk_sil_keep_first_error(&first, st);
    }
    return first;
}
