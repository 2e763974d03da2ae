"""The family interface: every verb a mission family offers, on one protocol (docs/guides/campaigns.md,
docs/guides/adding-a-mission.md).

A family is one class deriving from `FamilyDefaults` and implementing `MissionFamily`, whose one
instance `FAMILY` (in ogk.missions.<family>.family) ogk.missions.registry finds from the scenario's
`mission = "..."`. Its verbs:

  name, laws, campaign_doc, targets, fixed_lists, run_aliases, has_tables
                                            what it is, what it flies, where; `ogk run`'s old
                                            names; whether it makes ground tables
  load(header) -> scenario                  the typed scenario (every bad key: OgkInputError)
  default_runs(header) -> int | None        the runs the scenario states (None: --runs required)
  add_campaign_arguments(parser)            the family's own `ogk mc` options (the engine adds
                                            --runs --seed --workers --json --plots ...)
  plan(header, options) -> CampaignPlan     its ground products made or checked (provenance
                                            directory), and how to fly one run
  report(flown) -> (text, keys)             the campaign's report and its envelope keys
  plots(flown, dir) -> [path]               the campaign's PNGs
  add_tables_arguments, tables(header, args)   `ogk tables SCENARIO`
  add_run_arguments, run(header, args)         `ogk run SCENARIO`: one flight with its plots
  flight_config(plan, dir), flight_program(plan, target), target_job(plan, program),
  target_bounds(plan), on_target(plan, target)
                                            the plan's flight build (its generated C), its
                                            flight program, the plan flown by it on a target

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

A family that flies on a target lists it in `targets` (("host", "m7", "sparc")), and its plan
reads options["target"] (absent: "host") and calls `on_target`.

`options` is JSON: everything a run depends on besides its id and seed. It is the run log's key,
it is written into the campaign envelope, and `ogk replay` rebuilds the plan from it.
"""
from __future__ import annotations

import abc
import argparse
import dataclasses
from collections.abc import Callable, Mapping, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any, Protocol, runtime_checkable

import numpy as np
from numpy.typing import NDArray
from ogk_bindings.errors import OgkInputError
from ogk_host.scenario_file import ScenarioHeader

if TYPE_CHECKING:
    from .pil import FlightProgram

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
    #: they differ at all (docs/guides/pil.md, "Host vs target")
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


@dataclasses.dataclass
class Flown:
    """What a campaign produced: every run's record (run-id order) and how it was flown."""

    plan: CampaignPlan
    seed: int
    records: list[Record]
    workers: int
    wall_s: float
    cpu_s: float
    resumed_runs: int

    @property
    def run_ids(self) -> list[int]:
        return [int(r["run_id"]) for r in self.records]

    def failures(self) -> list[dict[str, Any]]:
        """[{run_id, reason}] of every failed run."""
        return [{"run_id": int(r["run_id"]), "reason": r["failure"]} for r in self.records
                if r.get("failure")]



@runtime_checkable
class MissionFamily(Protocol):
    """Every verb of a mission family: the one interface through which the CLI (`ogk tables`,
    `ogk run`, `ogk mc`, `ogk replay`, `ogk report`) and the engine reach a family. A family is one
    class (`FamilyDefaults` gives the optional verbs their defaults) and one line of
    ogk.missions.registry. mypy checks every family against it (tests/typecheck/families.py, `make
    test-imports`), tests/python/test_family_protocol.py its signatures and capabilities."""

    # what it is and what it has (read-only: a family states them as class attributes)
    @property
    def name(self) -> str:
        """`mission = "..."` of the family's scenarios."""

    @property
    def laws(self) -> tuple[str, ...]:
        """The guidance laws it flies ([guidance] law)."""

    @property
    def campaign_doc(self) -> str:
        """One sentence for `ogk mc SCENARIO --help`: what a run is."""

    @property
    def targets(self) -> tuple[str, ...]:
        """Where its flight software runs (ogk.sil.pil.TARGETS)."""

    @property
    def fixed_lists(self) -> bool:
        """A campaign may be a fixed list (then --runs may be omitted)."""

    @property
    def run_aliases(self) -> tuple[str, ...]:
        """Older spellings of `ogk run` for this family (`ogk nmpc`)."""

    @property
    def has_tables(self) -> bool:
        """It makes ground tables (`ogk tables`)."""

    # its verbs

    def load(self, header: ScenarioHeader) -> Any:
        """The typed scenario (every bad key: one OgkInputError line)."""

    def default_runs(self, header: ScenarioHeader) -> int | None:
        """The number of runs the scenario states, or None (then --runs is required)."""

    def add_campaign_arguments(self, parser: argparse.ArgumentParser) -> None:
        """The family's own `ogk mc` options (the engine adds its own first)."""

    def plan(self, header: ScenarioHeader, options: Mapping[str, Any]) -> CampaignPlan:
        """Ground products made or checked; everything needed to fly one run (on
        options["target"] when it is not the host)."""

    def report(self, flown: Flown) -> tuple[str, dict[str, Any]]:
        """The campaign's report and the JSON keys the family adds to the envelope."""

    def plots(self, flown: Flown, out_dir: Path) -> list[Path]:
        """The campaign's PNGs (none by default)."""

    def add_tables_arguments(self, parser: argparse.ArgumentParser) -> None:
        """The options of `ogk tables SCENARIO`."""

    def tables(self, header: ScenarioHeader, args: argparse.Namespace) -> int:
        """`ogk tables SCENARIO`: the ground products into the scenario's provenance directory."""

    def add_run_arguments(self, parser: argparse.ArgumentParser) -> None:
        """The options of `ogk run SCENARIO`."""

    def run(self, header: ScenarioHeader, args: argparse.Namespace) -> int:
        """`ogk run SCENARIO`: one flight, case or transfer with its plots; the exit code."""

    def flight_config(self, plan: CampaignPlan, out_dir: Path) -> list[Path]:
        """The generated C the plan's flight build compiles (a table image where the family has
        one, the const configuration headers) written into out_dir/c; the files written."""

    def flight_program(self, plan: CampaignPlan, target: str) -> FlightProgram:
        """The plan's flight program for target, built on its flight_config."""

    def target_job(self, plan: CampaignPlan, program: FlightProgram) -> ChunkFlight:
        """The plan's chunk flight with the flight software on `program` (ogk.sil.pil)."""

    def target_bounds(self, plan: CampaignPlan) -> tuple[dict[str, float], str]:
        """The largest allowed |host - target| per quantity on the same draws, and why they differ
        at all (docs/guides/pil.md, "Host vs target")."""

    def on_target(self, plan: CampaignPlan, target: str) -> None:
        """The plan flown by its flight program on `target` (flight_program, target_job)."""


class FamilyDefaults(abc.ABC):
    """MissionFamily as a base class: the verbs every family has are abstract (a family class that
    lacks one cannot be made), the optional ones have their defaults, which a family overrides
    when it has the capability. A verb a family does not have says so in one OgkInputError line."""

    name: str = ""
    laws: tuple[str, ...] = ()
    campaign_doc: str = ""
    targets: tuple[str, ...] = ("host",)
    fixed_lists: bool = False
    run_aliases: tuple[str, ...] = ()
    has_tables: bool = False
    #: a target campaign's watchdog allowance per run [s]
    target_watchdog_per_run_s: float = 60.0

    @abc.abstractmethod
    def load(self, header: ScenarioHeader) -> Any: ...

    @abc.abstractmethod
    def add_campaign_arguments(self, parser: argparse.ArgumentParser) -> None: ...

    @abc.abstractmethod
    def plan(self, header: ScenarioHeader, options: Mapping[str, Any]) -> CampaignPlan: ...

    @abc.abstractmethod
    def report(self, flown: Flown) -> tuple[str, dict[str, Any]]: ...

    @abc.abstractmethod
    def add_run_arguments(self, parser: argparse.ArgumentParser) -> None: ...

    @abc.abstractmethod
    def run(self, header: ScenarioHeader, args: argparse.Namespace) -> int: ...

    def default_runs(self, header: ScenarioHeader) -> int | None:
        return None

    def plots(self, flown: Flown, out_dir: Path) -> list[Path]:
        return []

    def add_tables_arguments(self, parser: argparse.ArgumentParser) -> None:
        return None

    def tables(self, header: ScenarioHeader, args: argparse.Namespace) -> int:
        """`ogk tables SCENARIO`: none (has_tables is False)."""
        raise OgkInputError(f"family {self.name!r} has no `ogk tables` (it makes no ground tables)",
                            path=header.path)

    def flight_config(self, plan: CampaignPlan, out_dir: Path) -> list[Path]:
        raise OgkInputError(f"the {self.name} family has no flight build", key="--target")

    def flight_program(self, plan: CampaignPlan, target: str) -> FlightProgram:
        raise OgkInputError(f"the {self.name} family has no flight program for target {target}",
                            key="--target")

    def target_job(self, plan: CampaignPlan, program: FlightProgram) -> ChunkFlight:
        raise OgkInputError(f"the {self.name} family flies no target job", key="--target")

    def target_bounds(self, plan: CampaignPlan) -> tuple[dict[str, float], str]:
        return {}, ""

    def on_target(self, plan: CampaignPlan, target: str) -> None:
        """The plan's flight replaced by the target job on the flight program; the plan then says
        so (target, options, the program's SHA-256 among the products, bounds, watchdog)."""
        from .pil import target_why
        from .pil_build import file_sha256

        program = self.flight_program(plan, target)
        plan.fly = self.target_job(plan, program)
        plan.target = target
        plan.options = {**plan.options, "target": target}     # `ogk replay` flies it there
        plan.products = {**plan.products, "flight_program": file_sha256(program.elf)}
        bounds, why = self.target_bounds(plan)
        plan.target_bounds = bounds
        plan.target_why = target_why(target, why)
        plan.watchdog_per_run_s = self.target_watchdog_per_run_s


def per_run(fly_one: Callable[[int, int], Record]) -> ChunkFlight:
    """A chunk flight from a one-run flight `fly_one(run_id, run_seed) -> record`."""
    def fly(run_ids: NDArray[np.int64], run_seeds: NDArray[np.uint64]) -> list[Record]:
        return [fly_one(int(i), int(s)) for i, s in zip(run_ids, run_seeds)]
    return fly
