#!/usr/bin/env bash
# The vcan-in-QEMU test (issue 9): the real SocketCAN path on a host whose own
# kernel lacks AF_CAN. Boots Debian's kernel (linux-image-amd64) under
# qemu-system-x86_64 with TCG (no KVM), with an initramfs holding
# busybox-static, can.ko/can-raw.ko/vcan.ko (+ dependencies from modules.dep)
# and the statically linked rig binaries; inside, vcan0 carries a short
# closed-loop scenario (controller, drive, IMU, plant nodes) and the rig's
# candump-format logger. Checks the result marker and the frame counts.
#
# usage: run_vcan_qemu.sh BUILD_DIR WORK_DIR [PYTHON_WITH_CANTOOLS]
set -euo pipefail
build=$(cd "${1:?usage: run_vcan_qemu.sh BUILD_DIR WORK_DIR}" && pwd)
work=${2:?usage: run_vcan_qemu.sh BUILD_DIR WORK_DIR}
here=$(cd "$(dirname "$0")" && pwd)
src=$(cd "$here/../../.." && pwd)
fail() { echo "FAIL: $*" >&2; exit 1; }

kernel=$(ls -1 /boot/vmlinuz-* 2>/dev/null | sort -V | tail -n 1)
[ -n "$kernel" ] && [ -r "$kernel" ] || fail "no readable /boot/vmlinuz-* (package linux-image-amd64)"
kver=${kernel#/boot/vmlinuz-}
mods=/lib/modules/$kver
[ -f "$mods/modules.dep" ] || fail "$mods/modules.dep missing"
command -v qemu-system-x86_64 >/dev/null || fail "qemu-system-x86_64 missing (package qemu-system-x86)"
busybox=$(command -v busybox || true)
[ -n "$busybox" ] || fail "busybox missing (package busybox-static)"

is_static() { ! LC_ALL=C readelf -l "$1" 2>/dev/null | grep -q 'INTERP'; }
is_static "$busybox" || fail "$busybox is dynamically linked (install busybox-static)"

rm -rf "$work"
mkdir -p "$work/root/bin" "$work/root/rig" "$work/root/modules" "$work/root/proc" \
         "$work/root/sys" "$work/root/dev" "$work/root/tmp"
root=$work/root
cp "$busybox" "$root/bin/busybox"
for b in hil_ctrl hil_drive hil_imu hil_plant hil_candump; do
  [ -x "$build/hil/$b" ] || fail "$build/hil/$b not built"
  is_static "$build/hil/$b" || fail "$b is not statically linked (HIL_STATIC=ON needed)"
  cp "$build/hil/$b" "$root/rig/"
done
cp "$here/vcan_scenario.txt" "$root/rig/scenario.txt"
cp "$here/init.sh" "$root/init"
chmod +x "$root/init"

# Kernel modules with their dependencies, dependencies first (modules.dep:
# "path: dep1 dep2 ..."; every listed path is relative to $mods).
declare -A seen=()
order=()
add_module() {
  local path=$1 line dep
  [ -n "${seen[$path]:-}" ] && return 0
  seen[$path]=1
  line=$(grep -E "^${path//./\\.}:" "$mods/modules.dep") || fail "$path not in modules.dep"
  for dep in ${line#*:}; do add_module "$dep"; done
  order+=("$path")
}
for name in can can-raw vcan; do
  path=$(grep -oE "^[^:]*/${name}\.ko(\.xz|\.zst|\.gz)?:" "$mods/modules.dep" | head -n 1 | tr -d ':')
  [ -n "$path" ] || fail "module $name not found for kernel $kver"
  add_module "$path"
done
: > "$root/modules/order"
for path in "${order[@]}"; do
  base=$(basename "$path")
  case $base in
    *.ko.xz) xz -dc "$mods/$path" > "$root/modules/${base%.xz}"; base=${base%.xz} ;;
    *.ko.zst) zstd -qdc "$mods/$path" > "$root/modules/${base%.zst}"; base=${base%.zst} ;;
    *.ko.gz) gzip -dc "$mods/$path" > "$root/modules/${base%.gz}"; base=${base%.gz} ;;
    *) cp "$mods/$path" "$root/modules/$base" ;;
  esac
  echo "$base" >> "$root/modules/order"
done
echo "modules: $(tr '\n' ' ' < "$root/modules/order")"

(cd "$root" && find . | LC_ALL=C sort | cpio -o -H newc --quiet | gzip -1) > "$work/initramfs.gz"

start=$(date +%s.%N)
set +e
timeout 110 qemu-system-x86_64 -accel tcg -nographic -no-reboot -m 512M -nic none \
  -kernel "$kernel" -initrd "$work/initramfs.gz" \
  -append "console=ttyS0 panic=-1 quiet rdinit=/init" < /dev/null > "$work/console.log" 2>&1
rc=$?
set -e
end=$(date +%s.%N)
tr -d '\r' < "$work/console.log" > "$work/console.txt"
boot_s=$(awk -v a="$start" -v b="$end" 'BEGIN { printf "%.1f", b - a }')
echo "qemu: exit $rc after $boot_s s (kernel $kver, TCG)"
[ $rc -eq 0 ] || { tail -n 40 "$work/console.txt"; fail "qemu exit status $rc"; }
grep -q 'HIL_QEMU_DONE' "$work/console.txt" || { tail -n 40 "$work/console.txt"; fail "no HIL_QEMU_DONE marker"; }
if grep -q 'HIL_QEMU_ERROR' "$work/console.txt"; then grep 'HIL_QEMU_ERROR' "$work/console.txt"; fail "set-up error in the guest"; fi
sed -n '/HIL_LOG_BEGIN$/,/^HIL_LOG_END$/p' "$work/console.txt" | sed '1d;$d' > "$work/frames.log"
grep -E 'HIL_(STATS|JITTER|CTRL|QEMU)' "$work/console.txt"

py=${3:-/usr/bin/python3}
exec "$py" "$here/check_vcan_run.py" "$work/console.txt" "$work/frames.log" "$here/vcan_scenario.txt" \
  "$src/hil/fracarm.dbc"
