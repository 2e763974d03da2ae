"""Robustness campaign of the orbit-injection family (issue 32): missions at the short-burn side of
the envelope the family states, with initial-state dispersions inside VTD-NOG's linear domain (no
warning line), flown end to end through the CLI (`ogk tables`, `ogk mc`, 6-DOF truth, CPD in the
loop, every dispersion, derived end-game settings) on one fixed seed that no tuning used.

The defect it would have caught: the terminal stage shaped the radius and plane with plans whose
turns the vehicle cannot make (a 1.5 g0 burn of 42 s, a 3.9 s window of which 1.9 s shaped, the
TVC giving 0.2 rad/s^2): 52 of 1000 runs failed at the short-burn corner (seed 4242, docs/design/vtd-nog.md).
The kernel now bounds each plan's tilt from the velocity to be gained by what the vehicle turns out
and back in the shaped window (ogk/terminal.h, "Turn limit"; the vehicle's angular acceleration is
derived by the ground tools). `test_the_campaign_catches_a_terminal_stage_without_turn_limit` flies
the same runs with the limit switched off in the scenario (`terminal_turn_accel_rad_s2 = 0`, the law
of before) and requires the failures back: the campaign is what would have caught it.

Missions (the Mission helper of test_new_missions.py; no other file names them):
- short_burn_corner_inside: the corner (R_f / r_p = 1.5, 1.5 g0, 4.5 km/s; t_f* = 41.8 s), radius
  sigma 1.5 km and velocities 20 m/s (the domain: 1.71 km, 22 m/s);
- short_hot_r2: R_f / r_p = 2, 1.4 g0, 4 km/s (t_f* = 64.2 s), radius 3.5 km, velocities 30 m/s (the
  domain: 3.77 km, 33 m/s).
Measured when written (`ogk mc FILE --runs 400 --seed 320711 --workers 1`): 0 and 0 failures; with the
limit off 8 at the corner (and 3 on short_hot_r2); about 8 s of CPU per campaign.
"""
from __future__ import annotations

import dataclasses
import json
import re
from pathlib import Path

import pytest

from test_new_missions import R_LEO, Mission, ogk, write_scenario

SEED = 320711
RUNS = 400


@dataclasses.dataclass(frozen=True)
class Case:
    mission: Mission
    radius_sigma_m: float
    velocity_sigma_m_s: float


CORNER = Case(Mission("short_burn_corner_inside", 1.5 * R_LEO, 1.5, 4500.0, derived_end_game=True),
              1500.0, 20.0)
CASES = [CORNER,
         Case(Mission("short_hot_r2", 2.0 * R_LEO, 1.4, 4000.0, derived_end_game=True), 3500.0, 30.0)]


def write_case(case: Case, directory: Path, turn_limit_off: bool = False) -> Path:
    """The Mission helper's scenario with the case's initial-state dispersions (Table 3's keys); with
    `turn_limit_off`, the terminal stage of before (no turn limit, the scenario says 0)."""
    path = write_scenario(case.mission, directory)
    text = path.read_text()
    edits = [(r"^radius_m = 5.0e3$", f"radius_m = {case.radius_sigma_m!r}")]
    edits += [(rf"^{k}_velocity_m_s = 30.0$", f"{k}_velocity_m_s = {case.velocity_sigma_m_s!r}")
              for k in ("radial", "transverse", "normal")]
    if turn_limit_off:
        edits.append((r"^(terminal_shape_lead_s = .*)$", r"\1\nterminal_turn_accel_rad_s2 = 0.0"))
    for old, new in edits:
        text, n = re.subn(old, new, text, count=1, flags=re.M)
        assert n == 1, old
    path.write_text(text)
    return path


def fly(case: Case, work: Path, turn_limit_off: bool = False) -> tuple[dict, str, dict]:
    """`ogk tables` then `ogk mc --runs RUNS --seed SEED --workers 1`: (campaign JSON, the tables'
    stderr, the manifest)."""
    scenario = write_case(case, work, turn_limit_off)
    tables = work / "tables"
    made = ogk("tables", str(scenario), "--out", str(tables))
    assert made.returncode == 0, made.stdout + made.stderr
    out = work / "mc.json"
    camp = ogk("mc", str(scenario), "--runs", str(RUNS), "--seed", str(SEED), "--workers", "1",
               "--tables", str(tables), "--json", str(out))
    assert camp.returncode in (0, 1), camp.stdout[-3000:] + camp.stderr
    doc = json.loads(out.read_text())
    assert (camp.returncode == 0) == (doc["failures"] == 0)
    return doc, made.stderr, json.loads((tables / "manifest.json").read_text())


def worst(doc: dict) -> dict[str, float]:
    flown = [r for r in doc["per_run"] if r["dvr_f_mps"] is not None]
    return {k: max(abs(r[k]) for r in flown) for k in ("dr_f_m", "dvr_f_mps", "dvt_f_mps", "dvn_f_mps")}


@pytest.mark.req("OGK-NOG-021", "OGK-NOG-022", "OGK-HAR-007")
@pytest.mark.parametrize("case", CASES, ids=lambda c: c.mission.name)
def test_inside_the_linear_domain_every_run_flies(case: Case, tmp_path: Path) -> None:
    doc, warnings, manifest = fly(case, tmp_path)
    # inside the domain the family states: not one warning line
    assert "warning" not in warnings, warnings
    turn = manifest["settings"]["terminal_turn_accel_rad_s2"]
    assert turn["source"] == "derived" and 0.1 < turn["value"] < 0.5
    assert doc["runs"] == RUNS and doc["failures"] == 0, (doc["failed_runs"], worst(doc))
    # every velocity within the scenario's 20 m/s with a margin, the radius within its 1 km
    tails = worst(doc)
    assert max(tails["dvr_f_mps"], tails["dvt_f_mps"], tails["dvn_f_mps"]) < 17.0, tails
    assert tails["dr_f_m"] < 500.0, tails


@pytest.mark.req("OGK-NOG-022")
def test_the_campaign_catches_a_terminal_stage_without_turn_limit(tmp_path: Path) -> None:
    """The same runs of the corner with the terminal stage of before: the shaped plans ask for
    turns the vehicle cannot make, and the campaign sees it (velocity tolerances broken)."""
    doc, _, manifest = fly(CORNER, tmp_path, turn_limit_off=True)
    assert manifest["settings"]["terminal_turn_accel_rad_s2"] == {"value": 0.0, "source": "scenario"}
    assert doc["failures"] >= 4, doc["failures"]
    assert all("dvr_f_mps" in f["reason"] or "dvn_f_mps" in f["reason"] for f in doc["failed_runs"])
