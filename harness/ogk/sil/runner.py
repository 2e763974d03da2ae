"""Mission-independent campaign runner: runs split in chunks over forked worker processes.

A mission hands the runner a picklable-free *job*: a callable `job(run_ids) -> chunk result`
that flies the given runs (all at once, vectorised) and returns whatever the mission merges. The
job is installed in the parent before the fork, so workers inherit it (nominal solutions, tables,
bindings) without pickling; only run ids go out and chunk results come back.

The same (seed, run id) gives the same numbers whatever the number of workers or chunks only if
the mission's job draws each run from its own generator and its arithmetic is elementwise over
runs (docs/sil.md).
"""
from __future__ import annotations

import multiprocessing as mp
import os
from collections.abc import Callable, Sequence
from typing import Any, TypeVar

import numpy as np
from numpy.typing import NDArray

R = TypeVar("R")

_JOB: Callable[[NDArray[np.int64]], Any] | None = None  # set in the parent before the fork


def _call_job(run_ids: NDArray[np.int64]) -> Any:
    job = _JOB
    if job is None:  # pragma: no cover - only if a worker was not forked from run_chunks
        raise RuntimeError("campaign job not installed in this process")
    return job(run_ids)


def run_ids_for(runs: int, run_ids: Sequence[int] | None = None) -> NDArray[np.int64]:
    """Ids 0..runs-1, or the given ones (to re-fly some runs of an earlier campaign)."""
    ids = np.arange(runs, dtype=np.int64) if run_ids is None else np.asarray(run_ids, np.int64)
    if ids.size == 0:
        raise ValueError("no runs")
    return ids


def run_chunks(job: Callable[[NDArray[np.int64]], R], ids: NDArray[np.int64], workers: int = 1,
               chunks: int | None = None) -> tuple[list[R], int, float]:
    """Flies `ids` in `chunks` chunks (default: one per worker) on `workers` forked processes.

    Returns the chunk results in run-id order, the number of workers used and the CPU time
    (user + system, parent and children) spent."""
    global _JOB
    workers = max(1, min(int(workers), ids.size))
    n_chunks = max(1, min(chunks or workers, ids.size))
    cpu_start = os.times()
    _JOB = job
    try:
        pieces = np.array_split(ids, n_chunks)
        if workers == 1:
            outs = [_call_job(p) for p in pieces]
        else:
            with mp.get_context("fork").Pool(workers) as pool:
                outs = pool.map(_call_job, pieces, chunksize=1)
    finally:
        _JOB = None
    cpu_end = os.times()
    cpu_s = sum(getattr(cpu_end, f) - getattr(cpu_start, f)
                for f in ("user", "system", "children_user", "children_system"))
    return outs, workers, cpu_s
