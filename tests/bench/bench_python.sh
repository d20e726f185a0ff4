#!/usr/bin/env bash
# The fracarm Python package (issue 20): call overhead of a libfrac step over
# a 1e5-sample numpy array against the plain C loop (python/tests/cdriver.c,
# same step, same input; goal <= 1.2x), and fleet gap diagnosis throughput on
# a LocalCluster with 1 and 2 worker processes (goal >= 1.8x with 2) plus
# the scheduler's overhead per task. Settings: tests/bench/bench_python.py.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
venv="$FRAC_BUILD/pyvenv-fracarm"
bash "$FRAC_SRC/python/scripts/setup_venv.sh" "$venv" "$FRAC_BUILD/python" > /dev/null
FRAC_SOURCE_DIR="$FRAC_SRC" FRAC_BINARY_DIR="$FRAC_BUILD" "$venv/bin/python" "$here/bench_python.py" \
  "$FRAC_BUILD/python/fracarm_cdriver"
