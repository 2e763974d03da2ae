"""Loads the compiled cffi extension, with a clear message when it is missing."""
from __future__ import annotations

try:
    from ogk_bindings._ogk_cffi import ffi, lib  # type: ignore[import-not-found]
except ImportError as exc:  # pragma: no cover - depends on the build state
    raise ImportError(
        "ogk kernel bindings are not built (or are stale): run `make ffi` "
        f"in the repository root ({exc})"
    ) from exc

__all__ = ["ffi", "lib"]
