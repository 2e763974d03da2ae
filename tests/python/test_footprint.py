"""port/profile/footprint.py: sizes read from the compiler's output against sizes known by construction
(an object of known arrays, a struct of known layout), and a mutable global failing the check."""
from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

pytestmark = pytest.mark.req("OGK-CORE-005")

ROOT = Path(__file__).resolve().parents[2]
CC = "arm-none-eabi-gcc -std=c99 -mthumb -mcpu=cortex-m7 -mfpu=fpv5-d16 -mfloat-abi=hard"


def footprint(tmp_path: Path, src: str):
    (tmp_path / "m.c").write_text(src)
    subprocess.run(CC.split() + ["-O2", "-c", "m.c", "-o", "m.o"], cwd=tmp_path, check=True)
    out = tmp_path / "f.json"
    r = subprocess.run([sys.executable, str(ROOT / "port/profile/footprint.py"), "--cc", CC,
                        "--size", "arm-none-eabi-size", "--nm", "arm-none-eabi-nm", "--json", str(out),
                        "--", str(tmp_path / "m.o")], capture_output=True, text=True)
    return r, json.loads(out.read_text())


def test_const_tables_are_read_only_and_pass(tmp_path):
    r, f = footprint(tmp_path, "const double table[100] = {1.0};\n"
                               "double pick(unsigned i) { return table[i % 100u]; }\n")
    assert r.returncode == 0, r.stdout
    assert f["modules"]["m"]["rodata"] == 800 and f["total"]["data"] == 0 and f["total"]["bss"] == 0
    assert f["modules"]["m"]["code"] > 0


@pytest.mark.parametrize("decl, kind, size", [("double state[3] = {1.0, 2.0, 3.0};", "data", 24),
                                               ("int counter[10];", "bss", 40)])
def test_a_mutable_global_fails(tmp_path, decl, kind, size):
    r, f = footprint(tmp_path, decl + "\nint touch(void);\nint touch(void) { return (int)sizeof "
                     + decl.split()[1].split("[")[0] + "; }\n")
    assert r.returncode == 1
    assert f["total"][kind] == size


def test_every_law_context_is_sized(tmp_path):
    """The context of every law is among the sized types (a law's RAM is its context)."""
    _, f = footprint(tmp_path, "const int unused = 1;\n")
    types = {t: n for per in f["types"].values() for t, n in per.items()}
    for ctx in ("ogk_nog_t", "ogk_cpd_t", "ogk_cutoff_t", "ogk_terminal_t", "ogk_mpsp_t", "ogk_nmpc_t",
                "ogk_blt_t"):
        assert types[ctx] > 0


def test_const_table_of_addresses_is_read_only_under_pie(tmp_path):
    """A const table of pointers is relocated once by the loader under position-independent code
    (.data.rel.ro on SPARC's Debian gcc): read-only data, not a mutable global."""
    cc = "sparc64-linux-gnu-gcc -std=c99 -m32 -mcpu=v8 -fPIE"
    (tmp_path / "n.c").write_text('static const char *const names[2] = {"first", "second"};\n'
                                  "const char *name(unsigned i);\n"
                                  "const char *name(unsigned i) { return names[i & 1u]; }\n")
    subprocess.run(cc.split() + ["-O2", "-c", "n.c", "-o", "n.o"], cwd=tmp_path, check=True)
    out = tmp_path / "f.json"
    r = subprocess.run([sys.executable, str(ROOT / "port/profile/footprint.py"), "--cc", cc,
                        "--size", "sparc64-linux-gnu-size", "--nm", "sparc64-linux-gnu-nm", "--json",
                        str(out), "--", str(tmp_path / "n.o")], capture_output=True, text=True)
    f = json.loads(out.read_text())
    assert r.returncode == 0, r.stdout
    assert f["total"]["data"] == 0 and f["modules"]["n"]["rodata"] >= 8
