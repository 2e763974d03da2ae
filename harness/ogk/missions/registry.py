"""Mission families by the name a scenario gives (`mission = "..."`), imported on first use.

A family is a module (an *adapter*) that may define any of:

  LAWS: tuple[str, ...]                                  guidance laws it flies ([guidance] law)
  tables(header, args) -> int                            `ogk tables SCENARIO`
  add_mc_arguments(parser); mc(header, args) -> int      `ogk mc SCENARIO ...`
  add_cases_arguments(parser); cases(header, args) -> int  `ogk cases SCENARIO ...`
  add_nmpc_arguments(parser); nmpc(header, args) -> int    `ogk nmpc SCENARIO ...`
  add_blt_arguments(parser); blt(header, args) -> int      `ogk blt SCENARIO ...`

A new family is one adapter module plus one line here (docs/adding-a-mission.md); a new mission of a
known family is one TOML file and nothing else.
"""
from __future__ import annotations

import importlib
from types import ModuleType

from ogk_bindings.errors import OgkInputError
from ogk_host.scenario_file import ScenarioHeader

FAMILIES: dict[str, str] = {
    "orbit-injection": "ogk.missions.orbit_injection.adapter",
    "low-thrust-transfer": "ogk.missions.low_thrust_transfer.adapter",
    "low-thrust-rendezvous": "ogk.missions.rendezvous.adapter",
    "binary-asteroid": "ogk.missions.binary.adapter",
}


def family(header: ScenarioHeader) -> ModuleType:
    """The adapter of the scenario's family, after checking that it flies the scenario's law."""
    module_name = FAMILIES.get(header.mission)
    if module_name is None:
        raise OgkInputError(f"unknown mission family {header.mission!r} (known: "
                            f"{', '.join(sorted(FAMILIES))})", path=header.path, key="mission")
    adapter = importlib.import_module(module_name)
    laws = getattr(adapter, "LAWS", ())
    if header.law not in laws:
        raise OgkInputError(f"family {header.mission!r} flies {', '.join(laws)}, not {header.law!r}",
                            path=header.path, key="guidance.law")
    return adapter


def command(header: ScenarioHeader, name: str) -> ModuleType:
    """The adapter, checked to implement command `name` (tables, mc, cases)."""
    adapter = family(header)
    if not callable(getattr(adapter, name, None)):
        have = [c for c in ("tables", "mc", "cases", "nmpc", "blt") if callable(getattr(adapter, c, None))]
        raise OgkInputError(f"family {header.mission!r} has no `ogk {name}` (it has: "
                            f"{', '.join('ogk ' + c for c in have)})", path=header.path)
    return adapter
