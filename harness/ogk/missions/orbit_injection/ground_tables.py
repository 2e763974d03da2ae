"""`ogk tables SCENARIO` of an orbit-injection scenario (the family's `tables`): the ground
nominal, the VTD-NOG gain tables with their manifest, the C table image and the flight
configuration header, each file named as it is written."""
from __future__ import annotations

import argparse
import math
import tempfile
from pathlib import Path

from ogk_host.dir_lock import directory_lock
from ogk_host.orbit_injection.scenario import load_scenario
from ogk_host.scenario_file import ScenarioHeader

from ogk.sil.outputs import check_output_dir
from ogk.sil.progress import Working


def add_tables_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("--out", default=None, metavar="DIR",
                   help="output directory (default: build/tables/<name>-<sha12> of the scenario); "
                        "a directory that ogk did not make is never written into")


def write_ground_tables(header: ScenarioHeader, args: argparse.Namespace) -> int:
    """The scenario's ground products into --out (default its provenance directory)."""
    from ogk_host.cgen import write_c_table
    from ogk_host.orbit_injection import tables as ground
    from ogk_host.orbit_injection.derive import TURN_ACCEL_KEY, resolve, warn_outside_envelope

    from .flight_config import write_flight_config
    from .terminal import shape_tilt_bound_rad

    scn = load_scenario(header.path)  # every bad key reported before the nominal is solved
    real = getattr(args, "precision", "double")   # of the flight build the products are for
    out = Path(args.out) if args.out else ground.default_table_dir(header.path, precision=real)
    check_output_dir(out, "--out")
    with directory_lock(out), Working(f"{header.name}: ground nominal and VTD-NOG gains"):
        manifest = ground.write_nog_tables(out, scenario_path=header.path, precision=real)
    bundle = out / ground.BUNDLE_FILE
    c_path, h_path = write_c_table(bundle.read_bytes(), "ogk_nog_bundle", out / "c",
                                   header.path, note="Validate with ogk_nog_table_view() or load "
                                                     "with ogk_nog_table_load() (ogk/nog.h).")
    print(f"{header.name}: t_f* = {manifest['t_f_s']:.6f} s, "
          f"f0* = {manifest['ignition_true_anomaly_deg']:.6f} deg")
    resolved = resolve(scn, manifest["t_f_s"])
    warn_outside_envelope(resolved, manifest["t_f_s"])
    for key, entry in manifest["settings"].items():
        if key.endswith("_window_s") or key == "dtf_max_s":
            print(f"  {key} = {entry['value']:.4g} s ({entry['source']})")
    turn = manifest["settings"].get(TURN_ACCEL_KEY)
    if turn is not None and resolved.end_game.terminal_window_s:
        tilt = shape_tilt_bound_rad(resolved)
        print(f"  {TURN_ACCEL_KEY} = {turn['value']:.4g} rad/s^2 ({turn['source']}): "
              + ("the shaped plans are not limited" if tilt is None else
                 f"shaped plans tilt at most {math.degrees(tilt):.3g} deg from v_go"))
    for name, value in manifest.get("residuals", {}).items():
        print(f"  residual {name:22s} {value: .3e}")
    for entry in manifest["files"]:
        print(f"  wrote {out / entry['file']}  kind {entry['kind']}  dims {entry['dims']}  "
              f"grid {entry['grid_size']}  {entry['bytes']} bytes")
    print(f"  wrote {c_path} and {h_path.name} (flight build: const table image)")
    with tempfile.TemporaryDirectory() as tmp:
        # the configurations are made by this process's (double) kernel from the table flown: an F32
        # table is read here as the F64 table of the same values (binary32 widens exactly)
        flown = bundle if real == "double" else _as_f64(bundle, Path(tmp) / bundle.name)
        for path in write_flight_config(out, resolved, header.path, flown):
            print(f"  wrote {path} (flight build: const configurations)")
    print(f"  wrote {out / 'manifest.json'}")
    return 0


def _as_f64(table: Path, dest: Path) -> Path:
    """The F32 bundle `table` written again as F64 at `dest`, for this process's double kernel: the same
    values, but for the time columns, which the double kernel checks to 1e-9 of t_f* (the float kernel
    to 4 eps): every row's x*' time is row 0's t_f*, its x* time t_f* tau, in double (each within an ulp
    of binary32 of the value the file holds)."""
    import numpy as np
    from ogk_bindings._ffi import lib
    from ogk_host import tablefile
    t = tablefile.decode_table(table.read_bytes(), precision="single")
    data = np.array(t.data, dtype=np.float64)
    x_time, xdot_time = int(lib.OGK_NOG_OFF_X) + 6, int(lib.OGK_NOG_OFF_XDOT) + 6   # nog.c's IDX_TIME
    data[:, xdot_time] = data[0, xdot_time]
    data[:, x_time] = data[0, xdot_time] * np.asarray(t.grid, dtype=np.float64)
    dest.write_bytes(tablefile.encode_table(t.kind, t.grid, data))
    return dest

