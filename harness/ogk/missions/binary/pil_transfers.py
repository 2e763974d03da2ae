"""The binary-asteroid transfers with every corrector call on the emulated Cortex-M7, beside the host's
(docs/guides/flight-integration-blt.md, "The transfers of the scenario on the target"):

    python -m ogk.missions.binary.pil_transfers SCENARIO [--transfer NAME ...] [--json FILE]

designs each transfer (all of the scenario's [transfers] by default: the seven of `make run` for moshup)
twice, on the host, then with every ogk_blt_solve of the ground's design (ogk_host.binary.design.solve:
the direct solve and any SRP/tide, gravity or thrust continuation) made by the scenario's flight program
(pil.corrections_on_target), and compares them solve by solve. Exit 1 when the iterations or the
convergence differ.
"""
from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path
from typing import Any

import numpy as np
from ogk_bindings.blt import BltReport, Transfer

from ogk.sil.pil import FlightProgram, PilSession

from .family import FAMILY
from .pil import corrections_on_target


def _host_solves() -> tuple[Any, list[dict[str, Any]]]:
    """design.Blt logging each host solve (the comparison's host column)."""
    from ogk_bindings.blt import Blt
    log: list[dict[str, Any]] = []

    class _Logged(Blt):
        def solve(self, guess: Transfer) -> tuple[Transfer, BltReport]:
            sol, rep = super().solve(guess)
            log.append(dict(status=rep.status, iterations=rep.iterations, err_norm=rep.err_norm))
            return sol, rep
    return _Logged, log


def scenario_program(header: Any) -> FlightProgram:
    """The scenario's flight program (BinaryFamily.scenario_program)."""
    return FAMILY.scenario_program(header)


def transfers_on_target(scenario_path: Path, names: list[str] | None = None) -> dict[str, Any]:
    """Each transfer designed on the host, then with its corrector calls on the target: per transfer
    the solves (iterations, status, |e|) side by side, instructions and stack of the target's."""
    from ogk_host.binary import design
    from ogk_host.binary import transfers as T
    from ogk_host.binary.scenario import load_scenario
    from ogk_host.scenario_file import read_header

    header = read_header(scenario_path)
    scenario = load_scenario(header.path)
    solver = T.solver_settings(scenario)
    names = names or list(scenario.transfers)
    program = scenario_program(header)
    out: dict[str, Any] = {"scenario": scenario.name, "flight_program": str(program.elf),
                           "transfers": []}
    session = PilSession(program)
    try:
        for k, name in enumerate(names):
            spec = T.transfer_spec(scenario, name)
            logged, host_log = _host_solves()
            saved = design.Blt
            design.Blt = logged       # type: ignore[misc]
            t0 = time.perf_counter()
            try:
                host = T.design(scenario, spec, solver)
            finally:
                design.Blt = saved    # type: ignore[misc]
            t1 = time.perf_counter()
            with corrections_on_target(session) as target_log:
                target = T.design(scenario, spec, solver)
            t2 = time.perf_counter()
            session.end_run(k)
            hr, tr = host.report, target.report
            out["transfers"].append(dict(
                transfer=name, host_solves=host_log, target_solves=target_log,
                host=dict(converged=hr.converged, iterations=hr.iterations, err_norm=hr.err_norm),
                target=dict(converged=tr.converged, iterations=tr.iterations, err_norm=tr.err_norm),
                iterations_equal=[h["iterations"] for h in host_log]
                == [t["iterations"] for t in target_log],
                max_err_norm_diff=max((abs(h["err_norm"] - t["err_norm"]) for h, t in
                                       zip(host_log, target_log)
                                       if np.isfinite(h["err_norm"]) and np.isfinite(t["err_norm"])),
                                      default=0.0),
                host_wall_s=t1 - t0, target_wall_s=t2 - t1))
        keys = session.close()
    except BaseException:
        session.kill()
        raise
    for k, row in enumerate(out["transfers"]):
        row["pil"] = keys.get(k, {})
    return out


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(prog="python -m ogk.missions.binary.pil_transfers",
                                description="the scenario's BLT transfers with every corrector call on "
                                            "the emulated Cortex-M7, beside the host's")
    p.add_argument("scenario", help="a binary-asteroid scenario (name or path)")
    p.add_argument("--transfer", nargs="+", default=None, metavar="NAME",
                   help="these [transfers.NAME] (default: all of the scenario's)")
    p.add_argument("--json", default=None, metavar="FILE")
    a = p.parse_args(argv)
    from ogk_host.scenario_file import resolve_scenario
    doc = transfers_on_target(resolve_scenario(a.scenario), a.transfer)
    print(f"{doc['scenario']}: host vs target (every ogk_blt_solve of the design on {doc['flight_program']})")
    print(f"  {'transfer':24s} {'solves':>6s} {'iterations host':>24s} {'iterations target':>24s} "
          f"{'max |d|e||':>10s} {'insn max':>11s} {'stack B':>7s} {'conv':>5s}")
    ok = True
    for row in doc["transfers"]:
        hi = ",".join(str(s["iterations"]) for s in row["host_solves"])
        ti = ",".join(str(s["iterations"]) for s in row["target_solves"])
        pil = row["pil"]
        ok &= row["iterations_equal"] and row["host"]["converged"] == row["target"]["converged"]
        print(f"  {row['transfer']:24s} {len(row['target_solves']):6d} {hi:>24s} {ti:>24s} "
              f"{row['max_err_norm_diff']:10.2e} {pil.get('pil.ogk_blt_solve.insn_max') or 0:11d} "
              f"{pil.get('pil.ogk_blt_solve.stack_bytes') or 0:7d} "
              f"{'yes' if row['target']['converged'] else 'no':>5s}")
    if a.json:
        Path(a.json).write_text(json.dumps(doc, indent=1, default=float))
    print("host and target agree" if ok else "host and target DIFFER")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
