"""LEO-to-GEO injection scenario (Pontani & Celani 2021, sec. 6, Tables 1-5): TOML file -> dataclasses.

Everything here is SI (m, s, kg, rad), as in scenarios/leo_geo.toml. The canonical units the solvers
use internally are built by `CanonicalUnits.for_scenario` (DU = target radius, TU = sqrt(DU^3 / mu)).
"""
from __future__ import annotations

import dataclasses
import math
import tomllib
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

FloatArray = NDArray[np.float64]

REPO_ROOT = Path(__file__).resolve().parents[3]
DEFAULT_SCENARIO_PATH = REPO_ROOT / "scenarios" / "leo_geo.toml"
SCHEMA = "ogk.missions.orbit_injection/1"


@dataclasses.dataclass(frozen=True)
class Thrust:
    """Sec. 6 thrust model T/m = n0 c / (c - n0 t)."""

    exhaust_velocity_m_s: float     #: c [m/s]
    initial_accel_g0: float         #: n0 / g0 [-]
    standard_gravity_m_s2: float    #: g0 [m/s^2]
    initial_mass_kg: float          #: m0 [kg]

    @property
    def initial_accel_m_s2(self) -> float:
        """n0 [m/s^2]."""
        return self.initial_accel_g0 * self.standard_gravity_m_s2

    @property
    def thrust_n(self) -> float:
        """Constant thrust T = n0 m0 [N]."""
        return self.initial_accel_m_s2 * self.initial_mass_kg

    @property
    def mass_flow_kg_s(self) -> float:
        """Constant mass flow T / c [kg/s]."""
        return self.thrust_n / self.exhaust_velocity_m_s

    def accel_m_s2(self, t_s: FloatArray | float) -> FloatArray:
        """T/m at time t since ignition [m/s^2]."""
        n0 = self.initial_accel_m_s2
        c = self.exhaust_velocity_m_s
        return n0 * c / (c - n0 * np.asarray(t_s, dtype=np.float64))

    def mass_kg(self, t_s: FloatArray | float) -> FloatArray:
        """m(t) = m0 - (T/c) t [kg]."""
        return self.initial_mass_kg - self.mass_flow_kg_s * np.asarray(t_s, dtype=np.float64)


@dataclasses.dataclass(frozen=True)
class PreIgnitionOrbit:
    """Keplerian ellipse before ignition (eq. 19 case B), with the 'p~ is really a' erratum applied."""

    semi_major_axis_m: float
    eccentricity: float
    leo_altitude_m: float
    earth_radius_m: float

    @property
    def semilatus_rectum_m(self) -> float:
        """p = a (1 - e^2): the p~ of eq. (19)."""
        return self.semi_major_axis_m * (1.0 - self.eccentricity**2)


@dataclasses.dataclass(frozen=True)
class MassProperties:
    """Table 1 / eq. (53): linear-in-time TVC arm and principal inertias."""

    tvc_arm_m: float
    tvc_arm_rate_m_s: float
    inertia_x_kg_m2: float
    inertia_y_kg_m2: float
    inertia_z_kg_m2: float
    inertia_x_rate_kg_m2_s: float
    inertia_y_rate_kg_m2_s: float
    inertia_z_rate_kg_m2_s: float

    def at(self, t_s: float) -> tuple[float, float, float, float]:
        """(l, I_x, I_y, I_z) at time t since ignition, eq. (53)."""
        return (self.tvc_arm_m + self.tvc_arm_rate_m_s * t_s,
                self.inertia_x_kg_m2 + self.inertia_x_rate_kg_m2_s * t_s,
                self.inertia_y_kg_m2 + self.inertia_y_rate_kg_m2_s * t_s,
                self.inertia_z_kg_m2 + self.inertia_z_rate_kg_m2_s * t_s)


@dataclasses.dataclass(frozen=True)
class Actuators:
    """Table 2: saturation limits and first-order time constants (eqs. 16-18)."""

    roll_torque_max_n_m: float
    deflection_y_max_rad: float
    deflection_z_max_rad: float
    time_constant_x_s: float
    time_constant_y_s: float
    time_constant_z_s: float


@dataclasses.dataclass(frozen=True)
class CpdGains:
    """One set of CPD gains (eqs. 45-46) with the plant gains G they were designed for."""

    gain_roll_g_per_kg_m2: float    #: G_x [1/(kg m^2)]
    gain_pitch_yaw_g_s2: float      #: G_y = G_z [1/s^2]
    kp_roll_n_m_per_rad: float      #: k_px
    kd_roll_n_m_s_per_rad: float    #: k_dx
    kp_pitch_yaw: float             #: k_py = k_pz [rad/rad]
    kd_pitch_yaw_s: float           #: k_dy = k_dz [s]


@dataclasses.dataclass(frozen=True)
class Cpd:
    """CPD attitude-control design (sec. 5.3 and 6)."""

    natural_frequency_rad_s: float
    damping_ratio: float
    roll_command_rad: float
    roll_torque_command_max_n_m: float
    deflection_y_command_max_rad: float
    deflection_z_command_max_rad: float
    roll_torque_rate_bound_n_m_s: float
    deflection_rate_bound_rad_s: float
    flown: str                      #: "printed" or "rederived"
    braking_margin: float           #: braking-curve cap (docs/cpd.md), 0 = the paper's law
    feedforward: bool               #: feed-forward of the commanded turn rate (docs/cpd.md)
    feedforward_rate_max_rad_s: float  #: clip of the feed-forward rate
    printed: CpdGains
    rederived: CpdGains

    def braking_accels_rad_s2(self, scn: "LeoGeoScenario") -> tuple[float, float, float]:
        """ogk_cpd_config_t.approach_accel_{x,y,z}: the margin times the smallest control
        acceleration at the command limits over the burn (roll M_xc / I_x0; pitch/yaw
        G_min sin(Delta_c) with G_min = T l0 / I_y0, I_z0)."""
        mp, thrust_n = scn.mass_properties, scn.thrust.thrust_n
        return (self.braking_margin * self.roll_torque_command_max_n_m / mp.inertia_x_kg_m2,
                self.braking_margin * thrust_n * mp.tvc_arm_m / mp.inertia_y_kg_m2
                * math.sin(self.deflection_y_command_max_rad),
                self.braking_margin * thrust_n * mp.tvc_arm_m / mp.inertia_z_kg_m2
                * math.sin(self.deflection_z_command_max_rad))

    @property
    def flown_gains(self) -> CpdGains:
        """The gain set selected by the `flown` key."""
        return self.rederived if self.flown == "rederived" else self.printed


@dataclasses.dataclass(frozen=True)
class InitialStateDispersion:
    """Table 3 (1-sigma)."""

    radius_m: float
    declination_rad: float
    radial_velocity_m_s: float
    transverse_velocity_m_s: float
    normal_velocity_m_s: float

    def sigma_state_si(self) -> FloatArray:
        """1-sigma of the 7-state [r, xi, phi, v_r, v_t, v_n, t] in SI (0 where not dispersed)."""
        return np.array([self.radius_m, 0.0, self.declination_rad, self.radial_velocity_m_s,
                         self.transverse_velocity_m_s, self.normal_velocity_m_s, 0.0])


@dataclasses.dataclass(frozen=True)
class AttitudeDispersion:
    """Table 4 (1-sigma)."""

    yaw_rad: float
    pitch_rad: float
    roll_rad: float
    roll_rate_rad_s: float
    pitch_rate_rad_s: float
    yaw_rate_rad_s: float


@dataclasses.dataclass(frozen=True)
class ActuatorDispersion:
    """Table 5 (1-sigma)."""

    roll_torque_n_m: float
    deflection_y_rad: float
    deflection_z_rad: float


@dataclasses.dataclass(frozen=True)
class ThrustDispersion:
    """Eq. (55): random Fourier series on n0, period t_f*."""

    harmonics: int
    coefficient_sigma: float


@dataclasses.dataclass(frozen=True)
class PaperResults:
    """Published figures, kept for comparison only."""

    min_time_s: float
    ignition_true_anomaly_rad: float
    monte_carlo_runs: int
    table6_final_errors: tuple[float, ...]
    table7_mean: tuple[float, ...]
    table7_sigma: tuple[float, ...]


@dataclasses.dataclass(frozen=True)
class EndGame:
    """Guard of the VTD-NOG law near cut-off (docs/vtd-nog.md, "End-game"); kernel ogk_nog_config_t."""

    dtf_max_s: float          #: bound on |dt_f|
    du_max_rad: float         #: bound on the angle between corrected and nominal thrust directions
    freeze_time_to_go_s: float  #: no new correction when the nominal time to go is below this


@dataclasses.dataclass(frozen=True)
class LeoGeoScenario:
    """Everything section 6 of the paper specifies for the LEO-to-GEO injection burn (SI units)."""

    name: str
    source: str
    mu_m3_s2: float
    thrust: Thrust
    pre_ignition: PreIgnitionOrbit
    target_radius_m: float
    mass_properties: MassProperties
    actuators: Actuators
    sample_interval_s: float
    end_game: EndGame
    cpd: Cpd
    initial_state_dispersion: InitialStateDispersion
    attitude_dispersion: AttitudeDispersion
    actuator_dispersion: ActuatorDispersion
    thrust_dispersion: ThrustDispersion
    paper: PaperResults

    @property
    def target_circular_speed_m_s(self) -> float:
        """sqrt(mu / R_f), eq. (20)."""
        return math.sqrt(self.mu_m3_s2 / self.target_radius_m)


def _section(raw: dict[str, Any], cls: type, key: str) -> Any:
    """Builds dataclass `cls` from table `key`, rejecting missing or unknown keys."""
    table = raw[key]
    names = {f.name for f in dataclasses.fields(cls)}
    scalars = {k: v for k, v in table.items() if not isinstance(v, dict)}
    missing = names - set(scalars)
    unknown = set(scalars) - names
    if missing or unknown:
        raise ValueError(f"[{key}]: missing {sorted(missing)}, unknown {sorted(unknown)}")
    return cls(**scalars)


def load_scenario(path: str | Path | None = None) -> LeoGeoScenario:
    """Reads scenarios/leo_geo.toml (or `path`) and checks it for consistency."""
    scenario_path = Path(path) if path is not None else DEFAULT_SCENARIO_PATH
    with open(scenario_path, "rb") as stream:
        raw = tomllib.load(stream)
    if raw.get("schema") != SCHEMA:
        raise ValueError(f"{scenario_path}: schema {raw.get('schema')!r}, expected {SCHEMA!r}")
    orbit_raw = dict(raw["pre_ignition_orbit"])
    if orbit_raw.pop("ignition_true_anomaly") != "free":
        raise ValueError("only the free-ignition case (eq. 19 case B) is implemented")
    cpd_raw = raw["cpd"]
    cpd_scalars = {k: v for k, v in cpd_raw.items() if not isinstance(v, dict)}
    cpd = Cpd(**cpd_scalars, printed=CpdGains(**cpd_raw["printed"]),
              rederived=CpdGains(**cpd_raw["rederived"]))
    if cpd.flown not in ("printed", "rederived"):
        raise ValueError(f"[cpd] flown must be 'printed' or 'rederived', got {cpd.flown!r}")
    paper_raw = raw["paper_results"]
    disp = raw["dispersions"]
    scenario = LeoGeoScenario(
        name=raw["name"],
        source=raw["source"],
        mu_m3_s2=float(raw["gravity"]["mu_m3_s2"]),
        thrust=_section(raw, Thrust, "thrust"),
        pre_ignition=PreIgnitionOrbit(**orbit_raw),
        target_radius_m=float(raw["target_orbit"]["radius_m"]),
        mass_properties=_section(raw, MassProperties, "mass_properties"),
        actuators=_section(raw, Actuators, "actuators"),
        sample_interval_s=float(raw["guidance"]["sample_interval_s"]),
        end_game=_section(raw["guidance"], EndGame, "end_game"),
        cpd=cpd,
        initial_state_dispersion=_section(disp, InitialStateDispersion, "initial_state"),
        attitude_dispersion=_section(disp, AttitudeDispersion, "attitude"),
        actuator_dispersion=_section(disp, ActuatorDispersion, "actuators"),
        thrust_dispersion=_section(disp, ThrustDispersion, "thrust"),
        paper=PaperResults(
            min_time_s=float(paper_raw["min_time_s"]),
            ignition_true_anomaly_rad=float(paper_raw["ignition_true_anomaly_rad"]),
            monte_carlo_runs=int(paper_raw["monte_carlo_runs"]),
            table6_final_errors=tuple(paper_raw["table6_final_errors"]),
            table7_mean=tuple(paper_raw["table7_mean"]),
            table7_sigma=tuple(paper_raw["table7_sigma"])),
    )
    _check(scenario)
    return scenario


def _check(scn: LeoGeoScenario) -> None:
    """Physical sanity checks; bad data is rejected with a message naming the key."""
    positive = {
        "gravity.mu_m3_s2": scn.mu_m3_s2,
        "thrust.exhaust_velocity_m_s": scn.thrust.exhaust_velocity_m_s,
        "thrust.initial_accel_g0": scn.thrust.initial_accel_g0,
        "thrust.initial_mass_kg": scn.thrust.initial_mass_kg,
        "pre_ignition_orbit.semi_major_axis_m": scn.pre_ignition.semi_major_axis_m,
        "target_orbit.radius_m": scn.target_radius_m,
        "guidance.sample_interval_s": scn.sample_interval_s,
        "guidance.end_game.dtf_max_s": scn.end_game.dtf_max_s,
        "guidance.end_game.du_max_rad": scn.end_game.du_max_rad,
    }
    for key, value in positive.items():
        if not value > 0.0:
            raise ValueError(f"{key} must be > 0, got {value}")
    if not 0.0 <= scn.pre_ignition.eccentricity < 1.0:
        raise ValueError("pre_ignition_orbit.eccentricity must be in [0, 1)")
