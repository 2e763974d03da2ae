/* consumer.h -- the flight loops of the example consumer of an installed ogk (docs/guides/cmake.md): one per
 * guidance or control law, each through the public API only (<ogk/...h>, never ogk/internal). Each
 * prints one line and returns 0 when every kernel call answered OGK_OK and the outcome is where the
 * law must put it, 1 otherwise. The contexts are static: they are too large for a flight stack. */
#ifndef OGK_CONSUMER_H
#define OGK_CONSUMER_H

int fly_nog(void);  /* VTD-NOG on a hand-made gain table: the corrected cut-off time */
int fly_cpd(void);  /* CPD pitch loop on a linearised vehicle: the pointing error settles */
int fly_mpsp(void); /* MPSP: a 5 % thrust loss corrected, the terminal conditions met */
int fly_nmpc(void); /* heliocentric NMPC: minimum-time radial transfer, then receding-horizon replans */
int fly_prox(void); /* proximity NMPC: minimum-fuel approach to a hold point around a keep-out disc */
int fly_blt(void);  /* BLT: a single burn corrected from a perturbed guess, its command flown */

/* Prints "law: PASS|FAIL detail" and returns 0 (pass) or 1. */
int consumer_verdict(const char *law, int pass, const char *detail);

#endif /* OGK_CONSUMER_H */
