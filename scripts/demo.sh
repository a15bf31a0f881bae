#!/usr/bin/env bash
# The README's main command: set up, build, and run the demo on the obstacle course (Sec. 7.2) -- in a
# window when there is a display; without one (a server, CI) it says so in one line, runs the course
# headless until it is done (the goal reached and nothing playing, at most 60 s), writes a video (ffmpeg,
# which this command installs for it) and a PNG strip of frames of the run, and prints where they are.
# The crowd (--crowd N) headless is a screenshot after 10 s instead.
#   scripts/demo.sh [prep-demo options...]      e.g. --scenario assets/scenarios/kick.json, --crowd 200
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
demo="$here/build/prep-demo"
out="$here/build/demo"

# Set-up and build; "video" adds ffmpeg, which only the headless run needs (the tests do not: CI stays lean).
setup() {
  if [ "${1:-}" = video ]; then
    PREP_EXTRA_PACKAGES="${PREP_EXTRA_PACKAGES:-} ffmpeg" "$here/scripts/setup.sh" "$here/build"
  else
    "$here/scripts/setup.sh" "$here/build"
  fi
}

if [ -n "${DISPLAY:-}" ] || [ -n "${WAYLAND_DISPLAY:-}" ]; then
  setup
  status=0
  "$demo" "$@" || status=$?
  # 2: no window could be opened on that display (prep-demo has said why); anything else is the demo's own.
  [ "$status" -eq 2 ] || exit "$status"
  echo "prep: no window could be opened on the display: running headless instead"
else
  echo "prep: no display (DISPLAY and WAYLAND_DISPLAY are unset): running headless"
fi

crowd=0
for arg in "$@"; do
  case "$arg" in --crowd | --crowd=*) crowd=1 ;; esac
done
if [ "$crowd" -eq 1 ]; then
  setup
  mkdir -p "$out"
  "$demo" --headless --seconds 10 --screenshot "$out/crowd.png" "$@"
  echo "prep: the crowd after 10 s is $out/crowd.png"
  exit 0
fi
setup video

mkdir -p "$out"
# The course up to its goal and a second after (--until-goal); --seconds bounds it (a later --seconds
# among the arguments replaces it).
if command -v ffmpeg >/dev/null 2>&1; then
  "$demo" --headless --until-goal --seconds 60 --video "$out/obstacles.mp4" --strip "$out/obstacles.png" "$@"
  echo "prep: the demo's video is $out/obstacles.mp4 (a strip of its frames: $out/obstacles.png)"
else
  "$demo" --headless --until-goal --seconds 60 --strip "$out/obstacles.png" "$@"
  echo "prep: ffmpeg is not installed, so no video: a strip of frames of the run is $out/obstacles.png"
fi
