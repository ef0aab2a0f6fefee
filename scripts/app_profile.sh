#!/bin/bash
# Where the app's frame spends its CPU time with 32 moving lights, by perf,
# against what its own frame report (the Stats panel) says.
#
#   bash scripts/app_profile.sh [build dir] [output dir]
#
# Runs the app under Xvfb (1920x1080) on the default map with 32 white lights
# of a = b = 128 and blur 2, the CPU tracer, every light moving a pixel each
# frame for 240 frames (script command move-lights), then save-stats. perf
# samples the app's own threads (not Mesa's llvmpipe threads, which stand in
# for the GPU); each sampled function is given to the stage that calls it by
# the table in scripts/app_profile.py. Needs perf (linux-perf) and xvfb-run.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$here/build/release}
out=${2:-$(mktemp -d)}
mkdir -p "$out"
app=$build/app/isolux
[ -x "$app" ] || { echo "app_profile: $app not built (cmake --build $build)" >&2; exit 2; }
command -v perf > /dev/null || { echo "app_profile: perf not found (apt-get install linux-perf)" >&2; exit 2; }

python3 "$here/scripts/app_profile.py" scene "$out/scene.json"
cat > "$out/script.txt" << EOF
wait 10
move-lights 240
save-stats $out/stats.json
quit
EOF
xvfb-run -a -s "-screen 0 1920x1080x24" perf record -q -F 499 -o "$out/perf.data" -- \
  "$app" --scene "$out/scene.json" --script "$out/script.txt" --tracer cpu --width 1920 --height 1080 > "$out/app.log" 2>&1
perf report -i "$out/perf.data" --stdio --no-children --comm isolux --sort sym --percent-limit 0.05 2> /dev/null \
  > "$out/perf.txt"
python3 "$here/scripts/app_profile.py" compare "$out/stats.json" "$out/perf.txt"
