"""The proximity-approach family (issue 33 part 3; harness/ogk/missions/proximity): the kernel's second NMPC
problem (ogk_prox_*, through ogk_bindings.proximity) and its IPOPT ground peer flown in closed loop against
a two-body truth that shares nothing with the kernel's Clohessy-Wiltshire model, through the engine's one
family protocol (test_family_protocol.py covers its verbs: the family is in the registry).

Checked here: the truth against the CW closed form where CW holds and against itself at a tighter tolerance,
the thrust applied as commanded (the r-t-n vector of the target's Hill frame, the bias, the minimum throttle);
one nominal flight of each law reaches the hold point at rest without entering the keep-out disc in the
truth, within the propellant budget; a short dispersed campaign through the engine loses no run and applies
its dispersions; a mission no other file names (another orbit, vehicle, start, hold point and disc) flown
by `ogk run` and `ogk mc` as a user would."""
from __future__ import annotations

import dataclasses
import json
import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from ogk_host.proximity.dynamics import Vehicle, coast_stm, rk4_interval
from ogk_host.proximity.scenario import load_scenario
from ogk_host.scenario_file import read_header, resolve_scenario

from ogk.missions import registry
from ogk.missions.proximity import closed_loop, truth as tr
from ogk.missions.proximity.family import FAMILY, judge
from ogk.missions.proximity.guidance import ground_plan
from ogk.sil import dispersion_check as dc
from ogk.sil.engine import fly_campaign

pytestmark = pytest.mark.req("OGK-HAR-022")

REPO = Path(__file__).resolve().parents[2]
OGK = Path(sys.executable).parent / "ogk"
SCENARIO = resolve_scenario("proximity_approach")
MU = 3.986004418e14


@pytest.fixture(scope="module")
def scenario():
    return load_scenario(SCENARIO)


@pytest.fixture(scope="module")
def first(scenario):
    return ground_plan(scenario)


def test_the_family_is_registered_with_its_scenario() -> None:
    header = read_header(SCENARIO)
    assert registry.family(header) is FAMILY and FAMILY.name == header.mission == "proximity-approach"
    assert FAMILY.targets == ("host", "m7", "m4f") and not FAMILY.has_tables


def test_truth_coasts_as_clohessy_wiltshire_where_it_holds_and_converges() -> None:
    """Unforced, from 250 m drifting to 3.3 km: the two-body truth's Hill-frame state follows the CW closed
    form to its linearisation error (|rho| / a = 5e-4 of the distance and the speed), and the same flight at rtol
    1e-13 agrees with the truth's tolerance to a micrometre."""
    a = 6.9e6
    n = math.sqrt(MU / a ** 3)
    rel = (-200.0, 150.0, 0.05, 0.1)
    t1 = 3000.0
    truth = tr.Truth(MU, 0.8, 2100.0)
    s0 = truth.initial_state(a, rel, 180.0)
    _, ss = truth.propagate(0.0, s0, t1, lambda t: (0.0, 0.0), 0.0)
    got = tr.hill_state(ss[-1])
    cw = coast_stm(n, t1) @ np.array(rel)
    dist = float(np.hypot(*cw[:2]))
    assert np.abs(got[:2] - cw[:2]).max() < dist / a * dist                        # 0.62 m of 3.3 km
    assert np.abs(got[2:] - cw[2:]).max() < dist / a * float(np.hypot(*cw[2:]))    # 0.7 of 1,950 mm/s
    rtol, atol = tr.RTOL, tr.ATOL
    try:
        tr.RTOL, tr.ATOL = 1e-13, tr.ATOL * 1e-2
        _, tight = truth.propagate(0.0, s0, t1, lambda t: (0.0, 0.0), 0.0)
    finally:
        tr.RTOL, tr.ATOL = rtol, atol
    assert np.abs(tr.hill_state(tight[-1]) - got).max() < 1e-6


def test_thrust_is_applied_as_commanded() -> None:
    """alpha from the radial axis towards along-track in the target's Hill frame, T_max (1 + b) w / m,
    m' = -T_max (1 + b) w / v_e (the forced CW equations of ogk_host.proximity.dynamics over 60 s, near the
    target where they hold); below the minimum throttle the engine is off."""
    a = 6.9e6
    n = math.sqrt(MU / a ** 3)
    for alpha, bias in ((0.0, 0.0), (math.pi / 2, 0.05), (2.5, -0.03)):
        truth = tr.Truth(MU, 0.8, 2100.0, bias, 0.01)
        s0 = truth.initial_state(a, (0.0, 0.0, 0.0, 0.0), 180.0)
        _, ss = truth.propagate(0.0, s0, 60.0, lambda t, al=alpha: (al, 0.5), 0.0)
        cw, _ = rk4_interval(np.array([0.0, 0.0, 0.0, 0.0, 180.0]), (alpha, 0.5), (alpha, 0.5), 60.0, 600, n,
                             Vehicle(0.8 * (1.0 + bias), 2100.0, 180.0, 140.0))
        assert tr.hill_state(ss[-1]) == pytest.approx(cw[:4], abs=1e-7)     # 8 m, 0.13 m/s of motion
        assert ss[-1, 8] == pytest.approx(cw[4], abs=1e-10)
    truth = tr.Truth(MU, 0.8, 2100.0, 0.0, 0.01)
    s0 = truth.initial_state(a, (0.0, 0.0, 0.0, 0.0), 180.0)
    _, ss = truth.propagate(0.0, s0, 1.0, lambda t: (0.0, 0.009), 0.0)
    assert ss[-1, 8] == s0[8]


def test_the_hill_frame_round_trip() -> None:
    target = np.array([6.9e6 * math.cos(0.3), 6.9e6 * math.sin(0.3), -7600.0 * math.sin(0.3), 7600.0 * math.cos(0.3)])
    rel = (12.0, -340.0, 0.02, -0.3)
    rho, rhod = tr.from_hill(target, rel)
    assert tr.hill_state(np.concatenate([target, rho, rhod, [1.0]])) == pytest.approx(rel, abs=1e-12)


@pytest.mark.parametrize("solver", ["kernel", "ipopt"])
def test_a_nominal_flight_reaches_the_hold_point_outside_the_disc(scenario, first, solver) -> None:
    r = closed_loop.fly(scenario, solver, first, seed=1, perturbed=False)
    rec = r.record()
    assert r.completed, r.reason
    assert judge(scenario.acceptance, rec) == "", rec
    acc = scenario.acceptance
    assert np.abs(r.hold_error[:2]).max() < 0.2 * acc.hold_position_box_m
    assert np.abs(r.hold_error[2:]).max() < 0.2 * acc.hold_velocity_box_m_s
    # the truth, sampled every 2 s at least, never inside the disc; the plans' margin mostly kept
    assert r.keepout_clearance_m > 0.5 * scenario.guidance.keepout_margin_m
    assert r.fuel_kg < acc.propellant_kg and r.failed_solves == 0
    assert r.mass.min() > scenario.vehicle.dry_mass_kg


@pytest.mark.parametrize("run_seed", [6554349508805164480, 31415926535897])
def test_an_ulp_of_the_start_moves_neither_the_end_nor_the_propellant(scenario, first, run_seed) -> None:
    """The kernel's flight from the start and from its y moved by 1 and 2 ulp ([guidance]
    fixed_final_time, MU = mass_unit_kg): the flights end at the ground plan's t_f to a microsecond and
    burn the same propellant to 2 % (free t_f, MU = m_0: 159 s and 4.7 g of 37 g on the first seed)."""
    flights = []
    y = scenario.start[1]
    for _ in range(3):
        s = dataclasses.replace(scenario, start=(scenario.start[0], y, *scenario.start[2:]))
        flights.append(closed_loop.fly(s, "kernel", first, run_seed, True))
        y = math.nextafter(y, math.inf)
    assert all(f.completed for f in flights), [f.reason for f in flights]
    t_f = [f.t_f_s for f in flights]
    fuel = [f.fuel_kg for f in flights]
    assert max(t_f) - min(t_f) < 1e-6
    assert abs(t_f[0] - first.t_f * scenario.units.time_s) < 1e-4
    assert max(fuel) - min(fuel) < 0.02 * min(fuel)


def test_a_short_dispersed_campaign_loses_no_run() -> None:
    header = read_header(SCENARIO)
    plan = FAMILY.plan(header, {})
    flown = fly_campaign(plan, 8, seed=20261205, workers=2, progress=False)
    assert [r["failure"] for r in flown.records] == [""] * 8
    check = dc.check_plan(plan, flown.records)
    assert check is not None and check.ok, check.summary()
    text, extra = FAMILY.report(flown)
    assert text.splitlines()[0].endswith("lost 0 of 8 runs") and extra["lost_runs"] == 0
    assert "worst run" in text.splitlines()[1]


MISSION = """schema = "ogk.proximity-approach/1"
mission = "proximity-approach"
name = "prox_test_7400km"
source = "tests/python/test_proximity_family.py"
[orbit]
radius_m = 7.4e6
mu_m3_s2 = 3.986004418e14
[vehicle]
initial_mass_kg = 95.0
dry_mass_kg = 80.0
thrust_max_n = 0.35
exhaust_velocity_m_s = 2600.0
min_throttle = 0.01
[approach]
start_m = [-120.0, 1100.0]
start_velocity_m_s = [0.0, 0.18]
hold_point_m = [0.0, -180.0]
horizon_s = [1500.0, 9500.0]
[keepout]
centres_m = [-150.0, 420.0]
radii_m = [110.0]
[guidance]
law = "nmpc"
strategy = "cncn"
objective = "min-fuel"
fuel_time_weight_kg_per_s = 1e-5
nodes = 16
rk4_steps = 8
replan_period_s = 400.0
final_phase_s = 120.0
min_horizon_s = 60.0
keepout_margin_m = 12.0
max_sweep_rad = 1.0
[dispersions]
initial_position_sigma_m = 5.0
initial_velocity_sigma_m_s = 0.003
thrust_level_sigma = 0.02
thrust_angle_sigma_rad = 0.015
initial_mass_sigma_kg = 0.5
[acceptance]
hold_position_box_m = 5.0
hold_velocity_box_m_s = 0.01
propellant_kg = 0.5
"""


def test_a_mission_no_other_file_names(tmp_path: Path) -> None:
    """Another orbit (7,400 km), vehicle (95 kg, 0.35 N, 2,600 m/s), start below V-bar and drifting, hold
    point and disc (below V-bar, in the way): one TOML file, flown by `ogk run` and `ogk mc`."""
    path = tmp_path / "prox_test_7400km.toml"
    path.write_text(MISSION)
    scn = load_scenario(path)
    assert scn.units.time_s == pytest.approx(math.sqrt(7.4e6 ** 3 / MU))
    run = subprocess.run([str(OGK), "run", str(path), "--json", str(tmp_path / "one.json")],
                         capture_output=True, text=True, timeout=120, cwd=REPO)
    assert run.returncode == 0, run.stdout + run.stderr
    one = json.loads((tmp_path / "one.json").read_text())
    assert one["completed"] and one["failure"] == "" and one["keepout_clearance_m"] > 0.0
    mc = subprocess.run([str(OGK), "mc", str(path), "--runs", "6", "--seed", "77123", "--workers", "2",
                         "--json", str(tmp_path / "mc.json")], capture_output=True, text=True, timeout=180,
                        cwd=REPO)
    assert mc.returncode == 0, mc.stdout + mc.stderr
    assert "lost 0 of 6 runs" in mc.stdout
