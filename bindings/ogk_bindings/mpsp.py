"""Typed bindings of the kernel's MPSP guidance (kernel/include/ogk/mpsp.h, docs/design/mpsp.md).

    cfg = MpspConfig(mu=1.0, t_max=..., c_exhaust=..., t0=0.0, tf=..., x0_nom=..., r_f=..., v_f=...,
                     fourier_order=15, fourier_period=2 * tf, weights_nom=eps0, lambda_m0_nom=lm0,
                     h_max=5e-4 * tf, tol_r=..., tol_v=..., tol_lambda_m=1e-6)
    # (ogk_mpsp_config_default underneath: the algorithm settings' defaults live in C)
    g = Mpsp(cfg)                                   # ogk_mpsp_init (KernelError on a rejected config)
    res = g.solve(x0, thrust_scale=1.0, target=None)  # ogk_mpsp_solve -> MpspResult
    traj = g.propagate(res.weights, res.lambda_m0, x0)  # the kernel's own propagation, dense output
    cmd = g.thrust_cmd(t)                           # the one command of every law (inertial ThrustCmd)

Normalised units throughout (the scenario's LU, TU, MU). The MPSP state is X = [r, v, m, lambda_m];
the weights are three blocks of 2 n + 1 Fourier coefficients (lambda_v x, y, z), basis
h(t) = [1/2, cos th, sin th, ..., cos n th, sin n th], th = 2 pi (t - fourier_t_ref) / fourier_period.
``solve`` returns a result also when MPSP does not converge (``converged`` False, ``status``
OGK_E_NOT_CONVERGED, ``weights`` = the safe command); every other failure raises KernelError.
"""
from __future__ import annotations

import dataclasses
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ogk_bindings._ffi import ffi, lib
from ogk_bindings._real import real_array, real_in, real_out, to_f64, to_real
from ogk_bindings.config import KernelConfig
from ogk_bindings.kernel import Status, ThrustCmd, _check, _thrust_cmd_call

F64 = NDArray[np.float64]

__all__ = ["BASIS_COSINE", "BASIS_FOURIER", "NX", "NY", "MAX_ORDER", "MAX_SWITCHES", "Mpsp",
           "SWEEP_MID2", "SWEEP_RK4", "MpspConfig", "MpspResult", "Trajectory", "fourier_basis", "n_weights", "paper_basis"]

NX: int = int(lib.OGK_MPSP_NX)
"""Size of the MPSP state X = [r, v, m, lambda_m]."""
NY: int = int(lib.OGK_MPSP_NY)
"""Size of the output Y = [r_f, v_f, lambda_mf]."""
MAX_ORDER: int = int(lib.OGK_MPSP_MAX_ORDER)
MAX_SWITCHES: int = int(lib.OGK_MPSP_MAX_SWITCHES)
BASIS_FOURIER: int = int(lib.OGK_MPSP_BASIS_FOURIER)
"""h = [1/2, cos k th, sin k th (k = 1..n)] (eq. C.1)."""
BASIS_COSINE: int = int(lib.OGK_MPSP_BASIS_COSINE)
"""h = [1/2, cos k th (k = 1..2n)]."""
SWEEP_RK4: int = int(lib.OGK_MPSP_SWEEP_RK4)
"""sens_sweep: the exact derivative of the RK4 steps (docs/design/mpsp.md, section 3)."""
SWEEP_MID2: int = int(lib.OGK_MPSP_SWEEP_MID2)
"""sens_sweep: second-order transition at the step midpoints, O(h^2) (docs/design/mpsp.md, section 8)."""
_MAX_WEIGHTS: int = int(lib.OGK_MPSP_MAX_WEIGHTS)
_MAX_NODES: int = int(lib.OGK_MPSP_MAX_NODES)


def n_weights(fourier_order: int) -> int:
    """Number of Fourier weights, 3 (2 n + 1)."""
    return 3 * (2 * int(fourier_order) + 1)


def fourier_basis(t: ArrayLike, fourier_order: int, period: float, t_ref: float,
                  kind: int = BASIS_FOURIER) -> F64:
    """h(t) of the kernel (eq. C.1 with a configurable period), shape (len(t), 2 n + 1)."""
    theta = 2.0 * np.pi * (np.atleast_1d(np.asarray(t, dtype=np.float64)) - t_ref) / period
    order = int(fourier_order)
    h = np.empty((theta.size, 2 * order + 1))
    h[:, 0] = 0.5
    if kind == BASIS_COSINE:
        h[:, 1:] = np.cos(np.outer(theta, np.arange(1, 2 * order + 1)))
        return h
    n = np.arange(1, order + 1)
    h[:, 1::2] = np.cos(np.outer(theta, n))
    h[:, 2::2] = np.sin(np.outer(theta, n))
    return h


def paper_basis(name: str, t0: float, tf: float) -> tuple[int, float, float]:
    """(fourier_kind, fourier_period, fourier_t_ref) of a basis named as in
    host/ogk_host/low_thrust_transfer/fourier.py: cos/sin(k pi eta) with eta mapped linearly from [t0, tf] onto
    "printed" [-pi, pi], "period_tf" [-1, 1], "period_2tf" [-1/2, 1/2], or "cosine_2tf"
    cos(k pi eta), eta in [0, 1], k = 1..2n."""
    span = tf - t0
    mid = 0.5 * (t0 + tf)
    table = {
        "printed": (BASIS_FOURIER, span / np.pi, mid),
        "period_tf": (BASIS_FOURIER, span, mid),
        "period_2tf": (BASIS_FOURIER, 2.0 * span, mid),
        "cosine_2tf": (BASIS_COSINE, 2.0 * span, t0),
    }
    if name not in table:
        raise ValueError(f"unknown basis {name!r}; known: {sorted(table)}")
    kind, period, t_ref = table[name]
    return int(kind), float(period), float(t_ref)


def _vec(a: ArrayLike, n: int, name: str) -> F64:
    v = np.ascontiguousarray(a, dtype=np.float64).reshape(-1)
    if v.size != n:
        raise ValueError(f"{name}: expected {n} values, got {v.size}")
    return v


_buf = real_in
_out = real_out


class MpspConfig(KernelConfig):
    """ogk_mpsp_config_t (normalised units; see kernel/include/ogk/mpsp.h for each field).

    Starts from ogk_mpsp_config_default -- the paper's algorithm settings (delta_max 1,
    delta_tau_0 0.5, delta_tau_min 0.1, R_eps = I, R_lambda 1, s_tol 1e-12, max_newton 100,
    max_outer 50, N_seg,tol 0 step 2, n_seg_nom 0 = counted at init) live in C only -- and sets
    any field by its C name (unknown name: TypeError). The mission data (mu, t_max, c_exhaust,
    t0, tf, x0_nom, r_f, v_f, fourier_order, fourier_period, weights_nom, lambda_m0_nom, h_max,
    tol_r, tol_v, tol_lambda_m) must be given. ``weights_nom`` and ``r_eps`` take (and read back)
    their first n_weights = 3 (2 n + 1) entries; ``r_eps=None`` keeps the identity."""

    _ctype = "ogk_mpsp_config_t"
    _default_fn = "ogk_mpsp_config_default"
    _REQUIRED = ("mu", "t_max", "c_exhaust", "t0", "tf", "x0_nom", "r_f", "v_f", "fourier_order",
                 "fourier_period", "weights_nom", "lambda_m0_nom", "h_max", "tol_r", "tol_v",
                 "tol_lambda_m")

    def __init__(self, **fields: Any) -> None:
        missing = [name for name in self._REQUIRED if name not in fields]
        if missing:
            raise TypeError(f"MpspConfig: mission data missing: {', '.join(missing)}")
        if fields.get("r_eps", 0) is None:
            del fields["r_eps"]
        order = int(fields["fourier_order"])
        if not 1 <= order <= MAX_ORDER:
            raise ValueError(f"fourier_order must be in 1..{MAX_ORDER}")
        nw = n_weights(order)
        for name in ("weights_nom", "r_eps"):
            if name in fields:
                fields[name] = _vec(fields[name], nw, name)
        fields["x0_nom"] = _vec(fields["x0_nom"], 7, "x0_nom")
        fields["r_f"] = _vec(fields["r_f"], 3, "r_f")
        fields["v_f"] = _vec(fields["v_f"], 3, "v_f")
        super().__init__(**fields)

    def _validate(self) -> None:
        if not 1 <= int(self._c.fourier_order) <= MAX_ORDER:
            raise ValueError(f"fourier_order must be in 1..{MAX_ORDER}")

    def _array_lengths(self) -> dict[str, int]:
        nw = n_weights(int(self._c.fourier_order))
        return {"weights_nom": nw, "r_eps": nw}


@dataclasses.dataclass(frozen=True)
class MpspResult:
    """ogk_mpsp_result_t of one ogk_mpsp_solve."""

    status: Status
    converged: bool
    newton_iterations: int       #: evaluations of eq. (45) (the paper's NI)
    inner_loops: int
    outer_steps: int             #: continuation inner loops (Algorithm 2)
    n_seg_tol: int
    tau_reached: float
    dy: F64                      #: Y(tf) - Y_d with the returned weights
    err_r: float                 #: [LU]
    err_v: float                 #: [LU/TU]
    lambda_mf: float
    m_f: float                   #: [MU]
    n_segments: int
    n_thrust_arcs: int
    switch_times: F64            #: [TU]
    weights: F64                 #: the command (safe command when not converged)
    lambda_m0: float
    dy_norm_log: F64             #: ||Delta Y|| before each Newton step


@dataclasses.dataclass(frozen=True)
class Trajectory:
    """Dense output of one ogk_mpsp_propagate: nodes of the RK4 grid and every switch node."""

    t: F64                       #: [TU] (n,)
    x: F64                       #: (n, 8): r, v, m, lambda_m
    mode: NDArray[np.uint8]      #: u of the step leaving each node
    switch_times: F64            #: [TU]
    n_segments: int
    n_thrust_arcs: int
    x_f: F64                     #: X(tf)


class Mpsp:
    """One MPSP guidance context (ogk_mpsp_t, 187 KiB, allocated by cffi)."""

    def __init__(self, cfg: MpspConfig) -> None:
        self.cfg = cfg
        self._c_cfg = cfg.to_c()
        self._ctx = ffi.new("ogk_mpsp_t *")
        _check(lib.ogk_mpsp_init(self._ctx, self._c_cfg), "ogk_mpsp_init")

    def reset(self) -> None:
        """ogk_mpsp_reset: back to the just-initialised state, configuration kept."""
        _check(lib.ogk_mpsp_reset(self._ctx), "ogk_mpsp_reset")

    @property
    def n_weights(self) -> int:
        return int(self._ctx.n_weights)

    @property
    def n_seg_nom(self) -> int:
        """N_seg,nom in use (counted at init when the config gave 0)."""
        return int(self._ctx.n_seg_nom)

    def solve(self, x0: ArrayLike, thrust_scale: float = 1.0,
              target: ArrayLike | None = None) -> MpspResult:
        """ogk_mpsp_solve from the nominal weights; target = [r_f, v_f] or None (configured)."""
        x = _vec(x0, 7, "x0")
        res = ffi.new("ogk_mpsp_result_t *")
        tgt = ffi.NULL if target is None else _buf(_vec(target, 6, "target"))
        st = int(lib.ogk_mpsp_solve(self._ctx, _buf(x), float(thrust_scale), tgt, res))
        if st not in (int(lib.OGK_OK), int(lib.OGK_E_NOT_CONVERGED)):
            _check(st, "ogk_mpsp_solve")
        nw = int(res.n_weights)
        return MpspResult(
            status=Status(st), converged=bool(res.converged),
            newton_iterations=int(res.newton_iterations), inner_loops=int(res.inner_loops),
            outer_steps=int(res.outer_steps), n_seg_tol=int(res.n_seg_tol),
            tau_reached=float(res.tau_reached), dy=np.array(list(res.dy)),
            err_r=float(res.err_r), err_v=float(res.err_v), lambda_mf=float(res.lambda_mf),
            m_f=float(res.m_f), n_segments=int(res.n_segments),
            n_thrust_arcs=int(res.n_thrust_arcs),
            switch_times=np.array(list(res.t_switch)[:min(int(res.n_switches), MAX_SWITCHES)]),
            weights=np.array(list(res.weights)[:nw]), lambda_m0=float(res.lambda_m0),
            dy_norm_log=np.array(list(res.dy_norm_log)[:int(res.n_log)]),
        )

    def propagate(self, weights: ArrayLike, lambda_m0: float, x0: ArrayLike,
                  thrust_scale: float = 1.0) -> Trajectory:
        """ogk_mpsp_propagate, then the dense trajectory (ogk_mpsp_trajectory)."""
        w = _vec(weights, self.n_weights, "weights")
        x = _vec(x0, 7, "x0")
        prop = ffi.new("ogk_mpsp_prop_t *")
        _check(lib.ogk_mpsp_propagate(self._ctx, _buf(w), float(lambda_m0), _buf(x),
                                      float(thrust_scale), prop), "ogk_mpsp_propagate")
        n = int(prop.n_nodes)
        t = real_array(n)
        xs = real_array((n, NX))
        mode = np.empty(n, dtype=np.uint8)
        count = ffi.new("size_t *")
        _check(lib.ogk_mpsp_trajectory(self._ctx, _out(t), _out(xs.reshape(-1)),
                                       ffi.from_buffer("uint8_t[]", mode, require_writable=True),
                                       n, count), "ogk_mpsp_trajectory")
        return Trajectory(t=to_f64(t), x=to_f64(xs), mode=mode,
                          switch_times=np.array(list(prop.t_switch)[:int(prop.n_switches)]),
                          n_segments=int(prop.n_segments), n_thrust_arcs=int(prop.n_thrust_arcs),
                          x_f=np.array(list(prop.x_f)))

    def state_at(self, t: ArrayLike) -> F64:
        """X at each t of the trajectory held (pchip inside a segment), shape (len(t), 8)."""
        ts = np.atleast_1d(np.asarray(t, dtype=np.float64))
        out = real_array((ts.size, NX))
        for i, ti in enumerate(ts):
            _check(lib.ogk_mpsp_state_at(self._ctx, float(ti), _out(out[i])), "ogk_mpsp_state_at")
        return to_f64(out)

    def control(self, weights: ArrayLike, t: ArrayLike) -> tuple[F64, F64]:
        """lambda_v(t) and its time derivative, each shape (len(t), 3)."""
        w = _vec(weights, self.n_weights, "weights")
        ts = np.atleast_1d(np.asarray(t, dtype=np.float64))
        lv = real_array((ts.size, 3))
        lvd = real_array((ts.size, 3))
        for i, ti in enumerate(ts):
            _check(lib.ogk_mpsp_control(self._ctx, _buf(w), float(ti), _out(lv[i]), _out(lvd[i])),
                   "ogk_mpsp_control")
        return to_f64(lv), to_f64(lvd)

    def sensitivity(self) -> tuple[F64, F64]:
        """dY/dW (7 x n_weights) and dY/dlambda_m0 (7) of the trajectory held."""
        dydw = real_array((NY, self.n_weights))
        dydl = real_array(NY)
        _check(lib.ogk_mpsp_sensitivity(self._ctx, _out(dydw.reshape(-1)), _out(dydl)),
               "ogk_mpsp_sensitivity")
        return to_f64(dydw), to_f64(dydl)

    def newton_update(self, dy: ArrayLike, weights: ArrayLike,
                      lambda_m0: float) -> tuple[F64, float]:
        """Eqs. (44)-(46) from the sensitivities held: the updated (weights, lambda_m0)."""
        w = to_real(_vec(weights, self.n_weights, "weights")).copy()
        lm = ffi.new("ogk_real_t *", float(lambda_m0))
        _check(lib.ogk_mpsp_newton_update(self._ctx, _buf(_vec(dy, NY, "dy")), _out(w), lm),
               "ogk_mpsp_newton_update")
        return to_f64(w), float(lm[0])

    def thrust_cmd(self, t: float) -> ThrustCmd:
        """ogk_mpsp_thrust_cmd: the held trajectory's command at t [TU], inertial: the primer
        direction -lambda_v / |lambda_v|, the bang-off-bang throttle; KernelError (partial = the
        safe command) without a trajectory, outside [t0, tf] or without a direction."""
        return _thrust_cmd_call("ogk_mpsp_thrust_cmd", self._ctx, t)

    def step_jacobian(self, weights: ArrayLike, t: float, x: ArrayLike, dt: float, mode: int,
                      thrust_scale: float = 1.0) -> tuple[F64, F64, F64]:
        """One RK4 step: (x_next, dX_next/dX (8 x 8), dX_next/dW (8 x n_weights)). Test entry point
        (kernel/include/ogk/internal/mpsp_test.h, not flight API)."""
        w = _vec(weights, self.n_weights, "weights")
        xn = real_array(NX)
        jx = real_array((NX, NX))
        jw = real_array((NX, self.n_weights))
        _check(lib.ogk_mpsp_step_jacobian(self._ctx, _buf(w), float(thrust_scale), float(t),
                                          _buf(_vec(x, NX, "x")), float(dt), int(mode), _out(xn),
                                          _out(jx.reshape(-1)), _out(jw.reshape(-1))),
               "ogk_mpsp_step_jacobian")
        return to_f64(xn), to_f64(jx), to_f64(jw)
