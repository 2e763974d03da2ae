"""Predictive model of Starek & Kolmanovsky 2012, eqs. (11)-(13), in normalised units.

State x = (r, theta, v_r, v_theta, m) in the rotating polar frame centred at the Sun; control alpha = the
thrust angle from the local vertical (0: radially outward, pi/2: along the circumferential direction,
sec. 4.1.1), thrust T along alpha. No perturbation: (f_perturb) = 0 in the predictive model (sec. 3.1).

Normalised units (docs/nmpc.md, "Units"):
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
        r_m = scenario.problem.mars_orbit_radius_m / u.length_m
        return cls(units=u, thrust=scenario.propulsion.thrust_max_n / u.force_n,
                   mass_flow=scenario.propulsion.mass_flow_at_max_kg_s / u.mass_flow_kg_s,
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
