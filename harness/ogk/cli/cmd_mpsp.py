"""`ogk mpsp apophis ...`: the older spelling of `ogk cases apophis ...` (README), the kernel's MPSP
on the paper's Apophis mission: `--case {initial,terminal,thrust} --param P` or `--paper-tables`
(docs/mpsp-cli.md). `--scenario FILE` flies another scenario of the same family."""
from __future__ import annotations

import argparse
from typing import Any

from ogk.cli.scenario_command import run_scenario_command

MISSIONS = {"apophis": "apophis"}


def register(sub: Any) -> None:
    p = sub.add_parser("mpsp", help="MPSP guidance on the Apophis mission (= ogk cases apophis)",
                       description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter,
                       add_help=False)
    p.add_argument("mission", choices=tuple(MISSIONS), nargs="?")
    p.add_argument("rest", nargs=argparse.REMAINDER)
    p.set_defaults(func=lambda args: run_scenario_command(
        "cases", MISSIONS.get(args.mission or "", None), args.rest, p))
