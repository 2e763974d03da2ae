"""Trajectory equations (3)-(6) with real time as 7th state, their partials, and the extremal field.

Canonical units (units.py, mu = 1). Every function is vectorised: x, lam of shape (..., 7),
u of shape (..., 2); outputs carry the same leading axes. They accept complex arrays too (used by the
complex-step derivative tests), except `optimal_control`.

  x = [r, xi, phi, v_r, v_t, v_n, t],  u = [alpha, beta]
  eq. (3)  r' = v_r,  xi' = v_t / (r cos phi),  phi' = v_n / r
  eq. (4)  v_r' = -mu/r^2 + (v_t^2 + v_n^2)/r + a(t) sin(alpha) cos(beta)
  eq. (5)  v_t' = v_t (v_n tan(phi) - v_r)/r + a(t) cos(alpha) cos(beta)
  eq. (6)  v_n' = -v_t^2 tan(phi)/r - v_r v_n/r + a(t) sin(beta)
           t'   = 1
with a(t) = T/m = n0 c / (c - n0 t) (sec. 6) or a tabulated T(t)/m(t) (sec. 7). Here ' is d/dt; in normalised time tau = t/t_f
(eq. 22) every rate is multiplied by t_f.

h(x, lam, u) = lam^T f~(x, u) is the Hamiltonian per unit time; H = t_f h (eq. 23).
"""
from __future__ import annotations

import dataclasses

import numpy as np
from numpy.typing import NDArray

from .scenario import OrbitInjectionScenario, TabulatedThrust
from .units import CanonicalUnits

FloatArray = NDArray[np.float64]

N_X = 7
N_U = 2
R, XI, PHI, VR, VT, VN, TIME = range(N_X)
#: Components constrained at injection (eq. 20): r, phi, v_r, v_t, v_n. xi and t are free.
CONSTRAINED_FINAL = (R, PHI, VR, VT, VN)
FREE_FINAL = (XI, TIME)


@dataclasses.dataclass(frozen=True)
class TabulatedAccel:
    """a(t) = T(t) / m(t) of a tabulated thrust and mass history (scenario.TabulatedThrust, sec. 7)
    in canonical units: t in TU, a in DU/TU^2."""

    thrust: TabulatedThrust
    time_unit_s: float         #: TU [s]
    accel_unit_m_s2: float     #: DU/TU^2 [m/s^2]

    @property
    def end(self) -> float:
        """Last tabulated time [TU]."""
        return self.thrust.end_s / self.time_unit_s

    @property
    def knots(self) -> FloatArray:
        """Interior spline breakpoints [TU] (the third derivative of a jumps there)."""
        return self.thrust.knots_s / self.time_unit_s

    def __call__(self, t: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray]:
        tu, au = self.time_unit_s, self.accel_unit_m_s2
        a, a1, a2 = self.thrust.accel_derivatives(np.real(np.asarray(t)) * tu)
        return a / au, a1 * (tu / au), a2 * (tu * tu / au)


@dataclasses.dataclass(frozen=True)
class Model:
    """Canonical-unit constants of the dynamics.

    Thrust acceleration: the sec. 6 formula a = n0 c / (c - n0 t) (table None), or a tabulated
    T(t) / m(t) (`TabulatedAccel`, sec. 7); then n0 = a(0) and c is the effective exhaust velocity at
    ignition, kept only for the coarse-scan time estimates.
    """

    mu: float                  #: gravitational parameter [DU^3/TU^2] (1 by construction)
    initial_accel: float       #: n0 [DU/TU^2]
    exhaust_velocity: float    #: c [VU]
    table: TabulatedAccel | None = None   #: tabulated a(t); None: the sec. 6 formula

    @classmethod
    def for_scenario(cls, scn: OrbitInjectionScenario, units: CanonicalUnits) -> "Model":
        """Converts the scenario's SI thrust model to canonical units."""
        table = None
        if isinstance(scn.thrust, TabulatedThrust):
            table = TabulatedAccel(scn.thrust, units.time_s, units.accel_m_s2)
        return cls(mu=scn.mu_m3_s2 * units.time_s**2 / units.length_m**3,
                   initial_accel=scn.thrust.initial_accel_m_s2 / units.accel_m_s2,
                   exhaust_velocity=scn.thrust.exhaust_velocity_m_s / units.velocity_m_s,
                   table=table)

    @property
    def max_time(self) -> float:
        """Latest real time an arc may reach [TU]: 0.95 of the burnout time c / n0 (a -> infinity),
        or the end of the thrust table."""
        if self.table is not None:
            return self.table.end
        return 0.95 * (self.exhaust_velocity / self.initial_accel)

    def tau_breaks(self, t_f: float, tau_ref: float, t_ref: float) -> FloatArray | None:
        """The table's knots as normalised times on an arc with t(tau_ref) = t_ref and t' = t_f
        (None without a table): the integrators restart there (`solve_ivp_segmented`)."""
        if self.table is None:
            return None
        return tau_ref + (self.table.knots - t_ref) / t_f

    def accel(self, t: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray]:
        """a(t) and its first two time derivatives: n0 c/(c - n0 t), a^2/c, 2 a^3/c^2 for the sec. 6
        formula, the spline derivatives of T/m for a table."""
        if self.table is not None:
            return self.table(t)
        c = self.exhaust_velocity
        a = self.initial_accel * c / (c - self.initial_accel * t)
        return a, a * a / c, 2.0 * a**3 / (c * c)


def _unpack(x: FloatArray) -> tuple[FloatArray, ...]:
    return tuple(x[..., i] for i in range(N_X))


def state_rate(model: Model, x: FloatArray, u: FloatArray) -> FloatArray:
    """f~(x, u) = dx/dt, eqs. (3)-(6) plus t' = 1."""
    r, _, phi, vr, vt, vn, t = _unpack(x)
    al, be = u[..., 0], u[..., 1]
    a, _, _ = model.accel(t)
    tphi = np.tan(phi)
    out = np.zeros(np.broadcast_shapes(x.shape, u.shape[:-1] + (N_X,)), dtype=np.result_type(x, u))
    out[..., R] = vr
    out[..., XI] = vt / (r * np.cos(phi))
    out[..., PHI] = vn / r
    out[..., VR] = -model.mu / r**2 + (vt**2 + vn**2) / r + a * np.sin(al) * np.cos(be)
    out[..., VT] = vt * (vn * tphi - vr) / r + a * np.cos(al) * np.cos(be)
    out[..., VN] = -vt**2 * tphi / r - vr * vn / r + a * np.sin(be)
    out[..., TIME] = 1.0
    return out


def state_jacobians(model: Model, x: FloatArray, u: FloatArray) -> tuple[FloatArray, FloatArray]:
    """(f_x (..., 7, 7), f_u (..., 7, 2)) of f~(x, u)."""
    r, _, phi, vr, vt, vn, t = _unpack(x)
    al, be = u[..., 0], u[..., 1]
    a, a1, _ = model.accel(t)
    cphi, tphi = np.cos(phi), np.tan(phi)
    sec2 = 1.0 / cphi**2
    sa, ca, sb, cb = np.sin(al), np.cos(al), np.sin(be), np.cos(be)
    lead = np.broadcast_shapes(x.shape[:-1], u.shape[:-1])
    dtype = np.result_type(x, u)
    fx = np.zeros(lead + (N_X, N_X), dtype=dtype)
    fu = np.zeros(lead + (N_X, N_U), dtype=dtype)
    fx[..., R, VR] = 1.0
    fx[..., XI, R] = -vt / (r**2 * cphi)
    fx[..., XI, PHI] = vt * tphi / (r * cphi)
    fx[..., XI, VT] = 1.0 / (r * cphi)
    fx[..., PHI, R] = -vn / r**2
    fx[..., PHI, VN] = 1.0 / r
    fx[..., VR, R] = 2.0 * model.mu / r**3 - (vt**2 + vn**2) / r**2
    fx[..., VR, VT] = 2.0 * vt / r
    fx[..., VR, VN] = 2.0 * vn / r
    fx[..., VR, TIME] = a1 * sa * cb
    fx[..., VT, R] = -vt * (vn * tphi - vr) / r**2
    fx[..., VT, PHI] = vt * vn * sec2 / r
    fx[..., VT, VR] = -vt / r
    fx[..., VT, VT] = (vn * tphi - vr) / r
    fx[..., VT, VN] = vt * tphi / r
    fx[..., VT, TIME] = a1 * ca * cb
    fx[..., VN, R] = (vt**2 * tphi + vr * vn) / r**2
    fx[..., VN, PHI] = -vt**2 * sec2 / r
    fx[..., VN, VR] = -vn / r
    fx[..., VN, VT] = -2.0 * vt * tphi / r
    fx[..., VN, VN] = -vr / r
    fx[..., VN, TIME] = a1 * sb
    fu[..., VR, 0] = a * ca * cb
    fu[..., VR, 1] = -a * sa * sb
    fu[..., VT, 0] = -a * sa * cb
    fu[..., VT, 1] = -a * ca * sb
    fu[..., VN, 1] = a * cb
    return fx, fu


def costate_rate_terms(model: Model, x: FloatArray, lam: FloatArray,
                       u: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray]:
    """(h, h_x (..., 7), h_u (..., 2)); the costate equation is lam' = -h_x (per unit time)."""
    fx, fu = state_jacobians(model, x, u)
    h = np.sum(lam * state_rate(model, x, u), axis=-1)
    h_x = np.einsum("...j,...ji->...i", lam, fx)
    h_u = np.einsum("...j,...ji->...i", lam, fu)
    return h, h_x, h_u


def hamiltonian_hessians(model: Model, x: FloatArray, lam: FloatArray,
                         u: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray]:
    """(h_xx (..., 7, 7), h_xu (..., 7, 2), h_uu (..., 2, 2)) of h = lam^T f~ (hand-derived)."""
    r, _, phi, vr, vt, vn, t = _unpack(x)
    l1, l2, l3, l4, l5, l6, _ = (lam[..., i] for i in range(N_X))
    al, be = u[..., 0], u[..., 1]
    a, a1, a2 = model.accel(t)
    mu = model.mu
    cphi, sphi, tphi = np.cos(phi), np.sin(phi), np.tan(phi)
    sec2 = 1.0 / cphi**2
    sa, ca, sb, cb = np.sin(al), np.cos(al), np.sin(be), np.cos(be)
    lead = np.broadcast_shapes(x.shape[:-1], lam.shape[:-1], u.shape[:-1])
    dtype = np.result_type(x, lam, u)
    hxx = np.zeros(lead + (N_X, N_X), dtype=dtype)
    hxu = np.zeros(lead + (N_X, N_U), dtype=dtype)
    huu = np.zeros(lead + (N_U, N_U), dtype=dtype)
    # thrust-direction projection of the velocity costate and its u-derivatives
    proj = l4 * sa * cb + l5 * ca * cb + l6 * sb
    proj_a = cb * (l4 * ca - l5 * sa)
    proj_b = -l4 * sa * sb - l5 * ca * sb + l6 * cb

    def put(i: int, j: int, value: FloatArray) -> None:
        hxx[..., i, j] = value
        hxx[..., j, i] = value

    put(R, R, 2.0 * l2 * vt / (r**3 * cphi) + 2.0 * l3 * vn / r**3
        + l4 * (-6.0 * mu / r**4 + 2.0 * (vt**2 + vn**2) / r**3)
        + 2.0 * l5 * vt * (vn * tphi - vr) / r**3 - 2.0 * l6 * (vt**2 * tphi + vr * vn) / r**3)
    put(R, PHI, -l2 * vt * tphi / (r**2 * cphi) - l5 * vt * vn * sec2 / r**2
        + l6 * vt**2 * sec2 / r**2)
    put(R, VR, l5 * vt / r**2 + l6 * vn / r**2)
    put(R, VT, -l2 / (r**2 * cphi) - 2.0 * l4 * vt / r**2 - l5 * (vn * tphi - vr) / r**2
        + 2.0 * l6 * vt * tphi / r**2)
    put(R, VN, -l3 / r**2 - 2.0 * l4 * vn / r**2 - l5 * vt * tphi / r**2 + l6 * vr / r**2)
    put(PHI, PHI, l2 * vt * (1.0 + sphi**2) / (r * cphi**3)
        + 2.0 * tphi * sec2 * (l5 * vt * vn - l6 * vt**2) / r)
    put(PHI, VT, l2 * tphi / (r * cphi) + l5 * vn * sec2 / r - 2.0 * l6 * vt * sec2 / r)
    put(PHI, VN, l5 * vt * sec2 / r)
    put(VR, VT, -l5 / r)
    put(VR, VN, -l6 / r)
    put(VT, VT, 2.0 * l4 / r - 2.0 * l6 * tphi / r)
    put(VT, VN, l5 * tphi / r)
    put(VN, VN, 2.0 * l4 / r)
    put(TIME, TIME, a2 * proj)
    hxu[..., TIME, 0] = a1 * proj_a
    hxu[..., TIME, 1] = a1 * proj_b
    huu[..., 0, 0] = -a * cb * (l4 * sa + l5 * ca)
    huu[..., 0, 1] = -a * sb * (l4 * ca - l5 * sa)
    huu[..., 1, 0] = huu[..., 0, 1]
    huu[..., 1, 1] = -a * proj
    return hxx, hxu, huu


def optimal_control(lam: FloatArray) -> FloatArray:
    """Eq. (27): the thrust points along -lambda_v; returns u = [alpha, beta] (..., 2)."""
    l4, l5, l6 = lam[..., VR], lam[..., VT], lam[..., VN]
    alpha = np.arctan2(-l4, -l5)
    beta = -np.arcsin(l6 / np.sqrt(l4**2 + l5**2 + l6**2))
    return np.stack([alpha, beta], axis=-1)


def extremal_rate(model: Model, z: FloatArray) -> FloatArray:
    """d[x; lam]/dt on an extremal (thrust along -lambda_v), z of shape (..., 14), real arithmetic.

    Multiply by t_f for d/dtau.
    """
    x, lam = z[..., :N_X], z[..., N_X:]
    u = optimal_control(lam)
    f = state_rate(model, x, u)
    _, h_x, _ = costate_rate_terms(model, x, lam, u)
    return np.concatenate([f, -h_x], axis=-1)


@dataclasses.dataclass(frozen=True)
class NeighboringMatrices:
    """Matrices of the linear two-point boundary-value problem in normalised time (docs/design/vtd-nog.md).

    dx' = A dx - B dlam + D da,  dlam' = -C dx - A^T dlam - E da,  dmu' = -E^T dx - D^T dlam - F da,
    and the control correction du = -H_uu^-1 (H_ux dx + H_ua da + F_u^T dlam) (eq. 30) = K_x dx + K_lam
    dlam + K_a da. All arrays carry the leading axes of the inputs.
    """

    A: FloatArray        #: (..., 7, 7)
    B: FloatArray        #: (..., 7, 7)
    C: FloatArray        #: (..., 7, 7)
    D: FloatArray        #: (..., 7)
    E: FloatArray        #: (..., 7)
    F: FloatArray        #: (...)
    H_uu: FloatArray     #: (..., 2, 2), normalised time (t_f h_uu)
    K_x: FloatArray      #: (..., 2, 7) = -H_uu^-1 H_ux
    K_lam: FloatArray    #: (..., 2, 7) = -H_uu^-1 F_u^T
    K_a: FloatArray      #: (..., 2)    = -H_uu^-1 H_ua


def neighboring_matrices(model: Model, x: FloatArray, lam: FloatArray, u: FloatArray,
                         t_f: float) -> NeighboringMatrices:
    """A..F of the accessory problem with F = t_f f~, H = t_f h, parameter a = t_f (eq. 22)."""
    fx, fu = state_jacobians(model, x, u)
    f = state_rate(model, x, u)
    h_x = np.einsum("...j,...ji->...i", lam, fx)
    h_u = np.einsum("...j,...ji->...i", lam, fu)
    hxx, hxu, huu = hamiltonian_hessians(model, x, lam, u)
    huu_inv = np.linalg.inv(huu)
    hux = np.swapaxes(hxu, -1, -2)
    fu_t = np.swapaxes(fu, -1, -2)
    # per unit time: the t_f factors of F_x, F_u, H_uu, H_ux, H_xx cancel or factor out
    k_x = -huu_inv @ hux                              # -H_uu^-1 H_ux (t_f cancels)
    k_lam = -huu_inv @ fu_t                           # -H_uu^-1 F_u^T
    k_a = -np.einsum("...ij,...j->...i", huu_inv, h_u) / t_f   # -H_uu^-1 H_ua, H_ua = h_u
    a_mat = t_f * (fx + fu @ k_x)
    b_mat = -t_f * (fu @ k_lam)
    c_mat = t_f * (hxx + hxu @ k_x)
    d_vec = f + t_f * np.einsum("...ij,...j->...i", fu, k_a)
    e_vec = h_x + t_f * np.einsum("...ij,...j->...i", hxu, k_a)
    f_sca = np.einsum("...i,...i->...", h_u, k_a)    # H_aa = 0, H_au = h_u
    return NeighboringMatrices(A=a_mat, B=b_mat, C=c_mat, D=d_vec, E=e_vec, F=f_sca,
                               H_uu=t_f * huu, K_x=k_x, K_lam=k_lam, K_a=k_a)
