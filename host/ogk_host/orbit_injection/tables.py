"""VTD-NOG flight tables for the LEO-to-GEO burn: SI arrays and ogk binary table files.

Every table has the normalised time tau as its grid (default_tau_grid: 0 <= tau < 1) and SI entries
(state [m, rad, rad, m/s, m/s, m/s, s], costates in s per state unit with h = -1, controls in rad,
' = d/dtau). Layout of each entry (row-major):

  kind        name               dims    content
  0x4E4F4701  nominal            (4, 7)  x*, x*', lambda*, lambda*'  (cubic-Hermite-ready)
  0x4E4F4702  control            (2, 2)  [alpha*, beta*], [alpha*', beta*']
  0x4E4F4703  gain               (8, 7)  [dlam_k; dt_f] = gain @ dx_k, dx_k = x(t_k) - x*(tau_k),
                                         dx_k[6] = t_k - t_f* tau_k; dt_f in s
  0x4E4F4704  costate_rate_gain  (7, 7)  dlam'(tau_k) = N @ dx_k (first-order hold of dlam)
  0x4E4F4705  control_gain       (2, 7)  du = K_lam @ dlam (eq. 30; H_ux = H_ua = 0 here)
  0x4E4F4706  scalars            (8,)    one grid point (tau = 0): t_f* [s], f0* [rad],
                                         Delta t_S [s], DU [m], TU [s], mu [m^3/s^2],
                                         n0 [m/s^2], c [m/s]

The flight code (kernel/include/ogk/nog.h) loads one bundle instead:

  0x4E4F4742  nog_bundle         (133,)  [x* (7), x*' (7), lambda* (7), lambda*' (7), G (56), N (49)]
                                         on the same grid plus tau = 1 (gain blocks zero there)

Command: `python -m ogk_host.orbit_injection.tables [OUT_DIR] [--scenario F]` writes the six .ogkt
files, the bundle nog_bundle.ogkt and a manifest.json into OUT_DIR (default
`default_table_dir`: build/tables/<name>-<sha12>). Provenance (docs/design/vtd-nog.md sec. 7): made_by,
scenario name/path/SHA-256, t_f*, f0*, residuals, grid (capacity from the kernel, measured
interpolation error), derived settings with their source, each file's SHA-256 and CRC.
`write_nog_tables` never writes into a directory it did not make; `check_tables` verifies a
directory against a scenario; `ensure_nog_tables` generates the default directory or checks.
"""
from __future__ import annotations

import argparse
import dataclasses
import datetime as _dt
import hashlib
import json
import math
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from .. import tablefile
from ogk_bindings.errors import OgkInputError, TableError
from ..dir_lock import directory_lock
from ..scenario_file import table_dir_for
from . import dynamics as dyn
from .derive import EffectiveSettings, effective_settings, freeze_rule_s, resolve
from .gains import (INTERPOLATION_ERROR_BOUND, GainTable, GridCapacityError, GridChoice,
                    choose_tau_grid, compute_gain_table, condition_numbers_si, interpolation_error,
                    kernel_table_capacity)
from .nominal import RESIDUAL_NAMES, Nominal, solve_nominal
from .scenario import DEFAULT_SCENARIO_PATH, load_scenario

FloatArray = NDArray[np.float64]

KIND_NOMINAL = 0x4E4F4701
KIND_CONTROL = 0x4E4F4702
KIND_GAIN = 0x4E4F4703
KIND_COSTATE_RATE_GAIN = 0x4E4F4704
KIND_CONTROL_GAIN = 0x4E4F4705
KIND_SCALARS = 0x4E4F4706
KIND_NOG_BUNDLE = 0x4E4F4742          #: OGK_NOG_TABLE_KIND ("NOGB") of kernel/include/ogk/nog.h
NOG_BUNDLE_ENTRY_LEN = 133            #: the host layout; checked against the kernel's OGK_NOG_ENTRY_LEN
GENERATOR = "ogk_host.orbit_injection.tables/3"  # /3: files named <table>.ogkt
MADE_BY = "ogk tables"                #: manifest["made_by"]: a directory this tool may overwrite
MANIFEST = "manifest.json"
BUNDLE_FILE = "nog_bundle.ogkt"


@dataclasses.dataclass(frozen=True)
class PlannedTable:
    """One table: kind, grid (N,), data (N, *dims), SI."""

    name: str
    kind: int
    grid: FloatArray
    data: FloatArray

    @property
    def dims(self) -> tuple[int, ...]:
        return tuple(int(d) for d in self.data.shape[1:])


def build_table_arrays(nominal: Nominal, table: GainTable) -> list[PlannedTable]:
    """The six flight tables as SI numpy arrays (canonical -> SI with units.py scales)."""
    units = nominal.problem.units
    x_scale, tu = units.state_scale, units.time_s
    lam_scale = tu / x_scale                          # lambda_SI = lambda_can * TU / X
    x, lam = table.z[:, :dyn.N_X], table.z[:, dyn.N_X:]
    rate = nominal.t_f * np.stack([dyn.extremal_rate(nominal.model, z) for z in table.z])
    nominal_rows = np.stack([x * x_scale, rate[:, :dyn.N_X] * x_scale,
                             lam * lam_scale, rate[:, dyn.N_X:] * lam_scale], axis=1)
    # u' = K_lam lambda' + K_x x' (H_u = 0 along the extremal)
    u_rate = (np.einsum("nij,nj->ni", table.control_gain, rate[:, dyn.N_X:])
              + np.einsum("nij,nj->ni", table.control_state_gain, rate[:, :dyn.N_X]))
    control_rows = np.stack([table.u, u_rate], axis=1)
    out_scale = np.append(lam_scale, tu)              # [dlam_SI; dt_f_s]
    gain_si = table.gain * out_scale[None, :, None] / x_scale[None, None, :]
    rate_gain_si = table.costate_rate_gain * lam_scale[None, :, None] / x_scale[None, None, :]
    control_gain_si = table.control_gain / lam_scale[None, None, :]
    scn = nominal.problem.scenario
    scalars = np.array([[nominal.t_f_s, nominal.f0, scn.sample_interval_s, units.length_m, tu,
                         scn.mu_m3_s2, scn.thrust.initial_accel_m_s2,
                         scn.thrust.exhaust_velocity_m_s]])
    grid = table.tau
    return [PlannedTable("nominal", KIND_NOMINAL, grid, nominal_rows),
            PlannedTable("control", KIND_CONTROL, grid, control_rows),
            PlannedTable("gain", KIND_GAIN, grid, gain_si),
            PlannedTable("costate_rate_gain", KIND_COSTATE_RATE_GAIN, grid, rate_gain_si),
            PlannedTable("control_gain", KIND_CONTROL_GAIN, grid, control_gain_si),
            PlannedTable("scalars", KIND_SCALARS, np.zeros(1), scalars)]


def build_nog_bundle(nominal: Nominal, table: GainTable) -> PlannedTable:
    """The single flight table of kernel/include/ogk/nog.h (kind OGK_NOG_TABLE_KIND, 133 doubles per
    node): the table's grid plus tau = 1, entries [x*, x*', lambda*, lambda*', G (8x7), N (7x7)] in SI;
    at tau = 1 the nominal blocks are filled and the (singular) gain blocks are zero."""
    planned = {p.name: p for p in build_table_arrays(nominal, table)}
    units = nominal.problem.units
    lam_scale = units.time_s / units.state_scale
    z1 = nominal.states(np.array([1.0]))[0]
    rate1 = nominal.t_f * dyn.extremal_rate(nominal.model, z1)
    last = np.concatenate([z1[:dyn.N_X] * units.state_scale, rate1[:dyn.N_X] * units.state_scale,
                           z1[dyn.N_X:] * lam_scale, rate1[dyn.N_X:] * lam_scale,
                           np.zeros(56 + 49)])
    body = np.concatenate([planned["nominal"].data.reshape(table.tau.size, -1),
                           planned["gain"].data.reshape(table.tau.size, -1),
                           planned["costate_rate_gain"].data.reshape(table.tau.size, -1)], axis=1)
    data = np.vstack([body, last])
    grid = np.append(table.tau, 1.0)
    max_grid, entry_len = kernel_table_capacity()
    if data.shape[1] != entry_len:
        raise ValueError(f"bundle entry of {data.shape[1]} doubles, the kernel's OGK_NOG_ENTRY_LEN "
                         f"is {entry_len}: host and kernel layouts disagree")
    if grid.size > max_grid:
        raise GridCapacityError(f"bundle of {grid.size} nodes does not fit OGK_NOG_MAX_GRID = "
                                f"{max_grid}: build the gains on `flight_grid` (tables.py)")
    return PlannedTable("nog_bundle", KIND_NOG_BUNDLE, grid, data)


def _sha256(path: Path) -> str:
    return hashlib.sha256(path.read_bytes()).hexdigest()


def default_table_dir(scenario_path: str | Path = DEFAULT_SCENARIO_PATH, precision: str = "double") -> Path:
    """build/tables/<scenario name>-<first 12 hex of the scenario file's SHA-256> under the
    repository root (`ogk_host.scenario_file.table_dir_for`, the same for every family): one
    directory per scenario content, so editing a scenario never reuses its previous tables.
    The tables of a single-precision kernel (F32, `precision` "single") have a directory of their
    own, the same name with "-single": double and single never share a file."""
    tablefile.element_type(precision)  # validates
    base = table_dir_for(scenario_path)
    return base if precision == "double" else base.with_name(f"{base.name}-{precision}")


def _manifest_precision(manifest: dict) -> str:
    """The precision of a manifest's tables (no "precision" key: double, as every file before it)."""
    return str(manifest.get("precision", "double"))


def flight_grid(nominal: Nominal, settings: EffectiveSettings | None = None,
                capacity: int | None = None) -> GridChoice:
    """The gain grid of the flight bundle: `choose_tau_grid` down to the effective freeze time
    (the kernel holds the correction past the last node), fitted to OGK_NOG_MAX_GRID."""
    scn = nominal.problem.scenario
    settings = effective_settings(scn) if settings is None else settings
    end_s = settings.freeze_time_to_go_s if settings.freeze_time_to_go_s > 0.0 else freeze_rule_s(scn)
    try:
        return choose_tau_grid(nominal.t_f_s, scn.sample_interval_s, end_s, capacity)
    except GridCapacityError as exc:
        raise GridCapacityError(exc.reason, path=getattr(scn, "path", None), key=exc.key) from None


def _is_ogk_dir(out: Path) -> bool:
    manifest = out / MANIFEST
    if not manifest.is_file():
        return False
    try:
        return json.loads(manifest.read_text()).get("made_by") == MADE_BY
    except (ValueError, OSError):
        return False


def write_nog_tables(out_dir: str | Path, scenario_path: str | Path = DEFAULT_SCENARIO_PATH, *,
                     nominal: Nominal | None = None, table: GainTable | None = None,
                     precision: str = "double") -> dict:
    """Writes <out_dir>/<name>.ogkt for every table and manifest.json; returns the manifest.

    Refuses (TableError) a non-empty directory without an ogk manifest: it never overwrites what it
    did not make. The manifest is removed first and written last, so a directory with a manifest
    is complete. `nominal`/`table` (optional) must come from the same scenario file; by default
    the nominal is solved and the gains computed on `flight_grid`, whose mid-node interpolation
    error is measured and must stay below INTERPOLATION_ERROR_BOUND. `precision` is the element
    type of the files (tablefile: "double" F64, "single" F32 for a kernel built with
    OGK_REAL_SINGLE=1); a single-precision manifest says so ("precision"), a double one is as before.
    """
    tablefile.element_type(precision)  # validates before the nominal is solved
    scenario_path = Path(scenario_path)
    out = Path(out_dir)
    if out.exists() and not out.is_dir():
        raise TableError("exists and is not a directory", path=out)
    if out.is_dir() and any(out.iterdir()) and not _is_ogk_dir(out):
        raise TableError(f"not empty and has no {MANIFEST} made by {MADE_BY!r}: refusing to write "
                         f"tables into it (give an empty or new directory)", path=out)
    scn = load_scenario(scenario_path)
    if nominal is None:
        nominal = solve_nominal(scn)
    settings = effective_settings(scn, nominal.t_f_s)   # with where each value came from
    scn = resolve(scn, nominal.t_f_s)          # what scales with the burn (derive.burn_scaled)
    check_burn_bounds(scn, nominal.t_f_s)
    grid = flight_grid(nominal, settings)
    if table is None:
        table = compute_gain_table(nominal, grid.tau)
    err_lam, err_dtf = interpolation_error(nominal, table)
    if err_lam > INTERPOLATION_ERROR_BOUND:
        raise GridCapacityError(
            f"gain interpolation error {err_lam:.3%} exceeds {INTERPOLATION_ERROR_BOUND:.1%} on the "
            f"grid that fits OGK_NOG_MAX_GRID = {grid.capacity} (uniform step {grid.step_s:g} s): "
            f"shorten sample_interval_s", path=scenario_path, key="guidance.sample_interval_s")
    bundle = build_nog_bundle(nominal, table)
    out.mkdir(parents=True, exist_ok=True)
    (out / MANIFEST).unlink(missing_ok=True)
    files = []
    for planned in build_table_arrays(nominal, table) + [bundle]:
        path = out / f"{planned.name}.ogkt"
        size = tablefile.write_table(path, planned.kind, planned.grid, planned.data, precision)
        header, _ = tablefile.TableHeader.unpack(path.read_bytes())
        files.append({"name": planned.name, "file": path.name, "kind": f"0x{planned.kind:08X}",
                      "dims": list(planned.dims), "grid_size": int(planned.grid.size),
                      "bytes": size, "sha256": _sha256(path),
                      "payload_crc32": f"0x{header.payload_crc:08X}"})
    manifest = {
        "made_by": MADE_BY,
        "generator": GENERATOR,
        "created_utc": _dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds"),
        "scenario": {"name": scn.name, "path": str(scenario_path.resolve()),
                     "sha256": _sha256(scenario_path)},
        "t_f_s": nominal.t_f_s,
        "ignition_true_anomaly_deg": math.degrees(nominal.f0),
        "nominal_method": nominal.method,
        "residuals": dict(zip(RESIDUAL_NAMES, (float(v) for v in nominal.residuals))),
        "max_cond_equilibrated": float(np.max(table.cond_equilibrated)),
        "grid": {"gain_nodes": int(table.tau.size), "bundle_nodes": int(table.tau.size) + 1,
                 "capacity_OGK_NOG_MAX_GRID": grid.capacity, "uniform_step_s": grid.step_s,
                 "max_relative_spacing": grid.relative_spacing,
                 "end_time_to_go_s": grid.end_time_to_go_s,
                 "interpolation_error_costate": err_lam, "interpolation_error_dt_f": err_dtf,
                 "interpolation_error_bound": INTERPOLATION_ERROR_BOUND},
        "settings": settings.as_manifest(),
        "files": files,
    }
    if precision != "double":
        manifest["precision"] = precision
    (out / MANIFEST).write_text(json.dumps(manifest, indent=2) + "\n")
    return manifest


def check_burn_bounds(scn: Any, t_f_star_s: float) -> None:
    """The settings the kernel bounds by the burn itself (ogk_nog_init: |dt_f| clip <= t_f*/2,
    sampling interval <= t_f*), checked against the nominal's t_f* so that a copied setting is one
    line naming its key here, not OGK_E_CONFIG when the campaign starts (issue 19)."""
    eg = scn.end_game
    if eg.dtf_max_s is not None and not eg.dtf_max_s <= 0.5 * t_f_star_s:
        raise OgkInputError(f"must be <= t_f*/2 = {0.5 * t_f_star_s:.4g} s for this burn "
                            f"(t_f* = {t_f_star_s:.4g} s), got {eg.dtf_max_s:g}",
                            path=scn.path, key="guidance.end_game.dtf_max_s")
    if not scn.sample_interval_s <= t_f_star_s:
        raise OgkInputError(f"must be <= t_f* = {t_f_star_s:.4g} s for this burn, got "
                            f"{scn.sample_interval_s:g}", path=scn.path,
                            key="guidance.sample_interval_s")


def check_tables(out_dir: str | Path, scenario_path: str | Path = DEFAULT_SCENARIO_PATH,
                 reference_tf_s: float | None = None, tf_tolerance_s: float = 1e-6,
                 precision: str = "double") -> dict:
    """The manifest of `out_dir` if its tables belong to `scenario_path` and are intact.

    TableError (one line) when there is no ogk manifest, when the manifest names another scenario
    (SHA-256 mismatch), when a file is missing or its SHA-256 or CRC does not match (corrupted),
    or when t_f* differs from `reference_tf_s` by more than `tf_tolerance_s`, or when the tables
    are not of `precision` (F64 for "double", F32 for "single").
    """
    out, scenario_path = Path(out_dir), Path(scenario_path)
    manifest_path = out / MANIFEST
    if not manifest_path.is_file():
        raise TableError(f"no {MANIFEST}: not a table directory made by {MADE_BY!r}", path=out)
    try:
        manifest = json.loads(manifest_path.read_text())
    except ValueError as exc:
        raise TableError(f"unreadable ({exc})", path=manifest_path) from None
    if not isinstance(manifest, dict) or manifest.get("made_by") != MADE_BY:
        raise TableError(f"not made by {MADE_BY!r}", path=manifest_path)
    want = _sha256(scenario_path)
    scn_rec = manifest.get("scenario") or {}
    if scn_rec.get("sha256") != want:
        raise TableError(
            f"made from scenario {scn_rec.get('name')!r} ({scn_rec.get('path')}, SHA-256 "
            f"{str(scn_rec.get('sha256'))[:12]}), not from {scenario_path} (SHA-256 {want[:12]}): "
            f"regenerate with `ogk tables` or use {default_table_dir(scenario_path, precision)}", path=out)
    if _manifest_precision(manifest) != precision:
        raise TableError(f"{_manifest_precision(manifest)}-precision tables, not {precision}: use "
                         f"{default_table_dir(scenario_path, precision)}", path=out)
    for entry in manifest.get("files", []):
        path = out / entry["file"]
        if not path.is_file():
            raise TableError(f"missing {entry['file']} listed in {MANIFEST}", path=out)
        if _sha256(path) != entry["sha256"]:
            raise TableError("corrupted: SHA-256 differs from the manifest", path=path)
        try:
            tablefile.decode_table(path.read_bytes(), int(entry["kind"], 16), precision)
        except tablefile.TableFormatError as exc:
            raise TableError(f"corrupted: {exc}", path=path) from None
    if not any(e.get("file") == BUNDLE_FILE for e in manifest.get("files", [])):
        raise TableError(f"no {BUNDLE_FILE} in {MANIFEST}", path=out)
    if reference_tf_s is not None and not abs(manifest["t_f_s"] - reference_tf_s) <= tf_tolerance_s:
        raise TableError(f"t_f* = {manifest['t_f_s']:.9g} s in {MANIFEST} disagrees with the "
                         f"reference {reference_tf_s:.9g} s", path=out)
    return manifest


def ensure_nog_tables(scenario_path: str | Path = DEFAULT_SCENARIO_PATH,
                      table_dir: str | Path | None = None, precision: str = "double") -> Path:
    """The checked table directory of `scenario_path` (the flight bundle is BUNDLE_FILE in it).

    table_dir None: the default directory (`default_table_dir`), generated when it has no tables,
    otherwise checked. A given table_dir is only checked (`check_tables`), except that it is
    generated when it does not exist (or is empty). Raises TableError (one line) otherwise.
    `precision`: the element type the flying kernel reads ("single": F32 tables, in their own default
    directory, `default_table_dir`).
    """
    scenario_path = Path(scenario_path)
    out = default_table_dir(scenario_path, precision) if table_dir is None else Path(table_dir)
    with directory_lock(out):   # another process may be writing the same tables
        empty = not out.exists() or (out.is_dir() and not any(out.iterdir()))
        if empty or (table_dir is None and not (out / MANIFEST).exists()):
            write_nog_tables(out, scenario_path, precision=precision)
        elif table_dir is None and _is_ogk_dir(out) and _generator(out) != GENERATOR:
            # the default directory is this tool's cache (keyed by the scenario's SHA-256): tables of
            # an older generator are remade there; a user's directory is only ever checked
            write_nog_tables(out, scenario_path, precision=precision)
        check_tables(out, scenario_path, precision=precision)
    return out


def _generator(out: Path) -> str | None:
    try:
        return json.loads((out / MANIFEST).read_text()).get("generator")
    except (ValueError, OSError):
        return None


def main(argv: list[str] | None = None) -> int:
    """CLI: solve the nominal, compute the gains, write the tables, print a summary."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out_dir", nargs="?", default=None,
                        help="output directory (default: build/tables/<name>-<sha12>)")
    parser.add_argument("--scenario", default=str(DEFAULT_SCENARIO_PATH))
    args = parser.parse_args(argv)
    out_dir = default_table_dir(args.scenario) if args.out_dir is None else Path(args.out_dir)
    scn = load_scenario(args.scenario)
    nominal = solve_nominal(scn)
    table = compute_gain_table(nominal, flight_grid(nominal).tau)
    manifest = write_nog_tables(out_dir, args.scenario, nominal=nominal, table=table)
    print(f"t_f* = {nominal.t_f_s:.6f} s, f0* = {math.degrees(nominal.f0):.6f} deg")
    for name, value in manifest["residuals"].items():
        print(f"  residual {name:22s} {value: .3e}")
    g = manifest["grid"]
    print(f"  grid: {g['gain_nodes']} gain nodes + tau = 1 (OGK_NOG_MAX_GRID = "
          f"{g['capacity_OGK_NOG_MAX_GRID']}), uniform step {g['uniform_step_s']:g} s, end "
          f"{g['end_time_to_go_s']:g} s to go; mid-node interpolation error "
          f"{g['interpolation_error_costate']:.3%} (costates), {g['interpolation_error_dt_f']:.3%} "
          f"(dt_f), bound {g['interpolation_error_bound']:.1%}")
    for key, rec in manifest["settings"].items():
        print(f"  {key}: {rec['source']} {rec['value']}")
    togo_s = (1.0 - table.tau) * nominal.t_f_s
    picks = sorted({int(np.argmin(np.abs(togo_s - t))) for t in
                    (105.8, 80.0, 53.0, 26.5, 10.8, 5.0, 2.0, 1.0, 0.5, 0.1)})
    cond_si = condition_numbers_si(nominal, table.tau[picks])
    gain_si = build_table_arrays(nominal, table)[2].data
    print("  time-to-go [s]  tau     cond(K) canonical  SI        equilibrated  min eig H_uu  "
          "dt_f/dv_t [s/(m/s)]")
    for i, c_si in zip(picks, cond_si):
        print(f"  {togo_s[i]:12.2f}  {table.tau[i]:.4f}  {table.cond_raw[i]:.3e}  {c_si:.3e}  "
              f"{table.cond_equilibrated[i]:10.3f}  {table.huu_min_eig[i]:.3e}  "
              f"{gain_si[i, dyn.N_X, dyn.VT]: .3e}")
    for entry in manifest["files"]:
        print(f"  wrote {out_dir / entry['file']} kind {entry['kind']} dims "
              f"{entry['dims']} grid {entry['grid_size']}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
