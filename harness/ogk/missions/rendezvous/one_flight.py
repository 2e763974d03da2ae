"""`ogk run SCENARIO` of a low-thrust rendezvous (the family's `run`; `ogk nmpc` is its older
spelling): the closed loop of sec. 2.3 (SNNS or CNCN, guidance by IPOPT or by the flight code's
ogk_nmpc) flown once against the truth model, unperturbed or perturbed (sec. 3.3-3.5); prints the
paper's Table I (min-time) or Table II (min-fuel) column of the same case beside the run, writes the
JSON and optionally the PNG figures (Figs. 5-10). Exit 0 when the flight reached the target (sec.
2.3.1's criterion), 1 when it did not, 2 on bad input.
"""
from __future__ import annotations

import argparse
import json
import math
import time
from pathlib import Path
from typing import Any

from ogk_bindings.errors import OgkInputError
from ogk_host.rendezvous.dynamics import DAY_S
from ogk_host.rendezvous.scenario import RendezvousScenario
from ogk_host.scenario_file import ScenarioHeader

from ogk.sil.outputs import check_output_dir, check_output_file, remove_stale, write_atomic
from ogk.sil.progress import Working
from ogk.sil.report import finite_or_none

STRATEGIES = ("snns", "cncn")
SOLVERS = ("ipopt", "kernel")


def add_run_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("--strategy", choices=STRATEGIES, default=None,
                   help="SNNS (sec. 2.3.3) or CNCN (sec. 2.3.1); default: the scenario's [nmpc] strategy")
    p.add_argument("--perturbed", action="store_true",
                   help="fly the perturbed truth model (Earth/Mars gravity, SRP, -10 %% thrust, angle noise)")
    p.add_argument("--seed", type=int, default=1, help="seed of the thrust-angle noise (default 1)")
    p.add_argument("--solver", choices=SOLVERS, default="kernel",
                   help="guidance: kernel (the flight code's ogk_nmpc) or ipopt (the ground NLP, CasADi + "
                        "IPOPT); default: %(default)s")
    p.add_argument("--json", required=True, metavar="FILE", help="write the result as JSON")
    p.add_argument("--plots", default=None, metavar="DIR", help="PNG figures (trajectory, control, miss)")
    p.add_argument("--third-bodies-in-model", choices=("scenario", "yes", "no"), default="scenario",
                   help="Earth and Mars gravity in the predictive model (default: the scenario's [nmpc])")
    p.add_argument("--max-replans", type=int, default=None, metavar="K",
                   help="stop after K replans (default: the scenario's [nmpc] max_replans)")
    p.add_argument("--trace", action="store_true", help="print one line per replan")
    p.add_argument("--hessian", choices=("scenario", "bfgs", "exact"), default="scenario",
                   help="the flight solver's QP Hessian (default: the scenario's [nmpc] hessian)")
    p.add_argument("--paper-problem", action="store_true",
                   help="fly the paper's problem: the flight solver's robustness of [nmpc] off (no thrust "
                        "margin, eq. 5 exactly, no departure planet, no keep-out; docs/design/nmpc-flight.md, "
                        "\"Robustness\"), e.g. to reproduce Table I's unperturbed row")
    p.add_argument("--target", choices=("host", "m7", "m4f"), default="host",
                   help="host: the kernel in this process (default); m7: every replan made by the "
                        "scenario's flight program on the emulated Cortex-M7 (docs/guides/pil.md); "
                        "m4f: on the Cortex-M4F with the single-precision kernel")


def _paper_prefix(strategy: str, perturbed: bool) -> str:
    return f"{strategy}{'_perturbed' if perturbed else ''}"


def paper_values(scenario: RendezvousScenario, strategy: str, perturbed: bool) -> dict[str, float | None]:
    """The paper's figures of the same case from [paper_results] (None where the paper has none)."""
    pre = _paper_prefix(strategy, perturbed)
    p = scenario.paper_results or {}
    t = p.get(f"{pre}_time_s")
    return {"t_f_days": None if t is None else t / DAY_S, "fuel_kg": p.get(f"{pre}_fuel_kg"),
            "max_comp_fraction": p.get(f"{pre}_max_comp_fraction"), "converged": True if t else None}


def _f(value: float | None, fmt: str) -> str:
    return "-" if value is None or (isinstance(value, float) and not math.isfinite(value)) else format(value, fmt)


def report_lines(scenario: RendezvousScenario, doc: dict[str, Any]) -> list[str]:
    """Table I (min-time) or Table II (min-fuel) of the paper, this run's column beside the paper's."""
    strategy, perturbed = doc["strategy"], doc["perturbed"]
    paper = paper_values(scenario, strategy, perturbed)
    table = "Table I" if scenario.ocp.objective == "min-time" else "Table II"
    case = ("perturbed EOMs" if perturbed else "unperturbed EOMs")
    title = (f"Starek & Kolmanovsky 2012, {table} ({scenario.name})" if scenario.paper_results
             else f"{scenario.name} (no paper figures in the scenario)")
    lines = [f"{title}: {strategy.upper()} MPC, {case}, solver {doc['solver']}, seed {doc['seed']}",
             f"  {'':34s} {'this run':>14s}" + (f" {'paper':>14s}" if scenario.paper_results else "")]

    def row(label: str, mine: str, theirs: str) -> None:   # the paper's column only when the scenario has one
        lines.append(f"  {label:34s} {mine:>14s}" + (f" {theirs:>14s}" if scenario.paper_results else ""))

    row(f"Reached {scenario.target_name}?", "yes" if doc["converged"] else f"no ({doc['reason']})",
        "-" if paper["converged"] is None else "yes")
    row("t_f - t_0 [d]", _f(doc["t_f_days"], ".2f"), _f(paper["t_f_days"], ".2f"))
    row("fuel m_0 - m_f [kg], nominal mdot", _f(doc["fuel_nominal_mdot_kg"], ".2f"), _f(paper["fuel_kg"], ".2f"))
    row("fuel m_0 - m_f [kg], truth mass", _f(doc["fuel_kg"], ".2f"), "-")
    row("max. comp. time / subinterval", _f(doc["max_comp_fraction"], ".3e"),
        _f(paper["max_comp_fraction"], ".3e"))
    row("replans / solves / failed", f"{doc['replans']} / {doc['solves']} / {doc['failed_solves']}", "-")
    row("subdivisions", str(doc["subdivisions"]), "-")
    row("solver iterations (total)", str(doc["iterations"]), "-")
    # three significant digits: a warm replan takes well under a millisecond on the host ("0 ms" before)
    row("solve time median / max [ms]", f"{doc['solve_ms']['median']:.3g} / {doc['solve_ms']['max']:.3g}", "-")
    row("final miss [km] / [m/s]", f"{doc['final_position_miss_km']:.0f} / {doc['final_velocity_miss_m_s']:.0f}",
        "-")
    ca = doc.get("closest_approach") or {}
    if ca and not doc["converged"]:
        row("closest approach [km] at [d]", f"{ca['position_miss_km']:.0f} @ {ca['t_days']:.1f}", "-")
    p = scenario.paper_results or {}
    if "open_loop_time_s" in p:
        lines.append(f"  paper's open loop (unperturbed): {p['open_loop_time_s'] / DAY_S:.2f} d, "
                     f"{p.get('open_loop_fuel_kg', float('nan')):.2f} kg; perturbed: not converged")
    if perturbed:
        lines.append("  fuel, nominal mdot: the paper's accounting (nominal mass flow x thrusting time; errata); truth "
                     f"mass: what the perturbed engine ({scenario.perturbations.thrust_offset_percent:+g} % thrust) "
                     "burned")
    else:
        lines.append("  fuel, nominal mdot: the paper's accounting (nominal mass flow x thrusting time); truth mass: "
                     "what the engine burned (unperturbed: nominal thrust and mass flow)")
    return lines


def run(header: ScenarioHeader, args: argparse.Namespace) -> int:
    """One closed-loop flight (module doc)."""
    from ogk_host.rendezvous.scenario import load_scenario

    scenario = load_scenario(header.path)
    if args.seed < 0:
        raise OgkInputError(f"must be >= 0, got {args.seed}", key="--seed")
    if args.max_replans is not None and args.max_replans < 1:
        raise OgkInputError(f"must be >= 1, got {args.max_replans}", key="--max-replans")
    json_path = check_output_file(args.json, "--json")
    plots_dir = check_output_dir(args.plots, "--plots") if args.plots else None
    if args.third_bodies_in_model != "scenario":
        import dataclasses
        scenario = dataclasses.replace(scenario, nmpc=dataclasses.replace(
            scenario.nmpc, third_bodies_in_model=args.third_bodies_in_model == "yes"))
    if args.paper_problem:
        from ogk_host.rendezvous.scenario import paper_problem
        scenario = paper_problem(scenario)
    if args.hessian != "scenario":
        import dataclasses
        scenario = dataclasses.replace(scenario, nmpc=dataclasses.replace(scenario.nmpc, hessian=args.hessian))
    strategy_name = args.strategy or scenario.nmpc.strategy

    from .closed_loop import fly_run
    from .guidance_base import strategy_settings
    from .guidance_factory import make_guidance

    settings = strategy_settings(scenario, strategy_name)
    session = None
    target = getattr(args, "target", "host")
    if target != "host":
        if args.solver != "kernel":
            raise OgkInputError(f"--target {target} flies the kernel's ogk_nmpc, got {args.solver!r}",
                                key="--solver")
        from ogk.sil.pil import PilSession

        from . import pil
        from .flight_config import write_flight_config
        from .kernel_guidance import kernel_config
        third = args.third_bodies_in_model
        program = pil.flight_program(   # the flight configuration of this flight's scenario
            Path(header.path), strategy_name, third,
            lambda out: write_flight_config(out, Path(header.path), scenario, strategy_name, third),
            target)
        session = PilSession(program)
        guidance: Any = pil.TargetGuidance(session, kernel_config(scenario, settings))
    else:
        guidance = make_guidance(args.solver, scenario, settings)
    remove_stale(json_path)

    def trace(rec: Any) -> None:
        print(f"  replan {rec.index:3d}  t = {rec.t_days:8.2f} d  N = {rec.nodes:2d}  miss {rec.position_miss_km:11.0f} km "
              f"{rec.velocity_miss_m_s:7.0f} m/s  plan t_f {rec.planned_t_f_days:8.2f} d  it {rec.iterations:3d}  "
              f"{rec.solve_ms:6.0f} ms{'  SUBDIVIDED' if rec.subdivided else ''}{'  FAILED' if rec.failed else ''}",
              flush=True)

    start = time.perf_counter()
    with Working(f"{scenario.name}: {strategy_name} {args.solver} closed loop") as work:
        def replanned(rec: Any) -> None:
            work.note(f"replan {rec.index}, t = {rec.t_days:.1f} d, miss {rec.position_miss_km:.3g} km")
            if args.trace:
                trace(rec)
        try:
            result = fly_run(scenario, guidance, args.perturbed, args.seed, strategy_name, args.solver,
                         max_replans=args.max_replans, progress=replanned)
            if session is not None:
                session.end_run(0)
                target_keys = session.close()[0]
        except BaseException:
            if session is not None:
                session.kill()
            raise
    wall = time.perf_counter() - start
    doc = result.to_json()
    if session is not None:     # the flight program's figures per entry point (docs/guides/pil.md)
        from ogk.sil.pil_build import file_sha256
        from ogk.sil.precision import TARGET_PRECISION
        doc.update({"target": target, "target_precision": TARGET_PRECISION[target],
                    "flight_program": file_sha256(session.program.elf),
                    **target_keys})
    doc.update({"scenario_path": str(header.path), "scenario_sha256": header.sha256,
                "objective": scenario.ocp.objective,
                "third_bodies_in_model": scenario.nmpc.third_bodies_in_model,
                "paper_problem": bool(args.paper_problem), "wall_s": wall})
    if scenario.paper_results:      # the paper's figures only for a scenario that carries them
        doc["paper"] = paper_values(scenario, strategy_name, args.perturbed)
    for line in report_lines(scenario, doc):
        print(line)
    write_atomic(json_path, json.dumps(finite_or_none(doc), indent=1) + "\n")
    print(f"wrote {json_path} (the flight took {wall:.4g} s, wall clock)")
    if plots_dir is not None:
        from .plots import write_plots
        for path in write_plots(scenario, result, Path(plots_dir)):
            print(f"wrote {path}")
    return 0 if result.converged else 1
