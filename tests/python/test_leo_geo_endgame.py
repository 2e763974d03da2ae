"""End-game of the kernel VTD-NOG on the worst runs of campaigns with thrust fluctuations (eq. 55).

Point-mass truth (guidance only), initial-state and thrust dispersions, 40 runs, fluctuation sigma at the
paper's 0.02 and at 2.5x (0.05), the scenario's end-game (energy cut-off, 0.5 s sampling in the last 20 s,
v_go steering in the last 3 s; the point-mass truth flies the terminal stage's command since 2026-12-02,
before it flew the law's). Measured (seed 7): paper sigma -- the guard engaged (LIMITED) in 9 runs, max
|dr_f| 4.5 m, max |dv| 0.0003 m/s, max |t_f - t_f*| 8.9 s; 2.5x -- LIMITED in 20 runs, max |dr_f| 11.1 m
(the radius is not steered in the window), max |dv| 0.001 m/s, every run inside the t_f bound. (With the
paper's end-game, cut-off fixed at the last 2 s sample, the 2.5x case left 42 m/s in dv_t.) The assertions
hold these with margin: termination, no failure, the flight-time bound, the guard engaging under stress,
bounded errors: dr_f within 2 (paper sigma) and 4 (2.5x) of Table 7's 4.26 m, velocities within 1 m/s.
"""
from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from ogk_host.orbit_injection.scenario import Acceptance, load_scenario

import oi_campaign
from ogk.missions.orbit_injection.dispersions import DispersionSwitches
from ogk.missions.orbit_injection.nog_guidance import KernelNogGuidance, prepare_tables

pytestmark = pytest.mark.req("OGK-NOG-018", "OGK-NOG-009")

_LOG: list["_Recording"] = []


class _Recording(KernelNogGuidance):
    def __init__(self, setup) -> None:  # type: ignore[no-untyped-def]
        super().__init__(setup, prepare_tables(load_scenario()).bundle)
        _LOG.append(self)


def _fly(sigma: float):
    scn = load_scenario()
    # The bounds are asserted below per quantity; the scenario's 10 m/s acceptance would count the
    # last-interval thrust error of the stressed runs as failures before they are looked at.
    scn = dataclasses.replace(scn, thrust_dispersion=dataclasses.replace(
        scn.thrust_dispersion, coefficient_sigma=sigma), acceptance=Acceptance(1e9, 1.0, 1e9))
    _LOG.clear()
    res = oi_campaign.fly(scn, runs=40, seed=7,
                          dispersions=DispersionSwitches(True, False, True, False),
                          truth="point-mass", guidance_factory=_Recording, guidance_name="nog")
    doc = res.to_json_dict(per_run=True)
    flags = np.array(_LOG[0].flag_history)
    return scn, doc, flags


def _column(doc: dict, key: str) -> np.ndarray:
    return np.array([run[key] for run in doc["per_run"]], dtype=float)


@pytest.mark.parametrize("sigma, max_dr, max_dv, guard_runs", [(0.02, 8.5, 1.0, 0),
                                                               (0.05, 17.0, 1.0, 1)])
def test_end_game_bounded_on_worst_runs(sigma: float, max_dr: float, max_dv: float,
                                        guard_runs: int) -> None:
    scn, doc, flags = _fly(sigma)
    assert doc["failures"] == 0
    tf = _column(doc, "tf_s")
    assert np.all(np.isfinite(tf))
    assert np.all(np.abs(tf - doc["nominal_tf_s"]) <= scn.end_game.dtf_max_s)
    assert np.max(np.abs(_column(doc, "dr_f_m"))) < max_dr
    for key in ("dvr_f_mps", "dvt_f_mps", "dvn_f_mps"):
        assert np.max(np.abs(_column(doc, key))) < max_dv
    limited_runs = int(((flags & 0x04) != 0).any(axis=0).sum())
    assert limited_runs >= guard_runs
    # Every run took its terminating sample (eq. 32) before cut-off.
    assert int(((flags & 0x01) != 0).any(axis=0).sum()) == 40
