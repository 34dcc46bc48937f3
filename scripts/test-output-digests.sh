#!/usr/bin/env bash
# Output by output, are two versions the same bytes? Runs the test suite of a build folder with
# INIM_TEST_DIGESTS set, so that every scratch folder (tests/fixtures.h, ScratchDir) records the
# FNV-1a digest of each file its tests left in it; then compares two such records. Files written
# under the same name by several tests are compared as sets of digests.
# Usage: scripts/test-output-digests.sh record BUILD_DIR RECORD.txt [ctest options...]
#        scripts/test-output-digests.sh compare OLD.txt NEW.txt
set -euo pipefail
case "${1:-}" in
  record)
    build="$2" record="$(realpath -m "$3")"
    shift 3
    rm -f "$record"
    (cd "$build" && INIM_TEST_DIGESTS="$record" ctest -j2 --timeout 1500 "$@") || true
    echo "recorded $(wc -l <"$record") files in $record" ;;
  compare)
    python3 - "$2" "$3" <<'PY'
import collections, sys
def load(path):
    d = collections.defaultdict(list)
    for line in open(path):
        key, digest = line.rstrip("\n").rsplit(" ", 1)
        d[key].append(digest)
    return {k: sorted(v) for k, v in d.items()}
old, new = load(sys.argv[1]), load(sys.argv[2])
both = sorted(set(old) & set(new))
differ = [k for k in both if old[k] != new[k]]
print(f"files in both runs: {len(both)}; same bytes: {len(both) - len(differ)}; differ: {len(differ)}")
print(f"only in the old run: {len(set(old) - set(new))}; only in the new run: {len(set(new) - set(old))}")
for k in differ:
    print("  differs:", k)
PY
    ;;
  *) echo "usage: $0 record BUILD_DIR RECORD.txt [ctest options] | compare OLD.txt NEW.txt" >&2; exit 2 ;;
esac
