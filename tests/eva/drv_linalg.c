/* tests/eva/drv_linalg.c -- EVA driver of ogk/linalg.h: 3 x 3 and 4 x 3
 * operands with entries in [-1e3, 1e3] (the products are unchecked by
 * contract: bounded entries keep them finite), the factorizations and their
 * solves on them, and the dimension and NULL rejections. */
#include "eva_driver.h"
#include "ogk/linalg.h"

static void fill(double *v, size_t n)
{
    size_t i;
    for (i = 0u; i < n; ++i) {
        v[i] = eva_in(-1.0e3, 1.0e3);
    }
}

void eva_linalg(void)
{
    static ogk_lu_t lu;
    static ogk_chol_t ch;
    static ogk_qr_t qr;
    double a[12];
    double b[12];
    double c[16];
    double x[4];
    double y[4];

    fill(a, 12u);
    fill(b, 12u);
    fill(x, 4u);
    (void)ogk_mat_vec(a, 4u, 3u, x, y);
    (void)ogk_mat_t_vec(a, 4u, 3u, x, y);
    (void)ogk_mat_mul(a, 3u, 3u, b, 3u, c);
    (void)ogk_mat_mul_at_b(a, 3u, 3u, b, 3u, c);
    (void)ogk_mat_mul_a_bt(a, 3u, 3u, b, 3u, c);
    (void)ogk_mat_transpose(a, 4u, 3u, c);
    if (ogk_lu_factor(&lu, a, 3u) == OGK_OK) {
        (void)ogk_lu_solve(&lu, x, y);
        (void)ogk_lu_inverse(&lu, c);
    }
    if (ogk_chol_factor(&ch, a, 3u) == OGK_OK) {
        (void)ogk_chol_solve(&ch, x, y);
    }
    (void)ogk_lstsq(&qr, a, 4u, 3u, x, y);
    (void)ogk_minnorm(&qr, a, 3u, 4u, x, y);
    /* rejections */
    (void)ogk_mat_vec(a, 0u, 3u, x, y);
    (void)ogk_mat_vec(NULL, 3u, 3u, x, y);
    (void)ogk_lu_factor(&lu, a, OGK_LA_MAX_N + 1u);
    (void)ogk_lu_solve(NULL, x, y);
}
