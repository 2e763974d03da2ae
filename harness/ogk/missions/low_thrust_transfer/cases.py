"""Kernel MPSP configured on a low-thrust transfer scenario (first: the paper's Apophis mission), and
its perturbation cases.

The configuration comes from the ground side (host/ogk_host/low_thrust_transfer): the scenario's own
fuel-optimal nominal (its ground product, build/tables/<name>-<sha12>/nominal_solution.json,
products.ensure_nominal), its least-squares Fourier fit of lambda_v (eqs. 49-50) and the scenario's
[mpsp] settings. A `Case` is one perturbed problem of Tables 3-6 in the kernel's terms
(initial state, thrust scale, target) together with the ground `Perturbation` describing the same
problem, so that the fuel-optimal solution of that problem can be computed for comparison.
"""
from __future__ import annotations

import dataclasses
import time
from pathlib import Path
from typing import TYPE_CHECKING, Literal

import numpy as np
from numpy.typing import NDArray

from ogk_bindings.mpsp import Mpsp, MpspConfig, MpspResult, paper_basis

if TYPE_CHECKING:  # ground side, imported at run time inside the functions
    from ogk_host.low_thrust_transfer.indirect import Solution
    from ogk_host.low_thrust_transfer.scenario import NormalisedProblem, Perturbation, Scenario

F64 = NDArray[np.float64]
CaseKind = Literal["initial", "terminal", "thrust"]
KINDS: tuple[CaseKind, ...] = ("initial", "terminal", "thrust")
TABLE_OF_KIND: dict[CaseKind, str] = {"initial": "table3", "terminal": "table5", "thrust": "table6"}


@dataclasses.dataclass(frozen=True)
class MpspSetup:
    """The kernel's guidance context on the nominal mission, and what it was built from."""

    scenario: "Scenario"
    nominal: "Solution"          #: ground fuel-optimal nominal (stored, re-propagated)
    problem: "NormalisedProblem"  #: nominal boundary value problem
    guidance: Mpsp
    basis: str
    order: int
    nominal_path: Path | None = None   #: the scenario's own nominal (products.ensure_nominal)
    nominal_sha256: str = ""           #: its SHA-256 (the envelope's products)

    @property
    def product_dir(self) -> Path:
        """build/tables/<name>-<sha12> of the scenario (or the directory given to build_setup)."""
        if self.nominal_path is not None:
            return self.nominal_path.parent
        from ogk_host.low_thrust_transfer.products import product_dir
        return product_dir(self.scenario.path)

    @property
    def lu_km(self) -> float:
        return float(self.scenario.units.length_km)

    @property
    def vu_km_s(self) -> float:
        return float(self.scenario.units.velocity_km_s)

    @property
    def mu_kg(self) -> float:
        return float(self.scenario.units.mass_kg)


def default_scenario_path() -> Path:
    from ogk_host.low_thrust_transfer.scenario import DEFAULT_SCENARIO_PATH
    return Path(DEFAULT_SCENARIO_PATH)


def build_setup(basis: str | None = None, order: int | None = None,
                scenario_path: str | Path | None = None, max_outer: int = 60,
                product_dir: str | Path | None = None) -> MpspSetup:
    """Kernel MPSP on the scenario's own fuel-optimal nominal with its section 4.1 settings.

    The nominal is the scenario's ground product (ogk_host.low_thrust_transfer.products:
    build/tables/<name>-<sha12>/nominal_solution.json, or `product_dir`), made when missing (from
    the shipped cache when the physics is the same, else solved) and refused when it was made from
    another scenario (TableError, one line). basis/order default to the scenario's `[mpsp]
    fourier_basis` / `fourier_order`."""
    from ogk_host.low_thrust_transfer import fourier
    from ogk_host.low_thrust_transfer.products import ensure_nominal
    from ogk_host.low_thrust_transfer.scenario import load_scenario, normalised_problem
    from ogk_host.scenario_file import file_sha256

    from ogk.sil.progress import Working
    sc = load_scenario(scenario_path if scenario_path is not None else default_scenario_path())
    basis = sc.mpsp.fourier_basis if basis is None else basis
    order = sc.mpsp.fourier_order if order is None else int(order)
    sol, nominal_path = ensure_nominal(sc, product_dir, working=Working)   # progress on a terminal
    prob = normalised_problem(sc, None)
    tf = prob.final_time
    t, lam_v = fourier.nominal_control_on_grid(sc, sol)
    eps = fourier.least_squares_weights(fourier.eta_of_time(t, 0.0, tf, basis), lam_v, order,
                                        basis)
    kind, period, t_ref = paper_basis(basis, 0.0, tf)
    lu_km = sc.units.length_km
    vu_km_s = sc.units.velocity_km_s
    m = sc.mpsp
    g = Mpsp(MpspConfig(mu=prob.mu, t_max=prob.max_thrust, c_exhaust=prob.exhaust_velocity,
                        t0=0.0, tf=tf, x0_nom=prob.x0, r_f=prob.rf, v_f=prob.vf,
                        fourier_order=order, fourier_period=period, fourier_t_ref=t_ref,
                        fourier_kind=kind, weights_nom=eps, lambda_m0_nom=float(sol.lam0[6]),
                        h_max=m.h_max_over_tf * tf, tol_r=m.tol_position_km / lu_km,
                        tol_v=m.tol_velocity_km_s / vu_km_s, tol_lambda_m=m.tol_lambda_mf,
                        delta_max=m.delta_max, delta_tau_0=m.delta_tau_initial,
                        delta_tau_min=m.delta_tau_min, n_seg_tol=m.n_seg_tol_initial,
                        n_seg_tol_step=m.n_seg_tol_increment, r_lambda=m.r_lambda,
                        max_newton=100, max_outer=max_outer))
    return MpspSetup(sc, sol, prob, g, basis, order, nominal_path, file_sha256(nominal_path))


@dataclasses.dataclass(frozen=True)
class Case:
    """One perturbed problem: kernel inputs + the ground perturbation of the same problem."""

    kind: CaseKind
    key: str                     #: file-name-safe identifier (reference cache)
    label: str                   #: as in the paper's tables
    param: float | tuple[float, float, float]  #: kappa, delta r_f [LU] or eta [%]
    perturbation: "Perturbation"
    x0: F64                      #: [r0, v0, m0] (7) flown by the kernel
    thrust_scale: float          #: 1 + eta
    target: F64 | None           #: [r_f, v_f] (6) or None (nominal target)


def initial_case(setup: MpspSetup, kappa: float) -> Case:
    """Table 3: r0 + kappa dr0, v0 + kappa dv0 (the scenario's 0.1-scaled vectors)."""
    from ogk_host.low_thrust_transfer.scenario import initial_state_case
    p = initial_state_case(setup.scenario, float(kappa))
    x0 = setup.problem.x0.copy()
    x0[:3] += p.delta_r0
    x0[3:6] += p.delta_v0
    return Case("initial", f"initial_kappa{kappa:+g}", f"T3 kappa={kappa:g}", float(kappa), p, x0,
                1.0, None)


def terminal_case(setup: MpspSetup, delta_rf: tuple[float, float, float] | F64,
                  label: str | None = None) -> Case:
    """Table 4/5: r_f + delta r_f [LU]."""
    from ogk_host.low_thrust_transfer.scenario import Perturbation
    d = np.asarray(delta_rf, dtype=np.float64).reshape(-1)
    if d.size != 3 or not np.all(np.isfinite(d)):
        raise ValueError(f"delta r_f must be 3 finite numbers (LU), got {delta_rf!r}")
    vec = (float(d[0]), float(d[1]), float(d[2]))
    name = "drf=" + ",".join(f"{v:+g}" for v in vec)
    p = Perturbation(delta_rf=d.copy(), label=name)
    target = np.concatenate((setup.problem.rf + d, setup.problem.vf))
    return Case("terminal", "terminal_" + "_".join(f"{v:+g}" for v in vec), label or f"T5 {name}",
                vec, p, setup.problem.x0.copy(), 1.0, target)


def thrust_case(setup: MpspSetup, eta_percent: float) -> Case:
    """Table 6: T_max (1 + eta) over the whole flight."""
    from ogk_host.low_thrust_transfer.scenario import thrust_case as ground_thrust_case
    p = ground_thrust_case(setup.scenario, float(eta_percent))
    return Case("thrust", f"thrust_eta{eta_percent:+g}", f"T6 eta={eta_percent:g}%",
                float(eta_percent), p, setup.problem.x0.copy(), 1.0 + p.thrust_fraction, None)


def _param_number(text: str, what: str) -> float:
    from ogk_bindings.errors import OgkInputError
    try:
        x = float(text)
    except (TypeError, ValueError):
        raise OgkInputError(f"{what} must be a number, got {text!r}", key="--param") from None
    if not np.isfinite(x):
        raise OgkInputError(f"{what} must be finite, got {text!r}", key="--param")
    return x


def check_param(kind: CaseKind, param: str) -> float | tuple[float, float, float]:
    """--param of --case `kind`, checked (OgkInputError `--param: REASON`): kappa and eta finite
    numbers, eta > -100 (the thrust stays > 0); the terminal offset 3 finite numbers in LU."""
    from ogk_bindings.errors import OgkInputError
    if kind == "initial":
        return _param_number(param, "kappa")
    if kind == "terminal":
        parts = [s for s in str(param).replace(" ", "").split(",") if s]
        if len(parts) != 3:
            raise OgkInputError(f"for --case terminal is 'dx,dy,dz' in LU, got {param!r}", key="--param")
        x, y, z = (_param_number(p, "each of dx,dy,dz") for p in parts)
        return (x, y, z)
    if kind == "thrust":
        eta = _param_number(param, "eta [%]")
        if not eta > -100.0:
            raise OgkInputError(f"eta must be > -100 % (T_max (1 + eta/100) > 0), got {param}",
                                key="--param")
        return eta
    raise OgkInputError(f"unknown case kind {kind!r}; known: {', '.join(KINDS)}", key="--case")


def make_case(setup: MpspSetup, kind: CaseKind, param: str) -> Case:
    """A case from the command line's --case/--param (P: kappa, 'dx,dy,dz' in LU, eta in %)."""
    value = check_param(kind, param)
    if kind == "initial":
        return initial_case(setup, float(value))  # type: ignore[arg-type]
    if kind == "terminal":
        return terminal_case(setup, value)        # type: ignore[arg-type]
    return thrust_case(setup, float(value))       # type: ignore[arg-type]


def paper_cases(setup: MpspSetup) -> list[Case]:
    """The cases of the scenario's [dispersions] as listed: for the paper's scenario the 23 cases of
    Tables 3, 5 (vertices of Table 4) and 6, in the tables' order."""
    pert = setup.scenario.dispersions
    cases = [initial_case(setup, k) for k in pert.kappa]
    cases += [terminal_case(setup, v, f"T5 case {i + 1}")
              for i, v in enumerate(pert.delta_rf_vertices)]
    cases += [thrust_case(setup, e) for e in pert.eta_percent]
    return cases


def fly_run(setup: MpspSetup, case: Case) -> tuple[MpspResult, float]:
    """The kernel's solve on one case and its CPU time (time.process_time around the solve only)."""
    start = time.process_time()
    res = setup.guidance.solve(case.x0, case.thrust_scale, case.target)
    return res, time.process_time() - start


def fuel_increase_percent(mpsp_final_mass_kg: float, optimal_final_mass_kg: float,
                          initial_mass_kg: float) -> float:
    """FI of Tables 3, 5, 6: extra propellant of the MPSP solution w.r.t. the fuel-optimal one [%]."""
    optimal_fuel = initial_mass_kg - optimal_final_mass_kg
    return 100.0 * ((initial_mass_kg - mpsp_final_mass_kg) - optimal_fuel) / optimal_fuel
