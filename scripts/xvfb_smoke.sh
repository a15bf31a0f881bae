#!/usr/bin/env bash
# Smoke test of the windowed demo on a virtual display: starts prep-demo on the obstacle course in a
# 1280x720 window under Xvfb and works the keys -- D held for about two seconds steers the character to
# the camera's right, then let go, Escape closes the demo -- with xdotool when it is installed, else
# through prep-demo's own --script (which feeds the same key handlers; PREP_SMOKE_KEYS=script forces
# that). The screenshot is read from the back buffer as the demo closes, after the keys.
# Checks: the keys reached the World (the goal the demo prints on closing left the course's goal, 14 m
# ahead, and leads the character: at most the steering lead away from it, 1.8 m, and some slack) and the
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
    if [ $focused = yes ]; then
      xdotool keydown d; sleep 2; xdotool keyup d; sleep 0.5; xdotool key Escape
    else
      echo "xvfb_smoke: cannot type into the window" >&2; kill $pid
    fi
    wait $pid' "$demo" "$out" "$@" | tee "$log"
else
  timeout 300 xvfb-run -a -s "-screen 0 1280x720x24" \
    "$demo" --no-vsync --script "30-230:d" --screenshot "$out" --screenshot-after 260 "$@" | tee "$log"
fi

# The keys steered the World's goal: "closing: ... goal X0 Z0 -> X1 Z1, user at UX UZ, ...".
read -r left lead < <(sed -n 's/.*closing: .* goal \([-0-9.]*\) \([-0-9.]*\) -> \([-0-9.]*\) \([-0-9.]*\), user at \([-0-9.]*\) \([-0-9.]*\),.*/\1 \2 \3 \4 \5 \6/p' "$log" |
  awk '{printf "%.2f %.2f\n", sqrt(($3-$1)^2 + ($4-$2)^2), sqrt(($3-$5)^2 + ($4-$6)^2)}') || true
[ -n "${lead:-}" ] || { echo "xvfb_smoke: the demo did not report its goal on closing" >&2; exit 1; }
awk -v l="$left" -v d="$lead" 'BEGIN { exit !(l > 4.0 && d < 2.3) }' ||
  { echo "xvfb_smoke: the keys did not steer (the goal moved $left m from the course's, is $lead m from the character)" >&2; exit 1; }

[ -s "$out" ] || { echo "xvfb_smoke: no screenshot written" >&2; exit 1; }
head -c 8 "$out" | od -An -tx1 | grep -q "89 50 4e 47 0d 0a 1a 0a" || { echo "xvfb_smoke: $out is not a PNG" >&2; exit 1; }
# The IHDR size: the window's framebuffer.
size=$(od -An -tu1 -j16 -N8 "$out" | awk '{print $1*16777216+$2*65536+$3*256+$4 "x" $5*16777216+$6*65536+$7*256+$8}')
[ "$size" = 1280x720 ] || { echo "xvfb_smoke: $out is $size, not 1280x720" >&2; exit 1; }
echo "xvfb_smoke: ok, the steered goal is $lead m from the character ($left m from the course's), $out ($size)"
