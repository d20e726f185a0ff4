#!/usr/bin/env bash
# Antenna FRF identification (seed 000): all 6 structures x 2 weightings on one
# noisy FRF (N = 7907), fracdesign (Ceres LM, automatic derivatives) vs
# scipy.optimize.least_squares (TRF) on the same residual, the same bounds
# and the same start points, in the same run. Goal: >= 5x faster at an equal
# or better cost J (eq. 26) per fit.
set -euo pipefail
tmp=$(mktemp -d /tmp/bench_ident.XXXXXX)
trap 'rm -rf "$tmp"' EXIT
starts=${IDENT_STARTS:-4}
"$FRAC_BENCH_BIN/bench_ident" "$starts" "$tmp" > "$tmp/ours.txt"
"$PY" "$FRAC_SRC/tests/bench/bench_ident_ref.py" "$tmp" > "$tmp/ref.txt"
printf "%-5s %-6s %16s %16s %10s %10s %7s %s\n" type weight J_fracdesign J_scipy cpu_fd_s cpu_scipy_s ratio cost
paste -d' ' "$tmp/ours.txt" "$tmp/ref.txt" | awk '
  $1 == "total" { tf = $2; ts = $4; next }
  { ratio = ($4 > 0) ? $8 / $4 : 0
    verdict = ($3 <= $7 * (1 + 1e-9)) ? "equal/better" : "WORSE"
    printf "%-5s %-6s %16.10g %16.10g %10.3f %10.3f %6.2fx %s\n", $1, $2, $3, $7, $4, $8, ratio, verdict }
  END { printf "%-5s %-6s %16s %16s %10.3f %10.3f %6.2fx\n", "all", "", "", "", tf, ts, ts / tf }'
echo "times are process CPU seconds; ratio = scipy time / fracdesign time (> 1: fracdesign faster); $starts starts per fit; goal >= 5x at equal or better J"
