#!/usr/bin/env bash
# The node executables as separate processes on the UDP loopback bus, the
# controller pacing in lockstep, must reproduce the in-process lockstep bench
# exactly: same controller signals cycle by cycle, same number of frames, and
# the logger's log holds every frame the nodes sent; the same through the
# one-line launcher hil_bench --processes, truth columns included.
# usage: udp_lockstep_matches_bench.sh BUILD_DIR WORK_DIR SCENARIO [SCENARIO2...]
# (SCENARIO2...: more scenarios for the hil_bench --processes comparison)
set -euo pipefail
bin=$(cd "${1:?usage: udp_lockstep_matches_bench.sh BUILD_DIR WORK_DIR SCENARIO}" && pwd)/hil
work=${2:?}
scen=${3:?}
rm -rf "$work"
mkdir -p "$work"
port=$((40000 + ($$ % 1000) * 8)) # disjoint from test_hil_udp (20000..36000)
bus() { echo "udp:$port:$1:5"; }
"$bin/hil_candump" --bus "$(bus 4)" --out "$work/frames.log" --idle-exit 1 2> "$work/candump.txt" &
# the logger opens its log once its socket is bound: start the nodes (whose
# boot-up heartbeats are the first frames) only then, not after a fixed sleep
# that a loaded machine can outrun
for _ in $(seq 200); do [ -e "$work/frames.log" ] && break; sleep 0.05; done
[ -e "$work/frames.log" ] || { echo "FAIL: hil_candump did not start within 10 s"; exit 1; }
"$bin/hil_plant" --bus "$(bus 1)" --scenario "$scen" --idle-exit 1 > "$work/plant.txt" &
"$bin/hil_drive" --bus "$(bus 2)" --scenario "$scen" --idle-exit 1 > "$work/drive.txt" &
"$bin/hil_imu" --bus "$(bus 3)" --scenario "$scen" --idle-exit 1 > "$work/imu.txt" &
sleep 0.2
"$bin/hil_ctrl" --lockstep --bus "$(bus 0)" --scenario "$scen" --csv "$work/ctrl.csv" > "$work/ctrl.txt"
wait
cat "$work"/ctrl.txt "$work"/drive.txt "$work"/imu.txt "$work"/plant.txt "$work"/candump.txt
"$bin/hil_bench" --scenario "$scen" --out "$work/bench"
status=0
sent=$(cat "$work"/ctrl.txt "$work"/drive.txt "$work"/imu.txt "$work"/plant.txt |
       sed -n 's/^HIL_STATS .* tx=\([0-9]*\) .*/\1/p' | awk '{ s += $1 } END { print s }')
logged=$(sed -n 's/.*logged=\([0-9]*\).*/\1/p' "$work/candump.txt")
lines=$(wc -l < "$work/frames.log")
bench=$(/usr/bin/python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["counts"]["frames_logged"])' "$work/bench/meta.json")
echo "frames: sent by the node processes $sent, logged $logged ($lines lines), in-process bench $bench"
[ "$sent" = "$logged" ] && [ "$logged" = "$lines" ] || { echo "FAIL: log does not hold every frame sent"; status=1; }
[ "$logged" = "$bench" ] || { echo "FAIL: frame count differs from the in-process bench"; status=1; }
if ! diff <(cut -d, -f1-8 "$work/ctrl.csv") <(cut -d, -f1-6,10,11 "$work/bench/signals.csv" | sed '1s/.*/t,ref,torque_cmd,motor_angle,motor_velocity,imu_rate,fault,run/') > "$work/diff.txt"; then
  echo "FAIL: controller signals differ from the in-process bench:"; head -n 10 "$work/diff.txt"; status=1
else
  echo "controller signals identical to the in-process bench ($(($(wc -l < "$work/ctrl.csv") - 1)) cycles)"
fi
grep -q 'step_timeouts=0' "$work/ctrl.txt" || { echo "FAIL: a lockstep wait timed out"; status=1; }
# The one-line launcher: hil_bench --processes writes the same signals.csv as
# the in-process bench (truth from the plant process joined row by row); the
# drive's torque travels as float32 to the plant, so that column agrees to 1e-4.
for extra in "$scen" "${@:4}"; do
  [ -n "$extra" ] || continue
  name=$(basename "$extra" .txt)
  "$bin/hil_bench" --processes --scenario "$extra" --out "$work/procs-$name" > /dev/null
  "$bin/hil_bench" --scenario "$extra" --out "$work/bench-$name" > /dev/null
  if ! diff <(cut -d, -f1-8,10,11 "$work/procs-$name/signals.csv") <(cut -d, -f1-8,10,11 "$work/bench-$name/signals.csv") > "$work/diff-$name.txt"; then
    echo "FAIL: $name: hil_bench --processes signals differ from the in-process bench:"; head -n 10 "$work/diff-$name.txt"; status=1
  elif ! paste -d, <(cut -d, -f9 "$work/procs-$name/signals.csv") <(cut -d, -f9 "$work/bench-$name/signals.csv") |
       awk -F, 'NR > 1 && ($1 - $2 > 1e-4 || $2 - $1 > 1e-4) { bad = 1 } END { exit bad }'; then
    echo "FAIL: $name: torque_actual differs by more than 1e-4 Nm"; status=1
  else
    echo "$name: hil_bench --processes signals.csv (controller view and truth) identical to the in-process bench"
  fi
done
exit $status
