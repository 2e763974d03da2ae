"""`ogk tables MISSION`: ground tables of a mission -- binary table files (CRC) and generated C."""
from __future__ import annotations

import argparse
from pathlib import Path
from typing import Any

MISSIONS = ("leo-geo",)


def run_tables(args: argparse.Namespace) -> int:
    from ogk_host.cgen import write_c_table
    from ogk_host.orbit_injection.scenario import DEFAULT_SCENARIO_PATH
    from ogk_host.orbit_injection.tables import write_nog_tables

    scenario = Path(args.scenario) if args.scenario else DEFAULT_SCENARIO_PATH
    out = Path(args.out)
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
    print(f"  wrote {out / 'manifest.json'}")
    return 0


def register(sub: Any) -> None:
    p = sub.add_parser("tables", help="generate a mission's ground tables (binary + C source)")
    p.add_argument("mission", choices=MISSIONS)
    p.add_argument("--out", default="build/tables/leo_geo", help="output directory")
    p.add_argument("--scenario", default=None, help="scenario file (default: scenarios/leo_geo.toml)")
    p.set_defaults(func=run_tables)
