#!/usr/bin/env bash
# DARE at the Exp. D size (24 states) and the unreduced size (48): the Kalman-filter
# Riccati equation of the seed 004 Exp. D design (reduced and unreduced arm);
# fracdesign's structured doubling vs scipy.linalg.solve_discrete_are, same matrices, same run.
# Residuals of both solutions are computed by the same numpy formula.
set -euo pipefail
tmp=$(mktemp -d /tmp/bench_dare.XXXXXX)
trap 'rm -rf "$tmp"' EXIT
reps=${DARE_REPS:-50}
printf "%-6s %14s %14s %7s %14s %14s %6s\n" "n" "fracdesign_us" "scipy_us" "ratio" "res_fracdesign" "res_scipy" "iters"
for n in 24 48; do
  read -r _ t_f _ it _ < <("$FRAC_BENCH_BIN/bench_dare" "$n" "$reps" "$tmp")
  read -r t_s r_s r_f < <("$PY" "$FRAC_SRC/tests/bench/bench_dare_ref.py" "$n" "$reps" "$tmp")
  ratio=$(awk -v a="$t_s" -v b="$t_f" 'BEGIN{printf "%.2f", a/b}')
  printf "%-6s %14s %14s %7s %14s %14s %6s\n" "$n" "$t_f" "$t_s" "${ratio}x" "$r_f" "$r_s" "$it"
done
echo "ratio = scipy time / fracdesign time (> 1: fracdesign faster); goal: faster at an equal or smaller residual"
