/* ogk_flight.h -- flight integration layer of the LEO-to-GEO burn: VTD-NOG guidance (ogk/nog.h)
 * and CPD attitude control (ogk/cpd.h) from a const table image and const configurations, with the
 * reaction to every status. Application code, not kernel code: copy it into your application
 * (docs/guides/flight-integration.md), it needs the kernel, the generated table image and the generated
 * flight configuration header (`ogk tables leo-geo`), nothing else (no stdio, no heap).
 *
 * Call sequence (one ogk_flight_t, statically allocated):
 *   ogk_flight_init(f, image, len, &nog_cfg, &cpd_cfg)   once, before ignition; its action must be
 *                                                      OGK_FLIGHT_FLY or the engine is not lit
 *   every control tick, t = n / control rate (50 Hz, 20 ms), from t = 0 (ignition):
 *     if (n % f->ticks_per_sample == 0 && !f->terminating)     every Delta t_S = 2 s
 *         ogk_flight_guidance(f, &nav)          navigation state at t -> new correction, cut-off
 *     ogk_flight_control(f, t, &att, &nav)      thrust-direction command at t + CPD step
 *     apply f->act (M_xc, delta_yc, delta_zc) until the next tick;
 * ogk_flight_control is NOG's command followed by ogk_flight_attitude(f, &cmd, &att, &nav), the
 * attitude tick that takes the one thrust command of every law (ogk_thrust_cmd_t, ogk/types.h) in
 * any frame CPD converts (r-t-n, inertial): another law plugs in there (docs/guides/flight-integration.md,
 * "Another guidance law").
 *     engine off when f->engine_on becomes 0 (t >= f->t_cutoff_s; the last tick is shortened to
 *     land on it).
 * Each function returns the action of ogk_flight_reaction for the status it got, and counts the
 * non-OK statuses. */
#ifndef OGK_FLIGHT_H
#define OGK_FLIGHT_H

#include <stddef.h>
#include <stdint.h>

#include "ogk/cpd.h"
#include "ogk/nog.h"
#include "ogk/status.h"
#include "ogk/types.h"

/* The table is read in place from the const image (ogk_nog_table_view: no RAM copy, the image must
 * stay unchanged and 8-byte aligned, which the generated C ensures). -DOGK_FLIGHT_TABLE_COPY=1
 * decodes it into RAM instead (ogk_nog_table_load, 268 KiB), e.g. for an uplinked image whose
 * buffer is reused, or on a big-endian target (SPARC/LEON, PowerPC), where the in-place view answers
 * OGK_E_BYTE_ORDER (docs/guides/ports.md). */
#ifndef OGK_FLIGHT_TABLE_COPY
#define OGK_FLIGHT_TABLE_COPY 0
#endif
#if OGK_FLIGHT_TABLE_COPY
typedef ogk_nog_table_t ogk_flight_table_t;
#else
typedef ogk_nog_table_view_t ogk_flight_table_t;
#endif

/* What the application does after a kernel call (docs/guides/flight-integration.md, "Reactions"). */
typedef enum {
    OGK_FLIGHT_FLY = 0,          /* status OK: fly the output */
    OGK_FLIGHT_SAFE = 1,         /* fly the kernel's safe output (NOG: last valid correction held,
                                    nominal before the first; CPD: zero torque, zero deflections) */
    OGK_FLIGHT_HOLD = 2,         /* context lost: re-initialise it from the const configuration and
                                    hold the safe output for this tick */
    OGK_FLIGHT_RELOAD_TABLE = 3, /* table image rejected: load it again (redundant copy / re-uplink) */
    OGK_FLIGHT_ABORT = 4         /* not recoverable in flight: inhibit ignition / cut the engine off */
} ogk_flight_action;

/* Which call produced the status. */
typedef enum {
    OGK_FLIGHT_CALL_TABLE = 0,   /* ogk_nog_table_load */
    OGK_FLIGHT_CALL_INIT = 1,    /* ogk_nog_init, ogk_cpd_init */
    OGK_FLIGHT_CALL_SAMPLE = 2,  /* ogk_nog_sample */
    OGK_FLIGHT_CALL_COMMAND = 3, /* ogk_nog_thrust_cmd */
    OGK_FLIGHT_CALL_CPD = 4      /* ogk_cpd_input_from_thrust_cmd, ogk_cpd_step */
} ogk_flight_call;

/* Attitude navigation at a control tick. */
typedef struct {
    ogk_real_t psi, theta, phi_roll;      /* [rad] Euler angles of eq. (9) */
    ogk_real_t rate_p, rate_q, rate_r;    /* [rad/s] body rates */
} ogk_flight_att_t;

typedef struct {
    ogk_flight_table_t table;    /* validated table: a view into the const image (in place) or,
                                    with OGK_FLIGHT_TABLE_COPY, its decoded RAM copy */
    ogk_nog_config_t nog_cfg;    /* the const configuration with .table bound */
    ogk_cpd_config_t cpd_cfg;    /* the const configuration (kept for a re-init) */
    ogk_nog_t nog;
    ogk_cpd_t cpd;
    ogk_nog_sample_t sample;     /* last guidance sample */
    ogk_thrust_cmd_t cmd;        /* last thrust-direction command (ogk/types.h; NOG's: r-t-n) */
    ogk_cpd_output_t act;        /* last actuator command: apply until the next tick */
    ogk_real_t t_cutoff_s;           /* [s] predicted (final once terminating) engine cut-off */
    uint32_t ticks_per_sample;   /* [-] control ticks per guidance sample (Delta t_S x rate) */
    uint32_t n_samples, n_ticks; /* [-] calls made */
    uint32_t n_nonok[OGK_FLIGHT_CALL_CPD + 1]; /* [-] non-OK statuses per call */
    ogk_status last_status;      /* status of the last call */
    uint8_t terminating;         /* eq. (32): the last sampling interval has started */
    uint8_t engine_on;           /* 1 from a successful init to the cut-off */
} ogk_flight_t;

/* The reaction to status st of call: the one place the application's policy is written. */
ogk_flight_action ogk_flight_reaction(ogk_flight_call call, ogk_status st);

/* Validates the table image (in place, or decoded into f->table), binds it to a copy of *nog_cfg, initialises NOG and CPD.
 * control_rate_hz: rate of ogk_flight_control; Delta t_S x rate must be a whole number of ticks.
 * Returns FLY; RELOAD_TABLE when the image is rejected (call again with a redundant copy or a
 * re-uplinked image); ABORT for a rejected configuration (do not ignite). */
ogk_flight_action ogk_flight_init(ogk_flight_t *f, const uint8_t *image, size_t len,
                                  const ogk_nog_config_t *nog_cfg,
                                  const ogk_cpd_config_t *cpd_cfg, ogk_real_t control_rate_hz);

/* Guidance sample at nav->t_s (every Delta t_S): new correction, cut-off time, terminating flag. */
ogk_flight_action ogk_flight_guidance(ogk_flight_t *f, const ogk_nav_state_t *nav);

/* Control tick at t_s: thrust-direction command (NOG) and attitude control (CPD) -> f->act.
 * nav: navigation state at the tick (CPD uses the position angles xi, phi). Sets engine_on = 0 at
 * or after the cut-off. */
ogk_flight_action ogk_flight_control(ogk_flight_t *f, ogk_real_t t_s, const ogk_flight_att_t *att,
                                     const ogk_nav_state_t *nav);

/* Attitude tick on any law's thrust command (the common ogk_thrust_cmd_t: NOG's ogk_nog_thrust_cmd,
 * ogk_mpsp_thrust_cmd, ogk_nmpc_thrust_cmd, ogk_blt_thrust_cmd after
 * ogk_thrust_cmd_synodic_to_inertial): copies it to f->cmd, sets engine_on = 0 when it lacks
 * OGK_THRUST_FLAG_ENGINE_ON, and runs CPD on it (ogk_cpd_input_from_thrust_cmd converts an inertial
 * direction to r-t-n at nav's xi, phi) -> f->act. A command CPD cannot take (OGK_E_FRAME: synodic or
 * unknown frame) is an integration fault: ABORT, f->act the safe command, engine off. */
ogk_flight_action ogk_flight_attitude(ogk_flight_t *f, const ogk_thrust_cmd_t *cmd,
                                      const ogk_flight_att_t *att, const ogk_nav_state_t *nav);

/* The attitude half of CPD's input (Euler angles and body rates); the command half is the law's. */
void ogk_flight_cpd_attitude(const ogk_flight_att_t *att, ogk_cpd_input_t *in);

#endif /* OGK_FLIGHT_H */
