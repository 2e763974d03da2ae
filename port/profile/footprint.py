#!/usr/bin/env python3
"""Memory of the kernel on one target: code, read-only data and RAM per module (kernel object files,
`size -A` sections summed by kind), and the size of every public struct type (a caller-owned context
is all of a law's RAM: the kernel has no globals). Read from the compiler's own output, never run, so
the same script serves every target; identical from run to run.

Usage: footprint.py --cc CC [--cflags ...] --size TOOL --nm TOOL --json OUT -- OBJ...
"""
from __future__ import annotations

import argparse
import json
import re
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
_TYPE = re.compile(r"^\}\s*(ogk_\w+_t);", re.M)


def sections(size_tool: str, obj: Path) -> dict[str, int]:
    """code / rodata / data / bss bytes of one object (section names of gcc's ELF output)."""
    out = {"code": 0, "rodata": 0, "data": 0, "bss": 0}
    text = subprocess.run([size_tool, "-A", str(obj)], check=True, capture_output=True, text=True).stdout
    for line in text.splitlines()[2:]:
        parts = line.split()
        if len(parts) < 2 or not parts[1].isdigit():
            continue
        name, n = parts[0], int(parts[1])
        if name.startswith(".text"):
            out["code"] += n
        elif name.startswith((".rodata", ".data.rel.ro")):
            # .data.rel.ro: const data holding addresses (a table of names), written once by the
            # loader under position-independent code and read-only after it (RELRO)
            out["rodata"] += n
        elif name.startswith(".data"):
            out["data"] += n
        elif name.startswith(".bss") or name == "COMMON":
            out["bss"] += n
    return out


def type_sizes(cc: list[str], nm: str) -> dict[str, dict[str, int]]:
    """sizeof of every public struct, per header, read back as the size of an array of that many bytes."""
    headers = sorted((ROOT / "kernel/include/ogk").glob("*.h"))
    types: list[tuple[str, str]] = []
    for h in headers:
        types += [(h.stem, t) for t in _TYPE.findall(h.read_text())]
    src = "".join(f'#include "ogk/{h.name}"\n' for h in headers)
    src += "".join(f"char ogk_sizeof__{t}[sizeof({t})];\n" for _, t in types)
    with tempfile.TemporaryDirectory() as d:
        c, o = Path(d) / "sizes.c", Path(d) / "sizes.o"
        c.write_text(src)
        subprocess.run(cc + ["-I", str(ROOT / "kernel/include"), "-fno-common", "-c", str(c), "-o", str(o)],
                       check=True)
        text = subprocess.run([nm, "-S", str(o)], check=True, capture_output=True, text=True).stdout
    got = {}
    for line in text.splitlines():
        p = line.split()
        if len(p) == 4 and p[3].startswith("ogk_sizeof__"):
            got[p[3][len("ogk_sizeof__"):]] = int(p[1], 16)
    out: dict[str, dict[str, int]] = {}
    for header, t in types:
        out.setdefault(header, {})[t] = got[t]
    return out


def main(argv: list[str]) -> int:
    ap = argparse.ArgumentParser()
    ap.add_argument("--cc", required=True, help="compiler and target flags, one string")
    ap.add_argument("--size", required=True)
    ap.add_argument("--nm", required=True)
    ap.add_argument("--json", type=Path, required=True)
    ap.add_argument("objects", type=Path, nargs="+")
    a = ap.parse_args(argv)
    modules = {o.stem: sections(a.size, o) for o in sorted(a.objects)}
    total = {k: sum(m[k] for m in modules.values()) for k in ("code", "rodata", "data", "bss")}
    doc = {"modules": modules, "total": total, "types": type_sizes(a.cc.split(), a.nm)}
    a.json.parent.mkdir(parents=True, exist_ok=True)
    a.json.write_text(json.dumps(doc, indent=1) + "\n")
    print(f"kernel: code {total['code']} B, read-only data {total['rodata']} B, "
          f"data {total['data']} B, bss {total['bss']} B over {len(modules)} modules")
    return 0 if total["data"] == 0 and total["bss"] == 0 else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
