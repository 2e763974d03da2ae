"""The proximity approach's guidance: the receding-horizon NMPC as the closed loop sees it.

`KernelGuidance` is the flight code, `ogk_prox_*` (kernel/include/ogk/proximity.h) through the bindings
`ogk_bindings.proximity`; `PeerGuidance` is its ground peer (IPOPT on the same transcription,
ground_peer.py: `ogk mc --solver ipopt`), the reference the kernel's flights are checked against. Both:

- start from the ground's plan (`ogk_host.proximity.ocp.solve` from the nominal start, loaded as the
  plan: `ogk_prox_load_plan`), then solve from the first measured state (`ogk_prox_solve`);
- replan from each measured state (`ogk_prox_replan`: CNCN, N nodes over the remaining horizon; SNNS,
  the nodes shrinking with it), the previous plan flown when a solve fails (stale);
- with [guidance] fixed_final_time, keep the ground plan's t_f (free on the ground, from the nominal
  start): each replan's horizon bounds are the remaining time to it (`FIXED_T_F_BAND` wide). The
  minimum-fuel objective is so flat in T that a replan's free t_f wandered by hundreds of seconds
  between replans and the flight's end moved with an ulp of the start;
- command (alpha, w) at t: the plan's controls linear between its nodes (`ogk_prox_thrust_cmd`: the
  r-t-n unit vector (cos alpha, sin alpha, 0) and the throttle, alpha taken back as atan2(u_t, u_r)).

The closed loop speaks SI (s, m, m/s, kg), the laws the normalised units of the scenario (LU = 1 km,
TU = 1 / n, MU = [guidance] mass_unit_kg; t = 0 at the start)."""
from __future__ import annotations

import bisect
import dataclasses
import functools
import math
import time
from typing import Any, Protocol

import numpy as np
from numpy.typing import NDArray
from ogk_host.proximity.scenario import ProximityScenario

from ogk_bindings._real import REAL_EPS

from .ground_peer import PeerProblem, PeerSolver

FloatArray = NDArray[np.float64]
SOLVERS = ("kernel", "ipopt")
#: [guidance] fixed_final_time: a replan's horizon within (1 -/+ this) x the time left to the ground
#: plan's t_f (the kernel's horizon_max must exceed its horizon_min: in a single-precision kernel 1e-9
#: would round both bounds to one float, so the band is at least 8 eps of the kernel's real type)
FIXED_T_F_BAND = max(1e-9, 8.0 * REAL_EPS)
#: a failed solve is retried with the first BFGS matrix this times the configuration's (longer first
#: steps; the first solve with T free too. Campaign of seed 2026120581: run 81's first solve failed with
#: OGK_E_INFEASIBLE at 1, converged at 1e-2)
RETRY_HESSIAN_INIT = 1e-2
#: [guidance] fixed_final_time: the first plan's continuation steps from the ground plan's start to the
#: measured one (campaign of seed 2026120591, one solve: run 37 found no first plan; 2, 4, 8 or 16
#: steps: converged)
FIRST_SOLVE_STEPS = 4


@dataclasses.dataclass(frozen=True)
class Plan:
    """A plan in normalised units: node states (N + 1, 5) and controls (N + 1, 2) over [t0, t0 + T]."""

    t0: float
    horizon: float
    states: FloatArray
    controls: FloatArray

    @property
    def nodes(self) -> int:
        return int(self.states.shape[0] - 1)

    @property
    def t_f(self) -> float:
        return self.t0 + self.horizon

    def times(self) -> FloatArray:
        return self.t0 + self.horizon * np.linspace(0.0, 1.0, self.nodes + 1)

    @functools.cached_property
    def _table(self) -> tuple[list[float], list[float], list[float]]:
        return self.times().tolist(), self.controls[:, 0].tolist(), self.controls[:, 1].tolist()

    def control(self, t: float) -> tuple[float, float]:
        """(alpha, w) linear between the nodes; the first node's before t0, the last's after t_f."""
        ts, a, w = self._table
        if t <= ts[0]:
            return a[0], w[0]
        if t >= ts[-1]:
            return a[-1], w[-1]
        k = bisect.bisect_right(ts, t) - 1
        f = (t - ts[k]) / (ts[k + 1] - ts[k])
        return a[k] + (a[k + 1] - a[k]) * f, w[k] + (w[k + 1] - w[k]) * f

    def resampled(self, t: float, x: FloatArray, nodes: int, horizon: float) -> "Plan":
        """The plan from t over `horizon` on `nodes` equal subintervals, states and controls interpolated
        (node 0 the measured state x): the warm start of a replan."""
        ts = t + horizon * np.linspace(0.0, 1.0, nodes + 1)
        src = self.times()
        s = np.column_stack([np.interp(ts, src, self.states[:, i]) for i in range(5)])
        u = np.column_stack([np.interp(ts, src, self.controls[:, i]) for i in range(2)])
        s[0] = x
        return Plan(t, horizon, s, u)


@dataclasses.dataclass(frozen=True)
class ReplanInfo:
    t_s: float
    converged: bool
    status: str
    iterations: int
    solve_s: float              #: wall time of the call
    nodes: int
    planned_t_f_s: float        #: the end of the plan flown from here
    fuel_planned_kg: float      #: m(t) - m_N of the plan flown


class Guidance(Protocol):
    name: str
    solves: int
    failed_solves: int

    def replan(self, t_s: float, x_si: FloatArray) -> ReplanInfo: ...
    def command(self, t_s: float) -> tuple[float, float]: ...
    def plan_si(self) -> tuple[FloatArray, FloatArray, FloatArray]: ...


def _scale(scn: ProximityScenario) -> FloatArray:
    u = scn.units
    return np.array([u.length_m, u.length_m, u.velocity_m_s, u.velocity_m_s, u.mass_kg])


def ground_plan(scn: ProximityScenario) -> Plan:
    """The ground's open-loop plan from the nominal start, normalised: ogk_host.proximity.ocp.solve (the
    plans' disc, [guidance] keepout_margin_m larger than the truth's), then polished by the ground peer
    with what the flight's plans have beyond it: the time weight and the sweep bound (the kernel's first
    solve then starts at its optimum: from the bare OCP's plan, whose angles wander where w = 0 and whose
    t_f sits on the window's bound, its SQP ran out of iterations on a mission of the tests)."""
    from ogk_host.proximity import ocp
    sol = ocp.solve(scn.approach())
    if not sol.success:
        raise RuntimeError(f"the ground plan did not converge: {sol.status}")
    controls = sol.controls.copy()
    # the same thrust at every node, the angles wrapped to within pi of their neighbours
    controls[:, 0] = np.unwrap(controls[:, 0])
    plan = Plan(0.0, sol.t_f_s / scn.units.time_s, sol.states / _scale(scn), controls)
    pb = peer_problem(scn)
    tu = scn.units.time_s
    polished = _peer(pb, pb.nodes).solve(plan.states[0], (scn.horizon_s[0] / tu, scn.horizon_s[1] / tu),
                                         plan.horizon, plan.states, plan.controls)
    if not polished.converged:
        raise RuntimeError(f"the ground plan's polish did not converge: {polished.status}")
    return Plan(0.0, polished.horizon, polished.states, polished.controls)


def peer_problem(scn: ProximityScenario) -> PeerProblem:
    u, g, v = scn.units, scn.guidance, scn.vehicle
    return PeerProblem(
        thrust=v.thrust_max_n / (u.mass_kg * u.accel_m_s2), exhaust_velocity=v.exhaust_velocity_m_s / u.velocity_m_s,
        hold=(scn.hold_point_m[0] / u.length_m, scn.hold_point_m[1] / u.length_m),
        keepout=tuple((k.centre_m[0] / u.length_m, k.centre_m[1] / u.length_m,
                       (k.radius_m + g.keepout_margin_m) / u.length_m) for k in scn.keepouts),
        mass_min=v.dry_mass_kg / u.mass_kg, objective=g.objective,
        time_weight=g.fuel_time_weight_kg_per_s * u.time_s / u.mass_kg, max_sweep=g.max_sweep_rad,
        nodes=g.nodes, rk4_steps=g.rk4_steps)


#: one PeerSolver per (problem, nodes) in a process (built in ~1 s, then reused by every flight)
_PEERS: dict[tuple[PeerProblem, int], PeerSolver] = {}


def _peer(pb: PeerProblem, nodes: int) -> PeerSolver:
    key = (pb, nodes)
    if key not in _PEERS:
        _PEERS[key] = PeerSolver(dataclasses.replace(pb, nodes=nodes))
    return _PEERS[key]


class _Base:
    name = ""

    def __init__(self, scn: ProximityScenario, first: Plan) -> None:
        self.scn = scn
        self.units = scn.units
        self.scale = _scale(scn)
        self.plan = first
        self.solves = 0
        self.failed_solves = 0
        self.started = False
        self.t_f_fixed = first.t_f if scn.guidance.fixed_final_time else None

    def _fixed_bounds(self, t: float) -> tuple[float, float] | None:
        """[guidance] fixed_final_time: the horizon bounds [TU] of a replan at t that keep the ground
        plan's t_f (None: free)."""
        if self.t_f_fixed is None:
            return None
        h_min = self.scn.guidance.min_horizon_s / self.units.time_s
        rem = max(self.t_f_fixed - t, h_min)
        return rem * (1.0 - FIXED_T_F_BAND), rem * (1.0 + FIXED_T_F_BAND)

    def command(self, t_s: float) -> tuple[float, float]:
        return self.plan.control(t_s / self.units.time_s)

    def plan_si(self) -> tuple[FloatArray, FloatArray, FloatArray]:
        """(node times [s], node states SI, node controls) of the plan flown."""
        return self.plan.times() * self.units.time_s, self.plan.states * self.scale, self.plan.controls

    def _nodes(self, remaining: float) -> int:
        """CNCN: N; SNNS: N shrunk with the remaining horizon (at least 4)."""
        g = self.scn.guidance
        if g.strategy == "cncn":
            return g.nodes
        total = self.scn.horizon_s[1] / self.units.time_s
        return max(4, min(g.nodes, int(math.ceil(g.nodes * remaining / total))))

    def _info(self, t_s: float, ok: bool, status: str, iterations: int, elapsed: float) -> ReplanInfo:
        return ReplanInfo(t_s=t_s, converged=ok, status=status, iterations=iterations, solve_s=elapsed,
                          nodes=self.plan.nodes, planned_t_f_s=self.plan.t_f * self.units.time_s,
                          fuel_planned_kg=float(np.interp(t_s / self.units.time_s, self.plan.times(),
                                                          self.plan.states[:, 4]) - self.plan.states[-1, 4])
                          * self.units.mass_kg)


class PeerGuidance(_Base):
    """The ground peer (module doc): IPOPT re-solves warm from the shifted plan; the final time within
    the scenario's window (approach.horizon_s, from the start), the horizon at least min_horizon_s."""

    name = "ipopt"

    def __init__(self, scn: ProximityScenario, first: Plan) -> None:
        super().__init__(scn, first)
        self.pb = peer_problem(scn)

    def replan(self, t_s: float, x_si: FloatArray) -> ReplanInfo:
        u = self.units
        t = t_s / u.time_s
        x = np.asarray(x_si, dtype=np.float64) / self.scale
        h_min = self.scn.guidance.min_horizon_s / u.time_s
        h_max = max(self.scn.horizon_s[1] / u.time_s - t, h_min * 1.001)
        fixed = self._fixed_bounds(t)
        if fixed is not None:
            h_min, h_max = fixed
        horizon = min(max(self.plan.t_f - t, h_min), h_max)
        nodes = self._nodes(horizon)
        guess = self.plan.resampled(t, x, nodes, horizon)
        start = time.perf_counter()
        sol = _peer(self.pb, nodes).solve(x, (h_min, h_max), horizon, guess.states, guess.controls)
        if fixed is not None and not self.started and not sol.converged:
            # as KernelGuidance: the first solve again with T free, its t_f kept from here on
            self.solves += 1
            self.failed_solves += 1
            h_min = self.scn.guidance.min_horizon_s / u.time_s
            h_max = max(self.scn.horizon_s[1] / u.time_s - t, h_min * 1.001)
            sol = _peer(self.pb, nodes).solve(x, (h_min, h_max), horizon, guess.states, guess.controls)
            if sol.converged:
                self.t_f_fixed = t + sol.horizon
        elapsed = time.perf_counter() - start
        self.solves += 1
        ok = sol.converged
        if ok:
            self.plan = Plan(t, sol.horizon, sol.states, sol.controls)
        else:
            self.failed_solves += 1
        self.started = True
        return self._info(t_s, ok, sol.status, sol.iterations, elapsed)


class KernelGuidance(_Base):
    """`ogk_prox_*` through `ogk_bindings.proximity` (module doc): the ground's plan loaded, the first
    call `ogk_prox_solve`, every later one `ogk_prox_replan`, the command `ogk_prox_thrust_cmd`. With
    [guidance] fixed_final_time (the flight program does the same: nmpc_flight.c,
    OGK_NMPC_FLIGHT_FINAL_TIME):

    - the first plan by continuation: FIRST_SOLVE_STEPS solves from the ground plan, their start moved
      from the ground plan's to the measured one in equal steps (the last one the measurement itself);
      failing that, from the ground plan with T free and the first BFGS matrix RETRY_HESSIAN_INIT
      times the configuration's, and its t_f kept from then on;
    - a failed replan solved again cold from the plan held (the previous one, shifted), T kept, with
      that smaller first BFGS matrix.

    Every solve counts in `solves`, every one that fails in `failed_solves`."""

    name = "kernel"

    def __init__(self, scn: ProximityScenario, first: Plan) -> None:
        super().__init__(scn, first)
        self.ctx = kernel_context(scn)
        self.ctx.load_plan(first.t0, first.horizon, first.states, first.controls)
        self.first = first
        self._free_bounds = self.ctx.horizon_bounds
        self._hessian_init = self.ctx.hessian_init

    def replan(self, t_s: float, x_si: FloatArray) -> ReplanInfo:
        t = t_s / self.units.time_s
        x = np.asarray(x_si, dtype=np.float64) / self.scale
        fixed = self._fixed_bounds(t)
        start = time.perf_counter()
        if fixed is None:
            rep = self._count(self.ctx.replan(t, x) if self.started else self.ctx.solve(t, x))
        elif self.started:
            rep = self._replan_kept(t, x, fixed)
        else:
            rep = self._first_kept(t, x, fixed)
        elapsed = time.perf_counter() - start
        self.started = True
        p = self.ctx.plan()
        self.plan = Plan(p.t0, p.horizon, p.states, p.controls)
        return self._info(t_s, rep.converged, rep.status, int(rep.sqp_iterations), elapsed)

    def _count(self, rep: Any) -> Any:
        self.solves += int(rep.solves)
        self.failed_solves += int(not rep.converged)
        return rep

    def _first_kept(self, t: float, x: FloatArray, fixed: tuple[float, float]) -> Any:
        self.ctx.set_horizon_bounds(*fixed)
        x_nom = self.first.states[0]
        rep = None
        for k in range(1, FIRST_SOLVE_STEPS + 1):
            x_k = x if k == FIRST_SOLVE_STEPS else x_nom + (k / FIRST_SOLVE_STEPS) * (x - x_nom)
            rep = self._count(self.ctx.solve(t, x_k))
            if not rep.converged:
                break
        assert rep is not None
        if not rep.converged:
            first = self.first
            self.ctx.set_horizon_bounds(*self._free_bounds)
            self.ctx.set_hessian_init(self._hessian_init * RETRY_HESSIAN_INIT)
            self.ctx.load_plan(first.t0, first.horizon, first.states, first.controls)
            rep = self._count(self.ctx.solve(t, x))
            self.ctx.set_hessian_init(self._hessian_init)
            if rep.converged:
                p = self.ctx.plan()
                self.t_f_fixed = p.t0 + p.horizon
        return rep

    def _replan_kept(self, t: float, x: FloatArray, fixed: tuple[float, float]) -> Any:
        self.ctx.set_horizon_bounds(*fixed)
        rep = self._count(self.ctx.replan(t, x))
        if not rep.converged:
            p = self.ctx.plan()
            self.ctx.set_hessian_init(self._hessian_init * RETRY_HESSIAN_INIT)
            self.ctx.load_plan(t, 0.5 * (fixed[0] + fixed[1]), p.states, p.controls)
            rep = self._count(self.ctx.solve(t, x))
            self.ctx.set_hessian_init(self._hessian_init)
        return rep

    def command(self, t_s: float) -> tuple[float, float]:
        cmd = self.ctx.thrust_cmd(t_s / self.units.time_s)     # r-t-n unit vector and throttle
        return math.atan2(cmd.u[1], cmd.u[0]), cmd.throttle


#: the kernel's SQP settings of the flight (beyond ogk_prox_config_default's). In MU = m_0 (J ~ 6e-4)
#: tol_obj 1e-7 was a loose 1.6e-4 relative, and 1e-10 gave many failed solves (campaign of seed 424242:
#: 85 in 47 of 100 runs, one lost run). With [guidance] mass_unit_kg = 0.1 kg (J ~ 1) and the ground
#: plan's t_f kept: tol_obj 1e-8 (relative now; on 4 run seeds an ulp of the start moves the fuel by
#: <= 0.12 g of ~23 g; 1e-7: up to 1.1 g; 1e-9, 1e-10 or max_iter 400 no better; elastic_weight 1.8e6 =
#: 1000 x m_0 / MU, the slacks' old price against J: up to 0.21 g)
KERNEL_SETTINGS: dict[str, Any] = {"max_iter": 400, "max_iter_cold": 500, "tol_obj": 1e-8}


def kernel_context(scn: ProximityScenario) -> Any:
    """An ogk_prox_t of a scenario (normalised: mean_motion 1; the plans' discs; the transcription,
    strategy, objective, time weight, sweep bound, horizon bounds and propellant limit)."""
    from ogk_bindings.nmpc import CNCN, SNNS
    from ogk_bindings.proximity import ProxModel, Proximity
    pb = peer_problem(scn)
    g = scn.guidance
    model = ProxModel(thrust_max=pb.thrust, mass_flow_max=pb.thrust / pb.exhaust_velocity, hold=pb.hold,
                      keepout=list(pb.keepout))
    return Proximity(model, nodes=g.nodes, rk4_steps=g.rk4_steps, strategy=CNCN if g.strategy == "cncn" else SNNS,
                     objective=0 if g.objective == "min-time" else 1, time_weight=pb.time_weight,
                     max_sweep=pb.max_sweep, horizon_min=g.min_horizon_s / scn.units.time_s,
                     horizon_max=scn.horizon_s[1] / scn.units.time_s, mass_min=pb.mass_min, **KERNEL_SETTINGS)


def make_guidance(solver: str, scn: ProximityScenario, first: Plan) -> Guidance:
    if solver == "kernel":
        return KernelGuidance(scn, first)
    return PeerGuidance(scn, first)


def kernel_available() -> bool:
    """ogk_bindings.proximity is built (branch prox-kernel merged)."""
    import importlib.util
    return importlib.util.find_spec("ogk_bindings.proximity") is not None
