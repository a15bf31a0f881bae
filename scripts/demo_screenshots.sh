#!/usr/bin/env bash
# The README's screenshots of the demo: each scenario of Sec. 7.2 at 1280x720 with the panels, taken
# headless a moment before the user's first target motion is launched (the character fully prepared:
# the hips lowered before the crawl, the guard up as the opponent closes in, the slowed approach to the
# ball). The moment is read from a first run's --json, so the pictures follow the engine as it changes.
#   scripts/demo_screenshots.sh [BUILD_DIR] [OUT_DIR]     (default: build, assets/readme)
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-$here/build}"
out="${2:-$here/assets/readme}"
demo="$build/prep-demo"
[ -x "$demo" ] || { echo "demo_screenshots: $demo not built" >&2; exit 1; }
command -v python3 >/dev/null || { echo "demo_screenshots: python3 is needed to read the launch times" >&2; exit 1; }
mkdir -p "$out"
lead=0.35  # s before the launch: the prepared posture, the source still highlighted
for scenario in obstacles kick fight; do
  file="$here/assets/scenarios/$scenario.json"
  at=$("$demo" --headless --scenario "$file" --seconds 40 --json 2>/dev/null | python3 -c '
import json, sys
run = json.load(sys.stdin)
user = [l for l in run["launches"] if l["control"] == "user"]
print(max(1.0, (user[0]["time"] if user else 5.0) - float(sys.argv[1])))' "$lead")
  "$demo" --headless --scenario "$file" --seconds "$at" --screenshot "$out/demo-$scenario.png" > /dev/null
  echo "demo_screenshots: $out/demo-$scenario.png ($scenario at $at s)"
done
