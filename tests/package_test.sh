#!/usr/bin/env bash
# Installs isolux from BUILD_DIR to a temporary prefix and builds a consumer
# with find_package(isolux) + isolux::core, then runs it.
set -eu
build=$1
src=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cmake --install "$build" --prefix "$tmp/prefix" >/dev/null
cmake -S "$src/tests/package" -B "$tmp/consumer" -G Ninja -DCMAKE_PREFIX_PATH="$tmp/prefix" >/dev/null
cmake --build "$tmp/consumer" >/dev/null
"$tmp/consumer/consumer"
test -f "$tmp/prefix/share/isolux/assets/default/tileset.json"
test -x "$tmp/prefix/bin/isolux-cli"
echo "package: 1 passed, 0 failed"
