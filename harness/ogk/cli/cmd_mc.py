"""`ogk mc leo-geo`: Monte Carlo campaign of the LEO-to-GEO injection burn (docs/sil.md).

  ogk mc leo-geo --runs N --seed S [--workers W] [--no-dispersions] [--truth {6dof,point-mass}]
                 --json FILE [--plots DIR] [--guidance {nog,nominal}]

prints the side-by-side table with the paper's Table 6 (no dispersions) or Table 7, writes the JSON
(statistics + every run's seed, dispersed values and injection errors) and optionally PNG plots.
"""
from __future__ import annotations

import argparse
import sys
from typing import Any

NOG_MODULE = "ogk.missions.orbit_injection.nog_guidance"
NOG_CLASS = "KernelNogGuidance"


def load_guidance(name: str) -> Any:
    """The guidance factory for --guidance: the kernel VTD-NOG or the open-loop nominal."""
    if name == "nominal":
        from ogk.missions.orbit_injection.guidance import NominalOpenLoopGuidance
        return NominalOpenLoopGuidance
    import importlib
    try:
        module = importlib.import_module(NOG_MODULE)
    except ModuleNotFoundError as exc:
        if exc.name != NOG_MODULE:
            raise
        raise SystemExit(f"ogk mc: --guidance nog needs {NOG_MODULE}.{NOG_CLASS} (the kernel "
                         f"VTD-NOG guidance), which is not available yet; use --guidance nominal "
                         f"for the open-loop reference") from None
    factory = getattr(module, NOG_CLASS, None)
    if factory is None:
        raise SystemExit(f"ogk mc: {NOG_MODULE} has no {NOG_CLASS}")
    return factory


def run_leo_geo(args: argparse.Namespace) -> int:
    from ogk.missions.orbit_injection.campaign import run_campaign
    from ogk.missions.orbit_injection.report import format_report
    from ogk.missions.orbit_injection.sil import SilSettings
    from ogk_host.orbit_injection.scenario import load_scenario

    factory = load_guidance(args.guidance)
    scn = load_scenario(args.scenario)
    settings = SilSettings(control_rate_hz=args.control_rate, truth_substeps=args.truth_substeps,
                           history_runs=args.history_runs if args.plots else 0,
                           cpd_gains=args.cpd_gains, cpd_pointing=args.cpd_pointing)
    res = run_campaign(scn, runs=args.runs, seed=args.seed, workers=args.workers,
                       dispersions=not args.no_dispersions, truth=args.truth,
                       guidance_factory=factory, guidance_name=args.guidance, settings=settings)
    print(format_report(res))
    res.write_json(args.json)
    print(f"\nwrote {args.json}")
    if args.plots:
        from ogk.missions.orbit_injection.plots import write_plots
        for path in write_plots(res, args.plots):
            print(f"wrote {path}")
    return 0 if res.n_failures == 0 else 1


def register(sub: Any) -> None:
    p = sub.add_parser("mc", help="Monte Carlo campaigns (software in the loop)")
    missions = p.add_subparsers(dest="mission", metavar="MISSION", required=True)
    lg = missions.add_parser(
        "leo-geo", help="LEO-to-GEO injection burn (Pontani & Celani 2021, sec. 6)",
        description="Flies the LEO-to-GEO injection burn with a 6-DOF (or point-mass) truth "
                    "model, the guidance and the kernel CPD attitude control; prints injection "
                    "errors side by side with the paper's Table 6 / Table 7.")
    lg.add_argument("--runs", type=int, required=True, help="number of runs")
    lg.add_argument("--seed", type=int, required=True, help="master seed (run i: SeedSequence(seed, (i,)))")
    lg.add_argument("--workers", type=int, default=1, help="parallel processes (default 1)")
    lg.add_argument("--no-dispersions", action="store_true",
                    help="no dispersions: alignment errors only (Table 6 case)")
    lg.add_argument("--truth", choices=("6dof", "point-mass"), default="6dof")
    lg.add_argument("--guidance", choices=("nog", "nominal"), default="nog",
                    help="nog: kernel VTD-NOG (ogk.missions.orbit_injection.nog_guidance); nominal: open-loop u*(t)")
    lg.add_argument("--json", required=True, help="output JSON file")
    lg.add_argument("--plots", default=None, help="directory for PNG plots")
    lg.add_argument("--history-runs", type=int, default=50,
                    help="runs whose time histories are recorded for --plots (default 50)")
    lg.add_argument("--scenario", default=None, help="scenario TOML (default scenarios/leo_geo.toml)")
    lg.add_argument("--control-rate", type=float, default=50.0, help="attitude control rate [Hz]")
    lg.add_argument("--truth-substeps", type=int, default=1,
                    help="truth RK4 steps per control step (default 1: 20 ms)")
    lg.add_argument("--cpd-gains", choices=("printed", "rederived"), default=None,
                    help="CPD gain set (default: the scenario's flown set)")
    lg.add_argument("--cpd-pointing", choices=("body", "euler"), default="body",
                    help="CPD pitch/yaw error: body-axis (default) or eqs. 45-46 literally")
    lg.set_defaults(func=run_leo_geo)


if __name__ == "__main__":
    from ogk.cli import main
    sys.exit(main(["mc", *sys.argv[1:]]))
