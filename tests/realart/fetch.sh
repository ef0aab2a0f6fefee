#!/usr/bin/env bash
# Fetches isometric art from Debian packages of open games that nobody on
# this project drew, for the real-art tests: freedroidrpg-data (trees with
# their shadows apart), lincity-ng-data (trees on a baked ground diamond),
# widelands-data (trees with baked drop shadows), freeciv-data (mountains,
# hills and walled cities that fill their tile) and flare-game (trees with
# drop shadows, a house spanning several tiles). Their files are GPL-2+ or
# CC-BY-SA-3.0+: they are unpacked into a cache outside the repository, never
# committed; of flare-game (130 MB) only the tilesets' images are kept.
# Usage: fetch.sh [CACHE]   (default: $ISOLUX_REALART_CACHE, else ~/.cache/isolux-realart)
set -euo pipefail
cache=${1:-${ISOLUX_REALART_CACHE:-$HOME/.cache/isolux-realart}}
mkdir -p "$cache"
cd "$cache"
for pkg in freedroidrpg-data lincity-ng-data widelands-data freeciv-data flare-game; do
  if [ -f "$pkg/.unpacked" ]; then continue; fi
  rm -rf "$pkg" "$pkg"_*.deb
  if ! apt-get download "$pkg" >/dev/null 2>download.log; then
    if [ "$(id -u)" -eq 0 ] || ! command -v sudo >/dev/null; then apt-get update -qq >/dev/null 2>&1 || true;
    else sudo apt-get update -qq >/dev/null 2>&1 || true; fi
    if ! apt-get download "$pkg" >/dev/null 2>download.log; then
      echo "realart: could not download $pkg from Debian's archive (apt-get download $pkg):" >&2
      cat download.log >&2
      exit 1
    fi
  fi
  dpkg -x "$pkg"_*.deb "$pkg"
  rm -f "$pkg"_*.deb
  if [ "$pkg" = flare-game ]; then
    keep=usr/share/games/flare/mods/fantasycore/images/tilesets
    mv "$pkg/$keep" tilesets.keep && rm -rf "$pkg" && mkdir -p "$pkg/$(dirname "$keep")" && mv tilesets.keep "$pkg/$keep"
  fi
  touch "$pkg/.unpacked"
done
echo "realart: art unpacked in $cache"
