#!/usr/bin/env python3
"""The worst error of every tolerance assertion of the unit tests, per build (make unit-errors).

Reads the logs of the unit tests built with -DOGK_TEST_MEASURE (tests/unit/ogk_test.h), one directory
per build under --build: host-double, host-single (*.log of each test program), m4f (the QEMU runs).
Each "OGK_ERR file:line value bound ratio expression" line is one site's worst ratio value / bound so
far; the last (largest) one of each site in each build is kept. Writes OUT.json (every site) and OUT.md
(per test file: every site whose single-precision tolerance differs from the double one or whose ratio
is above 0.01 in a build, with the worst value, its bound and the ratio in each build), and prints the
tests that did not pass in each build. Stdlib only.
"""
from __future__ import annotations

import argparse
import json
import math
import re
from pathlib import Path

BUILDS = ("host-double", "host-single", "m4f")
LINE = re.compile(r"OGK_ERR (?P<site>\S+):(?P<line>\d+) (?P<value>\S+) (?P<bound>\S+) (?P<ratio>\S+) (?P<expr>.*)$")
EXIT = re.compile(r"^exit (\d+)$")


def _num(text: str) -> float:
    try:
        return float(text)
    except ValueError:
        return math.nan


def read_build(folder: Path) -> tuple[dict, dict]:
    """{(file, line): {value, bound, ratio, expr}} and {test: exit code} of one build's logs."""
    sites: dict = {}
    exits: dict = {}
    for log in sorted(folder.glob("*.log")):
        test = log.stem
        code = None
        for raw in log.read_text(errors="replace").splitlines():
            m = LINE.search(raw)
            if m:
                key = (m["site"], int(m["line"]))
                rec = {"value": _num(m["value"]), "bound": _num(m["bound"]), "ratio": _num(m["ratio"]),
                       "expr": m["expr"].strip(), "test": test}
                old = sites.get(key)
                if old is None or math.isnan(rec["ratio"]) or rec["ratio"] >= old["ratio"]:
                    sites[key] = rec
                continue
            e = EXIT.match(raw.strip())
            if e:
                code = int(e.group(1))
        exits[test] = code
    return sites, exits


def fmt(rec: dict | None) -> str:
    if rec is None:
        return "-"
    return f"{rec['value']:.2e} / {rec['bound']:.2e} ({rec['ratio']:.2g})"


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--build", type=Path, required=True, help="build/unit-errors")
    ap.add_argument("--out", type=Path, required=True, help="output stem (.json, .md)")
    args = ap.parse_args()

    data = {}
    exits = {}
    for b in BUILDS:
        data[b], exits[b] = read_build(args.build / b)
    keys = sorted(set().union(*(d.keys() for d in data.values())))

    rows = []
    for key in keys:
        recs = {b: data[b].get(key) for b in BUILDS}
        rows.append({"file": key[0], "line": key[1],
                     "expr": next(r["expr"] for r in recs.values() if r is not None),
                     **{b: recs[b] for b in BUILDS}})
    args.out.parent.mkdir(parents=True, exist_ok=True)
    args.out.with_suffix(".json").write_text(json.dumps({"sites": rows, "exits": exits}, indent=1,
                                                         default=str))

    lines = ["# Worst error per tolerance assertion (make unit-errors)", "",
             "value / bound (ratio) at the worst ratio of each site; '-' where the build did not reach it.", ""]
    by_file: dict = {}
    for r in rows:
        by_file.setdefault(r["file"], []).append(r)
    for f, rs in by_file.items():
        shown = []
        for r in rs:
            d, s, m = r["host-double"], r["host-single"], r["m4f"]
            differs = (d is not None and s is not None and d["bound"] != s["bound"])
            high = any(x is not None and not (x["ratio"] <= 0.01) for x in (d, s, m))
            if differs or high:
                shown.append(r)
        if not shown:
            continue
        lines += [f"## {f}", "", "| line | expression | double (host) | single (host) | single (M4F) |",
                  "|---|---|---|---|---|"]
        for r in shown:
            lines.append(f"| {r['line']} | `{r['expr'][:60]}` | {fmt(r['host-double'])} | "
                         f"{fmt(r['host-single'])} | {fmt(r['m4f'])} |")
        lines.append("")
    lines += ["## Programs that did not pass", ""]
    for b in BUILDS:
        bad = sorted(t for t, c in exits[b].items() if c != 0)
        lines.append(f"- {b}: {', '.join(bad) if bad else 'none'} ({len(exits[b])} run)")
    args.out.with_suffix(".md").write_text("\n".join(lines) + "\n")
    for b in BUILDS:
        bad = sorted(t for t, c in exits[b].items() if c != 0)
        print(f"unit-errors: {b}: {len(exits[b])} programs, {len(data[b])} sites, "
              f"not passed: {', '.join(bad) if bad else 'none'}")
    print(f"unit-errors: {args.out.with_suffix('.md')}, {args.out.with_suffix('.json')}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
