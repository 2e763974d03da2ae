"""The proximity approach's open-loop OCP solved by IPOPT (the ground reference of the kernel's second NMPC
problem): the kernel's transcription (N equal subintervals of the free horizon, (alpha, w) linear between
the nodes, RK4 with the controls at the stage times), the keep-out disc at every RK4 step end, the hold point
at rest at t_f, the propellant limit m_N >= dry mass.

Solved in normalised units (LU = 1 km, TU = 1 / n, MU = m_0) for IPOPT's scaling; the solution is returned
in SI."""
from __future__ import annotations

import dataclasses
import math

import casadi as ca
import numpy as np

from .dynamics import NX, FloatArray, casadi_rhs
from .problem import Approach

LU_M = 1000.0


@dataclasses.dataclass(frozen=True)
class Solution:
    t_f_s: float
    states: FloatArray      #: (N + 1) x 5 node states [m, m, m/s, m/s, kg]
    controls: FloatArray    #: (N + 1) x 2 node controls (alpha [rad], w [-])
    fuel_kg: float
    delta_v_m_s: float      #: v_e ln(m_0 / m_N): the integral of the thrust acceleration
    success: bool
    status: str


def solve(ap: Approach, guess: Solution | None = None, tol: float = 1e-10) -> Solution:
    """The OCP from the guess (None: the detour guess below)."""
    n = ap.mean_motion_rad_s
    tu, mu_kg = 1.0 / n, ap.vehicle.initial_mass_kg
    thrust = ap.vehicle.thrust_max_n / (mu_kg * LU_M / tu ** 2)
    ve = ap.vehicle.exhaust_velocity_m_s / (LU_M / tu)
    scale = np.array([LU_M, LU_M, LU_M / tu, LU_M / tu, mu_kg])
    f = casadi_rhs()
    N, K = ap.nodes, ap.rk4_steps

    opti = ca.Opti()
    S = opti.variable(NX, N + 1)
    U = opti.variable(2, N + 1)
    T = opti.variable()
    opti.subject_to(S[:, 0] == ap.s0 / scale)
    c = np.array(ap.keepout_center_m) / LU_M
    R = ap.keepout_radius_m / LU_M
    h = T / N
    for k in range(N):
        s = S[:, k]
        for i in range(K):
            def u_at(frac: float) -> tuple[ca.MX, ca.MX]:
                return (U[0, k] + (U[0, k + 1] - U[0, k]) * frac, U[1, k] + (U[1, k + 1] - U[1, k]) * frac)
            a0, am, a1 = (u_at((i + q) / K) for q in (0.0, 0.5, 1.0))
            dt = h / K
            k1 = f(s, a0[0], a0[1], 1.0, thrust, ve)
            k2 = f(s + 0.5 * dt * k1, am[0], am[1], 1.0, thrust, ve)
            k3 = f(s + 0.5 * dt * k2, am[0], am[1], 1.0, thrust, ve)
            k4 = f(s + dt * k3, a1[0], a1[1], 1.0, thrust, ve)
            s = s + dt / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4)
            if R > 0.0:
                opti.subject_to((s[0] - c[0]) ** 2 + (s[1] - c[1]) ** 2 >= R * R)
        opti.subject_to(S[:, k + 1] == s)
    opti.subject_to(S[0:4, N] == ap.terminal / scale[:4])
    opti.subject_to(S[4, N] >= ap.vehicle.dry_mass_kg / mu_kg)
    opti.subject_to(opti.bounded(0.0, U[1, :], 1.0))
    opti.subject_to(opti.bounded(ap.horizon_s[0] / tu, T, ap.horizon_s[1] / tu))
    opti.minimize(T if ap.objective == "min-time" else S[4, 0] - S[4, N])

    g = guess or detour_guess(ap)
    opti.set_initial(S, (g.states / scale).T)
    opti.set_initial(U, g.controls.T)
    opti.set_initial(T, g.t_f_s / tu)
    opti.solver("ipopt", {"print_time": False}, {"tol": tol, "print_level": 0, "max_iter": 3000,
                                                  "constr_viol_tol": 1e-12})
    try:
        sol = opti.solve()
        ok, st = True, "Solve_Succeeded"
    except RuntimeError as exc:
        sol, ok, st = opti.debug, False, str(exc).splitlines()[-1]
    states = np.asarray(sol.value(S)).T * scale
    controls = np.asarray(sol.value(U)).T
    m_n = float(states[-1, 4])
    return Solution(t_f_s=float(sol.value(T)) * tu, states=states, controls=controls,
                    fuel_kg=ap.vehicle.initial_mass_kg - m_n,
                    delta_v_m_s=ap.vehicle.exhaust_velocity_m_s * math.log(ap.vehicle.initial_mass_kg / m_n),
                    success=ok, status=st)


def detour_guess(ap: Approach) -> Solution:
    """Positions blended from the start to the hold point around the keep-out disc (a bulge away from its
    centre, 1.5 radii), the velocities their derivatives, half throttle along the path, t_f mid-bounds."""
    N = ap.nodes
    t_f = 0.5 * (ap.horizon_s[0] + ap.horizon_s[1])
    tau = np.linspace(0.0, 1.0, N + 1)
    p0, p1 = np.array(ap.start[:2]), np.array(ap.hold_point_m)
    line = p0[None, :] + (p1 - p0)[None, :] * tau[:, None]
    c = np.array(ap.keepout_center_m)
    mid = 0.5 * (p0 + p1)
    away = mid - c
    if np.linalg.norm(away) < 1e-9:
        d = p1 - p0
        away = np.array([-d[1], d[0]])
    away = away / np.linalg.norm(away)
    bulge = max(0.0, 1.5 * ap.keepout_radius_m - float(np.linalg.norm(mid - c)))
    pos = line + bulge * np.sin(math.pi * tau)[:, None] * away[None, :]
    vel = np.gradient(pos, tau * t_f, axis=0)
    vel[-1] = 0.0
    mass = np.full(N + 1, ap.vehicle.initial_mass_kg)
    states = np.column_stack([pos, vel, mass])
    heading = np.arctan2(vel[:, 1], vel[:, 0])
    controls = np.column_stack([heading, np.full(N + 1, 0.5)])
    return Solution(t_f_s=t_f, states=states, controls=controls, fuel_kg=0.0, delta_v_m_s=0.0,
                    success=False, status="guess")
