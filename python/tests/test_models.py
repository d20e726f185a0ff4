"""Model documents and python-control round trips (fracarm.models)."""
import json
import os

import control
import numpy as np
import pytest

from conftest import SRC, cli
from fracarm import design, models
from fracarm.errors import FracarmError

RNG = np.random.default_rng(7)


def random_stable(n, m, p, dt=0):
    s = control.rss(n, p, m, dt=dt) if dt == 0 else control.drss(n, p, m, dt=dt)
    return s


def test_statespace_round_trip_keeps_the_matrices_and_sample_time():
    for dt in (0, 0.0012):
        s = random_stable(4, 2, 3, dt)
        m = models.Model.from_control(s, inputs=["u1 [N m]", "u2 [N m]"], outputs=["a [rad]", "b [rad]", "c [rad/s]"])
        back = m.to_control()
        for X in "ABCD":
            assert np.array_equal(getattr(back, X), getattr(s, X)), X
        assert back.dt == dt
        assert back.input_labels == ["u1 [N m]", "u2 [N m]"] and back.output_labels[2] == "c [rad/s]"


def test_transfer_function_round_trip_keeps_the_frequency_response():
    tf = control.tf([2.0, 3.0], [1.0, 0.4, 25.0])
    back = models.Model.from_control(tf).to_control()
    w = np.logspace(-1, 2, 30)
    assert np.allclose(control.frequency_response(back, w).complex.ravel(),
                       control.frequency_response(tf, w).complex.ravel(), rtol=1e-12, atol=1e-14)
    assert np.allclose(np.sort_complex(back.poles()), np.sort_complex(tf.poles()))


def test_save_and_load_round_trip_and_the_cli_reads_the_file(tmp_path):
    m = models.Model.from_control(random_stable(3, 1, 1, 0.01))
    p = tmp_path / "m.json"
    m.save(p)
    assert models.load(p).doc == m.doc
    st, out, err = cli("model", "--model", p, "--json")
    assert st == 0, err


def test_designed_model_document_loads_and_converts(tmp_path):
    p = tmp_path / "arm.json"
    design.model("arm", N=5, save=str(p))
    m = models.load(p)
    assert m.kind == "arm"
    s = m.to_control()
    A, B, C, D, Ts, *_ = m.lti()
    assert s.nstates == A.shape[0] and Ts == 0 and s.dt == 0


def test_bad_documents_raise_the_cli_message(tmp_path):
    doc = models.Model.from_control(random_stable(2, 1, 1)).doc
    doc["B"] = [[1.0]]
    p = tmp_path / "bad.json"
    p.write_text(json.dumps(doc))
    with pytest.raises(FracarmError) as e:
        models.load(p)
    st, _, err = cli("model", "--model", p)
    assert st == 1 and str(e.value) in err and "field 'B'" in str(e.value)
    with pytest.raises(FracarmError, match="field 'B'"):
        models.Model(doc)
    with pytest.raises(FracarmError, match="dt is None"):
        models.Model.from_control(control.ss([[-1.0]], [[1.0]], [[1.0]], [[0.0]], dt=None))
    with pytest.raises(FracarmError, match="irrational|antenna|foprocess"):
        models.Model(design.model("foprocess")["model"]).to_control()

