"""The campaign engine is the same for every mission family (ogk.sil.engine, ogk.sil.family,
ogk.sil.envelope; docs/guides/sil.md): each family's shipped scenario flown through `ogk mc` writes the
envelope and the Parquet table, `ogk replay` re-flies a run bit for bit, and the faults end the
same way in every family: a run that raises in a worker (its runs and status named), a killed
worker, a hung chunk (watchdog), Ctrl-C then --resume (the uninterrupted result), an unwritable
output (one line, exit 2, before any flight); the per-run numbers do not depend on the worker
count or the chunking.

The faults are injected by wrapping the family's own chunk flight (the plan's `fly`), so the family's
real plan, draws and kernel calls run around them. Nothing here may hang: every in-process campaign
runs under an alarm, every `ogk` call under a subprocess timeout."""
from __future__ import annotations

import dataclasses
import json
import os
import signal
import subprocess
import time
from pathlib import Path

import numpy as np
import pytest

from ogk_bindings.kernel import KernelError
from ogk_host.scenario_file import read_header, resolve_scenario

from ogk.missions import registry
from ogk.sil import envelope
from ogk.sil.engine import fly_campaign
from ogk.sil.runner import CampaignAborted, CampaignInterrupted, Watchdog

import point_mass_family

#: `ogk` in a subprocess that knows the test family too
OGK = point_mass_family.OGK
#: the test family's scenario, written by this test
POINT_MASS = point_mass_family.write_scenario(
    Path(__file__).resolve().parents[2] / "build" / "test-families" / "point_mass.toml")

#: family -> (shipped scenario, the family's options of a short campaign); the test family's row
FAMILIES = {
    "orbit-injection": ("leo-geo", {}),
    "low-thrust-transfer": ("apophis", {}),
    "low-thrust-rendezvous": ("rendezvous_nep_min_time", {}),
    "binary-asteroid": ("moshup", {"perturbation": [10.0, 40.0]}),
    "proximity-approach": ("proximity_approach", {}),
    point_mass_family.MISSION: (str(POINT_MASS), {}),
}
CLI_OPTIONS = {"binary-asteroid": ["--perturbation", "10", "40"]}


#: every in-process test ends within this many seconds (conftest.alarm)
ALARM_S = 240
pytestmark = pytest.mark.usefixtures("alarm", "point_mass_registered")


@pytest.fixture(scope="module")
def point_mass_registered():
    """The test family registered while this module runs (its one registry line)."""
    with point_mass_family.registered():
        yield



_PLANS: dict[str, object] = {}


def plan_of(family: str):
    """The family's real plan of its shipped scenario (built once per session)."""
    if family not in _PLANS:
        scenario, options = FAMILIES[family]
        header = read_header(resolve_scenario(scenario))
        fam = registry.family(header)
        assert fam.name == family
        _PLANS[family] = fam.plan(header, dict(options))
    return _PLANS[family]


def faulty(plan, fault):
    """The plan with `fault(run_id)` called before each run of its chunk flight."""
    real = plan.fly

    def fly(ids, seeds):
        for i in ids:
            fault(int(i))
        return real(ids, seeds)
    return dataclasses.replace(plan, fly=fly)


def without_timing(records):
    return [{k: v for k, v in r.items() if not k.startswith("timing.")} for r in records]


def same(a, b) -> bool:
    return all(not envelope.record_differences(x, y) for x, y in zip(a, b)) and len(a) == len(b)


def ogk(*args: str, timeout: float = 600.0) -> subprocess.CompletedProcess[str]:
    return subprocess.run([*OGK, *args], capture_output=True, text=True, timeout=timeout)


@pytest.mark.req("OGK-HAR-001", "OGK-HAR-002")
@pytest.mark.parametrize("family", FAMILIES)
def test_ogk_mc_writes_envelope_and_table_and_replay_is_bit_exact(family, tmp_path):
    scenario, _ = FAMILIES[family]
    out = tmp_path / "mc.json"
    res = ogk("mc", scenario, "--runs", "4", "--workers", "2", "--seed", "97",
              *CLI_OPTIONS.get(family, []), "--json", str(out))
    assert res.returncode in (0, 1), res.stdout + res.stderr
    assert "Traceback" not in res.stderr
    doc = json.loads(out.read_text())
    assert doc["schema"] == envelope.SCHEMA and doc["family"] == family and doc["runs"] == 4
    assert doc["seed"] == 97 and doc["workers"] == 2
    assert len(doc["scenario_sha256"]) == 64 and Path(doc["scenario_path"]).is_file()
    assert doc["failures"] == len(doc["failed_runs"]) == (res.returncode == 1) * doc["failures"]
    for q in doc["quantities"].values():
        assert set(q) == {"n", "mean", "std", "median", "robust_std", "worst", "farthest"}
    rows = envelope.read_table(tmp_path / doc["per_run_table"])
    # every failed run: its class, its stream and the command that replays it
    for f in doc["failed_runs"]:
        assert f["class"] and f["replay"] == f"ogk replay {out} {f['run_id']}"
        assert f["run_seed"] == rows[f["run_id"]]["run_seed"]
    rob = doc["robustness"]
    assert rob["runs"] == 4 and rob["lost_flights"] == len(rob["lost_runs"]) >= doc["failures"]
    # the median and the distances from it, recomputed from the table (numpy / scipy)
    from scipy.stats import median_abs_deviation
    for key, q in doc["quantities"].items():
        vals = np.array([float(r[key]) for r in rows if isinstance(r.get(key), (int, float))
                         and np.isfinite(r[key])])
        if vals.size < 2:
            continue
        med = float(np.median(vals))
        assert q["median"] == pytest.approx(med, rel=1e-12, abs=1e-300)
        mad = median_abs_deviation(vals, scale="normal")
        rstd = mad if mad > 0 else np.sqrt(np.pi / 2) * np.mean(np.abs(vals - med))
        assert q["robust_std"] == pytest.approx(rstd, rel=1e-9, abs=1e-300)
        far = np.max(np.abs(vals - med))
        assert abs(q["farthest"]["value"] - med) == pytest.approx(far, rel=1e-12, abs=1e-300)
        if q["std"] > 0:
            assert q["farthest"]["from_median_std"] == pytest.approx(far / q["std"], rel=1e-9)
    assert [r["run_id"] for r in rows] == list(range(4))
    assert all({"run_id", "run_seed", "failure"} <= set(r) for r in rows)
    assert len({r["run_seed"] for r in rows}) == 4          # four independent streams
    # a quantity's worst run is the run with the largest |value| in the table
    for key, q in doc["quantities"].items():
        vals = [(abs(r[key]), r["run_id"]) for r in rows
                if isinstance(r.get(key), (int, float)) and np.isfinite(r[key])]
        if vals:   # ties (e.g. counts of failed solves): the lowest run id, as the envelope documents
            top = max(v for v, _ in vals)
            assert q["worst"]["run_id"] == min(run for v, run in vals if v == top)
    rep = ogk("replay", str(out), "3")
    assert rep.returncode == 0 and "bit-exact" in rep.stdout, rep.stdout + rep.stderr
    rep = ogk("report", str(out))
    assert rep.returncode in (0, 1) and doc["mission"] in rep.stdout, rep.stderr


@pytest.mark.req("OGK-HAR-001")
@pytest.mark.parametrize("family", FAMILIES)
def test_records_do_not_depend_on_workers_or_chunks(family):
    plan = plan_of(family)
    one = fly_campaign(plan, 4, 11, workers=1, progress=False)
    two = fly_campaign(plan, 4, 11, workers=2, chunk_runs=1, progress=False)
    assert same(without_timing(one.records), without_timing(two.records))
    # a run alone gives the same record as in the campaign
    alone = fly_campaign(plan, 4, 11, workers=1, run_ids=[3], progress=False)
    assert same(without_timing(alone.records), without_timing(one.records[3:4]))


@pytest.mark.req("OGK-HAR-003")
@pytest.mark.parametrize("family", FAMILIES)
def test_a_run_that_raises_in_a_worker_aborts_naming_runs_and_status(family):
    def fault(i):
        if i == 3:
            raise KernelError(7, "ogk_fake_step")
    with pytest.raises(CampaignAborted) as err:
        fly_campaign(faulty(plan_of(family), fault), 6, 1, workers=2, chunk_runs=2,
                     progress=False)
    assert err.value.run_ids == [2, 3] and "KernelError" in err.value.reason
    assert err.value.status is not None


@pytest.mark.req("OGK-HAR-003")
@pytest.mark.parametrize("family", FAMILIES)
def test_a_killed_worker_is_reported_with_its_runs(family):
    def fault(i):
        if i == 4:
            os.kill(os.getpid(), signal.SIGKILL)
    with pytest.raises(CampaignAborted) as err:
        fly_campaign(faulty(plan_of(family), fault), 6, 1, workers=2, chunk_runs=2,
                     progress=False)
    assert err.value.run_ids == [4, 5] and "SIGKILL" in err.value.reason


@pytest.mark.req("OGK-HAR-003")
@pytest.mark.parametrize("family", FAMILIES)
def test_watchdog_kills_a_hung_chunk(family):
    def fault(i):
        if i == 0:
            time.sleep(120)
    start = time.perf_counter()
    with pytest.raises(CampaignAborted) as err:
        fly_campaign(faulty(plan_of(family), fault), 2, 1, workers=2, chunk_runs=1,
                     watchdog=Watchdog(base_s=3.0, per_run_s=0.0), progress=False)
    assert err.value.run_ids == [0] and "watchdog" in err.value.reason
    assert time.perf_counter() - start < 30.0


@pytest.mark.req("OGK-HAR-004")
@pytest.mark.parametrize("family", FAMILIES)
def test_ctrl_c_keeps_finished_runs_and_resume_gives_the_uninterrupted_result(family, tmp_path):
    plan = plan_of(family)
    log = tmp_path / "c.json.runs.jsonl"

    def fault(i):
        if i == 4:
            os.kill(os.getpid(), signal.SIGINT)     # one worker: the chunks fly in this process
    # Ctrl-C as on a terminal: a test run started as a background job by a shell without job
    # control (`make test &`) inherits SIGINT ignored, and Python then keeps it ignored
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        with pytest.raises(CampaignInterrupted) as err:
            fly_campaign(faulty(plan, fault), 6, 5, workers=1, chunk_runs=2, run_log=log,
                         progress=False)
    finally:
        signal.signal(signal.SIGINT, previous)
    assert "4 of 6 runs kept" in err.value.line()
    resumed = fly_campaign(plan, 6, 5, workers=2, chunk_runs=2, run_log=log, resume=True,
                           progress=False)
    assert resumed.resumed_runs == 4 and [r["run_id"] for r in resumed.records] == list(range(6))
    # the kept runs are the interrupted campaign's own records, the others flown now as they
    # would have been (a run's record does not depend on its campaign: the test above)
    kept = sorted((r for r in map(json.loads, log.read_text().splitlines()[1:]) if r["run_id"] < 4),
                  key=lambda r: r["run_id"])
    assert [r["run_id"] for r in kept] == [0, 1, 2, 3]
    assert same(without_timing(resumed.records[:4]), without_timing(kept))
    rest = fly_campaign(plan, 6, 5, workers=1, run_ids=[4, 5], progress=False)
    assert same(without_timing(resumed.records[4:]), without_timing(rest.records))


@pytest.mark.req("OGK-HAR-005")
@pytest.mark.parametrize("family", FAMILIES)
def test_unwritable_output_is_one_line_before_any_flight(family, tmp_path):
    scenario, _ = FAMILIES[family]
    locked = tmp_path / "locked"
    locked.mkdir()
    (locked / "mc.json").mkdir()            # a directory where the JSON must go
    start = time.perf_counter()
    res = ogk("mc", scenario, "--runs", "2", "--json", str(locked / "mc.json"), timeout=120)
    assert res.returncode == 2 and "Traceback" not in res.stderr
    assert res.stderr.count("\n") == 1 and "--json" in res.stderr, res.stderr
    assert time.perf_counter() - start < 60.0
