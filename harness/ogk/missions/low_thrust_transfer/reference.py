"""Fuel-optimal re-solves of the perturbed problems (ground indirect solver), cached on disk.

One JSON per case in <the scenario's product directory build/tables/<name>-<sha12>>/reference/<case
key>.json (keyed by scenario), valid while the scenario file's SHA-256 (and its nominal's, the warm
start) are unchanged; otherwise recomputed with
`solve_fuel_optimal(scenario, perturbation, warm_start=nominal)`. Loading re-integrates the stored
lambda_0 (DOP853, the scenario's final rtol) and recomputes arcs, final mass and terminal errors, so a
cache entry is only trusted after it has been verified against the dynamics.
"""
from __future__ import annotations

import dataclasses
import hashlib
import json
import time
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from ogk.missions.low_thrust_transfer.cases import MpspSetup, Case
from ogk.sil.runner import CallTimeout, call_with_timeout

F64 = NDArray[np.float64]
FORMAT = 1


@dataclasses.dataclass(frozen=True)
class Reference:
    """Fuel-optimal solution of one perturbed problem (verified by re-integration)."""

    key: str
    lam0: F64                    #: initial costates (7)
    final_mass_kg: float
    thrust_arcs: int
    arcs: tuple[tuple[float, float, float], ...]  #: (t_start, t_end, throttle) [TU]
    position_error_km: float     #: of the re-integration
    velocity_error_km_s: float
    lambda_mf: float
    solve_s: float               #: wall time of the ground solve that produced it
    method: str
    from_cache: bool


def sha256_of(path: Path) -> str:
    return hashlib.sha256(Path(path).read_bytes()).hexdigest()


def cache_key(setup: MpspSetup) -> dict[str, str]:
    """What an entry was made from: the scenario file and the scenario's own nominal (the warm
    start), by SHA-256; an entry of another scenario or nominal is recomputed, never used."""
    return {"scenario_sha256": sha256_of(setup.scenario.path),
            "nominal_sha256": setup.nominal_sha256}


def verify(setup: MpspSetup, case: Case, lam0: F64, solve_s: float, method: str,
           from_cache: bool) -> Reference:
    """Re-integrate lambda_0 of the perturbed problem: arcs, final mass, terminal errors."""
    from ogk_host.low_thrust_transfer.indirect import propagate, shooting_residual
    from ogk_host.low_thrust_transfer.scenario import normalised_problem
    sc = setup.scenario
    prob = normalised_problem(sc, case.perturbation)
    prop = propagate(prob, np.asarray(lam0, dtype=np.float64), 0.0, rtol=sc.homotopy.final_rtol)
    res = shooting_residual(prob, prop.z_final)
    arcs = tuple((float(a.t_start), float(a.t_end), float(a.throttle)) for a in prop.arcs)
    return Reference(case.key, np.asarray(lam0, dtype=np.float64).copy(),
                     float(prop.z_final[6] * sc.units.mass_kg),
                     sum(1 for a in arcs if a[2] == 1.0), arcs,
                     float(np.linalg.norm(res[0:3]) * sc.units.length_km),
                     float(np.linalg.norm(res[3:6]) * sc.units.velocity_km_s),
                     float(abs(prop.z_final[13])), float(solve_s), method, from_cache)


def is_converged(setup: MpspSetup, ref: Reference) -> bool:
    """Re-integrated terminal errors far inside the MPSP tolerances (a true optimum, not a guess)."""
    m = setup.scenario.mpsp
    return (ref.position_error_km <= 1e-3 * m.tol_position_km
            and ref.velocity_error_km_s <= 1e-3 * m.tol_velocity_km_s
            and ref.lambda_mf <= 1e-3 * m.tol_lambda_mf)


class ReferenceTimeout(RuntimeError):
    """The ground re-solve did not finish within the allowed wall time."""


def _solve(setup: MpspSetup, case: Case) -> tuple[list[float], float, str]:
    from ogk_host.low_thrust_transfer.indirect import solve_fuel_optimal
    start = time.perf_counter()
    sol = solve_fuel_optimal(setup.scenario, case.perturbation, warm_start=setup.nominal)
    return [float(x) for x in sol.lam0], time.perf_counter() - start, str(sol.method)


def solve_reference(setup: MpspSetup, case: Case, timeout_s: float | None = None) -> Reference:
    """Fresh ground re-solve (continuation from the nominal), verified. With timeout_s, the solve runs
    in a forked process that is killed after timeout_s of wall time (ReferenceTimeout;
    ogk.sil.runner.call_with_timeout)."""
    try:
        lam0, solve_s, method = call_with_timeout(lambda: _solve(setup, case), timeout_s)
    except CallTimeout:
        raise ReferenceTimeout(f"ground re-solve of {case.label} exceeded {timeout_s:g} s") from None
    except RuntimeError as err:
        raise RuntimeError(f"ground re-solve of {case.label} failed: {err}") from None
    return verify(setup, case, np.asarray(lam0), float(solve_s), str(method), False)


def committed_lambda0(setup: MpspSetup, case: Case) -> F64 | None:
    """lambda_0 of the same perturbed problem in the ground tool's committed references
    (the scenario's product directory, else the shipped host/ogk_host/low_thrust_transfer/data/
    perturbed_optima.json when its physics_sha256 is this scenario's; `python -m
    ogk_host.low_thrust_transfer references`), matched on the perturbation itself; None when absent.
    Used only after re-integration verifies it."""
    from ogk_host.low_thrust_transfer.products import references_for
    path = references_for(setup.scenario, setup.product_dir)
    if path is None:            # none made from this scenario's physics
        return None
    p = case.perturbation
    want = np.concatenate([p.delta_r0, p.delta_v0, p.delta_rf, [p.thrust_fraction]])
    for entry in json.loads(path.read_text()).get("cases", []):
        have = np.concatenate([entry["delta_r0_LU"], entry["delta_v0_LU_TU"], entry["delta_rf_LU"],
                               [entry["thrust_fraction"]]])
        if np.allclose(have, want, rtol=0.0, atol=1e-12):
            return np.asarray(entry["lambda0"], dtype=np.float64)
    return None


def load_or_solve(setup: MpspSetup, case: Case, cache_dir: Path | None = None,
                  timeout_s: float | None = None) -> Reference:
    """The cached reference of `case` if present, current and verified; else a fresh solve (stored)."""
    if cache_dir is None:
        cache_dir = setup.product_dir / "reference"
    path = Path(cache_dir) / f"{case.key}.json"
    key = cache_key(setup)
    if path.exists():
        try:
            doc = json.loads(path.read_text())
            if doc.get("format") == FORMAT and all(doc.get(k) == v for k, v in key.items()):
                ref = verify(setup, case, np.array(doc["lambda0"], dtype=np.float64),
                             float(doc["solve_s"]), str(doc["method"]), True)
                if is_converged(setup, ref):
                    return ref
        except (ValueError, KeyError, TypeError, RuntimeError):
            pass  # unreadable or stale entry: recompute
    ref = None
    seed = committed_lambda0(setup, case)
    if seed is not None:
        candidate = verify(setup, case, seed, 0.0, "committed ground reference", True)
        ref = candidate if is_converged(setup, candidate) else None
    if ref is None:
        ref = solve_reference(setup, case, timeout_s)
    if not is_converged(setup, ref):
        raise RuntimeError(f"ground re-solve of {case.label} does not re-integrate to the target")
    path.parent.mkdir(parents=True, exist_ok=True)
    doc = {"format": FORMAT, **key, "case": case.key, "label": case.label,
           "generator": "ogk mpsp apophis (ogk.missions.low_thrust_transfer.reference)",
           "lambda0": [float(x) for x in ref.lam0], "final_mass_kg": ref.final_mass_kg,
           "thrust_arcs": ref.thrust_arcs, "arcs_TU": [list(a) for a in ref.arcs],
           "position_error_km": ref.position_error_km,
           "velocity_error_km_s": ref.velocity_error_km_s, "lambda_mf": ref.lambda_mf,
           "solve_s": ref.solve_s, "method": ref.method}
    path.write_text(json.dumps(doc, indent=1) + "\n")
    return ref
