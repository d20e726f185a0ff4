#!/usr/bin/env python3
"""The rig's candump reader and writer (hil/candump.h) against python-can's
candump reader (can.io.CanutilsLogReader) on the same lines: hand-made
lines at the edges of the grammar, every line of a recorded bench log, and
seeded random mutations of valid lines. For every line:
  (a) a line the rig reads, python-can reads to the same time, interface,
      identifier, extended flag and data;
  (b) a line python-can refuses, the rig refuses;
  (c) a line the rig reads, the rig's writer writes, and reads back the same
      (one grammar: the reader accepts nothing the writer refuses);
and the hand-made lines get the rig's verdict written next to them.
Lines python-can reads and the rig refuses are the ones outside the rig's
grammar on purpose (RTR, CAN FD, rx/tx flags, free-form times, ...); they are
counted and printed.

usage: candump_grammar_vs_python_can.py CANDUMP_LINES_EXE FRAMES_LOG
"""
import io
import math
import random
import subprocess
import sys

import can

# (line, the rig reads it)
HAND = [
    ("(1700000000.123456) vcan0 201#0F00A0860100", True),
    ("(0.000000) vcan0 080#01", True),
    ("(0000000001.500000) can0 1ABCDEF0#", True),
    ("(12.500000) vcan0 201#0f00a0", True),
    ("(9000000000000000.000000) x 7FF#0011223344556677", True),
    ("(1.000000) abcdefghijklmno 000#", True),
    ("(1.000000) can-1.x_y:z 123#11", True),
    ("(1.000000) 0 123#11", True),
    ("(0.000000) can(0 123#11", False),
    ("(0.000000) can)0 123#11", False),
    ("(0.000000) ca#n0 123#11", False),
    ("(1.000000) abcdefghijklmnop 123#11", False),
    ("(0.5) vcan0 123#11", False),
    ("(1e3) vcan0 123#11", False),
    ("(-1.000000) vcan0 123#11", False),
    ("(1.0000000) vcan0 123#11", False),
    ("(.500000) vcan0 123#11", False),
    ("(10000000000000000.000000) vcan0 123#11", False),
    ("(9000000000000001.000000) vcan0 123#11", False),
    ("(1.000000) vcan0 123#R", False),
    ("(1.000000) vcan0 123#R2", False),
    ("(1.000000) vcan0 123##0112", False),
    ("(1.000000) vcan0 123#11 R", False),
    ("(1.000000) vcan0 123#11 T", False),
    ("(1.000000)  vcan0 123#11", False),
    (" (1.000000) vcan0 123#11", False),
    ("(1.000000) vcan0 123#11 ", False),
    ("(1.000000) vcan0 123#1", False),
    ("(1.000000) vcan0 12G#11", False),
    ("(1.000000) vcan0 123", False),
    ("(1.000000) vcan0 800#00", False),
    ("(1.000000) vcan0 20000000#00", False),
    ("(1.000000) vcan0 1234#00", False),
    ("(1.000000) vcan0 123#001122334455667788", False),
    ("(1.000000)vcan0 123#11", False),
    ("(1.000000) vcan0\t123#11", False),
    ("", False),
]

ALPHABET = "0123456789ABCDEFabcdef()#.R rTvcan-_:xe+"


def pycan(line):
    """python-can's reading: (t, channel, id, ext, data) or None (refused or
    no message)."""
    try:
        msgs = list(can.io.CanutilsLogReader(io.StringIO(line + "\n")))
    except Exception:  # python-can raises ValueError, IndexError, ... on bad lines
        return None
    if len(msgs) != 1:
        return None
    m = msgs[0]
    if m.is_error_frame:
        return ("error frame",)
    return (m.timestamp, str(m.channel), m.arbitration_id, m.is_extended_id, m.is_remote_frame, m.is_fd,
            bytes(m.data or b""), m.dlc)


def mutate(rng, line):
    s = list(line)
    for _ in range(rng.randint(1, 3)):
        op = rng.randrange(3)
        i = rng.randrange(len(s) + 1)
        if op == 0 and s:
            del s[min(i, len(s) - 1)]
        elif op == 1:
            s.insert(i, rng.choice(ALPHABET))
        elif s:
            s[min(i, len(s) - 1)] = rng.choice(ALPHABET)
    return "".join(s)


def main():
    exe, log = sys.argv[1:3]
    recorded = [l.rstrip("\n") for l in open(log)]
    assert len(recorded) > 1000, "the recorded log has %d lines" % len(recorded)
    rng = random.Random(18)
    valid = [l for l, ok in HAND if ok] + recorded[:200]
    mutated = [mutate(rng, rng.choice(valid)) for _ in range(30000)]
    lines = [l for l, _ in HAND] + recorded + mutated
    out = subprocess.run([exe], input="".join(l + "\n" for l in lines), capture_output=True, text=True,
                         check=True).stdout.splitlines()
    assert len(out) == len(lines), "%d lines in, %d verdicts out" % (len(lines), len(out))
    errors, stricter, accepted = [], {}, 0
    for i, (line, verdict) in enumerate(zip(lines, out)):
        v = verdict.split(" ")
        ours = v[0] == "ok"
        theirs = pycan(line)
        if i < len(HAND) and ours != HAND[i][1]:
            errors.append("rig %s %r (expected %s)" % ("reads" if ours else "refuses", line,
                                                       "read" if HAND[i][1] else "refused"))
        if i >= len(HAND) and i < len(HAND) + len(recorded) and not ours:
            errors.append("rig refuses a line of its own log: %r" % line)
        if not ours:
            if theirs is not None:
                stricter[line] = theirs
            continue
        accepted += 1
        t, iface, cid, ext, dlc, data, rt = float(v[1]), v[2], int(v[3], 16), v[4] == "1", int(v[5]), v[6], v[7]
        data = b"" if data == "-" else bytes.fromhex(data)
        if rt != "1":
            errors.append("(c) the writer does not write back what the reader read: %r" % line)
        if theirs is None:
            errors.append("(b) python-can refuses a line the rig reads: %r" % line)
            continue
        if len(theirs) == 1:
            errors.append("python-can reads an error frame the rig reads as data: %r" % line)
            continue
        pt, pch, pid, pext, prtr, pfd, pdata, pdlc = theirs
        if not (math.isclose(pt, t, rel_tol=1e-15, abs_tol=1e-9) and pch == iface and pid == cid and pext == ext
                and not prtr and not pfd and pdata == data and pdlc == dlc == len(data)):
            errors.append("(a) %r: rig %s, python-can %s" % (line, (t, iface, cid, ext, data), theirs))
    print("lines: %d (%d hand-made, %d recorded, %d mutated); the rig reads %d; python-can reads %d more "
          "that the rig refuses" % (len(lines), len(HAND), len(recorded), len(mutated), accepted, len(stricter)))
    for line in list(stricter)[:12]:
        print("  outside the rig's grammar, python-can reads: %r" % line)
    for e in errors[:40]:
        print("FAIL", e)
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main())
