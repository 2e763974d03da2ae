"""ogk_qp_solve (ogk/qp.h) from numpy: one problem struct built once over the caller's arrays, solved as often
as wanted (the tests' checks and the benches' timings call the same solve)."""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray

from ._ffi import ffi, lib
from ._real import to_real

F64 = NDArray[np.float64]


@dataclass
class QpSolve:
    """One dense QP (docs/design/qp.md): minimise 1/2 x^T H x + g^T x subject to A_eq x = b_eq, A_in x >= b_in,
    lb <= x <= ub (|bound| >= OGK_QP_INF: none). Empty arrays mean no rows / no bounds."""

    H: F64
    g: F64
    A_eq: F64
    b_eq: F64
    A_in: F64
    b_in: F64
    lb: F64
    ub: F64
    _keep: list = field(default_factory=list, repr=False)

    def __post_init__(self) -> None:
        self._arrays = [to_real(a) for a in  # the kernel's real type (ogk_bindings._real)
                        (self.H, self.g, self.A_eq, self.b_eq, self.A_in, self.b_in, self.lb, self.ub)]
        H, g, A_eq, b_eq, A_in, b_in, lb, ub = (self._ptr(a) for a in self._arrays)
        p = ffi.new("ogk_qp_problem_t *")
        p.n, p.m_eq, p.m_in = len(self._arrays[1]), len(self._arrays[3]), len(self._arrays[5])
        p.H, p.g, p.A_eq, p.b_eq, p.A_in, p.b_in, p.lb, p.ub = H, g, A_eq, b_eq, A_in, b_in, lb, ub
        self.problem = p
        self.workspace = ffi.new("ogk_qp_workspace_t *")
        self.solution = ffi.new("ogk_qp_solution_t *")

    def _ptr(self, a: F64):
        if a.size == 0:
            return ffi.NULL
        buf = ffi.from_buffer("ogk_real_t[]", a)
        self._keep.append(buf)
        return buf

    def solve(self) -> int:
        """ogk_qp_solve's status (an ogk_status code); the answer is in `solution`."""
        return int(lib.ogk_qp_solve(self.workspace, self.problem, self.solution))

    def result(self) -> dict:
        """status of the last solve is the caller's; x, y_eq, y_in, z_lb, z_ub, objective, iterations,
        n_active of the solution struct."""
        s, p = self.solution, self.problem

        def vec(c, k: int) -> F64:
            return np.array(ffi.unpack(c, k), dtype=float)

        return dict(x=vec(s.x, p.n), y_eq=vec(s.y_eq, p.m_eq), y_in=vec(s.y_in, p.m_in), z_lb=vec(s.z_lb, p.n),
                    z_ub=vec(s.z_ub, p.n), objective=float(s.objective), iterations=int(s.iterations),
                    n_active=int(s.n_active))
