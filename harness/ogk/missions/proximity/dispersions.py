"""The proximity family's dispersions ([dispersions] of the scenario, Gaussian sigmas) drawn from the
run's stream (ogk.sil.seeds.run_generator) in a fixed order: six standard normals at the start (the
start's x, y, v_x, v_y errors, the thrust-level bias, the initial mass error), then the thrust-angle
noise, one draw per replan period in flight order (held over the period). `--unperturbed` flies none.

Records (the naming rule of ogk.sil.dispersion_check): disp.initial_position_sigma_m[0..1],
disp.initial_velocity_sigma_m_s[0..1], disp.thrust_level_sigma, disp.initial_mass_sigma_kg (the values
applied), disp.thrust_angle_sigma_rad (the first draw flown; the later draws come from the same
generator)."""
from __future__ import annotations

import dataclasses
from typing import Any

import numpy as np
from numpy.typing import NDArray
from ogk_host.proximity.scenario import Dispersions, ProximityScenario

from ogk.sil.dispersion_check import Constant, Declaration, Declared, Gaussian
from ogk.sil.seeds import run_generator

POSITION = "initial_position_sigma_m"
VELOCITY = "initial_velocity_sigma_m_s"
THRUST = "thrust_level_sigma"
ANGLE = "thrust_angle_sigma_rad"
MASS = "initial_mass_sigma_kg"


@dataclasses.dataclass
class Draw:
    """One run's dispersions: the start's errors, the bias, the mass error, and its angle noise."""

    position_m: tuple[float, float]
    velocity_m_s: tuple[float, float]
    thrust_bias: float
    mass_kg: float
    angle_sigma_rad: float
    rng: np.random.Generator
    angles: dict[int, float] = dataclasses.field(default_factory=dict)
    first_angle_rad: float | None = None

    def angle(self, k: int) -> float:
        """The thrust-angle offset of replan period k (drawn the first time it is asked for)."""
        if k not in self.angles:
            self.angles[k] = float(self.rng.normal(0.0, self.angle_sigma_rad)) if self.angle_sigma_rad > 0 else 0.0
        if self.first_angle_rad is None:
            self.first_angle_rad = self.angles[k]
        return self.angles[k]

    def record(self) -> dict[str, Any]:
        return {f"disp.{POSITION}[0]": self.position_m[0], f"disp.{POSITION}[1]": self.position_m[1],
                f"disp.{VELOCITY}[0]": self.velocity_m_s[0], f"disp.{VELOCITY}[1]": self.velocity_m_s[1],
                f"disp.{THRUST}": self.thrust_bias, f"disp.{MASS}": self.mass_kg,
                f"disp.{ANGLE}": self.first_angle_rad}


def flown(d: Dispersions, perturbed: bool) -> Dispersions:
    """The sigmas a flight draws with: the scenario's, or all 0 unperturbed."""
    return d if perturbed else Dispersions(0.0, 0.0, 0.0, 0.0, 0.0)


def draw(d: Dispersions, seed: int) -> Draw:
    rng = run_generator(seed)
    z = rng.standard_normal(6)
    return Draw(position_m=(d.initial_position_sigma_m * float(z[0]), d.initial_position_sigma_m * float(z[1])),
                velocity_m_s=(d.initial_velocity_sigma_m_s * float(z[2]), d.initial_velocity_sigma_m_s * float(z[3])),
                thrust_bias=d.thrust_level_sigma * float(z[4]), mass_kg=d.initial_mass_sigma_kg * float(z[5]),
                angle_sigma_rad=d.thrust_angle_sigma_rad, rng=rng)


def draw_records(d: Dispersions, run_ids: NDArray[np.int64], run_seeds: NDArray[np.uint64]) -> list[dict[str, Any]]:
    """The disp.* keys of runs without flying them (the first angle draw included)."""
    out = []
    for s in run_seeds:
        dr = draw(d, int(s))
        dr.angle(0)
        out.append(dr.record())
    return out


def declared(scenario: ProximityScenario, table: dict[str, Any], perturbed: bool) -> Declaration:
    d = flown(scenario.dispersions, perturbed)

    def dist(sigma: float) -> Gaussian | Constant:
        return Gaussian(sigma) if sigma > 0.0 else Constant(0.0)
    return Declaration(table, (
        Declared(POSITION, dist(d.initial_position_sigma_m), size=2),
        Declared(VELOCITY, dist(d.initial_velocity_sigma_m_s), size=2),
        Declared(THRUST, dist(d.thrust_level_sigma)),
        Declared(ANGLE, dist(d.thrust_angle_sigma_rad)),
        Declared(MASS, dist(d.initial_mass_sigma_kg))))
