"""The `ogk` command. Each subcommand lives in its own module (ogk/cmd_<name>.py)
exposing `register(subparsers)`, which adds its parser and sets `func`
(args -> exit code). To add one, write the module and list it in SUBCOMMANDS.
Modules import the kernel bindings inside `func`, so `ogk --help` works before
`make ffi`."""
from __future__ import annotations

import argparse
import importlib
import sys
from collections.abc import Sequence

SUBCOMMANDS: tuple[str, ...] = (
    "ogk.cli.cmd_version",
    "ogk.cli.cmd_demo",
    "ogk.cli.cmd_tables",
    "ogk.cli.cmd_mc",
    "ogk.cli.cmd_mpsp",
)


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="ogk",
        description="ogk SIL harness and ground tools (kernel bindings, demos, campaigns).",
    )
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
    return int(func(args))


if __name__ == "__main__":
    sys.exit(main())
