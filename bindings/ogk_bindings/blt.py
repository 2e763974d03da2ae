"""Typed bindings of the kernel's BLT guidance with its NRPC corrector (kernel/include/ogk/blt.h,
docs/design/blt.md).

    cfg = BltConfig(model=dict(mu=..., body_radius=[...], thrust_accel=..., ...), n_segments=3,
                    segment_kind=[BURN, COAST, BURN], ...)       # ogk_blt_config_default underneath
    k = Blt(cfg)                                                  # ogk_blt_init (KernelError if rejected)
    sol, rep = k.solve(Transfer(...))                             # corrector; rep.status says how it ended
    rep = k.evaluate(tr); x_end, rep = k.propagate(tr); J = k.jacobian(tr)
    cmd = k.command(t)                                            # eq. (22) of the held solution
    c = k.thrust_cmd(t)                                           # the one command of every law (synodic)

Normalised units throughout (docs/design/blt.md, sec. 1: LU = separation, TU = T_o / 2 pi, mass fraction).
Bad inputs raise KernelError; a corrector that does not converge returns its report (status names why).
"""
from __future__ import annotations

import dataclasses

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ogk_bindings._ffi import ffi, lib
from ogk_bindings._real import real_view
from ogk_bindings.config import KernelConfig
from ogk_bindings.kernel import ThrustCmd, _check, _thrust_cmd_call, status_name

F64 = NDArray[np.float64]

__all__ = ["BURN", "COAST", "NRPC", "LM", "HYBRID", "CENTRAL", "VARIATIONAL", "Blt", "BltConfig", "BltReport",
           "Transfer", "MAX_SEGMENTS", "MAX_FREE_NODES"]

NX: int = int(lib.OGK_BLT_NX)
NP: int = int(lib.OGK_BLT_NP)
MAX_SEGMENTS: int = int(lib.OGK_BLT_MAX_SEGMENTS)
MAX_FREE_NODES: int = int(lib.OGK_BLT_MAX_FREE_NODES)
MAX_UNKNOWNS: int = int(lib.OGK_BLT_MAX_UNKNOWNS)
MAX_ERRORS: int = int(lib.OGK_BLT_MAX_ERRORS)
BURN: int = int(lib.OGK_BLT_SEG_BURN)
COAST: int = int(lib.OGK_BLT_SEG_COAST)
NRPC: int = int(lib.OGK_BLT_CORR_NRPC)
LM: int = int(lib.OGK_BLT_CORR_LM)
HYBRID: int = int(lib.OGK_BLT_CORR_HYBRID)
CENTRAL: int = int(lib.OGK_BLT_JAC_CENTRAL)
VARIATIONAL: int = int(lib.OGK_BLT_JAC_VARIATIONAL)
FLAGS: dict[str, int] = {name: int(getattr(lib, f"OGK_BLT_FLAG_{name}"))
                         for name in ("CONVERGED", "IMPACT", "SINGULAR", "ITER_LIMIT", "STALLED", "SAFE",
                                      "GUESS_IMPACT")}


class BltConfig(KernelConfig):
    _ctype = "ogk_blt_config_t"
    _default_fn = "ogk_blt_config_default"


@dataclasses.dataclass
class Transfer:
    """One transfer (ogk_blt_transfer_t): start, target and the corrector's unknowns."""

    t0: float                     #: [TU] start time (sets the Sun's direction)
    x0: F64                       #: (6,) [LU, VU] start state
    xf: F64                       #: (6,) [LU, VU] target state
    segments: F64                 #: (S, 7): A (3), B (3) [1/TU], T [TU] per segment (coast: T only)
    nodes: F64 = dataclasses.field(default_factory=lambda: np.zeros((0, NX)))  #: (F, 6) free nodes
    mass0: float = 1.0            #: [-] mass fraction at the start

    def to_c(self) -> object:
        seg = np.ascontiguousarray(self.segments, dtype=np.float64).reshape(-1, NP)
        nodes = np.ascontiguousarray(self.nodes, dtype=np.float64).reshape(-1, NX)
        if seg.shape[0] > MAX_SEGMENTS or nodes.shape[0] > MAX_FREE_NODES:
            raise ValueError(f"at most {MAX_SEGMENTS} segments and {MAX_FREE_NODES} free nodes")
        c = ffi.new("ogk_blt_transfer_t *")
        c.t0 = float(self.t0)
        c.mass0 = float(self.mass0)
        for i in range(NX):
            c.x0[i] = float(self.x0[i])
            c.xf[i] = float(self.xf[i])
        for k in range(seg.shape[0]):
            for p in range(NP):
                c.seg[k][p] = float(seg[k, p])
        for k in range(nodes.shape[0]):
            for i in range(NX):
                c.node[k][i] = float(nodes[k, i])
        return c

    @classmethod
    def from_c(cls, c: object, n_segments: int, n_nodes: int) -> "Transfer":
        seg = np.array([[c.seg[k][p] for p in range(NP)] for k in range(n_segments)])  # type: ignore[attr-defined]
        nodes = np.array([[c.node[k][i] for i in range(NX)] for k in range(n_nodes)]).reshape(-1, NX)  # type: ignore[attr-defined]
        return cls(t0=float(c.t0), x0=np.array(list(c.x0)), xf=np.array(list(c.xf)),  # type: ignore[attr-defined]
                   segments=seg, nodes=nodes, mass0=float(c.mass0))  # type: ignore[attr-defined]


@dataclasses.dataclass(frozen=True)
class BltReport:
    status: str                   #: "OGK_OK" or why the corrector stopped
    flags: int                    #: OGK_BLT_FLAG_*
    iterations: int
    propagations: int
    n_unknowns: int
    n_errors: int
    err_norm0: float              #: |e| of the guess
    err_norm: float               #: |e| of the returned transfer
    err: F64                      #: (n_errors,)
    burn_time: float              #: [TU]
    flight_time: float            #: [TU]
    mass_final: float             #: [-]
    min_distance: F64             #: (2,) [LU] closest approach to the primary, the secondary

    @property
    def converged(self) -> bool:
        return self.status == "OGK_OK"

    def flag_names(self) -> list[str]:
        return [name for name, bit in FLAGS.items() if self.flags & bit]


def _report(status: int, rep: object) -> BltReport:
    ne = int(rep.n_errors)  # type: ignore[attr-defined]
    return BltReport(status=status_name(status), flags=int(rep.flags), iterations=int(rep.iterations),  # type: ignore[attr-defined]
                     propagations=int(rep.propagations), n_unknowns=int(rep.n_unknowns), n_errors=ne,  # type: ignore[attr-defined]
                     err_norm0=float(rep.err_norm0), err_norm=float(rep.err_norm),  # type: ignore[attr-defined]
                     err=np.array([rep.err[i] for i in range(ne)]),  # type: ignore[attr-defined]
                     burn_time=float(rep.burn_time), flight_time=float(rep.flight_time),  # type: ignore[attr-defined]
                     mass_final=float(rep.mass_final),  # type: ignore[attr-defined]
                     min_distance=np.array([rep.min_distance[0], rep.min_distance[1]]))  # type: ignore[attr-defined]


#: statuses that are outcomes of a run, not bad input
_OUTCOMES = ("OGK_OK", "OGK_E_NOT_CONVERGED", "OGK_E_ITER_LIMIT")


class Blt:
    """One ogk_blt_t context (owned by Python, ~46 KiB with the default limits)."""

    def __init__(self, cfg: BltConfig) -> None:
        self.cfg = cfg
        self._ctx = ffi.new("ogk_blt_t *")
        _check(lib.ogk_blt_init(self._ctx, cfg.to_c()), "ogk_blt_init")
        self.n_segments = int(cfg.n_segments)
        self.n_nodes = int(cfg.n_free_nodes)
        self.n_unknowns = int(self._ctx.n_unknowns)
        self.n_errors = int(self._ctx.n_errors)
        self._rep = ffi.new("ogk_blt_report_t *")

    def reset(self) -> None:
        _check(lib.ogk_blt_reset(self._ctx), "ogk_blt_reset")

    def _outcome(self, status: int, fn: str) -> BltReport:
        if status_name(status) not in _OUTCOMES:
            _check(status, fn)
        return _report(status, self._rep)

    def solve(self, guess: Transfer) -> tuple[Transfer, BltReport]:
        g = guess.to_c()
        sol = ffi.new("ogk_blt_transfer_t *")
        st = lib.ogk_blt_solve(self._ctx, g, sol, self._rep)
        rep = self._outcome(st, "ogk_blt_solve")
        return Transfer.from_c(sol, self.n_segments, self.n_nodes), rep

    def evaluate(self, tr: Transfer) -> BltReport:
        return self._outcome(lib.ogk_blt_evaluate(self._ctx, tr.to_c(), self._rep), "ogk_blt_evaluate")

    def propagate(self, tr: Transfer) -> tuple[F64, BltReport]:
        x = ffi.new("ogk_real_t[6]")
        rep = self._outcome(lib.ogk_blt_propagate(self._ctx, tr.to_c(), x, self._rep), "ogk_blt_propagate")
        return np.array(list(x)), rep

    def jacobian(self, tr: Transfer) -> F64:
        """J = de/du (test entry point: kernel/include/ogk/internal/blt_test.h)."""
        n = self.n_errors * self.n_unknowns
        buf = ffi.new(f"ogk_real_t[{n}]")
        _check(lib.ogk_blt_jacobian(self._ctx, tr.to_c(), buf, n), "ogk_blt_jacobian")
        return real_view(buf).reshape(self.n_errors, self.n_unknowns)

    def thrust_cmd(self, t: float) -> ThrustCmd:
        """ogk_blt_thrust_cmd: the held solution's command at t [TU] in the synodic frame;
        KernelError (partial = the safe command) when there is none."""
        return _thrust_cmd_call("ogk_blt_thrust_cmd", self._ctx, t)

    def command(self, t: float) -> tuple[str, bool, F64, int]:
        """(status, engine_on, u_hat, segment) of the held solution at time t [TU]."""
        cmd = ffi.new("ogk_blt_command_t *")
        st = lib.ogk_blt_command(self._ctx, float(t), cmd)
        name = status_name(st)
        if name not in ("OGK_OK", "OGK_E_SAFE_COMMAND", "OGK_E_RANGE"):
            _check(st, "ogk_blt_command")
        return name, bool(cmd.engine_on), np.array(list(cmd.u_hat)), int(cmd.segment)


def unit_direction(segment: ArrayLike, tau: ArrayLike) -> F64:
    """eq. (22): (A + B tau) / |A + B tau| of one segment row (7,) at times tau (n,) -> (n, 3)."""
    p = np.asarray(segment, dtype=np.float64)
    t = np.atleast_1d(np.asarray(tau, dtype=np.float64))
    w = p[None, 0:3] + t[:, None] * p[None, 3:6]
    return w / np.linalg.norm(w, axis=1, keepdims=True)
