#!/usr/bin/env python3
"""The resource profile of the flight code per target (issue 22): build/profile/profile.json and the
generated docs/evidence/profile.md. Inputs, all produced by `make profile` in the same run:
  --stack T=FILE        stack_bound.py's bounds for target T (libm, libc, callbacks included)
  --footprint T=FILE    footprint.py's code / read-only / RAM per module and sizeof per public type
  --campaign T=FILE...  processor-in-the-loop envelopes (`ogk mc ... --target T`): instructions per call
                        and the painted stack of every entry point the flight programs call, worst over
                        the recorded inputs, with the run and step that produced it.
  --program T=NAME=FILE the QEMU plugin's report (count_insns*.sh) of a program run on target T: the
                        worst instructions per call of its entry points over that run (no painting).
  --beside A:B...       a section putting target B beside target A, entry point by entry point: stack
                        bound, code reachable from the entry point (flash, libraries included), worst
                        instructions and their ratio, and the two kernels' totals (e.g. m7:m4f, the
                        Cortex-M4F's single-precision build beside the Cortex-M7's double build).
The painted stack of every entry point must stay under its static bound (exit 1 otherwise): the
measurement cross-checks the bound on the worst input the campaigns recorded. Nothing timed goes in:
the profile is identical from run to run.
"""
from __future__ import annotations

import argparse
import json
import re
import sys
from pathlib import Path


def _pairs(items: list[str]) -> list[tuple[str, Path]]:
    return [(i.split("=", 1)[0], Path(i.split("=", 1)[1])) for i in items]


_FN = re.compile(r"^insn_count fn (\S+) entry 0x[0-9a-f]+ calls (\d+) total \d+ min \d+ max (\d+)")


def program_envelope(name: str, report: Path) -> dict:
    """A plugin report as the entries of a campaign envelope (the run and step are unknown: -1)."""
    entries = {}
    for line in report.read_text().splitlines():
        m = _FN.match(line)
        if m and int(m.group(2)) > 0:
            entries[m.group(1)] = {"calls": int(m.group(2)),
                                   "insn_max": {"value": int(m.group(3)), "run_id": -1, "step": -1}}
    return {"scenario": name, "runs": 1, "seed": None, "pil": {"entry_points": entries}}


def merge_campaigns(files: list[tuple[str, Path]],
                    programs: list[tuple[str, str, Path]] = ()) -> tuple[dict, list[dict]]:
    """target -> entry -> worst instructions and painted stack over every campaign, with where."""
    worst: dict[str, dict[str, dict]] = {}
    listed: list[dict] = []
    loaded = [(t, json.loads(p.read_text())) for t, p in files]
    loaded += [(t, program_envelope(n, p)) for t, n, p in programs]
    for target, env in loaded:
        name = Path(env.get("scenario_path") or env["scenario"]).stem
        hvt = (env.get("pil") or {}).get("host_vs_target") or {}
        listed.append({"target": target, "scenario": name, "runs": env.get("runs"),
                       "seed": env.get("seed"), "scenario_sha256": env.get("scenario_sha256"),
                       "failed_runs": env.get("failures"),
                       "host_vs_target_within_bounds": hvt.get("within_bounds"),
                       "host_vs_target_report_only": bool(hvt.get("report_only"))})
        for entry, e in (env.get("pil") or {}).get("entry_points", {}).items():
            w = worst.setdefault(target, {}).setdefault(entry, {"calls": 0, "insn_max": None,
                                                                  "stack_painted": None})
            w["calls"] += int(e["calls"])
            im = e.get("insn_max")
            if im and (w["insn_max"] is None or im["value"] > w["insn_max"]["value"]):
                w["insn_max"] = {**im, "scenario": name}
            sb = e.get("stack_bytes")
            if sb and (w["stack_painted"] is None or sb["value"] > w["stack_painted"]["value"]):
                w["stack_painted"] = {**sb, "scenario": name}
            if e.get("stack_window_exceeded"):
                w["stack_window_exceeded"] = True
    return worst, listed


def build(stack: list[tuple[str, Path]], foot: list[tuple[str, Path]],
          camp: list[tuple[str, Path]], programs: list[tuple[str, str, Path]] = ()) -> tuple[dict, list[str]]:
    worst, listed = merge_campaigns(camp, programs)
    problems: list[str] = []
    targets: dict[str, dict] = {}
    for target, path in stack:
        s = json.loads(path.read_text())
        problems += [f"{target}: {p}" for p in s["problems"]]
        entries = {}
        for entry, e in s["entry_points"].items():
            row = {"stack_bound": e["bytes"], "own_frame": e["frame"], "deepest_path": e["path"],
                   "code_bytes": e.get("code_bytes"),
                   "library_frames": e["outside_kernel"], "indirect_call": e["indirect"]}
            w = worst.get(target, {}).get(entry)
            if w:
                row.update(w)
                p = w["stack_painted"]
                if p and p["value"] > e["bytes"]:
                    problems.append(f"{target}: {entry}: painted {p['value']} B above the bound "
                                    f"{e['bytes']} B ({p['scenario']} run {p['run_id']})")
                if w.get("stack_window_exceeded"):
                    problems.append(f"{target}: {entry}: the painted window was exceeded")
            entries[entry] = row
        missing = sorted(set(worst.get(target, {})) - set(entries))
        problems += [f"{target}: {m}: measured by a campaign but has no static bound" for m in missing]
        targets[target] = {"isa": s["isa"], "entry_points": entries,
                           "frames_checked_against_gcc": s.get("frames_checked_against_gcc")}
    for target, path in foot:
        targets.setdefault(target, {})["footprint"] = json.loads(path.read_text())
    return {"targets": targets, "campaigns": listed}, problems


def beside(doc: dict, a: str, b: str) -> dict:
    """Target b beside target a, per entry point both have: stack bound, reachable code, worst
    instructions (None where no campaign measured it) and b's instructions over a's."""
    ta, tb = doc["targets"][a], doc["targets"][b]
    rows = {}
    for entry in sorted(set(ta.get("entry_points", {})) & set(tb.get("entry_points", {}))):
        ea, eb = ta["entry_points"][entry], tb["entry_points"][entry]
        ia = (ea.get("insn_max") or {}).get("value")
        ib = (eb.get("insn_max") or {}).get("value")
        rows[entry] = {"stack_bound": [ea["stack_bound"], eb["stack_bound"]],
                       "code_bytes": [ea.get("code_bytes"), eb.get("code_bytes")],
                       "insn_max": [ia, ib],
                       "insn_ratio": (ib / ia) if ia and ib else None}
    totals = {k: [ta.get("footprint", {}).get("total", {}).get(k), tb.get("footprint", {}).get("total", {}).get(k)]
              for k in ("code", "rodata", "data", "bss")}
    return {"a": a, "b": b, "entry_points": rows, "kernel_totals": totals}


def _cell(v: object) -> str:
    return "" if v is None else str(v)


def beside_markdown(s: dict) -> list[str]:
    a, b = s["a"], s["b"]
    tot = s["kernel_totals"]
    out = ["", f"## {b} beside {a}", "",
           f"Kernel code {_cell(tot['code'][0])} B on {a}, {_cell(tot['code'][1])} B on {b}; read-only data "
           f"{_cell(tot['rodata'][0])} B and {_cell(tot['rodata'][1])} B; no global data on either. Per entry "
           "point: the stack bound, the code its call may execute (its own, the kernel's it reaches, libm's "
           "and libc's, soft-float helpers included) and the worst instructions per call the campaigns above "
           "recorded on each.", "",
           f"| entry point | stack {a} [B] | stack {b} [B] | code {a} [B] | code {b} [B] | worst insns {a} "
           f"| worst insns {b} | {b} / {a} |", "|---|---:|---:|---:|---:|---:|---:|---:|"]
    for entry, r in s["entry_points"].items():
        ratio = "" if r["insn_ratio"] is None else f"{r['insn_ratio']:.2f}"
        out.append(f"| `{entry}` | {r['stack_bound'][0]} | {r['stack_bound'][1]} | {_cell(r['code_bytes'][0])} "
                   f"| {_cell(r['code_bytes'][1])} | {_cell(r['insn_max'][0])} | {_cell(r['insn_max'][1])} "
                   f"| {ratio} |")
    return out


def markdown(doc: dict) -> str:
    out = ["# Resource profile of the flight code (generated by `make profile`; do not edit)", "",
           "Every figure below is written by `make profile` (port/profile/profile.py) into "
           "build/profile/profile.json; docs quote this page, never restate it. Stack: the static bound over "
           "the deepest path of the linked program (libm, libc and the kernel's own callbacks included; "
           "a caller's own callback adds its frames), checked against the stack painted at the worst "
           "input the processor-in-the-loop campaigns recorded. Instructions: QEMU's count per call, "
           "worst over those inputs.", ""]
    out += ["Campaigns flown for this profile:", ""]
    for c in doc["campaigns"]:
        if c["seed"] is None:
            out.append(f"- `{c['scenario']}` on `{c['target']}`: one run of the program under the "
                       "QEMU plugin (instructions per call; no painted stack)")
            continue
        verdict = {True: "within the stated bounds", False: "OUTSIDE the stated bounds",
                   None: "not compared"}[c.get("host_vs_target_within_bounds")]
        if c.get("host_vs_target_report_only"):
            verdict = "compared, report only (a single-precision target: no bound)"
        out.append(f"- `{c['scenario']}` on `{c['target']}`: {c['runs']} runs, seed {c['seed']}; "
                   f"{c.get('failed_runs') or 0} failed their mission criterion; host against target "
                   f"{verdict}")
    for target, t in doc["targets"].items():
        out += ["", f"## {target}", "", "| entry point | stack bound [B] | painted max [B] | worst instructions "
                "| where (scenario, run, step) | calls | deepest path |", "|---|---:|---:|---:|---|---:|---|"]
        for entry, e in t.get("entry_points", {}).items():
            p = e.get("stack_painted")
            im = e.get("insn_max")
            where = (f"{im['scenario']} {im['run_id']} {im['step']}" if im and im["run_id"] >= 0
                     else f"{im['scenario']} (whole run)" if im else "")
            path = " > ".join(e["deepest_path"][1:6])
            out.append(f"| `{entry}` | {e['stack_bound']} | {p['value'] if p else ''} | "
                       f"{im['value'] if im else ''} | {where} | {e.get('calls', '')} | {path} |")
        f = t.get("footprint")
        if f:
            tot = f["total"]
            out += ["", f"Kernel memory on {target}: code {tot['code']} B, read-only data {tot['rodata']} B, "
                    f"initialised data {tot['data']} B, zero-initialised {tot['bss']} B (the kernel has no "
                    "globals: a law's RAM is its context).", "",
                    "| module | code [B] | read-only [B] |", "|---|---:|---:|"]
            out += [f"| {m} | {v['code']} | {v['rodata']} |" for m, v in f["modules"].items()]
            out += ["", "| header | type | size [B] |", "|---|---|---:|"]
            for h, types in f["types"].items():
                out += [f"| {h}.h | `{ty}` | {n} |" for ty, n in types.items()]
    for side in doc.get("beside", []):
        out += beside_markdown(side)
    return "\n".join(out) + "\n"


def main(argv: list[str]) -> int:
    ap = argparse.ArgumentParser()
    ap.add_argument("--stack", nargs="+", default=[])
    ap.add_argument("--footprint", nargs="*", default=[])
    ap.add_argument("--campaign", nargs="*", default=[])
    ap.add_argument("--program", nargs="*", default=[])
    ap.add_argument("--beside", nargs="*", default=[])
    ap.add_argument("--json", type=Path, required=True)
    ap.add_argument("--doc", type=Path, required=True)
    a = ap.parse_args(argv)
    programs = [(i.split("=", 2)[0], i.split("=", 2)[1], Path(i.split("=", 2)[2])) for i in a.program]
    doc, problems = build(_pairs(a.stack), _pairs(a.footprint), _pairs(a.campaign), programs)
    for pair in a.beside:
        ta, tb = pair.split(":", 1)
        missing = [t for t in (ta, tb) if t not in doc["targets"]]
        if missing:
            problems.append(f"--beside {pair}: no profile of {', '.join(missing)}")
            continue
        doc.setdefault("beside", []).append(beside(doc, ta, tb))
    doc["problems"] = problems
    a.json.parent.mkdir(parents=True, exist_ok=True)
    a.json.write_text(json.dumps(doc, indent=1, sort_keys=True) + "\n")
    a.doc.write_text(markdown(doc))
    for p in problems:
        print(f"PROFILE FAILED: {p}")
    print(f"profile: {a.json} and {a.doc}")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
