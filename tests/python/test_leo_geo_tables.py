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
#include "ogk_leo_geo_nog_bundle.h"
static ogk_nog_table_t table;
static uint8_t copy[sizeof ogk_leo_geo_nog_bundle];
int main(void)
{
    size_t k, j;
    ogk_status st = ogk_nog_table_load(&table, ogk_leo_geo_nog_bundle, ogk_leo_geo_nog_bundle_len);
    printf("status %d n_grid %zu tf %.17g\n", (int)st, table.n_grid, table.t_f_star_s);
    for (k = 0; k < table.n_grid; k += 25) {
        for (j = 0; j < OGK_NOG_ENTRY_LEN; j += 11) {
            printf("entry %zu %zu %.17g\n", k, j, table.entry[k * OGK_NOG_ENTRY_LEN + j]);
        }
    }
    memcpy(copy, ogk_leo_geo_nog_bundle, sizeof copy);
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


def test_generated_c_table_loads_with_ground_values(bundle, tmp_path):
    image_path = tmp_path / "bundle.ogkt"
    tablefile.write_table(image_path, bundle.kind, bundle.grid, bundle.data)
    c_path, h_path = write_c_table(image_path.read_bytes(), "ogk_leo_geo_nog_bundle", tmp_path,
                                   DEFAULT_SCENARIO_PATH)
    assert "SHA-256" in c_path.read_text()[:400]
    probe = tmp_path / "probe.c"
    probe.write_text(PROBE_MAIN)
    exe = tmp_path / "probe"
    kernel = sorted(str(p) for p in (ROOT / "kernel" / "src").glob("*.c"))
    subprocess.run([shutil.which("gcc") or "gcc", "-std=c99", "-O1", "-I", str(ROOT / "kernel/include"),
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


def test_bundle_through_bindings_flies_nominal(bundle, tmp_path):
    from ogk.bindings._ffi import ffi, lib
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
