#!/usr/bin/env bash
# make bench: builds the benchmark executables in BUILD and runs every
# tests/bench/bench_*.sh in name order. Each script prints one table per
# benchmark with the project's figure, the reference's figure measured in the
# same run, and their ratio.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
build=$(cd "${1:?usage: run.sh BUILD_DIR}" && pwd)
cmake --build "$build" --target benchmarks -j "$(nproc)"
export FRAC_BENCH_BIN="$build/tests/bench" FRAC_BUILD="$build" FRAC_SRC=$(cd "$here/../.." && pwd)
export PY=${PY:-/usr/bin/python3}
n=0
for s in "$here"/bench_*.sh; do
  [ -e "$s" ] || continue
  echo; echo "=== $(basename "$s" .sh) ==="
  bash "$s"
  n=$((n+1))
done
echo; echo "bench: $n benchmark scripts run"
