"""`ogk run SCENARIO` of a low-thrust transfer (the family's `run`; `ogk cases` and `ogk mpsp
apophis` are its older spellings): the kernel's MPSP on one perturbation case (--case, --param) or
on all of the paper's cases (--paper-tables), each with the fuel-optimal re-solve of the same
problem for the fuel increase (docs/guides/mpsp-cli.md).
"""
from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path
from typing import Any

from ogk_bindings.errors import OgkInputError
from ogk_host.low_thrust_transfer.scenario import FOURIER_BASES, MAX_FOURIER_ORDER
from ogk_host.scenario_file import ScenarioHeader

from ogk.sil.outputs import check_output_dir, check_output_file
from ogk.sil.report import finite_or_none

def add_run_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("--case", choices=("initial", "terminal", "thrust"), default=None)
    p.add_argument("--param", default=None,
                   help="kappa (initial), 'dx,dy,dz' in LU (terminal), eta in %% (thrust)")
    p.add_argument("--paper-tables", action="store_true", help="run the 23 cases of Tables 3, 5, 6")
    p.add_argument("--json", default=None, metavar="FILE", help="write the result(s) as JSON")
    p.add_argument("--plots", default=None, metavar="DIR", help="PNG figures (with --paper-tables)")
    p.add_argument("--basis", default=None, choices=FOURIER_BASES,
                   help="Fourier basis (printed, period_tf, period_2tf, cosine_2tf; default: scenario)")
    p.add_argument("--order", type=int, default=None, help="Fourier order (default: scenario, 15)")
    p.add_argument("--reference-dir", default=None,
                   help="cache of the fuel-optimal re-solves (default: reference/ in the scenario's "
                        "product directory build/tables/<name>-<sha12>)")
    p.add_argument("--reference-timeout", type=float, default=900.0, metavar="S",
                   help="wall-time limit of one ground re-solve (s; 0 = none; default 900)")
    p.add_argument("--no-reference", action="store_true",
                   help="skip the fuel-optimal re-solves (no FI)")


def run(header: ScenarioHeader, args: argparse.Namespace) -> int:
    """One MPSP case, or the paper's cases with --paper-tables; exit 1 when one fails [acceptance]."""
    from ogk.missions.low_thrust_transfer.cases import check_param
    from ogk_host.low_thrust_transfer.scenario import load_scenario
    args.scenario = str(header.path)
    load_scenario(header.path)           # every bad key, before anything is computed
    if args.case and args.param is not None:
        check_param(args.case, args.param)
    if args.reference_timeout is not None and not args.reference_timeout >= 0.0:
        raise OgkInputError(f"must be >= 0, got {args.reference_timeout}", key="--reference-timeout")
    if args.json:
        check_output_file(args.json, "--json")
    if args.plots:
        check_output_dir(args.plots, "--plots")
    if args.order is not None and not 1 <= args.order <= MAX_FOURIER_ORDER:
        raise OgkInputError(f"must be in 1..{MAX_FOURIER_ORDER} (the kernel's OGK_MPSP_MAX_ORDER), "
                            f"got {args.order}", key="--order")
    return _run(args)


def _write_json(path: str, doc: Any) -> None:
    out = Path(path)
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text(json.dumps(finite_or_none(doc), indent=1, allow_nan=False) + "\n")
    print(f"wrote {out}")


def _reference(setup: Any, case: Any, args: argparse.Namespace) -> Any:
    """Cached/fresh fuel-optimal reference, or None (skipped or the ground solver failed)."""
    from ogk.missions.low_thrust_transfer.reference import load_or_solve
    if args.no_reference:
        return None
    ref_dir = Path(args.reference_dir) if args.reference_dir else setup.product_dir / "reference"
    try:
        return load_or_solve(setup, case, ref_dir,
                             args.reference_timeout if args.reference_timeout > 0 else None)
    except RuntimeError as err:  # ShootingFailure
        print(f"  {case.label}: no fuel-optimal reference ({err})", file=sys.stderr)
        return None


def run_one(args: argparse.Namespace) -> int:
    from ogk.missions.low_thrust_transfer.cases import build_setup, make_case, fly_run
    from ogk.missions.low_thrust_transfer.report import header, make_record, table_line
    setup = build_setup(args.basis, args.order, args.scenario)
    case = make_case(setup, args.case, args.param)
    res, cpu = fly_run(setup, case)
    start = time.perf_counter()
    ref = _reference(setup, case, args)
    rec = make_record(setup, res, cpu, ref)
    print(header(False))                      # one case of our own: no paper row to compare with
    print(table_line(case, rec, None, ref, paper_columns=False))
    if ref is not None:
        print(f"fuel-optimal reference: final mass {ref.final_mass_kg:.4f} kg, {ref.thrust_arcs} thrust "
              f"arcs, {'cached' if ref.from_cache else 'solved'} "
              f"({ref.solve_s:.1f} s solve, {time.perf_counter() - start:.1f} s here)")
    if args.json:
        _write_json(args.json, rec.to_json())
    failure = judge(setup, rec)
    if failure:
        print(f"ogk run: {case.label}: FAILED: {failure}", file=sys.stderr)
        return 1
    return 0


def judge(setup: Any, rec: Any) -> str:
    """Why a case fails the scenario's [acceptance] ("" when it passes): MPSP converged, terminal
    errors within position_error_km / velocity_error_km_s (the family's judge in `ogk mc`)."""
    acc = setup.scenario.acceptance
    if not rec.converged:
        return "MPSP did not converge"
    if not rec.dr_f_km <= acc.position_error_km:
        return f"tolerance: |dr_f| = {rec.dr_f_km:.4g} km > {acc.position_error_km:.4g} ([acceptance])"
    if not rec.dv_f_kmps <= acc.velocity_error_km_s:
        return (f"tolerance: |dv_f| = {rec.dv_f_kmps:.4g} km/s > {acc.velocity_error_km_s:.4g} "
                "([acceptance])")
    return ""


def run_tables(args: argparse.Namespace) -> int:
    from ogk.missions.low_thrust_transfer.cases import build_setup, paper_cases, fly_run
    from ogk.missions.low_thrust_transfer.report import header, make_record, paper_rows, table_line
    setup = build_setup(args.basis, args.order, args.scenario)
    cases = paper_cases(setup)
    papers = paper_rows(setup, cases)
    with_paper = any(p is not None for p in papers)   # only a scenario with [paper_results]
    print(f"MPSP (kernel) on the {len(cases)} cases of {setup.scenario.path.name}'s [dispersions]: basis "
          f"{setup.basis}, order {setup.order}"
          + ("; paper = Wang & Topputo 2020, Tables 3, 5, 6 (MPSP-CT: MATLAB+MEX, i7-9750H)"
             if with_paper else ""))
    print(header(with_paper))
    runs = []
    records = []
    failures: list[str] = []
    ref_wall = 0.0
    for case, paper in zip(cases, papers):
        res, cpu = fly_run(setup, case)
        start = time.perf_counter()
        ref = _reference(setup, case, args)
        ref_wall += time.perf_counter() - start
        rec = make_record(setup, res, cpu, ref)
        print(table_line(case, rec, paper, ref, paper_columns=with_paper), flush=True)
        failure = judge(setup, rec)
        if failure:
            failures.append(f"{case.label}: {failure}")
        runs.append((case, res, ref))
        records.append({"case": case.label, "kind": case.kind,
                        "param": list(case.param) if isinstance(case.param, tuple) else case.param,
                        **rec.to_json(),
                        "reference_final_mass_kg": ref.final_mass_kg if ref else None,
                        "reference_thrust_arcs": ref.thrust_arcs if ref else None,
                        "reference_solve_s": ref.solve_s if ref else None,
                        "paper": None if paper is None else vars(paper)})
    n_conv = sum(1 for r in records if r["converged"])
    refs = [r for _, _, r in runs if r is not None]
    print(f"{n_conv}/{len(records)} converged; kernel CPU total "
          f"{sum(float(r['cpu_s']) for r in records):.2f} s")
    if not args.no_reference:
        solved = [r for r in refs if not r.from_cache]
        print(f"fuel-optimal references: {len(refs)}/{len(records)} available, "
              f"{len(solved)} solved now, {len(refs) - len(solved)} from cache (*) in "
              f"{args.reference_dir or setup.product_dir / 'reference'}; ground solve times (s, as recorded) total "
              f"{sum(r.solve_s for r in refs):.1f}, max {max((r.solve_s for r in refs), default=0.0):.1f}; "
              f"this run spent {ref_wall:.1f} s on references")
    if args.json:
        _write_json(args.json, {"basis": setup.basis, "order": setup.order, "cases": records})
    if args.plots:
        from ogk.missions.low_thrust_transfer.plots import write_plots
        for p in write_plots(setup, runs, Path(args.plots)):
            print(f"wrote {p}")
    for line in failures:
        print(f"ogk run: FAILED: {line}", file=sys.stderr)
    return 0 if not failures else 1


def _run(args: argparse.Namespace) -> int:
    if args.paper_tables:
        if args.case or args.param is not None:
            print("ogk cases: --paper-tables runs all cases; drop --case/--param", file=sys.stderr)
            return 2
        return run_tables(args)
    if not args.case or args.param is None:
        print("ogk cases: give --case and --param, or --paper-tables", file=sys.stderr)
        return 2
    if args.plots:
        print("ogk cases: --plots needs --paper-tables", file=sys.stderr)
        return 2
    try:
        return run_one(args)
    except ValueError as err:
        print(f"ogk cases: {err}", file=sys.stderr)
        return 2
