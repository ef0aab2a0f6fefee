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

# Lighting (paper 3.2): lights, layers, frames and every override flag.
check light_final 0 "" -- render --size 6x6 --light 400,250 --light 600,300,64,48,ffa040 --out "$tmp/lf.png"
check light_layer 0 "" -- render --size 6x6 --light 400,250 --layer light --out "$tmp/ll.png"
check light_outside_map 0 "" -- render --size 6x6 --light -100,-100,200,200 --out "$tmp/lo.png"
check frames 0 "" -- render --size 6x6 --light 400,250 --frames 5 --camera-step 3,2 --trace-every 2 --out "$tmp/fr.png"
if grep -q "frame 4:" "$tmp/out"; then pass=$((pass + 1)); else echo "FAIL --frames printed no per-frame stages"; fail=$((fail + 1)); fi
check overrides 0 "" -- render --size 6x6 --light 400,250 --ray-skip 2 --ambient 0.3 --mode shadow --delta-y 20 \
  --noise-window 2 --area 50,40 --blur 1 --trace-every 2 --falloff-scale 4 --dark-unlit --rays every_pixel --out "$tmp/ov.png"
check neg_area 2 "--area" -- render --size 3x3 --area -1,5 --out "$tmp/x.png"
check noise_zero 2 "noise" -- render --size 3x3 --noise-window 0 --out "$tmp/x.png"
check ambient_high 2 "ambient" -- render --size 3x3 --ambient 1.5 --out "$tmp/x.png"
check ambient_low 2 "ambient" -- render --size 3x3 --ambient -0.1 --out "$tmp/x.png"
check skip_zero 2 "ray_skip" -- render --size 3x3 --ray-skip 0 --out "$tmp/x.png"
check every_zero 2 "trace_every" -- render --size 3x3 --trace-every 0 --out "$tmp/x.png"
check bad_mode 2 "mode" -- render --size 3x3 --mode laser --out "$tmp/x.png"
check bad_light 2 "--light" -- render --size 3x3 --light 1 --out "$tmp/x.png"
check bad_light_color 2 "colour" -- render --size 3x3 --light 1,2,3,4,xyz --out "$tmp/x.png"
check bad_light_area 2 "--light" -- render --size 3x3 --light 1,2,-3,4 --out "$tmp/x.png"
check bad_falloff 2 "falloff" -- render --size 3x3 --falloff-scale 0 --out "$tmp/x.png"
check light_twice_same 0 "" -- render --size 6x6 --light 400,250 --out "$tmp/l1.png"
check light_twice_same2 0 "" -- render --size 6x6 --light 400,250 --out "$tmp/l2.png"
if cmp -s "$tmp/l1.png" "$tmp/l2.png"; then pass=$((pass + 1)); else echo "FAIL lit render not byte-identical"; fail=$((fail + 1)); fi
if cmp -s "$tmp/l1.png" "$tmp/a.png"; then echo "FAIL a light changed nothing"; fail=$((fail + 1)); else pass=$((pass + 1)); fi

# A camera at a fractional, negative position: the CLI rounds it as core does
# (floor), so it renders the same pixels as the explicit view.
cat >"$tmp/cam.json" <<'JSON'
{"schema_version": 1, "width": 6, "height": 6, "lights": [{"x": 300, "y": 200}],
 "camera": {"x": -10.5, "y": 20.25, "width": 96, "height": 64}}
JSON
check camera_floor 0 "" -- render --scene "$tmp/cam.json" --out "$tmp/cam.png"
check camera_view 0 "" -- render --scene "$tmp/cam.json" --view -11,20,96,64 --out "$tmp/view.png"
if cmp -s "$tmp/cam.png" "$tmp/view.png"; then pass=$((pass + 1)); else echo "FAIL camera rounded differently from core"; fail=$((fail + 1)); fi
# Old flag names stay as aliases of the table's.
check blur_alias 0 "" -- render --size 4x4 --light 200,100 --blur 3 --out "$tmp/blur_old.png"
check blur_new 0 "" -- render --size 4x4 --light 200,100 --blur-radius 3 --out "$tmp/blur_new.png"
if cmp -s "$tmp/blur_old.png" "$tmp/blur_new.png"; then pass=$((pass + 1)); else echo "FAIL --blur and --blur-radius differ"; fail=$((fail + 1)); fi
echo '{"schema_version": 1, "delta_y": 1e999}' >"$tmp/huge_number.json"
check json_huge_number 2 "malformed JSON" -- render --preset "$tmp/huge_number.json" --out "$tmp/x.png"

# The 3D reference: the truth's lit frame and where the model disagrees with it.
check truth 0 "" -- render --size 6x6 --light 400,250,h=48 --layer truth --out "$tmp/truth.png"
check difference 0 "" -- render --size 6x6 --light 400,250,h=48 --layer difference --reference 3d_facing --out "$tmp/diff.png"
check exact_line 0 "" -- render --size 6x6 --light 400,250 --layer truth --reference exact_line --out "$tmp/exact.png"
if cmp -s "$tmp/truth.png" "$tmp/exact.png"; then echo "FAIL the 3D and exact-line references agree everywhere"; fail=$((fail + 1)); else pass=$((pass + 1)); fi
check bad_reference 2 "reference" -- render --size 3x3 --layer truth --reference magic --out "$tmp/x.png"
check bad_light_height 2 "light_height" -- render --size 3x3 --light 10,10,h=-1 --out "$tmp/x.png"
check truth_needs_shapes 2 "has no shape" -- render --size 5x5 --tileset "$src/tests/data/foreign_tileset/tileset.json" --light 200,100 --layer truth --out "$tmp/x.png"
cat >"$tmp/sweep.json" <<'JSON'
{"schema_version": 1, "width": 6, "height": 6, "lights": [{"x": 400, "y": 250, "height": 24}],
 "camera": {"x": 200, "y": 100, "width": 320, "height": 200}}
JSON
check sweep_references 0 "" -- sweep --scene "$tmp/sweep.json" --param ray_skip=1,4 --reference 3d,every_pixel --frames 2 --repeats 1 --out "$tmp/sweep.csv" --chart "$tmp/sweep.svg"
if [ "$(python3 -c "import csv;print(sorted({r['reference'] for r in csv.DictReader(open('$tmp/sweep.csv'))}))")" = "['3d', 'every_pixel']" ]; then pass=$((pass + 1)); else echo "FAIL the sweep CSV lacks a row per reference"; fail=$((fail + 1)); fi

# check-tileset: every overlay's obstacle against its anchor, as text, JSON and a contact sheet.
check check_tileset 0 "" -- check-tileset "$src/assets/default/tileset.json" --sheet "$tmp/sheet.png"
check check_tileset_json 0 "" -- check-tileset "$src/tests/data/foreign_tileset/tileset.json" --json --footprint paper
cp "$tmp/out" "$tmp/check.json"
if python3 - "$tmp/check.json" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
assert set(d) == {"sprites"} and d["sprites"], d
for s in d["sprites"]:
    assert set(s) == {"name", "obstacle_center", "obstacle_rect", "anchor", "distance", "detected", "warning",
                      "objects", "solid_overlap"}, s
    assert s["obstacle_center"] is None or len(s["obstacle_center"]) == 2
    assert s["obstacle_rect"] is None or len(s["obstacle_rect"]) == 4
    # Each object's footprint is the obstacle's (its centre and box), and its solid stands above the ground.
    assert len(s["objects"]) == (0 if s["obstacle_center"] is None else 1), s
    for o in s["objects"]:
        assert set(o) == {"center", "rect", "height", "model"}, o
        assert o["model"] in ("revolution", "prism", "mound"), o
        # A solid of revolution stands on the footprint's centre (a prism or a mound on its own base).
        if o["model"] == "revolution":
            assert o["center"] == s["obstacle_center"] and o["rect"] == s["obstacle_rect"], s
        assert o["height"] > 0, s
    assert s["solid_overlap"] is None, s  # this tileset has no shapes
PY
then pass=$((pass + 1)); else echo "FAIL check-tileset --json is not the documented shape"; fail=$((fail + 1)); fi
[ -s "$tmp/sheet.png" ] && pass=$((pass + 1)) || { echo "FAIL no contact sheet"; fail=$((fail + 1)); }
# The town tileset: walls and houses are prisms, the tall tree a solid of revolution, and the contact sheet draws them.
check check_tileset_town 0 "" -- check-tileset "$src/assets/town/tileset.json" --json --occluders solids --sheet "$tmp/town_sheet.png"
if python3 - "$tmp/out" <<'PY'
import json, sys
models = {s["name"]: [o["model"] for o in s["objects"]] for s in json.load(open(sys.argv[1]))["sprites"]}
for name in ("long_wall", "house", "hedge"):
    assert models[name] == ["prism"], (name, models[name])
assert models["tall_tree"] == ["revolution"], models["tall_tree"]
PY
then pass=$((pass + 1)); else echo "FAIL check-tileset --json: the town's models"; fail=$((fail + 1)); fi
[ -s "$tmp/town_sheet.png" ] && pass=$((pass + 1)) || { echo "FAIL no town contact sheet"; fail=$((fail + 1)); }
check check_tileset_bad 2 "tileset.json" -- check-tileset "$tmp/nowhere/tileset.json"

# normals: a normal map (8-bit RGB) and a height map (16-bit grey) per sprite, never over the tileset's files.
check normals 0 "" -- normals --tileset "$src/assets/default/tileset.json" --out "$tmp/normals"
check normals_directx 0 "" -- normals --tileset "$src/assets/default/tileset.json" --out "$tmp/normals_dx" --convention directx
check normals_luminance 0 "" -- normals --tileset "$src/tests/data/foreign_tileset/tileset.json" --out "$tmp/normals_l" --from luminance
if python3 - "$tmp" "$src/assets/default/tileset.json" <<'PY'
import json, os, subprocess, sys
tmp, manifest = sys.argv[1], sys.argv[2]
names = [s["name"] for s in json.load(open(manifest))["sprites"]]
for n in names:
    for kind, want in (("normal", "3 channel, uint8"), ("height", "1 channel, uint16")):
        info = subprocess.run(["oiiotool", "--info", f"{tmp}/normals/{n}.{kind}.png"], capture_output=True, text=True).stdout
        assert want in info, (n, kind, info)
# DirectX's green is OpenGL's upside down; red and blue are the same.
def pixels(path):
    out = subprocess.run(["oiiotool", path, "--ch", "R,G,B", "-d", "uint8", "-o", f"{tmp}/raw.bmp"], capture_output=True)
    data = open(f"{tmp}/raw.bmp", "rb").read()
    return data[-128 * 128 * 3:]
a, b = pixels(f"{tmp}/normals/oak.normal.png"), pixels(f"{tmp}/normals_dx/oak.normal.png")
for i in range(0, len(a), 3):  # BMP stores b, g, r
    assert a[i] == b[i] and a[i + 2] == b[i + 2], i
    assert abs(a[i + 1] + b[i + 1] - 255) <= 1, (i, a[i + 1], b[i + 1])
assert any(a[i + 1] != 128 for i in range(0, len(a), 3))
PY
then pass=$((pass + 1)); else echo "FAIL normals: the files' formats or the conventions"; fail=$((fail + 1)); fi
check normals_over_input 2 "tileset's own files" -- normals --tileset "$src/assets/default/tileset.json" --out "$src/assets/default"
check normals_no_shapes 2 "sprite_shading shapes" -- normals --tileset "$src/tests/data/foreign_tileset/tileset.json" --out "$tmp/normals_s" --from shapes
[ ! -e "$tmp/normals_s" ] && pass=$((pass + 1)) || { echo "FAIL normals --from shapes wrote before it refused"; fail=$((fail + 1)); }
touch "$tmp/afile"
check normals_out_file 2 "is not a folder" -- normals --tileset "$src/assets/default/tileset.json" --out "$tmp/afile"
check normals_bad_from 2 "from" -- normals --tileset "$src/assets/default/tileset.json" --out "$tmp/n" --from hand

# Bad paths and hostile files: a clear refusal naming the file, never a crash or a hang.
mkfifo "$tmp/fifo.json"
ln -s "$tmp/loop_b.json" "$tmp/loop_a.json"; ln -s "$tmp/loop_a.json" "$tmp/loop_b.json"
mkdir -p "$tmp/adir.json"
check fifo_scene 2 "FIFO" -- render --scene "$tmp/fifo.json" --out "$tmp/x.png"
check loop_scene 2 "loop_a.json" -- render --scene "$tmp/loop_a.json" --out "$tmp/x.png"
check dir_scene 2 "folder" -- render --scene "$tmp/adir.json" --out "$tmp/x.png"
check devzero_preset 2 "device" -- render --size 3x3 --preset /dev/zero --out "$tmp/x.png"
mkdir -p "$tmp/bad_ts"
cp "$src/assets/default/grass.png" "$tmp/bad_ts/grass.png"
python3 - "$tmp/bad_ts/huge.png" <<'PY'
import struct, sys, zlib
def chunk(kind, data):
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xffffffff)
ihdr = struct.pack(">IIBBBBB", 65536, 65536, 8, 6, 0, 0, 0)
open(sys.argv[1], "wb").write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", ihdr) + chunk(b"IDAT", zlib.compress(b"\0")) + chunk(b"IEND", b""))
PY
ts_with() {  # ts_with OVERLAY_JSON: a manifest with a grass floor and one overlay
  printf '{"sprites": [{"name": "grass", "image": "grass.png", "kind": "floor", "tags": ["grass"]}, %s]}' "$1" >"$tmp/bad_ts/tileset.json"
}
ts_with '{"name": "big", "image": "huge.png", "kind": "overlay"}'
check huge_png 2 "megapixels" -- render --size 3x3 --tileset "$tmp/bad_ts/tileset.json" --out "$tmp/x.png"
ts_with '{"name": "far", "image": "grass.png", "rect": [2147483640, 0, 16, 16], "kind": "overlay"}'
check rect_overflow 2 "lies outside" -- render --size 3x3 --tileset "$tmp/bad_ts/tileset.json" --out "$tmp/x.png"
ts_with '{"name": "wrap", "image": "grass.png", "rect": [4294967297, 0, 16, 16], "kind": "overlay"}'
check rect_wrap 2 "lies outside" -- render --size 3x3 --tileset "$tmp/bad_ts/tileset.json" --out "$tmp/x.png"
ts_with '{"name": "lost", "image": "grass.png", "anchor": [-2147483648, 0], "kind": "overlay"}'
check anchor_min 2 "anchor" -- render --size 3x3 --tileset "$tmp/bad_ts/tileset.json" --out "$tmp/x.png"
ts_with '{"name": "pipe", "image": "../fifo.json", "kind": "overlay"}'
check fifo_image 2 "FIFO" -- render --size 3x3 --tileset "$tmp/bad_ts/tileset.json" --out "$tmp/x.png"

check out_is_a_folder 2 "is a folder" -- render --size 3x3 --out "$tmp/adir.json"

# Work known to take minutes is refused up front, with the flag that allows it.
check huge_area 2 "allow-huge" -- render --size 3x3 --light 100,100 --area 4096,4096 --rays every_pixel --out "$tmp/x.png"
check huge_quality 2 "allow-huge" -- render --size 3x3 --light 100,100 --preset quality --area 4096,4096 --out "$tmp/x.png"

# --stats: every stage that ran, with its time and rectangle; two threads
# give the same pixels as one.
check stats 0 "" -- render --size 8x8 --view 100,50,400,300 --light 200,150 --light 420,280 --frames 2 \
  --camera-step 0,0 --stats --out "$tmp/s1.png"
if grep -q "^frame 0: .* ms; 2 lights traced" "$tmp/out" && grep -qE "^  blur +[0-9.]+ ms  touched [0-9]+x[0-9]+ at " "$tmp/out" \
  && grep -qE "^  composite +[0-9.]+ ms  touched 400x300 at 100,50" "$tmp/out" \
  && grep -qE "^  opacity_correction +[0-9.]+ ms  touched [0-9]+x[0-9]+ at [-0-9]+,[-0-9]+ in [0-9]+ rectangles, [0-9]+ pixels" "$tmp/out"; then
  pass=$((pass + 1))
else
  echo "FAIL stats_lines: --stats output lacks a stage line"; cat "$tmp/out"; fail=$((fail + 1))
fi
check threads_two 0 "" -- render --size 8x8 --view 100,50,400,300 --light 200,150 --light 420,280 --threads 2 --out "$tmp/s2.png"
if cmp -s "$tmp/s1.png" "$tmp/s2.png"; then pass=$((pass + 1)); else echo "FAIL threads_same_pixels"; fail=$((fail + 1)); fi
check threads_range 2 "threads" -- render --size 3x3 --threads 999 --out "$tmp/x.png"

# Endless worlds: a view far out renders at its size; the same place from a
# scene file with "endless" sides and a camera gives the same pixels; an
# endless scene is refused where a map with an edge is needed.
check endless_far 0 "" -- render --size endless --view 64000000000,32000000000,400,300 --light 64000000200,32000000150 \
  --preset game --out "$tmp/e1.png"
if grep -q "(400x300," "$tmp/out"; then pass=$((pass + 1)); else echo "FAIL endless_far_size"; cat "$tmp/out"; fail=$((fail + 1)); fi
cat > "$tmp/endless.json" <<'JSON'
{"schema_version": 1, "width": "endless", "height": "endless", "preset": "game",
 "lights": [{"x": 64000000200, "y": 32000000150}], "camera": {"x": 64000000000, "y": 32000000000, "width": 400, "height": 300}}
JSON
check endless_scene 0 "" -- render --scene "$tmp/endless.json" --out "$tmp/e2.png"
if cmp -s "$tmp/e1.png" "$tmp/e2.png"; then pass=$((pass + 1)); else echo "FAIL endless_scene_same_pixels"; fail=$((fail + 1)); fi
check endless_export_refused 2 "endless world" -- export-tiled --scene "$tmp/endless.json" --out "$tmp/endless_level.tmx"
# A walk of six frames ends on the pixels of a render of its last view.
check endless_walk 0 "" -- render --size endless --view 100000,50000,400,300 --light 100700,50400 --frames 6 \
  --camera-step 120,60 --out "$tmp/walk.png"
check endless_walk_end 0 "" -- render --size endless --view 100600,50300,400,300 --light 100700,50400 --out "$tmp/walk_end.png"
if cmp -s "$tmp/walk.png" "$tmp/walk_end.png"; then pass=$((pass + 1)); else echo "FAIL endless_walk_same_pixels"; fail=$((fail + 1)); fi

# A flag every light overrides changes nothing, and says so on stderr (one
# line naming it); a flag some light takes from the preset says nothing.
show="$src/assets/scenes/showcase.json"
check override_height 0 "--light-height changes nothing: each of the 3 lights gives its own height" -- \
  render --scene "$show" --view 600,350,64,48 --light-height 100 --out "$tmp/o1.png"
check override_none 0 "" -- render --scene "$show" --view 600,350,64,48 --out "$tmp/o2.png"
if cmp -s "$tmp/o1.png" "$tmp/o2.png"; then pass=$((pass + 1)); else echo "FAIL override_height_same_pixels"; fail=$((fail + 1)); fi
if grep -q "changes nothing" "$tmp/err"; then echo "FAIL override_none said something"; fail=$((fail + 1)); else pass=$((pass + 1)); fi
check override_area 0 "--area changes nothing: the one light gives its own a (half-width)" -- \
  render --size 4x4 --light 200,100,30,20 --area 40,40 --out "$tmp/o3.png"
check override_partly 0 "" -- render --size 4x4 --light 200,100,30,20 --light 100,80 --area 40,40 --out "$tmp/o4.png"
if grep -q "changes nothing" "$tmp/err"; then echo "FAIL override_partly said something"; fail=$((fail + 1)); else pass=$((pass + 1)); fi
cat > "$tmp/high.json" <<'JSON'
{"schema_version": 1, "width": 4, "height": 4, "preset": {"area_a": 24, "area_b": 24},
 "lights": [{"x": 200, "y": 100, "height": 40}]}
JSON
check override_sweep 0 "--param light_height changes nothing: the one light gives its own height" -- \
  sweep --scene "$tmp/high.json" --param light_height=20,60 --no-carried-light --frames 1 --repeats 1 --out "$tmp/o.csv"

echo "cli: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
