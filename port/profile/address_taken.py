"""Functions whose address a program takes: the possible targets of its calls through a register.

Read from the relocations of the objects we compile (kernel, flight program): any relocation other than
a call or branch (literal pool word, movw/movt pair, SPARC sethi/or, a GOT entry, initialised data)
against a symbol, or against a function's own section under -ffunction-sections (.text.NAME), outside
debug information. Symbols that are not functions in the linked ELF drop out there.
"""
from __future__ import annotations

import re
import subprocess
from pathlib import Path

_SECTION = re.compile(r"^RELOCATION RECORDS FOR \[([^\]]+)\]:")
_RELOC = re.compile(r"^[0-9a-f]+\s+(R_\S+)\s+(\S+)")
# Direct calls and branches; every other relocation against a function takes its address (absolute,
# movw/movt, sethi/or, or through the GOT under -fPIE).
_CALLS = re.compile(r"^R_(?:ARM_(?:THM_CALL|THM_JUMP\d+|CALL|JUMP24|PC24|PLT32|V4BX)|"
                    r"SPARC_(?:WDISP\d+|WPLT30|DISP\d+|NONE))$")


_SYM = re.compile(r"^([0-9a-f]+)\s+\S*\s+F\s+(\S+)\s+[0-9a-f]+\s+(\S+)$")


def _functions_by_section(objdump: str, obj: Path) -> dict[tuple[str, int], str]:
    """(section, offset) -> function, to resolve a relocation against a section symbol plus offset
    (a static function's address without -ffunction-sections: `.text+0x1a4`)."""
    text = subprocess.run([objdump, "-t", str(obj)], check=True, capture_output=True, text=True).stdout
    return {(m.group(2), int(m.group(1), 16)): m.group(3)
            for line in text.splitlines() if (m := _SYM.match(line))}


def address_taken(objdump: str, objects: list[Path]) -> set[str]:
    names: set[str] = set()
    for obj in objects:
        at = _functions_by_section(objdump, obj)
        text = subprocess.run([objdump, "-r", str(obj)], check=True, capture_output=True,
                              text=True).stdout
        section = ""
        for line in text.splitlines():
            s = _SECTION.match(line)
            if s:
                section = s.group(1)
                continue
            r = _RELOC.match(line)
            if not r or section.startswith((".debug", ".rel.debug", ".ARM", ".comment", ".eh_frame")):
                continue
            if _CALLS.match(r.group(1)):
                continue
            sym, _, off = r.group(2).partition("+")
            if (sym, int(off or "0", 16)) in at:
                names.add(at[(sym, int(off or "0", 16))])
            elif sym.startswith(".text."):
                names.add(sym[len(".text."):])
            elif not sym.startswith("."):
                names.add(sym)
    return names
