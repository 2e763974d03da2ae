"""Libration points and the periodic orbits about them in the gravity-only model (Xiong & Wang, sec. III.C.2,
eqs. 32-33), with the degree-2 terms of both bodies when the model has them.

* `collinear_points`: L1, L2, L3 as roots of dOmega/dx = 0 on the x axis (Omega = (x^2 + y^2)/2 + U).
* `linear_modes`: the linearisation at a collinear point (saddle rate, in-plane and vertical frequencies).
* Planar Lyapunov and halo orbits by differential correction of a symmetric x-z plane crossing: the state
  (x0, 0, z0, 0, vy0, 0) at t = 0 and the conditions y = vx = vz = 0 at the next crossing, t = T/2 (the
  model is symmetric under y -> -y, t -> -t, and under z -> -z). Newton on (x0, z0, vy0, T/2) with the
  half-period STM (eqs. 32-33).
* Continuation: natural-parameter in the amplitude from the linear approximation (Lyapunov, `lyapunov_orbit`),
  pseudo-arclength along a family (`continue_family`), halos started at the bifurcation from the Lyapunov
  family (where the vertical pair of Floquet multipliers passes +1) on the pseudo-arclength tangent z0.
* The monodromy M = Phi(T) (eq. 32), its eigenvalues and the unstable/stable eigenvectors (eq. 34).

Amplitudes (scenario [orbits]): a Lyapunov orbit's Ax = half the distance between its two x-axis crossings;
a halo's Az = the larger |z| of its two x-z plane crossings (z is stationary there); branch "north" when z
is positive at that crossing, "south" when negative (the JPL catalogue's convention). The stored initial
state is always the crossing on the primary's side (the smaller x).
"""
from __future__ import annotations

import dataclasses
import math
from typing import Callable

import numpy as np
from numpy.typing import ArrayLike
from scipy.integrate import solve_ivp
from scipy.optimize import brentq, minimize_scalar

from .dynamics import FloatArray, GravityField, Model, gravity, gravity_gradient, jacobi
from .scenario import BinaryScenario, OrbitSpec

#: Tolerances of the reference propagations (the brief of docs/design/blt.md: DOP853, rtol 1e-12, atol 1e-13).
RTOL, ATOL = 1e-12, 1e-13
#: Looser tolerances for the intermediate members of a continuation (the final member is re-corrected
#: at RTOL/ATOL).
RTOL_CONT, ATOL_CONT = 1e-10, 1e-12
#: Newton stops when the crossing residual (y, vx, vz) is below this [LU, VU].
CORRECTION_TOL = 1e-11
POINTS = ("L1", "L2", "L3")
#: The symmetry y -> -y, t -> -t of the model (for the monodromy from the half-period STM).
_SIGMA = np.diag([1.0, -1.0, 1.0, -1.0, 1.0, -1.0])


class CorrectionError(RuntimeError):
    """Differential correction or continuation did not converge."""


# ---------------------------------------------------------------------------------------- libration points

def _dx_omega(model: Model, x: float) -> float:
    return x + float(gravity(model, np.array([x, 0.0, 0.0]))[0])


def collinear_points(model: Model) -> dict[str, float]:
    """x of L1 (between the bodies), L2 (beyond the secondary) and L3 (beyond the primary) [LU]: the roots
    of x + dU/dx (x, 0, 0) = 0, degree-2 terms included. Brackets stay outside each body's impact radius
    (inside the Brillouin sphere the degree-2 field is not the body's and may have spurious roots)."""
    x1, x2 = -model.mu, 1.0 - model.mu
    e1 = max(model.body_radius[0], 1e-9)
    e2 = max(model.body_radius[1], 1e-9)
    f = lambda x: _dx_omega(model, x)  # noqa: E731
    out = {"L1": brentq(f, x1 + e1, x2 - e2, xtol=1e-15, rtol=1e-15, maxiter=200),
           "L2": brentq(f, x2 + e2, x2 + 2.0, xtol=1e-15, rtol=1e-15, maxiter=200),
           "L3": brentq(f, x1 - 2.0, x1 - e1, xtol=1e-15, rtol=1e-15, maxiter=200)}
    return out


def libration_point(model: Model, point: str) -> FloatArray:
    """The position (3,) of L1, L2 or L3 [LU]."""
    if point not in POINTS:
        raise ValueError(f"point must be one of {POINTS}, got {point!r}")
    return np.array([collinear_points(model)[point], 0.0, 0.0])


@dataclasses.dataclass(frozen=True)
class LinearModes:
    """The linearised motion at a collinear point: Omega_xx > 0, Omega_yy < 0, Omega_zz < 0 there."""

    x: float                #: the point [LU]
    omega_xx: float
    omega_yy: float
    omega_zz: float
    saddle_rate: float      #: lambda of the real pair +-lambda [1/TU]
    planar_frequency: float     #: omega_p of the in-plane centre [rad/TU]
    vertical_frequency: float   #: omega_z = sqrt(-Omega_zz) [rad/TU]

    @property
    def planar_period(self) -> float:
        """2 pi / omega_p: the period of the infinitesimal Lyapunov orbit [TU]."""
        return 2.0 * math.pi / self.planar_frequency

    @property
    def vy_per_ax(self) -> float:
        """vy / (x - x_L) of the linear Lyapunov orbit at its x-axis crossings: x = x_L + A cos(omega_p t),
        y = -(omega_p^2 + Omega_xx) A / (2 omega_p) sin(omega_p t)."""
        return -(self.planar_frequency ** 2 + self.omega_xx) / 2.0


def linear_modes(model: Model, point: str) -> LinearModes:
    """Eigen-structure of the linearisation at L1/L2/L3 (the characteristic equation
    s^4 + (4 - Oxx - Oyy) s^2 + Oxx Oyy = 0 of the planar block, and z'' = Ozz z)."""
    xl = libration_point(model, point)
    h = gravity_gradient(model, xl)
    oxx, oyy, ozz = h[0, 0] + 1.0, h[1, 1] + 1.0, h[2, 2]
    b = 4.0 - oxx - oyy
    disc = math.sqrt(b * b - 4.0 * oxx * oyy)
    s2_plus, s2_minus = (-b + disc) / 2.0, (-b - disc) / 2.0
    return LinearModes(x=float(xl[0]), omega_xx=oxx, omega_yy=oyy, omega_zz=ozz,
                       saddle_rate=math.sqrt(s2_plus), planar_frequency=math.sqrt(-s2_minus),
                       vertical_frequency=math.sqrt(-ozz))


# ---------------------------------------------------------------------------------------- propagation

def _field(model: Model | GravityField) -> GravityField:
    return model if isinstance(model, GravityField) else GravityField(model)


def propagate(model: Model | GravityField, state: ArrayLike, duration: float, *, stm: bool = False,
              rtol: float = RTOL, atol: float = ATOL, dense_output: bool = False,
              events: list[Callable[..., float]] | None = None):
    """solve_ivp DOP853 of the gravity-only model over [0, duration] (negative: backward), with the STM
    (y = (x, Phi row-major)) when `stm`. Returns scipy's OdeResult."""
    f = _field(model)
    x0 = np.asarray(state, dtype=float)
    if stm:
        y0 = np.concatenate([x0, np.eye(6).ravel()])
        rhs = f.variational
    else:
        y0 = x0.copy()
        rhs = f.derivative
    sol = solve_ivp(rhs, (0.0, float(duration)), y0, method="DOP853", rtol=rtol, atol=atol,
                    dense_output=dense_output, events=events)
    if sol.status < 0:
        raise CorrectionError(_failure_reason(f.model, sol.t[-1], sol.y[0:3, -1], str(sol.message)))
    return sol


BODY_NAMES = ("primary", "secondary")


def _failure_reason(model: Model, t: float, position: FloatArray, message: str) -> str:
    """One line for a failed propagation: a fall into a body (the usual cause: the degree-2 field is
    singular at the centre) names the body and the distance; otherwise scipy's message."""
    dist = np.linalg.norm(model.body_positions - np.asarray(position, dtype=float)[None, :], axis=1)
    k = int(np.argmin(dist / np.maximum(np.asarray(model.body_radius), 1e-300)))
    if dist[k] <= max(model.body_radius[k], 1e-12):
        return (f"the trajectory falls into the {BODY_NAMES[k]} ({dist[k]:.4g} LU from its centre at "
                f"t = {t:.4g} TU, impact radius {model.body_radius[k]:.4g} LU)")
    return f"propagation failed at t = {t:.4g} TU: {message}"


def flow(model: Model | GravityField, state: ArrayLike, duration: float, *, rtol: float = RTOL,
         atol: float = ATOL) -> FloatArray:
    """The state after `duration` [TU] (gravity-only model)."""
    return propagate(model, state, duration, rtol=rtol, atol=atol).y[:, -1].copy()


def flow_stm(model: Model | GravityField, state: ArrayLike, duration: float, *, rtol: float = RTOL,
             atol: float = ATOL) -> tuple[FloatArray, FloatArray]:
    """(state, Phi) after `duration` [TU]."""
    y = propagate(model, state, duration, stm=True, rtol=rtol, atol=atol).y[:, -1]
    return y[0:6].copy(), y[6:42].reshape(6, 6).copy()


# ---------------------------------------------------------------------------------------- Floquet analysis

@dataclasses.dataclass(frozen=True)
class Floquet:
    """Eigen-structure of a monodromy matrix (eq. 32): the real pair lambda_u > 1 > lambda_s = 1/lambda_u
    with their eigenvectors w_u, w_s (eq. 34), the trivial pair at 1, and the remaining pair."""

    eigenvalues: FloatArray         #: all six, complex, sorted by decreasing modulus
    unstable_value: float           #: lambda_u
    stable_value: float             #: lambda_s
    unstable_vector: FloatArray     #: w_u (6,), unit 6-norm, oriented x <= 0 (towards the primary)
    stable_vector: FloatArray       #: w_s (6,), idem
    unit_values: FloatArray         #: the two eigenvalues nearest 1 (complex)
    other_values: FloatArray        #: the remaining pair (complex): the centre (or a second saddle)

    @property
    def stability_index(self) -> float:
        """nu = (lambda_u + 1 / lambda_u) / 2 (> 1: unstable)."""
        return 0.5 * (self.unstable_value + 1.0 / self.unstable_value)


def _oriented(vec: FloatArray) -> FloatArray:
    v = np.real_if_close(vec, tol=1e6).real.astype(float)
    v = v / np.linalg.norm(v)
    pivot = v[0] if abs(v[0]) > 1e-12 else v[np.argmax(np.abs(v))]
    return -v if pivot > 0.0 else v


def floquet(monodromy: ArrayLike) -> Floquet:
    """Eigenvalues and the unstable/stable eigenvectors of a monodromy matrix. The "+" deviation of eq. (34)
    along an eigenvector oriented here moves towards -x: for an L1 orbit into the primary's realm P (the
    paper's example, sec. III.C.2), for L2 into the secondary's realm S."""
    m = np.asarray(monodromy, dtype=float)
    vals, vecs = np.linalg.eig(m)
    order = np.argsort(-np.abs(vals))
    vals, vecs = vals[order], vecs[:, order]
    iu, is_ = 0, 5
    if abs(vals[iu].imag) > 1e-6 * abs(vals[iu]) or abs(vals[is_].imag) > 1e-6:
        raise CorrectionError(f"no real saddle pair in the monodromy: {vals}")
    rest = [i for i in range(6) if i not in (iu, is_)]
    unit = sorted(rest, key=lambda i: abs(vals[i] - 1.0))[:2]
    other = [i for i in rest if i not in unit]
    return Floquet(eigenvalues=vals, unstable_value=float(vals[iu].real), stable_value=float(vals[is_].real),
                   unstable_vector=_oriented(vecs[:, iu]), stable_vector=_oriented(vecs[:, is_]),
                   unit_values=vals[unit], other_values=vals[other])


# ---------------------------------------------------------------------------------------- periodic orbits

@dataclasses.dataclass(frozen=True)
class PeriodicOrbit:
    """A symmetric periodic orbit of the gravity-only model."""

    family: str                 #: "lyapunov" | "halo"
    point: str                  #: "L1" | "L2" | "L3"
    branch: str | None          #: halo: "north" | "south"
    state0: FloatArray          #: (x0, 0, z0, 0, vy0, 0) at the crossing on the primary's side
    period: float               #: T [TU]
    amplitude: float            #: Ax (Lyapunov) or Az (halo) [LU]
    jacobi: float               #: C (eq. 5)
    monodromy: FloatArray       #: Phi(T) (eq. 32), integrated over the whole period at RTOL/ATOL
    floquet: Floquet
    model: Model

    def states(self, n: int, *, include_end: bool = False) -> tuple[FloatArray, FloatArray]:
        """(times (n,), states (n, 6)) at n equally spaced phases of one period."""
        times = np.linspace(0.0, self.period, n, endpoint=include_end)
        sol = propagate(self.model, self.state0, self.period, dense_output=True)
        return times, sol.sol(times).T.copy()

    def min_distances(self, n: int = 2000) -> tuple[float, float]:
        """Smallest distance to each body's centre over one period [LU] (sampled at n phases, then refined
        by a local minimisation of the dense output)."""
        sol = propagate(self.model, self.state0, self.period, dense_output=True)
        t = np.linspace(0.0, self.period, n)
        pos = sol.sol(t)[0:3].T
        out = []
        for centre in self.model.body_positions:
            d = np.linalg.norm(pos - centre, axis=1)
            k = int(np.argmin(d))
            lo, hi = t[max(k - 1, 0)], t[min(k + 1, n - 1)]
            res = minimize_scalar(lambda s: float(np.linalg.norm(sol.sol(s)[0:3] - centre)), bounds=(lo, hi),
                                  method="bounded", options={"xatol": 1e-12})
            out.append(min(float(res.fun), float(d[k])))
        return out[0], out[1]


def _crossing(field: GravityField, x0: float, z0: float, vy0: float, half: float,
              rtol: float, atol: float) -> tuple[FloatArray, FloatArray, FloatArray]:
    """State, STM and xdot at t = half from (x0, 0, z0, 0, vy0, 0)."""
    s, phi = flow_stm(field, np.array([x0, 0.0, z0, 0.0, vy0, 0.0]), half, rtol=rtol, atol=atol)
    return s, phi, field.derivative(0.0, s)


def _amplitude(family: str, v: FloatArray, s: FloatArray) -> float:
    """Ax or Az (see the module docstring) from the unknowns and the half-period state."""
    if family == "lyapunov":
        return 0.5 * abs(s[0] - v[0])
    return max(abs(v[1]), abs(s[2]))


def _amplitude_row(family: str, v: FloatArray, s: FloatArray, phi: FloatArray,
                   sdot: FloatArray) -> tuple[float, FloatArray]:
    """(signed amplitude value used by Newton, its gradient in (x0, z0, vy0, half))."""
    cols = [0, 2, 4]
    if family == "lyapunov":
        sign = 1.0 if s[0] >= v[0] else -1.0
        grad = np.array([phi[0, 0] - 1.0, phi[0, 2], phi[0, 4], sdot[0]]) * 0.5 * sign
        return 0.5 * sign * (s[0] - v[0]), grad
    if abs(v[1]) >= abs(s[2]):
        sign = 1.0 if v[1] >= 0.0 else -1.0
        return sign * v[1], np.array([0.0, sign, 0.0, 0.0])
    sign = 1.0 if s[2] >= 0.0 else -1.0
    return sign * s[2], sign * np.array([phi[2, cols[0]], phi[2, cols[1]], phi[2, cols[2]], sdot[2]])


def _newton(field: GravityField, family: str, v0: FloatArray, *, fixed: dict[int, float] | None = None,
            amplitude: float | None = None, arclength: tuple[FloatArray, FloatArray, float] | None = None,
            rtol: float = RTOL, atol: float = ATOL, max_iter: int = 25) -> tuple[FloatArray, FloatArray]:
    """Newton on the unknowns (x0, z0, vy0, T/2) (Lyapunov: z0 = 0 fixed) for y = vx (= vz) = 0 at T/2,
    plus one closing equation: fixed unknowns, an amplitude, or the pseudo-arclength condition
    (v - v_prev) . tangent = ds. Returns (v, half-period state)."""
    planar = family == "lyapunov"
    free = [0, 2, 3] if planar else [0, 1, 2, 3]
    fixed = dict(fixed or {})
    if planar:
        fixed[1] = 0.0
    free = [i for i in free if i not in fixed]
    v = np.array(v0, dtype=float)
    for i, val in fixed.items():
        v[i] = val
    last = math.inf
    for _ in range(max_iter):
        if not v[3] > 0.0:
            raise CorrectionError("the half period became <= 0")
        s, phi, sdot = _crossing(field, v[0], v[1], v[2], v[3], rtol, atol)
        rows = [1, 3] if planar else [1, 3, 5]
        res = [s[r] for r in rows]
        jac = [np.array([phi[r, 0], phi[r, 2], phi[r, 4], sdot[r]]) for r in rows]
        if amplitude is not None:
            val, grad = _amplitude_row(family, v, s, phi, sdot)
            res.append(val - amplitude)
            jac.append(grad)
        if arclength is not None:
            vprev, tangent, ds = arclength
            res.append(float(np.dot(v - vprev, tangent) - ds))
            jac.append(np.array(tangent, dtype=float))
        r = np.array(res)
        j = np.array(jac)[:, free]
        norm = float(np.max(np.abs(r[: len(rows)])))
        extra = float(np.max(np.abs(r[len(rows):]))) if len(r) > len(rows) else 0.0
        if norm < CORRECTION_TOL and extra < 1e-12:
            return v, s
        if j.shape[0] != j.shape[1]:
            raise CorrectionError(f"{j.shape[0]} equations for {j.shape[1]} unknowns")
        step = np.linalg.solve(j, -r)
        # damp a step that would flip the half period or grow the residual wildly
        scale = 1.0
        if v[3] + step[free.index(3)] <= 0.2 * v[3]:
            scale = 0.5 * v[3] / abs(step[free.index(3)])
        v[free] += scale * step
        if norm > 1e3 * last and norm > 1e-3:
            raise CorrectionError(f"differential correction diverges (residual {norm:.3g})")
        last = min(last, norm)
    raise CorrectionError(f"differential correction did not converge in {max_iter} iterations "
                          f"(residual {norm:.3g})")


def _finish(field: GravityField, family: str, point: str, v: FloatArray,
            branch: str | None = None) -> PeriodicOrbit:
    """Re-corrects at RTOL/ATOL and builds the orbit with its full-period monodromy."""
    model = field.model
    state0 = np.array([v[0], 0.0, v[1], 0.0, v[2], 0.0])
    s_half = flow(field, state0, v[3])
    if s_half[0] < state0[0]:
        # start from the crossing on the primary's side: re-corrected there with its x0 held
        v, _ = _newton(field, family, np.array([s_half[0], s_half[2], s_half[4], v[3]]),
                       fixed={0: float(s_half[0])})
        state0 = np.array([v[0], 0.0, v[1], 0.0, v[2], 0.0])
    period = 2.0 * v[3]
    s_end, mono = flow_stm(field, state0, period)
    amp_v = np.array([state0[0], state0[2], state0[4], v[3]])
    s_h = flow(field, state0, v[3])
    amplitude = _amplitude(family, amp_v, s_h)
    if family == "halo":
        z_big = state0[2] if abs(state0[2]) >= abs(s_h[2]) else s_h[2]
        branch = "north" if z_big > 0.0 else "south"
    return PeriodicOrbit(family=family, point=point, branch=branch, state0=state0, period=period,
                         amplitude=amplitude, jacobi=float(jacobi(model, state0)), monodromy=mono,
                         floquet=floquet(mono), model=model)


def correct_orbit(model: Model, family: str, point: str, state0: ArrayLike, period: float, *,
                  fix: str = "x0") -> PeriodicOrbit:
    """Differential correction of a guess (x0, 0, z0, 0, vy0, 0) with period T (a published initial state,
    say) keeping x0 ("x0") or z0 ("z0", halos) fixed; RTOL/ATOL."""
    s = np.asarray(state0, dtype=float)
    v0 = np.array([s[0], s[2], s[4], 0.5 * period])
    idx = {"x0": 0, "z0": 1}[fix]
    field = GravityField(model)
    v, _ = _newton(field, family, v0, fixed={idx: float(v0[idx])})
    return _finish(field, family, point, v)


def _vertical_trace(field: GravityField, v: FloatArray, rtol: float, atol: float) -> float:
    """tr of the out-of-plane 2x2 block (z, vz) of the monodromy of a planar orbit, from the half-period
    STM through the symmetry: M = Sigma Phi(T/2)^-1 Sigma Phi(T/2)."""
    _, phi, _ = _crossing(field, v[0], 0.0, v[2], v[3], rtol, atol)
    m = _SIGMA @ np.linalg.solve(phi, _SIGMA @ phi)
    return float(m[2, 2] + m[5, 5])


def _lyapunov_guess(model: Model, point: str, amplitude: float) -> FloatArray:
    lm = linear_modes(model, point)
    a = -amplitude
    return np.array([lm.x + a, 0.0, lm.vy_per_ax * a, 0.5 * lm.planar_period])


def _lyapunov_path(field: GravityField, point: str, amplitudes: list[float]) -> list[FloatArray]:
    """Natural-parameter continuation in Ax through `amplitudes` (increasing), each member from the
    secant predictor of the two before it (the first from the linear approximation)."""
    out: list[FloatArray] = []
    prev_a: list[float] = []
    for a in amplitudes:
        if len(out) >= 2:
            w = (a - prev_a[-1]) / (prev_a[-1] - prev_a[-2])
            guess = out[-1] + w * (out[-1] - out[-2])
        elif out:
            guess = out[-1] * 1.0
            guess[0] -= a - prev_a[-1]
        else:
            guess = _lyapunov_guess(field.model, point, a)
        v, _ = _newton(field, "lyapunov", guess, amplitude=a, rtol=RTOL_CONT, atol=ATOL_CONT)
        out.append(v)
        prev_a.append(a)
    return out


def _start_amplitude(model: Model, point: str) -> float:
    """A small first amplitude for the continuation: 1e-3 of the distance from the point to the nearer body."""
    xl = collinear_points(model)[point]
    return 1e-3 * min(abs(xl + model.mu), abs(xl - 1.0 + model.mu))


def lyapunov_orbit(model: Model, point: str, amplitude: float, *, steps: int | None = None) -> PeriodicOrbit:
    """The planar Lyapunov orbit about `point` with Ax = `amplitude` [LU]: natural-parameter continuation in
    Ax from the linear approximation (geometric steps from a small amplitude), then a final correction at
    RTOL/ATOL."""
    field = GravityField(model.gravity_only())
    reach = _family_reach(model, point)
    if amplitude >= reach:
        raise CorrectionError(f"the {point} Lyapunov orbit with Ax = {amplitude:.4g} LU would reach an impact "
                              f"sphere (the point is {reach:.4g} LU from the nearer one)")
    a0 = min(_start_amplitude(model, point), amplitude)
    n = steps if steps is not None else max(2, int(math.ceil(math.log(amplitude / a0) / math.log(1.6))) + 1)
    amps = list(np.geomspace(a0, amplitude, n)) if amplitude > a0 else [amplitude]
    path = _lyapunov_path(field, point, amps)
    v, _ = _newton(field, "lyapunov", path[-1], amplitude=amplitude)
    return _finish(field, "lyapunov", point, v)


class NoBifurcation(CorrectionError):
    """The planar Lyapunov family has no halo bifurcation before it reaches a body (the vertical pair of
    multipliers moves away from +1: at the point the vertical frequency exceeds the planar one)."""


#: Geometric growth of the amplitude between members of the bifurcation scan (Moshup's scan is exactly
#: these steps); a member that fails is retried at half the step, BIFURCATION_RETRIES times.
BIFURCATION_RATIO = 1.25
BIFURCATION_RETRIES = 8


def _family_reach(model: Model, point: str) -> float:
    """Distance [LU] from the point to the nearer impact sphere along the x axis: no member of a family
    about the point can be larger than this."""
    xl = collinear_points(model)[point]
    return min(abs(xl + model.mu) - model.body_radius[0], abs(xl - 1.0 + model.mu) - model.body_radius[1])


def _crossings_clear(model: Model, v: FloatArray, s: FloatArray) -> bool:
    """Both x-axis crossings of a planar orbit (x0 and the half-period x) outside both impact spheres."""
    xs = np.array([v[0], s[0]])
    centres = np.array([-model.mu, 1.0 - model.mu])
    return bool(np.all(np.abs(xs[:, None] - centres[None, :]) > np.asarray(model.body_radius)[None, :]))


def _scan_member(field: GravityField, point: str, path: list[FloatArray], amps: list[float],
                 a_next: float) -> tuple[float, FloatArray]:
    """The next Lyapunov member of the bifurcation scan at Ax = a_next (secant predictor), retried at half the
    step on a failed correction or a member that reaches an impact sphere. Returns (amplitude, unknowns)."""
    a = amps[-1]
    reason = ""
    for _ in range(BIFURCATION_RETRIES + 1):
        if len(path) > 1:
            guess = path[-1] + (path[-1] - path[-2]) * (a_next - amps[-1]) / (amps[-1] - amps[-2])
        else:
            guess = _lyapunov_guess(field.model, point, a_next)
        try:
            v, s = _newton(field, "lyapunov", guess, amplitude=a_next, rtol=RTOL_CONT, atol=ATOL_CONT)
            if _crossings_clear(field.model, v, s):
                return a_next, v
            reason = "the member crosses the x axis inside an impact sphere"
        except CorrectionError as exc:
            reason = str(exc)
        a_next = a + 0.5 * (a_next - a)
    raise CorrectionError(f"the {point} Lyapunov family cannot be continued past Ax = {a:.4g} LU: {reason}")


def halo_bifurcation(model: Model, point: str, *,
                     amplitude_max: float | None = None) -> tuple[float, FloatArray]:
    """(Ax, unknowns) of the planar Lyapunov orbit where the halo family branches off: the first amplitude
    at which the out-of-plane pair of Floquet multipliers reaches +1 (trace of the (z, vz) block = 2).

    Scale-aware: the scan starts at 1e-3 of the point's distance to the nearer body, grows by
    BIFURCATION_RATIO, halves a step that fails (retries), and stops at 0.95 of the distance from the point
    to the nearer impact sphere (or at the first member whose crossing enters one). No bifurcation before
    that: `NoBifurcation`, one line naming the point and the frequencies."""
    field = GravityField(model.gravity_only())
    top = amplitude_max if amplitude_max is not None else 0.95 * _family_reach(model, point)
    a = _start_amplitude(model, point)
    amps = [a]
    path = _lyapunov_path(field, point, amps)
    f_prev = _vertical_trace(field, path[-1], RTOL_CONT, ATOL_CONT) - 2.0
    while True:                     # geometric steps until the trace passes 2
        if a >= top:
            raise NoBifurcation(_no_bifurcation(model, point, a, f"below Ax = {top:.4g} LU"))
        try:
            a_next, v = _scan_member(field, point, path, amps, min(BIFURCATION_RATIO * a, top))
        except CorrectionError as exc:
            raise NoBifurcation(_no_bifurcation(model, point, a, str(exc))) from exc
        f = _vertical_trace(field, v, RTOL_CONT, ATOL_CONT) - 2.0
        if f_prev < 0.0 <= f:
            lo, hi, v_lo, v_hi = amps[-1], a_next, path[-1], v
            break
        path.append(v)
        amps.append(a_next)
        f_prev, a = f, a_next

    cache: dict[float, FloatArray] = {lo: v_lo, hi: v_hi}

    def g(amp: float) -> float:
        near = min(cache, key=lambda k: abs(k - amp))
        guess = cache[near].copy()
        vv, _ = _newton(field, "lyapunov", guess, amplitude=amp, rtol=RTOL_CONT, atol=ATOL_CONT)
        cache[amp] = vv
        return _vertical_trace(field, vv, RTOL_CONT, ATOL_CONT) - 2.0

    a_bif = brentq(g, lo, hi, xtol=1e-10 * hi, rtol=1e-12)
    g(a_bif)
    return a_bif, cache[a_bif]


def _no_bifurcation(model: Model, point: str, amplitude: float, reason: str) -> str:
    lm = linear_modes(model.gravity_only(), point)
    rel = "exceeds" if lm.vertical_frequency > lm.planar_frequency else "is below"
    return (f"no halo bifurcation from the {point} Lyapunov family up to Ax = {amplitude:.4g} LU ({reason}); "
            f"at {point} the vertical frequency {lm.vertical_frequency:.6g} {rel} the planar "
            f"{lm.planar_frequency:.6g} rad/TU")


def continue_family(model: Model, family: str, start: ArrayLike, tangent: ArrayLike, step: float, count: int,
                    *, stop: Callable[[FloatArray, FloatArray], bool] | None = None) -> list[FloatArray]:
    """Pseudo-arclength continuation: `count` members after `start` (unknowns (x0, z0, vy0, T/2)), each the
    solution of the crossing conditions plus (v - v_prev) . t = step, predictor v_prev + step t, with t the
    unit null vector of the crossing Jacobian oriented along the previous t. Stops early when
    stop(v, half-period state) is true (that member included)."""
    field = GravityField(model.gravity_only())
    v = np.array(start, dtype=float)
    t = np.array(tangent, dtype=float)
    t /= np.linalg.norm(t)
    out: list[FloatArray] = []
    planar = family == "lyapunov"
    for _ in range(count):
        h = step
        reason = ""
        for _attempt in range(6):
            try:
                v_new, s = _newton(field, family, v + h * t, arclength=(v, t, h), rtol=RTOL_CONT, atol=ATOL_CONT)
                break
            except CorrectionError as exc:
                reason = str(exc)
                h *= 0.5
        else:
            raise CorrectionError(f"pseudo-arclength continuation of the {family} family stalled after "
                                  f"{len(out)} members: {reason}")
        # new tangent: null vector of the crossing Jacobian at v_new
        _, phi, sdot = _crossing(field, v_new[0], v_new[1], v_new[2], v_new[3], RTOL_CONT, ATOL_CONT)
        rows = [1, 3] if planar else [1, 3, 5]
        cols = [0, 2, 3] if planar else [0, 1, 2, 3]
        jac = np.array([[phi[r, 0], phi[r, 2], phi[r, 4], sdot[r]] for r in rows])[:, cols]
        null = np.linalg.svd(jac)[2][-1]
        t_new = np.zeros(4)
        t_new[cols] = null
        if np.dot(t_new, t) < 0.0:
            t_new = -t_new
        v, t = v_new, t_new
        out.append(v.copy())
        if stop is not None and stop(v, s):
            break
    return out


def halo_orbit(model: Model, point: str, amplitude: float, branch: str, *,
               step: float | None = None) -> PeriodicOrbit:
    """The halo orbit about `point` with Az = `amplitude` [LU] on `branch` ("north" | "south"): from the
    bifurcating Lyapunov orbit, pseudo-arclength continuation along the tangent z0 until Az brackets the
    target, then natural-parameter correction in Az at RTOL/ATOL. North and south are mirror images
    (z -> -z is a symmetry of the model)."""
    if branch not in ("north", "south"):
        raise ValueError(f"branch must be 'north' or 'south', got {branch!r}")
    gm = model.gravity_only()
    field = GravityField(gm)
    try:
        _, v_bif = halo_bifurcation(gm, point)
    except NoBifurcation as exc:
        return _halo_by_model_homotopy(gm, point, amplitude, branch, str(exc))
    ds = step if step is not None else amplitude / 8.0
    members = continue_family(gm, "halo", v_bif, [0.0, 1.0, 0.0, 0.0], ds, 400,
                              stop=lambda v, s: _amplitude("halo", v, s) >= amplitude)
    v = members[-1]
    s = flow(field, np.array([v[0], 0.0, v[1], 0.0, v[2], 0.0]), v[3], rtol=RTOL_CONT, atol=ATOL_CONT)
    if _amplitude("halo", v, s) < amplitude:
        raise CorrectionError(f"the {point} halo family did not reach Az = {amplitude:.4g}")
    prev = members[-2] if len(members) > 1 else v_bif
    # bracket [prev, v]: interpolate the guess linearly in the amplitude
    s_prev = flow(field, np.array([prev[0], 0.0, prev[1], 0.0, prev[2], 0.0]), prev[3], rtol=RTOL_CONT,
                  atol=ATOL_CONT)
    a_prev, a_v = _amplitude("halo", prev, s_prev), _amplitude("halo", v, s)
    w = (amplitude - a_prev) / (a_v - a_prev) if a_v > a_prev else 1.0
    guess = prev + w * (v - prev)
    v_fin, _ = _newton(field, "halo", guess, amplitude=amplitude)
    orbit = _finish(field, "halo", point, v_fin)
    if orbit.branch != branch:
        orbit = mirror(orbit)
    return orbit


#: The model homotopy's first step in lambda (the degree-2 coefficients' scale), its smallest step, and the
#: largest growth of the step after a success.
HOMOTOPY_STEP, HOMOTOPY_MIN_STEP, HOMOTOPY_GROWTH = 0.25, 1.0 / 1024.0, 1.5


def scaled_degree2(model: Model, lam: float) -> Model:
    """The model with both bodies' C20 and C22 multiplied by lam (0: point masses)."""
    return dataclasses.replace(model, c20=(lam * model.c20[0], lam * model.c20[1]),
                               c22=(lam * model.c22[0], lam * model.c22[1]))


def _halo_by_model_homotopy(model: Model, point: str, amplitude: float, branch: str,
                            reason: str) -> PeriodicOrbit:
    """A halo orbit of a model whose Lyapunov family has no halo bifurcation (at Didymos' L1, Dimorphos' C20
    lifts the vertical frequency above the planar one): the halo with the same Az and branch of the
    point-mass model, continued in lam (the degree-2 coefficients scaled by lam, 0 -> 1) at fixed Az, each
    step from the secant predictor, halved on a failed correction."""
    if not any(model.c20) and not any(model.c22):
        raise NoBifurcation(reason)
    base = halo_orbit(scaled_degree2(model, 0.0), point, amplitude, branch)
    x0 = base.state0
    path = [np.array([x0[0], x0[2], x0[4], 0.5 * base.period])]
    lams = [0.0]
    h = HOMOTOPY_STEP
    while lams[-1] < 1.0:
        lam = min(1.0, lams[-1] + h)
        guess = path[-1] if len(path) < 2 else \
            path[-1] + (path[-1] - path[-2]) * (lam - lams[-1]) / (lams[-1] - lams[-2])
        try:
            v, _ = _newton(GravityField(scaled_degree2(model, lam)), "halo", guess, amplitude=amplitude,
                           rtol=RTOL_CONT, atol=ATOL_CONT)
        except CorrectionError as exc:
            h *= 0.5
            if h < HOMOTOPY_MIN_STEP:
                raise CorrectionError(f"{reason}; the point-mass {point} halo at Az = {amplitude:.4g} LU does not "
                                      f"continue to the degree-2 model past {lams[-1]:.4g} of its "
                                      f"coefficients: {exc}") from exc
            continue
        path.append(v)
        lams.append(lam)
        h = min(HOMOTOPY_GROWTH * h, 1.0)
    field = GravityField(model)
    v_fin, _ = _newton(field, "halo", path[-1], amplitude=amplitude)
    orbit = _finish(field, "halo", point, v_fin)
    return orbit if orbit.branch == branch else mirror(orbit)


def mirror(orbit: PeriodicOrbit) -> PeriodicOrbit:
    """The z -> -z image of an orbit (north <-> south)."""
    flip = np.diag([1.0, 1.0, -1.0, 1.0, 1.0, -1.0])
    state0 = flip @ orbit.state0
    mono = flip @ orbit.monodromy @ flip
    branch = None if orbit.branch is None else ("south" if orbit.branch == "north" else "north")
    return dataclasses.replace(orbit, state0=state0, monodromy=mono, floquet=floquet(mono), branch=branch)


def _check_clear(orbit: PeriodicOrbit) -> None:
    """CorrectionError when the orbit passes inside a body's impact sphere (its closest approach)."""
    for k, d in enumerate(orbit.min_distances()):
        if d <= orbit.model.body_radius[k]:
            raise CorrectionError(f"the orbit passes {d:.4g} LU from the {BODY_NAMES[k]}'s centre, inside its "
                                  f"impact radius {orbit.model.body_radius[k]:.4g} LU")


def scenario_orbit(scenario: BinaryScenario, name: str, model: Model | None = None) -> PeriodicOrbit:
    """The orbit [orbits.NAME] of the scenario in `model` (default: the scenario's gravity, no SRP/Sun)."""
    from .dynamics import model_from_scenario

    if name not in scenario.orbits:
        raise KeyError(f"no [orbits.{name}] in {scenario.path} (has: {', '.join(scenario.orbits)})")
    spec: OrbitSpec = scenario.orbits[name]
    m = model if model is not None else model_from_scenario(scenario)
    amp = spec.amplitude_m / scenario.units.length_m
    try:
        if spec.family == "lyapunov":
            orbit = lyapunov_orbit(m, spec.point, amp)
        else:
            assert spec.branch is not None
            orbit = halo_orbit(m, spec.point, amp, spec.branch)
        _check_clear(orbit)
        return orbit
    except CorrectionError as exc:
        raise CorrectionError(f"[orbits.{name}] ({spec.family} about {spec.point}, amplitude "
                              f"{spec.amplitude_m:g} m = {amp:.4g} LU, reach {_family_reach(m, spec.point):.4g} "
                              f"LU to the nearer impact sphere): {exc}") from exc


def jacobi_at_point(model: Model, point: str) -> float:
    """C of the libration point at rest: 2 Omega(L) (the ZVC opens the neck at L below it)."""
    return float(jacobi(model, np.concatenate([libration_point(model, point), np.zeros(3)])))


def main(argv: list[str] | None = None) -> int:
    """`python -m ogk_host.binary.orbits [SCENARIO]`: the libration points and the scenario's orbits (the
    table of docs/design/blt-ground.md)."""
    import sys
    import time

    from .dynamics import model_from_scenario
    from .scenario import load_scenario

    args = sys.argv[1:] if argv is None else argv
    sc = load_scenario(args[0] if args else None)
    u = sc.units
    model = model_from_scenario(sc)
    pm = model_from_scenario(sc, gravity="point-mass")
    print(f"units: LU = {u.length_m:.6g} m, TU = {u.time_s:.10g} s, VU = {u.velocity_m_s:.10g} m/s, "
          f"ACC = {u.acceleration_m_s2:.10g} m/s^2, mu = {u.mu:.16g}")
    print(f"G(M1+M2): implied {u.gm_implied_m3_s2:.8g}, Table 1 {u.gm_table_m3_s2:.8g} m^3/s^2, "
          f"mismatch {100.0 * u.gm_mismatch:+.4f} %")
    for name, m in ((sc.gravity.model, model), ("point-mass", pm)):
        pts = collinear_points(m)
        print(f"{name:10s} " + "  ".join(f"{p} x = {x:.14f} LU ({x * u.length_m:.3f} m) C = "
                                         f"{jacobi_at_point(m, p):.10f}" for p, x in pts.items()))
    print("| orbit | point | amplitude [m] | period [h] | Jacobi C | stability index | "
          "min dist. Alpha [m] | min dist. Beta [m] |")
    print("|---|---|---|---|---|---|---|---|")
    for name in sc.orbits:
        t0 = time.time()
        o = scenario_orbit(sc, name, model)
        d1, d2 = o.min_distances()
        branch = f" {o.branch}" if o.branch else ""
        print(f"| {name} | {o.point}{branch} | {o.amplitude * u.length_m:.2f} | "
              f"{o.period * u.time_s / 3600.0:.4f} | {o.jacobi:.8f} | {o.floquet.stability_index:.1f} | "
              f"{d1 * u.length_m:.1f} | {d2 * u.length_m:.1f} |   ({time.time() - t0:.1f} s)")
        print(f"|   state0 = [{', '.join(f'{v:.15g}' for v in o.state0)}], T = {o.period:.15g} TU |")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
