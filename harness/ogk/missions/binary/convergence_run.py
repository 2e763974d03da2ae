"""The convergence Monte Carlo of Table 3 (Xiong & Wang, sec. V.A.2): the nominal UMP transfer perturbed and
corrected again by the flight kernel, plain NRPC, the damped corrector and the hybrid on the same draws.

"Perturbation %" (the paper leaves it undefined; the scenario's [monte_carlo] comment and docs/design/blt.md say the
same): with p the level and xi ~ N(0, (sigma_fraction)^2) clipped to [-1, 1] (the level is the largest
perturbation: "perturbed by values up to p"),
  - each component of A and B of every burn: + p xi |[A; B]| (the law's scale, 1 after normalisation);
  - every duration T: T (1 + p xi);
  - the departure: moved along the circle by an ignition-time error p xi T_1 (T_1 the first burn's duration);
  - the free node: re-predicted from the perturbed parameters (backward from the target, as the guess stage
    does; eq. 72); the target is not perturbed ("the orbit determination ... is assumed to be accurate").
Run i of a campaign flies level i mod L (L levels) from its own stream (ogk.sil.seeds, the campaign
engine's): a run is reproducible alone, and the same draw serves every corrector. A record carries
the level and the perturbations as applied (disp.*, dispersions.py)."""
from __future__ import annotations

import dataclasses
import math
import time
from typing import Any

import numpy as np

from ogk_bindings.blt import HYBRID, LM, NRPC, Blt, Transfer
from ogk_host.binary.dynamics import Model
from ogk_host.binary.guess import Circle, Layout, kernel_config, predicted_node

from .dispersions import applied_record, record_keys
from .trajectory import reference_errors

CORRECTORS = {"nrpc": NRPC, "lm": LM, "hybrid": HYBRID}


@dataclasses.dataclass(frozen=True)
class Nominal:
    """What a worker needs: the corrector's model, the layout, the converged nominal and its circle."""

    model: Model
    layout: Layout
    transfer: Transfer
    circle_radius: float          #: [LU]
    tol: float
    max_iter: int
    jacobian: int
    fields: dict[str, Any]
    #: the DOP853 confirmation's tolerance ([acceptance] error_tolerance; None: `tol`)
    error_tolerance: float | None = None

    @property
    def accept_tol(self) -> float:
        return self.tol if self.error_tolerance is None else self.error_tolerance


def draw(nominal: Nominal, level: float, sigma_fraction: float,
         rng: np.random.Generator, applied: dict[str, Any] | None = None
         ) -> tuple[Transfer, dict[str, Any]]:
    """A perturbed problem and guess (see the module docstring) and the draw itself; `applied`
    gets the run's disp.* keys (dispersions.py) before the free node is predicted."""
    guess, d = perturbed(nominal, level, sigma_fraction, rng)
    if applied is not None:
        applied.update(applied_record(nominal, level, guess))
    if nominal.layout.free_nodes:
        guess.nodes = predicted_node(nominal.model, nominal.layout, guess, how="backward")
    return guess, d


def perturbed(nominal: Nominal, level: float, sigma_fraction: float,
              rng: np.random.Generator) -> tuple[Transfer, dict[str, Any]]:
    """The perturbed problem, its node not yet re-predicted, and the draw itself."""
    tr = nominal.transfer
    n_seg = tr.segments.shape[0]
    xi = np.clip(rng.normal(0.0, sigma_fraction, size=(n_seg * 7 + 1)), -1.0, 1.0)
    seg = tr.segments.copy()
    for k, kind in enumerate(nominal.layout.kinds):
        if kind == "burn":
            scale = float(np.linalg.norm(seg[k, 0:6]))
            seg[k, 0:6] += level * xi[7 * k: 7 * k + 6] * scale
        seg[k, 6] *= 1.0 + level * xi[7 * k + 6]
    circle = Circle(nominal.circle_radius)
    lon0 = math.atan2(tr.x0[1], tr.x0[0])
    shift = level * xi[-1] * tr.segments[0, 6]
    x0 = circle.state(lon0 + circle.synodic_rate * shift)
    guess = Transfer(t0=tr.t0, x0=x0, xf=tr.xf.copy(), segments=seg, nodes=tr.nodes.copy(), mass0=tr.mass0)
    return guess, dict(xi=xi.tolist(), departure_shift=shift)


def reason(rep_flags: list[str], status: str) -> str:
    if status == "OGK_OK":
        return "converged"
    for name, why in (("GUESS_IMPACT", "guess hits a body"), ("ITER_LIMIT", "iteration limit"),
                      ("SINGULAR", "singular Jacobian"), ("STALLED", "no decreasing step")):
        if name in rep_flags:
            return why
    return status


def kernels(nominal: Nominal, correctors: tuple[str, ...]) -> dict[str, Blt]:
    """One flight-kernel context per corrector, configured as the nominal's."""
    return {name: Blt(kernel_config(nominal.model, nominal.layout, corrector=CORRECTORS[name],
                                    jacobian=nominal.jacobian, tol=nominal.tol,
                                    max_iter=nominal.max_iter, **nominal.fields))
            for name in correctors}


def fly_run(nominal: Nominal, solvers: dict[str, Blt], level: float, sigma_fraction: float,
            rng: np.random.Generator) -> dict[str, Any]:
    """One perturbed problem corrected by each corrector on the same draw: a flat record
    (`<corrector>.converged`, `.reason`, `.iterations`, ...; timings under `timing.`)."""
    out: dict[str, Any] = {"level_percent": 100.0 * level}
    applied: dict[str, Any] = dict.fromkeys(record_keys(nominal))
    try:
        guess, d = draw(nominal, level, sigma_fraction, rng, applied)
    except (ValueError, RuntimeError) as exc:       # the perturbed prediction itself fails (impact, mass)
        out["draw.xi"] = None
        out["draw.departure_shift"] = None
        for name in solvers:
            out.update({f"{name}.converged": False, f"{name}.reason": f"no guess: {exc}"})
        return {**out, **applied}
    out.update(applied)
    out["draw.xi"] = d["xi"]
    out["draw.departure_shift"] = float(d["departure_shift"])
    for name, kernel in solvers.items():
        start = time.process_time()
        try:
            sol, rep = kernel.solve(guess)
        except Exception as exc:                     # bad input the kernel refused (range): a failure
            out.update({f"{name}.converged": False, f"{name}.reason": f"rejected: {exc}"})
            continue
        out[f"timing.{name}.cpu_ms"] = 1e3 * (time.process_time() - start)
        out.update({f"{name}.converged": bool(rep.converged),
                    f"{name}.reason": reason(rep.flag_names(), rep.status),
                    f"{name}.iterations": int(rep.iterations), f"{name}.err_norm0": rep.err_norm0,
                    f"{name}.err_norm": rep.err_norm, f"{name}.burn_time": rep.burn_time,
                    f"{name}.mass_final": rep.mass_final})
        if rep.converged:
            # the independent check: the same error vector by DOP853 (rtol 1e-12) must meet the
            # scenario's acceptance tolerance (default: the corrector's own tol)
            ref = reference_errors(nominal.model, nominal.layout, sol)
            out[f"{name}.dop853_err_norm"] = ref.err_norm
            out[f"{name}.dop853_meets_tol"] = bool(ref.err_norm <= nominal.accept_tol and not ref.impact)
    return out


def summarise(records: list[dict[str, Any]], corrector: str) -> dict[str, Any]:
    """Converged %, DOP853 confirmations, failure reasons and iterations of one corrector."""
    res = [r for r in records if f"{corrector}.converged" in r]
    conv = [r for r in res if r[f"{corrector}.converged"]]
    reasons: dict[str, int] = {}
    for r in res:
        if not r[f"{corrector}.converged"]:
            why = r[f"{corrector}.reason"]
            reasons[why] = reasons.get(why, 0) + 1
    its = [r[f"{corrector}.iterations"] for r in conv]
    confirmed = sum(1 for r in conv if r.get(f"{corrector}.dop853_meets_tol"))
    return dict(runs=len(res), converged=len(conv), converged_pct=100.0 * len(conv) / max(len(res), 1),
                dop853_confirmed=confirmed,
                failures=reasons, iterations_median=float(np.median(its)) if its else None,
                iterations_max=int(max(its)) if its else None)
