#!/usr/bin/env python3
"""Decodes a recorded candump log of the lockstep bench with cantools and the
rig's DBC (an independent client: none of the rig's C decoders is used) and
checks the decoded values against what the nodes sent and saw (signals.csv,
meta.json).

usage: decode_with_cantools.py DBC RUN_DIR
"""
import csv
import json
import math
import sys

import cantools
import cantools.logreader


def main():
    dbc_path, run = sys.argv[1:3]
    db = cantools.database.load_file(dbc_path)
    meta = json.load(open(run + "/meta.json"))
    rows = list(csv.DictReader(open(run + "/signals.csv")))
    T = meta["parameters"]["T"]
    errors = []

    def check(cond, what):
        if not cond:
            errors.append(what)
        return cond

    frames = []
    with open(run + "/frames.log") as f:
        for fr in cantools.logreader.Parser(f):
            t = fr.timestamp.timestamp()
            frames.append((t, fr.frame_id, fr.data))
    check(len(frames) == meta["counts"]["frames_logged"],
          "log frames %d != frames_logged %d" % (len(frames), meta["counts"]["frames_logged"]))
    check(len(frames) == meta["counts"]["frames_sent"] - meta["counts"]["frames_lost"],
          "log frames != frames sent - lost")
    names = {}
    last_rate = 0.0
    sync_expect = 1
    k_seen = set()
    checked = {"rpdo": 0, "tpdo1": 0, "tpdo2": 0, "imu": 0, "truth": 0}
    tpdo = {}
    tip = 0.0
    for t, cob, data in frames:
        msg = db.get_message_by_frame_id(cob)
        sig = db.decode_message(cob, data, decode_choices=False)
        names[msg.name] = names.get(msg.name, 0) + 1
        k = int(math.floor(t / T + 1e-3))
        if msg.name == "SYNC":
            check(sig["sync_counter"] == sync_expect, "SYNC counter %d at cycle %d" % (sig["sync_counter"], k))
            sync_expect = sync_expect % 240 + 1
            k_seen.add(k)
        elif msg.name == "DRIVE_TPDO1":
            tpdo["pos"] = sig["position_actual"]
        elif msg.name == "DRIVE_TPDO2":
            tpdo["vel"] = sig["velocity_actual"]
        elif msg.name == "IMU_TPDO1":
            last_rate = sig["rate_z"]
        elif msg.name == "IMU_TPDO2":
            check(abs(sig["acc_z"] - 9.80665) < 0.1, "acc_z %.4f is not gravity" % sig["acc_z"])
        elif msg.name == "DRIVE_RPDO1" and k < len(rows):
            row = rows[k]
            u = float(row["torque_cmd"])
            check(abs(sig["target_torque"] - u) <= 0.0005 + 1e-9,
                  "cycle %d: RPDO torque %.6f vs commanded %.6f" % (k, sig["target_torque"], u))
            check(abs(tpdo["pos"] - float(row["motor_angle"])) <= 1e-9 * max(1.0, abs(tpdo["pos"])),
                  "cycle %d: TPDO1 position %.9f vs controller's %.9f" % (k, tpdo["pos"], float(row["motor_angle"])))
            check(abs(tpdo["vel"] - float(row["motor_velocity"])) <= 1e-9,
                  "cycle %d: TPDO2 velocity vs controller's" % k)
            check(abs(last_rate - float(row["imu_rate"])) <= 1e-9,
                  "cycle %d: IMU rate %.6f vs controller's %.6f" % (k, last_rate, float(row["imu_rate"])))
            checked["rpdo"] += 1
        elif msg.name == "RIG_TIPPOS":
            tip = sig["tip_angle"]
        elif msg.name == "RIG_MOTOR" and k + 1 < len(rows):
            # the plant's last RIG_TIPPOS of cycle k is the tip at t_{k+1}
            truth = float(rows[k + 1]["tip_angle"])
            check(abs(tip - truth) <= 1e-6 * max(1.0, abs(truth)),
                  "cycle %d: RIG_TIPPOS tip angle %.9f vs truth %.9f" % (k, tip, truth))
            checked["truth"] += 1
    cycles = meta["counts"]["cycles"]
    check(names.get("SYNC") == cycles, "SYNC frames %s != cycles %d" % (names.get("SYNC"), cycles))
    check(names.get("DRIVE_RPDO1") == cycles, "RPDO frames != cycles")
    check(checked["rpdo"] == cycles, "compared %d RPDO cycles" % checked["rpdo"])
    check(names.get("IMU_TPDO1", 0) == meta["counts"]["imu_readings"], "IMU readings")
    check(len(rows) == cycles, "signals.csv rows %d != cycles" % len(rows))
    moved = max(abs(float(r["motor_angle"])) for r in rows)
    check(moved > 0.1, "the arm moved (%.3f rad)" % moved)
    print("cantools %s decoded %d frames of %d kinds: %s" % (cantools.__version__, len(frames), len(names),
                                                             ", ".join("%s=%d" % kv for kv in sorted(names.items()))))
    print("compared per cycle: RPDO torque, TPDO1 position, TPDO2 velocity, IMU rate (%d cycles), "
          "RIG_TIPPOS vs truth (%d steps)" % (checked["rpdo"], checked["truth"]))
    for e in errors[:20]:
        print("FAIL", e)
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main())
