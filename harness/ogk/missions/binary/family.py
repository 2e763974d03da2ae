"""The binary-asteroid family (ogk.sil.family.MissionFamily): BLT transfers corrected by NRPC
(Xiong & Wang). `ogk run` flies one transfer (one_transfer.py; `ogk blt` is its older spelling);
`ogk mc` is the convergence Monte Carlo of Table 3 (sec. V.A.2): a run is the scenario's
[monte_carlo] transfer perturbed at one level of its [dispersions] (run i: level i mod L) and
corrected by each corrector on the same draw (convergence_run.py); on a target every corrector call
is the flight program's (pil.py). The family has no ground tables.

Acceptance (`scenario.acceptance`): a run fails when a corrector claims convergence that the DOP853
re-propagation does not confirm within [acceptance] error_tolerance (default: the [monte_carlo] tol
the correctors run with), or when the kernel rejected the perturbed problem. A corrector that does
not converge is what the campaign measures (the converged percentage per level), not a failure.
The paper's column is [paper_results.table3], printed only when the scenario has it.
"""
from __future__ import annotations

import argparse
import dataclasses
import hashlib
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np
from ogk_bindings.errors import OgkInputError
from ogk_host.binary import transfers as T
from ogk_host.binary.orbits import CorrectionError
from ogk_host.binary.scenario import LAWS, BinaryScenario, load_scenario
from ogk_host.scenario_file import ScenarioHeader, file_sha256

from ogk.sil.dispersion_check import scenario_table
from ogk.sil.engine import Flown
from ogk.sil.family import CampaignPlan, ChunkFlight, FamilyDefaults, Record, per_run
from ogk.sil.pil import FlightProgram
from ogk.sil.progress import Working
from ogk.sil.seeds import run_generator

from . import convergence_run
from .dispersions import applied_record, declared

ALL = ("nrpc", "lm", "hybrid")


@dataclasses.dataclass(frozen=True)
class _Base:
    scenario: BinaryScenario
    transfer: str
    thrust_n: float
    correctors: tuple[str, ...]
    levels_percent: tuple[float, ...]
    paper: dict[float, float]         #: level [%] -> the paper's converged % (empty: no paper column)
    nominal: convergence_run.Nominal  #: what every run perturbs and corrects
    sigma_fraction: float             #: a draw's sigma as a fraction of its level


def draw_record(nominal: convergence_run.Nominal, levels: tuple[float, ...], sigma: float, run_id: int,
                run_seed: int) -> Record:
    """Run `run_id`'s disp.* keys without correcting it: its level and its perturbed problem, drawn
    as fly_one draws them (convergence_run.perturbed; the node's re-prediction changes no disp.* key)."""
    level = levels[run_id % len(levels)] / 100.0
    guess, _ = convergence_run.perturbed(nominal, level, sigma, run_generator(run_seed))
    return applied_record(nominal, level, guess)


class BinaryFamily(FamilyDefaults):
    name = "binary-asteroid"
    laws = LAWS
    #: m7 / sparc: the corrector calls on the emulated Cortex-M7 / SPARC V8 (pil.py)
    targets = ("host", "m7", "sparc", "m4f")
    run_aliases = ("blt",)            #: `ogk blt`: the older `ogk run`
    target_watchdog_per_run_s = 120.0

    def default_runs(self, header: ScenarioHeader) -> int | None:
        """The scenario's [monte_carlo] runs per level times its [dispersions] levels (Table 3: 600 x 6)."""
        try:
            spec = T.monte_carlo_spec(self.load(header))
        except OgkInputError:
            return None          # reported with its key when the campaign is planned
        return spec.runs * len(spec.levels_percent)
    campaign_doc = ("the Table 3 convergence Monte Carlo: the scenario's [monte_carlo] transfer "
                    "perturbed, every corrector on the same draws, each converged run re-checked "
                    "by DOP853; run i flies level i mod L")

    def load(self, header: ScenarioHeader) -> BinaryScenario:
        return load_scenario(header.path)

    def add_campaign_arguments(self, parser: argparse.ArgumentParser) -> None:
        parser.add_argument("--perturbation", type=float, nargs="+", default=None, metavar="PCT",
                       help="perturbation levels [%%] (default: the scenario's [dispersions] levels)")
        parser.add_argument("--corrector", choices=("all", *ALL), default="all",
                       help="which corrector(s) to fly on the same draws (default all three)")
        parser.add_argument("--sigma-fraction", type=float, default=None, metavar="F",
                       help="sigma of a draw as a fraction of the level (default: the scenario's)")

    def plan(self, header: ScenarioHeader, options: Mapping[str, Any]) -> CampaignPlan:
        scenario = self.load(header)
        spec_mc = T.monte_carlo_spec(scenario)
        levels = tuple(float(v) for v in (options.get("perturbation") or spec_mc.levels_percent))
        bad = [v for v in levels if not 0.0 < v <= 100.0]
        if bad:
            raise OgkInputError(f"every level must be in (0, 100] %, got {bad[0]:g}",
                                key="--perturbation")
        sigma = options.get("sigma_fraction")
        sigma = spec_mc.sigma_fraction if sigma is None else float(sigma)
        if not sigma > 0.0:
            raise OgkInputError(f"must be > 0, got {sigma:g}", key="--sigma-fraction")
        chosen = options.get("corrector", "all")
        correctors = ALL if chosen == "all" else (str(chosen),)
        solver = T.solver_settings(scenario)
        spec = T.transfer_spec(scenario, spec_mc.transfer)
        with Working(f"{scenario.name}: nominal {spec.name}"):
            try:
                d = T.design(scenario, spec, solver)
            except CorrectionError as exc:      # an orbit or a guess that cannot be built: one line
                raise OgkInputError(str(exc), path=scenario.path, key=f"transfers.{spec.name}") from exc
        if not d.report.converged:
            raise OgkInputError(f"the nominal transfer {spec.name} did not converge "
                                f"({d.report.status})", path=scenario.path,
                                key=f"transfers.{spec.name}")
        assert spec.circle_radius_m is not None
        accept_tol = scenario.acceptance.tolerance(spec_mc.tol)
        nominal = convergence_run.Nominal(
            model=d.model, layout=d.guess.layout, transfer=d.transfer,
            circle_radius=spec.circle_radius_m / scenario.units.length_m, tol=spec_mc.tol,
            max_iter=spec_mc.max_iter, jacobian=T.JACOBIANS[solver.jacobian],
            fields=dict(fd_step=solver.fd_step, ls_trials=solver.ls_trials),
            error_tolerance=accept_tol)
        solvers = convergence_run.kernels(nominal, correctors)
        n_levels = len(levels)

        def fly_one(run_id: int, run_seed: int) -> Record:
            level = levels[run_id % n_levels]
            return convergence_run.fly_run(nominal, solvers, level / 100.0, sigma, run_generator(run_seed))

        tol = spec_mc.tol

        def judge(rec: Record) -> str:
            for c in correctors:
                why = str(rec.get(f"{c}.reason") or "")
                if why.startswith("rejected"):
                    return f"{c}: {why}"
                if rec.get(f"{c}.converged") and not rec.get(f"{c}.dop853_meets_tol"):
                    return (f"{c}: converged but DOP853 |e| = {rec.get(f'{c}.dop853_err_norm')} > "
                            f"{accept_tol:g}")
            return ""

        # the corrector the flight software flies: the scenario's [solver] corrector (the others are the
        # campaign's comparisons); when it did not converge the transfer is not flown (safe command,
        # engine off): a lost flight for the robustness summary (ogk.sil.robustness), not a failure
        flight = solver.corrector if solver.corrector in correctors else correctors[-1]

        def lost(rec: Record) -> str:
            if rec.get(f"{flight}.converged"):
                return ""
            return f"{flight}: {rec.get(f'{flight}.reason') or 'not converged'}"

        def solve_failures(rec: Record) -> list[str]:
            return [f"{c}: {rec.get(f'{c}.reason') or 'not converged'}" for c in correctors
                    if not rec.get(f"{c}.converged")]

        nominal_sha = hashlib.sha256(np.ascontiguousarray(d.transfer.segments).tobytes()
                                     + np.ascontiguousarray(d.transfer.nodes).tobytes()).hexdigest()
        table3 = (scenario.paper_results or {}).get("table3") or {}
        paper = {float(lv): float(pc) for lv, pc in zip(table3.get("levels_percent", ()),
                                                          table3.get("converged_percent", ()))}
        base = _Base(scenario, spec.name, spec.thrust_n, correctors, levels, paper, nominal, sigma)
        plan = CampaignPlan(
            family=self.name, law=header.law, mission=scenario.name, scenario_path=Path(header.path),
            scenario_sha256=file_sha256(header.path),
            options={"perturbation": list(levels), "sigma_fraction": sigma, "corrector": chosen,
                     "transfer": spec.name, "tol": tol, "max_iter": spec_mc.max_iter,
                     "jacobian": solver.jacobian},
            products={"nominal_transfer": nominal_sha},
            fly=per_run(fly_one), judge=judge,
            quantities=tuple(f"{c}.{q}" for c in correctors for q in ("iterations", "err_norm")),
            paper=lambda recs: self._paper(base, recs),
            acceptance={"dop853_tolerance": accept_tol,
                        "error_tolerance": scenario.acceptance.error_tolerance,
                        "non_convergence": "measured, not a failure"},
            watchdog_per_run_s=30.0, base=base, lost=lost, solve_failures=solve_failures,
            dispersions=declared(scenario_table(header.path), nominal, levels, sigma),
            draw=per_run(lambda run_id, run_seed: draw_record(nominal, levels, sigma, run_id,
                                                              run_seed)))
        if options.get("target", "host") != "host":
            self.on_target(plan, str(options["target"]))
        return plan

    # ------------------------------------------------------------------ ogk run
    def add_run_arguments(self, parser: argparse.ArgumentParser) -> None:
        from .one_transfer import add_run_arguments
        add_run_arguments(parser)

    def run(self, header: ScenarioHeader, args: argparse.Namespace) -> int:
        """`ogk run SCENARIO --transfer NAME`: one BLT transfer, checked by DOP853."""
        from .one_transfer import run
        return run(header, args, lambda: self.scenario_program(header, getattr(args, "target", "m7")))

    def scenario_program(self, header: ScenarioHeader, target: str = "m7") -> FlightProgram:
        """The scenario's flight program: the one its `ogk mc --target TARGET` flies (built for the
        corrector configurations of its [monte_carlo] nominal; a design's solves uplink their own)."""
        return self.flight_program(self.plan(header, {}), target)

    # ------------------------------------------------------------------ on a target
    # every corrector call made by the scenario's flight program (pil.py); the draws, the DOP853
    # checks and the judging stay on the host
    def flight_config(self, plan: CampaignPlan, out_dir: Path) -> list[Path]:
        """The three correctors' configurations of the [monte_carlo] nominal (the program's slots)."""
        from .flight_config import slot_configs, write_flight_config
        base: _Base = plan.base
        return [write_flight_config(out_dir / "c", plan.scenario_path, slot_configs(base.nominal),
                                    base.transfer)]

    def flight_program(self, plan: CampaignPlan, target: str) -> FlightProgram:
        from . import pil
        base: _Base = plan.base
        return pil.flight_program(base.nominal, plan.scenario_path,
                                  lambda out: self.flight_config(plan, out), target)

    def target_job(self, plan: CampaignPlan, program: FlightProgram) -> ChunkFlight:
        from . import pil
        base: _Base = plan.base
        return pil.TargetJob(base.nominal, base.correctors, base.levels_percent,
                             base.sigma_fraction, program)

    def target_bounds(self, plan: CampaignPlan) -> tuple[dict[str, float], str]:
        from . import pil
        base: _Base = plan.base
        return ({k: v for k, v in pil.BOUNDS.items() if k.split(".")[0] in base.correctors},
                pil.BOUNDS_WHY)

    # ------------------------------------------------------------------ reports
    def _levels(self, base: _Base, records: Sequence[Record]) -> list[dict[str, Any]]:
        out = []
        for level in base.levels_percent:
            recs = [r for r in records if r["level_percent"] == level]
            summary = {c: convergence_run.summarise(list(recs), c) for c in base.correctors}
            out.append(dict(level_percent=level, paper_converged_percent=base.paper.get(level),
                            runs=len(recs), summary=summary,
                            converged_pct={c: summary[c]["converged_pct"] for c in base.correctors}))
        return out

    def _paper(self, base: _Base, records: Sequence[Record]) -> dict[str, Any] | None:
        if not base.paper:
            return None
        return {"table": "Xiong & Wang, Table 3 (converged %)",
                "levels": [{"level_percent": lv["level_percent"],
                            "paper_converged_percent": lv["paper_converged_percent"],
                            **{f"{c}_converged_percent": lv["converged_pct"][c]
                               for c in base.correctors}}
                           for lv in self._levels(base, records)]}

    def report(self, flown: Flown) -> tuple[str, dict[str, Any]]:
        base: _Base = flown.plan.base
        levels = self._levels(base, flown.records)
        cs = base.correctors
        lines = [f"Xiong & Wang, Table 3 ({base.scenario.name} / {base.transfer}, "
                 f"{base.thrust_n * 1e3:g} mN): {len(flown.records)} runs over {len(levels)} levels, "
                 f"seed {flown.seed}, tol {flown.plan.options['tol']:g}",
                 f"  {'level [%]':>9s} {'runs':>5s} " + " ".join(f"{c + ' [%]':>10s}" for c in cs)
                 + (f" {'paper [%]':>10s}" if base.paper else "") + f"  not converged ({cs[-1]})"]
        for lv in levels:
            s = lv["summary"]
            paper = lv["paper_converged_percent"]
            lines.append(f"  {lv['level_percent']:9g} {lv['runs']:5d} "
                         + " ".join(f"{s[c]['converged_pct']:10.2f}" for c in cs)
                         + ("" if not base.paper else f" {paper:10.2f}" if paper is not None
                            else f" {'-':>10s}")
                         + "  " + ", ".join(f"{k}: {v}" for k, v in s[cs[-1]]["failures"].items())
                         + "".join(f"  [{c}: DOP853 confirms {s[c]['dop853_confirmed']}/"
                                   f"{s[c]['converged']}]" for c in cs
                                   if s[c]["dop853_confirmed"] != s[c]["converged"]))
        extra = {"scenario": base.scenario.name, "transfer": base.transfer,
                 "correctors": list(cs), "levels": levels,
                 "runs_per_level": {str(lv["level_percent"]): lv["runs"] for lv in levels}}
        return "\n".join(lines), extra

    def plots(self, flown: Flown, out_dir: Path) -> list[Path]:
        from .plots import mc_figure
        base: _Base = flown.plan.base
        levels = self._levels(base, flown.records)
        for lv in levels:   # the figure's shape: per run, per corrector
            recs = [r for r in flown.records if r["level_percent"] == lv["level_percent"]]
            lv["runs"] = [{"results": {c: {"converged": r.get(f"{c}.converged"),
                                           "iterations": r.get(f"{c}.iterations")}
                                       for c in base.correctors}} for r in recs]
        doc = {"scenario": base.scenario.name, "transfer": base.transfer, "levels": levels,
               "runs_per_level": len(flown.records) // max(len(levels), 1), "seed": flown.seed,
               "paper_levels_percent": list(base.paper), "paper_converged_percent":
                   list(base.paper.values())}
        return [mc_figure(doc, out_dir)]


FAMILY = BinaryFamily()
