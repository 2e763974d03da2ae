#!/usr/bin/env python3
"""mutants.py -- a small deterministic mutation run over kernel/src (make mutants, tests/gates/gates.mk).

Mutants: operator and constant changes at sites found in the code (comments, strings and
preprocessor lines excluded): `<` <-> `<=`, `>` <-> `>=`, `==` <-> `!=`, `&&` <-> `||`, binary
`+` <-> `-`, a unary minus dropped, a floating constant doubled (0.0 -> 1.0), an unsigned integer
constant + 1. From every site (less the equivalent ones of EQUIVALENT) a seeded sample (--seed,
--count) is drawn, plus the fixed mutants of FIXED (earlier survivors, kept so that their killing
tests stay checked; --fixed-only runs just those). The sample depends on the source text: the same
seed draws other mutants once kernel/src changes (docs/evidence/mutation.md records the commit of each score).

Each mutant is applied to a copy of the kernel under BUILD (build/mutants by default; the
working tree is never touched), the mutated source recompiled, every C unit test
(tests/unit/*/test_*.c, host, gcc -O1, no sanitizers) relinked and run until the first failure,
crash or time-out (killed). A mutant that does not compile is reported and not counted.
Prints one line per mutant (file:line:column of a sampled one) and the score = killed / (killed + survived); exit status 0 unless
the unmutated tree fails its own tests (2), a fixed mutant's fragment is no longer found once or
is found more than once (3: update FIXED), or --min-score is given and not reached (1).
"""
import argparse
import os
import random
import re
import shutil
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

# Fixed mutants, (file, code fragment, replacement, what it breaks): the survivors of issue 8
# item 3 and of the seeded runs of docs/evidence/mutation.md, each with its killing unit test, kept so that
# the test stays checked. A fragment is matched with every run of white space in it standing for
# any run of white space (so re-indenting or re-wrapping the code, e.g. the MISRA 15.5 single-exit
# rewrite, keeps it found); it must match exactly once, else the run reports it MISSING or
# AMBIGUOUS and exits 3. Fragments are the expression that is mutated, not a return line.
FIXED = [
    ("kernel/src/mpsp/mpsp_sensitivity.c",
     "= a * jump.s_u[c] * h[q];", "= -a * jump.s_u[c] * h[q];",
     "eq. (25) sign in ogk_mpsp_switch_jump (dX+/dW)"),
    ("kernel/src/mpsp/mpsp.c",
     "n_seg_tol += ctx->cfg.n_seg_tol_step;", "n_seg_tol += 1u;",
     "N_seg,tol step of the continuation"),
    ("kernel/src/cpd/cpd.c",
     "*alpha_a <= -CPD_PI", "*alpha_a < -CPD_PI",
     "alpha_a in (-pi, pi]: atan2's -pi (thrust along -t, xi = -pi) not mapped to +pi "
     "(test_cpd: test_thrust_angles_branch_cut)"),
    ("kernel/src/cpd/cpd.c",
     "*psi_c <= -CPD_PI", "*psi_c < -CPD_PI",
     "psi_c in (-pi, pi]: the same branch cut in ogk_cpd_commanded_attitude "
     "(test_cpd: test_thrust_angles_branch_cut)"),
    ("kernel/src/nog/nog.c",
     "(cfg->sample_interval_s > tbl", "(cfg->sample_interval_s >= tbl",
     "Delta t_S = t_f* rejected although the documented range is (0, t_f*] "
     "(test_nog: test_config_range_boundaries)"),
    ("kernel/src/nog/nog.c",
     "for (i = 0u; i < NX; ++i) { ctx->dlam_k[i] = scale * out8[i];",
     "for (i = 1u; i < NX; ++i) { ctx->dlam_k[i] = scale * out8[i];",
     "dlam_r, dlam_r' of [dlam_k; dt_f] = G dx, N dx not updated "
     "(test_nog: test_radius_error_moves_lambda_r_only)"),
    ("kernel/src/nog/nog.c",
     "for (i = 0u; i < NX; ++i) { dx[i] = nav_v[i] - x_star[i];",
     "for (i = 1u; i < NX; ++i) { dx[i] = nav_v[i] - x_star[i];",
     "dx_r of dx_k left uninitialised (test_nog: test_radius_error_moves_lambda_r_only)"),
    ("kernel/src/nog/nog.c",
     "if (st == OGK_OK) { st = OGK_E_SAFE_COMMAND;", "if (st != OGK_OK) { st = OGK_E_SAFE_COMMAND;",
     "overflowing costate in ogk_nog_thrust_cmd reported as OK "
     "(test_nog: test_overflowing_costate_gives_safe_command)"),
    ("kernel/src/core/interp.c",
     "values[((n - 1u) * m) + j]) / h0", "values[((n - 1u) * m) - j]) / h0",
     "pchip right-end secant of column j > 0 read from the wrong element "
     "(test_interp: test_pchip_end_slopes_of_every_column)"),
    ("kernel/src/core/interp.c",
     "(values[m + j] - values[j]) / (grid[1] - grid[0])",
     "(values[m - j] - values[j]) / (grid[1] - grid[0])",
     "pchip slopes of a two-node grid: column j > 0 reads another column "
     "(test_interp: test_pchip_two_points_every_column)"),
    ("kernel/src/nog/nog.c",
     "if (direction_angle(lam, lam_star) <= du_max) { scale = 1.0;",
     "if (direction_angle(lam, lam_star) < du_max) { scale = 1.0;",
     "du_max = pi limits an exact thrust reversal (angle pi) "
     "(test_nog: test_du_max_pi_admits_a_reversal)"),
    ("kernel/src/nog/nog.c",
     "!ogk_i_all_finite(out8, N_GAIN_ROWS) || !ogk_i_all_finite(dlam_rate, NX)",
     "!ogk_i_all_finite(out8, N_GAIN_ROWS) && !ogk_i_all_finite(dlam_rate, NX)",
     "an overflowing dt_f alone clipped to dtf_max instead of the safe command "
     "(test_nog: test_overflowing_dt_f_alone_gives_safe_command)"),
    ("kernel/src/nog/nog.c",
     "if (dt_f != out8[NX])", "if (fabs(dt_f) >= ctx->cfg.dtf_max_s)",
     "dt_f exactly at dtf_max flagged LIMITED (test_nog: test_dt_f_at_the_bound_is_not_limited)"),
    ("kernel/src/nog/nog.c",
     "(t_s >= ctx->t_k_s) && (t_s <= t_sample_max(ctx))",
     "(t_s >= ctx->t_k_s) && (t_s < t_sample_max(ctx))",
     "safe_sample: t_s = 2 t_f* + dtf_max (inside the closed envelope) treated as unusable "
     "(test_nog: test_sample_at_the_envelope_time_bound)"),
    ("kernel/src/nog/nog.c",
     "ctx->n_samples += 1u;", "ctx->n_samples += 2u;",
     "good-sample count of the context (test_nog: test_on_nominal_in_every_interval)"),
    ("kernel/src/nog/nog.c",
     "h = tbl->tau[k + 1u] - tbl->tau[k];", "h = tbl->tau[k + 1u] + tbl->tau[k];",
     "Hermite interval length wrong beyond the first interval "
     "(test_nog: test_on_nominal_in_every_interval)"),
    ("kernel/src/core/table.c",
     "(OGK_TABLE_MAX_VALUES / (v->entry_len + 1u))", "(OGK_TABLE_MAX_VALUES / (v->entry_len - 1u))",
     "value-count guard divides by entry_len - 1 (0 for scalar entries) "
     "(test_table: test_scalar_entries)"),
    ("kernel/src/core/table.c",
     "(*values > (OGK_TABLE_MAX_VALUES / 8u))", "(*values >= (OGK_TABLE_MAX_VALUES / 8u))",
     "the largest admitted payload, MAX / 8 values, rejected as too large "
     "(test_table: test_largest_payload_size)"),
    ("kernel/src/core/table.c",
     "for (i = 0u; (i < values)", "for (i = 1u; (i < values)",
     "finiteness scan of the payload skips grid[0] "
     "(test_table: test_nonfinite_first_and_last_value)"),
]

# Sites excluded from the sampling: equivalent mutants (no observable change; docs/evidence/mutation.md),
# as (file, code fragment, mutated token, why): a site is excluded when its token is that token
# and lies inside a match of the fragment (white space as in FIXED) that starts on the site's line
# (it may run over the next two lines). A fragment no longer found only excludes nothing (the
# mutant is then sampled again and shows up as a survivor).
EQUIVALENT = [
    ("kernel/src/core/interp.c", "(it < OGK_INTERP_MAX_SEARCH) && ((hi - lo) > 1u)", "&&",
     "ogk_interp_locate: with || the bisection runs its 64 iterations, but once hi - lo = 1 "
     "mid = lo and nothing changes; only the time differs"),
    ("kernel/src/core/interp.c", "(it < OGK_INTERP_MAX_SEARCH) && ((hi - lo) > 1u)", "<",
     "ogk_interp_locate: 65 instead of 64 bisection steps; 64 already halve any size_t range"),
    ("kernel/src/core/interp.c", "(it < OGK_INTERP_MAX_SEARCH) && ((hi - lo) > 1u)", ">",
     "ogk_interp_locate: with >= the loop goes on at hi - lo = 1, where mid = lo changes nothing"),
    ("kernel/src/core/interp.c", "(it < OGK_INTERP_MAX_SEARCH) && ((hi - lo) > 1u)", "-",
     "ogk_interp_locate: hi + lo > 1 keeps the loop going past hi - lo = 1, where nothing changes "
     "(and stops it at lo = 0, hi = 1, converged too)"),
    ("kernel/src/core/table.c", "(v->entry_len >= OGK_TABLE_MAX_VALUES)", ">=",
     "check_sizes: at entry_len = OGK_TABLE_MAX_VALUES the next clause, grid_size > MAX / (MAX + 1) "
     "= 0, gives the same OGK_E_TABLE_SIZE (grid_size >= 1 is checked before); the first clause "
     "only keeps entry_len + 1 from wrapping"),
    ("kernel/src/core/table.c", "(v->grid_size > (OGK_TABLE_MAX_VALUES / (v->entry_len + 1u)))", ">",
     "check_sizes: at grid_size = floor(MAX / (entry_len + 1)) >= 1 the value count is > MAX / 2, "
     "so the next check (values > MAX / 8) gives the same OGK_E_TABLE_SIZE"),
    ("kernel/src/nog/nog.c", "if (direction_angle(lam, lam_star) <= du_max) { lo = mid;", "<=",
     "direction_limit_scale bisection: < instead of <= differs only when a probe's angle is "
     "exactly du_max, and then moves the scale by one bisection step, 2^-40 of the correction "
     "(the bisection's own resolution)"),
    ("kernel/src/core/table.c", "(OGK_TABLE_MAX_VALUES / (v->entry_len + 1u))", "1u",
     "check_sizes: + 2u only tightens the guard; a grid it then rejects has > MAX / 2 values, "
     "which the value-count check rejects with the same OGK_E_TABLE_SIZE"),
    ("kernel/src/nog/nog.c", "(nav->t_s <= t_sample_max(ctx))", "<=",
     "nav_in_envelope: at t_s = 2 t_f* + dtf_max exactly, tau > 1 always (the cut-off is at "
     "most t_f* + dtf_max), so the tau > 1 branch rejects it with the same OGK_E_RANGE and "
     "the same safe_sample call"),
    ("kernel/src/core/rk4.c", "double ratio = 0.0;", "0.0",
     "grid_steps: ratio is read only when st == OGK_OK, which is set only after ratio is assigned "
     "(the initialiser is for the static analysers)"),
    ("kernel/src/core/interp.c", "for (it = 0u; (it < OGK_INTERP_MAX_SEARCH)", "0u",
     "ogk_interp_locate: 63 instead of 64 bisection steps; 63 halve any range of < 2^63 nodes "
     "(the grid is bounded by OGK_TABLE_MAX_VALUES)"),
]


def fragment_regex(frag):
    """The fragment as a regular expression: each run of white space matches any run."""
    return re.compile(r"\s+".join(re.escape(w) for w in frag.split()))


# The sanitizers of make test-unit-host: an out-of-bounds or undefined mutant is killed.
SAN = ["-fsanitize=address,undefined", "-fno-sanitize-recover=all", "-fno-omit-frame-pointer"]
CFLAGS = ["-std=c99", "-O1", "-g", "-w", "-Ikernel/include", "-Ikernel/src"] + SAN


def code_spans(text):
    """Yields (line_no, start, end) of the code parts of each line: outside comments, string and
    character literals, and preprocessor lines."""
    in_comment = False
    for no, line in enumerate(text.split("\n"), 1):
        if not in_comment and line.lstrip().startswith("#"):
            continue
        i = 0
        start = None
        n = len(line)
        while i < n:
            if in_comment:
                j = line.find("*/", i)
                if j < 0:
                    i = n
                    break
                in_comment = False
                i = j + 2
                continue
            if start is None:
                start = i
            if line.startswith("/*", i):
                if i > start:
                    yield no, start, i
                start = None
                in_comment = True
                i += 2
                continue
            if line.startswith("//", i):
                if i > start:
                    yield no, start, i
                start = None
                i = n
                break
            if line[i] in "\"'":
                q = line[i]
                if i > start:
                    yield no, start, i
                j = i + 1
                while j < n and line[j] != q:
                    j += 2 if line[j] == "\\" else 1
                i = j + 1
                start = None
                continue
            i += 1
        if start is not None and not in_comment and n > start:
            yield no, start, n


FLOAT = re.compile(r"(?<![\w.])(\d+\.\d*(?:[eE][+-]?\d+)?|\d+[eE][+-]?\d+)(?![\w.])")
UINT = re.compile(r"(?<![\w.])(\d+)u(?![\w.])")
OPS = [
    (re.compile(r"(?<=[\w)\]] )<(?= )"), "<="),
    (re.compile(r"(?<=[\w)\]] )<=(?= )"), "<"),
    (re.compile(r"(?<=[\w)\]] )>(?= )"), ">="),
    (re.compile(r"(?<=[\w)\]] )>=(?= )"), ">"),
    (re.compile(r"(?<= )==(?= )"), "!="),
    (re.compile(r"(?<= )!=(?= )"), "=="),
    (re.compile(r"(?<= )&&(?= )"), "||"),
    (re.compile(r"(?<= )\|\|(?= )"), "&&"),
    (re.compile(r"(?<=[\w)\]] )\+(?= )"), "-"),
    (re.compile(r"(?<=[\w)\]] )-(?= )"), "+"),
    (re.compile(r"(?<=[=(,] )-(?=[\w(])"), ""),  # unary minus dropped
]


def float_mutant(lit):
    v = float(lit)
    return "1.0" if v == 0.0 else repr(2.0 * v)


def sites(path, text):
    lines = text.split("\n")
    out = []
    for no, a, b in code_spans(text):
        seg = lines[no - 1][a:b]
        for rx, rep in OPS:
            for m in rx.finditer(seg):
                out.append((path, no, a + m.start(), a + m.end(), rep))
        for m in FLOAT.finditer(seg):
            out.append((path, no, a + m.start(), a + m.end(), float_mutant(m.group(1))))
        for m in UINT.finditer(seg):
            out.append((path, no, a + m.start(), a + m.end(), "%du" % (int(m.group(1)) + 1)))
    return out


def run(cmd, cwd, timeout=None):
    try:
        p = subprocess.run(cmd, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                           timeout=timeout)
        return p.returncode, p.stdout.decode(errors="replace")
    except subprocess.TimeoutExpired:
        return "timeout", ""


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--count", type=int, default=40, help="sampled mutants (plus the fixed ones)")
    ap.add_argument("--build", default=os.path.join(ROOT, "build", "mutants"))
    ap.add_argument("--timeout", type=float, default=120.0, help="seconds per test program")
    ap.add_argument("--min-score", type=float, default=None)
    ap.add_argument("--list", action="store_true", help="list the mutants (and the excluded sites) only")
    ap.add_argument("--fixed-only", action="store_true",
                    help="run the fixed mutants only (their killing tests still kill them)")
    args = ap.parse_args()

    ksrc = sorted(os.path.relpath(os.path.join(d, f), ROOT)
                  for d, _, files in os.walk(os.path.join(ROOT, "kernel/src")) for f in files if f.endswith(".c"))
    tests = sorted(os.path.relpath(os.path.join(d, f), ROOT)
                   for d, _, files in os.walk(os.path.join(ROOT, "tests/unit"))
                   for f in files if f.startswith("test_") and f.endswith(".c"))
    texts = {p: open(os.path.join(ROOT, p)).read() for p in ksrc}

    all_sites = []
    excluded = []
    for p in ksrc:
        lines = texts[p].split("\n")
        for site in sites(p, texts[p]):
            _, no, a, b, _ = site
            here = "\n".join(lines[no - 1:no + 2])  # the site's line and the next two
            why = [w for f, frag, tok, w in EQUIVALENT
                   if f == p and here[a:b] == tok
                   and any(m.start() <= a < m.end() for m in fragment_regex(frag).finditer(here))]
            if why:
                excluded.append((site, why[0]))
            else:
                all_sites.append(site)
    rng = random.Random(args.seed)
    sample = rng.sample(all_sites, min(args.count, len(all_sites)))
    sample.sort()
    mutants = []
    missing = []
    for path, frag, rep, what in FIXED:
        t = texts[path]
        found = list(fragment_regex(frag).finditer(t))
        if len(found) != 1:
            why = "MISSING" if not found else "AMBIGUOUS (%d matches)" % len(found)
            missing.append("%s: %s: %r" % (why, path, frag))
            print("mutants: fixed mutant %s (source changed? update FIXED in tests/gates/mutants.py): "
                  "%s: %r" % (why, path, frag))
            continue
        k, e = found[0].start(), found[0].end()
        no = t.count("\n", 0, k) + 1
        mutants.append((path, str(no), t[:k] + rep + t[e:], frag, rep, what))
    for path, no, a, b, rep in sample:
        lines = texts[path].split("\n")
        line = lines[no - 1]
        orig = line[a:b]
        lines[no - 1] = line[:a] + rep + line[b:]
        mutants.append((path, "%d:%d" % (no, a + 1), "\n".join(lines), orig, rep, line.strip()))
    if args.fixed_only:
        mutants = mutants[:len(FIXED) - len(missing)]
        sample = []
    print("mutants: %d sites in %d kernel sources (%d equivalent excluded), %d sampled (seed %d) + "
          "%d fixed (%d missing); %d unit tests"
          % (len(all_sites), len(ksrc), len(excluded), len(sample), args.seed, len(FIXED) - len(missing),
             len(missing), len(tests)))
    if args.list:
        for (path, no, a, b, rep), why in excluded:
            print("  excluded %s:%d: %r -> %r: %s" % (path, no, texts[path].split("\n")[no - 1][a:b], rep, why))
        for m in mutants:
            print("  %s:%s: %r -> %r   %s" % (m[0], m[1], m[3], m[4], m[5]))
        return 3 if missing else 0

    # A copy of the kernel and the unit tests; objects of the unmutated sources and of the tests.
    b = os.path.abspath(args.build)
    tree = os.path.join(b, "tree")
    if os.path.isdir(tree):
        shutil.rmtree(tree)
    for d in ("kernel", "tests/unit"):
        shutil.copytree(os.path.join(ROOT, d), os.path.join(tree, d))
    obj = os.path.join(b, "obj")
    os.makedirs(obj, exist_ok=True)
    kobj = {}
    for p in ksrc:
        o = os.path.join(obj, os.path.basename(p)[:-2] + ".o")
        rc, out = run(["gcc"] + CFLAGS + ["-c", p, "-o", o], tree)
        if rc != 0:
            print(out)
            print("mutants: the unmutated kernel does not compile")
            return 2
        kobj[p] = o
    tobj = []
    for t in tests:
        o = os.path.join(obj, os.path.basename(t)[:-2] + ".o")
        rc, out = run(["gcc"] + CFLAGS + ["-Itests/unit", "-c", t, "-o", o], tree)
        if rc != 0:
            print(out)
            print("mutants: %s does not compile" % t)
            return 2
        tobj.append(o)

    def test_all(objs):
        """None when every test passes, else the name of the first failing one."""
        for t, o in zip(tests, tobj):
            exe = o[:-2]
            rc, _ = run(["gcc"] + SAN + [o] + objs + ["-o", exe, "-lcmocka", "-lm"], tree)
            if rc != 0:
                return "%s (link)" % os.path.basename(t)
            rc, _ = run([exe], tree, timeout=args.timeout)
            if rc != 0:
                return "%s (%s)" % (os.path.basename(t)[:-2], "time-out" if rc == "timeout" else "exit %s" % rc)
        return None

    t0 = time.time()
    base = test_all([kobj[p] for p in ksrc])
    if base is not None:
        print("mutants: the unmutated tree fails %s: no mutation run" % base)
        return 2
    print("mutants: unmutated tree passes every unit test (%.1f s)" % (time.time() - t0))

    killed = survived = invalid = 0
    survivors = []
    mo = os.path.join(obj, "mutant.o")
    for i, (path, no, text, orig, rep, what) in enumerate(mutants, 1):
        src = os.path.join(tree, path)
        with open(src, "w") as f:
            f.write(text)
        rc, _ = run(["gcc"] + CFLAGS + ["-c", path, "-o", mo], tree)
        with open(src, "w") as f:
            f.write(texts[path])
        if rc != 0:
            invalid += 1
            verdict = "does not compile"
        else:
            by = test_all([mo if p == path else kobj[p] for p in ksrc])
            if by is None:
                survived += 1
                survivors.append((path, no, orig, rep, what))
                verdict = "SURVIVED"
            else:
                killed += 1
                verdict = "killed by " + by
        print("%3d %s:%s: %r -> %r: %s   [%s]" % (i, path, no, orig, rep, verdict, what[:70]))
        sys.stdout.flush()
    n = killed + survived
    score = 100.0 * killed / n if n else 0.0
    print("mutants: %d killed, %d survived, %d did not compile; score %.1f %% (%d/%d), %.0f s"
          % (killed, survived, invalid, score, killed, n, time.time() - t0))
    for path, no, orig, rep, what in survivors:
        print("  survivor: %s:%s: %r -> %r   %s" % (path, no, orig, rep, what))
    for m in missing:
        print("  fixed mutant not applied: %s" % m)
    if missing:
        return 3
    if args.min_score is not None and score < args.min_score:
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
