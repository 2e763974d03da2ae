#!/usr/bin/env python3
"""mutants.py -- a small deterministic mutation run over kernel/src (make mutants, tests/gates/gates.mk).

Mutants: operator and constant changes at sites found in the code (comments, strings and
preprocessor lines excluded): `<` <-> `<=`, `>` <-> `>=`, `==` <-> `!=`, `&&` <-> `||`, binary
`+` <-> `-`, a unary minus dropped, a floating constant doubled (0.0 -> 1.0), an unsigned integer
constant + 1. From every site a seeded sample (--seed, --count) is drawn, plus the fixed mutants
of FIXED (the survivors of issue 8 item 3, kept so that their killing tests stay checked).

Each mutant is applied to a copy of the kernel under BUILD (build/mutants by default; the
working tree is never touched), the mutated source recompiled, every C unit test
(tests/unit/test_*.c, host, gcc -O1, no sanitizers) relinked and run until the first failure,
crash or time-out (killed). A mutant that does not compile is reported and not counted.
Prints one line per mutant and the score = killed / (killed + survived); exit status 0 unless
the unmutated tree fails its own tests (or --min-score is given and not reached).
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

# (file, exact code fragment, replacement): the two survivors named in issue 8, item 3.
FIXED = [
    ("kernel/src/mpsp_sensitivity.c",
     "= a * jump.s_u[c] * h[q];", "= -a * jump.s_u[c] * h[q];",
     "eq. (25) sign in ogk_mpsp_switch_jump (dX+/dW)"),
    ("kernel/src/mpsp.c",
     "n_seg_tol += ctx->cfg.n_seg_tol_step;", "n_seg_tol += 1u;",
     "N_seg,tol step of the continuation"),
]

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
    ap.add_argument("--list", action="store_true", help="list the mutants only")
    args = ap.parse_args()

    ksrc = sorted(os.path.join("kernel/src", f) for f in os.listdir(os.path.join(ROOT, "kernel/src"))
                  if f.endswith(".c"))
    tests = sorted(os.path.join("tests/unit", f) for f in os.listdir(os.path.join(ROOT, "tests/unit"))
                   if f.startswith("test_") and f.endswith(".c"))
    texts = {p: open(os.path.join(ROOT, p)).read() for p in ksrc}

    all_sites = []
    for p in ksrc:
        all_sites.extend(sites(p, texts[p]))
    rng = random.Random(args.seed)
    sample = rng.sample(all_sites, min(args.count, len(all_sites)))
    sample.sort()
    mutants = []
    for path, frag, rep, what in FIXED:
        t = texts[path]
        k = t.find(frag)
        if k < 0:
            print("mutants: fixed mutant not found (source changed?): %s: %s" % (path, frag))
            continue
        no = t.count("\n", 0, k) + 1
        mutants.append((path, no, t[:k] + rep + t[k + len(frag):], frag, rep, what))
    for path, no, a, b, rep in sample:
        lines = texts[path].split("\n")
        line = lines[no - 1]
        orig = line[a:b]
        lines[no - 1] = line[:a] + rep + line[b:]
        mutants.append((path, no, "\n".join(lines), orig, rep, line.strip()))
    print("mutants: %d sites in %d kernel sources, %d sampled (seed %d) + %d fixed; %d unit tests"
          % (len(all_sites), len(ksrc), len(sample), args.seed, len(FIXED), len(tests)))
    if args.list:
        for m in mutants:
            print("  %s:%d: %r -> %r   %s" % (m[0], m[1], m[3], m[4], m[5]))
        return 0

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
        print("%3d %s:%d: %r -> %r: %s   [%s]" % (i, path, no, orig, rep, verdict, what[:70]))
        sys.stdout.flush()
    n = killed + survived
    score = 100.0 * killed / n if n else 0.0
    print("mutants: %d killed, %d survived, %d did not compile; score %.1f %% (%d/%d), %.0f s"
          % (killed, survived, invalid, score, killed, n, time.time() - t0))
    for path, no, orig, rep, what in survivors:
        print("  survivor: %s:%d: %r -> %r   %s" % (path, no, orig, rep, what))
    if args.min_score is not None and score < args.min_score:
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
