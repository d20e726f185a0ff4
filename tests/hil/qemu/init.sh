#!/bin/busybox sh
# /init of the vcan-in-QEMU initramfs: load the CAN modules, create vcan0,
# run the rig's nodes over SocketCAN and print what the host checks.
/bin/busybox --install -s /bin
export PATH=/bin:/rig
mount -t proc proc /proc
mount -t sysfs sys /sys
mount -t devtmpfs dev /dev
mkdir -p /tmp
for m in $(cat /modules/order); do
  insmod "/modules/$m" || echo "HIL_QEMU_ERROR insmod $m"
done
ip link add dev vcan0 type vcan || echo "HIL_QEMU_ERROR ip link add"
ip link set vcan0 up || echo "HIL_QEMU_ERROR ip link set"
echo "HIL_QEMU_VCAN $(cat /sys/class/net/vcan0/type 2>/dev/null) $(cat /sys/class/net/vcan0/operstate 2>/dev/null)"
S=/rig/scenario.txt
B=socketcan:vcan0
hil_candump --bus $B --out /tmp/frames.log --idle-exit 1.0 2>/tmp/candump.out &
# the logger's socket is bound before any other node sends: it opens its
# log once bound (busybox sh: a polling loop, at most 10 s)
i=0
while [ ! -e /tmp/frames.log ] && [ $i -lt 200 ]; do sleep 0.05; i=$((i + 1)); done
hil_plant --bus $B --scenario $S --idle-exit 1.0 >/tmp/plant.out 2>&1 &
hil_drive --bus $B --scenario $S --idle-exit 1.0 >/tmp/drive.out 2>&1 &
hil_imu --bus $B --scenario $S --idle-exit 1.0 >/tmp/imu.out 2>&1 &
sleep 0.3
hil_ctrl --lockstep --bus $B --scenario $S --csv /tmp/ctrl.csv >/tmp/ctrl.out 2>&1
echo "HIL_QEMU_CTRL_RC $?"
wait
cat /tmp/ctrl.out /tmp/drive.out /tmp/imu.out /tmp/plant.out /tmp/candump.out
echo "HIL_QEMU_LOGLINES $(wc -l < /tmp/frames.log)"
# The serial console is slow under TCG: the host gets the per-identifier
# frame counts and the first 300 log lines, not the whole log.
awk '/^\([0-9]+\.[0-9]{6}\) vcan0 [0-9A-F]{3}#([0-9A-F][0-9A-F])*$/ { split($3, a, "#"); c[a[1] " " length(a[2]) / 2]++; next }
     { bad++ } END { for (k in c) print "HIL_QEMU_IDCOUNT", k, c[k]; print "HIL_QEMU_BADLINES", bad + 0 }' /tmp/frames.log
echo "HIL_LOG_BEGIN"
head -n 300 /tmp/frames.log
echo "HIL_LOG_END"
echo "HIL_QEMU_UPTIME $(cut -d' ' -f1 /proc/uptime)"
echo "HIL_QEMU_DONE"
poweroff -f
