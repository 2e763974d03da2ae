"""Fourier representation of the MPSP control U = lambda_v (paper 000, eqs. 36-39, 49-50, App. C).

Basis (C.1): h(eta) = [1/2, cos(pi eta), sin(pi eta), ..., cos(n pi eta), sin(n pi eta)], with eta mapped
linearly from [t_0, t_f] onto [eta_0, eta_f] (eq. 39). Bases measured here (all 2n + 1 weights per axis):
  "printed"    (C.1), eta in [-pi, pi]:  fundamental period t_f/pi (about one orbit here), as printed
  "period_tf"  (C.1), eta in [-1, 1]:    fundamental period t_f (periodic extension of lambda_v)
  "period_2tf" (C.1), eta in [-1/2, 1/2]: fundamental period 2 t_f, nothing periodic imposed; but cos and
               sin over half a period are nearly linearly dependent (cond(P_hat) ~ 1e11)
  "cosine_2tf" [1/2, cos(pi eta), cos(2 pi eta), ..., cos(2n pi eta)], eta in [0, 1]: fundamental period
               2 t_f (even extension of lambda_v about t_0 and t_f), orthogonal on the grid
ERRATUM (paper 000, App. C): the printed range fits the nominal lambda_v badly. docs/design/apophis-nominal.md
gives the measurements behind the scenario's choice.

The initial weights eps_0 solve P_hat eps_0 = U_hat in the least-squares sense (eqs. 49-50) on the MPSP
grid: each segment between switches evenly split into N_k = ceil(dt_k/h_max) intervals (eq. 18).
"""
from __future__ import annotations

import dataclasses
import math

import numpy as np
from numpy.typing import NDArray
from scipy.integrate import solve_ivp

from .indirect import Solution, normalised_problem, propagate
from .scenario import Scenario

FloatArray = NDArray[np.float64]

BASIS_ETA_RANGE: dict[str, tuple[float, float]] = {
    "printed": (-math.pi, math.pi),
    "period_tf": (-1.0, 1.0),
    "period_2tf": (-0.5, 0.5),
    "cosine_2tf": (0.0, 1.0),
}


def eta_of_time(t: FloatArray, t0: float, tf: float, basis: str) -> FloatArray:
    """Eq. (39): linear map of t in [t_0, t_f] onto the basis' eta range."""
    eta0, etaf = BASIS_ETA_RANGE[basis]
    return (etaf - eta0) / (tf - t0) * (np.asarray(t, dtype=np.float64) - t0) + eta0


def basis_functions(eta: FloatArray, order: int, basis: str = "printed") -> FloatArray:
    """h(eta)^T for each eta: shape (len(eta), 2 order + 1). (C.1) unless basis == "cosine_2tf"."""
    eta = np.atleast_1d(np.asarray(eta, dtype=np.float64))
    h = np.empty((eta.size, 2 * order + 1))
    h[:, 0] = 0.5
    if basis == "cosine_2tf":
        h[:, 1:] = np.cos(np.pi * np.outer(eta, np.arange(1, 2 * order + 1)))
        return h
    phase = np.pi * np.outer(eta, np.arange(1, order + 1))
    h[:, 1::2] = np.cos(phase)
    h[:, 2::2] = np.sin(phase)
    return h


def control_matrix(eta: FloatArray, order: int, basis: str = "printed") -> FloatArray:
    """P(eta) of eq. (37) stacked over eta: shape (len(eta), 3, 3 (2 order + 1)), block diagonal."""
    h = basis_functions(eta, order, basis)
    n_h = h.shape[1]
    p = np.zeros((h.shape[0], 3, 3 * n_h))
    for axis in range(3):
        p[:, axis, axis * n_h:(axis + 1) * n_h] = h
    return p


def mpsp_time_grid(switch_times: FloatArray, t0: float, tf: float, h_max: float) -> FloatArray:
    """Evenly spaced grid of each segment between switches, N_k = ceil(dt_k/h_max) (eq. 18).

    Segment end points shared by neighbouring segments appear once.
    """
    bounds = np.concatenate([[t0], np.sort(np.asarray(switch_times, dtype=np.float64)), [tf]])
    pieces = [np.linspace(a, b, int(math.ceil((b - a) / h_max)) + 1)[:-1]
              for a, b in zip(bounds[:-1], bounds[1:])]
    return np.concatenate(pieces + [np.array([tf])])


def least_squares_weights(eta: FloatArray, control: FloatArray, order: int,
                          basis: str = "printed") -> FloatArray:
    """eps_0 = (P_hat^T P_hat)^-1 P_hat^T U_hat (eq. 50), with P_hat, U_hat stacked as in eq. (49).

    Solved by an orthogonal factorisation (np.linalg.lstsq): the same minimiser as the normal equations
    of eq. (50) when P_hat is well conditioned, and still the least-squares fit when it is not
    ("period_2tf": cond(P_hat^T P_hat) ~ 1e22, beyond double precision).
    """
    p_hat = control_matrix(eta, order, basis).reshape(-1, 3 * (2 * order + 1))
    u_hat = np.asarray(control, dtype=np.float64).reshape(-1)
    return np.linalg.lstsq(p_hat, u_hat, rcond=None)[0]


def evaluate(eta: FloatArray, weights: FloatArray, order: int, basis: str = "printed") -> FloatArray:
    """U(eta) = P(eta) eps (eq. 36): shape (len(eta), 3)."""
    n_h = 2 * order + 1
    h = basis_functions(eta, order, basis)
    return np.stack([h @ weights[a * n_h:(a + 1) * n_h] for a in range(3)], axis=1)


@dataclasses.dataclass(frozen=True)
class FitError:
    """How well the basis reproduces the nominal lambda_v on the MPSP grid."""

    basis: str
    order: int
    max_abs: float           #: max over time and components of |U_fit - U| [-]
    rms: float               #: root mean square over time and components [-]
    max_relative: float      #: max |U_fit - U| / max |U| (component-wise norms)
    max_angle_deg: float     #: max angle between fitted and nominal lambda_v (thrust direction error)
    condition_number: float  #: cond(h) of the per-axis design matrix (cond(P_hat^T P_hat) is its square)
    max_weight: float        #: max |eps_0|
    signal_min: float        #: min over time of |lambda_v|
    signal_max: float        #: max over time of |lambda_v|


@dataclasses.dataclass(frozen=True)
class FourierWeights:
    """Initial MPSP weights eps_0 and lambda_m0 from the nominal solution (section 3.3)."""

    basis: str
    order: int
    eta_range: tuple[float, float]
    epsilon: FloatArray        #: (3 (2 order + 1),) = [eps_x, eps_y, eps_z]
    lambda_m0: float
    fit: FitError


def nominal_control_on_grid(scenario: Scenario, solution: Solution,
                            ) -> tuple[FloatArray, FloatArray]:
    """(t, lambda_v(t)) of the solution on the MPSP grid of eq. (18)."""
    problem = normalised_problem(scenario, solution.perturbation)
    prop = propagate(problem, solution.lam0, 0.0, rtol=scenario.homotopy.final_rtol, dense=True)
    tf = problem.final_time
    t = mpsp_time_grid(prop.switch_times, 0.0, tf, scenario.mpsp.h_max_over_tf * tf)
    return t, prop.sample(t)[:, 10:13]


def fit_error(t: FloatArray, lam_v: FloatArray, tf: float, basis: str, order: int) -> FitError:
    """Least-squares fit of lambda_v with `basis` up to `order`, and its error."""
    eta = eta_of_time(t, 0.0, tf, basis)
    weights = least_squares_weights(eta, lam_v, order, basis)
    fitted = evaluate(eta, weights, order, basis)
    singular = np.linalg.svd(basis_functions(eta, order, basis), compute_uv=False)
    diff = fitted - lam_v
    norm_true = np.linalg.norm(lam_v, axis=1)
    cos_angle = np.sum(fitted * lam_v, axis=1) / (np.linalg.norm(fitted, axis=1) * norm_true)
    return FitError(basis, order, float(np.max(np.abs(diff))), float(np.sqrt(np.mean(diff**2))),
                    float(np.max(np.abs(diff)) / np.max(np.abs(lam_v))),
                    float(np.degrees(np.max(np.arccos(np.clip(cos_angle, -1.0, 1.0))))),
                    float(singular[0] / singular[-1]), float(np.max(np.abs(weights))),
                    float(norm_true.min()), float(norm_true.max()))


def initial_weights(scenario: Scenario, solution: Solution, basis: str | None = None,
                    order: int | None = None) -> FourierWeights:
    """eps_0 (eq. 50) and lambda_m0 of the nominal solution, with the scenario's basis by default."""
    basis = basis or scenario.mpsp.fourier_basis
    order = order or scenario.mpsp.fourier_order
    t, lam_v = nominal_control_on_grid(scenario, solution)
    tf = scenario.final_time
    eta = eta_of_time(t, 0.0, tf, basis)
    return FourierWeights(basis, order, BASIS_ETA_RANGE[basis],
                          least_squares_weights(eta, lam_v, order, basis), float(solution.lam0[6]),
                          fit_error(t, lam_v, tf, basis, order))


def fly_fitted_control(scenario: Scenario, solution: Solution, basis: str, weights: FloatArray,
                       order: int, lambda_m0: float | None = None, rtol: float = 1e-11,
                       ) -> FloatArray:
    """Terminal error Delta Y = [r(t_f) - r_f, v(t_f) - v_f, lambda_m(t_f)] of the MPSP dynamics
    (eq. 16, X = [r, v, m, lambda_m], U = lambda_v = P(eta) eps) flown with the fitted control.

    This is the error the MPSP inner loop starts from on the unperturbed problem (compare Delta_max).
    Switches of u at the zeros of S (eq. 10) are located as integration events.
    """
    problem = normalised_problem(scenario, solution.perturbation)
    c, thrust, mu, tf = (problem.exhaust_velocity, problem.max_thrust, problem.mu,
                         problem.final_time)
    lam_m0 = float(solution.lam0[6]) if lambda_m0 is None else lambda_m0

    def control(t: float) -> FloatArray:
        return evaluate(eta_of_time(np.array([t]), 0.0, tf, basis), weights, order, basis)[0]

    def switching(t: float, x: FloatArray) -> float:
        return 1.0 - c * float(np.linalg.norm(control(t))) / x[6] - x[7]

    def rhs(t: float, x: FloatArray, u: float) -> FloatArray:
        lam_v = control(t)
        lam_v_norm = float(np.linalg.norm(lam_v))
        r = x[0:3]
        return np.concatenate([x[3:6], -mu * r / float(np.linalg.norm(r))**3
                               - u * thrust / (x[6] * lam_v_norm) * lam_v,
                               [-u * thrust / c, -u * thrust * lam_v_norm / x[6]**2]])

    x = np.concatenate([problem.x0, [lam_m0]])
    t, u = 0.0, (1.0 if switching(0.0, x) < 0.0 else 0.0)
    for _ in range(200):
        def event(tt: float, xx: FloatArray, _u: float) -> float:
            return switching(tt, xx)
        event.terminal = True  # type: ignore[attr-defined]
        event.direction = 1.0 if u == 1.0 else -1.0  # type: ignore[attr-defined]
        sol = solve_ivp(rhs, (t, tf), x, method="DOP853", rtol=rtol, atol=rtol * 0.1,
                        events=event, args=(u,))
        if sol.status == 1:
            t, x, u = float(sol.t_events[0][0]), sol.y_events[0][0], 1.0 - u
            continue
        x = sol.y[:, -1]
        break
    return np.concatenate([x[0:3] - problem.rf, x[3:6] - problem.vf, [x[7]]])
