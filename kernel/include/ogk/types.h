/* ogk/types.h -- input/output types shared by every guidance and control law.
 *
 * A guidance law consumes the navigation state (ogk_nav_state_t) and produces a
 * thrust-direction command (ogk_thrust_cmd_t): every law of the kernel (NOG,
 * MPSP, NMPC, BLT) has a contract call that fills it. The attitude controller
 * (CPD, ogk/cpd.h) takes it whatever the law through
 * ogk_cpd_input_from_thrust_cmd, so any law can feed CPD. The helpers that
 * build, check and convert the command are in ogk/thrust_cmd.h. The contract
 * every law follows (config_default, init, reset, step; the init marker) is in
 * docs/guides/adding-a-law.md; the frames and the angle convention in
 * docs/design/kernel-core.md, "Thrust commands". */
#ifndef OGK_TYPES_H
#define OGK_TYPES_H

#include <stdint.h>
#include "ogk/status.h"
#include "ogk/real.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Navigation state at one time, spherical coordinates of the position and
 * velocity in the local r-t-n frame (Pontani & Celani 2021, eqs. 1-6). */
typedef struct {
    ogk_real_t t_s;        /* [s] time since ignition */
    ogk_real_t r_m;        /* [m] radius */
    ogk_real_t xi_rad;     /* [rad] right ascension */
    ogk_real_t phi_rad;    /* [rad] declination */
    ogk_real_t v_r_mps;    /* [m/s] radial velocity */
    ogk_real_t v_t_mps;    /* [m/s] transverse velocity */
    ogk_real_t v_n_mps;    /* [m/s] normal velocity */
} ogk_nav_state_t;

/* Flags of a thrust command (ogk_thrust_cmd_t.flags). */
#define OGK_THRUST_FLAG_ENGINE_ON 0x01u /* engine on; clear: cut-off (engine off) */
#define OGK_THRUST_FLAG_SAFE 0x02u      /* safe command: the law could not compute a new one */
#define OGK_THRUST_FLAG_LIMITED 0x04u   /* the law clipped its correction (a bound bit) */

/* Frame of a thrust direction (ogk_thrust_cmd_t.frame). All right-handed,
 * unit axes. "Inertial" is the law's inertial frame I: the one whose
 * spherical angles of the position are the navigation state's xi (in the
 * I1-I2 plane, from I1 towards I2) and phi (from that plane towards I3), so
 * r_hat = (cos phi cos xi, cos phi sin xi, sin phi) in I. */
typedef enum {
    /* Local r-t-n frame at the vehicle (as in ogk/cpd.h):
     * r = r_hat (radial, outward), t = (-sin xi, cos xi, 0) in I (transverse,
     * horizontal, eastward), n = r x t = (-sin phi cos xi, -sin phi sin xi,
     * cos phi) in I (towards I3's side of the local horizontal). In a planar
     * problem (phi = 0, polar angle theta = xi) t is the polar direction
     * theta_hat and n = I3. */
    OGK_FRAME_RTN = 0,
    /* The law's inertial frame I (above): NOG's c frame (c1-c2 = the nominal
     * orbit plane), MPSP's heliocentric frame of its normalised units. */
    OGK_FRAME_INERTIAL = 1,
    /* Rotating (synodic) frame of two primaries (BLT, Xiong & Wang eq. 4):
     * x from the primary towards the secondary, z along their orbital angular
     * velocity, y = z x x. It turns about z relative to the inertial frame
     * whose I3 is that z; converting it needs its angle at the command's time
     * (ogk_thrust_cmd_synodic_to_inertial). */
    OGK_FRAME_SYNODIC = 2,
    OGK_FRAME_COUNT = 3 /* number of frames (not a frame) */
} ogk_frame_t;

/* Thrust-direction command, what every guidance law produces (one command
 * for every law; build it with ogk/thrust_cmd.h).
 *
 * Direction: the unit vector u in `frame`. The one angle convention of the
 * kernel (Pontani & Celani 2021, eqs. 39 and 52): thrust along
 * (cos b sin a, cos b cos a, sin b) in r-t-n, i.e. alpha in the local
 * horizontal plane from t towards r, beta out of it towards n. In
 * OGK_FRAME_RTN the angles alpha_rad, beta_rad ARE the command and u holds
 * the same direction as a vector (the kernel's producers set both, so they
 * agree to rounding; r-t-n consumers -- CPD, the terminal steering -- read
 * the angles). In any other frame u is the command and the angles are 0: the
 * r-t-n angles need the position (ogk_thrust_cmd_to_rtn).
 *
 * throttle: the fraction of the law's available thrust, 0 whenever
 * ENGINE_ON is clear (1 for the constant-thrust laws NOG and BLT during a
 * burn, the bang-off-bang u of MPSP, NMPC's w).
 *
 * Fields after law_flags were added by issue 18; a command built field by
 * field in the old way (memset to 0, then the angles) is a valid r-t-n
 * command for the consumers that read the angles. */
typedef struct {
    ogk_real_t t_s;          /* [s, or the law's normalised TU] time the command is for (NOG: s since ignition; MPSP, NMPC, BLT: their TU) */
    ogk_real_t alpha_rad;    /* [rad] in-plane thrust angle, from t towards r (r-t-n frame; 0 in other frames) */
    ogk_real_t beta_rad;     /* [rad] out-of-plane thrust angle, towards n (r-t-n frame; 0 in other frames) */
    uint32_t flags;      /* [-] OGK_THRUST_FLAG_* */
    uint32_t law_flags;  /* [-] the producing law's own flags (OGK_NOG_FLAG_*, OGK_NMPC_FLAG_*, OGK_BLT_FLAG_*; MPSP: 0) */
    ogk_frame_t frame;   /* [-] frame of u (OGK_FRAME_*) */
    ogk_real_t u[3];         /* [-] unit thrust direction, components in frame (r-t-n: u_r, u_t, u_n) */
    ogk_real_t throttle;     /* [-] thrust fraction in [0, 1]; 0 when ENGINE_ON is clear */
} ogk_thrust_cmd_t;

#ifdef __cplusplus
}
#endif

#endif /* OGK_TYPES_H */
