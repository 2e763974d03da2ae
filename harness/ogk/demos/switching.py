"""Switching demo: minimum-fuel rest-to-rest transfer of a double integrator.

The kernel's RK4 integrates x = [r, v, lambda_r, lambda_v] with the harness's C
model (bindings/csrc/models.c) and locates the zeros of S = |lambda_v| - 1 by
bisection; the closed form (ogk_bindings.models.RestToRest) gives the exact switching
times and states. RK4 is exact for these piecewise-quadratic motions, so every
error left is the switch location's."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ogk_bindings import kernel, models


@dataclass(frozen=True)
class SwitchingDemo:
    problem: models.RestToRest
    step: float
    result: kernel.Rk4Result
    t_exact: tuple[float, ...]
    x_final_exact: np.ndarray

    @property
    def t_located(self) -> tuple[float, ...]:
        return tuple(e.t for e in self.result.switches)

    @property
    def switch_errors(self) -> np.ndarray:
        if len(self.t_located) != len(self.t_exact):
            return np.full(len(self.t_exact), np.inf)
        return np.subtract(self.t_located, self.t_exact)

    @property
    def final_error(self) -> np.ndarray:
        return self.result.xf - self.x_final_exact

    def ok(self, tolerance: float) -> bool:
        return bool(np.all(np.abs(self.switch_errors) <= tolerance)
                    and np.all(np.abs(self.final_error) <= tolerance))


def run_switching_demo(distance: float = 1.0, duration: float = 3.0, u_max: float = 1.0,
                       step: float = 0.1) -> SwitchingDemo:
    problem = models.RestToRest(distance=distance, duration=duration, u_max=u_max)
    model = models.min_fuel_double_integrator(u_max)
    result = kernel.rk4_propagate(model, problem.initial_state(), 0.0, duration, step,
                                  mode0=1, s_tol=1e-14, t_tol=1e-15)
    return SwitchingDemo(problem=problem, step=step, result=result,
                         t_exact=problem.switch_times,
                         x_final_exact=np.array(problem.state(duration)))


def format_report(demo: SwitchingDemo) -> str:
    p, r = demo.problem, demo.result
    lines = [
        f"min-fuel rest-to-rest double integrator: D = {p.distance:g}, T = {p.duration:g}, "
        f"u_max = {p.u_max:g}, RK4 step h = {demo.step:g}",
        f"kernel: {len(r.switches)} switches, {r.n_steps} steps, {r.n_rhs} rhs calls, "
        f"final mode {r.mode_final}",
        f"{'switch':>6} {'located t [s]':>22} {'closed form t [s]':>22} {'error [s]':>11} "
        f"{'mode after':>10} {'bisections':>10}",
    ]
    errors = demo.switch_errors
    for i, t_ex in enumerate(demo.t_exact):
        if i < len(r.switches):
            e = r.switches[i]
            lines.append(f"{i + 1:>6} {e.t:22.16f} {t_ex:22.16f} {errors[i]:11.2e} "
                         f"{e.mode_after:>10d} {e.bisections:>10d}")
        else:
            lines.append(f"{i + 1:>6} {'(not found)':>22} {t_ex:22.16f}")
    for extra in r.switches[len(demo.t_exact):]:
        lines.append(f"unexpected switch at t = {extra.t:.16f}")
    fe = demo.final_error
    lines.append(f"final state [r, v, lambda_r, lambda_v] error: "
                 + ", ".join(f"{v:.2e}" for v in fe)
                 + f"  (max |error| = {np.max(np.abs(fe)):.2e})")
    return "\n".join(lines)
