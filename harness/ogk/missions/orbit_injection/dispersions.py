"""Monte Carlo dispersions of an orbit-injection burn (Pontani & Celani 2021, Tables 3-5, eq. 55).

Reproducibility: run i owns the generator of ogk.sil.seeds (it depends on (seed, i) only).
Each generator is consumed in a fixed order: 5 initial-state normals, 3 attitude, 3 rates, 10 thrust
coefficients (always drawn, scaled by 0 when a group is switched off, so switching one group off does
not change the others), then the actuation noise, 3 normals per control step in blocks of
NOISE_BLOCK steps.
"""
from __future__ import annotations

import dataclasses
from collections.abc import Sequence

import numpy as np
from numpy.typing import NDArray

from ogk_host.orbit_injection.scenario import OrbitInjectionScenario

from ogk.sil.seeds import run_generator, run_seed

__all__ = ["ActuationNoise", "DispersionSwitches", "RunDraws", "draw_runs", "run_generator",
           "run_seed"]

F64 = NDArray[np.float64]

NOISE_BLOCK = 256      #: control steps of actuation noise drawn at once per run
N_THRUST_COEFFS = 10   #: a_1..a_10 of eq. (55)


@dataclasses.dataclass(frozen=True)
class DispersionSwitches:
    """Which dispersion groups are applied (all True: the paper's Table 7 campaign; all False: the
    Table 6 run with alignment errors only)."""

    initial_state: bool = True   #: Table 3: r0, phi0, v_r0, v_t0, v_n0
    attitude: bool = True        #: Table 4: Psi0, Theta0, Phi0, P0, Q0, R0
    thrust: bool = True          #: eq. (55) thrust fluctuation
    actuation: bool = True       #: Table 5 actuation errors

    @classmethod
    def none(cls) -> "DispersionSwitches":
        return cls(False, False, False, False)

    @property
    def any(self) -> bool:
        return self.initial_state or self.attitude or self.thrust or self.actuation


@dataclasses.dataclass(frozen=True)
class RunDraws:
    """Dispersed values of N runs (run-major), SI. Zero where a group is switched off."""

    run_id: NDArray[np.int64]      #: (N,)
    run_seed: NDArray[np.uint64]   #: (N,)
    d_state: F64                   #: (N, 6) [dr, dxi (0), dphi, dv_r, dv_t, dv_n] [m, rad, m/s]
    d_attitude: F64                #: (N, 3) [dPsi, dTheta, dPhi] [rad]
    rates0: F64                    #: (N, 3) [P0, Q0, R0] [rad/s]
    thrust_coeffs: F64             #: (N, 10) eq. (55) a_1..a_10 [-]

    @property
    def n_runs(self) -> int:
        return int(self.run_id.size)

    def subset(self, index: NDArray[np.int64] | slice) -> "RunDraws":
        return RunDraws(self.run_id[index], self.run_seed[index], self.d_state[index],
                        self.d_attitude[index], self.rates0[index], self.thrust_coeffs[index])

    @staticmethod
    def concatenate(parts: Sequence["RunDraws"]) -> "RunDraws":
        return RunDraws(*(np.concatenate([getattr(p, f.name) for p in parts])
                          for f in dataclasses.fields(RunDraws)))


def draw_runs(scn: OrbitInjectionScenario, master_seed: int, run_ids: Sequence[int] | NDArray[np.int64],
              switches: DispersionSwitches, run_seeds: NDArray[np.uint64] | None = None
              ) -> tuple[RunDraws, list[np.random.Generator]]:
    """Initial dispersions of the given runs, and each run's generator positioned for the
    actuation noise. `run_seeds` (the campaign engine's, ogk.sil.engine) are the streams of the
    runs; without them they are derived from `master_seed` the same way (ogk.sil.seeds)."""
    ids = np.asarray(run_ids, dtype=np.int64)
    seeds = (np.array([run_seed(master_seed, i) for i in ids], dtype=np.uint64)
             if run_seeds is None else np.asarray(run_seeds, dtype=np.uint64))
    isd, att = scn.initial_state_dispersion, scn.attitude_dispersion
    sig_state = np.array([isd.radius_m, isd.declination_rad, isd.radial_velocity_m_s,
                          isd.transverse_velocity_m_s, isd.normal_velocity_m_s])
    sig_att = np.array([att.yaw_rad, att.pitch_rad, att.roll_rad])
    sig_rate = np.array([att.roll_rate_rad_s, att.pitch_rate_rad_s, att.yaw_rate_rad_s])
    sig_thrust = scn.thrust_dispersion.coefficient_sigma
    if scn.thrust_dispersion.harmonics != N_THRUST_COEFFS // 2:
        raise ValueError("the truth model implements eq. (55) with 5 harmonics")
    n = ids.size
    d_state, d_att = np.zeros((n, 6)), np.zeros((n, 3))
    rates, coeffs = np.zeros((n, 3)), np.zeros((n, N_THRUST_COEFFS))
    gens = []
    for k, seed in enumerate(seeds):
        g = run_generator(int(seed))
        z_state = g.standard_normal(5)
        z_att, z_rate = g.standard_normal(3), g.standard_normal(3)
        z_thrust = g.standard_normal(N_THRUST_COEFFS)
        if switches.initial_state:
            d_state[k, [0, 2, 3, 4, 5]] = sig_state * z_state
        if switches.attitude:
            d_att[k] = sig_att * z_att
            rates[k] = sig_rate * z_rate
        if switches.thrust:
            coeffs[k] = sig_thrust * z_thrust
        gens.append(g)
    return RunDraws(ids, seeds, d_state, d_att, rates, coeffs), gens


class ActuationNoise:
    """Table 5 actuation errors, one draw per run per control step (held over the step).

    `next()` returns (3, N) [dM_x, dDelta_y, dDelta_z]; zeros when switched off (then the
    generators are not touched)."""

    def __init__(self, scn: OrbitInjectionScenario, generators: list[np.random.Generator],
                 enabled: bool) -> None:
        ad = scn.actuator_dispersion
        self._sigma = np.array([ad.roll_torque_n_m, ad.deflection_y_rad, ad.deflection_z_rad])
        self._gens = generators
        self._enabled = enabled
        self._block = np.zeros((NOISE_BLOCK, 3, len(generators)))
        self._pos = NOISE_BLOCK
        self._zeros = np.zeros((3, len(generators)))

    def next(self) -> F64:
        if not self._enabled:
            return self._zeros
        if self._pos == NOISE_BLOCK:
            for k, g in enumerate(self._gens):
                self._block[:, :, k] = g.standard_normal((NOISE_BLOCK, 3))
            self._block *= self._sigma[None, :, None]
            self._pos = 0
        out = self._block[self._pos]
        self._pos += 1
        return out
