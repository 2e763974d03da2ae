"""Proximity-approach scenarios (the `proximity-approach` family, issue 33's second NMPC problem): TOML ->
dataclasses, every bad key one `OgkInputError` line naming the file and the key.

Everything in the file is SI (m, s, kg, N, rad), in the target's Hill frame: x radial (away from the
Earth), y along-track, the target on a circular orbit of `[orbit] radius_m` about a point-mass Earth.
The normalised units the kernel and the ground OCP use (`Units`): LU = 1 km, TU = 1 / n
(n = sqrt(mu / a^3), the target's mean motion, so n = 1 in the model), MU = `[guidance] mass_unit_kg`
(default the initial mass). The SQP's tolerances are relative to max(|J|, 1) with J in MU: a mass unit
of the order of the objective (fuel + time weight x T, ~0.1 kg) makes J of order 1, so that they mean
what they say (in MU = m_0, J ~ 6e-4 and tol_obj 1e-7 was a loose 1.6e-4 relative).
"""
from __future__ import annotations

import dataclasses
import math
from pathlib import Path

from ..scenario_file import Section, check_header, read_toml, schema_of
from .dynamics import Vehicle
from .problem import Approach

MISSION = "proximity-approach"
SCHEMA = schema_of(MISSION)   #: "ogk.proximity-approach/1"
LAWS = ("nmpc",)
STRATEGIES = ("cncn", "snns")
OBJECTIVES = ("min-fuel", "min-time")
MAX_KEEPOUT = 2               #: OGK_PROX_MAX_KEEPOUT (kernel/include/ogk/proximity.h)
LENGTH_UNIT_M = 1000.0        #: LU


@dataclasses.dataclass(frozen=True)
class Units:
    """LU = 1 km, TU = 1 / n, MU = [guidance] mass_unit_kg (default m_0)."""

    length_m: float
    time_s: float
    mass_kg: float

    @property
    def velocity_m_s(self) -> float:
        return self.length_m / self.time_s

    @property
    def accel_m_s2(self) -> float:
        return self.length_m / self.time_s ** 2


@dataclasses.dataclass(frozen=True)
class Orbit:
    radius_m: float                 #: the target's circular orbit radius a
    mu_m3_s2: float                 #: Earth's gravitational parameter

    @property
    def mean_motion_rad_s(self) -> float:
        return math.sqrt(self.mu_m3_s2 / self.radius_m ** 3)


@dataclasses.dataclass(frozen=True)
class Keepout:
    centre_m: tuple[float, float]
    radius_m: float


@dataclasses.dataclass(frozen=True)
class Guidance:
    """[guidance]: the receding-horizon NMPC's settings."""

    law: str
    strategy: str                   #: "cncn" (constant nodes, compressed horizon) or "snns"
    objective: str                  #: "min-fuel" or "min-time"
    fuel_time_weight_kg_per_s: float  #: min-fuel: J = fuel + this x T (an interior optimum of T)
    nodes: int                      #: N subintervals of a plan
    rk4_steps: int                  #: RK4 steps per subinterval
    replan_period_s: float          #: a replan every this many seconds of flight
    final_phase_s: float            #: no replan once the plan has less than this left: flown to its end
    min_horizon_s: float            #: a replan's horizon lower bound
    keepout_margin_m: float         #: the plans' discs are this much larger than the truth's
    max_sweep_rad: float            #: the plans' |alpha_{k+1} - alpha_k| bound (the kernel's max_sweep)
    mass_unit_kg: float | None = None  #: MU of the laws' normalised units (None: the initial mass)
    fixed_final_time: bool = False  #: the flight's replans keep the ground plan's t_f (free on the ground)


@dataclasses.dataclass(frozen=True)
class Dispersions:
    """[dispersions]: Gaussian sigmas of what a campaign draws (run by run, ogk.sil.seeds)."""

    initial_position_sigma_m: float     #: each of x, y of the start
    initial_velocity_sigma_m_s: float   #: each of v_x, v_y of the start
    thrust_level_sigma: float           #: the engine's thrust bias (fraction of T_max), one per run
    thrust_angle_sigma_rad: float       #: angle noise, one draw per replan period (held in between)
    initial_mass_sigma_kg: float        #: the start's mass


@dataclasses.dataclass(frozen=True)
class Acceptance:
    """[acceptance]: a flight passes when, at the end of its last plan, the truth is within the box
    about the hold point (|x - x_h| and |y - y_h| each within hold_position_box_m, |v_x| and |v_y| each
    within hold_velocity_box_m_s), it never entered a keep-out disc (the truth's radius, no margin),
    and burnt no more than propellant_kg. Defaults: 5 m, 5 mm/s, the vehicle's propellant
    (initial mass - dry mass)."""

    hold_position_box_m: float = 5.0
    hold_velocity_box_m_s: float = 0.005
    propellant_kg: float | None = None


@dataclasses.dataclass(frozen=True)
class ProximityScenario:
    path: Path
    name: str
    source: str
    orbit: Orbit
    vehicle: Vehicle
    min_throttle: float                         #: the engine's: a command below it is off (the truth's)
    start: tuple[float, float, float, float]    #: (x, y, v_x, v_y) [m, m/s]
    hold_point_m: tuple[float, float]
    horizon_s: tuple[float, float]              #: the free final time's bounds from the start
    keepouts: tuple[Keepout, ...]
    guidance: Guidance
    dispersions: Dispersions
    acceptance: Acceptance
    paper_results: dict | None = None

    @property
    def units(self) -> Units:
        mu = self.guidance.mass_unit_kg
        return Units(LENGTH_UNIT_M, 1.0 / self.orbit.mean_motion_rad_s,
                     self.vehicle.initial_mass_kg if mu is None else mu)

    @property
    def propellant_kg(self) -> float:
        return self.vehicle.initial_mass_kg - self.vehicle.dry_mass_kg

    def approach(self, margin_m: float | None = None) -> Approach:
        """The ground OCP's problem (ogk_host.proximity.ocp): the plans' disc (truth's radius +
        [guidance] keepout_margin_m, or + margin_m) about the first keep-out (the ground reference
        takes one disc)."""
        margin = self.guidance.keepout_margin_m if margin_m is None else margin_m
        ko = self.keepouts[0] if self.keepouts else Keepout((0.0, 0.0), 0.0)
        return Approach(self.orbit.mean_motion_rad_s, self.vehicle, start=self.start,
                        hold_point_m=self.hold_point_m, keepout_center_m=ko.centre_m,
                        keepout_radius_m=ko.radius_m + margin if ko.radius_m > 0.0 else 0.0,
                        horizon_s=self.horizon_s, objective=self.guidance.objective,
                        nodes=self.guidance.nodes, rk4_steps=self.guidance.rk4_steps)


def _pair(sec: Section, key: str) -> tuple[float, float]:
    v = sec.numbers(key, length=2)
    if not all(math.isfinite(x) for x in v):
        raise sec.error(key, "must be finite")
    return (v[0], v[1])


def load_scenario(path: str | Path) -> ProximityScenario:
    p = Path(path)
    raw = read_toml(p)
    top = Section(raw, p, "")
    top.text("mission", choices=(MISSION,))
    check_header(raw, p, SCHEMA)
    top.text("schema")
    name = top.text("name")
    source = top.text("source", default="")

    o = top.section("orbit")
    orbit = Orbit(radius_m=o.number("radius_m", lo=6.5e6, hi=5e7), mu_m3_s2=o.number("mu_m3_s2", positive=True))
    o.finish()

    v = top.section("vehicle")
    m0 = v.number("initial_mass_kg", positive=True)
    dry = v.number("dry_mass_kg", positive=True)
    if not dry < m0:
        raise v.error("dry_mass_kg", f"must be below initial_mass_kg ({m0:g}), got {dry:g}")
    vehicle = Vehicle(thrust_max_n=v.number("thrust_max_n", positive=True),
                      exhaust_velocity_m_s=v.number("exhaust_velocity_m_s", positive=True),
                      initial_mass_kg=m0, dry_mass_kg=dry)
    min_throttle = v.number("min_throttle", lo=0.0, hi=0.5)
    v.finish()

    a = top.section("approach")
    pos = _pair(a, "start_m")
    vel = _pair(a, "start_velocity_m_s")
    hold = _pair(a, "hold_point_m")
    horizon = _pair(a, "horizon_s")
    if not 0.0 < horizon[0] < horizon[1]:
        raise a.error("horizon_s", f"must be 0 < lower < upper, got {list(horizon)}")
    a.finish()

    k = top.section("keepout", optional=True)
    centres = k.numbers("centres_m", default=())
    radii = k.numbers("radii_m", default=())
    k.finish()
    if len(radii) > MAX_KEEPOUT or len(centres) != 2 * len(radii):
        raise k.error("centres_m", f"one (x, y) per radius, at most {MAX_KEEPOUT} discs: got "
                      f"{len(centres)} numbers for {len(radii)} radii")
    keepouts = tuple(Keepout((centres[2 * j], centres[2 * j + 1]), radii[j]) for j in range(len(radii)))
    for j, ko in enumerate(keepouts):
        if not ko.radius_m > 0.0:
            raise k.error("radii_m", f"disc {j}: must be > 0, got {ko.radius_m:g}")
        for what, pt in (("approach.start_m", pos), ("approach.hold_point_m", hold)):
            if math.dist(pt, ko.centre_m) <= ko.radius_m:
                raise k.error("centres_m", f"disc {j} contains {what}")

    g = top.section("guidance")
    guidance = Guidance(
        law=g.text("law", choices=LAWS), strategy=g.text("strategy", choices=STRATEGIES),
        objective=g.text("objective", choices=OBJECTIVES),
        fuel_time_weight_kg_per_s=g.number("fuel_time_weight_kg_per_s", nonnegative=True), nodes=g.integer("nodes", lo=4, hi=40),
        rk4_steps=g.integer("rk4_steps", lo=1, hi=16),
        replan_period_s=g.number("replan_period_s", positive=True),
        final_phase_s=g.number("final_phase_s", nonnegative=True),
        min_horizon_s=g.number("min_horizon_s", positive=True),
        keepout_margin_m=g.number("keepout_margin_m", nonnegative=True),
        max_sweep_rad=g.number("max_sweep_rad", positive=True),
        mass_unit_kg=g.number("mass_unit_kg", default=None, positive=True),
        fixed_final_time=g.flag("fixed_final_time", default=False))
    g.finish()
    if guidance.min_horizon_s >= horizon[1]:
        raise g.error("min_horizon_s", f"must be below approach.horizon_s's upper bound {horizon[1]:g}")

    d = top.section("dispersions")
    dispersions = d.dataclass(Dispersions, **{f.name: {"nonnegative": True}
                                              for f in dataclasses.fields(Dispersions)})
    d.finish()

    acc = top.section("acceptance", optional=True)
    acceptance = Acceptance(
        hold_position_box_m=acc.number("hold_position_box_m", default=Acceptance.hold_position_box_m,
                                       positive=True),
        hold_velocity_box_m_s=acc.number("hold_velocity_box_m_s", default=Acceptance.hold_velocity_box_m_s,
                                         positive=True),
        propellant_kg=acc.number("propellant_kg", default=m0 - dry, positive=True))
    acc.finish()
    paper = top.raw_table("paper_results")
    top.finish()
    return ProximityScenario(path=p, name=name, source=source, orbit=orbit, vehicle=vehicle, min_throttle=min_throttle,
                             start=(pos[0], pos[1], vel[0], vel[1]), hold_point_m=hold, horizon_s=horizon,
                             keepouts=keepouts, guidance=guidance, dispersions=dispersions,
                             acceptance=acceptance, paper_results=None if paper is None else dict(paper))
