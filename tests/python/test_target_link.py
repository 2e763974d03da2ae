"""The processor-in-the-loop link (issue 20, first part; docs/guides/pil.md): frames between the host and a
flight program on QEMU's emulated Cortex-M7 (build/arm/link/link_echo.elf, built by `make test`
before pytest).

- bit-exact: 2000 frames of binary64 values (random, +-0, subnormals, +-inf, NaNs with payloads,
  the extremes) come back negated, compared as bit patterns against numpy's negation here;
- framing: the largest payload passes; a frame whose CRC is corrupted in transit is answered
  with OGK_LINK_ERROR (code 4: CRC) and the link goes on;
- robustness: a program killed mid-link, and one that never answers, are one TargetLinkError
  line within the timeout, never a hang; STOP ends the program with exit 0.
"""
from __future__ import annotations

import time
from pathlib import Path

import numpy as np
import pytest

from ogk.sil.target_link import ECHO, ERROR, MAX_PAYLOAD, TargetLink, TargetLinkError, f64_payload, \
    f64_values, frame

pytestmark = pytest.mark.req("OGK-HAR-012")

REPO = Path(__file__).resolve().parents[2]
ELF = REPO / "build" / "arm" / "link" / "link_echo.elf"


def _bits(x: np.ndarray) -> np.ndarray:
    return np.ascontiguousarray(x, dtype=np.float64).view(np.uint64)


def _special_values() -> np.ndarray:
    nan_payloads = np.array([0x7FF8000000000001, 0x7FF0000000000001, 0xFFF4000000000abc],
                            dtype=np.uint64).view(np.float64)
    return np.concatenate([[0.0, -0.0, 5e-324, -5e-324, 2.2250738585072009e-308, np.inf, -np.inf,
                            np.finfo(np.float64).max, -np.finfo(np.float64).max, 1.0, np.pi],
                           nan_payloads])


def test_frames_round_trip_bit_exact() -> None:
    rng = np.random.default_rng(20261203)
    t0 = time.perf_counter()
    with TargetLink(ELF) as link:
        for i in range(2000):
            n = int(rng.integers(1, 17))
            values = rng.standard_normal(n) * 10.0 ** rng.integers(-300, 300, n)
            if i == 0:
                values = _special_values()
            kind, payload = link.exchange(ECHO, f64_payload(values))
            assert kind == ECHO
            back = f64_values(payload)
            assert np.array_equal(_bits(back), _bits(np.negative(values))), i
    rate = 2000 / (time.perf_counter() - t0)
    print(f"link: {rate:.0f} round trips/s (up to 128 B payloads, QEMU start included)")
    assert link.close() == 0


def test_largest_payload_and_a_corrupted_frame() -> None:
    with TargetLink(ELF) as link:
        values = np.arange(MAX_PAYLOAD // 8, dtype=np.float64) - 64.5
        kind, payload = link.exchange(ECHO, f64_payload(values))
        assert kind == ECHO and np.array_equal(f64_values(payload), -values)
        bad = bytearray(frame(ECHO, f64_payload(np.ones(4))))
        bad[10] ^= 0x01                               # a payload bit flipped in transit
        assert link._proc.stdin is not None
        link._proc.stdin.write(bytes(bad))
        link._proc.stdin.flush()
        kind, payload = link.receive()
        assert kind == ERROR and payload == bytes([4, 0])      # OGK_LINK_E_CRC
        kind, payload = link.exchange(ECHO, f64_payload(np.array([2.5])))   # and it goes on
        assert kind == ECHO and f64_values(payload)[0] == -2.5


def test_a_dead_program_is_one_error_line() -> None:
    link = TargetLink(ELF, timeout_s=5.0)
    link.exchange(ECHO, f64_payload(np.array([1.0])))
    link.kill()
    t0 = time.perf_counter()
    with pytest.raises(TargetLinkError) as err:
        link.exchange(ECHO, f64_payload(np.array([1.0])))
    assert time.perf_counter() - t0 < 5.0
    assert "link_echo.elf" in str(err.value) and "\n" not in str(err.value)


def test_a_silent_program_times_out() -> None:
    with TargetLink(ELF, timeout_s=1.0) as link:
        t0 = time.perf_counter()
        with pytest.raises(TargetLinkError, match="no frame within 1 s"):
            link.receive()                            # nothing was sent: nothing comes back
        assert 0.9 < time.perf_counter() - t0 < 3.0
        link.kill()


def test_stop_ends_the_program() -> None:
    link = TargetLink(ELF)
    link.exchange(ECHO, f64_payload(np.array([3.0])))
    assert link.close() == 0
    assert "stack high-water mark" in link.output
