"""Orbit injection (VTD-NOG guidance + CPD attitude control; Pontani & Celani 2021 is its first user).

The family's adapter for ogk.missions.registry: `ogk tables SCENARIO` (nominal, gain tables, C
images) and `ogk mc SCENARIO` (SIL Monte Carlo, 6-DOF or point-mass truth).
"""
from __future__ import annotations

import argparse
from pathlib import Path

from ogk_bindings.errors import OgkInputError
from ogk_host.orbit_injection.scenario import LAWS as SCENARIO_LAWS
from ogk_host.orbit_injection.scenario import load_scenario
from ogk_host.scenario_file import ScenarioHeader

from ogk.sil.outputs import check_output_dir, check_output_file, remove_stale

LAWS = SCENARIO_LAWS


def add_tables_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("--out", default=None, metavar="DIR",
                   help="output directory (default: build/tables/<name>-<sha12> of the scenario); "
                        "a directory that ogk did not make is never written into")


def tables(header: ScenarioHeader, args: argparse.Namespace) -> int:
    from ogk_host.cgen import write_c_table
    from ogk_host.orbit_injection import tables as ground

    from .flight_config import write_flight_config

    load_scenario(header.path)  # every bad key reported before the nominal is solved
    out = Path(args.out) if args.out else ground.default_table_dir(header.path)
    check_output_dir(out, "--out")
    manifest = ground.write_nog_tables(out, scenario_path=header.path)
    bundle = out / ground.BUNDLE_FILE
    c_path, h_path = write_c_table(bundle.read_bytes(), "ogk_nog_bundle", out / "c",
                                   header.path, note="Validate with ogk_nog_table_view() or load "
                                                     "with ogk_nog_table_load() (ogk/nog.h).")
    print(f"{header.name}: t_f* = {manifest['t_f_s']:.6f} s, "
          f"f0* = {manifest['ignition_true_anomaly_deg']:.6f} deg")
    for name, value in manifest.get("residuals", {}).items():
        print(f"  residual {name:22s} {value: .3e}")
    for entry in manifest["files"]:
        print(f"  wrote {out / entry['file']}  kind {entry['kind']}  dims {entry['dims']}  "
              f"grid {entry['grid_size']}  {entry['bytes']} bytes")
    print(f"  wrote {c_path} and {h_path.name} (flight build: const table image)")
    for path in write_flight_config(out, header.path, bundle):
        print(f"  wrote {path} (flight build: const configurations)")
    print(f"  wrote {out / 'manifest.json'}")
    return 0


def add_mc_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("--runs", type=int, required=True, help="number of runs")
    p.add_argument("--seed", type=int, required=True,
                   help="master seed >= 0 (run i: SeedSequence(seed, (i,)))")
    p.add_argument("--workers", type=int, default=1, help="parallel processes (default 1)")
    p.add_argument("--no-dispersions", action="store_true",
                   help="no dispersions: alignment errors only (Table 6 case)")
    p.add_argument("--truth", choices=("6dof", "point-mass"), default="6dof")
    p.add_argument("--guidance", choices=("nog", "nominal"), default="nog",
                   help="nog: kernel VTD-NOG; nominal: open-loop u*(t) (a reference, not guidance)")
    p.add_argument("--json", required=True, help="output JSON file")
    p.add_argument("--plots", default=None, help="directory for PNG plots")
    p.add_argument("--tables", default=None, metavar="DIR",
                   help="VTD-NOG tables to fly (default: the scenario's own directory under "
                        "build/tables, generated when missing); checked against the scenario")
    p.add_argument("--history-runs", type=int, default=50,
                   help="runs whose time histories are recorded for --plots (default 50)")
    p.add_argument("--control-rate", type=float, default=50.0, help="attitude control rate [Hz]")
    p.add_argument("--truth-substeps", type=int, default=1,
                   help="truth RK4 steps per control step (default 1: 20 ms)")
    p.add_argument("--cpd-gains", choices=("printed", "rederived"), default=None,
                   help="CPD gain set (default: the scenario's flown set)")
    p.add_argument("--cpd-pointing", choices=("body", "euler"), default="body",
                   help="CPD pitch/yaw error: body-axis (default) or eqs. 45-46 literally")
    p.add_argument("--paper-end-game", action="store_true",
                   help="fly the paper's end-game (cut-off predicted at the samples, eq. 32; "
                        "Delta t_S throughout) instead of the scenario's [guidance.end_game]")
    p.add_argument("--resume", action="store_true",
                   help="keep the runs already in <json>.runs.jsonl (same scenario, seed and "
                        "settings) and fly only the others: the result of an uninterrupted run")
    p.add_argument("--chunk-runs", type=int, default=CHUNK_RUNS, metavar="K",
                   help=f"at most K runs per chunk (default {CHUNK_RUNS}): finished chunks are "
                        "kept in <json>.runs.jsonl as they complete")
    p.add_argument("--watchdog-per-run", type=float, default=2.0, metavar="S",
                   help="a chunk without a result after 120 s + S s per run is killed and the "
                        "campaign aborted (default 2)")


CHUNK_RUNS = 250


def run_log_path(json_path: str | Path) -> Path:
    """The campaign's run log, next to its JSON: <json>.runs.jsonl."""
    p = Path(json_path)
    return p.with_name(p.name + ".runs.jsonl")


def _check_mc_args(args: argparse.Namespace) -> None:
    """Every option checked before the nominal is solved."""
    if args.runs < 1:
        raise OgkInputError(f"must be >= 1, got {args.runs}", key="--runs")
    if args.seed < 0:
        raise OgkInputError(f"must be >= 0, got {args.seed}", key="--seed")
    if args.workers < 1:
        raise OgkInputError(f"must be >= 1, got {args.workers}", key="--workers")
    if not args.control_rate > 0.0 or args.control_rate > 1.0e4:
        raise OgkInputError(f"must be in (0, 1e4] Hz, got {args.control_rate:g}", key="--control-rate")
    if args.truth_substeps < 1:
        raise OgkInputError(f"must be >= 1, got {args.truth_substeps}", key="--truth-substeps")
    if args.history_runs < 0:
        raise OgkInputError(f"must be >= 0, got {args.history_runs}", key="--history-runs")
    if args.chunk_runs < 1:
        raise OgkInputError(f"must be >= 1, got {args.chunk_runs}", key="--chunk-runs")
    if not args.watchdog_per_run > 0.0:
        raise OgkInputError(f"must be > 0 s, got {args.watchdog_per_run:g}", key="--watchdog-per-run")
    check_output_file(args.json, "--json")
    check_output_file(run_log_path(args.json), "--json")
    if args.plots:
        check_output_dir(args.plots, "--plots")


def mc(header: ScenarioHeader, args: argparse.Namespace) -> int:
    from .campaign import run_campaign
    from .guidance import NominalOpenLoopGuidance
    from .nog_guidance import KernelNogGuidance, prepare_tables
    from .report import format_report
    from .sil import SilSettings

    from ogk.sil.runner import Watchdog

    _check_mc_args(args)
    remove_stale(args.json)          # no earlier result left looking new, whatever happens next
    scn = load_scenario(header.path)
    if args.guidance == "nog":
        tables = prepare_tables(scn, Path(args.tables) if args.tables else None)
        factory = KernelNogGuidance.for_tables(tables)
    else:
        tables, factory = None, NominalOpenLoopGuidance
    settings = SilSettings(control_rate_hz=args.control_rate, truth_substeps=args.truth_substeps,
                           history_runs=args.history_runs if args.plots else 0,
                           cpd_gains=args.cpd_gains, cpd_pointing=args.cpd_pointing,
                           # the open-loop reference flies no end-game (its cut-off is t_f*)
                           end_game=("paper" if args.paper_end_game or args.guidance == "nominal"
                                     else "scenario"))
    res = run_campaign(scn, runs=args.runs, seed=args.seed, workers=args.workers,
                       dispersions=not args.no_dispersions, truth=args.truth,
                       guidance_factory=factory, guidance_name=args.guidance, settings=settings,
                       header=header, tables=tables, chunk_runs=args.chunk_runs,
                       watchdog=Watchdog(per_run_s=args.watchdog_per_run),
                       run_log=run_log_path(args.json), resume=args.resume)
    print(format_report(res))
    if res.resumed_runs:
        print(f"\n{res.resumed_runs} of {res.runs} runs taken from {run_log_path(args.json)}")
    res.write_json(args.json)
    print(f"\nwrote {args.json}")
    if args.plots:
        from .plots import write_plots
        for path in write_plots(res, args.plots):
            print(f"wrote {path}")
    return 0 if res.n_failures == 0 else 1
