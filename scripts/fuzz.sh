#!/usr/bin/env bash
# Fuzzing, opt-in and not part of CI: builds the libFuzzer targets of fuzz/ with clang,
# AddressSanitizer and UBSan into build/fuzz, then runs each for SECONDS (default 30) on its
# corpus fuzz/corpus/<target>/ (inputs that add coverage are kept there; commit them). A crash,
# leak, UB report or an exception other than inim's InputError stops the target and is saved as
# build/fuzz/crash-*; the summary line per target gives executions, coverage and the result.
# Usage: scripts/fuzz.sh [SECONDS] [TARGET...]     (targets: fuzz/fuzz_<TARGET>.cpp; default all)
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD="$ROOT/build/fuzz"
SECONDS_EACH="${1:-30}"
shift || true
"$ROOT/scripts/setup.sh" --packages-only clang libclang-rt-14-dev

targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
  for f in "$ROOT"/fuzz/fuzz_*.cpp; do n="$(basename "$f" .cpp)"; targets+=("${n#fuzz_}"); done
fi
cmake -S "$ROOT" -B "$BUILD" -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo -DINIM_FUZZ=ON >/dev/null
cmake --build "$BUILD" -j2 --target "${targets[@]/#/fuzz_}"

mkdir -p "$BUILD/logs"
status=0
for t in "${targets[@]}"; do
  mkdir -p "$ROOT/fuzz/corpus/$t"
  log="$BUILD/logs/$t.log"
  if (cd "$BUILD" && ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
        TMPDIR="$BUILD" \
        "./fuzz_$t" -max_total_time="$SECONDS_EACH" -timeout=30 -rss_limit_mb=3072 -max_len=65536 \
        -print_final_stats=1 "$ROOT/fuzz/corpus/$t" >"$log" 2>&1); then
    result=ok
  else
    result="FOUND (see $log)"
    status=1
  fi
  execs="$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' || echo '?')"
  cov="$(grep -o 'cov: [0-9]*' "$log" | tail -1 | grep -o '[0-9]*' || echo '?')"
  printf 'fuzz %-16s %6ss  %10s execs  cov %6s  %s\n' "$t" "$SECONDS_EACH" "$execs" "$cov" "$result"
done
exit $status
