#!/usr/bin/env bash
# The browser test on a trained field: trains a small Lego model (300 iterations at 1/4 size,
# ~1 min on 2 cores; ../shared/data/lego or /work/shared/data/lego) and opens it in `inim place`.
# Skips (77) without the data.
# Usage: tests/web/trained_field.sh INIM_BINARY OUTDIR
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
# The shared reference data beside the clone, or at the workspace's fixed place (a clone elsewhere).
LEGO="${INIM_LEGO_DIR:-$ROOT/../shared/data/lego}"
[ -d "$LEGO" ] || [ -n "${INIM_LEGO_DIR:-}" ] || LEGO=/work/shared/data/lego
if [ ! -d "$LEGO" ]; then echo "no Lego data at $LEGO: skipped"; exit 77; fi
mkdir -p "$2"
"$1" train --data "$LEGO" --downscale 4 --iterations 300 --out "$2/lego.inimrf" >/dev/null
exec "$ROOT/scripts/browser-test.sh" "$1" "$2" --field "$2/lego.inimrf"
