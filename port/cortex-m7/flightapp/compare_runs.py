#!/usr/bin/env python3
"""Compares the injection errors of the flight app on the emulated Cortex-M7 with the same app built
for the host (gcc x86-64, glibc libm): the "flightapp: <run>: cut-off ..." lines must agree to TOL
(m, m/s, s) in every number; runs missing from one log are an error unless --common. Also compares
the app with the SIL (python -m ogk.missions.orbit_injection.flightapp_reference).
Usage: compare_runs.py [--tol T] [--common] LOG_A LOG_B"""
from __future__ import annotations

import re
import sys
from pathlib import Path

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
    global TOL
    args = argv[1:]
    common = "--common" in args
    args = [a for a in args if a != "--common"]
    if args[0] == "--tol":
        TOL, args = float(args[1]), args[2:]
    arm, host = runs(args[0]), runs(args[1])
    if common:
        keys = arm.keys() & host.keys()
        arm = {k: arm[k] for k in keys}
        host = {k: host[k] for k in keys}
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
    print(f"compare_runs: {len(arm)} runs ({', '.join(sorted(arm))}), largest difference "
          f"{Path(args[0]).name} vs {Path(args[1]).name} {worst:.3e} "
          f"(tolerance {TOL:g}): {'ok' if ok else 'FAILED'}")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv))
