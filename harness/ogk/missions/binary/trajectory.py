"""A corrected transfer flown again, independently of the kernel: each arc re-propagated with scipy's DOP853
(ogk_host.binary.reference) exactly as the kernel defines the arcs (forward from the left anchor to the
meeting interface, backward from the right anchor; docs/design/blt.md sec. 1), the same error vector recomputed,
and samples of the trajectory for the plots. Normalised units."""
from __future__ import annotations

import dataclasses

import numpy as np
from scipy.integrate import solve_ivp

from ogk_bindings.blt import Transfer
from ogk_host.binary.dynamics import Burn, FloatArray, Model, state_derivative
from ogk_host.binary.guess import Layout
from ogk_host.binary.reference import propagate_chain


def _segments(layout: Layout, tr: Transfer, lo: int, hi: int) -> list[tuple]:
    out: list[tuple] = []
    for k in range(lo, hi):
        s = tr.segments[k]
        out.append(("burn", s[0:3], s[3:6], s[6]) if layout.kinds[k] == "burn" else ("coast", s[6]))
    return out


def _start_time(tr: Transfer, k: int) -> float:
    return float(tr.t0 + tr.segments[:k, 6].sum())


def _start_mass(model: Model, layout: Layout, tr: Transfer, k: int) -> float:
    burned = sum(tr.segments[j, 6] for j in range(k) if layout.kinds[j] == "burn")
    return float(tr.mass0 - model.mass_flow * burned)


def _anchors(layout: Layout) -> list[int]:
    return [0, *layout.free_nodes, len(layout.kinds)]


def _meets(layout: Layout) -> list[int]:
    return list(layout.meets) if layout.meets else [*layout.free_nodes, len(layout.kinds)]


@dataclasses.dataclass(frozen=True)
class Reprop:
    errors: FloatArray            #: the error vector (eqs. 65, 70) by DOP853
    err_norm: float
    impact: bool
    closest_approach: tuple[float, float]   #: [LU]


def reference_errors(model: Model, layout: Layout, tr: Transfer) -> Reprop:
    """The kernel's error vector recomputed by DOP853 (rtol 1e-12, atol 1e-13)."""
    anchors, meets = _anchors(layout), _meets(layout)
    errs: list[float] = []
    closest = [np.inf, np.inf]
    impact = False
    for a in range(len(anchors) - 1):
        lo, hi, meet = anchors[a], anchors[a + 1], meets[a]
        left = tr.x0 if a == 0 else tr.nodes[a - 1]
        fwd = propagate_chain(model, left, _segments(layout, tr, lo, meet), t0=_start_time(tr, lo),
                              mass0=_start_mass(model, layout, tr, lo))
        impact |= fwd.impact is not None
        closest = [min(closest[i], fwd.closest_approach[i]) for i in range(2)]
        last = a == len(anchors) - 2
        if meet == hi and last:
            mask = [i for i in range(6) if (layout.target_mask >> i) & 1]
            errs.extend(float(fwd.state[i] - tr.xf[i]) for i in mask)
            continue
        right = tr.xf if last else tr.nodes[a]
        bwd = propagate_chain(model, right, _segments(layout, tr, meet, hi), t0=_start_time(tr, hi),
                              mass0=_start_mass(model, layout, tr, hi), backward=True)
        impact |= bwd.impact is not None
        closest = [min(closest[i], bwd.closest_approach[i]) for i in range(2)]
        errs.extend((fwd.state - bwd.state).tolist())
    e = np.array(errs)
    return Reprop(errors=e, err_norm=float(np.linalg.norm(e)), impact=impact,
                  closest_approach=(float(closest[0]), float(closest[1])))


@dataclasses.dataclass(frozen=True)
class Samples:
    time: FloatArray              #: (n,) [TU] absolute
    state: FloatArray             #: (n, 6)
    thrust: FloatArray            #: (n, 3) thrust direction (zeros on coasts)
    segment: np.ndarray           #: (n,) segment index


def sample(model: Model, layout: Layout, tr: Transfer, per_tu: int = 400) -> Samples:
    """Samples of the flown trajectory: each segment propagated from the state its arc gives it (forward
    from the left anchor up to the meeting interface, backward from the right anchor after it)."""
    anchors, meets = _anchors(layout), _meets(layout)
    times, states, thrusts, segs = [], [], [], []
    for a in range(len(anchors) - 1):
        lo, hi, meet = anchors[a], anchors[a + 1], meets[a]
        x = np.array(tr.x0 if a == 0 else tr.nodes[a - 1], dtype=float)
        pieces: dict[int, tuple[FloatArray, FloatArray]] = {}
        for k in range(lo, meet):
            pieces[k] = _segment(model, layout, tr, k, x, per_tu, backward=False)
            x = pieces[k][1][-1]
        x = np.array(tr.xf if a == len(anchors) - 2 else tr.nodes[a], dtype=float)
        for k in range(hi - 1, meet - 1, -1):
            t, s = _segment(model, layout, tr, k, x, per_tu, backward=True)
            x = s[0]
            pieces[k] = (t, s)
        for k in range(lo, hi):
            t, s = pieces[k]
            times.append(t)
            states.append(s)
            segs.append(np.full(t.size, k))
            seg = tr.segments[k]
            if layout.kinds[k] == "burn":
                w = seg[None, 0:3] + (t - _start_time(tr, k))[:, None] * seg[None, 3:6]
                thrusts.append(w / np.linalg.norm(w, axis=1, keepdims=True))
            else:
                thrusts.append(np.zeros((t.size, 3)))
    return Samples(time=np.concatenate(times), state=np.vstack(states), thrust=np.vstack(thrusts),
                   segment=np.concatenate(segs))


def _segment(model: Model, layout: Layout, tr: Transfer, k: int, x: FloatArray, per_tu: int,
             backward: bool) -> tuple[FloatArray, FloatArray]:
    """(times increasing (n,), states (n, 6)) of segment k from x at its start (forward) or end (backward)."""
    t_start = _start_time(tr, k)
    duration = float(tr.segments[k, 6])
    m_start = _start_mass(model, layout, tr, k)
    burn = None
    if layout.kinds[k] == "burn":
        seg = tr.segments[k]
        burn = Burn(a=tuple(seg[0:3]), b=tuple(seg[3:6]), start_time=t_start, mass_start=m_start)

    def rhs(t: float, s: FloatArray) -> FloatArray:
        return state_derivative(model, t, s, mass=m_start, burn=burn)
    n = max(2, int(per_tu * duration) + 1)
    grid = np.linspace(t_start, t_start + duration, n)
    span = (grid[-1], grid[0]) if backward else (grid[0], grid[-1])
    sol = solve_ivp(rhs, span, x, method="DOP853", rtol=1e-11, atol=1e-12, t_eval=grid[::-1] if backward else grid)
    t, s = sol.t, sol.y.T
    if backward:
        t, s = t[::-1], s[::-1]
    return t, s
