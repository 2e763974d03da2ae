/* ogk/interp.h -- interpolation of tabulated quantities over a strictly
 * increasing grid (normally normalised time tau in [0, 1]).
 *
 * values holds n_grid rows of m quantities (row-major, row k at grid[k]).
 * A query outside [grid[0], grid[n_grid-1]] returns OGK_E_RANGE and leaves
 * out untouched: nothing is extrapolated silently. */
#ifndef OGK_INTERP_H
#define OGK_INTERP_H

#include <stddef.h>
#include "ogk/status.h"
#include "ogk/real.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Checks that grid[0..n_grid-1] is finite and strictly increasing, n_grid >= 2. */
/*@ requires grid_valid: grid == \null || \valid_read(grid + (0 .. n_grid - 1)); */
ogk_status ogk_interp_check_grid(const ogk_real_t *grid, size_t n_grid);

/* Piecewise-linear interpolation of m quantities at tau. */
/*@ requires grid_valid: grid == \null || \valid_read(grid + (0 .. n_grid - 1));
    requires values_valid: values == \null || \valid_read(values + (0 .. n_grid * m - 1));
    requires out_valid: out == \null || \valid(out + (0 .. m - 1));
*/
ogk_status ogk_interp_linear(const ogk_real_t *grid, size_t n_grid,
                             const ogk_real_t *values, size_t m,
                             ogk_real_t tau, ogk_real_t *out);

/* Shape-preserving piecewise-cubic Hermite (pchip, Fritsch-Carlson slopes with
 * the Fritsch-Butland harmonic mean, one-sided three-point end slopes as in
 * Moler's pchip). Writes slopes (n_grid x m, d value / d tau) once on the ground
 * or at init; ogk_interp_pchip then evaluates in O(log n). Subnormal, tiny or
 * huge secants are handled without overflow or underflow (a scaled form of the
 * harmonic mean, the same result to rounding); OGK_E_RANGE if a secant itself
 * is not finite (value steps near DBL_MAX, or a subnormal grid step). */
/*@ requires grid_valid: grid == \null || \valid_read(grid + (0 .. n_grid - 1));
    requires values_valid: values == \null || \valid_read(values + (0 .. n_grid * m - 1));
    requires slopes_valid: slopes == \null || \valid(slopes + (0 .. n_grid * m - 1));
*/
ogk_status ogk_interp_pchip_slopes(const ogk_real_t *grid, size_t n_grid,
                                   const ogk_real_t *values, size_t m,
                                   ogk_real_t *slopes);

/*@ requires grid_valid: grid == \null || \valid_read(grid + (0 .. n_grid - 1));
    requires values_valid: values == \null || \valid_read(values + (0 .. n_grid * m - 1));
    requires slopes_valid: slopes == \null || \valid_read(slopes + (0 .. n_grid * m - 1));
    requires out_valid: out == \null || \valid(out + (0 .. m - 1));
*/
ogk_status ogk_interp_pchip(const ogk_real_t *grid, size_t n_grid,
                            const ogk_real_t *values, const ogk_real_t *slopes,
                            size_t m, ogk_real_t tau, ogk_real_t *out);

/* Index k of the interval [grid[k], grid[k+1]] holding tau (the last interval
 * for tau == grid[n_grid-1]). */
/*@ requires grid_valid: grid == \null || \valid_read(grid + (0 .. n_grid - 1));
    requires k_valid: k == \null || \valid(k);
*/
ogk_status ogk_interp_locate(const ogk_real_t *grid, size_t n_grid, ogk_real_t tau,
                             size_t *k);

#ifdef __cplusplus
}
#endif

#endif /* OGK_INTERP_H */
