"""Bad input to `ogk` ends with one line naming the file, the key and the reason, exit code 2, and
no traceback (run as a subprocess, as a user would); `--debug` shows the traceback.

Each case edits a copy of scenarios/leo_geo.toml (or gives a bad option) and must be refused before
any long computation: every run is bounded by a 60 s timeout, far below a nominal solve + campaign.
"""
from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

import pytest

pytestmark = pytest.mark.req("OGK-HAR-005")

OGK = Path(sys.executable).parent / "ogk"
SCENARIO = Path(__file__).resolve().parents[2] / "scenarios" / "leo_geo.toml"


def run(*args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run([str(OGK), *args], capture_output=True, text=True, timeout=60)


def edited(tmp_path: Path, old: str, new: str) -> Path:
    text = SCENARIO.read_text()
    assert re.search(old, text, flags=re.M), old
    path = tmp_path / "mission.toml"
    path.write_text(re.sub(old, new, text, count=1, flags=re.M))
    return path


def assert_one_line(out: subprocess.CompletedProcess[str], *words: str) -> str:
    assert out.returncode == 2, out.stdout + out.stderr
    lines = out.stderr.strip().splitlines()
    assert len(lines) == 1, out.stderr
    assert "Traceback" not in out.stderr
    for w in words:
        assert w in lines[0], (w, lines[0])
    return lines[0]


MC = ("--runs", "2", "--seed", "1")


@pytest.mark.parametrize("old, new, words", [
    (r"^radius_m = 42164.0e3", "radius_m = 6000.0e3", ["target_orbit.radius_m", "perigee"]),
    (r"^initial_mass_kg = 2400.0", "initial_mass_kg = -2400.0",
     ["thrust.initial_mass_kg", "must be > 0"]),
    (r"^exhaust_velocity_m_s = 3000.0", 'exhaust_velocity_m_s = "3 km/s"',
     ["thrust.exhaust_velocity_m_s", "must be a number"]),
    (r"^tvc_arm_m = 0.25", "tvc_arm = 0.25", ["mass_properties.tvc_arm_m", "missing key"]),
    (r"^harmonics = 5", "harmonics = 5\nharmonix = 3", ["dispersions.thrust.harmonix", "unknown key"]),
    (r"^sample_interval_s = 2.0", "sample_interval_s = 0.0",
     ["guidance.sample_interval_s", "must be > 0"]),
    (r'^law = "vtd-nog"', 'law = "nmpc"', ["guidance.law", "vtd-nog"]),
    (r"^terminal_shape_hold_s = 2.0", "terminal_shape_hold_s = 12.0",
     ["guidance.end_game.terminal_shape_hold_s", "terminal_window_s"]),
    (r"^terminal_shape_gain_normal = 1.0", "terminal_shape_gain_normal = 1.5",
     ["guidance.end_game.terminal_shape_gain_normal", "must be"]),
    (r'^mission = "orbit-injection"', 'mission = "orbit-insertion"', ["mission", "unknown"]),
    (r"^\[gravity\]", "[gravity", ["malformed TOML"]),
])
def test_bad_scenario_is_one_line(tmp_path: Path, old: str, new: str, words: list[str]) -> None:
    path = edited(tmp_path, old, new)
    line = assert_one_line(run("mc", str(path), *MC, "--json", str(tmp_path / "mc.json")), *words)
    assert str(path) in line
    assert not (tmp_path / "mc.json").exists()
    assert_one_line(run("tables", str(path), "--out", str(tmp_path / "t")), *words)


@pytest.mark.parametrize("args, words", [
    (("--runs", "0", "--seed", "1"), ["--runs", ">= 1"]),
    (("--runs", "2", "--seed", "-3"), ["--seed", ">= 0"]),
    (("--runs", "2", "--seed", "1", "--control-rate", "0"), ["--control-rate"]),
    (("--runs", "2", "--seed", "1", "--workers", "0"), ["--workers"]),
])
def test_bad_option_is_one_line(tmp_path: Path, args: tuple[str, ...], words: list[str]) -> None:
    assert_one_line(run("mc", "leo-geo", *args, "--json", str(tmp_path / "mc.json")), *words)


def test_unwritable_output_is_refused_before_the_campaign(tmp_path: Path) -> None:
    blocker = tmp_path / "file"
    blocker.write_text("not a directory")
    assert_one_line(run("mc", "leo-geo", *MC, "--json", str(blocker / "mc.json")), "--json",
                    str(blocker / "mc.json"))
    assert_one_line(run("mc", "leo-geo", *MC, "--json", str(tmp_path / "ok.json"),
                        "--plots", str(blocker)), "--plots")
    assert_one_line(run("cases", "apophis", "--case", "thrust", "--param", "3",
                        "--json", str(blocker / "x.json")), "--json")


def test_missing_and_unknown_scenarios(tmp_path: Path) -> None:
    assert_one_line(run("mc", str(tmp_path / "none.toml"), *MC, "--json", str(tmp_path / "j")),
                    "none.toml", "no such scenario file")
    assert_one_line(run("tables", "no-such-mission"), "no scenario named", "leo_geo")
    assert_one_line(run("cases", "leo-geo", "--paper-tables"), "orbit-injection", "ogk tables")


def test_debug_shows_the_traceback(tmp_path: Path) -> None:
    path = edited(tmp_path, r"^initial_mass_kg = 2400.0", "initial_mass_kg = -1.0")
    out = run("--debug", "mc", str(path), *MC, "--json", str(tmp_path / "mc.json"))
    assert out.returncode != 0 and "Traceback" in out.stderr and "OgkInputError" in out.stderr


def test_bad_mpsp_scenario_is_one_line(tmp_path: Path) -> None:
    """The low-thrust-transfer family's loader: unknown and missing keys, one line each."""
    src = SCENARIO.parent / "apophis_cubesat.toml"
    path = tmp_path / "transfer.toml"
    path.write_text(src.read_text().replace("r_lambda = 1.0", "r_lambda = 1.0\nr_lamda = 2.0"))
    assert_one_line(run("cases", str(path), "--case", "thrust", "--param", "3", "--no-reference"),
                    str(path), "mpsp.r_lamda", "unknown key")
    path.write_text(src.read_text().replace("cube_side_LU = 0.04", ""))
    assert_one_line(run("cases", str(path), "--paper-tables", "--no-reference"), "cube_side_LU",
                    "missing key")


def test_a_time_to_go_clip_longer_than_half_the_burn_is_one_line_at_tables(tmp_path: Path) -> None:
    """The kernel refuses |dt_f| clips above t_f*/2 (ogk_nog_init, OGK_E_CONFIG); t_f* is known
    only once the nominal is solved, so `ogk tables` checks it there and names the key (issue 19:
    a copied dtf_max_s used to pass `ogk tables` and abort `ogk mc` with a bare status). The paper's
    burn has t_f* = 105.8 s: 60 s is above its half, 52 s below."""
    path = edited(tmp_path, r"^dtf_max_s = 40\.0", "dtf_max_s = 60.0")
    line = assert_one_line(run("tables", str(path), "--out", str(tmp_path / "t")),
                           "guidance.end_game.dtf_max_s", "t_f*/2")
    half = float(re.search(r"t_f\*/2 = ([0-9.]+) s", line).group(1))
    assert 52.0 < half < 53.5
