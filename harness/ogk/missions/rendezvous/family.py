"""The low-thrust rendezvous family (ogk.sil.family.MissionFamily): the receding-horizon NMPC
closed loop (Starek & Kolmanovsky 2012). `ogk run` flies it once (one_flight.py; `ogk nmpc` is its
older spelling); `ogk mc` flies it on many thrust-angle noise streams: run i is one closed-loop
flight whose noise comes from its own stream (ogk.sil.seeds), a new guidance context per run, the
truth model perturbed unless --unperturbed; on a target every replan is the flight program's
(pil.py). The family has no ground tables.

Acceptance: the scenario's [acceptance] (`scenario.acceptance`): the flight arrives (the [convergence]
test: inside Mars' sphere of influence and within its velocity tolerance, before the replan and
flight-time limits) with its final miss within position_error_m / velocity_error_m_s (default: the
arrival condition itself) and, when the scenario states propellant_kg, no more propellant burnt; a
flight that stops for any other reason (impact, replan limit, truth failure) fails with that reason.
"""
from __future__ import annotations

import argparse
import dataclasses
import time
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import numpy as np
from ogk_bindings.errors import OgkInputError
from ogk_host.rendezvous.scenario import LAWS, Acceptance, RendezvousScenario, load_scenario
from ogk_host.scenario_file import ScenarioHeader, file_sha256

from ogk.sil.dispersion_check import scenario_table
from ogk.sil.engine import Flown
from ogk.sil.family import CampaignPlan, ChunkFlight, Detail, FamilyDefaults, Record, per_run
from ogk.sil.pil import FlightProgram

from .dispersions import FIRST_OFFSET_KEY, declared, draw_records

STRATEGIES = ("snns", "cncn")
SOLVERS = ("kernel", "ipopt")
RESULTS = ("t_f_days", "fuel_kg", "fuel_nominal_mdot_kg", "final_position_miss_km",
           "final_velocity_miss_m_s", "iterations", "solves", "replans", "failed_solves",
           "subdivisions")


def with_model(scenario: RendezvousScenario, third_bodies: str) -> RendezvousScenario:
    """The scenario with the predictive model's third bodies as the command says."""
    if third_bodies == "scenario":
        return scenario
    return dataclasses.replace(scenario, nmpc=dataclasses.replace(
        scenario.nmpc, third_bodies_in_model=third_bodies == "yes"))


def moved_start(scenario: RendezvousScenario, move: str | None) -> RendezvousScenario:
    """The scenario with its initial radius moved by `move`: '<k>ulp' (k steps to the next
    representable double, outward for k > 0) or '<x>m' (x metres); None or '' leaves it."""
    if not move:
        return scenario
    text = str(move).strip()
    r = scenario.initial.radius_m
    try:
        if text.endswith("ulp"):
            k = int(text[:-3])
            if abs(k) > 10**6:
                raise ValueError
            for _ in range(abs(k)):
                r = float(np.nextafter(r, np.inf if k > 0 else -np.inf))
        elif text.endswith("m"):
            r = r + float(text[:-1])
        else:
            raise ValueError
    except ValueError:
        raise OgkInputError(f"'<k>ulp' or '<x>m', got {move!r}", key="--move-start") from None
    return dataclasses.replace(scenario, initial=dataclasses.replace(scenario.initial, radius_m=r))


def judge(acceptance: Acceptance, rec: Mapping[str, Any]) -> str:
    """"" or why the flight fails the scenario's [acceptance] (module doc)."""
    if not rec["converged"]:
        return f"not arrived: {rec['reason']}"
    miss_m = None if rec.get("final_position_miss_km") is None else 1e3 * rec["final_position_miss_km"]
    if miss_m is not None and not miss_m <= acceptance.position_error_m:
        return f"tolerance: |r - r_T| = {miss_m:.4g} m > {acceptance.position_error_m:.4g}"
    dv = rec.get("final_velocity_miss_m_s")
    if dv is not None and not dv <= acceptance.velocity_error_m_s:
        return f"tolerance: |v - v_T| = {dv:.4g} m/s > {acceptance.velocity_error_m_s:.4g}"
    fuel = rec.get("fuel_kg")
    if acceptance.propellant_kg is not None and fuel is not None and not fuel <= acceptance.propellant_kg:
        return f"propellant: {fuel:.4g} kg > {acceptance.propellant_kg:.4g}"
    return ""


#: the per-run timing keys of flight_record (None on a run that did not fly to its end)
TIMING = ("timing.solve_ms_median", "timing.solve_ms_max", "timing.max_comp_fraction")


def flight_record(summary: Mapping[str, Any]) -> Record:
    """A flat record of one closed-loop flight (FlightResult.summary())."""
    rec: Record = {"converged": bool(summary["converged"]), "reason": str(summary["reason"])}
    rec.update({k: summary.get(k) for k in RESULTS})
    rec[FIRST_OFFSET_KEY] = summary.get(FIRST_OFFSET_KEY)   # the noise flown (dispersions.py)
    rec["timing.solve_ms_median"] = summary["solve_ms"]["median"]
    rec["timing.solve_ms_max"] = summary["solve_ms"]["max"]
    rec["timing.max_comp_fraction"] = summary["max_comp_fraction"]   # CPU time / control period
    return rec


@dataclasses.dataclass(frozen=True)
class _Base:
    """What the report and the target job read of a plan (family-private)."""

    scenario: RendezvousScenario        #: as flown (the command's model, start and Hessian)
    settings: Any                       #: guidance_base.StrategySettings of the strategy flown


class RendezvousFamily(FamilyDefaults):
    name = "low-thrust-rendezvous"
    laws = LAWS
    targets = ("host", "m7", "sparc", "m4f")   #: m7 / sparc / m4f: port/cortex-m7/pil/nmpc_pil.c (pil.py)
    run_aliases = ("nmpc",)             #: `ogk nmpc`: the older `ogk run`
    target_watchdog_per_run_s = 7200.0  #: a whole closed loop of QEMU re-solves
    campaign_doc = ("closed-loop NMPC flights on independent thrust-angle noise streams "
                    "(run i: its own stream); judged by the scenario's [acceptance] (default: "
                    "the arrival condition)")

    def load(self, header: ScenarioHeader) -> RendezvousScenario:
        return load_scenario(header.path)

    def add_campaign_arguments(self, parser: argparse.ArgumentParser) -> None:
        parser.add_argument("--strategy", choices=STRATEGIES, default=None,
                       help="SNNS or CNCN (default: the scenario's [nmpc] strategy)")
        parser.add_argument("--solver", choices=SOLVERS, default="kernel",
                       help="kernel: the flight code's ogk_nmpc (default); ipopt: the ground peer")
        parser.add_argument("--unperturbed", action="store_true",
                       help="fly the unperturbed truth (every run is then the same flight)")
        parser.add_argument("--third-bodies-in-model", choices=("scenario", "yes", "no"),
                       default="scenario", help="Earth and Mars gravity in the predictive model")
        parser.add_argument("--max-replans", type=int, default=None, metavar="K",
                       help="replan limit of a flight (default: the scenario's)")
        parser.add_argument("--hessian", choices=("scenario", "bfgs", "exact"), default="scenario",
                       help="the flight solver's QP Hessian (default: the scenario's [nmpc] hessian)")
        parser.add_argument("--move-start", default=None, metavar="MOVE",
                       help="the first measured state's radius moved by MOVE: '<k>ulp' (k representable "
                            "doubles) or '<x>m' (metres); the sensitivity study "
                            "(python -m ogk.missions.rendezvous.sensitivity)")

    def plan(self, header: ScenarioHeader, options: Mapping[str, Any]) -> CampaignPlan:
        from .closed_loop import fly_run
        from .guidance_base import strategy_settings
        from .guidance_factory import make_guidance

        third = str(options.get("third_bodies_in_model") or "scenario")
        move = options.get("move_start")
        scenario = moved_start(with_model(self.load(header), third), move)
        hessian = str(options.get("hessian") or "scenario")
        if hessian != "scenario":
            scenario = dataclasses.replace(scenario, nmpc=dataclasses.replace(scenario.nmpc, hessian=hessian))
        strategy = str(options.get("strategy") or scenario.nmpc.strategy)
        solver = str(options.get("solver") or "kernel")
        if strategy not in STRATEGIES:
            raise OgkInputError(f"one of {', '.join(STRATEGIES)}, got {strategy!r}", key="--strategy")
        if solver not in SOLVERS:
            raise OgkInputError(f"one of {', '.join(SOLVERS)}, got {solver!r}", key="--solver")
        max_replans = options.get("max_replans")
        if max_replans is not None and int(max_replans) < 1:
            raise OgkInputError(f"must be >= 1, got {max_replans}", key="--max-replans")
        perturbed = not bool(options.get("unperturbed"))
        settings = strategy_settings(scenario, strategy)

        def flight(run_seed: int) -> Any:
            guidance = make_guidance(solver, scenario, settings)
            return fly_run(scenario, guidance, perturbed, run_seed, strategy, solver,
                       max_replans=max_replans)

        def fly_one(run_id: int, run_seed: int) -> Record:
            start = time.perf_counter()
            try:
                rec = flight_record(flight(run_seed).summary())
            except RuntimeError as err:   # the truth integration stopped (e.g. through a planet)
                rec = {"converged": False, "reason": f"truth: {err}", **dict.fromkeys(RESULTS),
                       FIRST_OFFSET_KEY: None, **dict.fromkeys(TIMING)}
            rec["timing.wall_s"] = time.perf_counter() - start
            return rec

        def detail(run_id: int, run_seed: int, plots: Path | None) -> Detail:
            result = flight(run_seed)
            files: tuple[Path, ...] = ()
            if plots is not None:
                from .plots import write_plots
                files = tuple(write_plots(scenario, result, plots))
            return Detail(flight_record(result.summary()), files)

        plan = CampaignPlan(
            family=self.name, law=header.law, mission=scenario.name,
            scenario_path=Path(header.path), scenario_sha256=file_sha256(header.path),
            options={"strategy": strategy, "solver": solver, "unperturbed": not perturbed,
                     "third_bodies_in_model": third, "max_replans": max_replans,
                     **({"move_start": str(move)} if move else {}),
                     **({"hessian": hessian} if hessian != "scenario" else {})},
            products={}, fly=per_run(fly_one),
            judge=lambda rec: judge(scenario.acceptance, rec),
            quantities=("t_f_days", "fuel_kg", "fuel_nominal_mdot_kg", "final_position_miss_km",
                        "final_velocity_miss_m_s", "failed_solves"),
            acceptance={"arrival": f"the [convergence] test: inside {scenario.target_name}'s sphere of "
                                   "influence within its velocity tolerance; propellant within the dry mass",
                        **dataclasses.asdict(scenario.acceptance)},
            detail=detail, watchdog_per_run_s=600.0, base=_Base(scenario, settings),
            dispersions=declared(scenario, scenario_table(header.path), perturbed),
            draw=lambda ids, seeds: draw_records(scenario, perturbed, ids, seeds))
        if options.get("target", "host") != "host":
            self.on_target(plan, str(options["target"]))
        return plan

    # ------------------------------------------------------------------ ogk run
    def add_run_arguments(self, parser: argparse.ArgumentParser) -> None:
        from .one_flight import add_run_arguments
        add_run_arguments(parser)

    def run(self, header: ScenarioHeader, args: argparse.Namespace) -> int:
        """`ogk run SCENARIO`: one closed-loop NMPC flight, beside the paper's Table I or II."""
        from .one_flight import run
        return run(header, args)

    # ------------------------------------------------------------------ on a target
    # the plan's replans made by the scenario's flight program (pil.py); the truth, the noise and
    # the judging stay on the host
    def flight_config(self, plan: CampaignPlan, out_dir: Path) -> list[Path]:
        """The ogk_nmpc configuration and first guesses of the strategy and model flown."""
        from .flight_config import write_flight_config
        return [write_flight_config(out_dir, plan.scenario_path, plan.base.scenario,
                                    str(plan.options["strategy"]),
                                    str(plan.options["third_bodies_in_model"]))]

    def flight_program(self, plan: CampaignPlan, target: str) -> FlightProgram:
        from . import pil
        if plan.options["solver"] != "kernel":
            raise OgkInputError(f"--target {target} flies the kernel's ogk_nmpc, got "
                                f"{plan.options['solver']!r}", key="--solver")
        return pil.flight_program(plan.scenario_path, str(plan.options["strategy"]),
                                  str(plan.options["third_bodies_in_model"]),
                                  lambda out: self.flight_config(plan, out), target)

    def target_job(self, plan: CampaignPlan, program: FlightProgram) -> ChunkFlight:
        from . import pil
        opts = plan.options
        max_replans = opts["max_replans"]
        return pil.TargetJob(plan.base.scenario, plan.base.settings, str(opts["strategy"]),
                             not bool(opts["unperturbed"]),
                             None if max_replans is None else int(max_replans), program,
                             flight_record, RESULTS)

    def target_bounds(self, plan: CampaignPlan) -> tuple[dict[str, float], str]:
        from . import pil
        return pil.target_bounds(plan.base.scenario), pil.BOUNDS_WHY

    def report(self, flown: Flown) -> tuple[str, dict[str, Any]]:
        opts = flown.plan.options
        recs = flown.records
        lines = [f"{flown.plan.mission}: {opts['strategy']} {opts['solver']} "
                 f"{'unperturbed' if opts['unperturbed'] else 'perturbed'}: "
                 f"{flown.plan.base.scenario.target_name} reached on "
                 f"{sum(1 for r in recs if r['converged'])} of {len(recs)} runs",
                 "  run  reached  t_f [d]   fuel [kg]  solves  failed  subdiv  median ms"]
        for r in recs:
            lines.append(f"  {r['run_id']:3d}  {'yes' if r['converged'] else 'NO ':7s}  "
                         f"{_f(r['t_f_days'], '8.2f')}  {_f(r['fuel_kg'], '9.2f')}  "
                         f"{_f(r['solves'], '6d')}  {_f(r['failed_solves'], '6d')}  "
                         f"{_f(r['subdivisions'], '6d')}  {_f(r.get('timing.solve_ms_median'), '9.2f')}")
        reached = sum(1 for r in recs if r["converged"])
        extra: dict[str, Any] = {"reached_target": reached, "reached_mars": reached}   # reached_mars: older name
        paper = paper_row(flown.plan.base.scenario, str(opts["strategy"]), not bool(opts["unperturbed"]), recs)
        if paper is not None:
            lines.append(paper["line"])
            extra["paper_row"] = {k: v for k, v in paper.items() if k != "line"}
        return "\n".join(lines), extra


def paper_row(scenario: RendezvousScenario, strategy: str, perturbed: bool,
              recs: Any) -> dict[str, Any] | None:
    """The paper's row of the same case (Table I or II, [paper_results]) beside the campaign: how many
    runs arrived no later than its t_f and within its fuel (the paper's accounting: nominal mass flow x
    thrusting time, errata), None when the scenario has no such row."""
    from .one_flight import paper_values
    if scenario.paper_results is None:
        return None
    paper = paper_values(scenario, strategy, perturbed)
    t_p, f_p = paper["t_f_days"], paper["fuel_kg"]
    if t_p is None or f_p is None:
        return None
    met = sum(1 for r in recs if r["converged"] and r["t_f_days"] is not None
              and r["t_f_days"] <= t_p and r["fuel_nominal_mdot_kg"] <= f_p)
    table = "Table I" if scenario.ocp.objective == "min-time" else "Table II"
    case = "perturbed" if perturbed else "unperturbed"
    line = (f"  paper ({table}, {strategy.upper()} {case}): {t_p:.2f} d, {f_p:.2f} kg (nominal mdot); "
            f"met or beaten (time and fuel) by {met} of {len(recs)} runs")
    return {"table": table, "t_f_days": t_p, "fuel_nominal_mdot_kg": f_p, "runs_meeting": met,
            "runs": len(recs), "line": line}


def _f(value: Any, fmt: str) -> str:
    width = int(fmt.split(".")[0].rstrip("df") or 0)
    return "-".rjust(width) if value is None else format(value, fmt)


FAMILY = RendezvousFamily()
