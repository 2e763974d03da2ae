"""The kernel's terminal steering along the velocity to be gained (kernel/include/ogk/terminal.h)
for all runs of a SIL chunk: one ogk_terminal_t per run, stepped once per control step by the C
batch loop of csrc/terminal_batch.c. Flown when the scenario sets
`[guidance.end_game] terminal_window_s` > 0 (docs/design/vtd-nog.md, "End-game": beyond the paper).
"""
from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from ogk_host.orbit_injection import derive
from ogk_host.orbit_injection.scenario import OrbitInjectionScenario

from ogk_bindings._ffi import ffi, lib
from ogk_bindings.kernel import KernelError
from ogk_bindings.terminal import TerminalConfig

from .csrc_batch import lib as batch

F64 = NDArray[np.float64]
BoolArray = NDArray[np.bool_]


def terminal_config(scn: OrbitInjectionScenario) -> TerminalConfig:
    """ogk_terminal_config_t of the scenario's circular target orbit and terminal window."""
    derive.require_resolved(scn, derive.WINDOW_KEYS + (derive.TURN_ACCEL_KEY,))
    eg = scn.end_game
    return TerminalConfig(mu_m3_s2=scn.mu_m3_s2, target_radius_m=scn.target_radius_m,
                          window_s=eg.terminal_window_s, shape_gain=eg.terminal_shape_gain,
                          shape_gain_normal=eg.terminal_shape_gain_normal,
                          shape_hold_s=eg.terminal_shape_hold_s, shape_lead_s=eg.terminal_shape_lead_s,
                          # the turn limit (terminal.h): the vehicle's TVC-limited angular
                          # acceleration in the window
                          turn_accel_rad_s2=eg.terminal_turn_accel_rad_s2)


def shape_tilt_bound_rad(scn: OrbitInjectionScenario) -> float | None:
    """The largest tilt of a shaped plan from v_go that the kernel flies for this scenario (the turn
    limit of ogk/terminal.h, as ogk_terminal_init computes it), or None when it does not bind (no
    shaping, no turn limit, or a bound at OGK_TERMINAL_TILT_MAX_RAD)."""
    ctx = ffi.new("ogk_terminal_t *")
    status = lib.ogk_terminal_init(ctx, terminal_config(scn).to_c())
    if status != lib.OGK_OK:
        raise KernelError(status, "ogk_terminal_init")
    return float(ctx.shape_tilt_max_rad) if ctx.tilt_limited else None


class TerminalSteering:
    """Per-run ogk_terminal_t contexts, stepped together."""

    def __init__(self, scn: OrbitInjectionScenario, n_runs: int) -> None:
        self._n = n_runs
        self._ctx = ffi.new("ogk_terminal_t[]", n_runs)
        status = np.zeros(n_runs, dtype=np.int32)
        rc = batch.ogk_sil_terminal_init_batch(self._ctx, n_runs, terminal_config(scn).to_c(),
                                             ffi.from_buffer("int32_t[]", status,
                                                             require_writable=True))
        if rc != lib.OGK_OK:
            raise KernelError(rc, "ogk_terminal_init")
        self.engaged = np.zeros(n_runs, dtype=np.uint8)
        self.status = np.zeros(n_runs, dtype=np.int32)

    def step(self, active: BoolArray, t: F64, nav: F64, t_predicted: F64, alpha: F64,
             beta: F64) -> tuple[F64, F64]:
        """The command to fly per run from the law's (alpha, beta) [rad]; inactive runs keep the
        law's."""
        act = np.ascontiguousarray(active, dtype=np.uint8)
        a = np.array(alpha, dtype=np.float64)
        b = np.array(beta, dtype=np.float64)
        batch.ogk_sil_terminal_step_batch(
            self._ctx, self._n, ffi.from_buffer("uint8_t[]", act),
            ffi.from_buffer("double[]", np.ascontiguousarray(t, dtype=np.float64)),
            ffi.from_buffer("double[]", np.ascontiguousarray(nav, dtype=np.float64)),
            ffi.from_buffer("double[]", np.ascontiguousarray(t_predicted, dtype=np.float64)),
            ffi.from_buffer("double[]", a, require_writable=True),
            ffi.from_buffer("double[]", b, require_writable=True),
            ffi.from_buffer("uint8_t[]", self.engaged, require_writable=True),
            ffi.from_buffer("int32_t[]", self.status, require_writable=True))
        return a, b

    def failed(self) -> BoolArray:
        return self.status != lib.OGK_OK
