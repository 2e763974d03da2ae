"""The rendezvous family's dispersions (Starek & Kolmanovsky 2012, Table A.1, sec. 3.5): the
thrust-angle noise N(0, sigma_alpha_T), drawn in flight order from the run's stream
(ogk.sil.seeds.run_generator), held over a control subinterval or over a fixed draw period
(closed_loop.fly_run), and how a campaign's records show it (ogk.sil.dispersion_check).

Record (naming rule disp.<[dispersions] key>): disp.thrust_angle_sigma_rad, the offset of the
flight's first draw as the truth flies it (None when the flight stopped before its first
subinterval); thrust_angle_draw_period_s is a parameter of the noise (how often it is redrawn),
not drawn itself. The first draws of independent runs are independent N(0, sigma^2): one value
per run is what the check tests (the later draws of a run come from the same generator call).
"""
from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import NDArray

from ogk_host.rendezvous.scenario import RendezvousScenario

from ogk.sil.dispersion_check import Constant, Declaration, Declared, Gaussian, Parameter
from ogk.sil.seeds import run_generator

FIRST_OFFSET_KEY = "disp.thrust_angle_sigma_rad"


class AngleNoise:
    """The thrust-angle offsets of one flight: draw k (a subinterval or a draw period) is drawn
    from the run's generator the first time it is asked for, N(0, sigma^2); sigma 0 draws nothing
    (every offset 0)."""

    def __init__(self, sigma_rad: float, seed: int) -> None:
        self.sigma_rad = float(sigma_rad)
        self._rng = run_generator(seed)   # Generator(PCG64(seed)): the engine's stream of one run
        self._draws: dict[int, float] = {}
        self.first_rad: float | None = None   #: the first offset given to the flight

    def offset(self, k: int) -> float:
        if k not in self._draws:
            self._draws[k] = (float(self._rng.normal(0.0, self.sigma_rad)) if self.sigma_rad > 0.0
                              else 0.0)
        if self.first_rad is None:
            self.first_rad = self._draws[k]
        return self._draws[k]


def sigma_flown(scenario: RendezvousScenario, perturbed: bool) -> float:
    """The noise a flight draws: the scenario's sigma when perturbed, else none."""
    return scenario.dispersions.thrust_angle_sigma_rad if perturbed else 0.0


def draw_records(scenario: RendezvousScenario, perturbed: bool, run_ids: NDArray[np.int64],
                 run_seeds: NDArray[np.uint64]) -> list[dict[str, Any]]:
    """The disp.* keys of runs without flying them: the first offset each flight would be given."""
    sigma = sigma_flown(scenario, perturbed)
    return [{FIRST_OFFSET_KEY: AngleNoise(sigma, int(s)).offset(0)} for s in run_seeds]


def declared(scenario: RendezvousScenario, table: dict[str, Any], perturbed: bool) -> Declaration:
    """thrust_angle_sigma_rad: zero-mean Gaussian (a constant 0 when unperturbed or 0);
    thrust_angle_draw_period_s: its parameter."""
    sigma = sigma_flown(scenario, perturbed)
    return Declaration(table, (
        Declared("thrust_angle_sigma_rad", Gaussian(sigma) if sigma > 0.0 else Constant(0.0)),
        Declared("thrust_angle_draw_period_s", Parameter(
            "thrust_angle_sigma_rad", "how often the noise is redrawn: 0 = every subinterval"))))
