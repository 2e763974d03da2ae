"""A planar proximity approach: from a start state to a hold point at rest in the Hill frame, outside a
keep-out disc, with the vehicle of dynamics.Vehicle (SI throughout)."""
from __future__ import annotations

import dataclasses

import numpy as np

from .dynamics import FloatArray, Vehicle


@dataclasses.dataclass(frozen=True)
class Approach:
    mean_motion_rad_s: float                #: n of the target's circular orbit [rad/s]
    vehicle: Vehicle
    start: tuple[float, float, float, float]  #: (x, y, v_x, v_y) at t = 0 [m, m, m/s, m/s]
    hold_point_m: tuple[float, float]       #: (x, y) where the approach ends at rest [m]
    keepout_center_m: tuple[float, float]   #: centre of the keep-out disc [m]
    keepout_radius_m: float                 #: its radius [m] (0: none)
    horizon_s: tuple[float, float]          #: bounds of the free final time [s]
    objective: str = "min-fuel"             #: "min-fuel" (m_0 - m_N) or "min-time" (t_f)
    nodes: int = 20                         #: N subintervals, controls linear between the N + 1 nodes
    rk4_steps: int = 8                      #: RK4 steps per subinterval

    @property
    def s0(self) -> FloatArray:
        return np.array([*self.start, self.vehicle.initial_mass_kg])

    @property
    def terminal(self) -> FloatArray:
        """(x, y, v_x, v_y) at t_f."""
        return np.array([*self.hold_point_m, 0.0, 0.0])
