#!/usr/bin/env bash
# Configures and builds isolux (Release, Ninja) into build/release.
set -euo pipefail
cd "$(dirname "$0")/.."
cmake --preset release -DISOLUX_WERROR="${ISOLUX_WERROR:-OFF}" >/dev/null
cmake --build --preset release
