"""Campaigns that survive faults (harness/ogk/sil/runner.py, runlog.py; docs/sil.md): a kernel error
in a worker and a killed worker end the campaign with one line naming the runs and the status, the
watchdog ends a hung chunk, Ctrl-C keeps the finished runs and `--resume` completes the campaign
bit for bit, and the per-run numbers do not depend on the worker count or the chunking.

Nothing here may hang: in-process campaigns run under an alarm, `ogk mc` under subprocess
timeouts."""
from __future__ import annotations

import dataclasses
import functools
import json
import os
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

import ogk
import ogk_host

from ogk_bindings.kernel import KernelError
from ogk.missions.orbit_injection import nog_guidance
import oi_campaign
from ogk.missions.orbit_injection.guidance import GuidanceSetup, NominalOpenLoopGuidance
from ogk.missions.orbit_injection.nog_guidance import KernelNogGuidance, NogTables, prepare_tables
from ogk.missions.orbit_injection.sil import SilSettings
from ogk.sil.runner import CampaignAborted, Watchdog
from ogk_host.orbit_injection.scenario import Acceptance, load_scenario

REPO = Path(__file__).resolve().parents[2]
OGK = [sys.executable, "-c", "import sys; from ogk.cli import main; sys.exit(main())"]
#: `ogk` subprocesses import the same packages as this test process
ENV = {**os.environ, "PYTHONPATH": os.pathsep.join(
    [str(Path(m.__file__).resolve().parents[1]) for m in (ogk, ogk_host)]
    + [p for p in os.environ.get("PYTHONPATH", "").split(os.pathsep) if p])}
SHORT = functools.partial(NominalOpenLoopGuidance, cutoff_s=12.0)   # 12 s burns: fast tests


#: every in-process test ends within this many seconds (conftest.alarm)
ALARM_S = 90
pytestmark = pytest.mark.usefixtures("alarm")



@pytest.fixture(scope="module")
def scn():
    """The paper's scenario with opened tolerances (the tests check the machinery)."""
    return dataclasses.replace(load_scenario(), acceptance=Acceptance(1e12, 10.0, 1e9))


@pytest.fixture(scope="module")
def tables():
    return prepare_tables(load_scenario())


@pytest.fixture(scope="module")
def corrupted(tables, tmp_path_factory):
    """A copy of the scenario's tables with one byte of the bundle flipped (CRC no longer holds);
    the campaign is handed it directly, so the parent's file check does not stop it first."""
    d = tmp_path_factory.mktemp("bad_tables")
    for p in tables.directory.iterdir():
        if p.is_file():
            shutil.copy(p, d / p.name)
    bundle = d / tables.bundle.name
    data = bytearray(bundle.read_bytes())
    data[len(data) // 2] ^= 0x40
    bundle.write_bytes(bytes(data))
    return NogTables(d, bundle, tables.manifest, tables.sha256)


@pytest.mark.req("OGK-HAR-003", "OGK-CORE-001")
def test_kernel_error_is_picklable():
    import pickle
    err = pickle.loads(pickle.dumps(KernelError(3, "ogk_nog_table_load", partial=lambda: 0)))
    assert (err.code, err.func, err.partial) == (3, "ogk_nog_table_load", None)
    assert err.name.startswith("OGK_E_")


@pytest.mark.req("OGK-HAR-003", "OGK-HAR-008")
def test_corrupted_table_with_two_workers_aborts_naming_runs_and_status(scn, corrupted):
    t0 = time.monotonic()
    with pytest.raises(CampaignAborted) as info:
        oi_campaign.fly(scn, runs=4, seed=1, workers=2, truth="point-mass",
                     guidance_factory=KernelNogGuidance.for_tables(corrupted))
    err = info.value
    assert err.status is not None and err.status.startswith("OGK_E_TABLE")
    line = str(err)
    assert "\n" not in line and err.status in line and "ogk_nog_table_load" in line
    assert line.startswith("campaign aborted: runs 0-1: ") or line.startswith(
        "campaign aborted: runs 2-3: ")
    assert time.monotonic() - t0 < 30.0


@pytest.mark.req("OGK-HAR-003")
def test_ogk_mc_prints_one_line_and_exits_1_when_a_worker_raises(corrupted, tmp_path, capsys,
                                                                 monkeypatch):
    from ogk.cli import main
    monkeypatch.setattr(nog_guidance, "prepare_tables", lambda scn, directory=None: corrupted)
    out = tmp_path / "mc.json"
    out.write_text("{}\n")                             # a previous campaign's result
    code = main(["mc", "leo-geo", "--runs", "4", "--seed", "1", "--workers", "2",
                 "--truth", "point-mass", "--json", str(out)])
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 1 and len(err) == 1
    assert err[0].startswith("ogk mc: campaign aborted: runs ") and "OGK_E_TABLE" in err[0]
    assert not out.exists()                            # no stale JSON left looking new


class _KillsItself(NominalOpenLoopGuidance):
    """The worker holding run 3 is killed (SIGKILL) while it builds its guidance."""

    def __init__(self, setup: GuidanceSetup) -> None:
        if 3 in setup.run_ids.tolist():
            os.kill(os.getpid(), signal.SIGKILL)
        super().__init__(setup, cutoff_s=12.0)


@pytest.mark.req("OGK-HAR-003")
def test_killed_worker_is_reported_with_its_runs(scn, tmp_path):
    log = tmp_path / "mc.json.runs.jsonl"
    with pytest.raises(CampaignAborted) as info:
        oi_campaign.fly(scn, runs=6, seed=1, workers=2, chunks=3, truth="point-mass",
                     guidance_factory=_KillsItself, run_log=log)
    line = str(info.value)
    assert line.startswith("campaign aborted: runs 2-3: worker pid ")
    assert "killed by SIGKILL" in line and "\n" not in line
    assert info.value.run_ids == [2, 3]
    kept = [json.loads(x)["run_id"] for x in log.read_text().splitlines()[1:]]
    assert 2 not in kept and 3 not in kept             # what finished is kept, nothing else


@pytest.mark.req("OGK-HAR-003")
def test_ogk_mc_reports_a_killed_worker_in_one_line(tmp_path, capsys, monkeypatch):
    from ogk.cli import main
    from ogk.missions.orbit_injection import guidance as guidance_module
    monkeypatch.setattr(guidance_module, "NominalOpenLoopGuidance", _KillsItself)
    out = tmp_path / "mc.json"
    code = main(["mc", "leo-geo", "--runs", "6", "--seed", "1", "--workers", "2",
                 "--chunk-runs", "2", "--truth", "point-mass", "--guidance", "nominal",
                 "--json", str(out)])
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 1 and len(err) == 1, err
    assert err[0].startswith("ogk mc: campaign aborted: runs 2-3: worker pid "), err[0]
    assert "killed by SIGKILL" in err[0]
    assert not out.exists()
    kept = [json.loads(x)["run_id"] for x in
            (tmp_path / "mc.json.runs.jsonl").read_text().splitlines()[1:]]
    assert 2 not in kept and 3 not in kept             # resumable: the finished chunks are kept


class _Hangs(NominalOpenLoopGuidance):
    def __init__(self, setup: GuidanceSetup) -> None:
        if 1 in setup.run_ids.tolist():
            time.sleep(3600)
        super().__init__(setup, cutoff_s=12.0)


@pytest.mark.req("OGK-HAR-003")
def test_watchdog_kills_a_hung_chunk(scn):
    t0 = time.monotonic()
    with pytest.raises(CampaignAborted) as info:
        oi_campaign.fly(scn, runs=2, seed=1, workers=2, truth="point-mass", guidance_factory=_Hangs,
                     watchdog=Watchdog(base_s=3.0, per_run_s=0.5))
    assert str(info.value).startswith("campaign aborted: runs 1: watchdog: no result after 4 s")
    assert time.monotonic() - t0 < 20.0


def _per_run(res) -> str:
    """Every per-run value of the JSON, as written (repr of each float: bit for bit)."""
    return json.dumps(res.to_json_dict()["per_run"])


def _nog(tables, truth, workers=1, chunks=None, rate_hz=50.0):
    """Kernel VTD-NOG, 3 dispersed runs of seed 7 (their cut-offs differ: the runs land on
    different steps)."""
    return oi_campaign.fly(load_scenario(), runs=3, seed=7, workers=workers, chunks=chunks,
                        truth=truth, guidance_factory=KernelNogGuidance.for_tables(tables),
                        guidance_name="nog", tables=tables,
                        settings=SilSettings(control_rate_hz=rate_hz))


@pytest.fixture(scope="module")
def reference(tables):
    """Point-mass, 25 Hz, 1 worker, 1 chunk: what `ogk mc leo-geo --runs 3 --seed 7 --truth
    point-mass --control-rate 25` must write, interrupted and resumed or not."""
    return _nog(tables, "point-mass", rate_hz=25.0)


@pytest.mark.req("OGK-HAR-001")
def test_per_run_values_do_not_depend_on_workers_or_chunks(tables):
    """6-DOF (a landing step of one run used to change the eq. 55 factor of the other runs of its
    chunk by an ulp, which the attitude loop carried to 1e-14: run 0 of these differed): 1 worker
    / 1 chunk and 2 workers / 3 chunks write the same per-run values, bit for bit."""
    one = _nog(tables, "6dof")
    tf = one.errors["tf_s"]
    assert np.unique(np.round(tf, 6)).size == tf.size      # every run lands on its own step
    for workers, chunks in ((2, 3),):
        other = _nog(tables, "6dof", workers, chunks)
        assert _per_run(other) == _per_run(one), (workers, chunks)
        assert other.to_json_dict()["std"] == one.to_json_dict()["std"]


def _wait_for_runs(log: Path, proc: subprocess.Popen, n: int, timeout: float) -> int:
    end = time.monotonic() + timeout
    while time.monotonic() < end and proc.poll() is None:
        if log.exists() and len(log.read_text().splitlines()) - 1 >= n:
            return len(log.read_text().splitlines()) - 1
        time.sleep(0.05)
    raise AssertionError(f"no {n} runs in {log} (exit {proc.poll()})")


@pytest.mark.req("OGK-HAR-004")
def test_ctrl_c_keeps_finished_runs_and_resume_gives_the_uninterrupted_result(reference,
                                                                              tmp_path):
    out = tmp_path / "mc.json"
    log = tmp_path / "mc.json.runs.jsonl"
    out.write_text("{}\n")                              # a previous campaign's result
    def command(seed: int) -> list[str]:
        return [*OGK, "mc", "leo-geo", "--runs", "3", "--seed", str(seed), "--workers", "2",
                "--chunk-runs", "1", "--truth", "point-mass", "--control-rate", "25",
                "--json", str(out)]
    cmd = command(7)
    # SIGINT back to its default in the child: a test run started as a background job by a shell
    # without job control (`make test &`) inherits SIGINT ignored, and Python then keeps it ignored,
    # so the Ctrl-C below would be lost and the campaign would finish (exit 0).
    proc = subprocess.Popen(cmd, cwd=REPO, env=ENV, stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True,
                            preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    try:
        kept = _wait_for_runs(log, proc, 1, 60.0)
        proc.send_signal(signal.SIGINT)
        _, err = proc.communicate(timeout=30)
    finally:
        proc.kill()
    lines = err.strip().splitlines()
    assert proc.returncode == 130 and len(lines) == 1, err
    assert lines[0].startswith("ogk mc: campaign interrupted: ") and "--resume" in lines[0]
    assert not out.exists()
    kept = len(log.read_text().splitlines()) - 1
    assert 1 <= kept < 3
    done = subprocess.run([*cmd, "--resume"], cwd=REPO, env=ENV, capture_output=True, text=True,
                          timeout=90)
    assert done.returncode in (0, 1), done.stderr      # 1: a run outside the tolerances
    assert f"{kept} of 3 runs taken from" in done.stdout
    doc = json.loads(out.read_text())
    assert doc["resumed_runs"] == kept
    assert json.dumps(doc["per_run"]) == _per_run(reference)
    assert doc["std"] == reference.to_json_dict()["std"]
    # another seed does not resume from this file: one line, exit 2
    other = subprocess.run([*command(8), "--resume"], cwd=REPO,
                           capture_output=True, text=True, timeout=60)
    assert other.returncode == 2 and "belongs to another campaign (differs in seed)" in other.stderr
