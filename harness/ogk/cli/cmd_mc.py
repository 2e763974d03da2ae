"""`ogk mc SCENARIO ...`: a software-in-the-loop Monte Carlo campaign of the scenario's mission
family (`ogk mc leo-geo --help` lists the options of the orbit-injection family). Prints the report
(side by side with the paper when the scenario carries its results), writes the JSON, optionally PNG
plots; exits 1 when a run failed (the criterion is in docs/guides/sil.md), 2 on bad input."""
from __future__ import annotations

from typing import Any

from ogk.cli.scenario_command import register_scenario_command


def register(sub: Any) -> None:
    register_scenario_command(sub, "mc", "Monte Carlo campaign of a scenario (software in the loop)")
