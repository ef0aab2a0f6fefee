#!/usr/bin/env bash
# Builds the libFuzzer targets (clang, with ASan and UBSan), replays the kept
# corpus, then fuzzes each parser briefly. A crash leaves its input in
# build/fuzz/crashes/: add it to tests/fuzz/corpus/<target>/ once fixed, so it
# stays a regression test. Usage: scripts/fuzz.sh [SECONDS per target, default 20]
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-20}
bash scripts/deps.sh
cmake --preset fuzz -DISOLUX_WERROR="${ISOLUX_WERROR:-OFF}" >/dev/null
cmake --build --preset fuzz
(cd build/fuzz && ctest --output-on-failure -L fuzz)
rm -rf build/fuzz/crashes
mkdir -p build/fuzz/crashes
# Full stacks on allocation (the system libraries have no frame pointers), so
# the suppressions in tests/lsan.supp can match.
export LSAN_OPTIONS="suppressions=$PWD/tests/lsan.supp:print_suppressions=0"
export ASAN_OPTIONS="fast_unwind_on_malloc=0"
# Undefined behaviour is a crash: libFuzzer keeps its input like any other.
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
# Absolute paths: fuzz_cli works in a folder of its own (it chdirs there).
root=$PWD
targets="preset scene tileset sprite tiled cli capi"
# As many targets at once as there are cores; each one's log read afterwards.
running=0
for t in $targets; do
  work=$root/build/fuzz/corpus_$t
  mkdir -p "$work"
  echo "fuzz: $t for ${seconds}s"
  ./build/fuzz/tests/fuzz/fuzz_$t -max_total_time="$seconds" -max_len=65536 -rss_limit_mb=2048 \
    -artifact_prefix="$root/build/fuzz/crashes/$t-" -print_final_stats=1 "$work" "$root/tests/fuzz/corpus/$t" >build/fuzz/log_$t 2>&1 &
  running=$((running + 1))
  if [ "$running" -ge "$(nproc)" ]; then
    wait -n || true
    running=$((running - 1))
  fi
done
wait || true
for t in $targets; do
  echo "fuzz: $t"
  grep -E "number_of_executed_units|new_units_added|ERROR|SUMMARY|runtime error" build/fuzz/log_$t || true
  # The core library must be instrumented too: its parsers' branches show as
  # hundreds of edges (the fuzz targets alone give a few dozen).
  edges=$(grep -oE "DONE +cov: [0-9]+" build/fuzz/log_$t | grep -oE "[0-9]+$" || echo 0)
  echo "fuzz: $t reached $edges edges"
  if [ "${edges:-0}" -lt 250 ]; then
    echo "fuzz: $t reached only ${edges:-0} edges: is the core library instrumented (the fuzz preset's -fsanitize=fuzzer-no-link)?"
    exit 1
  fi
done
# The pipes above keep going on a crash; the artifacts say whether one happened.
if compgen -G "build/fuzz/crashes/*" >/dev/null; then
  echo "fuzz: crash inputs in build/fuzz/crashes:"; ls build/fuzz/crashes
  exit 1
fi
echo "fuzz: no crash"
