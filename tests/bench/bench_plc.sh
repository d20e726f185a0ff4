#!/usr/bin/env bash
# plc_blocks: callgrind instructions per Cyclic #1 cycle of ArmCtrl for each
# variant (issue 8 goal: Exp. D <= 6,000), and the block-call overhead: the
# inclusive count of each FracCtrl block per call against the libfrac call
# it wraps, measured in the same run (goal <= 10 %).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
. "$here/lib.sh"
bin="$FRAC_BENCH_BIN/bench_plc"
cycles=2000
printf '%-28s %14s %14s %8s\n' "ArmCtrl variant" "Ir/cycle" "goal" "ratio"
for v in A B C D; do
  ir=$(callgrind_ir armctrl_cyclic "$bin" armctrl "$v" "$cycles")
  pc=$(awk -v a="$ir" -v c="$cycles" 'BEGIN{printf "%.0f", a/c}')
  printf '%-28s %14s %14s %8s\n' "Exp. $v" "$pc" "6000" "$(ratio "$pc" 6000)"
done
echo "goal applies to Exp. D (Table 8.8 sizes: n = 16, d_i = 4, d_o = 3); ratio = Ir/cycle / 6000"
echo
printf '%-40s %14s %14s %8s %10s\n' "block (per call)" "block Ir" "libfrac Ir" "ratio" "overhead"
for pair in "lqg LQGDelay frac_lqg_step" "trajlut TrajLUT frac_trajlut_step" \
            "fracop FracOp frac_fo_step" "lut1d LUT1D frac_lut1_eval" \
            "friction FrictionComp frac_friction_eval"; do
  set -- $pair
  # 2N calls minus N calls: the first call (Enable edge, parameter
  # validation over the whole table) drops out of the per-call figure
  b2=$(callgrind_ir "$2" "$bin" block "$1" $((2 * cycles)))
  b1=$(callgrind_ir "$2" "$bin" block "$1" "$cycles")
  d2=$(callgrind_ir "$3" "$bin" block "$1" $((2 * cycles)))
  d1=$(callgrind_ir "$3" "$bin" block "$1" "$cycles")
  bp=$(awk -v a="$b2" -v b="$b1" -v c="$cycles" 'BEGIN{printf "%.0f", (a-b)/c}')
  dp=$(awk -v a="$d2" -v b="$d1" -v c="$cycles" 'BEGIN{printf "%.0f", (a-b)/c}')
  printf '%-40s %14s %14s %8s %10s\n' "$2 / $3" "$bp" "$dp" "$(ratio "$bp" "$dp")" "$((bp - dp))"
  eval "blk_$1=$bp; dir_$1=$dp"
done
# The Exp. D cycle wraps frac_lqg_step and frac_trajlut_step in blocks: the
# interface cost of both, relative to the libfrac work they wrap.
printf '%-40s %14s %14s %8s %10s\n' "Exp. D cycle: LQGDelay + TrajLUT" "$((blk_lqg + blk_trajlut))" \
  "$((dir_lqg + dir_trajlut))" "$(ratio $((blk_lqg + blk_trajlut)) $((dir_lqg + dir_trajlut)))" \
  "$((blk_lqg + blk_trajlut - dir_lqg - dir_trajlut))"
echo "ratio = block / direct libfrac call on the same inputs; goal <= 1.10"
echo "overhead = block Ir - libfrac Ir per call: the PLCopen interface (steady-state test, REAL <-> frac_real"
echo "conversions of the pins, status check, call frame): 23-27 Ir for a one-input block, more with more pins;"
echo "against a libfrac call of 45 (LUT1D) to 160 (FrictionComp) instructions no ratio of 1.10 is reachable"
