"""What a campaign says about a law's robustness, the same for every family (docs/guides/campaigns.md,
"Robustness"; ../shared/docs/ROBUSTNESS.md): how far the worst run sits from the bulk, every lost
flight with its class and the command that replays it, the failed solves per flight.

**Distance from the median.** For each summarised quantity, with m the median of the finite values:
  - `std`: the campaign's sample standard deviation (ddof 1), as the envelope has always stated it;
    a distance in these units can never exceed (n - 1) / sqrt(n) (Samuelson), because one outlier
    inflates the std it is measured in;
  - `robust_std`: 1.4826 x the median absolute deviation from m (the std of a normal law, unmoved by
    a few outliers); when more than half the values equal m (an integer count, a saturated error)
    the MAD is 0 and `robust_std` is 1.2533 x the mean absolute deviation from m (the same for a
    normal law), 0 only when every value is m (every distance is then 0).
  `worst` (the largest |value|, the envelope's since schema ogk.campaign/1) and `farthest` (the run
  farthest from m) each carry `from_median_std` = |value - m| / std and `from_median_robust_std` =
  |value - m| / robust_std (None when that sigma is 0 and the value is not m).

**Lost flights.** A run is lost when it failed the scenario's acceptance (its `failure`), or when the
family says so of a run that passed it (`CampaignPlan.lost`: the binary-asteroid family, whose
acceptance measures convergence instead of failing on it, calls a run lost when the scenario's own
corrector did not converge: the transfer is not flown). Each lost run has a class (`CampaignPlan.
classify`, else `failure_class` of its reason: numbers stripped, tolerances grouped by quantity).

**Failed solves.** `CampaignPlan.solve_failures(record)`: the class of each failed solve in a run
(NMPC re-solves, the correctors of a binary-asteroid draw); without it, a numeric `failed_solves`
key of the record counts unclassified ones; neither: the family has no solves to count (None).
"""
from __future__ import annotations

import math
import re
from collections.abc import Callable, Mapping, Sequence
from typing import Any

import numpy as np
from numpy.typing import NDArray

Record = dict[str, Any]

#: 1 / Phi^-1(3/4): MAD -> the std of a normal law
MAD_TO_STD = 1.482602218505602
#: sqrt(pi / 2): mean absolute deviation -> the std of a normal law
MEAN_ABS_TO_STD = 1.2533141373155001

_NUMBER = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")


def robust_std(values: NDArray[np.float64], median: float) -> float:
    """1.4826 MAD about `median`; 1.2533 x the mean absolute deviation when the MAD is 0 (module doc)."""
    dev = np.abs(values - median)
    mad = float(np.median(dev))
    if mad > 0.0:
        return MAD_TO_STD * mad
    return MEAN_ABS_TO_STD * float(np.mean(dev))


def _distance(value: float, median: float, sigma: float) -> float | None:
    d = abs(value - median)
    if sigma > 0.0:
        return d / sigma
    return 0.0 if d == 0.0 else None


def spread(run_ids: Sequence[int], values: NDArray[np.float64], worst_index: int) -> dict[str, Any]:
    """median, robust_std, the worst run's and the farthest run's distance from the median (module doc)."""
    med = float(np.median(values))
    std = float(values.std(ddof=1)) if values.size > 1 else 0.0
    rstd = robust_std(values, med)
    far = int(np.argmax(np.abs(values - med)))   # of equal ones, the lowest run id (run-id order)

    def at(i: int) -> dict[str, Any]:
        v = float(values[i])
        return {"run_id": int(run_ids[i]), "value": v,
                "from_median_std": _distance(v, med, std),
                "from_median_robust_std": _distance(v, med, rstd)}
    return {"median": med, "robust_std": rstd, "worst": at(worst_index), "farthest": at(far)}


def failure_class(reason: str) -> str:
    """The class of a failure reason: tolerance failures by quantity ("tolerance: |dr_f|"), others
    with their numbers taken out ("not arrived: impact with Mars at t = 12.5 d" -> "not arrived:
    impact with Mars at t = #")."""
    text = str(reason).strip()
    if text.startswith("tolerance:"):
        return text.split(" = ")[0]
    return re.sub(r"\s+", " ", _NUMBER.sub("#", text)).strip()


def replay_command(json_path: str | None, run_id: int) -> str | None:
    return None if json_path is None else f"ogk replay {json_path} {int(run_id)}"


def lost_runs(records: Sequence[Record], classify: Callable[[Record], str] | None,
              lost: Callable[[Record], str] | None, json_path: str | None) -> list[dict[str, Any]]:
    """[{run_id, run_seed, reason, class, replay}] of every lost run (module doc), in run-id order;
    `reason` is the run's failure, else what `lost` says."""
    out = []
    for r in records:
        reason = str(r.get("failure") or "") or (lost(r) if lost is not None else "")
        if not reason:
            continue
        cls = classify(r) if (classify is not None and r.get("failure")) else ""
        out.append({"run_id": int(r["run_id"]), "run_seed": r.get("run_seed"), "reason": reason,
                    "class": cls or failure_class(reason),
                    "acceptance": bool(r.get("failure")),
                    "replay": replay_command(json_path, int(r["run_id"]))})
    return out


def failed_solves(records: Sequence[Record],
                  solve_failures: Callable[[Record], Sequence[str]] | None) -> dict[str, Any] | None:
    """Failed solves over the campaign: total, per run (max and its run), by class; None when the
    family has no solves (module doc)."""
    def of(r: Record) -> list[str] | None:
        if solve_failures is not None:
            return [str(c) for c in solve_failures(r)]
        n = r.get("failed_solves")
        if isinstance(n, (int, float)) and not isinstance(n, bool) and math.isfinite(float(n)):
            return ["failed solve"] * int(n)
        return None
    per = [(int(r["run_id"]), of(r)) for r in records]
    counted = [(i, c) for i, c in per if c is not None]
    if not counted:
        return None
    by_class: dict[str, int] = {}
    for _, classes in counted:
        for c in classes:
            by_class[c] = by_class.get(c, 0) + 1
    worst_id, worst = max(counted, key=lambda ic: (len(ic[1]), -ic[0]))
    return {"runs": len(counted), "total": sum(len(c) for _, c in counted),
            "runs_with_any": sum(1 for _, c in counted if c),
            "per_run_max": len(worst), "run_of_max": worst_id if worst else None,
            "by_class": dict(sorted(by_class.items(), key=lambda kv: (-kv[1], kv[0])))}


def worst_run(quantities: Mapping[str, Any]) -> dict[str, Any] | None:
    """The run farthest from its quantity's median in robust std, over every quantity."""
    best: dict[str, Any] | None = None
    for key, q in quantities.items():
        far = q.get("farthest") if q.get("n") else None
        if not far or far.get("from_median_robust_std") is None:
            continue
        if best is None or far["from_median_robust_std"] > best["from_median_robust_std"]:
            best = {"quantity": key, **far, "median": q["median"], "robust_std": q["robust_std"],
                    "std": q["std"]}
    return best


def summary(records: Sequence[Record], quantities: Mapping[str, Any], lost: list[dict[str, Any]],
            solves: dict[str, Any] | None) -> dict[str, Any]:
    """The envelope's `robustness` (docs/guides/campaigns.md)."""
    by_class: dict[str, dict[str, Any]] = {}
    for f in lost:
        entry = by_class.setdefault(f["class"], {"count": 0, "runs": []})
        entry["count"] += 1
        entry["runs"].append(f["run_id"])
    return {"runs": len(records), "lost_flights": len(lost),
            "lost_by_class": dict(sorted(by_class.items(), key=lambda kv: (-kv[1]["count"], kv[0]))),
            "failed_solves": solves, "worst_run": worst_run(quantities)}


def short(v: float | None) -> str:
    return "-" if v is None else f"{v:.4g}"


def format_quantities(quantities: Mapping[str, Any]) -> str:
    """The quantities with the worst and the farthest run's distance from the median."""
    lines = ["quantities (distance from the median in the campaign's std / in robust std = "
             "1.4826 MAD; docs/guides/campaigns.md)",
             f"  {'quantity':28s} {'n':>5s} {'mean':>11s} {'std':>10s} {'median':>11s} "
             f"{'robust std':>10s} {'worst':>11s} {'run':>5s} {'std':>6s} {'rstd':>7s}  "
             f"farthest run, std, rstd"]
    for key, q in quantities.items():
        if not q.get("n"):
            lines.append(f"  {key:28s} {0:5d}  (no finite value)")
            continue
        w, f = q["worst"], q.get("farthest") or {}
        lines.append(f"  {key:28s} {q['n']:5d} {short(q['mean']):>11s} {short(q['std']):>10s} "
                     f"{short(q.get('median')):>11s} {short(q.get('robust_std')):>10s} "
                     f"{short(w['value']):>11s} {w['run_id']:5d} {short(w.get('from_median_std')):>6s} "
                     f"{short(w.get('from_median_robust_std')):>7s}  {f.get('run_id', '-')}, "
                     f"{short(f.get('from_median_std'))}, {short(f.get('from_median_robust_std'))}")
    return "\n".join(lines)


def format_summary(rob: Mapping[str, Any], family: str = "", mission: str = "") -> str:
    """One paragraph: lost flights by class (with runs), failed solves, the worst run."""
    head = f"robustness{': ' + mission if mission else ''}{' (' + family + ')' if family else ''}"
    lines = [f"{head}: {rob['lost_flights']} of {rob['runs']} flights lost"]
    for cls, e in rob["lost_by_class"].items():
        runs = ", ".join(str(i) for i in e["runs"][:12]) + (", ..." if len(e["runs"]) > 12 else "")
        lines.append(f"  lost: {e['count']} x {cls} (runs {runs})")
    s = rob.get("failed_solves")
    if s is None:
        lines.append("  failed solves: - (no solves to count)")
    else:
        lines.append(f"  failed solves: {s['total']} in {s['runs_with_any']} of {s['runs']} runs, at most "
                     f"{s['per_run_max']} per run" + (f" (run {s['run_of_max']})" if s['run_of_max']
                                                      is not None else ""))
        for cls, n in s["by_class"].items():
            lines.append(f"    {n} x {cls}")
    w = rob.get("worst_run")
    if w is not None:
        lines.append(f"  worst run: {w['run_id']} ({w['quantity']} = {w['value']:.6g}, median "
                     f"{w['median']:.6g}: {short(w['from_median_robust_std'])} robust std, "
                     f"{short(w['from_median_std'])} std)")
    return "\n".join(lines)
