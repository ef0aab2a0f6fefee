#!/usr/bin/env bash
# Installs isolux from BUILD_DIR to a temporary prefix and builds a consumer
# with find_package(isolux) + isolux::core, then runs it. The consumer uses
# the build's own compiler flags (a sanitizer build needs them to link).
set -u
build=$1
src=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
flag() { sed -n "s/^$1:[A-Z]*=//p" "$build/CMakeCache.txt" | head -n 1; }
run() {
  if ! "$@" >>"$tmp/log" 2>&1; then
    echo "FAIL: $*"; cat "$tmp/log"; echo "package: 0 passed, 1 failed"; exit 1
  fi
}
run cmake --install "$build" --prefix "$tmp/prefix"
run cmake -S "$src/tests/package" -B "$tmp/consumer" -G Ninja -DCMAKE_PREFIX_PATH="$tmp/prefix" \
  -DCMAKE_CXX_COMPILER="$(flag CMAKE_CXX_COMPILER)" -DCMAKE_CXX_FLAGS="$(flag CMAKE_CXX_FLAGS)" \
  -DCMAKE_EXE_LINKER_FLAGS="$(flag CMAKE_EXE_LINKER_FLAGS)"
run cmake --build "$tmp/consumer"
run "$tmp/consumer/consumer"
run test -f "$tmp/prefix/share/isolux/assets/default/tileset.json"
run test -x "$tmp/prefix/bin/isolux-cli"
echo "package: 1 passed, 0 failed"
