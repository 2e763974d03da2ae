"""Floating-point operations of one benchmark call, counted exactly from callgrind (`make bench-flops`).

    flops.py LABEL TOGGLE -- PROGRAM ARGS...

runs PROGRAM under callgrind with --toggle-collect=TOGGLE (the bench programs' `*_once` functions: exactly
the call measured) and --dump-instr=yes, reads every executed instruction's count and its mnemonic
(objdump of the binary and of the shared libraries it ran, libm's sin/cos included), and sums the
double-precision arithmetic: add, sub, mul, div, sqrt, min, max = 1 flop per element, fused multiply-add
= 2; scalar (sd) 1 element, packed 128-bit (pd on xmm) 2, 256-bit (ymm) 4. Moves, compares, conversions
and integer work are not flops. Prints `LABEL instructions flops instructions/flop kernel-share`, where
kernel-share is the part of the flops in the program itself (not in libm).
"""
from __future__ import annotations

import re
import subprocess
import sys
import tempfile
from collections import defaultdict
from functools import lru_cache
from pathlib import Path

ARITH = re.compile(r"^v?(add|sub|mul|div|sqrt|min|max)(sd|pd)$")
FMA = re.compile(r"^vf(n?)m(add|sub)(132|213|231)?(sd|pd)$")
FMA_MIXED = re.compile(r"^vfm(addsub|subadd)(132|213|231)?pd$")


def flops_of(mnemonic: str, operands: str) -> int:
    """Double-precision flops of one executed instruction."""
    width = 4 if "ymm" in operands else 2
    m = ARITH.match(mnemonic)
    if m:
        return 1 if m.group(2) == "sd" else width
    m = FMA.match(mnemonic)
    if m:
        return 2 if m.group(4) == "sd" else 2 * width
    if FMA_MIXED.match(mnemonic):
        return 2 * width
    return 0


@lru_cache(maxsize=None)
def disassembly(obj: str) -> dict[int, tuple[str, str]]:
    """address -> (mnemonic, operands) of every instruction of an ELF object (its own addresses); empty
    for an object callgrind could not name ("???": code without a file, e.g. a trampoline)."""
    if not Path(obj).is_file():
        return {}
    out = subprocess.run(["objdump", "-d", "--no-show-raw-insn", obj], capture_output=True, text=True,
                         check=True).stdout
    table: dict[int, tuple[str, str]] = {}
    for line in out.splitlines():
        m = re.match(r"^\s*([0-9a-f]+):\s+(\S+)\s*(.*)$", line)
        if m:
            table[int(m.group(1), 16)] = (m.group(2), m.group(3))
    return table


def executed(path: Path) -> dict[str, dict[int, int]]:
    """object -> {address: executions} from a callgrind file written with --dump-instr=yes
    --compress-pos=no --compress-strings=no (the cost line after `calls=` is inclusive: skipped)."""
    counts: dict[str, dict[int, int]] = defaultdict(lambda: defaultdict(int))
    obj, skip = "", False
    for line in path.read_text().splitlines():
        if line.startswith("ob="):
            obj = line[3:]
        elif line.startswith("calls="):
            skip = True
        elif line.startswith("0x"):
            if skip:
                skip = False
                continue
            parts = line.split()
            counts[obj][int(parts[0], 16)] += int(parts[2]) if len(parts) > 2 else 0
    return counts


def count(toggle: str, program: list[str]) -> tuple[int, int, int]:
    """(instructions, flops, flops in the program itself) of the calls of `toggle` in `program`."""
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp) / "callgrind.out"
        subprocess.run(["valgrind", "--tool=callgrind", f"--callgrind-out-file={out}", "--dump-instr=yes",
                        "--compress-pos=no", "--compress-strings=no", "--collect-atstart=no",
                        f"--toggle-collect={toggle}", *program], check=True, capture_output=True)
        per_obj = executed(out)
    main = str(Path(program[0]).resolve())
    insns = flops = own = 0
    for obj, addrs in per_obj.items():
        table = disassembly(obj)
        for addr, n in addrs.items():
            insns += n
            mnemonic, operands = table.get(addr, ("", ""))
            f = n * flops_of(mnemonic, operands)
            flops += f
            if Path(obj).resolve() == Path(main):
                own += f
    return insns, flops, own


def main(argv: list[str]) -> int:
    if len(argv) < 4 or argv[2] != "--":
        print(__doc__, file=sys.stderr)
        return 2
    label, toggle, program = argv[0], argv[1], argv[3:]
    insns, flops, own = count(toggle, program)
    share = own / flops if flops else 0.0
    per = insns / flops if flops else float("inf")
    print(f"{label:34s} {insns:>13,} instructions {flops:>13,} flops  {per:5.2f} instructions/flop  "
          f"{100 * share:5.1f} % of the flops in the kernel (the rest libm)")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
