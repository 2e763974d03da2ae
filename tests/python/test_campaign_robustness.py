"""Issue 32 (items 3-5b), the engine's part: the distance of the worst run from the median in both sigmas
(against scipy and closed forms), the class of a failure, lost flights and failed solves, a failed run's
replay command run for real, and `ogk soak` judging a campaign against its stated envelope (ogk.sil.robustness,
ogk.sil.soak; docs/guides/campaigns.md, "Robustness" and "make soak")."""
from __future__ import annotations

import json
import re
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from scipy.stats import median_abs_deviation

from ogk_bindings.errors import OgkInputError
from ogk_host.scenario_file import SCENARIO_DIR

from ogk.sil import robustness, soak

ALARM_S = 300
pytestmark = pytest.mark.usefixtures("alarm")
OGK = [sys.executable, "-c", "import sys; from ogk.cli import main; sys.exit(main())"]
REPO = Path(__file__).resolve().parents[2]


@pytest.mark.req("OGK-HAR-018")
def test_distance_from_the_median_against_scipy(rng: np.random.Generator) -> None:
    """A normal sample of 999 with one outlier at +40 sigma: the robust std (1.4826 MAD, scipy) stays near 1
    and puts the outlier near 40 robust std, while the campaign's std, inflated by the outlier itself,
    cannot put it beyond (n - 1) / sqrt(n) (Samuelson)."""
    vals = np.append(rng.normal(10.0, 1.0, 999), 50.0)
    ids = list(range(100, 1100))
    s = robustness.spread(ids, vals, int(np.argmax(np.abs(vals))))
    med = float(np.median(vals))
    assert s["median"] == med
    assert s["robust_std"] == pytest.approx(median_abs_deviation(vals, scale="normal"), rel=1e-12)
    assert 0.9 < s["robust_std"] < 1.1
    far = s["farthest"]
    assert far["run_id"] == 1099 and far["value"] == 50.0 and s["worst"] == far
    assert far["from_median_robust_std"] == pytest.approx((50.0 - med) / s["robust_std"])
    assert 36.0 < far["from_median_robust_std"] < 44.0
    std = float(np.std(vals, ddof=1))
    assert far["from_median_std"] == pytest.approx((50.0 - med) / std)
    assert far["from_median_std"] < (vals.size - 1) / np.sqrt(vals.size) + abs(med - vals.mean()) / std


@pytest.mark.req("OGK-HAR-018")
def test_robust_std_when_most_values_equal_the_median() -> None:
    """Iteration counts: 60 x 4, 30 x 5, one 35. The MAD is 0; the robust std is then sqrt(pi/2) x the mean
    absolute deviation (30 + 31) / 91, and the 35 sits 31 / that away."""
    vals = np.array([4.0] * 60 + [5.0] * 30 + [35.0])
    s = robustness.spread(list(range(91)), vals, 90)
    rstd = np.sqrt(np.pi / 2.0) * 61.0 / 91.0
    assert s["median"] == 4.0 and s["robust_std"] == pytest.approx(rstd, rel=1e-14)
    assert s["farthest"]["run_id"] == 90 and s["farthest"]["from_median_robust_std"] == pytest.approx(31.0 / rstd)
    # every value equal: sigma 0, distance 0
    s = robustness.spread([0, 1, 2], np.array([7.0, 7.0, 7.0]), 0)
    assert s["robust_std"] == 0.0 and s["worst"]["from_median_robust_std"] == 0.0
    assert s["worst"]["from_median_std"] == 0.0


@pytest.mark.req("OGK-HAR-018")
@pytest.mark.parametrize("reason,cls", [
    ("tolerance: |dr_f| = 612.3 km > 500", "tolerance: |dr_f|"),
    ("not arrived: impact with Mars at t = 12.5 d", "not arrived: impact with Mars at t = # d"),
    ("hybrid: iteration limit", "hybrid: iteration limit"),
    ("kernel OGK_E_RANGE at 3.2e-4 s", "kernel OGK_E_RANGE at # s"),
])
def test_failure_class(reason: str, cls: str) -> None:
    assert robustness.failure_class(reason) == cls


@pytest.mark.req("OGK-HAR-018")
def test_lost_flights_and_failed_solves() -> None:
    """Lost: a failed run (its class from the plan's classifier when it has one) or one the family calls
    lost; failed solves per run from the family's list or the record's count."""
    recs = [{"run_id": 0, "run_seed": 11, "failure": "", "failed_solves": 0},
            {"run_id": 1, "run_seed": 12, "failure": "tolerance: |dv| = 3 > 1", "failed_solves": 4},
            {"run_id": 2, "run_seed": 13, "failure": "", "failed_solves": 1, "mine": "no"}]
    lost = robustness.lost_runs(recs, None, lambda r: "corrector: stalled" if r.get("mine") else "", "c.json")
    assert [(f["run_id"], f["class"], f["acceptance"], f["replay"]) for f in lost] == [
        (1, "tolerance: |dv|", True, "ogk replay c.json 1"), (2, "corrector: stalled", False, "ogk replay c.json 2")]
    solves = robustness.failed_solves(recs, None)
    assert solves == {"runs": 3, "total": 5, "runs_with_any": 2, "per_run_max": 4, "run_of_max": 1,
                      "by_class": {"failed solve": 5}}
    assert robustness.failed_solves([{"run_id": 0}], None) is None        # no solves to count
    by = robustness.failed_solves(recs, lambda r: ["a"] * int(r["run_id"]) + ["b"] * (r["run_id"] == 2))
    assert by is not None and by["by_class"] == {"a": 3, "b": 1} and by["run_of_max"] == 2


def _strict_apophis(tmp_path: Path, name: str) -> Path:
    """Apophis with [acceptance] position_error_km = 1e-3: every converged case is a lost flight."""
    text = (SCENARIO_DIR / "apophis_cubesat.toml").read_text().split(
        "# ---------------------------------------------------------------- published")[0]
    text = re.sub(r'(?m)^name = .*$', f'name = "{name}"', text, count=1)
    path = tmp_path / f"{name}.toml"
    path.write_text(text + "\n[acceptance]\nposition_error_km = 1e-3\n")
    return path


def _ogk(*args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run([*OGK, *args], capture_output=True, text=True, timeout=600, cwd=REPO)


def _tables_of(name: str) -> list[Path]:
    return list((REPO / "build" / "tables").glob(f"{name}-*"))


@pytest.mark.req("OGK-HAR-018")
def test_a_failed_run_carries_its_class_and_its_replay_replays_it(tmp_path: Path) -> None:
    scenario = _strict_apophis(tmp_path, "robustness_strict_apophis")
    out = tmp_path / "mc.json"
    try:
        res = _ogk("mc", str(scenario), "--runs", "3", "--seed", "2026120434", "--json", str(out))
        assert res.returncode == 1, res.stderr[-2000:]
        assert "robustness: robustness_strict_apophis (low-thrust-transfer): 3 of 3 flights lost" in res.stdout
        assert "3 x tolerance: |dr_f|" in res.stdout
        doc = json.loads(out.read_text())
        assert doc["failure_classes"] == {"tolerance: |dr_f|": 3}
        f = doc["failed_runs"][1]
        assert f["run_id"] == 1 and f["replay"] == f"ogk replay {out} 1" and isinstance(f["run_seed"], int)
        # the stored command, run: the same run and the same failure, bit for bit
        rep = _ogk(*f["replay"].split()[1:])
        assert rep.returncode == 0 and "bit-exact" in rep.stdout and "failure: tolerance: |dr_f|" in rep.stdout
        assert "lost: 3 x tolerance: |dr_f| (runs 0, 1, 2)" in _ogk("report", str(out)).stdout
    finally:
        for d in _tables_of("robustness_strict_apophis"):
            shutil.rmtree(d, ignore_errors=True)


@pytest.mark.req("OGK-HAR-019")
def test_the_shipped_soak_plan() -> None:
    """soak.toml: every family, >= 1,000 runs each, seeds that no test, no scenario and no doc figure
    names outside soak.toml (the docs and the work notes quote its figures), the rendezvous with and without third bodies in the model."""
    plan = soak.load_plan()
    from ogk.missions import registry
    from ogk_host.scenario_file import read_header, resolve_scenario
    families = {registry.family(read_header(resolve_scenario(c.scenario))).name for c in plan}
    assert families == {"orbit-injection", "low-thrust-transfer", "low-thrust-rendezvous", "binary-asteroid"}
    assert all(c.runs >= 1000 for c in plan)
    assert len({c.seed for c in plan}) == len(plan)
    names = {(c.scenario, c.options) for c in plan}
    assert ("rendezvous_nep_min_time", ("--third-bodies-in-model", "yes")) in names
    assert ("rendezvous_nep_min_time", ()) in names
    used = subprocess.run(["git", "grep", "-l", "-E", "|".join(str(c.seed) for c in plan), "--", ".",
                           ":!soak.toml", ":!docs", ":!notes"], cwd=REPO, capture_output=True, text=True).stdout.split()
    assert used == [], used


@pytest.mark.req("OGK-HAR-019")
def test_soak_plan_errors_are_one_line(tmp_path: Path) -> None:
    bad = tmp_path / "bad.toml"
    for text, key in (('[[campaign]]\nname = "a"\nscenario = "apophis"\nruns = 0\nseed = 1\n', "campaign[0]"),
                      ('[[campaign]]\nname = "a"\nscenario = "apophis"\nruns = 5\nseed = 1\nextra = 2\n',
                       "campaign[0]"),
                      ('[[campaign]]\nname = "a"\nscenario = "apophis"\nruns = 5\nseed = 1\n'
                       '[[campaign.stated]]\nclass = "x"\nmax_fraction = 2.0\n', "campaign[0].stated[0]")):
        bad.write_text(text)
        with pytest.raises(OgkInputError) as err:
            soak.load_plan(bad)
        assert key in err.value.line()


@pytest.mark.req("OGK-HAR-019")
def test_soak_exits_1_on_a_lost_flight_its_envelope_does_not_state(tmp_path: Path) -> None:
    """Two plans over the same strict campaign (3 lost of 3): not stated -> exit 1 naming the class; stated
    with room for them -> exit 0; stated but over the fraction -> exit 1."""
    scenario = _strict_apophis(tmp_path, "robustness_soak_apophis")
    head = (f'[[campaign]]\nname = "strict"\nscenario = "{scenario}"\nruns = 3\nseed = 2026120435\n')
    try:
        for stated, code, text in (("", 1, "3 x tolerance: |dr_f| [NOT STATED]"),
                                   ('[[campaign.stated]]\nclass = "tolerance: |dr_f|"\nmax_fraction = 1.0\n', 0,
                                    "3 x tolerance: |dr_f| [stated]"),
                                   ('[[campaign.stated]]\nclass = "tolerance: |dr_f|"\nmax_fraction = 0.5\n', 1,
                                    "more than the stated 0.5 of 3 runs")):
            plan = tmp_path / "plan.toml"
            plan.write_text(head + stated)
            res = _ogk("soak", str(plan), "--out", str(tmp_path / "soak"), "--workers", "1")
            assert res.returncode == code and text in res.stdout, res.stdout[-3000:] + res.stderr[-2000:]
            assert "low-thrust-transfer: 1 campaigns, 3 runs, 3 lost" in res.stdout
    finally:
        for d in _tables_of("robustness_soak_apophis"):
            shutil.rmtree(d, ignore_errors=True)
