#!/usr/bin/python3
"""scipy reference for bench_fo.sh: the same 1e6-sample input through the
same Oustaloup N = 5 biquad table with scipy.signal.sosfilt (throughput and
agreement with libfrac's frac_sos_process output), and through the naive
direct form of the same transfer function (scipy.signal.sos2tf + lfilter:
cost and numerical error against the cascade).

usage: bench_fo_ref.py INPUT.f64 SOS.txt LIBFRAC_OUTPUT.f64
prints key=value lines.
"""
import sys
import time

import numpy as np
from scipy import signal


def best_of(f, n=5):
    best = float("inf")
    out = None
    for _ in range(n):
        t0 = time.perf_counter()
        out = f()
        best = min(best, time.perf_counter() - t0)
    return best, out


def main():
    x = np.fromfile(sys.argv[1], dtype=np.float64)
    sos = np.loadtxt(sys.argv[2], ndmin=2)
    ylib = np.fromfile(sys.argv[3], dtype=np.float64)
    n = len(x)
    t, y = best_of(lambda: signal.sosfilt(sos, x))
    scale = np.max(np.abs(y))
    print("sosfilt_ns=%.3f" % (1e9 * t / n))
    print("sosfilt_vs_libfrac=%.3e" % (np.max(np.abs(y - ylib)) / scale))
    b, a = signal.sos2tf(sos)
    with np.errstate(all="ignore"):
        tn, yn = best_of(lambda: signal.lfilter(b, a, x), 3)
        err = np.max(np.abs(yn - y)) / scale
        yn32 = signal.lfilter(b.astype(np.float32), a.astype(np.float32), x.astype(np.float32))
        err32 = np.max(np.abs(yn32.astype(np.float64) - y)) / scale
        ys32 = signal.sosfilt(sos.astype(np.float32), x.astype(np.float32))
        errs32 = np.max(np.abs(ys32.astype(np.float64) - y)) / scale
    poles = np.roots(a)
    print("direct_order=%d" % (len(a) - 1))
    print("direct_ns=%.3f" % (1e9 * tn / n))
    print("direct_err=%s" % ("%.3e" % err if np.isfinite(err) else "diverged"))
    print("direct_err_f32=%s" % ("%.3e" % err32 if np.isfinite(err32) else "diverged"))
    print("sos_err_f32=%.3e" % errs32)
    print("direct_max_pole=%.9f" % np.max(np.abs(poles)))


if __name__ == "__main__":
    main()
