"""The proximity-approach family (ogk.sil.family.MissionFamily): a planar approach in the target's Hill
frame to a hold point reached at rest, round keep-out discs, by the receding-horizon NMPC of the kernel's
second problem (ogk_prox_*, kernel/include/ogk/proximity.h; docs/design/nmpc-problem.md) against a two-body truth
(truth.py). `ogk run` flies it once with its plots; `ogk mc` flies it on dispersed starts, engines and
thrust-angle noise streams: run i draws from its own stream (ogk.sil.seeds), a new guidance per run, all
from the same ground plan (ogk_host.proximity.ocp.solve from the nominal start, made when the plan is
built: its SHA-256 is the campaign's product). No ground tables. On a target (--target m7) every replan
is the NMPC flight program's, on this problem (pil.py); the truth, the noise and the judging stay on the host.

Laws: --solver kernel (the flight code, through ogk_bindings.proximity: built on branch prox-kernel) or
--solver ipopt (its ground peer: IPOPT on the same transcription, ground_peer.py).

Acceptance ([acceptance], ogk_host.proximity.scenario.Acceptance): the flight flies its last plan to
the end, where the truth is within the box about the hold point in position and velocity; the truth
never enters a keep-out disc (the truth's radius; the plans keep [guidance] keepout_margin_m more);
no more propellant burnt than propellant_kg."""
from __future__ import annotations

import argparse
import dataclasses
import hashlib
import json
import math
import time
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np
from ogk_bindings.errors import OgkInputError
from ogk_host.proximity.scenario import LAWS, Acceptance, ProximityScenario, load_scenario
from ogk_host.scenario_file import ScenarioHeader, file_sha256

from ogk.sil.dispersion_check import scenario_table
from ogk.sil.engine import Flown
from ogk.sil.family import CampaignPlan, ChunkFlight, Detail, FamilyDefaults, Record, per_run
from ogk.sil.pil import FlightProgram

from .dispersions import declared, draw_records
from .dispersions import flown as flown_sigmas
from .guidance import SOLVERS, Plan, ground_plan, kernel_available

QUANTITIES = ("miss_m", "miss_velocity_m_s", "fuel_kg", "delta_v_m_s", "keepout_clearance_m", "t_f_s",
              "failed_solves")
RESULTS = ("completed", "reason", "t_f_s", "hold_error_x_m", "hold_error_y_m", "hold_error_vx_m_s",
           "hold_error_vy_m_s", "miss_m", "miss_velocity_m_s", "fuel_kg", "delta_v_m_s",
           "keepout_clearance_m", "replans", "solves", "failed_solves")


def judge(acc: Acceptance, rec: Mapping[str, Any]) -> str:
    """"" or why the flight fails the scenario's [acceptance] (module doc)."""
    if not rec.get("completed"):
        return f"not completed: {rec.get('reason')}"
    c = rec["keepout_clearance_m"]
    if not c >= 0.0:
        return f"keep-out: entered a disc by {-c:.3g} m"
    for k in ("hold_error_x_m", "hold_error_y_m"):
        if not abs(rec[k]) <= acc.hold_position_box_m:
            return f"tolerance: |{k[11]} - {k[11]}_h| = {abs(rec[k]):.3g} m > {acc.hold_position_box_m:g}"
    for k in ("hold_error_vx_m_s", "hold_error_vy_m_s"):
        if not abs(rec[k]) <= acc.hold_velocity_box_m_s:
            return f"tolerance: |{k[11:13]}| = {abs(rec[k]):.3g} m/s > {acc.hold_velocity_box_m_s:g}"
    if acc.propellant_kg is not None and not rec["fuel_kg"] <= acc.propellant_kg:
        return f"propellant: {rec['fuel_kg']:.4g} kg > {acc.propellant_kg:g}"
    return ""


def badness(acc: Acceptance, rec: Mapping[str, Any]) -> float:
    """How close a run came to failing: the largest of its errors over their tolerances, the keep-out's
    (> 1: failed; inf: did not complete, or entered a disc)."""
    if not rec.get("completed"):
        return math.inf
    return max(abs(rec["hold_error_x_m"]) / acc.hold_position_box_m,
               abs(rec["hold_error_y_m"]) / acc.hold_position_box_m,
               abs(rec["hold_error_vx_m_s"]) / acc.hold_velocity_box_m_s,
               abs(rec["hold_error_vy_m_s"]) / acc.hold_velocity_box_m_s,
               rec["fuel_kg"] / acc.propellant_kg if acc.propellant_kg else 0.0,
               math.inf if rec["keepout_clearance_m"] < 0.0 else 0.0)


def plan_sha256(p: Plan) -> str:
    h = hashlib.sha256()
    for a in (np.array([p.t0, p.horizon]), p.states, p.controls):
        h.update(np.ascontiguousarray(a, dtype=np.float64).tobytes())
    return h.hexdigest()


@dataclasses.dataclass(frozen=True)
class _Base:
    scenario: ProximityScenario
    first: Plan


def _solver(options: Mapping[str, Any]) -> str:
    solver = str(options.get("solver") or "kernel")
    if solver not in SOLVERS:
        raise OgkInputError(f"one of {', '.join(SOLVERS)}, got {solver!r}", key="--solver")
    if solver == "kernel" and not kernel_available():
        raise OgkInputError("the kernel's ogk_prox_* have no bindings yet (ogk_bindings.proximity, branch "
                            "prox-kernel): fly its ground peer with --solver ipopt", key="--solver")
    return solver


class ProximityFamily(FamilyDefaults):
    name = "proximity-approach"
    laws = LAWS
    campaign_doc = ("closed-loop NMPC approaches to the hold point from dispersed starts, engines and "
                    "thrust-angle noise streams (run i: its own stream); judged by the scenario's "
                    "[acceptance] (the hold box, the keep-out in the truth, the propellant)")

    def load(self, header: ScenarioHeader) -> ProximityScenario:
        return load_scenario(header.path)

    def add_campaign_arguments(self, parser: argparse.ArgumentParser) -> None:
        parser.add_argument("--solver", choices=SOLVERS, default="kernel",
                            help="kernel: the flight code's ogk_prox (default); ipopt: its ground peer")
        parser.add_argument("--unperturbed", action="store_true",
                            help="no dispersions (every run is then the same flight)")

    def plan(self, header: ScenarioHeader, options: Mapping[str, Any]) -> CampaignPlan:
        from .closed_loop import fly

        scenario = self.load(header)
        solver = _solver(options)
        perturbed = not bool(options.get("unperturbed"))
        first = ground_plan(scenario)

        def fly_one(run_id: int, run_seed: int) -> Record:
            start = time.perf_counter()
            try:
                rec = fly(scenario, solver, first, run_seed, perturbed).record()
            except RuntimeError as err:     # the truth integration stopped
                rec = {**dict.fromkeys(RESULTS), "completed": False, "reason": f"truth: {err}"}
            rec["timing.wall_s"] = time.perf_counter() - start
            return rec

        def detail(run_id: int, run_seed: int, plots: Path | None) -> Detail:
            r = fly(scenario, solver, first, run_seed, perturbed)
            files: tuple[Path, ...] = ()
            if plots is not None:
                from .plots import write_flight_plots
                files = tuple(write_flight_plots(scenario, r, plots, f"run{run_id}"))
            return Detail(r.record(), files)

        acc = scenario.acceptance
        campaign = CampaignPlan(
            family=self.name, law=header.law, mission=scenario.name, scenario_path=Path(header.path),
            scenario_sha256=file_sha256(header.path),
            options={"solver": solver, "unperturbed": not perturbed},
            products={"ground_plan": plan_sha256(first)}, fly=per_run(fly_one),
            judge=lambda rec: judge(acc, rec), quantities=QUANTITIES,
            acceptance={"hold": "the truth at the end of the last plan within the box about the hold point; "
                                "never inside a keep-out disc", **dataclasses.asdict(acc)},
            detail=detail, watchdog_per_run_s=300.0, base=_Base(scenario, first),
            dispersions=declared(scenario, scenario_table(header.path), perturbed),
            draw=lambda ids, seeds: draw_records(flown_sigmas(scenario.dispersions, perturbed), ids, seeds))
        if options.get("target", "host") != "host":
            self.on_target(campaign, str(options["target"]))
        return campaign

    # ------------------------------------------------------------------ on a target
    # the replans made by the NMPC flight program on this problem (pil.py); the truth, the noise and
    # the judging stay on the host
    targets = ("host", "m7", "m4f")
    target_watchdog_per_run_s = 1800.0

    def flight_config(self, plan: CampaignPlan, out_dir: Path) -> list[Path]:
        """The solver's settings, the problem's data and the ground plan as const C."""
        from .flight_config import write_flight_config
        return [write_flight_config(out_dir, plan.scenario_path, plan.base.scenario, plan.base.first)]

    def flight_program(self, plan: CampaignPlan, target: str) -> FlightProgram:
        from . import pil
        if plan.options["solver"] != "kernel":
            raise OgkInputError(f"--target {target} flies the kernel's ogk_prox problem, got "
                                f"{plan.options['solver']!r}", key="--solver")
        if target not in self.targets or target == "host":
            raise OgkInputError(f"one of {', '.join(self.targets[1:])}, got {target!r}", key="--target")
        return pil.flight_program(plan.scenario_path, lambda out: self.flight_config(plan, out), target)

    def target_job(self, plan: CampaignPlan, program: FlightProgram) -> ChunkFlight:
        from . import pil
        return pil.TargetJob(plan.base.scenario, plan.base.first, not bool(plan.options["unperturbed"]),
                             program, RESULTS)

    def target_bounds(self, plan: CampaignPlan) -> tuple[dict[str, float], str]:
        from . import pil
        return pil.target_bounds(plan.base.scenario), pil.BOUNDS_WHY

    def report(self, flown: Flown) -> tuple[str, dict[str, Any]]:
        plan = flown.plan
        scn: ProximityScenario = plan.base.scenario
        acc = scn.acceptance
        recs = flown.records
        lost = [r for r in recs if r["failure"]]
        ok = [r for r in recs if r.get("completed")]
        worst = max(recs, key=lambda r: badness(acc, r))
        med = {k: float(np.median([r[k] for r in ok])) if ok else None
               for k in ("miss_m", "miss_velocity_m_s", "fuel_kg", "keepout_clearance_m", "t_f_s")}
        lines = [f"{plan.mission}: {plan.options['solver']} "
                 f"{'unperturbed' if plan.options['unperturbed'] else 'dispersed'}: "
                 f"lost {len(lost)} of {len(recs)} runs"]
        for r in lost:
            lines.append(f"  lost run {r['run_id']}: {r['failure']}")
        lines.append(f"  worst run {worst['run_id']} ({badness(acc, worst):.3g} of its tolerances): "
                     f"|dx| {_f(worst.get('hold_error_x_m'), '.3g', abs)} m, "
                     f"|dy| {_f(worst.get('hold_error_y_m'), '.3g', abs)} m, "
                     f"|dvx| {_f(worst.get('hold_error_vx_m_s'), '.3g', abs)} m/s, "
                     f"|dvy| {_f(worst.get('hold_error_vy_m_s'), '.3g', abs)} m/s, "
                     f"clearance {_f(worst.get('keepout_clearance_m'), '.3g')} m, "
                     f"propellant {_f(worst.get('fuel_kg'), '.4g')} kg")
        if ok:
            lines.append(f"  median: miss {med['miss_m']:.3g} m, {med['miss_velocity_m_s']:.3g} m/s; propellant "
                         f"{med['fuel_kg'] * 1e3:.1f} g; t_f {med['t_f_s']:.0f} s; least keep-out clearance "
                         f"{min(r['keepout_clearance_m'] for r in ok):.3g} m")
        lines.append("  run  done  miss [m]  miss [mm/s]  fuel [g]  clear [m]  t_f [s]  replans  failed")
        for r in recs:
            lines.append(f"  {r['run_id']:3d}  {'yes' if r.get('completed') else 'NO ':4s}  "
                         f"{_f(r.get('miss_m'), '8.3f')}  {_f(_scaled(r.get('miss_velocity_m_s'), 1e3), '11.3f')}  "
                         f"{_f(_scaled(r.get('fuel_kg'), 1e3), '8.2f')}  {_f(r.get('keepout_clearance_m'), '9.2f')}  "
                         f"{_f(r.get('t_f_s'), '7.0f')}  {_f(r.get('replans'), '7d')}  {_f(r.get('failed_solves'), '6d')}")
        extra = {"lost_runs": len(lost), "worst_run": int(worst["run_id"]),
                 "medians": med}
        return "\n".join(lines), extra

    def plots(self, flown: Flown, out_dir: Path) -> list[Path]:
        from .plots import campaign_figure, write_flight_plots
        from ogk.sil.plots import save
        scn: ProximityScenario = flown.plan.base.scenario
        out_dir.mkdir(parents=True, exist_ok=True)
        files = [save(campaign_figure(scn, flown.records, f"{scn.name}: final errors at the hold point"),
                      out_dir / "hold_errors.png")]
        worst = max(flown.records, key=lambda r: badness(scn.acceptance, r))
        detail = flown.plan.detail
        if detail is not None:       # the worst run flown again with its histories
            files += list(detail(int(worst["run_id"]), int(worst["run_seed"]), out_dir).files)
        return files

    # ------------------------------------------------------------------ ogk run
    def add_run_arguments(self, parser: argparse.ArgumentParser) -> None:
        parser.add_argument("--solver", choices=SOLVERS, default="kernel",
                            help="kernel: the flight code's ogk_prox (default); ipopt: its ground peer")
        parser.add_argument("--dispersed", action="store_true", help="draw the [dispersions] from --seed")
        parser.add_argument("--seed", type=int, default=1, help="the run's stream (default 1)")
        parser.add_argument("--json", default=None, metavar="FILE", help="write the record as JSON")
        parser.add_argument("--plots", default=None, metavar="DIR", help="PNG: trajectory, throttle")

    def run(self, header: ScenarioHeader, args: argparse.Namespace) -> int:
        """`ogk run SCENARIO`: one closed-loop approach; exit 0 when it meets [acceptance], 1 when not."""
        from ogk.sil.outputs import check_output_dir, check_output_file, write_atomic
        from ogk.sil.report import finite_or_none

        from .closed_loop import fly
        from .plots import write_flight_plots
        scenario = self.load(header)
        solver = _solver({"solver": args.solver})
        json_path = check_output_file(args.json, "--json") if args.json else None
        plots = check_output_dir(args.plots, "--plots") if args.plots else None
        first = ground_plan(scenario)
        r = fly(scenario, solver, first, int(args.seed), bool(args.dispersed))
        rec = r.record()
        why = judge(scenario.acceptance, rec)
        print(f"{scenario.name}: {solver}, {'dispersed (seed ' + str(args.seed) + ')' if args.dispersed else 'nominal'}: "
              f"{r.reason} at t = {r.t_f_s:.0f} s after {len(r.replans)} replans; hold error "
              f"({rec['hold_error_x_m']:.3g}, {rec['hold_error_y_m']:.3g}) m, "
              f"({rec['hold_error_vx_m_s']:.3g}, {rec['hold_error_vy_m_s']:.3g}) m/s; propellant "
              f"{r.fuel_kg * 1e3:.2f} g (Delta v {r.delta_v_m_s:.4f} m/s); keep-out clearance "
              f"{r.keepout_clearance_m:.3g} m; {'PASS' if not why else 'FAIL: ' + why}")
        if json_path is not None:
            write_atomic(json_path, json.dumps(finite_or_none({**rec, "failure": why}), indent=1) + "\n")
        if plots is not None:
            for f in write_flight_plots(scenario, r, plots):
                print(f"  {f}")
        return 0 if not why else 1


def _scaled(v: Any, k: float) -> Any:
    return None if v is None else v * k


def _f(value: Any, fmt: str, fn: Any = None) -> str:
    if value is None or (isinstance(value, float) and not math.isfinite(value)):
        return "-"
    return format(fn(value) if fn else value, fmt)


FAMILY = ProximityFamily()
