# Helpers for bench_*.sh scripts (sourced).
# callgrind_ir FUNC CMD... : inclusive instruction count (Ir) of every call to
# the C function FUNC while running CMD, summed over calls. Stable across runs
# (instruction counts, not time), so it is the figure the goals are set in.
callgrind_ir() {
  local fn=$1; shift
  local out; out=$(mktemp /tmp/cg.XXXXXX)
  valgrind --tool=callgrind --callgrind-out-file="$out" --collect-atstart=no \
    --toggle-collect="$fn" "$@" >/dev/null 2>&1
  callgrind_annotate "$out" 2>/dev/null | awk '/PROGRAM TOTALS/{gsub(",","",$1); print $1; exit}'
  rm -f "$out"
}
# ratio A B : A/B with 2 decimals.
ratio() { awk -v a="$1" -v b="$2" 'BEGIN{ if (b==0) print "n/a"; else printf "%.2f", a/b }'; }
