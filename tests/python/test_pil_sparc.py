"""Processor in the loop on the big-endian target (docs/guides/pil.md, "SPARC V8"): the same flight program
as the Cortex-M7's (port/cortex-m7/pil/blt_pil.c over blt_flight.c) built for SPARC V8 Linux user
mode (port/sparc-v8/pil.mk) and flown under qemu-sparc32plus with the insn_count plugin, through the
family's target plan exactly as `ogk mc moshup --target sparc` flies it.

One short run (the scenario's Table 3 UMP transfer, 10 % perturbation, seed 7) keeps it cheap:
- the program is a 32-bit big-endian SPARC executable (its ELF header), and its stack probe takes a
  register window, so the %fp it reads is the caller's %sp (ogk_pil.c);
- the target campaign has no failure and agrees with the host's corrector calls (cffi, this
  process) on the same draws within the family's bounds (pil.BOUNDS: iterations equal);
- every entry point called has its instruction counts and a painted stack, and the painted stack is
  at most the static bound of the SPARC stack tool (make stack-bound-sparc) for that entry point.
"""
from __future__ import annotations

import json
import subprocess
from pathlib import Path

import pytest
from pil_checks import locked_make

ROOT = Path(__file__).resolve().parents[2]
SEED = 7
ENTRIES = ("ogk_blt_init", "ogk_blt_solve")
CORRECTORS = ("nrpc", "lm", "hybrid")


@pytest.fixture(scope="module")
def campaign() -> dict:
    from ogk_host.scenario_file import read_header
    from ogk.missions.binary import convergence_run as blt_campaign
    from ogk.missions.binary.family import FAMILY
    from ogk.sil import engine, target_summary
    from ogk.sil.seeds import run_generator, run_seed

    plan = FAMILY.plan(read_header(ROOT / "scenarios" / "moshup.toml"),
                       {"target": "sparc", "perturbation": [10.0]})
    assert plan.target == "sparc" and plan.options["target"] == "sparc"
    flown = engine.fly_campaign(plan, 1, SEED, 1, progress=False)
    job = plan.fly
    kernels = blt_campaign.kernels(job.nominal, job.correctors)
    host = [{"run_id": rid, **blt_campaign.fly_run(job.nominal, kernels, job.levels[0] / 100.0,
                                                   job.sigma, run_generator(run_seed(SEED, rid)))}
            for rid in flown.run_ids]
    summary = target_summary.summary(plan.target, flown.records, host, plan.target_bounds,
                                     plan.target_why, flown.wall_s, flown.workers)
    return {"plan": plan, "flown": flown, "host": host, "summary": summary,
            "elf": job.program.elf}


@pytest.mark.req("OGK-HAR-012")
def test_the_program_is_big_endian_sparc_and_its_probe_reads_the_callers_sp(campaign: dict) -> None:
    elf = campaign["elf"]
    head = subprocess.run(["sparc64-linux-gnu-readelf", "-h", str(elf)], check=True,
                          capture_output=True, text=True).stdout
    assert "ELF32" in head and "big endian" in head and "Sparc v8+" in head, head
    dis = subprocess.run(["sparc64-linux-gnu-objdump", "-d", "--no-show-raw-insn",
                          "--disassemble=ogk_pil_stack_paint", str(elf)], check=True,
                         capture_output=True, text=True).stdout
    body = [ln.split("\t", 1)[1] for ln in dis.splitlines() if ln.startswith("  ") and "\t" in ln]
    assert body and body[0].startswith("save  %sp, -"), body[:3]      # %fp is the caller's %sp
    assert any(ln.startswith("mov  %fp,") for ln in body), body


@pytest.mark.req("OGK-HAR-012", "OGK-BLT-010")
def test_the_big_endian_campaign_agrees_with_the_host(campaign: dict) -> None:
    from ogk.missions.binary.pil import BOUNDS
    flown, summary = campaign["flown"], campaign["summary"]
    assert len(flown.records) == 1 and not flown.failures()
    bounds = campaign["plan"].target_bounds        # the Cortex-M7's bounds, unchanged
    assert bounds and all(bounds[k] == BOUNDS[k] for k in bounds)
    hv = summary["host_vs_target"]
    assert hv["runs_compared"] == 1 and hv["within_bounds"] and not hv["failures_differ"]
    rec, host = flown.records[0], campaign["host"][0]
    for c in CORRECTORS:
        assert rec[f"{c}.iterations"] == host[f"{c}.iterations"], c
        assert abs(rec[f"{c}.err_norm"] - host[f"{c}.err_norm"]) <= BOUNDS[f"{c}.err_norm"], c


@pytest.mark.req("OGK-HAR-012")
def test_instructions_and_painted_stack_under_the_static_bound(campaign: dict) -> None:
    out = locked_make("stack-bound-sparc", timeout=1200)
    assert out.returncode == 0, out.stdout[-2000:] + out.stderr[-2000:]
    bound = json.loads((ROOT / "build" / "profile" / "stack_sparc.json").read_text())["entry_points"]
    rec = campaign["flown"].records[0]
    for e in ENTRIES:
        assert rec[f"pil.{e}.calls"] == 3, e                     # one per corrector context
        assert rec[f"pil.{e}.insn_max"] >= rec[f"pil.{e}.insn_median"] > 0, e
        painted = rec[f"pil.{e}.stack_bytes"]
        assert 0 < painted <= bound[e]["bytes"], (e, painted, bound[e]["bytes"])
        assert not rec.get(f"pil.{e}.stack_window_exceeded"), e
    worst = campaign["summary"]["entry_points"]["ogk_blt_solve"]
    assert worst["insn_max"]["value"] == rec["pil.ogk_blt_solve.insn_max"]
