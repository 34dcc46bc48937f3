#!/usr/bin/env bash
# The main job on the built-in default: installs what is missing, builds, then renders the
# default scene (scenes/paper-fig7.json) into out/default/.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD_DIR="${INIM_BUILD_DIR:-$ROOT/build/release}"
OUT="${1:-$ROOT/out/default}"
"$ROOT/scripts/setup.sh" inim
INIM="$BUILD_DIR/inim"
mkdir -p "$OUT"
echo "run: rendering the default scene (paper-fig7) to $OUT/paper-fig7.exr and .png"
"$INIM" render --out "$OUT/paper-fig7.exr" --width 1280 --height 560 --spp 32
echo "run: done; outputs in $OUT"
ls -l "$OUT"
