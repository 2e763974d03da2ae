"""What a target campaign states beyond the host's (docs/guides/pil.md): the worst case per entry point over
the campaign, and the host campaign on the same draws beside it.

Per entry point (from the runs' pil.<entry>.* keys, ogk.sil.pil):
  calls            every call the campaign made
  insn_median      the median of the runs' medians (instructions per call)
  insn_max         {value, run_id, step}: the most instructions one call took, where
  stack_bytes      {value, run_id}: the deepest stack one call used, where
Host vs target (per quantity of the plan, over the runs both flew):
  {max_abs_diff, run_id, bound, within}; failures_differ: the runs whose failure differs.
On a target whose kernel is single precision (ogk.sil.precision.TARGET_PRECISION: the Cortex-M4F) the comparison is
report only: the families' bounds are those of a double kernel (a few ulp of libm carried by the
closed loop), and a float kernel rounds every operation to binary32 (eps 1.2e-7, 5e8 times double's),
which the closed loop carries to the end of the flight by a gain no family has derived. The figures are
stated per quantity (bound None, within None), `report_only` is true and `within_bounds` true (nothing
is bounded); the run's acceptance is the scenario's own, judged on the target's records as on any
campaign, and failures_differ is still listed.
"""
from __future__ import annotations

import re
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

from .family import Record
from .precision import TARGET_PRECISION
from .report import is_finite_number

_ENTRY = re.compile(r"^pil\.(?P<entry>[A-Za-z_][A-Za-z0-9_]*)\.insn_max$")


def entry_points(records: Sequence[Record]) -> list[str]:
    """The entry points the records carry, in the order of their keys."""
    seen: dict[str, None] = {}
    for r in records:
        for key in r:
            m = _ENTRY.match(key)
            if m:
                seen[m.group("entry")] = None
    return list(seen)


def worst_per_entry(records: Sequence[Record]) -> dict[str, Any]:
    """Per entry point: calls, median, worst instructions (run, step), worst stack (run)."""
    out: dict[str, Any] = {}
    for e in entry_points(records):
        p = f"pil.{e}."
        runs = [r for r in records if is_finite_number(r.get(p + "insn_max"))]
        if not runs:
            out[e] = {"calls": 0, "insn_median": None, "insn_max": None, "stack_bytes": None}
            continue
        w = max(runs, key=lambda r: (int(r[p + "insn_max"]), -int(r["run_id"])))
        s = max(runs, key=lambda r: (int(r.get(p + "stack_bytes") or 0), -int(r["run_id"])))
        out[e] = {
            "calls": int(sum(int(r.get(p + "calls") or 0) for r in runs)),
            "insn_median": float(np.median([float(r[p + "insn_median"]) for r in runs])),
            "insn_max": {"value": int(w[p + "insn_max"]), "run_id": int(w["run_id"]),
                         "step": int(w[p + "insn_max_step"])},
            "stack_bytes": {"value": int(s.get(p + "stack_bytes") or 0),
                            "run_id": int(s["run_id"])},
            "stack_window_exceeded": any(bool(r.get(p + "stack_window_exceeded")) for r in runs)}
    return out


def host_vs_target(target: Sequence[Record], host: Sequence[Record],
                   bounds: Mapping[str, float], report_only: bool = False) -> dict[str, Any]:
    """The largest per-run difference of each bounded quantity between the two campaigns (with
    `report_only`, of each quantity named in `bounds`, none judged: module doc)."""
    by_id = {int(r["run_id"]): r for r in host}
    pairs = [(r, by_id[int(r["run_id"])]) for r in target if int(r["run_id"]) in by_id]
    out: dict[str, Any] = {}
    for key, bound in bounds.items():
        diffs = [(abs(float(t[key]) - float(h[key])), int(t["run_id"])) for t, h in pairs
                 if is_finite_number(t.get(key)) and is_finite_number(h.get(key))]
        stated = None if report_only else float(bound)
        if not diffs:
            out[key] = {"max_abs_diff": None, "run_id": None, "bound": stated,
                        "within": None if report_only else True}
            continue
        worst, where = max(diffs, key=lambda p: (p[0], -p[1]))
        out[key] = {"max_abs_diff": worst, "run_id": where, "bound": stated,
                    "within": None if report_only else worst <= float(bound)}
    differ = [int(t["run_id"]) for t, h in pairs
              if str(t.get("failure") or "") != str(h.get("failure") or "")]
    if report_only:
        return {"runs_compared": len(pairs), "quantities": out, "failures_differ": differ,
                "within_bounds": True, "report_only": True}
    return {"runs_compared": len(pairs), "quantities": out, "failures_differ": differ,
            "within_bounds": all(q["within"] for q in out.values()) and not differ}


def summary(target: str, records: Sequence[Record], host: Sequence[Record] | None,
            bounds: Mapping[str, float], why: str, wall_s: float, workers: int) -> dict[str, Any]:
    """The envelope's `pil` section (`precision`: that of the target's kernel, ogk.sil.precision.TARGET_PRECISION)."""
    precision = TARGET_PRECISION[target]
    doc: dict[str, Any] = {
        "target": target, "precision": precision, "entry_points": worst_per_entry(records),
        "runs_per_minute": (60.0 * len(records) / wall_s) if wall_s > 0.0 else None,
        "workers": int(workers)}
    if host is not None:
        doc["host_vs_target"] = {**host_vs_target(records, host, bounds,
                                                  report_only=precision == "single"), "why": why}
    return doc


def format_summary(pil: Mapping[str, Any]) -> str:
    """The report's lines: worst case per entry point, then host vs target."""
    single = " with the single-precision kernel" if pil.get("precision") == "single" else ""
    lines = [f"On the target ({pil['target']}{single}): worst case per entry point "
             f"(instructions per call, QEMU's count; stack below the caller)",
             f"  {'entry point':24s} {'calls':>9s} {'median':>10s} {'max':>10s} {'run':>6s} "
             f"{'step':>6s} {'stack B':>8s} {'run':>6s}"]
    for e, v in pil["entry_points"].items():
        if not v["calls"]:
            lines.append(f"  {e:24s} {0:9d}")
            continue
        over = " (window exceeded)" if v.get("stack_window_exceeded") else ""
        lines.append(f"  {e:24s} {v['calls']:9d} {v['insn_median']:10.0f} "
                     f"{v['insn_max']['value']:10d} {v['insn_max']['run_id']:6d} "
                     f"{v['insn_max']['step']:6d} {v['stack_bytes']['value']:8d} "
                     f"{v['stack_bytes']['run_id']:6d}{over}")
    if pil.get("runs_per_minute"):
        lines.append(f"  {pil['runs_per_minute']:.1f} runs per minute on {pil['workers']} "
                     f"worker(s)")
    hv = pil.get("host_vs_target")
    if hv:
        if hv.get("report_only"):
            lines.append(f"Host (double) vs target (single) on the same draws ({hv['runs_compared']} "
                         "runs): report only (no bound: ogk.sil.target_summary)")
        else:
            lines.append(f"Host vs target on the same draws ({hv['runs_compared']} runs): "
                         f"{'within' if hv['within_bounds'] else 'OUTSIDE'} the stated bounds")
        for key, q in hv["quantities"].items():
            diff = "n/a" if q["max_abs_diff"] is None else f"{q['max_abs_diff']:.3e}"
            judged = ("reported" if q["bound"] is None else
                      f"bound {q['bound']:.1e}  {'ok' if q['within'] else 'EXCEEDED'}")
            lines.append(f"  {key:24s} max |host - target| {diff:>10s}  (run {q['run_id']})  "
                         f"{judged}")
        if hv["failures_differ"]:
            lines.append(f"  failures differ in runs {hv['failures_differ'][:10]}")
        lines.append(f"  why they differ: {hv['why']}")
    return "\n".join(lines)
