"""libfrac's per-cycle objects over numpy arrays (libfrac/include/frac/).

Each class owns one libfrac object and its storage; ``run`` calls the C step
once per sample in a compiled loop, so the outputs are libfrac's bit for bit
(python/tests/test_libfrac.py compares them with a plain C loop). Parameters
are the C structs' fields; construction errors raise ValueError naming the
init function and the frac_status, e.g. ``frac_fo_init: FRAC_E_ORDER ...``.
Per-sample statuses (``status=True``) are frac_status codes: 0 ok, > 0
warnings (clamped, saturated, measurement skipped), < 0 errors (the output
then holds its last finite value and the state is untouched).

A realization of s^r (``op``): ``{"method": "gl", "memory": L}``,
``{"method": "oustaloup" | "oustaloup_refined", "wb": .., "wh": .., "n": N}``
or ``{"method": "cfe_tustin" | "cfe_alalaoui", "n": order}`` (fo_op.h).
"""
from __future__ import annotations

from typing import Dict, Optional, Sequence, Tuple, Union

import numpy as np

from . import _fracarm

ArrayLike = Union[np.ndarray, Sequence[float]]
METHODS = ("gl", "oustaloup", "oustaloup_refined", "cfe_tustin", "cfe_alalaoui")


def status_str(code: int) -> str:
    """The name of a frac_status code."""
    return _fracarm.status_str(int(code))


class FoOperator:
    """y = s^order x in one of libfrac's realizations (fo_op.h): GL, Oustaloup, refined Oustaloup, CFE."""

    def __init__(self, order: float, ts: float, method: str = "gl", memory: int = 0, wb: float = 0.0,
                 wh: float = 0.0, n: int = 0):
        self._c = _fracarm.FoOperator(float(order), float(ts),
                                      {"method": method, "memory": int(memory), "wb": float(wb), "wh": float(wh), "n": int(n)})

    def step(self, x: float) -> float:
        """One sample."""
        return self._c.step(float(x))

    def run(self, x: ArrayLike, status: bool = False):
        """Steps every sample of x (continuing from the current state); y, or (y, statuses)."""
        return self._c.run(np.ascontiguousarray(x, dtype=float), status)

    def reset(self) -> None:
        """Zero state."""
        self._c.reset()

    def freqresp(self, w: float) -> complex:
        """Frequency response of the discrete realization at w rad/s (<= pi/ts)."""
        re, im = self._c.freqresp(float(w))
        return complex(re, im)


class FoPid:
    """PI^lam D^mu with derivative filter, limits, anti-windup, bumpless transfer (fopid.h).

    u = kp (b r - y) + ki s^-lam (r - y) + kd s^mu/(1 + tf s) (c r - y) + delta y.
    antiwindup: "none", "clamp" or "backcalc" (time constant tt).
    """

    def __init__(self, ts: float, kp: float = 0.0, ki: float = 0.0, kd: float = 0.0, lam: float = 1.0,
                 mu: float = 1.0, tf: float = 0.0, b: float = 1.0, c: float = 1.0, delta: float = 0.0,
                 umin: float = -np.inf, umax: float = np.inf, antiwindup: str = "none", tt: float = 1.0,
                 op: Optional[Dict] = None):
        self._c = _fracarm.FoPid(dict(ts=float(ts), kp=float(kp), ki=float(ki), kd=float(kd), lam=float(lam),
                                      mu=float(mu), tf=float(tf), b=float(b), c=float(c), delta=float(delta),
                                      umin=float(umin), umax=float(umax), antiwindup=antiwindup, tt=float(tt),
                                      op=dict(op or {"method": "gl", "memory": 256})))

    def step(self, r: float, y: float) -> float:
        return self._c.step(float(r), float(y))

    def run(self, r: ArrayLike, y: ArrayLike, status: bool = False):
        """u for every sample of (r, y); u, or (u, statuses)."""
        return self._c.run(np.ascontiguousarray(r, dtype=float), np.ascontiguousarray(y, dtype=float), status)

    def set_mode(self, mode: str) -> None:
        """"auto" or "manual" (bumpless both ways)."""
        self._c.set_mode(mode)

    def set_manual(self, u: float) -> None:
        self._c.set_manual(float(u))

    def reset(self) -> None:
        self._c.reset()


class FoDamp:
    """The collocated fractional damping law of seed 002 with its prefilter (fodamp.h).

    u = F(s) ref - C(s) meas, C = kc s^alpha N(s)/(s^m D(s)), F = (1 + fa s^fbeta)/(1 + fb s).
    """

    def __init__(self, ts: float, kc: float, alpha: float, m: int = 0, n1: float = 0.0, n2: float = 0.0,
                 d1: float = 0.0, d2: float = 0.0, fa: float = 0.0, fbeta: float = 0.0, fb: float = 0.0,
                 op: Optional[Dict] = None):
        self._c = _fracarm.FoDamp(dict(ts=float(ts), kc=float(kc), alpha=float(alpha), m=int(m), n1=float(n1),
                                       n2=float(n2), d1=float(d1), d2=float(d2), fa=float(fa), fbeta=float(fbeta),
                                       fb=float(fb), op=dict(op or {"method": "gl", "memory": 256})))

    def step(self, ref: float, meas: float) -> float:
        return self._c.step(float(ref), float(meas))

    def run(self, ref: ArrayLike, meas: ArrayLike, status: bool = False):
        return self._c.run(np.ascontiguousarray(ref, dtype=float), np.ascontiguousarray(meas, dtype=float), status)

    def reset(self) -> None:
        self._c.reset()


def _mat(a, name: str) -> np.ndarray:
    a = np.ascontiguousarray(a, dtype=float)
    return a.reshape(1, -1) if a.ndim == 1 and name in ("C",) else a


class Kalman:
    """Time-varying Kalman filter in Joseph form (kalman.h): x' = A x + B u + w, y = C x + v."""

    def __init__(self, A: ArrayLike, B: Optional[ArrayLike], C: ArrayLike, Q: ArrayLike, R: ArrayLike,
                 P0: ArrayLike, x0: Optional[ArrayLike] = None):
        A = np.atleast_2d(np.asarray(A, dtype=float))
        B = np.zeros((A.shape[0], 0)) if B is None else np.asarray(B, dtype=float).reshape(A.shape[0], -1)
        C = np.asarray(C, dtype=float).reshape(-1, A.shape[0])
        self._c = _fracarm.Kalman(A, B, C, np.atleast_2d(np.asarray(Q, dtype=float)),
                                  np.atleast_2d(np.asarray(R, dtype=float)), np.atleast_2d(np.asarray(P0, dtype=float)),
                                  None if x0 is None else np.asarray(x0, dtype=float))

    def predict(self, u: ArrayLike = ()) -> int:
        """Time update; returns the frac_status."""
        return self._c.predict(np.ascontiguousarray(u, dtype=float))

    def update(self, y: ArrayLike) -> int:
        """Measurement update with the finite entries of y; returns the frac_status."""
        return self._c.update(np.ascontiguousarray(y, dtype=float))

    def filter(self, U: ArrayLike, Y: ArrayLike, status: bool = False):
        """Per sample k: update with Y[k], record x (a posteriori), predict with U[k]. X (N x n)."""
        Y = np.asarray(Y, dtype=float)
        Y = Y.reshape(len(Y), -1)
        U = np.asarray(U, dtype=float).reshape(len(Y), -1)
        return self._c.filter(np.ascontiguousarray(U), np.ascontiguousarray(Y), status)

    def reset(self, x0: Optional[ArrayLike] = None) -> None:
        self._c.reset(None if x0 is None else np.asarray(x0, dtype=float))

    @property
    def x(self) -> np.ndarray:
        return self._c.x

    @property
    def P(self) -> np.ndarray:
        return self._c.P


class Lqg:
    """The state-difference LQG step with input and output delays (lqg.h, seed 004 (7.24)-(7.27)).

    n plant states, d_i input delay, d_o one delay per output; A (n x n), B (n),
    C (p x n), K (n_bar), L ((n_bar + 1) x p), n_bar = n + d_i + sum(d_o).
    """

    def __init__(self, A: ArrayLike, B: ArrayLike, C: ArrayLike, K: ArrayLike, L: ArrayLike, d_i: int = 0,
                 d_o: Sequence[int] = ()):
        A = np.atleast_2d(np.asarray(A, dtype=float))
        n = A.shape[0]
        C = np.asarray(C, dtype=float).reshape(-1, n)
        self._p = C.shape[0]
        self._c = _fracarm.Lqg(n, int(d_i), [int(d) for d in d_o], A, np.asarray(B, dtype=float).ravel(), C,
                               np.asarray(K, dtype=float).ravel(), np.asarray(L, dtype=float).reshape(-1, self._p))

    def run(self, u_star: ArrayLike, y_ref: ArrayLike, y: ArrayLike, status: bool = False):
        """Torque commands for N cycles: u_star (N), y_ref and y (N x p)."""
        u_star = np.ascontiguousarray(u_star, dtype=float).ravel()
        shape = (len(u_star), self._p)
        return self._c.run(u_star, np.ascontiguousarray(np.asarray(y_ref, dtype=float).reshape(shape)),
                           np.ascontiguousarray(np.asarray(y, dtype=float).reshape(shape)), status)

    def friction_estimate(self) -> float:
        return self._c.friction_estimate()

    def reset(self) -> None:
        self._c.reset()


class Lut1:
    """1-D lookup table on breakpoints x (lut.h): interp "linear" | "cubic" (Fritsch-Carlson), range "clamp" | "extrapolate"."""

    def __init__(self, x: ArrayLike, y: ArrayLike, interp: str = "linear", range: str = "clamp"):
        self._c = _fracarm.Lut1(np.ascontiguousarray(x, dtype=float), np.ascontiguousarray(y, dtype=float), interp, range)

    def __call__(self, xq: ArrayLike, status: bool = False):
        return self._c.eval(np.ascontiguousarray(xq, dtype=float).ravel(), status)

    def inverse(self, yq: ArrayLike, status: bool = False):
        """x = f^-1(y) for strictly monotone data."""
        return self._c.inverse(np.ascontiguousarray(yq, dtype=float).ravel(), status)


class Lut2:
    """2-D lookup table z[i, j] at (x1[i], x2[j]) (lut.h): bilinear or separable monotone cubic."""

    def __init__(self, x1: ArrayLike, x2: ArrayLike, z: ArrayLike, interp: str = "linear", range: str = "clamp"):
        self._c = _fracarm.Lut2(np.ascontiguousarray(x1, dtype=float), np.ascontiguousarray(x2, dtype=float),
                                np.ascontiguousarray(z, dtype=float), interp, range)

    def __call__(self, x1: ArrayLike, x2: ArrayLike, status: bool = False):
        return self._c.eval(np.ascontiguousarray(x1, dtype=float).ravel(), np.ascontiguousarray(x2, dtype=float).ravel(),
                            status)
