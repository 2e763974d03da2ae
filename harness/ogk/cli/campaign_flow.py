"""`ogk replay CAMPAIGN RUN_ID` and `ogk report CAMPAIGN`: the same for every mission family (the
family found from the envelope by ogk.missions.registry); `ogk mc` is ogk.sil.command."""
from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
from ogk_bindings.errors import OgkInputError
from ogk_host.scenario_file import file_sha256, read_header

from ogk.missions import registry
from ogk.sil import dispersion_check, engine, envelope, numerics, target_summary
from ogk.sil.family import CampaignPlan, MissionFamily
from ogk.sil.outputs import check_output_dir, check_output_file


def campaign_plan(doc: dict[str, Any], path: str | Path) -> tuple[MissionFamily, CampaignPlan]:
    """The family and the plan of a campaign envelope, rebuilt from its scenario and options
    (refused when the scenario file changed since)."""
    scenario = Path(doc["scenario_path"])
    if not scenario.is_file():
        raise OgkInputError(f"scenario {scenario} of the campaign is missing", path=path,
                            key="scenario_path")
    if file_sha256(scenario) != doc["scenario_sha256"]:
        raise OgkInputError(f"scenario {scenario} changed since the campaign (SHA-256 differs)",
                            path=path, key="scenario_sha256")
    header = read_header(scenario)
    fam = registry.family(header)
    plan = fam.plan(header, doc["options"])
    if plan.products != doc["products"]:
        diff = sorted(k for k in set(plan.products) | set(doc["products"])
                      if plan.products.get(k) != doc["products"].get(k))
        raise OgkInputError(f"ground products differ from the campaign's ({', '.join(diff)})",
                            path=path, key="products")
    return fam, plan


def replay(campaign: str, run_id: int, plots: str | None, json_out: str | None) -> int:
    """`ogk replay CAMPAIGN RUN_ID`: run RUN_ID again, bit for bit against the stored table."""
    import json

    doc = envelope.read_envelope(campaign)
    table = Path(campaign).with_name(doc["per_run_table"] or envelope.table_path(campaign).name)
    stored = {int(r["run_id"]): r for r in envelope.read_table(table)}
    if run_id not in stored:
        raise OgkInputError(f"no run {run_id} in {table}", key="RUN_ID")
    if plots:
        check_output_dir(plots, "--plots")
    fam, plan = campaign_plan(doc, campaign)
    differ = numerics.differences(numerics.fingerprint(), doc.get("numerics") or {},
                                  "in the campaign")
    if doc.get("numerics") and differ:
        print("note: this machine's numerics differ from the campaign's, so the run may differ in "
              "its last bits (" + "; ".join(differ) + ")")
    again = engine.JudgedChunk(plan, int(doc["seed"]))(np.array([run_id], dtype=np.int64))[0]
    diff = envelope.record_differences(stored[run_id], again)
    print(f"{plan.mission}: run {run_id} of {campaign} (seed {doc['seed']}, run seed "
          f"{again['run_seed']}): {'bit-exact' if not diff else 'DIFFERS in ' + ', '.join(diff)}")
    for key in plan.quantities:
        print(f"  {key:28s} {again.get(key)!r}")
    if again.get("failure"):
        print(f"  failure: {again['failure']}")
    if plan.detail is not None and plots:
        detail = plan.detail(run_id, int(again["run_seed"]), Path(plots))
        for f in detail.files:
            print(f"wrote {f}")
    if json_out:
        check_output_file(json_out, "--json")
        from ogk.sil.outputs import write_atomic
        from ogk.sil.report import finite_or_none
        write_atomic(json_out, json.dumps(finite_or_none(
            {"campaign": str(campaign), "run_id": run_id, "bit_exact": not diff,
             "differences": diff, "record": again}), indent=1) + "\n")
        print(f"wrote {json_out}")
    return 0 if not diff else 1


def report(campaign: str) -> int:
    """`ogk report CAMPAIGN`: the campaign's tables (the paper's beside ours) from its JSON."""
    doc = envelope.read_envelope(campaign)
    table = Path(campaign).with_name(doc["per_run_table"] or envelope.table_path(campaign).name)
    records = envelope.read_table(table)
    # the family's own report, from the plan rebuilt as `ogk replay` does (nothing is flown)
    fam, plan = campaign_plan(doc, campaign)
    flown = engine.Flown(plan=plan, seed=int(doc["seed"]), records=records,
                         workers=int(doc["workers"]), wall_s=float(doc["timing"]["wall_s"] or 0.0),
                         cpu_s=float(doc["timing"]["cpu_s"] or 0.0),
                         resumed_runs=int(doc["resumed_runs"]))
    print(fam.report(flown)[0])
    print()
    print(generic_report(doc))
    disp = dispersion_check.check_plan(plan, records)     # the same verdict as `ogk mc`'s
    if disp is not None:
        print()
        print(disp.summary())
    return 0 if not doc["failures"] and (disp is None or not disp.structural_errors) else 1


def generic_report(doc: dict[str, Any]) -> str:
    """Quantities (with the worst run's distance from the median), failures with their classes and
    replay commands, the robustness summary and (when present) the paper's columns of any campaign;
    an envelope written before these keys existed gets the columns it has."""
    from ogk.sil import robustness
    lines = [f"{doc['mission']} ({doc['family']}, {doc['law']}): {doc['runs']} runs, seed "
             f"{doc['seed']}, {doc['failures']} failed"]
    if all("median" in q for q in doc["quantities"].values()):
        lines.append(robustness.format_quantities(doc["quantities"]))
    else:
        lines.append(f"  {'quantity':28s} {'mean':>14s} {'std':>14s} {'worst':>14s}  run")
        for key, q in doc["quantities"].items():
            if q["n"]:
                lines.append(f"  {key:28s} {q['mean']:14.6g} {q['std']:14.6g} "
                             f"{q['worst']['value']:14.6g}  {q['worst']['run_id']}")
    for reason, n in doc["failure_reasons"].items():
        lines.append(f"  failed: {n} x {reason}")
    for f in doc["failed_runs"]:
        if f.get("replay"):
            lines.append(f"  run {f['run_id']} ({f['class']}): {f['replay']}")
    if doc.get("robustness"):
        lines.append(robustness.format_summary(doc["robustness"], doc["family"], doc["mission"]))
    if doc.get("pil"):
        lines.append(target_summary.format_summary(doc["pil"]))
    return "\n".join(lines)
