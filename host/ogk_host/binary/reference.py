"""Reference propagation of a BLT segment chain (docs/design/blt.md section 1; Xiong & Wang eqs. 8-10 and 22):
scipy's DOP853 at rtol 1e-12, atol 1e-13, independent of the kernel's integrator, in the same model
(`dynamics.Model`, e.g. from `kernel_model`).

A chain is a list of segments, each ("burn", A, B, T) -- thrust along (A + B tau) / |A + B tau|, tau the
time since the burn started (eq. 22) -- or ("coast", T), T >= 0 [TU]. Mass is the fraction m / m0, constant
on coasts and m = m_start - mass_flow tau during a burn (closed form, eq. 8). The Sun's direction depends
on the absolute time t (phi = sun_angle0 + sun_rate t), so the chain starts at a time t0.

`propagate_chain` flies the chain forward from the start, or backward from the end (the same segments,
traversed in reverse: then `state`, `t0`, `mass0` are the chain's end state, end time and end mass). It
reports the closest approach to each body's centre (the zeros of rho . v along the way and the segment
ends) and stops at an impact (a terminal event on each impact radius, model.body_radius).
"""
from __future__ import annotations

import dataclasses
import math
from typing import Any, Sequence

import numpy as np
from numpy.typing import ArrayLike
from scipy.integrate import solve_ivp

from .dynamics import Burn, FloatArray, Model, kernel_model, model_from_scenario, state_derivative

__all__ = ["ChainResult", "Segment", "kernel_model", "model_from_scenario", "propagate_chain",
           "validate_segments", "RTOL", "ATOL"]

RTOL, ATOL = 1e-12, 1e-13
Segment = tuple[Any, ...]


@dataclasses.dataclass(frozen=True)
class ChainResult:
    """The outcome of `propagate_chain`."""

    state: FloatArray                   #: the state where the propagation stopped (6,) [LU, VU]
    mass: float                         #: the mass fraction there
    time: float                         #: the time there [TU]
    closest_approach: tuple[float, float]   #: smallest distance to each body's centre on the way [LU]
    impact: int | None                  #: 0 (primary) / 1 (secondary) if an impact sphere was hit
    impact_time: float | None           #: when [TU]
    interfaces: FloatArray              #: the states at the segment boundaries reached, in flight order


def validate_segments(segments: Sequence[Segment]) -> list[Segment]:
    """Normalises ("burn", A, B, T) / ("coast", T) tuples (A, B as 3-vectors of floats); ValueError otherwise."""
    out: list[Segment] = []
    for k, seg in enumerate(segments):
        if not seg or seg[0] not in ("burn", "coast"):
            raise ValueError(f"segment {k}: must start with 'burn' or 'coast', got {seg!r}")
        if seg[0] == "coast":
            if len(seg) != 2:
                raise ValueError(f"segment {k}: a coast is ('coast', T), got {seg!r}")
            duration = float(seg[1])
            if not (math.isfinite(duration) and duration >= 0.0):
                raise ValueError(f"segment {k}: T must be finite and >= 0, got {seg[1]!r}")
            out.append(("coast", duration))
            continue
        if len(seg) != 4:
            raise ValueError(f"segment {k}: a burn is ('burn', A, B, T), got {seg!r}")
        a = np.asarray(seg[1], dtype=float)
        b = np.asarray(seg[2], dtype=float)
        duration = float(seg[3])
        if a.shape != (3,) or b.shape != (3,) or not (np.all(np.isfinite(a)) and np.all(np.isfinite(b))):
            raise ValueError(f"segment {k}: A and B must be finite 3-vectors")
        if not (math.isfinite(duration) and duration >= 0.0):
            raise ValueError(f"segment {k}: T must be finite and >= 0, got {seg[3]!r}")
        out.append(("burn", tuple(a.tolist()), tuple(b.tolist()), duration))
    return out


def propagate_chain(model: Model, state: ArrayLike, segments: Sequence[Segment], *, t0: float = 0.0,
                    mass0: float = 1.0, backward: bool = False, rtol: float = RTOL,
                    atol: float = ATOL) -> ChainResult:
    """Flies `segments` from `state` at time t0 with mass fraction mass0 (backward: from the chain's end,
    see the module docstring). Returns where it stopped, the mass there, the closest approaches and the
    impact, if any."""
    segs = validate_segments(segments)
    x = np.asarray(state, dtype=float).copy()
    if x.shape != (6,):
        raise ValueError(f"state must have 6 components, got shape {x.shape}")
    if not mass0 > 0.0:
        raise ValueError(f"mass0 must be > 0, got {mass0!r}")
    t, m = float(t0), float(mass0)
    centres = model.body_positions
    closest = [float(np.linalg.norm(x[0:3] - c)) for c in centres]
    interfaces = [x.copy()]
    order = list(reversed(segs)) if backward else segs

    for seg in order:
        duration = seg[-1]
        if duration == 0.0:
            interfaces.append(x.copy())
            continue
        t_end = t - duration if backward else t + duration
        burn: Burn | None = None
        if seg[0] == "burn":
            start = t_end if backward else t
            m_start = m + model.mass_flow * duration if backward else m
            if not m_start - model.mass_flow * duration > 0.0:
                raise ValueError("the chain burns more than the whole mass (mass fraction <= 0)")
            burn = Burn(a=seg[1], b=seg[2], start_time=start, mass_start=m_start)
        mass_coast = m

        def rhs(tt: float, s: FloatArray, burn: Burn | None = burn, mc: float = mass_coast) -> FloatArray:
            return state_derivative(model, tt, s, mass=mc, burn=burn)

        events = []
        for i, centre in enumerate(centres):
            def approach(tt: float, s: FloatArray, c: FloatArray = centre) -> float:
                return float(np.dot(s[0:3] - c, s[3:6]))
            events.append(approach)
        impact_bodies = [i for i in range(2) if model.body_radius[i] > 0.0]
        for i in impact_bodies:
            def hit(tt: float, s: FloatArray, c: FloatArray = centres[i], rad: float = model.body_radius[i]) -> float:
                return float(np.linalg.norm(s[0:3] - c) - rad)
            hit.terminal = True  # type: ignore[attr-defined]
            events.append(hit)
        sol = solve_ivp(rhs, (t, t_end), x, method="DOP853", rtol=rtol, atol=atol, events=events)
        if sol.status < 0:
            raise RuntimeError(f"propagation failed: {sol.message}")
        for i in range(2):
            for s in sol.y_events[i]:
                closest[i] = min(closest[i], float(np.linalg.norm(s[0:3] - centres[i])))
        x = sol.y[:, -1].copy()
        t_stop = float(sol.t[-1])
        if burn is not None:
            m = float(burn.mass_start - model.mass_flow * (t_stop - burn.start_time))
        for i in range(2):
            closest[i] = min(closest[i], float(np.linalg.norm(x[0:3] - centres[i])))
        for k, i in enumerate(impact_bodies):
            if sol.t_events[2 + k].size > 0:
                return ChainResult(state=x, mass=m, time=t_stop, closest_approach=(closest[0], closest[1]),
                                   impact=i, impact_time=t_stop, interfaces=np.array(interfaces))
        t = t_end
        interfaces.append(x.copy())
    return ChainResult(state=x, mass=m, time=t, closest_approach=(closest[0], closest[1]), impact=None,
                       impact_time=None, interfaces=np.array(interfaces))
