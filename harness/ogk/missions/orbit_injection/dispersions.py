"""Monte Carlo dispersions of an orbit-injection burn (Pontani & Celani 2021, Tables 3-5, eq. 55).

Reproducibility: run i owns the generator of ogk.sil.seeds (it depends on (seed, i) only).
Each generator is consumed in a fixed order: 5 initial-state normals, 3 attitude, 3 rates, 10 thrust
coefficients (always drawn, scaled by 0 when a group is switched off, so switching one group off does
not change the others), then the actuation noise, 3 normals per control step in blocks of
NOISE_BLOCK steps.

Records (ogk.sil.dispersion_check, naming rule disp.<[dispersions] key>): each run carries the
values its flight is given: disp.initial_state.* and disp.attitude.* (Tables 3-4), the eq. (55)
coefficients a_1..a_10 as disp.thrust.coefficient_sigma[0..9], and disp.actuators.* the actuation
noise of the first control step (Table 5; 0 when the noise is off or the truth is point-mass,
which has no actuators). `declared` states the distribution of each.
"""
from __future__ import annotations

import copy
import dataclasses
from collections.abc import Sequence
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ogk_host.orbit_injection.scenario import OrbitInjectionScenario

from ogk.sil.dispersion_check import Constant, Declaration, Declared, Gaussian, Parameter
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
    #: (N, 3) [dM_x, dDelta_y, dDelta_z] actuation noise of the first control step, as the truth
    #: receives it (`with_first_actuation`); None when not known (draws rebuilt from records)
    actuation0: F64 | None = None

    @property
    def n_runs(self) -> int:
        return int(self.run_id.size)

    def subset(self, index: NDArray[np.int64] | slice) -> "RunDraws":
        return RunDraws(self.run_id[index], self.run_seed[index], self.d_state[index],
                        self.d_attitude[index], self.rates0[index], self.thrust_coeffs[index],
                        None if self.actuation0 is None else self.actuation0[index])

    @staticmethod
    def concatenate(parts: Sequence["RunDraws"]) -> "RunDraws":
        known = all(p.actuation0 is not None for p in parts)
        return RunDraws(*(np.concatenate([getattr(p, f.name) for p in parts])
                          if f.name != "actuation0" or known else None
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


def _noise_block(g: np.random.Generator) -> F64:
    """NOISE_BLOCK control steps of unit actuation noise of one run: (NOISE_BLOCK, 3)."""
    return g.standard_normal((NOISE_BLOCK, 3))


def with_first_actuation(scn: OrbitInjectionScenario, draws: RunDraws,
                         generators: list[np.random.Generator], applied: bool) -> RunDraws:
    """`draws` with the actuation noise of the first control step as ActuationNoise will give it
    to the truth (`applied`: the noise is on and the truth has actuators, as in sil.fly_runs),
    drawn from copies of the generators: the flight's streams are not touched."""
    ad = scn.actuator_dispersion
    sigma = np.array([ad.roll_torque_n_m, ad.deflection_y_rad, ad.deflection_z_rad])
    first = np.zeros((draws.n_runs, 3))
    if applied:
        for k, g in enumerate(generators):
            first[k] = _noise_block(copy.deepcopy(g))[0] * sigma
    return dataclasses.replace(draws, actuation0=first)


#: record key -> (RunDraws field, column) of the values a run is given
RECORD_COLUMNS: dict[str, tuple[str, int]] = {
    "initial_state.radius_m": ("d_state", 0),
    "initial_state.declination_rad": ("d_state", 2),
    "initial_state.radial_velocity_m_s": ("d_state", 3),
    "initial_state.transverse_velocity_m_s": ("d_state", 4),
    "initial_state.normal_velocity_m_s": ("d_state", 5),
    "attitude.yaw_rad": ("d_attitude", 0),        # Psi_0
    "attitude.pitch_rad": ("d_attitude", 1),      # Theta_0
    "attitude.roll_rad": ("d_attitude", 2),       # Phi_0
    "attitude.roll_rate_rad_s": ("rates0", 0),    # P_0
    "attitude.pitch_rate_rad_s": ("rates0", 1),   # Q_0
    "attitude.yaw_rate_rad_s": ("rates0", 2),     # R_0
    "actuators.roll_torque_n_m": ("actuation0", 0),
    "actuators.deflection_y_rad": ("actuation0", 1),
    "actuators.deflection_z_rad": ("actuation0", 2),
}


def dispersion_records(draws: RunDraws) -> list[dict[str, float | None]]:
    """The disp.* keys of each run (module doc)."""
    out = []
    for i in range(draws.n_runs):
        rec: dict[str, float | None] = {}
        for key, (field, col) in RECORD_COLUMNS.items():
            arr = getattr(draws, field)
            rec["disp." + key] = None if arr is None else float(arr[i, col])
        rec.update({f"disp.thrust.coefficient_sigma[{j}]": float(draws.thrust_coeffs[i, j])
                    for j in range(N_THRUST_COEFFS)})
        out.append(rec)
    return out


def declared(scn: OrbitInjectionScenario, table: dict[str, Any], switches: DispersionSwitches,
             six_dof: bool) -> Declaration:
    """The scenario's [dispersions] as a campaign applies them: each key a zero-mean Gaussian of
    its 1-sigma (Tables 3-5, eq. 55), a constant 0 when its group is switched off or its sigma is
    0 (or, for the actuators, when the truth has none)."""
    isd, att, ad = scn.initial_state_dispersion, scn.attitude_dispersion, scn.actuator_dispersion
    groups = {"initial_state": (isd, switches.initial_state), "attitude": (att, switches.attitude),
              "actuators": (ad, switches.actuation and six_dof)}
    out = []
    for key in RECORD_COLUMNS:
        group, name = key.split(".")
        obj, on = groups[group]
        sigma = float(getattr(obj, name))
        out.append(Declared(key, Gaussian(sigma) if on and sigma > 0.0 else Constant(0.0)))
    sigma = float(scn.thrust_dispersion.coefficient_sigma)
    out.append(Declared("thrust.coefficient_sigma",
                        Gaussian(sigma) if switches.thrust and sigma > 0.0 else Constant(0.0),
                        size=2 * int(scn.thrust_dispersion.harmonics)))
    out.append(Declared("thrust.harmonics", Parameter(
        "thrust.coefficient_sigma", "eq. (55): 2 x harmonics coefficients a_k")))
    return Declaration(table, tuple(out))


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
                self._block[:, :, k] = _noise_block(g)
            self._block *= self._sigma[None, :, None]
            self._pos = 0
        out = self._block[self._pos]
        self._pos += 1
        return out
