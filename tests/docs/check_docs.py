#!/usr/bin/env python3
"""Links of the documentation (`make docs-check`, run by `make test`; OGK-HAR-024).

`mkdocs build --strict` checks the Markdown links between the site's pages; the pages also name files
in plain text (`docs/guides/cmake.md`, `notes/session-12.md`), which no Markdown parser sees. This
checks, in docs/**/*.md, README.md and CHANGELOG.md (with --tree: every file git tracks):
- every relative Markdown link resolves to a file or folder of the repository;
- every path written as docs/... or notes/... exists;
- docs/ holds no dated work note (a session-N page, a notes/ folder): those live in notes/.
A line carrying `docs-check: ignore` is skipped.
Stdlib only; one line per problem, exit 1 when there is one.
"""
from __future__ import annotations

import argparse
import re
import subprocess
import sys
from pathlib import Path

LINK = re.compile(r"\]\(([^)\s]+)\)")
# A path of this repository: not the tail of another one (../shared/docs/X, build/docs/X).
PATH = re.compile(r"(?<![\w./-])(?:docs|notes)/[\w./-]*")
IGNORE = "docs-check: ignore"   # on a line that names a missing path on purpose (a test's fixture)
TEXT = {".md", ".py", ".c", ".h", ".mk", ".toml", ".txt", ".yml", ".yaml", ".cmake", ".sh", ".in", ".cfg"}


def doc_files(root: Path) -> list[Path]:
    return sorted(root.glob("docs/**/*.md")) + [p for p in (root / "README.md", root / "CHANGELOG.md")
                                                  if p.exists()]


def tree_files(root: Path) -> list[Path]:
    out = subprocess.run(["git", "ls-files", "-z"], cwd=root, capture_output=True, check=True).stdout
    files = [root / f for f in out.decode().split("\0") if f]
    return [p for p in files if p.is_file() and (p.suffix in TEXT or p.name in ("Makefile", "CMakeLists.txt"))]


def check_file(root: Path, path: Path, problems: list[str]) -> None:
    rel = path.relative_to(root).as_posix()
    in_code = False
    for n, line in enumerate(path.read_text(encoding="utf-8", errors="replace").splitlines(), 1):
        if IGNORE in line:
            continue
        if path.suffix == ".md" and line.lstrip().startswith("```"):
            in_code = not in_code
        if path.suffix == ".md" and not in_code:
            for m in LINK.finditer(line):
                target = m.group(1).split("#", 1)[0]
                if not target or re.match(r"^[a-z][a-z0-9+.-]*:", target):
                    continue   # an anchor on the same page, a URL
                if not (path.parent / target).exists():
                    problems.append(f"{rel}:{n}: link to {m.group(1)}: no such file")
        for m in PATH.finditer(line):
            p = m.group(0).rstrip(".")
            if not (root / p).exists():
                problems.append(f"{rel}:{n}: {p}: no such file")


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--root", type=Path, default=Path(__file__).resolve().parents[2])
    ap.add_argument("--tree", action="store_true", help="every tracked file, not only the documentation")
    args = ap.parse_args(argv)
    root: Path = args.root
    problems: list[str] = []
    files = tree_files(root) if args.tree else doc_files(root)
    for path in files:
        check_file(root, path, problems)
    for path in sorted((root / "docs").rglob("*")):
        if re.fullmatch(r"session-\d+\.md", path.name) or (path.is_dir() and path.name == "notes"):
            problems.append(f"{path.relative_to(root).as_posix()}: a dated work note in docs/ (notes/ holds them)")
    for p in problems:
        print(f"docs: {p}")
    if problems:
        print(f"docs: FAILED, {len(problems)} problem(s) in {len(files)} files")
        return 1
    print(f"docs: {len(files)} files, every link and docs/ or notes/ path resolves; no work note in docs/")
    return 0


if __name__ == "__main__":
    sys.exit(main())
