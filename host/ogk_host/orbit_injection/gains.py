"""VTD-NOG gain tables by transition matrices (docs/design/vtd-nog.md; VTD-NOG-NOTES.md secs. 2-3).

Linear TPBVP on [tau_k, 1] in y = [dx (7); dlam (7); dmu (1)] with the parameter change da = dt_f:
  y' = M(tau) y + G(tau) da,  M = [[A, -B, 0], [-C, -A^T, 0], [-E^T, -D^T, 0]],  G = [D; -E; -F].
Integrating backward from tau = 1 (Phi = I, Gamma = 0)
  d/dtau Phi(1, tau) = -Phi(1, tau) M(tau),   d/dtau Gamma(1, tau) = -Phi(1, tau) G(tau)
gives y(1) = Phi(1, tau_k) y(tau_k) + Gamma(1, tau_k) da. With y(tau_k) = [dx_k; dlam_k; 0] the eight
rows R = {r, phi, v_r, v_t, v_n | lambda_xi, lambda_t | mu} of y(1) vanish:
  K_k [dlam_k; da] = -Phi_R,x dx_k,   K_k = [Phi_R,lam  Gamma_R]   (8 x 8)
so the gain matrix is G_k = -K_k^-1 Phi_R,x (8 x 7): rows 0..6 give dlam_k, row 7 gives dt_f.
All in canonical units (units.py); `table_arrays_si` converts to SI for the flight tables.
"""
from __future__ import annotations

import dataclasses

import numpy as np
from numpy.typing import NDArray
from scipy.integrate import solve_ivp

from ogk_bindings.errors import OgkInputError
from . import dynamics as dyn
from .nominal import Nominal
from .propagation import ATOL, N_Z, RTOL, solve_ivp_segmented

FloatArray = NDArray[np.float64]

N_Y = N_Z + 1                     #: [dx; dlam; dmu]
MU = N_Z                          #: index of dmu in y
#: Rows of y(1) that vanish: constrained final states, free-final costates, parameter costate.
ZERO_ROWS = (dyn.R, dyn.PHI, dyn.VR, dyn.VT, dyn.VN, dyn.N_X + dyn.XI, dyn.N_X + dyn.TIME, MU)
N_GAIN_OUT = dyn.N_X + 1          #: (dlam (7), dt_f)


def linear_system(nominal: Nominal, z: FloatArray) -> tuple[FloatArray, FloatArray,
                                                             dyn.NeighboringMatrices]:
    """M (..., 15, 15), G (..., 15) and the A..F matrices at nominal points z (..., 14)."""
    x, lam = z[..., :dyn.N_X], z[..., dyn.N_X:]
    mats = dyn.neighboring_matrices(nominal.model, x, lam, dyn.optimal_control(lam), nominal.t_f)
    lead = z.shape[:-1]
    m_mat = np.zeros(lead + (N_Y, N_Y))
    m_mat[..., :dyn.N_X, :dyn.N_X] = mats.A
    m_mat[..., :dyn.N_X, dyn.N_X:N_Z] = -mats.B
    m_mat[..., dyn.N_X:N_Z, :dyn.N_X] = -mats.C
    m_mat[..., dyn.N_X:N_Z, dyn.N_X:N_Z] = -np.swapaxes(mats.A, -1, -2)
    m_mat[..., MU, :dyn.N_X] = -mats.E
    m_mat[..., MU, dyn.N_X:N_Z] = -mats.D
    g_vec = np.concatenate([mats.D, -mats.E, -mats.F[..., None]], axis=-1)
    return m_mat, g_vec, mats


@dataclasses.dataclass(frozen=True)
class BackwardTransition:
    """Phi(1, tau), Gamma(1, tau) and the nominal z(tau) at the requested tau (ascending)."""

    tau: FloatArray        #: (N,)
    z: FloatArray          #: (N, 14)
    phi: FloatArray        #: (N, 15, 15)
    gamma: FloatArray      #: (N, 15)


def backward_transition(nominal: Nominal, tau: FloatArray) -> BackwardTransition:
    """Integrates [z, Phi(1, .), Gamma(1, .)] backward from tau = 1 (DOP853, rtol 1e-12)."""
    tau = np.unique(np.asarray(tau, dtype=np.float64))
    if tau[0] < 0.0 or tau[-1] > 1.0:
        raise ValueError("tau must lie in [0, 1]")
    z1 = nominal.states(np.array([1.0]))[0]
    t_f = nominal.t_f

    def rhs(_: float, y: FloatArray) -> FloatArray:
        z = y[:N_Z]
        phi = y[N_Z:N_Z + N_Y * N_Y].reshape(N_Y, N_Y)
        m_mat, g_vec, mats = linear_system(nominal, z)
        dz = t_f * np.concatenate([mats.D, -mats.E])   # extremal flow (h_u = 0): g = [f~; -h_x]
        return np.concatenate([dz, (-phi @ m_mat).ravel(), -phi @ g_vec])

    y1 = np.concatenate([z1, np.eye(N_Y).ravel(), np.zeros(N_Y)])
    desc = tau[::-1]
    if desc[0] == 1.0 and desc.size == 1:
        ys = y1[None, :]
    else:
        sol = solve_ivp_segmented(rhs, (1.0, float(desc[-1])), y1, desc,
                                  nominal.model.tau_breaks(t_f, 0.0, 0.0),
                                  method="DOP853", rtol=RTOL, atol=ATOL)
        if not sol.success:
            raise RuntimeError(f"backward transition integration failed: {sol.message}")
        ys = sol.y.T[::-1]
    return BackwardTransition(tau=tau, z=ys[:, :N_Z],
                              phi=ys[:, N_Z:N_Z + N_Y * N_Y].reshape(-1, N_Y, N_Y),
                              gamma=ys[:, N_Z + N_Y * N_Y:])


def equilibrate(mat: FloatArray, sweeps: int = 30) -> tuple[FloatArray, FloatArray]:
    """Ruiz row/column scaling of square matrices (..., n, n) to unit max-norm rows and columns.

    Returns (row_scale, col_scale) such that diag(row) mat diag(col) is equilibrated.
    """
    row = np.ones(mat.shape[:-1])
    col = np.ones(mat.shape[:-2] + mat.shape[-1:])
    work = np.abs(mat)
    for _ in range(sweeps):
        scaled = work * row[..., :, None] * col[..., None, :]
        row = row / np.sqrt(np.max(scaled, axis=-1))
        scaled = work * row[..., :, None] * col[..., None, :]
        col = col / np.sqrt(np.max(scaled, axis=-2))
    return row, col


@dataclasses.dataclass(frozen=True)
class GainTable:
    """VTD-NOG tables over normalised time (canonical units).

    gain[k] maps dx_k = x(t_k) - x*(tau_k) (7, with dt_k = t_k - t_f* tau_k) to [dlam_k; dt_f].
    costate_rate_gain[k] = d(dlam)/dtau at tau_k per unit dx_k (for a first-order hold of dlam
    inside the sampling interval); control_gain[k] = K_lam = -H_uu^-1 F_u^T (du = K_lam dlam on this
    nominal, where H_ux, H_ua vanish).
    """

    t_f: float                       #: t_f* [TU]
    tau: FloatArray                  #: (N,)
    z: FloatArray                    #: (N, 14) nominal [x; lambda]
    u: FloatArray                    #: (N, 2) nominal [alpha, beta]
    gain: FloatArray                 #: (N, 8, 7)
    costate_rate_gain: FloatArray    #: (N, 7, 7)
    control_gain: FloatArray         #: (N, 2, 7)
    control_state_gain: FloatArray   #: (N, 2, 7)  K_x = -H_uu^-1 H_ux (0 on this nominal)
    huu_min_eig: FloatArray          #: (N,) smallest eigenvalue of H_uu (SOSC: > 0)
    cond_raw: FloatArray             #: (N,) 2-norm condition number of K_k
    cond_equilibrated: FloatArray    #: (N,) same after Ruiz equilibration


#: Largest grid spacing relative to the time-to-go (docs/design/vtd-nog.md sec. 7). The costate gains grow
#: like 1/time-to-go^3, so linear interpolation between nodes errs by about 1.6 rho^2 = 0.4 % of
#: their size; every grid built here keeps this spacing bound.
MAX_RELATIVE_SPACING = 0.05
#: Bound checked on the *measured* mid-node interpolation error of the costate gains (max error over
#: the entries / max entry, per node; `interpolation_error`): the 0.4 % of the spacing rule plus
#: margin (the paper's grid measures 0.39 %).
INTERPOLATION_ERROR_BOUND = 0.005


class GridCapacityError(OgkInputError):
    """The gain grid that keeps the interpolation bound does not fit the kernel's table capacity."""


def tau_grid(t_f_s: float, step_s: float, end_time_to_go_s: float,
             relative_spacing: float = MAX_RELATIVE_SPACING) -> FloatArray:
    """Grid over [0, 1): uniform steps of `step_s` from ignition until the time-to-go is
    step_s / relative_spacing, then geometric in the time-to-go (each step `relative_spacing` of
    it) down to `end_time_to_go_s`; so no step exceeds `relative_spacing` of the time-to-go.
    With no room for the uniform part the grid is geometric from ignition. tau = 1 is excluded
    (K_k is singular there)."""
    if not 0.0 < end_time_to_go_s < t_f_s:
        raise ValueError(f"grid end {end_time_to_go_s} s must be in (0, t_f* = {t_f_s} s)")
    switch_togo_s = step_s / relative_spacing
    n_uniform = max(0, int(np.floor((t_f_s - switch_togo_s) / step_s)))
    uniform_s = step_s * np.arange(n_uniform + 1)
    togo_s = t_f_s - uniform_s[-1]
    n_geo = max(0, int(np.ceil(np.log(end_time_to_go_s / togo_s) / np.log(1.0 - relative_spacing))))
    geometric_s = t_f_s - np.geomspace(togo_s, end_time_to_go_s, n_geo + 1)[1:]
    return np.concatenate([uniform_s, geometric_s]) / t_f_s


def uniform_step_candidates(sample_interval_s: float, t_f_s: float,
                            relative_spacing: float = MAX_RELATIVE_SPACING) -> list[float]:
    """Uniform steps tried, finest first: Delta t_S / 4, / 3, / 2, Delta t_S, then 2, 3, ...
    Delta t_S (so the nominal sampling instants stay nodes), ending with the first step whose
    uniform part is empty (a purely geometric grid)."""
    out = [sample_interval_s / m for m in (4, 3, 2, 1)]
    k = 2
    while out[-1] / relative_spacing < t_f_s:
        out.append(k * sample_interval_s)
        k += 1
    return out


def kernel_table_capacity() -> tuple[int, int]:
    """(OGK_NOG_MAX_GRID, OGK_NOG_ENTRY_LEN) read from the kernel through the bindings."""
    try:
        from ogk_bindings._ffi import lib
    except ImportError as exc:
        raise OgkInputError(f"the kernel bindings are needed for the table capacity: {exc}") from None
    return int(lib.OGK_NOG_MAX_GRID), int(lib.OGK_NOG_ENTRY_LEN)


@dataclasses.dataclass(frozen=True)
class GridChoice:
    """The chosen gain grid and why."""

    tau: FloatArray              #: (N,) gain nodes, tau < 1 (the bundle adds tau = 1)
    step_s: float                #: uniform step [s]
    relative_spacing: float
    end_time_to_go_s: float      #: time-to-go of the last gain node [s]
    capacity: int                #: OGK_NOG_MAX_GRID (bundle nodes, tau = 1 included)

    @property
    def bundle_nodes(self) -> int:
        return int(self.tau.size) + 1


def choose_tau_grid(t_f_s: float, sample_interval_s: float, end_time_to_go_s: float,
                    capacity: int | None = None,
                    relative_spacing: float = MAX_RELATIVE_SPACING) -> GridChoice:
    """The finest grid of `uniform_step_candidates` whose bundle (gain nodes + tau = 1) fits
    `capacity` (default: OGK_NOG_MAX_GRID from the kernel). Every candidate keeps the spacing
    bound; the finest uniform step is kept for its sampling-instant nodes. For the paper's data:
    0.5 s steps, 251 gain nodes (252 of 256 in the bundle), the same grid as before.
    Raises GridCapacityError when even the purely geometric grid does not fit."""
    if capacity is None:
        capacity = kernel_table_capacity()[0]
    needed = 0
    for step_s in uniform_step_candidates(sample_interval_s, t_f_s, relative_spacing):
        tau = tau_grid(t_f_s, step_s, end_time_to_go_s, relative_spacing)
        needed = tau.size + 1
        if needed <= capacity:
            return GridChoice(tau=tau, step_s=step_s, relative_spacing=relative_spacing,
                              end_time_to_go_s=end_time_to_go_s, capacity=capacity)
    min_end_s = t_f_s * (1.0 - relative_spacing) ** (capacity - 2)
    raise GridCapacityError(
        f"the gain grid needs {needed} nodes (spacing <= {relative_spacing:.0%} of the time-to-go "
        f"down to {end_time_to_go_s:.3g} s to go, t_f* = {t_f_s:.4g} s) but the kernel holds "
        f"OGK_NOG_MAX_GRID = {capacity}: raise freeze_time_to_go_s (the grid ends there) to at "
        f"least {min_end_s:.3g} s", key="guidance.end_game.freeze_time_to_go_s")


def default_tau_grid(nominal: Nominal, points_per_sample: int = 4,
                     relative_spacing: float = MAX_RELATIVE_SPACING,
                     end_time_to_go_s: float = 0.5) -> FloatArray:
    """`tau_grid` with the uniform step Delta t_S / points_per_sample (no capacity check; the
    flight tables use `choose_tau_grid`). For the paper's data: 251 nodes."""
    return tau_grid(nominal.t_f_s, nominal.problem.scenario.sample_interval_s / points_per_sample,
                    end_time_to_go_s, relative_spacing)


def compute_gain_table(nominal: Nominal, tau: FloatArray | None = None) -> GainTable:
    """Gain table at the given tau (default `default_tau_grid`); every tau must be < 1."""
    tau = default_tau_grid(nominal) if tau is None else np.unique(np.asarray(tau, dtype=np.float64))
    if np.any(tau >= 1.0):
        raise ValueError("the gain solve is singular at tau = 1; use tau < 1")
    trans = backward_transition(nominal, np.append(tau, 1.0))
    keep = trans.tau < 1.0
    phi, gamma = trans.phi[keep], trans.gamma[keep]
    z = nominal.states(tau)     # the forward solution from the exact ignition state (differs from
    #                             the backward-integrated trans.z by ~1e-13 relative)
    rows = list(ZERO_ROWS)
    k_mat = np.concatenate([phi[:, rows, dyn.N_X:N_Z], gamma[:, rows, None]], axis=-1)   # (N, 8, 8)
    rhs = -phi[:, rows, :dyn.N_X]                                                       # (N, 8, 7)
    row_s, col_s = equilibrate(k_mat)
    k_eq = k_mat * row_s[:, :, None] * col_s[:, None, :]
    # solve the equilibrated system: K = R^-1 K_eq C^-1  ->  K^-1 b = C K_eq^-1 R b
    gain = col_s[:, :, None] * np.linalg.solve(k_eq, row_s[:, :, None] * rhs)
    _, _, mats = linear_system(nominal, z)
    g_lam, g_a = gain[:, :dyn.N_X, :], gain[:, dyn.N_X, :]
    costate_rate = (-mats.C - np.swapaxes(mats.A, -1, -2) @ g_lam
                    - mats.E[:, :, None] * g_a[:, None, :])
    return GainTable(
        t_f=nominal.t_f, tau=tau, z=z, u=dyn.optimal_control(z[:, dyn.N_X:]), gain=gain,
        costate_rate_gain=costate_rate, control_gain=mats.K_lam, control_state_gain=mats.K_x,
        huu_min_eig=np.linalg.eigvalsh(mats.H_uu)[:, 0],
        cond_raw=np.linalg.cond(k_mat), cond_equilibrated=np.linalg.cond(k_eq))


def condition_numbers_si(nominal: Nominal, tau: FloatArray) -> FloatArray:
    """cond(K_k) with K_k written in SI units (rows: X for states, TU/X for costates, 1 for mu;
    columns: TU/X for dlam, TU for dt_f) -- for comparison with the canonical raw numbers."""
    units = nominal.problem.units
    x_scale, tu = units.state_scale, units.time_s
    tau = np.unique(np.asarray(tau, dtype=np.float64))
    trans = backward_transition(nominal, np.append(tau, 1.0))
    keep = trans.tau < 1.0
    rows = list(ZERO_ROWS)
    k_mat = np.concatenate([trans.phi[keep][:, rows, dyn.N_X:N_Z],
                            trans.gamma[keep][:, rows, None]], axis=-1)
    row_scale = np.concatenate([x_scale, tu / x_scale, [1.0]])[rows]
    col_scale = np.append(tu / x_scale, tu)
    return np.linalg.cond(k_mat * row_scale[None, :, None] / col_scale[None, None, :])


@dataclasses.dataclass(frozen=True)
class Correction:
    """First-order VTD-NOG correction at a sample (canonical units)."""

    dlam_k: FloatArray     #: (7,)
    dt_f: float            #: [TU]


def _interp_rows(table: GainTable, values: FloatArray, tau_k: float) -> FloatArray:
    """Linear interpolation of table rows in tau (exact at grid points); no extrapolation."""
    if not table.tau[0] <= tau_k <= table.tau[-1]:
        raise ValueError(f"tau = {tau_k} outside the table [{table.tau[0]}, {table.tau[-1]}]")
    idx = int(np.clip(np.searchsorted(table.tau, tau_k, side="right") - 1, 0, table.tau.size - 2))
    w = (tau_k - table.tau[idx]) / (table.tau[idx + 1] - table.tau[idx])
    return (1.0 - w) * values[idx] + w * values[idx + 1]


def predict_correction(table: GainTable, tau_k: float, dx_k: FloatArray) -> Correction:
    """(dlam_k, dt_f) = G(tau_k) dx_k, G linearly interpolated in tau between table points."""
    out = _interp_rows(table, table.gain, tau_k) @ np.asarray(dx_k, dtype=np.float64)
    return Correction(dlam_k=out[:dyn.N_X], dt_f=float(out[dyn.N_X]))


def predict_control_correction(table: GainTable, tau_k: float, dx_k: FloatArray,
                               tau: FloatArray, hold: str = "first-order") -> FloatArray:
    """du(tau) (N, 2) inside [tau_k, tau_k+1] from the table only.

    hold = "zero-order": dlam(tau) = dlam_k; "first-order": dlam(tau) = dlam_k + (tau - tau_k)
    N(tau_k) dx_k with N = costate_rate_gain. du = K_lam(tau) dlam(tau) (eq. 30 with H_ux = H_ua = 0;
    the table's control_state_gain is kept to let a caller verify that K_x = 0).
    """
    dx_k = np.asarray(dx_k, dtype=np.float64)
    corr = predict_correction(table, tau_k, dx_k)
    tau = np.atleast_1d(np.asarray(tau, dtype=np.float64))
    dlam = np.repeat(corr.dlam_k[None, :], tau.size, axis=0)
    if hold == "first-order":
        rate = _interp_rows(table, table.costate_rate_gain, tau_k) @ dx_k
        dlam = dlam + (tau - tau_k)[:, None] * rate[None, :]
    elif hold != "zero-order":
        raise ValueError(f"unknown hold {hold!r}")
    k_lam = np.stack([_interp_rows(table, table.control_gain, t) for t in tau])
    return np.einsum("nij,nj->ni", k_lam, dlam)


def propagate_neighboring(nominal: Nominal, tau_k: float, dx_k: FloatArray, correction: Correction,
                          tau: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Exact linear neighboring extremal from tau_k: (dx, dlam, du) at each tau >= tau_k.

    Integrates y' = M y + G dt_f together with the nominal (reference for the hold errors).
    """
    z_k = nominal.states(np.array([tau_k]))[0]
    t_f, da = nominal.t_f, correction.dt_f

    def rhs(_: float, w: FloatArray) -> FloatArray:
        m_mat, g_vec, mats = linear_system(nominal, w[:N_Z])
        return np.concatenate([t_f * np.concatenate([mats.D, -mats.E]), m_mat @ w[N_Z:] + g_vec * da])

    w0 = np.concatenate([z_k, dx_k, correction.dlam_k, [0.0]])
    tau = np.atleast_1d(np.asarray(tau, dtype=np.float64))
    sol = solve_ivp_segmented(rhs, (tau_k, float(tau.max())), w0, tau,
                              nominal.model.tau_breaks(t_f, 0.0, 0.0),
                              method="DOP853", rtol=RTOL, atol=ATOL)
    w = sol.y.T
    _, _, mats = linear_system(nominal, w[:, :N_Z])
    dx, dlam = w[:, N_Z:N_Z + dyn.N_X], w[:, N_Z + dyn.N_X:N_Z + 2 * dyn.N_X]
    du = (np.einsum("nij,nj->ni", mats.K_lam, dlam) + np.einsum("nij,nj->ni", mats.K_x, dx)
          + mats.K_a * da)
    return dx, dlam, du


def interpolation_error(nominal: Nominal, table: GainTable) -> tuple[float, float]:
    """Measured error of linear interpolation of the gains at the mid-nodes of the table's grid:
    (costate gains, dt_f row), each the max over nodes of max |interpolated - computed| / max
    |computed| at that node (canonical units). One extra gain computation at the mid-nodes."""
    mids = 0.5 * (table.tau[:-1] + table.tau[1:])
    exact = compute_gain_table(nominal, mids).gain
    interp = 0.5 * (table.gain[:-1] + table.gain[1:])
    err = np.abs(interp - exact)
    lam = np.max(err[:, :dyn.N_X, :], axis=(1, 2)) / np.max(np.abs(exact[:, :dyn.N_X, :]), axis=(1, 2))
    dtf = np.max(err[:, dyn.N_X, :], axis=1) / np.max(np.abs(exact[:, dyn.N_X, :]), axis=1)
    return float(np.max(lam)), float(np.max(dtf))
