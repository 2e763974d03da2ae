"""Processor in the loop for the binary-asteroid BLT guidance (docs/flight-integration-blt.md):
`ogk mc SCENARIO --target m7` makes every corrector call (ogk_blt_solve: NRPC, LM, hybrid) in the
scenario's flight program (port/cortex-m7/pil/blt_pil.c over blt_flight.c) on QEMU's Cortex-M7; the
host keeps the nominal design, the draws, the DOP853 checks and the judging.

On a mission no other file names (the Table 3 UMP transfer at 28 mN instead of 30 mN, without the
paper's results), made from a copy of scenarios/moshup.toml as a user would, 2 runs at 10 % and 50 %
(seed 7: the LM run at 50 % reaches the 40-iteration limit, so the flight software's SAFE reaction is flown):
- the target campaign has no failure and agrees with the host campaign the command flies on the same
  draws: iterations equal (bound 0), |e| and the DOP853 |e| within the family's bound (pil.BOUNDS);
- each run carries its instruction counts and stack per entry point (ogk_blt_init: 3 calls, one per
  corrector context; ogk_blt_solve: 3 calls), plausible (insn_max >= insn_median > 0, stack under
  the painted window) and the envelope names the worst call;
- the frames' flattening of the kernel structs round-trips (host side).
"""
from __future__ import annotations

import json
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[2]
OGK = Path(sys.executable).parent / "ogk"
ENTRIES = ("ogk_blt_init", "ogk_blt_solve")
CORRECTORS = ("nrpc", "lm", "hybrid")


def moshup_28mn(directory: Path) -> Path:
    text = (ROOT / "scenarios" / "moshup.toml").read_text()
    text = re.sub(r'^name = "moshup"', 'name = "pil_blt_moshup_28mn"', text, flags=re.M)
    at = text.index("[transfers.circle_to_l2_ump]")
    text = text[:at] + text[at:].replace("thrust_n = 0.030", "thrust_n = 0.028", 1)
    text = text[:text.index("\n[paper_results") + 1]          # not the paper's case
    path = directory / "pil_blt_moshup_28mn.toml"
    path.write_text(text)
    return path


@pytest.fixture(scope="module")
def campaign(tmp_path_factory: pytest.TempPathFactory) -> dict:
    d = tmp_path_factory.mktemp("pil_blt")
    scenario = moshup_28mn(d)
    out = subprocess.run([str(OGK), "mc", str(scenario), "--target", "m7", "--runs", "2",
                          "--perturbation", "10", "50", "--seed", "7", "--workers", "1",
                          "--json", str(d / "m7.json")],
                         capture_output=True, text=True, timeout=300, cwd=ROOT)
    assert out.returncode == 0, out.stdout[-3000:] + out.stderr[-3000:]
    import pyarrow.parquet as pq
    return {"stdout": out.stdout, "doc": json.loads((d / "m7.json").read_text()),
            "records": pq.read_table(d / "m7.parquet").to_pylist()}


def test_target_campaign_passes_and_agrees_with_the_host(campaign: dict) -> None:
    from ogk.missions.binary.pil import BOUNDS
    doc = campaign["doc"]
    assert doc["target"] == "m7" and doc["failures"] == 0 and doc["runs"] == 2
    assert doc["options"]["target"] == "m7" and "flight_program" in doc["products"]
    hv = doc["pil"]["host_vs_target"]
    assert hv["runs_compared"] == 2 and hv["within_bounds"] and not hv["failures_differ"]
    assert set(hv["quantities"]) == set(BOUNDS)
    for c in CORRECTORS:
        assert hv["quantities"][f"{c}.iterations"]["max_abs_diff"] == 0.0
        assert hv["quantities"][f"{c}.err_norm"]["max_abs_diff"] <= BOUNDS[f"{c}.err_norm"]
    # the draw exercises both reactions: converged (FLY) and the iteration limit (SAFE)
    reasons = {r[f"{c}.reason"] for r in campaign["records"] for c in CORRECTORS}
    assert reasons == {"converged", "iteration limit"}
    assert "Host vs target" in campaign["stdout"] and "within the stated bounds" in campaign["stdout"]


def test_every_entry_point_has_its_figures_per_run(campaign: dict) -> None:
    for r in campaign["records"]:
        assert r["pil.ogk_blt_init.calls"] == 3 and r["pil.ogk_blt_solve.calls"] == 3
        for e in ENTRIES:
            assert r[f"pil.{e}.insn_max"] >= r[f"pil.{e}.insn_median"] > 0, e
            assert 0 < r[f"pil.{e}.stack_bytes"] < 4096, e
            assert not r.get(f"pil.{e}.stack_window_exceeded"), e
        # the solves cost what their iterations do: a 40-iteration LM is the dearest call
        assert r["pil.ogk_blt_solve.insn_max"] > 1_000_000
    worst = campaign["doc"]["pil"]["entry_points"]
    runs = {r["run_id"]: r for r in campaign["records"]}
    for e in ENTRIES:
        w = worst[e]["insn_max"]
        assert w["value"] == max(r[f"pil.{e}.insn_max"] for r in campaign["records"])
        assert runs[w["run_id"]][f"pil.{e}.insn_max"] == w["value"]
    assert "On the target (m7)" in campaign["stdout"]


def test_frames_flatten_the_kernel_structs_both_ways() -> None:
    from ogk_bindings._ffi import ffi
    from ogk_bindings.blt import BltConfig, Transfer
    from ogk.missions.binary.pil import REPORT_N, TRANSFER_N, flatten, unflatten

    rng = np.random.default_rng(3)
    tr = Transfer(t0=0.5, x0=rng.normal(size=6), xf=rng.normal(size=6),
                  segments=rng.normal(size=(3, 7)), nodes=rng.normal(size=(1, 6)), mass0=0.9)
    v = flatten(tr.to_c())
    assert len(v) == TRANSFER_N == 55
    box = unflatten("ogk_blt_transfer_t", np.array(v))
    back = Transfer.from_c(box[0], 3, 1)
    assert np.array_equal(back.segments, tr.segments) and np.array_equal(back.nodes, tr.nodes)
    assert back.t0 == tr.t0 and back.mass0 == tr.mass0 and np.array_equal(back.x0, tr.x0)
    cfg = BltConfig(model=dict(mu=0.05, body_radius=[0.2, 0.05], thrust_accel=0.1), n_segments=3,
                    segment_kind=[1, 0, 1], meet_interface=[3], max_iter=17, tol=3e-7)
    c = unflatten("ogk_blt_config_t", np.array(flatten(cfg.to_c())))
    assert flatten(c) == flatten(cfg.to_c()) and c[0].max_iter == 17 and c[0].n_segments == 3
    assert len(flatten(ffi.new("ogk_blt_report_t *"))) == REPORT_N
