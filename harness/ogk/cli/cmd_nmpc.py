"""`ogk nmpc SCENARIO --strategy {snns,cncn} [--perturbed] [--seed S] [--solver {kernel,ipopt}] --json FILE
[--plots DIR]`: the receding-horizon NMPC closed loop of a rendezvous scenario (Starek & Kolmanovsky 2012,
sec. 2.3; `ogk nmpc rendezvous_nep_min_time --help` lists the options). Prints the paper's Table I or II
beside the run, writes the JSON, optionally PNG figures; exits 1 when the flight did not reach Mars, 2 on
bad input."""
from __future__ import annotations

from typing import Any

from ogk.cli.scenario_command import register_scenario_command


def register(sub: Any) -> None:
    register_scenario_command(sub, "nmpc", "receding-horizon NMPC closed loop of a rendezvous scenario", listed=False)
