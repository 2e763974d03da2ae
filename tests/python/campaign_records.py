"""Campaign records (tests/records/records.toml): fly an entry through `ogk mc`, normalise its run log,
compare it with the committed record. `python tests/python/campaign_records.py write|check [--all] [NAME...]`
(`make records`, `make records-check`); test_campaign_records.py checks the quick entries.

A record is the campaign's run log (`<json>.runs.jsonl`) without what a restructuring may move: the
`timing.*` keys (wall clock), the flight program's hash (`key.products`, it changes with any kernel edit),
and on a target the per-entry instruction and stack counts (`pil.<entry>.insn_*`, `.stack_bytes`),
which are held within INSN_RTOL of the record instead (issue 33: within 3 %)."""
from __future__ import annotations

import json
import math
import re
import subprocess
import sys
import tempfile
import tomllib
from dataclasses import dataclass
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[2]
RECORDS = ROOT / "tests" / "records"
OGK = ROOT / ".venv" / "bin" / "ogk"
INSN_RTOL = 0.03
_COUNT = re.compile(r"^pil\.[A-Za-z_][A-Za-z0-9_]*\.(insn_median|insn_max|insn_max_step|stack_bytes)$")


@dataclass(frozen=True)
class Entry:
    name: str
    scenario: str
    args: tuple[str, ...]
    quick: bool
    quick_runs: int | None = None   #: make test flies only the first runs (run i depends on (seed, i) only)

    def quick_args(self) -> tuple[str, ...]:
        """The arguments of the quick check: --runs cut to quick_runs."""
        if self.quick_runs is None:
            return self.args
        a = list(self.args)
        a[a.index("--runs") + 1] = str(self.quick_runs)
        return tuple(a)

    @property
    def path(self) -> Path:
        return RECORDS / f"{self.name}.jsonl"


def entries() -> list[Entry]:
    raw = tomllib.loads((RECORDS / "records.toml").read_text(encoding="utf-8"))
    return [Entry(r["name"], r["scenario"], tuple(r["args"]), bool(r["quick"]), r.get("quick_runs"))
            for r in raw["record"]]


def fly(entry: Entry, workdir: Path, quick: bool = False) -> list[dict[str, Any]]:
    """The entry's campaign, flown now (quick: its first quick_runs runs): its normalised run log
    (header line first)."""
    out = workdir / f"{entry.name}.json"
    args = entry.quick_args() if quick else entry.args
    res = subprocess.run([str(OGK), "mc", entry.scenario, *args, "--workers", "2",
                          "--json", str(out)], capture_output=True, text=True, timeout=3600, cwd=ROOT)
    if res.returncode not in (0, 1) or "Traceback" in res.stderr:
        raise RuntimeError(f"ogk mc {entry.name}: exit {res.returncode}\n{res.stdout[-3000:]}"
                           f"\n{res.stderr[-3000:]}")
    lines = Path(f"{out}.runs.jsonl").read_text(encoding="utf-8").splitlines()
    return normalise([json.loads(x) for x in lines if x.strip()])


def _rooted(v: Any) -> Any:
    """Paths under the checkout written relative to it (`<root>/...`): a record holds in any clone."""
    if isinstance(v, str):
        return v.replace(str(ROOT), "<root>")
    if isinstance(v, dict):
        return {k: _rooted(x) for k, x in v.items()}
    if isinstance(v, list):
        return [_rooted(x) for x in v]
    return v


def normalise(log: list[dict[str, Any]]) -> list[dict[str, Any]]:
    head, runs = dict(log[0]), sorted(log[1:], key=lambda r: int(r["run_id"]))
    head["key"] = _rooted({k: v for k, v in head["key"].items() if k != "products"})
    return [head] + [{k: v for k, v in r.items() if not k.startswith("timing.")} for r in runs]


def read(entry: Entry, quick: bool = False) -> list[dict[str, Any]]:
    """The committed record (quick: its header and first quick_runs runs)."""
    log = [json.loads(x) for x in entry.path.read_text(encoding="utf-8").splitlines() if x.strip()]
    return log[:1 + entry.quick_runs] if quick and entry.quick_runs is not None else log


def write(entry: Entry, log: list[dict[str, Any]]) -> None:
    entry.path.write_text("".join(json.dumps(r, sort_keys=True) + "\n" for r in log), encoding="utf-8")


def _same(a: Any, b: Any) -> bool:
    """Bit for bit (json round-trips a double exactly); NaN equals NaN."""
    if isinstance(a, float) and isinstance(b, float) and math.isnan(a) and math.isnan(b):
        return True
    return type(a) is type(b) and a == b


def differences(stored: list[dict[str, Any]], flown: list[dict[str, Any]]) -> list[str]:
    """What differs between a record and a campaign flown again; [] when it is the record."""
    if len(stored) != len(flown):
        return [f"{len(stored) - 1} runs recorded, {len(flown) - 1} flown"]
    out = [] if stored[0] == flown[0] else [f"header: {stored[0]} != {flown[0]}"]
    for s, f in zip(stored[1:], flown[1:]):
        for k in sorted(set(s) | set(f)):
            a, b = s.get(k), f.get(k)
            if _COUNT.match(k):
                if k.endswith("insn_max_step"):
                    continue                 # where the worst call falls moves with the counts
                if a is None or b is None or abs(b - a) > INSN_RTOL * abs(a):
                    out.append(f"run {s['run_id']}: {k} {a} -> {b} (more than {INSN_RTOL:.0%})")
            elif not _same(a, b):
                out.append(f"run {s['run_id']}: {k} {a!r} -> {b!r}")
    return out


def main(argv: list[str]) -> int:
    if not argv or argv[0] not in ("write", "check"):
        print(__doc__)
        return 2
    mode, rest = argv[0], argv[1:]
    everything = "--all" in rest
    names = {a for a in rest if not a.startswith("--")}
    chosen = [e for e in entries() if (e.name in names if names else everything or e.quick)]
    bad = 0
    with tempfile.TemporaryDirectory() as tmp:
        for e in chosen:
            log = fly(e, Path(tmp))
            if mode == "write":
                write(e, log)
                print(f"wrote {e.path.relative_to(ROOT)} ({len(log) - 1} runs)")
                continue
            diff = differences(read(e), log)
            bad += bool(diff)
            print(f"{e.name}: {'the record' if not diff else f'{len(diff)} differences'}")
            for d in diff[:20]:
                print(f"  {d}")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
