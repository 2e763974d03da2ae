/* blt_flight.h -- the binary-asteroid BLT flight software: the corrector contexts (NRPC, LM,
 * hybrid) in static storage, each configured from the generated flight configuration or from a
 * configuration the ground uplinks, and the correction of a guess with a defined reaction to every
 * status of the kernel (docs/guides/flight-integration-blt.md). Xiong & Wang, sec. III.D: the guidance
 * corrects the BLT parameters of the transfer (eqs. 61-76) before the burn and then flies the held
 * solution's eq. (22) direction (ogk_blt_thrust_cmd).
 *
 * Application code built on ogk/blt.h: copy it. Normalised units throughout (docs/design/blt.md: LU =
 * separation, TU = T_o / 2 pi, masses as fractions of m0).
 *
 *   ogk_blt_flight_init(f, slot, cfg)        once per context (or after an uplinked configuration):
 *                                            FLY, or ABORT (the configuration was rejected: no burn)
 *   ogk_blt_flight_correct(f, slot, &guess)  per guess (ground or on-board re-plan):
 *                                            f->solution, f->report; the action says what to fly
 *   ogk_blt_flight_command(f, slot, t, &cmd) at every control tick of the burn: eq. (22) of the
 *                                            held solution, or the safe command (engine off)
 * Every kernel call goes through CALL(slot, ...) so that a PIL build measures its stack. */
#ifndef BLT_FLIGHT_H
#define BLT_FLIGHT_H

#include <stdint.h>

#include "ogk/blt.h"
#include "ogk/thrust_cmd.h"

/* The contexts: one per corrector of the generated configuration (blt_flight_config.h, order
 * nrpc, lm, hybrid). */
#define OGK_BLT_FLIGHT_N_SLOTS 3u

/* The entry points (slots of the PIL stack probe, in this order). */
enum {
    OGK_BLT_FLIGHT_INIT = 0,
    OGK_BLT_FLIGHT_SOLVE = 1,
    OGK_BLT_FLIGHT_N_ENTRIES = 2
};

/* What the flight software does after a call (one reaction per kernel status). */
typedef enum {
    OGK_BLT_FLIGHT_FLY = 0,     /* OGK_OK: the corrected transfer is held; fly its eq. (22) command */
    OGK_BLT_FLIGHT_SAFE = 1,    /* OGK_E_ITER_LIMIT / OGK_E_NOT_CONVERGED: the kernel dropped the
                                   held solution; engine off (safe command) until a new guess
                                   converges (the ground re-plans; the report says why) */
    OGK_BLT_FLIGHT_REJECT = 2,  /* bad input (OGK_E_RANGE, OGK_E_NONFINITE, OGK_E_DIM, ...): the
                                   guess is refused, nothing was corrected; keep flying what
                                   ogk_blt_thrust_cmd gives (the held solution or the safe command) */
    OGK_BLT_FLIGHT_ABORT = 3    /* the context is not initialised (a rejected configuration, or
                                   never configured): no burn, wait for a valid configuration */
} ogk_blt_flight_action;

typedef struct {
    ogk_blt_t ctx[OGK_BLT_FLIGHT_N_SLOTS];     /* the corrector contexts (~46 KiB each) */
    uint8_t ready[OGK_BLT_FLIGHT_N_SLOTS];     /* [-] 1 once ogk_blt_init accepted the slot's config */
    ogk_blt_transfer_t solution;               /* the last correction's transfer (ogk_blt_solve) */
    ogk_blt_report_t report;                   /* its report */
    ogk_status status[OGK_BLT_FLIGHT_N_ENTRIES]; /* last status per entry point */
} ogk_blt_flight_t;

/* Configures context `slot` with cfg: FLY when the kernel accepts it, ABORT otherwise (the slot
 * is then unusable until a valid configuration comes). */
ogk_blt_flight_action ogk_blt_flight_init(ogk_blt_flight_t *f, uint32_t slot,
                                          const ogk_blt_config_t *cfg);

/* Corrects `guess` with context `slot` (ogk_blt_solve): f->solution, f->report and the action. */
ogk_blt_flight_action ogk_blt_flight_correct(ogk_blt_flight_t *f, uint32_t slot,
                                             const ogk_blt_transfer_t *guess);

/* The command of the held solution at time t [TU] (ogk_blt_thrust_cmd, synodic frame): the
 * kernel's safe command (engine off) when the slot holds no converged solution. */
ogk_status ogk_blt_flight_command(const ogk_blt_flight_t *f, uint32_t slot, ogk_real_t t,
                                  ogk_thrust_cmd_t *cmd);

#endif /* BLT_FLIGHT_H */
