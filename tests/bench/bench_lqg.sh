#!/usr/bin/env bash
# Predictor step + LQG law (frac_lqg_step) vs the same step with Eigen
# dynamic matrices (ref_eigen_lqg_step), Exp. D and unreduced sizes.
# Goals (issue 4): <= 3,000 instructions (Exp. D), <= 10,000 (unreduced).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
. "$here/lib.sh"
bin="$FRAC_BENCH_BIN/bench_lqg"
calls=2000
printf '%-34s %12s %12s %8s %10s %10s\n' "case" "frac Ir/call" "Eigen Ir/call" "ratio" "frac ns" "Eigen ns"
for size in expd full; do
  fi=$(callgrind_ir frac_lqg_step "$bin" frac "$size" "$calls")
  ei=$(callgrind_ir ref_eigen_lqg_step "$bin" eigen "$size" "$calls")
  fpc=$(awk -v a="$fi" -v c="$calls" 'BEGIN{printf "%.0f", a/c}')
  epc=$(awk -v a="$ei" -v c="$calls" 'BEGIN{printf "%.0f", a/c}')
  fns=$("$bin" frac "$size" 2000000 time)
  ens=$("$bin" eigen "$size" 2000000 time)
  case $size in
    expd) label="Exp. D 23+1 states, p=3 (goal 3000)";;
    full) label="unreduced 36+4+7+1, p=3 (goal 10000)";;
  esac
  printf '%-34s %12s %12s %8s %10s %10s\n' "$label" "$fpc" "$epc" "$(ratio "$fpc" "$epc")" "$fns" "$ens"
done
