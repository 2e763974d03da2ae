"""The `ogk` console script (run as a subprocess, as a user would)."""
from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

import pytest

OGK = Path(sys.executable).parent / "ogk"


def run(*args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run([str(OGK), *args], capture_output=True, text=True, timeout=60)


@pytest.mark.req("OGK-HAR-013")
def test_help() -> None:
    out = run("--help")
    assert out.returncode == 0, out.stderr
    assert "version" in out.stdout and "demo" in out.stdout
    # the verbs listed, the older spellings not (they still run: below)
    listed = re.findall(r"^    (\w+) ", out.stdout, flags=re.MULTILINE)
    assert {"tables", "mc", "run", "replay", "report", "soak"} <= set(listed)
    assert not {"cases", "mpsp", "nmpc", "blt"} & set(listed), listed
    for older in ("cases", "mpsp", "nmpc", "blt"):
        out = run(older, "--help")
        assert out.returncode == 0 and out.stdout.startswith(f"usage: ogk {older}"), (older, out.stderr)


@pytest.mark.req("OGK-HAR-013")
def test_scenario_command_help_without_scenario() -> None:
    """`ogk tables --help` prints the command's help and exits 0; after a SCENARIO, --help is the
    family's."""
    for args in (("tables", "--help"), ("mc", "-h")):
        out = run(*args)
        assert out.returncode == 0, out.stderr
        assert out.stdout.startswith(f"usage: ogk {args[0]} ") and f"`ogk {args[0]} SCENARIO" in out.stdout
    out = run("tables", "leo-geo", "--help")
    assert out.returncode == 0, out.stderr
    assert "--out" in out.stdout


@pytest.mark.req("OGK-HAR-013", "OGK-CORE-002")
def test_version() -> None:
    out = run("version")
    assert out.returncode == 0, out.stderr
    assert re.search(r"harness \d+\.\d+\.\d+", out.stdout)
    assert re.search(r"kernel\s+\d+\.\d+\.\d+", out.stdout)


@pytest.mark.req("OGK-HAR-013", "OGK-CORE-014")
def test_demo_switching() -> None:
    out = run("demo", "switching")
    assert out.returncode == 0, out.stdout + out.stderr
    assert "closed form" in out.stdout
    errors = [float(m) for m in re.findall(r"\s([-+]?\d\.\d+e[-+]\d+)\s+[01]\s+\d+\s*$",
                                            out.stdout, flags=re.M)]
    assert len(errors) == 2 and max(abs(e) for e in errors) < 1e-10


@pytest.mark.req("OGK-HAR-013")
def test_no_command_is_usage_error() -> None:
    out = run()
    assert out.returncode == 2
