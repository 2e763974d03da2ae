"""Writer and pure-Python reader of the ogk binary table format (kernel/include/ogk/table.h).

Layout (little-endian, no padding, 48-byte header):
    0  magic "OGKT"          4  format version (1)     6  element type (1 = F64, 2 = F32)
    8  table kind (u32)     12  ndims (u16, 1..4)      14  reserved (0)
   16  dims[4] (u32)        32  grid size (u32, >= 1)  36  payload bytes (u32)
   40  payload CRC-32       44  CRC-32 of header bytes 0..43
   48  payload: grid[grid size] then entry k (prod(dims) values, row-major) per k.
The element type is the precision of the kernel build that flies the table (kernel/include/ogk/real.h):
F64 (IEEE-754 binary64 little-endian, 8 bytes a value) for the default double build, F32 (binary32,
4 bytes) for a build with OGK_REAL_SINGLE=1; a kernel refuses the other one (OGK_E_TABLE_TYPE). The
writer's `precision` says which ("double", the default: every existing file and its CRCs unchanged,
or "single").
The reader mirrors the kernel loader's checks so the round trip can be tested in
pure Python; the kernel loader (ogk_bindings.kernel.table_load) is the authority on board.
"""
from __future__ import annotations

import struct
import zlib
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from numpy.typing import ArrayLike, NDArray

MAGIC = b"OGKT"
FORMAT_VERSION = 1
ELEM_F64 = 1
ELEM_F32 = 2
#: precision (kernel/include/ogk/real.h: the double build, or OGK_REAL_SINGLE=1) -> element type
PRECISION_ELEM = {"double": ELEM_F64, "single": ELEM_F32}
#: element type -> (numpy little-endian dtype, bytes per value)
ELEM_DTYPE = {ELEM_F64: ("<f8", 8), ELEM_F32: ("<f4", 4)}
HEADER_SIZE = 48
MAX_DIMS = 4
HEADER_CRC_OFFSET = 44
_HEADER_BODY = struct.Struct("<4sHHIHH4IIII")  # bytes 0..43
_U32_MAX = 0xFFFFFFFF

assert _HEADER_BODY.size == HEADER_CRC_OFFSET


class TableFormatError(ValueError):
    """A table buffer violates the format (reason names the failed check)."""


@dataclass(frozen=True)
class TableHeader:
    """Every header field, as stored (so tests can craft invalid headers)."""

    kind: int
    ndims: int
    dims: tuple[int, int, int, int]
    grid_size: int
    payload_bytes: int
    payload_crc: int
    magic: bytes = MAGIC
    version: int = FORMAT_VERSION
    elem_type: int = ELEM_F64
    reserved: int = 0

    def pack(self, header_crc: int | None = None) -> bytes:
        """48 header bytes; header_crc None = the correct CRC of bytes 0..43."""
        body = _HEADER_BODY.pack(self.magic, self.version, self.elem_type, self.kind,
                                 self.ndims, self.reserved, *self.dims, self.grid_size,
                                 self.payload_bytes, self.payload_crc)
        crc = zlib.crc32(body) if header_crc is None else header_crc
        return body + struct.pack("<I", crc)

    @staticmethod
    def unpack(buf: bytes) -> tuple["TableHeader", int]:
        """Header fields and the stored header CRC (no validation)."""
        if len(buf) < HEADER_SIZE:
            raise TableFormatError(f"truncated: {len(buf)} bytes < header {HEADER_SIZE}")
        f = _HEADER_BODY.unpack_from(buf, 0)
        (header_crc,) = struct.unpack_from("<I", buf, HEADER_CRC_OFFSET)
        hdr = TableHeader(magic=f[0], version=f[1], elem_type=f[2], kind=f[3], ndims=f[4],
                          reserved=f[5], dims=(f[6], f[7], f[8], f[9]), grid_size=f[10],
                          payload_bytes=f[11], payload_crc=f[12])
        return hdr, header_crc


@dataclass(frozen=True)
class TableFile:
    """A table: kind, grid (n,), data (n, *dims) with n = grid size."""

    kind: int
    grid: NDArray[np.float64]
    data: NDArray[np.float64]
    elem_type: int = ELEM_F64  #: ELEM_F64 or ELEM_F32 (the values above are float64 either way)

    @property
    def dims(self) -> tuple[int, ...]:
        return tuple(int(d) for d in self.data.shape[1:])


def element_type(precision: str) -> int:
    """The element type of a kernel build's precision ("double" -> ELEM_F64, "single" -> ELEM_F32)."""
    try:
        return PRECISION_ELEM[precision]
    except KeyError:
        raise TableFormatError(f"precision {precision!r}: one of {', '.join(PRECISION_ELEM)}") from None


def encode_table(kind: int, grid: ArrayLike, data: ArrayLike, precision: str = "double") -> bytes:
    """Bytes of a version-1 table. data has shape (len(grid), *dims), 1..4 dims. precision "double"
    (F64, the default) or "single" (F32: each value rounded to the nearest binary32, and refused if it
    is beyond binary32's range)."""
    elem = element_type(precision)
    dtype, _ = ELEM_DTYPE[elem]
    g = np.asarray(grid, dtype=np.float64)
    d = np.asarray(data, dtype=np.float64)
    if g.ndim != 1 or g.size < 1:
        raise TableFormatError(f"grid must be a non-empty vector, got shape {g.shape}")
    if d.ndim < 2 or d.ndim > MAX_DIMS + 1 or d.shape[0] != g.size:
        raise TableFormatError(
            f"data must have shape (grid={g.size}, d1[, ..., d{MAX_DIMS}]), got {d.shape}")
    dims = tuple(int(x) for x in d.shape[1:])
    if min(dims) < 1:
        raise TableFormatError(f"every dimension must be >= 1, got {dims}")
    if not (np.all(np.isfinite(g)) and np.all(np.isfinite(d))):
        raise TableFormatError("grid and data must be finite")
    if not 0 <= kind <= _U32_MAX:
        raise TableFormatError(f"kind {kind} does not fit in u32")
    with np.errstate(over="ignore"):
        g_out, d_out = g.astype(dtype), d.astype(dtype)
    if not (np.all(np.isfinite(g_out)) and np.all(np.isfinite(d_out))):
        raise TableFormatError(f"a value beyond the range of {precision} precision ({dtype})")
    payload = g_out.tobytes() + d_out.tobytes(order="C")
    if len(payload) > _U32_MAX:
        raise TableFormatError("payload larger than 4 GiB")
    header = TableHeader(kind=kind, ndims=len(dims),
                         dims=tuple(dims + (0,) * (MAX_DIMS - len(dims))),  # type: ignore[arg-type]
                         grid_size=g.size, payload_bytes=len(payload),
                         payload_crc=zlib.crc32(payload), elem_type=elem)
    return header.pack() + payload


def decode_table(buf: bytes, kind: int | None = None, precision: str | None = None) -> TableFile:
    """Parses and validates buf (the same checks as the kernel loader). precision None accepts either
    element type; "double" or "single" only that one, as a kernel of that build does."""
    hdr, header_crc = TableHeader.unpack(buf)
    if hdr.magic != MAGIC:
        raise TableFormatError(f"bad magic {hdr.magic!r}")
    if zlib.crc32(buf[:HEADER_CRC_OFFSET]) != header_crc:
        raise TableFormatError("header CRC mismatch")
    if hdr.version != FORMAT_VERSION:
        raise TableFormatError(f"unsupported version {hdr.version}")
    if hdr.elem_type not in ELEM_DTYPE or hdr.reserved != 0:
        raise TableFormatError(f"unsupported element type {hdr.elem_type} / reserved "
                               f"{hdr.reserved}")
    if precision is not None and hdr.elem_type != element_type(precision):
        raise TableFormatError(f"element type {hdr.elem_type}, the {precision} build reads "
                               f"{element_type(precision)}")
    if kind is not None and hdr.kind != kind:
        raise TableFormatError(f"kind {hdr.kind}, expected {kind}")
    if not 1 <= hdr.ndims <= MAX_DIMS:
        raise TableFormatError(f"ndims {hdr.ndims} outside 1..{MAX_DIMS}")
    dims = hdr.dims[: hdr.ndims]
    if min(dims) < 1 or any(hdr.dims[hdr.ndims:]):
        raise TableFormatError(f"bad dims {hdr.dims} for ndims {hdr.ndims}")
    if hdr.grid_size < 1:
        raise TableFormatError("grid size 0")
    entry_len = int(np.prod(dims))
    dtype, value_bytes = ELEM_DTYPE[hdr.elem_type]
    expected = value_bytes * hdr.grid_size * (1 + entry_len)
    if hdr.payload_bytes != expected:
        raise TableFormatError(f"payload size {hdr.payload_bytes} != {expected}")
    have = len(buf) - HEADER_SIZE
    if have < expected:
        raise TableFormatError(f"truncated: payload {have} of {expected} bytes")
    if have > expected:
        raise TableFormatError(f"{have - expected} bytes after the payload")
    payload = bytes(buf[HEADER_SIZE:])
    if zlib.crc32(payload) != hdr.payload_crc:
        raise TableFormatError("payload CRC mismatch")
    values = np.frombuffer(payload, dtype=dtype).astype(np.float64)
    if not np.all(np.isfinite(values)):
        raise TableFormatError("non-finite value in payload")
    grid = values[: hdr.grid_size].copy()
    data = values[hdr.grid_size:].reshape((hdr.grid_size, *dims)).copy()
    return TableFile(kind=hdr.kind, grid=grid, data=data, elem_type=hdr.elem_type)


def write_table(path: str | Path, kind: int, grid: ArrayLike, data: ArrayLike,
                precision: str = "double") -> int:
    """Writes a table file (precision as encode_table); returns its size in bytes."""
    blob = encode_table(kind, grid, data, precision)
    Path(path).write_bytes(blob)
    return len(blob)


def read_table(path: str | Path, kind: int | None = None, precision: str | None = None) -> TableFile:
    return decode_table(Path(path).read_bytes(), kind, precision)
