"""Attitude-control interface of the SIL loop and the kernel CPD through the C batch loop.

The loop calls `step` at every control sample (zero-order hold until the next one) with perfect
navigation of the attitude: (N, 6) [Psi, Theta, Phi (rad), P, Q, R (rad/s)] (Euler angles of eq. 9),
the guidance command (alpha_c, beta_c) and the position angles (xi, phi). It returns the commanded
actuator inputs of eqs. (16), (18) and the commanded attitude (for the histories).
"""
from __future__ import annotations

import dataclasses
from typing import Protocol

import numpy as np
from numpy.typing import NDArray

from ogk_host.orbit_injection.scenario import OrbitInjectionScenario

F64 = NDArray[np.float64]


@dataclasses.dataclass
class AttitudeCommand:
    """Per-run output of one control sample (arrays (N,))."""

    m_xc: F64          #: [N m] commanded roll torque, eq. (45)
    delta_yc: F64      #: [rad] commanded pitch deflection, eq. (46)
    delta_zc: F64      #: [rad] commanded yaw deflection, eq. (46)
    psi_c: F64         #: [rad] commanded yaw, eqs. (38)-(39)
    theta_c: F64       #: [rad] commanded pitch
    phi_c: F64         #: [rad] commanded roll
    status: NDArray[np.int32]   #: 0 = OK, else the controller's error code


class AttitudeControl(Protocol):
    def step(self, t: F64, attitude: F64, alpha_c: F64, beta_c: F64, xi: F64, phi: F64,
             active: NDArray[np.bool_]) -> AttitudeCommand: ...


POINTING_MODES = {"body": 0, "euler": 1}


def cpd_config(scn: OrbitInjectionScenario, gains: str | None = None, pointing: str = "body",
               control_period_s: float = 0.0) -> dict:
    """Field values of ogk_cpd_config_t from the scenario (gain set `gains` in {"printed",
    "rederived"}, default the scenario's `flown` choice). The re-derived gains and the braking
    accelerations are the ground tools' (ogk_host.orbit_injection.derive): the scenario's own
    values when it states them, the sec. 5.3 design rule otherwise."""
    from ogk_host.orbit_injection import derive
    cpd, act = scn.cpd, scn.actuators
    chosen = gains if gains is not None else cpd.flown
    if chosen not in ("printed", "rederived"):
        raise ValueError(f"unknown gain set {chosen!r}")
    settings = derive.effective_settings(scn)
    g = settings.cpd_gains if chosen == "rederived" else cpd.printed
    if g is None:
        raise ValueError(f"the scenario has no [cpd.{chosen}] gain set")
    return dict(k_px=g.kp_roll_n_m_per_rad, k_dx=g.kd_roll_n_m_s_per_rad,
                k_py=g.kp_pitch_yaw, k_dy=g.kd_pitch_yaw_s,
                k_pz=g.kp_pitch_yaw, k_dz=g.kd_pitch_yaw_s,
                m_xc_max=cpd.roll_torque_command_max_n_m,
                delta_yc_max=cpd.deflection_y_command_max_rad,
                delta_zc_max=cpd.deflection_z_command_max_rad,
                tau_x=act.time_constant_x_s, tau_y=act.time_constant_y_s,
                tau_z=act.time_constant_z_s, phi_c=cpd.roll_command_rad,
                pointing=POINTING_MODES[pointing],
                **dict(zip(("approach_accel_x", "approach_accel_y", "approach_accel_z"),
                           settings.braking_accels_rad_s2)),
                ff_period_s=control_period_s if cpd.feedforward else 0.0,
                ff_rate_max=cpd.feedforward_rate_max_rad_s)


class CpdBatchControl:
    """The kernel's ogk_cpd_step for N runs per call (csrc/sil_batch.c), one ogk_cpd_t per
    run in a cffi array."""

    name = "cpd"

    def __init__(self, scn: OrbitInjectionScenario, n_runs: int, gains: str | None = None,
                 pointing: str = "body", control_period_s: float = 0.02) -> None:
        from ogk_bindings._ffi import ffi, lib
        from ogk_bindings.cpd import CpdConfig

        from .csrc_batch import lib as batch
        self._ffi, self._lib, self._batch = ffi, lib, batch
        self.n_runs = n_runs
        self.config = cpd_config(scn, gains, pointing, control_period_s)
        # Typed wrapper: ogk_cpd_config_default, then every field by its C name (checked).
        cfg = CpdConfig(**self.config).to_c()
        self._ctx = ffi.new("ogk_cpd_t[]", max(n_runs, 1))
        self._in = np.zeros((int(batch.OGK_SIL_CPD_N_IN), n_runs))
        self._out = np.zeros((int(batch.OGK_SIL_CPD_N_OUT), n_runs))
        self._status = np.zeros(n_runs, dtype=np.int32)
        self._flags = np.zeros(n_runs, dtype=np.uint32)
        self._active = np.zeros(n_runs, dtype=np.uint8)
        st = batch.ogk_sil_cpd_init_batch(self._ctx, n_runs, cfg,
                                          ffi.from_buffer("int32_t[]", self._status))
        if st != lib.OGK_OK:
            from ogk_bindings.kernel import KernelError
            raise KernelError(st, "ogk_sil_cpd_init_batch")
        self._phi_c = np.full(n_runs, self.config["phi_c"])

    @property
    def flags(self) -> NDArray[np.uint32]:
        """OGK_CPD_FLAG_* of the last step per run."""
        return self._flags

    def step(self, t: F64, attitude: F64, alpha_c: F64, beta_c: F64, xi: F64, phi: F64,
             active: NDArray[np.bool_]) -> AttitudeCommand:
        ffi, batch = self._ffi, self._batch
        buf = self._in
        buf[0:6] = attitude.T
        buf[6], buf[7], buf[8], buf[9] = alpha_c, beta_c, xi, phi
        self._active[:] = active
        batch.ogk_sil_cpd_step_batch(
            self._ctx, self.n_runs, ffi.from_buffer("uint8_t[]", self._active),
            ffi.from_buffer("double[]", buf), ffi.from_buffer("double[]", self._out,
                                                               require_writable=True),
            ffi.from_buffer("int32_t[]", self._status, require_writable=True),
            ffi.from_buffer("uint32_t[]", self._flags, require_writable=True))
        out = self._out
        return AttitudeCommand(m_xc=out[0].copy(), delta_yc=out[1].copy(),
                               delta_zc=out[2].copy(), psi_c=out[3].copy(),
                               theta_c=out[4].copy(), phi_c=self._phi_c,
                               status=self._status.copy())
