"""ogk_qp_solve (kernel/src/qp/qp.c, Goldfarb-Idnani) through the cffi bindings
against an independent solver: qpOASES (CasADi's conic interface, an online
active-set method) on random feasible QPs of the NMPC's size, plus the KKT
conditions of the kernel's answer checked here in numpy and infeasible
problems detected. docs/design/qp.md."""
from __future__ import annotations

import casadi
import numpy as np
import pytest

from ogk_bindings._ffi import lib
from ogk_bindings.qp import QpSolve

pytestmark = pytest.mark.req("OGK-CORE-018")

INF = float(lib.OGK_QP_INF)


class QP:
    """One QP in numpy arrays, solvable by the kernel and by qpOASES."""

    def __init__(self, H, g, A_eq, b_eq, A_in, b_in, lb, ub):
        self.H = np.ascontiguousarray(H, dtype=float)
        self.g = np.ascontiguousarray(g, dtype=float)
        self.A_eq = np.ascontiguousarray(A_eq, dtype=float).reshape(-1, len(g))
        self.b_eq = np.ascontiguousarray(b_eq, dtype=float)
        self.A_in = np.ascontiguousarray(A_in, dtype=float).reshape(-1, len(g))
        self.b_in = np.ascontiguousarray(b_in, dtype=float)
        self.lb = np.ascontiguousarray(lb, dtype=float)
        self.ub = np.ascontiguousarray(ub, dtype=float)

    @property
    def n(self) -> int:
        return len(self.g)

    def objective(self, x: np.ndarray) -> float:
        return float(0.5 * x @ self.H @ x + self.g @ x)

    def kernel(self):
        """(status, x, y_eq, y_in, z_lb, z_ub, objective, iterations, n_active)."""
        q = QpSolve(self.H, self.g, self.A_eq, self.b_eq, self.A_in, self.b_in, self.lb, self.ub)
        st = q.solve()
        return dict(status=st, **q.result())

    def qpoases(self) -> tuple[np.ndarray, float, bool]:
        """x, objective and success of qpOASES (dense, tight tolerances)."""
        A = np.vstack([self.A_eq, self.A_in])
        lba = np.concatenate([self.b_eq, self.b_in])
        uba = np.concatenate([self.b_eq, np.full(len(self.b_in), np.inf)])
        lbx = np.where(self.lb <= -INF, -np.inf, self.lb)
        ubx = np.where(self.ub >= INF, np.inf, self.ub)
        solver = casadi.conic("q", "qpoases", {
            "h": casadi.DM(self.H).sparsity(), "a": casadi.Sparsity.dense(*A.shape)},
            {"printLevel": "none", "sparse": False, "error_on_fail": False,
             "terminationTolerance": 1e-12, "boundTolerance": 1e-12,
             "nWSR": 10000})
        r = solver(h=self.H, g=self.g, a=A, lba=lba, uba=uba, lbx=lbx, ubx=ubx)
        x = np.array(r["x"]).ravel()
        return x, self.objective(x), bool(solver.stats()["success"])


def random_qp(rng: np.random.Generator, n: int, m_eq: int = 4, m_in: int = 6,
              bound_share: float = 1.0 / 3.0) -> QP:
    """Feasible by construction: b from a known point x0 (equalities exact,
    inequalities with slack in [0, 1) or exactly 0, bounds around x0)."""
    M = rng.standard_normal((n, n))
    H = M @ M.T / n + 0.05 * np.eye(n)          # a BFGS-like SPD matrix, cond ~ 1e3
    g = 3.0 * rng.standard_normal(n)
    x0 = rng.uniform(-1.0, 1.0, n)
    A_eq = rng.standard_normal((m_eq, n))
    b_eq = A_eq @ x0
    A_in = rng.standard_normal((m_in, n))
    slack = np.where(rng.uniform(size=m_in) < 0.25, 0.0, rng.uniform(0.0, 1.0, m_in))
    b_in = A_in @ x0 - slack
    lb = np.full(n, -INF)
    ub = np.full(n, INF)
    bounded = rng.choice(n, size=int(round(bound_share * n)), replace=False)
    for i in bounded:
        kind = rng.integers(3)
        if kind != 1:
            lb[i] = x0[i] - (0.0 if rng.uniform() < 0.2 else rng.uniform(0.0, 0.5))
        if kind != 0:
            ub[i] = x0[i] + rng.uniform(0.0, 0.5)
    return QP(H, g, A_eq, b_eq, A_in, b_in, lb, ub)


def check_kkt(qp: QP, r: dict, tol: float = 1e-9) -> None:
    x = r["x"]
    scale = max(1.0, np.abs(x).max())
    stat = (qp.H @ x + qp.g - qp.A_eq.T @ r["y_eq"] - qp.A_in.T @ r["y_in"]
            - r["z_lb"] + r["z_ub"])
    mult = max(1.0, np.abs(np.concatenate([r["y_eq"], r["y_in"], r["z_lb"], r["z_ub"]])).max())
    assert np.abs(stat).max() <= tol * (np.abs(qp.H).max() * scale + mult + np.abs(qp.g).max())
    assert np.abs(qp.A_eq @ x - qp.b_eq).max(initial=0.0) <= tol * scale
    s_in = qp.A_in @ x - qp.b_in
    assert s_in.min(initial=0.0) >= -tol * scale
    assert r["y_in"].min(initial=0.0) >= 0.0 and r["z_lb"].min() >= 0.0 and r["z_ub"].min() >= 0.0
    assert np.abs(r["y_in"] * s_in).max(initial=0.0) <= tol * mult * scale
    has_lb, has_ub = qp.lb > -INF, qp.ub < INF
    assert np.all(x[has_lb] - qp.lb[has_lb] >= -tol * scale)
    assert np.all(qp.ub[has_ub] - x[has_ub] >= -tol * scale)
    assert np.all(r["z_lb"][~has_lb] == 0.0) and np.all(r["z_ub"][~has_ub] == 0.0)
    assert np.abs(r["z_lb"][has_lb] * (x - qp.lb)[has_lb]).max(initial=0.0) <= tol * mult * scale
    assert np.abs(r["z_ub"][has_ub] * (qp.ub - x)[has_ub]).max(initial=0.0) <= tol * mult * scale
    assert r["objective"] == pytest.approx(qp.objective(x), rel=1e-12, abs=1e-12)


def test_random_target_size_vs_qpoases(rng: np.random.Generator) -> None:
    """200 QPs, n = 32..67, 4 equalities, bounds on a third of the variables,
    2..10 inequality rows: x to 1e-8 relative, objective to 1e-10."""
    worst_x = worst_f = 0.0
    active_rows = 0
    for _ in range(200):
        n = int(rng.integers(32, 68))
        qp = random_qp(rng, n, m_eq=4, m_in=int(rng.integers(2, 11)))
        r = qp.kernel()
        assert r["status"] == lib.OGK_OK
        check_kkt(qp, r)
        x_ref, f_ref, ok = qp.qpoases()
        assert ok
        dx = np.abs(r["x"] - x_ref).max() / max(1.0, np.abs(x_ref).max())
        df = abs(r["objective"] - f_ref) / max(1.0, abs(f_ref))
        worst_x, worst_f = max(worst_x, dx), max(worst_f, df)
        assert dx <= 1e-8
        assert df <= 1e-10
        assert 4 <= r["n_active"] <= n
        active_rows += r["n_active"] - 4
    # the inequalities matter: on average several are active at the optimum
    assert active_rows >= 2 * 200
    print(f"worst |dx|/|x| {worst_x:.2e}, worst |df|/|f| {worst_f:.2e}")


def test_iteration_limit_not_reached_at_max_size(rng: np.random.Generator) -> None:
    """The compile-time limits: n = 72, 8 equalities, 80 rows, every variable
    bounded; the solve stays well inside OGK_QP_MAX_ITER."""
    n = int(lib.OGK_QP_MAX_N)
    qp = random_qp(rng, n, m_eq=int(lib.OGK_QP_MAX_EQ), m_in=int(lib.OGK_QP_MAX_IN),
                   bound_share=1.0)
    r = qp.kernel()
    assert r["status"] == lib.OGK_OK
    check_kkt(qp, r)
    x_ref, f_ref, ok = qp.qpoases()
    assert ok
    np.testing.assert_allclose(r["x"], x_ref, rtol=0, atol=1e-8 * max(1.0, np.abs(x_ref).max()))
    assert r["iterations"] < int(lib.OGK_QP_MAX_ITER) // 2


def test_infeasible_detected(rng: np.random.Generator) -> None:
    n = 40
    for _ in range(20):
        base = random_qp(rng, n)
        # 1. equalities against bounds: sum of the first 10 variables = 100,
        #    each of them in [-1, 1]
        A_eq = np.vstack([base.A_eq, np.r_[np.ones(10), np.zeros(n - 10)]])
        b_eq = np.r_[base.b_eq, 100.0]
        lb, ub = base.lb.copy(), base.ub.copy()
        lb[:10], ub[:10] = -1.0, 1.0
        qp = QP(base.H, base.g, A_eq, b_eq, base.A_in, base.b_in, lb, ub)
        assert qp.kernel()["status"] == lib.OGK_E_INFEASIBLE
        assert not qp.qpoases()[2]
        # 2. two inequality rows a^T x >= 1 and -2 a^T x >= 0
        a = rng.standard_normal(n)
        A_in = np.vstack([base.A_in, a, -2.0 * a])
        b_in = np.r_[base.b_in, 1.0, 0.0]
        qp = QP(base.H, base.g, base.A_eq, base.b_eq, A_in, b_in, base.lb, base.ub)
        r = qp.kernel()
        assert r["status"] == lib.OGK_E_INFEASIBLE
        assert np.all(r["x"] == 0.0) and np.all(r["y_in"] == 0.0)
        # 3. inconsistent dependent equality rows
        A_eq = np.vstack([base.A_eq, base.A_eq[0] + base.A_eq[1]])
        b_eq = np.r_[base.b_eq, base.b_eq[0] + base.b_eq[1] + 0.5]
        qp = QP(base.H, base.g, A_eq, b_eq, base.A_in, base.b_in, base.lb, base.ub)
        assert qp.kernel()["status"] == lib.OGK_E_INFEASIBLE
        # ... and consistent ones solve, to the same point as without the row
        b_eq[-1] -= 0.5
        r_dep = QP(base.H, base.g, A_eq, b_eq, base.A_in, base.b_in, base.lb, base.ub).kernel()
        r = base.kernel()
        assert r_dep["status"] == lib.OGK_OK and r["status"] == lib.OGK_OK
        np.testing.assert_allclose(r_dep["x"], r["x"], rtol=0, atol=1e-9)


def test_not_posdef_and_bad_input(rng: np.random.Generator) -> None:
    base = random_qp(rng, 32)
    w, V = np.linalg.eigh(base.H)
    w[0] = -1e-3
    qp = QP(V @ np.diag(w) @ V.T, base.g, base.A_eq, base.b_eq, base.A_in, base.b_in,
            base.lb, base.ub)
    assert qp.kernel()["status"] == lib.OGK_E_NOT_POSDEF
    lb = base.lb.copy()
    lb[3], ub3 = 2.0, base.ub.copy()
    ub3[3] = 1.0
    assert QP(base.H, base.g, base.A_eq, base.b_eq, base.A_in, base.b_in, lb,
              ub3).kernel()["status"] == lib.OGK_E_RANGE
    g = base.g.copy()
    g[5] = np.nan
    assert QP(base.H, g, base.A_eq, base.b_eq, base.A_in, base.b_in, base.lb,
              base.ub).kernel()["status"] == lib.OGK_E_NONFINITE
