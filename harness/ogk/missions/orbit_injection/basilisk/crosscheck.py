"""ogk's 6-DOF truth model against Basilisk on the same runs: the same draws, the same flight
software (the kernel's VTD-NOG, end-game and CPD), two independent vehicle models
(docs/guides/basilisk.md). `compare` flies a list of runs in both and returns their injection errors.

    .venv/bin/python -m ogk.missions.orbit_injection.basilisk.crosscheck [SCENARIO] --seed S --runs N [--substeps K]
"""
from __future__ import annotations

import argparse
import dataclasses
import json
import sys
import time
from collections.abc import Sequence
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ogk_host.orbit_injection.scenario import OrbitInjectionScenario, load_scenario
from ogk_host.scenario_file import resolve_scenario

from ogk.missions.orbit_injection.dispersions import DispersionSwitches, draw_runs
from ogk.missions.orbit_injection.guidance import GuidanceSetup
from ogk.missions.orbit_injection.nog_guidance import KernelNogGuidance, prepare_tables
from ogk.missions.orbit_injection.nominal_ref import nominal_reference, resolved_with_reference
from ogk.missions.orbit_injection.sil import ERROR_KEYS, EndGamePlan, SilSettings, fly_runs

from . import injection

F64 = NDArray[np.float64]


@dataclasses.dataclass
class Comparison:
    """Injection errors of the same runs in both truth models (ERROR_KEYS -> (N,))."""

    run_id: NDArray[np.int64]
    ours: dict[str, F64]
    basilisk: dict[str, F64]
    failures: dict[str, list[str]]
    ours_history: Any = None          #: sil.History of the runs (history_s > 0)
    basilisk_flights: list[Any] = dataclasses.field(default_factory=list)
    cpu_s: dict[str, float] = dataclasses.field(default_factory=dict)

    def difference(self) -> dict[str, F64]:
        """Basilisk minus ours, per key and run."""
        return {k: self.basilisk[k] - self.ours[k] for k in ERROR_KEYS}

    def statistics(self) -> dict[str, dict[str, dict[str, float]]]:
        """{model: {key: {mean, std}}} over the runs (std with ddof = 1)."""
        out: dict[str, dict[str, dict[str, float]]] = {}
        for name, err in (("ours", self.ours), ("basilisk", self.basilisk)):
            out[name] = {k: {"mean": float(np.mean(v)),
                             "std": float(np.std(v, ddof=1)) if v.size > 1 else 0.0}
                         for k, v in err.items()}
        return out


def compare(scn: OrbitInjectionScenario, seed: int, run_ids: Sequence[int],
            switches: DispersionSwitches = DispersionSwitches(),
            settings: SilSettings = SilSettings(), history_s: float = 0.0,
            ref: Any = None, tables: Any = None) -> Comparison:
    """Flies `run_ids` of campaign `seed` in ogk's 6-DOF truth (one batch, sil.fly_runs) and one
    by one in Basilisk (injection.fly), with the scenario's tables (generated when missing). `scn`
    is resolved where it was loaded (nominal_ref.resolved_with_reference)."""
    ref = nominal_reference(scn) if ref is None else ref
    tables = prepare_tables(scn) if tables is None else tables
    ids = np.asarray(run_ids, dtype=np.int64)
    if history_s:
        every = int(round(history_s * settings.control_rate_hz))
        settings = dataclasses.replace(settings, history_runs=int(ids.max()) + 1,
                                       history_every=every)
    c0 = time.process_time()
    draws, gens = draw_runs(scn, seed, ids, switches)
    plan = EndGamePlan.of(scn, settings)
    guidance = KernelNogGuidance(GuidanceSetup(scn, ref, draws.run_id, plan.fine_interval_s),
                                 tables.bundle)
    res = fly_runs(scn, ref, draws, gens, switches, guidance, settings)
    c1 = time.process_time()
    flights = []
    for rid in ids:
        d1, g1 = draw_runs(scn, seed, [int(rid)], switches)
        flights.append(injection.fly(scn, ref, tables, d1, g1[0], switches, settings,
                                     history_s=history_s))
    c2 = time.process_time()
    bsk = {k: np.array([f.errors[k] for f in flights]) for k in ERROR_KEYS}
    return Comparison(ids, {k: np.asarray(v) for k, v in res.errors.items()}, bsk,
                      {"ours": list(res.failure), "basilisk": [f.failure for f in flights]},
                      res.history, flights, {"ours": c1 - c0, "basilisk": c2 - c1})


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m ogk.missions.orbit_injection.basilisk.crosscheck",
                                 description="ogk's 6-DOF truth against Basilisk on the same runs")
    ap.add_argument("scenario", nargs="?", default="leo-geo",
                    help="a .toml path or a shipped scenario's name (default leo-geo)")
    ap.add_argument("--seed", type=int, default=7)
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--substeps", type=int, default=1, help="dynamics steps per control step")
    ap.add_argument("--no-dispersions", action="store_true")
    ap.add_argument("--json", help="write the per-run errors of both models here")
    args = ap.parse_args(argv)
    scn, ref = resolved_with_reference(load_scenario(resolve_scenario(args.scenario)))
    switches = DispersionSwitches.none() if args.no_dispersions else DispersionSwitches()
    cmp = compare(scn, args.seed, range(args.runs), switches,
                  SilSettings(truth_substeps=args.substeps), ref=ref)
    diff = cmp.difference()
    print(f"{scn.name}: seed {args.seed}, {args.runs} runs, dynamics step "
          f"{SilSettings(truth_substeps=args.substeps).truth_step_s * 1e3:g} ms; CPU s: "
          + ", ".join(f"{k} {v:.1f}" for k, v in cmp.cpu_s.items()))
    stats = cmp.statistics()
    print(f"{'':12s} {'ours mean':>12s} {'ours std':>11s} {'bsk mean':>12s} {'bsk std':>11s} "
          f"{'max |diff|':>11s}")
    for k in ERROR_KEYS:
        o, b = stats["ours"][k], stats["basilisk"][k]
        print(f"{k:12s} {o['mean']:12.5g} {o['std']:11.4g} {b['mean']:12.5g} {b['std']:11.4g} "
              f"{np.max(np.abs(diff[k])):11.3g}")
    if args.json:
        with open(args.json, "w") as f:
            json.dump({"scenario": scn.name, "seed": args.seed, "substeps": args.substeps,
                       "run_id": cmp.run_id.tolist(), "failures": cmp.failures,
                       "ours": {k: v.tolist() for k, v in cmp.ours.items()},
                       "basilisk": {k: v.tolist() for k, v in cmp.basilisk.items()},
                       "cpu_s": cmp.cpu_s}, f, indent=1)
    failed = any(cmp.failures["ours"]) or any(cmp.failures["basilisk"])
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
