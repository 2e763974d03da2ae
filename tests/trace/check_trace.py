#!/usr/bin/env python3
"""Requirements traceability of ogk (`make trace`, run by `make test`; docs/evidence/requirements.md).

Reads the requirements of docs/evidence/requirements.md (`- **OGK-XXX-NNN Title.** text`), the tags of the
tests and the gate map, and checks that

- every C unit test (a function named in `cmocka_unit_test*(...)` in tests/unit/**/test_*.c) carries a
  `/* req: OGK-... */` comment in the comment block just above its definition;
- every Python test (tests/python/test_*.py, `def test_*`, also in `class Test*`) carries
  `@pytest.mark.req("OGK-...", ...)` or its module's `pytestmark` does (parsed from the AST: no
  import, no collection);
- every tag names a defined requirement, every requirement is verified by at least one test or gate,
  no test is skipped unconditionally, every target of tests/trace/gates.txt is a make target;
- the committed matrix docs/evidence/traceability.md is the one these tags generate.

Every problem is printed on one line naming the file and test; exit 1 if there is any.
`--write` regenerates docs/evidence/traceability.md (then the other checks still run).

Usage: check_trace.py [--write] [--root DIR]
"""
from __future__ import annotations

import argparse
import ast
import re
import sys
from collections import defaultdict
from dataclasses import dataclass, field
from pathlib import Path

REQ_DEF = re.compile(r"^- \*\*(OGK-[A-Z]+-\d{3}) ([^*]+?)\*\*")
REQ_ID = re.compile(r"^OGK-[A-Z]+-\d{3}$")
C_TAG = re.compile(r"\breq:\s*(.*?)\s*(?:\*/|$)")
C_REGISTERED = re.compile(r"\bcmocka_unit_test\w*\(\s*(\w+)")
MAKE_TARGET = re.compile(r"^([A-Za-z0-9_.%-][A-Za-z0-9_. %-]*?)\s*:(?!=)")
GATE_LINE = re.compile(r"^([A-Za-z0-9_-]+)\s*:\s*([^#]*)(?:#\s*(.*))?$")


@dataclass
class Test:
    tid: str                      # path::name
    reqs: list[str] = field(default_factory=list)
    note: str = ""                # "slow", "skipif", "gate"


@dataclass
class Report:
    problems: list[str] = field(default_factory=list)

    def add(self, msg: str) -> None:
        self.problems.append(msg)


def read_requirements(path: Path, rep: Report) -> dict[str, str]:
    reqs: dict[str, str] = {}
    for n, line in enumerate(path.read_text().splitlines(), 1):
        m = REQ_DEF.match(line)
        if m:
            rid, title = m.group(1), m.group(2).strip().rstrip(".")
            if rid in reqs:
                rep.add(f"{path.name}:{n}: requirement {rid} defined twice")
            reqs[rid] = title
        elif re.match(r"^- \*\*OGK-", line):
            rep.add(f"{path.name}:{n}: malformed requirement line (want '- **OGK-XXX-NNN Title.** text')")
    return reqs


def split_ids(text: str) -> list[str]:
    return [t for t in re.split(r"[\s,]+", text.strip()) if t]


def c_tests(root: Path, rep: Report) -> list[Test]:
    tests: list[Test] = []
    for path in sorted((root / "tests" / "unit").rglob("test_*.c")):
        rel = path.relative_to(root).as_posix()
        lines = path.read_text().splitlines()
        text = "\n".join(lines)
        names = list(dict.fromkeys(C_REGISTERED.findall(text)))
        for name in names:
            define = re.compile(r"^\s*(?:static\s+)?void\s+" + re.escape(name) + r"\s*\(")
            idx = next((i for i, ln in enumerate(lines) if define.match(ln)), None)
            t = Test(f"{rel}::{name}")
            if idx is None:
                rep.add(f"{rel}: {name} is registered but its definition 'static void {name}(' was not found")
                tests.append(t)
                continue
            i = idx - 1
            while i >= 0:
                s = lines[i].strip()
                if not (s.startswith(("/*", "*", "//")) or s.endswith("*/")):
                    break
                m = C_TAG.search(s)
                if m:
                    t.reqs.extend(split_ids(m.group(1)))
                i -= 1
            tests.append(t)
    return tests


def _req_args(node: ast.AST) -> list[str] | None:
    """The ids of a `pytest.mark.req(...)` call, None when node is not one."""
    if not isinstance(node, ast.Call):
        return None
    f = node.func
    if not (isinstance(f, ast.Attribute) and f.attr == "req" and isinstance(f.value, ast.Attribute)
            and f.value.attr == "mark"):
        return None
    return [a.value if isinstance(a, ast.Constant) and isinstance(a.value, str) else f"<not a string: {ast.unparse(a)}>"
            for a in node.args]


def _mark_name(node: ast.AST) -> str:
    """'skip', 'skipif', 'slow', ... for pytest.mark.X or pytest.mark.X(...)."""
    if isinstance(node, ast.Call):
        node = node.func
    if isinstance(node, ast.Attribute) and isinstance(node.value, ast.Attribute) and node.value.attr == "mark":
        return node.attr
    return ""


def _marks(nodes: list[ast.AST]) -> tuple[list[str], set[str]]:
    ids: list[str] = []
    names: set[str] = set()
    for n in nodes:
        r = _req_args(n)
        if r is not None:
            ids.extend(r)
        names.add(_mark_name(n))
    return ids, names


def _pytestmark(body: list[ast.stmt]) -> list[ast.AST]:
    out: list[ast.AST] = []
    for st in body:
        if isinstance(st, ast.Assign) and any(isinstance(t, ast.Name) and t.id == "pytestmark" for t in st.targets):
            v = st.value
            out.extend(v.elts if isinstance(v, (ast.List, ast.Tuple)) else [v])
    return out


def py_tests(root: Path, rep: Report) -> list[Test]:
    tests: list[Test] = []
    for path in sorted((root / "tests" / "python").rglob("test_*.py")):
        rel = path.relative_to(root).as_posix()
        tree = ast.parse(path.read_text(), filename=rel)
        mod_ids, mod_names = _marks(_pytestmark(tree.body))

        def visit(body: list[ast.stmt], prefix: str, ids0: list[str], names0: set[str]) -> None:
            for st in body:
                if isinstance(st, (ast.FunctionDef, ast.AsyncFunctionDef)) and st.name.startswith("test"):
                    ids, names = _marks(st.decorator_list)
                    names |= names0
                    t = Test(f"{rel}::{prefix}{st.name}", ids0 + ids)
                    if "skip" in names:
                        rep.add(f"{t.tid}: skipped unconditionally (a skipped test verifies nothing)")
                    t.note = "slow" if "slow" in names else ("skipif" if "skipif" in names else "")
                    tests.append(t)
                elif isinstance(st, ast.ClassDef) and st.name.startswith("Test"):
                    ids, names = _marks(st.decorator_list + _pytestmark(st.body))
                    visit(st.body, f"{prefix}{st.name}::", ids0 + ids, names0 | names)
        visit(tree.body, "", mod_ids, mod_names)
    return tests


def make_targets(root: Path) -> set[str]:
    targets: set[str] = set()
    files = [root / "Makefile", *sorted(root.glob("**/*.mk"))]
    for f in files:
        if any(p in (".venv", "build", "node_modules") for p in f.relative_to(root).parts):
            continue
        for line in f.read_text().splitlines():
            if line.startswith(("\t", "#", " ")):
                continue
            m = MAKE_TARGET.match(line)
            if m and "$" not in m.group(1):
                targets.update(m.group(1).split())
    return targets


def gate_tests(root: Path, rep: Report) -> list[Test]:
    path = root / "tests" / "trace" / "gates.txt"
    targets = make_targets(root)
    out: list[Test] = []
    for n, line in enumerate(path.read_text().splitlines(), 1):
        s = line.strip()
        if not s or s.startswith("#"):
            continue
        m = GATE_LINE.match(s)
        if not m:
            rep.add(f"tests/trace/gates.txt:{n}: want 'make-target: OGK-... OGK-...  # what fails'")
            continue
        if m.group(1) not in targets:
            rep.add(f"tests/trace/gates.txt:{n}: '{m.group(1)}' is not a make target")
        out.append(Test(f"make {m.group(1)}", split_ids(m.group(2)), "gate"))
    return out


def render(reqs: dict[str, str], tests: list[Test]) -> str:
    by_req: dict[str, list[Test]] = defaultdict(list)
    for t in tests:
        for r in dict.fromkeys(t.reqs):
            by_req[r].append(t)
    groups: dict[str, list[str]] = defaultdict(list)
    for r in reqs:
        groups[r.split("-")[1]].append(r)
    n_c = sum(1 for t in tests if t.tid.endswith(".c") or ".c::" in t.tid)
    n_py = sum(1 for t in tests if ".py::" in t.tid)
    n_g = sum(1 for t in tests if t.note == "gate")
    lines = [
        "# Traceability matrix",
        "",
        "Generated by `make trace-matrix` (tests/trace/check_trace.py --write) from the requirements of",
        "[requirements.md](requirements.md), the `req:` tags of the tests and tests/trace/gates.txt;",
        "`make trace` (in `make test`) fails when this file is stale. Do not edit it by hand.",
        "",
        f"{len(reqs)} requirements; {n_c} C unit tests (cmocka, host ASan+UBSan, Cortex-M7 and Cortex-M4F), "
        f"{n_py} Python tests, {n_g} make gates.",
        "`(slow)`: run by `make test-slow`, not by `make test`.",
        "",
        "| group | requirements | verified by tests | by gates |",
        "|---|---|---|---|",
    ]
    for g, ids in groups.items():
        nt = sum(1 for r in ids if any(t.note != "gate" for t in by_req[r]))
        ng = sum(1 for r in ids if any(t.note == "gate" for t in by_req[r]))
        lines.append(f"| {g} | {len(ids)} | {nt} | {ng} |")
    lines += ["", "## Requirement -> tests", ""]
    for g, ids in groups.items():
        lines += [f"### OGK-{g}", ""]
        for r in ids:
            ts = by_req[r]
            lines.append(f"- **{r}** {reqs[r]} ({len(ts)})")
            for t in sorted(ts, key=lambda x: (x.note != "gate", x.tid)):
                lines.append(f"  - `{t.tid}`" + (" (slow)" if t.note == "slow" else ""))
        lines.append("")
    lines += ["## Test -> requirements", ""]
    cur = ""
    for t in sorted(tests, key=lambda x: (x.note == "gate", x.tid)):
        f = "make gates" if t.note == "gate" else t.tid.split("::")[0]
        if f != cur:
            lines += ["", f"### {f}", ""] if cur else [f"### {f}", ""]
            cur = f
        name = t.tid if t.note == "gate" else t.tid.split("::", 1)[1]
        lines.append(f"- `{name}`: {' '.join(dict.fromkeys(t.reqs))}")
    return "\n".join(lines) + "\n"


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--write", action="store_true", help="regenerate docs/evidence/traceability.md")
    ap.add_argument("--root", type=Path, default=Path(__file__).resolve().parents[2])
    args = ap.parse_args(argv)
    root: Path = args.root
    rep = Report()
    reqs = read_requirements(root / "docs" / "evidence" / "requirements.md", rep)
    tests = c_tests(root, rep) + py_tests(root, rep) + gate_tests(root, rep)
    for t in tests:
        where = t.tid
        if not t.reqs:
            how = ("add '/* req: OGK-... */' just above its definition" if ".c::" in where
                   else "add @pytest.mark.req(\"OGK-...\") or a module pytestmark" if ".py::" in where
                   else "name its requirements in tests/trace/gates.txt")
            rep.add(f"untagged test: {where} ({how})")
        for r in t.reqs:
            if not REQ_ID.match(r):
                rep.add(f"malformed tag '{r}' in {where} (want OGK-XXX-NNN)")
            elif r not in reqs:
                rep.add(f"unknown requirement {r} in {where} (not in docs/evidence/requirements.md)")
    covered = {r for t in tests for r in t.reqs}
    for r in reqs:
        if r not in covered:
            rep.add(f"requirement without a test: {r} {reqs[r]}")
    for r in reqs:
        if r in covered and all(t.note == "slow" for t in tests if r in t.reqs):
            rep.add(f"requirement verified only by slow tests (not in make test): {r}")
    matrix = root / "docs" / "evidence" / "traceability.md"
    text = render(reqs, tests)
    if args.write:
        matrix.write_text(text)
        print(f"trace: wrote {matrix.relative_to(root)}")
    elif not matrix.exists() or matrix.read_text() != text:
        rep.add("docs/evidence/traceability.md is stale: run `make trace-matrix` and commit it")
    for p in rep.problems:
        print(f"trace: {p}")
    n_tests = sum(1 for t in tests if t.note != "gate")
    if rep.problems:
        print(f"trace: FAILED, {len(rep.problems)} problem(s) ({len(reqs)} requirements, {n_tests} tests)")
        return 1
    print(f"trace: {len(reqs)} requirements, each verified; {n_tests} tests and "
          f"{len(tests) - n_tests} gates, each tracing to a requirement (docs/evidence/traceability.md up to date)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
