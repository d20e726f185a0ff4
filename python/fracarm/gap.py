"""The sim-to-real gap diagnosis (``fracdesign gap``, docs/gap.md).

:func:`diagnose` runs the CLI's pipeline in-process (gap::run_diagnosis): the
nominal model is replayed on the record, the residual located, every
candidate effect fitted and ranked on held-out data, effects added by
forward selection. Records are read by the CLI's strict reader, so a bad
record raises :class:`~fracarm.errors.FracarmError` with the CLI's message.
"""
from __future__ import annotations

import json
import os
import tempfile
from typing import Any, Dict, List, Optional, Sequence, Union

import numpy as np

from . import _fracarm
from .errors import FracarmError, UsageError
from .models import Model

def _num(x) -> float:
    return float("nan") if x is None else float(x)


def _unit_of(signal: str) -> str:
    """The bracketed unit of a signal name ("tau_M [N m]" -> "N m"), else "unit(<name>)"."""
    if "[" in signal and signal.rstrip().endswith("]"):
        return signal[signal.index("[") + 1:signal.rindex("]")].strip()
    return "unit(%s)" % signal


Record = Union[str, os.PathLike, "pandas.DataFrame"]  # noqa: F821


def effect_names() -> List[str]:
    """The candidate effects the diagnosis knows (``--effects`` values)."""
    return list(_fracarm.gap_effect_names())


def _record(data: Record, what: str) -> dict:
    if isinstance(data, (str, os.PathLike)):
        return {"path": os.fspath(data)}
    try:
        import pandas as pd
    except ImportError:  # pragma: no cover - pandas is in the package's venv
        pd = None
    if pd is not None and isinstance(data, pd.DataFrame):
        cols = list(map(str, data.columns))
        if not cols or cols[0] not in ("t", "t_s"):
            raise FracarmError("%s: the first column must be the time 't' in seconds (got %r)" % (what, cols[:1]))
        values = data.to_numpy(dtype=float, na_value=np.nan)
        lines = [",".join(cols)]
        # repr() round-trips every double, so the reader sees the frame's values exactly.
        lines += [",".join(repr(float(v)) for v in row) for row in values]
        return {"text": "\n".join(lines) + "\n", "origin": "<DataFrame %s>" % what}
    raise FracarmError("%s: expected a CSV path or a pandas DataFrame, got %s" % (what, type(data).__name__))


def _model(model: Union[Model, dict, str, os.PathLike]) -> dict:
    if isinstance(model, Model):
        return {"text": json.dumps(model.doc)}
    if isinstance(model, dict):
        return {"text": json.dumps(model)}
    if isinstance(model, (str, os.PathLike)):
        return {"path": os.fspath(model)}
    raise FracarmError("model: expected a fracarm.models.Model, a document dict or a path, got %s" % type(model).__name__)


class GapResult:
    """The result of one diagnosis: ``result.json`` (schema frac.gap v1) and its report."""

    def __init__(self, result_json: str, report_html: str, signals: Optional[Dict[str, str]] = None):
        self._signals = signals or {}
        self._json = result_json
        self._html = report_html
        self.doc: Dict[str, Any] = json.loads(result_json)

    @property
    def verdict(self) -> List[str]:
        """The verdict's effects in selection order (empty: none)."""
        e = list(self.doc["verdict"]["effects"])
        return [] if e == ["none"] else e

    @property
    def sites(self) -> List[str]:
        """Where each verdict effect acts (e.g. "input" or "coupling")."""
        return list(self.doc["verdict"].get("sites", []))

    @property
    def candidates(self) -> List[Dict[str, Any]]:
        """Every candidate fitted, best first (effect, site, shrink, score, parameters, ...)."""
        return list(self.doc["candidates"])

    @property
    def gap_before(self) -> float:
        """Aggregate held-out gap of the nominal model."""
        return _num(self.doc["gap_before_total"])

    @property
    def gap_after(self) -> float:
        """Aggregate held-out gap with the verdict's effects."""
        return _num(self.doc["verdict"]["gap_after_total"])

    @property
    def shrink(self) -> float:
        """1 - gap_after / gap_before."""
        return _num(self.doc["verdict"]["shrink"])

    @property
    def parameters(self) -> Dict[str, Dict[str, Any]]:
        """The verdict's parameters: name -> {"value", "std", "unit", "effect"}.

        ``std`` is None where the parameter is not identified by the record.
        Units follow docs/gap.md "Which: the effects": forces in the unit of
        the model's force input, velocities in that of its velocity output,
        output-specific parameters in their output's unit (a signal's unit is
        the bracketed part of its name, e.g. ``tau_M [N m]``; without one the
        unit is written as ``unit(<signal>)``).
        """
        v = self.doc["verdict"]
        effects = self.verdict
        out: Dict[str, Dict[str, Any]] = {}
        for k, val in v["params"].items():
            eff, name = (k.split(".", 1) if "." in k else (effects[0] if effects else "", k))
            out[k] = {"value": val, "std": v.get("params_std", {}).get(k), "effect": eff,
                      "unit": self._unit(eff, name, v["sites"][effects.index(eff)] if eff in effects else "")}
        return out

    def _unit(self, effect: str, name: str, site: str) -> str:
        u, vel = self._signals.get("force", "u"), self._signals.get("velocity", "v")
        outs = self.doc["where"]["outputs"]
        per_out = next((o for o in outs if name.endswith("_" + o)), None)
        if name.startswith("delay_s"):
            return "s"
        if name in ("alpha", "gain", "zeta", "share", "mount"):
            return "1"
        if name == "f_hz":
            return "Hz"
        if per_out is not None and name.startswith("gain_"):
            return "%s/%s" % (_unit_of(per_out), _unit_of(u))
        if per_out is not None:
            return _unit_of(per_out)
        if name == "Fv":
            return "%s/(%s)" % (_unit_of(u), _unit_of(vel))
        if name == "vs":
            return _unit_of(vel)
        if name == "width" and site == "coupling":
            return "unit(deflection)"
        if name == "width" and site == "gear":
            return "unit(position)"
        if name == "c":
            return "%s s^alpha/(%s)" % (_unit_of(u), "unit(deflection)" if site == "coupling" else _unit_of(vel) + " s")
        return _unit_of(u)

    def to_json(self) -> str:
        """result.json, byte for byte as ``fracdesign gap`` writes it."""
        return self._json

    def report(self, path: Union[str, os.PathLike]) -> None:
        """Writes report.html to ``path`` (atomically)."""
        path = os.fspath(path)
        fd, tmp = tempfile.mkstemp(dir=os.path.dirname(os.path.abspath(path)), prefix=".report-", suffix=".html")
        try:
            with os.fdopen(fd, "w") as f:
                f.write(self._html)
            os.replace(tmp, path)
        except BaseException:
            if os.path.exists(tmp):
                os.unlink(tmp)
            raise

    def __repr__(self) -> str:
        return "GapResult(verdict=%s, gap %.4g -> %.4g)" % (" + ".join(self.verdict) or "none", self.gap_before,
                                                           self.gap_after)


def diagnose(model: Union[Model, dict, str, os.PathLike], data: Record, validate: Optional[Record] = None,
             effects: Optional[Sequence[str]] = None, inputs: Optional[Sequence[str]] = None,
             outputs: Optional[Sequence[str]] = None, holdout: float = 0.3, command: Optional[str] = None,
             threads: int = 0, loop_feedback: str = "auto") -> GapResult:
    """Diagnoses the gap between ``model`` and the record ``data``.

    model: a :class:`~fracarm.models.Model`, a document dict or a path to one
      (a ``frac.model`` with the ``gap`` section for closed-loop records).
    data, validate: a signal CSV path or a pandas DataFrame whose first column
      is ``t`` in seconds. Without ``validate`` the last ``holdout`` fraction of
      ``data`` is held out and never fitted.
    effects: candidate effect names (default: all, see :func:`effect_names`).
    inputs, outputs: data columns driving the model / compared (defaults: the model's names).
    threads: workers for the independent candidate fits (0: one per core, as
      the CLI); the result does not depend on it. The fleet passes 1, since
      it runs one record per worker core.
    loop_feedback: what the replayed controller of a closed-loop nominal reads:
      "model" (its outputs: the loop simulated), "measured" (the record's
      columns of them: the plant replayed on the command the machine got) or
      "auto" (model; when that does not explain the gap, measured, whose
      effects also start a second closed-loop fit, and measured is kept when
      the closed loop names no effect or a weak one; docs/gap.md "Loop
      feedback"), as the CLI's --loop-feedback.
    command: recorded in result.json and the report (default: the equivalent
      ``fracdesign gap`` command line for path arguments, else a description).

    Raises UsageError for bad options (the CLI's exit 2) and FracarmError for
    bad files or documents (exit 1), with the CLI's messages.
    """
    if int(threads) < 0:
        raise UsageError("threads must be >= 0 (0: one per core)")
    if loop_feedback not in ("auto", "model", "measured"):
        raise UsageError("--loop-feedback must be auto, model or measured, got '%s'" % loop_feedback)
    opts: Dict[str, Any] = {"holdout": float(holdout), "threads": int(threads), "loop_feedback": loop_feedback}
    if effects is not None:
        known = set(effect_names()) | {"none"}
        for e in effects:
            if e not in known:
                raise UsageError("unknown effect '%s' (known: %s)" % (e, ", ".join(sorted(known))))
        opts["effects"] = list(effects)
    if inputs is not None:
        opts["inputs"] = list(inputs)
    if outputs is not None:
        opts["outputs"] = list(outputs)
    if not (0 < opts["holdout"] < 1):
        raise UsageError("--holdout must be in (0, 1)")
    m, d = _model(model), _record(data, "data")
    v = _record(validate, "validate") if validate is not None else None
    if command is None:
        command = _command(m, d, v, opts)
    try:
        text, html = _fracarm.gap_diagnose(m, d, v, opts, command)
    except ValueError as e:
        raise UsageError(str(e)) from None
    except RuntimeError as e:
        raise FracarmError(str(e)) from None
    return GapResult(text, html, _signal_roles(m))


def _signal_roles(m: dict) -> Dict[str, str]:
    """The model's force input and friction velocity signal names (its "gap" section)."""
    try:
        doc = json.loads(m["text"]) if "text" in m else json.load(open(m["path"]))
        g = doc.get("gap", {})
        ins, outs = doc.get("inputs", []), doc.get("outputs", [])
        roles = {}
        fi = g.get("force_input", 0)
        fi = ins.index(fi) if isinstance(fi, str) and fi in ins else fi
        if isinstance(fi, int) and 0 <= fi < len(ins):
            roles["force"] = ins[fi]
        ve = g.get("velocity")
        if isinstance(ve, str):
            roles["velocity"] = ve
        elif isinstance(ve, int) and 0 <= ve < len(outs):
            roles["velocity"] = outs[ve]
        return roles
    except (OSError, ValueError, AttributeError, TypeError):
        return {}


def _command(m: dict, d: dict, v: Optional[dict], opts: Dict[str, Any]) -> str:
    """The fracdesign gap command line these arguments correspond to."""
    name = lambda r, what: r["path"] if "path" in r else r.get("origin", "<%s>" % what)
    cmd = "fracdesign gap --model %s --data %s" % (name(m, "model"), name(d, "data"))
    if v is not None:
        cmd += " --validate %s" % name(v, "validate")
    for key in ("inputs", "outputs", "effects"):
        if key in opts:
            cmd += " --%s %s" % (key, ",".join(opts[key]))
    if opts["holdout"] != 0.3:
        cmd += " --holdout %s" % repr(opts["holdout"])
    if opts.get("loop_feedback", "auto") != "auto":
        cmd += " --loop-feedback %s" % opts["loop_feedback"]
    return cmd
