"""Loads the compiled cffi extension of the process's precision, with a clear message when it is missing or
of the wrong precision.

The kernel's real type (ogk/real.h) is chosen once per process, before this module is first imported, by
the environment variable ``OGK_PRECISION``: ``double`` (the default, ``ogk_bindings._ogk_cffi``) or
``single`` (the kernel built with OGK_REAL_SINGLE=1, ``ogk_bindings._ogk_cffi_single``: the cdef's
``ogk_real_t`` is float). Both extensions are built by `make ffi` (bindings/build_ffi.py) and by setup.py.
A child process (a campaign's worker pool, a Dask worker) inherits the variable and so loads the same
extension; `ogk mc ... --precision single` sets it before importing anything that imports the bindings.

The wrappers keep numpy float64 on the Python side whatever the precision; the conversion at the kernel
boundary is ogk_bindings._real's (one helper, dtype `REAL`).
"""
from __future__ import annotations

import importlib
import os

#: the environment variable that chooses the precision, and its values (bindings/build_ffi.py's PRECISIONS)
PRECISION_ENV = "OGK_PRECISION"
PRECISIONS = ("double", "single")
#: the extension of each precision
MODULES = {"double": "ogk_bindings._ogk_cffi", "single": "ogk_bindings._ogk_cffi_single"}
#: the size of the real type of each precision, in bytes
BYTES = {"double": 8, "single": 4}


def requested_precision() -> str:
    """The precision the environment asks for (``OGK_PRECISION``, default double); ValueError otherwise."""
    value = os.environ.get(PRECISION_ENV, "").strip().lower() or "double"
    if value not in PRECISIONS:
        raise ValueError(f"{PRECISION_ENV}={os.environ.get(PRECISION_ENV)!r}: expected one of {PRECISIONS}")
    return value


#: this process's precision, fixed at the first import of the bindings
PRECISION = requested_precision()

try:
    _module = importlib.import_module(MODULES[PRECISION])
except ImportError as exc:  # pragma: no cover - depends on the build state
    raise ImportError(
        f"ogk kernel bindings ({PRECISION} precision, {MODULES[PRECISION]}) are not built (or are stale): "
        f"run `make ffi` in the repository root ({exc})"
    ) from exc
ffi = _module.ffi
lib = _module.lib

#: The size of the real type every wrapper passes to the kernel (8: double, 4: float).
REAL_BYTES = BYTES[PRECISION]


def check_real_type() -> None:
    """Refuses a kernel whose real type is not the one this process asked for: a float kernel read as
    double (or the reverse) would take every array as garbage. The library's own answer
    (`ogk_real_bytes`) is checked against the cdef's `ogk_real_t` and the wrappers' REAL_BYTES."""
    answer = ffi.new("uint32_t *")
    status = int(lib.ogk_real_bytes(answer))
    declared = ffi.sizeof("ogk_real_t")
    if status != 0 or int(answer[0]) != declared or declared != REAL_BYTES:
        fix = ("rebuild the extension without OGK_REAL_SINGLE=1 (`make ffi`)" if PRECISION == "double" else
               "rebuild the single extension with OGK_REAL_SINGLE=1 (`make ffi`)")
        raise ImportError(
            f"ogk kernel bindings: the kernel's real type is {int(answer[0])} bytes (ogk_real_bytes, status "
            f"{status}; the cdef's ogk_real_t: {declared}), the bindings ({PRECISION}, {MODULES[PRECISION]}) "
            f"pass {REAL_BYTES}-byte reals: {fix}")


check_real_type()

__all__ = ["PRECISION", "PRECISIONS", "PRECISION_ENV", "REAL_BYTES", "check_real_type", "ffi", "lib",
           "requested_precision"]
