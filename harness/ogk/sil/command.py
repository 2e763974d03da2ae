"""`ogk mc SCENARIO` for any family: the engine's options, the plan of the family (ogk.sil.family),
the flight (ogk.sil.engine), the report the family prints, the envelope and Parquet table
(ogk.sil.envelope), the dispersion check (ogk.sil.dispersion_check). Exit 0 when every run passed
the scenario's acceptance and every declared dispersion was applied, 1 otherwise (a failed
distribution test is a warning: a correct campaign fails it with the check's significance)."""
from __future__ import annotations

import argparse
from pathlib import Path
from typing import Any

from ogk_bindings.errors import OgkInputError
from ogk_host.paths import need_repository
from ogk_host.scenario_file import ScenarioHeader

from . import dispersion_check, engine, envelope, precision, precision_twin, robustness, target_summary
from .family import CampaignPlan, MissionFamily
from .outputs import check_output_dir, check_output_file, remove_stale
from .pil import TARGETS
from .runner import Watchdog


def parser_for(fam: MissionFamily, prog: str, header: ScenarioHeader | None = None
               ) -> argparse.ArgumentParser:
    """The parser of a family's campaign: the engine's options, then the family's."""
    p = argparse.ArgumentParser(prog=prog, description=f"Monte Carlo campaign of a {fam.name} "
                                f"scenario ({', '.join(fam.laws)}): {fam.campaign_doc}")
    add_engine_arguments(p, fam, header)
    fam.add_campaign_arguments(p)
    return p


def add_engine_arguments(p: argparse.ArgumentParser, family: MissionFamily,
                         header: ScenarioHeader | None = None) -> None:
    """The options every campaign has (the family adds its own after them). The number of runs
    defaults to what the scenario states, when the family reads one (`default_runs(header)`)."""
    default_runs = family.default_runs(header) if header is not None else None
    p.add_argument("--runs", type=int, default=default_runs,
                   help="number of runs" + (f" (default {default_runs}, the scenario's)"
                                            if default_runs else
                                            " (required unless the campaign is a fixed list)"))
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
    p.add_argument("--dask", default=None, metavar="ADDRESS",
                   help="fly the chunks on a Dask cluster: a running scheduler's ADDRESS "
                        "(tcp://HOST:PORT) or local:N (N worker processes started here); the "
                        "records are the same bit for bit (docs/guides/scale-out.md)")
    add_target_argument(p)
    p.add_argument(precision.OPTION, choices=precision.CHOICES, default=precision.DEFAULT, help=precision.HELP)
    p.add_argument("--double-twin", action=argparse.BooleanOptionalAction, default=True,
                   help="with --precision single: also fly the same runs on the double kernel (a new "
                        "process) and report the largest difference per quantity (default: on)")
    p.add_argument("--watchdog-per-run", type=float, default=None, metavar="S",
                   help="a chunk without a result after 120 s + S s per run is killed and the "
                        "campaign aborted (default: the family's)")


def add_target_argument(p: argparse.ArgumentParser) -> None:
    p.add_argument("--target", choices=TARGETS, default="host",
                   help="host: the flight software in this process (SIL, default); m7: the "
                        "scenario's flight program on the emulated Cortex-M7 (QEMU), with the host "
                        "campaign on the same draws beside it (docs/guides/pil.md); sparc: on SPARC "
                        "V8; m4f: on the Cortex-M4F with the single-precision kernel")


def check_engine_arguments(args: argparse.Namespace) -> None:
    """Every engine option checked before any ground product is made."""
    if args.runs is not None and args.runs < 1:
        raise OgkInputError(f"must be >= 1, got {args.runs}", key="--runs")
    if args.seed < 0:
        raise OgkInputError(f"must be >= 0, got {args.seed}", key="--seed")
    if args.workers < 1:
        raise OgkInputError(f"must be >= 1, got {args.workers}", key="--workers")
    if getattr(args, "dask", None) is not None:     # `ogk run` checks these options too, without it
        from .dask_executor import check_address
        check_address(args.dask)
        if args.workers != 1:
            raise OgkInputError("the Dask cluster's workers fly the chunks: give --workers or "
                                "--dask, not both", key="--workers")
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
                  "watchdog_per_run", "debug", "dask", "precision", "double_twin")


def family_options(args: argparse.Namespace) -> dict[str, Any]:
    """The family's own options (what is not the engine's), and the target when it is not the host
    (a host campaign's options, hence its run log and envelope, are those of before --target)."""
    return {k: v for k, v in vars(args).items() if k not in ENGINE_OPTIONS
            and not (k == "target" and v == "host")}


def check_target(fam: MissionFamily, args: argparse.Namespace) -> None:
    target = getattr(args, "target", "host")
    if target not in fam.targets:
        raise OgkInputError(f"the {fam.name} family has no flight program for target {target} "
                            f"(its targets: {', '.join(fam.targets)})", key="--target")
    if target != "host":   # before any ground product: the flight program is built by make
        need_repository(f"the flight program of --target {target}", key="--target")


def fly(fam: MissionFamily, header: ScenarioHeader, args: argparse.Namespace) -> int:
    """`ogk mc SCENARIO ...` for any family `fam`; with `--dask` on a Dask
    cluster (ogk.sil.dask_executor), the same campaign."""
    check_engine_arguments(args)
    check_target(fam, args)
    precision.check(getattr(args, "precision", precision.DEFAULT), getattr(args, "target", "host"))
    if getattr(args, "dask", None) is None:
        return _fly(fam, header, args, None)
    from .dask_executor import DaskExecutor
    with DaskExecutor(args.dask, fam) as executor:
        return _fly(fam, header, args, executor)


def _fly(fam: MissionFamily, header: ScenarioHeader, args: argparse.Namespace,
         executor: Any) -> int:
    if args.runs is None and not fam.fixed_lists:
        raise OgkInputError("required: the number of runs", key="--runs")
    remove_stale(args.json)
    plan: CampaignPlan = fam.plan(header, family_options(args))
    plan.options = precision.stamp(plan.options)   # "precision": "single" (a double plan's unchanged)
    if args.runs is None:
        if plan.max_runs is None:
            raise OgkInputError("required: the number of runs (this campaign draws its runs)",
                                key="--runs")
        args.runs = plan.max_runs
    if plan.max_runs is not None and args.runs > plan.max_runs:
        raise OgkInputError(f"this campaign has {plan.max_runs} runs, got {args.runs}", key="--runs")
    wd = Watchdog(per_run_s=args.watchdog_per_run) if args.watchdog_per_run else None
    flown = engine.fly_campaign(plan, args.runs, args.seed, args.workers,
                                chunk_runs=args.chunk_runs, watchdog=wd,
                                run_log=engine.run_log_path(args.json), resume=args.resume,
                                executor=executor)
    pil = None
    if plan.target != "host":
        # the host campaign on the same draws: what the target changes, per run
        opts = {k: v for k, v in family_options(args).items() if k != "target"}
        host = engine.fly_campaign(fam.plan(header, opts), args.runs, args.seed, args.workers,
                                   run_ids=flown.run_ids, chunk_runs=args.chunk_runs,
                                   executor=executor)
        pil = target_summary.summary(plan.target, flown.records, host.records, plan.target_bounds,
                                     plan.target_why, flown.wall_s, flown.workers)
    twin = None
    if precision.of_options(plan.options) != precision.DEFAULT and args.double_twin:
        # the same runs on the double kernel: what float changes, per run
        ref = precision_twin.fly_double(fam, header, family_options(args), args.seed, flown.run_ids,
                                        args.workers, args.chunk_runs)
        twin = precision_twin.compare(flown.records, ref, plan.quantities)
    text, extra = fam.report(flown)
    disp = dispersion_check.check_plan(plan, flown.records)   # dispersions proven applied
    if precision.of_options(plan.options) != precision.DEFAULT:
        print(f"precision: {precision.of_options(plan.options)} (the kernel's ogk_real_t is float: "
              "OGK_REAL_SINGLE=1, F32 tables)\n")
    print(text)
    if pil is not None:
        print()
        print(target_summary.format_summary(pil))
    if twin is not None:
        print()
        print(precision_twin.format_comparison(twin))
    if disp is not None:
        print()
        print(disp.summary())
    if flown.resumed_runs:
        print(f"\n{flown.resumed_runs} of {len(flown.records)} runs taken from "
              f"{engine.run_log_path(args.json)}")
    doc = envelope.write_campaign(args.json, flown, extra, pil,
                                  None if disp is None else disp.to_json(), twin)
    print()
    print(robustness.format_quantities(doc["quantities"]))
    print()
    print(robustness.format_summary(doc["robustness"], plan.family, plan.mission))
    print(f"\nwrote {args.json} and {envelope.table_path(args.json)} "
          f"({len(flown.records)} runs, {flown.wall_s:.1f} s wall, {flown.workers} workers)")
    plots = fam.plots(flown, Path(args.plots)) if args.plots else []
    if plots and plan.target != "host":
        print("plots: time histories of the host's flights of the same runs (the target sends "
              "no histories back)")
    for path in plots:
        print(f"wrote {path}")
    agree = pil is None or pil["host_vs_target"]["within_bounds"]
    if not agree:
        print("the target campaign differs from the host's beyond the stated bounds (above)")
    if disp is not None and disp.structural_errors:
        print("a declared dispersion is not applied as the scenario states (above)")
    applied = disp is None or not disp.structural_errors   # a distribution test: a warning only
    return 0 if not flown.failures() and agree and applied else 1
