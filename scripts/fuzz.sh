#!/usr/bin/env bash
# Fuzzing, opt-in and not part of CI: builds the libFuzzer targets of fuzz/ with clang,
# AddressSanitizer and UBSan into build/fuzz, then runs each for SECONDS (default 30) on its
# corpus, stored as fuzz/corpus/<target>.tar.xz and unpacked to build/fuzz/corpus/<target>/. If
# the run found new coverage, the corpus is minimised (-merge=1: the inputs that keep its
# coverage) and the archive repacked, the same inputs always to the same bytes (commit it). A
# crash, leak, UB report or an exception other than inim's InputError stops the target and is
# saved as build/fuzz/crash-*; the summary line per target gives executions, coverage, corpus
# files and the result. --coverage runs each stored corpus once without fuzzing and prints its
# files, edges (cov) and features (ft); --add merges the given files into a target's corpus.
# Usage: scripts/fuzz.sh [SECONDS] [TARGET...]     (targets: fuzz/fuzz_<TARGET>.cpp; default all)
#        scripts/fuzz.sh --coverage [TARGET...]
#        scripts/fuzz.sh --add TARGET FILE...
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD="$ROOT/build/fuzz"
MODE=fuzz
inputs=()
case "${1:-}" in
  --coverage) MODE=coverage; shift ;;
  --add)
    MODE=add
    if [ $# -lt 3 ]; then echo "usage: scripts/fuzz.sh --add TARGET FILE..." >&2; exit 2; fi
    inputs=("${@:3}")
    set -- "$2" ;;
  *) SECONDS_EACH="${1:-30}"; shift || true ;;
esac
"$ROOT/scripts/setup.sh" --packages-only clang libclang-rt-14-dev

targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
  for f in "$ROOT"/fuzz/fuzz_*.cpp; do n="$(basename "$f" .cpp)"; targets+=("${n#fuzz_}"); done
fi
cmake -S "$ROOT" -B "$BUILD" -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo -DINIM_FUZZ=ON >/dev/null
cmake --build "$BUILD" -j2 --target "${targets[@]/#/fuzz_}"

# Runs fuzz_$1 in build/fuzz with the options of every run; the other arguments go to libFuzzer.
fuzzer() {
  local t="$1"
  shift
  (cd "$BUILD" && ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 TMPDIR="$BUILD" \
     LSAN_OPTIONS="suppressions=$ROOT/fuzz/lsan.supp" "./fuzz_$t" -timeout=30 -rss_limit_mb=3072 -max_len=65536 "$@")
}

# Unpacks the stored corpus of target $1 into a fresh build/fuzz/corpus/<target>/.
unpack() {
  local dir="$BUILD/corpus/$1" archive="$ROOT/fuzz/corpus/$1.tar.xz"
  rm -rf "$dir"
  mkdir -p "$dir"
  if [ -f "$archive" ]; then tar -xJf "$archive" -C "$dir"; fi
}

# Packs the files of directory $1 (named by their SHA-1, as libFuzzer names them) into archive $2:
# names sorted, no times, owners or modes of this checkout, xz single-threaded. The archive is
# only replaced if its bytes change.
pack() {
  (cd "$1" && find . -maxdepth 1 -type f -printf '%f\n' | LC_ALL=C sort |
     tar --sort=name --mtime=@0 --owner=0 --group=0 --numeric-owner --mode=0644 --format=gnu \
         --no-recursion -cf - -T - | xz -6 -T1 -c) >"$2.new"
  if cmp -s "$2.new" "$2"; then rm "$2.new"; else mv "$2.new" "$2"; fi
}

files() { find "$1" -maxdepth 1 -type f | wc -l; }

# Minimises build/fuzz/corpus/$1/ with the inputs of the further directories into a fresh
# directory (-merge=1), which becomes the corpus, and repacks the archive; fails if merging does.
minimise() {
  local t="$1" dir="$BUILD/corpus/$1" merged="$BUILD/corpus/$1.merged"
  shift
  rm -rf "$merged"
  mkdir -p "$merged"
  fuzzer "$t" -merge=1 "$merged" "$dir" "$@" >"$BUILD/logs/$t.merge.log" 2>&1 || return 1
  pack "$merged" "$ROOT/fuzz/corpus/$t.tar.xz"
  rm -rf "$dir"
  mv "$merged" "$dir"
}

mkdir -p "$BUILD/logs" "$BUILD/corpus"
status=0
if [ "$MODE" = coverage ]; then
  for t in "${targets[@]}"; do
    unpack "$t"
    dir="$BUILD/corpus/$t"
    log="$BUILD/logs/$t.coverage.log"
    if fuzzer "$t" -runs=0 "$dir" >"$log" 2>&1; then
      result=ok
    else
      result="FOUND (see $log)"
      status=1
    fi
    bytes="$(find "$dir" -maxdepth 1 -type f -printf '%s\n' | awk '{ s += $1 } END { print s + 0 }')"
    cov="$(grep -o 'cov: [0-9]*' "$log" | tail -1 | grep -o '[0-9]*' || echo '?')"
    ft="$(grep -o 'ft: [0-9]*' "$log" | tail -1 | grep -o '[0-9]*' || echo '?')"
    printf 'corpus %-16s %6s files %9s bytes  cov %6s  ft %7s  %s\n' "$t" "$(files "$dir")" "$bytes" \
      "$cov" "$ft" "$result"
  done
  exit $status
fi

if [ "$MODE" = add ]; then
  t="${targets[0]}"
  unpack "$t"
  before="$(files "$BUILD/corpus/$t")"
  rm -rf "$BUILD/corpus/$t.add"
  mkdir -p "$BUILD/corpus/$t.add"
  cp -- "${inputs[@]}" "$BUILD/corpus/$t.add/"
  if ! minimise "$t" "$BUILD/corpus/$t.add"; then
    echo "fuzz: merge failed (see $BUILD/logs/$t.merge.log)"
    exit 1
  fi
  echo "fuzz: $t corpus $before -> $(files "$BUILD/corpus/$t") files (fuzz/corpus/$t.tar.xz)"
  exit 0
fi

for t in "${targets[@]}"; do
  unpack "$t"
  dir="$BUILD/corpus/$t"
  stored="$BUILD/corpus/$t.stored"
  (cd "$dir" && ls -A) | LC_ALL=C sort >"$stored"
  log="$BUILD/logs/$t.log"
  if fuzzer "$t" -max_total_time="$SECONDS_EACH" -reduce_inputs=0 -print_final_stats=1 "$dir" \
       >"$log" 2>&1; then
    result=ok
  else
    result="FOUND (see $log)"
    status=1
  fi
  execs="$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' || echo '?')"
  cov="$(grep -o 'cov: [0-9]*' "$log" | tail -1 | grep -o '[0-9]*' || echo '?')"
  # Inputs the run added (new coverage only: -reduce_inputs=0 keeps it from writing smaller
  # copies of stored ones), minimised with the stored ones.
  if [ -n "$( (cd "$dir" && ls -A) | LC_ALL=C sort | LC_ALL=C comm -13 "$stored" -)" ]; then
    if ! minimise "$t"; then
      result="$result, merge FAILED (see $BUILD/logs/$t.merge.log)"
      status=1
    fi
  fi
  printf 'fuzz %-16s %6ss  %10s execs  cov %6s  corpus %5s  %s\n' "$t" "$SECONDS_EACH" "$execs" "$cov" \
    "$(files "$dir")" "$result"
done
exit $status
