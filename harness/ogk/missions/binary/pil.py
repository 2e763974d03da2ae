"""Binary-asteroid BLT on the emulated Cortex-M7 (docs/guides/flight-integration-blt.md, docs/guides/pil.md): the flight
program port/cortex-m7/pil/blt_pil.c holds the corrector contexts (blt_flight.c, static storage) and makes
every corrector call (ogk_blt_solve: NRPC, LM or hybrid) the host's campaign would make through cffi, on
the same inputs; the host keeps the nominal design, the dispersions, the DOP853 checks and the judging.

  * `ogk mc SCENARIO --target m7` (family.py `_on_target`): TargetJob flies the chunk's runs with
    convergence_run.fly_run on TargetCorrector contexts (one exchange per corrector call), configured from the
    generated flight configuration (flight_config.py).
  * `corrections_on_target(session)`: every corrector call of the ground's design (guess stage,
    continuations) made on the target, each solve's configuration uplinked first (the continuations
    re-scale the model per solve); `python -m ogk.missions.binary.pil_transfers SCENARIO` flies the
    scenario's transfers so, beside the host's (pil_transfers.py).
"""
from __future__ import annotations

import contextlib
import dataclasses
import hashlib
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray
from ogk_bindings._ffi import ffi
from ogk_bindings.blt import BltConfig, BltReport, Transfer, _report
from ogk_bindings.kernel import _check, status_name

from ogk.sil.pil import FlightProgram, PilSession, fly_runs_on_target
from ogk.sil.pil_build import PIL_BUILD, build_program
from ogk.sil.target_link import TargetLinkError

from . import convergence_run
from .flight_config import SLOTS, slot_configs

BLT_INIT, BLT_LOAD, BLT_SOLVE = 32, 33, 34      #: frame types of blt_pil.c
#: the entry points of the program, in its stack-slot order (blt_flight.h)
ENTRY_POINTS = ("ogk_blt_init", "ogk_blt_solve")
#: blt_flight.h ogk_blt_flight_action
ACTIONS = {0: "fly", 1: "safe", 2: "reject", 3: "abort"}

#: Host vs target on the same draws (docs/guides/flight-integration-blt.md, "Host vs target"). The
#: iterations must be the same (bound 0); |e| of the returned transfer may differ by what libm's
#: ulps make of it: the model calls sin/cos (the Sun's direction, eqs. 9-10) and newlib's are not
#: glibc's; a Newton step amplifies a last-bit difference of the error vector, so |e| (1e-9 ... 5e-5)
#: is compared absolutely at 1e-12 (measured: <= 1.8e-14 on moshup's 24-run target campaign, docs).
#: The DOP853 check of the converged transfer carries the same difference.
BOUNDS = {**{f"{c}.iterations": 0.0 for c in SLOTS},
          **{f"{c}.err_norm": 1e-12 for c in SLOTS},
          **{f"{c}.dop853_err_norm": 1e-12 for c in SLOTS}}
BOUNDS_WHY = ("the same C on both sides (ogk_blt_solve on the same configuration and guess); the "
              "model's sin/cos (Sun direction, SRP and tide) come from newlib on the target and "
              "glibc on the host, a few ulp apart, and the Newton iterations carry that to |e|; "
              "gcc contracts no FMA in ISO C mode on either side")


# ------------------------------------------------------------------------------------------ flattening
# The frames carry the kernel structs flattened in declaration order (blt_pil.c), arrays at their
# full compile-time length, integers as exact doubles: the walk below follows the cffi types, so a
# field added to a struct changes the length and the program's length check refuses the frame.

def _flatten(ctype: Any, value: Any, out: list[float]) -> None:
    if ctype.kind == "struct":
        for name, field in ctype.fields:
            _flatten(field.type, getattr(value, name), out)
    elif ctype.kind == "array":
        for i in range(ctype.length):
            _flatten(ctype.item, value[i], out)
    else:
        out.append(float(value))


def _fill(ctype: Any, owner: Any, key: Any, values: Iterator[float]) -> None:
    """owner[key] / owner.key = the next values, by ctype."""
    value = owner[key] if isinstance(key, int) else getattr(owner, key)
    if ctype.kind == "struct":
        for name, field in ctype.fields:
            _fill(field.type, value, name, values)
    elif ctype.kind == "array":
        for i in range(ctype.length):
            _fill(ctype.item, value, i, values)
    else:
        x = next(values)
        v: Any = float(x) if ctype.cname == "double" else int(x)
        if isinstance(key, int):
            owner[key] = v
        else:
            setattr(owner, key, v)


def flatten(cdata_ptr: Any) -> list[float]:
    out: list[float] = []
    _flatten(ffi.typeof(cdata_ptr).item, cdata_ptr[0], out)
    return out


def unflatten(ctype: str, values: NDArray[np.float64]) -> Any:
    """A new `ctype[1]` filled from values (the walk of flatten); it owns the memory: keep it alive
    while its element is read."""
    box = ffi.new(f"{ctype}[1]")
    it = iter(values.tolist())
    _fill(ffi.typeof(ctype), box, 0, it)
    return box


REPORT_N = len(flatten(ffi.new("ogk_blt_report_t *")))
TRANSFER_N = len(flatten(ffi.new("ogk_blt_transfer_t *")))


# ------------------------------------------------------------------------------------------ the program

def flight_program(nominal: convergence_run.Nominal, scenario_path: Path,
                   flight_config: Callable[[Path], object], target: str = "m7") -> FlightProgram:
    """The scenario's flight program for the corrector configurations of its Monte Carlo nominal
    (a build per distinct configuration set: the key is the SHA-256 of their values), its
    generated C written by `flight_config(DIR)` into DIR/c (the family's flight_config)."""
    configs = slot_configs(nominal)
    key = hashlib.sha256(np.array([v for c in configs for v in flatten(c.to_c())]).tobytes())
    out = PIL_BUILD / "binary" / f"{Path(scenario_path).stem}-{key.hexdigest()[:12]}"
    return FlightProgram(build_program("blt", out, lambda c_dir: flight_config(c_dir.parent),
                                       target), ENTRY_POINTS, target=target)


class TargetCorrector:
    """convergence_run.fly_run's corrector (the `solve` of ogk_bindings.blt.Blt) on a slot of the program:
    one BLT_SOLVE exchange per call."""

    def __init__(self, session: PilSession, slot: int, n_segments: int, n_nodes: int) -> None:
        self.session, self.slot = session, slot
        self.n_segments, self.n_nodes = n_segments, n_nodes
        self.last_action = ""

    def solve(self, guess: Transfer) -> tuple[Transfer, BltReport]:
        r = self.session.exchange(BLT_SOLVE, [float(self.slot), *flatten(guess.to_c())])
        if r.size != 2 + REPORT_N + TRANSFER_N:
            raise TargetLinkError(f"BLT_SOLVE reply of {r.size} values")
        status = int(r[0])
        self.last_action = ACTIONS.get(int(r[1]), str(r[1]))
        if status_name(status) not in ("OGK_OK", "OGK_E_NOT_CONVERGED", "OGK_E_ITER_LIMIT"):
            _check(status, "ogk_blt_solve")            # bad input: KernelError, as the host's Blt
        rep_box = unflatten("ogk_blt_report_t", r[2:2 + REPORT_N])    # (the boxes own the memory:
        sol_box = unflatten("ogk_blt_transfer_t", r[2 + REPORT_N:])   # keep them while reading)
        rep = _report(status, rep_box[0])
        return Transfer.from_c(sol_box[0], self.n_segments, self.n_nodes), rep


def configure(session: PilSession, slot: int, cfg: BltConfig | None = None) -> None:
    """Slot `slot` configured from the generated configuration (cfg None: BLT_INIT) or from cfg
    (BLT_LOAD, the ground's uplink). TargetLinkError when the flight software aborts."""
    if cfg is None:
        r = session.exchange(BLT_INIT, [float(slot)])
    else:
        r = session.exchange(BLT_LOAD, [float(slot), *flatten(cfg.to_c())])
    if int(r[0]) != 0:
        _check(int(r[1]), "ogk_blt_init (on the target)")
        raise TargetLinkError(f"slot {slot}: the flight software answered {ACTIONS.get(int(r[0]))}")


@dataclasses.dataclass(frozen=True)
class TargetJob:
    """The chunk flight of `ogk mc --target m7`: one QEMU per chunk; each run re-initialises the
    contexts from the generated configuration (BLT_INIT), then convergence_run.fly_run with the host's draw
    (the same run stream) makes its corrector calls on them."""

    nominal: convergence_run.Nominal
    correctors: tuple[str, ...]
    levels: tuple[float, ...]                 #: [%]
    sigma: float
    program: FlightProgram

    def __call__(self, run_ids: NDArray[np.int64], run_seeds: NDArray[np.uint64]
                 ) -> list[dict[str, Any]]:
        from ogk.sil.seeds import run_generator
        n_seg = int(self.nominal.transfer.segments.shape[0])
        n_nodes = len(self.nominal.layout.free_nodes)

        def fly_on_session(session: PilSession, run_id: int, run_seed: int) -> dict[str, Any]:
            solvers = {name: TargetCorrector(session, SLOTS.index(name), n_seg, n_nodes)
                       for name in self.correctors}
            for name in self.correctors:      # each run: a fresh init of its contexts
                configure(session, SLOTS.index(name))
            level = self.levels[run_id % len(self.levels)]
            return convergence_run.fly_run(self.nominal, solvers, level / 100.0, self.sigma,
                                           run_generator(run_seed))

        records, keys = fly_runs_on_target(self.program, run_ids, run_seeds, fly_on_session)
        for rid, rec in zip(run_ids, records):
            # (timing.<corrector>.cpu_ms stays: here the host's CPU during the exchange; the
            # target's cost is pil.ogk_blt_solve.insn_*)
            rec.update(keys[int(rid)])
        return records


# ------------------------------------------------------------------------------------------ the transfers

@contextlib.contextmanager
def corrections_on_target(session: PilSession) -> Iterator[list[dict[str, Any]]]:
    """Within: every corrector solve of the ground's design (ogk_host.binary.design.solve) made on the
    target, its configuration uplinked first (BLT_LOAD to slot 0, then BLT_SOLVE). Yields the list the
    solves are logged to."""
    from ogk_host.binary import design

    log: list[dict[str, Any]] = []

    class _OnTarget:
        def __init__(self, cfg: BltConfig) -> None:
            configure(session, 0, cfg)
            self._c = TargetCorrector(session, 0, int(cfg.n_segments), int(cfg.n_free_nodes))

        def solve(self, guess: Transfer) -> tuple[Transfer, BltReport]:
            sol, rep = self._c.solve(guess)
            log.append(dict(status=rep.status, iterations=rep.iterations, err_norm=rep.err_norm,
                            action=self._c.last_action))
            return sol, rep

    saved = design.Blt
    design.Blt = _OnTarget        # type: ignore[assignment,misc]
    try:
        yield log
    finally:
        design.Blt = saved        # type: ignore[misc]
