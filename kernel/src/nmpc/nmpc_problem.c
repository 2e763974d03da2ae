/* nmpc_problem.c -- the terminal residual every problem of the NMPC's
 * solver shares the form of (ogk/ocp.h): the first OGK_OCP_NC states at a
 * target state that may move with t_f. */
#include "nmpc_internal.h"

#define NC ((size_t)OGK_NMPC_NC)

void ogk_i_nmpc_terminal(const ogk_i_ocp_t *ocp, const ogk_real_t *x, ogk_real_t t_f, ogk_real_t *c, ogk_real_t *rate) /* NOLINT(bugprone-easily-swappable-parameters): internal, the residual then the target's rate, as nmpc_internal.h; checked by the records and test_nmpc_user_problem.c */
{
    ogk_real_t x_target[NC];
    ogk_real_t x_rate[NC];
    size_t i;
    ocp->ops->target(ocp->data, t_f, x_target, x_rate);
    for (i = 0u; i < NC; ++i) {
        c[i] = x[i] - x_target[i];
        if (rate != NULL) {
            rate[i] = x_rate[i];
        }
    }
}
