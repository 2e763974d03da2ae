"""ogk_qp_solve against DAQP and qpOASES on two sets of QPs (`make bench-qp`, docs/design/qp.md).

Sets: (a) "nmpc": every QP that `bench_nmpc once` hands to ogk_qp_solve (the open loop, then the one
warm re-solve), recorded by a build of tests/bench/bench_nmpc.c wrapped around ogk_qp_solve
(tests/bench/bench_qp_record.c); (b) "random": RANDOM_COUNT strictly convex QPs, n = 16-67,
4 equalities, 2-10 rows, bounds on a third of the variables, from tests/python/test_qp.py's
generator with seed RANDOM_SEED.

Timing, per QP the median of --reps solves, CPU time of the process:
  C      the kernel and DAQP (its C sources from the PyPI sdist, same compiler and -O2) called from
         one C program (tests/bench/bench_qp_peers.c) on the same arrays, alternately; DAQP through
         daqp_quadprog, its one-shot entry (setup, solve, its own malloc/free: what daqp.solve does)
  Python the kernel through cffi, daqp.solve and qpOASES (casadi.conic(..., 'qpoases'), dense) on
         pre-built arrays; each call pays its binding's overhead (cffi's is the smallest)
Per set: the median over the QPs of the per-QP medians, the ratio kernel / peer of those medians, the
median of the per-QP ratios, and the largest objective difference (absolute, and relative to
max(1, |f|)). Then callgrind: the kernel's instructions over the whole set (deterministic).
"""
from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tests" / "python"))

RANDOM_SEED = 21
RANDOM_COUNT = 100


def write_qp(f, n, H, g, A_eq, b_eq, A_in, b_in, lb, ub) -> None:
    np.array([n, len(b_eq), len(b_in)], dtype=np.int32).tofile(f)
    for a in (H, g, A_eq, b_eq, A_in, b_in, lb, ub):
        np.ascontiguousarray(a, dtype=float).tofile(f)


def read_set(path: Path):
    """The QPs of a set file as test_qp.QP objects."""
    from test_qp import QP

    raw = path.read_bytes()
    pos = 0
    out = []
    while pos < len(raw):
        n, me, mi = (int(v) for v in np.frombuffer(raw, dtype=np.int32, count=3, offset=pos))
        pos += 12
        parts = []
        for k in (n * n, n, me * n, me, mi * n, mi, n, n):
            parts.append(np.frombuffer(raw, dtype=float, count=k, offset=pos).copy())
            pos += 8 * k
        H, g, A_eq, b_eq, A_in, b_in, lb, ub = parts
        out.append(QP(H.reshape(n, n), g, A_eq, b_eq, A_in, b_in, lb, ub))
    return out


def make_random(path: Path) -> None:
    from test_qp import random_qp

    rng = np.random.default_rng(RANDOM_SEED)
    with path.open("wb") as f:
        for _ in range(RANDOM_COUNT):
            n = int(rng.integers(16, 68))
            qp = random_qp(rng, n, m_eq=4, m_in=int(rng.integers(2, 11)))
            write_qp(f, qp.n, qp.H, qp.g, qp.A_eq, qp.b_eq, qp.A_in, qp.b_in, qp.lb, qp.ub)


def record_nmpc(recorder: Path, path: Path) -> None:
    path.unlink(missing_ok=True)
    env = dict(os.environ, OGK_QP_RECORD=str(path))
    subprocess.run([str(recorder), "once"], check=True, env=env, cwd=ROOT,
                   stdout=subprocess.DEVNULL)


def c_timings(peers: Path, path: Path, reps: int):
    """Per QP: (status, t_ogk_ns, t_daqp_ns, f_ogk, f_daqp, daqp exitflag)."""
    out = subprocess.run([str(peers), "time", str(path), str(reps)], check=True,
                         capture_output=True, text=True).stdout
    rows = []
    for line in out.splitlines():
        v = line.split()
        rows.append((int(v[4]), float(v[5]), float(v[6]), float(v[7]), float(v[8]), int(v[9])))
    return rows


def callgrind(peers: Path, path: Path, solver: str = "kernel") -> int:
    """Instructions of every QP of the set solved once by `solver` ("kernel" or "daqp")."""
    mode, fn = ("once", "bench_qp_set_once") if solver == "kernel" else ("once-daqp", "bench_daqp_set_once")
    r = subprocess.run(["valgrind", "--tool=callgrind", "--callgrind-out-file=/dev/null",
                        "--collect-atstart=no", f"--toggle-collect={fn}",
                        str(peers), mode, str(path)], check=True, capture_output=True, text=True)
    for line in r.stderr.splitlines():
        if "Collected :" in line:
            return int(line.split(":")[-1])
    raise RuntimeError("callgrind: no count")


def cpu_median(fn, reps: int) -> float:
    ts = []
    for _ in range(reps):
        t0 = time.process_time_ns()
        fn()
        ts.append(time.process_time_ns() - t0)
    return float(statistics.median(ts))


class _Quiet:
    """Sends the C-level stdout to /dev/null (qpOASES prints its licence banner per instance)."""

    def __enter__(self):
        sys.stdout.flush()
        self.saved = os.dup(1)
        null = os.open(os.devnull, os.O_WRONLY)
        os.dup2(null, 1)
        os.close(null)

    def __exit__(self, *exc):
        os.dup2(self.saved, 1)
        os.close(self.saved)


def python_timings(qps, reps: int):
    """Per QP: (t_kernel_cffi, t_daqp_py, t_qpoases, f_kernel, f_daqp, f_qpoases), ns and objectives."""
    import casadi
    from ogk_bindings._ffi import lib
    from ogk_bindings.extras import need
    from ogk_bindings.qp import QpSolve

    daqp = need("daqp", "peers", "the DAQP peer of make bench")
    INF = float(lib.OGK_QP_INF)
    rows = []
    for qp in qps:
        n, me, mi = qp.n, len(qp.b_eq), len(qp.b_in)
        # kernel through cffi, arrays and structs built once
        q = QpSolve(qp.H, qp.g, qp.A_eq, qp.b_eq, qp.A_in, qp.b_in, qp.lb, qp.ub)
        t_k = cpu_median(q.solve, reps)
        f_k = float(q.solution.objective)
        # daqp.solve: bounds first (ms = n), then the rows; equalities by sense 5
        A = np.ascontiguousarray(np.vstack([qp.A_eq, qp.A_in]))
        bu = np.concatenate([np.where(qp.ub >= INF, 1e30, qp.ub), qp.b_eq, np.full(mi, 1e30)])
        bl = np.concatenate([np.where(qp.lb <= -INF, -1e30, qp.lb), qp.b_eq, qp.b_in])
        sense = np.concatenate([np.zeros(n), np.full(me, 5), np.zeros(mi)]).astype(np.intc)
        res = {}

        def run_daqp():
            res["d"] = daqp.solve(qp.H, qp.g, A, bu, bl, sense)

        t_d = cpu_median(run_daqp, reps)
        x_d = np.asarray(res["d"][0])
        # qpOASES (dense) through CasADi, tight tolerances as in test_qp.py
        Ac = np.vstack([qp.A_eq, qp.A_in])
        with _Quiet():
            solver = casadi.conic("q", "qpoases", {
                "h": casadi.DM(qp.H).sparsity(), "a": casadi.Sparsity.dense(*Ac.shape)},
                {"printLevel": "none", "sparse": False, "error_on_fail": False,
                 "terminationTolerance": 1e-12, "boundTolerance": 1e-12, "nWSR": 10000})
        args = dict(h=casadi.DM(qp.H), g=casadi.DM(qp.g), a=casadi.DM(Ac),
                    lba=casadi.DM(np.concatenate([qp.b_eq, qp.b_in])),
                    uba=casadi.DM(np.concatenate([qp.b_eq, np.full(mi, np.inf)])),
                    lbx=casadi.DM(np.where(qp.lb <= -INF, -np.inf, qp.lb)),
                    ubx=casadi.DM(np.where(qp.ub >= INF, np.inf, qp.ub)))

        def run_qpoases():
            res["q"] = solver(**args)

        with _Quiet():
            t_q = cpu_median(run_qpoases, reps)
        x_q = np.array(res["q"]["x"]).ravel()
        rows.append((t_k, t_d, t_q, f_k, qp.objective(x_d), qp.objective(x_q)))
    return rows


def fdiff(fa, fb):
    d = np.abs(np.asarray(fa) - np.asarray(fb))
    return float(d.max()), float((d / np.maximum(1.0, np.abs(np.asarray(fa)))).max())


def report(name: str, qps, c_rows, o3_rows, py_rows, insns: int, daqp_insns: int) -> None:
    n = [q.n for q in qps]
    st = [r[0] for r in c_rows]
    bad_daqp = sum(1 for r in c_rows if r[5] != 1)
    t_o = np.array([r[1] for r in c_rows]) / 1e3
    t_d = np.array([r[2] for r in c_rows]) / 1e3
    da, dr = fdiff([r[3] for r in c_rows], [r[4] for r in c_rows])
    print(f"== set {name}: {len(qps)} QPs, n = {min(n)}-{max(n)}, m_eq = "
          f"{min(len(q.b_eq) for q in qps)}-{max(len(q.b_eq) for q in qps)}, rows = "
          f"{min(len(q.b_in) for q in qps)}-{max(len(q.b_in) for q in qps)}; kernel status != OK: "
          f"{sum(1 for s in st if s != 0)}, DAQP exitflag != 1: {bad_daqp}")
    print("   both from C, same arrays, same compiler and -O2 (DAQP: daqp_quadprog, one-shot):")
    print(f"   kernel {np.median(t_o):8.2f} us   DAQP {np.median(t_d):8.2f} us   "
          f"kernel/DAQP: ratio of medians {np.median(t_o) / np.median(t_d):.3f}, "
          f"median of ratios {np.median(t_o / t_d):.3f} (range {np.min(t_o / t_d):.2f}-{np.max(t_o / t_d):.2f})")
    print(f"   largest |f_kernel - f_DAQP| {da:.2e} (relative to max(1, |f|): {dr:.2e})")
    if o3_rows is not None:
        o = np.array([r[1] for r in o3_rows]) / 1e3
        d = np.array([r[2] for r in o3_rows]) / 1e3
        print("   DAQP built with its setup.py flags (-O3 -fassociative-math -fno-signed-zeros "
              "-fno-trapping-math), the kernel at -O2:")
        print(f"   kernel {np.median(o):8.2f} us   DAQP {np.median(d):8.2f} us   "
              f"kernel/DAQP: ratio of medians {np.median(o) / np.median(d):.3f}, "
              f"median of ratios {np.median(o / d):.3f}")
    if py_rows is not None:
        k = np.array([r[0] for r in py_rows]) / 1e3
        d = np.array([r[1] for r in py_rows]) / 1e3
        q = np.array([r[2] for r in py_rows]) / 1e3
        qa, qr = fdiff([r[3] for r in py_rows], [r[5] for r in py_rows])
        da2, dr2 = fdiff([r[3] for r in py_rows], [r[4] for r in py_rows])
        print("   through Python, pre-built arrays, each call with its binding's overhead:")
        print(f"   kernel (cffi) {np.median(k):8.2f} us   daqp.solve {np.median(d):8.2f} us   "
              f"qpOASES (casadi.conic) {np.median(q):8.2f} us   kernel/daqp {np.median(k) / np.median(d):.3f}"
              f"   kernel/qpOASES {np.median(k) / np.median(q):.3f}")
        print(f"   largest objective difference: DAQP {da2:.2e} (rel {dr2:.2e}), qpOASES {qa:.2e} (rel {qr:.2e})")
    print(f"   callgrind (gcc -O2 both): kernel {insns:,} instructions for the set ({insns / len(qps):,.0f} per QP), "
          f"DAQP {daqp_insns:,} ({daqp_insns / len(qps):,.0f} per QP, its malloc/free included); "
          f"kernel/DAQP {insns / daqp_insns:.3f}")


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--peers", type=Path, required=True, help="build/bench/qp/bench_qp_peers")
    ap.add_argument("--peers-daqp-o3", type=Path, default=None,
                    help="the same program with DAQP built with its setup.py flags (-O3 ...)")
    ap.add_argument("--recorder", type=Path, required=True, help="build/bench/qp/bench_nmpc_record")
    ap.add_argument("--out", type=Path, required=True, help="directory for the set files")
    ap.add_argument("--reps", type=int, default=31, help="solves per QP and solver (median)")
    ap.add_argument("--no-python", action="store_true", help="only the C comparison")
    a = ap.parse_args()
    a.out.mkdir(parents=True, exist_ok=True)
    sets = {"nmpc": a.out / "nmpc.qps", "random": a.out / "random.qps"}
    record_nmpc(a.recorder, sets["nmpc"])
    make_random(sets["random"])
    load = os.getloadavg()
    print(f"== ogk_qp_solve vs DAQP {_daqp_version()} and qpOASES; "
          f"CPU time per solve, median of {a.reps} per QP; load average {load[0]:.2f} {load[1]:.2f} {load[2]:.2f}")
    for name, path in sets.items():
        qps = read_set(path)
        c_rows = c_timings(a.peers, path, a.reps)
        o3_rows = None if a.peers_daqp_o3 is None else c_timings(a.peers_daqp_o3, path, a.reps)
        py_rows = None if a.no_python else python_timings(qps, a.reps)
        report(name, qps, c_rows, o3_rows, py_rows, callgrind(a.peers, path),
               callgrind(a.peers, path, "daqp"))
        sys.stdout.flush()
    load = os.getloadavg()
    print(f"== load average at the end {load[0]:.2f} {load[1]:.2f} {load[2]:.2f}")
    return 0


def _daqp_version() -> str:
    import importlib.metadata

    return importlib.metadata.version("daqp")


if __name__ == "__main__":
    raise SystemExit(main())
