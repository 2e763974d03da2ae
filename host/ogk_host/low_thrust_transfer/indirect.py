"""Fuel-optimal rendezvous by the indirect method (paper 000, sections 2.2 and 3.3).

Unknowns: the initial costates lambda_0 = [lambda_r0, lambda_v0, lambda_m0] (7). Shooting function:
    F(lambda_0) = [r(t_f) - r_f, v(t_f) - v_f, lambda_m(t_f)]          (eqs. 3 and 7)
with t_f fixed and the final mass free. Its Jacobian comes from the variational equations
(Phi = dz/dlambda_0, 14 x 7), with the jump of eq. (24) applied at every bang-off-bang switch.

Smoothing homotopy (eq. 48): energy-optimal zeta = 1 down to zeta = 0 in steps of 0.05 (halved
locally when Newton fails), each level warm-started by secant extrapolation of the previous two;
the last level, zeta = 0, integrates arc by arc with the exact zeros of S found as events
(DOP853, rtol 1e-12; extrema of S are located too, so a zero pair inside one step is not missed).
The energy-optimal start is deterministic: a target continuation from the ballistic arc with the
thrust boosted (unsaturated throttle), then the thrust brought back to its value (docs/design/apophis-nominal.md).

`solve_fuel_optimal(scenario, perturbation, warm_start)` solves nominal or perturbed problems; from a
warm start it continues the perturbation C_tau = (1 - tau) C_nom + tau C_per (eq. 51), first directly
in the bang-off-bang problem, then, if the switching structure changes too much for Newton, along the
smoothed problem (zeta_c) followed by zeta -> 0.
"""
from __future__ import annotations

import dataclasses
import json
import time
from pathlib import Path
from typing import Callable

import numpy as np
from numpy.typing import NDArray
from scipy.integrate import OdeSolution, solve_ivp
from scipy.optimize import brentq

from . import dynamics as dyn
from .scenario import NormalisedProblem, Perturbation, Scenario, normalised_problem

FloatArray = NDArray[np.float64]

DATA_DIR = Path(__file__).resolve().parent / "data"
#: the shipped cache (of the scenario whose physics_sha256 each file states; products.py), read only
NOMINAL_PATH = DATA_DIR / "nominal_solution.json"
REFERENCES_PATH = DATA_DIR / "perturbed_optima.json"
MAX_ARCS = 200
LAMBDA_LIMIT = 1.0e3   # |lambda_0| components beyond this are treated as divergence


class ShootingFailure(RuntimeError):
    """Newton/continuation did not converge."""


# ---------------------------------------------------------------------------------------------------
# propagation
@dataclasses.dataclass(frozen=True)
class Arc:
    t_start: float   #: [TU]
    t_end: float     #: [TU]
    throttle: float  #: u on the arc (0 or 1)


@dataclasses.dataclass
class Propagation:
    z_final: FloatArray             #: (14,) state-costate at t_f
    phi_final: FloatArray | None    #: (14, 7) dz(t_f)/dlambda_0, if requested
    arcs: list[Arc]                 #: bang-off-bang arcs (zeta = 0 only)
    segments: list[OdeSolution]     #: dense output per arc (if requested)
    segment_bounds: list[tuple[float, float]]
    n_rhs: int

    @property
    def switch_times(self) -> FloatArray:
        return np.array([a.t_start for a in self.arcs[1:]])

    def sample(self, t: FloatArray) -> FloatArray:
        """z(t) (len(t), 14) from the dense output (propagate(..., dense=True))."""
        t = np.atleast_1d(np.asarray(t, dtype=np.float64))
        out = np.empty((t.size, dyn.N_Z))
        for k, (seg, (t0, t1)) in enumerate(zip(self.segments, self.segment_bounds)):
            last = k == len(self.segments) - 1
            mask = (t >= t0) & ((t <= t1) if last else (t < t1))
            if np.any(mask):
                out[mask] = seg(t[mask]).T[:, :dyn.N_Z]
        return out


def _initial_throttle(z0: FloatArray, problem: NormalisedProblem) -> float:
    s0 = float(dyn.switching_function(z0, problem.exhaust_velocity))
    if s0 == 0.0:
        s0 = -float(dyn.switching_function_rate(z0, problem))
    return 1.0 if s0 < 0.0 else 0.0


def propagate(problem: NormalisedProblem, lam0: FloatArray, zeta: float, *, stm: bool = False,
              rtol: float = 1e-12, atol: float = 1e-13, dense: bool = False) -> Propagation:
    """Integrate state and costates from t_0 = 0 to t_f.

    zeta > 0: smoothed throttle (eq. 48), one integration. zeta = 0: bang-off-bang (eq. 11), arc by
    arc, each switch located as an event S = 0 (solve_ivp root finding on the DOP853 dense output),
    with the STM jump of eq. (24).
    """
    z0 = np.concatenate([problem.x0, lam0])
    n_phi = dyn.N_Z * dyn.N_PARAM
    y0 = np.concatenate([z0, np.vstack([np.zeros((dyn.N_STATE, dyn.N_PARAM)),
                                        np.eye(dyn.N_PARAM)]).ravel()]) if stm else z0
    tf = problem.final_time
    if zeta > 0.0:
        if stm:
            fun: Callable[[float, FloatArray], FloatArray] = (
                lambda t, y: dyn.smoothed_rhs_with_stm(y, zeta, problem))
        else:
            def fun(t: float, y: FloatArray) -> FloatArray:
                s = float(dyn.switching_function(y, problem.exhaust_velocity))
                return dyn.rhs(y, float(dyn.smoothed_throttle(s, zeta)), problem)
        sol = solve_ivp(fun, (0.0, tf), y0, method="DOP853", rtol=rtol, atol=atol,
                        dense_output=dense)
        if sol.status != 0:
            raise ShootingFailure(f"integration failed: {sol.message}")
        y_end = sol.y[:, -1]
        return Propagation(y_end[:dyn.N_Z].copy(),
                           y_end[dyn.N_Z:].reshape(dyn.N_Z, dyn.N_PARAM).copy() if stm else None,
                           [], [sol.sol] if dense else [], [(0.0, tf)] if dense else [], sol.nfev)

    c = problem.exhaust_velocity

    def switch_event(t: float, y: FloatArray) -> float:
        return float(dyn.switching_function(y[:dyn.N_Z], c))

    def extremum_event(t: float, y: FloatArray) -> float:
        return float(dyn.switching_function_rate(y[:dyn.N_Z], problem))

    switch_event.terminal = True  # type: ignore[attr-defined]
    extremum_event.terminal = False  # type: ignore[attr-defined]
    throttle = _initial_throttle(z0, problem)
    t_start, y = 0.0, y0
    arcs: list[Arc] = []
    segments: list[OdeSolution] = []
    bounds: list[tuple[float, float]] = []
    n_rhs = 0
    for _ in range(MAX_ARCS):
        thrusting = throttle == 1.0
        # thrusting (S < 0) ends when S rises through 0, coasting when it falls through 0. A zero pair
        # inside one step escapes a sign test at the step ends (short, shallow arcs): every extremum of
        # S on the way (a maximum while thrusting, a minimum while coasting) is located too, and one on
        # the wrong side of 0 means a missed switch before it.
        switch_event.direction = 1.0 if thrusting else -1.0  # type: ignore[attr-defined]
        extremum_event.direction = -1.0 if thrusting else 1.0  # type: ignore[attr-defined]
        if stm:
            fun = (lambda u: lambda t, yy: dyn.fixed_throttle_rhs_with_stm(yy, u, problem))(throttle)
        else:
            fun = (lambda u: lambda t, yy: dyn.rhs(yy, u, problem))(throttle)
        sol = solve_ivp(fun, (t_start, tf), y, method="DOP853", rtol=rtol, atol=atol,
                        events=(switch_event, extremum_event), dense_output=dense)
        n_rhs += sol.nfev
        if sol.status == -1:
            raise ShootingFailure(f"integration failed: {sol.message}")
        t_end = float(sol.t_events[0][0]) if sol.status == 1 else tf
        missed = [float(te) for te, ye in zip(sol.t_events[1], sol.y_events[1])
                  if te < t_end and (switch_event(te, ye) > 0.0) == thrusting]
        if missed:
            t_extremum = missed[0]
            rerun = solve_ivp(fun, (t_start, t_extremum), y, method="DOP853", rtol=rtol, atol=atol,
                              dense_output=True)
            n_rhs += rerun.nfev
            t_low = float(rerun.t[-2]) if rerun.t.size > 1 else t_start
            t_switch = float(brentq(lambda tt: switch_event(tt, rerun.sol(tt)), t_low, t_extremum,
                                    xtol=1e-15, rtol=4.0 * np.finfo(float).eps))
            y_switch = rerun.sol(t_switch)
            dense_segment = rerun.sol
        elif sol.status == 1 and t_end < tf:
            t_switch, y_switch = t_end, sol.y_events[0][0].copy()
            dense_segment = sol.sol
        else:
            y = sol.y[:, -1]
            arcs.append(Arc(t_start, tf, throttle))
            if dense:
                segments.append(sol.sol)
                bounds.append((t_start, tf))
            break
        arcs.append(Arc(t_start, t_switch, throttle))
        if dense:
            segments.append(dense_segment)
            bounds.append((t_start, t_switch))
        new_throttle = 1.0 - throttle
        y = np.array(y_switch, dtype=np.float64)
        if stm:
            phi = y[dyn.N_Z:].reshape(dyn.N_Z, dyn.N_PARAM)
            y[dyn.N_Z:] = dyn.switch_jump(y[:dyn.N_Z], phi, throttle, new_throttle, problem).ravel()
        throttle, t_start = new_throttle, t_switch
    else:
        raise ShootingFailure(f"more than {MAX_ARCS} arcs (chattering switching function)")
    return Propagation(y[:dyn.N_Z].copy(),
                       y[dyn.N_Z:].reshape(dyn.N_Z, dyn.N_PARAM).copy() if stm else None,
                       arcs, segments, bounds, n_rhs)


def shooting_residual(problem: NormalisedProblem, z_final: FloatArray) -> FloatArray:
    """F = [r(t_f) - r_f, v(t_f) - v_f, lambda_m(t_f)] (eqs. 3, 7)."""
    return np.concatenate([z_final[0:3] - problem.rf, z_final[3:6] - problem.vf, z_final[13:14]])


_RESIDUAL_ROWS = np.array([0, 1, 2, 3, 4, 5, 13])


# ---------------------------------------------------------------------------------------------------
# Newton on the shooting function
@dataclasses.dataclass
class NewtonResult:
    lam0: FloatArray
    residual: FloatArray
    iterations: int
    converged: bool
    propagation: Propagation


def newton_shoot(problem: NormalisedProblem, lam0: FloatArray, zeta: float, *, rtol: float,
                 tol: float = 1e-10, max_iter: int = 30, max_halvings: int = 10,
                 max_step: float = 0.0) -> NewtonResult:
    """Damped Newton with the STM Jacobian and a backtracking line search on ||F||.

    max_step > 0 caps the Newton step norm (useful far from the solution).
    """
    lam = np.asarray(lam0, dtype=np.float64).copy()
    prop = propagate(problem, lam, zeta, stm=True, rtol=rtol)
    res = shooting_residual(problem, prop.z_final)
    norm = float(np.linalg.norm(res))
    for it in range(1, max_iter + 1):
        if not np.isfinite(norm):
            break
        if norm < tol:
            return NewtonResult(lam, res, it - 1, True, prop)
        jac = prop.phi_final[_RESIDUAL_ROWS]  # type: ignore[index]
        try:
            step = -np.linalg.solve(jac, res)
        except np.linalg.LinAlgError:
            step = -np.linalg.lstsq(jac, res, rcond=None)[0]
        if max_step > 0.0:
            step_norm = float(np.linalg.norm(step))
            if step_norm > max_step:
                step *= max_step / step_norm
        alpha = 1.0
        for _ in range(max_halvings + 1):
            trial = lam + alpha * step
            if float(np.max(np.abs(trial))) > LAMBDA_LIMIT:   # runaway costates: shorten the step
                alpha *= 0.5
                continue
            try:
                trial_prop = propagate(problem, trial, zeta, stm=True, rtol=rtol)
                trial_res = shooting_residual(problem, trial_prop.z_final)
                trial_norm = float(np.linalg.norm(trial_res))
            except (ShootingFailure, FloatingPointError, ValueError):
                trial_norm = np.inf
            if np.isfinite(trial_norm) and trial_norm < (1.0 - 1e-4 * alpha) * norm:
                break
            alpha *= 0.5
        else:
            return NewtonResult(lam, res, it, False, prop)
        lam, prop, res, norm = trial, trial_prop, trial_res, trial_norm
    return NewtonResult(lam, res, max_iter, norm < tol, prop)


# ---------------------------------------------------------------------------------------------------
# energy-optimal start and smoothing homotopy
def _to_cylindrical(r: FloatArray, v: FloatArray) -> FloatArray:
    """[rho, theta, z, v_rho, v_theta, v_z] in the ecliptic frame."""
    theta = float(np.arctan2(r[1], r[0]))
    e_rho = np.array([np.cos(theta), np.sin(theta), 0.0])
    e_theta = np.array([-np.sin(theta), np.cos(theta), 0.0])
    return np.array([np.hypot(r[0], r[1]), theta, r[2], v @ e_rho, v @ e_theta, v[2]])


def _from_cylindrical(cyl: FloatArray) -> tuple[FloatArray, FloatArray]:
    rho, theta, z, v_rho, v_theta, v_z = cyl
    e_rho = np.array([np.cos(theta), np.sin(theta), 0.0])
    e_theta = np.array([-np.sin(theta), np.cos(theta), 0.0])
    return (rho * e_rho + np.array([0.0, 0.0, z]),
            v_rho * e_rho + v_theta * e_theta + np.array([0.0, 0.0, v_z]))


def _continue(solve: Callable[[float, FloatArray], NewtonResult | None], lam0: FloatArray,
              first_step: float, min_step: float, what: str,
              log: Callable[[str], None] | None,
              predictor: Callable[[float, float, FloatArray, tuple[float, FloatArray] | None],
                                  FloatArray] | None = None,
              ) -> tuple[NewtonResult, int]:
    """Natural-parameter continuation s: 0 -> 1 with secant predictor and adaptive steps.

    solve(s, guess) returns a NewtonResult (or raises ShootingFailure); predictor(s_now, s_new, lam,
    previous (s, lam) or None) replaces the default secant predictor when given.
    """
    s_now, step, lam, total = 0.0, first_step, lam0.copy(), 0
    prev: tuple[float, FloatArray] | None = None
    result: NewtonResult | None = None
    while s_now < 1.0:
        target = min(1.0, s_now + step)
        if predictor is not None:
            guess = predictor(s_now, target, lam, prev)
        elif prev is not None:
            guess = lam + (lam - prev[1]) * (target - s_now) / (s_now - prev[0])
        else:
            guess = lam
        try:
            trial = solve(target, guess)
        except ShootingFailure:
            trial = None
        if trial is not None:
            total += trial.iterations
        if trial is None or not trial.converged:
            step *= 0.5
            if step < min_step:
                raise ShootingFailure(f"{what} continuation stalled at {s_now:.4g}")
            continue
        if log:
            log(f"  {what} {target:.4g}: {trial.iterations} iterations, "
                f"m_f = {trial.propagation.z_final[6]:.6f}")
        prev, s_now, lam, result = (s_now, lam), target, trial.lam0, trial
        if trial.iterations <= 4:
            step = min(2.0 * step, 1.0)
    assert result is not None
    return result, total


def energy_optimal_start(problem: NormalisedProblem, scenario: Scenario, *,
                         log: Callable[[str], None] | None = None) -> tuple[NewtonResult, int]:
    """Energy-optimal solution (zeta = zeta_start) by two deterministic continuations.

    1. With T_max multiplied by k = thrust_factor_start the energy-optimal throttle does not saturate.
       lambda_0 ~ 0 (no thrust) solves the problem whose target is the ballistic end state; the target
       is moved to (r_f, v_f) along a straight line in cylindrical coordinates (rho, theta, z and
       velocity components), theta taking the shorter way round.
    2. k is brought down to 1. While the throttle is unsaturated, u k and the trajectory do not depend
       on k and lambda scales as 1/k: that is the first predictor, secant extrapolation afterwards.
    Returns (solution, Newton iterations).
    """
    h = scenario.homotopy
    zeta, rtol = h.zeta_start, h.smoothed_rtol
    k0 = h.thrust_factor_start
    boosted = dataclasses.replace(problem, max_thrust=problem.max_thrust * k0)
    lam_ballistic = np.array([0.0, 0.0, 0.0, 1e-9, 0.0, 0.0, 0.0])
    z_ballistic = propagate(boosted, lam_ballistic, zeta, rtol=rtol).z_final
    cyl_start = _to_cylindrical(z_ballistic[0:3], z_ballistic[3:6])
    cyl_end = _to_cylindrical(problem.rf, problem.vf)
    cyl_end[1] = cyl_start[1] + (cyl_end[1] - cyl_start[1] + np.pi) % (2.0 * np.pi) - np.pi

    def solve_target(s: float, guess: FloatArray) -> NewtonResult:
        rf, vf = _from_cylindrical((1.0 - s) * cyl_start + s * cyl_end)
        return newton_shoot(dataclasses.replace(boosted, rf=rf, vf=vf), guess, zeta, rtol=rtol,
                            max_iter=12)

    if log:
        log(f"energy-optimal start: thrust factor {k0:g}, target continuation from the ballistic arc")
    result, iterations = _continue(solve_target, lam_ballistic, 0.25, 1e-3, "target s", log)

    def thrust_factor(s: float) -> float:
        return k0 + s * (1.0 - k0)

    def solve_thrust(s: float, guess: FloatArray) -> NewtonResult:
        scaled = dataclasses.replace(problem, max_thrust=problem.max_thrust * thrust_factor(s))
        return newton_shoot(scaled, guess, zeta, rtol=rtol, max_iter=12)

    def scaling_predictor(s_now: float, s_new: float, lam: FloatArray,
                          prev: tuple[float, FloatArray] | None) -> FloatArray:
        # secant on k lambda, which is constant while the throttle is unsaturated
        k_now, k_new = thrust_factor(s_now), thrust_factor(s_new)
        scaled = k_now * lam
        if prev is not None:
            scaled = scaled + (scaled - thrust_factor(prev[0]) * prev[1]) * (s_new - s_now) / (s_now - prev[0])
        return scaled / k_new

    if log:
        log(f"thrust factor continuation {k0:g} -> 1 (s = 0 -> 1)")
    result, more = _continue(solve_thrust, result.lam0, 0.5, 1e-4, "thrust s", log,
                             predictor=scaling_predictor)
    return result, iterations + more


@dataclasses.dataclass
class HomotopyStep:
    zeta: float
    iterations: int
    lam0: FloatArray


def smoothing_homotopy(problem: NormalisedProblem, lam0: FloatArray, scenario: Scenario, *,
                       zeta_start: float, log: Callable[[str], None] | None = None,
                       ) -> tuple[NewtonResult, list[HomotopyStep]]:
    """Continue a converged solution at zeta_start down to zeta = 0 (eq. 48)."""
    h = scenario.homotopy
    history = [HomotopyStep(zeta_start, 0, lam0.copy())]
    zeta, lam, step = zeta_start, lam0.copy(), h.zeta_step
    prev: tuple[float, FloatArray] | None = None
    while zeta > 0.0:
        step = min(step, zeta)
        target = max(zeta - step, 0.0)
        if target < 0.5 * h.zeta_step_min:
            target = 0.0
        guess = lam.copy()
        if prev is not None:   # secant predictor along the zeta path
            guess = lam + (lam - prev[1]) * (zeta - target) / (prev[0] - zeta)
        rtol = h.rtol(target)
        # Newton at zeta = 0 converges in a few iterations or not at all: fail it cheaply, the homotopy
        # then goes on with smaller zeta steps
        max_iter = 12 if target == 0.0 else 25
        try:
            result = newton_shoot(problem, guess, target, rtol=rtol, max_iter=max_iter)
            if not result.converged and prev is not None:
                result = newton_shoot(problem, lam, target, rtol=rtol, max_iter=max_iter)
        except ShootingFailure:
            result = None
        if result is None or not result.converged:
            step *= 0.5
            if step < h.zeta_step_min:
                raise ShootingFailure(f"smoothing homotopy stalled at zeta = {zeta:.3g}")
            if log:
                log(f"  zeta {zeta:.4g} -> {target:.4g} failed, step -> {step:.3g}")
            continue
        if log:
            log(f"  zeta = {target:.4g}: {result.iterations} Newton iterations, "
                f"|F| = {np.linalg.norm(result.residual):.2e}, m_f = {result.propagation.z_final[6]:.6f}")
        prev = (zeta, lam)
        zeta, lam = target, result.lam0
        history.append(HomotopyStep(zeta, result.iterations, lam.copy()))
        step = min(2.0 * step, h.zeta_step) if result.iterations <= 4 else step
    return result, history


# ---------------------------------------------------------------------------------------------------
# public solver
@dataclasses.dataclass
class Solution:
    """A converged fuel-optimal (bang-off-bang) solution."""

    perturbation: Perturbation
    lam0: FloatArray                #: initial costates (7), normalised units
    z_final: FloatArray             #: state-costate at t_f
    arcs: list[Arc]
    residual: FloatArray            #: shooting function at the solution (normalised)
    final_mass_kg: float
    position_error_km: float
    velocity_error_km_s: float
    newton_iterations: int
    runtime_s: float
    method: str
    homotopy: list[HomotopyStep] = dataclasses.field(default_factory=list)

    @property
    def switch_times(self) -> FloatArray:
        """[TU]"""
        return np.array([a.t_start for a in self.arcs[1:]])

    @property
    def thrust_arcs(self) -> int:
        return sum(1 for a in self.arcs if a.throttle == 1.0)

    @property
    def coast_arcs(self) -> int:
        return sum(1 for a in self.arcs if a.throttle == 0.0)

    def lam0_at(self, zeta: float) -> FloatArray | None:
        """Stored homotopy costates at a given zeta (nominal solution only)."""
        for h in self.homotopy:
            if abs(h.zeta - zeta) < 1e-12:
                return h.lam0
        return None


def _make_solution(scenario: Scenario, perturbation: Perturbation, problem: NormalisedProblem,
                   result: NewtonResult, iterations: int, t_start: float, method: str,
                   homotopy: list[HomotopyStep] | None = None) -> Solution:
    u = scenario.units
    res = result.residual
    return Solution(perturbation, result.lam0.copy(), result.propagation.z_final.copy(),
                    list(result.propagation.arcs), res.copy(),
                    float(result.propagation.z_final[6] * u.mass_kg),
                    float(np.linalg.norm(res[0:3]) * u.length_km),
                    float(np.linalg.norm(res[3:6]) * u.velocity_km_s), iterations,
                    time.perf_counter() - t_start, method, homotopy or [])


def solve_nominal_from_scratch(scenario: Scenario, perturbation: Perturbation | None = None, *,
                               log: Callable[[str], None] | None = None) -> Solution:
    """Energy-optimal start + full smoothing homotopy (no warm start)."""
    t0 = time.perf_counter()
    pert = perturbation if perturbation is not None else Perturbation()
    problem = normalised_problem(scenario, pert)
    h = scenario.homotopy
    start, start_iterations = energy_optimal_start(problem, scenario, log=log)
    result, history = smoothing_homotopy(problem, start.lam0, scenario, zeta_start=h.zeta_start,
                                         log=log)
    iterations = start_iterations + sum(s.iterations for s in history)
    return _make_solution(scenario, pert, problem, result, iterations, t0, "homotopy", history)


def _continue_bang_bang(scenario: Scenario, perturbation: Perturbation, lam0: FloatArray,
                        log: Callable[[str], None] | None) -> tuple[NewtonResult, int]:
    """Eq. (51) continuation in tau directly on the bang-off-bang problem."""
    m = scenario.mpsp
    rtol = scenario.homotopy.final_rtol
    tau, d_tau, lam, total = 0.0, 1.0, lam0.copy(), 0
    result: NewtonResult | None = None
    while tau < 1.0:
        target = min(1.0, tau + d_tau)
        problem = normalised_problem(scenario, perturbation.scaled(target))
        try:
            trial = newton_shoot(problem, lam, 0.0, rtol=rtol, max_iter=15)
        except ShootingFailure:
            trial = None
        if trial is not None:
            total += trial.iterations
        if trial is None or not trial.converged:
            d_tau *= 0.5
            if d_tau < 0.5 * m.delta_tau_min:
                raise ShootingFailure(f"bang-off-bang continuation stalled at tau = {tau:.3g}")
            continue
        if log:
            log(f"  tau = {target:.4g}: {trial.iterations} iterations, {len(trial.propagation.arcs)} arcs")
        tau, lam, result = target, trial.lam0, trial
        d_tau = min(2.0 * d_tau, 1.0)
    assert result is not None
    return result, total


def _continue_smoothed(scenario: Scenario, perturbation: Perturbation, lam0: FloatArray,
                       zeta_c: float, log: Callable[[str], None] | None,
                       ) -> tuple[NewtonResult, int, list[HomotopyStep]]:
    """Eq. (51) continuation at fixed zeta_c > 0 (smooth in tau), then zeta_c -> 0."""
    h = scenario.homotopy
    tau, d_tau, lam, total = 0.0, 0.5, lam0.copy(), 0
    nominal = normalised_problem(scenario, perturbation.scaled(0.0))
    first = newton_shoot(nominal, lam, zeta_c, rtol=h.rtol(zeta_c), max_iter=25)
    if not first.converged:
        raise ShootingFailure(f"nominal smoothed problem at zeta = {zeta_c} did not converge")
    lam, total = first.lam0, first.iterations
    while tau < 1.0:
        target = min(1.0, tau + d_tau)
        problem = normalised_problem(scenario, perturbation.scaled(target))
        try:
            trial = newton_shoot(problem, lam, zeta_c, rtol=h.rtol(zeta_c), max_iter=20)
        except ShootingFailure:
            trial = None
        if trial is not None:
            total += trial.iterations
        if trial is None or not trial.converged:
            d_tau *= 0.5
            if d_tau < 1e-3:
                raise ShootingFailure(f"smoothed continuation stalled at tau = {tau:.3g}")
            continue
        if log:
            log(f"  zeta = {zeta_c:g}, tau = {target:.4g}: {trial.iterations} iterations")
        tau, lam = target, trial.lam0
        d_tau = min(2.0 * d_tau, 1.0)
    problem = normalised_problem(scenario, perturbation)
    result, history = smoothing_homotopy(problem, lam, scenario, zeta_start=zeta_c, log=log)
    return result, total + sum(s.iterations for s in history), history


def solve_fuel_optimal(scenario: Scenario, perturbation: Perturbation | None = None,
                       warm_start: Solution | None = None, *,
                       log: Callable[[str], None] | None = None) -> Solution:
    """Fuel-optimal bang-off-bang solution of the nominal or a perturbed problem.

    Without warm_start: energy-optimal random start and the full smoothing homotopy. With a warm start
    (normally the nominal Solution): continuation of eq. (51) from it, trying in order
      1. Newton on the bang-off-bang problem with tau-continuation (fast; keeps the switching structure
         or changes it smoothly),
      2. continuation at zeta_c = 0.1 then 0.5, 1 (smoothed problems, from the warm start's stored
         homotopy costates where available), followed by zeta_c -> 0.
    """
    pert = perturbation if perturbation is not None else Perturbation()
    if warm_start is None:
        return solve_nominal_from_scratch(scenario, pert, log=log)
    if not warm_start.perturbation.is_nominal:
        raise ValueError("warm_start must be a nominal solution (continuation starts at tau = 0)")
    t0 = time.perf_counter()
    problem = normalised_problem(scenario, pert)
    try:
        result, iterations = _continue_bang_bang(scenario, pert, warm_start.lam0, log)
        return _make_solution(scenario, pert, problem, result, iterations, t0, "bang-bang continuation")
    except ShootingFailure as err:
        if log:
            log(f"  direct bang-off-bang continuation failed ({err}); smoothed continuation")
    for zeta_c in (0.1, 0.5, 1.0):
        stored = warm_start.lam0_at(zeta_c)
        lam_start = stored if stored is not None else warm_start.lam0
        try:
            result, iterations, history = _continue_smoothed(scenario, pert, lam_start, zeta_c, log)
        except ShootingFailure as err:
            if log:
                log(f"  smoothed continuation at zeta = {zeta_c} failed ({err})")
            continue
        return _make_solution(scenario, pert, problem, result, iterations, t0,
                              f"smoothed continuation (zeta_c = {zeta_c:g})", history)
    raise ShootingFailure(f"no fuel-optimal solution found for {pert.label}")


# ---------------------------------------------------------------------------------------------------
# storage of the nominal solution
def solution_record(solution: Solution, scenario: Scenario) -> dict[str, object]:
    """JSON-ready record of a solution (lambda_0 is what the tests re-integrate; the rest is for
    people and for the fuel-increase comparison)."""
    u = scenario.units
    pert = solution.perturbation
    return {
        "perturbation": pert.label,
        "delta_r0_LU": [float(x) for x in pert.delta_r0],
        "delta_v0_LU_TU": [float(x) for x in pert.delta_v0],
        "delta_rf_LU": [float(x) for x in pert.delta_rf],
        "thrust_fraction": pert.thrust_fraction,
        "lambda0": [float(x) for x in solution.lam0],
        "final_mass_kg": solution.final_mass_kg,
        "propellant_kg": scenario.spacecraft.initial_mass_kg - solution.final_mass_kg,
        "thrust_arcs": solution.thrust_arcs,
        "coast_arcs": solution.coast_arcs,
        "arcs": [{"t_start_TU": a.t_start, "t_end_TU": a.t_end, "throttle": a.throttle,
                  "t_start_days": a.t_start * u.time_s / 86400.0,
                  "t_end_days": a.t_end * u.time_s / 86400.0} for a in solution.arcs],
        "residual": [float(x) for x in solution.residual],
        "position_error_km": solution.position_error_km,
        "velocity_error_km_s": solution.velocity_error_km_s,
        "newton_iterations": solution.newton_iterations,
        "runtime_s": solution.runtime_s,
        "method": solution.method,
        "homotopy": [{"zeta": s.zeta, "iterations": s.iterations,
                      "lambda0": [float(x) for x in s.lam0]} for s in solution.homotopy],
    }


def _header(scenario: Scenario, command: str) -> dict[str, object]:
    return {
        "generator": f"python -m ogk_host.low_thrust_transfer {command}",
        "scenario": str(scenario.path.relative_to(scenario.path.parents[1])),
        "units": "normalised: LU, TU, MU, velocity LU/TU (Table 1)",
    }


def save_solution(solution: Solution, scenario: Scenario, path: Path) -> None:
    """Write the nominal solution as JSON to `path` (the ground product is written by
    products.write_nominal with its manifest; nothing writes into data/, a cache)."""
    path.parent.mkdir(parents=True, exist_ok=True)
    doc = {**_header(scenario, "regenerate"), **solution_record(solution, scenario)}
    path.write_text(json.dumps(doc, indent=1) + "\n")


def save_references(solutions: list[Solution], scenario: Scenario, path: Path) -> None:
    """Write the fuel-optimal solutions of perturbed problems (the FI references) as JSON."""
    path.parent.mkdir(parents=True, exist_ok=True)
    doc = {**_header(scenario, "references"),
           "cases": [solution_record(s, scenario) for s in solutions]}
    path.write_text(json.dumps(doc, indent=1) + "\n")


def load_references(path: Path = REFERENCES_PATH) -> dict[str, dict]:
    """Stored perturbed optima by label ("kappa=-2.5", "cube vertex 8", "eta=-10%")."""
    doc = json.loads(path.read_text())
    return {case["perturbation"]: case for case in doc["cases"]}


def load_solution(scenario: Scenario, path: Path = NOMINAL_PATH) -> Solution:
    """Read a stored nominal solution and re-propagate it (arcs, z_final and residual recomputed)."""
    doc = json.loads(path.read_text())
    lam0 = np.array(doc["lambda0"], dtype=np.float64)
    problem = normalised_problem(scenario)
    prop = propagate(problem, lam0, 0.0, rtol=scenario.homotopy.final_rtol)
    res = shooting_residual(problem, prop.z_final)
    result = NewtonResult(lam0, res, 0, True, prop)
    history = [HomotopyStep(h["zeta"], h["iterations"], np.array(h["lambda0"]))
               for h in doc["homotopy"]]
    sol = _make_solution(scenario, Perturbation(), problem, result, int(doc["newton_iterations"]),
                         time.perf_counter(), str(doc["method"]), history)
    sol.runtime_s = float(doc["runtime_s"])
    return sol
