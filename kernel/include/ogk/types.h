/* ogk/types.h -- input/output types shared by every guidance and control law.
 *
 * A guidance law consumes the navigation state (ogk_nav_state_t) and produces a
 * thrust-direction command (ogk_thrust_cmd_t); the attitude controller (CPD,
 * ogk/cpd.h) takes that command through ogk_cpd_input_from_thrust_cmd, so any
 * law can feed CPD. The contract every law follows (config_default, init,
 * reset, step; the init marker) is in docs/adding-a-law.md. */
#ifndef OGK_TYPES_H
#define OGK_TYPES_H

#include <stdint.h>
#include "ogk/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Navigation state at one time, spherical coordinates of the position and
 * velocity in the local r-t-n frame (Pontani & Celani 2021, eqs. 1-6). */
typedef struct {
    double t_s;        /* [s] time since ignition */
    double r_m;        /* [m] radius */
    double xi_rad;     /* [rad] right ascension */
    double phi_rad;    /* [rad] declination */
    double v_r_mps;    /* [m/s] radial velocity */
    double v_t_mps;    /* [m/s] transverse velocity */
    double v_n_mps;    /* [m/s] normal velocity */
} ogk_nav_state_t;

/* Flags of a thrust command (ogk_thrust_cmd_t.flags). */
#define OGK_THRUST_FLAG_ENGINE_ON 0x01u /* engine on; clear: cut-off (engine off) */
#define OGK_THRUST_FLAG_SAFE 0x02u      /* safe command: the law could not compute a new one */
#define OGK_THRUST_FLAG_LIMITED 0x04u   /* the law clipped its correction (a bound bit) */

/* Thrust-direction command: thrust along (cos b sin a, cos b cos a, sin b) in
 * r-t-n (Pontani & Celani 2021, eqs. 39 and 52). */
typedef struct {
    double t_s;          /* [s] time the command is for */
    double alpha_rad;    /* [rad] in-plane thrust angle, from t towards r */
    double beta_rad;     /* [rad] out-of-plane thrust angle, towards n */
    uint32_t flags;      /* [-] OGK_THRUST_FLAG_* */
    uint32_t law_flags;  /* [-] the producing law's own flags (OGK_NOG_FLAG_* for NOG) */
} ogk_thrust_cmd_t;

#ifdef __cplusplus
}
#endif

#endif /* OGK_TYPES_H */
