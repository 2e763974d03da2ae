/* nmpc_flight.h -- the rendezvous flight software of one NMPC replan (Starek & Kolmanovsky 2012,
 * sec. 2.3; docs/guides/flight-integration-nmpc.md): at the start of each control subinterval the
 * navigation state goes in, the receding-horizon re-solve runs (ogk_nmpc_replan; the first time the
 * open loop from the generated guesses), and the plan's command is flown until the report's t_next,
 * where the next replan is due. The same calls, in the same order, as the SIL's kernel guidance
 * (harness/ogk/missions/rendezvous/kernel_guidance.py), so a PIL campaign flies what the SIL flies.
 *
 * Application code: copy it. Needs the kernel and the flight configuration generated from the
 * scenario (harness/ogk/missions/rendezvous/flight_config.py: ogk_nmpc_flight_config.h).
 *
 *   ogk_nmpc_flight_init(f)            before the first replan; FLY or do not start the loop
 *   at each replan time t [TU] with the measured state x (r, theta, v_r, v_theta, m) [normalised]:
 *       ogk_nmpc_flight_step(f, &in)    -> action (ogk_nmpc_action), f->rep.t_next (next replan
 *                                          time), f->cmd (the command at t)
 *   between replans, at the control rate: ogk_nmpc_command(&f->ctx, t, &cmd) on the plan flown.
 * Every kernel call goes through CALL(slot, ...) so that a PIL build measures its stack. */
#ifndef NMPC_FLIGHT_H
#define NMPC_FLIGHT_H

#include <stdint.h>

#include "ogk/nmpc.h"

/* The entry points a replan calls (slots of the PIL stack probe, in this order). */
enum {
    OGK_NMPC_FL_INIT = 0,       /* ogk_nmpc_init */
    OGK_NMPC_FL_RESET = 1,      /* ogk_nmpc_reset */
    OGK_NMPC_FL_LOAD_PLAN = 2,  /* ogk_nmpc_load_plan */
    OGK_NMPC_FL_SOLVE = 3,      /* ogk_nmpc_solve (first replan: the open loop from a guess) */
    OGK_NMPC_FL_REPLAN = 4,     /* ogk_nmpc_replan (every later replan) */
    OGK_NMPC_FL_GET_PLAN = 5,   /* ogk_nmpc_get_plan */
    OGK_NMPC_FL_COMMAND = 6,    /* ogk_nmpc_command */
    OGK_NMPC_FL_N_ENTRIES = 7
};

/* What the application does after a replan (docs/guides/flight-integration-nmpc.md, "Reactions"). */
typedef enum {
    OGK_NMPC_FLY = 0,        /* OK: a new converged plan; fly f->cmd, replan at f->rep.t_next */
    OGK_NMPC_FLY_STALE = 1,  /* the SQP failed (ITER_LIMIT, NOT_CONVERGED, INFEASIBLE, NOT_POSDEF,
                                NONFINITE inside the solve): the previous plan, shifted, is flown
                                (command flag SAFE set); replan at f->rep.t_next */
    OGK_NMPC_HOLD = 2,       /* the measurement was rejected (NONFINITE, RANGE before any solve):
                                the plan held is flown unchanged; replan with the next measurement */
    OGK_NMPC_NO_PLAN = 3,    /* the first replan converged from no guess: engine off (the kernel's
                                safe command); the next replan starts cold again (the SIL's loop
                                stops here: "no first plan") */
    OGK_NMPC_REINIT = 4,     /* the context was lost (NOT_INIT, NULL): re-initialised from the const
                                configuration, engine off this step, the next replan starts cold */
    OGK_NMPC_ABORT = 5       /* the configuration is rejected: never start the loop */
} ogk_nmpc_action;

typedef struct {
    ogk_nmpc_t ctx;             /* the context flown (390,784 B: keep it in static storage) */
    ogk_nmpc_t time_opt;        /* minimum fuel only: the first replan's minimum-time pre-solve */
    ogk_nmpc_plan_t guess;      /* the guess being loaded (first replan) */
    ogk_nmpc_plan_t plan;       /* the plan flown after the step (ogk_nmpc_get_plan) */
    ogk_nmpc_input_t in;        /* the step's measurement [TU; LU, rad, LU/TU, LU/TU, MU] */
    ogk_nmpc_report_t rep;      /* the report of the step's last solve or replan */
    ogk_nmpc_command_t cmd;     /* the command at the replan time [rad, -] */
    ogk_status status;          /* [-] status of the step's last solve or replan call */
    ogk_status plan_status;     /* [-] status of ogk_nmpc_get_plan after the step */
    ogk_status cmd_status;      /* [-] status of ogk_nmpc_command at the replan time */
    uint32_t started;           /* [-] 1 once the first replan ran (later ones warm-start) */
    uint32_t pre_iterations;    /* [-] minimum fuel: SQP iterations of the last time pre-solve */
    uint32_t guesses_tried;     /* [-] guesses the first replan solved from */
    uint32_t step_solves;       /* [-] SQP solves of the flown context in the last step (ogk_nmpc_report_t.solves, summed) */
    uint32_t step_failed;       /* [-] its solve and replan calls of the last step that failed */
    uint32_t n_guesses;         /* [-] guesses of the generated configuration */
    ogk_real_t t_f_kept;            /* [TU] OGK_NMPC_FLIGHT_FINAL_TIME: the final time every solve keeps (the
                                 *      ground plan's; a first solve retried with T free: its own); 0 else */
    ogk_status settings_status; /* [-] the last in-flight setting's status (ogk_nmpc_set_*) */
    ogk_status last[OGK_NMPC_FL_N_ENTRIES]; /* [-] last status per entry point */
} ogk_nmpc_flight_t;

/* The probe hook: a PIL build defines OGK_PIL_PROBE to measure each call's stack (nmpc_pil.c). */

/* Initialises the context from the generated configuration. FLY, or ABORT (config rejected). */
ogk_nmpc_action ogk_nmpc_flight_init(ogk_nmpc_flight_t *f);

/* One replan at in->t from the measured in->x (kernel_guidance.KernelGuidance.replan): the first
 * time, the generated guesses in turn (minimum fuel: each through the minimum-time optimum at the
 * ground's throttle), reset + load + solve until one converges; afterwards ogk_nmpc_replan. Then
 * the plan flown (f->plan) and the command at in->t (f->cmd). Returns the reaction. */
ogk_nmpc_action ogk_nmpc_flight_step(ogk_nmpc_flight_t *f, const ogk_nmpc_input_t *in);

#endif /* NMPC_FLIGHT_H */
