#!/usr/bin/env bash
# One arm document through every stage (issue 16): model + reduced model, LQG on the unreduced arm
# with the document's delays, ArmCtrl tables (inverse-model and rigid-body feedforward) for MOVE, the
# HIL plant table and scenario, the rig with each table, a rig run of GAP_MOVE with Coulomb friction
# withheld from the nominal, and the gap diagnosis against the document's gap nominal. Every bound is
# derived from the design by arm_chain_check.py; nothing here is specific to one arm.
#   arm_document_chain.sh FRACDESIGN HIL_BENCH ARM.json MOVE GAP_MOVE OUTDIR
set -euo pipefail
fd=$1 bench=$2 arm=$3 move=$4 gap_move=$5 out=$6
here=$(cd "$(dirname "$0")" && pwd)
rm -rf "$out"; mkdir -p "$out"; cd "$out"
"$fd" model --arm "$arm" --json --save-plant plant.bin --gap-nominal nominal.json \
  --save-scenario scenario.txt --plant-table plant.bin --ctrl-table ctrl_inverse.bin --duration 4.0 > model.json
"$fd" lqg --arm "$arm" --json > lqg.json
"$fd" armctrl --arm "$arm" --move "$move" --post 1.0 --ff inverse --out ctrl_inverse.bin --json > armctrl_inverse.json
"$fd" armctrl --arm "$arm" --move "$move" --post 1.0 --ff rigid --out ctrl_rigid.bin --json > armctrl_rigid.json
"$fd" table check ctrl_inverse.bin > table_check.txt
"$bench" --scenario scenario.txt --out run_inverse > run_inverse.txt
"$bench" --scenario scenario.txt --set ctrl.table=ctrl_rigid.bin --out run_rigid > run_rigid.txt
# the withheld effect: Coulomb friction of 10 % of the rated torque (tanh(60 v) in the plant)
rated=$(sed -n 's/^drive.torque_rated = //p' scenario.txt)
fc=$(/usr/bin/python3 -c "print(0.1 * float('$rated'))")
"$fd" armctrl --arm "$arm" --move "$gap_move" --post 0.5 --ff inverse --out ctrl_gap.bin > /dev/null
"$bench" --scenario scenario.txt --set ctrl.table=ctrl_gap.bin --set plant.fric_b0="$fc" --out run_gap > run_gap.txt
"$fd" gap --model nominal.json --data run_gap/signals.csv --out gap > gap.txt
/usr/bin/python3 "$here/arm_chain_check.py" "$arm" "$move" "$fc" .
