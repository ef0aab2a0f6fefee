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
./build/tsan/tests/isolux_stability_tests
./build/tsan/tests/isolux_tests --gtest_filter='Frame*:Edits*:Light*:Parallel*:Threads*:OnlyWhatChanged*:LongWork*:SolidsPass.theTreePasses*'
echo "tsan: no race"
