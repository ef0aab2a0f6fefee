#!/usr/bin/env bash
# Installs isolux from BUILD_DIR to a temporary prefix, then builds outside
# the repository's build, as games would:
# - the installed headers: isolux/isolux.hpp includes every one, and none
#   declares a test or bench hook (those stay in core/src);
# - a C++ consumer with find_package(isolux) + isolux::core, including
#   isolux/isolux.hpp alone;
# - examples/walk with find_package(isolux) + isolux::isolux (the C API), run
#   headless, its frames checked against the installed isolux-cli;
# - examples/c/render.c with pkg-config's isolux module alone.
# The consumers use the build's own compiler flags (a sanitizer build needs
# them to link). The installed library finds its own default tileset: no
# ISOLUX_ASSETS here.
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
headers="$tmp/prefix/include/isolux"
run test -f "$headers/isolux.hpp"
for h in "$headers"/*; do
  name=$(basename "$h")
  [ "$name" = isolux.hpp ] || run grep -q "#include \"isolux/$name\"" "$headers/isolux.hpp"
done
# The hooks the tests and the bench reach through core/src: none installed.
hooks='bresenham_steps|tree_traces|TreeTraces|trace_light_ray_paper|(box_blur|box_blur_within|composite)_reference|_by_rays|composite_pixel|set_wide_kernels|struct FrameCache \{'
run test -z "$(grep -rlE "$hooks" "$headers")"
run cmake -S "$src/tests/package" -B "$tmp/consumer" -G Ninja -DCMAKE_PREFIX_PATH="$tmp/prefix" \
  -DCMAKE_CXX_COMPILER="$(flag CMAKE_CXX_COMPILER)" -DCMAKE_CXX_FLAGS="$(flag CMAKE_CXX_FLAGS)" \
  -DCMAKE_EXE_LINKER_FLAGS="$(flag CMAKE_EXE_LINKER_FLAGS)"
run cmake --build "$tmp/consumer"
run "$tmp/consumer/consumer"
run test -f "$tmp/prefix/share/isolux/assets/default/tileset.json"
run test -x "$tmp/prefix/bin/isolux-cli"
unset ISOLUX_ASSETS
lib=$(sed -n 's/^CMAKE_INSTALL_LIBDIR:[A-Z]*=//p' "$build/CMakeCache.txt" | head -n 1)
run cmake -S "$src/examples/walk" -B "$tmp/walk" -G Ninja -DCMAKE_PREFIX_PATH="$tmp/prefix" \
  -DCMAKE_C_COMPILER="$(flag CMAKE_C_COMPILER)" -DCMAKE_C_FLAGS="$(flag CMAKE_C_FLAGS)" \
  -DCMAKE_EXE_LINKER_FLAGS="$(flag CMAKE_EXE_LINKER_FLAGS)"
run cmake --build "$tmp/walk"
# --out: headless even under the test suite's Xvfb.
run "$tmp/walk/walk" --out "$tmp/walk-frames" --frames 24
run python3 "$src/tests/package/walk_check.py" "$tmp/prefix/bin/isolux-cli" "$src/examples/walk/level.json" "$tmp/walk-frames"
cat "$tmp/log" | grep -E "^frame|^walk" || true
: >"$tmp/log"
export PKG_CONFIG_PATH="$tmp/prefix/$lib/pkgconfig"
run test "$(pkg-config --modversion isolux)" = "$(sed -n 's/^CMAKE_PROJECT_VERSION:[A-Z]*=//p' "$build/CMakeCache.txt")"
# shellcheck disable=SC2046
run "$(flag CMAKE_C_COMPILER)" $(flag CMAKE_C_FLAGS) "$src/examples/c/render.c" -o "$tmp/render" \
  $(pkg-config --cflags --libs isolux) $(flag CMAKE_EXE_LINKER_FLAGS)
LD_LIBRARY_PATH="$tmp/prefix/$lib" run "$tmp/render" "$src/assets/scenes/default.json" "$tmp/default.pam"
run "$tmp/prefix/bin/isolux-cli" render --scene "$src/assets/scenes/default.json" --out "$tmp/default.png"
run python3 -c "
import sys; sys.path.insert(0, '$src/tests/capi')
from png_rgba import png_rgba
w, h, px = png_rgba('$tmp/default.png')
body = open('$tmp/default.pam', 'rb').read().split(b'ENDHDR\\n', 1)[1]
sys.exit(0 if body == px else 'render.c built with pkg-config: not isolux-cli\\'s bytes')"
echo "package: 5 passed, 0 failed"
