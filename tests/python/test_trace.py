"""The traceability check (tests/trace/check_trace.py, `make trace`) on a small made-up tree: every
fault it exists for is reported on its own line naming the file and test, a clean tree passes, and
the matrix it writes is what it then checks against."""
from __future__ import annotations

import importlib.util
import sys
import textwrap
from pathlib import Path

import pytest

pytestmark = pytest.mark.req("OGK-HAR-014")

ROOT = Path(__file__).resolve().parents[2]
_spec = importlib.util.spec_from_file_location("check_trace", ROOT / "tests" / "trace" / "check_trace.py")
assert _spec is not None and _spec.loader is not None
check_trace = importlib.util.module_from_spec(_spec)
sys.modules["check_trace"] = check_trace   # dataclasses look their module up
_spec.loader.exec_module(check_trace)

REQS = """\
# reqs
- **OGK-AAA-001 First.** text
- **OGK-AAA-002 Second.** text
- **OGK-BBB-001 Third.** text
"""
C_SRC = """\
#include "ogk_test.h"
/* what it checks */
/* req: OGK-AAA-001 */
static void test_one(void **state) { (void)state; }

static void test_two(void **state) { (void)state; }
int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_one), cmocka_unit_test(test_two)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
"""
PY_SRC = """\
import pytest

pytestmark = pytest.mark.req("OGK-AAA-002")


@pytest.mark.req("OGK-BBB-001")
def test_a():
    pass


class TestGroup:
    def test_b(self):
        pass
"""
PY_UNTAGGED = """\
import pytest


@pytest.mark.slow
def test_c():
    pass


@pytest.mark.skip(reason="x")
@pytest.mark.req("OGK-AAA-009", "AAA-1")
def test_d():
    pass
"""


def make_tree(root: Path, c_src: str = C_SRC, py: dict[str, str] | None = None, gates: str = "") -> Path:
    (root / "docs" / "evidence").mkdir(parents=True)
    (root / "docs" / "evidence" / "requirements.md").write_text(REQS)
    (root / "tests" / "unit").mkdir(parents=True)
    (root / "tests" / "unit" / "test_x.c").write_text(c_src)
    (root / "tests" / "python").mkdir()
    for name, src in (py or {"test_y.py": PY_SRC}).items():
        (root / "tests" / "python" / name).write_text(src)
    (root / "tests" / "trace").mkdir()
    (root / "tests" / "trace" / "gates.txt").write_text(gates)
    (root / "Makefile").write_text("lint: | apt\n\techo\n")
    return root


def run(root: Path, capsys: pytest.CaptureFixture[str], *args: str) -> tuple[int, list[str]]:
    rc = check_trace.main(["--root", str(root), *args])
    return rc, capsys.readouterr().out.splitlines()


def test_untagged_c_test_is_named_and_the_tree_fails(tmp_path: Path, capsys) -> None:
    root = make_tree(tmp_path)
    rc, out = run(root, capsys, "--write")
    assert rc == 1
    assert "trace: untagged test: tests/unit/test_x.c::test_two (add '/* req: OGK-... */' just above its definition)" in out
    assert not any("test_one" in line for line in out)


def test_clean_tree_passes_and_a_stale_matrix_fails(tmp_path: Path, capsys) -> None:
    c_src = C_SRC.replace("\nstatic void test_two", "\n/* req: OGK-AAA-001\n * OGK-AAA-002 on the next line is not a tag */\nstatic void test_two")
    root = make_tree(tmp_path, c_src=c_src)
    assert run(root, capsys, "--write")[0] == 0
    matrix = (root / "docs" / "evidence" / "traceability.md").read_text()
    assert "- **OGK-BBB-001** Third (1)\n  - `tests/python/test_y.py::test_a`" in matrix
    assert "- `TestGroup::test_b`: OGK-AAA-002" in matrix
    assert "- `test_two`: OGK-AAA-001\n" in matrix
    rc, out = run(root, capsys)
    assert rc == 0 and out[-1].startswith("trace: 3 requirements, each verified; 4 tests and 0 gates")
    (root / "docs" / "evidence" / "requirements.md").write_text(REQS.replace("Third", "Third, renamed"))
    rc, out = run(root, capsys)
    assert rc == 1 and "trace: docs/evidence/traceability.md is stale: run `make trace-matrix` and commit it" in out


def test_unknown_malformed_untested_skipped_and_slow_only(tmp_path: Path, capsys) -> None:
    root = make_tree(tmp_path, py={"test_y.py": PY_UNTAGGED},
                     c_src=C_SRC.replace("OGK-AAA-001 */", "OGK-AAA-001 OGK-ZZZ-001 */"))
    rc, out = run(root, capsys, "--write")
    assert rc == 1
    expected = [
        "trace: untagged test: tests/python/test_y.py::test_c (add @pytest.mark.req(\"OGK-...\") or a module pytestmark)",
        "trace: tests/python/test_y.py::test_d: skipped unconditionally (a skipped test verifies nothing)",
        "trace: unknown requirement OGK-ZZZ-001 in tests/unit/test_x.c::test_one (not in docs/evidence/requirements.md)",
        "trace: unknown requirement OGK-AAA-009 in tests/python/test_y.py::test_d (not in docs/evidence/requirements.md)",
        "trace: malformed tag 'AAA-1' in tests/python/test_y.py::test_d (want OGK-XXX-NNN)",
        "trace: requirement without a test: OGK-AAA-002 Second",
        "trace: requirement without a test: OGK-BBB-001 Third",
    ]
    for line in expected:
        assert line in out, line


def test_gate_map_names_real_targets(tmp_path: Path, capsys) -> None:
    gates = textwrap.dedent("""\
        # comment
        lint: OGK-AAA-002 OGK-BBB-001  # strict compile
        no-such-target: OGK-AAA-002
        not a line
        """)
    root = make_tree(tmp_path, gates=gates, c_src=C_SRC.replace("\nstatic void test_two", "\n/* req: OGK-AAA-001 */\nstatic void test_two"))
    rc, out = run(root, capsys, "--write")
    assert rc == 1
    assert "trace: tests/trace/gates.txt:3: 'no-such-target' is not a make target" in out
    assert "trace: tests/trace/gates.txt:4: want 'make-target: OGK-... OGK-...  # what fails'" in out
    assert not any("requirement without a test" in line for line in out)
    assert "  - `make lint`" in (root / "docs" / "evidence" / "traceability.md").read_text()


def test_duplicate_and_malformed_requirement_lines(tmp_path: Path, capsys) -> None:
    root = make_tree(tmp_path)
    (root / "docs" / "evidence" / "requirements.md").write_text(REQS + "- **OGK-AAA-001 Again.** x\n- **OGK-AAA-3 Bad** x\n")
    rc, out = run(root, capsys, "--write")
    assert rc == 1
    assert "trace: requirements.md:5: requirement OGK-AAA-001 defined twice" in out
    assert any(line.startswith("trace: requirements.md:6: malformed requirement line") for line in out)


def test_the_repository_traces(capsys) -> None:
    """The committed tree itself: what `make trace` checks in `make test`."""
    rc, out = run(ROOT, capsys)
    assert rc == 0, "\n".join(out)
