"""The cffi bindings reach everything the public headers and the test headers declare.

An independent scan of the header TEXT (comments stripped, regex; it shares no
code with bindings/build_ffi.py, which works from the preprocessor) lists every
public function, every field of every struct typedef, every enumerator and
every object-like OGK_* macro of kernel/include/ogk/*.h, bindings/csrc/*.h and the families' csrc/*.h;
each must be reachable through ``lib`` / ``ffi`` (a family's csrc/*.h: through the family's own
extension, ogk.missions.<family>._csrc_cffi, built by the family layer on the bindings' types). A header that gains a
function, field or macro the bindings miss fails here.

The kernel's test headers (kernel/include/ogk/internal/*.h: the test entry points
that are not flight API, e.g. ogk_nmpc_interval) are scanned the same way, as a
separate list (TEST_HEADERS): each of their functions must be reachable too, must
not be declared by a public header as well, and must be named by the public
header of its law as living there (so the move stays documented).
"""
from __future__ import annotations

import re
from pathlib import Path

import pytest

import importlib

from ogk_bindings import _ffi
from ogk_bindings._ffi import ffi, lib

ROOT = Path(__file__).resolve().parents[2]
PUBLIC_HEADERS = sorted((ROOT / "kernel" / "include" / "ogk").glob("*.h")) + sorted(
    (ROOT / "bindings" / "csrc").glob("*.h")) + sorted(
    (ROOT / "harness" / "ogk" / "missions").glob("*/csrc/*.h"))
TEST_HEADERS = sorted((ROOT / "kernel" / "include" / "ogk" / "internal").glob("*.h"))
HEADERS = PUBLIC_HEADERS + TEST_HEADERS
#: header name -> (ffi, lib) that must declare it: a family's csrc header, the family's extension
BOUND = {h.name: (importlib.import_module(f"ogk.missions.{h.parent.parent.name}._csrc_cffi")
                  if h.parent.name == "csrc" and "missions" in h.parts else None)
         for h in HEADERS}


def bound(header: str) -> tuple[object, object]:
    """(ffi, lib) of the extension that declares `header`."""
    module = BOUND.get(header)
    return (ffi, lib) if module is None else (module.ffi, module.lib)


def _strip_comments(text: str) -> str:
    text = re.sub(r"/\*.*?\*/", " ", text, flags=re.S)
    return re.sub(r"//[^\n]*", " ", text)


_PRECISION_IF = re.compile(r"^#\s*if\s+(!?)\s*OGK_REAL_SINGLE\s*$")


def _this_precision(lines: list[str]) -> list[str]:
    """The lines a compiler of this process's precision reads of the `#if OGK_REAL_SINGLE` /
    `#if !OGK_REAL_SINGLE` blocks (their `#else` branch too); every other line as it is. The float build
    declares a few things of its own (ogk/terminal.h's ogk_terminal_step_split): the bindings of the
    double build do not have them, the float build's do."""
    single = _ffi.PRECISION == "single"
    out: list[str] = []
    stack: list[tuple[bool, bool]] = []     # (is a precision block, keep its current branch)
    for line in lines:
        d = line.strip()
        m = _PRECISION_IF.match(d)
        if m:
            stack.append((True, single != bool(m.group(1))))
            continue
        if d.startswith("#if"):
            stack.append((False, True))
        elif d.startswith("#else") and stack and stack[-1][0]:
            stack[-1] = (True, not stack[-1][1])
            continue
        elif d.startswith("#endif") and stack:
            if stack.pop()[0]:
                continue
        if all(keep for _, keep in stack):
            out.append(line)
    return out


def _code(path: Path) -> str:
    """Header text without comments and without preprocessor lines (continuations joined), of this
    process's precision (`_this_precision`)."""
    text = _strip_comments(path.read_text()).replace("\\\n", " ")
    return "\n".join(l for l in _this_precision(text.splitlines()) if not l.lstrip().startswith("#"))


def _functions(path: Path) -> list[tuple[str, str]]:
    """(return type, name) of every prototype at file scope."""
    out = []
    for m in re.finditer(r"(?m)^\s*([A-Za-z_][\w \t\*]*?)\b(ogk_\w+)\s*\(", _code(path)):
        ret = m.group(1).strip()
        if ret.startswith("typedef"):
            continue  # function-pointer typedefs are types, not functions
        out.append((ret, m.group(2)))
    return out


def _structs(path: Path) -> list[tuple[str, list[str]]]:
    """(typedef name, field names) of every `typedef struct { ... } name;`."""
    out = []
    for m in re.finditer(r"typedef\s+struct\s*\w*\s*\{(.*?)\}\s*(\w+)\s*;", _code(path), re.S):
        fields = []
        for decl in m.group(1).split(";"):
            decl = decl.strip()
            if not decl:
                continue
            fp = re.search(r"\(\s*\*\s*(\w+)\s*\)", decl)  # function-pointer field
            if fp:
                fields.append(fp.group(1))
                continue
            decl = re.sub(r"\[[^\]]*\]", "", decl)  # array dimensions
            head, *more = decl.split(",")
            fields.append(re.findall(r"\w+", head)[-1])
            fields += [re.findall(r"\w+", d)[-1] for d in more]
        out.append((m.group(2), fields))
    return out


def _enumerators(path: Path) -> list[str]:
    names = []
    for m in re.finditer(r"enum\s*\w*\s*\{(.*?)\}", _code(path), re.S):
        names += [re.match(r"\s*(\w+)", e).group(1) for e in m.group(1).split(",") if e.strip()]
    return names


def _macros(path: Path) -> list[tuple[str, str]]:
    """(name, value text) of every object-like OGK_* macro with a value."""
    text = _strip_comments(path.read_text()).replace("\\\n", " ")
    out = []
    for m in re.finditer(r"(?m)^\s*#\s*define\s+(OGK_\w+)(?![\w(])[ \t]*(.*)$", text):
        if m.group(2).strip():
            out.append((m.group(1), m.group(2).strip()))
    return out


FUNCTIONS = [(h.name, ret, name) for h in HEADERS for ret, name in _functions(h)]
STRUCTS = [(h.name, name, fields) for h in HEADERS for name, fields in _structs(h)]
ENUMERATORS = [(h.name, name) for h in HEADERS for name in _enumerators(h)]
MACROS = [(h.name, name, value) for h in HEADERS for name, value in _macros(h)]
_VALUES = {name: value for _, name, value in MACROS}


_FLOAT_LIMIT = r"(?:DBL|FLT)_(?:EPSILON|MAX|MIN)|HUGE_VALF?"


def _resolved(value: str) -> str:
    """A macro that is another macro's name stands for that macro's value."""
    for _ in range(8):
        if value not in _VALUES:
            break
        value = _VALUES[value]
    return value


@pytest.mark.req("OGK-HAR-010")
def test_scan_found_the_api() -> None:
    """The scan itself works (guards against a regex that silently matches nothing)."""
    names = {n for _, _, n in FUNCTIONS}
    assert {"ogk_cpd_step", "ogk_nog_sample", "ogk_mpsp_solve", "ogk_rk4_propagate",
            "ogk_sil_cpd_step_batch"} <= names
    assert len(FUNCTIONS) > 50
    structs = {n: f for _, n, f in STRUCTS}
    assert "rhs" in structs["ogk_rk4_problem_t"]
    assert "entry" in structs["ogk_nog_table_t"]
    assert len(MACROS) > 50
    assert {"ogk_thrust_cmd_to_rtn", "ogk_nmpc_thrust_cmd", "ogk_mpsp_thrust_cmd",
            "ogk_blt_thrust_cmd", "ogk_nmpc_interval", "ogk_blt_jacobian"} <= names


#: the test entry points moved out of the public headers (issue 18), by test header
MOVED = {
    "nmpc_test.h": {"ogk_nmpc_model_rhs", "ogk_nmpc_interval"},
    "mpsp_test.h": {"ogk_mpsp_step_jacobian", "ogk_mpsp_switch_jump"},
    "blt_test.h": {"ogk_blt_jacobian"},
}


@pytest.mark.req("OGK-HAR-010")
def test_test_headers_found() -> None:
    """Each test header is scanned and holds (at least) what moved into it."""
    names = {h.name for h in TEST_HEADERS}
    assert set(MOVED) <= names
    for h in TEST_HEADERS:
        assert {n for _, n in _functions(h)} >= MOVED.get(h.name, set()), h.name


@pytest.mark.req("OGK-HAR-010")
@pytest.mark.parametrize("header", TEST_HEADERS, ids=[h.name for h in TEST_HEADERS])
def test_test_entry_points_not_public(header: Path) -> None:
    """A test entry point is declared by its test header only, and the law's public header
    points there (ogk/<law>.h names ogk/internal/<law>_test.h)."""
    public = {n for h in PUBLIC_HEADERS for _, n in _functions(h)}
    hooks = {n for _, n in _functions(header)}
    assert hooks, f"{header.name} declares no function"
    assert not hooks & public, f"{sorted(hooks & public)} also in a public header"
    law = header.name.removesuffix("_test.h")
    public_header = ROOT / "kernel" / "include" / "ogk" / f"{law}.h"
    assert f"ogk/internal/{header.name}" in public_header.read_text(), public_header.name


@pytest.mark.req("OGK-HAR-010")
@pytest.mark.parametrize("header,ret,name", FUNCTIONS, ids=[f[2] for f in FUNCTIONS])
def test_function_reachable(header: str, ret: str, name: str) -> None:
    its_ffi, its_lib = bound(header)
    assert hasattr(its_lib, name), f"{header}: {name} missing from the bindings"
    assert ret == "ogk_status", f"{header}: {name} must return ogk_status (returns {ret})"
    assert its_ffi.typeof(getattr(its_lib, name)).result is its_ffi.typeof("ogk_status")


@pytest.mark.req("OGK-HAR-010")
@pytest.mark.parametrize("header,name,fields", STRUCTS, ids=[s[1] for s in STRUCTS])
def test_struct_fields(header: str, name: str, fields: list[str]) -> None:
    have = [f for f, _ in bound(header)[0].typeof(name).fields]
    assert have == fields, f"{header}: {name} fields differ (header {fields}, bindings {have})"


@pytest.mark.req("OGK-HAR-010")
@pytest.mark.parametrize("header,name", ENUMERATORS, ids=[e[1] for e in ENUMERATORS])
def test_enumerator_readable(header: str, name: str) -> None:
    assert isinstance(getattr(bound(header)[1], name), int), f"{header}: {name}"


@pytest.mark.req("OGK-HAR-010")
@pytest.mark.parametrize("header,name,value", MACROS, ids=[m[1] for m in MACROS])
def test_macro_readable(header: str, name: str, value: str) -> None:
    v = getattr(bound(header)[1], name)
    value = _resolved(value)
    if value.startswith('"'):
        assert ffi.string(v).decode() == value.strip('"')
    elif (not re.search(r"0[xX]", value) and re.search(r"\d\.\d*|\d[eE][-+]?\d", value)) or \
            re.fullmatch(_FLOAT_LIMIT, value):
        # a floating literal, or a floating limit of <float.h> / <math.h> (ogk/real.h's
        # OGK_REAL_EPSILON is DBL_EPSILON, FLT_EPSILON in the float build)
        assert isinstance(v, float)
        if re.fullmatch(r"[-+]?[\d.]+(?:[eE][-+]?\d+)?", value):
            assert v == float(value)
    else:
        assert isinstance(v, int), f"{header}: {name} is not an integer"
        # a macro defined in several #if branches (OGK_MPSP_H_LANES: 2 with SSE2, else 1) must
        # take one of its definitions' values in this build; a single definition, exactly it
        branches = [_resolved(val) for _, n, val in MACROS if n == name]
        literal = r"(0[xX][0-9a-fA-F]+|\d+)[uUlL]*"
        if all(re.fullmatch(literal, b) for b in branches):
            assert v in {int(b.rstrip("uUlL"), 0) for b in branches}, f"{header}: {name}"


@pytest.mark.req("OGK-HAR-010", "OGK-CORE-019")
def test_thrust_cmd_wrapper_covers_the_struct() -> None:
    """kernel.ThrustCmd carries every field of ogk_thrust_cmd_t through to_c / from_c, and Frame
    is ogk_frame_t (the typed wrapper every law's thrust_cmd(t) returns)."""
    from ogk_bindings.kernel import Frame, ThrustCmd

    assert {f.name: int(f) for f in Frame} == {
        "RTN": lib.OGK_FRAME_RTN, "INERTIAL": lib.OGK_FRAME_INERTIAL, "SYNODIC": lib.OGK_FRAME_SYNODIC}
    assert len(Frame) == lib.OGK_FRAME_COUNT
    wrapped = {"t_s", "alpha_rad", "beta_rad", "flags", "law_flags", "frame", "u", "throttle"}
    assert {f for f, _ in ffi.typeof("ogk_thrust_cmd_t").fields} == wrapped
    c = ffi.new("ogk_thrust_cmd_t *")
    assert lib.ogk_thrust_cmd_from_angles(2.5, 0.3, -0.2, 0.5, lib.OGK_THRUST_FLAG_ENGINE_ON, 7, c) == lib.OGK_OK
    cmd = ThrustCmd.from_c(c)
    assert (cmd.t, cmd.frame, cmd.alpha, cmd.beta, cmd.throttle, cmd.law_flags) == (2.5, Frame.RTN, 0.3, -0.2, 0.5, 7)
    assert cmd.engine_on and not cmd.safe
    back = cmd.to_c()
    assert bytes(ffi.buffer(back)) == bytes(ffi.buffer(c))
