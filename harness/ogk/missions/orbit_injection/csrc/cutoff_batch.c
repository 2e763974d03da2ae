/* cutoff_batch.c -- SIL batch loops for the energy cut-off (not flight code; cutoff_batch.h). */
#include "cutoff_batch.h"

#include "nav_batch.h"

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
        (void)ogk_sil_keep_first_error(&first, st);
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
        (void)ogk_sil_nav_of_run(t, nav, i, &in); /* pointers checked above */
        st = ogk_cutoff_step(&ctx[i], &in, (ogk_real_t)t_predicted[i], &out);
        t_cutoff[i] = (double)out.t_cutoff_s;
        flags[i] = out.flags;
        status[i] = (int32_t)st;
        (void)ogk_sil_keep_first_error(&first, st);
    }
    return first;
}
