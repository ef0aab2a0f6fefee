#!/usr/bin/env bash
# The isolux app driven end to end under a display (ctest runs inside
# xvfb-run): a headless screenshot held to isolux-cli's render, and scripted
# input (place a light, move a slider, undo, save a preset and a scene).
# Usage: app_test.sh PATH/TO/isolux PATH/TO/isolux-cli SOURCE_DIR
set -u
app_bin=$1
cli=$2
src=$3
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
export ISOLUX_CONFIG_DIR="$tmp/config"
# The scripted runs click at places of a 1600x900 window: they ask for that
# size (an explicit size is exact; only a remembered or default one is fitted
# to the screen, which section 7 tests with the binary itself).
app="$tmp/isolux-1600x900"
cat >"$app" <<WRAP
#!/usr/bin/env bash
case " \$* " in *" --width "*) exec "$app_bin" "\$@" ;; *) exec "$app_bin" --width 1600 --height 900 "\$@" ;; esac
WRAP
chmod +x "$app"
# Under the sanitizers (scripts/sanitize.sh), the GL driver's own allocations
# (Mesa's JIT, unloaded at exit) read as leaks that no suppression can name:
# leak checking is off for the app's processes; ASan and UBSan stay on.
export ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0"
pass=0
fail=0
ok() { pass=$((pass + 1)); }
bad() { echo "FAIL $*"; fail=$((fail + 1)); }
json() { python3 -c "import json,sys; d=json.load(open(sys.argv[1])); print(eval(sys.argv[2]))" "$1" "$2"; }
# refused_screenshot NAME SCENE PATTERN: a screenshot run of SCENE stops with
# exit code 2, a message matching PATTERN (grep) and no picture.
refused_screenshot() {
  timeout 60 "$app" --scene "$2" --frames 2 --screenshot "$tmp/$1.png" >"$tmp/log" 2>&1; local code=$?
  if [ "$code" -eq 2 ] && grep -q "$3" "$tmp/log" && [ ! -e "$tmp/$1.png" ]; then ok
  else bad "$1 screenshot: exit $code"; cat "$tmp/log"; fi
}

# 1. Headless screenshot of the default scene, against the CPU renderer.
if timeout 120 "$app" --scene "$src/assets/scenes/default.json" --frames 3 --screenshot "$tmp/shot.png" >"$tmp/log" 2>&1; then ok; else bad "screenshot run"; cat "$tmp/log"; fi
"$cli" render --scene "$src/assets/scenes/default.json" --out "$tmp/cli.png" >/dev/null
# Within 2/255 on every pixel and channel.
if idiff -fail 0.0079 -warn 0.0079 "$tmp/shot.png" "$tmp/cli.png" >"$tmp/idiff" 2>&1; then ok; else bad "screenshot differs from isolux-cli"; cat "$tmp/idiff"; fi

# 1b. The tracer: the GPU's compute shader (--tracer gpu; llvmpipe has
# compute shaders) gives the CPU's pixels; the automatic choice takes the CPU
# on a software renderer, and says so.
timeout 120 "$app" --scene "$src/assets/scenes/default.json" --frames 3 --tracer gpu --screenshot "$tmp/gpu.png" >"$tmp/log_gpu" 2>&1 || { bad "gpu tracer run"; cat "$tmp/log_gpu"; }
timeout 120 "$app" --scene "$src/assets/scenes/default.json" --frames 3 --tracer cpu --screenshot "$tmp/cpu.png" >"$tmp/log_cpu" 2>&1 || { bad "cpu tracer run"; cat "$tmp/log_cpu"; }
if grep -q "^isolux: tracer: gpu (setting gpu; GPU tracer on " "$tmp/log_gpu" && grep -q "^isolux: tracer: cpu (setting cpu" "$tmp/log_cpu" \
  && grep -q "^isolux: tracer: cpu (setting auto; GPU tracer on llvmpipe" "$tmp/log" \
  && grep -q "traced by the gpu$" "$tmp/log_gpu" && grep -q "traced by the cpu$" "$tmp/log_cpu"; then ok; else bad "tracer choice"; cat "$tmp/log_gpu" "$tmp/log_cpu" "$tmp/log"; fi
if cmp -s "$tmp/gpu.png" "$tmp/cpu.png"; then ok; else bad "the GPU tracer's frame differs from the CPU tracer's"; fi

# 1c. Work beyond the budget (the CLI's --allow-huge): a script's change
# that would trace minutes is undone with a message, not run; a screenshot of
# such a scene stops with exit code 2, at once.
cat >"$tmp/huge.txt" <<EOF
param rays every_pixel
param area_a 4096
wait 2
save-preset $tmp/after_huge.json
sweep area_a=1024,2048 rays=every_pixel
wait-sweep
save-sweep $tmp/huge_sweep.csv
quit
EOF
timeout 60 "$app" --scene "$src/assets/scenes/default.json" --script "$tmp/huge.txt" >"$tmp/log" 2>&1 || { bad "huge-work script run (exit $?)"; cat "$tmp/log"; }
if grep -q "would trace about .* ray steps (minutes or more): the change was undone" "$tmp/log" \
  && [ "$(json "$tmp/after_huge.json" 'd["area_a"]')" = "128" ] && [ "$(json "$tmp/after_huge.json" 'd["rays"]')" = "every_pixel" ]; then ok
else bad "huge work undone"; cat "$tmp/log"; cat "$tmp/after_huge.json"; fi
# A sweep beyond the budget waits for "Run anyway" (isolux-cli's --allow-huge): none of it runs.
if grep -q "this sweep would trace about .* ray steps (minutes or more)" "$tmp/log" && [ "$(wc -l <"$tmp/huge_sweep.csv")" -eq 1 ]; then ok
else bad "huge sweep not started"; cat "$tmp/log"; cat "$tmp/huge_sweep.csv"; fi
python3 -c "import json,sys; d=json.load(open(sys.argv[1])); d['preset'].update(rays='every_pixel', area_a=4096, area_b=4096); json.dump(d, open(sys.argv[2], 'w'))" \
  "$src/assets/scenes/default.json" "$tmp/huge_scene.json"
refused_screenshot huge "$tmp/huge_scene.json" "would trace about .* ray steps"

# 1c'. A frame core refuses (occluders shapes on a tileset without shapes)
# undoes the change that asked for it, with the reason, and the app goes on;
# a screenshot of such a scene stops with exit code 2 and the reason.
python3 -c "import json,sys; d=json.load(open(sys.argv[1])); d['tileset']=sys.argv[2]; json.dump(d, open(sys.argv[3], 'w'))" \
  "$src/assets/scenes/default.json" "$src/tests/data/foreign_tileset/tileset.json" "$tmp/no_shapes.json"
cat >"$tmp/shapes.txt" <<EOF
param occluders shapes
wait 2
save-preset $tmp/after_shapes.json
quit
EOF
timeout 60 "$app" --scene "$tmp/no_shapes.json" --script "$tmp/shapes.txt" >"$tmp/log" 2>&1; code=$?
if [ "$code" -eq 0 ] && grep -q 'has no shape: .*: the change was undone' "$tmp/log" \
  && [ "$(json "$tmp/after_shapes.json" 'd["occluders"]')" = "footprints" ]; then ok
else bad "refused frame undone: exit $code"; cat "$tmp/log"; fi
python3 -c "import json,sys; d=json.load(open(sys.argv[1])); d['preset']['occluders']='shapes'; json.dump(d, open(sys.argv[2], 'w'))" \
  "$tmp/no_shapes.json" "$tmp/no_shapes_shapes.json"
refused_screenshot refused "$tmp/no_shapes_shapes.json" "has no shape"

# 1d. Approved long work runs on a worker with progress and Cancel: the
# script approves it (as "Trace it" would) and presses the prompt's Cancel
# once rays are under way; the trace stops at once, the change is kept and
# the app goes on. A long trace that finishes is picked up as a frame: one
# light of 2601x2601 pixels (8.8e9 estimated steps) in flat mode.
cat >"$tmp/cancel.txt" <<EOF
long-work cancel
param rays every_pixel
param area_a 4096
wait 2
save-preset $tmp/after_cancel.json
quit
EOF
start=$(date +%s)
timeout 120 "$app" --scene "$src/assets/scenes/default.json" --script "$tmp/cancel.txt" >"$tmp/log" 2>&1 || { bad "long-work cancel run (exit $?)"; cat "$tmp/log"; }
took=$(( $(date +%s) - start ))
if grep -q "long work cancelled at [0-9]*% after [0-9.]* s: the last frame stays" "$tmp/log" \
  && [ "$(json "$tmp/after_cancel.json" 'd["area_a"]')" = "4096" ] && [ "$took" -lt 60 ]; then ok
else bad "long work cancelled (took ${took}s)"; cat "$tmp/log"; fi
python3 -c "import json,sys; d=json.load(open(sys.argv[1])); d['lights']=[{'x':1400,'y':900,'color':'ffffff','intensity':1.0}]; d['preset'].update(mode='flat', rays='every_pixel'); json.dump(d, open(sys.argv[2], 'w'))" \
  "$src/assets/scenes/default.json" "$tmp/one_light.json"
cat >"$tmp/long.txt" <<EOF
long-work trace
view -400 -900 0.25
param area_a 1300
param area_b 1300
wait 2
save-preset $tmp/after_long.json
quit
EOF
timeout 300 "$app" --scene "$tmp/one_light.json" --script "$tmp/long.txt" >"$tmp/log" 2>&1 || { bad "long-work trace run (exit $?)"; cat "$tmp/log"; }
if grep -q "^isolux: long work done: 1 lights traced in " "$tmp/log" && ! grep -q "undone\|cancelled" "$tmp/log" \
  && [ "$(json "$tmp/after_long.json" 'd["area_b"]')" = "1300" ]; then ok
else bad "long work traced"; cat "$tmp/log"; fi

# A scene camera too large to render (65536 x 65536): refused by name, at once.
python3 -c "import json,sys; d=json.load(open(sys.argv[1])); d['camera'].update(width=65536, height=65536); json.dump(d, open(sys.argv[2], 'w'))" \
  "$src/assets/scenes/default.json" "$tmp/bigcam.json"
refused_screenshot bigcam "$tmp/bigcam.json" "bigcam.json: camera: shows 65536x65536 pixels"
env -u DISPLAY timeout 60 "$app" --scene "$tmp/bigcam.json" --screenshot "$tmp/bigcam.png" >"$tmp/log" 2>&1; code=$?
if [ "$code" -eq 2 ] && grep -q "bigcam.json: camera: the view is 65536x65536 pixels" "$tmp/log" && [ ! -e "$tmp/bigcam.png" ]; then ok
else bad "huge camera without a display: exit $code"; cat "$tmp/log"; fi

# An endless world: the editor's screenshot of its camera is isolux-cli's
# render of it; a script walks it (a light placed, the view panned 9,600
# pixels over new windows), saves it in the world's own pixels, and the
# saved level reopens to isolux-cli's pixels there. Without a display, the
# headless renderer draws its camera.
cat >"$tmp/endless.json" <<EOF
{"schema_version": 2, "width": "endless", "height": "endless", "seed": "walker",
 "camera": {"x": 3000, "y": -2000, "width": 640, "height": 360}, "lights": [{"x": 3300.5, "y": -1800.5}]}
EOF
timeout 120 "$app" --scene "$tmp/endless.json" --frames 3 --screenshot "$tmp/endless_app.png" >"$tmp/log" 2>&1 || { bad "endless screenshot"; cat "$tmp/log"; }
"$cli" render --scene "$tmp/endless.json" --out "$tmp/endless_cli.png" >/dev/null
if idiff -fail 0.0079 -warn 0.0079 "$tmp/endless_app.png" "$tmp/endless_cli.png" >"$tmp/idiff" 2>&1; then ok; else bad "endless screenshot differs from isolux-cli"; cat "$tmp/idiff"; fi
cat >"$tmp/walk.script" <<SCRIPT
wait 2
click 800 450
wait 2
pan 64 32 150
wait 2
save-scene $tmp/walked.json
export-tiled $tmp/walked.tmx
quit
SCRIPT
timeout 300 "$app" --size endless --script "$tmp/walk.script" >"$tmp/log" 2>&1 || { bad "endless walk run"; cat "$tmp/log"; }
if [ "$(json "$tmp/walked.json" "d['width'], d['height'], d['camera']['x'], d['camera']['y'], [(l['x'], l['y']) for l in d['lights']]")" = "('endless', 'endless', 9600.0, 4800.0, [(800.5, 450.5)])" ]; then ok
else bad "endless walk saved"; cat "$tmp/walked.json"; fi
# Its Tiled export (the chunks around the view) reads back as a map.
if "$cli" render --map "$tmp/walked.tmx" --view 0,0,64,64 --out "$tmp/walked_tmx.png" >"$tmp/log" 2>&1; then ok
else bad "the endless world's Tiled export"; cat "$tmp/log"; fi
timeout 120 "$app" --scene "$tmp/walked.json" --frames 3 --screenshot "$tmp/walked_app.png" >"$tmp/log" 2>&1 || { bad "walked screenshot"; cat "$tmp/log"; }
"$cli" render --scene "$tmp/walked.json" --out "$tmp/walked_cli.png" >/dev/null
if idiff -fail 0.0079 -warn 0.0079 "$tmp/walked_app.png" "$tmp/walked_cli.png" >"$tmp/idiff" 2>&1; then ok; else bad "reopened endless level differs from isolux-cli"; cat "$tmp/idiff"; fi
# The Map panel's "endless" box turns the default map endless, its lights kept.
cat >"$tmp/toggle.script" <<SCRIPT
wait 2
click 27 170
wait 3
save-scene $tmp/toggled.json
quit
SCRIPT
timeout 120 "$app" --scene "$src/assets/scenes/default.json" --script "$tmp/toggle.script" >"$tmp/log" 2>&1 || { bad "endless toggle run"; cat "$tmp/log"; }
if [ "$(json "$tmp/toggled.json" "d['width'], d['height'], len(d['lights'])")" = "('endless', 'endless', 2)" ]; then ok
else bad "the Map panel's endless box"; cat "$tmp/toggled.json"; fi
if env -u DISPLAY timeout 60 "$app" --scene "$tmp/endless.json" --headless-out "$tmp/endless_headless.png" >"$tmp/log" 2>&1 &&
   cmp -s "$tmp/endless_headless.png" "$tmp/endless_cli.png"; then ok
else bad "endless scene without a display"; cat "$tmp/log"; fi

# 2. Scripted input: place a light, move a slider, undo it, save.
cat >"$tmp/edit.script" <<SCRIPT
wait 2
click 800 450
wait 2
param ambient_clarity 0.7
wait 1
key ctrl+z
wait 2
save-preset $tmp/preset.json
save-scene $tmp/scene.json
quit
SCRIPT
if timeout 120 "$app" --scene "$src/assets/scenes/default.json" --script "$tmp/edit.script" --frames 1 >"$tmp/log" 2>&1; then ok; else bad "scripted run"; cat "$tmp/log"; fi
[ -f "$tmp/scene.json" ] && ok || bad "no scene saved"
[ "$(json "$tmp/scene.json" "len(d['lights'])")" = "3" ] && ok || bad "expected 3 lights (2 + the placed one)"
[ "$(json "$tmp/scene.json" "round(d['lights'][2]['x'])")" = "800" ] && ok || bad "the placed light is not under the click"
[ "$(json "$tmp/preset.json" "d['ambient_clarity']")" = "0.3" ] && ok || bad "undo did not revert the slider"
[ "$(json "$tmp/preset.json" "d['schema_version']")" = "1" ] && ok || bad "preset lacks schema_version"

# 2b. The script's param command takes every row of the parameter table,
# choices and booleans included, by field name (as presets spell them).
cat >"$tmp/params.script" <<SCRIPT
wait 2
param mode shadow
param rays every_pixel
param dark_unlit true
param blur_radius 4
param area_a 300
wait 2
save-preset $tmp/params.json
quit
SCRIPT
timeout 120 "$app" --scene "$src/assets/scenes/default.json" --script "$tmp/params.script" >"$tmp/log" 2>&1 || { bad "params run"; cat "$tmp/log"; }
[ "$(json "$tmp/params.json" "d['mode'], d['rays'], d['dark_unlit'], d['blur_radius'], d['area_a']")" = "('shadow', 'every_pixel', True, 4, 300)" ] && ok || bad "the param command ignored a parameter: $(cat "$tmp/params.json")"

# 2c. The Map panel edits the document: Enter in the seed field regenerates;
# after an undo the panel shows the undone size and Regenerate builds that
# size (it used to keep its own copy and rebuild the undone map). The window is
# 1600x900 and panels sit at their first-use places (no imgui.ini in scripts).
cat >"$tmp/map.script" <<SCRIPT
wait 3
click 121 66
wait 1
key ctrl+a
wait 1
type moss-7
wait 1
key enter
wait 3
save-scene $tmp/m_seeded.json
click 66 89
wait 1
key ctrl+a
wait 1
type 32
wait 1
key enter
wait 3
save-scene $tmp/m_sized.json
key ctrl+z
wait 3
save-scene $tmp/m_undone.json
click 57 135
wait 3
save-scene $tmp/m_regenerated.json
window-shot $tmp/m_window.png
quit
SCRIPT
timeout 120 "$app" --scene "$src/assets/scenes/default.json" --script "$tmp/map.script" >"$tmp/log" 2>&1 || { bad "map panel run"; cat "$tmp/log"; }
[ "$(json "$tmp/m_seeded.json" "d['seed'], d['width']")" = "('moss-7', 12)" ] && ok || bad "Enter in the seed field did not regenerate"
[ "$(json "$tmp/m_sized.json" "d['seed'], d['width'], d['height']")" = "('moss-7', 32, 12)" ] && ok || bad "the size field did not apply"
[ "$(json "$tmp/m_undone.json" "d['width']")" = "12" ] && ok || bad "undo did not restore the size"
[ "$(json "$tmp/m_regenerated.json" "d['seed'], d['width'], d['height']")" = "('moss-7', 12, 12)" ] && ok || bad "Regenerate after undo built another size than the document's"
[ "$(python3 -c "import struct;f=open('$tmp/m_window.png','rb');f.read(16);print(*struct.unpack('>II',f.read(8)))")" = "1600 900" ] && ok || bad "window-shot is not the window's size"

# 2d. The truth overlays: the 3D light texture, 2.5D against 3D, the 2.5D | 3D
# split, each drawn (the window changes) without an error.
cat >"$tmp/truth.script" <<SCRIPT
wait 3
window-shot $tmp/t_plain.png
overlay truth_difference on
wait 3
window-shot $tmp/t_diff.png
overlay truth_difference off
overlay split_view on
overlay split_with_3d on
wait 3
overlay split_view off
overlay truth_light on
wait 3
window-shot $tmp/t_light.png
save-scene $tmp/t_scene.json
quit
SCRIPT
timeout 120 "$app" --scene "$src/assets/scenes/default.json" --script "$tmp/truth.script" >"$tmp/log" 2>&1 || { bad "truth overlays run"; cat "$tmp/log"; }
[ -f "$tmp/t_scene.json" ] && ok || bad "the truth overlays run did not reach its end"
for shot in t_diff t_light; do
  if cmp -s "$tmp/t_plain.png" "$tmp/$shot.png"; then bad "$shot looks like the plain view"; else ok; fi
done

# 2e. The tileset inspector: a footprint set on a sprite is saved into the
# manifest, which keeps its other fields.
cp -r "$src/assets/default" "$tmp/ts"
python3 - "$tmp/ts/tileset.json" <<'PY'
import json, sys
d = json.load(open(sys.argv[1])); d["x_custom"] = "keep me"; d["sprites"][5]["x_note"] = "mine"
json.dump(d, open(sys.argv[1], "w"), indent=2)
PY
printf '{"schema_version": 1, "width": 6, "height": 6, "tileset": "%s", "lights": [{"x": 400, "y": 250}]}' "$tmp/ts/tileset.json" >"$tmp/ts_scene.json"
cat >"$tmp/inspect.script" <<SCRIPT
wait 3
inspect oak
wait 2
footprint oak {"run":[50,100,20],"object":{"foot":[64,108],"height":30}}
wait 3
window-shot $tmp/i_shot.png
overlay inspector_normals on
wait 3
window-shot $tmp/i_normals.png
overlay inspector_normals off
wait 1
inspect rock
wait 2
footprint rock {"object":{"model":"prism"}}
wait 3
window-shot $tmp/i_prism.png
save-footprints
quit
SCRIPT
timeout 120 "$app" --scene "$tmp/ts_scene.json" --script "$tmp/inspect.script" >"$tmp/log" 2>&1 || { bad "inspector run"; cat "$tmp/log"; }
[ "$(json "$tmp/ts/tileset.json" "d['x_custom'], d['sprites'][5]['x_note'], d['sprites'][5]['footprint']")" = "('keep me', 'mine', {'mode': 'run', 'object': {'foot': [64, 108], 'height': 30}, 'run': [50, 100, 20]})" ] && ok || bad "the inspector's footprint was not saved into the manifest with its other fields: $(head -c 300 "$tmp/ts/tileset.json")"
# The corrected solid, as check-tileset reads it from the saved manifest: its axis on that pixel, 30 px high.
"$cli" check-tileset "$tmp/ts/tileset.json" --json >"$tmp/ts_check.json" 2>/dev/null
[ "$(json "$tmp/ts_check.json" "[(o['center'], o['height']) for s in d['sprites'] if s['name'] == 'oak' for o in s['objects']]")" = "[([64.5, 108.5], 30.0)]" ] && ok || bad "check-tileset does not show the corrected solid: $(head -c 300 "$tmp/ts_check.json")"
# The inspector draws the oak's estimated solid as a yellow outline (255, 220, 0): dozens of pixels.
yellow=$(oiiotool "$tmp/i_shot.png" --colorcount "1,0.8627,0,1" 2>/dev/null | awk '{print $1}')
[ "${yellow:-0}" -gt 50 ] && ok || bad "the inspector shows no estimated solid (yellow pixels: ${yellow:-none})"
# With "normal map" the inspector draws the oak's normal map (as isolux-cli normals writes it, with the
# corrected solid's foot and height): hundreds of the window's pixels take its colours, few before.
"$cli" normals --tileset "$tmp/ts/tileset.json" --out "$tmp/ts_normals" >/dev/null 2>&1
python3 - "$tmp/ts_normals/oak.normal.png" "$tmp/i_normals.png" "$tmp/i_shot.png" >"$tmp/check" 2>&1 <<'PY' && ok || { bad "the inspector's normal map"; cat "$tmp/check"; }
import subprocess, sys
def colours(path):  # the picture's pixels, each its 3 bytes (binary PPM: "P6 W H 255" then the bytes)
    subprocess.run(["oiiotool", path, "--ch", "R,G,B", "-d", "uint8", "-o", path + ".ppm"], check=True)
    data = open(path + ".ppm", "rb").read()
    fields, at = [], 0
    while len(fields) < 4:
        while data[at:at + 1].isspace():
            at += 1
        start = at
        while not data[at:at + 1].isspace():
            at += 1
        fields.append(data[start:at])
    w, h = int(fields[1]), int(fields[2])
    px = data[at + 1:at + 1 + w * h * 3]
    return [px[i:i + 3] for i in range(0, len(px), 3)]
oak = {c for c in colours(sys.argv[1]) if c != b"\x80\x80\xff"}
now = sum(1 for c in colours(sys.argv[2]) if c in oak)
before = sum(1 for c in colours(sys.argv[3]) if c in oak)
print("pixels in the oak normal map's colours:", now, "with it on,", before, "before")
assert now > 2000 and now > 5 * before, (now, before)
PY
# The rock's model, picked as a prism: saved in its footprint's object, read back by check-tileset, and
# outlined in the prism's magenta (255, 80, 255) where the oak's revolution showed none of it.
[ "$(json "$tmp/ts/tileset.json" "[s['footprint'] for s in d['sprites'] if s['name'] == 'rock']")" = "[{'object': {'model': 'prism'}}]" ] && ok || bad "the picked model was not saved: $(head -c 300 "$tmp/ts/tileset.json")"
[ "$(json "$tmp/ts_check.json" "[o['model'] for s in d['sprites'] if s['name'] == 'rock' for o in s['objects']]")" = "['prism']" ] && ok || bad "check-tileset does not read the picked model: $(head -c 300 "$tmp/ts_check.json")"
magenta=$(oiiotool "$tmp/i_prism.png" --colorcount "1,0.3137,1,1" 2>/dev/null | awk '{print $1}')
magenta_before=$(oiiotool "$tmp/i_shot.png" --colorcount "1,0.3137,1,1" 2>/dev/null | awk '{print $1}')
[ "${magenta:-0}" -gt 30 ] && [ "${magenta:-0}" -gt "$((${magenta_before:-0} + 30))" ] && ok || bad "the inspector does not outline the picked prism (magenta pixels: ${magenta:-none}, before: ${magenta_before:-none})"

# 2f. A script with a bad number is refused with its line, not a crash.
printf 'wait 1\nclick abc 10\n' >"$tmp/badnum.script"
timeout 60 "$app" --script "$tmp/badnum.script" >"$tmp/log" 2>&1
code=$?
[ "$code" = "2" ] && grep -q "badnum.script:2" "$tmp/log" && ok || { bad "a bad script number: exit $code"; cat "$tmp/log"; }

# 3. A drag moves a light (one undo step), right-click removes one, Delete the selected.
cat >"$tmp/drag.script" <<SCRIPT
wait 2
drag 700 420 760 470
wait 3
save-scene $tmp/dragged.scene.json
rclick 760 470
wait 2
save-scene $tmp/removed.scene.json
key ctrl+z
wait 2
save-scene $tmp/restored.scene.json
quit
SCRIPT
timeout 120 "$app" --scene "$src/assets/scenes/default.json" --script "$tmp/drag.script" >"$tmp/log" 2>&1 || { bad "drag run"; cat "$tmp/log"; }
[ "$(json "$tmp/dragged.scene.json" "round(d['lights'][0]['x']), round(d['lights'][0]['y'])")" = "(760, 470)" ] && ok || bad "drag did not move light 1"
[ "$(json "$tmp/removed.scene.json" "len(d['lights'])")" = "1" ] && ok || bad "right-click did not remove the light"
[ "$(json "$tmp/restored.scene.json" "len(d['lights'])")" = "2" ] && ok || bad "undo did not restore the removed light"

# 4. Bad input never crashes nor loses the document; unsaved work is autosaved.
printf '{"seed": "x", "lights": [' >"$tmp/corrupt.json"
cat >"$tmp/bad.script" <<SCRIPT
wait 1
click 820 470
wait 1
load-scene $tmp/corrupt.json
load-preset $tmp/corrupt.json
wait 1
save-scene $tmp/after_bad.json
click 830 480
wait 3
quit
SCRIPT
rm -rf "$ISOLUX_CONFIG_DIR"
if timeout 120 "$app" --scene "$src/assets/scenes/default.json" --script "$tmp/bad.script" >"$tmp/log" 2>&1; then ok; else bad "bad-input run crashed"; cat "$tmp/log"; fi
[ "$(json "$tmp/after_bad.json" "len(d['lights'])")" = "3" ] && ok || bad "a corrupt file replaced the document"
# The window's own autosave (autosave-PID.json: each window has its own).
autosave=$(ls "$ISOLUX_CONFIG_DIR"/autosave-*.json 2>/dev/null | head -1)
[ -n "$autosave" ] && [ "$(ls "$ISOLUX_CONFIG_DIR"/autosave*.json | wc -l)" = "1" ] && ok || bad "unsaved work was not autosaved (in one file)"
[ "$(json "$autosave" "len(d['lights'])")" = "4" ] && ok || bad "the autosave lacks the last light"

# 4b. A closed window's autosave survives later clean runs that never
# offered it (a screenshot run, a script's quit), which keep their own apart.
cp "$autosave" "$tmp/autosave.before"
timeout 120 "$app" --scene "$src/assets/scenes/default.json" --frames 1 --screenshot "$tmp/again.png" >"$tmp/log" 2>&1 || { bad "screenshot run"; cat "$tmp/log"; }
printf 'wait 2\nquit\n' >"$tmp/quit.script"
timeout 120 "$app" --scene "$src/assets/scenes/default.json" --script "$tmp/quit.script" >"$tmp/log" 2>&1 || { bad "quit run"; cat "$tmp/log"; }
cmp -s "$autosave" "$tmp/autosave.before" && ok || bad "a clean run deleted or replaced an unrecovered autosave"

# 4c. move-lights moves every light each frame (each frame retraces them
#     all), and save-stats writes the Stats panel's mean stage times.
cat >"$tmp/move.script" <<SCRIPT
wait 2
move-lights 5
save-stats $tmp/stats.json
save-scene $tmp/moved.json
quit
SCRIPT
timeout 120 "$app" --scene "$src/assets/scenes/default.json" --script "$tmp/move.script" --tracer cpu >"$tmp/log" 2>&1 || { bad "move-lights run"; cat "$tmp/log"; }
[ "$(json "$tmp/moved.json" "int(d['lights'][0]['x'])")" = "701" ] && ok || bad "move-lights: light 1 is not 1 px right after 5 frames (+1 -1 +1 -1 +1)"
[ "$(json "$tmp/stats.json" "d['lights_traced'] == 2 and d['tracer'] == 'cpu' and d['cpu_ms']['trace'] > 0 and d['frames'] >= 7 and d['loop_ms'] > 0 and abs(d['fps'] * d['loop_ms'] - 1000) < 1")" = "True" ] \
  && ok || { bad "save-stats: not the moving frames' figures"; cat "$tmp/stats.json"; }

# 5. Every overlay, the error heat map, and the Accuracy panel's sweep: a
#    point applied from it becomes the preset.
cat >"$tmp/accuracy.script" <<SCRIPT
wait 2
overlay obstacles on
overlay opacity_maps on
overlay delta_y_bands on
overlay split_view on
wait 2
overlay raw_light on
wait 2
overlay heatmap on
wait 2
sweep ray_skip=1,8 blur_radius=0
wait-sweep
save-sweep $tmp/sweep.csv
apply-point 1
wait 1
save-preset $tmp/applied.json
quit
SCRIPT
if timeout 300 "$app" --scene "$src/assets/scenes/default.json" --script "$tmp/accuracy.script" >"$tmp/log" 2>&1; then ok; else bad "overlay and accuracy run"; cat "$tmp/log"; fi
[ "$(wc -l <"$tmp/sweep.csv" 2>/dev/null)" = "3" ] && ok || bad "the panel's sweep did not write two rows"
[ "$(json "$tmp/applied.json" "d['ray_skip'], d['blur_radius']")" = "(8, 0)" ] && ok || bad "applying a sweep point did not set its parameters"

# 5b. The Accuracy panel's Occluder resolution button: on the default scene
#     (footprints) it sweeps occluder_scale 1, 2, 4 with solids and shapes
#     against 3d; a point applied sets both.
cat >"$tmp/resolution.script" <<SCRIPT
wait 2
sweep-resolution
wait-sweep
save-sweep $tmp/resolution.csv
apply-point 4
wait 1
save-preset $tmp/resolution.json
quit
SCRIPT
if timeout 300 "$app" --scene "$src/assets/scenes/default.json" --script "$tmp/resolution.script" >"$tmp/log" 2>&1; then ok; else bad "occluder resolution sweep run"; cat "$tmp/log"; fi
[ "$(wc -l <"$tmp/resolution.csv" 2>/dev/null)" = "7" ] && ok || bad "the occluder resolution sweep did not write six rows"
[ "$(json "$tmp/resolution.json" "d['occluder_scale'] > 1, d['occluders'] in ('solids', 'shapes')")" = "(True, True)" ] && ok || bad "applying an occluder resolution point did not set occluder_scale and occluders"

# 7. Terrain editing: a lake (rectangle), a clearing (eraser), a wall of
#    trees (place), one undo and redo; saved, reopened and saved again the same;
#    rendered by the app and by isolux-cli within 2/255.
cat >"$tmp/terrain.script" <<SCRIPT
wait 2
fit
wait 2
tool rectangle
brush floor water
drag-tiles 1 1 4 3
wait 2
tool eraser
drag-tiles 6 6 7 7
wait 2
tool eraser
drag-tiles 0 9 3 9
wait 2
tool place
brush overlay pine
drag-tiles 0 9 3 9
wait 2
key ctrl+z
wait 2
save-scene $tmp/undone.json
key ctrl+y
wait 2
tool fill
brush floor sand
click-tile 2 2
wait 2
save-scene $tmp/level.json
quit
SCRIPT
if timeout 120 "$app" --scene "$src/assets/scenes/default.json" --script "$tmp/terrain.script" >"$tmp/log" 2>&1; then ok; else bad "terrain run"; cat "$tmp/log"; fi
cat >"$tmp/terrain_check.py" <<'PY'
import json, sys
level = json.load(open(sys.argv[1])); undone = json.load(open(sys.argv[2]))
assert level["schema_version"] == 2, level["schema_version"]
edits = {tuple(e["tile"]): e for e in level["edits"]}
# The lake, then the bucket: every tile of the rectangle holds sand now (it was all water, connected).
for c in range(1, 5):
    for r in range(1, 4):
        assert edits.get((c, r), {}).get("floor") == "sand", ((c, r), edits.get((c, r)))
# The clearing: no overlays on its corners.
for t in [(6, 6), (7, 7)]:
    assert t not in edits or edits[t].get("overlays", [None]) == [] or "overlays" not in edits[t], (t, edits.get(t))
# The wall of trees: each tile of row 9 from 0 to 3 ends with a pine.
for c in range(0, 4):
    e = edits.get((c, 9))
    assert e and e["overlays"][-1] == "pine", ((c, 9), e)
# Undo removed the wall.
u = {tuple(e["tile"]): e for e in undone["edits"]}
assert all(u.get((c, 9), {}).get("overlays", [""])[-1:] != ["pine"] or (c, 9) not in u for c in range(4)), u
print("ok")
PY
python3 "$tmp/terrain_check.py" "$tmp/level.json" "$tmp/undone.json" >"$tmp/check" 2>&1 && ok || { bad "terrain edits"; cat "$tmp/check"; }
printf 'wait 2\nsave-scene %s\nquit\n' "$tmp/level2.json" >"$tmp/reopen.script"
timeout 120 "$app" --scene "$tmp/level.json" --script "$tmp/reopen.script" >"$tmp/log" 2>&1 || { bad "reopen run"; cat "$tmp/log"; }
[ "$(json "$tmp/level2.json" "d['edits']")" = "$(json "$tmp/level.json" "d['edits']")" ] && ok || bad "reopening changed the edits"
timeout 120 "$app" --scene "$tmp/level.json" --frames 3 --screenshot "$tmp/level_app.png" >"$tmp/log" 2>&1 || { bad "level screenshot"; cat "$tmp/log"; }
"$cli" render --scene "$tmp/level.json" --out "$tmp/level_cli.png" >/dev/null 2>&1 || bad "isolux-cli could not render the edited scene"
if idiff -fail 0.0079 -warn 0.0079 "$tmp/level_app.png" "$tmp/level_cli.png" >"$tmp/idiff" 2>&1; then ok; else bad "edited scene: app and isolux-cli differ"; cat "$tmp/idiff"; fi
cmp -s "$tmp/level_cli.png" "$tmp/cli.png" && bad "the edits did not change isolux-cli's render" || ok

# 8. The editor's comforts: every panel inside 1280x720 and 1366x768 (floating
#    ones opened), the label font's symbols, an export of the window's exact
#    size, a dropped scene opened, New held by the unsaved-changes prompt.
for size in 1280x720 1366x768 1600x900; do
  w=${size%x*}; h=${size#*x}
  cat >"$tmp/panels.script" <<SCRIPT
wait 2
show stats
show help
wait 2
dump-panels $tmp/panels_$size.json
save-controls $tmp/controls_$size.json
show accuracy
inspect oak
wait 2
dump-panels $tmp/floating_$size.json
check-glyphs Δ×²
quit
SCRIPT
  if timeout 120 "$app" --width "$w" --height "$h" --script "$tmp/panels.script" >"$tmp/log" 2>&1; then ok; else bad "panels run $size (exit $?)"; cat "$tmp/log"; fi
  python3 - "$tmp/panels_$size.json" "$tmp/floating_$size.json" >"$tmp/check" 2>&1 <<'PY' && ok || { bad "a panel outside the $size window"; cat "$tmp/check"; }
import json, sys
names = set()
for f in sys.argv[1:]:
    rows = [json.loads(l) for l in open(f)]
    W, H = rows[-1]["window"]
    for p in rows[:-1]:
        names.add(p["name"])
        assert p["x"] >= 0 and p["y"] >= 0 and p["x"] + p["w"] <= W and p["y"] + p["h"] <= H, (f, p, W, H)
for n in ["Map", "Parameters", "Overlays", "Tools", "Lights", "Stats", "Help", "Accuracy", "Tileset inspector"]:
    assert n in names, (n, names)
PY
  # Every Parameters control within one scroll (the panel's content at most
  # two of its heights), inside the panel's width, and the look's controls
  # (occluders, ambient clarity, exposure, tone map) in view unscrolled.
  python3 - "$tmp/controls_$size.json" "$("$cli" params | tail -n +2 | wc -l)" >"$tmp/check" 2>&1 <<'PY' && ok || { bad "a Parameters control out of reach at $size"; cat "$tmp/check"; }
import json, sys
d = json.load(open(sys.argv[1]))
x, y, w, h = d["panels"]["Parameters"]["rect"]
scroll, scroll_max = d["panels"]["Parameters"]["scroll_y"], d["panels"]["Parameters"]["scroll_max_y"]
ctrls = [c for c in d["controls"] if c["panel"] == "Parameters"]
assert len(ctrls) == int(sys.argv[2]), (len(ctrls), sys.argv[2])
assert scroll == 0, scroll
assert scroll_max <= h - 20, ("more than one scroll", scroll_max, h)
for c in ctrls:
    cx, cy, cw, ch = c["rect"]
    assert cx >= x and cx + cw <= x + w + 0.5, ("wider than the panel", c, d["panels"]["Parameters"])
    if c["name"] in ("occluders", "ambient_clarity", "exposure", "tone_map"):
        assert cy + ch <= y + h, ("not in view unscrolled", c, d["panels"]["Parameters"])
print("controls", len(ctrls), "panel", w, h, "scroll_max", scroll_max)
PY
done
cat >"$tmp/comfort.script" <<SCRIPT
wait 2
export-final $tmp/exact.png
open-dropped $tmp/level.json
wait 2
save-scene $tmp/dropped.json
click 800 450
wait 2
key ctrl+n
wait 2
dump-panels $tmp/prompt.json
key escape
wait 2
save-scene $tmp/after_new.json
quit
SCRIPT
if timeout 120 "$app" --scene "$src/assets/scenes/default.json" --script "$tmp/comfort.script" >"$tmp/log" 2>&1; then ok; else bad "comfort run"; cat "$tmp/log"; fi
[ "$(python3 -c "import struct,sys; d=open(sys.argv[1],'rb').read(24); print(struct.unpack('>II', d[16:24]))" "$tmp/exact.png")" = "(1600, 900)" ] && ok || bad "the exported frame is not the window's 1600x900"
[ "$(json "$tmp/dropped.json" "len(d.get('edits', []))")" = "$(json "$tmp/level.json" "len(d['edits'])")" ] && ok || bad "the dropped scene was not opened"
grep -q '"Unsaved changes"' "$tmp/prompt.json" && ok || bad "New did not ask about unsaved changes"
[ "$(json "$tmp/after_new.json" "len(d['lights'])")" = "$(( $(json "$tmp/level.json" "len(d['lights'])") + 1 ))" ] && ok || bad "Cancel on the prompt lost the document"

# 9. Tiled: File > Export > Tiled map, then the map opened as a scene that
#    lights it (saved as JSON naming the map), rendered as isolux-cli does.
cat >"$tmp/tiled.script" <<SCRIPT
wait 2
export-tiled $tmp/tiled/level.tmx
wait 1
load-scene $tmp/tiled/level.tmx
wait 2
tool floor
brush floor water
click-tile 2 2
wait 2
save-scene $tmp/tiled/lighting.json
quit
SCRIPT
mkdir -p "$tmp/tiled"
if timeout 120 "$app" --scene "$tmp/level.json" --script "$tmp/tiled.script" >"$tmp/log" 2>&1; then ok; else bad "tiled run"; cat "$tmp/log"; fi
[ -f "$tmp/tiled/level.tmx" ] && [ -f "$tmp/tiled/level_overlays.tsx" ] && ok || bad "the app did not export the Tiled map"
[ "$(json "$tmp/tiled/lighting.json" "d.get('map')")" = "level.tmx" ] && ok || bad "the opened Tiled map is not the scene's map"
[ "$(json "$tmp/tiled/lighting.json" "len(d.get('edits', []))")" = "0" ] && ok || bad "terrain tools edited a Tiled map's scene"
"$cli" render --scene "$tmp/tiled/lighting.json" --out "$tmp/tiled/via_scene.png" >/dev/null 2>&1 || bad "isolux-cli could not render the scene of a Tiled map"
cmp -s "$tmp/tiled/via_scene.png" "$tmp/level_cli.png" && ok || bad "the Tiled map's scene renders differently from the level it came from"

# 6. No display: a clear message and the headless renderer.
if env -u DISPLAY "$app" --scene "$src/assets/scenes/default.json" --screenshot "$tmp/nodisplay.png" >"$tmp/log" 2>&1 &&
  grep -q "no display" "$tmp/log" && [ -f "$tmp/nodisplay.png" ]; then ok; else bad "no-display fallback"; cat "$tmp/log"; fi
if cmp -s "$tmp/nodisplay.png" "$tmp/cli.png"; then ok; else bad "the no-display render differs from isolux-cli"; fi
# The README's main command with no display (scripts/run.sh: no scene named):
# the showcase scene, as isolux-cli renders it.
"$cli" render --scene "$src/assets/scenes/showcase.json" --out "$tmp/showcase_cli.png" >/dev/null 2>&1 || bad "isolux-cli could not render the showcase"
if env -u DISPLAY "$app" --headless-out "$tmp/first_start.png" >"$tmp/log" 2>&1 && grep -q "no display" "$tmp/log" &&
  cmp -s "$tmp/first_start.png" "$tmp/showcase_cli.png"; then ok; else bad "the first start with no display is not the showcase"; cat "$tmp/log"; fi

# 7. The window fits the screen and remembers its size. On a 1280x720 screen
# the default 1600x900 window opens within the screen; resized to 900x600 and
# closed, it reopens at 900x600; an explicit --width/--height is exact and
# is not remembered.
fit_config="$tmp/fit_config"
cat >"$tmp/fit1.script" <<SCRIPT
wait 2
window-shot $tmp/fit_first.png
resize 900 600
wait 3
quit
SCRIPT
cat >"$tmp/fit2.script" <<SCRIPT
wait 3
window-shot $tmp/fit_second.png
quit
SCRIPT
png_size() { python3 -c "import struct,sys; d=open(sys.argv[1],'rb').read(24); print(*struct.unpack('>II', d[16:24]))" "$1"; }
ISOLUX_CONFIG_DIR="$fit_config" timeout 120 xvfb-run -a -s "-screen 0 1280x720x24" "$app_bin" --scene "$src/assets/scenes/default.json" --script "$tmp/fit1.script" >"$tmp/log" 2>&1 || { bad "fit run"; cat "$tmp/log"; }
read -r fw fh <<<"$(png_size "$tmp/fit_first.png" 2>/dev/null || echo "0 0")"
[ "$fw" -gt 0 ] && [ "$fw" -le 1280 ] && [ "$fh" -gt 0 ] && [ "$fh" -le 720 ] && ok || bad "the default window ($fw x $fh) does not fit a 1280x720 screen"
[ "$(json "$fit_config/settings.json" "d['window_width'], d['window_height']")" = "(900, 600)" ] && ok || bad "the window's last size was not remembered: $(cat "$fit_config/settings.json")"
ISOLUX_CONFIG_DIR="$fit_config" timeout 120 xvfb-run -a -s "-screen 0 1280x720x24" "$app_bin" --scene "$src/assets/scenes/default.json" --script "$tmp/fit2.script" >"$tmp/log" 2>&1 || { bad "reopen-size run"; cat "$tmp/log"; }
[ "$(png_size "$tmp/fit_second.png" 2>/dev/null)" = "900 600" ] && ok || bad "the window did not reopen at its last size: $(png_size "$tmp/fit_second.png" 2>/dev/null)"
ISOLUX_CONFIG_DIR="$fit_config" timeout 120 "$app_bin" --width 700 --height 500 --scene "$src/assets/scenes/default.json" --script "$tmp/fit2.script" >"$tmp/log" 2>&1 || { bad "explicit-size run"; cat "$tmp/log"; }
[ "$(png_size "$tmp/fit_second.png" 2>/dev/null)" = "700 500" ] && ok || bad "an explicit size is not exact"
[ "$(json "$fit_config/settings.json" "d['window_width'], d['window_height']")" = "(900, 600)" ] && ok || bad "an explicit size was remembered"

echo "app: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
