/* interp.c -- linear and pchip interpolation over a strictly increasing grid. */
#include "ogk/interp.h"

#include <math.h>
#include <stdbool.h>

#include "../ogk_checks.h"

/* Bisection steps that locate an interval in any grid a size_t can index. */
#define OGK_INTERP_MAX_SEARCH 64u

ogk_status ogk_interp_check_grid(const ogk_real_t *grid, size_t n_grid)
{
    size_t k;
    ogk_status st;

    if (grid == NULL) {
        st = OGK_E_NULL;
    } else if (n_grid < 2u) {
        st = OGK_E_DIM;
    } else {
        st = OGK_OK;
        for (k = 0u; (k < n_grid) && (st == OGK_OK); ++k) {
            if (!isfinite(grid[k])) {
                st = OGK_E_NONFINITE;
            } else if ((k > 0u) && (!(grid[k] > grid[k - 1u]))) {
                st = OGK_E_RANGE;
            } else {
                /* finite, and increasing so far */
            }
        }
    }
    return st;
}

ogk_status ogk_interp_locate(const ogk_real_t *grid, size_t n_grid, ogk_real_t tau,
                             size_t *k)
{
    ogk_status st;

    if ((grid == NULL) || (k == NULL)) {
        st = OGK_E_NULL;
    } else if (n_grid < 2u) {
        st = OGK_E_DIM;
    } else if (!isfinite(tau)) {
        st = OGK_E_NONFINITE;
    } else if ((tau < grid[0]) || (tau > grid[n_grid - 1u])) {
        st = OGK_E_RANGE;
    } else {
        /* Invariant: grid[lo] <= tau <= grid[hi]. */
        size_t lo = 0u;
        size_t hi = n_grid - 1u;
        unsigned it;
        for (it = 0u; (it < OGK_INTERP_MAX_SEARCH) && ((hi - lo) > 1u); ++it) {
            const size_t mid = lo + ((hi - lo) / 2u);
            if (grid[mid] <= tau) {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        if ((hi - lo) > 1u) {
            st = OGK_E_NOT_CONVERGED; /* unreachable for n_grid < 2^64 */
        } else {
            *k = lo;
            st = OGK_OK;
        }
    }
    return st;
}

ogk_status ogk_interp_linear(const ogk_real_t *grid, size_t n_grid,
                             const ogk_real_t *values, size_t m, /* NOLINT(bugprone-easily-swappable-parameters): order of the public header (grid, size, values, ...), checked by the unit tests and pytest */
                             ogk_real_t tau, ogk_real_t *out)
{
    size_t k = 0u;
    ogk_status st;

    if ((values == NULL) || (out == NULL)) {
        st = OGK_E_NULL;
    } else if (m == 0u) {
        st = OGK_E_DIM;
    } else {
        st = ogk_interp_locate(grid, n_grid, tau, &k);
    }
    if (st == OGK_OK) {
        const ogk_real_t w = (tau - grid[k]) / (grid[k + 1u] - grid[k]);
        size_t j;
        for (j = 0u; j < m; ++j) {
            const ogk_real_t y0 = values[(k * m) + j];
            const ogk_real_t y1 = values[((k + 1u) * m) + j];
            out[j] = y0 + (w * (y1 - y0));
        }
    }
    return st;
}

/* Magnitudes inside which the direct form of the interior slope cannot
 * overflow or lose its terms to underflow: every w / d is then within
 * [1e-300, 1e300] (float build: [1e-15, 1e15], every w / d within [1e-30,
 * 1e30]; ogk/real.h). Normal data (grid steps and secants far from 1e+-150)
 * take the direct form, bit for bit the formula of Fritsch & Butland. */
#define OGK_INTERP_DIRECT_LO OGK_REAL_ROOT_TINY
#define OGK_INTERP_DIRECT_HI OGK_REAL_ROOT_BIG

/* 2^537 and 2^-537: a ratio a / b of magnitudes b < 2^-537 is taken as
 * (a 2^537) / (b 2^537), the same quotient (scaling by a power of two is
 * exact here) with a divisor of at least 2^-537 (the smallest subnormal,
 * 2^-1074, scaled up). The float build's 2^75 and 2^-75 give a divisor of at
 * least 2^-74 (from 2^-149) and a quotient of at most 2^75 above the band. */
#if OGK_REAL_SINGLE
#define OGK_INTERP_SCALE_UP OGK_R(0x1p75)
#define OGK_INTERP_SCALE_DOWN OGK_R(0x1p-75)
#else
#define OGK_INTERP_SCALE_UP OGK_R(0x1p537)
#define OGK_INTERP_SCALE_DOWN OGK_R(0x1p-537)
#endif

static int sign_of(ogk_real_t v)
{
    return (v > OGK_R(0.0)) ? 1 : ((v < OGK_R(0.0)) ? -1 : 0);
}

static bool in_direct_range(ogk_real_t v)
{
    const ogk_real_t a = OGK_FABS(v);
    return (a >= OGK_INTERP_DIRECT_LO) && (a <= OGK_INTERP_DIRECT_HI);
}

/* a_lo / a_hi for 0 < a_lo <= a_hi, in [0, 1]. The branches on a_hi bound the
 * quotient without a relation between the operands (what a non-relational
 * analysis such as Frama-C EVA can use, docs/evidence/eva.md); each gives the correctly
 * rounded a_lo / a_hi, and the fmin calls only restate a_lo <= a_hi. */
static ogk_real_t magnitude_ratio(ogk_real_t a_lo, ogk_real_t a_hi)
{
    ogk_real_t r;
    if (a_hi >= OGK_R(1.0)) {
        r = a_lo / a_hi;
    } else if (a_hi >= OGK_INTERP_SCALE_DOWN) {
        r = OGK_FMIN(a_lo, OGK_R(1.0)) / a_hi;
    } else {
        r = (OGK_FMIN(a_lo, OGK_INTERP_SCALE_DOWN) * OGK_INTERP_SCALE_UP) /
            (a_hi * OGK_INTERP_SCALE_UP);
    }
    return OGK_FMIN(r, OGK_R(1.0));
}

/* Weighted harmonic mean (w0 + w1) / (w0 / a0 + w1 / a1) of two secant
 * magnitudes a0, a1 > 0 (weights w0, w1 > 0, w0 / w1 within [1/2, 2]). The
 * direct form runs only when every operand is within [1e-150, 1e150] (tested
 * on the operands themselves, so the analysis bounds each quotient). Else,
 * with a_hi = max(a0, a1), e = min(a0, a1) / a_hi in [0, 1] and the weights
 * scaled to u = w / max(w) in [1/2, 1], it is a_hi q with
 * q = e (u_hi + u_lo) / (u_hi e + u_lo) in [0, 1] (u_hi the weight of a_hi):
 * no step overflows, the result lies between a0 and a1, exact to rounding or
 * (when e underflows) within a subnormal of e times a_hi. */
static ogk_real_t harmonic_magnitude(ogk_real_t w0, ogk_real_t w1, ogk_real_t a0, ogk_real_t a1)
{
    ogk_real_t slope;

    if ((a0 >= OGK_INTERP_DIRECT_LO) && (a0 <= OGK_INTERP_DIRECT_HI) &&
        (a1 >= OGK_INTERP_DIRECT_LO) && (a1 <= OGK_INTERP_DIRECT_HI) &&
        in_direct_range(w0) && in_direct_range(w1)) {
        slope = (w0 + w1) / ((w0 / a0) + (w1 / a1));
    } else {
        const ogk_real_t wm = OGK_FMAX(w0, w1);
        const ogk_real_t u0 = w0 / wm;
        const ogk_real_t u1 = w1 / wm;
        ogk_real_t a_hi;
        ogk_real_t u_hi;
        ogk_real_t u_lo;
        ogk_real_t e;
        if (a0 >= a1) {
            a_hi = a0;
            u_hi = u0;
            u_lo = u1;
            e = magnitude_ratio(a1, a0);
        } else {
            a_hi = a1;
            u_hi = u1;
            u_lo = u0;
            e = magnitude_ratio(a0, a1);
        }
        /* q <= 1 since e <= 1; fmin only catches rounding. */
        slope = a_hi * OGK_FMIN((e * (u_hi + u_lo)) / ((u_hi * e) + u_lo), OGK_R(1.0));
    }
    return slope;
}

/* One-sided three-point end slope, shape-preserving (Moler, "Numerical
 * Computing with MATLAB", pchip): h0, h1 the first two intervals, d0, d1 their
 * secant slopes. */
static ogk_real_t pchip_end_slope(ogk_real_t h0, ogk_real_t h1, ogk_real_t d0, ogk_real_t d1)
{
    ogk_real_t s = ((((OGK_R(2.0) * h0) + h1) * d0) - (h0 * d1)) / (h0 + h1);
    if (sign_of(s) != sign_of(d0)) {
        s = OGK_R(0.0);
    } else if ((sign_of(d0) != sign_of(d1)) && (OGK_FABS(s) > OGK_FABS(OGK_R(3.0) * d0))) {
        s = OGK_R(3.0) * d0;
    } else {
        /* the three-point slope is kept */
    }
    return s;
}

/* pchip slopes of the m value columns over the checked grid (n_grid >= 2):
 * the secant for two points, else Fritsch-Butland inside and the one-sided
 * three-point slope at both ends. */
static void pchip_fill_slopes(const ogk_real_t *grid, size_t n_grid,
                              const ogk_real_t *values, size_t m, ogk_real_t *slopes)
{
    size_t k;
    size_t j;

    for (j = 0u; j < m; ++j) {
        if (n_grid == 2u) {
            const ogk_real_t d = (values[m + j] - values[j]) / (grid[1] - grid[0]);
            slopes[j] = d;
            slopes[m + j] = d;
            continue;
        }
        /* Interior: weighted harmonic mean of the adjacent secants
         * (Fritsch & Butland 1984), zero at local extrema. */
        for (k = 1u; (k + 1u) < n_grid; ++k) {
            const ogk_real_t h0 = grid[k] - grid[k - 1u];
            const ogk_real_t h1 = grid[k + 1u] - grid[k];
            const ogk_real_t d0 = (values[(k * m) + j] - values[((k - 1u) * m) + j]) / h0;
            const ogk_real_t d1 = (values[((k + 1u) * m) + j] - values[(k * m) + j]) / h1;
            const ogk_real_t w0 = (OGK_R(2.0) * h1) + h0;
            const ogk_real_t w1 = h1 + (OGK_R(2.0) * h0);
            /* Signs, not d0 * d1: the product of two tiny secants of the same
             * sign underflows to 0 and would flatten a monotone run. Tested on
             * the secants themselves (not through sign_of) so the analysis
             * knows each magnitude is positive. */
            if ((d0 > OGK_R(0.0)) && (d1 > OGK_R(0.0))) {
                slopes[(k * m) + j] = harmonic_magnitude(w0, w1, d0, d1);
            } else if ((d0 < OGK_R(0.0)) && (d1 < OGK_R(0.0))) {
                slopes[(k * m) + j] = -harmonic_magnitude(w0, w1, -d0, -d1);
            } else {
                slopes[(k * m) + j] = OGK_R(0.0);
            }
        }
        {
            const ogk_real_t h0 = grid[1] - grid[0];
            const ogk_real_t h1 = grid[2] - grid[1];
            const ogk_real_t d0 = (values[m + j] - values[j]) / h0;
            const ogk_real_t d1 = (values[(2u * m) + j] - values[m + j]) / h1;
            slopes[j] = pchip_end_slope(h0, h1, d0, d1);
        }
        {
            const size_t n = n_grid - 1u;
            const ogk_real_t h0 = grid[n] - grid[n - 1u];
            const ogk_real_t h1 = grid[n - 1u] - grid[n - 2u];
            const ogk_real_t d0 = (values[(n * m) + j] - values[((n - 1u) * m) + j]) / h0;
            const ogk_real_t d1 = (values[((n - 1u) * m) + j] - values[((n - 2u) * m) + j]) / h1;
            slopes[(n * m) + j] = pchip_end_slope(h0, h1, d0, d1);
        }
    }
}

ogk_status ogk_interp_pchip_slopes(const ogk_real_t *grid, size_t n_grid,
                                   const ogk_real_t *values, size_t m,
                                   ogk_real_t *slopes)
{
    ogk_status st;

    if ((values == NULL) || (slopes == NULL)) {
        st = OGK_E_NULL;
    } else if (m == 0u) {
        st = OGK_E_DIM;
    } else {
        st = ogk_interp_check_grid(grid, n_grid);
    }
    if ((st == OGK_OK) && (!ogk_i_all_finite(values, n_grid * m))) {
        st = OGK_E_NONFINITE;
    }
    if (st == OGK_OK) {
        pchip_fill_slopes(grid, n_grid, values, m, slopes);
        /* Finite grid and values can still give an infinite secant (a value
         * step near DBL_MAX, or one over a subnormal grid step): reported, never
         * handed on as a slope. */
        if (!ogk_i_all_finite(slopes, n_grid * m)) {
            st = OGK_E_RANGE;
        }
    }
    return st;
}

ogk_status ogk_interp_pchip(const ogk_real_t *grid, size_t n_grid,
                            const ogk_real_t *values, const ogk_real_t *slopes,
                            size_t m, ogk_real_t tau, ogk_real_t *out) /* NOLINT(bugprone-easily-swappable-parameters): order of the public header (grid, size, values, ...), checked by the unit tests and pytest */
{
    size_t k = 0u;
    ogk_status st;

    if ((values == NULL) || (slopes == NULL) || (out == NULL)) {
        st = OGK_E_NULL;
    } else if (m == 0u) {
        st = OGK_E_DIM;
    } else {
        st = ogk_interp_locate(grid, n_grid, tau, &k);
    }
    if (st == OGK_OK) {
        const ogk_real_t h = grid[k + 1u] - grid[k];
        const ogk_real_t s = (tau - grid[k]) / h;
        /* Cubic Hermite basis on [0, 1]. */
        const ogk_real_t h00 = (OGK_R(1.0) + (OGK_R(2.0) * s)) * (OGK_R(1.0) - s) * (OGK_R(1.0) - s);
        const ogk_real_t h10 = s * (OGK_R(1.0) - s) * (OGK_R(1.0) - s);
        const ogk_real_t h01 = s * s * (OGK_R(3.0) - (OGK_R(2.0) * s));
        const ogk_real_t h11 = s * s * (s - OGK_R(1.0));
        size_t j;
        for (j = 0u; j < m; ++j) {
            out[j] = (h00 * values[(k * m) + j]) + (h10 * h * slopes[(k * m) + j]) +
                     (h01 * values[((k + 1u) * m) + j]) + (h11 * h * slopes[((k + 1u) * m) + j]);
        }
    }
    return st;
}
