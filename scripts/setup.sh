#!/usr/bin/env bash
# Installs the Debian packages inim needs (only those missing) and builds it (Release, -j2).
# Usage: scripts/setup.sh [TARGET...]   (run by run-default.sh and test.sh; default: all targets)
#        scripts/setup.sh --packages-only [PACKAGE...]   (install inim's packages and these, no build)
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD_DIR="${INIM_BUILD_DIR:-$ROOT/build/release}"

PACKAGES=(build-essential cmake pkg-config libembree-dev libopenexr-dev libopencolorio-dev
          libglm-dev libtbb-dev libopenimageio-dev openimageio-tools nlohmann-json3-dev
          libcli11-dev libgtest-dev libbenchmark-dev libcairo2-dev libpango1.0-dev libfontconfig-dev
          fonts-dejavu-core opencolorio-tools python3-numpy libcivetweb-dev libssl-dev)
PACKAGES_ONLY=0
if [ "${1:-}" = "--packages-only" ]; then
  PACKAGES_ONLY=1
  shift
  PACKAGES+=("$@")
fi

missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing missing Debian packages: ${missing[*]}"
  SUDO=""
  if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
else
  echo "setup: all Debian packages present"
fi

if [ "$PACKAGES_ONLY" -eq 1 ]; then exit 0; fi

echo "setup: configuring and building Release in $BUILD_DIR (-j2)"
cmake -S "$ROOT" -B "$BUILD_DIR" -DCMAKE_BUILD_TYPE=Release >/dev/null
if [ $# -gt 0 ]; then
  cmake --build "$BUILD_DIR" -j2 --target "$@"
else
  cmake --build "$BUILD_DIR" -j2
fi
echo "setup: built $BUILD_DIR/inim"
