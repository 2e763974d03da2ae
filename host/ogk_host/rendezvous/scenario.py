"""Earth-to-Mars low-thrust rendezvous scenarios (Starek & Kolmanovsky 2012, Table A.1): TOML -> dataclasses.

Everything here is SI (m, s, kg, N, rad), as in scenarios/rendezvous_*.toml. The normalised units the
solvers use are built by `dynamics.Units.for_scenario` (LU = r_E, mu_sun = 1, MU = m0; docs/nmpc.md).
"""
from __future__ import annotations

import dataclasses
import math
from pathlib import Path

from ..scenario_file import Section, check_header, read_toml, schema_of

REPO_ROOT = Path(__file__).resolve().parents[3]
DEFAULT_SCENARIO_PATH = REPO_ROOT / "scenarios" / "rendezvous_nep_min_time.toml"
MISSION = "low-thrust-rendezvous"
SCHEMA = schema_of(MISSION)   #: "ogk.low-thrust-rendezvous/1" (the header, ogk_host.scenario_file)
LAWS = ("nmpc",)
PROPULSION_MODELS = ("nuclear-electric", "solar-electric")
THROTTLES = ("constant", "bounded")   #: sec. 3.2.1: T = T_0 (min-time) or 0 <= T <= T_max (eq. 12)
OBJECTIVES = ("min-time", "min-fuel")
CONTROLS = ("piecewise-linear",)
NMPC_STRATEGIES = ("snns", "cncn")     #: sec. 2.3.3 and 2.3.1
#: [paper_results] keys: Table I (open loop, CNCN, SNNS; unperturbed and perturbed; the maximum computation
#: time per subinterval as a fraction of the subinterval, Table I's footnote) and Table II (SNNS).
PAPER_RESULT_KEYS = ("open_loop_time_s", "open_loop_fuel_kg", "open_loop_max_comp_fraction",
                     "snns_time_s", "snns_fuel_kg", "snns_max_comp_fraction",
                     "snns_perturbed_time_s", "snns_perturbed_fuel_kg", "snns_perturbed_max_comp_fraction",
                     "cncn_time_s", "cncn_fuel_kg", "cncn_max_comp_fraction",
                     "cncn_perturbed_time_s", "cncn_perturbed_fuel_kg", "cncn_perturbed_max_comp_fraction")


@dataclasses.dataclass(frozen=True)
class Problem:
    """Table A.1, "Problem definition"."""

    start_time_s: float             #: t_0 [s]
    earth_orbit_radius_m: float     #: r_E [m]
    mars_orbit_radius_m: float      #: r_M [m]
    earth_mass_kg: float            #: m_E [kg]
    mars_mass_kg: float             #: m_M [kg]
    sun_mass_kg: float              #: m_S [kg]
    sun_mu_m3_s2: float             #: mu [m^3/s^2]


@dataclasses.dataclass(frozen=True)
class PolarState:
    """A planar heliocentric state in the rotating polar frame of eq. (11)."""

    radius_m: float                         #: r [m]
    polar_angle_rad: float                  #: theta [rad]
    radial_velocity_m_s: float              #: v_r [m/s]
    circumferential_velocity_m_s: float     #: v_theta [m/s]


@dataclasses.dataclass(frozen=True)
class Perturbations:
    """Table A.1, "Perturbation inputs" (the simulation model; unknown to the predictive model)."""

    area_m2: float                      #: A_s/c [m^2]
    reflectivity_efficiency: float      #: eta [-]
    solar_constant_w_m2: float          #: S_0 [W/m^2]
    speed_of_light_m_s: float           #: c [m/s]
    thrust_offset_percent: float        #: T_offset [%] (eq. 23)
    earth_mu_m3_s2: float               #: mu_E [m^3/s^2]
    mars_mu_m3_s2: float                #: mu_M [m^3/s^2]
    earth_initial_polar_angle_rad: float    #: (theta_E)_0 [rad]


@dataclasses.dataclass(frozen=True)
class Dispersions:
    """[dispersions]: what a perturbed flight draws at random (Table A.1's thrust-angle noise, sec. 3.5);
    the deterministic forces and the thrust offset are [perturbations]."""

    thrust_angle_sigma_rad: float       #: sigma_alpha_T [rad]
    #: How often the closed loop redraws the thrust-angle noise N(0, sigma_alpha_T) [s] (not in the paper,
    #: which only says "pseudorandom"); 0 = once per MPC control subinterval (docs/nmpc.md, "Truth model").
    thrust_angle_draw_period_s: float


@dataclasses.dataclass(frozen=True)
class Acceptance:
    """[acceptance]: a closed-loop flight passes when it arrives (the [convergence] test stops it) with its
    final miss within these and, when propellant_kg is given, burns no more propellant (truth mass).

    Default when the scenario has no [acceptance] (or leaves a key out): the arrival condition of
    [convergence]: position_error_m = mars_soi_radius_m, velocity_error_m_s = velocity_error_m_s, no
    propellant limit."""

    position_error_m: float             #: |r - r_M| at arrival [m]
    velocity_error_m_s: float           #: |v - v_M| at arrival [m/s]
    propellant_kg: float | None = None  #: m_0 - m_f limit [kg]; None: no limit


@dataclasses.dataclass(frozen=True)
class SolarElectric:
    """Solar-electric engine, eq. (14): T_max(r) = b1 + b2 P_0 (a1 r^2 + a2 r + a3) / (r^4 (1 + a4 r)) with
    r in AU, and mass rate dm/dt = c1 + c2 P, P = (T - b1) / b2. The paper prints a_i, b_i, c_i without
    units; the scenario stores them in SI read with the units of Kim's model (mN, kW, mg/s), the only
    reading under which T_0 = 0.5 N at 1 AU needs a plausible P_0 (13.9 kW; docs/nmpc.md)."""

    fit_length_unit_m: float            #: the unit of r in eq. (14): 1 AU [m]
    power_a1: float                     #: a1 [-]
    power_a2: float                     #: a2 [-]
    power_a3: float                     #: a3 [-]
    power_a4: float                     #: a4 [-]
    thrust_b1_n: float                  #: b1 [N]
    thrust_b2_n_per_w: float            #: b2 [N/W]
    mass_rate_c1_kg_s: float            #: c1 [kg/s] (dm/dt, negative)
    mass_rate_c2_kg_s_per_w: float      #: c2 [kg/(s W)]

    def power_ratio(self, radius_m: float) -> float:
        """P_max(r) / P_0, eq. (14)."""
        r = radius_m / self.fit_length_unit_m
        return (self.power_a1 * r * r + self.power_a2 * r + self.power_a3) / (r ** 4 * (1.0 + self.power_a4 * r))

    def reference_power_w(self, thrust_at_1au_n: float) -> float:
        """P_0 such that T_max(1 AU) = T_0 (sec. 4, test case (3): "T_0 = 0.5 N at 1 AU")."""
        return (thrust_at_1au_n - self.thrust_b1_n) / (self.thrust_b2_n_per_w
                                                        * self.power_ratio(self.fit_length_unit_m))


@dataclasses.dataclass(frozen=True)
class Propulsion:
    """Sec. 3.2. Nuclear-electric: 0 <= T <= T_max (eq. 12), mdot = -T / (g0 Isp) (eq. 13).
    Solar-electric: T_max is the thrust at 1 AU and `solar` holds eq. (14)."""

    model: str
    throttle: str                   #: "constant" (T = T_max) or "bounded"
    thrust_max_n: float             #: T_max [N] (solar-electric: T_0 at 1 AU)
    specific_impulse_s: float | None = None     #: I_sp [s] (nuclear-electric)
    standard_gravity_m_s2: float | None = None  #: g_0 [m/s^2] (nuclear-electric)
    solar: SolarElectric | None = None

    @property
    def mass_flow_at_max_kg_s(self) -> float:
        """|mdot| at T_max [kg/s] (eq. 13; nuclear-electric only)."""
        if self.specific_impulse_s is None or self.standard_gravity_m_s2 is None:
            raise ValueError("mass_flow_at_max_kg_s is defined for the nuclear-electric model (eq. 13)")
        return self.thrust_max_n / (self.standard_gravity_m_s2 * self.specific_impulse_s)


@dataclasses.dataclass(frozen=True)
class Convergence:
    """Table A.1, "Convergence criteria" and the rendezvous test of sec. 2.3.1 (MPC stop)."""

    earth_soi_radius_m: float
    mars_soi_radius_m: float
    velocity_error_m_s: float


@dataclasses.dataclass(frozen=True)
class OcpSettings:
    """Transcription of the open-loop OCP (sec. 2.3: direct multiple shooting, piecewise-linear control)."""

    objective: str
    nodes: int                      #: N control subintervals (N + 1 node values)
    control: str
    rk4_steps_per_interval: int
    #: Open-loop minimum fuel: arrival no later than t_0 + this [s] (None: t_f free). The fuel is flat in t_f
    #: past a knee (~490 d NEP, ~530 d SEP) and free t_f stops at a guess-dependent local optimum anywhere
    #: in 490-1700 d; the bound, just past the knee, cuts off the long branches (docs/nmpc.md, "Minimum fuel").
    transfer_time_max_s: float | None = None


@dataclasses.dataclass(frozen=True)
class NmpcSettings:
    """The closed loop of sec. 2.3 (`ogk nmpc`, harness/ogk/missions/rendezvous). The paper gives none of the
    SNNS parameters (errata): the values in the scenario files are ours (docs/nmpc.md, "Closed loop")."""

    strategy: str                       #: default strategy: "snns" (sec. 2.3.3) or "cncn" (sec. 2.3.1)
    doubling_threshold_percent: float   #: SNNS adopts 2N when its cost is lower by more than this [%]
    max_subdivisions: int               #: doublings allowed over the whole flight
    min_nodes: int                      #: SNNS never plans with fewer subintervals (regrids instead)
    max_replans: int                    #: the flight stops (not converged) after this many replans
    max_flight_days: float              #: ... or at this flight time [d]
    rk4_steps_per_interval: int         #: RK4 steps per subinterval of the predictive model
    third_bodies_in_model: bool         #: Earth and Mars gravity in the predictive model (paper: false)
    tol: float                          #: IPOPT tol
    constr_viol_tol: float              #: IPOPT constr_viol_tol
    max_iter: int                       #: IPOPT max_iter per solve
    fuel_time_weight_kg_per_day: float = 0.0  #: min-fuel closed loop: J = fuel + w T (beyond the paper; 0 = its J)
    earth_keepout_radius_m: float = 0.0  #: flight solver: interior plan nodes stay this far from Earth (0: none)


@dataclasses.dataclass(frozen=True)
class RendezvousScenario:
    path: Path
    name: str
    source: str
    problem: Problem
    initial: PolarState
    initial_mass_kg: float
    target: PolarState              #: Mars at t_0 (circular orbit, eq. 6)
    perturbations: Perturbations    #: the forces of the simulation model (deterministic)
    propulsion: Propulsion
    convergence: Convergence
    ocp: OcpSettings
    law: str
    paper_results: dict[str, float] | None   #: [paper_results]; None when the scenario has none
    nmpc: NmpcSettings
    dispersions: Dispersions        #: [dispersions]: the thrust-angle noise of a perturbed flight
    acceptance: Acceptance          #: [acceptance], or its default (the arrival condition)

    @property
    def mars_mean_motion_rad_s(self) -> float:
        """sqrt(mu / r_M^3), eq. (6)."""
        return math.sqrt(self.problem.sun_mu_m3_s2 / self.problem.mars_orbit_radius_m ** 3)


def _read_state(section: Section) -> PolarState:
    state = PolarState(radius_m=section.number("radius_m", positive=True),
                       polar_angle_rad=section.number("polar_angle_rad", lo=-2.0 * math.pi,
                                                      hi=2.0 * math.pi),
                       radial_velocity_m_s=section.number("radial_velocity_m_s"),
                       circumferential_velocity_m_s=section.number("circumferential_velocity_m_s",
                                                                   positive=True))
    return state


def _check_circular(section: Section, state: PolarState, mu: float, what: str) -> None:
    """Eqs. (4)-(5) put the spacecraft and Mars on circular orbits: v_theta = sqrt(mu / r), v_r = 0.
    Table A.1 prints 7 significant figures, so a relative mismatch above 1e-6 is a typo."""
    circular = math.sqrt(mu / state.radius_m)
    if abs(state.circumferential_velocity_m_s / circular - 1.0) > 1e-6:
        raise section.error("circumferential_velocity_m_s",
                            f"{what}: {state.circumferential_velocity_m_s:.8g} m/s is not the "
                            f"circular speed sqrt(mu / r) = {circular:.8g} m/s (eqs. 4-5)")
    if state.radial_velocity_m_s != 0.0:
        raise section.error("radial_velocity_m_s", f"{what}: must be 0 on a circular orbit (eqs. 4-5)")


def load_scenario(path: str | Path | None = None) -> RendezvousScenario:
    """Reads scenarios/rendezvous_nep_min_time.toml (or `path`) and checks it: every missing key, wrong
    type, unknown key or physically impossible value is an `OgkInputError` naming file and key."""
    scenario_path = Path(path) if path is not None else DEFAULT_SCENARIO_PATH
    raw = read_toml(scenario_path)
    top = Section(raw, scenario_path, "")
    top.text("mission", choices=(MISSION,))
    check_header(raw, scenario_path, SCHEMA)
    top.text("schema")
    name = top.text("name")
    source = top.text("source", default="")

    prob_s = top.section("problem")
    problem = prob_s.dataclass(Problem, start_time_s={"nonnegative": True},
                               **{f.name: {"positive": True} for f in dataclasses.fields(Problem)
                                  if f.name != "start_time_s"})
    prob_s.finish()
    if not problem.mars_orbit_radius_m > problem.earth_orbit_radius_m:
        raise prob_s.error("mars_orbit_radius_m", "must be above earth_orbit_radius_m (outward transfer)")

    init_s = top.section("initial_state")
    initial = _read_state(init_s)
    initial_mass = init_s.number("mass_kg", positive=True)
    init_s.finish()
    _check_circular(init_s, initial, problem.sun_mu_m3_s2, "spacecraft")

    target_s = top.section("target")
    target = _read_state(target_s)
    target_s.finish()
    _check_circular(target_s, target, problem.sun_mu_m3_s2, "Mars")
    if target.radius_m != problem.mars_orbit_radius_m:
        raise target_s.error("radius_m", "must equal problem.mars_orbit_radius_m (circular orbit, eq. 6)")

    pert_s = top.section("perturbations")
    perturbations = pert_s.dataclass(Perturbations, area_m2={"nonnegative": True},
                                     reflectivity_efficiency={"lo": 0.0, "hi": 1.0},
                                     solar_constant_w_m2={"nonnegative": True},
                                     speed_of_light_m_s={"positive": True},
                                     thrust_offset_percent={"lo": -100.0, "hi": 100.0},
                                     earth_mu_m3_s2={"nonnegative": True},
                                     mars_mu_m3_s2={"nonnegative": True})
    pert_s.finish()
    disp_s = top.section("dispersions")
    dispersions = disp_s.dataclass(Dispersions, thrust_angle_sigma_rad={"nonnegative": True},
                                   thrust_angle_draw_period_s={"nonnegative": True})
    disp_s.finish()

    prop_s = top.section("propulsion")
    model = prop_s.text("model", choices=PROPULSION_MODELS)
    throttle = prop_s.text("throttle", choices=THROTTLES)
    thrust_max = prop_s.number("thrust_max_n", positive=True)
    if model == "nuclear-electric":
        propulsion = Propulsion(model=model, throttle=throttle, thrust_max_n=thrust_max,
                                specific_impulse_s=prop_s.number("specific_impulse_s", positive=True),
                                standard_gravity_m_s2=prop_s.number("standard_gravity_m_s2",
                                                                    positive=True))
    else:
        sep_s = prop_s.section("solar_electric")
        solar = sep_s.dataclass(SolarElectric, fit_length_unit_m={"positive": True},
                                thrust_b2_n_per_w={"positive": True})
        sep_s.finish()
        if throttle != "bounded":
            raise prop_s.error("throttle", "the solar-electric thrust depends on r (eq. 14): "
                               "must be \"bounded\"")
        if not solar.reference_power_w(thrust_max) > 0.0:
            raise prop_s.error("thrust_max_n", "no positive reference power P_0 gives this thrust at "
                               "1 AU (eq. 14)")
        propulsion = Propulsion(model=model, throttle=throttle, thrust_max_n=thrust_max, solar=solar)
    prop_s.finish()

    conv_s = top.section("convergence")
    convergence = conv_s.dataclass(Convergence, **{f.name: {"positive": True}
                                                   for f in dataclasses.fields(Convergence)})
    conv_s.finish()
    acceptance = _read_acceptance(top.section("acceptance", optional=True), convergence)

    guid_s = top.section("guidance")
    law = guid_s.text("law", choices=LAWS)
    guid_s.finish()

    ocp_s = top.section("ocp")
    ocp = OcpSettings(objective=ocp_s.text("objective", choices=OBJECTIVES),
                      nodes=ocp_s.integer("nodes", lo=2, hi=1000),
                      control=ocp_s.text("control", choices=CONTROLS),
                      rk4_steps_per_interval=ocp_s.integer("rk4_steps_per_interval", lo=1, hi=100),
                      transfer_time_max_s=ocp_s.number("transfer_time_max_s", None, positive=True))
    ocp_s.finish()
    if ocp.objective == "min-time" and propulsion.throttle != "constant":
        raise ocp_s.error("objective", "min-time is posed with propulsion.throttle = \"constant\" "
                          "(sec. 3.2.1: min-time and min-fuel coincide only then)")

    nmpc_s = top.section("nmpc")
    nmpc = NmpcSettings(strategy=nmpc_s.text("strategy", choices=NMPC_STRATEGIES),
                        doubling_threshold_percent=nmpc_s.number("doubling_threshold_percent",
                                                                 nonnegative=True),
                        max_subdivisions=nmpc_s.integer("max_subdivisions", lo=0, hi=10),
                        min_nodes=nmpc_s.integer("min_nodes", lo=1, hi=ocp.nodes),
                        max_replans=nmpc_s.integer("max_replans", lo=1, hi=100000),
                        max_flight_days=nmpc_s.number("max_flight_days", positive=True),
                        rk4_steps_per_interval=nmpc_s.integer("rk4_steps_per_interval", lo=1, hi=100),
                        third_bodies_in_model=nmpc_s.flag("third_bodies_in_model"),
                        tol=nmpc_s.number("tol", positive=True, hi=1e-2),
                        constr_viol_tol=nmpc_s.number("constr_viol_tol", positive=True, hi=1e-2),
                        max_iter=nmpc_s.integer("max_iter", lo=1, hi=100000),
                        fuel_time_weight_kg_per_day=nmpc_s.number("fuel_time_weight_kg_per_day", default=0.0,
                                                                  nonnegative=True),
                        earth_keepout_radius_m=nmpc_s.number("earth_keepout_radius_m", default=0.0,
                                                             nonnegative=True))
    nmpc_s.finish()

    paper: dict[str, float] | None = None
    if top.has("paper_results"):
        paper = {}
        paper_s = top.section("paper_results")
        for key in PAPER_RESULT_KEYS:
            if paper_s.has(key):
                paper[key] = paper_s.number(key, positive=True)
        paper_s.finish()
    top.finish()
    return RendezvousScenario(path=scenario_path, name=name, source=source, problem=problem,
                              initial=initial, initial_mass_kg=initial_mass, target=target,
                              perturbations=perturbations, propulsion=propulsion,
                              convergence=convergence, ocp=ocp, law=law, paper_results=paper,
                              nmpc=nmpc, dispersions=dispersions, acceptance=acceptance)


def _read_acceptance(sec: Section, convergence: Convergence) -> Acceptance:
    """[acceptance]; STATED DEFAULT (docs/adding-a-mission.md, "The scenario header"): the arrival
    condition of [convergence] (Mars' sphere-of-influence radius, its velocity error), no propellant
    limit."""
    acc = Acceptance(position_error_m=sec.number("position_error_m", convergence.mars_soi_radius_m,
                                                 positive=True),
                     velocity_error_m_s=sec.number("velocity_error_m_s", convergence.velocity_error_m_s,
                                                   positive=True),
                     propellant_kg=sec.number("propellant_kg", None, positive=True))
    sec.finish()
    return acc
