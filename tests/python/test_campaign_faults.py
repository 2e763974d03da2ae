"""Campaigns that survive faults (harness/ogk/sil/runner.py, runlog.py; docs/guides/campaigns.md, "Faults"),
flown by the test family (point_mass_family.py): a kernel error in a worker and a killed worker end
the campaign with one line naming the runs and the status, the watchdog ends a hung chunk, Ctrl-C
keeps the finished runs and `--resume` completes the campaign bit for bit; and the test family itself
is a fifth family made of one class and one registry line, flown by every verb of `ogk`.

Nothing here may hang: in-process campaigns run under an alarm, `ogk mc` under subprocess
timeouts."""
from __future__ import annotations

import json
import signal
import subprocess
import time
from pathlib import Path

import pytest

from ogk_bindings.kernel import KernelError
from ogk_host.scenario_file import read_header

from ogk.cli import main
from ogk.missions import registry
from ogk.sil import envelope
from ogk.sil.engine import fly_campaign
from ogk.sil.runner import CampaignAborted, Watchdog

import point_mass_family as pm

#: every in-process test ends within this many seconds (conftest.alarm)
ALARM_S = 90
pytestmark = pytest.mark.usefixtures("alarm", "family")


@pytest.fixture(scope="module")
def family():
    with pm.registered():
        yield pm.FAMILY


@pytest.fixture(scope="module")
def scenario(tmp_path_factory) -> Path:
    return pm.write_scenario(tmp_path_factory.mktemp("pm") / "point_mass.toml")


def plan(scenario: Path, **options):
    return pm.FAMILY.plan(read_header(scenario), options)


@pytest.mark.req("OGK-HAR-003", "OGK-CORE-001")
def test_kernel_error_is_picklable():
    import pickle
    err = pickle.loads(pickle.dumps(KernelError(3, "ogk_nog_table_load", partial=lambda: 0)))
    assert (err.code, err.func, err.partial) == (3, "ogk_nog_table_load", None)
    assert err.name.startswith("OGK_E_")


@pytest.mark.req("OGK-HAR-003")
def test_a_kernel_error_in_a_worker_aborts_naming_runs_and_status(scenario):
    t0 = time.monotonic()
    with pytest.raises(CampaignAborted) as info:
        fly_campaign(plan(scenario, fault="raise:3"), 4, 1, workers=2, progress=False)
    err = info.value
    assert err.status == "OGK_E_DIM" and err.run_ids == [2, 3]
    line = str(err)
    assert "\n" not in line and err.status in line and "ogk_point_mass_step" in line
    assert line.startswith("campaign aborted: runs 2-3: ")
    assert time.monotonic() - t0 < 30.0


@pytest.mark.req("OGK-HAR-003")
def test_ogk_mc_prints_one_line_and_exits_1_when_a_worker_raises(scenario, tmp_path, capsys):
    out = tmp_path / "mc.json"
    out.write_text("{}\n")                             # a previous campaign's result
    code = main(["mc", str(scenario), "--runs", "4", "--seed", "1", "--workers", "2",
                 "--fault", "raise:1", "--json", str(out)])
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 1 and len(err) == 1
    assert err[0].startswith("ogk mc: campaign aborted: runs 0-1: ") and "OGK_E_DIM" in err[0]
    assert not out.exists()                            # no stale JSON left looking new


@pytest.mark.req("OGK-HAR-003")
def test_killed_worker_is_reported_with_its_runs(scenario, tmp_path):
    log = tmp_path / "mc.json.runs.jsonl"
    with pytest.raises(CampaignAborted) as info:
        fly_campaign(plan(scenario, fault="kill:3"), 6, 1, workers=2, chunks=3, run_log=log,
                     progress=False)
    line = str(info.value)
    assert line.startswith("campaign aborted: runs 2-3: worker pid ")
    assert "killed by SIGKILL" in line and "\n" not in line
    assert info.value.run_ids == [2, 3]
    kept = [json.loads(x)["run_id"] for x in log.read_text().splitlines()[1:]]
    assert 2 not in kept and 3 not in kept             # what finished is kept, nothing else


@pytest.mark.req("OGK-HAR-003")
def test_ogk_mc_reports_a_killed_worker_in_one_line(scenario, tmp_path, capsys):
    out = tmp_path / "mc.json"
    code = main(["mc", str(scenario), "--runs", "6", "--seed", "1", "--workers", "2",
                 "--chunk-runs", "2", "--fault", "kill:3", "--json", str(out)])
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 1 and len(err) == 1, err
    assert err[0].startswith("ogk mc: campaign aborted: runs 2-3: worker pid "), err[0]
    assert "killed by SIGKILL" in err[0]
    assert not out.exists()
    kept = [json.loads(x)["run_id"] for x in
            (tmp_path / "mc.json.runs.jsonl").read_text().splitlines()[1:]]
    assert 2 not in kept and 3 not in kept             # resumable: the finished chunks are kept


@pytest.mark.req("OGK-HAR-003")
def test_watchdog_kills_a_hung_chunk(scenario):
    t0 = time.monotonic()
    with pytest.raises(CampaignAborted) as info:
        fly_campaign(plan(scenario, fault="hang:1"), 2, 1, workers=2,
                     watchdog=Watchdog(base_s=3.0, per_run_s=0.5), progress=False)
    assert str(info.value).startswith("campaign aborted: runs 1: watchdog: no result after 4 s")
    assert time.monotonic() - t0 < 20.0


def _wait_for_runs(log: Path, proc: subprocess.Popen, n: int, timeout: float) -> int:
    end = time.monotonic() + timeout
    while time.monotonic() < end and proc.poll() is None:
        if log.exists() and len(log.read_text().splitlines()) - 1 >= n:
            return len(log.read_text().splitlines()) - 1
        time.sleep(0.05)
    raise AssertionError(f"no {n} runs in {log} (exit {proc.poll()})")


@pytest.mark.req("OGK-HAR-004")
def test_ctrl_c_keeps_finished_runs_and_resume_gives_the_uninterrupted_result(scenario, tmp_path):
    out = tmp_path / "mc.json"
    log = tmp_path / "mc.json.runs.jsonl"
    out.write_text("{}\n")                              # a previous campaign's result

    def command(seed: int) -> list[str]:
        return [*pm.OGK, "mc", str(scenario), "--runs", "3", "--seed", str(seed), "--workers",
                "2", "--chunk-runs", "1", "--seconds-per-run", "1", "--json", str(out)]
    cmd = command(7)
    # SIGINT back to its default in the child: a test run started as a background job by a shell
    # without job control (`make test &`) inherits SIGINT ignored, and Python then keeps it ignored,
    # so the Ctrl-C below would be lost and the campaign would finish (exit 0).
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    try:
        _wait_for_runs(log, proc, 1, 60.0)
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
    done = subprocess.run([*cmd, "--resume"], capture_output=True, text=True, timeout=90)
    assert done.returncode in (0, 1), done.stderr      # 1: a run outside the tolerance
    assert f"{kept} of 3 runs taken from" in done.stdout
    doc = json.loads(out.read_text())
    assert doc["resumed_runs"] == kept
    rows = envelope.read_table(out.with_suffix(".parquet"))
    uninterrupted = fly_campaign(plan(scenario, seconds_per_run=1.0), 3, 7, progress=False)
    for row, rec in zip(rows, uninterrupted.records, strict=True):
        assert not envelope.record_differences(row, rec), row["run_id"]
    # another seed does not resume from this file: one line, exit 2
    other = subprocess.run([*command(8), "--resume"], capture_output=True, text=True, timeout=60)
    assert other.returncode == 2 and "belongs to another campaign (differs in seed)" in other.stderr


@pytest.mark.req("OGK-HAR-021")
def test_a_fifth_family_is_one_class_and_one_registry_line(scenario, tmp_path, capsys):
    """The test family, registered by one line, is flown by every verb of `ogk`: mc, replay,
    report, run; `ogk tables` says it has none."""
    assert registry.family(read_header(scenario)) is pm.FAMILY
    out = tmp_path / "mc.json"
    assert main(["mc", str(scenario), "--runs", "5", "--seed", "3", "--json", str(out)]) in (0, 1)
    assert "point_mass: 5 runs" in capsys.readouterr().out
    assert main(["replay", str(out), "4"]) == 0 and "bit-exact" in capsys.readouterr().out
    assert main(["report", str(out)]) in (0, 1) and "point_mass" in capsys.readouterr().out
    assert main(["run", str(scenario), "--x0", "2"]) == 0 and "x_f" in capsys.readouterr().out
    assert main(["tables", str(scenario)]) == 2
    assert "has no `ogk tables`" in capsys.readouterr().err
