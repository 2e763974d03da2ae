/* tests/eva/eva_driver.h -- helpers shared by the EVA drivers (analysis only). */
#ifndef OGK_EVA_DRIVER_H
#define OGK_EVA_DRIVER_H

#include "libm_spec.h"
#include "__fc_builtin.h"
#include <float.h>
#include "ogk/types.h"

/* Any finite double: what a caller may pass where the kernel checks the range itself. */
static double eva_any_finite(void)
{
    return Frama_C_double_interval(-DBL_MAX, DBL_MAX);
}

/* A value in [lo, hi]. */
static double eva_in(double lo, double hi)
{
    return Frama_C_double_interval(lo, hi);
}

/* Any finite navigation state. */
static ogk_nav_state_t eva_any_nav(void)
{
    ogk_nav_state_t nav;
    nav.t_s = eva_any_finite();
    nav.r_m = eva_any_finite();
    nav.xi_rad = eva_any_finite();
    nav.phi_rad = eva_any_finite();
    nav.v_r_mps = eva_any_finite();
    nav.v_t_mps = eva_any_finite();
    nav.v_n_mps = eva_any_finite();
    return nav;
}

/* A navigation state inside the laws' common envelope (cutoff.h,
 * terminal.h, nog.h: radius within [r_min_m, 1e10] m, each velocity
 * component within 1e5 m/s, time within [0, 1e7] s). */
static ogk_nav_state_t eva_nav_in_envelope(double r_min_m)
{
    ogk_nav_state_t nav;
    nav.t_s = eva_in(0.0, 1.0e7);
    nav.r_m = eva_in(r_min_m, 1.0e10);
    nav.xi_rad = eva_in(-1.0e4, 1.0e4);
    nav.phi_rad = eva_in(-1.0e4, 1.0e4);
    nav.v_r_mps = eva_in(-1.0e5, 1.0e5);
    nav.v_t_mps = eva_in(-1.0e5, 1.0e5);
    nav.v_n_mps = eva_in(-1.0e5, 1.0e5);
    return nav;
}

/* A state outside that envelope in one field (which = 0 .. EVA_N_OUTSIDE - 1).
 * The driver calls the law once per case: EVA does not carry the envelope
 * test's verdict back from its helper, so a state joined over the cases
 * (any r, any v, any t) would be analysed as if accepted. */
#define EVA_N_OUTSIDE 5
static ogk_nav_state_t eva_nav_outside(int which)
{
    ogk_nav_state_t nav = eva_nav_in_envelope(1.0);
    switch (which) {
    case 0: nav.r_m = eva_in(-DBL_MAX, 0.0); break;
    case 1: nav.r_m = eva_in(1.0e10 * 1.5, DBL_MAX); break;
    case 2: nav.v_r_mps = eva_in(1.0e5 * 1.5, DBL_MAX); break;
    case 3: nav.t_s = eva_in(-DBL_MAX, -1.0); break;
    default: nav.t_s = eva_in(1.0e7 * 1.5, DBL_MAX); break;
    }
    return nav;
}

#endif /* OGK_EVA_DRIVER_H */
