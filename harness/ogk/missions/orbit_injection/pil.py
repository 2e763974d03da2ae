"""Orbit injection on the emulated Cortex-M7 (docs/guides/pil.md): the flight program
port/cortex-m7/pil/oi_pil.c (VTD-NOG + energy cut-off + terminal + CPD, oi_flight.c) flies the
control ticks, the host's 6-DOF truth (sil.fly_runs) flies the vehicle. One QEMU per chunk of runs;
each run is a fresh init of the flight software, its draws those of the host campaign.
"""
from __future__ import annotations

import dataclasses
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ogk.sil.pil import FlightProgram, PilSession, fly_runs_on_target
from ogk.sil.pil_build import PIL_BUILD, build_program
from ogk.sil.precision import TARGET_PRECISION
from ogk.sil.target_link import TargetLinkError

from .attitude import AttitudeCommand
from .sil import FAILURE_REASONS, SilSettings, Tick, fly_runs

F64 = NDArray[np.float64]

OI_INIT, OI_TICK = 32, 33           #: frame types of oi_pil.c
#: the entry points a tick calls, in the program's stack-slot order (oi_flight.h)
ENTRY_POINTS = ("ogk_nog_sample", "ogk_cutoff_step", "ogk_nog_thrust_cmd", "ogk_terminal_step",
                "ogk_cpd_step")
#: ... on a float kernel, whose terminal step takes the radius in two parts (oi_flight.c,
#: ogk_terminal_step_split; docs/design/vtd-nog.md, "Single precision")
ENTRY_POINTS_SINGLE = tuple("ogk_terminal_step_split" if e == "ogk_terminal_step" else e for e in ENTRY_POINTS)
#: oi_flight.h's ogk_oi_failure -> the SIL's failure reasons
FAILURES = {0: "", 1: "guidance", 2: "cutoff", 3: "terminal", 4: "attitude_control"}
assert all(v in FAILURE_REASONS for v in FAILURES.values() if v)

#: Host vs target on the same draws (docs/guides/pil.md, "Host vs target"): the largest difference of a
#: run's injection errors. The flight code is the same C; newlib's libm (sin, cos, atan2, ...) is
#: not glibc's (results a few ulp apart), and the closed loop carries those ulps to cut-off.
BOUNDS = {"dr_f_m": 1e-3, "dphi_f_deg": 1e-9, "dvr_f_mps": 1e-3, "dvt_f_mps": 1e-3,
          "dvn_f_mps": 1e-3, "tf_s": 1e-4}
BOUNDS_WHY = ("the same C on both sides; newlib's libm (sin, cos, atan2) differs from glibc's by "
              "a few ulp, and the closed loop carries the difference to cut-off; gcc contracts no "
              "FMA in ISO C mode on either side")


def flight_program(tables: Any, flight_config: Callable[[Path], object],
                   target: str = "m7") -> FlightProgram:
    """The scenario's flight program, built for the tables the campaign flies: one build per
    tables directory, its generated C written by `flight_config(DIR)` into DIR/c (the family's
    flight_config)."""
    out = PIL_BUILD / "orbit_injection" / Path(tables.directory).name
    entries = ENTRY_POINTS_SINGLE if TARGET_PRECISION[target] == "single" else ENTRY_POINTS
    return FlightProgram(build_program("oi", out, lambda c_dir: flight_config(c_dir.parent), target),
                         entries, target=target)


class TargetFlightComputer:
    """sil.FlightComputer on flight programs, one session per run of the batch: at each control
    tick an OI_TICK frame to every active run's program, then the replies (the QEMUs compute at
    once)."""

    def __init__(self, sessions: list[PilSession]) -> None:
        self._s = sessions
        for s in sessions:
            s.send(OI_INIT, [])
        for s in sessions:
            reply = s.receive(OI_INIT)
            if reply[0] != 0.0:
                raise TargetLinkError(f"the flight program's init answered action {reply[0]:g} "
                                      "(ogk_flight_action): the engine is not lit")

    def tick(self, k: int, t_s: F64, nav: F64, attitude: F64, active: NDArray[np.bool_]) -> Tick:
        n = len(self._s)
        r = np.full((n, 12), np.nan)
        live = np.flatnonzero(active)
        for i in live:
            self._s[i].send(OI_TICK, np.concatenate([[float(k), float(t_s[i])], nav[i],
                                                     attitude[i]]))
        for i in live:
            r[i] = self._s[i].receive(OI_TICK)
        failure = [FAILURES.get(int(c), "guidance") if a else "" for c, a in zip(r[:, 0], active)]
        att = AttitudeCommand(m_xc=r[:, 5], delta_yc=r[:, 6], delta_zc=r[:, 7], psi_c=r[:, 8],
                              theta_c=r[:, 9], phi_c=np.full(n, np.nan),
                              status=(r[:, 0] == 4.0).astype(np.int32))
        return Tick(failure=failure, t_predicted_s=r[:, 1], t_cutoff_s=r[:, 2], alpha_rad=r[:, 3],
                    beta_rad=r[:, 4], attitude=att)


@dataclasses.dataclass(frozen=True)
class TargetJob:
    """The chunk flight of `ogk mc --target m7`: the chunk's runs flown `batch` at a time, the host's
    truth vectorised over them and each run's flight software on its own QEMU (`batch` QEMUs per
    worker, each flying its runs one after the other), with the host job's draws."""

    host_job: Any                   #: campaign._Job (scenario, nominal, switches, settings)
    program: FlightProgram
    batch: int = 4

    def __call__(self, run_ids: NDArray[np.int64], run_seeds: NDArray[np.uint64]
                 ) -> list[dict[str, Any]]:
        from .flights import _run_records

        job = self.host_job

        def fly_batch(sessions: list[PilSession], ids: list[int], seeds: list[int]
                      ) -> list[dict[str, Any]]:
            """The runs `ids` under one vectorised truth, run i's ticks on sessions[i]."""
            draws, gens = job.draws(np.array(ids, dtype=np.int64), np.array(seeds, dtype=np.uint64))
            res = fly_runs(job.scenario, job.reference, draws, gens, job.switches, _NoGuidance(),
                           job.settings, flight_computer=TargetFlightComputer(sessions))
            return _run_records(draws, res)

        records, keys = fly_runs_on_target(self.program, run_ids.tolist(), run_seeds.tolist(),
                                           sessions=self.batch, fly_batch=fly_batch)
        for rec in records:
            rec.update(keys[int(rec["run_id"])])
        return records


class _NoGuidance:
    """fly_runs's guidance argument when the flight program flies the ticks (never called)."""

    flies_end_game = True

    def sample(self, t: F64, nav: F64, due: Any = None) -> None:
        raise AssertionError("the flight program samples")

    def command(self, t: F64) -> tuple[F64, F64]:
        raise AssertionError("the flight program commands")

    def cutoff_time(self) -> F64:
        raise AssertionError("the flight program cuts off")


def check_target_settings(settings: SilSettings, opts: dict[str, Any]) -> None:
    """What the generated flight configuration flies: refuse a campaign option it does not."""
    from ogk_bindings.errors import OgkInputError

    from .flight_config import CONTROL_RATE_HZ
    fixed = {"truth": "6dof", "guidance": "nog", "control_rate": CONTROL_RATE_HZ, "cpd_gains": None,
             "cpd_pointing": "body", "paper_end_game": False}
    for key, want in fixed.items():
        if opts.get(key, want) != want:
            raise OgkInputError(f"--target m7 flies the generated flight configuration "
                                f"({key} = {want!r}); got {opts[key]!r}",
                                key="--" + key.replace("_", "-"))
