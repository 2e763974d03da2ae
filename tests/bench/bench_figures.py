"""The `<prefix>_<key> <value>` lines the C benchmarks write into build/bench/<name>/*.txt (host time, callgrind,
the QEMU instruction-count plugin, the stack reports), read back by the benchmarks' Python tables."""
from __future__ import annotations

import re
from pathlib import Path


def read_figures(d: Path | None, prefix: str) -> dict[str, str]:
    """{key: value} of every `<prefix>_... value` line in d/*.txt (empty when d is None)."""
    out: dict[str, str] = {}
    if d is None:
        return out
    pattern = re.compile(rf"^({re.escape(prefix)}_[a-z0-9_]+)\s+(\S+)")
    for f in sorted(d.glob("*.txt")):
        for line in f.read_text().splitlines():
            m = pattern.match(line)
            if m:
                out[m.group(1)] = m.group(2)
    return out
