"""Minimum-time nominal of the LEO-to-GEO injection burn by an indirect method (sec. 3, eqs. 19-28).

Problem (canonical units, units.py; normalised time tau = t / t_f, eq. 21):
  minimise t_f subject to x' = t_f f~(x, u) with x = [r, xi, phi, v_r, v_t, v_n, t] (t' = t_f),
  x(0) on the pre-ignition ellipse at a free true anomaly f0 (eq. 19 case B, xi = phi = v_n = t = 0),
  x(1) on the target circular orbit (eq. 20; xi(1), t(1) free).
Necessary conditions used (eqs. 24-28 with real time as a state):
  u = argmin H: thrust along -lambda_v (eq. 27); lambda' = -t_f h_x (eq. 25);
  lambda_xi(1) = 0 and lambda_t(1) = 0 (free final right ascension and time; lambda_xi' = 0 gives
  lambda_xi = 0 everywhere);
  initial transversality for the free f0: lambda(0)^T dx0/df0 = 0;
  parameter condition (eq. 28): mu' = -H_a = -h, mu(0) = 0, mu(1) = dPhi/dt_f = 1; the system is
  autonomous in tau (time is a state), so h = lambda^T f~ is constant and the condition is h = -1.
The planar symmetric solution phi = v_n = lambda_phi = lambda_vn = 0 (beta = 0) is sought (sec. 3.2).

Solution method: the costates are homogeneous except for h = -1, so the shooting unknowns are
q = [f0, alpha0, kappa, t_f] with lambda_v(0) = -[sin alpha0, cos alpha0] (unit norm, alpha0 = initial
thrust angle) and lambda_r(0) = kappa / t_f (kappa ~ total turn of lambda_v).

- "continuation" (default for a transfer ellipse whose apogee is the target radius, the documented
  envelope of docs/design/vtd-nog.md sec. 2): natural-parameter continuation in the canonical
  (p, e, n0, c) from the paper's problem (PAPER_PARAMETERS) and its solution (PAPER_SOLUTION), full
  Newton correctors with the exact variational Jacobian, step doubled/halved; deterministic. Over
  the envelope (R_f / r_p 1.5..8, n0 0.5..1.5 g0, c 2.5..4.5 km/s) it takes 1-2 steps.
- "scan" (fallback, and the default for an ellipse that crosses the target orbit): a vectorised
  fixed-step RK4 scan over a coarse 4-D grid (f0 90..270 deg plus anomalies around the crossings,
  alpha0 -75..75 deg, kappa -3..3, t_f 0.6..3 times the rocket-equation estimate at apoapsis)
  ranks candidates by their scaled residuals; the best few are refined by Levenberg-Marquardt
  (DOP853 at rtol 1e-9) and damped Newton (rtol 1e-12); the minimum-t_f converged extremal is kept.

The costates are then rescaled to h = -1 and lambda_t(0) is fixed so that lambda_t(1) = 0
(lambda_t does not feed back into the other equations). No solution: NominalError (one line, with
the transfer-ellipse keys to set).
"""
from __future__ import annotations

import dataclasses
import math
from typing import Callable

import numpy as np
from numpy.typing import NDArray
from scipy.optimize import least_squares

from ogk_bindings.errors import OgkInputError
from . import dynamics as dyn
from .propagation import N_Z, integrate_extremal, rk4_extremal_batch
from .scenario import OrbitInjectionScenario, load_scenario
from .units import CanonicalUnits

FloatArray = NDArray[np.float64]

#: Names of the 6 residuals of the full necessary conditions, in `Nominal.residuals` order.
RESIDUAL_NAMES = ("r(1) - R_f", "v_r(1)", "v_t(1) - v_c", "lambda_t(1)",
                  "lambda(0)^T dx0/df0", "h + 1")


@dataclasses.dataclass(frozen=True)
class MinTimeProblem:
    """Canonical-unit data of the minimum-time problem."""

    scenario: OrbitInjectionScenario
    units: CanonicalUnits
    model: dyn.Model
    semilatus_rectum: float       #: p of the pre-ignition ellipse [DU] (case B; NaN for case A)
    eccentricity: float
    target_radius: float          #: R_f [DU] (1 by construction)
    #: eq. (19) case A: the specified ignition state (7 canonical components); None for case B
    fixed_state: tuple[float, ...] | None = None

    @classmethod
    def from_scenario(cls, scn: OrbitInjectionScenario) -> "MinTimeProblem":
        units = CanonicalUnits.for_scenario(scn)
        model = dyn.Model.for_scenario(scn, units)
        if getattr(scn, "pre_ignition", None) is None:
            x0 = units.state_from_si(scn.initial_state.state_si())
            return cls(scenario=scn, units=units, model=model, semilatus_rectum=math.nan,
                       eccentricity=math.nan, target_radius=scn.target_radius_m / units.length_m,
                       fixed_state=tuple(float(v) for v in x0))
        return cls(scenario=scn, units=units, model=model,
                   semilatus_rectum=scn.pre_ignition.semilatus_rectum_m / units.length_m,
                   eccentricity=scn.pre_ignition.eccentricity,
                   target_radius=scn.target_radius_m / units.length_m)

    @property
    def free_ignition(self) -> bool:
        """Eq. (19) case B (ignition anomaly free); False: case A (specified state)."""
        return self.fixed_state is None

    @property
    def circular_speed(self) -> float:
        """sqrt(mu / R_f) [VU]."""
        return math.sqrt(self.model.mu / self.target_radius)

    def ignition_state(self, f0: FloatArray | float) -> tuple[FloatArray, FloatArray, FloatArray]:
        """x0(f0) from eq. (19) case B, and its first and second derivatives in f0 (each (..., 7)).
        Case A: the specified state whatever f0, derivatives zero."""
        f0 = np.asarray(f0, dtype=np.float64)
        if self.fixed_state is not None:
            x0 = np.broadcast_to(np.array(self.fixed_state), f0.shape + (dyn.N_X,)).copy()
            return x0, np.zeros_like(x0), np.zeros_like(x0)
        p, e = self.semilatus_rectum, self.eccentricity
        vp = math.sqrt(self.model.mu / p)
        w = 1.0 + e * np.cos(f0)
        sf, cf = np.sin(f0), np.cos(f0)
        zeros = np.zeros_like(f0)
        x0 = np.stack([p / w, zeros, zeros, vp * e * sf, vp * w, zeros, zeros], axis=-1)
        dx0 = np.stack([p * e * sf / w**2, zeros, zeros, vp * e * cf, -vp * e * sf, zeros, zeros],
                       axis=-1)
        ddx0 = np.stack([p * e * cf / w**2 + 2.0 * p * e**2 * sf**2 / w**3, zeros, zeros,
                         -vp * e * sf, -vp * e * cf, zeros, zeros], axis=-1)
        return x0, dx0, ddx0

    def ignition_anomaly(self, f0: float) -> float:
        """The ignition true anomaly reported for a solution: f0 (case B), or the true anomaly of
        the specified state on its osculating orbit (case A)."""
        if self.fixed_state is None:
            return f0
        return self.scenario.initial_state.true_anomaly_rad(self.scenario.mu_m3_s2)

    def velocity_gain_time(self) -> float:
        """Case A: the time [TU] at which the integral of a(t) equals the speed difference
        |v_target - v0| (a crude impulsive estimate of t_f, for the scan range)."""
        x0 = self.fixed_state
        dv = math.hypot(x0[dyn.VR], self.circular_speed - x0[dyn.VT])
        t = np.linspace(0.0, self.model.max_time, 2001)
        a = self.model.accel(t)[0]
        gained = np.concatenate([[0.0], np.cumsum(0.5 * (a[1:] + a[:-1]) * np.diff(t))])
        if gained[-1] <= dv:
            return float(t[-1])
        return float(np.interp(dv, gained, t))

    def rocket_equation_time(self) -> float:
        """t_f of an impulsive-equivalent burn at apoapsis: the Delta v to circularise [TU]."""
        p, e = self.semilatus_rectum, self.eccentricity
        v_apo = math.sqrt(self.model.mu / p) * (1.0 - e)
        delta_v = self.circular_speed - v_apo
        c, n0 = self.model.exhaust_velocity, self.model.initial_accel
        return c / n0 * (1.0 - math.exp(-delta_v / c))


@dataclasses.dataclass(frozen=True)
class Nominal:
    """The minimum-time nominal (canonical units unless a name says otherwise)."""

    problem: MinTimeProblem
    t_f: float                    #: minimum time [TU]
    f0: float                     #: ignition true anomaly [rad]
    z0: FloatArray                #: [x(0); lambda(0)] (14,), costates scaled to h = -1
    residuals: FloatArray         #: the 6 necessary-condition residuals (RESIDUAL_NAMES)
    scan_candidates: int          #: grid points of the coarse scan (0: found by continuation)
    refined_starts: int           #: LM refinements run (continuation: accepted steps)
    method: str = "scan"          #: "continuation" or "scan"

    @property
    def t_f_s(self) -> float:
        """t_f* [s]."""
        return self.t_f * self.problem.units.time_s

    @property
    def model(self) -> dyn.Model:
        return self.problem.model

    def states(self, tau: FloatArray) -> FloatArray:
        """[x; lambda] at each tau (N, 14), integrated from tau = 0 at rtol 1e-12."""
        return integrate_extremal(self.model, self.z0, self.t_f, 0.0, tau).z


def _costate_from_q(alpha0: FloatArray, kappa: FloatArray, t_f: FloatArray) -> FloatArray:
    """Homogeneous initial costate (lambda_t = 0 placeholder), (..., 7)."""
    alpha0 = np.asarray(alpha0, dtype=np.float64)
    lam = np.zeros(alpha0.shape + (dyn.N_X,))
    lam[..., dyn.R] = kappa / t_f
    lam[..., dyn.VR] = -np.sin(alpha0)
    lam[..., dyn.VT] = -np.cos(alpha0)
    return lam


def _reduced_residual(problem: MinTimeProblem, q: FloatArray, free_f0: bool = True,
                      f0_fixed: float = 0.0, rtol: float = 1e-12,
                      with_jac: bool = True) -> tuple[FloatArray, FloatArray]:
    """Residual and Jacobian of the scaled shooting problem.

    q = [f0, alpha0, kappa, t_f] (free_f0) or [alpha0, kappa, t_f] (f0 = f0_fixed). Residual:
    [r(1) - R_f, v_r(1), v_t(1) - v_c] and, if free_f0, lambda(0)^T dx0/df0.
    """
    if free_f0:
        f0, alpha0, kappa, t_f = q
    else:
        f0 = f0_fixed
        alpha0, kappa, t_f = q
    x0, dx0, ddx0 = problem.ignition_state(f0)
    lam0 = _costate_from_q(alpha0, kappa, t_f)
    z0 = np.concatenate([x0, lam0])
    arc = integrate_extremal(problem.model, z0, t_f, 0.0, np.array([1.0]), sensitivity=with_jac,
                             rtol=rtol)
    z1 = arc.z[0]
    rows = [dyn.R, dyn.VR, dyn.VT]
    res = np.array([z1[dyn.R] - problem.target_radius, z1[dyn.VR], z1[dyn.VT] - problem.circular_speed])
    if free_f0:
        res = np.append(res, float(lam0 @ dx0))
    if not with_jac:
        return res, np.empty((0, 0))
    sens = arc.sensitivity[0]
    # dz0/dq columns
    dz0 = np.zeros((N_Z, 4))
    dz0[:dyn.N_X, 0] = dx0
    dz0[dyn.N_X + dyn.VR, 1] = -math.cos(alpha0)
    dz0[dyn.N_X + dyn.VT, 1] = math.sin(alpha0)
    dz0[dyn.N_X + dyn.R, 2] = 1.0 / t_f
    dz0[dyn.N_X + dyn.R, 3] = -kappa / t_f**2
    dz1 = sens[:, :N_Z] @ dz0
    dz1[:, 3] += sens[:, N_Z]
    jac = dz1[rows, :]
    if free_f0:
        dtrans = np.array([lam0 @ ddx0, dz0[dyn.N_X:, 1] @ dx0, dz0[dyn.N_X:, 2] @ dx0,
                           dz0[dyn.N_X:, 3] @ dx0])
        return res, np.vstack([jac, dtrans])
    return res, jac[:, 1:]


def newton(fun: Callable[[FloatArray], tuple[FloatArray, FloatArray]], q: FloatArray,
           max_iter: int = 12, tol: float = 1e-13,
           max_halvings: int = 8) -> tuple[FloatArray, FloatArray]:
    """Damped Newton iteration on fun(q) -> (residual, Jacobian).

    Each full step is halved until the residual 2-norm decreases; the iteration stops when the max
    residual falls below tol, when no damped step decreases it (the noise floor), or after max_iter
    steps. Returns (q, residual).
    """
    q = np.array(q, dtype=np.float64)
    res, jac = fun(q)
    for _ in range(max_iter):
        if np.max(np.abs(res)) < tol:
            break
        step = np.linalg.solve(jac, -res)
        for _ in range(max_halvings + 1):
            try:
                res_new, jac_new = fun(q + step)
            except RuntimeError:
                res_new = np.full_like(res, np.inf)
            if np.linalg.norm(res_new) < np.linalg.norm(res):
                break
            step = 0.5 * step
        else:
            break
        q, res, jac = q + step, res_new, jac_new
    return q, res


def crossing_anomalies(problem: MinTimeProblem) -> tuple[float, ...]:
    """True anomalies [rad] where the pre-ignition ellipse crosses the target radius (none when the
    target is outside (perigee, apogee))."""
    cos_f = (problem.semilatus_rectum / problem.target_radius - 1.0) / problem.eccentricity \
        if problem.eccentricity > 0.0 else math.inf
    if not -1.0 < cos_f < 1.0:
        return ()
    f_c = math.acos(cos_f)
    return (f_c, 2.0 * math.pi - f_c)


def apogee_excess(problem: MinTimeProblem) -> float:
    """apogee / R_f - 1 of the pre-ignition ellipse: ~0 for a transfer ellipse ending at R_f (the
    documented envelope), > 0 when the ellipse crosses the target orbit."""
    apogee = problem.semilatus_rectum / (1.0 - problem.eccentricity)
    return apogee / problem.target_radius - 1.0


def _scan(problem: MinTimeProblem, n_keep: int) -> tuple[FloatArray, int]:
    """Coarse vectorised RK4 scan; returns the n_keep best q (by scaled residual) and the grid size.

    f0: 90..270 deg every 7.5 deg plus, when the ellipse crosses the target orbit, anomalies
    -12..+3 deg around each crossing (mirrored for the descending one); t_f: 0.6..3 times the
    rocket-equation time of an apoapsis burn, below 0.9 of the burnout time."""
    t_ref = problem.rocket_equation_time()
    f0_deg = list(np.arange(90.0, 270.1, 7.5))
    for f_c in crossing_anomalies(problem)[:1]:
        for off in (-12.0, -8.0, -5.0, -3.0, -1.5, 0.0, 1.5, 3.0):
            f0_deg += [math.degrees(f_c) + off, 360.0 - math.degrees(f_c) - off]
    f0_grid = np.radians(np.unique(np.round(f0_deg, 9)))
    alpha_grid = np.radians(np.arange(-75.0, 75.1, 15.0))
    kappa_grid = np.arange(-3.0, 3.01, 0.5)
    tf_grid = t_ref * np.geomspace(0.6, 3.0, 16)
    tf_grid = tf_grid[tf_grid < 0.9 * problem.model.exhaust_velocity / problem.model.initial_accel]
    grid = np.stack(np.meshgrid(f0_grid, alpha_grid, kappa_grid, tf_grid, indexing="ij"),
                    axis=-1).reshape(-1, 4)
    x0, dx0, _ = problem.ignition_state(grid[:, 0])
    lam0 = _costate_from_q(grid[:, 1], grid[:, 2], grid[:, 3])
    with np.errstate(all="ignore"):
        z1 = rk4_extremal_batch(problem.model, np.concatenate([x0, lam0], axis=1), grid[:, 3], 40)
    # transversality as a cosine between lambda(0) and the tangent of the ignition manifold
    cos_trans = np.sum(lam0 * dx0, axis=1) / (np.linalg.norm(lam0, axis=1)
                                              * np.linalg.norm(dx0, axis=1))
    merit = np.sqrt((z1[:, dyn.R] - problem.target_radius)**2 + z1[:, dyn.VR]**2
                    + (z1[:, dyn.VT] - problem.circular_speed)**2 + 0.01 * cos_trans**2)
    merit[~np.isfinite(merit)] = np.inf
    best = np.argsort(merit)[:n_keep]
    return grid[best], grid.shape[0]


def _finish(problem: MinTimeProblem, q: FloatArray, scan_size: int, n_starts: int,
            method: str = "scan") -> Nominal:
    """Rescales the converged homogeneous costates to h = -1 and fixes lambda_t(0)."""
    f0, alpha0, kappa, t_f = (float(v) for v in q)
    x0, dx0, _ = problem.ignition_state(f0)
    lam0 = _costate_from_q(alpha0, kappa, t_f)
    z1 = integrate_extremal(problem.model, np.concatenate([x0, lam0]), t_f, 0.0, np.array([1.0])).z[0]
    lam0[dyn.TIME] = -z1[dyn.N_X + dyn.TIME]          # lambda_t(tau) = lambda_t(0) + g(tau)
    z1[dyn.N_X + dyn.TIME] = 0.0
    u1 = dyn.optimal_control(z1[dyn.N_X:])
    h1 = float(z1[dyn.N_X:] @ dyn.state_rate(problem.model, z1[:dyn.N_X], u1))
    if not h1 < 0.0:
        raise RuntimeError(f"extremal with h = {h1} >= 0 cannot be normalised to h = -1")
    z0 = np.concatenate([x0, lam0 * (-1.0 / h1)])
    residuals = necessary_condition_residuals(problem, z0, t_f, f0)
    return Nominal(problem=problem, t_f=t_f, f0=problem.ignition_anomaly(f0), z0=z0,
                   residuals=residuals,
                   scan_candidates=scan_size, refined_starts=n_starts, method=method)


def necessary_condition_residuals(problem: MinTimeProblem, z0: FloatArray, t_f: float,
                                  f0: float) -> FloatArray:
    """The 6 residuals of RESIDUAL_NAMES, re-integrated from z0 (canonical units)."""
    z1 = integrate_extremal(problem.model, z0, t_f, 0.0, np.array([1.0])).z[0]
    _, dx0, _ = problem.ignition_state(f0)
    lam1 = z1[dyn.N_X:]
    h1 = float(lam1 @ dyn.state_rate(problem.model, z1[:dyn.N_X], dyn.optimal_control(lam1)))
    return np.array([z1[dyn.R] - problem.target_radius, z1[dyn.VR],
                     z1[dyn.VT] - problem.circular_speed, lam1[dyn.TIME],
                     float(z0[dyn.N_X:] @ dx0), h1 + 1.0])


#: The paper's problem (scenarios/leo_geo.toml, erratum applied) in canonical units,
#: (p, e, n0, c) [DU, -, DU/TU^2, VU], and its minimum-time solution q = [f0, alpha0, kappa, t_f]
#: (found by the coarse scan, polished to 1e-13): the start of every continuation.
PAPER_PARAMETERS = (0.276996932003605, 0.723, 48.63751099172241, 0.9757156972733132)
PAPER_SOLUTION = (3.1393985144536964, 0.0175294883993016, -0.03650272123394877,
                  0.007715745002506479)


#: |apogee / R_f - 1| up to which "auto" continues from the paper (transfer ellipse ending at R_f;
#: the paper's ellipse has -1.2e-5). Beyond it the ellipse crosses (or misses) the target orbit, the
#: paper's solution sits at a bifurcation of that family (two crossings merge at apogee) and the
#: continuation was measured to follow a wrong branch (42 000 km: 193 s instead of 106.8 s), so
#: "auto" uses the scan.
APOGEE_TOLERANCE = 1e-3


class ContinuationError(RuntimeError):
    """The continuation from the paper's solution did not reach the scenario's parameters."""


class NominalError(OgkInputError):
    """No minimum-time nominal for this scenario (one line: which keys to change)."""


def problem_parameters(problem: MinTimeProblem) -> FloatArray:
    """(p, e, n0, c) of the problem in canonical units."""
    return np.array([problem.semilatus_rectum, problem.eccentricity, problem.model.initial_accel,
                     problem.model.exhaust_velocity])


def with_parameters(problem: MinTimeProblem, params: FloatArray) -> MinTimeProblem:
    """The same problem (units, target) with other canonical (p, e, n0, c)."""
    p, e, n0, c = (float(v) for v in params)
    return dataclasses.replace(problem, semilatus_rectum=p, eccentricity=e,
                               model=dyn.Model(mu=problem.model.mu, initial_accel=n0,
                                               exhaust_velocity=c))


def _homotopy(start: FloatArray, end: FloatArray, s: float) -> FloatArray:
    """Parameters at s in [0, 1]: p and e linear, n0 and c geometric (they stay positive)."""
    out = start + s * (end - start)
    out[2:] = start[2:] * (end[2:] / start[2:]) ** s
    return out


def _corrector(problem: MinTimeProblem, q: FloatArray, rtol: float, max_iter: int = 8,
               tol: float = 1e-10) -> tuple[FloatArray, bool]:
    """Full (undamped) Newton steps from q; (q, converged). Undamped on purpose: near the paper's
    solution the branch turns fast in (alpha0, kappa) and a monotone-residual damping stalls where
    the full steps converge quadratically. Divergence (residual growth by 1e6, a non-finite value,
    t_f <= 0 or burnout) ends it as not converged."""
    q = np.array(q, dtype=np.float64)
    first = None
    for _ in range(max_iter + 1):
        if not (np.all(np.isfinite(q)) and q[3] > 0.0):
            return q, False
        try:
            res, jac = _reduced_residual(problem, q, rtol=rtol)
        except (RuntimeError, ValueError):
            return q, False
        norm = float(np.max(np.abs(res)))
        if not np.isfinite(norm):
            return q, False
        if norm < tol:
            return q, True
        first = norm if first is None else first
        if norm > 1e6 * first:
            return q, False
        try:
            q = q + np.linalg.solve(jac, -res)
        except np.linalg.LinAlgError:
            return q, False
    return q, False


def continue_from_paper(problem: MinTimeProblem, min_step: float = 1.0 / 64.0,
                        rtol: float = 1e-10, max_solves: int = 24) -> tuple[FloatArray, int]:
    """Natural-parameter continuation of the extremal from PAPER_PARAMETERS to the problem's.

    Steps in s (homotopy parameter, 0 = paper, 1 = problem) start at 1 (a direct Newton solve),
    halve on failure and double on success; the predictor is the secant through the last two
    solutions. Each corrector is damped Newton with the exact variational Jacobian at `rtol`,
    accepted at residual < 1e-9. Deterministic; returns (q, accepted steps) or raises
    ContinuationError when the step falls below `min_step` or after `max_solves` corrector runs.
    """
    start, end = np.array(PAPER_PARAMETERS), problem_parameters(problem)
    q, s = np.array(PAPER_SOLUTION), 0.0
    q_prev: FloatArray | None = None
    s_prev = 0.0
    step, accepted, solves = 1.0, 0, 0
    while s < 1.0:
        if solves >= max_solves:
            raise ContinuationError(f"continuation from the paper's solution used {solves} "
                                    f"corrector runs and reached s = {s:.4f} only")
        solves += 1
        s_new = min(1.0, s + step)
        sub = with_parameters(problem, _homotopy(start, end, s_new))
        guess = q if q_prev is None else q + (q - q_prev) * (s_new - s) / (s - s_prev)
        q_new, ok = _corrector(sub, guess, rtol)
        if ok:
            q_prev, s_prev, q, s = q, s, q_new, s_new
            accepted += 1
            step = min(2.0 * step, 1.0)
        else:
            step *= 0.5
            if step < min_step:
                raise ContinuationError(f"continuation from the paper's solution stalled at "
                                        f"s = {s:.4f} (step < {min_step})")
    return q, accepted


def solve_nominal(scn: OrbitInjectionScenario | None = None, n_starts: int = 8,
                  method: str = "auto") -> Nominal:
    """Minimum-t_f extremal: continuation from the paper's solution ("continuation"), the coarse
    scan + Levenberg-Marquardt + damped Newton ("scan"), or the first, falling back on the
    second ("auto")."""
    problem = MinTimeProblem.from_scenario(scn if scn is not None else load_scenario())
    if not problem.free_ignition:
        if method not in ("auto", "scan"):
            raise ValueError(f"method {method!r}: a specified ignition state (eq. 19 case A) is "
                             f"solved by the scan only")
        return _solve_specified_state(problem, min(n_starts, SPECIFIED_STATE_STARTS))
    if method == "auto" and abs(apogee_excess(problem)) > APOGEE_TOLERANCE:
        method = "scan"        # an ellipse crossing the target: the paper's point is a bifurcation
    if method in ("auto", "continuation"):
        try:
            q, steps = continue_from_paper(problem)
            q, res = newton(lambda v: _reduced_residual(problem, v), q)
            if np.max(np.abs(res)) < 1e-12:
                q[0] = math.remainder(q[0], 2.0 * math.pi) % (2.0 * math.pi)
                return _finish(problem, q, 0, steps, method="continuation")
            if method == "continuation":
                raise ContinuationError(f"final Newton polish left residual {res}")
        except ContinuationError:
            if method == "continuation":
                raise
    elif method != "scan":
        raise ValueError(f"unknown method {method!r}")
    starts, scan_size = _scan(problem, n_starts)
    solutions: list[FloatArray] = []
    for q_start in starts:
        try:   # coarse-to-fine: LM at rtol 1e-9, then damped Newton at rtol 1e-12
            fit = least_squares(
                lambda q: _reduced_residual(problem, q, rtol=1e-9, with_jac=False)[0], q_start,
                jac=lambda q: _reduced_residual(problem, q, rtol=1e-9)[1], method="lm",
                xtol=1e-12, ftol=1e-12, gtol=1e-12, max_nfev=100)
        except (RuntimeError, ValueError):
            continue
        if not np.all(np.isfinite(fit.x)) or fit.x[3] <= 0.0 or np.max(np.abs(fit.fun)) > 1e-7:
            continue
        q, res = newton(lambda q: _reduced_residual(problem, q), fit.x)
        if not np.max(np.abs(res)) < 1e-12:
            continue
        q[0] = math.remainder(q[0], 2.0 * math.pi) % (2.0 * math.pi)
        solutions.append(q)
    if not solutions:
        key, reason = _outside_envelope_reason(problem)
        raise NominalError(reason, path=getattr(problem.scenario, "path", None), key=key)
    best = min(solutions, key=lambda q: q[3])
    return _finish(problem, best, scan_size, len(starts))


#: Refinements of the case-A scan (each LM + Newton costs ~10-30 s with a tabulated thrust; on
#: the sec. 7 data the best-ranked start already converges to the minimum).
SPECIFIED_STATE_STARTS = 3


def _solve_specified_state(problem: MinTimeProblem, n_starts: int) -> Nominal:
    """Eq. (19) case A (sec. 7, eq. 56): x(0) specified, unknowns q = [alpha0, kappa, t_f] and the
    three in-plane injection residuals. A vectorised RK4 scan (alpha0 -80..80 deg every 5 deg,
    kappa -2..2 every 0.1, t_f 0.8..1.6 times `velocity_gain_time`, inside the thrust table) ranks
    the candidates; the best n_starts are refined by Levenberg-Marquardt (rtol 1e-9) and damped
    Newton (rtol 1e-12); the minimum-t_f converged extremal is kept."""
    t_ref = problem.velocity_gain_time()
    alpha_grid = np.radians(np.arange(-80.0, 80.1, 5.0))
    kappa_grid = np.arange(-2.0, 2.001, 0.1)
    tf_grid = t_ref * np.geomspace(0.8, 1.6, 17)
    tf_grid = tf_grid[tf_grid < 0.999 * problem.model.max_time]
    grid = np.stack(np.meshgrid(alpha_grid, kappa_grid, tf_grid, indexing="ij"),
                    axis=-1).reshape(-1, 3)
    x0, _, _ = problem.ignition_state(np.zeros(grid.shape[0]))
    lam0 = _costate_from_q(grid[:, 0], grid[:, 1], grid[:, 2])
    with np.errstate(all="ignore"):
        z1 = rk4_extremal_batch(problem.model, np.concatenate([x0, lam0], axis=1), grid[:, 2], 40)
    merit = np.sqrt((z1[:, dyn.R] - problem.target_radius)**2 + z1[:, dyn.VR]**2
                    + (z1[:, dyn.VT] - problem.circular_speed)**2)
    merit[~np.isfinite(merit)] = np.inf
    starts = grid[np.argsort(merit)[:n_starts]]

    def fun(q: FloatArray, rtol: float = 1e-12, with_jac: bool = True) -> tuple[FloatArray, FloatArray]:
        return _reduced_residual(problem, q, free_f0=False, rtol=rtol, with_jac=with_jac)

    solutions: list[FloatArray] = []
    for q_start in starts:
        try:
            fit = least_squares(lambda q: fun(q, 1e-9, False)[0], q_start,
                                jac=lambda q: fun(q, 1e-9)[1], method="lm",
                                xtol=1e-12, ftol=1e-12, gtol=1e-12, max_nfev=100)
        except (RuntimeError, ValueError):
            continue
        if not np.all(np.isfinite(fit.x)) or fit.x[2] <= 0.0 or np.max(np.abs(fit.fun)) > 1e-7:
            continue
        try:
            q, res = newton(fun, fit.x)
        except (RuntimeError, ValueError):
            continue
        if np.max(np.abs(res)) < 1e-12:
            solutions.append(q)
    if not solutions:
        raise NominalError(f"no minimum-time burn found from the specified ignition state "
                           f"(eq. 19 case A) within the thrust table ({problem.model.max_time * problem.units.time_s:.4g} s): "
                           f"check [initial_state], [target_orbit] and [thrust]",
                           path=getattr(problem.scenario, "path", None), key="initial_state")
    best = min(solutions, key=lambda q: q[2])
    return _finish(problem, np.concatenate([[0.0], best]), grid.shape[0], len(starts))


def _outside_envelope_reason(problem: MinTimeProblem) -> tuple[str, str]:
    """(key, one line) for a nominal that neither the continuation nor the scan found; the key is
    the first scenario table outside the envelope (thrust, target_orbit, pre_ignition_orbit)."""
    scn = problem.scenario
    a_m, e = scn.pre_ignition.semi_major_axis_m, scn.pre_ignition.eccentricity
    perigee, apogee, r_f = a_m * (1.0 - e), a_m * (1.0 + e), scn.target_radius_m
    a_h, e_h = 0.5 * (perigee + r_f), (r_f - perigee) / (r_f + perigee)
    n0_g0, c_km_s = scn.thrust.initial_accel_g0, scn.thrust.exhaust_velocity_m_s / 1e3
    if not (0.5 <= n0_g0 <= 1.5 and 2.5 <= c_km_s <= 4.5):
        key = "thrust"
    elif not 1.5 <= r_f / perigee <= 8.0:
        key = "target_orbit.radius_m"
    else:
        key = "pre_ignition_orbit"
    return key, (f"no minimum-time burn found: the documented envelope (docs/design/vtd-nog.md, sec. 2) is a "
            f"pre-ignition transfer ellipse with apogee = target radius, R_f / perigee 1.5..8, "
            f"n0 0.5..1.5 g0, c 2.5..4.5 km/s; this one has apogee {apogee / 1e3:.1f} km, target "
            f"{r_f / 1e3:.1f} km, R_f / perigee {r_f / perigee:.3g}, n0 "
            f"{scn.thrust.initial_accel_g0:.3g} g0, c {scn.thrust.exhaust_velocity_m_s / 1e3:.3g} "
            f"km/s (for this perigee and target set semi_major_axis_m = {a_h:.6g}, "
            f"eccentricity = {e_h:.6g})")


def solve_fixed_ignition(nominal: Nominal, f0: float,
                         max_step_rad: float = math.radians(0.25)) -> float:
    """Minimum time [TU] with the ignition true anomaly fixed at f0 (eq. 19 case A with x0(f0)).

    Continuation from the nominal in steps of at most max_step_rad; used to verify that f0*
    minimises t_f (second-order check of the free-ignition transversality condition).
    """
    problem = nominal.problem
    lam0 = nominal.z0[dyn.N_X:]
    scale = math.hypot(lam0[dyn.VR], lam0[dyn.VT])
    q = np.array([math.atan2(-lam0[dyn.VR], -lam0[dyn.VT]), lam0[dyn.R] / scale * nominal.t_f,
                  nominal.t_f])
    n_steps = max(1, int(math.ceil(abs(f0 - nominal.f0) / max_step_rad)))
    for f0_step in nominal.f0 + (f0 - nominal.f0) * np.arange(1, n_steps + 1) / n_steps:
        q, res = newton(lambda q: _reduced_residual(problem, q, free_f0=False,
                                                    f0_fixed=float(f0_step)), q)
        if not np.max(np.abs(res)) < 1e-12:
            raise RuntimeError(f"fixed-ignition solve failed at f0 = {f0_step}: residual {res}")
    return float(q[2])
