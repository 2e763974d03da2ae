"""`ogk soak [PLAN]`: every campaign of the soak plan (default soak.toml at the repository root) flown by
`ogk mc` in its own process, its envelope judged against the law's stated envelope, and the summary per
family (ogk.sil.soak; docs/guides/campaigns.md, "make soak"). Outputs under --out (default build/soak/):
<name>.json, .parquet, .txt (the campaign's report). Exit 0 when no campaign lost a flight its law does
not state and none aborted, 1 otherwise."""
from __future__ import annotations

import argparse
import json
import subprocess
import sys
import time
from pathlib import Path
from typing import Any

OGK = [sys.executable, "-c", "import sys; from ogk.cli import main; sys.exit(main())"]


def register(sub: Any) -> None:
    p = sub.add_parser("soak", help="long campaigns of every family, judged against their stated envelopes",
                       description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("plan", nargs="?", default=None, metavar="PLAN",
                   help="the soak plan (default: soak.toml at the repository root)")
    p.add_argument("--out", default="build/soak", metavar="DIR", help="output directory (default build/soak)")
    p.add_argument("--workers", type=int, default=2, help="parallel processes per campaign (default 2)")
    p.add_argument("--only", nargs="+", default=None, metavar="NAME",
                   help="fly only these campaigns of the plan")
    p.add_argument("--runs", type=int, default=None, metavar="N",
                   help="every campaign at N runs instead of the plan's (a quick check of the soak itself)")
    p.set_defaults(func=_soak)


def _soak(args: argparse.Namespace) -> int:
    from ogk_bindings.errors import OgkInputError

    from ogk.sil import soak
    from ogk.sil.outputs import check_output_dir
    plan = soak.load_plan(args.plan or soak.default_plan())
    if args.only:
        unknown = sorted(set(args.only) - {c.name for c in plan})
        if unknown:
            raise OgkInputError(f"no campaign {unknown[0]!r} in the plan", key="--only")
        plan = [c for c in plan if c.name in args.only]
    if args.workers < 1 or (args.runs is not None and args.runs < 1):
        raise OgkInputError("must be >= 1", key="--workers" if args.workers < 1 else "--runs")
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    check_output_dir(str(out), "--out")
    done = []
    bad = 0
    for c in plan:
        runs = args.runs or c.runs
        env = out / f"{c.name}.json"
        cmd = ["mc", c.scenario, "--runs", str(runs), "--seed", str(c.seed), "--workers",
               str(args.workers), "--json", str(env), *c.options]
        print(f"ogk {' '.join(cmd)}", flush=True)
        start = time.perf_counter()
        with open(out / f"{c.name}.txt", "w", encoding="utf-8") as log:
            code = subprocess.run([*OGK, *cmd], stdout=log, stderr=subprocess.STDOUT).returncode
        wall = time.perf_counter() - start
        doc = json.loads(env.read_text()) if code in (0, 1) and env.is_file() else None
        if doc is None:
            bad += 1
            done.append((c, None, f"ogk mc exit {code}; see {out / (c.name + '.txt')}", wall))
            print(f"  aborted (exit {code}), {wall:.0f} s", flush=True)
            continue
        why = soak.violations(doc, c.stated)
        bad += bool(why)
        done.append((c, doc, "; ".join(why), wall))
        print(f"  {doc['robustness']['lost_flights']} of {doc['runs']} lost, {wall:.0f} s"
              + (f": {'; '.join(why)}" if why else ""), flush=True)
    print()
    print(soak.family_summary(done))
    print(f"\n{len(done) - bad} of {len(done)} campaigns within their stated envelopes")
    return 0 if bad == 0 else 1
