"""The rendezvous closed loop (Starek & Kolmanovsky 2012, secs. 2.3 and 4): guidance replans at the start of
each control subinterval from the measured truth state, the truth model flies the command over the
subinterval, and the flight ends at the first instant the rendezvous criterion holds.

Rendezvous (sec. 2.3.1): ||r - r_M|| < (r_SOI)_M and ||v - v_M|| < 1 km/s ([convergence] of the scenario).
It is checked on the truth model's integration grid inside every subinterval, and the first grid interval in
which it starts to hold is bisected (re-propagating from the last grid point where it did not) down to
`ARRIVAL_TOLERANCE_S`: the flight time reported is the first instant the criterion holds, as in the paper
(which "terminates the controller within a finite tolerance of the target defined by the SOI"), not the
end of the subinterval in which it happens. A flight whose truth trajectory passes inside Earth's or Mars'
radius (`EARTH_RADIUS_M`, the scenario's [target] body_radius_m: the truth's planets are point masses and would let
it through) ends there, not converged ("earth_impact", "target_impact"), checked on the same grid.

Perturbed flights: the truth model adds Earth and Mars gravity, solar radiation pressure and the -10 % thrust
offset (truth.py); the loop adds the thrust-angle noise N(0, sigma_alpha_T): one draw per control subinterval
when [dispersions] thrust_angle_draw_period_s is 0, otherwise one draw every that many seconds of flight
(draw k covers [k P, (k + 1) P) from t_0), held constant in between. The draws come from
ogk.sil.seeds.run_generator(seed) (PCG64(seed), the stream numpy's default generator of that seed gives) in flight
order, so a seed is one reproducible flight; a campaign gives each run its own seed (ogk.sil.engine).

Times and states are normalised (TU, LU, VU, MU) inside the loop; the result also carries SI figures.
"""
from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ogk_host.rendezvous.dynamics import DAY_S, Engine, Model
from ogk_host.rendezvous.scenario import RendezvousScenario

from .dispersions import FIRST_OFFSET_KEY, AngleNoise, sigma_flown
from .guidance_base import Guidance, ReplanInfo
from .truth import TruthModel

FloatArray = NDArray[np.float64]

ARRIVAL_TOLERANCE_S = 600.0     #: bisection of the first instant of rendezvous [s]
#: Earth's mean radius (IUGG; not in Table A.1; the target's is the scenario's [target] body_radius_m): the truth
#: model's planets are point masses, so a flight that passes closer than this to a planet's centre has hit it and
#: ends there ("earth_impact", "target_impact").
EARTH_RADIUS_M = 6.3710e6
#: A plan may arrive this much below the dry mass before it is refused (the plan's RK4 against the truth).
PROPELLANT_SLACK_KG = 1e-3
TRUTH_RTOL = 1e-10
TRUTH_ATOL = 1e-12


@dataclasses.dataclass(frozen=True)
class ReplanRecord:
    """One replan of the flight (Figs. 7/10: miss per iteration)."""

    index: int
    t_days: float
    position_miss_km: float         #: ||r - r_M|| at the replan
    velocity_miss_m_s: float        #: ||v - v_M|| at the replan
    nodes: int
    iterations: int
    solve_ms: float
    solves: int
    converged: bool
    failed: bool
    subdivided: bool
    planned_t_f_days: float         #: t_f of the plan flown from here
    subinterval_days: float         #: length of the subinterval flown
    angle_offset_deg: float         #: thrust-angle noise of the subinterval's first draw
    sweep_deg: float                #: |alpha_1 - alpha_0| of the flown subinterval (> 360: a winding)
    status: str
    status_n: str = ""              #: status of the N solve (SNNS: before the doubling test)
    cost_n_days: float | None = None    #: min-time: cost-to-go of the N solve [d] (None: failed)
    cost_2n_days: float | None = None   #: ... of the 2N solve (None: failed or not tried)

    def to_json(self) -> dict[str, Any]:
        return dataclasses.asdict(self)


@dataclasses.dataclass
class FlightResult:
    scenario: str
    strategy: str
    solver: str
    perturbed: bool
    seed: int
    converged: bool
    reason: str                     #: why the flight ended ("rendezvous", "max_replans", ...)
    t_f_days: float                 #: flight time to the first instant of rendezvous (or to the stop)
    fuel_kg: float                  #: m_0 - m(t_f) of the truth model
    fuel_nominal_mdot_kg: float     #: the paper's accounting: nominal mass flow x thrusting time
    final_position_miss_km: float
    final_velocity_miss_m_s: float
    solves: int
    failed_solves: int
    subdivisions: int
    iterations: int
    solve_ms: list[float]           #: solver wall time of each replan [ms]
    max_comp_fraction: float        #: max over replans of solve time / subinterval flown (Table I's figure)
    history: list[ReplanRecord]
    t: FloatArray                   #: truth trajectory times [TU]
    states: FloatArray              #: truth states (n, 5), normalised
    command_t: FloatArray           #: command samples [TU]
    command_alpha: FloatArray       #: commanded angle [rad]
    command_w: FloatArray           #: commanded throttle
    command_offset: FloatArray      #: thrust-angle noise added [rad]
    units: Any = None
    closest_approach: dict[str, float] = dataclasses.field(default_factory=dict)
    earth_encounter: dict[str, float] = dataclasses.field(default_factory=dict)  #: closest to Earth
    first_angle_offset_rad: float | None = None   #: the first thrust-angle noise flown (dispersions.py)

    def summary(self) -> dict[str, Any]:
        ms = np.asarray(self.solve_ms) if self.solve_ms else np.zeros(1)
        return {"scenario": self.scenario, "strategy": self.strategy, "solver": self.solver,
                "perturbed": self.perturbed, "seed": self.seed, "converged": self.converged,
                "reason": self.reason, "t_f_days": self.t_f_days, "fuel_kg": self.fuel_kg,
                "fuel_nominal_mdot_kg": self.fuel_nominal_mdot_kg,
                "final_position_miss_km": self.final_position_miss_km,
                "final_velocity_miss_m_s": self.final_velocity_miss_m_s,
                "iterations": self.iterations, "solves": self.solves, "replans": len(self.history),
                "failed_solves": self.failed_solves, "subdivisions": self.subdivisions,
                "solve_ms": {"median": float(np.median(ms)), "max": float(np.max(ms)),
                             "total": float(np.sum(ms))},
                "max_comp_fraction": self.max_comp_fraction,
                "closest_approach": self.closest_approach, "earth_encounter": self.earth_encounter,
                FIRST_OFFSET_KEY: self.first_angle_offset_rad}

    def to_json(self) -> dict[str, Any]:
        doc = self.summary()
        doc["history"] = [r.to_json() for r in self.history]
        return doc


# --------------------------------------------------------------------------------------------------------

def _mass_flow_max(scenario: RendezvousScenario, r: FloatArray) -> FloatArray:
    """Nominal mdot_max(r) [normalised] of the engine (the predictive model's, no thrust offset)."""
    return np.asarray(Engine.for_scenario(scenario).limits(r)[1], dtype=np.float64) * np.ones_like(r)


def polar_distance_m(x: FloatArray, body: FloatArray, units: Any) -> float:
    """|r - r_body| [m] of two normalised polar positions (r, theta, ...)."""
    dth = float(x[1]) - float(body[1])
    d2 = x[0] ** 2 + body[0] ** 2 - 2.0 * x[0] * body[0] * math.cos(dth)
    return math.sqrt(max(float(d2), 0.0)) * units.length_m


def _days(cost: float | None, scenario: RendezvousScenario, units: Any) -> float | None:
    """A min-time cost-to-go [TU] in days (None for min-fuel costs and failed solves)."""
    if cost is None or scenario.ocp.objective != "min-time":
        return None
    return cost * units.time_s / DAY_S


def _record(index: int, t: float, x: FloatArray, info: ReplanInfo, t_next: float, offset: float,
            truth: Any, scenario: RendezvousScenario, units: Any) -> ReplanRecord:
    dr0, dv0 = truth.miss(t, x)
    return ReplanRecord(index=index, t_days=t * units.time_s / DAY_S, position_miss_km=dr0 / 1e3,
                        velocity_miss_m_s=dv0, nodes=info.nodes, iterations=info.iterations,
                        solve_ms=info.solve_time_s * 1e3, solves=info.solves, converged=info.converged,
                        failed=info.failed, subdivided=info.subdivided,
                        planned_t_f_days=info.plan.t_f * units.time_s / DAY_S,
                        subinterval_days=(t_next - t) * units.time_s / DAY_S,
                        angle_offset_deg=math.degrees(offset),
                        sweep_deg=math.degrees(abs(float(info.plan.controls[1, 0] - info.plan.controls[0, 0]))),
                        status=info.status, status_n=info.status_n,
                        cost_n_days=_days(info.cost_n, scenario, units),
                        cost_2n_days=_days(info.cost_2n, scenario, units))


def fly_run(scenario: RendezvousScenario, guidance: Guidance, perturbed: bool, seed: int,
        strategy_name: str = "", solver_name: str = "", truth: Any = None,
        max_replans: int | None = None, max_flight_days: float | None = None,
        progress: Callable[[ReplanRecord], None] | None = None) -> FlightResult:
    """Flies the scenario from its initial state with `guidance` (module docstring)."""
    truth = truth if truth is not None else TruthModel.for_scenario(scenario, perturbed=perturbed)
    model = Model.for_scenario(scenario)
    units = model.units
    conv = scenario.convergence
    max_replans = max_replans or scenario.nmpc.max_replans
    t_max = (max_flight_days or scenario.nmpc.max_flight_days) * DAY_S / units.time_s
    period_s = scenario.dispersions.thrust_angle_draw_period_s
    period = period_s / units.time_s
    noise = AngleNoise(sigma_flown(scenario, perturbed), seed)   # dispersions.py
    offset_for = noise.offset

    def arrived(t: float, x: FloatArray) -> bool:
        dr, dv = truth.miss(t, x)
        return dr < conv.target_soi_radius_m and dv < conv.velocity_error_m_s

    t = scenario.problem.start_time_s / units.time_s
    x = np.array(model.x0, copy=True)
    ts: list[FloatArray] = [np.array([t])]
    xs: list[FloatArray] = [x[None, :]]
    cmd_t: list[float] = []
    cmd_a: list[float] = []
    cmd_w: list[float] = []
    cmd_o: list[float] = []
    history: list[ReplanRecord] = []
    infos: list[ReplanInfo] = []
    reason = ""
    done = False
    subinterval_count = 0
    while not done:
        if len(history) >= max_replans:
            reason = "max_replans"
            break
        if t >= t_max:
            reason = "max_flight_time"
            break
        info = guidance.replan(t, x)
        infos.append(info)
        # the dry mass (docs/design/nmpc.md, "Any circular rendezvous"): a plan that arrives below it is refused,
        # the flight stops with the reason (the predictive model knows no dry mass)
        if not history and not info.converged:
            reason = (f"no first plan to {scenario.target_name}: no solve converged from the guesses sized "
                      f"for this vehicle ({info.status})")
            history.append(_record(0, t, x, info, t, 0.0, truth, scenario, units))
            break
        need_kg = (float(x[4]) - float(info.plan.states[-1, 4])) * units.mass_kg
        left_kg = float(x[4]) * units.mass_kg - scenario.dry_mass_kg
        if not history and info.converged and info.outside_set:
            # the flight solver's propellant row holds and its terminal set is priced: a first plan that
            # ends outside the set is the closest the vehicle can get (docs/design/nmpc-flight.md, "Robustness")
            reason = (f"propellant: the plan to {scenario.target_name} needs more than the {left_kg:.1f} kg "
                      f"left (dry mass {scenario.dry_mass_kg:g} kg): the closest plan within it ends outside "
                      f"the target's set")
            history.append(_record(0, t, x, info, t, 0.0, truth, scenario, units))
            break
        if info.converged and need_kg > left_kg + PROPELLANT_SLACK_KG:
            reason = (f"propellant: the plan to {scenario.target_name} needs {need_kg:.1f} kg, "
                      f"{left_kg:.1f} kg left (dry mass {scenario.dry_mass_kg:g} kg)")
            history.append(_record(len(history), t, x, info, t, 0.0, truth, scenario, units))
            break
        t_next = min(info.t_next, t_max)
        if not t_next > t:
            reason = "empty_subinterval"
            break
        # thrust-angle noise: one draw per subinterval, or draws on a fixed period from t_0
        if period > 0.0:
            k0 = int(math.floor((t - 0.0) / period + 1e-12))
            edges = [t] + [k * period for k in range(k0 + 1, int(math.ceil(t_next / period)))] + [t_next]
            segs = [(edges[i], edges[i + 1], offset_for(k0 + i)) for i in range(len(edges) - 1)
                    if edges[i + 1] > edges[i]]
        else:
            segs = [(t, t_next, offset_for(subinterval_count))]
        subinterval_count += 1
        rec = _record(len(history), t, x, info, t_next, segs[0][2], truth, scenario, units)
        history.append(rec)
        if progress is not None:
            progress(rec)
        for (ta, tb, off) in segs:
            tg, xg = truth.propagate(ta, x, tb, guidance.command, off, TRUTH_RTOL, TRUTH_ATOL)
            tg = np.asarray(tg, dtype=np.float64)
            xg = np.asarray(xg, dtype=np.float64)
            if not np.all(np.isfinite(xg)) or np.min(xg[:, 0]) <= 0.05 or np.min(xg[:, 4]) <= 0.0:
                reason = "truth_invalid"
                done = True
                break
            dry = scenario.dry_mass_kg / units.mass_kg
            empty = np.nonzero(xg[1:, 4] < dry)[0]
            if len(empty):      # ran dry: the flight ends at the first grid point below the dry mass
                k = int(empty[0]) + 1
                tg, xg = tg[: k + 1], xg[: k + 1]
                reason = f"propellant: ran dry (dry mass {scenario.dry_mass_kg:g} kg) before {scenario.target_name}"
                done = True
            # a point-mass truth lets the spacecraft fly through a planet: the flight ends there
            impact, impact_reason = len(tg), ""
            for i in range(1, len(tg)):
                if polar_distance_m(xg[i], truth.earth_state(float(tg[i])), units) < EARTH_RADIUS_M:
                    impact, impact_reason = i, "earth_impact"
                    break
                if polar_distance_m(xg[i], truth.mars_state(float(tg[i])), units) < scenario.target_body_radius_m:
                    impact, impact_reason = i, "target_impact"
                    break
            hit = -1
            for i in range(1, impact):
                dr, dv = truth.miss(float(tg[i]), xg[i])
                if dr < conv.target_soi_radius_m and dv < conv.velocity_error_m_s:
                    hit = i
                    break
            if hit > 0:     # (before the dry-mass point when the flight also ran dry: the arrival wins)
                # bisect the first instant of rendezvous between grid points hit - 1 and hit
                lo_t, lo_x, hi_t, hi_x = float(tg[hit - 1]), xg[hit - 1], float(tg[hit]), xg[hit]
                tol = ARRIVAL_TOLERANCE_S / units.time_s
                while hi_t - lo_t > tol:
                    mid = 0.5 * (lo_t + hi_t)
                    _, xm = truth.propagate(lo_t, lo_x, mid, guidance.command, off, TRUTH_RTOL, TRUTH_ATOL)
                    xm = np.asarray(xm)[-1]
                    if arrived(mid, xm):
                        hi_t, hi_x = mid, xm
                    else:
                        lo_t, lo_x = mid, xm
                tg = np.concatenate([tg[:hit], [hi_t]])
                xg = np.vstack([xg[:hit], hi_x[None, :]])
                reason = "rendezvous"
                done = True
            elif impact < len(tg):
                tg, xg = tg[: impact + 1], xg[: impact + 1]
                reason = impact_reason
                done = True
            ts.append(tg[1:])
            xs.append(xg[1:])
            # command samples for the figures: the integration grid and 16 per segment
            samples = np.union1d(tg[:-1], np.linspace(tg[0], tg[-1], 17)[:-1]) if len(tg) > 1 else tg
            for tk in samples:
                a, w = guidance.command(float(tk))
                cmd_t.append(float(tk))
                cmd_a.append(a)
                cmd_w.append(w)
                cmd_o.append(off)
            x = xg[-1]
            t = float(tg[-1])
            if done:
                break
    t_arr = np.concatenate(ts)
    x_arr = np.vstack(xs)
    dr_f, dv_f = truth.miss(t, x)
    misses = np.array([truth.miss(float(tk), xk) for tk, xk in zip(t_arr, x_arr)])
    k_best = int(np.argmin(misses[:, 0]))
    # Earth encounters (unmodelled in the predictive model): the closest distance to Earth over the flight
    d_earth = np.array([polar_distance_m(xk, truth.earth_state(float(tk)), units) for tk, xk in zip(t_arr, x_arr)])
    k_emin = int(np.argmin(d_earth))
    # the paper's fuel accounting: nominal mass flow (no thrust offset) x throttle, integrated over the flight
    ct = np.asarray(cmd_t)
    cw = np.asarray(cmd_w)
    nominal = 0.0
    if len(t_arr) > 1:
        w_on_grid = np.interp(t_arr, ct, cw) if len(ct) else np.ones_like(t_arr)
        rate = _mass_flow_max(scenario, x_arr[:, 0]) * w_on_grid
        nominal = float(np.trapezoid(rate, t_arr)) * units.mass_kg
    ms = [i.solve_time_s * 1e3 for i in infos]
    frac = max((i.solve_time_s / ((min(i.t_next, t_max) - i.t) * units.time_s) for i in infos
                if min(i.t_next, t_max) > i.t), default=0.0)
    return FlightResult(
        scenario=scenario.name, strategy=strategy_name, solver=solver_name, perturbed=perturbed, seed=seed,
        converged=reason == "rendezvous", reason=reason or "stopped",
        t_f_days=(t - scenario.problem.start_time_s / units.time_s) * units.time_s / DAY_S,
        fuel_kg=float(model.x0[4] - x[4]) * units.mass_kg, fuel_nominal_mdot_kg=nominal,
        final_position_miss_km=dr_f / 1e3, final_velocity_miss_m_s=dv_f,
        solves=int(getattr(guidance, "solves", len(infos))),
        failed_solves=int(getattr(guidance, "failed_solves", sum(i.failed for i in infos))),
        subdivisions=int(getattr(guidance, "subdivisions", sum(i.subdivided for i in infos))),
        iterations=sum(i.iterations for i in infos), solve_ms=ms, max_comp_fraction=frac, history=history,
        t=t_arr, states=x_arr, command_t=ct, command_alpha=np.asarray(cmd_a), command_w=cw,
        command_offset=np.asarray(cmd_o), units=units,
        closest_approach={"position_miss_km": float(misses[k_best, 0]) / 1e3,
                          "t_days": float(t_arr[k_best]) * units.time_s / DAY_S,
                          "velocity_miss_m_s": float(misses[k_best, 1])},
        earth_encounter={"distance_km": float(d_earth[k_emin]) / 1e3,
                         "t_days": float(t_arr[k_emin]) * units.time_s / DAY_S,
                         "start_distance_km": float(d_earth[0]) / 1e3},
        first_angle_offset_rad=noise.first_rad)
