"""MPSP re-planning on the emulated Cortex-M7 (docs/guides/flight-integration-mpsp.md, docs/guides/pil.md): the
flight program port/cortex-m7/pil/mpsp_pil.c (mpsp_flight.c: ogk_mpsp_init, ogk_mpsp_solve,
ogk_mpsp_thrust_cmd on the generated configuration) solves each run's problem, the host draws the
problem, builds the record and judges it exactly as the host campaign does (family.py fly_one).

One exchange per kernel step: MPSP_INIT (ogk_mpsp_init) at the start of every run, then one
MPSP_REPLAN (one ogk_mpsp_solve, the whole two-loop MPSP of the run's case, and one
ogk_mpsp_thrust_cmd at t0 of the plan). Two QEMUs per worker compute at once, each taking the
chunk's next run when it is free.
"""
from __future__ import annotations

import dataclasses
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ogk.sil.pil import FlightProgram, PilSession, fly_runs_on_target
from ogk.sil.pil_build import PIL_BUILD, build_program
from ogk.sil.target_link import TargetLinkError

MPSP_INIT, MPSP_REPLAN = 32, 33         #: frame types of mpsp_pil.c
REPLY_HEAD = 30                         #: values before the weights in the MPSP_REPLAN reply
#: the entry points the flight software calls, in the program's stack-slot order (mpsp_flight.h)
ENTRY_POINTS = ("ogk_mpsp_init", "ogk_mpsp_solve", "ogk_mpsp_thrust_cmd")
STATUS_OK, STATUS_NOT_CONVERGED = 0, 20  #: ogk/status.h
#: The longest one solve may take on QEMU [s]: the configuration bounds a solve to max_newton (100)
#: iterations in each of up to 1 + max_outer (60) inner loops, ~4.3e7 instructions each, a few
#: hundred seconds on a loaded QEMU; the paper's worst case (91 iterations) takes ~10 s.
SOLVE_TIMEOUT_S = 1800.0

#: Host vs target on the same cases (docs/guides/flight-integration-mpsp.md, "Host vs target"): the largest
#: difference of a run's result. Measured on the 23 paper cases of apophis_cubesat (`ogk mc
#: apophis_cubesat --cases paper --target m7`): newton_iterations, outer_steps, thrust_arcs equal;
#: dr_f_km 1.4e-4 km, dv_f_kmps 2.6e-11 km/s, lambda_mf 5.9e-14, final_mass_kg 1.3e-12 kg. The
#: counts are bound exactly; the others leave a factor 7 (dr_f_km) to 2e4 over the differences.
BOUNDS = {"newton_iterations": 0.0, "outer_steps": 0.0, "thrust_arcs": 0.0,
          "dr_f_km": 1e-3, "dv_f_kmps": 1e-9, "lambda_mf": 1e-9, "final_mass_kg": 1e-9}
BOUNDS_WHY = ("the same C on both sides and the same configuration (generated from the scenario "
              "by cgen, doubles read back bit-exactly); newlib's libm (cos, sin, sqrt of the "
              "Fourier basis and the dynamics) differs from glibc's by a few ulp, which the RK4 "
              "propagation over the 2048-step grid and the Newton iterations carry to the terminal "
              "errors: the iteration counts are equal, the terminal errors those of the same "
              "converged weights up to the ulps (|dr_f| 0.14 m apart at most on the 23 paper "
              "cases, against a 500 km tolerance), the final mass within 1e-9 kg")


def flight_program(setup: Any, scenario_path: Path, flight_config: Callable[[Path], object],
                   target: str = "m7") -> FlightProgram:
    """The scenario's flight program, built for the configuration the campaign flies: one build
    per scenario file (SHA-256), basis, order and C configuration (its bytes: the nominal weights
    and every [mpsp] setting), its generated C written by `flight_config(DIR)` into DIR/c (the
    family's flight_config)."""
    from ogk_host.scenario_file import file_sha256

    key = (f"{file_sha256(scenario_path)[:12]}-{setup.basis}-{setup.order}-"
           f"{_config_digest(setup.guidance.cfg)}")
    out = PIL_BUILD / "low_thrust_transfer" / f"{Path(scenario_path).stem}-{key}"
    return FlightProgram(build_program("mpsp", out, lambda c_dir: flight_config(c_dir.parent),
                                       target), ENTRY_POINTS, timeout_s=SOLVE_TIMEOUT_S,
                         target=target)


def _config_digest(cfg: Any) -> str:
    """12 hex digits of the C configuration's bytes (a changed [mpsp] setting is another build)."""
    import hashlib

    from ogk_bindings._ffi import ffi
    return hashlib.sha256(bytes(ffi.buffer(cfg.to_c()))).hexdigest()[:12]


def request(case: Any, t_cmd: float = 0.0) -> NDArray[np.float64]:
    """The MPSP_REPLAN payload of a case: x0, thrust scale, the target (or none), t_cmd [TU]."""
    target = np.zeros(6) if case.target is None else np.asarray(case.target, dtype=np.float64)
    return np.concatenate([np.asarray(case.x0, dtype=np.float64), [float(case.thrust_scale)],
                           [0.0 if case.target is None else 1.0], target, [float(t_cmd)]])


def result_of(reply: NDArray[np.float64]) -> Any:
    """The target's plan as the bindings' MpspResult (switch times and the Newton log are not sent
    over the link: empty)."""
    from ogk_bindings.mpsp import MpspResult
    from ogk_bindings.kernel import Status

    st = int(reply[1])
    if st not in (STATUS_OK, STATUS_NOT_CONVERGED):
        raise TargetLinkError(f"the flight program's re-plan answered status {st} (action "
                              f"{int(reply[0])}) on a request the host accepts")
    nw = int(reply[29])
    return MpspResult(
        status=Status(st), converged=bool(reply[2]), newton_iterations=int(reply[3]),
        inner_loops=int(reply[4]), outer_steps=int(reply[5]), n_seg_tol=int(reply[6]),
        tau_reached=float(reply[7]), dy=np.array(reply[8:15]), err_r=float(reply[15]),
        err_v=float(reply[16]), lambda_mf=float(reply[17]), m_f=float(reply[18]),
        n_segments=int(reply[19]), n_thrust_arcs=int(reply[20]), switch_times=np.zeros(0),
        weights=np.array(reply[REPLY_HEAD:REPLY_HEAD + nw]), lambda_m0=float(reply[22]),
        dy_norm_log=np.zeros(0))


@dataclasses.dataclass(frozen=True)
class TargetJob:
    """The chunk flight of `ogk mc --target m7`: `batch` QEMUs per worker, each taking the chunk's
    next run when it is free (a solve takes 4 to 91 Newton iterations: no lock-step), the cases and
    records those of the host's fly_one.

    `case_of(run_id, run_seed)` is the host's case; `record_of(case, result, cpu_s)` the host's
    record of it (family.py), so the keys and the judging are the host's. Both run in the calling
    thread; the threads only wait on their QEMU's link."""

    case_of: Callable[[int, int], Any]
    record_of: Callable[[Any, Any, float], dict[str, Any]]
    program: FlightProgram
    t0: float = 0.0
    batch: int = 2

    def _fly_run(self, s: PilSession, case: Any) -> tuple[NDArray[np.float64], float]:
        """One run on session s: MPSP_INIT, MPSP_REPLAN; the reply and the host's wait for it
        (timing.cpu_s of a target run: QEMU time, not flight CPU time)."""
        init = s.exchange(MPSP_INIT, [])
        if init[0] != 0.0:
            raise TargetLinkError(f"the flight program's init answered action {init[0]:g} "
                                  "(ogk_mpsp_flight_action)")
        start = time.perf_counter()
        reply = s.exchange(MPSP_REPLAN, request(case, self.t0))
        return reply, time.perf_counter() - start

    def __call__(self, run_ids: NDArray[np.int64], run_seeds: NDArray[np.uint64]
                 ) -> list[dict[str, Any]]:
        ids = [int(i) for i in run_ids]
        cases = [self.case_of(rid, int(seed)) for rid, seed in zip(ids, run_seeds)]
        case_of_run = dict(zip(ids, cases))
        flown, keys = fly_runs_on_target(
            self.program, ids, run_seeds, lambda s, rid, seed: self._fly_run(s, case_of_run[rid]),
            sessions=self.batch)
        records: list[dict[str, Any]] = []
        for rid, case, (reply, wait) in zip(ids, cases, flown):
            rec = self.record_of(case, result_of(reply), wait)
            rec.update(keys[rid])
            records.append(rec)
        return records
