/* nav_batch.h -- what the SIL batch loops share (NOT flight code): the
 * run-major navigation array of a batch read as the kernel's ogk_nav_state_t,
 * and the first-error rule of their return status. Used by nog_batch.c,
 * cutoff_batch.c and terminal_batch.c. */
#ifndef OGK_NAV_BATCH_H
#define OGK_NAV_BATCH_H

#include <stddef.h>

#include "ogk/status.h"
#include "ogk/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Run i of a batch at time t[i]: nav[6 i .. 6 i + 5] = r [m], xi, phi [rad],
 * v_r, v_t, v_n [m/s] (run-major). Returns OGK_E_NULL for a NULL pointer. */
ogk_status ogk_sil_nav_of_run(const double *t, const double *nav, size_t i, ogk_nav_state_t *out);

/* The batch's return status: *first becomes st if it is still OGK_OK. */
ogk_status ogk_sil_keep_first_error(ogk_status *first, ogk_status st);

#ifdef __cplusplus
}
#endif

#endif /* OGK_NAV_BATCH_H */
