"""The family contract: what a mission family gives the campaign engine (docs/adding-a-mission.md).

A family is a module under ogk.missions (found by ogk.missions.registry from the scenario's
`mission = "..."`) that defines `FAMILY`, an object with

  name: str, laws: tuple[str, ...]          the family and the guidance laws it flies
  load(header) -> scenario                  the typed scenario (every bad key: OgkInputError)
  add_campaign_arguments(parser)            the family's own `ogk mc` options (the engine adds
                                            --runs --seed --workers --json --plots ...)
  plan(header, options) -> CampaignPlan     its ground products made or checked (provenance
                                            directory), and how to fly one run

and the campaign plan says everything the engine needs and nothing of the physics:

  fly(run_ids, run_seeds) -> [record]      flies a chunk of runs; run i draws only from
                                            ogk.sil.seeds.run_generator(run_seeds[i]); a record is
                                            flat: {name: number | str | bool | None}, timing keys
                                            under "timing." (they are not part of a replay check)
  judge(record) -> reason                   "" or why the run fails the scenario's [acceptance]
  quantities                                record keys summarised (mean, std, worst run)
  paper(records) -> dict | None             the paper's columns beside ours, when the scenario has them
  detail(run_id, run_seed, plots_dir)       one run again with its time histories and plots
  target, target_bounds, target_why         where the flight software runs; for "m7" the bound of
                                            each quantity against the host on the same draws
  dispersions                               the scenario's [dispersions] as the family applies them
                                            (ogk.sil.dispersion_check.Declaration): each record
                                            carries disp.<key>, checked after the campaign
  draw(run_ids, run_seeds) -> [record]      optional: the disp.* keys of runs without flying them,
                                            by the code the flight's records come from
  classify(record) -> str                  optional: the class of a failed run (default: its reason
                                            without numbers, ogk.sil.robustness.failure_class)
  lost(record) -> reason                    optional: why a run that passed the acceptance is still a
                                            lost flight (the binary family: its corrector did not converge)
  solve_failures(record) -> [class]         optional: each failed solve of the run (default: the
                                            record's `failed_solves` count, unclassified)

A family that flies on the target lists it in `targets` (("host", "m7")) and reads
options["target"] (absent: "host").

`options` is JSON: everything a run depends on besides its id and seed. It is the run log's key,
it is written into the campaign envelope, and `ogk replay` rebuilds the plan from it.
"""
from __future__ import annotations

import dataclasses
from collections.abc import Callable, Mapping, Sequence
from pathlib import Path
from typing import Any, Protocol

import numpy as np
from numpy.typing import NDArray

Record = dict[str, Any]
ChunkFlight = Callable[[NDArray[np.int64], NDArray[np.uint64]], Sequence[Record]]


@dataclasses.dataclass(frozen=True)
class Detail:
    """One run flown again with its histories: the record and the files written (plots, CSV)."""

    record: Record
    files: tuple[Path, ...] = ()


@dataclasses.dataclass
class CampaignPlan:
    """A family's campaign, ready for the engine (module doc)."""

    family: str
    law: str
    mission: str                      #: the scenario's name
    scenario_path: Path
    scenario_sha256: str
    options: dict[str, Any]           #: JSON; with the seed, all a run depends on
    products: dict[str, str]          #: ground product -> SHA-256 (tables, nominal, configuration)
    fly: ChunkFlight
    judge: Callable[[Record], str]
    quantities: tuple[str, ...]
    paper: Callable[[Sequence[Record]], dict[str, Any] | None] | None = None
    detail: Callable[[int, int, Path | None], Detail] | None = None
    max_runs: int | None = None       #: a campaign over a fixed list (e.g. the paper's cases)
    acceptance: dict[str, Any] = dataclasses.field(default_factory=dict)  #: as the report states it
    watchdog_per_run_s: float = 2.0   #: default watchdog allowance of one run [s]
    base: Any = None                  #: family-private (the report's inputs); never pickled
    #: where the flight software runs (ogk.sil.pil.TARGETS): "host" (the SIL) or "m7" (the flight
    #: program on the emulated Cortex-M7, whose records carry pil.<entry>.* keys)
    target: str = "host"
    #: a target campaign's largest allowed |host - target| per quantity on the same draws, and why
    #: they differ at all (docs/pil.md, "Host vs target")
    target_bounds: dict[str, float] = dataclasses.field(default_factory=dict)
    target_why: str = ""
    #: the scenario's [dispersions] and how each key is applied (ogk.sil.dispersion_check)
    dispersions: Any = None
    #: the disp.* keys of a chunk of runs drawn without flying (None: the family cannot)
    draw: ChunkFlight | None = None
    #: the class of a failed run (None: ogk.sil.robustness.failure_class of its reason)
    classify: Callable[[Record], str] | None = None
    #: "" or why a run that passed the acceptance is still a lost flight (ogk.sil.robustness)
    lost: Callable[[Record], str] | None = None
    #: the class of each failed solve of a run (None: the record's `failed_solves` count, if any)
    solve_failures: Callable[[Record], Sequence[str]] | None = None

    def key(self, seed: int) -> dict[str, Any]:
        """What the runs depend on besides their ids: the run log's key."""
        return {"family": self.family, "law": self.law, "scenario_sha256": self.scenario_sha256,
                "options": self.options, "products": self.products, "seed": int(seed)}


class MissionFamily(Protocol):
    """What every family's `FAMILY` object provides (module doc)."""

    name: str
    laws: tuple[str, ...]

    def load(self, header: Any) -> Any: ...

    def add_campaign_arguments(self, parser: Any) -> None: ...

    def plan(self, header: Any, options: Mapping[str, Any]) -> CampaignPlan: ...


def per_run(fly_one: Callable[[int, int], Record]) -> ChunkFlight:
    """A chunk flight from a one-run flight `fly_one(run_id, run_seed) -> record`."""
    def fly(run_ids: NDArray[np.int64], run_seeds: NDArray[np.uint64]) -> list[Record]:
        return [fly_one(int(i), int(s)) for i, s in zip(run_ids, run_seeds)]
    return fly
