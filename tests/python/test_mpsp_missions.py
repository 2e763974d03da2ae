"""A new MPSP mission is one TOML file; its nominal is its own ground product (issue 19).

From a copy of scenarios/apophis_cubesat.toml in tmp_path:
  - the edge of the Apophis transfer's envelope: T_max 1.35 mN, 10 % below the paper's (at 1.3 mN no
    nominal exists): its nominal by continuation from the cached one (~20 s); `ogk tables` makes it
    into its own directory build/tables/<name>-<sha12> with a manifest; `ogk run` of a case and
    `ogk mc --runs 3` fly it with MPSP converging; the nominal meets its boundary conditions when
    re-integrated here, independently of the ground tool (scipy solve_ivp, rtol 1e-12, the switching
    function's zeros as events); Apophis's products unchanged, both coexist, no tracked file changed;
  - a Bennu-like target (boundary state from published-style elements propagated here by a two-body
    solve_ivp; 2.5 mN, 1200 d), its nominal solved from scratch (~50 s), the same checks;
  - bad input: one line FILE: KEY: REASON, exit 2, in seconds (strings, nan/inf, zero or negative
    masses, thrusts, durations, --param nan, a duration too short to reach the target), a result
    beyond [acceptance] is exit 1 with the reason; another scenario's products are refused.
"""
from __future__ import annotations

import hashlib
import json
import math
import re
import shutil
import subprocess
import time
import tomllib
from pathlib import Path

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from ogk.cli import main

REPO = Path(__file__).resolve().parents[2]
APOPHIS = REPO / "scenarios" / "apophis_cubesat.toml"
DATA = REPO / "host" / "ogk_host" / "low_thrust_transfer" / "data"
TABLES = REPO / "build" / "tables"


def _sha(path: Path) -> str:
    return hashlib.sha256(path.read_bytes()).hexdigest()


def _porcelain() -> str:
    """Tracked files of the family and the scenarios changed in the work tree (other paths may be
    edited by someone else while the test runs)."""
    return subprocess.run(["git", "status", "--porcelain", "--untracked-files=no", "--",
                           "host/ogk_host/low_thrust_transfer", "harness/ogk/missions/low_thrust_transfer",
                           "scenarios"], cwd=REPO, capture_output=True, text=True, check=True).stdout


def _edit(dst: Path, src: Path = APOPHIS, drop_paper: bool = True, **values: str) -> Path:
    """A copy of `src` with `key = value` lines replaced (each key must occur once)."""
    text = src.read_text()
    for key, value in values.items():
        text, n = re.subn(rf"^{key} = .*$", f"{key} = {value}", text, flags=re.M)
        assert n == 1, key
    if drop_paper:   # the new mission has no paper to compare with
        text = text.split("# ---------------------------------------------------------------- published")[0]
    dst.write_text(text)
    return dst


def _product_dir(scenario: Path) -> Path:
    name = tomllib.loads(scenario.read_text())["name"]
    return TABLES / f"{name}-{_sha(scenario)[:12]}"


# ------------------------------------------------------------------ independent re-integration
def _reintegrate(scenario: Path, lam0: list[float]) -> tuple[float, float, float]:
    """|r(t_f) - r_f| [km], |v(t_f) - v_f| [km/s], |lambda_m(t_f)| of the fuel-optimal nominal
    lambda_0, integrated here from the scenario's raw numbers: two-body dynamics with thrust
    T_max u along -lambda_v, u = 1 where S = 1 - c |lambda_v| / m - lambda_m < 0 (the switches as
    events of solve_ivp), DOP853 at rtol 1e-12."""
    d = tomllib.loads(scenario.read_text())
    un, sc, bd = d["units"], d["spacecraft"], d["boundary"]
    lu, tu, mu_kg = un["length_unit_km"], un["time_unit_s"], un["mass_unit_kg"]
    vu = lu / tu
    mu = un["mu_sun_km3_s2"] * tu**2 / lu**3
    tmax = sc["max_thrust_N"] / (mu_kg * lu * 1e3 / tu**2)
    c = sc["specific_impulse_s"] * un["g0_m_s2"] * 1e-3 / vu
    tf = d["transfer"]["duration_days"] * 86400.0 / tu

    def switching(z: np.ndarray) -> float:
        return 1.0 - c * np.linalg.norm(z[10:13]) / z[6] - z[13]

    def rhs(t: float, z: np.ndarray, u: float) -> np.ndarray:
        r, m, lr, lv = z[0:3], z[6], z[7:10], z[10:13]
        rn = np.linalg.norm(r)
        lvn = np.linalg.norm(lv)
        out = np.empty(14)
        out[0:3] = z[3:6]
        out[3:6] = -mu * r / rn**3 - u * tmax / m * lv / lvn
        out[6] = -u * tmax / c
        out[7:10] = mu * (lv / rn**3 - 3.0 * r * (r @ lv) / rn**5)     # -dH/dr
        out[10:13] = -lr
        out[13] = -u * tmax * lvn / m**2
        return out

    z = np.concatenate([bd["initial_position_LU"], bd["initial_velocity_VU"],
                        [sc["initial_mass_kg"] / mu_kg], lam0])
    t = 0.0
    u = 1.0 if switching(z) < 0.0 else 0.0
    for _ in range(200):
        event = lambda t, y, u=u: switching(y)   # noqa: E731
        event.terminal = True
        sol = solve_ivp(rhs, (t, tf), z, args=(u,), method="DOP853", rtol=1e-12, atol=1e-13,
                        events=event)
        t, z = float(sol.t[-1]), sol.y[:, -1]
        if sol.status == 0:
            break
        u = 1.0 - u
        # step just past the switch so the event does not fire again at its own zero
        nudge = solve_ivp(rhs, (t, min(tf, t + 1e-9)), z, args=(u,), method="DOP853", rtol=1e-12,
                          atol=1e-14)
        t, z = float(nudge.t[-1]), nudge.y[:, -1]
    return (float(np.linalg.norm(z[0:3] - bd["final_position_LU"]) * lu),
            float(np.linalg.norm(z[3:6] - bd["final_velocity_VU"]) * vu), abs(float(z[13])))


# ------------------------------------------------------------------ a Bennu-like target
def bennu_like_target(days_before_arrival: float = 100.0,
                      true_anomaly_at_arrival_deg: float = 119.0) -> tuple[list[float], list[float]]:
    """Heliocentric ecliptic r, v [LU, LU/TU] at arrival of a body with Bennu-like elements
    (a = 1.1260 AU, e = 0.20375, i = 6.0349 deg, Omega = 2.0609 deg, omega = 66.2231 deg): the state
    from the elements `days_before_arrival` earlier (Kepler's equation), propagated to arrival by
    two-body solve_ivp. The phase puts the arrival near the longitude of Apophis's."""
    lu, tu, mu_sun = 1.495979e8, 5.022643e6, 1.327124e11
    mu = mu_sun * tu**2 / lu**3
    a, e = 1.1260, 0.20375
    inc, raan, argp = (math.radians(x) for x in (6.0349, 2.0609, 66.2231))
    nu_f = math.radians(true_anomaly_at_arrival_deg)
    ecc_f = 2.0 * math.atan(math.sqrt((1.0 - e) / (1.0 + e)) * math.tan(nu_f / 2.0))
    dt = days_before_arrival * 86400.0 / tu
    mean0 = ecc_f - e * math.sin(ecc_f) - math.sqrt(mu / a**3) * dt
    ecc = mean0
    for _ in range(50):
        ecc -= (ecc - e * math.sin(ecc) - mean0) / (1.0 - e * math.cos(ecc))
    nu = 2.0 * math.atan2(math.sqrt(1.0 + e) * math.sin(ecc / 2.0),
                          math.sqrt(1.0 - e) * math.cos(ecc / 2.0))
    p = a * (1.0 - e * e)
    r = p / (1.0 + e * math.cos(nu))
    r_pf = np.array([r * math.cos(nu), r * math.sin(nu), 0.0])
    v_pf = math.sqrt(mu / p) * np.array([-math.sin(nu), e + math.cos(nu), 0.0])

    def rz(x: float) -> np.ndarray:
        return np.array([[math.cos(x), -math.sin(x), 0.0], [math.sin(x), math.cos(x), 0.0],
                         [0.0, 0.0, 1.0]])

    rx = np.array([[1.0, 0.0, 0.0], [0.0, math.cos(inc), -math.sin(inc)],
                   [0.0, math.sin(inc), math.cos(inc)]])
    q = rz(raan) @ rx @ rz(argp)
    y0 = np.concatenate([q @ r_pf, q @ v_pf])
    sol = solve_ivp(lambda t, y: np.concatenate([y[3:], -mu * y[:3] / np.linalg.norm(y[:3])**3]),
                    (0.0, dt), y0, method="DOP853", rtol=1e-13, atol=1e-14)
    return [float(x) for x in sol.y[:3, -1]], [float(x) for x in sol.y[3:, -1]]


def _vec(v: list[float]) -> str:
    return "[" + ", ".join(repr(x) for x in v) + "]"


# ------------------------------------------------------------------ the flow, on any new mission
def _fly_new_mission(scenario: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str],
                     solved_from: str) -> None:
    before = _porcelain()
    shipped = {p.name: _sha(p) for p in DATA.glob("*.json")}
    out = _product_dir(scenario)
    shutil.rmtree(out, ignore_errors=True)
    try:
        start = time.perf_counter()
        assert main(["tables", str(scenario)]) == 0
        print(f"ogk tables {scenario.name}: {time.perf_counter() - start:.1f} s")
        manifest = json.loads((out / "manifest.json").read_text())
        nominal = out / "nominal_solution.json"
        assert manifest["scenario"]["sha256"] == _sha(scenario)
        assert manifest["scenario"]["path"] == str(scenario)
        assert manifest["nominal"]["sha256"] == _sha(nominal)
        doc = json.loads(nominal.read_text())
        assert solved_from in doc["method"]
        header = (out / "c" / "ogk_mpsp_flight_config.h").read_text()
        assert _sha(scenario) in header and manifest["nominal"]["sha256"] in header
        # a true optimum: the boundary conditions met by an independent re-integration
        dr, dv, lam_mf = _reintegrate(scenario, doc["lambda0"])
        assert dr < 5.0 and dv < 1e-6 and lam_mf < 1e-6, (dr, dv, lam_mf)
        # not Apophis's
        apophis = json.loads((DATA / "nominal_solution.json").read_text())
        assert not np.allclose(doc["lambda0"], apophis["lambda0"], rtol=0.0, atol=1e-6)

        acc = tomllib.loads(scenario.read_text()).get("acceptance", {})
        pos_tol = acc.get("position_error_km", 500.0)
        capsys.readouterr()
        one = tmp_path / "one.json"
        assert main(["run", str(scenario), "--case", "thrust", "--param=3", "--no-reference",
                     "--json", str(one)]) == 0, capsys.readouterr().err
        rec = json.loads(one.read_text())
        assert rec["converged"] and rec["newton_iterations"] > 0 and rec["dr_f_km"] <= pos_tol

        env = tmp_path / "mc.json"
        assert main(["mc", str(scenario), "--runs", "3", "--seed", "7", "--workers", "1",
                     "--json", str(env)]) == 0, capsys.readouterr().err
        envelope = json.loads(env.read_text())
        assert envelope["products"]["nominal_sha256"] == manifest["nominal"]["sha256"]
        assert not envelope.get("failures")
        rows = [json.loads(line) for line in Path(str(env) + ".runs.jsonl").read_text().splitlines()
                if line.strip()]
        rows = [r for r in rows if "run_id" in r]
        assert len(rows) == 3
        for row in rows:
            assert row["converged"] and not row["failure"], row
            assert row["newton_iterations"] > 0 and row["dr_f_km"] <= pos_tol, row

        # Apophis's products: unchanged and beside the new one
        capsys.readouterr()
        apo_out = tmp_path / "apophis"
        assert main(["tables", "apophis", "--out", str(apo_out)]) == 0
        apo = json.loads((apo_out / "nominal_solution.json").read_text())
        assert apo["lambda0"] == apophis["lambda0"]
        assert (out / "nominal_solution.json").exists()
        assert {p.name: _sha(p) for p in DATA.glob("*.json")} == shipped
        assert _porcelain() == before
    finally:
        shutil.rmtree(out, ignore_errors=True)


@pytest.mark.req("OGK-HAR-007")
def test_new_mission_at_the_thrust_edge(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """The Apophis target at 1.35 mN, 10 % below the paper's thrust: the edge of this transfer's
    envelope (at 1.3 mN no fuel-optimal nominal exists: the thrust continuation stalls, and 1.2 mN
    fails the reach check). A new mission, its nominal by continuation from the cache."""
    scenario = _edit(tmp_path / "apophis_edge.toml", name='"mpsp_test_apophis_1_35mN"',
                     max_thrust_N="1.35e-3", printed_vector_scale="0.01", cube_side_LU="0.004")
    # The dispersions scaled to the 4 % thrust margin: the paper's (kappa up to 3.5 x its vectors,
    # a 0.04 LU cube, eta -10 %) need more thrust than this vehicle has above the edge (measured:
    # 1 of 3 dispersed runs converge with them, 9 of 9 with these).
    text = scenario.read_text()
    block = text[text.index("delta_final_position_LU = ["):]
    block = block[:block.index("\n]\n") + 2]
    text = text.replace(block, block.replace("0.02", "0.002"))
    scenario.write_text(re.sub(r"^eta_percent = .*$", "eta_percent = [-1.0, -0.5, 0.5, 1.0]", text,
                               count=1, flags=re.M))
    _fly_new_mission(scenario, tmp_path, capsys, "from the cached nominal")


@pytest.mark.req("OGK-HAR-007")
def test_new_mission_bennu_like(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """A Bennu-like target, 2.5 mN, 1200 days: its nominal solved from scratch (about 2 min)."""
    rf, vf = bennu_like_target()
    scenario = _edit(tmp_path / "bennu_like.toml", name='"mpsp_test_bennu_like"',
                     max_thrust_N="2.5e-3", duration_days="1200.0",
                     final_position_LU=_vec(rf), final_velocity_VU=_vec(vf))
    _fly_new_mission(scenario, tmp_path, capsys, "homotopy")


@pytest.mark.req("OGK-HAR-008")
def test_comment_change_keeps_the_cache(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """The shipped nominal is a cache keyed by the physics: a comment or a [mpsp] change reuses it,
    a changed duration does not (checked without solving: the cache key differs)."""
    from ogk_host.low_thrust_transfer.products import physics_sha256
    shipped = json.loads((DATA / "nominal_solution.json").read_text())
    assert shipped["physics_sha256"] == physics_sha256(APOPHIS)
    assert json.loads((DATA / "perturbed_optima.json").read_text())["physics_sha256"] == shipped[
        "physics_sha256"]
    commented = tmp_path / "commented.toml"
    commented.write_text("# a comment\n" + APOPHIS.read_text().replace("delta_max = 1.0", "delta_max = 0.9"))
    assert physics_sha256(commented) == shipped["physics_sha256"]
    out = tmp_path / "out"
    assert main(["tables", str(commented), "--out", str(out)]) == 0
    doc = json.loads((out / "nominal_solution.json").read_text())
    assert doc["lambda0"] == shipped["lambda0"] and "cache" in doc
    longer = _edit(tmp_path / "longer.toml", duration_days="1157.0")
    assert physics_sha256(longer) != shipped["physics_sha256"]


@pytest.mark.req("OGK-HAR-008")
def test_products_of_another_scenario_refused(tmp_path: Path,
                                              capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "apophis"
    assert main(["tables", "apophis", "--out", str(out)]) == 0
    other = _edit(tmp_path / "other.toml", name='"other"', duration_days="1150.0")
    capsys.readouterr()
    assert main(["tables", str(other), "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "made from scenario 'apophis_cubesat'" in err, err
    # a nominal tampered with in the scenario's own directory
    (out / "nominal_solution.json").write_text((out / "nominal_solution.json").read_text() + " ")
    assert main(["tables", "apophis", "--out", str(out)]) == 2
    assert "corrupted" in capsys.readouterr().err


BAD = [
    ("max_thrust_N", '"1.5e-3"', "spacecraft.max_thrust_N: must be a number"),
    ("initial_mass_kg", "-25.0", "spacecraft.initial_mass_kg: must be > 0"),
    ("initial_mass_kg", "0.0", "spacecraft.initial_mass_kg: must be > 0"),
    ("max_thrust_N", "0.0", "spacecraft.max_thrust_N: must be > 0"),
    ("max_thrust_N", "nan", "spacecraft.max_thrust_N: must be finite"),
    ("specific_impulse_s", "inf", "spacecraft.specific_impulse_s: must be finite"),
    ("duration_days", "-1156.0", "transfer.duration_days: must be > 0"),
    ("duration_days", "0", "transfer.duration_days: must be > 0"),
    ("duration_days", "30", "transfer.duration_days: 30 days at 0.0015 N cannot reach the target"),
    ("final_position_LU", "[1.0, nan, 0.0]", "boundary.final_position_LU: must be 3 finite"),
    ("fourier_order", "0", "mpsp.fourier_order: must be >= 1"),
    ("tol_position_km", '"500"', "mpsp.tol_position_km: must be a number"),
]


@pytest.mark.req("OGK-HAR-005")
@pytest.mark.parametrize("verb", ["run", "tables", "mc"])
@pytest.mark.parametrize("key,value,reason", BAD, ids=[f"{k}={v}" for k, v, _ in BAD])
def test_bad_scenario_values(tmp_path: Path, capsys: pytest.CaptureFixture[str], verb: str,
                             key: str, value: str, reason: str) -> None:
    scenario = _edit(tmp_path / "bad.toml", **{key: value})
    argv = {"run": ["run", str(scenario), "--case", "thrust", "--param=3", "--no-reference"],
            "tables": ["tables", str(scenario), "--out", str(tmp_path / "out")],
            "mc": ["mc", str(scenario), "--runs", "3", "--json", str(tmp_path / "mc.json")]}[verb]
    start = time.perf_counter()
    assert main(argv) == 2
    assert time.perf_counter() - start < 15.0
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1, err
    assert err.startswith(f"ogk {verb}: {scenario}: {reason}"), err
    assert not (tmp_path / "out").exists()


@pytest.mark.req("OGK-HAR-005")
@pytest.mark.parametrize("case,param,reason", [
    ("thrust", "nan", "--param: eta [%] must be finite"),
    ("thrust", "-100", "--param: eta must be > -100"),
    ("thrust", "abc", "--param: eta [%] must be a number"),
    ("initial", "inf", "--param: kappa must be finite"),
    ("terminal", "0.01,nan,0", "--param: each of dx,dy,dz must be finite"),
    ("terminal", "0.01,0", "--param: for --case terminal is 'dx,dy,dz'"),
])
def test_bad_param(capsys: pytest.CaptureFixture[str], case: str, param: str, reason: str) -> None:
    start = time.perf_counter()
    assert main(["run", "apophis", "--case", case, f"--param={param}", "--no-reference"]) == 2
    assert time.perf_counter() - start < 15.0
    err = capsys.readouterr().err.strip()
    assert err == err.splitlines()[0] and err.startswith(f"ogk run: {reason}"), err


@pytest.mark.req("OGK-HAR-006")
def test_beyond_acceptance_is_a_failure(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """A converged case whose terminal error exceeds [acceptance]: exit 1 with the reason."""
    scenario = tmp_path / "strict.toml"
    scenario.write_text(APOPHIS.read_text().split("# ----------------------------------------------"
                                                  "------------------ published")[0]
                        + "\n[acceptance]\nposition_error_km = 1e-3\n")
    out = _product_dir(scenario)
    try:
        assert main(["run", str(scenario), "--case", "thrust", "--param=3", "--no-reference"]) == 1
        err = capsys.readouterr().err
        assert "FAILED: tolerance: |dr_f|" in err and "([acceptance])" in err, err
    finally:
        shutil.rmtree(out, ignore_errors=True)


@pytest.mark.req("OGK-HAR-005", "OGK-MPSP-002")
@pytest.mark.parametrize("verb", ["run", "mc"])
@pytest.mark.parametrize("option,value,reason", [
    ("--order", "16", "--order: must be in 1..15"),
    ("--order", "0", "--order: must be in 1..15"),
    ("--basis", "foo", "argument --basis: invalid choice: 'foo'"),
])
def test_bad_fourier_options(tmp_path: Path, capsys: pytest.CaptureFixture[str], verb: str,
                             option: str, value: str, reason: str) -> None:
    argv = (["run", "apophis", "--case", "thrust", "--param=3", "--no-reference"] if verb == "run"
            else ["mc", "apophis", "--runs", "2", "--json", str(tmp_path / "mc.json")])
    try:
        code = main(argv + [option, value])
    except SystemExit as exit_:          # argparse's own refusal
        code = exit_.code
    assert code == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert reason in err[-1], err
