"""fracarm: the notebook interface to the fracarm toolchain (issue 20).

Built from the same C/C++ code as the ``fracdesign`` CLI and libfrac:

* :mod:`fracarm.models` - the project's model documents (``frac.model``),
  to and from python-control;
* :mod:`fracarm.gap` - the sim-to-real gap diagnosis (``fracdesign gap``);
* :mod:`fracarm.frac` - libfrac's operators and controllers over numpy arrays;
* :mod:`fracarm.design` - the table-producing verbs (model, tune, lqg, armctrl);
* :mod:`fracarm.fleet` - fleet diagnosis and a sharded gap-bench on Dask.
"""
from . import design, frac, gap, models
from .errors import FracarmError, UsageError

__all__ = ["design", "frac", "gap", "models", "FracarmError", "UsageError"]
