#!/usr/bin/env bash
# run_qemu.sh ELF [TIMEOUT_S] -- run one bare-metal ARMv7-M program on a QEMU
# MPS2 board with semihosting, print a header, its output (stdout and stderr
# merged) and a footer with the exit code and wall time. Exits with QEMU's
# exit code: the program's return value (a cmocka group: its number of failed
# tests), 250 fault, 251 stack overflow (port/armv7m/ogk_armv7m.h), 124
# timeout, 134 QEMU abort (CPU lockup).
# Env: TARGET_NAME and QEMU_MACHINE, the core and its board (the make targets
# set both): cortex-m7 on mps2-an500 (the default), cortex-m4f on mps2-an386.
set -u
elf=${1:?usage: run_qemu.sh ELF [TIMEOUT_S]}
limit=${2:-300}
target=${TARGET_NAME:-cortex-m7}
machine=${QEMU_MACHINE:-mps2-an500}
name=$(basename "$elf" .elf)

echo "== $target (qemu $machine): $name"
start=$(date +%s.%N)
timeout --kill-after=5 "$limit" \
  qemu-system-arm -M "$machine" -nographic -monitor none -serial none \
    -semihosting-config enable=on,target=native -kernel "$elf" </dev/null 2>&1
rc=$?
end=$(date +%s.%N)
seconds=$(awk -v a="$start" -v b="$end" 'BEGIN { printf "%.2f", b - a }')

case $rc in
  0)   why="ok" ;;
  124) why="TIMEOUT after ${limit} s" ;;
  134) why="QEMU aborted (CPU lockup?)" ;;
  250) why="FAULT (see the [$target] FAULT line)" ;;
  251) why="STACK OVERFLOW" ;;
  *)   why="$rc failed test(s) or error" ;;
esac
echo "-- $name: qemu exit $rc ($why), ${seconds} s"
exit $rc
