#!/usr/bin/env bash
# isolux-cli end to end: exit codes, one-line errors, byte-identical renders.
# Usage: cli_test.sh PATH/TO/isolux-cli SOURCE_DIR
set -u
cli=$1
src=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail=0
pass=0

check() {  # check NAME EXPECTED_EXIT STDERR_PATTERN -- ARGS...
  local name=$1 want=$2 pattern=$3
  shift 4
  "$cli" "$@" >"$tmp/out" 2>"$tmp/err"
  local got=$?
  if [ "$got" -ne "$want" ]; then
    echo "FAIL $name: exit $got, want $want"; cat "$tmp/err"; fail=$((fail + 1)); return
  fi
  if [ -n "$pattern" ] && ! grep -q -- "$pattern" "$tmp/err"; then
    echo "FAIL $name: stderr lacks '$pattern'"; cat "$tmp/err"; fail=$((fail + 1)); return
  fi
  if [ "$want" -eq 2 ] && [ "$(wc -l <"$tmp/err")" -ne 1 ]; then
    echo "FAIL $name: error is not one line"; cat "$tmp/err"; fail=$((fail + 1)); return
  fi
  pass=$((pass + 1))
}

check render_default 0 "" -- render --size 6x6 --out "$tmp/a.png"
check render_again 0 "" -- render --size 6x6 --out "$tmp/b.png"
if cmp -s "$tmp/a.png" "$tmp/b.png"; then pass=$((pass + 1)); else echo "FAIL same seed, different bytes"; fail=$((fail + 1)); fi
check render_other_seed 0 "" -- render --size 6x6 --seed other --out "$tmp/c.png"
if cmp -s "$tmp/a.png" "$tmp/c.png"; then echo "FAIL another seed rendered the same map"; fail=$((fail + 1)); else pass=$((pass + 1)); fi
for layout in paper diamond staggered; do
  check "layout_$layout" 0 "" -- render --size 5x4 --layout $layout --out "$tmp/l_$layout.png"
done
for layer in map obstacles opacity; do
  check "layer_$layer" 0 "" -- render --size 5x5 --layer $layer --out "$tmp/layer_$layer.png"
done
check foreign_tileset 0 "" -- render --size 5x5 --tileset "$src/tests/data/foreign_tileset/tileset.json" --layer obstacles --out "$tmp/f.png"
check view_of_a_256_map 0 "" -- render --size 256x256 --view 16000,8000,300,200 --out "$tmp/v.png"
check whole_256_map_too_large 2 "256-megapixel" -- render --size 256x256 --out "$tmp/huge.png"
check size_zero 2 "--size" -- render --size 0x5 --out "$tmp/x.png"
check size_negative 2 "--size" -- render --size -3x5 --out "$tmp/x.png"
check size_too_large 2 "1024" -- render --size 5000x5 --out "$tmp/x.png"
check size_garbage 2 "WxH" -- render --size big --out "$tmp/x.png"
check bad_layout 2 "layout" -- render --layout hex --out "$tmp/x.png"
check bad_layer 2 "layer" -- render --layer nope --out "$tmp/x.png"
check missing_tileset 2 "nowhere.json" -- render --tileset "$tmp/nowhere.json" --out "$tmp/x.png"
echo '{"noise_window": 0}' >"$tmp/bad_preset.json"
check bad_preset 2 "noise_window" -- render --preset "$tmp/bad_preset.json" --out "$tmp/x.png"
echo '{"seed": "s", "width": ' >"$tmp/bad_scene.json"
check bad_scene 2 "bad_scene.json" -- render --scene "$tmp/bad_scene.json" --out "$tmp/x.png"
check bad_out_ext 2 "extension" -- render --size 3x3 --out "$tmp/x.bmp"
check no_subcommand 2 "" --
check builtin_preset 0 "" -- render --size 3x3 --preset fast --out "$tmp/p.png"
check tileset_regen 0 "" -- tileset --out "$tmp/tiles"
for f in "$src"/assets/default/*.png; do
  if ! cmp -s "$f" "$tmp/tiles/$(basename "$f")"; then
    echo "FAIL tileset regeneration differs: $(basename "$f")"; fail=$((fail + 1))
  fi
done
if cmp -s "$src/assets/default/tileset.json" "$tmp/tiles/tileset.json"; then pass=$((pass + 1)); else
  echo "FAIL tileset.json differs from the committed one"; fail=$((fail + 1)); fi

echo "cli: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
