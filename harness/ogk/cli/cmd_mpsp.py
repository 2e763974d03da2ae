"""`ogk mpsp apophis ...`: the older spelling of `ogk cases apophis ...` (README), the kernel's MPSP
on the paper's Apophis mission: `--case {initial,terminal,thrust} --param P` or `--paper-tables`
(docs/guides/mpsp-cli.md). `--scenario FILE` flies another scenario of the same family."""
from __future__ import annotations

import argparse
from typing import Any

from ogk.cli.scenario_command import run_scenario_command

MISSIONS = {"apophis": "apophis"}


def register(sub: Any) -> None:
    # an older spelling: works, not listed by `ogk --help` (no help text)
    p = sub.add_parser("mpsp", description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter,
                       add_help=False)
    p.add_argument("-h", "--help", action="store_true", dest="show_help",
                   help="show this help; after MISSION, the options of `ogk cases`")
    p.add_argument("mission", choices=tuple(MISSIONS), nargs="?")
    p.add_argument("rest", nargs=argparse.REMAINDER, help=argparse.SUPPRESS)

    def run(args: argparse.Namespace) -> int:
        if args.show_help and args.mission is None:
            p.print_help()
            return 0
        rest = ["--help", *args.rest] if args.show_help else args.rest
        return run_scenario_command("cases", MISSIONS.get(args.mission or "", None), rest, p)
    p.set_defaults(func=run)
