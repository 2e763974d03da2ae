#!/usr/bin/env python3
"""Compares the injection errors of the flight app on the emulated Cortex-M7 with the same app built
for the host (gcc x86-64, glibc libm): the "flightapp: <run>: cut-off ..." lines must agree to TOL
(m, m/s, s) in every number. Usage: compare_runs.py ARM_LOG HOST_LOG"""
from __future__ import annotations

import re
import sys

TOL = 1e-5
LINE = re.compile(r"^flightapp: (.+?): cut-off (.*)$")
NUM = re.compile(r"[-+]?\d+\.\d+(?:e[-+]?\d+)?")


def runs(path: str) -> dict[str, list[float]]:
    out = {}
    for line in open(path, encoding="utf-8", errors="replace"):
        m = LINE.match(line.strip())
        if m:
            out[m.group(1)] = [float(v) for v in NUM.findall(m.group(2))]
    return out


def main(argv: list[str]) -> int:
    arm, host = runs(argv[1]), runs(argv[2])
    if not arm or arm.keys() != host.keys():
        print(f"compare_runs: runs differ: arm {sorted(arm)} host {sorted(host)}")
        return 1
    worst = 0.0
    for name in arm:
        if len(arm[name]) != len(host[name]):
            print(f"compare_runs: {name}: different number of values")
            return 1
        worst = max([worst] + [abs(a - b) for a, b in zip(arm[name], host[name])])
    ok = worst <= TOL
    print(f"compare_runs: {len(arm)} runs, largest difference cortex-m7 vs host {worst:.3e} "
          f"(tolerance {TOL:g}): {'ok' if ok else 'FAILED'}")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv))
