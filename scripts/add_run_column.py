"""add_run_column.py IN.csv OUT.csv (make demo, tests/plc_replay): the rig record with a column `run`, 1 from the first sample whose
torque_cmd is nonzero (when the PLC's tasks started), 0 before."""
import csv
import sys

rows = list(csv.reader(open(sys.argv[1])))
k = rows[0].index("torque_cmd")
first = next(i for i, r in enumerate(rows[1:]) if float(r[k]) != 0.0)
w = csv.writer(open(sys.argv[2], "w"))
w.writerow(rows[0] + ["run"])
for i, r in enumerate(rows[1:]):
    w.writerow(r + ["1" if i >= first else "0"])
