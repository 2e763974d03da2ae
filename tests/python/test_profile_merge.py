"""port/profile/profile.py: the worst instructions and painted stack over several campaigns are the
largest of their inputs, with where they came from; a painted stack above the static bound, or an entry
point a campaign measured without a bound, fails the profile."""
from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

pytestmark = pytest.mark.req("OGK-CORE-006")

ROOT = Path(__file__).resolve().parents[2]


def envelope(path: Path, scenario: str, entries: dict) -> Path:
    path.write_text(json.dumps({"scenario_path": f"scenarios/{scenario}.toml", "runs": 3, "seed": 5,
                                "pil": {"entry_points": entries}}))
    return path


def entry(calls, insn, run, step, stack, srun):
    return {"calls": calls, "insn_median": insn / 2, "insn_max": {"value": insn, "run_id": run, "step": step},
            "stack_bytes": {"value": stack, "run_id": srun}, "stack_window_exceeded": False}


def run(tmp_path: Path, bound: int, extra: dict | None = None):
    stack = tmp_path / "stack.json"
    stack.write_text(json.dumps({"isa": "thumb", "problems": [], "frames_checked_against_gcc": 3,
                                 "entry_points": {"ogk_a_step": {"bytes": bound, "frame": 40,
                                                                 "path": ["ogk_a_step", "x"],
                                                                 "outside_kernel": [], "indirect": False}}}))
    e1 = envelope(tmp_path / "m1.json", "mission_one", {"ogk_a_step": entry(10, 900, 2, 7, 300, 1)})
    e2 = envelope(tmp_path / "m2.json", "mission_two", {"ogk_a_step": entry(5, 1200, 0, 3, 280, 4),
                                                         **(extra or {})})
    out, doc = tmp_path / "p.json", tmp_path / "p.md"
    r = subprocess.run([sys.executable, str(ROOT / "port/profile/profile.py"), "--stack", f"m7={stack}",
                        "--campaign", f"m7={e1}", f"m7={e2}", "--json", str(out), "--doc", str(doc)],
                       capture_output=True, text=True)
    return r, json.loads(out.read_text()), doc.read_text()


def test_worst_over_campaigns_with_where(tmp_path):
    r, prof, doc = run(tmp_path, bound=512)
    assert r.returncode == 0, r.stdout
    e = prof["targets"]["m7"]["entry_points"]["ogk_a_step"]
    assert e["calls"] == 15
    assert e["insn_max"] == {"value": 1200, "run_id": 0, "step": 3, "scenario": "mission_two"}
    assert e["stack_painted"] == {"value": 300, "run_id": 1, "scenario": "mission_one"}
    assert "| `ogk_a_step` | 512 | 300 | 1200 | mission_two 0 3 | 15 |" in doc


def test_painted_above_bound_fails(tmp_path):
    r, prof, _ = run(tmp_path, bound=296)
    assert r.returncode == 1
    assert "painted 300 B above the bound 296 B (mission_one run 1)" in r.stdout
    assert prof["problems"]


def test_measured_entry_without_bound_fails(tmp_path):
    r, _, _ = run(tmp_path, bound=512, extra={"ogk_b_step": entry(1, 10, 0, 0, 8, 0)})
    assert r.returncode == 1
    assert "ogk_b_step: measured by a campaign but has no static bound" in r.stdout


def test_a_program_report_adds_its_worst_call(tmp_path):
    """The plugin's report of a whole program run gives each entry's worst call, marked as a whole run."""
    stack = tmp_path / "stack.json"
    stack.write_text(json.dumps({"isa": "sparc", "problems": [], "entry_points": {
        "ogk_a_step": {"bytes": 900, "frame": 96, "path": ["ogk_a_step"], "outside_kernel": [],
                       "indirect": False}}}))
    rep = tmp_path / "rep.txt"
    rep.write_text("insn_count total 99\n"
                   "insn_count fn ogk_a_step entry 0x00010600 calls 7 total 70 min 4 max 31\n"
                   "insn_count fn ogk_never entry 0x00010700 calls 0 total 0 min 0 max 0\n"
                   "insn_count range ogk_a_step 0x00010600-0x00010640 executed 50\n")
    out, doc = tmp_path / "p.json", tmp_path / "p.md"
    r = subprocess.run([sys.executable, str(ROOT / "port/profile/profile.py"), "--stack", f"sparc={stack}",
                        "--program", f"sparc=demo_app={rep}", "--json", str(out), "--doc", str(doc)],
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stdout
    e = json.loads(out.read_text())["targets"]["sparc"]["entry_points"]["ogk_a_step"]
    assert e["calls"] == 7 and e["insn_max"]["value"] == 31 and e["stack_painted"] is None
    assert "| `ogk_a_step` | 900 |  | 31 | demo_app (whole run) | 7 |" in doc.read_text()


def test_beside_puts_a_second_target_next_to_the_first(tmp_path):
    """--beside m7:m4f: per entry point both targets profile, the two stack bounds, codes and worst
    instructions, and the second's instructions over the first's."""
    def stack(name, bound, code):
        p = tmp_path / f"stack_{name}.json"
        p.write_text(json.dumps({"isa": "thumb", "problems": [], "entry_points": {
            "ogk_a_step": {"bytes": bound, "frame": 40, "path": ["ogk_a_step"], "outside_kernel": [],
                           "indirect": False, "code_bytes": code},
            "ogk_only_here": {"bytes": 8, "frame": 8, "path": ["ogk_only_here"], "outside_kernel": [],
                              "indirect": False, "code_bytes": 12}}}))
        return p
    e7 = envelope(tmp_path / "a.json", "mission_a", {"ogk_a_step": entry(4, 1000, 1, 2, 100, 1)})
    e4 = envelope(tmp_path / "b.json", "mission_a", {"ogk_a_step": entry(4, 2500, 1, 2, 60, 1)})
    out, doc = tmp_path / "p.json", tmp_path / "p.md"
    r = subprocess.run([sys.executable, str(ROOT / "port/profile/profile.py"),
                        "--stack", f"m7={stack('m7', 512, 9000)}", f"m4f={stack('m4f', 300, 7000)}",
                        "--campaign", f"m7={e7}", f"m4f={e4}", "--beside", "m7:m4f", "nope:m4f",
                        "--json", str(out), "--doc", str(doc)], capture_output=True, text=True)
    prof = json.loads(out.read_text())
    (side,) = prof["beside"]
    row = side["entry_points"]["ogk_a_step"]
    assert row["stack_bound"] == [512, 300] and row["code_bytes"] == [9000, 7000]
    assert row["insn_max"] == [1000, 2500] and row["insn_ratio"] == 2.5
    assert "| `ogk_a_step` | 512 | 300 | 9000 | 7000 | 1000 | 2500 | 2.50 |" in doc.read_text()
    assert r.returncode == 1 and "--beside nope:m4f: no profile of nope" in r.stdout
