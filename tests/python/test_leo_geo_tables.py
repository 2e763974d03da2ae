"""The flight tables: the generated C source, compiled and loaded by the kernel's own loader in a
separate program, carries exactly the ground tool's numbers; the binary bundle read back through the
bindings gives the nominal thrust direction on the nominal state."""
from __future__ import annotations

import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest

from ogk_host.cgen import write_c_table
from ogk_host.orbit_injection.gains import compute_gain_table
from ogk_host.orbit_injection.scenario import DEFAULT_SCENARIO_PATH
from ogk_host.orbit_injection.tables import build_nog_bundle
from ogk_host import tablefile

ROOT = Path(__file__).resolve().parents[2]

PROBE_MAIN = r"""
#include <stdio.h>
#include <string.h>
#include "ogk/nog.h"
#include "ogk_nog_bundle.h"
static ogk_nog_table_t table;
static uint8_t copy[sizeof ogk_nog_bundle];
int main(void)
{
    size_t k, j;
    ogk_status st = ogk_nog_table_load(&table, ogk_nog_bundle, ogk_nog_bundle_len);
    printf("status %d n_grid %zu tf %.17g\n", (int)st, table.n_grid, table.t_f_star_s);
    for (k = 0; k < table.n_grid; k += 25) {
        for (j = 0; j < OGK_NOG_ENTRY_LEN; j += 11) {
            printf("entry %zu %zu %.17g\n", k, j, table.entry[k * OGK_NOG_ENTRY_LEN + j]);
        }
    }
    memcpy(copy, ogk_nog_bundle, sizeof copy);
    copy[sizeof copy / 2] ^= 0x40u;
    printf("corrupted %d\n", (int)ogk_nog_table_load(&table, copy, sizeof copy));
    return 0;
}
"""


@pytest.fixture(scope="module")
def bundle():
    from ogk_host.orbit_injection.nominal import solve_nominal
    from ogk_host.orbit_injection.scenario import load_scenario
    nominal = solve_nominal(load_scenario())
    return build_nog_bundle(nominal, compute_gain_table(nominal))


@pytest.mark.req("OGK-HAR-009", "OGK-NOG-001")
def test_generated_c_table_loads_with_ground_values(bundle, tmp_path):
    image_path = tmp_path / "bundle.ogkt"
    tablefile.write_table(image_path, bundle.kind, bundle.grid, bundle.data)
    c_path, h_path = write_c_table(image_path.read_bytes(), "ogk_nog_bundle", tmp_path,
                                   DEFAULT_SCENARIO_PATH)
    assert "SHA-256" in c_path.read_text()[:400]
    probe = tmp_path / "probe.c"
    probe.write_text(PROBE_MAIN)
    exe = tmp_path / "probe"
    kernel = sorted(str(p) for p in (ROOT / "kernel" / "src").rglob("*.c"))
    subprocess.run([shutil.which("gcc") or "gcc", "-std=c99", "-O1", "-I", str(ROOT / "kernel/include"),
                    "-I", str(ROOT / "kernel/src"),
                    "-I", str(tmp_path), str(probe), str(c_path), *kernel, "-lm", "-o", str(exe)],
                   check=True)
    lines = subprocess.run([str(exe)], check=True, capture_output=True, text=True).stdout.splitlines()
    head = lines[0].split()
    assert head[1] == "0" and int(head[3]) == bundle.grid.size
    assert float(head[5]) == pytest.approx(bundle.data[0, 7 + 6], rel=0, abs=0)   # t_f* = x*' of time
    checked = 0
    for line in lines[1:-1]:
        _, k, j, value = line.split()
        assert float(value) == bundle.data[int(k), int(j)]      # bit-exact through C and the loader
        checked += 1
    assert checked > 100
    assert lines[-1] == "corrupted 17"                            # OGK_E_TABLE_CRC


@pytest.mark.req("OGK-NOG-006", "OGK-NOG-014")
def test_bundle_through_bindings_flies_nominal(bundle, tmp_path):
    from ogk_bindings._ffi import ffi, lib
    image_path = tmp_path / "bundle.ogkt"
    tablefile.write_table(image_path, bundle.kind, bundle.grid, bundle.data)
    data = image_path.read_bytes()
    table = ffi.new("ogk_nog_table_t *")
    assert lib.ogk_nog_table_load(table, ffi.from_buffer("uint8_t[]", data), len(data)) == 0
    cfg = ffi.new("ogk_nog_config_t *", {"table": table, "sample_interval_s": 2.0,
                                         "dtf_max_s": 40.0, "du_max_rad": 1.0, "tau_freeze": 0.0})
    ctx = ffi.new("ogk_nog_t *")
    assert lib.ogk_nog_init(ctx, cfg) == 0
    x0 = bundle.data[0, :6]
    nav = ffi.new("ogk_nog_nav_t *", {"t_s": 0.0, "r_m": x0[0], "xi_rad": x0[1], "phi_rad": x0[2],
                                      "v_r_mps": x0[3], "v_t_mps": x0[4], "v_n_mps": x0[5]})
    out = ffi.new("ogk_nog_sample_t *")
    assert lib.ogk_nog_sample(ctx, nav, out) == 0
    assert abs(out.dt_f_s) < 1e-9
    lam = bundle.data[0, 14:21]
    alpha_ref = np.arctan2(-lam[3], -lam[4])          # eq. (27) from the ground costate
    assert out.alpha_rad == pytest.approx(alpha_ref, abs=1e-12)


# --- grid capacity and provenance (host/ogk_host/orbit_injection/{gains,tables}.py) -------------

@pytest.mark.req("OGK-HAR-008", "OGK-CORE-005")
def test_grid_fits_kernel_capacity_for_long_burns():
    """The capacity is the kernel's; every chosen grid keeps the 5 % spacing bound and fits it."""
    from ogk_bindings._ffi import lib
    from ogk_host.orbit_injection import gains
    cap = int(lib.OGK_NOG_MAX_GRID)
    assert gains.kernel_table_capacity() == (cap, int(lib.OGK_NOG_ENTRY_LEN))
    paper = gains.choose_tau_grid(105.80878, 2.0, 0.5)
    assert paper.step_s == 0.5 and paper.tau.size == 251          # today's grid, unchanged
    for t_f in (40.0, 105.8, 161.1, 222.5, 250.3, 600.0):
        choice = gains.choose_tau_grid(t_f, 2.0, 0.5)
        togo = t_f * (1.0 - np.append(choice.tau, 1.0 - 0.5 / t_f))
        assert choice.bundle_nodes <= cap
        assert np.all(-np.diff(togo) <= gains.MAX_RELATIVE_SPACING * togo[:-1] * (1 + 1e-12))


@pytest.mark.req("OGK-HAR-005")
def test_grid_capacity_error_names_the_setting():
    from ogk_bindings.errors import OgkInputError
    from ogk_host.orbit_injection import gains
    with pytest.raises(gains.GridCapacityError) as info:
        gains.choose_tau_grid(250.0, 2.0, 1e-9)
    assert isinstance(info.value, OgkInputError)
    assert "\n" not in str(info.value) and "freeze_time_to_go_s" in str(info.value)


@pytest.fixture(scope="module")
def table_dir(tmp_path_factory):
    from ogk_host.orbit_injection import tables
    out = tmp_path_factory.mktemp("tables") / "leo_geo"
    manifest = tables.write_nog_tables(out, DEFAULT_SCENARIO_PATH)
    return out, manifest


@pytest.mark.req("OGK-HAR-008")
def test_manifest_records_provenance(table_dir):
    import hashlib
    from ogk_host.orbit_injection import tables
    out, manifest = table_dir
    assert manifest["made_by"] == "ogk tables"
    assert manifest["scenario"]["name"] == "leo_geo"
    assert manifest["scenario"]["sha256"] == hashlib.sha256(DEFAULT_SCENARIO_PATH.read_bytes()).hexdigest()
    assert f"{manifest['t_f_s']:.5f}" == "105.80878"
    assert f"{manifest['ignition_true_anomaly_deg']:.5f}" == "179.87429"
    assert manifest["nominal_method"] == "continuation"
    grid = manifest["grid"]
    assert grid["bundle_nodes"] == 252 and grid["capacity_OGK_NOG_MAX_GRID"] == 256
    assert grid["interpolation_error_costate"] < grid["interpolation_error_bound"] == 0.005
    for entry in manifest["files"]:
        assert hashlib.sha256((out / entry["file"]).read_bytes()).hexdigest() == entry["sha256"]
    assert set(manifest["settings"]) == {"cpd_gains", "freeze_time_to_go_s", "braking_accels_rad_s2",
                                         "dtf_max_s", "fine_window_s", "terminal_window_s",
                                         "terminal_turn_accel_rad_s2"}
    assert manifest["settings"]["terminal_turn_accel_rad_s2"]["source"] == "derived"
    assert all(rec["source"] in ("scenario", "derived") for rec in manifest["settings"].values())
    assert tables.check_tables(out, DEFAULT_SCENARIO_PATH, reference_tf_s=manifest["t_f_s"]) == manifest
    name = tables.default_table_dir(DEFAULT_SCENARIO_PATH).name
    assert name == f"leo_geo-{manifest['scenario']['sha256'][:12]}"


def _copy(src, dst):
    shutil.copytree(src, dst)
    return dst


@pytest.mark.req("OGK-HAR-008")
def test_check_tables_rejects_other_scenario_corruption_and_tf(table_dir, tmp_path):
    from ogk_bindings.errors import TableError
    from ogk_host.orbit_injection import tables
    out, manifest = table_dir
    other = tmp_path / "other.toml"
    other.write_text(DEFAULT_SCENARIO_PATH.read_text() + "\n# edited\n")
    with pytest.raises(TableError, match="made from scenario 'leo_geo'"):
        tables.check_tables(out, other)
    with pytest.raises(TableError, match="disagrees with the reference"):
        tables.check_tables(out, DEFAULT_SCENARIO_PATH, reference_tf_s=manifest["t_f_s"] + 1e-3)
    bad = _copy(out, tmp_path / "flipped")
    gain = bad / "gain.ogkt"
    data = bytearray(gain.read_bytes())
    data[len(data) // 2] ^= 0x40
    gain.write_bytes(bytes(data))
    with pytest.raises(TableError, match="corrupted: SHA-256") as info:
        tables.check_tables(bad, DEFAULT_SCENARIO_PATH)
    assert "\n" not in str(info.value)
    # same flip with the manifest's SHA-256 "fixed": the file's own CRC still catches it
    import hashlib
    import json
    m = json.loads((bad / "manifest.json").read_text())
    for entry in m["files"]:
        if entry["file"] == gain.name:
            entry["sha256"] = hashlib.sha256(gain.read_bytes()).hexdigest()
    (bad / "manifest.json").write_text(json.dumps(m))
    with pytest.raises(TableError, match="corrupted: .*CRC|corrupted: .*crc"):
        tables.check_tables(bad, DEFAULT_SCENARIO_PATH)


@pytest.mark.req("OGK-HAR-008")
def test_writer_never_overwrites_a_foreign_directory(table_dir, tmp_path):
    from ogk_bindings.errors import TableError
    from ogk_host.orbit_injection import tables
    foreign = tmp_path / "mine"
    foreign.mkdir()
    (foreign / "notes.txt").write_text("not tables")
    with pytest.raises(TableError, match="refusing") as info:
        tables.write_nog_tables(foreign, DEFAULT_SCENARIO_PATH)
    assert "\n" not in str(info.value) and (foreign / "notes.txt").read_text() == "not tables"
    with pytest.raises(TableError):        # ensure with a user directory only checks
        tables.ensure_nog_tables(DEFAULT_SCENARIO_PATH, foreign)
    # a user directory of ours is checked, not regenerated
    ours = _copy(table_dir[0], tmp_path / "ours")
    stamp = (ours / "manifest.json").stat().st_mtime_ns
    assert tables.ensure_nog_tables(DEFAULT_SCENARIO_PATH, ours) == ours
    assert (ours / "manifest.json").stat().st_mtime_ns == stamp


@pytest.mark.req("OGK-HAR-008")
def test_ensure_generates_default_dir_then_checks(monkeypatch, tmp_path):
    from ogk_host import scenario_file
    from ogk_host.orbit_injection import tables
    monkeypatch.setattr(scenario_file, "TABLE_ROOT", tmp_path / "build" / "tables")
    out = tables.ensure_nog_tables(DEFAULT_SCENARIO_PATH)
    assert out == tables.default_table_dir(DEFAULT_SCENARIO_PATH) and out.parent == tmp_path / "build" / "tables"
    assert (out / tables.BUNDLE_FILE).is_file()
    stamp = (out / "manifest.json").stat().st_mtime_ns
    assert tables.ensure_nog_tables(DEFAULT_SCENARIO_PATH) == out      # second call: check only
    assert (out / "manifest.json").stat().st_mtime_ns == stamp
    # the default directory made by an older generator is remade (it is the tool's cache) ...
    import json
    doc = json.loads((out / "manifest.json").read_text())
    (out / "manifest.json").write_text(json.dumps({**doc, "generator": "older/1"}))
    assert tables.ensure_nog_tables(DEFAULT_SCENARIO_PATH) == out
    assert json.loads((out / "manifest.json").read_text())["generator"] == tables.GENERATOR
    # ... but a user's directory of an older generator is only checked, never rewritten
    (out / "manifest.json").write_text(json.dumps({**doc, "generator": "older/1"}))
    stamp = (out / "manifest.json").stat().st_mtime_ns
    assert tables.ensure_nog_tables(DEFAULT_SCENARIO_PATH, out) == out
    assert (out / "manifest.json").stat().st_mtime_ns == stamp
    # a user directory that does not exist is generated
    new = tmp_path / "new"
    assert tables.ensure_nog_tables(DEFAULT_SCENARIO_PATH, new) == new and (new / "manifest.json").is_file()
