"""The proximity approach's closed loop: the guidance replans from the measured truth state every
[guidance] replan_period_s (or final_phase_s before the plan's end when that comes first), the truth (truth.py) flies its command in between, until the plan has less
than [guidance] final_phase_s left: then it is flown to its end, where the flight is judged (the truth's
state against the hold point at rest), with the keep-out checked on the truth all along.

The run's dispersions (dispersions.py) are drawn first from its own stream: the start's position,
velocity and mass, the thrust-level bias; then the thrust-angle noise, one draw per replan period (draw k
covers [k P, (k + 1) P) from t = 0, held constant in between, the final phase included)."""
from __future__ import annotations

import dataclasses
import math
from typing import Any

import numpy as np
from numpy.typing import NDArray
from ogk_host.proximity.scenario import ProximityScenario

from .dispersions import Draw, draw, flown
from .guidance import Guidance, Plan, ReplanInfo, make_guidance
from .truth import Truth, hill_state

FloatArray = NDArray[np.float64]
MAX_REPLANS = 200
#: a plan that ends within final_phase_s + this of the replan is flown to its end (a replan made
#: final_phase_s before the end may move the end by a rounding)
FINAL_SLACK_S = 1.0


@dataclasses.dataclass
class FlightResult:
    reason: str                     #: "end_of_plan" (judged by [acceptance]) or why it stopped
    t_f_s: float
    final_hill: FloatArray          #: (x, y, v_x, v_y) of the truth at the end [m, m/s]
    hold_error: FloatArray          #: final_hill - (hold, 0, 0)
    fuel_kg: float                  #: m_0 - m_f of the truth
    delta_v_m_s: float              #: v_e ln(m_0 / m_f)
    keepout_clearance_m: float      #: min over the flight and the discs of |p - c| - R (< 0: entered)
    replans: list[ReplanInfo]
    solves: int
    failed_solves: int
    draw: Draw
    t: FloatArray                   #: truth samples [s]
    hill: FloatArray                #: (n, 4) Hill-frame truth states
    mass: FloatArray                #: (n,) [kg]
    command: FloatArray             #: (n, 2) commanded (alpha, w) at the samples
    offset: FloatArray              #: (n,) thrust-angle noise at the samples [rad]
    first_plan: Plan | None = None

    @property
    def completed(self) -> bool:
        return self.reason == "end_of_plan"

    def record(self) -> dict[str, Any]:
        e = self.hold_error
        ms = [r.solve_s * 1e3 for r in self.replans] or [0.0]
        return {"completed": self.completed, "reason": self.reason, "t_f_s": self.t_f_s,
                "hold_error_x_m": float(e[0]), "hold_error_y_m": float(e[1]),
                "hold_error_vx_m_s": float(e[2]), "hold_error_vy_m_s": float(e[3]),
                "miss_m": float(math.hypot(e[0], e[1])), "miss_velocity_m_s": float(math.hypot(e[2], e[3])),
                "fuel_kg": self.fuel_kg, "delta_v_m_s": self.delta_v_m_s,
                "keepout_clearance_m": self.keepout_clearance_m, "replans": len(self.replans),
                "solves": self.solves, "failed_solves": self.failed_solves,
                **self.draw.record(),
                "timing.solve_ms_median": float(np.median(ms)), "timing.solve_ms_max": float(np.max(ms))}


def clearance(scn: ProximityScenario, hill: FloatArray) -> float:
    """min over the samples and the truth's discs of |p - c| - R [m] (inf without a disc)."""
    if not scn.keepouts:
        return math.inf
    return float(min(np.min(np.hypot(hill[:, 0] - k.centre_m[0], hill[:, 1] - k.centre_m[1])) - k.radius_m
                     for k in scn.keepouts))


def fly(scn: ProximityScenario, solver: str, first: Plan, seed: int, perturbed: bool = True,
        guidance: Guidance | None = None) -> FlightResult:
    g = scn.guidance
    d = draw(flown(scn.dispersions, perturbed), seed)
    v = scn.vehicle
    truth = Truth(scn.orbit.mu_m3_s2, v.thrust_max_n, v.exhaust_velocity_m_s, d.thrust_bias, scn.min_throttle)
    rel0 = (scn.start[0] + d.position_m[0], scn.start[1] + d.position_m[1],
            scn.start[2] + d.velocity_m_s[0], scn.start[3] + d.velocity_m_s[1])
    m0 = v.initial_mass_kg + d.mass_kg
    s = truth.initial_state(scn.orbit.radius_m, rel0, m0)
    law = guidance if guidance is not None else make_guidance(solver, scn, first)
    period = g.replan_period_s
    t = 0.0
    ts, ss, cmds, offs = [np.array([0.0])], [s[None, :]], [np.array([law.command(0.0)])], [np.zeros(1)]
    replans: list[ReplanInfo] = []
    reason = ""
    while not reason:
        if len(replans) >= MAX_REPLANS:
            reason = "max_replans"
            break
        x = np.concatenate([hill_state(s), [s[8]]])
        info = law.replan(t, x)
        replans.append(info)
        if len(replans) == 1 and not info.converged:
            reason = f"no first plan: {info.status}"
            break
        node_t, _, _ = law.plan_si()
        t_f = float(node_t[-1])
        final = t_f - t <= g.final_phase_s + FINAL_SLACK_S
        # the next replan a period on, or final_phase_s before the plan's end if that comes first (so
        # that the last replan is never later than that)
        t_next = t_f if final else min(t + period, t_f - g.final_phase_s)
        edges = [t] + [k * period for k in range(int(math.floor(t / period)) + 1,
                                                 int(math.ceil(t_next / period)))] + [t_next]
        for a, b in zip(edges[:-1], edges[1:]):
            if not b > a:
                continue
            off = d.angle(int(math.floor(a / period + 1e-9)))
            tg, sg = truth.propagate(a, s, b, law.command, off, breaks=node_t)
            dry = np.nonzero(sg[1:, 8] < v.dry_mass_kg)[0]
            if len(dry):
                k = int(dry[0]) + 1
                tg, sg = tg[: k + 1], sg[: k + 1]
                reason = f"propellant: ran dry (dry mass {v.dry_mass_kg:g} kg)"
            ts.append(tg[1:])
            ss.append(sg[1:])
            cmds.append(np.array([law.command(float(tk)) for tk in tg[1:]]).reshape(-1, 2))
            offs.append(np.full(len(tg) - 1, off))
            t, s = float(tg[-1]), sg[-1]
            if reason:
                break
        if final and not reason:
            reason = "end_of_plan"
    t_arr = np.concatenate(ts)
    s_arr = np.vstack(ss)
    hill = hill_state(s_arr)
    hold = np.array([*scn.hold_point_m, 0.0, 0.0])
    m_f = float(s_arr[-1, 8])
    return FlightResult(
        reason=reason, t_f_s=t, final_hill=hill[-1], hold_error=hill[-1] - hold, fuel_kg=m0 - m_f,
        delta_v_m_s=v.exhaust_velocity_m_s * math.log(m0 / m_f), keepout_clearance_m=clearance(scn, hill),
        replans=replans, solves=law.solves, failed_solves=law.failed_solves, draw=d, t=t_arr, hill=hill,
        mass=s_arr[:, 8], command=np.vstack(cmds), offset=np.concatenate(offs), first_plan=first)
