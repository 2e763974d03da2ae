"""The ground NLP as a guidance of the rendezvous closed loop (Starek & Kolmanovsky 2012, sec. 2.3).

`IpoptGuidance`: the ground NLP (ogk_host.rendezvous.nlp.RendezvousNlp, CasADi + IPOPT) re-solved along the
flight with the strategies of strategy.py, warm started primal and dual from the shifted previous solution.
It is one `guidance_base.Guidance`; the flight code's is kernel_guidance.KernelGuidance, and
guidance_factory.make_guidance picks one by the `--solver` name.

All times and states are normalised (TU, LU, VU, MU: docs/design/nmpc.md, "Units").
"""
from __future__ import annotations

import dataclasses
from typing import Any

import casadi as ca
import numpy as np
from ogk_host.rendezvous.nlp import MIN_FUEL_GUESS_THROTTLE, NlpResult, RendezvousNlp, min_fuel_guess
from ogk_host.rendezvous.plan import Plan
from ogk_host.rendezvous.scenario import RendezvousScenario

from . import strategy as st
from .guidance_base import FloatArray, ReplanInfo, first_guess

#: IPOPT solvers an `IpoptGuidance` keeps, least recently used dropped first. RendezvousNlp builds one
#: CasADi solver (about 85 MB resident at N = 30, 170 MB at N = 60) and its symbolic NLP (about 2 MB) per
#: (node count, warm start) and keeps every one; SNNS asks for a new N at almost every replan (N - 1 after the
#: shift, 2N for the doubling test), so the flight's resident memory grew with its length (3.5 GB for the
#: perturbed SNNS flight of seed 1, 9.7 GB reported in issue 18). A replan uses at most three: (N, warm),
#: (N, cold) when the warm start stalls, (2N, cold); the fourth keeps the previous replan's N, which CNCN and
#: SNNS at min_nodes solve again. A dropped solver is built again when asked for: after an adopted doubling
#: SNNS walks down node counts it has flown before (25 of the 75 solves of that flight), which costs about
#: 30 s more CPU (0.3-1.2 s a build) for 0.79 GB instead of 3.5 GB (docs/design/nmpc.md, "Closed loop").
SOLVER_CACHE_SIZE = 4


class BoundedNlp(RendezvousNlp):
    """RendezvousNlp keeping at most `SOLVER_CACHE_SIZE` IPOPT solvers, and only the symbolic NLPs of their
    node counts (an LRU over RendezvousNlp's own caches, its `_solvers` and `_built` dictionaries)."""

    def _solver(self, n: int, warm: bool) -> ca.Function:
        solver = super()._solver(n, warm)
        key = (n, warm)
        self._solvers[key] = self._solvers.pop(key)      # most recently used last
        while len(self._solvers) > SOLVER_CACHE_SIZE:
            del self._solvers[next(iter(self._solvers))]
        kept = {nodes for nodes, _ in self._solvers}
        for nodes in [k for k in self._built if k not in kept]:
            del self._built[nodes]
        return solver


class IpoptGuidance:
    """The ground NLP re-solved along the flight with SNNS or CNCN (strategy.py).

    - first replan: the open-loop problem from the documented guess (`first_guess`; min-fuel: nlp's
      `min_fuel_guess`), N = [ocp] nodes;
    - SNNS: guess = the previous plan shifted (`strategy.snns_guess`), primal and dual warm start; while
      subdivisions remain, the doubled guess is solved too and adopted by `strategy.adopt_doubled`;
    - CNCN: guess = the previous plan regridded with the same N (primal warm start only: interpolated duals
      are no better than none);
    - a replan where no solve converges keeps flying the previous plan (its next subinterval) and is counted
      in `failed_solves`; its remainder is the guess of the next replan.
    """

    name = "ipopt"

    def __init__(self, scenario: RendezvousScenario, strategy: st.StrategySettings,
                 third_bodies: bool | None = None) -> None:
        self.scenario = scenario
        self.strategy = strategy
        n = scenario.nmpc
        self.third_bodies = n.third_bodies_in_model if third_bodies is None else third_bodies
        # one NLP object for every node count (it builds one IPOPT solver per N, cold and warm, and keeps the
        # SOLVER_CACHE_SIZE most recently used)
        # min-fuel: arrival by [ocp] transfer_time_max_s (with t_f free the fuel is flat past the knee and
        # has no minimum; docs/design/nmpc.md, "Minimum fuel"), an absolute deadline the re-plans keep
        deadline = scenario.ocp.transfer_time_max_s if scenario.ocp.objective == "min-fuel" else None
        self.nlp = BoundedNlp(scenario, rk4_steps=n.rk4_steps_per_interval, third_bodies=self.third_bodies,
                              tol=n.tol, constr_viol_tol=n.constr_viol_tol, max_iter=n.max_iter,
                              transfer_time_max_s=deadline,
                              time_weight_kg_per_day=n.fuel_time_weight_kg_per_day)
        self.nu = int(self.nlp.nu)
        self._plan: Plan | None = None          # basis of the next guess
        self._flying: Plan | None = None        # the plan commanded now
        self._duals: Any = None                 # duals of self._plan's solve (None after a regrid/failure)
        self.subdivisions = 0
        self.failed_solves = 0
        self.solves = 0
        self.replans = 0

    def _solve(self, t: float, x: FloatArray, guess: Plan, duals: Any) -> NlpResult:
        self.solves += 1
        res = self.nlp.solve(t, x, guess, duals=duals)
        if not res.converged and duals is not None:
            # A warm start can stall where a cold start from the same primal point does not; both count.
            self.solves += 1
            cold = self.nlp.solve(t, x, guess, duals=None)
            return dataclasses.replace(cold, iterations=cold.iterations + res.iterations,
                                       solve_time_s=cold.solve_time_s + res.solve_time_s)
        return res

    def _guess(self, t: float, x: FloatArray) -> tuple[Plan, Any]:
        s = self.strategy
        prev = self._plan
        if prev is None:
            if self.nlp.objective == "min-fuel":
                # the open loop's documented min-fuel guess: the min-time optimum at throttle 0.5 (nlp.py);
                # when that min-time solve fails (a vehicle far from the paper's), the sized guess itself
                try:
                    g, _ = min_fuel_guess(self.scenario, self.nlp)
                except RuntimeError:
                    g = first_guess(self.scenario, self.scenario.ocp.nodes, t, x, self.nu)
                    controls = np.array(g.controls, copy=True)
                    controls[:, 1] = MIN_FUEL_GUESS_THROTTLE
                    g = Plan(t0=t, horizon=g.horizon, states=g.states, controls=controls)
                states = np.array(g.states, copy=True)
                states[0] = x
                return Plan(t0=t, horizon=g.horizon, states=states, controls=g.controls), None
            return first_guess(self.scenario, self.scenario.ocp.nodes, t, x, self.nu), None
        if s.name == "cncn":
            return st.regrid(prev, t, x, self.scenario.ocp.nodes, s.min_horizon), None
        guess = st.snns_guess(prev, t, x, s.min_nodes, s.min_horizon)
        duals = None
        shifted = (guess.nodes == prev.nodes - 1 and guess.t0 == prev.t0 + prev.step)
        if shifted and self._duals is not None and self._duals.nodes == prev.nodes:
            duals = self._duals.shifted()
        return guess, duals

    def replan(self, t: float, x: FloatArray) -> ReplanInfo:
        x = np.asarray(x, dtype=np.float64)
        self.replans += 1
        guess, duals = self._guess(t, x)
        solves_before = self.solves
        res = self._solve(t, x, guess, duals)
        iterations, solve_s = res.iterations, res.solve_time_s
        adopted: NlpResult | None = res if res.converged else None
        subdivided = False
        cost_2n: float | None = None
        s = self.strategy
        if s.name == "snns" and self.subdivisions < s.max_subdivisions:
            base = res.plan if res.converged else guess
            res2 = self._solve(t, x, st.subdivide(base), None)
            iterations += res2.iterations
            solve_s += res2.solve_time_s
            cost_n = res.objective if res.converged else None
            cost_2n = res2.objective if res2.converged else None
            if st.adopt_doubled(cost_n, cost_2n, s.doubling_threshold_percent):
                adopted, subdivided = res2, True
                self.subdivisions += 1
        solves = self.solves - solves_before
        if adopted is not None:
            self._plan = self._flying = adopted.plan
            self._duals = adopted.duals
            flown = adopted.plan
            status = adopted.status
        else:
            self.failed_solves += 1
            self._plan = guess
            self._duals = None
            if self._flying is None:
                self._flying = guess
            flown = guess
            status = res.status
        return ReplanInfo(t=t, t_next=t + flown.step, converged=adopted is not None, failed=adopted is None,
                          iterations=iterations, solve_time_s=solve_s, solves=solves, nodes=flown.nodes,
                          subdivided=subdivided, objective=None if adopted is None else adopted.objective,
                          status=status, plan=flown, status_n=res.status,
                          cost_n=res.objective if res.converged else None, cost_2n=cost_2n)

    def command(self, t: float) -> tuple[float, float]:
        plan = self._flying
        if plan is None:
            raise RuntimeError("command() before the first replan()")
        u = plan.control_at(t)
        return float(u[0]), (float(u[1]) if u.shape[0] > 1 else 1.0)
