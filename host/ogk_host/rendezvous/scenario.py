"""Coplanar circular-orbit low-thrust rendezvous scenarios (Starek & Kolmanovsky 2012, Table A.1, is the
first: Earth to Mars): TOML -> dataclasses. The target is the scenario's `[target]` (its `name`, orbit radius
and phase), inward or outward of the departure orbit; the vehicle's dry mass is `[spacecraft] dry_mass_kg`
(docs/design/nmpc.md, "Any circular rendezvous": the envelope and what is derived from the vehicle).

Everything here is SI (m, s, kg, N, rad), as in scenarios/rendezvous_*.toml. The normalised units the
solvers use are built by `dynamics.Units.for_scenario` (LU = r_E, mu_sun = 1, MU = m0; docs/design/nmpc.md).
"""
from __future__ import annotations

import dataclasses
import math
from pathlib import Path

from ..paths import SCENARIO_DIR
from ..scenario_file import Section, check_header, read_toml, schema_of

DEFAULT_SCENARIO_PATH = SCENARIO_DIR / "rendezvous_nep_min_time.toml"
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


#: The envelope the family states (docs/design/nmpc.md, "Any circular rendezvous"): target orbit radius over
#: the departure orbit radius, and the vehicle's initial thrust acceleration T / m0 [m/s^2].
ENVELOPE_RADIUS_RATIO = (0.7, 1.55)
ENVELOPE_ACCEL_M_S2 = (2.5e-4, 3.2e-3)


def hohmann(mu: float, r1: float, r2: float) -> tuple[float, float]:
    """(Delta v [m/s], transfer time [s]) of the Hohmann transfer between circular orbits r1 and r2 (both
    burns; half the ellipse's period): the impulsive minimum for radius ratios below 11.94, so no
    low-thrust transfer needs less Delta v."""
    a = 0.5 * (r1 + r2)
    dv1 = abs(math.sqrt(mu / r1) * (math.sqrt(2.0 * r2 / (r1 + r2)) - 1.0))
    dv2 = abs(math.sqrt(mu / r2) * (1.0 - math.sqrt(2.0 * r1 / (r1 + r2))))
    return dv1 + dv2, math.pi * math.sqrt(a ** 3 / mu)


def exhaust_velocity_max_m_s(propulsion: "Propulsion", r_lo: float, r_hi: float) -> float:
    """The largest effective exhaust velocity T_max / mdot_max of the engine between the two orbits
    [m/s] (nuclear-electric: g0 Isp; solar-electric: eq. (14) sampled)."""
    if propulsion.solar is None:
        assert propulsion.specific_impulse_s is not None and propulsion.standard_gravity_m_s2 is not None
        return propulsion.specific_impulse_s * propulsion.standard_gravity_m_s2
    sol = propulsion.solar
    p0 = sol.reference_power_w(propulsion.thrust_max_n)
    best = 0.0
    for k in range(65):
        r = r_lo + (r_hi - r_lo) * k / 64.0
        power = p0 * sol.power_ratio(r)
        thrust = sol.thrust_b1_n + sol.thrust_b2_n_per_w * power
        flow = -(sol.mass_rate_c1_kg_s + sol.mass_rate_c2_kg_s_per_w * power)
        if thrust > 0.0 and flow > 0.0:
            best = max(best, thrust / flow)
    return best


def _check_propellant(prop_s: Section, propulsion: "Propulsion", problem: "Problem", initial: "PolarState",
                      target: "PolarState", initial_mass: float, dry_mass: float) -> None:
    """Refuses, before anything is flown, a vehicle outside the stated acceleration envelope and one
    whose propellant cannot give even the Hohmann Delta v (the impulsive minimum: no low-thrust transfer
    needs less) at the engine's best exhaust velocity (Tsiolkovsky)."""
    accel = propulsion.thrust_max_n / initial_mass
    lo, hi = ENVELOPE_ACCEL_M_S2
    if not lo <= accel <= hi:
        raise prop_s.error("thrust_max_n", f"T / m0 = {accel:.3g} m/s^2 is outside the envelope the family "
                           f"states ({lo:g}-{hi:g} m/s^2; docs/design/nmpc.md, \"Any circular rendezvous\")")
    r1, r2 = sorted((initial.radius_m, target.radius_m))
    dv_min, _ = hohmann(problem.sun_mu_m3_s2, r1, r2)
    ve = exhaust_velocity_max_m_s(propulsion, r1, r2)
    dv_max = ve * math.log(initial_mass / dry_mass)
    if not dv_max > dv_min:
        raise prop_s.error("thrust_max_n", f"not enough propellant: {initial_mass - dry_mass:.6g} kg "
                           f"(spacecraft.dry_mass_kg) give at most {dv_max:.0f} m/s, the transfer needs "
                           f"more than the Hohmann {dv_min:.0f} m/s")


@dataclasses.dataclass(frozen=True)
class Problem:
    """Table A.1, "Problem definition"."""

    start_time_s: float             #: t_0 [s]
    earth_orbit_radius_m: float     #: r_E [m] (the departure planet's orbit; the length unit)
    target_orbit_radius_m: float    #: r_T [m] (the paper's r_M)
    earth_mass_kg: float            #: m_E [kg]
    target_mass_kg: float           #: m_T [kg] (the paper's m_M)
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
    target_mu_m3_s2: float                #: mu_M [m^3/s^2]
    earth_initial_polar_angle_rad: float    #: (theta_E)_0 [rad]


@dataclasses.dataclass(frozen=True)
class Dispersions:
    """[dispersions]: what a perturbed flight draws at random (Table A.1's thrust-angle noise, sec. 3.5);
    the deterministic forces and the thrust offset are [perturbations]."""

    thrust_angle_sigma_rad: float       #: sigma_alpha_T [rad]
    #: How often the closed loop redraws the thrust-angle noise N(0, sigma_alpha_T) [s] (not in the paper,
    #: which only says "pseudorandom"); 0 = once per MPC control subinterval (docs/design/nmpc.md, "Truth model").
    thrust_angle_draw_period_s: float


@dataclasses.dataclass(frozen=True)
class Acceptance:
    """[acceptance]: a closed-loop flight passes when it arrives (the [convergence] test stops it) with its
    final miss within these and, when propellant_kg is given, burns no more propellant (truth mass).

    Default when the scenario has no [acceptance] (or leaves a key out): the arrival condition of
    [convergence]: position_error_m = target_soi_radius_m, velocity_error_m_s = velocity_error_m_s, and
    propellant_kg = the vehicle's propellant (initial_state.mass_kg - spacecraft.dry_mass_kg)."""

    position_error_m: float             #: |r - r_M| at arrival [m]
    velocity_error_m_s: float           #: |v - v_M| at arrival [m/s]
    propellant_kg: float | None = None  #: m_0 - m_f limit [kg]; None: no limit


@dataclasses.dataclass(frozen=True)
class SolarElectric:
    """Solar-electric engine, eq. (14): T_max(r) = b1 + b2 P_0 (a1 r^2 + a2 r + a3) / (r^4 (1 + a4 r)) with
    r in AU, and mass rate dm/dt = c1 + c2 P, P = (T - b1) / b2. The paper prints a_i, b_i, c_i without
    units; the scenario stores them in SI read with the units of Kim's model (mN, kW, mg/s), the only
    reading under which T_0 = 0.5 N at 1 AU needs a plausible P_0 (13.9 kW; docs/design/nmpc.md)."""

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
    target_soi_radius_m: float
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
    #: in 490-1700 d; the bound, just past the knee, cuts off the long branches (docs/design/nmpc.md, "Minimum fuel").
    transfer_time_max_s: float | None = None


#: [nmpc] departure_planet_in_model: "no" (the paper's predictive model), "hill-sphere" (Earth's gravity in
#: the flight solver's predictive model until a replan's measured state is beyond Earth's Hill sphere)
DEPARTURE_PLANET_IN_MODEL = ("no", "hill-sphere")
#: [nmpc] hessian: the flight solver's QP Hessian
NMPC_HESSIANS = ("bfgs", "exact")


@dataclasses.dataclass(frozen=True)
class NmpcSettings:
    """The closed loop of sec. 2.3 (`ogk nmpc`, harness/ogk/missions/rendezvous). The paper gives none of the
    SNNS parameters (errata): the values in the scenario files are ours (docs/design/nmpc.md, "Closed loop")."""

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
    earth_keepout_radius_m: float = 0.0  #: flight solver: plan nodes and arcs stay this far from Earth (0: none)
    #: flight solver, beyond the paper (docs/design/nmpc-flight.md, "Robustness"):
    thrust_margin_percent: float = 0.0   #: the plan's engine is this much weaker than the nominal one [%]
    terminal_set_fraction: float = 0.0   #: the plan ends inside this fraction of the arrival test (0: eq. 5 exactly)
    departure_planet_in_model: str = "no"  #: "hill-sphere": Earth's gravity predicted until the flight leaves its Hill sphere
    hessian: str = "bfgs"                #: flight solver's QP Hessian: "bfgs" (damped BFGS) or "exact" (docs/design/nmpc-flight.md)


@dataclasses.dataclass(frozen=True)
class RendezvousScenario:
    path: Path
    name: str
    source: str
    problem: Problem
    initial: PolarState
    initial_mass_kg: float
    target: PolarState              #: the target at t_0 (circular orbit, eq. 6)
    target_name: str                #: [target] name: what the outputs call it ("Mars")
    target_body_radius_m: float     #: [target] body_radius_m: the planet's radius (a flight inside it has hit it)
    dry_mass_kg: float              #: [spacecraft] dry_mass_kg: the mass with no propellant left
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
        """sqrt(mu / r_T^3), eq. (6)."""
        return math.sqrt(self.problem.sun_mu_m3_s2 / self.problem.target_orbit_radius_m ** 3)

    @property
    def earth_hill_radius_m(self) -> float:
        """Earth's Hill radius r_E (m_E / (3 m_S))^(1/3) [m]: inside it Earth, not the Sun, dominates the
        spacecraft's motion relative to Earth (1.497e9 m for Table A.1)."""
        p = self.problem
        return p.earth_orbit_radius_m * (p.earth_mass_kg / (3.0 * p.sun_mass_kg)) ** (1.0 / 3.0)

    @property
    def propellant_kg(self) -> float:
        """m_0 - dry mass: what the engine can burn."""
        return self.initial_mass_kg - self.dry_mass_kg

    @property
    def outward(self) -> bool:
        """The target's orbit is above the departure orbit."""
        return self.target.radius_m > self.initial.radius_m


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
    # inward and outward transfers alike; the envelope the family states is checked below (ENVELOPE_*)

    init_s = top.section("initial_state")
    initial = _read_state(init_s)
    initial_mass = init_s.number("mass_kg", positive=True)
    init_s.finish()
    _check_circular(init_s, initial, problem.sun_mu_m3_s2, "spacecraft")

    target_s = top.section("target")
    target_name = target_s.text("name")
    target_body_radius = target_s.number("body_radius_m", positive=True)
    target = _read_state(target_s)
    target_s.finish()
    _check_circular(target_s, target, problem.sun_mu_m3_s2, target_name)
    if target.radius_m != problem.target_orbit_radius_m:
        raise target_s.error("radius_m", "must equal problem.target_orbit_radius_m (circular orbit, eq. 6)")
    ratio = target.radius_m / initial.radius_m
    if not ENVELOPE_RADIUS_RATIO[0] <= ratio <= ENVELOPE_RADIUS_RATIO[1] or abs(ratio - 1.0) < 0.05:
        raise target_s.error("radius_m", f"target / departure orbit radius {ratio:.4g} is outside the "
                             f"envelope the family states ({ENVELOPE_RADIUS_RATIO[0]:g}-"
                             f"{ENVELOPE_RADIUS_RATIO[1]:g}, at least 5 % apart; docs/design/nmpc.md, "
                             f"\"Any circular rendezvous\")")

    craft_s = top.section("spacecraft")
    dry_mass = craft_s.number("dry_mass_kg", positive=True)
    craft_s.finish()
    if not dry_mass < initial_mass:
        raise craft_s.error("dry_mass_kg", f"{dry_mass:g} kg leaves no propellant: must be below "
                            f"initial_state.mass_kg = {initial_mass:g} kg")

    pert_s = top.section("perturbations")
    perturbations = pert_s.dataclass(Perturbations, area_m2={"nonnegative": True},
                                     reflectivity_efficiency={"lo": 0.0, "hi": 1.0},
                                     solar_constant_w_m2={"nonnegative": True},
                                     speed_of_light_m_s={"positive": True},
                                     thrust_offset_percent={"lo": -100.0, "hi": 100.0},
                                     earth_mu_m3_s2={"nonnegative": True},
                                     target_mu_m3_s2={"nonnegative": True})
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
    _check_propellant(prop_s, propulsion, problem, initial, target, initial_mass, dry_mass)

    conv_s = top.section("convergence")
    convergence = conv_s.dataclass(Convergence, **{f.name: {"positive": True}
                                                   for f in dataclasses.fields(Convergence)})
    conv_s.finish()
    if not target_body_radius < convergence.target_soi_radius_m:
        raise target_s.error("body_radius_m", f"{target_body_radius:g} m is not below the sphere of influence "
                             f"convergence.target_soi_radius_m = {convergence.target_soi_radius_m:g} m")
    escape = math.sqrt(2.0 * perturbations.target_mu_m3_s2 / convergence.target_soi_radius_m)
    if not convergence.velocity_error_m_s > escape:
        raise conv_s.error("velocity_error_m_s", f"{convergence.velocity_error_m_s:g} m/s is below "
                           f"{target_name}'s escape speed at its sphere of influence, sqrt(2 mu_T / r_SOI) = "
                           f"{escape:.0f} m/s: its pull alone would keep the arrival test from holding")
    acceptance = _read_acceptance(top.section("acceptance", optional=True), convergence,
                                   initial_mass - dry_mass)

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
                                                             nonnegative=True),
                        thrust_margin_percent=nmpc_s.number("thrust_margin_percent", default=0.0, lo=0.0,
                                                            hi=50.0),
                        terminal_set_fraction=nmpc_s.number("terminal_set_fraction", default=0.0, lo=0.0,
                                                            hi=0.9),
                        departure_planet_in_model=nmpc_s.text("departure_planet_in_model", default="no",
                                                              choices=DEPARTURE_PLANET_IN_MODEL),
                        hessian=nmpc_s.text("hessian", default="bfgs", choices=NMPC_HESSIANS))
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
                              target_name=target_name, target_body_radius_m=target_body_radius,
                              dry_mass_kg=dry_mass,
                              perturbations=perturbations, propulsion=propulsion,
                              convergence=convergence, ocp=ocp, law=law, paper_results=paper,
                              nmpc=nmpc, dispersions=dispersions, acceptance=acceptance)


def paper_problem(scenario: RendezvousScenario) -> RendezvousScenario:
    """The scenario with the flight solver's robustness of [nmpc] off: no thrust margin, eq. (5) exactly,
    no departure planet in the predictive model, no keep-out (docs/design/nmpc-flight.md, "Robustness"). It is
    the paper's NMPC problem, the one the ground NLP (nlp.py) and the peers of `make bench` solve."""
    return dataclasses.replace(scenario, nmpc=dataclasses.replace(
        scenario.nmpc, thrust_margin_percent=0.0, terminal_set_fraction=0.0, departure_planet_in_model="no",
        earth_keepout_radius_m=0.0))


def _read_acceptance(sec: Section, convergence: Convergence, propellant_kg: float) -> Acceptance:
    """[acceptance]; STATED DEFAULT (docs/guides/adding-a-mission.md, "The scenario header"): the arrival
    condition of [convergence] (the target's sphere-of-influence radius, its velocity error) and the
    vehicle's propellant (initial_state.mass_kg - spacecraft.dry_mass_kg)."""
    acc = Acceptance(position_error_m=sec.number("position_error_m", convergence.target_soi_radius_m,
                                                 positive=True),
                     velocity_error_m_s=sec.number("velocity_error_m_s", convergence.velocity_error_m_s,
                                                   positive=True),
                     propellant_kg=sec.number("propellant_kg", propellant_kg, positive=True))
    sec.finish()
    if acc.propellant_kg is not None and acc.propellant_kg > propellant_kg:
        raise sec.error("propellant_kg", f"{acc.propellant_kg:g} kg is more than the vehicle carries "
                        f"({propellant_kg:g} kg = initial_state.mass_kg - spacecraft.dry_mass_kg)")
    return acc
