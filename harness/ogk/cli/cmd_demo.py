"""`ogk demo NAME`: small end-to-end runs of the kernel through the harness."""
from __future__ import annotations

import argparse
from typing import Any


def run_switching(args: argparse.Namespace) -> int:
    from ogk.demos.switching import format_report, run_switching_demo

    demo = run_switching_demo(distance=args.distance, duration=args.duration,
                              u_max=args.u_max, step=args.step)
    print(format_report(demo))
    return 0 if demo.ok(args.tolerance) else 1


def register(sub: Any) -> None:
    p = sub.add_parser("demo", help="run a demonstration through the kernel")
    demos = p.add_subparsers(dest="demo", metavar="DEMO", required=True)
    sw = demos.add_parser(
        "switching",
        help="minimum-fuel double integrator: RK4 switch location vs closed form",
        description="Rest-to-rest minimum-fuel transfer of r'' = u, |u| <= u_max "
                    "(bang-off-bang), integrated by the kernel's RK4 with switching-"
                    "function detection; prints located vs closed-form switch times.",
    )
    sw.add_argument("--distance", type=float, default=1.0, help="transfer distance D [m]")
    sw.add_argument("--duration", type=float, default=3.0, help="transfer time T [s]")
    sw.add_argument("--u-max", type=float, default=1.0, help="thrust acceleration [m/s^2]")
    sw.add_argument("--step", type=float, default=0.1, help="RK4 step h [s]")
    sw.add_argument("--tolerance", type=float, default=1e-10,
                    help="exit 1 if any error exceeds this (default 1e-10)")
    sw.set_defaults(func=run_switching)
