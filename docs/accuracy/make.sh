#!/usr/bin/env bash
# Re-makes docs/accuracy.md: runs every sweep it reports (CSV and charts into
# docs/accuracy/ and docs/images/), then writes the page from them.
# Usage: bash docs/accuracy/make.sh [PATH/TO/isolux-cli]   (a few minutes on 2 cores)
set -euo pipefail
cd "$(dirname "$0")/../.."
cli=${1:-build/release/app/isolux-cli}
out=docs/accuracy
# A sweep that fails stops the script with its message (it would otherwise leave the page half made).
# Each sweep says what it starts (the CLI refuses one beyond the work budget, with its estimate).
# The town tileset's object kinds, each swept alone (below).
kinds=$(python3 -c 'import json; print(" ".join(s["name"] for s in json.load(open("assets/town/tileset.json"))["sprites"] if s["kind"] == "overlay"))')
sweeps_total=$((23 + $(wc -w <<< "$kinds")))
sweeps_done=0
sweep() {
  local said
  sweeps_done=$((sweeps_done + 1))
  echo "make.sh: sweep $sweeps_done of $sweeps_total: ${*: -1}" >&2
  said=$("$cli" sweep "$@" 2>&1 >/dev/null) || { echo "$said" >&2; return 1; }
}
for scene in default forest; do
  s=assets/scenes/$scene.json
  # The paper's model against every reference, by light height, with and without its opacity correction.
  sweep --scene "$s" --param light_height=4,16,32,64 --reference 3d,3d_facing,exact_line,every_pixel \
    --frames 8 --repeats 1 --out $out/${scene}_truth.csv
  sweep --scene "$s" --param light_height=4,16,32,64 --reference 3d,3d_facing,exact_line,every_pixel \
    --frames 8 --repeats 1 --no-opacity-correction --out $out/${scene}_truth_nocorr.csv
  # Beyond the paper: what stops the rays (footprints, solids estimated from the sprites, the true shapes).
  sweep --scene "$s" --param occluders=footprints,solids,shapes --param light_height=4,16,32,64 --reference 3d \
    --frames 8 --repeats 1 --out $out/${scene}_occluders.csv
  # Beyond the paper: rays over low obstacles.
  sweep --scene "$s" --param rays_over_obstacles=false,true --param light_height=4,16,32,64 --reference 3d \
    --frames 8 --repeats 1 --out $out/${scene}_height_rays.csv
  # Each speed knob alone, against the truth and against the model's own best.
  sweep --scene "$s" --param ray_skip=1,2,4,8 --reference 3d,every_pixel --frames 8 --repeats 3 \
    --out $out/${scene}_ray_skip.csv --chart docs/images/accuracy_${scene}_ray_skip.svg
  sweep --scene "$s" --param trace_every=1,2,4,8 --reference 3d,every_pixel --frames 8 --repeats 3 \
    --out $out/${scene}_trace_every.csv --chart docs/images/accuracy_${scene}_trace_every.svg
  sweep --scene "$s" --param blur_radius=0,1,2,4 --reference 3d,every_pixel --frames 8 --repeats 3 \
    --out $out/${scene}_blur.csv --chart docs/images/accuracy_${scene}_blur.svg
  sweep --scene "$s" --param area_a=64,128,254 --param rays=border,every_pixel --reference 3d,every_pixel --allow-huge \
    --frames 8 --repeats 3 --out $out/${scene}_area.csv --chart docs/images/accuracy_${scene}_area.svg
done
# Beyond the paper: what stops the rays, on the town tileset (walls, houses, rocks, a mountain, a grove).
sweep --scene assets/scenes/town.json --param occluders=footprints,solids,shapes --param light_height=4,16,32,64 \
  --reference 3d --frames 8 --repeats 1 --out $out/town_occluders.csv
# Beyond the paper: the occluders' resolution (occluder_scale), on the three scenes.
for scene in default forest town; do
  sweep --scene assets/scenes/$scene.json --param occluders=solids,shapes --param occluder_scale=1,2,4 \
    --param light_height=4,16,32,64 --reference 3d --allow-huge --frames 8 --repeats 1 \
    --out $out/${scene}_occluder_scale.csv
done
# Each object kind alone on the town scene's map (kind_scene.py), and the models the estimate gives each.
"$cli" check-tileset assets/town/tileset.json --json > $out/town_models.json
scenes=$(mktemp -d)
trap 'rm -rf "$scenes"' EXIT
for kind in $kinds; do
  python3 $out/kind_scene.py "$kind" "$scenes/$kind.json"
  sweep --scene "$scenes/$kind.json" --param occluders=footprints,solids,shapes --param light_height=4,16,32,64 \
    --reference 3d --frames 8 --repeats 1 --out $out/town_kind_$kind.csv
done
# Beyond the paper: sprite shading against the 3D reference with Lambert's term, on the default, forest and
# town scenes, for the occluders it is used with.
for scene in default forest town; do
  sweep --scene assets/scenes/$scene.json --param occluders=footprints,solids,shapes \
    --param sprite_shading=none,solids,shapes,luminance --param light_height=16,32,64 --reference 3d_shaded \
    --allow-huge --frames 8 --repeats 1 --out $out/${scene}_shading.csv
done
# The CPU the times come from, for the page.
lscpu | sed -n 's/^Model name: *//p' | head -1 > $out/machine.txt
# What the truth costs: the 3D reference of the default scene, and a 48-setting sweep against it.
"$(dirname "$cli")/../bench/isolux-bench" --benchmark_filter='^truth/' --benchmark_format=csv 2>/dev/null > $out/bench_truth.csv
python3 $out/report.py > docs/accuracy.md
echo "wrote docs/accuracy.md"
