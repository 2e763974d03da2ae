"""Flight configuration headers (ogk_host.cgen.write_c_config, `ogk tables`): every field of the
generated const initialisers reads back in C bit-exactly as the cffi struct the harness filled
(writers: ogk.missions.{orbit_injection,low_thrust_transfer}.flight_config, `ogk tables SCENARIO`).

Each test writes a header, generates a small C99 program that includes it and prints every leaf
field by name (doubles as their 64-bit pattern, integers and enums as values, pointers as NULL or
not), compiles it with the host gcc and the kernel's strict flags, runs it, and compares with the
values read from the cffi struct in Python. The headers are also compiled for the Cortex-M7 with the
flight flags when arm-none-eabi-gcc is installed.
"""
from __future__ import annotations

import math
import shutil
import struct
import subprocess
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from ogk_bindings._ffi import ffi, lib
from ogk_host.cgen import ConfigItem, c_double, write_c_config

pytestmark = pytest.mark.req("OGK-HAR-009")

REPO = Path(__file__).resolve().parents[2]
STRICT = ["-std=c99", "-pedantic", "-Wall", "-Wextra", "-Werror", "-Wconversion",
          "-Wdouble-promotion", "-Wshadow"]
ARM_CPU = ["-mthumb", "-mcpu=cortex-m7", "-mfpu=fpv5-d16", "-mfloat-abi=hard"]
SCENARIO = REPO / "scenarios" / "leo_geo.toml"


def _leaves(ctype: Any, value: Any, path: str) -> list[tuple[str, Any, Any]]:
    """(C expression suffix, ctype, value) of every scalar in value, in declaration order."""
    if ctype.kind == "struct":
        out = []
        for name, field in ctype.fields:
            out += _leaves(field.type, getattr(value, name), f"{path}.{name}")
        return out
    if ctype.kind == "array":
        out = []
        for i in range(ctype.length):
            out += _leaves(ctype.item, value[i], f"{path}[{i}]")
        return out
    return [(path, ctype, value)]


def _expected(ctype: Any, value: Any) -> str:
    if ctype.kind == "pointer":
        return "null"   # pointers are emitted NULL, bound by the flight code at init
    if ctype.kind == "primitive" and ctype.cname in ("double", "float"):
        return f"{struct.unpack('<Q', struct.pack('<d', float(value)))[0]:016x}"
    return str(int(value))


def _printer(ctype: Any, expr: str) -> str:
    if ctype.kind == "pointer":
        return f'    printf("%s\\n", ({expr}) == NULL ? "null" : "set");\n'
    if ctype.kind == "primitive" and ctype.cname in ("double", "float"):
        return (f"    {{ uint64_t u; double d = (double)({expr}); memcpy(&u, &d, sizeof u);\n"
                f'      printf("%016llx\\n", (unsigned long long)u); }}\n')
    return f'    printf("%lld\\n", (long long)({expr}));\n'


def _roundtrip(tmp_path: Path, items: list[ConfigItem], includes: tuple[str, ...]) -> int:
    """Writes the header, prints every field from C, compares with cffi; returns the leaf count."""
    header = write_c_config(ffi, items, tmp_path / "flight_config.h", SCENARIO, includes)
    body, expected = [], []
    for item in items:
        ctype = ffi.typeof(item.cdata)
        value = item.cdata
        if ctype.kind == "pointer":
            ctype, value = ctype.item, item.cdata[0]
        for suffix, leaf_type, leaf in _leaves(ctype, value, ""):
            body.append(_printer(leaf_type, item.symbol + suffix))
            expected.append(f"{item.symbol}{suffix} {_expected(leaf_type, leaf)}")
    src = tmp_path / "roundtrip.c"
    src.write_text('#include <stdio.h>\n#include <string.h>\n#include "flight_config.h"\n\n'
                   "int main(void)\n{\n" + "".join(body) + "    return 0;\n}\n")
    exe = tmp_path / "roundtrip"
    cc = subprocess.run(["gcc", *STRICT, "-O0", f"-I{REPO / 'kernel/include'}", f"-I{tmp_path}",
                         str(src), "-o", str(exe)], capture_output=True, text=True)
    assert cc.returncode == 0, f"generated header does not compile (stale `make ffi`?):\n{cc.stderr}"
    got = subprocess.run([str(exe)], check=True, capture_output=True, text=True).stdout.split()
    names = [e.split()[0] for e in expected]
    assert [f"{n} {g}" for n, g in zip(names, got)] == expected
    assert len(got) == len(expected)
    if shutil.which("arm-none-eabi-gcc"):
        cc = subprocess.run(["arm-none-eabi-gcc", *STRICT, *ARM_CPU, "-O2",
                             f"-I{REPO / 'kernel/include'}", f"-I{tmp_path}", "-c", str(src),
                             "-o", str(tmp_path / "roundtrip_arm.o")], capture_output=True, text=True)
        assert cc.returncode == 0, f"does not compile for the Cortex-M7:\n{cc.stderr}"
    assert header.read_text().count("static const") == len(items)
    return len(expected)


@pytest.fixture(scope="module")
def bundle(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """The LEO-to-GEO NOG bundle: an existing `ogk tables leo-geo` output made from the current
    scenario, else generated once (about 15 s)."""
    import hashlib
    import json
    sha = hashlib.sha256(SCENARIO.read_bytes()).hexdigest()
    # not build/arm/flightapp/tables: make test's other lane writes it while these tests run
    for d in [REPO / "build" / "tables" / "leo_geo",
              *sorted((REPO / "build" / "tables").glob("leo_geo-*"))]:
        manifest = d / "manifest.json"
        found = sorted(d.glob("nog_bundle.ogkt"))
        if found and manifest.exists() and json.loads(manifest.read_text()).get(
                "scenario_sha256") == sha:
            return found[0]
    from ogk_host.orbit_injection.tables import write_nog_tables
    out = tmp_path_factory.mktemp("tables")
    write_nog_tables(out, scenario_path=SCENARIO)
    return sorted(out.glob("nog_bundle.ogkt"))[0]


def _filled(ctype_name: str, rng: np.random.Generator) -> Any:
    """A struct with every double field set to a random value of random magnitude."""
    c = ffi.new(f"{ctype_name} *")
    for suffix, leaf_type, _ in _leaves(ffi.typeof(ctype_name), c[0], ""):
        if leaf_type.kind == "primitive" and leaf_type.cname == "double":
            value = float(rng.standard_normal() * 10.0 ** rng.integers(-300, 300))
            exec(f"c[0]{suffix} = value", {"c": c, "value": value})
    return c


def test_doubles_round_trip_bit_exactly(tmp_path: Path, rng: np.random.Generator) -> None:
    specials = [0.0, -0.0, 1.0, -1.0, 0.1, 1.0 / 3.0, math.pi, 2.0 ** -1074, 2.0 ** -1022,
                2.2250738585072009e-308, 1.7976931348623157e308, -1.7976931348623157e308,
                1e23, 5e-324, 9007199254740993.0, 123456789012345680.0]
    bits = rng.integers(0, 2 ** 63, size=200, dtype=np.uint64) | (
        rng.integers(0, 2, size=200, dtype=np.uint64) << np.uint64(63))
    randoms = [v for v in bits.view(np.float64) if math.isfinite(v)]
    values = specials + randoms
    arr = ffi.new(f"double[{len(values)}]", values)
    assert _roundtrip(tmp_path, [ConfigItem("values", arr)], ()) == len(values)


def test_non_finite_values_are_refused() -> None:
    for bad in (math.nan, math.inf, -math.inf):
        with pytest.raises(ValueError):
            c_double(bad)


def test_every_field_of_the_kernel_configs(tmp_path: Path, rng: np.random.Generator) -> None:
    """Random values in every double of every config type (the generator walks the cffi type, so a
    new kernel field is covered without changing this test)."""
    items = [ConfigItem(f"cfg_{name}", _filled(f"ogk_{name}_config_t", rng))
             for name in ("nog", "cpd", "mpsp")]
    items[1].cdata.pointing = lib.OGK_CPD_POINTING_EULER
    items[2].cdata.fourier_order = 7
    items[2].cdata.max_newton = 4294967295
    n = _roundtrip(tmp_path, items, ("ogk/nog.h", "ogk/cpd.h", "ogk/mpsp.h"))
    assert n > 2 * 93


def _resolved(bundle: Path) -> Any:
    """The LEO-to-GEO scenario resolved for the bundle's t_f* (as `ogk tables` resolves it)."""
    from ogk_host.orbit_injection.derive import resolve
    from ogk_host.orbit_injection.scenario import load_scenario

    from ogk.missions.orbit_injection.nog_guidance import load_table
    return resolve(load_scenario(SCENARIO), float(load_table(bundle).t_f_star_s))  # type: ignore[attr-defined]


def _sil_configs(bundle: Path) -> Any:
    """(NogConfig, CpdConfig) as the SIL flies them (flight_config.flight_configs); the NOG config
    keeps its table alive."""
    from ogk.missions.orbit_injection.flight_config import flight_configs
    from ogk.missions.orbit_injection.nog_guidance import load_table
    return flight_configs(_resolved(bundle), load_table(bundle))


def test_nested_structs_arrays_and_pointers(tmp_path: Path, bundle: Path) -> None:
    """A whole initialised CPD context (nested config and output structs, an array, integers) and
    a NOG config with its table pointer set (emitted NULL, "bound at init")."""
    nog_cfg, cpd = _sil_configs(bundle)
    nog, cpd_cfg = nog_cfg.to_c(), cpd.to_c()
    ctx = ffi.new("ogk_cpd_t *")
    assert lib.ogk_cpd_init(ctx, cpd_cfg) == lib.OGK_OK
    ctx.dir_prev_a = [0.25, -0.5, 1.0 / 3.0]
    assert nog.table != ffi.NULL
    items = [ConfigItem("nog", nog), ConfigItem("cpd_cfg", cpd_cfg), ConfigItem("cpd_ctx", ctx)]
    _roundtrip(tmp_path, items, ("ogk/nog.h", "ogk/cpd.h"))
    text = (tmp_path / "flight_config.h").read_text()
    assert ".table = NULL /* bound at init */" in text
    assert ".pointing = OGK_CPD_POINTING_BODY" in text


def test_leo_geo_header_is_the_sil_configuration(tmp_path: Path, bundle: Path) -> None:
    """The values of `ogk tables leo-geo` are those the SIL flies: NOG end-game from the scenario,
    tau_freeze = freeze time-to-go / t_f*, CPD with the 50 Hz feed-forward period."""
    from ogk.missions.orbit_injection.flight_config import write_flight_config
    from ogk_host.orbit_injection.scenario import load_scenario

    from ogk.missions.orbit_injection import nog_guidance
    nog, cpd = _sil_configs(bundle)
    scn = load_scenario(SCENARIO)
    assert nog.sample_interval_s == scn.sample_interval_s
    freeze = (nog_guidance.freeze_time_to_go_s(scn) if hasattr(nog_guidance, "freeze_time_to_go_s")
              else scn.end_game.freeze_time_to_go_s)
    assert nog.tau_freeze == freeze / nog.table.t_f_star_s
    assert cpd.ff_period_s == 0.02
    paths = write_flight_config(tmp_path, _resolved(bundle), SCENARIO, bundle)
    text = paths[0].read_text()
    assert f".tau_freeze = {c_double(nog.tau_freeze)}," in text
    assert f".k_dy = {c_double(cpd.k_dy)}," in text
    _roundtrip(tmp_path, [ConfigItem("ogk_flight_nog_config", nog.to_c()),
                          ConfigItem("ogk_flight_cpd_config", cpd.to_c())], ("ogk/nog.h", "ogk/cpd.h"))


def test_apophis_header_is_the_mpsp_configuration(tmp_path: Path) -> None:
    """`ogk tables apophis`: the config of `ogk mpsp apophis` (cases.build_setup) and the nominal
    weights, read back in C; the kernel accepts the header's config unchanged."""
    from ogk.cli import main
    from ogk.missions.low_thrust_transfer.cases import build_setup
    assert main(["tables", "apophis", "--out", str(tmp_path)]) == 0
    header = tmp_path / "c" / "ogk_mpsp_flight_config.h"
    text = header.read_text()
    setup = build_setup()
    cfg = setup.guidance.cfg.to_c()
    nw = setup.guidance.n_weights
    assert f"#define OGK_FLIGHT_MPSP_N_WEIGHTS {nw}" in text
    weights = ffi.new(f"double[{nw}]", list(np.asarray(setup.guidance.cfg.weights_nom, float)))
    _roundtrip(tmp_path, [ConfigItem("ogk_flight_mpsp_config", cfg),
                          ConfigItem("ogk_flight_mpsp_weights_nom", weights)], ("ogk/mpsp.h",))
    ctx = ffi.new("ogk_mpsp_t *")
    assert lib.ogk_mpsp_init(ctx, cfg) == lib.OGK_OK
