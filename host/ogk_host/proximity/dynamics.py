"""Planar proximity operations about a target on a circular orbit: the Clohessy-Wiltshire (Hill) equations
with a throttled engine of fixed exhaust velocity (issue 33: the NMPC solver's second problem).

Hill frame centred on the target: x radial (outward), y along-track (the target's velocity), n the target's
mean motion. State s = (x, y, v_x, v_y, m), control (alpha, w): thrust T_max w along alpha from the radial axis
(0: radially outward, pi/2: along-track; the rendezvous family's convention), w in [0, 1]:

    x'' = 3 n^2 x + 2 n y' + (w T_max / m) cos(alpha)
    y'' =          -2 n x' + (w T_max / m) sin(alpha)
    m'  = -w T_max / v_e,      v_e = g0 I_sp

Everything here is in SI. `coast_stm` is the closed form of the unforced motion (the independent reference
of the integrators); `rk4_interval` is the transcription's integrator (the control linear over a
subinterval, evaluated at the RK4 stage times), the twin of the kernel's.
"""
from __future__ import annotations

import dataclasses
import math

import casadi as ca
import numpy as np
from numpy.typing import NDArray

FloatArray = NDArray[np.float64]
NX = 5


@dataclasses.dataclass(frozen=True)
class Vehicle:
    """The chaser's engine and masses."""

    thrust_max_n: float         #: T_max [N]
    exhaust_velocity_m_s: float  #: v_e = g0 I_sp [m/s]
    initial_mass_kg: float      #: m_0 [kg]
    dry_mass_kg: float          #: [kg]


def rhs(s: FloatArray, alpha: float, w: float, n: float, veh: Vehicle) -> FloatArray:
    """ds/dt of the forced CW equations (module doc)."""
    x, _, vx, vy, m = s
    acc = w * veh.thrust_max_n / m
    return np.array([vx, vy, 3.0 * n * n * x + 2.0 * n * vy + acc * math.cos(alpha),
                     -2.0 * n * vx + acc * math.sin(alpha), -w * veh.thrust_max_n / veh.exhaust_velocity_m_s])


def casadi_rhs() -> ca.Function:
    """The same right-hand side for CasADi: f(s[5], alpha, w, n, T_max, v_e) -> ds[5]."""
    s = ca.SX.sym("s", NX)
    alpha, w, n, thrust, ve = (ca.SX.sym(k) for k in ("alpha", "w", "n", "thrust", "ve"))
    acc = w * thrust / s[4]
    ds = ca.vertcat(s[2], s[3], 3.0 * n * n * s[0] + 2.0 * n * s[3] + acc * ca.cos(alpha),
                    -2.0 * n * s[2] + acc * ca.sin(alpha), -w * thrust / ve)
    return ca.Function("cw_rhs", [s, alpha, w, n, thrust, ve], [ds])


def coast_stm(n: float, t: float) -> FloatArray:
    """Phi(t) (4 x 4) of the unforced CW equations, (x, y, v_x, v_y)(t) = Phi(t) (x, y, v_x, v_y)(0)
    (Clohessy & Wiltshire 1960; planar part)."""
    c, s = math.cos(n * t), math.sin(n * t)
    return np.array([[4.0 - 3.0 * c, 0.0, s / n, 2.0 * (1.0 - c) / n],
                     [6.0 * (s - n * t), 1.0, -2.0 * (1.0 - c) / n, (4.0 * s - 3.0 * n * t) / n],
                     [3.0 * n * s, 0.0, c, 2.0 * s],
                     [-6.0 * n * (1.0 - c), 0.0, -2.0 * s, 4.0 * c - 3.0]])


def rk4_interval(s0: FloatArray, u0: tuple[float, float], u1: tuple[float, float], h: float, steps: int,
                 n: float, veh: Vehicle) -> tuple[FloatArray, FloatArray]:
    """One subinterval of length h, the controls (alpha, w) linear from u0 to u1, `steps` RK4 steps with the
    controls at the stage times. Returns the end state and the states at the step ends (steps x 5)."""
    s = np.asarray(s0, dtype=np.float64)
    dt = h / steps
    ends = np.empty((steps, NX))

    def u_at(frac: float) -> tuple[float, float]:
        return (u0[0] + (u1[0] - u0[0]) * frac, u0[1] + (u1[1] - u0[1]) * frac)

    for i in range(steps):
        a0, am, a1 = (u_at((i + c) / steps) for c in (0.0, 0.5, 1.0))
        k1 = rhs(s, *a0, n, veh)
        k2 = rhs(s + 0.5 * dt * k1, *am, n, veh)
        k3 = rhs(s + 0.5 * dt * k2, *am, n, veh)
        k4 = rhs(s + dt * k3, *a1, n, veh)
        s = s + dt / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4)
        ends[i] = s
    return s, ends
