"""Exact re-solve of the minimum-time problem from a displaced state (the truth for the gain check).

At a sample tau_k the vehicle is at x_k (7 components, real time t_k included). The remaining
problem on [tau_k, 1] is: minimise the remaining time t_f (1 - tau_k) subject to x' = t_f f~(x, u),
x(tau_k) = x_k, and the injection conditions of eq. (20) at tau = 1. Its necessary conditions are those
of nominal.py without the ignition manifold: lambda_xi(1) = 0, lambda_t(1) = 0 and, from eq. (28) with
mu(tau_k) = 0, mu(1) = 1 - tau_k, the constant Hamiltonian h = lambda^T f~ = -1. The nominal restricted to
[tau_k, 1] satisfies them with its own costates, so lambda_k - lambda*(tau_k) and t_f - t_f* are the
exact changes the VTD-NOG gains predict to first order.

Unknowns q = [lambda(tau_k) (7), t_f]; residuals [r - R_f, phi, v_r, v_t - v_c, v_n, lambda_xi,
lambda_t, h + 1] at tau = 1; Newton with the exact Jacobian of the extremal flow (only the converged
root matters: it depends on f~ and h_x, not on the gain derivation), started from the nominal values.
"""
from __future__ import annotations

import dataclasses

import numpy as np
from numpy.typing import NDArray

from . import dynamics as dyn
from .nominal import Nominal, newton
from .propagation import N_Z, integrate_extremal

FloatArray = NDArray[np.float64]

RESIDUAL_NAMES = ("r(1) - R_f", "phi(1)", "v_r(1)", "v_t(1) - v_c", "v_n(1)", "lambda_xi(1)",
                  "lambda_t(1)", "h(1) + 1")


@dataclasses.dataclass(frozen=True)
class RemainingArcSolution:
    """Optimal remaining arc from (tau_k, x_k), canonical units."""

    tau_k: float
    x_k: FloatArray          #: (7,)
    lam_k: FloatArray        #: (7,) costates at tau_k, normalised to h = -1
    t_f: float               #: new total-time parameter [TU]; remaining time = t_f (1 - tau_k)
    residuals: FloatArray    #: (8,) RESIDUAL_NAMES


def _residual(nominal: Nominal, tau_k: float, x_k: FloatArray,
              q: FloatArray) -> tuple[FloatArray, FloatArray]:
    problem = nominal.problem
    lam_k, t_f = q[:dyn.N_X], float(q[dyn.N_X])
    arc = integrate_extremal(problem.model, np.concatenate([x_k, lam_k]), t_f, tau_k,
                             np.array([1.0]), sensitivity=True)
    z1, sens = arc.z[0], arc.sensitivity[0]
    x1, lam1 = z1[:dyn.N_X], z1[dyn.N_X:]
    u1 = dyn.optimal_control(lam1)
    f1 = dyn.state_rate(problem.model, x1, u1)
    _, h_x1, _ = dyn.costate_rate_terms(problem.model, x1, lam1, u1)
    res = np.array([x1[dyn.R] - problem.target_radius, x1[dyn.PHI], x1[dyn.VR],
                    x1[dyn.VT] - problem.circular_speed, x1[dyn.VN], lam1[dyn.XI],
                    lam1[dyn.TIME], float(lam1 @ f1) + 1.0])
    dz1_dq = np.hstack([sens[:, dyn.N_X:N_Z], sens[:, N_Z:]])          # (14, 8)
    rows = [dyn.R, dyn.PHI, dyn.VR, dyn.VT, dyn.VN, dyn.N_X + dyn.XI, dyn.N_X + dyn.TIME]
    dh = np.concatenate([h_x1, f1]) @ dz1_dq                            # h_u = 0 on an extremal
    return res, np.vstack([dz1_dq[rows, :], dh])


def solve_remaining_arc(nominal: Nominal, tau_k: float, x_k: FloatArray,
                        guess: FloatArray | None = None, tol: float = 1e-13,
                        max_continuation: int = 64) -> RemainingArcSolution:
    """Solves the remaining-arc problem from (tau_k, x_k), starting from the nominal values (or
    `guess`). If damped Newton does not reach `tol`, the displacement from the nominal state is
    applied in 2, 4, ... continuation steps (up to max_continuation), each started from the last."""
    x_k = np.asarray(x_k, dtype=np.float64)
    z_nom = nominal.states(np.array([tau_k]))[0]
    start = np.append(z_nom[dyn.N_X:], nominal.t_f) if guess is None else np.asarray(guess)
    n_steps = 1
    while True:
        q = start.copy()
        for frac in np.arange(1, n_steps + 1) / n_steps:
            x_frac = z_nom[:dyn.N_X] + frac * (x_k - z_nom[:dyn.N_X])
            q, res = newton(lambda q: _residual(nominal, tau_k, x_frac, q), q, max_iter=20, tol=tol)
        if np.max(np.abs(res)) < tol or n_steps >= max_continuation:
            break
        n_steps *= 2
    return RemainingArcSolution(tau_k=tau_k, x_k=x_k.copy(), lam_k=q[:dyn.N_X].copy(),
                                t_f=float(q[dyn.N_X]), residuals=res)
