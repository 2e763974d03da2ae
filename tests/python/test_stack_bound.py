"""The disassembly stack bound (port/profile) against gcc's own frame sizes on programs whose call
chains are written here: a chain, a call through a pointer, recursion, and libm, on the Cortex-M7
(Thumb-2) and on SPARC V8 (register windows). The reference for every frame is gcc -fstack-usage,
which the bound never reads for these programs' expected values."""
from __future__ import annotations

import json
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

pytestmark = pytest.mark.req("OGK-CORE-006")

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "port" / "profile"))
from elf_stack import bounds, by_name, code_bytes, disassemble, reachable  # noqa: E402

PROGRAM = r"""
#include <math.h>
typedef double (*leg_fn)(const double *v, int n);
double leaf(const double *v, int n);
double middle(const double *v, int n);
double small_cb(const double *v, int n);
double big_cb(const double *v, int n);
double through_pointer(leg_fn f, const double *v, int n);
double with_libm(double x);
double countdown(int k);
__attribute__((noipa)) double leaf(const double *v, int n)
{ volatile double buf[40]; double s = 0.0; for (int i = 0; i < n && i < 40; ++i) { buf[i] = v[i]; s += buf[i]; } return s; }
__attribute__((noipa)) double middle(const double *v, int n)
{ volatile double buf[100]; for (int i = 0; i < n && i < 100; ++i) buf[i] = 2.0 * v[i]; return leaf(v, n) + buf[0]; }
__attribute__((noipa)) double small_cb(const double *v, int n) { return v[0] * (double)n; }
__attribute__((noipa)) double big_cb(const double *v, int n)
{ volatile double buf[300]; for (int i = 0; i < n && i < 300; ++i) buf[i] = v[i]; return buf[n - 1]; }
__attribute__((noipa)) double through_pointer(leg_fn f, const double *v, int n)
{ volatile double pad[8]; pad[0] = v[0]; return f(v, n) + pad[0]; }
__attribute__((noipa)) double with_libm(double x) { return sin(x) + sqrt(x); }
__attribute__((noipa)) double countdown(int k) { volatile int pad[4]; pad[0] = k; return k <= 0 ? 0.0 : sin(countdown(pad[0] - 1)); }
leg_fn pick(int k);
leg_fn pick(int k) { return k ? big_cb : small_cb; }
int main(void);
int main(void)
{
    double v[4] = {1.0, 2.0, 3.0, 4.0};
    return (int)(middle(v, 4) + through_pointer(pick(1), v, 4) + with_libm(v[1]) + countdown(3));
}
"""

TARGETS = {
    "thumb": (["arm-none-eabi-gcc", "-mthumb", "-mcpu=cortex-m7", "-mfpu=fpv5-d16", "-mfloat-abi=hard",
               "--specs=nosys.specs"], "arm-none-eabi-objdump"),
    "sparc": (["sparc64-linux-gnu-gcc", "-m32", "-mcpu=v8", "-static", "-fno-pie", "-no-pie"],
              "sparc64-linux-gnu-objdump"),
}


def su(path: Path) -> dict[str, int]:
    out = {}
    for line in path.read_text().splitlines():
        m = re.match(r"^.+:\d+:\d+:(\S+)\t(\d+)\t", line)
        if m:
            out[m.group(1)] = int(m.group(2))
    return out


@pytest.fixture(params=sorted(TARGETS), scope="module")
def built(request, tmp_path_factory):
    isa = request.param
    cc, objdump = TARGETS[isa]
    if shutil.which(cc[0]) is None:
        pytest.fail(f"{cc[0]} missing: `make deps` installs it")
    d = tmp_path_factory.mktemp(isa)
    (d / "p.c").write_text(PROGRAM)
    subprocess.run(cc[:1] + cc[1:] + ["-std=c99", "-O2", "-fstack-usage", "-c", "p.c", "-o", "p.o"],
                   cwd=d, check=True)
    subprocess.run(cc + ["p.o", "-lm", "-o", "p.elf"], cwd=d, check=True)
    funcs = disassemble(objdump, d / "p.elf", isa)
    return isa, d, funcs, su(d / "p.su")


# glibc's libm on SPARC is built with the stack protector: its abort path sizes its message on the stack
# (a frame set from a register), and ends the process. The profile names it a terminating path.
NO_RETURN = frozenset({"__stack_chk_fail"})


def _bound_of(funcs, targets, name):
    addr = by_name(funcs)[name][0]
    return bounds(funcs, targets, NO_RETURN)[addr]


def test_frames_equal_gcc(built):
    isa, _, funcs, gcc = built
    names = by_name(funcs)
    for fn in ("leaf", "middle", "small_cb", "big_cb", "through_pointer", "with_libm", "main"):
        (addr,) = names[fn]
        assert funcs[addr].frame == gcc[fn], (isa, fn)


def test_chain_is_the_sum_of_its_frames(built):
    _, _, funcs, gcc = built
    b = _bound_of(funcs, set(), "middle")
    assert b.bytes == gcc["middle"] + gcc["leaf"]
    assert b.path == ["middle", "leaf"]


def test_pointer_call_takes_the_deepest_candidate(built):
    _, _, funcs, gcc = built
    names = by_name(funcs)
    cands = {names["small_cb"][0], names["big_cb"][0]}
    b = _bound_of(funcs, cands, "through_pointer")
    assert b.bytes == gcc["through_pointer"] + gcc["big_cb"]
    assert _bound_of(funcs, {names["small_cb"][0]}, "through_pointer").bytes == \
        gcc["through_pointer"] + gcc["small_cb"]


def test_libm_frames_are_counted(built):
    _, _, funcs, gcc = built
    b = _bound_of(funcs, set(), "with_libm")
    # sin's argument reduction has frames of its own: the bound must exceed with_libm's frame by them
    assert b.bytes is not None and b.bytes > gcc["with_libm"] + 100
    assert any(p.endswith("sin") for p in b.path)


def test_recursion_is_refused(built):
    _, _, funcs, _ = built
    b = _bound_of(funcs, set(), "countdown")
    assert b.bytes is None and b.why == "recursion"
    assert _bound_of(funcs, set(), "main").bytes is None


NM = {"thumb": "arm-none-eabi-nm", "sparc": "sparc64-linux-gnu-nm"}
OBJDUMP = {"thumb": "arm-none-eabi-objdump", "sparc": "sparc64-linux-gnu-objdump"}


def _symbol_sizes(isa: str, elf: Path) -> dict[str, int]:
    """The ELF symbol table's sizes (nm -S): the independent reference of each function's code."""
    out = subprocess.run([NM[isa], "-S", str(elf)], check=True, capture_output=True, text=True).stdout
    sizes = {}
    for line in out.splitlines():
        f = line.split()
        if len(f) == 4 and f[2] in "tT":
            sizes[f[3]] = int(f[1], 16)
    return sizes


def test_code_reachable_from_an_entry_point(built):
    """The flash a call may execute (profile's code column): the sum of the extents of what it reaches,
    each its ELF symbol's size (nm -S, a second reader of the symbol table)."""
    isa, d, funcs, _ = built
    names = by_name(funcs)
    size = code_bytes(OBJDUMP[isa], d / "p.elf", funcs)
    nm = _symbol_sizes(isa, d / "p.elf")
    for fn in ("leaf", "middle", "big_cb", "with_libm"):
        (addr,) = names[fn]
        assert size[addr] == nm[fn], (isa, fn, size[addr], nm[fn])

    def reached(name, targets=frozenset()):
        return {funcs[a].name for a in reachable(funcs, names[name][0], set(targets), NO_RETURN)}

    assert reached("middle") == {"middle", "leaf"}
    cands = {names["small_cb"][0], names["big_cb"][0]}
    assert reached("through_pointer", cands) == {"through_pointer", "small_cb", "big_cb"}
    lib = reached("with_libm")
    assert any(n.endswith("sin") for n in lib) and any("sqrt" in n for n in lib) and len(lib) > 3
    total = sum(size[a] for a in reachable(funcs, names["with_libm"][0], set(), NO_RETURN))
    assert total == sum(nm.get(n, 0) for n in lib) and total > nm["with_libm"] + 1000   # sin is kilobytes


def test_stack_bound_cli_flags_a_frame_mismatch(built, tmp_path):
    """The CLI cross-checks every frame against gcc; a .su that disagrees fails the run."""
    isa, d, _, gcc = built
    _, objdump = TARGETS[isa]
    bad = tmp_path / "su"
    bad.mkdir()
    text = (d / "p.su").read_text().replace(f"leaf\t{gcc['leaf']}\t", f"leaf\t{gcc['leaf'] + 8}\t")
    (bad / "p.su").write_text(text)
    out = tmp_path / "s.json"
    r = subprocess.run([sys.executable, str(ROOT / "port/profile/stack_bound.py"), "--isa", isa,
                        "--objdump", objdump, "--su-dir", str(bad), "--objects", str(d / "p.o"),
                        "--json", str(out), "--", str(d / "p.elf")], capture_output=True, text=True)
    assert r.returncode == 1
    assert f"leaf: disassembly {gcc['leaf']} B, gcc {gcc['leaf'] + 8} B" in r.stdout
    assert json.loads(out.read_text())["problems"]


@pytest.mark.parametrize("sections", [[], ["-ffunction-sections"]])
def test_static_callbacks_are_address_taken(built, tmp_path, sections):
    """A static function whose address is passed on is a possible target of an indirect call, whether its
    relocation names its own section (-ffunction-sections) or the .text section plus an offset."""
    from address_taken import address_taken
    isa, _, _, _ = built
    cc, objdump = TARGETS[isa]
    (tmp_path / "cb.c").write_text(
        "typedef int (*fn)(int);\nint apply(fn f, int x);\n"
        "static int twice(int x) { return 2 * x; }\nstatic int thrice(int x) { return 3 * x; }\n"
        "static int unused_direct(int x) { return x + 1; }\n"
        "int use(int x);\nint use(int x) { return apply(x ? twice : thrice, unused_direct(x)); }\n")
    subprocess.run(cc[:1] + cc[1:] + ["-std=c99", "-O2"] + sections + ["-c", "cb.c", "-o", "cb.o"],
                   cwd=tmp_path, check=True)
    taken = address_taken(objdump, [tmp_path / "cb.o"])
    assert {"twice", "thrice"} <= taken
    assert "unused_direct" not in taken and "use" not in taken


# ---------------------------------------------------------------- SPARC: computed jumps, v9 branches, dead code
# Hand-written instruction sequences in objdump's text (the shapes of glibc's v8plus memset and
# memcpy); the expected target ranges are worked out here from the SPARC semantics, not read from
# the code under test.
from isa import dead_code, local_jumps, sparc  # noqa: E402

MEMSET_LIKE = [(0x1000, "save  %sp, -96, %sp"),          # an entry (the function's start)
               (0x1004, "andcc  %o2, 0x78, %g5"),        # g5 in [0, 0x78]
               (0x1008, "be,pn   %xcc, 1060 <f+0x60>"),
               (0x100c, "andcc  %o2, 7, %o2"),           # writes o2, not g5
               (0x1010, "rd  %pc, %o4"),                 # o4 = 0x1010
               (0x1014, "srl  %g5, 1, %o3"),             # o3 in [0, 0x3c]
               (0x1018, "sub  %o4, %o3, %o4"),           # o4 in [0x1010 - 0x3c, 0x1010]
               (0x101c, "jmp  %o4 + 0x50"),              # targets [0x1024, 0x1060]
               (0x1020, "add  %o0, %g5, %o0")] + \
              [(0x1024 + 4 * i, "stx  %o1, [ %o0 + -8 ]") for i in range(16)] + \
              [(0x1064, "retl "), (0x1068, "nop ")]


def test_a_pc_relative_computed_jump_is_bounded_inside_its_function() -> None:
    got = local_jumps(MEMSET_LIKE, 0x1000, 0x106c, {0x1060})
    assert got == {0x101c: (0x1010 - 0x3c + 0x50, 0x1010 + 0x50, 0x1004)}


def test_a_computed_jump_is_not_proven_when_anything_may_break_the_reasoning() -> None:
    # a branch may enter between the mask and the jump: the index is unknown there
    assert local_jumps(MEMSET_LIKE, 0x1000, 0x106c, {0x1060, 0x1014}) == {}
    # the index rewritten by an instruction the analysis does not model
    changed = [(a, "ld  [ %o0 ], %g5" if a == 0x100c else t) for a, t in MEMSET_LIKE]
    assert local_jumps(changed, 0x1000, 0x106c, {0x1060}) == {}
    # the highest target (0x1010 + 0x150) past the function's end
    far = [(a, "jmp  %o4 + 0x150" if a == 0x101c else t) for a, t in MEMSET_LIKE]
    assert local_jumps(far, 0x1000, 0x106c, {0x1060}) == {}
    # a jump through a register loaded from memory (a function pointer): never proven
    ptr = [(0x2000, "ld  [ %o0 ], %g1"), (0x2004, "jmp  %g1"), (0x2008, "restore ")]
    assert local_jumps(ptr, 0x2000, 0x200c, set()) == {}
    # an annulled branch before the jump: its delay slot may be skipped, so nothing is known after
    ann = [(a, "bne,a   %xcc, 1060 <f+0x60>" if a == 0x1008 else t) for a, t in MEMSET_LIKE]
    assert local_jumps(ann, 0x1000, 0x106c, {0x1060}) == {}


def test_the_memcpy_large_shape_pc_plus_a_shifted_index() -> None:
    code = [(0x3000, "and  %g2, 7, %g2"), (0x3004, "rd  %pc, %g5"), (0x3008, "addcc  %g5, 0xf8, %g5"),
            (0x300c, "sll  %g2, 9, %g2"), (0x3010, "jmp  %g5 + %g2"), (0x3014, "nop ")]
    got = local_jumps(code, 0x3000, 0x4000, set())
    assert got == {0x3010: (0x3004 + 0xf8, 0x3004 + 0xf8 + (7 << 9), 0x3000)}
    assert local_jumps(code, 0x3000, 0x3004 + 0xf8 + (7 << 9), set()) == {}   # one byte short


def test_v9_branches_are_read_so_a_tail_call_by_branch_is_an_edge() -> None:
    # __math_uflow's `b %xcc, xflow` (V9 form) leaves the function: the reader must see its target
    assert sparc("b  %xcc, 381e0 <xflow>").target == 0x381E0
    assert sparc("be,pn   %xcc, 40154 <memcpy+0x2b4>").target == 0x40154
    assert sparc("bne,a,pt  %icc, 1234 <g>").target == 0x1234
    assert sparc("brz,pn  %o1, 4a0 <h>").target == 0x4A0
    assert sparc("btst  8, %o2").target is None


def test_code_after_a_return_or_a_terminating_call_is_dead_until_something_enters() -> None:
    code = [(0x100, "retl "), (0x104, "add  %o7, %l7, %l7"),          # delay slot: executed
            (0x108, "b,a   %xcc, 200 <deregister_tm_clones>"),         # padding no path reaches
            (0x10c, "nop "), (0x110, "call  300 <__stack_chk_fail>"), (0x114, "nop ")]
    assert dead_code(code, 0x100, set(), []) == {0x108, 0x10c, 0x110, 0x114}
    # the same padding entered by a branch from elsewhere is live
    assert dead_code(code, 0x100, {0x10c}, []) == {0x108}
    # inside a proven computed jump's targets: live
    assert dead_code(code, 0x100, set(), [(0x108, 0x10c)]) == set()
    # after a call of a terminating function
    tail = [(0x400, "call  300 <__stack_chk_fail>"), (0x404, "nop "), (0x408, "b,a  %xcc, 500 <g>")]
    assert dead_code(tail, 0x400, set(), [], frozenset({0x300})) == {0x408}
    assert dead_code(tail, 0x400, set(), []) == set()


def test_libc_memset_and_memcpy_call_nothing_through_a_register(built) -> None:
    """The libc linked into the program: on SPARC (glibc's v8plus memset and memcpy) their computed
    jumps are proven local, so the bound no longer routes `memset > mpsp_switch_cb > ...` through
    them (docs/evidence/profile.md before the fix); newlib's on the Cortex-M7 have none."""
    isa, _, funcs, _ = built
    names = by_name(funcs)
    for name in ("memset", "memcpy") if isa == "sparc" else ("memset",):   # newlib links no memcpy here
        assert name in names, (isa, name)
        f = funcs[names[name][0]]
        assert not f.indirect, (isa, name)
        assert (f.local_jumps >= 1) == (isa == "sparc"), (isa, name)
