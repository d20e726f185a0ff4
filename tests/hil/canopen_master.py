#!/usr/bin/env python3
"""An independent CANopen master against the rig's devices: the Python
`canopen` package on python-can, talking to hil_socketcand over TCP on
127.0.0.1 (python-can's "socketcand" interface: no kernel CAN support
needed), with nothing of the rig's C code but the devices themselves.

It loads hil/drive.eds and hil/imu.eds and
  1. boots both devices: NMT reset communication, SDO reads of 0x1000 and
     0x1018 compared with the EDS, every EDS default read back by SDO
     (expedited, and segmented for 0x1008), TPDO3 of the drive remapped by
     SDO (statusword, torque actual per mille, velocity), 0x1017 and
     0x6060 = 10 written, NMT start;
  2. walks the drive through the CiA 402 power state machine with its own
     decoder of the statusword (CiA 402 table 30) to operation enabled;
  3. runs >= 1,000 SYNC cycles with its own PD law moving the arm on a
     cos^2 move, checking every cycle's TPDOs (remapped TPDO3 against
     TPDO2 and 0x6076), the IMU readings and the heartbeats at 0x1017;
  4. provokes faults and resets them: RPDOs stopped (EMCY 0x8250) and the
     over-temperature trip lowered by SDO (EMCY 0x4310, reset refused while
     hot), each with 0x603F and 0x1001 read by SDO, then quick stop;
  5. checks every SDO abort path (CiA 301 codes) and segmented download.
Prints the measured SDO round trip and boot time (wall) and exits non-zero
with the list of failed checks.

usage: canopen_master.py HIL_SOCKETCAND DRIVE_EDS IMU_EDS
"""
import math
import statistics
import subprocess
import sys
import threading
import time

import canopen
from canopen.sdo.exceptions import SdoAbortedError

T = 1.2e-3
errors = []


def check(cond, what):
    if not cond:
        errors.append(what)
        print("FAIL:", what)
    return cond


def state402(sw):
    """CiA 402 table 30: the power state of a statusword."""
    if sw & 0x4F == 0x00:
        return "NOT READY TO SWITCH ON"
    if sw & 0x4F == 0x40:
        return "SWITCH ON DISABLED"
    if sw & 0x6F == 0x21:
        return "READY TO SWITCH ON"
    if sw & 0x6F == 0x23:
        return "SWITCHED ON"
    if sw & 0x6F == 0x27:
        return "OPERATION ENABLED"
    if sw & 0x6F == 0x07:
        return "QUICK STOP ACTIVE"
    if sw & 0x4F == 0x0F:
        return "FAULT REACTION ACTIVE"
    if sw & 0x4F == 0x08:
        return "FAULT"
    return "UNKNOWN"


# CiA 402 controlword commands (table 27) toward operation enabled.
NEXT_CW = {"SWITCH ON DISABLED": 0x06, "READY TO SWITCH ON": 0x07, "SWITCHED ON": 0x0F,
           "OPERATION ENABLED": 0x0F}


class Cycle:
    """SYNC + wait for the drive's TPDOs, then the RPDO: one controller cycle."""

    def __init__(self, net, drive, imu):
        self.net, self.drive, self.imu = net, drive, imu
        self.cond = threading.Condition()
        self.counts = {1: 0, 2: 0, 3: 0}
        self.imu_readings = []
        self.emcy = []
        self.heartbeats = {1: 0, 2: 0}
        self.sync_counter = 0
        for n in (1, 2, 3):
            drive.tpdo[n].add_callback(self._tpdo(n))
        imu.tpdo[1].add_callback(self._imu)
        drive.emcy.add_callback(lambda e: self.emcy.append(e.code))
        for node in (1, 2):
            net.subscribe(0x700 + node, self._hb(node))

    def _tpdo(self, n):
        def cb(_map):
            with self.cond:
                self.counts[n] += 1
                self.cond.notify_all()
        return cb

    def _hb(self, node):
        def cb(can_id, data, ts):
            self.heartbeats[node] += 1
        return cb

    def _imu(self, m):
        self.imu_readings.append({v.subindex + 16 * (v.index - 0x2000): v.raw for v in m.map})

    def sync(self, want=(1, 2, 3), timeout=1.0):
        before = dict(self.counts)
        self.sync_counter = self.sync_counter % 240 + 1
        self.net.send_message(0x80, bytes([self.sync_counter]))
        end = time.monotonic() + timeout
        with self.cond:
            while not all(self.counts[n] > before[n] for n in want):
                left = end - time.monotonic()
                if left <= 0:
                    return False
                self.cond.wait(left)
        return True

    def command(self, cw, torque_mnm):
        rp = self.drive.rpdo[1]
        rp["Controlword"].raw = cw
        rp["Target torque mNm"].raw = int(round(torque_mnm))
        rp.transmit()

    def sw(self):
        return self.drive.tpdo[1]["Statusword"].raw


def read_back_eds_defaults(node, skip):
    """Every object of the EDS read by SDO equals its DefaultValue."""
    n = 0
    for obj in node.object_dictionary.values():
        subs = [obj] if isinstance(obj, canopen.objectdictionary.ODVariable) else list(obj.values())
        for var in subs:
            if (var.index, var.subindex) in skip or var.default is None:
                continue
            raw = node.sdo.upload(var.index, var.subindex)
            want = var.encode_raw(var.default)
            check(raw == want, "node %d 0x%04X:%d reads %r, the EDS says %r" %
                  (node.id, var.index, var.subindex, raw, want))
            n += 1
    return n


def expect_abort(code, fn, what):
    try:
        fn()
    except SdoAbortedError as e:
        return check(e.code == code, "%s: abort 0x%08X, expected 0x%08X" % (what, e.code, code))
    return check(False, "%s: no abort (expected 0x%08X)" % (what, code))


def raw_sdo(node, data):
    """One request frame as bytes: the server's response frame, or its abort code."""
    try:
        return node.sdo.request_response(bytes(data))
    except SdoAbortedError as e:
        return e.code


def abort_code(resp):
    return resp if isinstance(resp, int) else None


def main():
    server_bin, drive_eds, imu_eds = sys.argv[1:4]
    srv = subprocess.Popen([server_bin, "--port", "0"], stdout=subprocess.PIPE, text=True)
    line = srv.stdout.readline()
    port = int(line.split("port=")[1])
    net = canopen.Network()
    net.connect(interface="socketcand", channel="can0", host="127.0.0.1", port=port, tcp_tune=True)
    drive = canopen.RemoteNode(1, drive_eds)
    imu = canopen.RemoteNode(2, imu_eds)
    net.add_node(drive)
    net.add_node(imu)
    for node in (drive, imu):
        node.sdo.RESPONSE_TIMEOUT = 1.0

    # 1. boot (the EDS read back first, after a reset, then the timed boot)
    bootup = {1: threading.Event(), 2: threading.Event()}
    for node in (1, 2):
        net.subscribe(0x700 + node, lambda can_id, data, ts: data[0] == 0 and bootup[can_id - 0x700].set())

    def reset_all():
        for e in bootup.values():
            e.clear()
        net.nmt.send_command(0x82)  # reset communication, all nodes
        for node in (1, 2):
            check(bootup[node].wait(2.0), "node %d boot-up after NMT reset communication" % node)

    reset_all()
    EDS_READ_BACK[0] = read_back_eds_defaults(drive, set()) + read_back_eds_defaults(imu, set())
    t_boot = time.monotonic()
    reset_all()
    for node, od in ((drive, drive.object_dictionary), (imu, imu.object_dictionary)):
        check(node.sdo[0x1000].raw == od[0x1000].default, "node %d device type" % node.id)
        check(node.sdo[0x1018][1].raw == od[0x1018][1].default, "node %d vendor id" % node.id)
        check(node.sdo[0x1018][2].raw == od[0x1018][2].default, "node %d product code" % node.id)
    boot_sdo = time.monotonic()
    check(drive.sdo[0x1008].raw == drive.object_dictionary[0x1008].default, "device name (segmented upload)")
    seg_upload = time.monotonic() - boot_sdo
    drive.tpdo.read()
    drive.rpdo.read()
    imu.tpdo.read()
    tp3 = drive.tpdo[3]
    tp3.clear()
    tp3.add_variable(0x6041)
    tp3.add_variable(0x6077)
    tp3.add_variable(0x606C)
    tp3.cob_id = 0x381
    tp3.trans_type = 1
    tp3.enabled = True
    tp3.save()
    check(drive.sdo[0x1A02][0].raw == 3 and drive.sdo[0x1A02][2].raw == 0x60770010, "TPDO3 mapping read back")
    drive.sdo[0x1017].raw = 50
    imu.sdo[0x1017].raw = 50
    drive.sdo[0x6060].raw = 10
    net.nmt.send_command(0x01)  # start all
    boot_wall = time.monotonic() - t_boot
    cyc = Cycle(net, drive, imu)
    rated_mnm = drive.sdo[0x6076].raw

    # 2. CiA 402 walk to operation enabled
    check(cyc.sync(), "first SYNC answered by TPDO1-3")
    visited = [state402(cyc.sw())]
    for _ in range(10):
        st = state402(cyc.sw())
        if st == "OPERATION ENABLED":
            break
        cyc.command(NEXT_CW[st], 0)
        cyc.sync()
        if state402(cyc.sw()) != visited[-1]:
            visited.append(state402(cyc.sw()))
    check(visited == ["SWITCH ON DISABLED", "READY TO SWITCH ON", "SWITCHED ON", "OPERATION ENABLED"],
          "402 walk %s" % visited)
    check(cyc.sw() & 0x1200 == 0x1200, "statusword remote (bit 9) and CST following (bit 12): 0x%04X" % cyc.sw())
    check(drive.sdo[0x6061].raw == 10, "0x6061 shows CST")

    # 3. >= 1,000 cycles with the arm moving (PD law on a cos^2 move of 0.5 rad)
    move, t0, tm, kp, kd = 0.5, 0.1, 0.5, 400.0, 60.0
    n_cycles, lost, hb0, cycle_wall = 1200, 0, dict(cyc.heartbeats), []
    imu0 = len(cyc.imu_readings)
    max_vel = 0.0
    for k in range(n_cycles):
        t = k * T
        s = min(max(t - t0, 0.0), tm)
        r = move * 0.5 * (1 - math.cos(math.pi * s / tm))
        rd = move * 0.5 * math.pi / tm * math.sin(math.pi * s / tm) if 0 < s < tm else 0.0
        theta = drive.tpdo[1]["Position actual value"].raw * 2 * math.pi / 2**20
        omega = drive.tpdo[2]["Velocity actual value"].raw * 1e-6
        max_vel = max(max_vel, abs(omega))
        cyc.command(0x0F, 1e3 * (kp * (r - theta) + kd * (rd - omega)))
        a = time.monotonic()
        if not cyc.sync():
            lost += 1
        cycle_wall.append(time.monotonic() - a)
        per_mille = drive.tpdo[3]["Torque actual value"].raw
        tq_mnm = drive.tpdo[2]["Torque actual value mNm"].raw
        if k % 50 == 0:
            check(abs(per_mille - round(tq_mnm / rated_mnm * 1000)) <= 1,
                  "cycle %d: TPDO3 torque %d per mille vs TPDO2 %d mNm" % (k, per_mille, tq_mnm))
            check(drive.tpdo[3]["Statusword"].raw == cyc.sw(), "cycle %d: TPDO3 statusword" % k)
    theta = drive.tpdo[1]["Position actual value"].raw * 2 * math.pi / 2**20
    check(lost == 0, "%d cycles without all TPDOs" % lost)
    check(abs(theta - move) < 0.02, "arm at %.4f rad, reference %.4f" % (theta, move))
    check(max_vel > 0.5, "the arm moved (max velocity %.3f rad/s)" % max_vel)
    readings = cyc.imu_readings[imu0:]
    want_readings = n_cycles * T / 2.4e-3
    check(abs(len(readings) - want_readings) <= 2, "IMU readings %d, expected %.0f" % (len(readings), want_readings))
    seqs = [r[32] for r in readings]
    check(all((b - a) % 256 == 1 for a, b in zip(seqs, seqs[1:])), "IMU sequence numbers consecutive")
    check(max(abs(r[3]) for r in readings) > 500, "IMU rate z saw the motion (mrad/s)")
    want_hb = n_cycles * T / 0.05
    for node in (1, 2):
        got = cyc.heartbeats[node] - hb0[node]
        check(abs(got - want_hb) <= 1.5, "node %d: %d heartbeats at 0x1017 = 50 ms, expected %.0f" % (node, got, want_hb))

    # 4a. fault: RPDOs stop -> 0x8250
    cyc.emcy.clear()
    for _ in range(5):
        cyc.sync()
    check(state402(cyc.sw()) == "FAULT", "RPDO timeout -> FAULT (%s)" % state402(cyc.sw()))
    check(0x8250 in cyc.emcy, "EMCY 0x8250 (%s)" % [hex(c) for c in cyc.emcy])
    check(drive.sdo[0x603F].raw == 0x8250, "0x603F = 0x8250")
    check(drive.sdo[0x1001].raw == 0x11, "0x1001 = generic + communication")
    cyc.command(0x80, 0)
    cyc.sync()
    check(state402(cyc.sw()) == "SWITCH ON DISABLED", "fault reset -> switch on disabled")
    check(drive.sdo[0x603F].raw == 0 and drive.sdo[0x1001].raw == 0, "errors cleared by the fault reset")
    check(0x0000 in cyc.emcy, "EMCY error reset")
    for cw in (0x06, 0x07, 0x0F):
        cyc.command(cw, 0)
        cyc.sync()
    check(state402(cyc.sw()) == "OPERATION ENABLED", "re-enabled after the fault")

    # 4b. fault: over-temperature (i^2t above a trip lowered to 20 % of rated^2)
    cyc.emcy.clear()
    drive.sdo[0x2101].raw = 200
    k = 0
    while state402(cyc.sw()) == "OPERATION ENABLED" and k < 2000:
        cyc.command(0x0F, 60000)
        cyc.sync()
        k += 1
    check(0x4310 in cyc.emcy and state402(cyc.sw()) == "FAULT", "over-temperature fault after %d cycles" % k)
    print("over-temperature fault after %d cycles" % k)
    check(drive.sdo[0x603F].raw == 0x4310 and drive.sdo[0x1001].raw == 0x09, "0x603F / 0x1001 over-temperature")
    i2t = drive.sdo[0x2100].raw
    check(i2t >= 200, "i2t estimate %d at or above the trip" % i2t)
    drive.sdo[0x2101].raw = 100  # torque is off and the drive cools: keep it above a lower trip
    cyc.command(0x80, 0)
    cyc.sync()
    check(state402(cyc.sw()) == "FAULT", "fault reset refused while the i2t estimate is above the trip")
    drive.sdo[0x2101].raw = 1100
    cyc.command(0x00, 0)
    cyc.sync()
    cyc.command(0x80, 0)
    cyc.sync()
    check(state402(cyc.sw()) == "SWITCH ON DISABLED", "fault reset once the trip is above the estimate")
    # 4c. quick stop (0x605A = 6: stay in quick stop active, torque 0)
    for cw in (0x06, 0x07, 0x0F, 0x02):
        cyc.command(cw, 5000)
        cyc.sync()
    for _ in range(10):
        cyc.command(0x02, 5000)
        cyc.sync()
    check(state402(cyc.sw()) == "QUICK STOP ACTIVE", "quick stop active (%s)" % state402(cyc.sw()))
    check(abs(drive.tpdo[2]["Torque actual value mNm"].raw) < 50, "torque 0 in quick stop")

    # 5. SDO abort paths (operational first, then pre-operational)
    expect_abort(0x06020000, lambda: drive.sdo.upload(0x5555, 0), "object does not exist")
    expect_abort(0x06090011, lambda: drive.sdo.upload(0x1018, 9), "sub-index does not exist")
    expect_abort(0x06010002, lambda: drive.sdo.download(0x6041, 0, b"\x00\x00"), "read-only 0x6041")
    expect_abort(0x06010002, lambda: drive.sdo.download(0x1000, 0, b"\x00\x00\x00\x00"), "const 0x1000")
    expect_abort(0x06090030, lambda: drive.sdo.download(0x6060, 0, bytes([8])), "mode 8 (CSP) unsupported")
    expect_abort(0x06090030, lambda: drive.sdo.download(0x605A, 0, (3).to_bytes(2, "little")), "quick stop option 3")
    expect_abort(0x06070010, lambda: drive.sdo.download(0x6040, 0, b"\x06\x00\x00\x00"), "4 bytes into 0x6040")
    expect_abort(0x08000022, lambda: drive.sdo.download(0x1A02, 0, bytes([0])), "mapping while operational")
    net.nmt.send_command(0x80)  # pre-operational
    time.sleep(0.05)
    expect_abort(0x08000022, lambda: drive.sdo.download(0x1A02, 0, bytes([0])), "mapping of a valid PDO")
    expect_abort(0x06090030, lambda: drive.sdo.download(0x1800, 1, (0x40000191).to_bytes(4, "little")),
                 "COB-ID of a valid PDO changed")
    expect_abort(0x06090030, lambda: imu.sdo.download(0x1800, 2, bytes([1])), "IMU TPDO synchronous")

    drive.sdo.download(0x1802, 1, (0xC0000381).to_bytes(4, "little"))
    drive.sdo.download(0x1A02, 0, bytes([0]))
    expect_abort(0x06040041, lambda: drive.sdo.download(0x1A02, 1, (0x10000020).to_bytes(4, "little")),
                 "0x1000 is not mappable")
    expect_abort(0x06040041, lambda: drive.sdo.download(0x1A02, 1, (0x60410020).to_bytes(4, "little")),
                 "0x6041 mapped with 32 bits")
    expect_abort(0x06040041, lambda: drive.sdo.download(0x1601, 1, (0x60410010).to_bytes(4, "little")),
                 "read-only 0x6041 into an RPDO")
    for k, m in enumerate((0x60640020, 0x606C0020, 0x20770020)):
        drive.sdo.download(0x1A02, k + 1, m.to_bytes(4, "little"))
    expect_abort(0x06040042, lambda: drive.sdo.download(0x1A02, 0, bytes([3])), "96 bits in a PDO")
    expect_abort(0x06090030, lambda: drive.sdo.download(0x1802, 2, bytes([250])), "reserved transmission type")
    expect_abort(0x06090030, lambda: drive.sdo.download(0x1A02, 0, bytes([9])), "9 mapped objects")
    # segmented download, read back
    drive.sdo.download(0x2101, 0, (900).to_bytes(2, "little"), force_segment=True)
    check(drive.sdo[0x2101].raw == 900, "segmented download of 0x2101")
    drive.sdo.download(0x2071, 0, (-1234).to_bytes(4, "little", signed=True), force_segment=True)
    check(drive.sdo[0x2071].raw == -1234, "segmented download of 0x2071")
    check(drive.sdo[0x6071].raw == round(-1234 / rated_mnm * 1000), "0x6071 per mille view of 0x2071")
    # protocol errors by raw frames
    check(abort_code(raw_sdo(drive, [0xC0, 0x00, 0x10, 0, 0, 0, 0, 0])) == 0x05040001, "block download refused")
    check(abort_code(raw_sdo(drive, [0x60, 0, 0, 0, 0, 0, 0, 0])) == 0x05040001, "segment without a transfer")
    resp = raw_sdo(drive, [0x40, 0x08, 0x10, 0, 0, 0, 0, 0])
    check(not isinstance(resp, int) and resp[0] == 0x41, "segmented upload of 0x1008 initiated")
    check(abort_code(raw_sdo(drive, [0x70, 0, 0, 0, 0, 0, 0, 0])) == 0x05030000, "toggle bit not alternated")
    raw_sdo(drive, [0x40, 0x08, 0x10, 0, 0, 0, 0, 0])
    drive.sdo.abort(0x05040000)  # client abort mid-transfer: no answer, next request served
    check(drive.sdo[0x1000].raw == 0x00020192, "served after a client abort")
    expect_abort(0x06070010, lambda: drive.sdo.download(0x2101, 0, b"\x01\x02\x03", force_segment=True),
                 "segmented download of 3 bytes into a 2-byte object")

    # SDO round trip (wall), expedited upload
    rt = []
    for _ in range(200):
        a = time.monotonic()
        drive.sdo.upload(0x6041, 0)
        rt.append(time.monotonic() - a)
    print("CANOPEN_MASTER sdo_round_trip_us_median=%.1f sdo_round_trip_us_p99=%.1f boot_wall_ms=%.1f "
          "segmented_upload_ms=%.2f cycle_us_median=%.1f cycles=%d eds_objects_read_back=%d" %
          (1e6 * statistics.median(rt), 1e6 * sorted(rt)[197], 1e3 * boot_wall, 1e3 * seg_upload,
           1e6 * statistics.median(cycle_wall), n_cycles, EDS_READ_BACK[0]))
    net.disconnect()
    out, _ = srv.communicate(timeout=10)
    print(out.strip())
    check(srv.returncode == 0, "hil_socketcand exit %s" % srv.returncode)
    check("malformed=0" in out, "no malformed socketcand command")
    socketcand_refuses_malformed(server_bin)
    if errors:
        print("%d checks failed" % len(errors))
        return 1
    print("all checks passed")
    return 0


def socketcand_refuses_malformed(server_bin):
    """Malformed socketcand commands: answered '< error ... >', counted, ignored."""
    import socket
    srv = subprocess.Popen([server_bin, "--port", "0"], stdout=subprocess.PIPE, text=True)
    port = int(srv.stdout.readline().split("port=")[1])
    sk = socket.create_connection(("127.0.0.1", port))
    f = sk.makefile("rb")

    def msg():
        out = b""
        while not out.endswith(b">"):
            out += f.read(1)
        return out.decode()

    check(msg() == "< hi >", "socketcand greeting")
    bad = ["< send 7FF9 1 0 >", "< send 601 9 0 0 0 0 0 0 0 0 0 >", "< send 601 2 1 >", "< send 601 1 100 >",
           "< send 601 1 1 2 >", "< bogus >", "< send xyz 1 0 >", "< " + "x" * 300 + " >"]
    for b in bad:
        sk.sendall(b.encode())
        check(msg().startswith("< error"), "socketcand refuses %r" % b[:40])
    sk.sendall(b"< send 000 2 81 0 >")  # a valid NMT reset node: the devices answer
    check(msg().startswith("< frame 701 "), "socketcand forwards the drive's boot-up after a valid frame")
    f.close()
    sk.close()
    out, _ = srv.communicate(timeout=10)
    check("malformed=%d" % len(bad) in out and "frames_in=1 " in out, "malformed commands counted: %s" % out.split("\n")[0])


EDS_READ_BACK = [0]

if __name__ == "__main__":
    sys.exit(main())
