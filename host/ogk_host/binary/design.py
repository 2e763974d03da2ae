"""The ground's convergence stage (Xiong & Wang, sec. III.D): a guess of ogk_host.binary.guess corrected by
the flight kernel's NRPC (ogk_blt_solve) in the realistic model, directly or, when that fails, by
continuation on the perturbations (SRP and the solar tide scaled from 0 to 1: the guess stage's model has
neither, and over a multi-TU coast SRP moves the spacecraft by ~0.1 LU, more than a Newton step from an
impulsive guess can absorb). Normalised units (docs/design/blt.md)."""
from __future__ import annotations

import dataclasses
import math
from typing import Any

from ogk_bindings.blt import HYBRID, LM, NRPC, Blt, BltReport, Transfer

from .dynamics import Model
from .guess import Guess, kernel_config

CORRECTORS = {"nrpc": NRPC, "lm": LM, "hybrid": HYBRID}
JACOBIANS = {"central": 0, "variational": 1}


@dataclasses.dataclass
class Converged:
    transfer: Transfer
    report: BltReport
    steps: list[dict[str, Any]]        #: one entry per kernel solve: perturbation scale, status, iterations


def solve(model: Model, guess: Guess, *, corrector: str = "nrpc", jacobian: str = "variational",
          **fields: Any) -> tuple[Transfer, BltReport]:
    """One kernel solve of `guess` in `model` (fields: any other ogk_blt_config_t field)."""
    cfg = kernel_config(model, guess.layout, corrector=CORRECTORS[corrector], jacobian=JACOBIANS[jacobian],
                        **fields)
    return Blt(cfg).solve(guess.transfer)


def converge(model: Model, guess: Guess, *, corrector: str = "nrpc", jacobian: str = "variational",
             scales: tuple[float, ...] = (0.0, 0.25, 0.5, 0.75, 1.0), **fields: Any) -> Converged:
    """The guess corrected in `model`: directly, else through `scales` of its SRP and solar tide (each
    solve starts from the previous one's solution). The report is the last solve's."""
    steps: list[dict[str, Any]] = []
    sol, rep = solve(model, guess, corrector=corrector, jacobian=jacobian, **fields)
    steps.append(dict(scale=1.0, status=rep.status, iterations=rep.iterations, err_norm=rep.err_norm))
    if rep.converged or (model.srp_accel == 0.0 and model.sun_tidal == 0.0):
        return Converged(sol, rep, steps)
    current = guess
    for scale in scales:
        m = dataclasses.replace(model, srp_accel=scale * model.srp_accel, sun_tidal=scale * model.sun_tidal)
        sol, rep = solve(m, current, corrector=corrector, jacobian=jacobian, **fields)
        steps.append(dict(scale=scale, status=rep.status, iterations=rep.iterations, err_norm=rep.err_norm))
        if not rep.converged:
            break
        current = Guess(layout=guess.layout, transfer=sol, info=guess.info)
    return Converged(sol, rep, steps)


def thrust_continuation(model: Model, guess: Guess, base_thrust_accel: float, *, ratio: float = 1.1,
                        corrector: str = "lm", jacobian: str = "variational", **fields: Any) -> Converged:
    """The transfer at model.thrust_accel reached from a solution at base_thrust_accel: the guess is first
    converged at the base thrust (directly or by `converge`), then the thrust is stepped geometrically by at
    most `ratio` per solve, each solve warm-started from the previous solution with every burn time scaled
    by sqrt(a_previous / a_next) (eq. 26's scaling) and the mass flow scaled with the thrust. Beyond the paper:
    SBIG's guess (eqs. 26-28) only converges near the thrust it was built for."""
    target = model.thrust_accel
    flow_per_accel = model.mass_flow / target

    def at(accel: float) -> Model:
        return dataclasses.replace(model, thrust_accel=accel, mass_flow=flow_per_accel * accel)
    result = converge(at(base_thrust_accel), guess, corrector=corrector, jacobian=jacobian, **fields)
    steps = [dict(thrust_accel=base_thrust_accel, **st) for st in result.steps]
    n = max(1, math.ceil(abs(math.log(target / base_thrust_accel)) / math.log(ratio)))
    current, accel = result, base_thrust_accel
    for k in range(1, n + 1):
        if not current.report.converged:
            break
        nxt = base_thrust_accel * (target / base_thrust_accel) ** (k / n)
        tr = current.transfer
        seg = tr.segments.copy()
        for i, kind in enumerate(guess.layout.kinds):
            if kind == "burn":
                seg[i, 6] *= math.sqrt(accel / nxt)
        warm = Guess(layout=guess.layout, transfer=dataclasses.replace(tr, segments=seg), info=guess.info)
        current = converge(at(nxt), warm, corrector=corrector, jacobian=jacobian, **fields)
        steps += [dict(thrust_accel=nxt, **st) for st in current.steps]
        accel = nxt
    return Converged(current.transfer, current.report, steps)

