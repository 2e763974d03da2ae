#!/usr/bin/env python3
"""The public API of ogk as a digest, and the check that a change to it comes with its version bump.

`make api-check` (in `make test`) compares the public headers with the interface recorded for the
last release (api/ogk-X.Y.Z.api, the highest version there) and fails when they differ by more than
the version in kernel/include/ogk/version.h allows; `make api-record` records the current interface
under the current version (CHANGELOG.md, "Versioning").

The digest: the public headers kernel/include/ogk/*.h (ogk/internal/ is no API) preprocessed by gcc
with their #defines kept (-dD), and without the host's predefined macros and C library (-undef
-nostdinc, empty stand-ins for <stdint.h> & co.), so the digest is the same on any machine. Per header:
every macro with its value, every top-level declaration (function prototype, typedef with its struct or
enum body, extern object), tokens joined by single spaces, parameter names dropped (renaming one breaks
no caller). A declaration that depends on the target (mpsp.h's SSE2 fields) is recorded per variant.

The rule (semantic versioning; the 0.x row as Cargo reads it, the minor number being the breaking one
while the major is 0 -- the same as ogkConfigVersion.cmake's SameMinorVersion for 0.x):
    removed or changed entry  incompatible  major bump (0.x: minor bump)
    added entries only        compatible    minor bump (0.x: patch bump)
A bump that covers the change passes, with the reminder to record at the release.

ogk/real.h's names are compared as the default build compiles them (as_compiled): a declaration spelled
`ogk_real_t` where the record says `double`, or a macro `OGK_R(1.0e4)` or `OGK_REAL_TINY` where it says
`1.0e4` or `1.0e-300`, is the same declaration (the type is double unless OGK_REAL_SINGLE=1, and a double
literal cast to double is that literal); a real that becomes float, or real.h's own typedef, still changes.

Usage: check_api.py check|record [--include DIR] [--api-dir DIR] [--cc GCC]
"""
from __future__ import annotations

import argparse
import re
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
# System headers the public headers include: empty stand-ins (their types stay names in the digest).
STUB_HEADERS = ("stdint.h", "stddef.h", "stdbool.h", "float.h", "math.h", "string.h", "limits.h")
# Target variants: "" is every target without SSE2 (Cortex-M7, SPARC), "sse2" the x86-64 host.
VARIANTS = (("", ()), ("sse2", ("-D__SSE2__",)))
TOKEN = re.compile(r'"(?:\\.|[^"\\])*"|\'(?:\\.|[^\'\\])*\'|[A-Za-z_]\w*|\.?\d(?:[eEpP][+-]|[\w.])*'
                   r'|\.\.\.|->|<<|>>|[<>=!]=|&&|\|\||##|\S')
LINE_MARKER = re.compile(r'^# \d+ "([^"]+)"')
DEFINE = re.compile(r"^#define\s+(\w+(?:\([^)]*\))?)\s*(.*)$")
VERSION = re.compile(r"^#define OGK_VERSION_(MAJOR|MINOR|PATCH) +(\d+) *$", re.M)
C_WORDS = {"void", "char", "short", "int", "long", "float", "double", "signed", "unsigned", "const",
           "volatile", "restrict", "struct", "union", "enum", "_Bool"}
IDENT = re.compile(r"^[A-Za-z_]\w*$")
VERSION_MACROS = {"OGK_VERSION_MAJOR", "OGK_VERSION_MINOR", "OGK_VERSION_PATCH", "OGK_VERSION_STRING"}


def tokens(text: str) -> list[str]:
    return TOKEN.findall(text)


def split_declarations(toks: list[str]) -> list[list[str]]:
    """Top-level declarations: up to a ';' outside any bracket."""
    out: list[list[str]] = []
    cur: list[str] = []
    depth = 0
    for t in toks:
        cur.append(t)
        if t in "({[":
            depth += 1
        elif t in ")}]":
            depth -= 1
        elif t == ";" and depth == 0:
            out.append(cur[:-1])
            cur = []
    if cur:
        out.append(cur)
    return out


def matching(toks: list[str], i: int) -> int:
    """Index of the bracket closing the one at i."""
    depth = 0
    for j in range(i, len(toks)):
        if toks[j] in "({[":
            depth += 1
        elif toks[j] in ")}]":
            depth -= 1
            if depth == 0:
                return j
    return len(toks) - 1


def drop_param_name(param: list[str]) -> list[str]:
    """`const double *x` -> `const double *`, `double u [ 3u ]` -> `double [ 3u ]`."""
    core = list(param)
    suffix: list[str] = []
    while core and core[-1] == "]":
        start = max(i for i, t in enumerate(core) if t == "[")
        suffix = core[start:] + suffix
        core = core[:start]
    if (len(core) >= 2 and IDENT.match(core[-1]) and core[-1] not in C_WORDS
            and core[-2] not in ("struct", "union", "enum")):
        core = core[:-1]
    return core + suffix


def strip_parameter_names(toks: list[str], top: bool = True) -> list[str]:
    """Every parameter list: outside braces each parenthesised group but `( * name )`; inside a
    struct body only the group after `( * name )` (a callback field's)."""
    out: list[str] = []
    i = 0
    while i < len(toks):
        t = toks[i]
        if t == "{":
            j = matching(toks, i)
            out += ["{", *strip_parameter_names(toks[i + 1:j], top=False), "}"]
            i = j + 1
            continue
        if t == "(":
            j = matching(toks, i)
            inner = toks[i + 1:j]
            if inner and inner[0] != "*" and (top or (out and out[-1] == ")")):
                params: list[list[str]] = [[]]
                depth = 0
                for u in inner:
                    if u == "," and depth == 0:
                        params.append([])
                        continue
                    depth += (u in "([") - (u in ")]")
                    params[-1].append(u)
                out.append("(")
                for n, p in enumerate(params):
                    if n:
                        out.append(",")
                    out.extend(drop_param_name(p))
                out.append(")")
            else:
                out.extend(toks[i:j + 1])
            i = j + 1
            continue
        out.append(t)
        i += 1
    return out


def outside_braces(toks: list[str]) -> list[str]:
    out, depth = [], 0
    for t in toks:
        depth += (t == "{") - (t == "}")
        if depth == 0 and t != "}":
            out.append(t)
    return out


def name_of(decl: list[str]) -> tuple[str, str]:
    """(kind, name) of one declaration."""
    top = outside_braces(decl)
    fptr = next((top[i + 2] for i in range(len(top) - 3)
                 if top[i] == "(" and top[i + 1] == "*" and IDENT.match(top[i + 2])), None)
    if top[0] == "typedef":
        if fptr:
            return "type", fptr
        idents = [t for t in top if IDENT.match(t) and t not in C_WORDS]
        return "type", idents[-1]
    if fptr:
        return "object", fptr
    if "(" in top:
        return "func", top[top.index("(") - 1]
    if top[0] in ("struct", "union", "enum") and len(top) == 2:
        return top[0], top[1]
    return "object", [t for t in top if IDENT.match(t)][-1]


def digest_variant(include: Path, defines: tuple[str, ...], cc: str) -> dict[str, str]:
    """key '[header] kind name' -> normalised text, for one target variant."""
    headers = sorted(p.name for p in (include / "ogk").glob("*.h"))
    with tempfile.TemporaryDirectory() as tmp:
        stubs = Path(tmp)
        for h in STUB_HEADERS:
            (stubs / h).write_text("")
        src = stubs / "all.c"
        src.write_text("".join(f'#include "ogk/{h}"\n' for h in headers))
        cmd = [cc, "-E", "-dD", "-undef", "-nostdinc", "-isystem", str(stubs), "-I", str(include),
               *defines, str(src)]
        text = subprocess.run(cmd, check=True, capture_output=True, text=True).stdout
    per_file: dict[str, list[str]] = {}
    entries: dict[str, str] = {}
    current = None
    for line in text.splitlines():
        m = LINE_MARKER.match(line)
        if m:
            path = Path(m.group(1))
            current = path.name if path.parent.name == "ogk" and path.parent.parent == include else None
            continue
        if current is None:
            continue
        d = DEFINE.match(line)
        if d:
            name, value = d.group(1), " ".join(tokens(d.group(2)))
            # include guards are no API; the version numbers are what the digest is compared against
            if not (name.endswith("_H") and not value) and name not in VERSION_MACROS:
                entries[f"[{current}] macro {name}"] = value
        elif not line.startswith("#"):
            per_file.setdefault(current, []).append(line)
    for header, lines in per_file.items():
        for decl in split_declarations(tokens("\n".join(lines))):
            if decl:
                kind, name = name_of(decl)
                entries[f"[{header}] {kind} {name}"] = " ".join(strip_parameter_names(decl))
    return entries


def digest(include: Path, cc: str = "gcc") -> dict[str, str]:
    """Every variant's entries; an entry that differs between variants is kept once per variant."""
    per = {name: digest_variant(include, defs, cc) for name, defs in VARIANTS}
    out: dict[str, str] = {}
    for key in sorted(set().union(*per.values())):
        values = {name: per[name].get(key) for name, _ in VARIANTS}
        if len(set(values.values())) == 1:
            out[key] = next(iter(values.values()))  # type: ignore[assignment]
        else:
            for name, value in values.items():
                if value is not None:
                    out[f"{key} @{name or 'no-sse2'}"] = value
    return out


# ogk/real.h's names, read as the default build compiles them (CHANGELOG.md, "Versioning"): the kernel's
# reals became ogk_real_t, which is double unless OGK_REAL_SINGLE=1, and its floating literals OGK_R(x),
# which is the cast of a double literal to double there. An entry whose text differs from the recorded
# one only by these spellings declares the same thing and is no change.
REAL_HEADER = "real.h"
FLOAT_LITERAL = re.compile(r"^(?:\d+\.\d*|\.\d+|\d+(?=[eE]))(?:[eE][-+]?\d+)?$")


def as_compiled(entries: dict[str, str]) -> dict[str, str]:
    """Every entry outside real.h with real.h's names (as `entries` define them) replaced by what the
    default build makes of them: ogk_real_t by its typedef's type, real.h's object-like macros
    (OGK_REAL_TINY, ...) by their values, then OGK_R ( <floating literal> ) by the literal. real.h's own
    entries, and entries that use none of its names, come back as they are."""
    typedef = entries.get(f"[{REAL_HEADER}] type ogk_real_t", "")
    toks = typedef.split(" ")
    real_type = toks[1:-1] if len(toks) > 2 and toks[0] == "typedef" and toks[-1] == "ogk_real_t" else []
    macros = {k.split(" ")[-1]: v.split(" ") for k, v in entries.items()
              if k.startswith(f"[{REAL_HEADER}] macro ") and "(" not in k.split(" ")[-1]}
    out: dict[str, str] = {}
    for key, text in entries.items():
        if key.startswith(f"[{REAL_HEADER}]"):
            out[key] = text
            continue
        words = text.split(" ")
        for _ in range(8):  # a macro of real.h may name another
            new: list[str] = []
            for w in words:
                if w == "ogk_real_t" and real_type:
                    new.extend(real_type)
                elif w in macros:
                    new.extend(macros[w])
                else:
                    new.append(w)
            if new == words:
                break
            words = new
        i, flat = 0, []
        while i < len(words):
            if (words[i:i + 2] == ["OGK_R", "("] and i + 3 < len(words) and words[i + 3] == ")"
                    and FLOAT_LITERAL.match(words[i + 2])):
                flat.append(words[i + 2])
                i += 4
            else:
                flat.append(words[i])
                i += 1
        out[key] = " ".join(flat)
    return out


def read_version(include: Path) -> tuple[int, int, int]:
    text = (include / "ogk" / "version.h").read_text()
    parts = dict(VERSION.findall(text))
    if set(parts) != {"MAJOR", "MINOR", "PATCH"}:
        raise SystemExit("api-check: ogk/version.h: no OGK_VERSION_MAJOR/MINOR/PATCH")
    version = (int(parts["MAJOR"]), int(parts["MINOR"]), int(parts["PATCH"]))
    string = re.search(r'^#define OGK_VERSION_STRING "([^"]*)"', text, re.M)
    if not string or string.group(1) != "%d.%d.%d" % version:
        raise SystemExit(f"api-check: FAILED: ogk/version.h: OGK_VERSION_STRING is not {'%d.%d.%d' % version}")
    return version


def vtext(v: tuple[int, int, int]) -> str:
    return "%d.%d.%d" % v


def write_record(path: Path, version: tuple[int, int, int], entries: dict[str, str]) -> None:
    lines = ["# The public API of ogk " + vtext(version) + ", recorded by `make api-record` "
             "(tests/api/check_api.py): one line per header entry, `[header] kind name = text`.",
             "version " + vtext(version)]
    lines += [f"{k} = {v}" for k, v in sorted(entries.items())]
    path.write_text("\n".join(lines) + "\n")


def read_record(path: Path) -> tuple[tuple[int, int, int], dict[str, str]]:
    version = None
    entries: dict[str, str] = {}
    for line in path.read_text().splitlines():
        if line.startswith("version "):
            a, b, c = line.split()[1].split(".")
            version = (int(a), int(b), int(c))
        elif line.startswith("["):
            key, _, value = line.partition(" = ")
            entries[key] = value
    if version is None:
        raise SystemExit(f"api-check: {path}: no version line")
    return version, entries


def latest_record(api_dir: Path) -> Path | None:
    records = [(tuple(int(x) for x in m.groups()), p) for p in api_dir.glob("ogk-*.api")
               if (m := re.fullmatch(r"ogk-(\d+)\.(\d+)\.(\d+)\.api", p.name))]
    return max(records)[1] if records else None


def needed_bump(recorded: tuple[int, int, int], incompatible: bool) -> tuple[int, int, int]:
    """The smallest version that allows the change."""
    major, minor, patch = recorded
    if major == 0:
        return (0, minor + 1, 0) if incompatible else (0, minor, patch + 1)
    return (major + 1, 0, 0) if incompatible else (major, minor + 1, 0)


def first_difference(old: str, new: str) -> str:
    a, b = old.split(" "), new.split(" ")
    i = next((k for k in range(min(len(a), len(b))) if a[k] != b[k]), min(len(a), len(b)))
    lo = max(0, i - 6)
    return f"recorded '... {' '.join(a[lo:i + 8])} ...', now '... {' '.join(b[lo:i + 8])} ...'"


def check(include: Path, api_dir: Path, cc: str) -> int:
    version = read_version(include)
    record = latest_record(api_dir)
    if record is None:
        print(f"api-check: FAILED: no recorded interface in {api_dir} (make api-record)")
        return 1
    rec_version, recorded = read_record(record)
    current = digest(include, cc)
    removed = sorted(set(recorded) - set(current))
    added = sorted(set(current) - set(recorded))
    compiled, compiled_record = as_compiled(current), as_compiled(recorded)
    differ = [k for k in set(recorded) & set(current) if recorded[k] != current[k]]
    changed = sorted(k for k in differ if compiled_record[k] != compiled[k])
    respelled = len(differ) - len(changed)
    rel = record.relative_to(ROOT) if record.is_relative_to(ROOT) else record
    if respelled:
        print(f"api-check: {respelled} entries differ from {vtext(rec_version)}'s only in the spelling of "
              "ogk/real.h's names (ogk_real_t / double, OGK_R(x) / x, OGK_REAL_*): the same declarations in "
              "the default build, no change")
    if not (removed or added or changed):
        print(f"api-check: the public API is the one recorded for {vtext(rec_version)} ({rel}, "
              f"{len(current)} entries); version.h says {vtext(version)}")
        return 0
    for k in removed:
        print(f"  removed: {k}")
    for k in changed:
        print(f"  changed: {k}: {first_difference(recorded[k], current[k])}")
    for k in added:
        print(f"  added:   {k}")
    incompatible = bool(removed or changed)
    need = needed_bump(rec_version, incompatible)
    what = ("incompatible (removed or changed entries): a major bump, the minor one while the major is 0"
            if incompatible else "compatible (added entries only): a minor bump, the patch one while the major is 0")
    if version >= need:
        print(f"api-check: the public API differs from {vtext(rec_version)}'s ({rel}) as listed above, "
              f"{what}; version.h's {vtext(version)} covers it. Record it when {vtext(version)} is "
              f"released: make api-record")
        return 0
    print(f"api-check: FAILED: the public API differs from {vtext(rec_version)}'s ({rel}) as listed above, "
          f"{what}: kernel/include/ogk/version.h must say at least {vtext(need)} (it says {vtext(version)}). "
          f"Bump it (and CHANGELOG.md), then record the interface at the release: make api-record")
    return 1


def main(argv: list[str]) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("action", choices=("check", "record"))
    ap.add_argument("--include", type=Path, default=ROOT / "kernel" / "include")
    ap.add_argument("--api-dir", type=Path, default=ROOT / "api")
    ap.add_argument("--cc", default="gcc")
    a = ap.parse_args(argv)
    include = a.include.resolve()
    if a.action == "check":
        return check(include, a.api_dir.resolve(), a.cc)
    version = read_version(include)
    entries = digest(include, a.cc)
    a.api_dir.mkdir(parents=True, exist_ok=True)
    path = a.api_dir / f"ogk-{vtext(version)}.api"
    write_record(path, version, entries)
    print(f"api-record: {len(entries)} entries of the public API of {vtext(version)} written to {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
