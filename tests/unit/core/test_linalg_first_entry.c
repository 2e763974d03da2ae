/* test_linalg_first_entry.c -- paths of linalg.c that the other tests leave unrun (make
 * coverage, docs/evidence/coverage.md; moved from test_gate_misc.c):
 *  - linalg: a factorization or check that fails on its first entry (the loops stop there), and
 *    a right-hand side inside the QR workspace. */
#include "ogk_test.h"

#include <float.h>
#include <string.h>

#include "ogk/linalg.h"

/* ------------------------------------------------------------------ linalg */

static ogk_qr_t qr_ws;

/* req: OGK-CORE-021 OGK-CORE-011 */
static void test_linalg_first_entry_failures(void **state)
{
    ogk_lu_t lu;
    ogk_chol_t ch;
    const ogk_real_t A2[4] = {4.0, 1.0, 1.0, 3.0};
    const ogk_real_t b2[2] = {1.0, 2.0};
    ogk_real_t x[3] = {-7.0, -7.0, -7.0};
    (void)state;
    /* the first permutation entry out of range: found before the others are looked at */
    OGK_ASSERT_STATUS(ogk_lu_factor(&lu, A2, 2u), OGK_OK);
    lu.perm[0] = 7u;
    OGK_ASSERT_STATUS(ogk_lu_solve(&lu, b2, x), OGK_E_NOT_INIT);
    OGK_ASSERT_NEAR(x[0], -7.0, 0.0);
    {
        /* not symmetric in its first off-diagonal pair (1, 0) / (0, 1) */
        const ogk_real_t A3[9] = {4.0, 1.0, 0.0, 2.0, 4.0, 0.0, 0.0, 0.0, 4.0};
        OGK_ASSERT_STATUS(ogk_chol_factor(&ch, A3, 3u), OGK_E_NOT_POSDEF);
        assert_int_equal(ch.n, 0u);
    }
    {
        /* not symmetric in the pair (2, 0) / (0, 2), found before (2, 1) is looked at */
        const ogk_real_t A3[9] = {4.0, 0.0, 1.0, 0.0, 4.0, 0.0, 2.0, 0.0, 4.0};
        OGK_ASSERT_STATUS(ogk_chol_factor(&ch, A3, 3u), OGK_E_NOT_POSDEF);
        assert_int_equal(ch.n, 0u);
    }
    {
        /* negative first pivot */
        const ogk_real_t A3[9] = {-1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0};
        OGK_ASSERT_STATUS(ogk_chol_factor(&ch, A3, 3u), OGK_E_NOT_POSDEF);
        assert_int_equal(ch.n, 0u);
    }
    {
        /* first column zero: rank deficient from the first diagonal entry of R */
        const ogk_real_t A32[6] = {0.0, 1.0, 0.0, 2.0, 0.0, 3.0};
        const ogk_real_t b3[3] = {1.0, 2.0, 3.0};
        OGK_ASSERT_STATUS(ogk_lstsq(&qr_ws, A32, 3u, 2u, b3, x), OGK_E_SINGULAR);
        /* a right-hand side that lies inside the workspace */
        OGK_ASSERT_STATUS(ogk_lstsq(&qr_ws, A32, 3u, 2u, qr_ws.tau, x), OGK_E_RANGE);
        /* and a solution that would be written into it */
        OGK_ASSERT_STATUS(ogk_lstsq(&qr_ws, A32, 3u, 2u, b3, qr_ws.tau), OGK_E_RANGE);
        OGK_ASSERT_NEAR(x[0], -7.0, 0.0);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_linalg_first_entry_failures),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
