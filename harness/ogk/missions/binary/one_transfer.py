"""`ogk run SCENARIO --transfer NAME --json FILE [--plots DIR]` of a binary-asteroid scenario (the
family's `run`; `ogk blt` is its older spelling): one transfer: the ground's initial guess, the
flight kernel's corrector in the realistic model, the independent DOP853 re-propagation of the
result, the paper's figures beside it. Exit 0 when the kernel converged and DOP853 confirms the
tolerance, 1 when not, 2 on bad input.
"""
from __future__ import annotations

import argparse
import dataclasses
import json
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np
from ogk_host.binary import transfers as T
from ogk_host.binary.orbits import CorrectionError, scenario_orbit
from ogk_host.binary.scenario import BinaryScenario, load_scenario
from ogk_bindings.errors import OgkInputError
from ogk_host.scenario_file import ScenarioHeader

from ogk.sil.pil import FlightProgram
from ogk.sil.outputs import check_output_dir, check_output_file, remove_stale, write_atomic
from ogk.sil.report import finite_or_none
from ogk.sil.progress import Working


def _scenario(header: ScenarioHeader) -> BinaryScenario:
    return load_scenario(header.path)


def add_run_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("--transfer", required=True, metavar="NAME", help="a [transfers.NAME] of the scenario")
    p.add_argument("--json", required=True, metavar="FILE", help="write the result as JSON")
    p.add_argument("--plots", default=None, metavar="DIR", help="PNG figures (synodic frame, C_J and control)")
    p.add_argument("--corrector", choices=("scenario", "nrpc", "lm", "hybrid"), default="scenario",
                   help="nrpc (eq. 64), lm (damped) or hybrid (eq. 64, LM when its search fails); default: the "
                        "scenario's [solver] corrector")
    p.add_argument("--jacobian", choices=("scenario", "variational", "central"), default="scenario",
                   help="variational equations or central differences (eq. 62); default: the scenario's")
    p.add_argument("--thrust-n", type=float, default=None, metavar="F",
                   help="fly the transfer at this thrust [N] instead of its thrust_n (a thrust sweep)")
    p.add_argument("--target", choices=("host", "m7", "m4f"), default="host",
                   help="m7: every corrector solve of the design made by the scenario's flight program "
                        "on the emulated Cortex-M7 (docs/guides/flight-integration-blt.md); m4f: on the "
                        "Cortex-M4F with the single-precision kernel; default host")


def blt_document(scenario: BinaryScenario, name: str, corrector: str | None, jacobian: str | None,
                 thrust_n: float | None = None) -> dict[str, Any]:
    from .trajectory import reference_errors
    solver = T.solver_settings(scenario)
    spec = T.transfer_spec(scenario, name)
    base_thrust = spec.thrust_n
    if thrust_n is not None:
        spec = dataclasses.replace(spec, thrust_n=thrust_n, paper={})   # the paper's figures are for its thrust
    cpu0 = time.process_time()
    with Working(f"{scenario.name}: {name}: guess, continuation and correction"):
        try:
            d = T.design(scenario, spec, solver, corrector=corrector, jacobian=jacobian,
                         base_thrust_n=base_thrust)
        except CorrectionError as exc:      # an orbit or a guess that cannot be built: one line, exit 2
            raise OgkInputError(str(exc), path=scenario.path, key=f"transfers.{name}") from exc
    cpu = time.process_time() - cpu0
    ref = reference_errors(d.model, d.guess.layout, d.transfer)
    accept_tol = scenario.acceptance.tolerance(solver.tol)   # [acceptance], default the [solver] tol
    fig = T.figures(scenario, d)
    rep = d.report
    u = scenario.units
    doc: dict[str, Any] = dict(
        scenario=scenario.name, transfer=name, kind=spec.kind, thrust_n=spec.thrust_n,
        corrector=corrector or solver.corrector, jacobian=jacobian or solver.jacobian, tol=solver.tol,
        converged=rep.converged, status=rep.status, flags=rep.flag_names(), iterations=rep.iterations,
        propagations=rep.propagations, continuation=d.result.steps,
        initial_error=rep.err_norm0,
        final_error_dop853=ref.err_norm, acceptance_tol=accept_tol,
        dop853_meets_tol=bool(ref.err_norm <= accept_tol and not ref.impact),
        **fig, guess_cpu_s=d.guess_s, kernel_solve_wall_s=d.solve_s, total_cpu_s=cpu,
        guess=dict(segments=d.guess.transfer.segments.tolist(), info=d.guess.info),
        solution=dict(t0=d.transfer.t0, x0=d.transfer.x0.tolist(), xf=d.transfer.xf.tolist(),
                      segments=d.transfer.segments.tolist(), nodes=d.transfer.nodes.tolist(),
                      kinds=list(d.guess.layout.kinds), free_nodes=list(d.guess.layout.free_nodes),
                      meets=list(d.guess.layout.meets)),
        units=dict(length_m=u.length_m, time_s=u.time_s, velocity_m_s=u.velocity_m_s),
        paper={k: v for k, v in spec.paper.items()})
    return doc


def report_lines(doc: dict[str, Any]) -> list[str]:
    """This run's figures, the paper's column beside them only when the scenario has the transfer's
    [paper_results.transfers.NAME]."""
    p = doc["paper"]
    lines = [f"Xiong & Wang, {doc['scenario']} / {doc['transfer']} ({doc['kind']}, {doc['thrust_n'] * 1e3:g} mN, "
             f"corrector {doc['corrector']}, Jacobian {doc['jacobian']})",
             f"  {'':34s} {'this run':>16s}" + (f" {'paper':>12s}" if p else "")]

    def row(label: str, mine: str, theirs: str = "-") -> None:
        lines.append(f"  {label:34s} {mine:>16s}" + (f" {theirs:>12s}" if p else ""))
    row("converged (|e| <= tol)", f"{'yes' if doc['converged'] else 'no: ' + doc['status']}")
    row("iterations", str(doc["iterations"]), f"{p['iterations']:g}" if "iterations" in p else "-")
    row("final |e| kernel / DOP853", f"{doc['final_error']:.2e} / {doc['final_error_dop853']:.2e}")
    row("burn time [min]", f"{doc['burn_time_s'] / 60:.1f}",
        f"{p['burn_time_s'] / 60:.1f}" if "burn_time_s" in p else "-")
    row("flight time [min]", f"{doc['flight_time_s'] / 60:.1f}",
        f"{p['flight_time_s'] / 60:.1f}" if "flight_time_s" in p else "-")
    row("fuel [g]", f"{doc['fuel_g']:.2f}", f"{p['fuel_g']:.2f}" if "fuel_g" in p else "-")
    row("delta-v [m/s]", f"{doc['delta_v_m_s']:.4f}")
    row("closest approach Alpha / Beta [m]", f"{doc['closest_approach_m'][0]:.0f} / {doc['closest_approach_m'][1]:.0f}")
    row("kernel solve wall [ms]", f"{doc['kernel_solve_wall_s'] * 1e3:.1f}")
    return lines


def run(header: ScenarioHeader, args: argparse.Namespace,
        target_program: Callable[[], FlightProgram] | None = None) -> int:
    """One transfer (module doc); with --target m7 every corrector solve on `target_program()`
    (the family's: the flight program its `ogk mc --target m7` flies)."""
    scenario = _scenario(header)
    out = check_output_file(args.json, "--json")
    plots = check_output_dir(args.plots, "--plots") if args.plots else None
    T.transfer_spec(scenario, args.transfer)      # bad names are input errors before any work
    remove_stale(out)
    corrector = None if args.corrector == "scenario" else args.corrector
    jacobian = None if args.jacobian == "scenario" else args.jacobian
    if args.thrust_n is not None and not args.thrust_n > 0.0:
        raise OgkInputError("must be > 0", key="--thrust-n")
    if getattr(args, "target", "host") != "host":
        if target_program is None:
            raise OgkInputError("this transfer has no flight program to fly on", key="--target")
        doc = _blt_on_target(target_program(), scenario, args.transfer, corrector, jacobian,
                             args.thrust_n)
    else:
        doc = blt_document(scenario, args.transfer, corrector, jacobian, args.thrust_n)
    if plots is not None:
        doc["plots"] = [str(p) for p in _transfer_plots(scenario, doc, plots)]
    write_atomic(out, json.dumps(finite_or_none(doc), indent=1, allow_nan=False))
    print("\n".join(report_lines(doc)))
    if "target_solves" in doc:
        pil = doc["pil"]
        print(f"  on the target ({doc['target']}): {len(doc['target_solves'])} solve(s), iterations "
              + ", ".join(str(s["iterations"]) for s in doc["target_solves"])
              + f"; ogk_blt_solve max {pil.get('pil.ogk_blt_solve.insn_max')} instructions, "
              f"stack {pil.get('pil.ogk_blt_solve.stack_bytes')} B")
    return 0 if doc["converged"] and doc["dop853_meets_tol"] else 1


def _blt_on_target(program: FlightProgram, scenario: BinaryScenario, name: str, corrector: str | None,
                   jacobian: str | None, thrust_n: float | None) -> dict[str, Any]:
    """blt_document with every corrector solve made by the scenario's flight program (pil.py): the
    document's keys plus target, flight_program (SHA-256), target_solves and the pil.* keys."""
    from ogk.sil.pil import PilSession
    from ogk.sil.pil_build import file_sha256

    from .pil import corrections_on_target
    session = PilSession(program)
    try:
        with corrections_on_target(session) as log:
            doc = blt_document(scenario, name, corrector, jacobian, thrust_n)
        session.end_run(0)
        keys = session.close()[0]
    except BaseException:
        session.kill()
        raise
    from ogk.sil.precision import TARGET_PRECISION
    doc.update(target=program.target, target_precision=TARGET_PRECISION[program.target],
               flight_program=file_sha256(program.elf), target_solves=log, pil=keys)
    return doc


def _transfer_plots(scenario: BinaryScenario, doc: dict[str, Any], out_dir: Path) -> list[Path]:
    from ogk_bindings.blt import Transfer
    from ogk_host.binary.guess import Layout, OrbitPhase

    from .plots import transfer_figures
    from .trajectory import sample
    spec = dataclasses.replace(T.transfer_spec(scenario, doc["transfer"]), thrust_n=doc["thrust_n"])
    solver = T.solver_settings(scenario)
    model = T.corrector_model(scenario, spec, solver)
    s = doc["solution"]
    lay = Layout(kinds=tuple(s["kinds"]), free_nodes=tuple(s["free_nodes"]), meets=tuple(s["meets"]))
    tr = Transfer(t0=s["t0"], x0=np.array(s["x0"]), xf=np.array(s["xf"]), segments=np.array(s["segments"]),
                  nodes=np.array(s["nodes"]).reshape(-1, 6))
    smp = sample(model, lay, tr)
    gm = model.gravity_only()
    orbit_states = []
    for key in ("from_orbit", "to_orbit"):
        name = getattr(spec, key, None)
        if name:
            o = scenario_orbit(scenario, name, gm)
            orbit_states.append(OrbitPhase(o)(np.linspace(0.0, o.period, 400)))
    title = (f"{doc['transfer']}: {doc['thrust_n'] * 1e3:g} mN, burn {doc['burn_time_s'] / 60:.1f} min, "
             f"fuel {doc['fuel_g']:.2f} g, {'converged' if doc['converged'] else 'NOT converged'}")
    return transfer_figures(doc["transfer"], model, smp, orbit_states, scenario.units.length_m,
                            scenario.units.time_s, out_dir, title)
