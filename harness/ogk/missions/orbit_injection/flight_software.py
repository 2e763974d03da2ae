"""The family's flight software as one call per control tick: sil.FlightComputer on the kernel
through cffi (VTD-NOG sampling schedule, energy cut-off, terminal steering, CPD).

It is the same sequence, the same calls in the same order, as the inline control sample of
sil.fly_runs, packaged so that another simulator can fly it: the Basilisk module of ogk.missions.orbit_injection.basilisk
calls `tick` once per control period with Basilisk's navigation. tests/python/test_basilisk.py
checks that sil.fly_runs with this flight computer gives bit-identical results to sil.fly_runs
without it (so the software flown in Basilisk is the software of our campaigns).
"""
from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from ogk_host.orbit_injection.scenario import OrbitInjectionScenario

from .attitude import CpdBatchControl
from .cutoff import EnergyCutoff
from .guidance import GuidanceSetup
from .nog_guidance import KernelNogGuidance, NogTables
from .nominal_ref import NominalReference
from .sil import EndGamePlan, SilSettings, Tick
from .terminal import TerminalSteering

F64 = NDArray[np.float64]


class KernelFlightSoftware:
    """sil.FlightComputer for N runs: guidance samples every Delta t_S (and every fine interval
    near the end), the cut-off and terminal stages of the scenario's end-game, CPD every tick.
    `scn` is resolved where it was loaded (nominal_ref.resolved_with_reference), as for sil.fly_runs."""

    def __init__(self, scn: OrbitInjectionScenario, ref: NominalReference, tables: NogTables,
                 run_ids: NDArray[np.int64], settings: SilSettings = SilSettings()) -> None:
        n = int(np.asarray(run_ids).size)
        ctrl_dt = 1.0 / settings.control_rate_hz
        self.plan = EndGamePlan.of(scn, settings)
        self.guidance = KernelNogGuidance(
            GuidanceSetup(scn, ref, np.asarray(run_ids, dtype=np.int64),
                          self.plan.fine_interval_s), tables.bundle)
        every = scn.sample_interval_s / ctrl_dt
        if abs(every - round(every)) > 1e-9 or round(every) < 1:
            raise ValueError("the guidance sampling interval must be a multiple of the control "
                             "period")
        self._sample_every = int(round(every))
        self._fine_every = (self._sample_every if self.plan.fine_interval_s is None
                            else int(round(self.plan.fine_interval_s / ctrl_dt)))
        self._cut = EnergyCutoff(scn, n, ctrl_dt) if self.plan.energy_cutoff else None
        self._terminal = TerminalSteering(scn, n) if self.plan.terminal_window_s > 0.0 else None
        self._cpd = CpdBatchControl(scn, n, settings.cpd_gains, settings.cpd_pointing, ctrl_dt)
        self._predicted = np.full(n, np.inf)
        self._n = n

    def tick(self, k: int, t_s: F64, nav: F64, attitude: F64, active: NDArray[np.bool_]) -> Tick:
        """Control tick k at times t_s (N,) with nav (N, 6) [r, xi, phi, v_r, v_t, v_n] and
        attitude (N, 6) [psi, theta, phi_roll, p, q, r] (sil.FlightComputer)."""
        g, n = self.guidance, self._n
        failure = [""] * n
        live = np.array(active, dtype=bool)

        def fail(mask: NDArray[np.bool_], reason: str) -> None:
            for i in np.flatnonzero(mask & live):
                failure[i] = reason
            live[mask] = False

        due = np.full(n, k % self._sample_every == 0)
        if self.plan.fine_interval_s is not None and k % self._fine_every == 0:
            due |= (self._predicted - t_s) <= self.plan.fine_window_s
        if due.any():
            g.sample(t_s, nav, due)
            fail(g.failed() & live, "guidance")
        predicted = np.asarray(g.cutoff_time(), dtype=np.float64)
        fail(np.isnan(predicted), "guidance")
        self._predicted = predicted
        cutoff = predicted
        if self._cut is not None:
            known = live & np.isfinite(predicted)
            cutoff = np.where(known, self._cut.step(known, t_s, nav, predicted), predicted)
            fail(self._cut.failed() & known, "cutoff")
        alpha, beta = (np.asarray(v, dtype=np.float64) for v in g.command(t_s))
        fail(~(np.isfinite(alpha) & np.isfinite(beta)), "guidance")
        if self._terminal is not None:
            known = live & np.isfinite(predicted)
            alpha, beta = self._terminal.step(known, t_s, nav, predicted, alpha, beta)
            fail(self._terminal.failed() & known, "terminal")
        att = self._cpd.step(t_s, attitude, alpha, beta, nav[:, 1], nav[:, 2], live)
        fail(att.status != 0, "attitude_control")
        return Tick(failure=failure, t_predicted_s=predicted, t_cutoff_s=cutoff,
                    alpha_rad=alpha, beta_rad=beta, attitude=att)
