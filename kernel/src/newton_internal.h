/* newton_internal.h -- the damped minimum-norm Newton step shared by the
 * correctors of MPSP (mpsp.c, eqs. 40-46 of Wang & Topputo) and BLT (blt.c,
 * eq. 64 and its Levenberg-Marquardt damping): each law keeps its own
 * scaling, sign and search; the step itself is computed here. Internal to
 * the kernel. */
#ifndef OGK_NEWTON_INTERNAL_H
#define OGK_NEWTON_INTERNAL_H

#include <stddef.h>

#include "ogk/linalg.h"
#include "ogk/status.h"

/* z = the minimum-norm solution of [J, sqrt(lambda) I] z = r (J m x n,
 * row-major; r m entries), by ogk_minnorm's QR of the transpose (ws):
 *   lambda = 0: z = J^T (J J^T)^-1 r, the minimum-norm Newton step;
 *   lambda > 0: z[0..n-1] = J^T (J J^T + lambda I)^-1 r, the Levenberg-
 *   Marquardt step (the augmented matrix is built in aug, m (n + m)
 *   entries; z then has n + m entries, the last m the slack).
 * An ill-conditioned system still gives its least-norm step: taken. On a
 * solved system, step (when not NULL) receives z[0..n-1]. Returns
 * ogk_minnorm's failure, OGK_E_NONFINITE when z[0..n-1] is not finite, or
 * OGK_OK. */
ogk_status ogk_i_newton_minnorm(ogk_qr_t *ws, const ogk_real_t *jac, size_t m, size_t n, ogk_real_t lambda,
                                const ogk_real_t *r, ogk_real_t *aug, ogk_real_t *z, ogk_real_t *step);

#endif /* OGK_NEWTON_INTERNAL_H */
