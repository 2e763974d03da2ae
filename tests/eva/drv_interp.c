/* tests/eva/drv_interp.c -- EVA driver of ogk_interp_* (ogk/interp.h): a
 * checked, non-uniform five-node grid (a table's grid is ground data, checked
 * at load), two value columns over [-1e6, 1e6], any finite query. */
#include "eva_driver.h"
#include "ogk/interp.h"

#define N_GRID 5u
#define M_COLS 2u

void eva_interp(void)
{
    static const double grid[N_GRID] = {0.0, 0.1, 0.35, 0.7, 1.0};
    double values[N_GRID * M_COLS];
    double slopes[N_GRID * M_COLS];
    double out[M_COLS];
    size_t i;
    size_t k;
    double tau = eva_any_finite();

    for (i = 0u; i < N_GRID * M_COLS; ++i) {
        values[i] = eva_in(-1.0e6, 1.0e6);
    }
    (void)ogk_interp_check_grid(grid, N_GRID);
    (void)ogk_interp_locate(grid, N_GRID, tau, &k);
    (void)ogk_interp_linear(grid, N_GRID, values, M_COLS, tau, out);
    if (ogk_interp_pchip_slopes(grid, N_GRID, values, M_COLS, slopes) == OGK_OK) {
        (void)ogk_interp_pchip(grid, N_GRID, values, slopes, M_COLS, tau, out);
    }
    /* two nodes: the secant slopes */
    if (ogk_interp_pchip_slopes(grid, 2u, values, M_COLS, slopes) == OGK_OK) {
        (void)ogk_interp_pchip(grid, 2u, values, slopes, M_COLS, tau, out);
    }
    /* rejections */
    (void)ogk_interp_check_grid(grid, 1u);
    (void)ogk_interp_locate(NULL, N_GRID, tau, &k);
    (void)ogk_interp_linear(grid, N_GRID, values, 0u, tau, out);
    (void)ogk_interp_pchip_slopes(grid, N_GRID, NULL, M_COLS, slopes);
}
