"""Orbit-injection campaigns of the physics tests, with a guidance and a scenario of their own (a
12 s open-loop burn, a faulty guidance, opened tolerances): the family's plan
(`OrbitInjectionFamily.plan_flights`, what `plan` builds from the command's options) flown by the
campaign engine, and the family's `CampaignResult` of the records (`campaign_result`, the
histories of the first `settings.history_runs` runs flown again by the plan's own chunk flight).
`ogk mc` goes through `FAMILY.plan`; only these tests inject a guidance."""
from __future__ import annotations

import dataclasses
from collections.abc import Sequence
from typing import Any

import numpy as np
from ogk_host.orbit_injection.scenario import OrbitInjectionScenario

from ogk.missions.orbit_injection.dispersions import DispersionSwitches
from ogk.missions.orbit_injection.family import FAMILY
from ogk.missions.orbit_injection.flights import CampaignResult
from ogk.missions.orbit_injection.guidance import GuidanceFactory, NominalOpenLoopGuidance
from ogk.missions.orbit_injection.sil import SilSettings
from ogk.sil.engine import fly_campaign


def fly(scenario: OrbitInjectionScenario, runs: int, seed: int, workers: int = 1, *,
        dispersions: bool | DispersionSwitches = True, truth: str = "6dof",
        guidance_factory: GuidanceFactory = NominalOpenLoopGuidance, guidance_name: str = "nominal",
        settings: SilSettings | None = None, run_ids: Sequence[int] | None = None,
        chunks: int | None = None, tables: Any = None, **engine: Any) -> CampaignResult:
    """`runs` runs of `scenario` (or the given `run_ids`) on `workers` processes in `chunks` chunks;
    `engine`: fly_campaign's watchdog, run_log, resume, chunk_runs."""
    switches = dispersions if isinstance(dispersions, DispersionSwitches) else (
        DispersionSwitches() if dispersions else DispersionSwitches.none())
    settings = dataclasses.replace(settings or SilSettings(), truth=truth)
    plan = FAMILY.plan_flights(scenario, scenario.path, "vtd-nog", settings, switches,
                               guidance_factory, guidance_name, tables, settings.history_runs)
    flown = fly_campaign(plan, runs, seed, workers, run_ids=run_ids, chunks=chunks,
                         progress=False, **engine)
    ids = np.asarray(flown.run_ids, dtype=np.int64)
    return FAMILY.campaign_result(plan, flown.records, flown,
                                  history_ids=ids[ids < settings.history_runs])
