"""Typed bindings of the kernel's CPD attitude control (kernel/include/ogk/cpd.h, docs/design/cpd.md).

    cfg = CpdConfig(k_px=..., ..., pointing=Pointing.BODY)  # ogk_cpd_config_default + fields by name
    ctl = Cpd(cfg)                               # ogk_cpd_init (KernelError on a rejected config)
    ctl.reset()                                  # ogk_cpd_reset
    out = ctl.step(CpdInput(psi=..., ...))       # ogk_cpd_step -> CpdOutput
    inp = CpdInput(psi=..., ...).with_thrust_cmd(cmd, xi, phi)   # any law's ThrustCmd (r-t-n, inertial)
    psi_c, theta_c = commanded_attitude(alpha_c, beta_c, xi, phi)
    alpha_a, beta_a = thrust_angles(psi, theta, phi_roll, xi, phi, delta_y, delta_z)

A step that fails (NaN input, angle out of range, ...) raises KernelError whose ``partial`` is the
safe command the kernel wrote (zero torque and deflections, ``safe`` flag); ``Cpd.step_or_safe``
returns (status, output) instead, for simulation loops that must keep flying.
Angles in rad, rates in rad/s, torque in N m.
"""
from __future__ import annotations

import dataclasses
import enum
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ogk_bindings._ffi import ffi, lib
from ogk_bindings.config import KernelConfig
from ogk_bindings.kernel import Status, ThrustCmd, _check

F64 = NDArray[np.float64]

__all__ = [
    "ANGLE_LIMIT", "Cpd", "CpdConfig", "CpdInput", "CpdOutput", "Flag", "Pointing",
    "commanded_attitude", "pointing_error_body", "thrust_angles", "wrap_pi",
]

ANGLE_LIMIT: float = float(lib.OGK_CPD_ANGLE_LIMIT)
"""Largest |angle| [rad] the kernel accepts (OGK_CPD_ANGLE_LIMIT)."""


class Pointing(enum.IntEnum):
    """Pitch/yaw pointing-error mode (ogk_cpd_pointing_t)."""

    BODY = int(lib.OGK_CPD_POINTING_BODY)
    EULER = int(lib.OGK_CPD_POINTING_EULER)


class Flag(enum.IntFlag):
    """Output flags (OGK_CPD_FLAG_*)."""

    SAT_X = int(lib.OGK_CPD_FLAG_SAT_X)
    SAT_Y = int(lib.OGK_CPD_FLAG_SAT_Y)
    SAT_Z = int(lib.OGK_CPD_FLAG_SAT_Z)
    SAFE = int(lib.OGK_CPD_FLAG_SAFE)
    BEHIND = int(lib.OGK_CPD_FLAG_BEHIND)
    YAW_UNDEFINED = int(lib.OGK_CPD_FLAG_YAW_UNDEFINED)


class CpdConfig(KernelConfig):
    """ogk_cpd_config_t: gains of eqs. (45)-(46), command limits, actuator time constants, the
    braking cap and the feed-forward. Starts from ogk_cpd_config_default (the defaults live in C:
    kernel/include/ogk/cpd.h) and sets any field by its C name; an unknown name is a TypeError.
    ``pointing`` reads back as a `Pointing`."""

    _ctype = "ogk_cpd_config_t"
    _default_fn = "ogk_cpd_config_default"
    _enums = {"pointing": Pointing}


@dataclasses.dataclass(frozen=True)
class CpdInput:
    """ogk_cpd_input_t: attitude, body rates, guidance command and position."""

    psi: float = 0.0            #: [rad] yaw
    theta: float = 0.0          #: [rad] pitch
    phi_roll: float = 0.0       #: [rad] roll
    rate_p: float = 0.0         #: [rad/s]
    rate_q: float = 0.0         #: [rad/s]
    rate_r: float = 0.0         #: [rad/s]
    alpha_c: float = 0.0        #: [rad]
    beta_c: float = 0.0         #: [rad]
    xi: float = 0.0             #: [rad] right ascension
    phi: float = 0.0            #: [rad] declination

    def to_c(self) -> Any:
        c = ffi.new("ogk_cpd_input_t *")
        for f in dataclasses.fields(self):
            setattr(c, f.name, float(getattr(self, f.name)))
        return c

    def with_thrust_cmd(self, cmd: ThrustCmd, xi: float, phi: float) -> "CpdInput":
        """This input with the guidance part from any law's command at position (xi, phi)
        (ogk_cpd_input_from_thrust_cmd: r-t-n angles as they are, an inertial direction rotated
        into r-t-n); KernelError (OGK_E_FRAME for a synodic command) otherwise."""
        c = self.to_c()
        nav = ffi.new("ogk_nav_state_t *")
        nav.xi_rad = float(xi)
        nav.phi_rad = float(phi)
        _check(lib.ogk_cpd_input_from_thrust_cmd(c, cmd.to_c(), nav), "ogk_cpd_input_from_thrust_cmd")
        return dataclasses.replace(self, alpha_c=float(c.alpha_c), beta_c=float(c.beta_c),
                                   xi=float(c.xi), phi=float(c.phi))


@dataclasses.dataclass(frozen=True)
class CpdOutput:
    """ogk_cpd_output_t: saturated commands, commanded attitude, errors used, flags."""

    m_xc: float                 #: [N m]
    delta_yc: float             #: [rad]
    delta_zc: float             #: [rad]
    psi_c: float                #: [rad]
    theta_c: float              #: [rad]
    phi_c: float                #: [rad]
    err_x: float                #: [rad]
    err_y: float                #: [rad]
    err_z: float                #: [rad]
    flags: Flag

    @classmethod
    def from_c(cls, c: Any) -> "CpdOutput":
        values = {f.name: float(getattr(c, f.name)) for f in dataclasses.fields(cls)
                  if f.name != "flags"}
        return cls(**values, flags=Flag(int(c.flags)))

    @property
    def safe(self) -> bool:
        return bool(self.flags & Flag.SAFE)


class Cpd:
    """A kernel CPD context (ogk_cpd_t) owned by Python."""

    def __init__(self, config: CpdConfig) -> None:
        self.config = config
        self._ctx = ffi.new("ogk_cpd_t *")
        self._cfg = config.to_c()
        _check(lib.ogk_cpd_init(self._ctx, self._cfg), "ogk_cpd_init")

    def reset(self) -> None:
        """ogk_cpd_reset: back to the just-initialised state, configuration kept."""
        _check(lib.ogk_cpd_reset(self._ctx), "ogk_cpd_reset")

    def step_or_safe(self, inp: CpdInput) -> tuple[Status, CpdOutput]:
        """One control sample; never raises for a kernel status (the output is then safe)."""
        out = ffi.new("ogk_cpd_output_t *")
        st = lib.ogk_cpd_step(self._ctx, inp.to_c(), out)
        return Status(int(st)), CpdOutput.from_c(out)

    def step(self, inp: CpdInput) -> CpdOutput:
        """One control sample; KernelError (partial = safe command) unless OGK_OK."""
        st, out = self.step_or_safe(inp)
        _check(int(st), "ogk_cpd_step", partial=out)
        return out

    @property
    def last(self) -> CpdOutput:
        """The context's last command (safe command before the first step)."""
        return CpdOutput.from_c(self._ctx.last)


# ----------------------------------------------------------------- geometry (element-wise)
def _elementwise(func: Any, name: str, n_out: int, *args: ArrayLike) -> Any:
    """Calls func over broadcast inputs; floats for scalar inputs, arrays otherwise."""
    arrays = np.broadcast_arrays(*[np.asarray(a, dtype=np.float64) for a in args])
    shape = arrays[0].shape
    flat = [a.ravel() for a in arrays]
    outs = [np.empty(flat[0].size) for _ in range(n_out)]
    ptrs = [ffi.new("ogk_real_t *") for _ in range(n_out)]
    for i in range(flat[0].size):
        _check(func(*[float(a[i]) for a in flat], *ptrs), name)
        for o, p in zip(outs, ptrs):
            o[i] = p[0]
    if shape == ():
        return tuple(float(o[0]) for o in outs) if n_out > 1 else float(outs[0][0])
    return tuple(o.reshape(shape) for o in outs) if n_out > 1 else outs[0].reshape(shape)


def commanded_attitude(alpha_c: ArrayLike, beta_c: ArrayLike, xi: ArrayLike,
                       phi: ArrayLike) -> tuple[Any, Any]:
    """(psi_c, theta_c) [rad] putting x_b on the commanded thrust direction, eqs. (38)-(39)."""
    return _elementwise(lib.ogk_cpd_commanded_attitude, "ogk_cpd_commanded_attitude", 2,
                        alpha_c, beta_c, xi, phi)  # type: ignore[no-any-return]


def thrust_angles(psi: ArrayLike, theta: ArrayLike, phi_roll: ArrayLike, xi: ArrayLike,
                  phi: ArrayLike, delta_y: ArrayLike, delta_z: ArrayLike) -> tuple[Any, Any]:
    """(alpha_a, beta_a) [rad] of the deflected thrust, eqs. (49)-(52)."""
    return _elementwise(lib.ogk_cpd_thrust_angles, "ogk_cpd_thrust_angles", 2,
                        psi, theta, phi_roll, xi, phi, delta_y,
                        delta_z)  # type: ignore[no-any-return]


def pointing_error_body(psi: ArrayLike, theta: ArrayLike, phi_roll: ArrayLike,
                        alpha_c: ArrayLike, beta_c: ArrayLike, xi: ArrayLike,
                        phi: ArrayLike) -> tuple[Any, Any]:
    """(err_y, err_z) [rad]: body components of the rotation vector taking x_b onto T_c."""
    return _elementwise(lib.ogk_cpd_pointing_error_body, "ogk_cpd_pointing_error_body", 2,
                        psi, theta, phi_roll, alpha_c, beta_c, xi,
                        phi)  # type: ignore[no-any-return]


def wrap_pi(angle: ArrayLike) -> Any:
    """angle + 2 pi k in (-pi, pi] (ogk_wrap_pi, ogk/mathutil.h: the one wrap of every law)."""
    return _elementwise(lib.ogk_wrap_pi, "ogk_wrap_pi", 1, angle)
