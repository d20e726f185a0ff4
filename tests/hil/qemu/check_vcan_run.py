#!/usr/bin/python3
"""Host-side checks of the vcan-in-QEMU run (run_vcan_qemu.sh).

usage: check_vcan_run.py CONSOLE_TXT FRAMES_LOG_HEAD SCENARIO DBC

Run with the test venv's python (cantools): the head of the log recorded on
vcan0 is decoded with the DBC as an independent client.

Frame accounting over the real SocketCAN path: every frame any node sent
appears exactly once in the candump-format log; SYNC and RPDO counts equal the
controller's cycles; every node counted the injected malformed frames (wrong
DLC, unknown identifier) and ignored them; the loop reached its reference.
"""
import re
import sys

LINE = re.compile(r"^\((\d+)\.(\d{6})\) vcan0 ([0-9A-F]{3}|[0-9A-F]{8})#((?:[0-9A-F]{2}){0,8})$")


def fields(line):
    return dict(kv.split("=", 1) for kv in line.split()[1:])


def main():
    console, log_path, scenario_path, dbc_path = sys.argv[1:5]
    # The serial console may put terminal escape codes before a marker.
    text = [l[l.index("HIL_"):] if "HIL_" in l else l
            for l in open(console, encoding="utf-8", errors="replace").read().splitlines()]
    stats, ctrl, jitter = {}, None, None
    idcount, bad_lines, loglines = {}, None, None
    vcan = None
    for line in text:
        if line.startswith("HIL_STATS "):
            f = fields(line)
            stats[f["node"]] = f
        elif line.startswith("HIL_CTRL "):
            ctrl = fields(line)
        elif line.startswith("HIL_JITTER "):
            jitter = fields(line)
        elif line.startswith("HIL_QEMU_IDCOUNT "):
            _, cob, dlc, n = line.split()
            idcount[(int(cob, 16), int(dlc))] = int(n)
        elif line.startswith("HIL_QEMU_BADLINES "):
            bad_lines = int(line.split()[1])
        elif line.startswith("HIL_QEMU_LOGLINES "):
            loglines = int(line.split()[1])
        elif line.startswith("HIL_QEMU_VCAN "):
            vcan = line.split()[1:]
    scen = {}
    for raw in open(scenario_path):
        raw = raw.split("#", 1)[0].strip()
        if raw:
            k, v = (s.strip() for s in raw.split("=", 1))
            scen[k] = v
    T = float(scen["T"])
    cycles = round(float(scen["duration"]) / T)
    move = float(scen["ctrl.move"])
    inject_every = int(scen["inject_every"])
    errors = []

    def check(cond, what):
        print(("ok   " if cond else "FAIL ") + what)
        if not cond:
            errors.append(what)

    check(vcan is not None and vcan[0] == "280", "vcan0 exists with ARPHRD_CAN type 280 (%s)" % vcan)
    for node in ("ctrl", "drive", "imu", "plant", "candump"):
        check(node in stats, "HIL_STATS from %s" % node)
    check(ctrl is not None and jitter is not None, "controller summary present")
    if errors:
        return 1
    head = []
    for line in open(log_path):
        m = LINE.match(line.rstrip("\n"))
        head.append(m is not None)
    check(len(head) > 0 and all(head), "the %d log lines shown are candump format" % len(head))
    import cantools
    import cantools.logreader
    db = cantools.database.load_file(dbc_path)
    decoded, sync_ok, expect = 0, True, 1
    with open(log_path) as f:
        for fr in cantools.logreader.Parser(f):
            if fr.frame_id == 0x555:  # the injected unknown identifier
                continue
            msg = db.get_message_by_frame_id(fr.frame_id)
            if msg.name == "DRIVE_RPDO1" and len(fr.data) != 6:  # the injected wrong-DLC RPDO
                continue
            sig = db.decode_message(fr.frame_id, fr.data)
            if msg.name == "SYNC":
                sync_ok &= sig["sync_counter"] == expect
                expect = expect % 240 + 1
            decoded += 1
    check(decoded > 250 and sync_ok,
          "cantools %s decoded %d frames recorded on vcan0, SYNC counters in sequence" % (cantools.__version__, decoded))
    check(bad_lines == 0, "every log line in the guest matched the candump format (%s bad)" % bad_lines)
    logged = int(stats["candump"]["logged"])
    check(loglines == logged, "log lines %s == frames the logger counted %d" % (loglines, logged))
    check(sum(idcount.values()) == logged, "per-identifier counts add up to %d" % sum(idcount.values()))
    sent = sum(int(stats[n]["tx"]) for n in ("ctrl", "drive", "imu", "plant"))
    check(logged == sent, "frames logged %d == frames sent by all nodes %d" % (logged, sent))
    check(all(int(stats[n]["tx_errors"]) == 0 for n in ("ctrl", "drive", "imu", "plant")), "no send errors")
    check(int(ctrl["cycles"]) == cycles, "controller ran %s cycles (want %d)" % (ctrl["cycles"], cycles))

    def count(cob, dlc):
        return idcount.get((cob, dlc), 0)

    check(count(0x080, 1) == cycles, "SYNC frames %d == cycles" % count(0x080, 1))
    check(count(0x201, 6) == cycles, "drive RPDO1 frames %d == cycles" % count(0x201, 6))
    check(count(0x6F0, 8) == cycles, "drive RIG_TORQUE frames %d == cycles" % count(0x6F0, 8))
    check(count(0x181, 6) == cycles and count(0x281, 8) == cycles,
          "drive TPDO1/TPDO2 frames %d/%d == cycles" % (count(0x181, 6), count(0x281, 8)))
    readings = count(0x182, 8)
    check(readings >= 2 * cycles // 4 - 2 and readings == count(0x282, 8),
          "IMU TPDO1/TPDO2 frames %d/%d, one reading per 4 acquisitions" % (readings, count(0x282, 8)))
    check(count(0x6F4, 2) == cycles, "IMU step-complete frames %d == cycles" % count(0x6F4, 2))
    check(count(0x000, 2) == 3, "NMT reset communication (boot), start and stop sent")
    check(count(0x601, 8) == count(0x581, 8) > 20 and count(0x602, 8) == count(0x582, 8) > 20,
          "boot by SDO over vcan0: every request to the drive (%d) and the IMU (%d) answered"
          % (count(0x601, 8), count(0x602, 8)))
    injected = int(ctrl["injected"])
    check(injected == 2 * (cycles // inject_every), "malformed frames injected: %d" % injected)
    check(count(0x201, 5) == injected // 2 and count(0x555, 8) == injected // 2,
          "injected frames on the bus and in the log")
    for node in ("drive", "imu", "plant"):
        s = stats[node]
        check(int(s["bad_dlc"]) == injected // 2 and int(s["unknown_id"]) == injected // 2,
              "%s counted and ignored %s wrong-DLC and %s unknown-ID frames" % (node, s["bad_dlc"], s["unknown_id"]))
    final = float(ctrl["final_angle"])
    check(abs(final - move) < 0.05 * abs(move) + 0.01,
          "closed loop over vcan0 reached %.4f rad (reference %.4f)" % (final, move))
    check(int(jitter["step_timeouts"]) == 0, "no lockstep wait timed out")
    print("figures: mode=%s cycles=%d frames=%d imu_readings=%d missed_inputs=%s wall_s=%s" %
          (jitter["mode"], cycles, logged, readings, ctrl["missed_inputs"], jitter["wall_s"]))
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main())
