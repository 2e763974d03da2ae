"""The flight code's NMPC (`ogk_nmpc`, kernel/include/ogk/nmpc.h) as a `Guidance` of the closed loop.

The kernel owns the whole receding-horizon logic (SNNS drop / min_nodes regrid / doubling test, CNCN
regrid, the stale-plan fallback); this adapter only maps the scenario to the kernel configuration
(normalised units of docs/design/nmpc.md) and times the calls:

- first replan: the documented guess (`guidance_base.first_guess`) loaded as the plan, then `ogk_nmpc_solve`
  (the open loop from (t, x), a cold BFGS start); minimum fuel first solves minimum time from that guess
  in a second context and starts from its optimum with throttle 0.5 (the ground's guess, nlp.py);
- every later replan: `ogk_nmpc_replan` (warm: the shifted plan, its multipliers and BFGS matrix).
"""
from __future__ import annotations

import math
import time

import numpy as np
from numpy.typing import ArrayLike, NDArray
from ogk_host.rendezvous.dynamics import DAY_S, Engine, Model, planets
from ogk_host.rendezvous.nlp import MIN_FUEL_GUESS_THROTTLE
from ogk_host.rendezvous.plan import Plan
from ogk_host.rendezvous.scenario import RendezvousScenario

from ogk_bindings.nmpc import CNCN, FLAG_OUTSIDE_SET, FLAG_SUBDIVIDED, MAX_NODES, SNNS, Nmpc, NmpcConfig

from ogk.sil import precision

from . import strategy as st
from .guidance_base import ReplanInfo, first_guesses

FloatArray = NDArray[np.float64]


#: The SQP's stop on the predicted change of J (ogk_nmpc_config_t.tol_obj). The kernel's default 1e-7 leaves
#: a minimum-fuel plan's t_f anywhere in its flat valley: the solar-electric flight's arrival moved by up to
#: 0.34 d over 20 ulp moves of its first measured radius (seed 2026120478, run 0); 1e-9: 0.05 d; 0 (the
#: stationarity test alone): 0.004 d at 44 % more SQP iterations. docs/design/nmpc-flight.md, "Robustness".
TOL_OBJ = 1e-9


def kernel_config(scenario: RendezvousScenario, strategy: st.StrategySettings,
                  third_bodies: bool | None = None, **overrides: object) -> NmpcConfig:
    """The kernel configuration of a scenario: model, target and transcription from the scenario, the
    strategy's parameters from [nmpc] (the doubling test runs while 2N fits OGK_NMPC_MAX_NODES), and the
    robustness of docs/design/nmpc-flight.md, "Robustness" (beyond the paper): the plan's engine derated by
    [nmpc] thrust_margin_percent (thrust and flow alike: the nominal specific impulse), the terminal set
    of [nmpc] terminal_set_fraction, the propellant limit at the dry mass, Earth's gravity until the
    flight leaves its Hill sphere ([nmpc] departure_planet_in_model), the keep-out along the arcs."""
    model = Model.for_scenario(scenario)
    engine = Engine.for_scenario(scenario)
    units = model.units
    n = scenario.nmpc
    use_bodies = n.third_bodies_in_model if third_bodies is None else third_bodies
    derate = 1.0 - n.thrust_margin_percent / 100.0
    fields: dict[str, object] = dict(
        mu=1.0,
        engine=0 if engine.nu == 1 else 1,
        power=1 if engine.solar else 0,
        thrust_max=engine.thrust * derate if not engine.solar else 1.0,
        mass_flow_max=engine.mass_flow * derate if not engine.solar else 1.0,
        solar_length_unit=1.0 / engine.au_per_lu,
        solar_a=list(engine.power), solar_thrust=[v * derate for v in engine.thrust_coef],
        solar_flow=[v * derate for v in engine.flow_coef],
        target_radius=model.mars_radius, target_phase0=model.mars_theta0, target_rate=model.mars_rate,
        objective=0 if scenario.ocp.objective == "min-time" else 1,
        # [nmpc] fuel_time_weight_kg_per_day in MU/TU (minimum fuel only)
        time_weight=n.fuel_time_weight_kg_per_day * units.time_s / DAY_S / units.mass_kg,
        nodes=scenario.ocp.nodes, rk4_steps=n.rk4_steps_per_interval,
        horizon_min=max(strategy.min_horizon, 1e-3),
        strategy=SNNS if strategy.name == "snns" else CNCN,
        min_nodes=strategy.min_nodes, max_subdivisions=strategy.max_subdivisions,
        doubling_threshold=strategy.doubling_threshold_percent / 100.0,
        doubling_max_nodes=MAX_NODES // 2,
        max_iter=200, max_iter_cold=500, tol_feas=1e-9, tol_stat=1e-6, tol_obj=TOL_OBJ,
        hessian=1 if n.hessian == "exact" else 0,
        terminal_box=terminal_box(scenario),
        # the propellant limit: a plan never burns below the dry mass
        mass_min=scenario.dry_mass_kg / units.mass_kg,
    )
    earth = planets(scenario)[0]
    if use_bodies:
        # as the ground NLP (nlp.py): Earth a point mass, Mars softened by its sphere of influence (the
        # plan ends at Mars' centre, where a point mass is singular)
        bodies = planets(scenario, mars_softening_m=scenario.convergence.target_soi_radius_m)
        fields.update(n_bodies=len(bodies), body_mu=[b.mu for b in bodies],
                      body_radius=[b.radius for b in bodies], body_phase0=[b.theta0 for b in bodies],
                      body_rate=[b.rate for b in bodies], body_softening=[b.softening for b in bodies])
    elif n.departure_planet_in_model == "hill-sphere":
        # the paper's predictive model, but for Earth while the flight is inside its Hill sphere: there the
        # paper's start (zero Earth-relative velocity at 0.62 Hill radii) is bound to Earth, which pulls
        # harder than the engine; released for good at the first replan beyond it
        fields.update(n_bodies=1, body_mu=[earth.mu], body_radius=[earth.radius],
                      body_phase0=[earth.theta0], body_rate=[earth.rate],
                      body_release=[scenario.earth_hill_radius_m / units.length_m])
    keepout = n.earth_keepout_radius_m / units.length_m
    if keepout > 0.0:
        if not use_bodies and n.departure_planet_in_model != "hill-sphere":
            # Earth's ephemeris only (no gravity) for the keep-out
            fields.update(n_bodies=1, body_mu=[0.0], body_radius=[earth.radius], body_phase0=[earth.theta0],
                          body_rate=[earth.rate])
        fields.update(keepout_radius=[keepout])
    fields.update(overrides)
    # a float kernel's solver tolerances (ogk.sil.precision: 1e-9 is below its rounding)
    return NmpcConfig(**precision.nmpc_tolerances(fields, precision.current()))


def terminal_box(scenario: RendezvousScenario) -> list[float]:
    """The plan's terminal set [LU, rad, VU, VU]: the square inscribed in [nmpc] terminal_set_fraction of
    the arrival test's sphere (position: the target's sphere of influence; velocity: the arrival's
    velocity tolerance), half-width f R / sqrt(2) in r and in R_T theta, f v / sqrt(2) in v_r and v_theta;
    all 0 (eq. 5 exactly, the paper) when the fraction is 0."""
    f = scenario.nmpc.terminal_set_fraction
    if not f > 0.0:
        return [0.0] * 4
    model = Model.for_scenario(scenario)
    units = model.units
    half_r = f * scenario.convergence.target_soi_radius_m / units.length_m / math.sqrt(2.0)
    half_v = f * scenario.convergence.velocity_error_m_s / units.velocity_m_s / math.sqrt(2.0)
    return [half_r, half_r / model.mars_radius, half_v, half_v]


def to_plan(p) -> Plan:  # type: ignore[no-untyped-def]
    return Plan(t0=p.t0, horizon=p.horizon, states=p.states, controls=p.controls)


class KernelGuidance:
    """`ogk_nmpc` flown by the closed loop (solve_time_s: wall clock of the C call through cffi)."""

    name = "kernel"

    def __init__(self, scenario: RendezvousScenario, strategy: st.StrategySettings,
                 third_bodies: bool | None = None, **overrides: object) -> None:
        self.scenario = scenario
        self.strategy = strategy
        self.cfg = kernel_config(scenario, strategy, third_bodies, **overrides)
        self.nmpc = Nmpc(self.cfg)
        self.nu = self.nmpc.nu
        self.started = False
        self.subdivisions = 0
        self.failed_solves = 0
        self.solves = 0
        self.replans = 0
        self.pre_iterations = 0

    def replan(self, t: float, x: ArrayLike) -> ReplanInfo:
        x = np.asarray(x, dtype=np.float64)
        self.replans += 1
        start = time.perf_counter()
        if not self.started:
            rep = None
            for g in first_guesses(self.scenario, self.scenario.ocp.nodes, t, x, self.nu):
                rep = self._first_solve(g, t, x)
                if rep.converged:
                    break
            assert rep is not None
            self.started = True
        else:
            rep = self.nmpc.replan(t, x)
        elapsed = time.perf_counter() - start
        self.solves += rep.solves
        subdivided = bool(rep.flags & FLAG_SUBDIVIDED)
        self.subdivisions += int(subdivided)
        self.failed_solves += int(not rep.converged)
        plan = to_plan(self.nmpc.plan())
        return ReplanInfo(t=t, t_next=rep.t_next, converged=rep.converged, failed=not rep.converged,
                          iterations=rep.sqp_iterations, solve_time_s=elapsed, solves=rep.solves,
                          nodes=rep.nodes, subdivided=subdivided,
                          objective=rep.objective if rep.converged else None, status=rep.status, plan=plan,
                          outside_set=rep.converged and bool(rep.flags & FLAG_OUTSIDE_SET))

    def _first_solve(self, g: Plan, t: float, x: FloatArray):  # type: ignore[no-untyped-def]
        """The open loop from one guess (min-fuel: through the min-time optimum at full throttle)."""
        if self.cfg.objective != 0:
            # minimum fuel starts from the minimum-time optimum at full throttle (the flight code
            # solves it too: a second context with the time objective), as the ground does (nlp.py)
            time_opt = Nmpc(self.cfg.replace(objective=0))
            time_opt.load_plan(g.t0, g.horizon, g.states, g.controls)
            pre = time_opt.solve(t, x)
            self.pre_iterations = pre.sqp_iterations
            if pre.converged:
                p = time_opt.plan()
                controls = p.controls.copy()
                controls[:, 1] = MIN_FUEL_GUESS_THROTTLE   # the ground's documented guess
                g = Plan(t0=p.t0, horizon=p.horizon, states=p.states, controls=controls)
        self.nmpc.reset()
        self.nmpc.load_plan(g.t0, g.horizon, g.states, g.controls)
        return self.nmpc.solve(t, x)

    def command(self, t: float) -> tuple[float, float]:
        alpha, throttle, _, _ = self.nmpc.command(t)
        return alpha, throttle


__all__ = ["KernelGuidance", "kernel_config", "DAY_S"]
