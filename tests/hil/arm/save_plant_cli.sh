#!/usr/bin/env bash
# fracdesign model arm --save-plant: the plant table of the HIL arm plant
# (docs/hil.md) - written with the entries and dimensions the bench reads,
# and every bad use refused with one line naming the cause.
# usage: save_plant_cli.sh FRACDESIGN WORK_DIR
set -uo pipefail
fd=${1:?usage: save_plant_cli.sh FRACDESIGN WORK_DIR}
work=${2:?}
rm -rf "$work" && mkdir -p "$work"
status=0
# expect RC PATTERN ARGS...: exit status RC and PATTERN on stderr
expect() {
  local rc=$1 pat=$2; shift 2
  "$fd" "$@" > "$work/out" 2> "$work/err"
  local got=$?
  if [ "$got" != "$rc" ] || ! grep -q -- "$pat" "$work/err"; then
    echo "FAIL: fracdesign $* -> exit $got, stderr: $(cat "$work/err") (want exit $rc and '$pat')"; status=1
  else
    echo "ok: fracdesign $* -> exit $rc: $(cat "$work/err")"
  fi
}
expect 2 "needs the full-order arm (--full)" model arm --N 9 --save-plant "$work/x.bin"
expect 2 "option --h: must be in (0, 0.1\] s" model arm --N 9 --full --h 0 --save-plant "$work/x.bin"
expect 2 "option --h: 'nan' is not a finite number" model arm --N 9 --full --h nan --save-plant "$work/x.bin"
expect 2 "option --h: only with --save-plant" model arm --N 9 --full --h 1e-4
expect 2 "only for the arm model" model beam --N 9 --save-plant "$work/x.bin"
expect 1 "cannot write" model arm --N 9 --full --save-plant "$work/no/such/dir/x.bin"
[ -e "$work/x.bin" ] && { echo "FAIL: a refused call wrote the table"; status=1; }
# the good path: entries and dimensions as the bench reads them
"$fd" model arm --N 9 --full --h 1e-4 --save-plant "$work/arm9.bin" > /dev/null || { echo "FAIL: --save-plant"; status=1; }
"$fd" table check "$work/arm9.bin" > "$work/check" || { echo "FAIL: table check"; status=1; }
cat "$work/check"
for want in "plant_dims 1 x 2 40 9" "h 1 x 1 0.0001" "Ad 40 x 40" "Bd 40 x 1" "Bd1 40 x 1" "C 4 x 40" "Ac 40 x 40" "Bc 40 x 1"; do
  set -- $want
  line=$(awk -v n="$1" '$1 == n' "$work/check" | tr -s ' ' | sed 's/^ //')
  case "$line" in
    "$want"*) ;;
    *) echo "FAIL: entry $1: '$line', want '$want'"; status=1 ;;
  esac
done
exit $status
