"""`ogk blt SCENARIO --transfer NAME --json FILE [--plots DIR]`: one BLT transfer of a binary-asteroid
scenario (Xiong & Wang): the ground's initial guess, the flight kernel's NRPC in the realistic model and the
independent DOP853 re-propagation; prints the paper's figures beside it, writes the JSON, optionally PNG
figures; exits 1 when the transfer did not converge, 2 on bad input."""
from __future__ import annotations

from typing import Any

from ogk.cli.scenario_command import register_scenario_command


def register(sub: Any) -> None:
    register_scenario_command(sub, "blt", "one BLT transfer of a binary-asteroid scenario (NRPC)", listed=False)
