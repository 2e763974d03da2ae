"""Processor in the loop on the Cortex-M4F with the single-precision kernel (docs/guides/pil.md,
"Cortex-M4F"): the orbit-injection flight program (port/cortex-m7/pil/oi_pil.c over oi_flight.c and
the flightapp's ogk_flight.c) built on build/m4f/libogk.a (-DOGK_REAL_SINGLE=1) by
port/cortex-m4f/pil.mk and flown on QEMU mps2-an386, exactly as `ogk mc leo_geo --target m4f` flies it.

One run (about 10 s with the host campaign beside it):
- the campaign meets the scenario's acceptance on the float kernel, the envelope records the target
  and its precision, every entry point has its instruction counts and painted stack;
- host (double) vs target (single) is report only (target_summary: no double bound applies), every
  quantity's difference stated;
- the flown table image is binary32 (a float kernel refuses F64: OGK_E_TABLE_TYPE) and the flight
  program's init accepted it (the run flew);
- doubles only at the boundary: the flight software's objects (oi_flight.o, ogk_flight.o) call none
  of libgcc's double routines; the *_pil.c handlers and ogk_pil.c convert the frames' binary64.
- the painted stack of every entry point is at most the M4F's static bound (make stack-bound-m4f);
- `ogk run` of three rendezvous replans on the float kernel (the NMPC program, its floored tolerances).
The generator's float mode and the report-only summary are checked on hand-made inputs.
"""
from __future__ import annotations

import json
import os
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[2]
OGK = Path(sys.executable).parent / "ogk"
SEED = "20261205"
ENTRIES = ("ogk_nog_sample", "ogk_cutoff_step", "ogk_nog_thrust_cmd", "ogk_terminal_step_split",
           "ogk_cpd_step")
#: libgcc's double-precision routines (soft-float on the M4F: its FPU is single precision only)
#: in a single-precision process: the float kernel's NOG loader on a table image (hex on argv), its status
LOAD_IN_SINGLE = """
import sys
from ogk_bindings._ffi import PRECISION, ffi, lib
assert PRECISION == "single"
data = bytes.fromhex(sys.argv[1])
table = ffi.new("ogk_nog_table_t *")
print(int(lib.ogk_nog_table_load(table, ffi.from_buffer("uint8_t[]", data), len(data))))
"""
DOUBLE_CALLS = re.compile(r"^__aeabi_(d\w+|f2d|l2d|ul2d|i2d|ui2d)$")


@pytest.fixture(scope="module")
def campaign(tmp_path_factory: pytest.TempPathFactory) -> dict:
    d = tmp_path_factory.mktemp("pil_m4f")
    out = subprocess.run([str(OGK), "mc", "leo_geo", "--target", "m4f", "--runs", "1", "--seed",
                          SEED, "--json", str(d / "m4f.json")], capture_output=True, text=True,
                         timeout=600, cwd=ROOT)
    assert out.returncode == 0, out.stdout[-3000:] + out.stderr[-3000:]
    import pyarrow.parquet as pq
    doc = json.loads((d / "m4f.json").read_text())
    return {"stdout": out.stdout, "doc": doc, "records": pq.read_table(d / "m4f.parquet").to_pylist()}


def _program_dir(doc: dict) -> Path:
    """The build directory of the campaign's flight program (DIR/m4f)."""
    from ogk.sil.pil_build import PIL_BUILD
    sha = doc["products"]["flight_program"]
    hits = [p.parent for p in (PIL_BUILD / "orbit_injection").glob("*/m4f/oi-*.elf")
            if p.name == f"oi-{sha[:16]}.elf"]
    assert hits, sha
    return hits[0]


@pytest.mark.req("OGK-HAR-012")
def test_the_float_kernel_flies_the_scenario_and_the_envelope_says_so(campaign: dict) -> None:
    doc, recs = campaign["doc"], campaign["records"]
    assert doc["target"] == "m4f" and doc["options"]["target"] == "m4f"
    assert doc["failures"] == 0 and doc["runs"] == 1 and len(recs) == 1
    pil = doc["pil"]
    assert pil["target"] == "m4f" and pil["precision"] == "single"
    assert doc["precision"] == "single"     # the envelope names the precision of the kernel that flew
    for e in ENTRIES:
        w = pil["entry_points"][e]
        assert w["calls"] > 0 and w["insn_max"]["value"] > 0 and w["stack_bytes"]["value"] > 0, e
        assert not w["stack_window_exceeded"], e
        assert recs[0][f"pil.{e}.insn_max"] == w["insn_max"]["value"], e
    assert "On the target (m4f with the single-precision kernel)" in campaign["stdout"]


@pytest.mark.req("OGK-HAR-012")
def test_host_vs_the_single_precision_target_is_reported_not_bounded(campaign: dict) -> None:
    hv = campaign["doc"]["pil"]["host_vs_target"]
    assert hv["report_only"] and hv["within_bounds"] and hv["runs_compared"] == 1
    assert not hv["failures_differ"]
    q = hv["quantities"]
    assert set(q) == {"dr_f_m", "dphi_f_deg", "dvr_f_mps", "dvt_f_mps", "dvn_f_mps", "tf_s"}
    for key, v in q.items():
        assert v["bound"] is None and v["within"] is None, key
        assert v["max_abs_diff"] is not None and np.isfinite(v["max_abs_diff"]), key
    # a float kernel is not the double one: the flight differs (by far more than the M7's bounds)
    assert q["tf_s"]["max_abs_diff"] > 0.0
    assert "single-precision kernel" in hv["why"] and "report only" in campaign["stdout"]


@pytest.mark.req("OGK-HAR-012")
def test_the_flown_table_is_binary32_and_doubles_stay_at_the_boundary(campaign: dict) -> None:
    from ogk_host import tablefile
    prog = _program_dir(campaign["doc"])
    text = (prog / "c" / "ogk_nog_bundle.c").read_text()
    body = text[text.index("{", text.index("ogk_nog_bundle[")) + 1:text.index("};")]
    image = bytes(int(b, 16) for b in re.findall(r"0x([0-9A-F]{2})", body))
    table = tablefile.decode_table(image, precision="single")       # F32, CRCs valid
    assert table.elem_type == tablefile.element_type("single")
    config = (prog / "c" / "ogk_orbit_injection_flight_config.h").read_text()
    assert "OGK_R(" in config
    for name in ("oi_flight.o", "ogk_flight.o"):
        undef = subprocess.run(["arm-none-eabi-nm", "-u", str(prog / "obj" / name)], check=True,
                               capture_output=True, text=True).stdout.split()
        assert not [s for s in undef if DOUBLE_CALLS.match(s)], (name, undef)
    boundary = subprocess.run(["arm-none-eabi-nm", "-u", str(prog / "obj" / "ogk_pil.o")],
                              check=True, capture_output=True, text=True).stdout.split()
    assert {"__aeabi_d2f", "__aeabi_f2d"} <= set(boundary)
    attrs = subprocess.run(["arm-none-eabi-readelf", "-A", str(next(prog.glob("oi-*.elf")))],
                           check=True, capture_output=True, text=True).stdout
    assert "Tag_ABI_HardFP_use: SP only" in attrs and "VFPv4-D16" in attrs, attrs


@pytest.mark.req("OGK-HAR-012")
def test_the_painted_stack_is_within_the_m4f_static_bound(campaign: dict) -> None:
    """Each entry point's painted stack on the board is at most the M4F's static bound (`make
    stack-bound-m4f`: own frame plus the deepest path, newlib's float libm included)."""
    from pil_checks import locked_make
    out = locked_make("stack-bound-m4f", timeout=600)
    assert out.returncode == 0, out.stdout[-2000:] + out.stderr[-2000:]
    bound = json.loads((ROOT / "build" / "profile" / "stack_m4f.json").read_text())["entry_points"]
    for e in ENTRIES:
        painted = campaign["doc"]["pil"]["entry_points"][e]["stack_bytes"]["value"]
        assert 0 < painted <= bound[e]["bytes"], (e, painted, bound[e])


@pytest.mark.req("OGK-HAR-012", "OGK-NMPC-010")
def test_ogk_run_makes_the_nmpc_replans_on_the_float_kernel(tmp_path: Path) -> None:
    """`ogk run rendezvous_nep_min_time --max-replans 3 --target m4f`: the NMPC program's cold first
    solve converges on the float kernel with the tolerances floored for binary32 (the double law's
    1e-9 found no first plan), every replan made on the board."""
    from ogk.sil.pil_build import PIL_BUILD
    from ogk.sil.precision import NMPC_SINGLE_FLOORS as SINGLE_FLOORS
    out = subprocess.run([str(OGK), "run", "rendezvous_nep_min_time", "--max-replans", "3", "--target",
                          "m4f", "--json", str(tmp_path / "m4f.json")], capture_output=True,
                         text=True, timeout=600, cwd=ROOT)
    assert out.returncode == 1, out.stdout[-2000:] + out.stderr[-2000:]   # not arrived in 3 replans
    a = json.loads((tmp_path / "m4f.json").read_text())
    assert a["target"] == "m4f" and a["target_precision"] == "single"
    assert a["replans"] == 3 and a["failed_solves"] == 0
    assert a["pil.ogk_nmpc_solve.calls"] == 1 and a["pil.ogk_nmpc_replan.calls"] == 2
    assert a["pil.ogk_nmpc_solve.insn_max"] > a["pil.ogk_nmpc_command.insn_max"] > 0
    elf = [p for p in PIL_BUILD.glob("rendezvous/*/m4f/nmpc-*.elf")
           if p.name == f"nmpc-{a['flight_program'][:16]}.elf"]
    assert len(elf) == 1
    config = (elf[0].parent / "c" / "ogk_nmpc_flight_config.h").read_text()
    assert f".tol_feas = OGK_R({SINGLE_FLOORS['tol_feas']!r})," in config


@pytest.mark.req("OGK-HAR-012")
def test_the_generator_writes_reals_for_a_float_kernel() -> None:
    from ogk_host import cgen
    from ogk_bindings._ffi import ffi
    cfg = ffi.new("ogk_cpd_config_t *")
    cfg.tau_x = 0.1
    ctype = ffi.typeof(cfg).item
    assert ".tau_x = 0.10000000000000001," in cgen.c_initializer(ffi, ctype, cfg[0])
    with cgen.generated_precision("single"):
        assert cgen.current_precision() == "single"
        assert ".tau_x = OGK_R(0.10000000000000001)," in cgen.c_initializer(ffi, ctype, cfg[0])
    assert cgen.current_precision() == "double"
    with pytest.raises(ValueError):
        with cgen.generated_precision("half"):
            pass


@pytest.mark.req("OGK-HAR-012")
def test_the_single_precision_table_is_the_double_table_rounded_and_the_float_kernel_loads_it() -> None:
    """The M4F's table image: every value the nearest binary32 of the double table's, and the float
    kernel's loader (its time columns checked to 4 eps of t_f) accepts it."""
    from ogk_host import tablefile
    from ogk.missions.orbit_injection.family import single_precision_bundle
    tau = np.linspace(0.0, 1.0, 7)
    t_f = 812.3456789
    data = np.full((7, 133), 1.0)
    data[:, 13] = t_f + 1e-12 * np.arange(7)       # the double table's rows agree to 1e-9 of t_f
    data[:, 6] = t_f * tau
    blob = single_precision_bundle(tablefile.encode_table(0x4E4F4742, tau, data))   # OGK_NOG_TABLE_KIND
    t = tablefile.decode_table(blob, precision="single")
    assert np.array_equal(t.data, data.astype(np.float32).astype(np.float64))
    assert np.array_equal(t.grid, tau.astype(np.float32).astype(np.float64))
    r = subprocess.run([sys.executable, "-c", LOAD_IN_SINGLE, blob.hex()], capture_output=True, text=True,
                       env={**os.environ, "OGK_PRECISION": "single"}, timeout=60)
    assert r.returncode == 0 and r.stdout.strip() == "0", r.stdout + r.stderr


@pytest.mark.req("OGK-HAR-012")
def test_report_only_for_a_single_precision_target() -> None:
    from ogk.sil import pil, target_summary
    from ogk.sil.precision import TARGET_PRECISION
    assert TARGET_PRECISION["m4f"] == "single" and "m4f" in pil.TARGETS
    host = [{"run_id": 0, "x": 1.0, "failure": ""}]
    tgt = [{"run_id": 0, "x": 1.5, "failure": ""}]
    doc = target_summary.summary("m4f", tgt, host, {"x": 1e-9}, "why", 1.0, 1)
    hv = doc["host_vs_target"]
    assert doc["precision"] == "single" and hv["report_only"] and hv["within_bounds"]
    assert hv["quantities"]["x"] == {"max_abs_diff": 0.5, "run_id": 0, "bound": None, "within": None}
    m7 = target_summary.summary("m7", tgt, host, {"x": 1e-9}, "why", 1.0, 1)["host_vs_target"]
    assert not m7["within_bounds"] and "report_only" not in m7
    assert "reported" in target_summary.format_summary(doc)


@pytest.mark.req("OGK-HAR-012")
def test_the_m4f_runs_on_mps2_an386_in_system_emulation() -> None:
    from ogk.sil import pil_build, target_link
    cmd = target_link.qemu_command("m4f", Path("/x/oi.elf"))
    assert cmd[:3] == ["qemu-system-arm", "-M", "mps2-an386"] and cmd[-2:] == ["-kernel", "/x/oi.elf"]
    assert pil_build.MAKE_GOAL["m4f"] == ("pil-program-m4f", "m4f")
    assert pil_build.TARGET_PRECISION["m4f"] == "single" and pil_build.GEN_DIR["m4f"] == "m4f"
