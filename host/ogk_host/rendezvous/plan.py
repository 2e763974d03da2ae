"""A receding-horizon plan of the rendezvous NMPC (Starek & Kolmanovsky 2012, sec. 2.3), normalised units.

One plan is what one OCP solve returns and what the next solve starts from: N subintervals of equal length
h = horizon / N from the absolute time t0, the 5 node states (r, theta, v_r, v_theta, m) and the node
controls, piecewise linear between the nodes (sec. 2.3). Control columns: 0 the thrust angle alpha [rad]
from the local vertical; 1 (bounded-thrust and solar-electric cases only) the throttle w in [0, 1], the
fraction of the engine's maximum thrust T_max(r) (docs/design/nmpc.md, "Throttle"). The same layout is the kernel's
(ogk/nmpc.h), so a plan passes between the ground, the IPOPT peer and the flight code unchanged.
"""
from __future__ import annotations

import dataclasses

import numpy as np
from numpy.typing import NDArray

FloatArray = NDArray[np.float64]


@dataclasses.dataclass(frozen=True)
class Plan:
    t0: float                 #: absolute time of node 0 [TU]
    horizon: float            #: t_f - t0 [TU]
    states: FloatArray        #: node states (N + 1, 5)
    controls: FloatArray      #: node controls (N + 1, nu): alpha [rad], throttle [-] when nu = 2

    def __post_init__(self) -> None:
        if self.states.ndim != 2 or self.states.shape[1] != 5:
            raise ValueError(f"states must be (N + 1, 5), got {self.states.shape}")
        if self.controls.ndim != 2 or self.controls.shape[0] != self.states.shape[0]:
            raise ValueError(f"controls must be (N + 1, nu), got {self.controls.shape}")

    @property
    def nodes(self) -> int:
        """N, the number of subintervals."""
        return int(self.states.shape[0] - 1)

    @property
    def nu(self) -> int:
        return int(self.controls.shape[1])

    @property
    def t_f(self) -> float:
        return self.t0 + self.horizon

    @property
    def step(self) -> float:
        """h = horizon / N [TU]."""
        return self.horizon / self.nodes

    def node_times(self) -> FloatArray:
        return self.t0 + self.step * np.arange(self.nodes + 1)

    def control_at(self, t: float) -> FloatArray:
        """The piecewise-linear control at absolute time t (held at the end values outside the plan)."""
        s = np.clip((t - self.t0) / self.step, 0.0, float(self.nodes))
        k = min(int(s), self.nodes - 1)
        frac = s - k
        return (1.0 - frac) * self.controls[k] + frac * self.controls[k + 1]
