"""One NMPC solve of the Earth-to-Mars rendezvous as a parametric NLP (Starek & Kolmanovsky 2012, secs. 2.1,
2.3, 3.1-3.2), for the three test cases of sec. 4: constant-thrust minimum time, bounded-thrust
nuclear-electric and solar-electric minimum fuel. Normalised units (docs/design/nmpc.md, "Units").

Transcription (docs/design/nmpc.md, "The NMPC NLP"; the flight-code SQP solves the same one):

  parameters   p = (t0, x0): the absolute time [TU] and state of node 0, so one built NLP is re-solved from
               any state (the MPC's measured state) without rebuilding.
  unknowns     w = (X_0, ..., X_N, U_0, ..., U_N, T): node states X_k (5 each: r, theta, v_r, v_theta, m),
               node controls U_k (nu each: alpha, and the throttle w when nu = 2), the free horizon
               T = t_f - t0. Layout: the 5 (N+1) states node by node, then the nu (N+1) controls node by
               node, then T.
  grid         N equal subintervals, h = T / N, node times t_k = t0 + k h.
  dynamics     RK4 with M = rk4_steps steps per subinterval, the control linear between U_k and U_{k+1}
               (sec. 2.3) and evaluated at the RK4 stage times (as ocp.MinTimeOcp); right-hand side
               `dynamics.casadi_throttle_rhs` (T = w T_max(r), dm/dt = -w mdot_max(r); w = 1 when nu = 1),
               plus, with `third_bodies`, Earth and Mars gravity at the absolute stage times
               (`dynamics.casadi_third_body_accel`, Mars softened by its sphere of influence, see below).
  constraints  g = (X_0 - x0 [5], F(X_k, U_k, U_{k+1}, h, t_k) - X_{k+1} [5 N, k = 0..N-1],
               X_N[0:4] - (r_M, theta_M(t0 + T), 0, sqrt(1 / r_M)) [4, eq. 5 exactly, theta unwrapped],
               optionally U_{k+1}[0] - U_k[0] in [-max_sweep, max_sweep] [N]); all equalities = 0.
  objective    "min-time": T; "min-fuel": x0[4] - X_N[4] (m_0 - m_f, sec. 2.1).
  bounds       r in [0.3, 5] LU ([0.6, 5] for the solar-electric engine: eq. 14's fit turns negative
               below 0.457 AU), theta in [-10, 40] rad, |v_r|, v_theta in [-2, 2], [0.1, 3] VU, m in
               [0.05, 1] MU, alpha in [-3 pi, 4 pi], w in [0, 1], T in [horizon_lo, horizon_hi].

IPOPT (CasADi 3.8, exact Hessian): tol 1e-10 / constr_viol_tol 1e-12 by default (the open loop); an MPC
passes looser ones. A warm solve (`duals` given) uses warm_start_init_point = yes with the bound pushes at
1e-9 and mu_init = `warm_mu_init` (1e-8 by default, see docs/design/nmpc.md), from the guess AND its duals.
One solver is built (lazily) and cached per (node count, warm) pair: SNNS changes N every step.

`third_bodies` (not in the paper, whose predictive model has no perturbation; sec. 3.1): Earth and Mars
point masses with the truth model's vector formula. The exact terminal condition puts t_f's node at Mars'
centre, where a point mass is singular, so Mars' pull is Plummer-softened with length (r_SOI)_M
(mu d / (|d|^2 + r_SOI^2)^(3/2): 35 % of the point mass at the SOI edge, 94 % at 5 r_SOI); inside its
SOI the paper's local controller takes over (sec. 2.3.1). Earth's is not softened (the flight starts at
its SOI edge and leaves).
"""
from __future__ import annotations

import dataclasses
import math
import time

import casadi as ca
import numpy as np
from numpy.typing import NDArray

from .dynamics import (DAY_S, Engine, Model, Units, casadi_third_body_accel, casadi_throttle_rhs, planets)
from .plan import Plan
from .scenario import RendezvousScenario

FloatArray = NDArray[np.float64]

#: Default horizon bounds [TU]: 1e-3 TU (1.4 h) lets an MPC plan shrink towards arrival; 30 TU (1744 d)
#: is beyond every transfer of the paper (Table II's longest: 1090.97 d). A scenario's [ocp]
#: horizon_max_s, when present, replaces the upper bound.
HORIZON_LO = 1e-3
HORIZON_HI = 30.0
ALPHA_BOUNDS = (-3.0 * math.pi, 4.0 * math.pi)


@dataclasses.dataclass(frozen=True)
class NlpDuals:
    """IPOPT's multipliers of one solve: lam_g (constraints, layout of g above) and lam_x (bounds, layout
    of w). Pass them back to `RendezvousNlp.solve` with a guess of the same node count."""

    nodes: int
    nu: int
    lam_g: FloatArray
    lam_x: FloatArray
    sweep: bool = False     #: lam_g carries the N sweep multipliers at its end

    def shifted(self) -> "NlpDuals":
        """The multipliers of the problem with the first subinterval dropped (the SNN step of sec. 2.3.2):
        node 0's constraint X_0 = x0 takes the old continuity multiplier of X_1 with its sign reversed
        (X_1 appears as -X_1 in F(X_0) - X_1 and as +X_0' in X_0' - x0), the other rows move up by one."""
        n, nu = self.nodes, self.nu
        if n < 2:
            raise ValueError("cannot shift a plan of one subinterval")
        cont = self.lam_g[5: 5 + 5 * n]
        term = self.lam_g[5 + 5 * n: 9 + 5 * n]
        parts = [-cont[:5], cont[5:], term]
        if self.sweep:
            parts.append(self.lam_g[9 + 5 * n + 1:])
        lx = self.lam_x
        states = lx[: 5 * (n + 1)][5:]
        controls = lx[5 * (n + 1): (5 + nu) * (n + 1)][nu:]
        return NlpDuals(nodes=n - 1, nu=nu, lam_g=np.concatenate(parts),
                        lam_x=np.concatenate([states, controls, lx[-1:]]), sweep=self.sweep)


@dataclasses.dataclass(frozen=True)
class NlpResult:
    converged: bool
    status: str             #: IPOPT's return status
    plan: Plan              #: the solution (t0, horizon, node states and controls)
    objective: float        #: T [TU] (min-time) or m_0 - m_f [MU] (min-fuel)
    iterations: int
    solve_time_s: float     #: wall clock of the IPOPT call
    duals: NlpDuals


def shift_plan(plan: Plan, t0: float | None = None, x0: FloatArray | None = None) -> Plan:
    """The SNN guess of sec. 2.3.2: `plan` without its first subinterval (N - 1 subintervals of the same
    length, starting at node 1's time), node 0's state replaced by `x0` (the measured state) if given.
    The horizon is kept consistent with t0: t_f stays the old t_f."""
    if plan.nodes < 2:
        raise ValueError("cannot shift a plan of one subinterval")
    start = plan.t0 + plan.step if t0 is None else t0
    states = plan.states[1:].copy()
    if x0 is not None:
        states[0] = x0
    return Plan(t0=start, horizon=plan.t_f - start, states=states, controls=plan.controls[1:].copy())


class RendezvousNlp:
    """The NLP of one MPC solve (module docstring), built per node count on first use and cached.

    scenario       propulsion (constant / bounded / solar-electric: nu = 1 or 2) and objective
    nodes          default N (the node count of a solve is the guess's; `nodes` only pre-builds)
    rk4_steps      RK4 steps per subinterval (default the scenario's [ocp] rk4_steps_per_interval)
    objective      "min-time" or "min-fuel" (default the scenario's); min-time with a bounded throttle
                   is allowed (the optimum is then full throttle: it gives min-fuel's guess)
    third_bodies   Earth and Mars gravity in the predictive model (module docstring)
    max_sweep_rad  bound on |alpha_{k+1} - alpha_k| (as MinTimeOcp; default off)
    horizon_bounds (lo, hi) on T [TU] (default HORIZON_LO, HORIZON_HI): relative to each solve's t0
    transfer_time_max_s  an absolute arrival deadline t_f <= t_0 + this [s] (t_0 of Table A.1; default
                   None). Absolute, not a horizon: a bound on T = t_f - t0 that is active at every replan
                   would recede with t0 and the arrival with it. The open loop of the minimum-fuel
                   scenarios passes [ocp] transfer_time_max_s (`open_loop`); the closed loop decides.
    tol, constr_viol_tol, max_iter   IPOPT's (default 1e-10, 1e-12, 500: the open loop)
    warm_mu_init   IPOPT mu_init of a warm solve (duals given)
    """

    def __init__(self, scenario: RendezvousScenario, nodes: int | None = None,
                 rk4_steps: int | None = None, third_bodies: bool = False, *,
                 objective: str | None = None, max_sweep_rad: float | None = None,
                 horizon_bounds: tuple[float, float] | None = None, tol: float = 1e-10,
                 constr_viol_tol: float = 1e-12, max_iter: int = 500, warm_mu_init: float = 1e-8,
                 transfer_time_max_s: float | None = None, time_weight_kg_per_day: float = 0.0) -> None:
        self.scenario = scenario
        #: min-fuel only: J = m_0 - m_f + w T in MU per TU (a closed-loop choice, [nmpc] fuel_time_weight_kg_per_day)
        self.time_weight = float(time_weight_kg_per_day) * Units.for_scenario(scenario).time_s / DAY_S \
            / Units.for_scenario(scenario).mass_kg
        self.model = Model.for_scenario(scenario)
        self.engine = Engine.for_scenario(scenario)
        self.nu = self.engine.nu
        self.objective = objective or scenario.ocp.objective
        if self.objective not in ("min-time", "min-fuel"):
            raise ValueError(f"objective must be min-time or min-fuel, got {self.objective!r}")
        if self.objective == "min-fuel" and self.nu == 1:
            raise ValueError("min-fuel with a constant throttle is min-time (sec. 3.2.1): use min-time")
        self.rk4_steps = int(rk4_steps or scenario.ocp.rk4_steps_per_interval)
        if self.rk4_steps < 1:
            raise ValueError("rk4_steps must be >= 1")
        self.third_bodies = bool(third_bodies)
        if max_sweep_rad is not None and not max_sweep_rad > 0.0:
            raise ValueError("max_sweep_rad must be > 0")
        self.max_sweep_rad = max_sweep_rad
        if horizon_bounds is None:
            horizon_bounds = (HORIZON_LO, HORIZON_HI)
        lo, hi = horizon_bounds
        if not 0.0 < lo < hi:
            raise ValueError(f"horizon bounds must satisfy 0 < lo < hi, got {horizon_bounds}")
        self.horizon_bounds = (float(lo), float(hi))
        #: absolute latest arrival [TU] (None: free): T <= arrival_max - t0 at every solve
        self.arrival_max: float | None = None
        if transfer_time_max_s is not None:
            if not transfer_time_max_s > 0.0:
                raise ValueError(f"transfer_time_max_s must be > 0, got {transfer_time_max_s}")
            self.arrival_max = ((scenario.problem.start_time_s + transfer_time_max_s)
                                / self.model.units.time_s)
        if not (tol > 0.0 and constr_viol_tol > 0.0 and max_iter >= 1 and warm_mu_init > 0.0):
            raise ValueError("tol, constr_viol_tol, warm_mu_init must be > 0 and max_iter >= 1")
        self.ipopt = {"ipopt.tol": tol, "ipopt.constr_viol_tol": constr_viol_tol,
                      "ipopt.max_iter": int(max_iter), "ipopt.print_level": 0, "print_time": False,
                      "ipopt.sb": "yes"}
        self.warm_mu_init = warm_mu_init
        self._interval = self._interval_function()
        self._built: dict[object, tuple[dict, dict[str, FloatArray]]] = {}
        self._solvers: dict[tuple[int, bool], ca.Function] = {}
        if nodes is not None:
            self._solver(self._check_nodes(nodes), warm=False)

    # -- units ---------------------------------------------------------------------------------------------
    def days(self, t: float) -> float:
        """Normalised time -> days."""
        return t * self.model.units.time_s / DAY_S

    def kg(self, m: float) -> float:
        return m * self.model.units.mass_kg

    # -- building ------------------------------------------------------------------------------------------
    @staticmethod
    def _check_nodes(nodes: int) -> int:
        if isinstance(nodes, bool) or not isinstance(nodes, (int, np.integer)) or not 1 <= nodes <= 1000:
            raise ValueError(f"nodes must be an integer in [1, 1000], got {nodes!r}")
        return int(nodes)

    def _interval_function(self) -> ca.Function:
        """F(x, u0, u1, h, tk): one subinterval of length h from absolute time tk, controls linear u0 -> u1,
        M RK4 steps, the controls and (third bodies) the planets at the stage times."""
        f = casadi_throttle_rhs(self.engine)
        accel = None
        if self.third_bodies:
            earth, mars = planets(self.scenario,
                                  mars_softening_m=self.scenario.convergence.target_soi_radius_m)
            accel = casadi_third_body_accel((earth, mars))
        nu, steps = self.nu, self.rk4_steps
        x = ca.SX.sym("x", 5)
        u0, u1 = ca.SX.sym("u0", nu), ca.SX.sym("u1", nu)
        h, tk = ca.SX.sym("h"), ca.SX.sym("tk")

        def rhs(xs: ca.SX, s: float) -> ca.SX:
            u = u0 + (u1 - u0) * s
            dx = f(xs, u[0], u[1] if nu == 2 else 1.0)
            if accel is not None:
                a = accel(tk + s * h, xs)
                dx = dx + ca.vertcat(0.0, 0.0, a[0], a[1], 0.0)
            return dx

        dt = h / steps
        xk = x
        for i in range(steps):
            s0 = i / steps
            s_mid, s_end = s0 + 0.5 / steps, s0 + 1.0 / steps
            k1 = rhs(xk, s0)
            k2 = rhs(xk + 0.5 * dt * k1, s_mid)
            k3 = rhs(xk + 0.5 * dt * k2, s_mid)
            k4 = rhs(xk + dt * k3, s_end)
            xk = xk + dt / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4)
        return ca.Function("interval", [x, u0, u1, h, tk], [xk], ["x", "u0", "u1", "h", "tk"], ["xf"])

    def interval(self, x: FloatArray, u0: FloatArray, u1: FloatArray, h: float, tk: float) -> FloatArray:
        """The NLP's own subinterval map F (numpy in, numpy out): for re-integration and shifted guesses."""
        return np.asarray(self._interval(x, np.atleast_1d(u0), np.atleast_1d(u1), h, tk)).ravel()

    def _build(self, n: int) -> tuple[ca.Function, dict[str, FloatArray]]:
        return self.problem(n)

    def problem(self, n: int, symbolic: str = "SX") -> tuple[dict, dict[str, FloatArray]]:
        """The NLP of N = n subintervals as CasADi expressions ({x, f, g, p}) and its bounds (lbx, ubx,
        lbg, ubg; fn = (w, p) -> (f, g) for checks). "SX" inlines every subinterval (IPOPT's own solver);
        "MX" keeps the subinterval map one function called N times, so generated or JIT-compiled code
        holds its derivatives once (the benches' compiled peers)."""
        key = n if symbolic == "SX" else (n, symbolic)
        if key in self._built:
            return self._built[key]
        if symbolic not in ("SX", "MX"):
            raise ValueError(f"symbolic must be SX or MX, got {symbolic!r}")
        sym = ca.SX.sym if symbolic == "SX" else ca.MX.sym
        m, nu = self.model, self.nu
        X = sym("X", 5, n + 1)
        U = sym("U", nu, n + 1)
        T = sym("T")
        P = sym("p", 6)           # (t0, x0)
        h = T / n
        tk = P[0] + h * ca.DM(np.arange(n)).T
        x_end = self._interval.map(n)(X[:, :n], U[:, :n], U[:, 1:], ca.repmat(h, 1, n), tk)
        t_f = P[0] + T
        mars = ca.vertcat(m.mars_radius, m.mars_theta0 + m.mars_rate * t_f, 0.0, m.mars_radius ** -0.5)
        g = [X[:, 0] - P[1:6], ca.reshape(x_end - X[:, 1:], -1, 1), X[:4, n] - mars]
        if self.max_sweep_rad is not None:
            g.append((U[0, 1:] - U[0, :n]).T)
        w = ca.vertcat(ca.reshape(X, -1, 1), ca.reshape(U, -1, 1), T)
        f = T if self.objective == "min-time" else P[5] - X[4, n] + self.time_weight * T
        nlp = {"x": w, "f": f, "g": ca.vertcat(*g), "p": P}
        r_lo = 0.6 if self.engine.solar else 0.3
        lbx = np.concatenate([np.tile([r_lo, -10.0, -2.0, 0.1, 0.05], n + 1),
                              np.tile([ALPHA_BOUNDS[0]] + [0.0] * (nu - 1), n + 1),
                              [self.horizon_bounds[0]]])
        ubx = np.concatenate([np.tile([5.0, 40.0, 2.0, 3.0, 1.0], n + 1),
                              np.tile([ALPHA_BOUNDS[1]] + [1.0] * (nu - 1), n + 1),
                              [self.horizon_bounds[1]]])
        ng = int(nlp["g"].shape[0])
        lbg, ubg = np.zeros(ng), np.zeros(ng)
        if self.max_sweep_rad is not None:
            lbg[9 + 5 * n:] = -self.max_sweep_rad
            ubg[9 + 5 * n:] = self.max_sweep_rad
        fn = ca.Function(f"nlp_{n}", [w, P], [f, nlp["g"]])   # for checks only
        self._built[key] = (nlp, {"lbx": lbx, "ubx": ubx, "lbg": lbg, "ubg": ubg, "fn": fn})
        return self._built[key]

    def _solver(self, n: int, warm: bool) -> ca.Function:
        key = (n, warm)
        if key not in self._solvers:
            nlp, _ = self._build(n)
            opts = dict(self.ipopt)
            if warm:
                opts.update({"ipopt.warm_start_init_point": "yes", "ipopt.mu_init": self.warm_mu_init,
                             "ipopt.warm_start_bound_push": 1e-9, "ipopt.warm_start_bound_frac": 1e-9,
                             "ipopt.warm_start_slack_bound_push": 1e-9,
                             "ipopt.warm_start_slack_bound_frac": 1e-9,
                             "ipopt.warm_start_mult_bound_push": 1e-9})
            self._solvers[key] = ca.nlpsol(f"rendezvous_{n}{'_warm' if warm else ''}", "ipopt", nlp, opts)
        return self._solvers[key]

    # -- solving -------------------------------------------------------------------------------------------
    def solve(self, t0: float, x0: FloatArray, guess: Plan, duals: NlpDuals | None = None) -> NlpResult:
        """Solves from absolute time t0 [TU] and state x0 (5,), N = guess.nodes, starting from the guess
        (its node states, controls and horizon; its t0 is not used) and, if given, its duals (warm)."""
        x0 = np.asarray(x0, dtype=np.float64)
        if x0.shape != (5,) or not np.all(np.isfinite(x0)) or not math.isfinite(t0):
            raise ValueError(f"x0 must be 5 finite numbers and t0 finite, got {x0!r}, {t0!r}")
        if not (x0[0] > 0.0 and 0.0 < x0[4] <= 1.0 + 1e-12):
            raise ValueError(f"x0 must have r > 0 and 0 < m <= 1 MU, got {x0}")
        if guess.nu != self.nu:
            raise ValueError(f"guess has {guess.nu} controls per node, this engine {self.nu}")
        n = self._check_nodes(guess.nodes)
        if not (math.isfinite(guess.horizon) and guess.horizon > 0.0):
            raise ValueError(f"guess horizon must be > 0, got {guess.horizon}")
        if not (np.all(np.isfinite(guess.states)) and np.all(np.isfinite(guess.controls))):
            raise ValueError("guess has non-finite values")
        if duals is not None and (duals.nodes != n or duals.nu != self.nu
                                  or duals.sweep != (self.max_sweep_rad is not None)):
            raise ValueError(f"duals are for N = {duals.nodes}, nu = {duals.nu}; the guess has N = {n}")
        _, b = self._build(n)
        lo, hi = self.horizon_bounds
        if self.arrival_max is not None:
            hi = min(hi, self.arrival_max - t0)
            if not hi > lo:
                raise ValueError(f"t0 = {t0:.6g} TU is past the arrival deadline {self.arrival_max:.6g} TU "
                                 f"(less than the shortest horizon {lo:g} TU left)")
        ubx = b["ubx"].copy()
        ubx[-1] = hi
        w0 = np.concatenate([guess.states.ravel(), guess.controls.ravel(),
                             [min(max(guess.horizon, lo), hi)]])
        w0 = np.clip(w0, b["lbx"], ubx)
        args = dict(x0=w0, p=np.concatenate([[t0], x0]), lbx=b["lbx"], ubx=ubx, lbg=b["lbg"],
                    ubg=b["ubg"])
        if duals is not None:
            args.update(lam_g0=duals.lam_g, lam_x0=duals.lam_x)
        solver = self._solver(n, warm=duals is not None)
        start = time.perf_counter()
        sol = solver(**args)
        elapsed = time.perf_counter() - start
        stats = solver.stats()
        w = np.asarray(sol["x"]).ravel()
        states = w[: 5 * (n + 1)].reshape(n + 1, 5)
        controls = w[5 * (n + 1): (5 + self.nu) * (n + 1)].reshape(n + 1, self.nu)
        plan = Plan(t0=float(t0), horizon=float(w[-1]), states=states, controls=controls)
        return NlpResult(converged=bool(stats["success"]), status=str(stats["return_status"]), plan=plan,
                         objective=float(sol["f"]), iterations=int(stats["iter_count"]),
                         solve_time_s=elapsed,
                         duals=NlpDuals(nodes=n, nu=self.nu, lam_g=np.asarray(sol["lam_g"]).ravel(),
                                        lam_x=np.asarray(sol["lam_x"]).ravel(),
                                        sweep=self.max_sweep_rad is not None))

    def constraint_violation(self, t0: float, x0: FloatArray, plan: Plan) -> float:
        """max |g| of the equality rows at a plan (a check that a plan is a trajectory of the NLP)."""
        n = plan.nodes
        _, b = self._build(n)
        w = np.concatenate([plan.states.ravel(), plan.controls.ravel(), [plan.horizon]])
        g = np.asarray(b["fn"](w, np.concatenate([[t0], x0]))[1]).ravel()
        return float(np.max(np.abs(g[: 9 + 5 * n])))


def min_time_guess(nlp: RendezvousNlp) -> Plan:
    """ocp's documented guess (docs/design/nmpc.md, "Initial guess": phase-matched, alpha = 135 deg, 225 deg for an
    inward transfer) with t_f sized from the vehicle and the transfer (`ocp.guess_transfer_days`: 370 d for
    the paper's) as a Plan from t0 = 0, full throttle when nu = 2."""
    from .ocp import DEFAULT_GUESS_SHAPE, guess_alpha_rad, guess_transfer_days, phase_matched_guess

    g = phase_matched_guess(nlp.model, nlp.scenario.ocp.nodes, guess_transfer_days(nlp.scenario),
                            DEFAULT_GUESS_SHAPE, guess_alpha_rad(nlp.scenario))
    controls = g.controls[:, None] if nlp.nu == 1 else np.stack([g.controls, np.ones_like(g.controls)], 1)
    return Plan(t0=0.0, horizon=g.t_f, states=g.states, controls=controls)


#: Throttle of the min-fuel guess at every node (docs/design/nmpc.md, "Minimum fuel"): from the min-time optimum's
#: states and angles, 0.5 (mid-box) reaches the best optimum found for both engines; 1 (the min-time
#: throttle) does for NEP but stops the SEP case at a worse local optimum (211.32 kg at the deadline).
MIN_FUEL_GUESS_THROTTLE = 0.5


def min_fuel_guess(scenario: RendezvousScenario, nlp: RendezvousNlp | None = None) -> tuple[Plan, NlpResult]:
    """The documented guess of the open-loop minimum-fuel problems (docs/design/nmpc.md, "Minimum fuel"): the
    minimum-time optimum of the same engine (objective "min-time", full throttle; from `min_time_guess`):
    its node states, angles and horizon, with the throttle MIN_FUEL_GUESS_THROTTLE at every node. IPOPT
    then opens the coast arcs. Returns (guess, the min-time result)."""
    mt = RendezvousNlp(scenario, objective="min-time",
                       rk4_steps=None if nlp is None else nlp.rk4_steps,
                       third_bodies=False if nlp is None else nlp.third_bodies)
    res = mt.solve(0.0, mt.model.x0, min_time_guess(mt))
    if not res.converged:
        raise RuntimeError(f"the minimum-time guess did not converge: {res.status}")
    p = res.plan
    controls = np.stack([p.controls[:, 0], np.full(p.nodes + 1, MIN_FUEL_GUESS_THROTTLE)], axis=1)
    return Plan(t0=p.t0, horizon=p.horizon, states=p.states, controls=controls), res


def open_loop(scenario: RendezvousScenario, free: bool = False, third_bodies: bool = False,
              nodes: int | None = None) -> tuple[RendezvousNlp, NlpResult, NlpResult | None]:
    """The open loop of a scenario (docs/design/nmpc.md): min-time from ocp's documented guess; min-fuel from the
    min-time optimum at full throttle, arrival by [ocp] transfer_time_max_s unless `free`. Returns (the NLP,
    its result, the min-time result used as min-fuel's guess or None)."""
    deadline = None if free else scenario.ocp.transfer_time_max_s
    nlp = RendezvousNlp(scenario, third_bodies=third_bodies, transfer_time_max_s=deadline)
    if nlp.objective == "min-time":
        guess = min_time_guess(nlp)
        if nodes is not None:
            raise ValueError("nodes: min-time starts from ocp's documented guess (scenario N)")
        return nlp, nlp.solve(0.0, nlp.model.x0, guess), None
    plan, mt = min_fuel_guess(scenario, nlp)
    return nlp, nlp.solve(0.0, nlp.model.x0, plan), mt


def main(argv: list[str] | None = None) -> int:
    """`python -m ogk_host.rendezvous.nlp [SCENARIO] [--free] [--third-bodies]`: the open loop of the
    scenario through RendezvousNlp (min-time: from ocp's documented guess; min-fuel: from the min-time
    optimum at full throttle, arrival by [ocp] transfer_time_max_s unless --free), docs/design/nmpc.md's figures."""
    import argparse

    from .scenario import load_scenario

    parser = argparse.ArgumentParser(description=main.__doc__)
    parser.add_argument("scenario", nargs="?", default=None)
    parser.add_argument("--free", action="store_true", help="ignore [ocp] transfer_time_max_s (t_f free)")
    parser.add_argument("--third-bodies", action="store_true", help="Earth and Mars in the predictive model")
    args = parser.parse_args(argv)
    scenario = load_scenario(args.scenario)
    nlp, res, mt = open_loop(scenario, free=args.free, third_bodies=args.third_bodies)
    deadline = "free" if nlp.arrival_max is None else f"<= {nlp.days(nlp.arrival_max):.1f} d"
    print(f"{scenario.name}: {scenario.propulsion.model}, throttle {scenario.propulsion.throttle}, "
          f"objective {nlp.objective}, N = {scenario.ocp.nodes}, RK4 steps {nlp.rk4_steps}, third bodies "
          f"{nlp.third_bodies}, t_f {deadline}")
    if mt is not None:
        print(f"  guess = min-time optimum (throttle {MIN_FUEL_GUESS_THROTTLE:g}): {mt.status}, t_f = {nlp.days(mt.plan.t_f):.4f} d, "
              f"fuel {nlp.kg(1.0 - mt.plan.states[-1, 4]):.2f} kg, {mt.iterations} iterations, "
              f"{mt.solve_time_s:.3f} s")
    p = res.plan
    print(f"  {nlp.objective}: {res.status}, t_f = {nlp.days(p.t_f):.4f} d, fuel = "
          f"{nlp.kg(1.0 - p.states[-1, 4]):.2f} kg, {res.iterations} iterations, {res.solve_time_s:.3f} s")
    if nlp.nu == 2:
        print("  throttle at the nodes: " + " ".join(f"{w:.2f}" for w in p.controls[:, 1]))
    paper = scenario.paper_results or {}
    for key in ("open_loop_time_s", "snns_time_s"):
        if key in paper:
            fuel = paper.get(key.replace("time_s", "fuel_kg"))
            print(f"  paper {key[:-7]}: t_f = {paper[key] / DAY_S:.4f} d, fuel = {fuel} kg")
    return 0 if res.converged else 1


if __name__ == "__main__":
    raise SystemExit(main())
