/* nav_batch.c -- shared pieces of the SIL batch loops (not flight code; nav_batch.h).
 *
 * The loops' arrays are double (the harness's numpy float64) whatever the kernel's real type: each
 * value is converted to ogk_real_t where it enters a kernel struct or call, and back to double where it
 * leaves one (explicit casts, the identity in the double build). */
#include "nav_batch.h"

ogk_status ogk_sil_nav_of_run(const double *t, const double *nav, size_t i, ogk_nav_state_t *out)
{
    if (t == NULL || nav == NULL || out == NULL) {
        return OGK_E_NULL;
    }
    out->t_s = (ogk_real_t)t[i];
    out->r_m = (ogk_real_t)nav[6u * i];
    out->xi_rad = (ogk_real_t)nav[6u * i + 1u];
    out->phi_rad = (ogk_real_t)nav[6u * i + 2u];
    out->v_r_mps = (ogk_real_t)nav[6u * i + 3u];
    out->v_t_mps = (ogk_real_t)nav[6u * i + 4u];
    out->v_n_mps = (ogk_real_t)nav[6u * i + 5u];
    return OGK_OK;
}

ogk_status ogk_sil_keep_first_error(ogk_status *first, ogk_status st)
{
    if (first == NULL) {
        return OGK_E_NULL;
    }
    if (st != OGK_OK && *first == OGK_OK) {
        *first = st;
    }
    return OGK_OK;
}
