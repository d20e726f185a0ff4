#!/usr/bin/env bash
# hil_bench never loses a run and always says why it stopped (issue 18, 5).
# usage: bench_refusals.sh CASE HIL_BENCH WORKDIR SCENARIO [TABLE_DIR]
#   keeps_previous_run   a refused run (corrupt plant table, plant.backlash
#                        on the arm plant, duration = -1, a scenario line the
#                        parser refuses) exits non-zero and leaves the
#                        previous run's frames.log, meta.json, signals.csv
#                        byte for byte; no temporary directory is left; a
#                        good run then replaces them (also after --processes)
#   corrupt_ctrl_table   a ctrl.table with one flipped byte: exit 2 before
#                        any output, the message names the failing field
#   scenario_messages    a bad value / unknown key names the key, the value
#                        and what is allowed
#   duration_bound       duration = 1e9 is refused at once (exit 2, nothing
#                        written) with the bound in the message
set -u
case_=$1 bench=$2 work=$3 scen=$4 tables=${5:-}
fail=0
check() { # check DESCRIPTION COMMAND...
  if "${@:2}"; then echo "ok   $1"; else echo "FAIL $1"; fail=1; fi
}
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
run() { # run ARGS...: exit code in $rc, stderr in err.txt
  "$bench" "$@" > out.txt 2> err.txt
  rc=$?
}
sums() { sha256sum run/frames.log run/meta.json run/signals.csv; }
no_tmp() { [ -z "$(find . -maxdepth 1 -name '.*hil-tmp-*')" ]; }
has() { grep -qF -- "$1" err.txt || { echo "     stderr was:"; sed 's/^/       /' err.txt; return 1; }; }

case $case_ in
keeps_previous_run)
  run --scenario "$scen" --out run
  check "a good run exits 0" [ "$rc" = 0 ]
  check "a good run writes non-empty files" [ -s run/frames.log -a -s run/meta.json -a -s run/signals.csv ]
  sums > before.txt
  cp "$tables/arm_n9.bin" corrupt.bin
  printf '\x55' | dd of=corrupt.bin bs=1 seek=4000 conv=notrunc status=none
  printf 'T = 0.0012\nduration = 0.1\nplant = rigid\nplant.J = -1\n' > bad_value.txt
  for bad in "--set plant=arm --set plant.table=$PWD/corrupt.bin" \
             "--set plant=arm --set plant.table=$tables/arm_n9.bin --set plant.backlash=0.01" \
             "--set duration=-1" "--scenario bad_value.txt" \
             "--processes --set plant=arm --set plant.table=$PWD/corrupt.bin"; do
    # shellcheck disable=SC2086
    run --scenario "$scen" $bad --out run
    check "refused ($bad): exit $rc != 0" [ "$rc" != 0 ]
    check "refused ($bad): the previous run is intact" bash -c "sha256sum -c --quiet before.txt"
    check "refused ($bad): no temporary directory left" no_tmp
  done
  check "the corrupt plant table is named with its field" has "crc32"
  # a node that cannot run (this host has no AF_CAN; with one, no vcan9):
  # its report is on stderr, the previous run intact
  run --scenario "$scen" --processes --bus socketcan:vcan9 --out run
  check "a node that cannot open its bus: exit 1 (was $rc)" [ "$rc" = 1 ]
  check "... its report on stderr" has "hil_candump: cannot open bus socketcan:vcan9"
  check "... the previous run is intact" bash -c "sha256sum -c --quiet before.txt"
  check "... no temporary directory left" no_tmp
  run --scenario "$scen" --set duration=0.12 --out run
  check "a new good run exits 0" [ "$rc" = 0 ]
  check "a new good run replaces the files" bash -c "! sha256sum -c --quiet before.txt 2>/dev/null"
  check "the new log is the new run's (0.12 s)" grep -q '"cycles": 100,' run/meta.json
  run --scenario "$scen" --processes --out run
  check "a --processes run exits 0" [ "$rc" = 0 ]
  check "a --processes run writes its reports" [ -s run/hil_ctrl.txt -a -s run/frames.log ]
  run --scenario "$scen" --out run
  check "a lockstep run after it leaves no stale node reports" [ ! -e run/hil_ctrl.txt -a -s run/frames.log ]
  check "no temporary directory left" no_tmp
  ;;
corrupt_ctrl_table)
  cp "$tables/armctrl_A.bin" corrupt.bin
  printf '\x55' | dd of=corrupt.bin bs=1 seek=3000 conv=notrunc status=none
  for mode in "" "--processes"; do
    # shellcheck disable=SC2086
    run --scenario "$scen" --set plant=twomass --set ctrl.law=armctrl --set ctrl.table=corrupt.bin $mode --out run
    check "corrupt ctrl.table $mode: exit 2 (was $rc)" [ "$rc" = 2 ]
    check "corrupt ctrl.table $mode: the message names the file and the field" has "ctrl.table corrupt.bin: ArmCtrl refuses the table"
    check "corrupt ctrl.table $mode: ... field crc32" has "field crc32"
    check "corrupt ctrl.table $mode: nothing written" [ ! -e run ]
    check "corrupt ctrl.table $mode: no temporary directory left" no_tmp
  done
  # a valid FRPT (CRC right) whose entry "pd" is renamed: ArmCtrl's layout
  # check names the missing entry
  /usr/bin/python3 - "$tables/armctrl_A.bin" renamed.bin <<'PY'
import struct, sys, zlib
b = bytearray(open(sys.argv[1], "rb").read())
n = struct.unpack_from("<I", b, 12)[0]
for i in range(n):
    off = 48 + 32 * i
    if b[off:off + 24].rstrip(b"\0") == b"pd":
        b[off:off + 2] = b"px"
struct.pack_into("<I", b, len(b) - 4, zlib.crc32(bytes(b[:-4])) & 0xFFFFFFFF)
open(sys.argv[2], "wb").write(b)
PY
  run --scenario "$scen" --set plant=twomass --set ctrl.law=armctrl --set ctrl.table=renamed.bin --out run
  check "ctrl.table without entry pd: exit 2" [ "$rc" = 2 ]
  check "ctrl.table without entry pd: the entry named" has "entry 'pd': missing"
  check "ctrl.table without entry pd: nothing written" [ ! -e run ]
  run --scenario "$scen" --set plant=twomass --set ctrl.law=armctrl --set ctrl.table=nonexistent.bin --out run
  check "missing ctrl.table: exit 2" [ "$rc" = 2 ]
  check "missing ctrl.table: named" has "ctrl.table nonexistent.bin: cannot read the file"
  ;;
scenario_messages)
  printf 'T = 0.0012\nduration = abc\n' > s1.txt
  run --scenario s1.txt --out run
  check "bad value: exit 2" [ "$rc" = 2 ]
  check "bad value: line, key, value and what is allowed" has "s1.txt: line 2: duration = 'abc': wants a finite number"
  printf '# a comment\nT = 0.0012\ndrive.dela = 4\n' > s2.txt
  run --scenario s2.txt --out run
  check "unknown key: exit 2" [ "$rc" = 2 ]
  check "unknown key: line and key" has "s2.txt: line 3: unknown key 'drive.dela'"
  check "unknown key: the keys of its group" has "drive.delay, drive.tau_current"
  printf 'plant = flexible\n' > s3.txt
  run --scenario s3.txt --out run
  check "bad plant: the allowed names" has "line 1: plant = 'flexible': wants rigid, twomass or arm"
  run --set imu.seed=-3 --out run
  check "bad --set: key, value and what is allowed" has "--set imu.seed=-3: imu.seed = '-3': wants an integer 0..18446744073709551615"
  printf 'T = 0.0012\nduration 3\n' > s4.txt
  run --scenario s4.txt --out run
  check "no '=': the line is quoted" has "line 2: 'duration 3' is not a 'key = value' line"
  run --set frame_loss=1.5 --out run
  check "frame_loss out of range" has "frame_loss = '1.5': wants a probability in [0, 1)"
  check "nothing written by any refused scenario" [ ! -e run ]
  ;;
duration_bound)
  timeout 10 "$bench" --scenario "$scen" --set duration=1e9 --out run > out.txt 2> err.txt
  rc=$?
  check "duration = 1e9: exit 2 at once (was $rc)" [ "$rc" = 2 ]
  check "duration = 1e9: the bound in the message" has "duration = '1e9': wants simulated seconds in (0, 600]"
  check "duration = 1e9: nothing written" [ ! -e run ]
  run --scenario "$scen" --set duration=600.0001 --out run
  check "just above the bound: refused" [ "$rc" = 2 ]
  ;;
*) echo "unknown case $case_"; exit 2 ;;
esac
exit $fail
