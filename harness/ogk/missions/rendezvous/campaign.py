"""Noise-seed campaigns of the rendezvous closed loop: the same scenario, strategy and guidance flown on a list
of thrust-angle noise seeds, every flight's figures and the count that reached Mars (issue 10: "Mars reached
on at least 9 of 10 noise seeds, every seed's t_f and fuel reported").

    python -m ogk.missions.rendezvous.campaign SCENARIO --strategy snns --solver kernel --seeds 1-10 \
        [--unperturbed] [--third-bodies-in-model yes|no|scenario] [--workers 2] --json FILE

Each flight is independent (its own guidance context, its own seed), so the seeds run in a process pool.
"""
from __future__ import annotations

import argparse
import concurrent.futures
import dataclasses
import json
import time
from pathlib import Path
from typing import Any

import numpy as np
from ogk_host.rendezvous.scenario import RendezvousScenario, load_scenario

from .closed_loop import fly
from .guidance import make_guidance, strategy_settings


def parse_seeds(text: str) -> list[int]:
    """'1-10' or '1,4,7' or '3'."""
    seeds: list[int] = []
    for part in text.split(","):
        if "-" in part:
            lo, hi = part.split("-", 1)
            seeds.extend(range(int(lo), int(hi) + 1))
        else:
            seeds.append(int(part))
    return seeds


def with_model(scenario: RendezvousScenario, third_bodies: str) -> RendezvousScenario:
    if third_bodies == "scenario":
        return scenario
    return dataclasses.replace(scenario, nmpc=dataclasses.replace(
        scenario.nmpc, third_bodies_in_model=third_bodies == "yes"))


def fly_one(path: str, strategy: str, solver: str, perturbed: bool, seed: int,
            third_bodies: str) -> dict[str, Any]:
    scenario = with_model(load_scenario(path), third_bodies)
    guidance = make_guidance(solver, scenario, strategy_settings(scenario, strategy))
    start = time.perf_counter()
    try:
        r = fly(scenario, guidance, perturbed, seed, strategy_name=strategy, solver_name=solver)
    except RuntimeError as err:   # the truth integration stopped (e.g. a pass through a planet's centre)
        return {"seed": seed, "converged": False, "reason": f"truth: {err}", "t_f_days": float("nan"),
                "fuel_kg": float("nan"), "fuel_nominal_mdot_kg": float("nan"), "solves": 0, "failed_solves": 0,
                "subdivisions": 0, "solve_ms": {"median": float("nan"), "max": float("nan")},
                "wall_s": time.perf_counter() - start,
                "third_bodies_in_model": scenario.nmpc.third_bodies_in_model}
    doc = r.summary()
    doc["wall_s"] = time.perf_counter() - start
    doc["third_bodies_in_model"] = scenario.nmpc.third_bodies_in_model
    return doc


def campaign(path: str, strategy: str, solver: str, perturbed: bool, seeds: list[int],
             third_bodies: str = "scenario", workers: int = 1) -> dict[str, Any]:
    args = [(path, strategy, solver, perturbed, s, third_bodies) for s in seeds]
    if workers > 1:
        with concurrent.futures.ProcessPoolExecutor(max_workers=workers) as pool:
            flights = list(pool.map(fly_one, *zip(*args)))
    else:
        flights = [fly_one(*a) for a in args]
    done = [f for f in flights if f["converged"]]
    t_f = np.array([f["t_f_days"] for f in done]) if done else np.zeros(0)
    fuel = np.array([f["fuel_kg"] for f in done]) if done else np.zeros(0)
    ms = np.array([f["solve_ms"]["median"] for f in flights if f["converged"]] or [float("nan")])
    return {"scenario": path, "strategy": strategy, "solver": solver, "perturbed": perturbed,
            "third_bodies_in_model": flights[0]["third_bodies_in_model"] if flights else None,
            "seeds": seeds, "reached_mars": len(done), "flights": len(flights),
            "t_f_days": {"mean": float(t_f.mean()) if t_f.size else None,
                         "std": float(t_f.std(ddof=1)) if t_f.size > 1 else None,
                         "max": float(t_f.max()) if t_f.size else None},
            "fuel_kg": {"mean": float(fuel.mean()) if fuel.size else None,
                        "max": float(fuel.max()) if fuel.size else None},
            "failed_solves_total": int(sum(f["failed_solves"] for f in flights)),
            "solve_ms_median_of_medians": float(np.median(ms)),
            "per_seed": flights}


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(prog="python -m ogk.missions.rendezvous.campaign", description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("scenario")
    p.add_argument("--strategy", choices=("snns", "cncn"), default="snns")
    p.add_argument("--solver", choices=("kernel", "ipopt"), default="kernel")
    p.add_argument("--seeds", default="1-10")
    p.add_argument("--unperturbed", action="store_true")
    p.add_argument("--third-bodies-in-model", choices=("scenario", "yes", "no"), default="scenario")
    p.add_argument("--workers", type=int, default=1)
    p.add_argument("--json", required=True)
    a = p.parse_args(argv)
    res = campaign(a.scenario, a.strategy, a.solver, not a.unperturbed, parse_seeds(a.seeds),
                   a.third_bodies_in_model, a.workers)
    Path(a.json).parent.mkdir(parents=True, exist_ok=True)
    Path(a.json).write_text(json.dumps(res, indent=1))
    print(f"{Path(a.scenario).stem} {a.strategy} {a.solver} perturbed={not a.unperturbed} "
          f"third_bodies_in_model={res['third_bodies_in_model']}: Mars reached on {res['reached_mars']} of "
          f"{res['flights']} seeds")
    print("  seed  reached  t_f [d]   fuel [kg]  fuel nominal mdot [kg]  solves  failed  subdiv  median ms")
    for f in res["per_seed"]:
        print(f"  {f['seed']:4d}  {'yes' if f['converged'] else 'NO ':7s}  {f['t_f_days']:8.2f}  {f['fuel_kg']:9.2f}"
              f"  {f['fuel_nominal_mdot_kg']:22.2f}  {f['solves']:6d}  {f['failed_solves']:6d}  "
              f"{f['subdivisions']:6d}  {f['solve_ms']['median']:9.2f}")
    return 0 if res["reached_mars"] == res["flights"] else 1


if __name__ == "__main__":
    raise SystemExit(main())
