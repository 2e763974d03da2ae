"""The MISRA ratchet refuses a run in which cppcheck analysed nothing of a source: a source an #error
stops (a guard testing a macro cppcheck cannot see) gives no findings, which would read as clean."""
from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

pytestmark = pytest.mark.req("OGK-CORE-004")

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tests" / "misra"))
from misra_gate import unanalysed  # noqa: E402


def test_a_blinded_source_is_reported(tmp_path):
    (tmp_path / "clean.c").write_text("int twice(int x);\nint twice(int x) { return 2 * x; }\n")
    # the case met in this project: a binary64 guard on <float.h>'s DBL_MANT_DIG, which cppcheck (no
    # system headers) reads as 0, so every configuration it tries stops at the #error
    (tmp_path / "blind.c").write_text("#if DBL_MANT_DIG != 53\n#error double is not binary64\n#endif\n"
                                      "int thrice(int x);\nint thrice(int x) { return 3 * x; }\n")
    build = tmp_path / "build"
    build.mkdir()
    subprocess.run(["cppcheck", "--std=c99", "--addon=misra", "--quiet", f"--cppcheck-build-dir={build}",
                    "clean.c", "blind.c"], cwd=tmp_path, capture_output=True, check=False)
    assert unanalysed(build, ["clean.c", "blind.c"]) == ["blind.c"]
    assert unanalysed(build, ["missing.c"]) == ["missing.c"]
