"""The SIL in single precision (issue 35 item 3): the float kernel's extension (`_ogk_cffi_single`, chosen by
OGK_PRECISION=single before the bindings are imported) loads and refuses what is not its own, the wrappers
give the same answers as the double kernel's within float's resolution, and a campaign flown with
`ogk mc ... --precision single` records its precision.

A process loads one precision (ogk_bindings._ffi): this one flies double, so each single-precision check
runs in a child process (`_single`) and hands its numbers back as JSON."""
from __future__ import annotations

import json
import os
import subprocess
import sys
import textwrap
from pathlib import Path
from typing import Any

import numpy as np
import pyarrow.parquet as pq
import pytest

from ogk_bindings import _ffi, kernel, models
from ogk_bindings._ffi import lib

ROOT = Path(__file__).resolve().parents[2]
OGK = Path(sys.executable).with_name("ogk")
#: float's machine epsilon (FLT_EPSILON), the unit of every tolerance below
FLT_EPS = float(np.finfo(np.float32).eps)
ALARM_S = 300

pytestmark = pytest.mark.req("OGK-CORE-028")


def _env(precision: str | None) -> dict[str, str]:
    env = dict(os.environ)
    env.pop("OGK_PRECISION", None)
    if precision is not None:
        env["OGK_PRECISION"] = precision
    return env


def _single(code: str, precision: str | None = "single", check: bool = True) -> subprocess.CompletedProcess:
    """`code` run by a fresh interpreter with OGK_PRECISION=`precision`."""
    return subprocess.run([sys.executable, "-c", textwrap.dedent(code)], capture_output=True, text=True,
                          env=_env(precision), cwd=ROOT, check=check, timeout=120)


def _json(code: str) -> Any:
    return json.loads(_single(code).stdout.strip().splitlines()[-1])


# ----------------------------------------------------------------- the extension and its checks
def test_this_process_is_double() -> None:
    assert _ffi.PRECISION == "double" and _ffi.REAL_BYTES == 8
    assert _ffi.ffi.typeof("ogk_real_t") is _ffi.ffi.typeof("double")


def test_the_single_extension_loads_with_float_everywhere() -> None:
    got = _json("""
        import json
        from ogk_bindings import _ffi, _real
        from ogk_bindings._ffi import ffi, lib
        answer = ffi.new("uint32_t *")
        assert lib.ogk_real_bytes(answer) == lib.OGK_OK
        print(json.dumps({"precision": _ffi.PRECISION,
                          "real_bytes": _ffi.REAL_BYTES, "answer": int(answer[0]),
                          "sizeof": ffi.sizeof("ogk_real_t"), "is_float": ffi.typeof("ogk_real_t") is ffi.typeof("float"),
                          "single": int(lib.OGK_REAL_SINGLE), "table_real": int(lib.OGK_TABLE_REAL),
                          "f32": int(lib.OGK_TABLE_F32), "eps": float(lib.OGK_REAL_EPSILON),
                          "dtype": __import__("numpy").dtype(_real.REAL).name,
                          "module_file": _ffi._module.__file__}))
    """)
    assert got["precision"] == "single" and got["real_bytes"] == got["answer"] == got["sizeof"] == 4
    assert got["is_float"] and got["single"] == 1 and got["table_real"] == got["f32"]
    assert got["eps"] == FLT_EPS and got["dtype"] == "float32"
    assert "_ogk_cffi_single" in got["module_file"]


def test_the_single_bindings_refuse_a_double_library() -> None:
    """A single-precision process handed a library that answers 8 bytes (a double kernel) refuses it."""
    out = _single("""
        from ogk_bindings import _ffi
        class Double:
            def ogk_real_bytes(self, out):
                out[0] = 8
                return 0
        _ffi.lib = Double()
        try:
            _ffi.check_real_type()
        except ImportError as exc:
            print("refused:", exc)
    """).stdout
    assert "refused:" in out and "OGK_REAL_SINGLE=1" in out and "4-byte" in out


def test_an_unknown_precision_is_refused_at_import() -> None:
    res = _single("import ogk_bindings._ffi", precision="half", check=False)
    assert res.returncode != 0 and "OGK_PRECISION='half'" in res.stderr


def test_the_float_kernel_reads_f32_tables_and_refuses_f64() -> None:
    """The kernel's own check (OGK_E_TABLE_TYPE) through the single bindings; F32 is read back exactly."""
    got = _json("""
        import json
        import numpy as np
        from ogk_host.tablefile import encode_table
        from ogk_bindings.kernel import KernelError, TableSpec, table_load
        grid = np.linspace(0.0, 1.0, 5)
        data = np.sin(grid)[:, None] * np.array([1.0, 3.0])
        spec = TableSpec(kind=0x54455354, dims=(2,))
        t = table_load(encode_table(0x54455354, grid, data, precision="single"), spec)
        try:
            table_load(encode_table(0x54455354, grid, data, precision="double"), spec)
            refused = ""
        except KernelError as exc:
            refused = exc.name
        print(json.dumps({"grid": t.grid.tolist(), "data": t.data.tolist(), "dtype": str(t.data.dtype),
                          "refused": refused}))
    """)
    grid = np.linspace(0.0, 1.0, 5)
    data = np.sin(grid)[:, None] * np.array([1.0, 3.0])
    assert got["refused"] == "OGK_E_TABLE_TYPE" and got["dtype"] == "float64"
    np.testing.assert_array_equal(got["grid"], grid.astype(np.float32).astype(np.float64))
    np.testing.assert_array_equal(got["data"], data.astype(np.float32).astype(np.float64))


def test_the_double_kernel_refuses_f32_tables() -> None:
    from ogk_host.tablefile import encode_table
    spec = kernel.TableSpec(kind=0x54455354, dims=(1,))
    with pytest.raises(kernel.KernelError, match="OGK_E_TABLE_TYPE"):
        kernel.table_load(encode_table(0x54455354, [0.0, 1.0], [[1.0], [2.0]], precision="single"), spec)


def test_an_output_buffer_of_another_dtype_is_refused() -> None:
    from ogk_bindings import _real
    with pytest.raises(TypeError, match="float64"):
        _real.real_out(np.empty(3, dtype=np.float32))
    assert _real.to_f64(_real.real_array(2)).dtype == np.float64


# ----------------------------------------------------------------- wrappers: single against double
_ROUND_TRIP = """
    import json
    import numpy as np
    from ogk_bindings import _ffi, kernel, models
    rng = np.random.default_rng(20261207)
    a = rng.normal(size=(6, 6)) + 6.0 * np.eye(6)
    b = rng.normal(size=6)
    grid = np.linspace(0.0, 2.0, 9)
    values = np.stack([np.sin(grid), np.cos(grid)], axis=1)
    taus = np.linspace(0.05, 1.95, 7)
    osc = kernel.rk4_propagate(models.oscillator(2.0), [1.0, 0.0], 0.0, 2.0, 0.01, s_tol=1e-5, t_tol=1e-5)
    out = {
        "mat_vec": kernel.mat_vec(a, b), "mat_mul": kernel.mat_mul(a, a.T),
        "lu_solve": kernel.lu_solve(a, b), "lu_inverse": kernel.lu_inverse(a),
        "cholesky_solve": kernel.cholesky_solve(a @ a.T, b),
        "lstsq": kernel.lstsq(a[:, :4], b), "minnorm": kernel.minnorm(a[:4], b[:4]),
        "interp_linear": kernel.interp_linear(grid, values, taus),
        "interp_pchip": kernel.interp_pchip(grid, values, taus),
        "rk4_xf": osc.xf, "rk4_switch_t": [s.t for s in osc.switches],
        "cond": float(np.linalg.cond(a)),
    }
    out = {k: (np.asarray(v).tolist() if not isinstance(v, float) else v) for k, v in out.items()}
    out["dtypes"] = sorted({str(np.asarray(v).dtype) for v in (kernel.mat_vec(a, b), osc.xf)})
    out["precision"] = _ffi.PRECISION
    print(json.dumps(out))
"""


def test_wrappers_in_single_agree_with_double_within_float_resolution() -> None:
    """The same calls in a single-precision process and in this (double) one: the float answers are the
    double ones to a few FLT_EPSILON, scaled by each problem's size and conditioning; the Python side is
    float64 in both."""
    single = _json(_ROUND_TRIP)
    ns: dict[str, Any] = {}
    import contextlib
    import io
    buf = io.StringIO()
    with contextlib.redirect_stdout(buf):
        exec(textwrap.dedent(_ROUND_TRIP), ns)  # noqa: S102 - the same code, in this double process
    double = json.loads(buf.getvalue().strip().splitlines()[-1])
    assert single["precision"] == "single" and double["precision"] == "double"
    assert single["dtypes"] == double["dtypes"] == ["float64"]
    cond = double["cond"]
    n = 6
    # (what, relative tolerance against max |double value|): products n eps; solves n eps cond(A)
    # (cond(A A^T) = cond^2 for Cholesky); interpolation a few eps of the values
    bounds = {"mat_vec": 4 * n * FLT_EPS, "mat_mul": 4 * n * FLT_EPS,
              "lu_solve": 4 * n * FLT_EPS * cond, "lu_inverse": 4 * n * FLT_EPS * cond,
              "cholesky_solve": 4 * n * FLT_EPS * cond ** 2, "lstsq": 4 * n * FLT_EPS * cond ** 2,
              "minnorm": 4 * n * FLT_EPS * cond ** 2, "interp_linear": 8 * FLT_EPS,
              "interp_pchip": 16 * FLT_EPS,
              # 200 RK4 steps of an oscillator: round-off grows with the step count
              "rk4_xf": 200 * 4 * FLT_EPS, "rk4_switch_t": 1e-4}
    for key, rel in bounds.items():
        d, s = np.asarray(double[key]), np.asarray(single[key])
        assert d.shape == s.shape, key
        scale = max(float(np.max(np.abs(d))), 1.0) if d.size else 1.0
        err = float(np.max(np.abs(s - d))) if d.size else 0.0
        assert err <= rel * scale, f"{key}: |single - double| = {err:.3e} > {rel * scale:.3e}"
        # and float is not double in disguise: the answers differ (beyond double's resolution)
        if key in ("lu_solve", "mat_mul"):
            assert err > 1e-12 * scale, key


# ----------------------------------------------------------------- a campaign in single precision
def _probe_scenario(tmp_path: Path) -> Path:
    """A mission no shipped file names: the Apophis low-thrust transfer (MPSP), renamed."""
    text = (ROOT / "scenarios" / "apophis_cubesat.toml").read_text()
    assert text.count('name = "apophis_cubesat"') == 1
    path = tmp_path / "precision_probe_transfer.toml"
    path.write_text(text.replace('name = "apophis_cubesat"', 'name = "precision_probe_transfer"'))
    return path


@pytest.mark.usefixtures("alarm")
def test_a_campaign_in_single_records_its_precision(tmp_path: Path) -> None:
    scenario = _probe_scenario(tmp_path)
    out = tmp_path / "probe.json"
    res = subprocess.run([str(OGK), "mc", str(scenario), "--runs", "2", "--seed", "3", "--precision", "single",
                          "--json", str(out)], capture_output=True, text=True, env=_env(None), cwd=tmp_path,
                         timeout=240)
    assert "precision: single" in res.stdout
    doc = json.loads(out.read_text())
    assert doc["precision"] == "single" and doc["options"]["precision"] == "single"
    assert doc["mission"] == "precision_probe_transfer" and doc["runs"] == 2
    # a real outcome of the float kernel's MPSP: both dispersed transfers converge within the scenario's
    # acceptance (final position and velocity errors), so the campaign passes (exit 0)
    assert res.returncode == 0, res.stdout + res.stderr
    assert doc["failures"] == 0 and doc["acceptance"]["converged"] is True
    dr = doc["quantities"]["dr_f_km"]
    assert dr["n"] == 2 and 0.0 < dr["worst"]["value"] <= doc["acceptance"]["dr_f_km"]
    assert 0.0 < doc["quantities"]["final_mass_kg"]["mean"]
    key = json.loads(Path(str(out) + ".runs.jsonl").read_text().splitlines()[0])["key"]
    assert key["options"]["precision"] == "single"   # the run log's key: never resumed by a double campaign
    # the double twin on the same draws (ogk.sil.precision_twin): its figures are those of the double
    # campaign of the same seed flown on its own, and of the single campaign's own records
    twin = doc["precision_vs_double"]
    assert twin["runs_compared"] == 2 and twin["failures_differ"] == []
    ref = tmp_path / "double.json"
    res_d = subprocess.run([str(OGK), "mc", str(scenario), "--runs", "2", "--seed", "3", "--json", str(ref)],
                           capture_output=True, text=True, env=_env(None), cwd=tmp_path, timeout=240)
    assert res_d.returncode == 0, res_d.stdout + res_d.stderr
    single_rows = pq.read_table(out.with_suffix(".parquet")).to_pylist()
    double_rows = pq.read_table(ref.with_suffix(".parquet")).to_pylist()
    for name in ("dr_f_km", "final_mass_kg"):
        diffs = [(abs(s[name] - d[name]), s["run_id"], s[name], d[name]) for s, d in zip(single_rows, double_rows)]
        worst = max(diffs)
        q = twin["quantities"][name]
        assert (q["max_abs_diff"], q["run_id"], q["single"], q["double"]) == worst, name
        assert q["max_abs_diff"] > 0.0, name       # float is not double in disguise
    assert "Single against double on the same draws (2 runs" in res.stdout
    # `ogk replay` flies a single campaign's run on the float kernel (the envelope's precision), bit-exact
    rep = subprocess.run([str(OGK), "replay", str(out), "1"], capture_output=True, text=True, env=_env(None),
                         cwd=tmp_path, timeout=240)
    assert rep.returncode == 0 and "bit-exact" in rep.stdout, rep.stdout + rep.stderr


def test_the_command_line_precision_wins_over_the_environment(tmp_path: Path) -> None:
    """`--precision double` in an environment that says single: the option is read before the bindings load,
    so the campaign flies double, and its options are a double campaign's (no "precision" key)."""
    out = tmp_path / "x.json"
    res = subprocess.run([str(OGK), "mc", str(_probe_scenario(tmp_path)), "--runs", "1", "--precision", "double",
                          "--json", str(out)], capture_output=True, text=True, env=_env("single"), cwd=tmp_path,
                         timeout=120)
    assert res.returncode == 0, res.stdout + res.stderr
    doc = json.loads(out.read_text())
    assert doc["precision"] == "double" and "precision" not in doc["options"]
    assert "precision:" not in res.stdout


def test_a_process_of_one_precision_refuses_the_other(monkeypatch: pytest.MonkeyPatch) -> None:
    """In a process whose bindings are loaded (this one: double), single cannot be selected any more."""
    from ogk.sil import precision
    monkeypatch.delenv("OGK_PRECISION", raising=False)   # select() sets it: restored after the test
    from ogk_bindings.errors import OgkInputError
    assert precision.select("double") == "double"
    with pytest.raises(OgkInputError, match="already loaded the double-precision"):
        precision.select("single")
    with pytest.raises(OgkInputError, match="flies the double-precision kernel"):
        precision.check("single")
    with pytest.raises(OgkInputError, match="expected one of"):
        precision.select("half")


def test_make_ffi_and_setup_py_build_both_precisions() -> None:
    """The wheel's extensions: the kernel's and each family's, in both precisions (setup.py's cffi_modules)."""
    import importlib.util
    spec = importlib.util.spec_from_file_location("build_csrc", ROOT / "harness" / "ogk" / "missions" / "build_csrc.py")
    assert spec is not None and spec.loader is not None
    build_csrc = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(build_csrc)
    specs = build_csrc.cffi_module_specs()
    assert "harness/ogk/missions/build_csrc.py:family_orbit_injection_single" in specs
    assert "harness/ogk/missions/build_csrc.py:family_orbit_injection" in specs
    assert "bindings/build_ffi.py:setuptools_builder_single" in (ROOT / "setup.py").read_text()
    kffi = build_csrc.kernel_ffi
    assert kffi.module_name("single") == "ogk_bindings._ogk_cffi_single"
    assert "typedef float ogk_real_t;" in kffi.declarations(kffi.bound_headers(), precision="single")
    assert "typedef double ogk_real_t;" in kffi.declarations(kffi.bound_headers())
    assert kffi.compile_args("double") == kffi.COMPILE_ARGS   # the double build's flags as they were
    assert kffi.build_dir("single") != kffi.build_dir("double")


# ----------------------------------------------------------------- ground products of a float flight build
@pytest.mark.usefixtures("alarm")
def test_ogk_tables_single_writes_what_the_float_flight_build_compiles_and_loads(tmp_path: Path) -> None:
    """`ogk tables SCN --precision single` (a mission no shipped file names: the LEO-GEO injection renamed):
    F32 table files the float kernel loads (and the double kernel refuses), and C for a float kernel that
    compiles under the flight flags with -Wfloat-conversion (a bare double literal in a float field fails)."""
    text = (ROOT / "scenarios" / "leo_geo.toml").read_text()
    assert text.count('name = "leo_geo"') == 1
    scenario = tmp_path / "float_probe_injection.toml"
    scenario.write_text(text.replace('name = "leo_geo"', 'name = "float_probe_injection"'))
    out = tmp_path / "products"
    res = subprocess.run([str(OGK), "tables", str(scenario), "--precision", "single", "--out", str(out)],
                         capture_output=True, text=True, env=_env(None), cwd=tmp_path, timeout=240)
    assert res.returncode == 0, res.stdout + res.stderr
    assert json.loads((out / "manifest.json").read_text())["precision"] == "single"
    bundle = (out / "nog_bundle.ogkt").read_bytes()
    status = _single(f"""
        from pathlib import Path
        from ogk_bindings._ffi import ffi, lib
        data = Path({str(out / "nog_bundle.ogkt")!r}).read_bytes()
        table = ffi.new("ogk_nog_table_t *")
        print(int(lib.ogk_nog_table_load(table, ffi.from_buffer("uint8_t[]", data), len(data))))
    """).stdout.strip()
    assert status == "0"
    table = _ffi.ffi.new("ogk_nog_table_t *")
    assert lib.ogk_nog_table_load(table, _ffi.ffi.from_buffer("uint8_t[]", bundle), len(bundle)) == \
        lib.OGK_E_TABLE_TYPE
    config = out / "c" / "ogk_orbit_injection_flight_config.h"
    assert "OGK_R(" in config.read_text()
    tu = tmp_path / "uses_products.c"
    tu.write_text('#include "ogk_orbit_injection_flight_config.h"\n#include "ogk_nog_bundle.h"\n'
                  "int main(void) { return (int)(ogk_flight_nog_config.du_max_rad > 1.0f) + "
                  "(int)(ogk_nog_bundle_len == 0u); }\n")
    cc = subprocess.run(["gcc", "-std=c99", "-pedantic", "-Wall", "-Wextra", "-Werror", "-Wconversion",
                         "-Wdouble-promotion", "-Wfloat-conversion", "-DOGK_REAL_SINGLE=1",
                         f"-I{ROOT / 'kernel' / 'include'}", f"-I{out / 'c'}", "-c", str(tu), "-o",
                         str(tmp_path / "uses_products.o")], capture_output=True, text=True)
    assert cc.returncode == 0, cc.stderr
