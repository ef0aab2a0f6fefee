#!/usr/bin/env bash
# Builds everything but the benchmarks with AddressSanitizer and
# UndefinedBehaviorSanitizer and runs the test suite under them (inside one
# Xvfb, like scripts/test.sh), but for the tests named below.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/deps.sh
# Assertions on (no NDEBUG): preconditions are checked under the sanitizers.
cmake --preset asan -DISOLUX_WERROR="${ISOLUX_WERROR:-OFF}" >/dev/null
cmake --build --preset asan
# Mesa's and X11's own allocations outlive the process by design: suppress
# leaks from those libraries only; isolux's own leaks still fail.
export LSAN_OPTIONS="suppressions=$PWD/tests/lsan.supp:print_suppressions=0"
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
cd build/asan
# Godot loads libisolux into its own, uninstrumented process: those tests
# (label "hosted") run in scripts/test.sh only. Python's do run here, with the
# sanitizer's runtime preloaded (tests/capi/run.py).
# The tests labelled heavy (judges and timing loops, tests/CMakeLists.txt)
# and the accuracy scenes of the solids and of the sprite shading (the same
# passes as the smaller SolidsPass and SpriteShading tests, over whole maps)
# run in scripts/test.sh only: under the sanitizers they would take a third
# of CI for no path of their own.
# So do the front ends' end-to-end scripts (app, cli): their code runs under
# the sanitizers through the editor's and the GL unit tests, the bad-input
# corpus (isolux-cli on every hostile input) and fuzz_cli. The app's binary
# is not built here at all (the asan preset sets ISOLUX_BUILD_GUI off).
left_out='^(app|cli)$|SolidsPass\.solids(HalveThePapersErrorOnTheAccuracyScenes|MislightAtMostHalfWhatFootprintsDoAgainst3d|NeverWorseThanFootprintsOnTheTownScene|NeverWorseThanFootprintsOnDrawnTownSeeds)|SpriteShading\.solidsShadingHalvesTheSpritesErrorAgainstTheShadedTruth'
echo "sanitize: leaving out the tests labelled hosted or heavy, the front ends' scripts and the accuracy scenes: $(ctest -N -L 'hosted|heavy' | sed -n 's/^ *Test *#[0-9]*: //p' | tr '\n' ' ')$(ctest -N -R "$left_out" | sed -n 's/^ *Test *#[0-9]*: //p' | tr '\n' ' ')"
xvfb-run -a -s "-screen 0 1280x1024x24" ctest --output-on-failure --timeout 1200 -j "$(nproc)" -LE 'hosted|heavy' -E "$left_out"
