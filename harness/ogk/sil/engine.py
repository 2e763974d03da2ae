"""The campaign engine, the same for every mission family: per-run random streams, chunks over
worker processes, watchdog and fault report (ogk.sil.runner), the append-only run log and
`--resume` (ogk.sil.runlog), progress on a terminal, and the records of all runs in run-id order.

A family brings a CampaignPlan (ogk.sil.family); the engine never looks inside a record except for
its run id. The numbers of run i depend on (plan.key(seed), i) only: its stream is
ogk.sil.seeds.run_seed(seed, i), whatever the worker count, the chunking or a resume.
"""
from __future__ import annotations

import dataclasses
import time
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from .family import CampaignPlan, Flown, Record
from .progress import Progress
from .runlog import RunLog
from .runner import CampaignInterrupted, Watchdog, run_chunks, run_ids_for
from .seeds import run_seed

#: runs per chunk unless the command says otherwise: finished chunks reach the run log this often
DEFAULT_CHUNK_RUNS = 250


def run_log_path(json_path: str | Path) -> Path:
    """The campaign's run log, next to its JSON: <json>.runs.jsonl."""
    p = Path(json_path)
    return p.with_name(p.name + ".runs.jsonl")


def seeds_of(seed: int, ids: NDArray[np.int64]) -> NDArray[np.uint64]:
    """The 64-bit stream seed of each run (ogk.sil.seeds)."""
    return np.array([run_seed(seed, int(i)) for i in ids], dtype=np.uint64)


@dataclasses.dataclass(frozen=True)
class JudgedChunk:
    """The job handed to the runner, the Dask executor and `ogk replay`: flies a chunk, stamps each
    run's id and seed, judges it (on one BLAS thread, as everything in ogk.sil: its __init__)."""

    plan: CampaignPlan
    seed: int

    def __call__(self, ids: NDArray[np.int64]) -> list[Record]:
        seeds = seeds_of(self.seed, ids)
        out = []
        for i, s, rec in zip(ids, seeds, self.plan.fly(ids, seeds)):
            rec = {"run_id": int(i), "run_seed": int(s), **rec}
            rec["failure"] = str(rec.get("failure") or "") or self.plan.judge(rec)
            out.append(rec)
        return out


def fly_campaign(plan: CampaignPlan, runs: int, seed: int, workers: int = 1, *,
                 run_ids: Sequence[int] | None = None, chunk_runs: int | None = None,
                 chunks: int | None = None, watchdog: Watchdog | None = None,
                 run_log: str | Path | None = None, resume: bool = False,
                 progress: bool | None = None, executor: Any = None) -> Flown:
    """Flies runs 0..runs-1 (or `run_ids`) of `plan`. With `run_log` each finished chunk's
    records are appended as they complete, and `resume` keeps the records of an earlier campaign
    with the same key and flies only the others. Raises CampaignAborted on a fault and
    CampaignInterrupted on Ctrl-C / SIGTERM (the finished runs stay in the run log).
    `executor`: None, the forked workers of ogk.sil.runner; or an object with
    `run(plan, seed, ids, chunk_runs, watchdog, on_chunk) -> (workers, cpu_s)` flying the same
    JudgedChunk elsewhere (ogk.sil.dask_executor.DaskExecutor); the run log is the same."""
    t0 = time.perf_counter()
    ids = run_ids_for(runs, run_ids)
    log = None if run_log is None else RunLog(run_log, plan.key(seed), resume=resume)
    records: dict[int, Record] = {} if log is None else dict(log.records)
    todo = np.array([i for i in ids.tolist() if i not in records], dtype=np.int64)
    bar = Progress(f"{plan.mission}: {plan.family} campaign", int(ids.size), enabled=progress,
                   done=int(ids.size - todo.size))

    def keep(chunk_ids: NDArray[np.int64], recs: list[Record]) -> None:
        if log is not None:
            log.append(recs)
        records.update((int(r["run_id"]), r) for r in recs)
        bar.advance(len(recs), sum(1 for r in recs if r["failure"]))

    cpu_s = 0.0
    used = 1
    if todo.size:
        wd = watchdog or Watchdog(per_run_s=plan.watchdog_per_run_s)
        size = chunk_runs or DEFAULT_CHUNK_RUNS
        try:
            if executor is not None:
                used, cpu_s = executor.run(plan, int(seed), todo, size, wd, keep)
            else:
                _, used, cpu_s = run_chunks(JudgedChunk(plan, int(seed)), todo, workers, chunks,
                                            chunk_runs=size, watchdog=wd, on_chunk=keep)
        except KeyboardInterrupt:
            kept = sum(1 for i in ids.tolist() if i in records)
            where = (f"{kept} of {ids.size} runs kept in {log.path}; the same command with "
                     f"--resume flies the rest" if log is not None
                     else f"{kept} of {ids.size} runs finished, no run log: lost")
            raise CampaignInterrupted(where) from None
        finally:
            bar.close()
    else:
        bar.close()
    return Flown(plan=plan, seed=int(seed), records=[records[i] for i in ids.tolist()],
                 workers=used, wall_s=time.perf_counter() - t0, cpu_s=cpu_s,
                 resumed_runs=int(ids.size - todo.size))
