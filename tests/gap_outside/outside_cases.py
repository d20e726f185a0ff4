#!/usr/bin/python3
"""Outside-style evaluation of `fracdesign gap` (issue 17: ">= 90 % pooled on
further cases generated independently of this project").

Built from the user documentation only (docs/gap.md, docs/model_format.md,
README.md) and the `fracdesign gap` command line: no project code is imported
or called besides that executable. The simulators below are this file's own
(numpy/scipy): exact zero-order-hold discretisation of the linear part on
sub-steps, the nonlinear torques held over each sub-step, dry friction by
operator splitting (the friction impulse that stops the body within the
sub-step, limited to the friction level), Grunwald-Letnikov fractional
derivatives (Podlubny 1999, eq. 2.54; weights by the recursion
w_j = w_{j-1} (1 - (alpha + 1)/j)) on the sub-step grid with full memory;
the fractional process by its exact step response (numerical Laplace
inversion on Talbot's contour) summed over the held input's steps.

Plants (parameters drawn per case):
  arm      motor - gear spring - hub - link spring - tip (three inertias), PD
           loop on motor angle and velocity (1-sample delay), a gyro at the
           tip, a torque dither added after the controller;
  servo    rigid axis (voltage -> torque), PD with a filtered difference of
           the encoder, +-10 V clip; only the encoder is recorded;
  foprocess y = K e^{-tau s}/(1 + T s^lambda) u, open loop, multi-level steps.
Visibility rule: a drawn effect is kept only when it changes a compared
output's noise-free record over the held-out tail (the last 30 %, where the
tool measures its gap) by an rms of at least VIS x that output's noise std;
else its size is redrawn 1.5 x larger, at most 8 times; a case still below
is listed as not scored. The servo's backlash comes with a stiff gear
(80-150 Hz; a play needs two bodies) that the rigid nominal lacks: its
visibility is the play's own, against the same gear without play. An effect
that drives the machine unstable (its record 100 x the nominal's peak) is
redrawn, as a real drive would trip and leave no record.

CLI: outside_cases.py --cases N --seed S --fracdesign PATH --out DIR
     [--family arm|servo|foprocess] [--min-top1 F] [--rescore]
Cases are split evenly over the families (or all of --family).
"""
import argparse
import json
import math
import os
import subprocess
import sys
import time

import numpy as np
from scipy.linalg import expm

VIS = 5.0          # visibility: rms change >= VIS noise std on some output
SUB = 10           # simulation sub-steps per sample

EFFECTS = {
    "arm": ["none", "coulomb_friction", "viscous_friction", "stribeck_friction",
            "backlash", "deadzone", "saturation", "input_delay", "output_delay",
            "sensor_offset", "quantization", "gain_error", "fractional_damping",
            "unmodelled_mode"],
    "servo": ["none", "coulomb_friction", "viscous_friction", "stribeck_friction",
              "backlash", "deadzone", "saturation", "input_delay", "output_delay",
              "sensor_offset", "quantization", "gain_error", "unmodelled_mode"],
    "foprocess": ["none", "input_delay", "deadzone", "saturation", "backlash",
                  "gain_error", "sensor_offset", "quantization"],
}


def loguni(rng, lo, hi):
    return float(math.exp(rng.uniform(math.log(lo), math.log(hi))))


def zoh(A, B, h):
    """Exact zero-order hold of x' = A x + B u over h (Van Loan block exponential)."""
    n, m = B.shape
    M = np.zeros((n + m, n + m))
    M[:n, :n] = A
    M[:n, n:] = B
    E = expm(M * h)
    return E[:n, :n], E[:n, n:]


def gl_weights(alpha, n):
    w = np.empty(n)
    w[0] = 1.0
    for j in range(1, n):
        w[j] = w[j - 1] * (1.0 - (alpha + 1.0) / j)
    return w


class Play:
    """Backlash (play operator) of width w: output follows the input once the
    input has taken up the play."""
    def __init__(self, w, y0=0.0):
        self.w = w
        self.y = y0

    def __call__(self, x):
        if x - self.y > self.w / 2:
            self.y = x - self.w / 2
        elif self.y - x > self.w / 2:
            self.y = x + self.w / 2
        return self.y


def deadzone(u, lo, hi):
    if u > hi:
        return u - hi
    if u < lo:
        return u - lo
    return 0.0


def fric_level(e, v):
    """Friction level at velocity v of the truth's friction effect e (dict)."""
    if e["name"] == "coulomb_friction":
        return e["Fc"]
    if e["name"] == "stribeck_friction":
        return e["Fc"] + (e["Fs"] - e["Fc"]) * math.exp(-(v / e["vs"]) ** 2)
    return 0.0


class Mode2:
    """A second-order low-pass w^2/(s^2 + 2 zeta w s + w^2) (unit static gain),
    stepped exactly (zero-order hold of its input over h)."""
    def __init__(self, f, zeta, h, x0=0.0):
        w = 2 * math.pi * f
        A = np.array([[0.0, 1.0], [-w * w, -2 * zeta * w]])
        B = np.array([[0.0], [w * w]])
        self.Ad, self.Bd = zoh(A, B, h)
        self.x = np.array([x0, 0.0])

    def __call__(self, u):
        self.x = self.Ad @ self.x + self.Bd[:, 0] * u
        return self.x[0]


# ---------------------------------------------------------------- arm family
def draw_arm(rng):
    p = {}
    p["Ts"] = 0.001
    p["N"] = int(rng.choice([6000, 8000]))
    p["Jm"] = loguni(rng, 0.02, 0.2)          # motor (load side) kg m^2
    p["Jh"] = p["Jm"] * loguni(rng, 0.2, 1.0)  # hub
    p["Jt"] = p["Jm"] * loguni(rng, 0.3, 1.5)  # link + tip (lumped)
    fg = loguni(rng, 25, 60)                   # gear frequency (motor vs hub)
    fl = loguni(rng, 2.5, 8)                   # link frequency (hub vs tip)
    p["kg"] = (2 * math.pi * fg) ** 2 * p["Jm"] * p["Jh"] / (p["Jm"] + p["Jh"])
    p["kl"] = (2 * math.pi * fl) ** 2 * p["Jh"] * p["Jt"] / (p["Jh"] + p["Jt"])
    p["dg"] = 2 * rng.uniform(0.02, 0.06) * math.sqrt(p["kg"] * p["Jm"] * p["Jh"] / (p["Jm"] + p["Jh"]))
    p["dl"] = 2 * rng.uniform(0.005, 0.02) * math.sqrt(p["kl"] * p["Jh"] * p["Jt"] / (p["Jh"] + p["Jt"]))
    p["bm"] = loguni(rng, 0.005, 0.05) * p["Jm"] * 10
    Jtot = p["Jm"] + p["Jh"] + p["Jt"]
    wc = 2 * math.pi * loguni(rng, 0.8, 1.8)     # PD bandwidth below the link mode
    p["kp"] = Jtot * wc ** 2
    p["kd"] = Jtot * 2 * 0.8 * wc
    amp = rng.uniform(0.2, 0.8)
    p["ref"] = [(amp * rng.uniform(0.4, 1), loguni(rng, 0.2, 0.6), rng.uniform(0, 6.28)),
                (amp * rng.uniform(0.1, 0.4), loguni(rng, 0.8, 2.0), rng.uniform(0, 6.28))]
    p["dither"] = [(loguni(rng, 0.5, 6), rng.uniform(0, 6.28)) for _ in range(6)]
    p["dither_amp"] = 0.03 * p["kp"] * amp     # torque units
    p["noise_rel"] = [loguni(rng, 0.001, 0.004), loguni(rng, 0.002, 0.008), loguni(rng, 0.003, 0.01)]
    return p


def arm_matrices(p):
    Jm, Jh, Jt = p["Jm"], p["Jh"], p["Jt"]
    kg, kl, dg, dl, bm = p["kg"], p["kl"], p["dg"], p["dl"], p["bm"]
    # x = [th_m, th_h, th_t, w_m, w_h, w_t]
    A = np.zeros((6, 6))
    A[0, 3] = A[1, 4] = A[2, 5] = 1
    A[3, :] = [-kg / Jm, kg / Jm, 0, -(dg + bm) / Jm, dg / Jm, 0]
    A[4, :] = [kg / Jh, -(kg + kl) / Jh, kl / Jh, dg / Jh, -(dg + dl) / Jh, dl / Jh]
    A[5, :] = [0, kl / Jt, -kl / Jt, 0, dl / Jt, -dl / Jt]
    B = np.zeros((6, 1))
    B[3, 0] = 1 / Jm
    C = np.zeros((3, 6))
    C[0, 0] = 1
    C[1, 3] = 1
    C[2, 5] = 1
    # extra spring torque T (same sense as k q) of the gear q = th_m - th_h
    tg = np.array([0, 0, 0, -1 / Jm, 1 / Jh, 0])
    tl = np.array([0, 0, 0, 0, -1 / Jh, 1 / Jt])   # link q = th_h - th_t
    twg = np.array([1, -1, 0, 0, 0, 0.0])
    twl = np.array([0, 1, -1, 0, 0, 0.0])
    return A, B, C, tg, tl, twg, twl


def arm_reference(p, t):
    r = np.zeros_like(t)
    for a, f, ph in p["ref"]:
        r += a * (np.sin(2 * math.pi * f * t + ph) - math.sin(ph))
    ramp = np.clip(t / 0.5, 0, 1)
    ramp = 0.5 - 0.5 * np.cos(math.pi * ramp)
    d = np.zeros_like(t)
    for f, ph in p["dither"]:
        d += np.sin(2 * math.pi * f * t + ph)
    d *= p["dither_amp"] / math.sqrt(len(p["dither"]) / 2)
    return r * ramp, d * ramp


def sim_arm(p, eff):
    """Closed loop: u(k) = kp (r(k-1) - qm(k-1)) - kd vm(k-1) (one sample late),
    plus the dither; the effect eff (dict or None) acting where it lives."""
    Ts, N = p["Ts"], p["N"]
    h = Ts / SUB
    t = np.arange(N) * Ts
    ref, dith = arm_reference(p, t)
    A, B, C, tg, tl, twg, twl = arm_matrices(p)
    name = eff["name"] if eff else "none"
    Bx = np.column_stack([B[:, 0], tg, tl])
    Ad, Bd = zoh(A, Bx, h)
    x = np.zeros(6)
    y = np.zeros((N, 3))
    ucmd_prev = 0.0
    # effect state
    play = Play(eff["width"]) if name == "backlash" else None
    series = Mode2(eff["f"], eff["zeta"], h) if name == "unmodelled_mode" and eff["site"] == "actuator" else None
    sensor = Mode2(eff["f"], eff["zeta"], Ts) if name == "unmodelled_mode" and eff["site"] == "sensor" else None
    dsub = 0
    ubuf = None
    if name == "input_delay":
        dsub = int(round(eff["delay_s"] / h))
        ubuf = np.zeros(dsub + 1)
    odel = int(round(eff["delay_s"] / Ts)) if name == "output_delay" else 0
    ybuf = []
    if name == "fractional_damping":
        M = N * SUB + 1
        wgl = gl_weights(eff["alpha"], M)[::-1].copy()   # reversed for dot
        qhist = np.zeros(M)
        c_h = eff["c"] / h ** eff["alpha"]
    ks = 0
    for k in range(N):
        # the sensors at t_k
        yk = C @ x
        if sensor is not None:
            yk[2] = sensor(yk[2])
        ybuf.append(yk.copy())
        if odel:      # the tip gyro's reading is odel samples old
            yk[2] = ybuf[k - odel][2] if k >= odel else 0.0
        if name == "sensor_offset":
            yk[OUTS["arm"].index(eff["output"])] += eff["offset"]
        if name == "quantization":
            yk[0] = eff["step"] * round(yk[0] / eff["step"])
        y[k] = yk
        # controller on the previous sample's measurements (1-sample delay)
        if k == 0:
            u = 0.0
        else:
            u = p["kp"] * (ref[k - 1] - y[k - 1, 0]) - p["kd"] * y[k - 1, 1]
        u += dith[k]
        if name == "gain_error":
            u *= eff["gain"]
        if name == "deadzone":
            u = deadzone(u, eff["lower"], eff["upper"])
        if name == "saturation":
            u = min(max(u, eff["lower"]), eff["upper"])
        for s in range(SUB):
            ua = u
            if series is not None:
                ua = series(u)
            if ubuf is not None:
                ubuf = np.roll(ubuf, 1)
                ubuf[0] = ua
                ua = ubuf[dsub]
            Tg = Tl = 0.0
            if play is not None:
                q = twg @ x
                dz = q - min(max(q, -play.w / 2), play.w / 2)
                Tg = p["kg"] * (dz - q)     # spring k dz(q) minus the nominal k q
            if name == "fractional_damping":
                qhist[ks] = twl @ x
                # GL derivative at the sub-step start, the torque c D^alpha q
                Tl = c_h * (wgl[M - 1 - ks:] @ qhist[:ks + 1])
                ks += 1
            f_v = 0.0
            if name == "viscous_friction":
                f_v = eff["Fv"] * x[3]
            x = Ad @ x + Bd @ np.array([ua - f_v, Tg, Tl])
            if name in ("coulomb_friction", "stribeck_friction"):
                lev = fric_level(eff, x[3])
                g = Bd[3, 0]           # motor-speed change per unit torque over h
                x[3] -= min(abs(x[3]), lev * g) * math.copysign(1.0, x[3])
    return t, ref, dith, y


# -------------------------------------------------------------- servo family
def draw_servo(rng):
    p = {"Ts": 0.001, "N": int(rng.choice([5000, 6000]))}
    p["a"] = loguni(rng, 50, 600)         # Kt/J: rad/s^2 per V
    p["b"] = loguni(rng, 0.5, 8)          # viscous / J [1/s]
    wc = 2 * math.pi * loguni(rng, 4, 15)
    p["kp"] = wc ** 2 / p["a"]
    p["kd"] = 2 * 0.7 * wc / p["a"]
    p["alpha"] = math.exp(-2 * math.pi * loguni(rng, 80, 200) * p["Ts"])  # diff filter pole
    # moves: peak command reaches the +-10 V clip now and then
    moves = []
    tt = 0.2
    T = p["N"] * p["Ts"]
    pos = 0.0
    while tt < T:
        dur = rng.uniform(0.25, 0.8)
        amp = rng.uniform(0.3, 1.0) * 10 * p["a"] / (2 * math.pi / dur) ** 2 * 8
        target = pos + amp * rng.choice([-1, 1])
        moves.append((tt, dur, pos, target))
        pos = target
        tt += dur + rng.uniform(0.05, 0.4)
    p["moves"] = moves
    p["noise_abs"] = [loguni(rng, 3e-4, 3e-3)]      # encoder noise [rad]
    return p


def servo_reference(p, t):
    r = np.zeros_like(t)
    for (t0, dur, a, b) in p["moves"]:
        s = np.clip((t - t0) / dur, 0, 1)
        prof = s - np.sin(2 * math.pi * s) / (2 * math.pi)
        r = np.where(t >= t0, a + (b - a) * prof, r)
    return r


def servo_ctrl_matrices(p):
    a, Ts = p["alpha"], p["Ts"]
    g = (1 - a) / Ts
    Ac = np.array([[0.0, 0.0], [-g, a]])
    Bc = np.array([[0.0, 1.0], [0.0, g]])
    Cc = np.array([[p["kd"] * g, -p["kd"] * a]])
    Dc = np.array([[p["kp"], -p["kp"] - p["kd"] * g]])
    return Ac, Bc, Cc, Dc


def sim_servo(p, eff):
    Ts, N = p["Ts"], p["N"]
    h = Ts / SUB
    t = np.arange(N) * Ts
    ref = servo_reference(p, t)
    name = eff["name"] if eff else "none"
    a, b = p["a"], p["b"]
    Ac, Bc, Cc, Dc = servo_ctrl_matrices(p)
    two_mass = name == "backlash"
    if two_mass:
        # motor (share rm of the inertia) - stiff gear with play - load; encoder on the motor
        rm = eff["rm"]
        wg = 2 * math.pi * eff["fg"]
        Jm, Jl = rm, 1 - rm                  # inertias per unit total J
        kg = wg ** 2 * Jm * Jl / (Jm + Jl)
        dgear = 2 * eff["zg"] * math.sqrt(kg * Jm * Jl / (Jm + Jl))
        # x = [qm, ql, vm, vl]; torques per unit J: a u on the motor, b v viscous on both
        A = np.array([[0, 0, 1, 0], [0, 0, 0, 1],
                      [-kg / Jm, kg / Jm, -(b * Jm + dgear) / Jm, dgear / Jm],
                      [kg / Jl, -kg / Jl, dgear / Jl, -(b * Jl + dgear) / Jl]])
        Bx = np.array([[0, 0], [0, 0], [a / Jm, -1 / Jm], [0, 1 / Jl]])
    else:
        A = np.array([[0.0, 1.0], [0.0, -b]])
        Bx = np.array([[0.0], [a]])
    Ad, Bd = zoh(A, Bx, h)
    x = np.zeros(A.shape[0])
    xc = np.zeros(2)
    y = np.zeros((N, 1))
    series = Mode2(eff["f"], eff["zeta"], h) if name == "unmodelled_mode" else None
    dsub = int(round(eff["delay_s"] / h)) if name == "input_delay" else 0
    ubuf = np.zeros(dsub + 1)
    odel = int(round(eff["delay_s"] / Ts)) if name == "output_delay" else 0
    qtrue = []
    meas = 0.0
    for k in range(N):
        # the encoder reading at k
        q = x[0]
        qtrue.append(q)
        m = qtrue[k - odel] if k >= odel else 0.0
        if name == "sensor_offset":
            m += eff["offset"]
        if name == "quantization":
            m = eff["step"] * round(m / eff["step"])
        y[k, 0] = m
        w = np.array([ref[k], m])
        u = (Cc @ xc + Dc @ w).item()
        xc = Ac @ xc + Bc @ w
        u = min(max(u, -10.0), 10.0)
        if name == "gain_error":
            u *= eff["gain"]
        if name == "deadzone":
            u = deadzone(u, eff["lower"], eff["upper"])
        if name == "saturation":
            u = min(max(u, eff["lower"]), eff["upper"])
        for s in range(SUB):
            ua = u
            if series is not None:
                ua = series(u)
            if dsub:
                ubuf = np.roll(ubuf, 1)
                ubuf[0] = ua
                ua = ubuf[dsub]
            if two_mass:
                qg = x[0] - x[1]
                dz = qg - min(max(qg, -eff["width"] / 2), eff["width"] / 2)
                Tg = kg * (dz - qg)
                x = Ad @ x + Bd @ np.array([ua, Tg])
            else:
                fv = eff["Fv"] * x[1] if name == "viscous_friction" else 0.0
                x = Ad @ x + Bd[:, 0] * (ua - fv)
                if name in ("coulomb_friction", "stribeck_friction"):
                    lev = fric_level(eff, x[1])
                    g = Bd[1, 0]
                    x[1] -= min(abs(x[1]), lev * g) * math.copysign(1.0, x[1])
    return t, ref, y


# ----------------------------------------------------------- foprocess family
def draw_fop(rng):
    p = {}
    p["lam"] = rng.uniform(0.4, 1.8)
    tc = loguni(rng, 0.1, 3.0)                     # time scale T^(1/lambda) [s]
    p["T"] = tc ** p["lam"]
    p["K"] = loguni(rng, 0.5, 5)
    p["tau"] = rng.uniform(0, 0.5) * tc
    p["Ts"] = float(rng.choice([0.005, 0.01, 0.02]))
    Trec = max(40 * tc, 20.0)
    p["N"] = int(min(max(Trec / p["Ts"], 1500), 4000))
    # multi-level steps, some held long enough to settle
    levels = []
    tt = 0.0
    T = p["N"] * p["Ts"]
    hold_hi = min(6.0 * tc, T / 8)
    hold_lo = min(1.0 * tc, hold_hi / 2)
    tt = rng.uniform(0.02, 0.08) * T
    bias = rng.uniform(-1, 1) if rng.uniform() < 0.5 else 0.0
    while tt < T:
        levels.append((tt, bias + rng.uniform(-1, 1) * 2))
        tt += rng.uniform(hold_lo, hold_hi)
    p["steps"] = levels
    p["noise_rel"] = [loguni(rng, 0.002, 0.008)]
    return p


def fop_input(p, t):
    u = np.zeros_like(t)
    for t0, lev in p["steps"]:
        u = np.where(t >= t0, lev, u)
    return u


def fop_step(p, tt):
    """Step response K (1 - E_lambda(-t^lambda / T)) of K/(1 + T s^lambda) at
    the times tt > 0, by numerical inversion of its Laplace transform
    K/(s (1 + T s^lambda)) on Talbot's contour (the fixed Talbot method:
    Abate & Valko, Int. J. Numer. Meth. Eng. 60, 2004, eq. (27)); M = 24
    nodes give about 1e-10 relative in double precision. Exact in the input's
    steps, unlike a Grunwald-Letnikov scheme, whose error at each step is of
    order h^lambda (Richardson's extrapolation, which assumes an expansion
    in h, does not remove it: at lambda = 0.44 it left a 50 Hz residual that
    a correct tool names an unmodelled mode)."""
    M = 24
    tt = np.asarray(tt, dtype=float).reshape(-1, 1)
    r = 2.0 * M / (5.0 * tt)
    th = (np.arange(1, M) * np.pi / M).reshape(1, -1)
    cot = 1.0 / np.tan(th)
    sk = r * th * (cot + 1j)
    sig = th + (th * cot - 1.0) * cot
    K, T, lam = p["K"], p["T"], p["lam"]
    # For 1 < lambda <= 2 the principal sheet holds the pole pair
    # s_p = T^(-1/lambda) e^(+-i pi/lambda) (residue of F: -K/lambda each),
    # which the contour need not enclose at large t: it is subtracted from F
    # and its response -(2K/lambda) e^(Re s_p t) cos(Im s_p t) added back.
    sp = T ** (-1.0 / lam) * np.exp(1j * np.pi / lam) if lam > 1 else None

    def F(z):
        f = K / (z * (1.0 + T * z ** lam))
        if sp is not None:
            f = f + (K / lam) * (1.0 / (z - sp) + 1.0 / (z - np.conj(sp)))
        return f
    acc = 0.5 * np.real(F(r) * np.exp(r * tt)) + np.sum(np.real(np.exp(tt * sk) * F(sk) * (1.0 + 1j * sig)), axis=1,
                                                         keepdims=True)
    y = (r / M * acc).ravel()
    if sp is not None:
        y -= (2.0 * K / lam) * np.exp(sp.real * tt.ravel()) * np.cos(sp.imag * tt.ravel())
    return y


def sim_fop(p, eff):
    """y = K e^{-(tau + extra) s}/(1 + T s^lambda) u for u held (zero order)
    between samples: the sum of the held input's steps times the step
    response (fop_step), each delayed."""
    Ts, N = p["Ts"], p["N"]
    t = np.arange(N) * Ts
    u = fop_input(p, t)
    name = eff["name"] if eff else "none"
    ue = u.copy()
    if name == "gain_error":
        ue = ue * eff["gain"]
    if name == "deadzone":
        ue = np.array([deadzone(v, eff["lower"], eff["upper"]) for v in ue])
    if name == "saturation":
        ue = np.clip(ue, eff["lower"], eff["upper"])
    if name == "backlash":
        pl = Play(eff["width"])
        ue = np.array([pl(v) for v in ue])
    delay = p["tau"] + (eff["delay_s"] if name == "input_delay" else 0.0)
    du = np.diff(np.concatenate([[0.0], ue]))
    y = np.zeros(N)
    for j in np.nonzero(du)[0]:
        # the input's step at sample j acts from j Ts + delay; the reading at
        # k Ts holds its response only for k Ts > j Ts + delay
        age = t - j * Ts - delay
        on = age > 1e-12
        if np.any(on):
            y[on] += du[j] * fop_step(p, age[on])
    if name == "sensor_offset":
        y = y + eff["offset"]
    return t, u, y.reshape(-1, 1)


# ------------------------------------------------------------ effect drawing
def draw_effect(fam, name, p, rng, scale, scales):
    """The effect's size, scaled up by `scale` on redraws. scales holds the
    effect-free record's magnitudes (peak command, rms velocity, ...)."""
    e = {"name": name}
    umax, vrms, yrms = scales["umax"], scales["vrms"], scales["yrms"]
    Ts = p["Ts"]
    if name == "none":
        return None
    if name == "coulomb_friction":
        e["Fc"] = rng.uniform(0.04, 0.12) * umax * scale
    elif name == "stribeck_friction":
        e["Fc"] = rng.uniform(0.04, 0.1) * umax * scale
        e["Fs"] = e["Fc"] * rng.uniform(1.6, 2.5)
        e["vs"] = rng.uniform(0.05, 0.2) * vrms
    elif name == "viscous_friction":
        e["Fv"] = rng.uniform(0.05, 0.2) * umax / vrms * scale
    elif name == "backlash":
        if fam == "arm":
            e["width"] = rng.uniform(0.5, 2.0) * scales["qg_rms"] * scale
        elif fam == "servo":
            e["width"] = rng.uniform(0.002, 0.01) * scale      # rad of play
            e["rm"] = rng.uniform(0.3, 0.7)
            e["fg"] = rng.uniform(80, 150)
            e["zg"] = rng.uniform(0.1, 0.2)
        else:
            e["width"] = rng.uniform(0.1, 0.3) * umax * scale
    elif name == "deadzone":
        a = rng.uniform(0.05, 0.15) * umax * scale
        asym = rng.uniform(0.6, 1.4) if rng.uniform() < 0.5 else 1.0
        e["lower"], e["upper"] = -a, a * asym
    elif name == "saturation":
        lo = rng.uniform(0.45, 0.75) / scale
        hi = lo * (rng.uniform(0.7, 1.3) if rng.uniform() < 0.5 else 1.0)
        e["lower"], e["upper"] = -lo * scales["uneg"], min(hi, 0.95) * scales["upos"]
    elif name == "input_delay":
        e["delay_s"] = rng.uniform(1.5, 6) * Ts * scale
    elif name == "output_delay":
        e["delay_s"] = int(round(rng.uniform(2, 6) * scale)) * Ts
        e["output"] = {"arm": "r_tip", "servo": "q"}[fam]
    elif name == "sensor_offset":
        # arm: the encoder (in the loop) or the tip gyro (outside it)
        e["output"] = str(rng.choice(["q_m", "r_tip"])) if fam == "arm" else \
            {"servo": "q", "foprocess": "y"}[fam]
        j = OUTS[fam].index(e["output"])
        e["offset"] = float(rng.choice([-1, 1]) * rng.uniform(0.03, 0.1) * scales["ystd"][j] * scale)
    elif name == "quantization":
        e["output"] = {"arm": "q_m", "servo": "q", "foprocess": "y"}[fam]
        e["step"] = max(rng.uniform(0.005, 0.02) * yrms * scale, 6 * scales["noise0"])
    elif name == "gain_error":
        d = rng.uniform(0.15, 0.3) * min(scale, 2)
        e["gain"] = 1 + d if rng.uniform() < 0.5 else 1 / (1 + d)
    elif name == "fractional_damping":
        e["alpha"] = rng.uniform(0.3, 0.8)
        wl = 2 * math.pi * scales["fl"]
        zeta = rng.uniform(0.02, 0.06) * scale
        # added damping ratio at the link mode: zeta = c w^alpha sin(pi alpha/2)/(2 k w^0) / w ... (k = kl)
        e["c"] = 2 * zeta * p["kl"] / (wl ** e["alpha"] * math.sin(math.pi * e["alpha"] / 2))
    elif name == "unmodelled_mode":
        if fam == "arm":
            e["site"] = rng.choice(["actuator", "sensor"])
            e["f"] = rng.uniform(12, 40) if e["site"] == "actuator" else rng.uniform(20, 60)
        else:
            e["site"] = "actuator"
            e["f"] = rng.uniform(15, 45)
        e["zeta"] = rng.uniform(0.03, 0.1) / min(scale, 2)
    return e


def simulate(fam, p, eff):
    if fam == "arm":
        t, ref, dith, y = sim_arm(p, eff)
        return {"t": t, "q_ref": ref, "dither": dith}, y
    if fam == "servo":
        t, ref, y = sim_servo(p, eff)
        return {"t": t, "q_ref": ref}, y
    t, u, y = sim_fop(p, eff)
    return {"t": t, "u": u}, y


OUTS = {"arm": ["q_m", "v_m", "r_tip"], "servo": ["q"], "foprocess": ["y"]}


# --------------------------------------------------------------- documents
def nominal_doc(fam, p, noise):
    if fam == "arm":
        A, B, C, tg, tl, twg, twl = arm_matrices(p)
        ctrl = {"time": "discrete", "Ts": p["Ts"], "A": [[0.0]], "B": [[0.0, 0.0, 0.0]],
                "C": [[0.0]], "D": [[p["kp"], -p["kp"], -p["kd"]]]}
        doc = {"schema": "frac.model", "version": 1, "kind": "statespace", "units": "SI",
               "name": "outside arm", "time": "continuous",
               "A": A.tolist(), "B": B.tolist(), "C": C.tolist(), "D": [[0.0]] * 3,
               "inputs": ["u"], "outputs": OUTS["arm"],
               "gap": {"velocity": "v_m", "force_input": "u",
                       "coupling": [
                           {"name": "gear", "twist": twg.tolist(), "torque": tg.tolist(),
                            "stiffness": p["kg"]},
                           {"name": "link", "twist": twl.tolist(), "torque": tl.tolist(),
                            "stiffness": p["kl"]}],
                       "closed_loop": {"references": ["q_ref"], "measured": ["q_m", "v_m"],
                                       "controller": ctrl, "delay_samples": 1,
                                       "additive": ["dither"]},
                       "initial_state": "at_rest",
                       "noise": dict(zip(OUTS["arm"], noise)),
                       "units": {"u": "N m", "q_m": "rad", "v_m": "rad/s", "r_tip": "rad/s"}}}
        doc["gap"]["coupling"][0]["unit"] = "rad"
        return doc
    if fam == "servo":
        Ac, Bc, Cc, Dc = servo_ctrl_matrices(p)
        return {"schema": "frac.model", "version": 1, "kind": "statespace", "units": "SI",
                "name": "outside servo", "time": "continuous",
                "A": [[0.0, 1.0], [0.0, -p["b"]]], "B": [[0.0], [p["a"]]],
                "C": [[1.0, 0.0], [0.0, 1.0]], "D": [[0.0], [0.0]],
                "inputs": ["u"], "outputs": ["q", "v"],
                "gap": {"velocity": "v", "force_input": "u",
                        "closed_loop": {"references": ["q_ref"], "measured": ["q"],
                                        "controller": {"time": "discrete", "Ts": p["Ts"],
                                                       "A": Ac.tolist(), "B": Bc.tolist(),
                                                       "C": Cc.tolist(), "D": Dc.tolist()},
                                        "delay_samples": 0, "saturation": 10.0},
                        "initial_state": "at_rest",
                        "noise": {"q": noise[0]},
                        "units": {"u": "V", "q": "rad", "v": "rad/s"}}}
    return {"schema": "frac.model", "version": 1, "kind": "foprocess", "units": "SI",
            "K": p["K"], "T": p["T"], "lambda": p["lam"], "tau": p["tau"],
            "inputs": ["u"], "outputs": ["y"],
            "gap": {"initial_state": "at_rest", "noise": {"y": noise[0]}}}


# ----------------------------------------------------------------- one case
def make_case(fam, label, seed, case_dir):
    rng = np.random.default_rng(seed)
    p = {"arm": draw_arm, "servo": draw_servo, "foprocess": draw_fop}[fam](rng)
    cols0, y0 = simulate(fam, p, None)
    ystd = y0.std(axis=0)
    if "noise_abs" in p:
        noise = [float(v) for v in p["noise_abs"]]
    else:
        noise = [float(r * s) for r, s in zip(p["noise_rel"], ystd)]
    scales = {"yrms": float(ystd[0]), "noise0": noise[0], "ystd": [float(v) for v in ystd]}
    if fam == "arm":
        # effect-free command (recomputed from the recorded signals)
        u = np.zeros(p["N"])
        u[1:] = p["kp"] * (cols0["q_ref"][:-1] - y0[:-1, 0]) - p["kd"] * y0[:-1, 1]
        u += cols0["dither"]
        scales["vrms"] = float(y0[:, 1].std())
        scales["fl"] = math.sqrt(p["kl"] * (p["Jh"] + p["Jt"]) / (p["Jh"] * p["Jt"])) / (2 * math.pi)
        # gear twist from a state replay is not recorded: estimate from the torque
        scales["qg_rms"] = float(np.std(u) / p["kg"])
    elif fam == "servo":
        Ac, Bc, Cc, Dc = servo_ctrl_matrices(p)
        xc = np.zeros(2)
        u = np.zeros(p["N"])
        for k in range(p["N"]):
            w = np.array([cols0["q_ref"][k], y0[k, 0]])
            u[k] = min(max((Cc @ xc + Dc @ w).item(), -10), 10)
            xc = Ac @ xc + Bc @ w
        scales["vrms"] = float(np.std(np.diff(y0[:, 0])) / p["Ts"])
    else:
        u = cols0["u"]
        scales["vrms"] = 1.0
    scales["umax"] = float(np.max(np.abs(u)))
    scales["upos"] = float(max(np.max(u), 1e-9))
    scales["uneg"] = float(max(-np.min(u), 1e-9))
    eff = None
    vis = vis_tail = 0.0
    scale = 1.0
    for attempt in range(9):
        eff = draw_effect(fam, label, p, rng, scale, scales)
        if eff is None:
            cols, y = cols0, y0
            break
        cols, y = simulate(fam, p, eff)
        # a machine the effect drives unstable (e.g. a lightly damped series
        # mode inside the loop's bandwidth) trips its drive: no record, redraw
        if not np.all(np.isfinite(y)) or np.max(np.abs(y)) > 100 * np.max(np.abs(y0)):
            scale *= 0.7
            continue
        # the servo's play needs two bodies: it comes with a stiff gear the
        # rigid nominal lacks; its visibility is the play's own (against the
        # same gear without play), else the gear alone could carry the label
        yv = y0
        if fam == "servo" and label == "backlash":
            yv = simulate(fam, p, dict(eff, width=0.0))[1]
        vis = float(np.max(np.sqrt(np.mean((y - yv) ** 2, axis=0)) / np.array(noise)))
        tail = int(0.7 * len(y))
        vis_tail = float(np.max(np.sqrt(np.mean((y[tail:] - yv[tail:]) ** 2, axis=0))
                                / np.array(noise)))
        if label == "quantization" and fam == "foprocess":
            # applied to the reading below (outside any loop): visible as the
            # lattice, the step being >= 6 noise std by its draw
            vis = vis_tail = eff["step"] / noise[0]
        if vis_tail >= VIS:
            break
        scale *= 1.5
    nrng = np.random.default_rng(seed + 7919)
    yn = y + nrng.standard_normal(y.shape) * np.array(noise)
    if label == "quantization":
        # the quantized channel is the reading itself (the noise is dithered before)
        j = OUTS[fam].index(eff["output"])
        yn[:, j] = eff["step"] * np.round(yn[:, j] / eff["step"])
    os.makedirs(case_dir, exist_ok=True)
    names = [k for k in cols if k != "t"]
    with open(os.path.join(case_dir, "record.csv"), "w") as f:
        f.write(",".join(["t"] + names + OUTS[fam]) + "\n")
        for k in range(len(cols["t"])):
            row = [cols["t"][k]] + [cols[n][k] for n in names] + list(yn[k])
            f.write(",".join("%.9g" % v for v in row) + "\n")
    doc = nominal_doc(fam, p, noise)
    with open(os.path.join(case_dir, "nominal.json"), "w") as f:
        json.dump(doc, f, indent=1)
    truth = {"family": fam, "label": label, "effect": eff, "visibility": vis, "visibility_heldout": vis_tail,
             "noise": noise, "seed": seed}
    with open(os.path.join(case_dir, "truth.json"), "w") as f:
        json.dump(truth, f, indent=1, default=float)
    return truth


def true_params(truth):
    """Tool parameter name -> true value, where comparable (docs/gap.md table)."""
    e = truth["effect"]
    if e is None:
        return {}
    n = e["name"]
    if n == "coulomb_friction":
        return {"Fc": e["Fc"]}
    if n == "stribeck_friction":
        return {"Fc": e["Fc"], "Fs": e["Fs"]}
    if n == "viscous_friction":
        return {"Fv": e["Fv"]}
    if n == "backlash":
        # the servo's play is in its gear (the tool's gear site): its width in rad
        return {"width": e["width"]}
    if n in ("deadzone", "saturation"):
        return {"lower": e["lower"], "upper": e["upper"]}
    if n == "input_delay":
        return {"delay_s": e["delay_s"]}
    if n == "output_delay":
        return {"delay_s_" + e["output"]: e["delay_s"]}
    if n == "sensor_offset":
        return {"offset_" + e["output"]: e["offset"]}
    if n == "quantization":
        return {"step_" + e["output"]: e["step"]}
    if n == "gain_error":
        return {"gain": e["gain"]}
    if n == "fractional_damping":
        return {"alpha": e["alpha"], "c": e["c"]}
    if n == "unmodelled_mode":
        return {"f_hz": e["f"]}
    return {}


def run_case(fd, case_dir, fam):
    out = os.path.join(case_dir, "gap")
    cmd = [fd, "gap", "--model", os.path.join(case_dir, "nominal.json"),
           "--data", os.path.join(case_dir, "record.csv"), "--out", out]
    if fam == "servo":
        cmd += ["--outputs", "q"]
    t0 = time.time()
    r = subprocess.run(cmd, capture_output=True, text=True)
    dt = time.time() - t0
    with open(os.path.join(case_dir, "command.txt"), "w") as f:
        f.write(" ".join(cmd) + "\n")
    if r.returncode != 0:
        return {"error": (r.stderr.strip().splitlines() or ["exit %d" % r.returncode])[-1],
                "seconds": dt}
    got = parse_result(os.path.join(out, "result.json"))
    got["seconds"] = dt
    return got


def parse_result(path):
    """The verdict's first effect, its parameters and site, and the look-alikes
    the tool names for it (verdict.confidence.look_alikes, docs/gap.md)."""
    with open(path) as f:
        res = json.load(f)
    v = res["verdict"]
    effs = v.get("effects", [])
    first = effs[0] if effs else "none"
    params = v.get("params", {})
    if len(effs) > 1:
        params = {k.split(".", 1)[1]: val for k, val in params.items()
                  if k.startswith(first + ".")}
    site = None
    for c in res.get("candidates", []):
        if c.get("effect") == first:
            site = c.get("site"), c.get("coupling")
            break
    looks = [x.get("effect") for x in (v.get("confidence") or {}).get("look_alikes", [])]
    return {"first": first, "effects": effs, "params": params, "shrink": v.get("shrink"),
            "site": site, "look_alikes": looks, "seconds": res.get("seconds", 0.0)}


def param_error(truth, got):
    tp = true_params(truth)
    if not tp:
        return None
    errs = []
    for k, tv in tp.items():
        gv = got["params"].get(k)
        errs.append(1.0 if gv is None else abs(gv - tv) / abs(tv))
    return float(np.mean(errs))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--cases", type=int, default=12)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--fracdesign", required=True)
    ap.add_argument("--out", required=True)
    ap.add_argument("--family", choices=list(EFFECTS))
    ap.add_argument("--min-top1", type=float, default=None,
                    help="exit 1 when the pooled top-1 accuracy is below this fraction")
    ap.add_argument("--rescore", action="store_true",
                    help="score the cases already in --out (truth.json, gap/result.json) again")
    args = ap.parse_args()
    fams = [args.family] if args.family else list(EFFECTS)
    # labels in shuffled rounds per family, so each occurs about equally often
    rng = np.random.default_rng(args.seed)
    plan = []
    per = [args.cases // len(fams) + (1 if i < args.cases % len(fams) else 0)
           for i in range(len(fams))]
    for fam, n in zip(fams, per):
        labels = []
        while len(labels) < n:
            rnd = list(EFFECTS[fam])
            rng.shuffle(rnd)
            labels += rnd
        for i in range(n):
            plan.append((fam, labels[i], args.seed * 100003 + len(plan) * 7 + 1))
    rows = []
    for i, (fam, label, seed) in enumerate(plan):
        cdir = os.path.join(args.out, "case_%03d_%s_%s" % (i, fam, label))
        t0 = time.time()
        if args.rescore:
            with open(os.path.join(cdir, "truth.json")) as f:
                truth = json.load(f)
            got = parse_result(os.path.join(cdir, "gap", "result.json"))
            tg = 0.0
        else:
            truth = make_case(fam, label, seed, cdir)
            tg = time.time() - t0
            got = run_case(args.fracdesign, cdir, fam)
        ok = got.get("first") == label
        got["look_alike_hit"] = ok or label in got.get("look_alikes", [])
        # an effect the held-out tail does not show (e.g. an in-loop offset of a
        # tracking loop that started at rest: only its start transient differs)
        # is reported but not scored
        truth["scored"] = label == "none" or truth["visibility_heldout"] >= VIS
        perr = param_error(truth, got) if ok else None
        rows.append((i, fam, label, truth, got, ok, perr))
        print("case %3d %-9s %-18s -> %-18s %s vis %.0f/%.0f  gen %.1fs diag %.1fs%s" % (
            i, fam, label, got.get("first", "ERROR"), "ok  " if ok else "MISS",
            truth["visibility"], truth["visibility_heldout"], tg, got["seconds"],
            "" if perr is None else "  param err %.1f %%" % (100 * perr)), flush=True)
        if "error" in got:
            print("   error: " + got["error"], flush=True)
    unscored = [x for x in rows if not x[3]["scored"]]
    if unscored:
        print("\nnot scored (effect below %.0f noise std in the held-out tail even at"
              " the largest size drawn):" % VIS)
        for i, fam, label, truth, got, ok, perr in unscored:
            print("  case %d %s: %s (held-out visibility %.1f, whole record %.1f) -> %s" % (
                i, fam, label, truth["visibility_heldout"], truth["visibility"],
                got.get("effects", got.get("error"))))
    rows = [x for x in rows if x[3]["scored"]]
    # tables
    print("\nper family:")
    for fam in fams:
        r = [x for x in rows if x[1] == fam]
        if r:
            print("  %-10s %2d/%2d  %.1f %%" % (fam, sum(x[5] for x in r), len(r),
                                                 100 * sum(x[5] for x in r) / len(r)))
    print("per effect (top-1, median parameter error of the found ones):")
    for lab in sorted({x[2] for x in rows}):
        r = [x for x in rows if x[2] == lab]
        pe = [x[6] for x in r if x[6] is not None]
        print("  %-19s %2d/%2d  %s" % (lab, sum(x[5] for x in r), len(r),
                                      "median err %.1f %%" % (100 * np.median(pe)) if pe else ""))
    pe = [x[6] for x in rows if x[6] is not None]
    n_ok = sum(x[5] for x in rows)
    print("pooled: %d/%d = %.1f %%, median parameter error %s" % (
        n_ok, len(rows), 100 * n_ok / len(rows),
        "%.1f %%" % (100 * np.median(pe)) if pe else "-"))
    n_la = sum(x[4].get("look_alike_hit", False) for x in rows)
    print("top-1 or named by the tool as a look-alike of its first: %d/%d = %.1f %%" % (
        n_la, len(rows), 100 * n_la / len(rows)))
    print("misses (truth -> verdict):")
    for i, fam, label, truth, got, ok, perr in rows:
        if not ok:
            print("  case %d %s: %s %s -> %s %s shrink %s site %s" % (
                i, fam, label, json.dumps(truth["effect"], default=float),
                got.get("effects", got.get("error")), json.dumps(got.get("params", {})),
                got.get("shrink"), got.get("site")))
            if got.get("look_alikes"):
                print("      look-alikes named: %s" % got["look_alikes"])
    with open(os.path.join(args.out, "summary.json"), "w") as f:
        json.dump([{"case": x[0], "family": x[1], "truth": x[3], "got": x[4], "ok": x[5],
                    "param_error": x[6]} for x in rows], f, indent=1, default=float)
    if args.min_top1 is not None and n_ok < args.min_top1 * len(rows):
        print("FAIL: top-1 %.3f below the floor %.3f" % (n_ok / len(rows), args.min_top1))
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
