"""Processor in the loop for the binary-asteroid BLT guidance (docs/guides/flight-integration-blt.md):
`ogk mc SCENARIO --target m7` makes every corrector call (ogk_blt_solve: NRPC, LM, hybrid) in the
scenario's flight program (port/cortex-m7/pil/blt_pil.c over blt_flight.c) on QEMU's Cortex-M7; the
host keeps the nominal design, the draws, the DOP853 checks and the judging.

On a mission no other file names (the Table 3 UMP transfer at 28 mN instead of 30 mN, without the
paper's results), made from a copy of scenarios/moshup.toml as a user would, 2 runs at 10 % and 50 %
(seed 7: the LM run at 50 % reaches the 40-iteration limit, so the flight software's SAFE reaction is
flown), through the engine with the family's target plan (one nominal design serves every test):
- the target campaign has no failure and agrees with the host's corrector calls (cffi, this process)
  on the same draws: iterations equal (bound 0), |e| and the DOP853 |e| within pil.BOUNDS;
- each run carries its instruction counts and stack per entry point (ogk_blt_init: 3 calls, one per
  corrector context; ogk_blt_solve: 3 calls), plausible (insn_max >= insn_median > 0, stack under
  the painted window) and the campaign summary names the worst call;
- the flight software's reactions, on the campaign's flight program: the nominal corrected (FLY, the
  host's iterations), a non-finite guess refused (REJECT), a rejected uplinked configuration (ABORT, then
  no solve on that context), an uplink whose integer field is not an exact uint32 (ABORT, OGK_E_RANGE);
- the frames' flattening of the kernel structs round-trips (host side).
The CLI (`ogk mc ... --target m7`, the engine's own host campaign beside it) is what the docs' figures
come from; tests/python/test_pil_orbit_injection.py covers the command's target path.
"""
from __future__ import annotations

import dataclasses
import re
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[2]
ENTRIES = ("ogk_blt_init", "ogk_blt_solve")
CORRECTORS = ("nrpc", "lm", "hybrid")
SEED = 7


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
    from ogk_host.scenario_file import read_header
    from ogk.missions.binary import convergence_run as blt_campaign
    from ogk.missions.binary.family import FAMILY
    from ogk.sil import engine, target_summary
    from ogk.sil.seeds import run_generator, run_seed

    scenario = moshup_28mn(tmp_path_factory.mktemp("pil_blt"))
    plan = FAMILY.plan(read_header(scenario), {"target": "m7", "perturbation": [10.0, 50.0]})
    assert plan.target == "m7" and plan.options["target"] == "m7"
    flown = engine.fly_campaign(plan, 2, SEED, 1, progress=False)
    # the host's corrector calls (cffi) on the same draws
    job = plan.fly
    kernels = blt_campaign.kernels(job.nominal, job.correctors)
    host = [{"run_id": rid, **blt_campaign.fly_run(job.nominal, kernels, job.levels[rid % 2] / 100.0,
                                                   job.sigma, run_generator(run_seed(SEED, rid)))}
            for rid in flown.run_ids]
    summary = target_summary.summary(plan.target, flown.records, host, plan.target_bounds,
                                     plan.target_why, flown.wall_s, flown.workers)
    return {"plan": plan, "flown": flown, "records": flown.records, "host": host,
            "summary": summary, "text": target_summary.format_summary(summary)}


@pytest.mark.req("OGK-HAR-012", "OGK-BLT-010")
def test_target_campaign_passes_and_agrees_with_the_host(campaign: dict) -> None:
    from ogk.missions.binary.pil import BOUNDS
    plan, flown = campaign["plan"], campaign["flown"]
    assert len(flown.records) == 2 and not flown.failures()
    assert "flight_program" in plan.products and plan.target_bounds == BOUNDS
    hv = campaign["summary"]["host_vs_target"]
    assert hv["runs_compared"] == 2 and hv["within_bounds"] and not hv["failures_differ"]
    for c in CORRECTORS:
        assert hv["quantities"][f"{c}.iterations"]["max_abs_diff"] == 0.0
        assert hv["quantities"][f"{c}.err_norm"]["max_abs_diff"] <= BOUNDS[f"{c}.err_norm"]
    # the same reasons run by run, and both reactions flown: converged (FLY), iteration limit (SAFE)
    for t, h in zip(campaign["records"], campaign["host"]):
        assert [t[f"{c}.reason"] for c in CORRECTORS] == [h[f"{c}.reason"] for c in CORRECTORS]
        assert t["draw.xi"] == h["draw.xi"]
    reasons = {r[f"{c}.reason"] for r in campaign["records"] for c in CORRECTORS}
    assert reasons == {"converged", "iteration limit"}
    assert "within the stated bounds" in campaign["text"]


@pytest.mark.req("OGK-HAR-012", "OGK-BLT-011")
def test_every_entry_point_has_its_figures_per_run(campaign: dict) -> None:
    for r in campaign["records"]:
        assert r["pil.ogk_blt_init.calls"] == 3 and r["pil.ogk_blt_solve.calls"] == 3
        for e in ENTRIES:
            assert r[f"pil.{e}.insn_max"] >= r[f"pil.{e}.insn_median"] > 0, e
            assert 0 < r[f"pil.{e}.stack_bytes"] < 4096, e
            assert not r.get(f"pil.{e}.stack_window_exceeded"), e
        # the solves cost what their iterations do: a 40-iteration LM is the dearest call
        assert r["pil.ogk_blt_solve.insn_max"] > 1_000_000
    worst = campaign["summary"]["entry_points"]
    runs = {r["run_id"]: r for r in campaign["records"]}
    for e in ENTRIES:
        w = worst[e]["insn_max"]
        assert w["value"] == max(r[f"pil.{e}.insn_max"] for r in campaign["records"])
        assert runs[w["run_id"]][f"pil.{e}.insn_max"] == w["value"]
    assert "On the target (m7)" in campaign["text"]


@pytest.mark.req("OGK-HAR-012")
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


@pytest.mark.req("OGK-HAR-012", "OGK-BLT-010")
def test_reactions_on_the_target(campaign: dict) -> None:
    from ogk_bindings.kernel import KernelError
    from ogk.missions.binary import convergence_run as campaign_mod
    from ogk.missions.binary import pil
    from ogk.missions.binary.flight_config import slot_configs
    from ogk.sil.pil import PilSession

    plan = campaign["plan"]
    nominal, program = plan.fly.nominal, plan.fly.program
    n_seg, n_nodes = nominal.transfer.segments.shape[0], len(nominal.layout.free_nodes)
    s = PilSession(program)
    try:
        pil.configure(s, 1)                                    # lm, the generated configuration
        lm = pil.TargetCorrector(s, 1, n_seg, n_nodes)
        sol, rep = lm.solve(nominal.transfer)
        host_sol, host_rep = campaign_mod.kernels(nominal, ("lm",))["lm"].solve(nominal.transfer)
        assert rep.converged and lm.last_action == "fly" and rep.iterations == host_rep.iterations
        assert abs(rep.err_norm - host_rep.err_norm) <= pil.BOUNDS["lm.err_norm"]
        assert np.allclose(sol.segments, host_sol.segments, rtol=0.0, atol=1e-12)
        bad = dataclasses.replace(nominal.transfer, x0=np.full(6, np.nan))
        with pytest.raises(KernelError):
            lm.solve(bad)
        assert lm.last_action == "reject"
        # a configuration the kernel rejects: the slot aborts, and its solves with it
        with pytest.raises(KernelError):
            pil.configure(s, 0, slot_configs(nominal)[0].replace(tol=-1.0))
        nrpc = pil.TargetCorrector(s, 0, n_seg, n_nodes)
        with pytest.raises(KernelError) as exc:
            nrpc.solve(nominal.transfer)
        assert exc.value.name == "OGK_E_NOT_INIT" and nrpc.last_action == "abort"
        # n_segments (the 17th value) 1.5: refused before the kernel sees it
        values = pil.flatten(slot_configs(nominal)[0].to_c())
        values[16] = 1.5
        r = s.exchange(pil.BLT_LOAD, [0.0, *values])
        assert list(r) == [3.0, 4.0]                           # ABORT, OGK_E_RANGE
        s.end_run(0)
        keys = s.close()[0]
    except BaseException:
        s.kill()
        raise
    # the unready slot never reached the kernel: two solves (the nominal, the refused guess)
    assert keys["pil.ogk_blt_init.calls"] == 2 and keys["pil.ogk_blt_solve.calls"] == 2

