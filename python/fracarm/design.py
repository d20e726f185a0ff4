"""The fracdesign verbs that produce designs and tables (model, tune, lqg, armctrl, table, traj, ...).

Each call runs the registered fracdesign subcommand in-process (the CLI's
own code, linked into the extension): the same option checks, the same
files written. Options are keyword arguments: ``design.tune("fopi", K=1,
T=0.5, lambda_=1.5, wc=1, phim=0.9, alpha=0.5)`` is ``fracdesign tune fopi
--K 1 --T 0.5 --lambda 1.5 --wc 1 --phim 0.9 --alpha 0.5``; an underscore
becomes a dash where the verb spells the option with one (``band_lo`` ->
``--band-lo``), a trailing underscore is dropped (``lambda_``), True is a
bare flag, a list is comma-joined. The verb's ``--json`` document is
returned as a dict; errors raise UsageError (exit 2) or FracarmError
(exit 1) with the CLI's stderr line.
"""
from __future__ import annotations

import json
from typing import Any, Dict, List

from . import _fracarm
from .errors import FracarmError, UsageError


def commands() -> List[str]:
    """The verbs available in-process."""
    return list(_fracarm.command_names())


def help(verb: str) -> str:  # noqa: A001 - the CLI's word
    """The verb's --help text."""
    return _fracarm.command_help(verb)


def argv(verb: str, *positional: str, **options: Any) -> List[str]:
    """The fracdesign argument list for these options (without the verb)."""
    text = _fracarm.command_help(verb)
    args = [str(p) for p in positional]
    for key, value in options.items():
        if value is None or value is False:
            continue
        name = key[:-1] if key.endswith("_") else key
        dashed = name.replace("_", "-")
        if dashed != name and "--" + dashed in text and "--" + name not in text:
            name = dashed
        if value is True:
            args.append("--" + name)
        else:
            if isinstance(value, (list, tuple)):
                value = ",".join(repr(float(v)) if isinstance(v, float) else str(v) for v in value)
            elif isinstance(value, float):
                value = repr(value)
            args += ["--" + name, str(value)]
    return args


def run(verb: str, *positional: str, **options: Any) -> Dict[str, Any]:
    """Runs ``fracdesign <verb> ... --json`` in-process; returns its JSON document."""
    a = argv(verb, *positional, **options) + ["--json"]
    status, out, err = _fracarm.run_command(verb, a)
    if status == 2:
        raise UsageError(err or "fracdesign %s: exit status 2" % verb)
    if status != 0:
        raise FracarmError(err or "fracdesign %s: exit status %d" % (verb, status))
    try:
        return json.loads(out)
    except ValueError:
        raise FracarmError("fracdesign %s: --json printed no JSON document" % verb) from None


def model(kind: str = None, **options: Any) -> Dict[str, Any]:
    """``fracdesign model <kind>`` (beam, arm, antenna, collocated, foprocess); ``save=PATH`` writes the document."""
    return run("model", *([kind] if kind else []), **options)


def tune(kind: str, **options: Any) -> Dict[str, Any]:
    """``fracdesign tune <fopi|fopd|collocated>``: FO-PI/FO-PD (seed 001) or the collocated law (seed 002)."""
    return run("tune", kind, **options)


def lqg(**options: Any) -> Dict[str, Any]:
    """``fracdesign lqg``: K and L_e for the reduced arm (seed 004 Exp. C/D); ``out=PATH`` writes the design."""
    return run("lqg", **options)


def armctrl(exp: str, out: str, **options: Any) -> Dict[str, Any]:
    """``fracdesign armctrl --exp A|B|C|D --out FILE``: the table ArmCtrl loads, written to FILE."""
    return run("armctrl", exp=exp, out=out, **options)
