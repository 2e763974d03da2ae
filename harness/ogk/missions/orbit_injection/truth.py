"""Truth models of the LEO-to-GEO injection burn, vectorised over Monte Carlo runs.

Pontani & Celani 2021 (seeds/004), sec. 2 (eqs. 3-6, 9-18), 5.4 (eqs. 49-52) and 6 (eqs. 53, 55).
Nothing here calls the kernel: the frames and the thrust geometry are built independently in numpy
(the tests compare them with the kernel's CPD geometry and with vector constructions).

Arrays are component-major: a state X has shape (n_state, N) and X[i] is one component for all N
runs, so every operation is one numpy call over the runs. Units SI (m, s, kg, rad, N, N m).

6-DOF state (16):
  0-5   r, xi, phi, v_r, v_t, v_n                  eqs. (3)-(6)
  6-9   q0, q1, q2, q3   quaternion (scalar first) of C_ba = R1(Phi) R2(Theta) R3(Psi) (eq. 9):
                         body components = C_ba @ a components. Same kinematics as eqs. (10)-(12)
                         without their singularity at Theta = +-90 deg (reached by 3-sigma tumbles
                         of Table 4); Euler angles are extracted for navigation.
  10-12 P, Q, R          body rates, eqs. (13)-(15)
  13-15 Mx~, Dy~, Dz~    first-order actuator states, eqs. (16), (18)
The actuator OUTPUTS are sat(state + noise) (eq. 17), the noise being Table 5's actuation error held
over one control step (see docs/guides/sil.md).

Point-mass state (6): r, xi, phi, v_r, v_t, v_n; thrust along the commanded (alpha, beta) exactly.

Thrust (sec. 6 and eq. 55): T(t) = m0 n0 [1 + f(t)], f(t) = sum_k a_k sin(2 k pi t / t_f*) +
a_{k+5} cos(2 k pi t / t_f*); the mass flow stays nominal (m(t) = m0 - m0 n0 t / c), so only the thrust
(and the TVC torque T l) fluctuates: T/m = n0 c / (c - n0 t) [1 + f(t)].
With a tabulated thrust (sec. 7, scenario [thrust] model = "tabulated") T(t) and m(t) are the
scenario's cubic splines (ogk_host.orbit_injection.scenario.TabulatedThrust, the same functions the
ground tools use): T(t) [1 + f(t)] / m(t), with T = 0 after the table (burnt out).
"""
from __future__ import annotations

import dataclasses
import math
import numpy as np
from numpy.typing import NDArray

from ogk_host.orbit_injection.scenario import OrbitInjectionScenario, TabulatedThrust

F64 = NDArray[np.float64]

# 6-DOF state layout
R_, XI, PHI, VR, VT, VN = range(6)
Q0, Q1, Q2, Q3 = range(6, 10)
RATE_P, RATE_Q, RATE_R = range(10, 13)
ACT_MX, ACT_DY, ACT_DZ = range(13, 16)
N_6DOF = 16
N_POINT_MASS = 6
N_FOURIER = 5           #: harmonics of eq. (55)

#: R_A of sec. 2.2: [a1 a2 a3]^T = R_A [c1 c2 c3]^T, a1 = c2, a2 = -c3, a3 = -c1.
R_A = np.array([[0.0, 1.0, 0.0], [0.0, 0.0, -1.0], [-1.0, 0.0, 0.0]])


@dataclasses.dataclass(frozen=True)
class TruthParams:
    """Vehicle and environment constants of sec. 6 (SI), and the period t_f* of eq. (55)."""

    mu: float               #: [m^3/s^2]
    n0: float               #: initial thrust acceleration [m/s^2]
    exhaust_velocity: float #: c [m/s]
    mass0: float            #: m0 [kg]
    arm0: float             #: l0 [m]
    arm_rate: float         #: ldot [m/s]
    inertia0: tuple[float, float, float]        #: I_x0, I_y0, I_z0 [kg m^2]
    inertia_rate: tuple[float, float, float]    #: Idot [kg m^2/s]
    output_max: tuple[float, float, float]      #: Mbar_x [N m], Deltabar_y, Deltabar_z [rad]
    time_constant: tuple[float, float, float]   #: tau_x, tau_y, tau_z [s]
    fluctuation_period: float                   #: t_f* of eq. (55) [s]
    #: sec. 7: tabulated thrust and mass histories (T(t), m(t) splines); None: the sec. 6 formula
    thrust_table: TabulatedThrust | None = None

    @classmethod
    def from_scenario(cls, scn: OrbitInjectionScenario, tf_nominal_s: float) -> "TruthParams":
        mp, act = scn.mass_properties, scn.actuators
        table = scn.thrust if isinstance(scn.thrust, TabulatedThrust) else None
        return cls(mu=scn.mu_m3_s2, n0=scn.thrust.initial_accel_m_s2,
                   exhaust_velocity=scn.thrust.exhaust_velocity_m_s,
                   mass0=scn.thrust.initial_mass_kg,
                   arm0=mp.tvc_arm_m, arm_rate=mp.tvc_arm_rate_m_s,
                   inertia0=(mp.inertia_x_kg_m2, mp.inertia_y_kg_m2, mp.inertia_z_kg_m2),
                   inertia_rate=(mp.inertia_x_rate_kg_m2_s, mp.inertia_y_rate_kg_m2_s,
                                 mp.inertia_z_rate_kg_m2_s),
                   output_max=(act.roll_torque_max_n_m, act.deflection_y_max_rad,
                               act.deflection_z_max_rad),
                   time_constant=(act.time_constant_x_s, act.time_constant_y_s,
                                  act.time_constant_z_s),
                   fluctuation_period=tf_nominal_s, thrust_table=table)

    @property
    def thrust0(self) -> float:
        """Nominal constant thrust T = n0 m0 [N] (with a table: the thrust at ignition)."""
        return self.n0 * self.mass0

    def thrust_mass(self, t: F64 | float) -> tuple[F64 | float, F64 | float]:
        """Nominal (T(t), m(t)) [N, kg]: T = n0 m0 and m = m0 - (T/c) t (sec. 6), or the tabulated
        histories (sec. 7; T = 0 after the table: burnt out)."""
        if self.thrust_table is None:
            return self.thrust0, self.mass0 - self.mass_flow * t
        return self.thrust_table.thrust_at(t), self.thrust_table.mass_kg_at(t)

    @property
    def mass_flow(self) -> float:
        """Nominal mass flow T / c [kg/s] (also under the eq. 55 fluctuation)."""
        return self.thrust0 / self.exhaust_velocity


# ----------------------------------------------------------------- thrust (sec. 6, eq. 55)
def _fourier_basis(p: TruthParams, t: float) -> list[float]:
    """[sin(k theta)] + [cos(k theta)], k = 1..5, theta = 2 pi t / t_f*, at one time (libm)."""
    theta = (2.0 * math.pi / p.fluctuation_period) * t
    return [math.sin(k * theta) for k in range(1, N_FOURIER + 1)] + \
           [math.cos(k * theta) for k in range(1, N_FOURIER + 1)]


def thrust_factor(p: TruthParams, t: F64 | float, coeffs: F64 | None) -> F64 | float:
    """1 + f(t) of eq. (55) per run; coeffs (10, N) = [a_1..a_5 (sin), a_6..a_10 (cos)] or None.
    t is a scalar (all runs at the same time) or (N,).

    A run's value depends on its own time and coefficients only, never on the other runs of its
    chunk: the per-run-time path (landing steps, where one run's time differs) evaluates the same
    basis at each distinct time with the same operations, in the same order, as the scalar path
    (docs/guides/sil.md, determinism)."""
    if coeffs is None:
        return 1.0
    if np.ndim(t) == 0:
        basis: list[F64] | list[float] = _fourier_basis(p, float(t))
    else:
        times, where = np.unique(np.asarray(t, dtype=np.float64), return_inverse=True)
        table = np.array([_fourier_basis(p, float(u)) for u in times])   # (n_times, 10)
        basis = list(table[where.reshape(-1)].T)                         # 10 x (N,)
    total = 1.0 + coeffs[0] * basis[0]
    for k in range(1, 2 * N_FOURIER):
        total += coeffs[k] * basis[k]
    return total


class ThrustFactorCache:
    """thrust_factor with the last few scalar times remembered: RK4 stages 2 and 3 share a time,
    and stage 4 is the next step's stage 1, so a step costs two evaluations instead of four."""

    def __init__(self, p: TruthParams, coeffs: F64 | None) -> None:
        self._p, self._coeffs = p, coeffs
        self._cache: dict[float, F64 | float] = {}

    def __call__(self, t: F64 | float) -> F64 | float:
        if self._coeffs is None:
            return 1.0
        if np.ndim(t) != 0:
            return thrust_factor(self._p, t, self._coeffs)
        key = float(t)
        value = self._cache.get(key)
        if value is None:
            if len(self._cache) > 4:
                self._cache.clear()
            value = thrust_factor(self._p, key, self._coeffs)
            self._cache[key] = value
        return value


def nominal_accel(p: TruthParams, t: F64) -> F64:
    """Nominal T/m = n0 c / (c - n0 t) [m/s^2], or the tabulated T(t) / m(t)."""
    if p.thrust_table is not None:
        return p.thrust_table.accel_m_s2(t)
    return p.n0 * p.exhaust_velocity / (p.exhaust_velocity - p.n0 * t)


def mass_properties(p: TruthParams, t: F64) -> tuple[F64, F64, F64, F64]:
    """(l, I_x, I_y, I_z) at t, eq. (53)."""
    return (p.arm0 + p.arm_rate * t, p.inertia0[0] + p.inertia_rate[0] * t,
            p.inertia0[1] + p.inertia_rate[1] * t, p.inertia0[2] + p.inertia_rate[2] * t)


# ----------------------------------------------------------------- frames (sec. 2.2, 5.4)
def frame_rotation(axis: int, angle: F64) -> F64:
    """Elementary frame rotation R_axis(angle) (counterclockwise, eq. 9): shape (..., 3, 3);
    [new]^T = R [old]^T, so components transform as v_new = R v_old. axis in {1, 2, 3}."""
    angle = np.asarray(angle, dtype=np.float64)
    c, s = np.cos(angle), np.sin(angle)
    i, j = {1: (1, 2), 2: (2, 0), 3: (0, 1)}[axis]
    k = 3 - i - j
    m = np.zeros(angle.shape + (3, 3))
    m[..., k, k] = 1.0
    m[..., i, i] = c
    m[..., j, j] = c
    m[..., i, j] = s
    m[..., j, i] = -s
    return m


def dcm_body_from_a(psi: F64, theta: F64, phi_roll: F64) -> F64:
    """C_ba = R1(Phi) R2(Theta) R3(Psi) (eq. 9), (..., 3, 3)."""
    return frame_rotation(1, phi_roll) @ frame_rotation(2, theta) @ frame_rotation(3, psi)


def dcm_a_from_rtn(xi: F64, phi: F64) -> F64:
    """N = R_A R3(-xi) R2(phi) (sec. 5.4): a components = N @ (r, t, n) components, (..., 3, 3)."""
    return R_A @ frame_rotation(3, -np.asarray(xi)) @ frame_rotation(2, phi)


def thrust_angles(psi: F64, theta: F64, phi_roll: F64, xi: F64, phi: F64, delta_y: F64,
                  delta_z: F64) -> tuple[F64, F64]:
    """Actual thrust angles (alpha_a, beta_a) of eqs. (49)-(52) with explicit rotation matrices.

    T_a in body axes (eq. 50), mapped to (r, t, n) by (C_ba N)^T (eqs. 49, 51), then identified with
    (cos b sin a, cos b cos a, sin b) (eq. 52)."""
    d_b = np.stack([np.cos(delta_z) * np.cos(delta_y), np.sin(delta_z),
                    np.cos(delta_z) * np.sin(delta_y)], axis=-1)
    c_b_rtn = dcm_body_from_a(psi, theta, phi_roll) @ dcm_a_from_rtn(xi, phi)
    t_rtn = np.einsum("...ji,...j->...i", c_b_rtn, d_b)
    alpha = np.arctan2(t_rtn[..., 0], t_rtn[..., 1])
    beta = np.arctan2(t_rtn[..., 2], np.hypot(t_rtn[..., 0], t_rtn[..., 1]))
    return alpha, beta


def commanded_attitude(alpha: F64, beta: F64, xi: F64, phi: F64) -> tuple[F64, F64]:
    """(Psi_c, Theta_c) putting x_b along (alpha, beta) at (xi, phi): eqs. (38)-(39)."""
    u_rtn = np.stack([np.cos(beta) * np.sin(alpha), np.cos(beta) * np.cos(alpha), np.sin(beta)],
                     axis=-1)
    t_a = np.einsum("...ij,...j->...i", dcm_a_from_rtn(xi, phi), u_rtn)
    return (np.arctan2(t_a[..., 1], t_a[..., 0]),
            np.arctan2(-t_a[..., 2], np.hypot(t_a[..., 0], t_a[..., 1])))


def euler_rates(phi_roll: F64, theta: F64, p: F64, q: F64, r: F64) -> tuple[F64, F64, F64]:
    """(dPhi/dt, dTheta/dt, dPsi/dt) of eqs. (10)-(12)."""
    sf, cf, tt = np.sin(phi_roll), np.cos(phi_roll), np.tan(theta)
    return (p + q * sf * tt + r * cf * tt, q * cf - r * sf, (q * sf + r * cf) / np.cos(theta))


# ----------------------------------------------------------------- quaternions
def quat_from_dcm(c: F64) -> F64:
    """Quaternion (scalar first, (4, ...) component-major) of a DCM (..., 3, 3), Shepperd's
    method; convention C = (q0^2 - |v|^2) I + 2 v v^T - 2 q0 [v x]."""
    c = np.asarray(c, dtype=np.float64)
    tr = np.trace(c, axis1=-2, axis2=-1)
    cand = np.stack([tr, c[..., 0, 0], c[..., 1, 1], c[..., 2, 2]], axis=-1)
    which = np.argmax(cand, axis=-1)
    q = np.zeros((4,) + c.shape[:-2])
    for idx in range(4):
        sel = which == idx
        cs = c[sel]
        if idx == 0:
            q0 = 0.5 * np.sqrt(1.0 + cs[:, 0, 0] + cs[:, 1, 1] + cs[:, 2, 2])
            v = np.stack([cs[:, 1, 2] - cs[:, 2, 1], cs[:, 2, 0] - cs[:, 0, 2],
                          cs[:, 0, 1] - cs[:, 1, 0]]) / (4.0 * q0)
            vals = np.concatenate([q0[None], v])
        else:
            i = idx - 1
            j, k = (i + 1) % 3, (i + 2) % 3
            qi = 0.5 * np.sqrt(1.0 + 2.0 * cs[:, i, i] - cs[:, 0, 0] - cs[:, 1, 1] - cs[:, 2, 2])
            vals = np.zeros((4, cs.shape[0]))
            vals[1 + i] = qi
            vals[0] = (cs[:, j, k] - cs[:, k, j]) / (4.0 * qi)
            vals[1 + j] = (cs[:, i, j] + cs[:, j, i]) / (4.0 * qi)
            vals[1 + k] = (cs[:, i, k] + cs[:, k, i]) / (4.0 * qi)
        q[:, sel] = vals
    return q * np.where(q[0] < 0.0, -1.0, 1.0)


def dcm_from_quat(q: F64) -> F64:
    """C (..., 3, 3) from q (4, ...) (convention of quat_from_dcm)."""
    q0, q1, q2, q3 = q
    return np.stack([
        np.stack([q0 * q0 + q1 * q1 - q2 * q2 - q3 * q3, 2 * (q1 * q2 + q0 * q3),
                  2 * (q1 * q3 - q0 * q2)], axis=-1),
        np.stack([2 * (q1 * q2 - q0 * q3), q0 * q0 - q1 * q1 + q2 * q2 - q3 * q3,
                  2 * (q2 * q3 + q0 * q1)], axis=-1),
        np.stack([2 * (q1 * q3 + q0 * q2), 2 * (q2 * q3 - q0 * q1),
                  q0 * q0 - q1 * q1 - q2 * q2 + q3 * q3], axis=-1)], axis=-2)


def euler_from_quat(q: F64) -> tuple[F64, F64, F64]:
    """(Psi, Theta, Phi) of eq. (9) from q (4, N): Psi = atan2(C01, C00), Theta = -asin(C02),
    Phi = atan2(C12, C22)."""
    q0, q1, q2, q3 = q
    c00 = q0 * q0 + q1 * q1 - q2 * q2 - q3 * q3
    c01 = 2.0 * (q1 * q2 + q0 * q3)
    c02 = 2.0 * (q1 * q3 - q0 * q2)
    c12 = 2.0 * (q2 * q3 + q0 * q1)
    c22 = q0 * q0 - q1 * q1 - q2 * q2 + q3 * q3
    return np.arctan2(c01, c00), -np.arcsin(np.clip(c02, -1.0, 1.0)), np.arctan2(c12, c22)


def quat_from_euler(psi: F64, theta: F64, phi_roll: F64) -> F64:
    """q (4, N) of R1(Phi) R2(Theta) R3(Psi)."""
    return quat_from_dcm(dcm_body_from_a(psi, theta, phi_roll))


# ----------------------------------------------------------------- right-hand sides
def _translational(p: TruthParams, x: F64, accel: F64, d_rtn: tuple[F64, F64, F64],
                   out: F64) -> None:
    """Eqs. (3)-(6) into out[0:6]; d_rtn = unit thrust direction in (r, t, n)."""
    r, phi, vr, vt, vn = x[R_], x[PHI], x[VR], x[VT], x[VN]
    inv_r = 1.0 / r
    tphi = np.tan(phi)
    out[R_] = vr
    out[XI] = vt * inv_r / np.cos(phi)
    out[PHI] = vn * inv_r
    out[VR] = -p.mu * inv_r * inv_r + (vt * vt + vn * vn) * inv_r + accel * d_rtn[0]
    out[VT] = vt * (vn * tphi - vr) * inv_r + accel * d_rtn[1]
    out[VN] = -(vt * vt * tphi + vr * vn) * inv_r + accel * d_rtn[2]


def rtn_from_a(xi: F64, phi: F64, v_a: tuple[F64, F64, F64]) -> tuple[F64, F64, F64]:
    """N^T v_a: (r, t, n) components of a vector given in a (N of sec. 5.4, written out:
    c = R_A^T a, then R2(-phi) R3(xi))."""
    vc1, vc2, vc3 = -v_a[2], v_a[0], -v_a[1]
    sx, cx, sp, cp = np.sin(xi), np.cos(xi), np.sin(phi), np.cos(phi)
    w1 = cx * vc1 + sx * vc2
    w2 = -sx * vc1 + cx * vc2
    return cp * w1 + sp * vc3, w2, -sp * w1 + cp * vc3


def actuator_outputs(p: TruthParams, x: F64, noise: F64 | None) -> tuple[F64, F64, F64]:
    """(M_x, Delta_y, Delta_z) = sat(actuator state + held noise), eq. (17)."""
    mx, dy, dz = x[ACT_MX], x[ACT_DY], x[ACT_DZ]
    if noise is not None:
        mx, dy, dz = mx + noise[0], dy + noise[1], dz + noise[2]
    return (np.clip(mx, -p.output_max[0], p.output_max[0]),
            np.clip(dy, -p.output_max[1], p.output_max[1]),
            np.clip(dz, -p.output_max[2], p.output_max[2]))


def thrust_direction_6dof(x: F64, delta_y: F64, delta_z: F64) -> tuple[F64, F64, F64]:
    """Unit thrust direction in (r, t, n) of the deflected nozzle (eqs. 50-51) for the 6-DOF state:
    d_b of eq. (50) -> a by C_ba^T (quaternion) -> (r, t, n) by N^T."""
    cdz = np.cos(delta_z)
    d0, d1, d2 = cdz * np.cos(delta_y), np.sin(delta_z), cdz * np.sin(delta_y)
    q0, q1, q2, q3 = x[Q0], x[Q1], x[Q2], x[Q3]
    # C^T d = (q0^2 - |v|^2) d + 2 (v.d) v + 2 q0 (v x d)
    s = q0 * q0 - (q1 * q1 + q2 * q2 + q3 * q3)
    vd2 = 2.0 * (q1 * d0 + q2 * d1 + q3 * d2)
    q02 = 2.0 * q0
    a0 = s * d0 + vd2 * q1 + q02 * (q2 * d2 - q3 * d1)
    a1 = s * d1 + vd2 * q2 + q02 * (q3 * d0 - q1 * d2)
    a2 = s * d2 + vd2 * q3 + q02 * (q1 * d1 - q2 * d0)
    return rtn_from_a(x[XI], x[PHI], (a0, a1, a2))


def rhs_6dof(p: TruthParams, t: F64 | float, x: F64, command: F64, noise: F64 | None,
             factor: F64 | float, out: F64) -> None:
    """dX/dt of the 6-DOF model into out (16, N); t scalar or (N,).

    command (3, N): held CPD commands [M_xc, Delta_yc, Delta_zc]; noise (3, N) held actuation
    errors or None; factor: 1 + f(t) of eq. (55) (thrust_factor), scalar or (N,)."""
    mx, dy, dz = actuator_outputs(p, x, noise)
    if p.thrust_table is None:
        thrust = p.thrust0 * factor
        mass = p.mass0 - p.mass_flow * t
    else:
        thrust_nom, mass = p.thrust_mass(t)
        thrust = thrust_nom * factor
    _translational(p, x, thrust / mass, thrust_direction_6dof(x, dy, dz), out)
    arm, ix, iy, iz = mass_properties(p, t)
    wp, wq, wr = x[RATE_P], x[RATE_Q], x[RATE_R]
    tl = thrust * arm
    out[RATE_P] = ((iy - iz) * wq * wr + mx) / ix                              # eq. (13)
    out[RATE_Q] = ((iz - ix) * wp * wr + tl * np.cos(dz) * np.sin(dy)) / iy    # eq. (14)
    out[RATE_R] = ((ix - iy) * wp * wq - tl * np.sin(dz)) / iz                 # eq. (15)
    q0, q1, q2, q3 = x[Q0], x[Q1], x[Q2], x[Q3]
    # dq/dt = 1/2 [ -v.w ; q0 w + v x w ] for C_ba (body rates w = (P, Q, R))
    out[Q0] = -0.5 * (q1 * wp + q2 * wq + q3 * wr)
    out[Q1] = 0.5 * (q0 * wp + q2 * wr - q3 * wq)
    out[Q2] = 0.5 * (q0 * wq + q3 * wp - q1 * wr)
    out[Q3] = 0.5 * (q0 * wr + q1 * wq - q2 * wp)
    tau_x, tau_y, tau_z = p.time_constant
    out[ACT_MX] = (command[0] - x[ACT_MX]) / tau_x                             # eq. (18)
    out[ACT_DY] = (command[1] - x[ACT_DY]) / tau_y                             # eq. (16)
    out[ACT_DZ] = (command[2] - x[ACT_DZ]) / tau_z


def rhs_point_mass(p: TruthParams, t: F64 | float, x: F64, alpha: F64, beta: F64,
                   factor: F64 | float, out: F64) -> None:
    """dX/dt of the point-mass model (eqs. 3-6, thrust along (alpha, beta)) into out (6, N);
    factor = 1 + f(t) of eq. (55)."""
    cb = np.cos(beta)
    accel = nominal_accel(p, t) * factor
    _translational(p, x, accel, (cb * np.sin(alpha), cb * np.cos(alpha), np.sin(beta)), out)


def normalise_quaternion(x: F64) -> None:
    """Renormalises rows Q0..Q3 in place (RK4 drifts off the unit sphere at O(h^5))."""
    norm = np.sqrt(x[Q0] ** 2 + x[Q1] ** 2 + x[Q2] ** 2 + x[Q3] ** 2)
    x[Q0:Q3 + 1] /= norm
