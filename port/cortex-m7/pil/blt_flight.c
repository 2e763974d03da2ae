/* blt_flight.c -- the binary-asteroid BLT flight software (blt_flight.h). */
#include "blt_flight.h"

#include <stddef.h>

#if defined(OGK_PIL_PROBE) && OGK_PIL_PROBE
#include "ogk_pil.h"
extern ogk_pil_stack_t ogk_pil_probe;   /* the PIL program's probe (blt_pil.c) */
#define CALL(slot, st, call) OGK_PIL_STACK(&ogk_pil_probe, (slot), (st) = (call))
#else
#define CALL(slot, st, call) ((st) = (call))
#endif

ogk_blt_flight_action ogk_blt_flight_init(ogk_blt_flight_t *f, uint32_t slot,
                                          const ogk_blt_config_t *cfg)
{
    ogk_status st;
    if (f == NULL || slot >= OGK_BLT_FLIGHT_N_SLOTS || cfg == NULL) {
        return OGK_BLT_FLIGHT_ABORT;
    }
    f->ready[slot] = 0u;
    CALL(OGK_BLT_FLIGHT_INIT, st, ogk_blt_init(&f->ctx[slot], cfg));
    f->status[OGK_BLT_FLIGHT_INIT] = st;
    if (st != OGK_OK) {
        return OGK_BLT_FLIGHT_ABORT;   /* OGK_E_CONFIG, OGK_E_RANGE, ...: no burn on this slot */
    }
    f->ready[slot] = 1u;
    return OGK_BLT_FLIGHT_FLY;
}

ogk_blt_flight_action ogk_blt_flight_correct(ogk_blt_flight_t *f, uint32_t slot,
                                             const ogk_blt_transfer_t *guess)
{
    ogk_status st;
    if (f == NULL || slot >= OGK_BLT_FLIGHT_N_SLOTS) {
        return OGK_BLT_FLIGHT_ABORT;
    }
    if (f->ready[slot] == 0u) {
        f->status[OGK_BLT_FLIGHT_SOLVE] = OGK_E_NOT_INIT;
        return OGK_BLT_FLIGHT_ABORT;
    }
    /* eqs. (61)-(76): the configured corrector (NRPC, LM or hybrid) from the guess */
    CALL(OGK_BLT_FLIGHT_SOLVE, st, ogk_blt_solve(&f->ctx[slot], guess, &f->solution, &f->report));
    f->status[OGK_BLT_FLIGHT_SOLVE] = st;
    switch (st) {
    case OGK_OK:
        return OGK_BLT_FLIGHT_FLY;               /* |e|_2 <= tol: the solution is held */
    case OGK_E_ITER_LIMIT:                       /* max_iter reached */
    case OGK_E_NOT_CONVERGED:                    /* stalled, J J^T singular, or the guess hits a body */
        return OGK_BLT_FLIGHT_SAFE;              /* the held solution was dropped: engine off */
    case OGK_E_NOT_INIT:
        f->ready[slot] = 0u;
        return OGK_BLT_FLIGHT_ABORT;
    default:                                     /* bad input: the guess is refused */
        return OGK_BLT_FLIGHT_REJECT;
    }
}

ogk_status ogk_blt_flight_command(const ogk_blt_flight_t *f, uint32_t slot, ogk_real_t t,
                                  ogk_thrust_cmd_t *cmd)
{
    if (f == NULL || cmd == NULL || slot >= OGK_BLT_FLIGHT_N_SLOTS || f->ready[slot] == 0u) {
        /* no context: the safe command in the synodic frame (engine off) */
        return (cmd == NULL) ? OGK_E_NULL
                             : ogk_thrust_cmd_safe(OGK_R(0.0), OGK_FRAME_SYNODIC, OGK_BLT_FLAG_SAFE, cmd);
    }
    /* eq. (22) of the held solution; engine off (OGK_E_SAFE_COMMAND) when none is held */
    return ogk_blt_thrust_cmd(&f->ctx[slot], t, cmd);
}
