#!/usr/bin/env bash
# Smoke test of the windowed demo on a virtual display: starts prep-demo in a 1280x720 window under Xvfb,
# presses keys (with xdotool when it is installed, else through prep-demo's own --script, which feeds the
# same key handler; PREP_SMOKE_KEYS=script forces that), and takes a screenshot from the back buffer after the keys.
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

# Keys: E orbits the camera three steps, Space pauses the clip (Escape closes the demo, xdotool only).
if [ "${PREP_SMOKE_KEYS:-xdotool}" = xdotool ] && command -v xdotool >/dev/null; then
  # The screenshot is taken as the demo closes on Escape, after the other keys.
  log=$(mktemp)
  timeout 300 xvfb-run -a -s "-screen 0 1280x720x24" bash -c '
    "$0" --no-vsync --screenshot "$1" --screenshot-after -1 "${@:2}" & pid=$!
    # Wait until the window is mapped (focusing an unmapped window is an X error), then focus and type.
    win=$(xdotool search --sync --onlyvisible --name "prep demo" 2>/dev/null | head -1)
    focused=no
    for i in $(seq 25); do xdotool windowfocus --sync "$win" 2>/dev/null && { focused=yes; break; }; sleep 0.2; done
    [ $focused = yes ] && xdotool key --delay 150 e e e space Escape || { echo "xvfb_smoke: cannot type into the window" >&2; kill $pid; }
    wait $pid' "$demo" "$out" "$@" | tee "$log"
else
  log=$(mktemp)
  timeout 300 xvfb-run -a -s "-screen 0 1280x720x24" \
    "$demo" --no-vsync --script "10:e,11:e,12:e,13:space" --screenshot "$out" --screenshot-after 40 "$@" | tee "$log"
fi
# Space paused the clip: the key reached the demo's handler.
grep -q "closing: .* paused" "$log" || { echo "xvfb_smoke: the keys did not reach the demo" >&2; rm -f "$log"; exit 1; }
rm -f "$log"

[ -s "$out" ] || { echo "xvfb_smoke: no screenshot written" >&2; exit 1; }
# PNG signature and the IHDR size: the window's framebuffer.
size=$(od -An -tu1 -j16 -N8 "$out" | awk '{print $1*16777216+$2*65536+$3*256+$4 "x" $5*16777216+$6*65536+$7*256+$8}')
head -c 8 "$out" | od -An -tx1 | grep -q "89 50 4e 47 0d 0a 1a 0a" || { echo "xvfb_smoke: $out is not a PNG" >&2; exit 1; }
echo "xvfb_smoke: ok, $out ($size)"
