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
from elf_stack import bounds, by_name, disassemble  # noqa: E402

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
