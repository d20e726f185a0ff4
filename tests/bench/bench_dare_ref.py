"""Reference for bench_dare: scipy.linalg.solve_discrete_are on the matrices
bench_dare wrote, timed in the same run, and the relative residual of both
solutions computed here with one formula:
  ||A'XA - X - A'XB (R + B'XB)^-1 B'XA + Q||_F / max(1, ||Q||_F + ||X||_F).
usage: bench_dare_ref.py N REPS DIR -> prints "median_us res_scipy res_fracdesign"
"""
import sys
import time

import numpy as np
import scipy.linalg as sl


def residual(A, B, Q, R, X):
    AXB = A.T @ X @ B
    res = A.T @ X @ A - X - AXB @ np.linalg.solve(R + B.T @ X @ B, AXB.T) + Q
    return np.linalg.norm(res) / max(1.0, np.linalg.norm(Q) + np.linalg.norm(X))


def main():
    n, reps, d = int(sys.argv[1]), int(sys.argv[2]), sys.argv[3]
    load = lambda name: np.atleast_2d(np.loadtxt(f"{d}/{name}_{n}.txt"))
    A, Q, R, Xf = load("A"), load("Q"), load("R"), load("X")
    B = np.loadtxt(f"{d}/B_{n}.txt").reshape(n, -1)
    times = []
    for _ in range(reps):
        t0 = time.perf_counter()
        X = sl.solve_discrete_are(A, B, Q, R)
        times.append((time.perf_counter() - t0) * 1e6)
    times.sort()
    print(f"{times[len(times) // 2]:.1f} {residual(A, B, Q, R, X):.3e} {residual(A, B, Q, R, Xf):.3e}")


main()
