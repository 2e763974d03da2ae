"""Kernel CRC-32 against zlib.crc32 (the same IEEE 802.3 reflected CRC)."""
from __future__ import annotations

import zlib

import numpy as np
import pytest

from ogk_bindings import kernel

pytestmark = pytest.mark.req("OGK-CORE-016")


def test_known_check_value() -> None:
    # The standard CRC-32 check value of "123456789".
    assert kernel.crc32(b"123456789") == 0xCBF43926


def test_empty_is_zero() -> None:
    assert kernel.crc32(b"") == 0
    assert kernel.crc32(b"", 0x12345678) == 0x12345678


@pytest.mark.parametrize("length", [1, 2, 3, 7, 64, 255, 1000, 65537])
def test_random_bytes_vs_zlib(rng: np.random.Generator, length: int) -> None:
    data = rng.integers(0, 256, size=length, dtype=np.uint8).tobytes()
    assert kernel.crc32(data) == zlib.crc32(data)


def test_incremental_update_vs_zlib(rng: np.random.Generator) -> None:
    data = rng.integers(0, 256, size=4097, dtype=np.uint8).tobytes()
    cuts = sorted(rng.integers(0, len(data), size=6))
    crc, start = 0, 0
    for cut in [*cuts, len(data)]:
        crc = kernel.crc32(data[start:cut], crc)
        start = cut
    assert crc == zlib.crc32(data)


def test_numpy_buffer(rng: np.random.Generator) -> None:
    arr = rng.standard_normal(100)
    assert kernel.crc32(arr) == zlib.crc32(arr.tobytes())
