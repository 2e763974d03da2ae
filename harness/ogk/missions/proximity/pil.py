"""The proximity approach on the emulated Cortex-M7: the rendezvous' NMPC flight program
(port/cortex-m7/pil/nmpc_pil.c over nmpc_flight.c) flies the second problem of the same solver
(ogk_nmpc_init_problem with ogk_prox_problem, flight_config.py), the host's truth and closed loop
(closed_loop.fly) around it. One QEMU per chunk of runs (ogk.sil.pil.fly_runs_on_target); each run a
fresh init of the flight software.

One replan = one NMPC_REPLAN exchange (the frames of nmpc_pil.c): the measured (t, x) out, the report,
the command at t and the plan flown back (its node states in NMPC_PLAN_X reads). Between replans the
truth asks for the command at any instant: ogk_prox_thrust_cmd on the host, in a context holding the
target's plan bit for bit, so the truth flies exactly the plan the target solved; the command at the
replan time, computed on the target, is checked against it.
"""
from __future__ import annotations

import dataclasses
import hashlib
import math
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray
from ogk_host.proximity.scenario import ProximityScenario

from ogk_bindings._ffi import ffi, lib
from ogk_bindings.kernel import _check, status_name
from ogk.sil.pil import FlightProgram, PilSession, fly_runs_on_target
from ogk.sil.pil_build import PIL_BUILD, build_program
from ogk.sil.target_link import TargetLinkError

from .guidance import Plan, ReplanInfo, _Base, kernel_context

F64 = NDArray[np.float64]

NMPC_INIT, NMPC_REPLAN, NMPC_PLAN_X = 32, 33, 34     #: frame types of nmpc_pil.c
HEAD = 23                                           #: NMPC_REPLAN reply values before the controls
ROWS_PER_FRAME = 25                                 #: node states per NMPC_PLAN_X reply
NX = 5
#: the entry points of a replan, in the program's stack-slot order (nmpc_flight.h); the init is
#: ogk_nmpc_init_problem here
ENTRY_POINTS = ("ogk_nmpc_init_problem", "ogk_nmpc_reset", "ogk_nmpc_load_plan", "ogk_nmpc_solve",
                "ogk_nmpc_replan", "ogk_nmpc_get_plan", "ogk_nmpc_command")
ACTIONS = {0: "fly", 1: "fly_stale", 2: "hold", 3: "no_plan", 4: "reinit", 5: "abort"}
STEP_TIMEOUT_S = 600.0
#: Host vs target on the same draws (docs/guides/pil.md, "Host vs target"). The same C on both sides, the plans
#: crossing the link bit for bit; newlib's libm (sin, cos, sqrt) is not glibc's, so each solve differs in
#: its last bits and the closed loop carries that to the end of the flight. The flight's end is the ground
#: plan's t_f, kept by every replan within a band of 1e-9 of the time left to it ([guidance]
#: fixed_final_time: guidance.FIXED_T_F_BAND; nmpc_flight.c, OGK_NMPC_FLIGHT_FINAL_TIME), so host and
#: target end within 1e-9 x 10^4 s = 10 us of it, unless one side's first solve is retried with T free
#: and the other's not (then failed_solves differs too): TF_BOUND_S. The misses: a tenth of the
#: acceptance box; the propellant: a hundredth of the budget.
TF_BOUND_S = 0.01
#: The failed solves: the count itself moves with the solves' last bits (the host against itself: 0 to 4
#: over 1-5 ulp moves of the start, session 17's note), each failure retried (nmpc_flight.c); a quarter of
#: a flight's 33 replans. The outcomes are what the other bounds hold.
FAILED_SOLVES_BOUND = 8.0
BOUNDS_WHY = ("the same C on both sides on the same inputs (the plan crosses the link bit for bit); newlib's libm is "
              "not glibc's, so each solve differs in its last bits and the closed loop carries that to the end. "
              "Every replan keeps the ground plan's final time within 1e-9 of the time left to it, so t_f is "
              "held to 10 ms; the misses to a tenth of the acceptance box, the propellant to a hundredth of the "
              "budget; the failed solves (which move with the last bits, each retried) to a quarter of the replans")


def target_bounds(scn: ProximityScenario) -> dict[str, float]:
    acc = scn.acceptance
    bounds = {"miss_m": 0.1 * acc.hold_position_box_m, "miss_velocity_m_s": 0.1 * acc.hold_velocity_box_m_s,
              "t_f_s": TF_BOUND_S, "failed_solves": FAILED_SOLVES_BOUND}
    if acc.propellant_kg:
        bounds["fuel_kg"] = 0.01 * acc.propellant_kg
    return bounds


def program_key(scenario_path: Path) -> str:
    h = hashlib.sha256(Path(scenario_path).read_bytes())
    h.update(b"\0proximity flight_config/2")   # /2: the final time kept (OGK_NMPC_FLIGHT_FINAL_TIME)
    return h.hexdigest()[:16]


def flight_program(scenario_path: Path, flight_config: Callable[[Path], object],
                   target: str = "m7") -> FlightProgram:
    """The scenario's flight program: the NMPC program built on its generated configuration."""
    out = PIL_BUILD / "proximity" / program_key(scenario_path)
    return FlightProgram(build_program("nmpc", out, lambda c_dir: flight_config(c_dir.parent), target),
                         ENTRY_POINTS, timeout_s=STEP_TIMEOUT_S, target=target)


class TargetGuidance(_Base):
    """The closed loop's Guidance whose replans run on the flight program (module doc)."""

    name = "kernel"

    def __init__(self, scn: ProximityScenario, first: Plan, session: PilSession) -> None:
        super().__init__(scn, first)
        self.session = session
        reply = session.exchange(NMPC_INIT, [])
        if reply[0] != 0.0:
            raise TargetLinkError(f"the flight program's init answered {ACTIONS.get(int(reply[0]))}: "
                                  "the configuration is rejected")
        if int(reply[1]) != 2:
            raise TargetLinkError(f"the flight program flies nu = {int(reply[1])}, the proximity problem 2")
        self._mirror = kernel_context(scn)      # holds the target's plan for the commands between replans
        # before the first replan, the ground's plan (as KernelGuidance loads it)
        self._mirror.load_plan(first.t0, first.horizon, first.states, first.controls)
        self.command_mismatch = 0

    def replan(self, t_s: float, x_si: F64) -> ReplanInfo:
        t = t_s / self.units.time_s
        x = np.asarray(x_si, dtype=np.float64) / self.scale
        start = time.perf_counter()
        r = self.session.exchange(NMPC_REPLAN, np.concatenate([[t], x]))
        elapsed = time.perf_counter() - start          # QEMU's wall time, not the M7's
        status, solves = int(r[1]), int(r[4])
        solver_codes = {int(lib.OGK_OK), int(lib.OGK_E_ITER_LIMIT), int(lib.OGK_E_NOT_CONVERGED),
                        int(lib.OGK_E_INFEASIBLE), int(lib.OGK_E_NOT_POSDEF)}
        if status not in solver_codes and not (status == int(lib.OGK_E_NONFINITE) and solves > 0):
            _check(status, "ogk_nmpc_replan" if self.started else "ogk_nmpc_solve")
        if int(r[18]) != int(lib.OGK_OK):
            raise TargetLinkError(f"the flight program has no plan after a replan ({ACTIONS.get(int(r[0]))})")
        self.plan = self._plan(r)
        alpha, w, _, _ = self._mirror.command(t)   # ogk_nmpc_command on the host, the target's C
        if (alpha, w) != (float(r[9]), float(r[10])):
            self.command_mismatch += 1
        converged = status == int(lib.OGK_OK)
        # the step's solves and failed solve calls, continuation and retries included (nmpc_flight.c,
        # counted), as KernelGuidance counts them
        self.solves += int(r[21])
        self.failed_solves += int(r[22])
        self.started = True
        return self._info(t_s, converged, status_name(status), int(r[3]), elapsed)

    def _plan(self, r: F64) -> Plan:
        """The target's plan: controls from the reply, node states read in frames; put in the mirror
        context bit for bit (not through load_plan, whose horizon bounds a stale remainder may leave)."""
        n, nu = int(r[16]), int(r[17])
        nc = (n + 1) * nu
        controls = np.array(r[HEAD:HEAD + nc]).reshape(n + 1, nu)
        lam = np.array(r[HEAD + nc:HEAD + nc + 4])
        rows = [self.session.exchange(NMPC_PLAN_X, [float(first)]) for first in range(0, n + 1, ROWS_PER_FRAME)]
        states = np.concatenate(rows).reshape(n + 1, NX)
        p = self._mirror._ctx.nmpc.plan
        p.t0, p.horizon, p.nodes, p.nu = float(r[14]), float(r[15]), n, nu
        ffi.memmove(p.x, np.ascontiguousarray(states).tobytes(), states.nbytes)
        ffi.memmove(p.u, np.ascontiguousarray(controls).tobytes(), controls.nbytes)
        for i in range(4):
            getattr(p, "lambda")[i] = float(lam[i])
        self._mirror._ctx.nmpc.have_plan = 1
        return Plan(float(r[14]), float(r[15]), states, controls)

    def command(self, t_s: float) -> tuple[float, float]:
        cmd = self._mirror.thrust_cmd(t_s / self.units.time_s)   # as KernelGuidance.command
        return math.atan2(cmd.u[1], cmd.u[0]), cmd.throttle


@dataclasses.dataclass(frozen=True)
class TargetJob:
    """The chunk flight of `ogk mc --target m7`: the chunk's runs one after the other on one QEMU."""

    scenario: ProximityScenario
    first: Plan
    perturbed: bool
    program: FlightProgram
    results: tuple[str, ...]

    def __call__(self, run_ids: NDArray[np.int64], run_seeds: NDArray[np.uint64]) -> list[dict[str, Any]]:
        from .closed_loop import fly

        def fly_on_session(session: PilSession, run_id: int, run_seed: int) -> dict[str, Any]:
            start = time.perf_counter()
            guidance = TargetGuidance(self.scenario, self.first, session)
            try:
                rec = fly(self.scenario, "kernel", self.first, run_seed, self.perturbed, guidance=guidance).record()
            except TargetLinkError:
                raise
            except RuntimeError as err:     # the truth integration stopped
                rec = {**dict.fromkeys(self.results), "completed": False, "reason": f"truth: {err}"}
            rec["timing.wall_s"] = time.perf_counter() - start
            rec["pil.command_mismatch"] = guidance.command_mismatch
            return rec

        records, keys = fly_runs_on_target(self.program, run_ids, run_seeds, fly_on_session)
        for rid, rec in zip(run_ids, records):
            rec.update(keys[int(rid)])
        return records

