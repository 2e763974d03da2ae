"""Command line of the Apophis ground tool.

  python -m ogk_host.low_thrust_transfer regenerate   solve the nominal from scratch, write it with its
                                          manifest into the scenario's product directory
                                          build/tables/<name>-<sha12>/ (never into the package)
  python -m ogk_host.low_thrust_transfer report       summary of the scenario's nominal + Fourier-basis measurement
  python -m ogk_host.low_thrust_transfer perturbed    fuel-optimal solutions of perturbed problems (warm start)
        [--kappa K ...] [--vertex I ...] [--eta PERCENT ...]   (default: kappa 1, vertex 1, eta -10)
  python -m ogk_host.low_thrust_transfer references   all cases of the scenario's [dispersions], written to
                                          perturbed_optima.json in its product directory (FI references)

Every command takes --scenario FILE (default scenarios/apophis_cubesat.toml) and --out DIR (default
build/tables/<name>-<sha12> of the scenario). The shipped data/*.json are a cache used only for a
scenario of the same physics (ogk_host.low_thrust_transfer.products); this tool never writes them.
"""
from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

import numpy as np

from . import fourier
from ogk_bindings.errors import OgkInputError

from . import products
from .indirect import Solution, save_references, solution_record, solve_fuel_optimal
from .scenario import (DEFAULT_SCENARIO_PATH, Perturbation, Scenario, initial_state_case,
                       load_scenario, terminal_position_case, thrust_case)


def _log(message: str) -> None:
    print(message, flush=True)


def describe(solution: Solution, scenario: Scenario) -> str:
    day = scenario.units.time_s / 86400.0
    lines = [
        f"{solution.perturbation.label}: final mass {solution.final_mass_kg:.4f} kg, "
        f"{solution.thrust_arcs} thrust arcs, {solution.coast_arcs} coast arcs ({solution.method})",
        "  switching times [days]: " + ", ".join(f"{t * day:.3f}" for t in solution.switch_times),
        f"  terminal errors: |dr| = {solution.position_error_km:.3e} km, "
        f"|dv| = {solution.velocity_error_km_s:.3e} km/s, |lambda_m(tf)| = {abs(solution.residual[6]):.3e}",
        f"  lambda_0 = {np.array2string(solution.lam0, precision=10, max_line_width=200)}",
        f"  Newton iterations {solution.newton_iterations}, runtime {solution.runtime_s:.1f} s",
    ]
    return "\n".join(lines)


def cmd_regenerate(scenario: Scenario, out: Path) -> int:
    start = time.perf_counter()
    solution = products.solve_nominal(scenario, log=_log)
    doc = {"generator": "python -m ogk_host.low_thrust_transfer regenerate",
           "units": "normalised: LU, TU, MU, velocity LU/TU (Table 1)",
           **solution_record(solution, scenario)}
    path = products.write_nominal(doc, scenario, out)
    print(describe(solution, scenario))
    print(f"written {path} and {out / products.MANIFEST} ({time.perf_counter() - start:.1f} s)")
    return 0


def cmd_report(scenario: Scenario, out: Path) -> int:
    solution, _ = products.ensure_nominal(scenario, out, log=_log)
    print(describe(solution, scenario))
    t, lam_v = fourier.nominal_control_on_grid(scenario, solution)
    print(f"Fourier fit of the nominal lambda_v on the MPSP grid ({t.size} points, "
          f"h_max = {scenario.mpsp.h_max_over_tf:g} t_f):")
    print("  basis       order  max|err|    rms   max rel  angle[deg]   cond(h)   max|eps|  |dY| flown")
    for basis in fourier.BASIS_ETA_RANGE:
        for order in (5, 10, scenario.mpsp.fourier_order):
            e = fourier.fit_error(t, lam_v, scenario.final_time, basis, order)
            eta = fourier.eta_of_time(t, 0.0, scenario.final_time, basis)
            eps = fourier.least_squares_weights(eta, lam_v, order, basis)
            flown = fourier.fly_fitted_control(scenario, solution, basis, eps, order)
            print(f"  {basis:<11} {order:>5}  {e.max_abs:8.4f} {e.rms:8.4f} {e.max_relative:8.4f} "
                  f"{e.max_angle_deg:9.3f} {e.condition_number:10.3g} {e.max_weight:10.3g} "
                  f"{np.linalg.norm(flown):10.3e}")
    print(f"  |lambda_v| ranges over [{e.signal_min:.3f}, {e.signal_max:.3f}]; |dY| = terminal error "
          "[LU, LU/TU, -] of eq. (16) flown with the fitted lambda_v and the nominal lambda_m0")
    w = fourier.initial_weights(scenario, solution)
    print(f"initial weights: basis {w.basis}, order {w.order}, eta in {w.eta_range}, "
          f"|eps_0| = {np.linalg.norm(w.epsilon):.4f}, lambda_m0 = {w.lambda_m0:.10f}")
    return 0


def cmd_perturbed(scenario: Scenario, kappas: list[float], vertices: list[int],
                  etas: list[float], out: Path, output: Path | None = None) -> int:
    nominal, _ = products.ensure_nominal(scenario, out, log=_log)
    cases: list[Perturbation] = ([initial_state_case(scenario, k) for k in kappas]
                                 + [terminal_position_case(scenario, v) for v in vertices]
                                 + [thrust_case(scenario, e) for e in etas])
    solutions: list[Solution] = []
    for case in cases:
        start = time.perf_counter()
        print(f"--- {case.label}", flush=True)
        solution = solve_fuel_optimal(scenario, case, warm_start=nominal, log=_log)
        solutions.append(solution)
        print(describe(solution, scenario))
        print(f"  (wall {time.perf_counter() - start:.1f} s)", flush=True)
    if output is not None:
        save_references(solutions, scenario, output)
        doc = json.loads(output.read_text())
        doc["physics_sha256"] = products.physics_sha256(scenario.path)
        output.write_text(json.dumps(doc, indent=1) + "\n")
        print(f"written {output}")
    print("case               final mass [kg]  thrust/coast arcs  runtime [s]")
    for s in solutions:
        print(f"  {s.perturbation.label:<16} {s.final_mass_kg:10.4f}  {s.thrust_arcs:>8}/{s.coast_arcs:<8}"
              f" {s.runtime_s:9.1f}")
    return 0


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m ogk_host.low_thrust_transfer", description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("command", choices=("regenerate", "report", "perturbed", "references"))
    parser.add_argument("--scenario", default=str(DEFAULT_SCENARIO_PATH))
    parser.add_argument("--out", default=None, metavar="DIR",
                        help="product directory (default build/tables/<name>-<sha12>)")
    parser.add_argument("--kappa", type=float, nargs="*", default=None)
    parser.add_argument("--vertex", type=int, nargs="*", default=None)
    parser.add_argument("--eta", type=float, nargs="*", default=None)
    args = parser.parse_args(argv)
    try:
        scenario = load_scenario(args.scenario)
        out = Path(args.out) if args.out else products.product_dir(scenario.path)
        if args.command == "regenerate":
            return cmd_regenerate(scenario, out)
        if args.command == "report":
            return cmd_report(scenario, out)
        if args.command == "references":
            p = scenario.dispersions
            return cmd_perturbed(scenario, list(p.kappa), list(range(1, 9)), list(p.eta_percent), out,
                                 out / products.REFERENCES_FILE)
        explicit = args.kappa is not None or args.vertex is not None or args.eta is not None
        return cmd_perturbed(scenario, args.kappa or ([] if explicit else [1.0]),
                             args.vertex or ([] if explicit else [1]),
                             args.eta or ([] if explicit else [-10.0]), out)
    except OgkInputError as err:
        print(err.line(), file=sys.stderr)
        return 2

if __name__ == "__main__":
    sys.exit(main())
