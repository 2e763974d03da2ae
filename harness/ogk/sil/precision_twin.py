"""A single-precision campaign's double twin: the same plan, seed and run ids flown on the double
kernel, and what float changes, per run (issue 35, "accuracy in the loop, same draws").

The real type is fixed per process when the bindings load (ogk.sil.precision), so the twin flies in a
new process started with OGK_PRECISION=double (multiprocessing's spawn: nothing of this process's
float extension is inherited). It rebuilds the plan from the family, the scenario header and the
family's options, exactly as the single campaign built its own before the precision stamp, and flies
the single campaign's run ids through the same engine and worker count: run i's draws are those of
(seed, i) in both (ogk.sil.seeds), so the two records of a run differ by the kernel's arithmetic only.

Comparison, per quantity the plan summarises (plan.quantities), over the runs both finished with a
finite value: the largest |single - double|, its run, the double value there, and that difference in
units of the double campaign's standard deviation of the quantity (how large float's effect is
against the dispersions' own). Then the runs whose failure differs. It is a measurement, reported
beside the campaign; the single campaign's acceptance is its own records' (the family's criteria).
"""
from __future__ import annotations

import multiprocessing
import os
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

from . import engine, precision
from .family import MissionFamily, Record
from .report import is_finite_number


def _fly_double(fam: MissionFamily, header: Any, options: dict[str, Any], seed: int,
                run_ids: list[int], workers: int, chunk_runs: int | None) -> list[Record]:
    """In the spawned process: the double plan and its campaign (no run log)."""
    precision.select(precision.DEFAULT)
    plan = fam.plan(header, options)
    flown = engine.fly_campaign(plan, len(run_ids), seed, workers, run_ids=run_ids,
                                chunk_runs=chunk_runs)
    return list(flown.records)


def _child(conn: Any, args: tuple[Any, ...]) -> None:
    """The spawned process: the records, or the exception that stopped it, sent back."""
    try:
        conn.send(("ok", _fly_double(*args)))
    except BaseException as exc:  # noqa: BLE001 - every failure goes back to the campaign
        try:
            conn.send(("error", exc))
        except Exception:  # noqa: BLE001 - an exception that does not pickle
            conn.send(("error", RuntimeError(repr(exc))))
    finally:
        conn.close()


def fly_double(fam: MissionFamily, header: Any, options: Mapping[str, Any], seed: int,
               run_ids: Sequence[int], workers: int = 1, chunk_runs: int | None = None) -> list[Record]:
    """The double campaign of the same runs, flown in a new process (module doc)."""
    ctx = multiprocessing.get_context("spawn")
    saved = os.environ.get(precision.ENV)
    os.environ[precision.ENV] = precision.DEFAULT      # the child's environment at its start
    parent, child = ctx.Pipe(duplex=False)
    args = (fam, header, dict(options), int(seed), [int(i) for i in run_ids], int(workers), chunk_runs)
    # not a Pool: its processes are daemons, and the engine's workers are children of this one
    proc = ctx.Process(target=_child, args=(child, args), name="ogk-double-twin")
    try:
        proc.start()
        child.close()
        try:
            kind, value = parent.recv()
        except EOFError:
            raise RuntimeError(f"the double twin's process ended without a result "
                               f"(exit code {proc.exitcode})") from None
    finally:
        proc.join()
        parent.close()
        if saved is None:
            os.environ.pop(precision.ENV, None)
        else:
            os.environ[precision.ENV] = saved
    if kind != "ok":
        raise value
    return list(value)


def compare(single: Sequence[Record], double: Sequence[Record], quantities: Sequence[str]) -> dict[str, Any]:
    """The envelope's `precision_vs_double` section (module doc)."""
    by_id = {int(r["run_id"]): r for r in double}
    pairs = [(s, by_id[int(s["run_id"])]) for s in single if int(s["run_id"]) in by_id]
    out: dict[str, Any] = {}
    for key in quantities:
        both = [(float(s[key]), float(d[key]), int(s["run_id"])) for s, d in pairs
                if is_finite_number(s.get(key)) and is_finite_number(d.get(key))]
        ref = [float(d[key]) for _, d in pairs if is_finite_number(d.get(key))]
        std = float(np.std(ref, ddof=1)) if len(ref) > 1 else None
        if not both:
            out[key] = {"max_abs_diff": None, "run_id": None, "double": None, "in_double_std": None,
                        "runs": 0}
            continue
        s, d, run = max(both, key=lambda t: (abs(t[0] - t[1]), -t[2]))
        diff = abs(s - d)
        out[key] = {"max_abs_diff": diff, "run_id": run, "double": d, "single": s,
                    "in_double_std": (diff / std) if std else None, "runs": len(both)}
    differ = [{"run_id": int(s["run_id"]), "single": str(s.get("failure") or ""),
               "double": str(d.get("failure") or "")}
              for s, d in pairs if str(s.get("failure") or "") != str(d.get("failure") or "")]
    return {"runs_compared": len(pairs), "quantities": out, "failures_differ": differ,
            "double_failures": sum(1 for _, d in pairs if d.get("failure")),
            "single_failures": sum(1 for s, _ in pairs if s.get("failure"))}


def format_comparison(doc: Mapping[str, Any]) -> str:
    """The report's lines."""
    lines = [f"Single against double on the same draws ({doc['runs_compared']} runs; lost: single "
             f"{doc['single_failures']}, double {doc['double_failures']})",
             f"  {'quantity':24s} {'max |single - double|':>22s} {'run':>6s} {'double there':>13s} "
             f"{'in double std':>14s}"]
    for key, q in doc["quantities"].items():
        if q["max_abs_diff"] is None:
            lines.append(f"  {key:24s} {'n/a':>22s}")
            continue
        in_std = "n/a" if q["in_double_std"] is None else f"{q['in_double_std']:.3g}"
        lines.append(f"  {key:24s} {q['max_abs_diff']:22.4e} {q['run_id']:6d} {q['double']:13.6g} "
                     f"{in_std:>14s}")
    for d in doc["failures_differ"][:10]:
        lines.append(f"  run {d['run_id']}: single {d['single'] or 'ok'!r}, double {d['double'] or 'ok'!r}")
    if len(doc["failures_differ"]) > 10:
        lines.append(f"  ... {len(doc['failures_differ']) - 10} more runs whose failure differs")
    return "\n".join(lines)
