#!/usr/bin/env bash
# HIL rig benchmarks (issue 9):
#  1. lockstep speed, simulated seconds per wall second: the in-process bench
#     (hil_bench) against the same scenario with every node as its own process
#     on the UDP loopback bus (hil_bench --processes), measured in this run;
#  2. real-time jitter at T = 1.2 ms on the UDP loopback transport: the
#     controller's SYNC lateness p50/p99/max (hil_bench --realtime) against a
#     bare clock_nanosleep loop at the same period (tests/hil/hil_sleep_ref.c),
#     with normal scheduling and with SCHED_FIFO priority 50.
#  3. lockstep speed with the flexible arm (plant = arm, full order, N = 9 and
#     N = 20 collocation points: 40 and 84 states, exact ZOH steps of 0.15 ms)
#     under ArmCtrl Exp. D from its table (hil/scenarios/exp_d.txt), against
#     the rigid test plant of 1. in the same run; goal >= 50x real time at
#     N = 9; and the callgrind instructions per simulated second.
#  4. CANopen (issue 18): the controller's boot of both devices by SDO before
#     cycle 0 in the lockstep bench - simulated time as the bus time of its
#     frames at 1 Mbit/s (47 + 8 DLC bits per frame, no stuffing: the
#     in-process bus has no bit timing) and wall time - and an independent
#     master (python canopen over hil_socketcand, tests/hil/canopen_master.py):
#     expedited SDO round trip against the SYNC -> 3 TPDOs cycle on the same
#     transport, and its boot of both devices (wall; simulated time does not
#     advance during a boot: the drive's clock is the master's SYNC).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
. "$here/lib.sh"
build=${FRAC_BUILD:?}
bin=$build/hil
cmake --build "$build" --target hil_apps hil_sleep_ref hil_tables >/dev/null
work=$(mktemp -d /tmp/bench_hil.XXXXXX)
trap 'rm -rf "$work"' EXIT

cat > "$work/speed.txt" <<SCEN
T = 0.0012
duration = 20
plant = rigid
SCEN
speed() { sed -n 's/.*(\([0-9.]*\)x real time).*/\1/p'; }
get() { echo "$1" | tr ' ' '\n' | sed -n "s/^$2=//p"; }
inproc_out=$("$bin/hil_bench" --scenario "$work/speed.txt" --out "$work/a")
inproc=$(echo "$inproc_out" | speed)
sed -i 's/^duration = 20/duration = 2/' "$work/speed.txt"
wall=$("$bin/hil_bench" --processes --scenario "$work/speed.txt" --out "$work/b" |
       sed -n 's/^HIL_JITTER .*wall_s=\([0-9.]*\).*/\1/p')
procs=$(awk -v w="$wall" 'BEGIN { printf "%.1f", 2.0 / w }')
printf '%-52s %12s %12s %8s\n' "lockstep speed [simulated s / wall s]" "hil_bench" "processes" "ratio"
printf '%-52s %12s %12s %8s\n' "rigid test plant, 1.2 ms, full logging (goal >= 50)" "$inproc" "$procs" "$(ratio "$inproc" "$procs")"
# Stable figure: instructions of hil_rig_run per simulated second (callgrind),
# rigid and twomass plants, with and without the logs.
printf 'T = 0.0012\nduration = 1\nplant = rigid\n' > "$work/one.txt"
ir_rigid=$(callgrind_ir hil_rig_run "$bin/hil_bench" --scenario "$work/one.txt" --out "$work/e")
printf 'T = 0.0012\nduration = 1\nplant = twomass\nplant.substeps = 8\nctrl.law = armctrl_a\n' > "$work/two.txt"
ir_two=$(callgrind_ir hil_rig_run "$bin/hil_bench" --scenario "$work/two.txt" --out "$work/f")
printf '%-52s %12s %12s %8s\n' "instructions per simulated second (callgrind)" "rigid+PD" "twomass+ArmCtrl" "ratio"
printf '%-52s %12s %12s %8s\n' "hil_rig_run incl. candump log and CSV" "$ir_rigid" "$ir_two" "$(ratio "$ir_two" "$ir_rigid")"

# The flexible arm (tables made by the build in $bin/tables), Exp. D.
echo
printf '%-52s %12s %12s %8s\n' "lockstep speed, arm + ArmCtrl Exp. D [sim s / wall s]" "arm" "rigid+PD" "ratio"
for N in 9 20; do
  goal=""
  [ $N = 9 ] && goal=" (goal >= 50)"
  arm=$("$bin/hil_bench" --scenario "$FRAC_SRC/hil/scenarios/exp_d.txt" --set plant.table=arm_n$N.bin \
        --set duration=20 --out "$work/g$N" | speed)
  printf '%-52s %12s %12s %8s\n' "N = $N, full logging$goal" "$arm" "$inproc" "$(ratio "$arm" "$inproc")"
done
printf '%-52s %12s %12s %8s\n' "instructions per simulated second (callgrind)" "arm" "rigid+PD" "ratio"
for N in 9 20; do
  ir_arm=$(callgrind_ir hil_rig_run "$bin/hil_bench" --scenario "$FRAC_SRC/hil/scenarios/exp_d.txt" \
           --set plant.table=arm_n$N.bin --set duration=1 --out "$work/h$N")
  printf '%-52s %12s %12s %8s\n' "N = $N, hil_rig_run incl. logs" "$ir_arm" "$ir_rigid" "$(ratio "$ir_arm" "$ir_rigid")"
done

echo
bus_us() { awk -F'#' '/ 080#/ { exit } { n = length($2) / 2; us += 47 + 8 * n } END { printf "%.0f", us }' "$1"; }
boot_frames=$(echo "$inproc_out" | sed -n 's/.*boot by SDO before cycle 0: \([0-9]*\) frames.*/\1/p')
boot_sdo=$(echo "$inproc_out" | sed -n 's/.* \([0-9]*\) SDO requests.*/\1/p')
boot_wall=$(echo "$inproc_out" | sed -n 's/.*SDO requests, \([0-9.]*\) ms wall.*/\1/p')
boot_bus=$(bus_us "$work/a/frames.log")
printf '%-52s %12s %12s %8s\n' "CANopen boot by the controller (lockstep bench)" "simulated" "wall" "ratio"
printf '%-52s %12s %12s %8s\n' "both devices, $boot_frames frames, $boot_sdo SDO transfers [ms]" \
  "$(awk -v u="$boot_bus" 'BEGIN { printf "%.2f", u / 1000 }')" "$boot_wall" "$(ratio "$(awk -v u="$boot_bus" 'BEGIN { printf "%.3f", u / 1000 }')" "$boot_wall")"
printf '%-52s %12s %12s\n' "SDO round trip (2 frames; wall: boot / transfers) [us]" "222" "$(awk -v w="$boot_wall" -v n="$boot_sdo" 'BEGIN { printf "%.2f", 1000 * w / n }')"
bash "$FRAC_SRC/tests/hil/setup_pyvenv.sh" "$build/pyvenv" >/dev/null
master=$("$build/pyvenv/bin/python" "$FRAC_SRC/tests/hil/canopen_master.py" "$bin/hil_socketcand" \
         "$FRAC_SRC/hil/drive.eds" "$FRAC_SRC/hil/imu.eds" 2>/dev/null | sed -n 's/^CANOPEN_MASTER //p')
echo
printf '%-52s %12s %12s %8s\n' "python canopen master over socketcand (TCP loopback)" "SDO" "SYNC->TPDOs" "ratio"
printf '%-52s %12s %12s %8s\n' "round trip, median [us]" "$(get "$master" sdo_round_trip_us_median)" \
  "$(get "$master" cycle_us_median)" "$(ratio "$(get "$master" sdo_round_trip_us_median)" "$(get "$master" cycle_us_median)")"
printf '%-52s %12s\n' "SDO round trip p99 [us]" "$(get "$master" sdo_round_trip_us_p99)"
printf '%-52s %12s\n' "boot of both devices (reset, identity, remap, start) [ms]" "$(get "$master" boot_wall_ms)"

cat > "$work/rt.txt" <<SCEN
T = 0.0012
duration = 3
plant = rigid
SCEN
# normal scheduling, then SCHED_FIFO 50 (hil_bench --rt-priority, chrt for the
# reference); the FIFO row needs the privilege, else it repeats the first.
for sched in normal fifo; do
  if [ $sched = fifo ]; then
    rt=$("$bin/hil_bench" --realtime --rt-priority 50 --scenario "$work/rt.txt" --out "$work/d" | sed -n 's/^HIL_JITTER //p')
    ref=$(chrt -f 50 "$build/tests/hil/hil_sleep_ref" 1200 2500 2>/dev/null || "$build/tests/hil/hil_sleep_ref" 1200 2500)
  else
    rt=$("$bin/hil_bench" --realtime --scenario "$work/rt.txt" --out "$work/c" | sed -n 's/^HIL_JITTER //p')
    ref=$("$build/tests/hil/hil_sleep_ref" 1200 2500)
  fi
  echo
  printf '%-52s %12s %12s %8s\n' "real-time jitter at 1.2 ms, UDP loopback, $sched [us]" "hil_ctrl" "bare sleep" "ratio"
  for q in p50_us p99_us max_us; do
    printf '%-52s %12s %12s %8s\n' "$q (goal p99 <= 100)" "$(get "$rt" "$q")" "$(get "$ref" "$q")" \
      "$(ratio "$(get "$rt" "$q")" "$(get "$ref" "$q")")"
  done
  printf '%-52s %12s %12s\n' "deadline misses (lateness > T) / cycles" \
    "$(get "$rt" deadline_misses)/$(get "$rt" cycles)" "$(get "$ref" misses)/2500"
done
echo "host load average: $(cut -d' ' -f1-3 /proc/loadavg) on $(nproc) CPUs"
