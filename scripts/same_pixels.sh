#!/bin/bash
# Two builds of isolux-cli render the same cases, and every pair of images
# must hold the same pixels: docs/performance.md's check that a change to the
# fast stages (or any change meant to keep the output) draws what the code
# before it drew.
#
#   bash scripts/same_pixels.sh OLD_CLI NEW_CLI [output dir]
#
# OLD_CLI: an isolux-cli built at an earlier commit (it finds the default
# tileset in its own source tree, so keep that checkout); NEW_CLI: this
# build's. The cases cover every fast stage: the blur's every path (none, the fused pass at
# radii 1 to 7, the 32-bit sums beyond), white lights' grey texture and
# coloured lights' RGB, the composite's clarities, mixes and dark-unlit, the
# opacity correction, light, shadow and flat modes, ray skips, the l frames,
# occluders solids and shapes (explicit flags, not a preset: light and
# shadow modes, light heights, the default and town tilesets)
# with a moving camera, three layouts and the layers; sprite shading
# (solids, luminance, a half strength, shadow mode); on seeded maps, both
# scenes, the real art of tests/realart (when tests/realart/fetch.sh has
# unpacked it) and Tiled's own example map. NEW_CLI also renders each case
# with --threads 2, which must give the same pixels. idiff
# (openimageio-tools) compares; exit 1 if any pair differs. Each build takes
# the kernels its CPU allows (AVX2 where there is one); the unit tests hold
# both builds of each kernel to the same oracles.
set -euo pipefail
[ $# -ge 2 ] || { echo "usage: same_pixels.sh OLD_CLI NEW_CLI [output dir]" >&2; exit 2; }
old=$1 new=$2
out=${3:-$(mktemp -d)}
mkdir -p "$out"
here=$(cd "$(dirname "$0")/.." && pwd)
for bin in "$old" "$new"; do [ -x "$bin" ] || { echo "same_pixels: $bin is not an executable" >&2; exit 2; }; done
command -v idiff > /dev/null || { echo "same_pixels: idiff not found (apt-get install openimageio-tools)" >&2; exit 2; }

# Falloff scale 8 spreads the light far enough to light sprites and their
# shadows (the paper's scale, 1, has its own case).
lights="--light 700,420 --light 900,520,96,64,ffd49a --light 1100,380,128,128,7fb0ff --light 500,600,64,96 --falloff-scale 8"
white="--light 700,420 --light 900,520 --light 1100,380 --light 520,600 --falloff-scale 8"
cases=(
  "seed-default|--seed isolux $lights"
  "seed-white|--seed isolux $white"
  "paper-falloff|--seed isolux ${lights% --falloff-scale 8}"
  "seed-other|--seed 'a longer seed, 2' --size 20x14 $lights"
  "blur0|$lights --blur 0"
  "blur1|$lights --blur 1"
  "blur3|$lights --blur 3"
  "blur5|$lights --blur 5"
  "blur6|$lights --blur 6"
  "blur7|$lights --blur 7"
  "blur7-white|$white --blur 7"
  "blur9|$lights --blur 9"
  "ambient0|$lights --ambient 0"
  "ambient1|$lights --ambient 1"
  "surface|$lights --light-mix surface --ambient 0.6"
  "dark-unlit|$lights --dark-unlit"
  "no-correction|$lights --no-opacity-correction"
  "shadow|$lights --mode shadow"
  "flat|$lights --mode flat"
  "skip4|$lights --ray-skip 4"
  "round-fade|$lights --falloff-shape euclidean --edge-fade"
  "every-pixel|--light 800,460,40,40 --rays every_pixel"
  "staggered|--layout staggered $lights"
  "paper-layout|--layout paper $lights"
  "frames|$lights --frames 9 --trace-every 4 --camera-step 3,1 --view 300,200,900,600"
  "view-cut|$lights --view 650,330,300,300"
  "layer-light|$lights --layer light"
  "layer-opacity|$lights --layer opacity"
  "layer-obstacles|$lights --layer obstacles"
  "scene-default|--scene $here/assets/scenes/default.json"
  "scene-forest|--scene $here/assets/scenes/forest.json"
  "scene-forest-blur3|--scene $here/assets/scenes/forest.json --blur 3 --ambient 0.1"
  "solids|$lights --occluders solids"
  "solids-high|$lights --occluders solids --light-height 96 --blur 3 --light-mix surface"
  "solids-shadow|$lights --occluders solids --mode shadow"
  "solids-skip2|$lights --occluders solids --ray-skip 2 --no-opacity-correction"
  "shapes|$lights --occluders shapes"
  "shapes-shadow|$lights --occluders shapes --mode shadow --light-height 16"
  "solids-town|--tileset $here/assets/town/tileset.json --size 10x10 $lights --occluders solids"
  "shapes-town|--tileset $here/assets/town/tileset.json --size 10x10 $lights --occluders shapes"
  "shaded-solids|$lights --occluders solids --sprite-shading solids"
  "shaded-half-shadow|$lights --occluders solids --sprite-shading solids --shading-strength 0.5 --mode shadow"
  "shaded-luminance-town|--tileset $here/assets/town/tileset.json --size 10x10 $lights --sprite-shading luminance"
)
art=${ISOLUX_REALART_CACHE:-$HOME/.cache/isolux-realart}
for name in freedroidrpg lincity-ng widelands; do
  manifest=$(ls "$art"/*/isolux-$name.json 2> /dev/null | head -1 || true)
  [ -n "$manifest" ] && cases+=("art-$name|--tileset $manifest --size 10x10 $lights")
done
tmx=/usr/share/doc/tiled/examples/isometric_grass_and_water.tmx
[ -f "$tmx" ] && cases+=("tiled-example|--map $tmx --light 600,300 --light 900,450,96,96,ffcc88 --light 1400,500 --falloff-scale 8")

differ=0 same=0
for case in "${cases[@]}"; do
  name=${case%%|*} flags=${case#*|}
  eval "\"$old\" render $flags --out \"$out/$name.old.png\"" > /dev/null
  eval "\"$new\" render $flags --out \"$out/$name.new.png\"" > /dev/null
  eval "\"$new\" render $flags --threads 2 --out \"$out/$name.new2.png\"" > /dev/null
  for side in new new2; do
    if idiff -fail 0 -failpercent 0 -warn 0 "$out/$name.old.png" "$out/$name.$side.png" > "$out/$name.$side.idiff" 2>&1; then
      same=$((same + 1))
    else
      differ=$((differ + 1)); echo "differ: $name ($side; $out/$name.$side.idiff)"
    fi
  done
done
echo "same_pixels: ${#cases[@]} cases, $same pairs the same, $differ differ (images in $out)"
[ "$differ" -eq 0 ]
