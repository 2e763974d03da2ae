"""One output shape for every campaign: a JSON envelope and the per-run table as Parquet.

Envelope (`ogk.campaign/1`, written atomically, NaN as null):
  schema, family, law, mission, scenario_path, scenario_sha256, products {name: SHA-256},
  options (what the runs depend on besides id and seed), seed, runs, workers, resumed_runs,
  failures (count), failure_reasons {reason: count}, failure_classes {class: count},
  failed_runs [{run_id, reason, class, run_seed, replay}] (replay: the `ogk replay` command of the run),
  acceptance (the criterion as the scenario states it),
  quantities {key: {n, mean, std, median, robust_std, worst: {run_id, value, from_median_std,
    from_median_robust_std}, farthest: {the same}}}  (worst: the largest |value|, the lowest run id
    on a tie; farthest: the run farthest from the median; ogk.sil.robustness),
  robustness {runs, lost_flights, lost_by_class {class: {count, runs}}, lost_runs [...],
    failed_solves {total, runs_with_any, per_run_max, run_of_max, by_class} | null, worst_run}
    (ogk.sil.robustness),
  paper (the paper's columns beside ours, only when the scenario carries them),
  per_run_table (the Parquet file's name), timing {wall_s, cpu_s}, target ("host", "m7", "sparc" or "m4f"),
  pil (a target campaign only: worst case per entry point, host vs target; ogk.sil.target_summary),
  precision_vs_double (a single-precision campaign only: its double twin on the same draws, the largest
    difference per quantity; ogk.sil.precision_twin),
  dispersion_check (each declared dispersion against the records; ogk.sil.dispersion_check),
  numerics (this host's numerics fingerprint: numpy, its SIMD targets, the BLAS kernels;
  ogk.sil.numerics; `ogk replay` on another machine says when it differs)
A family may add its own keys (its report's figures, older names kept as aliases): never one of
the above.

Parquet (`<json stem>.parquet` beside the JSON, pyarrow): one row per run, in run-id order: run_id,
run_seed, every drawn value, every result, failure ("" when the run passed); the value of each
declared dispersion as applied under disp.<[dispersions] key> (ogk.sil.dispersion_check).
"""
from __future__ import annotations

import json
import math
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from . import numerics, precision, robustness
from .engine import Flown
from .family import Record
from .outputs import write_atomic
from .report import finite_or_none

SCHEMA = "ogk.campaign/1"
ENVELOPE_KEYS = ("schema", "family", "law", "mission", "scenario_path", "scenario_sha256",
                 "products", "options", "seed", "runs", "workers", "resumed_runs", "failures",
                 "failure_reasons", "failure_classes", "failed_runs", "acceptance", "quantities",
                 "paper", "per_run_table", "timing", "target", "pil", "dispersion_check", "numerics",
                 "robustness", "precision", "precision_vs_double")


def table_path(json_path: str | Path) -> Path:
    """The Parquet table of a campaign JSON: same directory, same stem."""
    p = Path(json_path)
    return p.with_suffix(".parquet")


def _number(value: Any) -> float | None:
    if isinstance(value, bool) or value is None:
        return float(value) if isinstance(value, bool) else None
    if isinstance(value, (int, float, np.integer, np.floating)):
        return float(value)
    return None


def quantity_summary(records: Sequence[Record], keys: Sequence[str]) -> dict[str, Any]:
    """Mean, sample std (ddof 1), median, robust std and the worst run (largest |value|; of equal ones,
    the lowest run id) and the run farthest from the median, each with its distance from the median in
    both sigmas (ogk.sil.robustness), of each key over the runs where it is a finite number."""
    out: dict[str, Any] = {}
    for key in keys:
        pairs = [(int(r["run_id"]), v) for r in records
                 if (v := _number(r.get(key))) is not None and math.isfinite(v)]
        if not pairs:
            out[key] = {"n": 0, "mean": None, "std": None, "median": None, "robust_std": None,
                        "worst": None, "farthest": None}
            continue
        vals = np.array([v for _, v in pairs])
        k = int(np.argmax(np.abs(vals)))
        out[key] = {"n": len(pairs), "mean": float(vals.mean()),
                    "std": float(vals.std(ddof=1)) if vals.size > 1 else 0.0,
                    **robustness.spread([i for i, _ in pairs], vals, k)}
    return out


def failure_reasons(records: Sequence[Record]) -> dict[str, int]:
    """Reason -> count; tolerance failures grouped by the quantity that failed."""
    out: dict[str, int] = {}
    for r in records:
        f = str(r.get("failure") or "")
        if f:
            key = f.split(" = ")[0] if f.startswith("tolerance:") else f
            out[key] = out.get(key, 0) + 1
    return out


def envelope(flown: Flown, extra: Mapping[str, Any] | None = None,
             json_path: str | Path | None = None,
             pil: Mapping[str, Any] | None = None,
             dispersion_check: Mapping[str, Any] | None = None,
             precision_vs_double: Mapping[str, Any] | None = None) -> dict[str, Any]:
    """The campaign's JSON document (module doc); `extra`: the family's own keys."""
    plan, recs = flown.plan, flown.records
    doc: dict[str, Any] = dict(extra or {})
    clash = sorted(set(doc) & set(ENVELOPE_KEYS))
    if clash:
        raise ValueError(f"family keys shadow the envelope: {clash}")
    paper = plan.paper(recs) if plan.paper is not None else None
    path = None if json_path is None else str(json_path)
    lost = robustness.lost_runs(recs, plan.classify, plan.lost, path)
    failed = [{k: f[k] for k in ("run_id", "reason", "class", "run_seed", "replay")}
              for f in lost if f["acceptance"]]
    classes: dict[str, int] = {}
    for f in failed:
        classes[f["class"]] = classes.get(f["class"], 0) + 1
    quantities = quantity_summary(recs, plan.quantities)
    rob = robustness.summary(recs, quantities, lost, robustness.failed_solves(recs, plan.solve_failures))
    rob["lost_runs"] = lost
    doc.update({
        "schema": SCHEMA, "family": plan.family, "law": plan.law, "mission": plan.mission,
        "scenario_path": str(plan.scenario_path), "scenario_sha256": plan.scenario_sha256,
        "products": plan.products, "options": plan.options, "seed": flown.seed, "runs": len(recs),
        "workers": flown.workers, "resumed_runs": flown.resumed_runs,
        "failures": len(flown.failures()), "failure_reasons": failure_reasons(recs),
        "failure_classes": classes, "failed_runs": failed, "acceptance": plan.acceptance,
        "quantities": quantities, "robustness": rob,
        "per_run_table": None if json_path is None else table_path(json_path).name,
        "timing": {"wall_s": flown.wall_s, "cpu_s": flown.cpu_s}, "target": plan.target,
        "numerics": numerics.fingerprint(),
        # the real type of the kernel flown (ogk.sil.precision): "double", or "single" (float kernel):
        # on the host the campaign's --precision, on a target that target's (the M4F's: single)
        "precision": precision.of_options(plan.options) if plan.target == "host"
        else precision.TARGET_PRECISION[plan.target]})
    if paper is not None:
        doc["paper"] = paper
    if pil is not None:
        doc["pil"] = dict(pil)
    if dispersion_check is not None:
        doc["dispersion_check"] = dict(dispersion_check)
    if precision_vs_double is not None:
        # a single campaign's double twin on the same draws (ogk.sil.precision_twin)
        doc["precision_vs_double"] = dict(precision_vs_double)
    return finite_or_none(doc)


def write_table(path: str | Path, records: Sequence[Record]) -> Path:
    """The per-run table as Parquet, written through a temporary file and a rename."""
    import os
    import tempfile

    import pyarrow as pa
    import pyarrow.parquet as pq
    p = Path(path)
    columns: dict[str, None] = {}
    for r in records:
        columns.update(dict.fromkeys(r))
    # run seeds are 64-bit unsigned (ogk.sil.seeds): the one column whose type is stated
    table = pa.table({c: pa.array([r.get(c) for r in records],
                                  type=pa.uint64() if c == "run_seed" else None)
                      for c in columns})
    fd, tmp = tempfile.mkstemp(dir=p.parent, prefix=f".{p.name}.", suffix=".tmp")
    os.close(fd)
    try:
        pq.write_table(table, tmp)
        os.chmod(tmp, 0o644)
        os.replace(tmp, p)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise
    return p


def read_table(path: str | Path) -> list[Record]:
    """The rows of a campaign's Parquet table, as records."""
    import pyarrow.parquet as pq
    return pq.read_table(path).to_pylist()


def write_campaign(json_path: str | Path, flown: Flown,
                   extra: Mapping[str, Any] | None = None,
                   pil: Mapping[str, Any] | None = None,
                   dispersion_check: Mapping[str, Any] | None = None,
                   precision_vs_double: Mapping[str, Any] | None = None) -> dict[str, Any]:
    """Writes the Parquet table, then the envelope (the envelope last: a JSON that exists names a
    complete table). Returns the envelope."""
    write_table(table_path(json_path), flown.records)
    doc = envelope(flown, extra, json_path, pil, dispersion_check, precision_vs_double)
    write_atomic(json_path, json.dumps(doc, indent=1) + "\n")
    return doc


def read_envelope(path: str | Path) -> dict[str, Any]:
    from ogk_bindings.errors import OgkInputError
    try:
        doc = json.loads(Path(path).read_text(encoding="utf-8"))
    except (OSError, json.JSONDecodeError) as exc:
        raise OgkInputError(f"not a campaign JSON ({exc})", path=path) from None
    if not isinstance(doc, dict) or doc.get("schema") != SCHEMA:
        raise OgkInputError(f"not a campaign envelope (schema {SCHEMA})", path=path, key="schema")
    return doc


def same_numbers(a: Any, b: Any) -> bool:
    """Bit-for-bit equality of two record values (NaN equals NaN; lists elementwise)."""
    if isinstance(a, (list, tuple)) and isinstance(b, (list, tuple)):
        return len(a) == len(b) and all(same_numbers(x, y) for x, y in zip(a, b))
    fa, fb = _number(a), _number(b)
    if fa is not None and fb is not None and not isinstance(a, bool):
        return (math.isnan(fa) and math.isnan(fb)) or fa == fb
    if a is None and isinstance(b, float) and math.isnan(b):
        return True
    if b is None and isinstance(a, float) and math.isnan(a):
        return True
    return a == b


def record_differences(stored: Record, again: Record) -> list[str]:
    """Keys whose values differ between two flights of one run (timing.* keys excluded)."""
    keys = (set(stored) | set(again))
    return sorted(k for k in keys if not k.startswith("timing.")
                  and not same_numbers(stored.get(k), again.get(k)))
