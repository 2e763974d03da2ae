"""Failure criterion of a run, the same for every mission (docs/guides/sil.md):

a run fails when the kernel returned an error, when the truth model left its validity, or when
one of its final errors exceeds the tolerance the scenario states. The reason of each failure is
kept per run (first reason wins) and listed in the report and the JSON; a campaign with any
failure exits non-zero.
"""
from __future__ import annotations

import math
from collections.abc import Mapping, Sequence

import numpy as np
from numpy.typing import NDArray


def apply_tolerances(errors: Mapping[str, NDArray[np.float64]], tolerances: Mapping[str, float],
                     failure: Sequence[str], labels: Mapping[str, str] | None = None) -> list[str]:
    """`failure` with every run whose |error[key]| > tolerances[key] (or is not finite) marked,
    unless it had already failed for another reason."""
    out = list(failure)
    for key, tol in tolerances.items():
        values = np.asarray(errors[key], dtype=np.float64)
        for i, v in enumerate(values):
            if out[i]:
                continue
            if not math.isfinite(float(v)) or abs(float(v)) > tol:
                name = labels.get(key, key) if labels else key
                out[i] = f"tolerance: |{name}| = {abs(float(v)):.4g} > {tol:.4g}"
    return out


def failure_reasons(failure: Sequence[str]) -> dict[str, int]:
    """Reason -> count; tolerance failures grouped by the quantity that failed."""
    out: dict[str, int] = {}
    for f in failure:
        if f:
            key = f.split(" = ")[0] if f.startswith("tolerance:") else f
            out[key] = out.get(key, 0) + 1
    return out


def failure_list(run_ids: Sequence[int], failure: Sequence[str]) -> list[dict[str, object]]:
    """[{run_id, reason}] of the failed runs, in run-id order."""
    return [{"run_id": int(r), "reason": f} for r, f in zip(run_ids, failure) if f]


def statistics(errors: Mapping[str, NDArray[np.float64]], ok: NDArray[np.bool_]
               ) -> tuple[dict[str, float], dict[str, float]]:
    """Mean and sample standard deviation (ddof = 1; 0 for a single run) over the runs in `ok`."""
    mean = {k: float(np.mean(v[ok])) if ok.any() else float("nan") for k, v in errors.items()}
    std = {k: float(np.std(v[ok], ddof=1)) if ok.sum() > 1 else 0.0 for k, v in errors.items()}
    return mean, std


def tail_statistics(errors: Mapping[str, NDArray[np.float64]], ok: NDArray[np.bool_],
                    reference: Mapping[str, float] | None = None
                    ) -> tuple[dict[str, float], dict[str, float]]:
    """99.9th percentile of |error - reference| and the largest |error - reference| over the runs
    in `ok` (reference 0 unless given, e.g. the nominal for a free final time). A reviewer reads the
    worst run, not the sigma."""
    ref = reference or {}
    p999: dict[str, float] = {}
    worst: dict[str, float] = {}
    for k, v in errors.items():
        dev = np.abs(v[ok] - ref.get(k, 0.0))
        p999[k] = float(np.percentile(dev, 99.9)) if dev.size else float("nan")
        worst[k] = float(np.max(dev)) if dev.size else float("nan")
    return p999, worst
