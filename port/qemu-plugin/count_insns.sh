#!/usr/bin/env bash
# count_insns.sh ELF FUNCTION... -- run a bare-metal ARMv7-M ELF on QEMU
# (mps2-an500, the Cortex-M7; QEMU_MACHINE=mps2-an386 for the Cortex-M4F)
# with the insn_count plugin and print, for each FUNCTION, the
# instructions executed per call including callees (fn) and inside its own
# body only (range). Addresses and sizes come from arm-none-eabi-nm -S.
# The program's own output goes to stderr; the report to stdout.
# Env: QEMU_PLUGIN_SO (default build/qemu-plugin/libinsn_count.so); CALLS_OUT=PATH: every
# call's count, one line `NAME COUNT` per returned call (the plugin's calls= option).
# QEMU_USER=qemu-sparc32plus NM=sparc64-linux-gnu-nm: a Linux user-mode program instead (SPARC V8:
# calls return after their delay slot, which the plugin knows from the target's name).
set -euo pipefail
elf=${1:?usage: count_insns.sh ELF FUNCTION...}
shift
so=${QEMU_PLUGIN_SO:-build/qemu-plugin/libinsn_count.so}
[ -f "$so" ] || { echo "count_insns.sh: $so not built (make qemu-plugin)" >&2; exit 2; }
args=""
for fn in "$@"; do
  line=$("${NM:-arm-none-eabi-nm}" -S "$elf" | awk -v f="$fn" '!done && $4 == f && ($3 == "T" || $3 == "t") { print $1, $2; done = 1 }')
  [ -n "$line" ] || { echo "count_insns.sh: no function '$fn' with a size in $elf" >&2; exit 2; }
  read -r addr size <<< "$line"
  lo=$((16#$addr)); hi=$((lo + 16#$size))
  args="$args,fn=$fn@$(printf '0x%08x' $lo),range=$fn@$(printf '0x%08x-0x%08x' $lo $hi)"
done
report=$(mktemp)
trap 'rm -f "$report"' EXIT
plugin="$(realpath "$so")$args${CALLS_OUT:+,calls=$CALLS_OUT},out=$report"
set +e
if [ -n "${QEMU_USER:-}" ]; then
  "$QEMU_USER" -plugin "$plugin" -d plugin "$elf" </dev/null >&2 2>&1
else
  qemu-system-arm -M "${QEMU_MACHINE:-mps2-an500}" -nographic -monitor none -serial none \
    -semihosting-config enable=on,target=native -plugin "$plugin" -d plugin \
    -kernel "$elf" </dev/null >&2 2>&1
fi
rc=$?
set -e
cat "$report"
exit $rc
