#!/usr/bin/env bash
# The README's test command: set up, build, run every test; then the same under AddressSanitizer and
# UndefinedBehaviorSanitizer in a second build directory.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
jobs="$(nproc 2>/dev/null || echo 2)"
# Both trees are unity builds, each target one translation unit (batch size 0): most of CI's time is
# compiling, and every file of a target otherwise emits its own copy of the json, CLI11, doctest and std
# code it uses. Measured one target at a time under the sanitizers: engine/world 128 s of CPU as 13 files,
# 91 s in batches of 8, 86 s as one; the demo library 60 s in batches of 8, 50 s as one.
unity=(-DCMAKE_UNITY_BUILD=ON -DCMAKE_UNITY_BUILD_BATCH_SIZE=0)

# Both ctest runs include the fuzz corpora (label fuzz): tests/fuzz/CMakeLists.txt builds each fuzz target
# as a replay runner and runs it on every seed and regression input. Measured here (2 cores, one fuzzer
# running beside it): 18 s to compile and link the seven runners in this tree, 24 s in the sanitizer tree,
# under a second to run them in each, so about 45 s in all. A libFuzzer smoke run is left out: the clang
# fuzz tree alone took 3 min 7 s to build (4 min of CPU), past the 3 minutes this file may add to CI;
# scripts/fuzz.sh runs the fuzzers (tests/fuzz/README.md).
"$here/scripts/setup.sh" "$here/build" "${unity[@]}"
(cd "$here/build" && ctest --output-on-failure -j "$jobs")

echo "prep: tests again under AddressSanitizer + UndefinedBehaviorSanitizer"
# -O1 -g1 (the level the sanitizers' documentation recommends, with line tables for their stack traces):
# the sanitizer tree's compile time is most of CI. engine/world/world.cpp takes 13 s at -O1 -g1, 22 s at
# -O2 -g1, and full -g about doubled it again (measured here, one file at a time).
"$here/scripts/setup.sh" "$here/build-asan" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" \
  -DPREP_SANITIZE=ON -DPREP_BUILD_BENCH=OFF -DPREP_BUILD_CLI=OFF "${unity[@]}"
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
(cd "$here/build-asan" && ctest --output-on-failure -j "$jobs" -LE slow)
