#!/usr/bin/env bash
# Runs one loader's fuzz target (tests/fuzz/README.md) for a while on its seed corpus.
#   scripts/fuzz.sh TARGET SECONDS [more libFuzzer flags...]
#   TARGET: bvh, gltf, manifest, scenario, params, policy or retarget
# Builds build-fuzz/ (clang, libFuzzer + ASan + UBSan) when needed. New inputs go to a scratch corpus
# outside the repository ($PREP_FUZZ_DIR/TARGET, default /tmp/prep-fuzz/TARGET; kept between runs, so a
# later run goes on from there); the seeds (tests/fuzz/corpus/TARGET and the build's fuzz-seeds/TARGET) are
# only read. A failing input is written to $PREP_FUZZ_DIR/artifacts/. Prints the executions and the
# coverage at the end.
#
#   scripts/fuzz.sh --smoke SECONDS
# The smoke run of the tests (scripts/test.sh): every target for SECONDS, two at a time, from its seeds
# alone, in build-fuzz-smoke/ (compiled at -O0 as one file per module: it builds in half the time of the
# -O1 tree, and a few seconds of fuzzing need no speed) with a scratch folder that is removed after.
# Exits non-zero if any target fails.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
if (($# < 2)); then
  echo "usage: scripts/fuzz.sh TARGET SECONDS [libFuzzer flags...] | scripts/fuzz.sh --smoke SECONDS" >&2
  exit 2
fi
target="$1" seconds="$2"
shift 2

if [ "$target" = --smoke ]; then
  targets=(bvh gltf manifest scenario params policy retarget)
  smoke_build="$here/build-fuzz-smoke"
  if [ ! -f "$smoke_build/build.ninja" ]; then
    cmake -S "$here" -B "$smoke_build" -G Ninja -DPREP_FUZZ=ON -DCMAKE_C_COMPILER=clang-14 -DCMAKE_CXX_COMPILER=clang++-14 \
      -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG=-O0 -DCMAKE_UNITY_BUILD=ON -DCMAKE_UNITY_BUILD_BATCH_SIZE=0 \
      $(command -v ccache >/dev/null && echo -DCMAKE_CXX_COMPILER_LAUNCHER=ccache) >/dev/null
  fi
  cmake --build "$smoke_build" -j "$(nproc 2>/dev/null || echo 2)" --target prep_fuzz_all | grep -v '^ninja: no work to do' || true
  scratch="$(mktemp -d)"
  # A failing input is kept in build-fuzz-smoke/artifacts/ (the sanitizer's summary is printed).
  trap 'if compgen -G "$scratch/artifacts/*" >/dev/null; then mkdir -p "$smoke_build/artifacts"; cp "$scratch"/artifacts/* "$smoke_build/artifacts/"; fi; rm -rf "$scratch"' EXIT
  failed=0
  for t in "${targets[@]}"; do
    # Two at a time: wait for one of the running pair before starting another.
    while (($(jobs -rp | wc -l) >= 2)); do wait -n || failed=1; done
    PREP_FUZZ_BUILD="$smoke_build" PREP_FUZZ_BUILT=1 PREP_FUZZ_DIR="$scratch" "$0" "$t" "$seconds" &
  done
  while (($(jobs -rp | wc -l) > 0)); do wait -n || failed=1; done
  ((failed == 0)) || echo "fuzz: the smoke run failed; the inputs are in $smoke_build/artifacts/" >&2
  exit "$failed"
fi

[ -f "$here/tests/fuzz/${target}_fuzz.cpp" ] || { echo "fuzz: no target '$target' (no tests/fuzz/${target}_fuzz.cpp)" >&2; exit 2; }

if ! command -v clang++-14 >/dev/null || [ ! -e "$(clang++-14 -print-resource-dir)/lib/linux/libclang_rt.fuzzer-x86_64.a" ]; then
  echo "fuzz: needs clang-14 with libFuzzer: sudo apt-get install clang-14 libclang-rt-14-dev" >&2
  exit 2
fi
build="${PREP_FUZZ_BUILD:-$here/build-fuzz}"
if [ ! -f "$build/build.ninja" ]; then
  cmake -S "$here" -B "$build" -G Ninja -DPREP_FUZZ=ON -DCMAKE_C_COMPILER=clang-14 -DCMAKE_CXX_COMPILER=clang++-14 \
    -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1" \
    $(command -v ccache >/dev/null && echo -DCMAKE_CXX_COMPILER_LAUNCHER=ccache) >/dev/null
fi
# (Built already by the smoke run, which runs two targets at once: one ninja at a time per tree.)
[ -n "${PREP_FUZZ_BUILT:-}" ] || nice -n 10 cmake --build "$build" -j 2 --target "prep_fuzz_$target" | grep -v '^ninja: no work to do' || true
[ -x "$build/prep_fuzz_$target" ] || { echo "fuzz: build of prep_fuzz_$target failed" >&2; exit 1; }

scratch="${PREP_FUZZ_DIR:-/tmp/prep-fuzz}"
mkdir -p "$scratch/$target" "$scratch/artifacts"
flags=(-max_total_time="$seconds" -timeout=2 -rss_limit_mb=2048 -print_final_stats=1
       -artifact_prefix="$scratch/artifacts/$target-")
[ -f "$here/tests/fuzz/dict/$target.dict" ] && flags+=(-dict="$here/tests/fuzz/dict/$target.dict")
log="$scratch/$target.log"
status=0
start=$SECONDS
# The scratch folder comes first: libFuzzer writes what it finds into its first corpus folder.
# Seeds the build generated (tests/fuzz/bvh_seeds.cmake) are read beside the checked-in ones.
seeds=()
for folder in "$here/tests/fuzz/corpus/$target" "$build/fuzz-seeds/$target"; do
  [ -d "$folder" ] && seeds+=("$folder")
done
nice -n 15 "$build/prep_fuzz_$target" "${flags[@]}" "$@" "$scratch/$target" "${seeds[@]}" >"$log" 2>&1 || status=$?
# The last status line holds the coverage (cov: edges, ft: features); -print_final_stats the executions.
last="$(grep -aE '#[0-9]+.*cov: ' "$log" | tail -1 || true)"
execs="$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)"
echo "fuzz $target: ${execs:-?} executions in $((SECONDS - start)) s; cov $(sed -n 's/.*cov: \([0-9]*\).*/\1/p' <<<"$last") ft $(sed -n 's/.* ft: \([0-9]*\).*/\1/p' <<<"$last") (log: $log)"
if ((status != 0)); then
  echo "fuzz $target: FAILED (exit $status); the input is in $scratch/artifacts/:" >&2
  grep -aE '^(==[0-9]+==ERROR|SUMMARY|fuzz:|.*runtime error|artifact_prefix|Test unit written)' "$log" | head -20 >&2
  exit 1
fi
