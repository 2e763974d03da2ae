"""Worst-case stack of every function in a linked ELF, from its disassembly: the kernel, the flight
program's callbacks, libm and libc alike (what gcc's -fstack-usage cannot see: libraries come built).

frame(f) = the bytes f takes (isa.py); bound(f) = frame(f) + the largest bound of what f calls,
directly, by a tail call, or through a register. A call through a register may reach any function
whose address the program takes (relocations in the code and data of the objects we compile), so an
indirect call is bounded by the deepest of those. Recursion, or a frame the reader cannot size, on a
path makes that function's bound None (refused), never a guess.
"""
from __future__ import annotations

import bisect
import re
import subprocess
from dataclasses import dataclass, field
from pathlib import Path

from isa import READERS, dead_code, local_jumps

_HEAD = re.compile(r"^([0-9a-f]+) <([^>]+)>:$")
_LINE = re.compile(r"^\s*([0-9a-f]+):\s+(\S.*)$")


@dataclass
class Func:
    name: str
    start: int
    frame: int = 0
    calls: set[int] = field(default_factory=set)   # start addresses of the functions it calls
    indirect: bool = False
    local_jumps: int = 0     # computed jumps proven to stay inside the function (isa.local_jumps)
    unknown_sp: bool = False
    last: int = 0            # address of its last listed line (instruction or literal word)


@dataclass
class Bound:
    bytes: int | None         # None: recursion or an unsized frame on some path
    path: list[str]           # the deepest chain, entry first
    why: str = ""


def disassemble(objdump: str, elf: Path, isa: str, no_return: frozenset[str] = frozenset()
                ) -> dict[int, Func]:
    """Every function of `elf` (`no_return`: terminating functions: SPARC code after a call of one
    is unreachable, isa.dead_code)."""
    text = subprocess.run([objdump, "-d", "--no-show-raw-insn", str(elf)], check=True,
                          capture_output=True, text=True).stdout
    read = READERS[isa]
    funcs: dict[int, Func] = {}
    cur: Func | None = None
    raw: list[tuple[Func, int, bool, int]] = []
    code: dict[int, list[tuple[int, str]]] = {}     # SPARC: a function's instructions, in order
    jumps: dict[int, list[int]] = {}                # ... and its calls / jumps through a register
    for line in text.splitlines():
        h = _HEAD.match(line)
        if h:
            cur = Func(h.group(2), int(h.group(1), 16))
            funcs[cur.start] = cur
            continue
        m = _LINE.match(line)
        if cur is not None and m:
            cur.last = int(m.group(1), 16)
        if cur is None or not m or m.group(2).startswith("."):
            continue
        ins = read(m.group(2).replace("\t", " "))
        cur.frame += ins.push
        addr = int(m.group(1), 16)
        if isa == "sparc":
            code.setdefault(cur.start, []).append((addr, m.group(2).replace("\t", " ")))
            if ins.indirect:
                jumps.setdefault(cur.start, []).append(addr)
        cur.indirect |= ins.indirect
        cur.unknown_sp |= ins.unknown_sp
        if ins.target is not None:
            raw.append((cur, ins.target, ins.call, addr))
    starts = sorted(funcs)
    # a SPARC function whose every jump through a register is a computed jump proven to stay inside
    # it (isa.local_jumps) calls nothing through a register; in such a function the code no path
    # reaches (isa.dead_code) calls nothing either
    entries = {t for _, t, _, _ in raw}
    dead: set[int] = set()
    ends = frozenset(a for a, f in funcs.items() if f.name in no_return)
    for a in (starts if isa == "sparc" else []):
        proven = {}
        if a in jumps:
            end = code[a][-1][0] + 4        # past its last instruction (objdump's listing of it)
            proven = local_jumps(code[a], a, end, entries)
            funcs[a].local_jumps = sum(1 for j in jumps[a] if j in proven)
            funcs[a].indirect = any(j not in proven for j in jumps[a])
        if not funcs[a].indirect and a in code:
            dead |= dead_code(code[a], a, entries, [(lo, hi) for lo, hi, _ in proven.values()], ends)
    for f, target, call, src in raw:
        if src in dead:
            continue
        owner = starts[bisect.bisect_right(starts, target) - 1] if target >= starts[0] else None
        if owner is not None and (owner != f.start or (call and target == f.start)):
            f.calls.add(owner)      # leaves f (a call or a tail call), or calls itself
    return funcs


def bounds(funcs: dict[int, Func], indirect_targets: set[int],
           no_return: frozenset[str] = frozenset()) -> dict[int, Bound]:
    """Deepest stack below every function (iterative DFS; recursion is reported, not followed).
    A function named in no_return is a terminating error path (e.g. the stack-protector's abort):
    its own frame counts, what it calls does not."""
    out: dict[int, Bound] = {}
    for root in sorted(funcs):
        todo: list[tuple[int, int]] = [(root, 0)]
        on_path: set[int] = set()
        while todo:
            node, state = todo.pop()
            if state == 0:
                if node in out or node in on_path:
                    if node in on_path:
                        out[node] = Bound(None, [funcs[node].name], "recursion")
                    continue
                on_path.add(node)
                todo.append((node, 1))
                for c in sorted(_callees(funcs[node], indirect_targets, no_return)):
                    if c not in out and c not in on_path:
                        todo.append((c, 0))
            else:
                on_path.discard(node)
                f = funcs[node]
                if f.unknown_sp and f.name not in no_return:
                    out[node] = Bound(None, [f.name], "stack pointer set from a register")
                    continue
                best: Bound = Bound(0, [])
                for c in _callees(f, indirect_targets, no_return):
                    b = out.get(c) or Bound(None, [funcs[c].name], "recursion")
                    if b.bytes is None:
                        best = b
                        break
                    if b.bytes > (best.bytes or 0):
                        best = b
                if best.bytes is None:
                    out[node] = Bound(None, [f.name] + best.path, best.why)
                else:
                    out[node] = Bound(f.frame + best.bytes, [f.name] + best.path)
    return out


def _callees(f: Func, indirect_targets: set[int], no_return: frozenset[str]) -> set[int]:
    if f.name in no_return:
        return set()
    return f.calls | (indirect_targets if f.indirect else set())


_SYM = re.compile(r"^([0-9a-f]+)\s.*\sF\s+\S+\s+([0-9a-f]+)\s+(?:\S+\s+)?(\S+)$")


def code_bytes(objdump: str, elf: Path, funcs: dict[int, Func]) -> dict[int, int]:
    """The size of every function: its ELF symbol's (objdump -t), or where the symbol has none (a
    hand-written library routine), its extent in the listing up to the next function."""
    text = subprocess.run([objdump, "-t", str(elf)], check=True, capture_output=True, text=True).stdout
    sym: dict[int, int] = {}
    for line in text.splitlines():
        m = _SYM.match(line)
        if m and int(m.group(2), 16) > 0:
            sym[int(m.group(1), 16) & ~1] = int(m.group(2), 16)     # a Thumb symbol's address has bit 0 set
    starts = sorted(funcs)
    out = {}
    for i, a in enumerate(starts):
        end = max(funcs[a].last, a) + 4
        if i + 1 < len(starts):
            end = min(end, starts[i + 1])
        out[a] = sym.get(a, end - a)
    return out


def reachable(funcs: dict[int, Func], root: int, indirect_targets: set[int],
              no_return: frozenset[str] = frozenset()) -> set[int]:
    """Every function a call of `root` may execute (itself, its callees, the address-taken functions
    where it calls through a register): the code it needs in flash."""
    seen = {root}
    todo = [root]
    while todo:
        for c in _callees(funcs[todo.pop()], indirect_targets, no_return):
            if c not in seen:
                seen.add(c)
                todo.append(c)
    return seen


def by_name(funcs: dict[int, Func]) -> dict[str, list[int]]:
    names: dict[str, list[int]] = {}
    for a, f in funcs.items():
        names.setdefault(f.name, []).append(a)
    return names
