#!/usr/bin/env bash
# Sets up, builds and runs every test. The README's test command; .ci/run runs it.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/deps.sh
bash scripts/build.sh
# One Xvfb for the whole suite: the GL tests need a display, the rest ignore it.
cd build/release
# As many tests at once as there are cores; the long ones start first (COST).
xvfb-run -a -s "-screen 0 1280x1024x24" ctest --output-on-failure --timeout 600 -j "$(nproc)"
