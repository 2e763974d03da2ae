#!/usr/bin/env bash
# check_selftest.sh -- judges the runs of `make test-arm-selftest` (the Cortex-M7) and
# `make test-m4f-selftest` (the Cortex-M4F).
#   $1 selftest ELF (must pass)
#   $2 selftest ELF with -DOGK_SELFTEST_INJECT_FAILURES (must fail exactly the inject_* tests)
#   $3 selftest ELF with -DOGK_SELFTEST_INJECT_FAULT (must exit 250 with a fault report)
#   $4 selftest ELF with -DOGK_SELFTEST_INJECT_OVERFLOW (must exit 251)
#   $5 host binary, injected failures, real cmocka
#   $6 host binary, injected failures, the shim runner
#   $7 file with the preprocessed injected-failure source (expected test names)
# Env: TARGET_NAME and QEMU_MACHINE (run_qemu.sh; default cortex-m7 on mps2-an500), SELFTEST_GOAL
# (the make target named in the verdict; default test-arm-selftest).
set -u
here=$(cd "$(dirname "$0")/.." && pwd)
target=${TARGET_NAME:-cortex-m7}
goal=${SELFTEST_GOAL:-test-arm-selftest}
run="$here/run_qemu.sh"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
problems=0
bad() { echo "SELFTEST FAIL: $*"; problems=$((problems + 1)); }
# The runs below fail on purpose: their cmocka-style lines are kept out of the
# log (a CI reading "[  FAILED  ]" lines must not count them) and shown only
# when a check of this script fails.
summ() { echo "-- selftest run '$1': exit $3, $(wc -l < "$2") lines of output"; }
dump() { for f in "$tmp"/*.txt "$tmp"/*.out "$tmp"/*.err; do [ -f "$f" ] && { echo "---- $f"; cat "$f"; }; done; }

# Expected counts come from the source, not from the runner.
n_inject=$(grep -o '{ "inject_[a-z_0-9]*"' "$7" | sort -u | wc -l)
n_pass=$(grep -o '{ "test_[a-z_0-9]*"' "$7" | sort -u | wc -l)
[ "$n_inject" -ge 10 ] || bad "found only $n_inject inject_* tests in $7"

# 1. the selftest passes on the target
"$run" "$1" 60 > "$tmp/pass.txt"; rc=$?
summ "pass" "$tmp/pass.txt" $rc
[ $rc -eq 0 ] || bad "selftest exit $rc (expected 0)"

# 2. injected assertion failures are all detected, the rest still passes
"$run" "$2" 60 > "$tmp/inject.txt"; rc=$?
summ "inject" "$tmp/inject.txt" $rc
[ $rc -eq "$n_inject" ] || bad "injected-failure run exit $rc (expected $n_inject)"
grep -qxF "[  FAILED  ] $n_inject test(s), listed below:" "$tmp/inject.txt" \
  || bad "no '[  FAILED  ] $n_inject test(s), listed below:' line"
grep -qxF "[  PASSED  ] $n_pass test(s)." "$tmp/inject.txt" \
  || bad "no '[  PASSED  ] $n_pass test(s).' line"
listed=$(grep -c '^\[  FAILED  \] inject_' "$tmp/inject.txt")
[ "$listed" -eq $((2 * n_inject)) ] || bad "inject_* FAILED lines: $listed (expected $((2 * n_inject)))"

# 3. a fault ends the run with 250 and a report
"$run" "$3" 60 > "$tmp/fault.txt"; rc=$?
summ "fault" "$tmp/fault.txt" $rc
[ $rc -eq 250 ] || bad "fault run exit $rc (expected 250)"
grep -q "^\\[$target\\] FAULT: HardFault DIVBYZERO" "$tmp/fault.txt" || bad "no [$target] DIVBYZERO fault report"

# 4. a stack overflow ends the run with 251
"$run" "$4" 60 > "$tmp/overflow.txt"; rc=$?
summ "overflow" "$tmp/overflow.txt" $rc
[ $rc -eq 251 ] || bad "stack-overflow run exit $rc (expected 251)"
grep -q 'main stack overflow' "$tmp/overflow.txt" || bad "no stack-overflow report"

# 5. on the host, the shim prints exactly what cmocka 1.1.5 prints
echo "== host: shim runner vs cmocka $(basename "$5") (stdout, stderr, exit code)"
"$5" > "$tmp/real.out" 2> "$tmp/real.err"; rc_real=$?
"$6" > "$tmp/shim.out" 2> "$tmp/shim.err"; rc_shim=$?
diff -u "$tmp/real.out" "$tmp/shim.out" || bad "stdout differs between cmocka and the shim"
diff -u "$tmp/real.err" "$tmp/shim.err" || bad "stderr differs between cmocka and the shim"
[ $rc_real -eq $rc_shim ] || bad "exit code: cmocka $rc_real, shim $rc_shim"
[ $rc_real -eq "$n_inject" ] || bad "host cmocka exit $rc_real (expected $n_inject)"
[ $problems -eq 0 ] && echo "-- shim output identical to cmocka ($(wc -l < "$tmp/real.out") + $(wc -l < "$tmp/real.err") lines, exit $rc_real)"

if [ $problems -ne 0 ]; then
  dump
  echo "$goal: $problems problem(s)"
  exit 1
fi
echo "$goal: OK (pass run, $n_inject injected failures detected, fault -> 250, stack overflow -> 251, shim == cmocka)"
