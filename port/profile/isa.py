"""Per-ISA reading of one disassembled instruction (objdump -d --no-show-raw-insn): how many bytes it
takes from the stack, which function it calls, and whether it calls through a register.

Only what a stack bound needs. A frame is the sum of every stack decrement in the function: a
function whose prologue is shrink-wrapped into two branches is counted twice, which over-bounds and
never under-bounds. Anything else that writes the stack pointer (sp from a register) makes the frame
unknown: the bound then refuses the function rather than guess.
"""
from __future__ import annotations

import re
from dataclasses import dataclass


@dataclass(frozen=True)
class Insn:
    push: int = 0            # bytes taken from the stack by this instruction
    target: int | None = None  # address a branch or call goes to (the caller decides if it leaves)
    call: bool = False       # a call (links a return address): to its own start, it is recursion
    indirect: bool = False   # call (or tail call) through a register
    unknown_sp: bool = False  # writes sp in a way the bound cannot size


# ---------------------------------------------------------------- ARMv7-M Thumb-2 (Cortex-M7)
_T_REGLIST = re.compile(r"^(push(?:\.w)?|stmdb(?:\.w)?\s+sp!,)\s*\{([^}]*)\}")
_T_VPUSH = re.compile(r"^vpush\s*\{([^}]*)\}")
_T_SUBSP = re.compile(r"^sub(?:\.w|w)?\s+sp,\s*(?:sp,\s*)?#(\d+)")
_T_PREIDX = re.compile(r"^(?:str|strd|str\.w|vstr|vstmdb)\S*\s+[^\[]*\[sp, #-(\d+)\]!")
_T_CALL = re.compile(r"^(?:bl|blx|b|b\.w|b\.n|b(?:eq|ne|cs|cc|mi|pl|vs|vc|hi|ls|ge|lt|gt|le)(?:\.w|\.n)?)"
                     r"\s+([0-9a-f]+) <[^>]+>$")
_T_INDIRECT = re.compile(r"^(?:blx\s+r\d+|bx\s+(?:r\d+|ip)|mov\s+pc,)")
_T_SPWRITE = re.compile(r"^(?:mov|sub|add)(?:\.w|w|s)?\s+sp,")
_T_SPADD = re.compile(r"^add(?:\.w|w)?\s+sp,\s*(?:sp,\s*)?#\d+")


def _count_regs(text: str, width: int) -> int:
    n = 0
    for item in text.split(","):
        item = item.strip()
        if "-" in item:
            lo, hi = item.split("-")
            n += int(hi[1:]) - int(lo[1:]) + 1
        elif item:
            n += 1
    return n * width


def thumb(op: str) -> Insn:
    """One Thumb-2 instruction (mnemonic and operands, objdump's text)."""
    op = op.split("@")[0].strip()
    m = _T_REGLIST.match(op)
    if m:
        return Insn(push=_count_regs(m.group(2), 4))
    m = _T_VPUSH.match(op)
    if m:
        return Insn(push=_count_regs(m.group(1), 8))
    m = _T_SUBSP.match(op)
    if m:
        return Insn(push=int(m.group(1)))
    m = _T_PREIDX.match(op)
    if m:
        return Insn(push=int(m.group(1)))
    m = _T_CALL.match(op)
    if m:
        return Insn(target=int(m.group(1), 16), call=op.startswith("bl"))
    if _T_INDIRECT.match(op):
        return Insn(indirect=True)
    if _T_SPWRITE.match(op) and not _T_SPADD.match(op):
        return Insn(unknown_sp=True)
    return Insn()


# ---------------------------------------------------------------- SPARC V8 (LEON3)
# A frame is opened by `save %sp, -N, %sp` (N includes the 64-byte window save area the trap handler
# spills into); a leaf routine without save uses its caller's frame.
_S_SAVE = re.compile(r"^save\s+%sp,\s*-(\d+),\s*%sp")
_S_SAVE_REG = re.compile(r"^save\s+%sp,\s*%")
_S_ADDSP = re.compile(r"^add\s+%sp,\s*(-?(?:0x[0-9a-f]+|\d+)),\s*%sp$")
_S_SUBSP = re.compile(r"^sub\s+%sp,\s*(0x[0-9a-f]+|\d+),\s*%sp$")
_S_CALL = re.compile(r"^call\s+([0-9a-f]+)(?: <[^>]+>)?$")
_S_BRANCH_OUT = re.compile(r"^(?:b|ba|bn|bne|be|bg|ble|bge|bl|bgu|bleu|bcc|bcs|bpos|bneg|bvc|bvs|"
                           r"fb\w*)(?:,a)?\s+([0-9a-f]+)(?: <[^>]+>)?$")
_S_INDIRECT = re.compile(r"^(?:call\s+%|jmpl\s+%(?!i7|o7)|jmp\s+%(?!i7|o7))")
_S_SPWRITE = re.compile(r"^(?:add|sub|mov|or)\s+.*,\s*%sp$")


def sparc(op: str) -> Insn:
    """One SPARC V8 instruction."""
    op = re.sub(r"\s+", " ", op.split("!")[0].strip())
    m = _S_SAVE.match(op)
    if m:
        return Insn(push=int(m.group(1)))
    if _S_SAVE_REG.match(op):
        return Insn(unknown_sp=True)
    m = _S_ADDSP.match(op)
    if m:      # the frame grown past save's 13-bit immediate, or given back (positive)
        return Insn(push=max(0, -int(m.group(1), 0)))
    m = _S_SUBSP.match(op)
    if m:
        return Insn(push=int(m.group(1), 0))
    m = _S_CALL.match(op)
    if m:
        return Insn(target=int(m.group(1), 16), call=True)
    m = _S_BRANCH_OUT.match(op)
    if m:
        return Insn(target=int(m.group(1), 16))
    if _S_INDIRECT.match(op):
        return Insn(indirect=True)
    if _S_SPWRITE.match(op) and not op.startswith("save") and not op.startswith("restore"):
        return Insn(unknown_sp=True)
    return Insn()


READERS = {"thumb": thumb, "sparc": sparc}
