"""Processor in the loop for orbit injection (docs/guides/pil.md): `ogk mc SCENARIO --target m7` flies the
scenario's flight program (port/cortex-m7/pil/oi_pil.c over oi_flight.c) on QEMU's Cortex-M7.

On a mission no other file names (a heavier kick stage than the paper's: n0 = 1.25 g0, c = 3.2 km/s),
made from a copy of scenarios/leo_geo.toml as a user would:
- the target campaign passes the scenario's tolerances and agrees with the host campaign on the same
  draws within the family's stated bounds (the host campaign is flown independently, in this process);
- every entry point a tick calls carries its instruction counts and stack in the records, the envelope
  names the worst call with its run and step, and the stack stays under gcc's static worst case;
- `ogk replay` flies a run of the target campaign again on the target, bit for bit.
The parsing of the plugin's call log and the host-vs-target figures are checked on hand-made inputs.
"""
from __future__ import annotations

import json
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from ogk.sil import pil, target_summary
from pil_checks import assert_stack_within_static, assert_worst_matches_records

ROOT = Path(__file__).resolve().parents[2]
OGK = Path(sys.executable).parent / "ogk"
SEED = "20261203"
ENTRIES = ("ogk_nog_sample", "ogk_cutoff_step", "ogk_nog_thrust_cmd", "ogk_terminal_step",
           "ogk_cpd_step")


def ogk(*args: str, timeout: float = 600.0) -> subprocess.CompletedProcess[str]:
    return subprocess.run([str(OGK), *args], capture_output=True, text=True, timeout=timeout,
                          cwd=ROOT)


def heavy_kick_stage(directory: Path) -> Path:
    text = (ROOT / "scenarios" / "leo_geo.toml").read_text()
    text = re.sub(r'^name = "leo_geo"', 'name = "pil_heavy_kick"', text, flags=re.M)
    text = re.sub(r"^initial_accel_g0 = 1\.112", "initial_accel_g0 = 1.25", text, flags=re.M)
    text = re.sub(r"^exhaust_velocity_m_s = 3000\.0", "exhaust_velocity_m_s = 3200.0", text,
                  flags=re.M)
    text = text[:text.index("[paper_results]")]          # not the paper's case
    path = directory / "pil_heavy_kick.toml"
    path.write_text(text)
    return path


@pytest.fixture(scope="module")
def campaign(tmp_path_factory: pytest.TempPathFactory) -> dict:
    d = tmp_path_factory.mktemp("pil_oi")
    scenario = heavy_kick_stage(d)
    out = ogk("mc", str(scenario), "--target", "m7", "--runs", "3", "--seed", SEED,
              "--json", str(d / "m7.json"))
    assert out.returncode == 0, out.stdout[-3000:] + out.stderr[-3000:]
    host = ogk("mc", str(scenario), "--runs", "3", "--seed", SEED, "--json", str(d / "host.json"))
    assert host.returncode == 0, host.stdout[-2000:] + host.stderr[-2000:]
    import pyarrow.parquet as pq
    return {"dir": d, "scenario": scenario, "stdout": out.stdout,
            "doc": json.loads((d / "m7.json").read_text()),
            "records": pq.read_table(d / "m7.parquet").to_pylist(),
            "host": pq.read_table(d / "host.parquet").to_pylist()}


@pytest.mark.req("OGK-HAR-012", "OGK-NOG-018")
def test_target_campaign_passes_and_agrees_with_the_host(campaign: dict) -> None:
    doc = campaign["doc"]
    assert doc["target"] == "m7" and doc["failures"] == 0 and doc["runs"] == 3
    assert doc["options"]["target"] == "m7" and "flight_program" in doc["products"]
    hv = doc["pil"]["host_vs_target"]
    assert hv["runs_compared"] == 3 and hv["within_bounds"] and not hv["failures_differ"]
    # the host campaign flown on its own agrees run by run within the family's bounds
    from ogk.missions.orbit_injection.pil import BOUNDS
    host = {r["run_id"]: r for r in campaign["host"]}
    for r in campaign["records"]:
        for key, bound in BOUNDS.items():
            assert abs(r[key] - host[r["run_id"]][key]) <= bound, (r["run_id"], key)
    # and the draws are the host's (same streams)
    assert [r["d_state"] for r in campaign["records"]] == \
        [host[r["run_id"]]["d_state"] for r in campaign["records"]]


@pytest.mark.req("OGK-HAR-012", "OGK-NOG-018", "OGK-NOG-020", "OGK-CPD-013")
def test_every_entry_point_has_its_figures_per_run(campaign: dict) -> None:
    for r in campaign["records"]:
        ticks = r[f"pil.ogk_cpd_step.calls"]
        assert ticks > 3000                      # a ~95 s burn at 50 Hz
        for e in ENTRIES:
            assert r[f"pil.{e}.insn_max"] >= r[f"pil.{e}.insn_median"] > 0, e
            assert 0 < r[f"pil.{e}.stack_bytes"] < 4096, e
            assert 0 <= r[f"pil.{e}.insn_max_step"] < ticks + 1
        # one command and one CPD step per tick; samples every 2 s, faster at the end
        assert r["pil.ogk_nog_thrust_cmd.calls"] == ticks
        t_f = r["tf_s"]
        assert t_f / 2.0 < r["pil.ogk_nog_sample.calls"] < t_f / 2.0 + 60
    assert_worst_matches_records(campaign["doc"], campaign["records"], ENTRIES)
    assert "On the target (m7)" in campaign["stdout"] and "Host vs target" in campaign["stdout"]


@pytest.mark.req("OGK-HAR-012", "OGK-CORE-006", "OGK-NOG-020")
def test_stack_is_within_the_static_worst_case(campaign: dict) -> None:
    """What the painted window measured on the target is at most gcc's static worst case per entry
    point (make arm-stack: own frame + deepest path through the kernel's call graph) plus libm."""
    assert_stack_within_static(campaign["doc"]["pil"]["entry_points"], ENTRIES)


@pytest.mark.req("OGK-HAR-012", "OGK-NOG-018")
def test_replay_flies_the_run_again_on_the_target(campaign: dict) -> None:
    out = ogk("replay", str(campaign["dir"] / "m7.json"), "2")
    assert out.returncode == 0, out.stdout[-2000:] + out.stderr[-2000:]
    assert "bit-exact" in out.stdout


@pytest.mark.req("OGK-HAR-012")
def test_call_log_is_cut_into_runs_and_steps() -> None:
    log = ["a 10", "b 7", pil.TICK_MARK + " 4", "a 12", pil.TICK_MARK + " 4", "b 9", "a 12",
           pil.TICK_MARK + " 4", pil.RUN_MARK + " 5", "a 3", pil.TICK_MARK + " 4", pil.RUN_MARK + " 5"]
    runs = pil.parse_calls(log, ("a", "b"))
    assert len(runs) == 2
    assert runs[0].counts == {"a": [10, 12, 12], "b": [7, 9]}
    assert runs[0].steps == {"a": [0, 1, 2], "b": [0, 2]}
    keys = pil.entry_keys(runs[0], [40, 8], 0b10, ("a", "b"))
    assert keys["pil.a.calls"] == 3 and keys["pil.a.insn_median"] == 12.0
    assert keys["pil.a.insn_max"] == 12 and keys["pil.a.insn_max_step"] == 1   # the first maximum
    assert keys["pil.b.insn_max"] == 9 and keys["pil.b.insn_max_step"] == 2
    assert keys["pil.a.stack_bytes"] == 40 and keys["pil.b.stack_window_exceeded"] is True
    assert "pil.a.stack_window_exceeded" not in keys
    assert pil.entry_keys(runs[1], [0, 0], 0, ("a", "b"))["pil.b.insn_max"] is None


@pytest.mark.req("OGK-HAR-012")
def test_host_vs_target_names_the_worst_run() -> None:
    target = [{"run_id": 0, "x": 1.0, "failure": ""}, {"run_id": 1, "x": 2.5, "failure": ""},
              {"run_id": 2, "x": np.nan, "failure": "guidance"}]
    host = [{"run_id": 0, "x": 1.1, "failure": ""}, {"run_id": 1, "x": 2.0, "failure": ""},
            {"run_id": 2, "x": 3.0, "failure": ""}]
    hv = target_summary.host_vs_target(target, host, {"x": 0.4})
    q = hv["quantities"]["x"]
    assert q["run_id"] == 1 and q["max_abs_diff"] == pytest.approx(0.5) and not q["within"]
    assert hv["failures_differ"] == [2] and not hv["within_bounds"]
    assert target_summary.host_vs_target(target[:2], host[:2], {"x": 0.6})["within_bounds"]


@pytest.mark.req("OGK-HAR-012", "OGK-HAR-005")
@pytest.mark.parametrize("option", [("--truth", "point-mass"), ("--control-rate", "25"),
                                    ("--cpd-gains", "printed"), ("--paper-end-game",)])
def test_options_the_flight_configuration_does_not_fly_are_refused(option: tuple[str, ...],
                                                                    tmp_path: Path) -> None:
    """The flight program flies the generated configuration: a campaign option it does not fly is
    refused in one line naming the option, before anything is built or flown."""
    out = ogk("mc", "leo-geo", "--target", "m7", "--runs", "1", *option,
              "--json", str(tmp_path / "x.json"), timeout=120)
    assert out.returncode == 2, out.stdout + out.stderr
    line = out.stderr.strip().splitlines()[-1]
    assert f"{option[0]}: --target m7 flies the generated flight configuration" in line
    assert not (tmp_path / "x.json").exists()
