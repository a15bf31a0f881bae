#!/usr/bin/env bash
# The README's strips of the built-in motion library: each generated clip as 8 frames, evenly spaced over
# the clip, seen from its side, rendered through the demo's headless clip viewer (with the clip's obstacle).
#   scripts/library_strips.sh [BUILD_DIR] [OUT_DIR]     (default: build, assets/readme/library)
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-$here/build}"
out="${2:-$here/assets/readme/library}"
demo="$build/prep-demo"
[ -x "$demo" ] || { echo "library_strips: $demo not built" >&2; exit 1; }
mkdir -p "$out"
clips=$("$build/prep" info --json | python3 -c 'import json, sys; print(" ".join(c["name"] for c in json.load(sys.stdin)["clips"]))')
for clip in $clips; do
  "$demo" --headless --clip "$clip" --strip "$out/$clip.png" --frames 8 --width 200 --height 300 > /dev/null
  echo "library_strips: $out/$clip.png"
done
