"""The `ogk` command. Each subcommand lives in its own module (ogk/cli/cmd_<name>.py)
exposing `register(subparsers)`, which adds its parser and sets `func`
(args -> exit code). To add one, write the module and list it in SUBCOMMANDS.
Scenario commands (tables, mc, cases) dispatch to the scenario's mission family
(ogk.missions.registry). Bad input ends with one line naming the file, key and
reason and exit code 2; a campaign aborted by a fault (a run raised, a worker died, the
watchdog fired: ogk.sil.runner.CampaignAborted) with one line naming the runs and the status and
exit code 1; an interrupted one (Ctrl-C, SIGTERM) with one line and exit code 130 (a traceback
only with --debug)."""
from __future__ import annotations

import argparse
import importlib
import sys
from collections.abc import Sequence

from ogk_bindings.errors import OgkInputError

import ogk
from ogk.sil.runner import CampaignAborted, CampaignInterrupted

SUBCOMMANDS: tuple[str, ...] = (
    "ogk.cli.cmd_version",
    "ogk.cli.cmd_demo",
    "ogk.cli.cmd_tables",
    "ogk.cli.cmd_mc",
    "ogk.cli.cmd_run",
    "ogk.cli.cmd_replay",
    "ogk.cli.cmd_report",
    "ogk.cli.cmd_cases",
    "ogk.cli.cmd_mpsp",
    "ogk.cli.cmd_nmpc",
    "ogk.cli.cmd_blt",
    "ogk.cli.cmd_soak",
)


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="ogk",
        description="ogk SIL harness and ground tools (kernel bindings, demos, campaigns).",
        epilog="Older spellings still accepted, not listed: cases, mpsp, nmpc, blt (ogk run and ogk mc "
               "fly what they flew; docs/guides/harness.md).",
    )
    parser.add_argument("--debug", action="store_true",
                        help="show the traceback of an error instead of its one-line message")
    parser.add_argument("--version", action="version", version=f"ogk {ogk.__version__}",
                        help="print the version and exit (`ogk version`: the kernel's too)")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    for name in SUBCOMMANDS:
        importlib.import_module(name).register(sub)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    func = getattr(args, "func", None)
    if func is None:
        parser.print_help(sys.stderr)
        return 2
    try:
        return int(func(args))
    except OgkInputError as err:
        if args.debug:
            raise
        print(f"ogk {args.command}: {err.line()}", file=sys.stderr)
        return 2
    except CampaignAborted as err:
        if args.debug:
            raise
        print(f"ogk {args.command}: {err.line()}", file=sys.stderr)
        return 130 if isinstance(err, CampaignInterrupted) else 1
    except KeyboardInterrupt:
        if args.debug:
            raise
        print(f"ogk {args.command}: interrupted", file=sys.stderr)
        return 130


if __name__ == "__main__":
    sys.exit(main())
