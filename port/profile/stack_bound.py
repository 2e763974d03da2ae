#!/usr/bin/env python3
"""Worst-case stack of every public ogk_* entry point in linked ELFs, libm, libc and callbacks included.

Usage: stack_bound.py --isa thumb|sparc --objdump TOOL --su-dir DIR --objects OBJ... --json OUT ELF...

For each ELF: the disassembly bound (elf_stack.py), indirect calls bounded by the deepest function
whose address the compiled objects take (address_taken.py). Every kernel function's disassembled
frame is checked against gcc's -fstack-usage figure for it (the .su files): a mismatch means the
reader misses an instruction, and fails the run, so the same reader can be trusted on libm and libc,
which come without .su. An entry point's figure is its worst over the ELFs that link it.
Beside it, code_bytes: the flash that entry point's call may execute in that ELF (every function it
reaches, libraries and the address-taken callbacks included: elf_stack.reachable), e.g. the soft-float
helpers a double kernel pulls in on a single-precision FPU.
"""
from __future__ import annotations

import argparse
import json
import re
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from address_taken import address_taken  # noqa: E402
from elf_stack import bounds, by_name, code_bytes, disassemble, reachable  # noqa: E402

_SU = re.compile(r"^(.+):\d+:\d+:(\S+)\t(\d+)\t(\S+)$")
_CLONE_NO = re.compile(r"\.\d+(?=\.|$)")


def plain(name: str) -> str:
    """gcc's clone names without their numbers: the ELF's f.part.0.constprop.0 is the .su's
    f.part.0.constprop (gcc drops the last number there), so compare both as f.part.constprop."""
    return _CLONE_NO.sub("", name)


def su_frames(su_dir: Path) -> dict[str, int]:
    """Name -> frame for the functions defined once (static names defined twice are skipped)."""
    seen: dict[str, list[int]] = {}
    for su in sorted(su_dir.rglob("*.su")):
        for line in su.read_text().splitlines():
            m = _SU.match(line)
            if m:
                seen.setdefault(plain(m.group(2)), []).append(int(m.group(3)))
    return {n: v[0] for n, v in seen.items() if len(v) == 1}


def su_names(su_dir: Path) -> set[str]:
    return {plain(m.group(2)) for su in su_dir.rglob("*.su") for line in su.read_text().splitlines()
            if (m := _SU.match(line))}


def main(argv: list[str]) -> int:
    ap = argparse.ArgumentParser()
    ap.add_argument("--isa", choices=("thumb", "sparc"), required=True)
    ap.add_argument("--objdump", required=True)
    ap.add_argument("--su-dir", type=Path, required=True)
    ap.add_argument("--objects", type=Path, nargs="+", required=True)
    ap.add_argument("--json", type=Path, required=True)
    ap.add_argument("--no-return", nargs="*", default=[],
                    help="terminating error paths: their frame counts, their callees do not")
    ap.add_argument("elfs", type=Path, nargs="+")
    a = ap.parse_args(argv)
    taken = address_taken(a.objdump, a.objects)
    su = su_frames(a.su_dir)
    kernel_names = su_names(a.su_dir)
    problems: list[str] = []
    entry: dict[str, dict] = {}
    frames_checked: set[str] = set()
    taken_found: set[str] = set()
    for elf in a.elfs:
        funcs = disassemble(a.objdump, elf, a.isa, frozenset(a.no_return))
        names: dict[str, list[int]] = {}
        for n, addrs in by_name(funcs).items():
            names.setdefault(plain(n), []).extend(addrs)
        targets = {addr for n in taken for addr in names.get(plain(n), [])}
        taken_found |= {plain(n) for n in taken if plain(n) in names}
        for n, frame in su.items():
            for addr in names.get(n, []):
                frames_checked.add(n)
                if funcs[addr].frame != frame:
                    problems.append(f"{elf.name}: {n}: disassembly {funcs[addr].frame} B, gcc {frame} B")
        bd = bounds(funcs, targets, frozenset(a.no_return))
        size = code_bytes(a.objdump, elf, funcs)
        for addr, f in funcs.items():
            if not f.name.startswith("ogk_") or f.name.startswith("ogk_i_") or "." in f.name \
                    or f.name not in su:
                continue
            b = bd[addr]
            lib = [p for p in b.path if plain(p) not in kernel_names]
            old = entry.get(f.name)
            if b.bytes is None:
                problems.append(f"{elf.name}: {f.name}: no bound ({b.why} via {' > '.join(b.path)})")
                continue
            if old is None or b.bytes > old["bytes"]:
                entry[f.name] = {"bytes": b.bytes, "frame": f.frame, "path": b.path,
                                 "outside_kernel": lib, "elf": elf.name,
                                 "code_bytes": sum(size[x] for x in reachable(
                                     funcs, addr, targets, frozenset(a.no_return))),
                                 "indirect": any(funcs[x].indirect for x in funcs
                                                 if funcs[x].name in b.path)}
    a.json.parent.mkdir(parents=True, exist_ok=True)
    a.json.write_text(json.dumps({"isa": a.isa, "address_taken": sorted(taken_found),
                                  "entry_points": dict(sorted(entry.items())),
                                  "frames_checked_against_gcc": len(frames_checked),
                                  "problems": problems}, indent=1) + "\n")
    print(f"{'entry point':34s} {'frame':>6s} {'bound [B]':>9s}  deepest path (library frames marked *)")
    for n, e in sorted(entry.items()):
        chain = " > ".join(("*" if p in e["outside_kernel"] else "") + p for p in e["path"][1:5])
        print(f"{n:34s} {e['frame']:6d} {e['bytes']:9d}  {chain}")
    print(f"{len(frames_checked)} kernel functions' frames equal to gcc -fstack-usage's; "
          f"indirect-call targets (address taken): {', '.join(sorted(taken_found)) or 'none'}")
    for p in problems:
        print(f"STACK BOUND FAILED: {p}")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
