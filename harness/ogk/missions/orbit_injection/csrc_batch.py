"""The family's C batch loops (csrc/*.c: the kernel's step functions over many runs in one call),
from the family's own cffi extension (built by ogk/missions/build_csrc.py, `make ffi`): `lib` has
the ogk_sil_* functions and the OGK_SIL_* constants; the kernel's own functions, types and
constants stay ogk_bindings' (the extension shares its types, so its contexts are passed as they
are)."""
from __future__ import annotations

import importlib

from ogk_bindings._ffi import PRECISION

#: the extension of the process's precision (ogk_bindings._ffi.PRECISION): _csrc_cffi (double) or
#: _csrc_cffi_single (on the float kernel's extension); its loops take double arrays either way and
#: convert at the kernel's calls (csrc/nav_batch.c)
MODULE = f"{__package__}._csrc_cffi{'' if PRECISION == 'double' else '_' + PRECISION}"

try:
    _module = importlib.import_module(MODULE)
except ImportError as exc:  # pragma: no cover - depends on the build state
    raise ImportError(f"the orbit-injection batch loops ({PRECISION} precision) are not built (or are stale): "
                      f"run `make ffi` in the repository root ({exc})") from exc
ffi = _module.ffi
lib = _module.lib

__all__ = ["MODULE", "ffi", "lib"]
