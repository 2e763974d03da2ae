"""The kernel's real type (kernel/include/ogk/real.h) as the Python side sees it: the default build's
double reaches the bindings' cdef as `double`, the library says so at run time (ogk_real_bytes), and a
library built with OGK_REAL_SINGLE=1 is refused at import instead of being handed float64 arrays."""
from __future__ import annotations

import importlib.util
from pathlib import Path
from types import ModuleType
from typing import Any

import pytest

from ogk_bindings import _ffi
from ogk_bindings._ffi import ffi, lib

ROOT = Path(__file__).resolve().parents[2]

pytestmark = pytest.mark.req("OGK-CORE-028")


def test_the_default_build_is_double_everywhere() -> None:
    answer = ffi.new("uint32_t *")
    assert lib.ogk_real_bytes(answer) == lib.OGK_OK
    assert answer[0] == 8 == ffi.sizeof("ogk_real_t") == ffi.sizeof("double")
    assert ffi.typeof("ogk_real_t") is ffi.typeof("double")
    assert lib.OGK_REAL_SINGLE == 0 and lib.OGK_TABLE_REAL == lib.OGK_TABLE_F64
    assert lib.OGK_REAL_EPSILON == 2.0 ** -52 and lib.OGK_REAL_TINY == 1.0e-300
    assert lib.ogk_real_bytes(ffi.NULL) == lib.OGK_E_NULL
    # the cdef comes from the headers: the typedef as the default build compiles it
    build_ffi = _build_ffi()
    assert "typedef double ogk_real_t;" in build_ffi.declarations(build_ffi.bound_headers())


def _build_ffi() -> ModuleType:
    spec = importlib.util.spec_from_file_location("build_ffi", ROOT / "bindings" / "build_ffi.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


class _SingleLib:
    """A library that answers as a kernel built with OGK_REAL_SINGLE=1 would."""

    def ogk_real_bytes(self, out: Any) -> int:
        out[0] = 4
        return 0


def test_a_single_precision_library_is_refused(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(_ffi, "lib", _SingleLib())
    with pytest.raises(ImportError, match="OGK_REAL_SINGLE=1"):
        _ffi.check_real_type()
