#!/usr/bin/env python3
"""Flash and RAM of a linked ELF per input file, from the GNU ld map (-Wl,-Map): every input section
placed in the memory map, summed by its file (kernel library members, application objects, the
generated table, the runtime, newlib/libgcc). Flash = .vectors + .text (code and .rodata, the
linker script puts both there) + the load image of .data; RAM = .data + .bss (the stacks and the
heap are separate regions of the linker script, listed by arm-none-eabi-size).

Usage: map_sizes.py MAP"""
from __future__ import annotations

import re
import sys
from collections import defaultdict

OUT = re.compile(r"^(\.\S+)\s+0x[0-9a-f]+\s+0x[0-9a-f]+")
IN_ONE = re.compile(r"^ (\.\S+|COMMON)\s+(0x[0-9a-f]+)\s+(0x[0-9a-f]+)\s+(\S+)")
IN_NAME = re.compile(r"^ (\.\S+|COMMON)\s*$")
IN_REST = re.compile(r"^\s+(0x[0-9a-f]+)\s+(0x[0-9a-f]+)\s+(\S+)")
FLASH = (".vectors", ".text")
RAM = (".data", ".bss")


def group(path: str) -> str:
    m = re.search(r"libogk\.a\((\S+)\)", path)
    if m:
        return f"kernel {m.group(1)}"
    if "/flightapp/" in path:
        return f"app {path.rsplit('/', 1)[-1]}"
    if "/rt/" in path:
        return f"runtime {path.rsplit('/', 1)[-1]}"
    return "newlib/libgcc/crt"


def main(argv: list[str]) -> int:
    flash: dict[str, int] = defaultdict(int)
    ram: dict[str, int] = defaultdict(int)
    out_sec = None
    started = False
    pending = False
    for line in open(argv[1], encoding="utf-8"):
        if line.startswith("Linker script and memory map"):
            started = True
            continue
        if not started:
            continue
        m = OUT.match(line)
        if m:
            out_sec = m.group(1)
            continue
        if re.match(r"^\.\S+\s*$", line):
            out_sec = line.strip()
            continue
        size, path = None, None
        m = IN_ONE.match(line)
        if m:
            size, path = int(m.group(3), 16), m.group(4)
        elif IN_NAME.match(line):
            pending = True
            continue
        elif pending:
            m = IN_REST.match(line)
            if m:
                size, path = int(m.group(2), 16), m.group(3)
        pending = False
        if size is None or out_sec is None or size == 0:
            continue
        if out_sec in FLASH:
            flash[group(path)] += size
        elif out_sec in RAM:
            ram[group(path)] += size
            if out_sec == ".data":
                flash[group(path)] += size  # load image
    names = sorted(set(flash) | set(ram))
    print(f"{'input':34s} {'flash [B]':>10s} {'RAM [B]':>10s}")
    for n in names:
        print(f"{n:34s} {flash[n]:10d} {ram[n]:10d}")
    kern = [n for n in names if n.startswith("kernel ")]
    print(f"{'kernel total':34s} {sum(flash[n] for n in kern):10d} {sum(ram[n] for n in kern):10d}")
    print(f"{'all':34s} {sum(flash.values()):10d} {sum(ram.values()):10d}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
