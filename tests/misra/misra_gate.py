"""MISRA C:2012 ratchet over kernel/ (`make misra`, run by `make lint`).

Runs cppcheck's misra addon (rule numbers only: the rule texts are not shipped) over kernel/src and
compares the findings, counted per (file, rule), with tests/misra/baseline.json:

- a count above its baseline, or a rule in a file that had none, fails the gate and is listed line by
  line: new code is born under MISRA;
- a count below its baseline is reported, and `--update` writes the lower count (the baseline only
  ever goes down; `--update` refuses to raise it).

The baseline is the debt still to pay (docs/evidence/misra-deviations.md says which rules are to be fixed and
which are deviations with their rationale); the target is an empty baseline plus recorded deviations.
"""
from __future__ import annotations

import argparse
import hashlib
import json
import shutil
import re
import subprocess
import sys
from collections import Counter
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
BASELINE = ROOT / "tests" / "misra" / "baseline.json"
FINDING = re.compile(r"^(?P<file>[^:]+):(?P<line>\d+):misra-c2012-(?P<rule>[\d.]+)$")


def run_cppcheck(build: Path) -> list[tuple[str, int, str]]:
    sources = sorted(str(p.relative_to(ROOT)) for p in (ROOT / "kernel" / "src").rglob("*.c"))
    # the addon's dump files go to build, not next to the sources
    fresh_cache(build)
    proc = subprocess.run(
        ["cppcheck", "--std=c99", "--addon=misra", "--quiet", "-Ikernel/include", "-Ikernel/src",
         f"--cppcheck-build-dir={build}",
         "--template={file}:{line}:{id}", *sources],
        cwd=ROOT, capture_output=True, text=True, check=False)
    found = []
    for line in proc.stderr.splitlines():
        m = FINDING.match(line.strip())
        if m:
            found.append((m["file"], int(m["line"]), m["rule"]))
        elif "misra" in line and "error" in line.lower():
            raise SystemExit(f"misra: cppcheck failed: {line}")
    if proc.returncode != 0:
        raise SystemExit(f"misra: cppcheck exited {proc.returncode}: {proc.stderr[-500:]}")
    blind = unanalysed(build, sources)
    if blind:
        raise SystemExit("misra: cppcheck analysed no code of " + ", ".join(blind) + " (a #error or a "
                         "preprocessing failure stopped it, and the addon then finds nothing there)")
    return found


def fresh_cache(build: Path) -> None:
    """cppcheck's build directory caches each source's results keyed on that source alone: a header
    whose lines moved left stale findings (seen twice: a false rule 8.5, 28 spurious findings). The
    directory is emptied whenever any kernel header changed since it was filled."""
    headers = sorted((ROOT / "kernel").rglob("*.h"))
    digest = hashlib.sha256()
    for h in headers:
        digest.update(str(h.relative_to(ROOT)).encode() + b"\0" + h.read_bytes())
    stamp = build / "headers.sha256"
    if stamp.is_file() and stamp.read_text() == digest.hexdigest():
        return
    shutil.rmtree(build, ignore_errors=True)
    build.mkdir(parents=True, exist_ok=True)
    stamp.write_text(digest.hexdigest())


def unanalysed(build: Path, sources: list[str]) -> list[str]:
    """Sources whose dump holds raw tokens only: cppcheck stopped before its token list (an #error
    it hit, e.g. a guard testing a macro it cannot see), so a zero count there would mean nothing."""
    out = []
    for src in sources:
        dumps = sorted(build.glob(Path(src).stem + ".a*.dump"))
        if not dumps or not any("<token " in d.read_text(errors="replace") for d in dumps):
            out.append(src)
    return out


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--update", action="store_true", help="lower the baseline to today's counts")
    ap.add_argument("--init", action="store_true", help="write the baseline from scratch")
    ap.add_argument("--build", type=Path, default=ROOT / "build" / "misra",
                    help="cppcheck's build directory (default build/misra)")
    args = ap.parse_args(argv)
    found = run_cppcheck(args.build.resolve())
    counts = Counter(f"{f}|{r}" for f, _, r in found)
    by_rule = Counter(r for _, _, r in found)
    print(f"misra: {len(found)} findings over kernel/src ("
          + ", ".join(f"{r}: {n}" for r, n in by_rule.most_common()) + ")")
    if args.init:
        BASELINE.write_text(json.dumps(dict(sorted(counts.items())), indent=1) + "\n")
        print(f"misra: baseline written ({len(found)} findings)")
        return 0
    base: dict[str, int] = json.loads(BASELINE.read_text())
    worse = {k: (n, base.get(k, 0)) for k, n in counts.items() if n > base.get(k, 0)}
    better = {k: (counts.get(k, 0), b) for k, b in base.items() if counts.get(k, 0) < b}
    for key, (n, b) in sorted(worse.items()):
        file, rule = key.split("|")
        lines = sorted(ln for f, ln, r in found if f == file and r == rule)
        print(f"misra: NEW rule {rule} in {file}: {n} > baseline {b} (lines {', '.join(map(str, lines))})")
    if better:
        print(f"misra: {sum(b - n for n, b in better.values())} findings fewer than the baseline"
              + (" (baseline lowered)" if args.update else " (run with --update to lower it)"))
        if args.update and not worse:
            lowered = {k: v for k, v in base.items() if counts.get(k, 0) > 0}
            lowered.update({k: counts[k] for k in lowered})
            BASELINE.write_text(json.dumps(dict(sorted(lowered.items())), indent=1) + "\n")
    if worse:
        print(f"misra: FAILED: {sum(n - b for n, b in worse.values())} findings above the baseline "
              "(fix them, or record a deviation in docs/evidence/misra-deviations.md and justify raising it)")
        return 1
    print(f"misra: ok ({len(found)} findings, baseline {sum(base.values())})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
