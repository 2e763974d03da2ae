"""`ogk tables SCENARIO` of a low-thrust transfer (the family's `tables`): the scenario's ground
products into its provenance directory (default build/tables/<name>-<sha12>): the fuel-optimal
nominal (nominal_solution.json; from the shipped cache only when the physics is the same, else
solved), manifest.json (scenario path, SHA-256, physics SHA-256, the nominal's SHA-256), and the MPSP
flight configuration as a const C header."""
from __future__ import annotations

import argparse
from pathlib import Path

from ogk_host.scenario_file import ScenarioHeader, table_dir_for

from ogk.sil.outputs import check_output_dir


def add_tables_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("--out", default=None, metavar="DIR",
                   help="output directory (default: build/tables/<name>-<sha12> of the scenario)")


def write_ground_tables(header: ScenarioHeader, args: argparse.Namespace) -> int:
    """The scenario's ground products (module doc)."""
    from ogk_host.low_thrust_transfer.products import MANIFEST, record_file
    from ogk_host.low_thrust_transfer.scenario import load_scenario

    from .cases import build_setup
    from .flight_config import write_flight_config

    load_scenario(header.path)
    out = Path(args.out) if args.out else table_dir_for(header.path)
    check_output_dir(out, "--out")
    setup = build_setup(scenario_path=header.path, product_dir=out)
    nom = setup.nominal
    print(f"{header.name}: nominal final mass {nom.final_mass_kg:.4f} kg, {nom.thrust_arcs} thrust / "
          f"{nom.coast_arcs} coast arcs, |dr_f| = {nom.position_error_km:.2e} km, "
          f"|dv_f| = {nom.velocity_error_km_s:.2e} km/s ({nom.method})")
    print(f"  wrote {setup.nominal_path} (SHA-256 {setup.nominal_sha256[:12]})")
    for path in write_flight_config(out, header.path, setup):
        record_file(out, str(path.relative_to(out)), path)
        print(f"  wrote {path} (flight build: const MPSP configuration)")
    print(f"  wrote {out / MANIFEST}")
    return 0
