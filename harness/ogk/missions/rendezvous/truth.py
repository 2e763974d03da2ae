"""Truth ("simulation") model of the Earth-to-Mars rendezvous, Starek & Kolmanovsky 2012 secs. 3.1-3.5.

Normalised units of docs/design/nmpc.md (`ogk_host.rendezvous.dynamics.Units`: LU = r_E, mu_sun = 1, MU = m_0),
state x = (r, theta, v_r, v_theta, m), control (alpha, w): the thrust angle from the local vertical and the
throttle w in [0, 1] (w = 1 always for the constant-throttle engine).

Unperturbed (`perturbed=False`): exactly the predictive model, `dynamics.throttle_rhs` (eqs. 11-14; for the
constant-throttle nuclear-electric engine the same numbers as `dynamics.rhs`). No third body, no solar
radiation pressure, no thrust offset, no angle noise (a nonzero angle offset is rejected).

Perturbed: eq. (11) with (f_perturb) = the sum of
  * Earth and Mars point-mass gravity, derived from vectors (seeds/README.md, erratum to eqs. 15-18: as
    printed each planet pulls as if it were on the far side of the Sun). Planets on circular orbits: Earth at
    theta_E(t) = (theta_E)_0 + n_E t (Table A.1: -0.35414 deg, n_E = sqrt(mu / r_E^3)), Mars at
    theta_M(t) = 130 deg + n_M t (eq. 6). Acceleration of body i: -mu_i (r - r_i) / |r - r_i|^3 (direct)
    - mu_i r_i / |r_i|^3 (indirect: the Sun-centred frame accelerates towards the planet; 1.8e-8 m/s^2 for
    Earth, 1.6e-9 for Mars, included for completeness), projected on the spacecraft's e_r, e_theta.
    `dynamics.third_body_accel` (one formula for the truth and the NLP's `third_bodies` option; the truth
    uses no softening). The point mass is singular at a planet's centre: a closed loop stops at Mars' sphere
    of influence (sec. 2.3.1; `propagate(..., stop_at_mars_soi=True)`).
  * Solar radiation pressure, eq. (22) with the unit vector (erratum: the text multiplies by r):
    f = 2 eta P_rad(r) A / m r_hat, P_rad = S_0 / c (r_0 / r)^2, r_0 = 1 AU = r_E of Table A.1 (the paper's
    "mean Earth orbit radius"). At 1 AU and 1500 kg: 1.83e-7 m/s^2, radial, outward.
  * Control disturbances, eq. (23): the thrust is T (1 + T_offset / 100) (T_offset = -10 %) and the applied
    angle is alpha_cmd + `angle_offset`, the caller's draw from N(0, sigma_alpha_T) (held for
    [dispersions] thrust_angle_draw_period_s, 0 = one draw per MPC control subinterval).
    Mass flow: the engine delivers the offset thrust at its nominal specific impulse (for the solar-electric
    engine, at its nominal T_max(r) / mdot_max(r)), so the mass flow scales with the actual thrust:
    dm/dt = -w (1 + T_offset / 100) mdot_max(r). The paper's accounting (errata: its perturbed fuel equals
    nominal mass flow x t_f) is `paper_fuel_kg(actual fuel)` = actual / (1 + T_offset / 100), exact because
    the scale factor is constant.

Throttle model (docs/design/nmpc.md, "Throttle"): T = w T_max(r), dm/dt = -w mdot_max(r); nuclear-electric
T_max = T_0, mdot_max = T_0 / (g0 Isp); solar-electric eq. (14) in the "duty-cycle" reading (`dynamics.Engine`).
The commanded throttle is clipped to [0, 1] (an actuator saturates).
"""
from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable, Sequence

import numpy as np
from numpy.typing import NDArray
from scipy.integrate import solve_ivp

from ogk_host.rendezvous.dynamics import Engine, Model, ThirdBody, Units, planets, third_body_accel, throttle_rhs
from ogk_host.rendezvous.scenario import RendezvousScenario

FloatArray = NDArray[np.float64]
ControlFn = Callable[[float], Sequence[float] | FloatArray]


@dataclasses.dataclass(frozen=True)
class TruthModel:
    """The simulation model of one scenario (normalised units); build with `for_scenario`."""

    perturbed: bool
    units: Units
    engine: Engine
    x0: FloatArray              #: the scenario's initial state (eq. 4)
    earth: ThirdBody            #: point mass, circular orbit
    mars: ThirdBody             #: point mass, circular orbit (eq. 6)
    srp: float                  #: 2 eta (S_0 / c) A / MU in acceleration units: f_SRP = srp / (m r^2)
    thrust_scale: float         #: 1 + T_offset / 100 (1 unperturbed)
    angle_sigma_rad: float      #: sigma_alpha_T (0 unperturbed): the closed loop draws the offsets
    angle_draw_period: float    #: [TU]; 0 = one draw per MPC control subinterval
    mars_soi: float             #: (r_SOI)_M [LU] (rendezvous test, sec. 2.3.1)
    velocity_tol: float         #: 1 km/s [VU] (rendezvous test, sec. 2.3.1)

    @classmethod
    def for_scenario(cls, scenario: RendezvousScenario, perturbed: bool) -> "TruthModel":
        u = Units.for_scenario(scenario)
        earth, mars = planets(scenario)
        pert = scenario.perturbations
        accel_unit = u.length_m / u.time_s ** 2
        srp_si = (2.0 * pert.reflectivity_efficiency * pert.solar_constant_w_m2 / pert.speed_of_light_m_s
                  * pert.area_m2 / u.mass_kg)   # m/s^2 at r = r_E, m = m_0
        return cls(perturbed=perturbed, units=u, engine=Engine.for_scenario(scenario),
                   x0=Model.for_scenario(scenario).x0, earth=earth, mars=mars,
                   srp=srp_si / accel_unit if perturbed else 0.0,
                   thrust_scale=1.0 + pert.thrust_offset_percent / 100.0 if perturbed else 1.0,
                   angle_sigma_rad=scenario.dispersions.thrust_angle_sigma_rad if perturbed else 0.0,
                   angle_draw_period=scenario.dispersions.thrust_angle_draw_period_s / u.time_s,
                   mars_soi=scenario.convergence.target_soi_radius_m / u.length_m,
                   velocity_tol=scenario.convergence.velocity_error_m_s / u.velocity_m_s)

    # -- planets ----------------------------------------------------------------------------------------
    @staticmethod
    def _circular(body: ThirdBody, t: float) -> FloatArray:
        return np.array([body.radius, body.theta(t), 0.0, body.radius ** -0.5])

    def mars_state(self, t: float) -> FloatArray:
        """Mars at normalised time t, polar (r_M, theta_M(t), 0, sqrt(1 / r_M)) (eqs. 5-6)."""
        return self._circular(self.mars, t)

    def earth_state(self, t: float) -> FloatArray:
        """Earth at normalised time t, polar (r_E, theta_E(t), 0, sqrt(1 / r_E))."""
        return self._circular(self.earth, t)

    def miss(self, t: float, x: FloatArray) -> tuple[float, float]:
        """(|r - r_M| [m], |v - v_M| [m/s]) at time t: 2-norms of the Cartesian differences to Mars."""
        pos, vel = _cartesian(np.asarray(x[:4], dtype=np.float64))
        pos_m, vel_m = _cartesian(self.mars_state(t))
        return (float(np.linalg.norm(pos - pos_m)) * self.units.length_m,
                float(np.linalg.norm(vel - vel_m)) * self.units.velocity_m_s)

    def paper_fuel_kg(self, fuel_kg: float) -> float:
        """The paper's accounting of a flown fuel: nominal mass flow x burn time = actual / (1 + T_offset/100)."""
        return fuel_kg / self.thrust_scale

    # -- dynamics ---------------------------------------------------------------------------------------
    def perturbation(self, t: float, x: FloatArray) -> tuple[float, float]:
        """(f_r, f_theta) of eq. (11): third bodies + solar radiation pressure (0 unperturbed)."""
        if not self.perturbed:
            return 0.0, 0.0
        a_r, a_t = third_body_accel(t, x[0], x[1], (self.earth, self.mars))
        return float(a_r) + self.srp / (x[4] * x[0] * x[0]), float(a_t)

    def rhs(self, t: float, x: FloatArray, alpha_cmd: float, throttle_cmd: float,
            angle_offset: float = 0.0) -> FloatArray:
        """dx/dt (normalised) with the commanded angle and throttle and the caller's angle offset [rad]."""
        if not self.perturbed and angle_offset != 0.0:
            raise ValueError("the unperturbed truth model has no angle noise (angle_offset must be 0)")
        w = 1.0 if self.engine.throttle == "constant" else min(max(float(throttle_cmd), 0.0), 1.0)
        dx = throttle_rhs(x, alpha_cmd + angle_offset, w * self.thrust_scale, self.engine)
        if self.perturbed:
            f_r, f_t = self.perturbation(t, x)
            dx[2] += f_r
            dx[3] += f_t
        return dx

    def propagate(self, t0: float, x0: FloatArray, t1: float, control_fn: ControlFn,
                  angle_offset: float = 0.0, rtol: float = 1e-10, atol: float = 1e-12,
                  breaks: Sequence[float] = (), stop_at_mars_soi: bool = False
                  ) -> tuple[FloatArray, FloatArray]:
        """Integrates from (t0, x0) to t1 with DOP853: control_fn(t) -> (alpha, w) (or (alpha,) for the
        constant throttle), the angle offset held constant. `breaks`: times inside (t0, t1) where the
        control has kinks (the plan's node times): the integration restarts there. `stop_at_mars_soi`: end
        when |r - r_M| falls to Mars' sphere of influence (then the grid ends there). Returns (times (n,),
        states (n, 5)), the solver's own steps, t0 and the end included."""
        def f(t: float, x: FloatArray) -> FloatArray:
            u = control_fn(t)
            return self.rhs(t, x, float(u[0]), float(u[1]) if len(u) > 1 else 1.0, angle_offset)

        events = None
        if stop_at_mars_soi:
            def soi(t: float, x: FloatArray) -> float:
                return self.miss(t, x)[0] / self.units.length_m - self.mars_soi
            soi.terminal = True    # type: ignore[attr-defined]
            soi.direction = -1.0   # type: ignore[attr-defined]
            events = soi
        cuts = [t0] + sorted(b for b in breaks if t0 < b < t1) + [t1]
        times = [np.array([t0])]
        states = [np.asarray(x0, dtype=np.float64)[None, :]]
        x = states[0][0]
        for a, b in zip(cuts[:-1], cuts[1:]):
            sol = solve_ivp(f, (a, b), x, method="DOP853", rtol=rtol, atol=atol, events=events)
            if not sol.success:
                raise RuntimeError(f"truth propagation failed at t = {sol.t[-1]:.6g}: {sol.message}")
            times.append(sol.t[1:])
            states.append(sol.y[:, 1:].T)
            x = sol.y[:, -1]
            if sol.status == 1:     # terminal event: inside Mars' sphere of influence
                break
        return np.concatenate(times), np.concatenate(states)


def _cartesian(s: FloatArray) -> tuple[FloatArray, FloatArray]:
    """Polar (r, theta, v_r, v_theta) -> Cartesian position and velocity (normalised)."""
    r, th, vr, vt = s[0], s[1], s[2], s[3]
    c, sn = math.cos(th), math.sin(th)
    return np.array([r * c, r * sn]), np.array([vr * c - vt * sn, vr * sn + vt * c])
