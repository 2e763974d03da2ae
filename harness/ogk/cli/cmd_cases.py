"""`ogk cases SCENARIO ...`: the guidance law on the scenario's perturbation cases (for the MPSP
family: one case of Tables 3-6 of Wang & Topputo, or all of them with --paper-tables)."""
from __future__ import annotations

from typing import Any

from ogk.cli.scenario_command import register_scenario_command


def register(sub: Any) -> None:
    register_scenario_command(sub, "cases", "perturbation cases of a scenario (MPSP family)", listed=False)
