"""Issue 32 (items 3-4): short robustness campaigns of MPSP and BLT on fixed seeds, through the family's own
plan and the engine (ogk.sil.engine.fly_campaign, envelope.envelope), each asserting what the law's stated
envelope says (docs/design/mpsp.md and docs/design/blt.md, "Robustness"): no lost flight outside the stated classes, and a
bound on the worst run. The long campaigns are `make soak` (soak.toml) and the 1,000-run audits quoted there.

Missions: the shipped Apophis and Moshup scenarios, and two that no other file names, written here from them:
Apophis flown at 1.45 mN (3 % below the paper's thrust; its nominal by continuation from the cached one) and
Moshup's Table 3 transfer at 45 mN from a 3 km circle (its nominal designed by the ground tools).
Seeds 2026120430-33: used by no other test, no soak and no published figure."""
from __future__ import annotations

import re
import shutil
import tomllib
from pathlib import Path
from typing import Any

import pytest

from ogk_host.scenario_file import SCENARIO_DIR, read_header

from ogk.missions import registry
from ogk.sil import envelope
from ogk.sil.engine import fly_campaign

ALARM_S = 300
pytestmark = pytest.mark.usefixtures("alarm")

REPO = Path(__file__).resolve().parents[2]
TABLES = REPO / "build" / "tables"


def campaign(scenario: Path, runs: int, seed: int, **options: Any) -> tuple[dict[str, Any], list[dict[str, Any]]]:
    """The envelope and the records of `runs` runs of the scenario's family campaign (2 workers, as `ogk mc`)."""
    header = read_header(scenario)
    plan = registry.family(header).plan(header, options)
    flown = fly_campaign(plan, runs, seed, workers=2, progress=False)
    return envelope.envelope(flown, json_path="mc.json"), flown.records


def _mpsp_edit(dst: Path, thrust_n: str, name: str) -> Path:
    text = (SCENARIO_DIR / "apophis_cubesat.toml").read_text()
    text = text.split("# ---------------------------------------------------------------- published")[0]
    for key, value in (("name", f'"{name}"'), ("max_thrust_N", thrust_n)):
        text, n = re.subn(rf"^{key} = .*$", f"{key} = {value}", text, count=1, flags=re.M)
        assert n == 1
    dst.write_text(text)
    return dst


def _check_mpsp(doc: dict[str, Any], records: list[dict[str, Any]], max_iterations: int, lost: int = 0) -> None:
    rob = doc["robustness"]
    assert rob["runs"] == len(records) and doc["failures"] == lost, doc["failed_runs"][:5]
    assert rob["lost_flights"] == lost and rob["failed_solves"]["total"] == lost
    ok = [r for r in records if not r["failure"]]
    # converged means within the [mpsp] tolerances, and within the Newton budget we state
    assert max(r["dr_f_km"] for r in ok) <= 500.0 and max(r["dv_f_kmps"] for r in ok) <= 0.1
    assert max(r["newton_iterations"] for r in ok) <= max_iterations
    # each distance from the median is |value - median| / sigma of the same campaign
    q = doc["quantities"]
    for key in ("newton_iterations", "final_mass_kg"):
        w = q[key]["worst"]
        assert w["from_median_std"] == pytest.approx(abs(w["value"] - q[key]["median"]) / q[key]["std"])


@pytest.mark.req("OGK-MPSP-014", "OGK-HAR-018")
def test_mpsp_apophis_dispersed_campaign_loses_nothing() -> None:
    """Apophis at the scenario's dispersions (kappa in [-3, 3.5], the 0.04 LU cube, eta +-10 %), 450 runs:
    every one converges within the tolerances (the 1,000-run audit, seed 2026120410, and the soak's apophis campaign: 0 lost,
    worst 101 Newton iterations)."""
    doc, records = campaign(SCENARIO_DIR / "apophis_cubesat.toml", 450, 2026120430)
    _check_mpsp(doc, records, 110)
    print("apophis worst:", doc["robustness"]["worst_run"])


@pytest.mark.req("OGK-MPSP-014", "OGK-HAR-018")
def test_mpsp_new_mission_at_1_45_mn_loses_nothing(tmp_path: Path) -> None:
    """A mission no other file names: Apophis at 1.45 mN (its nominal continued from the cached one), at
    the paper's dispersions, 150 runs. Its envelope ends where the box leaves it without thrust: eta = -10 %
    is 1.305 mN, below the 1.35 mN edge of this transfer (test_mpsp_missions.py), and kappa near 3.5 needs
    more thrust than 1.45 mN gives. Every lost run is one of those corners (measured on this seed: 3 thrust
    cases at eta <= -9.0 %, 6 initial-state cases at kappa >= 2.96; every case inside them converges)."""
    scenario = _mpsp_edit(tmp_path / "apophis_1_45mN.toml", "1.45e-3", "robustness_apophis_1_45mN")
    sha = __import__("hashlib").sha256(scenario.read_bytes()).hexdigest()[:12]
    out = TABLES / f"robustness_apophis_1_45mN-{sha}"
    try:
        doc, records = campaign(scenario, 150, 2026120431)
        lost = [r for r in records if r["failure"]]
        assert all(r["failure"] == "MPSP did not converge" for r in lost)
        corner = [r for r in lost if (r["kind"] == "thrust" and r["eta_percent"] <= -9.0)
                  or (r["kind"] == "initial" and r["kappa"] >= 2.9)]
        assert corner == lost and len(lost) <= 15, [(r["run_id"], r["kind"], r["label"]) for r in lost]
        # inside the corners nothing is lost: every terminal case, every thrust case above -9 %
        assert all(not r["failure"] for r in records if r["kind"] == "terminal")
        _check_mpsp(doc, records, 110, lost=len(lost))
    finally:
        shutil.rmtree(out, ignore_errors=True)


#: The lost-flight classes BLT's hybrid states at the scenario's levels (docs/design/blt.md, "Robustness"; soak.toml)
BLT_STATED = {"hybrid: guess hits a body", "hybrid: iteration limit"}


def _check_blt(doc: dict[str, Any], records: list[dict[str, Any]], runs: int, high_fraction: float) -> None:
    """No lost flight at levels <= 30 %; above, only the stated classes, at most `high_fraction` of those
    draws."""
    rob = doc["robustness"]
    assert rob["runs"] == runs and doc["failures"] == 0, doc["failed_runs"][:5]   # DOP853 confirms all
    assert set(rob["lost_by_class"]) <= BLT_STATED, rob["lost_by_class"]
    lost = {f["run_id"] for f in rob["lost_runs"]}
    level = {int(r["run_id"]): r["level_percent"] for r in records}
    assert all(level[i] > 30.0 for i in lost), sorted((i, level[i]) for i in lost)
    high = sum(1 for v in level.values() if v > 30.0)
    assert len(lost) <= high_fraction * high, (len(lost), high)
    # every lost run names its class and the command that replays it
    assert all(f["class"] in BLT_STATED and f["replay"] == f"ogk replay mc.json {f['run_id']}"
               for f in rob["lost_runs"])
    q = doc["quantities"]["hybrid.iterations"]
    assert q["median"] <= 5 and q["n"] == runs


@pytest.mark.req("OGK-BLT-012", "OGK-HAR-018")
def test_blt_moshup_table3_campaign_within_its_envelope() -> None:
    """Moshup's Table 3 transfer at the scenario's six levels, the flight corrector (hybrid), 240 runs."""
    doc, records = campaign(SCENARIO_DIR / "moshup.toml", 240, 2026120432, corrector="hybrid")
    # stated: 6 of the 332 draws at 40-50 % in the 1,000-run audit (seed 2026120411): 1.8 %; bound 4 %
    _check_blt(doc, records, 240, 0.04)
    print("moshup:", doc["robustness"]["lost_by_class"], doc["robustness"]["worst_run"])


@pytest.mark.req("OGK-BLT-012", "OGK-HAR-018")
def test_blt_new_mission_45mn_from_3km_within_its_envelope(tmp_path: Path) -> None:
    """A mission no other file names: Moshup's UMP transfer at 45 mN from a 3 km circle, 120 runs. Its basin
    is smaller than the shipped transfer's at 40-50 % (measured on this seed: 4 iteration limits in its 40
    draws there, none at or below 30 %)."""
    text = (SCENARIO_DIR / "moshup.toml").read_text()
    text = re.sub(r"(?m)^\[paper_results.*", "", text.split("# ---------------------------------------------"
                                                                "------------------- published")[0])
    block = text[text.index("[transfers.circle_to_l2_ump]"):]
    block = block[:block.index("\n\n")]
    new = block.replace("circle_radius_m = 4000.0", "circle_radius_m = 3000.0").replace(
        "thrust_n = 0.030 ", "thrust_n = 0.045 ")
    assert new.count("3000.0") == 1 and new.count("0.045") == 1
    text = re.sub(r'(?m)^name = .*$', 'name = "robustness_moshup_45mN_3km"', text.replace(block, new), count=1)
    scenario = tmp_path / "moshup_45mN_3km.toml"
    scenario.write_text(text)
    assert tomllib.loads(text)["transfers"]["circle_to_l2_ump"]["thrust_n"] == 0.045
    doc, records = campaign(scenario, 120, 2026120433, corrector="hybrid")
    _check_blt(doc, records, 120, 0.15)
