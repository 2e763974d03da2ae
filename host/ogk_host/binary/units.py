"""Normalised units of the binary-asteroid model (Xiong & Wang, eq. 13, with the erratum of
../shared/seeds/README.md: the time unit is T_o / (2 pi), not T_o).

    LU  = D                 the separation of the two bodies [m]
    TU  = T_o / (2 pi)      so that the synodic frame turns at omega = 1 rad/TU
    VU  = LU / TU           [m/s]
    ACC = LU / TU^2         [m/s^2]
    mu  = M2 / (M1 + M2)    eq. (1), from the masses

With these units G (M1 + M2) = 1 LU^3/TU^2 is *implied* by the period and the separation (Kepler's third
law of the mutual orbit: omega^2 D^3 = G (M1 + M2)); it is not G times Table 1's masses. The two differ
(Table 1's figures are mutually inconsistent, seeds/README.md "002"): `Units.gm_mismatch` gives the figure,
docs/design/blt-ground.md prints it. The model keeps the period and the separation exact (they fix the frame's
rotation and the bodies' positions) and takes mu from the masses, as docs/design/blt.md section 1 prescribes.
"""
from __future__ import annotations

import dataclasses
import math

#: CODATA 2018 Newtonian constant of gravitation [m^3 kg^-1 s^-2]: only for the G (M1 + M2) check.
G_CODATA2018 = 6.67430e-11


@dataclasses.dataclass(frozen=True)
class Units:
    """Scale factors SI -> normalised: divide an SI value by the unit."""

    length_m: float     #: LU = D [m]
    time_s: float       #: TU = T_o / (2 pi) [s]
    mu: float           #: M2 / (M1 + M2) [-], eq. (1)
    total_mass_kg: float    #: M1 + M2 [kg] (Table 1)

    @classmethod
    def from_system(cls, separation_m: float, period_s: float, primary_mass_kg: float,
                    secondary_mass_kg: float) -> "Units":
        """The units of eq. (13) (erratum: T_o / (2 pi)) and mu of eq. (1)."""
        total = primary_mass_kg + secondary_mass_kg
        return cls(length_m=separation_m, time_s=period_s / (2.0 * math.pi),
                   mu=secondary_mass_kg / total, total_mass_kg=total)

    @property
    def velocity_m_s(self) -> float:
        """VU = LU / TU [m/s]."""
        return self.length_m / self.time_s

    @property
    def acceleration_m_s2(self) -> float:
        """ACC = LU / TU^2 [m/s^2]."""
        return self.length_m / self.time_s ** 2

    @property
    def gm_implied_m3_s2(self) -> float:
        """G (M1 + M2) that the units make 1: LU^3 / TU^2 [m^3/s^2] (Kepler's third law)."""
        return self.length_m ** 3 / self.time_s ** 2

    @property
    def gm_table_m3_s2(self) -> float:
        """G (M1 + M2) from Table 1's masses and CODATA 2018 G [m^3/s^2]."""
        return G_CODATA2018 * self.total_mass_kg

    @property
    def gm_mismatch(self) -> float:
        """gm_implied / gm_table - 1 [-]: how far Table 1's period and separation are from its masses."""
        return self.gm_implied_m3_s2 / self.gm_table_m3_s2 - 1.0

    @property
    def period_from_masses_s(self) -> float:
        """The mutual period Kepler's law gives for Table 1's masses and separation [s]."""
        return 2.0 * math.pi * math.sqrt(self.length_m ** 3 / self.gm_table_m3_s2)
