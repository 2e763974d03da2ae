"""Guidance interface of the SIL loop, and the open-loop nominal reference guidance.

A guidance object serves N runs at once (arrays with a leading run axis). The loop calls, in order:
  sample(t, nav)      at every sampling time t_k = k Delta t_S (2 s), with perfect navigation
                      nav = [r m, xi rad, phi rad, v_r, v_t, v_n m/s] (N, 6). Runs already cut off
                      are passed with t frozen at their cut-off time: leave them alone (t >= cutoff).
  cutoff_time()       at every control step (after the sample at sampling times): engine cut-off
                      time per run [s] (inf until known). The loop lands each run's truth step
                      exactly on it; a time already past ends the run at once.
  command(t)          (alpha_c, beta_c) (N,) [rad] at any t inside the current sampling interval:
                      at every control step (6-DOF truth) or every RK4 stage (point-mass truth).
  failed()            optional: (N,) bool, a guidance breakdown (the run is counted as failed).

A guidance class is its own factory: `cls(setup: GuidanceSetup)`.
"""
from __future__ import annotations

import dataclasses
from typing import Protocol, runtime_checkable

import numpy as np
from numpy.typing import NDArray

from ogk_host.orbit_injection.scenario import OrbitInjectionScenario

from .nominal_ref import NominalReference

F64 = NDArray[np.float64]
BoolArray = NDArray[np.bool_]


@dataclasses.dataclass(frozen=True)
class GuidanceSetup:
    """What a guidance factory receives: the scenario, the ground nominal, and the runs it serves
    (campaign run indices, one chunk of the campaign in each worker process)."""

    scenario: OrbitInjectionScenario
    reference: NominalReference
    run_ids: NDArray[np.int64]
    #: sampling interval at the end of the burn when the end-game samples faster (sil.EndGamePlan)
    last_interval_s: float | None = None

    @property
    def n_runs(self) -> int:
        return int(self.run_ids.size)


@runtime_checkable
class Guidance(Protocol):
    """Vectorised guidance (see module doc)."""

    def sample(self, t: F64, nav: F64, due: BoolArray | None = None) -> None: ...

    def command(self, t: F64) -> tuple[F64, F64]: ...

    def cutoff_time(self) -> F64: ...


class GuidanceFactory(Protocol):
    def __call__(self, setup: GuidanceSetup) -> Guidance: ...


class NominalOpenLoopGuidance:
    """Flies the nominal u*(t) open loop and cuts off at t_f* (or `cutoff_s`).

    The reference for tests: with the point-mass truth and no dispersions it must reproduce the
    ground nominal's final state (the check that the truth and the ground tools agree)."""

    #: an open-loop reference flies its own cut-off and command to the end: no end-game stage
    #: (sil.EndGamePlan.flown_by)
    flies_end_game = False

    name = "nominal"

    def __init__(self, setup: GuidanceSetup, cutoff_s: float | None = None) -> None:
        self._ref = setup.reference
        cut = self._ref.tf_s if cutoff_s is None else float(cutoff_s)
        self._cutoff = np.full(setup.n_runs, cut)
        self.samples = 0

    def sample(self, t: F64, nav: F64, due: BoolArray | None = None) -> None:
        self.samples += 1

    def command(self, t: F64) -> tuple[F64, F64]:
        u = self._ref.control(t)
        return u[..., 0], u[..., 1]

    def cutoff_time(self) -> F64:
        return self._cutoff

    def failed(self) -> BoolArray:
        return np.zeros(self._cutoff.size, dtype=bool)
