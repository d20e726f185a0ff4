#!/usr/bin/env bash
# Gap diagnosis speed (issue 10): a 10 s, 1 kHz, 3-output record with all
# candidates against the 30 s goal, and the growth with record length and
# number of candidates. Driven by bench_gap (tests/bench/bench_gap.cpp).
set -euo pipefail
"$FRAC_BENCH_BIN/bench_gap"
