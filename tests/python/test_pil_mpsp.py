"""Processor in the loop for MPSP re-planning (docs/guides/flight-integration-mpsp.md): `ogk mc SCENARIO
--target m7` solves every run's problem with the scenario's flight program
(port/cortex-m7/pil/mpsp_pil.c over mpsp_flight.c: ogk_mpsp_init, ogk_mpsp_solve,
ogk_mpsp_thrust_cmd) on QEMU's Cortex-M7, the host drawing the problems and judging the results.

On a mission no other file names, made from a copy of scenarios/apophis_cubesat.toml as a user
would (smaller dispersions: kappa in [-1, 1], eta in [3, 6] %, the paper's target cube; no
published results), a 3-run dispersed campaign (one initial-state, one target, one thrust
perturbation):
- every run converges within the scenario's tolerances on the target, and the target agrees with
  the host campaign on the same draws within the family's bounds (pil.BOUNDS): the same Newton
  iteration counts, continuation steps and thrust arcs; the terminal errors and final mass to the
  ulps of newlib's libm;
- every entry point carries its instruction counts and stack per run (one init and one solve per
  run), the envelope names the worst call, and the measured stack is within gcc's static worst
  case per entry point (make arm-stack) plus libm's frames;
- `ogk replay` flies a run of the target campaign again on the target, bit for bit.
About 20 s on a quiet machine, 33 s with load average 4 on 2 cores (QEMU: 2 sessions at once).
"""
from __future__ import annotations

import json
import re
import subprocess
import sys
from pathlib import Path

import pytest
from pil_checks import assert_stack_within_static, assert_worst_matches_records

ROOT = Path(__file__).resolve().parents[2]
OGK = Path(sys.executable).parent / "ogk"
SEED = "20261203"
ENTRIES = ("ogk_mpsp_init", "ogk_mpsp_solve", "ogk_mpsp_thrust_cmd")


def ogk(*args: str, timeout: float = 600.0) -> subprocess.CompletedProcess[str]:
    return subprocess.run([str(OGK), *args], capture_output=True, text=True, timeout=timeout,
                          cwd=ROOT)


def small_dispersions(directory: Path) -> Path:
    text = (ROOT / "scenarios" / "apophis_cubesat.toml").read_text()
    text = text.split("# ---------------------------------------------------------------- published")[0]
    for key, value in {"name": '"pil_mpsp_small"', "kappa": "[-1.0, 1.0]",
                       "eta_percent": "[3.0, 6.0]"}.items():
        text, n = re.subn(rf"^{key} = .*$", f"{key} = {value}", text, flags=re.M)
        assert n == 1, key
    path = directory / "pil_mpsp_small.toml"
    path.write_text(text)
    return path


@pytest.fixture(scope="module")
def campaign(tmp_path_factory: pytest.TempPathFactory) -> dict:
    d = tmp_path_factory.mktemp("pil_mpsp")
    scenario = small_dispersions(d)
    out = ogk("mc", str(scenario), "--target", "m7", "--runs", "3", "--seed", SEED,
              "--json", str(d / "m7.json"))
    assert out.returncode == 0, out.stdout[-3000:] + out.stderr[-3000:]
    host = ogk("mc", str(scenario), "--runs", "3", "--seed", SEED, "--json", str(d / "host.json"))
    assert host.returncode == 0, host.stdout[-2000:] + host.stderr[-2000:]
    import pyarrow.parquet as pq
    return {"dir": d, "stdout": out.stdout, "doc": json.loads((d / "m7.json").read_text()),
            "records": pq.read_table(d / "m7.parquet").to_pylist(),
            "host": pq.read_table(d / "host.parquet").to_pylist()}


@pytest.mark.req("OGK-HAR-012", "OGK-MPSP-012")
def test_target_campaign_passes_and_agrees_with_the_host(campaign: dict) -> None:
    from ogk.missions.low_thrust_transfer.pil import BOUNDS
    doc = campaign["doc"]
    assert doc["target"] == "m7" and doc["failures"] == 0 and doc["runs"] == 3
    assert doc["options"]["target"] == "m7" and "flight_program" in doc["products"]
    hv = doc["pil"]["host_vs_target"]
    assert hv["runs_compared"] == 3 and hv["within_bounds"] and not hv["failures_differ"]
    assert set(hv["quantities"]) == set(BOUNDS)
    host = {r["run_id"]: r for r in campaign["host"]}
    for r in campaign["records"]:
        h = host[r["run_id"]]
        assert r["converged"] and r["failure"] == ""
        # the host campaign flown on its own: the same problem (draws), the same iterations
        assert (r["kind"], r["kappa"], r["eta_percent"], r["delta_rf_lu"]) == \
            (h["kind"], h["kappa"], h["eta_percent"], h["delta_rf_lu"])
        assert r["newton_iterations"] == h["newton_iterations"] > 0
        for key, bound in BOUNDS.items():
            assert abs(r[key] - h[key]) <= bound, (r["run_id"], key, r[key], h[key])
    # the records carry the host's keys, plus the pil.* ones
    assert {k for k in campaign["records"][0] if not k.startswith("pil.")} == set(campaign["host"][0])
    assert sorted(r["kind"] for r in campaign["records"]) == ["initial", "terminal", "thrust"]


@pytest.mark.req("OGK-HAR-012", "OGK-MPSP-013")
def test_every_entry_point_has_its_figures_per_run(campaign: dict) -> None:
    for r in campaign["records"]:
        for e in ENTRIES:
            assert r[f"pil.{e}.calls"] == 1, e          # one init and one re-plan per run
            assert r[f"pil.{e}.insn_max"] >= r[f"pil.{e}.insn_median"] > 0, e
            assert 0 < r[f"pil.{e}.stack_bytes"] < 12288, e
            assert not r.get(f"pil.{e}.stack_window_exceeded"), e
        assert r["pil.ogk_mpsp_init.insn_max_step"] == 0       # step 0: MPSP_INIT
        assert r["pil.ogk_mpsp_solve.insn_max_step"] == 1      # step 1: MPSP_REPLAN
        # a solve is at least its Newton iterations' propagations (2048 RK4 steps each)
        assert r["pil.ogk_mpsp_solve.insn_max"] > 1e6 * r["newton_iterations"]
    assert_worst_matches_records(campaign["doc"], campaign["records"], ENTRIES)
    assert "On the target (m7)" in campaign["stdout"] and "Host vs target" in campaign["stdout"]


@pytest.mark.req("OGK-HAR-012", "OGK-CORE-006", "OGK-MPSP-013")
def test_stack_is_within_the_static_worst_case(campaign: dict) -> None:
    """What the painted window measured on the target is at most gcc's static worst case per entry
    point (make arm-stack: own frame + deepest path through the kernel's call graph) plus libm."""
    assert_stack_within_static(campaign["doc"]["pil"]["entry_points"], ENTRIES)


@pytest.mark.req("OGK-HAR-012", "OGK-MPSP-012")
def test_replay_flies_the_run_again_on_the_target(campaign: dict) -> None:
    out = ogk("replay", str(campaign["dir"] / "m7.json"), "1")
    assert out.returncode == 0, out.stdout[-2000:] + out.stderr[-2000:]
    assert "bit-exact" in out.stdout


@pytest.mark.req("OGK-HAR-012", "OGK-MPSP-012")
def test_flight_software_reacts_to_every_status_on_the_target(campaign: dict) -> None:
    """mpsp_flight.c's reactions, on the target: a bad request is refused and the plan held kept
    (HOLD: the nominal before the first re-plan, the last plan after it), a request MPSP cannot
    solve flies the kernel's safe plan (SAFE, the host's iterations and weights), a command
    outside [t0, tf] is the kernel's safe command (SAFE, engine off), a good request flies (FLY)
    with the host's iterations and weights. (NOT_INIT and CONFIG need a corrupted context or configuration,
    which the link cannot make: they are the kernel tests'.)"""
    import numpy as np

    from ogk_host.scenario_file import read_header

    from ogk.missions.low_thrust_transfer import pil
    from ogk.missions.low_thrust_transfer.cases import thrust_case
    from ogk.missions.low_thrust_transfer.family import FAMILY
    from ogk.sil.pil import PilSession
    fly, safe, hold = 0.0, 1.0, 2.0
    ok, nonfinite, out_of_range, not_converged = 0.0, 2.0, 4.0, 20.0
    scenario = campaign["dir"] / "pil_mpsp_small.toml"
    plan = FAMILY.plan(read_header(scenario), {})
    setup = plan.base.setup
    case = thrust_case(setup, 3.0)
    host = setup.guidance.solve(case.x0, case.thrust_scale, case.target)
    session = PilSession(FAMILY.flight_program(plan, "m7"))
    try:
        init = session.exchange(pil.MPSP_INIT, [])
        assert init[0] == fly and init[1] == setup.guidance.n_weights
        tf = float(init[3])
        bad_mass = pil.request(case)
        bad_mass[6] = -1.0                                   # m0 <= 0
        r = session.exchange(pil.MPSP_REPLAN, bad_mass)
        assert (r[0], r[1]) == (hold, out_of_range)
        assert r[23] == fly            # no re-plan yet: the nominal the init propagated flies
        good = session.exchange(pil.MPSP_REPLAN, pil.request(case))
        assert (good[0], good[1], good[23]) == (fly, ok, fly) and good[24] in (0.0, 1.0)
        assert int(good[3]) == host.newton_iterations
        np.testing.assert_allclose(good[pil.REPLY_HEAD:pil.REPLY_HEAD + int(good[29])],
                                   host.weights, rtol=0, atol=1e-9)
        nan_fix = pil.request(case)
        nan_fix[0] = float("nan")
        r = session.exchange(pil.MPSP_REPLAN, nan_fix)
        assert (r[0], r[1]) == (hold, nonfinite)
        assert np.array_equal(r[2:23], good[2:23]) and r[23] == fly   # the previous plan flies
        # T_max tripled: MPSP does not converge (6 iterations, 18 continuation loops); the safe
        # plan (the weights of the largest continuation parameter solved) is the host's and flies
        weak = thrust_case(setup, 200.0)
        host_weak = setup.guidance.solve(weak.x0, weak.thrust_scale, weak.target)
        assert not host_weak.converged
        r = session.exchange(pil.MPSP_REPLAN, pil.request(weak))
        assert (r[0], r[1], r[2]) == (safe, not_converged, 0.0)
        assert int(r[3]) == host_weak.newton_iterations and int(r[5]) == host_weak.outer_steps
        assert r[7] == pytest.approx(host_weak.tau_reached, abs=1e-12)
        np.testing.assert_allclose(r[pil.REPLY_HEAD:pil.REPLY_HEAD + int(r[29])],
                                   host_weak.weights, rtol=0, atol=1e-9)
        assert r[23] == fly
        late = session.exchange(pil.MPSP_REPLAN, pil.request(case, t_cmd=tf + 1.0))
        assert late[0] == fly and late[23] == safe and late[24] == 0.0   # t outside [t0, tf]
        assert int(late[28]) & 0x02                                     # OGK_THRUST_FLAG_SAFE
        session.end_run(0)
        keys = session.close()[0]
    except BaseException:
        session.kill()
        raise
    assert keys["pil.ogk_mpsp_solve.calls"] == 5 and keys["pil.ogk_mpsp_thrust_cmd.calls"] == 5
