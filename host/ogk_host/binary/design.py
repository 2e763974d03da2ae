"""The ground's convergence stage (Xiong & Wang, sec. III.D): a guess of ogk_host.binary.guess corrected by
the flight kernel's NRPC (ogk_blt_solve) in the realistic model, directly or, when that fails, by
continuation on the perturbations (SRP and the solar tide scaled from 0 to 1: the guess stage's model has
neither, and over a multi-TU coast SRP moves the spacecraft by ~0.1 LU, more than a Newton step from an
impulsive guess can absorb). Normalised units (docs/blt.md)."""
from __future__ import annotations

import dataclasses
from typing import Any

from ogk.bindings.blt import LM, NRPC, Blt, BltReport, Transfer

from .dynamics import Model
from .guess import Guess, kernel_config

CORRECTORS = {"nrpc": NRPC, "lm": LM}
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
