#!/bin/sh
# Runs every fuzz target of a FASCIA_FUZZ=ON build for SECONDS each (`make fuzz` calls it):
#   tests/fuzz/RunFuzz.sh BUILD_DIR SECONDS [TARGET...]
# Each target starts from its seeds (tests/fuzz/corpus/<t>, tests/fuzz/regressions/<t>) and from what
# earlier runs found (BUILD_DIR/corpus/<t>, where new inputs go); crashes, leaks, timeouts and
# out-of-memory inputs are written to BUILD_DIR/findings/<t>/ and the log to BUILD_DIR/logs/<t>.log.
# FUZZ_TIMEOUT (default 30) is the wall-clock seconds one input may take: on a loaded machine a
# few seconds of waiting for a core is no hang (an input of 0.13 s CPU time took 13 s at nice 19).
# Prints executions, coverage and findings per target; exits 1 when any target found something.
set -u
build=${1:?usage: RunFuzz.sh BUILD_DIR SECONDS [TARGET...]}
seconds=${2:?usage: RunFuzz.sh BUILD_DIR SECONDS [TARGET...]}
shift 2
src=$(cd "$(dirname "$0")" && pwd)
targets=${*:-scene gmsh legacy_vtk vtu tetgen surface}
# one thread (an OpenMP pool per input is wasted work here); LSan, UBSan and the suppressions of
# tests/sanitizer (docs/robustness.md)
export OMP_NUM_THREADS=1
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1:symbolize=1}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1:suppressions=$src/../sanitizer/ubsan.supp}"
export LSAN_OPTIONS="${LSAN_OPTIONS:-suppressions=$src/../sanitizer/lsan.supp:print_suppressions=0}"
status=0
summary=""
for t in $targets; do
  exe=$build/bin/fuzz/fuzz_$t
  if [ ! -x "$exe" ]; then
    echo "no fuzz target $exe (configure with -DFASCIA_FUZZ=ON and build)" >&2
    exit 2
  fi
  mkdir -p "$build/corpus/$t" "$build/findings/$t" "$build/logs"
  log=$build/logs/$t.log
  regressions=""
  [ -d "$src/regressions/$t" ] && regressions="$src/regressions/$t"
  echo "fuzzing $t for $seconds s (log: $log)"
  start=$(date +%s)
  "$exe" -max_total_time="$seconds" -timeout="${FUZZ_TIMEOUT:-30}" -rss_limit_mb=2048 -malloc_limit_mb=1024 -max_len=65536 \
         -dict="$src/dict/$t.dict" -artifact_prefix="$build/findings/$t/" -print_final_stats=1 \
         "$build/corpus/$t" "$src/corpus/$t" $regressions > "$log" 2>&1
  rc=$?
  took=$(( $(date +%s) - start ))  # less than SECONDS when a finding stopped it
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -n 1)
  cov=$(grep -o 'cov: [0-9]*' "$log" | tail -n 1 | sed 's/cov: //')
  found=$(find "$build/findings/$t" -type f \( -name 'crash-*' -o -name 'leak-*' -o -name 'timeout-*' -o -name 'oom-*' \) | wc -l)
  line=$(printf '%-11s %6s s  %10s execs  cov %6s  findings %s (exit %s)' "$t" "$took" "${execs:-?}" "${cov:-?}" "$found" "$rc")
  echo "$line"
  summary="$summary$line\n"
  if [ "$rc" -ne 0 ] || [ "$found" -ne 0 ]; then
    status=1
    grep -m 3 -E 'ERROR: |FINDING|runtime error' "$log" | sed 's/^/    /'
  fi
done
echo "--- fuzz summary ---"
printf "$summary"
[ $status -eq 0 ] || echo "findings are in $build/findings/<target>/; logs in $build/logs/"
exit $status
