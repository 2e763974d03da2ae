/* thrust_cmd.c -- the one thrust-direction command of every law
 * (ogk/thrust_cmd.h, ogk/types.h; docs/design/kernel-core.md, "Thrust commands"). */
#include "ogk/thrust_cmd.h"

#include <math.h>
#include <stdbool.h>
#include <string.h>

#include "ogk/mathutil.h"
#include "../ogk_checks.h"
#include "../thrust_cmd_internal.h"

/* true for a frame of ogk_frame_t. */
static bool frame_known(ogk_frame_t frame)
{
    bool known;
    switch (frame) {
    case OGK_FRAME_RTN:
    case OGK_FRAME_INERTIAL:
    case OGK_FRAME_SYNODIC:
        known = true;
        break;
    case OGK_FRAME_COUNT:
    default:
        known = false;
        break;
    }
    return known;
}

/* u of the angles, unchecked (any finite angles give a finite unit vector). */
static void unit_of_angles(ogk_real_t alpha, ogk_real_t beta, ogk_real_t *u)
{
    const ogk_real_t cb = OGK_COS(beta);
    u[0] = cb * OGK_SIN(alpha);
    u[1] = cb * OGK_COS(alpha);
    u[2] = OGK_SIN(beta);
}

/* The angles of a unit r-t-n vector, unchecked: alpha in (-pi, pi] (0 along
 * +-n), beta in [-pi/2, pi/2]. */
static ogk_real_t alpha_of_unit(const ogk_real_t *u)
{
    return OGK_ATAN2(u[0], u[1]);
}

static ogk_real_t beta_of_unit(const ogk_real_t *u)
{
    return OGK_ATAN2(u[2], OGK_HYPOT(u[0], u[1]));
}

/* Checks a direction (finite, unit within the tolerance) and writes u / |u|
 * to out (may alias u). */
static ogk_status unit_checked(const ogk_real_t *u, ogk_real_t *out)
{
    ogk_status st = OGK_OK;
    if (!ogk_i_all_finite(u, 3u)) {
        st = OGK_E_NONFINITE;
    } else {
        /* hypot: no overflow for finite components, so a huge vector is
         * rejected as not unit instead of becoming inf */
        const ogk_real_t norm = OGK_HYPOT(OGK_HYPOT(u[0], u[1]), u[2]);
        if (!(OGK_FABS(norm - OGK_R(1.0)) <= OGK_THRUST_CMD_UNIT_TOL)) {
            st = OGK_E_RANGE;
        } else {
            out[0] = u[0] / norm;
            out[1] = u[1] / norm;
            out[2] = u[2] / norm;
        }
    }
    return st;
}

/* Checks the time and the throttle of a command. */
static ogk_status time_throttle_checked(ogk_real_t t_s, ogk_real_t throttle)
{
    ogk_status st = OGK_OK;
    if (!isfinite(t_s) || !isfinite(throttle)) {
        st = OGK_E_NONFINITE;
    } else if ((throttle < OGK_R(0.0)) || (throttle > OGK_R(1.0))) {
        st = OGK_E_RANGE;
    } else {
        /* usable */
    }
    return st;
}

/* Writes the fields every command has (cmd zeroed first, so padding and the
 * fields the frame does not use are 0). */
static void fill_common(ogk_thrust_cmd_t *cmd, ogk_real_t t_s, ogk_frame_t frame, ogk_real_t throttle, /* NOLINT(bugprone-easily-swappable-parameters): the field order of ogk_thrust_cmd_t; static, every caller in this file names the fields it passes; each field checked by test_thrust_cmd.c */
                        uint32_t flags, uint32_t law_flags) /* NOLINT(bugprone-easily-swappable-parameters): as above */
{
    (void)memset(cmd, 0, sizeof *cmd); /* returns cmd: nothing to check */
    cmd->t_s = t_s;
    cmd->frame = frame;
    cmd->flags = flags;
    cmd->law_flags = law_flags;
    cmd->throttle = ((flags & OGK_THRUST_FLAG_ENGINE_ON) != 0u) ? throttle : OGK_R(0.0);
}

void ogk_i_thrust_cmd_angles(ogk_thrust_cmd_t *cmd, ogk_real_t t_s, ogk_real_t alpha_rad, ogk_real_t beta_rad, /* NOLINT(bugprone-easily-swappable-parameters): the argument order of ogk_thrust_cmd_from_angles (ogk/thrust_cmd.h) and the field order of ogk_thrust_cmd_t; each field checked by test_thrust_cmd.c and the laws' tests */
                             ogk_real_t throttle, uint32_t flags, uint32_t law_flags)
{
    fill_common(cmd, t_s, OGK_FRAME_RTN, throttle, flags, law_flags);
    cmd->alpha_rad = alpha_rad;
    cmd->beta_rad = beta_rad;
    unit_of_angles(alpha_rad, beta_rad, cmd->u);
}

void ogk_i_thrust_cmd_unit(ogk_thrust_cmd_t *cmd, ogk_real_t t_s, ogk_frame_t frame, const ogk_real_t *u,
                           ogk_real_t throttle, uint32_t flags, uint32_t law_flags)
{
    const ogk_real_t u0 = u[0];
    const ogk_real_t u1 = u[1];
    const ogk_real_t u2 = u[2];
    fill_common(cmd, t_s, frame, throttle, flags, law_flags);
    cmd->u[0] = u0;
    cmd->u[1] = u1;
    cmd->u[2] = u2;
    if (frame == OGK_FRAME_RTN) {
        cmd->alpha_rad = alpha_of_unit(cmd->u);
        cmd->beta_rad = beta_of_unit(cmd->u);
    }
}

void ogk_i_thrust_cmd_safe(ogk_thrust_cmd_t *cmd, ogk_real_t t_s, ogk_frame_t frame, uint32_t law_flags)
{
    fill_common(cmd, isfinite(t_s) ? t_s : OGK_R(0.0), frame, OGK_R(0.0), OGK_THRUST_FLAG_SAFE, law_flags);
    if (frame == OGK_FRAME_RTN) {
        cmd->u[1] = OGK_R(1.0); /* alpha = beta = 0: along t */
    } else {
        cmd->u[0] = OGK_R(1.0);
    }
}

/* Checks a pair of angles (finite, within OGK_ANGLE_LIMIT). */
static ogk_status angles_checked(ogk_real_t alpha_rad, ogk_real_t beta_rad)
{
    ogk_status st = OGK_OK;
    if (!isfinite(alpha_rad) || !isfinite(beta_rad)) {
        st = OGK_E_NONFINITE;
    } else if ((OGK_FABS(alpha_rad) > OGK_ANGLE_LIMIT) || (OGK_FABS(beta_rad) > OGK_ANGLE_LIMIT)) {
        st = OGK_E_RANGE;
    } else {
        /* usable */
    }
    return st;
}

ogk_status ogk_thrust_cmd_angles_to_unit(ogk_real_t alpha_rad, ogk_real_t beta_rad, ogk_real_t u[3])
{
    ogk_status st;
    if (u == NULL) {
        st = OGK_E_NULL;
    } else {
        st = angles_checked(alpha_rad, beta_rad);
        if (st == OGK_OK) {
            unit_of_angles(alpha_rad, beta_rad, u);
        }
    }
    return st;
}

ogk_status ogk_thrust_cmd_unit_to_angles(const ogk_real_t u[3], ogk_real_t *alpha_rad, ogk_real_t *beta_rad)
{
    ogk_status st;
    if ((u == NULL) || (alpha_rad == NULL) || (beta_rad == NULL)) {
        st = OGK_E_NULL;
    } else {
        ogk_real_t n[3];
        st = unit_checked(u, n);
        if (st == OGK_OK) {
            *alpha_rad = alpha_of_unit(n);
            *beta_rad = beta_of_unit(n);
        }
    }
    return st;
}

ogk_status ogk_thrust_cmd_from_angles(ogk_real_t t_s, ogk_real_t alpha_rad, ogk_real_t beta_rad,
                                      ogk_real_t throttle, uint32_t flags, uint32_t law_flags,
                                      ogk_thrust_cmd_t *cmd)
{
    ogk_status st;
    if (cmd == NULL) {
        st = OGK_E_NULL;
    } else {
        st = angles_checked(alpha_rad, beta_rad);
        if (st == OGK_OK) {
            st = time_throttle_checked(t_s, throttle);
        }
        if (st == OGK_OK) {
            ogk_i_thrust_cmd_angles(cmd, t_s, alpha_rad, beta_rad, throttle, flags, law_flags);
        }
    }
    return st;
}

ogk_status ogk_thrust_cmd_from_unit(ogk_real_t t_s, ogk_frame_t frame, const ogk_real_t u[3],
                                    ogk_real_t throttle, uint32_t flags, uint32_t law_flags,
                                    ogk_thrust_cmd_t *cmd)
{
    ogk_status st;
    ogk_real_t n[3];
    if ((u == NULL) || (cmd == NULL)) {
        st = OGK_E_NULL;
    } else if (!frame_known(frame)) {
        st = OGK_E_FRAME;
    } else {
        st = unit_checked(u, n);
        if (st == OGK_OK) {
            st = time_throttle_checked(t_s, throttle);
        }
        if (st == OGK_OK) {
            ogk_i_thrust_cmd_unit(cmd, t_s, frame, n, throttle, flags, law_flags);
        }
    }
    return st;
}

ogk_status ogk_thrust_cmd_safe(ogk_real_t t_s, ogk_frame_t frame, uint32_t law_flags,
                               ogk_thrust_cmd_t *cmd)
{
    ogk_status st = OGK_OK;
    if (cmd == NULL) {
        st = OGK_E_NULL;
    } else if (!frame_known(frame)) {
        st = OGK_E_FRAME;
    } else {
        ogk_i_thrust_cmd_safe(cmd, t_s, frame, law_flags);
    }
    return st;
}

/* r-t-n components of an inertial vector at (xi, phi): the rows of the
 * r-t-n axes in I (ogk/types.h). */
static void inertial_to_rtn(const ogk_real_t *u_i, ogk_real_t xi, ogk_real_t phi, ogk_real_t *u_rtn)
{
    const ogk_real_t cx = OGK_COS(xi);
    const ogk_real_t sx = OGK_SIN(xi);
    const ogk_real_t cp = OGK_COS(phi);
    const ogk_real_t sp = OGK_SIN(phi);
    u_rtn[0] = (cp * cx * u_i[0]) + (cp * sx * u_i[1]) + (sp * u_i[2]);
    u_rtn[1] = (-sx * u_i[0]) + (cx * u_i[1]);
    u_rtn[2] = (-sp * cx * u_i[0]) - (sp * sx * u_i[1]) + (cp * u_i[2]);
}

ogk_status ogk_i_thrust_cmd_rtn_direction(const ogk_thrust_cmd_t *in, const ogk_nav_state_t *nav,
                                          ogk_real_t ab[2], ogk_real_t *u_rtn)
{
    ogk_status st = time_throttle_checked(in->t_s, in->throttle);

    if (st != OGK_OK) {
        /* the time / throttle check's status */
    } else if (in->frame == OGK_FRAME_RTN) {
        if (!isfinite(in->alpha_rad) || !isfinite(in->beta_rad)) {
            st = OGK_E_NONFINITE;
        } else {
            ab[0] = in->alpha_rad;
            ab[1] = in->beta_rad;
            if (u_rtn != NULL) {
                unit_of_angles(ab[0], ab[1], u_rtn);
            }
        }
    } else if (in->frame == OGK_FRAME_INERTIAL) {
        ogk_real_t n[3];
        st = unit_checked(in->u, n);
        if (st != OGK_OK) {
            /* the direction check's status */
        } else if (!isfinite(nav->xi_rad) || !isfinite(nav->phi_rad)) {
            st = OGK_E_NONFINITE;
        } else if ((OGK_FABS(nav->xi_rad) > OGK_ANGLE_LIMIT) || (OGK_FABS(nav->phi_rad) > OGK_ANGLE_LIMIT)) {
            st = OGK_E_RANGE;
        } else {
            ogk_real_t u[3];
            inertial_to_rtn(n, nav->xi_rad, nav->phi_rad, u);
            ab[0] = alpha_of_unit(u);
            ab[1] = beta_of_unit(u);
            if (u_rtn != NULL) {
                u_rtn[0] = u[0];
                u_rtn[1] = u[1];
                u_rtn[2] = u[2];
            }
        }
    } else {
        st = OGK_E_FRAME; /* synodic: its angle is not known here; or not a frame */
    }
    return st;
}

/* ogk_thrust_cmd_to_rtn on non-NULL arguments. */
static ogk_status to_rtn_checked(const ogk_thrust_cmd_t *in, const ogk_nav_state_t *nav,
                                 ogk_thrust_cmd_t *out)
{
    ogk_real_t ab[2];
    ogk_real_t u[3];
    const ogk_status st = ogk_i_thrust_cmd_rtn_direction(in, nav, ab, u);
    if (st == OGK_OK) {
        const ogk_real_t t_s = in->t_s;
        const ogk_real_t throttle = in->throttle;
        const uint32_t flags = in->flags;
        const uint32_t law_flags = in->law_flags;
        fill_common(out, t_s, OGK_FRAME_RTN, throttle, flags, law_flags);
        out->alpha_rad = ab[0];
        out->beta_rad = ab[1];
        out->u[0] = u[0];
        out->u[1] = u[1];
        out->u[2] = u[2];
    }
    return st;
}

ogk_status ogk_thrust_cmd_to_rtn(const ogk_thrust_cmd_t *in, const ogk_nav_state_t *nav,
                                 ogk_thrust_cmd_t *out)
{
    ogk_status st;
    if ((in == NULL) || (nav == NULL) || (out == NULL)) {
        st = OGK_E_NULL;
    } else {
        st = to_rtn_checked(in, nav, out);
    }
    return st;
}

ogk_status ogk_thrust_cmd_synodic_to_inertial(const ogk_thrust_cmd_t *in, ogk_real_t angle_rad,
                                              ogk_thrust_cmd_t *out)
{
    ogk_status st;
    ogk_real_t n[3];
    if ((in == NULL) || (out == NULL)) {
        st = OGK_E_NULL;
    } else if (in->frame != OGK_FRAME_SYNODIC) {
        st = OGK_E_FRAME;
    } else if (!isfinite(angle_rad)) {
        st = OGK_E_NONFINITE;
    } else if (OGK_FABS(angle_rad) > OGK_ANGLE_LIMIT) {
        st = OGK_E_RANGE;
    } else {
        st = unit_checked(in->u, n);
        if (st == OGK_OK) {
            st = time_throttle_checked(in->t_s, in->throttle);
        }
        if (st == OGK_OK) {
            const ogk_real_t c = OGK_COS(angle_rad);
            const ogk_real_t s = OGK_SIN(angle_rad);
            const ogk_real_t t_s = in->t_s;
            const ogk_real_t throttle = in->throttle;
            const uint32_t flags = in->flags;
            const uint32_t law_flags = in->law_flags;
            fill_common(out, t_s, OGK_FRAME_INERTIAL, throttle, flags, law_flags);
            out->u[0] = (c * n[0]) - (s * n[1]);
            out->u[1] = (s * n[0]) + (c * n[1]);
            out->u[2] = n[2];
        }
    }
    return st;
}
