"""The scenario's end-game (energy cut-off by the kernel's ogk_cutoff, 0.5 s sampling in the last
20 s, ogk_terminal in the last 10 s: radius and plane shaped with a 0.5 s lead, along the velocity to
be gained in the last 2 s; docs/design/vtd-nog.md, "End-game") against the paper's (cut-off predicted at the 2 s samples, eq. 32) on the same runs: the
six runs of 1000 (seed 424242, 6-DOF, every dispersion) that the paper's end-game flies beyond the
scenario's 20 m/s acceptance.

Measured when written (ogk mc leo-geo --runs 1000 --seed 424242): paper's end-game 6 failures, worst
|dv_tf| 33.5 m/s (run 191, t_f 114.0 s: t_f^(k) at the dtf_max_s clip from 6 s before the end, the
predicted cut-off 2 s early); the scenario as flown (end-game, CPD feed-forward clip 0.4 rad/s,
braking margin 1) 0 failures, worst |dr_f| 10.6 m, |dv_rf| 0.12, |dv_tf| 0.00083, |dv_nf| 0.11 m/s
over the 1000 runs with the 3 s v_go window flown until 2026-12-02; with the shaped 10 s window
(2026-12-02) 0 failures, worst 3.07 m, 1.25, 0.0018, 0.16 m/s. On these six runs the shaped window
leaves at most 3.07 m and 0.14 m/s.
"""
from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from ogk_host.orbit_injection.scenario import load_scenario

from ogk.missions.orbit_injection.dispersions import DispersionSwitches, draw_runs
from ogk.missions.orbit_injection.guidance import GuidanceSetup
from ogk.missions.orbit_injection.nog_guidance import KernelNogGuidance, prepare_tables
from ogk.missions.orbit_injection.nominal_ref import resolved_with_reference
from ogk.missions.orbit_injection.sil import EndGamePlan, SilSettings, fly_runs

pytestmark = pytest.mark.req("OGK-NOG-016", "OGK-NOG-018")

WORST_RUNS = [102, 191, 255, 498, 631, 950]   # seed 424242, paper's end-game beyond 20 m/s
SEED = 424242


@pytest.fixture(scope="module")
def flown() -> dict[str, dict[str, np.ndarray]]:
    flown_as_is, ref = resolved_with_reference(load_scenario())
    bundle = prepare_tables(flown_as_is).bundle
    # "paper": the paper's end-game with the CPD feed-forward clip (0.05 rad/s) and braking margin
    # (0.5) flown before this work, i.e. the loop these six runs failed with; "scenario": everything
    # the scenario flies.
    before = dataclasses.replace(flown_as_is, cpd=dataclasses.replace(
        flown_as_is.cpd, feedforward_rate_max_rad_s=0.05, braking_margin=0.5))
    out = {}
    for end_game in ("paper", "scenario"):
        settings = SilSettings(end_game=end_game)
        scn = before if end_game == "paper" else flown_as_is
        plan = EndGamePlan.of(scn, settings)
        draws, gens = draw_runs(scn, SEED, WORST_RUNS, DispersionSwitches())
        guidance = KernelNogGuidance(GuidanceSetup(scn, ref, draws.run_id, plan.fine_interval_s),
                                     bundle)
        res = fly_runs(scn, ref, draws, gens, DispersionSwitches(), guidance, settings)
        assert res.failure == [""] * len(WORST_RUNS)
        out[end_game] = res.errors
    return out


def test_scenario_flies_the_energy_cutoff() -> None:
    plan = EndGamePlan.of(load_scenario(), SilSettings())
    assert plan.energy_cutoff and plan.fine_interval_s == 0.5 and plan.fine_window_s == 20.0
    assert plan.terminal_window_s == 10.0
    assert (EndGamePlan.of(load_scenario(), SilSettings(end_game="paper"))
            == EndGamePlan(False, None, 0.0, 0.0))


def test_paper_end_game_misses_on_these_runs(flown) -> None:
    paper = flown["paper"]
    worst = np.max(np.abs(np.stack([paper[k] for k in ("dvr_f_mps", "dvt_f_mps", "dvn_f_mps")])),
                   axis=0)
    assert np.all(worst > 20.0), worst          # each of them beyond the acceptance
    assert np.max(np.abs(paper["dvt_f_mps"])) > 30.0


def test_end_game_bounds_them(flown) -> None:
    ours = flown["scenario"]
    # The cut-off on energy leaves no along-track error: 0.2 m/s covers the linear extrapolation
    # of the energy inside a 20 ms control step at 18 m/s^2 many times over.
    assert np.max(np.abs(ours["dvt_f_mps"])) < 0.2
    # Thrust along v_go in the last 2 s: what is left is the attitude loop's pointing error over
    # it (about 0.1 m/s); 1 m/s is a third of the paper's dv_r sigma.
    for key in ("dvr_f_mps", "dvn_f_mps"):
        assert np.max(np.abs(ours[key])) < 1.0, (key, ours[key])
    # The radius is steered out in the window (E-guidance) until its last 2 s. The paper's end-game
    # leaves 38 m on run 498 of these; one paper sigma (Table 7) is 4.26 m.
    assert np.max(np.abs(ours["dr_f_m"])) < 4.26, ours["dr_f_m"]
