"""Canonical units of the LEO-to-GEO ground tools and SI <-> canonical conversions.

DU = target radius R_f, TU = sqrt(DU^3 / mu) (so mu = 1 and the target circular speed is 1 VU),
VU = DU / TU. For the paper's data: DU = 42164 km, TU = 13713.4 s, VU = 3074.7 m/s.

State x = [r, xi, phi, v_r, v_t, v_n, t] has the scale X = [DU, 1, 1, VU, VU, VU, TU]. Costates are
normalised so that the Hamiltonian per unit time, h = lambda^T dx/dt, equals -1 (minimum time, see
docs/design/vtd-nog.md); h is dimensionless in both systems, so lambda_i[SI] = lambda_i[canonical] * TU / X_i.
"""
from __future__ import annotations

import dataclasses
import math

import numpy as np
from numpy.typing import NDArray

from .scenario import OrbitInjectionScenario

FloatArray = NDArray[np.float64]


@dataclasses.dataclass(frozen=True)
class CanonicalUnits:
    """DU, TU (and VU = DU / TU) in SI."""

    length_m: float   #: DU [m]
    time_s: float     #: TU [s]

    @classmethod
    def for_scenario(cls, scn: OrbitInjectionScenario) -> "CanonicalUnits":
        """DU = R_f, TU = sqrt(R_f^3 / mu)."""
        du = scn.target_radius_m
        return cls(length_m=du, time_s=math.sqrt(du**3 / scn.mu_m3_s2))

    @property
    def velocity_m_s(self) -> float:
        """VU = DU / TU [m/s]."""
        return self.length_m / self.time_s

    @property
    def accel_m_s2(self) -> float:
        """DU / TU^2 [m/s^2]."""
        return self.length_m / self.time_s**2

    @property
    def state_scale(self) -> FloatArray:
        """X: SI value of one canonical unit of each state component."""
        du, tu, vu = self.length_m, self.time_s, self.velocity_m_s
        return np.array([du, 1.0, 1.0, vu, vu, vu, tu])

    def state_to_si(self, x: FloatArray) -> FloatArray:
        """Canonical state (..., 7) -> SI."""
        return np.asarray(x) * self.state_scale

    def state_from_si(self, x_si: FloatArray) -> FloatArray:
        """SI state (..., 7) -> canonical."""
        return np.asarray(x_si) / self.state_scale

    def costate_to_si(self, lam: FloatArray) -> FloatArray:
        """Canonical costate (..., 7) -> SI [s / unit of x_i]."""
        return np.asarray(lam) * self.time_s / self.state_scale

    def costate_from_si(self, lam_si: FloatArray) -> FloatArray:
        """SI costate (..., 7) -> canonical."""
        return np.asarray(lam_si) * self.state_scale / self.time_s
