"""The ground peer of the kernel's replan: IPOPT on the kernel's transcription (the twin of
ogk_host.proximity.ocp.solve, in the same normalised units LU = 1 km, TU = 1 / n, MU = m_0), built
once with the measured state and the horizon's bounds as parameters so that a receding-horizon
flight re-solves it warm from the shifted plan in a fraction of a second (`ogk mc --solver ipopt`).

N equal subintervals of the free horizon T, (alpha, w) linear between the N + 1 nodes, K RK4 steps
per subinterval with the controls at the stage times, the keep-out discs at every RK4 step end, the
hold point at rest at t_f, the propellant limit m_N >= the dry mass, w in [0, 1]; minimum fuel
(m_0 - m_N + time_weight T) or minimum time (T)."""
from __future__ import annotations

import dataclasses

import casadi as ca
import numpy as np
from numpy.typing import NDArray
from ogk_host.proximity.dynamics import NX, casadi_rhs

FloatArray = NDArray[np.float64]


@dataclasses.dataclass(frozen=True)
class PeerProblem:
    """The normalised problem (every field in LU, TU, MU; n = 1)."""

    thrust: float                        #: T_max [MU LU/TU^2]
    exhaust_velocity: float              #: v_e [LU/TU]
    hold: tuple[float, float]            #: [LU]
    keepout: tuple[tuple[float, float, float], ...]   #: (x_c, y_c, R) [LU] of each disc
    mass_min: float                      #: dry mass [MU]
    objective: str                       #: "min-fuel" or "min-time"
    time_weight: float                   #: min-fuel: J = m_0 - m_N + time_weight T [MU/TU]
    max_sweep: float                     #: |alpha_{k+1} - alpha_k| bound [rad] (0: none; the kernel's max_sweep)
    nodes: int
    rk4_steps: int


@dataclasses.dataclass(frozen=True)
class PeerSolution:
    horizon: float          #: T [TU]
    states: FloatArray      #: (N + 1, 5) normalised
    controls: FloatArray    #: (N + 1, 2): alpha [rad], w [-]
    converged: bool
    status: str
    iterations: int


class PeerSolver:
    """One nlpsol of the problem, parameters (s_0 [5], T_min, T_max)."""

    def __init__(self, pb: PeerProblem, tol: float = 1e-8, max_iter: int = 500) -> None:
        self.pb = pb
        f = casadi_rhs()
        N, K = pb.nodes, pb.rk4_steps
        S = ca.SX.sym("S", NX, N + 1)
        U = ca.SX.sym("U", 2, N + 1)
        T = ca.SX.sym("T")
        P = ca.SX.sym("P", NX + 2)
        g: list[ca.SX] = [S[:, 0] - P[:NX]]
        lbg: list[float] = [0.0] * NX
        ubg: list[float] = [0.0] * NX
        h = T / N
        dt = h / K
        for k in range(N):
            s = S[:, k]
            for i in range(K):
                def u_at(frac: float, k: int = k) -> tuple[ca.SX, ca.SX]:
                    return (U[0, k] + (U[0, k + 1] - U[0, k]) * frac, U[1, k] + (U[1, k + 1] - U[1, k]) * frac)
                a0, am, a1 = (u_at((i + q) / K) for q in (0.0, 0.5, 1.0))
                k1 = f(s, a0[0], a0[1], 1.0, pb.thrust, pb.exhaust_velocity)
                k2 = f(s + 0.5 * dt * k1, am[0], am[1], 1.0, pb.thrust, pb.exhaust_velocity)
                k3 = f(s + 0.5 * dt * k2, am[0], am[1], 1.0, pb.thrust, pb.exhaust_velocity)
                k4 = f(s + dt * k3, a1[0], a1[1], 1.0, pb.thrust, pb.exhaust_velocity)
                s = s + dt / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4)
                for (xc, yc, r) in pb.keepout:
                    if r > 0.0:
                        g.append((s[0] - xc) ** 2 + (s[1] - yc) ** 2)
                        lbg.append(r * r)
                        ubg.append(ca.inf)
            g.append(S[:, k + 1] - s)
            lbg += [0.0] * NX
            ubg += [0.0] * NX
            if pb.max_sweep > 0.0:
                g.append(U[0, k + 1] - U[0, k])
                lbg.append(-pb.max_sweep)
                ubg.append(pb.max_sweep)
        g.append(S[0:4, N] - ca.DM([pb.hold[0], pb.hold[1], 0.0, 0.0]))
        lbg += [0.0] * 4
        ubg += [0.0] * 4
        g.append(S[4, N])
        lbg.append(pb.mass_min)
        ubg.append(ca.inf)
        g.append(T - P[NX])
        lbg.append(0.0)
        ubg.append(ca.inf)
        g.append(P[NX + 1] - T)
        lbg.append(0.0)
        ubg.append(ca.inf)
        z = ca.vertcat(ca.vec(S), ca.vec(U), T)
        obj = T if pb.objective == "min-time" else S[4, 0] - S[4, N] + pb.time_weight * T
        nlp = {"x": z, "p": P, "f": obj, "g": ca.vertcat(*g)}
        self._solver = ca.nlpsol("prox_peer", "ipopt", nlp, {
            "print_time": False, "error_on_fail": False,
            "ipopt": {"print_level": 0, "tol": tol, "max_iter": max_iter, "constr_viol_tol": 1e-10,
                      "sb": "yes"}})
        self._lbg = np.array(lbg)
        self._ubg = np.array(ubg)
        nz = NX * (N + 1) + 2 * (N + 1) + 1
        lbx = np.full(nz, -np.inf)
        ubx = np.full(nz, np.inf)
        w0 = NX * (N + 1)
        lbx[w0 + 1: w0 + 2 * (N + 1): 2] = 0.0      # U is (2, N+1) column-major: w at odd offsets
        ubx[w0 + 1: w0 + 2 * (N + 1): 2] = 1.0
        lbx[-1] = 0.0
        self._lbx, self._ubx = lbx, ubx

    def solve(self, s0: FloatArray, horizon_bounds: tuple[float, float], guess_horizon: float,
              guess_states: FloatArray, guess_controls: FloatArray) -> PeerSolution:
        N = self.pb.nodes
        z0 = np.concatenate([np.asarray(guess_states, dtype=np.float64).reshape(-1),
                             np.asarray(guess_controls, dtype=np.float64).reshape(-1), [guess_horizon]])
        p = np.concatenate([np.asarray(s0, dtype=np.float64), horizon_bounds])
        res = self._solver(x0=z0, p=p, lbx=self._lbx, ubx=self._ubx, lbg=self._lbg, ubg=self._ubg)
        stats = self._solver.stats()
        z = np.asarray(res["x"]).ravel()
        states = z[: NX * (N + 1)].reshape(N + 1, NX)
        controls = z[NX * (N + 1): NX * (N + 1) + 2 * (N + 1)].reshape(N + 1, 2)
        return PeerSolution(horizon=float(z[-1]), states=states, controls=controls,
                            converged=bool(stats["success"]), status=str(stats["return_status"]),
                            iterations=int(stats["iter_count"]))
