#!/usr/bin/env bash
# The README's main command: set up, build, and run `prep info` on the built-in motion library
# (the demo takes over this command when it lands).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$here/scripts/setup.sh" "$here/build"
exec "$here/build/prep" info "$@"
