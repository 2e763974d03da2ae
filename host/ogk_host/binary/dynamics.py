"""The binary-asteroid model of docs/design/blt.md section 1 in numpy (Xiong & Wang, eqs. 4-10 and 22).

Synodic frame, normalised units (LU = D, TU = T_o / (2 pi), `units.Units`), omega = 1. The primary (mass
fraction 1 - mu) at (-mu, 0, 0), the secondary (mu) at (1 - mu, 0, 0). State x = (x, y, z, vx, vy, vz).
Mass is the fraction m / m0, known in closed form from the burn time flown (it is not a state).

    r'' = -2 omega x r' - omega x (omega x r) + sum_i grad U_i(r - r_i) + a_srp + a_sun + a_thrust   (4, 8)

    U_i = mu_i / s + mu_i R_i^2 [C20_i (3 Z^2 - s^2) / (2 s^5) + 3 C22_i (X^2 - Y^2) / s^5]          (7)
        = mu_i / s + mu_i R_i^2 (rho^T K_i rho) / s^5,  K_i = diag(3 C22 - C20/2, -3 C22 - C20/2, C20)

    a_srp    = -(srp_accel / m) s_hat(t)                          (9, divided by the mass)
    a_sun    = sun_tidal (3 s_hat (s_hat . r) - r)                (10, first-order tidal form)
    a_thrust = (thrust_accel / m) (A + B tau) / |A + B tau|       (22)

with s_hat(t) = (cos phi, sin phi, 0), phi = sun_angle0 + sun_rate t. `Model` holds exactly the fields of
the kernel's ogk_blt_model_t; `kernel_model` builds it from a scenario.

Every function of a position or a state takes arrays with any leading shape (..., 3) / (..., 6).
"""
from __future__ import annotations

import dataclasses
import math
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .scenario import BinaryScenario

FloatArray = NDArray[np.float64]


@dataclasses.dataclass(frozen=True)
class Model:
    """Normalised constants of the model: the kernel's ogk_blt_model_t, field for field."""

    mu: float                                   #: M2 / (M1 + M2), eq. (1)
    body_radius: tuple[float, float] = (0.0, 0.0)   #: impact radii [LU] (0: no impact check)
    ref_radius: tuple[float, float] = (0.0, 0.0)    #: normalising radius of C20/C22 [LU]
    c20: tuple[float, float] = (0.0, 0.0)       #: unnormalised C20 of each body
    c22: tuple[float, float] = (0.0, 0.0)       #: unnormalised C22 of each body
    srp_accel: float = 0.0                      #: p_SR A C_R / (m0 ACC) [LU/TU^2]
    sun_angle0: float = 0.0                     #: phi(0) [rad]
    sun_rate: float = 0.0                       #: n_helio TU - 1 [rad/TU]
    sun_tidal: float = 0.0                      #: mu_sun TU^2 / d^3 [1/TU^2]
    thrust_accel: float = 0.0                   #: F / (m0 ACC) [LU/TU^2]
    mass_flow: float = 0.0                      #: F TU / (Isp g0 m0) [1/TU]
    step_max: float = 0.0                       #: the kernel integrator's largest step [TU]

    @property
    def mass_fractions(self) -> tuple[float, float]:
        return (1.0 - self.mu, self.mu)

    @property
    def body_positions(self) -> FloatArray:
        """(2, 3): the primary at (-mu, 0, 0), the secondary at (1 - mu, 0, 0)."""
        return np.array([[-self.mu, 0.0, 0.0], [1.0 - self.mu, 0.0, 0.0]])

    @property
    def autonomous(self) -> bool:
        """True when nothing depends on time: no SRP and no Sun (the Jacobi constant is an integral)."""
        return self.srp_accel == 0.0 and self.sun_tidal == 0.0

    def gravity_only(self) -> "Model":
        """The same bodies without SRP, Sun or thrust: the autonomous model of orbits and manifolds."""
        return dataclasses.replace(self, srp_accel=0.0, sun_tidal=0.0, thrust_accel=0.0, mass_flow=0.0)

    def as_dict(self) -> dict[str, Any]:
        """The kernel's field names with plain floats and lists of 2."""
        out: dict[str, Any] = {}
        for f in dataclasses.fields(self):
            v = getattr(self, f.name)
            out[f.name] = [float(v[0]), float(v[1])] if isinstance(v, tuple) else float(v)
        return out

    @classmethod
    def from_dict(cls, data: dict[str, Any]) -> "Model":
        values = {f.name: (tuple(float(x) for x in data[f.name]) if isinstance(data[f.name], (list, tuple))
                           else float(data[f.name])) for f in dataclasses.fields(cls)}
        return cls(**values)


def kernel_model(scenario: BinaryScenario, thrust_n: float, *, gravity: str | None = None, srp: bool,
                 sun: bool, step_max: float) -> dict[str, Any]:
    """The kernel's ogk_blt_model_t for `scenario` with a constant thrust `thrust_n` [N], in normalised
    units (docs/design/blt.md section 1). gravity: "degree2" or "point-mass" (default: the scenario's [gravity]
    model; point-mass zeroes C20 and C22 and keeps the radii). srp / sun: include the SRP (eq. 9) / the
    solar tidal term (eq. 10). step_max [TU]: the kernel integrator's largest step."""
    return model_from_scenario(scenario, thrust_n, gravity=gravity, srp=srp, sun=sun,
                               step_max=step_max).as_dict()


def model_from_scenario(scenario: BinaryScenario, thrust_n: float = 0.0, *, gravity: str | None = None,
                        srp: bool = False, sun: bool = False, step_max: float = 0.0) -> Model:
    """`kernel_model` as a `Model` (defaults: no thrust, gravity only)."""
    if not (math.isfinite(thrust_n) and thrust_n >= 0.0):
        raise ValueError(f"thrust_n must be finite and >= 0, got {thrust_n!r}")
    if not (math.isfinite(step_max) and step_max >= 0.0):
        raise ValueError(f"step_max must be finite and >= 0, got {step_max!r}")
    kind = scenario.gravity.model if gravity is None else gravity
    if kind not in ("degree2", "point-mass"):
        raise ValueError(f"gravity must be 'degree2' or 'point-mass', got {kind!r}")
    u = scenario.units
    bodies = (scenario.gravity.primary, scenario.gravity.secondary)
    lu, tu, acc = u.length_m, u.time_s, u.acceleration_m_s2
    sc, s = scenario.spacecraft, scenario.sun
    degree2 = kind == "degree2"
    return Model(
        mu=u.mu,
        body_radius=(bodies[0].impact_radius_m / lu, bodies[1].impact_radius_m / lu),
        ref_radius=(bodies[0].equal_volume_radius_m / lu, bodies[1].equal_volume_radius_m / lu),
        c20=(bodies[0].c20, bodies[1].c20) if degree2 else (0.0, 0.0),
        c22=(bodies[0].c22, bodies[1].c22) if degree2 else (0.0, 0.0),
        srp_accel=(s.pressure_n_m2 * sc.area_m2 * sc.reflectivity_cr / (sc.mass_kg * acc)) if srp else 0.0,
        sun_angle0=s.angle0_rad,
        sun_rate=s.mean_motion_rad_s * tu - 1.0,
        sun_tidal=(s.mu_m3_s2 * tu * tu / s.distance_m ** 3) if sun else 0.0,
        thrust_accel=thrust_n / (sc.mass_kg * acc),
        mass_flow=thrust_n * tu / (sc.specific_impulse_s * sc.standard_gravity_m_s2 * sc.mass_kg),
        step_max=step_max)


# ---------------------------------------------------------------------------------------- gravity (eq. 7)

def _quadrupole_diag(c20: float, c22: float) -> FloatArray:
    """Diagonal of K with U2 = mu R^2 rho^T K rho / s^5 (trace 0: the field is harmonic)."""
    return np.array([3.0 * c22 - 0.5 * c20, -3.0 * c22 - 0.5 * c20, c20])


def _bodies(model: Model) -> list[tuple[FloatArray, float, float, FloatArray | None]]:
    out = []
    for i, (pos, m) in enumerate(zip(model.body_positions, model.mass_fractions)):
        k = None
        if model.c20[i] != 0.0 or model.c22[i] != 0.0:
            k = _quadrupole_diag(model.c20[i], model.c22[i])
        out.append((pos, m, model.ref_radius[i] ** 2, k))
    return out


def potential(model: Model, r: ArrayLike) -> FloatArray:
    """U(r) = U_1 + U_2 (eqs. 6-7, degree 2, positive sign convention of docs/design/blt.md) [LU^2/TU^2]."""
    r = np.asarray(r, dtype=float)
    total = np.zeros(r.shape[:-1])
    for pos, m, r2, k in _bodies(model):
        rho = r - pos
        s2 = np.einsum("...i,...i->...", rho, rho)
        s = np.sqrt(s2)
        total = total + m / s
        if k is not None:
            q = np.einsum("...i,i,...i->...", rho, k, rho)
            total = total + m * r2 * q / (s2 * s2 * s)
    return total


def gravity(model: Model, r: ArrayLike) -> FloatArray:
    """grad U(r) (..., 3): the gravitational acceleration of both bodies [LU/TU^2]."""
    r = np.asarray(r, dtype=float)
    total = np.zeros(r.shape)
    for pos, m, r2, k in _bodies(model):
        rho = r - pos
        s2 = np.einsum("...i,...i->...", rho, rho)[..., None]
        s = np.sqrt(s2)
        total = total - m * rho / (s2 * s)
        if k is not None:
            krho = k * rho
            q = np.einsum("...i,...i->...", rho, krho)[..., None]
            s5 = s2 * s2 * s
            total = total + m * r2 * (2.0 * krho / s5 - 5.0 * q * rho / (s5 * s2))
    return total


def gravity_gradient(model: Model, r: ArrayLike) -> FloatArray:
    """d(grad U)/dr (..., 3, 3): the analytic Hessian of U (the U_ij of eq. 33) [1/TU^2]."""
    r = np.asarray(r, dtype=float)
    eye = np.eye(3)
    total = np.zeros(r.shape + (3,))
    for pos, m, r2, k in _bodies(model):
        rho = r - pos
        s2 = np.einsum("...i,...i->...", rho, rho)[..., None, None]
        s = np.sqrt(s2)
        s3 = s2 * s
        rr = rho[..., :, None] * rho[..., None, :]
        total = total + m * (3.0 * rr / (s3 * s2) - eye / s3)
        if k is not None:
            krho = k * rho
            q = np.einsum("...i,...i->...", rho, krho)[..., None, None]
            s5 = s3 * s2
            s7 = s5 * s2
            cross = krho[..., :, None] * rho[..., None, :]
            total = total + m * r2 * (2.0 * np.diag(k) / s5 - 10.0 * (cross + np.swapaxes(cross, -1, -2)) / s7
                                      - 5.0 * q * eye / s7 + 35.0 * q * rr / (s7 * s2))
    return total


def effective_potential(model: Model, r: ArrayLike) -> FloatArray:
    """Omega = (x^2 + y^2) / 2 + U: gravity plus the centrifugal potential (omega = 1)."""
    r = np.asarray(r, dtype=float)
    return 0.5 * (r[..., 0] ** 2 + r[..., 1] ** 2) + potential(model, r)


def jacobi(model: Model, state: ArrayLike) -> FloatArray:
    """The Jacobi constant of eq. (5): C = 2 Omega - |v|^2 (an integral of the gravity-only model)."""
    x = np.asarray(state, dtype=float)
    v = x[..., 3:6]
    return 2.0 * effective_potential(model, x[..., 0:3]) - np.einsum("...i,...i->...", v, v)


# ---------------------------------------------------------------------------------------- perturbations

def sun_direction(model: Model, t: ArrayLike) -> FloatArray:
    """s_hat(t) (..., 3): the Sun's direction from the barycentre in the synodic frame (in the mutual
    orbit plane: the heliocentric inclination is ignored, as in the paper)."""
    phi = model.sun_angle0 + model.sun_rate * np.asarray(t, dtype=float)
    return np.stack([np.cos(phi), np.sin(phi), np.zeros_like(phi)], axis=-1)


def srp_acceleration(model: Model, t: ArrayLike, mass: ArrayLike = 1.0) -> FloatArray:
    """Eq. (9) divided by the mass (the paper's print omits it): -(srp_accel / m) s_hat, away from the Sun."""
    m = np.asarray(mass, dtype=float)[..., None]
    return -(model.srp_accel / m) * sun_direction(model, t)


def sun_tidal_acceleration(model: Model, r: ArrayLike, t: ArrayLike) -> FloatArray:
    """Eq. (10) to first order: sun_tidal (3 s_hat (s_hat . r) - r)."""
    r = np.asarray(r, dtype=float)
    sh = sun_direction(model, t)
    proj = np.einsum("...i,...i->...", sh, r)[..., None]
    return model.sun_tidal * (3.0 * sh * proj - r)


def blt_direction(a: ArrayLike, b: ArrayLike, tau: ArrayLike) -> FloatArray:
    """Eq. (22): u_hat = (A + B tau) / |A + B tau|, tau [TU] the time since the burn started."""
    t = np.asarray(tau, dtype=float)[..., None]
    w = np.asarray(a, dtype=float) + np.asarray(b, dtype=float) * t
    return w / np.linalg.norm(w, axis=-1, keepdims=True)


def burn_mass(model: Model, mass_start: float, tau: ArrayLike) -> FloatArray:
    """The closed-form mass fraction during a burn: m(tau) = m_start - mass_flow tau (eq. 8's denominator)."""
    return mass_start - model.mass_flow * np.asarray(tau, dtype=float)


def thrust_acceleration(model: Model, a: ArrayLike, b: ArrayLike, tau: ArrayLike,
                        mass_start: float) -> FloatArray:
    """(thrust_accel / m(tau)) u_hat(tau): the thrust term of eq. (8) with the BLT law (22)."""
    m = burn_mass(model, mass_start, tau)[..., None]
    return (model.thrust_accel / m) * blt_direction(a, b, tau)


# ---------------------------------------------------------------------------------------- equations of motion

@dataclasses.dataclass(frozen=True)
class Burn:
    """A BLT burn in progress: constant vectors A, B (eq. 22) of the synodic frame, started at time
    `start_time` [TU] with mass fraction `mass_start`."""

    a: tuple[float, float, float]
    b: tuple[float, float, float]
    start_time: float
    mass_start: float


def state_derivative(model: Model, t: float, state: ArrayLike, *, mass: float = 1.0,
                     burn: Burn | None = None) -> FloatArray:
    """xdot of eqs. (4) + (8) at time t: gravity, Coriolis and centrifugal terms, SRP and the solar tidal
    term (each when its constant is nonzero), and the BLT thrust during `burn` (whose closed-form mass
    then replaces `mass`)."""
    x = np.asarray(state, dtype=float)
    r, v = x[..., 0:3], x[..., 3:6]
    acc = gravity(model, r)
    acc[..., 0] += r[..., 0] + 2.0 * v[..., 1]
    acc[..., 1] += r[..., 1] - 2.0 * v[..., 0]
    m = mass
    if burn is not None:
        tau = t - burn.start_time
        m = float(burn_mass(model, burn.mass_start, tau))
        if not m > 0.0:
            raise ValueError(f"the mass fraction reached {m:g} during a burn")
        acc = acc + (model.thrust_accel / m) * blt_direction(burn.a, burn.b, tau)
    if model.srp_accel != 0.0:
        acc = acc + srp_acceleration(model, t, m)
    if model.sun_tidal != 0.0:
        acc = acc + sun_tidal_acceleration(model, r, t)
    return np.concatenate([v, acc], axis=-1)


def gravity_derivative(model: Model, state: ArrayLike) -> FloatArray:
    """xdot of the autonomous gravity-only model (eq. 4 with the degree-2 potential)."""
    x = np.asarray(state, dtype=float)
    r, v = x[..., 0:3], x[..., 3:6]
    acc = gravity(model, r)
    acc[..., 0] += r[..., 0] + 2.0 * v[..., 1]
    acc[..., 1] += r[..., 1] - 2.0 * v[..., 0]
    return np.concatenate([v, acc], axis=-1)


#: The Coriolis block of eq. (33): d(acceleration)/d(velocity).
_CORIOLIS = np.array([[0.0, 2.0, 0.0], [-2.0, 0.0, 0.0], [0.0, 0.0, 0.0]])
_CENTRIFUGAL = np.diag([1.0, 1.0, 0.0])


def jacobian(model: Model, state: ArrayLike) -> FloatArray:
    """Gamma of eq. (33) (..., 6, 6): d(xdot)/dx of the gravity-only model, analytic."""
    x = np.asarray(state, dtype=float)
    out = np.zeros(x.shape[:-1] + (6, 6))
    out[..., 0:3, 3:6] = np.eye(3)
    out[..., 3:6, 0:3] = gravity_gradient(model, x[..., 0:3]) + _CENTRIFUGAL
    out[..., 3:6, 3:6] = _CORIOLIS
    return out


def variational_derivative(model: Model, t: float, y: ArrayLike) -> FloatArray:
    """The 42 equations of the state and its 6x6 STM, Phi' = Gamma(x) Phi (eqs. 32-33), gravity only.

    y = (x (6), Phi row-major (36)). Written for solve_ivp (`t` unused: the model is autonomous)."""
    y = np.asarray(y, dtype=float)
    x = y[0:6]
    phi = y[6:42].reshape(6, 6)
    g = gravity_gradient(model, x[0:3])
    dphi = np.empty((6, 6))
    dphi[0:3] = phi[3:6]
    dphi[3:6] = (g + _CENTRIFUGAL) @ phi[0:3] + _CORIOLIS @ phi[3:6]
    return np.concatenate([gravity_derivative(model, x), dphi.ravel()])


# ---------------------------------------------------------------------------------------- fast scalar path

class GravityField:
    """The gravity-only right-hand sides for solve_ivp, written on Python floats (one state at a time,
    ~5x faster than the vectorised functions above, which stay the reference: the tests compare them).

    `derivative(t, x)`: eq. (4); `variational(t, y)`: eq. (4) with the STM of eqs. (32)-(33)."""

    def __init__(self, model: Model) -> None:
        self.model = model
        self._bodies: list[tuple[float, float, float, float, float, float]] = []
        for pos, m, r2, k in _bodies(model):
            kx, ky, kz = (0.0, 0.0, 0.0) if k is None else (float(k[0]), float(k[1]), float(k[2]))
            self._bodies.append((float(pos[0]), m, m * r2 if k is not None else 0.0, kx, ky, kz))

    def _field(self, x: float, y: float, z: float, hessian: bool) -> tuple[float, ...]:
        ax = ay = az = 0.0
        hxx = hxy = hxz = hyy = hyz = hzz = 0.0
        for px, m, c, kx, ky, kz in self._bodies:
            dx = x - px
            s2 = dx * dx + y * y + z * z
            s = math.sqrt(s2)
            i3 = m / (s2 * s)
            ax -= i3 * dx
            ay -= i3 * y
            az -= i3 * z
            if hessian:
                i5 = 3.0 * i3 / s2
                hxx += i5 * dx * dx - i3
                hyy += i5 * y * y - i3
                hzz += i5 * z * z - i3
                hxy += i5 * dx * y
                hxz += i5 * dx * z
                hyz += i5 * y * z
            if c != 0.0:
                kdx, kdy, kdz = kx * dx, ky * y, kz * z
                q = dx * kdx + y * kdy + z * kdz
                s5 = s2 * s2 * s
                s7 = s5 * s2
                f2 = 2.0 * c / s5
                f5 = 5.0 * c * q / s7
                ax += f2 * kdx - f5 * dx
                ay += f2 * kdy - f5 * y
                az += f2 * kdz - f5 * z
                if hessian:
                    f10 = 10.0 * c / s7
                    f35 = 35.0 * c * q / (s7 * s2)
                    hxx += f2 * kx - f10 * 2.0 * kdx * dx - f5 + f35 * dx * dx
                    hyy += f2 * ky - f10 * 2.0 * kdy * y - f5 + f35 * y * y
                    hzz += f2 * kz - f10 * 2.0 * kdz * z - f5 + f35 * z * z
                    hxy += -f10 * (kdx * y + dx * kdy) + f35 * dx * y
                    hxz += -f10 * (kdx * z + dx * kdz) + f35 * dx * z
                    hyz += -f10 * (kdy * z + y * kdz) + f35 * y * z
        return ax, ay, az, hxx, hxy, hxz, hyy, hyz, hzz

    def derivative(self, t: float, s: FloatArray) -> FloatArray:
        x, y, z, vx, vy, vz = (float(v) for v in s[0:6])
        ax, ay, az = self._field(x, y, z, False)[0:3]
        return np.array([vx, vy, vz, ax + x + 2.0 * vy, ay + y - 2.0 * vx, az])

    def variational(self, t: float, s: FloatArray) -> FloatArray:
        x, y, z, vx, vy, vz = (float(v) for v in s[0:6])
        ax, ay, az, hxx, hxy, hxz, hyy, hyz, hzz = self._field(x, y, z, True)
        phi = s[6:42].reshape(6, 6)
        h = np.array([[hxx + 1.0, hxy, hxz], [hxy, hyy + 1.0, hyz], [hxz, hyz, hzz]])
        out = np.empty(42)
        out[0:6] = (vx, vy, vz, ax + x + 2.0 * vy, ay + y - 2.0 * vx, az)
        d = out[6:42].reshape(6, 6)
        d[0:3] = phi[3:6]
        d[3:6] = h @ phi[0:3]
        d[3] += 2.0 * phi[4]
        d[4] -= 2.0 * phi[3]
        return out
