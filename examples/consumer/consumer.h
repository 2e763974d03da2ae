/* consumer.h -- the flight loops of the example consumer of an installed ogk (docs/guides/cmake.md): one per
 * guidance or control law, each through the public API only (<ogk/...h>, never ogk/internal). Each
 * prints one line and returns 0 when every kernel call answered OGK_OK and the outcome is where the
 * law must put it, 1 otherwise. The contexts are static: they are too large for a flight stack. */
#ifndef OGK_CONSUMER_H
#define OGK_CONSUMER_H

#include <float.h>

#include <ogk/real.h>
#include <ogk/thrust_cmd.h>

/* The loops compute as the kernel does, in ogk_real_t (double, or float in a package built with
 * OGK_PRECISION=single: ogk/real.h); the simulated world around them (the vehicle, the navigation, the
 * table written on the ground) stays double and is handed over with explicit conversions.
 * CONSUMER_TOL(tol_double, tol_single): a pass bound that depends on the real type, the first in the
 * double build, the second in the float build, each float value with its reason beside it (float's
 * epsilon times the problem's scale, the solver tolerance the loop sets, or measured on the
 * Cortex-M4F and the host: docs/design/precision-unit-tests.md). */
#if OGK_REAL_SINGLE
#define CONSUMER_TOL(tol_double, tol_single) (tol_single)
#else
#define CONSUMER_TOL(tol_double, tol_single) (tol_double)
#endif

int fly_nog(void);  /* VTD-NOG on a hand-made gain table: the corrected cut-off time */
int fly_cpd(void);  /* CPD pitch loop on a linearised vehicle: the pointing error settles */
int fly_mpsp(void); /* MPSP: a 5 % thrust loss corrected, the terminal conditions met */
int fly_nmpc(void); /* heliocentric NMPC: minimum-time radial transfer, then receding-horizon replans */
int fly_prox(void); /* proximity NMPC: minimum-fuel approach to a hold point around a keep-out disc */
int fly_blt(void);  /* BLT: a single burn corrected from a perturbed guess, its command flown */

/* Prints "law: PASS|FAIL detail" and returns 0 (pass) or 1. */
int consumer_verdict(const char *law, int pass, const char *detail);

/* | |u| - 1 | of a command's direction, in double (the float components' squares exact). A unit
 * vector normalised in float is within 4 eps of unit length (a sum of three squares and a root, each
 * rounded once): CONSUMER_UNIT_TOL. */
double consumer_unit_error(const ogk_thrust_cmd_t *cmd);
#define CONSUMER_UNIT_TOL CONSUMER_TOL(1e-12, 4.0 * (double)FLT_EPSILON)

#endif /* OGK_CONSUMER_H */
