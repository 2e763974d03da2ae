"""Typed numpy bindings of the ogk C kernel (thin layer over ogk_bindings._ogk_cffi).

Every wrapper converts its inputs to contiguous float64 arrays, calls the one
kernel function, and raises KernelError (status code and name) for any status
other than OGK_OK. Outputs are fresh float64 numpy arrays owned by Python. What
crosses into the kernel is converted to its real type by ogk_bindings._real
(float64 itself in the default double build; float32 in a single-precision
process, ogk_bindings._ffi.PRECISION).
"""
from __future__ import annotations

import enum
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ogk_bindings._ffi import ffi, lib
from ogk_bindings._real import real_array, real_in, real_like, real_out, to_f64

F64 = NDArray[np.float64]

__all__ = [
    "CModel", "Dense", "Frame", "KernelError", "LuFactor", "Rk4Result", "Status", "SwitchEvent",
    "Table", "TableSpec", "TableView", "ThrustCmd", "cholesky_solve", "crc32", "interp_check_grid",
    "interp_linear", "interp_locate", "interp_pchip", "limits", "lstsq", "lu_factor",
    "lu_inverse", "lu_rcond", "lu_solve", "mat_mul", "mat_vec", "minnorm", "pchip_slopes",
    "rk4_propagate", "rk4_step", "status_name", "table_load", "version",
]


# ----------------------------------------------------------------- status and errors
def status_name(code: int) -> str:
    """Identifier of a status code ("OGK_E_DIM", ...); "OGK_E_UNKNOWN" if not a code."""
    if not 0 <= int(code) <= 0xFFFFFFFF:  # not representable as the C enum
        return "OGK_E_UNKNOWN"
    name = ffi.new("const char **")
    lib.ogk_status_name(int(code), name)
    return str(ffi.string(name[0]).decode("ascii"))


Status = enum.IntEnum(  # type: ignore[misc]
    "Status", {status_name(c): c for c in range(int(lib.OGK_STATUS_COUNT))}
)
"""The kernel's ogk_status codes, e.g. Status.OGK_E_TABLE_CRC."""


class KernelError(Exception):
    """A kernel function returned a status other than OGK_OK.

    Attributes: code (int), name ("OGK_E_..."), func (the C function called),
    partial (a partial result where the kernel defines one, else None)."""

    def __init__(self, code: int, func: str, partial: Any = None) -> None:
        self.code = int(code)
        self.name = status_name(self.code)
        self.func = func
        self.partial = partial
        super().__init__(f"{func}: {self.name} ({self.code})")

    def __reduce__(self) -> tuple[Any, ...]:
        # picklable (a worker process's error reaches the parent); a partial result that cannot
        # be pickled (cffi data) is dropped
        import pickle
        partial = self.partial
        try:
            pickle.dumps(partial)
        except Exception:  # noqa: BLE001
            partial = None
        return (type(self), (self.code, self.func, partial))

    @property
    def status(self) -> "Status":
        return Status(self.code)


def _check(status: int, func: str, partial: Any = None) -> None:
    if status != lib.OGK_OK:
        raise KernelError(status, func, partial)


# ----------------------------------------------------------------- the one thrust command of every law
class Frame(enum.IntEnum):
    """Frame of a thrust command's direction (ogk_frame_t, ogk/types.h)."""

    RTN = int(lib.OGK_FRAME_RTN)
    INERTIAL = int(lib.OGK_FRAME_INERTIAL)
    SYNODIC = int(lib.OGK_FRAME_SYNODIC)


@dataclass(frozen=True)
class ThrustCmd:
    """ogk_thrust_cmd_t: what every law's contract call produces (ogk_nog_thrust_cmd,
    ogk_mpsp_thrust_cmd, ogk_nmpc_thrust_cmd, ogk_blt_thrust_cmd). ``u`` is the unit direction in
    ``frame``; in r-t-n ``alpha``, ``beta`` [rad] are the same direction (0 in the other frames).
    ``t`` is in the law's time unit (NOG: s; MPSP, NMPC, BLT: TU)."""

    t: float
    frame: Frame
    u: tuple[float, float, float]
    alpha: float
    beta: float
    throttle: float
    flags: int
    law_flags: int

    @property
    def engine_on(self) -> bool:
        return bool(self.flags & int(lib.OGK_THRUST_FLAG_ENGINE_ON))

    @property
    def safe(self) -> bool:
        return bool(self.flags & int(lib.OGK_THRUST_FLAG_SAFE))

    @classmethod
    def from_c(cls, c: Any) -> "ThrustCmd":
        return cls(t=float(c.t_s), frame=Frame(int(c.frame)), u=(float(c.u[0]), float(c.u[1]), float(c.u[2])),
                   alpha=float(c.alpha_rad), beta=float(c.beta_rad), throttle=float(c.throttle),
                   flags=int(c.flags), law_flags=int(c.law_flags))

    def to_c(self) -> Any:
        c = ffi.new("ogk_thrust_cmd_t *")
        c.t_s = self.t
        c.frame = int(self.frame)
        for i in range(3):
            c.u[i] = self.u[i]
        c.alpha_rad = self.alpha
        c.beta_rad = self.beta
        c.throttle = self.throttle
        c.flags = self.flags
        c.law_flags = self.law_flags
        return c


def _thrust_cmd_call(func: str, ctx: Any, t: float) -> ThrustCmd:
    """One law's contract call ``func(ctx, t, &cmd)``; a rejection raises KernelError with the law's
    safe command as ``partial``."""
    c = ffi.new("ogk_thrust_cmd_t *")
    st = getattr(lib, func)(ctx, float(t), c)
    cmd = ThrustCmd.from_c(c)
    _check(st, func, partial=cmd)
    return cmd


# ----------------------------------------------------------------- helpers
def _f64(a: ArrayLike) -> F64:
    return np.ascontiguousarray(a, dtype=np.float64)


_in = real_in
_out = real_out


def version() -> str:
    """Kernel version string (OGK_VERSION_STRING)."""
    text = ffi.new("const char **")
    _check(lib.ogk_version(text), "ogk_version")
    return str(ffi.string(text[0]).decode("ascii"))


def limits() -> dict[str, int]:
    """Compile-time capacity limits the extension was built with (ogk/config.h)."""
    names = ["OGK_LA_MAX_N", "OGK_LA_MAX_LONG", "OGK_RK4_MAX_STATE", "OGK_RK4_MAX_SWITCHES",
             "OGK_RK4_MAX_STEPS", "OGK_RK4_MAX_BISECTIONS", "OGK_TABLE_MAX_DIMS"]
    return {n: int(getattr(lib, n)) for n in names}


# ----------------------------------------------------------------- CRC-32
def crc32(data: bytes | bytearray | memoryview | NDArray[Any], crc: int = 0) -> int:
    """CRC-32 of data continuing from crc (0 for a new computation), as zlib.crc32."""
    value = ffi.new("uint32_t *", crc)
    buf = ffi.from_buffer("uint8_t[]", data)
    n = len(buf)
    _check(lib.ogk_crc32_update(value, buf if n else ffi.NULL, n), "ogk_crc32_update")
    return int(value[0])


# ----------------------------------------------------------------- tables
@dataclass(frozen=True)
class TableSpec:
    """What the caller expects of a table (ogk_table_spec_t); a dims entry of 0 = any."""

    kind: int
    dims: tuple[int, ...]
    min_grid: int = 1
    max_grid: int = 0xFFFFFFFF

    def to_c(self) -> Any:
        if len(self.dims) > int(lib.OGK_TABLE_MAX_DIMS):
            raise ValueError(f"at most {int(lib.OGK_TABLE_MAX_DIMS)} dims, got {self.dims}")
        spec = ffi.new("ogk_table_spec_t *")
        spec.kind = self.kind
        spec.ndims = len(self.dims)
        for i, d in enumerate(self.dims):
            spec.dims[i] = d
        spec.min_grid = self.min_grid
        spec.max_grid = self.max_grid
        return spec


@dataclass(frozen=True)
class Table:
    """A loaded table: grid (grid_size,) and data (grid_size, *dims)."""

    kind: int
    dims: tuple[int, ...]
    grid: F64
    data: F64


class TableView:
    """A table validated by ogk_table_open; keeps the bytes alive while in use."""

    def __init__(self, buf: bytes | bytearray, spec: TableSpec) -> None:
        self._bytes = bytes(buf)
        self._cbuf = ffi.from_buffer("uint8_t[]", self._bytes)
        self._spec = spec.to_c()
        self._view = ffi.new("ogk_table_view_t *")
        _check(lib.ogk_table_open(self._cbuf, len(self._bytes), self._spec, self._view),
               "ogk_table_open")

    @property
    def kind(self) -> int:
        return int(self._view.kind)

    @property
    def dims(self) -> tuple[int, ...]:
        return tuple(int(self._view.dims[i]) for i in range(int(self._view.ndims)))

    @property
    def grid_size(self) -> int:
        return int(self._view.grid_size)

    @property
    def entry_len(self) -> int:
        return int(self._view.entry_len)

    def grid(self) -> F64:
        out = real_array(self.grid_size)
        _check(lib.ogk_table_read_grid(self._view, _out(out), out.size), "ogk_table_read_grid")
        return to_f64(out)

    def data(self) -> F64:
        out = real_array(self.grid_size * self.entry_len)
        _check(lib.ogk_table_read_data(self._view, _out(out), out.size), "ogk_table_read_data")
        return to_f64(out).reshape((self.grid_size, *self.dims))

    def get(self, k: int, index: int) -> float:
        value = ffi.new("ogk_real_t *")
        _check(lib.ogk_table_get(self._view, k, index, value), "ogk_table_get")
        return float(value[0])


def table_load(buf: bytes | bytearray, spec: TableSpec) -> Table:
    """Validates buf with the kernel loader and copies out grid and data."""
    view = TableView(buf, spec)
    return Table(kind=view.kind, dims=view.dims, grid=view.grid(), data=view.data())


# ----------------------------------------------------------------- interpolation
def _grid_values(grid: ArrayLike, values: ArrayLike) -> tuple[F64, F64, int]:
    g = _f64(grid)
    v = _f64(values)
    if g.ndim != 1 or v.ndim < 1 or v.shape[0] != g.size:
        raise ValueError(f"grid {g.shape} and values {v.shape} do not match")
    m = int(np.prod(v.shape[1:], dtype=np.int64))
    return g, v, m


def interp_check_grid(grid: ArrayLike) -> None:
    g = _f64(grid)
    _check(lib.ogk_interp_check_grid(_in(g), g.size), "ogk_interp_check_grid")


def interp_locate(grid: ArrayLike, tau: float) -> int:
    g = _f64(grid)
    k = ffi.new("size_t *")
    _check(lib.ogk_interp_locate(_in(g), g.size, float(tau), k), "ogk_interp_locate")
    return int(k[0])


def _per_tau(tau: float | ArrayLike, shape: tuple[int, ...], one: Any) -> F64:
    taus = np.asarray(tau, dtype=np.float64)
    out = np.empty(taus.shape + shape)
    if taus.size == 0:
        return out
    flat_out = out.reshape(taus.size, -1)
    for i, t in enumerate(taus.ravel()):
        one(float(t), flat_out[i])
    return out


def interp_linear(grid: ArrayLike, values: ArrayLike, tau: float | ArrayLike) -> F64:
    """Piecewise-linear values at tau: shape tau.shape + values.shape[1:]."""
    g, v, m = _grid_values(grid, values)
    gp, vp = _in(g), _in(v)

    def one(t: float, row: F64) -> None:
        res = real_array(m)
        _check(lib.ogk_interp_linear(gp, g.size, vp, m, t, _out(res)), "ogk_interp_linear")
        row[:] = res

    return _per_tau(tau, v.shape[1:], one)


def pchip_slopes(grid: ArrayLike, values: ArrayLike) -> F64:
    """Pchip node slopes d values / d grid, same shape as values."""
    g, v, m = _grid_values(grid, values)
    out = real_like(v)
    _check(lib.ogk_interp_pchip_slopes(_in(g), g.size, _in(v), m, _out(out)),
           "ogk_interp_pchip_slopes")
    return to_f64(out)


def interp_pchip(grid: ArrayLike, values: ArrayLike, tau: float | ArrayLike,
                 slopes: ArrayLike | None = None) -> F64:
    """Pchip values at tau (slopes computed by the kernel unless given)."""
    g, v, m = _grid_values(grid, values)
    d = pchip_slopes(g, v) if slopes is None else _f64(slopes)
    if d.shape != v.shape:
        raise ValueError(f"slopes {d.shape} do not match values {v.shape}")
    gp, vp, dp = _in(g), _in(v), _in(d)

    def one(t: float, row: F64) -> None:
        res = real_array(m)
        _check(lib.ogk_interp_pchip(gp, g.size, vp, dp, m, t, _out(res)), "ogk_interp_pchip")
        row[:] = res

    return _per_tau(tau, v.shape[1:], one)


# ----------------------------------------------------------------- linear algebra
def _matrix(a: ArrayLike) -> F64:
    m = _f64(a)
    if m.ndim != 2:
        raise ValueError(f"expected a matrix, got shape {m.shape}")
    return m


def _vector(a: ArrayLike, length: int) -> F64:
    """The C side cannot see buffer sizes: every vector length is checked here."""
    v = _f64(a)
    if v.shape != (length,):
        raise ValueError(f"expected a vector of length {length}, got shape {v.shape}")
    return v


def mat_vec(A: ArrayLike, x: ArrayLike) -> F64:
    a = _matrix(A)
    v = _vector(x, a.shape[1])
    y = real_array(a.shape[0])
    _check(lib.ogk_mat_vec(_in(a), a.shape[0], a.shape[1], _in(v), _out(y)), "ogk_mat_vec")
    return to_f64(y)


def mat_mul(A: ArrayLike, B: ArrayLike) -> F64:
    a, b = _matrix(A), _matrix(B)
    if a.shape[1] != b.shape[0]:
        raise ValueError(f"shapes {a.shape} and {b.shape} do not chain")
    c = real_array((a.shape[0], b.shape[1]))
    _check(lib.ogk_mat_mul(_in(a), a.shape[0], a.shape[1], _in(b), b.shape[1], _out(c)),
           "ogk_mat_mul")
    return to_f64(c)


class LuFactor:
    """P A = L U held in a kernel ogk_lu_t (ill-conditioned factors are kept when allowed)."""

    def __init__(self, A: ArrayLike, allow_ill_conditioned: bool = False) -> None:
        a = _matrix(A)
        if a.shape[0] != a.shape[1]:
            raise ValueError(f"LU needs a square matrix, got {a.shape}")
        self._lu = ffi.new("ogk_lu_t *")
        st = lib.ogk_lu_factor(self._lu, _in(a), a.shape[0])
        self.ill_conditioned = st == lib.OGK_E_ILL_CONDITIONED
        if not (self.ill_conditioned and allow_ill_conditioned):
            _check(st, "ogk_lu_factor")

    @property
    def n(self) -> int:
        return int(self._lu.n)

    @property
    def rcond(self) -> float:
        return float(self._lu.rcond)

    @property
    def anorm1(self) -> float:
        return float(self._lu.anorm1)

    def solve(self, b: ArrayLike) -> F64:
        rhs = _f64(b)
        if rhs.shape[0] != self.n:
            raise ValueError(f"b has {rhs.shape[0]} rows, the matrix {self.n}")
        cols = rhs.reshape(self.n, -1).T.copy()
        out = real_like(cols)
        for j in range(cols.shape[0]):
            _check(lib.ogk_lu_solve(self._lu, _in(cols[j]), _out(out[j])), "ogk_lu_solve")
        return to_f64(out).T.reshape(rhs.shape).copy()

    def inverse(self) -> F64:
        out = real_array((self.n, self.n))
        _check(lib.ogk_lu_inverse(self._lu, _out(out)), "ogk_lu_inverse")
        return to_f64(out)


def lu_factor(A: ArrayLike, allow_ill_conditioned: bool = False) -> LuFactor:
    return LuFactor(A, allow_ill_conditioned)


def lu_solve(A: ArrayLike, b: ArrayLike) -> F64:
    """x with A x = b (b a vector or a matrix of right-hand sides)."""
    return LuFactor(A).solve(b)


def lu_inverse(A: ArrayLike) -> F64:
    return LuFactor(A).inverse()


def lu_rcond(A: ArrayLike) -> float:
    """Kernel's reciprocal 1-norm condition estimate (no error when ill-conditioned)."""
    return LuFactor(A, allow_ill_conditioned=True).rcond


def cholesky_solve(A: ArrayLike, b: ArrayLike) -> F64:
    """x with A x = b for symmetric positive definite A (b a vector)."""
    a = _matrix(A)
    rhs = _vector(b, a.shape[0])
    ch = ffi.new("ogk_chol_t *")
    _check(lib.ogk_chol_factor(ch, _in(a), a.shape[0] if a.shape[0] == a.shape[1] else 0),
           "ogk_chol_factor")
    x = real_array(a.shape[0])
    _check(lib.ogk_chol_solve(ch, _in(rhs), _out(x)), "ogk_chol_solve")
    return to_f64(x)


def lstsq(A: ArrayLike, b: ArrayLike) -> F64:
    """argmin |A x - b|_2 for a tall full-column-rank A (m >= n)."""
    a = _matrix(A)
    rhs = _vector(b, a.shape[0])
    ws = ffi.new("ogk_qr_t *")
    x = real_array(a.shape[1])
    _check(lib.ogk_lstsq(ws, _in(a), a.shape[0], a.shape[1], _in(rhs), _out(x)), "ogk_lstsq")
    return to_f64(x)


def minnorm(A: ArrayLike, b: ArrayLike) -> F64:
    """argmin |x|_2 subject to A x = b for a wide full-row-rank A (m <= n)."""
    a = _matrix(A)
    rhs = _vector(b, a.shape[0])
    ws = ffi.new("ogk_qr_t *")
    x = real_array(a.shape[1])
    _check(lib.ogk_minnorm(ws, _in(a), a.shape[0], a.shape[1], _in(rhs), _out(x)),
           "ogk_minnorm")
    return to_f64(x)


# ----------------------------------------------------------------- RK4
@dataclass(frozen=True)
class CModel:
    """A C right-hand side (and optional switching function) with its parameters.

    rhs / switch are cffi function pointers (ffi.addressof(lib, name)); user is
    the cdata of the parameter struct, kept alive by this object."""

    name: str
    n: int
    rhs: Any
    user: Any
    switch: Any = None


@dataclass(frozen=True)
class SwitchEvent:
    t: float            # switching time
    s: float            # S at the accepted point
    mode_after: int     # control mode from t on
    how: int            # OGK_SWITCH_BY_S_TOL or OGK_SWITCH_BY_TIME_TOL
    bisections: int     # bisection iterations used
    dense_index: int    # node of the dense output at t (0 without dense output)

    @property
    def by_time_tol(self) -> bool:
        return self.how == int(lib.OGK_SWITCH_BY_TIME_TOL)


@dataclass(frozen=True)
class Dense:
    """Every integration node, t0 and tf included, each switching point once.
    Node k to node k + 1 is one RK4 step taken in mode[k]."""

    t: F64                   # (K,)
    x: F64                   # (K, n)
    mode: NDArray[np.uint8]  # (K,) mode of the step leaving node k (mode at tf for the last)


@dataclass(frozen=True)
class Rk4Result:
    xf: F64
    t_reached: float
    mode_final: int
    n_steps: int
    n_rhs: int
    switches: tuple[SwitchEvent, ...]
    dense: Dense | None


def _problem(model: CModel, h: float, s_tol: float, t_tol: float) -> Any:
    p = ffi.new("ogk_rk4_problem_t *")
    p.n = model.n
    p.h = h
    p.rhs = model.rhs
    p.sw = ffi.NULL if model.switch is None else model.switch
    p.user = ffi.cast("void *", model.user)
    p.s_tol = s_tol
    p.t_tol = t_tol
    return p


def rk4_step(model: CModel, t: float, x: ArrayLike, dt: float, mode: int = 0) -> F64:
    """One RK4 step of length dt from (t, x) in mode."""
    x0 = _f64(x)
    if x0.shape != (model.n,):
        raise ValueError(f"{model.name}: state must have shape ({model.n},), got {x0.shape}")
    p = _problem(model, 1.0, 0.0, 1.0)  # h and tolerances unused by one step, only validated
    out = real_array(model.n)
    _check(lib.ogk_rk4_step(p, t, _in(x0), dt, mode, _out(out)), "ogk_rk4_step")
    return to_f64(out)


def rk4_propagate(model: CModel, x0: ArrayLike, t0: float, tf: float, h: float,
                  mode0: int = 0, s_tol: float = 1e-12, t_tol: float = 1e-13,
                  dense_capacity: int = 0) -> Rk4Result:
    """Propagates x0 from t0 to tf with fixed step h (ogk_rk4_propagate).

    dense_capacity > 0 asks for the dense grid (capacity nodes). On
    OGK_E_SWITCH_OVERFLOW the raised KernelError carries the partial Rk4Result."""
    x = _f64(x0)
    if x.shape != (model.n,):
        raise ValueError(f"{model.name}: x0 must have shape ({model.n},), got {x.shape}")
    p = _problem(model, h, s_tol, t_tol)
    res = ffi.new("ogk_rk4_result_t *")
    xf = real_array(model.n)
    dense = ffi.NULL
    if dense_capacity > 0:
        dt_buf = real_array(dense_capacity)
        dx_buf = real_array((dense_capacity, model.n))
        dm_buf = np.empty(dense_capacity, dtype=np.uint8)
        dense = ffi.new("ogk_rk4_dense_t *")
        dense.t = _out(dt_buf)
        dense.x = _out(dx_buf)
        dense.mode = ffi.from_buffer("uint8_t[]", dm_buf, require_writable=True)
        dense.capacity = dense_capacity
    st = lib.ogk_rk4_propagate(p, t0, _in(x), mode0, tf, res, _out(xf), dense)
    switches = tuple(
        SwitchEvent(t=float(e.t), s=float(e.s), mode_after=int(e.mode_after), how=int(e.how),
                    bisections=int(e.bisections), dense_index=int(e.dense_index))
        for e in (res.sw[i] for i in range(min(int(res.n_switches),
                                               int(lib.OGK_RK4_MAX_SWITCHES))))
    )
    dense_out = None
    if dense_capacity > 0:
        k = int(dense.count)
        dense_out = Dense(t=to_f64(dt_buf[:k]).copy(), x=to_f64(dx_buf[:k]).copy(), mode=dm_buf[:k].copy())
    result = Rk4Result(xf=to_f64(xf), t_reached=float(res.t_reached), mode_final=int(res.mode_final),
                       n_steps=int(res.n_steps), n_rhs=int(res.n_rhs), switches=switches,
                       dense=dense_out)
    _check(st, "ogk_rk4_propagate", partial=result)
    return result

