"""The NMPC bench's committed case (tests/bench/fixtures/nmpc_case.json, tests/bench/nmpc_case.py).

`make bench-nmpc` and `make bench-qp` read the case from a committed fixture so that nothing in it depends
on the machine's numpy, BLAS or libm (issue 32: regenerated through numpy, the guess's last bits moved
between machines). Checked here:

* the fixture is what the generator gives on the paper's problem (`paper_problem(scenario)`,
  `kernel_config(..., mass_min=0.0)`) within nmpc_case.GEN_RTOL = 1e-12 relative to max(|value|, 1), the
  integers exactly: regenerated on this machine, the same problem;
* it has every ogk_nmpc_config_t field, and it is the paper's problem (no terminal set, propellant row,
  body or keep-out), not the shipped scenario's robust configuration;
* the C header (`nmpc_case.py header`, a pure transform) holds the fixture's doubles bit for bit: every
  literal parsed back and compared by its bits, field by field and element by element.
"""
from __future__ import annotations

import re
import struct
import sys
from pathlib import Path

import numpy as np
import pytest

from ogk_bindings.nmpc import NmpcConfig

REPO = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(REPO / "tests" / "bench"))
import nmpc_case  # noqa: E402

pytestmark = pytest.mark.req("OGK-NMPC-003")


@pytest.fixture(scope="module")
def fixture() -> dict:
    return nmpc_case.load()


def _bits(v: float) -> int:
    return struct.unpack("<Q", struct.pack("<d", v))[0]


def test_fixture_equals_the_generator_on_the_papers_problem(fixture) -> None:
    diffs = nmpc_case.differences(fixture, nmpc_case.generate())
    print(diffs[-1])
    assert diffs[:-1] == [], "\n".join(diffs)


def test_fixture_has_every_config_field_and_is_the_papers_problem(fixture) -> None:
    assert list(fixture["config"]) == list(NmpcConfig.fields())
    c = nmpc_case.values(fixture)["config"]
    assert c["n_bodies"] == 0 and c["mass_min"] == 0.0
    assert not any(c["terminal_box"]) and not any(c["keepout_radius"]) and not any(c["body_release"])
    # the fixture's configuration loads in the kernel as it is
    cfg = NmpcConfig(**c)
    assert cfg.nodes == fixture["guess"]["nodes"] == 30
    # the shipped scenario's kernel configuration is not the paper's problem (robustness on)
    from ogk.missions.rendezvous.guidance_base import strategy_settings
    from ogk.missions.rendezvous.kernel_guidance import kernel_config
    from ogk_host.rendezvous.scenario import load_scenario
    shipped = load_scenario(REPO / nmpc_case.SCENARIO)
    robust = kernel_config(shipped, strategy_settings(shipped)).as_dict()
    assert robust["mass_min"] > 0.0 or robust["n_bodies"] > 0 or np.any(robust["terminal_box"])


_ASSIGN = re.compile(r"^\s*c->(\w+)(?:\[(\d+)\])? = ([^;]+);")
_HEX = re.compile(r"-?0x[0-9a-f]+(?:\.[0-9a-f]*)?p[+-]\d+|\(-?1\.0 / 0\.0\)")


def _c_value(tok: str) -> float:
    if tok.startswith("("):
        return float("-inf") if tok.startswith("(-") else float("inf")
    return float.fromhex(tok)


def test_header_holds_the_fixture_bit_for_bit(fixture, tmp_path) -> None:
    out = tmp_path / "bench_nmpc_case.h"
    assert nmpc_case.main(["header", str(nmpc_case.FIXTURE), str(out)]) == 0
    text = out.read_text()
    v = nmpc_case.values(fixture)
    seen: set[tuple[str, int | None]] = set()
    for line in text.splitlines():
        m = _ASSIGN.match(line)
        if not m:
            continue
        name, idx, rhs = m.group(1), m.group(2), m.group(3)
        want = v["config"][name] if idx is None else v["config"][name][int(idx)]
        if isinstance(want, int):
            assert rhs == f"{want}u", line
        else:
            assert _bits(_c_value(rhs.split()[0])) == _bits(want), line
        seen.add((name, None if idx is None else int(idx)))
    expected = {(k, None) if not isinstance(x, list) else None for k, x in v["config"].items()} - {None}
    expected |= {(k, i) for k, x in v["config"].items() if isinstance(x, list) for i in range(len(x))}
    assert seen == expected

    def array(name: str) -> list[float]:
        body = text[text.index(name):]
        body = body[body.index("{") + 1: body.index("}")]
        return [_c_value(t) for t in _HEX.findall(body)]

    g = v["guess"]
    assert [_bits(x) for x in array("bench_nmpc_guess_x[")] == [_bits(x) for row in g["states"] for x in row]
    assert [_bits(x) for x in array("bench_nmpc_guess_u[")] == [_bits(row[0]) for row in g["controls"]]
    assert [_bits(x) for x in array("bench_nmpc_x0[")] == [_bits(x) for x in v["x0"]]
    scalars = {"bench_nmpc_guess_t0 =": g["t0"], "bench_nmpc_guess_horizon =": g["horizon"],
               "BENCH_NMPC_DR ": v["replan"]["dr"], "BENCH_NMPC_DVT ": v["replan"]["dvt"],
               "BENCH_NMPC_TU_S ": v["units"]["time_s"]}
    for key, want in scalars.items():
        tok = _HEX.search(text[text.index(key):]).group(0)
        assert _bits(_c_value(tok)) == _bits(want), key
    assert f"#define BENCH_NMPC_NODES {g['nodes']}u" in text
    # the same text from the same fixture: a pure transform
    assert nmpc_case.header_text(fixture, "tests/bench/fixtures/nmpc_case.json") == text
