"""`ogk tables MISSION`: ground tables of a mission -- binary table files (CRC), generated C, and the
flight configuration header (the kernel configs the SIL flies, as const C99 initialisers).

  ogk tables leo-geo [--out build/tables/leo_geo]   NOG bundle (.ogkt + const C image), and
        c/ogk_leo_geo_flight_config.h: ogk_nog_config_t (table bound at init), ogk_cpd_config_t
        (the 50 Hz control period), plus c/ogk_leo_geo_sil_plant.h (scenario constants of the
        point-mass test plant of port/cortex-m7/flightapp, not flight data)
  ogk tables apophis [--out build/tables/apophis]   c/ogk_apophis_flight_config.h: ogk_mpsp_config_t
        and the nominal weights of `ogk mpsp apophis`

The configs are the cffi structs the harness itself flies (nog_guidance.nog_config,
attitude.cpd_config, low_thrust_transfer.cases.build_setup), handed to ogk_host.cgen.write_c_config,
so the header cannot drift from the SIL's configuration.
"""
from __future__ import annotations

import argparse
from pathlib import Path
from typing import Any

MISSIONS = ("leo-geo", "apophis")
DEFAULT_OUT = {"leo-geo": "build/tables/leo_geo", "apophis": "build/tables/apophis"}

#: Attitude-control rate of the flight configuration (the SIL's default, docs/sil.md).
CONTROL_RATE_HZ = 50.0


def leo_geo_configs(scenario: Path, bundle: Path) -> tuple[Any, Any, Any]:
    """(ffi, nog_config, cpd_config) as the SIL builds them, from the scenario and the bundle."""
    from ogk_host.orbit_injection.scenario import load_scenario

    from ogk.bindings._ffi import ffi
    from ogk.missions.orbit_injection.attitude import cpd_config
    from ogk.missions.orbit_injection.nog_guidance import load_table, nog_config

    scn = load_scenario(scenario)
    table = load_table(bundle)
    nog = nog_config(scn, table)
    cpd = ffi.new("ogk_cpd_config_t *")
    for key, value in cpd_config(scn, control_period_s=1.0 / CONTROL_RATE_HZ).items():
        setattr(cpd, key, value)
    return ffi, nog, cpd


def leo_geo_plant_defines(scenario: Path, t_f_star_s: float) -> dict[str, float]:
    """Scenario constants of the flight app's point-mass plant (eqs. 3-6, sec. 6 thrust)."""
    from ogk_host.orbit_injection.scenario import load_scenario
    scn = load_scenario(scenario)
    return {"OGK_LEO_GEO_MU_M3_S2": float(scn.mu_m3_s2),
            "OGK_LEO_GEO_N0_M_S2": float(scn.thrust.initial_accel_m_s2),
            "OGK_LEO_GEO_EXHAUST_VELOCITY_M_S": float(scn.thrust.exhaust_velocity_m_s),
            "OGK_LEO_GEO_TARGET_RADIUS_M": float(scn.target_radius_m),
            "OGK_LEO_GEO_T_F_STAR_S": float(t_f_star_s),
            "OGK_LEO_GEO_CONTROL_RATE_HZ": CONTROL_RATE_HZ}


def write_leo_geo_config(out: Path, scenario: Path, bundle: Path) -> list[Path]:
    from ogk_host.cgen import ConfigItem, write_c_config
    ffi, nog, cpd = leo_geo_configs(scenario, bundle)
    cfg = write_c_config(
        ffi, [ConfigItem("ogk_leo_geo_nog_config", nog,
                         "VTD-NOG (ogk/nog.h): set .table to the validated table, then ogk_nog_init"),
              ConfigItem("ogk_leo_geo_cpd_config", cpd,
                         f"CPD (ogk/cpd.h), ff_period_s = the {CONTROL_RATE_HZ:g} Hz control period")],
        out / "c" / "ogk_leo_geo_flight_config.h", scenario, includes=("ogk/nog.h", "ogk/cpd.h"),
        note=f"Table: {bundle.name}, t_f* = {float(nog.table.t_f_star_s):.17g} s.")
    plant = write_c_config(ffi, [], out / "c" / "ogk_leo_geo_sil_plant.h", scenario, includes=(),
                           defines=leo_geo_plant_defines(scenario, float(nog.table.t_f_star_s)),
                           note="Test-plant constants of the flight app (not flight data).")
    return [cfg, plant]


def write_apophis_config(out: Path, scenario: Path | None) -> list[Path]:
    import numpy as np

    from ogk_host.cgen import ConfigItem, write_c_config

    from ogk.bindings._ffi import ffi
    from ogk.missions.low_thrust_transfer.cases import build_setup, default_scenario_path

    setup = build_setup(scenario_path=scenario)
    cfg = setup.guidance.cfg.to_c()
    nw = setup.guidance.n_weights
    weights = ffi.new(f"double[{nw}]", [float(w) for w in np.asarray(setup.guidance.cfg.weights_nom)])
    path = write_c_config(
        ffi, [ConfigItem("ogk_apophis_mpsp_config", cfg,
                         f"MPSP (ogk/mpsp.h), basis {setup.basis}, order {setup.order}: ogk_mpsp_init"),
              ConfigItem("ogk_apophis_mpsp_weights_nom", weights,
                         "nominal Fourier weights epsilon_0 (eq. 50), = the config's weights_nom[0..n)")],
        out / "c" / "ogk_apophis_flight_config.h",
        scenario if scenario is not None else default_scenario_path(), includes=("ogk/mpsp.h",),
        defines={"OGK_APOPHIS_MPSP_N_WEIGHTS": nw, "OGK_APOPHIS_MPSP_N_SEG_NOM": setup.guidance.n_seg_nom,
                 "OGK_APOPHIS_MPSP_LAMBDA_M0_NOM": float(cfg.lambda_m0_nom)},
        note=f"Normalised units (LU = {setup.lu_km:.17g} km, MU = {setup.mu_kg:.17g} kg); "
             "n_seg_nom = 0: counted by ogk_mpsp_init.")
    return [path]


def run_tables(args: argparse.Namespace) -> int:
    out = Path(args.out if args.out else DEFAULT_OUT[args.mission])
    if args.mission == "apophis":
        for path in write_apophis_config(out, Path(args.scenario) if args.scenario else None):
            print(f"  wrote {path} (flight build: const MPSP configuration)")
        return 0

    from ogk_host.cgen import write_c_table
    from ogk_host.orbit_injection.scenario import DEFAULT_SCENARIO_PATH
    from ogk_host.orbit_injection.tables import write_nog_tables

    scenario = Path(args.scenario) if args.scenario else DEFAULT_SCENARIO_PATH
    manifest = write_nog_tables(out, scenario_path=scenario)
    bundle = out / "leo_geo_nog_bundle.ogkt"
    c_path, h_path = write_c_table(bundle.read_bytes(), "ogk_leo_geo_nog_bundle", out / "c",
                                   scenario, note="Load with ogk_nog_table_load() (ogk/nog.h).")
    print(f"t_f* = {manifest['t_f_s']:.6f} s, f0* = {manifest['ignition_true_anomaly_deg']:.6f} deg")
    for name, value in manifest["residuals"].items():
        print(f"  residual {name:22s} {value: .3e}")
    for entry in manifest["files"]:
        print(f"  wrote {out / entry['file']}  kind {entry['kind']}  dims {entry['dims']}  "
              f"grid {entry['grid_size']}  {entry['bytes']} bytes")
    print(f"  wrote {c_path} and {h_path.name} (flight build: const table image)")
    for path in write_leo_geo_config(out, scenario, bundle):
        print(f"  wrote {path} (flight build: const configurations)")
    print(f"  wrote {out / 'manifest.json'}")
    return 0


def register(sub: Any) -> None:
    p = sub.add_parser("tables", help="generate a mission's ground tables and flight configuration "
                                      "header (binary + C source)")
    p.add_argument("mission", choices=MISSIONS)
    p.add_argument("--out", default=None,
                   help="output directory (default: build/tables/leo_geo or build/tables/apophis)")
    p.add_argument("--scenario", default=None,
                   help="scenario file (default: scenarios/leo_geo.toml or apophis_cubesat.toml)")
    p.set_defaults(func=run_tables)
