"""The Dask executor of the campaign engine (`ogk mc SCENARIO ... --dask ADDRESS|local:N`;
docs/guides/scale-out.md): the same chunks as the forked runner (ogk.sil.runner.split_chunks), flown on
the workers of a Dask cluster, for every family and target.

The campaign goes out once as a `Shipment` (ogk.sil.shipping: scenario, options, ground products
with their SHA-256), as the result of a task of its own rather than scattered data: the scheduler's
memory manager keeps one replica of scattered data, and a worker lost with it would take every chunk
with it ("already forgotten"), where a task's result is recomputed on another worker. Each chunk is a
task `fly_chunk(shipment, seed, run_ids)` that rebuilds the plan on the worker (once per process,
checked against the shipment)
and returns the records of `JudgedChunk`, the very job of the local runner, so a run's record is
the same bit for bit whichever executor flew it. Records come back as each chunk finishes and go
to the engine's `on_chunk` (the run log: resume works across executors).

Faults, in one line as the local runner's (CampaignAborted naming the chunk's runs):
  * a run raised on a worker: its exception and kernel status;
  * a worker lost mid-chunk (killed, its machine gone): the scheduler re-runs that chunk elsewhere,
    the finished chunks are kept (their results are already here); only a chunk that killed
    `distributed.scheduler.allowed-failures` + 1 workers (default 4) aborts the campaign;
  * no chunk finished for the watchdog's limit of one chunk (120 s + S per run; PLAN_ALLOWANCE_S
    more until the first chunk finishes, since it also rebuilds the plan): the chunks in flight
    are named and cancelled.
Ctrl-C or SIGTERM cancels the chunks and raises KeyboardInterrupt (the engine keeps the log).
"""
from __future__ import annotations

import dataclasses
import logging
import os
import signal
import time
import uuid
from collections.abc import Callable
from typing import Any

import numpy as np
from numpy.typing import NDArray
from ogk_bindings.errors import OgkInputError
from ogk_bindings.extras import need

from .engine import JudgedChunk
from .family import CampaignPlan, MissionFamily, Record
from .runner import CampaignAborted, Watchdog, describe_error, split_chunks
from .shipping import Shipment, plan_of, ship

#: seconds to wait for a scheduler named by --dask ADDRESS
CONNECT_TIMEOUT_S = 15
#: the watchdog's extra allowance until the first chunk finishes: every worker's first chunk also
#: rebuilds the plan (binary family ~30 s of CPU; ten times that on a crowded machine: an OI
#: warm-up chunk once took 116 s at load average 23, next to the 122 s limit)
PLAN_ALLOWANCE_S = 600.0


def fly_chunk(shipment: Shipment, seed: int, run_ids: list[int]) -> tuple[list[Record], float]:
    """The task of one chunk, on a worker: its records (run-id order) and the CPU seconds."""
    cpu0 = time.process_time()
    plan = plan_of(shipment)
    records = JudgedChunk(plan, int(seed))(np.asarray(run_ids, dtype=np.int64))
    return records, time.process_time() - cpu0


def shipment_task(shipment: Shipment) -> Shipment:
    """The task whose result is the campaign's shipment (module doc: recomputable if lost)."""
    return shipment


def check_address(spec: str) -> str:
    """`local:N` (N >= 1) or a scheduler address (tcp://HOST:PORT, HOST:PORT): one line if not."""
    if spec.startswith("local:"):
        n = spec[len("local:"):]
        if not n.isdigit() or int(n) < 1:
            raise OgkInputError(f"local:N needs a worker count N >= 1, got {spec!r}", key="--dask")
        return spec
    if "://" not in spec and ":" not in spec:
        raise OgkInputError(f"expected local:N or a scheduler address HOST:PORT, got {spec!r}",
                            key="--dask")
    return spec


@dataclasses.dataclass
class DaskExecutor:
    """A Dask client for the engine (module doc); a context manager (`local:N` starts and stops
    its own cluster of N single-threaded worker processes on 127.0.0.1)."""

    address: str
    family: MissionFamily
    client: Any = None
    cluster: Any = None

    def __enter__(self) -> DaskExecutor:
        distributed = need("distributed", "dask", "ogk mc --dask")
        Client, LocalCluster = distributed.Client, distributed.LocalCluster
        check_address(self.address)
        if self.address.startswith("local:"):
            self.cluster = LocalCluster(n_workers=int(self.address.split(":", 1)[1]),
                                        threads_per_worker=1, processes=True, host="127.0.0.1",
                                        dashboard_address=None, silence_logs=logging.ERROR)
            self.client = Client(self.cluster)
        else:
            try:
                self.client = Client(self.address, timeout=f"{CONNECT_TIMEOUT_S}s")
            except (OSError, TimeoutError) as exc:
                raise OgkInputError(f"no Dask scheduler answered at {self.address} "
                                    f"({describe_error(exc)[0]})", key="--dask") from None
        return self

    def __exit__(self, *exc: object) -> None:
        if self.client is not None:
            self.client.close()
        if self.cluster is not None:
            self.cluster.close()
        self.client = self.cluster = None

    def workers(self) -> int:
        """Worker threads in the cluster now (each flies one chunk at a time)."""
        info = self.client.scheduler_info()["workers"]
        return max(1, sum(int(w.get("nthreads", 1)) for w in info.values()))

    def run(self, plan: CampaignPlan, seed: int, ids: NDArray[np.int64], chunk_runs: int,
            watchdog: Watchdog, on_chunk: Callable[[NDArray[np.int64], list[Record]], None]
            ) -> tuple[int, float]:
        """Flies `ids` in chunks of at most `chunk_runs` on the cluster; `on_chunk` as each
        finishes. Returns the worker count and the CPU seconds (workers' and this process's)."""
        wait = need("distributed", "dask", "ogk mc --dask").wait
        workers = self.workers()
        pieces = split_chunks(ids, workers, None, chunk_runs)
        cpu0 = os.times()
        tag = uuid.uuid4().hex[:12]
        shipment = self.client.submit(shipment_task, ship(plan, self.family),
                                      key=f"ogk-shipment-{tag}", pure=False, priority=1)
        pending = {self.client.submit(fly_chunk, shipment, int(seed), p.tolist(),
                                      key=f"ogk-chunk-{tag}-{k}", priority=-k, pure=False): k
                   for k, p in enumerate(pieces)}
        limit = watchdog.limit_s(max(p.size for p in pieces))
        worker_cpu = 0.0
        wait_s = limit + PLAN_ALLOWANCE_S
        old_term = _sigterm_raises()
        try:
            while pending:
                try:
                    done, _ = wait(list(pending), timeout=wait_s, return_when="FIRST_COMPLETED")
                except TimeoutError:
                    flying = self._in_flight(tag, pieces)
                    raise CampaignAborted(f"watchdog: no chunk finished for {wait_s:.0f} s "
                                          f"({watchdog.base_s:g} s + {watchdog.per_run_s:g} s per "
                                          f"run); chunks in flight cancelled", flying) from None
                wait_s = limit
                for fut in sorted(done, key=lambda f: pending[f]):
                    k = pending.pop(fut)
                    records, cpu = self._result(fut, pieces[k])
                    worker_cpu += cpu
                    on_chunk(pieces[k], records)
        finally:
            self.client.cancel(list(pending) + [shipment], force=True)
            if old_term is not None:
                signal.signal(signal.SIGTERM, old_term)
        cpu1 = os.times()
        own = (cpu1.user - cpu0.user) + (cpu1.system - cpu0.system)
        return workers, worker_cpu + own

    @staticmethod
    def _result(fut: Any, piece: NDArray[np.int64]) -> tuple[list[Record], float]:
        KilledWorker = need("distributed.scheduler", "dask", "ogk mc --dask").KilledWorker
        if fut.status == "error":
            exc = fut.exception()
            if isinstance(exc, KilledWorker):
                raise CampaignAborted(f"the chunk's workers died each time it ran ({exc})",
                                      piece.tolist())
            reason, status = describe_error(exc)
            raise CampaignAborted(f"worker raised {reason}", piece.tolist(), status)
        if fut.status == "cancelled":
            raise CampaignAborted("the scheduler cancelled the chunk", piece.tolist())
        records, cpu = fut.result()
        fut.release()
        return records, float(cpu)

    def _in_flight(self, tag: str, pieces: list[NDArray[np.int64]]) -> list[int]:
        keys = [str(k) for ks in self.client.processing().values() for k in ks]
        chunks = sorted(int(k.rsplit("-", 1)[1]) for k in keys if k.startswith(f"ogk-chunk-{tag}-"))
        return [int(i) for k in chunks for i in pieces[k]]


def _raise_keyboard_interrupt(signum: int, frame: Any) -> None:
    raise KeyboardInterrupt(f"signal {signum}")


def _sigterm_raises() -> Any:
    """SIGTERM as Ctrl-C while a campaign waits on the cluster (as in ogk.sil.runner)."""
    try:
        return signal.signal(signal.SIGTERM, _raise_keyboard_interrupt)
    except ValueError:          # not the main thread
        return None
