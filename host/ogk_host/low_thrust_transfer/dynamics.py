"""Heliocentric two-body dynamics with mass, costates and variational equations (paper 000, sec. 2).

State-costate vector z (14) = [r (3), v (3), m, lambda_r (3), lambda_v (3), lambda_m], normalised units.
  eq. (1):  r' = v,  v' = g(r) + u T/m alpha,  m' = -u T/c,   g(r) = -mu r/|r|^3
  eq. (6):  lambda_r' = -G(r)^T lambda_v,  lambda_v' = -lambda_r,  lambda_m' = u T/m^2 lambda_v^T alpha
  eq. (8):  alpha = -lambda_v/|lambda_v|
  eq. (10): S = 1 - c |lambda_v|/m - lambda_m
With the smoothing of eq. (48), J = T/c int [u - zeta u (1 - u)] dt, the u-dependent part of the
Hamiltonian is T/c [zeta u^2 + (S - zeta) u], minimised on [0, 1] by u = clip((zeta - S)/(2 zeta), 0, 1);
zeta = 0 gives the bang-off-bang law (11). The costate equations do not change with zeta (the running
cost does not depend on the state).

Functions taking `z` accept a single (14,) vector or a stack (..., 14) where that is noted.
"""
from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from .scenario import NormalisedProblem

FloatArray = NDArray[np.float64]

N_STATE = 7
N_Z = 14
N_PARAM = 7   # unknown initial costates lambda_0


def switching_function(z: FloatArray, exhaust_velocity: float) -> FloatArray:
    """Eq. (10) S = 1 - c |lambda_v|/m - lambda_m; z of shape (..., 14)."""
    lam_v = np.linalg.norm(z[..., 10:13], axis=-1)
    return 1.0 - exhaust_velocity * lam_v / z[..., 6] - z[..., 13]


def switching_function_rate(z: FloatArray, problem: NormalisedProblem) -> FloatArray:
    """Eq. (15) dS/dt = -c/(m |lambda_v|) lambda_v^T lambda_v' = c lambda_v^T lambda_r/(m |lambda_v|).

    Continuous across a switch (the u-terms of m' and lambda_m' cancel); z of shape (..., 14).
    """
    lam_v = z[..., 10:13]
    return (problem.exhaust_velocity * np.sum(lam_v * z[..., 7:10], axis=-1)
            / (z[..., 6] * np.linalg.norm(lam_v, axis=-1)))


def smoothed_throttle(switching: FloatArray | float, zeta: float) -> FloatArray:
    """Minimiser of zeta u^2 + (S - zeta) u on [0, 1] (eq. 48); zeta = 0 gives eq. (11)."""
    s = np.asarray(switching, dtype=np.float64)
    if zeta <= 0.0:
        return np.where(s < 0.0, 1.0, 0.0)
    return np.clip((zeta - s) / (2.0 * zeta), 0.0, 1.0)


def thrust_direction(z: FloatArray) -> FloatArray:
    """Eq. (8) alpha = -lambda_v/|lambda_v|; z of shape (..., 14)."""
    lam_v = z[..., 10:13]
    return -lam_v / np.linalg.norm(lam_v, axis=-1, keepdims=True)


def rhs(z: FloatArray, throttle: float, problem: NormalisedProblem) -> FloatArray:
    """dz/dt for a given throttle u (eqs. 1, 6, 8)."""
    r = z[0:3]
    m = z[6]
    lam_r = z[7:10]
    lam_v = z[10:13]
    mu = problem.mu
    thrust = problem.max_thrust
    r2 = r @ r
    r_norm = np.sqrt(r2)
    lam_v_norm = np.sqrt(lam_v @ lam_v)
    mu_r3 = mu / (r2 * r_norm)
    # G(r) lambda_v = mu (3 r (r.lambda_v)/r^5 - lambda_v/r^3), G symmetric
    g_lam_v = mu_r3 * (3.0 * (r @ lam_v) / r2 * r - lam_v)
    dz = np.empty(N_Z)
    dz[0:3] = z[3:6]
    dz[3:6] = -mu_r3 * r - (throttle * thrust / (m * lam_v_norm)) * lam_v
    dz[6] = -throttle * thrust / problem.exhaust_velocity
    dz[7:10] = -g_lam_v
    dz[10:13] = -lam_r
    dz[13] = -throttle * thrust * lam_v_norm / (m * m)
    return dz


def jacobian(z: FloatArray, throttle: float, problem: NormalisedProblem) -> FloatArray:
    """d(dz/dt)/dz at fixed throttle u (14 x 14)."""
    r = z[0:3]
    m = z[6]
    lam_v = z[10:13]
    mu = problem.mu
    thrust = problem.max_thrust
    r2 = r @ r
    r_norm = np.sqrt(r2)
    lam_v_norm = np.sqrt(lam_v @ lam_v)
    lam_hat = lam_v / lam_v_norm
    mu_r3 = mu / (r2 * r_norm)
    eye3 = np.eye(3)
    rr = np.outer(r, r) / r2
    gravity_gradient = mu_r3 * (3.0 * rr - eye3)          # G(r)
    r_dot_l = (r @ lam_v) / r2
    # d(G lambda_v)/dr = 3 mu/r^5 [ (r.l) I + r l^T + l r^T - 5 (r.l) r r^T / r^2 ]
    d_g_lam_dr = 3.0 * mu_r3 / r2 * ((r @ lam_v) * eye3 + np.outer(r, lam_v) + np.outer(lam_v, r)
                                     - 5.0 * r_dot_l * np.outer(r, r))
    a = np.zeros((N_Z, N_Z))
    a[0:3, 3:6] = eye3
    a[3:6, 0:3] = gravity_gradient
    a[10:13, 7:10] = -eye3
    a[7:10, 0:3] = -d_g_lam_dr
    a[7:10, 10:13] = -gravity_gradient
    if throttle != 0.0:
        ut = throttle * thrust
        a[3:6, 6] = ut / (m * m) * lam_hat
        a[3:6, 10:13] = -ut / (m * lam_v_norm) * (eye3 - np.outer(lam_hat, lam_hat))
        a[13, 6] = 2.0 * ut * lam_v_norm / (m * m * m)
        a[13, 10:13] = -ut / (m * m) * lam_hat
    return a


def throttle_sensitivity(z: FloatArray, problem: NormalisedProblem) -> FloatArray:
    """dS/dz (14,), the row vector S_z of eqs. (24)-(25) extended to the full state-costate."""
    m = z[6]
    lam_v = z[10:13]
    lam_v_norm = np.sqrt(lam_v @ lam_v)
    c = problem.exhaust_velocity
    s_z = np.zeros(N_Z)
    s_z[6] = c * lam_v_norm / (m * m)
    s_z[10:13] = -c / (m * lam_v_norm) * lam_v
    s_z[13] = -1.0
    return s_z


def rhs_du(z: FloatArray, problem: NormalisedProblem) -> FloatArray:
    """d(dz/dt)/du (14,)."""
    m = z[6]
    lam_v = z[10:13]
    lam_v_norm = np.sqrt(lam_v @ lam_v)
    thrust = problem.max_thrust
    f_u = np.zeros(N_Z)
    f_u[3:6] = -thrust / (m * lam_v_norm) * lam_v
    f_u[6] = -thrust / problem.exhaust_velocity
    f_u[13] = -thrust * lam_v_norm / (m * m)
    return f_u


def smoothed_rhs_with_stm(z_phi: FloatArray, zeta: float, problem: NormalisedProblem,
                          ) -> FloatArray:
    """d/dt [z, Phi] for the smoothed problem (zeta > 0), Phi = dz/dlambda_0 (14 x 7).

    The throttle is a function of z, so the variational matrix gains f_u (du/dS) S_z where u is
    unsaturated.
    """
    z = z_phi[:N_Z]
    phi = z_phi[N_Z:].reshape(N_Z, N_PARAM)
    s = float(switching_function(z, problem.exhaust_velocity))
    u = float(smoothed_throttle(s, zeta))
    a = jacobian(z, u, problem)
    out = np.empty_like(z_phi)
    out[:N_Z] = rhs(z, u, problem)
    d_phi = a @ phi
    if 0.0 < u < 1.0:
        d_phi += np.outer(rhs_du(z, problem), (-0.5 / zeta) * (throttle_sensitivity(z, problem) @ phi))
    out[N_Z:] = d_phi.ravel()
    return out


def fixed_throttle_rhs_with_stm(z_phi: FloatArray, throttle: float, problem: NormalisedProblem,
                                ) -> FloatArray:
    """d/dt [z, Phi] on one bang-off-bang arc (u constant)."""
    z = z_phi[:N_Z]
    phi = z_phi[N_Z:].reshape(N_Z, N_PARAM)
    out = np.empty_like(z_phi)
    out[:N_Z] = rhs(z, throttle, problem)
    out[N_Z:] = (jacobian(z, throttle, problem) @ phi).ravel()
    return out


def switch_jump(z: FloatArray, phi: FloatArray, throttle_before: float, throttle_after: float,
                problem: NormalisedProblem) -> FloatArray:
    """STM across a switch, eq. (24)/(B.4): Phi+ = [I + (f+ - f-) S_z / S'] Phi-."""
    f_jump = (throttle_after - throttle_before) * rhs_du(z, problem)
    s_rate = float(switching_function_rate(z, problem))
    return phi + np.outer(f_jump, throttle_sensitivity(z, problem) @ phi) / s_rate
