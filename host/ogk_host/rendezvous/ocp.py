"""Open-loop minimum-time Earth-to-Mars rendezvous (Starek & Kolmanovsky 2012, secs. 2.1, 2.3, 4.1.1).

Transcription (docs/design/nmpc.md, "Formulation"): free final time t_f, normalised time tau = t / t_f in [0, 1],
N subintervals of equal length, the thrust angle piecewise linear between its N + 1 node values (sec. 2.3),
direct multiple shooting with `rk4_steps_per_interval` RK4 steps per subinterval (the angle evaluated at
the RK4 stage times), constant thrust T_0 and mass flow of eq. (13), exact terminal conditions of eq. (5):
r = r_M, theta = theta_M(t_f), v_r = 0, v_theta = sqrt(mu / r_M). Solved by IPOPT (exact Hessian).

The problem has many local optima (errata: 370.1-384 days), so the initial guess is part of the method:
`phase_matched_guess` and `multi_start` below.
"""
from __future__ import annotations

import dataclasses
import math
import time

import casadi as ca
import numpy as np
from numpy.typing import NDArray

from .dynamics import DAY_S, Model, casadi_rhs
from .scenario import RendezvousScenario, hohmann

FloatArray = NDArray[np.float64]

#: The documented guess (docs/design/nmpc.md, "Initial guess"): t_f guess, radius-profile exponent and thrust
#: angle. 135 deg (prograde with an inward component) was measured the most robust of 45 / 90 / 135 deg
#: over t_f guesses of 300-460 d (20 of 21 starts reach the best optimum found, 10 of 21 with 90 deg).
DEFAULT_GUESS_TF_DAYS = 370.0
DEFAULT_GUESS_SHAPE = 1.0
DEFAULT_GUESS_ALPHA_RAD = 0.75 * math.pi


#: The paper's transfer (Table A.1: Earth to Mars, 0.5 N on 1500 kg): its Hohmann time is the time scale
#: the documented 370-day guess belongs to (docs/design/nmpc.md, "Any circular rendezvous").
PAPER_ORBITS_M = (1.49597871e11, 2.279391e11)
PAPER_SUN_MU = 1.32712440018e20
#: The guess never plans to burn more than this fraction of the propellant (its mass stays above dry).
GUESS_PROPELLANT_FRACTION = 0.9


def transfer_time_scale_s(scenario: RendezvousScenario) -> float:
    """max(Hohmann time, Hohmann Delta v / (T / m0)) [s]: the transfer's time scale, from the orbits
    and the vehicle's initial acceleration (a weak vehicle needs longer than the coast)."""
    r1, r2 = scenario.initial.radius_m, scenario.target.radius_m
    dv, t_h = hohmann(scenario.problem.sun_mu_m3_s2, r1, r2)
    accel = scenario.propulsion.thrust_max_n / scenario.initial_mass_kg
    return max(t_h, dv / accel)


def guess_transfer_days(scenario: RendezvousScenario) -> float:
    """The first guess's t_f [d]: the documented 370 d (the paper's vehicle and orbits) scaled by this
    transfer's time scale over the paper's, and short enough that full thrust burns at most
    GUESS_PROPELLANT_FRACTION of the propellant (nominal mass flow at the departure orbit)."""
    ref = max(hohmann(PAPER_SUN_MU, *PAPER_ORBITS_M)[1],
              hohmann(PAPER_SUN_MU, *PAPER_ORBITS_M)[0] / (0.5 / 1500.0))
    days = DEFAULT_GUESS_TF_DAYS * transfer_time_scale_s(scenario) / ref
    flow = Model.for_scenario(scenario)
    mdot_kg_s = flow.mass_flow * flow.units.mass_flow_kg_s
    if mdot_kg_s > 0.0:
        days = min(days, GUESS_PROPELLANT_FRACTION * scenario.propellant_kg / mdot_kg_s / DAY_S)
    return days


def guess_alpha_rad(scenario: RendezvousScenario) -> float:
    """The guess's thrust angle: 135 deg outward (prograde, tilted inward: the documented guess), its
    mirror 225 deg (retrograde) inward."""
    return DEFAULT_GUESS_ALPHA_RAD if scenario.outward else 2.0 * math.pi - DEFAULT_GUESS_ALPHA_RAD


@dataclasses.dataclass(frozen=True)
class Guess:
    """Initial guess of the NLP: node states (N+1, 5), node angles (N+1,), t_f [normalised]."""

    label: str
    states: FloatArray
    controls: FloatArray
    t_f: float


@dataclasses.dataclass(frozen=True)
class OcpResult:
    converged: bool
    status: str                 #: IPOPT's return status
    t_f_days: float
    fuel_kg: float
    iterations: int
    solve_time_s: float         #: wall clock of the IPOPT call
    time_days: FloatArray       #: node times (N+1,)
    states: FloatArray          #: node states (N+1, 5), normalised (docs/design/nmpc.md, "Units")
    controls_rad: FloatArray    #: node thrust angles (N+1,) [rad]
    guess: str                  #: label of the initial guess


def phase_matched_guess(model: Model, nodes: int, t_f_days: float = DEFAULT_GUESS_TF_DAYS,
                        shape: float = DEFAULT_GUESS_SHAPE, alpha_rad: float = 0.5 * math.pi,
                        label: str | None = None) -> Guess:
    """A phase-matched guess: with s = tau^shape the radius goes from r_0 to r_M as
    r = r_0 + (r_M - r_0)(3 s^2 - 2 s^3) (zero radial speed at both ends), the polar angle linearly
    from theta_0 to Mars' theta_M(t_f) (so the guess ends exactly at Mars' state of eq. 5), v_r = dr/dt
    (finite differences over the nodes),
    v_theta the circular speed sqrt(1 / r), the mass m0 - mdot t, the angle `alpha_rad` everywhere
    (pi/2: circumferential thrust)."""
    t_f = t_f_days * DAY_S / model.units.time_s
    tau = np.linspace(0.0, 1.0, nodes + 1)
    s = tau ** shape
    r0, r1 = model.x0[0], model.mars_radius
    r = r0 + (r1 - r0) * (3.0 * s ** 2 - 2.0 * s ** 3)
    v_r = np.gradient(r, tau * t_f)   # finite differences: dr/dtau is singular at 0 for shape < 1
    theta = model.x0[1] + (model.mars_state(t_f)[1] - model.x0[1]) * tau
    mass = model.x0[4] - model.mass_flow * t_f * tau
    states = np.stack([r, theta, v_r, r ** -0.5, mass], axis=-1)
    controls = np.full(nodes + 1, alpha_rad)
    return Guess(label or f"phase-matched tf={t_f_days:g} d shape={shape:g} alpha={alpha_rad:.3g}",
                 states, controls, t_f)


class MinTimeOcp:
    """The NLP, built once per scenario and solved from any number of guesses.

    `max_sweep_rad` (not in the paper, default off): bounds |alpha_{k+1} - alpha_k|, the angle swept
    linearly over one subinterval. Without it the angle may wind through whole turns inside a subinterval,
    which averages the thrust down (a throttle the constant-thrust model does not have): every local
    optimum but the best one found winds so (docs/design/nmpc.md, "Windings")."""

    def __init__(self, scenario: RendezvousScenario, nodes: int | None = None,
                 rk4_steps: int | None = None, max_sweep_rad: float | None = None) -> None:
        if scenario.ocp.objective != "min-time":
            raise ValueError(f"{scenario.path}: ocp.objective is {scenario.ocp.objective!r}, not min-time")
        self.model = Model.for_scenario(scenario)
        self.nodes = nodes or scenario.ocp.nodes
        self.rk4_steps = rk4_steps or scenario.ocp.rk4_steps_per_interval
        self.max_sweep_rad = max_sweep_rad
        self._build()

    def _interval_function(self) -> ca.Function:
        """x(tau_k) -> x(tau_{k+1}) over one subinterval of duration h, angle linear a0 -> a1."""
        f = casadi_rhs()
        m = self.model
        x = ca.SX.sym("x", 5)
        a0, a1, h = ca.SX.sym("a0"), ca.SX.sym("a1"), ca.SX.sym("h")
        dt = h / self.rk4_steps
        xk = x
        for i in range(self.rk4_steps):
            s0 = i / self.rk4_steps
            a_start = a0 + (a1 - a0) * s0
            a_mid = a0 + (a1 - a0) * (s0 + 0.5 / self.rk4_steps)
            a_end = a0 + (a1 - a0) * (s0 + 1.0 / self.rk4_steps)
            k1 = f(xk, a_start, m.thrust, m.mass_flow)
            k2 = f(xk + 0.5 * dt * k1, a_mid, m.thrust, m.mass_flow)
            k3 = f(xk + 0.5 * dt * k2, a_mid, m.thrust, m.mass_flow)
            k4 = f(xk + dt * k3, a_end, m.thrust, m.mass_flow)
            xk = xk + dt / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4)
        return ca.Function("interval", [x, a0, a1, h], [xk])

    def _build(self) -> None:
        n, m = self.nodes, self.model
        step = self._interval_function().map(n)
        X = ca.SX.sym("X", 5, n + 1)
        U = ca.SX.sym("U", 1, n + 1)
        tf = ca.SX.sym("tf")
        h = ca.repmat(tf / n, 1, n)
        x_end = step(X[:, :n], U[:, :n], U[:, 1:], h)
        mars = ca.vertcat(m.mars_radius, m.mars_theta0 + m.mars_rate * tf, 0.0, m.mars_radius ** -0.5)
        g = ca.vertcat(X[:, 0] - m.x0,                              # eq. (4)
                       ca.reshape(x_end - X[:, 1:], -1, 1),         # continuity (multiple shooting)
                       X[:4, n] - mars)                             # eq. (5)
        self._ng_eq = g.shape[0]
        if self.max_sweep_rad is not None:
            g = ca.vertcat(g, (U[0, 1:] - U[0, :n]).T)
        w = ca.vertcat(ca.reshape(X, -1, 1), ca.reshape(U, -1, 1), tf)
        self._n_w = w.shape[0]
        # Bounds keep IPOPT in the physical region only (no active bound at the optima measured).
        lbx = np.concatenate([np.tile([0.3, -10.0, -2.0, 0.1, 0.05], n + 1),
                              np.full(n + 1, -3.0 * math.pi), [1.0]])
        ubx = np.concatenate([np.tile([5.0, 20.0, 2.0, 3.0, 1.0], n + 1),
                              np.full(n + 1, 4.0 * math.pi), [30.0]])
        self._lbx, self._ubx = lbx, ubx
        self._ng = g.shape[0]
        opts = {"ipopt.tol": 1e-10, "ipopt.constr_viol_tol": 1e-12, "ipopt.max_iter": 500,
                "ipopt.print_level": 0, "print_time": False, "ipopt.sb": "yes"}
        self._solver = ca.nlpsol("min_time", "ipopt", {"x": w, "f": tf, "g": g}, opts)

    def solve(self, guess: Guess) -> OcpResult:
        n, m = self.nodes, self.model
        w0 = np.concatenate([guess.states.T.ravel(order="F"), guess.controls, [guess.t_f]])
        start = time.perf_counter()
        lbg = np.zeros(self._ng)
        ubg = np.zeros(self._ng)
        if self.max_sweep_rad is not None:
            lbg[self._ng_eq:] = -self.max_sweep_rad
            ubg[self._ng_eq:] = self.max_sweep_rad
        sol = self._solver(x0=w0, lbx=self._lbx, ubx=self._ubx, lbg=lbg, ubg=ubg)
        elapsed = time.perf_counter() - start
        stats = self._solver.stats()
        w = np.asarray(sol["x"]).ravel()
        states = w[: 5 * (n + 1)].reshape(n + 1, 5)
        controls = w[5 * (n + 1): 6 * (n + 1)]
        t_f = float(w[-1])
        units = m.units
        return OcpResult(converged=bool(stats["success"]), status=str(stats["return_status"]),
                         t_f_days=t_f * units.time_s / DAY_S,
                         fuel_kg=(states[0, 4] - states[-1, 4]) * units.mass_kg,
                         iterations=int(stats["iter_count"]), solve_time_s=elapsed,
                         time_days=np.linspace(0.0, t_f, n + 1) * units.time_s / DAY_S,
                         states=states, controls_rad=controls, guess=guess.label)


def default_guess(ocp: MinTimeOcp) -> Guess:
    """The documented guess (docs/design/nmpc.md): phase-matched, t_f = 370 d, smoothstep radius, alpha = 135 deg."""
    return phase_matched_guess(ocp.model, ocp.nodes, DEFAULT_GUESS_TF_DAYS, DEFAULT_GUESS_SHAPE,
                               DEFAULT_GUESS_ALPHA_RAD, label="documented")


def multi_start_guesses(ocp: MinTimeOcp) -> list[Guess]:
    """A handful of deterministic guesses (8): t_f guesses across and beyond the band of local optima
    (300-460 d), early / late climbs (shape 0.5, 2) and thrust angles tilted off circumferential
    (45 and 135 deg). Each of them, alone, was measured to converge to a different optimum or to the
    documented guess's (docs/design/nmpc.md, "Multi-start")."""
    spec = [(300.0, 1.0, 0.25), (330.0, 1.0, 0.5), (350.0, 2.0, 0.5), (400.0, 2.0, 0.5),
            (460.0, 1.0, 0.25), (370.0, 0.5, 0.75), (430.0, 0.5, 0.25), (300.0, 0.5, 0.75)]
    return [phase_matched_guess(ocp.model, ocp.nodes, tf, shape, alpha * math.pi)
            for tf, shape, alpha in spec]


def grid_guesses(ocp: MinTimeOcp) -> list[Guess]:
    """The wider survey of docs/design/nmpc.md: t_f guess 300-460 d (7 values) x shape 0.5, 1, 2 x angle
    45, 90, 135 deg: 63 starts."""
    return [phase_matched_guess(ocp.model, ocp.nodes, tf, shape, alpha * math.pi)
            for tf in (300.0, 330.0, 350.0, 370.0, 400.0, 430.0, 460.0)
            for shape in (0.5, 1.0, 2.0) for alpha in (0.25, 0.5, 0.75)]


def multi_start(ocp: MinTimeOcp, guesses: list[Guess] | None = None,
                distinct_days: float = 1e-3) -> tuple[list[OcpResult], list[OcpResult]]:
    """Solves from every guess; returns (all results, the distinct converged local optima sorted by t_f,
    two optima being the same when their t_f differ by less than `distinct_days`)."""
    results = [ocp.solve(g) for g in (guesses if guesses is not None else multi_start_guesses(ocp))]
    optima: list[OcpResult] = []
    for res in sorted((r for r in results if r.converged), key=lambda r: r.t_f_days):
        if not optima or res.t_f_days - optima[-1].t_f_days > distinct_days:
            optima.append(res)
    return results, optima


def main(argv: list[str] | None = None) -> int:
    """`python -m ogk_host.rendezvous.ocp [scenario] [--multi-start | --grid] [--max-sweep-pi A]`: the
    figures of docs/design/nmpc.md."""
    import argparse

    from .scenario import load_scenario

    parser = argparse.ArgumentParser(description=main.__doc__)
    parser.add_argument("scenario", nargs="?", default=None)
    group = parser.add_mutually_exclusive_group()
    group.add_argument("--multi-start", action="store_true", help="the 8 starts of multi_start_guesses")
    group.add_argument("--grid", action="store_true", help="the 63 starts of grid_guesses")
    parser.add_argument("--max-sweep-pi", type=float, default=None,
                        help="bound the angle swept per subinterval to this many pi (MinTimeOcp.max_sweep_rad)")
    args = parser.parse_args(argv)
    sweep = None if args.max_sweep_pi is None else args.max_sweep_pi * math.pi
    ocp = MinTimeOcp(load_scenario(args.scenario), max_sweep_rad=sweep)
    if args.multi_start or args.grid:
        results, optima = multi_start(ocp, grid_guesses(ocp) if args.grid else None)
    else:
        results = [ocp.solve(default_guess(ocp))]
        optima = [r for r in results if r.converged]
    for r in results:
        print(f"{r.guess:48s} {r.status:22s} t_f = {r.t_f_days:.4f} d  fuel = {r.fuel_kg:.2f} kg  "
              f"iterations = {r.iterations:3d}  solve = {r.solve_time_s:.3f} s")
    print(f"{len(optima)} distinct local optima [d]: " + ", ".join(f"{o.t_f_days:.4f}" for o in optima))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
