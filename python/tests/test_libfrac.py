"""fracarm.frac is libfrac bit for bit: each object against the plain C loop
of python/tests/cdriver.c on the same inputs, plus the error paths."""
import subprocess

import numpy as np
import pytest

from conftest import CDRIVER
from fracarm import frac

RNG = np.random.default_rng(20)
N = 3000


def c_run(tokens):
    p = subprocess.run([CDRIVER], input=" ".join(map(str, tokens)), capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    return np.array([float.fromhex(x) for x in p.stdout.split()])


def same_bits(a, b):
    a, b = np.asarray(a, dtype=float).ravel(), np.asarray(b, dtype=float).ravel()
    assert a.shape == b.shape
    assert np.array_equal(a.view(np.uint64), b.view(np.uint64)), np.max(np.abs(a - b))


def signal(n=N):
    t = np.arange(n) * 1e-3
    return np.sin(7.3 * t) + 0.3 * RNG.standard_normal(n)


OPS = [
    ("gl", dict(memory=200)),
    ("oustaloup", dict(wb=0.3, wh=900.0, n=5)),
    ("oustaloup_refined", dict(wb=0.3, wh=900.0, n=4)),
    ("cfe_tustin", dict(n=5)),
    ("cfe_alalaoui", dict(n=4)),
]


def op_tokens(method, kw):
    return [method, kw.get("memory", 0), repr(kw.get("wb", 0.0)), repr(kw.get("wh", 0.0)), kw.get("n", 0)]


@pytest.mark.parametrize("method,kw", OPS)
def test_fo_operator_is_libfrac_bit_for_bit(method, kw):
    order = float(RNG.uniform(0.1, 0.9))
    x = signal()
    y = frac.FoOperator(order, 1e-3, method, **kw).run(x)
    same_bits(y, c_run(["fo", repr(order), repr(1e-3)] + op_tokens(method, kw) + [N] + [repr(float(v)) for v in x]))


@pytest.mark.parametrize("method,kw", OPS[:2])
def test_fopid_is_libfrac_bit_for_bit(method, kw):
    p = dict(kp=float(RNG.uniform(0.5, 3)), ki=float(RNG.uniform(0.1, 2)), kd=float(RNG.uniform(0.01, 0.3)),
             lam=float(RNG.uniform(0.3, 1.5)), mu=float(RNG.uniform(0.2, 0.9)), tf=0.01, b=0.8, c=0.5, delta=0.1,
             umin=-1.5, umax=1.5, tt=0.2, ts=1e-3)
    r, y = np.sign(signal()), signal()
    u = frac.FoPid(antiwindup="backcalc", op=dict(method=method, **kw), **p).run(r, y)
    tok = ["fopid"] + [repr(p[k]) for k in ("kp", "ki", "kd", "lam", "mu", "tf", "b", "c", "delta", "umin", "umax")]
    tok += [2, repr(p["tt"]), repr(p["ts"])] + op_tokens(method, kw) + [N]
    tok += [repr(float(v)) for pair in zip(r, y) for v in pair]
    same_bits(u, c_run(tok))


def test_fodamp_is_libfrac_bit_for_bit():
    # seed 002's structure (m = 2, N = 1 + n1 s) with parameters drawn here.
    p = dict(kc=float(RNG.uniform(2, 8)), alpha=float(RNG.uniform(0.6, 0.95)), m=2, n1=float(RNG.uniform(0.005, 0.03)),
             n2=0.0, d1=0.0, d2=0.0, fa=float(RNG.uniform(0.05, 0.2)), fbeta=0.55, fb=0.011, ts=1e-3)
    op = dict(memory=300)
    ref, meas = signal(), signal()
    u = frac.FoDamp(op=dict(method="gl", **op), **p).run(ref, meas)
    tok = ["fodamp", repr(p["kc"]), repr(p["alpha"]), 2] + [repr(p[k]) for k in ("n1", "n2", "d1", "d2", "fa", "fbeta", "fb", "ts")]
    tok += op_tokens("gl", op) + [N] + [repr(float(v)) for pair in zip(ref, meas) for v in pair]
    same_bits(u, c_run(tok))


@pytest.mark.parametrize("interp", ["linear", "cubic"])
def test_lookup_tables_are_libfrac_bit_for_bit(interp):
    x = np.cumsum(RNG.uniform(0.1, 1.0, 12))
    y = np.cumsum(RNG.uniform(0.0, 2.0, 12))
    q = RNG.uniform(x[0] - 1, x[-1] + 1, 500)
    code = 0 if interp == "linear" else 1
    same_bits(frac.Lut1(x, y, interp, "extrapolate")(q),
              c_run(["lut1", code, 1, 12] + [repr(float(v)) for v in np.r_[x, y]] + [500] + [repr(float(v)) for v in q]))
    x2 = np.cumsum(RNG.uniform(0.1, 1.0, 7))
    z = RNG.standard_normal((12, 7))
    q2 = RNG.uniform(x2[0], x2[-1], 500)
    same_bits(frac.Lut2(x, x2, z, interp, "clamp")(q, q2),
              c_run(["lut2", code, 0, 12] + [repr(float(v)) for v in x] + [7] + [repr(float(v)) for v in x2] + [repr(float(v)) for v in z.ravel()]
                    + [500] + [repr(float(v)) for pair in zip(q, q2) for v in pair]))


def test_kalman_filter_is_libfrac_bit_for_bit():
    n, m, p = 3, 1, 2
    A = np.eye(n) + 0.01 * RNG.standard_normal((n, n))
    B = RNG.standard_normal((n, m))
    C = RNG.standard_normal((p, n))
    Q, R, P0 = 0.01 * np.eye(n), 0.1 * np.eye(p), np.eye(n)
    U, Y = RNG.standard_normal((400, m)), RNG.standard_normal((400, p))
    X = frac.Kalman(A, B, C, Q, R, P0).filter(U, Y)
    tok = ["kalman", n, m, p] + [repr(float(v)) for M in (A, B, C, Q, R, P0) for v in M.ravel()] + [400]
    tok += [repr(float(v)) for k in range(400) for v in np.r_[U[k], Y[k]]]
    same_bits(X, c_run(tok))


def test_lqg_step_is_libfrac_bit_for_bit():
    n, d_i, d_o = 2, 2, [1, 0]
    nb = n + d_i + sum(d_o)
    A = np.array([[1.0, 1e-3], [-0.05, 0.999]])
    B = np.array([0.0, 1e-3])
    C = RNG.standard_normal((2, n))
    K = RNG.uniform(-1, 1, nb)
    L = 0.1 * RNG.standard_normal((nb + 1, 2))
    us, yr, y = RNG.standard_normal(300), RNG.standard_normal((300, 2)), RNG.standard_normal((300, 2))
    u = frac.Lqg(A, B, C, K, L, d_i=d_i, d_o=d_o).run(us, yr, y)
    tok = ["lqg", n, d_i, 2] + d_o + [repr(float(v)) for M in (A, B, C, K, L) for v in M.ravel()] + [300]
    tok += [repr(float(v)) for k in range(300) for v in np.r_[us[k], yr[k], y[k]]]
    same_bits(u, c_run(tok))


def test_bad_parameters_raise_with_the_status():
    with pytest.raises(ValueError, match="frac_fo_init: .*status -6"):
        frac.FoOperator(5.0, 1e-3, "gl", memory=10)
    with pytest.raises(ValueError, match="method: 'euler' is not one of"):
        frac.FoOperator(0.5, 1e-3, "euler")
    with pytest.raises(ValueError, match="frac_fopid_init: .*status -10"):
        frac.FoPid(ts=1e-3, kp=1, umin=1, umax=-1)
    with pytest.raises(ValueError, match="frac_lut1_init: .*status -12"):
        frac.Lut1([0, 2, 1], [0, 1, 2])
    with pytest.raises(ValueError, match="frac_kalman_init: .*status -13"):
        frac.Kalman(np.eye(2), None, np.eye(2), np.eye(2), -np.eye(2), np.eye(2))


def test_nonfinite_input_returns_an_error_status_and_holds_the_output():
    op = frac.FoOperator(0.5, 1e-3, "gl", memory=50)
    y, st = op.run(np.array([1.0, 2.0, np.nan, 3.0]), status=True)
    assert st.tolist()[:2] == [0, 0] and st[2] == -2 and y[2] == y[1] and st[3] == 0
    assert frac.status_str(-2) == "error: non-finite input"
