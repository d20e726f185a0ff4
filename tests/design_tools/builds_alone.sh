#!/usr/bin/env bash
# design_tools builds and installs without plc_blocks and hil (ARCHITECTURE.md:
# "design_tools never includes or links plc_blocks or hil"). Configures the
# source tree with FRAC_DESIGN_ONLY=ON (libfrac + design_tools only) into
# BINDIR and fails when
#   - the configure fails (design_tools asks for a target it does not own),
#   - a hil, plc_blocks or bench target exists there,
#   - the compile flags of fracdesign_core / fracdesign name a hil, plc_blocks
#     or bench include directory (so no such header can be included), or
#     their link lines name a hil, plc or bench library,
#   - a design_tools source includes a hil, plc_blocks or bench header.
# With FRAC_BUILD_ALONE=1 it also builds that tree (libfrac, fracdesign) and
# installs it.
# usage: builds_alone.sh SOURCE_DIR BINDIR
set -euo pipefail
src=$1 bin=$2
fail() { echo "design_tools_builds_alone: $*" >&2; exit 1; }
rm -rf "$bin"
extra=()
[ -n "${CMAKE_CXX_COMPILER_LAUNCHER:-}" ] && extra+=("-DCMAKE_CXX_COMPILER_LAUNCHER=$CMAKE_CXX_COMPILER_LAUNCHER")
cmake -S "$src" -B "$bin" -DFRAC_DESIGN_ONLY=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo "${extra[@]}" > "$bin.configure.log" 2>&1 \
  || { cat "$bin.configure.log" >&2; fail "configure of libfrac + design_tools alone failed"; }
targets=$(cmake --build "$bin" --target help)
echo "$targets" | grep -q 'fracdesign_core' || fail "no fracdesign_core target in the design-only tree"
if echo "$targets" | grep -Eq '(hil|plc|bench)'; then fail "hil/plc/bench targets in the design-only tree: $(echo "$targets" | grep -E '(hil|plc|bench)' | tr '\n' ' ')"; fi
for t in fracdesign_core fracdesign; do
  d="$bin/design_tools/CMakeFiles/$t.dir"
  [ -f "$d/flags.make" ] || fail "no $d/flags.make (generator not Unix Makefiles?)"
  if grep -Eq -- "-I[^ ]*/(hil|plc_blocks|bench)/" "$d/flags.make"; then fail "$t compiles with a hil/plc_blocks/bench include directory"; fi
  if [ -f "$d/link.txt" ] && grep -Eq '(hil|plc|bench)' "$d/link.txt"; then fail "$t links a hil/plc/bench library: $(cat "$d/link.txt")"; fi
done
if grep -rEn '#[[:space:]]*include[[:space:]]*[<"](hil/|fracbench/|plctypes\.h|FracCtrl\.h|plc_)' "$src/design_tools"; then
  fail "a design_tools source includes a hil/plc_blocks/bench header (above)"
fi
if [ "${FRAC_BUILD_ALONE:-0}" = 1 ]; then
  cmake --build "$bin" -j 2 > "$bin.build.log" 2>&1 || { tail -30 "$bin.build.log" >&2; fail "build failed"; }
  cmake --install "$bin" --prefix "$bin/prefix" > /dev/null || fail "install failed"
  "$bin/prefix/bin/fracdesign" --help > /dev/null || fail "the installed fracdesign does not run"
fi
echo "design_tools_builds_alone: libfrac + design_tools configure alone; no hil/plc/bench target, include directory, library or header"
