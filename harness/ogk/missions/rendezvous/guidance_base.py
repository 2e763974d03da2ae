"""What every guidance of the rendezvous closed loop shares (Starek & Kolmanovsky 2012, sec. 2.3).

`Guidance` is what the closed loop (closed_loop.py) flies: at the start of each control subinterval it calls
`replan(t, x)` with the measured (truth) state, then flies `command(t)` until the returned `t_next` (the end
of the plan's first subinterval), and replans there. Its implementations:

- `guidance.IpoptGuidance`: the ground NLP (ogk_host.rendezvous.nlp, CasADi + IPOPT) re-solved with the
  strategies of strategy.py;
- `kernel_guidance.KernelGuidance`: the flight code's `ogk_nmpc` (C kernel, through cffi);

`guidance_factory.make_guidance` picks one by the `--solver` name. This module holds what both
implementations use (`ReplanInfo`, `first_guess`, `strategy_settings`) and imports neither, so that no
module of the family imports one that imports it back (tests/python/test_import_cycles.py).

All times and states are normalised (TU, LU, VU, MU: docs/design/nmpc.md, "Units").
"""
from __future__ import annotations

import dataclasses
from typing import Protocol

import numpy as np
from numpy.typing import ArrayLike, NDArray
from ogk_host.rendezvous.dynamics import DAY_S, Model
from ogk_host.rendezvous.ocp import DEFAULT_GUESS_SHAPE
from ogk_host.rendezvous.ocp import GUESS_PROPELLANT_FRACTION, guess_alpha_rad, guess_transfer_days
from ogk_host.rendezvous.ocp import phase_matched_guess
from ogk_host.rendezvous.plan import Plan
from ogk_host.rendezvous.scenario import RendezvousScenario

from . import strategy as st

FloatArray = NDArray[np.float64]


@dataclasses.dataclass(frozen=True)
class ReplanInfo:
    """What one replan did (one row of the flight's history)."""

    t: float                    #: time of the replan [TU]
    t_next: float               #: time of the next replan: end of the flown plan's first subinterval [TU]
    converged: bool             #: the plan flown from t was solved now (False: the previous plan is flown on)
    failed: bool                #: no solve of this replan converged
    iterations: int             #: solver iterations, every solve of this replan (N and 2N)
    solve_time_s: float         #: solver wall time, every solve of this replan
    solves: int                 #: NLP solves in this replan (SNNS: 2 while doubling is tested)
    nodes: int                  #: N of the plan flown from t
    subdivided: bool            #: the doubled plan was adopted here
    objective: float | None     #: cost-to-go of the adopted solution (normalised), None when failed
    status: str                 #: solver status of the adopted (or failed N) solve
    plan: Plan                  #: the plan flown from t (on a failure: the previous plan's remainder)
    status_n: str = ""          #: status of the N solve (SNNS: before the doubling test)
    cost_n: float | None = None     #: cost-to-go of the N solve (None when it failed)
    cost_2n: float | None = None    #: cost-to-go of the 2N solve (None: failed or not tried)
    outside_set: bool = False       #: the plan converged outside its terminal set: the target is out of reach


class Guidance(Protocol):
    """What the closed loop needs from a guidance implementation."""

    name: str

    def replan(self, t: float, x: FloatArray) -> ReplanInfo:
        """Called at the start of each control subinterval with the measured state."""
        ...

    def command(self, t: float) -> tuple[float, float]:
        """(alpha [rad], throttle w in [0, 1]) at time t: the piecewise-linear plan control (w = 1 for a
        constant-thrust engine)."""
        ...


#: Multiples of the sized guess tried in turn when a first solve does not converge.
GUESS_FACTORS = (1.0, 0.8, 1.25, 0.65, 1.6)


def first_guesses(scenario: RendezvousScenario, nodes: int, t: float, x: ArrayLike, nu: int) -> list[Plan]:
    """The documented open-loop guess (ocp.default_guess: phase-matched, smoothstep radius, 135 deg)
    with t_f sized from the vehicle and the transfer (`guess_transfer_days`; 370 d for the paper's),
    then the same at the other GUESS_FACTORS (none burning more than the propellant): the first
    replan tries them in turn. A throttle column of 1 (full thrust) when nu = 2. The guess's mass never
    goes below the dry mass."""
    model = Model.for_scenario(scenario)
    base = guess_transfer_days(scenario)
    cap = GUESS_PROPELLANT_FRACTION * scenario.propellant_kg / max(
        model.mass_flow * model.units.mass_flow_kg_s, 1e-30) / DAY_S
    dry = scenario.dry_mass_kg / model.units.mass_kg
    plans = []
    for factor in GUESS_FACTORS:
        days = base * factor
        if factor > 1.0:            # a longer guess only while full thrust stays within the propellant
            days = min(days, cap)
            if days <= base * 1.0001:
                continue
        g = phase_matched_guess(model, nodes, days, DEFAULT_GUESS_SHAPE, guess_alpha_rad(scenario),
                                label="documented")
        controls = g.controls.reshape(-1, 1)
        if nu == 2:
            controls = np.hstack([controls, np.ones_like(controls)])
        states = np.array(g.states, copy=True)
        states[:, 4] = np.maximum(states[:, 4], dry)
        states[0] = np.asarray(x, dtype=np.float64)
        plans.append(Plan(t0=t, horizon=g.t_f, states=states, controls=controls))
    return plans


def first_guess(scenario: RendezvousScenario, nodes: int, t: float, x: ArrayLike, nu: int) -> Plan:
    """The first of `first_guesses` (for the paper's vehicle: the documented guess, t_f 370 d)."""
    return first_guesses(scenario, nodes, t, x, nu)[0]


def strategy_settings(scenario: RendezvousScenario, name: str | None = None) -> st.StrategySettings:
    """The strategy of scenario [nmpc] (`name` overrides its default strategy)."""
    n = scenario.nmpc
    units = Model.for_scenario(scenario).units
    return st.StrategySettings(name=name or n.strategy, doubling_threshold_percent=n.doubling_threshold_percent,
                               max_subdivisions=n.max_subdivisions, min_nodes=n.min_nodes,
                               min_horizon=DAY_S / units.time_s)
