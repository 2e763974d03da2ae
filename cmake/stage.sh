#!/bin/sh
# stage.sh BUILD_DIR STAGE_DIR -- puts what the CMake build in BUILD_DIR made of the kernel where the
# Makefile's rules read it: STAGE_DIR/libogk.a (and libogk.so where built), and each object with its
# -fstack-usage file as STAGE_DIR/kernel/<module>/<name>.o / .su (the stack bound, footprint and size
# evidence reads the very objects the library holds). The object list is CMake's own
# (BUILD_DIR/ogk_objects.txt), so nothing here knows CMake's directory layout.
set -eu
build=$1
stage=$2
rm -rf "$stage/kernel" # a removed source leaves no stale object or .su behind
while read -r obj; do
  [ -n "$obj" ] || continue
  rel=${obj##*/ogk_objects.dir/kernel/src/}
  mkdir -p "$stage/kernel/$(dirname "$rel")"
  cp "$obj" "$stage/kernel/$rel"
  if [ -f "${obj%.o}.su" ]; then cp "${obj%.o}.su" "$stage/kernel/${rel%.o}.su"; fi
done < "$build/ogk_objects.txt"
cp "$build/libogk.a" "$stage/libogk.a"
if [ -e "$build/libogk.so" ]; then cp -L "$build/libogk.so" "$stage/libogk.so"; fi
