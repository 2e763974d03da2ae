"""LEO-to-GEO injection scenario (Pontani & Celani 2021, sec. 6, Tables 1-5): TOML file -> dataclasses.

Everything here is SI (m, s, kg, rad), as in scenarios/leo_geo.toml. The canonical units the solvers
use internally are built by `CanonicalUnits.for_scenario` (DU = target radius, TU = sqrt(DU^3 / mu)).
"""
from __future__ import annotations

import bisect
import dataclasses
import functools
import math
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray
from scipy.interpolate import CubicSpline

from ..paths import SCENARIO_DIR
from ..scenario_file import Section, check_header, read_toml, schema_of

FloatArray = NDArray[np.float64]

DEFAULT_SCENARIO_PATH = SCENARIO_DIR / "leo_geo.toml"
MISSION = "orbit-injection"   #: the family name of ogk.missions.registry
SCHEMA = schema_of(MISSION)    #: "ogk.orbit-injection/1" (the header, ogk_host.scenario_file)
LAWS = ("vtd-nog",)            #: guidance laws this family flies


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

    @property
    def min_thrust_n(self) -> float:
        """Smallest thrust over the burn (sec. 5.3 G_min): T itself."""
        return self.thrust_n

    @property
    def burnout_s(self) -> float:
        """Time at which the whole mass would be gone, c / n0 [s] (a(t) -> infinity)."""
        return self.exhaust_velocity_m_s / self.initial_accel_m_s2


@dataclasses.dataclass(frozen=True)
class TabulatedThrust:
    """Thrust and mass histories tabulated versus time since ignition (sec. 7: "the actual time
    histories of the rocket thrust magnitude and mass are employed").

    Both columns are interpolated by not-a-knot cubic splines (scipy CubicSpline), so the thrust
    acceleration a(t) = T(t) / m(t) is twice continuously differentiable: the ground tools need
    a' and a'' (eqs. 25 and the accessory problem, docs/design/vtd-nog.md). Outside the table the motor is
    burnt out: T = 0 after the last time (the truth model), m held at its last value. The ground
    tools refuse an arc that leaves the table.
    """

    time_s: tuple[float, ...]       #: t_i [s], strictly increasing, t_0 = 0 (ignition)
    thrust_n: tuple[float, ...]     #: T(t_i) [N], > 0
    mass_kg: tuple[float, ...]      #: m(t_i) [kg], > 0, decreasing

    @functools.cached_property
    def _splines(self) -> tuple[CubicSpline, CubicSpline]:
        t = np.asarray(self.time_s, dtype=np.float64)
        return (CubicSpline(t, np.asarray(self.thrust_n, dtype=np.float64), bc_type="not-a-knot"),
                CubicSpline(t, np.asarray(self.mass_kg, dtype=np.float64), bc_type="not-a-knot"))

    @functools.cached_property
    def _coefficients(self) -> tuple[FloatArray, FloatArray]:
        """(breakpoints (n,), coefficients (4, n-1, 2)) of both splines [T, m], highest power
        first (scipy PPoly layout), for the fast evaluation of `_eval`."""
        ts, ms = self._splines
        return np.asarray(ts.x), np.stack([ts.c, ms.c], axis=-1)

    def _eval(self, t: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray]:
        """([T, m], d/dt, d2/dt2) at t (..., 2), each piece's cubic by Horner (equals the
        CubicSpline values to rounding, at a fraction of its call overhead)."""
        x, c = self._coefficients
        i = np.clip(np.searchsorted(x, t, side="right") - 1, 0, x.size - 2)
        dt = (t - x[i])[..., None]
        c0, c1, c2, c3 = c[0][i], c[1][i], c[2][i], c[3][i]
        return (((c0 * dt + c1) * dt + c2) * dt + c3, (3.0 * c0 * dt + 2.0 * c1) * dt + c2,
                6.0 * c0 * dt + 2.0 * c1)

    @property
    def end_s(self) -> float:
        """Last tabulated time: burnout [s]."""
        return self.time_s[-1]

    @property
    def burnout_s(self) -> float:
        return self.end_s

    @property
    def knots_s(self) -> FloatArray:
        """Interior breakpoints of the splines [s]: the derivatives of a(t) beyond the second jump
        there, so the ground integrators restart at them (propagation.solve_ivp_segmented)."""
        return np.asarray(self.time_s[1:-1], dtype=np.float64)

    def thrust_mass_at(self, t_s: FloatArray | float) -> tuple[FloatArray, FloatArray]:
        """(T(t) [N], m(t) [kg]); after the table T = 0 (burnt out) and m holds its last value."""
        t = np.asarray(t_s, dtype=np.float64)
        value = self._eval(np.clip(t, 0.0, self.end_s))[0]
        return np.where(t > self.end_s, 0.0, value[..., 0]), value[..., 1]

    def thrust_at(self, t_s: FloatArray | float) -> FloatArray:
        """T(t) [N]; 0 after the table (burnt out)."""
        return self.thrust_mass_at(t_s)[0]

    def mass_kg_at(self, t_s: FloatArray | float) -> FloatArray:
        """m(t) [kg], held at the last value after the table."""
        return self.thrust_mass_at(t_s)[1]

    def mass_kg(self, t_s: FloatArray | float) -> FloatArray:
        return self.mass_kg_at(t_s)

    def accel_m_s2(self, t_s: FloatArray | float) -> FloatArray:
        """T/m at time t since ignition [m/s^2] (0 after burnout)."""
        thrust, mass = self.thrust_mass_at(t_s)
        return thrust / mass

    @functools.cached_property
    def _scalar_pieces(self) -> tuple[list[float], list[tuple[float, ...]]]:
        """Breakpoints and per-piece coefficients as Python floats (scalar fast path)."""
        x, c = self._coefficients
        return [float(v) for v in x], [tuple(float(v) for v in c[:, i, :].ravel())
                                       for i in range(x.size - 1)]

    def _accel_scalar(self, t: float) -> tuple[float, float, float]:
        x, pieces = self._scalar_pieces
        i = min(max(bisect.bisect_right(x, t) - 1, 0), len(x) - 2)
        d = t - x[i]
        t0, m0, t1, m1, t2, m2, t3, m3 = pieces[i]
        thr, mass = ((t0 * d + t1) * d + t2) * d + t3, ((m0 * d + m1) * d + m2) * d + m3
        thr1, mass1 = (3.0 * t0 * d + 2.0 * t1) * d + t2, (3.0 * m0 * d + 2.0 * m1) * d + m2
        thr2, mass2 = 6.0 * t0 * d + 2.0 * t1, 6.0 * m0 * d + 2.0 * m1
        a = thr / mass
        a1 = (thr1 - a * mass1) / mass
        return a, a1, (thr2 - 2.0 * a1 * mass1 - a * mass2) / mass

    def accel_derivatives(self, t_s: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray]:
        """(a, da/dt, d2a/dt2) of a = T/m inside the table (the end pieces extrapolated) [SI]."""
        if np.ndim(t_s) == 0:
            return self._accel_scalar(float(t_s))
        v, v1, v2 = self._eval(np.asarray(t_s, dtype=np.float64))
        thr, thr1, thr2 = v[..., 0], v1[..., 0], v2[..., 0]
        m, m1, m2 = v[..., 1], v1[..., 1], v2[..., 1]
        a = thr / m
        a1 = (thr1 - a * m1) / m
        a2 = (thr2 - 2.0 * a1 * m1 - a * m2) / m
        return a, a1, a2

    @property
    def initial_mass_kg(self) -> float:
        return float(self.mass_kg[0])

    @property
    def initial_accel_m_s2(self) -> float:
        """a(0) [m/s^2]."""
        return float(self.thrust_n[0] / self.mass_kg[0])

    @property
    def exhaust_velocity_m_s(self) -> float:
        """Effective exhaust velocity at ignition, T(0) / (-dm/dt(0)) [m/s] (informative)."""
        return float(self.thrust_n[0] / -self._splines[1](0.0, 1))

    @property
    def min_thrust_n(self) -> float:
        """Smallest tabulated thrust [N] (sec. 5.3 G_min; sec. 7: T_min)."""
        return float(min(self.thrust_n))


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
class InitialState:
    """Specified ignition state (eq. 19 case A, sec. 7 eq. 56): xi = phi = v_n = 0 (sec. 3.1)."""

    radius_m: float                 #: r_i
    radial_velocity_m_s: float      #: v_r,i
    transverse_velocity_m_s: float  #: v_t,i

    def state_si(self) -> FloatArray:
        """[r, xi, phi, v_r, v_t, v_n, t] at ignition (SI)."""
        return np.array([self.radius_m, 0.0, 0.0, self.radial_velocity_m_s,
                         self.transverse_velocity_m_s, 0.0, 0.0])

    def true_anomaly_rad(self, mu_m3_s2: float) -> float:
        """True anomaly of the state on its osculating (coast) orbit, in [0, 2 pi) [rad]."""
        h = self.radius_m * self.transverse_velocity_m_s
        p = h * h / mu_m3_s2
        return math.atan2(self.radial_velocity_m_s * h / mu_m3_s2, p / self.radius_m - 1.0) \
            % (2.0 * math.pi)


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
    braking_margin: float           #: braking-curve cap (docs/design/cpd.md), 0 = the paper's law
    feedforward: bool               #: feed-forward of the commanded turn rate (docs/design/cpd.md)
    feedforward_rate_max_rad_s: float  #: clip of the feed-forward rate
    printed: CpdGains | None        #: eq. (54) as printed; None when the scenario has none
    rederived: CpdGains | None      #: sec. 5.3 rule; None: derived by the ground tools



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
    ignition_true_anomaly_rad: float | None   #: None when the paper gives none (sec. 7)
    monte_carlo_runs: int
    table6_final_errors: tuple[float, ...]
    table7_mean: tuple[float, ...]
    table7_sigma: tuple[float, ...]
    #: the paper's numbering of the two tables (the keys above keep the LEO-to-GEO names, sec. 6)
    single_run_table: str = "Table 6"
    monte_carlo_table: str = "Table 7"


@dataclasses.dataclass(frozen=True)
class Dispersions:
    """[dispersions]: what a campaign draws at random (Tables 3-5, eq. 55), and only that."""

    initial_state: InitialStateDispersion
    attitude: AttitudeDispersion
    actuators: ActuatorDispersion
    thrust: ThrustDispersion


@dataclasses.dataclass(frozen=True)
class Acceptance:
    """Failure criterion: a run whose injection error exceeds one of these has failed.

    Default when the scenario has no [acceptance] (or leaves a key out): 1 km on the radius, the
    same 1 km seen from the target radius on the declination (radius_error_m / R_f), 10 m/s on
    each velocity component."""

    radius_error_m: float           #: |dr_f|
    declination_error_rad: float    #: |dphi_f|
    velocity_error_m_s: float       #: each of |dv_rf|, |dv_tf|, |dv_nf|


CUTOFFS = ("predicted", "energy")
THRUST_MODELS = ("constant", "tabulated")  #: [thrust] model: sec. 6 formula or sec. 7 histories  #: engine cut-off decision (EndGame.cutoff)


@dataclasses.dataclass(frozen=True)
class EndGame:
    """Guard of the VTD-NOG law near cut-off (docs/design/vtd-nog.md, "End-game"); kernel ogk_nog_config_t."""

    dtf_max_s: float | None   #: bound on |dt_f|; None: derived from t_f* (derive.resolve)
    du_max_rad: float         #: bound on the angle between corrected and nominal thrust directions
    freeze_time_to_go_s: float | None  #: no new correction below this nominal time to go; None: derived
    #: "predicted": cut-off at the time predicted at the last sample (eq. 32, the paper);
    #: "energy": kernel ogk_cutoff, cut when the orbital energy reaches the target's (beyond the paper)
    cutoff: str = "predicted"
    cutoff_arm_s: float | None = None         #: energy cut-off armed this long before the prediction; None: Delta t_S
    cutoff_extend_max_s: float | None = None  #: latest cut-off after the prediction; None: 2 Delta t_S
    fine_sample_interval_s: float | None = None  #: sampling interval near the end; None: Delta t_S throughout
    #: fine sampling while the predicted time to go is at most this; None: derived from t_f*
    #: (derive.resolve; only with the energy cut-off, else 0 = never)
    fine_window_s: float | None = 0.0
    #: kernel ogk_terminal: steer along the velocity to be gained once the predicted time to go is at
    #: most this (0: never; beyond the paper); None: derived from t_f* (derive.resolve; only with
    #: the energy cut-off, else 0)
    terminal_window_s: float | None = 0.0
    #: ogk_terminal position shaping: fraction of the radius and of the plane-normal position miss
    #: steered out in the window (0: not steered) and the time to go below which v_go steering
    #: takes over
    terminal_shape_gain: float = 0.0
    terminal_shape_gain_normal: float = 0.0
    terminal_shape_hold_s: float = 1.0
    terminal_shape_lead_s: float = 0.0
    #: kernel ogk_terminal turn limit: the vehicle's angular acceleration at its TVC command limit in
    #: the terminal window [rad/s^2] (0: none); None: derived from the vehicle (derive.resolve)
    terminal_turn_accel_rad_s2: float | None = None

    @property
    def terminal_shaped(self) -> bool:
        """The terminal window shapes the radius or the plane (else pure v_go steering)."""
        return self.terminal_shape_gain > 0.0 or self.terminal_shape_gain_normal > 0.0

    def arm_s(self, sample_interval_s: float) -> float:
        return self.cutoff_arm_s if self.cutoff_arm_s is not None else sample_interval_s

    def extend_max_s(self, sample_interval_s: float) -> float:
        return (self.cutoff_extend_max_s if self.cutoff_extend_max_s is not None
                else 2.0 * sample_interval_s)


@dataclasses.dataclass(frozen=True)
class OrbitInjectionScenario:
    """Everything section 6 of the paper specifies for the LEO-to-GEO injection burn (SI units)."""

    name: str
    source: str
    mu_m3_s2: float
    thrust: Thrust | TabulatedThrust
    pre_ignition: PreIgnitionOrbit | None   #: eq. (19) case B (free ignition anomaly), or None
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
    paper: PaperResults | None      #: published figures, only for the paper's own scenario
    acceptance: Acceptance = Acceptance(1000.0, 1000.0 / 42164.0e3, 10.0)
    path: Path | None = None        #: the file it was read from
    initial_state: InitialState | None = None   #: eq. (19) case A (specified state), or None

    @property
    def dispersions(self) -> Dispersions:
        """[dispersions] as one object (the same attribute name in every family)."""
        return Dispersions(self.initial_state_dispersion, self.attitude_dispersion,
                           self.actuator_dispersion, self.thrust_dispersion)

    @property
    def paper_results(self) -> dict[str, Any] | None:
        """[paper_results] as a dict, or None when the scenario has none (every family's name;
        `paper` is the same figures typed)."""
        return None if self.paper is None else dataclasses.asdict(self.paper)

    @property
    def target_circular_speed_m_s(self) -> float:
        """sqrt(mu / R_f), eq. (20)."""
        return math.sqrt(self.mu_m3_s2 / self.target_radius_m)


def load_scenario(path: str | Path | None = None) -> OrbitInjectionScenario:
    """Reads scenarios/leo_geo.toml (or `path`) and checks it: every missing key, wrong type,
    unknown key or physically impossible value is an `OgkInputError` naming file and key."""
    scenario_path = Path(path) if path is not None else DEFAULT_SCENARIO_PATH
    raw = read_toml(scenario_path)
    top = Section(raw, scenario_path, "")
    top.text("mission", choices=(MISSION,))
    check_header(raw, scenario_path, SCHEMA)
    top.text("schema")
    name = top.text("name")
    source = top.text("source", default="")
    gravity = top.section("gravity")
    mu = gravity.number("mu_m3_s2", positive=True)
    gravity.finish()

    thrust_s = top.section("thrust")
    thrust: Thrust | TabulatedThrust
    if thrust_s.text("model", "constant", choices=THRUST_MODELS) == "tabulated":
        thrust = _read_tabulated_thrust(thrust_s)
    else:
        thrust = thrust_s.dataclass(Thrust, exhaust_velocity_m_s={"positive": True},
                                    initial_accel_g0={"positive": True},
                                    standard_gravity_m_s2={"positive": True},
                                    initial_mass_kg={"positive": True})
    thrust_s.finish()

    pre: PreIgnitionOrbit | None = None
    initial: InitialState | None = None
    if top.has("initial_state") == top.has("pre_ignition_orbit"):
        raise top.error("initial_state", "give exactly one of [initial_state] (eq. 19 case A, a "
                        "specified ignition state) and [pre_ignition_orbit] (case B, free anomaly)")
    if top.has("pre_ignition_orbit"):
        orbit_s = top.section("pre_ignition_orbit")
        orbit_s.text("ignition_true_anomaly", choices=("free",))  # eq. 19 case B
        pre = orbit_s.dataclass(PreIgnitionOrbit, semi_major_axis_m={"positive": True},
                                eccentricity={"lo": 0.0, "hi": 0.99},
                                leo_altitude_m={"nonnegative": True},
                                earth_radius_m={"positive": True})
        orbit_s.finish()
    else:
        init_s = top.section("initial_state")
        initial = init_s.dataclass(InitialState, radius_m={"positive": True},
                                   transverse_velocity_m_s={"positive": True})
        init_s.finish()

    target_s = top.section("target_orbit")
    target_radius = target_s.number("radius_m", positive=True)
    target_s.finish()
    if pre is not None:
        perigee = pre.semi_major_axis_m * (1.0 - pre.eccentricity)
        apogee = pre.semi_major_axis_m * (1.0 + pre.eccentricity)
        if not target_radius > perigee:
            raise target_s.error("radius_m", f"target radius {target_radius:.6g} m is not above "
                                 f"the pre-ignition perigee {perigee:.6g} m")
        if apogee < target_radius * 0.5:
            raise target_s.error("radius_m", f"target radius {target_radius:.6g} m is more than "
                                 f"twice the pre-ignition apogee {apogee:.6g} m: outside the "
                                 f"documented envelope")
    elif not 0.5 < target_radius / initial.radius_m < 2.0:
        raise target_s.error("radius_m", f"target radius {target_radius:.6g} m is not within a "
                             f"factor 2 of the initial radius {initial.radius_m:.6g} m")

    mp_s = top.section("mass_properties")
    mass_properties = mp_s.dataclass(MassProperties, tvc_arm_m={"positive": True},
                                     inertia_x_kg_m2={"positive": True},
                                     inertia_y_kg_m2={"positive": True},
                                     inertia_z_kg_m2={"positive": True})
    mp_s.finish()
    act_s = top.section("actuators")
    actuators = act_s.dataclass(Actuators, **{f.name: {"positive": True}
                                              for f in dataclasses.fields(Actuators)})
    act_s.finish()

    guid_s = top.section("guidance")
    guid_s.text("law", choices=LAWS)
    sample_interval = guid_s.number("sample_interval_s", positive=True)
    eg_s = guid_s.section("end_game")
    cutoff = eg_s.text("cutoff", "predicted", choices=CUTOFFS)
    # what scales with the burn is derived from t_f* when absent (derive.resolve, issue 19); the
    # windows only with the energy cut-off (the paper's end-game has none)
    window_default = None if cutoff == "energy" else 0.0
    end_game = EndGame(dtf_max_s=eg_s.number("dtf_max_s", None, positive=True),
                       du_max_rad=eg_s.number("du_max_rad", positive=True, hi=math.pi),
                       freeze_time_to_go_s=eg_s.number("freeze_time_to_go_s", None,
                                                       nonnegative=True),
                       cutoff=cutoff,
                       cutoff_arm_s=eg_s.number("cutoff_arm_s", None, nonnegative=True),
                       cutoff_extend_max_s=eg_s.number("cutoff_extend_max_s", None,
                                                       nonnegative=True),
                       fine_sample_interval_s=eg_s.number("fine_sample_interval_s", None,
                                                          positive=True,
                                                          hi=sample_interval),
                       fine_window_s=eg_s.number(
                           "fine_window_s", window_default if eg_s.has("fine_sample_interval_s")
                           else 0.0, nonnegative=True),
                       terminal_window_s=eg_s.number("terminal_window_s", window_default,
                                                     nonnegative=True),
                       terminal_shape_gain=eg_s.number("terminal_shape_gain", 0.0,
                                                       nonnegative=True, hi=1.0),
                       terminal_shape_gain_normal=eg_s.number("terminal_shape_gain_normal", 0.0,
                                                              nonnegative=True, hi=1.0),
                       terminal_shape_hold_s=eg_s.number("terminal_shape_hold_s", 1.0,
                                                         positive=True),
                       terminal_shape_lead_s=eg_s.number("terminal_shape_lead_s", 0.0,
                                                         nonnegative=True, hi=1.0e7),
                       # kernel OGK_TERMINAL_TURN_ACCEL_MAX_RAD_S2
                       terminal_turn_accel_rad_s2=eg_s.number("terminal_turn_accel_rad_s2", None,
                                                              nonnegative=True, hi=1.0e4))
    shaped = end_game.terminal_shaped
    if (shaped and end_game.terminal_window_s is not None
            and not end_game.terminal_shape_hold_s <= end_game.terminal_window_s):
        raise eg_s.error("terminal_shape_hold_s",
                         f"must be <= terminal_window_s ({end_game.terminal_window_s:g} s) when "
                         f"a shape gain is set, got {end_game.terminal_shape_hold_s:g}")
    if shaped and end_game.terminal_shape_hold_s < 1.0e-3:
        raise eg_s.error("terminal_shape_hold_s", "must be >= 1e-3 s (kernel "
                         f"OGK_TERMINAL_HOLD_MIN_S), got {end_game.terminal_shape_hold_s:g}")
    eg_s.finish()
    guid_s.finish()

    cpd = _read_cpd(top.section("cpd"))
    disp = top.section("dispersions")
    isd_s, att_s, actd_s, thr_s = (disp.section(k) for k in
                                   ("initial_state", "attitude", "actuators", "thrust"))
    nonneg = {"nonnegative": True}
    initial_state = isd_s.dataclass(InitialStateDispersion, **{
        f.name: nonneg for f in dataclasses.fields(InitialStateDispersion)})
    attitude = att_s.dataclass(AttitudeDispersion, **{
        f.name: nonneg for f in dataclasses.fields(AttitudeDispersion)})
    actuator = actd_s.dataclass(ActuatorDispersion, **{
        f.name: nonneg for f in dataclasses.fields(ActuatorDispersion)})
    thrust_disp = ThrustDispersion(harmonics=thr_s.integer("harmonics", lo=0, hi=50),
                                   coefficient_sigma=thr_s.number("coefficient_sigma",
                                                                  nonnegative=True))
    for sec in (isd_s, att_s, actd_s, thr_s, disp):
        sec.finish()

    acceptance = _read_acceptance(top.section("acceptance", optional=True), target_radius)
    paper = _read_paper(top.section("paper_results")) if top.has("paper_results") else None
    top.finish()

    scenario = OrbitInjectionScenario(
        name=name, source=source, mu_m3_s2=mu, thrust=thrust, pre_ignition=pre,
        target_radius_m=target_radius, mass_properties=mass_properties, actuators=actuators,
        sample_interval_s=sample_interval, end_game=end_game, cpd=cpd,
        initial_state_dispersion=initial_state, attitude_dispersion=attitude,
        actuator_dispersion=actuator, thrust_dispersion=thrust_disp, paper=paper,
        acceptance=acceptance, path=Path(scenario_path), initial_state=initial)
    _check(scenario, top)
    return scenario


def _read_cpd(sec: Section) -> Cpd:
    gains = {}
    for key in ("printed", "rederived"):
        if sec.has(key):
            g = sec.section(key)
            gains[key] = g.dataclass(CpdGains, **{f.name: {"positive": True}
                                                  for f in dataclasses.fields(CpdGains)})
            g.finish()
        else:
            gains[key] = None
    flown = sec.text("flown", default="rederived", choices=("printed", "rederived"))
    if flown == "printed" and gains["printed"] is None:
        raise sec.error("flown", "is 'printed' but there is no [cpd.printed] table")
    cpd = Cpd(natural_frequency_rad_s=sec.number("natural_frequency_rad_s", positive=True),
              damping_ratio=sec.number("damping_ratio", positive=True),
              roll_command_rad=sec.number("roll_command_rad"),
              roll_torque_command_max_n_m=sec.number("roll_torque_command_max_n_m", positive=True),
              deflection_y_command_max_rad=sec.number("deflection_y_command_max_rad", positive=True),
              deflection_z_command_max_rad=sec.number("deflection_z_command_max_rad", positive=True),
              roll_torque_rate_bound_n_m_s=sec.number("roll_torque_rate_bound_n_m_s", positive=True),
              deflection_rate_bound_rad_s=sec.number("deflection_rate_bound_rad_s", positive=True),
              flown=flown,
              braking_margin=sec.number("braking_margin", nonnegative=True, hi=1.0),
              feedforward=sec.flag("feedforward"),
              feedforward_rate_max_rad_s=sec.number("feedforward_rate_max_rad_s", positive=True),
              printed=gains["printed"], rederived=gains["rederived"])
    sec.finish()
    return cpd


def _read_acceptance(sec: Section, target_radius_m: float) -> Acceptance:
    """Failure criterion of a run (docs/guides/sil.md): |error| above these is a failed injection.
    STATED DEFAULT (docs/guides/adding-a-mission.md, "The scenario header"): radius_error_m = 1000 m,
    declination_error_rad = radius_error_m / R_f, velocity_error_m_s = 10 m/s."""
    radius = sec.number("radius_error_m", 1000.0, positive=True)
    acc = Acceptance(
        radius_error_m=radius,
        declination_error_rad=sec.number("declination_error_rad", radius / target_radius_m,
                                         positive=True),
        velocity_error_m_s=sec.number("velocity_error_m_s", 10.0, positive=True))
    sec.finish()
    return acc


def _read_paper(sec: Section) -> PaperResults:
    paper = PaperResults(
        min_time_s=sec.number("min_time_s", positive=True),
        ignition_true_anomaly_rad=sec.number("ignition_true_anomaly_rad", None),
        monte_carlo_runs=sec.integer("monte_carlo_runs", lo=1),
        table6_final_errors=sec.numbers("table6_final_errors", 6),
        table7_mean=sec.numbers("table7_mean", 6),
        table7_sigma=sec.numbers("table7_sigma", 6),
        single_run_table=sec.text("single_run_table", "Table 6"),
        monte_carlo_table=sec.text("monte_carlo_table", "Table 7"))
    sec.finish()
    return paper


def _read_tabulated_thrust(sec: Section) -> TabulatedThrust:
    """[thrust] with model = "tabulated": time_s, thrust_n, mass_kg of equal lengths (>= 4 points),
    time from 0 strictly increasing, thrust > 0, mass > 0 and decreasing."""
    time_s = sec.numbers("time_s")
    n = len(time_s)
    if n < 4:
        raise sec.error("time_s", f"needs at least 4 points for the cubic interpolation, got {n}")
    thrust_n, mass_kg = sec.numbers("thrust_n", n), sec.numbers("mass_kg", n)
    if time_s[0] != 0.0:
        raise sec.error("time_s", f"must start at 0 (ignition), got {time_s[0]:g}")
    if any(b <= a for a, b in zip(time_s, time_s[1:])):
        raise sec.error("time_s", "must be strictly increasing")
    if not all(v > 0.0 and math.isfinite(v) for v in thrust_n):
        raise sec.error("thrust_n", "every entry must be > 0")
    if not all(v > 0.0 and math.isfinite(v) for v in mass_kg):
        raise sec.error("mass_kg", "every entry must be > 0")
    if any(b >= a for a, b in zip(mass_kg, mass_kg[1:])):
        raise sec.error("mass_kg", "must decrease (the motor burns propellant)")
    return TabulatedThrust(time_s=time_s, thrust_n=thrust_n, mass_kg=mass_kg)


def _check(scn: OrbitInjectionScenario, top: Section) -> None:
    """Cross-key physics: the propellant must last well beyond any plausible burn."""
    burnout_s = scn.thrust.burnout_s
    if burnout_s <= 4.0 * scn.sample_interval_s:
        raise top.section("guidance").error(
            "sample_interval_s", f"{scn.sample_interval_s:g} s is too long for a burn that "
            f"exhausts the whole mass in {burnout_s:.3g} s")
