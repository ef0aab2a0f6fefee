#!/usr/bin/env bash
# ThreadSanitizer over what runs on threads: the frame (tracing, correction,
# accumulation, blur and composite on a pool: tests/stability/parallel_test.cpp
# and the Frame, Edits, Light, OnlyWhatChanged and LongWork tests; the solids
# passes walking one light's rays on several threads) and the whole
# stability suite. Any race fails.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/deps.sh
cmake --preset tsan -DISOLUX_WERROR="${ISOLUX_WERROR:-OFF}" >/dev/null
cmake --build --preset tsan --target isolux_stability_tests isolux_tests
export TSAN_OPTIONS="halt_on_error=1:second_deadlock_stack=1"
# The two binaries side by side, one a core; each one's output kept whole.
./build/tsan/tests/isolux_stability_tests >build/tsan/stability.log 2>&1 &
stability=$!
./build/tsan/tests/isolux_tests --gtest_filter='Frame*:Edits*:Light*:Parallel*:Threads*:OnlyWhatChanged*:LongWork*:SolidsPass.theTreePasses*' \
  >build/tsan/frame.log 2>&1 &
frame=$!
status=0
wait "$stability" || status=1
wait "$frame" || status=1
tail -n 3 build/tsan/stability.log build/tsan/frame.log
if [ "$status" -ne 0 ]; then
  cat build/tsan/stability.log build/tsan/frame.log
  echo "tsan: a test failed or a race was found (above)"
  exit 1
fi
echo "tsan: no race"
