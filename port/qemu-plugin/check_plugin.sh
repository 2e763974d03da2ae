#!/usr/bin/env bash
# check_plugin.sh ELF -- known-answer test of the insn_count plugin on
# known_counts.elf (expected values from the construction of known_counts.c)
# and a repeatability check (two runs, identical reports).
# SPARC V8 (known_counts_sparc.c, qemu-user): QEMU_USER=qemu-sparc32plus NM=sparc64-linux-gnu-nm
# TEN=12 CALLS=17 (ten_nops: 10 nops, retl and its delay slot; calls_ten_nops: save, call, delay
# nop, ret, restore). Defaults: Thumb-2 on the Cortex-M7 (11 and 14); the Cortex-M4F's are the same
# (QEMU_MACHINE=mps2-an386, known_counts linked with the M4F's runtime).
set -u
here=$(dirname "$0")
elf=${1:?usage: check_plugin.sh known_counts.elf}
TEN=${TEN:-11}
CALLS=${CALLS:-14}
count() { "$here/count_insns.sh" "$@"; }
r1=$(count "$elf" ten_nops calls_ten_nops 2>/dev/null); rc=$?
r2=$(count "$elf" ten_nops calls_ten_nops 2>/dev/null)
echo "$r1"
problems=0
expect() { grep -qE "$1" <<< "$r1" || { echo "PLUGIN FAIL: expected /$1/"; problems=$((problems + 1)); }; }
[ $rc -eq 0 ] || { echo "PLUGIN FAIL: qemu exit $rc"; problems=$((problems + 1)); }
expect "^insn_count fn ten_nops entry 0x[0-9a-f]+ calls 6 total $((6 * TEN)) min $TEN max $TEN skipped 1\$"
expect "^insn_count fn calls_ten_nops entry 0x[0-9a-f]+ calls 1 total $CALLS min $CALLS max $CALLS\$"
expect "^insn_count range ten_nops 0x[0-9a-f]+-0x[0-9a-f]+ executed $((7 * TEN))\$"
expect "^insn_count range calls_ten_nops 0x[0-9a-f]+-0x[0-9a-f]+ executed $((CALLS - TEN))\$"
expect '^insn_count total [0-9]+$'
[ "$r1" = "$r2" ] || { echo "PLUGIN FAIL: two runs differ"; problems=$((problems + 1)); }
# calls=: every returned call, in return order: ten_nops (11) six times, the one inside
# calls_ten_nops returning before it (14)
calls=$(mktemp)
CALLS_OUT=$calls count "$elf" ten_nops calls_ten_nops >/dev/null 2>&1
[ "$(grep -c "^ten_nops $TEN\$" "$calls")" = 6 ] && [ "$(grep -c "^calls_ten_nops $CALLS\$" "$calls")" = 1 ] \
  && [ "$(wc -l < "$calls")" = 7 ] \
  && [ "$(grep -B1 "^calls_ten_nops $CALLS\$" "$calls" | head -n 1)" = "ten_nops $TEN" ] \
  || { echo "PLUGIN FAIL: calls= log"; cat "$calls"; problems=$((problems + 1)); }
rm -f "$calls"
if [ $problems -ne 0 ]; then echo "test-qemu-plugin: $problems problem(s)"; exit 1; fi
echo "test-qemu-plugin: OK (known counts exact, two runs identical, the per-call log)"
