#!/usr/bin/env bash
# Replay cost per sample of each gap controller kind (issue 21 item 4), the
# linear statespace law as the reference; and each kind's step against the
# direct libfrac calls of its PLC block. Driven by bench_gap_controllers
# (tests/bench/bench_gap_controllers.cpp).
set -euo pipefail
"$FRAC_BENCH_BIN/bench_gap_controllers"
