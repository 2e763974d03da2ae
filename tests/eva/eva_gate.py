"""Frama-C EVA over the kernel's public entry points (`make eva`, run by `make test`).

Each driver of DRIVERS (tests/eva/drv_*.c) calls the public functions of one module with the ranges
their contracts allow (the ACSL `requires` of kernel/include/ogk/*.h, Frama_C_*_interval values).
EVA runs once per driver; this script parses its report and counts, per driver:

- the alarms EVA emits (`[eva:alarm]`: a possible run-time error: overflow, division by zero,
  invalid memory access, uninitialised read, a non-finite double), and
- the logical properties it cannot prove or finds false (preconditions of the kernel's and libm's
  contracts, tests/eva/libm_spec.h; assertions),

and fails when a driver's count exceeds tests/eva/baseline.json (the baseline may only go down,
`--update` lowers it), when a driver of ZERO has any, or when a driver does not reach the end of its
main function (an analysis that stops early proves nothing). docs/evidence/eva.md lists the remaining alarms.
"""
from __future__ import annotations

import argparse
import concurrent.futures
import json
import re
import shutil
import signal
import subprocess
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
BASELINE = ROOT / "tests" / "eva" / "baseline.json"
K = "kernel/src/"


@dataclass(frozen=True)
class Driver:
    name: str                  # the driver's main function, eva_<name>
    sources: tuple[str, ...]   # kernel sources analysed with it
    driver: str                # tests/eva/drv_*.c
    options: tuple[str, ...] = field(default=())
    defines: tuple[str, ...] = field(default=())  # -D of the kernel's compile-time sizes (small for EVA)


# The modules whose drivers must stay at zero (issue 22, item 3).
ZERO = {"crc32", "mathutil", "status", "rk4", "cpd", "terminal", "cutoff", "interp", "nog", "linalg"}

DRIVERS = (
    Driver("crc32", (K + "core/crc32.c",), "drv_core.c"),
    Driver("mathutil", (K + "core/mathutil.c",), "drv_core.c"),
    Driver("status", (K + "core/status.c",), "drv_core.c"),
    Driver("interp", (K + "core/interp.c",), "drv_interp.c"),
    Driver("rk4", (K + "core/rk4.c",), "drv_rk4.c"),
    Driver("linalg", (K + "core/linalg.c", K + "core/chol.c"), "drv_linalg.c"),
    Driver("cutoff", (K + "nog/cutoff.c",), "drv_cutoff.c"),
    Driver("terminal", (K + "nog/terminal.c", K + "contract/thrust_cmd.c"), "drv_terminal.c"),
    Driver("cpd", (K + "cpd/cpd.c", K + "contract/thrust_cmd.c"), "drv_cpd.c"),
    Driver("nog", (K + "nog/nog.c", K + "core/interp.c", K + "core/linalg.c", K + "core/chol.c", K + "core/table.c", K + "core/crc32.c",
                   K + "contract/thrust_cmd.c"), "drv_nog.c"),
    Driver("qp", (K + "qp/qp.c", K + "qp/qp_blas.c", K + "core/chol.c"), "drv_qp.c"),
    Driver("mpsp", (K + "mpsp/mpsp.c", K + "mpsp/mpsp_adjoint.c", K + "mpsp/mpsp_bv.c", K + "mpsp/mpsp_control.c", K + "mpsp/mpsp_dynamics.c",
                    K + "mpsp/mpsp_propagate.c", K + "mpsp/mpsp_sensitivity.c", K + "core/rk4.c", K + "core/linalg.c", K + "core/chol.c", K + "core/newton.c",
                    K + "core/interp.c", K + "contract/thrust_cmd.c"),
           "drv_mpsp.c", defines=("OGK_MPSP_MAX_ORDER=1u", "OGK_MPSP_MAX_STEPS=2u", "OGK_MPSP_MAX_SWITCHES=2u",
                                  "OGK_MPSP_SENS_BLOCK=3u", "OGK_MPSP_MAX_LOG=4u", "OGK_RK4_MAX_SWITCHES=2u")),
    Driver("nmpc", (K + "nmpc/nmpc.c", K + "nmpc/nmpc_condense.c", K + "nmpc/nmpc_hess.c", K + "nmpc/nmpc_keepout.c", K + "nmpc/nmpc_model.c",
                    K + "nmpc/nmpc_plan.c", K + "nmpc/nmpc_sens_cache.c", K + "nmpc/nmpc_shoot.c", K + "nmpc/nmpc_shoot_hess.c",
                    K + "nmpc/nmpc_sqp.c", K + "nmpc/nmpc_helio.c", K + "nmpc/nmpc_problem.c", K + "qp/qp.c", K + "qp/qp_blas.c",
                    K + "core/chol.c", K + "contract/thrust_cmd.c"),
           "drv_nmpc.c", defines=("OGK_NMPC_MAX_NODES=2u", "OGK_NMPC_MAX_RK4_STEPS=2u", "OGK_QP_MAX_N=16u",
                                  "OGK_QP_MAX_EQ=4u", "OGK_QP_MAX_IN=17u")),
    Driver("blt", (K + "blt/blt.c", K + "blt/blt_arc.c", K + "blt/blt_model.c", K + "core/linalg.c", K + "core/chol.c", K + "core/newton.c",
                   K + "contract/thrust_cmd.c"),
           "drv_blt.c", defines=("OGK_BLT_MAX_SEGMENTS=1u", "OGK_BLT_MAX_SEGMENT_STEPS=4u")),
)

#: a driver's budget in CPU seconds (RLIMIT_CPU: the analysis is single-threaded, and CPU time does
#: not stretch on a crowded machine as wall time does: the QP driver took 68 s of CPU and 496 s of
#: wall at load 5-9, next to the former 300 s wall limit); wall time only as a backstop
TIMEOUT_S = 300
WALL_BACKSTOP_S = 3600


def _cpu_limit() -> None:
    import resource
    resource.setrlimit(resource.RLIMIT_CPU, (TIMEOUT_S, TIMEOUT_S + 10))
COMMON = ("-eva", "-machdep", "x86_32", "-eva-precision", "3", "-eva-split-return", "auto")
CPP = "-cpp-extra-args=-Ikernel/include -Ikernel/src -Itests/eva -DOGK_EVA"
ALARM = re.compile(r"^\[eva:alarm\] (?P<where>[^:]+:\d+): Warning:\s*(?P<what>.*)$")
PROP = re.compile(r"^\s*(?P<kind>Assertions|Preconditions)\s+(?P<valid>\d+) valid\s+(?P<unknown>\d+) "
                  r"unknown\s+(?P<invalid>\d+) invalid")


def run(d: Driver) -> dict:
    # one -cpp-extra-args (Frama-C keeps only the last one given)
    cpp = " ".join((CPP, *("-D" + x for x in d.defines)))
    cmd = ["frama-c", *COMMON, cpp, *d.options, *d.sources, "tests/eva/" + d.driver, "-main", "eva_" + d.name]
    t0 = time.monotonic()
    try:
        proc = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True, check=False,
                              timeout=WALL_BACKSTOP_S, preexec_fn=_cpu_limit)
    except subprocess.TimeoutExpired:
        return {"name": d.name, "rc": -1, "alarms": [], "unproven": 0, "unproven_lines": [],
                "finished": False, "secs": float(WALL_BACKSTOP_S), "reached": "?",
                "cmd": " ".join(cmd), "tail": f"timed out after {WALL_BACKSTOP_S} s of wall time"}
    secs = time.monotonic() - t0
    if proc.returncode in (-signal.SIGXCPU, -signal.SIGKILL):
        return {"name": d.name, "rc": proc.returncode, "alarms": [], "unproven": 0,
                "unproven_lines": [], "finished": False, "secs": secs, "reached": "?",
                "cmd": " ".join(cmd), "tail": f"stopped after {TIMEOUT_S} s of CPU time"}
    out = proc.stdout + proc.stderr
    lines = out.splitlines()
    alarms = []
    unproven_lines = []
    for i, line in enumerate(lines):
        m = ALARM.match(line)
        if m:
            what = m["what"]
            # the alarm's annotation is on the following indented line(s)
            j = i + 1
            while j < len(lines) and lines[j].startswith("  ") and not lines[j].startswith("  ---"):
                what += " " + lines[j].strip()
                j += 1
            # an unproven precondition is reported as an alarm too: counted once, with the
            # summary's unknown/invalid properties below
            if "precondition" in what or "assertion" in what:
                unproven_lines.append(f"{m['where']}: {what}")
            else:
                alarms.append(f"{m['where']}: {what}")
    unproven = 0
    for line in lines:
        m = PROP.match(line)
        if m:
            unproven += int(m["unknown"]) + int(m["invalid"])
    # reaching the end of the driver: its final-states section exists and is not
    # "NON TERMINATING FUNCTION" (every path cut, e.g. by an infinity EVA proves)
    end = out.split(f"Values at end of function eva_{d.name}:", 1)
    finished = len(end) == 2 and not end[1].lstrip().startswith("NON TERMINATING")
    reach = re.search(r"(\d+) statements reached \(out of (\d+)\)", out)
    reached = f"{reach[1]}/{reach[2]} stmts" if reach else "?"
    return {"name": d.name, "rc": proc.returncode, "alarms": alarms, "unproven": unproven,
            "unproven_lines": unproven_lines, "finished": finished, "secs": secs, "reached": reached,
            "cmd": " ".join(cmd), "tail": "\n".join(lines[-40:])}


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--update", action="store_true", help="lower the baseline to today's counts")
    ap.add_argument("--init", action="store_true", help="write the baseline from scratch")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--only", nargs="*", help="run only these drivers (no gate, prints the alarms)")
    args = ap.parse_args(argv)
    if shutil.which("frama-c") is None:
        print("eva: frama-c not found (frama-c-base, APT_PKGS)", file=sys.stderr)
        return 1
    drivers = [d for d in DRIVERS if not args.only or d.name in args.only]
    t0 = time.monotonic()
    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        results = list(pool.map(run, drivers))
    baseline = json.loads(BASELINE.read_text()) if BASELINE.exists() else {}
    failed = False
    counts = {}
    unfinished = {r["name"] for r in results if r["rc"] != 0 or not r["finished"]}
    for r in results:
        n = len(r["alarms"]) + r["unproven"]
        counts[r["name"]] = n
        base = baseline.get(r["name"])
        verdict = "ok"
        if r["rc"] != 0 or not r["finished"]:
            verdict = "FAIL (analysis did not finish)"
        elif r["name"] in ZERO and n > 0:
            verdict = "FAIL (must be zero)"
        elif not args.init and (base is None or n > base):
            verdict = f"FAIL (baseline {base})"
        elif base is not None and n < base:
            verdict = f"ok (below baseline {base}: --update)"
        failed |= verdict.startswith("FAIL")
        print(f"eva: {r['name']:<14} {len(r['alarms']):3d} alarms {r['unproven']:3d} unproven "
              f"{r['reached']:>13} ({r['secs']:5.1f} s) {verdict}")
        if n and (verdict.startswith("FAIL") or args.only):
            for a in r["alarms"]:
                print(f"    alarm: {a}")
            for u in r["unproven_lines"]:
                print(f"    unproven: {u}")
        if r["rc"] != 0 or not r["finished"]:
            print(f"    command: {r['cmd']}\n" + r["tail"])
    print(f"eva: {len(results)} drivers, {sum(counts.values())} alarms+unproven in all, "
          f"{time.monotonic() - t0:.0f} s")
    if args.only:
        return 1 if failed else 0
    if args.init or args.update:
        new = dict(baseline)
        for name, n in counts.items():
            if name in unfinished:
                continue  # an analysis that stopped early counted nothing: keep its baseline
            if args.init or n < new.get(name, n + 1):
                new[name] = n
        BASELINE.write_text(json.dumps(dict(sorted(new.items())), indent=1) + "\n")
        print(f"eva: baseline written ({BASELINE.relative_to(ROOT)})")
        return 0
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
