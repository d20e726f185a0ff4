"""The project's model documents (``frac.model`` v1, docs/model_format.md).

A :class:`Model` holds one document as a dict, exactly as fracdesign reads and
writes it (extension sections such as ``gap`` are kept). Every document is
validated by fracdesign's own reader, so errors carry its messages, e.g.
``model: field 'B': must have 2 rows, has 1``.
"""
from __future__ import annotations

import json
import os
import tempfile
from typing import Any, Optional, Sequence

import numpy as np

from . import _fracarm
from .errors import FracarmError


class Model:
    """One ``frac.model`` document (validated)."""

    def __init__(self, doc: dict):
        try:
            self.kind: str = _fracarm.model_check(json.dumps(doc))
        except (RuntimeError, ValueError) as e:
            raise FracarmError(str(e)) from None
        self.doc: dict = doc

    def __repr__(self) -> str:
        return "Model(kind=%r%s)" % (self.kind, ", name=%r" % self.doc["name"] if "name" in self.doc else "")

    def to_json(self) -> str:
        """The document as fracdesign writes JSON (2-space indent, trailing newline)."""
        return json.dumps(self.doc, indent=2) + "\n"

    def save(self, path: str | os.PathLike) -> None:
        """Writes the document to ``path`` atomically (a temporary file renamed into place)."""
        path = os.fspath(path)
        d = os.path.dirname(os.path.abspath(path))
        fd, tmp = tempfile.mkstemp(dir=d, prefix=".model-", suffix=".json")
        try:
            with os.fdopen(fd, "w") as f:
                f.write(self.to_json())
            os.replace(tmp, path)
        except BaseException:
            if os.path.exists(tmp):
                os.unlink(tmp)
            raise

    def lti(self):
        """(A, B, C, D, Ts, inputs, outputs, states) of a rational kind (Ts = 0: continuous).

        Raises FracarmError for the irrational kinds (antenna, foprocess).
        """
        try:
            return _fracarm.model_lti(json.dumps(self.doc))
        except (RuntimeError, ValueError) as e:
            raise FracarmError(str(e)) from None

    def to_control(self):
        """The model as a python-control ``StateSpace`` (``dt`` = Ts; 0 for continuous time)."""
        import control

        A, B, C, D, Ts, inputs, outputs, states = self.lti()
        kw: dict[str, Any] = {}
        if inputs:
            kw["inputs"] = list(inputs)
        if outputs:
            kw["outputs"] = list(outputs)
        if states:
            kw["states"] = list(states)
        return control.ss(A, B, C, D, Ts if Ts > 0 else 0, **kw)

    @staticmethod
    def from_control(sys, inputs: Optional[Sequence[str]] = None, outputs: Optional[Sequence[str]] = None,
                     name: Optional[str] = None) -> "Model":
        """A ``statespace`` document from a python-control StateSpace or TransferFunction.

        A TransferFunction is realized by ``control.ss`` (the same transfer
        matrix, a state basis of python-control's choosing). ``dt`` None or
        True (unspecified sample time) is refused: the document needs a Ts.
        Signal names default to python-control's (``u[0]``, ``y[0]``, ...).
        """
        import control

        ss = control.ss(sys) if isinstance(sys, control.TransferFunction) else sys
        if not isinstance(ss, control.StateSpace):
            raise FracarmError("from_control: expected a control.StateSpace or control.TransferFunction, got %s"
                               % type(sys).__name__)
        dt = ss.dt
        if dt is None or dt is True:
            raise FracarmError("from_control: the system's dt is %r; give a continuous (dt=0) or sampled (dt>0) system" % dt)
        mat = lambda M, r, c: np.asarray(M, dtype=float).reshape(r, c).tolist()
        n, m, p = ss.nstates, ss.ninputs, ss.noutputs
        doc: dict[str, Any] = {"schema": "frac.model", "version": 1, "kind": "statespace", "units": "SI"}
        if name:
            doc["name"] = name
        doc["time"] = "continuous" if dt == 0 else "discrete"
        if dt:
            doc["Ts"] = float(dt)
        doc.update({"A": mat(ss.A, n, n), "B": mat(ss.B, n, m), "C": mat(ss.C, p, n), "D": mat(ss.D, p, m)})
        doc["inputs"] = list(inputs) if inputs is not None else list(ss.input_labels)
        doc["outputs"] = list(outputs) if outputs is not None else list(ss.output_labels)
        return Model(doc)


def load(path: str | os.PathLike) -> Model:
    """Reads a model document file (fracdesign's reader checks it; errors name the file and field)."""
    path = os.fspath(path)
    try:
        _fracarm.model_read(path)
    except (RuntimeError, ValueError) as e:
        raise FracarmError(str(e)) from None
    with open(path) as f:
        return Model(json.load(f))


def from_control(sys, **kw) -> Model:
    """Shorthand for :meth:`Model.from_control`."""
    return Model.from_control(sys, **kw)
