#!/usr/bin/env bash
# Sets up, builds and starts isolux on the default seed and assets: the
# README's main command. With no display the app says so and renders the
# scene with the headless renderer to out/isolux.png instead.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/deps.sh
bash scripts/build.sh
mkdir -p out
exec ./build/release/app/isolux --headless-out out/isolux.png "$@"
