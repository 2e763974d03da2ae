"""Binary-asteroid BLT on the emulated Cortex-M7 (docs/flight-integration-blt.md, docs/pil.md): the flight
program port/cortex-m7/pil/blt_pil.c holds the corrector contexts (blt_flight.c, static storage) and makes
every corrector call (ogk_blt_solve: NRPC, LM or hybrid) the host's campaign would make through cffi, on
the same inputs; the host keeps the nominal design, the dispersions, the DOP853 checks and the judging.

  * `ogk mc SCENARIO --target m7` (family.py `_on_target`): TargetJob flies the chunk's runs with
    campaign.fly_run on TargetCorrector contexts (one exchange per corrector call), configured from the
    generated flight configuration (flight_config.py).
  * `python -m ogk.missions.binary.pil SCENARIO [--transfer NAME ...]`: the scenario's transfers designed
    twice, on the host and with every corrector call of the ground's design (guess, continuation) made on
    the target (each solve uplinks its configuration: the continuations re-scale the model per solve),
    and their solves compared one by one (iterations, status, |e|).
"""
from __future__ import annotations

import argparse
import contextlib
import dataclasses
import hashlib
import json
import sys
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray
from ogk_bindings._ffi import ffi, lib
from ogk_bindings.blt import BltConfig, BltReport, Transfer, _report
from ogk_bindings.kernel import _check, status_name

from ogk.sil.pil import FlightProgram, PilSession
from ogk.sil.pil_build import PIL_BUILD, build_program
from ogk.sil.target_link import TargetLinkError

from . import campaign
from .flight_config import SLOTS, slot_configs, write_flight_config

BLT_INIT, BLT_LOAD, BLT_SOLVE = 32, 33, 34      #: frame types of blt_pil.c
#: the entry points of the program, in its stack-slot order (blt_flight.h)
ENTRY_POINTS = ("ogk_blt_init", "ogk_blt_solve")
#: blt_flight.h ogk_blt_flight_action
ACTIONS = {0: "fly", 1: "safe", 2: "reject", 3: "abort"}

#: Host vs target on the same draws (docs/flight-integration-blt.md, "Host vs target"). The
#: iterations must be the same (bound 0); |e| of the returned transfer may differ by what libm's
#: ulps make of it: the model calls sin/cos (the Sun's direction, eqs. 9-10) and newlib's are not
#: glibc's; a Newton step amplifies a last-bit difference of the error vector, so |e| (1e-9 ... 5e-5)
#: is compared absolutely at 1e-12 (measured: <= 5e-15 over 60 runs, docs). The DOP853 check of the
#: converged transfer carries the same difference.
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

def flight_program(nominal: campaign.Nominal, scenario_path: Path, transfer: str) -> FlightProgram:
    """The scenario's flight program for the corrector configurations of its Monte Carlo nominal
    (a build per distinct configuration set: the key is the SHA-256 of their values)."""
    configs = slot_configs(nominal)
    key = hashlib.sha256(np.array([v for c in configs for v in flatten(c.to_c())]).tobytes())
    out = PIL_BUILD / "binary" / f"{Path(scenario_path).stem}-{key.hexdigest()[:12]}"
    return FlightProgram(build_program("blt", out, lambda c_dir: write_flight_config(
        c_dir, Path(scenario_path), configs, transfer)), ENTRY_POINTS)


class TargetCorrector:
    """campaign.fly_run's corrector (the `solve` of ogk_bindings.blt.Blt) on a slot of the program:
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
    contexts from the generated configuration (BLT_INIT), then campaign.fly_run with the host's draw
    (the same run stream) makes its corrector calls on them."""

    nominal: campaign.Nominal
    correctors: tuple[str, ...]
    levels: tuple[float, ...]                 #: [%]
    sigma: float
    program: FlightProgram

    def __call__(self, run_ids: NDArray[np.int64], run_seeds: NDArray[np.uint64]
                 ) -> list[dict[str, Any]]:
        from ogk.sil.seeds import run_generator
        session = PilSession(self.program)
        n_seg = int(self.nominal.transfer.segments.shape[0])
        n_nodes = len(self.nominal.layout.free_nodes)
        records: list[dict[str, Any]] = []
        try:
            solvers = {name: TargetCorrector(session, SLOTS.index(name), n_seg, n_nodes)
                       for name in self.correctors}
            for rid, seed in zip(run_ids, run_seeds):
                for name in self.correctors:      # each run: a fresh init of its contexts
                    configure(session, SLOTS.index(name))
                level = self.levels[int(rid) % len(self.levels)]
                records.append(campaign.fly_run(self.nominal, solvers, level / 100.0, self.sigma,
                                                run_generator(int(seed))))
                session.end_run(int(rid))
            keys = session.close()
        except BaseException:
            session.kill()
            raise
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


def _host_solves() -> tuple[Any, list[dict[str, Any]]]:
    """design.Blt logging each host solve (the comparison's host column)."""
    from ogk_bindings.blt import Blt
    log: list[dict[str, Any]] = []

    class _Logged(Blt):
        def solve(self, guess: Transfer) -> tuple[Transfer, BltReport]:
            sol, rep = super().solve(guess)
            log.append(dict(status=rep.status, iterations=rep.iterations, err_norm=rep.err_norm))
            return sol, rep
    return _Logged, log


def transfers_on_target(scenario_path: Path, names: list[str] | None = None) -> dict[str, Any]:
    """Each transfer designed on the host, then with its corrector calls on the target: per transfer
    the solves (iterations, status, |e|) side by side, instructions and stack of the target's."""
    from ogk_host.binary import design
    from ogk_host.binary import transfers as T
    from ogk_host.binary.scenario import load_scenario

    from .family import FAMILY
    from ogk_host.scenario_file import read_header

    header = read_header(scenario_path)
    scenario = load_scenario(header.path)
    solver = T.solver_settings(scenario)
    names = names or list(scenario.transfers)
    plan = FAMILY.plan(header, {"target": "m7", "runs": 1})  # the scenario's program
    program = plan.fly.program                                  # type: ignore[attr-defined]
    out: dict[str, Any] = {"scenario": scenario.name, "flight_program": str(program.elf),
                           "transfers": []}
    session = PilSession(program)
    try:
        for k, name in enumerate(names):
            spec = T.transfer_spec(scenario, name)
            logged, host_log = _host_solves()
            saved = design.Blt
            design.Blt = logged       # type: ignore[misc]
            t0 = time.perf_counter()
            try:
                host = T.design(scenario, spec, solver)
            finally:
                design.Blt = saved    # type: ignore[misc]
            t1 = time.perf_counter()
            with corrections_on_target(session) as target_log:
                target = T.design(scenario, spec, solver)
            t2 = time.perf_counter()
            session.end_run(k)
            hr, tr = host.report, target.report
            out["transfers"].append(dict(
                transfer=name, host_solves=host_log, target_solves=target_log,
                host=dict(converged=hr.converged, iterations=hr.iterations, err_norm=hr.err_norm),
                target=dict(converged=tr.converged, iterations=tr.iterations, err_norm=tr.err_norm),
                iterations_equal=[h["iterations"] for h in host_log]
                == [t["iterations"] for t in target_log],
                max_err_norm_diff=max((abs(h["err_norm"] - t["err_norm"]) for h, t in
                                       zip(host_log, target_log)
                                       if np.isfinite(h["err_norm"]) and np.isfinite(t["err_norm"])),
                                      default=0.0),
                host_wall_s=t1 - t0, target_wall_s=t2 - t1))
        keys = session.close()
    except BaseException:
        session.kill()
        raise
    for k, row in enumerate(out["transfers"]):
        row["pil"] = keys.get(k, {})
    return out


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(prog="python -m ogk.missions.binary.pil",
                                description="the scenario's BLT transfers with every corrector call on "
                                            "the emulated Cortex-M7, beside the host's")
    p.add_argument("scenario", help="a binary-asteroid scenario (name or path)")
    p.add_argument("--transfer", nargs="+", default=None, metavar="NAME",
                   help="these [transfers.NAME] (default: all of the scenario's)")
    p.add_argument("--json", default=None, metavar="FILE")
    a = p.parse_args(argv)
    from ogk_host.scenario_file import resolve_scenario
    doc = transfers_on_target(resolve_scenario(a.scenario), a.transfer)
    print(f"{doc['scenario']}: host vs target (every ogk_blt_solve of the design on {doc['flight_program']})")
    print(f"  {'transfer':24s} {'solves':>6s} {'iterations host':>24s} {'iterations target':>24s} "
          f"{'max |d|e||':>10s} {'insn max':>11s} {'stack B':>7s} {'conv':>5s}")
    ok = True
    for row in doc["transfers"]:
        hi = ",".join(str(s["iterations"]) for s in row["host_solves"])
        ti = ",".join(str(s["iterations"]) for s in row["target_solves"])
        pil = row["pil"]
        ok &= row["iterations_equal"] and row["host"]["converged"] == row["target"]["converged"]
        print(f"  {row['transfer']:24s} {len(row['target_solves']):6d} {hi:>24s} {ti:>24s} "
              f"{row['max_err_norm_diff']:10.2e} {pil.get('pil.ogk_blt_solve.insn_max') or 0:11d} "
              f"{pil.get('pil.ogk_blt_solve.stack_bytes') or 0:7d} "
              f"{'yes' if row['target']['converged'] else 'no':>5s}")
    if a.json:
        Path(a.json).write_text(json.dumps(doc, indent=1, default=float))
    print("host and target agree" if ok else "host and target DIFFER")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
