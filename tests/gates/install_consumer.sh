#!/usr/bin/env bash
# Installs the build into a scratch prefix, then builds and runs a consumer
# (a) with find_package(frac) (shared and static targets) and (b) with
# pkg-config --cflags --libs frac, as a downstream user would.
# usage: install_consumer.sh BUILD_DIR WORK_DIR SOURCE_DIR
set -euo pipefail
build=$1; work=$2; src=$3
rm -rf "$work"; mkdir -p "$work"
prefix=$work/prefix
cmake --install "$build" --prefix "$prefix" > "$work/install.log"
cmake -S "$src/tests/gates/consumer" -B "$work/cmake" -DCMAKE_PREFIX_PATH="$prefix" > "$work/configure.log"
cmake --build "$work/cmake" > "$work/build.log"
"$work/cmake/consumer_static"
LD_LIBRARY_PATH="$prefix/lib:${LD_LIBRARY_PATH:-}" "$work/cmake/consumer_shared"
pc=$(find "$prefix" -name frac.pc | head -1)
[ -n "$pc" ] || { echo "no frac.pc installed"; exit 1; }
export PKG_CONFIG_PATH=$(dirname "$pc")
cc $(pkg-config --cflags frac) "$src/tests/gates/consumer/main.c" -o "$work/consumer_pc" $(pkg-config --libs frac) -lm
LD_LIBRARY_PATH="$(pkg-config --variable=libdir frac)" "$work/consumer_pc"
echo "PASS: find_package(frac) and pkg-config frac consumers built and ran"
