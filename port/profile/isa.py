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
# Branches, V8's and the V9 forms the v8plus libc uses (prediction bits, a condition-code or register
# operand): a branch that leaves its function is a tail call, so every form must be read.
_S_BRANCH_OUT = re.compile(r"^(?:b(?:a|n|ne|e|g|le|ge|l|gu|leu|cc|cs|pos|neg|vc|vs|nz|z|geu|lu)?|"
                           r"fb\w*|br(?:z|lez|lz|nz|gz|gez))(?:,a)?(?:,p[nt])?\s+"
                           r"(?:%(?:[xi]cc|fcc[0-3]|[gilo][0-7]),\s*)?([0-9a-f]+)(?: <[^>]+>)?$")
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


# ---------------------------------------------------------------- SPARC computed jumps inside a function
# glibc's memcpy and memset (sparcv9 multiarch, in the v8plus libc of the qemu-user route) enter an
# unrolled store block through a PC-relative computed jump:
#     andcc %o2, 0x70, %g6 ; ... ; rd %pc, %o5 ; sll %g6, 1, %g5 ; sub %o5, %g5, %o5 ; jmp %o5 + 0xf8
# The reader above calls every `jmp %reg` an indirect call (any address-taken function). For this
# idiom the target is computable: local_jumps bounds it by interval arithmetic over the straight-line
# code before the jump, and a jump whose every possible target lies inside its own function is an
# intra-procedural edge (no link, no frame: the function's bound already covers all its code).
# Sound by construction: every register starts unknown at the function's start, at each address any
# direct branch or call targets and after every control transfer (annulled delay slots included);
# any instruction not modelled makes the register it may write unknown (its last operand), ldd/ldda/
# ldtw into integer registers (a pair), save/restore and calls make everything unknown. Only and/andcc with a non-negative
# immediate, sll/srl by an immediate, rd %pc and add/sub of such values give a bound; the caller also
# checks that no proven jump lands inside another's window. Anything else stays an indirect call.
_S_REG = re.compile(r"^%([gilo][0-7]|sp|fp)$")
_S_JMP_PC = re.compile(r"^jmp %(\w+)(?: \+ (-?(?:0x[0-9a-f]+|\d+)|%\w+))?$")
_S_UNCOND = re.compile(r"^(?:ba|b|bn|jmp|jmpl|ret|retl|call|ta|t\w*|done|retry)(?:,a)?(?:,p[nt])?\b")


def _s_ops(op: str) -> tuple[str, list[str]]:
    mnem, _, rest = op.partition(" ")
    return mnem, [o.strip() for o in rest.split(",")] if rest else []


def _s_imm(text: str) -> int | None:
    try:
        return int(text, 0)
    except ValueError:
        return None


def local_jumps(insns: list[tuple[int, str]], start: int, end: int, entries: set[int]
                ) -> dict[int, tuple[int, int, int]]:
    """Computed jumps of one SPARC function proven to stay inside [start, end): jump address ->
    (lowest target, highest target, lowest address its proof reads). `insns`: (address, objdump
    text) in order; `entries`: every address a direct branch or call targets (block entries)."""
    # state: register -> ("int", lo, hi, anchor) or ("pc", lo, hi, anchor): value pc-relative offsets
    state: dict[str, tuple[str, int, int, int]] = {}
    out: dict[int, tuple[int, int, int]] = {}
    reset_after = False
    for addr, raw in insns:
        op = re.sub(r"\s+", " ", raw.split("!")[0].strip())
        if addr in entries or reset_after:
            state.clear()
            reset_after = False
        mnem, ops = _s_ops(op)
        m = _S_JMP_PC.match(op)
        if m and m.group(1) in state and state[m.group(1)][0] == "pc":
            kind, lo, hi, anchor = state[m.group(1)]
            second = m.group(2) or "0"
            if second.startswith("%"):          # jmp %pcform + %index
                idx = state.get(second[1:])
                add = (idx[1], idx[2]) if idx is not None and idx[0] == "int" else None
                anchor = min(anchor, idx[3]) if idx is not None else anchor
            else:
                add = (_s_imm(second) or 0, _s_imm(second) or 0)
            if add is not None and start <= lo + add[0] and hi + add[1] < end:
                out[addr] = (lo + add[0], hi + add[1], anchor)
        if _S_UNCOND.match(op) or ",a" in mnem:
            reset_after = True    # after the delay slot: nothing falls through, or it may be skipped
            # (the delay slot itself still runs before the reset on the path we follow)
        dest = ops[-1] if ops and _S_REG.match(ops[-1]) else None
        if mnem in ("save", "restore") or mnem.startswith("call") or \
                (mnem.startswith(("ldd", "ldtw")) and dest is not None):   # an integer register pair
            state.clear()
            continue
        if dest is None:
            continue
        val: tuple[str, int, int, int] | None = None
        src = [o[1:] if _S_REG.match(o) else o for o in ops[:-1]]
        if mnem in ("and", "andcc") and len(ops) == 3 and _S_REG.match(ops[0]):
            k = _s_imm(ops[1])
            if k is not None and 0 <= k < 4096:
                val = ("int", 0, k, addr)
        elif mnem in ("sll", "srl") and len(ops) == 3 and src[0] in state and state[src[0]][0] == "int":
            k = _s_imm(ops[1])
            _, lo, hi, anchor = state[src[0]]
            if k is not None and 0 <= k < 12 and lo >= 0:
                val = ("int", lo << k, hi << k, anchor) if mnem == "sll" else ("int", lo >> k, hi >> k,
                                                                               anchor)
        elif mnem == "rd" and ops[0] == "%pc":
            val = ("pc", addr, addr, addr)
        elif mnem in ("add", "addcc", "sub", "subcc") and len(ops) == 3 and src[0] in state \
                and state[src[0]][0] == "pc" and _s_imm(ops[1]) is not None:
            k = _s_imm(ops[1]) or 0
            k = k if mnem.startswith("add") else -k
            a = state[src[0]]
            val = ("pc", a[1] + k, a[2] + k, a[3])
        elif mnem in ("add", "addcc", "sub", "subcc") and len(ops) == 3 and src[0] in state \
                and src[1] in state:
            a, b = state[src[0]], state[src[1]]
            if a[0] == "pc" and b[0] == "int":
                val = (("pc", a[1] + b[1], a[2] + b[2], min(a[3], b[3])) if mnem.startswith("add") else
                       ("pc", a[1] - b[2], a[2] - b[1], min(a[3], b[3])))
        if val is None:
            state.pop(dest[1:], None)
        else:
            state[dest[1:]] = val
    # a proof reads straight-line code: no other proven jump may land inside its window
    return {j: t for j, t in out.items()
            if not any(lo <= j and t[2] <= hi for k, (lo, hi, _) in out.items() if k != j)}


_S_NO_FALL = re.compile(r"^(?:ba?(?:,a)?(?:,p[nt])?|jmp|ret|retl|return)(?: |$)")


def dead_code(insns: list[tuple[int, str]], start: int, entries: set[int],
              local_targets: list[tuple[int, int]], no_return: frozenset[int] = frozenset()
              ) -> set[int]:
    """Addresses of one SPARC function that no path reaches: after an instruction that never falls
    through (b / ba, jmp, ret, retl, return, a call of a terminating function at an address in
    `no_return`) and its delay slot, up to the next address something enters (`entries`: every direct branch or call target in the program; `local_targets`: the
    ranges of its proven computed jumps). Only for a function whose every jump through a register
    is proven (an unproven one might enter anywhere): the caller checks. Its calls and branches are
    no edges (e.g. crt's padding after __sparc_get_pc_thunk's retl, `b,a deregister_tm_clones`, and
    gas's alignment fill `b,a NEXT_FUNCTION` after libm's call of __stack_chk_fail)."""
    dead: set[int] = set()
    state = "live"          # live -> slot (the delay slot, executed) -> dead
    for addr, raw in insns:
        op = re.sub(r"\s+", " ", raw.split("!")[0].strip())
        if addr == start or addr in entries or any(lo <= addr <= hi for lo, hi in local_targets):
            state = "live"
        if state == "dead":
            dead.add(addr)
            continue
        if state == "slot":
            state = "dead"
            continue
        c = _S_CALL.match(op)
        if _S_NO_FALL.match(op) or (c and int(c.group(1), 16) in no_return):
            state = "slot"
    return dead
