#!/bin/bash
# run_fuzz.sh BUILD_DIR SECONDS TARGET... -- runs each libFuzzer harness BUILD_DIR/fuzz_TARGET for
# SECONDS on its working corpus BUILD_DIR/corpus/TARGET (seeded from tests/fuzz/corpus/TARGET),
# prints executions, corpus size and coverage per target, and fails if any harness found a crash,
# a leak, a timeout or a sanitizer report (artifacts in BUILD_DIR/artifacts/).
set -u
b=$1; secs=$2; shift 2
fail=0
mkdir -p "$b/artifacts" "$b/logs"
for t in "$@"; do
  work="$b/corpus/$t"; seeds="tests/fuzz/corpus/$t"
  mkdir -p "$work"
  log="$b/logs/$t.log"
  "$b/fuzz_$t" -max_total_time="$secs" -max_len=16400 -timeout=10 -rss_limit_mb=2048 \
    -print_final_stats=1 -artifact_prefix="$b/artifacts/$t-" "$work" "$seeds" > "$log" 2>&1
  rc=$?
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  cov=$(grep -o 'cov: [0-9]*' "$log" | tail -1)
  n=$(ls "$work" | wc -l)
  if [ $rc -ne 0 ]; then
    fail=1
    echo "fuzz: $t: FAILED (exit $rc) after ${execs:-?} executions; log $log"
    grep -E 'ERROR|runtime error|fuzz oracle|SUMMARY|Test unit written' "$log" | head -8
  else
    echo "fuzz: $t: ${execs:-?} executions in ${secs} s, ${cov:-cov: ?}, corpus $n, no finding"
  fi
done
exit $fail
