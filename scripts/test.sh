#!/usr/bin/env bash
# The README's test command: set up, build, run every test; then the same under AddressSanitizer and
# UndefinedBehaviorSanitizer in a second build directory; then a short libFuzzer run of every loader.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
jobs="$(nproc 2>/dev/null || echo 2)"
# Both trees are unity builds, each target one translation unit (batch size 0): most of CI's time is
# compiling, and every file of a target otherwise emits its own copy of the json, CLI11, doctest and std
# code it uses. Measured one target at a time under the sanitizers: engine/world 128 s of CPU as 13 files,
# 91 s in batches of 8, 86 s as one; the demo library 60 s in batches of 8, 50 s as one.
unity=(-DCMAKE_UNITY_BUILD=ON -DCMAKE_UNITY_BUILD_BATCH_SIZE=0)
# Each phase's wall-clock seconds, printed as it ends: the whole must stay within CI's 20 minutes.
phase_start=$SECONDS
phase_done() { echo "prep: $1 took $((SECONDS - phase_start)) s"; phase_start=$SECONDS; }

# The fuzz corpora (tests/fuzz/README.md): the normal tree builds each fuzz target as a replay runner and
# ctest runs it on every seed and regression input (label fuzz). The sanitizer tree does not: the libFuzzer
# smoke run at the end runs the same inputs under the same sanitizers, and fuzzes a little beyond them.
# clang and its libFuzzer runtime are installed for that run and for the sanitizer tree.
export PREP_EXTRA_PACKAGES="clang-14 libclang-rt-14-dev ${PREP_EXTRA_PACKAGES:-}"
"$here/scripts/setup.sh" "$here/build" "${unity[@]}"
phase_done "set-up and the release build"
(cd "$here/build" && ctest --output-on-failure -j "$jobs")
phase_done "the release tests"

echo "prep: tests again under AddressSanitizer + UndefinedBehaviorSanitizer, built with clang"
# The sanitizer tree is built with clang (installed above for the fuzz run), the release tree with GCC:
# every test then passes under two compilers, which catches what one of them happens to accept (an
# evaluation order the language leaves open, an extension). And clang builds it faster: on a clean clone
# of this 2-core machine the GCC sanitizer tree took 394 s to build and its tests 234 s, the clang one
# 273 s and 167 s. -O1 -g1: the level the sanitizers' documentation recommends, with line tables for their
# stack traces.
# A tree configured before with another compiler is configured afresh: when the compiler changes under an
# existing cache, CMake drops the other settings given (the sanitizers among them).
asan_cache="$here/build-asan/CMakeCache.txt"
if [ -f "$asan_cache" ] && ! grep -q '^CMAKE_CXX_COMPILER:[A-Z]*=.*clang++-14$' "$asan_cache"; then
  rm -rf "$asan_cache" "$here/build-asan/CMakeFiles"
fi
"$here/scripts/setup.sh" "$here/build-asan" -DCMAKE_C_COMPILER=clang-14 -DCMAKE_CXX_COMPILER=clang++-14 \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" \
  -DPREP_SANITIZE=ON -DPREP_BUILD_BENCH=OFF -DPREP_BUILD_CLI=OFF -DPREP_FUZZ_REPLAY=OFF "${unity[@]}"
phase_done "the sanitizer build"
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
# Tests labelled slow (a minute of the demo under stress, 50 random courses) run in the normal tree only:
# under the sanitizers they would take over two minutes, and the shorter tests cover the same code there.
(cd "$here/build-asan" && ctest --output-on-failure -j "$jobs" -LE slow)
phase_done "the tests under the sanitizers"

echo "prep: fuzz smoke run: every loader's libFuzzer target for 10 s under AddressSanitizer + UndefinedBehaviorSanitizer"
# Measured on this 2-core machine: the -O0 fuzz tree takes about 1.5 minutes of CPU to build (the -O1 tree
# of scripts/fuzz.sh TARGET 3.8), and the seven targets, two at a time, about 45 s. The whole of this file
# took 818 s on a clean clone (1006 s with the GCC sanitizer tree, the same day).
unset ASAN_OPTIONS UBSAN_OPTIONS  # libFuzzer sets its own
"$here/scripts/fuzz.sh" --smoke 10
phase_done "the fuzz build and smoke run"
echo "prep: every test passed in $SECONDS s"
