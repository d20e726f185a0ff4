"""Reference for bench_ident: scipy.optimize.least_squares on the same residual.

Reads DIR/frf.csv (w_rad_s, re, im) and DIR/starts.txt (per fit: structure,
weighting, n, box, start points) written by bench_ident, and fits every
structure/weighting from the same start points with the same residual:
sqrt(W_p) (Re, Im)(G_exp - G), zeta and gamma as logarithms, same bounds
(seed 000 eq. 25 with the corrected beta^4 of notes 000 sec. 2.3; weights of
eq. 27). Trust-region reflective with a 2-point finite-difference Jacobian
(scipy's default for bounded problems). Prints: structure weighting J
CPU seconds (time.process_time, as bench_ident measures its own).
usage: bench_ident_ref.py DIR
"""
import sys
import time

import numpy as np
from scipy.optimize import least_squares

L, RHO, E, I = 0.98, 4.7e-3, 1.15e11, 7.85e-13
EI = E * I
NAMES = {1: ("zeta",), 2: ("gamma",), 3: ("zeta", "gamma"), 4: ("zeta", "alpha"),
         5: ("gamma", "lambda"), 6: ("zeta", "alpha", "gamma", "lambda")}
FIXED = {1: dict(alpha=1.0, gamma=0.0, lam=0.0), 2: dict(alpha=0.0, zeta=0.0, lam=1.0),
         3: dict(alpha=1.0, lam=1.0), 4: dict(gamma=0.0, lam=0.0), 5: dict(alpha=0.0, zeta=0.0), 6: {}}
ROMAN = {1: "I", 2: "II", 3: "III", 4: "IV", 5: "V", 6: "VI"}


def model(w, zeta, alpha, gamma, lam):
    s = 1j * w
    sa = w ** alpha * np.exp(1j * np.pi * alpha / 2)
    sl = w ** lam * np.exp(1j * np.pi * lam / 2)
    internal = 1 + zeta * sa
    b4 = -((RHO / EI) * s ** 2 + gamma * sl) / internal
    b = b4 ** 0.25
    x = b * L
    return -EI * internal * b * (np.sin(x) * np.cosh(x) - np.cos(x) * np.sinh(x)) / (1 + np.cos(x) * np.cosh(x))


def main():
    d = sys.argv[1]
    data = np.loadtxt(d + "/frf.csv", delimiter=",", skiprows=1)
    w, g = data[:, 0], data[:, 1] + 1j * data[:, 2]
    total = 0.0
    for line in open(d + "/starts.txt"):
        v = line.split()
        st, wt, n = int(v[0]), int(v[1]), int(v[2])
        box = np.array(v[3:3 + 2 * n], float).reshape(n, 2)
        x0s = np.array(v[3 + 2 * n:], float).reshape(-1, n)
        W = np.full(w.size, 1.0 / w.size) if wt == 0 else (1 / w) / np.sum(1 / w)
        sw = np.sqrt(W)
        names = NAMES[st]

        def resid(x):
            p = dict(zeta=0.0, alpha=0.0, gamma=0.0, lam=0.0)
            p.update(FIXED[st])
            for name, xi in zip(names, x):
                key = "lam" if name == "lambda" else name
                p[key] = np.exp(xi) if name in ("zeta", "gamma") else xi
            e = sw * (g - model(w, p["zeta"], p["alpha"], p["gamma"], p["lam"]))
            return np.concatenate([e.real, e.imag])

        t0 = time.process_time()
        best = np.inf
        with np.errstate(all="ignore"):
            for x0 in x0s:
                r = least_squares(resid, x0, bounds=(box[:, 0], box[:, 1]), method="trf",
                                  ftol=1e-14, xtol=1e-12, gtol=1e-15, max_nfev=200 * (n + 1))
                best = min(best, 2 * r.cost)
        dt = time.process_time() - t0
        total += dt
        print(f"{ROMAN[st]} {'const' if wt == 0 else '1/w'} {best:.10g} {dt:.4f}")
    print(f"total {total:.4f}")


if __name__ == "__main__":
    main()
