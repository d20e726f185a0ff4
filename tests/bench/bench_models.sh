#!/usr/bin/env bash
# Seed 004 model construction (issue 5). Goal: N = 9 build + Krylov reduce + couple <= 20 ms.
# Reference (same run): build + dense eigendecomposition with eigenvectors of the 4N-state model, the
# core of a modal truncation to the same order (the alternative the thesis compares Krylov with).
# Times are medians of repeated runs (wall clock, microseconds).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
. "$here/lib.sh"
bin="$FRAC_BENCH_BIN/bench_models"
printf '%-44s %14s %16s %8s\n' "case" "project us" "reference us" "ratio"
for N in 9 20 40 80; do
  reps=21; [ "$N" -ge 80 ] && reps=5
  p=$("$bin" arm "$N" "$reps")
  r=$("$bin" modal "$N" "$reps")
  label="N = $N build + Krylov r=12 + couple"
  [ "$N" = 9 ] && label="$label (goal 20000)"
  printf '%-44s %14s %16s %8s\n' "$label" "$p" "$r" "$(ratio "$p" "$r")"
done
p=$("$bin" table31 5)
r=$("$bin" table31ref 5)
printf '%-44s %14s %16s %8s\n' "Table 3.1 (6 spectra) + Table C.1" "$p" "$r" "$(ratio "$p" "$r")"
