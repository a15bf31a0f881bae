#!/usr/bin/env bash
# Smoke test of the windowed demo on a virtual display: starts prep-demo on the obstacle course in a
# 1280x720 window under Xvfb and presses keys -- W W D move the goal 2 m away from the camera and 1 m to
# its right, Escape closes the demo -- with xdotool when it is installed, else through prep-demo's own
# --script (which feeds the same key handler; PREP_SMOKE_KEYS=script forces that). The screenshot is read
# from the back buffer as the demo closes, after the keys.
# Checks: the keys reached the World (the goal the demo prints on closing moved by about 2.2 m) and the
# screenshot is a 1280x720 PNG. tests/render/xvfb_test.cpp runs this and checks the screenshot's pixels.
#   scripts/xvfb_smoke.sh [BUILD_DIR] [OUT.png] [extra prep-demo args...]
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-$here/build}"
out="${2:-$build/xvfb_smoke.png}"
shift 2 || shift $# || true
demo="$build/prep-demo"
[ -x "$demo" ] || { echo "xvfb_smoke: $demo not built" >&2; exit 1; }
command -v xvfb-run >/dev/null || { echo "xvfb_smoke: xvfb-run missing (apt-get install xvfb xauth)" >&2; exit 1; }
rm -f "$out"
log=$(mktemp)
trap 'rm -f "$log"' EXIT

if [ "${PREP_SMOKE_KEYS:-xdotool}" = xdotool ] && command -v xdotool >/dev/null; then
  timeout 300 xvfb-run -a -s "-screen 0 1280x720x24" bash -c '
    "$0" --no-vsync --screenshot "$1" --screenshot-after -1 "${@:2}" & pid=$!
    # Wait until the window is mapped (focusing an unmapped window is an X error), then focus and type.
    win=$(xdotool search --sync --onlyvisible --name "prep demo" 2>/dev/null | head -1)
    focused=no
    for i in $(seq 25); do xdotool windowfocus --sync "$win" 2>/dev/null && { focused=yes; break; }; sleep 0.2; done
    # A second of frames first: the panels have laid themselves out, the world runs.
    sleep 1
    [ $focused = yes ] && xdotool key --delay 150 w w d Escape || { echo "xvfb_smoke: cannot type into the window" >&2; kill $pid; }
    wait $pid' "$demo" "$out" "$@" | tee "$log"
else
  timeout 300 xvfb-run -a -s "-screen 0 1280x720x24" \
    "$demo" --no-vsync --script "30:w,31:w,32:d" --screenshot "$out" --screenshot-after 60 "$@" | tee "$log"
fi

# The keys moved the World's goal: "closing: ... goal X0 Z0 -> X1 Z1 ...".
moved=$(sed -n 's/.*closing: .* goal \([-0-9.]*\) \([-0-9.]*\) -> \([-0-9.]*\) \([-0-9.]*\),.*/\1 \2 \3 \4/p' "$log" |
        awk '{d = sqrt(($3-$1)^2 + ($4-$2)^2); printf "%.2f", d}')
[ -n "$moved" ] || { echo "xvfb_smoke: the demo did not report its goal on closing" >&2; exit 1; }
awk -v d="$moved" 'BEGIN { exit !(d > 2.0 && d < 2.4) }' ||
  { echo "xvfb_smoke: the keys did not move the goal as W W D should (moved $moved m)" >&2; exit 1; }

[ -s "$out" ] || { echo "xvfb_smoke: no screenshot written" >&2; exit 1; }
head -c 8 "$out" | od -An -tx1 | grep -q "89 50 4e 47 0d 0a 1a 0a" || { echo "xvfb_smoke: $out is not a PNG" >&2; exit 1; }
# The IHDR size: the window's framebuffer.
size=$(od -An -tu1 -j16 -N8 "$out" | awk '{print $1*16777216+$2*65536+$3*256+$4 "x" $5*16777216+$6*65536+$7*256+$8}')
[ "$size" = 1280x720 ] || { echo "xvfb_smoke: $out is $size, not 1280x720" >&2; exit 1; }
echo "xvfb_smoke: ok, the goal moved $moved m, $out ($size)"
