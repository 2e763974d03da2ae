/* terminal_batch.c -- SIL batch loop for the terminal steering (not flight code; terminal_batch.h). */
#include "terminal_batch.h"
#include "ogk/thrust_cmd.h"

#include "nav_batch.h"

ogk_status ogk_sil_terminal_init_batch(ogk_terminal_t *ctx, size_t n_runs,
                                       const ogk_terminal_config_t *cfg, int32_t *status)
{
    ogk_status first = OGK_OK;
    size_t i;
    if (ctx == NULL || cfg == NULL || status == NULL) {
        return OGK_E_NULL;
    }
    for (i = 0u; i < n_runs; ++i) {
        const ogk_status st = ogk_terminal_init(&ctx[i], cfg);
        status[i] = (int32_t)st;
        (void)ogk_sil_keep_first_error(&first, st);
    }
    return first;
}

ogk_status ogk_sil_terminal_step_batch(ogk_terminal_t *ctx, size_t n_runs, const uint8_t *active,
                                       const double *t, const double *nav,
                                       const double *t_predicted, double *alpha, double *beta,
                                       uint8_t *engaged, int32_t *status)
{
    ogk_status first = OGK_OK;
    size_t i;
    if (ctx == NULL || active == NULL || t == NULL || nav == NULL || t_predicted == NULL ||
        alpha == NULL || beta == NULL || engaged == NULL || status == NULL) {
        return OGK_E_NULL;
    }
    for (i = 0u; i < n_runs; ++i) {
        ogk_nav_state_t in;
        ogk_thrust_cmd_t law;
        ogk_thrust_cmd_t out;
        ogk_status st;
        if (active[i] == 0u) {
            continue;
        }
        (void)ogk_sil_nav_of_run(t, nav, i, &in); /* pointers checked above */
        /* the law's complete command (frame r-t-n, unit vector, throttle 1) from its angles */
        st = ogk_thrust_cmd_from_angles((ogk_real_t)t[i], (ogk_real_t)alpha[i], (ogk_real_t)beta[i],
                                        OGK_R(1.0), OGK_THRUST_FLAG_ENGINE_ON, 0u, &law);
        if (st != OGK_OK) {   /* not finite: the step is not flown, the status says why */
            engaged[i] = 0u;
            status[i] = (int32_t)st;
            (void)ogk_sil_keep_first_error(&first, st);
            continue;
        }
#if OGK_REAL_SINGLE
        /* the float kernel gets the radius in two parts: the float r_m and what it cannot hold
         * (ogk_terminal_step_split; docs/design/vtd-nog.md, "Single precision") */
        st = ogk_terminal_step_split(&ctx[i], &in, (ogk_real_t)(nav[6u * i] - (double)in.r_m),
                                     (ogk_real_t)t_predicted[i], &law, &out);
#else
        st = ogk_terminal_step(&ctx[i], &in, (ogk_real_t)t_predicted[i], &law, &out);
#endif
        alpha[i] = (double)out.alpha_rad;
        beta[i] = (double)out.beta_rad;
        engaged[i] = (uint8_t)((out.law_flags & OGK_TERMINAL_FLAG_ENGAGED) != 0u);
        status[i] = (int32_t)st;
        (void)ogk_sil_keep_first_error(&first, st);
    }
    return first;
}
