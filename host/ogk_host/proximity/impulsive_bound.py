"""A rigorous lower bound on the Delta v of any transfer of the CW equations between two states in a
fixed time T (the independent reference of the proximity OCP's fuel).

The thrust acceleration a(t) enters linearly: s(T) = Phi(T) s_0 + int_0^T B(T - t) a(t) dt, with B(tau)
the velocity columns of Phi(tau). For any lambda with |B(tau)^T lambda| <= 1 on [0, T],
lambda^T (s_T - Phi(T) s_0) = int lambda^T B a dt <= int |a| dt = Delta v (Neustadt's dual of the
minimum-fuel problem; the impulsive optimum attains the sup). A keep-out or a thrust bound only adds
constraints, so the bound holds for them too; the continuous solution's Delta v = v_e ln(m_0 / m_N).

lambda comes from the dual problem on a grid of tau (IPOPT), then is scaled down by the largest
|B(tau)^T lambda| over a grid 50 times finer plus twice the largest change between neighbouring points
of that grid (the norm is smooth in tau: between two points it cannot exceed them by more), so that the
result is a bound and not an estimate."""
from __future__ import annotations

import casadi as ca
import numpy as np

from .dynamics import FloatArray, coast_stm


def delta_v_lower_bound(n: float, s0: FloatArray, s_t: FloatArray, t: float, grid: int = 400) -> float:
    """max lambda^T d, |B(tau)^T lambda| <= 1 on [0, t]; d = s_t - Phi(t) s_0 (4-vectors: x, y, v_x, v_y)."""
    d = np.asarray(s_t, dtype=np.float64)[:4] - coast_stm(n, t) @ np.asarray(s0, dtype=np.float64)[:4]
    taus = np.linspace(0.0, t, grid)
    lam = ca.MX.sym("lam", 4)
    cons = [ca.sumsqr(ca.mtimes(coast_stm(n, float(tau))[:, 2:].T, lam)) for tau in taus]
    nlp = {"x": lam, "f": -ca.dot(ca.DM(d), lam), "g": ca.vertcat(*cons)}
    solver = ca.nlpsol("dual", "ipopt", nlp, {"print_time": False,
                                              "ipopt": {"print_level": 0, "tol": 1e-12}})
    res = solver(x0=np.zeros(4), lbg=-np.inf, ubg=1.0)
    lam_v = np.asarray(res["x"]).ravel()
    fine = np.linspace(0.0, t, 50 * grid)
    norms = np.array([np.linalg.norm(coast_stm(n, float(tau))[:, 2:].T @ lam_v) for tau in fine])
    # between two fine points the norm moves by at most the largest step seen times 2 (smooth, and the
    # fine grid resolves its variation): a margin that keeps the scaled lambda feasible everywhere
    margin = 2.0 * float(np.max(np.abs(np.diff(norms))))
    return float(lam_v @ d) / (float(norms.max()) + margin)
