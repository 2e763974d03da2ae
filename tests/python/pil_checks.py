"""What the PIL tests of every family check the same way (tests/python/test_pil_*.py)."""
from __future__ import annotations

import re
import subprocess
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]

#: newlib's libm functions the entry points call (sin, cos, atan2, pow, ...) are outside gcc's call
#: graph (stack_report.py counts them as 0): their frames on top of the static worst case [B]
LIBM_SLACK_B = 256


def locked_make(target: str, timeout: float) -> subprocess.CompletedProcess[str]:
    """`make -s TARGET` under the lock the Makefile's `locked` takes for it (build/.lock-TARGET's
    name): `make test` makes the same target in its other lane, and two makes of one target at once
    would write the same files."""
    lock = ROOT / "build" / f".lock-{target}"
    lock.parent.mkdir(parents=True, exist_ok=True)
    return subprocess.run(["flock", str(lock), "make", "-s", target], cwd=ROOT, capture_output=True,
                          text=True, timeout=timeout)


def static_worst_stack() -> dict[str, int]:
    """gcc's static worst-case stack per kernel entry point on the Cortex-M7 (`make arm-stack`: own
    frame plus the deepest path through the kernel's call graph) [B]."""
    out = locked_make("arm-stack", timeout=600)
    assert out.returncode == 0, out.stdout[-2000:] + out.stderr[-2000:]
    return {m.group(1): int(m.group(3)) for m in
            re.finditer(r"^(ogk_\w+)\s+(\d+)\s+(\d+)", out.stdout, flags=re.M)}


def assert_stack_within_static(entry_points: dict, entries: tuple[str, ...]) -> dict[str, int]:
    """Each measured stack (the envelope's pil.entry_points) is positive and at most the static
    worst case plus libm's frames. Returns the static figures."""
    static = static_worst_stack()
    for e in entries:
        measured = entry_points[e]["stack_bytes"]["value"]
        assert 0 < measured <= static[e] + LIBM_SLACK_B, (e, measured, static[e])
    return static


def assert_worst_matches_records(doc: dict, records: list[dict], entries: tuple[str, ...]) -> None:
    """The envelope's worst call per entry point is the largest of the runs' own, at the run and
    step that run records."""
    worst = doc["pil"]["entry_points"]
    runs = {r["run_id"]: r for r in records}
    for e in entries:
        w = worst[e]["insn_max"]
        assert w["value"] == max(r[f"pil.{e}.insn_max"] for r in records), e
        assert runs[w["run_id"]][f"pil.{e}.insn_max"] == w["value"], e
        assert runs[w["run_id"]][f"pil.{e}.insn_max_step"] == w["step"], e
