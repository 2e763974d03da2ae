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

Command: `python -m ogk_host.orbit_injection.tables build/tables/leo_geo` writes the six .ogkt files, the
bundle leo_geo_nog_bundle.ogkt and a manifest.json (provenance: scenario SHA-256, generator, UTC date,
t_f*, f0*, residuals).
"""
from __future__ import annotations

import argparse
import dataclasses
import datetime as _dt
import hashlib
import json
import math
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from .. import tablefile
from . import dynamics as dyn
from .gains import GainTable, compute_gain_table, condition_numbers_si
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
NOG_BUNDLE_ENTRY_LEN = 133            #: OGK_NOG_ENTRY_LEN
NOG_BUNDLE_MAX_GRID = 256             #: OGK_NOG_MAX_GRID (default)
GENERATOR = "ogk_host.orbit_injection.tables/1"


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
    if data.shape[1] != NOG_BUNDLE_ENTRY_LEN or grid.size > NOG_BUNDLE_MAX_GRID:
        raise ValueError(f"bundle {data.shape} does not fit OGK_NOG_ENTRY_LEN / OGK_NOG_MAX_GRID")
    return PlannedTable("nog_bundle", KIND_NOG_BUNDLE, grid, data)


def write_nog_tables(out_dir: str | Path, nominal: Nominal | None = None,
                     table: GainTable | None = None,
                     scenario_path: str | Path = DEFAULT_SCENARIO_PATH) -> dict:
    """Writes <out_dir>/leo_geo_<name>.ogkt for every table and manifest.json; returns the manifest."""
    scenario_path = Path(scenario_path)
    if nominal is None:
        nominal = solve_nominal(load_scenario(scenario_path))
    if table is None:
        table = compute_gain_table(nominal)
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    files = []
    for planned in build_table_arrays(nominal, table) + [build_nog_bundle(nominal, table)]:
        path = out / f"leo_geo_{planned.name}.ogkt"
        size = tablefile.write_table(path, planned.kind, planned.grid, planned.data)
        files.append({"name": planned.name, "file": path.name, "kind": f"0x{planned.kind:08X}",
                      "dims": list(planned.dims), "grid_size": int(planned.grid.size),
                      "bytes": size, "sha256": hashlib.sha256(path.read_bytes()).hexdigest()})
    manifest = {
        "generator": GENERATOR,
        "created_utc": _dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds"),
        "scenario": str(scenario_path),
        "scenario_sha256": hashlib.sha256(scenario_path.read_bytes()).hexdigest(),
        "t_f_s": nominal.t_f_s,
        "ignition_true_anomaly_deg": math.degrees(nominal.f0),
        "residuals": dict(zip(RESIDUAL_NAMES, (float(v) for v in nominal.residuals))),
        "max_cond_equilibrated": float(np.max(table.cond_equilibrated)),
        "files": files,
    }
    (out / "manifest.json").write_text(json.dumps(manifest, indent=2) + "\n")
    return manifest


def main(argv: list[str] | None = None) -> int:
    """CLI: solve the nominal, compute the gains, write the tables, print a summary."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out_dir", nargs="?", default="build/tables/leo_geo")
    parser.add_argument("--scenario", default=str(DEFAULT_SCENARIO_PATH))
    args = parser.parse_args(argv)
    nominal = solve_nominal(load_scenario(args.scenario))
    table = compute_gain_table(nominal)
    manifest = write_nog_tables(args.out_dir, nominal, table, args.scenario)
    print(f"t_f* = {nominal.t_f_s:.6f} s, f0* = {math.degrees(nominal.f0):.6f} deg")
    for name, value in manifest["residuals"].items():
        print(f"  residual {name:22s} {value: .3e}")
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
        print(f"  wrote {Path(args.out_dir) / entry['file']} kind {entry['kind']} dims "
              f"{entry['dims']} grid {entry['grid_size']}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())


def ensure_nog_tables(out_dir: str | Path = "build/tables/leo_geo",
                      scenario_path: str | Path = DEFAULT_SCENARIO_PATH) -> Path:
    """Path of the flight bundle in `out_dir`, regenerated when missing or when its manifest was
    made from another scenario file or generator (the cache key is the scenario's SHA-256)."""
    out = Path(out_dir)
    scenario_path = Path(scenario_path)
    bundle = out / "leo_geo_nog_bundle.ogkt"
    manifest_path = out / "manifest.json"
    want = hashlib.sha256(scenario_path.read_bytes()).hexdigest()
    if bundle.exists() and manifest_path.exists():
        manifest = json.loads(manifest_path.read_text())
        if manifest.get("scenario_sha256") == want and manifest.get("generator") == GENERATOR:
            return bundle
    write_nog_tables(out, scenario_path=scenario_path)
    return bundle
