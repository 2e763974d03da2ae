/* ogk/proximity.h -- receding-horizon NMPC of a planar proximity approach:
 * the Clohessy-Wiltshire equations in the target's Hill frame with a
 * throttled engine, a hold point reached at rest and keep-out discs about
 * the target, solved by the NMPC's SQP and strategies (ogk/nmpc.h) as the
 * second user of its problem interface (ogk/ocp.h; docs/design/nmpc-problem.md).
 *
 * Model (normalised: the scenario documents its units; the harness uses
 * LU = 1 km, TU = 1 / n, MU = the initial mass, so mean_motion = 1):
 *   x' = v_x, y' = v_y,
 *   v_x' = 3 n^2 x + 2 n v_y + (T_max w / m) cos(alpha),
 *   v_y' = -2 n v_x + (T_max w / m) sin(alpha),
 *   m' = -mdot_max w,
 * x radial (away from the Earth), y along-track; alpha from the radial axis
 * (the rendezvous law's convention: the thrust command is the same r-t-n
 * vector, ogk_prox_thrust_cmd). Terminal set: (x, y, v_x, v_y) = (hold, 0)
 * at t_f. */
#ifndef OGK_PROXIMITY_H
#define OGK_PROXIMITY_H

#include <stdint.h>
#include "ogk/nmpc.h"
#include "ogk/status.h"
#include "ogk/types.h"
#include "ogk/real.h"

#ifdef __cplusplus
extern "C" {
#endif

#define OGK_PROX_MAX_KEEPOUT 2u  /* keep-out discs (<= OGK_OCP_MAX_KEEPOUT) */
#define OGK_PROX_INIT_MARKER 0x50524F58u /* "PROX" */

/* The model: what ogk_ocp_problem_t's callbacks read. */
typedef struct {
    ogk_real_t mean_motion;         /* [rad/TU] n of the target's circular orbit, > 0 (normalised: 1) */
    ogk_real_t thrust_max;          /* [MU LU/TU^2] T_max, > 0 */
    ogk_real_t mass_flow_max;       /* [MU/TU] mdot at full throttle, >= 0 */
    ogk_real_t hold[2];             /* [LU] the hold point (x, y), reached at rest */
    uint32_t n_keepout;         /* [-] keep-out discs, 0..OGK_PROX_MAX_KEEPOUT */
    ogk_real_t keepout_centre[2u * OGK_PROX_MAX_KEEPOUT]; /* [LU] disc j's centre (x, y) at 2 j */
    ogk_real_t keepout_radius[OGK_PROX_MAX_KEEPOUT];      /* [LU] disc j's radius, >= 0 (0: none) */
} ogk_prox_model_t;

/* Configuration: the model, and the solver's settings (ogk_nmpc_config_t's
 * transcription, SQP and strategy fields, ogk_prox_config_default; its
 * heliocentric model and target fields are not read, its engine is the
 * throttled one). */
typedef struct {
    ogk_prox_model_t model;
    ogk_nmpc_config_t solver;
} ogk_prox_config_t;

/* Context. Treat as opaque. */
typedef struct {
    ogk_prox_model_t model;     /* the problem's data */
    ogk_nmpc_t nmpc;            /* the SQP's settings, workspace and plan */
    uint32_t init_marker;       /* [-] OGK_PROX_INIT_MARKER once initialised */
} ogk_prox_t;

/* The problem's callback table (ogk/ocp.h) over an ogk_prox_model_t: for a
 * caller who runs the NMPC directly (ogk_nmpc_init_problem), whose data must
 * then be a validated ogk_prox_model_t (the callbacks convert it back:
 * docs/evidence/misra-deviations.md, D10). */
extern const ogk_ocp_problem_t ogk_prox_problem;

/* Defaults: the solver's of ogk_nmpc_config_default with the throttled
 * engine and minimum fuel; the model zeroed (mean_motion 1; thrust_max,
 * mass_flow_max and hold must be set). OGK_E_NULL. */
ogk_status ogk_prox_config_default(ogk_prox_config_t *cfg);

/* Validates the model (OGK_E_NONFINITE, OGK_E_CONFIG) and the solver's
 * settings (as ogk_nmpc_init_problem) and initialises. */
ogk_status ogk_prox_init(ogk_prox_t *ctx, const ogk_prox_config_t *cfg);

/* Back to the state right after init. */
ogk_status ogk_prox_reset(ogk_prox_t *ctx);

/* As ogk_nmpc_set_horizon_bounds and ogk_nmpc_set_hessian_init. */
ogk_status ogk_prox_set_horizon_bounds(ogk_prox_t *ctx, ogk_real_t horizon_min, ogk_real_t horizon_max);
ogk_status ogk_prox_set_hessian_init(ogk_prox_t *ctx, ogk_real_t hessian_init);

/* As ogk_nmpc_load_plan, ogk_nmpc_get_plan, ogk_nmpc_solve, ogk_nmpc_replan,
 * ogk_nmpc_command and ogk_nmpc_thrust_cmd (plan states (x, y, v_x, v_y, m)
 * [LU, LU, LU/TU, LU/TU, MU], controls (alpha [rad], w [-])); a state with
 * m <= 0 is outside the model's domain (OGK_E_RANGE). */
ogk_status ogk_prox_load_plan(ogk_prox_t *ctx, const ogk_nmpc_plan_t *plan);
ogk_status ogk_prox_get_plan(const ogk_prox_t *ctx, ogk_nmpc_plan_t *plan);
ogk_status ogk_prox_solve(ogk_prox_t *ctx, const ogk_nmpc_input_t *in, ogk_nmpc_report_t *rep);
ogk_status ogk_prox_replan(ogk_prox_t *ctx, const ogk_nmpc_input_t *in, ogk_nmpc_report_t *rep);
ogk_status ogk_prox_command(const ogk_prox_t *ctx, ogk_real_t t, ogk_nmpc_command_t *cmd);
ogk_status ogk_prox_thrust_cmd(const ogk_prox_t *ctx, ogk_real_t t, ogk_thrust_cmd_t *cmd);

#ifdef __cplusplus
}
#endif

#endif /* OGK_PROXIMITY_H */
