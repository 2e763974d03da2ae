"""The shape every scenario command shares: `ogk COMMAND SCENARIO [family options]`.

The first parser takes the scenario (a path or a name under scenarios/); its family
(ogk.sil.family.MissionFamily, found by ogk.missions.registry) then parses the rest with the options
it declares, so `ogk mc leo-geo --help` lists that family's
options. Bad input of any kind is an OgkInputError: one line, exit code 2 (ogk.cli.main).
"""
from __future__ import annotations

import argparse
from collections.abc import Sequence
from typing import Any

from ogk_bindings.errors import OgkInputError
from ogk_host.scenario_file import ScenarioHeader, read_header, resolve_scenario

from ogk.missions import registry
from ogk.sil import precision
from ogk.sil.family import MissionFamily


def register_scenario_command(sub: Any, name: str, help_text: str, listed: bool = True) -> None:
    """`ogk NAME SCENARIO ...`; listed=False: an older spelling that works but `ogk --help` does not
    list (argparse lists a subcommand only when it is given a help text)."""
    listing = {"help": help_text} if listed else {}
    p = sub.add_parser(name, **listing, add_help=False,
                       description=f"{help_text}. SCENARIO is a .toml path or a name under "
                                   f"scenarios/ (leo-geo, apophis, ...); `ogk {name} SCENARIO "
                                   "--help` lists the options of its mission family.")
    # -h before any SCENARIO is this parser's (`ogk tables --help`: this help, exit 0); after it, the
    # family's (`ogk tables leo-geo --help`: `rest` takes it).
    p.add_argument("-h", "--help", action="store_true", dest="show_help",
                   help="show this help; after SCENARIO, the options of its mission family")
    p.add_argument("scenario", metavar="SCENARIO", nargs="?",
                   help="a .toml path or a name under scenarios/")
    p.add_argument("rest", nargs=argparse.REMAINDER, help=argparse.SUPPRESS)

    def run(args: argparse.Namespace) -> int:
        if args.show_help:   # `ogk tables --help [SCENARIO]`
            if args.scenario is None:
                return run_scenario_command(name, "--help", [], p)
            return run_scenario_command(name, args.scenario, ["--help", *args.rest], p)
        return run_scenario_command(name, args.scenario, args.rest, p)

    p.set_defaults(func=run)


def run_scenario_command(name: str, scenario: str | None, rest: Sequence[str],
                         top: argparse.ArgumentParser | None = None,
                         overrides: dict[str, Any] | None = None) -> int:
    if scenario is None or scenario in ("-h", "--help"):
        if top is not None:
            top.print_help()
        return 0 if scenario else 2
    rest = list(rest)
    # `--scenario FILE` (the older spelling `ogk mc leo-geo --scenario FILE`) names the file flown.
    if "--scenario" in rest:
        i = rest.index("--scenario")
        if i + 1 >= len(rest):
            raise OgkInputError("needs a file", key="--scenario")
        scenario = rest[i + 1]
        del rest[i:i + 2]
    # `--precision single` (ogk mc, ogk run): the kernel's real type, chosen before the family's modules
    # import the bindings (ogk.sil.precision); `ogk mc`'s parser declares the option, the others' do not
    chosen = precision.take(rest, remove=name != "mc")
    if chosen is not None and name != "tables":
        precision.select(chosen)
    # `ogk tables --precision single`: the ground products of a float flight build (F32 tables, C for a
    # float kernel); the ground tools themselves compute in double
    products = chosen or precision.DEFAULT
    if products not in precision.CHOICES:
        raise OgkInputError(f"expected one of {', '.join(precision.CHOICES)}, got {products!r}",
                            key=precision.OPTION)
    header = read_header(resolve_scenario(scenario))
    fam = registry.family(header)
    if name == "mc":
        return _campaign(fam, header, scenario, rest, overrides)
    if name == "tables" and fam.has_tables:
        add_arguments, verb = fam.add_tables_arguments, fam.tables
    elif name == "run" or name in fam.run_aliases:
        add_arguments, verb = fam.add_run_arguments, fam.run
    else:
        have = [*(["ogk tables"] if fam.has_tables else []), "ogk run",
                *(f"ogk {a}" for a in fam.run_aliases), "ogk mc"]
        raise OgkInputError(f"family {header.mission!r} has no `ogk {name}` (it has: "
                            f"{', '.join(have)})", path=header.path)
    parser = argparse.ArgumentParser(prog=f"ogk {name} {scenario}",
                                     description=(verb.__doc__ or "").strip().splitlines()[0])
    add_arguments(parser)
    args = parser.parse_args(rest)
    for key, value in (overrides or {}).items():
        setattr(args, key, value)
    if chosen is not None and chosen != precision.DEFAULT:
        print(f"precision: {chosen} (the kernel's ogk_real_t is float: OGK_REAL_SINGLE=1)")
    if name == "tables":
        from ogk_host.cgen import generated_precision
        args.precision = products
        with generated_precision(products):
            return int(verb(header, args))
    return int(verb(header, args))


def _campaign(fam: MissionFamily, header: ScenarioHeader, scenario: str, rest: Sequence[str],
              overrides: dict[str, Any] | None) -> int:
    """`ogk mc SCENARIO`: the engine's options, then the family's (ogk.sil.command)."""
    from ogk.sil import command
    args = command.parser_for(fam, f"ogk mc {scenario}", header).parse_args(rest)
    for key, value in (overrides or {}).items():
        setattr(args, key, value)
    return command.fly(fam, header, args)
