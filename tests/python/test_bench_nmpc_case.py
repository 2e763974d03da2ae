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


def _ulps(x: float, k: int) -> float:
    for _ in range(abs(k)):
        x = float(np.nextafter(x, np.inf if k > 0 else -np.inf))
    return x


def test_re_solve_counts_stable_under_ulp_moves_of_the_start(fixture) -> None:
    """The bench's re-solve (the kernel through cffi, from the fixture) in each mode of `bench_nmpc`: one SQP
    and one QP count, and t_f within 1e-12 TU, when any component of its start (x_1, t_1) moves by 1 or 20
    ulps either way (issue 32; `make bench-nmpc-scan` moves every ulp from -20 to 20 and the open loop's
    start too)."""
    import ogk_bindings._ffi as f
    from ogk_bindings.nmpc import Nmpc

    v = nmpc_case.values(fixture)
    g = v["guess"]
    k = Nmpc(NmpcConfig(**v["config"]))
    k.load_plan(g["t0"], g["horizon"], np.array(g["states"]), np.array(g["controls"]))
    rep = k.solve(0.0, np.array(v["x0"]))
    assert rep.converged
    plan = k.plan()
    x1 = np.array(plan.states[1], dtype=np.float64)
    x1[0] += v["replan"]["dr"]
    x1[3] += v["replan"]["dvt"]
    t1 = rep.t_next
    size = f.ffi.sizeof("ogk_nmpc_t")
    saved = f.ffi.new("ogk_nmpc_t *")
    f.ffi.memmove(saved, k._ctx, size)   # noqa: SLF001 (the C bench's memcpy of the pre-replan context)
    counts = {}
    for label, tol_obj, hessian in [("default", None, None), ("tol0", 0.0, None), ("exact", None, 1),
                                    ("exact tol0", 0.0, 1)]:
        seen: set[tuple[int, int]] = set()
        tfs = []
        for comp in range(6):
            for move in (-20, -1, 0, 1, 20):
                x, t = x1.copy(), t1
                if comp < 5:
                    x[comp] = _ulps(float(x[comp]), move)
                else:
                    t = _ulps(t, move)
                f.ffi.memmove(k._ctx, saved, size)   # noqa: SLF001
                if tol_obj is not None:
                    k._ctx.cfg.tol_obj = tol_obj   # noqa: SLF001
                if hessian is not None:
                    k._ctx.cfg.hessian = hessian   # noqa: SLF001
                r = k.replan(t, x)
                assert r.converged, (label, comp, move, r.status)
                seen.add((r.sqp_iterations, r.qp_iterations))
                tfs.append(r.t_f)
        counts[label] = seen
        assert len(seen) == 1, (label, seen)
        assert max(tfs) - min(tfs) <= 1e-12, (label, max(tfs) - min(tfs))
    print({k_: sorted(c) for k_, c in counts.items()})
