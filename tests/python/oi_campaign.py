"""Orbit-injection campaigns of the physics tests, with a guidance and a scenario of their own (a
12 s open-loop burn, a faulty guidance, opened tolerances): the family's plan builder
(`flights.campaign_plan`, what `OrbitInjectionFamily.plan` returns) flown by the campaign engine,
assembled into the family's `CampaignResult` with the histories of the first
`settings.history_runs` runs. `ogk mc` goes through `FAMILY.plan`; only these tests inject a
guidance."""
from __future__ import annotations

import dataclasses
from collections.abc import Sequence
from typing import Any

import numpy as np
from ogk_host.orbit_injection import derive
from ogk_host.orbit_injection.scenario import OrbitInjectionScenario

from ogk.missions.orbit_injection.dispersions import DispersionSwitches
from ogk.missions.orbit_injection.flights import CampaignResult, _assemble, _Job, campaign_plan
from ogk.missions.orbit_injection.guidance import GuidanceFactory, NominalOpenLoopGuidance
from ogk.missions.orbit_injection.nominal_ref import nominal_reference
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
    ref = nominal_reference(scenario)
    scenario = derive.resolve(scenario, ref.tf_s)          # what scales with the burn
    plan = campaign_plan(scenario, ref, switches, settings, guidance_factory, guidance_name,
                         tables, scenario.path, "vtd-nog")
    flown = fly_campaign(plan, runs, seed, workers, run_ids=run_ids, chunks=chunks,
                         progress=False, **engine)
    draws, errors, rates, failure = _assemble(flown.records)
    history, truth_steps = None, 0
    ids = np.asarray(flown.run_ids, dtype=np.int64)
    shown = ids[ids < settings.history_runs]
    if shown.size:      # the plotted runs again, with histories, in this process
        res = _Job(scenario, ref, int(seed), switches, settings, guidance_factory)(shown)[1]
        history, truth_steps = res.history, int(res.truth_steps)
    return CampaignResult(scenario=scenario, seed=int(seed), truth=truth, guidance=guidance_name,
                          switches=switches, settings=settings, nominal_tf_s=ref.tf_s, draws=draws,
                          errors=errors, max_rates=rates, failure=failure, history=history,
                          wall_time_s=flown.wall_s, workers=flown.workers,
                          flight_cpu_s=flown.cpu_s, truth_steps=truth_steps,
                          scenario_path=str(scenario.path), scenario_sha256=plan.scenario_sha256,
                          resumed_runs=flown.resumed_runs, tables=tables, engine_result=flown)
