"""Mission families by the name a scenario gives (`mission = "..."`), imported on first use.

A family is a package ogk.missions.<family> with
  family.py   FAMILY: the family contract of the campaign engine (ogk.sil.family): `ogk mc`,
              `ogk replay`, `ogk report` go through it, the same for every family;
  adapter.py  LAWS and the family's other verbs:
                tables(header, args) -> int                   `ogk tables SCENARIO`
                add_run_arguments(parser); run(header, args)   `ogk run SCENARIO ...` (one flight,
                                                               case or transfer, with plots)
              and the older per-law spellings kept as aliases of `ogk run` (cases, nmpc, blt).

A new family is one package plus one line here (docs/adding-a-mission.md); a new mission of a
known family is one TOML file and nothing else.
"""
from __future__ import annotations

import importlib
from types import ModuleType
from typing import Any

from ogk_bindings.errors import OgkInputError
from ogk_host.scenario_file import ScenarioHeader

PACKAGES: dict[str, str] = {
    "orbit-injection": "ogk.missions.orbit_injection",
    "low-thrust-transfer": "ogk.missions.low_thrust_transfer",
    "low-thrust-rendezvous": "ogk.missions.rendezvous",
    "binary-asteroid": "ogk.missions.binary",
}
FAMILIES: dict[str, str] = {name: f"{pkg}.adapter" for name, pkg in PACKAGES.items()}
#: the verbs every family has through its adapter; older spellings are aliases of `run`
VERBS = ("tables", "run", "cases", "nmpc", "blt")


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
        have = [c for c in VERBS if callable(getattr(adapter, c, None))]
        raise OgkInputError(f"family {header.mission!r} has no `ogk {name}` (it has: "
                            f"{', '.join('ogk ' + c for c in have)})", path=header.path)
    return adapter


def family_named(name: str) -> Any:
    """The campaign contract (FAMILY) of a family by its name."""
    pkg = PACKAGES.get(name)
    if pkg is None:
        raise OgkInputError(f"unknown mission family {name!r} (known: {', '.join(sorted(PACKAGES))})",
                            key="family")
    return importlib.import_module(f"{pkg}.family").FAMILY


def campaign_family(header: ScenarioHeader) -> Any:
    """The campaign contract of the scenario's family, after checking its law."""
    family(header)
    return family_named(header.mission)
