#!/usr/bin/env bash
# 1-D LUT lookup, 4096 knots, linear: frac_lut1_eval vs a textbook
# reference (floor index / bisection from scratch). Goals (issue 4):
# <= 50 instructions uniform, <= 120 non-uniform.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
. "$here/lib.sh"
bin="$FRAC_BENCH_BIN/bench_lut"
calls=4096
printf '%-44s %12s %12s %8s %9s %9s\n' "case" "frac Ir/call" "ref Ir/call" "ratio" "frac ns" "ref ns"
for mode in uniform nonuniform sequential; do
  case $mode in
    uniform) ref=ref_lut_uniform; label="uniform, random queries (goal 50)";;
    nonuniform) ref=ref_lut_nonuniform; label="breakpoints, random queries (goal 120)";;
    sequential) ref=ref_lut_nonuniform; label="breakpoints, sequential (cached segment)";;
  esac
  fi=$(callgrind_ir frac_lut1_eval "$bin" frac "$mode" "$calls")
  ri=$(callgrind_ir "$ref" "$bin" ref "$mode" "$calls")
  fpc=$(awk -v a="$fi" -v c="$calls" 'BEGIN{printf "%.1f", a/c}')
  rpc=$(awk -v a="$ri" -v c="$calls" 'BEGIN{printf "%.1f", a/c}')
  fns=$("$bin" frac "$mode" 20000000 time)
  rns=$("$bin" ref "$mode" 20000000 time)
  printf '%-44s %12s %12s %8s %9s %9s\n' "$label" "$fpc" "$rpc" "$(ratio "$fpc" "$rpc")" "$fns" "$rns"
done
