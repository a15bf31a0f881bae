#!/usr/bin/env bash
# Regenerates the README's measured results and prints them as markdown:
#   - the quality tables (scenario x method x metric, and the acceptance checks) on the built-in
#     library and on the CMU motion capture, from `prep evaluate`;
#   - the alpha-over-time plots of the three methods per scenario (assets/readme/alpha_<scenario>.png);
#   - the training curve of the paper's configuration (assets/readme/training_curve.png), from `prep train`;
#   - the speed table, from `prep bench`.
# Usage: scripts/results.sh [BUILD_DIR]   (default: build; the `prep` target is built first)
# Policies are cached in $PREP_CACHE_DIR (default: BUILD_DIR/cache), so a rerun skips their training.
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=$(cd "${1:-$root/build}" && pwd)
prep="$build/prep"
out="$root/assets/readme"
export PREP_CACHE_DIR="${PREP_CACHE_DIR:-$build/cache}"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

cmake --build "$build" --target prep >&2
mkdir -p "$out"
cd "$root"

echo "### Quality on the built-in library"
echo
echo '`prep evaluate --scenario assets/scenarios/{kick,obstacles,fight}.json --seconds 45 --markdown --plot-dir assets/readme`'
echo
"$prep" evaluate --scenario assets/scenarios/kick.json --scenario assets/scenarios/obstacles.json \
  --scenario assets/scenarios/fight.json --seconds 45 --markdown --plot-dir "$out"
echo
echo "### Quality on CMU motion capture"
echo
echo '`prep evaluate --scenario assets/scenarios/{kick_daz43,duck_cmu31,jump_cmu31,fight_cmu31}.json --seconds 45 --markdown --plot-dir assets/readme`'
echo
"$prep" evaluate --scenario assets/scenarios/kick_daz43.json --scenario assets/scenarios/duck_cmu31.json \
  --scenario assets/scenarios/jump_cmu31.json --scenario assets/scenarios/fight_cmu31.json --seconds 45 \
  --markdown --plot-dir "$out"
echo
echo "### Training curve (the paper's configuration, 19,200 states)"
echo
echo '`prep train --out policy.bin --json` (the curve: policy-curve.png, copied to assets/readme/training_curve.png)'
echo
"$prep" train --out "$work/policy.bin" --json | tee "$work/train.json" | sed 's/^/    /'
cp "$work/policy-curve.png" "$out/training_curve.png"
echo
echo "### Speed (a shared 2-core machine: figures vary by 15-30% from run to run)"
echo
echo '`prep bench`'
"$prep" bench
echo
echo "Images written: $(cd "$out" && ls alpha_*.png training_curve.png | tr '\n' ' ')"
