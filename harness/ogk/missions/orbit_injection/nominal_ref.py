"""The ground nominal (host/ogk_host/orbit_injection) sampled densely in SI for the SIL harness.

`nominal_reference(scn)` solves the minimum-time nominal once per process (about 5 s) and keeps a
cubic-Hermite interpolant of the state (exact derivatives from the extremal field) and a cubic spline
of the optimal thrust angles u*(t) on 4001 points of tau (one every 26 ms of flight).
"""
from __future__ import annotations

import dataclasses
import functools
import math

import numpy as np
from numpy.typing import NDArray
from scipy.interpolate import CubicHermiteSpline, CubicSpline

from ogk_host.orbit_injection import derive
from ogk_host.orbit_injection import dynamics as dyn
from ogk_host.orbit_injection.nominal import Nominal, solve_nominal
from ogk_host.orbit_injection.scenario import OrbitInjectionScenario, load_scenario

F64 = NDArray[np.float64]

N_GRID = 4001


@dataclasses.dataclass(frozen=True)
class NominalReference:
    """Dense SI samples of the nominal: x = [r, xi, phi, v_r, v_t, v_n], u = [alpha, beta]."""

    scenario: OrbitInjectionScenario
    nominal: Nominal
    t_s: F64            #: (n,) time since ignition [s], 0 .. t_f*
    x_si: F64           #: (n, 6) [m, rad, rad, m/s, m/s, m/s]
    u_rad: F64          #: (n, 2) [alpha*, beta*] [rad]
    _x_interp: CubicHermiteSpline = dataclasses.field(repr=False)
    _u_interp: CubicSpline = dataclasses.field(repr=False)

    @property
    def tf_s(self) -> float:
        """Nominal minimum time t_f* [s]."""
        return float(self.nominal.t_f_s)

    @property
    def initial_state(self) -> F64:
        """x*(0) (6,) SI: the nominal ignition state (eq. 19 case B at f0*, or the specified
        state of case A, e.g. eq. 56)."""
        return self.x_si[0].copy()

    @property
    def final_state(self) -> F64:
        """x*(t_f*) (6,) SI."""
        return self.x_si[-1].copy()

    def state(self, t_s: F64) -> F64:
        """x*(t) (..., 6) SI, t clipped to [0, t_f*]."""
        return self._x_interp(np.clip(t_s, 0.0, self.tf_s))

    def control(self, t_s: F64) -> F64:
        """u*(t) (..., 2) [rad], held constant outside [0, t_f*]."""
        return self._u_interp(np.clip(t_s, 0.0, self.tf_s))


def build_reference(scn: OrbitInjectionScenario, n_grid: int = N_GRID) -> NominalReference:
    """Solves the nominal and samples it (canonical -> SI with the ground tool's units)."""
    nominal = solve_nominal(scn)
    units = nominal.problem.units
    tau = np.linspace(0.0, 1.0, n_grid)
    z = nominal.states(tau)
    rate = np.stack([dyn.extremal_rate(nominal.model, zi) for zi in z])   # d/dt in TU
    scale = units.state_scale[:6]
    x_si = z[:, :6] * scale
    xdot_si = rate[:, :6] * scale / units.time_s
    t_s = tau * nominal.t_f_s
    u = dyn.optimal_control(z[:, dyn.N_X:])
    return NominalReference(scenario=scn, nominal=nominal, t_s=t_s, x_si=x_si, u_rad=u,
                            _x_interp=CubicHermiteSpline(t_s, x_si, xdot_si, axis=0),
                            _u_interp=CubicSpline(t_s, u, axis=0))


@functools.lru_cache(maxsize=4)
def nominal_reference(scn: OrbitInjectionScenario | None = None) -> NominalReference:
    """Cached `build_reference` (the scenario dataclasses are frozen, hence hashable)."""
    return build_reference(scn if scn is not None else load_scenario())


def resolved_with_reference(scn: OrbitInjectionScenario
                            ) -> tuple[OrbitInjectionScenario, NominalReference]:
    """(scn with what it leaves to the burn derived from t_f*, its nominal): what every flight of
    the scenario takes, made once where the scenario is loaded. The end-game settings that scale
    with the burn (derive.resolve) need the nominal's t_f*; the flight code only checks them
    (derive.require_resolved)."""
    ref = nominal_reference(scn)
    return derive.resolve(scn, ref.tf_s), ref


def circular_speed(scn: OrbitInjectionScenario) -> float:
    """sqrt(mu / R_f) [m/s], eq. (20)."""
    return math.sqrt(scn.mu_m3_s2 / scn.target_radius_m)
