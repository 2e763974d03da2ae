#!/usr/bin/env bash
# run_qemu.sh ELF [TIMEOUT_S] -- run one bare-metal Cortex-M7 program on QEMU's
# mps2-an500 board with semihosting, print a header, its output (stdout and
# stderr merged) and a footer with the exit code and wall time. Exits with
# QEMU's exit code: the program's return value (a cmocka group: its number of
# failed tests), 250 fault, 251 stack overflow (port/cortex-m7/ogk_cm7.h),
# 124 timeout, 134 QEMU abort (CPU lockup).
set -u
elf=${1:?usage: run_qemu.sh ELF [TIMEOUT_S]}
limit=${2:-300}
name=$(basename "$elf" .elf)

echo "== cortex-m7 (qemu mps2-an500): $name"
start=$(date +%s.%N)
timeout --kill-after=5 "$limit" \
  qemu-system-arm -M mps2-an500 -nographic -monitor none -serial none \
    -semihosting-config enable=on,target=native -kernel "$elf" </dev/null 2>&1
rc=$?
end=$(date +%s.%N)
seconds=$(awk -v a="$start" -v b="$end" 'BEGIN { printf "%.2f", b - a }')

case $rc in
  0)   why="ok" ;;
  124) why="TIMEOUT after ${limit} s" ;;
  134) why="QEMU aborted (CPU lockup?)" ;;
  250) why="FAULT (see the [cortex-m7] FAULT line)" ;;
  251) why="STACK OVERFLOW" ;;
  *)   why="$rc failed test(s) or error" ;;
esac
echo "-- $name: qemu exit $rc ($why), ${seconds} s"
exit $rc
