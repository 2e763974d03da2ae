"""Stable and unstable manifolds of the libration-point orbits (Xiong & Wang, sec. III.C.2, eqs. 34-35).

The eigenvectors w_u, w_s of the monodromy at the orbit's initial state (orbits.Floquet, unit 6-norm) are
carried to the phase tau by the STM, w(tau) = Phi(tau) w(0), and renormalised; the manifold's first state is

    x_u = x(tau) +- d w_u(tau),   x_s = x(tau) +- d w_s(tau)                     (34)
    x_u = x(tau) +- d v(w_u(tau)),  x_s = x(tau) +- d v(w_s(tau))                 (35)

with d = 1e-6 by default (the paper's "generally, 10^-6"); eq. (35) keeps only the velocity part of the
eigenvector, here rescaled to unit norm so that d is the velocity deviation itself [VU] (the paper leaves
the scale open: d is a free variable of its optimisation, eq. 36). The unstable manifold W^u is propagated
forward, the stable W^s backward, to a Poincare cut x = const (scipy events, terminal) or to an impact.

Sign (the paper's example, sec. III.C.2: "positive x_s^+ generates W^{s,P}_{L1} in the P realm, negative
x_s^- generates W^{s,S}_{L1} in the S realm"): the eigenvectors are oriented with a non-positive x component
at the initial state (orbits.floquet) and carried continuously along the orbit, so "+" leaves towards -x:
from an L1 orbit into the primary's realm P, "-" into the secondary's realm S; from an L2 orbit "+" into S,
"-" into the exterior realm. `realm` labels a position (a geometric stand-in for the zero-velocity-curve
realms of Fig. 2, good at the necks and the cuts x = -mu, x = 1 - mu).
"""
from __future__ import annotations

import dataclasses

import numpy as np
from numpy.typing import ArrayLike
from scipy.integrate import solve_ivp

from .dynamics import FloatArray, GravityField, Model, state_derivative
from .orbits import ATOL, RTOL, PeriodicOrbit, collinear_points, propagate

DEFAULT_DEVIATION = 1e-6
#: Which realm the "+" and "-" branches of an orbit's manifolds enter (see the module docstring).
REALM_OF_SIGN = {("L1", 1): "P", ("L1", -1): "S", ("L2", 1): "S", ("L2", -1): "exterior"}


def realm(model: Model, r: ArrayLike) -> str:
    """"P", "S" or "exterior" for a position (3,): S when between L1 and L2 and nearer the secondary than
    the farther of the two points; P when on the primary's side of L1 and nearer the primary than L1;
    otherwise the exterior realm."""
    p = np.asarray(r, dtype=float)
    pts = collinear_points(model)
    r1, r2 = model.body_positions
    s_radius = max(pts["L2"] - r2[0], r2[0] - pts["L1"])
    if pts["L1"] <= p[0] <= pts["L2"] and np.linalg.norm(p - r2) <= s_radius:
        return "S"
    if p[0] < pts["L1"] and np.linalg.norm(p - r1) <= pts["L1"] - r1[0]:
        return "P"
    return "exterior"


def transported_eigenvectors(orbit: PeriodicOrbit, phases: ArrayLike) -> tuple[FloatArray, FloatArray, FloatArray]:
    """(states (n, 6), w_u (n, 6), w_s (n, 6)) at the phases tau [TU] (0 <= tau < T): w(tau) = Phi(tau) w(0),
    renormalised to unit 6-norm (the orientation, hence the sign convention, is kept)."""
    taus = np.atleast_1d(np.asarray(phases, dtype=float))
    y0 = np.concatenate([orbit.state0, np.eye(6).ravel()])
    field = GravityField(orbit.model.gravity_only())
    states = np.empty((taus.size, 6))
    wu = np.empty((taus.size, 6))
    ws = np.empty((taus.size, 6))
    order = np.argsort(taus)
    t_end = float(taus.max()) if taus.size else 0.0
    if t_end > 0.0:
        sol = solve_ivp(field.variational, (0.0, t_end), y0, method="DOP853", rtol=RTOL, atol=ATOL,
                        dense_output=True)
        ys = sol.sol(taus[order]).T
    else:
        ys = np.tile(y0, (taus.size, 1))
    for k, i in enumerate(order):
        y = ys[k] if t_end > 0.0 else y0
        if taus[i] == 0.0:
            y = y0
        phi = y[6:42].reshape(6, 6)
        states[i] = y[0:6]
        for out, w in ((wu, orbit.floquet.unstable_vector), (ws, orbit.floquet.stable_vector)):
            v = phi @ w
            out[i] = v / np.linalg.norm(v)
    return states, wu, ws


def manifold_states(orbit: PeriodicOrbit, phases: ArrayLike, *, stable: bool, sign: int = 1,
                    deviation: float = DEFAULT_DEVIATION, velocity_only: bool = False) -> FloatArray:
    """First states (n, 6) of the manifold at the phases tau [TU]: eq. (34), or eq. (35) when
    `velocity_only` (the velocity part of w, unit norm, times d). sign = +1 or -1 (see the module)."""
    if sign not in (1, -1):
        raise ValueError(f"sign must be +1 or -1, got {sign!r}")
    states, wu, ws = transported_eigenvectors(orbit, phases)
    w = ws if stable else wu
    if velocity_only:
        dv = w.copy()
        dv[:, 0:3] = 0.0
        dv /= np.linalg.norm(dv, axis=1, keepdims=True)
        w = dv
    return states + sign * deviation * w


@dataclasses.dataclass(frozen=True)
class CutCrossing:
    """Where a propagation stopped: at the cut, on an impact sphere, or at t_max."""

    state: FloatArray       #: the final state (6,)
    time: float             #: the signed propagation time [TU] (negative for backward)
    reached_cut: bool
    impact: int | None      #: 0 (primary) or 1 (secondary) when the impact sphere was hit, else None


def propagate_to_cut(model: Model, state: ArrayLike, x_cut: float, *, backward: bool = False,
                     t_max: float = 50.0, t0: float = 0.0, mass: float = 1.0) -> CutCrossing:
    """Propagates `state` (forward, or backward for a stable manifold) until it crosses the Poincare cut
    x = x_cut, hits an impact sphere (model.body_radius) or runs for t_max [TU]. The gravity-only model when
    `model` is autonomous, else eq. (8) without thrust from the time t0 with the mass fraction `mass`."""
    x = np.asarray(state, dtype=float)
    if model.autonomous:
        field = GravityField(model)
        rhs = field.derivative
        t_start = 0.0
    else:
        rhs = lambda t, s: state_derivative(model, t, s, mass=mass)  # noqa: E731
        t_start = t0
    side = np.sign(x[0] - x_cut)

    def cut(t: float, s: FloatArray) -> float:
        return float(s[0] - x_cut)
    cut.terminal = True  # type: ignore[attr-defined]
    cut.direction = -side if side != 0.0 else 0.0  # type: ignore[attr-defined]

    events = [cut]
    for i, centre in enumerate(model.body_positions):
        radius = model.body_radius[i]
        if radius > 0.0:
            def hit(t: float, s: FloatArray, c: FloatArray = centre, rad: float = radius) -> float:
                return float(np.linalg.norm(s[0:3] - c) - rad)
            hit.terminal = True  # type: ignore[attr-defined]
            events.append(hit)
    t_end = t_start - t_max if backward else t_start + t_max
    sol = solve_ivp(rhs, (t_start, t_end), x, method="DOP853", rtol=RTOL, atol=ATOL, events=events)
    if sol.status < 0:
        raise RuntimeError(f"propagation failed: {sol.message}")
    reached = sol.t_events[0].size > 0
    impact = None
    for i in range(1, len(events)):
        if sol.t_events[i].size > 0:
            impact = [k for k in range(2) if model.body_radius[k] > 0.0][i - 1]
    return CutCrossing(state=sol.y[:, -1].copy(), time=float(sol.t[-1] - t_start), reached_cut=reached,
                       impact=impact)


def manifold_to_cut(orbit: PeriodicOrbit, phases: ArrayLike, x_cut: float, *, stable: bool, sign: int = 1,
                    deviation: float = DEFAULT_DEVIATION, velocity_only: bool = False,
                    t_max: float = 50.0) -> list[CutCrossing]:
    """The manifold's trajectories from `manifold_states` to the cut x = x_cut (W^u forward, W^s backward),
    in the orbit's gravity-only model with its impact spheres."""
    starts = manifold_states(orbit, phases, stable=stable, sign=sign, deviation=deviation,
                             velocity_only=velocity_only)
    return [propagate_to_cut(orbit.model, s, x_cut, backward=stable, t_max=t_max) for s in starts]


def departure_growth(orbit: PeriodicOrbit, *, deviation: float = 1e-9, stable: bool = False) -> float:
    """|x(T) - x_orbit(T)| / d for the manifold state x0 + d w at phase 0 after one period (forward for the
    unstable, backward for the stable manifold): lambda_u to first order in d (eq. 34)."""
    w = orbit.floquet.stable_vector if stable else orbit.floquet.unstable_vector
    duration = -orbit.period if stable else orbit.period
    ref = propagate(orbit.model, orbit.state0, duration).y[:, -1]
    dev = propagate(orbit.model, orbit.state0 + deviation * w, duration).y[:, -1]
    return float(np.linalg.norm(dev - ref) / deviation)


def realm_cut(model: Model, realm_name: str) -> float:
    """The Poincare cut of a realm used by `main` and the tests: x = -mu (P, through the primary), x = 1 - mu
    (S, through the secondary, the paper's example), x = x_L2 + 0.5 (exterior)."""
    return {"P": -model.mu, "S": 1.0 - model.mu, "exterior": collinear_points(model)["L2"] + 0.5}[realm_name]


def main(argv: list[str] | None = None) -> int:
    """`python -m ogk_host.binary.manifolds [SCENARIO] [N]`: for every scenario orbit, both signs, W^u forward
    and W^s backward from N phases (eq. 34, d = 1e-6) to the cut of the realm the sign leads into: how many
    reach it, how many hit a body, the flight times (docs/design/blt-ground.md)."""
    import sys

    from .dynamics import model_from_scenario
    from .orbits import scenario_orbit
    from .scenario import load_scenario

    args = sys.argv[1:] if argv is None else argv
    sc = load_scenario(args[0] if args else None)
    n = int(args[1]) if len(args) > 1 else 16
    model = model_from_scenario(sc)
    tu_h = sc.units.time_s / 3600.0
    print("| orbit | branch | realm | cut x [LU] | reach the cut | hit Alpha | hit Beta | neither (20 TU) | "
          "time to the cut [h] |")
    print("|---|---|---|---|---|---|---|---|---|")
    for name in sc.orbits:
        orbit = scenario_orbit(sc, name, model)
        phases = np.linspace(0.0, orbit.period, n, endpoint=False)
        for sign in (1, -1):
            where = REALM_OF_SIGN[(orbit.point, sign)]
            cut = realm_cut(model, where)
            for stable in (False, True):
                ends = manifold_to_cut(orbit, phases, cut, stable=stable, sign=sign, t_max=20.0)
                reach = [abs(e.time) * tu_h for e in ends if e.reached_cut]
                hits = [sum(1 for e in ends if e.impact == i) for i in (0, 1)]
                none = n - len(reach) - hits[0] - hits[1]
                span = f"{min(reach):.2f}-{max(reach):.2f}" if reach else "-"
                label = ("W^s" if stable else "W^u") + (" +" if sign > 0 else " -")
                print(f"| {name} | {label} | {where} | {cut:.4f} | {len(reach)}/{n} | {hits[0]} | {hits[1]} | "
                      f"{none} | {span} |")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
