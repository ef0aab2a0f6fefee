#!/usr/bin/env bash
# Sets up, builds and runs isolux on the default seed and assets. The README's
# main command. Extra arguments go to the renderer.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/deps.sh
bash scripts/build.sh
mkdir -p out
./build/release/app/isolux-cli render --scene assets/scenes/default.json --out out/isolux.png "$@"
echo "open out/isolux.png to see the map"
