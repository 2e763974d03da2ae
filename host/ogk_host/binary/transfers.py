"""Transfers of a binary-asteroid scenario as data: [solver], [transfers.NAME] and [monte_carlo] read key by
key (every complaint an OgkInputError naming the key), and the ground pipeline of one transfer: orbits,
initial guess (ogk_host.binary.guess), convergence by the kernel (ogk_host.binary.design), the figures.

    [solver]                       the corrector's settings (SI; defaults: the paper's tolerance and limits)
    [transfers.NAME] kind = "single-burn"      SBIG (eqs. 23-31) from_orbit -> to_orbit, StoS (eq. 65)
    [transfers.NAME] kind = "ump-backward"     UbMPIG (eqs. 53-60) circle -> to_orbit, burn-coast-burn
    [transfers.NAME] kind = "bmp"              BMPIG (eqs. 36-43) from_orbit -> to_orbit via x = 1 - mu, 3 burns
    [monte_carlo]                  the convergence campaign of Table 3 (ogk.missions.binary
                                   .convergence_run): the transfer flown, runs per level, the corrector's tol and max_iter there;
                                   what it draws is [dispersions] (levels_percent, sigma_fraction), the
                                   paper's column [paper_results.table3]
"""
from __future__ import annotations

import dataclasses
import math
import time
from typing import Any

import numpy as np

from ogk_bindings.blt import BltReport, Transfer

from ogk_bindings.errors import OgkInputError
from ..scenario_file import Section
from .design import CORRECTORS, JACOBIANS, Converged, converge, thrust_continuation
from .dynamics import Model, model_from_scenario
from .guess import Circle, Guess, OrbitPhase, bmpig, sbig, ubmpig
from .orbits import CorrectionError, scaled_degree2, scenario_orbit
from .scenario import BinaryScenario

KINDS = ("single-burn", "ump-backward", "bmp")


#: The RK4 step bound when [solver] step_max_s is left out: this fraction of the scenario's time unit
#: (Moshup's 20 s is 2.0e-3 of its TU = 9982 s; DOP853 re-checks every flown transfer's |e|).
STEP_MAX_TU = 2.0e-3


@dataclasses.dataclass(frozen=True)
class SolverSettings:
    step_max_s: float = 20.0          #: [s] RK4 step bound (default: STEP_MAX_TU of the scenario's TU)
    tol: float = 1e-6                 #: [-] |e|_2, normalised (the paper's, sec. III.D)
    max_iter: int = 40                #: the paper's NRPC limit (sec. VI)
    fd_step: float = 1e-6             #: [-] central-difference step, normalised
    ls_trials: int = 4                #: step lengths 1, 1/10, 1/100, 1/1000
    corrector: str = "hybrid"         #: nrpc | lm | hybrid
    jacobian: str = "variational"     #: variational | central
    gravity: str = "scenario"         #: scenario | degree2 | point-mass
    srp: bool = True                  #: SRP in the corrector's model (eq. 9)
    sun: bool = True                  #: solar tide in the corrector's model (eq. 10)

    def kernel_fields(self, tol: float | None = None, max_iter: int | None = None) -> dict[str, Any]:
        return dict(tol=self.tol if tol is None else tol, max_iter=self.max_iter if max_iter is None else max_iter,
                    fd_step=self.fd_step, ls_trials=self.ls_trials)


@dataclasses.dataclass(frozen=True)
class TransferSpec:
    name: str
    kind: str                         #: single-burn | ump-backward
    thrust_n: float                   #: [N]
    to_orbit: str
    from_orbit: str | None = None     #: single-burn
    circle_radius_m: float | None = None   #: ump-backward: departure circle about the barycentre [m]
    manifold_sign: int = -1           #: ump-backward: branch of the target's stable manifold (-1: exterior)
    insertion_dv_m_s: tuple[float, float] = (0.0128, 0.0383)   #: ump-backward: bounds of d [m/s]
    #: the paper's figures of this transfer ([paper_results.transfers.NAME]: flight_time_s, burn_time_s,
    #: fuel_g, iterations); empty when the scenario has none
    paper: dict[str, float] = dataclasses.field(default_factory=dict)
    step_max_s: float | None = None   #: [s] this transfer's RK4 step bound (default: [solver] step_max_s)


@dataclasses.dataclass(frozen=True)
class MonteCarloSpec:
    transfer: str
    levels_percent: tuple[float, ...]
    runs: int
    tol: float
    max_iter: int
    sigma_fraction: float             #: sigma of a draw as a fraction of the level (1/3: the level is 3 sigma)


def solver_settings(scenario: BinaryScenario) -> SolverSettings:
    s = Section(scenario.solver, scenario.path, "solver")
    d = SolverSettings()
    out = SolverSettings(step_max_s=s.number("step_max_s", STEP_MAX_TU * scenario.units.time_s,
                                             positive=True),
                         tol=s.number("tol", d.tol, positive=True),
                         max_iter=s.integer("max_iter", d.max_iter, lo=1, hi=500),
                         fd_step=s.number("fd_step", d.fd_step, positive=True),
                         ls_trials=s.integer("ls_trials", d.ls_trials, lo=1, hi=30),
                         corrector=s.text("corrector", d.corrector, choices=tuple(CORRECTORS)),
                         jacobian=s.text("jacobian", d.jacobian, choices=tuple(JACOBIANS)),
                         gravity=s.text("gravity", d.gravity, choices=("scenario", "degree2", "point-mass")),
                         srp=s.flag("srp", d.srp), sun=s.flag("sun", d.sun))
    s.finish()
    return out


def transfer_spec(scenario: BinaryScenario, name: str) -> TransferSpec:
    if name not in scenario.transfers:
        raise OgkInputError(f"no [transfers.{name}] (has: {', '.join(scenario.transfers) or 'none'})",
                            path=scenario.path, key="--transfer")
    s = Section(scenario.transfers[name], scenario.path, f"transfers.{name}")
    kind = s.text("kind", choices=KINDS)
    thrust = s.number("thrust_n", positive=True)
    to_orbit = s.text("to_orbit")
    paper = {k: float(v) for k, v in
             ((scenario.paper_results or {}).get("transfers", {}).get(name, {})).items()}
    for orbit in [to_orbit] + ([scenario.transfers[name].get("from_orbit")] if kind != "ump-backward" else []):
        if orbit not in scenario.orbits:
            raise s.error("to_orbit" if orbit == to_orbit else "from_orbit",
                          f"no [orbits.{orbit}] (has: {', '.join(scenario.orbits)})")
    if kind in ("single-burn", "bmp"):
        spec = TransferSpec(name=name, kind=kind, thrust_n=thrust, to_orbit=to_orbit, from_orbit=s.text("from_orbit"),
                            paper=paper)
        if kind == "bmp":
            spec = dataclasses.replace(spec, insertion_dv_m_s=(s.number("manifold_dv_m_s", positive=True),) * 2)
    else:
        bounds = s.numbers("insertion_dv_m_s", length=2)
        if not 0.0 < bounds[0] < bounds[1]:
            raise s.error("insertion_dv_m_s", "must be [low, high] with 0 < low < high")
        spec = TransferSpec(name=name, kind=kind, thrust_n=thrust, to_orbit=to_orbit,
                            circle_radius_m=s.number("circle_radius_m", positive=True),
                            manifold_sign=s.integer("manifold_sign", -1, lo=-1, hi=1),
                            insertion_dv_m_s=(bounds[0], bounds[1]), paper=paper)
        if spec.manifold_sign == 0:
            raise s.error("manifold_sign", "must be +1 or -1")
    if s.has("step_max_s"):
        spec = dataclasses.replace(spec, step_max_s=s.number("step_max_s", positive=True))
    s.finish()
    return spec


def monte_carlo_spec(scenario: BinaryScenario) -> MonteCarloSpec:
    """[monte_carlo] (the campaign's settings) with [dispersions] (what it draws)."""
    if not scenario.monte_carlo:
        raise OgkInputError("no [monte_carlo] table", path=scenario.path)
    if scenario.dispersions is None:
        raise OgkInputError("missing table: the [monte_carlo] campaign draws what [dispersions] states "
                            "(levels_percent, sigma_fraction)", path=scenario.path, key="dispersions")
    s = Section(scenario.monte_carlo, scenario.path, "monte_carlo")
    spec = MonteCarloSpec(transfer=s.text("transfer"), levels_percent=scenario.dispersions.levels_percent,
                          runs=s.integer("runs", lo=1), tol=s.number("tol", positive=True),
                          max_iter=s.integer("max_iter", lo=1, hi=500),
                          sigma_fraction=scenario.dispersions.sigma_fraction)
    s.finish()
    if spec.transfer not in scenario.transfers:
        raise s.error("transfer", f"no [transfers.{spec.transfer}]")
    return spec


# ------------------------------------------------------------------------------------------ the pipeline

def corrector_model(scenario: BinaryScenario, spec: TransferSpec, solver: SolverSettings) -> Model:
    """The kernel's model of this transfer (normalised; docs/design/blt.md sec. 1)."""
    gravity = None if solver.gravity == "scenario" else solver.gravity
    step = solver.step_max_s if spec.step_max_s is None else spec.step_max_s
    return model_from_scenario(scenario, spec.thrust_n, gravity=gravity, srp=solver.srp, sun=solver.sun,
                               step_max=step / scenario.units.time_s)


def initial_guess(scenario: BinaryScenario, spec: TransferSpec, model: Model) -> Guess:
    """SBIG or UbMPIG in the scenario's gravity (orbits and manifolds: the gravity-only model)."""
    gravity_model = model.gravity_only()
    target = scenario_orbit(scenario, spec.to_orbit, gravity_model)
    if spec.kind == "single-burn":
        assert spec.from_orbit is not None
        return sbig(model, scenario_orbit(scenario, spec.from_orbit, gravity_model), target)
    if spec.kind == "bmp":
        assert spec.from_orbit is not None
        return bmpig(model, scenario_orbit(scenario, spec.from_orbit, gravity_model), target,
                     deviation=spec.insertion_dv_m_s[0] / scenario.units.velocity_m_s)
    assert spec.circle_radius_m is not None
    vu = scenario.units.velocity_m_s
    return ubmpig(model, Circle(spec.circle_radius_m / scenario.units.length_m), target, sign=spec.manifold_sign,
                  deviation_bounds=(spec.insertion_dv_m_s[0] / vu, spec.insertion_dv_m_s[1] / vu))


@dataclasses.dataclass
class Design:
    spec: TransferSpec
    model: Model
    guess: Guess
    result: Converged
    guess_s: float                    #: [s] wall time of the guess stage
    solve_s: float                    #: [s] wall time of the convergence stage (all kernel solves)

    @property
    def transfer(self) -> Transfer:
        return self.result.transfer

    @property
    def report(self) -> BltReport:
        return self.result.report


#: When no manifold pair of a BMP reaches the cut without impact at the scenario's manifold_dv_m_s (the
#: Moshup L1 halo's, docs/design/blt-transfers.md), the guess is retried at these multiples of it: a larger d
#: leaves the orbit faster and clears the secondary (0.15 VU: 2 of 48 L1-halo phases reach the cut).
BMP_WIDER_DEVIATIONS = (3.0, 6.0)


def _wider_bmp_guess(scenario: BinaryScenario, spec: TransferSpec, model: Model,
                     first: CorrectionError) -> tuple[TransferSpec, Guess]:
    """BMPIG at BMP_WIDER_DEVIATIONS x manifold_dv_m_s; the first that finds an impact-free pair."""
    for scale in BMP_WIDER_DEVIATIONS:
        d = spec.insertion_dv_m_s[0] * scale
        wider = dataclasses.replace(spec, insertion_dv_m_s=(d, d))
        try:
            return wider, initial_guess(scenario, wider, model)
        except CorrectionError:
            continue
    raise CorrectionError(f"{first} (nor at {' or '.join(f'{k:g}' for k in BMP_WIDER_DEVIATIONS)} x "
                          f"manifold_dv_m_s)") from first


#: The gravity continuation's first step in lambda (the degree-2 coefficients' scale, 1 -> 0) and its smallest.
GRAVITY_STEP, GRAVITY_MIN_STEP = 0.25, 1.0 / 32.0


def _gravity_continuation(scenario: BinaryScenario, spec: TransferSpec, solver: SolverSettings, model: Model,
                          corrector: str, jacobian: str) -> tuple[Guess, Converged]:
    """A single burn in the point-mass model (`model`) reached from the scenario's degree-2 model: the transfer
    converged there, then lambda (both bodies' C20, C22 x lambda) stepped 1 -> 0, at each step both orbits
    rebuilt in the lambda model, the start and the target moved to the same phase fraction of them, the solve
    warm-started from the last solution; a failed step is halved (to GRAVITY_MIN_STEP). Beyond the paper: the
    point-mass guesses of Moshup's halo pair stall (L2 -> L1) or graze Beta (L1 -> L2)."""
    assert spec.from_orbit is not None and spec.to_orbit is not None
    full = corrector_model(scenario, spec, dataclasses.replace(solver, gravity="degree2"))
    guess = initial_guess(scenario, spec, full)
    fields = solver.kernel_fields()
    result = converge(full, guess, corrector=corrector, jacobian=jacobian, **fields)
    steps = [dict(gravity_scale=1.0, **st) for st in result.steps]

    def orbits(m: Model) -> tuple[OrbitPhase, OrbitPhase]:
        gm = m.gravity_only()
        return (OrbitPhase(scenario_orbit(scenario, spec.from_orbit or "", gm)),
                OrbitPhase(scenario_orbit(scenario, spec.to_orbit or "", gm)))
    phases = orbits(full)
    frac = (guess.info["phase_departure"] / phases[0].orbit.period,
            guess.info["phase_arrival"] / phases[1].orbit.period)
    lam, h = 1.0, GRAVITY_STEP
    while result.report.converged and lam > 0.0:
        nxt = max(0.0, lam - h)
        m = model if nxt == 0.0 else scaled_degree2(full, nxt)
        dep, arr = orbits(m)
        tr = dataclasses.replace(result.transfer, x0=dep(frac[0] * dep.orbit.period),
                                 xf=arr(frac[1] * arr.orbit.period))
        attempt = converge(m, Guess(layout=guess.layout, transfer=tr, info=guess.info), corrector=corrector,
                           jacobian=jacobian, **fields)
        steps += [dict(gravity_scale=nxt, **st) for st in attempt.steps]
        if attempt.report.converged:
            lam, result = nxt, attempt
        elif h / 2.0 >= GRAVITY_MIN_STEP:
            h /= 2.0
        else:
            result = attempt
    result.steps = steps
    return guess, result


def design(scenario: BinaryScenario, spec: TransferSpec, solver: SolverSettings, *, corrector: str | None = None,
           jacobian: str | None = None, base_thrust_n: float | None = None) -> Design:
    """Guess, then the kernel's corrector in the realistic model (design.converge). When that fails and
    `base_thrust_n` (the thrust the transfer is defined at) differs from spec.thrust_n, the guess is built at
    the base thrust and carried to spec.thrust_n by design.thrust_continuation."""
    model = corrector_model(scenario, spec, solver)
    corr, jac = corrector or solver.corrector, jacobian or solver.jacobian
    start = time.perf_counter()
    guess_spec = spec
    try:
        guess = initial_guess(scenario, spec, model)
    except CorrectionError as exc:
        if spec.kind != "bmp":
            raise
        guess_spec, guess = _wider_bmp_guess(scenario, spec, model, exc)
    mid = time.perf_counter()
    result = converge(model, guess, corrector=corr, jacobian=jac, **solver.kernel_fields())
    if spec.kind == "bmp":
        # the manifold pair the grid picks moves with d: a few neighbouring d before giving up
        for scale in (0.8, 1.25, 0.64, 1.5625):
            if result.report.converged:
                break
            d = guess_spec.insertion_dv_m_s[0] * scale
            try:
                alt = initial_guess(scenario, dataclasses.replace(spec, insertion_dv_m_s=(d, d)), model)
            except CorrectionError:
                continue
            attempt = converge(model, alt, corrector=corr, jacobian=jac, **solver.kernel_fields())
            attempt.steps = [dict(deviation_scale=scale, **st) for st in attempt.steps]
            attempt.steps = result.steps + attempt.steps
            guess, result = alt, attempt
    if (not result.report.converged and spec.kind == "single-burn" and scenario.gravity.model == "degree2"
            and not any(model.c20) and not any(model.c22)):
        direct = result.steps
        guess, result = _gravity_continuation(scenario, spec, solver, model, corr, jac)
        result.steps = [dict(direct=True, **st) for st in direct] + result.steps
    if not result.report.converged and base_thrust_n is not None and base_thrust_n != spec.thrust_n:
        base = corrector_model(scenario, dataclasses.replace(spec, thrust_n=base_thrust_n), solver)
        guess = initial_guess(scenario, guess_spec, base)
        direct = result.steps
        result = thrust_continuation(model, guess, base.thrust_accel, corrector=corr, jacobian=jac,
                                     **solver.kernel_fields())
        result.steps = [dict(direct=True, **st) for st in direct] + result.steps
    return Design(spec=spec, model=model, guess=guess, result=result, guess_s=mid - start,
                  solve_s=time.perf_counter() - mid)


def figures(scenario: BinaryScenario, d: Design) -> dict[str, Any]:
    """SI figures of a designed transfer: burn and flight times, fuel, delta-v, closest approaches."""
    u, sc = scenario.units, scenario.spacecraft
    rep = d.report
    fuel_kg = (1.0 - rep.mass_final) * sc.mass_kg
    c = sc.specific_impulse_s * sc.standard_gravity_m_s2
    return dict(burn_time_s=rep.burn_time * u.time_s, flight_time_s=rep.flight_time * u.time_s,
                fuel_g=fuel_kg * 1e3, delta_v_m_s=c * math.log(1.0 / rep.mass_final),
                closest_approach_m=[float(x) * u.length_m for x in rep.min_distance],
                segment_times_s=[float(t) * u.time_s for t in d.transfer.segments[:, 6]],
                final_error=float(rep.err_norm), final_error_position_m=float(np.linalg.norm(rep.err[0:3])) * u.length_m
                if rep.n_errors >= 3 else None)
