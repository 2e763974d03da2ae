"""Table files: host writer -> kernel loader round trip, and every corruption
rejected by the kernel with its specific status code (kernel/include/ogk/table.h).
The pure-Python reader is checked against the same cases."""
from __future__ import annotations

import dataclasses
import struct
import zlib
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from ogk_bindings import kernel
from ogk_bindings._ffi import lib
from ogk_host import tablefile as tf

KIND = 0x4E4F4701  # an arbitrary application kind
DIMS = (3, 2)
GRID_SIZE = 11


@pytest.fixture
def table(rng: np.random.Generator) -> tuple[np.ndarray, np.ndarray, bytes]:
    grid = np.linspace(0.0, 1.0, GRID_SIZE)
    data = rng.standard_normal((GRID_SIZE, *DIMS)) * 10.0 ** rng.integers(-5, 5, (GRID_SIZE, *DIMS))
    return grid, data, tf.encode_table(KIND, grid, data)


def spec(**changes: Any) -> kernel.TableSpec:
    base = kernel.TableSpec(kind=KIND, dims=DIMS, min_grid=1, max_grid=1000)
    return dataclasses.replace(base, **changes)


def reheader(blob: bytes, fix_crc: bool = True, **changes: Any) -> bytes:
    """blob with header fields changed; header CRC recomputed unless fix_crc is False."""
    hdr, crc = tf.TableHeader.unpack(blob)
    new = dataclasses.replace(hdr, **changes)
    return new.pack(None if fix_crc else crc) + blob[tf.HEADER_SIZE:]


def expect_code(blob: bytes, code: int, s: kernel.TableSpec | None = None) -> None:
    with pytest.raises(kernel.KernelError) as info:
        kernel.table_load(blob, s or spec())
    assert info.value.code == code, f"got {info.value.name}"


# ----------------------------------------------------------------- format layout
@pytest.mark.req("OGK-CORE-017")
def test_header_layout_by_hand(table: tuple[np.ndarray, np.ndarray, bytes]) -> None:
    """Decode the header with explicit offsets (independent of the writer's struct)."""
    grid, data, blob = table
    u16 = lambda off: int.from_bytes(blob[off:off + 2], "little")  # noqa: E731
    u32 = lambda off: int.from_bytes(blob[off:off + 4], "little")  # noqa: E731
    assert blob[0:4] == b"OGKT"
    assert (u16(4), u16(6), u32(8), u16(12), u16(14)) == (1, 1, KIND, 2, 0)
    assert [u32(16 + 4 * i) for i in range(4)] == [3, 2, 0, 0]
    assert u32(32) == GRID_SIZE
    assert u32(36) == 8 * GRID_SIZE * (1 + 6) == len(blob) - 48
    assert u32(40) == zlib.crc32(blob[48:])
    assert u32(44) == zlib.crc32(blob[:44])
    payload = np.frombuffer(blob[48:], dtype="<f8")
    assert np.array_equal(payload[:GRID_SIZE], grid)
    assert np.array_equal(payload[GRID_SIZE:], data.ravel())


# ----------------------------------------------------------------- round trips
@pytest.mark.req("OGK-CORE-017")
def test_kernel_round_trip_is_bit_exact(table: tuple[np.ndarray, np.ndarray, bytes]) -> None:
    grid, data, blob = table
    loaded = kernel.table_load(blob, spec())
    assert loaded.kind == KIND and loaded.dims == DIMS
    assert np.array_equal(loaded.grid, grid)
    assert np.array_equal(loaded.data, data)


@pytest.mark.req("OGK-CORE-017")
def test_kernel_accepts_wildcard_dims(table: tuple[np.ndarray, np.ndarray, bytes]) -> None:
    _, data, blob = table
    loaded = kernel.table_load(blob, spec(dims=(0, 0)))
    assert np.array_equal(loaded.data, data)


@pytest.mark.req("OGK-CORE-017")
def test_kernel_get_single_values(table: tuple[np.ndarray, np.ndarray, bytes]) -> None:
    _, data, blob = table
    view = kernel.TableView(blob, spec())
    flat = data.reshape(GRID_SIZE, -1)
    for k in (0, 5, GRID_SIZE - 1):
        for idx in range(flat.shape[1]):
            assert view.get(k, idx) == flat[k, idx]
    for k, idx in [(GRID_SIZE, 0), (0, flat.shape[1])]:
        with pytest.raises(kernel.KernelError) as info:
            view.get(k, idx)
        assert info.value.code == lib.OGK_E_RANGE


@pytest.mark.req("OGK-CORE-017")
@pytest.mark.parametrize("shape", [(1, 1), (5, 7), (4, 2, 3), (3, 1, 2, 3, 2)])
def test_round_trip_shapes(rng: np.random.Generator, shape: tuple[int, ...]) -> None:
    grid = np.cumsum(rng.uniform(0.1, 1.0, shape[0]))
    data = rng.standard_normal(shape)
    blob = tf.encode_table(9, grid, data)
    loaded = kernel.table_load(blob, kernel.TableSpec(kind=9, dims=shape[1:]))
    assert np.array_equal(loaded.grid, grid) and np.array_equal(loaded.data, data)
    py = tf.decode_table(blob, kind=9)
    assert np.array_equal(py.grid, grid) and np.array_equal(py.data, data)
    assert py.dims == shape[1:]


@pytest.mark.req("OGK-CORE-017")
def test_file_write_read(tmp_path: Path, table: tuple[np.ndarray, np.ndarray, bytes]) -> None:
    grid, data, blob = table
    path = tmp_path / "gains.ogkt"
    assert tf.write_table(path, KIND, grid, data) == len(blob)
    assert path.read_bytes() == blob
    back = tf.read_table(path, kind=KIND)
    assert np.array_equal(back.grid, grid) and np.array_equal(back.data, data)


# ----------------------------------------------------------------- corruptions
@pytest.mark.req("OGK-CORE-017")
def test_payload_byte_flip_is_crc(table: tuple[np.ndarray, np.ndarray, bytes]) -> None:
    _, _, blob = table
    for off in (48, 48 + 8 * GRID_SIZE + 17, len(blob) - 8):  # low mantissa bytes
        bad = bytearray(blob)
        bad[off] ^= 0x01
        expect_code(bytes(bad), lib.OGK_E_TABLE_CRC)


@pytest.mark.req("OGK-CORE-017")
@pytest.mark.parametrize("offset", [4, 6, 8, 12, 14, 16, 20, 32, 36, 40, 44, 47])
def test_header_byte_flip_is_crc(table: tuple[np.ndarray, np.ndarray, bytes],
                                 offset: int) -> None:
    _, _, blob = table
    bad = bytearray(blob)
    bad[offset] ^= 0x04
    expect_code(bytes(bad), lib.OGK_E_TABLE_CRC)


@pytest.mark.req("OGK-CORE-017")
@pytest.mark.parametrize("fix_crc", [True, False])
def test_bad_magic(table: tuple[np.ndarray, np.ndarray, bytes], fix_crc: bool) -> None:
    _, _, blob = table
    expect_code(reheader(blob, fix_crc=fix_crc, magic=b"OGKX"), lib.OGK_E_TABLE_MAGIC)
    expect_code(b"PNG\x00" + blob[4:20], lib.OGK_E_TABLE_MAGIC)  # short and wrong


@pytest.mark.req("OGK-CORE-017")
def test_bad_version(table: tuple[np.ndarray, np.ndarray, bytes]) -> None:
    _, _, blob = table
    for v in (0, 2, 0x0100):
        expect_code(reheader(blob, version=v), lib.OGK_E_TABLE_VERSION)


@pytest.mark.req("OGK-CORE-017")
def test_bad_element_type_or_kind(table: tuple[np.ndarray, np.ndarray, bytes]) -> None:
    _, _, blob = table
    expect_code(reheader(blob, elem_type=2), lib.OGK_E_TABLE_TYPE)
    expect_code(blob, lib.OGK_E_TABLE_TYPE, spec(kind=KIND + 1))


@pytest.mark.req("OGK-CORE-017")
def test_nonzero_reserved_rejected(table: tuple[np.ndarray, np.ndarray, bytes]) -> None:
    _, _, blob = table
    with pytest.raises(kernel.KernelError):
        kernel.table_load(reheader(blob, reserved=1), spec())


@pytest.mark.req("OGK-CORE-017")
@pytest.mark.parametrize("changes", [
    {"dims": (3, 3)}, {"dims": (2, 2)}, {"dims": (6,)}, {"dims": (3, 2, 1)},
    {"min_grid": GRID_SIZE + 1}, {"max_grid": GRID_SIZE - 1},
])
def test_wrong_expected_dims(table: tuple[np.ndarray, np.ndarray, bytes],
                             changes: dict[str, Any]) -> None:
    _, _, blob = table
    expect_code(blob, lib.OGK_E_TABLE_DIM, spec(**changes))


@pytest.mark.req("OGK-CORE-017")
def test_inconsistent_header_dims(table: tuple[np.ndarray, np.ndarray, bytes]) -> None:
    _, _, blob = table
    expect_code(reheader(blob, ndims=0), lib.OGK_E_TABLE_DIM, spec(dims=()))
    expect_code(reheader(blob, ndims=5), lib.OGK_E_TABLE_DIM)
    expect_code(reheader(blob, dims=(3, 2, 0, 4)), lib.OGK_E_TABLE_DIM)  # beyond ndims
    expect_code(reheader(blob, dims=(3, 0, 0, 0)), lib.OGK_E_TABLE_DIM, spec(dims=(0, 0)))
    expect_code(reheader(blob, grid_size=0), lib.OGK_E_TABLE_DIM, spec(min_grid=0))


@pytest.mark.req("OGK-CORE-017")
@pytest.mark.parametrize("keep", [0, 1, 10, 47, 48, 100, -1])
def test_truncated(table: tuple[np.ndarray, np.ndarray, bytes], keep: int) -> None:
    _, _, blob = table
    short = blob[:keep] if keep >= 0 else blob[:len(blob) + keep]
    expect_code(short, lib.OGK_E_TABLE_TRUNCATED)


@pytest.mark.req("OGK-CORE-017")
def test_too_long_or_size_field_wrong(table: tuple[np.ndarray, np.ndarray, bytes]) -> None:
    _, _, blob = table
    expect_code(blob + b"\x00", lib.OGK_E_TABLE_SIZE)
    hdr, _ = tf.TableHeader.unpack(blob)
    expect_code(reheader(blob, payload_bytes=hdr.payload_bytes - 8), lib.OGK_E_TABLE_SIZE)
    expect_code(reheader(blob, payload_bytes=hdr.payload_bytes + 8), lib.OGK_E_TABLE_SIZE)


@pytest.mark.req("OGK-CORE-017")
def test_nonfinite_value_with_valid_crcs(table: tuple[np.ndarray, np.ndarray, bytes]) -> None:
    _, _, blob = table
    for bad_value in (np.nan, np.inf):
        payload = bytearray(blob[48:])
        payload[8 * (GRID_SIZE + 4):8 * (GRID_SIZE + 5)] = struct.pack("<d", bad_value)
        hdr, _ = tf.TableHeader.unpack(blob)
        hdr = dataclasses.replace(hdr, payload_crc=zlib.crc32(payload))
        bad = hdr.pack() + bytes(payload)
        expect_code(bad, lib.OGK_E_NONFINITE)
        with pytest.raises(tf.TableFormatError):
            tf.decode_table(bad)


# ----------------------------------------------------------------- precision of the elements
@pytest.mark.req("OGK-CORE-028", "OGK-HAR-008")
def test_f32_table_header_payload_and_crc_by_hand(table: tuple[np.ndarray, np.ndarray, bytes]) -> None:
    """precision="single" writes an F32 table (kernel/include/ogk/table.h: element type 2, 4 bytes a
    value), checked here with explicit offsets, struct's own binary32 packing and zlib, not the writer's
    code; the double kernel refuses it (OGK_E_TABLE_TYPE), as a kernel refuses the other build's table."""
    grid, data, f64_blob = table
    blob = tf.encode_table(KIND, grid, data, precision="single")
    u16 = lambda off: int.from_bytes(blob[off:off + 2], "little")  # noqa: E731
    u32 = lambda off: int.from_bytes(blob[off:off + 4], "little")  # noqa: E731
    values = np.concatenate([grid, data.ravel()])
    assert blob[0:4] == b"OGKT"
    assert (u16(4), u16(6), u32(8), u16(12), u16(14)) == (1, 2, KIND, 2, 0)
    assert [u32(16 + 4 * i) for i in range(4)] == [3, 2, 0, 0]
    assert u32(32) == GRID_SIZE
    assert u32(36) == 4 * GRID_SIZE * (1 + 6) == 4 * values.size == len(blob) - 48
    assert u32(40) == zlib.crc32(blob[48:])
    assert u32(44) == zlib.crc32(blob[:44])
    # grid then the rows, each value the nearest binary32, little-endian
    assert blob[48:] == struct.pack(f"<{values.size}f", *values)
    expect_code(blob, lib.OGK_E_TABLE_TYPE)
    assert lib.OGK_TABLE_REAL == lib.OGK_TABLE_F64 == tf.ELEM_F64
    assert lib.OGK_TABLE_F32 == tf.ELEM_F32
    # the pure-Python reader reads either (float64 arrays), or only one build's when asked
    back = tf.decode_table(blob, KIND)
    assert back.elem_type == tf.ELEM_F32
    np.testing.assert_array_equal(back.data, data.astype(np.float32).astype(np.float64))
    np.testing.assert_array_equal(back.grid, grid.astype(np.float32).astype(np.float64))
    assert tf.decode_table(blob, KIND, precision="single").elem_type == tf.ELEM_F32
    with pytest.raises(tf.TableFormatError, match="element type 2"):
        tf.decode_table(blob, KIND, precision="double")
    with pytest.raises(tf.TableFormatError, match="element type 1"):
        tf.decode_table(f64_blob, KIND, precision="single")


@pytest.mark.req("OGK-CORE-028", "OGK-HAR-008")
def test_default_precision_writes_the_f64_file_of_before() -> None:
    """The precision parameter's default is the F64 file, byte for byte what the writer wrote before it
    had the parameter (the CRC of this file recorded then), so every existing table and its CRCs stay."""
    grid, data = [0.0, 0.5, 1.0], np.array([[1.0, -2.5], [3.0, 0.1], [1e-3, 7.0]])
    blob = tf.encode_table(0x4E4F4701, grid, data)
    assert (len(blob), zlib.crc32(blob)) == (120, 0xD92635EF)
    assert tf.encode_table(0x4E4F4701, grid, data, precision="double") == blob
    assert tf.decode_table(blob).elem_type == tf.ELEM_F64


@pytest.mark.req("OGK-HAR-008")
def test_f32_writer_refuses_what_binary32_cannot_hold() -> None:
    with pytest.raises(tf.TableFormatError, match="range of single"):
        tf.encode_table(KIND, [0.0, 1.0], [[1.0], [1e39]], precision="single")
    with pytest.raises(tf.TableFormatError, match="precision 'half'"):
        tf.encode_table(KIND, [0.0, 1.0], [[1.0], [2.0]], precision="half")


# ----------------------------------------------------------------- pure-Python reader / writer
@pytest.mark.req("OGK-HAR-008", "OGK-CORE-017")
def test_python_reader_rejects_corruptions(table: tuple[np.ndarray, np.ndarray, bytes]) -> None:
    _, _, blob = table
    flipped = bytearray(blob)
    flipped[60] ^= 0x01
    cases = {
        "payload CRC": bytes(flipped),
        "header CRC": reheader(blob, fix_crc=False, kind=KIND + 1),
        "magic": reheader(blob, magic=b"XGKT"),
        "version": reheader(blob, version=2),
        "element type": reheader(blob, elem_type=2),
        "truncated": blob[:-1],
        "after the payload": blob + b"\x00",
    }
    for reason, bad in cases.items():
        with pytest.raises(tf.TableFormatError):
            tf.decode_table(bad)
    with pytest.raises(tf.TableFormatError):
        tf.decode_table(blob, kind=KIND + 1)


@pytest.mark.req("OGK-HAR-008")
@pytest.mark.parametrize("grid, data", [
    (np.arange(3.0), np.zeros(3)),                   # no entry dimension
    (np.arange(3.0), np.zeros((4, 2))),              # grid / data mismatch
    (np.arange(3.0), np.zeros((3, 1, 1, 1, 1, 1))),  # 5 dims
    (np.arange(3.0), np.zeros((3, 0))),              # empty dim
    (np.array([0.0, np.nan, 1.0]), np.zeros((3, 2))),
    (np.arange(3.0), np.full((3, 2), np.inf)),
    (np.zeros(0), np.zeros((0, 2))),
])
def test_writer_rejects_invalid_input(grid: np.ndarray, data: np.ndarray) -> None:
    with pytest.raises(tf.TableFormatError):
        tf.encode_table(KIND, grid, data)
