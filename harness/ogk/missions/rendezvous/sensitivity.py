"""How the rendezvous closed loop's outcome moves when its first measured state moves a little (issue 32,
docs/design/nmpc-flight.md, "Robustness"): the same runs of a campaign (same noise streams) flown with the
initial radius moved by 1..K representable doubles and by a few metres, through the campaign engine
(`ogk mc SCENARIO --move-start MOVE`); per run the spread of arrival time and fuel over the moves.

A law whose outcome is a continuous function of what it measures keeps these spreads at the size of its
solver tolerances; a branch switch or a failed solve that one move triggers shows as a jump of days.

    python -m ogk.missions.rendezvous.sensitivity SCENARIO --seed S --runs 0,1,2 [--ulps 20]
        [--metres 0.001,1] [--third-bodies-in-model yes] [--workers 2] [--json F]
"""
from __future__ import annotations

import argparse
import json
import sys
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np

from ogk_host.scenario_file import read_header, resolve_scenario

from ogk.sil.engine import fly_campaign

from .family import FAMILY


def moves(ulps: int, metres: Sequence[float]) -> list[str]:
    """The moves of a study: none, 1..ulps representable doubles outward, then each distance in metres."""
    return [""] + [f"{k}ulp" for k in range(1, ulps + 1)] + [f"{m:g}m" for m in metres]


def study(scenario: str | Path, seed: int, run_ids: Sequence[int], move_list: Sequence[str],
          options: dict[str, Any] | None = None, workers: int = 1) -> dict[str, Any]:
    """Flies runs `run_ids` of the campaign (scenario, seed) once per move; returns the per-move records
    and, per run, the spread (max - min) of t_f and fuel over the ulp moves and over every move."""
    header = read_header(resolve_scenario(scenario))
    flown: dict[str, list[dict[str, Any]]] = {}
    for move in move_list:
        plan = FAMILY.plan(header, {**(options or {}), "move_start": move})
        f = fly_campaign(plan, len(run_ids), int(seed), workers, run_ids=list(run_ids), progress=False)
        flown[move] = [{k: r.get(k) for k in ("run_id", "converged", "reason", "t_f_days", "fuel_kg",
                                                "failed_solves")} for r in f.records]
    per_run = []
    for i, rid in enumerate(run_ids):
        rows = {m: recs[i] for m, recs in flown.items()}
        ulp = [m for m in move_list if m.endswith("ulp") or m == ""]

        def spread(key: str, which: Sequence[str]) -> float | None:
            vals = [rows[m][key] for m in which if rows[m]["converged"]]
            return float(np.ptp(vals)) if len(vals) == len(which) else None
        per_run.append({"run_id": int(rid), "t_f_days": rows[""]["t_f_days"],
                        "lost": sum(1 for m in move_list if not rows[m]["converged"]),
                        "failed_solves_max": max(int(rows[m]["failed_solves"] or 0) for m in move_list),
                        "t_f_spread_ulp_days": spread("t_f_days", ulp),
                        "fuel_spread_ulp_kg": spread("fuel_kg", ulp),
                        "t_f_spread_all_days": spread("t_f_days", move_list),
                        "fuel_spread_all_kg": spread("fuel_kg", move_list),
                        "by_move": {m or "none": {"t_f_days": rows[m]["t_f_days"], "fuel_kg": rows[m]["fuel_kg"],
                                                  "reason": rows[m]["reason"]} for m in move_list}})
    return {"scenario": str(scenario), "seed": int(seed), "moves": list(move_list),
            "options": options or {}, "runs": per_run}


def report(doc: dict[str, Any]) -> str:
    lines = [f"{doc['scenario']}: the first measured radius moved ({len(doc['moves']) - 1} moves: "
             f"{', '.join(m for m in doc['moves'] if m)}), campaign seed {doc['seed']}",
             "  run    t_f [d]  lost  failed max  t_f spread ulp [d]  fuel spread ulp [kg]  t_f spread all [d]"]

    def f(v: float | None) -> str:
        return "-" if v is None else f"{v:.4g}"
    for r in doc["runs"]:
        lines.append(f"  {r['run_id']:3d}  {f(r['t_f_days']):>9s}  {r['lost']:4d}  {r['failed_solves_max']:10d}"
                     f"  {f(r['t_f_spread_ulp_days']):>18s}  {f(r['fuel_spread_ulp_kg']):>20s}"
                     f"  {f(r['t_f_spread_all_days']):>18s}")
    return "\n".join(lines)


def main(argv: Sequence[str] | None = None) -> int:
    p = argparse.ArgumentParser(prog="python -m ogk.missions.rendezvous.sensitivity",
                                description=__doc__.split("\n\n")[0])
    p.add_argument("scenario")
    p.add_argument("--seed", type=int, required=True, help="the campaign's master seed")
    p.add_argument("--runs", default="0,1,2", help="run ids, comma-separated (default 0,1,2)")
    p.add_argument("--ulps", type=int, default=20, help="moves of 1..K representable doubles (default 20)")
    p.add_argument("--metres", default="0.001,1", help="moves in metres, comma-separated (default 0.001,1)")
    p.add_argument("--third-bodies-in-model", choices=("scenario", "yes", "no"), default="scenario")
    p.add_argument("--workers", type=int, default=2)
    p.add_argument("--json", default=None, metavar="FILE")
    a = p.parse_args(argv)
    runs = [int(v) for v in a.runs.split(",") if v.strip()]
    metres = [float(v) for v in a.metres.split(",") if v.strip()]
    doc = study(a.scenario, a.seed, runs, moves(a.ulps, metres),
                {"third_bodies_in_model": a.third_bodies_in_model}, a.workers)
    print(report(doc))
    if a.json:
        Path(a.json).write_text(json.dumps(doc, indent=1))
        print(f"wrote {a.json}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
