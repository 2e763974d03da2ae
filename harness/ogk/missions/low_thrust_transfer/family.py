"""The low-thrust transfer family (ogk.sil.family.MissionFamily): the kernel's MPSP re-planned on
perturbed problems (Wang & Topputo 2020, sec. 4). `ogk tables` makes the fuel-optimal nominal and
the flight configuration (ground_tables.py), `ogk run` flies one case or the paper's list
(one_case.py; `ogk cases` is its older spelling), `ogk mc` the campaign below; on a target the
solves are the flight program's (pil.py).

Two campaigns:
  --cases dispersed (default)  run i perturbs one thing, kind i mod 3 (initial state, target,
                               thrust), by a value drawn uniformly from its own stream within the
                               range of the scenario's [dispersions] (kappa in [min, max], the
                               target offset inside the cube, eta in [min, max]);
  --cases paper                run i is case i of the scenario's [dispersions] as listed (Tables 3,
                               5, 6: 23 runs, no draw), the paper's columns beside ours when the
                               scenario has [paper_results].
With --reference, each run also gets the fuel-optimal re-solve of the same problem (cached) and
its fuel increase FI. Each record carries the perturbation as the solve was given it (disp.*,
dispersions.py).

Acceptance: MPSP converged, and its terminal errors within the scenario's [acceptance]
(`scenario.acceptance`: position_error_km, velocity_error_km_s; default the [mpsp] tolerances
tol_position_km, tol_velocity_km_s).
"""
from __future__ import annotations

import argparse
import dataclasses
import hashlib
import json
from collections.abc import Callable, Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np
from ogk_bindings.errors import OgkInputError
from ogk_host.low_thrust_transfer.scenario import FOURIER_BASES, LAWS, MAX_FOURIER_ORDER, load_scenario
from ogk_host.scenario_file import ScenarioHeader, file_sha256

from ogk.sil.dispersion_check import scenario_table
from ogk.sil.engine import Flown
from ogk.sil.family import CampaignPlan, ChunkFlight, FamilyDefaults, Record, per_run
from ogk.sil.pil import FlightProgram
from ogk.sil.seeds import run_generator

from .cases import KINDS, MpspSetup, Case, build_setup, initial_case, paper_cases, fly_run
from .cases import terminal_case, thrust_case
from .dispersions import applied_record, declared
from .pil import SOLVE_TIMEOUT_S
from .report import CaseRecord, header, make_record, paper_rows, table_line

RESULTS = ("converged", "newton_iterations", "outer_steps", "dr_f_km", "dv_f_kmps", "lambda_mf",
           "final_mass_kg", "fuel_increase_pct", "thrust_arcs")


def dispersed_case(setup: MpspSetup, run_id: int, rng: np.random.Generator) -> Case:
    """Run `run_id`'s problem: kind run_id mod 3, its size drawn within the scenario's range."""
    pert = setup.scenario.dispersions
    kind = KINDS[run_id % len(KINDS)]
    if kind == "initial":
        return initial_case(setup, float(rng.uniform(min(pert.kappa), max(pert.kappa))))
    if kind == "terminal":
        lo = np.min(pert.delta_rf_vertices, axis=0)
        hi = np.max(pert.delta_rf_vertices, axis=0)
        return terminal_case(setup, rng.uniform(lo, hi), label=f"dispersed target {run_id}")
    return thrust_case(setup, float(rng.uniform(min(pert.eta_percent), max(pert.eta_percent))))


@dataclasses.dataclass(frozen=True)
class _Base:
    """What the report and the target job read of a plan (family-private)."""

    setup: MpspSetup
    papers: list[Case] | None                       #: the paper's cases (--cases paper), or None
    case_of: Callable[[int, int], Case]             #: run id, run seed -> the run's problem
    record_of: Callable[[Case, Any, float], Record]  #: a run's record from its solve


class LowThrustFamily(FamilyDefaults):
    name = "low-thrust-transfer"
    laws = LAWS
    fixed_lists = True           #: --cases paper: the number of runs is the list's
    #: --target m7 / sparc / m4f: the solves on the flight program (pil.py)
    targets = ("host", "m7", "sparc", "m4f")
    has_tables = True                   #: `ogk tables`: ground_tables.py
    run_aliases = ("cases",)     #: `ogk cases` (and `ogk mpsp apophis`): the older `ogk run`
    campaign_doc = ("MPSP re-planned on perturbed problems: --cases dispersed (run i: one "
                    "perturbation of kind i mod 3 drawn in the scenario's range) or --cases paper "
                    "(the paper's 23 cases)")

    def load(self, header: ScenarioHeader) -> Any:
        return load_scenario(header.path)

    def add_campaign_arguments(self, parser: argparse.ArgumentParser) -> None:
        parser.add_argument("--cases", choices=("dispersed", "paper"), default="dispersed",
                       help="dispersed draws (default) or the paper's 23 cases (--runs 23)")
        parser.add_argument("--basis", default=None, choices=FOURIER_BASES,
                       help="Fourier basis (printed, period_tf, period_2tf, cosine_2tf; default: "
                            "the scenario's)")
        parser.add_argument("--order", type=int, default=None, help="Fourier order (default: scenario)")
        parser.add_argument("--reference", action="store_true",
                       help="the fuel-optimal re-solve of every run's problem, for FI (cached in "
                            "--reference-dir)")
        parser.add_argument("--reference-dir", default=None,
                       help="cache of the fuel-optimal re-solves (default: reference/ in the "
                            "scenario's product directory build/tables/<name>-<sha12>)")

    def plan(self, header: ScenarioHeader, options: Mapping[str, Any]) -> CampaignPlan:
        order = options.get("order")
        if order is not None and not 1 <= int(order) <= MAX_FOURIER_ORDER:
            raise OgkInputError(f"must be in 1..{MAX_FOURIER_ORDER} (the kernel's OGK_MPSP_MAX_ORDER), "
                                f"got {order}", key="--order")
        basis = options.get("basis")
        if basis is not None and basis not in FOURIER_BASES:
            raise OgkInputError(f"must be one of {', '.join(FOURIER_BASES)}, got {basis!r}",
                                key="--basis")
        self.load(header)     # every bad key reported before the setup is built
        setup = build_setup(options.get("basis"), order, header.path)
        which = str(options.get("cases") or "dispersed")
        papers = paper_cases(setup) if which == "paper" else None
        reference = bool(options.get("reference"))
        ref_dir = (Path(str(options["reference_dir"])) if options.get("reference_dir")
                   else setup.product_dir / "reference")
        acc = setup.scenario.acceptance

        def case_of(run_id: int, run_seed: int) -> Case:
            if papers is not None:
                return papers[run_id]
            return dispersed_case(setup, run_id, run_generator(run_seed))

        def fly_one(run_id: int, run_seed: int) -> Record:
            case = case_of(run_id, run_seed)
            res, cpu = fly_run(setup, case)
            return record_of(case, res, cpu)

        def record_of(case: Case, res: Any, cpu: float) -> Record:
            """A run's record from its case and the solve's result (host or target)."""
            from .reference import load_or_solve
            ref = None
            if reference:
                try:
                    ref = load_or_solve(setup, case, ref_dir)
                except RuntimeError:          # no fuel-optimal reference: FI stays None
                    ref = None
            rec = make_record(setup, res, cpu, ref).to_json()
            out: Record = {"kind": case.kind, "label": case.label,
                           "kappa": float(case.param) if case.kind == "initial" else None,
                           "delta_rf_lu": list(case.param) if case.kind == "terminal" else None,
                           "eta_percent": float(case.param) if case.kind == "thrust" else None}
            out.update({k: rec[k] for k in RESULTS})
            out.update(applied_record(setup, case))      # what the solve was given (dispersions.py)
            out["reference_final_mass_kg"] = None if ref is None else ref.final_mass_kg
            out["timing.cpu_s"] = rec["cpu_s"]
            return out

        def judge(rec: Record) -> str:
            if not rec["converged"]:
                return "MPSP did not converge"
            if not rec["dr_f_km"] <= acc.position_error_km:
                return f"tolerance: |dr_f| = {rec['dr_f_km']:.4g} km > {acc.position_error_km:.4g}"
            if not rec["dv_f_kmps"] <= acc.velocity_error_km_s:
                return f"tolerance: |dv_f| = {rec['dv_f_kmps']:.4g} km/s > {acc.velocity_error_km_s:.4g}"
            return ""

        nominal = hashlib.sha256(json.dumps([float(x) for x in setup.nominal.lam0]).encode())
        plan = CampaignPlan(
            family=self.name, law=header.law, mission=header.name,
            scenario_path=Path(header.path), scenario_sha256=file_sha256(header.path),
            options={"cases": which, "basis": setup.basis, "order": setup.order,
                     "reference": reference, "reference_dir": str(ref_dir)},
            products={"nominal": str(setup.nominal_path), "nominal_sha256": setup.nominal_sha256,
                      "nominal_lambda0": nominal.hexdigest()},
            fly=per_run(fly_one), judge=judge,
            quantities=("newton_iterations", "dr_f_km", "dv_f_kmps", "lambda_mf",
                        "final_mass_kg", "fuel_increase_pct"),
            paper=(None if papers is None else lambda recs: self._paper(setup, papers, recs)),
            max_runs=None if papers is None else len(papers),
            acceptance={"converged": True, "dr_f_km": acc.position_error_km,
                        "dv_f_kmps": acc.velocity_error_km_s},
            watchdog_per_run_s=120.0, base=_Base(setup, papers, case_of, record_of),
            # a run is one MPSP solve (Algorithms 1-2): it failed when it did not converge
            solve_failures=lambda rec: [] if rec["converged"] else ["MPSP did not converge"],
            dispersions=declared(setup, scenario_table(header.path), which),
            draw=per_run(lambda run_id, run_seed: applied_record(setup, case_of(run_id, run_seed))))
        if options.get("target", "host") != "host":
            self.on_target(plan, str(options["target"]))
        return plan

    # ------------------------------------------------------------------ ogk tables, ogk run
    def add_tables_arguments(self, parser: argparse.ArgumentParser) -> None:
        from .ground_tables import add_tables_arguments
        add_tables_arguments(parser)

    def tables(self, header: ScenarioHeader, args: argparse.Namespace) -> int:
        """`ogk tables SCENARIO`: the fuel-optimal nominal, its manifest, the flight configuration."""
        from .ground_tables import write_ground_tables
        return write_ground_tables(header, args)

    def add_run_arguments(self, parser: argparse.ArgumentParser) -> None:
        from .one_case import add_run_arguments
        add_run_arguments(parser)

    def run(self, header: ScenarioHeader, args: argparse.Namespace) -> int:
        """`ogk run SCENARIO`: one MPSP case (--case, --param) or the paper's (--paper-tables)."""
        from .one_case import run
        return run(header, args)

    # ------------------------------------------------------------------ on a target
    # the plan's solves made by the scenario's flight program (pil.py); the cases, records and
    # judging stay the host's
    target_watchdog_per_run_s = SOLVE_TIMEOUT_S

    def flight_config(self, plan: CampaignPlan, out_dir: Path) -> list[Path]:
        """The MPSP configuration header (the nominal's weights, every [mpsp] setting)."""
        from .flight_config import write_flight_config
        return write_flight_config(out_dir, plan.scenario_path, plan.base.setup)

    def flight_program(self, plan: CampaignPlan, target: str) -> FlightProgram:
        from . import pil
        return pil.flight_program(plan.base.setup, plan.scenario_path,
                                  lambda out: self.flight_config(plan, out), target)

    def target_job(self, plan: CampaignPlan, program: FlightProgram) -> ChunkFlight:
        from . import pil
        base: _Base = plan.base
        return pil.TargetJob(base.case_of, base.record_of, program,
                             t0=float(base.setup.guidance.cfg.t0))

    def target_bounds(self, plan: CampaignPlan) -> tuple[dict[str, float], str]:
        from . import pil
        return dict(pil.BOUNDS), pil.BOUNDS_WHY

    def _paper(self, setup: MpspSetup, papers: list[Case],
               records: Sequence[Record]) -> dict[str, Any] | None:
        rows = paper_rows(setup, papers)
        if all(r is None for r in rows):
            return None
        return {"table": "Wang & Topputo 2020, Tables 3, 5, 6",
                "cases": [{"run_id": int(r["run_id"]), "case": papers[int(r["run_id"])].label,
                           "paper": None if rows[int(r["run_id"])] is None
                           else vars(rows[int(r["run_id"])]),
                           **{k: r[k] for k in RESULTS}} for r in records]}

    def report(self, flown: Flown) -> tuple[str, dict[str, Any]]:
        setup, papers = flown.plan.base.setup, flown.plan.base.papers
        rows = paper_rows(setup, papers) if papers is not None else None
        if rows is not None and all(r is None for r in rows):
            rows = None                 # no [paper_results]: no paper columns
        lines = [f"MPSP (kernel) on {flown.plan.mission}: {flown.plan.options['cases']} cases, "
                 f"basis {setup.basis}, order {setup.order}"
                 + ("; paper = Wang & Topputo 2020, Tables 3, 5, 6 (MPSP-CT: MATLAB+MEX, i7-9750H)"
                    if rows is not None else ""), header(rows is not None)]
        for r in flown.records:
            i = int(r["run_id"])
            case = papers[i] if papers is not None else _Label(str(r["label"]))
            rec = CaseRecord(**{k: r[k] for k in RESULTS}, cpu_s=float(r["timing.cpu_s"]))
            lines.append(table_line(case, rec, None if rows is None else rows[i], None,
                                    paper_columns=rows is not None))
        conv = sum(1 for r in flown.records if r["converged"])
        lines.append(f"{conv}/{len(flown.records)} converged; kernel CPU total "
                     f"{sum(float(r['timing.cpu_s']) for r in flown.records):.2f} s")
        return "\n".join(lines), {"basis": setup.basis, "order": setup.order}


class _Label:
    """What table_line reads of a case: its label."""

    def __init__(self, label: str) -> None:
        self.label = label


FAMILY = LowThrustFamily()
