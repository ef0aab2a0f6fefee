#!/usr/bin/env bash
# Installs the Debian 12 packages isolux builds and tests with. Idempotent:
# installs only what is missing. Needs root (or sudo).
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config clang libclang-rt-14-dev
  libopenimageio-dev openimageio-tools nlohmann-json3-dev libcli11-dev
  libgtest-dev libgmock-dev libbenchmark-dev libtcod-dev
  libimgui-dev libglfw3-dev libgl-dev libegl-dev
  fonts-dejavu-core libpugixml-dev zlib1g-dev libzstd-dev zstd tiled libglm-dev
  godot3-server godot3
  xvfb xauth libgl1-mesa-dri libegl-mesa0 python3
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "deps: all ${#packages[@]} packages already installed"
  exit 0
fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then
  if command -v sudo >/dev/null 2>&1; then SUDO="sudo"; else
    echo "deps: missing packages (${missing[*]}) and not root: run as root or install sudo" >&2
    exit 1
  fi
fi
echo "deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
