"""Integration of extremals z = [x; lambda] (14) in normalised time tau, with optional sensitivities.

  dz/dtau = t_f g(z),  g = [f~(x, u*(lambda)); -h_x(x, lambda, u*(lambda))]   (eqs. 22, 25, 27)

On an extremal (u minimises H, so H_u = 0) the Jacobian of t_f g is exactly [[A, -B], [-C, -A^T]]
(docs/design/vtd-nog.md, sec. 2) and d(t_f g)/dt_f = g = [D; -E]: the sensitivity S = dz(tau)/d[z(tau0), t_f]
(14 x 15) obeys S' = J S + [0 | g].
"""
from __future__ import annotations

import dataclasses

import numpy as np
from numpy.typing import NDArray
from scipy.integrate import solve_ivp

from . import dynamics as dyn

FloatArray = NDArray[np.float64]

N_Z = 2 * dyn.N_X
RTOL = 1e-12
ATOL = 1e-14


@dataclasses.dataclass(frozen=True)
class SegmentedSolution:
    """The parts of scipy's OdeResult that the callers use."""

    t: FloatArray
    y: FloatArray          #: (n_y, n_eval)
    success: bool
    message: str
    nfev: int


def solve_ivp_segmented(rhs, span: tuple[float, float], y0: FloatArray, t_eval: FloatArray,
                        breaks: FloatArray | None, **options):
    """solve_ivp(rhs, span, y0, t_eval=t_eval, **options), restarted at every break strictly
    inside the span. A tabulated thrust (cubic splines) makes the right-hand side only piecewise
    smooth: restarting at the knots keeps DOP853 from shrinking its steps around each of them.
    Without breaks inside the span this is exactly one solve_ivp call."""
    lo, hi = min(span), max(span)
    inner = np.array([]) if breaks is None else np.asarray(breaks, dtype=np.float64)
    inner = inner[(inner > lo) & (inner < hi)]
    if inner.size == 0:
        return solve_ivp(rhs, span, y0, t_eval=t_eval, **options)
    direction = 1.0 if span[1] >= span[0] else -1.0
    edges = np.concatenate([[span[0]], np.sort(inner)[::int(direction)], [span[1]]])
    t_eval = np.asarray(t_eval, dtype=np.float64)
    cols = np.empty((np.size(y0), t_eval.size))
    taken = np.zeros(t_eval.size, dtype=bool)
    y, nfev = np.asarray(y0, dtype=np.float64), 0
    for a, b in zip(edges[:-1], edges[1:]):
        want = ~taken & (direction * (t_eval - a) >= 0.0) & (direction * (t_eval - b) <= 0.0)
        pts = np.unique(np.append(t_eval[want], b))[::int(direction)]
        sol = solve_ivp(rhs, (float(a), float(b)), y, t_eval=pts, **options)
        if not sol.success:
            return SegmentedSolution(t_eval, cols, False, sol.message, nfev + int(sol.nfev))
        nfev += int(sol.nfev)
        for k in np.flatnonzero(want):
            cols[:, k] = sol.y[:, int(np.flatnonzero(pts == t_eval[k])[0])]
        taken |= want
        y = sol.y[:, -1]
    return SegmentedSolution(t_eval, cols, True, "segmented", nfev)


def extremal_jacobian(model: dyn.Model, z: FloatArray, t_f: float) -> tuple[FloatArray, FloatArray]:
    """(J (..., 14, 14), dz'/dt_f (..., 14)) of dz/dtau = t_f g(z) along an extremal."""
    x, lam = z[..., :dyn.N_X], z[..., dyn.N_X:]
    u = dyn.optimal_control(lam)
    mats = dyn.neighboring_matrices(model, x, lam, u, t_f)
    top = np.concatenate([mats.A, -mats.B], axis=-1)
    bottom = np.concatenate([-mats.C, -np.swapaxes(mats.A, -1, -2)], axis=-1)
    jac = np.concatenate([top, bottom], axis=-2)
    return jac, np.concatenate([mats.D, -mats.E], axis=-1)


@dataclasses.dataclass(frozen=True)
class ExtremalArc:
    """Result of `integrate_extremal`: values at the requested tau (in the order given)."""

    tau: FloatArray                 #: (N,)
    z: FloatArray                   #: (N, 14)
    sensitivity: FloatArray | None  #: (N, 14, 15) = dz/d[z(tau0), t_f], or None
    n_rhs: int                      #: right-hand-side evaluations


def integrate_extremal(model: dyn.Model, z_start: FloatArray, t_f: float, tau_start: float,
                       tau_eval: FloatArray, sensitivity: bool = False, rtol: float = RTOL,
                       atol: float = ATOL) -> ExtremalArc:
    """Integrates from (tau_start, z_start) to every tau in `tau_eval` (all on one side of tau_start).

    DOP853 at rtol 1e-12 by default. Values at tau_eval are integration nodes (t_eval), not
    interpolants.
    """
    tau_eval = np.atleast_1d(np.asarray(tau_eval, dtype=np.float64))
    direction = 1.0 if np.all(tau_eval >= tau_start) else -1.0
    if not (np.all(tau_eval >= tau_start) or np.all(tau_eval <= tau_start)):
        raise ValueError("tau_eval must lie on one side of tau_start")
    order = np.argsort(direction * tau_eval, kind="stable")
    tau_end = float(tau_eval[order[-1]])
    t_end = float(z_start[dyn.TIME]) + t_f * (tau_end - tau_start)
    t_max = model.max_time      # a(t) -> infinity as m -> 0, or the end of the thrust table
    if not (t_f > 0.0 and max(t_end, float(z_start[dyn.TIME])) < t_max):
        raise RuntimeError(f"t_f = {t_f} out of range: the arc would reach burnout (t = {t_max})")

    if sensitivity:
        def rhs(_: float, y: FloatArray) -> FloatArray:
            z = y[:N_Z]
            sens = y[N_Z:].reshape(N_Z, N_Z + 1)
            jac, d_tf = extremal_jacobian(model, z, t_f)
            dsens = jac @ sens
            dsens[:, -1] += d_tf
            return np.concatenate([t_f * d_tf, dsens.ravel()])   # g = [D; -E] on an extremal
        y0 = np.concatenate([z_start, np.hstack([np.eye(N_Z), np.zeros((N_Z, 1))]).ravel()])
    else:
        def rhs(_: float, y: FloatArray) -> FloatArray:
            return t_f * dyn.extremal_rate(model, y)
        y0 = np.asarray(z_start, dtype=np.float64)

    if tau_end == tau_start:
        ys = np.repeat(y0[None, :], tau_eval.size, axis=0)
        nfev = 0
    else:
        breaks = model.tau_breaks(t_f, tau_start, float(np.real(z_start[dyn.TIME])))
        sol = solve_ivp_segmented(rhs, (tau_start, tau_end), y0, tau_eval[order], breaks,
                                  method="DOP853", rtol=rtol, atol=atol)
        if not sol.success:
            raise RuntimeError(f"extremal integration failed: {sol.message}")
        ys = np.empty((tau_eval.size, y0.size))
        ys[order] = sol.y.T
        nfev = int(sol.nfev)
    sens_out = ys[:, N_Z:].reshape(-1, N_Z, N_Z + 1) if sensitivity else None
    return ExtremalArc(tau=tau_eval, z=ys[:, :N_Z], sensitivity=sens_out, n_rhs=nfev)


def _planar_extremal_rate(model: dyn.Model, y: FloatArray) -> FloatArray:
    """d/dt of y = [r, v_r, v_t, t, lambda_r, lambda_vr, lambda_vt] on a planar extremal with
    lambda_xi = 0 (the in-plane subset of `dyn.extremal_rate`, for fast batch scans)."""
    r, vr, vt, t, l1, l4, l5 = (y[..., i] for i in range(7))
    a, _, _ = model.accel(t)
    norm = np.sqrt(l4 * l4 + l5 * l5)
    return np.stack([
        vr,
        -model.mu / r**2 + vt * vt / r - a * l4 / norm,
        -vt * vr / r - a * l5 / norm,
        np.ones_like(r),
        -(l4 * (2.0 * model.mu / r**3 - vt * vt / r**2) + l5 * vt * vr / r**2),
        -(l1 - l5 * vt / r),
        -(2.0 * l4 * vt / r - l5 * vr / r)], axis=-1)


def rk4_extremal_batch(model: dyn.Model, z_start: FloatArray, t_f: FloatArray,
                       n_steps: int) -> FloatArray:
    """Fixed-step RK4 from tau = 0 to 1 for a batch of planar extremals (z_start (N, 14) with
    phi = v_n = lambda_xi = lambda_phi = lambda_vn = 0, t_f (N,)).

    Only for coarse scans (no error control); returns z(1) of shape (N, 14) (lambda_t not integrated).
    """
    cols = [dyn.R, dyn.VR, dyn.VT, dyn.TIME,
            dyn.N_X + dyn.R, dyn.N_X + dyn.VR, dyn.N_X + dyn.VT]
    y = np.array(z_start, dtype=np.float64)[:, cols]
    scale = np.asarray(t_f, dtype=np.float64)[:, None]
    step = 1.0 / n_steps
    for _ in range(n_steps):
        k1 = scale * _planar_extremal_rate(model, y)
        k2 = scale * _planar_extremal_rate(model, y + 0.5 * step * k1)
        k3 = scale * _planar_extremal_rate(model, y + 0.5 * step * k2)
        k4 = scale * _planar_extremal_rate(model, y + step * k3)
        y = y + step / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4)
    z = np.array(z_start, dtype=np.float64)
    z[:, cols] = y
    return z
