/* newton.c -- the damped minimum-norm Newton step of the MPSP and BLT
 * correctors (newton_internal.h). */
#include "../newton_internal.h"

#include <math.h>
#include <string.h>

ogk_status ogk_i_newton_minnorm(ogk_qr_t *ws, const ogk_real_t *jac, size_t m, size_t n, ogk_real_t lambda, /* NOLINT(bugprone-easily-swappable-parameters): (J, its rows, its columns, damping) in the formula's order; checked through the MPSP and BLT tests */
                                const ogk_real_t *r, ogk_real_t *aug, ogk_real_t *z, ogk_real_t *step)
{
    ogk_status st;
    if (lambda > OGK_R(0.0)) {
        /* [J, sqrt(lambda) I]: the minimum-norm [du; s] has du = J^T (J J^T + lambda I)^-1 r */
        const ogk_real_t root = OGK_SQRT(lambda);
        const size_t na = n + m;
        size_t i;
        size_t j;
        for (i = 0u; i < m; ++i) {
            for (j = 0u; j < n; ++j) {
                aug[(i * na) + j] = jac[(i * n) + j];
            }
            for (j = n; j < na; ++j) {
                aug[(i * na) + j] = ((j - n) == i) ? root : OGK_R(0.0);
            }
        }
        st = ogk_minnorm(ws, aug, m, na, r, z);
    } else {
        st = ogk_minnorm(ws, jac, m, n, r, z);
    }
    if ((st == OGK_OK) || (st == OGK_E_ILL_CONDITIONED)) {
        size_t i;
        if (step != NULL) {
            (void)memcpy(step, z, sizeof(ogk_real_t) * n);
        }
        /* defensive: ogk_minnorm bounds a solved step by OGK_LA_SOLVE_MAX
         * (ogk/linalg.h), so it is finite; every entry is looked at (no
         * early exit), one condition per decision */
        st = OGK_OK;
        for (i = 0u; i < n; ++i) {
            if (!isfinite(z[i])) {
                st = OGK_E_NONFINITE;
            }
        }
    }
    return st;
}
