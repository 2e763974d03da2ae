"""The receding-horizon strategies of Starek & Kolmanovsky (2012), sec. 2.3, as pure functions on `Plan`.

A plan (ogk_host.rendezvous.plan) is N equal subintervals from t0 to t_f = t0 + horizon, node states and node
controls, the control piecewise linear between the nodes. After the first subinterval [t0, t0 + h] has been
flown, the next OCP needs a guess (and a node count):

- SNN/SNNS (sec. 2.3.2-2.3.3): `snns_shift` drops the first subinterval (N -> N - 1); every remaining node
  keeps its time, state and control bit for bit, and node 0's state becomes the measured one.
- SNNS subdivision: `subdivide` splits each subinterval in two (N -> 2N). The midpoint control is the mean
  of the two ends, which is the piecewise-linear control itself at the midpoint, so the doubled plan's
  control equals the old one at every instant; the midpoint state is the linear interpolation of the ends
  (only a multiple-shooting guess: the solver closes the continuity defects). `adopt_doubled` is the
  doubling test (percentage improvement GREATER than the threshold; the paper's text says "less",
  erratum), also adopting 2N when N failed and 2N converged.
- CNCN (sec. 2.3.1): `regrid` keeps N and spreads the nodes over [t, t_f of the previous plan]; controls are
  the previous piecewise-linear control sampled at the new node times (exact there), states the linear
  interpolation of the previous node states (the multiple-shooting guess), node 0 the measured state.

The minimum node count (`snns_guess`): the paper enforces one "to prevent a loss of controllability" and
does not say how. Ours: when the shift would leave fewer than `min_nodes` subintervals, the previous plan
is regridded with `min_nodes` subintervals over the remaining horizon (CNCN's rule at the tail), so N never
drops below `min_nodes` and the subintervals keep shrinking towards t_f. Subdivision stays a decision of
the doubling test only (it is never forced), so the limit on subdivisions means what it says.

All times are normalised (TU), states (r, theta, v_r, v_theta, m) normalised as in docs/design/nmpc.md.
"""
from __future__ import annotations

import dataclasses

import numpy as np
from numpy.typing import ArrayLike, NDArray
from ogk_host.rendezvous.plan import Plan

FloatArray = NDArray[np.float64]

STRATEGIES = ("snns", "cncn")


def _with_state0(states: FloatArray, x0: ArrayLike) -> FloatArray:
    out = np.array(states, dtype=np.float64, copy=True)
    out[0] = np.asarray(x0, dtype=np.float64)
    return out


def snns_shift(plan: Plan, x_measured: ArrayLike) -> Plan:
    """The previous plan without its first subinterval (N -> N - 1), node 0 = the measured state.

    The new t0 is the old node 1's time (t0 + h) and the subinterval length h is unchanged: nodes 1..N of
    `plan` become nodes 0..N-1, their controls and (except node 0's) states bit-identical."""
    if plan.nodes < 2:
        raise ValueError(f"cannot shift a plan of {plan.nodes} subinterval(s)")
    h = plan.step
    return Plan(t0=plan.t0 + h, horizon=h * (plan.nodes - 1),
                states=_with_state0(plan.states[1:], x_measured),
                controls=np.array(plan.controls[1:], dtype=np.float64, copy=True))


def subdivide(plan: Plan) -> Plan:
    """Each subinterval split in two (N -> 2N): even nodes are the old nodes (bit-identical), odd nodes the
    midpoints with the mean of the end controls (exact for a piecewise-linear control) and the mean of the
    end states (a linear-interpolation guess)."""
    n = plan.nodes
    states = np.empty((2 * n + 1, plan.states.shape[1]))
    controls = np.empty((2 * n + 1, plan.nu))
    states[0::2] = plan.states
    controls[0::2] = plan.controls
    states[1::2] = 0.5 * (plan.states[:-1] + plan.states[1:])
    controls[1::2] = 0.5 * (plan.controls[:-1] + plan.controls[1:])
    return Plan(t0=plan.t0, horizon=plan.horizon, states=states, controls=controls)


def _interp_rows(t_new: FloatArray, t_old: FloatArray, rows: FloatArray) -> FloatArray:
    return np.stack([np.interp(t_new, t_old, rows[:, j]) for j in range(rows.shape[1])], axis=-1)


def regrid(plan: Plan, t: float, x_measured: ArrayLike, nodes: int, min_horizon: float = 0.0) -> Plan:
    """CNCN (sec. 2.3.1): `nodes` equal subintervals from t to the previous plan's t_f (at least
    `min_horizon` long: a plan whose t_f has passed is stretched to that), the previous control sampled at the
    new node times (held at the ends beyond the old plan), the node states interpolated linearly in time,
    node 0 the measured state."""
    if nodes < 1:
        raise ValueError(f"nodes must be >= 1, got {nodes}")
    horizon = max(plan.t_f - t, min_horizon)
    if not horizon > 0.0:
        raise ValueError(f"no horizon left: t = {t} is past t_f = {plan.t_f}")
    t_new = t + horizon / nodes * np.arange(nodes + 1)
    t_old = plan.node_times()
    controls = np.stack([plan.control_at(float(tk)) for tk in t_new])
    states = _interp_rows(t_new, t_old, plan.states)
    return Plan(t0=t, horizon=horizon, states=_with_state0(states, x_measured), controls=controls)


def snns_guess(plan: Plan, t: float, x_measured: ArrayLike, min_nodes: int,
               min_horizon: float = 0.0) -> Plan:
    """The SNNS guess at time t (= the end of `plan`'s first subinterval when it was flown): the shift when
    it leaves at least `min_nodes` subintervals, otherwise `plan` regridded with `min_nodes` subintervals
    (module docstring). A t other than plan.t0 + h (a flight that does not follow the plan's grid) also
    regrids, keeping N - 1 subintervals."""
    n_next = plan.nodes - 1
    on_grid = abs(t - (plan.t0 + plan.step)) <= 1e-12 * max(1.0, abs(t))
    if n_next >= min_nodes and on_grid:
        return snns_shift(plan, x_measured)
    return regrid(plan, t, x_measured, max(n_next, min_nodes), min_horizon)


def cost_improvement_percent(cost_n: float, cost_2n: float) -> float:
    """100 (J_N - J_2N) / |J_N|: positive when the doubled plan is cheaper."""
    return 100.0 * (cost_n - cost_2n) / abs(cost_n) if cost_n != 0.0 else 0.0


def adopt_doubled(cost_n: float | None, cost_2n: float | None, threshold_percent: float) -> bool:
    """The SNNS doubling test (sec. 2.3.3 with the erratum): adopt 2N when both converged and 2N improves the
    cost by MORE than `threshold_percent`, or when N failed (None) and 2N converged."""
    if cost_2n is None:
        return False
    if cost_n is None:
        return True
    return cost_improvement_percent(cost_n, cost_2n) > threshold_percent


@dataclasses.dataclass(frozen=True)
class StrategySettings:
    """The strategy's parameters (scenario [nmpc]; docs/design/nmpc.md, "Closed loop")."""

    name: str                           #: "snns" or "cncn"
    doubling_threshold_percent: float
    max_subdivisions: int
    min_nodes: int
    min_horizon: float = 0.0            #: floor of a regridded horizon [TU] (a plan whose t_f has passed)

    def __post_init__(self) -> None:
        if self.name not in STRATEGIES:
            raise ValueError(f"strategy must be one of {', '.join(STRATEGIES)}, got {self.name!r}")
