"""Typed bindings of the kernel's proximity approach (kernel/include/ogk/proximity.h): the planar
Clohessy-Wiltshire problem with a throttled engine, solved by the NMPC's SQP and strategies
(docs/design/nmpc-problem.md).

    model = ProxModel(thrust_max=..., mass_flow_max=..., hold=(x, y), keepout=[(cx, cy, r)])
    g = Proximity(model, nodes=16, rk4_steps=8, horizon_min=..., horizon_max=..., mass_min=...)
    g.load_plan(t0, horizon, states, controls)       # a guess or the ground's plan
    rep = g.solve(t, x)                              # open loop from (t, x), the plan as the guess
    rep = g.replan(t, x)                             # one MPC step
    alpha, throttle, flags, law_flags = g.command(t)
    cmd = g.thrust_cmd(t)                            # r-t-n ThrustCmd (x radial, y along-track)

Normalised units (ogk/proximity.h: LU, TU = 1 / n, MU = the initial mass, so mean_motion = 1 by
default). The solver's settings are ogk_nmpc_config_t's fields by name (ogk_prox_config_default's
defaults: the throttled engine, minimum fuel); its heliocentric model and target fields are not read.
Reports, plans and failures as ogk_bindings.nmpc: ``solve``/``replan`` return a report also when the SQP
fails, bad inputs raise KernelError.
"""
from __future__ import annotations

import dataclasses
from collections.abc import Sequence
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from ogk_bindings._ffi import ffi, lib
from ogk_bindings.config import KernelConfig
from ogk_bindings.kernel import ThrustCmd, _check, _thrust_cmd_call, status_name
from ogk_bindings.nmpc import NmpcPlan, NmpcReport, SolverSettings, plan_cdata, plan_of

__all__ = ["MAX_KEEPOUT", "ProxConfig", "ProxModel", "Proximity"]

NX: int = int(lib.OGK_OCP_NX)
NU: int = 2
MAX_NODES: int = int(lib.OGK_NMPC_MAX_NODES)
MAX_KEEPOUT: int = int(lib.OGK_PROX_MAX_KEEPOUT)


@dataclasses.dataclass(frozen=True)
class ProxModel:
    """ogk_prox_model_t in normalised units."""

    thrust_max: float                         #: [MU LU/TU^2] T_max, > 0
    mass_flow_max: float                      #: [MU/TU] mdot at full throttle, >= 0
    hold: tuple[float, float]                 #: [LU] the hold point (x, y), reached at rest
    keepout: Sequence[tuple[float, float, float]] = ()  #: [LU] discs (centre x, centre y, radius)
    mean_motion: float = 1.0                  #: [rad/TU] n, > 0

    def fields(self) -> dict[str, Any]:
        """The C struct's fields by name (ProxConfig's ``model``)."""
        if len(self.keepout) > MAX_KEEPOUT:
            raise ValueError(f"at most {MAX_KEEPOUT} keep-out discs, got {len(self.keepout)}")
        return {"mean_motion": self.mean_motion, "thrust_max": self.thrust_max,
                "mass_flow_max": self.mass_flow_max, "hold": list(self.hold),
                "n_keepout": len(self.keepout),
                "keepout_centre": [c for d in self.keepout for c in d[:2]],
                "keepout_radius": [d[2] for d in self.keepout]}


class ProxConfig(KernelConfig):
    """ogk_prox_config_t: ``model`` and ``solver`` are nested structs (mappings of their fields)."""

    _ctype = "ogk_prox_config_t"
    _default_fn = "ogk_prox_config_default"


def _report(r: Any, status: int) -> NmpcReport:
    return NmpcReport(status=status_name(status), flags=int(r.flags), sqp_iterations=int(r.sqp_iterations),
                      qp_iterations=int(r.qp_iterations), solves=int(r.solves), nodes=int(r.nodes),
                      t_next=float(r.t_next), t_f=float(r.t_f), objective=float(r.objective),
                      feas=float(r.feas), stat=float(r.stat))


class Proximity(SolverSettings):
    """One ogk_prox_t context (owned by Python); its in-flight settings through ogk_prox_set_*."""

    PREFIX = "ogk_prox"

    def __init__(self, model: ProxModel, **solver: Any) -> None:
        self.config = ProxConfig(model=model.fields(), solver=solver)
        self._ctx = ffi.new("ogk_prox_t *")
        _check(lib.ogk_prox_init(self._ctx, self.config.to_c()), "ogk_prox_init")
        self._in = ffi.new("ogk_nmpc_input_t *")
        self._rep = ffi.new("ogk_nmpc_report_t *")
        self._cmd = ffi.new("ogk_nmpc_command_t *")

    def reset(self) -> None:
        _check(lib.ogk_prox_reset(self._ctx), "ogk_prox_reset")

    def _solver(self) -> Any:
        return self._ctx.nmpc

    def load_plan(self, t0: float, horizon: float, states: ArrayLike, controls: ArrayLike,
                  multipliers: ArrayLike | None = None) -> None:
        """Node states (N + 1, 5) [LU, LU, LU/TU, LU/TU, MU], controls (N + 1, 2) (alpha [rad], w)."""
        x = np.ascontiguousarray(states, dtype=np.float64)
        u = np.ascontiguousarray(controls, dtype=np.float64)
        n = x.shape[0] - 1
        if x.ndim != 2 or x.shape[1] != NX or not 1 <= n <= MAX_NODES or u.shape != (n + 1, NU):
            raise ValueError(f"states (N + 1, {NX}) and controls (N + 1, {NU}) with 1 <= N <= {MAX_NODES}, "
                             f"got {x.shape} and {u.shape}")
        _check(lib.ogk_prox_load_plan(self._ctx, plan_cdata(t0, horizon, x, u, multipliers)), "ogk_prox_load_plan")

    def plan(self) -> NmpcPlan:
        p = ffi.new("ogk_nmpc_plan_t *")
        _check(lib.ogk_prox_get_plan(self._ctx, p), "ogk_prox_get_plan")
        return plan_of(p)

    def _call(self, fn: str, t: float, x: ArrayLike) -> NmpcReport:
        self._in.t = float(t)
        xs = np.ascontiguousarray(x, dtype=np.float64).reshape(-1)
        if xs.size != NX:
            raise ValueError(f"the state has {NX} components, got {xs.size}")
        for i in range(NX):
            self._in.x[i] = float(xs[i])
        status = int(getattr(lib, fn)(self._ctx, self._in, self._rep))
        solver_codes = {int(lib.OGK_OK), int(lib.OGK_E_ITER_LIMIT), int(lib.OGK_E_NOT_CONVERGED),
                        int(lib.OGK_E_INFEASIBLE), int(lib.OGK_E_NOT_POSDEF)}
        solver_failed_inside = status == int(lib.OGK_E_NONFINITE) and self._rep.solves > 0
        if status not in solver_codes and not solver_failed_inside:
            _check(status, fn)
        return _report(self._rep, status)

    def solve(self, t: float, x: ArrayLike) -> NmpcReport:
        return self._call("ogk_prox_solve", t, x)

    def replan(self, t: float, x: ArrayLike) -> NmpcReport:
        return self._call("ogk_prox_replan", t, x)

    def command(self, t: float) -> tuple[float, float, int, int]:
        _check(lib.ogk_prox_command(self._ctx, float(t), self._cmd), "ogk_prox_command")
        c = self._cmd
        return float(c.alpha), float(c.throttle), int(c.flags), int(c.law_flags)

    def thrust_cmd(self, t: float) -> ThrustCmd:
        """ogk_prox_thrust_cmd: the plan's command at t [TU] in r-t-n; KernelError (partial = the safe
        command) when there is none."""
        return _thrust_cmd_call("ogk_prox_thrust_cmd", self._ctx, t)
