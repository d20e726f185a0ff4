"""Driven by bench_python.sh (see there). Prints the two tables."""
import os
import subprocess
import sys
import tempfile
import time

import numpy as np

N = 100_000
REPS = 20
FLEET_RECORDS = 12
SRC, BIN = os.environ["FRAC_SOURCE_DIR"], os.environ["FRAC_BINARY_DIR"]
sys.path.insert(0, os.path.join(SRC, "python", "tests"))


def c_ns(cdriver, op_tokens, x):
    tok = ["time", REPS, "fo"] + op_tokens + [len(x)] + [repr(float(v)) for v in x]
    out = subprocess.run([cdriver], input=" ".join(map(str, tok)), capture_output=True, text=True, check=True).stdout
    return float(out.split()[1])


def py_ns(op, x):
    best = float("inf")
    for _ in range(3):
        t0 = time.perf_counter()
        for _ in range(REPS):
            op.reset()
            op.run(x)
        best = min(best, (time.perf_counter() - t0) / (REPS * len(x)) * 1e9)
    return best


def step_table(cdriver):
    from fracarm import frac

    x = np.sin(np.arange(N) * 1e-3 * 7.3) + 0.1 * np.random.default_rng(1).standard_normal(N)
    print("libfrac step over a %d-sample numpy array (ns/sample; C: the plain loop in cdriver.c)" % N)
    print("  %-28s %10s %10s %8s  %s" % ("realization", "Python", "C loop", "ratio", "goal <= 1.2x"))
    for name, op, tok in (
            ("Oustaloup N = 5, r = 0.5", frac.FoOperator(0.5, 1e-3, "oustaloup", wb=0.1, wh=1000.0, n=5),
             [repr(0.5), repr(1e-3), "oustaloup", 0, repr(0.1), repr(1000.0), 5]),
            ("GL L = 256, r = 0.5", frac.FoOperator(0.5, 1e-3, "gl", memory=256),
             [repr(0.5), repr(1e-3), "gl", 256, "0", "0", 0]),
            ("CFE Tustin n = 5, r = 0.5", frac.FoOperator(0.5, 1e-3, "cfe_tustin", n=5),
             [repr(0.5), repr(1e-3), "cfe_tustin", 0, "0", "0", 5])):
        c = min(c_ns(cdriver, tok, x) for _ in range(3))
        p = py_ns(op, x)
        print("  %-28s %10.2f %10.2f %8.3f  %s" % (name, p, c, p / c, "met" if p / c <= 1.2 else "NOT met"))


def noop(i):
    return i


def fleet_table():
    import hil_records
    from distributed import Client, LocalCluster

    from fracarm import fleet

    tmp = tempfile.mkdtemp(prefix="bench_python.")
    nominal = os.path.join(SRC, "hil", "scenarios", "demo_nominal.json")
    hil_records.make(SRC, os.path.join(BIN, "hil", "hil_bench"), nominal, tmp, FLEET_RECORDS, 5)
    rate = {}
    overhead = None
    for w in (1, 2):
        lc = LocalCluster(n_workers=w, threads_per_worker=1, processes=True, dashboard_address=":0")
        c = Client(lc)
        c.submit(noop, 0).result()
        t0 = time.perf_counter()
        t = fleet.diagnose(os.path.join(tmp, "manifest.csv"), os.path.join(tmp, "out%d" % w), client=c)
        wall = time.perf_counter() - t0
        assert t["error"].isna().all()
        rate[w] = len(t) / wall * 60
        if w == 1:
            n = 500
            t0 = time.perf_counter()
            c.gather([c.submit(noop, i, pure=False) for i in range(n)])
            overhead = (time.perf_counter() - t0) / n * 1e3
            busy = float(t["wall_s"].sum()) / wall
        c.close()
        lc.close()
    print("fleet gap diagnosis, %d HIL records (demo scenario, 2.2 s each), LocalCluster, 1 thread per worker" % FLEET_RECORDS)
    print("  %-28s %12s" % ("workers", "records/min"))
    for w in (1, 2):
        print("  %-28d %12.1f" % (w, rate[w]))
    s = rate[2] / rate[1]
    print("  %-28s %12.2f  goal >= 1.8x: %s (this machine has %d cores)" % ("speed-up 2 vs 1", s, "met" if s >= 1.8 else "NOT met",
                                                                             os.cpu_count()))
    print("  %-28s %12.2f ms (500 no-op tasks on 1 worker, submit to gather)" % ("scheduler overhead per task", overhead))
    print("  %-28s %12.1f %% of the 1-worker wall time in diagnosis" % ("busy fraction", 100 * busy))


if __name__ == "__main__":
    step_table(sys.argv[1])
    print()
    fleet_table()
