"""Typed bindings of the kernel's receding-horizon NMPC (kernel/include/ogk/nmpc.h, docs/design/nmpc.md).

    cfg = NmpcConfig(thrust_max=..., mass_flow_max=..., target_radius=..., target_phase0=...,
                     target_rate=..., nodes=30, strategy=SNNS)   # ogk_nmpc_config_default underneath
    g = Nmpc(cfg)                                    # ogk_nmpc_init (KernelError on a rejected config)
    g.load_plan(t0, horizon, states, controls)       # the ground's plan or a guess
    rep = g.solve(t, x)                              # open loop from (t, x), the plan as the guess
    rep = g.replan(t, x)                             # one MPC step: strategy shift, solve, doubling test
    alpha, throttle, flags, law_flags = g.command(t)
    cmd = g.thrust_cmd(t)                            # the one command of every law (r-t-n ThrustCmd)

Normalised units throughout (the scenario's LU, TU, MU). ``solve``/``replan`` return a report also when
the SQP fails (``rep.status`` names why, the previous plan stays flown); bad inputs raise KernelError.
"""
from __future__ import annotations

import dataclasses
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ogk_bindings._ffi import ffi, lib
from ogk_bindings._real import real_array, real_in, real_out, real_view, to_f64, to_real
from ogk_bindings.config import KernelConfig
from ogk_bindings.kernel import ThrustCmd, _check, _thrust_cmd_call, status_name

F64 = NDArray[np.float64]

__all__ = ["CNCN", "SNNS", "MAX_NODES", "Nmpc", "NmpcConfig", "NmpcReport", "NmpcPlan", "plan_cdata", "plan_of"]

NX: int = int(lib.OGK_NMPC_NX)
MAX_NODES: int = int(lib.OGK_NMPC_MAX_NODES)
MAX_NU: int = int(lib.OGK_NMPC_MAX_NU)
SNNS: int = int(lib.OGK_NMPC_SNNS)
CNCN: int = int(lib.OGK_NMPC_CNCN)
FLAG_CONVERGED: int = int(lib.OGK_NMPC_FLAG_CONVERGED)
FLAG_STALE: int = int(lib.OGK_NMPC_FLAG_STALE)
FLAG_SUBDIVIDED: int = int(lib.OGK_NMPC_FLAG_SUBDIVIDED)
FLAG_REGRIDDED: int = int(lib.OGK_NMPC_FLAG_REGRIDDED)
FLAG_RELEASED: int = int(lib.OGK_NMPC_FLAG_RELEASED)
FLAG_OUTSIDE_SET: int = int(lib.OGK_NMPC_FLAG_OUTSIDE_SET)


class NmpcConfig(KernelConfig):
    _ctype = "ogk_nmpc_config_t"
    _default_fn = "ogk_nmpc_config_default"


@dataclasses.dataclass(frozen=True)
class NmpcPlan:
    t0: float               #: [TU] time of node 0
    horizon: float          #: [TU] t_f - t0
    states: F64             #: (N + 1, 5)
    controls: F64           #: (N + 1, nu)
    multipliers: F64        #: (4,) of eq. (5)


@dataclasses.dataclass(frozen=True)
class NmpcReport:
    status: str             #: "OGK_OK" or why the (last) solve failed
    flags: int              #: OGK_NMPC_FLAG_*
    sqp_iterations: int
    qp_iterations: int
    solves: int
    nodes: int
    t_next: float           #: [TU]
    t_f: float              #: [TU]
    objective: float        #: [TU or MU]
    feas: float
    stat: float

    @property
    def converged(self) -> bool:
        return self.status == "OGK_OK"

    @property
    def subdivided(self) -> bool:
        return bool(self.flags & FLAG_SUBDIVIDED)


def plan_cdata(t0: float, horizon: float, x: NDArray[np.float64], u: NDArray[np.float64],
               multipliers: ArrayLike | None = None) -> object:
    """An ogk_nmpc_plan_t of node states x (N + 1, NX) and controls u (N + 1, nu), checked by the caller
    (shared by every problem's bindings: ogk_bindings.proximity too)."""
    plan = ffi.new("ogk_nmpc_plan_t *")
    plan.t0 = float(t0)
    plan.horizon = float(horizon)
    plan.nodes = x.shape[0] - 1
    plan.nu = u.shape[1]
    xr, ur = to_real(x), to_real(u)  # the kernel's real type (ogk_bindings._real)
    ffi.memmove(plan.x, xr.tobytes(), xr.nbytes)
    ffi.memmove(plan.u, ur.tobytes(), ur.nbytes)
    if multipliers is not None:
        lam = to_real(multipliers)
        ffi.memmove(getattr(plan, "lambda"), lam.tobytes(), lam.nbytes)
    return plan


def plan_of(p: object) -> NmpcPlan:
    """The NmpcPlan of an ogk_nmpc_plan_t."""
    c: Any = p
    n, nu = int(c.nodes), int(c.nu)
    x = real_view(c.x, (n + 1) * NX).reshape(n + 1, NX)
    u = real_view(c.u, (n + 1) * nu).reshape(n + 1, nu)
    lam = np.array([getattr(c, "lambda")[i] for i in range(4)])
    return NmpcPlan(t0=float(c.t0), horizon=float(c.horizon), states=x, controls=u, multipliers=lam)


class SolverSettings:
    """The in-flight settings of a context (ogk/nmpc.h, ogk_nmpc_set_*), shared by `Nmpc` and
    `ogk_bindings.proximity.Proximity`: PREFIX names its C functions, `_solver` its ogk_nmpc_t."""

    PREFIX = "ogk_nmpc"
    _ctx: Any

    def _solver(self) -> Any:
        return self._ctx

    def set_horizon_bounds(self, horizon_min: float, horizon_max: float) -> None:
        """The bounds of T [TU] of the solves and replans that follow (PREFIX_set_horizon_bounds)."""
        fn = f"{self.PREFIX}_set_horizon_bounds"
        _check(getattr(lib, fn)(self._ctx, float(horizon_min), float(horizon_max)), fn)

    def set_hessian_init(self, hessian_init: float) -> None:
        """The first BFGS matrix's scale of the next cold solve (PREFIX_set_hessian_init)."""
        fn = f"{self.PREFIX}_set_hessian_init"
        _check(getattr(lib, fn)(self._ctx, float(hessian_init)), fn)

    @property
    def horizon_bounds(self) -> tuple[float, float]:
        """The bounds of T [TU] in force."""
        cfg = self._solver().cfg
        return float(cfg.horizon_min), float(cfg.horizon_max)

    @property
    def hessian_init(self) -> float:
        """The first BFGS matrix's scale in force."""
        return float(self._solver().cfg.hessian_init)


class Nmpc(SolverSettings):
    """One ogk_nmpc_t context (owned by Python; ~230 KiB with the default limits)."""

    def __init__(self, cfg: NmpcConfig) -> None:
        self._ctx = ffi.new("ogk_nmpc_t *")
        _check(lib.ogk_nmpc_init(self._ctx, cfg.to_c()), "ogk_nmpc_init")
        self.nu = int(self._ctx.nu)
        self._in = ffi.new("ogk_nmpc_input_t *")
        self._rep = ffi.new("ogk_nmpc_report_t *")
        self._cmd = ffi.new("ogk_nmpc_command_t *")

    def reset(self) -> None:
        _check(lib.ogk_nmpc_reset(self._ctx), "ogk_nmpc_reset")

    def load_plan(self, t0: float, horizon: float, states: ArrayLike, controls: ArrayLike,
                  multipliers: ArrayLike | None = None) -> None:
        x = np.ascontiguousarray(states, dtype=np.float64)
        u = np.ascontiguousarray(controls, dtype=np.float64).reshape(x.shape[0], -1)
        n = x.shape[0] - 1
        if x.ndim != 2 or x.shape[1] != NX or not 1 <= n <= MAX_NODES:
            raise ValueError(f"states must be (N + 1, {NX}) with 1 <= N <= {MAX_NODES}, got {x.shape}")
        _check(lib.ogk_nmpc_load_plan(self._ctx, plan_cdata(t0, horizon, x, u, multipliers)), "ogk_nmpc_load_plan")

    def plan(self) -> NmpcPlan:
        p = ffi.new("ogk_nmpc_plan_t *")
        _check(lib.ogk_nmpc_get_plan(self._ctx, p), "ogk_nmpc_get_plan")
        return plan_of(p)

    def _call(self, fn: str, t: float, x: ArrayLike) -> NmpcReport:
        self._in.t = float(t)
        xs = np.ascontiguousarray(x, dtype=np.float64)
        for i in range(NX):
            self._in.x[i] = float(xs[i])
        status = int(getattr(lib, fn)(self._ctx, self._in, self._rep))
        solver_codes = {int(lib.OGK_OK), int(lib.OGK_E_ITER_LIMIT), int(lib.OGK_E_NOT_CONVERGED),
                        int(lib.OGK_E_INFEASIBLE), int(lib.OGK_E_NOT_POSDEF)}
        r = self._rep
        solver_failed_inside = status == int(lib.OGK_E_NONFINITE) and r.solves > 0
        if status not in solver_codes and not solver_failed_inside:
            _check(status, fn)
        return NmpcReport(status=status_name(status), flags=int(r.flags), sqp_iterations=int(r.sqp_iterations),
                          qp_iterations=int(r.qp_iterations), solves=int(r.solves), nodes=int(r.nodes),
                          t_next=float(r.t_next), t_f=float(r.t_f), objective=float(r.objective),
                          feas=float(r.feas), stat=float(r.stat))

    def solve(self, t: float, x: ArrayLike) -> NmpcReport:
        return self._call("ogk_nmpc_solve", t, x)

    def replan(self, t: float, x: ArrayLike) -> NmpcReport:
        return self._call("ogk_nmpc_replan", t, x)

    def command(self, t: float) -> tuple[float, float, int, int]:
        _check(lib.ogk_nmpc_command(self._ctx, float(t), self._cmd), "ogk_nmpc_command")
        c = self._cmd
        return float(c.alpha), float(c.throttle), int(c.flags), int(c.law_flags)

    def thrust_cmd(self, t: float) -> ThrustCmd:
        """ogk_nmpc_thrust_cmd: the plan's command at t [TU] in r-t-n (alpha = pi/2 - the angle
        from the vertical); KernelError (partial = the safe command) when there is none."""
        return _thrust_cmd_call("ogk_nmpc_thrust_cmd", self._ctx, t)

    # Test entry points (kernel/include/ogk/internal/nmpc_test.h, not flight API).
    def model_rhs(self, t: float, x: ArrayLike, u: ArrayLike) -> F64:
        xs = np.ascontiguousarray(x, dtype=np.float64)
        us = np.ascontiguousarray(u, dtype=np.float64)
        out = real_array(NX)
        _check(lib.ogk_nmpc_model_rhs(self._ctx, float(t), real_in(xs), real_in(us), real_out(out)),
               "ogk_nmpc_model_rhs")
        return to_f64(out)

    def interval(self, t0: float, h: float, x0: ArrayLike, u0: ArrayLike,
                 u1: ArrayLike) -> tuple[F64, F64, F64, F64, F64, F64]:
        """(x1, dfdx (5, 5), dfdu0 (5, nu), dfdu1 (5, nu), dfdh (5,), dfdt0 (5,)) of one subinterval."""
        nu = self.nu
        bufs = [real_array(NX), real_array(NX * NX), real_array(NX * nu), real_array(NX * nu), real_array(NX),
                real_array(NX)]
        xs = np.ascontiguousarray(x0, dtype=np.float64)
        a = np.ascontiguousarray(u0, dtype=np.float64)
        b = np.ascontiguousarray(u1, dtype=np.float64)
        _check(lib.ogk_nmpc_interval(self._ctx, float(t0), float(h), real_in(xs), real_in(a), real_in(b),
                                     *[real_out(q) for q in bufs]), "ogk_nmpc_interval")
        out = [to_f64(q) for q in bufs]
        return (out[0], out[1].reshape(NX, NX), out[2].reshape(NX, nu), out[3].reshape(NX, nu),
                out[4], out[5])
