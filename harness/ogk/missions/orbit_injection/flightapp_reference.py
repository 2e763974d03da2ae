"""The flight application's runs A and B (port/cortex-m7/flightapp/main.c) flown by this family's host
SIL (sil.py: point-mass truth, the kernel NOG through cffi, no dispersion but the run's fixed ignition
offset), printed in the flight app's format so that port/cortex-m7/flightapp/compare_runs.py can compare
them with the app built with -DFLIGHTAPP_STAGE_COMMANDS=1 (the same plant semantics: command evaluated at
every RK4 stage).

    .venv/bin/python -m ogk.missions.orbit_injection.flightapp_reference TABLE_DIR > sil.log

A manual cross-check (about 15 s, most of it the nominal solve), run by `make flight-app-sil-compare`, not
by make test-flight-app (docs/guides/flight-integration.md, "Verification"). It lives with the family because it
flies the family's SIL; the flight port imports no mission.
"""
from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
from ogk_host.orbit_injection.scenario import DEFAULT_SCENARIO_PATH, load_scenario

from ogk.sil.seeds import run_generator

from .dispersions import DispersionSwitches, RunDraws
from .guidance import GuidanceSetup
from .nog_guidance import KernelNogGuidance
from .nominal_ref import resolved_with_reference
from .sil import SilSettings, fly_runs

# The offsets of main.c: A none, B +1 sigma of Table 3 on r, phi, v_r, v_t, v_n.
RUNS = {"A nominal": [0.0] * 6,
        "B +1 sigma": [5.0e3, 0.0, 1.186823891356144e-4, 30.0, 30.0, 30.0]}


def main(argv: list[str]) -> int:
    table_dir = Path(argv[1]) if len(argv) > 1 else Path("build/tables/leo_geo")
    bundle = next(table_dir.glob("nog_bundle.ogkt"))
    scn, ref = resolved_with_reference(load_scenario(DEFAULT_SCENARIO_PATH))
    n = len(RUNS)
    draws = RunDraws(np.arange(n, dtype=np.int64), np.zeros(n, dtype=np.uint64),
                     np.array(list(RUNS.values()), dtype=np.float64), np.zeros((n, 3)),
                     np.zeros((n, 3)), np.zeros((n, 10)))
    gens = [run_generator(i) for i in range(n)]   # PCG64(i): the streams the reference always had
    guidance = KernelNogGuidance(GuidanceSetup(scn, ref, draws.run_id), bundle)
    res = fly_runs(scn, ref, draws, gens, DispersionSwitches.none(), guidance,
                   SilSettings(truth="point-mass", end_game="paper"))  # as the flight app flies
    vc = float(np.sqrt(scn.mu_m3_s2 / scn.target_radius_m))
    for i, name in enumerate(RUNS):
        r, _, phi, vr, vt, vn = res.final_state[i]
        t_f = float(res.errors["tf_s"][i]) if "tf_s" in res.errors else float("nan")
        print(f"flightapp: {name}: cut-off t_f = {t_f:.6f} s: dr_f = {r - scn.target_radius_m:.6f} m, "
              f"dphi_f = {np.degrees(phi):.3e} deg, dv_rf = {vr:.6f} m/s, dv_tf = {vt - vc:.6f} m/s, "
              f"dv_nf = {vn:.6f} m/s")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
