"""Missions no other file names, made as a user would: edit a copy of scenarios/leo_geo.toml, run
`ogk tables`, `ogk mc` and `ogk run` on it end to end (subprocesses, few runs, 6-DOF truth, every
dispersion), then check

- the nominal against an independent re-solve: a direct method written here (planar Cartesian
  dynamics, thrust angle piecewise linear in time, SLSQP on f0, t_f and the nodes), which can only
  be as fast as the true optimum, so its t_f must agree with the ground tools' t_f* from above;
- the injection errors against the tolerances the scenario states (`ogk mc` exits 0, no failure);
- `ogk run --seed S` is run 0 of `ogk mc --seed S`, to the bit;
- provenance: the JSON names the scenario's SHA-256 and the tables flown; tables of another
  scenario and a corrupted table are refused with one line; a user's directory is never written.

The four missions differ in target radius, thrust level and exhaust velocity; one burns > 125 s.
long_burn_corner sits at the long-burn corner of the envelope the family states (R_f / r_p = 8,
n0 = 0.5 g0, c = 2.5 km/s: t_f* = 222 s) and leaves the burn-scaled end-game settings out, so it
flies the ones derived from its t_f* (ogk_host.orbit_injection.derive.burn_scaled). The short-burn
corner (1.5, 1.5 g0, 4.5 km/s: t_f* = 41.8 s) with the paper's dispersions is outside the linear
domain the family states: `ogk tables` names each dispersion key in one warning line, with what was
measured there; inside that domain the corner flies (test_orbit_injection_robustness.py).
"""
from __future__ import annotations

import dataclasses
import hashlib
import json
import math
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from scipy.optimize import minimize

OGK = Path(sys.executable).parent / "ogk"
PAPER_SCENARIO = Path(__file__).resolve().parents[2] / "scenarios" / "leo_geo.toml"
MU = 3.986004e14
R_LEO = 6778.137e3
G0 = 9.80665


@dataclasses.dataclass(frozen=True)
class Mission:
    name: str
    target_radius_m: float
    accel_g0: float          #: initial thrust acceleration / g0
    exhaust_velocity_m_s: float
    derived_end_game: bool = False   #: dtf_max_s and the end-game windows left out (derived)

    @property
    def hohmann(self) -> tuple[float, float]:
        """(a, e) of the transfer ellipse from the 400 km LEO to the target radius."""
        a = 0.5 * (R_LEO + self.target_radius_m)
        return a, (self.target_radius_m - R_LEO) / (self.target_radius_m + R_LEO)


MISSIONS = [
    Mission("meo_20000km_low_thrust", 20000.0e3, 0.8, 3200.0),
    Mission("high_30000km_hot", 30000.0e3, 1.4, 4200.0),
    Mission("geo_long_burn", 42164.0e3, 0.6, 2700.0),   # ~190 s burn
    Mission("long_burn_corner", 8.0 * R_LEO, 0.5, 2500.0, derived_end_game=True),
]
BURN_SCALED = ("dtf_max_s", "fine_window_s", "terminal_window_s")


def ogk(*args: str, timeout: float = 600.0) -> subprocess.CompletedProcess[str]:
    return subprocess.run([str(OGK), *args], capture_output=True, text=True, timeout=timeout)


def write_scenario(mission: Mission, directory: Path) -> Path:
    """The paper's file with the mission's values, its paper results and precomputed CPD gains
    removed (the ground tools derive the gains from the new thrust and inertia)."""
    text = PAPER_SCENARIO.read_text()
    a, e = mission.hohmann
    edits = [(r'^name = "leo_geo"', f'name = "{mission.name}"'),
             (r"^semi_major_axis_m = .*$", f"semi_major_axis_m = {a!r}"),
             (r"^eccentricity = .*$", f"eccentricity = {e!r}"),
             (r"^radius_m = 42164.0e3", f"radius_m = {mission.target_radius_m!r}"),
             (r"^initial_accel_g0 = .*$", f"initial_accel_g0 = {mission.accel_g0!r}"),
             (r"^exhaust_velocity_m_s = .*$", f"exhaust_velocity_m_s = {mission.exhaust_velocity_m_s!r}"),
             (r"^\[paper_results\][\s\S]*\Z", ""),
             (r"^\[cpd\.printed\][\s\S]*?(?=^\[cpd\.rederived)", ""),
             (r"^\[cpd\.rederived\][\s\S]*?(?=^\[dispersions)", ""),
             (r"^freeze_time_to_go_s = .*$", "")]
    if mission.derived_end_game:
        edits += [(rf"^{key} = .*$", "") for key in BURN_SCALED]
    for old, new in edits:
        text, n = re.subn(old, new, text, count=1, flags=re.M)
        assert n == 1, old
    path = directory / f"{mission.name}.toml"
    path.write_text(text)
    return path


# ------------------------------------------------------------------ independent direct re-solve
def _fly(z: np.ndarray, mission: Mission, nodes: int, steps: int = 800) -> np.ndarray:
    """Terminal [r - R_f, v_r, v_t - v_c] (scaled) of the decision vector [f0, t_f, alpha_1..n]:
    planar Cartesian two-body motion with the thrust at angle alpha(t) from the local horizontal,
    classical RK4 with `steps` fixed steps (scalar arithmetic: fast enough for finite differences)."""
    f0, tf = float(z[0]), float(z[1])
    alphas = [float(v) for v in z[2:]]
    a, e = mission.hohmann
    p = a * (1.0 - e * e)
    r0 = p / (1.0 + e * math.cos(f0))
    state = (r0, 0.0, math.sqrt(MU / p) * e * math.sin(f0),
             math.sqrt(MU / p) * (1.0 + e * math.cos(f0)))
    n0, c = mission.accel_g0 * G0, mission.exhaust_velocity_m_s
    seg = tf / (nodes - 1)

    def rhs(t: float, x: float, y: float, vx: float, vy: float) -> tuple[float, float, float, float]:
        r2 = x * x + y * y
        r = math.sqrt(r2)
        k = min(int(t / seg), nodes - 2)
        w = t / seg - k
        al = (1.0 - w) * alphas[k] + w * alphas[k + 1]
        a_t = n0 * c / (c - n0 * t)
        ca, sa = math.cos(al), math.sin(al)
        g = -MU / (r2 * r)
        # local horizontal (-y, x)/r and radial (x, y)/r
        return (vx, vy, g * x + a_t * (-ca * y + sa * x) / r, g * y + a_t * (ca * x + sa * y) / r)

    h = tf / steps
    x, y, vx, vy = state
    t = 0.0
    for _ in range(steps):
        k1 = rhs(t, x, y, vx, vy)
        k2 = rhs(t + 0.5 * h, x + 0.5 * h * k1[0], y + 0.5 * h * k1[1], vx + 0.5 * h * k1[2],
                 vy + 0.5 * h * k1[3])
        k3 = rhs(t + 0.5 * h, x + 0.5 * h * k2[0], y + 0.5 * h * k2[1], vx + 0.5 * h * k2[2],
                 vy + 0.5 * h * k2[3])
        k4 = rhs(t + h, x + h * k3[0], y + h * k3[1], vx + h * k3[2], vy + h * k3[3])
        x += h / 6.0 * (k1[0] + 2.0 * k2[0] + 2.0 * k3[0] + k4[0])
        y += h / 6.0 * (k1[1] + 2.0 * k2[1] + 2.0 * k3[1] + k4[1])
        vx += h / 6.0 * (k1[2] + 2.0 * k2[2] + 2.0 * k3[2] + k4[2])
        vy += h / 6.0 * (k1[3] + 2.0 * k2[3] + 2.0 * k3[3] + k4[3])
        t += h
    r = math.hypot(x, y)
    vr, vt = (x * vx + y * vy) / r, (x * vy - y * vx) / r
    vc = math.sqrt(MU / mission.target_radius_m)
    return np.array([(r - mission.target_radius_m) / mission.target_radius_m, vr / vc, vt / vc - 1.0])


def direct_min_time(mission: Mission, f0_guess: float, tf_guess: float, nodes: int = 12
                    ) -> tuple[float, float]:
    """Minimum-time (f0, t_f) by direct shooting. The guess is the ground tools' answer moved off it
    (f0 by 3 deg, t_f by +3 %, the steering flat): the direct method must find its own way back."""
    z0 = np.concatenate([[f0_guess + math.radians(3.0), 1.03 * tf_guess], np.zeros(nodes)])
    scale = np.concatenate([[1.0, tf_guess], np.ones(nodes)])
    res = minimize(lambda w: w[1], z0 / scale, method="SLSQP",
                   constraints=[{"type": "eq", "fun": lambda w: _fly(w * scale, mission, nodes)}],
                   bounds=[(None, None), (0.5, 2.0)] + [(-1.2, 1.2)] * nodes,
                   options={"maxiter": 300, "ftol": 1e-13})
    z = res.x * scale
    assert res.success, res.message
    assert np.max(np.abs(_fly(z, mission, nodes))) < 1e-8
    return float(z[0]), float(z[1])


# ------------------------------------------------------------------ the end-to-end campaign
@pytest.fixture(scope="module")
def flown(tmp_path_factory: pytest.TempPathFactory) -> dict[str, dict]:
    """Each mission: tables + a 3-run 6-DOF campaign with every dispersion, through the CLI."""
    out: dict[str, dict] = {}
    for mission in MISSIONS:
        work = tmp_path_factory.mktemp(mission.name)
        scenario = write_scenario(mission, work)
        tables = work / "tables"
        made = ogk("tables", str(scenario), "--out", str(tables))
        assert made.returncode == 0, made.stdout + made.stderr
        camp = ogk("mc", str(scenario), "--runs", "3", "--seed", "20261201", "--workers", "1",
                   "--tables", str(tables), "--json", str(work / "mc.json"))
        one = ogk("run", str(scenario), "--seed", "20261201", "--tables", str(tables),
                  "--json", str(work / "run.json"))
        out[mission.name] = {"mission": mission, "scenario": scenario, "tables": tables,
                             "manifest": json.loads((tables / "manifest.json").read_text()),
                             "mc": camp, "doc": json.loads((work / "mc.json").read_text())
                             if (work / "mc.json").exists() else None, "run": one,
                             "one": json.loads((work / "run.json").read_text())
                             if (work / "run.json").exists() else None}
    return out


@pytest.mark.req("OGK-HAR-007", "OGK-NOG-018")
@pytest.mark.parametrize("mission", MISSIONS, ids=lambda m: m.name)
def test_campaign_meets_the_stated_tolerances(flown: dict, mission: Mission) -> None:
    run = flown[mission.name]
    assert run["mc"].returncode == 0, run["mc"].stdout[-3000:] + run["mc"].stderr
    doc = run["doc"]
    assert doc["failures"] == 0 and doc["runs"] == 3
    assert mission.name in run["mc"].stdout and "paper" not in run["mc"].stdout
    for key, tol in doc["tolerances"].items():
        assert max(abs(r[key]) for r in doc["per_run"]) <= tol
    # provenance: this scenario, these tables
    assert doc["scenario_sha256"] == hashlib.sha256(run["scenario"].read_bytes()).hexdigest()
    for name, sha in doc["tables"]["sha256"].items():
        assert hashlib.sha256((run["tables"] / name).read_bytes()).hexdigest() == sha
    assert doc["nominal_tf_s"] == pytest.approx(run["manifest"]["t_f_s"], rel=1e-9)


@pytest.mark.req("OGK-HAR-001")
@pytest.mark.parametrize("mission", MISSIONS, ids=lambda m: m.name)
def test_ogk_run_flies_run_0_of_the_campaign(flown: dict, mission: Mission) -> None:
    """`ogk run --seed S` is one flight: run 0 of `ogk mc --seed S`, to the bit, within the tolerances."""
    run = flown[mission.name]
    assert run["run"].returncode == 0, run["run"].stdout[-3000:] + run["run"].stderr
    one, camp = run["one"], run["doc"]
    assert one["runs"] == 1 and one["failures"] == 0
    first = next(r for r in camp["per_run"] if r["run_id"] == 0)
    assert one["per_run"][0] == first
    for key, tol in one["tolerances"].items():
        assert abs(one["per_run"][0][key]) <= tol


@pytest.mark.req("OGK-HAR-007")
def test_one_mission_burns_longer_than_125_s(flown: dict) -> None:
    assert max(r["manifest"]["t_f_s"] for r in flown.values()) > 125.0


@pytest.mark.req("OGK-HAR-007", "OGK-NOG-013")
@pytest.mark.parametrize("mission", MISSIONS, ids=lambda m: m.name)
def test_nominal_agrees_with_an_independent_direct_re_solve(flown: dict, mission: Mission) -> None:
    manifest = flown[mission.name]["manifest"]
    tf_star = float(manifest["t_f_s"])
    f0_star = math.radians(float(manifest["ignition_true_anomaly_deg"]))
    f0, tf = direct_min_time(mission, f0_star, tf_star)
    # A piecewise-linear steering cannot beat the optimum (up to the 800-step RK4 error); 12 nodes
    # come within 4e-12 of t_f* and 4e-5 deg of f0* on these missions (measured when written).
    assert tf >= tf_star * (1.0 - 1e-8)
    assert tf <= tf_star * (1.0 + 1e-6)
    assert abs(math.degrees(f0 - f0_star)) < 0.01


@pytest.mark.req("OGK-HAR-008")
def test_tables_of_another_scenario_are_refused(flown: dict, tmp_path: Path) -> None:
    a, b = (flown[m.name] for m in MISSIONS[:2])
    out = ogk("mc", str(a["scenario"]), "--runs", "1", "--seed", "1", "--tables", str(b["tables"]),
              "--json", str(tmp_path / "x.json"), timeout=120)
    assert out.returncode == 2, out.stdout + out.stderr
    assert len(out.stderr.strip().splitlines()) == 1 and "Traceback" not in out.stderr
    assert not (tmp_path / "x.json").exists()


@pytest.mark.req("OGK-HAR-008")
def test_corrupted_table_is_refused(flown: dict, tmp_path: Path) -> None:
    src = flown[MISSIONS[0].name]
    copy = tmp_path / "tables"
    copy.mkdir()
    for f in src["tables"].iterdir():
        if f.is_file():
            (copy / f.name).write_bytes(f.read_bytes())
    bundle = next(copy.glob("nog_bundle.ogkt"))
    data = bytearray(bundle.read_bytes())
    data[len(data) // 2] ^= 0x01
    bundle.write_bytes(bytes(data))
    out = ogk("mc", str(src["scenario"]), "--runs", "1", "--seed", "1", "--tables", str(copy),
              "--json", str(tmp_path / "x.json"), timeout=120)
    assert out.returncode == 2, out.stdout + out.stderr
    assert len(out.stderr.strip().splitlines()) == 1 and "Traceback" not in out.stderr


@pytest.mark.req("OGK-HAR-008")
def test_a_users_directory_is_never_written(flown: dict, tmp_path: Path) -> None:
    mine = tmp_path / "my_tables"
    mine.mkdir()
    (mine / "notes.txt").write_text("mine")
    scenario = flown[MISSIONS[0].name]["scenario"]
    out = ogk("tables", str(scenario), "--out", str(mine), timeout=120)
    assert out.returncode == 2, out.stdout + out.stderr
    assert sorted(p.name for p in mine.iterdir()) == ["notes.txt"]
    out = ogk("mc", str(scenario), "--runs", "1", "--seed", "1", "--tables", str(mine),
              "--json", str(tmp_path / "x.json"), timeout=120)
    assert out.returncode == 2 and sorted(p.name for p in mine.iterdir()) == ["notes.txt"]


@pytest.mark.req("OGK-HAR-007", "OGK-NOG-009")
def test_burn_scaled_settings_are_derived_and_flown(flown: dict) -> None:
    """The edge mission leaves dtf_max_s and the windows out: the manifest records them as derived,
    within the kernel's bound (|dt_f| clip <= t_f*/2) and growing with the burn (longer than the
    paper's 40 / 20 / 10 s for this 222 s burn); its campaign met the tolerances above."""
    run = flown["long_burn_corner"]
    tf = float(run["manifest"]["t_f_s"])
    assert tf > 200.0
    settings = run["manifest"]["settings"]
    for key, paper in zip(BURN_SCALED, (40.0, 20.0, 10.0)):
        assert settings[key]["source"] == "derived"
        assert paper < settings[key]["value"] < 0.5 * tf
    assert "warning" not in run["mc"].stderr


@pytest.mark.req("OGK-HAR-005")
def test_short_burn_corner_names_each_key_outside_the_linear_domain(tmp_path: Path) -> None:
    """At the short-burn corner the paper's dispersions (5 km, 30 m/s) are large against the burn
    (n0 t_f*^2 = 25.7 km, Delta v = 661 m/s): one warning line per key, and the derived |dt_f| clip
    fits the kernel's t_f*/2 bound where the copied 40 s did not (exit 0, tables written)."""
    corner = Mission("short_burn_corner", 1.5 * R_LEO, 1.5, 4500.0, derived_end_game=True)
    scenario = write_scenario(corner, tmp_path)
    out = ogk("tables", str(scenario), "--out", str(tmp_path / "tables"), timeout=300)
    assert out.returncode == 0, out.stdout + out.stderr
    lines = out.stderr.strip().splitlines()
    keys = [re.match(rf"^{re.escape(str(scenario))}: (\S+): warning: ", ln) for ln in lines]
    assert all(keys), lines
    assert [k.group(1) for k in keys if k] == [
        "dispersions.initial_state.radius_m", "dispersions.initial_state.radial_velocity_m_s",
        "dispersions.initial_state.transverse_velocity_m_s",
        "dispersions.initial_state.normal_velocity_m_s"]
    # each line states what was measured beyond the domain (derive.*_BEYOND_MEASURED): the paper's
    # dispersions at this corner fail a fifth of the runs
    assert "20 % at 0.58" in lines[0] and "0.1-0.2 % fail at 0.136" in lines[1]
    manifest = json.loads((tmp_path / "tables" / "manifest.json").read_text())
    tf = float(manifest["t_f_s"])
    assert 41.0 < tf < 42.5
    assert manifest["settings"]["dtf_max_s"]["source"] == "derived"
    assert manifest["settings"]["dtf_max_s"]["value"] <= 0.5 * tf
    # the terminal stage's turn limit, derived from the vehicle: its shaped plans tilt a few degrees
    turn = manifest["settings"]["terminal_turn_accel_rad_s2"]
    assert turn["source"] == "derived" and 0.15 < turn["value"] < 0.25
    tilt = re.search(r"shaped plans tilt at most (\S+) deg from v_go", out.stdout)
    assert tilt and float(tilt.group(1)) < 5.0, out.stdout

    # the paper's windows copied (20 s and 10 s on a 41.8 s burn): a warning each, naming the key
    copied = Mission("short_burn_copied_windows", 1.5 * R_LEO, 1.5, 4500.0)
    path = write_scenario(copied, tmp_path)
    path.write_text(path.read_text().replace("dtf_max_s = 40.0", "dtf_max_s = 15.0"))
    out = ogk("tables", str(path), "--out", str(tmp_path / "copied"), timeout=300)
    assert out.returncode == 0, out.stdout + out.stderr
    named = [ln.split(": ")[1] for ln in out.stderr.strip().splitlines()]
    assert named[:2] == ["guidance.end_game.fine_window_s", "guidance.end_game.terminal_window_s"]
    assert "fail 8.6 % of 1000 runs" in out.stderr
    assert len(named) == 6
