"""The binary family's dispersions (Xiong & Wang, Table 3; convergence_run.py's module doc): run i flies
level p = levels_percent[i mod L], and every BLT parameter and the departure is perturbed by
p xi, xi ~ N(0, sigma_fraction^2) clipped to [-1, 1]; and how a campaign's records show them
(ogk.sil.dispersion_check).

Records (naming rule disp.<[dispersions] key>): disp.levels_percent, the run's level;
disp.sigma_fraction[j], the normalised perturbations xi *as applied*, recovered from the perturbed
problem against the nominal: the 6 A/B components of each burn (relative to |[A; B]|), then the
duration of every segment (relative), then the departure's ignition-time shift (relative to the
first burn's duration, from the departure's longitude on its circle). A coast's A/B entries are
not perturbed (xi drawn and unused), so they are not recorded.
"""
from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any, Protocol

import numpy as np

from ogk.sil.dispersion_check import Cycle, Declaration, Declared, Gaussian

if TYPE_CHECKING:
    from ogk_bindings.blt import Transfer

LEVEL_KEY = "disp.levels_percent"


class Nominal(Protocol):
    """What the dispersions read of convergence_run.Nominal (a protocol, so that this module does not
    import convergence_run.py, which imports it)."""

    layout: Any           #: the chain's layout: .kinds, "burn" or a coast per segment
    transfer: Any         #: the nominal Transfer
    circle_radius: float  #: the binary's circle radius [normalised]


def n_applied(nominal: "Nominal") -> int:
    """Perturbations applied per run: 6 per burn, 1 per segment, 1 departure."""
    kinds = nominal.layout.kinds
    return 6 * sum(1 for k in kinds if k == "burn") + len(kinds) + 1


def record_keys(nominal: "Nominal") -> list[str]:
    return [LEVEL_KEY] + [f"disp.sigma_fraction[{j}]" for j in range(n_applied(nominal))]


def applied_record(nominal: "Nominal", level: float, guess: "Transfer") -> dict[str, Any]:
    """The disp.* keys of a run: its level and the xi its perturbed problem carries (module doc)."""
    from ogk_host.binary.guess import Circle
    tr = nominal.transfer
    xi: list[float] = []
    for k, kind in enumerate(nominal.layout.kinds):
        if kind == "burn":
            scale = float(np.linalg.norm(tr.segments[k, 0:6]))
            xi += ((guess.segments[k, 0:6] - tr.segments[k, 0:6]) / (level * scale)).tolist()
        xi.append((float(guess.segments[k, 6]) / float(tr.segments[k, 6]) - 1.0) / level)
    lon0 = math.atan2(tr.x0[1], tr.x0[0])
    dlon = math.remainder(math.atan2(guess.x0[1], guess.x0[0]) - lon0, 2.0 * math.pi)
    shift = dlon / Circle(nominal.circle_radius).synodic_rate
    xi.append(shift / (level * float(tr.segments[0, 6])))
    return {LEVEL_KEY: 100.0 * level, **{f"disp.sigma_fraction[{j}]": float(v)
                                         for j, v in enumerate(xi)}}


def declared(table: dict[str, Any], nominal: "Nominal", levels_percent: tuple[float, ...],
             sigma_fraction: float) -> Declaration:
    """levels_percent: flown in turn (run i: level i mod L); sigma_fraction: each applied xi a
    Gaussian of that sigma clipped to [-1, 1] (the campaign's levels and sigma: the scenario's
    unless --perturbation / --sigma-fraction say otherwise)."""
    return Declaration(table, (
        Declared("levels_percent", Cycle(tuple(float(v) for v in levels_percent))),
        Declared("sigma_fraction", Gaussian(float(sigma_fraction), clip=(-1.0, 1.0)),
                 size=n_applied(nominal))))
