"""The kernel's energy cut-off monitor (kernel/include/ogk/cutoff.h) for all runs of a SIL chunk.

One ogk_cutoff_t per run; the C batch loop of csrc/cutoff_batch.c crosses from Python once
per control step. Flown when the scenario says `[guidance.end_game] cutoff = "energy"`
(docs/design/vtd-nog.md, "End-game": beyond the paper).
"""
from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from ogk_host.orbit_injection.scenario import OrbitInjectionScenario

from ogk_bindings._ffi import ffi, lib
from ogk_bindings.cutoff import CutoffConfig
from ogk_bindings.kernel import KernelError

from .csrc_batch import lib as batch

F64 = NDArray[np.float64]
BoolArray = NDArray[np.bool_]


def cutoff_config(scn: OrbitInjectionScenario, control_period_s: float) -> CutoffConfig:
    """ogk_cutoff_config_t: the target orbit's semi-major axis (circular: its radius) and the
    scenario's arm / extend windows."""
    return CutoffConfig(mu_m3_s2=scn.mu_m3_s2, target_sma_m=scn.target_radius_m,
                        arm_before_s=scn.end_game.arm_s(scn.sample_interval_s),
                        extend_max_s=scn.end_game.extend_max_s(scn.sample_interval_s),
                        control_period_s=control_period_s)


class EnergyCutoff:
    """Per-run ogk_cutoff_t contexts, stepped together."""

    def __init__(self, scn: OrbitInjectionScenario, n_runs: int, control_period_s: float) -> None:
        self._n = n_runs
        self._ctx = ffi.new("ogk_cutoff_t[]", n_runs)
        status = np.zeros(n_runs, dtype=np.int32)
        rc = batch.ogk_sil_cutoff_init_batch(self._ctx, n_runs,
                                             cutoff_config(scn, control_period_s).to_c(),
                                             ffi.from_buffer("int32_t[]", status,
                                                             require_writable=True))
        if rc != lib.OGK_OK:
            raise KernelError(rc, "ogk_cutoff_init")
        self.t_cutoff = np.full(n_runs, np.inf)
        self.flags = np.zeros(n_runs, dtype=np.uint32)
        self.status = np.zeros(n_runs, dtype=np.int32)

    def step(self, active: BoolArray, t: F64, nav: F64, t_predicted: F64) -> F64:
        """One control step of the runs `active` at times t (N,), nav (N, 6) [r, xi, phi, v_r,
        v_t, v_n]; returns the cut-off time in force per run (inactive runs: unchanged)."""
        act = np.ascontiguousarray(active, dtype=np.uint8)
        t = np.ascontiguousarray(t, dtype=np.float64)
        nav = np.ascontiguousarray(nav, dtype=np.float64)
        pred = np.ascontiguousarray(t_predicted, dtype=np.float64)
        batch.ogk_sil_cutoff_step_batch(
            self._ctx, self._n, ffi.from_buffer("uint8_t[]", act), ffi.from_buffer("double[]", t),
            ffi.from_buffer("double[]", nav), ffi.from_buffer("double[]", pred),
            ffi.from_buffer("double[]", self.t_cutoff, require_writable=True),
            ffi.from_buffer("uint32_t[]", self.flags, require_writable=True),
            ffi.from_buffer("int32_t[]", self.status, require_writable=True))
        return self.t_cutoff.copy()

    def failed(self) -> BoolArray:
        return self.status != lib.OGK_OK

    def decided(self) -> BoolArray:
        return (self.flags & lib.OGK_CUTOFF_FLAG_DECIDED) != 0
