"""The MPSP nominal as a ground product of its scenario (issue 19).

`ogk tables SCENARIO` (and `ogk run` / `ogk mc` when it is missing) makes the fuel-optimal nominal of
the scenario into its provenance directory `build/tables/<name>-<sha12>/`:

  nominal_solution.json   lambda_0 and the rest (indirect.solution_record), with `physics_sha256`
  manifest.json           made_by, scenario {name, path, sha256, physics_sha256}, nominal {file, sha256}

Nothing is written into the package. The shipped `data/nominal_solution.json` and
`data/perturbed_optima.json` are a cache: each states the `physics_sha256` of the scenario it was made
from, and is used only for a scenario of the same physics (`physics_sha256`: the sections that
determine the nominal, [units], [spacecraft], [transfer] duration_days, [boundary], [homotopy], as
parsed, so a comment or a [mpsp]/[dispersions] change does not invalidate it). Otherwise the nominal
is solved from scratch (energy-optimal start + smoothing homotopy, progress on a terminal).

Every nominal is re-propagated when loaded and must meet its boundary conditions; one made from
another scenario is refused (TableError, one line).
"""
from __future__ import annotations

import hashlib
import json
import os
from pathlib import Path
from typing import Any, Callable

from ogk_bindings.errors import OgkInputError, TableError

from ..paths import SCENARIO_DIR
from ..scenario_file import file_sha256, read_toml, table_dir_for
from .scenario import Scenario

MANIFEST = "manifest.json"
NOMINAL_FILE = "nominal_solution.json"
REFERENCES_FILE = "perturbed_optima.json"
MADE_BY = "ogk tables (low-thrust-transfer)"
#: the sections (and keys) of a scenario that determine its fuel-optimal nominal
PHYSICS_SECTIONS = ("units", "spacecraft", "boundary", "homotopy")
PHYSICS_KEYS = (("transfer", "duration_days"),)


def physics_sha256(scenario_path: str | Path) -> str:
    """SHA-256 of what determines the nominal: PHYSICS_SECTIONS and PHYSICS_KEYS as parsed (canonical
    JSON, keys sorted), so comments, [mpsp], [dispersions], [acceptance], [paper_results] and the
    header do not count."""
    raw = read_toml(scenario_path)
    doc: dict[str, Any] = {s: raw.get(s) for s in PHYSICS_SECTIONS}
    for sec, key in PHYSICS_KEYS:
        doc[f"{sec}.{key}"] = (raw.get(sec) or {}).get(key)
    text = json.dumps(doc, sort_keys=True, separators=(",", ":"), allow_nan=True)
    return hashlib.sha256(text.encode()).hexdigest()


def product_dir(scenario_path: str | Path) -> Path:
    """build/tables/<name>-<sha12> of the scenario file (ogk_host.scenario_file.table_dir_for)."""
    return table_dir_for(scenario_path)


def shipped_cache(what: str = NOMINAL_FILE) -> Path:
    return Path(__file__).resolve().parent / "data" / what


def cache_matches(path: Path, scenario_path: str | Path) -> bool:
    """The shipped cache file `path` was made from a scenario of the same physics."""
    try:
        doc = json.loads(Path(path).read_text())
    except (OSError, ValueError):
        return False
    return isinstance(doc, dict) and doc.get("physics_sha256") == physics_sha256(scenario_path)


def _write_atomic(path: Path, text: str) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(f".{path.name}.{os.getpid()}.tmp")
    tmp.write_text(text)
    os.replace(tmp, path)


def write_nominal(doc: dict[str, Any], scenario: Scenario, out: Path) -> Path:
    """nominal_solution.json (with physics_sha256) and manifest.json into `out`."""
    doc = {**doc, "physics_sha256": physics_sha256(scenario.path),
           "scenario_sha256": file_sha256(scenario.path), "scenario": str(scenario.path)}
    path = Path(out) / NOMINAL_FILE
    _write_atomic(path, json.dumps(doc, indent=1) + "\n")
    _write_manifest(Path(out), scenario)
    return path


def _write_manifest(out: Path, scenario: Scenario) -> None:
    from ..scenario_file import read_header
    header = read_header(scenario.path)
    manifest_path = out / MANIFEST
    manifest: dict[str, Any] = {}
    if manifest_path.is_file():
        try:
            manifest = json.loads(manifest_path.read_text())
        except ValueError:
            manifest = {}
    nominal = out / NOMINAL_FILE
    manifest.update({
        "made_by": MADE_BY,
        "scenario": {"name": header.name, "path": str(scenario.path), "sha256": header.sha256,
                     "physics_sha256": physics_sha256(scenario.path)},
        "nominal": {"file": NOMINAL_FILE, "sha256": file_sha256(nominal)},
    })
    _write_atomic(manifest_path, json.dumps(manifest, indent=1) + "\n")


def record_file(out: Path, name: str, path: Path) -> None:
    """Add a product file (e.g. the C header) with its SHA-256 to the manifest of `out`."""
    manifest_path = Path(out) / MANIFEST
    manifest = json.loads(manifest_path.read_text())
    files = [f for f in manifest.get("files", []) if f.get("file") != name]
    files.append({"file": name, "sha256": file_sha256(path)})
    manifest["files"] = files
    _write_atomic(manifest_path, json.dumps(manifest, indent=1) + "\n")


def check_nominal(out: Path, scenario: Scenario) -> Path:
    """The nominal file of `out` if it belongs to `scenario` (manifest: this file's SHA-256; nominal:
    its SHA-256 and physics), else TableError (one line)."""
    out = Path(out)
    manifest_path, nominal = out / MANIFEST, out / NOMINAL_FILE
    try:
        manifest = json.loads(manifest_path.read_text())
        doc = json.loads(nominal.read_text())
    except (OSError, ValueError) as exc:
        raise TableError(f"no readable {MANIFEST} and {NOMINAL_FILE} ({exc.__class__.__name__}); "
                         "make them with `ogk tables`", path=out) from None
    want = file_sha256(scenario.path)
    rec = manifest.get("scenario") or {}
    if manifest.get("made_by") != MADE_BY or rec.get("sha256") != want:
        raise TableError(f"made from scenario {rec.get('name')!r} ({rec.get('path')}, SHA-256 "
                         f"{str(rec.get('sha256'))[:12]}), not from {scenario.path} (SHA-256 "
                         f"{want[:12]}): regenerate with `ogk tables` or use "
                         f"{product_dir(scenario.path)}", path=out)
    if (manifest.get("nominal") or {}).get("sha256") != file_sha256(nominal):
        raise TableError("corrupted: SHA-256 differs from the manifest", path=nominal)
    if doc.get("physics_sha256") != physics_sha256(scenario.path):
        raise TableError("the nominal was made from another problem (physics_sha256 differs)",
                         path=nominal)
    return nominal


def _verified(scenario: Scenario, path: Path) -> Any:
    """Load (re-propagate) the nominal at `path`; refuse one that misses its boundary conditions."""
    from .indirect import load_solution
    sol = load_solution(scenario, path)
    m = scenario.mpsp
    if not (sol.position_error_km <= 1e-3 * m.tol_position_km
            and sol.velocity_error_km_s <= 1e-3 * m.tol_velocity_km_s
            and abs(float(sol.residual[6])) <= 1e-3 * m.tol_lambda_mf):
        raise TableError(f"the nominal does not meet the boundary conditions when re-integrated "
                         f"(|dr_f| = {sol.position_error_km:.3g} km, |dv_f| = "
                         f"{sol.velocity_error_km_s:.3g} km/s): regenerate with `ogk tables`",
                         path=path)
    return sol


class _Quiet:
    """A long step shown nowhere: what the ground tools use unless their caller shows progress."""

    def __init__(self, title: str) -> None:
        self.title = title

    def __enter__(self) -> "_Quiet":
        return self

    def __exit__(self, *exc: object) -> None:
        return None

    def note(self, text: str) -> None:
        return None


#: a context manager factory `working(title)` whose value has `note(text)`: the harness passes
#: ogk.sil.progress.Working (progress on a terminal); the ground tools do not import upward
Working = Callable[[str], Any]


def solve_nominal(scenario: Scenario, log: Callable[[str], None] | None = None,
                  working: Working | None = None) -> Any:
    """The fuel-optimal nominal from scratch; `working` shows its progress (module's Working)."""
    from .indirect import ShootingFailure, solve_fuel_optimal
    show = working or _Quiet
    try:
        with show(f"{scenario.path.name}: fuel-optimal nominal") as work:
            def note(text: str) -> None:
                work.note(text.strip())
                if log:
                    log(text)
            return solve_fuel_optimal(scenario, None, log=note)
    except ShootingFailure as err:
        raise OgkInputError(f"no fuel-optimal nominal for this transfer ({err}); the problem may be "
                            "infeasible (thrust, duration, target)", path=scenario.path,
                            key="transfer") from None


def continue_from_cache(scenario: Scenario, log: Callable[[str], None] | None = None,
                        working: Working | None = None) -> Any:
    """The nominal of `scenario` by continuation (eq. 51) from the shipped cache's nominal, when
    the two problems differ only in what a Perturbation moves (initial state, target position,
    T_max) and agree in units, mass, Isp, duration, target velocity and homotopy; None otherwise or
    when the continuation fails (the caller then solves from scratch). The result is re-propagated
    on `scenario`'s own problem by ensure_nominal before it is used."""
    import dataclasses

    import numpy as np

    from .indirect import ShootingFailure, load_solution, solve_fuel_optimal
    from .scenario import Perturbation, load_scenario, normalised_problem
    cache = shipped_cache(NOMINAL_FILE)
    try:
        doc = json.loads(cache.read_text())
        # the cache names its scenario as the repository does ("scenarios/apophis_cubesat.toml"):
        # the shipped file of that name, the repository's or the wheel's (ogk_host.paths)
        base_path = SCENARIO_DIR / Path(str(doc.get("scenario", ""))).name
        if not base_path.is_file() or physics_sha256(base_path) != doc.get("physics_sha256"):
            return None
        base = load_scenario(base_path)
    except (OSError, ValueError, OgkInputError):
        return None
    if (base.units != scenario.units or base.homotopy != scenario.homotopy
            or base.duration_days != scenario.duration_days
            or base.spacecraft.initial_mass_kg != scenario.spacecraft.initial_mass_kg
            or base.spacecraft.specific_impulse_s != scenario.spacecraft.specific_impulse_s
            or not np.array_equal(base.boundary.vf, scenario.boundary.vf)):
        return None
    b, n = base.boundary, scenario.boundary
    pert = Perturbation(delta_r0=n.r0 - b.r0, delta_v0=n.v0 - b.v0, delta_rf=n.rf - b.rf,
                        thrust_fraction=scenario.spacecraft.max_thrust_N / base.spacecraft.max_thrust_N
                        - 1.0, label=f"{scenario.path.name} from the cached nominal")
    show = working or _Quiet
    title = f"{scenario.path.name}: nominal by continuation from {base_path.name}'s"
    try:
        warm = load_solution(base, cache)
        with show(title) as work:
            sol = solve_fuel_optimal(base, pert, warm_start=warm,
                                     log=lambda text: (work.note(text.strip()),
                                                       log(text) if log else None))
    except ShootingFailure as err:
        if log:
            log(f"continuation from the cached nominal failed ({err}); solving from scratch")
        return None
    if np.max(np.abs(normalised_problem(base, pert).x0 - normalised_problem(scenario).x0)) > 1e-12:
        return None
    return dataclasses.replace(sol, perturbation=Perturbation(),
                               method=f"{sol.method} from the cached nominal of {base_path.name}")


def ensure_nominal(scenario: Scenario, out: str | Path | None = None, *,
                   log: Callable[[str], None] | None = None,
                   working: Working | None = None) -> tuple[Any, Path]:
    """The scenario's own nominal (Solution, file): checked if `out` (default its product directory)
    has one; else taken from the shipped cache when its physics is the same, or solved; written with
    its manifest into `out`. A user's `out` holding another scenario's products is refused."""
    directory = Path(out) if out is not None else product_dir(scenario.path)
    if (directory / NOMINAL_FILE).exists() or (directory / MANIFEST).exists():
        manifest_path = directory / MANIFEST
        if (directory / NOMINAL_FILE).exists():
            path = check_nominal(directory, scenario)
            return _verified(scenario, path), path
        # a manifest without nominal (e.g. older `ogk tables`): must still be this scenario's
        try:
            rec = json.loads(manifest_path.read_text()).get("scenario") or {}
        except ValueError:
            rec = {}
        if rec.get("sha256") not in (None, file_sha256(scenario.path)):
            raise TableError(f"made from scenario {rec.get('name')!r} ({rec.get('path')}), not from "
                             f"{scenario.path}", path=directory)
    cache = shipped_cache(NOMINAL_FILE)
    if cache.exists() and cache_matches(cache, scenario.path):
        doc = json.loads(cache.read_text())
        doc["cache"] = f"shipped {cache.name} (physics_sha256 {doc['physics_sha256'][:12]})"
        path = write_nominal(doc, scenario, directory)
        return _verified(scenario, path), path
    from .indirect import solution_record
    sol = continue_from_cache(scenario, log, working) if cache.exists() else None
    if sol is None:
        sol = solve_nominal(scenario, log, working)
    doc = {"generator": "ogk tables (ogk_host.low_thrust_transfer.products.ensure_nominal)",
           "units": "normalised: LU, TU, MU, velocity LU/TU (Table 1)",
           **solution_record(sol, scenario)}
    path = write_nominal(doc, scenario, directory)
    return _verified(scenario, path), path


def references_for(scenario: Scenario, out: str | Path | None = None) -> Path | None:
    """The perturbed optima (FI seeds) of this scenario's physics: its product directory's
    perturbed_optima.json, else the shipped one when its physics_sha256 matches, else None."""
    own = (Path(out) if out is not None else product_dir(scenario.path)) / REFERENCES_FILE
    if own.exists() and cache_matches(own, scenario.path):
        return own
    shipped = shipped_cache(REFERENCES_FILE)
    if shipped.exists() and cache_matches(shipped, scenario.path):
        return shipped
    return None

