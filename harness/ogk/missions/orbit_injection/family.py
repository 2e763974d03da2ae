"""The orbit-injection family (ogk.sil.family.MissionFamily): VTD-NOG + CPD (Pontani & Celani
2021). `ogk tables` makes the nominal and the gain tables (ground_tables.py); `ogk mc` is the SIL
Monte Carlo: run i is one dispersed flight (initial state, attitude, rates, thrust; dispersions.py)
drawn from its own stream, chunks of runs flown vectorised (flights._Job); `ogk run` is run 0 of
that campaign with its plots. Acceptance: the scenario's [acceptance] tolerances on the injection
errors, plus any kernel error or truth-model failure (flights.tolerances). On a target (m7, sparc)
the flight software is the scenario's flight program (pil.py).
"""
from __future__ import annotations

import argparse
import dataclasses
from collections.abc import Mapping
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
from ogk_bindings.errors import OgkInputError
from ogk_host.orbit_injection import derive
from ogk_host.orbit_injection.scenario import LAWS, OrbitInjectionScenario, load_scenario
from ogk_host.scenario_file import ScenarioHeader

from ogk.sil.engine import Flown, seeds_of
from ogk.sil.envelope import ENVELOPE_KEYS
from ogk.sil.family import CampaignPlan, ChunkFlight, Detail, FamilyDefaults
from ogk.sil.pil import FlightProgram

from .flights import CampaignResult, _assemble, _Job, _run_records, campaign_plan
from .dispersions import DispersionSwitches
from .guidance import GuidanceFactory
from .nominal_ref import resolved_with_reference
from .sil import SilSettings

if TYPE_CHECKING:
    from .nog_guidance import NogTables


def single_precision_bundle(blob: bytes) -> bytes:
    """The NOG table image `blob` (F64) for the single-precision kernel: the same table with every value
    rounded to the nearest binary32 (F32). The float kernel's loader accepts it as it is: its time
    columns are checked to 4 eps of t_f there (kernel/src/nog/nog.c, OGK_NOG_TF_CONSISTENCY)."""
    from ogk_host import tablefile

    t = tablefile.decode_table(blob)
    return tablefile.encode_table(t.kind, t.grid, t.data, precision="single")


@dataclasses.dataclass(frozen=True)
class _Base:
    scenario: OrbitInjectionScenario
    job: _Job                   #: the flight with its nominal, guidance factory and settings
    switches: DispersionSwitches
    settings: SilSettings
    guidance: str
    tables: Any
    history_runs: int


class OrbitInjectionFamily(FamilyDefaults):
    name = "orbit-injection"
    laws = LAWS
    targets = ("host", "m7", "sparc", "m4f")   #: m7 / sparc / m4f: port/cortex-m7/pil/oi_pil.c (pil.py)
    has_tables = True                   #: `ogk tables`: ground_tables.py
    target_watchdog_per_run_s = 60.0
    campaign_doc = ("dispersed flights of the kernel's VTD-NOG + CPD with the scenario's end-game "
                    "(6-DOF or point-mass truth), side by side with Tables 6-7 when the scenario "
                    "carries them")

    def load(self, header: ScenarioHeader) -> OrbitInjectionScenario:
        return load_scenario(header.path)

    def add_campaign_arguments(self, parser: argparse.ArgumentParser) -> None:
        parser.add_argument("--no-dispersions", action="store_true",
                       help="no dispersions: alignment errors only (Table 6 case)")
        parser.add_argument("--truth", choices=("6dof", "point-mass"), default="6dof")
        parser.add_argument("--guidance", choices=("nog", "nominal"), default="nog",
                       help="nog: kernel VTD-NOG; nominal: open-loop u*(t) (a reference, not guidance)")
        parser.add_argument("--tables", default=None, metavar="DIR",
                       help="VTD-NOG tables to fly (default: the scenario's own directory under "
                            "build/tables, generated when missing); checked against the scenario")
        parser.add_argument("--history-runs", type=int, default=50,
                       help="runs whose time histories are drawn with --plots (default 50)")
        parser.add_argument("--control-rate", type=float, default=50.0, help="attitude control rate [Hz]")
        parser.add_argument("--truth-substeps", type=int, default=1,
                       help="truth RK4 steps per control step (default 1: 20 ms)")
        parser.add_argument("--cpd-gains", choices=("printed", "rederived"), default=None,
                       help="CPD gain set (default: the scenario's flown set)")
        parser.add_argument("--cpd-pointing", choices=("body", "euler"), default="body",
                       help="CPD pitch/yaw error: body-axis (default) or eqs. 45-46 literally")
        parser.add_argument("--paper-end-game", action="store_true",
                       help="fly the paper's end-game (cut-off predicted at the samples, eq. 32; "
                            "Delta t_S throughout) instead of the scenario's [guidance.end_game]")

    def plan(self, header: ScenarioHeader, options: Mapping[str, Any]) -> CampaignPlan:
        from .guidance import NominalOpenLoopGuidance
        from .nog_guidance import KernelNogGuidance, prepare_tables

        opts = {"no_dispersions": False, "truth": "6dof", "guidance": "nog", "tables": None,
                "history_runs": 50, "control_rate": 50.0, "truth_substeps": 1, "cpd_gains": None,
                "cpd_pointing": "body", "paper_end_game": False, **dict(options)}
        rate = float(opts["control_rate"])
        if not rate > 0.0 or rate > 1.0e4:
            raise OgkInputError(f"must be in (0, 1e4] Hz, got {rate:g}", key="--control-rate")
        if int(opts["truth_substeps"]) < 1:
            raise OgkInputError(f"must be >= 1, got {opts['truth_substeps']}", key="--truth-substeps")
        if int(opts["history_runs"]) < 0:
            raise OgkInputError(f"must be >= 0, got {opts['history_runs']}", key="--history-runs")
        scn = self.load(header)
        if opts["guidance"] == "nog":
            tables = prepare_tables(scn, Path(opts["tables"]) if opts["tables"] else None)
            factory: Any = KernelNogGuidance.for_tables(tables)
            opts["tables"] = str(tables.directory)
        else:
            tables, factory = None, NominalOpenLoopGuidance
        settings = SilSettings(control_rate_hz=rate, truth_substeps=int(opts["truth_substeps"]),
                               cpd_gains=opts["cpd_gains"], cpd_pointing=str(opts["cpd_pointing"]),
                               truth=str(opts["truth"]),
                               # the open-loop reference flies no end-game (its cut-off is t_f*)
                               end_game=("paper" if opts["paper_end_game"]
                                         or opts["guidance"] == "nominal" else "scenario"))
        switches = DispersionSwitches.none() if opts["no_dispersions"] else DispersionSwitches()
        history_runs = int(opts.pop("history_runs"))    # what is drawn, not what is flown
        plan = self.plan_flights(scn, header.path, header.law, settings, switches, factory,
                                 str(opts["guidance"]), tables, history_runs, opts)
        if opts.get("target", "host") != "host":
            self.on_target(plan, str(opts["target"]))
        return plan

    def plan_flights(self, scn: OrbitInjectionScenario, scenario_path: Path | None, law: str,
                     settings: SilSettings, switches: DispersionSwitches, guidance: GuidanceFactory,
                     guidance_name: str, tables: "NogTables | None", history_runs: int = 0,
                     options: dict[str, Any] | None = None) -> CampaignPlan:
        """The campaign of `scn` as loaded (resolved here, once, against its nominal) flying
        `guidance`: what `plan` builds from the command's options, and what a physics test builds
        with a guidance or an in-memory scenario of its own (tests/python/oi_campaign.py); the
        engine flies either. `options`: the run key (default: the settings, flights.run_key)."""
        scn, ref = resolved_with_reference(scn)     # what scales with the burn
        if tables is not None and abs(tables.t_f_star_s - ref.tf_s) > 1e-6 * max(ref.tf_s, 1.0):
            raise OgkInputError(f"tables made for t_f* = {tables.t_f_star_s:.6f} s, the nominal is "
                                f"{ref.tf_s:.6f} s: regenerate them with `ogk tables`",
                                path=tables.directory)
        derive.warn_outside_envelope(scn, ref.tf_s)
        plan = campaign_plan(scn, ref, switches, settings, guidance, guidance_name, tables,
                             scenario_path, law, options)
        plan.base = _Base(scn, _Job(scn, ref, 0, switches, settings, guidance), switches, settings,
                          guidance_name, tables, history_runs)

        def detail(run_id: int, run_seed: int, plots: Path | None) -> Detail:
            res = self.campaign_result(plan, [], history_ids=np.array([run_id], dtype=np.int64),
                               run_seeds=np.array([run_seed], dtype=np.uint64))
            files = () if plots is None else tuple(self._write_plots(res, plots))
            return Detail({}, files)

        plan.detail = detail
        return plan

    # ------------------------------------------------------------------ ogk tables, ogk run
    def add_tables_arguments(self, parser: argparse.ArgumentParser) -> None:
        from .ground_tables import add_tables_arguments
        add_tables_arguments(parser)

    def tables(self, header: ScenarioHeader, args: argparse.Namespace) -> int:
        """`ogk tables SCENARIO`: nominal, VTD-NOG gain tables, C table image, flight configuration."""
        from .ground_tables import write_ground_tables
        return write_ground_tables(header, args)

    def add_run_arguments(self, parser: argparse.ArgumentParser) -> None:
        from ogk.sil.command import add_target_argument
        parser.add_argument("--seed", type=int, default=1, help="seed of the flight's draws (run 0 of a "
                       "campaign with this seed; default 1)")
        parser.add_argument("--json", required=True, metavar="FILE", help="the flight as a campaign of one")
        parser.add_argument("--plots", default=None, metavar="DIR", help="PNG plots of the flight")
        self.add_campaign_arguments(parser)
        add_target_argument(parser)

    def run(self, header: ScenarioHeader, args: argparse.Namespace) -> int:
        """`ogk run SCENARIO`: one dispersed flight (run 0 of `ogk mc` with the same seed)."""
        from ogk.sil import command
        for name, value in (("runs", 1), ("workers", 1), ("resume", False), ("chunk_runs", None),
                            ("watchdog_per_run", None)):
            setattr(args, name, value)
        return command.fly(self, header, args)

    # ------------------------------------------------------------------ on a target
    def flight_config(self, plan: CampaignPlan, out_dir: Path) -> list[Path]:
        """The table image of the tables flown and the configuration headers (flight_config.py)."""
        from ogk_host.cgen import current_precision, write_c_table

        from .flight_config import write_flight_config
        base: _Base = plan.base
        tables = base.tables
        blob, note = tables.bundle.read_bytes(), "The PIL flight program's table image (ogk_nog_table_view)."
        if current_precision() == "single":
            # a float kernel refuses an F64 table (OGK_E_TABLE_TYPE): the same table in binary32
            blob = single_precision_bundle(blob)
            note += " Binary32 (F32) for the single-precision kernel."
        image = write_c_table(blob, "ogk_nog_bundle", out_dir / "c", plan.scenario_path, note=note)
        return [*image, *write_flight_config(out_dir, base.scenario, plan.scenario_path,
                                             tables.bundle)]

    def flight_program(self, plan: CampaignPlan, target: str) -> FlightProgram:
        """The scenario's flight program for the tables the campaign flies (pil.py)."""
        from . import pil
        pil.check_target_settings(plan.base.settings, plan.options)
        return pil.flight_program(plan.base.tables, lambda out: self.flight_config(plan, out),
                                  target)

    def target_job(self, plan: CampaignPlan, program: FlightProgram) -> ChunkFlight:
        from . import pil
        job = dataclasses.replace(plan.base.job, settings=dataclasses.replace(
            plan.base.settings, history_runs=0))
        return pil.TargetJob(job, program)

    def target_bounds(self, plan: CampaignPlan) -> tuple[dict[str, float], str]:
        from . import pil
        return dict(pil.BOUNDS), pil.BOUNDS_WHY

    # ------------------------------------------------------------------ reports
    def campaign_result(self, plan: CampaignPlan, records: list[dict[str, Any]], flown: Flown | None = None,
                history_ids: np.ndarray | None = None,
                run_seeds: np.ndarray | None = None) -> CampaignResult:
        """The family's CampaignResult (report and plots) from the engine's records; the runs in
        `history_ids` flown again here with their histories."""
        base: _Base = plan.base
        history, truth_steps = None, 0
        if history_ids is not None and history_ids.size:
            settings = dataclasses.replace(base.settings, history_runs=int(history_ids.max()) + 1)
            job = dataclasses.replace(base.job, settings=settings)
            seed = 0 if flown is None else flown.seed
            draws_res = job(history_ids, seeds_of(seed, history_ids) if run_seeds is None
                            else run_seeds)
            history, truth_steps = draws_res[1].history, int(draws_res[1].truth_steps)
            if not records:
                records = _run_records(*draws_res)
        draws, errors, rates, failure = _assemble(records)
        return CampaignResult(
            scenario=base.scenario, seed=0 if flown is None else flown.seed, truth=base.settings.truth,
            guidance=base.guidance, switches=base.switches, settings=base.settings,
            nominal_tf_s=base.job.reference.tf_s, draws=draws, errors=errors, max_rates=rates,
            failure=failure, history=history, wall_time_s=0.0 if flown is None else flown.wall_s,
            workers=1 if flown is None else flown.workers,
            flight_cpu_s=0.0 if flown is None else flown.cpu_s, truth_steps=truth_steps,
            scenario_path=str(plan.scenario_path), scenario_sha256=plan.scenario_sha256,
            resumed_runs=0 if flown is None else flown.resumed_runs, tables=base.tables,
            engine_result=flown)

    def report(self, flown: Flown) -> tuple[str, dict[str, Any]]:
        from .report import format_report
        res = self.campaign_result(flown.plan, flown.records, flown)
        extra = res.to_json_dict(per_run=True)
        extra["family_schema"] = extra.pop("schema")
        for key in ENVELOPE_KEYS:       # the envelope states these (same meaning, one source)
            extra.pop(key, None)
        return format_report(res), extra

    def plots(self, flown: Flown, out_dir: Path) -> list[Path]:
        base: _Base = flown.plan.base
        ids = np.array([i for i in flown.run_ids if i < base.history_runs], dtype=np.int64)
        res = self.campaign_result(flown.plan, flown.records, flown, history_ids=ids)
        return self._write_plots(res, out_dir)

    @staticmethod
    def _write_plots(res: CampaignResult, out_dir: Path) -> list[Path]:
        from .plots import write_plots
        return list(write_plots(res, out_dir))


FAMILY = OrbitInjectionFamily()
