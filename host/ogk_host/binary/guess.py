"""Initial guesses of the BLT corrector (Xiong & Wang, sec. III.C): the single-burn guess SBIG (eqs. 23-31)
and the unilateral backward manifold-patching guess UbMPIG (eqs. 53-60), as kernel transfers.

A guess is a `Layout` (the kernel's transfer structure: segment kinds, free nodes, meeting interfaces;
docs/design/blt.md sec. 1) and the values of an `ogk_blt_transfer_t` (start, target, segment parameters, nodes).
Everything is in the normalised units of docs/design/blt.md; the orbits and manifolds come from the
gravity-only model (the paper's "simplified model", sec. II.B.1); the phase adjustment of eq. (29) flies
the burn with the kernel's own propagator (ogk_blt_propagate: the same integrator the corrector uses).
"""
from __future__ import annotations

import dataclasses
import math
from typing import Any

import numpy as np
from numpy.typing import ArrayLike
from scipy.integrate import solve_ivp
from scipy.optimize import minimize

from ogk_bindings.blt import BURN, COAST, Blt, BltConfig, Transfer

from .dynamics import FloatArray, GravityField, Model, jacobi
from .manifolds import manifold_states
from .orbits import ATOL, RTOL, CorrectionError, PeriodicOrbit, propagate

KIND = {"burn": BURN, "coast": COAST}


@dataclasses.dataclass(frozen=True)
class Layout:
    """The kernel's transfer structure (ogk_blt_config_t fields)."""

    kinds: tuple[str, ...]                  #: "burn" / "coast" per segment
    free_nodes: tuple[int, ...] = ()        #: interior interfaces holding a free node
    meets: tuple[int, ...] = ()             #: meeting interface of each arc (default: its right anchor)
    start_free_mask: int = 0
    target_mask: int = 0x3F

    def config_fields(self) -> dict[str, Any]:
        meets = self.meets or tuple(list(self.free_nodes) + [len(self.kinds)])
        return dict(n_segments=len(self.kinds), segment_kind=[KIND[k] for k in self.kinds],
                    n_free_nodes=len(self.free_nodes), free_node_interface=list(self.free_nodes) or [0],
                    meet_interface=list(meets), start_free_mask=self.start_free_mask,
                    target_mask=self.target_mask)


@dataclasses.dataclass
class Guess:
    layout: Layout
    transfer: Transfer
    info: dict[str, Any]                    #: what the guess stage found (phases, delta-v, ...)


def kernel_config(model: Model, layout: Layout, **fields: Any) -> BltConfig:
    """The kernel configuration of `model` and `layout`, other fields from `fields`."""
    return BltConfig(model=model.as_dict(), **layout.config_fields(), **fields)


# ------------------------------------------------------------------------------------------ orbit phases

class OrbitPhase:
    """x(t) on a periodic orbit, t [TU] from its state0 (any real t: taken modulo the period)."""

    def __init__(self, orbit: PeriodicOrbit) -> None:
        self.orbit = orbit
        self._sol = propagate(orbit.model.gravity_only(), orbit.state0, orbit.period, dense_output=True)

    def __call__(self, t: ArrayLike) -> FloatArray:
        tt = np.mod(np.asarray(t, dtype=float), self.orbit.period)
        return np.asarray(self._sol.sol(tt)).T


# ------------------------------------------------------------------------------------------ SBIG

def blt_from_separation(dr: FloatArray, dv: FloatArray, thrust_accel: float) -> FloatArray:
    """eqs. (26)-(28): (A, B, T) from the closest state separation (dr, dv)."""
    nr = float(np.linalg.norm(dr))
    duration = math.sqrt(2.0 * nr / thrust_accel)                     # (26)
    a = dr / nr                                                       # (27)
    b = dv / float(np.linalg.norm(dv)) - dr / (nr * duration)         # (28)
    return np.concatenate([a, b, [duration]])


def closest_states(dep: OrbitPhase, arr: OrbitPhase, samples: int = 360) -> tuple[float, float]:
    """eqs. (23)-(25): the phases (t_i, t_t) [TU] of the closest pair of states of the two orbits (6-norm),
    a grid of `samples` phases each, then BFGS."""
    ti = np.linspace(0.0, dep.orbit.period, samples, endpoint=False)
    tt = np.linspace(0.0, arr.orbit.period, samples, endpoint=False)
    xi, xt = dep(ti), arr(tt)
    d2 = ((xt[None, :, :] - xi[:, None, :]) ** 2).sum(axis=2)
    i, j = np.unravel_index(int(np.argmin(d2)), d2.shape)

    def cost(p: FloatArray) -> float:
        return float(((arr(p[1]) - dep(p[0])) ** 2).sum())
    res = minimize(cost, np.array([ti[i], tt[j]]), method="BFGS")
    return float(res.x[0]), float(res.x[1])


def sbig(model: Model, departure: PeriodicOrbit, arrival: PeriodicOrbit, *, t0: float = 0.0,
         samples: int = 360, scan: int = 24) -> Guess:
    """Single-burn initial guess (sec. III.C.1): closest states (eqs. 23-25), BLT parameters (eqs. 26-28),
    then the phase adjustment of eqs. (29)-(31) with the burn flown in `model` (the corrector's model: an
    impact-free guess there is what the corrector needs): Nelder-Mead on (dt_i, dt_t) from three starts
    (0, 0), (-T/2, T/2), (-T, 0).

    Beyond the paper: when every start's burn hits a body (eq. 27 aims A at the target, and between the
    L2 and L1 halos the straight line goes through the secondary), the pair of phases is chosen on a
    `scan` x `scan` grid instead, as the impact-free pair whose eqs. (26)-(28) burn misses least."""
    dep, arr = OrbitPhase(departure), OrbitPhase(arrival)
    layout = Layout(kinds=("burn",))
    k = Blt(kernel_config(model, layout))

    def miss(ti: float, tt: float, params: FloatArray) -> float:
        tr = Transfer(t0=t0, x0=dep(ti), xf=arr(tt), segments=params[None, :])
        rep = k.evaluate(tr)
        return float(rep.err_norm ** 2) if rep.status == "OGK_OK" else math.inf

    def adjust(ti: float, tt: float, params: FloatArray) -> tuple[float, float, float]:
        T = params[6]
        best_fun, best_x = math.inf, (0.0, 0.0)
        for start in ((0.0, 0.0), (-0.5 * T, 0.5 * T), (-T, 0.0)):
            res = minimize(lambda v: min(miss(ti + v[0], tt + v[1], params), 1e6), np.array(start),
                           method="Nelder-Mead", options={"xatol": 1e-6, "fatol": 1e-12, "maxiter": 400})
            if res.fun < best_fun:
                best_fun, best_x = float(res.fun), (float(res.x[0]), float(res.x[1]))
        return best_fun, best_x[0], best_x[1]

    t_i, t_t = closest_states(dep, arr, samples)
    sep = arr(t_t) - dep(t_i)
    params = blt_from_separation(sep[0:3], sep[3:6], model.thrust_accel)
    fun, dt_i, dt_t = adjust(t_i, t_t, params)
    scanned = False
    if not fun < 1e6:
        scanned = True
        best = (math.inf, 0.0, 0.0, params)
        for ti in np.linspace(0.0, departure.period, scan, endpoint=False):
            for tt in np.linspace(0.0, arrival.period, scan, endpoint=False):
                s = arr(tt) - dep(ti)
                p = blt_from_separation(s[0:3], s[3:6], model.thrust_accel)
                f = miss(float(ti), float(tt), p)
                if f < best[0]:
                    best = (f, float(ti), float(tt), p)
        if not math.isfinite(best[0]):
            raise CorrectionError(f"every single-burn guess between the {departure.point} {departure.family} and the {arrival.point} {arrival.family} hits a body (a {scan} x {scan} scan of the phases)")
        _, t_i, t_t, params = best
        sep = arr(t_t) - dep(t_i)
        fun, dt_i, dt_t = adjust(t_i, t_t, params)
    x0, xf = dep(t_i + dt_i), arr(t_t + dt_t)
    tr = Transfer(t0=t0, x0=x0, xf=xf, segments=params[None, :])
    return Guess(layout=layout, transfer=tr,
                 info=dict(phase_departure=t_i + dt_i, phase_arrival=t_t + dt_t, closest_separation=sep.tolist(),
                           phase_shift=[dt_i, dt_t], guess_miss=math.sqrt(fun), impact_scan=scanned))


# ------------------------------------------------------------------------------------------ UbMPIG

@dataclasses.dataclass(frozen=True)
class Circle:
    """A circular orbit about the barycentre, radius [LU], prograde in the inertial frame."""

    radius: float

    @property
    def synodic_rate(self) -> float:
        """[rad/TU] angular rate in the synodic frame (inertial mean motion - 1)."""
        return self.radius ** -1.5 - 1.0

    def state(self, longitude: float) -> FloatArray:
        """Synodic state at a longitude [rad] (the angle from the x axis in the synodic frame)."""
        c, s = math.cos(longitude), math.sin(longitude)
        speed = self.radius * self.synodic_rate
        return np.array([self.radius * c, self.radius * s, 0.0, -speed * s, speed * c, 0.0])


def _backward_to_circle(model: Model, state: FloatArray, circle: Circle,
                        t_max: float) -> tuple[FloatArray, float] | None:
    """Backward flow of a stable-manifold state to its first crossing of the circle (from outside or
    inside), or None (impact, t_max)."""
    field = GravityField(model.gravity_only())
    r0 = float(np.linalg.norm(state[0:3]))

    def cross(t: float, s: FloatArray) -> float:
        return float(math.sqrt(s[0] ** 2 + s[1] ** 2 + s[2] ** 2) - circle.radius)
    cross.terminal = True  # type: ignore[attr-defined]
    cross.direction = 1.0 if r0 < circle.radius else -1.0  # type: ignore[attr-defined]
    events = [cross]
    for centre, radius in zip(model.body_positions, model.body_radius):
        def hit(t: float, s: FloatArray, c: FloatArray = centre, rr: float = radius) -> float:
            return float(np.linalg.norm(s[0:3] - c) - rr)
        hit.terminal = True  # type: ignore[attr-defined]
        events.append(hit)
    sol = solve_ivp(field.derivative, (0.0, -t_max), state, method="DOP853", rtol=1e-10, atol=1e-12,
                    events=events)
    if sol.t_events[0].size == 0:
        return None
    return sol.y_events[0][0].copy(), float(-sol.t_events[0][0])


def ubmpig(model: Model, circle: Circle, target: PeriodicOrbit, *, sign: int = -1,
           deviation_bounds: tuple[float, float] = (5e-2, 1.5e-1), phases: int = 120, coast_max: float = 20.0,
           coast_margin: float = 1.5, split_coast: bool = True, t0: float = 0.0) -> Guess:
    """Unilateral backward manifold patching (sec. III.C.2, eqs. 53-60), StoS read as OtoS for the circle
    (the departure longitude is free, eq. 55): the stable manifold of `target` (velocity-only deviation d,
    eq. 35, branch `sign`) flown backward to the circle; the patch minimises the total impulsive delta-v
    |dv_circle| + |dv_orbit| over the orbit phase and d (the paper's objective, eq. 55, replaces the circle's
    delta-v by the Jacobi-constant gap; we minimise the burn time itself). Then eqs. (57)-(60): burns along
    the impulses, T_k = |dv_k| / a_th, departure advanced by T_1 / 2 on the circle, arrival delayed by T_3 / 2
    on the orbit, coast = TOC - (T_1 + T_3) / 2. The free node at the end of the coast starts as the backward
    prediction from the target through the last burn, i.e. on the manifold: eq. (72)'s mean with the
    forward prediction is no guess here, as that prediction has coasted for TOC (several TU) along an
    unstable flow from an impulse replaced by a burn. Patches whose time of coasting is shorter than
    `coast_margin` times the total burn time are skipped (their coast would vanish in eq. 59). d is kept
    in `deviation_bounds` [VU]: the paper's d = 1e-6 makes the insertion burn a few milliseconds long and the
    coast days long; d is the insertion burn's delta-v here, so its floor sets a burn the thrusters can fly."""
    orbit_phase = OrbitPhase(target)
    taus = np.linspace(0.0, target.period, phases, endpoint=False)
    best: tuple[float, float, float] | None = None   # (cost, tau, d)

    def patch(tau: float, d: float) -> tuple[float, dict[str, Any]] | None:
        xs = manifold_states(target, [tau % target.period], stable=True, sign=sign, deviation=d,
                             velocity_only=True)[0]
        hit = _backward_to_circle(model, xs, circle, coast_max)
        if hit is None:
            return None
        xc, toc = hit
        lon = math.atan2(xc[1], xc[0])
        dv_circle = xc[3:6] - circle.state(lon)[3:6]
        dv_orbit = orbit_phase(tau)[3:6] - xs[3:6]
        cost = float(np.linalg.norm(dv_circle) + np.linalg.norm(dv_orbit))
        if toc < coast_margin * cost / model.thrust_accel:
            return None   # the burns (eq. 59) would eat the coast: not a burn-coast-burn transfer
        return cost, dict(tau=tau, d=d, longitude=lon, toc=toc, dv_circle=dv_circle, dv_orbit=dv_orbit,
                          crossing=xc, manifold_state=xs)

    d_lo, d_hi = deviation_bounds
    for d in np.geomspace(d_lo, d_hi, 3):
        for tau in taus:
            p = patch(float(tau), float(d))
            if p is not None and (best is None or p[0] < best[0]):
                best = (p[0], float(tau), float(d))
    if best is None:
        raise CorrectionError("no stable-manifold trajectory of the target orbit crosses the circle")
    res = minimize(lambda v: (patch(v[0], math.exp(v[1])) or (1e3, {}))[0],
                   np.array([best[1], math.log(best[2])]), method="Nelder-Mead",
                   bounds=[(None, None), (math.log(d_lo), math.log(d_hi))],
                   options={"xatol": 1e-7, "fatol": 1e-10, "maxiter": 300})
    found = patch(float(res.x[0]), math.exp(float(res.x[1])))
    if found is None or found[0] > best[0]:
        found = patch(best[1], best[2])
    assert found is not None
    info = found[1]
    acc = model.thrust_accel
    dv1, dv3 = info["dv_circle"], info["dv_orbit"]
    t1, t3 = float(np.linalg.norm(dv1)) / acc, float(np.linalg.norm(dv3)) / acc        # (57)
    u1, u3 = dv1 / np.linalg.norm(dv1), dv3 / np.linalg.norm(dv3)
    coast = info["toc"] - 0.5 * (t1 + t3)                                              # (59)
    if coast <= 0.0:
        raise CorrectionError(f"the burns ({t1:.3f} + {t3:.3f} TU) outlast the coast ({info['toc']:.3f} TU)")
    x0 = circle.state(info["longitude"] - circle.synodic_rate * 0.5 * t1)               # (60)
    xf = orbit_phase(info["tau"] + 0.5 * t3)
    if split_coast:
        # the free node in the middle of the coast: two arcs of TOC / 2 each instead of one of TOC
        segments = np.array([np.concatenate([u1, u1, [t1]]), [0, 0, 0, 0, 0, 0, 0.5 * coast],
                             [0, 0, 0, 0, 0, 0, 0.5 * coast], np.concatenate([u3, u3, [t3]])])
        layout = Layout(kinds=("burn", "coast", "coast", "burn"), free_nodes=(2,), meets=(2, 3))
    else:
        segments = np.array([np.concatenate([u1, u1, [t1]]), [0, 0, 0, 0, 0, 0, coast],
                             np.concatenate([u3, u3, [t3]])])
        layout = Layout(kinds=("burn", "coast", "burn"), free_nodes=(2,), meets=(1, 2))
    tr = Transfer(t0=t0, x0=x0, xf=xf, segments=segments, nodes=np.zeros((1, 6)))
    tr.nodes = predicted_node(model, layout, tr, how="backward")
    info_out = {k: (v.tolist() if isinstance(v, np.ndarray) else v) for k, v in info.items()}
    info_out.update(dv_total=float(np.linalg.norm(dv1) + np.linalg.norm(dv3)), burn_times=[t1, t3],
                    jacobi_gap=float(jacobi(model.gravity_only(), info["crossing"]) -
                                     jacobi(model.gravity_only(), circle.state(info["longitude"]))))
    return Guess(layout=layout, transfer=tr, info=info_out)


def predicted_node(model: Model, layout: Layout, tr: Transfer, how: str = "mean") -> FloatArray:
    """Each free node's first value: eq. (72)'s mean of the forward prediction from the start and the
    backward prediction from the target (how = "mean"), or either alone ("forward", "backward"); flown with
    DOP853 in `model` without SRP/Sun."""
    from .reference import propagate_chain
    nodes = []
    segs = [("burn", s[0:3], s[3:6], s[6]) if k == "burn" else ("coast", s[6])
            for k, s in zip(layout.kinds, tr.segments)]
    gm = dataclasses.replace(model.gravity_only(), thrust_accel=model.thrust_accel, mass_flow=model.mass_flow)
    for node in layout.free_nodes:
        fwd = propagate_chain(gm, tr.x0, segs[:node], t0=tr.t0, mass0=tr.mass0, rtol=1e-10, atol=1e-12)
        burned = sum(s[6] for k, s in zip(layout.kinds, tr.segments) if k == "burn")
        t_end = tr.t0 + float(sum(s[6] for s in tr.segments))
        bwd = propagate_chain(gm, tr.xf, segs[node:], t0=t_end, mass0=tr.mass0 - model.mass_flow * burned,
                              backward=True, rtol=1e-10, atol=1e-12)
        nodes.append({"mean": 0.5 * (fwd.state + bwd.state), "forward": fwd.state, "backward": bwd.state}[how])
    return np.array(nodes)


# ------------------------------------------------------------------------------------------ BMPIG

def _manifold_cut(orbit: PeriodicOrbit, tau: float, d: float, sign: int, stable: bool,
                  x_cut: float) -> tuple[FloatArray, FloatArray, float] | None:
    """(manifold start state, crossing state on x = x_cut, |time of flight|) or None (impact, no crossing)."""
    from .manifolds import propagate_to_cut
    xs = manifold_states(orbit, [tau % orbit.period], stable=stable, sign=sign, deviation=d, velocity_only=True)[0]
    c = propagate_to_cut(orbit.model, xs, x_cut, backward=stable, t_max=20.0)
    if not c.reached_cut or c.impact is not None:
        return None
    return xs, c.state, abs(c.time)


def bmpig(model: Model, departure: PeriodicOrbit, arrival: PeriodicOrbit, *, deviation: float = 0.05,
          phases: int = 48, t0: float = 0.0) -> Guess:
    """Bilateral manifold patching (sec. III.C.2, eqs. 36-43) between an L1 and an L2 orbit through the
    secondary's realm S: the unstable manifold of `departure` (branch into S) forward and the stable manifold
    of `arrival` (branch into S) backward to the cut x = 1 - mu; the patch matches their positions on the cut
    (eq. 37's constraint) and minimises the total impulsive delta-v d_1 + |dv_cut| + d_2 (ours: eq. 37
    minimises d_1^2 + d_2^2 + |Delta C_J|; the cut impulse is what a burn pays). A `phases` x `phases` grid of
    the two orbits' phases at d_1 = d_2 = `deviation` [VU] picks the pair whose crossings are closest in
    position, SLSQP then closes the position gap over (tau_1, tau_2, d_1, d_2), d in [deviation / 3, 3
    deviation]. Conversion, eqs. (40)-(43): three burns along the impulses, T_k = |dv_k| / a_th, the
    departure advanced by T_1 / 2, the arrival delayed by T_3 / 2, each coast shortened by its own burn's half
    and a share of T_cut proportional to its length (eq. 42). Kernel layout: burn-coast-burn-coast-burn, the
    free node at the start of the cut burn (the forward prediction along the unstable manifold), arcs meeting
    at the node (forward) and at the end of the cut burn."""
    from scipy.optimize import minimize as _minimize
    x_cut = 1.0 - model.mu
    sign_dep = -1 if departure.point == "L1" else 1     # manifolds.REALM_OF_SIGN: the branch into S
    sign_arr = 1 if arrival.point == "L2" else -1
    taus1 = np.linspace(0.0, departure.period, phases, endpoint=False)
    taus2 = np.linspace(0.0, arrival.period, phases, endpoint=False)
    c1 = [_manifold_cut(departure, float(t), deviation, sign_dep, False, x_cut) for t in taus1]
    c2 = [_manifold_cut(arrival, float(t), deviation, sign_arr, True, x_cut) for t in taus2]
    best: tuple[float, int, int] | None = None
    for i, a in enumerate(c1):
        for j, b in enumerate(c2):
            if a is None or b is None:
                continue
            gap = float(np.linalg.norm(a[1][0:3] - b[1][0:3]))
            if best is None or gap < best[0]:
                best = (gap, i, j)
    if best is None:
        raise CorrectionError(f"no pair of manifold trajectories of the {departure.point} {departure.family} and the {arrival.point} {arrival.family} reaches the cut x = 1 - mu without impact (d = {deviation:.4g} VU)")

    Cut = tuple[FloatArray, FloatArray, float]

    def crossing(v: FloatArray) -> tuple[Cut, Cut] | None:
        a = _manifold_cut(departure, float(v[0]), math.exp(v[2]), sign_dep, False, x_cut)
        b = _manifold_cut(arrival, float(v[1]), math.exp(v[3]), sign_arr, True, x_cut)
        return None if a is None or b is None else (a, b)

    def cost(v: FloatArray) -> float:
        cb = crossing(v)
        if cb is None:
            return 1e3
        return float(math.exp(v[2]) + math.exp(v[3]) + np.linalg.norm(cb[1][1][3:6] - cb[0][1][3:6]))

    def gap(v: FloatArray) -> FloatArray:
        cb = crossing(v)
        return np.ones(3) if cb is None else cb[1][1][0:3] - cb[0][1][0:3]
    ld = math.log(deviation)
    v0 = np.array([taus1[best[1]], taus2[best[2]], ld, ld])
    res = _minimize(cost, v0, method="SLSQP", constraints=[{"type": "eq", "fun": lambda v: gap(v)[1:3]}],
                    bounds=[(None, None), (None, None)] + [(ld - math.log(3.0), ld + math.log(3.0))] * 2,
                    options={"maxiter": 60, "ftol": 1e-10})
    v = res.x if crossing(res.x) is not None and float(np.linalg.norm(gap(res.x))) < 1e-6 else v0
    cb = crossing(v)
    assert cb is not None
    (xs1, xc1, toc1), (xs2, xc2, toc2) = cb
    d1, d2 = math.exp(v[2]), math.exp(v[3])
    dep_phase, arr_phase = OrbitPhase(departure), OrbitPhase(arrival)
    dv1 = xs1[3:6] - dep_phase(v[0])[3:6]
    dv3 = arr_phase(v[1])[3:6] - xs2[3:6]
    dvc = xc2[3:6] - xc1[3:6]
    acc = model.thrust_accel
    t1, tc, t3 = d1 / acc, float(np.linalg.norm(dvc)) / acc, d2 / acc                       # (40)
    share = toc1 / (toc1 + toc2)
    coast1 = toc1 - 0.5 * t1 - tc * share                                                  # (42)
    coast2 = toc2 - 0.5 * t3 - tc * (1.0 - share)
    if coast1 <= 0.0 or coast2 <= 0.0:
        raise CorrectionError(f"the burns outlast a coast ({coast1:.3f}, {coast2:.3f} TU)")
    u1, uc, u3 = dv1 / np.linalg.norm(dv1), dvc / np.linalg.norm(dvc), dv3 / np.linalg.norm(dv3)
    segments = np.array([np.concatenate([u1, u1, [t1]]), [0, 0, 0, 0, 0, 0, coast1], np.concatenate([uc, uc, [tc]]),
                         [0, 0, 0, 0, 0, 0, coast2], np.concatenate([u3, u3, [t3]])])
    layout = Layout(kinds=("burn", "coast", "burn", "coast", "burn"), free_nodes=(2,), meets=(2, 3))
    tr = Transfer(t0=t0, x0=dep_phase(v[0] - 0.5 * t1), xf=arr_phase(v[1] + 0.5 * t3), segments=segments,
                  nodes=np.zeros((1, 6)))                                                    # (43)
    tr.nodes = predicted_node(model, layout, tr, how="forward")
    info = dict(tau=[float(v[0]), float(v[1])], d=[d1, d2], toc=[toc1, toc2], dv_cut=dvc.tolist(),
                position_gap=float(np.linalg.norm(xc2[0:3] - xc1[0:3])), grid_gap=best[0],
                dv_total=float(d1 + d2 + np.linalg.norm(dvc)), burn_times=[t1, tc, t3])
    return Guess(layout=layout, transfer=tr, info=info)
