#!/usr/bin/env bash
# Installs what is missing, builds Release with -j2, and runs the whole test suite (ctest).
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD_DIR="${INIM_BUILD_DIR:-$ROOT/build/release}"
"$ROOT/scripts/setup.sh"
echo "test: running ctest in $BUILD_DIR"
cd "$BUILD_DIR"
ctest --output-on-failure -j2 --timeout 900
