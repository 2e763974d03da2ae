/* ogk/cutoff.h -- engine cut-off on the orbital energy, decided between
 * guidance samples (beyond Pontani & Celani 2021; docs/design/vtd-nog.md, "End-game").
 *
 * VTD-NOG predicts the cut-off time at each guidance sample (eq. 32,
 * t_k + (1 - tau_k) t_f^(k)). A thrust fluctuation after the last sample, or a
 * prediction clipped by the end-game bounds, then moves the injection velocity
 * by the thrust acceleration times the timing error (about 18 m/s per second
 * at the end of the LEO-to-GEO burn). This monitor runs at the control rate on
 * the navigation state and cuts the engine when the specific orbital energy
 * reaches the target orbit's, -mu / (2 a), the way real upper stages cut off
 * on velocity or energy: the crossing time inside the coming control period is
 * extrapolated from the energy rate measured over the last period, so the
 * cut-off is not quantised to the control period.
 *
 * Use: once per control period, call ogk_cutoff_step with the navigation state
 * and the guidance's predicted cut-off; fly until out->t_cutoff_s. The monitor
 * is armed from arm_before_s before the predicted cut-off; until it decides,
 * t_cutoff_s is the backstop, the predicted cut-off plus extend_max_s (a run
 * whose energy never reaches the target still stops). Once decided, the
 * cut-off time is final and stays (it latches by design: the engine has been
 * commanded off; ogk_cutoff_reset for a new burn). A rejected call (NaN, a
 * value outside the envelope, time not increasing) changes nothing in the
 * context and reports the cut-off time in force: one bad sample neither
 * decides nor blocks a later decision.
 *
 * Static memory, no globals; many contexts side by side. */
#ifndef OGK_CUTOFF_H
#define OGK_CUTOFF_H

#include <stdbool.h>
#include <stdint.h>
#include "ogk/status.h"
#include "ogk/types.h"
#include "ogk/real.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Envelope of ogk_cutoff_step's navigation input (OGK_E_RANGE outside). */
#define OGK_CUTOFF_R_MAX_M OGK_R(1.0e10)    /* [m] radius, (0, 1e10]: beyond the Moon by 25x */
#define OGK_CUTOFF_V_MAX_MPS OGK_R(1.0e5)   /* [m/s] |v_r|, |v_t|, |v_n| */
#define OGK_CUTOFF_T_MAX_S OGK_R(1.0e7)     /* [s] time since ignition, [0, 1e7] (115 days) */

/* Flags of ogk_cutoff_out_t. */
#define OGK_CUTOFF_FLAG_ARMED 0x01u    /* inside the window before the predicted cut-off */
#define OGK_CUTOFF_FLAG_DECIDED 0x02u  /* energy crossing found: t_cutoff_s is final */
#define OGK_CUTOFF_FLAG_BACKSTOP 0x04u /* not decided: t_cutoff_s is prediction + extend_max_s */

typedef struct {
    ogk_real_t mu_m3_s2;         /* [m^3/s^2] gravitational parameter, > 0 */
    ogk_real_t target_sma_m;     /* [m] semi-major axis of the target orbit (its radius if circular), > 0 */
    ogk_real_t arm_before_s;     /* [s] armed from this long before the predicted cut-off, >= 0 */
    ogk_real_t extend_max_s;     /* [s] latest cut-off after the predicted one (backstop), >= 0 */
    ogk_real_t control_period_s; /* [s] time between ogk_cutoff_step calls, > 0 */
} ogk_cutoff_config_t;

typedef struct {
    ogk_cutoff_config_t cfg;
    ogk_real_t energy_target_j_kg; /* [J/kg] -mu / (2 a) */
    ogk_real_t energy_prev_j_kg;   /* [J/kg] energy at the previous accepted call */
    ogk_real_t t_prev_s;           /* [s] time of the previous accepted call */
    ogk_real_t t_cutoff_s;         /* [s] the decided cut-off time, valid once decided */
    ogk_real_t t_backstop_s;       /* [s] backstop of the last accepted call (T_MAX before one) */
    bool have_prev;            /* [-] an accepted call is held (the rate needs two) */
    bool decided;              /* [-] cut-off decided (final) */
    uint32_t init_marker;      /* [-] set by ogk_cutoff_init */
} ogk_cutoff_t;

typedef struct {
    ogk_real_t t_cutoff_s;        /* [s] cut-off time in force: decided, else the backstop */
    ogk_real_t energy_j_kg;       /* [J/kg] specific orbital energy of the input state (0 if rejected) */
    ogk_real_t energy_rate_w_kg;  /* [W/kg] energy rate over the last period (0 until known) */
    uint32_t flags;           /* [-] OGK_CUTOFF_FLAG_* */
} ogk_cutoff_out_t;

/* Defaults: mu of the Earth, target 42164 km, arm 2 s, extend 10 s, 20 ms. */
/*@ requires cfg_valid: cfg == \null || \valid(cfg); */
ogk_status ogk_cutoff_config_default(ogk_cutoff_config_t *cfg);

/* OGK_E_CONFIG for a non-finite or out-of-range field (context untouched). */
/*@ requires ctx_valid: ctx == \null || \valid(ctx);
    requires cfg_valid: cfg == \null || \valid_read(cfg);
*/
ogk_status ogk_cutoff_init(ogk_cutoff_t *ctx, const ogk_cutoff_config_t *cfg);

/* Back to the state after init (a new burn). */
/*@ requires ctx_valid: ctx == \null || \valid(ctx); */
ogk_status ogk_cutoff_reset(ogk_cutoff_t *ctx);

/* One control period: nav at nav->t_s, the guidance's predicted cut-off
 * t_predicted_s (finite, >= 0). out->t_cutoff_s is the time to cut the engine
 * (it may lie inside the coming period: the sequencer cuts at that time).
 * OGK_E_NONFINITE / OGK_E_RANGE (outside the envelope, or t_s not after the
 * previous accepted call): context unchanged, out holds the cut-off in force:
 * the decided one; else the backstop of the prediction if it is usable; else
 * the last accepted call's backstop; else (nothing known yet)
 * OGK_CUTOFF_T_MAX_S, i.e. the monitor never stops an engine on bad data. */
/*@ requires ctx_valid: ctx == \null || \valid(ctx);
    requires nav_valid: nav == \null || \valid_read(nav);
    requires out_valid: out == \null || \valid(out);
*/
ogk_status ogk_cutoff_step(ogk_cutoff_t *ctx, const ogk_nav_state_t *nav, ogk_real_t t_predicted_s,
                           ogk_cutoff_out_t *out);

#ifdef __cplusplus
}
#endif

#endif /* OGK_CUTOFF_H */
