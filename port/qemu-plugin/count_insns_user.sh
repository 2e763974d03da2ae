#!/usr/bin/env bash
# count_insns_user.sh QEMU NM ELF FUNCTION... -- count_insns.sh for a Linux user-mode QEMU (the SPARC V8
# route: qemu-sparc32plus, sparc64-linux-gnu-nm): the same plugin items (fn and range per FUNCTION) and
# report. The program's own output goes to stderr; the report to stdout.
# Env: QEMU_PLUGIN_SO (default build/qemu-plugin/libinsn_count.so); CALLS_OUT=PATH as in count_insns.sh.
set -euo pipefail
qemu=${1:?usage: count_insns_user.sh QEMU NM ELF FUNCTION...}
nm=${2:?}
elf=${3:?}
shift 3
so=${QEMU_PLUGIN_SO:-build/qemu-plugin/libinsn_count.so}
[ -f "$so" ] || { echo "count_insns_user.sh: $so not built (make qemu-plugin)" >&2; exit 2; }
args=""
for fn in "$@"; do
  line=$("$nm" -S "$elf" | awk -v f="$fn" '!done && $4 == f && ($3 == "T" || $3 == "t") { print $1, $2; done = 1 }')
  [ -n "$line" ] || { echo "count_insns_user.sh: no function '$fn' with a size in $elf" >&2; exit 2; }
  read -r addr size <<< "$line"
  lo=$((16#$addr)); hi=$((lo + 16#$size))
  args="$args,fn=$fn@$(printf '0x%08x' $lo),range=$fn@$(printf '0x%08x-0x%08x' $lo $hi)"
done
report=$(mktemp)
trap 'rm -f "$report"' EXIT
set +e
"$qemu" -plugin "$(realpath "$so")$args${CALLS_OUT:+,calls=$CALLS_OUT},out=$report" -d plugin "$elf" </dev/null >&2 2>&1
rc=$?
set -e
cat "$report"
exit $rc
