"""Loads the compiled cffi extension, with a clear message when it is missing or of the wrong precision."""
from __future__ import annotations

try:
    from ogk_bindings._ogk_cffi import ffi, lib  # type: ignore[import-not-found]
except ImportError as exc:  # pragma: no cover - depends on the build state
    raise ImportError(
        "ogk kernel bindings are not built (or are stale): run `make ffi` "
        f"in the repository root ({exc})"
    ) from exc

#: The size of the real type every wrapper passes (numpy float64 arrays through `double[]`).
REAL_BYTES = 8


def check_real_type() -> None:
    """Refuses a kernel whose real type is not the bindings' double: one built with OGK_REAL_SINGLE=1
    (ogk/real.h), whose every `ogk_real_t` is a float, would read the float64 arrays as garbage. The
    library's own answer (`ogk_real_bytes`) is checked against the cdef's `ogk_real_t` and the wrappers'."""
    answer = ffi.new("uint32_t *")
    status = int(lib.ogk_real_bytes(answer))
    declared = ffi.sizeof("ogk_real_t")
    if status != 0 or int(answer[0]) != declared or declared != REAL_BYTES:
        raise ImportError(
            f"ogk kernel bindings: the kernel's real type is {int(answer[0])} bytes (ogk_real_bytes, status "
            f"{status}; the cdef's ogk_real_t: {declared}), the bindings pass {REAL_BYTES}-byte doubles: "
            "rebuild the extension without OGK_REAL_SINGLE=1 (`make ffi`)")


check_real_type()

__all__ = ["REAL_BYTES", "check_real_type", "ffi", "lib"]
