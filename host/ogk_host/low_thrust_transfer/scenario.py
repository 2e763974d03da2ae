"""Apophis CubeSat scenario (Wang & Topputo 2020, Tables 1-6): TOML file -> dataclasses.

Everything the solvers use is in the paper's normalised units: LU, TU, MU and velocities in LU/TU
(not the printed VU, see the ERRATUM note in scenarios/apophis_cubesat.toml). `NormalisedProblem`
holds one boundary value problem (nominal or perturbed) in those units.
"""
from __future__ import annotations

import dataclasses
import math
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ogk_bindings.errors import OgkInputError
from ..paths import SCENARIO_DIR
from ..scenario_file import Section, check_header, read_toml, schema_of

FloatArray = NDArray[np.float64]

SECONDS_PER_DAY = 86400.0
DEFAULT_SCENARIO_PATH = SCENARIO_DIR / "apophis_cubesat.toml"
MISSION = "low-thrust-transfer"  #: the family name of ogk.missions.registry
SCHEMA = schema_of(MISSION)      #: "ogk.low-thrust-transfer/1" (the header, ogk_host.scenario_file)
LAWS = ("mpsp",)                 #: guidance laws this family flies
#: [paper_results] of Wang & Topputo 2020: the columns of Tables 3, 5, 6 (one entry per case, rows in the
#: order of [dispersions]), the row labels some tables print, and the nominal of section 4.1.
PAPER_COLUMNS = ("position_error_km", "velocity_error_km_s", "lambda_mf", "newton_iterations",
                 "fuel_increase_percent", "mpsp_time_s", "tpbvp_time_s")
PAPER_ROW_LABELS = {"table3": "kappa", "table5": None, "table6": "eta_percent"}
PAPER_NOMINAL = ("final_mass_kg", "thrust_arcs", "coast_arcs")


@dataclasses.dataclass(frozen=True)
class Units:
    """Table 1 normalisation units."""

    length_km: float           #: LU [km]
    time_s: float              #: TU [s]
    mass_kg: float             #: MU [kg]
    velocity_km_s_printed: float  #: VU as printed [km/s]; unused (LU/TU is used instead)
    mu_sun_km3_s2: float       #: Sun gravitational parameter [km^3/s^2]
    g0_m_s2: float             #: gravitational acceleration at sea level [m/s^2]

    @property
    def velocity_km_s(self) -> float:
        """Velocity unit consistent with LU and TU [km/s]."""
        return self.length_km / self.time_s

    @property
    def acceleration_m_s2(self) -> float:
        """Acceleration unit LU/TU^2 [m/s^2]."""
        return self.length_km * 1.0e3 / self.time_s**2

    @property
    def force_N(self) -> float:
        """Force unit MU LU/TU^2 [N]."""
        return self.mass_kg * self.acceleration_m_s2


@dataclasses.dataclass(frozen=True)
class Spacecraft:
    initial_mass_kg: float
    max_thrust_N: float
    specific_impulse_s: float


@dataclasses.dataclass(frozen=True)
class Boundary:
    """Table 2 boundary conditions [LU, LU/TU]."""

    r0: FloatArray
    v0: FloatArray
    rf: FloatArray
    vf: FloatArray


@dataclasses.dataclass(frozen=True)
class Homotopy:
    """Smoothing homotopy of eq. (48) and shooting tolerances."""

    zeta_start: float
    thrust_factor_start: float
    zeta_step: float
    zeta_step_min: float
    final_rtol: float
    smoothed_rtol: float
    tight_below_zeta: float

    def rtol(self, zeta: float) -> float:
        """Integration tolerance for the shooting at smoothing level zeta."""
        return self.final_rtol if zeta < self.tight_below_zeta else self.smoothed_rtol


@dataclasses.dataclass(frozen=True)
class MpspSettings:
    """Section 4.1 MPSP settings (consumed by the MPSP tool, not by the indirect solver)."""

    fourier_order: int
    eta_start: float
    eta_end: float
    fourier_basis: str
    h_max_over_tf: float
    delta_max: float
    delta_tau_initial: float
    delta_tau_min: float
    n_seg_tol_initial: int
    n_seg_tol_increment: int
    r_epsilon: str
    r_lambda: float
    switch_tolerance: float
    tol_position_km: float
    tol_velocity_km_s: float
    tol_lambda_mf: float


@dataclasses.dataclass(frozen=True)
class Dispersions:
    """[dispersions]: the perturbation cases of sections 4.2-4.4 (Tables 3, 4, 6), flown as listed
    (`ogk mc --cases paper`) or drawn within their ranges (`--cases dispersed`)."""

    kappa: tuple[float, ...]
    delta_r0_printed: FloatArray      #: [LU] as printed
    delta_v0_printed: FloatArray      #: [VU] as printed
    printed_vector_scale: float       #: ERRATUM factor (0.1) applied to both printed vectors
    cube_side: float                  #: [LU]
    delta_rf_vertices: FloatArray     #: (8, 3) [LU]
    eta_percent: tuple[float, ...]

    @property
    def delta_r0(self) -> FloatArray:
        """Basic initial-position perturbation actually used [LU]."""
        return self.printed_vector_scale * self.delta_r0_printed

    @property
    def delta_v0(self) -> FloatArray:
        """Basic initial-velocity perturbation actually used [LU/TU]."""
        return self.printed_vector_scale * self.delta_v0_printed


@dataclasses.dataclass(frozen=True)
class Scenario:
    path: Path
    units: Units
    spacecraft: Spacecraft
    duration_days: float
    boundary: Boundary
    homotopy: Homotopy
    mpsp: MpspSettings
    dispersions: Dispersions
    paper_results: dict[str, Any] | None   #: [paper_results] (section 4.1, Tables 3, 5, 6); None: none
    acceptance: "Acceptance"

    @property
    def final_time(self) -> float:
        """Transfer duration t_f - t_0 [TU]."""
        return self.duration_days * SECONDS_PER_DAY / self.units.time_s


@dataclasses.dataclass(frozen=True)
class Acceptance:
    """[acceptance]: a case passes when MPSP converged with terminal errors no larger than these.

    Default when the scenario has no [acceptance] (or leaves a key out): the MPSP convergence
    tolerances of [mpsp], position_error_km = tol_position_km, velocity_error_km_s = tol_velocity_km_s."""

    position_error_km: float        #: ||Delta r_f|| [km]
    velocity_error_km_s: float      #: ||Delta v_f|| [km/s]


@dataclasses.dataclass(frozen=True)
class Perturbation:
    """Deviation of one problem from the nominal one (section 4.2-4.4); zero = nominal.

    `scaled(tau)` gives C_tau = (1 - tau) C_nom + tau C_per of eq. (51).
    """

    delta_r0: FloatArray = dataclasses.field(default_factory=lambda: np.zeros(3))  #: [LU]
    delta_v0: FloatArray = dataclasses.field(default_factory=lambda: np.zeros(3))  #: [LU/TU]
    delta_rf: FloatArray = dataclasses.field(default_factory=lambda: np.zeros(3))  #: [LU]
    thrust_fraction: float = 0.0   #: eta: T_max -> (1 + eta) T_max
    label: str = "nominal"

    def scaled(self, tau: float) -> "Perturbation":
        return Perturbation(tau * self.delta_r0, tau * self.delta_v0, tau * self.delta_rf,
                            tau * self.thrust_fraction, f"{self.label} (tau={tau:.4g})")

    @property
    def is_nominal(self) -> bool:
        return (not np.any(self.delta_r0) and not np.any(self.delta_v0)
                and not np.any(self.delta_rf) and self.thrust_fraction == 0.0)


def initial_state_case(scenario: Scenario, kappa: float) -> Perturbation:
    """Table 3 case: r0 + kappa dr0, v0 + kappa dv0 (printed vectors times the ERRATUM scale)."""
    p = scenario.dispersions
    return Perturbation(delta_r0=kappa * p.delta_r0, delta_v0=kappa * p.delta_v0,
                        label=f"kappa={kappa:g}")


def terminal_position_case(scenario: Scenario, case: int) -> Perturbation:
    """Table 4 case 1..8: r_f + vertex of the 0.04 LU cube."""
    vertex = scenario.dispersions.delta_rf_vertices[case - 1]
    return Perturbation(delta_rf=vertex.copy(), label=f"cube vertex {case}")


def thrust_case(scenario: Scenario, eta_percent: float) -> Perturbation:
    """Table 6 case: T_max (1 + eta)."""
    return Perturbation(thrust_fraction=eta_percent / 100.0, label=f"eta={eta_percent:g}%")


@dataclasses.dataclass(frozen=True)
class NormalisedProblem:
    """One fixed-time rendezvous problem in normalised units (mu = mu_sun TU^2/LU^3 ~ 1)."""

    mu: float
    max_thrust: float       #: T_max [MU LU/TU^2], already scaled by (1 + eta)
    exhaust_velocity: float  #: c = Isp g0 [LU/TU]
    final_time: float       #: t_f [TU] (t_0 = 0)
    x0: FloatArray          #: [r0, v0, m0] (7)
    rf: FloatArray
    vf: FloatArray


def normalised_problem(scenario: Scenario,
                       perturbation: Perturbation | None = None) -> NormalisedProblem:
    u = scenario.units
    sc = scenario.spacecraft
    b = scenario.boundary
    pert = perturbation if perturbation is not None else Perturbation()
    mu = u.mu_sun_km3_s2 * u.time_s**2 / u.length_km**3
    max_thrust = sc.max_thrust_N * (1.0 + pert.thrust_fraction) / u.force_N
    exhaust_velocity = sc.specific_impulse_s * u.g0_m_s2 * 1.0e-3 / u.velocity_km_s
    x0 = np.concatenate([b.r0 + pert.delta_r0, b.v0 + pert.delta_v0,
                         [sc.initial_mass_kg / u.mass_kg]])
    return NormalisedProblem(mu=mu, max_thrust=max_thrust, exhaust_velocity=exhaust_velocity,
                             final_time=scenario.final_time, x0=x0,
                             rf=b.rf + pert.delta_rf, vf=b.vf.copy())


def _vec(values: Any) -> FloatArray:
    return np.asarray(values, dtype=np.float64)


def load_scenario(path: str | Path = DEFAULT_SCENARIO_PATH) -> Scenario:
    """Read scenarios/apophis_cubesat.toml (or another file of the same shape)."""
    path = Path(path)
    d = read_toml(path)
    if d.get("mission") != MISSION or d.get("guidance", {}).get("law") not in LAWS:
        raise OgkInputError(f"mission must be {MISSION!r} with [guidance] law in {LAWS}, got "
                            f"{d.get('mission')!r} / {d.get('guidance', {}).get('law')!r}", path=path)
    check_header(d, path, SCHEMA)
    tracked = _Tracked.wrap(d)
    for key in ("schema", "name", "source", "mission"):  # the header (ogk_host.scenario_file)
        tracked.get(key)
    tracked.get("guidance", {}).get("law")
    for key in ("departure_utc", "arrival_utc"):  # descriptive
        tracked.get("transfer", {}).get(key)
    _check_values(d, path)          # every number: type, finite, sign (one line, before computing)
    try:
        scenario = _build(path, tracked)
    except KeyError as exc:
        raise OgkInputError(f"missing key {exc.args[0]!r}", path=path) from None
    except (TypeError, ValueError) as exc:
        raise OgkInputError(str(exc), path=path) from None
    top = Section(d, path, "")
    scenario = dataclasses.replace(
        scenario, paper_results=_read_paper(top.raw_table("paper_results"), path),
        acceptance=_read_acceptance(top.section("acceptance", optional=True), scenario.mpsp))
    unknown = tracked.unread(skip=("paper_results", "acceptance"))
    if unknown:
        raise OgkInputError("unknown key" + (f" (also {', '.join(unknown[1:])})" if len(unknown) > 1
                                             else ""), path=path, key=unknown[0])
    check_reachable(scenario)
    return scenario


#: OGK_MPSP_MAX_ORDER of kernel/include/ogk/mpsp.h (the kernel's weight arrays)
MAX_FOURIER_ORDER = 15
#: the Fourier bases of fourier.py / ogk_bindings.mpsp.paper_basis
FOURIER_BASES = ("printed", "period_tf", "period_2tf", "cosine_2tf")

#: [section] -> keys that must be finite numbers > 0
_POSITIVE = {
    "units": ("length_unit_km", "time_unit_s", "mass_unit_kg", "velocity_unit_km_s_printed",
              "mu_sun_km3_s2", "g0_m_s2"),
    "spacecraft": ("initial_mass_kg", "max_thrust_N", "specific_impulse_s"),
    "transfer": ("duration_days",),
    "homotopy": ("zeta_start", "thrust_factor_start", "zeta_step", "zeta_step_min", "final_rtol",
                 "smoothed_rtol", "tight_below_zeta"),
    "mpsp": ("h_max_over_tf", "delta_max", "delta_tau_initial", "delta_tau_min", "r_lambda",
             "switch_tolerance", "tol_position_km", "tol_velocity_km_s", "tol_lambda_mf"),
}


def _check_values(d: dict[str, Any], path: Path) -> None:
    """Types and ranges of every number the solvers use (OgkInputError FILE: KEY: REASON): a string
    where a number belongs, nan/inf, a zero or negative mass, thrust, Isp, duration, unit or
    tolerance are refused here, before anything is computed."""
    top = Section(d, path, "")
    for name, keys in _POSITIVE.items():
        sec = top.section(name)
        for key in keys:
            sec.number(key, positive=True)
    ho, mp = top.section("homotopy"), top.section("mpsp")
    ho.number("zeta_start", hi=1.0)
    ho.number("thrust_factor_start", lo=1.0)
    for key in ("final_rtol", "smoothed_rtol"):
        ho.number(key, hi=1e-3)
    mp.number("h_max_over_tf", hi=1.0)
    mp.number("delta_tau_initial", hi=1.0)
    mp.number("delta_tau_min", hi=1.0)
    mp.number("eta_start")
    mp.number("eta_end")
    mp.integer("fourier_order", lo=1, hi=MAX_FOURIER_ORDER)
    mp.integer("n_seg_tol_initial", lo=0)
    mp.integer("n_seg_tol_increment", lo=0)
    mp.text("fourier_basis")
    mp.text("r_epsilon")
    bd = top.section("boundary")
    for key in ("initial_position_LU", "initial_velocity_VU", "final_position_LU", "final_velocity_VU"):
        vec = bd.numbers(key, 3)
        if not all(math.isfinite(x) for x in vec):
            raise bd.error(key, f"must be 3 finite numbers, got {list(vec)}")
    for key in ("initial_position_LU", "final_position_LU"):
        if not sum(x * x for x in bd.numbers(key, 3)) > 0.0:
            raise bd.error(key, "must not be the origin (the Sun)")
    disp = top.section("dispersions")
    ini, ter, thr = disp.section("initial"), disp.section("terminal"), disp.section("thrust")
    for sec, key, n in ((ini, "kappa", None), (ini, "delta_position_printed_LU", 3),
                        (ini, "delta_velocity_printed_VU", 3), (thr, "eta_percent", None)):
        vec = sec.numbers(key, n)
        if not vec or not all(math.isfinite(x) for x in vec):
            raise sec.error(key, f"must be a non-empty list of finite numbers, got {list(vec)}")
    if not min(thr.numbers("eta_percent")) > -100.0:
        raise thr.error("eta_percent", "must be > -100 (T_max (1 + eta/100) > 0)")
    ini.number("printed_vector_scale")
    ter.number("cube_side_LU", positive=True)
    vertices = ter._get("delta_final_position_LU", None)
    if (not isinstance(vertices, list) or len(vertices) != 8
            or any(not isinstance(v, list) or len(v) != 3
                   or any(isinstance(x, bool) or not isinstance(x, (int, float)) or not math.isfinite(x)
                          for x in v) for v in vertices)):
        raise ter.error("delta_final_position_LU", "must be the 8 vertices of the cube, 3 finite "
                        "numbers each")


#: STATED ENVELOPE (docs/guides/mpsp-cli.md, "Input checks"): a transfer is refused before any solve when
#: the target is out of reach of the engine even in free space with this margin for gravity.
REACH_MARGIN = 10.0


def check_reachable(scenario: Scenario) -> None:
    """A necessary condition for the nominal to exist, checked before any solve: the target's
    offset from the ballistic (thrust-free) arc at t_f must be within REACH_MARGIN times what the
    engine can give in free space over t_f at full thrust, in velocity the rocket equation
    dv = c ln(m0 / (m0 - mdot t_f)), in position the double integral of that acceleration
    (<= dv t_f). A duration far too short for the transfer ends here as one line, not as a
    3e8 km miss reported as a result."""
    from scipy.integrate import solve_ivp
    prob = normalised_problem(scenario, None)
    tf, mu = prob.final_time, prob.mu
    def rhs(t: float, y: FloatArray) -> FloatArray:
        r = y[:3]
        return np.concatenate([y[3:], -mu * r / float(np.linalg.norm(r)) ** 3])
    sol = solve_ivp(rhs, (0.0, tf), prob.x0[:6], method="DOP853", rtol=1e-9, atol=1e-12)
    if sol.status != 0:
        return  # a collision course; the solver will say more
    y = sol.y[:, -1]
    m0, c, tmax = float(prob.x0[6]), prob.exhaust_velocity, prob.max_thrust
    burn = min(tmax / c * tf, 0.999 * m0)       # propellant at full thrust over t_f (capped)
    dv = c * math.log(m0 / (m0 - burn))
    need_v = float(np.linalg.norm(prob.vf - y[3:6]))
    need_r = float(np.linalg.norm(prob.rf - y[0:3]))
    u = scenario.units
    if need_v > REACH_MARGIN * dv or need_r > REACH_MARGIN * dv * tf:
        raise OgkInputError(
            f"{scenario.duration_days:g} days at {scenario.spacecraft.max_thrust_N:g} N cannot reach the "
            f"target: it is {need_r * u.length_km:.3g} km and {need_v * u.velocity_km_s:.3g} km/s from "
            f"the thrust-free arc at t_f, the engine gives at most {dv * u.velocity_km_s:.3g} km/s "
            f"(envelope: {REACH_MARGIN:g} x the free-space reach, docs/guides/mpsp-cli.md)",
            path=scenario.path, key="transfer.duration_days")


class _Tracked(dict):  # type: ignore[type-arg]
    """A TOML table that remembers which keys were read, so that a key no loader reads (a typo)
    is reported instead of silently ignored."""

    @classmethod
    def wrap(cls, value: Any) -> Any:
        if isinstance(value, dict):
            out = cls({k: cls.wrap(v) for k, v in value.items()})
            out.read_keys = set()
            return out
        return value

    def __getitem__(self, key: str) -> Any:
        self.read_keys.add(key)
        return super().__getitem__(key)

    def get(self, key: str, default: Any = None) -> Any:
        self.read_keys.add(key)
        return super().get(key, default)

    def unread(self, prefix: str = "", skip: tuple[str, ...] = ()) -> list[str]:
        out: list[str] = []
        for key, value in self.items():
            name = f"{prefix}{key}"
            if key in skip:
                continue
            if key not in self.read_keys:
                out.append(name)
            elif isinstance(value, _Tracked):
                out.extend(value.unread(f"{name}."))
        return sorted(out)


def _build(path: Path, d: dict[str, Any]) -> Scenario:
    un, sc, bd, ho, mp = d["units"], d["spacecraft"], d["boundary"], d["homotopy"], d["mpsp"]
    pi, pt, pth = (d["dispersions"]["initial"], d["dispersions"]["terminal"],
                   d["dispersions"]["thrust"])
    vertices = _vec(pt["delta_final_position_LU"])
    if vertices.shape != (8, 3) or not np.allclose(np.abs(vertices), pt["cube_side_LU"] / 2.0):
        raise ValueError("dispersions.terminal: must be the 8 vertices of the cube")
    if mp["fourier_basis"] not in ("printed", "period_tf", "period_2tf", "cosine_2tf"):
        raise ValueError(f"mpsp.fourier_basis: unknown {mp['fourier_basis']!r}")
    return Scenario(
        path=path,
        units=Units(un["length_unit_km"], un["time_unit_s"], un["mass_unit_kg"],
                    un["velocity_unit_km_s_printed"], un["mu_sun_km3_s2"], un["g0_m_s2"]),
        spacecraft=Spacecraft(sc["initial_mass_kg"], sc["max_thrust_N"], sc["specific_impulse_s"]),
        duration_days=float(d["transfer"]["duration_days"]),
        boundary=Boundary(_vec(bd["initial_position_LU"]), _vec(bd["initial_velocity_VU"]),
                          _vec(bd["final_position_LU"]), _vec(bd["final_velocity_VU"])),
        homotopy=Homotopy(ho["zeta_start"], ho["thrust_factor_start"], ho["zeta_step"], ho["zeta_step_min"],
                          ho["final_rtol"], ho["smoothed_rtol"], ho["tight_below_zeta"]),
        mpsp=MpspSettings(int(mp["fourier_order"]), mp["eta_start"], mp["eta_end"],
                          mp["fourier_basis"], mp["h_max_over_tf"], mp["delta_max"],
                          mp["delta_tau_initial"], mp["delta_tau_min"], int(mp["n_seg_tol_initial"]),
                          int(mp["n_seg_tol_increment"]), mp["r_epsilon"], mp["r_lambda"],
                          mp["switch_tolerance"], mp["tol_position_km"], mp["tol_velocity_km_s"],
                          mp["tol_lambda_mf"]),
        dispersions=Dispersions(tuple(pi["kappa"]), _vec(pi["delta_position_printed_LU"]),
                                _vec(pi["delta_velocity_printed_VU"]),
                                float(pi["printed_vector_scale"]), float(pt["cube_side_LU"]),
                                vertices, tuple(pth["eta_percent"])),
        paper_results=None,                       # read by load_scenario (Section)
        acceptance=Acceptance(float(mp["tol_position_km"]), float(mp["tol_velocity_km_s"])),
    )


def _read_acceptance(sec: Section, mpsp: MpspSettings) -> Acceptance:
    """[acceptance]; STATED DEFAULT (docs/guides/adding-a-mission.md, "The scenario header"): the [mpsp]
    convergence tolerances tol_position_km and tol_velocity_km_s."""
    acc = Acceptance(position_error_km=sec.number("position_error_km", mpsp.tol_position_km, positive=True),
                     velocity_error_km_s=sec.number("velocity_error_km_s", mpsp.tol_velocity_km_s,
                                                    positive=True))
    sec.finish()
    return acc


def _read_paper(raw: dict[str, Any] | None, path: Path) -> dict[str, Any] | None:
    """[paper_results]: optional; [paper_results.nominal] (section 4.1) and [paper_results.table3|5|6],
    each table's columns lists of numbers of one length (PAPER_COLUMNS, plus its row labels)."""
    if raw is None:
        return None
    top = Section(raw, path, "paper_results")
    if top.has("nominal"):
        nom = top.section("nominal")
        for key in PAPER_NOMINAL:
            if nom.has(key):
                nom.number(key, positive=True)
        nom.finish()
    for table, label in PAPER_ROW_LABELS.items():
        if not top.has(table):
            continue
        sec = top.section(table)
        length = len(sec.numbers(label)) if label is not None and sec.has(label) else None
        for key in PAPER_COLUMNS:
            if sec.has(key):
                length = len(sec.numbers(key, length))
        sec.finish()
    top.finish()
    return raw
