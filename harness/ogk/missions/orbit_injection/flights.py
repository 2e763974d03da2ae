"""The orbit-injection campaign's flights: a chunk of dispersed runs flown vectorised (`_Job`),
their records, the campaign plan the family's `plan` returns (`campaign_plan`) and the
`CampaignResult` its report and plots read.

The same (seed, run id) gives the same numbers whatever the number of runs, workers or chunks:
every run draws from its own generator (dispersions.py), and every truth/control operation is
elementwise over runs. Each chunk builds its own guidance with
`guidance_factory(GuidanceSetup(...))`. The campaign itself is the engine's (ogk.sil.engine).
"""
from __future__ import annotations

import dataclasses
import hashlib
import json
import math
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from ogk_host.orbit_injection.scenario import OrbitInjectionScenario
from ogk_host.scenario_file import file_sha256

from ogk.sil.dispersion_check import scenario_table
from ogk.sil.criteria import (apply_tolerances, failure_list, failure_reasons, statistics,
                              tail_statistics)
from ogk.sil.outputs import write_atomic
from ogk.sil.report import finite_or_none
from ogk.sil.family import CampaignPlan

from .dispersions import (DispersionSwitches, RunDraws, declared, dispersion_records, draw_runs,
                          with_first_actuation)
from .guidance import GuidanceFactory, GuidanceSetup
from .nominal_ref import NominalReference
from .sil import ERROR_KEYS, RATE_KEYS, EndGamePlan, History, SilSettings, fly_runs

if TYPE_CHECKING:
    from .nog_guidance import NogTables

F64 = NDArray[np.float64]
JSON_SCHEMA = "ogk.leo_geo.mc/1"


@dataclasses.dataclass
class CampaignResult:
    """All runs of a campaign (run-major arrays, in run-id order)."""

    scenario: OrbitInjectionScenario
    seed: int
    truth: str
    guidance: str
    switches: DispersionSwitches
    settings: SilSettings
    nominal_tf_s: float
    draws: RunDraws
    errors: dict[str, F64]          #: ERROR_KEYS -> (N,), NaN where failed
    max_rates: dict[str, F64]       #: RATE_KEYS -> (N,)
    failure: list[str]              #: "" or the reason, per run
    history: History | None
    wall_time_s: float              #: whole campaign, including the nominal solve if not cached
    workers: int
    nominal_solve_s: float = 0.0    #: time spent solving the ground nominal (0 when cached)
    truth_steps: int = 0            #: truth steps of the longest chunk
    flight_cpu_s: float = 0.0       #: CPU time (user + system) of the flight, all processes
    scenario_path: str | None = None
    scenario_sha256: str | None = None
    tables: "NogTables | None" = None  #: the VTD-NOG tables flown (None: open-loop reference)
    resumed_runs: int = 0           #: runs taken from the run log of an interrupted campaign
    engine_result: Any = None       #: the engine's records (ogk.sil.engine.Flown)

    @property
    def flight_s(self) -> float:
        """Wall time of the runs themselves (forks, loops, merge)."""
        return self.wall_time_s - self.nominal_solve_s

    @property
    def runs(self) -> int:
        return self.draws.n_runs

    @property
    def ok(self) -> NDArray[np.bool_]:
        return np.array([f == "" for f in self.failure], dtype=bool)

    @property
    def n_failures(self) -> int:
        return int((~self.ok).sum())

    def failure_reasons(self) -> dict[str, int]:
        return failure_reasons(self.failure)

    def failures_list(self) -> list[dict[str, object]]:
        """[{run_id, reason}] of every failed run."""
        return failure_list(self.draws.run_id.tolist(), self.failure)

    @property
    def flown(self) -> NDArray[np.bool_]:
        """Runs that reached cut-off with finite injection errors: every run the statistics cover,
        including those outside the acceptance tolerances (they flew; they are counted as failures
        as well, not dropped from the dispersion)."""
        return np.all(np.stack([np.isfinite(self.errors[k]) for k in ERROR_KEYS]), axis=0)

    def mean(self) -> dict[str, float]:
        return statistics(self.errors, self.flown)[0]

    def std(self) -> dict[str, float]:
        """Sample standard deviation (ddof = 1; 0 for a single run)."""
        return statistics(self.errors, self.flown)[1]

    def tails(self) -> tuple[dict[str, float], dict[str, float]]:
        """(99.9th percentile, largest) of |error| per quantity over the flown runs; for t_f, of
        |t_f - mean t_f| (the final time is free)."""
        return tail_statistics(self.errors, self.flown, {"tf_s": self.mean()["tf_s"]})

    def max_rates_overall(self) -> dict[str, float]:
        """Largest actuator rate over all flown runs (NaN for the point-mass truth)."""
        ok = self.flown
        return {k: float(np.max(v[ok])) if ok.any() else float("nan")
                for k, v in self.max_rates.items()}

    def to_json_dict(self, per_run: bool = True) -> dict[str, Any]:
        scn = self.scenario
        out: dict[str, Any] = {
            "schema": JSON_SCHEMA,
            "scenario": scn.name,
            "source": scn.source,
            "runs": self.runs,
            "seed": self.seed,
            "truth": self.truth,
            "guidance": self.guidance,
            "dispersions": dataclasses.asdict(self.switches),
            "settings": {"control_rate_hz": self.settings.control_rate_hz,
                         "truth_step_s": self.settings.truth_step_s,
                         "guidance_sample_s": scn.sample_interval_s,
                         "cpd_gains": self.settings.cpd_gains or scn.cpd.flown,
                         "cpd_pointing": self.settings.cpd_pointing,
                         "end_game": dataclasses.asdict(EndGamePlan.of(scn, self.settings))},
            "p99_9_abs": self.tails()[0],
            "max_abs": self.tails()[1],
            "failures": self.n_failures,
            "failure_reasons": self.failure_reasons(),
            "mean": self.mean(),
            "std": self.std(),
            "max_rates": self.max_rates_overall(),
            "max_rates_bound_eq47": eq47_bounds(scn),
            "nominal_tf_s": self.nominal_tf_s,
            "wall_time_s": self.wall_time_s,
            "timing": {"nominal_solve_s": self.nominal_solve_s, "flight_s": self.flight_s,
                       "flight_cpu_s": self.flight_cpu_s, "truth_steps": self.truth_steps,
                       "flight_ms_per_truth_step": 1e3 * self.flight_s / max(self.truth_steps, 1)},
            "workers": self.workers,
            "resumed_runs": self.resumed_runs,
            "scenario_path": self.scenario_path,
            "scenario_sha256": self.scenario_sha256,
            "tolerances": tolerances(scn),
            "failed_runs": self.failures_list(),
            "tables": None if self.tables is None else {
                "directory": str(self.tables.directory), "sha256": self.tables.sha256,
                "t_f_s": self.tables.t_f_star_s},
        }
        if per_run:
            d = self.draws
            out["per_run"] = [
                {"run_id": int(d.run_id[i]), "run_seed": int(d.run_seed[i]),
                 "failure": self.failure[i],
                 "d_state": d.d_state[i].tolist(), "d_attitude_rad": d.d_attitude[i].tolist(),
                 "rates0_radps": d.rates0[i].tolist(), "thrust_coeffs": d.thrust_coeffs[i].tolist(),
                 **{k: float(self.errors[k][i]) for k in ERROR_KEYS},
                 **{k: float(self.max_rates[k][i]) for k in RATE_KEYS}}
                for i in range(self.runs)]
        return finite_or_none(out)

    def write_json(self, path: str | Path, per_run: bool = True) -> None:
        """Written atomically (temporary file + rename)."""
        write_atomic(path, json.dumps(self.to_json_dict(per_run), indent=1) + "\n")


def eq47_bounds(scn: OrbitInjectionScenario) -> dict[str, float]:
    """Eq. (47): |dM_x/dt| <= 2 Mbar_xc / tau_x, |dDelta/dt| <= 2 Deltabar_c / tau (RATE_KEYS units)."""
    cpd, act = scn.cpd, scn.actuators
    return {"Mx_dot_Nmps": 2.0 * cpd.roll_torque_command_max_n_m / act.time_constant_x_s,
            "Dy_dot_degps": float(np.degrees(2.0 * cpd.deflection_y_command_max_rad
                                             / act.time_constant_y_s)),
            "Dz_dot_degps": float(np.degrees(2.0 * cpd.deflection_z_command_max_rad
                                             / act.time_constant_z_s))}


def tolerances(scn: OrbitInjectionScenario) -> dict[str, float]:
    """The scenario's acceptance tolerances per error key (t_f has none: it is free)."""
    acc = scn.acceptance
    return {"dr_f_m": acc.radius_error_m, "dphi_f_deg": math.degrees(acc.declination_error_rad),
            "dvr_f_mps": acc.velocity_error_m_s, "dvt_f_mps": acc.velocity_error_m_s,
            "dvn_f_mps": acc.velocity_error_m_s}


@dataclasses.dataclass(frozen=True)
class _Job:
    """One chunk of runs, called in a forked worker (ogk.sil.runner)."""

    scenario: OrbitInjectionScenario
    reference: NominalReference
    seed: int
    switches: DispersionSwitches
    settings: SilSettings
    guidance_factory: GuidanceFactory

    def __call__(self, run_ids: NDArray[np.int64],
                 run_seeds: NDArray[np.uint64] | None = None) -> tuple[RunDraws, Any]:
        draws, gens = self.draws(run_ids, run_seeds)
        plan = EndGamePlan.of(self.scenario, self.settings)
        guidance = self.guidance_factory(GuidanceSetup(self.scenario, self.reference, draws.run_id,
                                                       plan.fine_interval_s))
        # (a guidance that flies no end-game ignores last_interval_s: sil.EndGamePlan.flown_by)
        res = fly_runs(self.scenario, self.reference, draws, gens, self.switches, guidance,
                       self.settings)
        return draws, res

    def draws(self, run_ids: NDArray[np.int64], run_seeds: NDArray[np.uint64] | None = None
              ) -> tuple[RunDraws, list[np.random.Generator]]:
        """The runs' draws, with the first actuation noise the truth will receive (fly_runs:
        on when the switch is and the truth is 6-DOF), and their generators positioned for the
        actuation noise."""
        draws, gens = draw_runs(self.scenario, self.seed, run_ids, self.switches, run_seeds)
        return with_first_actuation(self.scenario, draws, gens, self.switches.actuation
                                    and self.settings.truth == "6dof"), gens

    def draw_records(self, run_ids: NDArray[np.int64],
                     run_seeds: NDArray[np.uint64]) -> list[dict[str, Any]]:
        """The disp.* keys of the runs, drawn without flying (the plan's `draw`)."""
        return dispersion_records(self.draws(run_ids, run_seeds)[0])


def run_key(scenario: OrbitInjectionScenario, seed: int, truth: str, guidance: str,
            switches: DispersionSwitches, settings: SilSettings, scenario_sha256: str | None,
            tables: "NogTables | None") -> dict[str, Any]:
    """What a run's numbers depend on besides its id: the run log's key (ogk.sil.runlog)."""
    return {"schema": JSON_SCHEMA, "scenario_sha256": scenario_sha256,
            "scenario_data_sha256": hashlib.sha256(repr(scenario).encode()).hexdigest(),
            "seed": int(seed), "truth": truth, "guidance": guidance,
            "dispersions": dataclasses.asdict(switches),
            "settings": {"control_rate_hz": settings.control_rate_hz,
                         "truth_substeps": settings.truth_substeps, "t_max_s": settings.t_max_s,
                         "cpd_gains": settings.cpd_gains or scenario.cpd.flown,
                         "cpd_pointing": settings.cpd_pointing,
                         "end_game": settings.end_game},
            "tables_sha256": None if tables is None else tables.sha256}


def _run_records(draws: RunDraws, res: Any) -> list[dict[str, Any]]:
    """One record per run of a chunk (the run log's lines); `failure` is the loop's reason, the
    tolerances are applied when the campaign is assembled."""
    return [{"run_id": int(draws.run_id[i]), "run_seed": int(draws.run_seed[i]),
             "failure": res.failure[i],
             "d_state": draws.d_state[i].tolist(), "d_attitude_rad": draws.d_attitude[i].tolist(),
             "rates0_radps": draws.rates0[i].tolist(),
             "thrust_coeffs": draws.thrust_coeffs[i].tolist(),
             **{k: float(res.errors[k][i]) for k in ERROR_KEYS},
             **{k: float(res.max_rates[k][i]) for k in RATE_KEYS}, **disp}
            for i, disp in enumerate(dispersion_records(draws))]


def _assemble(records: list[dict[str, Any]]) -> tuple[RunDraws, dict[str, F64], dict[str, F64],
                                                      list[str]]:
    draws = RunDraws(run_id=np.array([r["run_id"] for r in records], dtype=np.int64),
                     run_seed=np.array([r["run_seed"] for r in records], dtype=np.uint64),
                     d_state=np.array([r["d_state"] for r in records], dtype=np.float64),
                     d_attitude=np.array([r["d_attitude_rad"] for r in records], dtype=np.float64),
                     rates0=np.array([r["rates0_radps"] for r in records], dtype=np.float64),
                     thrust_coeffs=np.array([r["thrust_coeffs"] for r in records],
                                            dtype=np.float64))
    errors = {k: np.array([r[k] for r in records], dtype=np.float64) for k in ERROR_KEYS}
    rates = {k: np.array([r[k] for r in records], dtype=np.float64) for k in RATE_KEYS}
    return draws, errors, rates, [str(r["failure"]) for r in records]


@dataclasses.dataclass(frozen=True)
class _ChunkFlight:
    """The family's chunk flight for the campaign engine: records without histories."""

    job: _Job

    def __call__(self, run_ids: NDArray[np.int64],
                 run_seeds: NDArray[np.uint64]) -> list[dict[str, Any]]:
        return _run_records(*self.job(run_ids, run_seeds))


def campaign_plan(scenario: OrbitInjectionScenario, ref: NominalReference, switches: DispersionSwitches,
                  settings: SilSettings, guidance_factory: GuidanceFactory, name: str,
                  tables: "NogTables | None", scenario_path: Path | None, law: str,
                  options: dict[str, Any] | None = None) -> CampaignPlan:
    """The campaign of the engine (ogk.sil.family): chunks flown vectorised by `_Job` (histories
    off), judged against the scenario's tolerances. `options`: the command's options (what
    `ogk replay` rebuilds the plan from); by default the run key's settings."""
    sha = None if scenario_path is None else file_sha256(scenario_path)
    flight = dataclasses.replace(settings, history_runs=0)
    job = _Job(scenario, ref, 0, switches, flight, guidance_factory)
    tol = tolerances(scenario)
    labels = {k: k for k in tol}

    def judge(rec: dict[str, Any]) -> str:
        return apply_tolerances({k: np.array([rec[k]]) for k in tol}, tol, [""], labels)[0]

    key = run_key(scenario, 0, settings.truth, name, switches, settings, sha, tables)
    key.pop("seed")
    table = {} if scenario_path is None else scenario_table(scenario_path)
    return CampaignPlan(
        family="orbit-injection", law=law, mission=scenario.name,
        scenario_path=Path(scenario_path) if scenario_path is not None else Path(""),
        scenario_sha256=sha or "", options=options if options is not None else key,
        products={} if tables is None else {"nog_tables": tables.sha256},
        fly=_ChunkFlight(job), judge=judge, quantities=ERROR_KEYS,
        acceptance=tol, watchdog_per_run_s=2.0, base=job,
        dispersions=declared(scenario, table, switches, settings.truth == "6dof"),
        draw=job.draw_records)
