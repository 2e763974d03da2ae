"""`ogk mpsp apophis` (harness/ogk/cli/cmd_mpsp.py): one case of each kind through the command line.

Convergence is checked against the paper's tolerances (section 4.1: 500 km, 0.1 km/s, |lambda_m(tf)|
<= 1e-6); the fuel increase of one case against a fresh fuel-optimal re-solve by the ground indirect
solver (host/ogk_host/low_thrust_transfer/indirect.py), whose terminal conditions are re-integrated here.
The 23-case comparison with Tables 3, 5, 6 is the slow command `ogk mpsp apophis --paper-tables`.
"""
from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from ogk.missions.low_thrust_transfer.report import JSON_KEYS
from ogk.cli import main

LU_KM = 1.495979e8
M0_KG = 25.0


def _run(tmp_path: Path, *args: str) -> dict[str, object]:
    out = tmp_path / "case.json"
    rc = main(["mpsp", "apophis", *args, "--json", str(out),
               "--reference-dir", str(tmp_path / "ref")])
    doc = json.loads(out.read_text())
    assert rc == (0 if doc["converged"] else 1)
    return doc


def _assert_within_paper_tolerances(doc: dict[str, object]) -> None:
    assert set(doc) == set(JSON_KEYS)
    assert doc["converged"] is True
    assert 0.0 <= float(doc["dr_f_km"]) <= 500.0  # type: ignore[arg-type]
    assert 0.0 <= float(doc["dv_f_kmps"]) <= 0.1  # type: ignore[arg-type]
    assert abs(float(doc["lambda_mf"])) <= 1e-6  # type: ignore[arg-type]
    assert 1 <= int(doc["newton_iterations"]) <= 100  # type: ignore[call-overload]
    assert float(doc["cpu_s"]) > 0.0  # type: ignore[arg-type]


@pytest.mark.req("OGK-MPSP-012")
@pytest.mark.parametrize(("kind", "param", "paper_ni"), [
    ("terminal", "-0.02,-0.02,0.02", 9),   # Table 4/5 case 7: nominal thrust sequence kept
    ("thrust", "3", 4),                    # Table 6 eta = +3 %
])
def test_case_converges_within_paper_tolerances(tmp_path: Path, kind: str, param: str,
                                                paper_ni: int) -> None:
    doc = _run(tmp_path, "--case", kind, f"--param={param}", "--no-reference")
    _assert_within_paper_tolerances(doc)
    assert doc["fuel_increase_pct"] is None
    # both cases keep the nominal 5 thrust arcs in the paper (Figs. 7, 10); few iterations
    assert doc["thrust_arcs"] == 5
    assert abs(int(doc["newton_iterations"]) - paper_ni) <= 6  # type: ignore[call-overload]
    # the propellant used moves with the perturbation but stays near the nominal 3.94 kg
    assert 20.5 < float(doc["final_mass_kg"]) < 21.5  # type: ignore[arg-type]


@pytest.mark.req("OGK-MPSP-012")
def test_initial_case_fuel_increase_against_fresh_reoptimisation(tmp_path: Path) -> None:
    """Table 3 kappa = -1 (paper: NI 5, FI 2.28 %): FI of the command against a fuel-optimal solution
    of the same perturbed problem computed here, verified by re-integrating its costates."""
    from ogk_host.low_thrust_transfer.indirect import (load_solution, propagate, shooting_residual,
                                           solve_fuel_optimal)
    from ogk_host.low_thrust_transfer.scenario import (initial_state_case, load_scenario,
                                           normalised_problem)
    doc = _run(tmp_path, "--case", "initial", "--param=-1")
    _assert_within_paper_tolerances(doc)
    assert abs(int(doc["newton_iterations"]) - 5) <= 2  # type: ignore[call-overload]

    sc = load_scenario()
    pert = initial_state_case(sc, -1.0)
    opt = solve_fuel_optimal(sc, pert, warm_start=load_solution(sc))
    prob = normalised_problem(sc, pert)
    prop = propagate(prob, opt.lam0, 0.0, rtol=1e-12)
    res = shooting_residual(prob, prop.z_final)
    assert np.linalg.norm(res[:3]) * LU_KM < 1.0 and abs(res[6]) < 1e-9  # a true optimum
    m_opt = float(prop.z_final[6]) * sc.units.mass_kg
    fi = 100.0 * ((M0_KG - float(doc["final_mass_kg"])) - (M0_KG - m_opt)) / (M0_KG - m_opt)  # type: ignore[arg-type]
    assert doc["fuel_increase_pct"] == pytest.approx(fi, abs=1e-3)
    # MPSP meets the constraints only to 500 km, so it may undercut the optimum by a hair at most;
    # and the paper's FI values are all below 6.1 %
    assert -0.5 < float(doc["fuel_increase_pct"]) < 6.1  # type: ignore[arg-type]

    # second run: the reference comes from the cache (verified), same FI
    cached = _run(tmp_path, "--case", "initial", "--param=-1")
    assert cached["fuel_increase_pct"] == pytest.approx(doc["fuel_increase_pct"], abs=1e-6)
    entry = json.loads((tmp_path / "ref" / "initial_kappa-1.json").read_text())
    assert entry["final_mass_kg"] == pytest.approx(m_opt, abs=1e-6)


@pytest.mark.req("OGK-HAR-008")
def test_stale_or_corrupt_reference_is_recomputed(tmp_path: Path) -> None:
    """A cache entry of another scenario file, or whose costates do not re-integrate to the target,
    is not trusted."""
    ref_dir = tmp_path / "ref"
    ref_dir.mkdir()
    bogus = {"format": 1, "scenario_sha256": "0" * 64, "nominal_sha256": "0" * 64,
             "lambda0": [1.0, 0, 0, 0, 1.0, 0, 0.5], "final_mass_kg": 24.9, "solve_s": 0.0,
             "method": "bogus"}
    (ref_dir / "thrust_eta+3.json").write_text(json.dumps(bogus))
    doc = _run(tmp_path, "--case", "thrust", "--param", "3")
    entry = json.loads((ref_dir / "thrust_eta+3.json").read_text())
    assert entry["method"] != "bogus" and entry["scenario_sha256"] != "0" * 64
    assert 20.5 < entry["final_mass_kg"] < 21.5
    assert doc["fuel_increase_pct"] is not None and -0.5 < float(doc["fuel_increase_pct"]) < 6.1  # type: ignore[arg-type]


@pytest.mark.req("OGK-HAR-005")
def test_bad_arguments_are_rejected(tmp_path: Path) -> None:
    assert main(["mpsp", "apophis", "--case", "terminal", "--param", "0.02,0.02",
                 "--no-reference"]) == 2
    assert main(["mpsp", "apophis"]) == 2
    assert main(["mpsp", "apophis", "--paper-tables", "--case", "thrust", "--param", "3"]) == 2
