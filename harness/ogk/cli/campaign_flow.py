"""`ogk mc SCENARIO`, `ogk replay CAMPAIGN RUN_ID`, `ogk report CAMPAIGN`: the same flow for every
mission family. The family (ogk.missions.<family>.family.FAMILY, ogk.sil.family) says what a run
is; the engine (ogk.sil.engine) flies the runs; the envelope (ogk.sil.envelope) writes the JSON and
the Parquet table. Exit 0 when every run passed the scenario's acceptance, 1 otherwise."""
from __future__ import annotations

import argparse
from pathlib import Path
from typing import Any

import numpy as np
from ogk_bindings.errors import OgkInputError
from ogk_host.scenario_file import ScenarioHeader, file_sha256, read_header

from ogk.missions import registry
from ogk.sil import engine, envelope
from ogk.sil.family import CampaignPlan
from ogk.sil.outputs import check_output_dir, check_output_file, remove_stale
from ogk.sil.runner import Watchdog


def add_engine_arguments(p: argparse.ArgumentParser, family: Any) -> None:
    """The options every campaign has (the family adds its own after them)."""
    default_runs = getattr(family, "default_runs", None)
    p.add_argument("--runs", type=int, default=default_runs, required=default_runs is None,
                   help="number of runs" + (f" (default {default_runs})" if default_runs else ""))
    p.add_argument("--seed", type=int, default=1,
                   help="master seed >= 0 (run i draws from SeedSequence(seed, (i,)); default 1)")
    p.add_argument("--workers", type=int, default=1, help="parallel processes (default 1)")
    p.add_argument("--json", required=True, metavar="FILE",
                   help="the campaign envelope; the per-run table is FILE's stem + .parquet")
    p.add_argument("--plots", default=None, metavar="DIR", help="directory for PNG plots")
    p.add_argument("--resume", action="store_true",
                   help="keep the runs already in <json>.runs.jsonl (same campaign) and fly the rest")
    p.add_argument("--chunk-runs", type=int, default=None, metavar="K",
                   help=f"at most K runs per chunk (default {engine.DEFAULT_CHUNK_RUNS}); finished "
                        "chunks are kept in <json>.runs.jsonl as they complete")
    p.add_argument("--watchdog-per-run", type=float, default=None, metavar="S",
                   help="a chunk without a result after 120 s + S s per run is killed and the "
                        "campaign aborted (default: the family's)")


def check_engine_arguments(args: argparse.Namespace) -> None:
    """Every engine option checked before any ground product is made."""
    if args.runs is None or args.runs < 1:
        raise OgkInputError(f"must be >= 1, got {args.runs}", key="--runs")
    if args.seed < 0:
        raise OgkInputError(f"must be >= 0, got {args.seed}", key="--seed")
    if args.workers < 1:
        raise OgkInputError(f"must be >= 1, got {args.workers}", key="--workers")
    if args.chunk_runs is not None and args.chunk_runs < 1:
        raise OgkInputError(f"must be >= 1, got {args.chunk_runs}", key="--chunk-runs")
    if args.watchdog_per_run is not None and not args.watchdog_per_run > 0.0:
        raise OgkInputError(f"must be > 0 s, got {args.watchdog_per_run:g}",
                            key="--watchdog-per-run")
    check_output_file(args.json, "--json")
    check_output_file(engine.run_log_path(args.json), "--json")
    check_output_file(envelope.table_path(args.json), "--json")
    if args.plots:
        check_output_dir(args.plots, "--plots")


ENGINE_OPTIONS = ("runs", "seed", "workers", "json", "plots", "resume", "chunk_runs",
                  "watchdog_per_run", "debug")


def family_options(args: argparse.Namespace) -> dict[str, Any]:
    """The family's own options (what is not the engine's)."""
    return {k: v for k, v in vars(args).items() if k not in ENGINE_OPTIONS}


def fly(header: ScenarioHeader, args: argparse.Namespace) -> int:
    """`ogk mc SCENARIO ...` for any family."""
    fam = registry.campaign_family(header)
    check_engine_arguments(args)
    remove_stale(args.json)
    plan: CampaignPlan = fam.plan(header, family_options(args))
    if plan.max_runs is not None and args.runs > plan.max_runs:
        raise OgkInputError(f"this campaign has {plan.max_runs} runs, got {args.runs}", key="--runs")
    wd = Watchdog(per_run_s=args.watchdog_per_run) if args.watchdog_per_run else None
    flown = engine.fly_campaign(plan, args.runs, args.seed, args.workers,
                                chunk_runs=args.chunk_runs, watchdog=wd,
                                run_log=engine.run_log_path(args.json), resume=args.resume)
    text, extra = fam.report(flown)
    print(text)
    if flown.resumed_runs:
        print(f"\n{flown.resumed_runs} of {len(flown.records)} runs taken from "
              f"{engine.run_log_path(args.json)}")
    envelope.write_campaign(args.json, flown, extra)
    print(f"\nwrote {args.json} and {envelope.table_path(args.json)} "
          f"({len(flown.records)} runs, {flown.wall_s:.1f} s wall, {flown.workers} workers)")
    if args.plots and hasattr(fam, "plots"):
        for path in fam.plots(flown, Path(args.plots)):
            print(f"wrote {path}")
    return 0 if not flown.failures() else 1


def campaign_plan(doc: dict[str, Any], path: str | Path) -> tuple[Any, CampaignPlan]:
    """The family and the plan of a campaign envelope, rebuilt from its scenario and options
    (refused when the scenario file changed since)."""
    scenario = Path(doc["scenario_path"])
    if not scenario.is_file():
        raise OgkInputError(f"scenario {scenario} of the campaign is missing", path=path,
                            key="scenario_path")
    if file_sha256(scenario) != doc["scenario_sha256"]:
        raise OgkInputError(f"scenario {scenario} changed since the campaign (SHA-256 differs)",
                            path=path, key="scenario_sha256")
    header = read_header(scenario)
    fam = registry.campaign_family(header)
    plan = fam.plan(header, doc["options"])
    if plan.products != doc["products"]:
        diff = sorted(k for k in set(plan.products) | set(doc["products"])
                      if plan.products.get(k) != doc["products"].get(k))
        raise OgkInputError(f"ground products differ from the campaign's ({', '.join(diff)})",
                            path=path, key="products")
    return fam, plan


def replay(campaign: str, run_id: int, plots: str | None, json_out: str | None) -> int:
    """`ogk replay CAMPAIGN RUN_ID`: run RUN_ID again, bit for bit against the stored table."""
    import json

    doc = envelope.read_envelope(campaign)
    table = Path(campaign).with_name(doc["per_run_table"] or envelope.table_path(campaign).name)
    stored = {int(r["run_id"]): r for r in envelope.read_table(table)}
    if run_id not in stored:
        raise OgkInputError(f"no run {run_id} in {table}", key="RUN_ID")
    if plots:
        check_output_dir(plots, "--plots")
    fam, plan = campaign_plan(doc, campaign)
    again = engine._Chunk(plan, int(doc["seed"]))(np.array([run_id], dtype=np.int64))[0]
    diff = envelope.record_differences(stored[run_id], again)
    print(f"{plan.mission}: run {run_id} of {campaign} (seed {doc['seed']}, run seed "
          f"{again['run_seed']}): {'bit-exact' if not diff else 'DIFFERS in ' + ', '.join(diff)}")
    for key in plan.quantities:
        print(f"  {key:28s} {again.get(key)!r}")
    if again.get("failure"):
        print(f"  failure: {again['failure']}")
    if plan.detail is not None and plots:
        detail = plan.detail(run_id, int(again["run_seed"]), Path(plots))
        for f in detail.files:
            print(f"wrote {f}")
    if json_out:
        check_output_file(json_out, "--json")
        from ogk.sil.outputs import write_atomic
        from ogk.sil.report import finite_or_none
        write_atomic(json_out, json.dumps(finite_or_none(
            {"campaign": str(campaign), "run_id": run_id, "bit_exact": not diff,
             "differences": diff, "record": again}), indent=1) + "\n")
        print(f"wrote {json_out}")
    return 0 if not diff else 1


def report(campaign: str) -> int:
    """`ogk report CAMPAIGN`: the campaign's tables (the paper's beside ours) from its JSON."""
    doc = envelope.read_envelope(campaign)
    table = Path(campaign).with_name(doc["per_run_table"] or envelope.table_path(campaign).name)
    records = envelope.read_table(table)
    fam = registry.family_named(doc["family"])
    if hasattr(fam, "report_from"):
        print(fam.report_from(doc, records))
    else:
        print(generic_report(doc))
    return 0 if not doc["failures"] else 1


def generic_report(doc: dict[str, Any]) -> str:
    """Quantities, failures and (when present) the paper's columns of any campaign."""
    lines = [f"{doc['mission']} ({doc['family']}, {doc['law']}): {doc['runs']} runs, seed "
             f"{doc['seed']}, {doc['failures']} failed",
             f"  {'quantity':28s} {'mean':>14s} {'std':>14s} {'worst':>14s}  run"]
    for key, q in doc["quantities"].items():
        if q["n"]:
            lines.append(f"  {key:28s} {q['mean']:14.6g} {q['std']:14.6g} "
                         f"{q['worst']['value']:14.6g}  {q['worst']['run_id']}")
    for reason, n in doc["failure_reasons"].items():
        lines.append(f"  failed: {n} x {reason}")
    return "\n".join(lines)

