"""Binary-asteroid BLT scenarios (Xiong & Wang, Table 1 and sec. IV): TOML -> frozen dataclasses.

Everything in the file is SI (m, s, kg, N, W, rad), with the unit in each key's name; the normalised units
of the model (LU = D, TU = T_o / (2 pi), docs/design/blt.md section 1) are built by `units.Units` and
`BinaryScenario.units`. Every complaint is an `OgkInputError` naming the file and the key.

Sections: [system] (Table 1), [gravity] (the model and the assumed homogeneous ellipsoid of each body),
[sun], [spacecraft] (sec. IV), [orbits.NAME] (the libration-point orbits of the study, built by
`orbits.scenario_orbit`), [transfers.NAME], [solver] and [monte_carlo] (returned as the raw TOML tables,
read key by key by `transfers`), and the common header tables (docs/guides/adding-a-mission.md, "The scenario
header"): [dispersions] (what the Table 3 campaign draws: levels_percent, sigma_fraction), [acceptance]
(error_tolerance) and the optional [paper_results] ([paper_results.transfers.NAME], [paper_results.table3]).
"""
from __future__ import annotations

import dataclasses
import math
from pathlib import Path
from typing import Any

from ..paths import SCENARIO_DIR
from ..scenario_file import Section, check_header, read_toml, schema_of
from .units import Units

DEFAULT_SCENARIO_PATH = SCENARIO_DIR / "moshup.toml"
MISSION = "binary-asteroid"
SCHEMA = schema_of(MISSION)     #: "ogk.binary-asteroid/1" (the header, ogk_host.scenario_file)
LAWS = ("blt",)
GRAVITY_MODELS = ("degree2", "point-mass")
ORBIT_FAMILIES = ("lyapunov", "halo")
LIBRATION_POINTS = ("L1", "L2")
HALO_BRANCHES = ("north", "south")
#: The homogeneous ellipsoid's mass rho V must agree with Table 1's mass within this fraction: the
#: ellipsoid is an assumption about the shape, never a second mass (docs/design/blt-ground.md, "Gravity").
ELLIPSOID_MASS_TOLERANCE = 0.02
#: [paper_results.transfers.NAME]: the paper's figures of one transfer; [paper_results.table3]: Table 3.
PAPER_TRANSFER_KEYS = ("flight_time_s", "burn_time_s", "fuel_g", "iterations")
PAPER_TABLE3_KEYS = ("levels_percent", "converged_percent")


@dataclasses.dataclass(frozen=True)
class System:
    """Table 1 ("Facts about 66391 Moshup"), in SI."""

    primary_mass_kg: float          #: M1
    secondary_mass_kg: float        #: M2
    primary_density_kg_m3: float    #: sigma_1
    secondary_density_kg_m3: float  #: sigma_2
    primary_radius_m: float         #: "~500 m" (printed; inconsistent with mass and density; unused)
    secondary_radius_m: float       #: "~100 m" (idem)
    mutual_period_s: float          #: T_o
    separation_m: float             #: D

    @property
    def mu(self) -> float:
        """Eq. (1): M2 / (M1 + M2)."""
        return self.secondary_mass_kg / (self.primary_mass_kg + self.secondary_mass_kg)


@dataclasses.dataclass(frozen=True)
class Ellipsoid:
    """The assumed homogeneous triaxial ellipsoid of one body, its axes along the synodic x, y, z (the
    secondary's long axis points at the primary; the primary is axisymmetric, docs/design/blt.md section 1)."""

    semi_axes_m: tuple[float, float, float]   #: (a, b, c) along x, y, z [m]
    impact_radius_m: float                    #: radius of the sphere that counts as an impact [m]

    @property
    def volume_m3(self) -> float:
        a, b, c = self.semi_axes_m
        return 4.0 / 3.0 * math.pi * a * b * c

    @property
    def equal_volume_radius_m(self) -> float:
        """R = (a b c)^(1/3): the normalising radius of C20 and C22."""
        a, b, c = self.semi_axes_m
        return (a * b * c) ** (1.0 / 3.0)

    @property
    def c20(self) -> float:
        """Unnormalised C20 of a homogeneous ellipsoid, (2 c^2 - a^2 - b^2) / (10 R^2)."""
        a, b, c = self.semi_axes_m
        return (2.0 * c * c - a * a - b * b) / (10.0 * self.equal_volume_radius_m ** 2)

    @property
    def c22(self) -> float:
        """Unnormalised C22 of a homogeneous ellipsoid, (a^2 - b^2) / (20 R^2)."""
        a, b, _ = self.semi_axes_m
        return (a * a - b * b) / (20.0 * self.equal_volume_radius_m ** 2)


@dataclasses.dataclass(frozen=True)
class Gravity:
    """[gravity]: "degree2" (eq. 7 to degree 2 of each ellipsoid) or "point-mass" (C20 = C22 = 0)."""

    model: str
    primary: Ellipsoid
    secondary: Ellipsoid


@dataclasses.dataclass(frozen=True)
class Sun:
    """[sun]: sec. II.B.2 (aphelion, 1.622e8 km) and the SRP constants of eq. (9)."""

    distance_m: float               #: d, Sun to the binary's barycentre
    mu_m3_s2: float                 #: mu_sun
    astronomical_unit_m: float      #: 1 AU, the reference distance of the flux
    flux_1au_w_m2: float            #: solar flux at 1 AU
    speed_of_light_m_s: float       #: c
    angle0_rad: float               #: phi(0): the Sun's direction in the synodic frame at t = 0

    @property
    def pressure_n_m2(self) -> float:
        """p_SR = flux_1AU (1 AU / d)^2 / c [N/m^2] (eq. 9, "p_SR at 1.1 AU")."""
        return self.flux_1au_w_m2 * (self.astronomical_unit_m / self.distance_m) ** 2 / self.speed_of_light_m_s

    @property
    def mean_motion_rad_s(self) -> float:
        """n_helio = sqrt(mu_sun / d^3): the binary's heliocentric angular rate, taken circular at d
        (the paper gives only the distance; an assumption, docs/design/blt-ground.md)."""
        return math.sqrt(self.mu_m3_s2 / self.distance_m ** 3)


@dataclasses.dataclass(frozen=True)
class Spacecraft:
    """Sec. IV: the DART-like spacecraft."""

    mass_kg: float                  #: m0
    area_m2: float                  #: A_sc (12.5 m x 4 m)
    reflectivity_cr: float          #: C_R
    specific_impulse_s: float       #: I_sp
    standard_gravity_m_s2: float    #: g0


@dataclasses.dataclass(frozen=True)
class OrbitSpec:
    """[orbits.NAME]: one libration-point orbit of the study (built by `orbits.scenario_orbit`).

    amplitude_m: a planar Lyapunov orbit's Ax = half the distance between its two x-axis crossings; a
    halo's Az = the larger |z| of its two x-z plane crossings. branch (halos only): "north" if z is
    positive at that crossing, "south" if negative (JPL's catalogue convention)."""

    name: str
    family: str                     #: "lyapunov" | "halo"
    point: str                      #: "L1" | "L2"
    amplitude_m: float
    branch: str | None = None       #: "north" | "south" for a halo, None for a Lyapunov orbit


@dataclasses.dataclass(frozen=True)
class Dispersions:
    """[dispersions]: what the Table 3 campaign draws (docs/design/blt.md, "Monte Carlo"): at each level p, every
    BLT parameter and the departure perturbed by p xi, xi ~ N(0, sigma_fraction^2) clipped to [-1, 1]."""

    levels_percent: tuple[float, ...]   #: the perturbation levels p [%]
    sigma_fraction: float               #: sigma of a draw as a fraction of the level (1/3: the level is 3 sigma)


@dataclasses.dataclass(frozen=True)
class Acceptance:
    """[acceptance]: a corrector that claims convergence must be confirmed by the DOP853 re-propagation of
    the same error vector within error_tolerance (normalised |e|_2); a corrector that does not converge is
    measured (the converged %), not a failure.

    Default when the scenario has no [acceptance]: None, the tolerance the corrector itself was run with:
    [monte_carlo] tol in `ogk mc`, [solver] tol in `ogk blt` / `ogk run` (`tolerance(corrector_tol)`)."""

    error_tolerance: float | None = None

    def tolerance(self, corrector_tol: float) -> float:
        return corrector_tol if self.error_tolerance is None else self.error_tolerance


@dataclasses.dataclass(frozen=True)
class BinaryScenario:
    path: Path
    name: str
    source: str
    law: str
    system: System
    gravity: Gravity
    sun: Sun
    spacecraft: Spacecraft
    orbits: dict[str, OrbitSpec]
    transfers: dict[str, Any]       #: [transfers.NAME]: raw TOML tables, read by later tools
    paper_results: dict[str, Any] | None   #: [paper_results] (for comparison only); None: none
    dispersions: Dispersions | None        #: [dispersions] (the Table 3 campaign's); None: none
    acceptance: Acceptance
    solver: dict[str, Any] = dataclasses.field(default_factory=dict)       #: [solver] (ogk_host.binary.transfers)
    monte_carlo: dict[str, Any] = dataclasses.field(default_factory=dict)  #: [monte_carlo] (idem)

    @property
    def units(self) -> Units:
        s = self.system
        return Units.from_system(s.separation_m, s.mutual_period_s, s.primary_mass_kg, s.secondary_mass_kg)


def _read_ellipsoid(section: Section, mass_kg: float, density_kg_m3: float, mass_key: str,
                    axisymmetric: bool) -> Ellipsoid:
    axes = section.numbers("semi_axes_m", length=3)
    if any(not (v > 0.0 and math.isfinite(v)) for v in axes):
        raise section.error("semi_axes_m", f"must be 3 positive finite lengths, got {list(axes)}")
    impact = section.number("impact_radius_m", positive=True)
    section.finish()
    body = Ellipsoid(semi_axes_m=(axes[0], axes[1], axes[2]), impact_radius_m=impact)
    if axisymmetric and axes[0] != axes[1]:
        raise section.error("semi_axes_m", "the primary spins in 2.76 h, not with the synodic frame: "
                            "its C22 must be 0, so a must equal b (docs/design/blt.md section 1)")
    if impact < max(axes):
        raise section.error("impact_radius_m", f"{impact:g} m is inside the body's largest semi-axis "
                            f"{max(axes):g} m: the degree-2 field is only valid outside the Brillouin sphere")
    ratio = density_kg_m3 * body.volume_m3 / mass_kg
    if abs(ratio - 1.0) > ELLIPSOID_MASS_TOLERANCE:
        raise section.error("semi_axes_m", f"the homogeneous ellipsoid's mass (density x volume = "
                            f"{density_kg_m3 * body.volume_m3:.4g} kg) is {100.0 * (ratio - 1.0):+.1f} % "
                            f"from {mass_key} = {mass_kg:.4g} kg (tolerance "
                            f"{100.0 * ELLIPSOID_MASS_TOLERANCE:g} %)")
    return body


def _read_orbit(section: Section, name: str) -> OrbitSpec:
    family = section.text("family", choices=ORBIT_FAMILIES)
    point = section.text("point", choices=LIBRATION_POINTS)
    amplitude = section.number("amplitude_m", positive=True)
    branch: str | None = None
    if family == "halo":
        branch = section.text("branch", choices=HALO_BRANCHES)
    elif section.has("branch"):
        section.text("branch")
        raise section.error("branch", "only a halo orbit has a branch")
    section.finish()
    return OrbitSpec(name=name, family=family, point=point, amplitude_m=amplitude, branch=branch)


def load_scenario(path: str | Path | None = None) -> BinaryScenario:
    """Reads scenarios/moshup.toml (or `path`) and checks it: every missing key, wrong type, unknown key
    or physically impossible value is an `OgkInputError` naming file and key."""
    scenario_path = Path(path) if path is not None else DEFAULT_SCENARIO_PATH
    raw = read_toml(scenario_path)
    top = Section(raw, scenario_path, "")
    top.text("mission", choices=(MISSION,))
    check_header(raw, scenario_path, SCHEMA)
    top.text("schema")
    name = top.text("name")
    source = top.text("source", default="")

    guid_s = top.section("guidance")
    law = guid_s.text("law", choices=LAWS)
    guid_s.finish()

    sys_s = top.section("system")
    system = sys_s.dataclass(System, **{f.name: {"positive": True} for f in dataclasses.fields(System)})
    sys_s.finish()
    if not system.secondary_mass_kg < system.primary_mass_kg:
        raise sys_s.error("secondary_mass_kg", "must be below primary_mass_kg (mu < 1/2)")

    grav_s = top.section("gravity")
    model = grav_s.text("model", choices=GRAVITY_MODELS)
    primary = _read_ellipsoid(grav_s.section("primary"), system.primary_mass_kg,
                              system.primary_density_kg_m3, "system.primary_mass_kg", axisymmetric=True)
    secondary = _read_ellipsoid(grav_s.section("secondary"), system.secondary_mass_kg,
                                system.secondary_density_kg_m3, "system.secondary_mass_kg",
                                axisymmetric=False)
    grav_s.finish()
    if primary.impact_radius_m + secondary.impact_radius_m >= system.separation_m:
        raise grav_s.error("secondary.impact_radius_m", "the two impact spheres overlap "
                           "(sum of the impact radii >= system.separation_m)")
    gravity = Gravity(model=model, primary=primary, secondary=secondary)

    sun_s = top.section("sun")
    sun = sun_s.dataclass(Sun, angle0_rad={"lo": -2.0 * math.pi, "hi": 2.0 * math.pi},
                          flux_1au_w_m2={"nonnegative": True},
                          **{k: {"positive": True} for k in ("distance_m", "mu_m3_s2", "astronomical_unit_m",
                                                             "speed_of_light_m_s")})
    sun_s.finish()

    sc_s = top.section("spacecraft")
    spacecraft = sc_s.dataclass(Spacecraft, area_m2={"nonnegative": True},
                                reflectivity_cr={"lo": 0.0, "hi": 2.0},
                                **{k: {"positive": True} for k in ("mass_kg", "specific_impulse_s",
                                                                   "standard_gravity_m_s2")})
    sc_s.finish()

    orbits: dict[str, OrbitSpec] = {}
    if top.has("orbits"):
        orb_s = top.section("orbits")
        for key in raw["orbits"]:       # the table's keys are the orbit names
            orbits[key] = _read_orbit(orb_s.section(key), key)
        orb_s.finish()

    transfers: dict[str, Any] = {}
    if top.has("transfers"):
        tr_s = top.section("transfers")
        for key in raw["transfers"]:
            tr_s.section(key)   # each transfer must be a table; its keys belong to the transfer tools
            transfers[key] = raw["transfers"][key]
        tr_s.finish()
    paper = _read_paper(top.raw_table("paper_results"), scenario_path, transfers)
    dispersions = _read_dispersions(top.section("dispersions")) if top.has("dispersions") else None
    acc_s = top.section("acceptance", optional=True)
    acceptance = Acceptance(error_tolerance=acc_s.number("error_tolerance", None, positive=True))
    acc_s.finish()
    extra: dict[str, dict[str, Any]] = {}
    for table in ("solver", "monte_carlo"):   # read key by key by ogk_host.binary.transfers
        if top.has(table):
            top.section(table)
            extra[table] = dict(raw[table])
    top.finish()
    return BinaryScenario(path=scenario_path, name=name, source=source, law=law, system=system,
                          gravity=gravity, sun=sun, spacecraft=spacecraft, orbits=orbits,
                          transfers=transfers, paper_results=paper, dispersions=dispersions,
                          acceptance=acceptance, solver=extra.get("solver", {}),
                          monte_carlo=extra.get("monte_carlo", {}))


def _read_dispersions(sec: Section) -> Dispersions:
    levels = sec.numbers("levels_percent")
    if not levels or any(not 0.0 < v <= 100.0 for v in levels):
        raise sec.error("levels_percent", f"must be a non-empty list of levels in (0, 100] %, got {list(levels)}")
    out = Dispersions(levels_percent=levels, sigma_fraction=sec.number("sigma_fraction", positive=True))
    sec.finish()
    return out


def _read_paper(raw: dict[str, Any] | None, path: Path, transfers: dict[str, Any]) -> dict[str, Any] | None:
    """[paper_results], the paper's figures for comparison only, or None. Checked: each
    [paper_results.transfers.NAME] names a transfer and holds only PAPER_TRANSFER_KEYS (numbers),
    [paper_results.table3] levels_percent and converged_percent of one length. Other keys are kept as
    read (figures a report may quote)."""
    if raw is None:
        return None
    top = Section(raw, path, "paper_results")
    if top.has("transfers"):
        tr_s = top.section("transfers")
        for name in raw["transfers"]:
            sec = tr_s.section(name)
            if name not in transfers:
                raise tr_s.error(name, f"no [transfers.{name}] (has: {', '.join(transfers) or 'none'})")
            for key in PAPER_TRANSFER_KEYS:
                if sec.has(key):
                    sec.number(key, positive=True)
            sec.finish()
        tr_s.finish()
    if top.has("table3"):
        t3 = top.section("table3")
        levels = t3.numbers("levels_percent")
        t3.numbers("converged_percent", length=len(levels))
        t3.finish()
    return dict(raw)
