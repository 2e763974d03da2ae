"""Newton iterations of the 23 Apophis cases with a chosen MPSP sensitivity sweep (docs/design/mpsp.md 8).

    .venv/bin/python tests/bench/mpsp_sweep_ni.py rk4|mid2 [period_2tf|cosine_2tf|...] [--json FILE]

Flies the cases of `ogk cases apophis --paper-tables --no-reference` (the same setup,
ogk.missions.low_thrust_transfer.cases.build_setup) with `sens_sweep` set in the kernel's
configuration, and prints per case the Newton iterations (the paper's NI), convergence, thrust arcs,
terminal residuals and kernel CPU: the measurement behind the sixth step's default.
"""
from __future__ import annotations

import argparse
import json
from typing import Any

import ogk.missions.low_thrust_transfer.cases as cases
from ogk_bindings.mpsp import SWEEP_MID2, SWEEP_RK4, MpspConfig

SWEEPS = {"rk4": SWEEP_RK4, "mid2": SWEEP_MID2}


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("sweep", choices=sorted(SWEEPS))
    p.add_argument("basis", nargs="?", default=None, help="Fourier basis (default: the scenario's)")
    p.add_argument("--json", default=None, metavar="FILE", help="the rows as JSON")
    args = p.parse_args()
    sweep = SWEEPS[args.sweep]

    def config(**kw: Any) -> MpspConfig:
        return MpspConfig(sens_sweep=sweep, **kw)

    cases.MpspConfig = config  # type: ignore[assignment,misc]   # build_setup's constructor
    setup = cases.build_setup(args.basis, None, None)
    lu_km, vu_km_s = setup.lu_km, setup.vu_km_s
    rows = []
    for case in cases.paper_cases(setup):
        res, cpu = cases.fly_run(setup, case)
        row = {"case": case.label, "ni": int(res.newton_iterations), "converged": bool(res.converged),
               "thrust_arcs": int(res.n_thrust_arcs), "dr_km": float(res.err_r) * lu_km,
               "dv_km_s": float(res.err_v) * vu_km_s, "lambda_mf": float(res.lambda_mf), "cpu_s": cpu}
        rows.append(row)
        print(f"{case.label:16s} NI {row['ni']:3d}  converged {int(row['converged'])}  arcs "
              f"{row['thrust_arcs']}  |dr_f| {row['dr_km']:8.2f} km  |dv_f| {row['dv_km_s']:.2e} km/s  "
              f"lambda_mf {row['lambda_mf']:+.2e}  CPU {cpu:.3f} s", flush=True)
    print(f"sweep {args.sweep}, basis {setup.basis}: {sum(r['converged'] for r in rows)}/{len(rows)} "
          f"converged, NI total {sum(r['ni'] for r in rows)}, kernel CPU {sum(r['cpu_s'] for r in rows):.3f} s")
    if args.json:
        with open(args.json, "w") as f:
            json.dump(rows, f, indent=1)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
