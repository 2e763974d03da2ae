"""`ogk tables SCENARIO [--out DIR]`: the ground products of a scenario, made by its mission family --
binary table files (CRC) with their manifest, the generated C table image, and the flight
configuration header (the kernel configs the SIL flies, as const C99 initialisers).

  ogk tables leo-geo      orbit injection: nominal, VTD-NOG bundle (.ogkt + const C image),
                          c/*_flight_config.h (ogk_nog_config_t, ogk_cpd_config_t), manifest.json
  ogk tables apophis      low-thrust transfer: c/*_flight_config.h (ogk_mpsp_config_t + nominal weights)

Default DIR: build/tables/<scenario name>-<first 12 hex of its SHA-256> (docs/design/architecture.md).
--precision single: the products of a float flight build (OGK_REAL_SINGLE=1, e.g. the Cortex-M4F): F32
table files and image, the C written for a float kernel; default DIR <...>-single (docs/precision.md).
"""
from __future__ import annotations

from typing import Any

from ogk.cli.scenario_command import register_scenario_command


def register(sub: Any) -> None:
    register_scenario_command(sub, "tables", "ground tables and flight configuration of a scenario")
