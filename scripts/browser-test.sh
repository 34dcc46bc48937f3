#!/usr/bin/env bash
# Real-browser test of `inim place`: installs what is missing (Debian's chromium, nodejs, npm;
# puppeteer-core, pinned in tests/web/package-lock.json, into build/web-test/, never into the
# source tree), then runs tests/web/place_browser.mjs. Exit code = the test's.
# Usage: scripts/browser-test.sh INIM_BINARY OUTDIR [--field MODEL.inimrf] [--[no-]predict] [--compare-eia]
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
WEB_DIR="${INIM_WEB_TEST_DIR:-$ROOT/build/web-test}"

if [ $# -lt 2 ]; then
  echo "usage: scripts/browser-test.sh INIM_BINARY OUTDIR [--field MODEL.inimrf] [--[no-]predict] [--compare-eia]" >&2
  exit 2
fi

PACKAGES=(chromium)
# A node and npm from elsewhere (nvm, NodeSource) serve as well as Debian's.
if ! command -v node >/dev/null || ! command -v npm >/dev/null; then PACKAGES+=(nodejs npm); fi
"$ROOT/scripts/setup.sh" --packages-only "${PACKAGES[@]}"

# npm ci in a copy of the manifest, so node_modules lands in build/, not in the source tree;
# repeated only when the lock file changed.
mkdir -p "$WEB_DIR"
if ! cmp -s "$ROOT/tests/web/package-lock.json" "$WEB_DIR/package-lock.json" || [ ! -d "$WEB_DIR/node_modules/puppeteer-core" ]; then
  echo "browser-test: npm ci (puppeteer-core) in $WEB_DIR"
  cp "$ROOT/tests/web/package.json" "$ROOT/tests/web/package-lock.json" "$WEB_DIR/"
  (cd "$WEB_DIR" && npm ci --ignore-scripts --no-audit --no-fund --loglevel=error)
fi

export INIM_WEB_MODULES="$WEB_DIR"
set +e
node "$ROOT/tests/web/place_browser.mjs" "$@"
code=$?
set -e
exit $code
