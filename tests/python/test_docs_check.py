"""The documentation's link check (tests/docs/check_docs.py, `make docs-check`) on a small made-up
tree: a clean tree passes; a broken relative link, a docs/ or notes/ path that does not exist and a
dated work note under docs/ each fail on a line naming the file. The repository's own docs pass."""
from __future__ import annotations

import importlib.util
from pathlib import Path

import pytest

pytestmark = pytest.mark.req("OGK-HAR-024")

ROOT = Path(__file__).resolve().parents[2]
_spec = importlib.util.spec_from_file_location("check_docs", ROOT / "tests" / "docs" / "check_docs.py")
assert _spec is not None and _spec.loader is not None
check_docs = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(check_docs)


def make_tree(root: Path) -> Path:
    (root / "docs" / "guides").mkdir(parents=True)
    (root / "notes").mkdir()
    (root / "notes" / "session-1.md").write_text("# history\n")
    (root / "docs" / "index.md").write_text("Start: [build](guides/build.md#make).\n")
    (root / "docs" / "guides" / "build.md").write_text(
        "# Build\nSee docs/index.md and [home](../index.md); history: notes/session-1.md.\n"
        "```\n[not a link](in/a/code/block.md)\n```\n")
    (root / "README.md").write_text("Docs: docs/index.md, ../shared/docs/STYLE.md is not ours.\n")
    return root


def run(root: Path, capsys: pytest.CaptureFixture[str]) -> tuple[int, list[str]]:
    rc = check_docs.main(["--root", str(root)])
    return rc, capsys.readouterr().out.splitlines()


def test_a_clean_tree_passes(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    rc, out = run(make_tree(tmp_path), capsys)
    assert rc == 0, out


def test_each_fault_is_one_line(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    root = make_tree(tmp_path)
    page = root / "docs" / "guides" / "build.md"
    gone = "[gone](cmake.md), docs/guides/gone.md, notes/session-2.md.\n"  # docs-check: ignore
    page.write_text(page.read_text() + gone)
    (root / "docs" / "notes").mkdir()
    (root / "docs" / "notes" / "session-3.md").write_text("# dated\n")
    rc, out = run(root, capsys)
    assert rc == 1
    assert "docs: docs/guides/build.md:6: link to cmake.md: no such file" in out
    assert "docs: docs/guides/build.md:6: docs/guides/gone.md: no such file" in out  # docs-check: ignore
    assert "docs: docs/guides/build.md:6: notes/session-2.md: no such file" in out  # docs-check: ignore
    assert any(line.startswith("docs: docs/notes: a dated work note") for line in out)  # docs-check: ignore
    note = "docs: docs/notes/session-3.md: a dated work note"  # docs-check: ignore
    assert any(line.startswith(note) for line in out)
    assert out[-1].startswith("docs: FAILED, 5 problem(s)")


def test_the_repository_passes(capsys: pytest.CaptureFixture[str]) -> None:
    rc, out = run(ROOT, capsys)
    assert rc == 0, out
