#!/usr/bin/env bash
# Saves and exports into a full file system and a read-only one: a clear
# message naming the file and the reason, exit code 2, and the old file
# byte for byte as it was. The file systems are small tmpfs mounts inside a
# user and mount namespace of this test's own (`unshare -rm`), so the test
# needs no root and leaves nothing mounted. Usage: full_disk.sh PATH/TO/isolux-cli SOURCE_DIR
set -u
cli=$1
src=$2
if ! unshare -rm true 2>/dev/null; then
  echo "FAIL full_disk: 'unshare -rm' is not allowed here (user namespaces are off); this test needs them"
  exit 1
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir "$work/fs"
export cli src work
unshare -rm bash -c '
set -u
fail=0; pass=0
ok() { pass=$((pass + 1)); }
bad() { echo "FAIL $*"; fail=$((fail + 1)); }
fs=$work/fs
# expect NAME PATTERN FILE_KEPT -- ARGS...: exit 2, one line with PATTERN, FILE_KEPT unchanged.
expect() {
  local name=$1 pattern=$2 kept=$3
  shift 4
  cp "$kept" "$work/before"
  "$cli" "$@" >"$work/out" 2>"$work/err"
  local got=$?
  if [ "$got" -ne 2 ]; then bad "$name: exit $got, want 2"; cat "$work/err"; return; fi
  if ! grep -q -- "$pattern" "$work/err" || [ "$(wc -l <"$work/err")" -ne 1 ]; then bad "$name: message"; cat "$work/err"; return; fi
  if ! cmp -s "$kept" "$work/before"; then bad "$name: the old file changed"; return; fi
  if ls -A "$fs" | grep -q "\.tmp\|_images"; then bad "$name: a temporary file or a new folder was left"; ls -A "$fs"; return; fi
  ok
}
mount -t tmpfs -o size=256k tmpfs "$fs" || { echo "FAIL cannot mount a tmpfs in the namespace"; exit 1; }
"$cli" render --size 3x3 --out "$fs/shot.png" >/dev/null || bad "first render"
"$cli" preset --out "$fs/preset.json" >/dev/null || bad "first preset"
cp "$src/assets/scenes/default.json" "$fs/scene.json"
# Fill the file system to the last block.
dd if=/dev/zero of="$fs/filler" bs=4k >/dev/null 2>&1
expect full_png "No space left on device\|is the disk full" "$fs/shot.png" -- render --size 6x6 --out "$fs/shot.png"
expect full_exr "No space left on device\|is the disk full\|cannot write" "$fs/shot.png" -- render --size 6x6 --out "$fs/shot.exr"
expect full_preset "No space left on device" "$fs/preset.json" -- preset --preset quality --out "$fs/preset.json"
expect full_tiled "No space left on device\|is the disk full" "$fs/scene.json" -- export-tiled --scene "$fs/scene.json" --out "$fs/level.tmx"
# Read-only: nothing can be created, root or not.
rm -f "$fs/filler"
mount -o remount,ro "$fs" || { echo "FAIL cannot remount read-only"; exit 1; }
expect ro_png "Read-only file system" "$fs/shot.png" -- render --size 6x6 --out "$fs/shot.png"
expect ro_preset "Read-only file system" "$fs/preset.json" -- preset --preset quality --out "$fs/preset.json"
expect ro_tiled "Read-only file system" "$fs/scene.json" -- export-tiled --scene "$fs/scene.json" --out "$fs/level.tmx"
echo "full_disk: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
'
