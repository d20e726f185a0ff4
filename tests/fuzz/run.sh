#!/usr/bin/env bash
# Runs every fuzz target of a FRAC_FUZZ build for a bounded time and prints
# one line per target: seconds, executions, executions/s, corpus entries,
# findings. usage: run.sh BUILD_DIR SECONDS_PER_TARGET
# Seeds: tests/fuzz/corpus/<name>/ (read only); what the fuzzer adds goes to
# BUILD_DIR/fuzz-corpus/<name>/, crashes to BUILD_DIR/fuzz-findings/<name>-*.
# Exit 1 when a target finds anything (the reproducer's path is printed).
set -uo pipefail
build=${1:?usage: run.sh BUILD_DIR SECONDS}
secs=${2:?usage: run.sh BUILD_DIR SECONDS}
src=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$build/fuzz-findings"
rc=0
printf '%-22s %6s %12s %10s %8s %s\n' target seconds executions exec/s corpus findings
for f in "$src"/fuzz_*.c "$src"/fuzz_*.cpp; do
  [ -e "$f" ] || continue
  t=$(basename "${f%.*}")
  name=${t#fuzz_}
  exe="$build/tests/fuzz/$t"
  seeds="$src/corpus/$name"
  work="$build/fuzz-corpus/$name"
  if [ ! -x "$exe" ]; then echo "$t: not built ($exe)"; rc=1; continue; fi
  if [ ! -d "$seeds" ]; then echo "$t: no seed corpus $seeds"; rc=1; continue; fi
  mkdir -p "$work"
  log="$build/fuzz-findings/$t.log"
  # findings of an earlier run were reported by it; this run counts its own
  rm -f "$build/fuzz-findings/$t"-*
  ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    "$exe" -max_total_time="$secs" -print_final_stats=1 -timeout=10 -rss_limit_mb=2048 \
    -artifact_prefix="$build/fuzz-findings/$t-" "$work" "$seeds" > "$log" 2>&1
  st=$?
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log" | tail -1)
  n=$(find "$work" -type f | wc -l)
  found=$(find "$build/fuzz-findings" -name "$t-*" -type f | wc -l)
  printf '%-22s %6s %12s %10s %8s %s\n' "$t" "$secs" "${execs:-?}" "${rate:-?}" "$n" "$found"
  if [ "$st" -ne 0 ] || [ "$found" -ne 0 ]; then
    rc=1
    echo "  $t failed (exit $st); log $log:"
    grep -E "ERROR|SUMMARY|runtime error|Test unit written|deadly signal" "$log" | head -8 | sed 's/^/    /'
  fi
done
exit $rc
