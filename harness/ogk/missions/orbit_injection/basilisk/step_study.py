"""The tolerances of the Basilisk cross-check for any orbit-injection scenario, from the two truth
models' own step errors (docs/guides/basilisk.md, "Tolerances"):

    .venv/bin/python -m ogk.missions.orbit_injection.basilisk.step_study [SCENARIO] --seed S --runs N

The models integrate the same equations, so they differ by their discretisation errors only. Each
model flies the nominal (no dispersions) and runs 0 .. N-1 of seed S at the dynamics steps h, h/2 and
h/4 (h: the control step, 20 ms); its error at h is estimated by step halving,
e(h) ~ 4/3 |x(h) - x(h/2)| (second order, the slower of the two models), and the observed order
log2(|x(h) - x(h/2)| / |x(h/2) - x(h/4)|) is printed as the check of that assumption. The proposed
tolerance per injection error is 3 (e_ogk + e_bsk), the largest over the runs, rounded up to one
significant digit: what tests/python/test_basilisk.py states per scenario.
"""
from __future__ import annotations

import argparse
import math
import sys

import numpy as np

from ogk_host.orbit_injection.scenario import load_scenario
from ogk_host.scenario_file import resolve_scenario

from ogk.missions.orbit_injection.dispersions import DispersionSwitches
from ogk.missions.orbit_injection.nog_guidance import prepare_tables
from ogk.missions.orbit_injection.nominal_ref import resolved_with_reference
from ogk.missions.orbit_injection.sil import ERROR_KEYS, SilSettings

from .crosscheck import compare

SUBSTEPS = (1, 2, 4)   #: h, h/2, h/4
SAFETY = 3.0           #: tolerance = SAFETY (e_ogk + e_bsk)


def round_up(x: float) -> float:
    """x rounded up to one significant digit (0 stays 0)."""
    if x <= 0.0:
        return 0.0
    e = math.floor(math.log10(x))
    return math.ceil(x / 10.0 ** e - 1e-9) * 10.0 ** e


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m ogk.missions.orbit_injection.basilisk.step_study", description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("scenario", nargs="?", default="leo-geo",
                    help="a .toml path or a shipped scenario's name (default leo-geo)")
    ap.add_argument("--seed", type=int, default=7)
    ap.add_argument("--runs", type=int, default=2)
    args = ap.parse_args(argv)
    scn, ref = resolved_with_reference(load_scenario(resolve_scenario(args.scenario)))
    tables = prepare_tables(scn)
    cases = [("nominal", DispersionSwitches.none(), [0]),
             (f"seed {args.seed}", DispersionSwitches(), list(range(args.runs)))]
    # flown[case][k] = Comparison at SUBSTEPS[k]
    flown = {name: [compare(scn, args.seed, ids, sw, SilSettings(truth_substeps=k),
                            ref=ref, tables=tables) for k in SUBSTEPS]
             for name, sw, ids in cases}
    print(f"{scn.name}: step study at h = 20, 10, 5 ms (nominal and seed {args.seed} runs "
          f"0..{args.runs - 1})")
    print(f"{'key':12s} {'e_ogk':>10s} {'order':>6s} {'e_bsk':>10s} {'order':>6s} "
          f"{'|diff| at h':>11s} {'tolerance':>10s}")
    for key in ERROR_KEYS:
        worst, e_o_max, e_b_max, d_max, orders = 0.0, 0.0, 0.0, 0.0, {"ours": [], "basilisk": []}
        for cmps in flown.values():
            e = {}
            for model in ("ours", "basilisk"):
                x = [getattr(c, model)[key] for c in cmps]
                d1, d2 = np.abs(x[0] - x[1]), np.abs(x[1] - x[2])
                e[model] = 4.0 / 3.0 * d1
                ok = (d1 > 0) & (d2 > 0)
                orders[model] += list(np.log2(d1[ok] / d2[ok]))
            worst = max(worst, float(np.max(SAFETY * (e["ours"] + e["basilisk"]))))
            e_o_max = max(e_o_max, float(np.max(e["ours"])))
            e_b_max = max(e_b_max, float(np.max(e["basilisk"])))
            d_max = max(d_max, float(np.max(np.abs(cmps[0].difference()[key]))))
        med = {m: (float(np.median(v)) if v else math.nan) for m, v in orders.items()}
        print(f"{key:12s} {e_o_max:10.2g} {med['ours']:6.2f} {e_b_max:10.2g} "
              f"{med['basilisk']:6.2f} {d_max:11.2g} {round_up(worst):10.2g}")
    failed = any(any(f for fl in c.failures.values() for f in fl)
                 for cmps in flown.values() for c in cmps)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
