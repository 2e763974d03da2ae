"""Predictive model of Starek & Kolmanovsky 2012, eqs. (11)-(13), in normalised units.

State x = (r, theta, v_r, v_theta, m) in the rotating polar frame centred at the Sun; control alpha = the
thrust angle from the local vertical (0: radially outward, pi/2: along the circumferential direction,
sec. 4.1.1), thrust T along alpha. No perturbation: (f_perturb) = 0 in the predictive model (sec. 3.1).

Normalised units (docs/design/nmpc.md, "Units"):
    LU = r_E = 149597871 km (Table A.1), mu_sun = 1, so TU = sqrt(LU^3 / mu) = 5.0226429e6 s = 58.132 d,
    VU = LU / TU = 29.784692 km/s; MU = m0 = 1500 kg; force unit MU LU / TU^2.
"""
from __future__ import annotations

import dataclasses
import math

import casadi as ca
import numpy as np
from numpy.typing import NDArray

from .scenario import RendezvousScenario

FloatArray = NDArray[np.float64]
DAY_S = 86400.0


@dataclasses.dataclass(frozen=True)
class Units:
    """Scale factors SI -> normalised (divide an SI value by the unit)."""

    length_m: float     #: LU [m]
    time_s: float       #: TU [s]
    mass_kg: float      #: MU [kg]

    @classmethod
    def for_scenario(cls, scenario: RendezvousScenario) -> "Units":
        lu = scenario.problem.earth_orbit_radius_m
        return cls(length_m=lu, time_s=math.sqrt(lu ** 3 / scenario.problem.sun_mu_m3_s2),
                   mass_kg=scenario.initial_mass_kg)

    @property
    def velocity_m_s(self) -> float:
        return self.length_m / self.time_s

    @property
    def force_n(self) -> float:
        return self.mass_kg * self.length_m / self.time_s ** 2

    @property
    def mass_flow_kg_s(self) -> float:
        return self.mass_kg / self.time_s


@dataclasses.dataclass(frozen=True)
class Model:
    """Normalised constants of the predictive model."""

    units: Units
    thrust: float           #: T / force unit (constant throttle: T = T_max)
    mass_flow: float        #: T / (g0 Isp) / (MU / TU), eq. (13)
    x0: FloatArray          #: initial state (5,), eq. (4)
    mars_radius: float      #: r_M / LU
    mars_theta0: float      #: (theta_T)_0 [rad]
    mars_rate: float        #: sqrt(1 / r_M^3), eq. (6) [rad/TU]

    @classmethod
    def for_scenario(cls, scenario: RendezvousScenario) -> "Model":
        u = Units.for_scenario(scenario)
        s0 = scenario.initial
        x0 = np.array([s0.radius_m / u.length_m, s0.polar_angle_rad,
                       s0.radial_velocity_m_s / u.velocity_m_s,
                       s0.circumferential_velocity_m_s / u.velocity_m_s, 1.0])
        r_m = scenario.problem.target_orbit_radius_m / u.length_m
        # Solar-electric (eq. 14): the constant-throttle pair is the engine's at r_E (Engine.limits), only
        # so that Model (x0, Mars, units) exists for every scenario; its throttle model is `Engine`.
        thrust, mass_flow = Engine.for_scenario(scenario).limits(1.0)
        return cls(units=u, thrust=float(thrust), mass_flow=float(mass_flow),
                   x0=x0, mars_radius=r_m, mars_theta0=scenario.target.polar_angle_rad,
                   mars_rate=r_m ** -1.5)

    def mars_state(self, t: float) -> FloatArray:
        """Mars at normalised time t on its circular orbit, eqs. (5)-(6): (r_M, theta_M(t), 0, sqrt(1/r_M))."""
        return np.array([self.mars_radius, self.mars_theta0 + self.mars_rate * t, 0.0,
                         self.mars_radius ** -0.5])


def rhs(x: FloatArray, alpha: FloatArray | float, thrust: float, mass_flow: float) -> FloatArray:
    """dx/dt of eqs. (11) and (13), mu = 1, for states (..., 5) and angles (...) (vectorised)."""
    x = np.asarray(x, dtype=np.float64)
    r, vr, vt, m = x[..., 0], x[..., 2], x[..., 3], x[..., 4]
    accel = thrust / m
    alpha = np.asarray(alpha, dtype=np.float64)
    return np.stack([vr, vt / r, vt * vt / r - 1.0 / (r * r) + accel * np.cos(alpha),
                     -vt * vr / r + accel * np.sin(alpha), np.broadcast_to(-mass_flow, r.shape)],
                    axis=-1)


def casadi_rhs() -> ca.Function:
    """The same right-hand side as a CasADi function f(x[5], alpha, thrust, mass_flow) -> dx[5]."""
    x = ca.SX.sym("x", 5)
    alpha = ca.SX.sym("alpha")
    thrust = ca.SX.sym("thrust")
    mass_flow = ca.SX.sym("mass_flow")
    r, vr, vt, m = x[0], x[2], x[3], x[4]
    accel = thrust / m
    dx = ca.vertcat(vr, vt / r, vt * vt / r - 1.0 / (r * r) + accel * ca.cos(alpha),
                    -vt * vr / r + accel * ca.sin(alpha), -mass_flow)
    return ca.Function("rendezvous_rhs", [x, alpha, thrust, mass_flow], [dx],
                       ["x", "alpha", "thrust", "mass_flow"], ["xdot"])


def rk4_interval(x0: FloatArray, alpha0: float, alpha1: float, h: float, steps: int,
                 thrust: float, mass_flow: float) -> FloatArray:
    """One subinterval of length h with the angle linear from alpha0 to alpha1 (sec. 2.3), `steps` RK4
    steps, the angle evaluated at the stage times (numpy twin of the OCP's integrator)."""
    x = np.asarray(x0, dtype=np.float64)
    dt = h / steps
    for i in range(steps):
        s0 = i / steps
        a = [alpha0 + (alpha1 - alpha0) * (s0 + c / steps) for c in (0.0, 0.5, 1.0)]
        k1 = rhs(x, a[0], thrust, mass_flow)
        k2 = rhs(x + 0.5 * dt * k1, a[1], thrust, mass_flow)
        k3 = rhs(x + 0.5 * dt * k2, a[1], thrust, mass_flow)
        k4 = rhs(x + dt * k3, a[2], thrust, mass_flow)
        x = x + dt / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4)
    return x


# ---------------------------------------------------------------------------------------------------------
# Throttle model (docs/design/nmpc.md, "Throttle and the solar-electric engine"), shared by the NLP
# (ogk_host.rendezvous.nlp) and the truth model (harness/ogk/missions/rendezvous/truth.py).
#
# Control (alpha, w), throttle w in [0, 1]: T = w T_max(r), dm/dt = -w mdot_max(r).
#   nuclear-electric (eqs. 12-13): T_max = T_0, mdot_max = T_0 / (g0 Isp);
#   solar-electric (eq. 14, "duty-cycle" reading): T_max(r) = b1 + b2 P_0 p(r), mdot_max(r) = -(c1 + c2 P_0
#   p(r)), p(r) = (a1 r^2 + a2 r + a3) / (r^4 (1 + a4 r)) with r in AU, P_0 = reference_power_w(T_0). The
#   engine runs at the full power available a fraction w of the time: eq. (14)'s mass rate c1 + c2 P is that
#   of an engine that is on (at T = 0 it would still burn c1 + c2 (-b1 / b2) < 0), so it is scaled by w too.
#   The fit is used as printed; p(r) < 0 below r = 0.457 AU (the NLP keeps r above 0.6 AU for this engine).
# throttle "constant": w = 1 always (nu = 1, the control is alpha only).
# ---------------------------------------------------------------------------------------------------------

@dataclasses.dataclass(frozen=True)
class Engine:
    """Normalised throttle model of a scenario's engine (T and mdot in force and mass-flow units)."""

    model: str              #: "nuclear-electric" or "solar-electric"
    throttle: str           #: "constant" (w = 1, nu = 1) or "bounded" (0 <= w <= 1, nu = 2)
    thrust: float           #: nuclear-electric T_0 (normalised); solar-electric: unused (0)
    mass_flow: float        #: nuclear-electric T_0 / (g0 Isp) (normalised); solar-electric: unused (0)
    au_per_lu: float = 1.0  #: solar-electric: LU / (eq. 14's 1 AU)
    power: tuple[float, float, float, float] = (0.0, 0.0, 0.0, 0.0)  #: a1..a4 of eq. (14)
    thrust_coef: tuple[float, float] = (0.0, 0.0)   #: (b1, b2 P_0) / force unit
    flow_coef: tuple[float, float] = (0.0, 0.0)     #: (-c1, -c2 P_0) / mass-flow unit (mdot_max > 0)

    @classmethod
    def for_scenario(cls, scenario: RendezvousScenario) -> "Engine":
        u = Units.for_scenario(scenario)
        prop = scenario.propulsion
        if prop.model == "nuclear-electric":
            return cls(model=prop.model, throttle=prop.throttle, thrust=prop.thrust_max_n / u.force_n,
                       mass_flow=prop.mass_flow_at_max_kg_s / u.mass_flow_kg_s)
        sol = prop.solar
        assert sol is not None
        p0 = sol.reference_power_w(prop.thrust_max_n)
        return cls(model=prop.model, throttle=prop.throttle, thrust=0.0, mass_flow=0.0,
                   au_per_lu=u.length_m / sol.fit_length_unit_m,
                   power=(sol.power_a1, sol.power_a2, sol.power_a3, sol.power_a4),
                   thrust_coef=(sol.thrust_b1_n / u.force_n, sol.thrust_b2_n_per_w * p0 / u.force_n),
                   flow_coef=(-sol.mass_rate_c1_kg_s / u.mass_flow_kg_s,
                              -sol.mass_rate_c2_kg_s_per_w * p0 / u.mass_flow_kg_s))

    @property
    def nu(self) -> int:
        """Number of controls: 1 (alpha) for the constant throttle, 2 (alpha, w) otherwise."""
        return 1 if self.throttle == "constant" else 2

    @property
    def solar(self) -> bool:
        return self.model == "solar-electric"

    def _limits(self, r, lib):  # type: ignore[no-untyped-def]
        if not self.solar:
            return self.thrust + 0.0 * r, self.mass_flow + 0.0 * r
        a1, a2, a3, a4 = self.power
        ra = r * self.au_per_lu
        p = (a1 * ra * ra + a2 * ra + a3) / (ra ** 4 * (1.0 + a4 * ra))
        return (self.thrust_coef[0] + self.thrust_coef[1] * p, self.flow_coef[0] + self.flow_coef[1] * p)

    def limits(self, r: FloatArray | float) -> tuple[FloatArray, FloatArray]:
        """(T_max(r), mdot_max(r)) normalised, numpy (vectorised over r); mdot_max > 0 is -dm/dt at w = 1."""
        r = np.asarray(r, dtype=np.float64)
        return self._limits(r, np)

    def casadi_limits(self, r: ca.SX) -> tuple[ca.SX, ca.SX]:
        return self._limits(r, ca)


def throttle_rhs(x: FloatArray, alpha: FloatArray | float, w: FloatArray | float,
                 engine: Engine) -> FloatArray:
    """dx/dt of eqs. (11)-(14), mu = 1, control (alpha, w) (vectorised like `rhs`); for a constant
    throttle pass w = 1. With the nuclear-electric engine and w = 1 this is `rhs(x, alpha, T_0, mdot)`."""
    x = np.asarray(x, dtype=np.float64)
    t_max, mdot_max = engine.limits(x[..., 0])
    w = np.asarray(w, dtype=np.float64)
    return rhs(x, alpha, w * t_max, 0.0) - np.stack(
        [np.zeros_like(t_max)] * 4 + [np.broadcast_to(w * mdot_max, t_max.shape)], axis=-1)


def casadi_throttle_rhs(engine: Engine) -> ca.Function:
    """`throttle_rhs` as a CasADi function f(x[5], alpha, w) -> dx[5]."""
    x = ca.SX.sym("x", 5)
    alpha = ca.SX.sym("alpha")
    w = ca.SX.sym("w")
    t_max, mdot_max = engine.casadi_limits(x[0])
    dx = casadi_rhs()(x, alpha, w * t_max, w * mdot_max)
    return ca.Function("rendezvous_throttle_rhs", [x, alpha, w], [dx], ["x", "alpha", "w"], ["xdot"])


# ---------------------------------------------------------------------------------------------------------
# Third-body gravity (sec. 3.3 with the errata: eqs. 15-18 are wrong as printed, derived here from vectors).
# ---------------------------------------------------------------------------------------------------------

@dataclasses.dataclass(frozen=True)
class ThirdBody:
    """A planet on a circular orbit (normalised): position r_i (cos th_i(t), sin th_i(t)), th_i(t) =
    theta0 + rate t. `softening` (LU, default 0 = point mass) replaces |d|^3 by (|d|^2 + eps^2)^(3/2)
    (Plummer): only the predictive model's Mars uses it (docs/design/nmpc.md), the truth never does."""

    mu: float
    radius: float
    theta0: float
    rate: float
    softening: float = 0.0

    def theta(self, t):  # type: ignore[no-untyped-def]
        return self.theta0 + self.rate * t


def planets(scenario: RendezvousScenario, mars_softening_m: float = 0.0) -> tuple[ThirdBody, ThirdBody]:
    """(Earth, Mars) of Table A.1 in normalised units: Earth at theta_E0 + n_E t (n_E = sqrt(mu / r_E^3)
    = 1 / TU), Mars at (theta_T)_0 + n_M t (eq. 6)."""
    u = Units.for_scenario(scenario)
    mu_unit = u.length_m ** 3 / u.time_s ** 2
    pert = scenario.perturbations
    r_e = scenario.problem.earth_orbit_radius_m / u.length_m
    r_m = scenario.problem.target_orbit_radius_m / u.length_m
    earth = ThirdBody(mu=pert.earth_mu_m3_s2 / mu_unit, radius=r_e,
                      theta0=pert.earth_initial_polar_angle_rad, rate=r_e ** -1.5)
    mars = ThirdBody(mu=pert.target_mu_m3_s2 / mu_unit, radius=r_m, theta0=scenario.target.polar_angle_rad,
                     rate=r_m ** -1.5, softening=mars_softening_m / u.length_m)
    return earth, mars


def _third_body_polar(t, r, theta, bodies, lib):  # type: ignore[no-untyped-def]
    """(a_r, a_theta): sum over the bodies of -mu_i (r - r_i) / |r - r_i|^3 (direct) - mu_i r_i / |r_i|^3
    (indirect: the Sun-centred frame accelerates towards the planet), Cartesian vectors projected on the
    spacecraft's radial and circumferential unit vectors e_r = (cos th, sin th), e_th = (-sin th, cos th)."""
    c, s = lib.cos(theta), lib.sin(theta)
    x, y = r * c, r * s
    ax = 0.0 * r
    ay = 0.0 * r
    for b in bodies:
        th = b.theta(t)
        xi, yi = b.radius * lib.cos(th), b.radius * lib.sin(th)
        dx, dy = x - xi, y - yi
        d2 = dx * dx + dy * dy + b.softening ** 2
        k = b.mu / (d2 * lib.sqrt(d2))
        ki = b.mu / b.radius ** 3
        ax = ax - k * dx - ki * xi
        ay = ay - k * dy - ki * yi
    return ax * c + ay * s, -ax * s + ay * c


def third_body_accel(t: FloatArray | float, r: FloatArray | float, theta: FloatArray | float,
                     bodies: tuple[ThirdBody, ...]) -> tuple[FloatArray, FloatArray]:
    """Radial and circumferential third-body acceleration (normalised), numpy (vectorised)."""
    return _third_body_polar(np.asarray(t, dtype=np.float64), np.asarray(r, dtype=np.float64),
                             np.asarray(theta, dtype=np.float64), bodies, np)


def casadi_third_body_accel(bodies: tuple[ThirdBody, ...]) -> ca.Function:
    """The same as a CasADi function f(t, x[5]) -> (a_r, a_theta)."""
    t = ca.SX.sym("t")
    x = ca.SX.sym("x", 5)
    a_r, a_t = _third_body_polar(t, x[0], x[1], bodies, ca)
    return ca.Function("rendezvous_third_bodies", [t, x], [ca.vertcat(a_r, a_t)], ["t", "x"], ["a"])
