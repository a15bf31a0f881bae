#!/usr/bin/env bash
# The README's main command: set up, build, and run the demo on the obstacle course (Sec. 7.2) -- in a window
# when there is a display; without one (a server, CI) it says so in one line, runs the course headless and
# writes a short video (ffmpeg) or, when ffmpeg is missing, a PNG strip of frames, and prints where it is.
#   scripts/demo.sh [prep-demo options...]      e.g. --scenario assets/scenarios/kick.json
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$here/scripts/setup.sh" "$here/build"
demo="$here/build/prep-demo"
out="$here/build/demo"

if [ -n "${DISPLAY:-}" ] || [ -n "${WAYLAND_DISPLAY:-}" ]; then
  status=0
  "$demo" "$@" || status=$?
  # 2: no window could be opened on that display (prep-demo has said why); anything else is the demo's own.
  [ "$status" -eq 2 ] || exit "$status"
  echo "prep: no window could be opened on the display: running the obstacle course headless instead"
else
  echo "prep: no display (DISPLAY and WAYLAND_DISPLAY are unset): running the obstacle course headless"
fi

mkdir -p "$out"
# 40 simulated seconds: the whole course, goal included.
if command -v ffmpeg >/dev/null 2>&1; then
  "$demo" --headless --seconds 40 --video "$out/obstacles.mp4" "$@"
  echo "prep: the demo's video is $out/obstacles.mp4"
else
  "$demo" --headless --seconds 40 --strip "$out/obstacles.png" "$@"
  echo "prep: ffmpeg is not installed, so no video: a strip of frames of the run is $out/obstacles.png"
fi
