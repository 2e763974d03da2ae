"""The family's C batch loops (csrc/*.c: the kernel's step functions over many runs in one call),
from the family's own cffi extension (built by ogk/missions/build_csrc.py, `make ffi`): `lib` has
the ogk_sil_* functions and the OGK_SIL_* constants; the kernel's own functions, types and
constants stay ogk_bindings' (the extension shares its types, so its contexts are passed as they
are)."""
from __future__ import annotations

try:
    from ._csrc_cffi import ffi, lib  # type: ignore[import-not-found]
except ImportError as exc:  # pragma: no cover - depends on the build state
    raise ImportError("the orbit-injection batch loops are not built (or are stale): run "
                      f"`make ffi` in the repository root ({exc})") from exc

__all__ = ["ffi", "lib"]
