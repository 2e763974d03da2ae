"""The one conversion at the kernel boundary between the Python side's float64 and the kernel's real type.

Every wrapper keeps numpy float64 (and Python float) on its Python side whatever the process's precision
(ogk_bindings._ffi.PRECISION); what it hands to the kernel goes through these helpers:

* `real_in(a)`: a read-only `ogk_real_t[]` over `a` converted to the kernel's dtype (`REAL`; in double a
  float64 contiguous array is passed as it is, without a copy);
* `real_array(shape)` / `real_like(a)`: an output buffer in the kernel's dtype, `real_out(buf)` the
  writable `ogk_real_t[]` over it (refuses any other dtype, so a float64 buffer cannot be handed to a
  float kernel by mistake), and `to_f64(buf)` the float64 result (no copy in double);
* `real_view(cdata, count)`: float64 values of an `ogk_real_t` array inside a kernel struct.

In the double build each of these is what the wrappers did before (the same arrays, no copy), so the
default precision's outputs are unchanged bit for bit.
"""
from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ogk_bindings._ffi import PRECISION, REAL_BYTES, ffi

#: the numpy dtype of the kernel's ogk_real_t in this process
REAL: type[np.floating[Any]] = np.float64 if PRECISION == "double" else np.float32
#: the machine epsilon of the kernel's real type (DBL_EPSILON or FLT_EPSILON)
REAL_EPS = float(np.finfo(REAL).eps)
assert np.dtype(REAL).itemsize == REAL_BYTES

F64 = NDArray[np.float64]

__all__ = ["F64", "REAL", "REAL_EPS", "real_array", "real_in", "real_like", "real_out", "real_view",
           "to_f64", "to_real"]


def to_real(a: ArrayLike) -> NDArray[Any]:
    """`a` as a C-contiguous array of the kernel's dtype (no copy when it already is one)."""
    return np.ascontiguousarray(a, dtype=REAL)


def real_in(a: ArrayLike) -> Any:
    """A read-only ``ogk_real_t[]`` over `a` in the kernel's dtype (the converted array is kept alive by
    the cdata)."""
    return ffi.from_buffer("ogk_real_t[]", to_real(a))


def real_array(shape: int | tuple[int, ...]) -> NDArray[Any]:
    """An uninitialised output buffer of the kernel's dtype."""
    return np.empty(shape, dtype=REAL)


def real_like(a: NDArray[Any]) -> NDArray[Any]:
    """An uninitialised output buffer of the kernel's dtype, of `a`'s shape."""
    return np.empty(np.shape(a), dtype=REAL)


def real_out(buf: NDArray[Any]) -> Any:
    """A writable ``ogk_real_t[]`` over `buf`, which must be a C-contiguous array of the kernel's dtype
    (`real_array`): TypeError for any other, whose memory the kernel would misread."""
    if buf.dtype != REAL or not buf.flags.c_contiguous:
        raise TypeError(f"a kernel output buffer must be C-contiguous {np.dtype(REAL).name}, got "
                        f"{buf.dtype.name}{'' if buf.flags.c_contiguous else ' (not contiguous)'}")
    return ffi.from_buffer("ogk_real_t[]", buf, require_writable=True)


def to_f64(buf: ArrayLike) -> F64:
    """A kernel output as float64 (the same array in double; a converted copy in single)."""
    return np.asarray(buf).astype(np.float64, copy=False)


def real_view(cdata: Any, count: int | None = None) -> F64:
    """float64 copy of the first `count` values (all without) of an ``ogk_real_t`` array in a kernel
    struct (e.g. a plan's states)."""
    values = np.frombuffer(ffi.buffer(cdata), dtype=REAL)
    if count is not None:
        values = values[:count]
    return values.astype(np.float64)
