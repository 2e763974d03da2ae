"""Processor in the loop (docs/guides/pil.md): a family's flight program on an emulated target (TARGETS:
the Cortex-M7 under qemu-system-arm, or big-endian SPARC V8 Linux user mode under qemu-sparc32plus),
talked to over the link (ogk.sil.target_link), with the instructions of every entry-point call counted
by QEMU's insn_count plugin and the stack of every call measured on the target (painted window).

`PilSession(program)` starts one QEMU for a sequence of runs. A family's chunk flight
  * `exchange(kind, values)` at every step (binary64 values in and out; or `send` to several
    sessions, then `receive` from each, so that their QEMUs compute at once),
  * `end_run(run_id)` after each run (the target answers with its stack per entry point),
  * `close()` at the end of the chunk: the plugin's call log (one line `NAME COUNT` per returned
    call, cut into steps and runs by the program's markers) becomes, per run and entry point, the
    record keys of `entry_keys`:
      pil.<entry>.calls, .insn_median, .insn_max, .insn_max_step (the step of the maximum, from 0),
      .stack_bytes (deepest stack of the run's calls below the caller's stack pointer).
The engine summarises those keys over the campaign (ogk.sil.target_summary).

The session loop of a family's target job is written once, here: `fly_runs_on_target` flies a chunk
run by run on one or more sessions (each session takes the chunk's next run when it is free), or,
given `fly_batch`, in lock step: `sessions` runs at a time, one per session (orbit injection: a
batch of runs under one vectorised truth); it ends each run and hands back the results with their
pil.* keys. A family gives only how one run (or one batch) is flown.
"""
from __future__ import annotations

import dataclasses
import subprocess
import tempfile
import threading
from collections.abc import Callable, Sequence
from functools import lru_cache
from pathlib import Path
from typing import Any, TypeVar

import numpy as np
from numpy.typing import NDArray
from ogk_host.paths import WORK_ROOT

from .target_link import ERROR, TargetLink, TargetLinkError, f64_payload, f64_values

RUN_END = 16                        #: OGK_PIL_RUN_END (port/cortex-m7/pil/ogk_pil.h)
TICK_MARK = "ogk_pil_tick_mark"     #: called by the program after every step it answers
RUN_MARK = "ogk_pil_run_mark"       #: ... and after every run
TARGETS = ("host", "m7", "sparc", "m4f")   #: where a campaign's flight software runs
#: target -> the nm that reads its flight programs' symbols
NM = {"m7": "arm-none-eabi-nm", "sparc": "sparc64-linux-gnu-nm", "m4f": "arm-none-eabi-nm"}
#: target -> the precision of its kernel (ogk_real_t): the M4F flies the float kernel
#: the instruction-counting QEMU plugin, built by the repository (make qemu-plugin)
PLUGIN = WORK_ROOT / "build" / "qemu-plugin" / "libinsn_count.so"


@dataclasses.dataclass(frozen=True)
class FlightProgram:
    """One scenario's flight program: the ELF and its entry points in the order of its stack slots."""

    elf: Path
    entry_points: tuple[str, ...]
    timeout_s: float = 30.0         #: the longest a step may take on QEMU
    target: str = "m7"              #: the processor it is built for (TARGETS, not "host")


def target_why(target: str, why: str) -> str:
    """A family's reason why host and target differ (written for the Cortex-M7 and newlib), with
    what is different on SPARC V8 and on the single-precision Cortex-M4F."""
    if target == "m4f":
        return ("the Cortex-M4F flies the single-precision kernel (ogk_real_t float): every value is "
                "rounded to binary32 at the program's boundary (ogk_pil.h) and every operation of "
                "the flight software in binary32 (eps 1.2e-7), which the closed loop carries to the "
                "end of the flight; report only, the scenario's acceptance judged on the target's "
                "runs (the double targets' reasons and bounds: " + why + ")")
    if target != "sparc":
        return why
    return ("on SPARC V8 both sides use glibc's libm (the target's built for v8plus, not x86-64's), "
            "so the differences are those of the libm builds and of the code generation; the "
            "Cortex-M7's reasons and bounds: " + why)


@lru_cache(maxsize=16)
def _symbols(elf: str, mtime_ns: int, nm: str = "arm-none-eabi-nm") -> dict[str, int]:
    """Function name -> address (Thumb bit cleared; SPARC instructions are 4-aligned) of an ELF."""
    out = subprocess.run([nm, "-S", elf], check=True, capture_output=True, text=True).stdout
    syms: dict[str, int] = {}
    for line in out.splitlines():
        parts = line.split()
        if len(parts) == 4 and parts[2] in ("T", "t") and parts[3] not in syms:
            syms[parts[3]] = int(parts[0], 16) & ~1
    return syms


def plugin_arguments(program: FlightProgram, calls_path: Path, report_path: Path) -> str:
    """The -plugin argument: one fn= item per entry point and marker, the call log, the report."""
    from .pil_build import ensure_plugin     # built on demand, as the flight programs are
    ensure_plugin(PLUGIN)
    syms = _symbols(str(program.elf), program.elf.stat().st_mtime_ns, NM[program.target])
    items = []
    for name in (*program.entry_points, TICK_MARK, RUN_MARK):
        if name not in syms:
            raise TargetLinkError(f"{program.elf.name}: no function {name}")
        items.append(f"fn={name}@0x{syms[name]:08x}")
    return ",".join([str(PLUGIN), *items, f"calls={calls_path}", f"out={report_path}"])


@dataclasses.dataclass
class _RunCalls:
    counts: dict[str, list[int]]
    steps: dict[str, list[int]]


def parse_calls(lines: Sequence[str], entry_points: Sequence[str]) -> list[_RunCalls]:
    """The call log cut into runs (at RUN_MARK) and steps (at TICK_MARK): per run and entry point,
    every call's instruction count and the step it belongs to."""
    runs: list[_RunCalls] = []
    cur = _RunCalls({e: [] for e in entry_points}, {e: [] for e in entry_points})
    step = 0
    for line in lines:
        name, _, count = line.partition(" ")
        if name == TICK_MARK:
            step += 1
        elif name == RUN_MARK:
            runs.append(cur)
            cur = _RunCalls({e: [] for e in entry_points}, {e: [] for e in entry_points})
            step = 0
        elif name in cur.counts:
            cur.counts[name].append(int(count))
            cur.steps[name].append(step)
    return runs


def entry_keys(calls: _RunCalls, stack: Sequence[int], overflow: int,
               entry_points: Sequence[str]) -> dict[str, Any]:
    """The record keys of one run (module doc)."""
    out: dict[str, Any] = {}
    for slot, e in enumerate(entry_points):
        c = np.asarray(calls.counts[e], dtype=np.int64)
        k = int(np.argmax(c)) if c.size else -1
        out[f"pil.{e}.calls"] = int(c.size)
        out[f"pil.{e}.insn_median"] = float(np.median(c)) if c.size else None
        out[f"pil.{e}.insn_max"] = int(c[k]) if c.size else None
        out[f"pil.{e}.insn_max_step"] = int(calls.steps[e][k]) if c.size else None
        out[f"pil.{e}.stack_bytes"] = int(stack[slot]) if c.size else None
        if overflow & (1 << slot):
            out[f"pil.{e}.stack_window_exceeded"] = True
    return out


class PilSession:
    """One flight program on QEMU for a chunk of runs (module doc)."""

    def __init__(self, program: FlightProgram) -> None:
        self.program = program
        self._dir = tempfile.TemporaryDirectory(prefix="ogk-pil-")
        self._calls = Path(self._dir.name) / "calls.log"
        plugin = plugin_arguments(program, self._calls, Path(self._dir.name) / "report.txt")
        self.link = TargetLink(program.elf, timeout_s=program.timeout_s,
                               extra_args=("-plugin", plugin), target=program.target)
        self._runs: list[int] = []
        self._stack: list[tuple[list[int], int]] = []
        self.exchanges = 0

    def exchange(self, kind: int, values: NDArray[np.float64] | Sequence[float]
                 ) -> NDArray[np.float64]:
        """One step: values out, the reply's values back (a reply of another kind: TargetLinkError)."""
        self.send(kind, values)
        return self.receive(kind)

    def send(self, kind: int, values: NDArray[np.float64] | Sequence[float]) -> None:
        """The first half of an exchange (several sessions then compute at once)."""
        self.link.send(kind, f64_payload(np.asarray(values, dtype=np.float64)))

    def receive(self, kind: int) -> NDArray[np.float64]:
        """The second half: the reply of `kind`."""
        got, payload = self.link.receive()
        self.exchanges += 1
        if got != kind:
            what = f"error code {payload[0]}" if got == ERROR and payload else f"frame type {got}"
            raise TargetLinkError(f"{self.program.elf.name}: {what} in reply to frame type {kind}")
        return f64_values(payload)

    def end_run(self, run_id: int) -> None:
        got, payload = self.link.exchange(RUN_END, b"")
        n = len(self.program.entry_points)
        if got != RUN_END or len(payload) != 4 * (n + 1):
            raise TargetLinkError(f"{self.program.elf.name}: bad RUN_END reply (type {got}, "
                                  f"{len(payload)} bytes)")
        words = np.frombuffer(payload, dtype="<u4").astype(np.int64)
        self._runs.append(int(run_id))
        self._stack.append(([int(w) for w in words[:n]], int(words[n])))

    def close(self) -> dict[int, dict[str, Any]]:
        """Ends the program; run id -> its pil.* record keys."""
        try:
            code = self.link.close()
            if code != 0:
                raise TargetLinkError(f"{self.program.elf.name} ended with exit {code}: "
                                      f"{self.link.output.strip()[-300:]}")
            lines = self._calls.read_text().splitlines() if self._calls.exists() else []
        finally:
            self._dir.cleanup()
        runs = parse_calls(lines, self.program.entry_points)
        if len(runs) != len(self._runs):
            raise TargetLinkError(f"{self.program.elf.name}: the call log has {len(runs)} runs, "
                                  f"{len(self._runs)} were flown")
        return {rid: entry_keys(calls, stack, overflow, self.program.entry_points)
                for rid, calls, (stack, overflow) in zip(self._runs, runs, self._stack)}

    def kill(self) -> None:
        self.link.kill()
        self._dir.cleanup()


R = TypeVar("R")


def _fly_sessions(program: FlightProgram, n: int, fly: Callable[[list[PilSession]], R]
                  ) -> tuple[R, dict[int, dict[str, Any]]]:
    """Starts `n` sessions of `program`, calls `fly(sessions)`, ends them: (fly's result, run id ->
    its pil.* record keys, for every run the sessions ended with `end_run`). Any error kills every
    session's QEMU and propagates."""
    sessions: list[PilSession] = []
    try:
        sessions = [PilSession(program) for _ in range(n)]
        out = fly(sessions)
        keys: dict[int, dict[str, Any]] = {}
        for s in sessions:
            keys.update(s.close())
    except BaseException:
        for s in sessions:
            s.kill()
        raise
    return out, keys


#: fly_batch(sessions, run_ids, run_seeds) -> one result per run: run i on sessions[i], in lock step
FlyBatch = Callable[[list[PilSession], list[int], list[int]], Sequence[R]]


def fly_runs_on_target(program: FlightProgram, run_ids: Sequence[int], run_seeds: Sequence[int],
                       fly_run: Callable[[PilSession, int, int], R] | None = None,
                       sessions: int = 1, *, fly_batch: FlyBatch[R] | None = None
                       ) -> tuple[list[R], dict[int, dict[str, Any]]]:
    """A chunk's runs on `sessions` QEMUs of `program`. `fly_run(session, run_id, run_seed)` flies
    one run on a free session (with one session, in run order in this thread; with more, each in
    its own thread taking the chunk's next run); or `fly_batch(sessions, run_ids, run_seeds)` flies
    the chunk's next `sessions` runs together, run i on session i (lock step: a family whose host
    side is vectorised over the runs). Each session then ends its run. Returns (the results in run
    order, run id -> the run's pil.* record keys). An error in any run kills every session's QEMU
    and propagates."""
    from concurrent.futures import FIRST_EXCEPTION, ThreadPoolExecutor, wait

    if (fly_run is None) == (fly_batch is None):
        raise TypeError("fly_runs_on_target: give exactly one of fly_run and fly_batch")
    ids = [int(i) for i in run_ids]
    seeds = [int(s) for s in run_seeds]
    n = max(1, min(int(sessions), len(ids)))
    results: list[Any] = [None] * len(ids)

    def fly_one(s: PilSession, k: int) -> None:
        assert fly_run is not None
        results[k] = fly_run(s, ids[k], seeds[k])
        s.end_run(ids[k])

    def in_order(ss: list[PilSession]) -> None:
        for k in range(len(ids)):
            fly_one(ss[0], k)

    def in_threads(ss: list[PilSession]) -> None:
        queue = iter(range(len(ids)))
        lock = threading.Lock()

        def take(s: PilSession) -> None:
            while True:
                with lock:
                    k = next(queue, None)
                if k is None:
                    return
                fly_one(s, k)

        with ThreadPoolExecutor(max_workers=n, thread_name_prefix="ogk-pil") as pool:
            futures = [pool.submit(take, s) for s in ss]
            done, _ = wait(futures, return_when=FIRST_EXCEPTION)
            if any(f.exception() is not None for f in done):
                for s in ss:            # the other threads' links fail at once
                    s.kill()
            for f in futures:
                f.result()

    def in_lock_step(ss: list[PilSession]) -> None:
        assert fly_batch is not None
        for g in range(0, len(ids), len(ss)):
            batch = range(g, min(g + len(ss), len(ids)))
            out = list(fly_batch(ss[:len(batch)], ids[g:batch.stop], seeds[g:batch.stop]))
            if len(out) != len(batch):
                raise ValueError(f"fly_batch returned {len(out)} results for {len(batch)} runs")
            for s, k, result in zip(ss, batch, out):
                results[k] = result
                s.end_run(ids[k])

    fly = in_lock_step if fly_batch is not None else in_order if n == 1 else in_threads
    _, keys = _fly_sessions(program, n, fly)
    return results, keys
