"""`ogk run SCENARIO [...]`: one flight, case or transfer of the scenario's family, with plots
(`ogk run SCENARIO --help` lists the family's options). The older per-law verbs (`ogk cases`,
`ogk nmpc`, `ogk blt`) are aliases of it."""
from __future__ import annotations

from typing import Any

from ogk.cli.scenario_command import register_scenario_command


def register(sub: Any) -> None:
    register_scenario_command(sub, "run", "one flight, case or transfer of a scenario, with plots")
