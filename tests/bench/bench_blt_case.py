"""The cost of ogk_blt's NRPC (docs/design/blt.md, "Cost"): the benchmark cases as C, and the table.

    bench_blt_case.py header OUT.h          the cases as C (tests/bench/bench_blt.c includes it)
    bench_blt_case.py run [--figures DIR]   the kernel through cffi here (the same cases), plus the C bench's
                                            figures (host ms, callgrind, Cortex-M7, stack) read from DIR: one table

The cases come from the scenario through the ground pipeline, nothing typed by hand:
scenarios/moshup.toml, `transfers.solver_settings`, `transfer_spec`, `corrector_model` (the realistic model:
degree-2 gravity of both bodies, SRP, solar tide, mass flow; RK4 step <= 20 s = 2.0e-3 TU) and
`initial_guess` (SBIG or UbMPIG); the kernel configuration is `guess.kernel_config(model, guess.layout,
corrector=NRPC, jacobian=..., **solver.kernel_fields())` (tol 1e-6, max_iter 40, fd_step 1e-6, 4 step lengths:
the scenario's [solver]), the guess `guess.transfer`. Two transfers:

    sb   l2_to_l1_lyapunov   single burn, StoS (eq. 65): 7 unknowns, 6 errors
    ump  circle_to_l2_ump    Table 3's burn-coast-burn, a free node mid-coast (eq. 70): 22 unknowns, 12 errors

each with the central-difference Jacobian (cd, eq. 62) and the variational one (var), NRPC (eq. 64 and the
paper's 1/10 step-length search). The paper's timing (sec. VI): 14 s for 11 NRPC iterations in MATLAB on an
i7-10750H at 2.6 GHz, 1.27 s per iteration, for "the shortest transfer in Fig. 11d" (the UMP transfer to the L2
Lyapunov orbit, at 1.5 mN; ump is that geometry at Table 3's 30 mN); the goal is 1000x that per iteration,
i.e. < 1.3 ms.
"""
from __future__ import annotations

import argparse
import math
import statistics
import sys
import time
from pathlib import Path
from typing import Any

import numpy as np

from bench_figures import read_figures
from ogk_bindings.blt import CENTRAL, MAX_FREE_NODES, MAX_SEGMENTS, NRPC, NX, VARIATIONAL, Blt, BltConfig, Transfer
from ogk_host.binary import transfers as T
from ogk_host.binary.guess import kernel_config
from ogk_host.binary.scenario import load_scenario

SCENARIO = "scenarios/moshup.toml"
TRANSFERS = (("sb", "l2_to_l1_lyapunov"), ("ump", "circle_to_l2_ump"))
JACS = (("cd", CENTRAL, "central (eq. 62)"), ("var", VARIATIONAL, "variational"))
PAPER_S_PER_ITER = 14.0 / 11.0     #: [s] sec. VI: 14 s, 11 iterations, MATLAB, i7-10750H 2.6 GHz
GOAL_RATIO = 1000.0


# ------------------------------------------------------------------------------------------------ the cases
def cases() -> list[dict[str, Any]]:
    """One entry per (transfer, Jacobian): key, transfer name, Jacobian, kernel configuration, guess."""
    sc = load_scenario(SCENARIO)
    so = T.solver_settings(sc)
    out = []
    for short, name in TRANSFERS:
        spec = T.transfer_spec(sc, name)
        model = T.corrector_model(sc, spec, so)
        guess = T.initial_guess(sc, spec, model)
        for jshort, jac, jlabel in JACS:
            cfg = kernel_config(model, guess.layout, corrector=NRPC, jacobian=jac, **so.kernel_fields())
            out.append(dict(key=f"{short}_{jshort}", transfer=name, jacobian=jlabel, cfg=cfg,
                            guess=guess.transfer))
    return out


def _c_double(v: float) -> str:
    return float(v).hex() if math.isfinite(v) else "(1.0 / 0.0)"


def _config_lines(prefix: str, d: dict[str, Any]) -> list[str]:
    """Assignments of every field of `d` (as_dict of a BltConfig; nested dicts: nested structs)."""
    lines: list[str] = []
    for name, value in d.items():
        if isinstance(value, dict):
            lines += _config_lines(f"{prefix}{name}.", value)
        elif isinstance(value, np.ndarray):
            for i, v in enumerate(value.reshape(-1)):
                if np.issubdtype(value.dtype, np.floating):
                    lines.append(f"    {prefix}{name}[{i}] = {_c_double(float(v))};")
                else:
                    lines.append(f"    {prefix}{name}[{i}] = {int(v)}u;")
        elif isinstance(value, float):
            lines.append(f"    {prefix}{name} = {_c_double(value)}; /* {value!r} */")
        else:
            lines.append(f"    {prefix}{name} = {int(value)}u;")
    return lines


def _transfer_init(tr: Transfer) -> list[str]:
    seg = np.zeros((MAX_SEGMENTS, 7))
    s = np.asarray(tr.segments, dtype=np.float64).reshape(-1, 7)
    seg[:s.shape[0]] = s
    node = np.zeros((MAX_FREE_NODES, NX))
    n = np.asarray(tr.nodes, dtype=np.float64).reshape(-1, NX)
    node[:n.shape[0]] = n

    def row(v: Any) -> str:
        return "{" + ", ".join(_c_double(float(x)) for x in v) + "}"
    return ["    {",
            f"        {_c_double(tr.t0)}, /* t0 */",
            f"        {_c_double(tr.mass0)}, /* mass0 */",
            f"        {row(tr.x0)}, /* x0 */",
            f"        {row(tr.xf)}, /* xf */",
            "        {" + ",\n         ".join(row(r) for r in seg) + "}, /* seg: A, B, T */",
            "        {" + ",\n         ".join(row(r) for r in node) + "}, /* node */",
            "    }"]


def write_header(path: Path) -> None:
    """Every ogk_blt_config_t field of each case (hex floats: bit-exact) and its guess."""
    cs = cases()
    lines = [f"/* Generated by tests/bench/bench_blt_case.py header from {SCENARIO}: do not edit.",
             " * The NRPC cases of docs/design/blt.md, \"Cost\": every configuration field of",
             " * guess.kernel_config(model, layout, corrector=NRPC, jacobian=..., **solver.kernel_fields())",
             " * and the guess of transfers.initial_guess, bit-exact. */",
             "#ifndef BENCH_BLT_CASE_H", "#define BENCH_BLT_CASE_H", "",
             f"#define BENCH_BLT_NCASES {len(cs)}u", ""]
    for c in cs:
        lines += [f"/* {c['key']}: {c['transfer']}, {c['jacobian']} Jacobian, NRPC */",
                  f"static void bench_blt_config_{c['key']}(ogk_blt_config_t *c)", "{"]
        lines += _config_lines("c->", c["cfg"].as_dict())
        lines += ["}", "", f"static const ogk_blt_transfer_t bench_blt_guess_{c['key']} ="]
        lines += _transfer_init(c["guess"])
        lines[-1] += ";"
        lines.append("")
    lines += ["typedef struct {", "    const char *key;          /* <transfer>_<jacobian> */",
              "    const char *transfer;     /* [transfers.NAME] of the scenario */",
              "    void (*config)(ogk_blt_config_t *c);",
              "    const ogk_blt_transfer_t *guess;", "} bench_blt_case_t;", "",
              "static const bench_blt_case_t bench_blt_cases[BENCH_BLT_NCASES] = {"]
    lines += [f"    {{\"{c['key']}\", \"{c['transfer']}\", bench_blt_config_{c['key']}, &bench_blt_guess_{c['key']}}},"
              for c in cs]
    lines += ["};", "", "#endif /* BENCH_BLT_CASE_H */", ""]
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text("\n".join(lines))


# ------------------------------------------------------------------------------------------------ the table


def cffi_runs(cfg: BltConfig, guess: Transfer, reps: int) -> dict[str, Any]:
    """The whole convergence through cffi: median wall time of `reps` solves, the report."""
    k = Blt(cfg)
    times = []
    rep = None
    for _ in range(reps):
        start = time.perf_counter()
        _, rep = k.solve(guess)
        times.append(time.perf_counter() - start)
    assert rep is not None
    one = Blt(cfg.replace(max_iter=1))
    _, rep1 = one.solve(guess)
    return dict(rep=rep, wall_s=statistics.median(times), reps=reps, rep1=rep1)


def cpu_model() -> str:
    """The host's CPU as /proc/cpuinfo names it (what lscpu prints as "Model name")."""
    try:
        lines = Path("/proc/cpuinfo").read_text().splitlines()
    except OSError:
        return "unknown CPU"
    names = [ln.split(":", 1)[1].strip() for ln in lines if ln.startswith("model name")]
    mhz = [ln.split(":", 1)[1].strip() for ln in lines if ln.startswith("cpu MHz")]
    return f"{names[0] if names else 'unknown CPU'}, {len(names)} CPUs" + (f", {float(mhz[0]):.0f} MHz" if mhz else "")


def run(args: argparse.Namespace) -> int:
    cs = cases()
    fig = read_figures(args.figures, "blt")
    ok = True

    def num(key: str) -> float | None:
        return float(fig[key]) if key in fig else None

    def ms(key: str) -> str:
        v = num(key)
        return "-" if v is None else f"{v * 1e-6:.3f}"

    def count(key: str, unit: str = "") -> str:
        return f"{int(fig[key]):,}{unit}" if key in fig and fig[key].isdigit() else "-"

    print(f"== ogk_blt NRPC cost: {SCENARIO}, the realistic model (each transfer's RK4 step bound below); host "
          f"x86-64 gcc -O2, Cortex-M7 gcc -O2 (QEMU instruction counts) ==")
    head = f"{'':44s}" + "".join(f"{c['key']:>18s}" for c in cs)
    print(head)
    results = [cffi_runs(c["cfg"], c["guess"], args.reps) for c in cs]

    def row(label: str, cells: list[str]) -> None:
        print(f"{label:44s}" + "".join(f"{x:>18s}" for x in cells))
    row("unknowns x errors", [f"{r['rep'].n_unknowns} x {r['rep'].n_errors}" for r in results])
    row("RK4 step bound [TU]", [f"{float(c['cfg'].model['step_max']):.1e}" for c in cs])
    row("one iteration, host wall [ms]", [ms(f"blt_{c['key']}_iter_ns") for c in cs])
    row("one iteration, host CPU [ms]", [ms(f"blt_{c['key']}_iter_cpu_ns") for c in cs])
    row("one iteration, callgrind [instructions]", [count(f"blt_{c['key']}_iter_callgrind") for c in cs])
    row("one iteration, Cortex-M7 [instructions]", [count(f"blt_{c['key']}_iter_m7_insns") for c in cs])
    row("one iteration, propagations", [fig.get(f"blt_{c['key']}_iter_props", "-") for c in cs])
    row("convergence, host wall [ms]", [ms(f"blt_{c['key']}_conv_ns") for c in cs])
    row("convergence, host CPU [ms]", [ms(f"blt_{c['key']}_conv_cpu_ns") for c in cs])
    row("convergence, through cffi, wall [ms]", [f"{r['wall_s'] * 1e3:.3f}" for r in results])
    row("convergence, callgrind [instructions]", [count(f"blt_{c['key']}_conv_callgrind") for c in cs])
    row("convergence, Cortex-M7 [instructions]", [count(f"blt_{c['key']}_conv_m7_insns") for c in cs])
    row("convergence, iterations (C bench)", [fig.get(f"blt_{c['key']}_conv_iters", "-") for c in cs])
    row("convergence, iterations (cffi, Cortex-M7)",
        [f"{r['rep'].iterations}, {fig.get('blt_m7_' + c['key'] + '_conv_iters', '-')}" for c, r in zip(cs, results)])
    row("convergence, propagations", [fig.get(f"blt_{c['key']}_conv_props", "-") for c in cs])
    row("|e|: guess, converged", [f"{r['rep'].err_norm0:.1e}, {r['rep'].err_norm:.1e}" for r in results])
    row("Cortex-M7 stack, convergence (QEMU) [B]", [count(f"blt_m7_{c['key']}_conv_stack") for c in cs])
    print()
    for c, r in zip(cs, results):
        it = num(f"blt_{c['key']}_iter_cpu_ns")
        wall = num(f"blt_{c['key']}_iter_ns")
        if not r["rep"].converged:
            print(f"WARNING: {c['key']} did not converge through cffi ({r['rep'].status})")
            ok = False
        for src in (f"blt_{c['key']}_conv_iters", f"blt_m7_{c['key']}_conv_iters"):
            if src in fig and int(fig[src]) != r["rep"].iterations:
                print(f"WARNING: {c['key']}: {src} {fig[src]}, cffi {r['rep'].iterations}: not the same convergence")
                ok = False
        if it is not None:
            ratio = PAPER_S_PER_ITER / (it * 1e-9)
            ratio_wall = PAPER_S_PER_ITER / (wall * 1e-9) if wall else float("nan")
            print(f"ratio {c['key']:7s} paper 1.27 s / {it * 1e-6:.3f} ms (host CPU per iteration) = {ratio:,.0f}x "
                  f"(wall: {ratio_wall:,.0f}x); goal >= {GOAL_RATIO:,.0f}x (< 1.3 ms): "
                  f"{'MET' if ratio >= GOAL_RATIO else 'NOT MET'}")
    print("(the paper's 1.27 s per iteration: Fig. 11d, the UMP transfer at 1.5 mN, MATLAB on an i7-10750H 2.6 GHz; "
          f"here: {cpu_model()})")
    print(f"sizeof(ogk_blt_t) {count('blt_sizeof_ctx', ' B')} host, {count('blt_m7_sizeof_ctx', ' B')} Cortex-M7 "
          f"(static storage); sizeof(ogk_blt_transfer_t) {count('blt_sizeof_transfer', ' B')}")
    print(f"Cortex-M7 stack, static worst case (stack_report.py): ogk_blt_solve {count('blt_stack_solve', ' B')}, "
          f"ogk_blt_jacobian {count('blt_stack_jacobian', ' B')}, "
          f"ogk_blt_evaluate {count('blt_stack_evaluate', ' B')}; "
          f"measured on QEMU, the whole run's high-water mark {count('blt_m7_stack_hwm', ' B')}")
    print(f"(one iteration = ogk_blt_solve with max_iter = 1 from the guess: the guess's evaluation, one Jacobian, "
          f"one minimum-norm step, its line-search trials; medians of up to {fig.get('blt_reps_max', '-')} repetitions "
          f"in C, {args.reps} through cffi)")
    return 0 if ok else 1


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = p.add_subparsers(dest="cmd", required=True)
    h = sub.add_parser("header")
    h.add_argument("out", type=Path)
    r = sub.add_parser("run")
    r.add_argument("--figures", type=Path, default=None, help="directory of the C bench's *.txt figures")
    r.add_argument("--reps", type=int, default=11, help="cffi repetitions of each whole convergence")
    args = p.parse_args(argv)
    if args.cmd == "header":
        write_header(args.out)
        return 0
    return run(args)


if __name__ == "__main__":
    sys.exit(main())
