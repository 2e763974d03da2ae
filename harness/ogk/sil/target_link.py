"""The host end of the processor-in-the-loop link (docs/guides/pil.md; the target end is
port/cortex-m7/link/ogk_link.h): one flight program on QEMU, framed messages over its stdin and
stdout: on the Cortex-M7 (target "m7") QEMU's mps2-an500 and its semihosting console, on the
Cortex-M4F (target "m4f") mps2-an386 and the same console; on SPARC V8 (target "sparc") a static
Linux program under qemu-sparc32plus (user mode: glibc's read/write). The values of the frames are
binary64 on every target: a single-precision program converts them at its boundary (ogk_pil.h).

Frame (every field little-endian): b"OGKL" | type u16 | length u16 | payload | CRC-32 u32 of type,
length and payload (zlib's). The runtime's own text (the stack report at exit, a fault report) also
reaches stdout: it is read as such only after the program has ended, never between frames.

`TargetLink(elf)` starts QEMU; `send` / `receive` exchange frames; a frame that does not arrive
within `timeout_s`, a dead QEMU or a corrupt frame raise `TargetLinkError` (one line, with the
program's exit code and the tail of its output when it has ended). `close()` sends STOP and waits.
"""
from __future__ import annotations

import os
import select
import struct
import subprocess
import time
import zlib
from pathlib import Path
from types import TracebackType

import numpy as np
from numpy.typing import NDArray

MAGIC = b"OGKL"
MAX_PAYLOAD = 1024           #: OGK_LINK_MAX_PAYLOAD
STOP, ERROR, ECHO = 1, 2, 3  #: OGK_LINK_STOP, OGK_LINK_ERROR, OGK_LINK_ECHO
QEMU = ("qemu-system-arm", "-M", "mps2-an500", "-nographic", "-monitor", "none", "-serial", "none",
        "-semihosting-config", "enable=on,target=native")
QEMU_SPARC = ("qemu-sparc32plus",)
#: the Cortex-M4F: QEMU's mps2-an386 board (single-precision FPU), the same semihosting console
QEMU_M4F = ("qemu-system-arm", "-M", "mps2-an386", "-nographic", "-monitor", "none", "-serial", "none",
            "-semihosting-config", "enable=on,target=native")
#: target -> (how QEMU is named in messages, the command line before the extra arguments)
TARGET_QEMU = {"m7": ("qemu mps2-an500", QEMU), "sparc": ("qemu-sparc32plus", QEMU_SPARC),
               "m4f": ("qemu mps2-an386", QEMU_M4F)}
#: the targets QEMU runs in system emulation (the ELF loaded as the kernel; the others: user mode)
SYSTEM_TARGETS = ("m7", "m4f")


def qemu_command(target: str, elf: Path, extra_args: tuple[str, ...] = ()) -> list[str]:
    """The command line that runs `elf` on `target` (system emulation loads it as the kernel; user
    mode runs it as the program)."""
    if target not in TARGET_QEMU:
        raise TargetLinkError(f"no QEMU for target {target!r} (known: {', '.join(TARGET_QEMU)})")
    base = TARGET_QEMU[target][1]
    return ([*base, *extra_args, "-kernel", str(elf)] if target in SYSTEM_TARGETS
            else [*base, *extra_args, str(elf)])


class TargetLinkError(RuntimeError):
    """The link broke: timeout, QEMU ended, or a corrupt frame."""


def frame(kind: int, payload: bytes) -> bytes:
    """One frame of `kind` carrying `payload`."""
    if len(payload) > MAX_PAYLOAD:
        raise ValueError(f"payload of {len(payload)} bytes exceeds {MAX_PAYLOAD}")
    head = struct.pack("<HH", kind, len(payload))
    return MAGIC + head + payload + struct.pack("<I", zlib.crc32(head + payload))


def f64_payload(values: NDArray[np.float64]) -> bytes:
    """binary64 values as 8 little-endian bytes each (bit patterns kept, NaN payloads included)."""
    return np.ascontiguousarray(values, dtype="<f8").tobytes()


def f64_values(payload: bytes) -> NDArray[np.float64]:
    return np.frombuffer(payload, dtype="<f8").astype(np.float64)


class TargetLink:
    """One flight program on an emulated target ("m7", "m4f" or "sparc"), talked to in frames."""

    def __init__(self, elf: str | Path, timeout_s: float = 10.0, extra_args: tuple[str, ...] = (),
                 target: str = "m7") -> None:
        self.elf = Path(elf)
        if not self.elf.is_file():
            raise TargetLinkError(f"{self.elf}: no such flight program (make link-echo builds the link's)")
        self.timeout_s = timeout_s
        self.target = target
        # SPARC runs in user mode: the guest's initial stack holds its environment and program path,
        # so their lengths move every stack address, and glibc's memcpy/memset take other branches
        # for other alignments (instruction counts differed by up to 0.6 % between an `ogk mc` run
        # and the same run under make). A fixed empty environment and the path "./NAME" (flown
        # copies are NAME-<sha16>.elf: one length) give the same stack on every run and clone.
        user = target not in SYSTEM_TARGETS
        self._proc = subprocess.Popen(qemu_command(target, Path("./" + self.elf.name) if user
                                                   else self.elf, extra_args),
                                      cwd=self.elf.parent if user else None,
                                      env={} if user else None,
                                      stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                                      stderr=subprocess.STDOUT)
        assert self._proc.stdin is not None and self._proc.stdout is not None
        self._out = self._proc.stdout.fileno()
        self._buf = bytearray()

    # ---------------------------------------------------------------- frames
    def send(self, kind: int, payload: bytes = b"") -> None:
        assert self._proc.stdin is not None
        try:
            self._proc.stdin.write(frame(kind, payload))
            self._proc.stdin.flush()
        except (BrokenPipeError, ValueError) as exc:
            raise self._error(f"send failed ({exc})") from None

    def receive(self) -> tuple[int, bytes]:
        """(type, payload) of the next frame."""
        head = self._read(8)
        if head[:4] != MAGIC:
            raise self._error(f"no frame: {bytes(head)!r} where a frame starts")
        kind, length = struct.unpack("<HH", head[4:])
        if length > MAX_PAYLOAD:
            raise self._error(f"frame length {length} above {MAX_PAYLOAD}")
        body = self._read(length + 4)
        payload, (crc,) = bytes(body[:length]), struct.unpack("<I", body[length:])
        if crc != zlib.crc32(head[4:] + payload):
            raise self._error("frame CRC mismatch")
        return kind, payload

    def exchange(self, kind: int, payload: bytes) -> tuple[int, bytes]:
        self.send(kind, payload)
        return self.receive()

    # ---------------------------------------------------------------- ending
    def close(self, timeout_s: float = 10.0) -> int:
        """STOP, then the program's exit code (QEMU killed if it does not end in `timeout_s`)."""
        if self._proc.poll() is None:
            try:
                self.send(STOP)
            except TargetLinkError:
                pass
            try:
                self._proc.wait(timeout_s)
            except subprocess.TimeoutExpired:
                self._proc.kill()
                self._proc.wait()
        self._drain()
        return int(self._proc.returncode)

    def kill(self) -> None:
        if self._proc.poll() is None:
            self._proc.kill()
            self._proc.wait()

    @property
    def output(self) -> str:
        """What the program wrote that is not a frame (after it ended: the runtime's reports)."""
        return self._buf.decode("utf-8", errors="replace")

    def __enter__(self) -> "TargetLink":
        return self

    def __exit__(self, exc_type: type[BaseException] | None, exc: BaseException | None,
                 tb: TracebackType | None) -> None:
        if exc_type is None:
            self.close()
        else:
            self.kill()

    # ---------------------------------------------------------------- internals
    def _read(self, n: int) -> bytearray:
        deadline = time.monotonic() + self.timeout_s
        while len(self._buf) < n:
            left = deadline - time.monotonic()
            if left <= 0.0:
                raise self._error(f"no frame within {self.timeout_s:g} s")
            ready, _, _ = select.select([self._out], [], [], left)
            if ready:
                chunk = os.read(self._out, 65536)
                if not chunk:
                    self._proc.wait()
                    raise self._error("the program ended")
                self._buf += chunk
        out, self._buf = self._buf[:n], self._buf[n:]
        return out

    def _drain(self) -> None:
        while True:
            ready, _, _ = select.select([self._out], [], [], 0.0)
            chunk = os.read(self._out, 65536) if ready else b""
            if not chunk:
                return
            self._buf += chunk

    def _error(self, what: str) -> TargetLinkError:
        code = self._proc.poll()
        if code is not None:
            self._drain()
        tail = " | ".join(self.output.strip().splitlines()[-3:])
        ended = "running" if code is None else f"exit {code}"
        return TargetLinkError(f"{self.elf.name} on {TARGET_QEMU[self.target][0]} ({ended}): {what}"
                               + (f"; output: {tail}" if tail else ""))
