#!/usr/bin/env python3
"""MC/DC gate of `make mcdc` (tests/gates/gates.mk; docs/evidence/coverage.md, "MC/DC").

Reads llvm-cov-19's `report -show-mcdc-summary` (the TOTAL MC/DC column) and `show -show-mcdc`
(every decision, its conditions and which independence pairs are missing), and the exceptions
list (docs/evidence/mcdc-exceptions.md). Fails when

  * the conditions covered over kernel/src are under --threshold percent, or
  * a missed condition, or a decision clang left uninstrumented (its "unsupported MC/DC boolean
    expression" warning, from the compile logs), is not listed with a reason.

Listed entries that match nothing any more are reported (the condition is now covered: remove
the row, so the list shrinks). Entries are keyed by file, function and condition text, not by
line, so that edits elsewhere in a file do not move them.

Exceptions list rows (a Markdown table; the first four cells are read):
  | file | function | condition | reason |
`condition` is the condition's source text in backquotes, whitespace-insensitive; for an
uninstrumented decision it is the whole decision's text prefixed by `uninstrumented: `.
"""
import argparse
import glob
import os
import re
import sys

FILE_RE = re.compile(r"^(/\S+\.[ch]):$")
DECISION_RE = re.compile(r"MC/DC Decision Region \((\d+):(\d+)\) to \((\d+):(\d+)\)")
COND_RE = re.compile(r"Condition C(\d+) --> \((\d+):(\d+)\)")
PAIR_RE = re.compile(r"C(\d+)-Pair: (covered|not covered)")
TOTAL_RE = re.compile(r"^TOTAL\s")
FUNC_RE = re.compile(r"^(?:static\s+)?(?:inline\s+)?[A-Za-z_][\w\s\*]*?\b([A-Za-z_]\w*)\s*\(")
UNSUPPORTED_RE = re.compile(r"^(\S+\.[ch]):(\d+):(\d+): warning: unsupported MC/DC boolean expression")


def norm(text):
    return " ".join(text.split())


def strip_parens(text):
    """Strip operators and unbalanced parentheses from the ends of a condition's text."""
    text = text.strip()
    changed = True
    while changed:
        changed = False
        for op in ("&&", "||", ";", "{"):
            if text.endswith(op):
                text = text[: -len(op)].strip()
                changed = True
        if text.endswith("(") or (text.startswith("(") and text.count("(") > text.count(")")):
            text = (text[:-1] if text.endswith("(") else text[1:]).strip()
            changed = True
        if text.endswith(")") and text.count(")") > text.count("("):
            text = text[:-1].strip()
            changed = True
    # drop one level of enclosing parentheses around the whole condition
    while text.startswith("(") and text.endswith(")") and balanced(text[1:-1]):
        text = text[1:-1].strip()
    return text


def balanced(text):
    depth = 0
    for ch in text:
        depth += (ch == "(") - (ch == ")")
        if depth < 0:
            return False
    return depth == 0


def text_between(lines, l0, c0, l1, c1):
    """Source text from (l0, c0) up to but excluding (l1, c1), 1-based lines and columns."""
    if l0 == l1:
        return lines[l0 - 1][c0 - 1 : c1 - 1]
    parts = [lines[l0 - 1][c0 - 1 :]]
    parts += lines[l0 : l1 - 1]
    parts.append(lines[l1 - 1][: c1 - 1])
    return " ".join(parts)


def enclosing_function(lines, line):
    for i in range(line - 1, -1, -1):
        src = lines[i]
        if not src or src[0] in " \t{}#/*":
            continue
        m = FUNC_RE.match(src)
        if m and not src.rstrip().endswith(";"):
            return m.group(1)
    return "?"


def decision_end_text(lines, l1, c1):
    # the region's end column is inclusive
    return l1, c1 + 1


def parse_show(path, root):
    """Yield (file, function, condition text, line) for every condition with a missing pair."""
    sources = {}
    cur = None
    decision = None
    conds = {}
    out = []
    with open(path) as fh:
        for raw in fh:
            m = FILE_RE.match(raw.rstrip("\n"))
            if m:
                cur = m.group(1)
                if cur not in sources:
                    with open(cur) as sf:
                        sources[cur] = sf.read().split("\n")
                continue
            m = DECISION_RE.search(raw)
            if m:
                decision = tuple(int(x) for x in m.groups())
                conds = {}
                continue
            m = COND_RE.search(raw)
            if m and decision is not None:
                conds[int(m.group(1))] = (int(m.group(2)), int(m.group(3)))
                continue
            m = PAIR_RE.search(raw)
            if m and decision is not None and m.group(2) == "not covered":
                idx = int(m.group(1))
                lines = sources[cur]
                l0, c0 = conds[idx]
                if idx + 1 in conds:
                    l1, c1 = conds[idx + 1]
                else:
                    l1, c1 = decision_end_text(lines, decision[2], decision[3])
                text = norm(strip_parens(text_between(lines, l0, c0, l1, c1)))
                rel = os.path.relpath(cur, root)
                out.append((rel, enclosing_function(lines, l0), text, l0))
    return out


def parse_unsupported(logs, root):
    out = []
    for log in logs:
        with open(log) as fh:
            for raw in fh:
                m = UNSUPPORTED_RE.match(raw)
                if not m:
                    continue
                path = m.group(1)
                with open(path) as sf:
                    lines = sf.read().split("\n")
                line = int(m.group(2))
                # the decision's text: from the column to the end of its line, without the `{`
                text = lines[line - 1][int(m.group(3)) - 1 :].rstrip().rstrip("{").strip()
                text = norm(strip_parens(text))
                rel = os.path.relpath(path, root) if os.path.isabs(path) else path
                out.append((rel, enclosing_function(lines, line), "uninstrumented: " + text, line))
    return out


ROW_RE = re.compile(r"^\|\s*(\S+\.[ch])\s*\|\s*(\S+)\s*\|\s*`((?:[^`])*)`\s*\|(.*)\|\s*$")


def parse_exceptions(path):
    """Rows `| file | function | `condition` | reason |`; a `|` inside the condition is written `\|`."""
    rows = []
    with open(path) as fh:
        for n, raw in enumerate(fh, 1):
            m = ROW_RE.match(raw.rstrip("\n"))
            if not m:
                continue
            cond = norm(m.group(3).replace("\\|", "|"))
            reason = m.group(4).strip()
            if not reason:
                raise SystemExit(f"mcdc: {path}:{n}: a row without its reason")
            rows.append(((m.group(1), m.group(2), cond), reason, n))
    return rows


def total_percent(report):
    with open(report) as fh:
        for raw in fh:
            if TOTAL_RE.match(raw):
                cols = raw.split()
                # ... MC/DC Conditions, Missed Conditions, Cover are the last three columns
                return int(cols[-3]), int(cols[-2]), cols[-1]
    raise SystemExit("mcdc: no TOTAL line in " + report)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--report", required=True)
    ap.add_argument("--show", required=True)
    ap.add_argument("--exceptions", required=True)
    ap.add_argument("--threshold", type=float, required=True)
    ap.add_argument("--compile-logs", default="")
    ap.add_argument("--missed-out", required=True)
    ap.add_argument("--root", default=os.getcwd())
    args = ap.parse_args()

    n_cond, n_missed, cover = total_percent(args.report)
    missed = parse_show(args.show, args.root)
    logs = sorted(glob.glob(args.compile_logs, recursive=True)) if args.compile_logs else []
    missed += parse_unsupported(logs, args.root)
    listed = parse_exceptions(args.exceptions)
    keys = {k for k, _, _ in listed}

    with open(args.missed_out, "w") as fh:
        for f, fn, text, line in missed:
            fh.write(f"| {f} | {fn} | `{text}` | (line {line}) |\n")

    unlisted = [m for m in missed if (m[0], m[1], m[2]) not in keys]
    seen = {(m[0], m[1], m[2]) for m in missed}
    stale = [(k, n) for k, _, n in listed if k not in seen]

    pct = 100.0 * (n_cond - n_missed) / n_cond if n_cond else 100.0
    fail = False
    print(f"mcdc: {n_cond - n_missed} / {n_cond} conditions ({pct:.2f} %), {n_missed} missed, "
          f"{len(missed) - n_missed} decision(s) uninstrumented; per file: {args.report}")
    for k, n in stale:
        print(f"mcdc: {args.exceptions}:{n}: listed but not missed any more (covered now, or its text "
              f"changed): {k[0]} {k[1]} `{k[2]}`: remove the row")
    for f, fn, text, line in unlisted:
        print(f"mcdc: {f}:{line}: missed condition not in {args.exceptions}: | {f} | {fn} | `{text}` |")
    if unlisted:
        print(f"mcdc: {len(unlisted)} missed condition(s) not listed: cover them with a test, or list "
              f"each with its reason (all missed: {args.missed_out})")
        fail = True
    if pct < args.threshold:
        print(f"mcdc: under the threshold COVERAGE_MCDC = {args.threshold:g} %")
        fail = True
    if fail:
        return 1
    print(f"mcdc: at or above COVERAGE_MCDC = {args.threshold:g} %, every missed condition listed "
          f"with its reason ({len(listed)} rows in {args.exceptions})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
