#!/usr/bin/env python3
"""`make test-wheel` (in `make test`; docs/guides/install.md): ogk as an analyst installs it, outside the repository.

1. `python -m build`: the sdist, then the wheel built from it (setup.py compiles the kernel and the
   families' extensions), into OUT/dist;
2. a clean venv, OUT/venv, and `pip install` of the wheel alone (its dependencies from the index or
   pip's cache; no extra);
3. from a temporary directory outside the repository, with the venv's `ogk`:
   * `ogk --version` is version.h's;
   * `ogk mc leo-geo --runs 4 --seed 1 --json F`: exit 0, F an envelope (ogk.campaign/1) of 4 runs,
     its scenario the wheel's copy, its tables made under the directory (build/tables);
   * `ogk run apophis_cubesat --case thrust --param=3 --json G`: exit 0, G the one case, converged,
     with its fuel increase over the fuel-optimal reference (the shipped cache's);
   * what needs the repository or an extra says so in one line, exit 2: `ogk mc leo-geo --target m7`
     and `ogk mc leo-geo --dask local:1` (Dask is the extra ogk[dask], not installed here).
Each step's time is printed; the first failure ends the check (exit 1) with its last lines.

Usage: check_wheel.py [--out DIR]   (run with the repository's venv: it has `build`)
"""
from __future__ import annotations

import argparse
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
VERSION_H = ROOT / "kernel" / "include" / "ogk" / "version.h"


class Failed(Exception):
    pass


def step(title: str, cmd: list[str], cwd: Path, expect: int = 0, log: Path | None = None,
         env: dict[str, str] | None = None) -> subprocess.CompletedProcess[str]:
    start = time.monotonic()
    proc = subprocess.run(cmd, cwd=cwd, capture_output=True, text=True, env=env)
    took = time.monotonic() - start
    if log is not None:
        log.write_text(proc.stdout + proc.stderr)
    if proc.returncode != expect:
        tail = "\n".join((proc.stdout + proc.stderr).strip().splitlines()[-15:])
        raise Failed(f"{title}: exit {proc.returncode}, expected {expect} ({' '.join(cmd)})\n{tail}")
    print(f"test-wheel: {title}: {took:.1f} s")
    return proc


def version() -> str:
    text = VERSION_H.read_text()
    return ".".join(re.search(rf"^#define OGK_VERSION_{p} +(\d+)", text, re.M).group(1)  # type: ignore[union-attr]
                    for p in ("MAJOR", "MINOR", "PATCH"))


def check(out: Path) -> None:
    start = time.monotonic()
    shutil.rmtree(out, ignore_errors=True)       # the last check's venv too: the next one is clean
    out.mkdir(parents=True)
    print(f"test-wheel: {out} emptied: {time.monotonic() - start:.1f} s")
    step("python -m build (sdist, then the wheel from it)",
         [sys.executable, "-m", "build", "--outdir", str(out / "dist"), str(ROOT)], ROOT,
         log=out / "build.log")
    wheels = sorted((out / "dist").glob("ogk-*.whl"))
    if len(wheels) != 1:
        raise Failed(f"python -m build: {len(wheels)} wheels in {out / 'dist'}")
    wheel = wheels[0]
    names = subprocess.run([sys.executable, "-m", "zipfile", "-l", str(wheel)], capture_output=True,
                           text=True, check=True).stdout
    shipped = sorted(set(re.findall(r"ogk_host/scenarios/(\w+)\.toml", names)))
    expected = sorted(p.stem for p in (ROOT / "scenarios").glob("*.toml"))
    if shipped != expected:
        raise Failed(f"{wheel.name}: ships the scenarios {shipped}, not scenarios/'s {expected}")
    print(f"test-wheel: {wheel.name}: {wheel.stat().st_size / 1e6:.2f} MB, {len(shipped)} scenarios")

    venv = out / "venv"
    step("clean venv", [sys.executable, "-m", "venv", str(venv)], out)
    step("pip install the wheel", [str(venv / "bin" / "python"), "-m", "pip", "install", "-q",
                                   "--disable-pip-version-check", str(wheel)], out,
         log=out / "pip.log")
    ogk = str(venv / "bin" / "ogk")
    # the venv's own environment only: nothing of the repository's venv or sources
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "VIRTUAL_ENV", "PYTHONHOME")}
    env["PATH"] = f"{venv / 'bin'}{os.pathsep}{env.get('PATH', '')}"
    with tempfile.TemporaryDirectory(prefix="ogk-wheel-") as tmp:
        work = Path(tmp)
        if ROOT in work.resolve().parents:
            raise Failed(f"{work} is inside the repository")
        got = step("ogk --version", [ogk, "--version"], work, env=env).stdout.strip()
        if got != f"ogk {version()}":
            raise Failed(f"ogk --version printed {got!r}, not 'ogk {version()}' (version.h)")

        f = work / "F.json"
        step("ogk mc leo-geo --runs 4", [ogk, "mc", "leo-geo", "--runs", "4", "--seed", "1",
                                         "--json", str(f)], work, log=out / "mc.log", env=env)
        doc = json.loads(f.read_text())
        if doc.get("schema") != "ogk.campaign/1" or doc.get("runs") != 4:
            raise Failed(f"{f.name}: schema {doc.get('schema')!r}, runs {doc.get('runs')!r}: not an "
                         "ogk.campaign/1 envelope of 4 runs")
        scenario = str(doc.get("scenario_path", ""))
        if "site-packages/ogk_host/scenarios/leo_geo.toml" not in scenario:
            raise Failed(f"{f.name}: scenario {scenario!r} is not the wheel's copy")
        if not any((work / "build" / "tables").glob("leo_geo-*/manifest.json")):
            raise Failed(f"no tables under {work / 'build' / 'tables'}")
        print(f"test-wheel:   {f.name}: {doc['runs']} runs, {len(doc.get('failures') or [])} failed")

        g = work / "G.json"
        proc = step("ogk run apophis_cubesat --case thrust --param=3",
             [ogk, "run", "apophis_cubesat", "--case", "thrust", "--param=3", "--json", str(g)], work,
             log=out / "run.log", env=env)
        case = json.loads(g.read_text())
        if not isinstance(case, dict) or case.get("converged") is not True \
                or case.get("fuel_increase_pct") is None:
            raise Failed(f"{g.name}: not one converged case with its fuel-optimal reference: {case}")
        reference = [line for line in proc.stdout.splitlines() if line.startswith("fuel-optimal")]
        print(f"test-wheel:   {g.name}: converged in {case['newton_iterations']} iterations, final mass "
              f"{case['final_mass_kg']:.4f} kg, FI {case['fuel_increase_pct']:.3f} %; "
              + (reference[0] if reference else "no reference line"))

        for what, args, needs in (
                ("--target m7", ["--target", "m7"], "needs the ogk repository"),
                ("--dask local:1", ["--dask", "local:1"], "ogk[dask] is needed for ogk mc --dask: "
                                                          "pip install 'ogk[dask]'")):
            proc = step(f"ogk mc leo-geo {what} (exit 2)", [ogk, "mc", "leo-geo", "--runs", "1", *args,
                                                           "--json", str(work / "x.json")],
                        work, expect=2, env=env)
            lines = proc.stderr.strip().splitlines()
            if len(lines) != 1 or needs not in lines[0]:
                raise Failed(f"ogk mc leo-geo {what}: stderr {proc.stderr.strip()!r}, not one line "
                             f"saying {needs!r}")
            print(f"test-wheel:   {lines[0]}")


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", type=Path, default=ROOT / "build" / "wheel",
                    help="the wheel, the clean venv and the logs (default build/wheel)")
    args = ap.parse_args()
    start = time.monotonic()
    try:
        check(args.out.resolve())
    except Failed as err:
        print(f"test-wheel: FAILED: {err}", file=sys.stderr)
        return 1
    print(f"test-wheel: passed in {time.monotonic() - start:.0f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
