"""Mission families by the name a scenario gives (`mission = "..."`), imported on first use.

A family is a package ogk.missions.<family> whose family.py defines `FAMILY`: the one object that
implements every verb of ogk.sil.family.MissionFamily (`ogk tables`, `ogk run`, `ogk mc`,
`ogk replay`, `ogk report` all go through it, the same for every family). The older per-law
spellings of `ogk run` (`ogk cases`, `ogk nmpc`, `ogk blt`) are the family's `run_aliases`.

A new family is one class plus one line here (docs/guides/adding-a-mission.md); a new mission of a known
family is one TOML file and nothing else.
"""
from __future__ import annotations

import importlib

from ogk_bindings.errors import OgkInputError
from ogk_host.scenario_file import ScenarioHeader

from ogk.sil.family import MissionFamily

#: family name -> the module that defines its FAMILY
PACKAGES: dict[str, str] = {
    "orbit-injection": "ogk.missions.orbit_injection.family",
    "low-thrust-transfer": "ogk.missions.low_thrust_transfer.family",
    "low-thrust-rendezvous": "ogk.missions.rendezvous.family",
    "binary-asteroid": "ogk.missions.binary.family",
    "proximity-approach": "ogk.missions.proximity.family",
}


def family_named(name: str) -> MissionFamily:
    """The family of that name."""
    module = PACKAGES.get(name)
    if module is None:
        raise OgkInputError(f"unknown mission family {name!r} (known: {', '.join(sorted(PACKAGES))})",
                            key="family")
    fam: MissionFamily = importlib.import_module(module).FAMILY
    return fam


def family(header: ScenarioHeader) -> MissionFamily:
    """The scenario's family, after checking that it flies the scenario's law."""
    if header.mission not in PACKAGES:
        raise OgkInputError(f"unknown mission family {header.mission!r} (known: "
                            f"{', '.join(sorted(PACKAGES))})", path=header.path, key="mission")
    fam = family_named(header.mission)
    if header.law not in fam.laws:
        raise OgkInputError(f"family {header.mission!r} flies {', '.join(fam.laws)}, "
                            f"not {header.law!r}", path=header.path, key="guidance.law")
    return fam
