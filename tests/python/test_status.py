"""Status codes: names from ogk_status_name and their mapping to KernelError."""
from __future__ import annotations

import pytest

from ogk_bindings import kernel
from ogk_bindings._ffi import lib

# The codes of kernel/include/ogk/status.h, written out independently here.
EXPECTED = [
    "OGK_OK", "OGK_E_NULL", "OGK_E_NONFINITE", "OGK_E_DIM", "OGK_E_RANGE",
    "OGK_E_SINGULAR", "OGK_E_ILL_CONDITIONED", "OGK_E_NOT_POSDEF",
    "OGK_E_SWITCH_OVERFLOW", "OGK_E_STEP_LIMIT", "OGK_E_CALLBACK",
    "OGK_E_TABLE_MAGIC", "OGK_E_TABLE_VERSION", "OGK_E_TABLE_TYPE", "OGK_E_TABLE_DIM",
    "OGK_E_TABLE_TRUNCATED", "OGK_E_TABLE_SIZE", "OGK_E_TABLE_CRC", "OGK_E_NOT_INIT",
    "OGK_E_CONFIG", "OGK_E_NOT_CONVERGED", "OGK_E_SAFE_COMMAND", "OGK_E_ALIGN",
    "OGK_E_TABLE_STALE",
    "OGK_E_INFEASIBLE",
    "OGK_E_ITER_LIMIT",
    "OGK_E_FRAME",
    "OGK_E_BYTE_ORDER",
    "OGK_E_OVERFLOW",
]


@pytest.mark.req("OGK-CORE-001")
def test_status_names_match_header() -> None:
    assert int(lib.OGK_STATUS_COUNT) == len(EXPECTED)
    for code, name in enumerate(EXPECTED):
        assert kernel.status_name(code) == name
        assert getattr(lib, name) == code
        assert kernel.Status[name] == code


@pytest.mark.req("OGK-CORE-001")
@pytest.mark.parametrize("code", [-1, len(EXPECTED), 1000])
def test_unknown_status_name(code: int) -> None:
    assert kernel.status_name(code) == "OGK_E_UNKNOWN"


@pytest.mark.req("OGK-CORE-001")
def test_kernel_error_carries_code_and_name() -> None:
    with pytest.raises(kernel.KernelError) as info:
        kernel.interp_locate([0.0, 1.0], 2.0)
    err = info.value
    assert err.code == lib.OGK_E_RANGE
    assert err.name == "OGK_E_RANGE"
    assert err.status is kernel.Status.OGK_E_RANGE
    assert err.func == "ogk_interp_locate"
    assert "OGK_E_RANGE" in str(err)


@pytest.mark.req("OGK-CORE-002")
def test_version_matches_header() -> None:
    v = kernel.version()
    assert v == f"{lib.OGK_VERSION_MAJOR}.{lib.OGK_VERSION_MINOR}.{lib.OGK_VERSION_PATCH}"
