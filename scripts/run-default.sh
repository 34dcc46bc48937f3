#!/usr/bin/env bash
# The main job on the built-in default: installs what is missing, builds, then runs inim on
# the paper's display (optics/displays/paper-prototype.json) and the default scene
# (scenes/paper-fig7.json), writing everything into out/default/ (or the folder given).
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD_DIR="${INIM_BUILD_DIR:-$ROOT/build/release}"
OUT="${1:-$ROOT/out/default}"
"$ROOT/scripts/setup.sh" inim
INIM="$BUILD_DIR/inim"
mkdir -p "$OUT"

echo "run: display quantities of the paper's prototype -> $OUT/display-info.txt, .json"
"$INIM" display info > "$OUT/display-info.txt"
"$INIM" display info --json > "$OUT/display-info.json"

echo "run: orthoscopic EIA of paper-fig7 on the paper's display (6,215,625 rays, 4 spp)"
"$INIM" eia --out "$OUT/eia.exr" --preview "$OUT/eia-preview.png" --sdf "$OUT/triads.sdf" \
        --aovs --spp 4

echo "run: the scene itself, rendered spectrally from 350 mm -> $OUT/paper-fig7.exr, .png"
"$INIM" render --out "$OUT/paper-fig7.exr" --width 1280 --height 560 --spp 32

echo "run: colour calibration of the display as the camera sees it at 0 and +-7 deg -> $OUT/calibration/"
"$INIM" calibrate --out "$OUT/calibration"

echo "run: the paper's Fig. 11 in software: 5 reconstructed + 5 reference views, the error budget and"
echo "     the error against depth of each -> $OUT/fig11/"
"$INIM" fig11 --out "$OUT/fig11" --budget --budget-calibration "$OUT/calibration/panel_correction.cube"

echo "run: Fig. 11 with that calibration applied to the EIA -> $OUT/fig11-calibrated/"
"$INIM" fig11 --out "$OUT/fig11-calibrated" --calibration "$OUT/calibration/panel_correction.cube"

echo "run: Fig. 11 on the design fix: the same hardware, EIs toed-in for 350 mm and made at the viewing gap"
echo "     (optics/displays/paper-prototype-toed-in.json): every depth rebuilt where it belongs, the error"
echo "     against depth lowest around L -> $OUT/fig11-toed-in/"
"$INIM" fig11 --out "$OUT/fig11-toed-in" --display "$ROOT/optics/displays/paper-prototype-toed-in.json"

echo "run: done; outputs in $OUT"
ls -l "$OUT"
