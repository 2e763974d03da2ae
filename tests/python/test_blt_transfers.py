"""Issue 11: the BLT transfers of scenarios/moshup.toml end to end: the ground's guess (SBIG / UbMPIG), the
flight kernel's corrector (ogk_blt_solve through the bindings) in the realistic model, and the independent
check: the same error vector recomputed by scipy's DOP853 (ogk.missions.binary.trajectory), which shares no
integrator with the kernel, must meet the tolerance. Plus `ogk blt` / `ogk mc` on small runs."""
from __future__ import annotations

import json
import subprocess
import sys
from functools import lru_cache
from pathlib import Path

import numpy as np
import pytest

from ogk.sil import envelope

from ogk_bindings.blt import Transfer
from ogk.missions.binary.convergence_run import Nominal, draw
from ogk.missions.binary.trajectory import reference_errors
from ogk_host.binary import transfers as T
from ogk_host.binary.reference import propagate_chain
from ogk_host.binary.scenario import load_scenario

REPO = Path(__file__).resolve().parents[2]
SCENARIO = REPO / "scenarios" / "moshup.toml"
SINGLE = ("l2_to_l1_lyapunov", "l1_to_l2_lyapunov", "l2_to_l1_halo", "l1_to_l2_halo")


@lru_cache(maxsize=None)
def designed(name: str, corrector: str) -> T.Design:
    sc = load_scenario(SCENARIO)
    return T.design(sc, T.transfer_spec(sc, name), T.solver_settings(sc), corrector=corrector)


def _check_converged(d: T.Design, tol: float) -> None:
    assert d.report.converged, (d.report.status, d.report.flag_names(), d.result.steps)
    assert d.report.err_norm <= tol
    ref = reference_errors(d.model, d.guess.layout, d.transfer)
    assert not ref.impact
    assert ref.err_norm <= tol, f"DOP853 recomputes |e| = {ref.err_norm:.3e} > tol {tol:g}"
    for i in range(2):       # no impact anywhere along the solution, by either integrator
        assert d.report.min_distance[i] > d.model.body_radius[i]
        assert ref.closest_approach[i] > d.model.body_radius[i]


@pytest.mark.req("OGK-BLT-010", "OGK-BLT-004")
@pytest.mark.parametrize("corrector", ("lm", "hybrid"))
@pytest.mark.parametrize("name", SINGLE)
def test_single_burn_converges_with_the_damped_correctors(name: str, corrector: str) -> None:
    """Done-when: single-burn StoS in both directions between the L1/L2 Lyapunov and halo orbits at 24 mN, to
    the paper's 1e-6, confirmed by DOP853."""
    _check_converged(designed(name, corrector), 1e-6)


@pytest.mark.req("OGK-BLT-010", "OGK-BLT-004")
@pytest.mark.parametrize("name", ("l2_to_l1_lyapunov", "l1_to_l2_lyapunov", "l1_to_l2_halo"))
def test_single_burn_converges_with_plain_nrpc(name: str) -> None:
    d = designed(name, "nrpc")
    _check_converged(d, 1e-6)
    assert d.report.iterations <= 40


@pytest.mark.req("OGK-BLT-010")
def test_single_burn_figures_are_of_the_papers_order() -> None:
    """The paper's 24 mN L2 -> L1 halo single burn: 190 min and 13.64 g (sec. IV.B). Our orbits' amplitudes
    are not the paper's (it prints none), so only the order is asserted: within 25 %; and fuel = mdot T."""
    sc = load_scenario(SCENARIO)
    d = designed("l2_to_l1_halo", "lm")
    fig = T.figures(sc, d)
    assert abs(fig["burn_time_s"] / 11400.0 - 1.0) < 0.25
    assert abs(fig["fuel_g"] / 13.64 - 1.0) < 0.25
    mdot = 0.024 / (2000.0 * 9.80665)      # [kg/s], independent of the kernel's normalisation
    assert fig["fuel_g"] == pytest.approx(mdot * fig["burn_time_s"] * 1e3, rel=1e-9)


@pytest.mark.req("OGK-BLT-010")
@pytest.mark.parametrize("corrector", ("nrpc", "lm", "hybrid"))
def test_ump_transfer_of_table3_converges(corrector: str) -> None:
    """Done-when: the UMP burn-coast-burn transfer used for Table 3 converges (bilateral arcs, a free node)."""
    d = designed("circle_to_l2_ump", corrector)
    assert d.guess.layout.kinds == ("burn", "coast", "coast", "burn")
    _check_converged(d, 1e-6)


@pytest.mark.req("OGK-BLT-010")
def test_bmp_transfer_converges() -> None:
    """BMPIG (eqs. 36-43) L1 -> L2 Lyapunov through x = 1 - mu: three burns, two coasts, one free node."""
    d = designed("l1_to_l2_lyapunov_bmp", "hybrid")
    assert d.guess.layout.kinds == ("burn", "coast", "burn", "coast", "burn")
    _check_converged(d, 1e-6)
    single = designed("l1_to_l2_lyapunov", "hybrid")
    assert d.report.burn_time < 0.5 * single.report.burn_time   # the manifolds do most of the work


@pytest.mark.req("OGK-BLT-010")
def test_halo_bmp_of_fig_11b_converges() -> None:
    """Fig. 11b, L1 halo -> L2 halo by bilateral manifold patching ([transfers.l1_to_l2_halo_bmp] of
    moshup.toml): at the Lyapunov BMP's d = 0.05 VU every manifold of the L1 halo hits a body before the cut
    (docs/design/blt-ground.md sec. 8); the guess is retried at 3 x d (0.15 VU), where an impact-free pair exists."""
    sc = load_scenario(SCENARIO)
    spec = T.transfer_spec(sc, "l1_to_l2_halo_bmp")
    d = T.design(sc, spec, T.solver_settings(sc), corrector="hybrid")
    assert d.guess.layout.kinds == ("burn", "coast", "burn", "coast", "burn")
    _check_converged(d, 1e-6)
    single = designed("l1_to_l2_halo", "hybrid")
    assert d.report.burn_time < 0.6 * single.report.burn_time      # the manifolds do most of the work
    fig = T.figures(sc, d)
    assert fig["flight_time_s"] > 3.0 * fig["burn_time_s"]


@pytest.mark.req("OGK-BLT-010")
@pytest.mark.parametrize("name", ("l2_to_l1_halo", "l1_to_l2_halo"))
def test_halo_single_burns_converge_in_the_point_mass_model(name: str, tmp_path: Path) -> None:
    """[solver] gravity = "point-mass": the direct solve stalls (L2 -> L1) or its guess grazes Beta (L1 -> L2);
    the transfer is converged in the degree-2 model and carried to point masses by the gravity continuation
    (C20, C22 x lambda, 1 -> 0, the orbits rebuilt at each step), then confirmed by DOP853 in point masses."""
    path = tmp_path / "moshup_point_mass.toml"
    text = SCENARIO.read_text()
    assert text.count('gravity = "scenario"') == 1
    path.write_text(text.replace('gravity = "scenario"', 'gravity = "point-mass"'))
    sc = load_scenario(path)
    d = T.design(sc, T.transfer_spec(sc, name), T.solver_settings(sc))
    assert d.model.c20 == (0.0, 0.0) and d.model.c22 == (0.0, 0.0)
    assert [st["gravity_scale"] for st in d.result.steps if "gravity_scale" in st][-1] == 0.0
    _check_converged(d, 1e-6)
    fig = T.figures(sc, d)      # the paper's 190 min / 13.64 g (L2 -> L1), as in the degree-2 model: within 25 %
    assert abs(fig["burn_time_s"] / 11400.0 - 1.0) < 0.25 and abs(fig["fuel_g"] / 13.64 - 1.0) < 0.25


@pytest.mark.req("OGK-BLT-002")
def test_kernel_propagation_matches_dop853() -> None:
    """The kernel's RK4 (2e-3 TU steps) against DOP853 on the converged L2 -> L1 Lyapunov burn, forward."""
    d = designed("l2_to_l1_lyapunov", "lm")
    from ogk_bindings.blt import Blt
    from ogk_host.binary.guess import kernel_config
    x_kernel, _ = Blt(kernel_config(d.model, d.guess.layout)).propagate(d.transfer)
    s = d.transfer.segments[0]
    ref = propagate_chain(d.model, d.transfer.x0, [("burn", s[0:3], s[3:6], s[6])], t0=d.transfer.t0)
    assert np.max(np.abs(x_kernel - ref.state)) < 1e-9


@pytest.mark.req("OGK-BLT-010")
def test_monte_carlo_draws_are_reproducible_and_bounded() -> None:
    d = designed("circle_to_l2_ump", "nrpc")
    nom = Nominal(model=d.model, layout=d.guess.layout, transfer=d.transfer, circle_radius=4000.0 / 2550.0,
                  tol=5e-5, max_iter=40, jacobian=1, fields={})
    g1, d1 = draw(nom, 0.2, 1.0 / 3.0, np.random.default_rng([5, 1, 3]))
    g2, d2 = draw(nom, 0.2, 1.0 / 3.0, np.random.default_rng([5, 1, 3]))
    assert d1 == d2 and np.array_equal(g1.segments, g2.segments)
    assert max(abs(x) for x in d1["xi"]) <= 1.0
    rel = g1.segments[:, 6] / d.transfer.segments[:, 6] - 1.0
    assert np.all(np.abs(rel) <= 0.2 + 1e-12)
    assert np.linalg.norm(g1.x0[0:3]) == pytest.approx(4000.0 / 2550.0, rel=1e-12)   # still on the circle
    assert np.array_equal(g1.xf, d.transfer.xf)                                       # the target is not perturbed


def _ogk(*args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run([str(Path(sys.executable).parent / "ogk"), *args], capture_output=True, text=True,
                          cwd=REPO, timeout=600)


@pytest.mark.req("OGK-BLT-010", "OGK-HAR-002")
def test_ogk_blt_writes_json_and_plots(tmp_path: Path) -> None:
    r = _ogk("blt", "moshup", "--transfer", "l1_to_l2_lyapunov", "--json", str(tmp_path / "t.json"),
             "--plots", str(tmp_path / "p"))
    assert r.returncode == 0, r.stderr
    doc = json.loads((tmp_path / "t.json").read_text())
    for key in ("converged", "iterations", "final_error", "final_error_dop853", "burn_time_s", "fuel_g",
                "delta_v_m_s", "closest_approach_m", "total_cpu_s"):
        assert key in doc
    assert doc["converged"] and doc["dop853_meets_tol"]
    assert sorted(p.name for p in (tmp_path / "p").iterdir()) == ["l1_to_l2_lyapunov_history.png",
                                                                   "l1_to_l2_lyapunov_synodic.png"]


@pytest.mark.req("OGK-BLT-010", "OGK-HAR-002")
def test_ogk_mc_small_campaign(tmp_path: Path) -> None:
    r = _ogk("mc", "moshup", "--perturbation", "20", "--runs", "6", "--seed", "4242", "--workers", "1",
             "--json", str(tmp_path / "mc.json"))
    assert r.returncode == 0, r.stderr
    doc = json.loads((tmp_path / "mc.json").read_text())
    (level,) = doc["levels"]
    assert level["level_percent"] == 20.0 and level["runs"] == 6
    for c in ("nrpc", "lm", "hybrid"):
        s = level["summary"][c]
        assert 0.0 <= s["converged_pct"] <= 100.0 and s["runs"] == 6
        assert s["converged"] + sum(s["failures"].values()) == 6
        assert s["dop853_confirmed"] == s["converged"]     # every converged run re-propagated independently
    # every run's draw is in the per-run table (the campaign engine's Parquet)
    rows = envelope.read_table(tmp_path / doc["per_run_table"])
    assert len(rows) == 6 and all(r["level_percent"] == 20.0 for r in rows)
    assert all(r["draw.xi"] is not None and len(r["draw.xi"]) == 29 for r in rows)
    assert doc["paper"]["levels"][0]["paper_converged_percent"] == 80.51
    assert "80.51" in r.stdout        # Table 3's 20 % figure printed beside ours


@pytest.mark.req("OGK-HAR-005")
@pytest.mark.parametrize("args", (("blt", "moshup", "--transfer", "nope", "--json", "/tmp/x.json"),
                                  ("mc", "moshup", "--perturbation", "0", "--json", "/tmp/x.json")))
def test_bad_input_exits_2(args: tuple[str, ...]) -> None:
    r = _ogk(*args)
    assert r.returncode == 2, (r.returncode, r.stderr)
    assert r.stderr.count("\n") == 1
