#!/usr/bin/env bash
# Fractional operators and the PI^l D^m (issue 3): per-sample cost in ns
# and callgrind instructions, GL cost per memory tap, libfrac's biquad
# cascade against scipy.signal.sosfilt on the same 1e6-sample input, and
# the naive direct form of the same transfer function (cost and error).
# Goals: Oustaloup N = 5 <= 150 instructions/sample; GL <= 3 instructions
# per memory tap. Settings: tests/bench/bench_fo.c header.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
source "$here/lib.sh"
B="$FRAC_BENCH_BIN/bench_fo"
tmp=$(mktemp -d /tmp/bench_fo.XXXXXX)
trap 'rm -rf "$tmp"' EXIT
N=20000

declare -A NS IR
while read -r kind ns _; do NS[$kind]=$ns; done < <("$B" time)
fn_of() { case $1 in pid) echo frac_fopid_step ;; naive) echo naive_step ;; *) echo frac_fo_step ;; esac; }
for kind in oustaloup5 gl256 gl1024 gl4096 cfe5 pid naive; do
  ir=$(callgrind_ir "$(fn_of $kind)" "$B" run $kind $N)
  IR[$kind]=$(awk -v a="$ir" -v n=$N 'BEGIN{printf "%.1f", a/n}')
done
ir_os=$(callgrind_ir frac_sos_step "$B" run oustaloup5 $N)
ir_os=$(awk -v a="$ir_os" -v n=$N 'BEGIN{printf "%.1f", a/n}')
slope=$(awk -v a="${IR[gl256]}" -v b="${IR[gl4096]}" 'BEGIN{printf "%.3f", (b-a)/(4096-256)}')
mid=$(awk -v a="${IR[gl256]}" -v b="${IR[gl4096]}" -v c="${IR[gl1024]}" 'BEGIN{p=a+(b-a)*(1024-256)/(4096-256); printf "%.2f", 100*(c-p)/p}')

echo "per-sample cost (r = 0.5, Ts = 1 ms; Release build)"
printf "  %-34s %10s %14s  %s\n" "realization" "ns/sample" "instr/sample" "goal"
printf "  %-34s %10s %14s  %s\n" "Oustaloup N = 5 (fo_op front)" "${NS[oustaloup5]}" "${IR[oustaloup5]}" \
  "<= 150: $(awk -v a="${IR[oustaloup5]}" 'BEGIN{print (a<=150)?"met":"NOT met"}')"
printf "  %-34s %10s %14s\n" "  of which frac_sos_step (6 biquads)" "" "$ir_os"
for L in 256 1024 4096; do
  printf "  %-34s %10s %14s\n" "Grünwald–Letnikov L = $L" "${NS[gl$L]}" "${IR[gl$L]}"
done
printf "  %-34s %10s %14s  %s\n" "  GL per memory tap (slope)" "" "$slope" \
  "<= 3: $(awk -v a="$slope" 'BEGIN{print (a<=3)?"met":"NOT met"}'); L = 1024 off the line by ${mid} %"
printf "  %-34s %10s %14s\n" "CFE Tustin n = 5" "${NS[cfe5]}" "${IR[cfe5]}"
printf "  %-34s %10s %14s\n" "PI^0.8 D^0.5 (Oustaloup N = 5 x2)" "${NS[pid]}" "${IR[pid]}"
printf "  %-34s %10s %14s\n" "naive direct form, order 12" "${NS[naive]}" "${IR[naive]}"

"$B" input "$tmp/x.f64"
"$B" sos "$tmp/sos.txt"
lib_ns=$("$B" filter "$tmp/x.f64" "$tmp/y.f64")
declare -A R
while IFS='=' read -r k v; do R[$k]=$v; done < <("$PY" "$here/bench_fo_ref.py" "$tmp/x.f64" "$tmp/sos.txt" "$tmp/y.f64")
read -r _ nerr nerr32 < <("$B" naive)
echo
echo "Oustaloup N = 5 cascade on the same 1e6-sample input: libfrac vs scipy.signal.sosfilt"
printf "  %-34s %10s ns/sample  (%s Msamples/s)\n" "libfrac frac_sos_process" "$lib_ns" "$(awk -v a="$lib_ns" 'BEGIN{printf "%.1f", 1000/a}')"
printf "  %-34s %10s ns/sample  (%s Msamples/s)\n" "scipy.signal.sosfilt" "${R[sosfilt_ns]}" "$(awk -v a="${R[sosfilt_ns]}" 'BEGIN{printf "%.1f", 1000/a}')"
printf "  %-34s %10s x\n" "throughput ratio libfrac/scipy" "$(ratio "${R[sosfilt_ns]}" "$lib_ns")"
printf "  %-34s %10s (max |diff| / max |y|)\n" "outputs agree to" "${R[sosfilt_vs_libfrac]}"
echo
echo "naive direct form of the same transfer function (order ${R[direct_order]}, largest pole |z| = ${R[direct_max_pole]})"
printf "  %-34s %10s ns/sample (libfrac C), %s ns/sample (scipy lfilter)\n" "cost" "${NS[naive]}" "${R[direct_ns]}"
printf "  %-34s %10s (libfrac C), %s (scipy lfilter)\n" "error vs cascade, double" "$nerr" "${R[direct_err]}"
printf "  %-34s %10s (libfrac C), %s (scipy lfilter)\n" "error vs cascade, float32" "$nerr32" "${R[direct_err_f32]}"
printf "  %-34s %10s (scipy sosfilt in float32)\n" "cascade itself in float32" "${R[sos_err_f32]}"
