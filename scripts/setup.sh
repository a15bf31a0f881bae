#!/usr/bin/env bash
# Installs what prep needs from Debian's packages (only what is missing, so it is idempotent) and builds.
#   scripts/setup.sh [BUILD_DIR] [extra cmake args...]
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-$here/build}"
shift || true

packages=(build-essential cmake ninja-build pkg-config
          libglm-dev nlohmann-json3-dev libcli11-dev doctest-dev libbenchmark-dev libstb-dev
          libtinygltf-dev libglfw3-dev libimgui-dev libosmesa6-dev xvfb xauth xdotool
          locales-all  # a comma-decimal locale for the BVH locale test
          ${PREP_EXTRA_PACKAGES:-})
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "prep: installing ${missing[*]}"
  sudo_cmd=(); [ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
  "${sudo_cmd[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq "${missing[@]}" >/dev/null
fi

# The Khronos glTF-Validator (npm package, pinned by tools/gltf-validator/package-lock.json) for the tests.
if command -v npm >/dev/null 2>&1 && [ ! -d "$here/tools/gltf-validator/node_modules/gltf-validator" ]; then
  echo "prep: installing gltf-validator (npm ci)"
  npm ci --prefix "$here/tools/gltf-validator" --no-audit --no-fund >/dev/null
fi

jobs="$(nproc 2>/dev/null || echo 2)"
cmake -S "$here" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release "$@" >/dev/null
cmake --build "$build" -j "$jobs"
