"""Mission-independent campaign runner: runs split in chunks over forked worker processes, with a
watchdog, fault reporting and a result per chunk as soon as it is done.

A mission hands the runner a *job*: a callable `job(run_ids) -> chunk result` that flies the given
runs (all at once, vectorised) and returns whatever the mission merges. The job is installed in the
parent before the fork, so workers inherit it (nominal solutions, tables, bindings) without
pickling; only run ids go out and chunk results come back (pickled through a pipe).

Faults end the campaign with `CampaignAborted`, whose message names the runs of the chunk and what
happened, in one line:
  * the job raised (a `KernelError` keeps its status name, e.g. OGK_E_TABLE_CRC);
  * a worker died (killed by a signal, or exited without a result);
  * a chunk ran longer than the watchdog limit `Watchdog.limit_s(runs in the chunk)`
    (default 120 s + 2 s per run; the worker is killed).
The other workers are killed at once; chunks already finished have been handed to `on_chunk`, so
a mission can keep them (ogk.sil.runlog) and resume. Ctrl-C (KeyboardInterrupt) or SIGTERM in the
parent kills the workers and raises KeyboardInterrupt; workers ignore SIGINT (the parent decides)
and die with the parent (PR_SET_PDEATHSIG on Linux).

With one worker the chunks are flown in the parent process (no fork, no watchdog), a job's error
still ends as CampaignAborted.

The same (seed, run id) gives the same numbers whatever the number of workers or chunks only if
the mission's job draws each run from its own generator and its arithmetic is elementwise over
runs (docs/guides/sil.md).
"""
from __future__ import annotations

import dataclasses
import multiprocessing as mp
import os
import signal
import time
from collections.abc import Callable, Sequence
from multiprocessing.connection import wait
from typing import Any, TypeVar

import numpy as np
from numpy.typing import NDArray

R = TypeVar("R")

_JOB: Callable[[NDArray[np.int64]], Any] | None = None  # set in the parent before the fork


class CampaignAborted(RuntimeError):
    """A campaign could not finish: a run raised, a worker died or the watchdog fired.

    `run_ids` are the runs of the chunk concerned, `reason` says what happened (one line);
    `status` is the kernel status name when a KernelError caused it."""

    def __init__(self, reason: str, run_ids: Sequence[int] = (), status: str | None = None) -> None:
        self.reason = reason
        self.run_ids = [int(i) for i in run_ids]
        self.status = status
        super().__init__(self.line())

    def line(self) -> str:
        where = f"runs {format_ids(self.run_ids)}: " if self.run_ids else ""
        return f"campaign aborted: {where}{self.reason}"

    def __reduce__(self) -> tuple[Any, ...]:
        return (type(self), (self.reason, self.run_ids, self.status))


class CampaignInterrupted(CampaignAborted):
    """Ctrl-C or SIGTERM during the flight (the mission says where the finished runs are)."""

    def line(self) -> str:
        return f"campaign interrupted: {self.reason}"


@dataclasses.dataclass(frozen=True)
class Watchdog:
    """Wall-time limit of one chunk: `base_s + per_run_s * runs in the chunk`."""

    base_s: float = 120.0
    per_run_s: float = 2.0

    def limit_s(self, n_runs: int) -> float:
        return self.base_s + self.per_run_s * n_runs


def format_ids(ids: Sequence[int]) -> str:
    """Run ids as ranges: [0, 1, 2, 5] -> "0-2, 5"."""
    ids = [int(i) for i in ids]
    parts: list[str] = []
    k = 0
    while k < len(ids):
        j = k
        while j + 1 < len(ids) and ids[j + 1] == ids[j] + 1:
            j += 1
        parts.append(str(ids[k]) if j == k else f"{ids[k]}-{ids[j]}")
        k = j + 1
    return ", ".join(parts)


def describe_error(exc: BaseException) -> tuple[str, str | None]:
    """(one-line description, kernel status name or None) of an exception raised by a job."""
    status = getattr(exc, "name", None) if hasattr(exc, "code") and hasattr(exc, "func") else None
    text = str(exc).strip().splitlines()[0] if str(exc).strip() else ""
    kind = type(exc).__name__
    return (f"{kind}: {text}" if text else kind), (str(status) if status else None)


def _call_job(run_ids: NDArray[np.int64]) -> Any:
    job = _JOB
    if job is None:  # pragma: no cover - only if a worker was not forked from run_chunks
        raise RuntimeError("campaign job not installed in this process")
    return job(run_ids)


def _die_with_parent() -> None:
    try:
        import ctypes
        libc = ctypes.CDLL(None, use_errno=True)
        libc.prctl(1, int(signal.SIGKILL))   # PR_SET_PDEATHSIG
    except (OSError, AttributeError):        # pragma: no cover - not Linux
        pass


def _worker(run_ids: NDArray[np.int64], conn: Any) -> None:
    """Body of a forked worker: the chunk's result or a failure record, never an exception
    object (which may not survive unpickling)."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    signal.pthread_sigmask(signal.SIG_UNBLOCK, _DEFERRED_SIGNALS)  # blocked by the parent's start
    _die_with_parent()
    try:
        message: tuple[str, Any] = ("ok", _call_job(run_ids))
    except BaseException as exc:  # noqa: BLE001 - everything is reported to the parent
        message = ("error", describe_error(exc))
    try:
        conn.send(message)
    except Exception as exc:  # noqa: BLE001 - e.g. a result that cannot be pickled
        conn.send(("error", (f"result not sent: {describe_error(exc)[0]}", None)))
    finally:
        conn.close()


def run_ids_for(runs: int, run_ids: Sequence[int] | None = None) -> NDArray[np.int64]:
    """Ids 0..runs-1, or the given ones (to re-fly some runs of an earlier campaign)."""
    ids = np.arange(runs, dtype=np.int64) if run_ids is None else np.asarray(run_ids, np.int64)
    if ids.size == 0:
        raise ValueError("no runs")
    return ids


def split_chunks(ids: NDArray[np.int64], workers: int, chunks: int | None = None,
                 chunk_runs: int | None = None) -> list[NDArray[np.int64]]:
    """Contiguous chunks: `chunks` of them (default one per worker), more if needed so that no
    chunk holds more than `chunk_runs` runs."""
    if ids.size == 0:
        return []
    n = max(1, min(chunks or workers, ids.size))
    if chunk_runs:
        n = max(n, -(-ids.size // int(chunk_runs)))
    return [p for p in np.array_split(ids, min(n, ids.size)) if p.size]


def _kill(procs: Sequence[Any]) -> None:
    for p in procs:
        if p.is_alive():
            try:
                os.kill(p.pid, signal.SIGKILL)
            except ProcessLookupError:  # pragma: no cover - raced with its exit
                pass
    for p in procs:
        p.join(5.0)


#: signals held back while a worker is started (_run_forked)
_DEFERRED_SIGNALS = {signal.SIGINT, signal.SIGTERM}


def _raise_keyboard_interrupt(signum: int, frame: Any) -> None:
    raise KeyboardInterrupt(f"signal {signum}")


def run_chunks(job: Callable[[NDArray[np.int64]], R], ids: NDArray[np.int64], workers: int = 1,
               chunks: int | None = None, *, chunk_runs: int | None = None,
               watchdog: Watchdog | None = None,
               on_chunk: Callable[[NDArray[np.int64], R], None] | None = None,
               ) -> tuple[list[R], int, float]:
    """Flies `ids` in chunks (`split_chunks`) on `workers` forked processes.

    `on_chunk(run_ids, result)` is called in the parent as each chunk finishes (in completion
    order). Returns the chunk results in run-id order, the number of workers used and the CPU time
    (user + system, parent and children). Raises CampaignAborted on a fault (module doc) and
    KeyboardInterrupt on Ctrl-C / SIGTERM, after killing the workers."""
    global _JOB
    watchdog = watchdog or Watchdog()
    pieces = split_chunks(ids, workers, chunks, chunk_runs)
    workers = max(1, min(int(workers), len(pieces) or 1))
    cpu_start = os.times()
    outs: list[Any] = [None] * len(pieces)
    _JOB = job
    try:
        old_term = signal.signal(signal.SIGTERM, _raise_keyboard_interrupt)
    except ValueError:  # not the main thread: SIGTERM keeps its handler
        old_term = None
    try:
        if workers == 1:
            for k, piece in enumerate(pieces):
                try:
                    outs[k] = _call_job(piece)
                except Exception as exc:
                    reason, status = describe_error(exc)
                    raise CampaignAborted(reason, piece.tolist(), status) from exc
                if on_chunk is not None:
                    on_chunk(piece, outs[k])
        else:
            _run_forked(pieces, workers, watchdog, outs, on_chunk)
    finally:
        _JOB = None
        if old_term is not None:
            signal.signal(signal.SIGTERM, old_term)
    cpu_end = os.times()
    cpu_s = sum(getattr(cpu_end, f) - getattr(cpu_start, f)
                for f in ("user", "system", "children_user", "children_system"))
    return outs, workers, cpu_s


def _run_forked(pieces: list[NDArray[np.int64]], workers: int, watchdog: Watchdog,
                outs: list[Any], on_chunk: Callable[[NDArray[np.int64], Any], None] | None) -> None:
    ctx = mp.get_context("fork")
    todo = list(range(len(pieces)))
    running: dict[int, tuple[Any, Any, float]] = {}   # chunk -> (process, connection, deadline)
    try:
        while todo or running:
            while todo and len(running) < workers:
                k = todo.pop(0)
                # Ctrl-C / SIGTERM wait until the worker is started: a KeyboardInterrupt inside
                # Process.start leaves a half-built multiprocessing finaliser that prints a
                # traceback at exit (seen once in the Ctrl-C test), after the one-line message.
                old_mask = signal.pthread_sigmask(signal.SIG_BLOCK, _DEFERRED_SIGNALS)
                try:
                    recv, send = ctx.Pipe(duplex=False)
                    proc = ctx.Process(target=_worker, args=(pieces[k], send), daemon=True)
                    proc.start()
                    send.close()
                    running[k] = (proc, recv, time.monotonic() + watchdog.limit_s(pieces[k].size))
                finally:
                    signal.pthread_sigmask(signal.SIG_SETMASK, old_mask)
            now = time.monotonic()
            timeout = max(0.0, min(d for _, _, d in running.values()) - now)
            ready = set(wait([c for _, c, _ in running.values()]
                             + [p.sentinel for p, _, _ in running.values()], timeout))
            for k in list(running):
                proc, conn, deadline = running[k]
                ids = pieces[k].tolist()
                if conn in ready or conn.poll():
                    try:
                        kind, payload = conn.recv()
                    except (EOFError, OSError):
                        kind, payload = "died", None
                elif proc.sentinel in ready:
                    kind, payload = "died", None
                elif time.monotonic() >= deadline:
                    _kill([proc])
                    raise CampaignAborted(
                        f"watchdog: no result after {watchdog.limit_s(len(ids)):.0f} s "
                        f"({watchdog.base_s:g} s + {watchdog.per_run_s:g} s per run); "
                        f"worker pid {proc.pid} killed", ids)
                else:
                    continue
                del running[k]
                conn.close()
                if kind == "ok":
                    proc.join()
                    outs[k] = payload
                    if on_chunk is not None:
                        on_chunk(pieces[k], payload)
                    continue
                if kind == "error":
                    proc.join(5.0)
                    reason, status = payload
                    raise CampaignAborted(f"worker raised {reason}", ids, status)
                proc.join(5.0)
                code = proc.exitcode
                how = f"exit code {code}"
                if code is not None and code < 0:
                    try:
                        how = f"killed by {signal.Signals(-code).name}"
                    except ValueError:
                        how = f"killed by signal {-code}"
                raise CampaignAborted(f"worker pid {proc.pid} died ({how}) without a result", ids)
    finally:
        _kill([p for p, _, _ in running.values()])
        for _, conn, _ in running.values():
            conn.close()


class CallTimeout(RuntimeError):
    """`call_with_timeout`: the call did not finish within its wall-time limit."""


def _call_in_child(fn: Callable[[], Any], conn: Any) -> None:
    _die_with_parent()
    try:
        message: tuple[str, Any] = ("ok", fn())
    except BaseException as exc:  # noqa: BLE001 - reported to the parent, which raises
        message = ("error", describe_error(exc)[0])
    try:
        conn.send(message)
    finally:
        conn.close()


def call_with_timeout(fn: Callable[[], R], timeout_s: float | None) -> R:
    """`fn()` in a forked process killed after `timeout_s` of wall time (CallTimeout); a long ground
    solve that must not hang a command. Without a limit, or inside a campaign worker (a daemon may
    not fork; the campaign's watchdog bounds it there), `fn()` runs in this process. The result
    comes back pickled; an exception as RuntimeError with its one-line description."""
    if timeout_s is None or mp.current_process().daemon:
        return fn()
    ctx = mp.get_context("fork")
    recv, send = ctx.Pipe(duplex=False)
    proc = ctx.Process(target=_call_in_child, args=(fn, send), daemon=True)
    proc.start()
    send.close()
    try:
        if not recv.poll(timeout_s):
            raise CallTimeout(f"no result after {timeout_s:g} s")
        kind, payload = recv.recv()
    except EOFError:
        kind, payload = "error", "the process died without a result"
    finally:
        _kill([proc])
        recv.close()
    if kind != "ok":
        raise RuntimeError(payload)
    return payload
