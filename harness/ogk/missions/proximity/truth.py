"""The proximity approach's truth model, independent of the kernel's Clohessy-Wiltshire model: the target
and the chaser about a point-mass Earth, integrated in inertial (Earth-centred, planar) coordinates by
scipy's DOP853 at tight tolerance: the target's state r_T, v_T and the chaser's relative to it,
rho = r_C - r_T, rho' = v_C - v_T (the exact nonlinear relative equations in the inertial frame,
rho'' = g(r_T + rho) - g(r_T) + a_thrust, g(r) = -mu r / |r|^3: no linearisation, and the small
relative state keeps its own error control), and the chaser's mass.

Thrust as the kernel commands it (ogk_prox_thrust_cmd, the rendezvous family's convention): the unit
vector (cos alpha, sin alpha) in r-t-n of the target's Hill frame, alpha from the radial axis r_hat
towards the along-track axis t_hat (r_hat = r_T / |r_T|, t_hat = h_hat x r_hat), throttle w in [0, 1]
(clipped: an actuator saturates; below the engine's minimum throttle `min_throttle` it is off, which
also keeps the integrator from resolving the plan's arbitrary angles where the plan's throttle is an
interior-point solver's 1e-9 rather than 0). With the run's dispersions: the thrust is T_max (1 + b) w along
alpha + delta (b the run's thrust-level bias, delta the thrust-angle noise held over a replan period),
and the engine burns at its nominal exhaust velocity: m' = -T_max (1 + b) w / v_e.

The measured state the guidance gets is the truth's relative state in the target's Hill frame
(`hill_state`: x radial, y along-track, their rates in the rotating frame; perfect navigation, as the
rendezvous family's), SI."""
from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable, Sequence

import numpy as np
from numpy.typing import NDArray
from scipy.integrate import solve_ivp

FloatArray = NDArray[np.float64]
ControlFn = Callable[[float], tuple[float, float]]

RTOL = 1e-11
#: absolute tolerances of the state (r_T [m], v_T [m/s], rho [m], rho' [m/s], m [kg]): micrometres and
#: nanometres per second where the acceptance is metres and centimetres per second
ATOL = np.array([1e-5, 1e-5, 1e-8, 1e-8, 1e-6, 1e-6, 1e-9, 1e-9, 1e-9])
#: the keep-out is checked on the dense solution at least this often [s] (0.5 m/s at most: 1 m)
KEEPOUT_SAMPLE_S = 2.0


def hill_axes(target: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray]:
    """(r_hat, t_hat, omega) of target states (..., 4): the Hill frame's axes and its rotation rate
    (h / r^2, about the orbit normal)."""
    r = target[..., 0:2]
    v = target[..., 2:4]
    rn = np.linalg.norm(r, axis=-1)
    r_hat = r / rn[..., None]
    h = r[..., 0] * v[..., 1] - r[..., 1] * v[..., 0]
    t_hat = np.stack([-r_hat[..., 1], r_hat[..., 0]], axis=-1) * np.sign(h)[..., None]
    return r_hat, t_hat, np.abs(h) / rn ** 2


def hill_state(state: FloatArray) -> FloatArray:
    """(x, y, v_x, v_y) in the target's Hill frame of truth states (..., 9) (vectorised)."""
    r_hat, t_hat, w = hill_axes(state[..., 0:4])
    rho, rhod = state[..., 4:6], state[..., 6:8]
    x = np.sum(rho * r_hat, axis=-1)
    y = np.sum(rho * t_hat, axis=-1)
    # rates in the rotating frame: d/dt (rho . r_hat) = rho' . r_hat + rho . (w t_hat)
    vx = np.sum(rhod * r_hat, axis=-1) + w * y
    vy = np.sum(rhod * t_hat, axis=-1) - w * x
    return np.stack([x, y, vx, vy], axis=-1)


def from_hill(target: FloatArray, rel: Sequence[float]) -> tuple[FloatArray, FloatArray]:
    """(rho, rho') inertial of a Hill-frame state (x, y, v_x, v_y) about one target state (4,)."""
    r_hat, t_hat, w = hill_axes(np.asarray(target, dtype=np.float64))
    x, y, vx, vy = (float(v) for v in rel)
    rho = x * r_hat + y * t_hat
    rhod = (vx - w * y) * r_hat + (vy + w * x) * t_hat
    return rho, rhod


@dataclasses.dataclass(frozen=True)
class Truth:
    """The truth of one flight (SI): Earth's mu, the engine, the run's thrust-level bias."""

    mu: float
    thrust_max_n: float
    exhaust_velocity_m_s: float
    thrust_bias: float = 0.0        #: b: the thrust is T_max (1 + b) w
    min_throttle: float = 0.0       #: a command below it is engine off

    def initial_state(self, orbit_radius_m: float, rel: Sequence[float], mass_kg: float) -> FloatArray:
        """The target at (a, 0) on its circular orbit (the Hill frame aligned with the inertial one at
        t = 0), the chaser at `rel` (x, y, v_x, v_y) in it."""
        a = orbit_radius_m
        target = np.array([a, 0.0, 0.0, math.sqrt(self.mu / a)])
        rho, rhod = from_hill(target, rel)
        return np.concatenate([target, rho, rhod, [mass_kg]])

    def rhs(self, s: FloatArray, alpha: float, w: float) -> FloatArray:
        """ds/dt (module doc); scalar arithmetic (it is called some 10^4 times a flight)."""
        xt, yt, vxt, vyt, px, py, vpx, vpy, m = (float(v) for v in s)
        rt2 = xt * xt + yt * yt
        rt = math.sqrt(rt2)
        kt = -self.mu / (rt2 * rt)
        xc, yc = xt + px, yt + py
        rc2 = xc * xc + yc * yc
        kc = -self.mu / (rc2 * math.sqrt(rc2))
        w = 0.0 if w < self.min_throttle else min(w, 1.0)
        thrust = self.thrust_max_n * (1.0 + self.thrust_bias) * w
        # the target's Hill axes: r_hat = r_T / |r_T|, t_hat = h_hat x r_hat (h = r_T x v_T > 0: prograde)
        sgn = 1.0 if xt * vyt - yt * vxt >= 0.0 else -1.0
        rx, ry = xt / rt, yt / rt
        tx, ty = -ry * sgn, rx * sgn
        a = thrust / m
        ca, sa = math.cos(alpha), math.sin(alpha)
        return np.array([vxt, vyt, kt * xt, kt * yt, vpx, vpy,
                         kc * xc - kt * xt + a * (ca * rx + sa * tx),
                         kc * yc - kt * yt + a * (ca * ry + sa * ty),
                         -thrust / self.exhaust_velocity_m_s])

    def propagate(self, t0: float, s0: FloatArray, t1: float, control: ControlFn, angle_offset: float,
                  breaks: Sequence[float] = ()) -> tuple[FloatArray, FloatArray]:
        """From (t0, s0) to t1 with control(t) -> (alpha, w) and the angle offset held; the integration
        restarts at `breaks` (the plan's node times: the command's kinks). Returns (times, states) on
        the solver's steps and a dense sampling every KEEPOUT_SAMPLE_S at least (t0 and t1 included)."""
        def f(t: float, s: FloatArray) -> FloatArray:
            alpha, w = control(t)
            return self.rhs(s, alpha + angle_offset, w)

        cuts = [t0] + sorted(b for b in set(breaks) if t0 < b < t1) + [t1]
        times = [np.array([t0])]
        states = [np.asarray(s0, dtype=np.float64)[None, :]]
        s = states[0][0]
        for a, b in zip(cuts[:-1], cuts[1:]):
            sol = solve_ivp(f, (a, b), s, method="DOP853", rtol=RTOL, atol=ATOL, dense_output=True)
            if not sol.success:
                raise RuntimeError(f"truth propagation failed at t = {sol.t[-1]:.6g} s: {sol.message}")
            k = max(1, int(math.ceil((b - a) / KEEPOUT_SAMPLE_S)))
            ts = np.union1d(sol.t, np.linspace(a, b, k + 1))[1:]
            ys = sol.sol(ts).T
            ys[-1] = sol.y[:, -1]
            times.append(ts)
            states.append(ys)
            s = sol.y[:, -1]
        return np.concatenate(times), np.vstack(states)
