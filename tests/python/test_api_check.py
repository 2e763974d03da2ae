"""The API check of `make test` (tests/api/check_api.py, CHANGELOG.md "Versioning") on a scratch copy of
the public headers and the recorded interface: a changed, a removed and an added declaration without
the version bump they need fail the check and are named; the bump passes it; a re-record makes the
copy's interface the recorded one."""
from __future__ import annotations

import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
CHECK = ROOT / "tests" / "api" / "check_api.py"

pytestmark = pytest.mark.req("OGK-CORE-026")


@pytest.fixture()
def scratch(tmp_path: Path) -> Path:
    """kernel/include and api/ copied; the copy checks clean."""
    shutil.copytree(ROOT / "kernel" / "include", tmp_path / "include")
    shutil.copytree(ROOT / "api", tmp_path / "api")
    return tmp_path


def run(scratch: Path, action: str = "check") -> subprocess.CompletedProcess[str]:
    return subprocess.run([sys.executable, str(CHECK), action, "--include", str(scratch / "include"),
                           "--api-dir", str(scratch / "api")], capture_output=True, text=True)


def edit(path: Path, old: str, new: str) -> None:
    text = path.read_text()
    assert old in text, f"{path.name}: '{old}' not found"
    path.write_text(text.replace(old, new, 1))


def set_version(scratch: Path, major: int, minor: int, patch: int) -> None:
    header = scratch / "include" / "ogk" / "version.h"
    text = header.read_text()
    for part, value in (("MAJOR", major), ("MINOR", minor), ("PATCH", patch)):
        text = re.sub(rf"(#define OGK_VERSION_{part}) \d+", rf"\g<1> {value}", text)
    text = re.sub(r'(#define OGK_VERSION_STRING) "[^"]*"', rf'\1 "{major}.{minor}.{patch}"', text)
    header.write_text(text)


def recorded_version() -> tuple[int, int, int]:
    record = (ROOT / "api").glob("ogk-*.api")
    best = max(tuple(int(x) for x in re.fullmatch(r"ogk-(\d+)\.(\d+)\.(\d+)\.api", p.name).groups())
               for p in record)
    return best  # type: ignore[return-value]


def test_unchanged_headers_pass(scratch: Path) -> None:
    r = run(scratch)
    assert r.returncode == 0, r.stdout + r.stderr
    assert "is the one recorded" in r.stdout


def test_changed_declaration_needs_the_breaking_bump(scratch: Path) -> None:
    """A parameter's type changed (a caller no longer compiles): fails until the version says
    the next breaking release (0.x: the next minor)."""
    edit(scratch / "include" / "ogk" / "cpd.h", "ogk_status ogk_cpd_step(ogk_cpd_t *ctx, const ogk_cpd_input_t *in,",
         "ogk_status ogk_cpd_step(ogk_cpd_t *ctx, ogk_cpd_input_t *in,")
    major, minor, patch = recorded_version()
    breaking = (major + 1, 0, 0) if major else (0, minor + 1, 0)
    r = run(scratch)
    assert r.returncode == 1, r.stdout
    assert "changed: [cpd.h] func ogk_cpd_step" in r.stdout
    assert f"must say at least {'%d.%d.%d' % breaking}" in r.stdout
    set_version(scratch, major, minor, patch + 1)  # a patch bump is not enough
    assert run(scratch).returncode == 1
    set_version(scratch, *breaking)
    r = run(scratch)
    assert r.returncode == 0, r.stdout
    assert "covers it" in r.stdout and "make api-record" in r.stdout


def test_changed_macro_and_removed_function_fail(scratch: Path) -> None:
    """A flag's value and a removed function are incompatible too (the macros are API)."""
    edit(scratch / "include" / "ogk" / "nog.h", "#define OGK_NOG_FLAG_SAFE 0x08u", "#define OGK_NOG_FLAG_SAFE 0x40u")
    edit(scratch / "include" / "ogk" / "nog.h",
         "ogk_status ogk_nog_tau_at(const ogk_nog_t *ctx, ogk_real_t t_s, ogk_real_t *tau);", "")
    r = run(scratch)
    assert r.returncode == 1, r.stdout
    assert "changed: [nog.h] macro OGK_NOG_FLAG_SAFE" in r.stdout
    assert "removed: [nog.h] func ogk_nog_tau_at" in r.stdout


def test_added_declaration_needs_the_compatible_bump(scratch: Path) -> None:
    """An added function: the next compatible release (0.x: the next patch) is enough; a renamed
    parameter is no change at all."""
    edit(scratch / "include" / "ogk" / "nog.h", "ogk_status ogk_nog_reset(ogk_nog_t *ctx);",
         "ogk_status ogk_nog_reset(ogk_nog_t *context);\nogk_status ogk_nog_hold(ogk_nog_t *ctx, double t_s);")
    r = run(scratch)
    assert r.returncode == 1, r.stdout
    assert "added:   [nog.h] func ogk_nog_hold" in r.stdout
    assert "ogk_nog_reset" not in r.stdout
    major, minor, patch = recorded_version()
    compatible = (major, minor + 1, 0) if major else (0, minor, patch + 1)
    set_version(scratch, *compatible)
    assert run(scratch).returncode == 0
    # recorded at the release, the copy's interface is the new reference
    assert run(scratch, "record").returncode == 0
    r = run(scratch)
    assert r.returncode == 0 and "is the one recorded for %d.%d.%d" % compatible in r.stdout


def test_real_type_spelling_is_no_change(scratch: Path) -> None:
    """ogk/real.h's names read as the default build compiles them (issue 35): a parameter spelled double
    where the record says ogk_real_t, a macro's bare literal where it says OGK_R(literal), and one
    spelled with a real.h limit, declare the same API and pass without a bump."""
    mathutil = scratch / "include" / "ogk" / "mathutil.h"
    edit(mathutil, "ogk_status ogk_wrap_pi(ogk_real_t angle, ogk_real_t *wrapped);",
         "ogk_status ogk_wrap_pi(double angle, ogk_real_t *wrapped);")
    edit(mathutil, "#define OGK_ANGLE_LIMIT OGK_R(1.0e4)", "#define OGK_ANGLE_LIMIT 1.0e4")
    edit(scratch / "include" / "ogk" / "linalg.h", "#define OGK_LA_PIVOT_MIN OGK_REAL_TINY",
         "#define OGK_LA_PIVOT_MIN 1.0e-300")
    r = run(scratch)
    assert r.returncode == 0, r.stdout
    assert "3 entries differ from" in r.stdout and "only in the spelling of ogk/real.h's names" in r.stdout
    assert "changed:" not in r.stdout


def test_real_type_made_float_is_a_change(scratch: Path) -> None:
    """What the reading of real.h's names must not hide: a real that becomes float, a macro whose value
    differs, and the default build's real type itself."""
    mathutil = scratch / "include" / "ogk" / "mathutil.h"
    edit(mathutil, "ogk_status ogk_wrap_pi(ogk_real_t angle, ogk_real_t *wrapped);",
         "ogk_status ogk_wrap_pi(float angle, ogk_real_t *wrapped);")
    edit(scratch / "include" / "ogk" / "linalg.h", "#define OGK_LA_PIVOT_MIN OGK_REAL_TINY",
         "#define OGK_LA_PIVOT_MIN OGK_REAL_MIN")
    r = run(scratch)
    assert r.returncode == 1, r.stdout
    assert "changed: [mathutil.h] func ogk_wrap_pi" in r.stdout
    assert "changed: [linalg.h] macro OGK_LA_PIVOT_MIN" in r.stdout
    edit(scratch / "include" / "ogk" / "real.h", "typedef double ogk_real_t;", "typedef float ogk_real_t;")
    r = run(scratch)
    assert "changed: [real.h] type ogk_real_t" in r.stdout and r.returncode == 1

